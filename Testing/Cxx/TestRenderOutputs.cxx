// mrgi-render's outputs (Module/Apps/mrgiRenderOutputs): paths are checked
// before rendering, outputs are all written or none is left, and SIGTERM or
// SIGINT removes what a write had staged and exits 128 + the signal. No
// OpenGL needed.
#include "mrgiRenderOutputs.h"
#include "mrgiTestUtilities.h"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace
{
std::string Directory()
{
  const char* tmp = std::getenv("MRGI_TEST_TMP");
  const std::string dir = std::string(tmp ? tmp : "/tmp") + "/render_outputs";
  mkdir(dir.c_str(), 0777);
  return dir;
}

void WriteFile(const std::string& path, const char* text)
{
  FILE* f = std::fopen(path.c_str(), "wb");
  MRGI_TEST_CHECK(f != nullptr);
  std::fputs(text, f);
  std::fclose(f);
}

// Every name in the test directory, for "nothing left" checks.
std::vector<std::string> Listing()
{
  std::vector<std::string> names;
  const std::string command = "ls -A '" + Directory() + "'";
  FILE* ls = popen(command.c_str(), "r");
  char line[4096];
  while (ls && std::fgets(line, sizeof(line), ls))
  {
    std::string name(line);
    if (!name.empty() && name.back() == '\n')
    {
      name.pop_back();
    }
    names.push_back(name);
  }
  if (ls)
  {
    pclose(ls);
  }
  return names;
}

void Clean()
{
  const std::string command = "rm -rf '" + Directory() + "'/*";
  MRGI_TEST_CHECK(std::system(command.c_str()) == 0);
}

void TestCheckRefuses()
{
  Clean();
  const std::string dir = Directory();
  mkdir((dir + "/folder.png").c_str(), 0777);
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
    { { dir + "/a.jpg" }, ".png or .exr" },
    { { dir + "/a.png", dir + "/a.png" }, "given twice" },
    { { dir + "/folder.png" }, "is a directory" },
    { { dir + "/missing/a.png" }, "does not exist" },
    { { dir + "/a.png", dir + "/missing/b.exr" }, "missing/b.exr" },
  };
  for (const auto& c : bad)
  {
    mrgirender::Outputs outputs;
    std::string why;
    MRGI_TEST_CHECK(!outputs.Check(c.first, why));
    std::printf("refused: %s\n", why.c_str());
    MRGI_TEST_CHECK(why.find(c.second) != std::string::npos);
  }
  // Nothing made: no probe left behind, no output.
  MRGI_TEST_CHECK(Listing() == std::vector<std::string>{ "folder.png" });
}

void TestCommit()
{
  Clean();
  const std::string dir = Directory();
  std::vector<std::string> finals = { dir + "/a.png", dir + "/b.exr" };
  mrgirender::Outputs outputs;
  std::string why;
  MRGI_TEST_CHECK(outputs.Check(finals, why));
  MRGI_TEST_CHECK(Listing().empty()); // checking makes nothing
  for (size_t i = 0; i < finals.size(); ++i)
  {
    const std::string& staging = outputs.StagingPath(i);
    // The staging name keeps the output's extension (writers choose by it).
    MRGI_TEST_CHECK(staging.substr(staging.size() - 4) == finals[i].substr(finals[i].size() - 4));
    WriteFile(staging, "image");
  }
  MRGI_TEST_CHECK(outputs.Commit(why));
  std::vector<std::string> names = Listing();
  MRGI_TEST_CHECK((names == std::vector<std::string>{ "a.png", "b.exr" }));
}

void TestAllOrNothing()
{
  Clean();
  const std::string dir = Directory();
  std::vector<std::string> finals = { dir + "/a.png", dir + "/b.exr" };
  {
    mrgirender::Outputs outputs;
    std::string why;
    MRGI_TEST_CHECK(outputs.Check(finals, why));
    WriteFile(outputs.StagingPath(0), "image");
    WriteFile(outputs.StagingPath(1), "image");
    // The second output's place is taken after the check: its rename fails.
    mkdir((dir + "/b.exr").c_str(), 0777);
    WriteFile(dir + "/b.exr/keep", "x");
    MRGI_TEST_CHECK(!outputs.Commit(why));
    std::printf("commit failed: %s\n", why.c_str());
    MRGI_TEST_CHECK(why.find("b.exr") != std::string::npos);
    // The first output, already renamed, is removed again; no staging left.
    MRGI_TEST_CHECK((Listing() == std::vector<std::string>{ "b.exr" }));
  }
  // A run that never commits (a failed write) leaves nothing either.
  Clean();
  {
    mrgirender::Outputs outputs;
    std::string why;
    MRGI_TEST_CHECK(outputs.Check(finals, why));
    WriteFile(outputs.StagingPath(0), "image");
  }
  MRGI_TEST_CHECK(Listing().empty());
}

void SignalDuringWrite(int signal)
{
  Clean();
  const std::string dir = Directory();
  const pid_t child = fork();
  MRGI_TEST_CHECK(child >= 0);
  if (child == 0)
  {
    mrgirender::Outputs outputs;
    std::string why;
    if (!outputs.Check({ dir + "/a.png", dir + "/b.exr" }, why))
    {
      _exit(3);
    }
    // The first image is staged, the second is being written by the core
    // writer (its own temporary, "STAGING.tmp-PID-0").
    WriteFile(outputs.StagingPath(0), "image");
    WriteFile(outputs.StagingPath(1) + ".tmp-" + std::to_string(getpid()) + "-0", "half");
    kill(getpid(), signal);
    _exit(4); // not reached: the handler exits
  }
  int status = 0;
  MRGI_TEST_CHECK(waitpid(child, &status, 0) == child);
  std::printf("child: exited %d, status %d\n", WIFEXITED(status), WEXITSTATUS(status));
  MRGI_TEST_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 128 + signal);
  const std::vector<std::string> left = Listing();
  for (const std::string& name : left)
  {
    std::printf("left: %s\n", name.c_str());
  }
  MRGI_TEST_CHECK(left.empty());
}

void TestSigtermDuringWrite()
{
  SignalDuringWrite(SIGTERM);
}

void TestSigintDuringWrite()
{
  SignalDuringWrite(SIGINT);
}
}

int main(int argc, char* argv[])
{
  return mrgitest::RunCases(argc, argv,
    { MRGI_TEST_CASE(TestCheckRefuses), MRGI_TEST_CASE(TestCommit),
      MRGI_TEST_CASE(TestAllOrNothing), MRGI_TEST_CASE(TestSigtermDuringWrite),
      MRGI_TEST_CASE(TestSigintDuringWrite) });
}
