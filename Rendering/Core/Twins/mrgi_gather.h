/**
 * @file mrgi_gather.h
 * @brief Full-resolution gather of one-bounce indirect light: every receiver
 *        pixel sums every VPL (no visibility). The reference the
 *        multiresolution gather approximates, and the C twin of its shader.
 *
 * Nichols, Shopf and Wyman 2009, "Hierarchical Image-Space Radiosity",
 * section 3.2.2, equations 1 and 5; derivation in Documentation/IndirectLight.md.
 *
 * ## What is computed
 *
 * Per receiver i (position P_i, unit normal N_i) and VPL j (position P_j,
 * unit normal N_j, area A_j, flux Phi_j; see mrgi_vpl.h), with
 * V_ij = P_j - P_i, r^2 = |V_ij|^2, w_ij = V_ij / r = -w_ji:
 *
 *     E_i = sum_j Phi_j * max(0, N_i . w_ij) * max(0, N_j . w_ji) / (pi * r^2 + A_j)
 *
 * This is eq. 1's disk-to-point form factor
 * F_j->i = A_j cos_i cos_j / (pi r^2 + A_j) times the VPL's radiance
 * Phi_j / A_j (eq. 5 with I_j rho_j = Phi_j / A_j), in VTK irradiance units
 * (physical irradiance / pi, mrgi_vpl.h): the indirect radiance the
 * composite shows is albedo_i * E_i; the composite multiplies, this returns E_i.
 *
 * As implemented (the GLSL mirrors it term by term):
 *
 *     d = P_j - P_i;  r2 = dot(d, d)
 *     skip VPL j when r2 == 0                       (direction undefined: contribution 0)
 *     cos_i_r = dot(N_i, d);  cos_j_r = -dot(N_j, d)  (cosines times r)
 *     skip when cos_i_r <= 0 or cos_j_r <= 0        (back-facing or grazing: 0)
 *     E_i += Phi_j * (cos_i_r * cos_j_r / r2) / (pi * r2 + A_j)
 *
 * Guards: r2 > 0 keeps every division defined; with A_j > 0 the denominator
 * is >= A_j, so a VPL adds at most Phi_j / A_j however close it is. A VPL
 * with A_j = 0 is a point light (Phi_j / (pi r^2)); it adds 0 at r = 0.
 *
 * ## Spaces and transforms
 *
 * Receivers are in "receiver space" (eye space for the GPU). VPLs are in
 * world space and are brought over with the caller's 4x4 matrix M
 * (column-major as OpenGL: element (row, col) at m[col * 4 + row]), which
 * must be rigid: last row (0, 0, 0, 1) exactly, upper 3x3 R orthonormal
 * within ::MRGI_GATHER_RIGID_TOLERANCE (a VTK view matrix is). Rigid maps
 * keep areas and the form factor, so A_j is used unchanged:
 *
 *     P_j' = R P_j + t;   N_j' = normalize(R N_j)
 *
 * Receiver normals are normalized too (G-buffer normals need not be unit).
 *
 * ## Receivers and the output
 *
 * Two RGBA float arrays of W x H pixels in OpenGL read-back order: pixel
 * (x, y) at index y * W + x, ROW 0 = BOTTOM (no flip):
 * position xyz + valid flag w (valid when w > MRGI_VALID_THRESHOLD),
 * normal xyz + unused w. The output is a W x H x 3 ::mrgi_image (E_i RGB)
 * in the SAME order, row 0 = bottom, unlike the core's usual top-down
 * images: it compares directly with the GPU read-back; pass it (and the GPU
 * image) through mrgi_image_flip_rows() before writing files.
 * Invalid receivers and malformed ones (valid flag set but non-finite
 * position or normal, or a zero normal) get E = 0.
 *
 * ## Precision and malformed VPLs
 *
 * This C twin accumulates each pixel in double (positions transformed in
 * double from the float inputs) and stores floats, clamped to [0, FLT_MAX]
 * (a sum of point-light VPLs at a vanishing distance could exceed float).
 * The GPU accumulates in float; C/GPU parity is judged at 1e-4 relative
 * error. VPLs with zero flux (empty grid blocks) are skipped. VPLs with any
 * non-finite value, negative flux or area, or a zero normal are skipped and
 * counted (::mrgi_gather_info::vpls_malformed): one bad VPL never poisons an
 * image. (Selection never emits such VPLs; the GPU need not test for them.)
 *
 * ## Visibility (indirect shadows; mrgi_gather_full_visibility())
 *
 * The same sum with each VPL's term multiplied by a visibility V_ij in
 * [0, 1], computed only where the term is > 0 (the GPU does the same):
 *
 * - ::MRGI_GATHER_VISIBILITY_NONE: V = 1; the sum is mrgi_gather_full()'s,
 *   term for term (mrgi_gather_full() is this with no visibility).
 * - ::MRGI_GATHER_VISIBILITY_ISM: imperfect shadow maps (Ritschel et al. 2008
 *   3.3, 2011 6.1): V = mrgi_ism_visibility() of tile j (the VPL's index in
 *   `vpls`), from the VPL's WORLD-space record (position, normal as given)
 *   to the receiver brought back to world space in double and rounded to
 *   float (x_w = R^T (x - t) for M = [R t]). The atlas must have one tile
 *   per VPL (layout vpl_count == vpl_count).
 * - ::MRGI_GATHER_VISIBILITY_VOXELS: screen-space voxels (Nichols, Penmatsa
 *   and Wyman 2010 3.3.1, the naive query): V = mrgi_voxel_march() from the
 *   receiver (its position and G-buffer normal, as float) to the VPL brought
 *   into receiver space (rounded to float), V in {0, 1}. The receivers must
 *   be in the EYE space of the camera the voxels were built with (M the view
 *   matrix); occluders the camera does not see are missed.
 */
#ifndef MRGI_GATHER_H
#define MRGI_GATHER_H

#include "mrgi_error.h"
#include "mrgi_image.h"
#include "mrgi_ism_atlas.h"
#include "mrgi_ism_visibility.h"
#include "mrgi_vpl.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** pi, as used in the denominator pi r^2 + A_j (eq. 1). */
#define MRGI_PI 3.14159265358979323846
/** Largest |R^T R - I| element accepted for the world->receiver rotation. */
#define MRGI_GATHER_RIGID_TOLERANCE 1e-4

/** Receiver pixels as read back from the G-buffer (borrowed; see the file comment). */
typedef struct mrgi_gather_receivers
{
  int32_t width;         /**< W, 1..MRGI_IMAGE_MAX_DIMENSION. */
  int32_t height;        /**< H, 1..MRGI_IMAGE_MAX_DIMENSION. */
  const float* position; /**< W*H RGBA: receiver-space xyz, w = valid flag; row 0 = bottom. */
  const float* normal;   /**< W*H RGBA: receiver-space normal xyz, w unused; row 0 = bottom. */
} mrgi_gather_receivers;

/** Counts of what a gather used and skipped. */
typedef struct mrgi_gather_info
{
  int32_t vpls_used;           /**< VPLs that entered the sums. */
  int32_t vpls_zero_flux;      /**< VPLs skipped because their flux is (0, 0, 0). */
  int32_t vpls_malformed;      /**< VPLs skipped for non-finite/negative values or a zero normal. */
  int64_t receivers_gathered;  /**< Valid, well-formed receivers (E computed). */
  int64_t receivers_invalid;   /**< Receivers whose valid flag is not set (E = 0). */
  int64_t receivers_malformed; /**< Receivers flagged valid but non-finite or with a zero normal (E = 0). */
} mrgi_gather_info;

/**
 * @brief Check that `world_to_receiver` is a rigid transform (see the file comment).
 * @param world_to_receiver 16 floats, column-major.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, non-finite values, a last
 *         row other than (0, 0, 0, 1) or a non-orthonormal 3x3 block.
 */
mrgi_status mrgi_gather_check_transform(const float world_to_receiver[16], mrgi_error* err);

/**
 * @brief Full-resolution gather: E_i for every receiver from every VPL
 *        (formula in the file comment).
 *
 * Cost W * H * vpl_count; meant as a reference, not for interactive use.
 *
 * @param receivers         W x H receiver arrays; pointers not NULL.
 * @param vpls              World-space VPLs (mrgi_vpl_select_grid/importance).
 * @param vpl_count         MRGI_VPL_MIN_COUNT..MRGI_VPL_MAX_COUNT.
 * @param world_to_receiver Rigid column-major 4x4 world -> receiver matrix;
 *                          NULL means identity (receivers in world space).
 * @param out_irradiance    Receives a new W x H x 3 image, row 0 = BOTTOM
 *                          (treated as uninitialized; zeroed on failure).
 * @param out_info          Receives counts; may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments, sizes or count out
 *         of range, a non-rigid matrix; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_gather_full(const mrgi_gather_receivers* receivers, const mrgi_vpl* vpls,
                             int32_t vpl_count, const float* world_to_receiver,
                             mrgi_image* out_irradiance, mrgi_gather_info* out_info,
                             mrgi_error* err);

struct mrgi_voxel_view; /* mrgi_voxel_march.h (which includes this header through mrgi_multires.h) */

/** Kinds of visibility a gather can weight its VPL terms with (file comment). */
typedef enum mrgi_gather_visibility_mode
{
  MRGI_GATHER_VISIBILITY_NONE = 0,  /**< V = 1 (the gathers without visibility). */
  MRGI_GATHER_VISIBILITY_ISM = 1,   /**< Imperfect shadow maps, one tile per VPL (or tree root). */
  MRGI_GATHER_VISIBILITY_VOXELS = 2 /**< Screen-space voxel march per receiver and VPL. */
} mrgi_gather_visibility_mode;

/** The visibility term of a gather (borrowed pointers; see the file comment). */
typedef struct mrgi_gather_visibility
{
  int32_t mode;                           /**< ::mrgi_gather_visibility_mode. */
  const mrgi_ism_atlas_layout* ism_layout; /**< ISM: the atlas layout. */
  const float* ism_depth;                 /**< ISM: push-pulled atlas, width * height floats. */
  mrgi_ism_lookup_params ism_lookup;      /**< ISM: bias and PCF. */
  const struct mrgi_voxel_view* voxels;   /**< VOXELS: the voxel buffer and march parameters. */
} mrgi_gather_visibility;

/**
 * @brief Check a visibility term for a gather with `tile_count` VPLs (or
 *        tree roots): a known mode; ISM: layout and depth not NULL, layout
 *        vpl_count == tile_count, lookup parameters valid
 *        (mrgi_ism_lookup_params_validate()); VOXELS: a view that passes
 *        mrgi_voxel_view_check(). NULL means NONE.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the problem.
 */
mrgi_status mrgi_gather_visibility_check(const mrgi_gather_visibility* visibility,
                                         int32_t tile_count, mrgi_error* err);

/**
 * @brief mrgi_gather_full() with a visibility term (file comment,
 *        "Visibility"); `visibility` NULL or NONE gives mrgi_gather_full()'s
 *        image bit for bit. Errors: mrgi_gather_full()'s and
 *        mrgi_gather_visibility_check()'s (tile_count = vpl_count).
 */
mrgi_status mrgi_gather_full_visibility(const mrgi_gather_receivers* receivers,
                                        const mrgi_vpl* vpls, int32_t vpl_count,
                                        const float* world_to_receiver,
                                        const mrgi_gather_visibility* visibility,
                                        mrgi_image* out_irradiance, mrgi_gather_info* out_info,
                                        mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
