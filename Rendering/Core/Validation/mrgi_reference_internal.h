/* Internal to the ground-truth renderer (not installed): the state one
 * render shares among mrgi_reference.c (options, passes, results),
 * mrgi_reference_kernel.c (the per-pixel kernel) and mrgi_reference_scene.c
 * (Embree geometry, lights and camera). Include after defining
 * _POSIX_C_SOURCE 200809L (clock_gettime). */
#ifndef mrgi_reference_internal_h
#define mrgi_reference_internal_h

#include "mrgi_reference.h"

#include <embree3/rtcore.h>

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <time.h>

#define REF_PI 3.14159265358979323846

/* ---- small vector helpers (double) ---- */

static inline double ref_dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void ref_cross(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Normalize in place; returns the former length (0 leaves v unchanged). */
static inline double ref_normalize(double v[3])
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

static inline double ref_seconds_now(void)
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

static inline uint64_t ref_mix64(uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

static inline uint64_t ref_rng_next(uint64_t* state)
{
  *state += 0x9E3779B97F4A7C15ULL;
  return ref_mix64(*state);
}

/* Uniform in [0, 1): the top 53 bits scaled by 2^-53. */
static inline double ref_rng_unit(uint64_t* state)
{
  return (double)(ref_rng_next(state) >> 11) * 0x1.0p-53;
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

/* The first message Embree reported through
 * mrgi_reference_embree_error_callback(). */
typedef struct ref_embree_error
{
  char message[256];
} ref_embree_error;

/* ---- mrgi_reference_scene.c ---- */

/* rtcSetDeviceErrorFunction callback; user is a ref_embree_error. */
void mrgi_reference_embree_error_callback(void* user, enum RTCError code, const char* str);

/* Upload every mesh's usable triangles; geometry ids are 0.. in upload order.
 * with_filter installs the hit-collecting filter (secondary visibility
 * through emitters); skipped counts degenerate or non-finite triangles. */
mrgi_status mrgi_reference_build_scene(RTCDevice device, const mrgi_scene* scene, int with_filter,
                                       const ref_embree_error* embree_error, RTCScene* out_scene,
                                       ref_geometry* geometries, int64_t* skipped, mrgi_error* err);

/* The scene's point, spot and directional lights, reduced to ref_light. */
void mrgi_reference_setup_lights(const mrgi_scene* scene, ref_shared* shared);

/* The camera frame (eye, forward, right, up, aspect, half height); an error
 * when view_up is parallel to the view direction. */
mrgi_status mrgi_reference_setup_camera(const mrgi_camera* camera,
                                        const mrgi_reference_options* o, ref_shared* shared,
                                        mrgi_error* err);

/* ---- mrgi_reference_kernel.c ---- */

/* pthread entry: renders rows taken from shared->next_row until none is left,
 * accumulating into the shared per-pixel slots. arg is a ref_worker. */
void* mrgi_reference_worker_run(void* arg);

#endif /* mrgi_reference_internal_h */
