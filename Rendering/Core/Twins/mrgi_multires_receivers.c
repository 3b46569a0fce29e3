#include "mrgi_multires_receivers.h"

#include "mrgi_buffers.h"

#include <math.h>
#include <string.h>

/* n / sqrt(max(|n|^2, tiny)), as the GLSL writes it. */
static void mrgi_receivers_normalize(const float in[3], float out[3])
{
  float length2 = in[0] * in[0] + in[1] * in[1] + in[2] * in[2];
  if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE))
  {
    length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE;
  }
  const float inverse_length = 1.0f / sqrtf(length2);
  for (int k = 0; k < 3; ++k)
  {
    out[k] = in[k] * inverse_length;
  }
}

mrgi_status mrgi_multires_receivers_build(const mrgi_multires_layout* layout,
                                          const mrgi_gather_receivers* gbuffer, float* position,
                                          float* normal, size_t count, mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!gbuffer || !gbuffer->position || !gbuffer->normal || !position || !normal)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "receivers: the G-buffer and both output arrays are required");
  }
  if (gbuffer->width != layout->width || gbuffer->height != layout->height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "receivers: G-buffer is %d x %d but the layout is for %d x %d",
                          gbuffer->width, gbuffer->height, layout->width, layout->height);
  }
  const size_t needed = 4 * (size_t)mrgi_multires_texel_count(layout);
  if (count < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "receivers: arrays of %zu floats are too small for %zu", count, needed);
  }
  memset(position, 0, needed * sizeof(float));
  memset(normal, 0, needed * sizeof(float));
  for (int32_t y = 0; y < layout->height; ++y)
  {
    for (int32_t x = 0; x < layout->width; ++x)
    {
      const size_t p = 4 * ((size_t)y * (size_t)layout->width + (size_t)x);
      const float* P = gbuffer->position + p;
      const float* N = gbuffer->normal + p;
      const int valid = P[3] > MRGI_GBUFFER_VALID_THRESHOLD && isfinite(P[2]) && isfinite(N[0]) &&
                        isfinite(N[1]) && isfinite(N[2]) && isfinite(P[0]) && isfinite(P[1]);
      if (!valid)
      {
        continue;
      }
      const size_t t = 4 * mrgi_multires_index(layout, 0, x, y);
      position[t + 0] = P[0];
      position[t + 1] = P[1];
      position[t + 2] = P[2];
      position[t + 3] = 1.0f;
      mrgi_receivers_normalize(N, normal + t);
    }
  }
  for (int32_t i = 1; i < layout->level_count; ++i)
  {
    const int32_t cw = layout->level_width[i - 1];
    const int32_t ch = layout->level_height[i - 1];
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        float sum_p[3] = { 0.0f, 0.0f, 0.0f }, sum_n[3] = { 0.0f, 0.0f, 0.0f }, total = 0.0f;
        for (int32_t b = 0; b < 2; ++b)
        {
          for (int32_t c = 0; c < 2; ++c)
          {
            const int32_t cx = 2 * x + c, cy = 2 * y + b;
            if (cx >= cw || cy >= ch)
            {
              continue;
            }
            const size_t s = 4 * mrgi_multires_index(layout, i - 1, cx, cy);
            const float w = position[s + 3];
            if (!(w > 0.0f))
            {
              continue;
            }
            for (int k = 0; k < 3; ++k)
            {
              sum_p[k] += w * position[s + k];
              sum_n[k] += w * normal[s + k];
            }
            total += w;
          }
        }
        if (!(total > 0.0f))
        {
          continue;
        }
        const size_t t = 4 * mrgi_multires_index(layout, i, x, y);
        for (int k = 0; k < 3; ++k)
        {
          position[t + k] = sum_p[k] / total;
        }
        position[t + 3] = total;
        mrgi_receivers_normalize(sum_n, normal + t);
      }
    }
  }
  return MRGI_OK;
}
