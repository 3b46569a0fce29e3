/**
 * @file mrgi_specular_stencil.h
 * @brief The stencil of the multiresolution area-light specular gather:
 *        the geometric refinement plus the Phong lobe-size metric, with the
 *        material pyramid it reads. C twin of the GPU stage "specular
 *        stencil" (vtkMRGISpecularStencilFS.glsl, driven by
 *        vtkMRGISpecularStencil::Build()).
 *
 * Paper: Nichols, Penmatsa and Wyman 2010 (NPW10), section 3.2.1 ("when we
 * create our depth and normal mipmaps, we also compute the cross-sectional
 * Phong lobe size at the light. Image-space sample spacing must be denser
 * than the lobe width, which we add as a Phong-specific refinement metric";
 * "we separate diffuse and Phong components into separate gather passes")
 * and 3.4 (the stencil combines depth, normal "and BRDF frequency metrics").
 *
 * ## 1. Material pyramid (per level, RGBA32F on the GPU; 4 floats per
 *    flattened texel here)
 *
 * The lobe of a texel needs a Phong exponent n. A coarse texel's exponent
 * is the LARGEST exponent of the specular pixels in its footprint (the
 * sharpest lobe: the lobe metric then refines conservatively, never less
 * than any of the pixels would ask for), and the texel knows how many
 * exponents it mixes:
 *
 *     level 0, pixel p (G-buffer position P, k_s c_s, exponent n):
 *       specular(p) = P.w > MRGI_GBUFFER_VALID_THRESHOLD && max(k_s c_s) > 0
 *       M_0(p) = specular(p) ? (max(k_s c_s), n, n, 0)
 *                            : (0, 0, MRGI_MULTIRES_FLT_MAX, 0)
 *     level i >= 1: over the 2x2 children (clamped, as the mipmaps):
 *       M_i = (max x, max y, min z, 0)
 *
 * So x > 0 ("K") exactly when the footprint holds a specular pixel, y is
 * the largest exponent of those pixels and z the smallest (z = FLT_MAX, y = 0
 * when none). k_s c_s itself is not averaged: the gather computes S alone
 * and the resolve multiplies the upsampled S by each pixel's own k_s c_s
 * (material edges stay sharp).
 *
 * ## 2. Refinement and selection
 *
 * Inputs: the layout, flags (NONEMPTY, REFINE) of mrgi_multires.h, the
 * finest gathering level f, the receivers of every level
 * (mrgi_multires_receivers.h: eye-space mean position + pixel count, mean
 * normal), the material pyramid, the light, the eye -> world matrix, the
 * projection and the pixel-size coefficients (a, b)
 * (mrgi_multires_pixel_size_coefficients()). Level-j texel u is REFINED for
 * the specular gather when
 *
 *     Q_j(u) = j > f && NONEMPTY(u) && ( R_j(u)
 *              || ( K_j(u) && ( z_j(u) < y_j(u) || (lobe && m_j(u) > c) ) ) )
 *
 * with c = lobe_threshold (NPW10's criterion is c = 1: sample spacing equal
 * to the lobe width; sampling a lobe, not just touching it, wants a few
 * samples across it, c < 1).
 *
 * - R_j(u): the geometric refinement flag (depth, normals, balance);
 * - z < y: the footprint mixes exponents (a BRDF discontinuity on a smooth
 *   surface, e.g. two materials on one floor);
 * - m_j(u) = mrgi_area_light_phong_refinement() for the lobe
 *   (mrgi_area_light_phong_lobe()) of u's receiver with exponent y_j(u):
 *   P = M (p, 1), N = M3 n, V = M3 (-p) (M3 (0, 0, 1) for a parallel
 *   projection), e = |p| (MRGI_MULTIRES_FLT_MAX for parallel: the mirrored
 *   eye is at infinity), texel size s = 2^j max(a |p.z| + b,
 *   MRGI_MULTIRES_MIN_PIXEL_SIZE) (2^j pixels at the receiver's depth).
 *   A texel whose receiver is not valid (w <= MRGI_GBUFFER_VALID_THRESHOLD,
 *   non-finite position or normal, zero normal) has m = 0. The metric does
 *   NOT look at whether the lobe reaches the light (its peak): a coarse
 *   texel's lobe may miss while its children's hit (conservative).
 *
 * Q is made monotone top-down (NPW10 3.4: "render one resolution at a time,
 * from coarsest to finest"): a texel is refined only when every ancestor is,
 *
 *     Q'_j(u) = Q_j(u) && (j == L || Q'_{j+1}(parent(u)))
 *
 * and the selection (the specular stencil) is
 *
 *     SEL_i(t) = i >= f && NONEMPTY(t) && K_i(t) && !Q'_i(t)
 *                && (i == L || Q'_{i+1}(parent(t)))
 *
 * Every valid specular pixel lies in exactly one selected footprint (walk
 * its ancestors from level L down to the first one not refined); a texel
 * whose footprint holds no specular pixel is never selected, so nothing is
 * gathered there. Because R is monotone (mrgi_multires.h section 4), Q'
 * contains R, and with the lobe off and no mixed exponents SEL = S && K
 * (the geometric selection restricted to specular footprints). The
 * one-level balance between neighbours holds for R; refinement added by the
 * lobe metric or mixed exponents is not balanced (the upsampling
 * interpolates across any level difference, mrgi_upsample.h).
 *
 * ## Precision
 *
 * The refinement test is float arithmetic in the order of the GLSL, whose
 * exp2, sqrt and division are not correctly rounded: GPU and C agree
 * except where m is within float rounding of 1 (the parity test counts
 * disagreements with |m - 1| > 1e-3 as failures). Everything else (the
 * pyramid reduction, the ancestor walk, the selection) is exact.
 */
#ifndef MRGI_SPECULAR_STENCIL_H
#define MRGI_SPECULAR_STENCIL_H

#include "mrgi_area_light.h"
#include "mrgi_error.h"
#include "mrgi_multires.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Bits of the per-texel refinement output (GPU: red channel of the refine texture). */
#define MRGI_SPECULAR_STENCIL_REFINE 1  /**< Q (before the top-down walk). */
#define MRGI_SPECULAR_STENCIL_LOBE 2    /**< The lobe metric alone fired (m > 1, K, j > f). */
#define MRGI_SPECULAR_STENCIL_SPECULAR 4 /**< NONEMPTY && K. */

/** What the specular stencil selected. */
typedef struct mrgi_specular_stencil_stats
{
  int64_t selected[MRGI_MULTIRES_MAX_LEVELS]; /**< Selected texels per level. */
  int64_t lobe[MRGI_MULTIRES_MAX_LEVELS];     /**< Texels whose lobe metric fired, per level. */
  int64_t selected_total;                     /**< All selected texels. */
} mrgi_specular_stencil_stats;

/**
 * @brief The material pyramid of section 1 from a W x H G-buffer (rows
 *        bottom-up), 4 floats per flattened texel (0 outside the levels).
 * @param position  4 floats per pixel (w = validity); `pixels` pixels.
 * @param specular  4 floats per pixel (rgb = k_s c_s).
 * @param shininess 4 floats per pixel (r = Phong exponent).
 * @param material  Receives 4 * mrgi_multires_texel_count() floats; `material_floats`.
 */
mrgi_status mrgi_specular_material_build(const mrgi_multires_layout* layout,
                                         const float* position, const float* specular,
                                         const float* shininess, size_t pixels, float* material,
                                         size_t material_floats, mrgi_error* err);

/** The view of section 2. */
typedef struct mrgi_specular_stencil_view
{
  float view_to_world[16]; /**< Eye -> world, column-major (OpenGL's order). */
  int32_t parallel;        /**< 1: parallel projection. */
  float pixel_size[2];     /**< (a, b): pixel size at depth d is max(a |d| + b, MIN). */
  int32_t lobe;            /**< 1: the lobe metric is on. */
  float lobe_threshold;    /**< Refine where m > this; > 0 (NPW10: 1, the spacing equals the lobe width; smaller refines earlier). */
} mrgi_specular_stencil_view;

/**
 * @brief m_j(u) of section 2 for one texel (0 for an invalid receiver).
 * @param receiver_position 4 floats (eye space xyz, w = pixel count / validity).
 * @param receiver_normal   3 floats (eye space).
 * @param power             The texel's exponent y_j(u).
 * @param level             j (the texel spans 2^j pixels).
 */
float mrgi_specular_stencil_metric(const mrgi_area_light_uniforms* light,
                                   const mrgi_specular_stencil_view* view,
                                   const float receiver_position[4],
                                   const float receiver_normal[3], float power, int32_t level);

/**
 * @brief The refinement bits (MRGI_SPECULAR_STENCIL_*, Q before the walk)
 *        and the selection SEL (section 2), one byte per flattened texel each.
 * @param flags              mrgi_multires.h flags, `texel_bytes` bytes.
 * @param material           Section 1, 4 floats per texel; `material_floats`.
 * @param receiver_position  4 floats per texel (level 0: the G-buffer); `receiver_floats`.
 * @param receiver_normal    4 floats per texel; `receiver_floats`.
 * @param refine             Receives the bits (may be NULL); `texel_bytes` bytes.
 * @param selection          Receives SEL; `texel_bytes` bytes.
 * @param stats              May be NULL.
 */
mrgi_status mrgi_specular_stencil_build(
  const mrgi_multires_layout* layout, int32_t finest_level, const uint8_t* flags,
  const float* material, size_t material_floats, const float* receiver_position,
  const float* receiver_normal, size_t receiver_floats, const mrgi_area_light_uniforms* light,
  const mrgi_specular_stencil_view* view, uint8_t* refine, uint8_t* selection, size_t texel_bytes,
  mrgi_specular_stencil_stats* stats, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
