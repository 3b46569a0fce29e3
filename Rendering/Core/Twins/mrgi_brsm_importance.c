/* BRSM importance (RIHKS11 4, 4.2) and the flux-importance mix; contract in
 * mrgi_brsm_importance.h. */
#include "mrgi_brsm_importance.h"

#include "mrgi_gather_term.h"

#include <float.h>
#include <math.h>
#include <string.h>

double mrgi_brsm_hash01(uint64_t seed, uint64_t index)
{
  uint64_t z = seed + 0x9E3779B97F4A7C15ull * (index + 1u);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

static double mrgi_brsm_luminance(const double rgb[3])
{
  return MRGI_LUMINANCE_R * rgb[0] + MRGI_LUMINANCE_G * rgb[1] + MRGI_LUMINANCE_B * rgb[2];
}

static mrgi_status mrgi_brsm_check_view(const mrgi_brsm_view* view, mrgi_error* err)
{
  if (!view || !view->samples)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BRSM view samples are NULL");
  }
  if (view->sample_count < 1 || view->sample_count > MRGI_BRSM_MAX_VIEW_SAMPLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM view sample count %d is outside 1..%d", view->sample_count,
                          MRGI_BRSM_MAX_VIEW_SAMPLES);
  }
  if (view->samples_per_texel < 1 || view->samples_per_texel > MRGI_BRSM_MAX_VIEW_SAMPLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM samples per texel %d is outside 1..%d", view->samples_per_texel,
                          MRGI_BRSM_MAX_VIEW_SAMPLES);
  }
  if (view->world_to_clip && (view->width < 1 || view->height < 1))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM guide viewport %dx%d is empty", view->width, view->height);
  }
  return MRGI_OK;
}

/* E_tm = lum(albedo_m * Phi_t * T(t, m)); 0 for an invalid or malformed sample. */
static double mrgi_brsm_contribution(const mrgi_gather_vpl* vpl, const float* sample)
{
  if (!(sample[11] > MRGI_VALID_THRESHOLD))
  {
    return 0.0;
  }
  double position[3], normal[3], albedo[3];
  for (int c = 0; c < 3; ++c)
  {
    position[c] = sample[c];
    normal[c] = sample[4 + c];
    albedo[c] = sample[8 + c];
  }
  if (!isfinite(mrgi_gather_dot3(position, position)) || !mrgi_gather_normalize3(normal) ||
      !isfinite(mrgi_gather_dot3(albedo, albedo)))
  {
    return 0.0;
  }
  const double transfer = mrgi_gather_transfer(position, normal, vpl);
  const double rgb[3] = { albedo[0] * vpl->flux[0] * transfer, albedo[1] * vpl->flux[1] * transfer,
                          albedo[2] * vpl->flux[2] * transfer };
  const double e = mrgi_brsm_luminance(rgb);
  return e > 0.0 && isfinite(e) ? e : 0.0;
}

/* Window position of world point p through the column-major matrix m; 0 if behind the camera. */
static int mrgi_brsm_project(const float* m, const double p[3], int32_t width, int32_t height,
                             double out[2])
{
  double clip[4];
  for (int row = 0; row < 4; ++row)
  {
    clip[row] = (double)m[row] * p[0] + (double)m[4 + row] * p[1] + (double)m[8 + row] * p[2] +
                (double)m[12 + row];
  }
  if (!(clip[3] > 0.0) || !isfinite(clip[0] + clip[1] + clip[3]))
  {
    return 0;
  }
  out[0] = (clip[0] / clip[3] * 0.5 + 0.5) * width;
  out[1] = (clip[1] / clip[3] * 0.5 + 0.5) * height;
  return isfinite(out[0]) && isfinite(out[1]);
}

mrgi_status mrgi_brsm_importance(const mrgi_rsm* rsm, const mrgi_brsm_view* view, uint64_t seed,
                                 float* importance, size_t capacity, mrgi_error* err)
{
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK || (status = mrgi_brsm_check_view(view, err)) != MRGI_OK)
  {
    return status;
  }
  const size_t texel_count = mrgi_vpl_importance_scratch_count(rsm);
  if (!importance || capacity < texel_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM importance output holds %zu floats but the RSM has %zu texels",
                          importance ? capacity : (size_t)0, texel_count);
  }
  const int32_t M = view->sample_count;
  const int32_t K = view->samples_per_texel;
  const int exact = !view->guided && K >= M;
  double cdf[MRGI_BRSM_MAX_VIEW_SAMPLES]; /* c_m, then the inclusive prefix sums of q_m */
  for (size_t t = 0; t < texel_count; ++t)
  {
    importance[t] = 0.0f;
    if (!mrgi_rsm_texel_usable(rsm, (int64_t)t))
    {
      continue;
    }
    const mrgi_vpl record = {
      { rsm->position[4 * t], rsm->position[4 * t + 1], rsm->position[4 * t + 2] },
      rsm->flux[4 * t + 3],
      { rsm->normal[4 * t], rsm->normal[4 * t + 1], rsm->normal[4 * t + 2] },
      0.0f,
      { rsm->flux[4 * t], rsm->flux[4 * t + 1], rsm->flux[4 * t + 2] },
      0.0f
    };
    mrgi_gather_vpl vpl;
    if (mrgi_gather_vpl_prepare(&record, NULL, &vpl) != MRGI_GATHER_VPL_USABLE)
    {
      continue; /* zero flux or zero normal: lights nothing */
    }
    double sum = 0.0;
    if (exact)
    {
      for (int32_t m = 0; m < M; ++m)
      {
        const double e =
          mrgi_brsm_contribution(&vpl, view->samples + (size_t)m * MRGI_BRSM_VIEW_SAMPLE_FLOATS);
        sum += e * e; /* squares: the RMS, see the header */
      }
      sum = sqrt(sum / (double)M);
    }
    else
    {
      double centre[2];
      const int guide = view->guided && view->world_to_clip &&
                        mrgi_brsm_project(view->world_to_clip, vpl.position, view->width,
                                          view->height, centre);
      double total = 0.0;
      for (int32_t m = 0; m < M; ++m)
      {
        double c = 1.0;
        if (guide)
        {
          const float* s = view->samples + (size_t)m * MRGI_BRSM_VIEW_SAMPLE_FLOATS;
          const double dx = s[3] - centre[0], dy = s[7] - centre[1];
          const double x2 = dx * dx + dy * dy;
          const double r2 = MRGI_BRSM_GUIDE_RADIUS * MRGI_BRSM_GUIDE_RADIUS;
          c = x2 > r2 && isfinite(x2) ? r2 / x2 : (isfinite(x2) ? 1.0 : 0.0);
          c = c > 1e-30 ? c : 1e-30; /* q_m > 0 for every sample (unbiasedness) */
        }
        cdf[m] = c;
        total += c;
      }
      /* Defensive mixture with the uniform choice: q_m = (1 - a) c_m / sum c + a / M. */
      const double a = guide ? MRGI_BRSM_GUIDE_UNIFORM_SHARE : 1.0;
      double running = 0.0;
      for (int32_t m = 0; m < M; ++m)
      {
        running += (1.0 - a) * cdf[m] / total + a / (double)M;
        cdf[m] = running;
      }
      total = running; /* 1 up to rounding */
      const double h = mrgi_brsm_hash01(seed, (uint64_t)t);
      for (int32_t k = 0; k < K; ++k)
      {
        const double target = ((double)k + h) / (double)K * total;
        int32_t low = 0, high = M - 1; /* first m with cdf[m] > target */
        while (low < high)
        {
          const int32_t middle = low + (high - low) / 2;
          if (cdf[middle] > target)
          {
            high = middle;
          }
          else
          {
            low = middle + 1;
          }
        }
        const double c = cdf[low] - (low > 0 ? cdf[low - 1] : 0.0);
        const double q = c / total;
        const double e =
          mrgi_brsm_contribution(&vpl, view->samples + (size_t)low * MRGI_BRSM_VIEW_SAMPLE_FLOATS);
        sum += e * e / ((double)M * q); /* unbiased for the mean square over the M */
      }
      sum = sqrt(sum / (double)K);
    }
    importance[t] = sum > 0.0 && sum < FLT_MAX ? (float)sum : (sum > 0.0 ? FLT_MAX : 0.0f);
  }
  return MRGI_OK;
}

mrgi_status mrgi_brsm_mix(const mrgi_rsm* rsm, double beta, float* importance, size_t count,
                          mrgi_error* err)
{
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!(beta >= 0.0 && beta <= 1.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "BRSM flux share %g is outside 0..1",
                          beta);
  }
  const size_t texel_count = mrgi_vpl_importance_scratch_count(rsm);
  if (!importance || count < texel_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "BRSM importance holds %zu floats but the RSM has %zu texels",
                          importance ? count : (size_t)0, texel_count);
  }
  double sum_i = 0.0, sum_w = 0.0;
  for (size_t t = 0; t < texel_count; ++t)
  {
    if (!(importance[t] >= 0.0f) || !isfinite(importance[t]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "BRSM importance of texel %zu is negative or not finite", t);
    }
    if (mrgi_rsm_texel_usable(rsm, (int64_t)t))
    {
      const double flux[3] = { rsm->flux[4 * t], rsm->flux[4 * t + 1], rsm->flux[4 * t + 2] };
      sum_w += mrgi_brsm_luminance(flux);
      sum_i += importance[t];
    }
  }
  const double a = sum_i > 0.0 ? (1.0 - beta) / sum_i : 0.0;
  const double b = sum_w > 0.0 ? (sum_i > 0.0 ? beta : 1.0) / sum_w : 0.0;
  for (size_t t = 0; t < texel_count; ++t)
  {
    double p = 0.0;
    if (mrgi_rsm_texel_usable(rsm, (int64_t)t))
    {
      const double flux[3] = { rsm->flux[4 * t], rsm->flux[4 * t + 1], rsm->flux[4 * t + 2] };
      const double w = mrgi_brsm_luminance(flux);
      p = w > 0.0 ? a * importance[t] + b * w : 0.0; /* no flux: nothing to estimate */
    }
    importance[t] = (float)p;
  }
  return MRGI_OK;
}
