/* mrgi_las: LAS 1.2 and 1.4 files written here byte by byte (formats 0, 2,
 * 3, 6, 7, 10, extra bytes) read back exactly: UTM-sized coordinates keep
 * millimetres after recentring, attributes and RGB (8- and 16-bit) come
 * through; LAZ, truncated files, bad signatures, versions, scales, record
 * lengths and counts are refused with a message naming the problem. */
#include "mrgi_las.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct test_point
{
  double x, y, z;
  uint16_t intensity;
  uint8_t return_number, number_of_returns, classification;
  uint16_t rgb[3];
} test_point;

static void put_u16(unsigned char* p, unsigned v)
{
  p[0] = (unsigned char)(v & 0xFF);
  p[1] = (unsigned char)((v >> 8) & 0xFF);
}

static void put_u32(unsigned char* p, uint32_t v)
{
  for (int i = 0; i < 4; ++i)
  {
    p[i] = (unsigned char)((v >> (8 * i)) & 0xFF);
  }
}

static void put_u64(unsigned char* p, uint64_t v)
{
  put_u32(p, (uint32_t)(v & 0xFFFFFFFFu));
  put_u32(p + 4, (uint32_t)(v >> 32));
}

static void put_f64(unsigned char* p, double v)
{
  uint64_t u;
  memcpy(&u, &v, sizeof(u));
  put_u64(p, u);
}

/* A LAS file of version 1.`minor`, point `format`, `extra` extra bytes per
 * record, scale 0.001 and the given offsets. The caller frees it. */
static unsigned char* make_las(int minor, int format, int extra, const test_point* points, int n,
  const double offset[3], size_t* size)
{
  const int header = minor >= 4 ? 375 : minor == 3 ? 235 : 227;
  const int record = mrgi_las_record_length(format) + extra;
  *size = (size_t)header + (size_t)record * (size_t)n;
  unsigned char* b = (unsigned char*)calloc(1, *size);
  MRGI_CHECK(b != NULL);
  memcpy(b, "LASF", 4);
  b[24] = 1;
  b[25] = (unsigned char)minor;
  put_u16(b + 94, (unsigned)header);
  put_u32(b + 96, (uint32_t)header);
  b[104] = (unsigned char)format;
  put_u16(b + 105, (unsigned)record);
  put_u32(b + 107, minor >= 4 ? 0u : (uint32_t)n);
  if (minor >= 4)
  {
    put_u64(b + 247, (uint64_t)n);
  }
  for (int c = 0; c < 3; ++c)
  {
    put_f64(b + 131 + 8 * c, 0.001);
    put_f64(b + 155 + 8 * c, offset[c]);
  }
  const int extended = format >= 6;
  const int rgb = format == 2 ? 20 : (format == 3 || format == 5) ? 28 : (format >= 7 && format != 9) ? 30 : -1;
  for (int i = 0; i < n; ++i)
  {
    unsigned char* r = b + header + (size_t)record * (size_t)i;
    const double xyz[3] = { points[i].x, points[i].y, points[i].z };
    for (int c = 0; c < 3; ++c)
    {
      put_u32(r + 4 * c, (uint32_t)(int32_t)lround((xyz[c] - offset[c]) / 0.001));
    }
    put_u16(r + 12, points[i].intensity);
    if (extended)
    {
      r[14] = (unsigned char)(points[i].return_number | (points[i].number_of_returns << 4));
      r[16] = points[i].classification;
    }
    else
    {
      r[14] = (unsigned char)(points[i].return_number | (points[i].number_of_returns << 3));
      r[15] = points[i].classification;
    }
    for (int c = 0; rgb >= 0 && c < 3; ++c)
    {
      put_u16(r + rgb + 2 * c, points[i].rgb[c]);
    }
  }
  return b;
}

static const test_point utm[3] = {
  { 512345.678, 5432109.876, 312.345, 100, 1, 2, 2, { 65535, 0, 32768 } },
  { 512346.001, 5432110.002, 313.001, 200, 2, 2, 5, { 0, 65535, 0 } },
  { 512399.999, 5432150.500, 290.250, 300, 1, 1, 9, { 1000, 2000, 3000 } },
};
static const double utm_offset[3] = { 500000.0, 5400000.0, 0.0 };

static void check_points(const mrgi_las_points* p, const test_point* expected, int n, int has_rgb,
  double rgb_scale, int extended)
{
  MRGI_CHECK(p->count == n);
  for (int i = 0; i < n; ++i)
  {
    const double xyz[3] = { expected[i].x, expected[i].y, expected[i].z };
    for (int c = 0; c < 3; ++c)
    {
      /* Recentred float keeps well under a millimetre here. */
      MRGI_CHECK_NEAR((double)p->positions[3 * i + c] + p->origin[c], xyz[c], 2e-4);
    }
    MRGI_CHECK(p->intensity[i] == expected[i].intensity);
    MRGI_CHECK(p->return_number[i] == expected[i].return_number);
    MRGI_CHECK(p->number_of_returns[i] == expected[i].number_of_returns);
    MRGI_CHECK(p->classification[i] == (extended ? expected[i].classification : (expected[i].classification & 0x1F)));
    if (has_rgb)
    {
      MRGI_CHECK(p->colors != NULL);
      for (int c = 0; c < 3; ++c)
      {
        MRGI_CHECK_NEAR(p->colors[3 * i + c], expected[i].rgb[c] * rgb_scale, 1e-6);
      }
    }
    else
    {
      MRGI_CHECK(p->colors == NULL);
    }
  }
  MRGI_CHECK_NEAR(p->bounds[0], 512345.678, 1e-6);
  MRGI_CHECK_NEAR(p->bounds[1], 512399.999, 1e-6);
  MRGI_CHECK_NEAR(p->origin[1], 0.5 * (5432109.876 + 5432150.500), 1e-6);
}

static void test_formats(void)
{
  static const struct
  {
    int minor, format, extra, rgb;
  } cases[] = {
    { 0, 0, 0, 0 }, { 2, 0, 0, 0 }, { 2, 1, 0, 0 }, { 2, 2, 0, 1 }, { 2, 3, 0, 1 },
    { 3, 5, 0, 1 }, { 4, 6, 0, 0 }, { 4, 7, 0, 1 }, { 4, 8, 0, 1 }, { 4, 10, 0, 1 },
    { 2, 0, 7, 0 }, { 4, 7, 13, 1 },
  };
  for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]); ++k)
  {
    size_t size;
    unsigned char* b = make_las(cases[k].minor, cases[k].format, cases[k].extra, utm, 3, utm_offset, &size);
    mrgi_las_points p;
    mrgi_error err;
    const mrgi_status status = mrgi_las_read_buffer(b, size, 1000, &p, &err);
    if (status != MRGI_OK)
    {
      MRGI_FAIL("1.%d format %d: %s", cases[k].minor, cases[k].format, err.message);
    }
    check_points(&p, utm, 3, cases[k].rgb, 1.0 / 65535.0, cases[k].format >= 6);
    mrgi_las_points_destroy(&p);
    MRGI_CHECK(p.positions == NULL && p.count == 0);
    free(b);
  }
}

static void test_eight_bit_rgb_and_file(void)
{
  test_point small[2] = { utm[0], utm[1] };
  small[0].rgb[0] = 255;
  small[0].rgb[1] = 0;
  small[0].rgb[2] = 128;
  small[1].rgb[0] = 10;
  small[1].rgb[1] = 20;
  small[1].rgb[2] = 30;
  size_t size;
  unsigned char* b = make_las(2, 2, 0, small, 2, utm_offset, &size);
  char path[512];
  mrgi_test_tmp_path("test-las-8bit.las", path, sizeof(path));
  FILE* f = fopen(path, "wb");
  MRGI_CHECK(f != NULL);
  MRGI_CHECK(fwrite(b, 1, size, f) == size);
  fclose(f);
  mrgi_las_points p;
  mrgi_error err;
  MRGI_CHECK(mrgi_las_read(path, 1000, &p, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(p.colors[0], 1.0, 1e-6);
  MRGI_CHECK_NEAR(p.colors[2], 128.0 / 255.0, 1e-6);
  MRGI_CHECK_NEAR(p.colors[5], 30.0 / 255.0, 1e-6);
  mrgi_las_points_destroy(&p);
  free(b);
}

static void expect_error(const unsigned char* b, size_t size, mrgi_status expected_status, const char* expected)
{
  mrgi_las_points p;
  mrgi_error err;
  const mrgi_status status = mrgi_las_read_buffer(b, size, 1000, &p, &err);
  if (status != expected_status || !strstr(err.message, expected))
  {
    MRGI_FAIL("expected status %d with '%s', got %d: '%s'", (int)expected_status, expected,
      (int)status, err.message);
  }
  MRGI_CHECK(p.positions == NULL && p.count == 0);
}

static void test_bad_files(void)
{
  size_t size;
  unsigned char* good = make_las(2, 3, 0, utm, 3, utm_offset, &size);
  unsigned char* b = (unsigned char*)malloc(size);
  MRGI_CHECK(b != NULL);
#define RESET() memcpy(b, good, size)
  RESET();
  b[0] = 'X';
  expect_error(b, size, MRGI_ERR_FORMAT, "signature");
  RESET();
  expect_error(b, 100, MRGI_ERR_FORMAT, "shorter than a LAS header");
  RESET();
  b[25] = 7;
  expect_error(b, size, MRGI_ERR_FORMAT, "version 1.7");
  RESET();
  b[104] = (unsigned char)(3 | 0x80);
  expect_error(b, size, MRGI_ERR_UNSUPPORTED, "compressed LAZ is not supported");
  RESET();
  b[104] = 11;
  expect_error(b, size, MRGI_ERR_FORMAT, "point format 11");
  RESET();
  put_u16(b + 105, 20);
  expect_error(b, size, MRGI_ERR_FORMAT, "record length 20 is shorter");
  RESET();
  put_f64(b + 139, 0.0);
  expect_error(b, size, MRGI_ERR_FORMAT, "y scale factor");
  RESET();
  put_f64(b + 171, NAN);
  expect_error(b, size, MRGI_ERR_FORMAT, "z offset is not finite");
  RESET();
  expect_error(b, size - 1, MRGI_ERR_FORMAT, "truncated");
  RESET();
  put_u32(b + 107, 0xFFFFFFFFu);
  expect_error(b, size, MRGI_ERR_FORMAT, "truncated");
  RESET();
  put_u32(b + 107, 0);
  expect_error(b, size, MRGI_ERR_FORMAT, "no points");
  RESET();
  put_u32(b + 96, (uint32_t)size + 10);
  expect_error(b, size, MRGI_ERR_FORMAT, "point data offset");
  RESET();
  put_u16(b + 94, 100);
  expect_error(b, size, MRGI_ERR_FORMAT, "header size 100");
  {
    /* A LAS 1.4 file cut inside its 375-byte header (past the 227 bytes
       every version has): named as truncation. */
    size_t size14;
    unsigned char* las14 = make_las(4, 6, 0, utm, 3, utm_offset, &size14);
    MRGI_CHECK(las14 != NULL && size14 > 300);
    expect_error(las14, 300, MRGI_ERR_FORMAT, "ends inside its 375-byte header");
    free(las14);
  }
  RESET();
  put_f64(b + 131, 1e308);
  put_f64(b + 155, 1e308);
  expect_error(b, size, MRGI_ERR_FORMAT, "overflow");
  RESET();
  put_f64(b + 131, 1e30);
  expect_error(b, size, MRGI_ERR_FORMAT, "too wide to recentre");
#undef RESET
  /* More points than the caller allows. */
  mrgi_las_points p;
  mrgi_error err;
  MRGI_CHECK(mrgi_las_read_buffer(good, size, 2, &p, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "exceed the limit") != NULL);
  MRGI_CHECK(mrgi_las_read_buffer(good, size, 0, &p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_las_read_buffer(NULL, size, 10, &p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  char missing[512];
  MRGI_CHECK(mrgi_las_read(mrgi_test_tmp_path("no-such.las", missing, sizeof(missing)), 10, &p, &err) == MRGI_ERR_IO);
  free(b);
  free(good);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_formats),
    MRGI_TEST_CASE(test_eight_bit_rgb_and_file),
    MRGI_TEST_CASE(test_bad_files),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
