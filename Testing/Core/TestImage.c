/* Tests of mrgi_image: creation limits, copies, validation, flips, 8-bit conversion. */
#include "mrgi_image.h"
#include "mrgi_test.h"

#include <float.h>
#include <stdint.h>
#include <string.h>

#if defined(__SANITIZE_ADDRESS__)
#define MRGI_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MRGI_TEST_UNDER_ASAN 1
#endif
#endif
#ifndef MRGI_TEST_UNDER_ASAN
#define MRGI_TEST_UNDER_ASAN 0
#endif

static void test_create_zero_filled(void)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 5, 3, 2, NULL) == MRGI_OK);
  MRGI_CHECK(img.width == 5 && img.height == 3 && img.channels == 2);
  MRGI_CHECK(mrgi_image_pixel_count(&img) == 15);
  MRGI_CHECK(mrgi_image_value_count(&img) == 30);
  for (size_t i = 0; i < 30; ++i)
  {
    MRGI_CHECK(img.pixels[i] == 0.0f);
  }
  /* at(): interleaved, row 0 first. */
  MRGI_CHECK(mrgi_image_at(&img, 0, 0) == img.pixels);
  MRGI_CHECK(mrgi_image_at(&img, 4, 2) == img.pixels + (2 * 5 + 4) * 2);
  mrgi_image_destroy(&img);
  MRGI_CHECK(img.pixels == NULL && img.width == 0);
  mrgi_image_destroy(&img); /* idempotent */
  mrgi_image_destroy(NULL); /* NULL-safe */
}

static void test_create_rejects_bad_sizes(void)
{
  mrgi_error err;
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 0, 4, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "width 0"));
  MRGI_CHECK(img.pixels == NULL && img.width == 0);
  MRGI_CHECK(mrgi_image_create(&img, 4, -2, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "height -2"));
  MRGI_CHECK(mrgi_image_create(&img, 4, 4, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channel count 0"));
  MRGI_CHECK(mrgi_image_create(&img, 4, 4, 65, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channel count 65"));
  MRGI_CHECK(mrgi_image_create(&img, (int64_t)MRGI_IMAGE_MAX_DIMENSION + 1, 1, 1, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "width"));
  MRGI_CHECK(mrgi_image_create(&img, INT64_MAX, INT64_MAX, 64, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_image_create(NULL, 1, 1, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL"));
#if !MRGI_TEST_UNDER_ASAN
  /* Within limits but far beyond memory (256 TiB): a clean out-of-memory,
   * never a crash. AddressSanitizer aborts on such requests by default. */
  mrgi_status s = mrgi_image_create(&img, MRGI_IMAGE_MAX_DIMENSION, MRGI_IMAGE_MAX_DIMENSION, 64,
                                    &err);
  MRGI_CHECK(s == MRGI_ERR_OUT_OF_MEMORY);
  MRGI_CHECK(strstr(err.message, "cannot allocate"));
  MRGI_CHECK(img.pixels == NULL);
#endif
}

static void test_validate(void)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_image_validate(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL"));
  mrgi_image bad = { 4, 4, 3, NULL };
  MRGI_CHECK(mrgi_image_validate(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "no pixel buffer"));
  float storage[12];
  mrgi_image neg = { -1, 4, 3, storage };
  MRGI_CHECK(mrgi_image_validate(&neg, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "width -1"));
  mrgi_image good = { 2, 2, 3, storage };
  MRGI_CHECK(mrgi_image_validate(&good, &err) == MRGI_OK);
}

static void test_copy(void)
{
  mrgi_image src;
  MRGI_CHECK(mrgi_image_create(&src, 3, 2, 1, NULL) == MRGI_OK);
  for (int i = 0; i < 6; ++i)
  {
    src.pixels[i] = (float)i + 0.5f;
  }
  mrgi_image dst;
  MRGI_CHECK(mrgi_image_copy(&dst, &src, NULL) == MRGI_OK);
  MRGI_CHECK(dst.pixels != src.pixels);
  MRGI_CHECK(dst.width == 3 && dst.height == 2 && dst.channels == 1);
  MRGI_CHECK(memcmp(dst.pixels, src.pixels, 6 * sizeof(float)) == 0);

  mrgi_error err;
  MRGI_CHECK(mrgi_image_copy(&src, &src, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "same image"));
  mrgi_image empty = { 0, 0, 0, NULL };
  mrgi_image out;
  MRGI_CHECK(mrgi_image_copy(&out, &empty, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "copy source"));
  MRGI_CHECK(out.pixels == NULL);
  MRGI_CHECK(mrgi_image_copy(NULL, &src, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "destination"));
  mrgi_image_destroy(&src);
  mrgi_image_destroy(&dst);
}

static void test_count_nonfinite(void)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 2, 2, 2, NULL) == MRGI_OK);
  img.pixels[1] = NAN;
  img.pixels[4] = INFINITY;
  img.pixels[7] = -INFINITY;
  img.pixels[3] = FLT_MAX;
  int64_t count = -1;
  MRGI_CHECK(mrgi_image_count_nonfinite(&img, &count, NULL) == MRGI_OK);
  MRGI_CHECK(count == 3);
  mrgi_error err;
  MRGI_CHECK(mrgi_image_count_nonfinite(&img, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "count pointer is NULL"));
  MRGI_CHECK(mrgi_image_count_nonfinite(NULL, &count, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "image pointer is NULL"));
  mrgi_image_destroy(&img);
}

static void test_flip_rows(void)
{
  /* Odd height: the middle row stays; 2 channels so values within a pixel keep order. */
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 2, 3, 2, NULL) == MRGI_OK);
  for (int32_t y = 0; y < 3; ++y)
  {
    for (int32_t x = 0; x < 2; ++x)
    {
      mrgi_image_at(&img, x, y)[0] = (float)(10 * y + x);
      mrgi_image_at(&img, x, y)[1] = -(float)(10 * y + x);
    }
  }
  MRGI_CHECK(mrgi_image_flip_rows(&img, NULL) == MRGI_OK);
  for (int32_t y = 0; y < 3; ++y)
  {
    for (int32_t x = 0; x < 2; ++x)
    {
      MRGI_CHECK(mrgi_image_at(&img, x, y)[0] == (float)(10 * (2 - y) + x));
      MRGI_CHECK(mrgi_image_at(&img, x, y)[1] == -(float)(10 * (2 - y) + x));
    }
  }
  mrgi_image_destroy(&img);
  mrgi_error err;
  MRGI_CHECK(mrgi_image_flip_rows(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL"));
}

static void test_srgb_curve(void)
{
  MRGI_CHECK_NEAR(mrgi_srgb_encode(0.0f), 0.0, 0.0);
  MRGI_CHECK_NEAR(mrgi_srgb_encode(1.0f), 1.0, 1e-6);
  MRGI_CHECK_NEAR(mrgi_srgb_encode(0.18f), 0.46135, 1e-4); /* mid grey */
  MRGI_CHECK_NEAR(mrgi_srgb_decode(mrgi_srgb_encode(0.3f)), 0.3, 1e-6);
  MRGI_CHECK(mrgi_srgb_encode(NAN) == 0.0f);
  MRGI_CHECK(mrgi_srgb_encode(5.0f) == mrgi_srgb_encode(1.0f));
}

static void test_to_rgba8(void)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 3, 1, 4, NULL) == MRGI_OK);
  const float values[12] = { 0.0f, 0.5f, 1.0f, 0.5f,      /* ordinary */
                             NAN, -1.0f, 7.0f, NAN,       /* NaN -> 0, clamping */
                             0.25f, INFINITY, -INFINITY, 2.0f };
  memcpy(img.pixels, values, sizeof(values));
  uint8_t out[12];
  MRGI_CHECK(mrgi_image_to_rgba8(&img, out, sizeof(out), 0, 1.0f, NULL) == MRGI_OK);
  const uint8_t expected_linear[12] = { 0, 128, 255, 128, 0, 0, 255, 0, 64, 255, 0, 255 };
  MRGI_CHECK(memcmp(out, expected_linear, sizeof(out)) == 0);

  /* Exposure scales colour, not alpha. */
  MRGI_CHECK(mrgi_image_to_rgba8(&img, out, sizeof(out), 0, 2.0f, NULL) == MRGI_OK);
  MRGI_CHECK(out[1] == 255 && out[3] == 128 && out[8] == 128);

  /* sRGB encodes colour (0.5 -> 188), not alpha. */
  MRGI_CHECK(mrgi_image_to_rgba8(&img, out, sizeof(out), 1, 1.0f, NULL) == MRGI_OK);
  MRGI_CHECK(out[1] == 188 && out[3] == 128);

  mrgi_error err;
  MRGI_CHECK(mrgi_image_to_rgba8(&img, out, 11, 0, 1.0f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "needs 12"));
  MRGI_CHECK(mrgi_image_to_rgba8(&img, NULL, 12, 0, 1.0f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL"));
  MRGI_CHECK(mrgi_image_to_rgba8(&img, out, 12, 0, NAN, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "exposure"));
  MRGI_CHECK(mrgi_image_to_rgba8(&img, out, 12, 0, 0.0f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "exposure"));
  mrgi_image_destroy(&img);

  mrgi_image wide;
  MRGI_CHECK(mrgi_image_create(&wide, 1, 1, 5, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_image_to_rgba8(&wide, out, 12, 0, 1.0f, &err) == MRGI_ERR_UNSUPPORTED);
  MRGI_CHECK(strstr(err.message, "has 5"));
  mrgi_image_destroy(&wide);
}

static void test_from_rgba8(void)
{
  const uint8_t bytes[8] = { 0, 255, 51, 128, 255, 0, 188, 64 };
  mrgi_image img;
  MRGI_CHECK(mrgi_image_from_rgba8(&img, bytes, sizeof(bytes), 2, 2, 2, 0, NULL) == MRGI_OK);
  MRGI_CHECK(img.width == 2 && img.height == 2 && img.channels == 2);
  MRGI_CHECK_NEAR(img.pixels[0], 0.0, 0.0);
  MRGI_CHECK_NEAR(img.pixels[1], 1.0, 0.0);
  MRGI_CHECK_NEAR(img.pixels[2], 0.2, 1e-7);
  mrgi_image_destroy(&img);

  /* sRGB decode affects gray (channel 0), not alpha (channel 1). */
  MRGI_CHECK(mrgi_image_from_rgba8(&img, bytes, sizeof(bytes), 2, 2, 2, 1, NULL) == MRGI_OK);
  MRGI_CHECK_NEAR(img.pixels[6], 0.5029, 1e-3); /* 188 -> ~0.503 linear */
  MRGI_CHECK_NEAR(img.pixels[7], 64.0 / 255.0, 1e-7);
  mrgi_image_destroy(&img);

  mrgi_error err;
  MRGI_CHECK(mrgi_image_from_rgba8(&img, bytes, 7, 2, 2, 2, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "holds 7 bytes"));
  MRGI_CHECK(img.pixels == NULL);
  MRGI_CHECK(mrgi_image_from_rgba8(&img, NULL, 8, 2, 2, 2, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NULL"));
  MRGI_CHECK(mrgi_image_from_rgba8(&img, bytes, 8, 2, 2, 5, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channel count 5"));
  MRGI_CHECK(mrgi_image_from_rgba8(&img, bytes, 8, 0, 2, 2, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "width 0"));
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_create_zero_filled),
    MRGI_TEST_CASE(test_create_rejects_bad_sizes),
    MRGI_TEST_CASE(test_validate),
    MRGI_TEST_CASE(test_copy),
    MRGI_TEST_CASE(test_count_nonfinite),
    MRGI_TEST_CASE(test_flip_rows),
    MRGI_TEST_CASE(test_srgb_curve),
    MRGI_TEST_CASE(test_to_rgba8),
    MRGI_TEST_CASE(test_from_rgba8),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
