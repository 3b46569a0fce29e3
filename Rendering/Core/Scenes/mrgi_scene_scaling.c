#include "mrgi_scene_scaling.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Byte-identical output needs a*b+c rounded twice everywhere: forbid fused
 * multiply-add contraction. GCC in ISO C mode (-std=c11, as the build uses)
 * does not contract and does not know this pragma; Clang contracts by default. */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

/* ---- random numbers: splitmix64 ----
 * Steele, Lea and Flood, "Fast Splittable Pseudorandom Number Generators",
 * OOPSLA 2014; constants as in Vigna's public-domain splitmix64.c. Passes
 * BigCrush, needs one word of state, and any seed (0 included) is fine. */

typedef struct mrgi_scaling_rng
{
  uint64_t state;
} mrgi_scaling_rng;

static uint64_t mrgi_scaling_rng_next(mrgi_scaling_rng* rng)
{
  uint64_t z = (rng->state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/* Uniform in [0, 1): the top 53 bits scaled by 2^-53, exact in double. */
static double mrgi_scaling_rng_unit(mrgi_scaling_rng* rng)
{
  return (double)(mrgi_scaling_rng_next(rng) >> 11) * 0x1.0p-53;
}

/* ---- deterministic sine and cosine ----
 * sin and cos of 2 pi num / den. The argument is reduced EXACTLY in integers
 * to [0, pi/4] (quadrant, then complement), then Taylor polynomials through
 * x^15 and x^16 are evaluated in Horner form: truncation error below 1e-16 on
 * [0, pi/4], and only correctly rounded operations, so every IEEE-754
 * platform gets the same bits. Exact zeros and ones at multiples of 90 deg. */
static void mrgi_scaling_sincos_turn(int64_t num, int64_t den, double* s, double* c)
{
  static const double half_pi = 1.57079632679489661923;
  num %= den;
  if (num < 0)
  {
    num += den;
  }
  const int64_t quarters = 4 * num; /* den < 2^40 in this file: no overflow */
  const int64_t quadrant = quarters / den;
  int64_t rest = quarters - quadrant * den; /* angle in quadrant = (pi/2) rest / den */
  const int complement = 2 * rest > den;
  if (complement)
  {
    rest = den - rest;
  }
  const double x = half_pi * ((double)rest / (double)den);
  const double x2 = x * x;
  const double sin_x =
    x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0 *
    (1.0 - x2 / 110.0 * (1.0 - x2 / 156.0 * (1.0 - x2 / 210.0)))))));
  const double cos_x =
    1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 *
    (1.0 - x2 / 90.0 * (1.0 - x2 / 132.0 * (1.0 - x2 / 182.0 * (1.0 - x2 / 240.0)))))));
  const double sin_q = complement ? cos_x : sin_x; /* within the quadrant */
  const double cos_q = complement ? sin_x : cos_x;
  switch (quadrant)
  {
    case 0:
      *s = sin_q;
      *c = cos_q;
      break;
    case 1:
      *s = cos_q;
      *c = -sin_q;
      break;
    case 2:
      *s = -sin_q;
      *c = -cos_q;
      break;
    default:
      *s = -cos_q;
      *c = sin_q;
      break;
  }
}

/* ---- what each object is (depends on seed and index only) ---- */

typedef enum mrgi_scaling_shape
{
  MRGI_SCALING_SPHERE = 0,
  MRGI_SCALING_TORUS = 1
} mrgi_scaling_shape;

typedef struct mrgi_scaling_object
{
  mrgi_scaling_shape shape;
  double center[3];
  double radius;      /* sphere radius, or torus major radius */
  double tube_radius; /* torus only */
  double tilt_sin, tilt_cos; /* torus axis tilt about x */
  int palette_index;
} mrgi_scaling_object;

/* Linear-RGB diffuse albedos: saturated enough that colour bleeding shows,
 * none above 0.85, so no surface is a near-perfect reflector. */
static const float mrgi_scaling_palette[8][3] = {
  { 0.80f, 0.80f, 0.80f }, /* white */
  { 0.75f, 0.25f, 0.20f }, /* red */
  { 0.25f, 0.60f, 0.25f }, /* green */
  { 0.20f, 0.35f, 0.75f }, /* blue */
  { 0.85f, 0.70f, 0.25f }, /* yellow */
  { 0.60f, 0.30f, 0.70f }, /* purple */
  { 0.25f, 0.70f, 0.70f }, /* cyan */
  { 0.85f, 0.50f, 0.25f }, /* orange */
};
static const float mrgi_scaling_ground_albedo[3] = { 0.5f, 0.5f, 0.5f };

static const double mrgi_scaling_cell_m = 1.0;
/* The tilt is drawn as k / 1024 turn, k in 0..256: 0..90 degrees in exact steps. */
static const int64_t mrgi_scaling_tilt_steps = 1024;

/* Every object consumes the same number of draws whatever its shape, so
 * object i's parameters depend only on (seed, i). */
static void mrgi_scaling_draw_object(mrgi_scaling_rng* rng, double cell_x, double cell_z,
                                     mrgi_scaling_object* object)
{
  const uint64_t shape_bits = mrgi_scaling_rng_next(rng);
  const double size = mrgi_scaling_rng_unit(rng);
  const double tube = mrgi_scaling_rng_unit(rng);
  const uint64_t tilt_bits = mrgi_scaling_rng_next(rng);
  const uint64_t colour_bits = mrgi_scaling_rng_next(rng);
  const double jitter_x = mrgi_scaling_rng_unit(rng);
  const double jitter_z = mrgi_scaling_rng_unit(rng);

  memset(object, 0, sizeof(*object));
  object->shape = (shape_bits >> 63) ? MRGI_SCALING_TORUS : MRGI_SCALING_SPHERE;
  object->palette_index = (int)(colour_bits >> 61); /* top 3 bits: 0..7 */
  /* Sizes keep every object under half a cell even at the coarsest
   * tessellation with its silhouette scale (sphere 0.38 * 1.140 + 0.04 =
   * 0.473, torus 1.111 (0.26 + 1.209 * 0.117) + 0.04 = 0.486): no overlaps. */
  const double jitter = 0.04 * mrgi_scaling_cell_m;
  object->center[0] = cell_x + (2.0 * jitter_x - 1.0) * jitter;
  object->center[2] = cell_z + (2.0 * jitter_z - 1.0) * jitter;
  if (object->shape == MRGI_SCALING_SPHERE)
  {
    object->radius = (0.25 + 0.13 * size) * mrgi_scaling_cell_m;
    object->tilt_cos = 1.0;
    object->center[1] = object->radius; /* resting on the ground */
  }
  else
  {
    object->radius = (0.18 + 0.08 * size) * mrgi_scaling_cell_m;
    object->tube_radius = object->radius * (0.30 + 0.15 * tube);
    const int64_t tilt_step = (int64_t)(tilt_bits % (uint64_t)(mrgi_scaling_tilt_steps / 4 + 1));
    mrgi_scaling_sincos_turn(tilt_step, mrgi_scaling_tilt_steps, &object->tilt_sin,
                             &object->tilt_cos);
    /* A torus whose axis leans by t from vertical reaches R sin t + r below its centre. */
    object->center[1] = object->radius * object->tilt_sin + object->tube_radius;
  }
}

/* ---- tessellation budget ---- */

/* Grid of a x c quads (a >= 3 rings or tube segments, c around): the largest
 * a * c <= k with a <= c <= 4a, ties to c nearest 2a (a sphere's c slices
 * span twice the angle of its a + 1 stacks; a torus tube is about half as
 * wide as its ring), then to the larger a (the coarser direction decides how
 * far facets cut into the silhouette). Any k >= 12 has a solution (3 x 4). */
static void mrgi_scaling_choose_grid(int64_t k, int64_t* rings, int64_t* around)
{
  int64_t best_a = 3, best_c = 4, best_product = 12;
  for (int64_t a = 3; a * a <= k; ++a)
  {
    int64_t c = k / a;
    c = c > 4 * a ? 4 * a : c;
    const int64_t product = a * c;
    const int64_t skew = c > 2 * a ? c - 2 * a : 2 * a - c;
    const int64_t best_skew = best_c > 2 * best_a ? best_c - 2 * best_a : 2 * best_a - best_c;
    if (product > best_product || (product == best_product && skew <= best_skew))
    {
      best_a = a;
      best_c = c;
      best_product = product;
    }
  }
  *rings = best_a;
  *around = best_c;
}

/* ---- mesh generation ---- */

/* Radius factor that gives a regular n-gon the perimeter of its circle,
 * pi / (n sin(pi / n)): 1.111 for a square, 1.026 for an octagon, 1.0004 for
 * 100 sides. An inscribed polygon's mean width (Cauchy: perimeter / pi) and
 * hence its silhouette shrink with coarse tessellation; scaled this way the
 * facets cut off about as much as they add, so the objects' projected areas
 * stay within a few percent of the exact shapes' at any triangle count
 * (TestSceneScaling measures it). Unscaled, 64 triangles per object lose
 * 11 % of their projected area on average. */
static double mrgi_scaling_silhouette_scale(int64_t n)
{
  static const double pi = 3.14159265358979323846;
  double s, c;
  mrgi_scaling_sincos_turn(1, 2 * n, &s, &c);
  return pi / ((double)n * s);
}

static void mrgi_scaling_put_vertex(mrgi_mesh* mesh, int64_t v, const mrgi_scaling_object* object,
                                    const double local[3], const double normal[3])
{
  /* Tilt about x (identity for spheres), then translate. */
  const double ty = object->tilt_cos * local[1] - object->tilt_sin * local[2];
  const double tz = object->tilt_sin * local[1] + object->tilt_cos * local[2];
  const double ny = object->tilt_cos * normal[1] - object->tilt_sin * normal[2];
  const double nz = object->tilt_sin * normal[1] + object->tilt_cos * normal[2];
  float* p = mesh->positions + 3 * v;
  float* n = mesh->normals + 3 * v;
  p[0] = (float)(object->center[0] + local[0]);
  p[1] = (float)(object->center[1] + ty);
  p[2] = (float)(object->center[2] + tz);
  n[0] = (float)normal[0];
  n[1] = (float)ny;
  n[2] = (float)nz;
}

static void mrgi_scaling_put_triangle(mrgi_mesh* mesh, int64_t t, int64_t a, int64_t b, int64_t c)
{
  uint32_t* tri = mesh->indices + 3 * t;
  tri[0] = (uint32_t)a;
  tri[1] = (uint32_t)b;
  tri[2] = (uint32_t)c;
}

/* Sine and cosine of j / count turn (or half turn) for j = 0..count, so the
 * per-vertex loops do no trigonometry. */
static void mrgi_scaling_fill_table(int64_t count, int64_t turn_divisor, double* sines,
                                    double* cosines)
{
  for (int64_t j = 0; j <= count; ++j)
  {
    mrgi_scaling_sincos_turn(j, turn_divisor, &sines[j], &cosines[j]);
  }
}

/* UV sphere: north pole, `rings` latitude rings of `around` vertices at polar
 * angles pi i / (rings + 1), south pole. 2 * rings * around triangles,
 * counter-clockwise seen from outside. The meridian polygon (2 (rings + 1)
 * sides) and the latitude polygons (`around` sides) get their silhouette
 * scales; normals stay the exact sphere's. */
static void mrgi_scaling_fill_sphere(mrgi_mesh* mesh, const mrgi_scaling_object* object,
                                     int64_t rings, int64_t around, const double* polar_sin,
                                     const double* polar_cos, const double* azim_sin,
                                     const double* azim_cos)
{
  const double r = object->radius * mrgi_scaling_silhouette_scale(2 * (rings + 1));
  const double r_around = r * mrgi_scaling_silhouette_scale(around);
  const int64_t south = 1 + rings * around;
  const double up[3] = { 0.0, 1.0, 0.0 };
  const double down[3] = { 0.0, -1.0, 0.0 };
  const double north_pos[3] = { 0.0, r, 0.0 };
  const double south_pos[3] = { 0.0, -r, 0.0 };
  mrgi_scaling_put_vertex(mesh, 0, object, north_pos, up);
  for (int64_t i = 1; i <= rings; ++i)
  {
    for (int64_t j = 0; j < around; ++j)
    {
      const double normal[3] = { polar_sin[i] * azim_cos[j], polar_cos[i],
                                 polar_sin[i] * azim_sin[j] };
      const double local[3] = { r_around * normal[0], r * normal[1], r_around * normal[2] };
      mrgi_scaling_put_vertex(mesh, 1 + (i - 1) * around + j, object, local, normal);
    }
  }
  mrgi_scaling_put_vertex(mesh, south, object, south_pos, down);

  int64_t t = 0;
  for (int64_t j = 0; j < around; ++j)
  {
    const int64_t next = (j + 1) % around;
    mrgi_scaling_put_triangle(mesh, t++, 0, 1 + next, 1 + j);
  }
  for (int64_t i = 1; i < rings; ++i)
  {
    const int64_t upper = 1 + (i - 1) * around, lower = upper + around;
    for (int64_t j = 0; j < around; ++j)
    {
      const int64_t next = (j + 1) % around;
      mrgi_scaling_put_triangle(mesh, t++, upper + j, upper + next, lower + next);
      mrgi_scaling_put_triangle(mesh, t++, upper + j, lower + next, lower + j);
    }
  }
  const int64_t last = 1 + (rings - 1) * around;
  for (int64_t j = 0; j < around; ++j)
  {
    const int64_t next = (j + 1) % around;
    mrgi_scaling_put_triangle(mesh, t++, last + j, last + next, south);
  }
}

/* Torus about the local y axis: `around` segments around the axis, `rings`
 * around the tube. 2 * rings * around triangles, counter-clockwise seen from
 * outside. Tube and ring polygons get their silhouette scales; normals stay
 * the exact torus's. */
static void mrgi_scaling_fill_torus(mrgi_mesh* mesh, const mrgi_scaling_object* object,
                                    int64_t rings, int64_t around, const double* tube_sin,
                                    const double* tube_cos, const double* azim_sin,
                                    const double* azim_cos)
{
  const double around_scale = mrgi_scaling_silhouette_scale(around);
  const double big = object->radius, small = object->tube_radius * mrgi_scaling_silhouette_scale(rings);
  for (int64_t i = 0; i < around; ++i)
  {
    for (int64_t j = 0; j < rings; ++j)
    {
      const double normal[3] = { tube_cos[j] * azim_cos[i], tube_sin[j],
                                 tube_cos[j] * azim_sin[i] };
      const double reach = around_scale * (big + small * tube_cos[j]);
      const double local[3] = { reach * azim_cos[i], small * tube_sin[j], reach * azim_sin[i] };
      mrgi_scaling_put_vertex(mesh, i * rings + j, object, local, normal);
    }
  }
  int64_t t = 0;
  for (int64_t i = 0; i < around; ++i)
  {
    const int64_t i_next = (i + 1) % around;
    for (int64_t j = 0; j < rings; ++j)
    {
      const int64_t j_next = (j + 1) % rings;
      const int64_t a = i * rings + j, b = i_next * rings + j;
      const int64_t c = i * rings + j_next, d = i_next * rings + j_next;
      mrgi_scaling_put_triangle(mesh, t++, a, c, d);
      mrgi_scaling_put_triangle(mesh, t++, a, d, b);
    }
  }
}

static mrgi_status mrgi_scaling_build_object(const mrgi_scaling_object* object, int64_t index,
                                             int64_t quads, mrgi_mesh* mesh, mrgi_error* err)
{
  int64_t rings = 0, around = 0;
  mrgi_scaling_choose_grid(quads, &rings, &around);
  const int is_sphere = object->shape == MRGI_SCALING_SPHERE;
  char name[MRGI_MESH_NAME_SIZE];
  snprintf(name, sizeof(name), "%s_%04d", is_sphere ? "sphere" : "torus", (int)index);
  const int64_t vertex_count = is_sphere ? 2 + rings * around : rings * around;
  mrgi_status status = mrgi_mesh_create(mesh, name, vertex_count, 2 * rings * around, 1, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  /* Tables: polar (half turns of rings + 1 steps) or tube angles, and azimuths. */
  const size_t ring_entries = (size_t)rings + 2, around_entries = (size_t)around + 1;
  double* table = malloc(2 * (ring_entries + around_entries) * sizeof(double));
  if (!table)
  {
    mrgi_mesh_destroy(mesh);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "mesh '%s': cannot allocate angle tables",
                          name);
  }
  double* ring_sin = table;
  double* ring_cos = ring_sin + ring_entries;
  double* azim_sin = ring_cos + ring_entries;
  double* azim_cos = azim_sin + around_entries;
  mrgi_scaling_fill_table(around, around, azim_sin, azim_cos);
  if (is_sphere)
  {
    mrgi_scaling_fill_table(rings + 1, 2 * (rings + 1), ring_sin, ring_cos);
    mrgi_scaling_fill_sphere(mesh, object, rings, around, ring_sin, ring_cos, azim_sin, azim_cos);
  }
  else
  {
    mrgi_scaling_fill_table(rings, rings, ring_sin, ring_cos);
    mrgi_scaling_fill_torus(mesh, object, rings, around, ring_sin, ring_cos, azim_sin, azim_cos);
  }
  free(table);
  memcpy(mesh->albedo, mrgi_scaling_palette[object->palette_index], sizeof(mesh->albedo));
  return MRGI_OK;
}

/* The ground rectangle as `triangles` (>= 2) triangles: a strip of quads
 * along x and, for an odd count, a pentagon fan at the +x end (its extra
 * vertex lies on the outer edge, so no T-junction). Normals +y. */
static mrgi_status mrgi_scaling_build_ground(const double extent[4], int64_t triangles,
                                             mrgi_mesh* mesh, mrgi_error* err)
{
  const int64_t quads = triangles / 2;
  const int odd = (int)(triangles % 2);
  mrgi_status status = mrgi_mesh_create(mesh, "ground", 4 * quads + odd, triangles, 1, err);
  mrgi_mesh_cursor cursor = { 0, 0 };
  const double x0 = extent[0], x1 = extent[1], z0 = extent[2], z1 = extent[3];
  for (int64_t q = 0; status == MRGI_OK && q < quads; ++q)
  {
    const float xa = (float)(x0 + (x1 - x0) * (double)q / (double)quads);
    const float xb = q + 1 == quads ? (float)x1 : (float)(x0 + (x1 - x0) * (double)(q + 1) / (double)quads);
    /* Counter-clockwise seen from above: (xa,z0) (xa,z1) (xb,z1) [(xb,mid)] (xb,z0). */
    const float polygon[5][3] = { { xa, 0.0f, (float)z0 },
                                  { xa, 0.0f, (float)z1 },
                                  { xb, 0.0f, (float)z1 },
                                  { xb, 0.0f, (float)(0.5 * (z0 + z1)) },
                                  { xb, 0.0f, (float)z0 } };
    const int pentagon = odd && q + 1 == quads;
    if (pentagon)
    {
      status = mrgi_mesh_put_polygon(mesh, &cursor, polygon, 5, err);
    }
    else
    {
      const float quad[4][3] = { { xa, 0.0f, (float)z0 },
                                 { xa, 0.0f, (float)z1 },
                                 { xb, 0.0f, (float)z1 },
                                 { xb, 0.0f, (float)z0 } };
      status = mrgi_mesh_put_polygon(mesh, &cursor, quad, 4, err);
    }
  }
  if (status == MRGI_OK)
  {
    status = mrgi_mesh_cursor_finish(mesh, &cursor, err);
  }
  if (status == MRGI_OK)
  {
    memcpy(mesh->albedo, mrgi_scaling_ground_albedo, sizeof(mesh->albedo));
  }
  return status;
}

/* ---- the scene ---- */

int64_t mrgi_scene_scaling_min_triangles(int64_t object_count)
{
  if (object_count < 1 || object_count > MRGI_SCALING_MAX_OBJECTS)
  {
    return -1;
  }
  return MRGI_SCALING_GROUND_TRIANGLES + MRGI_SCALING_MIN_TRIANGLES_PER_OBJECT * object_count;
}

static void mrgi_scaling_camera_and_lights(int64_t columns, int64_t rows, mrgi_scene* scene)
{
  /* A sphere around the target that holds every object: the grid's half
   * diagonal plus more than the tallest object (a coarse torus on edge,
   * 0.377 + 0.446 = 0.82 m). */
  const double half_x = 0.5 * (double)columns * mrgi_scaling_cell_m;
  const double half_z = 0.5 * (double)rows * mrgi_scaling_cell_m;
  const double radius = sqrt(half_x * half_x + half_z * half_z) + 0.9 * mrgi_scaling_cell_m;
  double elevation_sin, elevation_cos, half_view_sin, half_view_cos;
  mrgi_scaling_sincos_turn(35, 360, &elevation_sin, &elevation_cos);
  mrgi_scaling_sincos_turn(15, 360, &half_view_sin, &half_view_cos);
  const double distance = radius / half_view_sin;

  mrgi_camera* camera = &scene->camera;
  camera->focal_point[1] = 0.3 * mrgi_scaling_cell_m;
  camera->position[0] = 0.0;
  camera->position[1] = camera->focal_point[1] + distance * elevation_sin;
  camera->position[2] = -distance * elevation_cos;
  camera->view_up[1] = 1.0;
  camera->view_angle_deg = 30.0;

  /* Spot with a 45 degree cone: at height 1.1 g the ground's corners (half
   * diagonal g, ground one cell wider than the grid) are atan(1 / 1.1) =
   * 42.3 degrees off the axis, inside the cone. */
  const double ground_x = half_x + mrgi_scaling_cell_m, ground_z = half_z + mrgi_scaling_cell_m;
  const double ground_half_diagonal = sqrt(ground_x * ground_x + ground_z * ground_z);
  mrgi_light* spot = &scene->lights[0];
  spot->type = MRGI_LIGHT_SPOT;
  spot->position[1] = 1.1 * ground_half_diagonal;
  spot->color[0] = spot->color[1] = spot->color[2] = 1.0;
  spot->intensity = 1.0;
  spot->cone_angle_deg = 45.0;
  spot->exponent = 1.0;

  mrgi_light* sun = &scene->lights[1];
  sun->type = MRGI_LIGHT_DIRECTIONAL;
  sun->position[0] = -1.0;
  sun->position[1] = 2.0;
  sun->position[2] = -0.5;
  sun->color[0] = sun->color[1] = sun->color[2] = 1.0;
  sun->intensity = 0.5;
  sun->cone_angle_deg = 90.0;
  sun->exponent = 1.0;
  scene->light_count = 2;
}

mrgi_status mrgi_scene_scaling(int64_t object_count, int64_t triangle_count, uint64_t seed,
                               mrgi_scene* out, mrgi_error* err)
{
  static const char* caller = "mrgi_scene_scaling";
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: out is NULL", caller);
  }
  memset(out, 0, sizeof(*out));
  if (object_count < 1 || object_count > MRGI_SCALING_MAX_OBJECTS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: object_count %" PRId64 " is outside 1..%d", caller, object_count,
                          MRGI_SCALING_MAX_OBJECTS);
  }
  const int64_t min_triangles = mrgi_scene_scaling_min_triangles(object_count);
  if (triangle_count < min_triangles || triangle_count > MRGI_SCALING_MAX_TRIANGLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: triangle_count %" PRId64 " is outside %" PRId64 "..%d for %" PRId64
                          " objects (each object needs %d triangles, the ground %d)",
                          caller, triangle_count, min_triangles, MRGI_SCALING_MAX_TRIANGLES,
                          object_count, MRGI_SCALING_MIN_TRIANGLES_PER_OBJECT,
                          MRGI_SCALING_GROUND_TRIANGLES);
  }

  int64_t columns = 1;
  while (columns * columns < object_count)
  {
    ++columns;
  }
  const int64_t rows = (object_count + columns - 1) / columns;

  mrgi_status status = mrgi_scene_create(out, (int32_t)(object_count + 1), err);
  mrgi_scaling_rng rng = { seed };
  /* Error diffusion: each object takes at most its share of what is left,
   * so the total never overshoots and the leftover is small. */
  int64_t remaining = triangle_count - MRGI_SCALING_GROUND_TRIANGLES;
  for (int64_t i = 0; status == MRGI_OK && i < object_count; ++i)
  {
    const double cell_x = ((double)(i % columns) + 0.5 - 0.5 * (double)columns) * mrgi_scaling_cell_m;
    const double cell_z = ((double)(i / columns) + 0.5 - 0.5 * (double)rows) * mrgi_scaling_cell_m;
    mrgi_scaling_object object;
    mrgi_scaling_draw_object(&rng, cell_x, cell_z, &object);
    const int64_t share = remaining / (object_count - i);
    mrgi_mesh* mesh = &out->meshes[1 + i];
    status = mrgi_scaling_build_object(&object, i, share / 2, mesh, err);
    remaining -= status == MRGI_OK ? mesh->triangle_count : 0;
  }
  if (status == MRGI_OK)
  {
    const double half_x = 0.5 * (double)columns * mrgi_scaling_cell_m + mrgi_scaling_cell_m;
    const double half_z = 0.5 * (double)rows * mrgi_scaling_cell_m + mrgi_scaling_cell_m;
    const double extent[4] = { -half_x, half_x, -half_z, half_z };
    status = mrgi_scaling_build_ground(extent, MRGI_SCALING_GROUND_TRIANGLES + remaining,
                                       &out->meshes[0], err);
  }
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "%s: ", caller);
    mrgi_scene_destroy(out);
    return status;
  }
  mrgi_scaling_camera_and_lights(columns, rows, out);
  return MRGI_OK;
}
