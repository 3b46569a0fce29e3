/* Tests of mrgi_mesh_sample: points on the mesh, in proportion to area
 * (between triangles and inside one), the triangles' normals, the radius
 * formula, determinism, and rejection of bad arguments. */
#include "mrgi_mesh_sample.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* A unit square in z = 0 (area 1, normal +z) and a triangle in x = 5
 * (legs 2 and 3: area 3, normal +x). */
static void make_mesh(mrgi_mesh* mesh)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_mesh_create(mesh, "two", 7, 3, 0, &err) == MRGI_OK);
  mrgi_mesh_cursor cursor = { 0, 0 };
  static const float square[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  static const float triangle[3][3] = { { 5, 0, 0 }, { 5, 2, 0 }, { 5, 0, 3 } };
  MRGI_CHECK(mrgi_mesh_put_polygon(mesh, &cursor, square, 4, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_mesh_put_polygon(mesh, &cursor, triangle, 3, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_mesh_cursor_finish(mesh, &cursor, &err) == MRGI_OK);
}

enum
{
  N = 200000
};

static void test_area_proportional(void)
{
  mrgi_mesh mesh;
  make_mesh(&mesh);
  float* positions = malloc(sizeof(float) * 3 * N);
  float* normals = malloc(sizeof(float) * 3 * N);
  float* radii = malloc(sizeof(float) * N);
  MRGI_CHECK(positions && normals && radii);
  const mrgi_mesh_samples out = { N, positions, normals, radii };
  double radius = 0.0;
  mrgi_error err;
  MRGI_CHECK(mrgi_mesh_sample(&mesh, N, 7, 2.0, &out, &radius, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(radius, 2.0 * sqrt(4.0 / (PI * N)), 1e-12);

  int64_t on_square = 0, left_half = 0, low_triangle = 0;
  for (int64_t i = 0; i < N; ++i)
  {
    const float* p = positions + 3 * i;
    const float* n = normals + 3 * i;
    MRGI_CHECK(radii[i] == (float)radius);
    if (p[2] == 0.0f && p[0] <= 1.0f)
    {
      ++on_square;
      MRGI_CHECK(p[0] >= 0.0f && p[1] >= 0.0f && p[1] <= 1.0f);
      MRGI_CHECK(n[0] == 0.0f && n[1] == 0.0f && n[2] == 1.0f);
      left_half += p[0] < 0.5f;
    }
    else
    {
      /* Inside the triangle y/2 + z/3 <= 1 in the plane x = 5. */
      MRGI_CHECK(p[0] == 5.0f && p[1] >= 0.0f && p[2] >= 0.0f);
      MRGI_CHECK(p[1] / 2.0f + p[2] / 3.0f <= 1.0f + 1e-6f);
      MRGI_CHECK(n[0] == 1.0f && n[1] == 0.0f && n[2] == 0.0f);
      /* z < 1.5 cuts the triangle into 3/4 and 1/4 of its area. */
      low_triangle += p[2] < 1.5f;
    }
  }
  /* Binomial counts, checked to 5 standard deviations. */
  const double sigma_square = sqrt(N * 0.25 * 0.75);
  MRGI_CHECK_NEAR((double)on_square, 0.25 * N, 5.0 * sigma_square);
  const double sigma_left = sqrt(on_square * 0.25);
  MRGI_CHECK_NEAR((double)left_half, 0.5 * on_square, 5.0 * sigma_left);
  const int64_t on_triangle = N - on_square;
  const double sigma_low = sqrt(on_triangle * 0.75 * 0.25);
  MRGI_CHECK_NEAR((double)low_triangle, 0.75 * on_triangle, 5.0 * sigma_low);
  free(positions);
  free(normals);
  free(radii);
  mrgi_mesh_destroy(&mesh);
}

static void test_deterministic(void)
{
  mrgi_mesh mesh;
  make_mesh(&mesh);
  enum
  {
    M = 1000
  };
  float a[3 * M], b[3 * M], c[3 * M], n[3 * M];
  mrgi_mesh_samples out = { M, a, n, NULL };
  mrgi_error err;
  MRGI_CHECK(mrgi_mesh_sample(&mesh, M, 42, 1.0, &out, NULL, &err) == MRGI_OK);
  out.positions = b;
  MRGI_CHECK(mrgi_mesh_sample(&mesh, M, 42, 1.0, &out, NULL, &err) == MRGI_OK);
  MRGI_CHECK(memcmp(a, b, sizeof(a)) == 0);
  out.positions = c;
  MRGI_CHECK(mrgi_mesh_sample(&mesh, M, 43, 1.0, &out, NULL, &err) == MRGI_OK);
  MRGI_CHECK(memcmp(a, c, sizeof(a)) != 0);
  mrgi_mesh_destroy(&mesh);
}

static void test_bad_arguments(void)
{
  mrgi_mesh mesh;
  make_mesh(&mesh);
  float p[30], n[30];
  mrgi_mesh_samples out = { 10, p, n, NULL };
  mrgi_error err;
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 0, 1, 1.0, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "count") != NULL);
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 11, 1, 1.0, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 10, 1, 0.0, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 10, 1, NAN, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_sample(NULL, 10, 1, 1.0, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 10, 1, 1.0, NULL, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  out.normals = NULL;
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 10, 1, 1.0, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  out.normals = n;
  /* A non-finite vertex fails the mesh's own check, named. */
  mesh.positions[0] = NAN;
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 10, 1, 1.0, &out, NULL, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "mrgi_mesh_sample") != NULL);
  /* A mesh of zero area: nothing to sample. */
  for (int64_t i = 0; i < 3 * mesh.vertex_count; ++i)
  {
    mesh.positions[i] = 1.0f;
  }
  MRGI_CHECK(mrgi_mesh_sample(&mesh, 10, 1, 1.0, &out, NULL, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "area") != NULL);
  mrgi_mesh_destroy(&mesh);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_area_proportional),
    MRGI_TEST_CASE(test_deterministic), MRGI_TEST_CASE(test_bad_arguments) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
