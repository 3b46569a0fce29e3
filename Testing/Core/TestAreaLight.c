/* Tests of mrgi_area_light: validation; the texture pyramid (means, exact
 * block averages, GL sizes, storage contract); light samples (cover the
 * rectangle, areas, determinism, radiance of constant and power-of-two
 * textures, orientation); the diffuse gather against the closed-form
 * rectangle-to-point form factor and brute-force integrals, its point-light
 * limit, its early-outs and extremes (1 and 4096 samples, receivers in the
 * light's plane, edge-on, huge lights, black textures, scales 1e-6..1e6);
 * the Phong term (convergence, exact lobe peak, lobe-miss bound, the 5 x 5
 * lobe grid, the refinement metric). Reference values are computed here,
 * in double, independently of the code under test. */
#include "mrgi_area_light.h"
#include "mrgi_test.h"

#include <float.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

static int message_has(const mrgi_error* err, const char* text)
{
  if (!strstr(err->message, text))
  {
    fprintf(stderr, "message '%s' lacks '%s'\n", err->message, text);
    return 0;
  }
  return 1;
}

static void set3(double v[3], double x, double y, double z)
{
  v[0] = x;
  v[1] = y;
  v[2] = z;
}

/* A white light of intensity `intensity`, centre c, edges u and v. */
static mrgi_area_light make_light(double cx, double cy, double cz, double ux, double uy, double uz,
                                  double vx, double vy, double vz, double intensity)
{
  mrgi_area_light light;
  memset(&light, 0, sizeof(light));
  set3(light.center, cx, cy, cz);
  set3(light.edge_u, ux, uy, uz);
  set3(light.edge_v, vx, vy, vz);
  set3(light.color, 1.0, 1.0, 1.0);
  light.intensity = intensity;
  return light;
}

/* A side x side light at height h over the origin, facing DOWN (u = +x,
 * v = -y: u x v = -z). */
static mrgi_area_light ceiling_light(double side, double h, double intensity)
{
  return make_light(0, 0, h, side, 0, 0, 0, -side, 0, intensity);
}

/* A random texture, values in [0, 1), deterministic. */
static mrgi_image random_texture(int32_t w, int32_t h, int32_t channels, uint64_t seed)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, w, h, channels, NULL) == MRGI_OK);
  uint64_t state = seed;
  for (size_t i = 0; i < mrgi_image_value_count(&img); ++i)
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    img.pixels[i] = (float)((double)(state >> 40) / (double)(1ULL << 24));
  }
  return img;
}

static mrgi_image constant_texture(int32_t w, int32_t h, float r, float g, float b)
{
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, w, h, 3, NULL) == MRGI_OK);
  for (int64_t i = 0; i < (int64_t)w * h; ++i)
  {
    img.pixels[3 * i] = r;
    img.pixels[3 * i + 1] = g;
    img.pixels[3 * i + 2] = b;
  }
  return img;
}

/* Samples of a light (pyramid built here when textured); returns the count. */
typedef struct light_samples
{
  mrgi_area_light_texture_pyramid pyramid;
  mrgi_area_light_uniforms uniforms;
  mrgi_area_light_sample* samples;
  int32_t count;
} light_samples;

static light_samples make_samples(const mrgi_area_light* light, int32_t n, int32_t jitter,
                                 uint64_t seed)
{
  light_samples t;
  memset(&t, 0, sizeof(t));
  mrgi_error err;
  MRGI_CHECK(mrgi_area_light_texture_pyramid_create(&t.pyramid, light->texture, &err) == MRGI_OK);
  t.samples = (mrgi_area_light_sample*)malloc(sizeof(mrgi_area_light_sample) * (size_t)n);
  MRGI_CHECK(t.samples != NULL);
  const mrgi_status s =
    mrgi_area_light_make_samples(light, &t.pyramid, n, jitter, seed, t.samples, n, &t.count, &err);
  if (s)
  {
    fprintf(stderr, "make_samples: %s\n", err.message);
  }
  MRGI_CHECK(s == MRGI_OK);
  MRGI_CHECK(mrgi_area_light_uniforms_init(light, &t.pyramid, &t.uniforms, &err) == MRGI_OK);
  return t;
}

static void free_samples(light_samples* t)
{
  mrgi_area_light_texture_pyramid_destroy(&t->pyramid);
  free(t->samples);
}

static void diffuse_at(const light_samples* t, double px, double py, double pz, double nx, double ny,
                       double nz, float out[3])
{
  const float p[3] = { (float)px, (float)py, (float)pz };
  const float n[3] = { (float)nx, (float)ny, (float)nz };
  mrgi_area_light_diffuse(&t->uniforms, t->samples, t->count, p, n, out);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK(isfinite(out[c]) && out[c] >= 0.0f);
  }
}

/* ---- closed forms and brute-force integrals (double) ---- */

/* View factor from a differential area to a parallel rectangle at distance
 * h, normal through a corner, sides a and b (Hottel; Howell's catalogue of
 * configuration factors, case B-3). */
static double view_factor_corner(double a, double b, double h)
{
  const double A = a / h, B = b / h;
  const double sa = sqrt(1.0 + A * A), sb = sqrt(1.0 + B * B);
  return (A / sa * atan(B / sa) + B / sb * atan(A / sb)) / (2.0 * pi);
}

/* ...any parallel rectangle [x0, x1] x [y0, y1] relative to the element. */
static double view_factor_rect(double x0, double x1, double y0, double y1, double h)
{
  const double xs[2] = { x0, x1 }, ys[2] = { y0, y1 };
  double f = 0.0;
  for (int i = 0; i < 2; ++i)
  {
    for (int j = 0; j < 2; ++j)
    {
      const double sign = ((i == j) ? 1.0 : -1.0) * (xs[i] < 0 ? -1.0 : 1.0) * (ys[j] < 0 ? -1.0 : 1.0);
      f += sign * view_factor_corner(fabs(xs[i]), fabs(ys[j]), h);
    }
  }
  return f;
}

/* Midpoint-rule integrals over the light on an m x m grid of its (s, t):
 * diffuse X = (1/pi) int L cos_p cos_y / r^2 dA and, when power >= 0,
 * specular S = int (n+2)/(2 pi) max(0, R.w)^n L cos_p cos_y / r^2 dA
 * (mrgi_area_light.h). L from mrgi_area_light_emitted() (the exact texel). */
static void brute_force(const mrgi_area_light* light, const double p[3], const double n_in[3],
                        const double r_dir[3], double power, int32_t m, double out[3])
{
  double ln[3];
  ln[0] = light->edge_u[1] * light->edge_v[2] - light->edge_u[2] * light->edge_v[1];
  ln[1] = light->edge_u[2] * light->edge_v[0] - light->edge_u[0] * light->edge_v[2];
  ln[2] = light->edge_u[0] * light->edge_v[1] - light->edge_u[1] * light->edge_v[0];
  const double area = sqrt(ln[0] * ln[0] + ln[1] * ln[1] + ln[2] * ln[2]);
  for (int k = 0; k < 3; ++k)
  {
    ln[k] /= area;
  }
  const double nl = sqrt(n_in[0] * n_in[0] + n_in[1] * n_in[1] + n_in[2] * n_in[2]);
  const double n[3] = { n_in[0] / nl, n_in[1] / nl, n_in[2] / nl };
  const double da = area / ((double)m * m);
  double sum[3] = { 0, 0, 0 };
  for (int32_t j = 0; j < m; ++j)
  {
    const double t = (j + 0.5) / m;
    for (int32_t i = 0; i < m; ++i)
    {
      const double s = (i + 0.5) / m;
      double d[3];
      for (int k = 0; k < 3; ++k)
      {
        d[k] = light->center[k] + (s - 0.5) * light->edge_u[k] + (t - 0.5) * light->edge_v[k] - p[k];
      }
      const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      const double r = sqrt(r2);
      const double cp = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / r;
      double cy = -(ln[0] * d[0] + ln[1] * d[1] + ln[2] * d[2]) / r;
      if (light->two_sided)
      {
        cy = fabs(cy);
      }
      if (!(cp > 0.0 && cy > 0.0))
      {
        continue;
      }
      double f = 1.0 / pi;
      if (power >= 0.0)
      {
        const double rw = (r_dir[0] * d[0] + r_dir[1] * d[1] + r_dir[2] * d[2]) / r;
        if (!(rw > 0.0))
        {
          continue;
        }
        f = (power + 2.0) / (2.0 * pi) * pow(rw, power);
      }
      double l[3];
      mrgi_area_light_emitted(light, s, t, l);
      for (int c = 0; c < 3; ++c)
      {
        sum[c] += l[c] * f * cp * cy / r2 * da;
      }
    }
  }
  out[0] = sum[0];
  out[1] = sum[1];
  out[2] = sum[2];
}

/* The sample sums of the header, in double, with no early-out at all. */
static void sample_sums(const light_samples* t, const double p[3], const double n_in[3],
                        const double r_dir[3], double power, double diffuse[3], double specular[3])
{
  const double nl = sqrt(n_in[0] * n_in[0] + n_in[1] * n_in[1] + n_in[2] * n_in[2]);
  const double n[3] = { n_in[0] / nl, n_in[1] / nl, n_in[2] / nl };
  for (int c = 0; c < 3; ++c)
  {
    diffuse[c] = specular[c] = 0.0;
  }
  for (int32_t j = 0; j < t->count; ++j)
  {
    const mrgi_area_light_sample* s = &t->samples[j];
    const double d[3] = { s->position[0] - p[0], s->position[1] - p[1], s->position[2] - p[2] };
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(r2 > 0.0))
    {
      continue;
    }
    const double ci = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    double cj = -(s->normal[0] * d[0] + s->normal[1] * d[1] + s->normal[2] * d[2]);
    if (t->uniforms.two_sided)
    {
      cj = fabs(cj);
    }
    if (!(ci > 0.0 && cj > 0.0))
    {
      continue;
    }
    const double transfer = s->area * (ci * cj / r2) / (pi * r2 + s->area);
    double lobe = 0.0;
    if (r_dir)
    {
      const double rw = (r_dir[0] * d[0] + r_dir[1] * d[1] + r_dir[2] * d[2]) / sqrt(r2);
      lobe = rw > 0.0 ? 0.5 * (power + 2.0) * pow(rw, power) : 0.0;
    }
    for (int c = 0; c < 3; ++c)
    {
      diffuse[c] += s->radiance[c] * transfer;
      specular[c] += s->radiance[c] * transfer * lobe;
    }
  }
}

static void reflect_dir(const double n_in[3], const double v_in[3], double r[3])
{
  const double nl = sqrt(n_in[0] * n_in[0] + n_in[1] * n_in[1] + n_in[2] * n_in[2]);
  const double vl = sqrt(v_in[0] * v_in[0] + v_in[1] * v_in[1] + v_in[2] * v_in[2]);
  const double n[3] = { n_in[0] / nl, n_in[1] / nl, n_in[2] / nl };
  const double v[3] = { v_in[0] / vl, v_in[1] / vl, v_in[2] / vl };
  const double nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
  for (int k = 0; k < 3; ++k)
  {
    r[k] = 2.0 * nv * n[k] - v[k];
  }
}

static double rel(double a, double b)
{
  return fabs(a - b) / fabs(b);
}

/* ---- 1. validation ---- */

#define EXPECT_BAD(change, text)                                                   \
  do {                                                                             \
    mrgi_area_light bad_ = good;                                                   \
    mrgi_area_light* light = &bad_;                                                \
    (void)light;                                                                   \
    change;                                                                        \
    mrgi_error e_;                                                                 \
    MRGI_CHECK(mrgi_area_light_check(&bad_, &e_) == MRGI_ERR_INVALID_ARGUMENT);    \
    MRGI_CHECK(e_.status == MRGI_ERR_INVALID_ARGUMENT);                            \
    MRGI_CHECK(message_has(&e_, text));                                            \
  } while (0)

static void test_validation(void)
{
  mrgi_image texture = random_texture(4, 3, 3, 1);
  mrgi_area_light good = make_light(1, 2, 3, 2, 0, 0, 0, 0, 0.5, 3.0);
  good.texture = &texture;
  mrgi_error err;
  MRGI_CHECK(mrgi_area_light_check(&good, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_area_light_check(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "NULL"));

  EXPECT_BAD(light->center[1] = NAN, "center[1]");
  EXPECT_BAD(light->edge_u[0] = INFINITY, "edge_u[0]");
  EXPECT_BAD(light->edge_v[2] = -INFINITY, "edge_v[2]");
  EXPECT_BAD(light->edge_v[2] = 0.0, "edge_v is a zero-length edge");
  EXPECT_BAD(set3(light->edge_u, 0, 0, 0), "edge_u is a zero-length edge");
  EXPECT_BAD(set3(light->edge_v, 4, 0, 0), "parallel");
  EXPECT_BAD(set3(light->edge_v, 0.01, 0, 0.5), "not perpendicular");
  EXPECT_BAD(light->intensity = -1.0, "intensity");
  EXPECT_BAD(light->intensity = NAN, "intensity");
  EXPECT_BAD(light->color[1] = -0.5, "color[1]");
  EXPECT_BAD(light->color[2] = INFINITY, "color[2]");
  EXPECT_BAD((light->intensity = 1e30, light->color[0] = 1e10), "float range");
  EXPECT_BAD((set3(light->edge_u, 1e-30, 0, 0), set3(light->edge_v, 0, 1e-30, 0)), "float range");

  /* textures: zero size, no pixels, wrong channels, NaN / negative / inf texels */
  mrgi_image broken = texture;
  broken.width = 0;
  EXPECT_BAD(light->texture = &broken, "texture: image width 0");
  broken = texture;
  broken.pixels = NULL;
  EXPECT_BAD(light->texture = &broken, "texture: image 4x3x3 has no pixel buffer");
  mrgi_image two = random_texture(2, 2, 2, 3);
  EXPECT_BAD(light->texture = &two, "texture has 2 channels");
  mrgi_image_destroy(&two);
  mrgi_image_at(&texture, 2, 1)[1] = NAN;
  EXPECT_BAD((void)0, "texture texel (2, 1) channel 1");
  mrgi_image_at(&texture, 2, 1)[1] = -1.0f;
  EXPECT_BAD((void)0, "texture texel (2, 1) channel 1");
  mrgi_image_at(&texture, 2, 1)[1] = INFINITY;
  EXPECT_BAD((void)0, "texture texel (2, 1) channel 1");
  mrgi_image_at(&texture, 2, 1)[1] = 0.5f;
  MRGI_CHECK(mrgi_area_light_check(&good, &err) == MRGI_OK);
  /* an RGBA texture is fine (alpha is ignored, even NaN) */
  mrgi_image rgba = random_texture(3, 3, 4, 4);
  rgba.pixels[3] = NAN;
  good.texture = &rgba;
  MRGI_CHECK(mrgi_area_light_check(&good, &err) == MRGI_OK);

  /* sample requests */
  int32_t sx = 0, sy = 0, count = 0;
  MRGI_CHECK(mrgi_area_light_sample_layout(&good, 0, &sx, &sy, &count, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "sample count 0 is outside 1..4096"));
  MRGI_CHECK(mrgi_area_light_sample_layout(&good, 4097, &sx, &sy, &count, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  mrgi_area_light_sample samples[16];
  memset(samples, 0x5A, sizeof(samples));
  MRGI_CHECK(mrgi_area_light_make_samples(&good, NULL, 4, 0, 1, samples, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "no texture pyramid"));
  mrgi_area_light_texture_pyramid wrong;
  MRGI_CHECK(mrgi_area_light_texture_pyramid_create(&wrong, &texture, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_area_light_make_samples(&good, &wrong, 4, 0, 1, samples, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "is not the pyramid"));
  good.texture = NULL;
  MRGI_CHECK(mrgi_area_light_make_samples(&good, &wrong, 4, 0, 1, samples, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "has no texture"));
  mrgi_area_light_texture_pyramid_destroy(&wrong);
  MRGI_CHECK(mrgi_area_light_make_samples(&good, NULL, 16, 0, 1, samples, 15, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "capacity 15"));
  MRGI_CHECK(mrgi_area_light_make_samples(&good, NULL, 4, 2, 1, samples, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "jitter"));
  MRGI_CHECK(mrgi_area_light_make_samples(&good, NULL, 4, 0, 1, NULL, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  good.intensity = -2.0;
  MRGI_CHECK(mrgi_area_light_make_samples(&good, NULL, 4, 0, 1, samples, 4, NULL, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "intensity"));
  /* nothing written on failure */
  const unsigned char* bytes = (const unsigned char*)samples;
  for (size_t i = 0; i < sizeof(samples); ++i)
  {
    MRGI_CHECK(bytes[i] == 0x5A);
  }
  mrgi_area_light_uniforms uniforms;
  MRGI_CHECK(mrgi_area_light_uniforms_init(&good, NULL, &uniforms, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_area_light_uniforms_init(&good, NULL, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_image_destroy(&rgba);
  mrgi_image_destroy(&texture);
  printf("validation: ok\n");
}

/* ---- 2. texture pyramid ---- */

static void level_mean(const mrgi_area_light_texture_pyramid* p, int32_t k, double mean[3])
{
  const size_t n = (size_t)p->width[k] * (size_t)p->height[k];
  mean[0] = mean[1] = mean[2] = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      mean[c] += p->texels[p->offset[k] + 3 * i + c];
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    mean[c] /= (double)n;
  }
}

static void test_pyramid(void)
{
  mrgi_error err;
  /* non-power-of-two: GL sizes, same mean at every level */
  mrgi_image texture = random_texture(37, 23, 4, 7);
  mrgi_area_light_texture_pyramid p;
  MRGI_CHECK(mrgi_area_light_texture_pyramid_create(&p, &texture, &err) == MRGI_OK);
  const int32_t widths[6] = { 37, 18, 9, 4, 2, 1 }, heights[6] = { 23, 11, 5, 2, 1, 1 };
  MRGI_CHECK(p.level_count == 6 && p.owned == 1);
  size_t floats = 0;
  for (int32_t k = 0; k < 6; ++k)
  {
    MRGI_CHECK(p.width[k] == widths[k] && p.height[k] == heights[k]);
    MRGI_CHECK(p.offset[k] == floats);
    floats += 3 * (size_t)widths[k] * (size_t)heights[k];
  }
  MRGI_CHECK(p.float_count == floats && mrgi_area_light_texture_pyramid_float_count(37, 23) == floats);
  /* level 0 is the texture's RGB (alpha dropped) */
  MRGI_CHECK(p.texels[3 * (5 * 37 + 11) + 2] == mrgi_image_at(&texture, 11, 5)[2]);
  double mean0[3];
  level_mean(&p, 0, mean0);
  for (int32_t k = 1; k < 6; ++k)
  {
    double mean[3];
    level_mean(&p, k, mean);
    for (int c = 0; c < 3; ++c)
    {
      MRGI_CHECK_NEAR(mean[c], mean0[c], 1e-6);
    }
  }
  /* the footprint box: level-1 texel (17, 10) covers x in [37/18*17, 37),
   * y in [23/11*10, 23) of level 0 */
  {
    const double rx = 37.0 / 18.0, ry = 23.0 / 11.0;
    double sum = 0.0;
    for (int32_t y = 0; y < 23; ++y)
    {
      for (int32_t x = 0; x < 37; ++x)
      {
        const double ox = fmax(0.0, fmin(x + 1.0, 18 * rx) - fmax((double)x, 17 * rx));
        const double oy = fmax(0.0, fmin(y + 1.0, 11 * ry) - fmax((double)y, 10 * ry));
        sum += ox * oy * mrgi_image_at(&texture, x, y)[0];
      }
    }
    MRGI_CHECK_NEAR(p.texels[p.offset[1] + 3 * (10 * 18 + 17)], sum / (rx * ry), 1e-6);
  }
  mrgi_area_light_texture_pyramid_destroy(&p);
  mrgi_area_light_texture_pyramid_destroy(&p); /* idempotent */
  mrgi_area_light_texture_pyramid_destroy(NULL);
  mrgi_image_destroy(&texture);

  /* power of two, caller storage: a level-k texel is the mean of its
   * 2^k x 2^k block */
  texture = random_texture(16, 8, 3, 9);
  const size_t need = mrgi_area_light_texture_pyramid_float_count(16, 8);
  MRGI_CHECK(need == 3 * (128 + 32 + 8 + 2 + 1));
  float* storage = (float*)malloc(need * sizeof(float));
  MRGI_CHECK(storage != NULL);
  MRGI_CHECK(mrgi_area_light_texture_pyramid_init(&p, &texture, storage, need - 1, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "needs 513"));
  MRGI_CHECK(p.texels == NULL && p.level_count == 0);
  MRGI_CHECK(mrgi_area_light_texture_pyramid_init(&p, &texture, storage, need, &err) == MRGI_OK);
  MRGI_CHECK(p.owned == 0 && p.texels == storage && p.level_count == 5);
  for (int32_t k = 1; k < 5; ++k)
  {
    const int32_t b = 1 << k;
    for (int32_t y = 0; y < p.height[k]; ++y)
    {
      for (int32_t x = 0; x < p.width[k]; ++x)
      {
        for (int c = 0; c < 3; ++c)
        {
          double sum = 0.0;
          int32_t n = 0;
          for (int32_t yy = y * b; yy < (y + 1) * b && yy < 8; ++yy)
          {
            for (int32_t xx = x * b; xx < (x + 1) * b; ++xx)
            {
              sum += mrgi_image_at(&texture, xx, yy)[c];
              ++n;
            }
          }
          /* the last levels (2x1, 1x1) average whole rows: 8 rows only */
          MRGI_CHECK_NEAR(p.texels[p.offset[k] + 3 * ((size_t)y * p.width[k] + x) + c], sum / n,
                          1e-6);
        }
      }
    }
  }
  /* trilinear lookups: texel centres return texels, lod between levels mixes */
  float rgb[3];
  mrgi_area_light_texture_sample(&p, (5 + 0.5f) / 16.0f, 1.0f - (2 + 0.5f) / 8.0f, 0.0f, rgb);
  MRGI_CHECK_NEAR(rgb[1], mrgi_image_at(&texture, 5, 2)[1], 1e-6);
  mrgi_area_light_texture_sample(&p, (3 + 0.5f) / 8.0f, 1.0f - (1 + 0.5f) / 4.0f, 1.0f, rgb);
  const float l1 = p.texels[p.offset[1] + 3 * (1 * 8 + 3)];
  MRGI_CHECK_NEAR(rgb[0], l1, 1e-6);
  float below[3];
  mrgi_area_light_texture_sample(&p, 0.5f, 0.5f, 2.0f, below);
  float above[3];
  mrgi_area_light_texture_sample(&p, 0.5f, 0.5f, 3.0f, above);
  mrgi_area_light_texture_sample(&p, 0.5f, 0.5f, 2.25f, rgb);
  MRGI_CHECK_NEAR(rgb[2], 0.75 * below[2] + 0.25 * above[2], 1e-6);
  mrgi_area_light_texture_sample(&p, 0.3f, 0.9f, 40.0f, rgb); /* clamped to the 1x1 level */
  MRGI_CHECK_NEAR(rgb[0], p.texels[p.offset[4]], 1e-7);
  mrgi_area_light_texture_sample(&p, 0.0f, 1.0f, -3.0f, rgb); /* clamp to edge, top-left */
  MRGI_CHECK_NEAR(rgb[0], mrgi_image_at(&texture, 0, 0)[0], 1e-7);
  mrgi_area_light_texture_pyramid_destroy(&p); /* caller storage: not freed */
  MRGI_CHECK(storage[0] == mrgi_image_at(&texture, 0, 0)[0]);
  free(storage);
  mrgi_image_destroy(&texture);

  /* no texture: 1x1 white */
  MRGI_CHECK(mrgi_area_light_texture_pyramid_create(&p, NULL, &err) == MRGI_OK);
  MRGI_CHECK(p.level_count == 1 && p.width[0] == 1 && p.texels[0] == 1.0f && p.texels[2] == 1.0f);
  mrgi_area_light_texture_pyramid_destroy(&p);
  MRGI_CHECK(mrgi_area_light_texture_pyramid_create(NULL, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_area_light_texture_pyramid_float_count(0, 4) == 0);
  printf("pyramid: ok\n");
}

/* ---- 3. light samples ---- */

static void test_layout(void)
{
  struct
  {
    double lu, lv;
    int32_t n, sx, sy;
  } cases[] = { { 1, 1, 256, 16, 16 }, { 1, 1, 4096, 64, 64 }, { 16, 1, 4096, 256, 16 },
                { 1, 16, 4096, 16, 256 }, { 1, 1, 1000, 32, 31 }, { 1, 1, 1, 1, 1 },
                { 1, 1, 7, 3, 2 }, { 1e4, 1, 256, 256, 1 }, { 1, 1e4, 256, 1, 256 },
                { 2, 1, 2, 2, 1 } };
  for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]); ++k)
  {
    mrgi_area_light light = make_light(0, 0, 0, cases[k].lu, 0, 0, 0, cases[k].lv, 0, 1);
    int32_t sx = 0, sy = 0, count = 0;
    MRGI_CHECK(mrgi_area_light_sample_layout(&light, cases[k].n, &sx, &sy, &count, NULL) == MRGI_OK);
    if (sx != cases[k].sx || sy != cases[k].sy)
    {
      fprintf(stderr, "layout %g x %g, N %d: %d x %d\n", cases[k].lu, cases[k].lv,
              (int)cases[k].n, (int)sx, (int)sy);
    }
    MRGI_CHECK(sx == cases[k].sx && sy == cases[k].sy && count == sx * sy && count <= cases[k].n);
  }
}

/* Local coordinates (a, b) in [-1/2, 1/2]^2 of a point of a light. */
static void local_coords(const mrgi_area_light* light, const float p[3], double* a, double* b)
{
  const double uu = light->edge_u[0] * light->edge_u[0] + light->edge_u[1] * light->edge_u[1] +
                    light->edge_u[2] * light->edge_u[2];
  const double vv = light->edge_v[0] * light->edge_v[0] + light->edge_v[1] * light->edge_v[1] +
                    light->edge_v[2] * light->edge_v[2];
  double pu = 0.0, pv = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    pu += ((double)p[k] - light->center[k]) * light->edge_u[k];
    pv += ((double)p[k] - light->center[k]) * light->edge_v[k];
  }
  *a = pu / uu;
  *b = pv / vv;
}

static void test_samples(void)
{
  test_layout();
  /* a tilted 3 x 1.5 light */
  const double s2 = sqrt(0.5);
  mrgi_area_light light = make_light(1, -2, 5, 3 * s2, 0, 3 * s2, 0, 1.5, 0, 2.0);
  light.color[1] = 0.5;
  for (int32_t jitter = 0; jitter < 2; ++jitter)
  {
    light_samples t = make_samples(&light, 256, jitter, 42);
    int32_t sx = 0, sy = 0;
    MRGI_CHECK(mrgi_area_light_sample_layout(&light, 256, &sx, &sy, NULL, NULL) == MRGI_OK);
    MRGI_CHECK(sx == 23 && sy == 11 && t.count == 253);
    double area = 0.0;
    for (int32_t k = 0; k < t.count; ++k)
    {
      const mrgi_area_light_sample* s = &t.samples[k];
      double a, b;
      local_coords(&light, s->position, &a, &b);
      /* inside the rectangle, in its own cell */
      const int32_t i = (int32_t)floor((a + 0.5) * sx), j = (int32_t)floor((b + 0.5) * sy);
      MRGI_CHECK(i == k % sx && j == k / sx);
      if (!jitter)
      {
        MRGI_CHECK_NEAR(a, (i + 0.5) / sx - 0.5, 1e-6);
        MRGI_CHECK_NEAR(b, (j + 0.5) / sy - 0.5, 1e-6);
      }
      MRGI_CHECK_NEAR(s->normal[0], -s2 * 1.0, 1e-7); /* (3s2,0,3s2) x (0,1.5,0) / 4.5 */
      MRGI_CHECK_NEAR(s->normal[1], 0.0, 0.0);
      MRGI_CHECK_NEAR(s->normal[2], s2, 1e-7);
      MRGI_CHECK(s->radiance[0] == 2.0f && s->radiance[1] == 1.0f && s->radiance[2] == 2.0f);
      MRGI_CHECK(s->pad0 == 0.0f && s->pad1 == 0.0f);
      area += s->area;
    }
    MRGI_CHECK_NEAR(area, 4.5, 4.5e-6);
    MRGI_CHECK(mrgi_area_light_sample_texture_data(t.samples) == (const float*)t.samples);
    free_samples(&t);
  }
  /* deterministic for a seed, different across seeds */
  light_samples a = make_samples(&light, 100, 1, 7), b = make_samples(&light, 100, 1, 7);
  light_samples c = make_samples(&light, 100, 1, 8);
  MRGI_CHECK(a.count == 98 && b.count == 98 && c.count == 98); /* 14 x 7 */
  MRGI_CHECK(memcmp(a.samples, b.samples, 98 * sizeof(*a.samples)) == 0);
  MRGI_CHECK(memcmp(a.samples, c.samples, 98 * sizeof(*a.samples)) != 0);
  free_samples(&a);
  free_samples(&b);
  free_samples(&c);

  /* a constant texture gives colour * intensity * texel at every level */
  const int32_t sizes[5][2] = { { 64, 64 }, { 37, 23 }, { 1, 1 }, { 5, 300 }, { 1024, 3 } };
  const int32_t counts[5] = { 1, 7, 256, 1000, 4096 };
  for (int s = 0; s < 5; ++s)
  {
    mrgi_image texture = constant_texture(sizes[s][0], sizes[s][1], 0.25f, 0.5f, 1.5f);
    light.texture = &texture;
    for (int n = 0; n < 5; ++n)
    {
      light_samples t = make_samples(&light, counts[n], 1, 3);
      for (int32_t k = 0; k < t.count; ++k)
      {
        MRGI_CHECK_NEAR(t.samples[k].radiance[0], 2.0 * 0.25, 1e-6);
        MRGI_CHECK_NEAR(t.samples[k].radiance[1], 2.0 * 0.5 * 0.5, 1e-6);
        MRGI_CHECK_NEAR(t.samples[k].radiance[2], 2.0 * 1.5, 3e-6);
      }
      free_samples(&t);
    }
    mrgi_image_destroy(&texture);
  }

  /* power-of-two texture and grid: each sample carries its cell's exact mean,
   * so the samples' flux is the light's exact flux; orientation: sample
   * (i, j) of a 64 x 64 grid on a 64 x 64 texture is texel (i, 63 - j) */
  mrgi_image texture = random_texture(64, 64, 3, 11);
  mrgi_area_light square = make_light(0, 0, 0, 2, 0, 0, 0, 2, 0, 3.0);
  square.texture = &texture;
  for (int32_t n = 16; n <= 4096; n *= 4)
  {
    light_samples t = make_samples(&square, n, 1, 5);
    const int32_t side = (int32_t)sqrt((double)n), block = 64 / side;
    double flux = 0.0, exact = 0.0;
    double worst = 0.0;
    for (int32_t j = 0; j < side; ++j)
    {
      for (int32_t i = 0; i < side; ++i)
      {
        double mean = 0.0;
        for (int32_t y = 64 - (j + 1) * block; y < 64 - j * block; ++y)
        {
          for (int32_t x = i * block; x < (i + 1) * block; ++x)
          {
            mean += mrgi_image_at(&texture, x, y)[1];
          }
        }
        mean *= 3.0 / (block * block);
        const mrgi_area_light_sample* s = &t.samples[j * side + i];
        worst = fmax(worst, fabs(s->radiance[1] - mean));
        flux += s->radiance[1] * s->area;
        exact += mean * 4.0 / n;
      }
    }
    MRGI_CHECK(worst < 2e-6);
    double emitted = 0.0;
    for (int32_t y = 0; y < 64; ++y)
    {
      for (int32_t x = 0; x < 64; ++x)
      {
        emitted += 3.0 * mrgi_image_at(&texture, x, y)[1] * 4.0 / 4096.0;
      }
    }
    MRGI_CHECK_NEAR(flux, emitted, 1e-5 * emitted);
    MRGI_CHECK_NEAR(exact, emitted, 1e-9 * emitted + 1e-12);
    if (n == 4096)
    {
      for (int32_t k = 0; k < 4096; k += 97)
      {
        const int32_t i = k % 64, j = k / 64;
        MRGI_CHECK_NEAR(t.samples[k].radiance[0], 3.0 * mrgi_image_at(&texture, i, 63 - j)[0], 2e-6);
        double l[3];
        mrgi_area_light_emitted(&square, (i + 0.5) / 64, (j + 0.5) / 64, l);
        MRGI_CHECK_NEAR(t.samples[k].radiance[0], l[0], 2e-6);
      }
    }
    free_samples(&t);
  }
  /* the top-left texel lights the corner c - u/2 + v/2 */
  double l[3];
  mrgi_area_light_emitted(&square, 0.0, 1.0, l);
  MRGI_CHECK(l[2] == 3.0 * mrgi_image_at(&texture, 0, 0)[2]);
  mrgi_area_light_emitted(&square, 1.0, 0.0, l);
  MRGI_CHECK(l[2] == 3.0 * mrgi_image_at(&texture, 63, 63)[2]);
  mrgi_image_destroy(&texture);
  printf("samples: ok\n");
}

/* ---- 4. diffuse: closed form, brute force, point limit ---- */

static void test_diffuse_convergence(void)
{
  /* unit square light at height 1 facing down, receivers facing up:
   * X = L * F (Hottel's view factor) */
  const double L = 2.5;
  mrgi_area_light light = ceiling_light(1.0, 1.0, L);
  const double receivers[3][2] = { { 0, 0 }, { 0.7, 0.2 }, { -1.5, 0.4 } };
  printf("diffuse vs closed form (unit square at height 1), relative error:\n");
  printf("   N  centre      (0.7,0.2)   (-1.5,0.4)  | jittered centre\n");
  double last[3] = { 0, 0, 0 }, first[3] = { 0, 0, 0 };
  for (int32_t n = 1; n <= 4096; n *= 4)
  {
    light_samples t = make_samples(&light, n, 0, 1);
    light_samples tj = make_samples(&light, n, 1, 1);
    double errors[3];
    for (int r = 0; r < 3; ++r)
    {
      const double x = receivers[r][0], y = receivers[r][1];
      /* the light spans [-1/2, 1/2]^2 above; relative to the receiver: */
      const double exact = L * view_factor_rect(-0.5 - x, 0.5 - x, -0.5 - y, 0.5 - y, 1.0);
      float out[3];
      diffuse_at(&t, x, y, 0, 0, 0, 1, out);
      MRGI_CHECK(out[0] == out[1] && out[1] == out[2]);
      errors[r] = rel(out[0], exact);
      if (n == 1)
      {
        first[r] = errors[r];
      }
      last[r] = errors[r];
    }
    float jittered[3];
    diffuse_at(&tj, 0, 0, 0, 0, 0, 1, jittered);
    const double exact0 = L * view_factor_rect(-0.5, 0.5, -0.5, 0.5, 1.0);
    printf("%5d  %.3e   %.3e   %.3e   | %.3e\n", (int)t.count, errors[0], errors[1], errors[2],
           rel(jittered[0], exact0));
    if (n == 4096)
    {
      MRGI_CHECK(rel(jittered[0], exact0) < 2e-3);
    }
    free_samples(&t);
    free_samples(&tj);
  }
  for (int r = 0; r < 3; ++r)
  {
    MRGI_CHECK(last[r] < 5e-4);
    MRGI_CHECK(last[r] < 0.05 * first[r]);
  }

  /* tilted receiver, textured two-sided light, against the brute-force
   * integral of the exact texels */
  mrgi_image texture = random_texture(64, 64, 3, 21);
  light.texture = &texture;
  light.two_sided = 1;
  const double p[3] = { 0.3, -0.2, -0.6 }; /* below the light: sees its front */
  const double n_up[3] = { 0.3, 0.1, 1.0 };
  const double q[3] = { 0.1, 0.2, 1.8 }; /* above it: sees its back (two-sided) */
  const double n_down[3] = { -0.2, 0.0, -1.0 };
  double exact_p[3], exact_q[3];
  brute_force(&light, p, n_up, NULL, -1.0, 2048, exact_p);
  brute_force(&light, q, n_down, NULL, -1.0, 2048, exact_q);
  double errors[2] = { 0, 0 };
  for (int32_t n = 64; n <= 4096; n *= 4)
  {
    light_samples t = make_samples(&light, n, 1, 9);
    float out_p[3], out_q[3];
    diffuse_at(&t, p[0], p[1], p[2], n_up[0], n_up[1], n_up[2], out_p);
    diffuse_at(&t, q[0], q[1], q[2], n_down[0], n_down[1], n_down[2], out_q);
    errors[0] = rel(out_p[1], exact_p[1]);
    errors[1] = rel(out_q[2], exact_q[2]);
    printf("textured two-sided light, N %4d: front %.3e, back %.3e\n", (int)n, errors[0], errors[1]);
    free_samples(&t);
  }
  MRGI_CHECK(errors[0] < 2e-3 && errors[1] < 2e-3);
  /* the same light one-sided: nothing reaches q */
  light.two_sided = 0;
  light_samples t = make_samples(&light, 256, 1, 9);
  float out[3];
  diffuse_at(&t, q[0], q[1], q[2], n_down[0], n_down[1], n_down[2], out);
  MRGI_CHECK(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f);
  free_samples(&t);
  mrgi_image_destroy(&texture);
}

static void test_point_limit(void)
{
  /* a tiny square of radiance L and area A at height 1, tilted 30 degrees
   * about x: a Lambertian point source of power L A. */
  const double L = 7.0;
  const double c30 = cos(pi / 6), s30 = sin(pi / 6);
  const double receiver[3] = { 0.3, 0.4, 0.0 };
  double previous = INFINITY;
  for (double side = 0.1; side >= 1e-3; side *= 0.1)
  {
    /* u = side x, v = side (0, -c30, s30): normal u x v = (0, -s30, -c30) */
    mrgi_area_light light = make_light(0, 0, 1, side, 0, 0, 0, -side * c30, side * s30, L);
    const double normal[3] = { 0, -s30, -c30 };
    const double d[3] = { -receiver[0], -receiver[1], 1.0 - receiver[2] };
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double cos_p = d[2] / sqrt(r2);
    const double cos_y = -(normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2]) / sqrt(r2);
    const double point = L * side * side * cos_p * cos_y / (pi * r2);
    for (int32_t n = 1; n <= 256; n *= 256)
    {
      light_samples t = make_samples(&light, n, 0, 4); /* N = 1: the centre */
      float out[3];
      diffuse_at(&t, receiver[0], receiver[1], receiver[2], 0, 0, 1, out);
      const double e = rel(out[0], point);
      printf("point limit: side %.0e, N %3d: X %.6e, point light %.6e, rel. diff %.2e\n", side,
             (int)n, out[0], point, e);
      if (n == 1)
      {
        MRGI_CHECK(e < previous);
        previous = e;
      }
      free_samples(&t);
    }
  }
  MRGI_CHECK(previous < 1e-5);
}

/* ---- 5. early-outs are exact ---- */

static double random_unit(uint64_t* state)
{
  *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*state >> 11) * 0x1.0p-53;
}

static void test_early_outs(void)
{
  uint64_t state = 99;
  int32_t behind = 0, facing_away = 0, lit = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 12; ++trial)
  {
    /* a random rectangle: u and v from a random rotation */
    double u[3] = { random_unit(&state) - 0.5, random_unit(&state) - 0.5, random_unit(&state) - 0.5 };
    double w[3] = { random_unit(&state) - 0.5, random_unit(&state) - 0.5, random_unit(&state) - 0.5 };
    double v[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
    const double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double su = 0.5 + 2.0 * random_unit(&state), sv = 0.5 + random_unit(&state);
    /* Drawn one at a time: the order in which a call evaluates its arguments
     * is unspecified (gcc goes right to left, clang left to right), and the
     * test must check the same points whichever compiled it. This is the
     * order gcc used, so the points are those the test has always checked. */
    const double cz = random_unit(&state), cy = random_unit(&state), cx = random_unit(&state);
    mrgi_area_light light = make_light(cx, cy, cz, u[0] * su / lu, u[1] * su / lu, u[2] * su / lu,
      v[0] * sv / lv, v[1] * sv / lv, v[2] * sv / lv, 1.5);
    light.two_sided = trial % 3 == 0;
    light_samples t = make_samples(&light, 64 + 50 * trial, trial % 2, (uint64_t)trial);
    for (int r = 0; r < 400; ++r)
    {
      const double p[3] = { 6 * random_unit(&state) - 3, 6 * random_unit(&state) - 3,
                            6 * random_unit(&state) - 3 };
      const double n[3] = { random_unit(&state) - 0.5, random_unit(&state) - 0.5,
                            random_unit(&state) - 0.5 };
      float out[3];
      diffuse_at(&t, p[0], p[1], p[2], n[0], n[1], n[2], out);
      double expect[3], unused[3];
      sample_sums(&t, p, n, NULL, 0.0, expect, unused);
      /* which early-out applies (test-side, in double) */
      double side = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        side += t.uniforms.normal[k] * (p[k] - t.uniforms.center[k]);
      }
      int away = 1;
      for (int c = 0; c < 4; ++c)
      {
        double dot = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          dot += n[k] * (t.uniforms.corners[c][k] - p[k]);
        }
        away = away && dot <= 0.0;
      }
      if (!light.two_sided && side <= 0.0)
      {
        ++behind;
        MRGI_CHECK(out[0] == 0.0f);
        MRGI_CHECK(expect[0] <= 1e-6 * light.intensity); /* the loop would give 0 too */
      }
      else if (away)
      {
        ++facing_away;
        MRGI_CHECK(out[0] == 0.0f);
        MRGI_CHECK(expect[0] <= 1e-6 * light.intensity);
      }
      else
      {
        ++lit;
        const double e = fabs(out[0] - expect[0]) / (expect[0] + 1e-6);
        worst = fmax(worst, e);
        MRGI_CHECK(e < 1e-4);
      }
    }
    free_samples(&t);
  }
  printf("early-outs: %d behind, %d facing away (all 0 in the full sum), %d lit (worst rel. "
         "diff to the double sum %.1e)\n",
         (int)behind, (int)facing_away, (int)lit, worst);
  MRGI_CHECK(behind > 200 && facing_away > 200 && lit > 1000);
}

/* ---- 6. extremes ---- */

static void test_extremes(void)
{
  const double L = 1.0;
  mrgi_area_light light = ceiling_light(1.0, 1.0, L);
  float out[3];
  /* receivers in the light's plane (z = 1): one- and two-sided, facing the
   * light edge-on from outside, or lying inside the rectangle */
  for (int two = 0; two < 2; ++two)
  {
    light.two_sided = two;
    for (int32_t n = 1; n <= 4096; n *= 4096)
    {
      light_samples t = make_samples(&light, n, 1, 2);
      diffuse_at(&t, 2.0, 0.0, 1.0, -1, 0, 0, out); /* edge-on, looking at the light */
      MRGI_CHECK(out[0] == 0.0f);
      diffuse_at(&t, 0.1, 0.1, 1.0, 0, 0, -1, out); /* inside the rectangle, in its plane */
      MRGI_CHECK(out[0] == 0.0f);
      diffuse_at(&t, 0.0, 0.0, 1.0, 0, 0, 1, out);
      MRGI_CHECK(out[0] == 0.0f);
      /* on a sample point: r = 0 for that sample, finite */
      const mrgi_area_light_sample* s = &t.samples[t.count / 2];
      diffuse_at(&t, s->position[0], s->position[1], s->position[2] - 1e-3, 0, 0, 1, out);
      MRGI_CHECK(out[0] <= L * 1.0001f);
      /* edge-on but slightly below the plane: small, finite, as the integral */
      diffuse_at(&t, 2.0, 0.0, 0.999, -1, 0, 0, out);
      MRGI_CHECK(out[0] >= 0.0f && out[0] < 1e-3f);
      /* zero normal */
      diffuse_at(&t, 0.0, 0.0, 0.0, 0, 0, 0, out);
      MRGI_CHECK(out[0] == 0.0f);
      free_samples(&t);
    }
  }
  light.two_sided = 0;
  /* edge-on from below: a receiver facing the light's edge sideways at the
   * height of the plane minus a little, against brute force */
  {
    light_samples t = make_samples(&light, 4096, 0, 2);
    const double p[3] = { 1.5, 0.0, 0.9 }, n[3] = { -1, 0, 0 };
    double exact[3];
    brute_force(&light, p, n, NULL, -1.0, 2048, exact);
    diffuse_at(&t, p[0], p[1], p[2], n[0], n[1], n[2], out);
    printf("edge-on receiver 0.1 below the plane: X %.5e, integral %.5e (rel. %.1e)\n", out[0],
           exact[0], rel(out[0], exact[0]));
    MRGI_CHECK(rel(out[0], exact[0]) < 0.02);
    free_samples(&t);
  }
  /* a light 1e4 times the scene: bounded and finite near it, exact when the
   * receiver is as far as the samples are apart */
  {
    mrgi_area_light huge = ceiling_light(1e4, 1.0, L);
    light_samples t = make_samples(&huge, 256, 1, 6);
    diffuse_at(&t, 0.0, 0.0, 0.0, 0, 0, 1, out);
    const double exact_near = L * view_factor_rect(-5e3, 5e3, -5e3, 5e3, 1.0);
    printf("light 1e4 x the scene at distance 1, 256 samples: X %.3e (integral %.6f: samples "
           "%.0f apart cannot resolve it)\n",
           out[0], exact_near, 1e4 / 16);
    MRGI_CHECK(out[0] <= L);
    free_samples(&t);
    huge = ceiling_light(1e4, 5e3, L);
    t = make_samples(&huge, 256, 1, 6);
    diffuse_at(&t, 1e3, -2e3, 0.0, 0, 0, 1, out);
    const double exact_far = L * view_factor_rect(-6e3, 4e3, -3e3, 7e3, 5e3);
    printf("light 1e4 at distance 5e3, 256 samples: X %.6f, closed form %.6f (rel. %.1e)\n", out[0],
           exact_far, rel(out[0], exact_far));
    MRGI_CHECK(rel(out[0], exact_far) < 0.01);
    free_samples(&t);
  }
  /* black texture: zero everywhere, no NaN */
  {
    mrgi_image black = constant_texture(8, 8, 0.0f, 0.0f, 0.0f);
    mrgi_area_light dark = ceiling_light(1.0, 1.0, 5.0);
    dark.texture = &black;
    light_samples t = make_samples(&dark, 256, 1, 1);
    for (int32_t k = 0; k < t.count; ++k)
    {
      MRGI_CHECK(t.samples[k].radiance[0] == 0.0f && t.samples[k].radiance[2] == 0.0f);
    }
    diffuse_at(&t, 0.2, 0.1, 0.0, 0, 0, 1, out);
    MRGI_CHECK(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f);
    const float p[3] = { 0.2f, 0.1f, 0.0f }, n[3] = { 0, 0, 1 }, v[3] = { 0, 0, 1 };
    mrgi_area_light_specular(&t.uniforms, t.samples, t.count, &t.pyramid, p, n, v, 50.0f, out, NULL);
    MRGI_CHECK(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f);
    free_samples(&t);
    mrgi_image_destroy(&black);
  }
  /* scale invariance from 1e-6 to 1e6 (float math throughout) */
  {
    float reference[3];
    light_samples t = make_samples(&light, 1024, 1, 8);
    diffuse_at(&t, 0.3, -0.2, 0.0, 0.1, 0.0, 1.0, reference);
    free_samples(&t);
    const double scales[4] = { 1e-6, 1e-4, 1e5, 1e6 };
    for (int k = 0; k < 4; ++k)
    {
      const double s = scales[k];
      mrgi_area_light scaled = ceiling_light(s, s, L);
      t = make_samples(&scaled, 1024, 1, 8);
      diffuse_at(&t, 0.3 * s, -0.2 * s, 0.0, 0.1, 0.0, 1.0, out);
      printf("scale %.0e: X %.7f (scale 1: %.7f)\n", s, out[0], reference[0]);
      MRGI_CHECK(rel(out[0], reference[0]) < 1e-4);
      free_samples(&t);
    }
  }
}

/* ---- 7. Phong ---- */

static void specular_at(const light_samples* t, const double p[3], const double n[3],
                        const double v[3], float power, float out[3],
                        mrgi_area_light_specular_info* info)
{
  const float pf[3] = { (float)p[0], (float)p[1], (float)p[2] };
  const float nf[3] = { (float)n[0], (float)n[1], (float)n[2] };
  const float vf[3] = { (float)v[0], (float)v[1], (float)v[2] };
  mrgi_area_light_specular(&t->uniforms, t->samples, t->count, &t->pyramid, pf, nf, vf, power, out,
                           info);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK(isfinite(out[c]) && out[c] >= 0.0f);
  }
}

static void test_specular_convergence(void)
{
  /* receiver at (0.3, 0, 0) facing up, eye so that R points at (0.1, 0.1, 1) on the light */
  mrgi_area_light light = ceiling_light(1.0, 1.0, 3.0);
  const double p[3] = { 0.3, 0.0, 0.0 }, n[3] = { 0, 0, 1 };
  const double target[3] = { 0.1 - 0.3, 0.1, 1.0 };
  const double v[3] = { -target[0], -target[1], target[2] }; /* mirror of R about the normal */
  const float powers[3] = { 1.0f, 20.0f, 128.0f };
  for (int k = 0; k < 3; ++k)
  {
    double r[3], exact[3];
    reflect_dir(n, v, r);
    brute_force(&light, p, n, r, powers[k], 2048, exact);
    printf("Phong n = %3.0f vs integral %.5f: ", (double)powers[k], exact[0]);
    double e = 0.0;
    for (int32_t count = 16; count <= 4096; count *= 4)
    {
      light_samples t = make_samples(&light, count, 1, 13);
      float out[3];
      mrgi_area_light_specular_info info;
      specular_at(&t, p, n, v, powers[k], out, &info);
      e = rel(out[0], exact[0]);
      printf(" N %d%s %.1e", (int)count,
             info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID ? " (grid)" : "", e);
      MRGI_CHECK(info.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES ||
                 info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID);
      MRGI_CHECK(info.lobe.hits_light && info.lobe.peak == 1.0f);
      if (info.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES)
      {
        MRGI_CHECK(info.samples_in_lobe >= MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES);
        double d[3], s[3];
        sample_sums(&t, p, n, r, powers[k], d, s);
        MRGI_CHECK(rel(out[0], s[0]) < 1e-4);
      }
      else
      {
        MRGI_CHECK(info.samples_in_lobe < MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES);
        MRGI_CHECK(info.grid_cells > 0 && info.grid_cells <= 25);
      }
      free_samples(&t);
    }
    printf("\n");
    MRGI_CHECK(e < (powers[k] > 100.0f ? 6e-3 : 3e-3)); /* N = 4096, jittered */
  }
  /* normalisation: a light filling most of the hemisphere, seen straight
   * down: S -> L for every n (the lobe integrates to 1) */
  {
    mrgi_area_light big = ceiling_light(400.0, 1.0, 2.0);
    const double p0[3] = { 0, 0, 0 }, up[3] = { 0, 0, 1 };
    for (int k = 0; k < 3; ++k)
    {
      double exact[3];
      brute_force(&big, p0, up, up, powers[k], 4096, exact);
      printf("hemisphere light, n = %3.0f: S integral %.5f (L = 2)\n", (double)powers[k], exact[0]);
      MRGI_CHECK(exact[0] > 2.0 * 0.99 && exact[0] < 2.0 * 1.0001);
    }
  }
}

/* Brute-force max over the rectangle of cos(R, y - P). */
static double brute_peak_cos(const mrgi_area_light* light, const double p[3], const double r[3])
{
  double best = -1.0;
  const int32_t m = 400;
  for (int32_t j = 0; j <= m; ++j)
  {
    for (int32_t i = 0; i <= m; ++i)
    {
      double d[3];
      for (int k = 0; k < 3; ++k)
      {
        d[k] = light->center[k] + ((double)i / m - 0.5) * light->edge_u[k] +
               ((double)j / m - 0.5) * light->edge_v[k] - p[k];
      }
      const double c = (r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) /
                       sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      best = fmax(best, c);
    }
  }
  return best;
}

static void test_lobe_peak_and_miss(void)
{
  /* a long light; R passes just beside the middle of its long edge: the
   * corners see a weak lobe, the edge a strong one */
  mrgi_area_light light = ceiling_light(1.0, 1.0, 1.0);
  set3(light.edge_u, 10.0, 0.0, 0.0);
  light_samples t = make_samples(&light, 256, 0, 1);
  const double p[3] = { 0.0, 0.0, 0.0 }, n[3] = { 0, 0, 1 };
  const double v[3] = { 0.0, 0.55, 1.0 }; /* R = (0, -0.55, 1): meets z = 1 at y = -0.55 */
  double r[3];
  reflect_dir(n, v, r);
  const float pf[3] = { 0, 0, 0 }, nf[3] = { 0, 0, 1 };
  const float vf[3] = { (float)v[0], (float)v[1], (float)v[2] };
  mrgi_area_light_lobe lobe;
  mrgi_area_light_phong_lobe(&t.uniforms, pf, nf, vf, 128.0f, &lobe);
  const double rl = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  const double ru[3] = { r[0] / rl, r[1] / rl, r[2] / rl };
  const double brute = brute_peak_cos(&light, p, ru);
  double corners = -1.0;
  for (int c = 0; c < 4; ++c)
  {
    double d[3], len = 0.0, dot = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      d[k] = t.uniforms.corners[c][k] - p[k];
      len += d[k] * d[k];
      dot += ru[k] * d[k];
    }
    corners = fmax(corners, dot / sqrt(len));
  }
  printf("lobe peak (n = 128) beside a long edge: %.4f (brute force %.4f); corners only: %.2e\n",
         (double)lobe.peak, pow(brute, 128), pow(corners, 128));
  MRGI_CHECK(!lobe.hits_light && lobe.reaches_plane);
  MRGI_CHECK_NEAR(lobe.peak, pow(brute, 128), 2e-3);
  MRGI_CHECK(pow(corners, 128) < 1e-3 && lobe.peak > 0.5f);
  float out[3];
  mrgi_area_light_specular_info info;
  specular_at(&t, p, n, v, 128.0f, out, &info);
  MRGI_CHECK(info.path != MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS && out[0] > 0.0f);
  free_samples(&t);

  /* random receivers and views: the peak is the exact max, and a lobe miss
   * drops at most MRGI_AREA_LIGHT_LOBE_DISCARD (n + 2)/2 X */
  uint64_t state = 5;
  light = ceiling_light(1.0, 1.0, 1.0);
  set3(light.edge_u, 1.5, 0.0, 0.3);
  set3(light.edge_v, 0.0, -1.0, 0.0);
  t = make_samples(&light, 256, 1, 2);
  int32_t misses = 0, hits = 0, others = 0;
  double worst_peak = 0.0;
  for (int trial = 0; trial < 600; ++trial)
  {
    const double q[3] = { 4 * random_unit(&state) - 2, 4 * random_unit(&state) - 2,
                          1.5 * random_unit(&state) - 1.0 };
    const double nq[3] = { random_unit(&state) - 0.5, random_unit(&state) - 0.5, 1.0 };
    const double vq[3] = { random_unit(&state) - 0.5, random_unit(&state) - 0.5,
                           random_unit(&state) };
    const float power = trial % 3 == 0 ? 5.0f : (trial % 3 == 1 ? 50.0f : 128.0f);
    double rq[3];
    reflect_dir(nq, vq, rq);
    specular_at(&t, q, nq, vq, power, out, &info);
    if (info.path == MRGI_AREA_LIGHT_SPECULAR_BEHIND ||
        info.path == MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY)
    {
      MRGI_CHECK(out[0] == 0.0f);
      continue;
    }
    if (trial < 200)
    {
      const double b = brute_peak_cos(&light, q, rq);
      const double expect = b > 0.0 ? pow(b, power) : 0.0;
      worst_peak = fmax(worst_peak, fabs(info.lobe.peak - expect));
      MRGI_CHECK(fabs(info.lobe.peak - expect) < 2e-3 + 1e-3 * power * 1e-2);
    }
    double d[3], s[3];
    sample_sums(&t, q, nq, rq, power, d, s);
    if (info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS)
    {
      ++misses;
      MRGI_CHECK(out[0] == 0.0f);
      MRGI_CHECK(s[0] <= MRGI_AREA_LIGHT_LOBE_DISCARD * 0.5 * (power + 2.0) * d[0] * 1.0001 + 1e-12);
    }
    else if (info.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES)
    {
      ++hits;
      MRGI_CHECK(fabs(out[0] - s[0]) <= 1e-4 * s[0] + 1e-9);
    }
    else
    {
      ++others;
    }
  }
  printf("random lobes: %d misses (within the bound), %d sample sums (= double sum), %d lobe "
         "grids; worst peak error %.1e\n",
         (int)misses, (int)hits, (int)others, worst_peak);
  MRGI_CHECK(misses > 50 && hits > 50);
  free_samples(&t);
}

static void test_lobe_grid(void)
{
  /* n = 128 and few samples: the 5 x 5 grid replaces the sample sum and
   * tracks the integral; the 4-sample sum alone cannot */
  mrgi_image texture = random_texture(32, 32, 3, 17);
  for (int textured = 0; textured < 2; ++textured)
  {
    mrgi_area_light light = ceiling_light(1.0, 1.0, 2.0);
    light.texture = textured ? &texture : NULL;
    const double p[3] = { 0.3, 0.0, 0.0 }, n[3] = { 0, 0, 1 };
    const double v[3] = { 0.2 + 0.3, -0.15, 1.0 }; /* R meets the light at (-0.2, 0.15) */
    double r[3], exact[3];
    reflect_dir(n, v, r);
    brute_force(&light, p, n, r, 128.0, 2048, exact);
    light_samples t = make_samples(&light, 4, 0, 1);
    float out[3];
    mrgi_area_light_specular_info info;
    specular_at(&t, p, n, v, 128.0f, out, &info);
    double d[3], s[3];
    sample_sums(&t, p, n, r, 128.0, d, s);
    printf("lobe grid (n = 128, %s light, 4 samples): grid %.5f, integral %.5f (rel. %.1e); "
           "4-sample sum %.5f\n",
           textured ? "textured" : "uniform", out[1], exact[1], rel(out[1], exact[1]), s[1]);
    MRGI_CHECK(info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID && info.grid_cells == 25);
    MRGI_CHECK(rel(out[1], exact[1]) < (textured ? 0.08 : 0.03));
    MRGI_CHECK(rel(s[1], exact[1]) > 0.5);
    /* enough samples in the lobe: the sample sum */
    free_samples(&t);
    t = make_samples(&light, 4096, 0, 1);
    specular_at(&t, p, n, v, 128.0f, out, &info);
    MRGI_CHECK(info.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES && info.samples_in_lobe >= 9);
    MRGI_CHECK(rel(out[1], exact[1]) < 0.02);
    free_samples(&t);
    /* a lobe straddling the light's edge: clipped cells */
    t = make_samples(&light, 4, 0, 1);
    const double v_edge[3] = { 0.3 + 0.5, 0.0, 1.0 }; /* R meets the plane at x = -0.5 */
    reflect_dir(n, v_edge, r);
    brute_force(&light, p, n, r, 128.0, 2048, exact);
    specular_at(&t, p, n, v_edge, 128.0f, out, &info);
    printf("  lobe on the edge: grid %.5f, integral %.5f (rel. %.1e), %d cells\n", out[1],
           exact[1], rel(out[1], exact[1]), (int)info.grid_cells);
    MRGI_CHECK(info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID && info.grid_cells == 15);
    MRGI_CHECK(rel(out[1], exact[1]) < (textured ? 0.1 : 0.05));
    free_samples(&t);
  }
  mrgi_image_destroy(&texture);
}

/* Visibility in the specular sum (header, "Shadowed highlights"): the
 * path never depends on it; sample bits and query visibilities weight the
 * terms linearly; the dropped corner follows its two edge neighbours. */
static void test_specular_visibility(void)
{
  mrgi_image texture = random_texture(16, 16, 3, 5);
  mrgi_area_light light = ceiling_light(1.0, 1.0, 2.0);
  light.texture = &texture;
  const double p[3] = { 0.3, 0.0, 0.0 }, n[3] = { 0, 0, 1 };
  const double v[3] = { 0.2 + 0.3, -0.15, 1.0 };
  const float pf[3] = { 0.3f, 0.0f, 0.0f }, nf[3] = { 0, 0, 1 };
  const float vf[3] = { 0.5f, -0.15f, 1.0f };
  /* 1. sample path (n = 10, 256 samples) */
  light_samples t = make_samples(&light, 256, 0, 1);
  float full[3], out[3], even[3], odd[3];
  mrgi_area_light_specular_info info, vinfo;
  specular_at(&t, p, n, v, 10.0f, full, &info);
  MRGI_CHECK(info.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES && full[1] > 0.0f);
  uint32_t ones[8], none[8], evens[8], odds[8];
  for (int w = 0; w < 8; ++w)
  {
    ones[w] = 0xffffffffu;
    none[w] = 0u;
    evens[w] = 0x55555555u;
    odds[w] = 0xaaaaaaaau;
  }
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 10.0f,
                                   ones, NULL, out, &vinfo);
  MRGI_CHECK(memcmp(out, full, sizeof(out)) == 0 && vinfo.path == info.path &&
             vinfo.samples_in_lobe == info.samples_in_lobe);
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 10.0f,
                                   none, NULL, out, &vinfo);
  MRGI_CHECK(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f);
  MRGI_CHECK(vinfo.path == info.path && vinfo.samples_in_lobe == info.samples_in_lobe);
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 10.0f,
                                   evens, NULL, even, NULL);
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 10.0f,
                                   odds, NULL, odd, NULL);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK(even[c] > 0.0f && odd[c] > 0.0f);
    MRGI_CHECK(rel(even[c] + odd[c], full[c]) < 1e-5);
  }
  free_samples(&t);
  /* 2. lobe-grid path (n = 128, 4 samples): the cells and their visibility */
  t = make_samples(&light, 4, 0, 1);
  specular_at(&t, p, n, v, 128.0f, full, &info);
  MRGI_CHECK(info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID && info.grid_cells == 25);
  mrgi_area_light_specular_info cinfo;
  mrgi_area_light_specular_classify(&t.uniforms, t.samples, t.count, pf, nf, vf, 128.0f, &cinfo);
  MRGI_CHECK(cinfo.path == info.path && cinfo.grid_cells == info.grid_cells &&
             cinfo.samples_in_lobe == info.samples_in_lobe);
  mrgi_area_light_lobe_grid grid;
  MRGI_CHECK(mrgi_area_light_lobe_grid_cells(&t.uniforms, &info.lobe, &grid) == 1);
  MRGI_CHECK(grid.cells == 25 && grid.on_light[MRGI_AREA_LIGHT_LOBE_CELLS - 1]);
  for (int32_t j = 0; j < MRGI_AREA_LIGHT_LOBE_CELLS; ++j)
  {
    /* cell j = (a, b) in raster order around the hit point (-0.2, 0.15) */
    const int32_t a = j % MRGI_AREA_LIGHT_LOBE_GRID - 2, b = j / MRGI_AREA_LIGHT_LOBE_GRID - 2;
    if (fabs(grid.area[j] - grid.spacing_u * grid.spacing_v) < 1e-6 * grid.area[j])
    {
      /* not clipped by the light's edges */
      MRGI_CHECK_NEAR(grid.u[j], info.lobe.hit_u + a * grid.spacing_u, 1e-5);
      MRGI_CHECK_NEAR(grid.v[j], info.lobe.hit_v + b * grid.spacing_v, 1e-5);
    }
    MRGI_CHECK(fabs(grid.u[j]) <= 0.5 && fabs(grid.v[j]) <= 0.5);
    MRGI_CHECK_NEAR(grid.position[j][2], 1.0, 1e-6); /* on the light's plane */
  }
  float q[MRGI_AREA_LIGHT_LOBE_CELLS - 1];
  for (int j = 0; j < MRGI_AREA_LIGHT_LOBE_CELLS - 1; ++j)
  {
    q[j] = 1.0f;
  }
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 128.0f,
                                   none, q, out, &vinfo); /* the sample mask is not read here */
  MRGI_CHECK(memcmp(out, full, sizeof(out)) == 0 && vinfo.path == info.path);
  for (int j = 0; j < MRGI_AREA_LIGHT_LOBE_CELLS - 1; ++j)
  {
    q[j] = 0.0f;
  }
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 128.0f,
                                   NULL, q, out, NULL);
  MRGI_CHECK(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f); /* the corner too */
  /* linear in each query; the corner (2, 2) takes the mean of queries 23
   * (1, 2) and 19 (2, 1): dropping both halves drops half of all three */
  const int32_t left = MRGI_AREA_LIGHT_LOBE_CELLS - 2, below = MRGI_AREA_LIGHT_LOBE_CELLS - 1 - MRGI_AREA_LIGHT_LOBE_GRID;
  float s_left[3], s_below[3], s_half[3], s_centre[3];
  for (int j = 0; j < MRGI_AREA_LIGHT_LOBE_CELLS - 1; ++j)
  {
    q[j] = 1.0f;
  }
  q[left] = 0.0f;
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 128.0f,
                                   NULL, q, s_left, NULL);
  q[left] = 1.0f;
  q[below] = 0.0f;
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 128.0f,
                                   NULL, q, s_below, NULL);
  q[left] = q[below] = 0.5f;
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 128.0f,
                                   NULL, q, s_half, NULL);
  q[left] = q[below] = 1.0f;
  q[12] = 0.0f; /* the centre cell (0, 0) */
  mrgi_area_light_specular_visible(&t.uniforms, t.samples, t.count, &t.pyramid, pf, nf, vf, 128.0f,
                                   NULL, q, s_centre, NULL);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK(s_left[c] < full[c] && s_below[c] < full[c]);
    const double dropped = (full[c] - s_left[c]) + (full[c] - s_below[c]);
    MRGI_CHECK_NEAR(s_half[c], full[c] - 0.5 * dropped, 1e-5 * full[c]);
    MRGI_CHECK(full[c] - s_centre[c] > 0.1 * full[c]); /* the centre carries the lobe */
  }
  printf("specular visibility: sample halves sum to the whole; lobe grid centre cell %.0f%% of "
         "the highlight, corner rule linear\n",
         100.0 * (full[1] - s_centre[1]) / full[1]);
  free_samples(&t);
  mrgi_image_destroy(&texture);
}

static void test_refinement(void)
{
  mrgi_area_light light = ceiling_light(4.0, 2.0, 1.0);
  light_samples t = make_samples(&light, 16, 0, 1);
  const float p[3] = { 0.2f, 0.0f, 0.0f }, n[3] = { 0, 0, 1 }, v[3] = { 0, 0, 1 };
  mrgi_area_light_lobe lobe;
  float previous = 0.0f;
  const float powers[4] = { 1.0f, 10.0f, 100.0f, 1000.0f };
  for (int k = 0; k < 4; ++k)
  {
    mrgi_area_light_phong_lobe(&t.uniforms, p, n, v, powers[k], &lobe);
    const double theta = acos(pow(2.0, -1.0 / powers[k]));
    MRGI_CHECK(lobe.reaches_plane && lobe.hits_light);
    MRGI_CHECK_NEAR(lobe.distance, 2.0, 1e-6);
    MRGI_CHECK_NEAR(lobe.width, 4.0 * tan(theta), 1e-5 * 4.0 * tan(theta));
    MRGI_CHECK_NEAR(lobe.hit_u, 0.2, 1e-6);
    MRGI_CHECK_NEAR(lobe.hit_v, 0.0, 1e-6);
    /* eye 3 away, texels of 0.01: m = 0.01 (1/3 + 1/2) / (2 tan theta) */
    const float m = mrgi_area_light_phong_refinement(&lobe, 3.0f, 0.01f);
    MRGI_CHECK_NEAR(m, 0.01 * (1.0 / 3.0 + 0.5) / (2.0 * tan(theta)), 1e-5 * m);
    MRGI_CHECK(m > previous); /* sharper lobe, finer sampling */
    previous = m;
  }
  /* the flat-mirror reading: m = 1 exactly when the texel, seen on the
   * light through the mirror, is as wide as the lobe */
  mrgi_area_light_phong_lobe(&t.uniforms, p, n, v, 100.0f, &lobe);
  const float s = lobe.width * 3.0f / (3.0f + 2.0f);
  MRGI_CHECK_NEAR(mrgi_area_light_phong_refinement(&lobe, 3.0f, s), 1.0, 1e-5);
  /* n = 0: no lobe to resolve; bad eye distance: always refine; R away from
   * the plane: only the eye term */
  mrgi_area_light_phong_lobe(&t.uniforms, p, n, v, 0.0f, &lobe);
  MRGI_CHECK(lobe.width == FLT_MAX && mrgi_area_light_phong_refinement(&lobe, 3.0f, 0.01f) == 0.0f);
  MRGI_CHECK(mrgi_area_light_phong_refinement(&lobe, 0.0f, 0.01f) == FLT_MAX);
  const float away[3] = { 0.0f, 0.0f, -1.0f }; /* V below the surface: R points down */
  mrgi_area_light_phong_lobe(&t.uniforms, p, n, away, 10.0f, &lobe);
  MRGI_CHECK(!lobe.reaches_plane && lobe.inverse_distance == 0.0f && lobe.width == FLT_MAX);
  MRGI_CHECK(lobe.peak == 0.0f);
  const double theta = acos(pow(2.0, -0.1));
  MRGI_CHECK_NEAR(mrgi_area_light_phong_refinement(&lobe, 3.0f, 0.01f),
                  0.01 / 3.0 / (2.0 * tan(theta)), 1e-6);
  free_samples(&t);
  printf("refinement metric: ok\n");
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_validation),
    MRGI_TEST_CASE(test_pyramid),
    MRGI_TEST_CASE(test_samples),
    MRGI_TEST_CASE(test_diffuse_convergence),
    MRGI_TEST_CASE(test_point_limit),
    MRGI_TEST_CASE(test_early_outs),
    MRGI_TEST_CASE(test_extremes),
    MRGI_TEST_CASE(test_specular_convergence),
    MRGI_TEST_CASE(test_lobe_peak_and_miss),
    MRGI_TEST_CASE(test_lobe_grid),
    MRGI_TEST_CASE(test_specular_visibility),
    MRGI_TEST_CASE(test_refinement),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
