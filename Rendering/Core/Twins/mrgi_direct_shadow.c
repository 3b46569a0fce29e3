/* Shadow factors from the reflective shadow maps; contract in mrgi_direct_shadow.h.
 * vtkMRGIDirectShadowFS.glsl translates this file statement by statement
 * (in float); keep the two in the same order. */
#include "mrgi_direct_shadow.h"

#include "mrgi_buffers.h"

#include <math.h>
#include <stdlib.h>

void mrgi_direct_shadow_params_default(mrgi_direct_shadow_params* params)
{
  if (!params)
  {
    return;
  }
  params->mode = MRGI_DIRECT_SHADOW_SOFT;
  params->samples_side = MRGI_DIRECT_SHADOW_DEFAULT_SIDE;
  params->light_radius = 0.0;
}

mrgi_status mrgi_direct_shadow_params_check(const mrgi_direct_shadow_params* params, mrgi_error* err)
{
  if (!params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "direct shadows: no parameters");
  }
  if (params->mode != MRGI_DIRECT_SHADOW_HARD && params->mode != MRGI_DIRECT_SHADOW_SOFT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: mode %d is neither hard (%d) nor soft (%d)", params->mode,
      MRGI_DIRECT_SHADOW_HARD, MRGI_DIRECT_SHADOW_SOFT);
  }
  if (params->samples_side < 1 || params->samples_side > MRGI_DIRECT_SHADOW_MAX_SIDE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: samples side %d is outside 1..%d", params->samples_side,
      MRGI_DIRECT_SHADOW_MAX_SIDE);
  }
  if (!(params->light_radius >= 0.0) || !isfinite(params->light_radius))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: light radius %g is not a finite value >= 0", params->light_radius);
  }
  return MRGI_OK;
}

int mrgi_direct_shadow_view_usable(const mrgi_direct_shadow_view* view)
{
  if (!view || view->size < 1 || !view->positions)
  {
    return 0;
  }
  for (int k = 0; k < 16; ++k)
  {
    if (!isfinite(view->world_to_view[k]))
    {
      return 0;
    }
  }
  if (!(view->scale[0] > 0.0) || !(view->scale[1] > 0.0) || !isfinite(view->scale[0]) ||
    !isfinite(view->scale[1]))
  {
    return 0;
  }
  if (view->perspective && (!(view->near_plane > 0.0) || !isfinite(view->near_plane)))
  {
    return 0;
  }
  return 1;
}

/* View coordinates of world point p (w = 1) or direction (w = 0). */
static void to_view(const double m[16], const double p[3], double w, double out[3])
{
  for (int r = 0; r < 3; ++r)
  {
    out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] * w;
  }
}

mrgi_status mrgi_direct_shadow_depth_map(
  const mrgi_direct_shadow_view* view, float* depth, size_t capacity, mrgi_error* err)
{
  if (!mrgi_direct_shadow_view_usable(view) || !depth)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: the view is degenerate (size, positions, matrix or projection) "
      "or there is no depth buffer");
  }
  const size_t texels = (size_t)view->size * (size_t)view->size;
  if (capacity < texels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: the depth buffer holds %zu floats, the view needs %zu", capacity, texels);
  }
  const double* m = view->world_to_view;
  for (size_t t = 0; t < texels; ++t)
  {
    const float* q = view->positions + 4 * t;
    float d = MRGI_DIRECT_SHADOW_NO_OCCLUDER;
    if (q[3] > MRGI_GBUFFER_VALID_THRESHOLD && isfinite(q[0]) && isfinite(q[1]) && isfinite(q[2]))
    {
      const double z = m[2] * q[0] + m[6] * q[1] + m[10] * q[2] + m[14];
      if (-z > 0.0 && isfinite(z))
      {
        d = (float)(-z);
      }
    }
    depth[t] = d;
  }
  return MRGI_OK;
}

/* c of the file comment for view coordinates q; -1 when the view does not hold q. */
static double view_centrality(const mrgi_direct_shadow_view* view, const double q[3])
{
  const double d = -q[2];
  const double m = fmax(fabs(view->scale[0] * q[0]), fabs(view->scale[1] * q[1]));
  double c = m;
  if (view->perspective)
  {
    if (!(d > view->near_plane))
    {
      return -1.0;
    }
    c = m / d;
  }
  return c <= 1.0 ? c : -1.0;
}

int mrgi_direct_shadow_select_view(const mrgi_direct_shadow_view* views, int count,
  const double p[3], mrgi_direct_shadow_stats* stats)
{
  int best = -1;
  double bestC = 0.0;
  for (int v = 0; v < count && views; ++v)
  {
    if (!mrgi_direct_shadow_view_usable(&views[v]))
    {
      if (stats)
      {
        stats->invalid_views++;
      }
      continue;
    }
    double q[3];
    to_view(views[v].world_to_view, p, 1.0, q);
    const double c = view_centrality(&views[v], q);
    if (c >= 0.0 && (best < 0 || c < bestC))
    {
      best = v;
      bestC = c;
    }
  }
  return best;
}

/* The receiver as one view sees it. */
typedef struct receiver
{
  const mrgi_direct_shadow_view* view;
  const float* depth;
  double q[3]; /* view coordinates */
  double n[3]; /* view-space unit normal facing the light */
  double d;    /* depth */
  double T;    /* texel size: perspective per unit depth, orthographic world */
  double f;    /* footprint at the receiver, world */
  double u, v; /* continuous texel coordinates */
} receiver;

/* Depth of the receiver's tangent plane along texel (i, j)'s ray. */
static double plane_depth(const receiver* r, int i, int j)
{
  const mrgi_direct_shadow_view* view = r->view;
  const double S = (double)view->size;
  const double cx = ((double)i + 0.5) / S * 2.0 - 1.0;
  const double cy = ((double)j + 0.5) / S * 2.0 - 1.0;
  if (view->perspective)
  {
    const double a = cx / view->scale[0], b = cy / view->scale[1];
    const double aP = r->q[0] / r->d, bP = r->q[1] / r->d;
    const double den =
      fmin(r->n[0] * a + r->n[1] * b - r->n[2], -1.0 / MRGI_DIRECT_SHADOW_MAX_SLOPE);
    return r->d + r->d * (r->n[0] * (aP - a) + r->n[1] * (bP - b)) / den;
  }
  const double den = fmax(r->n[2], 1.0 / MRGI_DIRECT_SHADOW_MAX_SLOPE);
  return r->d +
    (r->n[0] * (cx / view->scale[0] - r->q[0]) + r->n[1] * (cy / view->scale[1] - r->q[1])) / den;
}

/* Whether the tap at continuous texel coordinates (tu, tv) occludes; its depth in *depth. */
static int tap_occludes(const receiver* r, double tu, double tv, double* depth)
{
  const int S = r->view->size;
  const double fi = floor(tu), fj = floor(tv);
  if (!(fi >= 0.0 && fj >= 0.0 && fi < (double)S && fj < (double)S))
  {
    return 0;
  }
  const int i = (int)fi, j = (int)fj;
  const double dt = (double)r->depth[(size_t)j * (size_t)S + (size_t)i];
  if (!(dt > 0.0))
  {
    return 0; /* MRGI_DIRECT_SHADOW_NO_OCCLUDER */
  }
  *depth = dt;
  return dt < plane_depth(r, i, j) - MRGI_DIRECT_SHADOW_BIAS_TEXELS * r->f;
}

/* Taps of an n x n grid of radius w: the number that occlude and the sum of their depths. */
static int grid_occluders(const receiver* r, int n, double w, double* depthSum)
{
  int count = 0;
  double sum = 0.0;
  for (int l = 0; l < n; ++l)
  {
    const double ov = (((double)l + 0.5) / (double)n * 2.0 - 1.0) * w;
    for (int k = 0; k < n; ++k)
    {
      const double ou = (((double)k + 0.5) / (double)n * 2.0 - 1.0) * w;
      double dt = 0.0;
      if (tap_occludes(r, r->u + ou, r->v + ov, &dt))
      {
        ++count;
        sum += dt;
      }
    }
  }
  *depthSum = sum;
  return count;
}

static double clamp_radius(double w)
{
  return fmin(fmax(w, MRGI_DIRECT_SHADOW_MIN_RADIUS), MRGI_DIRECT_SHADOW_MAX_RADIUS);
}

double mrgi_direct_shadow_factor(const mrgi_direct_shadow_view* views, const float* const* depths,
  int count, const mrgi_direct_shadow_params* params, const double p[3], const double n[3],
  mrgi_direct_shadow_stats* stats)
{
  if (mrgi_direct_shadow_params_check(params, NULL) != MRGI_OK || !views || !depths || !p || !n ||
    count < 0 || count > MRGI_DIRECT_SHADOW_MAX_VIEWS)
  {
    return 1.0;
  }
  const double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]) || !(nn > 0.0) || !isfinite(nn))
  {
    if (stats)
    {
      stats->invalid_receivers++;
    }
    return 1.0;
  }
  const int v = mrgi_direct_shadow_select_view(views, count, p, stats);
  if (v < 0 || !depths[v])
  {
    if (stats)
    {
      stats->outside++;
    }
    return 1.0;
  }
  receiver r;
  r.view = &views[v];
  r.depth = depths[v];
  to_view(r.view->world_to_view, p, 1.0, r.q);
  const double unit[3] = { n[0] / nn, n[1] / nn, n[2] / nn };
  to_view(r.view->world_to_view, unit, 0.0, r.n);
  const int perspective = r.view->perspective;
  /* Toward the light: -q (perspective, the light at the origin) or +z. */
  const double facing =
    perspective ? -(r.n[0] * r.q[0] + r.n[1] * r.q[1] + r.n[2] * r.q[2]) : r.n[2];
  if (facing < 0.0)
  {
    r.n[0] = -r.n[0];
    r.n[1] = -r.n[1];
    r.n[2] = -r.n[2];
  }
  /* Grazing receivers: past the slope clamp the receiver plane no longer
   * bounds the taps and a lit surface would shadow itself in stripes; the
   * shadow fades out over one more clamp angle instead (the header). */
  const double qn = sqrt(r.q[0] * r.q[0] + r.q[1] * r.q[1] + r.q[2] * r.q[2]);
  const double cosine = perspective ? (qn > 0.0 ? fabs(facing) / qn : 1.0) : fabs(facing);
  const double grazing = mrgi_direct_shadow_grazing_weight(cosine);
  if (!(grazing > 0.0))
  {
    return 1.0;
  }
  const double S = (double)r.view->size;
  const double sMin = fmin(r.view->scale[0], r.view->scale[1]);
  r.d = -r.q[2];
  r.T = 2.0 / (S * sMin);
  r.f = perspective ? r.d * r.T : r.T;
  const double nx = perspective ? r.view->scale[0] * r.q[0] / r.d : r.view->scale[0] * r.q[0];
  const double ny = perspective ? r.view->scale[1] * r.q[1] / r.d : r.view->scale[1] * r.q[1];
  r.u = (nx * 0.5 + 0.5) * S;
  r.v = (ny * 0.5 + 0.5) * S;

  double sum = 0.0;
  if (params->mode == MRGI_DIRECT_SHADOW_HARD)
  {
    const int side = MRGI_DIRECT_SHADOW_HARD_SIDE;
    const int blocked = grid_occluders(&r, side, 0.5 * (double)side, &sum);
    return 1.0 - grazing * (double)blocked / (double)(side * side);
  }

  /* PCSS: the blocker search over the region a blocker at depth >= d_n can shadow. */
  const double radius = params->light_radius;
  const double near = perspective ? r.view->near_plane : 0.0;
  const double dn = fmax(near, MRGI_DIRECT_SHADOW_SEARCH_NEAR * r.d);
  const double theta = radius * sMin; /* orthographic: angular radius */
  const double search = clamp_radius(
    perspective ? radius * (r.d - dn) / (r.d * dn * r.T) : theta * (r.d - dn) / r.T);
  const int blockers = grid_occluders(&r, MRGI_DIRECT_SHADOW_BLOCKER_SIDE, search, &sum);
  if (blockers == 0)
  {
    return 1.0;
  }
  const double db = sum / (double)blockers;
  const double width = clamp_radius(
    perspective ? radius * (r.d - db) / (r.d * db * r.T) : theta * (r.d - db) / r.T);
  const int side = params->samples_side;
  const int blocked = grid_occluders(&r, side, width, &sum);
  return 1.0 - grazing * (double)blocked / (double)(side * side);
}

double mrgi_direct_shadow_grazing_weight(double cosine)
{
  const double c0 = 1.0 / sqrt(1.0 + MRGI_DIRECT_SHADOW_MAX_SLOPE * MRGI_DIRECT_SHADOW_MAX_SLOPE);
  const double w = (cosine - c0) / c0;
  return w > 1.0 ? 1.0 : (w > 0.0 ? w : 0.0);
}

/* Factors (level -1: every pixel, `factor`, 1 without geometry) or BMR
 * level `level` >= 0 (1 - factor at each block's centre pixel, 0 without
 * geometry) of a G-buffer; the public functions check `level`. */
static mrgi_status shadow_gbuffer(int width, int height, int level, const float* positions,
  const float* normals, const double view_to_world[16], const mrgi_direct_shadow_view* views,
  int count, const mrgi_direct_shadow_params* params, float* out,
  mrgi_direct_shadow_stats* stats, mrgi_error* err)
{
  if (width < 1 || height < 1 || !positions || !normals || !view_to_world || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: a %d x %d G-buffer needs positions, normals, a view-to-world matrix "
      "and a factor buffer",
      width, height);
  }
  if (count < 0 || count > MRGI_DIRECT_SHADOW_MAX_VIEWS || (count > 0 && !views))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: %d views (0..%d allowed)", count, MRGI_DIRECT_SHADOW_MAX_VIEWS);
  }
  mrgi_status status = mrgi_direct_shadow_params_check(params, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  float* maps[MRGI_DIRECT_SHADOW_MAX_VIEWS] = { NULL };
  for (int v = 0; v < count; ++v)
  {
    if (!mrgi_direct_shadow_view_usable(&views[v]))
    {
      continue; /* skipped (and counted) by the selection */
    }
    const size_t texels = (size_t)views[v].size * (size_t)views[v].size;
    maps[v] = (float*)malloc(texels * sizeof(float));
    if (!maps[v])
    {
      status = mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
        "direct shadows: no memory for a %d x %d depth map", views[v].size, views[v].size);
      break;
    }
    status = mrgi_direct_shadow_depth_map(&views[v], maps[v], texels, err);
    if (status != MRGI_OK)
    {
      break;
    }
  }
  if (status == MRGI_OK)
  {
    const double* m = view_to_world;
    /* Level k: texel (i, j) is the receiver at its 2^k block's centre pixel
     * (vtkMRGIDirectShadowFS.glsl, mrgiLevel >= 0). */
    const int side = level > 0 ? 1 << level : 1;
    const int centre = side / 2;
    const int out_w = (width + side - 1) / side, out_h = (height + side - 1) / side;
    for (int j = 0; j < out_h; ++j)
    {
      for (int i = 0; i < out_w; ++i)
      {
        const int x = i * side + centre < width - 1 ? i * side + centre : width - 1;
        const int y = j * side + centre < height - 1 ? j * side + centre : height - 1;
        const size_t t = (size_t)y * (size_t)width + (size_t)x;
        float* o = out + (size_t)j * (size_t)out_w + (size_t)i;
        const float* e = positions + 4 * t;
        const float* en = normals + 4 * t;
        if (!(e[3] > MRGI_GBUFFER_VALID_THRESHOLD))
        {
          *o = level < 0 ? 1.0f : 0.0f;
          continue;
        }
        const double pe[3] = { e[0], e[1], e[2] }, ne[3] = { en[0], en[1], en[2] };
        double p[3], n[3];
        to_view(m, pe, 1.0, p);
        to_view(m, ne, 0.0, n);
        const double f =
          mrgi_direct_shadow_factor(views, (const float* const*)maps, count, params, p, n, stats);
        *o = level < 0 ? (float)f : (float)(1.0 - f);
      }
    }
  }
  for (int v = 0; v < count; ++v)
  {
    free(maps[v]);
  }
  return status;
}

mrgi_status mrgi_direct_shadow_gbuffer(int width, int height, const float* positions,
  const float* normals, const double view_to_world[16], const mrgi_direct_shadow_view* views,
  int count, const mrgi_direct_shadow_params* params, float* factors,
  mrgi_direct_shadow_stats* stats, mrgi_error* err)
{
  return shadow_gbuffer(width, height, -1, positions, normals, view_to_world, views, count,
    params, factors, stats, err);
}

mrgi_status mrgi_direct_shadow_level(int width, int height, int level, const float* positions,
  const float* normals, const double view_to_world[16], const mrgi_direct_shadow_view* views,
  int count, const mrgi_direct_shadow_params* params, float* occlusion,
  mrgi_direct_shadow_stats* stats, mrgi_error* err)
{
  if (level < 0 || level > MRGI_DIRECT_SHADOW_MAX_LEVEL)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "direct shadows: level %d (0..%d allowed)", level, MRGI_DIRECT_SHADOW_MAX_LEVEL);
  }
  return shadow_gbuffer(width, height, level, positions, normals, view_to_world, views, count,
    params, occlusion, stats, err);
}
