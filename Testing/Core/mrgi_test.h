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

#endif
