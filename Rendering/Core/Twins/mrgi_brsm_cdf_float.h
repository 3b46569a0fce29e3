/**
 * @file mrgi_brsm_cdf_float.h
 * @brief Float twin of the BRSM 2-D CDF inversion (RIHKS11 4.1, "column CDFs
 *        and a CDF of the column sums, inverted by binary search") that the
 *        GPU pass (glsl/main/vtkMRGIBRSMInvertFS.glsl) mirrors operation for
 *        operation, so both pick exactly the same texels and fractions.
 *        Spec: shared/plans/paper-specs.md, Package 2.4.
 *
 * ## Float CDF (mrgi_brsm_cdf_to_float)
 * The double CDF of mrgi_brsm_cdf_build() rounded to float, entry by entry
 * (rounding is monotone, so the columns stay non-decreasing), laid out as a
 * (V*S) x (S + 1) R32F texture: row x (x < S) = column x's CDF over the
 * R = V*S stacked rows, row S = the column-sum CDF in its first S entries,
 * the rest 0. mrgi_brsm_cdf_float_count() = R * (S + 1) floats. These floats
 * ARE what the GPU searches: upload them unchanged.
 *
 * ## Samples (mrgi_brsm_sample_values)
 * (u1, u2) of sample k are mrgi_brsm_sample.h's values (same seed, same
 * stratification and lattice) computed in double and rounded to float;
 * the GPU reads them from a texture instead of re-hashing (GLSL 1.50 has no
 * 64-bit integers). A value that rounds up to 1 takes the last texel with
 * positive weight, as in the double twin.
 *
 * ## Inversion (mrgi_brsm_cdf_float_invert), all in float
 *   W = sums[S-1]; none when !(W > 0);
 *   t1 = u1 * W; x = first x with sums[x] > t1 (past the end: the last x
 *   with a positive step); fx = clamp((t1 - sums[x-1]) / (sums[x] - sums[x-1]), 0, 1)
 *   (0.5 for a zero step; sums[-1] = 0);
 *   t2 = u2 * column_x[R-1]; r likewise in column x; fy likewise;
 *   p = (column_x[r] - column_x[r-1]) / W.
 * Each step is one IEEE float operation, which the GPU rounds identically
 * as long as it keeps division correctly rounded and does not contract
 * u*W - c into a fused multiply-add (checked by cxx.TestMRGIBRSM).
 *
 * ## Texel VPL record (mrgi_brsm_float_vpl)
 * The texel's position and normal, Phi_k = Phi_t * s, A_k = A_t * s with
 * s = 1 / (float(N) * p), in float (mrgi_brsm_sample.h's inter_texel = 0
 * record with the float p; the GPU agrees to float rounding).
 */
#ifndef MRGI_BRSM_CDF_FLOAT_H
#define MRGI_BRSM_CDF_FLOAT_H

#include "mrgi_brsm_sample.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Floats of the float CDF texture: V*S * (S + 1) (0 for a bad RSM size). */
size_t mrgi_brsm_cdf_float_count(const mrgi_rsm* rsm);

/**
 * @brief Round a built double CDF (mrgi_brsm_cdf_build) into the texture layout.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming a short array or a bad RSM.
 */
mrgi_status mrgi_brsm_cdf_to_float(const mrgi_rsm* rsm, const double* cdf, size_t cdf_count,
                                   float* out, size_t out_count, mrgi_error* err);

/**
 * @brief (u1, u2) of the N samples as floats, interleaved: out[2k], out[2k+1].
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad N or a short array.
 */
mrgi_status mrgi_brsm_sample_values(int32_t count, uint64_t seed, float* out, size_t out_count,
                                    mrgi_error* err);

/** @brief Invert the float CDF; 1 with `pick` filled, 0 when W = 0. No checks. */
int mrgi_brsm_cdf_float_invert(const mrgi_rsm* rsm, const float* cdf, float u1, float u2,
                               mrgi_brsm_pick* pick);

/** @brief Texel VPL of `pick` for N samples (see the file comment); zero when pdf = 0. */
void mrgi_brsm_float_vpl(const mrgi_rsm* rsm, const mrgi_brsm_pick* pick, int32_t count,
                         mrgi_vpl* vpl);

#ifdef __cplusplus
}
#endif

#endif
