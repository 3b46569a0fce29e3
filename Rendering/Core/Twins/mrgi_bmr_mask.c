#include "mrgi_bmr_mask.h"

#include "mrgi_buffers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int mrgi_bmr_finite(float v)
{
  return !isnan(v) && !isinf(v);
}

const char* mrgi_bmr_effect_name(int32_t effect)
{
  switch (effect)
  {
    case MRGI_BMR_EFFECT_SSAO:
      return "ssao";
    case MRGI_BMR_EFFECT_SSM:
      return "ssm";
    case MRGI_BMR_EFFECT_SSGI:
      return "ssgi";
    default:
      return NULL;
  }
}

mrgi_status mrgi_bmr_preset_params(int32_t effect, mrgi_bmr_params* params, mrgi_error* err)
{
  static const double table[MRGI_BMR_EFFECT_COUNT][2][MRGI_BMR_LEVELS] = {
    { { MRGI_BMR_SSAO_VARIANCE_1, MRGI_BMR_SSAO_VARIANCE_2, MRGI_BMR_SSAO_VARIANCE_3,
        MRGI_BMR_SSAO_VARIANCE_4 },
      { MRGI_BMR_SSAO_WEIGHT_1, MRGI_BMR_SSAO_WEIGHT_2, MRGI_BMR_SSAO_WEIGHT_3,
        MRGI_BMR_SSAO_WEIGHT_4 } },
    { { MRGI_BMR_SSM_VARIANCE_1, MRGI_BMR_SSM_VARIANCE_2, MRGI_BMR_SSM_VARIANCE_3,
        MRGI_BMR_SSM_VARIANCE_4 },
      { MRGI_BMR_SSM_WEIGHT_1, MRGI_BMR_SSM_WEIGHT_2, MRGI_BMR_SSM_WEIGHT_3,
        MRGI_BMR_SSM_WEIGHT_4 } },
    { { MRGI_BMR_SSGI_VARIANCE_1, MRGI_BMR_SSGI_VARIANCE_2, MRGI_BMR_SSGI_VARIANCE_3,
        MRGI_BMR_SSGI_VARIANCE_4 },
      { MRGI_BMR_SSGI_WEIGHT_1, MRGI_BMR_SSGI_WEIGHT_2, MRGI_BMR_SSGI_WEIGHT_3,
        MRGI_BMR_SSGI_WEIGHT_4 } },
  };
  if (!params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BMR preset: params is NULL");
  }
  if (effect < 0 || effect >= MRGI_BMR_EFFECT_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR preset: unknown effect %d (0 ssao, 1 ssm, 2 ssgi)", (int)effect);
  }
  memset(params, 0, sizeof(*params));
  params->depth_threshold = MRGI_BMR_DEFAULT_DEPTH_THRESHOLD;
  params->normal_threshold = MRGI_BMR_DEFAULT_NORMAL_THRESHOLD;
  params->combine = MRGI_BMR_COMBINE_MAX;
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    params->variance[k] = table[effect][0][k];
    params->weight[k] = table[effect][1][k];
  }
  if (effect == MRGI_BMR_EFFECT_SSGI)
  {
    params->skip[MRGI_BMR_SSGI_SKIP_LEVEL] = 1;
  }
  return MRGI_OK;
}

mrgi_status mrgi_bmr_params_validate(const mrgi_bmr_params* params, mrgi_error* err)
{
  if (!params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BMR params is NULL");
  }
  if (!(params->depth_threshold >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR depth threshold must be >= 0 (+inf: off), got %g", params->depth_threshold);
  }
  if (!(params->normal_threshold >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR normal threshold must be >= 0 (+inf: off), got %g", params->normal_threshold);
  }
  if (params->combine != MRGI_BMR_COMBINE_MAX && params->combine != MRGI_BMR_COMBINE_MIN)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR combine must be %d (max) or %d (min), got %d", MRGI_BMR_COMBINE_MAX,
      MRGI_BMR_COMBINE_MIN, (int)params->combine);
  }
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    if (!(params->variance[k] >= 0.0 && params->variance[k] <= MRGI_BMR_MAX_VARIANCE))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "BMR variance of level %d must be in [0, %g], got %g", k + 1, MRGI_BMR_MAX_VARIANCE,
        params->variance[k]);
    }
    if (!(params->weight[k] >= 0.0 && params->weight[k] <= 1e30))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "BMR weight of level %d must be finite and >= 0, got %g", k + 1, params->weight[k]);
    }
    if (params->skip[k] != 0 && params->skip[k] != 1)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "BMR skip flag of level %d must be 0 or 1, got %d", k + 1, (int)params->skip[k]);
    }
  }
  if (params->skip[MRGI_BMR_LEVELS - 1])
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR level %d covers every pixel and cannot be skipped", MRGI_BMR_LEVELS);
  }
  return MRGI_OK;
}

void mrgi_bmr_masks_destroy(mrgi_bmr_masks* masks)
{
  if (!masks)
  {
    return;
  }
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    free(masks->edge[k]);
    free(masks->nonempty[k]);
    free(masks->mask[k]);
    free(masks->required[k]);
    free(masks->stencil[k]);
  }
  memset(masks, 0, sizeof(*masks));
}

/* Sizes and arrays for a W x H image. */
static mrgi_status mrgi_bmr_masks_alloc(mrgi_bmr_masks* out, int32_t W, int32_t H, mrgi_error* err)
{
  memset(out, 0, sizeof(*out));
  out->width = W;
  out->height = H;
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    const int32_t scale = (int32_t)1 << k;
    out->level_width[k] = (W + scale - 1) / scale;
    out->level_height[k] = (H + scale - 1) / scale;
    const size_t n = (size_t)out->level_width[k] * (size_t)out->level_height[k];
    out->edge[k] = (uint8_t*)calloc(n, 1);
    out->nonempty[k] = (uint8_t*)calloc(n, 1);
    out->mask[k] = (float*)calloc(n, sizeof(float));
    out->required[k] = (uint8_t*)calloc(n, 1);
    out->stencil[k] = (uint8_t*)calloc(n, 1);
    if (!out->edge[k] || !out->nonempty[k] || !out->mask[k] || !out->required[k] ||
      !out->stencil[k])
    {
      mrgi_bmr_masks_destroy(out);
      return mrgi_error_set(
        err, MRGI_ERR_OUT_OF_MEMORY, "BMR masks: out of memory at %d x %d", (int)W, (int)H);
    }
  }
  return MRGI_OK;
}

/* Max of `src` (level k-1) over the children of each level-k texel. */
static void mrgi_bmr_max_down(
  const uint8_t* src, int32_t sw, int32_t sh, uint8_t* dst, int32_t dw, int32_t dh)
{
  for (int32_t y = 0; y < dh; ++y)
  {
    for (int32_t x = 0; x < dw; ++x)
    {
      uint8_t m = 0;
      for (int32_t b = 0; b < 2; ++b)
      {
        for (int32_t a = 0; a < 2; ++a)
        {
          const int32_t cx = 2 * x + a, cy = 2 * y + b;
          if (cx < sw && cy < sh && src[(size_t)cy * (size_t)sw + (size_t)cx])
          {
            m = 1;
          }
        }
      }
      dst[(size_t)y * (size_t)dw + (size_t)x] = m;
    }
  }
}

/* Gaussian blur, masks and stencils from E_k and NE_k (sections 2-3). */
static mrgi_status mrgi_bmr_finish(
  mrgi_bmr_masks* out, const mrgi_bmr_params* params, mrgi_error* err)
{
  const size_t n0 = (size_t)out->level_width[0] * (size_t)out->level_height[0];
  float* row = (float*)malloc(n0 * sizeof(float));
  if (!row)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "BMR masks: out of memory");
  }
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    const int32_t w = out->level_width[k], h = out->level_height[k];
    float* a = out->mask[k];
    const uint8_t* E = out->edge[k];
    if (params->skip[k])
    {
      memset(a, 0, (size_t)w * (size_t)h * sizeof(float));
    }
    else
    {
      const float variance = (float)params->variance[k];
      const int32_t radius = variance > 0.0f ? (int32_t)ceilf(3.0f * sqrtf(variance)) : 0;
      float g[MRGI_BMR_MAX_RADIUS + 1];
      for (int32_t j = 0; j <= radius; ++j)
      {
        g[j] = radius == 0 ? 1.0f : expf(-(float)(j * j) / (2.0f * variance));
      }
      /* Horizontal pass into `row`, then vertical into a. */
      for (int32_t y = 0; y < h; ++y)
      {
        for (int32_t x = 0; x < w; ++x)
        {
          float sum = 0.0f, wsum = 0.0f;
          for (int32_t j = -radius; j <= radius; ++j)
          {
            const int32_t q = x + j;
            if (q < 0 || q >= w)
            {
              continue;
            }
            const float gj = g[j < 0 ? -j : j];
            sum += gj * (float)E[(size_t)y * (size_t)w + (size_t)q];
            wsum += gj;
          }
          row[(size_t)y * (size_t)w + (size_t)x] = sum / wsum;
        }
      }
      for (int32_t y = 0; y < h; ++y)
      {
        for (int32_t x = 0; x < w; ++x)
        {
          float sum = 0.0f, wsum = 0.0f;
          for (int32_t j = -radius; j <= radius; ++j)
          {
            const int32_t q = y + j;
            if (q < 0 || q >= h)
            {
              continue;
            }
            const float gj = g[j < 0 ? -j : j];
            sum += gj * row[(size_t)q * (size_t)w + (size_t)x];
            wsum += gj;
          }
          a[(size_t)y * (size_t)w + (size_t)x] = sum / wsum;
        }
      }
    }
    /* R_k and S_k. */
    for (int32_t y = 0; y < h; ++y)
    {
      for (int32_t x = 0; x < w; ++x)
      {
        const size_t t = (size_t)y * (size_t)w + (size_t)x;
        int required = 0;
        if (out->nonempty[k][t])
        {
          if (k == MRGI_BMR_LEVELS - 1 || a[t] > 0.0f)
          {
            required = 1;
          }
          else if (k > 0)
          {
            const int32_t sw = out->level_width[k - 1], sh = out->level_height[k - 1];
            for (int32_t b = 0; b < 2; ++b)
            {
              for (int32_t c = 0; c < 2; ++c)
              {
                const int32_t cx = 2 * x + c, cy = 2 * y + b;
                if (cx < sw && cy < sh &&
                  out->required[k - 1][(size_t)cy * (size_t)sw + (size_t)cx])
                {
                  required = 1;
                }
              }
            }
          }
        }
        out->required[k][t] = (uint8_t)required;
        out->stencil[k][t] = (uint8_t)(required && !params->skip[k]);
      }
    }
  }
  free(row);
  return MRGI_OK;
}

/* Pixel validity as in mrgi_multires.h. */
static int mrgi_bmr_valid(const mrgi_gather_receivers* g, size_t p)
{
  const float* P = g->position + 4 * p;
  const float* N = g->normal + 4 * p;
  return P[3] > MRGI_GBUFFER_VALID_THRESHOLD && mrgi_bmr_finite(P[2]) && mrgi_bmr_finite(N[0]) &&
    mrgi_bmr_finite(N[1]) && mrgi_bmr_finite(N[2]);
}

/* Unit normal component c of pixel p (as mrgi_multires.c). */
static void mrgi_bmr_unit_normal(const mrgi_gather_receivers* g, size_t p, float n[3])
{
  const float* N = g->normal + 4 * p;
  float length2 = N[0] * N[0] + N[1] * N[1] + N[2] * N[2];
  if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE))
  {
    length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE;
  }
  const float inverse_length = 1.0f / sqrtf(length2);
  for (int c = 0; c < 3; ++c)
  {
    n[c] = N[c] * inverse_length;
  }
}

mrgi_status mrgi_bmr_mask_build(const mrgi_gather_receivers* gbuffer, const float* shadow,
  const float pixel_size_coefficients[2], const mrgi_bmr_params* params, mrgi_bmr_masks* out,
  mrgi_error* err)
{
  if (out)
  {
    memset(out, 0, sizeof(*out));
  }
  if (!gbuffer || !gbuffer->position || !gbuffer->normal || !pixel_size_coefficients || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR mask: the G-buffer, its arrays, the pixel-size coefficients and "
      "the output must not be NULL");
  }
  const int32_t W = gbuffer->width, H = gbuffer->height;
  if (W < 1 || H < 1 || W > MRGI_IMAGE_MAX_DIMENSION || H > MRGI_IMAGE_MAX_DIMENSION)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR mask: G-buffer size %d x %d is outside 1..%d", (int)W, (int)H,
      (int)MRGI_IMAGE_MAX_DIMENSION);
  }
  const float ca = pixel_size_coefficients[0], cb = pixel_size_coefficients[1];
  if (!(mrgi_bmr_finite(ca) && mrgi_bmr_finite(cb) && ca >= 0.0f && cb >= 0.0f &&
        (ca > 0.0f || cb > 0.0f)))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "BMR mask: pixel-size coefficients (%g, %g) must be finite, >= 0 and "
      "not both 0",
      (double)ca, (double)cb);
  }
  mrgi_status status = mrgi_bmr_params_validate(params, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_bmr_masks_alloc(out, W, H, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const int depth_on = !isinf(params->depth_threshold);
  const int normal_on = !isinf(params->normal_threshold);
  const int shadow_on = shadow != NULL;
  const float Td = (float)params->depth_threshold;
  const float Tn = (float)params->normal_threshold;
  const int use_min = params->combine == MRGI_BMR_COMBINE_MIN;
  uint8_t* e = out->edge[0];
  for (int32_t y = 0; y < H; ++y)
  {
    for (int32_t x = 0; x < W; ++x)
    {
      const size_t p = (size_t)y * (size_t)W + (size_t)x;
      if (!mrgi_bmr_valid(gbuffer, p))
      {
        continue;
      }
      out->nonempty[0][p] = 1;
      /* The four neighbours: left, right, down, up (inside flags). */
      const int32_t nx[4] = { x - 1, x + 1, x, x };
      const int32_t ny[4] = { y, y, y - 1, y + 1 };
      int inside[4];
      size_t q[4];
      int silhouette = 0, shadow_edge = 0;
      for (int i = 0; i < 4; ++i)
      {
        inside[i] = nx[i] >= 0 && nx[i] < W && ny[i] >= 0 && ny[i] < H;
        q[i] = inside[i] ? (size_t)ny[i] * (size_t)W + (size_t)nx[i] : p;
        const int valid = inside[i] ? mrgi_bmr_valid(gbuffer, q[i]) : 1;
        if (!valid)
        {
          silhouette = 1;
        }
        else if (shadow_on && inside[i] && shadow[q[i]] != shadow[p])
        {
          shadow_edge = 1;
        }
      }
      int depth_edge = silhouette;
      int normal_edge = silhouette;
      if (!silhouette && normal_on)
      {
        /* Clamped central differences: an outside neighbour is p itself. */
        float np[4][3];
        for (int i = 0; i < 4; ++i)
        {
          mrgi_bmr_unit_normal(gbuffer, q[i], np[i]);
        }
        float m = 0.0f;
        for (int c = 0; c < 3; ++c)
        {
          const float dx = fabsf(np[1][c] - np[0][c]);
          const float dy = fabsf(np[3][c] - np[2][c]);
          m = fmaxf(m, fmaxf(dx, dy));
        }
        normal_edge = m * 0.5f >= Tn;
      }
      if (!silhouette && depth_on)
      {
        const float d = -gbuffer->position[4 * p + 2];
        float sum = 0.0f;
        if (inside[0] && inside[1])
        {
          const float dl = -gbuffer->position[4 * q[0] + 2];
          const float dr = -gbuffer->position[4 * q[1] + 2];
          sum += fabsf(dr + dl - 2.0f * d);
        }
        if (inside[2] && inside[3])
        {
          const float dd = -gbuffer->position[4 * q[2] + 2];
          const float du = -gbuffer->position[4 * q[3] + 2];
          sum += fabsf(du + dd - 2.0f * d);
        }
        float s = ca * fabsf(d) + cb;
        s = s > MRGI_MULTIRES_MIN_PIXEL_SIZE ? s : MRGI_MULTIRES_MIN_PIXEL_SIZE;
        depth_edge = sum / s >= Td;
      }
      /* Combine the tests that are on. */
      int any = 0, all = 1, on = 0;
      if (depth_on)
      {
        ++on;
        any |= depth_edge;
        all &= depth_edge;
      }
      if (normal_on)
      {
        ++on;
        any |= normal_edge;
        all &= normal_edge;
      }
      if (shadow_on)
      {
        ++on;
        any |= shadow_edge;
        all &= shadow_edge;
      }
      e[p] = (uint8_t)(on > 0 && (use_min ? all : any));
    }
  }
  for (int k = 1; k < MRGI_BMR_LEVELS; ++k)
  {
    mrgi_bmr_max_down(out->edge[k - 1], out->level_width[k - 1], out->level_height[k - 1],
      out->edge[k], out->level_width[k], out->level_height[k]);
    mrgi_bmr_max_down(out->nonempty[k - 1], out->level_width[k - 1], out->level_height[k - 1],
      out->nonempty[k], out->level_width[k], out->level_height[k]);
  }
  status = mrgi_bmr_finish(out, params, err);
  if (status != MRGI_OK)
  {
    mrgi_bmr_masks_destroy(out);
  }
  return status;
}

mrgi_status mrgi_bmr_mask_from_flags(const mrgi_multires_layout* layout, const uint8_t* flags,
  size_t flags_size, const mrgi_bmr_params* params, mrgi_bmr_masks* out, mrgi_error* err)
{
  if (out)
  {
    memset(out, 0, sizeof(*out));
  }
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BMR mask from flags: out is NULL");
  }
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_multires_check_array(layout, flags, flags_size, 1, "BMR mask flags", err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_bmr_params_validate(params, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_bmr_masks_alloc(out, layout->width, layout->height, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    if (k < layout->level_count)
    {
      for (int32_t y = 0; y < out->level_height[k]; ++y)
      {
        for (int32_t x = 0; x < out->level_width[k]; ++x)
        {
          const uint8_t f = flags[mrgi_multires_index(layout, k, x, y)];
          const size_t t = (size_t)y * (size_t)out->level_width[k] + (size_t)x;
          out->nonempty[k][t] = (f & MRGI_MULTIRES_FLAG_NONEMPTY) ? 1 : 0;
          out->edge[k][t] = (f & MRGI_MULTIRES_FLAG_DISCONTINUOUS) ? 1 : 0;
        }
      }
    }
    else
    {
      mrgi_bmr_max_down(out->edge[k - 1], out->level_width[k - 1], out->level_height[k - 1],
        out->edge[k], out->level_width[k], out->level_height[k]);
      mrgi_bmr_max_down(out->nonempty[k - 1], out->level_width[k - 1], out->level_height[k - 1],
        out->nonempty[k], out->level_width[k], out->level_height[k]);
    }
  }
  status = mrgi_bmr_finish(out, params, err);
  if (status != MRGI_OK)
  {
    mrgi_bmr_masks_destroy(out);
  }
  return status;
}

mrgi_status mrgi_bmr_stats_compute(
  const mrgi_bmr_masks* masks, mrgi_bmr_stats* stats, mrgi_error* err)
{
  if (!masks || !stats || !masks->stencil[0])
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BMR stats: NULL or empty masks");
  }
  memset(stats, 0, sizeof(*stats));
  int64_t total = 0;
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    const size_t n = (size_t)masks->level_width[k] * (size_t)masks->level_height[k];
    stats->texels[k] = (int64_t)n;
    for (size_t t = 0; t < n; ++t)
    {
      stats->stencilled[k] += masks->stencil[k][t];
    }
    total += stats->stencilled[k];
  }
  for (int32_t y = 0; y < masks->height; ++y)
  {
    for (int32_t x = 0; x < masks->width; ++x)
    {
      if (!masks->nonempty[0][(size_t)y * (size_t)masks->width + (size_t)x])
      {
        continue;
      }
      ++stats->valid_pixels;
      for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
      {
        const size_t t = (size_t)(y >> k) * (size_t)masks->level_width[k] + (size_t)(x >> k);
        if (masks->stencil[k][t])
        {
          ++stats->finest_pixels[k];
          break;
        }
      }
    }
  }
  stats->work_fraction =
    stats->valid_pixels > 0 ? (double)total / (double)stats->valid_pixels : 0.0;
  return MRGI_OK;
}
