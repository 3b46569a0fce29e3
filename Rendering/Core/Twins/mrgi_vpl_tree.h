/**
 * @file mrgi_vpl_tree.h
 * @brief The light-space pyramid of a reflective shadow map (RSM): every
 *        view presented as a G-buffer seen from the light, and one VPL record
 *        per node of its mipmap with the node's flux and area sums.
 *
 * Papers: Nichols, Shopf and Wyman 2009, "Hierarchical Image-Space
 * Radiosity" (NSW09), sections 3.3-3.5: light-space patches are the texels
 * of a min-max mipmap of the RSM, 16 x 16 roots; each patch is one VPL.
 * Spec: shared/plans/paper-specs.md, Package 1, 1.1. Units and the RSM
 * contract: mrgi_vpl.h.
 *
 * ## 1. The RSM view as a G-buffer (mrgi_rsm_view_receivers)
 *
 * View v's camera (::mrgi_rsm_view_camera) is its rigid world -> view
 * transform M (column-major, view space looks down -z; per cube face for
 * positional lights) and its projection: perspective with the view's full
 * field of view (spot: twice the cone angle; cube faces: 90 degrees), or
 * orthographic with half the view's extent as the parallel scale
 * (directional lights). The receivers are a T x T G-buffer, T =
 * mrgi_vpl_tree_side(S) (S rounded up to a power of two), rows bottom-up
 * as the RSM (row 0 = the first row read back from GL):
 * - texel (x, y) with x, y < S and usable (mrgi_rsm_texel_usable()):
 *   position = (M p, MRGI_GBUFFER_VALID), normal = (R n, 0), R = M's 3x3;
 * - every other texel (invalid, rejected, or padding x >= S or y >= S): zeros
 *   (w = 0, not valid).
 * These positions and normals are what mrgi_multires_mipmap_build() and
 * mrgi_multires_flags_compute() read on the eye side, so the light side's
 * discontinuity flags are the eye side's code, unchanged. The pixel-size
 * coefficients come from mrgi_multires_pixel_size_coefficients() with the
 * camera's projection and height S (the texel pitch of the real map, not of
 * the padding).
 *
 * ## 2. Node layout
 *
 * One ::mrgi_multires_layout for T x T with coarsest_side =
 * MRGI_VPL_TREE_ROOT_SIDE (NSW09's 16 x 16 roots; a map smaller than that
 * has one level). Level i has w_i x w_i nodes (w_i = T / 2^i); node (x, y)
 * of level i covers the texels [x 2^i, (x+1) 2^i) x [y 2^i, (y+1) 2^i),
 * clipped to the map's S x S (the rest is padding, never usable). Records
 * are stored coarse levels first and contiguous (NSW09 3.5's tree texture):
 *
 *     index = level_first[i] + (v * w_i + y) * w_i + x,
 *     level_first[L] = 0, level_first[i] = level_first[i+1] + V * w_{i+1}^2.
 *
 * ## 3. Node records
 *
 * Node P's ::mrgi_vpl is mrgi_vpl_from_rsm_block() on its clipped block:
 * Phi_P = sum of the usable texels' Phi_t and A_P = sum of their A_t, summed
 * in double in scan order then rounded to float (clamped to FLT_MAX);
 * position and normal of the usable texel nearest the block centre, ties to
 * the lowest index. For a power-of-two S, the level-k records of view v are
 * therefore bit-equal to mrgi_vpl_select_grid() with G = S / 2^k (the
 * grid's blocks are the same texels). The pads carry the patch's extent:
 * - pad0 = R_P: the largest world distance from the representative's
 *   position to a usable texel position of the block (bounding radius);
 * - pad1 = Dmax_P: the largest light distance over the block's usable
 *   texels, |M p| for a perspective view (the light sits at the view
 *   origin), max(0, -(M p).z) for an orthographic one (NSW09 3.5's "max depth
 *   over the patch").
 * Both are computed in double and rounded up to float; 0 for an empty node.
 * The exact double sums are kept too (`sums`, 4 per node: flux rgb, area),
 * so that the flux over any cut of the tree adds up to the RSM's total to
 * double rounding. A VPL uploaded for the gather must have zero pads
 * (mrgi_vpl.h); mrgi_vpl_clusters.h clears them.
 *
 * ## Errors
 *
 * ::MRGI_ERR_INVALID_ARGUMENT for a bad RSM (mrgi_rsm_validate()), a NULL
 * pointer, a view index out of range, a transform that is not rigid
 * (mrgi_gather_check_transform()), a bad projection or a short array;
 * ::MRGI_ERR_OUT_OF_MEMORY. An RSM whose views see nothing is no error: its
 * tree has every record zero and nonempty_node_count = 0.
 */
#ifndef MRGI_VPL_TREE_H
#define MRGI_VPL_TREE_H

#include "mrgi_error.h"
#include "mrgi_gather.h"
#include "mrgi_multires.h"
#include "mrgi_vpl.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Side of the tree's coarsest level: 16 x 16 roots per view (NSW09 3.5). */
#define MRGI_VPL_TREE_ROOT_SIDE 16

/** The camera of one RSM view (section 1). */
typedef struct mrgi_rsm_view_camera
{
  float world_to_view[16];             /**< Rigid, column-major (m[col * 4 + row]). */
  mrgi_multires_projection projection; /**< Full fov (perspective) or half extent (parallel). */
} mrgi_rsm_view_camera;

/** The light-space pyramid of one RSM (sections 2-3). Filled by mrgi_vpl_tree_build(). */
typedef struct mrgi_vpl_tree
{
  int32_t rsm_size;                /**< S of the RSM it was built from. */
  int32_t side;                    /**< T = mrgi_vpl_tree_side(S). */
  int32_t view_count;              /**< V. */
  mrgi_multires_layout layout;     /**< T x T, coarsest side MRGI_VPL_TREE_ROOT_SIDE. */
  int64_t level_first[MRGI_MULTIRES_MAX_LEVELS]; /**< First record of each level (section 2). */
  int64_t node_count;              /**< V * sum over the levels of w_i^2. */
  int64_t nonempty_node_count;     /**< Nodes with at least one usable texel. */
  int64_t usable_texel_count;      /**< Usable texels of the RSM (each counted once). */
  int64_t rejected_texel_count;    /**< Valid texels that are not usable (counted once). */
  mrgi_vpl* nodes;                 /**< node_count records (section 3). */
  double* sums;                    /**< 4 doubles per node: flux rgb and area sums. */
} mrgi_vpl_tree;

/** @brief T: the smallest power of two >= rsm_size; 0 when rsm_size is outside 1..MRGI_RSM_MAX_SIZE. */
int32_t mrgi_vpl_tree_side(int32_t rsm_size);

/** @brief Record index of node (x, y) of `level` in `view` (section 2). No checks. */
static inline int64_t mrgi_vpl_tree_index(const mrgi_vpl_tree* tree, int32_t level, int32_t view,
                                          int32_t x, int32_t y)
{
  const int64_t w = tree->layout.level_width[level];
  return tree->level_first[level] + ((int64_t)view * w + y) * w + x;
}

/**
 * @brief Check a view camera: rigid transform, valid projection (fov in
 *        (0, 180) degrees or a finite positive parallel scale).
 */
mrgi_status mrgi_rsm_view_camera_check(const mrgi_rsm_view_camera* camera, mrgi_error* err);

/**
 * @brief The receivers of RSM view `view` in the light's view space (section 1).
 * @param rsm      Valid RSM.
 * @param view     0..V-1.
 * @param camera   The view's camera (only its transform is used here).
 * @param position Receives T*T RGBA floats.
 * @param normal   Receives T*T RGBA floats.
 * @param count    Floats each array holds: at least 4*T*T.
 * @param out      Receives a T x T mrgi_gather_receivers over the two arrays.
 */
mrgi_status mrgi_rsm_view_receivers(const mrgi_rsm* rsm, int32_t view,
                                    const mrgi_rsm_view_camera* camera, float* position,
                                    float* normal, size_t count, mrgi_gather_receivers* out,
                                    mrgi_error* err);

/**
 * @brief Build the node records of every view (sections 2-3).
 * @param cameras V cameras, one per view (for Dmax_P).
 * @param out     Receives the tree (treated as uninitialized; zeroed on
 *                failure); release with mrgi_vpl_tree_destroy().
 */
mrgi_status mrgi_vpl_tree_build(const mrgi_rsm* rsm, const mrgi_rsm_view_camera* cameras,
                                mrgi_vpl_tree* out, mrgi_error* err);

/** @brief Free the arrays and zero the struct. NULL-safe and idempotent. */
void mrgi_vpl_tree_destroy(mrgi_vpl_tree* tree);

#ifdef __cplusplus
}
#endif

#endif
