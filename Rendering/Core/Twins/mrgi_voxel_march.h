/**
 * @file mrgi_voxel_march.h
 * @brief Visibility of one light sample from one receiver by marching the
 *        screen-space voxel buffer: C twin of the per-ray loop of the
 *        visibility shaders (the naive query of NPW10 section 3.3.1).
 *
 * Paper: Nichols, Penmatsa and Wyman 2010 (NPW10), section 3.3.1: "we
 * instead sample the ray uniformly between each fragment and VPL [...] we
 * partially compensate for missed occlusions by checking multiple bits in
 * texels fetched from the voxel buffer. This essentially thickens the ray";
 * section 4.3: self-occlusion ("shadow acne") is fought with "a bias to push
 * the ray origin away from the surface". Bit layout, slicing, projection:
 * mrgi_voxel.h. Every step below is what the GLSL writes, in float.
 *
 * ## Inputs
 *
 * Eye space (the G-buffer's): receiver position P with normal Np (the
 * G-buffer normal, facing the viewer), light sample position L with normal
 * Nl (the light's surface normal), each normal optional: NULL or a zero
 * vector means "none" (no offset, no horizon test at that end). Normals
 * need not be unit. All inputs finite (the batch functions in
 * mrgi_visibility_pyramid.h check them; this per-ray function does not).
 *
 * ## The march, step by step
 *
 *  1. D = L - P. D == 0 (zero-length segment): VISIBLE.
 *  2. Horizon: with Np, dot(Np, D) <= 0 -> OCCLUDED (the sample is below
 *     the receiver's tangent plane: its own surface hides it; the cosine of
 *     eq. 2's G is 0 there anyway). With Nl, dot(Nl, -D) <= 0 -> OCCLUDED.
 *  3. Bias, part 1: the voxel size at an end X is
 *       vs(X) = max(2 w / (scale_x VW), 2 w / (scale_y VH), 1 / slice_scale),
 *     w = |d_X| (perspective) or 1 (parallel): the larger of the voxel
 *     pixel's eye-space width and height at X's depth and the slice
 *     thickness. The segment marched runs from O = P + normal_offset vs(P) n_p
 *     to E = L + normal_offset vs(L) n_l (n = unit normal; no offset without
 *     a normal). normal_offset is in voxel sizes. That is the default
 *     direction (offset_along_ray MRGI_VOXEL_OFFSET_NORMALS). Along the ray
 *     instead (MRGI_VOXEL_OFFSET_RAY_AT_RECEIVER: at P; _RAY_AT_BOTH: at
 *     both ends), an end X with height h = normal_offset vs(X), unit normal
 *     n and unit direction u to the other end, c = dot(n, u) > 0, moves
 *       X + a u + (h - a c) n,   a = min(w h / c, MAX_SHARE |D|),
 *       w = clamp((c - MIN_COS) / (FULL_COS - MIN_COS), 0, 1)
 *     (MRGI_VOXEL_ALONG_RAY_*: 0.25, 0.5, 0.25): the same height h above
 *     X's plane, reached along the ray where it leaves steeply (w = 1),
 *     along the normal where it grazes (w = 0; a grazing ray would travel
 *     far along it), blended between, at most a quarter of the segment
 *     along it (the ends never cross) (mrgi_voxel_offset_end()).
 *  4. Clip O -> E against the view frustum (Liang-Barsky, t in [0, 1]),
 *     six half-spaces f(X) >= 0 with w = d or 1:
 *       d - near, far - d, scale_x x + (1 + offset_x) w,
 *       -scale_x x + (1 - offset_x) w, and the same two for y.
 *     Parts outside [near, far] hold no voxels (mrgi_voxel.h section 2), and
 *     the near plane (near > 0 for perspective) also cuts away whatever lies
 *     behind the camera: a light sample behind the camera is marched up to
 *     the near plane. Parts off the screen hold no voxels either: they are
 *     treated as empty (VISIBLE there): occluders outside the view frustum
 *     are unknown to a screen-space method. An empty clipped segment: VISIBLE.
 *     A = O + t0 (E - O), B = O + t1 (E - O).
 *  5. Project A and B (mrgi_voxel_project): (uA, vA, dA), (uB, vB, dB).
 *  6. Step rule: n = int(clamp(ceil(max(|uB - uA|, |vB - vA|)), 1, max_steps)):
 *     one step per voxel pixel along the major axis of the projected segment
 *     (uniform in screen space, NPW10 3.3.1), capped at max_steps (steps then
 *     grow longer than a pixel; only the pixel at each step's middle is read).
 *  7. Bias, part 2: the skip boxes. For an end X in {P, L} inside the frustum
 *     (all six f(X) >= 0), its voxel (floor(u), floor(v)) clamped to the
 *     grid, slice(d). A step whose pixel is within skip_radius (Chebyshev
 *     distance) of that voxel's pixel ignores the slices within skip_radius
 *     of that voxel's slice: the (2r+1)^3 voxels around each end never
 *     occlude, so neither the receiver's own surface nor the emitter's (an
 *     area light is usually scene geometry: a TV screen) shadows the ray.
 *  8. Step k = 0 .. n-1 covers screen parameters [s0, s1] = [k/n, (k+1)/n]:
 *       pixel  = clamp(floor((uA, vA) + ((uB, vB) - (uA, vA)) sm), 0, size - 1),
 *                sm = (k + 0.5) / n;
 *       depth(s) = 1 / (1/dA + (1/dB - 1/dA) s)   (perspective: 1/d is linear
 *                  in screen space) or dA + (dB - dA) s (parallel);
 *       [lo, hi] = [slice(min(depth(s0), depth(s1))), slice(max(...))];
 *       for each layer l from lo >> 7 to hi >> 7 (mrgi_voxel.h section 1;
 *       one layer unless the step crosses a multiple of 128 slices):
 *         mask_l = range_mask(lo - 128 l, hi - 128 l) minus the skip boxes
 *                  (their slices shifted by -128 l the same way);
 *       OCCLUDED when (texel(pixel, l) & mask_l) != 0 for some l.
 *     The depth along the segment is monotone, so [depth(s0), depth(s1)] is
 *     every depth the step's piece of segment passes: all the slices it
 *     crosses are tested, not only the one at the sample point, and a wall
 *     one slice thick cannot fall between two samples in depth.
 *  9. No step hit: VISIBLE.
 *
 * ## The bias in voxel units, and why
 *
 * Why voxel units: the receiver's own surface occupies its voxels, and how
 * far a ray must get before it leaves them scales with the voxel (the
 * slice thickness or the pixel's eye-space size, whichever is larger), not
 * with the scene. A planar receiver seen at angle alpha between the view
 * ray and the plane is voxelized (mrgi_voxel.h section 5) over its depth
 * range per pixel, +-p cos(alpha) / (2 sin(alpha)) (p = voxel pixel size),
 * rounded out to whole slices. A point at height H above the plane sits
 * H / sin(alpha) in front of it along the view ray, and a step's depth
 * interval spans up to one more pixel's worth of the segment; both sides
 * grow as 1 / sin(alpha), so the requirement H > c1 p cos(alpha) +
 * c2 thickness sin(alpha) holds at every view angle once H is a small
 * multiple of the voxel size, and above a plane the ray only climbs.
 * Measured (TestVoxel: planes tilted 0..90 degrees, seen from 2 to 90
 * degrees, lights at 1..80 degrees elevation, 128^2..512^2 voxels):
 * offsets of 1.25 voxel sizes and more never self-shadow, 1.0 does (up to
 * 9% of the rays on planes tilted 45..70 degrees). The default is
 * MRGI_VOXEL_DEFAULT_NORMAL_OFFSET = 1.5 (margin), skip_radius
 * MRGI_VOXEL_DEFAULT_SKIP_RADIUS = 1: the skip box absorbs curved receivers
 * and the first steps, whose footprint straddles the receiver's pixel, and
 * protects the light end (an emitter is usually scene geometry). The cost,
 * as NPW10 4.3 says: contact shadows of geometry within the offset are
 * missed; on TestVoxel's random box scenes at 128^2, rays wrongly visible
 * are 0.7% at 1.5 voxel sizes, 1.5% at 2 and 3.4% at 3, while rays wrongly
 * occluded stay near 2.3% (they are near misses within a voxel of other
 * geometry). Give light samples their normals when the emitter is
 * geometry: without one, the sample's own surface voxels stop rays that
 * reach it at a grazing angle (TestVoxel: 56% of reversed
 * surface-to-surface rays change their answer).
 *
 * Why along the ray: an offset along a normal moves the whole ray sideways
 * (by h at the end, shrinking towards the other end), towards whatever lies
 * on the normal's side. Rays that pass an occluder's edge closely, the
 * penumbra, then meet its voxels (cornell-area's back wall behind the tall
 * block, whose receivers face the block, is too dark there). Along the ray
 * the segment is the exact one, shortened. The cost: occluders within the
 * skipped part (at most 2 h along the ray) are missed, and an emitter set
 * into geometry (the living room's TV) meets its surroundings' voxels along
 * rays the normal offset lifted clear of them. Which is better depends on
 * the scene; measured in Documentation/Status.md and by TestVoxel
 * (test_march_offset_direction, random boxes), so the default stays NPW10's.
 *
 * ## Symmetry
 *
 * Swapping the ends (receiver <-> light, with their normals) marches the
 * same steps in reverse order: the step midpoints k + 0.5 map to
 * n - k - 0.5, the depth intervals and both skip boxes are the same, so
 * the answer is the same except (a) where float rounding moves a step's
 * midpoint or a depth across a pixel or slice boundary (the clip parameters
 * and interpolations are computed from the other end), (b) when only one
 * end has a normal (the offset and horizon test then apply to one end),
 * (c) with MRGI_VOXEL_OFFSET_RAY_AT_RECEIVER (the ends are offset
 * differently), and (d) when the step cap binds (steps longer than a pixel read other pixels
 * when walked from the other end only through (a)). TestVoxel measures it.
 *
 * ## Precision
 *
 * The C twin computes in float in the order written above. The answer is
 * binary, so the GPU and the twin agree exactly except where a step's
 * middle, a depth or a clip parameter lies within float rounding of a
 * pixel or slice boundary (GLSL's division and 1/d need not be correctly
 * rounded); parity tests should compare masks and allow such isolated
 * bits, counting them.
 *
 * ## Occluder distance (variance shadow query, NPW10 3.3.3)
 *
 * mrgi_voxel_march_occluder_fraction() marches the same steps from the
 * light end (k = n-1 down to 0) and returns, for the first step that hits,
 * z = |L - X| / |L - P|, X the point at the step's middle (screen parameter
 * sm mapped back to the segment: tau = sm (1/dB) / (1/dA + (1/dB - 1/dA) sm)
 * for perspective, tau = sm for parallel; X = A + tau (B - A)), clamped to
 * [0, 1]: the distance from the light sample to the nearest occluder, as a
 * fraction of the ray's length; 1 when no step hits or the segment has zero
 * length (the receiver itself is the first surface, as in a shadow map);
 * 0 below either horizon (occluded at the light, as the binary march says).
 */
#ifndef MRGI_VOXEL_MARCH_H
#define MRGI_VOXEL_MARCH_H

#include "mrgi_error.h"
#include "mrgi_voxel.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest step cap (also the GLSL loop's compile-time bound). */
#define MRGI_VOXEL_MAX_STEPS 4096
/** Default step cap: covers the diagonal of a 181^2 buffer one pixel per step. */
#define MRGI_VOXEL_DEFAULT_MAX_STEPS 256
/** Default offset along the normals, in voxel sizes (see "The bias"). */
#define MRGI_VOXEL_DEFAULT_NORMAL_OFFSET 1.5f
/** Largest accepted normal offset, in voxel sizes. */
#define MRGI_VOXEL_MAX_NORMAL_OFFSET 16.0f
/** mrgi_voxel_march_params::offset_along_ray: both ends offset along their normals (NPW10 4.3; default). */
#define MRGI_VOXEL_OFFSET_NORMALS 0
/** ... the receiver's end along the ray (blended, see "The bias"), the light's along its normal. */
#define MRGI_VOXEL_OFFSET_RAY_AT_RECEIVER 1
/** ... both ends along the ray (blended). */
#define MRGI_VOXEL_OFFSET_RAY_AT_BOTH 2
/** Offset direction at an end whose cosine c to the other end is below this: along the normal. */
#define MRGI_VOXEL_ALONG_RAY_MIN_COS 0.25f
/** ... at or above this: along the ray (to the same height); a linear blend between (see "The bias"). */
#define MRGI_VOXEL_ALONG_RAY_FULL_COS 0.5f
/** Most of the segment one end's offset moves along the ray (the ends never cross). */
#define MRGI_VOXEL_ALONG_RAY_MAX_SHARE 0.25f
/** Default skip box radius, in voxels. */
#define MRGI_VOXEL_DEFAULT_SKIP_RADIUS 1
/** Largest accepted skip box radius, in voxels. */
#define MRGI_VOXEL_MAX_SKIP_RADIUS 8

/**
 * Loop iterations one shader invocation may spend marching. Mesa's
 * llvmpipe ends every loop of an invocation once 65535 iterations have run
 * in all (gallivm's loop limiter), silently: a gather that marched 256
 * samples x 256 steps in one fragment lost half its samples (measured).
 * Shaders that march many samples per fragment take them in batches of
 * mrgi_voxel_samples_per_batch().
 */
#define MRGI_VOXEL_ITERATION_BUDGET 60000
/**
 * Loop iterations charged per march step: the step and its layer loop, one
 * iteration per layer the step's depth interval reaches (1 to
 * MRGI_VOXEL_MAX_LAYERS; the range mask itself is written without a loop),
 * so at most 5, with a margin.
 */
#define MRGI_VOXEL_ITERATIONS_PER_STEP 8
/** Loop iterations charged per march besides its steps (clipping planes, the sample loop). */
#define MRGI_VOXEL_ITERATIONS_PER_MARCH 32

/** Knobs of the march. */
typedef struct mrgi_voxel_march_params
{
  int32_t max_steps;   /**< Step cap, 1..MRGI_VOXEL_MAX_STEPS. */
  float normal_offset; /**< Bias along the normals in voxel sizes, [0, MRGI_VOXEL_MAX_NORMAL_OFFSET]. */
  int32_t skip_radius; /**< Skip box radius in voxels, 0..MRGI_VOXEL_MAX_SKIP_RADIUS. */
  int32_t offset_along_ray; /**< MRGI_VOXEL_OFFSET_NORMALS (default), _RAY_AT_RECEIVER or _RAY_AT_BOTH. */
} mrgi_voxel_march_params;

/** @brief Defaults: the MRGI_VOXEL_DEFAULT_* values. NULL-safe. */
void mrgi_voxel_march_params_default(mrgi_voxel_march_params* params);

/**
 * @brief Light samples one shader invocation may march within
 *        ::MRGI_VOXEL_ITERATION_BUDGET at this step cap:
 *        max(1, budget / (max_steps * MRGI_VOXEL_ITERATIONS_PER_STEP + MRGI_VOXEL_ITERATIONS_PER_MARCH)).
 *        (28 at the default 256 steps.) Non-positive max_steps count as 1.
 */
int32_t mrgi_voxel_samples_per_batch(int32_t max_steps);

/**
 * @brief Most steps one march through `grid` takes at step cap `max_steps`:
 *        min(max_steps, max(width, height) + 2), at least 1. A march steps
 *        once per voxel pixel along the major axis of its segment clipped to
 *        the view frustum (step 6), which spans at most the grid's larger
 *        side (+ 2 for rounding at the frustum's faces). Pass it to
 *        mrgi_voxel_samples_per_batch(): a 128^2 buffer marches twice the
 *        samples per batch that the default cap of 256 steps allows.
 */
int32_t mrgi_voxel_step_bound(const mrgi_voxel_grid* grid, int32_t max_steps);

/** @brief Check the knobs' ranges. ::MRGI_ERR_INVALID_ARGUMENT naming the bad field. */
mrgi_status mrgi_voxel_march_params_validate(const mrgi_voxel_march_params* params,
                                             mrgi_error* err);

/** Everything a march reads: the shader's uniforms and its voxel texture (borrowed). */
typedef struct mrgi_voxel_view
{
  mrgi_voxel_grid grid;               /**< From mrgi_voxel_grid_init(). */
  mrgi_voxel_projection projection;   /**< The camera that rendered the G-buffer. */
  mrgi_voxel_march_params params;     /**< Step cap and bias. */
  const uint32_t* voxels;             /**< The voxel buffer (mrgi_voxel.h section 3). */
  size_t voxel_words;                 /**< Words in `voxels`, >= mrgi_voxel_buffer_words(). */
} mrgi_voxel_view;

/**
 * @brief Check a view once before marching: grid, projection, params, the
 *        buffer's size, and near > 0 for a perspective projection.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the problem.
 */
mrgi_status mrgi_voxel_view_check(const mrgi_voxel_view* view, mrgi_error* err);

/** @brief Voxel size vs(X) at a point of linear depth d (step 3). */
float mrgi_voxel_size_at(const mrgi_voxel_view* view, float depth);

/**
 * @brief March from a receiver to a light sample (steps 1-9). No checks:
 *        `view` passed mrgi_voxel_view_check(), points finite.
 * @param receiver_normal,sample_normal May be NULL (none).
 * @return 1 visible, 0 occluded.
 */
int mrgi_voxel_march(const mrgi_voxel_view* view, const float receiver[3],
                     const float* receiver_normal, const float sample[3],
                     const float* sample_normal);

/**
 * @brief Distance from the light sample to the nearest occluder as a
 *        fraction of the segment, in [0, 1]; 1: none (see the file comment).
 *        Same preconditions as mrgi_voxel_march(); consistent with it:
 *        the result is < 1 only if mrgi_voxel_march() says occluded (up to a
 *        hit whose middle maps to the receiver end exactly).
 */
float mrgi_voxel_march_occluder_fraction(const mrgi_voxel_view* view, const float receiver[3],
                                         const float* receiver_normal, const float sample[3],
                                         const float* sample_normal);

#ifdef __cplusplus
}
#endif

#endif
