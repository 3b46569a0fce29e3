/**
 * @file mrgi_point_normals.h
 * @brief Normals and splat radii of an unstructured point cloud: k nearest
 *        neighbours over a uniform grid, PCA normals, radii from the local
 *        spacing. The fallback of the PCL normals (MRGI::RenderingPCL) where
 *        PCL is absent (the ParaView build), and the reference they are
 *        compared with.
 *
 * For every finite point p:
 * - its k nearest other finite points are found exactly (Euclidean; a tie at
 *   the k-th distance keeps the first found, deterministically) over a
 *   uniform grid over the points' bounding box: first about one cell per two
 *   points; when the occupied cells hold more than 6 points on average (a
 *   surface in a volume grid), the edge is shrunk once by sqrt(occupancy /
 *   3), within 4 n + 1 cells;
 * - the normal is the eigenvector of the smallest eigenvalue of the
 *   covariance of p and its neighbours (a least-squares plane), unit length;
 * - the normal is oriented (see ::mrgi_normals_orientation): towards a
 *   viewpoint, else along an up vector, else away from the centroid of the
 *   finite points (consistent on closed, star-shaped surfaces: spheres,
 *   statues; not on open or folded ones);
 * - the radius is `radius_scale * d_k * sqrt(pi / k)`, with d_k the distance
 *   to the k-th neighbour: on a surface sampled with density rho the k
 *   nearest lie within a disk of area k / rho, so d_k * sqrt(pi / k) is the
 *   sample spacing 1 / sqrt(rho) (0.99 times the spacing on a square grid,
 *   k = 16). Disks of radius 0.71 x the spacing close a square grid, 0.58 x
 *   a hexagonal one; the default scale 1.0 also covers most gaps of
 *   irregular samples.
 *
 * Degenerate cases (all counted in ::mrgi_point_normals_stats, flagged per
 * point when `flags` is given), never NaN in the outputs:
 * - a non-finite point (NaN or infinite coordinate, e.g. the padding of an
 *   organized cloud) is skipped: no neighbour of anyone, normal = the
 *   fallback direction, radius 0, flag ::MRGI_POINT_NON_FINITE;
 * - fewer than k other finite points: all of them are used;
 * - neighbourhoods whose points are all equal (duplicates) or on a line
 *   (collinear) have no plane: the normal is the fallback direction
 *   (made perpendicular to the line when collinear), flag
 *   ::MRGI_POINT_DEGENERATE. The fallback direction is the viewpoint
 *   direction, else up, else +z;
 * - no other finite point, or the k nearest all at distance 0: radius 0,
 *   flag ::MRGI_POINT_NO_SPACING (a renderer draws such points at its
 *   minimum size).
 *
 * Cost: O(n k) for evenly spread points; the grid follows the bounding box,
 * so a dense cluster inside a large, empty box makes the search within that
 * cluster's cells quadratic. Memory: one allocation of at most 9 n + 2
 * 4-byte words per call (per point its cell, its slot and a copy of its
 * position in cell order; the cells' starts); nothing is allocated per
 * point.
 * Single-threaded, no global state, deterministic (the same input gives the
 * same output bit for bit).
 */
#ifndef MRGI_POINT_NORMALS_H
#define MRGI_POINT_NORMALS_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Default number of neighbours. */
#define MRGI_NORMALS_DEFAULT_K 16
/** Smallest and largest accepted number of neighbours. */
#define MRGI_NORMALS_MIN_K 3
#define MRGI_NORMALS_MAX_K 128
/** Largest accepted number of points (32-bit indices). */
#define MRGI_NORMALS_MAX_POINTS ((int64_t)0x3FFFFFFF)

/** Per-point flags (bit set). */
enum
{
  MRGI_POINT_NON_FINITE = 1, /**< The position has a NaN or infinite coordinate. */
  MRGI_POINT_DEGENERATE = 2, /**< The neighbourhood had no plane: fallback normal. */
  MRGI_POINT_NO_SPACING = 4  /**< No neighbour at a distance > 0: radius 0. */
};

/** How normals are oriented. */
typedef enum mrgi_normals_orientation
{
  MRGI_ORIENT_VIEWPOINT = 0, /**< dot(n, viewpoint - p) >= 0: seen from the sensor. */
  MRGI_ORIENT_UP = 1,        /**< dot(n, up) >= 0 (LAS: up = +z). */
  MRGI_ORIENT_OUTWARD = 2    /**< dot(n, p - centroid) >= 0. */
} mrgi_normals_orientation;

/** Parameters; mrgi_point_normals_default_options() fills the defaults. */
typedef struct mrgi_point_normals_options
{
  int32_t k;           /**< Neighbours, [MRGI_NORMALS_MIN_K, MRGI_NORMALS_MAX_K]; 16. */
  double radius_scale; /**< Radius factor on the spacing, finite, > 0; 1.0. */
  mrgi_normals_orientation orientation; /**< MRGI_ORIENT_OUTWARD. */
  double viewpoint[3];                  /**< For MRGI_ORIENT_VIEWPOINT; finite. */
  double up[3];                         /**< For MRGI_ORIENT_UP; finite, non-zero; (0, 0, 1). */
} mrgi_point_normals_options;

/** What happened, for messages and tests. */
typedef struct mrgi_point_normals_stats
{
  int64_t finite;     /**< Points with finite coordinates. */
  int64_t non_finite; /**< Points skipped (MRGI_POINT_NON_FINITE). */
  int64_t degenerate; /**< Points given the fallback normal (MRGI_POINT_DEGENERATE). */
  int64_t no_spacing; /**< Finite points given radius 0 (MRGI_POINT_NO_SPACING). */
  double mean_radius; /**< Mean radius of the points with a radius > 0; 0 if none. */
  int64_t grid_cells; /**< Cells of the search grid. */
} mrgi_point_normals_stats;

/** @brief Fill `options` with the defaults above; NULL is a no-op. */
void mrgi_point_normals_default_options(mrgi_point_normals_options* options);

/**
 * @brief Estimate a normal and a splat radius for every point.
 * @param positions xyz of `count` points, interleaved (any units; radii are
 *                  in the same units). Non-finite points are allowed.
 * @param count     [0, MRGI_NORMALS_MAX_POINTS]; 0 is a success with no output.
 * @param options   NULL for the defaults.
 * @param normals   3 * count floats, unit vectors; NULL to skip.
 * @param radii     count floats, >= 0; NULL to skip.
 * @param flags     count bytes of MRGI_POINT_* bits; NULL to skip.
 * @param stats     Receives the counts; may be NULL. Zeroed on failure.
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT (message naming the
 *         argument) for NULL positions with count > 0, count out of range,
 *         k out of range, a radius_scale not finite or <= 0, an unknown
 *         orientation, a non-finite viewpoint or a zero/non-finite up with
 *         their orientations; ::MRGI_ERR_OUT_OF_MEMORY. Outputs are left
 *         untouched on failure.
 */
mrgi_status mrgi_point_normals_compute(const float* positions, int64_t count,
  const mrgi_point_normals_options* options, float* normals, float* radii, uint8_t* flags,
  mrgi_point_normals_stats* stats, mrgi_error* err);

/**
 * @brief Smallest-eigenvalue eigenvector of a symmetric 3x3 matrix
 *        (row-major, only the upper triangle is read), by Jacobi rotations.
 * @param eigenvalues Receives the three eigenvalues, ascending; may be NULL.
 * @param normal      Receives the unit eigenvector of the smallest one.
 * Shared with the PCL module's tests (which compare against it).
 */
void mrgi_point_normals_smallest_eigenvector(
  const double covariance[9], double eigenvalues[3], double normal[3]);

#ifdef __cplusplus
}
#endif

#endif
