/**
 * @file mrgi_mesh.h
 * @brief Triangle meshes in plain arrays: the geometry form of every stage.
 *
 * The VTK layer converts a mesh to vtkPolyData, the ground-truth renderer
 * hands the same arrays to Embree, and the CPU twins of the GPU stages read
 * them directly; so the layout is the one all three accept without copying:
 *
 * - `positions`: `3 * vertex_count` floats, x y z of each vertex in turn.
 * - `normals`: the same layout, unit length, or NULL when the mesh has none.
 * - `indices`: `3 * triangle_count` vertex numbers, three per triangle.
 *
 * Winding: a triangle's corners (a, b, c) are counter-clockwise seen from
 * the side its geometric normal `(b - a) x (c - a)` points to, which is the
 * front face (OpenGL's default `GL_CCW`, VTK's and Embree's convention).
 * Vertex normals, where present, point to the same side.
 *
 * Units are the scene's (the Cornell box is in millimetres); the mesh does
 * not care. Reflectance and emission are linear RGB.
 *
 * Ownership: a mesh made by mrgi_mesh_create() owns its arrays and is
 * released with mrgi_mesh_destroy(). Output parameters are treated as
 * uninitialized: passing a mesh that still owns arrays as an output leaks them.
 *
 * Building: count first, allocate once, then fill. A builder that knows its
 * counts (every builder in the core does) calls mrgi_mesh_create() with the
 * exact sizes and writes polygons through an ::mrgi_mesh_cursor; the cursor
 * checks capacity on every write and mrgi_mesh_cursor_finish() checks that
 * every slot was written. No realloc, no capacity fields for consumers to
 * confuse with counts.
 */
#ifndef MRGI_MESH_H
#define MRGI_MESH_H

#include "mrgi_error.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Largest accepted vertex count. Indices are uint32; the all-ones index
 * 0xFFFFFFFF is kept free because OpenGL reserves it as the primitive
 * restart index (GL 4.3 fixed-index restart).
 */
#define MRGI_MESH_MAX_VERTICES ((int64_t)UINT32_MAX)
/**
 * Largest accepted triangle count: glDrawElements() takes the index count as
 * a GLsizei (int32), so 3 * triangle_count must fit in INT32_MAX.
 */
#define MRGI_MESH_MAX_TRIANGLES ((int64_t)(INT32_MAX / 3))
/** Size of ::mrgi_mesh::name, terminating NUL included. */
#define MRGI_MESH_NAME_SIZE 64

/** An indexed triangle mesh with one diffuse material. See the file comment for layout. */
typedef struct mrgi_mesh
{
  int64_t vertex_count;   /**< 1..MRGI_MESH_MAX_VERTICES in a created mesh; 0 when empty. */
  int64_t triangle_count; /**< 1..MRGI_MESH_MAX_TRIANGLES in a created mesh; 0 when empty. */
  float* positions;       /**< 3 * vertex_count floats. */
  float* normals;         /**< 3 * vertex_count floats, unit length; may be NULL. */
  uint32_t* indices;      /**< 3 * triangle_count vertex numbers, each < vertex_count. */
  float albedo[3];        /**< Diffuse reflectance, linear RGB, each in [0, 1]. */
  float emission[3];      /**< Emitted radiance, linear RGB, >= 0; zero for non-emitters. */
  char name[MRGI_MESH_NAME_SIZE]; /**< NUL-terminated label, e.g. "floor"; may be empty. */
} mrgi_mesh;

/**
 * @brief Allocate a mesh with zero-filled arrays, albedo and emission 0.
 * @param out            Receives the mesh; zeroed on failure (destroying it is safe).
 * @param name           Label, shorter than MRGI_MESH_NAME_SIZE bytes; NULL means "".
 * @param vertex_count   1..MRGI_MESH_MAX_VERTICES.
 * @param triangle_count 1..MRGI_MESH_MAX_TRIANGLES.
 * @param with_normals   Non-zero to allocate `normals` as well.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out`, a count out of range or a
 *         name too long; ::MRGI_ERR_OUT_OF_MEMORY when an allocation fails.
 */
mrgi_status mrgi_mesh_create(mrgi_mesh* out, const char* name, int64_t vertex_count,
                             int64_t triangle_count, int with_normals, mrgi_error* err);

/** @brief Free the arrays and zero the struct. NULL-safe and idempotent. */
void mrgi_mesh_destroy(mrgi_mesh* mesh);

/**
 * @brief Check a mesh before it is used: counts in range, arrays present,
 *        every index < vertex_count, positions and normals finite, albedo in
 *        [0, 1], emission finite and >= 0, name NUL-terminated.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL; ::MRGI_ERR_FORMAT naming the
 *         first offence (e.g. "triangle 7 corner 2: index 12 >= vertex_count 8",
 *         "vertex 3: position is not finite (nan, 0, 1)").
 */
mrgi_status mrgi_mesh_validate(const mrgi_mesh* mesh, mrgi_error* err);

/**
 * @brief Axis-aligned bounds of all vertices (referenced or not).
 * @param bounds Receives xmin, xmax, ymin, ymax, zmin, zmax (VTK's order).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or an empty mesh;
 *         ::MRGI_ERR_FORMAT if a position is not finite. `bounds` is only
 *         written on success.
 */
mrgi_status mrgi_mesh_bounds(const mrgi_mesh* mesh, double bounds[6], mrgi_error* err);

/**
 * @brief Geometric quantities of one triangle, computed in double.
 * @param triangle 0..triangle_count-1.
 * @param normal   Receives the unit geometric normal (b-a)x(c-a)/|..| (the
 *                 front side, see the winding rule), or (0,0,0) for a degenerate
 *                 triangle. May be NULL.
 * @param centroid Receives (a+b+c)/3. May be NULL.
 * @param area     Receives the area (scene units squared). May be NULL.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL mesh or triangle out of range;
 *         ::MRGI_ERR_FORMAT for an index >= vertex_count.
 */
mrgi_status mrgi_mesh_triangle_geometry(const mrgi_mesh* mesh, int64_t triangle, double normal[3],
                                        double centroid[3], double* area, mrgi_error* err);

/**
 * @brief Sum of the triangle areas (scene units squared), accumulated in double.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL; ::MRGI_ERR_FORMAT for an
 *         index out of range. `area` is only written on success.
 */
mrgi_status mrgi_mesh_total_area(const mrgi_mesh* mesh, double* area, mrgi_error* err);

/**
 * @brief Smooth vertex normals: each vertex gets the normalized sum of the
 *        geometric normals of its triangles weighted by their areas (the sum
 *        of the unnormalized cross products). Allocates `normals` if NULL.
 *
 * Flat shading needs no call: give each face its own vertices (as
 * mrgi_mesh_put_polygon() does) and their normals are the face normal.
 * A vertex no triangle uses, or whose triangles cancel out, gets (0, 0, 0).
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL or an empty mesh;
 *         ::MRGI_ERR_FORMAT for an index out of range; ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_mesh_compute_vertex_normals(mrgi_mesh* mesh, mrgi_error* err);

/** Next vertex and triangle slot to write while filling a created mesh. Start at {0, 0}. */
typedef struct mrgi_mesh_cursor
{
  int64_t vertex;   /**< Next vertex slot, 0..vertex_count. */
  int64_t triangle; /**< Next triangle slot, 0..triangle_count. */
} mrgi_mesh_cursor;

/**
 * @brief Write a flat convex polygon as a triangle fan with its own vertices.
 *
 * Uses `point_count` vertex slots and `point_count - 2` triangle slots:
 * triangles (0, i, i+1). Points are counter-clockwise seen from the front.
 * If the mesh has normals, every vertex gets the polygon's Newell normal,
 * the direction of its vector area 1/2 sum_i p_i x p_(i+1): the face normal
 * of a planar polygon and a well-defined average for a slightly warped one
 * (the published Cornell left wall is warped by about 3 mm).
 * @param points      `point_count` points, x y z each.
 * @param point_count 3..MRGI_MESH_MAX_POLYGON_POINTS.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL, a count out of range, a
 *         non-finite point, a polygon of zero area, or not enough slots left.
 *         Nothing is written on failure.
 */
mrgi_status mrgi_mesh_put_polygon(mrgi_mesh* mesh, mrgi_mesh_cursor* cursor,
                                  const float (*points)[3], int32_t point_count, mrgi_error* err);

/** Largest polygon mrgi_mesh_put_polygon() accepts. */
#define MRGI_MESH_MAX_POLYGON_POINTS 64

/**
 * @brief Check that a cursor filled the mesh exactly (every slot written).
 * @return ::MRGI_ERR_INVALID_ARGUMENT naming the counts when it did not.
 */
mrgi_status mrgi_mesh_cursor_finish(const mrgi_mesh* mesh, const mrgi_mesh_cursor* cursor,
                                    mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
