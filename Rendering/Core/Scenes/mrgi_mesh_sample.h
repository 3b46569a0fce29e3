/**
 * @file mrgi_mesh_sample.h
 * @brief Point clouds sampled from a triangle mesh, uniformly by area: the
 *        clouds the tests and benchmarks compare with the mesh they came from.
 *
 * Sampling: a triangle is chosen with probability proportional to its area
 * (binary search in the prefix sums of the areas, in double), then a point
 * uniformly inside it (the square-root warp of Osada et al. 2002:
 * p = (1 - sqrt(u)) a + sqrt(u) (1 - v) b + sqrt(u) v c).
 * Random numbers come from splitmix64 seeded with `seed` only: the same
 * mesh, count and seed give the same points on every machine (the arithmetic
 * is IEEE float/double, no library random generator).
 *
 * Normal: the triangle's unit geometric normal (its front side, mrgi_mesh.h's
 * winding rule), which is what VTK draws for a mesh without point normals.
 *
 * Radius: every point gets r = radius_factor * sqrt(A / (pi N)), A the
 * mesh's area, N the count. With factor 1 the disks' areas add up to A; as
 * the points are independent, the fraction of the surface no disk covers is
 * exp(-factor^2) (Poisson coverage): 37% at 1, 1.8% at 2, 0.19% at 2.5,
 * 0.012% at 3. ::MRGI_MESH_SAMPLE_RADIUS_FACTOR is the value the tests and
 * benchmarks use.
 *
 * Errors (nothing written): ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments,
 * a count outside 1..capacity, a factor that is not a positive number;
 * the mesh's own check (mrgi_mesh_validate()) fails with its status, and
 * ::MRGI_ERR_FORMAT for a mesh of zero area; ::MRGI_ERR_OUT_OF_MEMORY
 * (the area table: 8 bytes per triangle, freed before return).
 */
#ifndef MRGI_MESH_SAMPLE_H
#define MRGI_MESH_SAMPLE_H

#include "mrgi_error.h"
#include "mrgi_mesh.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Radius factor of the tests and benchmarks: 0.19% of the surface left uncovered. */
#define MRGI_MESH_SAMPLE_RADIUS_FACTOR 2.5

/** Where the samples go; arrays are the caller's. */
typedef struct mrgi_mesh_samples
{
  int64_t capacity; /**< Points each array holds (positions and normals: 3 floats per point). */
  float* positions; /**< Receives 3 * count floats. */
  float* normals;   /**< Receives 3 * count floats, unit. */
  float* radii;     /**< Receives count radii, or NULL. */
} mrgi_mesh_samples;

/**
 * @brief Sample `count` points of `mesh` (see the file comment).
 * @param count         1..out->capacity.
 * @param seed          Any value; 0 is fine.
 * @param radius_factor > 0, finite.
 * @param radius        Receives the radius every point got; may be NULL.
 */
mrgi_status mrgi_mesh_sample(const mrgi_mesh* mesh, int64_t count, uint64_t seed,
  double radius_factor, const mrgi_mesh_samples* out, double* radius, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
