/* Tests of mrgi_gather_full: the disk-to-point formula by hand, facing and
 * grazing rules, r -> 0, the world->receiver matrix, scale invariance,
 * extreme intensities, invalid receivers, malformed VPLs and bad input. */
#include "mrgi_gather.h"
#include "mrgi_test.h"

#include <float.h>
#include <string.h>

/* Receivers with owned arrays, all invalid. */
typedef struct test_receivers
{
  mrgi_gather_receivers receivers;
  float* position;
  float* normal;
} test_receivers;

static test_receivers make_receivers(int32_t width, int32_t height)
{
  test_receivers t;
  const size_t floats = 4 * (size_t)width * (size_t)height;
  t.position = (float*)calloc(floats, sizeof(float));
  t.normal = (float*)calloc(floats, sizeof(float));
  MRGI_CHECK(t.position && t.normal);
  t.receivers.width = width;
  t.receivers.height = height;
  t.receivers.position = t.position;
  t.receivers.normal = t.normal;
  return t;
}

static void free_receivers(test_receivers* t)
{
  free(t->position);
  free(t->normal);
}

static void set_receiver(test_receivers* t, size_t index, double px, double py, double pz,
                         double nx, double ny, double nz)
{
  t->position[4 * index + 0] = (float)px;
  t->position[4 * index + 1] = (float)py;
  t->position[4 * index + 2] = (float)pz;
  t->position[4 * index + 3] = MRGI_GBUFFER_VALID;
  t->normal[4 * index + 0] = (float)nx;
  t->normal[4 * index + 1] = (float)ny;
  t->normal[4 * index + 2] = (float)nz;
}

static mrgi_vpl make_vpl(double px, double py, double pz, double nx, double ny, double nz,
                         double r, double g, double b, double area)
{
  mrgi_vpl vpl;
  memset(&vpl, 0, sizeof(vpl));
  vpl.position[0] = (float)px;
  vpl.position[1] = (float)py;
  vpl.position[2] = (float)pz;
  vpl.normal[0] = (float)nx;
  vpl.normal[1] = (float)ny;
  vpl.normal[2] = (float)nz;
  vpl.flux[0] = (float)r;
  vpl.flux[1] = (float)g;
  vpl.flux[2] = (float)b;
  vpl.area = (float)area;
  return vpl;
}

/* Gather and check the call succeeded and every output value is finite. */
static mrgi_image gather(const test_receivers* t, const mrgi_vpl* vpls, int32_t count,
                         const float* matrix, mrgi_gather_info* info)
{
  mrgi_image out;
  mrgi_error err;
  const mrgi_status status = mrgi_gather_full(&t->receivers, vpls, count, matrix, &out, info, &err);
  if (status != MRGI_OK)
  {
    fprintf(stderr, "gather failed: %s\n", err.message);
  }
  MRGI_CHECK(status == MRGI_OK);
  MRGI_CHECK(out.width == t->receivers.width && out.height == t->receivers.height &&
             out.channels == 3);
  int64_t nonfinite = -1;
  MRGI_CHECK(mrgi_image_count_nonfinite(&out, &nonfinite, NULL) == MRGI_OK);
  MRGI_CHECK(nonfinite == 0);
  return out;
}

static void check_relative(double got, double expected, double tolerance)
{
  MRGI_CHECK_NEAR(got, expected, tolerance * fabs(expected));
}

static void test_one_vpl_by_hand(void)
{
  test_receivers t = make_receivers(2, 1);
  set_receiver(&t, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0); /* straight below the VPL */
  set_receiver(&t, 1, 2.0, 0.0, 0.0, 0.0, 0.0, 2.0); /* 45 degrees off; normal not unit */
  const mrgi_vpl vpl = make_vpl(0.0, 0.0, 2.0, 0.0, 0.0, -1.0, 1.0, 2.0, 3.0, 0.5);
  mrgi_gather_info info;
  mrgi_image out = gather(&t, &vpl, 1, NULL, &info);
  MRGI_CHECK(info.vpls_used == 1 && info.receivers_gathered == 2);
  /* r = 2, cos = cos = 1: E = Phi / (4 pi + 0.5). */
  const double facing = 1.0 / (4.0 * MRGI_PI + 0.5);
  /* r^2 = 8, cos = cos = 1/sqrt(2): E = Phi * 0.5 / (8 pi + 0.5). */
  const double tilted = 0.5 / (8.0 * MRGI_PI + 0.5);
  for (int c = 0; c < 3; ++c)
  {
    check_relative(out.pixels[c], (c + 1) * facing, 1e-6);
    check_relative(out.pixels[3 + c], (c + 1) * tilted, 1e-6);
  }
  mrgi_image_destroy(&out);
  free_receivers(&t);
}

static void test_facing_rules(void)
{
  test_receivers t = make_receivers(3, 1);
  set_receiver(&t, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
  set_receiver(&t, 1, 5.0, 0.0, 0.0, 0.0, 0.0, -1.0); /* back-facing receiver */
  set_receiver(&t, 2, 10.0, 0.0, 0.0, 0.0, 0.0, 1.0);
  const mrgi_vpl vpls[3] = {
    make_vpl(0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0),   /* faces away from receiver 0 */
    make_vpl(5.0, 0.0, 1.0, 0.0, 0.0, -1.0, 1.0, 1.0, 1.0, 1.0),  /* faces receiver 1, which faces away */
    make_vpl(11.0, 0.0, 0.0, -1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0), /* grazing receiver 2 (cos_i = 0) */
  };
  for (int32_t j = 0; j < 3; ++j)
  {
    /* VPL j is set up against receiver j (the others may see it). */
    mrgi_image out = gather(&t, vpls + j, 1, NULL, NULL);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_CHECK(out.pixels[3 * j + c] == 0.0f);
    }
    mrgi_image_destroy(&out);
  }
  /* A VPL in the receiver's plane (grazing for the VPL: cos_j = 0). */
  const mrgi_vpl in_plane = make_vpl(1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 1.0, 1.0, 1.0, 1.0);
  mrgi_image out = gather(&t, &in_plane, 1, NULL, NULL);
  MRGI_CHECK(out.pixels[0] == 0.0f);
  mrgi_image_destroy(&out);
  /* Next to a lighting VPL, the rejected ones add exactly nothing (no negative terms). */
  const mrgi_vpl mixed[5] = {
    make_vpl(0.5, 0.0, 1.0, 0.0, 0.0, -1.0, 1.0, 2.0, 3.0, 0.1),
    vpls[0],                                                   /* cos_i > 0, cos_j < 0 */
    make_vpl(0.0, 0.0, -1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0), /* cos_i < 0, cos_j > 0 */
    vpls[2], in_plane };
  mrgi_image lit = gather(&t, mixed, 1, NULL, NULL);
  mrgi_image lit_mixed = gather(&t, mixed, 5, NULL, NULL);
  MRGI_CHECK(lit.pixels[0] > 0.0f);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK(lit_mixed.pixels[c] == lit.pixels[c]);
  }
  mrgi_image_destroy(&lit);
  mrgi_image_destroy(&lit_mixed);
  free_receivers(&t);
}

static void test_vanishing_distance(void)
{
  test_receivers t = make_receivers(3, 1);
  set_receiver(&t, 0, 1.0, 2.0, 3.0, 0.0, 0.0, 1.0);
  set_receiver(&t, 1, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
  set_receiver(&t, 2, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
  /* r = 0 exactly: contribution 0, whatever the area. */
  const mrgi_vpl coincident[2] = { make_vpl(1.0, 2.0, 3.0, 0.0, 0.0, -1.0, 1e6, 1e6, 1e6, 0.0),
                                   make_vpl(1.0, 2.0, 3.0, 0.0, 0.0, -1.0, 1.0, 1.0, 1.0, 1.0) };
  mrgi_image out = gather(&t, coincident, 2, NULL, NULL);
  MRGI_CHECK(out.pixels[0] == 0.0f);
  mrgi_image_destroy(&out);
  /* r = 1e-20 on the axis: E -> Phi / A (at most), finite. */
  const mrgi_vpl close_with_area = make_vpl(0.0, 0.0, 1e-20, 0.0, 0.0, -1.0, 3.0, 3.0, 3.0, 2.0);
  out = gather(&t, &close_with_area, 1, NULL, NULL);
  check_relative(out.pixels[3], 1.5, 1e-6);
  mrgi_image_destroy(&out);
  /* A point VPL (A = 0) at r = 1e-30 with Phi = 1e30: far beyond float, clamped, finite. */
  const mrgi_vpl close_point = make_vpl(0.0, 0.0, 1e-30, 0.0, 0.0, -1.0, 1e30, 1e30, 1e30, 0.0);
  out = gather(&t, &close_point, 1, NULL, NULL);
  MRGI_CHECK(out.pixels[3] == FLT_MAX);
  mrgi_image_destroy(&out);
  free_receivers(&t);
}

/* A small scene: 4 x 3 receivers on a wavy floor, 7 VPLs above it. */
static void make_scene(test_receivers* t, mrgi_vpl vpls[7], double position_scale,
                       double flux_scale)
{
  *t = make_receivers(4, 3);
  for (int32_t y = 0; y < 3; ++y)
  {
    for (int32_t x = 0; x < 4; ++x)
    {
      const double tilt = 0.2 * sin(x + 2.0 * y);
      set_receiver(t, (size_t)(y * 4 + x), position_scale * x, position_scale * y,
                   position_scale * 0.1 * tilt, tilt, 0.1 * y, 1.0);
    }
  }
  for (int32_t j = 0; j < 7; ++j)
  {
    const double angle = 0.9 * j;
    vpls[j] = make_vpl(position_scale * (1.5 + cos(angle)), position_scale * (1.0 + sin(angle)),
                       position_scale * (0.5 + 0.3 * j), 0.1 * cos(angle), 0.2, -1.0,
                       flux_scale * (1.0 + j), flux_scale * 0.5, flux_scale * (7.0 - j),
                       position_scale * position_scale * 0.05 * (j + 1));
  }
}

/* Column-major rigid matrix: rotation by `degrees` about axis z then x, then a translation. */
static void make_rigid(float m[16], double degrees, double tx, double ty, double tz)
{
  const double a = degrees * MRGI_PI / 180.0;
  const double ca = cos(a), sa = sin(a);
  /* R = Rx(a) * Rz(a) */
  const double rz[3][3] = { { ca, -sa, 0.0 }, { sa, ca, 0.0 }, { 0.0, 0.0, 1.0 } };
  const double rx[3][3] = { { 1.0, 0.0, 0.0 }, { 0.0, ca, -sa }, { 0.0, sa, ca } };
  memset(m, 0, 16 * sizeof(float));
  for (int row = 0; row < 3; ++row)
  {
    for (int col = 0; col < 3; ++col)
    {
      double value = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        value += rx[row][k] * rz[k][col];
      }
      m[col * 4 + row] = (float)value;
    }
  }
  m[12] = (float)tx;
  m[13] = (float)ty;
  m[14] = (float)tz;
  m[15] = 1.0f;
}

static void test_matrix_applied(void)
{
  test_receivers t;
  mrgi_vpl vpls[7];
  make_scene(&t, vpls, 1.0, 1.0);
  mrgi_image world = gather(&t, vpls, 7, NULL, NULL);
  MRGI_CHECK(world.pixels[3 * 5] > 0.0f);

  /* Receivers moved into a rotated and translated space; VPLs stay in world space. */
  float m[16];
  make_rigid(m, 30.0, 5.0, -3.0, 7.0);
  for (size_t i = 0; i < 12; ++i)
  {
    float moved_position[3];
    float moved_normal[3];
    for (int row = 0; row < 3; ++row)
    {
      moved_position[row] = m[row] * t.position[4 * i] + m[4 + row] * t.position[4 * i + 1] +
                            m[8 + row] * t.position[4 * i + 2] + m[12 + row];
      moved_normal[row] = m[row] * t.normal[4 * i] + m[4 + row] * t.normal[4 * i + 1] +
                          m[8 + row] * t.normal[4 * i + 2];
    }
    memcpy(t.position + 4 * i, moved_position, sizeof(moved_position));
    memcpy(t.normal + 4 * i, moved_normal, sizeof(moved_normal));
  }
  mrgi_image moved = gather(&t, vpls, 7, m, NULL);
  for (size_t k = 0; k < 36; ++k)
  {
    MRGI_CHECK_NEAR(moved.pixels[k], world.pixels[k], 1e-5 * world.pixels[k] + 1e-9);
  }
  /* Without the matrix the answer does change (the test can fail). */
  mrgi_image unmoved = gather(&t, vpls, 7, NULL, NULL);
  MRGI_CHECK(fabs(unmoved.pixels[3 * 5] - world.pixels[3 * 5]) > 1e-3 * world.pixels[3 * 5]);

  /* Non-rigid and projective matrices are refused. */
  mrgi_image out;
  mrgi_error err;
  float scaled[16];
  memcpy(scaled, m, sizeof(scaled));
  for (int k = 0; k < 11; ++k)
  {
    scaled[k] *= 2.0f;
  }
  MRGI_CHECK(mrgi_gather_full(&t.receivers, vpls, 7, scaled, &out, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "not rigid") != NULL && out.pixels == NULL);
  float projective[16];
  memcpy(projective, m, sizeof(projective));
  projective[11] = -1.0f;
  MRGI_CHECK(mrgi_gather_full(&t.receivers, vpls, 7, projective, &out, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "last row") != NULL);
  projective[11] = NAN;
  MRGI_CHECK(mrgi_gather_check_transform(projective, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_gather_check_transform(m, NULL) == MRGI_OK);
  mrgi_image_destroy(&world);
  mrgi_image_destroy(&moved);
  mrgi_image_destroy(&unmoved);
  free_receivers(&t);
}

static void test_scale_invariance(void)
{
  test_receivers reference_receivers;
  mrgi_vpl vpls[7];
  make_scene(&reference_receivers, vpls, 1.0, 1.0);
  mrgi_image reference = gather(&reference_receivers, vpls, 7, NULL, NULL);
  const double scales[2] = { 1e-4, 1e5 };
  for (int s = 0; s < 2; ++s)
  {
    test_receivers scaled_receivers;
    make_scene(&scaled_receivers, vpls, scales[s], scales[s] * scales[s]);
    mrgi_image scaled = gather(&scaled_receivers, vpls, 7, NULL, NULL);
    double largest = 0.0;
    for (size_t k = 0; k < 36; ++k)
    {
      largest = fmax(largest, reference.pixels[k]);
    }
    MRGI_CHECK(largest > 0.0);
    for (size_t k = 0; k < 36; ++k)
    {
      MRGI_CHECK_NEAR(scaled.pixels[k], reference.pixels[k], 1e-5 * reference.pixels[k] + 1e-9 * largest);
    }
    mrgi_image_destroy(&scaled);
    free_receivers(&scaled_receivers);
  }
  mrgi_image_destroy(&reference);
  free_receivers(&reference_receivers);
}

static void test_extreme_intensities(void)
{
  test_receivers t;
  mrgi_vpl vpls[7];
  make_scene(&t, vpls, 1.0, 1.0);
  mrgi_image unit = gather(&t, vpls, 7, NULL, NULL);
  const double intensities[2] = { 1e-6, 1e6 };
  for (int s = 0; s < 2; ++s)
  {
    free_receivers(&t);
    make_scene(&t, vpls, 1.0, intensities[s]);
    mrgi_image out = gather(&t, vpls, 7, NULL, NULL);
    for (size_t k = 0; k < 36; ++k)
    {
      MRGI_CHECK_NEAR(out.pixels[k] / intensities[s], unit.pixels[k], 1e-5 * unit.pixels[k]);
    }
    mrgi_image_destroy(&out);
  }
  /* 4096 VPLs of flux 1e6 at the same spot: 4096 times one of them, no overflow. */
  mrgi_vpl* many = (mrgi_vpl*)malloc(sizeof(mrgi_vpl) * MRGI_VPL_MAX_COUNT);
  MRGI_CHECK(many != NULL);
  for (int32_t j = 0; j < MRGI_VPL_MAX_COUNT; ++j)
  {
    many[j] = make_vpl(1.0, 1.0, 1.0, 0.0, 0.0, -1.0, 1e6, 1e6, 1e6, 1e-3);
  }
  mrgi_image one = gather(&t, many, 1, NULL, NULL);
  mrgi_image all = gather(&t, many, MRGI_VPL_MAX_COUNT, NULL, NULL);
  for (size_t k = 0; k < 36; ++k)
  {
    MRGI_CHECK_NEAR(all.pixels[k], 4096.0 * one.pixels[k], 1e-6 * 4096.0 * one.pixels[k]);
  }
  mrgi_image_destroy(&one);
  mrgi_image_destroy(&all);
  free(many);
  mrgi_image_destroy(&unit);
  free_receivers(&t);
}

static void test_receiver_flags_and_order(void)
{
  /* 2 x 2, GL order: index y*W + x, row 0 = bottom; the output keeps that order. */
  test_receivers t = make_receivers(2, 2);
  set_receiver(&t, 1, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0); /* (x 1, y 0): the only good one */
  set_receiver(&t, 2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0); /* valid flag but zero normal */
  set_receiver(&t, 3, NAN, 0.0, 0.0, 0.0, 0.0, 1.0); /* valid flag but NaN position */
  t.position[4 * 0 + 2] = -1.0f;                     /* invalid (w = 0) whatever it holds */
  t.normal[4 * 0 + 2] = 1.0f;
  const mrgi_vpl vpl = make_vpl(0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 1.0, 1.0, 1.0, 1.0);
  mrgi_gather_info info;
  mrgi_image out = gather(&t, &vpl, 1, NULL, &info);
  MRGI_CHECK(info.receivers_gathered == 1 && info.receivers_invalid == 1 &&
             info.receivers_malformed == 2);
  MRGI_CHECK(mrgi_image_at(&out, 1, 0)[0] > 0.0f);
  MRGI_CHECK(mrgi_image_at(&out, 0, 0)[0] == 0.0f);
  MRGI_CHECK(mrgi_image_at(&out, 0, 1)[1] == 0.0f);
  MRGI_CHECK(mrgi_image_at(&out, 1, 1)[2] == 0.0f);
  mrgi_image_destroy(&out);
  free_receivers(&t);
}

static void test_malformed_vpls_skipped(void)
{
  test_receivers t;
  mrgi_vpl vpls[7];
  make_scene(&t, vpls, 1.0, 1.0);
  mrgi_image clean = gather(&t, vpls, 7, NULL, NULL);
  mrgi_vpl bad[12];
  memcpy(bad, vpls, sizeof(vpls));
  bad[7] = vpls[0];
  bad[7].position[1] = NAN;
  bad[8] = vpls[1];
  bad[8].flux[2] = INFINITY;
  bad[9] = vpls[2];
  bad[9].area = -1.0f;
  bad[10] = vpls[3];
  bad[10].normal[0] = bad[10].normal[1] = bad[10].normal[2] = 0.0f;
  memset(bad + 11, 0, sizeof(mrgi_vpl)); /* an empty grid block */
  mrgi_gather_info info;
  mrgi_image out = gather(&t, bad, 12, NULL, &info);
  MRGI_CHECK(info.vpls_used == 7 && info.vpls_malformed == 4 && info.vpls_zero_flux == 1);
  for (size_t k = 0; k < 36; ++k)
  {
    MRGI_CHECK(out.pixels[k] == clean.pixels[k]);
  }
  mrgi_image_destroy(&out);
  mrgi_image_destroy(&clean);
  free_receivers(&t);
}

static void test_bad_input(void)
{
  test_receivers t = make_receivers(2, 2);
  const mrgi_vpl vpl = make_vpl(0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 1.0, 1.0, 1.0, 1.0);
  mrgi_image out;
  mrgi_error err;
  MRGI_CHECK(mrgi_gather_full(NULL, &vpl, 1, NULL, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(out.pixels == NULL && strstr(err.message, "NULL") != NULL);
  MRGI_CHECK(mrgi_gather_full(&t.receivers, NULL, 1, NULL, &out, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_gather_full(&t.receivers, &vpl, 1, NULL, NULL, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_gather_full(&t.receivers, &vpl, 0, NULL, &out, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "count 0") != NULL);
  MRGI_CHECK(mrgi_gather_full(&t.receivers, &vpl, MRGI_VPL_MAX_COUNT + 1, NULL, &out, NULL,
                              &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_gather_receivers bad = t.receivers;
  bad.normal = NULL;
  MRGI_CHECK(mrgi_gather_full(&bad, &vpl, 1, NULL, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "normal") != NULL);
  bad = t.receivers;
  bad.width = 0;
  MRGI_CHECK(mrgi_gather_full(&bad, &vpl, 1, NULL, &out, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(out.pixels == NULL);
  MRGI_CHECK(mrgi_gather_check_transform(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  free_receivers(&t);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_one_vpl_by_hand),
    MRGI_TEST_CASE(test_facing_rules),
    MRGI_TEST_CASE(test_vanishing_distance),
    MRGI_TEST_CASE(test_matrix_applied),
    MRGI_TEST_CASE(test_scale_invariance),
    MRGI_TEST_CASE(test_extreme_intensities),
    MRGI_TEST_CASE(test_receiver_flags_and_order),
    MRGI_TEST_CASE(test_malformed_vpls_skipped),
    MRGI_TEST_CASE(test_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
