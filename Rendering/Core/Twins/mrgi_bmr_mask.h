/**
 * @file mrgi_bmr_mask.h
 * @brief BMR edge masks and inclusive per-level stencils: C twin of the GPU
 *        stage vtkMRGIBMRMask (vtkMRGIBMRMaskFS.glsl).
 *
 * Paper: Besenthal, Maisch and Ropinski, "Multi-Resolution Rendering for
 * Computationally Expensive Lighting Effects" (BMR), sections 3.1 and 4.1,
 * Table 1. Levels are counted from 0 here: level k is BMR's sub-image
 * i = k + 1 (k = 0 full, 1 half, 2 quarter, 3 eighth resolution).
 *
 * ## Level sizes and footprints
 *
 * For a W x H G-buffer, level k is w_k = ceil(W / 2^k) by h_k = ceil(H / 2^k)
 * texels (the sizes of mrgi_multires.h's layout). Level k texel (x, y) covers
 * the full-resolution pixels [x 2^k, min((x+1) 2^k, W)) x [y 2^k,
 * min((y+1) 2^k, H)) (its footprint). Arrays are per level, row-major,
 * index y * w_k + x, row 0 = BOTTOM (the G-buffer's order).
 *
 * ## 1. Edge value e(p) in {0, 1} (BMR 3.1)
 *
 * Pixel p = (x, y) is valid when position.w > MRGI_GBUFFER_VALID_THRESHOLD
 * and position.z and the normal are finite (as mrgi_multires.h); an
 * invalid pixel has e = 0. For a valid pixel, with linear depth
 * d = -position.z, unit normal n = N / sqrt(max(N.N, MRGI_MULTIRES_MIN_PIXEL_SIZE))
 * and pixel size s(d) = max(a |d| + b, MRGI_MULTIRES_MIN_PIXEL_SIZE) ((a, b)
 * from mrgi_multires_pixel_size_coefficients(): the same scale-free unit as
 * the multiresolution thresholds):
 *
 * - silhouette: some 4-neighbour inside the image is invalid. A silhouette
 *   pixel passes both geometric tests (depth and normal) when they are on:
 *   the geometry ends there (as mrgi_multires.h's MIXED texels).
 * - normal test (T_n finite), first derivatives by central differences with
 *   coordinates clamped to the image:
 *       m_n = max over c in {x, y, z} of max(|n_c(x+1, y) - n_c(x-1, y)|,
 *                                            |n_c(x, y+1) - n_c(x, y-1)|) / 2
 *       edge when m_n >= T_n (a spread of one unit normal component, 0..1).
 * - depth test (T_d finite), second derivatives; an axis whose two
 *   neighbours are not both inside the image contributes 0 (no one-sided
 *   "second derivative", which would be a first derivative):
 *       m_d = (|d(x+1) + d(x-1) - 2 d| + |d(y+1) + d(y-1) - 2 d|) / s(d)
 *       edge when m_d >= T_d (a depth kink in pixel widths: identical at any
 *       scene scale and for both projections).
 * - shadow test (a shadow image is given): edge when some valid 4-neighbour
 *   inside the image has a different shadow value (exact float compare;
 *   BMR's one-sample shadow test gives 0 or 1).
 * Combination of the tests that are on (BMR: "minimum or maximum"):
 * MRGI_BMR_COMBINE_MAX: e = 1 when any passes (OR); MRGI_BMR_COMBINE_MIN:
 * e = 1 when all pass (AND). With no test on, e = 0 everywhere.
 * Threshold 0 makes every valid pixel an edge (the full-resolution path).
 *
 * Ablation source (BMR 3.1, "min-max mipmaps ... as explained by Nichols
 * and Wyman"): mrgi_bmr_mask_from_flags() takes E_k(t) =
 * MRGI_MULTIRES_FLAG_DISCONTINUOUS of mrgi_multires_flags_compute() at
 * multires level k (3x3 window min-max test, mrgi_multires.h section 3);
 * levels the multires layout lacks take the max-downsample of the level
 * below. Everything after E is the same.
 *
 * ## 2. Per-level masks a_k (BMR 3.1)
 *
 * - E_0 = e; E_k(t) = max of E_{k-1} over t's children (= max of e over its
 *   footprint). NE_k(t) (non-empty) = some pixel of the footprint is valid.
 * - a_k = E_k blurred by a Gaussian of variance sigma_k^2 **in level-k
 *   texels** (BMR leaves the unit open; one level-k texel is 2^k pixels, so
 *   the blur widens with the level, as BMR's Fig. 3 suggests). Weights
 *   g(j) = expf(-(j j) / (2 sigma^2)) for |j| <= R = ceil(3 sigma), 0
 *   beyond, so "a > 0" is well defined. Separable: a horizontal pass
 *   h(x, y) = sum_j g(j) E(x+j, y) / sum_j g(j), then the same vertically on
 *   h; both sums run over the taps inside the level (renormalised at the
 *   border, so a constant mask stays constant). sigma^2 = 0: a_k = E_k.
 *   a_k is in [0, 1]; a_k > 0 exactly where an E_k = 1 texel lies within
 *   the (2R+1)^2 window (g never underflows at |j| <= 3 sigma).
 *
 * ## 3. Inclusive stencils (BMR 3.1, 4.1, Fig. 2-3)
 *
 *     R_k(t) = NE_k(t) && (a_k(t) > 0 || OR over t's children c of R_{k-1}(c))
 *     R_3(t) = NE_3(t)                           (level 3 covers every valid pixel)
 *     S_k    = skipped(k) ? 0 : R_k
 * with a_k = 0 at a skipped level (BMR: SSGI does not use its second
 * sub-image). Every level's stencil covers the finer levels' (through R, so
 * also across a skipped level): S_j(c) = 1 implies S_k(ancestor of c) = 1
 * for every k > j that is not skipped. Level 3 may not be skipped.
 *
 * ## Presets (BMR Table 1)
 *
 * MRGI_BMR_<EFFECT>_VARIANCE_<i> and _WEIGHT_<i> (i = 1..4 as in the
 * paper); mrgi_bmr_preset_params() fills a ::mrgi_bmr_params. SSGI's
 * level 2 is skipped (Table 1's "-"); its variance and weight are 0.
 *
 * ## Precision
 *
 * The C twin computes in float in the order written; the GPU agrees
 * exactly on e, E, NE and the stencils (except where a metric equals its
 * threshold to within float rounding) and to 1e-4 relative on a_k.
 */
#ifndef MRGI_BMR_MASK_H
#define MRGI_BMR_MASK_H

#include "mrgi_error.h"
#include "mrgi_gather.h"
#include "mrgi_multires.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** BMR's four sub-images: full, 1/2, 1/4, 1/8 resolution. */
#define MRGI_BMR_LEVELS 4
/** Largest accepted variance sigma^2 (level-k texels^2); its radius is MRGI_BMR_MAX_RADIUS. */
#define MRGI_BMR_MAX_VARIANCE 16.0
/** ceil(3 sqrt(MRGI_BMR_MAX_VARIANCE)): the GLSL blur loop's bound. */
#define MRGI_BMR_MAX_RADIUS 12

/** How the tests that are on combine into e (BMR 3.1: minimum or maximum). */
#define MRGI_BMR_COMBINE_MAX 0
#define MRGI_BMR_COMBINE_MIN 1

/** Effects with Table 1 presets. */
#define MRGI_BMR_EFFECT_SSAO 0
#define MRGI_BMR_EFFECT_SSM 1
#define MRGI_BMR_EFFECT_SSGI 2
#define MRGI_BMR_EFFECT_COUNT 3

/** BMR Table 1: variances (level-k texels^2) and blend weights, sub-image i = 1..4. */
#define MRGI_BMR_SSAO_VARIANCE_1 0.924
#define MRGI_BMR_SSAO_VARIANCE_2 1.848
#define MRGI_BMR_SSAO_VARIANCE_3 3.696
#define MRGI_BMR_SSAO_VARIANCE_4 0.0
#define MRGI_BMR_SSAO_WEIGHT_1 100.0
#define MRGI_BMR_SSAO_WEIGHT_2 50.0
#define MRGI_BMR_SSAO_WEIGHT_3 20.0
#define MRGI_BMR_SSAO_WEIGHT_4 1.0
#define MRGI_BMR_SSM_VARIANCE_1 0.924
#define MRGI_BMR_SSM_VARIANCE_2 1.848
#define MRGI_BMR_SSM_VARIANCE_3 3.696
#define MRGI_BMR_SSM_VARIANCE_4 0.0
#define MRGI_BMR_SSM_WEIGHT_1 1000.0
#define MRGI_BMR_SSM_WEIGHT_2 1000.0
#define MRGI_BMR_SSM_WEIGHT_3 1000.0
#define MRGI_BMR_SSM_WEIGHT_4 1.0
#define MRGI_BMR_SSGI_VARIANCE_1 0.924
#define MRGI_BMR_SSGI_VARIANCE_2 0.0
#define MRGI_BMR_SSGI_VARIANCE_3 0.924
#define MRGI_BMR_SSGI_VARIANCE_4 0.0
#define MRGI_BMR_SSGI_WEIGHT_1 1000.0
#define MRGI_BMR_SSGI_WEIGHT_2 0.0
#define MRGI_BMR_SSGI_WEIGHT_3 100.0
#define MRGI_BMR_SSGI_WEIGHT_4 1.0
/** SSGI skips BMR's second sub-image (level k = 1). */
#define MRGI_BMR_SSGI_SKIP_LEVEL 1

/** Mask and blend settings (see the file comment). */
typedef struct mrgi_bmr_params
{
  double depth_threshold;  /**< T_d, [0, +inf] (+inf: test off); depth kink in pixel widths. */
  double normal_threshold; /**< T_n, [0, +inf] (+inf: test off); unit-normal component change. */
  int32_t combine;         /**< MRGI_BMR_COMBINE_MAX (OR) or MRGI_BMR_COMBINE_MIN (AND). */
  double
    variance[MRGI_BMR_LEVELS];    /**< sigma_k^2 in level-k texels^2, [0, MRGI_BMR_MAX_VARIANCE]. */
  double weight[MRGI_BMR_LEVELS]; /**< w_k of the blend (mrgi_bmr_blend.h), finite >= 0. */
  int32_t skip[MRGI_BMR_LEVELS];  /**< 1: level k is not rendered (S_k = 0); skip[3] must be 0. */
} mrgi_bmr_params;

/**
 * @brief Table 1's preset of `effect` (MRGI_BMR_EFFECT_*), with the
 *        multiresolution defaults' thresholds
 *        (MRGI_BMR_DEFAULT_DEPTH_THRESHOLD, MRGI_BMR_DEFAULT_NORMAL_THRESHOLD)
 *        and MRGI_BMR_COMBINE_MAX.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `params` or an unknown effect (params untouched).
 */
mrgi_status mrgi_bmr_preset_params(int32_t effect, mrgi_bmr_params* params, mrgi_error* err);

/** Default depth threshold: a kink of one pixel width (section 1). */
#define MRGI_BMR_DEFAULT_DEPTH_THRESHOLD 1.0
/** Default normal threshold: a unit-normal component changing by 0.1 per pixel. */
#define MRGI_BMR_DEFAULT_NORMAL_THRESHOLD 0.1

/** @brief "ssao", "ssm", "ssgi"; NULL for an unknown effect. */
const char* mrgi_bmr_effect_name(int32_t effect);

/**
 * @brief Check thresholds (>= 0, not NaN), combine, variances, weights and skip flags.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the bad field.
 */
mrgi_status mrgi_bmr_params_validate(const mrgi_bmr_params* params, mrgi_error* err);

/** The masks of one frame (sections 2-3). Arrays per level, index y * w_k + x. */
typedef struct mrgi_bmr_masks
{
  int32_t width;                         /**< W. */
  int32_t height;                        /**< H. */
  int32_t level_width[MRGI_BMR_LEVELS];  /**< w_k = ceil(W / 2^k). */
  int32_t level_height[MRGI_BMR_LEVELS]; /**< h_k = ceil(H / 2^k). */
  uint8_t* edge[MRGI_BMR_LEVELS];        /**< E_k in {0, 1} (E_0 = e). */
  uint8_t* nonempty[MRGI_BMR_LEVELS];    /**< NE_k in {0, 1}. */
  float* mask[MRGI_BMR_LEVELS];          /**< a_k in [0, 1] (0 at a skipped level). */
  uint8_t* required[MRGI_BMR_LEVELS];    /**< R_k in {0, 1} (section 3). */
  uint8_t* stencil[MRGI_BMR_LEVELS];     /**< S_k in {0, 1}. */
} mrgi_bmr_masks;

/**
 * @brief Masks and stencils from a G-buffer (sections 1-3).
 * @param gbuffer  W x H position and normal RGBA (mrgi_gather.h), row 0 = bottom.
 * @param shadow   NULL (no shadow test) or W x H floats, one per pixel.
 * @param pixel_size_coefficients (a, b) from mrgi_multires_pixel_size_coefficients().
 * @param out      Receives new arrays (treated as uninitialized; zeroed on
 *                 failure); release with mrgi_bmr_masks_destroy().
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, bad sizes, bad
 *         params or coefficients that are negative, not finite or both 0;
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_bmr_mask_build(const mrgi_gather_receivers* gbuffer, const float* shadow,
  const float pixel_size_coefficients[2], const mrgi_bmr_params* params, mrgi_bmr_masks* out,
  mrgi_error* err);

/**
 * @brief The ablation: masks whose E_k are the NW09 min-max flags
 *        (DISCONTINUOUS of mrgi_multires_flags_compute() on `layout`), with
 *        NE_k from the flags' NONEMPTY (section 1, "Ablation source").
 *        The params' thresholds are not used (the flags carry their own).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, a short `flags`,
 *         a bad layout or bad params; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_bmr_mask_from_flags(const mrgi_multires_layout* layout, const uint8_t* flags,
  size_t flags_size, const mrgi_bmr_params* params, mrgi_bmr_masks* out, mrgi_error* err);

/** @brief Free the arrays and zero the struct. NULL-safe and idempotent. */
void mrgi_bmr_masks_destroy(mrgi_bmr_masks* masks);

/** Texels and valid pixels per level, for reports. */
typedef struct mrgi_bmr_stats
{
  int64_t stencilled[MRGI_BMR_LEVELS]; /**< Texels with S_k = 1. */
  int64_t texels[MRGI_BMR_LEVELS];     /**< w_k h_k. */
  /** Valid full-resolution pixels whose finest stencilled level is k (sums to valid_pixels). */
  int64_t finest_pixels[MRGI_BMR_LEVELS];
  int64_t valid_pixels; /**< NE_0 count. */
  /** sum_k stencilled[k] / valid_pixels: 1 = the cost of one full-resolution pass (0 without valid
   * pixels). */
  double work_fraction;
} mrgi_bmr_stats;

/** @brief Count the stencils of `masks`. ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers or empty
 * masks. */
mrgi_status mrgi_bmr_stats_compute(
  const mrgi_bmr_masks* masks, mrgi_bmr_stats* stats, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
