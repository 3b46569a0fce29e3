#include "mrgi_incremental_stencil.h"

#include "mrgi_buffers.h"
#include "mrgi_visibility_pyramid.h"

#include <math.h>
#include <string.h>

/* A receiver texel (mrgi_multires_receivers.h): w above the threshold, xyz finite. */
static int mrgi_stencil_receiver(const float* position, size_t t)
{
  const float* P = position + 4 * t;
  return P[3] > MRGI_GBUFFER_VALID_THRESHOLD && isfinite(P[0]) && isfinite(P[1]) &&
         isfinite(P[2]);
}

/* F_level(x, y) of the file comment: the bit-count metric over the 3x3
 * level-`level` texels around (x, y), clamped, non-receivers skipped. */
static int mrgi_stencil_discontinuity(const mrgi_multires_layout* layout, int32_t level,
                                      int32_t x, int32_t y, const float* position,
                                      const uint32_t* masks, int32_t words, int32_t metric_kind,
                                      int32_t threshold)
{
  const uint32_t* neighbours[MRGI_VOXEL_NEIGHBOURS];
  int k = 0;
  for (int32_t dy = -1; dy <= 1; ++dy)
  {
    for (int32_t dx = -1; dx <= 1; ++dx)
    {
      const size_t t = mrgi_multires_clamped_index(layout, level, x, y, dx, dy);
      neighbours[k++] = mrgi_stencil_receiver(position, t) ? masks + t * (size_t)words : NULL;
    }
  }
  mrgi_voxel_metric metric;
  mrgi_voxel_neighbourhood_metric(neighbours, words, &metric);
  return mrgi_voxel_needs_refinement(&metric, metric_kind, threshold);
}

mrgi_status mrgi_incremental_stencil_build(
  const mrgi_multires_layout* layout, int32_t finest_level, const uint8_t* flags,
  const uint8_t* selection, size_t texel_bytes, const float* receiver_position,
  size_t receiver_floats, const uint32_t* masks, int32_t words, size_t mask_words,
  int32_t metric_kind, int32_t threshold, uint8_t* rendered, size_t rendered_size,
  mrgi_incremental_stencil_stats* stats, mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t texels = (size_t)mrgi_multires_texel_count(layout);
  if ((status = mrgi_multires_check_array(layout, flags, texel_bytes, 1, "flags", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, selection, texel_bytes, 1, "selection", err)) !=
        MRGI_OK ||
      (status = mrgi_multires_check_array(layout, receiver_position, receiver_floats, 4,
                                          "receiver positions", err)) != MRGI_OK)
  {
    return status;
  }
  if (words < 1 || words > MRGI_VOXEL_MAX_MASK_WORDS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mask words %d is outside 1..%d", words,
                          MRGI_VOXEL_MAX_MASK_WORDS);
  }
  if ((status = mrgi_multires_check_array(layout, masks, mask_words, (size_t)words, "masks",
                                          err)) != MRGI_OK)
  {
    return status;
  }
  if (metric_kind != MRGI_VOXEL_METRIC_DISAGREE && metric_kind != MRGI_VOXEL_METRIC_COUNT_SPREAD)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "refinement metric %d is unknown",
                          metric_kind);
  }
  if (threshold < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "refinement threshold %d is negative",
                          threshold);
  }
  if (finest_level < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "finest level %d is negative",
                          finest_level);
  }
  if ((status = mrgi_multires_check_array(layout, rendered, rendered_size, 1, "output mask",
                                          err)) != MRGI_OK)
  {
    return status;
  }
  const int32_t coarsest = layout->level_count - 1;
  const int32_t finest = finest_level < coarsest ? finest_level : coarsest;
  mrgi_incremental_stencil_stats counts;
  memset(&counts, 0, sizeof(counts));
  memset(rendered, 0, texels);
  for (int32_t i = finest; i <= coarsest; ++i)
  {
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        if (!(flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY))
        {
          continue;
        }
        if (selection[t])
        {
          rendered[t] = 1;
          ++counts.selected[i];
          continue;
        }
        const int refined = i != finest && (flags[t] & MRGI_MULTIRES_FLAG_REFINE);
        if (i < coarsest && !refined &&
            mrgi_stencil_discontinuity(layout, i + 1, x / 2, y / 2, receiver_position, masks, words,
                                       metric_kind, threshold))
        {
          rendered[t] = 1;
          ++counts.added[i];
        }
      }
    }
    counts.rendered_total += counts.selected[i] + counts.added[i];
  }
  if (stats)
  {
    *stats = counts;
  }
  return MRGI_OK;
}

/* usable_j(t): rendered at level j and a receiver. */
static int mrgi_stencil_usable(const float* position, const uint8_t* rendered, size_t t)
{
  return rendered[t] && mrgi_stencil_receiver(position, t);
}

/* The DIFFERENCE test of one channel (header, last section). */
static int mrgi_stencil_differs(float En, float Ep, float threshold)
{
  const float larger = En > Ep ? En : Ep;
  return fabsf(En - Ep) > threshold * larger;
}

/* F_level(x, y) of the illumination rule (header, last section). The float
 * expressions are the shader's (vtkMRGIIncrementalStencilFS.glsl). */
static int mrgi_stencil_light_discontinuity(const mrgi_multires_layout* layout, int32_t level,
                                            int32_t x, int32_t y, const float* position,
                                            const float* irradiance, const uint8_t* rendered,
                                            int32_t metric, float threshold)
{
  const size_t p = mrgi_multires_index(layout, level, x, y);
  if (!mrgi_stencil_usable(position, rendered, p))
  {
    return 0;
  }
  if (threshold == 0.0f)
  {
    return 1;
  }
  const float* Ep = irradiance + 4 * p;
  if (metric == MRGI_INCREMENTAL_ILLUMINATION_CURVATURE)
  {
    static const int32_t axes[4][2] = { { 1, 0 }, { 0, 1 }, { 1, 1 }, { 1, -1 } };
    for (int k = 0; k < 4; ++k)
    {
      const int32_t ax = x - axes[k][0], ay = y - axes[k][1];
      const int32_t bx = x + axes[k][0], by = y + axes[k][1];
      if (ax < 0 || ay < 0 || ay >= layout->level_height[level] ||
          bx >= layout->level_width[level] || by < 0 || by >= layout->level_height[level])
      {
        continue; /* a line leaving the level: no prediction */
      }
      const size_t a = mrgi_multires_index(layout, level, ax, ay);
      const size_t b = mrgi_multires_index(layout, level, bx, by);
      const int ua = mrgi_stencil_usable(position, rendered, a);
      const int ub = mrgi_stencil_usable(position, rendered, b);
      const float* Ea = irradiance + 4 * a;
      const float* Eb = irradiance + 4 * b;
      for (int c = 0; c < 3; ++c)
      {
        if (ua && ub)
        {
          const float ab = Ea[c] > Eb[c] ? Ea[c] : Eb[c];
          const float larger = ab > Ep[c] ? ab : Ep[c];
          if (fabsf(0.5f * (Ea[c] + Eb[c]) - Ep[c]) > threshold * larger)
          {
            return 1;
          }
        }
        else if ((ua && mrgi_stencil_differs(Ea[c], Ep[c], threshold)) ||
                 (ub && mrgi_stencil_differs(Eb[c], Ep[c], threshold)))
        {
          return 1;
        }
      }
    }
    return 0;
  }
  for (int32_t dy = -1; dy <= 1; ++dy)
  {
    for (int32_t dx = -1; dx <= 1; ++dx)
    {
      const size_t n = mrgi_multires_clamped_index(layout, level, x, y, dx, dy);
      if (!mrgi_stencil_usable(position, rendered, n))
      {
        continue;
      }
      const float* En = irradiance + 4 * n;
      for (int c = 0; c < 3; ++c)
      {
        if (mrgi_stencil_differs(En[c], Ep[c], threshold))
        {
          return 1;
        }
      }
    }
  }
  return 0;
}

mrgi_status mrgi_incremental_stencil_illumination_level(const mrgi_multires_layout* layout,
  int32_t finest_level, int32_t level, const uint8_t* flags, const uint8_t* selection,
  size_t texel_bytes, const float* receiver_position, size_t receiver_floats,
  const float* irradiance, size_t irradiance_floats, int32_t metric, float threshold,
  uint8_t* rendered, size_t rendered_size, int64_t* added, mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if ((status = mrgi_multires_check_array(layout, flags, texel_bytes, 1, "flags", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, selection, texel_bytes, 1, "selection", err)) !=
        MRGI_OK ||
      (status = mrgi_multires_check_array(layout, receiver_position, receiver_floats, 4,
                                          "receiver positions", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, irradiance, irradiance_floats, 4, "irradiance",
                                          err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, rendered, rendered_size, 1, "rendered mask",
                                          err)) != MRGI_OK)
  {
    return status;
  }
  if (metric != MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE &&
      metric != MRGI_INCREMENTAL_ILLUMINATION_CURVATURE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "illumination metric %d is unknown",
                          metric);
  }
  if (!(threshold >= 0.0f) || isinf(threshold))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "illumination threshold %g is not finite and >= 0", (double)threshold);
  }
  const int32_t coarsest = layout->level_count - 1;
  if (finest_level < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "finest level %d is negative",
                          finest_level);
  }
  const int32_t finest = finest_level < coarsest ? finest_level : coarsest;
  if (level < finest || level > coarsest)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "level %d is outside %d..%d", level,
                          finest, coarsest);
  }
  int64_t count = 0;
  const int32_t i = level;
  for (int32_t y = 0; y < layout->level_height[i]; ++y)
  {
    for (int32_t x = 0; x < layout->level_width[i]; ++x)
    {
      const size_t t = mrgi_multires_index(layout, i, x, y);
      uint8_t r = 0;
      if (flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY)
      {
        const int refined = i != finest && (flags[t] & MRGI_MULTIRES_FLAG_REFINE);
        if (selection[t])
        {
          r = 1;
        }
        else if (i < coarsest && !refined &&
                 mrgi_stencil_light_discontinuity(layout, i + 1, x / 2, y / 2, receiver_position,
                                                  irradiance, rendered, metric, threshold))
        {
          r = 1;
          ++count;
        }
      }
      rendered[t] = r;
    }
  }
  if (added)
  {
    *added = count;
  }
  return MRGI_OK;
}
