/* Tests of mrgi_surfels: the basis, vertices on the tangent plane at the
 * documented distance, the polygon's area (pi r^2), winding, unit normals,
 * degenerate points skipped and counted, capacities and bad arguments. */
#include "mrgi_surfels.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static double dot3(const float* a, const float* b)
{
  return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

static double length3(const float* a)
{
  return sqrt(dot3(a, a));
}

/* Normals over the sphere, the poles and the -z singularity of the naive basis. */
static void fill_normals(float* normals, int count)
{
  uint64_t state = 12345;
  for (int i = 0; i < count; ++i)
  {
    float* n = normals + 3 * i;
    if (i < 6)
    {
      n[0] = n[1] = n[2] = 0.0f;
      n[i / 2] = (i % 2) ? -1.0f : 1.0f;
      continue;
    }
    if (i == 6)
    {
      /* Nearly -z: where Frisvad's 2012 basis loses precision. */
      n[0] = 1e-4f;
      n[1] = 2e-4f;
      n[2] = -1.0f;
      continue;
    }
    double v[3];
    for (int c = 0; c < 3; ++c)
    {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      v[c] = (double)(state >> 11) / 9007199254740992.0 * 2.0 - 1.0;
    }
    /* Not unit on purpose: the builder normalizes. */
    for (int c = 0; c < 3; ++c)
    {
      n[c] = (float)(v[c] * 3.0);
    }
  }
}

static void test_basis_orthonormal(void)
{
  enum
  {
    N = 200
  };
  float normals[3 * N];
  fill_normals(normals, N);
  for (int i = 0; i < N; ++i)
  {
    float n[3], t1[3], t2[3];
    const double len = length3(normals + 3 * i);
    for (int c = 0; c < 3; ++c)
    {
      n[c] = (float)(normals[3 * i + c] / len);
    }
    mrgi_surfel_basis(n, t1, t2);
    MRGI_CHECK_NEAR(length3(t1), 1.0, 1e-5);
    MRGI_CHECK_NEAR(length3(t2), 1.0, 1e-5);
    MRGI_CHECK_NEAR(dot3(t1, t2), 0.0, 1e-5);
    MRGI_CHECK_NEAR(dot3(t1, n), 0.0, 1e-5);
    MRGI_CHECK_NEAR(dot3(t2, n), 0.0, 1e-5);
    /* Right-handed: t1 x t2 = n, so the corners wind counter-clockwise around n. */
    const float cross[3] = { t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2],
      t1[0] * t2[1] - t1[1] * t2[0] };
    MRGI_CHECK_NEAR(dot3(cross, n), 1.0, 1e-5);
  }
}

static void check_shape(mrgi_surfel_shape shape)
{
  enum
  {
    N = 64
  };
  float positions[3 * N], normals[3 * N], radii[N];
  fill_normals(normals, N);
  for (int i = 0; i < N; ++i)
  {
    positions[3 * i] = (float)i;
    positions[3 * i + 1] = -2.5f * (float)i;
    positions[3 * i + 2] = 100.0f + 0.25f * (float)i;
    radii[i] = 0.01f + 0.05f * (float)i;
  }
  const int V = (int)shape;
  float* out_p = malloc(sizeof(float) * 3 * (size_t)V * N);
  float* out_n = malloc(sizeof(float) * 3 * (size_t)V * N);
  int64_t source[N];
  MRGI_CHECK(out_p && out_n);
  const mrgi_surfel_input input = { N, positions, normals, radii, 0.0f, 2.0f, 0 };
  const mrgi_surfel_output output = { out_p, 3 * V * N, out_n, 3 * V * N, source, N };
  mrgi_surfel_counts counts;
  mrgi_error err;
  MRGI_CHECK(mrgi_surfels_build(&input, shape, &output, &counts, &err) == MRGI_OK);
  MRGI_CHECK(counts.kept == N);
  MRGI_CHECK(counts.bad_position == 0 && counts.bad_normal == 0 && counts.bad_radius == 0);

  uint32_t fan[12];
  const int32_t triangles = mrgi_surfel_fan(shape, fan);
  MRGI_CHECK(triangles == V - 2);
  const double factor = mrgi_surfel_circumradius_factor(shape);
  for (int i = 0; i < N; ++i)
  {
    MRGI_CHECK(source[i] == i);
    const float* p = positions + 3 * i;
    const double len = length3(normals + 3 * i);
    float n[3];
    for (int c = 0; c < 3; ++c)
    {
      n[c] = (float)(normals[3 * i + c] / len);
    }
    const double r = 2.0 * radii[i];
    const double tolerance = 1e-5 * (1.0 + length3(p));
    double area_vector[3] = { 0, 0, 0 };
    for (int k = 0; k < V; ++k)
    {
      const float* q = out_p + 3 * (V * i + k);
      const float* m = out_n + 3 * (V * i + k);
      const float d[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
      /* On the tangent plane, at the circumradius. */
      MRGI_CHECK_NEAR(dot3(d, n), 0.0, tolerance);
      MRGI_CHECK_NEAR(length3(d), factor * r, tolerance);
      /* The point's normal, unit. */
      MRGI_CHECK_NEAR(length3(m), 1.0, 1e-6);
      MRGI_CHECK_NEAR(dot3(m, n), 1.0, 1e-6);
    }
    /* The fan's vector area: magnitude pi r^2, direction +n (front face). */
    for (int t = 0; t < triangles; ++t)
    {
      const float* a = out_p + 3 * (V * i + (int)fan[3 * t]);
      const float* b = out_p + 3 * (V * i + (int)fan[3 * t + 1]);
      const float* c = out_p + 3 * (V * i + (int)fan[3 * t + 2]);
      const double u[3] = { (double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2] };
      const double v[3] = { (double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2] };
      area_vector[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
      area_vector[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
      area_vector[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
    }
    const double area_along_n =
      area_vector[0] * n[0] + area_vector[1] * n[1] + area_vector[2] * n[2];
    MRGI_CHECK_NEAR(area_along_n / (PI * r * r), 1.0, 1e-3 + 1e-4 * length3(p) / r);
  }
  free(out_p);
  free(out_n);
}

static void test_square(void)
{
  check_shape(MRGI_SURFEL_SQUARE);
}

static void test_hexagon(void)
{
  check_shape(MRGI_SURFEL_HEXAGON);
}

static void test_factors(void)
{
  /* Square: side r sqrt(pi), half-diagonal r sqrt(pi / 2). */
  MRGI_CHECK_NEAR(mrgi_surfel_circumradius_factor(MRGI_SURFEL_SQUARE), sqrt(PI / 2.0), 1e-12);
  MRGI_CHECK_NEAR(
    1.5 * sqrt(3.0) * pow(mrgi_surfel_circumradius_factor(MRGI_SURFEL_HEXAGON), 2), PI, 1e-12);
  MRGI_CHECK(mrgi_surfel_circumradius_factor((mrgi_surfel_shape)5) == 0.0);
  uint32_t fan[12];
  MRGI_CHECK(mrgi_surfel_fan((mrgi_surfel_shape)3, fan) == 0);
  MRGI_CHECK(mrgi_surfel_fan(MRGI_SURFEL_SQUARE, NULL) == 0);
}

static void test_degenerate_points_counted(void)
{
  const float inf = INFINITY, nan = NAN;
  /* 0 good, 1 nan position, 2 inf normal, 3 zero normal, 4 zero radius,
   * 5 negative radius, 6 nan radius, 7 nan position and zero normal (counted once, as position),
   * 8 good, 9 tiny normal (1e-20: below 1e-12). */
  const float positions[] = { 0, 0, 0, nan, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5, 5, 5, 0,
    inf, 0, 7, 7, 7, 8, 8, 8 };
  const float normals[] = { 0, 0, 1, 0, 0, 1, 0, inf, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1, 0, 0, 0,
    0, 0, 0, -2, 1e-20f, 0, 0 };
  const float radii[] = { 1, 1, 1, 1, 0, -1, nan, 1, 0.5f, 1 };
  const mrgi_surfel_input input = { 10, positions, normals, radii, 0.0f, 0.0f, 1 };
  mrgi_surfel_counts counts;
  mrgi_error err;
  MRGI_CHECK(mrgi_surfels_count(&input, &counts, &err) == MRGI_OK);
  MRGI_CHECK(counts.kept == 2);
  MRGI_CHECK(counts.bad_position == 2);
  MRGI_CHECK(counts.bad_normal == 3);
  MRGI_CHECK(counts.bad_radius == 3);

  float out_p[3 * 4 * 2], out_n[3 * 4 * 2];
  int64_t source[2];
  const mrgi_surfel_output output = { out_p, 24, out_n, 24, source, 2 };
  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_SQUARE, &output, &counts, &err) == MRGI_OK);
  MRGI_CHECK(counts.kept == 2 && source[0] == 0 && source[1] == 8);
  for (int i = 0; i < 24; ++i)
  {
    MRGI_CHECK(isfinite(out_p[i]) && isfinite(out_n[i]));
  }
  /* The second surfel's normal is -z normalized, radius 0.5. */
  MRGI_CHECK(out_n[12 + 2] == -1.0f);
  MRGI_CHECK_NEAR(out_p[14], 7.0, 1e-6);

  /* An all-bad cloud is no error: zero surfels. */
  const mrgi_surfel_input bad = { 1, positions + 3, normals + 3, radii + 3, 0.0f, 0.0f, 0 };
  MRGI_CHECK(mrgi_surfels_build(&bad, MRGI_SURFEL_SQUARE, &output, &counts, &err) == MRGI_OK);
  MRGI_CHECK(counts.kept == 0 && counts.bad_position == 1);
}

static void test_bad_arguments(void)
{
  const float positions[] = { 0, 0, 0, 1, 0, 0 };
  const float normals[] = { 0, 0, 1, 0, 0, 1 };
  float out_p[36], out_n[36];
  int64_t source[2];
  mrgi_surfel_counts counts;
  mrgi_error err;
  mrgi_surfel_input input = { 2, positions, normals, NULL, 0.5f, 1.0f, 0 };
  mrgi_surfel_output output = { out_p, 36, out_n, 36, source, 2 };

  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_HEXAGON, &output, &counts, &err) == MRGI_OK);
  MRGI_CHECK(counts.kept == 2);

  /* One radius for all: too small a capacity names the needs and what it got. */
  output.positions_capacity = 35;
  memset(out_p, 0, sizeof(out_p));
  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_HEXAGON, &output, &counts, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "need 36 floats") != NULL);
  MRGI_CHECK(out_p[0] == 0.0f);
  output.positions_capacity = 36;
  output.source_capacity = 1;
  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_HEXAGON, &output, &counts, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  output.source_capacity = 2;

  MRGI_CHECK(mrgi_surfels_build(&input, (mrgi_surfel_shape)5, &output, &counts, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "shape") != NULL);
  MRGI_CHECK(mrgi_surfels_build(NULL, MRGI_SURFEL_SQUARE, &output, &counts, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_SQUARE, NULL, &counts, NULL) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_SQUARE, &output, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);

  input.radius = 0.0f;
  MRGI_CHECK(mrgi_surfels_count(&input, &counts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "radius") != NULL);
  input.radius = 0.5f;
  input.radius_scale = -1.0f;
  MRGI_CHECK(mrgi_surfels_count(&input, &counts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  input.radius_scale = 1.0f;
  input.normals = NULL;
  MRGI_CHECK(mrgi_surfels_count(&input, &counts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "normals") != NULL);
  input.normals = normals;
  input.stride = -2;
  MRGI_CHECK(mrgi_surfels_count(&input, &counts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "stride") != NULL);
  input.stride = 0;
  input.count = -1;
  MRGI_CHECK(mrgi_surfels_count(&input, &counts, &err) == MRGI_ERR_INVALID_ARGUMENT);
  input.count = 0;
  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_SQUARE, &output, &counts, &err) == MRGI_OK);
  MRGI_CHECK(counts.kept == 0);
}

/* Every k-th point, radius x sqrt(k): the disks' total area stays the same. */
static void test_stride(void)
{
  enum
  {
    N = 10
  };
  float positions[3 * N], normals[3 * N];
  for (int i = 0; i < N; ++i)
  {
    positions[3 * i] = (float)i;
    positions[3 * i + 1] = positions[3 * i + 2] = 0.0f;
    normals[3 * i] = normals[3 * i + 1] = 0.0f;
    normals[3 * i + 2] = 1.0f;
  }
  /* Point 3 is bad, but stride 3 keeps 0, 3, 6, 9: it is counted bad, not strided out. */
  positions[9] = NAN;
  const mrgi_surfel_input input = { N, positions, normals, NULL, 1.0f, 0.0f, 3 };
  float out_p[3 * 4 * N], out_n[3 * 4 * N];
  int64_t source[N];
  const mrgi_surfel_output output = { out_p, 3 * 4 * N, out_n, 3 * 4 * N, source, N };
  mrgi_surfel_counts counts;
  mrgi_error err;
  MRGI_CHECK(mrgi_surfels_build(&input, MRGI_SURFEL_SQUARE, &output, &counts, &err) == MRGI_OK);
  MRGI_CHECK(counts.kept == 3 && counts.bad_position == 1 && counts.strided_out == 6);
  MRGI_CHECK(source[0] == 0 && source[1] == 6 && source[2] == 9);
  const double expected = sqrt(3.0) * mrgi_surfel_circumradius_factor(MRGI_SURFEL_SQUARE);
  for (int j = 0; j < 3; ++j)
  {
    for (int k = 0; k < 4; ++k)
    {
      const float* q = out_p + 3 * (4 * j + k);
      const float d[3] = { q[0] - (float)source[j], q[1], q[2] };
      MRGI_CHECK_NEAR(length3(d), expected, 1e-5);
    }
  }
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_basis_orthonormal),
    MRGI_TEST_CASE(test_square), MRGI_TEST_CASE(test_hexagon), MRGI_TEST_CASE(test_factors),
    MRGI_TEST_CASE(test_degenerate_points_counted), MRGI_TEST_CASE(test_bad_arguments),
    MRGI_TEST_CASE(test_stride) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
