/**
 * @file mrgi_brsm_temporal.h
 * @brief Temporal blend of the BRSM selection pdf: an exponential moving
 *        average over frames of the pdf mrgi_brsm_mix() makes (beyond
 *        RIHKS11, whose importance is re-estimated from scratch each frame).
 *
 * ## Why
 * The pdf is estimated every frame from K view samples per texel (RIHKS11
 * 4), so it changes from frame to frame even where the scene does not, and
 * VPLs drawn from it (stratified, mrgi_brsm_sample.h) move where a grid's
 * stay: the image flickers (issue 13's temporal target: BRSM no worse than
 * 256 grid VPLs). Averaging the pdf over frames, with weight a for this
 * frame, moves it by at most a per frame (a time constant of about 1/a
 * frames) and averages the estimates of about 2/a - 1 frames.
 *
 * ## Rule (mrgi_brsm_temporal_blend)
 * Over `count` texels, with p this frame's pdf and h the history (the
 * previous frame's blended pdf over the same texels):
 *     b_t = a p_t + (1 - a) h_t   where p_t > 0,   b_t = 0 where p_t = 0,
 *     p_t <- b_t / sum b,         h_t <- p_t.
 * Without a history (`has_history` 0) p is left as it is and copied to h.
 * So is a stale one: when the two pdfs, each normalised, share less than
 * MRGI_BRSM_HISTORY_MIN_OVERLAP of their mass (mrgi_brsm_temporal_overlap:
 * sum of min(p_t, h_t)), the scene changed at once (a cut, a light switched
 * or moved far) and the history would only cost variance for about 1/a
 * frames. Consecutive frames of a light or camera moving smoothly share
 * far more (Documentation/IndirectShadows.md, "Flicker").
 *
 * ## Unbiasedness
 * The VPL estimator divides each VPL's flux by N times the pdf it was drawn
 * from, so any pdf gives an unbiased estimate as long as it is positive
 * wherever the integrand is not zero. mrgi_brsm_mix() makes p_t > 0 for
 * every texel with flux (beta > 0), and b_t >= a p_t > 0 there, since
 * a > 0 and h >= 0. Texels with p_t = 0 carry no flux this frame; the
 * history there is dropped rather than spend VPLs on them. A stale history
 * (the light or the camera moved) costs variance, never bias.
 *
 * No allocation. Errors (::MRGI_ERR_INVALID_ARGUMENT) name the bad
 * argument; nothing is written on failure.
 */
#ifndef MRGI_BRSM_TEMPORAL_H
#define MRGI_BRSM_TEMPORAL_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Below this overlap of this frame's pdf and the history, the history is dropped. */
#define MRGI_BRSM_HISTORY_MIN_OVERLAP 0.5
/** Smallest weight a of this frame (0 would freeze the pdf and could leave a lit texel at p = 0). */
#define MRGI_BRSM_MIN_TEMPORAL_WEIGHT 0.001
/**
 * Default weight a of this frame in the blend (vtkMRGIVPLSelection::
 * BRSMTemporalWeight): a time constant of about 200 frames (the
 * stale-history rule keeps a cut from lasting that long). The VPLs move
 * about in proportion to a, since each frame's estimate is noisy; a
 * longer memory lags a moving light more (Documentation/IndirectShadows.md,
 * "Flicker", measures both). 1 turns the blend off.
 */
#define MRGI_BRSM_DEFAULT_TEMPORAL_WEIGHT 0.005

/**
 * @brief The mass two pdfs share once each is normalised, sum of
 *        min(p_t / sum p, h_t / sum h), in [0, 1]; 0 when either has no
 *        positive mass or for NULL. Negative values count as 0.
 */
double mrgi_brsm_temporal_overlap(const float* pdf, const float* history, size_t count);

/**
 * @brief In place: blend this frame's pdf with the history and store the
 *        result as the next history (see the file comment).
 * @param weight      a, MRGI_BRSM_MIN_TEMPORAL_WEIGHT..1.
 * @param pdf         `count` floats, finite and >= 0 (mrgi_brsm_mix()'s
 *                    output); receives the blended pdf (sums to 1 unless
 *                    every p_t is 0, which is left as it is).
 * @param history     `count` floats; read when `has_history` is non-zero
 *                    (finite, >= 0), always overwritten with the new pdf.
 * @param count       Texels, >= 1.
 * @param has_history 0 for the first frame (or after a reset): no blend.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL arrays, count 0, aliased
 *         arrays, a weight outside the range (or NaN), or a negative or
 *         non-finite pdf or history value.
 */
mrgi_status mrgi_brsm_temporal_blend(double weight, float* pdf, float* history, size_t count,
                                     int32_t has_history, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
