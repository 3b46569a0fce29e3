/**
 * @file mrgi_ism_visibility.h
 * @brief Visibility of a receiver from a VPL through that VPL's imperfect
 *        shadow map: the shadow test of the gather (C twin of
 *        vtkMRGIISMLookup.glsl).
 *
 * Papers: Ritschel et al. 2008 (RGK08) section 3.3 and Ritschel et al. 2011
 * (RIHKS11) 6.1: each VPL's ISM tile (mrgi_ism_atlas.h) holds the distance to
 * the nearest scene point in each cos-sphere texel; a receiver farther than
 * that (minus a bias) is in shadow. Spec: shared/plans/paper-specs.md,
 * Package 2.
 *
 * ## The test, step by step (world space; the GLSL writes the same, in float)
 *
 *  1. w = x - v (receiver minus VPL position), dist = |w|.
 *     dist < MRGI_ISM_MIN_DEPTH or not finite: VISIBLE (1); nothing can lie
 *     between two coincident points, and the gather term is 0 there anyway.
 *  2. d = w / dist. c = d . n (n = the VPL's unit normal). c <= 0: VISIBLE
 *     (the receiver is behind the VPL: the gather term is 0 there; the tile
 *     does not cover that hemisphere).
 *  2b. Grazing directions (beyond the papers): with max_texel_angle > 0,
 *     where a texel spans more than that angle, 2 / (T c) > max_texel_angle,
 *     the tile is not consulted: VISIBLE. The cos-sphere map spends few
 *     texels near the VPL's horizon (equal areas of projected solid angle),
 *     and a sparse point tile puts the surfaces around the VPL into those
 *     wide texels at depths far nearer than a receiver along the same
 *     direction: receivers there are shadowed by what only shares their
 *     texel. Measured against the ground truth with secondary visibility
 *     (Documentation/IndirectShadows.md, "Session 16"), this false shadow
 *     made ISM worse than no visibility in `corridor-large`. The directions
 *     skipped carry a share c0^2 of the VPL's power (c0 = 2 / (T angle)).
 *  3. Cos-sphere coordinates (mrgi_ism_atlas.h section 3): (s, t) = (d . t_n,
 *     d . b_n) with (t_n, b_n) = mrgi_ism_vpl_frame(n); continuous tile
 *     coordinates (u, v) = ((s + 1) / 2 T, (t + 1) / 2 T).
 *  4. Bias (RGK08 3.3; NPW10 4.3 discusses the same trade for voxels): the
 *     ISM is point-sampled, so the receiver's own surface appears in its
 *     texel at a depth up to about one texel's footprint nearer than dist.
 *     A texel spans 2 / T in s, i.e. an angle of about 2 / (T c) at the
 *     receiver's direction (ds = cos(theta) d theta), a length of
 *     dist 2 / (T c) there. The bias is
 *         bias = dist (relative_bias + texel_bias 2 / (T max(c, MRGI_ISM_BIAS_MIN_COS)))
 *     proportional to the distance and to the texel footprint.
 *  5. Compare: a texel with depth z says VISIBLE when dist - bias <= z.
 *     Without PCF the texel is (floor(u), floor(v)) clamped to 0..T-1, the
 *     same texel mrgi_ism_point_texel() would draw x into.
 *     With 2x2 PCF: the four texels around (u - 1/2, v - 1/2), i.e.
 *     i0 = floor(u - 1/2), j0 = floor(v - 1/2), i0 + 1, j0 + 1, each
 *     clamped to 0..T-1 (never into a neighbour tile), weighted
 *     bilinearly by fu = (u - 1/2) - i0, fv = (v - 1/2) - j0:
 *         h0 = V00 + (V10 - V00) fu,  h1 = V01 + (V11 - V01) fu,
 *         V = h0 + (h1 - h0) fv
 *     (the bilinear weights written as lerps a + (b - a) f, so that four
 *     visible texels give exactly 1 and four shadowed ones exactly 0; the
 *     weighted sum (1-fu)(1-fv) V00 + ... can round to 0.99999994).
 *  6. Empty texels hold MRGI_ISM_EMPTY_DEPTH: visible from any distance
 *     below 1e30.
 * Result: V in [0, 1] (0 or 1 without PCF). The gather multiplies the VPL's
 * term by V.
 *
 * ## Precision
 * The twin computes in float in the order above (as the GLSL), so GPU and
 * C agree except where float rounding moves (u, v) across a texel edge or
 * dist - bias across z; parity tests count those cases.
 */
#ifndef MRGI_ISM_VISIBILITY_H
#define MRGI_ISM_VISIBILITY_H

#include "mrgi_error.h"
#include "mrgi_ism_atlas.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Smallest cosine the texel footprint of the bias uses (grazing directions). */
#define MRGI_ISM_BIAS_MIN_COS 0.1f
/** Default relative bias (fraction of the distance). */
#define MRGI_ISM_DEFAULT_RELATIVE_BIAS 0.02f
/**
 * Default texel bias (texel footprints). Two effects pull against each other:
 * (a) a receiver's own surface appears in its texel (and the PCF neighbours)
 * at up to several footprints nearer, and self-shadows it; (b) the bias is
 * a length, dist 2 texel_bias / (T c): at T = 32 and 3 footprints it is 20%
 * of the distance facing the VPL and larger than the distance itself near
 * c = 0.2, so an occluder close to its receiver (the corridor's statue and
 * the floor behind it) can never shadow it.
 * (a) depends on how densely points cover the tile. On a dense, push-pulled
 * tile (core.TestISMVisibility: 64^2 tile, 40k points on a plane facing the
 * VPL and on a tilted wall, receivers up to 60..65 degrees off the VPL
 * normal, PCF on) receivers self-shadowed at texel bias 1.0: 23% / 16%,
 * 2.0: 2.8%, 2.5: 0.1%, 3.0: none. With the stage's defaults (256 points per
 * 32^2 tile, no push-pull, MRGI_ISM_DEFAULT_PUSH_PULL) most texels are empty
 * and (a) is rare: Testing/Benchmarks/ism_visibility_diagnostic.c (exact
 * ray casts, 64 VPLs, adaptive points) gives, as unoccluded light wrongly
 * removed / rel. RMS of the gathered light vs exact (no visibility: 0.028 and
 * 0.44): corridor texel bias 1: 1.9% / 0.021, 1.5: 1.0% / 0.016,
 * 3: 0.2% / 0.026; u-shape 1: 11% / 0.30, 1.5: 7.9% / 0.31, 3: 1.7% / 0.39;
 * open corner (nothing occluded) 1: 1.9%, 1.5: 1.1%, 3: 0.2%. Against the
 * ground truth with secondary visibility (Documentation/IndirectShadows.md,
 * "Session 12"): with the default one-level mean push-pull
 * (MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS), 1.5 keeps the corridor's statue
 * shadow within 14% of the truth, where 1.25 over-shadows the corridor
 * (error above no visibility) and 2.0 leaves the shadow 50% too bright.
 * Without push-pull 1.0 is the better choice. Raise it to 3 for dense tiles
 * (PointsPerVPL >= T^2).
 */
#define MRGI_ISM_DEFAULT_TEXEL_BIAS 1.5f
/** Largest accepted relative bias / texel bias. */
#define MRGI_ISM_MAX_BIAS 16.0f
/**
 * Default widest texel (radians) the test trusts (step 2b): at the default
 * 32^2 tiles, directions with c < 0.39 (15% of a VPL's power) are not
 * shadowed. Measured (Documentation/IndirectShadows.md, "Session 16") on
 * the corridors, where it removes false shadows, and on the closed Cornell
 * boxes, where it costs least. 0 turns the rule off.
 */
#define MRGI_ISM_DEFAULT_MAX_TEXEL_ANGLE 0.16f
/** Largest accepted max_texel_angle (radians). */
#define MRGI_ISM_MAX_TEXEL_ANGLE_LIMIT 4.0f

/** Lookup parameters (section 4 and 5). */
typedef struct mrgi_ism_lookup_params
{
  float relative_bias; /**< >= 0, <= MRGI_ISM_MAX_BIAS. */
  float texel_bias;    /**< >= 0, <= MRGI_ISM_MAX_BIAS. */
  int32_t pcf;         /**< 0: one texel; 1: 2x2 bilinear PCF. */
  float max_texel_angle; /**< Step 2b, radians, 0..MRGI_ISM_MAX_TEXEL_ANGLE_LIMIT; 0: off. */
} mrgi_ism_lookup_params;

/** @brief The defaults above, PCF on. */
void mrgi_ism_lookup_params_default(mrgi_ism_lookup_params* params);

/** @brief ::MRGI_ERR_INVALID_ARGUMENT naming a negative, NaN or absurd bias or angle, or a bad pcf flag. */
mrgi_status mrgi_ism_lookup_params_validate(const mrgi_ism_lookup_params* params, mrgi_error* err);

/**
 * @brief V of receiver x from VPL `vpl_index` (section "The test").
 * @param depth  The push-pulled atlas (layout->width * layout->height floats).
 * @param vpl_normal Normal of the VPL (normalized here in float, as the
 *                   GLSL's normalize(); a zero or non-finite one gives 1).
 * @return V in [0, 1]; 1 for out-of-range vpl_index (never used by valid callers).
 */
float mrgi_ism_visibility(const mrgi_ism_atlas_layout* layout, const float* depth,
  int32_t vpl_index, const float vpl_position[3], const float vpl_normal[3],
  const float receiver[3], const mrgi_ism_lookup_params* params);

#ifdef __cplusplus
}
#endif

#endif
