/**
 * @file mrgi_surfels.h
 * @brief Point clouds as geometry: each oriented point becomes a small flat
 *        polygon (a surfel) in its tangent plane.
 *
 * Why geometry and not point sprites: a polygon goes through every stage that
 * consumes triangles unchanged (VTK's direct light, the G-buffer capture, the
 * reflective shadow maps of every light type, the area-light voxelization,
 * the Embree ground truth; in ParaView IceT too), with no gl_PointSize limit
 * (llvmpipe caps sprites at 255 px) and no gl_FragDepth write. See
 * Documentation/PointClouds-Surfels.md for what was measured and the costs.
 *
 * Shapes (::mrgi_surfel_shape): a square (4 vertices, 2 triangles) or a
 * regular hexagon (6 vertices, 4 triangles). The polygon has the same area as
 * the disk of radius r it stands for, pi r^2, so a cloud covers the surface
 * it samples as its disks would: its vertices lie at the circumradius
 * r * mrgi_surfel_circumradius_factor(shape) from the point (sqrt(pi / 2)
 * = 1.2533 for the square, sqrt(2 pi / (3 sqrt 3)) = 1.0996 for the
 * hexagon).
 *
 * Frame: the tangent directions t1, t2 come from the branchless orthonormal
 * basis of Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT
 * 2017), exact to float rounding for every unit normal including -z; t1 x
 * t2 = n, so vertex k at angle 2 pi k / V (V = vertices per surfel) is
 * counter-clockwise seen from the side the normal points to: the front face
 * (the winding rule of mrgi_mesh.h). A triangle fan (0, k, k+1) of the V
 * vertices gives the triangles; mrgi_surfel_fan() lists them.
 *
 * Output layout, for the j-th surfel written (j = 0, 1, ... in input order of
 * the points kept): vertices j*V .. j*V+V-1; `positions` and `normals` hold
 * 3 floats per vertex; every vertex of a surfel carries the point's normal,
 * normalized (the input normal need not be unit); `source[j]`, when asked
 * for, is the index of the input point (so the caller can repeat per-point
 * data such as colours per vertex).
 *
 * Degenerate points are skipped and counted, never written and never an
 * error: a position with a non-finite coordinate, a normal that is not finite
 * or shorter than 1e-12, a radius (after the scale) that is not finite or
 * <= 0. A point with several faults counts once, under the first of
 * position, normal, radius.
 *
 * Level of detail: with `stride` k > 1 only every k-th point (index i with
 * i % k == 0) is considered and its radius is multiplied by sqrt(k), so the
 * disks of a cloud k times sparser cover the same area (the fraction of a
 * surface a cloud of independent samples leaves uncovered depends only on
 * density x r^2). A cloud far denser than the pixels it covers then costs
 * 1/k of the geometry with the same look at that distance.
 *
 * Errors (::MRGI_ERR_INVALID_ARGUMENT, nothing written): NULL input arrays
 * or outputs, a negative count or stride, an unknown shape, neither `radii` nor a
 * radius given, an output capacity smaller than the points kept need
 * (mrgi_surfels_count() says how many; the message names the capacities).
 * No allocation, no global state; safe to call on disjoint ranges from
 * several threads.
 */
#ifndef MRGI_SURFELS_H
#define MRGI_SURFELS_H

#include "mrgi_error.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The polygon each point becomes. The value is its vertex count. */
typedef enum mrgi_surfel_shape
{
  MRGI_SURFEL_SQUARE = 4, /**< 4 vertices, 2 triangles: cheapest, corners reach 1.25 r. */
  MRGI_SURFEL_HEXAGON = 6 /**< 6 vertices, 4 triangles: closer to the disk, corners at 1.10 r. */
} mrgi_surfel_shape;

/** An oriented point cloud. Arrays are read only. */
typedef struct mrgi_surfel_input
{
  int64_t count;          /**< Points, >= 0. */
  const float* positions; /**< 3 * count floats, x y z. */
  const float* normals;   /**< 3 * count floats; any length > 1e-12 (normalized here). */
  const float* radii;     /**< count disk radii, or NULL: every point has `radius`. */
  float radius;           /**< The radius of every point when `radii` is NULL. */
  float radius_scale;     /**< Multiplies every radius; 0 is read as 1. */
  int64_t
    stride; /**< Level of detail: every stride-th point, radius x sqrt(stride); 0 or 1: all. */
} mrgi_surfel_input;

/** Why points were skipped, and how many were kept. */
typedef struct mrgi_surfel_counts
{
  int64_t kept;         /**< Points that became surfels. */
  int64_t bad_position; /**< Skipped: a non-finite coordinate. */
  int64_t bad_normal;   /**< Skipped: a non-finite or (near) zero normal. */
  int64_t bad_radius;   /**< Skipped: a radius that is not finite or <= 0. */
  int64_t strided_out;  /**< Left out by the level of detail (stride); not counted as bad. */
} mrgi_surfel_counts;

/** Caller-provided outputs; capacities count floats (positions, normals) or entries. */
typedef struct mrgi_surfel_output
{
  float* positions;           /**< Receives 3 * V floats per kept point. */
  int64_t positions_capacity; /**< Floats `positions` holds. */
  float* normals;             /**< Receives 3 * V floats per kept point. */
  int64_t normals_capacity;   /**< Floats `normals` holds. */
  int64_t* source;            /**< Receives the input index of each kept point, or NULL. */
  int64_t source_capacity;    /**< Entries `source` holds (ignored when NULL). */
} mrgi_surfel_output;

/** Corner distance over r for `shape` (the polygon's area is pi r^2); 0 for an unknown shape. */
double mrgi_surfel_circumradius_factor(mrgi_surfel_shape shape);

/**
 * @brief The fan triangles of one surfel, indices local to its first vertex.
 * @param triangles Receives 3 * (V - 2) indices (6 for a square, 12 for a hexagon).
 * @return V - 2, the triangle count; 0 (nothing written) for an unknown shape or NULL.
 */
int32_t mrgi_surfel_fan(mrgi_surfel_shape shape, uint32_t* triangles);

/**
 * @brief The branchless orthonormal basis of Duff et al. (2017) for a unit
 *        normal: t1, t2 unit, orthogonal to n and to each other, t1 x t2 = n.
 */
void mrgi_surfel_basis(const float n[3], float t1[3], float t2[3]);

/**
 * @brief Classify every point as mrgi_surfels_build() will, writing nothing else.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for a NULL argument, a negative count
 *         or stride, or a NULL `radii` with `radius` <= 0 or not finite.
 */
mrgi_status mrgi_surfels_count(
  const mrgi_surfel_input* input, mrgi_surfel_counts* counts, mrgi_error* err);

/**
 * @brief Write the surfels of the points kept (see the file comment).
 * @param counts Receives the counts (also on an error about capacities).
 * @return ::MRGI_ERR_INVALID_ARGUMENT as mrgi_surfels_count(), for an
 *         unknown shape, NULL outputs, or a capacity below
 *         3 * V * kept floats (positions, normals) or kept entries (source).
 */
mrgi_status mrgi_surfels_build(const mrgi_surfel_input* input, mrgi_surfel_shape shape,
  const mrgi_surfel_output* output, mrgi_surfel_counts* counts, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
