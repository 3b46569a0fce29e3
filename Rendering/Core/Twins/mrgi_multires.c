#include "mrgi_multires.h"

#include "mrgi_buffers.h"
#include "mrgi_image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

mrgi_status mrgi_multires_layout_init(mrgi_multires_layout* layout, int32_t width,
                                      int32_t height, int32_t coarsest_side, mrgi_error* err)
{
  if (!layout)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "multires layout pointer is NULL");
  }
  memset(layout, 0, sizeof(*layout));
  if (width < 1 || width > MRGI_IMAGE_MAX_DIMENSION || height < 1 ||
      height > MRGI_IMAGE_MAX_DIMENSION)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "multires buffer size %d x %d is outside 1..%d per side", width, height,
                          MRGI_IMAGE_MAX_DIMENSION);
  }
  if (coarsest_side < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "coarsest level side %d must be >= 1 (default %d)", coarsest_side,
                          MRGI_MULTIRES_DEFAULT_COARSEST_SIDE);
  }
  int32_t w = width;
  int32_t h = height;
  int32_t offset = 0;
  int32_t level = 0;
  for (;;)
  {
    layout->level_width[level] = w;
    layout->level_height[level] = h;
    layout->level_offset[level] = offset;
    offset += w;
    if ((w <= coarsest_side && h <= coarsest_side) || level + 1 == MRGI_MULTIRES_MAX_LEVELS)
    {
      break; /* the second test never fires: 2^20 pixels are 1 x 1 at level 20 */
    }
    w = (w + 1) / 2; /* ceil(w / 2) == ceil(W / 2^(level+1)) */
    h = (h + 1) / 2;
    ++level;
  }
  layout->width = width;
  layout->height = height;
  layout->coarsest_side = coarsest_side;
  layout->level_count = level + 1;
  layout->total_width = offset;
  layout->total_height = height;
  return MRGI_OK;
}

int64_t mrgi_multires_texel_count(const mrgi_multires_layout* layout)
{
  if (!layout || layout->total_width < 1 || layout->total_height < 1)
  {
    return 0;
  }
  return (int64_t)layout->total_width * (int64_t)layout->total_height;
}

int mrgi_multires_locate(const mrgi_multires_layout* layout, int32_t flat_x, int32_t flat_y,
                         int32_t* level, int32_t* x, int32_t* y)
{
  if (!layout || flat_x < 0 || flat_y < 0 || flat_x >= layout->total_width ||
      flat_y >= layout->total_height)
  {
    return 0;
  }
  for (int32_t i = 0; i < layout->level_count; ++i)
  {
    const int32_t local_x = flat_x - layout->level_offset[i];
    if (local_x >= 0 && local_x < layout->level_width[i])
    {
      if (flat_y >= layout->level_height[i])
      {
        return 0;
      }
      if (level)
      {
        *level = i;
      }
      if (x)
      {
        *x = local_x;
      }
      if (y)
      {
        *y = flat_y;
      }
      return 1;
    }
  }
  return 0;
}

mrgi_status mrgi_multires_pixel_size_coefficients(const mrgi_multires_projection* projection,
                                                  int32_t height, float coefficients[2],
                                                  mrgi_error* err)
{
  if (!projection || !coefficients)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s is NULL",
                          !projection ? "projection" : "pixel size coefficients");
  }
  if (height < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "image height %d must be >= 1",
                          height);
  }
  if (projection->parallel)
  {
    const double scale = projection->parallel_scale;
    if (!(scale > 0.0) || !isfinite(scale) || !isfinite((float)(2.0 * scale / height)) ||
        !((float)(2.0 * scale / height) > 0.0f))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "parallel scale %g must be finite and > 0 (and its pixel size "
                            "representable as a float)",
                            scale);
    }
    coefficients[0] = 0.0f;
    coefficients[1] = (float)(2.0 * scale / height);
    return MRGI_OK;
  }
  const double angle = projection->view_angle_deg;
  if (!(angle > 0.0 && angle < 180.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "perspective view angle %g degrees is outside (0, 180)", angle);
  }
  const double a = 2.0 * tan(angle * (MRGI_PI / 360.0)) / height;
  if (!((float)a > 0.0f) || !isfinite((float)a))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "view angle %g degrees over %d rows gives a pixel size factor %g "
                          "that a float cannot hold",
                          angle, height, a);
  }
  coefficients[0] = (float)a;
  coefficients[1] = 0.0f;
  return MRGI_OK;
}

void mrgi_multires_mipmap_destroy(mrgi_multires_mipmap* mipmap)
{
  if (!mipmap)
  {
    return;
  }
  for (int k = 0; k < MRGI_MULTIRES_TEX_COUNT; ++k)
  {
    free(mipmap->texture[k]);
  }
  memset(mipmap, 0, sizeof(*mipmap));
}

mrgi_status mrgi_multires_layout_check(const mrgi_multires_layout* layout, mrgi_error* err)
{
  if (!layout)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "multires layout is NULL");
  }
  mrgi_multires_layout expected;
  if (mrgi_multires_layout_init(&expected, layout->width, layout->height, layout->coarsest_side,
                                NULL) != MRGI_OK ||
      memcmp(&expected, layout, sizeof(expected)) != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "multires layout was not made by mrgi_multires_layout_init() "
                          "(or was modified)");
  }
  return MRGI_OK;
}

static int mrgi_is_finite_float(float v)
{
  return isfinite(v);
}

/* s(d) = max(a |d| + b, FLT_MIN), as the GLSL writes it. */
static float mrgi_pixel_size(const float ab[2], float d)
{
  const float s = ab[0] * fabsf(d) + ab[1];
  return s > MRGI_MULTIRES_MIN_PIXEL_SIZE ? s : MRGI_MULTIRES_MIN_PIXEL_SIZE;
}

static int32_t mrgi_clamp_i32(int32_t v, int32_t lo, int32_t hi)
{
  return v < lo ? lo : (v > hi ? hi : v);
}

mrgi_status mrgi_multires_mipmap_build(const mrgi_multires_layout* layout,
                                       const mrgi_gather_receivers* gbuffer,
                                       const float pixel_size_coefficients[2],
                                       mrgi_multires_mipmap* out, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output mipmap is NULL");
  }
  memset(out, 0, sizeof(*out));
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!gbuffer || !gbuffer->position || !gbuffer->normal)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "G-buffer %s is NULL",
                          !gbuffer ? "pointer" : (!gbuffer->position ? "position array"
                                                                     : "normal array"));
  }
  if (gbuffer->width != layout->width || gbuffer->height != layout->height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "G-buffer is %d x %d but the multires layout is for %d x %d",
                          gbuffer->width, gbuffer->height, layout->width, layout->height);
  }
  if (!pixel_size_coefficients)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "pixel size coefficients are NULL");
  }
  const float* ab = pixel_size_coefficients;
  if (!mrgi_is_finite_float(ab[0]) || !mrgi_is_finite_float(ab[1]) || ab[0] < 0.0f ||
      ab[1] < 0.0f || (ab[0] == 0.0f && ab[1] == 0.0f))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "pixel size coefficients (%g, %g) must be finite, >= 0 and not both 0 "
                          "(mrgi_multires_pixel_size_coefficients())",
                          (double)ab[0], (double)ab[1]);
  }
  const size_t texels = (size_t)mrgi_multires_texel_count(layout);
  for (int k = 0; k < MRGI_MULTIRES_TEX_COUNT; ++k)
  {
    out->texture[k] = (float*)calloc(texels * 4, sizeof(float));
    if (!out->texture[k])
    {
      mrgi_multires_mipmap_destroy(out);
      return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                            "cannot allocate a %d x %d RGBA float mipmap texture",
                            layout->total_width, layout->total_height);
    }
  }
  out->layout = *layout;
  float* depth = out->texture[MRGI_MULTIRES_TEX_DEPTH];
  float* nmin = out->texture[MRGI_MULTIRES_TEX_NORMAL_MIN];
  float* nmax = out->texture[MRGI_MULTIRES_TEX_NORMAL_MAX];
  const int32_t W = layout->width;
  const int32_t H = layout->height;

  /* Level 0, pass 1: validity, depth, unit normal (g filled by pass 2). */
  for (int32_t y = 0; y < H; ++y)
  {
    for (int32_t x = 0; x < W; ++x)
    {
      const size_t p = (size_t)y * (size_t)W + (size_t)x;
      const float* P = gbuffer->position + 4 * p;
      const float* N = gbuffer->normal + 4 * p;
      const size_t t = 4 * mrgi_multires_index(layout, 0, x, y);
      const int valid = P[3] > MRGI_GBUFFER_VALID_THRESHOLD && mrgi_is_finite_float(P[2]) &&
                        mrgi_is_finite_float(N[0]) && mrgi_is_finite_float(N[1]) &&
                        mrgi_is_finite_float(N[2]);
      if (!valid)
      {
        depth[t + 0] = MRGI_MULTIRES_FLT_MAX;
        depth[t + 1] = -MRGI_MULTIRES_FLT_MAX;
        depth[t + 2] = 0.0f;
        depth[t + 3] = (float)MRGI_MULTIRES_INVALID_BIT;
        for (int c = 0; c < 3; ++c)
        {
          nmin[t + c] = MRGI_MULTIRES_FLT_MAX;
          nmax[t + c] = -MRGI_MULTIRES_FLT_MAX;
        }
        continue;
      }
      const float d = -P[2];
      float length2 = N[0] * N[0] + N[1] * N[1] + N[2] * N[2];
      if (!(length2 > MRGI_MULTIRES_MIN_PIXEL_SIZE))
      {
        length2 = MRGI_MULTIRES_MIN_PIXEL_SIZE;
      }
      const float inverse_length = 1.0f / sqrtf(length2);
      depth[t + 0] = d;
      depth[t + 1] = d;
      depth[t + 2] = 0.0f;
      depth[t + 3] = (float)MRGI_MULTIRES_VALID_BIT;
      for (int c = 0; c < 3; ++c)
      {
        const float n = N[c] * inverse_length;
        nmin[t + c] = n;
        nmax[t + c] = n;
      }
    }
  }
  /* Level 0, pass 2: depth derivative g over the depth-valid 8-neighbours (NPW10 3.2). */
  for (int32_t y = 0; y < H; ++y)
  {
    for (int32_t x = 0; x < W; ++x)
    {
      const size_t t = 4 * mrgi_multires_index(layout, 0, x, y);
      if (depth[t + 3] != (float)MRGI_MULTIRES_VALID_BIT)
      {
        continue;
      }
      const float dp = depth[t];
      float g = 0.0f;
      for (int32_t dy = -1; dy <= 1; ++dy)
      {
        for (int32_t dx = -1; dx <= 1; ++dx)
        {
          const int32_t qx = mrgi_clamp_i32(x + dx, 0, W - 1);
          const int32_t qy = mrgi_clamp_i32(y + dy, 0, H - 1);
          /* The neighbour's depth straight from the G-buffer: its flag and
           * depth decide, not its normal (one texture read per neighbour on
           * the GPU instead of two). */
          const float* Q = gbuffer->position + 4 * ((size_t)qy * (size_t)W + (size_t)qx);
          if (!(Q[3] > MRGI_GBUFFER_VALID_THRESHOLD && mrgi_is_finite_float(Q[2])))
          {
            continue;
          }
          const float dq = -Q[2];
          const float s = mrgi_pixel_size(ab, fminf(fabsf(dp), fabsf(dq)));
          float slope = fabsf(dq - dp) / s;
          if (!(slope <= MRGI_MULTIRES_FLT_MAX))
          {
            slope = MRGI_MULTIRES_FLT_MAX; /* overflow to +inf */
          }
          g = fmaxf(g, slope);
        }
      }
      depth[t + 2] = g;
    }
  }
  /* Levels 1..L: 2x2 reduction of the children (clamped). */
  for (int32_t i = 1; i < layout->level_count; ++i)
  {
    const int32_t cw = layout->level_width[i - 1];
    const int32_t ch = layout->level_height[i - 1];
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        float a[4] = { MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX, 0.0f, 0.0f };
        float lo[3] = { MRGI_MULTIRES_FLT_MAX, MRGI_MULTIRES_FLT_MAX, MRGI_MULTIRES_FLT_MAX };
        float hi[3] = { -MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX };
        int bits = 0;
        for (int32_t b = 0; b < 2; ++b)
        {
          for (int32_t c = 0; c < 2; ++c)
          {
            const int32_t cx = mrgi_clamp_i32(2 * x + c, 0, cw - 1);
            const int32_t cy = mrgi_clamp_i32(2 * y + b, 0, ch - 1);
            const size_t s = 4 * mrgi_multires_index(layout, i - 1, cx, cy);
            a[0] = fminf(a[0], depth[s + 0]);
            a[1] = fmaxf(a[1], depth[s + 1]);
            a[2] = fmaxf(a[2], depth[s + 2]);
            bits |= (int)depth[s + 3];
            for (int k = 0; k < 3; ++k)
            {
              lo[k] = fminf(lo[k], nmin[s + k]);
              hi[k] = fmaxf(hi[k], nmax[s + k]);
            }
          }
        }
        const size_t t = 4 * mrgi_multires_index(layout, i, x, y);
        depth[t + 0] = a[0];
        depth[t + 1] = a[1];
        depth[t + 2] = a[2];
        depth[t + 3] = (float)bits;
        for (int k = 0; k < 3; ++k)
        {
          nmin[t + k] = lo[k];
          nmax[t + k] = hi[k];
        }
      }
    }
  }
  return MRGI_OK;
}

void mrgi_multires_params_default(mrgi_multires_params* params)
{
  if (!params)
  {
    return;
  }
  params->depth_threshold = MRGI_MULTIRES_DEFAULT_DEPTH_THRESHOLD;
  params->normal_threshold = MRGI_MULTIRES_DEFAULT_NORMAL_THRESHOLD;
  params->finest_level = 0;
  params->balance = 1;
}

float mrgi_multires_threshold_uniform(double threshold)
{
  if (!(threshold >= 0.0) || !isfinite(threshold))
  {
    return MRGI_MULTIRES_THRESHOLD_OFF;
  }
  const float t = (float)threshold;
  return isfinite(t) ? t : MRGI_MULTIRES_THRESHOLD_OFF; /* above FLT_MAX: nothing reaches it */
}

mrgi_status mrgi_multires_params_validate(const mrgi_multires_params* params,
                                          const mrgi_multires_layout* layout, mrgi_error* err)
{
  if (!params || !layout)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "multires %s is NULL",
                          !params ? "parameters" : "layout");
  }
  if (!(params->depth_threshold >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "depth threshold %g must be >= 0 (+inf turns the test off)",
                          params->depth_threshold);
  }
  if (!(params->normal_threshold >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "normal threshold %g must be >= 0 (+inf turns the test off)",
                          params->normal_threshold);
  }
  if (params->finest_level < 0 || params->finest_level >= layout->level_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "finest level %d is outside 0..%d (this %d x %d buffer has %d levels)",
                          params->finest_level, layout->level_count - 1, layout->width,
                          layout->height, layout->level_count);
  }
  if (params->balance != 0 && params->balance != 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "balance flag %d must be 0 or 1",
                          params->balance);
  }
  return MRGI_OK;
}

mrgi_status mrgi_multires_check_array(const mrgi_multires_layout* layout, const void* array,
                                      size_t count, size_t per_texel, const char* what,
                                      mrgi_error* err)
{
  const uint64_t needed = (uint64_t)mrgi_multires_texel_count(layout) * (uint64_t)per_texel;
  if (!array)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s is NULL", what);
  }
  if ((uint64_t)count < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s holds %zu values but the %d x %d flattened layout needs %llu",
                          what, count, layout->total_width, layout->total_height,
                          (unsigned long long)needed);
  }
  return MRGI_OK;
}

static mrgi_status mrgi_multires_check_buffer(const mrgi_multires_layout* layout,
                                              const void* buffer, size_t size, const char* what,
                                              mrgi_error* err)
{
  return mrgi_multires_check_array(layout, buffer, size, 1, what, err);
}

/* D of level i texel (x, y) (section 3); `t_depth`, `t_normal` are the
 * shader uniforms (< 0: off). */
static int mrgi_multires_discontinuous(const mrgi_multires_mipmap* mipmap, int32_t i, int32_t x,
                                       int32_t y, float t_depth, float t_normal)
{
  const mrgi_multires_layout* layout = &mipmap->layout;
  const float* depth = mipmap->texture[MRGI_MULTIRES_TEX_DEPTH];
  const float* nmin = mipmap->texture[MRGI_MULTIRES_TEX_NORMAL_MIN];
  const float* nmax = mipmap->texture[MRGI_MULTIRES_TEX_NORMAL_MAX];
  const int bits = (int)depth[4 * mrgi_multires_index(layout, i, x, y) + 3];
  if (!(bits & MRGI_MULTIRES_VALID_BIT))
  {
    return 0;
  }
  float g = 0.0f;
  float lo[3] = { MRGI_MULTIRES_FLT_MAX, MRGI_MULTIRES_FLT_MAX, MRGI_MULTIRES_FLT_MAX };
  float hi[3] = { -MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX };
  const int32_t w = layout->level_width[i];
  const int32_t h = layout->level_height[i];
  for (int32_t dy = -1; dy <= 1; ++dy)
  {
    for (int32_t dx = -1; dx <= 1; ++dx)
    {
      const size_t s = 4 * mrgi_multires_index(layout, i, mrgi_clamp_i32(x + dx, 0, w - 1),
                                               mrgi_clamp_i32(y + dy, 0, h - 1));
      g = fmaxf(g, depth[s + 2]);
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = fminf(lo[k], nmin[s + k]);
        hi[k] = fmaxf(hi[k], nmax[s + k]);
      }
    }
  }
  const int mixed = (bits & MRGI_MULTIRES_INVALID_BIT) != 0;
  if (t_depth >= 0.0f && (mixed || g >= t_depth))
  {
    return 1;
  }
  if (t_normal >= 0.0f)
  {
    const float spread = fmaxf(fmaxf(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
    if (spread >= t_normal)
    {
      return 1;
    }
  }
  return 0;
}

mrgi_status mrgi_multires_flags_compute(const mrgi_multires_mipmap* mipmap,
                                        const mrgi_multires_params* params, uint8_t* flags,
                                        size_t flags_size, mrgi_error* err)
{
  if (!mipmap)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mipmap is NULL");
  }
  const mrgi_multires_layout* layout = &mipmap->layout;
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  for (int k = 0; k < MRGI_MULTIRES_TEX_COUNT; ++k)
  {
    if (!mipmap->texture[k])
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "mipmap texture %d is NULL (not built or destroyed)", k);
    }
  }
  status = mrgi_multires_params_validate(params, layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_multires_check_buffer(layout, flags, flags_size, "flags", err);
  if (status != MRGI_OK)
  {
    return status;
  }
  memset(flags, 0, (size_t)mrgi_multires_texel_count(layout));
  const float t_depth = mrgi_multires_threshold_uniform(params->depth_threshold);
  const float t_normal = mrgi_multires_threshold_uniform(params->normal_threshold);
  const float* depth = mipmap->texture[MRGI_MULTIRES_TEX_DEPTH];
  const int32_t f = params->finest_level;
  for (int32_t i = 0; i < layout->level_count; ++i)
  {
    const int32_t w = layout->level_width[i];
    const int32_t h = layout->level_height[i];
    for (int32_t y = 0; y < h; ++y)
    {
      for (int32_t x = 0; x < w; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        const int bits = (int)depth[4 * t + 3];
        if (!(bits & MRGI_MULTIRES_VALID_BIT))
        {
          continue; /* EMPTY: all flags 0 */
        }
        int flag = MRGI_MULTIRES_FLAG_NONEMPTY;
        if (bits & MRGI_MULTIRES_INVALID_BIT)
        {
          flag |= MRGI_MULTIRES_FLAG_MIXED;
        }
        const int discontinuous = mrgi_multires_discontinuous(mipmap, i, x, y, t_depth, t_normal);
        if (discontinuous)
        {
          flag |= MRGI_MULTIRES_FLAG_DISCONTINUOUS;
        }
        int refine = 0;
        if (i == f)
        {
          refine = discontinuous;
        }
        else if (i > f)
        {
          refine = discontinuous;
          /* Children (2x..2x+1) or, with balance, children plus ring (2x-1..2x+2). */
          const int32_t reach_lo = params->balance ? -1 : 0;
          const int32_t reach_hi = params->balance ? 2 : 1;
          const int32_t cw = layout->level_width[i - 1];
          const int32_t ch = layout->level_height[i - 1];
          for (int32_t b = reach_lo; b <= reach_hi && !refine; ++b)
          {
            for (int32_t c = reach_lo; c <= reach_hi && !refine; ++c)
            {
              const size_t s =
                mrgi_multires_index(layout, i - 1, mrgi_clamp_i32(2 * x + c, 0, cw - 1),
                                    mrgi_clamp_i32(2 * y + b, 0, ch - 1));
              refine = (flags[s] & MRGI_MULTIRES_FLAG_REFINE) != 0;
            }
          }
        }
        if (refine)
        {
          flag |= MRGI_MULTIRES_FLAG_REFINE;
        }
        flags[t] = (uint8_t)flag;
      }
    }
  }
  return MRGI_OK;
}

static mrgi_status mrgi_multires_check_select(const mrgi_multires_layout* layout,
                                              const uint8_t* flags, size_t flags_size,
                                              int32_t finest_level, uint8_t* mask,
                                              size_t mask_size, mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status == MRGI_OK)
  {
    status = mrgi_multires_check_buffer(layout, flags, flags_size, "flags", err);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_multires_check_buffer(layout, mask, mask_size, "selection mask", err);
  }
  if (status == MRGI_OK && (finest_level < 0 || finest_level >= layout->level_count))
  {
    status = mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "finest level %d is outside 0..%d", finest_level,
                            layout->level_count - 1);
  }
  return status;
}

mrgi_status mrgi_multires_select_one_pass(const mrgi_multires_layout* layout,
                                          const uint8_t* flags, size_t flags_size,
                                          int32_t finest_level, uint8_t* mask, size_t mask_size,
                                          mrgi_error* err)
{
  const mrgi_status status =
    mrgi_multires_check_select(layout, flags, flags_size, finest_level, mask, mask_size, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  memset(mask, 0, (size_t)mrgi_multires_texel_count(layout));
  const int32_t coarsest = layout->level_count - 1;
  for (int32_t i = finest_level; i <= coarsest; ++i)
  {
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        const int flag = flags[t];
        int selected = (flag & MRGI_MULTIRES_FLAG_NONEMPTY) &&
                       (i == finest_level || !(flag & MRGI_MULTIRES_FLAG_REFINE));
        if (selected && i < coarsest)
        {
          const int parent = flags[mrgi_multires_index(layout, i + 1, x / 2, y / 2)];
          selected = (parent & MRGI_MULTIRES_FLAG_REFINE) != 0;
        }
        mask[t] = (uint8_t)(selected ? 1 : 0);
      }
    }
  }
  return MRGI_OK;
}

/* A patch of the iterative refinement: level texel (x, y). */
typedef struct mrgi_multires_patch
{
  int32_t level;
  int32_t x;
  int32_t y;
} mrgi_multires_patch;

mrgi_status mrgi_multires_select_iterative(const mrgi_multires_layout* layout,
                                           const uint8_t* flags, size_t flags_size,
                                           int32_t finest_level, uint8_t* mask, size_t mask_size,
                                           mrgi_error* err)
{
  const mrgi_status status =
    mrgi_multires_check_select(layout, flags, flags_size, finest_level, mask, mask_size, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  /* Two lists, each as long as the largest level a list can hold. */
  const size_t capacity = (size_t)layout->level_width[finest_level] *
                          (size_t)layout->level_height[finest_level];
  mrgi_multires_patch* current =
    (mrgi_multires_patch*)malloc(2 * capacity * sizeof(mrgi_multires_patch));
  if (!current)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "cannot allocate %zu refinement patches",
                          2 * capacity);
  }
  mrgi_multires_patch* next = current + capacity;
  memset(mask, 0, (size_t)mrgi_multires_texel_count(layout));

  /* CoarseImageSampling(): every non-empty coarsest texel. */
  const int32_t coarsest = layout->level_count - 1;
  size_t count = 0;
  for (int32_t y = 0; y < layout->level_height[coarsest]; ++y)
  {
    for (int32_t x = 0; x < layout->level_width[coarsest]; ++x)
    {
      if (flags[mrgi_multires_index(layout, coarsest, x, y)] & MRGI_MULTIRES_FLAG_NONEMPTY)
      {
        const mrgi_multires_patch patch = { coarsest, x, y };
        current[count++] = patch;
      }
    }
  }
  /* Refinement passes: keep a patch, or replace it by its non-empty children. */
  while (count > 0)
  {
    size_t next_count = 0;
    for (size_t k = 0; k < count; ++k)
    {
      const mrgi_multires_patch p = current[k];
      const size_t t = mrgi_multires_index(layout, p.level, p.x, p.y);
      if (p.level == finest_level || !(flags[t] & MRGI_MULTIRES_FLAG_REFINE))
      {
        mask[t] = 1;
        continue;
      }
      const int32_t child_level = p.level - 1;
      for (int32_t b = 0; b < 2; ++b)
      {
        for (int32_t c = 0; c < 2; ++c)
        {
          const int32_t cx = 2 * p.x + c;
          const int32_t cy = 2 * p.y + b;
          if (cx >= layout->level_width[child_level] || cy >= layout->level_height[child_level])
          {
            continue; /* NPOT edge: this child does not exist */
          }
          if (flags[mrgi_multires_index(layout, child_level, cx, cy)] &
              MRGI_MULTIRES_FLAG_NONEMPTY)
          {
            const mrgi_multires_patch child = { child_level, cx, cy };
            next[next_count++] = child;
          }
        }
      }
    }
    mrgi_multires_patch* swap = current;
    current = next;
    next = swap;
    count = next_count;
  }
  free(current < next ? current : next);
  return MRGI_OK;
}

mrgi_status mrgi_multires_stats_compute(const mrgi_multires_layout* layout, const uint8_t* flags,
                                        size_t flags_size, const uint8_t* mask, size_t mask_size,
                                        mrgi_multires_stats* stats, mrgi_error* err)
{
  if (!stats)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "statistics pointer is NULL");
  }
  memset(stats, 0, sizeof(*stats));
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status == MRGI_OK)
  {
    status = mrgi_multires_check_buffer(layout, flags, flags_size, "flags", err);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_multires_check_buffer(layout, mask, mask_size, "selection mask", err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  for (int32_t i = 0; i < layout->level_count; ++i)
  {
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        if (mask[t])
        {
          ++stats->selected[i];
        }
        if (i == 0 && (flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY))
        {
          ++stats->valid_pixels;
        }
      }
    }
    stats->selected_total += stats->selected[i];
  }
  stats->work_fraction =
    stats->valid_pixels > 0 ? (double)stats->selected_total / (double)stats->valid_pixels : 0.0;
  return MRGI_OK;
}

/* Chosen from the frontier measured by Testing/Benchmarks/multires_sweep.py
 * on the Cornell box (spot) at 1024 x 1024, 256 VPLs, grid depth threshold
 * {4, 16, 64, off} x normal threshold {0.25, 0.5, 1} x finest level {0, 1} x
 * refinement {geometry, illumination T 0.1, 0.15, 0.2}
 * (Documentation/Multiresolution.md). Relative RMS against the full gather
 * and share of its work gathered:
 *   accurate (16, 0.5, 0, T 0.1):  ~1.0%, ~12%  -- more accurate than any
 *                          geometric setting (best 1.90% at 22.5%);
 *   balanced (16, 0.5, 0, T 0.15): ~1.6%, ~9%   -- the geometric balanced
 *                          (4, 1, 0) is 2.27% at 22.3%: the depth-derivative
 *                          test refines every grazing wall, the illumination
 *                          rule only where the light changes;
 *   fast     (16, 0.5, 1): 4.29%, 3.3% -- the gather ~16x cheaper, for interaction.
 * The area lights keep the geometric presets' thresholds (balanced (4, 1),
 * accurate (4, 0.25)): at (16, 0.5) the living room's per-pixel error
 * against its ground truth rose from 0.085 to 0.097 (256^2, incremental
 * visibility), since shadows change at the depth edges that test finds.
 * Errors and work shares do not depend on the machine; times do. */
static const struct
{
  const char* name;
  double depth_threshold;
  double normal_threshold;
  int32_t finest_level;
  double illumination_threshold; /* INFINITY: geometry alone */
  double area_depth_threshold;   /* the area lights' (the geometric presets' own) */
  double area_normal_threshold;
} mrgi_multires_presets[MRGI_MULTIRES_PRESET_COUNT] = {
  { "fast", 16.0, 0.5, 1, INFINITY, 16.0, 0.5 },
  { "balanced", 16.0, 0.5, 0, 0.15, 4.0, 1.0 },
  { "accurate", 16.0, 0.5, 0, 0.1, 4.0, 0.25 },
};

static mrgi_status mrgi_multires_preset_check(
  int32_t preset, const void* out, const char* what, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "multires preset: %s is NULL", what);
  }
  if (preset < 0 || preset >= MRGI_MULTIRES_PRESET_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "multires preset: unknown preset %d (0 fast, 1 balanced, 2 accurate)", (int)preset);
  }
  return MRGI_OK;
}

mrgi_status mrgi_multires_preset_params(
  int32_t preset, mrgi_multires_params* params, mrgi_error* err)
{
  const mrgi_status status = mrgi_multires_preset_check(preset, params, "params", err);
  if (status != MRGI_OK)
  {
    return status;
  }
  mrgi_multires_params_default(params);
  params->depth_threshold = mrgi_multires_presets[preset].depth_threshold;
  params->normal_threshold = mrgi_multires_presets[preset].normal_threshold;
  params->finest_level = mrgi_multires_presets[preset].finest_level;
  return MRGI_OK;
}

mrgi_status mrgi_multires_preset_area_light_params(int32_t preset, mrgi_multires_params* params,
                                                   mrgi_error* err)
{
  const mrgi_status status = mrgi_multires_preset_params(preset, params, err);
  if (status == MRGI_OK)
  {
    params->depth_threshold = mrgi_multires_presets[preset].area_depth_threshold;
    params->normal_threshold = mrgi_multires_presets[preset].area_normal_threshold;
  }
  return status;
}

mrgi_status mrgi_multires_preset_illumination_threshold(
  int32_t preset, double* threshold, mrgi_error* err)
{
  const mrgi_status status = mrgi_multires_preset_check(preset, threshold, "threshold", err);
  if (status == MRGI_OK)
  {
    *threshold = mrgi_multires_presets[preset].illumination_threshold;
  }
  return status;
}

const char* mrgi_multires_preset_name(int32_t preset)
{
  return (preset >= 0 && preset < MRGI_MULTIRES_PRESET_COUNT) ? mrgi_multires_presets[preset].name : NULL;
}
