/**
 * @file mrgi_ssgi.h
 * @brief Screen-space one-bounce indirect light and directional occlusion
 *        (Ritschel, Grosch and Seidel 2009, "SSDO"), as BMR evaluates
 *        SSGI. C twin of the GPU stage vtkMRGISSGI (vtkMRGISSGIFS.glsl).
 *
 * ## 1. Kernel (mrgi_ssgi_kernel)
 *
 * N points k_i in the unit upper half ball (z > 0), deterministic (no
 * random engine, so the C++ layer uploads exactly these floats): for
 * i = 0..N-1, with g2(m), g3(m) the radical inverses of m in bases 2 and 3,
 *
 *     cos_i = g2(i + 1)                 (in (0, 1): never on the tangent plane)
 *     phi_i = 2 pi g3(i + 1)
 *     s_i   = cbrt((i + 0.5) / N)       (uniform in the ball's volume)
 *     k_i   = s_i (sqrt(1 - cos_i^2) cos phi_i, sqrt(1 - cos_i^2) sin phi_i, cos_i)
 *
 * computed in double, stored as float. Directions are uniform in solid
 * angle over the hemisphere (z = cos uniform), as in Ritschel et al.
 *
 * ## 2. One receiver (mrgi_ssgi_receiver)
 *
 * Inputs: a G-buffer of W x H pixels, rows bottom-up (pixel (x, y) at
 * window coordinate (x + 0.5, y + 0.5)): eye-space position (xyz, w >
 * MRGI_GBUFFER_VALID_THRESHOLD where geometry), normal (xyz), and the direct
 * light image (attachment MRGI_GBUFFER_DIRECT, rgb); the projection; the
 * kernel; radius R > 0; bias b >= 0. The receiver: eye position P, normal n
 * (normalised here), diffuse albedo rho.
 *
 * Units are VTK's non-attenuating light units of
 * Documentation/IndirectLight.md: a direct-image pixel is the outgoing
 * radiance L of that surface (rho X for a Lambertian one), irradiance is
 * X = E / pi. The frame (T, B, n) is Duff et al.'s branchless orthonormal
 * basis of n (sign s = n.z >= 0 ? 1 : -1): no noise texture, so the result
 * depends only on P, n and the buffers, not on the pixel.
 *
 *     c_i = k_i.z / |k_i|, C = sum_i c_i          (cosine of sample direction)
 *     S   = P + R (T k.x + B k.y + n k.z)
 *     u   = (proj(S).xy / w) * 0.5 + 0.5; off screen (u outside [0, 1)): skip
 *     q   = floor(u (W, H)); Q = position(q); skip when Q is background
 *     occluded when Q.z >= S.z + b, d = |Q - P| <= MRGI_SSGI_RANGE R and
 *       n.(Q - P) > b (above the receiver's tangent plane: at grazing angles a
 *       pixel's footprint exceeds the bias and a plane would block itself)
 *     occluded sample i:  visibility loses c_i / C, and Q is a sender:
 *       w = (Q - P) / d, cr = max(0, n.w), cs = max(0, -n_Q.w)
 *       A = pi R^2 / N                          (the sender area)
 *       F_i = min(A cr cs / (pi d^2 + A), c_i / C)
 *       X  += F_i L(q)
 *     V = 1 - sum_{occluded} c_i / C          (directional occlusion, [0, 1])
 *     bounce radiance = rho X
 *
 * Sender area: Ritschel et al. split the disk of radius R around the
 * receiver among the N samples, A = pi R^2 / N; the disk-to-point form
 * factor A cr cs / (pi d^2 + A) is the one of the VPL gather (IndirectLight.md
 * section 4), bounded near d = 0. The clamp F_i <= c_i / C keeps a sender
 * from covering more than its sample's share of the projected hemisphere, so
 * sum_i F_i <= 1 and X <= max L(q): the bounce never exceeds rho times the
 * brightest sender (energy sanity). The estimator is biased: senders far
 * across the disk get less than their share of the hemisphere, so a
 * receiver 0.1 R in front of a uniform wall, whose exact X is the wall's
 * radiance, gets about a third of it (core.TestSSGI, test_energy_crevice).
 *
 * A sample whose pixel holds a surface in front of it (toward the eye) is
 * taken as blocked in that direction; the blocking surface is the sender
 * (Ritschel et al. section 3.2: occluders send). An unblocked sample sees
 * the far field, which the ambient term and the VPL gather light; it sends
 * nothing here. Surfaces farther than MRGI_SSGI_RANGE R from P do not block
 * (a foreground object far in front is not near-field geometry).
 *
 * Left out: senders outside the image or hidden behind the first depth
 * layer; the sender's own visibility to P (one depth layer, no ray march);
 * specular and ambient parts of the direct image are sent as if diffuse;
 * light bouncing more than once; per-pixel kernel rotation and the blur that
 * would hide its pattern (the kernel is the same for every pixel, so the
 * result is smooth but biased by the kernel's N directions).
 *
 * Never NaN: an invalid receiver (background, non-finite P, a zero or
 * non-finite normal) gets X = 0, V = 1; non-finite buffer values at a sample
 * skip the sample.
 *
 * ## 3. Levels
 *
 * mrgi_ssgi_compute() evaluates level l >= 0 (block side 2^l): level texel
 * (i, j) is the receiver at pixel (min(i 2^l + c, W - 1), min(j 2^l + c,
 * H - 1)), c = 2^l / 2, as mrgi_ssao_compute(); samples read the
 * full-resolution buffers. Level 0 is the full-resolution effect.
 *
 * ## 4. Decision margin
 *
 * The result is continuous in the buffers except at four tests: the
 * depth test (|Q.z - (S.z + b)| / max(|S.z|, 1e-30)), the range test
 * (|d - MRGI_SSGI_RANGE R| / (MRGI_SSGI_RANGE R)), the plane test
 * (|n.(Q - P) - b| / R) and the texel a sample
 * falls in (distance of u (W, H) to the nearest texel edge, in texels,
 * the image borders included). The receiver returns the smallest margin;
 * parity tests compare only receivers whose margin is not tiny.
 */
#ifndef MRGI_SSGI_H
#define MRGI_SSGI_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest kernel (a uniform array of the GPU stage; BMR quotes 228 and 288). */
#define MRGI_SSGI_MAX_SAMPLES 512
/** Default samples and radius (eye-space units, as SSAO's). */
#define MRGI_SSGI_DEFAULT_SAMPLES 64
#define MRGI_SSGI_DEFAULT_RADIUS 0.5
#define MRGI_SSGI_DEFAULT_BIAS 0.01
/** A blocker farther from the receiver than this times R does not block. */
#define MRGI_SSGI_RANGE 2.0
/** Largest level (block side 2^8). */
#define MRGI_SSGI_MAX_LEVEL 8
/** Channels of mrgi_ssgi_compute()'s output: bounce rgb, visibility, margin. */
#define MRGI_SSGI_CHANNELS 5

/**
 * @brief The kernel of `count` samples (section 1).
 * @param count 1..MRGI_SSGI_MAX_SAMPLES.
 * @param out   3 * count floats; written only on success.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a count out of range or NULL `out`.
 */
mrgi_status mrgi_ssgi_kernel(int32_t count, float* out, mrgi_error* err);

/** What one SSGI evaluation reads; nothing is owned. */
typedef struct mrgi_ssgi_params
{
  const float* kernel;  /**< 3 * sample_count floats (mrgi_ssgi_kernel()). */
  int32_t sample_count; /**< 1..MRGI_SSGI_MAX_SAMPLES. */
  float radius;         /**< R, eye-space units; finite, > 0. */
  float bias;           /**< Depth bias, eye-space units; finite, >= 0. */
  float projection[16]; /**< Eye -> clip, column-major; finite. */
} mrgi_ssgi_params;

/** What one receiver gets. */
typedef struct mrgi_ssgi_result
{
  float irradiance[3]; /**< X, VTK irradiance from the near-field senders. */
  float radiance[3];   /**< rho X: the one-bounce radiance it reflects. */
  float visibility;    /**< V in [0, 1]: unblocked share of the ambient term. */
  float margin;        /**< Section 4; FLT_MAX for an invalid receiver. */
} mrgi_ssgi_result;

/**
 * @brief Check `params`: sample count and kernel, finite radius > 0, finite
 *        bias >= 0, finite projection.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the first bad field.
 */
mrgi_status mrgi_ssgi_params_validate(const mrgi_ssgi_params* params, mrgi_error* err);

/**
 * @brief Section 2 for one receiver. `params` must have passed
 *        mrgi_ssgi_params_validate(); `position`, `normal`, `direct` are equal
 *        sized images of >= 3 (position: 4) channels, rows bottom-up.
 * @param eye_position, normal_vector, albedo The receiver (3 floats each);
 *        any value is accepted (invalid ones give X = 0, V = 1).
 */
void mrgi_ssgi_receiver(const mrgi_ssgi_params* params, const mrgi_image* position,
  const mrgi_image* normal, const mrgi_image* direct, const float eye_position[3],
  const float normal_vector[3], const float albedo[3], mrgi_ssgi_result* out);

/**
 * @brief Every texel of level `level` (section 3); receivers read position,
 *        normal and albedo of their pixel (background: X = 0, V = 1).
 * @param position, normal, albedo, direct Valid W x H images, 4 channels
 *        (direct and albedo: >= 3), rows bottom-up.
 * @param level 0..MRGI_SSGI_MAX_LEVEL.
 * @param out Receives a new ceil(W / 2^l) x ceil(H / 2^l) image of
 *            MRGI_SSGI_CHANNELS channels (rho X rgb, V, margin); zeroed on
 *            failure.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for invalid params, mismatched images,
 *         a level out of range; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_ssgi_compute(const mrgi_ssgi_params* params, const mrgi_image* position,
  const mrgi_image* normal, const mrgi_image* albedo, const mrgi_image* direct, int32_t level,
  mrgi_image* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
