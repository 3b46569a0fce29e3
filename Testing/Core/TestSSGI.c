/* Tests of mrgi_ssgi (screen-space one bounce and directional occlusion):
 * the kernel, a flat lit plane (no bounce, no occlusion), a red wall beside a
 * grey floor (the floor near the wall turns red, less with distance), exact
 * scale invariance, levels, energy (bounce <= albedo x brightest sender),
 * bad input (never NaN), a 1 x 1 image. */
#include "mrgi_buffers.h"
#include "mrgi_ssgi.h"

#include "mrgi_test.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* An analytic G-buffer: rays through the pixel centres of a perspective
 * camera at the eye-space origin looking down -z, hitting a floor
 * y = floor_y (when floor_y < 0; normal +y) and a wall z = -wall_z (normal
 * +z); everything scaled by `scale`. The wall's direct radiance is
 * wall_light, the floor's floor_light; albedo 0.5 grey everywhere. */
typedef struct scene
{
  mrgi_image position, normal, albedo, direct;
  float kernel[3 * MRGI_SSGI_MAX_SAMPLES];
  mrgi_ssgi_params params;
} scene;

static const float wall_light[3] = { 1.0f, 0.0f, 0.0f };
static const float floor_light[3] = { 0.5f, 0.5f, 0.5f };

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
  int samples, float radius, float bias)
{
  memset(s, 0, sizeof(*s));
  MRGI_CHECK(mrgi_image_create(&s->position, w, h, 4, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_image_create(&s->normal, w, h, 4, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_image_create(&s->albedo, w, h, 4, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_image_create(&s->direct, w, h, 4, NULL) == MRGI_OK);
  const float fovy = 30.0f, aspect = (float)w / (float)h;
  const float t = tanf(fovy * 0.5f * 3.14159265f / 180.0f);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const float dx = (2.0f * ((float)x + 0.5f) / (float)w - 1.0f) * t * aspect;
      const float dy = (2.0f * ((float)y + 0.5f) / (float)h - 1.0f) * t;
      float d = wall_z;
      float n[4] = { 0.0f, 0.0f, 1.0f, 1.0f };
      const float* light = wall_light;
      if (floor_y < 0.0f && dy < 0.0f && floor_y / dy < d)
      {
        d = floor_y / dy;
        n[1] = 1.0f;
        n[2] = 0.0f;
        light = floor_light;
      }
      float* p = mrgi_image_at(&s->position, x, y);
      p[0] = dx * d * scale;
      p[1] = dy * d * scale;
      p[2] = -d * scale;
      p[3] = 1.0f;
      memcpy(mrgi_image_at(&s->normal, x, y), n, sizeof(n));
      float* a = mrgi_image_at(&s->albedo, x, y);
      a[0] = a[1] = a[2] = 0.5f;
      a[3] = 1.0f;
      float* l = mrgi_image_at(&s->direct, x, y);
      memcpy(l, light, 3 * sizeof(float));
      l[3] = 1.0f;
    }
  }
  MRGI_CHECK(mrgi_ssgi_kernel(samples, s->kernel, NULL) == MRGI_OK);
  s->params.kernel = s->kernel;
  s->params.sample_count = samples;
  s->params.radius = radius * scale;
  s->params.bias = bias * scale;
  make_projection(s->params.projection, fovy, aspect, 0.1f * scale, 100.0f * scale);
}

static void free_scene(scene* s)
{
  mrgi_image_destroy(&s->position);
  mrgi_image_destroy(&s->normal);
  mrgi_image_destroy(&s->albedo);
  mrgi_image_destroy(&s->direct);
}

/* Deterministic, inside the unit upper half ball, directions spread. */
static void test_kernel(void)
{
  static float a[3 * MRGI_SSGI_MAX_SAMPLES], b[3 * MRGI_SSGI_MAX_SAMPLES];
  MRGI_CHECK(mrgi_ssgi_kernel(MRGI_SSGI_MAX_SAMPLES, a, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ssgi_kernel(MRGI_SSGI_MAX_SAMPLES, b, NULL) == MRGI_OK);
  MRGI_CHECK(memcmp(a, b, sizeof(a)) == 0);
  int positive = 0;
  double mean_cos = 0.0;
  for (int i = 0; i < MRGI_SSGI_MAX_SAMPLES; ++i)
  {
    const float* k = a + 3 * i;
    const double len = sqrt((double)k[0] * k[0] + (double)k[1] * k[1] + (double)k[2] * k[2]);
    MRGI_CHECK(k[2] > 0.0f);
    MRGI_CHECK(len <= 1.0 + 1e-6);
    positive += k[0] > 0.0f;
    mean_cos += k[2] / len;
  }
  MRGI_CHECK(positive > 200 && positive < 312);
  /* Uniform in solid angle: the mean cosine is 1/2. */
  MRGI_CHECK_NEAR(mean_cos / MRGI_SSGI_MAX_SAMPLES, 0.5, 0.01);
  mrgi_error err;
  MRGI_CHECK(mrgi_ssgi_kernel(0, b, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "count 0") != NULL);
  MRGI_CHECK(mrgi_ssgi_kernel(MRGI_SSGI_MAX_SAMPLES + 1, b, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_ssgi_kernel(8, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/* A lit plane facing the camera, and a floor seen at a grazing angle: no
 * sample is behind the depth buffer, so nothing bounces and nothing blocks. */
static void test_flat_plane(void)
{
  static scene s;
  for (int variant = 0; variant < 2; ++variant)
  {
    /* variant 1: a floor with the wall beyond the range of every floor pixel */
    make_scene(&s, 96, 64, variant ? -1.0f : 0.0f, variant ? 90.0f : 5.0f, 1.0f, 64, 0.5f, 0.01f);
    mrgi_image out;
    MRGI_CHECK(mrgi_ssgi_compute(&s.params, &s.position, &s.normal, &s.albedo, &s.direct, 0, &out,
                 NULL) == MRGI_OK);
    MRGI_CHECK(out.width == 96 && out.height == 64 && out.channels == MRGI_SSGI_CHANNELS);
    int checked = 0;
    for (int y = 0; y < out.height; ++y)
    {
      for (int x = 0; x < out.width; ++x)
      {
        if (variant && mrgi_image_at(&s.normal, x, y)[1] != 1.0f)
        {
          continue; /* the far wall */
        }
        const float* o = mrgi_image_at(&out, x, y);
        MRGI_CHECK(o[0] == 0.0f && o[1] == 0.0f && o[2] == 0.0f);
        MRGI_CHECK(o[3] == 1.0f);
        ++checked;
      }
    }
    MRGI_CHECK(checked > 500);
    mrgi_image_destroy(&out);
    free_scene(&s);
  }
}

/* A red wall beside a grey floor: floor receivers near the wall get red
 * light (only red: the wall sends no green or blue, the flat floor does not
 * light itself), more the nearer they are; beyond R from the wall, none.
 * The floor near the wall is also partly blocked (V < 1). */
static void test_wall_bleeding(void)
{
  static scene s;
  const float radius = 0.5f;
  make_scene(&s, 96, 64, -1.0f, 5.0f, 1.0f, 128, radius, 0.01f);
  mrgi_image out;
  MRGI_CHECK(mrgi_ssgi_compute(
               &s.params, &s.position, &s.normal, &s.albedo, &s.direct, 0, &out, NULL) == MRGI_OK);
  const int x = 48;
  float previous = -1.0f;
  int near = 0, far = 0, rising = 0, rows = 0;
  /* Rows from the bottom (nearest the camera) up to the wall: distance to
   * the wall shrinks, the red bounce must grow. */
  for (int y = 0; y < out.height; ++y)
  {
    if (mrgi_image_at(&s.normal, x, y)[1] != 1.0f)
    {
      break;
    }
    const float* o = mrgi_image_at(&out, x, y);
    const float gap = 5.0f + mrgi_image_at(&s.position, x, y)[2]; /* to the wall */
    MRGI_CHECK(o[1] == 0.0f && o[2] == 0.0f);
    if (gap > radius * 1.01f)
    {
      MRGI_CHECK(o[0] == 0.0f);
      MRGI_CHECK(o[3] == 1.0f);
      ++far;
    }
    else if (gap < 0.5f * radius)
    {
      MRGI_CHECK(o[0] > 0.0f);
      MRGI_CHECK(o[3] < 1.0f);
      ++near;
    }
    rising += o[0] >= previous;
    previous = o[0];
    ++rows;
  }
  MRGI_CHECK(near >= 1 && far >= 3);
  /* Monotone up to kernel noise: almost every step toward the wall gains. */
  MRGI_CHECK(rising >= rows - 2);
  /* The floor's last row beside the wall is clearly red: a visible bounce. */
  MRGI_CHECK(previous > 0.01f);
  mrgi_image_destroy(&out);
  free_scene(&s);
}

/* Scaling the scene, R and the bias by a power of two changes no float
 * rounding: the result is identical. */
static void test_scale_invariance(void)
{
  static scene a, b;
  make_scene(&a, 64, 48, -1.0f, 5.0f, 1.0f, 64, 0.5f, 0.01f);
  make_scene(&b, 64, 48, -1.0f, 5.0f, 4.0f, 64, 0.5f, 0.01f);
  mrgi_image oa, ob;
  MRGI_CHECK(mrgi_ssgi_compute(
               &a.params, &a.position, &a.normal, &a.albedo, &a.direct, 0, &oa, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ssgi_compute(
               &b.params, &b.position, &b.normal, &b.albedo, &b.direct, 0, &ob, NULL) == MRGI_OK);
  double sum = 0.0;
  for (int y = 0; y < oa.height; ++y)
  {
    for (int x = 0; x < oa.width; ++x)
    {
      const float* p = mrgi_image_at(&oa, x, y);
      const float* q = mrgi_image_at(&ob, x, y);
      for (int c = 0; c < 4; ++c)
      {
        MRGI_CHECK_NEAR(p[c], q[c], 1e-6 * fabs(p[c]) + 1e-12);
      }
      sum += p[0];
    }
  }
  MRGI_CHECK(sum > 0.0); /* the comparison saw a bounce */
  mrgi_image_destroy(&oa);
  mrgi_image_destroy(&ob);
  free_scene(&a);
  free_scene(&b);
}

/* A level-l texel is the receiver at its block's centre pixel. */
static void test_levels(void)
{
  static scene s;
  make_scene(&s, 61, 47, -1.0f, 5.0f, 1.0f, 32, 0.5f, 0.01f);
  mrgi_image full, l1, l2;
  MRGI_CHECK(mrgi_ssgi_compute(
               &s.params, &s.position, &s.normal, &s.albedo, &s.direct, 0, &full, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ssgi_compute(
               &s.params, &s.position, &s.normal, &s.albedo, &s.direct, 1, &l1, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ssgi_compute(
               &s.params, &s.position, &s.normal, &s.albedo, &s.direct, 2, &l2, NULL) == MRGI_OK);
  MRGI_CHECK(l1.width == 31 && l1.height == 24 && l2.width == 16 && l2.height == 12);
  for (int j = 0; j < l2.height; ++j)
  {
    for (int i = 0; i < l2.width; ++i)
    {
      const int x = i * 4 + 2 < 61 ? i * 4 + 2 : 60, y = j * 4 + 2 < 47 ? j * 4 + 2 : 46;
      MRGI_CHECK(memcmp(mrgi_image_at(&l2, i, j), mrgi_image_at(&full, x, y),
                   MRGI_SSGI_CHANNELS * sizeof(float)) == 0);
    }
  }
  for (int j = 0; j < l1.height; ++j)
  {
    for (int i = 0; i < l1.width; ++i)
    {
      const int x = i * 2 + 1 < 61 ? i * 2 + 1 : 60, y = j * 2 + 1 < 47 ? j * 2 + 1 : 46;
      MRGI_CHECK(memcmp(mrgi_image_at(&l1, i, j), mrgi_image_at(&full, x, y),
                   MRGI_SSGI_CHANNELS * sizeof(float)) == 0);
    }
  }
  mrgi_error err;
  mrgi_image bad;
  MRGI_CHECK(mrgi_ssgi_compute(&s.params, &s.position, &s.normal, &s.albedo, &s.direct,
               MRGI_SSGI_MAX_LEVEL + 1, &bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "level") != NULL);
  MRGI_CHECK(bad.pixels == NULL);
  mrgi_image_destroy(&full);
  mrgi_image_destroy(&l1);
  mrgi_image_destroy(&l2);
  free_scene(&s);
}

/* Energy: a very bright wall, a large radius, many samples close to the
 * corner: every bounce stays <= albedo x the brightest sender, V in [0, 1]. */
static void test_energy(void)
{
  static scene s;
  make_scene(&s, 64, 48, -1.0f, 4.0f, 1.0f, 256, 3.0f, 0.0f);
  /* Make the wall send 1000 in red and the floor 1 in all channels. */
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      float* l = mrgi_image_at(&s.direct, x, y);
      l[0] = l[0] > 0.9f ? 1000.0f : 1.0f;
      l[1] = l[2] = 1.0f;
    }
  }
  mrgi_image out;
  MRGI_CHECK(mrgi_ssgi_compute(
               &s.params, &s.position, &s.normal, &s.albedo, &s.direct, 0, &out, NULL) == MRGI_OK);
  float largest = 0.0f;
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      const float* o = mrgi_image_at(&out, x, y);
      MRGI_CHECK(o[0] <= 0.5f * 1000.0f * (1.0f + 1e-5f));
      MRGI_CHECK(o[1] <= 0.5f * (1.0f + 1e-5f) && o[2] <= 0.5f * (1.0f + 1e-5f));
      MRGI_CHECK(o[0] >= 0.0f && o[1] >= 0.0f && o[2] >= 0.0f);
      MRGI_CHECK(o[3] >= 0.0f && o[3] <= 1.0f);
      largest = fmaxf(largest, o[0]);
    }
  }
  MRGI_CHECK(largest > 1.0f); /* the corner did bounce */
  mrgi_image_destroy(&out);
  free_scene(&s);
}

/* Energy where the per-sample clamp binds: a receiver 0.1 R in front of a
 * bright wall, facing it (a crevice). Unclamped, the senders' form factors
 * would sum far above 1 (X > 1000 here); clamped, X stays <= the wall's
 * radiance. The exact X is the wall's radiance (form factor 1); the
 * estimator gives about a third of it (0.34 L when written: senders far
 * across the disk get less than their share of the hemisphere), so the
 * lower bound only asks for a substantial bounce. */
static void test_energy_crevice(void)
{
  static scene s;
  make_scene(&s, 64, 48, 0.0f, 5.0f, 1.0f, 256, 1.0f, 0.0f);
  for (int y = 0; y < 48; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      float* l = mrgi_image_at(&s.direct, x, y);
      l[0] = l[1] = l[2] = 1000.0f;
    }
  }
  const float p[3] = { 0.0f, 0.0f, -4.9f }, n[3] = { 0.0f, 0.0f, -1.0f };
  const float albedo[3] = { 1.0f, 0.5f, 0.25f };
  mrgi_ssgi_result r;
  mrgi_ssgi_receiver(&s.params, &s.position, &s.normal, &s.direct, p, n, albedo, &r);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK(r.irradiance[c] <= 1000.0f * (1.0f + 1e-5f));
    MRGI_CHECK(r.irradiance[c] > 200.0f);
    MRGI_CHECK(r.radiance[c] == albedo[c] * r.irradiance[c]);
  }
  MRGI_CHECK(r.visibility < 0.5f);
  free_scene(&s);
}

/* Background, NaN and zero normals, NaN positions and light, invalid
 * parameters: errors or finite values, never NaN. */
static void test_invalid_input(void)
{
  static scene s;
  make_scene(&s, 32, 24, -1.0f, 5.0f, 1.0f, 16, 0.5f, 0.01f);
  for (int y = 0; y < 24; ++y)
  {
    for (int x = 0; x < 32; ++x)
    {
      const int kind = (x + 3 * y) % 5;
      if (kind == 0)
      {
        mrgi_image_at(&s.position, x, y)[3] = 0.0f; /* background */
      }
      else if (kind == 1)
      {
        mrgi_image_at(&s.normal, x, y)[0] = NAN;
      }
      else if (kind == 2)
      {
        memset(mrgi_image_at(&s.normal, x, y), 0, 3 * sizeof(float));
      }
      else if (kind == 3)
      {
        mrgi_image_at(&s.direct, x, y)[1] = INFINITY;
        mrgi_image_at(&s.position, x, y)[2] = NAN;
      }
    }
  }
  mrgi_image out;
  MRGI_CHECK(mrgi_ssgi_compute(
               &s.params, &s.position, &s.normal, &s.albedo, &s.direct, 0, &out, NULL) == MRGI_OK);
  int64_t bad = -1;
  /* The margin channel may be FLT_MAX, finite; none is NaN or infinite. */
  MRGI_CHECK(mrgi_image_count_nonfinite(&out, &bad, NULL) == MRGI_OK && bad == 0);
  for (int y = 0; y < 24; ++y)
  {
    for (int x = 0; x < 32; ++x)
    {
      const float* o = mrgi_image_at(&out, x, y);
      MRGI_CHECK(o[3] >= 0.0f && o[3] <= 1.0f);
      if ((x + 3 * y) % 5 <= 2)
      {
        MRGI_CHECK(o[0] == 0.0f && o[3] == 1.0f); /* no receiver */
      }
    }
  }
  mrgi_image_destroy(&out);
  mrgi_error err;
  mrgi_ssgi_params p = s.params;
  p.radius = NAN;
  MRGI_CHECK(mrgi_ssgi_compute(&p, &s.position, &s.normal, &s.albedo, &s.direct, 0, &out, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "radius") != NULL);
  p = s.params;
  p.bias = -1.0f;
  MRGI_CHECK(mrgi_ssgi_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "bias") != NULL);
  p = s.params;
  p.sample_count = 0;
  MRGI_CHECK(mrgi_ssgi_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p = s.params;
  p.projection[5] = INFINITY;
  MRGI_CHECK(mrgi_ssgi_params_validate(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_image small;
  MRGI_CHECK(mrgi_image_create(&small, 8, 8, 4, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_ssgi_compute(&s.params, &s.position, &s.normal, &s.albedo, &small, 0, &out,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "direct") != NULL);
  MRGI_CHECK(mrgi_ssgi_compute(&s.params, &s.position, NULL, &s.albedo, &s.direct, 0, &out, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  mrgi_image_destroy(&small);
  free_scene(&s);
}

/* A 1 x 1 G-buffer, any level. */
static void test_one_pixel(void)
{
  static scene s;
  make_scene(&s, 1, 1, -1.0f, 5.0f, 1.0f, 64, 0.5f, 0.01f);
  for (int level = 0; level <= MRGI_SSGI_MAX_LEVEL; level += MRGI_SSGI_MAX_LEVEL)
  {
    mrgi_image out;
    MRGI_CHECK(mrgi_ssgi_compute(&s.params, &s.position, &s.normal, &s.albedo, &s.direct, level,
                 &out, NULL) == MRGI_OK);
    MRGI_CHECK(out.width == 1 && out.height == 1);
    const float* o = mrgi_image_at(&out, 0, 0);
    MRGI_CHECK(isfinite(o[0]) && isfinite(o[3]) && o[3] >= 0.0f && o[3] <= 1.0f);
    mrgi_image_destroy(&out);
  }
  free_scene(&s);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_kernel),
    MRGI_TEST_CASE(test_flat_plane),
    MRGI_TEST_CASE(test_wall_bleeding),
    MRGI_TEST_CASE(test_scale_invariance),
    MRGI_TEST_CASE(test_levels),
    MRGI_TEST_CASE(test_energy),
    MRGI_TEST_CASE(test_energy_crevice),
    MRGI_TEST_CASE(test_invalid_input),
    MRGI_TEST_CASE(test_one_pixel),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
