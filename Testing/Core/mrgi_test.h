/**
 * @file mrgi_test.h
 * @brief Assertion macros and a runner of named cases for the core unit tests.
 *
 * A test program lists its cases and hands them to mrgi_test_main():
 *
 *     static void test_double(void) { MRGI_CHECK(...); ... }
 *     int main(int argc, char** argv)
 *     {
 *       static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_double), ... };
 *       return MRGI_TEST_MAIN(argc, argv, cases);
 *     }
 *
 * Every case runs (in the listed order); a failed check prints file, line and
 * the failed expression and ends its case only; at the end the program names
 * the failed cases and exits non-zero if there was one. `TestX --list` prints
 * the case names, `TestX --case NAME` (repeatable) runs only those cases.
 * Outside mrgi_test_main() (a program without cases) a failed check exits
 * with status 1.
 *
 * A failed case leaves what it allocated behind (tests only); a case that
 * crashes still ends the whole program.
 */
#ifndef MRGI_TEST_H
#define MRGI_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Where a failed check returns to: the running case's jump buffer, or NULL. */
static jmp_buf* mrgi_test_current_case_ = NULL;

/* A failed check: end the running case, or the program outside a case. */
static inline _Noreturn void mrgi_test_fail_(void)
{
  fflush(stdout);
  if (mrgi_test_current_case_)
  {
    longjmp(*mrgi_test_current_case_, 1);
  }
  exit(1);
}

#define MRGI_CHECK(cond)                                                                           \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);                     \
      mrgi_test_fail_();                                                                           \
    }                                                                                              \
  } while (0)

#define MRGI_CHECK_NEAR(a, b, tol)                                                                 \
  do                                                                                               \
  {                                                                                                \
    double mrgi_a_ = (double)(a), mrgi_b_ = (double)(b);                                           \
    if (!(fabs(mrgi_a_ - mrgi_b_) <= (double)(tol)))                                               \
    {                                                                                              \
      fprintf(stderr, "%s:%d: %s = %.9g, %s = %.9g, differ by more than %g\n", __FILE__, __LINE__, \
        #a, mrgi_a_, #b, mrgi_b_, (double)(tol));                                                  \
      mrgi_test_fail_();                                                                           \
    }                                                                                              \
  } while (0)

/* Fail unconditionally, with a printf-style message. */
#define MRGI_FAIL(...)                                                                             \
  do                                                                                               \
  {                                                                                                \
    fprintf(stderr, "%s:%d: failed: ", __FILE__, __LINE__);                                        \
    fprintf(stderr, __VA_ARGS__);                                                                  \
    fputc('\n', stderr);                                                                           \
    mrgi_test_fail_();                                                                             \
  } while (0)

/* One named case of a test program. */
typedef struct mrgi_test_case
{
  const char* name;
  void (*run)(void);
} mrgi_test_case;

/* A case named after its function. */
/* clang-format off */
#define MRGI_TEST_CASE(function) { #function, function }
/* clang-format on */

/* mrgi_test_main() over a static array of cases. */
#define MRGI_TEST_MAIN(argc, argv, cases)                                                          \
  mrgi_test_main((argc), (argv), (cases), sizeof(cases) / sizeof((cases)[0]))

/* Runs one case; 1 when it passed. (Its own function: nothing of the
 * caller's lives between setjmp and longjmp.) */
static inline int mrgi_test_run_case_(const mrgi_test_case* test)
{
  jmp_buf jump;
  if (setjmp(jump) != 0)
  {
    mrgi_test_current_case_ = NULL;
    return 0;
  }
  mrgi_test_current_case_ = &jump;
  test->run();
  mrgi_test_current_case_ = NULL;
  return 1;
}

/* The program name without its directory. */
static inline const char* mrgi_test_program_(const char* argv0)
{
  const char* slash = argv0 ? strrchr(argv0, '/') : NULL;
  return slash ? slash + 1 : (argv0 ? argv0 : "test");
}

/*
 * Runs the cases the command line asks for (all by default; `--case NAME`,
 * repeatable; `--list` prints the names). Returns main's exit code: 0 when
 * every case ran passed, 1 when one failed, 2 for a bad command line.
 */
static inline int mrgi_test_main(int argc, char** argv, const mrgi_test_case* cases, size_t count)
{
  const char* program = mrgi_test_program_(argc > 0 ? argv[0] : NULL);
  unsigned char* selected = (unsigned char*)calloc(count + 1, 1);
  unsigned char* failed = (unsigned char*)calloc(count + 1, 1);
  if (!selected || !failed)
  {
    fprintf(stderr, "%s: out of memory\n", program);
    return 2;
  }
  int any_selected = 0;
  for (int i = 1; i < argc; ++i)
  {
    if (strcmp(argv[i], "--list") == 0)
    {
      for (size_t c = 0; c < count; ++c)
      {
        printf("%s\n", cases[c].name);
      }
      free(selected);
      free(failed);
      return 0;
    }
    if (strcmp(argv[i], "--case") == 0 && i + 1 < argc)
    {
      const char* name = argv[++i];
      size_t c = 0;
      while (c < count && strcmp(cases[c].name, name) != 0)
      {
        ++c;
      }
      if (c == count)
      {
        fprintf(stderr, "%s: no case '%s' (--list lists them)\n", program, name);
        free(selected);
        free(failed);
        return 2;
      }
      selected[c] = 1;
      any_selected = 1;
      continue;
    }
    fprintf(stderr, "usage: %s [--list] [--case NAME]...\n", program);
    free(selected);
    free(failed);
    return 2;
  }
  size_t ran = 0, failures = 0;
  for (size_t c = 0; c < count; ++c)
  {
    if (any_selected && !selected[c])
    {
      continue;
    }
    printf("[ RUN    ] %s\n", cases[c].name);
    fflush(stdout);
    ++ran;
    if (mrgi_test_run_case_(&cases[c]))
    {
      printf("[     OK ] %s\n", cases[c].name);
    }
    else
    {
      failed[c] = 1;
      ++failures;
      printf("[ FAILED ] %s\n", cases[c].name);
    }
    fflush(stdout);
  }
  if (failures)
  {
    fprintf(stderr, "%s: %zu of %zu cases failed:", program, failures, ran);
    for (size_t c = 0; c < count; ++c)
    {
      if (failed[c])
      {
        fprintf(stderr, " %s", cases[c].name);
      }
    }
    fprintf(stderr, "\n");
  }
  else
  {
    printf("%s: all %zu cases passed\n", program, ran);
  }
  free(selected);
  free(failed);
  return failures ? 1 : 0;
}

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
