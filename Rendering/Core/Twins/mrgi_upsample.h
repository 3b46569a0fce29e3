/**
 * @file mrgi_upsample.h
 * @brief Upsampling and combination of the multiresolution illumination
 *        buffer into one full-resolution image: C twin of the GPU
 *        "upsample + combine" stage.
 *
 * Nichols and Wyman 2009, "Multiresolution Splatting for Indirect
 * Illumination", section 3.5 (coarse to fine; every texel holding data is
 * interpolated with same-resolution neighbours holding data; energy is never
 * pulled from empty texels nor spread into them); Besenthal, Maisch and
 * Ropinski, "Multi-Resolution Rendering for Computationally Expensive
 * Lighting Effects", section 3.3 and equation 1 (mask-weighted blending).
 * Layout, flags and selection: mrgi_multires.h.
 *
 * ## Inputs
 *
 * - the flattened illumination buffer (rows bottom-up, index
 *   Y * total_width + X, `channels` floats per texel, the first three = RGB),
 *   holding the gathered value at every selected texel; other texels are
 *   ignored (whatever they hold);
 * - the selection mask S (1 byte per texel) and the flags (NONEMPTY,
 *   DISCONTINUOUS) of mrgi_multires.h.
 *
 * ## The passes (one GPU pass per level, i = L down to 0)
 *
 * For level i texel t, with parent p = level i+1 texel (x/2, y/2):
 *
 *     HAS_i(t) = S_i(t) || (i < L && NONEMPTY_i(t) && HAS_{i+1}(p))
 *     V_i(t)   = S_i(t) ? I_i(t) : (HAS_i(t) ? U_{i+1}(p) : 0)      (nearest upsampling)
 *     E_i(t)   = HAS_i(t) && !DISCONTINUOUS_i(t)                    (may be blended)
 *
 * A texel holds data (HAS) when gathered at this level or upsampled from a
 * coarser texel holding data; upsampling never enters an EMPTY texel. Only
 * texels with E take part in interpolation, as sources and as targets:
 * the 3x3 window test of mrgi_multires.h section 3 guarantees that two
 * 8-adjacent texels that are both not DISCONTINUOUS have no depth step,
 * normal crease or background between them, so nothing leaks across a
 * discontinuity or from/onto background. (Above the finest level every
 * texel holding data is continuous; at and below it, DISCONTINUOUS texels
 * keep their own value.)
 *
 * Tent weights over the 3x3 same-level neighbourhood N(t) (no clamping:
 * neighbours outside the level are skipped), k(dx, dy) = (2-|dx|)(2-|dy|):
 * 4 at the centre, 2 at edges, 1 at corners.
 *
 * MRGI_UPSAMPLE_TENT (NW09 3.5):
 *
 *     U_i(t) = sum_{n in N(t), E(n)} k V(n) / sum_{n in N(t), E(n)} k     if E(t)
 *     U_i(t) = V_i(t)                                                   if HAS(t) && !E(t)
 *     U_i(t) = 0                                                        otherwise
 *
 * MRGI_UPSAMPLE_MASK_WEIGHTED (Besenthal et al. eq. 1, c' = c_i min(a w, 1)
 * + c'_{i+1} (1 - min(a w, 1))), for E(t), sums over n in N(t) with E(n):
 *
 *     a      = sum k S(n) / sum k                 (tent-blurred mask of level i)
 *     fine   = sum k S(n) V(n) / sum k S(n)       (level i's own gathered data)
 *     coarse = sum k (1-S(n)) V(n) / sum k (1-S(n))   (data upsampled from coarser levels)
 *     lambda = min(a * mask_weight, 1)
 *     U_i(t) = a == 0 ? coarse : (a == 1 ? fine : coarse + lambda (fine - coarse))
 *
 * With mask_weight = 1 this equals the tent mode (a fine + (1-a) coarse is
 * the tent average); larger weights let the finer level win near its
 * texels, as Besenthal's per-level weights (Table 1) do. !E texels as in
 * the tent mode.
 *
 * Output: full-resolution pixel (x, y) = U_0(x, y) for a valid pixel
 * (NONEMPTY at level 0), 0 for background. The image is W x H x 3 floats in
 * the G-buffer's row order (row 0 = BOTTOM, as mrgi_gather_full()).
 *
 * Properties (tested): a constant illumination stays constant; selecting
 * every valid pixel at level 0 with all of them DISCONTINUOUS (threshold 0)
 * is the identity; background stays 0; values never cross a depth step.
 * The C twin computes in float in the order written; the GPU must agree to
 * 1e-4 relative error.
 */
#ifndef MRGI_UPSAMPLE_H
#define MRGI_UPSAMPLE_H

#include "mrgi_error.h"
#include "mrgi_image.h"
#include "mrgi_multires.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Upsampling modes (GLSL: the same values). */
#define MRGI_UPSAMPLE_TENT 0
#define MRGI_UPSAMPLE_MASK_WEIGHTED 1
/** Default mask weight of the mask-weighted mode (Besenthal et al. Table 1 uses 100 and 1000). */
#define MRGI_UPSAMPLE_DEFAULT_MASK_WEIGHT 100.0f
/** Largest accepted mask weight. */
#define MRGI_UPSAMPLE_MAX_MASK_WEIGHT 1.0e6f

/** Upsampling knobs. */
typedef struct mrgi_upsample_params
{
  int32_t mode;      /**< MRGI_UPSAMPLE_TENT (default) or MRGI_UPSAMPLE_MASK_WEIGHTED. */
  float mask_weight; /**< Mask-weighted mode: w, 1..MRGI_UPSAMPLE_MAX_MASK_WEIGHT (1 = tent). */
} mrgi_upsample_params;

/** @brief Defaults: tent mode, mask weight MRGI_UPSAMPLE_DEFAULT_MASK_WEIGHT. NULL-safe. */
void mrgi_upsample_params_default(mrgi_upsample_params* params);

/**
 * @brief Upsample and combine the illumination buffer (file comment).
 * @param layout       The flattened layout (mrgi_multires_layout_init()).
 * @param flags        mrgi_multires_flags_compute() output, texel count bytes.
 * @param mask         Selection (either mrgi_multires_select_*), texel count bytes.
 * @param illumination texel count * channels floats, flattened, rows bottom-up.
 * @param illumination_count Number of floats in `illumination`.
 * @param channels     3 (RGB) or 4 (RGBA as read back; alpha ignored).
 * @param params       Mode and weight; NULL means the defaults.
 * @param out          Receives a new W x H x 3 image, row 0 = BOTTOM
 *                     (treated as uninitialized; zeroed on failure).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, short buffers, a
 *         channel count other than 3 or 4, an unknown mode or a weight out of
 *         range; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_upsample(const mrgi_multires_layout* layout, const uint8_t* flags,
                          size_t flags_size, const uint8_t* mask, size_t mask_size,
                          const float* illumination, size_t illumination_count,
                          int32_t channels, const mrgi_upsample_params* params, mrgi_image* out,
                          mrgi_error* err);

/**
 * @brief Surface-detail modulation, nichols-wyman-2009 section 4.2, eq. 2:
 *        c_out = c * (alpha * max(V . N, 0) + (1 - alpha)).
 *
 * Brings back shading detail that coarse texels blur out (high normal
 * thresholds) by darkening the indirect light where the surface turns away
 * from the viewer. Applied per full-resolution pixel after upsampling.
 *
 * @param position_eye Eye-space position of the pixel (the G-buffer's).
 * @param normal_eye   Eye-space normal (any length; normalised here).
 * @param parallel     Non-zero for a parallel projection (V = +z in eye space).
 * @param alpha        Strength in [0, 1]; 0 leaves c unchanged (factor 1).
 * @return The factor multiplying c: in [1 - alpha, 1] for alpha in [0, 1].
 *         V = -position / |position| (perspective; +z when the position is
 *         the eye itself); a zero or non-finite normal or position gives the
 *         factor of a surface seen edge-on, 1 - alpha; never NaN.
 *         The GLSL twin is in vtkMRGIMultiresUpsampleFS.glsl (resolve).
 */
float mrgi_surface_detail_factor(const float position_eye[3], const float normal_eye[3],
                                 int32_t parallel, float alpha);

#ifdef __cplusplus
}
#endif

#endif
