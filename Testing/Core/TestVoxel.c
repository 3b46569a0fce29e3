/* Tests of mrgi_voxel, mrgi_voxel_march and mrgi_voxel_incremental: bit
 * layout and slice mapping at the range ends, the window -> voxel mapping,
 * projections, voxelization of known fragments and depth buffers, the ray
 * march on constructed scenes (walls, a thin wall, grazing floors, near
 * plane, light behind the camera, off-screen, zero length, symmetry),
 * incremental and interleaved visibility against the naive one, the
 * refinement metric, the variance shadow query, bad input, and random box
 * scenes against exact ray-box visibility at voxel resolutions 128/256/512. */
#include "mrgi_voxel.h"
#include "mrgi_variance_shadow.h"
#include "mrgi_visibility_pyramid.h"
#include "mrgi_voxel_march.h"

#include "mrgi_buffers.h"
#include "mrgi_multires_receivers.h"
#include "mrgi_test.h"

#include <float.h>
#include <string.h>

/* ---- small deterministic random numbers ---- */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint32_t rng_u32(void)
{
  rng_state ^= rng_state << 13;
  rng_state ^= rng_state >> 7;
  rng_state ^= rng_state << 17;
  return (uint32_t)(rng_state >> 11);
}
static double rng_unit(void) /* [0, 1) */
{
  return (double)rng_u32() / 4294967296.0;
}
static double rng_range(double lo, double hi)
{
  return lo + (hi - lo) * rng_unit();
}

/* ---- box scenes in eye space (the camera at the origin looking down -z) ---- */
#define MAX_BOXES 48
typedef struct box
{
  double lo[3];
  double hi[3];
} box;

typedef struct scene
{
  int count;
  box boxes[MAX_BOXES];
} scene;

static void scene_add(scene* s, double x0, double y0, double z0, double x1, double y1, double z1)
{
  MRGI_CHECK(s->count < MAX_BOXES);
  box* b = s->boxes + s->count++;
  b->lo[0] = x0;
  b->lo[1] = y0;
  b->lo[2] = z0;
  b->hi[0] = x1;
  b->hi[1] = y1;
  b->hi[2] = z1;
}

/* View ray through NDC (nx, ny): origin o, direction r with r.z = -1, so the
 * ray parameter is the linear depth. */
static void view_ray(const mrgi_voxel_projection* p, double nx, double ny, double o[3], double r[3])
{
  const double x = (nx - p->offset_x) / p->scale_x;
  const double y = (ny - p->offset_y) / p->scale_y;
  if (p->parallel)
  {
    o[0] = x;
    o[1] = y;
    o[2] = 0.0;
    r[0] = 0.0;
    r[1] = 0.0;
  }
  else
  {
    o[0] = o[1] = o[2] = 0.0;
    r[0] = x;
    r[1] = y;
  }
  r[2] = -1.0;
}

/* Slab test of the line o + t r: entry/exit parameters and the axes of the
 * entry/exit faces. 0 when the line misses the box. */
static int ray_box(const double o[3], const double r[3], const box* b, double* t_in, int* a_in,
                   double* t_out, int* a_out)
{
  double t0 = -DBL_MAX, t1 = DBL_MAX;
  int a0 = -1, a1 = -1;
  for (int c = 0; c < 3; ++c)
  {
    if (r[c] == 0.0)
    {
      if (o[c] < b->lo[c] || o[c] > b->hi[c])
      {
        return 0;
      }
      continue;
    }
    double ta = (b->lo[c] - o[c]) / r[c];
    double tb = (b->hi[c] - o[c]) / r[c];
    if (ta > tb)
    {
      const double t = ta;
      ta = tb;
      tb = t;
    }
    if (ta > t0)
    {
      t0 = ta;
      a0 = c;
    }
    if (tb < t1)
    {
      t1 = tb;
      a1 = c;
    }
  }
  if (t0 > t1)
  {
    return 0;
  }
  *t_in = t0;
  *a_in = a0;
  *t_out = t1;
  *a_out = a1;
  return 1;
}

/* Depth at which the view ray through NDC (nx, ny) meets the plane X_axis = c. */
static double plane_depth(const mrgi_voxel_projection* p, double nx, double ny, int axis, double c)
{
  double o[3], r[3];
  view_ray(p, nx, ny, o, r);
  return (c - o[axis]) / r[axis];
}

/* The GPU's voxelization pass on a box scene: every face of every box is
 * rasterized at the voxel pixel centres (entry and exit of the view ray), with
 * half span 0.5 fwidth(d) of the face's plane and the face's depth range as
 * the primitive range (a face is two triangles on the GPU, each with a range
 * inside the face's: this stand-in is slightly more conservative). Returns
 * fragments written. */
static int64_t voxelize_scene(const scene* s, const mrgi_voxel_grid* g,
                              const mrgi_voxel_projection* p, uint32_t* voxels, size_t words)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_voxel_clear(g, voxels, words, &err) == MRGI_OK);
  mrgi_voxel_fragment* row =
    (mrgi_voxel_fragment*)malloc(sizeof(mrgi_voxel_fragment) * (size_t)g->width * 2 * MAX_BOXES);
  MRGI_CHECK(row != NULL);
  int64_t written = 0;
  const double px = 2.0 / g->width;
  const double py = 2.0 / g->height;
  for (int32_t y = 0; y < g->height; ++y)
  {
    size_t n = 0;
    for (int32_t x = 0; x < g->width; ++x)
    {
      const double nx = (x + 0.5) * px - 1.0;
      const double ny = (y + 0.5) * py - 1.0;
      double o[3], r[3];
      view_ray(p, nx, ny, o, r);
      for (int k = 0; k < s->count; ++k)
      {
        double t[2];
        int a[2];
        if (!ray_box(o, r, s->boxes + k, &t[0], &a[0], &t[1], &a[1]))
        {
          continue;
        }
        for (int e = 0; e < 2; ++e)
        {
          const int axis = a[e];
          const double c = o[axis] + t[e] * r[axis]; /* the face's plane */
          double h = 0.0;
          if (!p->parallel)
          {
            const double dx =
              plane_depth(p, nx + 0.5 * px, ny, axis, c) - plane_depth(p, nx - 0.5 * px, ny, axis, c);
            const double dy =
              plane_depth(p, nx, ny + 0.5 * py, axis, c) - plane_depth(p, nx, ny - 0.5 * py, axis, c);
            h = 0.5 * (fabs(dx) + fabs(dy));
            if (!isfinite(h) || h > 1e6)
            {
              h = 1e6;
            }
          }
          /* depth = -z is linear over the face: extreme at its corners */
          const box* b = s->boxes + k;
          const double dmin = axis == 2 ? -c : -b->hi[2];
          const double dmax = axis == 2 ? -c : -b->lo[2];
          mrgi_voxel_fragment f = { x, y, (float)t[e], (float)h, (float)dmin, (float)dmax };
          row[n++] = f;
        }
      }
    }
    mrgi_voxel_info info;
    MRGI_CHECK(mrgi_voxel_voxelize(g, row, n, voxels, words, &info, &err) == MRGI_OK);
    written += info.fragments_written;
  }
  free(row);
  return written;
}

/* First surface along the view ray through NDC (nx, ny): position and the
 * outward normal of the entry face (the G-buffer). 0 for background. */
static int scene_hit(const scene* s, const mrgi_voxel_projection* p, double nx, double ny,
                     float position[3], float normal[3])
{
  double o[3], r[3];
  view_ray(p, nx, ny, o, r);
  double best = DBL_MAX;
  int best_axis = -1;
  for (int k = 0; k < s->count; ++k)
  {
    double t0, t1;
    int a0, a1;
    if (ray_box(o, r, s->boxes + k, &t0, &a0, &t1, &a1) && t0 > 0.0 && t0 < best)
    {
      best = t0;
      best_axis = a0;
    }
  }
  if (best_axis < 0)
  {
    return 0;
  }
  for (int c = 0; c < 3; ++c)
  {
    position[c] = (float)(o[c] + best * r[c]);
    normal[c] = 0.0f;
  }
  normal[best_axis] = r[best_axis] > 0.0 ? -1.0f : 1.0f;
  return 1;
}

/* Exact visibility: the segment from P (pushed 1e-4 along N off its surface) to L misses every box. */
static int exact_visible(const scene* s, const float P[3], const float N[3], const float L[3])
{
  double o[3], r[3];
  for (int c = 0; c < 3; ++c)
  {
    o[c] = P[c] + 1e-4 * N[c];
    r[c] = L[c] - o[c];
  }
  for (int k = 0; k < s->count; ++k)
  {
    double t0, t1;
    int a0, a1;
    if (ray_box(o, r, s->boxes + k, &t0, &a0, &t1, &a1) && t0 < t1 && t1 > 0.0 && t0 < 1.0)
    {
      return 0;
    }
  }
  return 1;
}

/* A voxel view over a fresh buffer. */
typedef struct test_view
{
  mrgi_voxel_view view;
  uint32_t* voxels;
} test_view;

static test_view make_sliced_view(int32_t width, int32_t height, int32_t slices, double near_depth,
  double far_depth, const mrgi_voxel_projection* projection)
{
  test_view t;
  mrgi_error err;
  memset(&t, 0, sizeof(t));
  MRGI_CHECK(mrgi_voxel_grid_init(
               &t.view.grid, width, height, slices, near_depth, far_depth, &err) == MRGI_OK);
  t.view.projection = *projection;
  mrgi_voxel_march_params_default(&t.view.params);
  t.view.voxel_words = mrgi_voxel_buffer_words(&t.view.grid);
  t.voxels = (uint32_t*)calloc(t.view.voxel_words, sizeof(uint32_t));
  MRGI_CHECK(t.voxels != NULL);
  t.view.voxels = t.voxels;
  return t;
}

static test_view make_view(int32_t width, int32_t height, double near_depth, double far_depth,
  const mrgi_voxel_projection* projection)
{
  return make_sliced_view(
    width, height, MRGI_VOXEL_DEFAULT_SLICES, near_depth, far_depth, projection);
}

static mrgi_voxel_projection perspective_projection(double angle_deg, double aspect)
{
  mrgi_multires_projection camera = { 0, angle_deg, 1.0 };
  mrgi_voxel_projection p;
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &camera, aspect, NULL) == MRGI_OK);
  return p;
}

/* ---- 1. bit layout, slicing, mapping, projection ---- */
static void test_layout(void)
{
  mrgi_error err;
  const double ranges[3][2] = { { 2.0, 30.0 }, { -5.0, 3.0 }, { 0.1, 1000.0 } };
  for (int r = 0; r < 3; ++r)
  {
    mrgi_voxel_grid g;
    MRGI_CHECK(mrgi_voxel_grid_init(&g, 128, 64, MRGI_VOXEL_DEFAULT_SLICES, ranges[r][0],
                 ranges[r][1], &err) == MRGI_OK);
    MRGI_CHECK(mrgi_voxel_grid_check(&g, &err) == MRGI_OK);
    MRGI_CHECK(mrgi_voxel_buffer_words(&g) == 128 * 64 * 4);
    MRGI_CHECK(mrgi_voxel_slice(&g, g.near_depth) == 0);
    MRGI_CHECK(mrgi_voxel_slice(&g, g.far_depth) == 127);
    MRGI_CHECK(mrgi_voxel_slice(&g, g.near_depth - 1.0f) == 0);
    MRGI_CHECK(mrgi_voxel_slice(&g, g.far_depth + 1.0f) == 127);
    MRGI_CHECK(mrgi_voxel_slice(&g, -INFINITY) == 0 && mrgi_voxel_slice(&g, INFINITY) == 127);
    MRGI_CHECK(mrgi_voxel_slice(&g, NAN) == 0);
    const double thickness = 1.0 / g.slice_scale;
    for (int32_t s = 0; s < MRGI_VOXEL_LAYER_SLICES; ++s)
    {
      /* round trip slice -> depth -> slice, and slice -> (channel, bit) -> slice */
      MRGI_CHECK(mrgi_voxel_slice(&g, (float)mrgi_voxel_slice_center(&g, s)) == s);
      const int32_t c = mrgi_voxel_slice_channel(s);
      const int32_t b = mrgi_voxel_slice_bit(s);
      MRGI_CHECK(c >= 0 && c < MRGI_VOXEL_CHANNELS && b >= 0 && b < 32);
      MRGI_CHECK(c * MRGI_VOXEL_CHANNEL_BITS + b == s);
      uint32_t m[4];
      mrgi_voxel_range_mask(s, s, m);
      for (int k = 0; k < 4; ++k)
      {
        MRGI_CHECK(m[k] == (k == c ? 1u << b : 0u));
      }
      /* just inside either end of the slice */
      const double lo = g.near_depth + s * thickness;
      MRGI_CHECK(mrgi_voxel_slice(&g, (float)(lo + 0.01 * thickness)) == s);
      MRGI_CHECK(mrgi_voxel_slice(&g, (float)(lo + 0.99 * thickness)) == s);
    }
  }
  /* slice 0 = R bit 0, slice 127 = A bit 31, 31|32 straddle R and G */
  uint32_t m[4];
  mrgi_voxel_range_mask(0, 127, m);
  MRGI_CHECK(m[0] == 0xFFFFFFFFu && m[1] == 0xFFFFFFFFu && m[2] == 0xFFFFFFFFu &&
             m[3] == 0xFFFFFFFFu);
  mrgi_voxel_range_mask(31, 32, m);
  MRGI_CHECK(m[0] == 0x80000000u && m[1] == 1u && m[2] == 0u && m[3] == 0u);
  mrgi_voxel_range_mask(127, 127, m);
  MRGI_CHECK(m[3] == 0x80000000u && m[0] == 0u);
  /* every (lo, hi) against a bit-by-bit reference, clamping included */
  for (int32_t lo = -3; lo <= 131; ++lo)
  {
    for (int32_t hi = -3; hi <= 131; ++hi)
    {
      uint32_t ref[4] = { 0, 0, 0, 0 };
      for (int32_t s = 0; s < 128; ++s)
      {
        if (s >= lo && s <= hi)
        {
          ref[s >> 5] |= 1u << (s & 31);
        }
      }
      mrgi_voxel_range_mask(lo, hi, m);
      MRGI_CHECK(memcmp(m, ref, sizeof(ref)) == 0);
    }
  }

  /* window -> voxel pixel mapping */
  for (int32_t x = 0; x < 1024; ++x)
  {
    MRGI_CHECK(mrgi_voxel_pixel_from_window(x, 1024, 128) == x / 8);
    MRGI_CHECK(mrgi_voxel_pixel_from_window(x, 1024, 1024) == x);
  }
  const int32_t windows[4] = { 1000, 100, 1920, 7 };
  const int32_t voxels[4] = { 128, 128, 256, 3 };
  for (int k = 0; k < 4; ++k)
  {
    int32_t counts[256];
    memset(counts, 0, sizeof(counts));
    int32_t previous = -1;
    for (int32_t x = 0; x < windows[k]; ++x)
    {
      const int32_t v = mrgi_voxel_pixel_from_window(x, windows[k], voxels[k]);
      MRGI_CHECK(v >= 0 && v < voxels[k] && v >= previous);
      if (voxels[k] > windows[k])
      {
        MRGI_CHECK(v > previous); /* upsampling: injective */
      }
      previous = v;
      ++counts[v];
      /* the integer rule is floor((x + 0.5) V / W) */
      MRGI_CHECK(v == (int32_t)floor((x + 0.5) * voxels[k] / windows[k]));
    }
    if (voxels[k] <= windows[k])
    {
      for (int32_t v = 0; v < voxels[k]; ++v)
      {
        MRGI_CHECK(counts[v] == windows[k] / voxels[k] || counts[v] == (windows[k] + voxels[k] - 1) / voxels[k]);
      }
    }
  }
  MRGI_CHECK(mrgi_voxel_pixel_from_window(MRGI_VOXEL_MAX_SIZE - 1, MRGI_VOXEL_MAX_SIZE,
                                          MRGI_VOXEL_MAX_SIZE) == MRGI_VOXEL_MAX_SIZE - 1);

  /* projection: a point on the view ray of window pixel x lands in voxel pixel
   * mrgi_voxel_pixel_from_window(x) (both projections, non-square window) */
  const int32_t W = 640, H = 480, VW = 128, VH = 96;
  mrgi_multires_projection cams[2] = { { 0, 40.0, 1.0 }, { 1, 30.0, 3.5 } };
  for (int c = 0; c < 2; ++c)
  {
    mrgi_voxel_projection p;
    MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, cams + c, (double)W / H, &err) == MRGI_OK);
    mrgi_voxel_grid g;
    MRGI_CHECK(
      mrgi_voxel_grid_init(&g, VW, VH, MRGI_VOXEL_DEFAULT_SLICES, 1.0, 50.0, &err) == MRGI_OK);
    int mismatches = 0;
    for (int32_t y = 0; y < H; y += 7)
    {
      for (int32_t x = 0; x < W; x += 5)
      {
        double o[3], r[3];
        view_ray(&p, (2.0 * x + 1.0) / W - 1.0, (2.0 * y + 1.0) / H - 1.0, o, r);
        const double d = 3.0 + 0.1 * x;
        const float point[3] = { (float)(o[0] + d * r[0]), (float)(o[1] + d * r[1]),
                                 (float)(o[2] + d * r[2]) };
        float uvd[3];
        MRGI_CHECK(mrgi_voxel_project(&g, &p, point, uvd) == 1);
        MRGI_CHECK_NEAR(uvd[2], d, 1e-4 * d);
        mismatches += (int32_t)floorf(uvd[0]) != mrgi_voxel_pixel_from_window(x, W, VW);
        mismatches += (int32_t)floorf(uvd[1]) != mrgi_voxel_pixel_from_window(y, H, VH);
      }
    }
    MRGI_CHECK(mismatches == 0);
  }
  /* projection from an OpenGL matrix: perspective (off-centre) and parallel */
  {
    const double n = 1.0, f = 100.0, l = -0.6, rr = 0.4, b = -0.5, t = 0.5;
    double pm[16] = { 0 };
    pm[0] = 2 * n / (rr - l);
    pm[5] = 2 * n / (t - b);
    pm[8] = (rr + l) / (rr - l);
    pm[9] = (t + b) / (t - b);
    pm[10] = -(f + n) / (f - n);
    pm[11] = -1.0;
    pm[14] = -2 * f * n / (f - n);
    mrgi_voxel_projection p;
    MRGI_CHECK(mrgi_voxel_projection_from_matrix(&p, pm, &err) == MRGI_OK);
    MRGI_CHECK(p.parallel == 0);
    /* the frustum's left edge maps to ndc x = -1, its top edge to ndc y = +1 */
    MRGI_CHECK_NEAR(p.scale_x * l / n + p.offset_x, -1.0, 1e-6);
    MRGI_CHECK_NEAR(p.scale_y * t / n + p.offset_y, 1.0, 1e-6);
    double q[16] = { 0 };
    q[0] = 0.5;
    q[5] = 0.25;
    q[10] = -0.1;
    q[12] = 0.2;
    q[13] = -0.3;
    q[15] = 1.0;
    MRGI_CHECK(mrgi_voxel_projection_from_matrix(&p, q, &err) == MRGI_OK);
    MRGI_CHECK(p.parallel == 1 && p.scale_x == 0.5f && p.offset_x == 0.2f && p.offset_y == -0.3f);
    q[15] = 0.5;
    MRGI_CHECK(mrgi_voxel_projection_from_matrix(&p, q, &err) == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(strstr(err.message, "last row") != NULL);
    q[15] = 1.0;
    q[0] = -0.5;
    MRGI_CHECK(mrgi_voxel_projection_from_matrix(&p, q, &err) == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(strstr(err.message, "scales") != NULL);
  }
  /* voxel size: the larger of the pixel's eye-space width and height and the slice */
  {
    mrgi_voxel_view v;
    memset(&v, 0, sizeof(v));
    MRGI_CHECK(mrgi_voxel_grid_init(&v.grid, 100, 50, MRGI_VOXEL_DEFAULT_SLICES, 2.0, 66.0, &err) ==
      MRGI_OK);                                                                  /* slice 0.5 */
    v.projection = perspective_projection(90.0, 2.0);                            /* sx 0.5, sy 1 */
    MRGI_CHECK_NEAR(mrgi_voxel_size_at(&v, 10.0f), 0.5, 1e-6);  /* pixel 0.4 x 0.4 < slice */
    MRGI_CHECK_NEAR(mrgi_voxel_size_at(&v, 40.0f), 1.6, 1e-5);  /* 2 * 40 / (0.5 * 100) */
    MRGI_CHECK_NEAR(mrgi_voxel_size_at(&v, -40.0f), 1.6, 1e-5); /* behind the eye: |d| */
    v.projection.parallel = 1;
    MRGI_CHECK_NEAR(mrgi_voxel_size_at(&v, 40.0f), 0.5, 1e-6);  /* 2 / 50 < slice */
  }
  /* behind the eye */
  {
    mrgi_voxel_grid g;
    MRGI_CHECK(
      mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 1.0, 2.0, &err) == MRGI_OK);
    const mrgi_voxel_projection p = perspective_projection(60.0, 1.0);
    const float behind[3] = { 0.0f, 0.0f, 1.0f };
    float uvd[3];
    MRGI_CHECK(mrgi_voxel_project(&g, &p, behind, uvd) == 0 && uvd[2] == -1.0f);
  }
}

static void test_grid_errors(void)
{
  mrgi_error err;
  mrgi_voxel_grid g;
  MRGI_CHECK(mrgi_voxel_grid_init(NULL, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 1.0, 2.0, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  const int32_t sizes[4][2] = { { 0, 8 }, { 8, 0 }, { -1, 8 }, { MRGI_VOXEL_MAX_SIZE + 1, 8 } };
  for (int k = 0; k < 4; ++k)
  {
    MRGI_CHECK(mrgi_voxel_grid_init(&g, sizes[k][0], sizes[k][1], MRGI_VOXEL_DEFAULT_SLICES, 1.0,
                 2.0, &err) == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(strstr(err.message, "outside") != NULL);
    MRGI_CHECK(g.width == 0); /* zeroed on failure */
  }
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 3.0, 3.0, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "empty") != NULL);
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 1e30, 1e30 + 1.0, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "empty") != NULL); /* equal as floats */
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 5.0, 2.0, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "reversed") != NULL);
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, NAN, 2.0, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "not finite") != NULL);
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 1.0, INFINITY, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 1.0, 1e39, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, 0.0, 1e-40, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "slice scale") != NULL);
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 8, 8, MRGI_VOXEL_DEFAULT_SLICES, -3e38, 3e38, &err) ==
    MRGI_OK); /* wide but fine */
  MRGI_CHECK(mrgi_voxel_grid_init(&g, 1, 1, MRGI_VOXEL_DEFAULT_SLICES, 1.0, 2.0, &err) == MRGI_OK);
  g.slice_scale *= 2.0f;
  MRGI_CHECK(mrgi_voxel_grid_check(&g, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "modified") != NULL);
  MRGI_CHECK(mrgi_voxel_buffer_words(NULL) == 0);

  mrgi_voxel_projection p;
  mrgi_multires_projection cam = { 0, 180.0, 1.0 };
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &cam, 1.0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "view angle") != NULL);
  cam.view_angle_deg = 30.0;
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &cam, 0.0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "aspect") != NULL);
  cam.parallel = 1;
  cam.parallel_scale = -1.0;
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &cam, 1.0, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "parallel scale") != NULL);
  p = perspective_projection(30.0, 1.0);
  p.parallel = 2;
  MRGI_CHECK(mrgi_voxel_projection_check(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.parallel = 0;
  p.offset_y = NAN;
  MRGI_CHECK(mrgi_voxel_projection_check(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "offsets") != NULL);
}

/* ---- 2. voxelization ---- */
static void test_voxelize(void)
{
  mrgi_error err;
  mrgi_voxel_grid g;
  /* 4 x 2 voxels, depth 0..128: slice = floor(d) */
  MRGI_CHECK(
    mrgi_voxel_grid_init(&g, 4, 2, MRGI_VOXEL_DEFAULT_SLICES, 0.0, 128.0, &err) == MRGI_OK);
  MRGI_CHECK(g.slice_scale == 1.0f);
  uint32_t v[32];
  memset(v, 0xAB, sizeof(v));
  MRGI_CHECK(mrgi_voxel_clear(&g, v, 31, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "needs 32") != NULL);
  MRGI_CHECK(mrgi_voxel_clear(&g, v, 32, &err) == MRGI_OK);
  for (int k = 0; k < 32; ++k)
  {
    MRGI_CHECK(v[k] == 0u);
  }
  const float lo = -FLT_MAX, hi = FLT_MAX; /* no primitive clamp */
  const mrgi_voxel_fragment frags[] = {
    { 0, 0, 0.5f, 0.0f, lo, hi },      /* slice 0: R bit 0 */
    { 0, 0, 5.2f, NAN, lo, hi },       /* OR-ed: R bit 5 (NaN span = one bit) */
    { 1, 0, 31.5f, 1.0f, lo, hi },     /* slices 30..32 */
    { 2, 1, 127.9f, 0.0f, lo, hi },    /* A bit 31 */
    { 3, 1, 128.0f, 0.0f, lo, hi },    /* d == far: kept, slice 127 */
    { 3, 1, 128.5f, 0.0f, lo, hi },    /* beyond far: clipped */
    { 0, 1, -0.1f, 5.0f, lo, hi },     /* before near: clipped although its span reaches in */
    { 1, 1, NAN, 0.0f, lo, hi },       /* not a depth: clipped */
    { 2, 0, 64.0f, 1000.0f, lo, hi },  /* span over the whole range, clamped: all bits */
    { 3, 0, 1.0f, -2.0f, lo, hi },     /* negative span = one bit */
    { 1, 1, 40.5f, 10.0f, 38.2f, 41.7f }, /* span clamped to the primitive: slices 38..41 */
    { 1, 1, 70.5f, 0.0f, 71.0f, 80.0f },  /* centre outside [dmin, dmax] by rounding: kept */
  };
  mrgi_voxel_info info;
  MRGI_CHECK(mrgi_voxel_voxelize(&g, frags, sizeof(frags) / sizeof(frags[0]), v, 32, &info, &err) ==
             MRGI_OK);
  MRGI_CHECK(info.fragments_written == 9 && info.fragments_clipped == 3);
  const uint32_t* t;
  t = v + mrgi_voxel_index(&g, 0, 0);
  MRGI_CHECK(t[0] == ((1u << 0) | (1u << 5)) && t[1] == 0 && t[2] == 0 && t[3] == 0);
  t = v + mrgi_voxel_index(&g, 1, 0);
  MRGI_CHECK(t[0] == 0xC0000000u && t[1] == 1u && t[2] == 0 && t[3] == 0);
  t = v + mrgi_voxel_index(&g, 2, 1);
  MRGI_CHECK(t[0] == 0 && t[3] == 0x80000000u);
  t = v + mrgi_voxel_index(&g, 3, 1);
  MRGI_CHECK(t[0] == 0 && t[1] == 0 && t[2] == 0 && t[3] == 0x80000000u);
  t = v + mrgi_voxel_index(&g, 0, 1);
  MRGI_CHECK((t[0] | t[1] | t[2] | t[3]) == 0u);
  t = v + mrgi_voxel_index(&g, 1, 1);
  MRGI_CHECK(t[0] == 0u && t[1] == (0xFu << 6) && t[2] == (1u << 6) && t[3] == 0u);
  t = v + mrgi_voxel_index(&g, 2, 0);
  MRGI_CHECK((t[0] & t[1] & t[2] & t[3]) == 0xFFFFFFFFu);
  t = v + mrgi_voxel_index(&g, 3, 0);
  MRGI_CHECK(t[0] == 2u && t[1] == 0);
  /* a fragment outside the grid: error, buffer untouched */
  uint32_t copy[32];
  memcpy(copy, v, sizeof(v));
  const mrgi_voxel_fragment bad[2] = { { 0, 0, 9.0f, 0.0f, lo, hi }, { 4, 0, 1.0f, 0.0f, lo, hi } };
  MRGI_CHECK(mrgi_voxel_voxelize(&g, bad, 2, v, 32, &info, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "fragment 1") != NULL);
  MRGI_CHECK(memcmp(copy, v, sizeof(v)) == 0);
  MRGI_CHECK(mrgi_voxel_voxelize(&g, NULL, 1, v, 32, &info, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_voxelize(&g, NULL, 0, v, 32, &info, &err) == MRGI_OK);
  MRGI_CHECK(info.fragments_written == 0);

  /* Depth buffer 8 x 4 -> 4 x 2 voxels (2 x 2 window pixels per voxel pixel):
   * columns 0..3 are the plane d = 10 + x, columns 4..7 the plane d = 60 + x
   * (a silhouette between x = 3 and 4), pixel (6, 3) is background. */
  float depth[32];
  for (int32_t y = 0; y < 4; ++y)
  {
    for (int32_t x = 0; x < 8; ++x)
    {
      depth[y * 8 + x] = (float)(x < 4 ? 10 + x : 60 + x);
    }
  }
  depth[3 * 8 + 6] = NAN;
  for (int conservative = 0; conservative <= 1; ++conservative)
  {
    MRGI_CHECK(mrgi_voxel_clear(&g, v, 32, &err) == MRGI_OK);
    MRGI_CHECK(mrgi_voxel_voxelize_depth(&g, depth, 8, 4, conservative, v, 32, &info, &err) ==
               MRGI_OK);
    MRGI_CHECK(info.fragments_written == 31 && info.fragments_clipped == 0);
    for (int32_t vy = 0; vy < 2; ++vy)
    {
      for (int32_t vx = 0; vx < 4; ++vx)
      {
        uint32_t expected[4] = { 0, 0, 0, 0 };
        for (int32_t y = 2 * vy; y < 2 * vy + 2; ++y)
        {
          for (int32_t x = 2 * vx; x < 2 * vx + 2; ++x)
          {
            const float d = depth[y * 8 + x];
            if (!isfinite(d))
            {
              continue;
            }
            /* gx = 1 on both planes (the one-sided rule picks the same
             * surface at the silhouette), gy = 0; (5, 3) keeps gx = 1 from
             * its left neighbour, (7, 3) has no neighbour in x holding a
             * depth: gx = 0, one bit */
            float h = conservative ? 0.5f : 0.0f;
            if (y == 3 && x == 7)
            {
              h = 0.0f;
            }
            for (int32_t s = (int32_t)floorf(d - h); s <= (int32_t)floorf(d + h); ++s)
            {
              expected[s >> 5] |= 1u << (s & 31);
            }
          }
        }
        MRGI_CHECK(memcmp(v + mrgi_voxel_index(&g, vx, vy), expected, sizeof(expected)) == 0);
      }
    }
  }
  /* bridging check: at the silhouette the conservative span stays 1 slice
   * wide (no bits between the two surfaces at 13..64) */
  t = v + mrgi_voxel_index(&g, 1, 0);
  MRGI_CHECK(t[1] == 0u);                   /* slices 32..63 empty */
  MRGI_CHECK((t[0] & 0xFFFF0000u) == 0u);   /* nothing from 16 to 31 */
  MRGI_CHECK(mrgi_voxel_voxelize_depth(&g, depth, 8, 4, 2, v, 32, &info, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "conservative") != NULL);
  MRGI_CHECK(mrgi_voxel_voxelize_depth(&g, depth, 0, 4, 1, v, 32, &info, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_voxelize_depth(&g, NULL, 8, 4, 1, v, 32, &info, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
}

/* ---- 3. the ray march on constructed scenes ---- */

/* A standard perspective setup: 50 degree camera, square window, voxel
 * buffer `res`^2 over depths [3, 31]. */
static test_view sliced_scene_view(const scene* s, int32_t res, int32_t slices)
{
  const mrgi_voxel_projection p = perspective_projection(50.0, 1.0);
  test_view t = make_sliced_view(res, res, slices, 3.0, 31.0, &p);
  voxelize_scene(s, &t.view.grid, &p, t.voxels, t.view.voxel_words);
  return t;
}

static test_view scene_view(const scene* s, int32_t res)
{
  return sliced_scene_view(s, res, MRGI_VOXEL_DEFAULT_SLICES);
}

/* The offset's direction (mrgi_voxel_march_params::offset_along_ray): a
 * receiver on a wall facing the camera (normal +z) under a slab standing in
 * front of the wall, lights above and in front. Rays from the wall climb
 * past the slab's back edge; an offset along the normal moves them forward,
 * into the slab's voxels (cornell-area's corner behind the tall block), an
 * offset along the ray does not move them. */
static void test_march_offset_direction(void)
{
  mrgi_error err;
  scene s = { 0 };
  scene_add(&s, -6, -3, -12.3, 6, 3, -12);       /* the wall, front face z = -12 */
  scene_add(&s, -3, -0.6, -10.8, 3, -0.4, -8.5); /* the slab, back edge 1.2 in front of it */
  test_view t = scene_view(&s, 64);
  const float wall_n[3] = { 0, 0, 1 };
  const float down[3] = { 0, -1, 0 };
  int32_t false_hidden[3] = { 0, 0, 0 }, false_visible[3] = { 0, 0, 0 }, visible = 0, rays = 0;
  for (int32_t mode = MRGI_VOXEL_OFFSET_NORMALS; mode <= MRGI_VOXEL_OFFSET_RAY_AT_BOTH; ++mode)
  {
    t.view.params.offset_along_ray = mode;
    MRGI_CHECK(mrgi_voxel_view_check(&t.view, &err) == MRGI_OK);
    for (int32_t i = 0; i < 24 * 24; ++i)
    {
      const float P[3] = { -2.0f + 4.0f * (float)(i % 24) / 23.0f,
                           -2.8f + 2.0f * (float)(i / 24) / 23.0f, -12.0f };
      for (int32_t j = 0; j < 8 * 8; ++j)
      {
        const float L[3] = { -1.0f + 2.0f * (float)(j % 8) / 7.0f, 2.5f,
                             -11.8f + 3.8f * (float)(j / 8) / 7.0f };
        const int exact = exact_visible(&s, P, wall_n, L);
        const int marched = mrgi_voxel_march(&t.view, P, wall_n, L, down);
        false_hidden[mode] += exact && !marched;
        false_visible[mode] += !exact && marched;
        if (mode == 0)
        {
          visible += exact;
          ++rays;
        }
      }
    }
    printf("offset direction %d (0 normals, 1 ray at the receiver, 2 ray at both ends): of %d rays "
           "(%d visible) %d falsely hidden, %d falsely visible\n",
           (int)mode, (int)rays, (int)visible, (int)false_hidden[mode], (int)false_visible[mode]);
  }
  MRGI_CHECK(visible > rays / 10 && visible < rays - rays / 10);
  /* the normal offset hides penumbra rays that the ray offset keeps */
  MRGI_CHECK(false_hidden[0] > 100);
  MRGI_CHECK(2 * false_hidden[1] < false_hidden[0] && 2 * false_hidden[2] < false_hidden[0]);
  MRGI_CHECK(false_visible[1] <= false_visible[0] + rays / 100 &&
             false_visible[2] <= false_visible[0] + rays / 100);
  t.view.params.offset_along_ray = 3;
  MRGI_CHECK(mrgi_voxel_view_check(&t.view, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "offset_along_ray") != NULL);
  free(t.voxels);
}

static void test_march_walls(void)
{
  mrgi_error err;
  scene s = { 0 };
  scene_add(&s, -12, -2.5, -30, 12, -2, -3); /* floor, top at y = -2 */
  const float floor_n[3] = { 0, 1, 0 };
  const float P[3] = { 0.0f, -2.0f, -10.0f };
  const float L[3] = { 0.5f, 3.0f, -10.5f };
  const float down[3] = { 0, -1, 0 };
  test_view t = scene_view(&s, 128);
  MRGI_CHECK(mrgi_voxel_view_check(&t.view, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, floor_n, L, down) == 1);
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, floor_n, L, NULL) == 1);
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, NULL, L, NULL) == 1);
  free(t.voxels);

  /* a horizontal slab between them */
  scene_add(&s, -2, 0.5, -12, 2, 0.8, -8);
  t = scene_view(&s, 128);
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, floor_n, L, down) == 0);
  MRGI_CHECK(mrgi_voxel_march(&t.view, L, down, P, floor_n) == 0); /* reversed */
  MRGI_CHECK(mrgi_voxel_march_occluder_fraction(&t.view, P, floor_n, L, down) < 1.0f);
  free(t.voxels);

  /* a wall facing the camera between a floor point and a light behind it */
  s.count = 1;
  scene_add(&s, -2.0, -2.0, -10.15, 2.0, 1.0, -9.85);
  t = scene_view(&s, 128);
  const float F[3] = { 0.0f, -2.0f, -7.0f };
  const float G[3] = { 0.3f, 0.5f, -13.0f };
  MRGI_CHECK(exact_visible(&s, F, floor_n, G) == 0);
  MRGI_CHECK(mrgi_voxel_march(&t.view, F, floor_n, G, NULL) == 0);
  const float G2[3] = { 0.3f, 6.0f, -13.0f }; /* over the wall (y = 2 at the wall) */
  MRGI_CHECK(exact_visible(&s, F, floor_n, G2) == 1);
  MRGI_CHECK(mrgi_voxel_march(&t.view, F, floor_n, G2, NULL) == 1);
  free(t.voxels);

  /* a vertical wall seen obliquely (x = 3: its side faces cover ~16 pixels) */
  s.count = 1;
  scene_add(&s, 2.85, -2.0, -12.0, 3.15, 1.0, -8.0);
  t = scene_view(&s, 128);
  const float A[3] = { 0.5f, -2.0f, -10.0f };
  const float B[3] = { 5.5f, 0.5f, -10.0f };
  MRGI_CHECK(exact_visible(&s, A, floor_n, B) == 0);
  MRGI_CHECK(mrgi_voxel_march(&t.view, A, floor_n, B, NULL) == 0);
  const float C[3] = { 5.5f, 5.0f, -10.0f }; /* over the wall */
  MRGI_CHECK(exact_visible(&s, A, floor_n, C) == 1);
  MRGI_CHECK(mrgi_voxel_march(&t.view, A, floor_n, C, NULL) == 1);
  free(t.voxels);

  /* Known limitation (documented in mrgi_voxel.h): the same wall seen
   * edge-on (x = 0) is 0.3 voxel pixels wide per face; OR-ed surface
   * voxels only exist where a face covers a pixel centre, so a ray crossing
   * between its front and back faces at mid depth is not stopped. */
  s.count = 1;
  scene_add(&s, -0.15, -2.0, -12.0, 0.15, 1.0, -8.0);
  t = scene_view(&s, 128);
  const float A2[3] = { -3.0f, -2.0f, -10.0f };
  const float B2[3] = { 3.0f, 0.5f, -10.0f };
  MRGI_CHECK(exact_visible(&s, A2, floor_n, B2) == 0);
  printf("edge-on wall 0.3 voxel pixels wide, crossed at mid depth: march says %s (exact: "
         "occluded)\n",
         mrgi_voxel_march(&t.view, A2, floor_n, B2, NULL) ? "visible" : "occluded");
  free(t.voxels);
}

/* A wall thinner than one slice, crossed steeply in depth: the step's depth
 * interval catches it where the slice at the step's middle alone does not. */
static void test_march_thin_wall(void)
{
  scene s = { 0 };
  const mrgi_voxel_projection p = perspective_projection(50.0, 1.0);
  test_view t = make_view(128, 128, 2.0, 20.0, &p);
  const double thickness = 1.0 / t.view.grid.slice_scale; /* 0.140625 */
  const double z0 = -(2.0 + 60.5 * thickness);              /* inside slice 60 */
  scene_add(&s, -5, -5, z0 - 0.3 * thickness, 5, 5, z0);
  voxelize_scene(&s, &t.view.grid, &p, t.voxels, t.view.voxel_words);
  /* the wall occupies exactly one slice */
  const uint32_t* centre = t.voxels + mrgi_voxel_index(&t.view.grid, 64, 64);
  MRGI_CHECK(centre[0] == 0 && centre[1] == (1u << 28) && centre[2] == 0 && centre[3] == 0);

  t.view.params.normal_offset = 0.0f; /* the ends lie in empty space */
  t.view.params.skip_radius = 0;
  const float P[3] = { 0.0f, 0.0f, -12.0f };
  const float L[3] = { 0.3f, 0.1f, -4.5f };
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, NULL, L, NULL) == 0);
  /* how a single-slice test would have done: the slices at the step middles */
  float a[3], b[3];
  MRGI_CHECK(mrgi_voxel_project(&t.view.grid, &p, P, a) && mrgi_voxel_project(&t.view.grid, &p, L, b));
  const int32_t n = (int32_t)ceilf(fmaxf(fabsf(b[0] - a[0]), fabsf(b[1] - a[1])));
  MRGI_CHECK(n >= 2 && n < 64);
  int hit_by_point = 0;
  for (int32_t k = 0; k < n; ++k)
  {
    const float sm = ((float)k + 0.5f) / (float)n;
    const float d = 1.0f / (1.0f / a[2] + (1.0f / b[2] - 1.0f / a[2]) * sm);
    hit_by_point |= mrgi_voxel_slice(&t.view.grid, d) == 60;
  }
  MRGI_CHECK(!hit_by_point);
  printf("thin wall: 1 slice thick, crossed in %d steps of ~%.1f slices: caught by the interval "
         "mask, missed by single-slice sampling\n",
         n, (fabs(P[2] - L[2]) / n) / thickness);
  /* no wall: visible */
  memset(t.voxels, 0, t.view.voxel_words * sizeof(uint32_t));
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, NULL, L, NULL) == 1);
  free(t.voxels);
}

/* Receivers on a plane, lights at grazing elevations: the bias must prevent
 * every self-shadow; without it there are many. Returns self-shadowed rays. */
static int64_t grazing_floor(double tilt_deg, int32_t res, int32_t window, float normal_offset,
                             int32_t skip_radius, int64_t* rays)
{
  const mrgi_voxel_projection p = perspective_projection(50.0, 1.0);
  test_view t = make_view(res, res, 2.0, 40.0, &p);
  t.view.params.normal_offset = normal_offset;
  t.view.params.skip_radius = skip_radius;
  const double phi = tilt_deg * MRGI_PI / 180.0;
  const double n[3] = { 0.0, cos(phi), sin(phi) };
  const double Q[3] = { 0.0, -1.5, -8.0 };
  const double nQ = n[0] * Q[0] + n[1] * Q[1] + n[2] * Q[2];
  float* depth = (float*)malloc(sizeof(float) * (size_t)window * (size_t)window);
  MRGI_CHECK(depth != NULL);
  for (int32_t y = 0; y < window; ++y)
  {
    for (int32_t x = 0; x < window; ++x)
    {
      double o[3], r[3];
      view_ray(&p, (2.0 * x + 1.0) / window - 1.0, (2.0 * y + 1.0) / window - 1.0, o, r);
      const double d = (nQ - (n[0] * o[0] + n[1] * o[1] + n[2] * o[2])) /
                       (n[0] * r[0] + n[1] * r[1] + n[2] * r[2]);
      depth[(size_t)y * (size_t)window + (size_t)x] = d > 2.0 && d < 40.0 ? (float)d : NAN;
    }
  }
  mrgi_error err;
  MRGI_CHECK(mrgi_voxel_voxelize_depth(&t.view.grid, depth, window, window, 1, t.voxels,
                                       t.view.voxel_words, NULL, &err) == MRGI_OK);
  /* tangent frame */
  const double t1[3] = { 1.0, 0.0, 0.0 };
  const double t2[3] = { n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                         n[0] * t1[1] - n[1] * t1[0] };
  const float nf[3] = { (float)n[0], (float)n[1], (float)n[2] };
  const double elevations[7] = { 1, 2, 5, 10, 20, 45, 80 };
  int64_t shadowed = 0;
  *rays = 0;
  for (int32_t y = 3; y < window; y += window / 24)
  {
    for (int32_t x = 5; x < window; x += window / 24)
    {
      const float d = depth[(size_t)y * (size_t)window + (size_t)x];
      if (!isfinite(d))
      {
        continue;
      }
      double o[3], r[3];
      view_ray(&p, (2.0 * x + 1.0) / window - 1.0, (2.0 * y + 1.0) / window - 1.0, o, r);
      const float P[3] = { (float)(o[0] + d * r[0]), (float)(o[1] + d * r[1]),
                           (float)(o[2] + d * r[2]) };
      const double vs = mrgi_voxel_size_at(&t.view, d);
      for (int e = 0; e < 7; ++e)
      {
        const double th = elevations[e] * MRGI_PI / 180.0;
        /* The light sample at least 3 voxel sizes above the plane (at 1 degree
         * that is ~50 units away; the frustum clips the segment): a sample
         * hovering within a voxel of a surface lies in that surface's voxels
         * itself, which no receiver-side bias can fix. */
        const double R = fmax(4.0, 3.0 * vs / sin(th));
        for (int a = 0; a < 8; ++a)
        {
          const double psi = a * MRGI_PI / 4.0 + 0.1;
          float L[3];
          for (int c = 0; c < 3; ++c)
          {
            L[c] = (float)(P[c] + R * (cos(th) * (cos(psi) * t1[c] + sin(psi) * t2[c]) +
                                       sin(th) * n[c]));
          }
          shadowed += !mrgi_voxel_march(&t.view, P, nf, L, NULL);
          ++*rays;
        }
      }
    }
  }
  free(depth);
  free(t.voxels);
  return shadowed;
}

static void test_march_grazing(void)
{
  const double tilts[5] = { 0, 20, 45, 70, 90 };
  const int32_t res[2] = { 128, 512 };
  for (int r = 0; r < 2; ++r)
  {
    for (int k = 0; k < 5; ++k)
    {
      int64_t rays = 0;
      const int64_t biased = grazing_floor(tilts[k], res[r], 512, MRGI_VOXEL_DEFAULT_NORMAL_OFFSET,
                                           MRGI_VOXEL_DEFAULT_SKIP_RADIUS, &rays);
      int64_t rays_raw = 0;
      const int64_t raw = grazing_floor(tilts[k], res[r], 512, 0.0f, 0, &rays_raw);
      printf("grazing floor, plane tilt %2.0f deg, voxels %3d^2: self-shadowed %lld / %lld with "
             "the default bias, %lld without\n",
             tilts[k], res[r], (long long)biased, (long long)rays, (long long)raw);
      MRGI_CHECK(rays > 1000);
      MRGI_CHECK(biased == 0);
      MRGI_CHECK(raw > rays / 2); /* the test can fail: without bias the floor shadows itself */
    }
  }
}

static void test_march_extremes(void)
{
  mrgi_error err;
  scene s = { 0 };
  scene_add(&s, -12, -2.5, -30, 12, -2, -3);
  test_view t = scene_view(&s, 128);
  const float up[3] = { 0, 1, 0 };
  const float toward[3] = { 0, 0, 1 };

  /* zero-length segment: visible; below the horizon: occluded */
  const float P[3] = { 0.0f, -2.0f, -10.0f };
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, up, P, NULL) == 1);
  MRGI_CHECK(mrgi_voxel_march_occluder_fraction(&t.view, P, up, P, NULL) == 1.0f);
  const float below[3] = { 1.0f, -3.0f, -10.0f };
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, up, below, NULL) == 0);
  MRGI_CHECK(mrgi_voxel_march_occluder_fraction(&t.view, P, up, below, NULL) == 0.0f);
  const float above[3] = { 1.0f, 2.0f, -10.0f };
  const float light_up[3] = { 0, 1, 0 }; /* the light faces away from the receiver */
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, up, above, light_up) == 0);
  const float zero[3] = { 0, 0, 0 }; /* a zero normal means none */
  MRGI_CHECK(mrgi_voxel_march(&t.view, P, zero, above, zero) == 1);

  /* receiver exactly at the near plane (depth 3) on a surface facing +x */
  const float Pn[3] = { 0.2f, 0.1f, -3.0f };
  const float side[3] = { 1, 0, 0 };
  const float Ln[3] = { 1.5f, 0.5f, -6.0f };
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pn, side, Ln, NULL) == 1);
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pn, toward, Ln, NULL) == 0); /* behind its plane */
  const float Ln2[3] = { 1.0f, 0.5f, 2.0f }; /* light behind the camera too */
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pn, side, Ln2, NULL) == 1);
  free(t.voxels);
  scene_add(&s, -0.5, -0.5, -5.0, 3.0, 2.0, -4.6); /* a box between them */
  t = scene_view(&s, 128);
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pn, side, Ln, NULL) == 0);

  /* light sample behind the camera: the segment is clipped at the near plane */
  free(t.voxels);
  s.count = 1;
  t = scene_view(&s, 128);
  const float Pf[3] = { 0.0f, -2.0f, -12.0f };
  const float Lb[3] = { 0.0f, 1.0f, 4.0f };
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pf, up, Lb, NULL) == 1);
  free(t.voxels);
  scene_add(&s, -1.0, -1.5, -8.0, 1.0, 0.0, -7.0); /* on the segment, in front of the camera */
  t = scene_view(&s, 128);
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pf, up, Lb, NULL) == 0);
  MRGI_CHECK(mrgi_voxel_march(&t.view, Lb, NULL, Pf, up) == 0);
  free(t.voxels);

  /* segment leaving the screen: occluders off screen are unknown (visible),
   * occluders on the on-screen part are found */
  s.count = 1;
  const float Pe[3] = { -3.5f, -2.0f, -9.0f };   /* near the left edge (x/d = -0.39, edge 0.47) */
  const float Le[3] = { -14.0f, 2.0f, -9.0f };   /* far outside to the left */
  scene_add(&s, -11.0, -2.0, -10.0, -9.0, 3.0, -8.0); /* off screen, on the segment */
  t = scene_view(&s, 128);
  MRGI_CHECK(exact_visible(&s, Pe, up, Le) == 0); /* really occluded */
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pe, up, Le, NULL) == 1);
  free(t.voxels);
  scene_add(&s, -4.0, -2.0, -9.5, -3.8, 0.0, -8.5); /* on screen, on the segment */
  t = scene_view(&s, 128);
  MRGI_CHECK(mrgi_voxel_march(&t.view, Pe, up, Le, NULL) == 0);
  /* a segment entirely off screen, and one entirely beyond far */
  const float O1[3] = { -20.0f, 0.0f, -10.0f };
  const float O2[3] = { -25.0f, 3.0f, -10.0f };
  MRGI_CHECK(mrgi_voxel_march(&t.view, O1, NULL, O2, NULL) == 1);
  const float F1[3] = { 0.0f, 0.0f, -40.0f };
  const float F2[3] = { 0.0f, 3.0f, -45.0f };
  MRGI_CHECK(mrgi_voxel_march(&t.view, F1, NULL, F2, NULL) == 1);

  /* bad views */
  mrgi_voxel_view bad = t.view;
  bad.voxel_words -= 1;
  MRGI_CHECK(mrgi_voxel_view_check(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "needs") != NULL);
  bad = t.view;
  bad.voxels = NULL;
  MRGI_CHECK(mrgi_voxel_view_check(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  bad = t.view;
  bad.params.max_steps = 0;
  MRGI_CHECK(mrgi_voxel_view_check(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "max_steps") != NULL);
  bad = t.view;
  bad.params.normal_offset = NAN;
  MRGI_CHECK(mrgi_voxel_view_check(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "normal_offset") != NULL);
  bad = t.view;
  bad.params.skip_radius = MRGI_VOXEL_MAX_SKIP_RADIUS + 1;
  MRGI_CHECK(mrgi_voxel_view_check(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "skip_radius") != NULL);
  bad = t.view;
  MRGI_CHECK(mrgi_voxel_grid_init(
               &bad.grid, 128, 128, MRGI_VOXEL_DEFAULT_SLICES, -1.0, 31.0, &err) == MRGI_OK);
  bad.voxel_words = mrgi_voxel_buffer_words(&bad.grid);
  MRGI_CHECK(mrgi_voxel_view_check(&bad, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "near > 0") != NULL);
  bad.projection.parallel = 1; /* parallel projections accept it */
  MRGI_CHECK(mrgi_voxel_view_check(&bad, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_voxel_view_check(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  free(t.voxels);
}

/* Random box scenes on a floor with an area light above. */
static void random_scene(scene* s, int boxes)
{
  s->count = 0;
  scene_add(s, -12, -2.5, -30, 12, -2, -3);
  for (int k = 0; k < boxes; ++k)
  {
    const double cx = rng_range(-6.0, 6.0);
    const double cz = rng_range(-20.0, -7.0);
    const double sx = rng_range(0.2, 1.5);
    const double sz = rng_range(0.2, 1.5);
    const double y0 = rng_unit() < 0.3 ? rng_range(-1.0, 1.5) : -2.0; /* some float */
    scene_add(s, cx - sx, y0, cz - sz, cx + sx, y0 + rng_range(0.3, 2.5), cz + sz);
  }
}

/* 8 x 8 (count 64) or 16 x 16 samples on the quad x [-3, 3], z [-15, -9] at y = 5, facing down. */
static void light_samples(int side, float* position, float* normal)
{
  for (int j = 0; j < side * side; ++j)
  {
    position[3 * j + 0] = (float)(-3.0 + 6.0 * ((j % side) + 0.5) / side);
    position[3 * j + 1] = 5.0f;
    position[3 * j + 2] = (float)(-15.0 + 6.0 * ((j / side) + 0.5) / side);
    normal[3 * j + 0] = 0.0f;
    normal[3 * j + 1] = -1.0f;
    normal[3 * j + 2] = 0.0f;
  }
}

static void test_march_symmetry(void)
{
  const mrgi_voxel_projection p = perspective_projection(50.0, 1.0);
  int64_t pairs = 0, occluded = 0, asymmetric = 0, asymmetric_receiver_normal_only = 0;
  for (int trial = 0; trial < 6; ++trial)
  {
    scene s;
    random_scene(&s, 10);
    test_view t = scene_view(&s, 128);
    for (int k = 0; k < 12000; ++k)
    {
      float A[3], NA[3], B[3], NB[3];
      if (!scene_hit(&s, &p, rng_range(-1, 1), rng_range(-1, 1), A, NA) ||
          !scene_hit(&s, &p, rng_range(-1, 1), rng_range(-1, 1), B, NB))
      {
        continue;
      }
      const float D[3] = { B[0] - A[0], B[1] - A[1], B[2] - A[2] };
      if (D[0] * NA[0] + D[1] * NA[1] + D[2] * NA[2] <= 0.0f ||
          D[0] * NB[0] + D[1] * NB[1] + D[2] * NB[2] >= 0.0f)
      {
        continue; /* facing away: both directions stop at the horizon test */
      }
      const int ab = mrgi_voxel_march(&t.view, A, NA, B, NB);
      const int ba = mrgi_voxel_march(&t.view, B, NB, A, NA);
      asymmetric += ab != ba;
      occluded += !ab;
      /* the usual use: only the receiver end has a normal (offset at one end) */
      asymmetric_receiver_normal_only +=
        mrgi_voxel_march(&t.view, A, NA, B, NULL) != mrgi_voxel_march(&t.view, B, NB, A, NULL);
      ++pairs;
    }
    free(t.voxels);
  }
  const double fraction = (double)asymmetric / (double)pairs;
  printf("symmetry: %lld of %lld facing surface-to-surface rays (%.1f%% occluded) differ when "
         "reversed (%.4f%%); %.2f%% when only the receiver end has a normal\n",
         (long long)asymmetric, (long long)pairs, 100.0 * (double)occluded / (double)pairs,
         100.0 * fraction, 100.0 * (double)asymmetric_receiver_normal_only / (double)pairs);
  MRGI_CHECK(pairs > 5000);
  MRGI_CHECK(occluded > pairs / 20);
  MRGI_CHECK(fraction < 0.002);
}

/* ---- 4. incremental, interleaved, metric ---- */
static void test_masks_and_metric(void)
{
  MRGI_CHECK(mrgi_voxel_mask_words(1) == 1 && mrgi_voxel_mask_words(32) == 1 &&
             mrgi_voxel_mask_words(33) == 2 && mrgi_voxel_mask_words(4096) == 128);
  MRGI_CHECK(mrgi_voxel_phase_word_mask(1) == 0x11111111u);
  MRGI_CHECK(mrgi_voxel_phase_word_mask(5) == 0x55555555u);
  MRGI_CHECK(mrgi_voxel_phase_word_mask(MRGI_VOXEL_ALL_PHASES) == 0xFFFFFFFFu);
  MRGI_CHECK(mrgi_voxel_phase_word_mask(8) == 0x88888888u);
  MRGI_CHECK(mrgi_voxel_interleave_phase(0, 0) == 0 && mrgi_voxel_interleave_phase(1, 0) == 1 &&
             mrgi_voxel_interleave_phase(0, 1) == 2 && mrgi_voxel_interleave_phase(3, 5) == 3);
  for (int k = 0; k < 10000; ++k)
  {
    const uint32_t v = k < 3 ? (k == 0 ? 0u : (k == 1 ? 0xFFFFFFFFu : 0x80000001u)) : rng_u32();
    uint32_t ref = 0;
    for (int b = 0; b < 32; ++b)
    {
      ref += (v >> b) & 1u;
    }
    MRGI_CHECK(mrgi_voxel_popcount(v) == ref);
  }
  /* metric by hand: 40 samples (2 words) */
  const uint32_t m0[2] = { 0xFFFFFFFFu, 0xFFu };
  const uint32_t m1[2] = { 0xFFFFFFF0u, 0xFFu };  /* 4 fewer */
  const uint32_t m2[2] = { 0x0FFFFFFFu, 0x0Fu };  /* 8 fewer, others */
  const uint32_t* masks[9] = { m0, NULL, m1, NULL, m2, NULL, NULL, m0, NULL };
  mrgi_voxel_metric metric;
  mrgi_voxel_neighbourhood_metric(masks, 2, &metric);
  MRGI_CHECK(metric.masks == 4);
  MRGI_CHECK(metric.disagree == 4 + 4 + 4); /* bits 0-3, 28-31 of word 0, bits 4-7 of word 1 */
  MRGI_CHECK(metric.count_max == 40 && metric.count_min == 32);
  MRGI_CHECK(mrgi_voxel_needs_refinement(&metric, MRGI_VOXEL_METRIC_DISAGREE, 12) == 1);
  MRGI_CHECK(mrgi_voxel_needs_refinement(&metric, MRGI_VOXEL_METRIC_DISAGREE, 13) == 0);
  MRGI_CHECK(mrgi_voxel_needs_refinement(&metric, MRGI_VOXEL_METRIC_COUNT_SPREAD, 8) == 1);
  MRGI_CHECK(mrgi_voxel_needs_refinement(&metric, MRGI_VOXEL_METRIC_COUNT_SPREAD, 9) == 0);
  /* two masks that swap samples: equal counts, spread 0, disagreement 2 */
  const uint32_t s0[1] = { 1u };
  const uint32_t s1[1] = { 2u };
  const uint32_t* swap[9] = { s0, s1, NULL, NULL, NULL, NULL, NULL, NULL, NULL };
  mrgi_voxel_neighbourhood_metric(swap, 1, &metric);
  MRGI_CHECK(metric.disagree == 2 && metric.count_max - metric.count_min == 0);
  const uint32_t* none[9] = { NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL };
  mrgi_voxel_neighbourhood_metric(none, 1, &metric);
  MRGI_CHECK(metric.masks == 0 && metric.disagree == 0);
  MRGI_CHECK(mrgi_voxel_needs_refinement(&metric, MRGI_VOXEL_METRIC_DISAGREE, 0) == 1);
  MRGI_CHECK(mrgi_voxel_refine_threshold(0.5f, 256) == 128);
  MRGI_CHECK(mrgi_voxel_refine_threshold(0.001f, 64) == 1);
  MRGI_CHECK(mrgi_voxel_refine_threshold(0.0f, 64) == 0);
  MRGI_CHECK(mrgi_voxel_refine_threshold(1.5f, 64) == -1);
  MRGI_CHECK(mrgi_voxel_refine_threshold(NAN, 64) == -1);
  /* same-surface test of the interleaving */
  const float pa[3] = { 0.0f, -2.0f, -10.0f }, up[3] = { 0.0f, 2.0f, 0.0f };
  const float pb[3] = { 0.3f, -2.0f, -10.4f };   /* same floor */
  const float pc[3] = { 0.3f, -1.5f, -10.4f };   /* 0.5 above it: a step */
  const float tilted[3] = { 0.0f, 1.0f, 1.0f };  /* 45 degrees off */
  const float slight[3] = { 0.0f, 1.0f, 0.2f };  /* 11 degrees off */
  MRGI_CHECK(mrgi_voxel_same_surface(pa, up, pb, up) == 1);
  MRGI_CHECK(mrgi_voxel_same_surface(pa, up, pb, slight) == 1);
  MRGI_CHECK(mrgi_voxel_same_surface(pa, up, pc, up) == 0);
  MRGI_CHECK(mrgi_voxel_same_surface(pa, up, pb, tilted) == 0);
  MRGI_CHECK(mrgi_voxel_same_surface(pa, NULL, pb, up) == 0);
  const float down[3] = { 0.0f, -1.0f, 0.0f };
  MRGI_CHECK(mrgi_voxel_same_surface(pa, up, pb, down) == 0);
  /* interleave combination */
  const uint32_t q0[2] = { 0xFFFFFFFFu, 0x1u };
  const uint32_t q2[2] = { 0x44444444u, 0x0u };
  const uint32_t* quarters[4] = { q0, NULL, q2, NULL };
  uint32_t out[2];
  mrgi_voxel_interleave_combine(quarters, 2, out);
  MRGI_CHECK(out[0] == 0x55555555u && out[1] == 0x1u);
}

/* The G-buffer of a scene at W x H and its multires receivers. */
typedef struct pyramid_setup
{
  mrgi_multires_layout layout;
  float* position;
  float* normal;
  size_t floats;
} pyramid_setup;

static pyramid_setup make_pyramid(const scene* s, const mrgi_voxel_projection* p, int32_t size)
{
  pyramid_setup ps;
  mrgi_error err;
  MRGI_CHECK(mrgi_multires_layout_init(&ps.layout, size, size, 8, &err) == MRGI_OK);
  float* gpos = (float*)calloc((size_t)size * (size_t)size * 4, sizeof(float));
  float* gnor = (float*)calloc((size_t)size * (size_t)size * 4, sizeof(float));
  MRGI_CHECK(gpos && gnor);
  for (int32_t y = 0; y < size; ++y)
  {
    for (int32_t x = 0; x < size; ++x)
    {
      float P[3], N[3];
      const size_t k = 4 * ((size_t)y * (size_t)size + (size_t)x);
      if (scene_hit(s, p, (2.0 * x + 1.0) / size - 1.0, (2.0 * y + 1.0) / size - 1.0, P, N))
      {
        memcpy(gpos + k, P, sizeof(P));
        memcpy(gnor + k, N, sizeof(N));
        gpos[k + 3] = MRGI_GBUFFER_VALID;
      }
    }
  }
  const mrgi_gather_receivers view = { size, size, gpos, gnor };
  ps.floats = 4 * (size_t)mrgi_multires_texel_count(&ps.layout);
  ps.position = (float*)malloc(ps.floats * sizeof(float));
  ps.normal = (float*)malloc(ps.floats * sizeof(float));
  MRGI_CHECK(ps.position && ps.normal);
  MRGI_CHECK(mrgi_multires_receivers_build(&ps.layout, &view, ps.position, ps.normal, ps.floats,
                                           &err) == MRGI_OK);
  free(gpos);
  free(gnor);
  return ps;
}

static void free_pyramid(pyramid_setup* ps)
{
  free(ps->position);
  free(ps->normal);
}

/* Naive masks at every receiver texel (zero elsewhere). */
static uint32_t* naive_masks(const pyramid_setup* ps, const mrgi_voxel_view* view,
                             const mrgi_voxel_samples* samples)
{
  const size_t texels = (size_t)mrgi_multires_texel_count(&ps->layout);
  const int32_t words = mrgi_voxel_mask_words(samples->count);
  uint32_t* m = (uint32_t*)calloc(texels * (size_t)words, sizeof(uint32_t));
  MRGI_CHECK(m != NULL);
  for (size_t t = 0; t < texels; ++t)
  {
    if (ps->position[4 * t + 3] > MRGI_GBUFFER_VALID_THRESHOLD)
    {
      const float* n = ps->normal + 4 * t;
      mrgi_voxel_visibility(view, samples, ps->position + 4 * t,
                            (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f) ? n : NULL, NULL, 1,
                            MRGI_VOXEL_ALL_PHASES, m + t * (size_t)words);
    }
  }
  return m;
}

/* Fraction of sample bits that differ between two mask sets at the receiver texels of `level`. */
static double mask_difference(const pyramid_setup* ps, int32_t level, const uint32_t* a,
                              const uint32_t* b, int32_t count, int64_t* bits_out)
{
  const int32_t words = mrgi_voxel_mask_words(count);
  int64_t differ = 0, bits = 0;
  for (int32_t y = 0; y < ps->layout.level_height[level]; ++y)
  {
    for (int32_t x = 0; x < ps->layout.level_width[level]; ++x)
    {
      const size_t t = mrgi_multires_index(&ps->layout, level, x, y);
      if (!(ps->position[4 * t + 3] > MRGI_GBUFFER_VALID_THRESHOLD))
      {
        continue;
      }
      for (int32_t w = 0; w < words; ++w)
      {
        differ += mrgi_voxel_popcount(a[t * (size_t)words + (size_t)w] ^ b[t * (size_t)words + (size_t)w]);
      }
      bits += count;
    }
  }
  if (bits_out)
  {
    *bits_out = bits;
  }
  return bits ? (double)differ / (double)bits : 0.0;
}

static int masks_equal_everywhere(const pyramid_setup* ps, const uint32_t* a, const uint32_t* b,
                                  int32_t count)
{
  for (int32_t i = 0; i < ps->layout.level_count; ++i)
  {
    if (mask_difference(ps, i, a, b, count, NULL) != 0.0)
    {
      return 0;
    }
  }
  return 1;
}

static void test_incremental(void)
{
  mrgi_error err;
  const mrgi_voxel_projection p = perspective_projection(50.0, 1.0);
  float lp[3 * 64], ln[3 * 64];
  light_samples(8, lp, ln);
  const mrgi_voxel_samples samples = { 64, lp, ln, 0 };
  MRGI_CHECK(mrgi_voxel_samples_check(&samples, &err) == MRGI_OK);
  const int32_t size = 64;

  /* (a) unoccluded (floor only) and (b) fully occluded (a roof over everything) */
  for (int k = 0; k < 2; ++k)
  {
    scene s = { 0 };
    scene_add(&s, -12, -2.5, -30, 12, -2, -3);
    if (k == 1)
    {
      scene_add(&s, -40, 2.0, -40, 40, 2.5, 0.5);
    }
    test_view t = scene_view(&s, 64);
    pyramid_setup ps = make_pyramid(&s, &p, size);
    uint32_t* naive = naive_masks(&ps, &t.view, &samples);
    const size_t texels = (size_t)mrgi_multires_texel_count(&ps.layout);
    /* naive is uniform: all visible / all occluded at every receiver */
    int64_t ones = 0, receivers = 0;
    for (size_t q = 0; q < texels; ++q)
    {
      if (ps.position[4 * q + 3] > MRGI_GBUFFER_VALID_THRESHOLD)
      {
        ones += mrgi_voxel_popcount(naive[2 * q]) + mrgi_voxel_popcount(naive[2 * q + 1]);
        ++receivers;
      }
    }
    MRGI_CHECK(receivers > 1000);
    MRGI_CHECK(ones == (k == 0 ? 64 * receivers : 0));
    uint32_t* masks = (uint32_t*)malloc(texels * 2 * sizeof(uint32_t));
    MRGI_CHECK(masks != NULL);
    for (int interleave = 0; interleave <= 1; ++interleave)
    {
      for (int f = 0; f < 3; ++f)
      {
        const float fractions[3] = { 0.0f, 1.0f / 64.0f, 0.5f };
        mrgi_voxel_incremental_params params = { interleave, MRGI_VOXEL_METRIC_DISAGREE,
                                                 fractions[f] };
        mrgi_voxel_incremental_stats stats;
        MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                                 &t.view, &samples, NULL, 0, &params, masks,
                                                 texels * 2, &stats, &err) == MRGI_OK);
        MRGI_CHECK(masks_equal_everywhere(&ps, masks, naive, 64));
        /* uniform visibility: at fraction > 0 nothing below the coarsest level is computed */
        const int32_t L = ps.layout.level_count - 1;
        if (interleave)
        {
          /* a quarter each, plus the quarters of block-mates that are missing */
          MRGI_CHECK(stats.rays[L] >= 16 * stats.computed[L] &&
                     stats.rays[L] < 64 * stats.computed[L]);
        }
        else
        {
          MRGI_CHECK(stats.rays[L] == 64 * stats.computed[L]);
        }
        if (fractions[f] > 0.0f)
        {
          /* Level 0 inherits everything. Between it and the coarsest level
           * only texels at the floor's edges on screen are computed (the
           * surround rule, section 3, from MRGI_VOXEL_SURROUND_MIN_LEVEL):
           * they reuse the agreed visible bits, and march the agreed hidden
           * ones again. */
          MRGI_CHECK(stats.computed[0] == 0 && stats.inherited[0] > 0);
          MRGI_CHECK(k == 0 ? stats.rays_total == stats.rays[L] : stats.rays_total > stats.rays[L]);
          MRGI_CHECK(stats.rays[0] == 0 && stats.rays[1] == 0);
        }
        else
        {
          /* computed everywhere, all reused below the coarsest level but the
           * agreed hidden bits at the floor's edges (the surround rule) */
          MRGI_CHECK(k == 0 ? stats.rays_total == stats.rays[L] : stats.rays_total > stats.rays[L]);
          MRGI_CHECK(stats.computed[0] > 1000 && stats.inherited[0] == 0);
        }
      }
    }
    free(masks);
    free(naive);
    free_pyramid(&ps);
    free(t.voxels);
  }

  /* (c) occluders: the incremental rule checked bit by bit */
  rng_state = 12345;
  scene s;
  random_scene(&s, 8);
  test_view t = scene_view(&s, 64);
  pyramid_setup ps = make_pyramid(&s, &p, size);
  const size_t texels = (size_t)mrgi_multires_texel_count(&ps.layout);
  uint32_t* naive = naive_masks(&ps, &t.view, &samples);
  uint32_t* masks = (uint32_t*)malloc(texels * 2 * sizeof(uint32_t));
  uint32_t* again = (uint32_t*)malloc(texels * 2 * sizeof(uint32_t));
  MRGI_CHECK(masks && again);
  mrgi_voxel_incremental_params params = { 0, MRGI_VOXEL_METRIC_DISAGREE, 0.0f };
  mrgi_voxel_incremental_stats stats0;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, NULL, 0, &params, masks,
                                           texels * 2, &stats0, &err) == MRGI_OK);
  const int32_t L = ps.layout.level_count - 1;
  MRGI_CHECK(mask_difference(&ps, L, masks, naive, 64, NULL) == 0.0); /* coarsest = naive */
  int64_t disagreeing_bits = 0, reused_bits = 0;
  for (int32_t i = L - 1; i >= 0; --i)
  {
    for (int32_t y = 0; y < ps.layout.level_height[i]; ++y)
    {
      for (int32_t x = 0; x < ps.layout.level_width[i]; ++x)
      {
        const size_t q = mrgi_multires_index(&ps.layout, i, x, y);
        if (!(ps.position[4 * q + 3] > MRGI_GBUFFER_VALID_THRESHOLD))
        {
          continue;
        }
        uint32_t all[2] = { 0xFFFFFFFFu, 0xFFFFFFFFu }, any[2] = { 0, 0 };
        int kept = 0;
        int sides[2] = { 0, 0 }; /* the surround rule: bit 0 before, bit 1 after */
        for (int32_t dy = -1; dy <= 1; ++dy)
        {
          for (int32_t dx = -1; dx <= 1; ++dx)
          {
            int32_t cx = x / 2 + dx, cy = y / 2 + dy;
            cx = cx < 0 ? 0 : (cx >= ps.layout.level_width[i + 1] ? ps.layout.level_width[i + 1] - 1 : cx);
            cy = cy < 0 ? 0 : (cy >= ps.layout.level_height[i + 1] ? ps.layout.level_height[i + 1] - 1 : cy);
            const size_t c = mrgi_multires_index(&ps.layout, i + 1, cx, cy);
            if (ps.position[4 * c + 3] > MRGI_GBUFFER_VALID_THRESHOLD)
            {
              /* the same-surface guard: reuse needs a neighbour on q's surface */
              const int same = mrgi_voxel_same_surface(ps.position + 4 * q, ps.normal + 4 * q,
                                                       ps.position + 4 * c, ps.normal + 4 * c);
              kept += same;
              for (int a = 0; same && a < 2; ++a)
              {
                const int side = mrgi_voxel_screen_side(ps.position + 4 * q, ps.position + 4 * c,
                                                        t.view.projection.parallel, a);
                sides[a] |= (side <= 0 ? 1 : 0) | (side >= 0 ? 2 : 0);
              }
              for (int w = 0; w < 2; ++w)
              {
                all[w] &= masks[2 * c + (size_t)w];
                any[w] |= masks[2 * c + (size_t)w];
              }
            }
          }
        }
        for (int w = 0; w < 2; ++w)
        {
          /* without a neighbour on its surface every bit is re-marched; not
           * surrounded by them, also the bits they agree are hidden */
          const int surrounded = (sides[0] == 3 && sides[1] == 3) || i < MRGI_VOXEL_SURROUND_MIN_LEVEL;
          const uint32_t disagree =
            kept ? (all[w] ^ any[w]) | (surrounded ? 0u : ~all[w]) : 0xFFFFFFFFu;
          /* disagreeing bits were re-marched: equal to the naive bits */
          MRGI_CHECK(((masks[2 * q + (size_t)w] ^ naive[2 * q + (size_t)w]) & disagree) == 0u);
          /* agreeing bits are the neighbours' common value */
          MRGI_CHECK(((masks[2 * q + (size_t)w] ^ all[w]) & ~disagree) == 0u);
          disagreeing_bits += mrgi_voxel_popcount(disagree);
          reused_bits += 32 - mrgi_voxel_popcount(disagree);
        }
      }
    }
  }
  int64_t bits0 = 0;
  const double differ0 = mask_difference(&ps, 0, masks, naive, 64, &bits0);
  printf("incremental (no interleave, every texel): %.2f%% of level-0 bits differ from naive; "
         "re-marched %.2f%% of bits below the coarsest level; rays %lld vs naive %lld (%.1f%%)\n",
         100.0 * differ0, 100.0 * (double)disagreeing_bits / (double)(disagreeing_bits + reused_bits),
         (long long)stats0.rays_total, (long long)stats0.rays_naive,
         100.0 * (double)stats0.rays_total / (double)stats0.rays_naive);
  MRGI_CHECK(disagreeing_bits > 0);                 /* the scene has shadow boundaries */
  MRGI_CHECK(stats0.rays_total < stats0.rays_naive); /* and the reuse saves rays */
  MRGI_CHECK(differ0 < 0.04);

  /* threshold 1 (DISAGREE) == threshold 0, with fewer texels computed */
  params.refine_fraction = 1.0f / 64.0f;
  mrgi_voxel_incremental_stats stats1;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, NULL, 0, &params, again,
                                           texels * 2, &stats1, &err) == MRGI_OK);
  MRGI_CHECK(masks_equal_everywhere(&ps, masks, again, 64));
  MRGI_CHECK(stats1.rays_total == stats0.rays_total);
  MRGI_CHECK(stats1.computed[0] < stats0.computed[0]);
  /* a refine mask forcing every texel equals threshold 0, whatever the threshold */
  uint8_t* force = (uint8_t*)malloc(texels);
  MRGI_CHECK(force != NULL);
  memset(force, 1, texels);
  params.refine_fraction = 1.0f;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, force, texels, &params, again,
                                           texels * 2, &stats1, &err) == MRGI_OK);
  MRGI_CHECK(masks_equal_everywhere(&ps, masks, again, 64));
  /* the paper's threshold (half the samples) and the count-spread metric: fewer rays, some error */
  const int metrics[2] = { MRGI_VOXEL_METRIC_DISAGREE, MRGI_VOXEL_METRIC_COUNT_SPREAD };
  for (int m = 0; m < 2; ++m)
  {
    for (int interleave = 0; interleave <= 1; ++interleave)
    {
      const float fractions[3] = { 0.0f, 0.125f, 0.5f };
      for (int f = 0; f < 3; ++f)
      {
        mrgi_voxel_incremental_params pp = { interleave, metrics[m], fractions[f] };
        mrgi_voxel_incremental_stats st;
        MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                                 &t.view, &samples, NULL, 0, &pp, again,
                                                 texels * 2, &st, &err) == MRGI_OK);
        const double d = mask_difference(&ps, 0, again, naive, 64, NULL);
        printf("  metric %s, interleave %d, refine fraction %.3f: level-0 bits differing from "
               "naive %.2f%%, rays %.1f%% of naive, level-0 texels computed %lld / %lld\n",
               m == 0 ? "disagree" : "spread  ", interleave, (double)fractions[f], 100.0 * d,
               100.0 * (double)st.rays_total / (double)st.rays_naive,
               (long long)st.computed[0], (long long)(st.computed[0] + st.inherited[0]));
        /* interleaving trades a neighbour's bits for 3/4 of the rays */
        /* a deliberately coarse setup (64^2 image, 8^2 coarsest level); at
         * 256^2 with a 16^2 coarsest level and 256 samples the same sweep
         * measures 0.5..2.1% without and 1.3..4.9% with interleaving */
        MRGI_CHECK(d < (interleave ? 0.12 : 0.08));
        MRGI_CHECK(st.rays_total < st.rays_naive);
      }
    }
  }
  /* interleaving on the coarsest level alone: a pixel's own phase is its naive bits */
  params.interleave = 1;
  params.refine_fraction = 0.0f;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, NULL, 0, &params, again,
                                           texels * 2, &stats1, &err) == MRGI_OK);
  for (int32_t y = 0; y < ps.layout.level_height[L]; ++y)
  {
    for (int32_t x = 0; x < ps.layout.level_width[L]; ++x)
    {
      const size_t q = mrgi_multires_index(&ps.layout, L, x, y);
      const uint32_t own = mrgi_voxel_phase_word_mask(1u << mrgi_voxel_interleave_phase(x, y));
      for (int w = 0; w < 2; ++w)
      {
        MRGI_CHECK(((again[2 * q + (size_t)w] ^ naive[2 * q + (size_t)w]) & own) == 0u);
      }
    }
  }
  /* the coarsest level's interleaved rays: a quarter of naive plus the fill-ins */
  MRGI_CHECK(stats1.rays[L] < stats0.rays[L]);

  /* bad input */
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, NULL, 0, &params, again,
                                           texels * 2 - 1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mask array") != NULL);
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, 3, &t.view,
                                           &samples, NULL, 0, &params, again, texels * 2, NULL,
                                           &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "receiver") != NULL);
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, force, texels - 1, &params, again,
                                           texels * 2, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "refine mask") != NULL);
  params.refine_fraction = -0.5f;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, NULL, 0, &params, again,
                                           texels * 2, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "refine fraction") != NULL);
  params.refine_fraction = 0.5f;
  params.metric = 7;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, NULL, 0, &params, again,
                                           texels * 2, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "metric") != NULL);
  params.metric = 0;
  params.interleave = 3;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &samples, NULL, 0, &params, again,
                                           texels * 2, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_voxel_samples bad_samples = samples;
  bad_samples.count = 0;
  MRGI_CHECK(mrgi_voxel_samples_check(&bad_samples, &err) == MRGI_ERR_INVALID_ARGUMENT);
  bad_samples.count = MRGI_VOXEL_MAX_SAMPLES + 1;
  MRGI_CHECK(mrgi_voxel_samples_check(&bad_samples, &err) == MRGI_ERR_INVALID_ARGUMENT);
  float nan_lp[3 * 64];
  memcpy(nan_lp, lp, sizeof(lp));
  nan_lp[3 * 2 + 1] = NAN;
  bad_samples.count = 64;
  bad_samples.position = nan_lp;
  MRGI_CHECK(mrgi_voxel_samples_check(&bad_samples, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "light sample 2") != NULL && strstr(err.message, "position"));
  params.interleave = 1;
  MRGI_CHECK(mrgi_voxel_visibility_pyramid(&ps.layout, ps.position, ps.normal, ps.floats,
                                           &t.view, &bad_samples, NULL, 0, &params, again,
                                           texels * 2, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  free(force);
  free(masks);
  free(again);
  free(naive);
  free_pyramid(&ps);
  free(t.voxels);
}

/* The same-surface guard (mrgi_visibility_pyramid.h section 3): the top of a
 * box (y = -0.5, normal up), lit from above, at level 0 (8 x 8); level 1
 * (4 x 4) holds coarse receivers as a texel averaging the top and the front
 * face across the box's front edge gets them: the mean normal halfway
 * between, the mean position inside the box. Those coarse receivers are
 * hidden (naive at the coarsest level) and agree on it; without the guard
 * every fine texel under them inherited "hidden" (or reused it). Left
 * half: coarse receivers on the top itself (visible, reused). */
/* The surround rule's screen test (mrgi_visibility_pyramid.h section 3). */
static void test_screen_side(void)
{
  const float p[3] = { 1.0f, -2.0f, -10.0f };
  /* perspective: q to the right on screen (x / -z larger), at any depth */
  const float right[3] = { 3.0f, -2.0f, -20.0f };   /* x/-z 0.15 > 0.1 */
  const float behind[3] = { 1.5f, -2.0f, -20.0f };  /* x/-z 0.075 < 0.1: left, though x is larger */
  const float above[3] = { 1.0f, -1.0f, -10.0f };
  const float same_ray[3] = { 2.0f, -4.0f, -20.0f }; /* on the eye ray through p */
  MRGI_CHECK(mrgi_voxel_screen_side(p, right, 0, 0) == 1);
  MRGI_CHECK(mrgi_voxel_screen_side(p, behind, 0, 0) == -1);
  MRGI_CHECK(mrgi_voxel_screen_side(p, above, 0, 1) == 1);
  MRGI_CHECK(mrgi_voxel_screen_side(p, above, 0, 0) == 0);
  MRGI_CHECK(mrgi_voxel_screen_side(p, same_ray, 0, 0) == 0 &&
             mrgi_voxel_screen_side(p, same_ray, 0, 1) == 0);
  MRGI_CHECK(mrgi_voxel_screen_side(p, p, 0, 0) == 0 && mrgi_voxel_screen_side(p, p, 1, 1) == 0);
  /* parallel: plain coordinates, depth ignored */
  MRGI_CHECK(mrgi_voxel_screen_side(p, behind, 1, 0) == 1);
  MRGI_CHECK(mrgi_voxel_screen_side(p, same_ray, 1, 1) == -1);
  /* antisymmetric */
  MRGI_CHECK(mrgi_voxel_screen_side(right, p, 0, 0) == -1 && mrgi_voxel_screen_side(behind, p, 1, 0) == -1);
}

static void test_incremental_guard(void)
{
  mrgi_error err;
  float lp[3 * 64], ln[3 * 64];
  light_samples(8, lp, ln);
  const mrgi_voxel_samples samples = { 64, lp, ln, 0 };
  scene s = { 0 };
  scene_add(&s, -12, -2.5, -30, 12, -2, -3); /* floor */
  scene_add(&s, -3, -2, -12, 3, -0.5, -9);   /* the box: top y = -0.5, front z = -9 */
  test_view t = scene_view(&s, 64);
  mrgi_multires_layout layout;
  MRGI_CHECK(mrgi_multires_layout_init(&layout, 8, 8, 4, &err) == MRGI_OK);
  MRGI_CHECK(layout.level_count == 2);
  const size_t texels = (size_t)mrgi_multires_texel_count(&layout);
  float* position = (float*)calloc(4 * texels, sizeof(float));
  float* normal = (float*)calloc(4 * texels, sizeof(float));
  uint32_t* masks = (uint32_t*)calloc(2 * texels, sizeof(uint32_t));
  MRGI_CHECK(position && normal && masks);
  for (int32_t i = 0; i < 2; ++i)
  {
    const int32_t side = layout.level_width[i];
    for (int32_t y = 0; y < side; ++y)
    {
      for (int32_t x = 0; x < side; ++x)
      {
        const size_t q = mrgi_multires_index(&layout, i, x, y);
        float* P = position + 4 * q;
        float* N = normal + 4 * q;
        P[0] = (float)(-2.0 + 4.0 * (x + 0.5) / side);
        P[1] = -0.5f;
        P[2] = (float)(-11.5 + 2.0 * (y + 0.5) / side);
        P[3] = i == 0 ? MRGI_GBUFFER_VALID : 4.0f;
        N[1] = 1.0f;
        if (i == 1 && x >= 2)
        {
          /* across the front edge: inside the box, normal between up and +z */
          P[1] = -1.0f;
          P[2] = -9.5f;
          N[1] = 0.7071f;
          N[2] = 0.7071f;
          MRGI_CHECK(!mrgi_voxel_same_surface(position + 4 * mrgi_multires_index(&layout, 0, 2 * x, 2 * y),
                                              normal + 4 * mrgi_multires_index(&layout, 0, 2 * x, 2 * y),
                                              P, N));
        }
      }
    }
  }
  for (int interleave = 0; interleave <= 1; ++interleave)
  {
    for (int f = 0; f < 2; ++f)
    {
      const float fractions[2] = { 0.0f, 0.5f };
      mrgi_voxel_incremental_params params = { interleave, MRGI_VOXEL_METRIC_DISAGREE,
                                               fractions[f] };
      mrgi_voxel_incremental_stats stats;
      MRGI_CHECK(mrgi_voxel_visibility_pyramid(&layout, position, normal, 4 * texels, &t.view,
                                               &samples, NULL, 0, &params, masks, 2 * texels,
                                               &stats, &err) == MRGI_OK);
      for (int32_t y = 0; y < 4; ++y)
      {
        for (int32_t x = 0; x < 4; ++x)
        {
          /* the coarse receivers: inside the box hidden (all agree), on the top visible */
          const uint32_t* m = masks + 2 * mrgi_multires_index(&layout, 1, x, y);
          MRGI_CHECK(m[0] == (x >= 2 ? 0u : 0xFFFFFFFFu) && m[1] == m[0]);
        }
      }
      for (int32_t y = 0; y < 8; ++y)
      {
        for (int32_t x = 0; x < 8; ++x)
        {
          /* every fine texel on the lit top sees every sample, under the hidden parents too */
          const uint32_t* m = masks + 2 * mrgi_multires_index(&layout, 0, x, y);
          MRGI_CHECK(m[0] == 0xFFFFFFFFu && m[1] == 0xFFFFFFFFu);
        }
      }
      /* the guard keeps the reuse where the neighbourhood is on the surface */
      if (f == 1)
      {
        MRGI_CHECK(stats.inherited[0] > 0);
      }
      MRGI_CHECK(stats.rays[0] > 0 && stats.rays_total < stats.rays_naive + stats.rays[1]);
    }
  }
  free(position);
  free(normal);
  free(masks);
  free(t.voxels);
}

/* ---- 5. variance shadow query ---- */
static void test_vsm(void)
{
  mrgi_error err;
  /* query cells: 24 distinct cells of the 5 x 5 lobe grid (-2..2), corner (2, 2) dropped */
  MRGI_CHECK(MRGI_VOXEL_VSM_QUERIES == 24 && MRGI_VOXEL_VSM_TARGETS == 3);
  int seen[25] = { 0 };
  for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
  {
    int32_t cx, cy;
    mrgi_voxel_vsm_query_cell(j, &cx, &cy);
    MRGI_CHECK(cx >= -2 && cx <= 2 && cy >= -2 && cy <= 2);
    MRGI_CHECK(!(cx == 2 && cy == 2));
    MRGI_CHECK(seen[(cy + 2) * 5 + cx + 2] == 0);
    seen[(cy + 2) * 5 + cx + 2] = 1;
  }
  /* Chebyshev with the receiver at 1 */
  MRGI_CHECK(mrgi_voxel_vsm_chebyshev(1.0f, 1.0f, 0.0f) == 1.0f);
  MRGI_CHECK(mrgi_voxel_vsm_chebyshev(0.5f, 0.25f, 0.0f) == 0.0f); /* one sharp occluder */
  MRGI_CHECK_NEAR(mrgi_voxel_vsm_chebyshev(0.5f, 0.25f, 1e-4f), 1e-4 / (1e-4 + 0.25), 1e-7);
  /* 5 lit (z = 1), 4 occluded at z = 0.5: mean 7/9, mean_sq 6/9 -> 5/9 */
  MRGI_CHECK_NEAR(mrgi_voxel_vsm_chebyshev(7.0f / 9.0f, 6.0f / 9.0f, 0.0f), 5.0 / 9.0, 1e-5);

  /* resolve on a synthetic 3 x 3 image (one query): the centre's window holds them all */
  float moments[9 * 2];
  uint8_t phases[9];
  for (int k = 0; k < 9; ++k)
  {
    const float z = k < 5 ? 1.0f : 0.5f;
    moments[2 * k] = z;
    moments[2 * k + 1] = z * z;
    phases[k] = MRGI_VOXEL_ALL_PHASES;
  }
  float vis[9];
  MRGI_CHECK(mrgi_voxel_vsm_resolve(3, 3, 1, moments, phases, 1, 0.0f, vis, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(vis[4], 5.0 / 9.0, 1e-5);
  MRGI_CHECK(vis[0] == 1.0f);            /* window: pixels 0, 1, 3, 4, all lit */
  MRGI_CHECK_NEAR(vis[8], 0.25, 1e-5);   /* window: 4 lit, 5, 7, 8 at 0.5 -> 1/4 */
  MRGI_CHECK(mrgi_voxel_vsm_resolve(3, 3, 1, moments, phases, 0, 0.0f, vis, &err) == MRGI_OK);
  MRGI_CHECK(vis[0] == 1.0f && vis[8] == 0.0f); /* no blur: binary */
  phases[4] = 0;
  MRGI_CHECK(mrgi_voxel_vsm_resolve(3, 3, 1, moments, phases, 1, 0.0f, vis, &err) == MRGI_OK);
  MRGI_CHECK(vis[4] == 0.0f); /* not a receiver */
  MRGI_CHECK(mrgi_voxel_vsm_resolve(3, 3, 1, moments, phases, 17, 0.0f, vis, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "radius") != NULL);
  MRGI_CHECK(mrgi_voxel_vsm_resolve(3, 3, 1, moments, phases, 1, -1.0f, vis, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_vsm_resolve(3, 3, 1, NULL, phases, 1, 0.0f, vis, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);

  /* a real shadow edge: a box's edge over the floor, receivers on a row
   * crossing it, 24 queries on a small patch of the light */
  scene s = { 0 };
  scene_add(&s, -12, -2.5, -30, 12, -2, -3);
  scene_add(&s, -6.0, 0.5, -14, 0.0, 0.8, -8); /* edge at x = 0, 2.5 above the floor */
  test_view t = scene_view(&s, 128);
  float qp[3 * MRGI_VOXEL_VSM_QUERIES], qn[3 * MRGI_VOXEL_VSM_QUERIES];
  for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
  {
    int32_t cx, cy;
    mrgi_voxel_vsm_query_cell(j, &cx, &cy);
    qp[3 * j] = (float)(0.1 * cx);
    qp[3 * j + 1] = 5.0f;
    qp[3 * j + 2] = (float)(-11.0 + 0.1 * cy);
    qn[3 * j] = 0.0f;
    qn[3 * j + 1] = -1.0f;
    qn[3 * j + 2] = 0.0f;
  }
  const mrgi_voxel_samples queries = { MRGI_VOXEL_VSM_QUERIES, qp, qn, 0 };
  enum { ROW = 48 };
  float* row_moments = (float*)malloc(sizeof(float) * ROW * 2 * MRGI_VOXEL_VSM_QUERIES);
  float* row_vis = (float*)malloc(sizeof(float) * ROW * MRGI_VOXEL_VSM_QUERIES);
  uint8_t row_phases[ROW];
  MRGI_CHECK(row_moments && row_vis);
  const float up[3] = { 0, 1, 0 };
  for (int k = 0; k < ROW; ++k)
  {
    const float P[3] = { (float)(-4.0 + 8.0 * k / (ROW - 1)), -2.0f, -11.0f };
    row_phases[k] = MRGI_VOXEL_ALL_PHASES;
    mrgi_voxel_vsm_moments(&t.view, &queries, P, up, MRGI_VOXEL_ALL_PHASES,
                           row_moments + (size_t)k * 2 * MRGI_VOXEL_VSM_QUERIES);
    /* consistent with the binary march */
    for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
    {
      const float z = row_moments[((size_t)k * MRGI_VOXEL_VSM_QUERIES + (size_t)j) * 2];
      const int visible = mrgi_voxel_march(&t.view, P, up, qp + 3 * j, qn + 3 * j);
      MRGI_CHECK(visible ? z == 1.0f : z < 1.0f);
      MRGI_CHECK(z >= 0.0f && z <= 1.0f);
    }
  }
  /* with interleaving each pixel computes one phase only */
  float* moments_q = (float*)malloc(sizeof(float) * 2 * MRGI_VOXEL_VSM_QUERIES);
  MRGI_CHECK(moments_q != NULL);
  const float P0[3] = { -4.0f, -2.0f, -11.0f };
  mrgi_voxel_vsm_moments(&t.view, &queries, P0, up, 1u << 2, moments_q);
  for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
  {
    MRGI_CHECK((j & 3) == 2 ? moments_q[2 * j] > 0.0f : moments_q[2 * j] == 0.0f);
  }
  free(moments_q);
  MRGI_CHECK(mrgi_voxel_vsm_resolve(ROW, 1, MRGI_VOXEL_VSM_QUERIES, row_moments, row_phases, 2,
                                    1e-4f, row_vis, &err) == MRGI_OK);
  /* mean visibility over the queries per receiver: 0 under the box, 1 in
   * the open, in between near the edge */
  int intermediate = 0;
  float previous = -1.0f;
  int monotone_breaks = 0;
  for (int k = 0; k < ROW; ++k)
  {
    float mean = 0.0f;
    for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
    {
      mean += row_vis[(size_t)k * MRGI_VOXEL_VSM_QUERIES + (size_t)j];
    }
    mean /= MRGI_VOXEL_VSM_QUERIES;
    if (k < 12)
    {
      MRGI_CHECK(mean < 0.05f); /* x <= -2: under the box */
    }
    if (k > ROW - 12)
    {
      MRGI_CHECK(mean == 1.0f); /* x >= 2: open */
    }
    intermediate += mean > 0.05f && mean < 0.95f;
    monotone_breaks += mean < previous - 0.05f;
    previous = mean;
  }
  printf("variance shadow query: %d of %d receivers across the shadow edge get fractional "
         "visibility\n",
         intermediate, ROW);
  MRGI_CHECK(intermediate >= 2);
  MRGI_CHECK(monotone_breaks == 0);
  free(row_moments);
  free(row_vis);
  free(t.voxels);
}

/* The moments pass of a specular G-buffer (section 6): receivers on a
 * glossy floor whose reflections meet a small light above, past the edge of
 * a shelf (eye space = world space here). */
static void test_vsm_specular_moments(void)
{
  mrgi_error err;
  scene s = { 0 };
  scene_add(&s, -12, -2.5, -30, 12, -2, -3);      /* floor */
  scene_add(&s, -6.0, 0.5, -16, 0.0, 0.8, -11.0); /* shelf, edge at x = 0 */
  test_view t = scene_view(&s, 128);
  /* P = (x, -2, -6) reflects the eye towards (4.5 x, 5, -27), crossing the
   * shelf's height at (2.25 x, 0.5, -13.5): shadowed for x in [-2.67, 0] */
  mrgi_area_light light;
  memset(&light, 0, sizeof(light));
  light.center[1] = 5.0;
  light.center[2] = -27.0;
  light.edge_u[0] = 1.0;
  light.edge_v[2] = 1.0; /* u x v = -y: faces the floor */
  light.color[0] = light.color[1] = light.color[2] = 1.0;
  light.intensity = 1.0;
  mrgi_area_light_uniforms u;
  MRGI_CHECK(mrgi_area_light_uniforms_init(&light, NULL, &u, &err) == MRGI_OK);
  mrgi_area_light_sample samples[4];
  int32_t count = 0;
  MRGI_CHECK(mrgi_area_light_make_samples(&light, NULL, 4, 0, 1, samples, 4, &count, &err) ==
             MRGI_OK);
  const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  const float up[3] = { 0, 1, 0 };
  float moments[2 * MRGI_VOXEL_VSM_QUERIES];
  int shadowed = 0, lit = 0, off_light = 0;
  for (int k = 0; k < 16; ++k)
  {
    const float x = -0.75f + 0.1f * (float)k;
    const float P[3] = { x, -2.0f, -6.0f };
    const float V[3] = { -x, 2.0f, 6.0f };
    /* one phase (the interleaved pass): the other queries stay 0 */
    const uint32_t phase = (uint32_t)(k & 3);
    MRGI_CHECK(mrgi_voxel_vsm_specular_moments(&t.view, &u, samples, count, identity, P, up, V,
                                               128.0f, P, up, 1u << phase, moments) == 1);
    for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
    {
      MRGI_CHECK((uint32_t)(j & 3) == phase || (moments[2 * j] == 0.0f && moments[2 * j + 1] == 0.0f));
    }
    MRGI_CHECK(mrgi_voxel_vsm_specular_moments(&t.view, &u, samples, count, identity, P, up, V,
                                               128.0f, P, up, MRGI_VOXEL_ALL_PHASES, moments) == 1);
    mrgi_area_light_specular_info info;
    mrgi_area_light_specular_classify(&u, samples, count, P, up, V, 128.0f, &info);
    MRGI_CHECK(info.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID);
    mrgi_area_light_lobe_grid grid;
    MRGI_CHECK(mrgi_area_light_lobe_grid_cells(&u, &info.lobe, &grid) == 1);
    float occluded = 0.0f;
    for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
    {
      const float z = moments[2 * j];
      MRGI_CHECK(z >= 0.0f && z <= 1.0f && moments[2 * j + 1] == z * z);
      if (!grid.on_light[j])
      {
        MRGI_CHECK(z == 1.0f); /* nothing there to hide */
        ++off_light;
        continue;
      }
      /* the binary march toward the same cell centre agrees */
      MRGI_CHECK(mrgi_voxel_march(&t.view, P, up, grid.position[j], u.normal) ? z == 1.0f
                                                                                : z < 1.0f);
      occluded += z < 1.0f;
    }
    shadowed += x < -0.4f && occluded > 0;
    lit += x > 0.4f && occluded == 0;
  }
  printf("VSM specular moments: %d shadowed receivers under the shelf, %d unshadowed past its "
         "edge, %d queries toward cells off the light\n",
         shadowed, lit, off_light);
  MRGI_CHECK(shadowed >= 3 && lit >= 3 && off_light > 0);
  /* a glossy lobe with many samples inside it takes the sample path: nothing computed */
  mrgi_area_light_sample many[1024];
  MRGI_CHECK(mrgi_area_light_make_samples(&light, NULL, 1024, 0, 1, many, 1024, &count, &err) ==
             MRGI_OK);
  const float P[3] = { 0.0f, -2.0f, -6.0f }, V[3] = { 0.0f, 2.0f, 6.0f };
  MRGI_CHECK(mrgi_voxel_vsm_specular_moments(&t.view, &u, many, count, identity, P, up, V, 20.0f, P,
                                             up, MRGI_VOXEL_ALL_PHASES, moments) == 0);
  for (int32_t j = 0; j < 2 * MRGI_VOXEL_VSM_QUERIES; ++j)
  {
    MRGI_CHECK(moments[j] == 0.0f);
  }
  free(t.voxels);
}

/* ---- 6. random box scenes against exact ray-box visibility ---- */
static void test_random_scenes(void)
{
  const mrgi_voxel_projection p = perspective_projection(50.0, 1.0);
  enum { SCENES = 4, RECEIVERS = 600, SIDE = 8 };
  float lp[3 * SIDE * SIDE], ln[3 * SIDE * SIDE];
  light_samples(SIDE, lp, ln);
  /* Voxel sides at 128 slices (both step caps), then 256 and 512 slices at 512^2. */
  const int32_t res[5] = { 128, 256, 512, 512, 512 };
  const int32_t slices[5] = { 128, 128, 128, 256, 512 };
  double fraction[5][2];
  for (int cap = 0; cap < 2; ++cap)
  {
    for (int r = 0; r < (cap ? 3 : 5); ++r)
    {
      int64_t rays = 0, false_occluded = 0, false_visible = 0, occluded = 0;
      rng_state = 777;
      for (int sc = 0; sc < SCENES; ++sc)
      {
        scene s;
        random_scene(&s, 12);
        test_view t = sliced_scene_view(&s, res[r], slices[r]);
        if (cap)
        {
          t.view.params.max_steps = 1024; /* never binds: one step per voxel pixel */
        }
        for (int k = 0; k < RECEIVERS; ++k)
        {
          /* a window pixel of a 512^2 window */
          const int32_t x = (int32_t)(rng_u32() % 512), y = (int32_t)(rng_u32() % 512);
          float P[3], N[3];
          if (!scene_hit(&s, &p, (2.0 * x + 1.0) / 512 - 1.0, (2.0 * y + 1.0) / 512 - 1.0, P, N))
          {
            continue;
          }
          for (int j = 0; j < SIDE * SIDE; ++j)
          {
            const float* L = lp + 3 * j;
            const float D[3] = { L[0] - P[0], L[1] - P[1], L[2] - P[2] };
            if (D[0] * N[0] + D[1] * N[1] + D[2] * N[2] <= 0.0f)
            {
              continue; /* below the horizon: both say occluded, not informative */
            }
            const int exact = exact_visible(&s, P, N, L);
            const int voxel = mrgi_voxel_march(&t.view, P, N, L, ln + 3 * j);
            false_occluded += exact && !voxel;
            false_visible += !exact && voxel;
            occluded += !exact;
            ++rays;
          }
        }
        free(t.voxels);
      }
      fraction[r][cap] = (double)(false_occluded + false_visible) / (double)rays;
      printf("random boxes, voxels %3d^2 x %3d, step cap %4d: %lld rays (%.1f%% occluded), "
             "disagreeing %.2f%% (false occlusion %.2f%%, false visibility %.2f%%)\n",
        res[r], slices[r], cap ? 1024 : MRGI_VOXEL_DEFAULT_MAX_STEPS, (long long)rays,
        100.0 * (double)occluded / (double)rays, 100.0 * fraction[r][cap],
        100.0 * (double)false_occluded / (double)rays,
        100.0 * (double)false_visible / (double)rays);
      MRGI_CHECK(rays > 50000);
      MRGI_CHECK(occluded > rays / 20); /* the scenes do cast shadows */
      MRGI_CHECK(fraction[r][cap] < 0.05);
    }
  }
  /* With 128 slices over [3, 31] (0.22 units), depth quantization and the
   * bias (both in slice units here) dominate, so the lateral resolution
   * changes little; each resolution stays within 5%. Thinner slices are
   * what narrows the voxels (mrgi_voxel.h section 1): at 512^2, 256 and 512
   * slices must each disagree clearly less than the slices before them. */
  MRGI_CHECK(fraction[3][0] < 0.85 * fraction[2][0]);
  MRGI_CHECK(fraction[4][0] < 0.85 * fraction[3][0]);
}

/* Batches of marched samples stay within the loop budget of one shader
 * invocation, at every step cap, and never drop to 0. */
/* mrgi_voxel_step_bound(): capping the march there changes no result (the
 * batches sized with it hold), capping it at half of it does. */
static void test_step_bound(void)
{
  const mrgi_voxel_grid wide = { 128, 64, MRGI_VOXEL_DEFAULT_SLICES, 1.0f, 2.0f, 128.0f };
  MRGI_CHECK(mrgi_voxel_step_bound(&wide, 256) == 130);
  MRGI_CHECK(mrgi_voxel_step_bound(&wide, 100) == 100);
  MRGI_CHECK(mrgi_voxel_step_bound(NULL, 256) == 256);
  MRGI_CHECK(mrgi_voxel_step_bound(&wide, 0) == 1);
  MRGI_CHECK(mrgi_voxel_samples_per_batch(mrgi_voxel_step_bound(&wide, 256)) >
             mrgi_voxel_samples_per_batch(256));
  const mrgi_voxel_projection p = perspective_projection(50.0, 1.0);
  float lp[3 * 64], ln[3 * 64];
  light_samples(8, lp, ln);
  const int32_t sides[2] = { 16, 64 };
  for (int r = 0; r < 2; ++r)
  {
    int64_t rays = 0, differ_at_bound = 0, differ_at_half = 0;
    rng_state = 4242;
    for (int sc = 0; sc < 3; ++sc)
    {
      scene s;
      random_scene(&s, 12);
      test_view t = scene_view(&s, sides[r]);
      const int32_t bound = mrgi_voxel_step_bound(&t.view.grid, MRGI_VOXEL_MAX_STEPS);
      MRGI_CHECK(bound == sides[r] + 2);
      for (int k = 0; k < 400; ++k)
      {
        const int32_t x = (int32_t)(rng_u32() % 256), y = (int32_t)(rng_u32() % 256);
        float P[3], N[3];
        if (!scene_hit(&s, &p, (2.0 * x + 1.0) / 256 - 1.0, (2.0 * y + 1.0) / 256 - 1.0, P, N))
        {
          continue;
        }
        for (int j = 0; j < 64 + 8; ++j)
        {
          /* the light's samples, and far points in every direction (clipped by the frustum) */
          float far[3];
          for (int c = 0; c < 3; ++c)
          {
            far[c] = P[c] + 1000.0f * ((float)(rng_u32() % 2001) / 1000.0f - 1.0f);
          }
          const float* L = j < 64 ? lp + 3 * j : far;
          const float* NL = j < 64 ? ln + 3 * j : NULL;
          t.view.params.max_steps = MRGI_VOXEL_MAX_STEPS;
          const int free_march = mrgi_voxel_march(&t.view, P, N, L, NL);
          t.view.params.max_steps = bound;
          differ_at_bound += mrgi_voxel_march(&t.view, P, N, L, NL) != free_march;
          t.view.params.max_steps = bound / 2;
          differ_at_half += mrgi_voxel_march(&t.view, P, N, L, NL) != free_march;
          ++rays;
        }
      }
      free(t.voxels);
    }
    printf("step bound %d^2: %lld rays, %lld differ capped at the bound, %lld at half of it\n",
           sides[r], (long long)rays, (long long)differ_at_bound, (long long)differ_at_half);
    MRGI_CHECK(rays > 10000);
    MRGI_CHECK(differ_at_bound == 0);
    MRGI_CHECK(differ_at_half > 0);
  }
}

static void test_samples_per_batch(void)
{
  for (int32_t steps = -1; steps <= MRGI_VOXEL_MAX_STEPS; steps += (steps < 64 ? 1 : 61))
  {
    const int32_t batch = mrgi_voxel_samples_per_batch(steps);
    const int64_t used = (int64_t)batch * ((steps > 0 ? steps : 1) * (int64_t)MRGI_VOXEL_ITERATIONS_PER_STEP +
                                           MRGI_VOXEL_ITERATIONS_PER_MARCH);
    MRGI_CHECK(batch >= 1);
    MRGI_CHECK(batch == 1 || used <= MRGI_VOXEL_ITERATION_BUDGET);
  }
  MRGI_CHECK(mrgi_voxel_samples_per_batch(MRGI_VOXEL_DEFAULT_MAX_STEPS) == 28);
  MRGI_CHECK(mrgi_voxel_samples_per_batch(1) > mrgi_voxel_samples_per_batch(2));
}

/* The slicing range fitted to a box: the corners' eye-depth range plus the
 * margin, inside the clipping range; the clipping range for an empty box,
 * a box behind or outside it, and errors for bad arguments. */
static void test_fit_depth_range(void)
{
  /* Camera at the origin looking down -z, rotated 90 degrees about y in a
   * second case (eye z = world x). Row-major world -> eye. */
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  const double turned[16] = { 0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1 };
  const double fit_box[6] = { -1, 1, -1, 1, -30, -10 };
  const double clip[2] = { 1.0, 100.0 };
  double range[2];
  mrgi_error err;
  MRGI_CHECK(mrgi_voxel_fit_depth_range(identity, fit_box, clip, range, &err) == MRGI_OK);
  MRGI_CHECK(fabs(range[0] - (10.0 - 0.2)) < 1e-12 && fabs(range[1] - (30.0 + 0.2)) < 1e-12);
  /* eye z = world x: box x in [-30, -10] gives depths 10..30 as well */
  const double box_x[6] = { -30, -10, -1, 1, -1, 1 };
  MRGI_CHECK(mrgi_voxel_fit_depth_range(turned, box_x, clip, range, &err) == MRGI_OK);
  MRGI_CHECK(fabs(range[0] - 9.8) < 1e-12 && fabs(range[1] - 30.2) < 1e-12);
  /* clipped to the clipping range */
  const double tight[2] = { 12.0, 20.0 };
  MRGI_CHECK(mrgi_voxel_fit_depth_range(identity, fit_box, tight, range, &err) == MRGI_OK);
  MRGI_CHECK(range[0] == 12.0 && range[1] == 20.0);
  /* VTK's uninitialised bounds, a non-finite box, a box behind the camera, a flat box */
  const double empty[6] = { 1, -1, 1, -1, 1, -1 };
  const double nan_box[6] = { 0, 1, 0, 1, NAN, 1 };
  const double behind[6] = { -1, 1, -1, 1, 10, 20 };
  const double flat[6] = { -1, 1, -1, 1, -10, -10 };
  const double* fallbacks[4] = { empty, nan_box, behind, flat };
  for (int k = 0; k < 4; ++k)
  {
    MRGI_CHECK(mrgi_voxel_fit_depth_range(identity, fallbacks[k], clip, range, &err) == MRGI_OK);
    MRGI_CHECK(range[0] == clip[0] && range[1] == clip[1]);
  }
  /* errors */
  const double reversed[2] = { 5.0, 1.0 };
  const double bad_matrix[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, NAN, 0, 0, 0, 0, 1 };
  MRGI_CHECK(mrgi_voxel_fit_depth_range(identity, fit_box, reversed, range, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "clipping range") != NULL);
  MRGI_CHECK(mrgi_voxel_fit_depth_range(bad_matrix, fit_box, clip, range, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "not finite") != NULL);
  MRGI_CHECK(mrgi_voxel_fit_depth_range(NULL, fit_box, clip, range, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
}

/* The per-pixel clamp of the voxelization (mrgi_voxel.h section 5): the
 * depths of the triangle clipped to the pixel square, for parallel (depth
 * linear in screen space) and perspective (1 / depth linear) triangles; a
 * pixel cut by an edge keeps only the triangle's side; outside: none. */
/* Eye-space width of one voxel pixel at depth d, measured through
 * mrgi_voxel_project() (section 4), not through the formula under test. */
static double measured_pixel_width(const mrgi_voxel_projection* p, int32_t vw, int32_t vh,
  double near_depth, double far_depth, double d)
{
  mrgi_voxel_grid grid;
  MRGI_CHECK(mrgi_voxel_grid_init(
               &grid, vw, vh, MRGI_VOXEL_DEFAULT_SLICES, near_depth, far_depth, NULL) == MRGI_OK);
  const float a[3] = { 0.0f, 0.0f, (float)-d };
  const float b[3] = { 1.0f, 0.0f, (float)-d };
  float ua[3], ub[3];
  MRGI_CHECK(mrgi_voxel_project(&grid, p, a, ua) == 1 && mrgi_voxel_project(&grid, p, b, ub) == 1);
  return 1.0 / (double)(ub[0] - ua[0]);
}

static void test_isotropic_size(void)
{
  mrgi_error err;
  int32_t size[2];
  /* A Cornell box seen from the front (cornell-area's camera and fitted
   * range) and the same at twice the width: voxel pixels as wide as a slice
   * is deep at the middle depth, up to the rounding to the step. */
  const mrgi_multires_projection cam = { 0, 39.3, 0.0 };
  const double aspects[2] = { 1.0, 2.0 };
  for (int k = 0; k < 2; ++k)
  {
    mrgi_voxel_projection p;
    MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &cam, aspects[k], NULL) == MRGI_OK);
    const double near_depth = 794.0, far_depth = 1365.0;
    MRGI_CHECK(mrgi_voxel_isotropic_size(
                 &p, MRGI_VOXEL_DEFAULT_SLICES, near_depth, far_depth, size, &err) == MRGI_OK);
    MRGI_CHECK(size[0] % MRGI_VOXEL_AUTO_STEP == 0 && size[1] % MRGI_VOXEL_AUTO_STEP == 0);
    MRGI_CHECK(size[1] > MRGI_VOXEL_AUTO_MIN_SIZE && size[0] < MRGI_VOXEL_AUTO_MAX_SIZE);
    const double slice = (far_depth - near_depth) / MRGI_VOXEL_DEFAULT_SLICES;
    const double width =
      measured_pixel_width(&p, size[0], size[1], near_depth, far_depth, 0.5 * (near_depth + far_depth));
    /* Rounding to the step moves the side by at most half a step. */
    MRGI_CHECK(fabs(width / slice - 1.0) <= 0.5 * MRGI_VOXEL_AUTO_STEP / size[0] + 1e-4);
    MRGI_CHECK(abs(size[0] - (int32_t)lround(aspects[k] * size[1])) <= MRGI_VOXEL_AUTO_STEP);
  }
  /* A room seen from inside (thick slices): the least side; a thin slab
   * seen from far away (thin slices): the largest. */
  const mrgi_multires_projection wide = { 0, 55.0, 0.0 };
  mrgi_voxel_projection p;
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &wide, 1.0, NULL) == MRGI_OK);
  MRGI_CHECK(
    mrgi_voxel_isotropic_size(&p, MRGI_VOXEL_DEFAULT_SLICES, 0.01, 5.6, size, &err) == MRGI_OK);
  MRGI_CHECK(size[0] == MRGI_VOXEL_AUTO_MIN_SIZE && size[1] == MRGI_VOXEL_AUTO_MIN_SIZE);
  MRGI_CHECK(mrgi_voxel_isotropic_size(&p, MRGI_VOXEL_DEFAULT_SLICES, 1000.0, 1000.5, size, &err) ==
    MRGI_OK);
  MRGI_CHECK(size[0] == MRGI_VOXEL_AUTO_MAX_SIZE && size[1] == MRGI_VOXEL_AUTO_MAX_SIZE);
  /* Parallel: the pixel is the same width at every depth. */
  const mrgi_multires_projection ortho = { 1, 0.0, 100.0 };
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &ortho, 1.0, NULL) == MRGI_OK);
  MRGI_CHECK(
    mrgi_voxel_isotropic_size(&p, MRGI_VOXEL_DEFAULT_SLICES, -50.0, 78.0, size, &err) == MRGI_OK);
  MRGI_CHECK(size[0] > MRGI_VOXEL_AUTO_MIN_SIZE && size[0] < MRGI_VOXEL_AUTO_MAX_SIZE);
  const double slice = 128.0 / MRGI_VOXEL_DEFAULT_SLICES;
  const double width = measured_pixel_width(&p, size[0], size[1], -50.0, 78.0, 10.0);
  MRGI_CHECK(fabs(width / slice - 1.0) <= 0.5 * MRGI_VOXEL_AUTO_STEP / size[0] + 1e-4);
  /* Errors name the problem and leave the output alone. */
  size[0] = size[1] = -7;
  MRGI_CHECK(mrgi_voxel_isotropic_size(&p, MRGI_VOXEL_DEFAULT_SLICES, 5.0, 5.0, size, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "depth range") != NULL && size[0] == -7);
  MRGI_CHECK(mrgi_voxel_isotropic_size(&p, MRGI_VOXEL_DEFAULT_SLICES, NAN, 5.0, size, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_isotropic_size(NULL, MRGI_VOXEL_DEFAULT_SLICES, 1.0, 5.0, size, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_isotropic_size(&p, MRGI_VOXEL_DEFAULT_SLICES, 1.0, 5.0, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_voxel_projection_from_camera(&p, &wide, 1.0, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_voxel_isotropic_size(&p, MRGI_VOXEL_DEFAULT_SLICES, -10.0, 4.0, size, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "in front of the eye") != NULL && size[0] == -7);
}

static void test_triangle_pixel_range(void)
{
  const float u[3] = { 0.0f, 10.0f, 0.0f };
  const float v[3] = { 0.0f, 0.0f, 10.0f };
  const float ones[3] = { 1.0f, 1.0f, 1.0f };
  const float linear[3] = { 100.0f, 110.0f, 100.0f }; /* parallel: d = 100 + u */
  float r[2];
  MRGI_CHECK(mrgi_voxel_triangle_pixel_range(u, v, linear, ones, 2, 3, r) == 1);
  MRGI_CHECK(fabsf(r[0] - 102.0f) < 1e-4f && fabsf(r[1] - 103.0f) < 1e-4f);
  /* the hypotenuse u + v = 10 cuts pixel (9, 0): only u in [9, 10] inside */
  MRGI_CHECK(mrgi_voxel_triangle_pixel_range(u, v, linear, ones, 9, 0, r) == 1);
  MRGI_CHECK(fabsf(r[0] - 109.0f) < 1e-4f && fabsf(r[1] - 110.0f) < 1e-4f);
  /* pixel (9, 5) lies beyond the hypotenuse */
  r[0] = r[1] = -1.0f;
  MRGI_CHECK(mrgi_voxel_triangle_pixel_range(u, v, linear, ones, 9, 5, r) == 0);
  MRGI_CHECK(r[0] == -1.0f && r[1] == -1.0f);
  MRGI_CHECK(mrgi_voxel_triangle_pixel_range(u, v, linear, ones, 20, 20, r) == 0);
  /* perspective: w = d, 1/d linear in screen space: 1/d(u) = 1/100 - u / 2000 */
  const float d[3] = { 100.0f, 200.0f, 100.0f };
  MRGI_CHECK(mrgi_voxel_triangle_pixel_range(u, v, d, d, 4, 0, r) == 1);
  MRGI_CHECK(fabsf(r[0] - 125.0f) < 1e-3f && fabsf(r[1] - 400.0f / 3.0f) < 1e-3f);
  /* an edge-on face's skirt: the whole triangle spans [100, 200], a pixel
   * at its near end only [100, 1 / (1/100 - 1/2000)] */
  MRGI_CHECK(mrgi_voxel_triangle_pixel_range(u, v, d, d, 0, 9, r) == 1);
  MRGI_CHECK(fabsf(r[0] - 100.0f) < 1e-3f && fabsf(r[1] - 2000.0f / 19.0f) < 1e-3f);
  /* a vertex at or behind the eye: no answer (the caller's fallback) */
  const float behind[3] = { 100.0f, -5.0f, 100.0f };
  MRGI_CHECK(mrgi_voxel_triangle_pixel_range(u, v, d, behind, 4, 0, r) == 0);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_samples_per_batch),
    MRGI_TEST_CASE(test_step_bound),
    MRGI_TEST_CASE(test_layout),
    MRGI_TEST_CASE(test_fit_depth_range),
    MRGI_TEST_CASE(test_isotropic_size),
    MRGI_TEST_CASE(test_triangle_pixel_range),
    MRGI_TEST_CASE(test_grid_errors),
    MRGI_TEST_CASE(test_voxelize),
    MRGI_TEST_CASE(test_march_walls),
    MRGI_TEST_CASE(test_march_thin_wall),
    MRGI_TEST_CASE(test_march_grazing),
    MRGI_TEST_CASE(test_march_offset_direction),
    MRGI_TEST_CASE(test_march_extremes),
    MRGI_TEST_CASE(test_march_symmetry),
    MRGI_TEST_CASE(test_masks_and_metric),
    MRGI_TEST_CASE(test_incremental),
    MRGI_TEST_CASE(test_screen_side),
    MRGI_TEST_CASE(test_incremental_guard),
    MRGI_TEST_CASE(test_vsm),
    MRGI_TEST_CASE(test_vsm_specular_moments),
    MRGI_TEST_CASE(test_random_scenes),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
