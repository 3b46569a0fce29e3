/**
 * @file mrgi_vpl_clusters.h
 * @brief Multiresolution VPL clusters (image-space radiosity, ISR): a
 *        variable number of VPLs, large light-space patches where the RSM is
 *        smooth and small ones near its depth and normal discontinuities.
 *
 * Paper: Nichols, Shopf and Wyman 2009, "Hierarchical Image-Space
 * Radiosity" (NSW09), sections 3.3-3.4: light-space normal and depth
 * min-max mipmaps, discontinuity detection "similar to those used during
 * eye-space rendering", one VPL per selected patch. Spec:
 * shared/plans/paper-specs.md, Package 1, 1.2. The pyramid and node records
 * are mrgi_vpl_tree.h's.
 *
 * ## 1. Light-space flags (mrgi_vpl_cluster_flags)
 *
 * Per view: mrgi_rsm_view_receivers(), mrgi_multires_mipmap_build() with
 * mrgi_multires_pixel_size_coefficients(camera projection, S), then
 * mrgi_multires_flags_compute() with
 *     depth_threshold  = ClusterDepthThreshold  (same meaning as the eye side's T_d),
 *     normal_threshold = ClusterNormalThreshold (same meaning as T_n),
 *     finest_level     = f_L,
 *     balance          = 0 (NSW09's rule; the eye side's level balance exists
 *                        for upsampling, which VPLs do not need).
 * The flags of view v occupy bytes [v * F, (v+1) * F) of the flags array,
 * F = mrgi_multires_texel_count(&tree->layout), in the flattened layout.
 * f_L defaults (MRGI_VPL_CLUSTER_FINEST_AUTO) to the level whose side is
 * MRGI_VPL_CLUSTER_DEFAULT_FINEST_SIDE (T / 2^f_L = 64), clamped to the tree's levels.
 *
 * ## 2. Selection (mrgi_vpl_clusters_from_flags)
 *
 * The iterative rule of mrgi_multires.h section 5 on every view, with a cap:
 * - start: every root (level L node) of every view is selected, including
 *   roots without usable texels (they give zero VPLs, as the grid's empty
 *   blocks do), so that thresholds +inf reproduce the grid with G = 16;
 * - for levels i = L .. f_L + 1 (coarse to fine), views in order, nodes in
 *   scan order (y, then x): a selected node with the REFINE flag is replaced
 *   by its children that have the NONEMPTY flag, unless that would bring the
 *   selected count above `max_count`; then it stays selected (a leaf) and
 *   `capped` counts it. Deterministic.
 * Without the cap this selects, apart from the empty roots, exactly the
 * non-empty texels of mrgi_multires_select_one_pass(). Thresholds +inf
 * (no refinement) give the roots, i.e. the grid VPLs with G = 16, in the
 * same order; thresholds 0 give every non-empty node of level f_L (when the
 * cap allows). The selected nodes partition the usable texels, so the VPL
 * fluxes add up to the RSM's total for any thresholds (energy conservation).
 *
 * ## 3. Output
 *
 * One VPL per selected node, in record order (coarse levels first, then
 * view, y, x): the node's record (mrgi_vpl_tree.h section 3, the sums
 * replace NSW09's "omega_j by level") with both pads set to 0, as the VPL
 * texture requires.
 */
#ifndef MRGI_VPL_CLUSTERS_H
#define MRGI_VPL_CLUSTERS_H

#include "mrgi_error.h"
#include "mrgi_vpl.h"
#include "mrgi_vpl_tree.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Most cluster VPLs: the gather's loop cap (MRGI_VPL_MAX_COUNT). */
#define MRGI_VPL_CLUSTER_MAX MRGI_VPL_MAX_COUNT
/** Side of the default finest light level f_L (NSW09: 64 x 64 of a larger RSM). */
#define MRGI_VPL_CLUSTER_DEFAULT_FINEST_SIDE 64
/** finest_level value meaning "the level of side MRGI_VPL_CLUSTER_DEFAULT_FINEST_SIDE". */
#define MRGI_VPL_CLUSTER_FINEST_AUTO (-1)

/** Knobs of the cluster selection. */
typedef struct mrgi_vpl_cluster_params
{
  double depth_threshold;  /**< ClusterDepthThreshold, [0, +inf] (+inf: off); see mrgi_multires.h section 3. */
  double normal_threshold; /**< ClusterNormalThreshold, [0, +inf] (+inf: off). */
  int32_t finest_level;    /**< f_L, 0..levels-1, or MRGI_VPL_CLUSTER_FINEST_AUTO. */
  int32_t max_count;       /**< Cap on the VPL count, 1..MRGI_VPL_CLUSTER_MAX; at least the roots' count. */
} mrgi_vpl_cluster_params;

/** What a cluster selection did. */
typedef struct mrgi_vpl_cluster_info
{
  int32_t vpl_count;                            /**< VPLs written. */
  int32_t empty_vpl_count;                      /**< Of those, VPLs with zero flux. */
  int32_t finest_level;                         /**< f_L actually used. */
  int32_t capped;                               /**< Refinements the cap refused. */
  int32_t per_level[MRGI_MULTIRES_MAX_LEVELS];  /**< VPLs per tree level. */
  int64_t usable_texel_count;                   /**< As the tree counts them. */
  int64_t rejected_texel_count;                 /**< Valid texels ignored (non-finite, negative). */
} mrgi_vpl_cluster_info;

/** @brief Defaults: eye-side default thresholds, f_L auto, cap MRGI_VPL_CLUSTER_MAX. NULL-safe. */
void mrgi_vpl_cluster_params_default(mrgi_vpl_cluster_params* params);

/**
 * @brief f_L for a tree: `requested` when in 0..levels-1, the automatic
 *        level for MRGI_VPL_CLUSTER_FINEST_AUTO, -1 for anything else.
 */
int32_t mrgi_vpl_cluster_finest_level(const mrgi_vpl_tree* tree, int32_t requested);

/**
 * @brief Light-space discontinuity and refinement flags of every view (section 1).
 * @param flags      Receives V * mrgi_multires_texel_count(&tree->layout) bytes.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a tree not built
 *         from this RSM's sizes, bad cameras, bad thresholds or finest level,
 *         a short buffer; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_vpl_cluster_flags(const mrgi_rsm* rsm, const mrgi_rsm_view_camera* cameras,
                                   const mrgi_vpl_tree* tree,
                                   const mrgi_vpl_cluster_params* params, uint8_t* flags,
                                   size_t flags_size, mrgi_error* err);

/**
 * @brief Selection and output (sections 2-3).
 * @param flags     From mrgi_vpl_cluster_flags() with the same params.
 * @param selected  Receives tree->node_count bytes, 1 for a selected node.
 * @param vpls      Receives the VPLs; `capacity` records.
 * @param capacity  Records `vpls` holds; at least params->max_count (the
 *                  count never exceeds it).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, short buffers, a cap
 *         below the roots' count (V * 16 * 16 for S >= 16) or above
 *         MRGI_VPL_CLUSTER_MAX, a capacity below the cap.
 */
mrgi_status mrgi_vpl_clusters_from_flags(const mrgi_vpl_tree* tree, const uint8_t* flags,
                                         size_t flags_size, const mrgi_vpl_cluster_params* params,
                                         uint8_t* selected, size_t selected_size, mrgi_vpl* vpls,
                                         int32_t capacity, mrgi_vpl_cluster_info* out_info,
                                         mrgi_error* err);

/**
 * @brief The whole stage: tree, flags, selection, output (allocates its
 *        work arrays once per call and frees them).
 * @param cameras V view cameras.
 */
mrgi_status mrgi_vpl_select_clusters(const mrgi_rsm* rsm, const mrgi_rsm_view_camera* cameras,
                                     const mrgi_vpl_cluster_params* params, mrgi_vpl* vpls,
                                     int32_t capacity, mrgi_vpl_cluster_info* out_info,
                                     mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
