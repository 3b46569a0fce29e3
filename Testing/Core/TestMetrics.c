/* Tests of mrgi_metrics against values computed by hand on small images. */
#include "mrgi_metrics.h"
#include "mrgi_test.h"

#include <float.h>
#include <stdint.h>
#include <string.h>

static mrgi_image make_image(int32_t w, int32_t h, int32_t c, const float* values)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, w, h, c, NULL) == MRGI_OK);
  if (values)
  {
    memcpy(img.pixels, values, mrgi_image_value_count(&img) * sizeof(float));
  }
  return img;
}

static mrgi_image make_constant(int32_t w, int32_t h, int32_t c, float v)
{
  mrgi_image img = make_image(w, h, c, NULL);
  for (size_t i = 0; i < mrgi_image_value_count(&img); ++i)
  {
    img.pixels[i] = v;
  }
  return img;
}

/* A smooth image with structure, values in [0.1, 0.9]. */
static mrgi_image make_gradient(int32_t w, int32_t h, int32_t c)
{
  mrgi_image img = make_image(w, h, c, NULL);
  for (int32_t y = 0; y < h; ++y)
  {
    for (int32_t x = 0; x < w; ++x)
    {
      for (int32_t k = 0; k < c; ++k)
      {
        mrgi_image_at(&img, x, y)[k] =
          0.1f + 0.8f * (float)((x * 3 + y * 5 + k * 7) % 32) / 31.0f;
      }
    }
  }
  return img;
}

/* ref + uniform noise in [-amplitude, amplitude] (deterministic LCG). */
static mrgi_image add_noise(const mrgi_image* ref, float amplitude, uint32_t seed)
{
  mrgi_image out;
  MRGI_CHECK(mrgi_image_copy(&out, ref, NULL) == MRGI_OK);
  uint32_t state = seed;
  for (size_t i = 0; i < mrgi_image_value_count(&out); ++i)
  {
    state = state * 1664525u + 1013904223u;
    const float u = (float)(state >> 8) / 16777216.0f; /* [0,1) */
    out.pixels[i] += amplitude * (2.0f * u - 1.0f);
  }
  return out;
}

static void test_identical_images(void)
{
  mrgi_image ref = make_gradient(20, 13, 3);
  mrgi_image test;
  MRGI_CHECK(mrgi_image_copy(&test, &ref, NULL) == MRGI_OK);
  mrgi_metrics m;
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, NULL, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.rms == 0.0 && m.relative_rms == 0.0 && m.max_abs_error == 0.0);
  MRGI_CHECK(m.psnr_db == MRGI_METRICS_PSNR_MAX_DB);
  MRGI_CHECK_NEAR(m.ssim, 1.0, 1e-12);
  MRGI_CHECK(m.compared_pixels == 20 * 13);
  MRGI_CHECK(m.ssim_windows == (20 - 7) * (13 - 7));
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);
}

static void test_known_values_on_2x2(void)
{
  /* diffs 0,1,2,3: sum sq 14, MSE 3.5, ||ref|| = 2. */
  const float t[4] = { 1.0f, 2.0f, 3.0f, 4.0f };
  const float r[4] = { 1.0f, 1.0f, 1.0f, 1.0f };
  mrgi_image test = make_image(2, 2, 1, t);
  mrgi_image ref = make_image(2, 2, 1, r);
  mrgi_metrics m;
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, NULL, 4.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK_NEAR(m.rms, sqrt(3.5), 1e-12);
  MRGI_CHECK_NEAR(m.relative_rms, sqrt(14.0) / 2.0, 1e-12);
  MRGI_CHECK_NEAR(m.max_abs_error, 3.0, 0.0);
  MRGI_CHECK_NEAR(m.psnr_db, 10.0 * log10(16.0 / 3.5), 1e-12);
  MRGI_CHECK(m.compared_pixels == 4);
  /* 2x2 image: one 2x2 window. Hand SSIM: mx = 2.5, my = 1, vx = 5/3,
   * vy = 0, cov = 0, C1 = 0.0016, C2 = 0.0144. */
  const double c1 = 0.0016, c2 = 0.0144;
  const double expected = (2 * 2.5 * 1.0 + c1) * c2 / ((2.5 * 2.5 + 1.0 + c1) * (5.0 / 3.0 + c2));
  MRGI_CHECK(m.ssim_windows == 1);
  MRGI_CHECK_NEAR(m.ssim, expected, 1e-12);

  /* Ignore the pixel with the largest error. */
  const uint8_t mask[4] = { 0, 0, 0, 1 };
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, mask, 4.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.compared_pixels == 3);
  MRGI_CHECK_NEAR(m.max_abs_error, 2.0, 0.0);
  MRGI_CHECK_NEAR(m.rms, sqrt(5.0 / 3.0), 1e-12);
  MRGI_CHECK_NEAR(m.relative_rms, sqrt(5.0) / sqrt(3.0), 1e-12);
  MRGI_CHECK(m.ssim_windows == 0 && m.ssim == 0.0); /* the only window is masked */
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);
}

static void test_constant_offset(void)
{
  /* test = ref + 0.1 on a constant 0.5 image, peak 1. */
  mrgi_image ref = make_constant(16, 12, 1, 0.5f);
  mrgi_image test = make_constant(16, 12, 1, 0.6f);
  mrgi_metrics m;
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, NULL, 1.0, &m, NULL) == MRGI_OK);
  const double offset = (double)0.6f - (double)0.5f;
  MRGI_CHECK_NEAR(m.rms, offset, 1e-12);
  MRGI_CHECK_NEAR(m.max_abs_error, offset, 1e-12);
  MRGI_CHECK_NEAR(m.psnr_db, 20.0 * log10(1.0 / offset), 1e-9);
  MRGI_CHECK_NEAR(m.psnr_db, 20.0, 1e-5);
  MRGI_CHECK_NEAR(m.relative_rms, offset / 0.5, 1e-12);
  /* Flat windows: SSIM is the luminance term alone. */
  const double mx = (double)0.6f, my = 0.5, c1 = 1e-4;
  MRGI_CHECK_NEAR(m.ssim, (2 * mx * my + c1) / (mx * mx + my * my + c1), 1e-12);
  MRGI_CHECK(m.ssim_windows == 9 * 5);
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);
}

/* Straightforward SSIM of one 8x8 single-channel window, for comparison. */
static double reference_ssim_8x8(const mrgi_image* a, const mrgi_image* b, double peak)
{
  double ma = 0, mb = 0;
  for (int i = 0; i < 64; ++i)
  {
    ma += a->pixels[i];
    mb += b->pixels[i];
  }
  ma /= 64;
  mb /= 64;
  double va = 0, vb = 0, cov = 0;
  for (int i = 0; i < 64; ++i)
  {
    va += (a->pixels[i] - ma) * (a->pixels[i] - ma);
    vb += (b->pixels[i] - mb) * (b->pixels[i] - mb);
    cov += (a->pixels[i] - ma) * (b->pixels[i] - mb);
  }
  va /= 63;
  vb /= 63;
  cov /= 63;
  const double c1 = (0.01 * peak) * (0.01 * peak), c2 = (0.03 * peak) * (0.03 * peak);
  return (2 * ma * mb + c1) * (2 * cov + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
}

static void test_ssim_matches_direct_formula(void)
{
  mrgi_image ref = make_gradient(8, 8, 1);
  mrgi_image test = add_noise(&ref, 0.2f, 7u);
  mrgi_metrics m;
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, NULL, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.ssim_windows == 1);
  MRGI_CHECK_NEAR(m.ssim, reference_ssim_8x8(&test, &ref, 1.0), 1e-12);
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);
}

static void test_ssim_decreases_with_noise(void)
{
  mrgi_image ref = make_gradient(32, 24, 3);
  mrgi_image low = add_noise(&ref, 0.02f, 1u);
  mrgi_image high = add_noise(&ref, 0.2f, 2u);
  mrgi_metrics m_low, m_high;
  MRGI_CHECK(mrgi_metrics_compare(&low, &ref, NULL, 1.0, &m_low, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_metrics_compare(&high, &ref, NULL, 1.0, &m_high, NULL) == MRGI_OK);
  MRGI_CHECK(m_low.ssim < 1.0);
  MRGI_CHECK(m_high.ssim < m_low.ssim - 0.1);
  MRGI_CHECK(m_high.rms > m_low.rms);
  MRGI_CHECK(m_high.psnr_db < m_low.psnr_db);
  /* Uniform noise in [-a, a] has RMS a / sqrt(3). */
  MRGI_CHECK_NEAR(m_high.rms, 0.2 / sqrt(3.0), 0.01);
  mrgi_image_destroy(&low);
  mrgi_image_destroy(&high);
  mrgi_image_destroy(&ref);
}

static void test_masked_ssim_skips_windows(void)
{
  mrgi_image ref = make_gradient(16, 16, 1);
  mrgi_image test = add_noise(&ref, 0.05f, 3u);
  uint8_t mask[16 * 16];
  memset(mask, 0, sizeof(mask));
  mask[0] = 1; /* corner pixel: in exactly one of the 9x9 windows */
  mrgi_metrics m;
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, mask, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.ssim_windows == 80);
  MRGI_CHECK(m.compared_pixels == 255);
  mask[8 * 16 + 8] = 1; /* in the 64 windows starting at x, y = 1..8; none holds the corner too */
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, mask, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.ssim_windows == 81 - 1 - 64);
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);
}

static void test_zero_reference_conventions(void)
{
  mrgi_image zero = make_constant(4, 4, 1, 0.0f);
  mrgi_image zero2 = make_constant(4, 4, 1, 0.0f);
  mrgi_image some = make_constant(4, 4, 1, 0.0f);
  some.pixels[5] = 0.25f;
  mrgi_metrics m;
  MRGI_CHECK(mrgi_metrics_compare(&zero2, &zero, NULL, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.relative_rms == 0.0 && m.psnr_db == MRGI_METRICS_PSNR_MAX_DB);
  MRGI_CHECK_NEAR(m.ssim, 1.0, 1e-12);
  MRGI_CHECK(mrgi_metrics_compare(&some, &zero, NULL, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.relative_rms == DBL_MAX);
  MRGI_CHECK(isfinite(m.psnr_db) && isfinite(m.ssim) && isfinite(m.rms));
  MRGI_CHECK_NEAR(m.max_abs_error, 0.25, 0.0);
  mrgi_image_destroy(&zero);
  mrgi_image_destroy(&zero2);
  mrgi_image_destroy(&some);
}

static void test_compare_rejects_bad_input(void)
{
  mrgi_image a = make_constant(4, 4, 1, 0.5f);
  mrgi_image b = make_constant(4, 4, 1, 0.5f);
  mrgi_image tall = make_constant(4, 3, 1, 0.5f);
  mrgi_image rgb = make_constant(4, 4, 3, 0.5f);
  mrgi_metrics m;
  memset(&m, 0x7f, sizeof(m));
  const mrgi_metrics before = m;
  mrgi_error err;

  MRGI_CHECK(mrgi_metrics_compare(NULL, &b, NULL, 1.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "test image: image pointer is NULL"));
  MRGI_CHECK(mrgi_metrics_compare(&a, NULL, NULL, 1.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "reference image: image pointer is NULL"));
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, NULL, 1.0, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output pointer is NULL"));
  MRGI_CHECK(mrgi_metrics_compare(&a, &tall, NULL, 1.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "test image is 4x4 with 1 channels but the reference is 4x3"));
  MRGI_CHECK(mrgi_metrics_compare(&a, &rgb, NULL, 1.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "reference is 4x4 with 3 channels"));
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, NULL, 0.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "peak value 0"));
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, NULL, NAN, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "peak value"));
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, NULL, INFINITY, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "peak value"));
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, NULL, -1.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "peak value -1"));

  uint8_t all[16];
  memset(all, 1, sizeof(all));
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, all, 1.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mask ignores all 16 pixels"));

  a.pixels[3] = NAN;
  a.pixels[7] = NAN;
  b.pixels[9] = -INFINITY;
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, NULL, 1.0, &m, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "NaN or infinite values: 2 in the test image, 1 in the reference"));
  MRGI_CHECK(memcmp(&m, &before, sizeof(m)) == 0); /* untouched on failure */

  /* NaN in ignored pixels does not matter. */
  uint8_t mask[16];
  memset(mask, 0, sizeof(mask));
  mask[3] = mask[7] = mask[9] = 1;
  MRGI_CHECK(mrgi_metrics_compare(&a, &b, mask, 1.0, &m, &err) == MRGI_OK);
  MRGI_CHECK(m.compared_pixels == 13 && m.rms == 0.0);

  mrgi_image_destroy(&a);
  mrgi_image_destroy(&b);
  mrgi_image_destroy(&tall);
  mrgi_image_destroy(&rgb);
}

static void test_difference_image(void)
{
  const float t[6] = { 1.0f, -2.0f, 0.5f, 4.0f, 0.0f, 9.0f };
  const float r[6] = { 0.5f, 1.0f, 0.5f, 1.0f, 2.0f, -9.0f };
  mrgi_image test = make_image(3, 1, 2, t);
  mrgi_image ref = make_image(3, 1, 2, r);
  const uint8_t mask[3] = { 0, 0, 1 };
  mrgi_image diff;
  MRGI_CHECK(mrgi_metrics_difference_image(&test, &ref, mask, &diff, NULL) == MRGI_OK);
  MRGI_CHECK(diff.width == 3 && diff.height == 1 && diff.channels == 2);
  const float expected[6] = { 0.5f, 3.0f, 0.0f, 3.0f, 0.0f, 0.0f };
  MRGI_CHECK(memcmp(diff.pixels, expected, sizeof(expected)) == 0);
  mrgi_image_destroy(&diff);

  mrgi_error err;
  MRGI_CHECK(mrgi_metrics_difference_image(&test, &ref, NULL, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output pointer is NULL"));
  mrgi_image other = make_constant(3, 2, 2, 0.0f);
  MRGI_CHECK(mrgi_metrics_difference_image(&test, &other, NULL, &diff, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "but the reference is 3x2"));
  MRGI_CHECK(diff.pixels == NULL);
  test.pixels[0] = NAN;
  MRGI_CHECK(mrgi_metrics_difference_image(&test, &ref, NULL, &diff, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "1 in the test image"));
  mrgi_image_destroy(&other);
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);
}

static void test_small_images_use_smaller_windows(void)
{
  mrgi_image ref = make_gradient(3, 2, 1);
  mrgi_image test = add_noise(&ref, 0.1f, 5u);
  mrgi_metrics m;
  MRGI_CHECK(mrgi_metrics_compare(&test, &ref, NULL, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.ssim_windows == 2); /* 2x2 windows at x = 0 and 1 */
  MRGI_CHECK(m.ssim < 1.0 && m.ssim > -1.0);
  mrgi_image_destroy(&test);
  mrgi_image_destroy(&ref);

  mrgi_image one_a = make_constant(1, 1, 4, 0.25f);
  mrgi_image one_b = make_constant(1, 1, 4, 0.25f);
  MRGI_CHECK(mrgi_metrics_compare(&one_a, &one_b, NULL, 1.0, &m, NULL) == MRGI_OK);
  MRGI_CHECK(m.ssim_windows == 1 && m.ssim == 1.0);
  mrgi_image_destroy(&one_a);
  mrgi_image_destroy(&one_b);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_identical_images),
    MRGI_TEST_CASE(test_known_values_on_2x2),
    MRGI_TEST_CASE(test_constant_offset),
    MRGI_TEST_CASE(test_ssim_matches_direct_formula),
    MRGI_TEST_CASE(test_ssim_decreases_with_noise),
    MRGI_TEST_CASE(test_masked_ssim_skips_windows),
    MRGI_TEST_CASE(test_zero_reference_conventions),
    MRGI_TEST_CASE(test_compare_rejects_bad_input),
    MRGI_TEST_CASE(test_difference_image),
    MRGI_TEST_CASE(test_small_images_use_smaller_windows),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
