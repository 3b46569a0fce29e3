/**
 * @file mrgi_direct_shadow.h
 * @brief Shadow factors of VTK's lights from the reflective shadow maps
 *        (hard PCF, or PCSS soft shadows, Fernando 2005): the C twin of
 *        vtkMRGIDirectShadows and vtkMRGIDirectShadowFS.glsl.
 *
 * The reflective shadow maps (mrgi_buffers.h) are the shadow maps: a light
 * has 1 view (spot: perspective; directional: orthographic) or up to 6
 * (point: cube faces). A view texel holds the WORLD position of the surface
 * nearest the light (w > MRGI_GBUFFER_VALID_THRESHOLD where geometry was
 * drawn). For a receiver (world position P, unit normal N) the factor is
 * the fraction of shadow-map taps that do not occlude it: 1 fully lit, 0 in
 * the umbra. Documentation/DirectShadows.md explains the choices.
 *
 * **Views.** ::mrgi_direct_shadow_view: world -> view matrix (column-major,
 * OpenGL's order; view space looks down -z; rigid), the projection's scale
 * terms sx = P[0][0], sy = P[1][1] (centred projections: no off-axis
 * terms), perspective or orthographic, the near plane (perspective only),
 * S and the S x S x 4 world positions (rows bottom-up). Texel (i, j) covers
 * NDC [2 i / S - 1, 2 (i + 1) / S - 1] in x (the same in y).
 *
 * **Depth.** Light-view depth d(X) = -(world_to_view X).z, for both kinds
 * of view. The depth map of a view (mrgi_direct_shadow_depth_map()) holds
 * d of each valid texel's position, or MRGI_DIRECT_SHADOW_NO_OCCLUDER
 * (< 0) where the texel is invalid (w not above the threshold, a non-finite
 * position, or d not above 0): such texels never occlude.
 *
 * **Which view** (mrgi_direct_shadow_select_view()): with the receiver's
 * view coordinates (x, y, z), d = -z, a view holds it when c <= 1, where
 * c = max(|sx x|, |sy y|) / d for perspective views (which also need
 * d > near) and c = max(|sx x|, |sy y|) for orthographic ones. Among the
 * views that hold it the smallest c wins, ties to the lowest index. For
 * cube faces c is the ratio of the two minor to the major direction
 * component, so the rule partitions every direction into exactly one face.
 * No view: factor 1 (the light's views cover all the scene's props, so a
 * receiver outside them is outside the light's reach or the RSM pass
 * skipped it).
 *
 * **Footprint.** T = 2 / (S min(sx, sy)) and the receiver's texel
 * footprint f = d T (perspective) or f = T (orthographic), world units.
 * Every length below is in texels or in f, so factors do not depend on the
 * scene's scale.
 *
 * **Bias (receiver plane).** N is flipped to face the light (toward
 * -view position for perspective views, toward +z for orthographic ones).
 * A tap of texel (i, j) (NDC centre cx, cy) compares the texel's depth with
 * the depth of the receiver's tangent plane along that texel's ray:
 * - perspective: a = cx / sx, b = cy / sy, a_P = x / d, b_P = y / d;
 *   plane depth = d + d (Nx (a_P - a) + Ny (b_P - b)) / min(N . (a, b, -1),
 *   -1 / MRGI_DIRECT_SHADOW_MAX_SLOPE);
 * - orthographic: plane depth = d + (Nx (cx / sx - x) + Ny (cy / sy - y)) /
 *   max(Nz, 1 / MRGI_DIRECT_SHADOW_MAX_SLOPE).
 * The clamp bounds the plane's slope to MRGI_DIRECT_SHADOW_MAX_SLOPE (about
 * 88 degrees), so nothing is infinite. The tap occludes when it is valid,
 * inside the map and its depth < plane depth - MRGI_DIRECT_SHADOW_BIAS_TEXELS
 * f. A planar receiver never shadows itself at any kernel size or angle up
 * to the clamp; an occluder closer than the bias to the receiver's plane
 * (about one texel) casts nothing (no acne, at most ~1 texel of "peter
 * panning").
 *
 * **Taps.** The receiver projects to continuous texel coordinates
 * u = (sx x / d * 0.5 + 0.5) S (orthographic: without / d), v likewise. A
 * grid of n x n taps of radius w texels: tap (k, l) reads texel
 * (floor(u + o_k), floor(v + o_l)), o_k = ((k + 0.5) / n * 2 - 1) w. Taps
 * outside [0, S) do not occlude. The same grid and order on the GPU.
 * - HARD: PCF, n = MRGI_DIRECT_SHADOW_HARD_SIDE (3), w = n / 2 (so the
 *   taps are the texels at offsets -1, 0, 1: a 3 x 3 box); factor = the
 *   fraction of taps that do not occlude.
 * - SOFT (PCSS): (1) blocker search: n = MRGI_DIRECT_SHADOW_BLOCKER_SIDE,
 *   radius R_s; no occluding tap -> factor 1 exactly; else the blockers'
 *   mean depth d_b. (2) PCF with n = samples_side and radius w_p.
 *   With r the light radius (world units), d_n = max(near,
 *   MRGI_DIRECT_SHADOW_SEARCH_NEAR d) (orthographic: near = 0):
 *   - perspective: R_s = r (d - d_n) / (d d_n T), w_p = r (d - d_b) / (d d_b T)
 *     (the light disc's shadow through a blocker at depth d_b, at the
 *     receiver, in receiver texels);
 *   - orthographic (directional light): an angular radius theta =
 *     r min(sx, sy) = r / (half-width of the view, which the RSM pass fits
 *     to the scene's bounding sphere): R_s = theta (d - d_n) / T,
 *     w_p = theta (d - d_b) / T.
 *   Both are clamped to [MRGI_DIRECT_SHADOW_MIN_RADIUS,
 *   MRGI_DIRECT_SHADOW_MAX_RADIUS] texels. r -> 0 gives the PCF of
 *   radius MRGI_DIRECT_SHADOW_MIN_RADIUS (a hard edge).
 *
 * **Grazing receivers.** Where the cosine between the (light-facing)
 * normal and the direction to the light falls below c0 = 1 / sqrt(1 +
 * MRGI_DIRECT_SHADOW_MAX_SLOPE^2) (about 1.8 degrees above the surface),
 * the slope clamp no longer bounds the receiver plane and a lit surface
 * would shadow itself in stripes. The occluded fraction is therefore
 * scaled by g = clamp((cos - c0) / c0, 0, 1)
 * (mrgi_direct_shadow_grazing_weight()): full above 2 c0, none below c0.
 * VTK's diffuse light there is at most 2 c0 (6%) of the light's, so a
 * grazing surface in true shadow keeps at most that much light.
 *
 * **Errors.** Never NaN: a receiver with a non-finite position or normal,
 * a zero normal, a view with S < 1, no positions, a non-finite matrix or
 * scale <= 0 (perspective: near <= 0) give factor 1 (the view is skipped)
 * and count in ::mrgi_direct_shadow_stats. Computation is in double; the
 * GPU computes in float, so a tap can fall in the neighbouring texel (or a
 * depth compare flip) where a value lies within rounding of a boundary; the
 * taps of a grid row share their offset, so a row moves as one (n taps).
 * The parity test allows a few such pixels, by at most 2 / n.
 */
#ifndef MRGI_DIRECT_SHADOW_H
#define MRGI_DIRECT_SHADOW_H

#include "mrgi_error.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Modes (::mrgi_direct_shadow_params::mode). */
#define MRGI_DIRECT_SHADOW_HARD 0
#define MRGI_DIRECT_SHADOW_SOFT 1
/** Views of one light at most (a cube). */
#define MRGI_DIRECT_SHADOW_MAX_VIEWS 6
/** Side of the hard PCF kernel (3 x 3 texels). */
#define MRGI_DIRECT_SHADOW_HARD_SIDE 3
/** Side of the PCSS blocker-search grid (8 x 8 = 64 taps). */
#define MRGI_DIRECT_SHADOW_BLOCKER_SIDE 8
/** Largest PCSS filter side (14 x 14 = 196 taps, BMR's count). */
#define MRGI_DIRECT_SHADOW_MAX_SIDE 14
/** The pass's default PCSS filter side (8 x 8 = 64 taps). */
#define MRGI_DIRECT_SHADOW_DEFAULT_SIDE 8
/** Constant depth bias, in receiver texel footprints. */
#define MRGI_DIRECT_SHADOW_BIAS_TEXELS 1.0
/** Largest receiver-plane slope used by the bias (tan of about 88 degrees). */
#define MRGI_DIRECT_SHADOW_MAX_SLOPE 32.0
/** Nearest blocker depth the search accounts for, as a fraction of the receiver's depth. */
#define MRGI_DIRECT_SHADOW_SEARCH_NEAR 0.25
/** Search and filter radii, texels. */
#define MRGI_DIRECT_SHADOW_MIN_RADIUS 0.5
#define MRGI_DIRECT_SHADOW_MAX_RADIUS 32.0
/** Depth-map value of a texel that holds no occluder. */
#define MRGI_DIRECT_SHADOW_NO_OCCLUDER (-1.0f)
/**
 * The light radius vtkMRGIPass uses when none is set, as a fraction of the
 * visible props' bounding radius (VTK's lights are points; measured in
 * Documentation/DirectShadows.md).
 */
#define MRGI_SHADOW_AUTO_LIGHT_RADIUS 0.01
/** Largest BMR level mrgi_direct_shadow_level() takes (blocks of 2^8 = 256 pixels). */
#define MRGI_DIRECT_SHADOW_MAX_LEVEL 8

/** One shadow-map view (see the file comment). Plain data, nothing owned. */
typedef struct mrgi_direct_shadow_view
{
  double world_to_view[16]; /**< column-major: element (row r, column c) at [4 c + r] */
  int perspective;          /**< 1 perspective, 0 orthographic */
  double scale[2];          /**< sx = P[0][0], sy = P[1][1] of the projection, > 0 */
  double near_plane;        /**< perspective: depth of the near plane, > 0 */
  int size;                 /**< S, texels per side, >= 1 */
  const float* positions;   /**< S x S x 4 world positions, rows bottom-up */
} mrgi_direct_shadow_view;

/** How factors are computed. */
typedef struct mrgi_direct_shadow_params
{
  int mode;            /**< MRGI_DIRECT_SHADOW_HARD or _SOFT */
  int samples_side;    /**< SOFT: PCF side n, 1..MRGI_DIRECT_SHADOW_MAX_SIDE (n^2 taps) */
  double light_radius; /**< SOFT: world units, >= 0 (directional: see the file comment) */
} mrgi_direct_shadow_params;

/** Counted problems (add up over calls; zero it first). */
typedef struct mrgi_direct_shadow_stats
{
  long long invalid_receivers; /**< non-finite position or normal, zero normal: factor 1 */
  long long invalid_views;     /**< views skipped as degenerate (per receiver that looked) */
  long long outside;           /**< receivers that no view holds: factor 1 */
} mrgi_direct_shadow_stats;

/** @brief Defaults: SOFT, MRGI_DIRECT_SHADOW_DEFAULT_SIDE, light radius 0. */
void mrgi_direct_shadow_params_default(mrgi_direct_shadow_params* params);

/** @brief Whether `params` is in range; MRGI_ERR_INVALID_ARGUMENT naming the field otherwise. */
mrgi_status mrgi_direct_shadow_params_check(const mrgi_direct_shadow_params* params, mrgi_error* err);

/** @brief The grazing weight g of a receiver whose light-facing cosine is `cosine` ("Grazing receivers"). */
double mrgi_direct_shadow_grazing_weight(double cosine);

/** @brief Whether `view` can be used (see "Errors"); 1 or 0. */
int mrgi_direct_shadow_view_usable(const mrgi_direct_shadow_view* view);

/**
 * @brief The view's depth map: S x S floats (rows bottom-up), d of each
 *        valid texel, MRGI_DIRECT_SHADOW_NO_OCCLUDER elsewhere.
 * @return MRGI_ERR_INVALID_ARGUMENT when the view is not usable or
 *         `capacity` < S x S.
 */
mrgi_status mrgi_direct_shadow_depth_map(
  const mrgi_direct_shadow_view* view, float* depth, size_t capacity, mrgi_error* err);

/**
 * @brief The view of `views[0..count)` that holds world point `p` (rule in
 *        the file comment); -1 when none. Unusable views are skipped (and
 *        counted in `stats` when it is not NULL).
 */
int mrgi_direct_shadow_select_view(const mrgi_direct_shadow_view* views, int count,
  const double p[3], mrgi_direct_shadow_stats* stats);

/**
 * @brief Factor in [0, 1] of one receiver (world position `p`, world
 *        normal `n`, any length > 0) for one light with `count` views
 *        (<= MRGI_DIRECT_SHADOW_MAX_VIEWS) and their depth maps.
 *        Invalid `params` give 1 (callers check them first).
 */
double mrgi_direct_shadow_factor(const mrgi_direct_shadow_view* views, const float* const* depths,
  int count, const mrgi_direct_shadow_params* params, const double p[3], const double n[3],
  mrgi_direct_shadow_stats* stats);

/**
 * @brief Factors of a G-buffer for one light: `width` x `height` eye-space
 *        positions and normals (RGBA, w > MRGI_GBUFFER_VALID_THRESHOLD
 *        where geometry), `view_to_world` (column-major) -> `factors`
 *        (width x height; 1 where no geometry).
 * @return MRGI_ERR_INVALID_ARGUMENT for NULL buffers, sizes < 1, count out
 *         of 0..MRGI_DIRECT_SHADOW_MAX_VIEWS or bad params;
 *         MRGI_ERR_OUT_OF_MEMORY when the depth maps cannot be allocated.
 */
mrgi_status mrgi_direct_shadow_gbuffer(int width, int height, const float* positions,
  const float* normals, const double view_to_world[16], const mrgi_direct_shadow_view* views,
  int count, const mrgi_direct_shadow_params* params, float* factors,
  mrgi_direct_shadow_stats* stats, mrgi_error* err);

/**
 * @brief One level of the multiresolution path (BMR 3-4), as
 *        vtkMRGIDirectShadows::ComputeLevels() writes it for one light:
 *        level `level` of a `width` x `height` G-buffer has
 *        ceil(width / 2^level) x ceil(height / 2^level) texels (rows
 *        bottom-up, into `occlusion`). Texel (i, j) stands for the 2^level
 *        x 2^level block of pixels it covers and is evaluated at the block's
 *        centre pixel (min(i 2^l + c, width - 1), min(j 2^l + c,
 *        height - 1)), c = 2^l / 2 (c = 0 at level 0), with that pixel's
 *        position and normal; it holds 1 - factor (the blend of the levels
 *        then writes 0 where nothing was drawn), 0 where the pixel has no
 *        geometry. The shadow-map taps are those of the full-resolution
 *        factor of that receiver (lengths in shadow-map texels and the
 *        receiver's shadow-map footprint, not in screen pixels), so level 0
 *        is 1 - mrgi_direct_shadow_gbuffer().
 * @return MRGI_ERR_INVALID_ARGUMENT for a level outside
 *         0..MRGI_DIRECT_SHADOW_MAX_LEVEL and as mrgi_direct_shadow_gbuffer().
 */
mrgi_status mrgi_direct_shadow_level(int width, int height, int level, const float* positions,
  const float* normals, const double view_to_world[16], const mrgi_direct_shadow_view* views,
  int count, const mrgi_direct_shadow_params* params, float* occlusion,
  mrgi_direct_shadow_stats* stats, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
