/**
 * @file mrgi_multires.h
 * @brief The multiresolution buffer: its flattened layout, the min-max
 *        mipmaps of the G-buffer, the discontinuity and refinement flags
 *        (with the level-balance rule), the selection of the texels that
 *        gather light (the "stencil"), and selection statistics.
 *
 * C twin of the GPU stages "min-max mipmaps" and "stencil refinement".
 * Papers: Nichols and Wyman 2009, "Multiresolution Splatting for Indirect
 * Illumination" (NW09), sections 3.2-3.3; Nichols, Shopf and Wyman 2009,
 * "Hierarchical Image-Space Radiosity" (NSW09), section 3.2.1; Nichols,
 * Penmatsa and Wyman 2010, "Interactive, Multiresolution Image-Space
 * Rendering for Dynamic Area Lighting" (NPW10), section 3.2. Every rule
 * below is the GPU contract: the GLSL computes the same function, with the
 * constants injected by mrgi_glsl_defines().
 *
 * ## 1. Flattened layout
 *
 * For a W x H image: level 0 is W x H; level i is
 * w_i = ceil(W / 2^i) by h_i = ceil(H / 2^i) (ceil keeps the edge pixels of
 * non-power-of-two sizes; note w_{i+1} = ceil(w_i / 2)). Level count L + 1:
 * L is the smallest i with w_i <= coarsest_side and h_i <= coarsest_side
 * (a W x H <= coarsest_side image has one level). All levels lie side by
 * side in one texture, bottom-aligned: level i at x offset
 * o_i = w_0 + ... + w_{i-1}, y offset 0. The flattened texture is
 * total_width = o_L + w_L by total_height = H. Flattened texel (X, Y) is
 * texel (X - o_i, Y) of level i when o_i <= X < o_i + w_i and Y < h_i;
 * every other texel (above a level's rows) belongs to no level. Arrays in
 * this layout are row-major, index Y * total_width + X, row 0 = BOTTOM (the
 * G-buffer's order). "Level i texel (x, y)" covers the full-resolution
 * pixels [x 2^i, min((x+1) 2^i, W)) x [y 2^i, min((y+1) 2^i, H)) (its
 * footprint); its parent is level i+1 texel (x/2, y/2) (integer division);
 * its children are the level i-1 texels (2x+a, 2y+b), a, b in {0, 1}, that
 * exist (one, two or four). Level L is "coarsest"; ::mrgi_multires_params::
 * finest_level is the finest level that may gather (0 = full resolution).
 *
 * Clamping: every neighbourhood read below clamps coordinates to the
 * level's own rectangle, x to [0, w_i - 1] and y to [0, h_i - 1] (on the
 * GPU: to [o_i, o_i + w_i - 1] in the flattened texture, never into the
 * next level). Clamping only repeats texels of the neighbourhood, which
 * min, max and OR ignore.
 *
 * ## 2. Min-max mipmaps (NW09 3.2, NPW10 3.2)
 *
 * Three RGBA32F textures in the flattened layout (arrays of 4 floats per
 * texel in ::mrgi_multires_mipmap), the "exact footprint" pyramid P:
 * - MRGI_MULTIRES_TEX_DEPTH:      (dmin, dmax, gmax, validity bits)
 * - MRGI_MULTIRES_TEX_NORMAL_MIN: (min nx, min ny, min nz, 0)
 * - MRGI_MULTIRES_TEX_NORMAL_MAX: (max nx, max ny, max nz, 0)
 *
 * Level 0, pixel p with G-buffer position P and normal N:
 * - valid(p) = P.w > MRGI_GBUFFER_VALID_THRESHOLD and P.z, N.x, N.y, N.z
 *   are finite (GLSL: !isnan && !isinf);
 * - linear depth d_p = -P.z (eye space looks down -z; also used as is for
 *   parallel projection, where it may be <= 0);
 * - unit normal n_p = N * inversesqrt(max(dot(N, N), MRGI_MULTIRES_MIN_PIXEL_SIZE))
 *   (a zero normal stays zero);
 * - pixel size at depth d: s(d) = max(a |d| + b, MRGI_MULTIRES_MIN_PIXEL_SIZE),
 *   the world-space side of one full-resolution pixel at depth d, with
 *   (a, b) = (2 tan(view_angle / 2) / H, 0) for perspective and
 *   (0, 2 parallel_scale / H) for parallel projection (VTK's camera
 *   ViewAngle in degrees and ParallelScale): mrgi_multires_pixel_size_coefficients();
 * - depth derivative (NPW10 3.2, made dimensionless):
 *     g_p = max over the depth-valid 8-neighbours q of p (clamped at the
 *           image edge) of min(|d_q - d_p| / s(min(|d_p|, |d_q|)), FLT_MAX),
 *   0 when p has no such neighbour. A neighbour is depth-valid when its
 *   flag is set and its depth finite (its normal does not matter: one
 *   G-buffer read per neighbour on the GPU). g is "depth change per pixel width":
 *   tan(tilt) on a plane tilted away from the viewer, step / pixel width at
 *   a depth step, identical at any scene scale and for both projections;
 * - valid pixel:   (d_p, d_p, g_p, MRGI_MULTIRES_VALID_BIT), normals (n_p, 0), (n_p, 0);
 *   invalid pixel: (MRGI_MULTIRES_FLT_MAX, -MRGI_MULTIRES_FLT_MAX, 0,
 *   MRGI_MULTIRES_INVALID_BIT), normal min (FLT_MAX x3, 0), max (-FLT_MAX x3, 0)
 *   (the neutral elements of min and max).
 * Level i >= 1, texel t: the reduction of its children (2x2, clamped):
 * min of dmin and normal mins, max of dmax, gmax and normal maxes, bitwise
 * OR of the validity bits (stored as a float 0..3). So P_i(t) holds exactly
 * the min and max over t's footprint. A texel is EMPTY when its
 * MRGI_MULTIRES_VALID_BIT is clear (no valid pixel: never selected, never
 * gathered) and MIXED when both bits are set (geometry against background).
 *
 * ## 3. Discontinuity test: the 3x3 window
 *
 * The authors test 3x3 neighbourhoods "to catch discontinuities on block
 * borders". Here every metric of level i texel t is read over the WINDOW of
 * t = the 3x3 level-i texels centred on t (clamped), i.e. t's footprint plus
 * a ring one level-i texel wide: G = max gmax, NMIN = min normal mins,
 * NMAX = max normal maxes over the window. Validity is t's own (EMPTY,
 * MIXED). With T_d, T_n the depth and normal thresholds (see below):
 *
 *     D_i(t) = !EMPTY(t) && ( (T_d on && (MIXED(t) || G >= T_d))
 *                          || (T_n on && max_c(NMAX_c - NMIN_c) >= T_n) )
 *
 * - T_d is dimensionless (units of g): refine where a surface tilts more
 *   than atan(T_d) from facing the viewer or steps by more than T_d pixel
 *   widths; a MIXED texel counts as an infinite depth step (geometry edge
 *   against background). T_n is the largest accepted spread of one unit
 *   normal component, 0..2. Both mean the same at any scene scale and
 *   either projection, and at every level (no level-dependent factor).
 * - Threshold 0 selects every valid texel at the finest level (D everywhere:
 *   the full-resolution gather); +infinity turns the test off (with both off,
 *   the coarsest level everywhere). GLSL has no portable infinity: a
 *   threshold reaches the shader as mrgi_multires_threshold_uniform(), which
 *   maps +inf to MRGI_MULTIRES_THRESHOLD_OFF (< 0); the shader tests
 *   `T >= 0.0 && metric >= T`.
 * - Windows nest (the window of a child lies inside its parent's window) and
 *   the metrics are min/max over the window, so D is monotone: D_i(child)
 *   implies D_{i+1}(parent). The flags below OR the children in anyway.
 *
 * ## 4. Refinement flag and balance (the rule the authors left out)
 *
 * Computed fine to coarse, one pass per level (like a mipmap), for the
 * levels i = f .. L (f = finest_level; 0 below f):
 *
 *     R_f(t) = D_f(t)
 *     R_i(t) = !EMPTY(t) && ( D_i(t) || OR over children c of R_{i-1}(c)
 *              || (balance && OR over the ring of R_{i-1}) )       for i > f
 *
 * where the ring is the level i-1 texels (2x-1..2x+2, 2y-1..2y+2) that are
 * not children of t, i.e. the level i-1 texels 8-adjacent to t's footprint
 * (on the GPU: OR of R_{i-1} over that 4x4 block, clamped). R is monotone
 * (R_{i-1}(c) implies R_i(parent)) and EMPTY texels have R = 0.
 * Balance: if a level i-1 texel touching t is refined, t is refined too.
 * Then two selected texels whose footprints touch (8-adjacency of the
 * full-resolution pixels they cover) differ by at most one level. Proof:
 * let leaf t (level i) touch leaf u (level k <= i-2); u's ancestor c at
 * level i-1 is refined (all ancestors of a leaf are), is disjoint from t and
 * touches it, so it lies in t's ring and R_i(t) holds: t is no leaf.
 *
 * ## 5. Selection (the stencil), two equal definitions
 *
 * One byte per flattened texel, 1 = selected (stencil set), 0 elsewhere
 * (also outside the levels). With R as above:
 * - iterative (NW09 3.3): start from every non-empty level L texel; a patch
 *   at level i > f with R_i is replaced by its non-empty children; every
 *   other patch is selected.
 * - one pass (NSW09 3.2.1), per texel t at level i:
 *       selected = i >= f && !EMPTY(t) && (i == f || !R_i(t))
 *                  && (i == L || R_{i+1}(parent(t)))
 * Because R is monotone these select the same texels; every valid
 * full-resolution pixel lies in exactly one selected footprint. With
 * balance = 0, R is D with the children ORed in (the authors' rule).
 *
 * ## 6. Flags texture
 *
 * One byte per flattened texel (GPU: R8UI), bits MRGI_MULTIRES_FLAG_NONEMPTY,
 * _MIXED, _DISCONTINUOUS (D), _REFINE (R). The upsampling reads them.
 *
 * ## Precision
 *
 * The C twin computes in float in the order written above, as the GLSL
 * does; the masks agree exactly except where a metric equals its threshold
 * to within float rounding (the GPU's division is not correctly rounded).
 */
#ifndef MRGI_MULTIRES_H
#define MRGI_MULTIRES_H

#include "mrgi_error.h"
#include "mrgi_gather.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Most levels a layout has (2^20 pixels reach 1 x 1 at level 20, so never limiting). */
#define MRGI_MULTIRES_MAX_LEVELS 24
/** Default coarsest size: stop when both sides are <= 16 texels (NW09 use 16x16). */
#define MRGI_MULTIRES_DEFAULT_COARSEST_SIDE 16

/** Textures of the min-max mipmap (also the order of MRT outputs). */
#define MRGI_MULTIRES_TEX_DEPTH 0
#define MRGI_MULTIRES_TEX_NORMAL_MIN 1
#define MRGI_MULTIRES_TEX_NORMAL_MAX 2
#define MRGI_MULTIRES_TEX_COUNT 3

/** Validity bits in the depth texture's w (a float holding 0..3). */
#define MRGI_MULTIRES_VALID_BIT 1
#define MRGI_MULTIRES_INVALID_BIT 2

/** Bits of the flags texture. */
#define MRGI_MULTIRES_FLAG_NONEMPTY 1
#define MRGI_MULTIRES_FLAG_MIXED 2
#define MRGI_MULTIRES_FLAG_DISCONTINUOUS 4
#define MRGI_MULTIRES_FLAG_REFINE 8

/** Neutral element of min (and minus it of max): FLT_MAX. */
#define MRGI_MULTIRES_FLT_MAX 3.40282346638528859812e+38F
/** Floor of the pixel size s(d) and of dot(N, N): FLT_MIN. */
#define MRGI_MULTIRES_MIN_PIXEL_SIZE 1.17549435082228750797e-38F
/** A threshold as passed to GLSL when it is +infinity (test off). */
#define MRGI_MULTIRES_THRESHOLD_OFF (-1.0f)

/** Default thresholds (see section 3 of the file comment). */
#define MRGI_MULTIRES_DEFAULT_DEPTH_THRESHOLD 4.0
#define MRGI_MULTIRES_DEFAULT_NORMAL_THRESHOLD 0.25

/** The flattened layout (section 1). Plain data, filled by mrgi_multires_layout_init(). */
typedef struct mrgi_multires_layout
{
  int32_t width;         /**< W, level 0 width, 1..MRGI_IMAGE_MAX_DIMENSION. */
  int32_t height;        /**< H, level 0 height. */
  int32_t coarsest_side; /**< As given to mrgi_multires_layout_init(). */
  int32_t level_count;   /**< L + 1, 1..MRGI_MULTIRES_MAX_LEVELS. */
  int32_t level_width[MRGI_MULTIRES_MAX_LEVELS];  /**< w_i = ceil(W / 2^i); 0 past level_count. */
  int32_t level_height[MRGI_MULTIRES_MAX_LEVELS]; /**< h_i = ceil(H / 2^i); 0 past level_count. */
  int32_t level_offset[MRGI_MULTIRES_MAX_LEVELS]; /**< o_i = sum of w_k, k < i; 0 past level_count. */
  int32_t total_width;   /**< o_L + w_L. */
  int32_t total_height;  /**< H. */
} mrgi_multires_layout;

/**
 * @brief Compute the layout of a W x H multiresolution buffer (section 1).
 * @param layout        Receives the layout; zeroed on failure.
 * @param width         W, 1..MRGI_IMAGE_MAX_DIMENSION.
 * @param height        H, 1..MRGI_IMAGE_MAX_DIMENSION.
 * @param coarsest_side Stop at the first level whose sides are both <= this;
 *                      >= 1 (MRGI_MULTIRES_DEFAULT_COARSEST_SIDE is usual).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `layout` or a value out of range.
 */
mrgi_status mrgi_multires_layout_init(mrgi_multires_layout* layout, int32_t width,
                                      int32_t height, int32_t coarsest_side, mrgi_error* err);

/**
 * @brief Check that `layout` is what mrgi_multires_layout_init() makes for its
 *        own width, height and coarsest side (a cheap consistency check every
 *        function taking a layout runs).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or a modified layout.
 */
mrgi_status mrgi_multires_layout_check(const mrgi_multires_layout* layout, mrgi_error* err);

/** @brief total_width * total_height: texels (bytes of a mask, RGBA texels of a texture). */
int64_t mrgi_multires_texel_count(const mrgi_multires_layout* layout);

/**
 * @brief Check an array in the flattened layout: not NULL and at least
 *        `per_texel` values per texel (`count` values given).
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming `what` ("%s is NULL", "%s holds
 *         N values but the W x H flattened layout needs M").
 */
mrgi_status mrgi_multires_check_array(const mrgi_multires_layout* layout, const void* array,
                                      size_t count, size_t per_texel, const char* what,
                                      mrgi_error* err);

/**
 * @brief Flattened index of level `level` texel (x, y). No checks (hot loops):
 *        0 <= level < level_count, 0 <= x < w_level, 0 <= y < h_level.
 */
static inline size_t mrgi_multires_index(const mrgi_multires_layout* layout, int32_t level,
                                         int32_t x, int32_t y)
{
  return (size_t)y * (size_t)layout->total_width + (size_t)layout->level_offset[level] +
         (size_t)x;
}

/**
 * @brief Flattened index of level `level` texel (x + dx, y + dy), clamped to
 *        the level (the 3x3 neighbourhoods of the stencils: edges repeat).
 *        No other checks: 0 <= level < level_count, (x, y) in the level.
 */
static inline size_t mrgi_multires_clamped_index(const mrgi_multires_layout* layout,
                                                 int32_t level, int32_t x, int32_t y, int32_t dx,
                                                 int32_t dy)
{
  const int32_t w = layout->level_width[level], h = layout->level_height[level];
  const int32_t nx = x + dx < 0 ? 0 : (x + dx >= w ? w - 1 : x + dx);
  const int32_t ny = y + dy < 0 ? 0 : (y + dy >= h ? h - 1 : y + dy);
  return mrgi_multires_index(layout, level, nx, ny);
}

/**
 * @brief Which level texel a flattened texel is.
 * @param level,x,y Receive the level and the texel's coordinates in it; each may be NULL.
 * @return 1 when (flat_x, flat_y) belongs to a level, 0 otherwise (outside
 *         the texture or above a level's rows); outputs untouched then.
 */
int mrgi_multires_locate(const mrgi_multires_layout* layout, int32_t flat_x, int32_t flat_y,
                         int32_t* level, int32_t* x, int32_t* y);

/** Projection of the camera that rendered the G-buffer (VTK's vtkCamera terms). */
typedef struct mrgi_multires_projection
{
  int32_t parallel;      /**< 0: perspective, 1: parallel (orthographic). */
  double view_angle_deg; /**< Perspective: vertical full field of view, (0, 180) degrees. */
  double parallel_scale; /**< Parallel: half the view height in world units, finite > 0. */
} mrgi_multires_projection;

/**
 * @brief (a, b) of the pixel size s(d) = max(a |d| + b, MRGI_MULTIRES_MIN_PIXEL_SIZE)
 *        for a G-buffer `height` pixels tall (section 2); the GPU's uniform.
 * @param coefficients Receives (a, b) as floats, both finite and >= 0, not both 0.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, height < 1, an angle
 *         outside (0, 180) or a parallel scale that is not finite and > 0.
 */
mrgi_status mrgi_multires_pixel_size_coefficients(const mrgi_multires_projection* projection,
                                                  int32_t height, float coefficients[2],
                                                  mrgi_error* err);

/** Min-max mipmap (section 2): three RGBA32F textures in the flattened layout. */
typedef struct mrgi_multires_mipmap
{
  mrgi_multires_layout layout; /**< The layout the arrays follow. */
  float* texture[MRGI_MULTIRES_TEX_COUNT]; /**< 4 floats per flattened texel each; texels outside the levels hold 0. */
} mrgi_multires_mipmap;

/**
 * @brief Build the min-max mipmap of a G-buffer (section 2).
 * @param layout   Layout for the G-buffer's size (width and height must match).
 * @param gbuffer  W x H position and normal RGBA arrays, row 0 = bottom
 *                 (mrgi_gather.h); position.w is the valid flag.
 * @param pixel_size_coefficients (a, b) from mrgi_multires_pixel_size_coefficients().
 * @param out      Receives new arrays (treated as uninitialized; zeroed on failure);
 *                 release with mrgi_multires_mipmap_destroy().
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a size mismatch or
 *         coefficients that are negative, non-finite or both 0;
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_multires_mipmap_build(const mrgi_multires_layout* layout,
                                       const mrgi_gather_receivers* gbuffer,
                                       const float pixel_size_coefficients[2],
                                       mrgi_multires_mipmap* out, mrgi_error* err);

/** @brief Free the arrays and zero the struct. NULL-safe and idempotent. */
void mrgi_multires_mipmap_destroy(mrgi_multires_mipmap* mipmap);

/** Refinement knobs (sections 3-5). */
typedef struct mrgi_multires_params
{
  double depth_threshold;  /**< T_d, [0, +inf] (+inf: off); dimensionless, see section 3. */
  double normal_threshold; /**< T_n, [0, +inf] (+inf: off); spread of a unit normal component. */
  int32_t finest_level;    /**< f, 0..level_count-1: finest level that gathers (0 = full resolution). */
  int32_t balance;         /**< 1: neighbouring selected texels differ by <= 1 level (default); 0: the authors' rule. */
} mrgi_multires_params;

/** @brief Defaults: the MRGI_MULTIRES_DEFAULT_* thresholds, finest level 0, balance on. NULL-safe. */
void mrgi_multires_params_default(mrgi_multires_params* params);

/**
 * Presets: points on the measured speed/accuracy frontier
 * (Testing/Benchmarks/multires_sweep.py, Documentation/Multiresolution.md),
 * not guesses. Balanced is what MRGI uses whenever indirect light is on and
 * nothing else is asked for.
 */
typedef enum mrgi_multires_preset
{
  MRGI_MULTIRES_PRESET_FAST = 0,
  MRGI_MULTIRES_PRESET_BALANCED = 1,
  MRGI_MULTIRES_PRESET_ACCURATE = 2
} mrgi_multires_preset;

#define MRGI_MULTIRES_PRESET_COUNT 3

/**
 * @brief The settings of a preset (thresholds, finest level; balance on).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `params` or an unknown preset
 *         (params untouched).
 */
mrgi_status mrgi_multires_preset_params(int32_t preset, mrgi_multires_params* params, mrgi_error* err);

/**
 * @brief A preset's illumination threshold T: a texel below the geometric
 *        cut is also gathered where its parent's 3x3 gathered irradiance
 *        differs by more than T, relative (the illumination rule of
 *        mrgi_incremental_stencil.h, nichols-penmatsa-wyman-2010 3.4 applied
 *        to the indirect light). +inf: the preset refines by geometry alone.
 *        The rule lets a preset relax the depth-derivative test, which
 *        refines every grazing surface whether its light changes or not.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `threshold` or an unknown
 *         preset (threshold untouched).
 */
mrgi_status mrgi_multires_preset_illumination_threshold(
  int32_t preset, double* threshold, mrgi_error* err);

/**
 * Smallest view (pixels) where the presets' illumination rule runs: from
 * 384^2 up it measured at least as fast as the geometric setting and more
 * accurate (cornell-spot, 256 VPLs: 384^2, 512^2, 1024^2); at 256^2 it was
 * slower and less accurate (Documentation/IlluminationRefinement.md). A
 * smaller view selects with the preset's area-light (geometric) settings.
 */
#define MRGI_MULTIRES_ILLUMINATION_MIN_PIXELS (384 * 384)

/**
 * @brief The settings of a preset for the area lights' gather: the finest
 *        level and balance of mrgi_multires_preset_params(), with the
 *        thresholds the area lights measured best. Their light is direct
 *        and shadowed, and shadows change at depth discontinuities, where
 *        the depth-derivative test refines; the indirect light, smooth
 *        across such edges, relaxes that test where the illumination rule
 *        runs (Documentation/IlluminationRefinement.md).
 * @return ::MRGI_ERR_INVALID_ARGUMENT as mrgi_multires_preset_params().
 */
mrgi_status mrgi_multires_preset_area_light_params(int32_t preset, mrgi_multires_params* params,
                                                   mrgi_error* err);

/** @brief "fast", "balanced", "accurate"; NULL for an unknown preset. */
const char* mrgi_multires_preset_name(int32_t preset);

/**
 * @brief The threshold as the shader receives it: the value as a float, or
 *        MRGI_MULTIRES_THRESHOLD_OFF for +infinity. The caller validates first
 *        (mrgi_multires_params_validate); other input maps to OFF too.
 */
float mrgi_multires_threshold_uniform(double threshold);

/**
 * @brief Check thresholds (>= 0, not NaN; +inf allowed), finest level
 *        (0..level_count-1 of `layout`) and balance (0 or 1).
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the bad field.
 */
mrgi_status mrgi_multires_params_validate(const mrgi_multires_params* params,
                                          const mrgi_multires_layout* layout, mrgi_error* err);

/**
 * @brief Discontinuity and refinement flags (sections 3, 4, 6), one byte
 *        per flattened texel: NONEMPTY, MIXED and DISCONTINUOUS at every
 *        level; REFINE at levels >= finest_level. Texels outside the levels get 0.
 * @param flags      Destination of mrgi_multires_texel_count() bytes.
 * @param flags_size Size of `flags` in bytes.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a short buffer, bad
 *         params or a mipmap without arrays.
 */
mrgi_status mrgi_multires_flags_compute(const mrgi_multires_mipmap* mipmap,
                                        const mrgi_multires_params* params, uint8_t* flags,
                                        size_t flags_size, mrgi_error* err);

/**
 * @brief Selection mask by the one-pass rule (section 5, NSW09 3.2.1).
 * @param flags     Flags from mrgi_multires_flags_compute() with the same finest_level.
 * @param mask      Destination of mrgi_multires_texel_count() bytes: 1 selected, 0 not.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, short buffers or a
 *         finest level out of range.
 */
mrgi_status mrgi_multires_select_one_pass(const mrgi_multires_layout* layout,
                                          const uint8_t* flags, size_t flags_size,
                                          int32_t finest_level, uint8_t* mask, size_t mask_size,
                                          mrgi_error* err);

/**
 * @brief Selection mask by iterative subdivision of a patch list (section 5,
 *        NW09 3.3); the same texels as mrgi_multires_select_one_pass().
 *        Arguments as there; allocates its patch lists once (::MRGI_ERR_OUT_OF_MEMORY).
 */
mrgi_status mrgi_multires_select_iterative(const mrgi_multires_layout* layout,
                                           const uint8_t* flags, size_t flags_size,
                                           int32_t finest_level, uint8_t* mask, size_t mask_size,
                                           mrgi_error* err);

/** What a selection costs. */
typedef struct mrgi_multires_stats
{
  int64_t selected[MRGI_MULTIRES_MAX_LEVELS]; /**< Selected texels per level. */
  int64_t selected_total;                     /**< Sum over the levels: gathers per VPL. */
  int64_t valid_pixels;                       /**< Valid full-resolution pixels (non-empty level 0 texels). */
  double work_fraction; /**< selected_total / valid_pixels: 1 = the full-resolution gather; 0 without valid pixels. */
} mrgi_multires_stats;

/**
 * @brief Count a selection (mask) per level; valid pixels from the flags' NONEMPTY at level 0.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers or short buffers.
 */
mrgi_status mrgi_multires_stats_compute(const mrgi_multires_layout* layout, const uint8_t* flags,
                                        size_t flags_size, const uint8_t* mask, size_t mask_size,
                                        mrgi_multires_stats* stats, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
