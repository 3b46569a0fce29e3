/**
 * @file mrgi_scene_scaling.h
 * @brief A deterministic benchmark scene: N objects, any triangle count.
 *
 * Purpose: measure how each stage's cost grows with the triangle count while
 * everything a screen-space method sees stays fixed. So the object layout,
 * shapes, sizes and colours depend ONLY on (object_count, seed); the
 * triangle count only changes how finely each object is tessellated. The
 * same seed and object count give the same silhouettes, hence the same
 * screen coverage, whatever triangle_count is: coarse polygons are scaled
 * to the perimeter of their circles (see mrgi_scene_scaling.c), so an
 * object's projected area stays close to the exact shape's. Measured over
 * 20 seeds against 1000x finer tessellations, the summed projected area
 * differs by at most 7 % at 24 triangles per object, 4 % at 60, 2 % at 150;
 * single coarse tori by up to 20 %.
 *
 * Layout (units: metres, y up): objects sit on a ground plane y = 0 in a
 * grid of 1 m cells, ceil(sqrt(N)) columns, centred on the origin. Each
 * object is a UV sphere (radius 0.25..0.38 m) or a torus (major radius
 * 0.18..0.26 m, tube 30..45 % of that, tilted 0..90 degrees about x),
 * jittered by up to 4 cm inside its cell, resting on the ground (coarse
 * tessellations, being scaled up, may dip into it by a few centimetres),
 * never reaching into a neighbour's cell. Albedo from a fixed palette of 8 colours. The
 * ground extends one cell beyond the grid, albedo 0.5 grey.
 *
 * Meshes: [0] "ground", then one per object, "sphere_0000" / "torus_0001" ...
 * (number = object index, row-major over the grid from -x/-z). Objects have
 * shared vertices and exact analytic unit normals; the ground is flat.
 *
 * Triangle count: exactly `triangle_count`. Objects share the budget
 * (minus the ground's 2) with error diffusion (each takes at most its share of
 * what is left; what the last leaves over goes to the ground, as a strip of
 * extra quads, and, if odd, one fan of three triangles at its +x edge).
 *
 * Camera: looks at (0, 0.3, 0) from 35 degrees above the horizon, from -z,
 * vertical view angle 30 degrees, far enough that the bounding sphere of
 * all objects fits the view. Lights: [0] a spot light (cone half-angle 45,
 * exponent 1, intensity 1, white) above the origin aimed straight down, high
 * enough that the whole ground is inside the cone; [1] a directional light
 * (intensity 0.5, white) from direction (-1, 2, -0.5) (towards the origin).
 *
 * Determinism: random choices come from a splitmix64 generator seeded with
 * `seed` (no global state, no rand()); angles come from an in-file sine and
 * cosine built from + - * / only, because libm's sin/cos are not correctly
 * rounded and differ between C libraries. On IEEE-754 platforms evaluating
 * double in double (FLT_EVAL_METHOD 0, e.g. x86-64 SSE2 and ARM64) and
 * without fused multiply-add contraction (off in ISO C mode), the same
 * arguments give byte-identical mesh arrays everywhere.
 */
#ifndef MRGI_SCENE_SCALING_H
#define MRGI_SCENE_SCALING_H

#include "mrgi_error.h"
#include "mrgi_scene.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest accepted object count. */
#define MRGI_SCALING_MAX_OBJECTS 4096
/** Largest accepted triangle count (all meshes together). */
#define MRGI_SCALING_MAX_TRIANGLES 20000000
/**
 * Fewest triangles an object gets: a 4-slice, 4-stack sphere or a 4 x 3
 * torus. Below that the shapes stop resembling their silhouettes.
 */
#define MRGI_SCALING_MIN_TRIANGLES_PER_OBJECT 24
/** Triangles of the ground plane at least (one quad). */
#define MRGI_SCALING_GROUND_TRIANGLES 2

/**
 * @brief Smallest triangle_count mrgi_scene_scaling() accepts for `object_count`
 *        objects: 24 per object plus 2 for the ground; -1 if object_count is
 *        outside 1..MRGI_SCALING_MAX_OBJECTS.
 */
int64_t mrgi_scene_scaling_min_triangles(int64_t object_count);

/**
 * @brief Build the scaling scene (see the file comment).
 * @param object_count   1..MRGI_SCALING_MAX_OBJECTS.
 * @param triangle_count mrgi_scene_scaling_min_triangles(object_count)..MRGI_SCALING_MAX_TRIANGLES;
 *                       the scene has exactly this many triangles.
 * @param seed           Any value; chooses shapes, sizes, jitter and colours.
 * @param out            Receives the scene; zeroed on failure. Release with mrgi_scene_destroy().
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out` or a count out of range
 *         (the message gives the accepted range); ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_scene_scaling(int64_t object_count, int64_t triangle_count, uint64_t seed,
                               mrgi_scene* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
