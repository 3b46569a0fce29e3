/**
 * @file mrgi_grid_radii.h
 * @brief Splat radii of an organized point cloud (a depth camera's frame)
 *        from its pixel grid: each point's surfel is made large enough to
 *        cover its own grid cell, however stretched the cell is.
 *
 * Why: the radii of ::mrgi_point_normals_compute come from the distance to
 * the k-th nearest neighbour, which measures the spacing of evenly sampled
 * surfaces. A depth camera samples a surface seen at a grazing angle far
 * more finely across the view than along it (the cell's sides differ by
 * 1 / cos of the angle), and a round splat sized from the k nearest
 * neighbours then leaves gaps along the long side of the cell
 * (Documentation/PointClouds-Kinect.md).
 *
 * For every point i with a finite position at pixel (x, y) of the
 * width x height grid, its grid neighbours are the finite points at the 8
 * pixels around it that are on the same surface: their ranges (distances to
 * `origin`, the sensor) differ from point i's by at most `range_step` times
 * the smaller of the two (a larger step is a depth discontinuity: an object's
 * edge). With d the largest distance from p_i to such a neighbour,
 *
 *     radii[i] = max(radii[i], scale * d / sqrt(pi))
 *
 * A square surfel of area pi r^2 (the default of ::mrgi_surfels, corners at
 * r sqrt(pi / 2)) has an inscribed circle of radius r sqrt(pi) / 2, so with
 * scale 1 it covers the disk of radius d / 2, which holds the half of the
 * grid cell on point i's side of each neighbour (the cell's corners are at
 * most half a diagonal from p_i), whatever the square's rotation in its
 * plane; a hexagonal surfel of the same area covers more. Radii are only
 * raised, never lowered: a point with no grid neighbour keeps its radius.
 *
 * Inputs: `positions` xyz of `count` points (interleaved floats, NaN or
 * infinite allowed: such points are skipped); `pixels[i]` the row-major
 * index y * width + x of point i in the grid; a negative or out-of-range
 * index, or a pixel claimed by two points, leaves the point out of the grid
 * (its radius unchanged, counted in `unplaced`). `radii` count floats, read
 * and written; non-finite or negative radii are treated as 0.
 *
 * Errors (::MRGI_ERR_INVALID_ARGUMENT, message naming the argument; the
 * radii untouched): NULL positions, pixels or radii with count > 0; count
 * outside [0, MRGI_GRID_RADII_MAX_POINTS]; width or height < 1, or
 * width * height > MRGI_GRID_RADII_MAX_PIXELS; a non-finite origin; a
 * range_step not finite or <= 0; a scale not finite or <= 0.
 * ::MRGI_ERR_OUT_OF_MEMORY when the grid (4 bytes per pixel, the one
 * allocation) cannot be allocated.
 *
 * Cost: O(width * height + count). Single-threaded, no global state,
 * deterministic.
 */
#ifndef MRGI_GRID_RADII_H
#define MRGI_GRID_RADII_H

#include "mrgi_error.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest accepted number of points (32-bit indices in the grid). */
#define MRGI_GRID_RADII_MAX_POINTS ((int64_t)0x7FFFFFFE)
/** Largest accepted grid, in pixels (4 GiB of indices). */
#define MRGI_GRID_RADII_MAX_PIXELS ((int64_t)1 << 30)
/** The range step vtkMRGIPointCloudNormals uses: 3% of the range. */
#define MRGI_GRID_RADII_DEFAULT_RANGE_STEP 0.03

/** What happened, for messages and tests. */
typedef struct mrgi_grid_radii_stats
{
  int64_t placed;   /**< Finite points placed on the grid. */
  int64_t unplaced; /**< Finite points with a bad or duplicate pixel index. */
  int64_t raised;   /**< Points whose radius the grid raised. */
  int64_t isolated; /**< Placed points with no grid neighbour (radius kept). */
} mrgi_grid_radii_stats;

/**
 * @brief Raise each point's radius to cover its grid cell (see above).
 * @param stats Receives the counts; may be NULL. Zeroed on failure.
 * @return ::MRGI_OK, ::MRGI_ERR_INVALID_ARGUMENT or ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_grid_radii_apply(const float* positions, const int64_t* pixels, int64_t count,
  int64_t width, int64_t height, const double origin[3], double range_step, double scale,
  float* radii, mrgi_grid_radii_stats* stats, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
