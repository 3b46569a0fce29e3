/**
 * @file mrgi_bmr_blend.h
 * @brief Blending of the BMR sub-images into one full-resolution image:
 *        C twin of the GPU stage vtkMRGIBMRBlend (vtkMRGIBMRBlendFS.glsl).
 *
 * Paper: Besenthal, Maisch and Ropinski (BMR), sections 3.3 and 4.2,
 * equation 1, with its index corrected (the paper blends c'_i with
 * c'_{i-1}, the next finer image, although it composes from the coarsest
 * up) and with the stencils respected. Levels k = 0..3 as in
 * mrgi_bmr_mask.h (k = BMR's i - 1).
 *
 * ## Inputs
 *
 * - per level k, the effect's values c_k: w_k x h_k texels of `channels`
 *   floats (index (y * w_k + x) * channels + c, row 0 = bottom), valid
 *   where S_k = 1; every other texel is ignored, whatever it holds (NaN too);
 * - the masks a_k, the stencils S_k and NE_0 of a ::mrgi_bmr_masks;
 * - the weights w_k and skip flags of a ::mrgi_bmr_params.
 *
 * ## Sampling level k at full-resolution pixel p = (x, y)
 *
 * The pixel centre in level-k texel coordinates is
 * u = (x + 0.5) / 2^k - 0.5, v = (y + 0.5) / 2^k - 0.5 (the level's texels
 * are 2^k pixels wide; with w_k = ceil(W / 2^k) this is not W / w_k, so the
 * GPU fetches texels, it does not use normalised texture coordinates).
 * Taps x0 = floor(u), x0 + 1 and y0 = floor(v), y0 + 1, clamped to the
 * level; weights (1 - fx, fx) (1 - fy, fy) with fx = u - x0, fy = v - y0.
 *
 * - bilin(a_k): the weighted sum of a_k over the four taps.
 * - bilin*(c_k): sum over the taps with weight > 0 and S_k = 1 of weight c_k,
 *   divided by the sum of those weights ("bilinear over stencilled taps,
 *   renormalised"); undefined (n/a) when no such tap exists.
 *
 * ## Equation 1, index corrected
 *
 *     U_3 = bilin*(c_3)            (S_3 = NE_3: level 3 holds every valid pixel)
 *     U_k = lambda_k bilin*(c_k) + (1 - lambda_k) U_{k+1},    k = 2, 1, 0
 *     lambda_k = min(bilin(a_k) w_k, 1);  lambda_k = 0 when level k is
 *               skipped or bilin*(c_k) is n/a
 * evaluated as: lambda = 0 -> U_{k+1}; lambda = 1 -> bilin*(c_k); else
 * U_{k+1} + lambda (bilin*(c_k) - U_{k+1}) (so lambda = 1 returns level k's
 * value as is; a constant effect comes back to float rounding of the
 * renormalisation, and exactly where a single tap carries all the weight).
 * Level 3 uses bilin* under S_3 rather than BMR's plain bilin: the texels
 * of empty footprints are never rendered, so a plain bilinear tap at a
 * silhouette would read whatever they hold. For a valid pixel the level-3
 * texel holding it is always a tap with weight >= 1/4, so U_3 is defined.
 *
 * Output pixel p = U_0 for a valid pixel (NE_0), 0 for background.
 *
 * Properties (tested): a constant effect blends to the constant; with
 * every level stencilled and a_0 w_0 >= 1 everywhere (threshold 0: the
 * full-resolution path) the output is c_0 exactly; values at unstencilled
 * texels never reach the output.
 * The C twin computes in float in the order written; the GPU agrees to
 * 1e-4 relative.
 */
#ifndef MRGI_BMR_BLEND_H
#define MRGI_BMR_BLEND_H

#include "mrgi_bmr_mask.h"
#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Most channels per texel. */
#define MRGI_BMR_MAX_CHANNELS 4

/**
 * @brief Blend the levels (see the file comment).
 * @param masks     Masks and stencils (mrgi_bmr_mask_build() or _from_flags()).
 * @param params    Weights and skip flags (mrgi_bmr_params_validate()).
 * @param levels    MRGI_BMR_LEVELS arrays, level k holding
 *                  masks->level_width[k] * level_height[k] * channels floats.
 * @param channels  1..MRGI_BMR_MAX_CHANNELS.
 * @param out       W * H * channels floats, row 0 = bottom.
 * @param out_size  Floats in `out`.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, empty masks, bad
 *         params, a bad channel count or a short `out`.
 */
mrgi_status mrgi_bmr_blend(const mrgi_bmr_masks* masks, const mrgi_bmr_params* params,
  const float* const levels[MRGI_BMR_LEVELS], int32_t channels, float* out, size_t out_size,
  mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
