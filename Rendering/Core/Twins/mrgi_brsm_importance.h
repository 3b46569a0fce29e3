/**
 * @file mrgi_brsm_importance.h
 * @brief Bidirectional RSM (BRSM) importance: how much each RSM texel,
 *        used as a VPL, lights a few view samples (Ritschel et al. 2011,
 *        "Making Imperfect Shadow Maps View-Adaptive", RIHKS11 4 and 4.2;
 *        spec: shared/plans/paper-specs.md, Package 2.1-2.3).
 *
 * ## View samples (the "small view-sample texture")
 * M = 1..MRGI_BRSM_MAX_VIEW_SAMPLES points of the frame's G-buffer in world
 * space, MRGI_BRSM_VIEW_SAMPLE_FLOATS floats each (3 RGBA texels, so the
 * array is also the GPU texture's memory, 3 texels wide, M rows tall):
 * position xyz + pixel x, unit normal xyz + pixel y, albedo rgb + valid flag
 * (> MRGI_VALID_THRESHOLD). Pixel x, y are the sample's window coordinates
 * (pixel centres at i + 1/2) in a viewport of width x height pixels.
 * Invalid or non-finite samples count as receiving nothing.
 *
 * ## Importance of texel t (mrgi_brsm_importance)
 * With E_tm = lum(albedo_m * Phi_t * T(t, m)), T the gather's transfer of a
 * VPL at the texel (mrgi_gather.h, NSW09 eq. 1: cos cos / (r^2 (pi r^2 + A_t))),
 * the texel's importance is the ROOT MEAN SQUARE of its contributions,
 *     I_t = sqrt((1/M) sum_m E_tm^2),
 * not their mean (RIHKS11 4: "each pVPL's average contribution"). Why
 * (beyond the paper): with N VPLs drawn from p, the variance of pixel m's
 * estimate is (1/N) (sum_t E_tm^2 / p_t - E_m^2); summed over the pixels,
 * sum_t S_t / p_t with S_t = sum_m E_tm^2, which is least for p_t
 * proportional to sqrt(S_t) (Lagrange; the image's L2 error, the error this
 * project measures). The mean weights a texel by its total light; the RMS
 * also by how concentrated that light is, so texels near a receiver (the
 * corners of RIHKS11 figure 5, whose 1/r^2 peaks light few pixels
 * strongly) get more VPLs. Measured in Documentation/IndirectShadows.md
 * (`corner`, `u-shape`). The pdf stays unbiased whatever I_t is: only
 * p_t > 0 where the integrand is nonzero matters (the flux mix below).
 *
 * Guided selection (RIHKS11 4.2): the texel draws K view
 * samples from the M with probability
 *     q_m = (1 - a) c_m / sum c + a / M,   c_m = min(1, R^2 / x_m^2)
 * where x_m is the pixel distance from sample m to the texel's projection
 * through `world_to_clip` (the paper's 1/x^2 fall-off clamped to 1, with
 * the clamp radius R = MRGI_BRSM_GUIDE_RADIUS pixels), mixed with a share
 * a = MRGI_BRSM_GUIDE_UNIFORM_SHARE of the uniform choice. The mixture is
 * beyond the paper: the guide assumes a texel lights the receivers near its
 * own projection, which fails when the texel is hidden from the camera
 * (u-shape: the lit arm projects onto the wall in front of it, whose
 * receivers it cannot light); the pure guide then draws almost only zeros
 * and, rarely, a hit divided by a tiny q, a heavy-tailed estimate whose
 * outliers become VPLs of huge weight. The mixture bounds each draw's
 * weight by E_m^2 / a (defensive importance sampling). A texel behind the
 * camera (clip w <= 0), a NULL matrix, or guidance off use q_m = 1/M.
 * Draw k of texel t uses u = (k + h) / K, h = hash(seed, t) in [0, 1)
 * (stratified over the texel's CDF of q). The estimate
 *     I_t = sqrt((1/K) sum_k E_{t m_k}^2 / (M q_{m_k}))
 * squares an unbiased estimate of the mean square over the M samples
 * (E[E_m^2/(M q_m)] = (1/M) sum E_m^2), whatever the guide, as long as
 * q_m > 0 for every m, which min(1, R^2/x^2) > 0 guarantees (the root
 * itself is biased low by Jensen, which only shapes the pdf). K >= M
 * without guidance gives the exact RMS (every sample once). Non-usable
 * texels (mrgi_vpl.h) get 0.
 *
 * ## Mixing with flux importance (mrgi_brsm_mix)
 * p_t = (1 - beta) I_t / sum I + beta w_t / sum w, w_t = lum(Phi_t) of the
 * usable texels (as mrgi_vpl_select_importance()). Beyond the paper: any
 * texel with flux has w_t > 0, so p_t >= beta w_t / sum w > 0 and the VPL
 * estimator (weights 1/(N p)) stays unbiased; a texel whose view samples all
 * missed it (I_t = 0) can still be picked. RIHKS11 accepts that bias
 * silently. sum I = 0 gives p = flux importance. Texels without flux get
 * p = 0 (the blur may have spread importance onto them; a VPL there would
 * carry nothing, and p = 0 where the integrand is 0 costs no bias).
 *
 * Neither function allocates. Errors (::MRGI_ERR_INVALID_ARGUMENT) name the
 * bad argument; nothing is written on failure.
 */
#ifndef MRGI_BRSM_IMPORTANCE_H
#define MRGI_BRSM_IMPORTANCE_H

#include "mrgi_error.h"
#include "mrgi_vpl.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Floats per view sample (3 RGBA texels): position+px, normal+py, albedo+valid. */
#define MRGI_BRSM_VIEW_SAMPLE_FLOATS 12
/** Most view samples one importance pass reads (a 32 x 32 subsample of the G-buffer). */
#define MRGI_BRSM_MAX_VIEW_SAMPLES 1024
/**
 * Default view samples K drawn per texel. RIHKS11 4 evaluates "a few randomly
 * chosen view samples (in practice, ~0.1%)" of the frame's, about 1000 at
 * 1024^2; 32 keeps the CPU cost small while the estimate's noise no longer
 * dominates the selection's error (16, 32 and 64 compared in
 * Documentation/IndirectShadows.md).
 */
#define MRGI_BRSM_DEFAULT_SAMPLES_PER_TEXEL 32
/** View samples per block of the guided draw's walk (mrgi_brsm_importance.c; no effect on results). */
#define MRGI_BRSM_GUIDE_BLOCK 32
/** Radius R in pixels inside which the guide's 1/x^2 fall-off is clamped to 1 (RIHKS11 4.2). */
#define MRGI_BRSM_GUIDE_RADIUS 8.0
/**
 * Share a of the uniform choice in the guided draw (defensive mixture,
 * Hesterberg 1995; beyond RIHKS11 4.2): q_m = (1 - a) c_m / sum c + a / M.
 */
#define MRGI_BRSM_GUIDE_UNIFORM_SHARE 0.5
/** Default share beta of flux importance in the mix (paper-specs 2.3). */
#define MRGI_BRSM_DEFAULT_FLUX_SHARE 0.1

/** Parameters of mrgi_brsm_importance(). */
typedef struct mrgi_brsm_view
{
  const float* samples;        /**< M * MRGI_BRSM_VIEW_SAMPLE_FLOATS floats (see the file comment). */
  int32_t sample_count;        /**< M, 1..MRGI_BRSM_MAX_VIEW_SAMPLES. */
  const float* world_to_clip;  /**< Column-major 4x4 world -> clip of the camera, or NULL (no guide). */
  int32_t width;               /**< Viewport width in pixels (>= 1 when world_to_clip is set). */
  int32_t height;              /**< Viewport height in pixels (>= 1 when world_to_clip is set). */
  int32_t samples_per_texel;   /**< K, 1..MRGI_BRSM_MAX_VIEW_SAMPLES. */
  int32_t guided;              /**< 1: RIHKS11 4.2 guide, 0: uniform choice (RIHKS11 4). */
} mrgi_brsm_view;

/**
 * @brief Per-texel BRSM importance I_t >= 0 (finite; the RMS contribution) of all V*S*S texels.
 * @param rsm        Valid RSM (mrgi_rsm_validate()).
 * @param view       View samples and guide; see mrgi_brsm_view.
 * @param seed       Any value; the same seed gives the same importance.
 * @param importance Receives V*S*S floats (texel order of mrgi_vpl.h).
 * @param capacity   Floats `importance` holds; at least V*S*S.
 */
mrgi_status mrgi_brsm_importance(const mrgi_rsm* rsm, const mrgi_brsm_view* view, uint64_t seed,
                                 float* importance, size_t capacity, mrgi_error* err);

/**
 * @brief In place: importance[t] = (1 - beta) I_t / sum I + beta w_t / sum w
 *        (see the file comment); 0 for non-usable texels.
 * @param beta 0..1; 0 is pure BRSM (biased where I_t = 0), 1 pure flux.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad RSM, beta, size, or a
 *         negative or non-finite importance.
 */
mrgi_status mrgi_brsm_mix(const mrgi_rsm* rsm, double beta, float* importance, size_t count,
                          mrgi_error* err);

/** @brief Hash of (seed, index) to [0, 1) shared by the BRSM stages (SplitMix64 finaliser). */
double mrgi_brsm_hash01(uint64_t seed, uint64_t index);

#ifdef __cplusplus
}
#endif

#endif
