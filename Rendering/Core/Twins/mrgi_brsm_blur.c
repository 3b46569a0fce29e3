/* Geometry-aware blur of the BRSM importance (RIHKS11 6.5); contract in mrgi_brsm_blur.h. */
#include "mrgi_brsm_blur.h"

#include <math.h>

int32_t mrgi_brsm_blur_radius(int32_t size)
{
  const int32_t r = (int32_t)floor(MRGI_BRSM_BLUR_RADIUS_SHARE * size + 0.5);
  return r > 1 ? r : 1;
}

int mrgi_brsm_same_surface(const mrgi_rsm* rsm, int64_t t, int64_t s, double texel_distance)
{
  const float* nt = rsm->normal + 4 * t;
  const float* ns = rsm->normal + 4 * s;
  const double cosine = (double)nt[0] * ns[0] + (double)nt[1] * ns[1] + (double)nt[2] * ns[2];
  if (!(cosine > MRGI_BRSM_SAME_SURFACE_COS))
  {
    return 0;
  }
  const float* pt = rsm->position + 4 * t;
  const float* ps = rsm->position + 4 * s;
  const double d[3] = { (double)pt[0] - ps[0], (double)pt[1] - ps[1], (double)pt[2] - ps[2] };
  const double at = rsm->flux[4 * t + 3], as = rsm->flux[4 * s + 3];
  const double limit = MRGI_BRSM_SAME_SURFACE_TEXELS * sqrt(at > as ? at : as) * texel_distance;
  return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < limit * limit;
}

mrgi_status mrgi_brsm_blur(const mrgi_rsm* rsm, const float* in, float* out, size_t count,
                           mrgi_error* err)
{
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t texel_count = mrgi_vpl_importance_scratch_count(rsm);
  if (!in || !out || count < texel_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM blur needs two arrays of %zu floats (got %s, %zu)", texel_count,
                          (!in || !out) ? "NULL" : "arrays", count);
  }
  if ((in < out + texel_count) && (out < in + texel_count))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BRSM blur input and output overlap");
  }
  for (size_t t = 0; t < texel_count; ++t)
  {
    if (!(in[t] >= 0.0f) || !isfinite(in[t]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "BRSM importance of texel %zu is negative or not finite", t);
    }
  }
  const int32_t S = rsm->size;
  const int32_t r = mrgi_brsm_blur_radius(S);
  const double sigma = 0.5 * r;
  const double inv_two_sigma2 = 1.0 / (2.0 * sigma * sigma);
  for (int32_t v = 0; v < rsm->view_count; ++v)
  {
    for (int32_t y = 0; y < S; ++y)
    {
      for (int32_t x = 0; x < S; ++x)
      {
        const int64_t t = ((int64_t)v * S + y) * S + x;
        if (!mrgi_rsm_texel_usable(rsm, t))
        {
          out[t] = 0.0f;
          continue;
        }
        double sum = 0.0, weight = 0.0;
        for (int32_t sy = y - r; sy <= y + r; ++sy)
        {
          for (int32_t sx = x - r; sx <= x + r; ++sx)
          {
            if (sx < 0 || sy < 0 || sx >= S || sy >= S)
            {
              continue;
            }
            const int64_t s = ((int64_t)v * S + sy) * S + sx;
            const double d2 = (double)(sx - x) * (sx - x) + (double)(sy - y) * (sy - y);
            if (s != t && (!mrgi_rsm_texel_usable(rsm, s) ||
                           !mrgi_brsm_same_surface(rsm, t, s, sqrt(d2))))
            {
              continue;
            }
            const double g = exp(-d2 * inv_two_sigma2);
            sum += g * in[s];
            weight += g;
          }
        }
        out[t] = (float)(sum / weight); /* weight >= 1 (the centre) */
      }
    }
  }
  return MRGI_OK;
}
