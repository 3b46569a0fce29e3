#include "mrgi_metrics.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Checks shared by compare and difference: both images valid and alike,
 * some pixel compared, no NaN/inf among compared values. */
static mrgi_status mrgi_metrics_check_inputs(const mrgi_image* test, const mrgi_image* reference,
                                             const uint8_t* mask, int64_t* out_compared,
                                             mrgi_error* err)
{
  mrgi_status status = mrgi_image_validate(test, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "test image: ");
    return status;
  }
  status = mrgi_image_validate(reference, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "reference image: ");
    return status;
  }
  if (test->width != reference->width || test->height != reference->height ||
      test->channels != reference->channels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "test image is %dx%d with %d channels but the reference is %dx%d with "
                          "%d channels",
                          test->width, test->height, test->channels, reference->width,
                          reference->height, reference->channels);
  }
  const int64_t pixels = mrgi_image_pixel_count(test);
  const size_t channels = (size_t)test->channels;
  int64_t compared = 0;
  int64_t test_nonfinite = 0;
  int64_t reference_nonfinite = 0;
  for (int64_t p = 0; p < pixels; ++p)
  {
    if (mask && mask[p])
    {
      continue;
    }
    ++compared;
    const float* t = test->pixels + (size_t)p * channels;
    const float* r = reference->pixels + (size_t)p * channels;
    for (size_t c = 0; c < channels; ++c)
    {
      test_nonfinite += !isfinite(t[c]);
      reference_nonfinite += !isfinite(r[c]);
    }
  }
  if (compared == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mask ignores all %lld pixels; nothing is left to compare",
                          (long long)pixels);
  }
  if (test_nonfinite > 0 || reference_nonfinite > 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "compared pixels hold NaN or infinite values: %lld in the test image, "
                          "%lld in the reference",
                          (long long)test_nonfinite, (long long)reference_nonfinite);
  }
  *out_compared = compared;
  return MRGI_OK;
}

/* The single plane SSIM looks at (see the header for the choice). */
static double mrgi_metrics_plane_value(const float* pixel, int32_t channels)
{
  if (channels == 1)
  {
    return pixel[0];
  }
  if (channels == 3 || channels == 4)
  {
    return 0.2126 * pixel[0] + 0.7152 * pixel[1] + 0.0722 * pixel[2];
  }
  double sum = 0.0;
  for (int32_t c = 0; c < channels; ++c)
  {
    sum += pixel[c];
  }
  return sum / channels;
}

/* Window sums kept per window column: x, y, x^2, y^2, xy, ignored pixels. */
enum
{
  MRGI_SSIM_SX,
  MRGI_SSIM_SY,
  MRGI_SSIM_SXX,
  MRGI_SSIM_SYY,
  MRGI_SSIM_SXY,
  MRGI_SSIM_MASKED,
  MRGI_SSIM_SUM_COUNT
};

/* Mean SSIM over unmasked windows. Works row by row: each row's horizontal
 * window sums go into a ring of `window` rows, and the vertical sum over the
 * ring gives each window's statistics. Memory is O(window * width), and
 * nothing is allocated inside the loops. */
static mrgi_status mrgi_metrics_ssim(const mrgi_image* test, const mrgi_image* reference,
                                     const uint8_t* mask, double peak, double* out_ssim,
                                     int64_t* out_windows, mrgi_error* err)
{
  const int32_t width = test->width;
  const int32_t height = test->height;
  int32_t window = MRGI_METRICS_SSIM_WINDOW;
  window = window < width ? window : width;
  window = window < height ? window : height;
  const size_t columns = (size_t)(width - window + 1);
  const size_t ring_size = (size_t)window * MRGI_SSIM_SUM_COUNT * columns;

  double* ring = (double*)malloc(sizeof(double) * ring_size);
  double* row_test = (double*)malloc(sizeof(double) * (size_t)width);
  double* row_reference = (double*)malloc(sizeof(double) * (size_t)width);
  double* row_masked = (double*)malloc(sizeof(double) * (size_t)width);
  if (!ring || !row_test || !row_reference || !row_masked)
  {
    free(ring);
    free(row_test);
    free(row_reference);
    free(row_masked);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "cannot allocate SSIM buffers for a %d-pixel-wide image", width);
  }
  const double n = (double)window * (double)window;
  /* Sample (co)variance divides by N-1 (Wang et al. 2004); a 1-pixel window
   * has no spread, so its denominator only needs to be non-zero. */
  const double dof = n > 1.0 ? n - 1.0 : 1.0;
  const double c1 = (0.01 * peak) * (0.01 * peak);
  const double c2 = (0.03 * peak) * (0.03 * peak);
  double ssim_sum = 0.0;
  int64_t windows = 0;

  for (int32_t y = 0; y < height; ++y)
  {
    for (int32_t x = 0; x < width; ++x)
    {
      row_test[x] = mrgi_metrics_plane_value(mrgi_image_at(test, x, y), test->channels);
      row_reference[x] =
        mrgi_metrics_plane_value(mrgi_image_at(reference, x, y), reference->channels);
      row_masked[x] = (mask && mask[(size_t)y * (size_t)width + (size_t)x]) ? 1.0 : 0.0;
    }
    double* sums = ring + (size_t)(y % window) * MRGI_SSIM_SUM_COUNT * columns;
    for (size_t x0 = 0; x0 < columns; ++x0)
    {
      double s[MRGI_SSIM_SUM_COUNT] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
      for (size_t k = x0; k < x0 + (size_t)window; ++k)
      {
        const double a = row_test[k];
        const double b = row_reference[k];
        s[MRGI_SSIM_SX] += a;
        s[MRGI_SSIM_SY] += b;
        s[MRGI_SSIM_SXX] += a * a;
        s[MRGI_SSIM_SYY] += b * b;
        s[MRGI_SSIM_SXY] += a * b;
        s[MRGI_SSIM_MASKED] += row_masked[k];
      }
      for (int q = 0; q < MRGI_SSIM_SUM_COUNT; ++q)
      {
        sums[(size_t)q * columns + x0] = s[q];
      }
    }
    if (y < window - 1)
    {
      continue;
    }
    for (size_t x0 = 0; x0 < columns; ++x0)
    {
      double s[MRGI_SSIM_SUM_COUNT] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
      for (int32_t k = 0; k < window; ++k)
      {
        const double* row_sums = ring + (size_t)k * MRGI_SSIM_SUM_COUNT * columns;
        for (int q = 0; q < MRGI_SSIM_SUM_COUNT; ++q)
        {
          s[q] += row_sums[(size_t)q * columns + x0];
        }
      }
      if (s[MRGI_SSIM_MASKED] > 0.0)
      {
        continue;
      }
      const double mean_x = s[MRGI_SSIM_SX] / n;
      const double mean_y = s[MRGI_SSIM_SY] / n;
      const double var_x = (s[MRGI_SSIM_SXX] - s[MRGI_SSIM_SX] * mean_x) / dof;
      const double var_y = (s[MRGI_SSIM_SYY] - s[MRGI_SSIM_SY] * mean_y) / dof;
      const double cov_xy = (s[MRGI_SSIM_SXY] - s[MRGI_SSIM_SX] * mean_y) / dof;
      const double numerator = (2.0 * mean_x * mean_y + c1) * (2.0 * cov_xy + c2);
      const double denominator = (mean_x * mean_x + mean_y * mean_y + c1) * (var_x + var_y + c2);
      ssim_sum += numerator / denominator;
      ++windows;
    }
  }
  free(ring);
  free(row_test);
  free(row_reference);
  free(row_masked);
  *out_ssim = windows > 0 ? ssim_sum / (double)windows : 0.0;
  *out_windows = windows;
  return MRGI_OK;
}

mrgi_status mrgi_metrics_compare(const mrgi_image* test, const mrgi_image* reference,
                                 const uint8_t* mask, double peak, mrgi_metrics* out,
                                 mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "metrics output pointer is NULL");
  }
  if (!isfinite(peak) || peak <= 0.0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "peak value %g must be finite and greater than 0", peak);
  }
  int64_t compared = 0;
  mrgi_status status = mrgi_metrics_check_inputs(test, reference, mask, &compared, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const int64_t pixels = mrgi_image_pixel_count(test);
  const size_t channels = (size_t)test->channels;
  double sum_sq_diff = 0.0;
  double sum_sq_ref = 0.0;
  double max_abs = 0.0;
  for (int64_t p = 0; p < pixels; ++p)
  {
    if (mask && mask[p])
    {
      continue;
    }
    const float* t = test->pixels + (size_t)p * channels;
    const float* r = reference->pixels + (size_t)p * channels;
    for (size_t c = 0; c < channels; ++c)
    {
      const double d = (double)t[c] - (double)r[c];
      sum_sq_diff += d * d;
      sum_sq_ref += (double)r[c] * (double)r[c];
      max_abs = fabs(d) > max_abs ? fabs(d) : max_abs;
    }
  }
  const double values = (double)compared * (double)channels;
  const double mse = sum_sq_diff / values;

  mrgi_metrics result;
  memset(&result, 0, sizeof(result));
  result.compared_pixels = compared;
  result.rms = sqrt(mse);
  result.max_abs_error = max_abs;
  if (sum_sq_ref > 0.0)
  {
    result.relative_rms = sqrt(sum_sq_diff) / sqrt(sum_sq_ref);
  }
  else
  {
    result.relative_rms = sum_sq_diff == 0.0 ? 0.0 : DBL_MAX;
  }
  if (mse > 0.0)
  {
    const double psnr = 10.0 * log10(peak * peak / mse);
    result.psnr_db = psnr < MRGI_METRICS_PSNR_MAX_DB ? psnr : MRGI_METRICS_PSNR_MAX_DB;
  }
  else
  {
    result.psnr_db = MRGI_METRICS_PSNR_MAX_DB;
  }
  status = mrgi_metrics_ssim(test, reference, mask, peak, &result.ssim, &result.ssim_windows, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  *out = result;
  return MRGI_OK;
}

mrgi_status mrgi_metrics_difference_image(const mrgi_image* test, const mrgi_image* reference,
                                          const uint8_t* mask, mrgi_image* out_diff,
                                          mrgi_error* err)
{
  if (!out_diff)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "difference image output pointer is NULL");
  }
  memset(out_diff, 0, sizeof(*out_diff));
  int64_t compared = 0;
  mrgi_status status = mrgi_metrics_check_inputs(test, reference, mask, &compared, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  mrgi_image diff;
  status = mrgi_image_create(&diff, test->width, test->height, test->channels, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const int64_t pixels = mrgi_image_pixel_count(test);
  const size_t channels = (size_t)test->channels;
  for (int64_t p = 0; p < pixels; ++p)
  {
    if (mask && mask[p])
    {
      continue; /* stays 0 from mrgi_image_create */
    }
    const size_t first = (size_t)p * channels;
    for (size_t c = 0; c < channels; ++c)
    {
      /* In double, then clamped: |FLT_MAX - (-FLT_MAX)| does not fit a float. */
      const double d = fabs((double)test->pixels[first + c] - (double)reference->pixels[first + c]);
      diff.pixels[first + c] = d < FLT_MAX ? (float)d : FLT_MAX;
    }
  }
  *out_diff = diff;
  return MRGI_OK;
}
