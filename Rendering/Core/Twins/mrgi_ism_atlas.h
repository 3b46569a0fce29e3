/**
 * @file mrgi_ism_atlas.h
 * @brief Imperfect-shadow-map atlas: one square tile per VPL, the point ->
 *        VPL assignment, the cos-sphere projection, the exact texel a point
 *        lands in, and push-pull hole filling inside each tile.
 *
 * Papers: Ritschel et al. 2008 (RGK08) section 3.3 (one ISM per VPL in one
 * texture, each VPL sees a different point subset, pull-push), Ritschel et
 * al. 2011 (RIHKS11) 6.1 (cos-sphere parameterization). Spec:
 * shared/plans/paper-specs.md, Packages 2 and 3.
 *
 * ## 1. Layout (mrgi_ism_atlas_layout_make)
 * V tiles of T x T texels (T a power of two, 4..MRGI_ISM_MAX_TILE), C tiles
 * per row (C = ceil(sqrt V)), R = ceil(V / C) rows; atlas C T x R T texels,
 * at most MRGI_ISM_MAX_ATLAS per side. Tile of VPL l at column l mod C,
 * row l / C; texel (x, y) of the tile is atlas texel (col T + x, row T + y),
 * row-major, atlas index = Y * width + X.
 *
 * ## 2. Point subsets (mrgi_ism_point_vpl)
 * Point i goes to VPL i mod V. The point records come in stratified CDF order
 * (mrgi_ism_points.h), so consecutive records cover consecutive strata;
 * i mod V hands every VPL one record of each run of V strata: each subset is
 * itself a stratified sample of the whole scene with P / V points, and the
 * subsets are disjoint (RGK08 3.3: "each VPL uses a different subset").
 *
 * ## 3. Cos-sphere projection (RIHKS11 6.1)
 * In the VPL frame (unit normal n, tangents t, b from mrgi_ism_vpl_frame),
 * a unit direction d with d.n >= 0 maps to the disk point
 *     (s, t) = (d.t, d.b),   inverse  d = s t + t b + sqrt(1 - s^2 - t^2) n.
 * Equal area in projected solid angle: with d = (sin th cos ph, sin th sin ph,
 * cos th), (s, t) = sin th (cos ph, sin ph), so the Jacobian of polar
 * coordinates gives ds dt = r dr dph = sin th cos th dth dph = cos th dw.
 * The disk area of any set of directions is its projected solid angle; the
 * whole hemisphere (projected solid angle pi) fills the unit disk (area pi).
 * Texel coordinates: X = floor((s + 1) / 2 * T), Y = floor((t + 1) / 2 * T),
 * clamped to 0..T-1. Directions with d.n < 0 and points closer than
 * MRGI_ISM_MIN_DEPTH to the VPL land nowhere.
 * Depth is the Euclidean distance |x - vpl| (scene units); empty texels hold
 * MRGI_ISM_EMPTY_DEPTH (+inf is avoided so that GPU textures can hold it).
 *
 * ## 4. Push-pull (mrgi_ism_push_pull)
 * Per tile, on tile-local mip levels T, T/2, .., T >> K, where K = min(levels,
 * log2 T) (ritschel-et-al-2008 3.3 "pull-push", limited to K levels):
 * pull - a level-k texel (1 <= k <= K) is the mean of the depths of its
 * valid children, summed in float in the order (0,0), (1,0), (0,1), (1,1)
 * and divided by their count (empty if none); push - from level K-1 down to
 * 0, every empty texel takes its parent's depth. Only the tile's own texels
 * are read, so tiles never mix. A texel stays empty only when its whole
 * 2^K x 2^K block is empty (with K = log2 T: when the tile is).
 * Why the mean over few levels: the tiles are sparse (the default 256 points
 * per 32^2 tile cover about a fifth of the texels), so the holes between the
 * points of one surface let light leak through it; one level fills them with
 * that surface's depth. Pulling the minimum, or over many levels, instead
 * spreads the nearest depth of a small occluder over a whole empty region and
 * shadows receivers that nothing occludes (Documentation/IndirectShadows.md,
 * "Session 12").
 *
 * ## 5. Rendering an atlas (mrgi_ism_atlas_render; C twin of the GPU draw)
 * Inputs: `point_count` world-space points (xyz floats) and the layout's V
 * VPL records (mrgi_vpl.h, world space). Every texel starts empty
 * (MRGI_ISM_EMPTY_DEPTH); point i goes to VPL i mod V (section 2), its texel
 * and distance come from mrgi_ism_point_texel() (section 3) and the texel
 * keeps the minimum distance (the GPU's GL_MIN blending). VPLs with a zero
 * or non-finite normal (empty VPLs, mrgi_vpl.h) and non-finite points draw
 * nothing. Then, if `push_pull_levels` is positive, mrgi_ism_push_pull()
 * over that many levels.
 * Errors: NULL arrays, point_count < 0, push_pull_levels < 0, a layout
 * whose vpl_count does not match, too little scratch.
 */
#ifndef MRGI_ISM_ATLAS_H
#define MRGI_ISM_ATLAS_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest tile side. */
#define MRGI_ISM_MAX_TILE 1024
/** Largest atlas side (GL 3.2 guarantees 1024; common GPUs 16384). */
#define MRGI_ISM_MAX_ATLAS 16384
/** Depth of an empty texel (scene units). */
#define MRGI_ISM_EMPTY_DEPTH 1e30f
/** Points nearer than this to the VPL are not drawn (scene units). */
#define MRGI_ISM_MIN_DEPTH 1e-6
/**
 * Push-pull levels of the GPU stage by default (section 4): 1, holes filled
 * from their 2x2 block. Measured against the ground truth with secondary
 * visibility (Documentation/IndirectShadows.md, "Session 12"), one level with
 * the mean pull fills the holes of the closed Cornell boxes' walls without
 * the false shadows that the old minimum pull over all levels cast in open
 * scenes and behind the corridor's statue. 0 turns push-pull off; dense
 * tiles (several points per texel) have few holes and need none.
 */
#define MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS 1
/** Most push-pull levels (any more than log2 T act as log2 T). */
#define MRGI_ISM_MAX_PUSH_PULL_LEVELS 16

/** Atlas layout (section 1). */
typedef struct mrgi_ism_atlas_layout
{
  int32_t vpl_count;     /**< V. */
  int32_t tile_size;     /**< T. */
  int32_t tiles_per_row; /**< C. */
  int32_t tile_rows;     /**< R. */
  int32_t width;         /**< C T. */
  int32_t height;        /**< R T. */
} mrgi_ism_atlas_layout;

/** @brief Layout for V VPLs and tile side T; errors name bad or absurd sizes. */
mrgi_status mrgi_ism_atlas_layout_make(
  int32_t vpl_count, int32_t tile_size, mrgi_ism_atlas_layout* layout, mrgi_error* err);

/** @brief VPL of point record i (section 2): i mod V; -1 for bad arguments. */
int32_t mrgi_ism_point_vpl(int64_t point_index, int32_t vpl_count);

/** @brief Orthonormal tangents t, b of a unit normal n (deterministic, branch-safe). */
void mrgi_ism_vpl_frame(const double n[3], double t[3], double b[3]);

/** @brief Forward cos-sphere map of a unit direction; returns 0 if d.n < 0. */
int mrgi_ism_cos_sphere_forward(const double n[3], const double d[3], double st[2]);

/** @brief Inverse map of a disk point (s^2 + t^2 <= 1) to a unit direction. */
void mrgi_ism_cos_sphere_inverse(const double n[3], const double st[2], double d[3]);

/**
 * @brief Atlas texel and depth of a point seen from VPL `vpl_index` (section 3).
 * @return 1 and *texel (atlas index), *depth when the point lands; 0 otherwise.
 */
int mrgi_ism_point_texel(const mrgi_ism_atlas_layout* layout, int32_t vpl_index,
  const double vpl_pos[3], const double vpl_normal[3], const double point[3], int64_t* texel,
  float* depth);

/**
 * @brief Push-pull every tile in place over `levels` levels (section 4).
 * @param depth    width * height depths; empty = MRGI_ISM_EMPTY_DEPTH.
 * @param levels   1..MRGI_ISM_MAX_PUSH_PULL_LEVELS (more than log2 T act as log2 T).
 * @param scratch  At least mrgi_ism_push_pull_scratch_size(layout) floats (no hidden allocation).
 */
mrgi_status mrgi_ism_push_pull(const mrgi_ism_atlas_layout* layout, float* depth, int32_t levels,
  float* scratch, size_t scratch_count, mrgi_error* err);

/** @brief Floats of scratch mrgi_ism_push_pull needs: the mip chain of one tile. */
size_t mrgi_ism_push_pull_scratch_size(const mrgi_ism_atlas_layout* layout);

struct mrgi_vpl;

/**
 * @brief Render the atlas of world-space points for the layout's VPLs (section 5).
 * @param depth    Receives width * height depths (overwritten).
 * @param push_pull_levels  0 (no push-pull) .. MRGI_ISM_MAX_PUSH_PULL_LEVELS.
 * @param scratch  mrgi_ism_push_pull_scratch_size() floats (unused, may be
 *                 NULL, when push_pull_levels is 0).
 */
mrgi_status mrgi_ism_atlas_render(const mrgi_ism_atlas_layout* layout, const float* points,
  int64_t point_count, const struct mrgi_vpl* vpls, int32_t push_pull_levels, float* depth,
  float* scratch, size_t scratch_count, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
