/**
 * @file mrgi_incremental_stencil.h
 * @brief Incremental stencil rendering for area lights: the texels a level
 *        renders depend on the illumination discontinuities found at the
 *        coarser level, not only on depth and normals. C twin of the GPU
 *        stage "incremental stencil" (vtkMRGIIncrementalStencilFS.glsl).
 *
 * Paper: Nichols, Penmatsa and Wyman 2010 (NPW10), section 3.4. The
 * geometric stencil (mrgi_multires.h sections 4-5: refinement flags R and the
 * selection S) refines where depth or normals change. Shadows add high
 * frequencies where the geometry is smooth (a penumbra across a flat floor):
 * there S gathers one coarse texel, and its single visibility mask paints a
 * blocky shadow. NPW10 renders the levels coarse to fine and lets a coarse
 * patch with a "light discontinuity" re-render its children at the next
 * finer level (their pseudocode: `if HasIlluminationDiscontinuity(f, i + 1)
 * then SetStencil(f)`); where a texel is not rendered, the coarser result is
 * upsampled and interpolated (mrgi_upsample.h).
 *
 * ## The rule
 *
 * Inputs: the layout, flags (NONEMPTY, REFINE) and selection S of
 * mrgi_multires.h, the finest gathering level f, the receivers of every
 * level (mrgi_multires_receivers.h: a texel is a receiver when its position
 * w > MRGI_GBUFFER_VALID_THRESHOLD and xyz is finite) and the visibility masks
 * of every texel (mrgi_voxel_visibility_pyramid(), W words per texel). The
 * illumination discontinuity of a level-j texel p is the bit-count metric of
 * NPW10 3.3.2 over p's 3x3 level-j neighbourhood (clamped, non-receivers
 * skipped; mrgi_voxel_neighbourhood_metric()):
 *
 *     F_j(p) = mrgi_voxel_needs_refinement(metric over p's 3x3, kind, threshold)
 *
 * the same test that makes the visibility pyramid COMPUTE p's children
 * (mrgi_visibility_pyramid.h section 5), so a re-rendered texel is one whose
 * visibility was also recomputed. Level-i texel t (parent p) is RENDERED when
 *
 *     i >= f && NONEMPTY_i(t) && ( S_i(t)
 *        || ( i < L && (i == f || !R_i(t)) && F_{i+1}(p) ) )
 *
 * - S_i(t): the geometric stencil, unchanged (every valid pixel lies in one
 *   selected footprint);
 * - the second term re-renders t at level i although a coarser texel
 *   covering it was rendered: the coarse patch saw a light discontinuity.
 *   A geometrically refined t (R_i, above f) is left out: finer selected
 *   texels cover its footprint anyway.
 *
 * A decision made here: the test reads F at the parent whether or not the
 * parent itself was rendered (NPW10's loop reads the coarse patch's result).
 * Every texel has a mask (COMPUTED or INHERITED), so F is defined
 * everywhere, and a discontinuity that first shows between level-j masks
 * still reaches level j - 1 when level j + 1 saw none (a small shadow).
 *
 * The result replaces S for the gather and for the upsampling: HAS and the
 * values of mrgi_upsample.h read RENDERED where they read S, so the finest
 * rendered texel covering a pixel wins and unrendered texels interpolate the
 * coarser data as before. RENDERED contains S. With threshold 0 every
 * non-empty texel at or above f below the geometric cut is rendered; with
 * the metric never firing RENDERED = S.
 *
 * Exactness: integer logic on integer masks; the GPU must agree bit for bit.
 *
 * ## Illumination: the same rule on the gathered light (indirect light)
 *
 * NPW10 3.4 tests a colour threshold on the coarse result; here the rule
 * above drives the indirect gather with F read from the irradiance E that
 * level j gathered (issue 17 part 2: refine where the light changes, not
 * where grazing geometry does). The levels are gathered coarse to fine and
 * level i's stencil is built after level i + 1 was gathered
 * (mrgi_incremental_stencil_illumination_level(), one call per level from
 * L down to f). With RENDERED_{j} the texels level j rendered (E defined
 * there only) and "usable" = RENDERED and a receiver:
 *
 *     F_j(p) = usable_j(p) && ( T == 0 || exists channel c and, by metric,
 *       DIFFERENCE: a usable n in p's 3x3 (clamped) with
 *                   |E_n,c - E_p,c| > T max(E_n,c, E_p,c)
 *       CURVATURE:  one of the 4 lines (a, p, b) through p (horizontal,
 *                   vertical, both diagonals; a = p - k, b = p + k; a line
 *                   with a or b outside the level is skipped)
 *                   with a and b usable and
 *                   |0.5 (E_a,c + E_b,c) - E_p,c| > T max(E_a,c, E_b,c, E_p,c),
 *                   or with one of them usable, n, and the DIFFERENCE test on n )
 *
 * DIFFERENCE is NPW10's colour test on neighbours; it refines every smooth
 * gradient steeper than T per coarse texel. CURVATURE compares p with the
 * linear prediction of its neighbours, so that a light that changes
 * linearly across a coarse texel (what the upsampling interpolates) does
 * not refine; a step still does (a discontinuity deviates from any line).
 *
 * T is relative and dimensionless (0.1: neighbouring coarse results differ
 * by more than 10% of the larger). T = 0 renders every non-empty texel at
 * or above f below a rendered parent (every level down to f gathers
 * everything: the full-resolution gather at f = 0); T >= 1 never fires for
 * non-negative E (RENDERED = S). A NaN irradiance compares false. The
 * comparison is the same float expression on both sides (the GPU reads
 * RENDERED_{j} as the gathered irradiance's alpha, 1 where the gather
 * drew), so the masks agree bit for bit on the same E.
 *
 * Geometric edges that matter need no depth test of their own here: a
 * coarse texel whose neighbours lie on another surface with other light
 * fires F; where the light is the same on both sides the coarse value
 * (times the full-resolution albedo at the resolve) is right anyway.
 * The geometric selection S still refines down to its own finest level;
 * with Illumination the pass relaxes its thresholds (vtkMRGIPass).
 */
#ifndef MRGI_INCREMENTAL_STENCIL_H
#define MRGI_INCREMENTAL_STENCIL_H

#include "mrgi_error.h"
#include "mrgi_multires.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** What the stencil rendered. */
typedef struct mrgi_incremental_stencil_stats
{
  int64_t selected[MRGI_MULTIRES_MAX_LEVELS]; /**< Texels of S per level. */
  int64_t added[MRGI_MULTIRES_MAX_LEVELS];    /**< RENDERED texels not in S (illumination discontinuities) per level. */
  int64_t rendered_total;                     /**< All RENDERED texels. */
} mrgi_incremental_stencil_stats;

/**
 * @brief The RENDERED texels (file comment), one byte per flattened texel
 *        (1 rendered, 0 elsewhere, also outside the levels).
 * @param layout       From mrgi_multires_layout_init().
 * @param finest_level f, 0..level_count - 1 (larger values are clamped, as
 *                     the selection does).
 * @param flags,selection One byte per flattened texel (mrgi_multires.h);
 *                     `texel_bytes` each.
 * @param receiver_position 4 floats per flattened texel; `receiver_floats` of them.
 * @param masks        `words` (1..MRGI_VOXEL_MAX_MASK_WORDS) words per
 *                     flattened texel; `mask_words` of them.
 * @param metric_kind  MRGI_VOXEL_METRIC_DISAGREE or _COUNT_SPREAD.
 * @param threshold    >= 0 (mrgi_voxel_refine_threshold()).
 * @param rendered     Receives the mask; `rendered_size` bytes.
 * @param stats        Receives the counts; may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, short arrays or a
 *         value out of range (nothing written).
 */
mrgi_status mrgi_incremental_stencil_build(
  const mrgi_multires_layout* layout, int32_t finest_level, const uint8_t* flags,
  const uint8_t* selection, size_t texel_bytes, const float* receiver_position,
  size_t receiver_floats, const uint32_t* masks, int32_t words, size_t mask_words,
  int32_t metric_kind, int32_t threshold, uint8_t* rendered, size_t rendered_size,
  mrgi_incremental_stencil_stats* stats, mrgi_error* err);

/** Default relative threshold T of the illumination rule (file comment, last section). */
#define MRGI_INCREMENTAL_ILLUMINATION_DEFAULT_THRESHOLD 0.1
/** Metrics of the illumination rule (file comment, last section). */
#define MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE 0
#define MRGI_INCREMENTAL_ILLUMINATION_CURVATURE 1

/**
 * @brief One level of the illumination rule (file comment, last section):
 *        writes RENDERED for level `level` only, reading RENDERED and E of
 *        level + 1 (ignored at the coarsest level, where RENDERED = S).
 *        Call for level = L, L - 1, ..., finest_level, gathering E of each
 *        level between the calls.
 * @param layout,finest_level,flags,selection,texel_bytes As
 *                     mrgi_incremental_stencil_build().
 * @param level        finest_level..level_count - 1 (finest_level clamped
 *                     as there); other levels are untouched.
 * @param receiver_position 4 floats per flattened texel (receivers of every level).
 * @param irradiance   4 floats per flattened texel (RGB = E; alpha unread),
 *                     `irradiance_floats` of them; only level + 1 is read.
 * @param metric       MRGI_INCREMENTAL_ILLUMINATION_DIFFERENCE or _CURVATURE.
 * @param threshold    T, finite and >= 0.
 * @param rendered     In: levels above `level` as earlier calls wrote them;
 *                     out: level `level` (1 rendered, 0 not).
 * @param added        Receives the texels of this level rendered outside S; may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, short arrays or a
 *         value out of range (nothing written).
 */
mrgi_status mrgi_incremental_stencil_illumination_level(const mrgi_multires_layout* layout,
  int32_t finest_level, int32_t level, const uint8_t* flags, const uint8_t* selection,
  size_t texel_bytes, const float* receiver_position, size_t receiver_floats,
  const float* irradiance, size_t irradiance_floats, int32_t metric, float threshold,
  uint8_t* rendered, size_t rendered_size, int64_t* added, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
