/*
 * ism_visibility_diagnostic: the ISM shadow test of the gather
 * (mrgi_ism_visibility.h) against exact ray casts on a built-in triangle
 * scene, all in the C core (issue 13, "corridor").
 *
 *   ism_visibility_diagnostic [SCENE] [TILE] [POINTS_PER_VPL] [MODE] [RES] [VPLS]
 *
 * SCENE: corridor (default), corridor-large, corner, u-shape. TILE: ISM
 * tile side (32). POINTS_PER_VPL (256). MODE: 0 uniform, 1 adaptive-1,
 * 2 adaptive-8 (default; view samples = the receivers). RES: receivers are
 * the first hits of RES x RES camera rays (48). VPLS: the first hits of
 * VPLS rays of the scene's spot, stratified over its cone and weighted by
 * its fall-off (64). The atlas is mrgi_ism_atlas_render() (the GPU draw's
 * twin, push-pull on).
 *
 * For every receiver x (normal n_x) and VPL j (position v, normal n) the
 * term is max(0, n.d) max(0, -n_x.d) / max(|x - v|^2, 0.01) (d = (x - v) /
 * |x - v|); E = sum of terms times the spot weight. E_none: no visibility;
 * E_exact: times an exact segment test against every triangle; E_ism: times
 * mrgi_ism_visibility() with the core's default lookup parameters. Printed:
 *  - the shadow region (receivers whose E_exact < 0.7 E_none, among those
 *    with E_none above the median: the rule of indirect_shadows.py, per
 *    receiver instead of per 4x4 box) and its mean E / mean E_exact;
 *  - the relative RMS of E_none and E_ism against E_exact over all receivers;
 *  - the share of the term weight the ISM gets wrong: occluded terms it
 *    calls visible (missed) and visible terms it calls occluded (false
 *    shadow), inside the region and everywhere, as % of sum E_exact.
 * Knobs (environment, for sweeps): ISM_TB / ISM_RB texel / relative bias
 * (default: the core's defaults); ISM_PP the twin's push-pull levels, 0 off
 * (default MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS); ISM_PULL 0/1/2 an extra push-pull after the render with the pull
 * taking the min / mean / max of the valid children, over ISM_PPL levels
 * (default all); ISM_NO k: look up from x + k footprints along x's normal.
 * Build and run (after scripts/build.sh):
 *   cc -O2 -std=c11 -D_DEFAULT_SOURCE -o /tmp/ismdiag \
 *     Testing/Benchmarks/ism_visibility_diagnostic.c -IRendering/Core/Twins \
 *     -IRendering/Core/Scenes -Lbuild/lib -lMRGICoreScenes -lMRGICore -lm \
 *     -Wl,-rpath,$PWD/build/lib
 *   ISM_PP=0 /tmp/ismdiag corridor 32 256 2 64
 */
#include "mrgi_ism_atlas.h"
#include "mrgi_ism_points.h"
#include "mrgi_ism_visibility.h"
#include "mrgi_scene.h"
#include "mrgi_scene_indirect.h"
#include "mrgi_vpl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct tri_scene
{
  int32_t vertex_count, triangle_count;
  float* positions;
  int32_t* triangles;
} tri_scene;

static void sub3(const double a[3], const double b[3], double o[3])
{
  o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2];
}
static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void cross3(const double a[3], const double b[3], double o[3])
{
  o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
static void norm3(double a[3])
{
  const double l = sqrt(dot3(a, a));
  a[0] /= l, a[1] /= l, a[2] /= l;
}

/* Moller-Trumbore; nearest hit in (tmin, tmax), its triangle in *hit. */
static double cast(const tri_scene* s, const double o[3], const double d[3], double tmin, double tmax,
  int any, int32_t* hit)
{
  double best = tmax;
  *hit = -1;
  for (int32_t t = 0; t < s->triangle_count; ++t)
  {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a)
        p[k][a] = s->positions[3 * s->triangles[3 * t + k] + a];
    double e1[3], e2[3], pv[3], tv[3], qv[3];
    sub3(p[1], p[0], e1);
    sub3(p[2], p[0], e2);
    cross3(d, e2, pv);
    const double det = dot3(e1, pv);
    if (fabs(det) < 1e-14)
      continue;
    sub3(o, p[0], tv);
    const double u = dot3(tv, pv) / det;
    if (u < 0.0 || u > 1.0)
      continue;
    cross3(tv, e1, qv);
    const double v = dot3(d, qv) / det;
    if (v < 0.0 || u + v > 1.0)
      continue;
    const double tt = dot3(e2, qv) / det;
    if (tt > tmin && tt < best)
    {
      best = tt, *hit = t;
      if (any)
        return best;
    }
  }
  return best;
}

static void face_normal(const tri_scene* s, int32_t t, const double d[3], double n[3])
{
  double p[3][3], e1[3], e2[3];
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a)
      p[k][a] = s->positions[3 * s->triangles[3 * t + k] + a];
  sub3(p[1], p[0], e1);
  sub3(p[2], p[0], e2);
  cross3(e1, e2, n);
  norm3(n);
  if (dot3(n, d) > 0.0) /* face the ray's origin */
    n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
}

static void basis(const double w[3], double u[3], double v[3])
{
  const double a[3] = { fabs(w[0]) < 0.9 ? 1.0 : 0.0, fabs(w[0]) < 0.9 ? 0.0 : 1.0, 0.0 };
  cross3(w, a, u);
  norm3(u);
  cross3(w, u, v);
}

/* Push-pull variants over one atlas (pull: 0 min, 1 mean, 2 max of valid children). */
static void push_pull_variant(const mrgi_ism_atlas_layout* L, float* depth, float* scratch, int pull)
{
  const int32_t T = L->tile_size;
  const float E = MRGI_ISM_EMPTY_DEPTH;
  for (int32_t l = 0; l < L->vpl_count; ++l)
  {
    const int64_t x0 = (int64_t)(l % L->tiles_per_row) * T, y0 = (int64_t)(l / L->tiles_per_row) * T;
    float* lev[16];
    int32_t nlev = 0;
    size_t off = 0;
    for (int32_t s = T; s >= 1; s >>= 1)
      lev[nlev++] = scratch + off, off += (size_t)s * s;
    if (getenv("ISM_PPL") && nlev > atoi(getenv("ISM_PPL")) + 1)
      nlev = atoi(getenv("ISM_PPL")) + 1;
    for (int32_t y = 0; y < T; ++y)
      for (int32_t x = 0; x < T; ++x)
        lev[0][y * T + x] = depth[(y0 + y) * L->width + x0 + x];
    for (int32_t k = 1; k < nlev; ++k)
    {
      const int32_t s = T >> k, w = 2 * s;
      for (int32_t y = 0; y < s; ++y)
        for (int32_t x = 0; x < s; ++x)
        {
          const float* c = lev[k - 1];
          const float q[4] = { c[2 * y * w + 2 * x], c[2 * y * w + 2 * x + 1], c[(2 * y + 1) * w + 2 * x],
            c[(2 * y + 1) * w + 2 * x + 1] };
          float m = E, sum = 0.0f, mx = 0.0f;
          int n = 0;
          for (int i = 0; i < 4; ++i)
            if (q[i] < E)
              m = q[i] < m ? q[i] : m, sum += q[i], ++n, mx = q[i] > mx ? q[i] : mx;
          lev[k][y * s + x] = n == 0 ? E : (pull == 0 ? m : pull == 1 ? sum / (float)n : mx);
        }
    }
    for (int32_t k = nlev - 2; k >= 0; --k)
    {
      const int32_t s = T >> k;
      for (int32_t y = 0; y < s; ++y)
        for (int32_t x = 0; x < s; ++x)
          if (!(lev[k][y * s + x] < E))
            lev[k][y * s + x] = lev[k + 1][(y / 2) * (s / 2) + x / 2];
    }
    for (int32_t y = 0; y < T; ++y)
      for (int32_t x = 0; x < T; ++x)
        depth[(y0 + y) * L->width + x0 + x] = lev[0][y * T + x];
  }
}

static int cmp_double(const void* a, const void* b)
{
  const double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : x > y;
}

int main(int argc, char** argv)
{
  const char* name = argc > 1 ? argv[1] : "corridor";
  const int tile = argc > 2 ? atoi(argv[2]) : 32;
  const int ppv = argc > 3 ? atoi(argv[3]) : 256;
  const int mode = argc > 4 ? atoi(argv[4]) : 2;
  const int res = argc > 5 ? atoi(argv[5]) : 48;
  const int vpl_rays = argc > 6 ? atoi(argv[6]) : 64;
  mrgi_error err;
  mrgi_indirect_scene which;
  mrgi_scene scene;
  if (mrgi_indirect_scene_parse(name, &which, &err) != MRGI_OK ||
    mrgi_scene_indirect(which, &scene, &err) != MRGI_OK)
  {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  tri_scene s = { 0, 0, NULL, NULL };
  for (int32_t m = 0; m < scene.mesh_count; ++m)
    s.vertex_count += (int32_t)scene.meshes[m].vertex_count,
      s.triangle_count += (int32_t)scene.meshes[m].triangle_count;
  s.positions = malloc(sizeof(float) * 3 * (size_t)s.vertex_count);
  s.triangles = malloc(sizeof(int32_t) * 3 * (size_t)s.triangle_count);
  for (int32_t m = 0, vb = 0, tb = 0; m < scene.mesh_count; ++m)
  {
    const mrgi_mesh* mesh = &scene.meshes[m];
    memcpy(s.positions + 3 * vb, mesh->positions, sizeof(float) * 3 * (size_t)mesh->vertex_count);
    for (int64_t i = 0; i < 3 * mesh->triangle_count; ++i)
      s.triangles[3 * tb + i] = vb + (int32_t)mesh->indices[i];
    vb += (int32_t)mesh->vertex_count, tb += (int32_t)mesh->triangle_count;
  }

  /* Receivers: first hits of a pinhole camera (vertical fov, square). */
  const mrgi_camera* cam = &scene.camera;
  double fwd[3], right[3], up[3];
  sub3(cam->focal_point, cam->position, fwd);
  norm3(fwd);
  cross3(fwd, cam->view_up, right);
  norm3(right);
  cross3(right, fwd, up);
  const double half = tan(0.5 * cam->view_angle_deg * M_PI / 180.0);
  double* rx = malloc(sizeof(double) * 3 * (size_t)(res * res));
  double* rn = malloc(sizeof(double) * 3 * (size_t)(res * res));
  int32_t nrec = 0;
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i)
    {
      const double sx = (2.0 * (i + 0.5) / res - 1.0) * half, sy = (1.0 - 2.0 * (j + 0.5) / res) * half;
      double d[3] = { fwd[0] + sx * right[0] + sy * up[0], fwd[1] + sx * right[1] + sy * up[1],
        fwd[2] + sx * right[2] + sy * up[2] };
      norm3(d);
      int32_t hit;
      const double t = cast(&s, cam->position, d, 1e-6, 1e30, 0, &hit);
      if (hit < 0)
        continue;
      for (int a = 0; a < 3; ++a)
        rx[3 * nrec + a] = cam->position[a] + t * d[a];
      face_normal(&s, hit, d, rn + 3 * nrec);
      ++nrec;
    }

  /* VPLs: first hits of the spot's rays, stratified over its cone. */
  const mrgi_light* light = &scene.lights[0];
  double axis[3], lu[3], lv[3];
  sub3(light->focal_point, light->position, axis);
  norm3(axis);
  basis(axis, lu, lv);
  const int g = (int)ceil(sqrt((double)vpl_rays));
  const double cos_max = cos(light->cone_angle_deg * M_PI / 180.0);
  mrgi_vpl* vpls = calloc((size_t)(g * g), sizeof(mrgi_vpl));
  double* vw = calloc((size_t)(g * g), sizeof(double));
  int32_t nv = 0;
  for (int j = 0; j < g; ++j)
    for (int i = 0; i < g; ++i)
    {
      const double c = 1.0 - (1.0 - cos_max) * (j + 0.5) / g, phi = 2.0 * M_PI * (i + 0.5) / g;
      const double sn = sqrt(1.0 - c * c);
      double d[3];
      for (int a = 0; a < 3; ++a)
        d[a] = c * axis[a] + sn * (cos(phi) * lu[a] + sin(phi) * lv[a]);
      int32_t hit;
      const double t = cast(&s, light->position, d, 1e-6, 1e30, 0, &hit);
      if (hit < 0)
        continue;
      double n[3];
      face_normal(&s, hit, d, n);
      for (int a = 0; a < 3; ++a)
        vpls[nv].position[a] = (float)(light->position[a] + t * d[a]), vpls[nv].normal[a] = (float)n[a];
      vw[nv] = pow(c, light->exponent) * -dot3(n, d);
      ++nv;
    }

  /* Points and atlas. */
  const int32_t total = ppv * nv;
  double* weights = malloc(sizeof(double) * (size_t)s.triangle_count);
  double* cdf = malloc(sizeof(double) * (size_t)(s.triangle_count + 1));
  mrgi_ism_point* records = malloc(sizeof(mrgi_ism_point) * (size_t)total);
  float* points = malloc(sizeof(float) * 3 * (size_t)total);
  const int32_t views = nrec < 4096 ? nrec : 4096;
  mrgi_ism_atlas_layout layout;
  if (mrgi_ism_triangle_weights(s.positions, s.vertex_count, s.triangles, s.triangle_count,
        (mrgi_ism_mode)mode, mode ? rx : NULL, mode ? views : 0, 1u, weights, &err) != MRGI_OK ||
    mrgi_ism_cdf_build(weights, s.triangle_count, cdf, &err) != MRGI_OK ||
    mrgi_ism_sample(cdf, s.triangle_count, 1u, 0u, total, 0, total, records, &err) != MRGI_OK ||
    mrgi_ism_points_evaluate(s.positions, s.vertex_count, s.triangles, s.triangle_count, records,
      total, points, NULL, &err) != MRGI_OK ||
    mrgi_ism_atlas_layout_make(nv, tile, &layout, &err) != MRGI_OK)
  {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  const size_t scratch_count = mrgi_ism_push_pull_scratch_size(&layout);
  float* depth = malloc(sizeof(float) * (size_t)layout.width * (size_t)layout.height);
  float* scratch = malloc(sizeof(float) * scratch_count);
  if (mrgi_ism_atlas_render(&layout, points, total, vpls, getenv("ISM_PP") ? atoi(getenv("ISM_PP")) : MRGI_ISM_DEFAULT_PUSH_PULL_LEVELS, depth, scratch, scratch_count, &err) !=
    MRGI_OK)
  {
    fprintf(stderr, "%s\n", err.message);
    return 1;
  }
  if (getenv("ISM_PULL"))
    push_pull_variant(&layout, depth, scratch, atoi(getenv("ISM_PULL")));
  mrgi_ism_lookup_params params;
  mrgi_ism_lookup_params_default(&params);
  if (getenv("ISM_RB"))
    params.relative_bias = (float)atof(getenv("ISM_RB"));
  if (getenv("ISM_TB"))
    params.texel_bias = (float)atof(getenv("ISM_TB"));
  const double normal_offset = getenv("ISM_NO") ? atof(getenv("ISM_NO")) : 0.0;

  /* Gather. */
  double* e_none = calloc((size_t)nrec, sizeof(double));
  double* e_exact = calloc((size_t)nrec, sizeof(double));
  double* e_ism = calloc((size_t)nrec, sizeof(double));
  double* missed = calloc((size_t)nrec, sizeof(double));
  double* false_shadow = calloc((size_t)nrec, sizeof(double));
  for (int32_t r = 0; r < nrec; ++r)
    for (int32_t j = 0; j < nv; ++j)
    {
      const double v[3] = { vpls[j].position[0], vpls[j].position[1], vpls[j].position[2] };
      const double n[3] = { vpls[j].normal[0], vpls[j].normal[1], vpls[j].normal[2] };
      double d[3];
      sub3(rx + 3 * r, v, d);
      const double dist = sqrt(dot3(d, d));
      if (dist < 1e-6)
        continue;
      d[0] /= dist, d[1] /= dist, d[2] /= dist;
      const double term = vw[j] * fmax(0.0, dot3(n, d)) * fmax(0.0, -dot3(rn + 3 * r, d)) /
        fmax(dist * dist, 0.01);
      if (term <= 0.0)
        continue;
      int32_t hit;
      const double eps = 1e-4 * (1.0 + dist);
      cast(&s, v, d, eps, dist - eps, 1, &hit);
      const double vx = hit < 0 ? 1.0 : 0.0;
      float xf[3] = { (float)rx[3 * r], (float)rx[3 * r + 1], (float)rx[3 * r + 2] };
      float nf[3] = { (float)rn[3 * r], (float)rn[3 * r + 1], (float)rn[3 * r + 2] };
      if (normal_offset > 0.0)
      {
        const double c = fmax(dot3(n, d), MRGI_ISM_BIAS_MIN_COS);
        const double foot = dist * 2.0 / (tile * c);
        for (int a = 0; a < 3; ++a)
          xf[a] += (float)(normal_offset * foot * nf[a]);
      }
      const double vi =
        mrgi_ism_visibility(&layout, depth, j, vpls[j].position, vpls[j].normal, xf, &params);
      e_none[r] += term, e_exact[r] += term * vx, e_ism[r] += term * vi;
      if (vx < vi)
        missed[r] += term * (vi - vx);
      if (vx > vi)
        false_shadow[r] += term * (vx - vi);
    }

  double* sorted = malloc(sizeof(double) * (size_t)nrec);
  memcpy(sorted, e_none, sizeof(double) * (size_t)nrec);
  qsort(sorted, (size_t)nrec, sizeof(double), cmp_double);
  const double median = sorted[nrec / 2];
  double reg_n = 0, reg_x = 0, reg_i = 0, reg_m = 0, reg_f = 0, all_x = 0, all_m = 0, all_f = 0;
  double se_none = 0, se_ism = 0, sx2 = 0;
  int32_t reg_count = 0;
  for (int32_t r = 0; r < nrec; ++r)
  {
    if (e_none[r] > median && e_exact[r] < 0.7 * e_none[r])
    {
      reg_n += e_none[r], reg_x += e_exact[r], reg_i += e_ism[r], reg_m += missed[r],
        reg_f += false_shadow[r];
      ++reg_count;
    }
    all_x += e_exact[r], all_m += missed[r], all_f += false_shadow[r];
    se_none += (e_none[r] - e_exact[r]) * (e_none[r] - e_exact[r]);
    se_ism += (e_ism[r] - e_exact[r]) * (e_ism[r] - e_exact[r]);
    sx2 += e_exact[r] * e_exact[r];
  }
  printf("%s tile %d points/VPL %d mode %d: %d receivers, %d VPLs, %d triangles\n", name, tile, ppv,
    mode, nrec, nv, s.triangle_count);
  printf("  region (%d receivers): mean / exact: none %.3f ism %.3f; missed %.1f%%, false %.1f%% of "
         "exact\n",
    reg_count, reg_n / reg_x, reg_i / reg_x, 100.0 * reg_m / reg_x, 100.0 * reg_f / reg_x);
  printf("  all: rel. RMS vs exact: none %.4f ism %.4f; missed %.1f%%, false %.1f%% of exact\n",
    sqrt(se_none / sx2), sqrt(se_ism / sx2), 100.0 * all_m / all_x, 100.0 * all_f / all_x);
  return 0;
}
