/**
 * @file mrgi_test.h
 * @brief Minimal assertion macros for MRGICore unit tests.
 *
 * Each test program runs its checks in order and returns non-zero from main
 * at the first failed check, printing file, line and the failed expression.
 */
#ifndef MRGI_TEST_H
#define MRGI_TEST_H

#include <math.h>
#include <stdint.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>

#define MRGI_CHECK(cond)                                                     \
  do {                                                                       \
    if (!(cond)) {                                                           \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
      exit(1);                                                               \
    }                                                                        \
  } while (0)

#define MRGI_CHECK_NEAR(a, b, tol)                                           \
  do {                                                                       \
    double mrgi_a_ = (double)(a), mrgi_b_ = (double)(b);                     \
    if (!(fabs(mrgi_a_ - mrgi_b_) <= (double)(tol))) {                       \
      fprintf(stderr, "%s:%d: %s = %.9g, %s = %.9g, differ by more than %g\n", \
              __FILE__, __LINE__, #a, mrgi_a_, #b, mrgi_b_, (double)(tol));  \
      exit(1);                                                               \
    }                                                                        \
  } while (0)

/* Path of a scratch file for this test: $MRGI_TEST_TMP/name (or /tmp/name). */
static inline const char* mrgi_test_tmp_path(const char* name, char* buf, size_t n)
{
  const char* dir = getenv("MRGI_TEST_TMP");
  snprintf(buf, n, "%s/%s", dir && dir[0] ? dir : "/tmp", name);
  return buf;
}

/* Whether anything exists at `path`. */
static inline int mrgi_test_file_exists(const char* path)
{
  struct stat info;
  return stat(path, &info) == 0;
}

/* The whole (non-empty) file at `path`, malloc'ed; its size in *size. */
static inline uint8_t* mrgi_test_read_file(const char* path, size_t* size)
{
  FILE* f = fopen(path, "rb");
  MRGI_CHECK(f != NULL);
  MRGI_CHECK(fseek(f, 0, SEEK_END) == 0);
  const long n = ftell(f);
  MRGI_CHECK(n > 0);
  MRGI_CHECK(fseek(f, 0, SEEK_SET) == 0);
  uint8_t* data = (uint8_t*)malloc((size_t)n);
  MRGI_CHECK(data != NULL);
  MRGI_CHECK(fread(data, 1, (size_t)n, f) == (size_t)n);
  fclose(f);
  *size = (size_t)n;
  return data;
}

/* Write `size` bytes to `path` (size 0 makes an empty file). */
static inline void mrgi_test_write_file(const char* path, const uint8_t* data, size_t size)
{
  FILE* f = fopen(path, "wb");
  MRGI_CHECK(f != NULL);
  MRGI_CHECK(size == 0 || fwrite(data, 1, size, f) == size);
  MRGI_CHECK(fclose(f) == 0);
}

#endif
