/* mrgi_pcd_check: well-formed ascii, binary and binary_compressed headers
 * and bodies pass with what they declare; every case that crashed PCL
 * 1.13's reader, made it allocate what the file cannot hold, or made it
 * return wrong data silently (Documentation/reliability/pcl.md) is refused
 * with a message naming the file and the problem; the path entry refuses
 * directories and missing files. */
#include "mrgi_pcd_check.h"
#include "mrgi_test.h"

#include <stdio.h>
#include <string.h>

static char g_buffer[1 << 16];

/* A header with the given pieces, then `body` of `body_size` bytes, in
 * g_buffer; returns the total size. */
static size_t make(const char* fields, const char* size, const char* type, const char* count,
  const char* width, const char* height, const char* points, const char* data, const void* body,
  size_t body_size)
{
  int n = snprintf(g_buffer, sizeof(g_buffer),
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS %s\nSIZE %s\nTYPE %s\n%s%s%s"
    "WIDTH %s\n%s%s%sVIEWPOINT 1 2 3 1 0 0 0\nPOINTS %s\nDATA %s\n",
    fields, size, type, count ? "COUNT " : "", count ? count : "", count ? "\n" : "", width,
    height ? "HEIGHT " : "", height ? height : "", height ? "\n" : "", points, data);
  MRGI_CHECK(n > 0 && (size_t)n + body_size < sizeof(g_buffer));
  memcpy(g_buffer + n, body, body_size);
  return (size_t)n + body_size;
}

static void expect_ok(size_t size, mrgi_pcd_info* info)
{
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status st = mrgi_pcd_check_buffer(g_buffer, size, "t.pcd", 1000000, info, &err);
  if (st != MRGI_OK)
  {
    MRGI_FAIL("expected success, got: %s", err.message);
  }
}

static void expect_error(size_t size, const char* needle)
{
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  mrgi_pcd_info info;
  const mrgi_status st = mrgi_pcd_check_buffer(g_buffer, size, "t.pcd", 1000000, &info, &err);
  printf("  -> %s\n", err.message);
  MRGI_CHECK(st == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "t.pcd") != NULL);
  if (!strstr(err.message, needle))
  {
    MRGI_FAIL("message '%s' lacks '%s'", err.message, needle);
  }
}

static void test_valid(void)
{
  mrgi_pcd_info info;
  const char* ascii = "0 0 0 255\n1 0 0 7\n\n0 1 nan 3\n";
  expect_ok(make("x y z rgb", "4 4 4 4", "F F F U", "1 1 1 1", "3", "1", "3", "ascii", ascii,
              strlen(ascii)),
    &info);
  MRGI_CHECK(info.points == 3 && info.width == 3 && info.height == 1);
  MRGI_CHECK(info.data == MRGI_PCD_ASCII && info.record_size == 16 && info.field_count == 4);
  MRGI_CHECK(info.has_viewpoint && info.viewpoint[0] == 1.0 && info.viewpoint[3] == 1.0);
  /* No COUNT, no HEIGHT (PCD v.5 files, bunny.pcd). */
  expect_ok(
    make("x y z", "4 4 4", "F F F", NULL, "2", NULL, "2", "ascii", "1 2 3\r\n4 5 6\r\n", 14),
    &info);
  MRGI_CHECK(info.height == 1 && info.record_size == 12);
  /* Binary, organized 2 x 2, a field with COUNT 3 and a double. */
  unsigned char body[4 * (12 + 12 + 1 + 8)];
  memset(body, 0, sizeof(body));
  expect_ok(make("x y z normal _ d", "4 4 4 4 1 8", "F F F F U F", "1 1 1 3 1 1", "2", "2", "4",
              "binary", body, sizeof(body)),
    &info);
  MRGI_CHECK(info.record_size == 12 + 12 + 1 + 8 && info.points == 4 && info.height == 2);
  /* binary_compressed: sizes consistent (the LZF stream is PCL's to check). */
  unsigned char comp[8 + 20];
  const unsigned u = 3 * 12, c = 20;
  memcpy(comp, (const unsigned char[4]){ (unsigned char)c, 0, 0, 0 }, 4);
  memcpy(comp + 4, (const unsigned char[4]){ (unsigned char)u, 0, 0, 0 }, 4);
  memset(comp + 8, 0, 20);
  expect_ok(make("x y z", "4 4 4", "F F F", "1 1 1", "3", "1", "3", "binary_compressed", comp,
              sizeof(comp)),
    &info);
  MRGI_CHECK(info.data == MRGI_PCD_BINARY_COMPRESSED);
}

static void test_bad_headers(void)
{
  const char* ok = "0 0 0\n1 0 0\n0 1 0\n";
  const size_t n = strlen(ok);
  expect_error(0, "empty");
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "3", NULL, "3", "ascii", ok, n) - n - 11, "DATA");
  expect_error(make("x y z", "4 4 4", "Q F F", NULL, "3", NULL, "3", "ascii", ok, n), "TYPE");
  expect_error(make("x y z", "3 4 4", "F F F", NULL, "3", NULL, "3", "ascii", ok, n), "SIZE");
  expect_error(make("x y z", "4 4", "F F F", NULL, "3", NULL, "3", "ascii", ok, n), "SIZE");
  expect_error(
    make("x y z", "4 4 4", "F F F", "1 1 2000000000", "3", NULL, "3", "ascii", ok, n), "COUNT");
  expect_error(make("x y z", "4 4 4", "F F F", "1 1 0", "3", NULL, "3", "ascii", ok, n), "COUNT");
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "-5", NULL, "3", "ascii", ok, n), "WIDTH");
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "abc", NULL, "3", "ascii", ok, n), "WIDTH");
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "3", NULL, "7", "ascii", ok, n), "POINTS");
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "0", NULL, "0", "ascii", "", 0), "no points");
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "2000000000", NULL, "2000000000", "ascii", ok, n),
    "more than");
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "100000", "100000", "10000000000", "binary", ok, n),
    "more than");
  expect_error(
    make("a b c", "4 4 4", "F F F", NULL, "3", NULL, "3", "ascii", ok, n), "no field 'x'");
  expect_error(make("x y z", "4 4 4", "F F I", NULL, "3", NULL, "3", "ascii", ok, n), "'z'");
  expect_error(
    make("x y z x", "4 4 4 4", "F F F F", NULL, "3", NULL, "3", "ascii", ok, n), "twice");
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "3", NULL, "3", "foo", ok, n), "DATA 'foo'");
  expect_error(make("x y z", "2 4 4", "F F F", NULL, "3", NULL, "3", "ascii", ok, n), "SIZE 2");
  /* No FIELDS at all (PCL 1.13 crashed on this). */
  const char* nofields = "VERSION 0.7\nWIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n0 0 0\n";
  memcpy(g_buffer, nofields, strlen(nofields));
  expect_error(strlen(nofields), "lacks FIELDS");
  /* Random bytes (crashed PCL): no DATA line / unknown key. */
  for (size_t i = 0; i < 4000; ++i)
  {
    g_buffer[i] = (char)((i * 2654435761u) >> 13);
  }
  expect_error(4000, "binary data");
  /* One line longer than the limit. */
  {
    const size_t big = 3 * MRGI_PCD_MAX_LINE;
    char* b = (char*)malloc(big);
    MRGI_CHECK(b != NULL);
    memcpy(b, "FIELDS ", 7);
    memset(b + 7, 'x', big - 7);
    mrgi_error err;
    MRGI_CHECK(mrgi_pcd_check_buffer(b, big, "t.pcd", 10, NULL, &err) == MRGI_ERR_FORMAT);
    printf("  -> %s\n", err.message);
    MRGI_CHECK(strstr(err.message, "longer than") != NULL);
    free(b);
  }
  const char* v = "VIEWPOINT 0 0 0 1 0 0\n";
  size_t s = make("x y z", "4 4 4", "F F F", NULL, "3", NULL, "3", "ascii", ok, n);
  char* at = strstr(g_buffer, "VIEWPOINT");
  memcpy(at, v, strlen(v) - 1);
  memcpy(at + strlen(v) - 1, " \n", 2);
  expect_error(s, "VIEWPOINT");
}

static void test_bad_bodies(void)
{
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "5", NULL, "5", "ascii", "0 0 0\n1 0 0\n", 12),
    "truncated");
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "3", NULL, "3", "ascii", "a b c\nx y z\n1 2\n", 16),
    "not a number");
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "3", NULL, "3", "ascii", "1 2 3\n1 2\n1 2 3\n", 17),
    "has 2 values");
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "2", NULL, "2", "ascii", "1 2 3\n1 2 3\n1 2 3\n", 18),
    "more data lines");
  unsigned char body[12 * 10];
  memset(body, 0, sizeof(body));
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "1000", NULL, "1000", "binary", body, sizeof(body)),
    "truncated");
  unsigned char comp[8 + 10];
  memset(comp, 0, sizeof(comp));
  comp[0] = 100;  /* 100 compressed bytes declared, 10 present */
  comp[5] = 0x2E; /* 12000 = 0x2EE0 */
  comp[4] = 0xE0;
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "1000", NULL, "1000", "binary_compressed",
                 comp, sizeof(comp)),
    "truncated");
  comp[0] = 10;
  comp[4] = 0xF0;
  comp[5] = comp[6] = comp[7] = 0xFF; /* ~4 GiB uncompressed */
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "1000", NULL, "1000", "binary_compressed",
                 comp, sizeof(comp)),
    "uncompressed");
  comp[4] = 0xE0;
  comp[5] = 0x2E;
  comp[6] = comp[7] = 0;
  expect_error(make("x y z", "4 4 4", "F F F", NULL, "1000", NULL, "1000", "binary_compressed",
                 comp, sizeof(comp)),
    "LZF");
  expect_error(
    make("x y z", "4 4 4", "F F F", NULL, "1000", NULL, "1000", "binary_compressed", comp, 4),
    "lacks its two sizes");
}

/* WIDTH x HEIGHT beyond int64 with a limit that lets each through. */
static void test_no_overflow(void)
{
  const char* h = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1099511627776\n"
                  "HEIGHT 1099511627776\nPOINTS 1099511627776\nDATA binary\n";
  mrgi_error err;
  MRGI_CHECK(
    mrgi_pcd_check_buffer(h, strlen(h), "t.pcd", INT64_MAX, NULL, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "is not POINTS") != NULL);
}

static void test_paths(void)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_pcd_check("/", 10, NULL, &err) == MRGI_ERR_IO);
  MRGI_CHECK(mrgi_pcd_check("/nonexistent/x.pcd", 10, NULL, &err) == MRGI_ERR_IO);
  MRGI_CHECK(strstr(err.message, "/nonexistent/x.pcd") != NULL);
  MRGI_CHECK(mrgi_pcd_check(NULL, 10, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_pcd_check_buffer("x", 1, NULL, 0, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  const char* tmp = getenv("MRGI_TEST_TMP");
  char path[1024];
  snprintf(path, sizeof(path), "%s/TestPCDCheck.pcd", tmp ? tmp : ".");
  const size_t n = make("x y z", "4 4 4", "F F F", NULL, "1", NULL, "1", "ascii", "1 2 3\n", 6);
  FILE* fp = fopen(path, "wb");
  MRGI_CHECK(fp != NULL);
  MRGI_CHECK(fwrite(g_buffer, 1, n, fp) == n);
  fclose(fp);
  mrgi_pcd_info info;
  MRGI_CHECK(mrgi_pcd_check(path, 10, &info, &err) == MRGI_OK);
  MRGI_CHECK(info.points == 1);
  remove(path);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_valid),
    MRGI_TEST_CASE(test_bad_headers),
    MRGI_TEST_CASE(test_bad_bodies),
    MRGI_TEST_CASE(test_no_overflow),
    MRGI_TEST_CASE(test_paths),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
