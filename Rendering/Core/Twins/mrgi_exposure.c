#include "mrgi_exposure.h"

#include "mrgi_vpl.h"

#include <math.h>
#include <string.h>

float mrgi_tone_curve(float x)
{
  const float k = (float)MRGI_TONE_SHOULDER;
  if (!(x > 0.0f))
  {
    return 0.0f; /* also NaN */
  }
  if (x <= k)
  {
    return x;
  }
  if (isinf(x))
  {
    return 1.0f;
  }
  return k + (1.0f - k) * (1.0f - expf(-(x - k) / (1.0f - k)));
}

float mrgi_exposure_scale(double ev)
{
  if (isnan(ev))
  {
    return 1.0f;
  }
  if (ev < MRGI_EXPOSURE_MIN_EV)
  {
    ev = MRGI_EXPOSURE_MIN_EV;
  }
  if (ev > MRGI_EXPOSURE_MAX_EV)
  {
    ev = MRGI_EXPOSURE_MAX_EV;
  }
  return (float)exp2(ev);
}

void mrgi_exposure_apply(const float rgb_in[3], float scale, int tone_map, float rgb_out[3])
{
  for (int c = 0; c < 3; ++c)
  {
    const float x = scale * rgb_in[c];
    rgb_out[c] = tone_map ? mrgi_tone_curve(x) : x;
  }
}

/* Luminance of pixel i, or -1 when it does not count (background, not finite, negative). */
static double foreground_luminance(const float* rgb, int32_t stride, const float* depth, int64_t i)
{
  if (depth && !(depth[i] < 1.0f))
  {
    return -1.0; /* background (or NaN depth) */
  }
  const float* p = rgb + (size_t)i * (size_t)stride;
  const double l = MRGI_LUMINANCE_R * p[0] + MRGI_LUMINANCE_G * p[1] + MRGI_LUMINANCE_B * p[2];
  return (l >= 0.0 && !isinf(l)) ? l : -1.0;
}

mrgi_status mrgi_exposure_log_average(const float* rgb, int32_t stride, const float* depth,
  int64_t count, double* log_average, int64_t* used, mrgi_error* err)
{
  if (!log_average || count < 0 || (count > 0 && !rgb) || stride < 3 || stride > 64)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "mrgi_exposure_log_average: needs pixels, a stride in 3..64 and a count >= 0");
  }
  double sum = 0.0;
  int64_t n = 0;
  for (int64_t i = 0; i < count; ++i)
  {
    const double l = foreground_luminance(rgb, stride, depth, i);
    if (l < 0.0)
    {
      continue;
    }
    sum += log(MRGI_EXPOSURE_DELTA + l);
    ++n;
  }
  *log_average = n > 0 ? exp(sum / (double)n) : 0.0;
  if (used)
  {
    *used = n;
  }
  return MRGI_OK;
}

mrgi_status mrgi_exposure_quantile(const float* rgb, int32_t stride, const float* depth,
  int64_t count, double fraction, double* quantile, mrgi_error* err)
{
  enum
  {
    BINS = (MRGI_EXPOSURE_HISTOGRAM_MAX_LOG2 - MRGI_EXPOSURE_HISTOGRAM_MIN_LOG2) *
      MRGI_EXPOSURE_HISTOGRAM_BINS
  };
  if (!quantile || count < 0 || (count > 0 && !rgb) || stride < 3 || stride > 64 ||
    !(fraction > 0.0 && fraction <= 1.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "mrgi_exposure_quantile: needs pixels, a stride in 3..64, a count >= 0 and a fraction "
      "in (0, 1]");
  }
  int64_t histogram[BINS];
  memset(histogram, 0, sizeof(histogram));
  int64_t n = 0;
  for (int64_t i = 0; i < count; ++i)
  {
    const double l = foreground_luminance(rgb, stride, depth, i);
    if (l < 0.0)
    {
      continue;
    }
    double bin = l > 0.0
      ? floor((log2(l) - MRGI_EXPOSURE_HISTOGRAM_MIN_LOG2) * MRGI_EXPOSURE_HISTOGRAM_BINS)
      : 0.0;
    bin = bin < 0.0 ? 0.0 : bin > BINS - 1 ? BINS - 1 : bin;
    ++histogram[(int)bin];
    ++n;
  }
  *quantile = 0.0;
  if (n == 0)
  {
    return MRGI_OK;
  }
  const double target = fraction * (double)n;
  int64_t cumulative = 0;
  for (int b = 0; b < BINS; ++b)
  {
    cumulative += histogram[b];
    if ((double)cumulative >= target)
    {
      *quantile =
        exp2(MRGI_EXPOSURE_HISTOGRAM_MIN_LOG2 + (double)(b + 1) / MRGI_EXPOSURE_HISTOGRAM_BINS);
      break;
    }
  }
  return MRGI_OK;
}

static int usable(double v)
{
  return v > 0.0 && !isinf(v);
}

double mrgi_exposure_auto_ev(double log_average, double highlight, double key)
{
  if (!usable(key) || (!usable(log_average) && !usable(highlight)))
  {
    return 0.0;
  }
  double ev = MRGI_EXPOSURE_MAX_EV;
  if (usable(log_average))
  {
    ev = log2(key / log_average);
  }
  if (usable(highlight) && log2(1.0 / highlight) < ev)
  {
    ev = log2(1.0 / highlight);
  }
  if (ev < MRGI_EXPOSURE_MIN_EV)
  {
    ev = MRGI_EXPOSURE_MIN_EV;
  }
  if (ev > MRGI_EXPOSURE_MAX_EV)
  {
    ev = MRGI_EXPOSURE_MAX_EV;
  }
  return ev;
}
