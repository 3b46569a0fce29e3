/**
 * @file mrgi_rsm_composite.h
 * @brief Depth compositing of two renderings of one reflective shadow map
 *        (RSM) view: the reduction that gives every MPI rank the same RSMs.
 *
 * With partitioned data each rank renders the RSM views of the same lights
 * (the same cameras) over its own geometry only. Keeping, texel by texel,
 * the record nearest the light over all ranks gives what one process would
 * have rendered over all the geometry (the depth test's result), so VPL
 * selection then sees the same maps on every rank.
 *
 * **Layout (planar, the RSM's own):** a view of `texels` texels is one float
 * array of 3 planes, each `texels` x 4 floats (RGBA, rows as read back):
 * plane MRGI_RSM_POSITION (world position xyz, w = MRGI_GBUFFER_VALID or 0),
 * plane MRGI_RSM_NORMAL (world normal, w = 0), plane MRGI_RSM_FLUX (flux
 * rgb, w = texel area); see mrgi_buffers.h. A texel's record is its 12
 * floats (4 of each plane).
 *
 * **Nearest:** the RSM keeps no depth channel, so the depth is recomputed
 * from the world position (mrgi_rsm_composite_depth()): for a perspective
 * view the distance from the light, for an orthographic view the distance
 * along the view direction. Along one texel's ray both order surfaces as
 * the depth buffer did.
 *
 * **Empty and invalid texels:** a record is *valid* when its position w is
 * above MRGI_GBUFFER_VALID_THRESHOLD and all 12 floats are finite; any other
 * record (cleared texels, NaN/Inf) is *empty*, infinitely far, and comes out
 * as 12 zeros (the cleared texel), so no NaN leaves the composite.
 *
 * **The operation is a minimum over a total order**, so it is commutative
 * and associative as MPI requires, and its result is always one of its
 * inputs (bit for bit) or the zero record: valid records order by depth,
 * then, at equal depth, by their 12 floats' bit patterns read as unsigned
 * 32-bit integers, compared lexicographically (the smaller wins); the zero
 * record is after every valid one. An all-zero view is the identity (for
 * valid texels; empty ones come out as zeros).
 *
 * Unlit or normal-less geometry writes empty texels in an RSM (it reflects
 * nothing), so after compositing it no longer hides geometry of another
 * rank behind it, as it would in one process.
 */
#ifndef MRGI_RSM_COMPOSITE_H
#define MRGI_RSM_COMPOSITE_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Floats per texel over the three planes (position, normal, flux RGBA). */
#define MRGI_RSM_COMPOSITE_RECORD_FLOATS 12

/** What "near" means in one view. Plain data. */
typedef struct mrgi_rsm_view_key
{
  /** Perspective: the light's world position. Orthographic: any point (depths are relative to it).
   */
  double origin[3];
  /** Orthographic only: the view direction (towards the geometry), any non-zero length. */
  double direction[3];
  /** 1: perspective view (depth = |p - origin|); 0: orthographic (depth = (p - origin) . direction
   * / |direction|). */
  int32_t perspective;
} mrgi_rsm_view_key;

/**
 * @brief Depth of texel `i` of a planar view (see the file comment), or
 *        +infinity when the texel is empty or invalid.
 * @param view   Planar view of `texels` texels (not NULL).
 * @param texels Texels per plane.
 * @param i      0..texels-1 (not checked).
 * @param key    Validated key (mrgi_rsm_composite() checks it).
 */
double mrgi_rsm_composite_depth(
  const float* view, size_t texels, size_t i, const mrgi_rsm_view_key* key);

/**
 * @brief inout = composite(in, inout): per texel, the record nearest the
 *        light of the two (ties and empties as the file comment says).
 * @param in     Planar view of `texels` texels; may equal `inout`.
 * @param inout  Planar view of `texels` texels; receives the result.
 * @param texels Texels per plane; 0 does nothing.
 * @param key    Finite origin; for an orthographic view a finite, non-zero
 *               direction; `perspective` 0 or 1.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a NULL array (with texels > 0),
 *         a NULL or invalid key, or texels so large that the planes
 *         overflow size_t; `inout` is then untouched.
 */
mrgi_status mrgi_rsm_composite(
  const float* in, float* inout, size_t texels, const mrgi_rsm_view_key* key, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
