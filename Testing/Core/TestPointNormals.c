/* mrgi_point_normals: planes (grid and jittered, tilted) and a sphere give
 * normals within a few degrees of the truth, oriented as asked (viewpoint,
 * up, outward), radii close to the sample spacing; the grid's k nearest
 * equal a brute-force search (uniform, clustered with an outlier);
 * NaN points, one point, duplicates and lines get the documented fallbacks
 * and flags, never NaN; bad arguments are refused with a message. */
#include "mrgi_point_normals.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* A deterministic generator (xorshift), uniform in [0, 1). */
static double rnd(uint64_t* s)
{
  *s ^= *s << 13;
  *s ^= *s >> 7;
  *s ^= *s << 17;
  return (double)(*s >> 11) / 9007199254740992.0;
}

static double angle_deg(const float* n, const double* t)
{
  double d = n[0] * t[0] + n[1] * t[1] + n[2] * t[2];
  d = d > 1.0 ? 1.0 : d < -1.0 ? -1.0 : d;
  return acos(d) * 180.0 / PI;
}

static int unit_and_finite(const float* n)
{
  const double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
  return isfinite(n[0]) && isfinite(n[1]) && isfinite(n[2]) && fabs(l - 1.0) < 1e-5;
}

/* A side x side grid with `spacing` in the plane through `centre` with unit
 * normal `nrm` (two tangents built from it), optionally jittered. */
static float* make_plane(int side, double spacing, const double centre[3], const double nrm[3],
  double jitter, uint64_t seed)
{
  double t1[3] = { -nrm[1], nrm[0], 0.0 };
  double l = sqrt(t1[0] * t1[0] + t1[1] * t1[1]);
  if (l < 1e-6)
  {
    t1[0] = 1.0;
    t1[1] = 0.0;
    l = 1.0;
  }
  t1[0] /= l;
  t1[1] /= l;
  const double t2[3] = { nrm[1] * t1[2] - nrm[2] * t1[1], nrm[2] * t1[0] - nrm[0] * t1[2],
    nrm[0] * t1[1] - nrm[1] * t1[0] };
  float* p = (float*)malloc(sizeof(float) * 3 * (size_t)side * (size_t)side);
  MRGI_CHECK(p != NULL);
  uint64_t s = seed;
  for (int j = 0; j < side; ++j)
  {
    for (int i = 0; i < side; ++i)
    {
      const double u = (i - side / 2 + jitter * (rnd(&s) - 0.5)) * spacing;
      const double v = (j - side / 2 + jitter * (rnd(&s) - 0.5)) * spacing;
      for (int a = 0; a < 3; ++a)
      {
        p[3 * (j * side + i) + a] = (float)(centre[a] + u * t1[a] + v * t2[a]);
      }
    }
  }
  return p;
}

typedef struct outputs
{
  float* normals;
  float* radii;
  uint8_t* flags;
  mrgi_point_normals_stats stats;
} outputs;

static outputs run(const float* p, int64_t n, const mrgi_point_normals_options* o)
{
  outputs r;
  r.normals = (float*)malloc(sizeof(float) * 3 * (size_t)(n > 0 ? n : 1));
  r.radii = (float*)malloc(sizeof(float) * (size_t)(n > 0 ? n : 1));
  r.flags = (uint8_t*)malloc((size_t)(n > 0 ? n : 1));
  MRGI_CHECK(r.normals && r.radii && r.flags);
  mrgi_error err;
  const mrgi_status st =
    mrgi_point_normals_compute(p, n, o, r.normals, r.radii, r.flags, &r.stats, &err);
  if (st != MRGI_OK)
  {
    MRGI_FAIL("mrgi_point_normals_compute: %s", err.message);
  }
  for (int64_t i = 0; i < n; ++i)
  {
    MRGI_CHECK(unit_and_finite(r.normals + 3 * i));
    MRGI_CHECK(isfinite(r.radii[i]) && r.radii[i] >= 0.0f);
  }
  return r;
}

static void release(outputs* r)
{
  free(r->normals);
  free(r->radii);
  free(r->flags);
}

/* A tilted grid plane: normals within 0.5 degrees, towards the viewpoint on
 * either side, interior radii within 5% of the spacing. */
static void test_plane_grid(void)
{
  const int side = 100;
  const double spacing = 0.01, centre[3] = { 1.0, -2.0, 0.5 };
  double nrm[3] = { 0.3, -0.2, 0.9 };
  const double l = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
  for (int a = 0; a < 3; ++a)
  {
    nrm[a] /= l;
  }
  float* p = make_plane(side, spacing, centre, nrm, 0.0, 1);
  for (int flip = 0; flip < 2; ++flip)
  {
    mrgi_point_normals_options o;
    mrgi_point_normals_default_options(&o);
    o.orientation = MRGI_ORIENT_VIEWPOINT;
    const double sign = flip ? -1.0 : 1.0;
    for (int a = 0; a < 3; ++a)
    {
      o.viewpoint[a] = centre[a] + sign * 5.0 * nrm[a];
    }
    outputs r = run(p, side * side, &o);
    const double truth[3] = { sign * nrm[0], sign * nrm[1], sign * nrm[2] };
    double worst = 0.0;
    for (int i = 0; i < side * side; ++i)
    {
      const double e = angle_deg(r.normals + 3 * i, truth);
      worst = e > worst ? e : worst;
    }
    MRGI_CHECK(worst < 0.5);
    for (int j = 3; j < side - 3; ++j)
    {
      for (int i = 3; i < side - 3; ++i)
      {
        MRGI_CHECK_NEAR(r.radii[j * side + i], spacing, 0.05 * spacing);
      }
    }
    MRGI_CHECK(r.stats.finite == side * side && r.stats.degenerate == 0 && r.stats.non_finite == 0);
    release(&r);
  }
  free(p);
}

/* A jittered plane (each point moved up to +-0.4 spacing): normals within
 * 3 degrees, mean radius within 15% of the spacing; up orientation both ways. */
static void test_plane_jittered_up(void)
{
  const int side = 120;
  const double spacing = 0.5, centre[3] = { 0, 0, 3 }, nrm[3] = { 0, 0, 1 };
  float* p = make_plane(side, spacing, centre, nrm, 0.8, 7);
  for (int flip = 0; flip < 2; ++flip)
  {
    mrgi_point_normals_options o;
    mrgi_point_normals_default_options(&o);
    o.orientation = MRGI_ORIENT_UP;
    o.up[2] = flip ? -2.0 : 2.0;
    outputs r = run(p, side * side, &o);
    const double truth[3] = { 0, 0, flip ? -1.0 : 1.0 };
    for (int i = 0; i < side * side; ++i)
    {
      MRGI_CHECK(angle_deg(r.normals + 3 * i, truth) < 3.0);
    }
    MRGI_CHECK_NEAR(r.stats.mean_radius, spacing, 0.15 * spacing);
    release(&r);
  }
  free(p);
}

/* A Fibonacci sphere of 20000 points: normals radial within 2 degrees
 * (mean under 0.5), outward by default, inward seen from the centre; radii
 * within 15% of sqrt(area / n). */
static void test_sphere(void)
{
  const int n = 20000;
  const double R = 2.5, c[3] = { 10.0, 20.0, -5.0 };
  float* p = (float*)malloc(sizeof(float) * 3 * n);
  double* truth = (double*)malloc(sizeof(double) * 3 * n);
  MRGI_CHECK(p && truth);
  const double golden = PI * (3.0 - sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = sqrt(1.0 - z * z), phi = golden * i;
    truth[3 * i + 0] = r * cos(phi);
    truth[3 * i + 1] = r * sin(phi);
    truth[3 * i + 2] = z;
    for (int a = 0; a < 3; ++a)
    {
      p[3 * i + a] = (float)(c[a] + R * truth[3 * i + a]);
    }
  }
  const double spacing = sqrt(4.0 * PI * R * R / n);
  for (int inward = 0; inward < 2; ++inward)
  {
    mrgi_point_normals_options o;
    mrgi_point_normals_default_options(&o);
    if (inward)
    {
      o.orientation = MRGI_ORIENT_VIEWPOINT;
      memcpy(o.viewpoint, c, sizeof(c));
    }
    outputs r = run(p, n, &o);
    double worst = 0.0, sum = 0.0;
    for (int i = 0; i < n; ++i)
    {
      double t[3];
      for (int a = 0; a < 3; ++a)
      {
        t[a] = inward ? -truth[3 * i + a] : truth[3 * i + a];
      }
      const double e = angle_deg(r.normals + 3 * i, t);
      worst = e > worst ? e : worst;
      sum += e;
      MRGI_CHECK_NEAR(r.radii[i], spacing, 0.15 * spacing);
    }
    printf("sphere: worst %.3f deg, mean %.4f deg, mean radius %.5f (spacing %.5f)\n", worst,
      sum / n, r.stats.mean_radius, spacing);
    MRGI_CHECK(worst < 2.0);
    MRGI_CHECK(sum / n < 0.5);
    release(&r);
  }
  free(truth);
  free(p);
}

/* Brute-force k-th neighbour distance of point i. */
static double brute_kth(const float* p, int n, int i, int k)
{
  double best[MRGI_NORMALS_MAX_K];
  int found = 0;
  for (int j = 0; j < n; ++j)
  {
    if (j == i || !isfinite(p[3 * j]) || !isfinite(p[3 * j + 1]) || !isfinite(p[3 * j + 2]))
    {
      continue;
    }
    const double dx = (double)p[3 * j] - p[3 * i], dy = (double)p[3 * j + 1] - p[3 * i + 1],
                 dz = (double)p[3 * j + 2] - p[3 * i + 2];
    const double d = dx * dx + dy * dy + dz * dz;
    if (found == k && d >= best[k - 1])
    {
      continue;
    }
    int at = found < k ? found++ : k - 1;
    while (at > 0 && best[at - 1] > d)
    {
      best[at] = best[at - 1];
      --at;
    }
    best[at] = d;
  }
  return found ? sqrt(best[found - 1]) : 0.0;
}

/* The grid search is exact: the radii are those of a brute-force kNN, for a
 * uniform cube, and for a dense cluster plus far outliers (a skewed grid). */
static void test_knn_exact(void)
{
  const int n = 3000;
  float* p = (float*)malloc(sizeof(float) * 3 * n);
  MRGI_CHECK(p != NULL);
  for (int layout = 0; layout < 2; ++layout)
  {
    uint64_t s = 99 + (uint64_t)layout;
    for (int i = 0; i < n; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        p[3 * i + a] = (float)(layout == 0 ? rnd(&s) : 0.01 * rnd(&s));
      }
    }
    if (layout == 1)
    {
      p[0] = 100.0f;
      p[4] = -50.0f;
      p[3 * 7 + 2] = NAN;
    }
    for (int k = 3; k <= 40; k += 37)
    {
      mrgi_point_normals_options o;
      mrgi_point_normals_default_options(&o);
      o.k = k;
      outputs r = run(p, n, &o);
      for (int i = 0; i < n; ++i)
      {
        if (r.flags[i] & MRGI_POINT_NON_FINITE)
        {
          MRGI_CHECK(r.radii[i] == 0.0f);
          continue;
        }
        const double expect = brute_kth(p, n, i, k) * sqrt(PI / k);
        MRGI_CHECK_NEAR(r.radii[i], expect, 1e-5 * expect + 1e-12);
      }
      release(&r);
    }
  }
  free(p);
}

/* An organized cloud with NaN padding: the NaNs are flagged, normal +z,
 * radius 0, counted; the rest is as without them. */
static void test_nan_points(void)
{
  const int side = 40;
  const double centre[3] = { 0, 0, 0 }, nrm[3] = { 0, 0, 1 };
  float* p = make_plane(side, 0.1, centre, nrm, 0.0, 3);
  int nans = 0;
  for (int i = 0; i < side * side; i += 3)
  {
    p[3 * i + (i / 3) % 3] = (i % 2) ? NAN : INFINITY;
    ++nans;
  }
  mrgi_point_normals_options o;
  mrgi_point_normals_default_options(&o);
  o.orientation = MRGI_ORIENT_VIEWPOINT;
  o.viewpoint[2] = 10.0;
  outputs r = run(p, side * side, &o);
  MRGI_CHECK(r.stats.non_finite == nans);
  MRGI_CHECK(r.stats.finite == side * side - nans);
  const double up[3] = { 0, 0, 1 };
  for (int i = 0; i < side * side; ++i)
  {
    if (i % 3 == 0)
    {
      MRGI_CHECK(r.flags[i] & MRGI_POINT_NON_FINITE);
      MRGI_CHECK(r.radii[i] == 0.0f);
    }
    else
    {
      MRGI_CHECK(r.flags[i] == 0);
      MRGI_CHECK(angle_deg(r.normals + 3 * i, up) < 0.5);
      MRGI_CHECK(r.radii[i] > 0.05f && r.radii[i] < 0.3f);
    }
  }
  release(&r);
  /* Every point NaN: all flagged, no crash. */
  for (int i = 0; i < 3 * side * side; ++i)
  {
    p[i] = NAN;
  }
  r = run(p, side * side, &o);
  MRGI_CHECK(r.stats.non_finite == side * side && r.stats.finite == 0);
  release(&r);
  free(p);
}

/* One point, two points, duplicates: fallback normal, flags, radius 0 where
 * there is no spacing. */
static void test_one_point_and_duplicates(void)
{
  const float one[3] = { 1, 2, 3 };
  outputs r = run(one, 1, NULL);
  MRGI_CHECK(r.flags[0] == (MRGI_POINT_DEGENERATE | MRGI_POINT_NO_SPACING));
  MRGI_CHECK(r.normals[2] == 1.0f && r.radii[0] == 0.0f);
  MRGI_CHECK(r.stats.degenerate == 1 && r.stats.no_spacing == 1);
  release(&r);

  /* 40 copies of one point. */
  float dup[3 * 40];
  for (int i = 0; i < 40; ++i)
  {
    memcpy(dup + 3 * i, one, sizeof(one));
  }
  r = run(dup, 40, NULL);
  MRGI_CHECK(r.stats.degenerate == 40 && r.stats.no_spacing == 40);
  release(&r);

  /* A grid plane with every point twice: normals still right, radii those
   * of twice the density (the 16th neighbour is at sqrt(2) spacings:
   * sqrt(2) * sqrt(pi / 16) = 0.63, about 1 / sqrt(2)). */
  const int side = 30;
  const double centre[3] = { 0, 0, 0 }, nrm[3] = { 0, 1, 0 };
  float* g = make_plane(side, 1.0, centre, nrm, 0.0, 5);
  float* p = (float*)malloc(sizeof(float) * 6 * side * side);
  MRGI_CHECK(p != NULL);
  memcpy(p, g, sizeof(float) * 3 * side * side);
  memcpy(p + 3 * side * side, g, sizeof(float) * 3 * side * side);
  mrgi_point_normals_options o;
  mrgi_point_normals_default_options(&o);
  o.orientation = MRGI_ORIENT_UP;
  o.up[1] = 1.0;
  o.up[2] = 0.0;
  r = run(p, 2 * side * side, &o);
  MRGI_CHECK(r.stats.degenerate == 0);
  for (int i = 0; i < 2 * side * side; ++i)
  {
    MRGI_CHECK(angle_deg(r.normals + 3 * i, nrm) < 0.5);
  }
  const int mid = (side / 2) * side + side / 2;
  MRGI_CHECK_NEAR(r.radii[mid], sqrt(2.0) * sqrt(PI / 16.0), 1e-4);
  release(&r);
  free(p);
  free(g);
}

/* Points on a line: every normal is the fallback made perpendicular to it. */
static void test_collinear(void)
{
  float p[3 * 50];
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int i = 0; i < 50; ++i)
    {
      p[3 * i + 0] = axis == 0 ? (float)i * 0.1f : 1.0f;
      p[3 * i + 1] = axis == 1 ? (float)i * 0.1f : 2.0f;
      p[3 * i + 2] = axis == 2 ? (float)i * 0.1f : 3.0f;
    }
    mrgi_point_normals_options o;
    mrgi_point_normals_default_options(&o);
    o.orientation = MRGI_ORIENT_UP;
    outputs r = run(p, 50, &o);
    MRGI_CHECK(r.stats.degenerate == 50);
    for (int i = 0; i < 50; ++i)
    {
      MRGI_CHECK(r.flags[i] == MRGI_POINT_DEGENERATE);
      MRGI_CHECK(fabs(r.normals[3 * i + axis]) < 1e-5); /* perpendicular to the line */
      if (axis != 2)
      {
        MRGI_CHECK(r.normals[3 * i + 2] > 0.9999f); /* the up fallback itself */
      }
      if (i >= 8 && i < 42)
      {
        /* 8 neighbours on each side: the 16th at 0.8. */
        MRGI_CHECK_NEAR(r.radii[i], 0.1 * 8 * sqrt(PI / 16.0), 1e-4);
      }
    }
    release(&r);
  }
}

/* Bad arguments: refused with a message, outputs untouched. */
static void test_bad_arguments(void)
{
  const float p[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  float normals[9] = { 7, 7, 7, 7, 7, 7, 7, 7, 7 };
  mrgi_error err;
  mrgi_point_normals_options o;
  for (int c = 0; c < 9; ++c)
  {
    mrgi_point_normals_default_options(&o);
    const float* pos = p;
    int64_t n = 3;
    switch (c)
    {
      case 0:
        o.k = 2;
        break;
      case 1:
        o.k = MRGI_NORMALS_MAX_K + 1;
        break;
      case 2:
        o.radius_scale = 0.0;
        break;
      case 3:
        o.radius_scale = NAN;
        break;
      case 4:
        o.orientation = (mrgi_normals_orientation)7;
        break;
      case 5:
        o.orientation = MRGI_ORIENT_UP;
        o.up[2] = 0.0;
        break;
      case 6:
        o.orientation = MRGI_ORIENT_VIEWPOINT;
        o.viewpoint[1] = INFINITY;
        break;
      case 7:
        pos = NULL;
        break;
      default:
        n = -1;
        break;
    }
    memset(&err, 0, sizeof(err));
    MRGI_CHECK(mrgi_point_normals_compute(pos, n, &o, normals, NULL, NULL, NULL, &err) ==
      MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(err.status == MRGI_ERR_INVALID_ARGUMENT && strlen(err.message) > 10);
    MRGI_CHECK(strstr(err.message, "point normals") != NULL);
    MRGI_CHECK(normals[0] == 7.0f && normals[8] == 7.0f);
  }
  /* Zero points: nothing to do. */
  mrgi_point_normals_stats st;
  MRGI_CHECK(mrgi_point_normals_compute(NULL, 0, NULL, NULL, NULL, NULL, &st, &err) == MRGI_OK);
  MRGI_CHECK(st.finite == 0);
}

/* The same input gives the same bits. */
static void test_deterministic(void)
{
  const int n = 5000;
  float* p = (float*)malloc(sizeof(float) * 3 * n);
  MRGI_CHECK(p != NULL);
  uint64_t s = 4242;
  for (int i = 0; i < 3 * n; ++i)
  {
    p[i] = (float)rnd(&s);
  }
  outputs a = run(p, n, NULL), b = run(p, n, NULL);
  MRGI_CHECK(memcmp(a.normals, b.normals, sizeof(float) * 3 * n) == 0);
  MRGI_CHECK(memcmp(a.radii, b.radii, sizeof(float) * n) == 0);
  release(&a);
  release(&b);
  free(p);
}

/* The eigen solver on a known matrix: diag(3, 1, 2) rotated. */
static void test_eigen(void)
{
  const double c = cos(0.3), s = sin(0.3);
  /* R diag(3,1,2) R^T with R a rotation about z: smallest eigenvector is R e_y. */
  const double m[9] = { 3 * c * c + s * s, (3 - 1) * c * s, 0, (3 - 1) * c * s, 3 * s * s + c * c,
    0, 0, 0, 2 };
  double values[3], n[3];
  mrgi_point_normals_smallest_eigenvector(m, values, n);
  MRGI_CHECK_NEAR(values[0], 1.0, 1e-12);
  MRGI_CHECK_NEAR(values[1], 2.0, 1e-12);
  MRGI_CHECK_NEAR(values[2], 3.0, 1e-12);
  MRGI_CHECK_NEAR(fabs(n[0] * -s + n[1] * c), 1.0, 1e-12);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_eigen),
    MRGI_TEST_CASE(test_plane_grid),
    MRGI_TEST_CASE(test_plane_jittered_up),
    MRGI_TEST_CASE(test_sphere),
    MRGI_TEST_CASE(test_knn_exact),
    MRGI_TEST_CASE(test_nan_points),
    MRGI_TEST_CASE(test_one_point_and_duplicates),
    MRGI_TEST_CASE(test_collinear),
    MRGI_TEST_CASE(test_bad_arguments),
    MRGI_TEST_CASE(test_deterministic),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
