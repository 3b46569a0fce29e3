/* Tests of mrgi_exr: round trips, channel names and order, value sanitizing,
 * atomic writes, and rejection of missing, foreign, truncated and corrupt files. */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_exr.h"
#include "mrgi_test.h"

#include <dirent.h>
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- helpers ------------------------------------------------------------- */

static long find_bytes(const uint8_t* data, size_t size, const void* pattern, size_t length)
{
  for (size_t i = 0; i + length <= size; ++i)
  {
    if (memcmp(data + i, pattern, length) == 0)
    {
      return (long)i;
    }
  }
  return -1;
}

static void put_le32(uint8_t* p, int32_t v)
{
  const uint32_t u = (uint32_t)v;
  p[0] = (uint8_t)(u & 0xffu);
  p[1] = (uint8_t)((u >> 8) & 0xffu);
  p[2] = (uint8_t)((u >> 16) & 0xffu);
  p[3] = (uint8_t)((u >> 24) & 0xffu);
}

/* A w x h image whose every value is distinct and includes negatives,
 * fractions and values of very different magnitude. */
static mrgi_image make_pattern(int32_t w, int32_t h, int32_t c, float scale)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, w, h, c, NULL) == MRGI_OK);
  const size_t n = mrgi_image_value_count(&img);
  for (size_t i = 0; i < n; ++i)
  {
    const float sign = (i % 3 == 0) ? -1.0f : 1.0f;
    img.pixels[i] = sign * scale * (0.001f + (float)i * 0.37f);
  }
  return img;
}

static void expect_read_fails(const char* path, mrgi_status expected, const char* fragment)
{
  mrgi_error err;
  mrgi_image img = { 7, 7, 7, (float*)&img }; /* garbage: must be zeroed */
  const mrgi_status s = mrgi_exr_read(path, &img, &err);
  if (s != expected || !strstr(err.message, fragment))
  {
    fprintf(stderr, "reading '%s': got %s '%s', expected %s with '%s'\n", path,
            mrgi_status_name(s), err.message, mrgi_status_name(expected), fragment);
  }
  MRGI_CHECK(s == expected);
  MRGI_CHECK(strstr(err.message, fragment));
  MRGI_CHECK(img.pixels == NULL && img.width == 0);
}

/* ---- round trips --------------------------------------------------------- */

static void test_float_round_trip_is_exact(void)
{
  char path[1024];
  mrgi_test_tmp_path("exr_float_rgba.exr", path, sizeof(path));
  /* 37 rows: more than one 16-line chunk and a partial last chunk. */
  mrgi_image img = make_pattern(19, 37, 4, 1.0f);
  img.pixels[5] = 1e30f;
  img.pixels[6] = -1e-30f;
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_FLOAT, NULL) == MRGI_OK);

  mrgi_image back;
  char names[4][MRGI_EXR_CHANNEL_NAME_SIZE];
  MRGI_CHECK(mrgi_exr_read_channels(path, &back, names, 4, NULL) == MRGI_OK);
  MRGI_CHECK(back.width == 19 && back.height == 37 && back.channels == 4);
  MRGI_CHECK(strcmp(names[0], "R") == 0 && strcmp(names[1], "G") == 0);
  MRGI_CHECK(strcmp(names[2], "B") == 0 && strcmp(names[3], "A") == 0);
  MRGI_CHECK(memcmp(back.pixels, img.pixels, mrgi_image_value_count(&img) * sizeof(float)) == 0);
  /* Row 0 is the top row: spot-check a pixel away from the diagonal. */
  MRGI_CHECK(mrgi_image_at(&back, 3, 30)[2] == mrgi_image_at(&img, 3, 30)[2]);
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&img);
}

/* A 16-line block of a real image (a 4x4 box average of the corridor's
 * ground truth) that OpenEXR 3.1.5 (Debian 12) wrote as a corrupt ZIP chunk:
 * read back with non-finite and negative values (also by OpenEXR's own C++
 * reader; ZIPS corrupted other images' lines). The writer stores pixels
 * uncompressed, which writes every image right. */
static void test_real_block_round_trip_is_exact(void)
{
  char data[1024];
  snprintf(data, sizeof(data), "%s/EXR/zip-fallback-16x64x3.f32", MRGI_TEST_DATA_DIR);
  FILE* f = fopen(data, "rb");
  MRGI_CHECK(f != NULL);
  if (!f)
  {
    return;
  }
  mrgi_image img = make_pattern(64, 16, 3, 0.0f);
  const size_t count = mrgi_image_value_count(&img);
  MRGI_CHECK(fread(img.pixels, sizeof(float), count, f) == count);
  fclose(f);
  char path[1024];
  mrgi_test_tmp_path("exr_real_block.exr", path, sizeof(path));
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_FLOAT, NULL) == MRGI_OK);
  mrgi_image back;
  MRGI_CHECK(mrgi_exr_read(path, &back, NULL) == MRGI_OK);
  MRGI_CHECK(back.width == 64 && back.height == 16 && back.channels == 3);
  MRGI_CHECK(memcmp(back.pixels, img.pixels, count * sizeof(float)) == 0);
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&img);
}

/* Every channel count of a colour image, RGBA included: OpenEXR 3.1's fast
 * unpackers for four HALF channels once scrambled RGBA into file order. */
static void test_half_round_trip_within_half_precision(void)
{
  for (int32_t channels = 1; channels <= 4; ++channels)
  {
    if (channels == 2)
    {
      continue; /* two channels need explicit names; see test_channel_names_and_order */
    }
    char path[1024];
    char file[64];
    snprintf(file, sizeof(file), "exr_half_%d.exr", channels);
    mrgi_test_tmp_path(file, path, sizeof(path));
    mrgi_image img = make_pattern(23, 17, channels, 0.01f);
    MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_HALF, NULL) == MRGI_OK);
    mrgi_image back;
    MRGI_CHECK(mrgi_exr_read(path, &back, NULL) == MRGI_OK);
    MRGI_CHECK(back.width == 23 && back.height == 17 && back.channels == channels);
    for (size_t i = 0; i < mrgi_image_value_count(&img); ++i)
    {
      const double tolerance = fmax(1e-3 * fabs(img.pixels[i]), 2.98023223876953125e-08);
      MRGI_CHECK_NEAR(back.pixels[i], img.pixels[i], tolerance);
    }
    mrgi_image_destroy(&back);
    mrgi_image_destroy(&img);
  }

  char path[1024];
  mrgi_test_tmp_path("exr_half_rgb.exr", path, sizeof(path));
  mrgi_image img = make_pattern(23, 17, 3, 0.01f);
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_HALF, NULL) == MRGI_OK);
  mrgi_image back;
  char names[3][MRGI_EXR_CHANNEL_NAME_SIZE];
  MRGI_CHECK(mrgi_exr_read_channels(path, &back, names, 3, NULL) == MRGI_OK);
  MRGI_CHECK(back.width == 23 && back.height == 17 && back.channels == 3);
  MRGI_CHECK(strcmp(names[0], "R") == 0 && strcmp(names[1], "G") == 0 &&
             strcmp(names[2], "B") == 0);
  const size_t n = mrgi_image_value_count(&img);
  for (size_t i = 0; i < n; ++i)
  {
    /* Relative 1e-3 for normal halves; below 2^-14 halves are subnormal with
     * a fixed spacing of 2^-24, so rounding errs by at most 2^-25. */
    const double tolerance = fmax(1e-3 * fabs(img.pixels[i]), 2.98023223876953125e-08);
    MRGI_CHECK_NEAR(back.pixels[i], img.pixels[i], tolerance);
  }
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&img);
}

static void test_half_conversion_rounding_and_subnormals(void)
{
  char path[1024];
  mrgi_test_tmp_path("exr_half_values.exr", path, sizeof(path));
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 8, 1, 1, NULL) == MRGI_OK);
  /* Exactly representable values must come back exactly, including the
   * largest half, the smallest normal and subnormals. */
  const float exact[8] = { 0.0f, 1.0f, -2.5f, 65504.0f, 6.103515625e-05f /* 2^-14 */,
                           5.9604644775390625e-08f /* 2^-24 */, -3.0517578125e-05f /* 2^-15 */,
                           1.0009765625f /* 1 + 2^-10 */ };
  memcpy(img.pixels, exact, sizeof(exact));
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_HALF, NULL) == MRGI_OK);
  mrgi_image back;
  MRGI_CHECK(mrgi_exr_read(path, &back, NULL) == MRGI_OK);
  for (int i = 0; i < 8; ++i)
  {
    MRGI_CHECK(back.pixels[i] == exact[i]);
  }
  mrgi_image_destroy(&back);

  /* Ties round to even: 1 + 2^-11 lies halfway between 1 and 1 + 2^-10. */
  img.pixels[0] = 1.00048828125f;
  img.pixels[1] = 1.00146484375f; /* 1 + 3*2^-11: halfway, rounds up to 1 + 2^-9 */
  img.pixels[2] = 2.98023223876953125e-08f; /* 2^-25: halfway to 2^-24, rounds to 0 */
  img.pixels[3] = 3.0e-08f;                 /* just above: rounds to 2^-24 */
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_HALF, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_exr_read(path, &back, NULL) == MRGI_OK);
  MRGI_CHECK(back.pixels[0] == 1.0f);
  MRGI_CHECK(back.pixels[1] == 1.001953125f);
  MRGI_CHECK(back.pixels[2] == 0.0f);
  MRGI_CHECK(back.pixels[3] == 5.9604644775390625e-08f);
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&img);
}

static void test_nonfinite_and_overflow_are_never_written(void)
{
  char path[1024];
  mrgi_test_tmp_path("exr_sanitize.exr", path, sizeof(path));
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 5, 1, 1, NULL) == MRGI_OK);
  const float values[5] = { NAN, INFINITY, -INFINITY, 1e6f, -70000.0f };
  memcpy(img.pixels, values, sizeof(values));

  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_HALF, NULL) == MRGI_OK);
  mrgi_image back;
  MRGI_CHECK(mrgi_exr_read(path, &back, NULL) == MRGI_OK);
  const float half_expected[5] = { 0.0f, 65504.0f, -65504.0f, 65504.0f, -65504.0f };
  for (int i = 0; i < 5; ++i)
  {
    MRGI_CHECK(back.pixels[i] == half_expected[i]);
  }
  mrgi_image_destroy(&back);

  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_FLOAT, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_exr_read(path, &back, NULL) == MRGI_OK);
  const float float_expected[5] = { 0.0f, FLT_MAX, -FLT_MAX, 1e6f, -70000.0f };
  for (int i = 0; i < 5; ++i)
  {
    MRGI_CHECK(back.pixels[i] == float_expected[i]);
  }
  int64_t nonfinite = -1;
  MRGI_CHECK(mrgi_image_count_nonfinite(&back, &nonfinite, NULL) == MRGI_OK && nonfinite == 0);
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&img);
}

static void test_channel_names_and_order(void)
{
  char path[1024];
  mrgi_test_tmp_path("exr_names.exr", path, sizeof(path));

  /* One channel defaults to Y. */
  mrgi_image gray = make_pattern(4, 3, 1, 1.0f);
  MRGI_CHECK(mrgi_exr_write(path, &gray, NULL, MRGI_EXR_FLOAT, NULL) == MRGI_OK);
  mrgi_image back;
  char names[8][MRGI_EXR_CHANNEL_NAME_SIZE];
  MRGI_CHECK(mrgi_exr_read_channels(path, &back, names, 8, NULL) == MRGI_OK);
  MRGI_CHECK(back.channels == 1 && strcmp(names[0], "Y") == 0);
  MRGI_CHECK(memcmp(back.pixels, gray.pixels, 12 * sizeof(float)) == 0);
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&gray);

  /* Custom names in an unusual order: read back as R, G, B, then the rest. */
  mrgi_image img = make_pattern(3, 2, 4, 1.0f);
  const char* const custom[4] = { "Z", "B", "R", "G" };
  MRGI_CHECK(mrgi_exr_write(path, &img, custom, MRGI_EXR_FLOAT, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_exr_read_channels(path, &back, names, 8, NULL) == MRGI_OK);
  MRGI_CHECK(back.channels == 4);
  MRGI_CHECK(strcmp(names[0], "R") == 0 && strcmp(names[1], "G") == 0);
  MRGI_CHECK(strcmp(names[2], "B") == 0 && strcmp(names[3], "Z") == 0);
  const int from[4] = { 2, 3, 1, 0 }; /* output channel k came from input channel from[k] */
  for (int32_t y = 0; y < 2; ++y)
  {
    for (int32_t x = 0; x < 3; ++x)
    {
      for (int k = 0; k < 4; ++k)
      {
        MRGI_CHECK(mrgi_image_at(&back, x, y)[k] == mrgi_image_at(&img, x, y)[from[k]]);
      }
    }
  }
  mrgi_image_destroy(&back);

  /* Fewer name slots than channels: only those are written. */
  memset(names, 0, sizeof(names));
  MRGI_CHECK(mrgi_exr_read_channels(path, &back, names, 2, NULL) == MRGI_OK);
  MRGI_CHECK(back.channels == 4 && strcmp(names[1], "G") == 0 && names[2][0] == '\0');
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&img);

  /* Two channels need names; they come back in file (alphabetical) order. */
  mrgi_image two = make_pattern(2, 2, 2, 1.0f);
  const char* const pair[2] = { "mask", "depth" };
  MRGI_CHECK(mrgi_exr_write(path, &two, pair, MRGI_EXR_HALF, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_exr_read_channels(path, &back, names, 8, NULL) == MRGI_OK);
  MRGI_CHECK(strcmp(names[0], "depth") == 0 && strcmp(names[1], "mask") == 0);
  MRGI_CHECK_NEAR(back.pixels[0], two.pixels[1], 1e-3 * fabs(two.pixels[1]));
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&two);
}

/* ---- bad input on write -------------------------------------------------- */

static void test_write_rejects_bad_input(void)
{
  char path[1024];
  mrgi_test_tmp_path("exr_bad_write.exr", path, sizeof(path));
  unlink(path);
  mrgi_error err;
  mrgi_image img = make_pattern(4, 4, 2, 1.0f);

  MRGI_CHECK(mrgi_exr_write(NULL, &img, NULL, MRGI_EXR_HALF, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "path is NULL"));
  MRGI_CHECK(mrgi_exr_write(path, NULL, NULL, MRGI_EXR_HALF, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "image pointer is NULL"));
  mrgi_image broken = { 4, 4, 3, NULL };
  MRGI_CHECK(mrgi_exr_write(path, &broken, NULL, MRGI_EXR_HALF, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "no pixel buffer"));
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_HALF, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "no default channel names for a 2-channel image"));
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, (mrgi_exr_pixel_type)7, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "unknown EXR pixel type 7"));
  const char* const twice[2] = { "A", "A" };
  MRGI_CHECK(mrgi_exr_write(path, &img, twice, MRGI_EXR_HALF, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "'A' is used twice"));
  const char* const empty[2] = { "A", "" };
  MRGI_CHECK(mrgi_exr_write(path, &img, empty, MRGI_EXR_HALF, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channel name 1 is NULL or empty"));
  const char* const missing[2] = { NULL, "B" };
  MRGI_CHECK(mrgi_exr_write(path, &img, missing, MRGI_EXR_HALF, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channel name 0 is NULL or empty"));
  const char* const long_name[2] = { "A", "this_channel_name_is_far_too_long_for_us" };
  MRGI_CHECK(mrgi_exr_write(path, &img, long_name, MRGI_EXR_HALF, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "longer than 31 characters"));
  MRGI_CHECK(!mrgi_test_file_exists(path));
  mrgi_image_destroy(&img);
}

static void test_write_to_missing_directory_leaves_nothing(void)
{
  char dir[1024];
  char path[1024];
  mrgi_test_tmp_path("exr_no_such_dir", dir, sizeof(dir));
  mrgi_test_tmp_path("exr_no_such_dir/out.exr", path, sizeof(path));
  rmdir(dir);
  mrgi_image img = make_pattern(4, 4, 3, 1.0f);
  mrgi_error err;
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, MRGI_EXR_HALF, &err) == MRGI_ERR_IO);
  MRGI_CHECK(strstr(err.message, "No such file or directory"));
  MRGI_CHECK(!mrgi_test_file_exists(path));
  MRGI_CHECK(!mrgi_test_file_exists(dir));
  mrgi_image_destroy(&img);

  /* A successful write leaves no temporary beside the output either. */
  char tmpdir[1024];
  char ok_path[1024];
  mrgi_test_tmp_path("", tmpdir, sizeof(tmpdir));
  mrgi_test_tmp_path("exr_clean.exr", ok_path, sizeof(ok_path));
  img = make_pattern(4, 4, 3, 1.0f);
  MRGI_CHECK(mrgi_exr_write(ok_path, &img, NULL, MRGI_EXR_HALF, NULL) == MRGI_OK);
  DIR* d = opendir(tmpdir);
  MRGI_CHECK(d != NULL);
  for (struct dirent* e = readdir(d); e; e = readdir(d))
  {
    MRGI_CHECK(strncmp(e->d_name, "exr_clean.exr.tmp-", 18) != 0);
  }
  closedir(d);
  mrgi_image_destroy(&img);
}

/* ---- bad input on read --------------------------------------------------- */

static void test_read_rejects_missing_and_foreign_files(void)
{
  char path[1024];
  mrgi_test_tmp_path("exr_does_not_exist.exr", path, sizeof(path));
  unlink(path);
  expect_read_fails(path, MRGI_ERR_IO, "No such file or directory");

  mrgi_test_tmp_path("exr_not_exr.exr", path, sizeof(path));
  const char* text = "P3\n1 1\n255\n0 0 0\nthis is not an OpenEXR file";
  mrgi_test_write_file(path, (const uint8_t*)text, strlen(text));
  expect_read_fails(path, MRGI_ERR_FORMAT, "not an OpenEXR file");

  mrgi_test_tmp_path("exr_empty.exr", path, sizeof(path));
  mrgi_test_write_file(path, NULL, 0);
  expect_read_fails(path, MRGI_ERR_FORMAT, "not an OpenEXR file");

  mrgi_test_tmp_path("", path, sizeof(path));
  expect_read_fails(path, MRGI_ERR_IO, "not a regular file");

  mrgi_error err;
  mrgi_image img;
  MRGI_CHECK(mrgi_exr_read(NULL, &img, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "path is NULL"));
  MRGI_CHECK(mrgi_exr_read(path, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output image pointer is NULL"));
  MRGI_CHECK(mrgi_exr_read_channels(path, &img, NULL, 3, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "names is NULL"));
  char names[1][MRGI_EXR_CHANNEL_NAME_SIZE];
  MRGI_CHECK(mrgi_exr_read_channels(path, &img, names, -1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "-1 channel-name slots"));
}

/* Writes a valid file and returns its bytes. */
static uint8_t* make_valid_file(const char* path, size_t* size, mrgi_exr_pixel_type type)
{
  mrgi_image img = make_pattern(21, 40, 3, 0.5f);
  MRGI_CHECK(mrgi_exr_write(path, &img, NULL, type, NULL) == MRGI_OK);
  mrgi_image_destroy(&img);
  return mrgi_test_read_file(path, size);
}

static void test_read_rejects_truncated_files(void)
{
  char source[1024];
  char path[1024];
  mrgi_test_tmp_path("exr_truncate_source.exr", source, sizeof(source));
  mrgi_test_tmp_path("exr_truncated.exr", path, sizeof(path));
  size_t size = 0;
  uint8_t* data = make_valid_file(source, &size, MRGI_EXR_HALF);

  /* Cut in half: the header survives, the pixel data does not. */
  mrgi_test_write_file(path, data, size / 2);
  expect_read_fails(path, MRGI_ERR_FORMAT, path);

  /* Every shorter length must fail cleanly, never crash or succeed. */
  for (size_t length = 0; length < size; ++length)
  {
    mrgi_test_write_file(path, data, length);
    mrgi_error err;
    mrgi_image img;
    const mrgi_status s = mrgi_exr_read(path, &img, &err);
    if (s == MRGI_OK)
    {
      fprintf(stderr, "a file truncated to %zu of %zu bytes was accepted\n", length, size);
    }
    MRGI_CHECK(s == MRGI_ERR_FORMAT);
    MRGI_CHECK(err.message[0] != '\0');
    MRGI_CHECK(img.pixels == NULL);
  }
  free(data);
}

static void test_read_rejects_corrupt_files(void)
{
  char source[1024];
  char path[1024];
  mrgi_test_tmp_path("exr_corrupt_source.exr", source, sizeof(source));
  mrgi_test_tmp_path("exr_corrupt.exr", path, sizeof(path));
  size_t size = 0;
  uint8_t* data = make_valid_file(source, &size, MRGI_EXR_FLOAT);
  uint8_t* copy = (uint8_t*)malloc(size);
  MRGI_CHECK(copy != NULL);

  /* Broken magic number. */
  memcpy(copy, data, size);
  copy[0] ^= 0xff;
  mrgi_test_write_file(path, copy, size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "not an OpenEXR file");

  /* Garbage over the compressed pixel data (the last quarter of the file). */
  memcpy(copy, data, size);
  for (size_t i = size - size / 4; i < size; ++i)
  {
    copy[i] = (uint8_t)(i * 7u + 13u);
  }
  mrgi_test_write_file(path, copy, size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "corrupt");

  /* Flip each byte in turn: the reader may accept harmless damage (e.g. in
   * an attribute value) but must never crash, leak or return a bad image. */
  int rejected = 0;
  for (size_t i = 0; i < size; ++i)
  {
    memcpy(copy, data, size);
    copy[i] ^= 0x5a;
    mrgi_test_write_file(path, copy, size);
    mrgi_error err;
    mrgi_image img;
    const mrgi_status s = mrgi_exr_read(path, &img, &err);
    if (s == MRGI_OK)
    {
      MRGI_CHECK(mrgi_image_validate(&img, NULL) == MRGI_OK);
      mrgi_image_destroy(&img);
    }
    else
    {
      MRGI_CHECK(err.message[0] != '\0');
      MRGI_CHECK(img.pixels == NULL);
      ++rejected;
    }
  }
  MRGI_CHECK(rejected > 0);
  free(copy);
  free(data);
}

static void test_read_rejects_absurd_data_windows(void)
{
  char source[1024];
  char path[1024];
  mrgi_test_tmp_path("exr_window_source.exr", source, sizeof(source));
  mrgi_test_tmp_path("exr_window.exr", path, sizeof(path));
  size_t size = 0;
  uint8_t* data = make_valid_file(source, &size, MRGI_EXR_HALF);
  static const char key[] = "dataWindow\0box2i";
  const long at = find_bytes(data, size, key, sizeof(key)); /* includes the type's NUL */
  MRGI_CHECK(at > 0);
  /* After name and type: int32 attribute size (16), then xmin, ymin, xmax, ymax. */
  uint8_t* box = data + at + (long)sizeof(key) + 4;

  /* Within the per-side limit, but far more chunks than the file can hold. */
  put_le32(box + 8, 999999);
  put_le32(box + 12, 999999);
  mrgi_test_write_file(path, data, size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "data window 1000000x1000000");

  /* Within the per-side limit and few enough chunks, but more pixel data
   * than any codec can decode from a file this small (found by reading the
   * reader: a 597-byte file made it allocate 7 GiB). */
  put_le32(box + 8, (1 << 20) - 1);
  put_le32(box + 12, (int32_t)(size / 16) * 16 - 1);
  mrgi_test_write_file(path, data, size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "more than a file of");

  /* Beyond the per-side limit. */
  put_le32(box + 8, 2000000000);
  put_le32(box + 12, 20);
  mrgi_test_write_file(path, data, size);
  mrgi_error err;
  mrgi_image img;
  const mrgi_status s = mrgi_exr_read(path, &img, &err);
  MRGI_CHECK(s == MRGI_ERR_UNSUPPORTED || s == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "exr_window.exr"));
  MRGI_CHECK(img.pixels == NULL);

  /* Inverted window. */
  put_le32(box + 0, 50);
  put_le32(box + 8, 10);
  mrgi_test_write_file(path, data, size);
  MRGI_CHECK(mrgi_exr_read(path, &img, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "exr_window.exr"));
  MRGI_CHECK(img.pixels == NULL);
  free(data);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_float_round_trip_is_exact),
    MRGI_TEST_CASE(test_real_block_round_trip_is_exact),
    MRGI_TEST_CASE(test_half_round_trip_within_half_precision),
    MRGI_TEST_CASE(test_half_conversion_rounding_and_subnormals),
    MRGI_TEST_CASE(test_nonfinite_and_overflow_are_never_written),
    MRGI_TEST_CASE(test_channel_names_and_order),
    MRGI_TEST_CASE(test_write_rejects_bad_input),
    MRGI_TEST_CASE(test_write_to_missing_directory_leaves_nothing),
    MRGI_TEST_CASE(test_read_rejects_missing_and_foreign_files),
    MRGI_TEST_CASE(test_read_rejects_truncated_files),
    MRGI_TEST_CASE(test_read_rejects_corrupt_files),
    MRGI_TEST_CASE(test_read_rejects_absurd_data_windows),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
