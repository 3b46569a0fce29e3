#include "mrgi_bmr_blend.h"

#include <math.h>
#include <string.h>

/* The four taps of level k at pixel (x, y): texel indices and weights. */
typedef struct mrgi_bmr_taps
{
  size_t index[4];
  float weight[4];
} mrgi_bmr_taps;

static void mrgi_bmr_taps_at(
  const mrgi_bmr_masks* m, int k, int32_t x, int32_t y, mrgi_bmr_taps* taps)
{
  const float scale = 1.0f / (float)((int32_t)1 << k);
  const float u = ((float)x + 0.5f) * scale - 0.5f;
  const float v = ((float)y + 0.5f) * scale - 0.5f;
  const float fu = floorf(u), fv = floorf(v);
  const float fx = u - fu, fy = v - fv;
  const int32_t w = m->level_width[k], h = m->level_height[k];
  const int32_t x0 = (int32_t)fu, y0 = (int32_t)fv;
  const int32_t xs[2] = { x0 < 0 ? 0 : (x0 > w - 1 ? w - 1 : x0),
    x0 + 1 < 0 ? 0 : (x0 + 1 > w - 1 ? w - 1 : x0 + 1) };
  const int32_t ys[2] = { y0 < 0 ? 0 : (y0 > h - 1 ? h - 1 : y0),
    y0 + 1 < 0 ? 0 : (y0 + 1 > h - 1 ? h - 1 : y0 + 1) };
  const float wx[2] = { 1.0f - fx, fx };
  const float wy[2] = { 1.0f - fy, fy };
  for (int b = 0; b < 2; ++b)
  {
    for (int a = 0; a < 2; ++a)
    {
      taps->index[2 * b + a] = (size_t)ys[b] * (size_t)w + (size_t)xs[a];
      taps->weight[2 * b + a] = wx[a] * wy[b];
    }
  }
}

mrgi_status mrgi_bmr_blend(const mrgi_bmr_masks* masks, const mrgi_bmr_params* params,
  const float* const levels[MRGI_BMR_LEVELS], int32_t channels, float* out, size_t out_size,
  mrgi_error* err)
{
  if (!masks || !levels || !out || !masks->stencil[0])
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "BMR blend: masks, levels and out must not be NULL or empty");
  }
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    if (!levels[k] || !masks->mask[k] || !masks->stencil[k])
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BMR blend: level %d is NULL", k + 1);
    }
  }
  mrgi_status status = mrgi_bmr_params_validate(params, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (channels < 1 || channels > MRGI_BMR_MAX_CHANNELS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR blend: channels must be 1..%d, got %d", MRGI_BMR_MAX_CHANNELS, (int)channels);
  }
  const int32_t W = masks->width, H = masks->height;
  const size_t needed = (size_t)W * (size_t)H * (size_t)channels;
  if (out_size < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR blend: out holds %zu floats but %d x %d x %d needs %zu", out_size, (int)W, (int)H,
      (int)channels, needed);
  }
  const size_t C = (size_t)channels;
  for (int32_t y = 0; y < H; ++y)
  {
    for (int32_t x = 0; x < W; ++x)
    {
      const size_t p = (size_t)y * (size_t)W + (size_t)x;
      float U[MRGI_BMR_MAX_CHANNELS] = { 0.0f, 0.0f, 0.0f, 0.0f };
      if (masks->nonempty[0][p])
      {
        for (int k = MRGI_BMR_LEVELS - 1; k >= 0; --k)
        {
          if (params->skip[k])
          {
            continue;
          }
          mrgi_bmr_taps taps;
          mrgi_bmr_taps_at(masks, k, x, y, &taps);
          float fine[MRGI_BMR_MAX_CHANNELS] = { 0.0f, 0.0f, 0.0f, 0.0f };
          float wsum = 0.0f, alpha = 0.0f;
          for (int t = 0; t < 4; ++t)
          {
            const float w = taps.weight[t];
            alpha += w * masks->mask[k][taps.index[t]];
            if (w > 0.0f && masks->stencil[k][taps.index[t]])
            {
              const float* c = levels[k] + taps.index[t] * C;
              for (size_t i = 0; i < C; ++i)
              {
                fine[i] += w * c[i];
              }
              wsum += w;
            }
          }
          if (!(wsum > 0.0f))
          {
            continue; /* lambda_k = 0 */
          }
          for (size_t i = 0; i < C; ++i)
          {
            fine[i] = fine[i] / wsum;
          }
          float lambda = k == MRGI_BMR_LEVELS - 1 ? 1.0f : alpha * (float)params->weight[k];
          lambda = lambda < 1.0f ? lambda : 1.0f;
          if (lambda >= 1.0f)
          {
            memcpy(U, fine, sizeof(U));
          }
          else if (lambda > 0.0f)
          {
            for (size_t i = 0; i < C; ++i)
            {
              U[i] = U[i] + lambda * (fine[i] - U[i]);
            }
          }
        }
      }
      for (size_t i = 0; i < C; ++i)
      {
        out[p * C + i] = U[i];
      }
    }
  }
  return MRGI_OK;
}
