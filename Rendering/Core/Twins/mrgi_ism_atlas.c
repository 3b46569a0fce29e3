/* ISM atlas: see mrgi_ism_atlas.h (RGK08 3.3, RIHKS11 6.1). */
#include "mrgi_ism_atlas.h"

#include "mrgi_vpl.h"

#include <math.h>

mrgi_status mrgi_ism_atlas_layout_make(
  int32_t vpl_count, int32_t tile_size, mrgi_ism_atlas_layout* layout, mrgi_error* err)
{
  if (!layout)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM atlas: NULL layout");
  if (tile_size < 4 || tile_size > MRGI_ISM_MAX_TILE || (tile_size & (tile_size - 1)))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM atlas: tile size %d is not a power of two in 4..%d", tile_size, MRGI_ISM_MAX_TILE);
  if (vpl_count <= 0)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM atlas: VPL count %d < 1", vpl_count);
  int32_t c = (int32_t)ceil(sqrt((double)vpl_count));
  while ((int64_t)c * c < vpl_count)
    ++c;
  const int32_t r = (vpl_count + c - 1) / c;
  if ((int64_t)c * tile_size > MRGI_ISM_MAX_ATLAS || (int64_t)r * tile_size > MRGI_ISM_MAX_ATLAS)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM atlas: %d VPLs of %d x %d tiles need a %lld x %lld atlas (max %d)", vpl_count, tile_size,
      tile_size, (long long)c * tile_size, (long long)r * tile_size, MRGI_ISM_MAX_ATLAS);
  layout->vpl_count = vpl_count;
  layout->tile_size = tile_size;
  layout->tiles_per_row = c;
  layout->tile_rows = r;
  layout->width = c * tile_size;
  layout->height = r * tile_size;
  return MRGI_OK;
}

int32_t mrgi_ism_point_vpl(int64_t point_index, int32_t vpl_count)
{
  if (point_index < 0 || vpl_count <= 0)
    return -1;
  return (int32_t)(point_index % vpl_count);
}

void mrgi_ism_vpl_frame(const double n[3], double t[3], double b[3])
{
  /* Duff et al. 2017, "Building an orthonormal basis, revisited". */
  const double sign = n[2] >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (sign + n[2]);
  const double c = n[0] * n[1] * a;
  t[0] = 1.0 + sign * n[0] * n[0] * a;
  t[1] = sign * c;
  t[2] = -sign * n[0];
  b[0] = c;
  b[1] = sign + n[1] * n[1] * a;
  b[2] = -n[1];
}

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int mrgi_ism_cos_sphere_forward(const double n[3], const double d[3], double st[2])
{
  double t[3], b[3];
  mrgi_ism_vpl_frame(n, t, b);
  if (dot3(d, n) < 0.0)
    return 0;
  st[0] = dot3(d, t);
  st[1] = dot3(d, b);
  return 1;
}

void mrgi_ism_cos_sphere_inverse(const double n[3], const double st[2], double d[3])
{
  double t[3], b[3];
  mrgi_ism_vpl_frame(n, t, b);
  const double r2 = st[0] * st[0] + st[1] * st[1];
  const double z = r2 < 1.0 ? sqrt(1.0 - r2) : 0.0;
  for (int k = 0; k < 3; ++k)
    d[k] = st[0] * t[k] + st[1] * b[k] + z * n[k];
}

int mrgi_ism_point_texel(const mrgi_ism_atlas_layout* layout, int32_t vpl_index,
  const double vpl_pos[3], const double vpl_normal[3], const double point[3], int64_t* texel,
  float* depth)
{
  if (!layout || !vpl_pos || !vpl_normal || !point || vpl_index < 0 ||
    vpl_index >= layout->vpl_count)
    return 0;
  const double v[3] = { point[0] - vpl_pos[0], point[1] - vpl_pos[1], point[2] - vpl_pos[2] };
  const double dist = sqrt(dot3(v, v));
  if (!(dist >= MRGI_ISM_MIN_DEPTH) || !isfinite(dist))
    return 0;
  const double d[3] = { v[0] / dist, v[1] / dist, v[2] / dist };
  double st[2];
  if (!mrgi_ism_cos_sphere_forward(vpl_normal, d, st))
    return 0;
  const int32_t T = layout->tile_size;
  int32_t x = (int32_t)floor((st[0] + 1.0) * 0.5 * T);
  int32_t y = (int32_t)floor((st[1] + 1.0) * 0.5 * T);
  x = x < 0 ? 0 : (x >= T ? T - 1 : x);
  y = y < 0 ? 0 : (y >= T ? T - 1 : y);
  const int64_t X = (int64_t)(vpl_index % layout->tiles_per_row) * T + x;
  const int64_t Y = (int64_t)(vpl_index / layout->tiles_per_row) * T + y;
  if (texel)
    *texel = Y * layout->width + X;
  if (depth)
    *depth = (float)dist;
  return 1;
}

size_t mrgi_ism_push_pull_scratch_size(const mrgi_ism_atlas_layout* layout)
{
  if (!layout || layout->tile_size <= 0)
    return 0;
  const size_t t = (size_t)layout->tile_size;
  return (t * t * 4) / 3 + 1; /* levels T .. 1 */
}

mrgi_status mrgi_ism_push_pull(const mrgi_ism_atlas_layout* layout, float* depth, int32_t levels,
  float* scratch, size_t scratch_count, mrgi_error* err)
{
  if (!layout || !depth || !scratch)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM atlas: NULL push-pull arrays");
  if (levels < 1 || levels > MRGI_ISM_MAX_PUSH_PULL_LEVELS)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM atlas: %d push-pull levels, must be 1..%d", (int)levels, MRGI_ISM_MAX_PUSH_PULL_LEVELS);
  if (scratch_count < mrgi_ism_push_pull_scratch_size(layout))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM atlas: push-pull scratch holds %zu floats, needs %zu", scratch_count,
      mrgi_ism_push_pull_scratch_size(layout));
  const int32_t T = layout->tile_size;
  const float E = MRGI_ISM_EMPTY_DEPTH;
  for (int32_t l = 0; l < layout->vpl_count; ++l)
  {
    const int64_t x0 = (int64_t)(l % layout->tiles_per_row) * T;
    const int64_t y0 = (int64_t)(l / layout->tiles_per_row) * T;
    /* Level 0 = the tile copied into scratch; level k side T >> k follows. */
    float* lev[16];
    int32_t nlev = 0;
    size_t off = 0;
    for (int32_t s = T; s >= 1 && nlev <= levels; s >>= 1)
    {
      lev[nlev++] = scratch + off;
      off += (size_t)s * s;
    }
    for (int32_t y = 0; y < T; ++y)
      for (int32_t x = 0; x < T; ++x)
      {
        const float d = depth[(y0 + y) * layout->width + x0 + x];
        lev[0][y * T + x] = (isfinite(d) && d < E) ? d : E;
      }
    for (int32_t k = 1; k < nlev; ++k) /* pull: mean of the valid children */
    {
      const int32_t s = T >> k;
      for (int32_t y = 0; y < s; ++y)
        for (int32_t x = 0; x < s; ++x)
        {
          const float* c = lev[k - 1];
          const int32_t w = 2 * s;
          const float q[4] = { c[2 * y * w + 2 * x], c[2 * y * w + 2 * x + 1],
            c[(2 * y + 1) * w + 2 * x], c[(2 * y + 1) * w + 2 * x + 1] };
          float sum = 0.0f;
          int count = 0;
          for (int i = 0; i < 4; ++i)
            if (q[i] < E)
            {
              sum += q[i];
              ++count;
            }
          lev[k][y * s + x] = count > 0 ? sum / (float)count : E;
        }
    }
    for (int32_t k = nlev - 2; k >= 0; --k) /* push: holes take the parent's depth */
    {
      const int32_t s = T >> k;
      for (int32_t y = 0; y < s; ++y)
        for (int32_t x = 0; x < s; ++x)
          if (!(lev[k][y * s + x] < E))
            lev[k][y * s + x] = lev[k + 1][(y / 2) * (s / 2) + x / 2];
    }
    for (int32_t y = 0; y < T; ++y)
      for (int32_t x = 0; x < T; ++x)
        depth[(y0 + y) * layout->width + x0 + x] = lev[0][y * T + x];
  }
  return MRGI_OK;
}

mrgi_status mrgi_ism_atlas_render(const mrgi_ism_atlas_layout* layout, const float* points,
  int64_t point_count, const struct mrgi_vpl* vpls, int32_t push_pull_levels, float* depth,
  float* scratch, size_t scratch_count, mrgi_error* err)
{
  if (!layout || !depth || !vpls || (point_count > 0 && !points))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM atlas: NULL render arrays");
  if (point_count < 0)
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "ISM atlas: point count %lld < 0", (long long)point_count);
  if (layout->vpl_count < 1 || layout->width != layout->tiles_per_row * layout->tile_size ||
    layout->height != layout->tile_rows * layout->tile_size)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM atlas: malformed layout");
  if (push_pull_levels < 0 || push_pull_levels > MRGI_ISM_MAX_PUSH_PULL_LEVELS)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM atlas: %d push-pull levels, must be 0..%d", (int)push_pull_levels,
      MRGI_ISM_MAX_PUSH_PULL_LEVELS);
  if (push_pull_levels > 0 && scratch_count < mrgi_ism_push_pull_scratch_size(layout))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM atlas: push-pull scratch holds %zu floats, needs %zu", scratch_count,
      mrgi_ism_push_pull_scratch_size(layout));
  const size_t n = (size_t)layout->width * (size_t)layout->height;
  for (size_t k = 0; k < n; ++k)
    depth[k] = MRGI_ISM_EMPTY_DEPTH;
  const int32_t V = layout->vpl_count;
  for (int64_t i = 0; i < point_count; ++i)
  {
    const int32_t l = mrgi_ism_point_vpl(i, V); /* section 2: VPL i mod V */
    const mrgi_vpl* L = &vpls[l];
    const double nrm[3] = { L->normal[0], L->normal[1], L->normal[2] };
    const double n2 = dot3(nrm, nrm);
    if (!(n2 > 0.0) || !isfinite(n2)) /* empty VPL: draws nothing */
      continue;
    const double pos[3] = { L->position[0], L->position[1], L->position[2] };
    const double x[3] = { points[3 * i], points[3 * i + 1], points[3 * i + 2] };
    int64_t texel;
    float d;
    if (mrgi_ism_point_texel(layout, l, pos, nrm, x, &texel, &d) && d < depth[texel])
      depth[texel] = d; /* GL_MIN blending */
  }
  return push_pull_levels > 0
    ? mrgi_ism_push_pull(layout, depth, push_pull_levels, scratch, scratch_count, err)
    : MRGI_OK;
}
