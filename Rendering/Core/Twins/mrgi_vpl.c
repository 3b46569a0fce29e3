#include "mrgi_vpl.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* The record must be exactly its MRGI_VPL_TEXELS RGBA texels, in order. */
_Static_assert(sizeof(mrgi_vpl) == MRGI_VPL_FLOATS * sizeof(float),
               "mrgi_vpl must be MRGI_VPL_FLOATS tightly packed floats");
_Static_assert(MRGI_VPL_FLOATS == 4 * MRGI_VPL_TEXELS, "a VPL texel is 4 floats");
_Static_assert(offsetof(mrgi_vpl, position) == 4 * MRGI_VPL_TEXEL_POSITION * sizeof(float),
               "position starts texel MRGI_VPL_TEXEL_POSITION");
_Static_assert(offsetof(mrgi_vpl, area) == (4 * MRGI_VPL_TEXEL_POSITION + 3) * sizeof(float),
               "area is the w of texel MRGI_VPL_TEXEL_POSITION");
_Static_assert(offsetof(mrgi_vpl, normal) == 4 * MRGI_VPL_TEXEL_NORMAL * sizeof(float),
               "normal starts texel MRGI_VPL_TEXEL_NORMAL");
_Static_assert(offsetof(mrgi_vpl, flux) == 4 * MRGI_VPL_TEXEL_FLUX * sizeof(float),
               "flux starts texel MRGI_VPL_TEXEL_FLUX");

mrgi_status mrgi_rsm_validate(const mrgi_rsm* rsm, mrgi_error* err)
{
  if (!rsm)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM pointer is NULL");
  }
  if (rsm->size < 1 || rsm->size > MRGI_RSM_MAX_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "RSM size %d is outside 1..%d texels", rsm->size, MRGI_RSM_MAX_SIZE);
  }
  if (rsm->view_count < 1 || rsm->view_count > MRGI_RSM_MAX_VIEWS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "RSM view count %d is outside 1..%d", rsm->view_count,
                          MRGI_RSM_MAX_VIEWS);
  }
  if (!rsm->position || !rsm->normal || !rsm->flux)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "RSM %s array is NULL",
                          !rsm->position ? "position" : (!rsm->normal ? "normal" : "flux"));
  }
  return MRGI_OK;
}

mrgi_status mrgi_vpl_grid_layout(int32_t requested_count, int32_t view_count, int32_t rsm_size,
                                 int32_t* out_grid_side, int32_t* out_vpl_count, mrgi_error* err)
{
  if (requested_count < MRGI_VPL_MIN_COUNT || requested_count > MRGI_VPL_MAX_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "requested VPL count %d is outside %d..%d", requested_count,
                          MRGI_VPL_MIN_COUNT, MRGI_VPL_MAX_COUNT);
  }
  if (view_count < 1 || view_count > MRGI_RSM_MAX_VIEWS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM view count %d is outside 1..%d",
                          view_count, MRGI_RSM_MAX_VIEWS);
  }
  if (rsm_size < 1 || rsm_size > MRGI_RSM_MAX_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM size %d is outside 1..%d texels",
                          rsm_size, MRGI_RSM_MAX_SIZE);
  }
  /* G = floor(sqrt(N / V)) exactly: the largest G with V*G*G <= N, at least 1. */
  int32_t side = 1;
  while ((int64_t)view_count * (side + 1) * (side + 1) <= requested_count)
  {
    ++side;
  }
  if (side > rsm_size)
  {
    side = rsm_size; /* every block keeps at least one texel */
  }
  if (out_grid_side)
  {
    *out_grid_side = side;
  }
  if (out_vpl_count)
  {
    *out_vpl_count = view_count * side * side;
  }
  return MRGI_OK;
}

/* Whether texel `index` (in the (v*S + y)*S + x order) is valid, and whether
 * a valid texel is well formed (see "usable" in the header). */
typedef enum mrgi_texel_kind
{
  MRGI_TEXEL_INVALID,
  MRGI_TEXEL_REJECTED,
  MRGI_TEXEL_USABLE
} mrgi_texel_kind;

static mrgi_texel_kind mrgi_rsm_texel_kind(const mrgi_rsm* rsm, size_t index)
{
  const float* position = rsm->position + 4 * index;
  const float* normal = rsm->normal + 4 * index;
  const float* flux = rsm->flux + 4 * index;
  if (!(position[3] > MRGI_VALID_THRESHOLD))
  {
    return MRGI_TEXEL_INVALID;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!isfinite(position[c]) || !isfinite(normal[c]) || !isfinite(flux[c]) || flux[c] < 0.0f)
    {
      return MRGI_TEXEL_REJECTED;
    }
  }
  if (!isfinite(flux[3]) || flux[3] < 0.0f)
  {
    return MRGI_TEXEL_REJECTED;
  }
  return MRGI_TEXEL_USABLE;
}

int mrgi_rsm_texel_usable(const mrgi_rsm* rsm, int64_t index)
{
  return mrgi_rsm_texel_kind(rsm, (size_t)index) == MRGI_TEXEL_USABLE;
}

/* Common argument checks of both selections. */
static mrgi_status mrgi_vpl_check_output(const mrgi_rsm* rsm, int32_t count, const mrgi_vpl* vpls,
                                         mrgi_error* err)
{
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (count < MRGI_VPL_MIN_COUNT || count > MRGI_VPL_MAX_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VPL count %d is outside %d..%d",
                          count, MRGI_VPL_MIN_COUNT, MRGI_VPL_MAX_COUNT);
  }
  if (!vpls)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VPL output array is NULL");
  }
  return MRGI_OK;
}

int64_t mrgi_vpl_from_rsm_block(const mrgi_rsm* rsm, int32_t view, int32_t x0, int32_t x1,
                                int32_t y0, int32_t y1, mrgi_vpl* out, double sums[4],
                                int64_t* usable, int64_t* rejected)
{
  const int64_t size = rsm->size;
  double flux_sum[3] = { 0.0, 0.0, 0.0 };
  double area_sum = 0.0;
  int64_t best_index = -1;
  int64_t best_distance2 = INT64_MAX;
  for (int32_t y = y0; y < y1; ++y)
  {
    for (int32_t x = x0; x < x1; ++x)
    {
      const int64_t index = ((int64_t)view * size + y) * size + x;
      const mrgi_texel_kind kind = mrgi_rsm_texel_kind(rsm, (size_t)index);
      if (kind != MRGI_TEXEL_USABLE)
      {
        *rejected += kind == MRGI_TEXEL_REJECTED;
        continue;
      }
      ++*usable;
      const float* flux = rsm->flux + 4 * index;
      flux_sum[0] += flux[0];
      flux_sum[1] += flux[1];
      flux_sum[2] += flux[2];
      area_sum += flux[3];
      /* Doubled distance from texel centre x + 1/2 to block centre (x0 + x1)/2,
       * in integers: 2x + 1 - (x0 + x1). Scan order makes ties go to the lowest index. */
      const int64_t dx = 2 * (int64_t)x + 1 - ((int64_t)x0 + x1);
      const int64_t dy = 2 * (int64_t)y + 1 - ((int64_t)y0 + y1);
      const int64_t distance2 = dx * dx + dy * dy;
      if (distance2 < best_distance2)
      {
        best_distance2 = distance2;
        best_index = index;
      }
    }
  }
  if (sums)
  {
    sums[0] = flux_sum[0];
    sums[1] = flux_sum[1];
    sums[2] = flux_sum[2];
    sums[3] = area_sum;
  }
  memset(out, 0, sizeof(*out));
  if (best_index < 0)
  {
    return -1; /* empty block: zero flux, zero area, zero normal */
  }
  const float* position = rsm->position + 4 * best_index;
  const float* normal = rsm->normal + 4 * best_index;
  for (int c = 0; c < 3; ++c)
  {
    out->position[c] = position[c];
    out->normal[c] = normal[c];
    /* Sums of finite floats; clamp keeps a sum of huge fluxes finite. */
    out->flux[c] = flux_sum[c] < FLT_MAX ? (float)flux_sum[c] : FLT_MAX;
  }
  out->area = area_sum < FLT_MAX ? (float)area_sum : FLT_MAX;
  return best_index;
}

mrgi_status mrgi_vpl_select_grid(const mrgi_rsm* rsm, int32_t requested_count, mrgi_vpl* vpls,
                                 int32_t capacity, mrgi_vpl_selection_info* out_info,
                                 mrgi_error* err)
{
  mrgi_status status = mrgi_vpl_check_output(rsm, requested_count, vpls, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  int32_t side = 0;
  int32_t vpl_count = 0;
  status = mrgi_vpl_grid_layout(requested_count, rsm->view_count, rsm->size, &side, &vpl_count,
                                err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (capacity < vpl_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL array holds %d records but a %dx%d grid on %d view(s) makes %d",
                          capacity, side, side, rsm->view_count, vpl_count);
  }
  const int64_t size = rsm->size;
  mrgi_vpl_selection_info info = { vpl_count, 0, 0, 0 };
  for (int32_t view = 0; view < rsm->view_count; ++view)
  {
    for (int32_t j = 0; j < side; ++j)
    {
      const int32_t y0 = (int32_t)(j * size / side);
      const int32_t y1 = (int32_t)((j + 1) * size / side);
      for (int32_t i = 0; i < side; ++i)
      {
        const int32_t x0 = (int32_t)(i * size / side);
        const int32_t x1 = (int32_t)((i + 1) * size / side);
        mrgi_vpl* vpl = vpls + ((int64_t)view * side + j) * side + i;
        (void)mrgi_vpl_from_rsm_block(rsm, view, x0, x1, y0, y1, vpl, NULL,
                                      &info.usable_texel_count, &info.rejected_texel_count);
        info.empty_vpl_count += vpl->flux[0] == 0.0f && vpl->flux[1] == 0.0f &&
                                vpl->flux[2] == 0.0f;
      }
    }
  }
  if (out_info)
  {
    *out_info = info;
  }
  return MRGI_OK;
}

size_t mrgi_vpl_importance_scratch_count(const mrgi_rsm* rsm)
{
  if (!rsm || rsm->size < 1 || rsm->size > MRGI_RSM_MAX_SIZE || rsm->view_count < 1 ||
      rsm->view_count > MRGI_RSM_MAX_VIEWS)
  {
    return 0;
  }
  return (size_t)rsm->view_count * (size_t)rsm->size * (size_t)rsm->size;
}

/* Importance weight of texel `index`: flux luminance when usable, else 0. */
static double mrgi_rsm_texel_weight(const mrgi_rsm* rsm, size_t index, mrgi_texel_kind kind)
{
  if (kind != MRGI_TEXEL_USABLE)
  {
    return 0.0;
  }
  const float* flux = rsm->flux + 4 * index;
  return MRGI_LUMINANCE_R * flux[0] + MRGI_LUMINANCE_G * flux[1] + MRGI_LUMINANCE_B * flux[2];
}

/* SplitMix64 (Steele, Lea and Flood 2014): one well-mixed 64-bit value per seed. */
static uint64_t mrgi_splitmix64(uint64_t seed)
{
  uint64_t z = seed + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* First index whose inclusive prefix sum exceeds `target`, or `count` if none. */
static size_t mrgi_prefix_search(const double* prefix, size_t count, double target)
{
  size_t low = 0;
  size_t high = count;
  while (low < high)
  {
    const size_t middle = low + (high - low) / 2;
    if (prefix[middle] > target)
    {
      high = middle;
    }
    else
    {
      low = middle + 1;
    }
  }
  return low;
}

mrgi_status mrgi_vpl_select_importance(const mrgi_rsm* rsm, int32_t count, uint64_t seed,
                                       double* scratch, size_t scratch_count, mrgi_vpl* vpls,
                                       int32_t capacity, mrgi_vpl_selection_info* out_info,
                                       mrgi_error* err)
{
  mrgi_status status = mrgi_vpl_check_output(rsm, count, vpls, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (capacity < count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL array holds %d records but %d VPLs were requested", capacity,
                          count);
  }
  const size_t texel_count = mrgi_vpl_importance_scratch_count(rsm);
  if (scratch && scratch_count < texel_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "importance scratch holds %zu doubles but the RSM has %zu texels",
                          scratch_count, texel_count);
  }
  double* prefix = scratch;
  if (!prefix)
  {
    prefix = (double*)malloc(sizeof(double) * texel_count);
    if (!prefix)
    {
      return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                            "cannot allocate the importance CDF of %zu texels", texel_count);
    }
  }

  /* Inclusive prefix sums of the weights (the unnormalized CDF). */
  mrgi_vpl_selection_info info = { count, 0, 0, 0 };
  double total = 0.0;
  size_t last_positive = 0;
  for (size_t t = 0; t < texel_count; ++t)
  {
    const mrgi_texel_kind kind = mrgi_rsm_texel_kind(rsm, t);
    info.usable_texel_count += kind == MRGI_TEXEL_USABLE;
    info.rejected_texel_count += kind == MRGI_TEXEL_REJECTED;
    const double weight = mrgi_rsm_texel_weight(rsm, t, kind);
    if (weight > 0.0)
    {
      last_positive = t;
    }
    total += weight;
    prefix[t] = total;
  }

  memset(vpls, 0, sizeof(mrgi_vpl) * (size_t)count);
  if (total > 0.0)
  {
    const double offset = (double)(mrgi_splitmix64(seed) >> 11) * 0x1.0p-53;
    for (int32_t k = 0; k < count; ++k)
    {
      const double u = ((double)k + offset) / (double)count;
      size_t t = mrgi_prefix_search(prefix, texel_count, u * total);
      if (t >= texel_count)
      {
        t = last_positive; /* u * total rounded up to the total */
      }
      const double weight = mrgi_rsm_texel_weight(rsm, t, MRGI_TEXEL_USABLE);
      /* 1 / (N p_t) = W / (N w_t); w_t > 0 because the prefix sum rose at t. */
      const double scale = total / ((double)count * weight);
      const float* position = rsm->position + 4 * t;
      const float* normal = rsm->normal + 4 * t;
      const float* flux = rsm->flux + 4 * t;
      mrgi_vpl* vpl = vpls + k;
      for (int c = 0; c < 3; ++c)
      {
        vpl->position[c] = position[c];
        vpl->normal[c] = normal[c];
        const double scaled_flux = flux[c] * scale;
        vpl->flux[c] = scaled_flux < FLT_MAX ? (float)scaled_flux : FLT_MAX;
      }
      const double scaled_area = flux[3] * scale;
      vpl->area = scaled_area < FLT_MAX ? (float)scaled_area : FLT_MAX;
    }
  }
  else
  {
    info.empty_vpl_count = count;
  }
  if (!scratch)
  {
    free(prefix);
  }
  if (out_info)
  {
    *out_info = info;
  }
  return MRGI_OK;
}
