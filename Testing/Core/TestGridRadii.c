/* Tests of mrgi_grid_radii: a stretched grid gets radii that cover its
 * cells, depth discontinuities are not bridged, radii are only raised,
 * isolated, non-finite and misplaced points, and bad arguments. */
#include "mrgi_grid_radii.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#define SQRT_PI 1.77245385090551602730
#define W 8
#define H 6

/* A W x H grid on the plane z = 1: spacing a across, b down (a grazing view). */
static void stretched_grid(float* xyz, int64_t* pixels, double a, double b)
{
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      const int i = y * W + x;
      xyz[3 * i + 0] = (float)(a * x);
      xyz[3 * i + 1] = (float)(b * y);
      xyz[3 * i + 2] = 1.0f;
      pixels[i] = i;
    }
  }
}

static void test_stretched_cells_covered(void)
{
  float xyz[3 * W * H], radii[W * H];
  int64_t pixels[W * H];
  const double a = 0.002, b = 0.008; /* cells 4x longer than wide */
  stretched_grid(xyz, pixels, a, b);
  for (int i = 0; i < W * H; ++i)
  {
    radii[i] = (float)a; /* what the kNN spacing gives along the short side */
  }
  const double origin[3] = { 0.0, 0.0, 0.0 };
  mrgi_grid_radii_stats stats;
  mrgi_error err;
  MRGI_CHECK(mrgi_grid_radii_apply(
               xyz, pixels, W * H, W, H, origin, 0.03, 1.0, radii, &stats, &err) == MRGI_OK);
  MRGI_CHECK(stats.placed == W * H && stats.unplaced == 0 && stats.isolated == 0);
  MRGI_CHECK(stats.raised == W * H);
  const double diagonal = sqrt(a * a + b * b);
  for (int i = 0; i < W * H; ++i)
  {
    /* Every point has a diagonal neighbour: r = diagonal / sqrt(pi). */
    MRGI_CHECK_NEAR(radii[i], diagonal / SQRT_PI, 1e-6);
    /* The square surfel of area pi r^2 holds the disk of radius r sqrt(pi) / 2,
     * which reaches the cell's corners (half a diagonal away) at any rotation. */
    MRGI_CHECK(radii[i] * SQRT_PI / 2.0 >= 0.5 * diagonal - 1e-7);
  }
}

static void test_scale_and_only_raised(void)
{
  float xyz[3 * W * H], radii[W * H];
  int64_t pixels[W * H];
  stretched_grid(xyz, pixels, 0.002, 0.002);
  for (int i = 0; i < W * H; ++i)
  {
    radii[i] = i == 0 ? 1.0f : 0.0f; /* point 0 already larger than its cell */
  }
  const double origin[3] = { 0.0, 0.0, 0.0 };
  mrgi_grid_radii_stats stats;
  mrgi_error err;
  MRGI_CHECK(mrgi_grid_radii_apply(
               xyz, pixels, W * H, W, H, origin, 0.03, 2.0, radii, &stats, &err) == MRGI_OK);
  MRGI_CHECK(radii[0] == 1.0f);
  MRGI_CHECK(stats.raised == W * H - 1);
  MRGI_CHECK_NEAR(radii[W + 1], 2.0 * 0.002 * sqrt(2.0) / SQRT_PI, 1e-6);
}

static void test_discontinuity_not_bridged(void)
{
  /* The left half at range 1, the right half at range 0.5 (an object in
   * front): points at the edge take only their own side's neighbours. */
  float xyz[3 * W * H], radii[W * H];
  int64_t pixels[W * H];
  const double s = 0.002;
  stretched_grid(xyz, pixels, s, s);
  for (int y = 0; y < H; ++y)
  {
    for (int x = W / 2; x < W; ++x)
    {
      float* p = xyz + 3 * (y * W + x);
      p[0] *= 0.5f;
      p[1] *= 0.5f;
      p[2] = 0.5f;
    }
  }
  memset(radii, 0, sizeof(radii));
  const double origin[3] = { 0.0, 0.0, 0.0 };
  mrgi_error err;
  MRGI_CHECK(mrgi_grid_radii_apply(
               xyz, pixels, W * H, W, H, origin, 0.03, 1.0, radii, NULL, &err) == MRGI_OK);
  const int edge_far = 2 * W + W / 2 - 1, edge_near = 2 * W + W / 2;
  MRGI_CHECK_NEAR(radii[edge_far], s * sqrt(2.0) / SQRT_PI, 1e-6);
  MRGI_CHECK_NEAR(radii[edge_near], 0.5 * s * sqrt(2.0) / SQRT_PI, 1e-6);
  /* A step of 3% would be bridged with range_step 0.5. */
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, pixels, W * H, W, H, origin, 1.5, 1.0, radii, NULL, &err) ==
    MRGI_OK);
  MRGI_CHECK(radii[edge_far] > 0.2f);
}

static void test_isolated_nonfinite_misplaced(void)
{
  float xyz[3 * W * H], radii[W * H];
  int64_t pixels[W * H];
  stretched_grid(xyz, pixels, 0.002, 0.002);
  /* Point 0's neighbours (1, W, W + 1) removed: isolated. */
  xyz[3 * 1] = NAN;
  xyz[3 * W + 1] = INFINITY;
  xyz[3 * (W + 1) + 2] = NAN;
  /* Point 5 claims point 6's pixel: both left out; point 7 out of range. */
  pixels[5] = 6;
  pixels[7] = (int64_t)W * H;
  for (int i = 0; i < W * H; ++i)
  {
    radii[i] = 0.5f;
  }
  radii[0] = 0.25f;
  const double origin[3] = { 0.0, 0.0, 0.0 };
  mrgi_grid_radii_stats stats;
  mrgi_error err;
  MRGI_CHECK(mrgi_grid_radii_apply(
               xyz, pixels, W * H, W, H, origin, 0.03, 1.0, radii, &stats, &err) == MRGI_OK);
  MRGI_CHECK(stats.unplaced == 3);
  MRGI_CHECK(stats.placed == W * H - 3 - 3);
  MRGI_CHECK(stats.isolated == 1);
  MRGI_CHECK(stats.raised == 0);
  MRGI_CHECK(radii[0] == 0.25f);
  for (int i = 0; i < W * H; ++i)
  {
    MRGI_CHECK(isfinite(radii[i]));
  }
}

static void test_bad_arguments(void)
{
  float xyz[3 * W * H], radii[W * H];
  int64_t pixels[W * H];
  stretched_grid(xyz, pixels, 0.002, 0.002);
  memset(radii, 0, sizeof(radii));
  const double origin[3] = { 0.0, 0.0, 0.0 };
  const double bad_origin[3] = { 0.0, NAN, 0.0 };
  mrgi_grid_radii_stats stats;
  mrgi_error err;
  MRGI_CHECK(mrgi_grid_radii_apply(NULL, pixels, 4, W, H, origin, 0.03, 1, radii, &stats, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "positions") != NULL);
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, NULL, 4, W, H, origin, 0.03, 1, radii, &stats, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "pixels") != NULL);
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, pixels, -1, W, H, origin, 0.03, 1, radii, &stats, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, pixels, 4, 0, H, origin, 0.03, 1, radii, &stats, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, pixels, 4, (int64_t)1 << 20, (int64_t)1 << 20, origin, 0.03,
               1, radii, &stats, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "grid") != NULL);
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, pixels, 4, W, H, bad_origin, 0.03, 1, radii, &stats,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, pixels, 4, W, H, origin, 0.0, 1, radii, &stats, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "range_step") != NULL);
  MRGI_CHECK(mrgi_grid_radii_apply(xyz, pixels, 4, W, H, origin, 0.03, NAN, radii, &stats, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "scale") != NULL);
  MRGI_CHECK(stats.placed == 0 && stats.raised == 0);
  for (int i = 0; i < W * H; ++i)
  {
    MRGI_CHECK(radii[i] == 0.0f); /* untouched on failure */
  }
  MRGI_CHECK(
    mrgi_grid_radii_apply(NULL, NULL, 0, W, H, origin, 0.03, 1, NULL, &stats, &err) == MRGI_OK);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = { MRGI_TEST_CASE(test_stretched_cells_covered),
    MRGI_TEST_CASE(test_scale_and_only_raised), MRGI_TEST_CASE(test_discontinuity_not_bridged),
    MRGI_TEST_CASE(test_isolated_nonfinite_misplaced), MRGI_TEST_CASE(test_bad_arguments) };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
