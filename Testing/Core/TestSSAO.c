/* Tests of mrgi_ssao (vtkSSAOPass's kernel and AO factor): the kernel's
 * shape, a flat plane (no occlusion), a corner (occlusion), exact scale
 * invariance, levels, bad input (never NaN), a 1 x 1 image. The bit-exact
 * kernel against vtkSSAOPass's own is checked by cxx.TestMRGISSAOvsVTK. */
#include "mrgi_buffers.h"
#include "mrgi_ssao.h"

#include "mrgi_test.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* A small analytic G-buffer: rays through the pixel centres of a perspective
 * camera at the eye-space origin, hitting a floor y = floor_y (when
 * floor_y < 0) and a wall z = -wall_z; everything scaled by `scale`. */
typedef struct scene
{
  mrgi_image position, normal;
  float noise[MRGI_SSAO_NOISE_SIZE * MRGI_SSAO_NOISE_SIZE];
  float kernel[3 * MRGI_SSAO_MAX_KERNEL_SIZE];
  mrgi_ssao_params params;
} scene;

static void make_projection(float m[16], float fovy_deg, float aspect, float n, float f)
{
  memset(m, 0, 16 * sizeof(float));
  const float c = 1.0f / tanf(fovy_deg * 0.5f * 3.14159265f / 180.0f);
  m[0] = c / aspect;
  m[5] = c;
  m[10] = -(f + n) / (f - n);
  m[11] = -1.0f;
  m[14] = -2.0f * f * n / (f - n);
}

static void make_scene(scene* s, int w, int h, float floor_y, float wall_z, float scale,
  int kernel_size, float radius, float bias)
{
  memset(s, 0, sizeof(*s));
  MRGI_CHECK(mrgi_image_create(&s->position, w, h, 4, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_image_create(&s->normal, w, h, 4, NULL) == MRGI_OK);
  const float fovy = 30.0f, aspect = (float)w / (float)h;
  const float t = tanf(fovy * 0.5f * 3.14159265f / 180.0f);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const float dx = (2.0f * ((float)x + 0.5f) / (float)w - 1.0f) * t * aspect;
      const float dy = (2.0f * ((float)y + 0.5f) / (float)h - 1.0f) * t;
      float d = wall_z; /* ray parameter of the wall z = -wall_z (dir z = -1) */
      float n[3] = { 0.0f, 0.0f, 1.0f };
      if (floor_y < 0.0f && dy < 0.0f && floor_y / dy < d)
      {
        d = floor_y / dy;
        n[1] = 1.0f;
        n[2] = 0.0f;
      }
      float* p = mrgi_image_at(&s->position, x, y);
      p[0] = dx * d * scale;
      p[1] = dy * d * scale;
      p[2] = -d * scale;
      p[3] = 1.0f;
      memcpy(mrgi_image_at(&s->normal, x, y), n, sizeof(n));
    }
  }
  uint32_t state = 12345u;
  for (int i = 0; i < MRGI_SSAO_NOISE_SIZE * MRGI_SSAO_NOISE_SIZE; ++i)
  {
    state = state * 1664525u + 1013904223u;
    s->noise[i] = (float)(state >> 8) / 16777216.0f;
  }
  MRGI_CHECK(mrgi_ssao_kernel(kernel_size, s->kernel, NULL) == MRGI_OK);
  s->params.kernel = s->kernel;
  s->params.kernel_size = kernel_size;
  s->params.radius = radius * scale;
  s->params.bias = bias * scale;
  s->params.noise = s->noise;
  make_projection(s->params.projection, fovy, aspect, 0.1f * scale, 100.0f * scale);
}

static void free_scene(scene* s)
{
  mrgi_image_destroy(&s->position);
  mrgi_image_destroy(&s->normal);
}

/* The kernel: deterministic, in the unit upper hemisphere, scaled by
 * 0.1 + 0.9 (i/N)^2, sizes out of range refused. */
static void test_kernel(void)
{
  static float a[3 * MRGI_SSAO_MAX_KERNEL_SIZE], b[3 * MRGI_SSAO_MAX_KERNEL_SIZE];
  MRGI_CHECK(mrgi_ssao_kernel(MRGI_SSAO_MAX_KERNEL_SIZE, a, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ssao_kernel(MRGI_SSAO_MAX_KERNEL_SIZE, b, NULL) == MRGI_OK);
  MRGI_CHECK(memcmp(a, b, sizeof(a)) == 0);
  for (int i = 0; i < MRGI_SSAO_MAX_KERNEL_SIZE; ++i)
  {
    const float* k = a + 3 * i;
    const float f = (float)i / (float)MRGI_SSAO_MAX_KERNEL_SIZE;
    const double scale = 0.1 + 0.9 * (double)f * (double)f;
    const double len = sqrt((double)k[0] * k[0] + (double)k[1] * k[1] + (double)k[2] * k[2]);
    MRGI_CHECK(k[2] >= 0.0f);
    MRGI_CHECK(len <= scale * (1.0 + 1e-6));
  }
  /* The draws spread over the hemisphere: both signs of x and y. */
  int positive = 0;
  for (int i = 0; i < MRGI_SSAO_MAX_KERNEL_SIZE; ++i)
  {
    positive += a[3 * i] > 0.0f;
  }
  MRGI_CHECK(positive > 400 && positive < 600);
  /* The size changes the scale, not the draws: sample 0 of every size is
   * the first accepted draw times 0.1. */
  MRGI_CHECK(mrgi_ssao_kernel(1, b, NULL) == MRGI_OK);
  MRGI_CHECK(b[0] == a[0] && b[1] == a[1] && b[2] == a[2]);
  mrgi_error err;
  MRGI_CHECK(mrgi_ssao_kernel(0, b, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "size 0") != NULL);
  MRGI_CHECK(mrgi_ssao_kernel(MRGI_SSAO_MAX_KERNEL_SIZE + 1, b, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_ssao_kernel(8, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/* A plane facing the camera: every sample is in front of it, nothing
 * occludes, AO is exactly 1. */
static void test_flat_plane(void)
{
  static scene s;
  make_scene(&s, 96, 64, 0.0f, 5.0f, 1.0f, 32, 0.5f, 0.01f);
  mrgi_image out;
  MRGI_CHECK(mrgi_ssao_compute(&s.params, &s.position, &s.normal, 0, &out, NULL) == MRGI_OK);
  MRGI_CHECK(out.width == 96 && out.height == 64 && out.channels == 2);
  for (int y = 0; y < out.height; ++y)
  {
    for (int x = 0; x < out.width; ++x)
    {
      MRGI_CHECK(mrgi_image_at(&out, x, y)[0] == 1.0f);
    }
  }
  mrgi_image_destroy(&out);
  free_scene(&s);
}

/* A floor meeting a wall: receivers near the crease are occluded, the
 * wall far above the floor is not. */
static void test_corner(void)
{
  static scene s;
  make_scene(&s, 128, 128, -1.0f, 5.0f, 1.0f, 32, 0.5f, 0.01f);
  mrgi_image out;
  MRGI_CHECK(mrgi_ssao_compute(&s.params, &s.position, &s.normal, 0, &out, NULL) == MRGI_OK);
  /* The crease is where the floor ray parameter equals the wall's:
   * dy = -1/5, i.e. row y with (2 (y + 0.5) / 128 - 1) tan(15 deg) = -0.2. */
  const float t = tanf(15.0f * 3.14159265f / 180.0f);
  const int crease = (int)((-0.2f / t + 1.0f) * 64.0f - 0.5f);
  double nearSum = 0.0, farSum = 0.0, minimum = 1.0;
  for (int x = 0; x < 128; ++x)
  {
    for (int dy = -2; dy <= 2; ++dy)
    {
      const float ao = mrgi_image_at(&out, x, crease + dy)[0];
      nearSum += ao;
      minimum = fmin(minimum, ao);
    }
    farSum += mrgi_image_at(&out, x, 120)[0];
  }
  const double nearMean = nearSum / (128 * 5), farMean = farSum / 128;
  printf("corner: crease row %d, mean AO %.4f near it, %.4f far above, min %.4f\n", crease,
    nearMean, farMean, minimum);
  MRGI_CHECK(farMean == 1.0);
  MRGI_CHECK(nearMean < 0.9);
  MRGI_CHECK(minimum < 0.8);
  MRGI_CHECK(minimum > 0.0);
  mrgi_image_destroy(&out);
  free_scene(&s);
}

/* Scene, radius, bias, near and far scaled by a power of two: every float
 * operation scales exactly, so AO is bit-equal; by 3, equal where the
 * decisions are not within rounding. */
static void test_scale_invariance(void)
{
  static scene a, b;
  make_scene(&a, 80, 60, -1.0f, 5.0f, 1.0f, 32, 0.5f, 0.01f);
  mrgi_image outA;
  MRGI_CHECK(mrgi_ssao_compute(&a.params, &a.position, &a.normal, 0, &outA, NULL) == MRGI_OK);
  const float scales[] = { 4.0f, 0.125f, 1024.0f, 3.0f };
  for (size_t k = 0; k < sizeof(scales) / sizeof(scales[0]); ++k)
  {
    make_scene(&b, 80, 60, -1.0f, 5.0f, scales[k], 32, 0.5f, 0.01f);
    mrgi_image outB;
    MRGI_CHECK(mrgi_ssao_compute(&b.params, &b.position, &b.normal, 0, &outB, NULL) == MRGI_OK);
    int compared = 0, occluded = 0;
    for (int y = 0; y < 60; ++y)
    {
      for (int x = 0; x < 80; ++x)
      {
        const float* pa = mrgi_image_at(&outA, x, y);
        const float* pb = mrgi_image_at(&outB, x, y);
        occluded += pa[0] < 1.0f;
        if (k < 3)
        {
          MRGI_CHECK(pa[0] == pb[0]);
        }
        else if (pa[1] > 1e-4f)
        {
          MRGI_CHECK(fabsf(pa[0] - pb[0]) <= 1e-5f);
          ++compared;
        }
      }
    }
    MRGI_CHECK(occluded > 100);
    MRGI_CHECK(k < 3 || compared > 80 * 60 * 7 / 10);
    mrgi_image_destroy(&outB);
    free_scene(&b);
  }
  mrgi_image_destroy(&outA);
  free_scene(&a);
}

/* A level-l texel is the receiver at its block's centre pixel; odd sizes
 * round the level up and clamp the centre. */
static void test_levels(void)
{
  static scene s;
  make_scene(&s, 67, 45, -1.0f, 5.0f, 1.0f, 16, 0.5f, 0.01f);
  for (int level = 0; level <= 3; ++level)
  {
    mrgi_image out;
    MRGI_CHECK(mrgi_ssao_compute(&s.params, &s.position, &s.normal, level, &out, NULL) == MRGI_OK);
    const int side = 1 << level;
    MRGI_CHECK(out.width == (67 + side - 1) / side && out.height == (45 + side - 1) / side);
    for (int j = 0; j < out.height; ++j)
    {
      for (int i = 0; i < out.width; ++i)
      {
        int x = i * side + side / 2, y = j * side + side / 2;
        x = x < 67 ? x : 66;
        y = y < 45 ? y : 44;
        float margin = 0.0f;
        const float ao = mrgi_ssao_receiver(&s.params, &s.position, &s.normal, x, y, &margin);
        MRGI_CHECK(mrgi_image_at(&out, i, j)[0] == ao);
        MRGI_CHECK(mrgi_image_at(&out, i, j)[1] == margin);
      }
    }
    mrgi_image_destroy(&out);
  }
  mrgi_image out;
  mrgi_error err;
  MRGI_CHECK(mrgi_ssao_compute(&s.params, &s.position, &s.normal, MRGI_SSAO_MAX_LEVEL + 1, &out,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "level") != NULL);
  MRGI_CHECK(out.pixels == NULL);
  free_scene(&s);
}

/* Background, NaN, infinite and zero normals, NaN positions next to valid
 * ones: every AO is finite in [0, 1], invalid receivers are 1; bad
 * parameters are refused with the field named. */
static void test_invalid_pixels(void)
{
  static scene s;
  make_scene(&s, 32, 32, -1.0f, 5.0f, 1.0f, 32, 0.5f, 0.01f);
  for (int y = 0; y < 32; ++y)
  {
    for (int x = 0; x < 32; ++x)
    {
      float* p = mrgi_image_at(&s.position, x, y);
      float* n = mrgi_image_at(&s.normal, x, y);
      switch ((x + 3 * y) % 7)
      {
        case 0:
          p[3] = 0.0f;
          break; /* background */
        case 1:
          p[2] = NAN;
          break; /* NaN depth */
        case 2:
          n[0] = n[1] = n[2] = 0.0f;
          break; /* zero normal */
        case 3:
          p[0] = INFINITY;
          break; /* infinite position */
        case 4:
          n[1] = NAN;
          break; /* NaN normal */
        case 5:
          p[2] = 1.0f;
          break; /* behind the camera */
        default:
          break;
      }
    }
  }
  mrgi_image out;
  MRGI_CHECK(mrgi_ssao_compute(&s.params, &s.position, &s.normal, 0, &out, NULL) == MRGI_OK);
  for (int y = 0; y < 32; ++y)
  {
    for (int x = 0; x < 32; ++x)
    {
      const float ao = mrgi_image_at(&out, x, y)[0];
      MRGI_CHECK(ao >= 0.0f && ao <= 1.0f);
      const int kind = (x + 3 * y) % 7;
      if (kind <= 5)
      {
        MRGI_CHECK(ao == 1.0f);
      }
    }
  }
  mrgi_image_destroy(&out);

  mrgi_error err;
  mrgi_ssao_params bad = s.params;
  bad.radius = 0.0f;
  MRGI_CHECK(
    mrgi_ssao_compute(&bad, &s.position, &s.normal, 0, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "radius") != NULL);
  bad.radius = NAN;
  MRGI_CHECK(mrgi_ssao_params_validate(&bad, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  bad.radius = -1.0f;
  MRGI_CHECK(mrgi_ssao_params_validate(&bad, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  bad = s.params;
  bad.bias = INFINITY;
  MRGI_CHECK(mrgi_ssao_params_validate(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "bias") != NULL);
  bad = s.params;
  bad.projection[5] = NAN;
  MRGI_CHECK(mrgi_ssao_params_validate(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "projection") != NULL);
  bad = s.params;
  bad.noise = NULL;
  MRGI_CHECK(mrgi_ssao_params_validate(&bad, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  bad = s.params;
  bad.kernel_size = 0;
  MRGI_CHECK(mrgi_ssao_params_validate(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "kernel") != NULL);
  MRGI_CHECK(mrgi_ssao_params_validate(NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  /* Images of other sizes or channel counts. */
  mrgi_image small;
  MRGI_CHECK(mrgi_image_create(&small, 16, 32, 4, NULL) == MRGI_OK);
  MRGI_CHECK(
    mrgi_ssao_compute(&s.params, &s.position, &small, 0, &out, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "equal-sized") != NULL);
  MRGI_CHECK(
    mrgi_ssao_compute(&s.params, NULL, &s.normal, 0, &out, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_ssao_compute(&s.params, &s.position, &s.normal, 0, NULL, NULL) ==
    MRGI_ERR_INVALID_ARGUMENT);
  mrgi_image_destroy(&small);
  free_scene(&s);
}

/* One pixel: the samples all land on it (clamped); a wall facing the camera
 * is not occluded, and a receiver whose normal lies in the view plane (its
 * tangent frame may degenerate) gives a finite AO. */
static void test_one_pixel(void)
{
  static scene s;
  make_scene(&s, 1, 1, 0.0f, 5.0f, 1.0f, 32, 0.5f, 0.01f);
  mrgi_image out;
  MRGI_CHECK(mrgi_ssao_compute(&s.params, &s.position, &s.normal, 0, &out, NULL) == MRGI_OK);
  MRGI_CHECK(out.width == 1 && out.height == 1 && mrgi_image_at(&out, 0, 0)[0] == 1.0f);
  mrgi_image_destroy(&out);
  for (int i = 0; i < 64; ++i)
  {
    const float a = 6.283185f * s.noise[0];
    float* n = mrgi_image_at(&s.normal, 0, 0);
    n[0] = cosf(a + (float)i * 0.1f);
    n[1] = sinf(a + (float)i * 0.1f);
    n[2] = 0.0f;
    const float ao = mrgi_ssao_receiver(&s.params, &s.position, &s.normal, 0, 0, NULL);
    MRGI_CHECK(ao >= 0.0f && ao <= 1.0f);
  }
  MRGI_CHECK(mrgi_ssao_compute(
               &s.params, &s.position, &s.normal, MRGI_SSAO_MAX_LEVEL, &out, NULL) == MRGI_OK);
  MRGI_CHECK(out.width == 1 && out.height == 1);
  mrgi_image_destroy(&out);
  free_scene(&s);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_kernel),
    MRGI_TEST_CASE(test_flat_plane),
    MRGI_TEST_CASE(test_corner),
    MRGI_TEST_CASE(test_scale_invariance),
    MRGI_TEST_CASE(test_levels),
    MRGI_TEST_CASE(test_invalid_pixels),
    MRGI_TEST_CASE(test_one_pixel),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
