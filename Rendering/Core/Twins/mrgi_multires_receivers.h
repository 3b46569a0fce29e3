/**
 * @file mrgi_multires_receivers.h
 * @brief The receivers of the multiresolution gather: one eye-space position
 *        and normal per texel of the flattened layout (mrgi_multires.h).
 *
 * A texel at level i stands for the valid full-resolution pixels of its
 * footprint (a 2^i x 2^i block, cut at the image edge). Its receiver is
 * their mean position and the normalized mean of their unit normals (the
 * "standard average mipmap" nichols-wyman-2009 section 3.4 gathers at), built
 * level by level from the finer level's 2x2 children, weighted by the
 * children's pixel counts. Unlike the min-max mipmaps, children outside the
 * finer level are skipped, not clamped: a mean must not count a pixel twice.
 *
 * Level 0: a pixel is valid as in mrgi_multires_mipmap_build() (w above the
 * G-buffer threshold, finite z and normal); position = its position, w = 1;
 * normal = its normal times 1/sqrt(max(|n|^2, MRGI_MULTIRES_MIN_PIXEL_SIZE)).
 * Level i > 0, children c with count w_c > 0:
 *   count = sum w_c;  position = (sum w_c * p_c) / count, w = count;
 *   normal = m / sqrt(max(|m|^2, MRGI_MULTIRES_MIN_PIXEL_SIZE)), m = sum w_c * n_c.
 * Sums run over the children in the order (0,0), (1,0), (0,1), (1,1), in
 * float, as the GLSL writes them. A texel without valid pixels holds zeros
 * (w = 0: not a receiver).
 *
 * The result is two RGBA float arrays in the flattened layout, rows
 * bottom-up, directly usable as mrgi_gather_receivers (position w is the
 * pixel count, > MRGI_VALID_THRESHOLD for every receiver): the C twin of the
 * multiresolution gather is mrgi_gather_full() on them.
 */
#ifndef MRGI_MULTIRES_RECEIVERS_H
#define MRGI_MULTIRES_RECEIVERS_H

#include "mrgi_error.h"
#include "mrgi_gather.h"
#include "mrgi_multires.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Build the receivers of every texel of `layout` from a G-buffer.
 * @param layout   From mrgi_multires_layout_init(), for the G-buffer's size.
 * @param gbuffer  W x H eye-space positions and normals (rows bottom-up).
 * @param position Receives 4 floats per flattened texel (mean xyz, count).
 * @param normal   Receives 4 floats per flattened texel (unit normal, 0).
 * @param count    Floats each array holds: at least 4 * mrgi_multires_texel_count().
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments, a layout not made for
 *         this G-buffer's size, or arrays too small.
 */
mrgi_status mrgi_multires_receivers_build(const mrgi_multires_layout* layout,
                                          const mrgi_gather_receivers* gbuffer, float* position,
                                          float* normal, size_t count, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
