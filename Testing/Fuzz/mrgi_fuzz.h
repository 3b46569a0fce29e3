/**
 * @file mrgi_fuzz.h
 * @brief What every fuzz harness of Testing/Fuzz shares.
 *
 * A harness is one file that defines LLVMFuzzerTestOneInput(): it hands the
 * bytes to one reader and checks the reader's contract (a status from the
 * documented list, an error message on failure, outputs in their documented
 * ranges). A broken contract calls MRGI_FUZZ_REQUIRE, which aborts, so the
 * fuzzer reports it like a crash. The same file is linked twice (see
 * mrgi_add_fuzzer() in CMakeLists.txt): with libFuzzer in the fuzz build, and
 * with mrgi_fuzz_replay.c in every build, where it replays the seeds and the
 * regression inputs as an ordinary test.
 *
 * Readers that take a path get the input through a scratch file, one per
 * process (mrgi_fuzz_file()); new readers should get a buffer entry point and
 * be fuzzed through it instead.
 */
#ifndef MRGI_FUZZ_H
#define MRGI_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The libFuzzer entry point; returns 0 (inputs are never rejected from the corpus). */
int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

#ifdef __cplusplus
}
#endif

/** Abort with file, line and the failed condition: libFuzzer keeps the input as a crash.
 *  The message goes straight to file descriptor 2, like the sanitizers' reports,
 *  so a harness may silence the reader's own messages (stdio's stderr). */
#define MRGI_FUZZ_REQUIRE(condition)                                                               \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      mrgi_fuzz_broken_(__FILE__, __LINE__, #condition);                                           \
    }                                                                                              \
  } while (0)

static inline void mrgi_fuzz_broken_(const char* file, int line, const char* condition)
{
  char text[1024];
  const int n = snprintf(text, sizeof(text), "%s:%d: contract broken: %s\n", file, line, condition);
  if (n > 0)
  {
    const ssize_t written = write(2, text, (size_t)n < sizeof(text) ? (size_t)n : sizeof(text) - 1);
    (void)written;
  }
  abort();
}

static char mrgi_fuzz_path_[4096];

static inline void mrgi_fuzz_remove_file_(void)
{
  if (mrgi_fuzz_path_[0])
  {
    unlink(mrgi_fuzz_path_);
  }
}

/**
 * @brief Write `data` to this process's scratch file ($TMPDIR or /tmp,
 *        "mrgi-fuzz-PID" + suffix) and return its path.
 *
 * The file is rewritten on every call and removed at exit. Aborts when it
 * cannot be written: a harness that does not test the reader must not pass.
 */
static inline const char* mrgi_fuzz_file(const uint8_t* data, size_t size, const char* suffix)
{
  if (!mrgi_fuzz_path_[0])
  {
    const char* dir = getenv("TMPDIR");
    snprintf(mrgi_fuzz_path_, sizeof(mrgi_fuzz_path_), "%s/mrgi-fuzz-%ld%s",
      dir && dir[0] ? dir : "/tmp", (long)getpid(), suffix);
    atexit(mrgi_fuzz_remove_file_);
  }
  FILE* file = fopen(mrgi_fuzz_path_, "wb");
  MRGI_FUZZ_REQUIRE(file != NULL);
  MRGI_FUZZ_REQUIRE(size == 0 || fwrite(data, 1, size, file) == size);
  MRGI_FUZZ_REQUIRE(fclose(file) == 0);
  return mrgi_fuzz_path_;
}

/** Whether a failed call left a status and a non-empty, terminated message. */
#define MRGI_FUZZ_REQUIRE_ERROR(status, err)                                                       \
  do                                                                                               \
  {                                                                                                \
    MRGI_FUZZ_REQUIRE((err).status == (status));                                                   \
    MRGI_FUZZ_REQUIRE(memchr((err).message, '\0', sizeof((err).message)) != NULL);                 \
    MRGI_FUZZ_REQUIRE((err).message[0] != '\0');                                                   \
  } while (0)

#endif
