/* Float twin of the BRSM CDF inversion (RIHKS11 4.1); contract in mrgi_brsm_cdf_float.h. */
#include "mrgi_brsm_cdf_float.h"

#include "mrgi_brsm_importance.h"

#include <math.h>
#include <string.h>

size_t mrgi_brsm_cdf_float_count(const mrgi_rsm* rsm)
{
  const size_t texels = mrgi_vpl_importance_scratch_count(rsm);
  return texels ? texels / (size_t)rsm->size * (size_t)(rsm->size + 1) : 0;
}

mrgi_status mrgi_brsm_cdf_to_float(const mrgi_rsm* rsm, const double* cdf, size_t cdf_count,
                                   float* out, size_t out_count, mrgi_error* err)
{
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!cdf || cdf_count < mrgi_brsm_cdf_count(rsm))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM CDF holds %zu doubles but needs %zu", cdf ? cdf_count : (size_t)0,
                          mrgi_brsm_cdf_count(rsm));
  }
  const size_t needed = mrgi_brsm_cdf_float_count(rsm);
  if (!out || out_count < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM float CDF holds %zu floats but needs %zu",
                          out ? out_count : (size_t)0, needed);
  }
  const size_t S = (size_t)rsm->size;
  const size_t R = (size_t)rsm->view_count * S;
  memset(out, 0, sizeof(float) * needed);
  for (size_t i = 0; i < S * R + S; ++i)
  {
    out[i] = (float)cdf[i]; /* row S starts at S*R: the column sums */
  }
  return MRGI_OK;
}

mrgi_status mrgi_brsm_sample_values(int32_t count, uint64_t seed, float* out, size_t out_count,
                                    mrgi_error* err)
{
  if (count < MRGI_VPL_MIN_COUNT || count > MRGI_VPL_MAX_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BRSM VPL count %d is outside %d..%d",
                          count, MRGI_VPL_MIN_COUNT, MRGI_VPL_MAX_COUNT);
  }
  if (!out || out_count < 2 * (size_t)count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM sample array holds %zu floats but needs %zu",
                          out ? out_count : (size_t)0, 2 * (size_t)count);
  }
  /* Exactly mrgi_brsm_sample_vpls()'s u1, u2 (mrgi_brsm_sample.h). */
  const double xi1 = mrgi_brsm_hash01(seed, 0);
  const double xi2 = mrgi_brsm_hash01(seed, 1);
  for (int32_t k = 0; k < count; ++k)
  {
    double u2 = xi2 + (double)k * MRGI_BRSM_LATTICE_STEP;
    u2 -= floor(u2);
    out[2 * k] = (float)(((double)k + xi1) / (double)count);
    out[2 * k + 1] = (float)u2;
  }
  return MRGI_OK;
}

/* First i in [0, n) with c[i] > target; the last i with a positive step when none.
   Mirrored by mrgiSearch() in vtkMRGIBRSMInvertFS.glsl. */
static int64_t mrgi_brsm_search_f(const float* c, int64_t n, float target)
{
  int64_t low = 0, high = n;
  while (low < high)
  {
    const int64_t middle = low + (high - low) / 2;
    if (c[middle] > target)
    {
      high = middle;
    }
    else
    {
      low = middle + 1;
    }
  }
  if (low >= n)
  {
    low = n - 1;
    while (low > 0 && !(c[low] > c[low - 1]))
    {
      --low;
    }
  }
  return low;
}

static float mrgi_brsm_fraction_f(const float* c, int64_t i, float target)
{
  const float before = i > 0 ? c[i - 1] : 0.0f;
  const float step = c[i] - before;
  float f = step > 0.0f ? (target - before) / step : 0.5f;
  return f < 0.0f ? 0.0f : (f > 1.0f ? 1.0f : f);
}

int mrgi_brsm_cdf_float_invert(const mrgi_rsm* rsm, const float* cdf, float u1, float u2,
                               mrgi_brsm_pick* pick)
{
  const int64_t S = rsm->size;
  const int64_t R = (int64_t)rsm->view_count * S;
  const float* sums = cdf + S * R;
  const float W = sums[S - 1];
  if (!(W > 0.0f))
  {
    return 0;
  }
  const float t1 = u1 * W;
  const int64_t x = mrgi_brsm_search_f(sums, S, t1);
  const float* column = cdf + x * R;
  const float t2 = u2 * column[R - 1];
  const int64_t r = mrgi_brsm_search_f(column, R, t2);
  pick->view = (int32_t)(r / S);
  pick->x = (int32_t)x;
  pick->y = (int32_t)(r % S);
  pick->fx = mrgi_brsm_fraction_f(sums, x, t1);
  pick->fy = mrgi_brsm_fraction_f(column, r, t2);
  pick->pdf = (column[r] - (r > 0 ? column[r - 1] : 0.0f)) / W;
  return 1;
}

void mrgi_brsm_float_vpl(const mrgi_rsm* rsm, const mrgi_brsm_pick* pick, int32_t count,
                         mrgi_vpl* vpl)
{
  memset(vpl, 0, sizeof(*vpl));
  if (!(pick->pdf > 0.0f))
  {
    return;
  }
  const int64_t S = rsm->size;
  const int64_t t = ((int64_t)pick->view * S + pick->y) * S + pick->x;
  const float scale = 1.0f / ((float)count * pick->pdf);
  for (int k = 0; k < 3; ++k)
  {
    vpl->position[k] = rsm->position[4 * t + k];
    vpl->normal[k] = rsm->normal[4 * t + k];
    vpl->flux[k] = rsm->flux[4 * t + k] * scale;
  }
  vpl->area = rsm->flux[4 * t + 3] * scale;
}
