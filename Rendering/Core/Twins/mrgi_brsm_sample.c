/* 2-D CDF sampling and inter-texel VPLs (RIHKS11 4.1, 6.5); contract in mrgi_brsm_sample.h. */
#include "mrgi_brsm_sample.h"

#include "mrgi_brsm_blur.h"
#include "mrgi_brsm_importance.h"

#include <float.h>
#include <math.h>
#include <string.h>

size_t mrgi_brsm_cdf_count(const mrgi_rsm* rsm)
{
  const size_t texels = mrgi_vpl_importance_scratch_count(rsm);
  return texels ? texels + (size_t)rsm->size : 0;
}

mrgi_status mrgi_brsm_cdf_build(const mrgi_rsm* rsm, const float* weights, size_t weight_count,
                                double* cdf, size_t cdf_count, double* total, mrgi_error* err)
{
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t texels = mrgi_vpl_importance_scratch_count(rsm);
  if (!weights || weight_count < texels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM weights hold %zu floats but the RSM has %zu texels",
                          weights ? weight_count : (size_t)0, texels);
  }
  if (!cdf || cdf_count < mrgi_brsm_cdf_count(rsm))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM CDF holds %zu doubles but needs %zu", cdf ? cdf_count : (size_t)0,
                          mrgi_brsm_cdf_count(rsm));
  }
  for (size_t t = 0; t < texels; ++t)
  {
    if (!(weights[t] >= 0.0f) || !isfinite(weights[t]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "BRSM weight of texel %zu is negative or not finite", t);
    }
  }
  const int64_t S = rsm->size;
  const int64_t R = (int64_t)rsm->view_count * S;
  double running = 0.0;
  for (int64_t x = 0; x < S; ++x)
  {
    double column = 0.0;
    for (int64_t r = 0; r < R; ++r)
    {
      const int64_t t = r * S + x; /* (v*S + y)*S + x with r = v*S + y */
      column += mrgi_rsm_texel_usable(rsm, t) ? (double)weights[t] : 0.0;
      cdf[x * R + r] = column;
    }
    running += column;
    cdf[S * R + x] = running;
  }
  if (total)
  {
    *total = running;
  }
  return MRGI_OK;
}

/* First i in [0, n) with c[i] > target; the last i with a positive step when none. */
static int64_t mrgi_brsm_search(const double* c, int64_t n, double target)
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

static float mrgi_brsm_fraction(const double* c, int64_t i, double target)
{
  const double before = i > 0 ? c[i - 1] : 0.0;
  const double step = c[i] - before;
  double f = step > 0.0 ? (target - before) / step : 0.5;
  f = f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
  return (float)f;
}

int mrgi_brsm_cdf_invert(const mrgi_rsm* rsm, const double* cdf, double u1, double u2,
                         mrgi_brsm_pick* pick)
{
  const int64_t S = rsm->size;
  const int64_t R = (int64_t)rsm->view_count * S;
  const double* sums = cdf + S * R;
  const double W = sums[S - 1];
  if (!(W > 0.0))
  {
    return 0;
  }
  const double t1 = u1 * W;
  const int64_t x = mrgi_brsm_search(sums, S, t1);
  const double* column = cdf + x * R;
  const double t2 = u2 * column[R - 1];
  const int64_t r = mrgi_brsm_search(column, R, t2);
  pick->view = (int32_t)(r / S);
  pick->x = (int32_t)x;
  pick->y = (int32_t)(r % S);
  pick->fx = mrgi_brsm_fraction(sums, x, t1);
  pick->fy = mrgi_brsm_fraction(column, r, t2);
  pick->pdf = (float)((column[r] - (r > 0 ? column[r - 1] : 0.0)) / W);
  return 1;
}

static double mrgi_brsm_texel_pdf(const mrgi_rsm* rsm, const double* cdf, int64_t t)
{
  const int64_t S = rsm->size;
  const int64_t R = (int64_t)rsm->view_count * S;
  const int64_t x = t % S, r = t / S;
  const double* column = cdf + x * R;
  return (column[r] - (r > 0 ? column[r - 1] : 0.0)) / cdf[S * R + S - 1];
}

static int mrgi_brsm_ndc(const float* m, const float* p, double out[2])
{
  double clip[4];
  for (int row = 0; row < 4; ++row)
  {
    clip[row] = (double)m[row] * p[0] + (double)m[4 + row] * p[1] + (double)m[8 + row] * p[2] +
                (double)m[12 + row];
  }
  if (!(clip[3] > 0.0))
  {
    return 0;
  }
  out[0] = clip[0] / clip[3];
  out[1] = clip[1] / clip[3];
  return isfinite(out[0]) && isfinite(out[1]);
}

static float mrgi_brsm_store(double value)
{
  return value > 0.0 ? (value < FLT_MAX ? (float)value : FLT_MAX) : 0.0f;
}

/* The record of pick `k` (see the file comment). */
static void mrgi_brsm_make_vpl(const mrgi_rsm* rsm, const double* cdf, const mrgi_brsm_pick* pick,
                               const mrgi_brsm_sampling* sampling, mrgi_vpl* vpl)
{
  const int64_t S = rsm->size;
  const int64_t base = (int64_t)pick->view * S * S;
  const int64_t t0 = base + (int64_t)pick->y * S + pick->x;
  int64_t texel[4] = { t0, t0, t0, t0 };
  double c[4] = { 1.0, 0.0, 0.0, 0.0 };
  if (sampling->inter_texel)
  {
    /* Bilinear neighbours of the point (x + fx, y + fy), centres at i + 1/2. */
    const double bx = pick->x + (double)pick->fx - 0.5, by = pick->y + (double)pick->fy - 0.5;
    const int64_t x0 = (int64_t)floor(bx), y0 = (int64_t)floor(by);
    const double wx = bx - (double)x0, wy = by - (double)y0;
    double ndc0[2];
    const int has_ndc = sampling->world_to_clip &&
                        mrgi_brsm_ndc(sampling->world_to_clip, rsm->position + 4 * t0, ndc0);
    double total = 0.0;
    for (int i = 0; i < 4; ++i)
    {
      int64_t xi = x0 + (i & 1), yi = y0 + (i >> 1);
      const double w = ((i & 1) ? wx : 1.0 - wx) * ((i >> 1) ? wy : 1.0 - wy);
      xi = xi < 0 ? 0 : (xi >= S ? S - 1 : xi);
      yi = yi < 0 ? 0 : (yi >= S ? S - 1 : yi);
      const int64_t t = base + yi * S + xi;
      double g = 0.0;
      if (t == t0)
      {
        g = 1.0;
      }
      else if (w > 0.0 && mrgi_rsm_texel_usable(rsm, t) && mrgi_brsm_texel_pdf(rsm, cdf, t) > 0.0 &&
               mrgi_brsm_same_surface(rsm, t0, t,
                                      sqrt((double)((xi - pick->x) * (xi - pick->x) +
                                                    (yi - pick->y) * (yi - pick->y)))))
      {
        double ndc[2];
        g = 1.0;
        if (has_ndc && mrgi_brsm_ndc(sampling->world_to_clip, rsm->position + 4 * t, ndc))
        {
          const double dx = ndc[0] - ndc0[0], dy = ndc[1] - ndc0[1];
          g = exp(-(dx * dx + dy * dy) / (2.0 * MRGI_BRSM_INTER_TEXEL_VARIANCE));
        }
      }
      texel[i] = t;
      c[i] = w * g;
      total += c[i];
    }
    if (!(total > 0.0))
    {
      texel[0] = t0; /* T_0 has bilinear weight > 0 unless on an edge; fall back to it */
      c[0] = 1.0;
      c[1] = c[2] = c[3] = 0.0;
      total = 1.0;
    }
    for (int i = 0; i < 4; ++i)
    {
      c[i] /= total;
    }
  }
  double position[3] = { 0, 0, 0 }, normal[3] = { 0, 0, 0 };
  double radiance[3] = { 0, 0, 0 }, area = 0.0, pdf = 0.0;
  for (int i = 0; i < 4; ++i)
  {
    if (c[i] == 0.0)
    {
      continue;
    }
    const int64_t t = texel[i];
    const double a = rsm->flux[4 * t + 3];
    for (int k = 0; k < 3; ++k)
    {
      position[k] += c[i] * rsm->position[4 * t + k];
      normal[k] += c[i] * rsm->normal[4 * t + k];
      /* Texel VPLs need no radiance: Phi / A * A is Phi (also when A = 0). */
      radiance[k] += c[i] * (a > 0.0 ? rsm->flux[4 * t + k] / a : 0.0);
    }
    area += c[i] * a;
    pdf += c[i] * mrgi_brsm_texel_pdf(rsm, cdf, t);
  }
  const double scale = 1.0 / ((double)sampling->count * pdf);
  const double n2 = normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2];
  const double inv_n = n2 > 0.0 ? 1.0 / sqrt(n2) : 0.0;
  for (int k = 0; k < 3; ++k)
  {
    vpl->position[k] = (float)position[k];
    vpl->normal[k] = (float)(normal[k] * inv_n);
    const double flux = sampling->inter_texel ? radiance[k] * area : (double)rsm->flux[4 * t0 + k];
    vpl->flux[k] = mrgi_brsm_store(flux * scale);
  }
  vpl->area = mrgi_brsm_store(area * scale);
  vpl->pad0 = 0.0f;
  vpl->pad1 = 0.0f;
}

mrgi_status mrgi_brsm_sample_vpls(const mrgi_rsm* rsm, const double* cdf, size_t cdf_count,
                                  const mrgi_brsm_sampling* sampling, mrgi_brsm_pick* picks,
                                  mrgi_vpl* vpls, int32_t capacity,
                                  mrgi_vpl_selection_info* out_info, mrgi_error* err)
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
  if (!sampling || sampling->count < MRGI_VPL_MIN_COUNT || sampling->count > MRGI_VPL_MAX_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BRSM VPL count %d is outside %d..%d",
                          sampling ? sampling->count : 0, MRGI_VPL_MIN_COUNT, MRGI_VPL_MAX_COUNT);
  }
  if (!vpls || capacity < sampling->count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL array holds %d records but %d VPLs were requested",
                          vpls ? capacity : 0, sampling->count);
  }
  const int32_t N = sampling->count;
  const double xi1 = mrgi_brsm_hash01(sampling->seed, 0);
  const double xi2 = mrgi_brsm_hash01(sampling->seed, 1);
  mrgi_vpl_selection_info info = { N, 0, 0, 0 };
  memset(vpls, 0, sizeof(mrgi_vpl) * (size_t)N);
  for (int32_t k = 0; k < N; ++k)
  {
    const double u1 = ((double)k + xi1) / (double)N;
    double u2 = xi2 + (double)k * MRGI_BRSM_LATTICE_STEP;
    u2 -= floor(u2);
    mrgi_brsm_pick pick = { 0, 0, 0, 0.0f, 0.0f, 0.0f };
    if (mrgi_brsm_cdf_invert(rsm, cdf, u1, u2, &pick))
    {
      mrgi_brsm_make_vpl(rsm, cdf, &pick, sampling, vpls + k);
    }
    else
    {
      ++info.empty_vpl_count;
    }
    if (picks)
    {
      picks[k] = pick;
    }
  }
  const size_t texels = mrgi_vpl_importance_scratch_count(rsm);
  for (size_t t = 0; t < texels; ++t)
  {
    info.usable_texel_count += mrgi_rsm_texel_usable(rsm, (int64_t)t);
  }
  if (out_info)
  {
    *out_info = info;
  }
  return MRGI_OK;
}
