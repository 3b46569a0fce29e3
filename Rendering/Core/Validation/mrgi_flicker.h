/**
 * @file mrgi_flicker.h
 * @brief Temporal flicker of an image sequence against a reference sequence.
 *
 * Issue 12 part 6. Temporal incoherence from VPLs that change between
 * frames is problem 2 of instant radiosity in nichols-shopf-wyman-2009
 * (section 2; figure 5 shows the frame-to-frame differences of 256 RSM
 * VPLs, ISR and HISR); this is a number for it. For K frames I_0..I_{K-1}
 * of a method and R_0..R_{K-1} of the reference, rendered along the same
 * light path or camera path,
 *
 *     F = mean over k in [0, K-2] of  rms((I_{k+1} - I_k) - (R_{k+1} - R_k)) / rms(R_k)
 *
 * i.e. the part of the method's frame-to-frame change that the reference
 * does not have, relative to the reference's brightness. A method that
 * follows the reference's motion exactly (I = R, or I = R + a constant
 * offset, a constant bias) has F = 0, however wrong each frame is; the
 * per-frame error is a separate metric (mrgi_metrics.h).
 *
 * Contract:
 * - rms(X) = sqrt(mean of X^2 over all pixels and the compared channels),
 *   in double. No mask: a pixel zero in all four frames of a pair adds 0
 *   to both numerator and denominator sums and the same count to both
 *   means, so black background does not change a pair's ratio.
 * - Compared channels: the first 3 when both sequences have >= 3 channels
 *   (an RGBA GPU image against an RGB reference: alpha ignored); otherwise
 *   every channel, and both sequences must then have the same count.
 * - Box averaging: with box = n > 1 every frame is first replaced by the
 *   means of its n x n pixel boxes (rows and columns past the last whole
 *   box dropped), as the issues' "4x4 box-averaged" errors are; box = 1 is
 *   per pixel. Computed on the fly, no allocation.
 * - A pair whose rms(R_k) is 0 (black reference frame) is excluded from the
 *   mean and counted in pairs_excluded; if every pair is excluded F is
 *   undefined and that is an error.
 * - Values are unitless ratios >= 0 (the images' units cancel).
 *
 * Errors (::MRGI_ERR_INVALID_ARGUMENT, message naming the problem): NULL
 * pointers, fewer than 2 frames, an invalid image, frames of different
 * sizes or channel counts within or across the sequences, box < 1 or larger
 * than a frame's width or height, NaN or infinity in a frame (the message
 * says which sequence and frame and how many values), every reference frame
 * of the pairs black.
 */
#ifndef MRGI_FLICKER_H
#define MRGI_FLICKER_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** One pair (k, k+1) of a sequence. */
typedef struct mrgi_flicker_pair
{
  double change_rms;    /**< rms((I_{k+1} - I_k) - (R_{k+1} - R_k)). */
  double reference_rms; /**< rms(R_k). */
  double value;         /**< change_rms / reference_rms; 0 when excluded. */
  int excluded;         /**< 1 when reference_rms is 0 (value then means nothing). */
} mrgi_flicker_pair;

/** Result of mrgi_flicker_sequence(). */
typedef struct mrgi_flicker_result
{
  double flicker;         /**< F: mean of the counted pairs' values. */
  double max_pair;        /**< Largest counted pair value. */
  int32_t pairs_counted;  /**< Pairs in the mean (K - 1 - pairs_excluded). */
  int32_t pairs_excluded; /**< Pairs skipped because rms(R_k) = 0. */
} mrgi_flicker_result;

/**
 * @brief The term of one pair: I_k = image0, I_{k+1} = image1, R_k = ref0, R_{k+1} = ref1.
 *
 * @param box Box side in pixels, >= 1 (1 = per pixel).
 * @param out Receives the pair; untouched on failure. A black ref0 is not
 *            an error here: the pair comes back with excluded = 1.
 * @return The errors of the file comment (except "every pair excluded").
 */
mrgi_status mrgi_flicker_compute_pair(const mrgi_image* image0, const mrgi_image* image1,
                                      const mrgi_image* ref0, const mrgi_image* ref1, int32_t box,
                                      mrgi_flicker_pair* out, mrgi_error* err);

/**
 * @brief F over a sequence of `count` frames.
 *
 * @param images     count frames I_k.
 * @param references count frames R_k.
 * @param count      K >= 2.
 * @param box        Box side in pixels, >= 1.
 * @param pairs      NULL or room for count - 1 pair terms (filled in order).
 * @param out        Receives F; untouched on failure.
 * @return The errors of the file comment.
 */
mrgi_status mrgi_flicker_sequence(const mrgi_image* images, const mrgi_image* references,
                                  int32_t count, int32_t box, mrgi_flicker_pair* pairs,
                                  mrgi_flicker_result* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
