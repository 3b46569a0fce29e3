#include "mrgi_mesh.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- small vector helpers (double, so float inputs lose nothing) ---- */

static void mrgi_mesh_load_vertex(const mrgi_mesh* mesh, uint32_t index, double p[3])
{
  const float* src = mesh->positions + 3 * (size_t)index;
  p[0] = src[0];
  p[1] = src[1];
  p[2] = src[2];
}

static void mrgi_mesh_cross(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static double mrgi_mesh_length(const double v[3])
{
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* Unnormalized normal (b-a)x(c-a) of a triangle whose indices are known valid;
 * its length is twice the area. */
static void mrgi_mesh_triangle_cross(const mrgi_mesh* mesh, int64_t triangle, double out[3])
{
  const uint32_t* tri = mesh->indices + 3 * (size_t)triangle;
  double a[3], b[3], c[3];
  mrgi_mesh_load_vertex(mesh, tri[0], a);
  mrgi_mesh_load_vertex(mesh, tri[1], b);
  mrgi_mesh_load_vertex(mesh, tri[2], c);
  const double ab[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double ac[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  mrgi_mesh_cross(ab, ac, out);
}

static const char* mrgi_mesh_label(const mrgi_mesh* mesh)
{
  /* The name may be unterminated in a corrupt mesh; never read past it. */
  return memchr(mesh->name, '\0', sizeof(mesh->name)) ? mesh->name : "?";
}

/* Reports the first index >= vertex_count. Shared by every function that
 * walks triangles so none of them reads outside `positions`. */
static mrgi_status mrgi_mesh_check_indices(const mrgi_mesh* mesh, const char* caller,
                                           mrgi_error* err)
{
  const int64_t index_count = 3 * mesh->triangle_count;
  for (int64_t i = 0; i < index_count; ++i)
  {
    if ((int64_t)mesh->indices[i] >= mesh->vertex_count)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
                            "%s: mesh '%s': triangle %" PRId64 " corner %d: index %" PRIu32
                            " >= vertex_count %" PRId64,
                            caller, mrgi_mesh_label(mesh), i / 3, (int)(i % 3), mesh->indices[i],
                            mesh->vertex_count);
    }
  }
  return MRGI_OK;
}

/* Counts in range and arrays present: the precondition of every walk. */
static mrgi_status mrgi_mesh_check_shape(const mrgi_mesh* mesh, const char* caller,
                                         mrgi_error* err)
{
  if (!mesh)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: mesh is NULL", caller);
  }
  if (mesh->vertex_count < 1 || mesh->vertex_count > MRGI_MESH_MAX_VERTICES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: mesh '%s': vertex_count %" PRId64 " is outside 1..%" PRId64,
                          caller, mrgi_mesh_label(mesh), mesh->vertex_count,
                          MRGI_MESH_MAX_VERTICES);
  }
  if (mesh->triangle_count < 1 || mesh->triangle_count > MRGI_MESH_MAX_TRIANGLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: mesh '%s': triangle_count %" PRId64 " is outside 1..%" PRId64,
                          caller, mrgi_mesh_label(mesh), mesh->triangle_count,
                          MRGI_MESH_MAX_TRIANGLES);
  }
  if (!mesh->positions || !mesh->indices)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: mesh '%s': %s is NULL", caller,
                          mrgi_mesh_label(mesh), mesh->positions ? "indices" : "positions");
  }
  return MRGI_OK;
}

/* ---- lifetime ---- */

mrgi_status mrgi_mesh_create(mrgi_mesh* out, const char* name, int64_t vertex_count,
                             int64_t triangle_count, int with_normals, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_mesh_create: out is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (!name)
  {
    name = "";
  }
  const size_t name_length = strlen(name);
  if (name_length >= MRGI_MESH_NAME_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_mesh_create: name of %zu bytes is longer than %d", name_length,
                          MRGI_MESH_NAME_SIZE - 1);
  }
  if (vertex_count < 1 || vertex_count > MRGI_MESH_MAX_VERTICES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_mesh_create: mesh '%s': vertex_count %" PRId64
                          " is outside 1..%" PRId64,
                          name, vertex_count, MRGI_MESH_MAX_VERTICES);
  }
  if (triangle_count < 1 || triangle_count > MRGI_MESH_MAX_TRIANGLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_mesh_create: mesh '%s': triangle_count %" PRId64
                          " is outside 1..%" PRId64,
                          name, triangle_count, MRGI_MESH_MAX_TRIANGLES);
  }
  /* On a 32-bit size_t the largest vertex array does not fit; refuse before
   * the multiplication wraps. */
  const uint64_t vertex_floats = 3 * (uint64_t)vertex_count;
  const uint64_t index_values = 3 * (uint64_t)triangle_count;
  if (vertex_floats > SIZE_MAX / sizeof(float) || index_values > SIZE_MAX / sizeof(uint32_t))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_mesh_create: mesh '%s': %" PRId64 " vertices and %" PRId64
                          " triangles exceed this platform's address space",
                          name, vertex_count, triangle_count);
  }

  memcpy(out->name, name, name_length + 1);
  out->positions = calloc((size_t)vertex_floats, sizeof(float));
  out->indices = calloc((size_t)index_values, sizeof(uint32_t));
  if (with_normals)
  {
    out->normals = calloc((size_t)vertex_floats, sizeof(float));
  }
  if (!out->positions || !out->indices || (with_normals && !out->normals))
  {
    mrgi_mesh_destroy(out);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "mrgi_mesh_create: mesh '%s': cannot allocate %" PRId64
                          " vertices and %" PRId64 " triangles",
                          name, vertex_count, triangle_count);
  }
  out->vertex_count = vertex_count;
  out->triangle_count = triangle_count;
  return MRGI_OK;
}

void mrgi_mesh_destroy(mrgi_mesh* mesh)
{
  if (!mesh)
  {
    return;
  }
  free(mesh->positions);
  free(mesh->normals);
  free(mesh->indices);
  memset(mesh, 0, sizeof(*mesh));
}

/* ---- checks and measures ---- */

static int mrgi_mesh_finite3(const float v[3])
{
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

mrgi_status mrgi_mesh_validate(const mrgi_mesh* mesh, mrgi_error* err)
{
  static const char* caller = "mrgi_mesh_validate";
  mrgi_status status = mrgi_mesh_check_shape(mesh, caller, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!memchr(mesh->name, '\0', sizeof(mesh->name)))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: mesh name is not NUL-terminated", caller);
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!(mesh->albedo[c] >= 0.0f && mesh->albedo[c] <= 1.0f))
    {
      /* An albedo above 1 reflects more light than arrives and makes the
       * indirect bounce gain energy. */
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: mesh '%s': albedo[%d] = %g is outside [0, 1]",
                            caller, mrgi_mesh_label(mesh), c, (double)mesh->albedo[c]);
    }
    if (!(mesh->emission[c] >= 0.0f && isfinite(mesh->emission[c])))
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
                            "%s: mesh '%s': emission[%d] = %g is not finite and >= 0", caller,
                            mrgi_mesh_label(mesh), c, (double)mesh->emission[c]);
    }
  }
  status = mrgi_mesh_check_indices(mesh, caller, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  for (int64_t v = 0; v < mesh->vertex_count; ++v)
  {
    const float* p = mesh->positions + 3 * v;
    if (!mrgi_mesh_finite3(p))
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
                            "%s: mesh '%s': vertex %" PRId64 ": position is not finite (%g, %g, %g)",
                            caller, mrgi_mesh_label(mesh), v, (double)p[0], (double)p[1], (double)p[2]);
    }
  }
  if (mesh->normals)
  {
    for (int64_t v = 0; v < mesh->vertex_count; ++v)
    {
      const float* n = mesh->normals + 3 * v;
      if (!mrgi_mesh_finite3(n))
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
                              "%s: mesh '%s': vertex %" PRId64 ": normal is not finite (%g, %g, %g)",
                              caller, mrgi_mesh_label(mesh), v, (double)n[0], (double)n[1], (double)n[2]);
      }
    }
  }
  return MRGI_OK;
}

mrgi_status mrgi_mesh_bounds(const mrgi_mesh* mesh, double bounds[6], mrgi_error* err)
{
  static const char* caller = "mrgi_mesh_bounds";
  if (!bounds)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: bounds is NULL", caller);
  }
  const mrgi_status status = mrgi_mesh_check_shape(mesh, caller, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  double result[6] = { INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY };
  for (int64_t v = 0; v < mesh->vertex_count; ++v)
  {
    const float* p = mesh->positions + 3 * v;
    if (!mrgi_mesh_finite3(p))
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
                            "%s: mesh '%s': vertex %" PRId64 ": position is not finite", caller,
                            mrgi_mesh_label(mesh), v);
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      const double x = p[axis];
      result[2 * axis] = x < result[2 * axis] ? x : result[2 * axis];
      result[2 * axis + 1] = x > result[2 * axis + 1] ? x : result[2 * axis + 1];
    }
  }
  memcpy(bounds, result, sizeof(result));
  return MRGI_OK;
}

mrgi_status mrgi_mesh_triangle_geometry(const mrgi_mesh* mesh, int64_t triangle, double normal[3],
                                        double centroid[3], double* area, mrgi_error* err)
{
  static const char* caller = "mrgi_mesh_triangle_geometry";
  const mrgi_status status = mrgi_mesh_check_shape(mesh, caller, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (triangle < 0 || triangle >= mesh->triangle_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: mesh '%s': triangle %" PRId64 " is outside 0..%" PRId64, caller,
                          mrgi_mesh_label(mesh), triangle, mesh->triangle_count - 1);
  }
  const uint32_t* tri = mesh->indices + 3 * triangle;
  for (int corner = 0; corner < 3; ++corner)
  {
    if ((int64_t)tri[corner] >= mesh->vertex_count)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
                            "%s: mesh '%s': triangle %" PRId64 " corner %d: index %" PRIu32
                            " >= vertex_count %" PRId64,
                            caller, mrgi_mesh_label(mesh), triangle, corner, tri[corner], mesh->vertex_count);
    }
  }
  double cross[3];
  mrgi_mesh_triangle_cross(mesh, triangle, cross);
  const double length = mrgi_mesh_length(cross);
  if (normal)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      normal[axis] = length > 0.0 ? cross[axis] / length : 0.0;
    }
  }
  if (centroid)
  {
    double a[3], b[3], c[3];
    mrgi_mesh_load_vertex(mesh, tri[0], a);
    mrgi_mesh_load_vertex(mesh, tri[1], b);
    mrgi_mesh_load_vertex(mesh, tri[2], c);
    for (int axis = 0; axis < 3; ++axis)
    {
      centroid[axis] = (a[axis] + b[axis] + c[axis]) / 3.0;
    }
  }
  if (area)
  {
    *area = 0.5 * length;
  }
  return MRGI_OK;
}

mrgi_status mrgi_mesh_total_area(const mrgi_mesh* mesh, double* area, mrgi_error* err)
{
  static const char* caller = "mrgi_mesh_total_area";
  if (!area)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: area is NULL", caller);
  }
  mrgi_status status = mrgi_mesh_check_shape(mesh, caller, err);
  if (status == MRGI_OK)
  {
    status = mrgi_mesh_check_indices(mesh, caller, err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  double sum = 0.0;
  for (int64_t t = 0; t < mesh->triangle_count; ++t)
  {
    double cross[3];
    mrgi_mesh_triangle_cross(mesh, t, cross);
    sum += 0.5 * mrgi_mesh_length(cross);
  }
  *area = sum;
  return MRGI_OK;
}

mrgi_status mrgi_mesh_compute_vertex_normals(mrgi_mesh* mesh, mrgi_error* err)
{
  static const char* caller = "mrgi_mesh_compute_vertex_normals";
  mrgi_status status = mrgi_mesh_check_shape(mesh, caller, err);
  if (status == MRGI_OK)
  {
    status = mrgi_mesh_check_indices(mesh, caller, err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  /* Accumulate in double: a vertex shared by thousands of small triangles
   * would lose their contributions in float. */
  double* sums = calloc(3 * (size_t)mesh->vertex_count, sizeof(double));
  float* normals = mesh->normals ? mesh->normals
                                 : calloc(3 * (size_t)mesh->vertex_count, sizeof(float));
  if (!sums || !normals)
  {
    free(sums);
    if (normals != mesh->normals)
    {
      free(normals);
    }
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "%s: mesh '%s': cannot allocate normals for %" PRId64 " vertices",
                          caller, mrgi_mesh_label(mesh), mesh->vertex_count);
  }
  for (int64_t t = 0; t < mesh->triangle_count; ++t)
  {
    double cross[3];
    mrgi_mesh_triangle_cross(mesh, t, cross);
    for (int corner = 0; corner < 3; ++corner)
    {
      double* sum = sums + 3 * (size_t)mesh->indices[3 * t + corner];
      sum[0] += cross[0];
      sum[1] += cross[1];
      sum[2] += cross[2];
    }
  }
  for (int64_t v = 0; v < mesh->vertex_count; ++v)
  {
    const double* sum = sums + 3 * v;
    const double length = mrgi_mesh_length(sum);
    for (int axis = 0; axis < 3; ++axis)
    {
      normals[3 * v + axis] = length > 0.0 ? (float)(sum[axis] / length) : 0.0f;
    }
  }
  free(sums);
  mesh->normals = normals;
  return MRGI_OK;
}

/* ---- filling ---- */

mrgi_status mrgi_mesh_put_polygon(mrgi_mesh* mesh, mrgi_mesh_cursor* cursor,
                                  const float (*points)[3], int32_t point_count, mrgi_error* err)
{
  static const char* caller = "mrgi_mesh_put_polygon";
  const mrgi_status status = mrgi_mesh_check_shape(mesh, caller, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!cursor || !points)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: mesh '%s': %s is NULL", caller,
                          mrgi_mesh_label(mesh), cursor ? "points" : "cursor");
  }
  if (point_count < 3 || point_count > MRGI_MESH_MAX_POLYGON_POINTS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: mesh '%s': point_count %d is outside 3..%d", caller, mrgi_mesh_label(mesh),
                          (int)point_count, MRGI_MESH_MAX_POLYGON_POINTS);
  }
  const int64_t triangles = point_count - 2;
  if (cursor->vertex < 0 || cursor->triangle < 0 ||
      cursor->vertex > mesh->vertex_count - point_count ||
      cursor->triangle > mesh->triangle_count - triangles)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: mesh '%s': a %d-gon at vertex %" PRId64 ", triangle %" PRId64
                          " does not fit in %" PRId64 " vertices, %" PRId64 " triangles",
                          caller, mrgi_mesh_label(mesh), (int)point_count, cursor->vertex, cursor->triangle,
                          mesh->vertex_count, mesh->triangle_count);
  }
  /* Newell's method: the vector area 1/2 sum p_i x p_(i+1). */
  double newell[3] = { 0.0, 0.0, 0.0 };
  for (int32_t i = 0; i < point_count; ++i)
  {
    if (!mrgi_mesh_finite3(points[i]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "%s: mesh '%s': point %d is not finite", caller, mrgi_mesh_label(mesh), (int)i);
    }
    const float* p = points[i];
    const float* q = points[(i + 1) % point_count];
    const double pd[3] = { p[0], p[1], p[2] };
    const double qd[3] = { q[0], q[1], q[2] };
    double cross[3];
    mrgi_mesh_cross(pd, qd, cross);
    newell[0] += cross[0];
    newell[1] += cross[1];
    newell[2] += cross[2];
  }
  const double length = mrgi_mesh_length(newell);
  if (!(length > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: mesh '%s': polygon has zero area",
                          caller, mrgi_mesh_label(mesh));
  }

  const int64_t first = cursor->vertex;
  for (int32_t i = 0; i < point_count; ++i)
  {
    memcpy(mesh->positions + 3 * (first + i), points[i], 3 * sizeof(float));
    if (mesh->normals)
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        mesh->normals[3 * (first + i) + axis] = (float)(newell[axis] / length);
      }
    }
  }
  for (int64_t t = 0; t < triangles; ++t)
  {
    uint32_t* tri = mesh->indices + 3 * (cursor->triangle + t);
    tri[0] = (uint32_t)first;
    tri[1] = (uint32_t)(first + t + 1);
    tri[2] = (uint32_t)(first + t + 2);
  }
  cursor->vertex += point_count;
  cursor->triangle += triangles;
  return MRGI_OK;
}

mrgi_status mrgi_mesh_cursor_finish(const mrgi_mesh* mesh, const mrgi_mesh_cursor* cursor,
                                    mrgi_error* err)
{
  if (!mesh || !cursor)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_mesh_cursor_finish: %s is NULL",
                          mesh ? "cursor" : "mesh");
  }
  if (cursor->vertex != mesh->vertex_count || cursor->triangle != mesh->triangle_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_mesh_cursor_finish: mesh '%s': filled %" PRId64 " of %" PRId64
                          " vertices and %" PRId64 " of %" PRId64 " triangles",
                          mrgi_mesh_label(mesh), cursor->vertex, mesh->vertex_count,
                          cursor->triangle, mesh->triangle_count);
  }
  return MRGI_OK;
}
