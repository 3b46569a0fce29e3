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
  /*
   * The guide's inner loop runs over all M samples for every texel, so it
   * reads the samples' pixel coordinates as two packed arrays (filled once
   * per call), computes the weights c_m without branches (vectorizable), and
   * draws the K stratified samples by one forward walk over block sums of q
   * instead of a full prefix sum and K binary searches. A non-finite pixel
   * coordinate becomes a far one, which gives c_m = 1e-30 as before.
   */
  float pixel_x[MRGI_BRSM_MAX_VIEW_SAMPLES], pixel_y[MRGI_BRSM_MAX_VIEW_SAMPLES];
  float weight[MRGI_BRSM_MAX_VIEW_SAMPLES]; /* c_m of the current texel */
  double block_start[MRGI_BRSM_MAX_VIEW_SAMPLES / MRGI_BRSM_GUIDE_BLOCK + 1];
  for (int32_t m = 0; m < M; ++m)
  {
    const float* s = view->samples + (size_t)m * MRGI_BRSM_VIEW_SAMPLE_FLOATS;
    const int finite = isfinite(s[3]) && isfinite(s[7]);
    pixel_x[m] = finite ? s[3] : 1e30f;
    pixel_y[m] = finite ? s[7] : 1e30f;
  }
  const int32_t blocks = (M + MRGI_BRSM_GUIDE_BLOCK - 1) / MRGI_BRSM_GUIDE_BLOCK;
  const float r2 = (float)(MRGI_BRSM_GUIDE_RADIUS * MRGI_BRSM_GUIDE_RADIUS);
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
      /* Defensive mixture with the uniform choice: q_m = (1 - a) c_m / sum c + a / M. */
      const double a = guide ? MRGI_BRSM_GUIDE_UNIFORM_SHARE : 1.0;
      double scale = 0.0; /* (1 - a) / sum c */
      if (guide)
      {
        const float cx = (float)centre[0], cy = (float)centre[1];
        for (int32_t m = 0; m < M; ++m)
        {
          const float dx = pixel_x[m] - cx, dy = pixel_y[m] - cy;
          const float x2 = dx * dx + dy * dy; /* +inf for a far sample: c = 0 */
          /* min(1, R^2 / x^2) without a branch, so that the loop vectorizes. */
          const float c = r2 / (x2 > r2 ? x2 : r2);
          weight[m] = c > 1e-30f ? c : 1e-30f; /* q_m > 0 for every sample (unbiasedness) */
        }
        double total = 0.0;
        for (int32_t b = 0; b < blocks; ++b)
        {
          block_start[b] = total;
          const int32_t end = b + 1 < blocks ? (b + 1) * MRGI_BRSM_GUIDE_BLOCK : M;
          float partial = 0.0f;
          for (int32_t m = b * MRGI_BRSM_GUIDE_BLOCK; m < end; ++m)
          {
            partial += weight[m];
          }
          total += partial;
        }
        scale = (1.0 - a) / total;
      }
      const double uniform = a / (double)M;
      const double h = mrgi_brsm_hash01(seed, (uint64_t)t);
      int32_t m = 0, b = 0;
      double below = 0.0; /* Q(m - 1): the mass of the samples before m */
      for (int32_t k = 0; k < K; ++k)
      {
        const double target = ((double)k + h) / (double)K; /* the first m with Q(m) > target */
        if (!guide)
        {
          m = (int32_t)(target * (double)M);
          m = m < M ? m : M - 1;
        }
        else
        {
          /* Skip whole blocks whose end is not past the target, then walk. */
          while (b + 1 < blocks)
          {
            const int32_t next = (b + 1) * MRGI_BRSM_GUIDE_BLOCK;
            const double at_next = scale * block_start[b + 1] + uniform * (double)next;
            if (at_next > target || next <= m)
            {
              break;
            }
            ++b;
            m = next;
            below = at_next;
          }
          while (m + 1 < M && below + scale * weight[m] + uniform <= target)
          {
            below += scale * weight[m] + uniform;
            ++m;
            b = m / MRGI_BRSM_GUIDE_BLOCK;
          }
        }
        const double q = guide ? scale * weight[m] + uniform : uniform;
        const double e =
          mrgi_brsm_contribution(&vpl, view->samples + (size_t)m * MRGI_BRSM_VIEW_SAMPLE_FLOATS);
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
