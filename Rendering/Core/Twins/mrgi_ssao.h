/**
 * @file mrgi_ssao.h
 * @brief Screen-space ambient occlusion as VTK 9.1's vtkSSAOPass computes
 *        it: its hemisphere kernel and the AO factor of one receiver. C twin
 *        of the GPU stage vtkMRGISSAO (vtkMRGISSAOFS.glsl).
 *
 * ## 1. Kernel (mrgi_ssao_kernel)
 *
 * vtkSSAOPass::ComputeKernel() draws from a default-constructed
 * std::default_random_engine (libstdc++: minstd_rand0, x <- 16807 x mod
 * 2^31 - 1, seed 1) through std::uniform_real_distribution<float>(0, 1),
 * i.e. u = float(x - 1) / 2^31 in float (nextafterf(1, 0) if that rounds to
 * 1). Sample i takes three draws, (2 u0 - 1, 2 u1 - 1, u2); a sample whose
 * float length sqrtf(x^2 + y^2 + z^2) exceeds 1 is drawn again (the
 * hemisphere z >= 0 of the unit ball); the accepted one is scaled by
 * 0.1 + 0.9 (i / N)^2 (more samples near the receiver). Deterministic: the
 * same N always gives the same kernel, bit for bit the one of
 * vtkSSAOPass (checked by cxx.TestMRGISSAOvsVTK against the pass's own
 * Kernel member). Note that the kernel of size N is not a prefix of a larger
 * one (the scale depends on N).
 *
 * ## 2. AO factor of one receiver (mrgi_ssao_receiver)
 *
 * Inputs: a G-buffer of W x H pixels, rows bottom-up (GL's order: pixel
 * (x, y) is at window coordinate (x + 0.5, y + 0.5)): eye-space position
 * (4 floats, xyz, w > MRGI_GBUFFER_VALID_THRESHOLD where geometry) and
 * normal (4 floats, xyz unit); the camera's projection (eye -> clip,
 * column-major); the noise tile (vtkOpenGLRenderWindow's 64 x 64 Perlin
 * texture, values in [0, 1], repeated); the kernel; radius r > 0; bias b.
 *
 * For the receiver at pixel (x, y) with position P and normal n, exactly
 * vtkSSAOPass's shader, in float, in its order:
 *
 *     D = P(P, 1); z_P = D.z / D.w * 0.5 + 0.5     (window depth)
 *     receiver valid: P.w > threshold, P, n finite, n != 0, 0 < z_P < 1
 *     noise texel: s = (W / 64, H / 64) (integer division, as the shader's
 *       ivec2 / ivec2), c = ((x, y) + 0.5) / (W, H) * s,
 *       t = floor(c * 64) mod 64;  angle = 6.283185 * noise(t)
 *     v = (cos angle, sin angle, 0); T = normalize(v - n (v.n)); B = n x T
 *     for each kernel sample k_i:
 *       S = P + (T k.x + B k.y + n k.z) r
 *       C = P(S, 1); u = C.xy / C.w * 0.5 + 0.5
 *       q = clamp(floor(u * (W, H)), 0, (W, H) - 1)   (nearest, clamp to edge)
 *       if position(q) is valid:
 *         d = position(q).z
 *         range = smoothstep(0, 1, r / |P.z - d|)
 *         occlusion += (d >= S.z + b ? 1 : 0) * range
 *     AO = 1 - occlusion / N
 *
 * An invalid receiver, or one whose tangent frame is degenerate (n parallel
 * to v: vtkSSAOPass would normalise a zero vector and write NaN), has AO = 1
 * (no occlusion). AO is in [0, 1] and never NaN.
 *
 * ### Where this differs from vtkSSAOPass, and why
 *
 * - vtkSSAOPass stores positions as RGB16F (half floats: an eye depth of
 *   5 is rounded to 1/256) and reads the sample's depth from a mipmap level
 *   round(40 |u - u_P|) of them (a speed trick of "scalable ambient
 *   obscurance"); MRGI reads its float G-buffer at level 0. The two agree
 *   where the sample lands within about 0.0125 of the image width of the
 *   receiver and half-float rounding does not flip a depth test.
 * - A sample that lands on the background: vtkSSAOPass reads whatever its
 *   position buffer was cleared to (the renderer's background colour as a
 *   position); here the background never occludes.
 * - vtkSSAOPass also requires z_P - depth < 0.0001 with the depth
 *   buffer's depth: MRGI's float position is that of the visible surface,
 *   so the test is implied; vtkSSAOPass's half-float position may fail it
 *   (the receiver then gets AO 1). With params->depth the twin applies it.
 * - vtkSSAOPass writes AO to an 8-bit texture (steps of 1/255); this twin
 *   and vtkMRGISSAO keep it in float.
 *
 * ## 3. Levels
 *
 * mrgi_ssao_compute() evaluates a whole level l >= 0 (block side 2^l): level
 * texel (i, j) is the receiver at pixel (min(i 2^l + c, W - 1), min(j 2^l + c,
 * H - 1)), c = 2^l / 2 (the block's centre pixel; c = 0 at level 0), with
 * that pixel's noise; samples still read the full-resolution G-buffer.
 * Level 0 is vtkSSAOPass's full-resolution AO.
 *
 * ## 4. Decision margin
 *
 * AO is a sum of step functions: a position that moves by one float ulp
 * may flip a sample. mrgi_ssao_receiver() also returns the smallest margin of
 * the receiver's decisions: min over samples of |d - (S.z + b)| / max(|S.z|,
 * 1e-30), of the distance of u (W, H) to the nearest texel edge (in
 * texels) and of the distance of c * 64 to the nearest noise texel edge
 * (c * 64 is often an integer when W or H is not a multiple of 64: a GPU's
 * interpolated texture coordinate then falls on either side). Parity tests
 * compare only receivers whose margin is not tiny.
 */
#ifndef MRGI_SSAO_H
#define MRGI_SSAO_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** vtkSSAOPass's default kernel size, radius and bias (VTK 9.1). */
#define MRGI_SSAO_DEFAULT_KERNEL_SIZE 32
#define MRGI_SSAO_DEFAULT_RADIUS 0.5
#define MRGI_SSAO_DEFAULT_BIAS 0.01
/** Largest kernel (vtkSSAOPass clamps KernelSize to 1..1000). */
#define MRGI_SSAO_MAX_KERNEL_SIZE 1000
/** Side of vtkOpenGLRenderWindow's noise texture. */
#define MRGI_SSAO_NOISE_SIZE 64
/** Largest level (block side 2^8 = 256 pixels). */
#define MRGI_SSAO_MAX_LEVEL 8

/**
 * @brief vtkSSAOPass's kernel of `size` samples.
 * @param size 1..MRGI_SSAO_MAX_KERNEL_SIZE.
 * @param out  3 * size floats (x, y, z per sample); written only on success.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a size out of range or a NULL `out`.
 */
mrgi_status mrgi_ssao_kernel(int32_t size, float* out, mrgi_error* err);

/** What one SSAO evaluation reads; nothing is owned. */
typedef struct mrgi_ssao_params
{
  const float* kernel;  /**< 3 * kernel_size floats (mrgi_ssao_kernel()). */
  int32_t kernel_size;  /**< 1..MRGI_SSAO_MAX_KERNEL_SIZE. */
  float radius;         /**< Kernel radius in eye-space units; finite, > 0. */
  float bias;           /**< Depth bias in eye-space units; finite. */
  float projection[16]; /**< Eye -> clip, column-major (GL's order); finite. */
  const float* noise;   /**< MRGI_SSAO_NOISE_SIZE^2 values, row 0 bottom; finite. */
  /**
   * Optional (NULL: none, MRGI's case): the window depth of every pixel of
   * the G-buffer (W x H, rows bottom-up), for vtkSSAOPass's own receiver
   * test: depth in (0, 1) and z_P - depth < 0.0001. Lets the twin
   * reproduce vtkSSAOPass from its buffers (its half-float positions can
   * fail that test; section 2).
   */
  const float* depth;
} mrgi_ssao_params;

/**
 * @brief Check `params`: kernel size and pointers, finite radius > 0,
 *        finite bias, projection and noise.
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the first bad field.
 */
mrgi_status mrgi_ssao_params_validate(const mrgi_ssao_params* params, mrgi_error* err);

/**
 * @brief AO factor of the receiver at pixel (x, y) (section 2); `params`
 *        must have passed mrgi_ssao_params_validate(), `position` and
 *        `normal` are W x H x 4 images (rows bottom-up), (x, y) inside.
 * @param margin When not NULL, receives the decision margin (section 4;
 *               FLT_MAX for an invalid receiver).
 * @return AO in [0, 1]; 1 for an invalid receiver.
 */
float mrgi_ssao_receiver(const mrgi_ssao_params* params, const mrgi_image* position,
  const mrgi_image* normal, int32_t x, int32_t y, float* margin);

/**
 * @brief AO of every texel of level `level` (section 3) into `out`.
 * @param position, normal Valid W x H x 4 images, rows bottom-up.
 * @param level 0..MRGI_SSAO_MAX_LEVEL.
 * @param out Receives a new ceil(W / 2^l) x ceil(H / 2^l) image of 2
 *            channels (AO, margin), rows bottom-up; zeroed on failure.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for invalid params, images of other
 *         sizes or channel counts, a level out of range;
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_ssao_compute(const mrgi_ssao_params* params, const mrgi_image* position,
  const mrgi_image* normal, int32_t level, mrgi_image* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
