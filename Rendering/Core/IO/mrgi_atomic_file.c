#include "mrgi_atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

/* How many names ".tmp-PID-0", ".tmp-PID-1", ... are tried before giving up;
 * only other writers of the same output in this process can take names. */
#define MRGI_ATOMIC_FILE_MAX_ATTEMPTS 1000

mrgi_status mrgi_atomic_file_begin(const char* final_path, char* temp_path, size_t temp_size,
                                   mrgi_error* err)
{
  if (!final_path || final_path[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output path is NULL or empty");
  }
  if (!temp_path)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "temporary path buffer for '%s' is NULL", final_path);
  }
  const size_t final_length = strlen(final_path);
  if (temp_size < final_length + MRGI_ATOMIC_FILE_SUFFIX_MAX)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "temporary path buffer of %zu bytes is too small for '%s' "
                          "(needs %zu)",
                          temp_size, final_path, final_length + MRGI_ATOMIC_FILE_SUFFIX_MAX);
  }
  if (final_path[final_length - 1] == '/')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "output path '%s' names a directory, not a file", final_path);
  }
  const long pid = (long)getpid();
  for (int attempt = 0; attempt < MRGI_ATOMIC_FILE_MAX_ATTEMPTS; ++attempt)
  {
    snprintf(temp_path, temp_size, "%s.tmp-%ld-%d", final_path, pid, attempt);
    const int fd = open(temp_path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0)
    {
      close(fd);
      return MRGI_OK;
    }
    if (errno != EEXIST)
    {
      const int saved = errno;
      mrgi_status status = mrgi_error_set(
        err, MRGI_ERR_IO, "cannot create temporary file '%s' for '%s': %s", temp_path,
        final_path, strerror(saved));
      temp_path[0] = '\0';
      return status;
    }
  }
  temp_path[0] = '\0';
  return mrgi_error_set(err, MRGI_ERR_IO,
                        "cannot create a temporary file for '%s': %d names already taken",
                        final_path, MRGI_ATOMIC_FILE_MAX_ATTEMPTS);
}

mrgi_status mrgi_atomic_file_commit(const char* temp_path, const char* final_path,
                                    mrgi_error* err)
{
  if (!temp_path || temp_path[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "temporary path is NULL or empty");
  }
  if (!final_path || final_path[0] == '\0')
  {
    mrgi_atomic_file_abort(temp_path);
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output path is NULL or empty");
  }
  if (rename(temp_path, final_path) != 0)
  {
    const int saved = errno;
    mrgi_atomic_file_abort(temp_path);
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot move '%s' to '%s': %s", temp_path,
                          final_path, strerror(saved));
  }
  return MRGI_OK;
}

void mrgi_atomic_file_abort(const char* temp_path)
{
  if (temp_path && temp_path[0] != '\0')
  {
    (void)unlink(temp_path);
  }
}
