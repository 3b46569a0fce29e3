/**
 * @file mrgi_ism_points.h
 * @brief Point sets for imperfect shadow maps (ISM): points on opaque
 *        triangles stored as (triangle, barycentrics) so they follow
 *        deforming meshes; uniform or view-adaptive density; lazy update.
 *
 * Papers: Ritschel et al. 2008, "Imperfect Shadow Maps" (RGK08, section 3:
 * points with density proportional to area, the baseline mode) and Ritschel
 * et al. 2011, "View-adaptive imperfect shadow maps" (RIHKS11, 5.1-5.3).
 * Spec: shared/plans/paper-specs.md, Packages 2 and 3.
 *
 * ## 1. Triangle weights (mrgi_ism_triangle_weights)
 * Inputs: vertex positions (xyz floats, finite), triangles (3 int32 indices
 * each, in 0..vertex_count-1). Zero-area triangles are allowed and get
 * weight 0 (they can hold no point); non-finite positions, bad indices,
 * no triangles or a mesh whose total area is 0 are errors.
 * - MRGI_ISM_UNIFORM:    w_t = A_t / sum A (pdf proportional to area, RGK08).
 * View samples come as a pool of view_count world positions (e.g. the
 * framebuffer's points; 1..MRGI_ISM_MAX_VIEW_POOL). Each triangle draws its
 * own K samples from the pool, index hash(seed, t, k) mod view_count
 * (RIHKS11 5.2: "a different randomly chosen set of view samples for each
 * triangle"); a pool of one is RIHKS11 5.1's single view sample.
 * - MRGI_ISM_ADAPTIVE_1: K = 1 view sample per triangle,
 * - MRGI_ISM_ADAPTIVE_8: K = MRGI_ISM_VIEW_SAMPLES_PER_TRIANGLE (8, RIHKS11 5.2):
 *   s_t = mean over its K samples c of the exact solid angle of the
 *   triangle seen from c (Van Oosterom-Strackee; vertex distances clamped
 *   below at MRGI_ISM_MIN_VIEW_DISTANCE), then
 *       w_t = (1 - MRGI_ISM_UNIFORM_SHARE) s_t / sum s + MRGI_ISM_UNIFORM_SHARE A_t / sum A.
 *   Why the uniform share: a triangle the view does not see (behind the
 *   samples, edge-on, far away) still casts shadows for VPLs that see it;
 *   with p = 0 it would vanish from every ISM and its occlusion would be
 *   lost for good, and the estimator that weights points by 1/p needs p > 0
 *   wherever the integrand is non-zero. The share bounds the density of any
 *   triangle below by SHARE times its uniform density.
 * Weights sum to 1.
 *
 * ## 2. CDF and stratified samples (mrgi_ism_cdf_build, mrgi_ism_sample)
 * cdf[0] = 0, cdf[i+1] = cdf[i] + w_i, cdf[n] forced to 1. Record i of P
 * draws xi = (i + r) / P with r a hash of (seed, i, generation) in [0, 1):
 * one sample per stratum of the CDF (stratified), then the first index t
 * with cdf[t] <= xi < cdf[t+1] and w_t > 0 (binary search), barycentrics
 * u = 1 - sqrt(a), v = b sqrt(a) with a, b two more hashes (uniform on the
 * triangle). Each record depends only on (seed, i, generation), so any
 * range of records can be (re)drawn alone and the result is deterministic.
 * For point clouds (section 4) the same routine picks point indices; u, v
 * are then 0.
 *
 * ## 3. Lazy update (mrgi_ism_lazy_range_n, RIHKS11 5.3)
 * With N = lazy_frames (>= 1; the paper's N = MRGI_ISM_LAZY_FRAMES = 8 is
 * mrgi_ism_lazy_range), frame k resamples exactly the records
 * [floor(j P / N), floor((j+1) P / N)) with j = k mod N, using generation
 * k / N + 1. For any P (multiple of N or not) the N ranges are disjoint,
 * cover 0..P-1 and each holds floor(P/N) or ceil(P/N) records; N = 1
 * resamples every record every frame (a fresh generation each frame).
 *
 * ## 4. Point clouds (mrgi_ism_cloud_weights)
 * A point cloud is its own point set: weights per point, w_p = 1/N for
 * MRGI_ISM_UNIFORM, else (1 - SHARE) q_p / sum q + SHARE / N with q_p the
 * mean over view samples of 1 / max(|x_p - c|, MIN)^2 (each point stands
 * for an equal surface patch). Subsample with mrgi_ism_sample().
 *
 * ## 5. Evaluation (mrgi_ism_points_evaluate)
 * Position x = (1-u-v) p0 + u p1 + v p2 and the unit geometric normal of
 * the CURRENT vertices, so points stay on a deforming surface.
 */
#ifndef MRGI_ISM_POINTS_H
#define MRGI_ISM_POINTS_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Share of the uniform (area) pdf mixed into the adaptive pdf (section 1). */
#define MRGI_ISM_UNIFORM_SHARE 0.1
/** View samples per triangle of MRGI_ISM_ADAPTIVE_8 (RIHKS11 5.2). */
#define MRGI_ISM_VIEW_SAMPLES_PER_TRIANGLE 8
/** Most view samples in a pool. */
#define MRGI_ISM_MAX_VIEW_POOL (1 << 24)
/** Lower clamp on the view distance in the solid-angle weight (scene units). */
#define MRGI_ISM_MIN_VIEW_DISTANCE 1e-3
/** Most records in one point set. */
#define MRGI_ISM_MAX_POINTS (1 << 26)
/** Frames over which the lazy update cycles (RIHKS11 5.3). */
#define MRGI_ISM_LAZY_FRAMES 8

/** Density modes. */
typedef enum mrgi_ism_mode
{
  MRGI_ISM_UNIFORM = 0,    /**< pdf proportional to area (RGK08). */
  MRGI_ISM_ADAPTIVE_1 = 1, /**< Solid angle from 1 view sample (RIHKS11 5.2). */
  MRGI_ISM_ADAPTIVE_8 = 2  /**< Mean solid angle from 8 view samples per triangle. */
} mrgi_ism_mode;

/** One point record: triangle (or cloud point) index and barycentrics. */
typedef struct mrgi_ism_point
{
  int32_t index; /**< Triangle index (meshes) or point index (clouds). */
  float u;       /**< Barycentric of vertex 1 (0 for clouds). */
  float v;       /**< Barycentric of vertex 2 (0 for clouds). */
} mrgi_ism_point;

/**
 * @brief Triangle weights (section 1). `weights` receives triangle_count doubles.
 * @param view_samples  xyz of a pool of view_count samples; NULL/0 for MRGI_ISM_UNIFORM.
 * @param seed          Picks each triangle's view samples (deterministic).
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the problem (NULL, empty mesh,
 *         bad index, non-finite vertex, total area 0, bad mode or view count).
 */
mrgi_status mrgi_ism_triangle_weights(const float* positions, int32_t vertex_count,
  const int32_t* triangles, int32_t triangle_count, mrgi_ism_mode mode, const double* view_samples,
  int32_t view_count, uint32_t seed, double* weights, mrgi_error* err);

/** @brief Point-cloud weights (section 4); `weights` receives point_count doubles. */
mrgi_status mrgi_ism_cloud_weights(const float* positions, int32_t point_count, mrgi_ism_mode mode,
  const double* view_samples, int32_t view_count, double* weights, mrgi_error* err);

/**
 * @brief CDF of weights (section 2); `cdf` receives count + 1 doubles.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for negative/non-finite weights or sum 0.
 */
mrgi_status mrgi_ism_cdf_build(const double* weights, int32_t count, double* cdf, mrgi_error* err);

/**
 * @brief Draw records [begin, end) of a set of `total` records (section 2).
 * No allocation. `points` holds `total` records; others are untouched.
 */
mrgi_status mrgi_ism_sample(const double* cdf, int32_t count, uint32_t seed, uint32_t generation,
  int32_t total, int32_t begin, int32_t end, mrgi_ism_point* points, mrgi_error* err);

/**
 * @brief Records frame `frame` resamples with a cycle of `lazy_frames` frames
 * (section 3); *begin = *end = 0 if total <= 0; lazy_frames < 1 acts as 1.
 */
void mrgi_ism_lazy_range_n(
  int32_t total, int64_t frame, int32_t lazy_frames, int32_t* begin, int32_t* end);

/** @brief Generation of frame `frame` with a cycle of `lazy_frames`: frame / N + 1. */
uint32_t mrgi_ism_lazy_generation_n(int64_t frame, int32_t lazy_frames);

/** @brief mrgi_ism_lazy_range_n with N = MRGI_ISM_LAZY_FRAMES (section 3). */
void mrgi_ism_lazy_range(int32_t total, int64_t frame, int32_t* begin, int32_t* end);

/** @brief Generation used by frame `frame`: frame / 8 + 1 (generation 0 = initial draw). */
uint32_t mrgi_ism_lazy_generation(int64_t frame);

/**
 * @brief Positions and unit normals (xyz floats each, may be NULL) of records (section 5).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, non-finite vertices, bad
 *         indices or records outside the mesh / barycentric range.
 */
mrgi_status mrgi_ism_points_evaluate(const float* positions, int32_t vertex_count,
  const int32_t* triangles, int32_t triangle_count, const mrgi_ism_point* points,
  int32_t point_count, float* out_positions, float* out_normals, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
