/**
 * @file mrgi_brsm_sample.h
 * @brief VPLs drawn from a weight map over the RSM texels with a 2-D CDF
 *        (RIHKS11 4.1, "importance sampling ... column CDFs and a CDF of the
 *        column sums, inverted by binary search") and inter-texel VPLs with
 *        geometry-aware bilinear weights (RIHKS11 6.5). Spec:
 *        shared/plans/paper-specs.md, Package 2.4-2.5.
 *
 * ## The CDF (mrgi_brsm_cdf_build)
 * The V views are stacked vertically: R = V*S rows, S columns; texel (x, y)
 * of view v is row r = v*S + y. Weights w_t (e.g. mrgi_brsm_mix() output)
 * must be >= 0 and finite; non-usable texels count as 0. In double:
 * - column CDFs: cdf[x*R + r] = sum_{r' <= r} w(x, r')   (S*R values),
 * - column-sum CDF: cdf[S*R + x] = sum_{x' <= x} column total(x')  (S values).
 * mrgi_brsm_cdf_count() = S*R + S doubles.
 *
 * ## Samples and inversion (mrgi_brsm_sample_vpls)
 * xi1 = mrgi_brsm_hash01(seed, 0), xi2 = mrgi_brsm_hash01(seed, 1); sample k of N:
 *   u1 = (k + xi1) / N,  u2 = frac(xi2 + k * MRGI_BRSM_LATTICE_STEP)
 * (u1 stratified in N strata, u2 a randomly shifted rank-1 lattice: for a
 * random seed each (u1, u2) is uniform on its stratum x [0, 1), and the
 * strata tile [0, 1)^2 once, so the sum below is unbiased for any N).
 * Column x = first x with cdf_x[x] > u1 * W, fraction
 * fx = (u1 W - cdf_x[x-1]) / (cdf_x[x] - cdf_x[x-1]); row r = first r with
 * cdf[x*R + r] > u2 * total(x), fraction fy likewise (binary searches;
 * rounding past the end takes the last entry with positive weight).
 * The texel's probability is p_t = w_t / W: the sampled point (x + fx,
 * r + fy) has the piecewise-constant density p_t inside texel t.
 *
 * ## VPL records (mrgi_vpl.h layout)
 * inter_texel = 0: VPL k = texel t's position and normal with
 *     Phi_k = Phi_t / (N p_t), A_k = A_t / (N p_t)
 * (exactly mrgi_vpl_select_importance()'s record; E[sum Phi_k] = sum_t Phi_t
 * over texels with w_t > 0, i.e. over all texels with flux when the weights
 * come from mrgi_brsm_mix() with beta > 0: the estimator is unbiased).
 * inter_texel = 1 (RIHKS11 6.5): the four texels T_i around the point
 * (centres at i + 1/2, clamped to the view) with bilinear weights w_i;
 * T_0 = the sampled texel (the nearest); g_0 = 1 and for i > 0
 *     g_i = [T_i usable, w > 0 and on T_0's surface (mrgi_brsm_same_surface)]
 *           * exp(-|pi(T_i) - pi(T_0)|^2 / (2 * MRGI_BRSM_INTER_TEXEL_VARIANCE))
 * with pi the NDC position through `world_to_clip` (the paper's Gaussian of
 * variance 0.01 in post-projective space; omitted when NULL or behind the
 * camera). The hard same-surface gate is beyond the paper: it keeps a VPL
 * from ever floating across a depth step. With c_i = w_i g_i / sum w g:
 * position = sum c_i P_i, normal = normalize(sum c_i N_i), radiance
 * L = sum c_i Phi_i / A_i, area A = sum c_i A_i, p = sum c_i p_i, and
 *     Phi_k = L A / (N p),  A_k = A / (N p).
 * The paper does not say how it weights flux; this choice keeps the
 * radiance continuous and equals the texel record when the neighbours are
 * alike, but it is only consistent (bias of the order of the variation of
 * Phi/p over one texel), not unbiased; inter_texel = 0 is the exact estimator.
 *
 * Errors (::MRGI_ERR_INVALID_ARGUMENT) name the argument; nothing is written
 * on failure. W = 0 gives N all-zero VPLs (info.empty_vpl_count = N).
 */
#ifndef MRGI_BRSM_SAMPLE_H
#define MRGI_BRSM_SAMPLE_H

#include "mrgi_error.h"
#include "mrgi_vpl.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Step of the u2 rank-1 lattice: the golden ratio's fractional part. */
#define MRGI_BRSM_LATTICE_STEP 0.6180339887498949
/** Variance of the inter-texel Gaussian in NDC (RIHKS11 6.5: "a variance of 0.01"). */
#define MRGI_BRSM_INTER_TEXEL_VARIANCE 0.01

/** Where sample k landed: texel and fractional position inside it. */
typedef struct mrgi_brsm_pick
{
  int32_t view;   /**< View v. */
  int32_t x;      /**< Texel column, 0..S-1. */
  int32_t y;      /**< Texel row inside the view, 0..S-1. */
  float fx;       /**< Fraction along x inside the texel, [0, 1]. */
  float fy;       /**< Fraction along y inside the texel, [0, 1]. */
  float pdf;      /**< p_t = w_t / W of the picked texel (0 only when W = 0). */
} mrgi_brsm_pick;

/** How to sample. */
typedef struct mrgi_brsm_sampling
{
  int32_t count;              /**< N, MRGI_VPL_MIN_COUNT..MRGI_VPL_MAX_COUNT. */
  uint64_t seed;              /**< Any value; the same seed gives the same VPLs. */
  int32_t inter_texel;        /**< 1: RIHKS11 6.5 inter-texel VPLs, 0: texel VPLs. */
  const float* world_to_clip; /**< Column-major camera matrix for g_i, or NULL. */
} mrgi_brsm_sampling;

/** @brief Doubles of the 2-D CDF: S*V*S + S (0 for a bad RSM size). */
size_t mrgi_brsm_cdf_count(const mrgi_rsm* rsm);

/**
 * @brief Build the 2-D CDF of `weights` (V*S*S floats, >= 0, finite).
 * @param total Receives W (may be NULL).
 */
mrgi_status mrgi_brsm_cdf_build(const mrgi_rsm* rsm, const float* weights, size_t weight_count,
                                double* cdf, size_t cdf_count, double* total, mrgi_error* err);

/**
 * @brief Invert the CDF at (u1, u2) in [0, 1)^2 (see the file comment).
 * @return 1 with `pick` filled, 0 when W = 0. No checks (per sample).
 */
int mrgi_brsm_cdf_invert(const mrgi_rsm* rsm, const double* cdf, double u1, double u2,
                         mrgi_brsm_pick* pick);

/**
 * @brief N VPLs from a built CDF.
 * @param picks    Receives N picks, or NULL.
 * @param vpls     Receives N records; `capacity` >= N.
 */
mrgi_status mrgi_brsm_sample_vpls(const mrgi_rsm* rsm, const double* cdf, size_t cdf_count,
                                  const mrgi_brsm_sampling* sampling, mrgi_brsm_pick* picks,
                                  mrgi_vpl* vpls, int32_t capacity,
                                  mrgi_vpl_selection_info* out_info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
