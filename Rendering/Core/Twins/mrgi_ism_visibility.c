/* ISM shadow lookup: see mrgi_ism_visibility.h (RGK08 3.3, RIHKS11 6.1).
 * Float throughout, in the header's order, as vtkMRGIISMLookup.glsl. */
#include "mrgi_ism_visibility.h"

#include <math.h>

void mrgi_ism_lookup_params_default(mrgi_ism_lookup_params* params)
{
  if (!params)
    return;
  params->relative_bias = MRGI_ISM_DEFAULT_RELATIVE_BIAS;
  params->texel_bias = MRGI_ISM_DEFAULT_TEXEL_BIAS;
  params->pcf = 1;
  params->max_texel_angle = MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE;
}

mrgi_status mrgi_ism_lookup_params_validate(const mrgi_ism_lookup_params* params, mrgi_error* err)
{
  if (!params)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM lookup: NULL parameters");
  if (!(params->relative_bias >= 0.0f && params->relative_bias <= MRGI_ISM_MAX_BIAS))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM lookup: relative bias %g is not in [0, %g]", (double)params->relative_bias,
      (double)MRGI_ISM_MAX_BIAS);
  if (!(params->texel_bias >= 0.0f && params->texel_bias <= MRGI_ISM_MAX_BIAS))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM lookup: texel bias %g is not in [0, %g]", (double)params->texel_bias,
      (double)MRGI_ISM_MAX_BIAS);
  if (!(params->max_texel_angle >= 0.0f && params->max_texel_angle <= MRGI_ISM_MAX_TEXEL_ANGLE_LIMIT))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM lookup: max texel angle %g is not in [0, %g] radians", (double)params->max_texel_angle,
      (double)MRGI_ISM_MAX_TEXEL_ANGLE_LIMIT);
  if (params->pcf != 0 && params->pcf != 1)
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "ISM lookup: pcf flag %d is not 0 or 1", (int)params->pcf);
  return MRGI_OK;
}

static float dot3f(const float a[3], const float b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Step 5's compare of one tile texel (i, j), already clamped to the tile. */
static float texel_visible(const mrgi_ism_atlas_layout* layout, const float* depth,
  int32_t vpl_index, int32_t i, int32_t j, float biased)
{
  const int32_t tile = layout->tile_size;
  const int64_t x = (int64_t)(vpl_index % layout->tiles_per_row) * tile + i;
  const int64_t y = (int64_t)(vpl_index / layout->tiles_per_row) * tile + j;
  return biased <= depth[y * layout->width + x] ? 1.0f : 0.0f;
}

static int32_t clamp_texel(int32_t i, int32_t tile)
{
  return i < 0 ? 0 : (i > tile - 1 ? tile - 1 : i);
}

float mrgi_ism_visibility(const mrgi_ism_atlas_layout* layout, const float* depth,
  int32_t vpl_index, const float vpl_position[3], const float vpl_normal[3],
  const float receiver[3], const mrgi_ism_lookup_params* params)
{
  if (!layout || !depth || !vpl_position || !vpl_normal || !receiver || !params ||
    vpl_index < 0 || vpl_index >= layout->vpl_count || layout->tile_size < 1 ||
    layout->tiles_per_row < 1)
    return 1.0f;
  /* 1. w = x - v, dist = |w|. */
  const float w[3] = { receiver[0] - vpl_position[0], receiver[1] - vpl_position[1],
    receiver[2] - vpl_position[2] };
  const float dist = sqrtf(dot3f(w, w));
  if (!(dist >= (float)MRGI_ISM_MIN_DEPTH) || !isfinite(dist))
    return 1.0f;
  /* 2. d = w / dist; c = d . n (n normalized here as the GLSL's normalize()). */
  const float nlen = sqrtf(dot3f(vpl_normal, vpl_normal));
  if (!(nlen > 0.0f) || !isfinite(nlen))
    return 1.0f;
  const float n[3] = { vpl_normal[0] / nlen, vpl_normal[1] / nlen, vpl_normal[2] / nlen };
  const float d[3] = { w[0] / dist, w[1] / dist, w[2] / dist };
  const float c = dot3f(d, n);
  if (!(c > 0.0f))
    return 1.0f;
  const float tile = (float)layout->tile_size;
  /* 2b. Grazing: the texel is wider than the test trusts. */
  if (params->max_texel_angle > 0.0f && 2.0f / (tile * c) > params->max_texel_angle)
    return 1.0f;
  /* 3. Cos-sphere tile coordinates (RIHKS11 6.1), the frame of
   * mrgi_ism_vpl_frame() / mrgiISMFrame() in float. */
  const float sign = n[2] >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sign + n[2]);
  const float bxy = n[0] * n[1] * a;
  const float t[3] = { 1.0f + sign * n[0] * n[0] * a, sign * bxy, -sign * n[0] };
  const float b[3] = { bxy, sign + n[1] * n[1] * a, -n[1] };
  const float u = (dot3f(d, t) + 1.0f) * 0.5f * tile;
  const float v = (dot3f(d, b) + 1.0f) * 0.5f * tile;
  /* 4. Bias (RGK08 3.3): relative part plus texel footprints at this angle. */
  const float bias = dist *
    (params->relative_bias +
      params->texel_bias * 2.0f / (tile * fmaxf(c, MRGI_ISM_BIAS_MIN_COS)));
  const float biased = dist - bias;
  /* 5. One texel, or 2x2 bilinear PCF clamped to the tile. */
  const int32_t T = layout->tile_size;
  if (!params->pcf)
    return texel_visible(layout, depth, vpl_index, clamp_texel((int32_t)floorf(u), T),
      clamp_texel((int32_t)floorf(v), T), biased);
  const float uc = u - 0.5f;
  const float vc = v - 0.5f;
  const float fi = floorf(uc);
  const float fj = floorf(vc);
  const float fu = uc - fi;
  const float fv = vc - fj;
  const int32_t i0 = clamp_texel((int32_t)fi, T);
  const int32_t j0 = clamp_texel((int32_t)fj, T);
  const int32_t i1 = clamp_texel((int32_t)fi + 1, T);
  const int32_t j1 = clamp_texel((int32_t)fj + 1, T);
  const float v00 = texel_visible(layout, depth, vpl_index, i0, j0, biased);
  const float v10 = texel_visible(layout, depth, vpl_index, i1, j0, biased);
  const float v01 = texel_visible(layout, depth, vpl_index, i0, j1, biased);
  const float v11 = texel_visible(layout, depth, vpl_index, i1, j1, biased);
  /* Lerps as a + (b - a) f: exactly 1 (0) when all four are 1 (0). */
  const float h0 = v00 + (v10 - v00) * fu;
  const float h1 = v01 + (v11 - v01) * fu;
  return h0 + (h1 - h0) * fv;
}
