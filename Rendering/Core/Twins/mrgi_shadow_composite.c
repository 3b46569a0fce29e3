#include "mrgi_shadow_composite.h"

#include <math.h>

static float mrgi_clean_factor(float f)
{
  // A broken factor never darkens: NaN, Inf and values outside [0, 1] are 1.
  return (isfinite(f) && f >= 0.0f && f <= 1.0f) ? f : 1.0f;
}

void mrgi_shadow_composite_pixel(
  const float colour[4], const float* terms, const float* factors, float out[4])
{
  float removed[3] = { 0.0f, 0.0f, 0.0f };
  int shadowed = 0;
  int gamma = 0;
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    const float* term = terms + 4 * s;
    const float occluded = 1.0f - mrgi_clean_factor(factors[s]);
    for (int c = 0; c < 3; ++c)
    {
      const float t = isfinite(term[c]) ? term[c] : 0.0f;
      gamma |= t < 0.0f;
      if (occluded > 0.0f)
      {
        removed[c] += occluded * fabsf(t);
        shadowed = 1;
      }
    }
  }
  const float a = colour[3];
  if (!shadowed)
  {
    // Lit: VTK's own value, untouched.
    out[0] = colour[0];
    out[1] = colour[1];
    out[2] = colour[2];
    out[3] = a;
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    const float v = colour[c];
    if (!isfinite(v))
    {
      out[c] = v;
    }
    else if (gamma)
    {
      const float linear = powf(fmaxf(v, 0.0f), MRGI_SHADOW_PBR_GAMMA);
      out[c] = powf(fmaxf(linear - removed[c], 0.0f), 1.0f / MRGI_SHADOW_PBR_GAMMA);
    }
    else
    {
      out[c] = fmaxf(v - removed[c], 0.0f);
    }
  }
  out[3] = a;
}

mrgi_status mrgi_shadow_composite(const float* colour, const float* const terms[MRGI_SHADOW_SLOTS],
  const float* factors, size_t count, float* out, mrgi_error* err)
{
  if (!colour || !terms || !factors || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_shadow_composite: missing array");
  }
  for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
  {
    if (!terms[s])
    {
      return mrgi_error_set(
        err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_shadow_composite: no terms for slot %d", s);
    }
  }
  for (size_t i = 0; i < count; ++i)
  {
    float pixelTerms[4 * MRGI_SHADOW_SLOTS];
    float pixelFactors[MRGI_SHADOW_SLOTS];
    for (int s = 0; s < MRGI_SHADOW_SLOTS; ++s)
    {
      for (int c = 0; c < 4; ++c)
      {
        pixelTerms[4 * s + c] = terms[s][4 * i + (size_t)c];
      }
      pixelFactors[s] = factors[4 * i + (size_t)s];
    }
    mrgi_shadow_composite_pixel(colour + 4 * i, pixelTerms, pixelFactors, out + 4 * i);
  }
  return MRGI_OK;
}
