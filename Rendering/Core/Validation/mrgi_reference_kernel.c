/* Ground-truth renderer, per-pixel kernel: surfaces from Embree hits, direct
 * light from point, spot, directional and area lights, one cosine-sampled
 * diffuse bounce, and the worker loop over rows (mrgi_reference.h; shared
 * state in mrgi_reference_internal.h). */
/* clock_gettime: POSIX.1-2008 */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_reference_internal.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

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
    /* Drawn in both modes: the later draws of `rng` stay the same. */
    double jx = ref_rng_unit(&rng), jy = ref_rng_unit(&rng);
    if (o->pixel_filter == MRGI_REFERENCE_PIXEL_CENTER)
    {
      jx = jy = 0.5;
    }
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

void* mrgi_reference_worker_run(void* arg)
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
