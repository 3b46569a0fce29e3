/**
 * @file mrgi_box_filter.h
 * @brief Box-filter downsampling: the resolve of supersampling (SSAA).
 *
 * An image rendered at `factor` times the width and height is averaged
 * over each factor x factor block into one pixel: out(x, y, c) =
 * mean over 0 <= i, j < factor of in(factor x + i, factor y + j, c), every
 * channel alike (alpha too). The mean is summed in double. An area that is
 * flat in the input stays exactly flat (the mean of equal floats is that
 * float); only blocks that straddle an edge get intermediate values.
 *
 * Callers averaging display values (8-bit read-backs) average what the
 * eye sees; callers averaging HDR radiance (EXR) average light.
 */
#ifndef MRGI_BOX_FILTER_H
#define MRGI_BOX_FILTER_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest supported supersampling factor per axis. */
#define MRGI_BOX_FILTER_MAX_FACTOR 16

/**
 * @brief Downsample `src` by `factor` per axis into a new image `dst`.
 * @param src    Valid image whose width and height are multiples of `factor`.
 * @param factor 1..MRGI_BOX_FILTER_MAX_FACTOR (1 copies).
 * @param dst    Receives a new image (treated as uninitialized; zeroed on failure),
 *               width/factor x height/factor, same channels. Must not be `src`.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for an invalid image, a factor out of
 *         range or a size that is not a multiple of it; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_box_downsample(
  const mrgi_image* src, int32_t factor, mrgi_image* dst, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
