/**
 * @file mrgi_vpl_tree_gather.h
 * @brief The hierarchical image-space radiosity (HISR) gather: every
 *        receiver walks the light-space VPL tree (mrgi_vpl_tree.h) depth
 *        first from its 16 x 16 roots and refines a node only where its
 *        form-factor bound exceeds a threshold tau. C twin of the GPU tree
 *        gather (vtkMRGIGatherFS.glsl with MRGI_GATHER_TREE).
 *
 * Paper: Nichols, Shopf and Wyman 2009, "Hierarchical Image-Space
 * Radiosity" (NSW09), section 3.5: the node records in one texture, coarse
 * levels first; per receiver a depth-first traversal with an explicit
 * stack; a node is used as one VPL when it is "small enough" as seen from
 * the receiver, otherwise its four children are visited. Spec:
 * shared/plans/paper-specs.md, Package 1, 1.3; derivation of the bound in
 * Documentation/IndirectLight.md, "The VPL tree".
 *
 * ## 1. The refinement bound (VTK's non-attenuating light units)
 *
 * A node P (a light-space patch: representative position c_P, normal n_P,
 * summed area A_P and flux Phi_P, bounding radius R_P, mrgi_vpl_tree.h
 * section 3) adds, at a receiver x with normal n_x (mrgi_gather.h),
 *
 *     E_P(x) = Phi_P * F_P(x) / A_P,   F_P(x) = A_P cos_x cos_P / (pi d^2 + A_P)
 *
 * with d = |c_P - x|. Every texel of the patch lies within R_P of c_P, so
 * d_min = max(0, |c_P - x| - R_P) bounds the distance of every texel from
 * below, and with both cosines <= 1
 *
 *     B_P(x) = A_P / (pi d_min^2 + A_P)                     (B_P = 0 when A_P = 0)
 *
 * bounds the patch's form factor from above (it is increasing in A_P and
 * decreasing in d): F_P(x) <= B_P(x) wherever within R_P of c_P the
 * representative lies, and every texel t of P has
 * A_t cos_x cos_t / (pi d_t^2 + A_t) <= B_P(x) (A_t <= A_P, d_t >= d_min).
 * It does not bound the sum of the texels' disk form factors (the disk
 * model counts overlapping solid angle twice when d_min is small); that
 * sum is bounded by A_P / (pi d_min^2) instead. B_P is in [0, 1]: B_P = 1
 * exactly when d_min = 0 (the receiver is inside the patch's bounding sphere).
 *
 * ## 2. The traversal (per receiver, every view, every root)
 *
 * For every root (level L = layout.level_count - 1; global root index
 * r = (v * w_L + y) * w_L + x over views v) in increasing r, push the root;
 * while the stack is not empty, pop node P (level i) and:
 *
 * 1. skip P when its flux is (0, 0, 0): every descendant has zero flux too
 *    (fluxes are sums of non-negative texel fluxes); a malformed record
 *    (mrgi_gather.h; mrgi_vpl_tree_build() makes none) is skipped too;
 * 2. cull P when its whole bounding sphere is behind the receiver's plane,
 *    n_x . (c_P - x) + R_P <= 0: every texel of P has cos_x <= 0 and adds 0,
 *    so culling is exact for every tau;
 * 3. refine P when i > 0 and B_P(x) > tau: push its children of level i - 1,
 *    (2x+1, 2y+1), (2x, 2y+1), (2x+1, 2y), (2x, 2y) in this order, so that
 *    they pop in scan order (2x, 2y) first;
 * 4. otherwise use P as one VPL: E += mrgi_gather_full()'s term for P's
 *    record (position, normal, area, flux; the pads are ignored), and count
 *    one VPL for the receiver.
 *
 * Every node popped counts in nodes_visited; only step 4 counts a VPL (a
 * culled node is no VPL). The node is brought into receiver space first
 * (P' = R P + t, N' = normalize(R N), mrgi_gather.h); the cull and B_P use
 * P' and the receiver, which a rigid map leaves at the same distances.
 *
 * Consequences (the invariants core.TestVPLTreeGather checks):
 * - tau >= 1: no node is refined (B_P <= 1), every receiver uses the roots:
 *   the same sum, term for term and in the same order, as mrgi_gather_full()
 *   over the level-L records (pads ignored); for a power-of-two S those are
 *   mrgi_vpl_select_grid() with G = w_L (16 for S >= 16) on every view
 *   (mrgi_vpl_tree.h section 3). For another S the roots cover T/16-texel
 *   blocks clipped to S, not the grid's floor(i S / 16) blocks;
 * - tau = 0: every node with A_P > 0 is refined down to level 0, so the sum
 *   is mrgi_gather_full() over every usable texel of the RSM as its own VPL
 *   (texels with A_t = 0 and flux > 0, which an RSM does not produce, would
 *   stay merged in the coarsest zero-area ancestor);
 * - energy is conserved for every tau (a refined node is replaced by
 *   children whose fluxes add up to its own), the selected nodes of a
 *   receiver partition the usable texels it does not cull.
 *
 * ## 3. The GPU texture and batching
 *
 * The records go into one RGBA32F texture of
 * MRGI_VPL_TREE_RECORDS_PER_ROW * MRGI_VPL_TEXELS texels per row
 * (mrgi_vpl_tree_texture_size()); record k's texel t is at
 * (MRGI_VPL_TEXELS * (k % MRGI_VPL_TREE_RECORDS_PER_ROW) + t,
 *  k / MRGI_VPL_TREE_RECORDS_PER_ROW). The tree's pads (R_P in the normal
 * texel's w, Dmax_P in the flux texel's w) travel with it; the gather reads R_P.
 *
 * llvmpipe stops a loop silently after 65,535 iterations, so the GPU
 * traverses the roots in batches (one draw each, added with blending): a
 * batch of K roots costs at most K * N_sub loop iterations, N_sub =
 * (4^(L+1) - 1) / 3 the nodes of one root's subtree, and
 * mrgi_vpl_tree_roots_per_batch() returns the largest K with
 * K * N_sub <= MRGI_VPL_TREE_MAX_LOOP_ITERATIONS. Batching changes only
 * the order of the float additions; the C twin sums every receiver in
 * double in root order, batch by batch.
 *
 * The stack holds at most 3 L + 1 entries; MRGI_VPL_TREE_STACK_SIZE bounds
 * it for every tree this gather accepts (S <= MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE).
 *
 * ## 4. Visibility (indirect shadows; mrgi_vpl_tree_gather_visibility())
 *
 * Step 4's term is multiplied by a visibility V in [0, 1] where it is > 0
 * (mrgi_gather.h, "Visibility"); the traversal (cull, bound, refinement)
 * does not change, nor do the counts.
 *
 * - ISM: imperfect shadow maps exist only per ROOT: the ISM pass renders one
 *   tile per VPL of the flat VPL cache, which in Tree mode holds the roots
 *   in global root order r (vtkMRGIVPLSelection). Every node of root r's
 *   subtree is therefore tested with tile r, looked up from root r's record
 *   (world-space position c_r and normal n_r, as stored in the tree) towards
 *   the receiver: the node's occlusion is approximated by that of its root
 *   patch's representative point (Ritschel et al. 2008 3.3 render one ISM per
 *   VPL; a node is a part of the root's patch, seen from the same side and
 *   within R_r of c_r). V is thus constant over a root's subtree for one
 *   receiver; both C and GLSL compute it once per (receiver, root), at the
 *   first node of the subtree whose term is > 0. Shadows of occluders
 *   closer to a node than to c_r are approximate, more so for coarse trees.
 *   The atlas must have V * w_L^2 tiles (mrgi_vpl_tree_root_count()).
 * - VOXELS: one march per (receiver, node used as a VPL), to the node's
 *   position and normal in receiver (eye) space, as the flat gather.
 *   (vtkMRGIGather's GPU tree gathers draw fewer roots per batch so that
 *   every node's march fits llvmpipe's loop budget, mrgi_voxel_march.h,
 *   and refuse a tree whose one root's subtree alone does not.)
 *
 * ## Errors
 *
 * ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments, a tree that was not
 * built (no nodes), whose layout, level offsets or node count are not what
 * mrgi_vpl_tree_build() makes for its RSM size, or whose RSM side exceeds
 * MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE,
 * a tau that is NaN or negative (+inf is allowed and means tau >= 1), bad
 * receiver sizes, a non-rigid matrix (mrgi_gather_check_transform());
 * ::MRGI_ERR_OUT_OF_MEMORY. On error both images are empty (zeroed structs)
 * and the info is zero. Invalid and malformed receivers get E = 0 and
 * 0 VPLs, as in mrgi_gather_full(). The gather allocates only its output
 * images; the stack is MRGI_VPL_TREE_STACK_SIZE entries on the C stack.
 */
#ifndef MRGI_VPL_TREE_GATHER_H
#define MRGI_VPL_TREE_GATHER_H

#include "mrgi_error.h"
#include "mrgi_gather.h"
#include "mrgi_image.h"
#include "mrgi_vpl_tree.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Node records per row of the tree texture (section 3). */
#define MRGI_VPL_TREE_RECORDS_PER_ROW 1024
/** Most loop iterations one GPU invocation may run (llvmpipe's silent limit is 65,535). */
#define MRGI_VPL_TREE_MAX_LOOP_ITERATIONS 65535
/** Largest RSM side the tree gather accepts (bounds the levels, the stack and the texture height). */
#define MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE 1024
/** Entries of the traversal stack (3 L + 1 <= 19 for S <= 1024, L <= 6). */
#define MRGI_VPL_TREE_STACK_SIZE 24
/** Default threshold tau of vtkMRGIVPLSelection's Tree mode. */
#define MRGI_VPL_TREE_DEFAULT_THRESHOLD 0.05

/** What a tree gather did, for logs, tests and the VPLs-per-pixel statistic. */
typedef struct mrgi_vpl_tree_gather_info
{
  int64_t receivers_gathered;  /**< Valid, well-formed receivers. */
  int64_t receivers_invalid;   /**< Receivers whose valid flag is not set. */
  int64_t receivers_malformed; /**< Flagged valid but non-finite or with a zero normal. */
  int64_t vpls_used;           /**< Sum over receivers of the nodes used as VPLs (step 4). */
  int64_t nodes_visited;       /**< Sum over receivers of the nodes popped. */
  int32_t max_vpls_per_pixel;  /**< Largest count of one receiver. */
  int32_t max_stack_depth;     /**< Deepest stack any receiver reached. */
  double mean_vpls_per_pixel;  /**< vpls_used / receivers_gathered (0 without receivers). */
} mrgi_vpl_tree_gather_info;

/**
 * @brief Roots per GPU batch (section 3): the largest K >= 1 with
 *        K * N_sub <= MRGI_VPL_TREE_MAX_LOOP_ITERATIONS (not capped by the
 *        root count: 65,535 for a one-level tree); 0 for a tree that was
 *        not built or whose one root's subtree alone exceeds the limit (S > 2048).
 */
int32_t mrgi_vpl_tree_roots_per_batch(const mrgi_vpl_tree* tree);

/** @brief Roots of all views: V * w_L^2; 0 for a tree that was not built. */
int32_t mrgi_vpl_tree_root_count(const mrgi_vpl_tree* tree);

/**
 * @brief The tree texture's size in texels (section 3):
 *        width = MRGI_VPL_TREE_RECORDS_PER_ROW * MRGI_VPL_TEXELS,
 *        height = ceil(node_count / MRGI_VPL_TREE_RECORDS_PER_ROW).
 *        Its data is `nodes` followed by zero records up to width * height / MRGI_VPL_TEXELS.
 */
mrgi_status mrgi_vpl_tree_texture_size(const mrgi_vpl_tree* tree, int32_t* out_width,
                                       int32_t* out_height, mrgi_error* err);

/**
 * @brief B_P(x) of section 1 in double, for one node record (c_P = position,
 *        A_P = area, R_P = pad0) and a world-space receiver; 0 when A_P <= 0;
 *        1 (refine) for NULL arguments or a distance that is not a number.
 */
double mrgi_vpl_tree_refinement_bound(const mrgi_vpl* node, const double receiver[3]);

/**
 * @brief The tree gather (section 2) at every receiver.
 * @param receivers          W x H receivers (mrgi_gather.h; receiver space, row 0 = bottom).
 * @param tree               Built by mrgi_vpl_tree_build() (world space).
 * @param threshold          tau >= 0 (+inf allowed).
 * @param world_to_receiver  Rigid column-major 4x4, or NULL for identity (as mrgi_gather_full()).
 * @param out_irradiance     Receives a new W x H x 3 image of E (row 0 = bottom), as mrgi_gather_full().
 * @param out_vpls_per_pixel NULL, or receives a new W x H x 1 image: the VPLs each receiver used
 *                           (row 0 = bottom; 0 for invalid and malformed receivers).
 * @param out_info           Receives counts; may be NULL.
 */
mrgi_status mrgi_vpl_tree_gather(const mrgi_gather_receivers* receivers, const mrgi_vpl_tree* tree,
                                 double threshold, const float* world_to_receiver,
                                 mrgi_image* out_irradiance, mrgi_image* out_vpls_per_pixel,
                                 mrgi_vpl_tree_gather_info* out_info, mrgi_error* err);

/**
 * @brief mrgi_vpl_tree_gather() with a visibility term (section 4);
 *        `visibility` NULL or NONE gives mrgi_vpl_tree_gather()'s images
 *        bit for bit. Errors: mrgi_vpl_tree_gather()'s and
 *        mrgi_gather_visibility_check()'s with tile_count = the root count.
 */
mrgi_status mrgi_vpl_tree_gather_visibility(const mrgi_gather_receivers* receivers,
                                            const mrgi_vpl_tree* tree, double threshold,
                                            const float* world_to_receiver,
                                            const mrgi_gather_visibility* visibility,
                                            mrgi_image* out_irradiance,
                                            mrgi_image* out_vpls_per_pixel,
                                            mrgi_vpl_tree_gather_info* out_info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
