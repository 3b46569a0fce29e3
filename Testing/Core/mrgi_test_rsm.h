/* Synthetic reflective shadow maps for the light-space tree and cluster
 * tests: random texels, and a corner of three planes seen from a light
 * (perspective or orthographic) so that the light-space pyramid has real
 * depth and normal discontinuities. Header-only, test code. */
#ifndef MRGI_TEST_RSM_H
#define MRGI_TEST_RSM_H

#include "mrgi_test.h"
#include "mrgi_vpl_tree.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct test_rsm
{
  mrgi_rsm rsm;
  float* position;
  float* normal;
  float* flux;
  mrgi_rsm_view_camera cameras[MRGI_RSM_MAX_VIEWS];
} test_rsm;

static inline double test_uniform(uint32_t* state)
{
  *state = *state * 1664525u + 1013904223u;
  return (double)(*state >> 8) / 16777216.0;
}

/* Rotation by `angle` about y, then translation t: world -> view, column-major. */
static inline void test_camera(mrgi_rsm_view_camera* camera, double angle, const double t[3],
                               int parallel, double fov_or_scale)
{
  memset(camera, 0, sizeof(*camera));
  const double c = cos(angle);
  const double s = sin(angle);
  float* m = camera->world_to_view;
  m[0] = (float)c;
  m[2] = (float)-s;
  m[5] = 1.0f;
  m[8] = (float)s;
  m[10] = (float)c;
  m[12] = (float)t[0];
  m[13] = (float)t[1];
  m[14] = (float)t[2];
  m[15] = 1.0f;
  camera->projection.parallel = parallel;
  camera->projection.view_angle_deg = parallel ? 30.0 : fov_or_scale;
  camera->projection.parallel_scale = parallel ? fov_or_scale : 1.0;
}

static inline test_rsm test_rsm_make(int32_t size, int32_t views)
{
  test_rsm t;
  memset(&t, 0, sizeof(t));
  const size_t floats = 4 * (size_t)views * (size_t)size * (size_t)size;
  t.position = (float*)calloc(floats, sizeof(float));
  t.normal = (float*)calloc(floats, sizeof(float));
  t.flux = (float*)calloc(floats, sizeof(float));
  MRGI_CHECK(t.position && t.normal && t.flux);
  t.rsm.size = size;
  t.rsm.view_count = views;
  t.rsm.position = t.position;
  t.rsm.normal = t.normal;
  t.rsm.flux = t.flux;
  const double zero[3] = { 0.0, 0.0, 0.0 };
  for (int32_t v = 0; v < views; ++v)
  {
    test_camera(&t.cameras[v], 0.0, zero, 0, 90.0);
  }
  return t;
}

static inline void test_rsm_free(test_rsm* t)
{
  free(t->position);
  free(t->normal);
  free(t->flux);
}

static inline size_t test_rsm_index(const test_rsm* t, int32_t view, int32_t x, int32_t y)
{
  return ((size_t)view * (size_t)t->rsm.size + (size_t)y) * (size_t)t->rsm.size + (size_t)x;
}

/* Every texel: valid with probability `valid`, random position, unit
 * normal, flux and area. */
static inline void test_rsm_fill_random(test_rsm* t, uint32_t seed, double valid)
{
  uint32_t state = seed;
  const int32_t s = t->rsm.size;
  for (int32_t v = 0; v < t->rsm.view_count; ++v)
  {
    for (int32_t y = 0; y < s; ++y)
    {
      for (int32_t x = 0; x < s; ++x)
      {
        const size_t i = test_rsm_index(t, v, x, y);
        const int ok = test_uniform(&state) < valid;
        double n[3] = { test_uniform(&state) - 0.5, test_uniform(&state) - 0.5,
                        test_uniform(&state) + 0.1 };
        const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int c = 0; c < 3; ++c)
        {
          t->position[4 * i + c] = (float)(10.0 * test_uniform(&state) - 5.0);
          t->normal[4 * i + c] = (float)(n[c] / len);
          t->flux[4 * i + c] = (float)(test_uniform(&state) * 3.0);
        }
        t->position[4 * i + 3] = ok ? MRGI_GBUFFER_VALID : 0.0f;
        t->flux[4 * i + 3] = (float)(0.01 + test_uniform(&state));
      }
    }
  }
}

/* View `view` sees a corner: back wall z = -6 (normal +z), floor y = -2
 * (normal +y), side wall x = 2 (normal -x), and a box face z = -3 for
 * x in [-1.5, -0.5], y in [-2, 0] (a depth step), all in the view's own
 * space, then moved to world space by the inverse of the view's camera.
 * Rays leaving through the top (nothing hit) stay invalid. */
static inline void test_rsm_fill_corner(test_rsm* t, int32_t view)
{
  const mrgi_rsm_view_camera* camera = &t->cameras[view];
  const int32_t s = t->rsm.size;
  const float* m = camera->world_to_view;
  const double tanh = tan(camera->projection.view_angle_deg * 3.14159265358979323846 / 360.0);
  for (int32_t y = 0; y < s; ++y)
  {
    for (int32_t x = 0; x < s; ++x)
    {
      const double u = (2.0 * (x + 0.5) / s - 1.0);
      const double w = (2.0 * (y + 0.5) / s - 1.0);
      double o[3] = { 0.0, 0.0, 0.0 };
      double d[3] = { u * tanh, w * tanh, -1.0 };
      if (camera->projection.parallel)
      {
        o[0] = u * camera->projection.parallel_scale;
        o[1] = w * camera->projection.parallel_scale;
        d[0] = 0.0;
        d[1] = 0.0;
      }
      double best = INFINITY;
      double normal[3] = { 0.0, 0.0, 0.0 };
      /* planes: n . p = c, hit where n . (o + t d) = c */
      const double planes[3][4] = { { 0, 0, 1, -6 }, { 0, 1, 0, -2 }, { -1, 0, 0, -2 } };
      for (int k = 0; k < 3; ++k)
      {
        const double nd = planes[k][0] * d[0] + planes[k][1] * d[1] + planes[k][2] * d[2];
        if (nd >= 0.0)
        {
          continue; /* facing away or parallel */
        }
        const double hit =
          (planes[k][3] - (planes[k][0] * o[0] + planes[k][1] * o[1] + planes[k][2] * o[2])) / nd;
        if (hit > 0.0 && hit < best)
        {
          best = hit;
          normal[0] = planes[k][0];
          normal[1] = planes[k][1];
          normal[2] = planes[k][2];
        }
      }
      const double box = (-3.0 - o[2]) / d[2];
      const double bx = o[0] + box * d[0];
      const double by = o[1] + box * d[1];
      if (box > 0.0 && box < best && bx >= -1.5 && bx <= -0.5 && by >= -2.0 && by <= 0.0)
      {
        best = box;
        normal[0] = 0.0;
        normal[1] = 0.0;
        normal[2] = 1.0;
      }
      const size_t i = test_rsm_index(t, view, x, y);
      if (!isfinite(best) || best > 50.0)
      {
        continue;
      }
      /* view -> world: R^T (p - t) */
      const double p[3] = { o[0] + best * d[0] - m[12], o[1] + best * d[1] - m[13],
                            o[2] + best * d[2] - m[14] };
      for (int c = 0; c < 3; ++c)
      {
        t->position[4 * i + c] = (float)(m[4 * c + 0] * p[0] + m[4 * c + 1] * p[1] +
                                         m[4 * c + 2] * p[2]);
        t->normal[4 * i + c] = (float)(m[4 * c + 0] * normal[0] + m[4 * c + 1] * normal[1] +
                                       m[4 * c + 2] * normal[2]);
      }
      t->position[4 * i + 3] = MRGI_GBUFFER_VALID;
      const double shade = 0.2 + 0.8 * fabs(normal[0] * 0.3 + normal[1] * 0.5 + normal[2] * 0.8);
      t->flux[4 * i + 0] = (float)(shade * best * 0.01);
      t->flux[4 * i + 1] = (float)(shade * 0.02);
      t->flux[4 * i + 2] = (float)(0.005 * (1 + (x ^ y) % 7));
      t->flux[4 * i + 3] = (float)(best * best * 1e-3);
    }
  }
}

/* Sum of the usable texels' flux and area, in double. */
static inline void test_rsm_total(const test_rsm* t, double total[4])
{
  memset(total, 0, 4 * sizeof(double));
  const size_t texels = (size_t)t->rsm.view_count * (size_t)t->rsm.size * (size_t)t->rsm.size;
  for (size_t i = 0; i < texels; ++i)
  {
    if (mrgi_rsm_texel_usable(&t->rsm, (int64_t)i))
    {
      for (int c = 0; c < 4; ++c)
      {
        total[c] += t->flux[4 * i + c];
      }
    }
  }
}

#endif
