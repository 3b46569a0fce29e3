/* Ground-truth renderer: Embree 3 ray casting of direct light and one diffuse
 * bounce in VTK's lighting model. The contract is in mrgi_reference.h; this
 * file follows its order: options, geometry upload, lighting, sampling, the
 * per-pixel kernel, threads and passes. */
/* clock_gettime, sysconf(_SC_NPROCESSORS_ONLN): POSIX.1-2008 */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_reference.h"
#include "mrgi_reference_noise.h"

#include <embree3/rtcore.h>

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define REF_PI 3.14159265358979323846

/* ---- small vector helpers (double) ---- */

static double ref_dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void ref_cross(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Normalize in place; returns the former length (0 leaves v unchanged). */
static double ref_normalize(double v[3])
{
  const double len = sqrt(ref_dot(v, v));
  if (len > 0.0 && isfinite(len))
  {
    v[0] /= len;
    v[1] /= len;
    v[2] /= len;
  }
  return len;
}

static double ref_seconds_now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- random numbers: splitmix64 ----
 * Steele, Lea and Flood, "Fast Splittable Pseudorandom Number Generators",
 * OOPSLA 2014 (constants of Vigna's public-domain splitmix64.c). One word of
 * state, so every pixel of every pass can own a stream keyed by (seed, pass,
 * pixel): images then do not depend on how rows are shared among threads. */

static uint64_t ref_mix64(uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

static uint64_t ref_rng_next(uint64_t* state)
{
  *state += 0x9E3779B97F4A7C15ULL;
  return ref_mix64(*state);
}

/* Uniform in [0, 1): the top 53 bits scaled by 2^-53. */
static double ref_rng_unit(uint64_t* state)
{
  return (double)(ref_rng_next(state) >> 11) * 0x1.0p-53;
}

/* ---- options ---- */

void mrgi_reference_options_default(mrgi_reference_options* options)
{
  if (!options)
  {
    return;
  }
  memset(options, 0, sizeof(*options));
  options->width = 256;
  options->height = 256;
  options->pixel_samples = 1;
  options->indirect_samples = 16;
  options->target_relative_error = MRGI_REFERENCE_DEFAULT_TARGET;
  options->target_percentile = MRGI_REFERENCE_DEFAULT_PERCENTILE;
  options->max_passes = MRGI_REFERENCE_DEFAULT_MAX_PASSES;
  options->max_seconds = 0.0;
  options->shadows = 1;
  options->secondary_visibility = 1;
  options->shading_normals = 1;
  options->parallel_projection = 0;
  options->parallel_scale = 1.0;
  options->seed = 1;
  options->threads = 0;
  options->area_light_samples = 16;
}

static mrgi_status ref_check_int(const char* name, int32_t value, int32_t lo, int32_t hi,
                                 mrgi_error* err)
{
  if (value < lo || value > hi)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option %s = %d is outside %d..%d", name, (int)value,
                          (int)lo, (int)hi);
  }
  return MRGI_OK;
}

mrgi_status mrgi_reference_options_validate(const mrgi_reference_options* o, mrgi_error* err)
{
  if (!o)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_reference: options is NULL");
  }
  mrgi_status s = ref_check_int("width", o->width, 1, MRGI_REFERENCE_MAX_DIMENSION, err);
  if (!s)
    s = ref_check_int("height", o->height, 1, MRGI_REFERENCE_MAX_DIMENSION, err);
  if (!s)
    s = ref_check_int("pixel_samples", o->pixel_samples, 1, MRGI_REFERENCE_MAX_PIXEL_SAMPLES, err);
  if (!s)
    s = ref_check_int("indirect_samples", o->indirect_samples, 0,
                      MRGI_REFERENCE_MAX_INDIRECT_SAMPLES, err);
  if (!s)
    s = ref_check_int("max_passes", o->max_passes, 1, MRGI_REFERENCE_MAX_PASSES, err);
  if (!s)
    s = ref_check_int("shadows", o->shadows, 0, 1, err);
  if (!s)
    s = ref_check_int("secondary_visibility", o->secondary_visibility, 0, 1, err);
  if (!s)
    s = ref_check_int("shading_normals", o->shading_normals, 0, 1, err);
  if (!s)
    s = ref_check_int("parallel_projection", o->parallel_projection, 0, 1, err);
  if (!s)
    s = ref_check_int("threads", o->threads, 0, MRGI_REFERENCE_MAX_THREADS, err);
  if (!s)
    s = ref_check_int("area_light_samples", o->area_light_samples, 0,
                      MRGI_REFERENCE_MAX_AREA_LIGHT_SAMPLES, err);
  if (s)
  {
    return s;
  }
  if (!(isfinite(o->target_relative_error) && o->target_relative_error >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option target_relative_error = %g is not finite and >= 0",
                          o->target_relative_error);
  }
  if (!(o->target_percentile > 0.0 && o->target_percentile <= 1.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option target_percentile = %g is outside (0, 1]",
                          o->target_percentile);
  }
  if (!(isfinite(o->max_seconds) && o->max_seconds >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option max_seconds = %g is not finite and >= 0",
                          o->max_seconds);
  }
  if (o->parallel_projection && !(isfinite(o->parallel_scale) && o->parallel_scale > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference: option parallel_scale = %g is not finite and > 0",
                          o->parallel_scale);
  }
  return MRGI_OK;
}

/* ---- shared state of one render ---- */

/* One Embree geometry: the mesh it came from and, because skipped triangles
 * leave gaps, the mesh triangle behind each Embree primitive. */
typedef struct ref_geometry
{
  const mrgi_mesh* mesh;
  uint32_t* triangle_of_prim;
  int emitter;
} ref_geometry;

/* A light reduced to what the kernel needs. */
typedef struct ref_light
{
  int directional;
  int spot;
  double position[3];
  double to_light[3]; /* directional only: unit l, constant */
  double axis[3];     /* spot only: unit focal_point - position */
  double cos_cone;
  double exponent;
  double rgb[3]; /* intensity * color */
} ref_light;

/* An area light reduced to what the kernel needs. */
typedef struct ref_area_light
{
  const mrgi_area_light* light; /* borrowed: mrgi_area_light_emitted() */
  double center[3], edge_u[3], edge_v[3];
  double normal[3]; /* unit, edge_u x edge_v */
  double weight;    /* area / (pi * cells): one cell's share of (1/pi) int dA */
  int32_t cells_u, cells_v;
  int two_sided;
} ref_area_light;

typedef struct ref_shared
{
  RTCScene rtc;
  const ref_geometry* geometries;
  ref_light lights[MRGI_SCENE_MAX_LIGHTS];
  int32_t light_count;
  ref_area_light area_lights[MRGI_REFERENCE_MAX_AREA_LIGHTS];
  int32_t area_light_count;
  mrgi_reference_options options;
  /* camera frame */
  double eye[3], forward[3], right[3], up[3];
  double half_height; /* tan(fov/2) or parallel_scale */
  double aspect;
  double epsilon_floor; /* 1 % of the scene extent, see ref_epsilon */
  /* accumulators, one slot per pixel; each row is written by one thread per pass */
  double* sums;       /* 9 per pixel: direct rgb, indirect rgb, albedo rgb */
  double* est_mean;   /* Welford running mean of the per-pass indirect estimate */
  double* est_m2;     /* Welford sum of squared deviations */
  double* dir_mean;   /* the same for the per-pass direct estimate (area lights only) */
  double* dir_m2;
  uint8_t* hit;       /* 1 once any primary ray of the pixel hit a surface */
  double* noise_scratch; /* one double per pixel for the percentile, allocated once */
  int32_t pass;
  atomic_int next_row;
} ref_shared;

typedef struct ref_hit_record
{
  float t;
  uint32_t geom_id, prim_id;
  float ng[3];
  float u, v;
} ref_hit_record;

/* Embree passes the context to the filter; ours extends it (first member,
 * the pattern of Embree's own tutorials) with the hit list of one ray. */
typedef struct ref_collect_context
{
  struct RTCIntersectContext rtc;
  ref_hit_record* hits;
  int32_t count;
  int32_t overflowed;
} ref_collect_context;

typedef struct ref_worker
{
  ref_shared* shared;
  ref_hit_record* hits; /* MRGI_REFERENCE_MAX_RAY_HITS, allocated once per render */
  int64_t rays;
  int64_t overflows;
  /* Area-light points of the bounce's L(q): a stream of its own per (pass,
   * pixel), so the point lights' bounce is unchanged by area lights. */
  uint64_t bounce_area_rng;
} ref_worker;

/* A surface point as the kernel sees it. */
typedef struct ref_surface
{
  double p[3];
  double ng[3]; /* unit geometric normal, turned towards the ray's origin */
  double ns[3]; /* unit shading normal on the same side */
  double epsilon;
  const ref_geometry* geometry;
} ref_surface;

/* Offset for rays leaving p: 1e-5 of max(|p|_inf, 1 % of the extent). Float
 * positions carry a relative error of ~6e-8, Embree's hit points a few ulps
 * more; 1e-5 is ~100 ulps, far below any feature of a sane scene. */
static double ref_epsilon(const ref_shared* shared, const double p[3])
{
  double m = fabs(p[0]);
  m = fabs(p[1]) > m ? fabs(p[1]) : m;
  m = fabs(p[2]) > m ? fabs(p[2]) : m;
  m = shared->epsilon_floor > m ? shared->epsilon_floor : m;
  return 1e-5 * m;
}

static void ref_ray_init(struct RTCRay* ray, const double org[3], const double dir[3],
                         double tfar)
{
  ray->org_x = (float)org[0];
  ray->org_y = (float)org[1];
  ray->org_z = (float)org[2];
  ray->tnear = 0.0f;
  ray->dir_x = (float)dir[0];
  ray->dir_y = (float)dir[1];
  ray->dir_z = (float)dir[2];
  ray->time = 0.0f;
  ray->tfar = isfinite(tfar) ? (float)tfar : INFINITY;
  ray->mask = 0xFFFFFFFFu;
  ray->id = 0;
  ray->flags = 0;
}

/* Fill `s` from an Embree hit of the ray org + t dir. */
static void ref_surface_from_hit(const ref_shared* shared, uint32_t geom_id, uint32_t prim_id,
                                 const float ng[3], float u, float v, const double org[3],
                                 const double dir[3], double t, ref_surface* s)
{
  const ref_geometry* g = &shared->geometries[geom_id];
  s->geometry = g;
  for (int k = 0; k < 3; ++k)
  {
    s->p[k] = org[k] + t * dir[k];
    s->ng[k] = (double)ng[k];
  }
  ref_normalize(s->ng);
  if (ref_dot(s->ng, dir) > 0.0)
  {
    s->ng[0] = -s->ng[0];
    s->ng[1] = -s->ng[1];
    s->ng[2] = -s->ng[2];
  }
  s->ns[0] = s->ng[0];
  s->ns[1] = s->ng[1];
  s->ns[2] = s->ng[2];
  const mrgi_mesh* mesh = g->mesh;
  if (shared->options.shading_normals && mesh->normals)
  {
    /* Embree's barycentrics: p = (1-u-v) v0 + u v1 + v v2. */
    const uint32_t* tri = mesh->indices + 3 * (size_t)g->triangle_of_prim[prim_id];
    const double w[3] = { 1.0 - (double)u - (double)v, (double)u, (double)v };
    double n[3] = { 0.0, 0.0, 0.0 };
    for (int c = 0; c < 3; ++c)
    {
      const float* nv = mesh->normals + 3 * (size_t)tri[c];
      for (int k = 0; k < 3; ++k)
      {
        n[k] += w[c] * (double)nv[k];
      }
    }
    /* VTK flips the vertex normal of a back face (gl_FrontFacing); vertex
     * normals point to the front (mrgi_mesh.h), so turning n to the side of
     * the oriented geometric normal is the same flip. */
    if (ref_normalize(n) > 0.0)
    {
      const double sgn = ref_dot(n, s->ng) < 0.0 ? -1.0 : 1.0;
      for (int k = 0; k < 3; ++k)
      {
        s->ns[k] = sgn * n[k];
      }
    }
  }
  s->epsilon = ref_epsilon(shared, s->p);
}

/* VTK irradiance X at s (see mrgi_reference.h), optionally with shadows. */
static void ref_irradiance(ref_worker* w, const ref_surface* s, int shadowed, double x[3])
{
  const ref_shared* shared = w->shared;
  x[0] = x[1] = x[2] = 0.0;
  for (int32_t i = 0; i < shared->light_count; ++i)
  {
    const ref_light* light = &shared->lights[i];
    double l[3];
    double distance = INFINITY;
    if (light->directional)
    {
      l[0] = light->to_light[0];
      l[1] = light->to_light[1];
      l[2] = light->to_light[2];
    }
    else
    {
      for (int k = 0; k < 3; ++k)
      {
        l[k] = light->position[k] - s->p[k];
      }
      distance = ref_normalize(l);
      if (!(distance > 0.0))
      {
        continue; /* the light sits on the surface: no direction, VTK gives 0 as well */
      }
    }
    const double n_dot_l = ref_dot(s->ns, l);
    if (!(n_dot_l > 0.0))
    {
      continue;
    }
    double spot = 1.0;
    if (light->spot)
    {
      const double cos_a = -ref_dot(l, light->axis);
      if (!(cos_a >= light->cos_cone))
      {
        continue;
      }
      spot = pow(cos_a > 0.0 ? cos_a : 0.0, light->exponent);
    }
    if (shadowed)
    {
      /* Light behind the geometric surface (possible with shading normals):
       * the surface itself is in the way. */
      if (!(ref_dot(s->ng, l) > 0.0))
      {
        continue;
      }
      double org[3];
      for (int k = 0; k < 3; ++k)
      {
        org[k] = s->p[k] + s->epsilon * s->ng[k];
      }
      struct RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      struct RTCRay ray;
      ref_ray_init(&ray, org, l, distance - 2.0 * s->epsilon);
      if (!(ray.tfar > 0.0f))
      {
        ray.tfar = 0.0f;
      }
      rtcOccluded1(shared->rtc, &context, &ray);
      ++w->rays;
      if (ray.tfar < 0.0f)
      {
        continue; /* Embree marks an occluded ray with tfar = -inf */
      }
    }
    const double f = n_dot_l * spot;
    for (int k = 0; k < 3; ++k)
    {
      x[k] += light->rgb[k] * f;
    }
  }
}

/* VTK irradiance X_area at s from the area lights (mrgi_reference.h):
 * stratified points, one per cell of each light's grid, each tested with a
 * shadow ray when `shadowed`. */
static void ref_area_irradiance(ref_worker* w, const ref_surface* s, int shadowed, uint64_t* rng,
                                double x[3])
{
  const ref_shared* shared = w->shared;
  x[0] = x[1] = x[2] = 0.0;
  for (int32_t i = 0; i < shared->area_light_count; ++i)
  {
    const ref_area_light* a = &shared->area_lights[i];
    for (int32_t cv = 0; cv < a->cells_v; ++cv)
    {
      for (int32_t cu = 0; cu < a->cells_u; ++cu)
      {
        const double su = ((double)cu + ref_rng_unit(rng)) / (double)a->cells_u;
        const double tv = ((double)cv + ref_rng_unit(rng)) / (double)a->cells_v;
        double y[3], l[3];
        for (int k = 0; k < 3; ++k)
        {
          y[k] = a->center[k] + (su - 0.5) * a->edge_u[k] + (tv - 0.5) * a->edge_v[k];
          l[k] = y[k] - s->p[k];
        }
        const double distance = ref_normalize(l);
        if (!(distance > 0.0))
        {
          continue; /* the point lies on the surface: no direction */
        }
        const double cos_p = ref_dot(s->ns, l);
        double cos_y = -ref_dot(a->normal, l);
        if (a->two_sided)
        {
          cos_y = fabs(cos_y);
        }
        if (!(cos_p > 0.0) || !(cos_y > 0.0))
        {
          continue;
        }
        double radiance[3];
        mrgi_area_light_emitted(a->light, su, tv, radiance);
        if (!(radiance[0] > 0.0 || radiance[1] > 0.0 || radiance[2] > 0.0))
        {
          continue; /* black texel: no shadow ray needed */
        }
        if (shadowed)
        {
          if (!(ref_dot(s->ng, l) > 0.0))
          {
            continue; /* behind the geometric surface (shading normals) */
          }
          double org[3], dir[3];
          for (int k = 0; k < 3; ++k)
          {
            org[k] = s->p[k] + s->epsilon * s->ng[k];
            dir[k] = y[k] - org[k];
          }
          const double reach = ref_normalize(dir);
          /* Stop short of y, so that a surface in the light's plane (its
           * emitter quad) does not hide it. */
          double margin = ref_epsilon(shared, y);
          margin = s->epsilon > margin ? s->epsilon : margin;
          margin = 1e-5 * reach > margin ? 1e-5 * reach : margin;
          struct RTCIntersectContext context;
          rtcInitIntersectContext(&context);
          struct RTCRay ray;
          ref_ray_init(&ray, org, dir, reach - 2.0 * margin);
          if (!(ray.tfar > 0.0f))
          {
            ray.tfar = 0.0f;
          }
          rtcOccluded1(shared->rtc, &context, &ray);
          ++w->rays;
          if (ray.tfar < 0.0f)
          {
            continue; /* occluded */
          }
        }
        const double f = a->weight * cos_p * cos_y / (distance * distance);
        for (int k = 0; k < 3; ++k)
        {
          x[k] += radiance[k] * f;
        }
      }
    }
  }
}

/* Outgoing radiance of q towards the ray's origin, shadowed: albedo_q * X_q;
 * 0 for emitters (their emission is not part of the one bounce). */
static void ref_bounce_radiance(ref_worker* w, const ref_surface* q, double out[3])
{
  out[0] = out[1] = out[2] = 0.0;
  if (q->geometry->emitter)
  {
    return;
  }
  double x[3];
  ref_irradiance(w, q, 1, x);
  if (w->shared->area_light_count > 0)
  {
    /* The area lights' one bounce: X_area(q), shadowed as the direct path
     * shadows it (an RSM holds lit surfaces; mrgi_area_light_rsm.h). */
    double x_area[3];
    ref_area_irradiance(w, q, 1, &w->bounce_area_rng, x_area);
    for (int k = 0; k < 3; ++k)
    {
      x[k] += x_area[k];
    }
  }
  const float* albedo = q->geometry->mesh->albedo;
  for (int k = 0; k < 3; ++k)
  {
    out[k] = (double)albedo[k] * x[k];
  }
}

/* Cosine-weighted direction about unit n (pdf cos/pi): Malley's method,
 * uniform disk point lifted to the hemisphere; frame of Duff et al.,
 * "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017. */
static void ref_sample_cosine(const double n[3], double u1, double u2, double out[3])
{
  const double r = sqrt(u1);
  const double phi = 2.0 * REF_PI * u2;
  const double lx = r * cos(phi), ly = r * sin(phi);
  const double lz = sqrt(1.0 - u1 > 0.0 ? 1.0 - u1 : 0.0);
  const double sign = copysign(1.0, n[2]);
  const double a = -1.0 / (sign + n[2]);
  const double b = n[0] * n[1] * a;
  const double b1[3] = { 1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0] };
  const double b2[3] = { b, sign + n[1] * n[1] * a, -n[1] };
  for (int k = 0; k < 3; ++k)
  {
    out[k] = lx * b1[k] + ly * b2[k] + lz * n[k];
  }
}

/* Embree context filter of the RSM mode: record every candidate hit and
 * reject it, so traversal goes on to all the surfaces along the ray. Spatial
 * splits can report one primitive twice: keep the first. Called with N = 1
 * (rtcIntersect1); the SOA layouts are those of rtcore_ray.h. */
static void ref_collect_filter(const struct RTCFilterFunctionNArguments* args)
{
  ref_collect_context* ctx = (ref_collect_context*)args->context;
  const unsigned int n = args->N;
  const float* ray = (const float*)args->ray;
  const float* hit = (const float*)args->hit;
  const unsigned int* hit_u = (const unsigned int*)args->hit;
  for (unsigned int i = 0; i < n; ++i)
  {
    if (!args->valid[i])
    {
      continue;
    }
    args->valid[i] = 0;
    const uint32_t prim_id = hit_u[5 * n + i];
    const uint32_t geom_id = hit_u[6 * n + i];
    int duplicate = 0;
    for (int32_t j = 0; j < ctx->count && !duplicate; ++j)
    {
      duplicate = ctx->hits[j].prim_id == prim_id && ctx->hits[j].geom_id == geom_id;
    }
    if (duplicate)
    {
      continue;
    }
    if (ctx->count >= MRGI_REFERENCE_MAX_RAY_HITS)
    {
      ctx->overflowed = 1;
      continue;
    }
    ref_hit_record* r = &ctx->hits[ctx->count++];
    r->t = ray[8 * n + i];
    r->ng[0] = hit[0 * n + i];
    r->ng[1] = hit[1 * n + i];
    r->ng[2] = hit[2 * n + i];
    r->u = hit[3 * n + i];
    r->v = hit[4 * n + i];
    r->prim_id = prim_id;
    r->geom_id = geom_id;
  }
}

/* Gather along one bounce ray from p: L(q) of the nearest surface
 * (secondary_visibility) or the sum over all distinct surfaces crossed. */
static void ref_gather(ref_worker* w, const double org[3], const double dir[3], double out[3])
{
  const ref_shared* shared = w->shared;
  out[0] = out[1] = out[2] = 0.0;
  ++w->rays;
  if (shared->options.secondary_visibility)
  {
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    struct RTCRayHit rh;
    ref_ray_init(&rh.ray, org, dir, INFINITY);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(shared->rtc, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
    {
      return;
    }
    const float ng[3] = { rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z };
    ref_surface q;
    ref_surface_from_hit(shared, rh.hit.geomID, rh.hit.primID, ng, rh.hit.u, rh.hit.v, org, dir,
                         (double)rh.ray.tfar, &q);
    ref_bounce_radiance(w, &q, out);
    return;
  }
  ref_collect_context ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.rtc.filter = ref_collect_filter;
  ctx.hits = w->hits;
  ctx.count = 0;
  ctx.overflowed = 0;
  struct RTCRayHit rh;
  ref_ray_init(&rh.ray, org, dir, INFINITY);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(shared->rtc, &ctx.rtc, &rh);
  w->overflows += ctx.overflowed;
  /* Sort by distance (insertion sort: lists are short), then merge hits at
   * the same distance: one surface split into triangles is hit on their
   * shared edge by both, and coincident copies of a surface are one surface
   * to a reflective shadow map (its depth test keeps one). */
  ref_hit_record* h = ctx.hits;
  for (int32_t i = 1; i < ctx.count; ++i)
  {
    const ref_hit_record key = h[i];
    int32_t j = i - 1;
    while (j >= 0 && (h[j].t > key.t || (h[j].t == key.t && (h[j].geom_id > key.geom_id ||
                                                           (h[j].geom_id == key.geom_id &&
                                                            h[j].prim_id > key.prim_id)))))
    {
      h[j + 1] = h[j];
      --j;
    }
    h[j + 1] = key;
  }
  double kept_t = -INFINITY;
  for (int32_t i = 0; i < ctx.count; ++i)
  {
    const double t = (double)h[i].t;
    if (t - kept_t <= 4e-6 * t + ref_epsilon(shared, org) * 1e-2)
    {
      continue;
    }
    kept_t = t;
    ref_surface q;
    ref_surface_from_hit(shared, h[i].geom_id, h[i].prim_id, h[i].ng, h[i].u, h[i].v, org, dir, t,
                         &q);
    double l[3];
    ref_bounce_radiance(w, &q, l);
    out[0] += l[0];
    out[1] += l[1];
    out[2] += l[2];
  }
}

/* Primary ray through image point (sx, sy) in [-1, 1] (sy = +1 at the top). */
static void ref_camera_ray(const ref_shared* shared, double sx, double sy, double org[3],
                           double dir[3])
{
  const double h = shared->half_height;
  const double ox = sx * shared->aspect * h, oy = sy * h;
  if (shared->options.parallel_projection)
  {
    for (int k = 0; k < 3; ++k)
    {
      org[k] = shared->eye[k] + ox * shared->right[k] + oy * shared->up[k];
      dir[k] = shared->forward[k];
    }
    return;
  }
  for (int k = 0; k < 3; ++k)
  {
    org[k] = shared->eye[k];
    dir[k] = shared->forward[k] + ox * shared->right[k] + oy * shared->up[k];
  }
  ref_normalize(dir);
}

/* One pass over one pixel. */
static void ref_render_pixel(ref_worker* w, int32_t x, int32_t y)
{
  ref_shared* shared = w->shared;
  const mrgi_reference_options* o = &shared->options;
  const size_t pixel = (size_t)y * (size_t)o->width + (size_t)x;
  /* pixel < 2^28 and pass < 2^20: the key is unique per (pass, pixel) */
  uint64_t rng = ref_mix64(o->seed ^ ref_mix64(((uint64_t)(uint32_t)shared->pass << 32) |
                                               (uint64_t)pixel));
  double* sums = shared->sums + 9 * pixel;
  double estimate = 0.0;
  /* Area-light points draw from a stream of their own (indirect unchanged). */
  uint64_t area_rng = ref_mix64(rng ^ 0xA5EA1167A5EA1167ULL);
  w->bounce_area_rng = ref_mix64(rng ^ 0xB0B0CE0FA5EA1167ULL);
  double direct_estimate = 0.0;
  for (int32_t sample = 0; sample < o->pixel_samples; ++sample)
  {
    const double jx = ref_rng_unit(&rng), jy = ref_rng_unit(&rng);
    const double sx = 2.0 * ((double)x + jx) / (double)o->width - 1.0;
    const double sy = 1.0 - 2.0 * ((double)y + jy) / (double)o->height;
    double org[3], dir[3];
    ref_camera_ray(shared, sx, sy, org, dir);
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    struct RTCRayHit rh;
    ref_ray_init(&rh.ray, org, dir, INFINITY);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(shared->rtc, &context, &rh);
    ++w->rays;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
    {
      continue;
    }
    shared->hit[pixel] = 1;
    const float ng[3] = { rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z };
    ref_surface s;
    ref_surface_from_hit(shared, rh.hit.geomID, rh.hit.primID, ng, rh.hit.u, rh.hit.v, org, dir,
                         (double)rh.ray.tfar, &s);
    const mrgi_mesh* mesh = s.geometry->mesh;
    for (int k = 0; k < 3; ++k)
    {
      sums[6 + k] += (double)mesh->albedo[k];
    }
    if (s.geometry->emitter)
    {
      for (int k = 0; k < 3; ++k)
      {
        sums[k] += (double)mesh->emission[k];
        direct_estimate += (double)mesh->emission[k] / 3.0;
      }
      continue;
    }
    double x_direct[3];
    ref_irradiance(w, &s, o->shadows, x_direct);
    if (shared->area_light_count > 0)
    {
      double x_area[3];
      ref_area_irradiance(w, &s, o->shadows, &area_rng, x_area);
      for (int k = 0; k < 3; ++k)
      {
        x_direct[k] += x_area[k];
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      sums[k] += (double)mesh->albedo[k] * x_direct[k];
      direct_estimate += (double)mesh->albedo[k] * x_direct[k] / 3.0;
    }
    if (o->indirect_samples == 0)
    {
      continue;
    }
    double bounce_org[3];
    for (int k = 0; k < 3; ++k)
    {
      bounce_org[k] = s.p[k] + s.epsilon * s.ng[k];
    }
    double x_indirect[3] = { 0.0, 0.0, 0.0 };
    for (int32_t b = 0; b < o->indirect_samples; ++b)
    {
      const double u1 = ref_rng_unit(&rng), u2 = ref_rng_unit(&rng);
      double bounce_dir[3], l[3];
      ref_sample_cosine(s.ng, u1, u2, bounce_dir);
      ref_gather(w, bounce_org, bounce_dir, l);
      for (int k = 0; k < 3; ++k)
      {
        x_indirect[k] += l[k];
      }
    }
    double mean_channel = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const double v = (double)mesh->albedo[k] * x_indirect[k] / (double)o->indirect_samples;
      sums[3 + k] += v;
      mean_channel += v / 3.0;
    }
    estimate += mean_channel;
  }
  /* Welford's running mean and variance of the per-pass estimates (Knuth,
   * TAOCP vol. 2, 4.2.2): no cancellation, unlike sum and sum of squares. */
  estimate /= (double)o->pixel_samples;
  const double n = (double)(shared->pass + 1);
  const double delta = estimate - shared->est_mean[pixel];
  shared->est_mean[pixel] += delta / n;
  shared->est_m2[pixel] += delta * (estimate - shared->est_mean[pixel]);
  if (shared->dir_mean)
  {
    direct_estimate /= (double)o->pixel_samples;
    const double direct_delta = direct_estimate - shared->dir_mean[pixel];
    shared->dir_mean[pixel] += direct_delta / n;
    shared->dir_m2[pixel] += direct_delta * (direct_estimate - shared->dir_mean[pixel]);
  }
}

static void* ref_worker_run(void* arg)
{
  ref_worker* w = (ref_worker*)arg;
  ref_shared* shared = w->shared;
  const int32_t width = shared->options.width, height = shared->options.height;
  for (;;)
  {
    const int row = atomic_fetch_add(&shared->next_row, 1);
    if (row >= height)
    {
      break;
    }
    for (int32_t x = 0; x < width; ++x)
    {
      ref_render_pixel(w, x, (int32_t)row);
    }
  }
  return NULL;
}

/* ---- Embree setup ---- */

typedef struct ref_embree_error
{
  char message[256];
} ref_embree_error;

static void ref_embree_error_callback(void* user, enum RTCError code, const char* str)
{
  ref_embree_error* e = (ref_embree_error*)user;
  if (e->message[0] == '\0')
  {
    snprintf(e->message, sizeof(e->message), "Embree error %d: %s", (int)code, str ? str : "");
  }
}

static int ref_triangle_usable(const mrgi_mesh* mesh, int64_t t)
{
  const uint32_t* tri = mesh->indices + 3 * t;
  double c[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[i][k] = (double)mesh->positions[3 * (size_t)tri[i] + k];
      if (!isfinite(c[i][k]))
      {
        return 0;
      }
    }
  }
  const double e1[3] = { c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2] };
  const double e2[3] = { c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2] };
  double n[3];
  ref_cross(e1, e2, n);
  const double twice_area = sqrt(ref_dot(n, n));
  return twice_area > 0.0 && isfinite(twice_area);
}

/* Upload every mesh's usable triangles; geometry ids are 0.. in upload order. */
static mrgi_status ref_build_scene(RTCDevice device, const mrgi_scene* scene, int with_filter,
                                   const ref_embree_error* embree_error, RTCScene* out_scene,
                                   ref_geometry* geometries, int64_t* skipped, mrgi_error* err)
{
  static const char* caller = "mrgi_reference_render";
  RTCScene rtc = rtcNewScene(device);
  if (!rtc)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED, "%s: rtcNewScene failed: %s", caller,
                          embree_error->message);
  }
  /* ROBUST: no traversal shortcuts that lose accuracy (rays along shared
   * edges must not slip through); CONTEXT_FILTER: the RSM hit collector. */
  rtcSetSceneFlags(rtc, (enum RTCSceneFlags)(RTC_SCENE_FLAG_ROBUST |
                                             (with_filter ? RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION
                                                          : 0)));
  rtcSetSceneBuildQuality(rtc, RTC_BUILD_QUALITY_MEDIUM);
  *skipped = 0;
  uint32_t next_id = 0;
  for (int32_t m = 0; m < scene->mesh_count; ++m)
  {
    const mrgi_mesh* mesh = &scene->meshes[m];
    int64_t usable = 0;
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      usable += ref_triangle_usable(mesh, t);
    }
    *skipped += mesh->triangle_count - usable;
    if (usable == 0)
    {
      continue;
    }
    ref_geometry* g = &geometries[next_id];
    g->mesh = mesh;
    g->emitter = mesh->emission[0] > 0.0f || mesh->emission[1] > 0.0f || mesh->emission[2] > 0.0f;
    g->triangle_of_prim = malloc((size_t)usable * sizeof(uint32_t));
    if (!g->triangle_of_prim)
    {
      rtcReleaseScene(rtc);
      return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "%s: no memory for mesh %d's triangle map",
                            caller, (int)m);
    }
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    /* Embree allocates (and pads, as its SIMD loads need) its own buffers:
     * the mesh's exactly-sized arrays cannot be shared. */
    float* vertices = geom ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                     RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                     (size_t)mesh->vertex_count)
                           : NULL;
    uint32_t* indices = vertices ? rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                           RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                           (size_t)usable)
                                 : NULL;
    if (!indices)
    {
      if (geom)
      {
        rtcReleaseGeometry(geom);
      }
      rtcReleaseScene(rtc);
      return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "%s: Embree buffers for mesh %d: %s",
                            caller, (int)m, embree_error->message);
    }
    memcpy(vertices, mesh->positions, 3 * sizeof(float) * (size_t)mesh->vertex_count);
    int64_t k = 0;
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      if (ref_triangle_usable(mesh, t))
      {
        memcpy(indices + 3 * k, mesh->indices + 3 * t, 3 * sizeof(uint32_t));
        g->triangle_of_prim[k] = (uint32_t)t;
        ++k;
      }
    }
    rtcCommitGeometry(geom);
    const unsigned int id = rtcAttachGeometry(rtc, geom);
    rtcReleaseGeometry(geom);
    if (id != next_id)
    {
      rtcReleaseScene(rtc);
      return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                            "%s: Embree gave geometry id %u, expected %u: %s", caller, id,
                            (unsigned)next_id, embree_error->message);
    }
    ++next_id;
  }
  if (next_id == 0)
  {
    rtcReleaseScene(rtc);
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: the scene has no usable triangles (%d meshes, %lld skipped as "
                          "degenerate or non-finite)",
                          caller, (int)scene->mesh_count, (long long)*skipped);
  }
  rtcCommitScene(rtc);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE || embree_error->message[0])
  {
    rtcReleaseScene(rtc);
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED, "%s: building the Embree scene failed: %s",
                          caller, embree_error->message);
  }
  *out_scene = rtc;
  return MRGI_OK;
}

static void ref_setup_lights(const mrgi_scene* scene, ref_shared* shared)
{
  shared->light_count = scene->light_count;
  for (int32_t i = 0; i < scene->light_count; ++i)
  {
    const mrgi_light* in = &scene->lights[i];
    ref_light* l = &shared->lights[i];
    memset(l, 0, sizeof(*l));
    l->directional = in->type == MRGI_LIGHT_DIRECTIONAL;
    l->spot = in->type == MRGI_LIGHT_SPOT;
    for (int k = 0; k < 3; ++k)
    {
      l->position[k] = in->position[k];
      l->to_light[k] = in->position[k] - in->focal_point[k];
      l->axis[k] = in->focal_point[k] - in->position[k];
      l->rgb[k] = in->intensity * in->color[k];
    }
    ref_normalize(l->to_light);
    ref_normalize(l->axis);
    l->cos_cone = cos(in->cone_angle_deg * REF_PI / 180.0);
    l->exponent = in->exponent;
  }
}

static mrgi_status ref_setup_camera(const mrgi_camera* camera, const mrgi_reference_options* o,
                                    ref_shared* shared, mrgi_error* err)
{
  for (int k = 0; k < 3; ++k)
  {
    shared->eye[k] = camera->position[k];
    shared->forward[k] = camera->focal_point[k] - camera->position[k];
  }
  ref_normalize(shared->forward);
  /* vtkCamera: the image's right is direction_of_projection x view_up; the
   * true up is right x direction, view_up orthogonalized. */
  ref_cross(shared->forward, camera->view_up, shared->right);
  if (!(ref_normalize(shared->right) > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_reference_render: camera view_up is parallel to the view direction");
  }
  ref_cross(shared->right, shared->forward, shared->up);
  ref_normalize(shared->up);
  shared->aspect = (double)o->width / (double)o->height;
  shared->half_height = o->parallel_projection
                          ? o->parallel_scale
                          : tan(0.5 * camera->view_angle_deg * REF_PI / 180.0);
  return MRGI_OK;
}

/* ---- result ---- */

void mrgi_reference_result_destroy(mrgi_reference_result* result)
{
  if (!result)
  {
    return;
  }
  mrgi_image_destroy(&result->direct);
  mrgi_image_destroy(&result->indirect);
  mrgi_image_destroy(&result->albedo);
  mrgi_image_destroy(&result->indirect_stderr);
  mrgi_image_destroy(&result->direct_stderr);
  free(result->background);
  memset(result, 0, sizeof(*result));
}

/* Noise of the per-pass estimates (mean, m2) after `passes` passes
 * (definitions in the header); `enabled` = 0: known exactly. */
static void ref_noise_of(const ref_shared* shared, const double* est_mean, const double* est_m2,
                         int enabled, int32_t passes, double* relative, double* per_pixel)
{
  const size_t count = (size_t)shared->options.width * (size_t)shared->options.height;
  double sum_mean = 0.0, sum_var = 0.0;
  size_t lit = 0;
  for (size_t i = 0; i < count; ++i)
  {
    if (!shared->hit[i])
    {
      continue;
    }
    ++lit;
    sum_mean += est_mean[i];
    if (passes > 1)
    {
      sum_var += est_m2[i] / ((double)(passes - 1) * (double)passes);
    }
  }
  if (!enabled || !(sum_mean > 0.0))
  {
    *relative = 0.0;
    *per_pixel = 0.0;
    return;
  }
  if (passes < 2)
  {
    *relative = INFINITY;
    *per_pixel = INFINITY;
    return;
  }
  *relative = sqrt(sum_var) / sum_mean;
  *per_pixel = *relative * sqrt((double)lit);
}

/* Noise of the indirect (relative_error, pixel_relative_error). */
static void ref_noise(const ref_shared* shared, int32_t passes, double* relative,
                      double* per_pixel)
{
  ref_noise_of(shared, shared->est_mean, shared->est_m2, shared->options.indirect_samples != 0,
               passes, relative, per_pixel);
}

/* Noise of the direct image: area lights only (direct_relative_error). */
static double ref_direct_noise(const ref_shared* shared, int32_t passes)
{
  double relative = 0.0, per_pixel = 0.0;
  if (shared->dir_mean)
  {
    ref_noise_of(shared, shared->dir_mean, shared->dir_m2, 1, passes, &relative, &per_pixel);
  }
  return relative;
}

/* The stopping statistic (mrgi_reference_noise.h) of the per-pass estimates
 * (mean, m2); `enabled` = 0 or NULL accumulators: known exactly, 0. The
 * arguments were checked when the call began, so this cannot fail. */
static double ref_pixel_error_of(const ref_shared* shared, const double* est_mean,
                                 const double* est_m2, int enabled, int32_t passes)
{
  if (!enabled || !est_mean)
  {
    return 0.0;
  }
  const size_t count = (size_t)shared->options.width * (size_t)shared->options.height;
  double error = INFINITY;
  if (mrgi_reference_pixel_error(est_mean, est_m2, shared->hit, count, passes,
                                 shared->options.target_percentile, shared->noise_scratch,
                                 &error, NULL) != MRGI_OK)
  {
    return INFINITY; /* unreachable: keeps rendering rather than stopping on a bad value */
  }
  return error;
}

static int32_t ref_thread_count(const mrgi_reference_options* o)
{
  int64_t n = o->threads;
  if (n == 0)
  {
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    n = online > 0 ? online : 1;
  }
  if (n > MRGI_REFERENCE_MAX_THREADS)
  {
    n = MRGI_REFERENCE_MAX_THREADS;
  }
  if (n > o->height)
  {
    n = o->height;
  }
  return (int32_t)n;
}

/* Everything one call owns, released in one place. */
typedef struct ref_call
{
  RTCDevice device;
  RTCScene rtc;
  ref_geometry* geometries;
  int32_t geometry_slots;
  ref_worker* workers;
  pthread_t* thread_ids;
  ref_hit_record* hit_storage;
  ref_shared shared;
} ref_call;

static void ref_call_release(ref_call* c)
{
  if (c->rtc)
  {
    rtcReleaseScene(c->rtc);
  }
  if (c->device)
  {
    rtcReleaseDevice(c->device);
  }
  for (int32_t i = 0; c->geometries && i < c->geometry_slots; ++i)
  {
    free(c->geometries[i].triangle_of_prim);
  }
  free(c->geometries);
  free(c->workers);
  free(c->thread_ids);
  free(c->hit_storage);
  free(c->shared.sums);
  free(c->shared.est_mean);
  free(c->shared.est_m2);
  free(c->shared.dir_mean);
  free(c->shared.dir_m2);
  free(c->shared.hit);
  free(c->shared.noise_scratch);
}

/* Run one pass with `thread_count` workers; the calling thread is worker 0.
 * A thread that cannot be started just leaves its rows to the others. */
static void ref_run_pass(ref_call* c, int32_t thread_count)
{
  atomic_store(&c->shared.next_row, 0);
  int32_t started = 0;
  for (int32_t i = 1; i < thread_count; ++i)
  {
    if (pthread_create(&c->thread_ids[started], NULL, ref_worker_run, &c->workers[i]) == 0)
    {
      ++started;
    }
  }
  ref_worker_run(&c->workers[0]);
  for (int32_t i = 0; i < started; ++i)
  {
    pthread_join(c->thread_ids[i], NULL);
  }
}

/* Fills a progress report after `passes` passes that took `pass_seconds`
 * (the Embree build not included). The stopping statistic (the worse of
 * the indirect's and the direct's pixel_error) falls as 1/sqrt(passes): the
 * target is expected after passes * (worst / target)^2 passes. */
static void ref_progress(const mrgi_reference_options* o, int32_t passes, double relative,
  double direct_relative, double pixel, double direct_pixel, double seconds, double pass_seconds,
  mrgi_reference_progress* p)
{
  const double worst = direct_pixel > pixel ? direct_pixel : pixel;
  double expected = (double)o->max_passes;
  if (o->target_relative_error > 0.0 && isfinite(worst))
  {
    const double ratio = worst / o->target_relative_error;
    const double needed = worst == 0.0 ? (double)passes : (double)passes * ratio * ratio;
    /* The loop stops after pass 2 at the earliest (file comment). */
    const double at_least = worst == 0.0 ? (double)passes : 2.0;
    expected = needed < expected ? needed : expected;
    expected = expected < at_least ? at_least : expected;
  }
  if (expected < (double)passes)
  {
    expected = (double)passes;
  }
  p->passes = passes;
  p->max_passes = o->max_passes;
  p->relative_error = relative;
  p->direct_relative_error = direct_relative;
  p->pixel_error = pixel;
  p->direct_pixel_error = direct_pixel;
  p->target_relative_error = o->target_relative_error;
  p->seconds = seconds;
  p->passes_expected = expected;
  p->fraction = (double)passes / expected;
  p->seconds_left = (expected - (double)passes) * (pass_seconds / (double)passes);
}

static mrgi_status ref_write_images(const ref_call* c, int32_t passes, mrgi_reference_result* out,
                                    mrgi_error* err)
{
  const mrgi_reference_options* o = &c->shared.options;
  mrgi_status s = mrgi_image_create(&out->direct, o->width, o->height, 3, err);
  if (!s)
    s = mrgi_image_create(&out->indirect, o->width, o->height, 3, err);
  if (!s)
    s = mrgi_image_create(&out->albedo, o->width, o->height, 3, err);
  if (!s)
    s = mrgi_image_create(&out->indirect_stderr, o->width, o->height, 1, err);
  if (!s)
    s = mrgi_image_create(&out->direct_stderr, o->width, o->height, 1, err);
  if (s)
  {
    return s;
  }
  const size_t count = (size_t)o->width * (size_t)o->height;
  out->background = calloc(count, 1);
  if (!out->background)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "mrgi_reference_render: no memory for the background mask");
  }
  const double scale = 1.0 / ((double)passes * (double)o->pixel_samples);
  for (size_t i = 0; i < count; ++i)
  {
    const double* sums = c->shared.sums + 9 * i;
    for (int k = 0; k < 3; ++k)
    {
      out->direct.pixels[3 * i + k] = (float)(sums[k] * scale);
      out->indirect.pixels[3 * i + k] = (float)(sums[3 + k] * scale);
      out->albedo.pixels[3 * i + k] = (float)(sums[6 + k] * scale);
    }
    out->background[i] = !c->shared.hit[i];
    const double var_of_mean =
      passes > 1 ? c->shared.est_m2[i] / ((double)(passes - 1) * (double)passes) : 0.0;
    out->indirect_stderr.pixels[i] = (float)sqrt(var_of_mean > 0.0 ? var_of_mean : 0.0);
    if (c->shared.dir_mean && passes > 1)
    {
      const double direct_var = c->shared.dir_m2[i] / ((double)(passes - 1) * (double)passes);
      out->direct_stderr.pixels[i] = (float)sqrt(direct_var > 0.0 ? direct_var : 0.0);
    }
  }
  return MRGI_OK;
}

/* Reduce the (checked) area lights to ref_area_light records. */
static void ref_setup_area_lights(const mrgi_area_light* lights, int32_t count,
                                  int32_t samples, ref_shared* shared)
{
  shared->area_light_count = count;
  for (int32_t i = 0; i < count; ++i)
  {
    const mrgi_area_light* in = &lights[i];
    ref_area_light* a = &shared->area_lights[i];
    memset(a, 0, sizeof(*a));
    a->light = in;
    memcpy(a->center, in->center, sizeof(a->center));
    memcpy(a->edge_u, in->edge_u, sizeof(a->edge_u));
    memcpy(a->edge_v, in->edge_v, sizeof(a->edge_v));
    ref_cross(in->edge_u, in->edge_v, a->normal);
    const double area = ref_normalize(a->normal);
    int32_t cells_u = 1, cells_v = 1;
    /* cannot fail: light and count were checked by the caller */
    mrgi_area_light_sample_layout(in, samples, &cells_u, &cells_v, NULL, NULL);
    a->cells_u = cells_u;
    a->cells_v = cells_v;
    a->weight = area / (REF_PI * (double)cells_u * (double)cells_v);
    a->two_sided = in->two_sided != 0;
  }
}

mrgi_status mrgi_reference_render(const mrgi_scene* scene, const mrgi_reference_options* options,
                                  mrgi_reference_result* out, mrgi_error* err)
{
  return mrgi_reference_render_area_lights(scene, options, NULL, 0, out, err);
}

mrgi_status mrgi_reference_render_area_lights(const mrgi_scene* scene,
                                              const mrgi_reference_options* options,
                                              const mrgi_area_light* area_lights,
                                              int32_t area_light_count,
                                              mrgi_reference_result* out, mrgi_error* err)
{
  static const char* caller = "mrgi_reference_render";
  const double start = ref_seconds_now();
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: out is NULL", caller);
  }
  memset(out, 0, sizeof(*out));
  if (!scene)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: scene is NULL", caller);
  }
  mrgi_status status = mrgi_reference_options_validate(options, err);
  if (status)
  {
    return status;
  }
  status = mrgi_scene_validate(scene, err);
  if (status)
  {
    mrgi_error_prefix(err, "%s: ", caller);
    return status;
  }
  if (mrgi_scene_triangle_count(scene) == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: the scene has no triangles",
                          caller);
  }
  if (area_light_count < 0 || area_light_count > MRGI_REFERENCE_MAX_AREA_LIGHTS ||
      (area_light_count > 0 && !area_lights))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: area_light_count %d is outside 0..%d or the area lights are NULL",
                          caller, (int)area_light_count, MRGI_REFERENCE_MAX_AREA_LIGHTS);
  }
  for (int32_t i = 0; i < area_light_count; ++i)
  {
    status = mrgi_area_light_check(&area_lights[i], err);
    if (status)
    {
      mrgi_error_prefix(err, "%s: area light %d: ", caller, (int)i);
      return status;
    }
  }
  if (area_light_count > 0 && options->area_light_samples < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "%s: option area_light_samples = %d, but %d area lights are to be "
                          "rendered (1..%d needed)",
                          caller, (int)options->area_light_samples, (int)area_light_count,
                          MRGI_REFERENCE_MAX_AREA_LIGHT_SAMPLES);
  }

  ref_call c;
  memset(&c, 0, sizeof(c));
  c.shared.options = *options;
  status = ref_setup_camera(&scene->camera, options, &c.shared, err);
  if (status)
  {
    return status;
  }
  ref_setup_lights(scene, &c.shared);
  ref_setup_area_lights(area_lights, area_light_count, options->area_light_samples, &c.shared);
  double bounds[6];
  status = mrgi_scene_bounds(scene, bounds, err);
  if (status)
  {
    mrgi_error_prefix(err, "%s: ", caller);
    return status;
  }
  double extent = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = bounds[2 * k + 1] - bounds[2 * k];
    extent = e > extent ? e : extent;
  }
  c.shared.epsilon_floor = 0.01 * extent;

  const int32_t thread_count = ref_thread_count(options);
  const size_t count = (size_t)options->width * (size_t)options->height;
  c.geometry_slots = scene->mesh_count;
  c.geometries = calloc((size_t)scene->mesh_count, sizeof(ref_geometry));
  c.workers = calloc((size_t)thread_count, sizeof(ref_worker));
  c.thread_ids = calloc((size_t)thread_count, sizeof(pthread_t));
  c.hit_storage =
    calloc((size_t)thread_count * MRGI_REFERENCE_MAX_RAY_HITS, sizeof(ref_hit_record));
  c.shared.sums = calloc(9 * count, sizeof(double));
  c.shared.est_mean = calloc(count, sizeof(double));
  c.shared.est_m2 = calloc(count, sizeof(double));
  c.shared.hit = calloc(count, 1);
  c.shared.noise_scratch = malloc(count * sizeof(double));
  if (area_light_count > 0)
  {
    c.shared.dir_mean = calloc(count, sizeof(double));
    c.shared.dir_m2 = calloc(count, sizeof(double));
  }
  if (!c.geometries || !c.workers || !c.thread_ids || !c.hit_storage || !c.shared.sums ||
      !c.shared.est_mean || !c.shared.est_m2 || !c.shared.hit || !c.shared.noise_scratch ||
      (area_light_count > 0 && (!c.shared.dir_mean || !c.shared.dir_m2)))
  {
    ref_call_release(&c);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "%s: no memory for %dx%d accumulation buffers", caller,
                          (int)options->width, (int)options->height);
  }

  ref_embree_error embree_error;
  memset(&embree_error, 0, sizeof(embree_error));
  c.device = rtcNewDevice(NULL);
  if (!c.device)
  {
    ref_call_release(&c);
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED, "%s: rtcNewDevice failed (Embree error %d)",
                          caller, (int)rtcGetDeviceError(NULL));
  }
  rtcSetDeviceErrorFunction(c.device, ref_embree_error_callback, &embree_error);
  if (!options->secondary_visibility &&
      !rtcGetDeviceProperty(c.device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
  {
    ref_call_release(&c);
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                          "%s: secondary_visibility = 0 needs Embree filter functions, and this "
                          "Embree was built without them",
                          caller);
  }
  const double build_start = ref_seconds_now();
  status = ref_build_scene(c.device, scene, !options->secondary_visibility, &embree_error, &c.rtc,
                           c.geometries, &out->skipped_triangles, err);
  if (status)
  {
    ref_call_release(&c);
    return status;
  }
  out->build_seconds = ref_seconds_now() - build_start;
  c.shared.rtc = c.rtc;
  c.shared.geometries = c.geometries;
  for (int32_t i = 0; i < thread_count; ++i)
  {
    c.workers[i].shared = &c.shared;
    c.workers[i].hits = c.hit_storage + (size_t)i * MRGI_REFERENCE_MAX_RAY_HITS;
  }

  int32_t passes = 0;
  int32_t cancelled = 0;
  double relative = INFINITY, per_pixel = INFINITY, direct_relative = INFINITY;
  double pixel = INFINITY, direct_pixel = INFINITY;
  const double passes_start = ref_seconds_now();
  while (passes < options->max_passes)
  {
    c.shared.pass = passes;
    ref_run_pass(&c, thread_count);
    ++passes;
    ref_noise(&c.shared, passes, &relative, &per_pixel);
    direct_relative = ref_direct_noise(&c.shared, passes); /* 0 without area lights */
    /* The stopping rule: per pixel (mrgi_reference_noise.h), on the direct
     * image too when area lights make it noisy. */
    pixel = ref_pixel_error_of(&c.shared, c.shared.est_mean, c.shared.est_m2,
                               options->indirect_samples != 0, passes);
    direct_pixel = ref_pixel_error_of(&c.shared, c.shared.dir_mean, c.shared.dir_m2, 1, passes);
    const double worst = direct_pixel > pixel ? direct_pixel : pixel;
    if (options->progress)
    {
      mrgi_reference_progress p;
      ref_progress(options, passes, relative, direct_relative, pixel, direct_pixel,
        ref_seconds_now() - start,
        ref_seconds_now() - passes_start, &p);
      if (options->progress(options->progress_user_data, &p) != 0)
      {
        cancelled = 1;
        break;
      }
    }
    if (options->target_relative_error > 0.0 && worst <= options->target_relative_error &&
        (passes >= 2 || worst == 0.0))
    {
      break;
    }
    if (options->max_seconds > 0.0 && ref_seconds_now() - start >= options->max_seconds)
    {
      break;
    }
  }
  for (int32_t i = 0; i < thread_count; ++i)
  {
    out->rays_traced += c.workers[i].rays;
    out->hit_list_overflows += c.workers[i].overflows;
  }
  const int64_t skipped = out->skipped_triangles;
  const double build_seconds = out->build_seconds;
  const int64_t rays = out->rays_traced, overflows = out->hit_list_overflows;
  status = ref_write_images(&c, passes, out, err);
  ref_call_release(&c);
  if (status)
  {
    mrgi_reference_result_destroy(out);
    return status;
  }
  out->skipped_triangles = skipped;
  out->build_seconds = build_seconds;
  out->rays_traced = rays;
  out->hit_list_overflows = overflows;
  out->relative_error = relative;
  out->pixel_relative_error = per_pixel;
  out->direct_relative_error = direct_relative;
  out->pixel_error = pixel;
  out->direct_pixel_error = direct_pixel;
  out->passes = passes;
  out->cancelled = cancelled;
  out->threads = thread_count;
  out->seconds = ref_seconds_now() - start;
  return MRGI_OK;
}
