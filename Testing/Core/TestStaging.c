/* The staging's core pieces: mrgi_up_axis decides the up axis of a table
 * with a flat base, an open-bottomed box, a thin slab and a cube (no
 * answer: +y), in every orientation; mrgi_framing fills the asked
 * fraction with the projection centred, for wide, tall and square images;
 * mrgi_iso_value splits a two-population histogram between them. Bad
 * arguments are refused with a message. */
#include "mrgi_framing.h"
#include "mrgi_iso_value.h"
#include "mrgi_test.h"
#include "mrgi_up_axis.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Rotate p so that +y goes to direction `up` (a rotation, not a mirror). */
static void orient(mrgi_axis up, const double p[3], double out[3])
{
  switch (up)
  {
    case MRGI_AXIS_POS_Y:
      out[0] = p[0], out[1] = p[1], out[2] = p[2];
      break;
    case MRGI_AXIS_NEG_Y:
      out[0] = -p[0], out[1] = -p[1], out[2] = p[2];
      break;
    case MRGI_AXIS_POS_Z:
      out[0] = p[0], out[1] = -p[2], out[2] = p[1];
      break;
    case MRGI_AXIS_NEG_Z:
      out[0] = p[0], out[1] = p[2], out[2] = -p[1];
      break;
    case MRGI_AXIS_POS_X:
      out[0] = p[1], out[1] = -p[0], out[2] = p[2];
      break;
    case MRGI_AXIS_NEG_X:
    default:
      out[0] = -p[1], out[1] = p[0], out[2] = p[2];
      break;
  }
}

/* Gathers evidence from quads (two triangles each) given in a y-up frame,
 * rotated to `up`; `open` quads are left out and their edges added as
 * boundary edges. */
typedef struct quad
{
  double c[4][3];
} quad;

static void bounds_of(const quad* q, int n, mrgi_axis up, double b[6])
{
  for (int k = 0; k < 3; ++k)
  {
    b[2 * k] = INFINITY;
    b[2 * k + 1] = -INFINITY;
  }
  for (int i = 0; i < n; ++i)
  {
    for (int v = 0; v < 4; ++v)
    {
      double p[3];
      orient(up, q[i].c[v], p);
      for (int k = 0; k < 3; ++k)
      {
        b[2 * k] = fmin(b[2 * k], p[k]);
        b[2 * k + 1] = fmax(b[2 * k + 1], p[k]);
      }
    }
  }
}

static mrgi_up_decision decide(const quad* q, int n, int open, mrgi_axis up)
{
  double b[6];
  bounds_of(q, n, up, b);
  mrgi_up_evidence ev;
  MRGI_CHECK(mrgi_up_evidence_init(&ev, b, NULL) == MRGI_OK);
  for (int i = 0; i < n; ++i)
  {
    double p[4][3];
    for (int v = 0; v < 4; ++v)
    {
      orient(up, q[i].c[v], p[v]);
    }
    if (i == open)
    {
      for (int v = 0; v < 4; ++v)
      {
        mrgi_up_add_boundary_edge(&ev, p[v], p[(v + 1) % 4]);
      }
      continue;
    }
    mrgi_up_add_triangle(&ev, p[0], p[1], p[2]);
    mrgi_up_add_triangle(&ev, p[0], p[2], p[3]);
  }
  mrgi_up_decision d;
  MRGI_CHECK(mrgi_up_decide(&ev, &d, NULL) == MRGI_OK);
  return d;
}

/* The six faces of a box [x0,x1] x [y0,y1] x [z0,z1], outward; face 2 is the bottom (y0). */
static void box(double x0, double x1, double y0, double y1, double z0, double z1, quad* q)
{
  const quad faces[6] = {
    { { { x0, y0, z0 }, { x0, y0, z1 }, { x0, y1, z1 }, { x0, y1, z0 } } },
    { { { x1, y0, z0 }, { x1, y1, z0 }, { x1, y1, z1 }, { x1, y0, z1 } } },
    { { { x0, y0, z0 }, { x1, y0, z0 }, { x1, y0, z1 }, { x0, y0, z1 } } },
    { { { x0, y1, z0 }, { x0, y1, z1 }, { x1, y1, z1 }, { x1, y1, z0 } } },
    { { { x0, y0, z0 }, { x0, y1, z0 }, { x1, y1, z0 }, { x1, y0, z0 } } },
    { { { x0, y0, z1 }, { x1, y0, z1 }, { x1, y1, z1 }, { x0, y1, z1 } } },
  };
  memcpy(q, faces, sizeof(faces));
}

static void test_flat_base(void)
{
  /* A pedestal: a wide low slab (its bottom is the base) with a tall
   * thin column on it, whose top is small. */
  quad q[12];
  box(-1, 1, 0, 0.2, -1, 1, q);
  box(-0.1, 0.1, 0.2, 3, -0.1, 0.1, q + 6);
  for (int a = 0; a < 6; ++a)
  {
    const mrgi_up_decision d = decide(q, 12, -1, (mrgi_axis)a);
    MRGI_CHECK(d.up == (mrgi_axis)a);
    MRGI_CHECK(d.reason == MRGI_UP_REASON_FLAT_BASE);
  }
}

static void test_open_base(void)
{
  /* A box without its bottom, faces tilted by 20 degrees: no flat base
   * (the top is tilted too), the hole says where the bottom is. A tall
   * box, so that the extents alone would not say it. */
  quad q[6];
  box(-1, 1, 0, 1.5, -1, 1, q);
  const double t = tan(20.0 * 3.14159265358979323846 / 180.0);
  for (int i = 0; i < 6; ++i)
  {
    for (int v = 0; v < 4; ++v)
    {
      q[i].c[v][1] += t * q[i].c[v][0] * (i == 3 ? 1.0 : 0.0); /* tilt the top */
    }
  }
  for (int a = 0; a < 6; ++a)
  {
    const mrgi_up_decision d = decide(q, 6, 2, (mrgi_axis)a);
    MRGI_CHECK(d.up == (mrgi_axis)a);
    MRGI_CHECK(d.reason == MRGI_UP_REASON_OPEN_BASE);
  }
}

static void test_point_base(void)
{
  /* Points spread evenly (a 0.05 grid) over the pedestal's faces, as a
   * scanner samples them: its slab's bottom holds most of them at the low
   * end. In every orientation. */
  quad q[12];
  box(-1, 1, 0, 0.2, -1, 1, q);
  box(-0.1, 0.1, 0.2, 3, -0.1, 0.1, q + 6);
  for (int a = 0; a < 6; ++a)
  {
    double b[6];
    bounds_of(q, 12, (mrgi_axis)a, b);
    mrgi_up_evidence ev;
    MRGI_CHECK(mrgi_up_evidence_init(&ev, b, NULL) == MRGI_OK);
    for (int i = 0; i < 12; ++i)
    {
      double lu = 0, lv = 0;
      for (int k = 0; k < 3; ++k)
      {
        lu += (q[i].c[1][k] - q[i].c[0][k]) * (q[i].c[1][k] - q[i].c[0][k]);
        lv += (q[i].c[3][k] - q[i].c[0][k]) * (q[i].c[3][k] - q[i].c[0][k]);
      }
      const int nu = (int)ceil(sqrt(lu) / 0.05), nv = (int)ceil(sqrt(lv) / 0.05);
      for (int s = 0; s <= nu; ++s)
      {
        for (int t = 0; t <= nv; ++t)
        {
          double p[3], o[3];
          for (int k = 0; k < 3; ++k)
          {
            const double u = (double)s / nu, v = (double)t / nv;
            p[k] = (1 - u) * (1 - v) * q[i].c[0][k] + u * (1 - v) * q[i].c[1][k] +
              u * v * q[i].c[2][k] + (1 - u) * v * q[i].c[3][k];
          }
          orient((mrgi_axis)a, p, o);
          mrgi_up_add_point(&ev, o);
        }
      }
    }
    mrgi_up_decision d;
    MRGI_CHECK(mrgi_up_decide(&ev, &d, NULL) == MRGI_OK);
    MRGI_CHECK(d.up == (mrgi_axis)a);
    MRGI_CHECK(d.reason == MRGI_UP_REASON_POINT_BASE);
    /* With a triangle, the points no longer decide. */
    const double t0[3] = { b[0], b[2], b[4] }, t1[3] = { b[1], b[2], b[4] },
                 t2[3] = { b[0], b[3], b[5] };
    mrgi_up_add_triangle(&ev, t0, t1, t2);
    MRGI_CHECK(mrgi_up_decide(&ev, &d, NULL) == MRGI_OK);
    MRGI_CHECK(d.reason != MRGI_UP_REASON_POINT_BASE);
  }
}

static void test_thin_and_default(void)
{
  quad q[6];
  /* A thin slab lies flat: both ends are flat, so the extent decides (+axis). */
  box(-2, 2, 0, 0.3, -2, 2, q);
  mrgi_up_decision d = decide(q, 6, -1, MRGI_AXIS_POS_Z);
  MRGI_CHECK(d.up == MRGI_AXIS_POS_Z);
  MRGI_CHECK(d.reason == MRGI_UP_REASON_THIN_EXTENT);
  /* A cube says nothing: +y. */
  box(-1, 1, -1, 1, -1, 1, q);
  d = decide(q, 6, -1, MRGI_AXIS_POS_X);
  MRGI_CHECK(d.up == MRGI_AXIS_POS_Y);
  MRGI_CHECK(d.reason == MRGI_UP_REASON_DEFAULT);
  /* Points only (no triangles): the extents, else +y. */
  mrgi_up_evidence ev;
  const double flat[6] = { 0, 100, 0, 80, 0, 5 };
  MRGI_CHECK(mrgi_up_evidence_init(&ev, flat, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_up_decide(&ev, &d, NULL) == MRGI_OK);
  MRGI_CHECK(d.up == MRGI_AXIS_POS_Z && d.reason == MRGI_UP_REASON_THIN_EXTENT);
  const double round[6] = { 0, 1, 0, 1, 0, 1 };
  MRGI_CHECK(mrgi_up_evidence_init(&ev, round, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_up_decide(&ev, &d, NULL) == MRGI_OK);
  MRGI_CHECK(d.up == MRGI_AXIS_POS_Y && d.reason == MRGI_UP_REASON_DEFAULT);
}

static void test_axis_names_and_errors(void)
{
  const char* names[] = { "x", "-x", "y", "-Y", "+z", "-z" };
  const mrgi_axis axes[] = { MRGI_AXIS_POS_X, MRGI_AXIS_NEG_X, MRGI_AXIS_POS_Y, MRGI_AXIS_NEG_Y,
    MRGI_AXIS_POS_Z, MRGI_AXIS_NEG_Z };
  for (int i = 0; i < 6; ++i)
  {
    mrgi_axis a;
    MRGI_CHECK(mrgi_axis_parse(names[i], &a, NULL) == MRGI_OK);
    MRGI_CHECK(a == axes[i]);
    double v[3];
    mrgi_axis_vector(a, v);
    MRGI_CHECK(fabs(v[i / 2]) == 1.0 && v[i / 2] == (i % 2 ? -1.0 : 1.0));
  }
  MRGI_CHECK(strcmp(mrgi_axis_name(MRGI_AXIS_NEG_Z), "-z") == 0);
  const char* bad[] = { "", "w", "xx", "+", "--x", "x ", "1" };
  for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i)
  {
    mrgi_axis a;
    mrgi_error err;
    MRGI_CHECK(mrgi_axis_parse(bad[i], &a, &err) == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(strstr(err.message, "is not an axis") != NULL);
  }
  mrgi_up_evidence ev;
  mrgi_error err;
  const double inverted[6] = { 1, 0, 0, 1, 0, 1 };
  MRGI_CHECK(mrgi_up_evidence_init(&ev, inverted, &err) == MRGI_ERR_INVALID_ARGUMENT);
  const double nan_bounds[6] = { 0, NAN, 0, 1, 0, 1 };
  MRGI_CHECK(mrgi_up_evidence_init(&ev, nan_bounds, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_up_decide(NULL, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

/* A pseudo-random cloud in an elongated, off-centre box. */
static double* cloud(int n)
{
  double* p = malloc(sizeof(double) * 3 * (size_t)n);
  MRGI_CHECK(p != NULL);
  unsigned s = 12345u;
  for (int i = 0; i < 3 * n; ++i)
  {
    s = s * 1664525u + 1013904223u;
    const double u = (double)(s >> 8) / 16777216.0;
    const double scale[3] = { 3.0, 1.0, 0.5 };
    const double offset[3] = { 10.0, -4.0, 2.0 };
    p[i] = offset[i % 3] + scale[i % 3] * (u - 0.5);
  }
  return p;
}

static void test_framing(void)
{
  const int n = 2000;
  double* p = cloud(n);
  const double dirs[2][3] = { { 0, -0.4, -1 }, { 1, -0.2, 0.3 } };
  const double up[3] = { 0, 1, 0 };
  const double aspects[3] = { 1.0, 16.0 / 9.0, 0.5 };
  const double fills[2] = { 0.8, 0.3 };
  for (int di = 0; di < 2; ++di)
  {
    for (int ai = 0; ai < 3; ++ai)
    {
      for (int fi = 0; fi < 2; ++fi)
      {
        mrgi_framing f;
        MRGI_CHECK(
          mrgi_frame_points(p, n, dirs[di], up, 30.0, aspects[ai], fills[fi], &f, NULL) == MRGI_OK);
        double dir[3];
        for (int k = 0; k < 3; ++k)
        {
          dir[k] = f.focal[k] - f.position[k];
        }
        double fill = 0, center[2] = { 1, 1 };
        MRGI_CHECK(mrgi_frame_fill(
                     p, n, f.position, dir, up, 30.0, aspects[ai], &fill, center, NULL) == MRGI_OK);
        MRGI_CHECK_NEAR(fill, fills[fi], 1e-3 * fills[fi]);
        MRGI_CHECK_NEAR(f.fill, fill, 1e-9);
        MRGI_CHECK(fabs(center[0]) < 1e-3 && fabs(center[1]) < 1e-3);
        /* The direction is kept. */
        const double dn = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        const double gn =
          sqrt(dirs[di][0] * dirs[di][0] + dirs[di][1] * dirs[di][1] + dirs[di][2] * dirs[di][2]);
        for (int k = 0; k < 3; ++k)
        {
          MRGI_CHECK_NEAR(dir[k] / dn, dirs[di][k] / gn, 1e-9);
        }
      }
    }
  }
  /* One point: no fill, a camera at distance 1. */
  mrgi_framing f;
  MRGI_CHECK(mrgi_frame_points(p, 1, dirs[0], up, 30.0, 1.0, 0.8, &f, NULL) == MRGI_OK);
  MRGI_CHECK(f.fill == 0.0);
  /* Bad arguments. */
  mrgi_error err;
  MRGI_CHECK(
    mrgi_frame_points(p, 0, dirs[0], up, 30.0, 1.0, 0.8, &f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_frame_points(p, n, up, up, 30.0, 1.0, 0.8, &f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "parallel") != NULL);
  MRGI_CHECK(
    mrgi_frame_points(p, n, dirs[0], up, 180.0, 1.0, 0.8, &f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_frame_points(p, n, dirs[0], up, 30.0, NAN, 0.8, &f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_frame_points(p, n, dirs[0], up, 30.0, 1.0, 1.5, &f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_frame_points(p, n, dirs[0], up, 30.0, 1.0, 0.0, &f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p[7] = NAN;
  MRGI_CHECK(
    mrgi_frame_points(p, n, dirs[0], up, 30.0, 1.0, 0.8, &f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "point 2") != NULL);
  free(p);
}

static void test_iso_value(void)
{
  /* Background around 10, object around 200, over 0..255. */
  double h[MRGI_ISO_VALUE_BINS] = { 0 };
  for (int i = 5; i < 16; ++i)
  {
    h[i] = 1000.0;
  }
  for (int i = 190; i < 211; ++i)
  {
    h[i] = 50.0;
  }
  double t = 0;
  int otsu = -1;
  MRGI_CHECK(mrgi_iso_value_otsu(h, MRGI_ISO_VALUE_BINS, 0.0, 256.0, &t, &otsu, NULL) == MRGI_OK);
  MRGI_CHECK(otsu == 1);
  MRGI_CHECK(t == 0.5 * (16.0 + 190.0)); /* every t between the populations ties: the middle */
  /* A 0/1 mask: 0.5. */
  double mask[MRGI_ISO_VALUE_BINS] = { 0 };
  mask[0] = 900.0;
  mask[MRGI_ISO_VALUE_BINS - 1] = 100.0;
  MRGI_CHECK(mrgi_iso_value_otsu(mask, MRGI_ISO_VALUE_BINS, 0.0, 1.0, &t, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(t == 0.5);
  /* One bin: the midpoint. */
  double one[4] = { 0, 7, 0, 0 };
  MRGI_CHECK(mrgi_iso_value_otsu(one, 4, -1.0, 3.0, &t, &otsu, NULL) == MRGI_OK);
  MRGI_CHECK(otsu == 0 && t == 1.0);
  /* Two bins: the boundary between them. */
  double two[2] = { 3, 5 };
  MRGI_CHECK(mrgi_iso_value_otsu(two, 2, 0.0, 1.0, &t, NULL, NULL) == MRGI_OK);
  MRGI_CHECK(t == 0.5);
  mrgi_error err;
  double zero[3] = { 0, 0, 0 };
  MRGI_CHECK(mrgi_iso_value_otsu(zero, 3, 0.0, 1.0, &t, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  double negative[3] = { 1, -1, 0 };
  MRGI_CHECK(
    mrgi_iso_value_otsu(negative, 3, 0.0, 1.0, &t, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_iso_value_otsu(two, 2, 1.0, 1.0, &t, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_iso_value_otsu(two, 1, 0.0, 1.0, &t, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(
    mrgi_iso_value_otsu(two, 2, 0.0, INFINITY, &t, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_flat_base),
    MRGI_TEST_CASE(test_open_base), MRGI_TEST_CASE(test_point_base),
    MRGI_TEST_CASE(test_thin_and_default), MRGI_TEST_CASE(test_axis_names_and_errors),
    MRGI_TEST_CASE(test_framing), MRGI_TEST_CASE(test_iso_value) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
