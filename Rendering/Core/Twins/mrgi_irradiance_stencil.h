/**
 * @file mrgi_irradiance_stencil.h
 * @brief Incremental stencil rendering for area lights, the irradiance
 *        term: re-render a coarse patch's children where the light's
 *        unshadowed irradiance varies across the patch by more than a
 *        relative tolerance. C twin of the irradiance test in
 *        vtkMRGIIncrementalStencilFS.glsl.
 *
 * Paper: Nichols, Penmatsa and Wyman 2010 (NPW10), section 3.4: a coarse
 * patch re-renders at the next finer level where it sees an illumination
 * discontinuity; NPW10 names visibility and colour changes. The visibility
 * term is mrgi_incremental_stencil.h. This is the colour term for the light's
 * geometric part, predicted instead of read back: the geometric
 * multiresolution selection (mrgi_multires.h) gathers a flat wall facing
 * the camera at coarse levels, and near a large emitter its irradiance
 * changes faster than the tent interpolation of mrgi_upsample.h follows
 * (cornell-area: blotchy bands on the back wall). A departure from NPW10,
 * which compares gathered colours coarse to fine with one pass per level:
 * the estimate needs no gathered value, so the whole stencil still builds
 * in one draw per level before a single gather.
 *
 * ## The estimate
 *
 * E(P, N) at a world-space receiver (P, N): the rectangle cut into
 * G x G equal cells (G = MRGI_IRRADIANCE_STENCIL_GRID), each cell's
 * disk-to-point form factor at its centre as the gather takes it
 * (mrgi_area_light.h, NPW10 eq. 2, without radiance, texture or
 * visibility):
 *
 *     q_ab  = c_0 + ((a + 1/2) / G) (c_1 - c_0) + ((b + 1/2) / G) (c_3 - c_0)
 *     d     = q_ab - P, r2 = d.d, ci = N.d, cj = -n_L.d (|.| when two-sided)
 *     E    += A_c (ci cj / r2) / (pi r2 + A_c)      when r2 > 0, ci > 0, cj > 0
 *
 * with A_c = area / G^2, b outer, a inner; E = 0 behind a one-sided light
 * or in the light's plane (the gather's early-out 1). Eye-space receivers
 * are brought to world space with the view-to-world matrix M (column
 * major, as GLSL's mat4): P = M (p, 1), N = normalize(M3 n).
 *
 * ## The rule
 *
 * For a level-j texel p, over its 3x3 level-j neighbours (clamped,
 * receivers only as in mrgi_incremental_stencil.h, a zero normal skipped):
 *
 *     V_j(p) = Emax > 0 && Emax - Emin > tau Emax
 *
 * Level-i texel t (parent p) is added to `rendered` when
 *
 *     i >= f && i < L && NONEMPTY_i(t) && (i == f || !R_i(t)) && V_{i+1}(p)
 *
 * exactly the condition of mrgi_incremental_stencil.h with V for F, so the
 * two terms OR together. tau = 0 turns the term off (nothing is added).
 *
 * Exactness: float; the GPU's rounding may flip a texel whose spread lies
 * within a few ulps of tau Emax. The parity test brackets the GPU between
 * the twin at tau (1 +- 1e-4).
 */
#ifndef MRGI_IRRADIANCE_STENCIL_H
#define MRGI_IRRADIANCE_STENCIL_H

#include "mrgi_area_light.h"
#include "mrgi_error.h"
#include "mrgi_multires.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Cells per side of the light in the estimate (GLSL: the same value). */
#define MRGI_IRRADIANCE_STENCIL_GRID 4
/** Default relative tolerance tau (vtkMRGIIncrementalStencil::IrradianceTolerance). */
#define MRGI_IRRADIANCE_STENCIL_DEFAULT_TOLERANCE 0.25f

/**
 * @brief E(P, N) of the file comment, world space. No checks: valid
 *        uniforms (mrgi_area_light_uniforms_init()), finite P, unit N.
 */
float mrgi_irradiance_stencil_estimate(const mrgi_area_light_uniforms* light, const float P[3],
                                       const float N[3]);

/**
 * @brief Add the texels of the rule (file comment) to `rendered`.
 * @param layout,finest_level,flags As mrgi_incremental_stencil_build();
 *                     `texel_bytes` bytes each.
 * @param receiver_position,receiver_normal Eye space, 4 floats per
 *                     flattened texel (mrgi_multires_receivers.h);
 *                     `receiver_floats` each.
 * @param view_to_world Column-major eye-to-world matrix.
 * @param light        World-space light (mrgi_area_light_uniforms_init()).
 * @param tolerance    tau in [0, 1]; 0 adds nothing.
 * @param rendered     In/out, one byte per flattened texel; `rendered_size` bytes.
 * @param added        Receives the texels this call set per level (those
 *                     already set are not counted); may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, short arrays, a
 *         negative finest level or a tolerance outside [0, 1] (nothing
 *         written).
 */
mrgi_status mrgi_irradiance_stencil_add(
  const mrgi_multires_layout* layout, int32_t finest_level, const uint8_t* flags,
  size_t texel_bytes, const float* receiver_position, const float* receiver_normal,
  size_t receiver_floats, const float view_to_world[16], const mrgi_area_light_uniforms* light,
  float tolerance, uint8_t* rendered, size_t rendered_size,
  int64_t added[MRGI_MULTIRES_MAX_LEVELS], mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
