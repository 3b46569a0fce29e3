/**
 * @file mrgi_metrics.h
 * @brief Error of an image against a reference of the same size.
 *
 * All sums run over the compared pixels (those the mask does not ignore)
 * and all their channels, in double precision. Every reported metric is
 * finite (never NaN or infinity), so results can go straight into CSV/JSON:
 *
 * - relative_rms = ||test - ref|| / ||ref|| (Euclidean norms). When ||ref|| = 0
 *   it is 0 if the test is also all zero, else DBL_MAX ("infinitely wrong").
 * - psnr_db = 10 log10(peak^2 / MSE), capped at ::MRGI_METRICS_PSNR_MAX_DB;
 *   identical images report exactly that cap.
 * - ssim follows Wang et al. 2004 (eq. 13, sample (co)variances over N-1)
 *   on a single plane: the channel itself for 1 channel, Rec. 709 luminance
 *   0.2126 R + 0.7152 G + 0.0722 B for 3 or 4 channels (alpha ignored), the
 *   channel mean otherwise. Windows are ::MRGI_METRICS_SSIM_WINDOW pixels
 *   square (smaller if the image is), uniform weights, sliding by one pixel;
 *   windows containing any ignored pixel are skipped; ssim is the mean over
 *   the rest. C1 = (0.01 peak)^2, C2 = (0.03 peak)^2.
 */
#ifndef MRGI_METRICS_H
#define MRGI_METRICS_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** PSNR reported for identical images, and the ceiling of every PSNR. */
#define MRGI_METRICS_PSNR_MAX_DB 100.0
/** Side of the square SSIM window, in pixels. */
#define MRGI_METRICS_SSIM_WINDOW 8

/** Result of mrgi_metrics_compare(). */
typedef struct mrgi_metrics
{
  double relative_rms;     /**< ||test-ref|| / ||ref||; see the file comment for ||ref|| = 0. */
  double rms;              /**< sqrt(mean squared difference) over compared values. */
  double max_abs_error;    /**< Largest |test - ref| over compared values. */
  double psnr_db;          /**< 10 log10(peak^2 / MSE), at most MRGI_METRICS_PSNR_MAX_DB. */
  double ssim;             /**< Mean SSIM in [-1, 1]; 0 when ssim_windows is 0. */
  int64_t compared_pixels; /**< Pixels not ignored by the mask. */
  int64_t ssim_windows;    /**< Windows averaged into ssim; 0 = SSIM undefined (every window masked). */
} mrgi_metrics;

/**
 * @brief Compare `test` against `reference`.
 *
 * @param test      Valid image.
 * @param reference Valid image with the same width, height and channels.
 * @param mask      NULL (compare every pixel) or width*height bytes, row 0 = top;
 *                  a non-zero byte means "ignore this pixel".
 * @param peak      Largest meaningful value (1 for [0,1] images), finite and > 0;
 *                  used by PSNR and the SSIM constants.
 * @param out       Receives the metrics; untouched on failure.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL/invalid images, a size or
 *         channel mismatch, NaN or infinity in a compared pixel of either
 *         image (the message gives the count), a mask that ignores every
 *         pixel, a bad peak; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_metrics_compare(const mrgi_image* test, const mrgi_image* reference,
                                 const uint8_t* mask, double peak, mrgi_metrics* out,
                                 mrgi_error* err);

/**
 * @brief Per-value absolute difference |test - reference|, for pictures of the error.
 *
 * @param out_diff Receives a new image with the inputs' size and channel
 *                 count (treated as uninitialized; zeroed on failure).
 *                 Ignored pixels are 0.
 * @return The same input errors as mrgi_metrics_compare() (peak aside).
 */
mrgi_status mrgi_metrics_difference_image(const mrgi_image* test, const mrgi_image* reference,
                                          const uint8_t* mask, mrgi_image* out_diff,
                                          mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
