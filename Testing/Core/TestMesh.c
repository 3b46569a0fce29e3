/* Tests of mrgi_mesh: creation limits, filling through a cursor, validation
 * of bad indices and non-finite data, bounds, areas and normals. */
#include "mrgi_mesh.h"
#include "mrgi_test.h"

#include <stdint.h>
#include <string.h>

static int is_zeroed(const mrgi_mesh* mesh)
{
  static const mrgi_mesh zero;
  return memcmp(mesh, &zero, sizeof(zero)) == 0;
}

static int message_has(const mrgi_error* err, const char* text)
{
  if (!strstr(err->message, text))
  {
    fprintf(stderr, "message '%s' lacks '%s'\n", err->message, text);
    return 0;
  }
  return 1;
}

/* A unit square in z = 0, counter-clockwise seen from +z. */
static const float unit_square[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };

static void make_square(mrgi_mesh* mesh, int with_normals)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_mesh_create(mesh, "square", 4, 2, with_normals, &err) == MRGI_OK);
  mrgi_mesh_cursor cursor = { 0, 0 };
  MRGI_CHECK(mrgi_mesh_put_polygon(mesh, &cursor, unit_square, 4, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_mesh_cursor_finish(mesh, &cursor, &err) == MRGI_OK);
}

static void test_create_rejects_bad_sizes(void)
{
  mrgi_error err;
  mrgi_mesh mesh;
  MRGI_CHECK(mrgi_mesh_create(NULL, "x", 3, 1, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_create(NULL, "x", 3, 1, 0, NULL) == MRGI_ERR_INVALID_ARGUMENT);

  const int64_t bad_vertices[] = { 0, -1, INT64_MIN, MRGI_MESH_MAX_VERTICES + 1, INT64_MAX };
  for (size_t i = 0; i < sizeof(bad_vertices) / sizeof(bad_vertices[0]); ++i)
  {
    memset(&mesh, 0xAB, sizeof(mesh));
    MRGI_CHECK(mrgi_mesh_create(&mesh, "bad", bad_vertices[i], 1, 1, &err) ==
               MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(err.status == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(message_has(&err, "vertex_count"));
    MRGI_CHECK(is_zeroed(&mesh));
  }
  const int64_t bad_triangles[] = { 0, -5, MRGI_MESH_MAX_TRIANGLES + 1, INT64_MAX };
  for (size_t i = 0; i < sizeof(bad_triangles) / sizeof(bad_triangles[0]); ++i)
  {
    MRGI_CHECK(mrgi_mesh_create(&mesh, "bad", 3, bad_triangles[i], 0, &err) ==
               MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(message_has(&err, "triangle_count"));
    MRGI_CHECK(is_zeroed(&mesh));
  }
  char long_name[MRGI_MESH_NAME_SIZE + 1];
  memset(long_name, 'n', sizeof(long_name) - 1);
  long_name[sizeof(long_name) - 1] = '\0';
  MRGI_CHECK(mrgi_mesh_create(&mesh, long_name, 3, 1, 0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "name"));

}

static void test_create_and_destroy(void)
{
  mrgi_error err;
  mrgi_mesh mesh;
  MRGI_CHECK(mrgi_mesh_create(&mesh, NULL, 3, 1, 0, &err) == MRGI_OK);
  MRGI_CHECK(mesh.name[0] == '\0');
  MRGI_CHECK(mesh.vertex_count == 3 && mesh.triangle_count == 1);
  MRGI_CHECK(mesh.positions && mesh.indices && !mesh.normals);
  MRGI_CHECK(mesh.albedo[0] == 0.0f && mesh.emission[2] == 0.0f);
  /* Zero-filled arrays: a degenerate but index-valid mesh. */
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_OK);
  mrgi_mesh_destroy(&mesh);
  MRGI_CHECK(is_zeroed(&mesh));
  mrgi_mesh_destroy(&mesh); /* idempotent */
  mrgi_mesh_destroy(NULL);  /* NULL-safe */
}

static void test_put_polygon(void)
{
  mrgi_error err;
  mrgi_mesh mesh;
  make_square(&mesh, 1);
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_OK);
  static const uint32_t expected_indices[6] = { 0, 1, 2, 0, 2, 3 };
  MRGI_CHECK(memcmp(mesh.indices, expected_indices, sizeof(expected_indices)) == 0);
  for (int v = 0; v < 4; ++v)
  {
    MRGI_CHECK_NEAR(mesh.normals[3 * v + 0], 0.0, 0.0);
    MRGI_CHECK_NEAR(mesh.normals[3 * v + 1], 0.0, 0.0);
    MRGI_CHECK_NEAR(mesh.normals[3 * v + 2], 1.0, 0.0);
  }
  for (int64_t t = 0; t < mesh.triangle_count; ++t)
  {
    double normal[3], centroid[3], area;
    MRGI_CHECK(mrgi_mesh_triangle_geometry(&mesh, t, normal, centroid, &area, &err) == MRGI_OK);
    MRGI_CHECK_NEAR(normal[2], 1.0, 1e-12);
    MRGI_CHECK_NEAR(area, 0.5, 1e-12);
  }

  /* Full: another polygon does not fit, and nothing is written. */
  mrgi_mesh_cursor full = { 4, 2 };
  const float other[3][3] = { { 5, 5, 5 }, { 6, 5, 5 }, { 5, 6, 5 } };
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &full, other, 3, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "does not fit"));
  MRGI_CHECK(full.vertex == 4 && full.triangle == 2);

  /* Bad polygons. */
  mrgi_mesh_cursor start = { 0, 0 };
  const float degenerate[3][3] = { { 0, 0, 0 }, { 1, 1, 1 }, { 2, 2, 2 } };
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &start, degenerate, 3, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "zero area"));
  const float not_finite[3][3] = { { 0, 0, 0 }, { NAN, 0, 0 }, { 0, 1, 0 } };
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &start, not_finite, 3, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "point 1"));
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &start, unit_square, 2, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &start, NULL, 3, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, NULL, unit_square, 4, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  mrgi_mesh_cursor negative = { -1, 0 };
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &negative, unit_square, 4, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(start.vertex == 0 && start.triangle == 0);

  /* A cursor that stopped early is caught. */
  MRGI_CHECK(mrgi_mesh_cursor_finish(&mesh, &start, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "filled 0 of 4"));
  mrgi_mesh_destroy(&mesh);

  /* Putting into an empty (never created) mesh fails cleanly. */
  mrgi_mesh empty;
  memset(&empty, 0, sizeof(empty));
  MRGI_CHECK(mrgi_mesh_put_polygon(&empty, &start, unit_square, 4, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
}

static void test_warped_quad_gets_newell_normal(void)
{
  /* Lift one corner: the Newell normal is the normalized sum of the two
   * triangles' cross products (the quad's vector area). */
  const float warped[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0.2f }, { 0, 1, 0 } };
  mrgi_error err;
  mrgi_mesh mesh;
  MRGI_CHECK(mrgi_mesh_create(&mesh, "warped", 4, 2, 1, &err) == MRGI_OK);
  mrgi_mesh_cursor cursor = { 0, 0 };
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &cursor, warped, 4, &err) == MRGI_OK);
  double sum[3] = { 0, 0, 0 };
  for (int64_t t = 0; t < 2; ++t)
  {
    double normal[3], area;
    MRGI_CHECK(mrgi_mesh_triangle_geometry(&mesh, t, normal, NULL, &area, &err) == MRGI_OK);
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += 2.0 * area * normal[a];
    }
  }
  const double length = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
  for (int v = 0; v < 4; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      MRGI_CHECK_NEAR(mesh.normals[3 * v + a], sum[a] / length, 1e-6);
    }
  }
  mrgi_mesh_destroy(&mesh);
}

static void test_validate_catches_bad_data(void)
{
  mrgi_error err;
  mrgi_mesh mesh;
  make_square(&mesh, 1);

  mesh.indices[5] = 4; /* triangle 1, corner 2: one past the last vertex */
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "triangle 1 corner 2"));
  MRGI_CHECK(message_has(&err, "index 4 >= vertex_count 4"));
  /* Every walker refuses the bad index instead of reading past the array. */
  double area = -1.0, bounds[6];
  MRGI_CHECK(mrgi_mesh_total_area(&mesh, &area, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(area == -1.0);
  MRGI_CHECK(mrgi_mesh_triangle_geometry(&mesh, 1, NULL, NULL, &area, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(mrgi_mesh_compute_vertex_normals(&mesh, &err) == MRGI_ERR_FORMAT);
  mesh.indices[5] = UINT32_MAX;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  mesh.indices[5] = 3;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_OK);

  mesh.positions[3 * 2 + 1] = NAN;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "vertex 2: position is not finite"));
  MRGI_CHECK(mrgi_mesh_bounds(&mesh, bounds, &err) == MRGI_ERR_FORMAT);
  mesh.positions[3 * 2 + 1] = INFINITY;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  mesh.positions[3 * 2 + 1] = 1.0f;

  mesh.normals[3 * 3] = NAN;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "vertex 3: normal is not finite"));
  mesh.normals[3 * 3] = 0.0f;

  mesh.albedo[1] = 1.5f;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "albedo[1]"));
  mesh.albedo[1] = NAN;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  mesh.albedo[1] = 0.5f;
  mesh.emission[0] = -1.0f;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "emission[0]"));
  mesh.emission[0] = 0.0f;

  memset(mesh.name, 'x', sizeof(mesh.name)); /* unterminated */
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "NUL"));
  strcpy(mesh.name, "square");
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_OK);

  /* Corrupt counts and missing arrays. */
  mesh.vertex_count = -4;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "vertex_count -4"));
  mesh.vertex_count = 4;
  uint32_t* indices = mesh.indices;
  mesh.indices = NULL;
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "indices is NULL"));
  mesh.indices = indices;
  MRGI_CHECK(mrgi_mesh_validate(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_validate(NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_mesh_destroy(&mesh);

  /* A destroyed (empty) mesh is not valid. */
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_bounds(&mesh, bounds, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

static void test_bounds_and_area(void)
{
  /* Two squares: the unit square and one scaled by 2 and moved to z = -3,
   * x 10..12; plus an unused vertex, which bounds include. */
  mrgi_error err;
  mrgi_mesh mesh;
  MRGI_CHECK(mrgi_mesh_create(&mesh, "two", 9, 4, 0, &err) == MRGI_OK);
  mrgi_mesh_cursor cursor = { 0, 0 };
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &cursor, unit_square, 4, &err) == MRGI_OK);
  const float big[4][3] = { { 10, 0, -3 }, { 12, 0, -3 }, { 12, 2, -3 }, { 10, 2, -3 } };
  MRGI_CHECK(mrgi_mesh_put_polygon(&mesh, &cursor, big, 4, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_mesh_cursor_finish(&mesh, &cursor, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mesh.positions[3 * 8 + 1] = -7.0f; /* the unused ninth vertex */

  double bounds[6];
  MRGI_CHECK(mrgi_mesh_bounds(&mesh, bounds, &err) == MRGI_OK);
  const double expected[6] = { 0, 12, -7, 2, -3, 0 };
  for (int i = 0; i < 6; ++i)
  {
    MRGI_CHECK_NEAR(bounds[i], expected[i], 0.0);
  }
  double area = 0.0;
  MRGI_CHECK(mrgi_mesh_total_area(&mesh, &area, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(area, 5.0, 1e-12);
  MRGI_CHECK(mrgi_mesh_total_area(&mesh, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_bounds(&mesh, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_triangle_geometry(&mesh, 4, NULL, NULL, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_triangle_geometry(&mesh, -1, NULL, NULL, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  double centroid[3];
  MRGI_CHECK(mrgi_mesh_triangle_geometry(&mesh, 2, NULL, centroid, NULL, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(centroid[0], (10.0 + 12.0 + 12.0) / 3.0, 1e-12);
  MRGI_CHECK_NEAR(centroid[2], -3.0, 1e-12);
  mrgi_mesh_destroy(&mesh);
}

static void test_vertex_normals(void)
{
  /* A roof: two faces meeting at a ridge along x, sharing its two vertices.
   * Faces point (0, 1, -1)/sqrt2 and (0, 1, 1)/sqrt2; ridge vertices get +y. */
  mrgi_error err;
  mrgi_mesh mesh;
  MRGI_CHECK(mrgi_mesh_create(&mesh, "roof", 6, 4, 0, &err) == MRGI_OK);
  const float positions[6][3] = { { 0, 0, -1 }, { 1, 0, -1 }, { 0, 1, 0 },
                                   { 1, 1, 0 },  { 0, 0, 1 },  { 1, 0, 1 } };
  const uint32_t indices[4][3] = { { 0, 2, 1 }, { 1, 2, 3 }, { 2, 4, 5 }, { 2, 5, 3 } };
  memcpy(mesh.positions, positions, sizeof(positions));
  memcpy(mesh.indices, indices, sizeof(indices));
  MRGI_CHECK(mrgi_mesh_compute_vertex_normals(&mesh, &err) == MRGI_OK);
  MRGI_CHECK(mesh.normals != NULL);
  const double h = sqrt(0.5);
  MRGI_CHECK_NEAR(mesh.normals[3 * 0 + 1], h, 1e-6);
  MRGI_CHECK_NEAR(mesh.normals[3 * 0 + 2], -h, 1e-6);
  MRGI_CHECK_NEAR(mesh.normals[3 * 5 + 2], h, 1e-6);
  for (int v = 2; v <= 3; ++v)
  {
    MRGI_CHECK_NEAR(mesh.normals[3 * v + 0], 0.0, 1e-6);
    MRGI_CHECK_NEAR(mesh.normals[3 * v + 1], 1.0, 1e-6);
    MRGI_CHECK_NEAR(mesh.normals[3 * v + 2], 0.0, 1e-6);
  }
  /* Recomputing into the existing array gives the same result. */
  float first[18];
  memcpy(first, mesh.normals, sizeof(first));
  MRGI_CHECK(mrgi_mesh_compute_vertex_normals(&mesh, &err) == MRGI_OK);
  MRGI_CHECK(memcmp(first, mesh.normals, sizeof(first)) == 0);
  MRGI_CHECK(mrgi_mesh_validate(&mesh, &err) == MRGI_OK);
  mrgi_mesh_destroy(&mesh);

  /* Flat quad built without normals: computed ones equal the face normal
   * at every vertex. */
  make_square(&mesh, 0);
  MRGI_CHECK(mrgi_mesh_compute_vertex_normals(&mesh, &err) == MRGI_OK);
  for (int v = 0; v < 4; ++v)
  {
    MRGI_CHECK_NEAR(mesh.normals[3 * v + 2], 1.0, 1e-7);
  }
  mrgi_mesh_destroy(&mesh);
  MRGI_CHECK(mrgi_mesh_compute_vertex_normals(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_create_rejects_bad_sizes),
    MRGI_TEST_CASE(test_create_and_destroy),
    MRGI_TEST_CASE(test_put_polygon),
    MRGI_TEST_CASE(test_warped_quad_gets_newell_normal),
    MRGI_TEST_CASE(test_validate_catches_bad_data),
    MRGI_TEST_CASE(test_bounds_and_area),
    MRGI_TEST_CASE(test_vertex_normals),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
