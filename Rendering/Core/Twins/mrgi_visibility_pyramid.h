/**
 * @file mrgi_visibility_pyramid.h
 * @brief Visibility of N light samples at a texel as a bit mask, computed
 *        naively or incrementally coarse to fine, 2x2 interleaved sampling,
 *        and the bit-count refinement metric: the C twin of
 *        vtkMRGIVisibilityPyramid.
 *
 * Paper: Nichols, Penmatsa and Wyman 2010 (NPW10), sections 3.3.2 (incremental
 * voxel-space visibility, bit-counting metric, interleaved sampling [KH01]),
 * and
 * 3.4 (incremental stencil rendering, coarse to fine). One ray is
 * mrgi_voxel_march() (mrgi_voxel_march.h); the multiresolution layout and
 * receivers are mrgi_multires.h and mrgi_multires_receivers.h.
 *
 * ## 1. Sample masks
 *
 * N = 1..MRGI_VOXEL_MAX_SAMPLES light samples (eye-space positions, optional
 * normals). A texel's visibility is N bits in W = ceil(N / 32) uint32 words
 * (mrgi_voxel_mask_words()): sample j is bit j & 31 of word j >> 5, 1 =
 * visible. Bits >= N of the last word are always 0. On the GPU a mask is a
 * set of RGBA32UI targets, word w in target w / 4, channel w % 4; OpenGL 3.2
 * guarantees 8 draw buffers, i.e. 1024 bits per pass: N <= 1024 per pixel,
 * and N <= 4096 with 2x2 interleaving (each pixel stores N / 4 bits).
 *
 * ## 2. Naive and incremental visibility at one texel
 *
 * mrgi_voxel_visibility() computes the bits of the samples whose PHASE
 * (j & 3, section 4) is in `phase_set` (MRGI_VOXEL_ALL_PHASES: all) and
 * writes 0 for the others. With coarse neighbour masks C_1..C_m (m >= 1, the
 * coarser level's 3x3 texels around the parent, section 3) it uses, per
 * word, AND = C_1 & ... & C_m and OR = C_1 | ... | C_m:
 *
 *     agree  = wanted & ~(AND ^ OR)      (all neighbours say the same)
 *     mask   = AND & agree               (reused: NPW10 3.3.2 "we reuse a
 *                                          VPL's visibility when coarse samples
 *                                          in a 3x3 region agree")
 *     then every wanted bit not in `agree` is re-marched (bit j set when
 *     mrgi_voxel_march() says visible).
 *
 * Without coarse masks (m = 0) every wanted bit is marched: the naive query
 * (NPW10 3.3.1, Figure 4 left). GLSL 1.50 has neither findLSB nor bitCount
 * (GLSL 4.00): the shader walks the 32 bits of a word with a shift test and
 * counts bits with the SWAR sequence of mrgi_voxel_popcount().
 *
 * ## 3. Coarse to fine over the multiresolution levels (NPW10 3.4)
 *
 * mrgi_voxel_visibility_pyramid(), on the flattened layout of mrgi_multires.h
 * with one receiver per texel (mrgi_multires_receivers_build(); a texel is a
 * receiver when its position w > MRGI_GBUFFER_VALID_THRESHOLD and xyz is
 * finite; a non-finite or zero normal counts as none). From the coarsest
 * level L down to level 0, every receiver texel t at level i gets a mask:
 *
 * - COMPUTED when i == L (naive), or when `refine` (optional caller mask,
 *   e.g. the multires selection or DISCONTINUOUS flags) is set at t, or when
 *   the parent is not on t's surface (the same-surface guard below), or when
 *   the refinement metric fires (section 5) over the parent's 3x3
 *   level-(i+1) neighbourhood (clamped to the level, non-receivers skipped);
 *   the mask then follows section 2 with that same 3x3 as coarse neighbours,
 *   except that without any neighbour on t's surface every wanted bit is
 *   marched (naive at t).
 * - INHERITED otherwise: the parent's mask, unchanged (upsampled, NPW10 3.4
 *   step 3: "when the stencil is not set, upsample and interpolate").
 *
 * Same-surface guard (a decision made here; NPW10's rule has none). Texel
 * t (receiver P, N) classifies each receiver neighbour c (Q, M) of its 3x3
 * as KEPT when mrgi_voxel_same_surface(P, N, Q, M) (section 4's test), else
 * EXCLUDED. t inherits only when its parent is kept (and the metric does
 * not fire); t reuses agreeing bits only when at least one neighbour is
 * kept. Excluded neighbours still take part in the metric and in AND/OR:
 * they can veto reuse (a bit on which any receiver neighbour disagrees is
 * re-marched) but never vouch for it alone. Why: a coarse receiver is the
 * mean position / normal of its pixels; one that averages pixels across a
 * depth or normal discontinuity (the front edge of the living room's TV
 * stand under the screen) lies inside geometry and sees nothing, so its 3x3
 * agreed "hidden" and fine texels on the lit top inherited or reused that
 * (living room, 256^2, relative RMS against the ground truth: NPW10's rule
 * 0.33, naive 0.11). The guard stops that; keeping the excluded neighbours
 * in the veto matters as much: those mixed receivers sit exactly where
 * contact shadows are, and their disagreement is what re-marches the fine
 * texels there. Excluding them from the metric and AND/OR as well was
 * measured and rejected: living room 0.18, and on TestMRGIAreaLightPass's
 * Cornell box (spot) the incremental result moved from 0.076 to 0.14
 * relative RMS against naive at a third of the rays. With the guard as
 * written: living room 0.18 with interleaving (the default; 0.126 with
 * interleaving alone, no reuse) and 0.111 without it; the Cornell box 0.073
 * against naive at 15% of the naive rays (0.076 at 14% before); TestVoxel's
 * random boxes (64^2, no interleaving, threshold 0) 0.21% of the level-0
 * bits differ from naive (1.35% before) at 34% of the naive rays (19.5%).
 * A texel without a normal keeps no neighbour: naive.
 *
 * Surround rule (a decision made here; NPW10's rule has none). The kept
 * receivers SURROUND t when, on screen (mrgi_voxel_screen_side()), along x
 * and along y some kept receiver lies at or before P and some at or after
 * it. At levels i >= MRGI_VOXEL_SURROUND_MIN_LEVEL, a texel that is not
 * surrounded does not inherit (it is COMPUTED), and reuses only the bits
 * its coarse neighbours agree are VISIBLE: the agreed hidden bits are
 * marched again. Why: beyond the last coarse receiver of a surface
 * (towards its edge on screen) the coarse masks extrapolate instead of
 * interpolating. On `cornell-area` the strip of floor between the short
 * block's base and the floor's front edge (background below) got no light:
 * its level-4 receiver, the mean of 160 floor pixels, lies at the block's
 * base in full shadow, its 3x3 agreed, and every finer level inherited or
 * reused those zeros, while the truth brightens towards the camera.
 * Finer levels keep the plain rule: there the coarse neighbours lie a
 * pixel or two away, and marching again only added the voxels' aliasing.
 * Only the hidden bits are distrusted: re-marching every agreed bit of
 * such texels fixed the strip as well, for more rays and a higher error
 * (both variants measured in Documentation/Status.md, session 18).
 *
 * Non-receiver texels and texels outside the levels get all-zero masks.
 * Threshold 0 computes every texel ("incremental everywhere"). With the
 * DISAGREE metric and threshold 1 the result is identical to threshold 0:
 * a texel is inherited only when no bit disagrees in the parent's 3x3 and
 * the parent is kept, and then the incremental rule reuses every bit from
 * that same neighbourhood.
 * Only thresholds > 1 trade accuracy for rays.
 *
 * Exactness: at a computed texel, every bit on which its coarse neighbours
 * disagree equals the naive bit (it is re-marched), and so does every bit
 * when no neighbour is on t's surface, and every agreed hidden bit where
 * the surround rule applies. Bits on which they agree are reused
 * (only with a kept neighbour among them) and differ from the naive bit
 * only where the visibility of that sample changes between coarse samples
 * without any of the 9 seeing it (an occluder smaller than the coarse
 * spacing): the approximation NPW10 accept ("our incremental approach can
 * converge to a correct solution, this is rarely necessary"). Inherited
 * masks come from a parent on t's surface only (the guard above), and
 * from level MRGI_VOXEL_SURROUND_MIN_LEVEL up only between kept receivers.
 *
 * ## 4. 2x2 interleaved sampling (NPW10 3.3.2, [KH01])
 *
 * With `interleave` on, level-i texel (x, y) has phase
 * q = (x & 1) | ((y & 1) << 1) (mrgi_voxel_interleave_phase()) and marches
 * only the samples j with (j & 3) == q: each pixel of a 2x2 block takes
 * every fourth sample by index, so with the light's samples in raster order
 * (a grid) every quarter spreads over the whole light, not one corner of it.
 * Combination, per COMPUTED texel t: for each phase q, the bits of phase q
 * come from the texel u of the same aligned 2x2 block ((x & ~1) | (q & 1),
 * (y & ~1) | (q >> 1)) when u exists, is a receiver, was COMPUTED at this
 * level and lies on the same surface as t (mrgi_voxel_same_surface():
 * normals within acos(MRGI_VOXEL_INTERLEAVE_MIN_COS) ~ 26 degrees and each
 * receiver within MRGI_VOXEL_INTERLEAVE_MAX_SLOPE of the other's tangent
 * plane, |n . (p_u - p_t)| <= 0.2 |n| |p_u - p_t|); otherwise t computes
 * phase q itself (the section 2 rule restricted to phase q; a second GPU
 * pass can do this, it is the same function). The paper combines
 * unconditionally; the same-surface test is a decision made here: blocks
 * straddling a silhouette or crease would otherwise trade visibility between
 * surfaces that see the light differently (measured on TestVoxel's box
 * scene, 64^2, one level, against per-pixel naive masks: 5.5% of the bits
 * wrong in blocks with a depth step or crease when combined
 * unconditionally, 2.8% with the test; 0.5% in flat blocks either way).
 * Full blocks on one surface hold the same combined mask in all four
 * pixels; the next finer level reads the combined masks. On the GPU each
 * pixel stores its own N / 4 bits packed (quarter bit k = sample 4k + q);
 * the C twin keeps the unpacked N-bit layout, zeros in the other phases.
 *
 * ## 5. Bit-count refinement metric (NPW10 3.3.2)
 *
 * Over the 9 masks of a 3x3 neighbourhood (non-receivers skipped):
 * - MRGI_VOXEL_METRIC_DISAGREE (the paper's, default): the number of samples
 *   "partially visible in a neighborhood", popcount(OR ^ AND);
 * - MRGI_VOXEL_METRIC_COUNT_SPREAD: max - min of the per-texel visible
 *   counts (always <= DISAGREE; blind to samples that swap visibility
 *   between texels while counts stay equal).
 * A child is refined (computed) when metric >= threshold. The paper refines
 * "only when at least half the VPLs (i.e., 128) were partially visible":
 * threshold = ceil(refine_fraction N) with the default refine_fraction 0.5
 * (and >= 1 whenever refine_fraction > 0).
 *
 */
#ifndef MRGI_VISIBILITY_PYRAMID_H
#define MRGI_VISIBILITY_PYRAMID_H

#include "mrgi_area_light.h"
#include "mrgi_error.h"
#include "mrgi_multires.h"
#include "mrgi_voxel_march.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Most light samples per texel. */
#define MRGI_VOXEL_MAX_SAMPLES 4096
/** Words of the largest mask (128). */
#define MRGI_VOXEL_MAX_MASK_WORDS (MRGI_VOXEL_MAX_SAMPLES / 32)
/** Interleaving phases (2x2 blocks). */
#define MRGI_VOXEL_INTERLEAVE_PHASES 4
/** Phase set with every phase. */
#define MRGI_VOXEL_ALL_PHASES 15
/** Coarse neighbours read per texel (3x3). */
#define MRGI_VOXEL_NEIGHBOURS 9
/** Refinement metrics (section 5); GLSL: the same values. */
#define MRGI_VOXEL_METRIC_DISAGREE 0
#define MRGI_VOXEL_METRIC_COUNT_SPREAD 1
/** Default refinement fraction (NPW10 3.3.2: half the VPLs). */
#define MRGI_VOXEL_DEFAULT_REFINE_FRACTION 0.5f
/** Interleaving's same-surface test (section 4): smallest cosine between the normals. */
#define MRGI_VOXEL_INTERLEAVE_MIN_COS 0.9f
/** Interleaving's same-surface test: largest |n . d| / (|n| |d|) of the offset d between receivers. */
#define MRGI_VOXEL_INTERLEAVE_MAX_SLOPE 0.2f
/** The surround rule (section 3) applies to texels of this level and coarser
 *  (4 x 4 pixels and more): finer ones extrapolate by a pixel or two. */
#define MRGI_VOXEL_SURROUND_MIN_LEVEL 2

/** Light samples in eye space (borrowed). */
typedef struct mrgi_voxel_samples
{
  int32_t count;         /**< N, 1..MRGI_VOXEL_MAX_SAMPLES. */
  const float* position; /**< 3 N floats. */
  const float* normal;   /**< 3 N floats (the light surface's normals; give them when the emitter is geometry, mrgi_voxel_march.h), or NULL: none. */
  int32_t two_sided;     /**< Non-zero: the light emits on both sides, and a sample's normal is flipped to face the receiver (n . (P - y) < 0, summed x, y, z left to right) before the march, as the shaders do. 0 (one-sided): as given. */
} mrgi_voxel_samples;

/**
 * @brief Check a sample set: count in range, positions finite, normals (if
 *        any) finite. ::MRGI_ERR_INVALID_ARGUMENT naming the first bad sample.
 */
mrgi_status mrgi_voxel_samples_check(const mrgi_voxel_samples* samples, mrgi_error* err);

/** @brief Words of an N-sample mask: ceil(N / 32). */
static inline int32_t mrgi_voxel_mask_words(int32_t count)
{
  return (count + 31) >> 5;
}

/** @brief Interleaving phase of texel (x, y): (x & 1) | ((y & 1) << 1). */
static inline int32_t mrgi_voxel_interleave_phase(int32_t x, int32_t y)
{
  return (x & 1) | ((y & 1) << 1);
}

/** @brief Bits of one word whose samples are in `phase_set` (4 bits): (set & 15) * 0x11111111. */
uint32_t mrgi_voxel_phase_word_mask(uint32_t phase_set);

/** @brief Bits set in v, by the SWAR sequence the GLSL 1.50 shader writes. */
uint32_t mrgi_voxel_popcount(uint32_t v);

/**
 * @brief Visibility bits of the samples of `phase_set` at one receiver
 *        (section 2). No checks (hot path): `view` and `samples` checked,
 *        receiver finite.
 * @param normal   Receiver normal or NULL.
 * @param coarse   MRGI_VOXEL_NEIGHBOURS coarse masks (NULL entries skipped),
 *                 or NULL: naive.
 * @param reuse_hidden 1: every agreed bit is reused (section 2); 0: only the
 *                 bits all coarse masks agree are visible, the agreed hidden
 *                 ones are marched (section 3, the surround rule).
 * @param phase_set Subset of MRGI_VOXEL_ALL_PHASES.
 * @param mask     Receives mrgi_voxel_mask_words(N) words.
 * @return Rays marched.
 */
int64_t mrgi_voxel_visibility(const mrgi_voxel_view* view, const mrgi_voxel_samples* samples,
                              const float receiver[3], const float* normal,
                              const uint32_t* const* coarse, int reuse_hidden, uint32_t phase_set,
                              uint32_t* mask);

/**
 * @brief On which side of eye-space receiver p receiver q lies on screen
 *        along `axis` (0: x, 1: y): 1 after, -1 before, 0 at the same place
 *        (section 3, the surround rule). Perspective (both z < 0): the sign
 *        of p_a q_z - q_a p_z (q_a / -q_z - p_a / -p_z without a division);
 *        parallel: of q_a - p_a. 0 when q == p exactly, as the GLSL does.
 */
int mrgi_voxel_screen_side(const float p[3], const float q[3], int parallel, int axis);

/** Refinement metric of a neighbourhood (section 5). */
typedef struct mrgi_voxel_metric
{
  int32_t disagree;  /**< popcount(OR ^ AND) over the masks; 0 without masks. */
  int32_t count_min; /**< Smallest visible count; 0 without masks. */
  int32_t count_max; /**< Largest visible count; 0 without masks. */
  int32_t masks;     /**< Masks that took part. */
} mrgi_voxel_metric;

/** @brief Metric over MRGI_VOXEL_NEIGHBOURS masks (NULL entries skipped) of `words` words. */
void mrgi_voxel_neighbourhood_metric(const uint32_t* const* masks, int32_t words,
                                     mrgi_voxel_metric* metric);

/** @brief 1 when `metric` (MRGI_VOXEL_METRIC_*) reaches `threshold` (>= 0; 0 always refines). */
int mrgi_voxel_needs_refinement(const mrgi_voxel_metric* metric, int32_t metric_kind,
                                int32_t threshold);

/**
 * @brief Whether receivers (p, n) and (q, m) lie on one surface (section 4):
 *        both normals given, cos(n, m) >= MRGI_VOXEL_INTERLEAVE_MIN_COS, and
 *        |n . (q - p)| <= MRGI_VOXEL_INTERLEAVE_MAX_SLOPE |n| |q - p| and the
 *        same with m (squared, without divisions, as the GLSL writes it).
 *        Normals need not be unit; NULL means none (0).
 */
int mrgi_voxel_same_surface(const float p[3], const float n[3], const float q[3],
                            const float m[3]);

/**
 * @brief Combine interleaved quarters (section 4): phase q's bits from
 *        quarter[q]; a NULL quarter leaves its bits 0.
 */
void mrgi_voxel_interleave_combine(const uint32_t* const quarter[MRGI_VOXEL_INTERLEAVE_PHASES],
                                   int32_t words, uint32_t* out);

/** Knobs of the coarse-to-fine visibility. */
typedef struct mrgi_voxel_incremental_params
{
  int32_t interleave;    /**< 1: 2x2 interleaved sampling (default), 0: every texel marches all. */
  int32_t metric;        /**< MRGI_VOXEL_METRIC_DISAGREE (default) or _COUNT_SPREAD. */
  float refine_fraction; /**< [0, 1]; threshold = ceil(fraction N), >= 1 when > 0; 0 computes every texel. */
} mrgi_voxel_incremental_params;

/** @brief Defaults: interleave on, DISAGREE, MRGI_VOXEL_DEFAULT_REFINE_FRACTION. NULL-safe. */
void mrgi_voxel_incremental_params_default(mrgi_voxel_incremental_params* params);

/** @brief The integer threshold for N samples (section 5); -1 for bad input. */
int32_t mrgi_voxel_refine_threshold(float refine_fraction, int32_t count);

/** What a coarse-to-fine run cost. */
typedef struct mrgi_voxel_incremental_stats
{
  int64_t computed[MRGI_MULTIRES_MAX_LEVELS];  /**< COMPUTED receiver texels per level. */
  int64_t inherited[MRGI_MULTIRES_MAX_LEVELS]; /**< INHERITED receiver texels per level. */
  int64_t rays[MRGI_MULTIRES_MAX_LEVELS];      /**< Rays marched per level. */
  int64_t rays_total;                          /**< Sum of rays. */
  int64_t rays_naive; /**< N x receivers at level 0: the brute-force per-pixel cost. */
} mrgi_voxel_incremental_stats;

/**
 * @brief Coarse-to-fine visibility masks at every texel (sections 3-5).
 * @param layout    From mrgi_multires_layout_init().
 * @param receiver_position,receiver_normal 4 floats per flattened texel
 *                  (mrgi_multires_receivers_build()); `receiver_floats` each.
 * @param view      Checked here (mrgi_voxel_view_check()).
 * @param samples   Checked here.
 * @param refine    Optional: one byte per flattened texel, nonzero forces
 *                  COMPUTED; NULL for none. `refine_size` its bytes.
 * @param params    NULL means the defaults.
 * @param masks     Receives mrgi_voxel_mask_words(N) words per flattened
 *                  texel (texel index t at t * words); `mask_words` its size.
 * @param stats     Receives the costs; may be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL pointers, short arrays, a bad
 *         layout, view, samples or params; ::MRGI_ERR_OUT_OF_MEMORY (scratch
 *         is allocated once per call).
 */
mrgi_status mrgi_voxel_visibility_pyramid(
  const mrgi_multires_layout* layout, const float* receiver_position,
  const float* receiver_normal, size_t receiver_floats, const mrgi_voxel_view* view,
  const mrgi_voxel_samples* samples, const uint8_t* refine, size_t refine_size,
  const mrgi_voxel_incremental_params* params, uint32_t* masks, size_t mask_words,
  mrgi_voxel_incremental_stats* stats, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
