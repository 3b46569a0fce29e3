/* mrgi_ply_check: sound PLY files pass (ASCII and binary, with and without
 * faces); malformed headers, missing coordinates and truncated bodies fail
 * with a message naming the problem. */
#include "mrgi_ply_check.h"
#include "mrgi_test.h"

#include <string.h>

static const char* write_file(const char* name, const void* data, size_t size)
{
  static char path[512];
  mrgi_test_tmp_path(name, path, sizeof(path));
  FILE* f = fopen(path, "wb");
  MRGI_CHECK(f != NULL);
  MRGI_CHECK(fwrite(data, 1, size, f) == size);
  fclose(f);
  return path;
}

static void expect_failure(const char* name, const char* text, const char* expected)
{
  mrgi_error err;
  const char* path = write_file(name, text, strlen(text));
  const mrgi_status status = mrgi_ply_check(path, NULL, &err);
  MRGI_CHECK(status == MRGI_ERR_FORMAT);
  if (!strstr(err.message, expected))
  {
    MRGI_FAIL("message '%s' lacks '%s'", err.message, expected);
  }
}

static const char* const header = "ply\nformat ascii 1.0\ncomment test\nelement vertex 3\n"
                                  "property float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\n"
                                  "end_header\n";

static void test_sound_files(void)
{
  mrgi_error err;
  mrgi_ply_info info;
  char text[1024];
  snprintf(text, sizeof(text), "%s0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", header);
  MRGI_CHECK(mrgi_ply_check(write_file("ok.ply", text, strlen(text)), &info, &err) == MRGI_OK);
  MRGI_CHECK(info.vertex_count == 3 && info.face_count == 1 && info.binary == 0);

  /* A point cloud: vertices only, CRLF line ends. */
  const char* points = "ply\r\nformat ascii 1.0\r\nelement vertex 2\r\nproperty float x\r\n"
                       "property float y\r\nproperty float z\r\nend_header\r\n0 0 0\r\n1 1 1\r\n";
  MRGI_CHECK(mrgi_ply_check(write_file("points.ply", points, strlen(points)), &info, &err) == MRGI_OK);
  MRGI_CHECK(info.vertex_count == 2 && info.face_count == 0);
}

static void test_binary(void)
{
  mrgi_error err;
  mrgi_ply_info info;
  /* Binary: 2 vertices x 12 bytes needed. */
  const char* bheader = "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n";
  unsigned char binary[256];
  const size_t hl = strlen(bheader);
  memcpy(binary, bheader, hl);
  memset(binary + hl, 0, 24);
  MRGI_CHECK(mrgi_ply_check(write_file("bin.ply", binary, hl + 24), &info, &err) == MRGI_OK);
  MRGI_CHECK(info.binary == 1);
  MRGI_CHECK(mrgi_ply_check(write_file("bin_short.ply", binary, hl + 23), NULL, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "truncated") != NULL);
}

static void test_malformed_files(void)
{
  expect_failure("no_magic.ply", "plx\nformat ascii 1.0\nend_header\n", "not a PLY");
  expect_failure("no_yz.ply", "ply\nformat ascii 1.0\nelement vertex 99\nproperty float x\nend_header\n1\n", "lacks y z");
  expect_failure("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "end_header");
  expect_failure("no_format.ply", "ply\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n", "format");
  expect_failure("bad_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n", "bad property");
  expect_failure("bad_count.ply", "ply\nformat ascii 1.0\nelement vertex -4\nend_header\n", "bad element");
  expect_failure("no_vertex.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int v\nend_header\n", "no vertex");
  expect_failure("empty.ply", "", "empty");
  char text[1024];
  snprintf(text, sizeof(text), "%s0 0 0\n1 0 0\n", header);
  expect_failure("truncated.ply", text, "truncated");
}

static void test_missing_file_and_bad_arguments(void)
{
  mrgi_error err;
  char missing[512];
  MRGI_CHECK(mrgi_ply_check(mrgi_test_tmp_path("does-not-exist.ply", missing, sizeof(missing)), NULL, &err) == MRGI_ERR_IO);
  MRGI_CHECK(strstr(err.message, "cannot open") != NULL);
  MRGI_CHECK(mrgi_ply_check(NULL, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_sound_files),
    MRGI_TEST_CASE(test_binary),
    MRGI_TEST_CASE(test_malformed_files),
    MRGI_TEST_CASE(test_missing_file_and_bad_arguments),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
