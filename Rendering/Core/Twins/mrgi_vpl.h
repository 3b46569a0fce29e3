/**
 * @file mrgi_vpl.h
 * @brief Virtual point lights (VPLs): the record shared by C and GLSL, and
 *        their selection from a reflective shadow map (RSM).
 *
 * C twin of the GPU "VPL selection" stage (Nichols and Wyman 2009,
 * "Multiresolution Splatting for Indirect Illumination", section 3.1;
 * Nichols, Shopf and Wyman 2009, "Hierarchical Image-Space Radiosity",
 * section 3.2.2). Derivations: Documentation/IndirectLight.md.
 *
 * ## Units (VTK's light model)
 *
 * VTK lights do not attenuate with distance. A Lambertian surface of albedo
 * rho lit by a light of intensity I and colour c from direction l shows the
 * radiance L = rho * X, with the "VTK irradiance"
 *
 *     X = I * c * max(0, n.l) * spot          (physical irradiance / pi)
 *
 * (spot = pow(cos(angle to the axis), exponent) inside the cone, 0 outside,
 * 1 for other lights). Fluxes below are in the same units: flux = radiance * area.
 *
 * ## The RSM contract (produced on the GPU, consumed here)
 *
 * One RSM has V "views" of S x S texels: a spot light has 1 perspective
 * view, a directional light 1 orthographic view, a positional light without
 * a cone 6 perspective cube faces (+X, -X, +Y, -Y, +Z, -Z). Each view has
 * three RGBA32F arrays; texel (x, y) of view v is at index (v * S + y) * S + x
 * (4 floats each), row 0 being the first row as read back from GL (no flip):
 *
 * - position: world x, y, z; w = 1 where a surface was seen, 0 where nothing
 *   was (a texel is "valid" when w > ::MRGI_VALID_THRESHOLD);
 * - normal:   world unit normal x, y, z oriented towards the light; w = 0;
 * - flux:     rgb = reflected flux Phi_t = rho_t * X_t * A_t; w = A_t, the
 *   world-space area the texel covers:
 *     perspective view:  A_t = omega_t * r^2 / max(cos theta_t, MRGI_RSM_MIN_COS),
 *                        omega_t = (2 tan(fov/2) / S)^2 * cos^3(alpha),
 *     orthographic view: A_t = (texel cross-section) / max(cos theta_t, MRGI_RSM_MIN_COS),
 *   r = distance light-surface, theta_t = angle between the surface normal
 *   and the direction to the light, alpha = angle of the texel's ray off the
 *   view axis, fov = the view's full field of view (90 degrees for cube faces).
 *   Phi_t / A_t = rho_t * X_t is the texel's radiance.
 *
 * A valid texel is "usable" when its position xyz, normal xyz, flux rgb and
 * area are all finite, flux rgb >= 0 and area >= 0. Selection ignores valid
 * texels that are not usable and counts them (::mrgi_vpl_selection_info).
 * Invalid texels are ignored whatever they hold.
 *
 * ## The VPL record and the GPU VPL texture
 *
 * A VPL is ::MRGI_VPL_TEXELS RGBA32F texels (one ::mrgi_vpl, 12 floats):
 * texel MRGI_VPL_TEXEL_POSITION = position xyz + area A_j,
 * texel MRGI_VPL_TEXEL_NORMAL   = unit normal xyz + 0,
 * texel MRGI_VPL_TEXEL_FLUX     = flux Phi_j rgb + 0.
 * An array of N ::mrgi_vpl IS the GPU texture's memory: upload it as a 2D
 * RGBA32F texture MRGI_VPL_TEXELS texels wide and N rows tall
 * (`glTexImage2D(..., MRGI_VPL_TEXELS, N, 0, GL_RGBA, GL_FLOAT, vpls)`), and
 * read VPL j's texel k with `texelFetch(vpls, ivec2(k, j), 0)`.
 * A VPL with zero flux (an empty grid block) also has zero area and a zero
 * normal; gathers skip it.
 */
#ifndef MRGI_VPL_H
#define MRGI_VPL_H

#include "mrgi_buffers.h"
#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** RGBA32F texels per VPL in the GPU VPL texture. */
#define MRGI_VPL_TEXELS 3
/** Texel holding position xyz and area A_j. */
#define MRGI_VPL_TEXEL_POSITION 0
/** Texel holding the unit normal xyz (w = 0). */
#define MRGI_VPL_TEXEL_NORMAL 1
/** Texel holding the flux Phi_j rgb (w = 0). */
#define MRGI_VPL_TEXEL_FLUX 2
/** Floats per VPL record (MRGI_VPL_TEXELS RGBA texels). */
#define MRGI_VPL_FLOATS 12
/** Fewest VPLs a caller may request. */
#define MRGI_VPL_MIN_COUNT 1
/** Most VPLs a caller may request or a gather may take (a 64 x 64 grid). */
#define MRGI_VPL_MAX_COUNT 4096

/** Lower bound of cos(theta_t) in the RSM texel area A_t (bounds A_t at grazing angles). */
#define MRGI_RSM_MIN_COS 0.05f
/** Most views of one RSM (the 6 cube faces of a positional light). */
#define MRGI_RSM_MAX_VIEWS 6
/** Largest accepted RSM side S, in texels. */
#define MRGI_RSM_MAX_SIZE 8192
/** A w flag (RSM position.w, G-buffer position.w) means "valid" when it is greater than this. */
#define MRGI_VALID_THRESHOLD MRGI_GBUFFER_VALID_THRESHOLD

/** Rec. 709 luminance weights of the importance pdf: Y = R*R_w + G*G_w + B*B_w. */
#define MRGI_LUMINANCE_R 0.2126
#define MRGI_LUMINANCE_G 0.7152
#define MRGI_LUMINANCE_B 0.0722

/**
 * One VPL; the same 12 floats, in the same order, as its MRGI_VPL_TEXELS
 * RGBA texels (checked at compile time in mrgi_vpl.c).
 */
typedef struct mrgi_vpl
{
  float position[3]; /**< World position (texel MRGI_VPL_TEXEL_POSITION, xyz). */
  float area;        /**< Surface area A_j >= 0 the VPL stands for (texel MRGI_VPL_TEXEL_POSITION, w). */
  float normal[3];   /**< World unit normal (texel MRGI_VPL_TEXEL_NORMAL, xyz); zero for an empty VPL. */
  float pad0;        /**< 0 in a VPL texture (mrgi_vpl_tree.h nodes keep R_P here). */
  float flux[3];     /**< Reflected flux Phi_j rgb >= 0 (texel MRGI_VPL_TEXEL_FLUX, xyz). */
  float pad1;        /**< 0 in a VPL texture (mrgi_vpl_tree.h nodes keep Dmax_P here). */
} mrgi_vpl;

/** A reflective shadow map as read back from the GPU; see the file comment. Borrowed pointers. */
typedef struct mrgi_rsm
{
  int32_t size;          /**< S, texels per side, 1..MRGI_RSM_MAX_SIZE. */
  int32_t view_count;    /**< V, 1..MRGI_RSM_MAX_VIEWS (1 spot/directional, 6 cube). */
  const float* position; /**< V*S*S RGBA: world xyz, w = valid flag. */
  const float* normal;   /**< V*S*S RGBA: world unit normal xyz, w = 0. */
  const float* flux;     /**< V*S*S RGBA: Phi_t rgb, w = A_t. */
} mrgi_rsm;

/** What a selection did, for logs and tests. */
typedef struct mrgi_vpl_selection_info
{
  int32_t vpl_count;            /**< VPLs written. */
  int32_t empty_vpl_count;      /**< Of those, VPLs with zero flux (grid blocks without usable texels, all-black RSM). */
  int64_t usable_texel_count;   /**< Valid, well-formed texels the selection drew from. */
  int64_t rejected_texel_count; /**< Valid texels ignored for non-finite or negative values. */
} mrgi_vpl_selection_info;

/**
 * @brief Check an RSM's sizes and pointers (not its values).
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the bad field.
 */
mrgi_status mrgi_rsm_validate(const mrgi_rsm* rsm, mrgi_error* err);

/**
 * @brief Grid size of mrgi_vpl_select_grid() for a request.
 *
 * G = max(1, floor(sqrt(requested_count / view_count))) (computed exactly, in
 * integers), then G = min(G, rsm_size) so that every block holds a texel.
 * The grid selection writes view_count * G * G VPLs, which is at most
 * requested_count when requested_count >= view_count, and view_count otherwise.
 *
 * @param requested_count MRGI_VPL_MIN_COUNT..MRGI_VPL_MAX_COUNT.
 * @param view_count      1..MRGI_RSM_MAX_VIEWS.
 * @param rsm_size        S, 1..MRGI_RSM_MAX_SIZE.
 * @param out_grid_side   Receives G (may be NULL).
 * @param out_vpl_count   Receives view_count * G * G (may be NULL).
 */
mrgi_status mrgi_vpl_grid_layout(int32_t requested_count, int32_t view_count, int32_t rsm_size,
                                 int32_t* out_grid_side, int32_t* out_vpl_count, mrgi_error* err);

/**
 * @brief Grid selection, the papers' default (Nichols and Wyman 2009, 3.1):
 *        one VPL per block of a regular G x G grid on every view.
 *
 * G comes from mrgi_vpl_grid_layout(). Block (i, j) of view v (i along x, j
 * along y) covers texels x in [floor(i*S/G), floor((i+1)*S/G)) and
 * y in [floor(j*S/G), floor((j+1)*S/G)) (integer division; S need not be a
 * multiple of G). It becomes VPL number (v * G + j) * G + i with
 *
 * - flux Phi_j = sum of the block's usable Phi_t, area A_j = sum of their A_t
 *   (summed in double): energy is exact, the VPL fluxes add up to the RSM's;
 * - position and normal of the usable texel whose centre (x + 1/2, y + 1/2)
 *   is nearest (Euclidean) to the block's centre ((x0 + x1)/2, (y0 + y1)/2);
 *   ties go to the lowest index y * S + x;
 * - no usable texel: every field 0 (zero flux, zero area, zero normal); the
 *   VPL stays in the list so that the count is fixed.
 *
 * @param rsm             Valid RSM (mrgi_rsm_validate()).
 * @param requested_count N, MRGI_VPL_MIN_COUNT..MRGI_VPL_MAX_COUNT.
 * @param vpls            Receives V*G*G records (the GPU texture's memory).
 * @param capacity        Records `vpls` can hold; at least V*G*G.
 * @param out_info        Receives counts (vpl_count = V*G*G); may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad RSM, count or capacity,
 *         NULL `vpls`. Nothing is written on failure.
 */
mrgi_status mrgi_vpl_select_grid(const mrgi_rsm* rsm, int32_t requested_count, mrgi_vpl* vpls,
                                 int32_t capacity, mrgi_vpl_selection_info* out_info,
                                 mrgi_error* err);

/**
 * @brief 1 when texel `index` ((v*S + y)*S + x) is usable (see the file
 *        comment), 0 otherwise. No checks: the caller validated the RSM and index.
 */
int mrgi_rsm_texel_usable(const mrgi_rsm* rsm, int64_t index);

/**
 * @brief One grid block's VPL (the rule of mrgi_vpl_select_grid()), shared
 *        with the light-space tree (mrgi_vpl_tree.h) so both apply the same
 *        sums and tie rule.
 *
 * Block = texels x in [x0, x1), y in [y0, y1) of `view`. Sums the usable
 * texels' flux and area in double in scan order (y outer, x inner), picks
 * the usable texel nearest the block centre ((x0 + x1)/2, (y0 + y1)/2), ties
 * to the lowest index, and fills `out` as mrgi_vpl_select_grid() documents
 * (all zero without a usable texel). No argument checks (hot loop): the
 * caller validated the RSM, 0 <= view < V, 0 <= x0 < x1 <= S, 0 <= y0 < y1 <= S.
 *
 * @param sums     Receives the double sums (flux rgb, area); may be NULL.
 * @param usable   Incremented by the block's usable texels.
 * @param rejected Incremented by its valid texels that are not usable.
 * @return The representative's texel index ((v*S + y)*S + x), -1 for none.
 */
int64_t mrgi_vpl_from_rsm_block(const mrgi_rsm* rsm, int32_t view, int32_t x0, int32_t x1,
                                int32_t y0, int32_t y1, mrgi_vpl* out, double sums[4],
                                int64_t* usable, int64_t* rejected);

/**
 * @brief Scratch doubles mrgi_vpl_select_importance() needs: one per texel, V*S*S.
 * @return 0 for an RSM whose sizes are out of range.
 */
size_t mrgi_vpl_importance_scratch_count(const mrgi_rsm* rsm);

/**
 * @brief Flux importance sampling: N VPLs drawn from the texels of all views
 *        with probability proportional to their flux luminance.
 *
 * Weight of texel t: w_t = MRGI_LUMINANCE_R*Phi_t.r + MRGI_LUMINANCE_G*Phi_t.g
 * + MRGI_LUMINANCE_B*Phi_t.b for a usable texel, 0 otherwise; W = sum w_t;
 * p_t = w_t / W. Every texel with non-zero flux has p_t > 0 (weights are
 * positive and fluxes non-negative), which makes the estimator unbiased.
 *
 * Samples: offset = (splitmix64(seed) >> 11) * 2^-53 in [0, 1), then for
 * k = 0..N-1, u_k = (k + offset) / N (stratified: one sample per stratum
 * [k/N, (k+1)/N), each uniform in it over random seeds). Texel of sample k:
 * the first t (in index order (v*S + y)*S + x) whose inclusive prefix sum
 * of weights exceeds u_k * W (the last texel with w_t > 0 if rounding leaves
 * none). VPL k = that texel's position and normal with
 *
 *     Phi_k = Phi_t / (N p_t),   A_k = A_t / (N p_t)     (computed in double)
 *
 * so E[sum_k Phi_k] = sum_t Phi_t over usable texels, and Phi_k / A_k keeps
 * the texel's radiance. A_k is clamped to FLT_MAX (only reachable for
 * texels whose flux is near the float underflow). W = 0 (no usable texel
 * with flux) gives N all-zero VPLs. Deterministic for a given seed.
 *
 * @param rsm             Valid RSM.
 * @param count           N, MRGI_VPL_MIN_COUNT..MRGI_VPL_MAX_COUNT.
 * @param seed            Any value; the same seed gives the same VPLs.
 * @param scratch         NULL (the function allocates V*S*S doubles once,
 *                        before sampling) or caller memory for the prefix sums.
 * @param scratch_count   Doubles in `scratch`; at least
 *                        mrgi_vpl_importance_scratch_count() when scratch is not NULL.
 * @param vpls            Receives N records.
 * @param capacity        Records `vpls` can hold; at least N.
 * @param out_info        Receives counts (vpl_count = N); may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a bad RSM, count, capacity,
 *         scratch size or NULL `vpls`; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_vpl_select_importance(const mrgi_rsm* rsm, int32_t count, uint64_t seed,
                                       double* scratch, size_t scratch_count, mrgi_vpl* vpls,
                                       int32_t capacity, mrgi_vpl_selection_info* out_info,
                                       mrgi_error* err);

/**
 * @brief The GPU VPL texture's data for `vpls`: MRGI_VPL_FLOATS floats per
 *        VPL (the same memory, no copy). See the file comment for the texture shape.
 */
static inline const float* mrgi_vpl_texture_data(const mrgi_vpl* vpls)
{
  return (const float*)(const void*)vpls;
}

#ifdef __cplusplus
}
#endif

#endif
