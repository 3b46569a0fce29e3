/**
 * @file mrgi_reference_noise.h
 * @brief The ground truth's stopping statistic: a percentile of the per-pixel
 *        relative standard error of a progressive Monte Carlo image.
 *
 * Why per pixel: the error the project measures (relative RMS per pixel and
 * on 4x4 boxes, mrgi_metrics.h) compares pixels, so the truth must be
 * converged per pixel. The older rule, the relative standard error of the
 * IMAGE MEAN, is sqrt(N) times smaller than the per-pixel error on N pixels
 * (256 on a 256x256 image): at 0.01 it stopped the Cornell box after two
 * passes with 0.30 relative RMS of noise per pixel (issue 12, part 4).
 *
 * Inputs, per pixel i of `count` (the progressive renderer's Welford
 * accumulators of its per-pass estimates e_k, k = 1..n):
 * - mean[i]: the mean of e_k (radiance units of the scene, >= 0);
 * - m2[i]: the sum of squared deviations from that mean (>= 0);
 * - mask[i]: non-zero where the pixel counts (a surface was hit); others
 *   are left out of everything below.
 *
 * Statistic, over the M counted pixels, after n passes:
 *   s_i   = sqrt(m2[i] / ((n - 1) n))         standard error of the pixel's mean
 *   floor = MRGI_REFERENCE_NOISE_FLOOR * (sum of mean[i]) / M
 *   r_i   = s_i / max(mean[i], floor)
 *   error = the `percentile` quantile of r_i, nearest rank: the k-th smallest
 *           r_i with k = max(1, ceil(percentile * M)).
 * Why the floor is the image's mean pixel value: the metrics divide the
 * per-pixel difference by the image's mean (relative RMS), so a dark pixel's
 * noise matters in units of that mean, not of its own value (relative to
 * itself, a nearly black pixel in a corner would never converge and would
 * hold the whole image back). Pixels brighter than the mean are held to
 * their own value, which is stricter.
 *
 * Special values (never NaN):
 * - 0 when nothing is counted, or the counted mean is 0 (no light at all:
 *   known exactly);
 * - +infinity when n < 2 and there is light (the spread is unknown).
 *
 * Determinism: the quantile is a selection (no randomness), so the value
 * depends on the inputs only.
 */
#ifndef MRGI_REFERENCE_NOISE_H
#define MRGI_REFERENCE_NOISE_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The floor of r_i's denominator, as a fraction of the image's mean pixel value (file comment). */
#define MRGI_REFERENCE_NOISE_FLOOR 1.0

/** Default percentile of the per-pixel relative standard error that must reach the target. */
#define MRGI_REFERENCE_DEFAULT_PERCENTILE 0.95

/**
 * @brief The nearest-rank quantile of `values`: the k-th smallest value, with
 *        k = max(1, ceil(percentile * count)).
 *
 * Reorders `values` (a selection, O(count) expected; no allocation).
 * @param values     count finite values, reordered by the call.
 * @param count      >= 1.
 * @param percentile In (0, 1].
 * @param out        Receives the quantile.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, count 0 or a
 *         percentile outside (0, 1].
 */
mrgi_status mrgi_reference_quantile(double* values, size_t count, double percentile, double* out,
                                    mrgi_error* err);

/**
 * @brief The per-pixel stopping statistic of the file comment.
 *
 * @param mean, m2, mask count values each (see the file comment).
 * @param count      Pixels, >= 1.
 * @param passes     n, >= 1.
 * @param percentile In (0, 1] (MRGI_REFERENCE_DEFAULT_PERCENTILE).
 * @param scratch    count doubles the call may overwrite (allocate once,
 *                   reuse every pass).
 * @param error      Receives the statistic (0, finite >= 0 or +inf).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, count 0, passes < 1
 *         or a percentile outside (0, 1].
 */
mrgi_status mrgi_reference_pixel_error(const double* mean, const double* m2, const uint8_t* mask,
                                       size_t count, int32_t passes, double percentile,
                                       double* scratch, double* error, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
