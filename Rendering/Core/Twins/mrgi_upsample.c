#include "mrgi_upsample.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void mrgi_upsample_params_default(mrgi_upsample_params* params)
{
  if (!params)
  {
    return;
  }
  params->mode = MRGI_UPSAMPLE_TENT;
  params->mask_weight = MRGI_UPSAMPLE_DEFAULT_MASK_WEIGHT;
}

static mrgi_status mrgi_upsample_check(const mrgi_multires_layout* layout, const uint8_t* flags,
                                       size_t flags_size, const uint8_t* mask, size_t mask_size,
                                       const float* illumination, size_t illumination_count,
                                       int32_t channels, const mrgi_upsample_params* params,
                                       mrgi_error* err)
{
  const mrgi_status layout_status = mrgi_multires_layout_check(layout, err);
  if (layout_status != MRGI_OK)
  {
    return layout_status;
  }
  const uint64_t texels = (uint64_t)mrgi_multires_texel_count(layout);
  if (!flags || !mask || !illumination)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s is NULL",
                          !flags ? "flags buffer" : (!mask ? "selection mask" : "illumination buffer"));
  }
  if ((uint64_t)flags_size < texels || (uint64_t)mask_size < texels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s holds %zu bytes but the %d x %d flattened layout needs %llu",
                          (uint64_t)flags_size < texels ? "flags buffer" : "selection mask",
                          (uint64_t)flags_size < texels ? flags_size : mask_size,
                          layout->total_width, layout->total_height, (unsigned long long)texels);
  }
  if (channels != 3 && channels != 4)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "illumination has %d channels; 3 (RGB) or 4 (RGBA) expected", channels);
  }
  if ((uint64_t)illumination_count < texels * (uint64_t)channels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "illumination buffer holds %zu floats but %d x %d texels x %d channels "
                          "need %llu",
                          illumination_count, layout->total_width, layout->total_height, channels,
                          (unsigned long long)(texels * (uint64_t)channels));
  }
  if (params)
  {
    if (params->mode != MRGI_UPSAMPLE_TENT && params->mode != MRGI_UPSAMPLE_MASK_WEIGHTED)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "upsampling mode %d is neither MRGI_UPSAMPLE_TENT (%d) nor "
                            "MRGI_UPSAMPLE_MASK_WEIGHTED (%d)",
                            params->mode, MRGI_UPSAMPLE_TENT, MRGI_UPSAMPLE_MASK_WEIGHTED);
    }
    if (params->mode == MRGI_UPSAMPLE_MASK_WEIGHTED &&
        !(params->mask_weight >= 1.0f && params->mask_weight <= MRGI_UPSAMPLE_MAX_MASK_WEIGHT))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "mask weight %g is outside 1..%g", (double)params->mask_weight,
                            (double)MRGI_UPSAMPLE_MAX_MASK_WEIGHT);
    }
  }
  return MRGI_OK;
}

/* Bits of the per-texel state array. */
#define MRGI_UPSAMPLE_HAS 1u      /* holds data */
#define MRGI_UPSAMPLE_BLEND 2u    /* E: may be blended */
#define MRGI_UPSAMPLE_SELECTED 4u /* S */

/* U of level i texel (x, y) from V and the state of level i (file comment). */
static void mrgi_upsample_filter(const mrgi_multires_layout* layout, int32_t i, int32_t x,
                                 int32_t y, const float* value, const uint8_t* state,
                                 const mrgi_upsample_params* params, float out[3])
{
  const size_t t = mrgi_multires_index(layout, i, x, y);
  if (!(state[t] & MRGI_UPSAMPLE_BLEND))
  {
    for (int c = 0; c < 3; ++c)
    {
      out[c] = (state[t] & MRGI_UPSAMPLE_HAS) ? value[3 * t + c] : 0.0f;
    }
    return;
  }
  const int32_t w = layout->level_width[i];
  const int32_t h = layout->level_height[i];
  float weight_all = 0.0f;
  float weight_selected = 0.0f;
  float sum_all[3] = { 0.0f, 0.0f, 0.0f };
  float sum_selected[3] = { 0.0f, 0.0f, 0.0f };
  float sum_upsampled[3] = { 0.0f, 0.0f, 0.0f };
  for (int32_t dy = -1; dy <= 1; ++dy)
  {
    for (int32_t dx = -1; dx <= 1; ++dx)
    {
      const int32_t nx = x + dx;
      const int32_t ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= w || ny >= h)
      {
        continue;
      }
      const size_t n = mrgi_multires_index(layout, i, nx, ny);
      if (!(state[n] & MRGI_UPSAMPLE_BLEND))
      {
        continue;
      }
      const float k = (float)((2 - abs(dx)) * (2 - abs(dy)));
      const int selected = (state[n] & MRGI_UPSAMPLE_SELECTED) != 0;
      weight_all += k;
      if (selected)
      {
        weight_selected += k;
      }
      for (int c = 0; c < 3; ++c)
      {
        const float kv = k * value[3 * n + c];
        sum_all[c] += kv;
        if (selected)
        {
          sum_selected[c] += kv;
        }
        else
        {
          sum_upsampled[c] += kv;
        }
      }
    }
  }
  /* weight_all >= 4: t itself takes part. */
  if (params->mode == MRGI_UPSAMPLE_TENT)
  {
    for (int c = 0; c < 3; ++c)
    {
      out[c] = sum_all[c] / weight_all;
    }
    return;
  }
  const float a = weight_selected / weight_all;
  const float weight_upsampled = weight_all - weight_selected;
  float lambda = a * params->mask_weight;
  lambda = lambda < 1.0f ? lambda : 1.0f;
  for (int c = 0; c < 3; ++c)
  {
    if (a == 0.0f)
    {
      out[c] = sum_upsampled[c] / weight_upsampled;
    }
    else if (a == 1.0f)
    {
      out[c] = sum_selected[c] / weight_selected;
    }
    else
    {
      const float fine = sum_selected[c] / weight_selected;
      const float coarse = sum_upsampled[c] / weight_upsampled;
      out[c] = coarse + lambda * (fine - coarse);
    }
  }
}

mrgi_status mrgi_upsample(const mrgi_multires_layout* layout, const uint8_t* flags,
                          size_t flags_size, const uint8_t* mask, size_t mask_size,
                          const float* illumination, size_t illumination_count,
                          int32_t channels, const mrgi_upsample_params* params, mrgi_image* out,
                          mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output image is NULL");
  }
  memset(out, 0, sizeof(*out));
  mrgi_status status = mrgi_upsample_check(layout, flags, flags_size, mask, mask_size,
                                           illumination, illumination_count, channels, params,
                                           err);
  if (status != MRGI_OK)
  {
    return status;
  }
  mrgi_upsample_params defaults;
  mrgi_upsample_params_default(&defaults);
  if (!params)
  {
    params = &defaults;
  }
  const size_t texels = (size_t)mrgi_multires_texel_count(layout);
  float* value = (float*)calloc(texels * 3, sizeof(float));    /* V */
  float* filtered = (float*)calloc(texels * 3, sizeof(float)); /* U */
  uint8_t* state = (uint8_t*)calloc(texels, 1);
  if (!value || !filtered || !state)
  {
    free(value);
    free(filtered);
    free(state);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "cannot allocate upsampling buffers for %d x %d texels",
                          layout->total_width, layout->total_height);
  }
  status = mrgi_image_create(out, layout->width, layout->height, 3, err);
  if (status != MRGI_OK)
  {
    free(value);
    free(filtered);
    free(state);
    mrgi_error_prefix(err, "upsampled image: ");
    return status;
  }

  const int32_t coarsest = layout->level_count - 1;
  for (int32_t i = coarsest; i >= 0; --i)
  {
    const int32_t w = layout->level_width[i];
    const int32_t h = layout->level_height[i];
    /* HAS, S, E and V (combine + nearest upsampling). */
    for (int32_t y = 0; y < h; ++y)
    {
      for (int32_t x = 0; x < w; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        unsigned bits = 0;
        if (mask[t])
        {
          bits = MRGI_UPSAMPLE_HAS | MRGI_UPSAMPLE_SELECTED;
          for (int c = 0; c < 3; ++c)
          {
            value[3 * t + c] = illumination[(size_t)channels * t + (size_t)c];
          }
        }
        else if (i < coarsest && (flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY))
        {
          const size_t p = mrgi_multires_index(layout, i + 1, x / 2, y / 2);
          if (state[p] & MRGI_UPSAMPLE_HAS)
          {
            bits = MRGI_UPSAMPLE_HAS;
            for (int c = 0; c < 3; ++c)
            {
              value[3 * t + c] = filtered[3 * p + c];
            }
          }
        }
        if ((bits & MRGI_UPSAMPLE_HAS) && !(flags[t] & MRGI_MULTIRES_FLAG_DISCONTINUOUS))
        {
          bits |= MRGI_UPSAMPLE_BLEND;
        }
        state[t] = (uint8_t)bits;
      }
    }
    /* U: interpolation with same-level neighbours that may be blended. */
    for (int32_t y = 0; y < h; ++y)
    {
      for (int32_t x = 0; x < w; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        mrgi_upsample_filter(layout, i, x, y, value, state, params, filtered + 3 * t);
      }
    }
  }
  /* Level 0 -> image: valid pixels only (same bottom-up row order). */
  for (int32_t y = 0; y < layout->height; ++y)
  {
    for (int32_t x = 0; x < layout->width; ++x)
    {
      const size_t t = mrgi_multires_index(layout, 0, x, y);
      float* pixel = mrgi_image_at(out, x, y);
      if (flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY)
      {
        for (int c = 0; c < 3; ++c)
        {
          pixel[c] = filtered[3 * t + c];
        }
      }
    }
  }
  free(value);
  free(filtered);
  free(state);
  return MRGI_OK;
}

/* v / |v| computed on v / max|v_i| so that neither tiny nor huge scene
 * scales underflow or overflow; 0 when v is zero or not finite. */
static int mrgi_unit(const float v[3], float out[3])
{
  const float m = fmaxf(fmaxf(fabsf(v[0]), fabsf(v[1])), fabsf(v[2]));
  if (!(m > 0.0f && m <= MRGI_MULTIRES_FLT_MAX))
  {
    return 0;
  }
  const float x = v[0] / m, y = v[1] / m, z = v[2] / m;
  const float inverse = 1.0f / sqrtf(x * x + y * y + z * z);
  out[0] = x * inverse;
  out[1] = y * inverse;
  out[2] = z * inverse;
  return 1;
}

float mrgi_surface_detail_factor(const float position_eye[3], const float normal_eye[3],
                                 int32_t parallel, float alpha)
{
  /* Same operations, same order as the GLSL twin (resolve stage). */
  float v[3] = { 0.0f, 0.0f, 1.0f };
  float to_point[3];
  if (!parallel && mrgi_unit(position_eye, to_point))
  {
    v[0] = -to_point[0];
    v[1] = -to_point[1];
    v[2] = -to_point[2];
  }
  float n[3];
  float facing = 0.0f;
  if (mrgi_unit(normal_eye, n))
  {
    facing = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  }
  facing = facing > 0.0f ? facing : 0.0f; /* also NaN -> 0 */
  return alpha * facing + (1.0f - alpha);
}
