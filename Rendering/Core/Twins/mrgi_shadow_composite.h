/**
 * @file mrgi_shadow_composite.h
 * @brief Shadows applied to VTK's direct light: C twin of the "shadows.apply"
 *        step (vtkMRGIShadowComposite, vtkMRGIShadowCompositeFS.glsl).
 *
 * VTK's fragment shader sums, per pixel, an ambient term and one term per
 * light. While MRGI captures the G-buffer it also stores the term C_s of
 * VTK's first MRGI_SHADOW_SLOTS shader lights (attachments
 * MRGI_GBUFFER_LIGHT0.., mrgi_buffers.h), as VTK's own light loop computed
 * it. Given a shadow factor f_s in [0, 1] per light (1 = lit), the shadowed
 * colour is what VTK's loop would have produced with each term scaled by f_s:
 *
 *     linear (Phong, Gouraud, flat, unlit):
 *         out = max(colour - sum_s (1 - f_s) C_s, 0)
 *     PBR (VTK writes pow(x, 1/2.2); its terms are stored negated):
 *         out = pow(max(pow(colour, 2.2) - sum_s (1 - f_s) |C_s|, 0), 1/2.2)
 *
 * per rgb channel; alpha is kept. Where every f_s is 1 (lit, or no light
 * reaches the pixel's slot) the output is `colour` itself, bit for bit: a
 * lit pixel is exactly VTK's own lighting. A pixel is PBR when any
 * component of any C_s is negative. Non-finite or out-of-range factors count
 * as 1 (a broken factor never darkens); non-finite terms count as 0; a
 * non-finite colour channel is passed through (the pass reports those).
 *
 * The GPU computes the same in float, in this order; pow() may differ from
 * C's powf in the last bits (parity: 1e-4 relative).
 */
#ifndef MRGI_SHADOW_COMPOSITE_H
#define MRGI_SHADOW_COMPOSITE_H

#include "mrgi_buffers.h"
#include "mrgi_error.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** VTK's PBR display gamma (vtkOpenGLPolyDataMapper writes pow(color, 1/2.2)). */
#define MRGI_SHADOW_PBR_GAMMA 2.2f

/**
 * @brief The shadowed colour of one pixel.
 * @param colour  RGBA as VTK wrote it.
 * @param terms   MRGI_SHADOW_SLOTS RGBA records (the MRGI_GBUFFER_LIGHT0..
 *                attachments' texels), slot after slot.
 * @param factors Shadow factor of each slot (MRGI_SHADOW_SLOTS values).
 * @param out     RGBA result (may alias `colour`).
 */
void mrgi_shadow_composite_pixel(
  const float colour[4], const float* terms, const float* factors, float out[4]);

/**
 * @brief The shadowed colour of `count` pixels.
 * @param colour  count RGBA texels (VTK's colour).
 * @param terms   MRGI_SHADOW_SLOTS arrays of count RGBA texels, one per slot.
 * @param factors count RGBA texels: channel s holds slot s's factor (the
 *                layout vtkMRGIDirectShadows writes; channels past
 *                MRGI_SHADOW_SLOTS are ignored).
 * @param out     count RGBA texels (may alias `colour`).
 * @return ::MRGI_ERR_INVALID_ARGUMENT when an array is missing.
 */
mrgi_status mrgi_shadow_composite(const float* colour, const float* const terms[MRGI_SHADOW_SLOTS],
  const float* factors, size_t count, float* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
