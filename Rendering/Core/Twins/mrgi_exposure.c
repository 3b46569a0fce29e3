#include "mrgi_exposure.h"

#include "mrgi_vpl.h"

#include <math.h>

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
    if (depth && !(depth[i] < 1.0f))
    {
      continue; /* background (or NaN depth) */
    }
    const float* p = rgb + (size_t)i * (size_t)stride;
    const double l = MRGI_LUMINANCE_R * p[0] + MRGI_LUMINANCE_G * p[1] + MRGI_LUMINANCE_B * p[2];
    if (!(l >= 0.0) || isinf(l))
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

double mrgi_exposure_auto_ev(double log_average, double key)
{
  if (!(log_average > 0.0) || !(key > 0.0) || isinf(log_average) || isinf(key))
  {
    return 0.0;
  }
  double ev = log2(key / log_average);
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
