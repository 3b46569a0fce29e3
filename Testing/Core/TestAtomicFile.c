/* Tests of mrgi_atomic_file: unique temporaries, commit, abort, failures leave nothing. */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_atomic_file.h"
#include "mrgi_test.h"

#include <dirent.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Number of entries in `dir` whose name starts with `prefix`. */
static int count_entries_with_prefix(const char* dir, const char* prefix)
{
  DIR* d = opendir(dir);
  MRGI_CHECK(d != NULL);
  int count = 0;
  for (struct dirent* e = readdir(d); e; e = readdir(d))
  {
    count += strncmp(e->d_name, prefix, strlen(prefix)) == 0;
  }
  closedir(d);
  return count;
}

static void write_text(const char* path, const char* text)
{
  FILE* f = fopen(path, "wb");
  MRGI_CHECK(f != NULL);
  MRGI_CHECK(fputs(text, f) >= 0);
  MRGI_CHECK(fclose(f) == 0);
}

static void read_text(const char* path, char* buf, size_t n)
{
  FILE* f = fopen(path, "rb");
  MRGI_CHECK(f != NULL);
  const size_t got = fread(buf, 1, n - 1, f);
  buf[got] = '\0';
  fclose(f);
}

static void test_commit_replaces_atomically(void)
{
  char dir[1024];
  char final_path[1024];
  mrgi_test_tmp_path("", dir, sizeof(dir));
  mrgi_test_tmp_path("atomic_commit.txt", final_path, sizeof(final_path));
  unlink(final_path);
  write_text(final_path, "old");

  char temp[MRGI_ATOMIC_FILE_PATH_MAX];
  MRGI_CHECK(mrgi_atomic_file_begin(final_path, temp, sizeof(temp), NULL) == MRGI_OK);
  MRGI_CHECK(strncmp(temp, final_path, strlen(final_path)) == 0);
  MRGI_CHECK(strstr(temp, ".tmp-") != NULL);
  MRGI_CHECK(mrgi_test_file_exists(temp));

  /* A second writer of the same output gets a different temporary. */
  char temp2[MRGI_ATOMIC_FILE_PATH_MAX];
  MRGI_CHECK(mrgi_atomic_file_begin(final_path, temp2, sizeof(temp2), NULL) == MRGI_OK);
  MRGI_CHECK(strcmp(temp, temp2) != 0);
  mrgi_atomic_file_abort(temp2);
  MRGI_CHECK(!mrgi_test_file_exists(temp2));

  write_text(temp, "new");
  char buf[16];
  read_text(final_path, buf, sizeof(buf));
  MRGI_CHECK(strcmp(buf, "old") == 0); /* not visible before commit */
  MRGI_CHECK(mrgi_atomic_file_commit(temp, final_path, NULL) == MRGI_OK);
  read_text(final_path, buf, sizeof(buf));
  MRGI_CHECK(strcmp(buf, "new") == 0);
  MRGI_CHECK(!mrgi_test_file_exists(temp));
  MRGI_CHECK(count_entries_with_prefix(dir, "atomic_commit.txt.tmp-") == 0);
  unlink(final_path);
}

static void test_abort_removes_temporary(void)
{
  char final_path[1024];
  mrgi_test_tmp_path("atomic_abort.txt", final_path, sizeof(final_path));
  unlink(final_path);
  char temp[MRGI_ATOMIC_FILE_PATH_MAX];
  MRGI_CHECK(mrgi_atomic_file_begin(final_path, temp, sizeof(temp), NULL) == MRGI_OK);
  write_text(temp, "partial");
  mrgi_atomic_file_abort(temp);
  MRGI_CHECK(!mrgi_test_file_exists(temp));
  MRGI_CHECK(!mrgi_test_file_exists(final_path));
  mrgi_atomic_file_abort(temp); /* already gone: fine */
  mrgi_atomic_file_abort(NULL);
  mrgi_atomic_file_abort("");
}

static void test_missing_directory_fails_cleanly(void)
{
  char dir[1024];
  char final_path[1024];
  mrgi_test_tmp_path("no_such_dir", dir, sizeof(dir));
  mrgi_test_tmp_path("no_such_dir/out.exr", final_path, sizeof(final_path));
  rmdir(dir);
  char temp[MRGI_ATOMIC_FILE_PATH_MAX];
  mrgi_error err;
  MRGI_CHECK(mrgi_atomic_file_begin(final_path, temp, sizeof(temp), &err) == MRGI_ERR_IO);
  MRGI_CHECK(strstr(err.message, "cannot create temporary file"));
  MRGI_CHECK(strstr(err.message, "No such file or directory"));
  MRGI_CHECK(strstr(err.message, final_path));
  MRGI_CHECK(temp[0] == '\0');
  MRGI_CHECK(!mrgi_test_file_exists(dir));
}

static void test_commit_failure_removes_temporary(void)
{
  char final_path[1024];
  char bad_target[1024];
  mrgi_test_tmp_path("atomic_commit_fail.txt", final_path, sizeof(final_path));
  mrgi_test_tmp_path("no_such_dir/target.txt", bad_target, sizeof(bad_target));
  char temp[MRGI_ATOMIC_FILE_PATH_MAX];
  MRGI_CHECK(mrgi_atomic_file_begin(final_path, temp, sizeof(temp), NULL) == MRGI_OK);
  mrgi_error err;
  MRGI_CHECK(mrgi_atomic_file_commit(temp, bad_target, &err) == MRGI_ERR_IO);
  MRGI_CHECK(strstr(err.message, "cannot move"));
  MRGI_CHECK(!mrgi_test_file_exists(temp));
  MRGI_CHECK(!mrgi_test_file_exists(bad_target));
}

static void test_bad_arguments(void)
{
  char temp[MRGI_ATOMIC_FILE_PATH_MAX];
  mrgi_error err;
  MRGI_CHECK(mrgi_atomic_file_begin(NULL, temp, sizeof(temp), &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL or empty"));
  MRGI_CHECK(mrgi_atomic_file_begin("", temp, sizeof(temp), &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL or empty"));
  MRGI_CHECK(mrgi_atomic_file_begin("/tmp/x", NULL, 100, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "buffer"));
  char small[8];
  MRGI_CHECK(mrgi_atomic_file_begin("/tmp/x", small, sizeof(small), &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "too small"));
  MRGI_CHECK(mrgi_atomic_file_begin("/tmp/", temp, sizeof(temp), &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "directory"));
  MRGI_CHECK(mrgi_atomic_file_commit(NULL, "/tmp/x", &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "temporary path"));
  MRGI_CHECK(mrgi_atomic_file_commit("/tmp/x.tmp-1-0", "", &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output path"));
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_commit_replaces_atomically),
    MRGI_TEST_CASE(test_abort_removes_temporary),
    MRGI_TEST_CASE(test_missing_directory_fails_cleanly),
    MRGI_TEST_CASE(test_commit_failure_removes_temporary),
    MRGI_TEST_CASE(test_bad_arguments),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
