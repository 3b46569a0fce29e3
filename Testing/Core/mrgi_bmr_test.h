/* Test G-buffers for TestBMRMask and TestBMRBlend: ray-cast planes under a
 * perspective or parallel camera (eye space, looking down -z), and random
 * G-buffers. */
#ifndef MRGI_BMR_TEST_H
#define MRGI_BMR_TEST_H

#include "mrgi_bmr_mask.h"
#include "mrgi_buffers.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint64_t bmr_rng_state = 0x9E3779B97F4A7C15ull;
static uint32_t bmr_rng_u32(void)
{
  bmr_rng_state ^= bmr_rng_state << 13;
  bmr_rng_state ^= bmr_rng_state >> 7;
  bmr_rng_state ^= bmr_rng_state << 17;
  return (uint32_t)(bmr_rng_state >> 11);
}
static double bmr_rng_unit(void)
{
  return (double)bmr_rng_u32() / 4294967296.0;
}
static int32_t bmr_rng_int(int32_t lo, int32_t hi)
{
  return lo + (int32_t)(bmr_rng_u32() % (uint32_t)(hi - lo + 1));
}

typedef enum bmr_scene_kind
{
  BMR_SCENE_PLANE,  /* one plane facing the viewer at depth 10 */
  BMR_SCENE_TILTED, /* one plane tilted 60 degrees about x, through depth 10 */
  BMR_SCENE_STEP,   /* two facing planes, depth 10 left of the middle, 12 right */
  BMR_SCENE_CREASE, /* two planes meeting at the middle column (a ridge), continuous depth */
} bmr_scene_kind;

typedef struct bmr_gbuffer
{
  int32_t width, height;
  float* position;
  float* normal;
  float ab[2]; /* pixel-size coefficients */
  mrgi_gather_receivers view;
} bmr_gbuffer;

static void bmr_gbuffer_alloc(bmr_gbuffer* g, int32_t W, int32_t H)
{
  memset(g, 0, sizeof(*g));
  g->width = W;
  g->height = H;
  g->position = (float*)calloc((size_t)W * (size_t)H * 4, sizeof(float));
  g->normal = (float*)calloc((size_t)W * (size_t)H * 4, sizeof(float));
  MRGI_CHECK(g->position && g->normal);
  mrgi_gather_receivers v = { W, H, g->position, g->normal };
  g->view = v;
}

static void bmr_gbuffer_free(bmr_gbuffer* g)
{
  free(g->position);
  free(g->normal);
  memset(g, 0, sizeof(*g));
}

/* Intersect the ray o + t r with the plane n.P = c; t (or -1). */
static double bmr_hit(const double o[3], const double r[3], const double n[3], double c)
{
  const double nr = n[0] * r[0] + n[1] * r[1] + n[2] * r[2];
  if (fabs(nr) < 1e-12)
  {
    return -1.0;
  }
  return (c - (n[0] * o[0] + n[1] * o[1] + n[2] * o[2])) / nr;
}

/* Ray-cast `kind` at scene scale `scale` (every length times scale) into a
 * W x H G-buffer. Perspective: 30 degree vertical field of view; parallel:
 * parallel scale 2 * scale. */
static void bmr_gbuffer_scene(
  bmr_gbuffer* g, int32_t W, int32_t H, bmr_scene_kind kind, double scale, int parallel)
{
  bmr_gbuffer_alloc(g, W, H);
  const double half_angle = 15.0 * 3.14159265358979323846 / 180.0;
  const double pixel = parallel ? 2.0 * 2.0 * scale / H : 2.0 * tan(half_angle) / H;
  g->ab[0] = parallel ? 0.0f : (float)pixel;
  g->ab[1] = parallel ? (float)pixel : 0.0f;
  for (int32_t y = 0; y < H; ++y)
  {
    for (int32_t x = 0; x < W; ++x)
    {
      const double sx = (x + 0.5 - 0.5 * W) * pixel, sy = (y + 0.5 - 0.5 * H) * pixel;
      double o[3] = { 0, 0, 0 }, r[3] = { sx, sy, -1.0 };
      if (parallel)
      {
        o[0] = sx;
        o[1] = sy;
        r[0] = 0.0;
        r[1] = 0.0;
      }
      double n[3] = { 0, 0, 1 }, t = -1.0;
      const int right = 2 * x >= W;
      switch (kind)
      {
        case BMR_SCENE_PLANE:
          t = bmr_hit(o, r, n, -10.0 * scale);
          break;
        case BMR_SCENE_TILTED:
          n[1] = sin(60.0 * 3.14159265358979323846 / 180.0);
          n[2] = cos(60.0 * 3.14159265358979323846 / 180.0);
          t = bmr_hit(o, r, n, -10.0 * scale * n[2]);
          break;
        case BMR_SCENE_STEP:
          t = bmr_hit(o, r, n, (right ? -12.0 : -10.0) * scale);
          break;
        case BMR_SCENE_CREASE:
        {
          /* Planes through the line x = 0, z = -10 scale; normals tilted
           * +-30 degrees about y. The ridge column is where the ray's x
           * changes sign: the middle of the image. */
          const double s30 = 0.5, c30 = 0.86602540378443865;
          n[0] = right ? s30 : -s30;
          n[2] = c30;
          t = bmr_hit(o, r, n, -10.0 * scale * c30);
          break;
        }
      }
      const size_t p = (size_t)y * (size_t)W + (size_t)x;
      for (int c = 0; c < 3; ++c)
      {
        g->position[4 * p + c] = (float)(o[c] + t * r[c]);
        g->normal[4 * p + c] = (float)n[c];
      }
      g->position[4 * p + 3] = t > 0.0 ? MRGI_GBUFFER_VALID : 0.0f;
    }
  }
}

/* A random G-buffer: smooth depth with random steps, random normals and
 * holes, some non-unit normals. */
static void bmr_gbuffer_random(bmr_gbuffer* g, int32_t W, int32_t H)
{
  bmr_gbuffer_alloc(g, W, H);
  g->ab[0] = (float)(0.001 + 0.01 * bmr_rng_unit());
  g->ab[1] = 0.0f;
  const double hole = 0.15 * bmr_rng_unit();
  for (int32_t y = 0; y < H; ++y)
  {
    for (int32_t x = 0; x < W; ++x)
    {
      const size_t p = (size_t)y * (size_t)W + (size_t)x;
      const double d = 5.0 + 0.01 * x + (bmr_rng_unit() < 0.05 ? 3.0 * bmr_rng_unit() : 0.0);
      g->position[4 * p + 0] = (float)(0.01 * x);
      g->position[4 * p + 1] = (float)(0.01 * y);
      g->position[4 * p + 2] = (float)-d;
      g->position[4 * p + 3] = bmr_rng_unit() < hole ? 0.0f : MRGI_GBUFFER_VALID;
      const int bent = bmr_rng_unit() < 0.05;
      g->normal[4 * p + 0] = bent ? (float)(bmr_rng_unit() - 0.5) : 0.0f;
      g->normal[4 * p + 1] = bent ? (float)(bmr_rng_unit() - 0.5) : 0.0f;
      g->normal[4 * p + 2] = (float)(0.5 + 2.0 * bmr_rng_unit());
    }
  }
}

/* Random valid params (thresholds may be 0, finite or off). */
static void bmr_params_random(mrgi_bmr_params* params)
{
  MRGI_CHECK(
    mrgi_bmr_preset_params(bmr_rng_int(0, MRGI_BMR_EFFECT_COUNT - 1), params, NULL) == MRGI_OK);
  const double choices[4] = { 0.0, 0.5, 2.0, INFINITY };
  params->depth_threshold = choices[bmr_rng_int(0, 3)];
  params->normal_threshold = choices[bmr_rng_int(0, 3)] * 0.1;
  params->combine = bmr_rng_int(0, 1);
  for (int k = 0; k < MRGI_BMR_LEVELS; ++k)
  {
    params->variance[k] = bmr_rng_unit() < 0.2 ? 0.0 : MRGI_BMR_MAX_VARIANCE * bmr_rng_unit() * 0.5;
    params->weight[k] = 100.0 * bmr_rng_unit();
    params->skip[k] = k < MRGI_BMR_LEVELS - 1 && bmr_rng_unit() < 0.25;
  }
}

#endif
