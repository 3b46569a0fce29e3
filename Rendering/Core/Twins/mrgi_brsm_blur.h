/**
 * @file mrgi_brsm_blur.h
 * @brief Geometry-aware blur of the BRSM importance (RIHKS11 6.5: "a
 *        geometry-aware blur kernel (of approximate 1% of the BRSM)";
 *        spec: shared/plans/paper-specs.md, Package 2.3).
 *
 * out_t = sum_s g_ts a_ts in_s / sum_s g_ts a_ts over the texels s of t's
 * view with |x_s - x_t| <= r and |y_s - y_t| <= r, where
 * - r = max(1, round(MRGI_BRSM_BLUR_RADIUS_SHARE * S)) texels,
 * - g_ts = exp(-d^2 / (2 sigma^2)), d the texel distance, sigma = r / 2,
 * - a_ts = 1 when s is usable and on t's surface (mrgi_brsm_same_surface()),
 *   0 otherwise; a_tt = 1.
 * Non-usable texels get 0. The weights are >= 0 with g_tt a_tt = 1 > 0, so
 * the output is a convex combination of the input: >= 0 and finite when the
 * input is, never mixing two surfaces. No allocation; `in` and `out` must
 * not overlap.
 */
#ifndef MRGI_BRSM_BLUR_H
#define MRGI_BRSM_BLUR_H

#include "mrgi_error.h"
#include "mrgi_vpl.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Blur radius as a share of the RSM side (RIHKS11 6.5: about 1%). */
#define MRGI_BRSM_BLUR_RADIUS_SHARE 0.01
/** Same surface: normals' dot product above this (paper-specs 2.3). */
#define MRGI_BRSM_SAME_SURFACE_COS 0.9
/** Same surface: world distance below this many texel sizes sqrt(A_t) (paper-specs 2.3). */
#define MRGI_BRSM_SAME_SURFACE_TEXELS 2.0

/** @brief Blur radius r in texels for RSM side S (see the file comment). */
int32_t mrgi_brsm_blur_radius(int32_t size);

/**
 * @brief 1 when usable texels t and s lie on one surface: n_t . n_s >
 *        MRGI_BRSM_SAME_SURFACE_COS and |P_t - P_s| < MRGI_BRSM_SAME_SURFACE_TEXELS
 *        * sqrt(max(A_t, A_s)) * texel_distance (the distance two texels apart
 *        on one flat surface may have). No checks (inner loop).
 */
int mrgi_brsm_same_surface(const mrgi_rsm* rsm, int64_t t, int64_t s, double texel_distance);

/**
 * @brief Blur `in` (V*S*S floats, >= 0, finite) into `out`.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad RSM, NULL, short or
 *         overlapping arrays, or a negative or non-finite input value.
 */
mrgi_status mrgi_brsm_blur(const mrgi_rsm* rsm, const float* in, float* out, size_t count,
                           mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
