/* Tests of mrgi_exposure (output transform: exposure, tone curve, automatic
 * exposure after Reinhard 2002) and mrgi_box_filter (the SSAA resolve). */
#include "mrgi_box_filter.h"
#include "mrgi_exposure.h"
#include "mrgi_vpl.h"

#include "mrgi_test.h"

#include <math.h>
#include <string.h>

/* T keeps mid-grey and everything below the shoulder, is continuous with a
 * continuous slope at the shoulder, increases, and stays below 1. */
static void test_tone_curve_shape(void)
{
  MRGI_CHECK(mrgi_tone_curve(0.18f) == 0.18f);
  MRGI_CHECK(mrgi_tone_curve((float)MRGI_TONE_SHOULDER) == (float)MRGI_TONE_SHOULDER);
  MRGI_CHECK(mrgi_tone_curve(0.0f) == 0.0f);
  MRGI_CHECK(mrgi_tone_curve(-3.0f) == 0.0f);
  MRGI_CHECK(mrgi_tone_curve(NAN) == 0.0f);
  MRGI_CHECK(mrgi_tone_curve(INFINITY) == 1.0f);
  const float k = (float)MRGI_TONE_SHOULDER, h = 1e-3f;
  /* slope 1 on both sides of the shoulder */
  MRGI_CHECK_NEAR((mrgi_tone_curve(k + h) - mrgi_tone_curve(k)) / h, 1.0, 2e-3);
  MRGI_CHECK_NEAR((mrgi_tone_curve(k) - mrgi_tone_curve(k - h)) / h, 1.0, 2e-3);
  float last = 0.0f;
  for (int i = 1; i <= 4000; ++i)
  {
    const float x = (float)i * 0.005f;
    const float y = mrgi_tone_curve(x);
    MRGI_CHECK(y >= last);
    MRGI_CHECK(y < 1.0f || x > 8.0f); /* float rounding reaches 1 only beyond 16 x the shoulder */
    MRGI_CHECK(y <= x);
    last = y;
  }
  /* highlights are compressed, not clipped: 1 and 2 stay distinguishable */
  MRGI_CHECK(mrgi_tone_curve(2.0f) - mrgi_tone_curve(1.0f) > 0.1f);
}

static void test_scale_and_apply(void)
{
  MRGI_CHECK(mrgi_exposure_scale(0.0) == 1.0f);
  MRGI_CHECK(mrgi_exposure_scale(1.0) == 2.0f);
  MRGI_CHECK(mrgi_exposure_scale(-2.0) == 0.25f);
  MRGI_CHECK(mrgi_exposure_scale(NAN) == 1.0f);
  MRGI_CHECK(mrgi_exposure_scale(1000.0) == (float)exp2(MRGI_EXPOSURE_MAX_EV));
  const float in[3] = { 0.09f, 0.5f, 4.0f };
  float out[3];
  mrgi_exposure_apply(in, 2.0f, 0, out);
  MRGI_CHECK(out[0] == 0.18f && out[1] == 1.0f && out[2] == 8.0f);
  mrgi_exposure_apply(in, 2.0f, 1, out);
  MRGI_CHECK(out[0] == 0.18f);
  MRGI_CHECK(out[1] == mrgi_tone_curve(1.0f) && out[2] == mrgi_tone_curve(8.0f));
  /* in place */
  float io[3] = { 0.25f, 0.25f, 0.25f };
  mrgi_exposure_apply(io, 0.5f, 1, io);
  MRGI_CHECK(io[0] == 0.125f && io[2] == 0.125f);
}

/* The log-average of a constant image is that luminance (up to delta); the
 * background (depth 1) does not count; NaN/inf/negative pixels do not count. */
static void test_log_average(void)
{
  enum
  {
    N = 64
  };
  float rgba[N * 4];
  float depth[N];
  for (int i = 0; i < N; ++i)
  {
    rgba[4 * i + 0] = rgba[4 * i + 1] = rgba[4 * i + 2] = 0.045f;
    rgba[4 * i + 3] = 1.0f;
    depth[i] = 0.5f;
  }
  /* a quarter of the pixels are a bright background */
  for (int i = 0; i < N / 4; ++i)
  {
    rgba[4 * i + 0] = rgba[4 * i + 1] = rgba[4 * i + 2] = 100.0f;
    depth[i] = 1.0f;
  }
  rgba[4 * 20 + 1] = NAN;
  rgba[4 * 21 + 0] = INFINITY;
  double lw = 0.0;
  int64_t used = 0;
  MRGI_CHECK(mrgi_exposure_log_average(rgba, 4, depth, N, &lw, &used, NULL) == MRGI_OK);
  MRGI_CHECK(used == N - N / 4 - 2);
  MRGI_CHECK_NEAR(lw, 0.045 + MRGI_EXPOSURE_DELTA, 1e-6);
  /* two stops below the key */
  MRGI_CHECK_NEAR(mrgi_exposure_auto_ev(lw, 0.0, MRGI_EXPOSURE_KEY), 2.0, 0.01);
  /* without depth every finite pixel counts: the background dominates */
  MRGI_CHECK(mrgi_exposure_log_average(rgba, 4, NULL, N, &lw, &used, NULL) == MRGI_OK);
  MRGI_CHECK(used == N - 2);
  MRGI_CHECK(lw > 0.1);
  /* geometric, not arithmetic, mean: 0.01 and 1 average to 0.1 */
  const float two[6] = { 0.01f, 0.01f, 0.01f, 1.0f, 1.0f, 1.0f };
  MRGI_CHECK(mrgi_exposure_log_average(two, 3, NULL, 2, &lw, NULL, NULL) == MRGI_OK);
  MRGI_CHECK_NEAR(lw, 0.1, 1e-3);
}

static void test_auto_ev_edges(void)
{
  double lw = -1.0;
  int64_t used = -1;
  const float depth[2] = { 1.0f, NAN };
  const float rgb[6] = { 1, 1, 1, 1, 1, 1 };
  MRGI_CHECK(mrgi_exposure_log_average(rgb, 3, depth, 2, &lw, &used, NULL) == MRGI_OK);
  MRGI_CHECK(lw == 0.0 && used == 0);
  MRGI_CHECK(mrgi_exposure_auto_ev(0.0, 0.0, MRGI_EXPOSURE_KEY) == 0.0);
  MRGI_CHECK(mrgi_exposure_auto_ev(NAN, NAN, MRGI_EXPOSURE_KEY) == 0.0);
  MRGI_CHECK(mrgi_exposure_auto_ev(INFINITY, 0.0, MRGI_EXPOSURE_KEY) == 0.0);
  MRGI_CHECK(mrgi_exposure_auto_ev(1e-30, 0.0, MRGI_EXPOSURE_KEY) == MRGI_EXPOSURE_MAX_EV);
  MRGI_CHECK(mrgi_exposure_auto_ev(1e30, 0.0, MRGI_EXPOSURE_KEY) == MRGI_EXPOSURE_MIN_EV);
  MRGI_CHECK(mrgi_exposure_auto_ev(0.18, 0.0, 0.18) == 0.0);
  /* the highlight cap wins when it is lower; alone it still decides */
  MRGI_CHECK_NEAR(mrgi_exposure_auto_ev(0.01, 0.25, 0.18), 2.0, 1e-12);
  MRGI_CHECK_NEAR(mrgi_exposure_auto_ev(0.09, 0.25, 0.18), 1.0, 1e-12);
  MRGI_CHECK_NEAR(mrgi_exposure_auto_ev(0.0, 4.0, 0.18), -2.0, 1e-12);
  MRGI_CHECK(mrgi_exposure_auto_ev(0.09, 0.25, 0.0) == 0.0);
  mrgi_error err;
  MRGI_CHECK(
    mrgi_exposure_log_average(NULL, 3, NULL, 4, &lw, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_exposure_log_average(rgb, 2, NULL, 2, &lw, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_exposure_log_average(rgb, 3, NULL, -1, &lw, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_exposure_log_average(rgb, 3, NULL, 2, NULL, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mrgi_exposure_log_average") != NULL);
}

/* The histogram quantile is never below the true quantile and within one
 * bin (1/MRGI_EXPOSURE_HISTOGRAM_BINS stop) above it; background ignored. */
static void test_quantile(void)
{
  enum
  {
    N = 1000
  };
  static float rgb[N * 3];
  static float depth[N];
  for (int i = 0; i < N; ++i)
  {
    /* luminances 0.001 .. 1.0, grey so L = the value */
    rgb[3 * i + 0] = rgb[3 * i + 1] = rgb[3 * i + 2] = (float)(i + 1) * 0.001f;
    depth[i] = i >= 900 ? 1.0f : 0.3f; /* the brightest 100 are background */
  }
  double q = 0.0;
  MRGI_CHECK(mrgi_exposure_quantile(rgb, 3, depth, N, 0.5, &q, NULL) == MRGI_OK);
  MRGI_CHECK(q >= 0.45 && q <= 0.45 * exp2(1.0 / MRGI_EXPOSURE_HISTOGRAM_BINS) * 1.0001);
  MRGI_CHECK(mrgi_exposure_quantile(rgb, 3, NULL, N, 0.97, &q, NULL) == MRGI_OK);
  MRGI_CHECK(q >= 0.97 && q <= 0.97 * exp2(1.0 / MRGI_EXPOSURE_HISTOGRAM_BINS) * 1.0001);
  MRGI_CHECK(mrgi_exposure_quantile(rgb, 3, NULL, N, 1.0, &q, NULL) == MRGI_OK);
  MRGI_CHECK(q >= 1.0 && q <= exp2(1.0 / MRGI_EXPOSURE_HISTOGRAM_BINS) * 1.0001);
  /* black pixels land in the first bin; no foreground gives 0 */
  const float black[3] = { 0, 0, 0 };
  MRGI_CHECK(mrgi_exposure_quantile(black, 3, NULL, 1, 1.0, &q, NULL) == MRGI_OK);
  MRGI_CHECK(q > 0.0 && q < 1e-6);
  const float far[1] = { 1.0f };
  MRGI_CHECK(mrgi_exposure_quantile(black, 3, far, 1, 1.0, &q, NULL) == MRGI_OK && q == 0.0);
  mrgi_error err;
  MRGI_CHECK(mrgi_exposure_quantile(rgb, 3, NULL, N, 0.0, &q, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_exposure_quantile(rgb, 3, NULL, N, 1.5, &q, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_exposure_quantile(rgb, 3, NULL, N, 0.5, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

/* Box filter: exact block means, flat regions stay flat, bad input refused. */
static void test_box_downsample(void)
{
  mrgi_image src, dst;
  MRGI_CHECK(mrgi_image_create(&src, 8, 4, 2, NULL) == MRGI_OK);
  for (int32_t y = 0; y < 4; ++y)
  {
    for (int32_t x = 0; x < 8; ++x)
    {
      float* p = mrgi_image_at(&src, x, y);
      p[0] = x < 5 ? 0.3f : 0.9f; /* an edge inside the second block column */
      p[1] = (float)(y * 8 + x);
    }
  }
  MRGI_CHECK(mrgi_box_downsample(&src, 4, &dst, NULL) == MRGI_OK);
  MRGI_CHECK(dst.width == 2 && dst.height == 1 && dst.channels == 2);
  MRGI_CHECK(mrgi_image_at(&dst, 0, 0)[0] == 0.3f); /* flat block: exactly kept */
  MRGI_CHECK_NEAR(mrgi_image_at(&dst, 1, 0)[0], 0.3 * 0.25 + 0.9 * 0.75, 1e-6);
  MRGI_CHECK_NEAR(mrgi_image_at(&dst, 0, 0)[1], 13.5, 1e-6); /* mean of x 0..3, y 0..3 */
  mrgi_image_destroy(&dst);
  MRGI_CHECK(mrgi_box_downsample(&src, 1, &dst, NULL) == MRGI_OK);
  MRGI_CHECK(dst.width == 8 && memcmp(dst.pixels, src.pixels, 8 * 4 * 2 * sizeof(float)) == 0);
  mrgi_image_destroy(&dst);
  mrgi_error err;
  MRGI_CHECK(mrgi_box_downsample(&src, 3, &dst, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "multiple") != NULL && dst.pixels == NULL);
  MRGI_CHECK(mrgi_box_downsample(&src, 0, &dst, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_box_downsample(&src, MRGI_BOX_FILTER_MAX_FACTOR + 1, &dst, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_box_downsample(NULL, 2, &dst, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_box_downsample(&src, 2, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_image_destroy(&src);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_tone_curve_shape),
    MRGI_TEST_CASE(test_scale_and_apply), MRGI_TEST_CASE(test_log_average),
    MRGI_TEST_CASE(test_auto_ev_edges), MRGI_TEST_CASE(test_quantile),
    MRGI_TEST_CASE(test_box_downsample) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
