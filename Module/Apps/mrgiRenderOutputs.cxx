#include "mrgiRenderOutputs.h"

#include "mrgi_atomic_file.h"
#include "mrgi_error.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

namespace
{
// ---- What the signal handler removes. ----
//
// Fixed storage, filled before the handler can need it: the handler reads
// only `Active` flags and NUL-terminated paths, calls unlink() and _exit().
// A slot's path is written while its flag is 0 and flagged afterwards.
const int MaxCleanupPaths = 256;
const size_t MaxCleanupPathLength = MRGI_ATOMIC_FILE_PATH_MAX + 64;
char CleanupPaths[MaxCleanupPaths][MaxCleanupPathLength];
volatile sig_atomic_t CleanupActive[MaxCleanupPaths];

extern "C" void RemoveAndExit(int signal)
{
  for (int i = 0; i < MaxCleanupPaths; ++i)
  {
    if (CleanupActive[i])
    {
      unlink(CleanupPaths[i]);
    }
  }
  _exit(128 + signal);
}

// Registers `path` for removal on a signal; returns its slot, or -1 when
// the table is full (then the path is only removed by normal cleanup).
int Register(const std::string& path)
{
  if (path.size() >= MaxCleanupPathLength)
  {
    return -1;
  }
  for (int i = 0; i < MaxCleanupPaths; ++i)
  {
    if (!CleanupActive[i])
    {
      std::memcpy(CleanupPaths[i], path.c_str(), path.size() + 1);
      CleanupActive[i] = 1;
      return i;
    }
  }
  return -1;
}

void Unregister(const std::string& path)
{
  for (int i = 0; i < MaxCleanupPaths; ++i)
  {
    if (CleanupActive[i] && path == CleanupPaths[i])
    {
      CleanupActive[i] = 0;
    }
  }
}

void InstallHandlers()
{
  static bool installed = false;
  if (installed)
  {
    return;
  }
  installed = true;
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = RemoveAndExit;
  sigfillset(&action.sa_mask); // one handler at a time
  for (int signal : { SIGTERM, SIGINT, SIGHUP })
  {
    sigaction(signal, &action, nullptr);
  }
}

bool EndsWithNoCase(const std::string& s, const char* extension)
{
  const size_t e = std::strlen(extension);
  return s.size() > e && strcasecmp(s.c_str() + s.size() - e, extension) == 0;
}

// The writers' own temporary for `path` in this process: "PATH.tmp-PID-0"
// (mrgi_atomic_file.h; the staging name is unique to this process, so the
// first attempt's name is free).
std::string WriterTemporary(const std::string& path)
{
  return path + ".tmp-" + std::to_string(static_cast<long>(getpid())) + "-0";
}
}

namespace mrgirender
{
Outputs::Outputs()
{
  InstallHandlers();
}

Outputs::~Outputs()
{
  if (!this->Committed)
  {
    this->Abandon();
  }
}

bool Outputs::Check(const std::vector<std::string>& paths, std::string& why)
{
  for (size_t i = 0; i < paths.size(); ++i)
  {
    const std::string& path = paths[i];
    const std::string quoted = "output '" + path + "'";
    const char* extension = EndsWithNoCase(path, ".png") ? ".png"
      : EndsWithNoCase(path, ".exr")                     ? ".exr"
                                                         : nullptr;
    if (!extension)
    {
      why = quoted + ": the file name must end in .png or .exr";
      return false;
    }
    for (size_t j = 0; j < i; ++j)
    {
      if (paths[j] == path)
      {
        why = quoted + ": given twice";
        return false;
      }
    }
    if (path.size() > MRGI_ATOMIC_FILE_PATH_MAX - MRGI_ATOMIC_FILE_SUFFIX_MAX - 64)
    {
      why = quoted + ": the path is too long";
      return false;
    }
    struct stat st;
    if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    {
      why =
        quoted + (S_ISDIR(st.st_mode) ? ": is a directory" : ": exists and is not a regular file");
      return false;
    }
    const size_t slash = path.find_last_of('/');
    const std::string directory =
      slash == std::string::npos ? std::string(".") : (slash == 0 ? "/" : path.substr(0, slash));
    if (stat(directory.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    {
      why = quoted + ": the directory '" + directory + "' does not exist";
      return false;
    }
    // The probe: can a new file be made beside the output? Its name (the
    // writer's first temporary for `path`) is registered before it exists,
    // so that a signal while it exists removes it too.
    char probe[MRGI_ATOMIC_FILE_PATH_MAX];
    mrgi_error err;
    const std::string probeName = WriterTemporary(path);
    Register(probeName);
    if (mrgi_atomic_file_begin(path.c_str(), probe, sizeof(probe), &err) != MRGI_OK)
    {
      Unregister(probeName);
      why = quoted + ": cannot create a file in '" + directory + "': " + err.message;
      return false;
    }
    mrgi_atomic_file_abort(probe);
    Unregister(probeName);
    this->Finals.push_back(path);
    std::string staging = path + ".tmp-" + std::to_string(static_cast<long>(getpid())) + extension;
    this->Stagings.push_back(staging);
  }
  // Registered now, so that a signal at any later point removes them.
  for (const std::string& staging : this->Stagings)
  {
    Register(staging);
    Register(WriterTemporary(staging));
  }
  return true;
}

const std::string& Outputs::StagingPath(size_t i) const
{
  return this->Stagings.at(i);
}

bool Outputs::Commit(std::string& why)
{
  for (size_t i = 0; i < this->Finals.size(); ++i)
  {
    // The output joins the paths a signal removes before it exists; the
    // staging file leaves them once it is gone (renamed).
    Register(this->Finals[i]);
    if (std::rename(this->Stagings[i].c_str(), this->Finals[i].c_str()) != 0)
    {
      const int saved = errno;
      Unregister(this->Finals[i]);
      why = "cannot move '" + this->Stagings[i] + "' to '" + this->Finals[i] +
        "': " + std::strerror(saved);
      for (size_t j = 0; j < i; ++j)
      {
        unlink(this->Finals[j].c_str());
        Unregister(this->Finals[j]);
      }
      this->Abandon();
      return false;
    }
    Unregister(this->Stagings[i]);
  }
  // Done: from here on a signal leaves the outputs in place.
  for (size_t i = 0; i < this->Finals.size(); ++i)
  {
    Unregister(this->Finals[i]);
    Unregister(WriterTemporary(this->Stagings[i]));
  }
  this->Committed = true;
  return true;
}

void Outputs::Abandon()
{
  for (const std::string& staging : this->Stagings)
  {
    unlink(staging.c_str());
    unlink(WriterTemporary(staging).c_str());
    Unregister(staging);
    Unregister(WriterTemporary(staging));
  }
}
}
