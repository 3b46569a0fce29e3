/* Shadow factors from shadow-map views (mrgi_direct_shadow.h) on analytic
 * scenes whose maps are ray-cast here: a square occluder over a plane, a
 * plane at 85 degrees, invalid texels, cube faces, scale invariance and
 * degenerate input. */
#include "mrgi_direct_shadow.h"

#include "mrgi_buffers.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>

#define S 256

/* A scene: the plane z = 0 (normal +z) and optionally a square
 * |x|, |y| <= half at height h, both scaled by `scale`; or a plane through
 * the origin with normal `tilt`. */
typedef struct scene
{
  double scale;
  int plane;
  int occluder;
  double half, height;
  int tilted;
  double tilt[3];
} scene;

/* Nearest hit t > 0 of origin + t dir; 0 when nothing. */
static double scene_hit(const scene* sc, const double o[3], const double d[3])
{
  double best = 0.0;
  if (sc->plane && d[2] != 0.0)
  {
    const double t = -o[2] / d[2];
    if (t > 0.0)
    {
      best = t;
    }
  }
  if (sc->occluder && d[2] != 0.0)
  {
    const double t = (sc->height * sc->scale - o[2]) / d[2];
    const double x = o[0] + t * d[0], y = o[1] + t * d[1];
    if (t > 0.0 && fabs(x) <= sc->half * sc->scale && fabs(y) <= sc->half * sc->scale &&
      (best == 0.0 || t < best))
    {
      best = t;
    }
  }
  if (sc->tilted)
  {
    const double den = sc->tilt[0] * d[0] + sc->tilt[1] * d[1] + sc->tilt[2] * d[2];
    const double t = den != 0.0 ? -(sc->tilt[0] * o[0] + sc->tilt[1] * o[1] + sc->tilt[2] * o[2]) / den : 0.0;
    if (t > 0.0 && (best == 0.0 || t < best))
    {
      best = t;
    }
  }
  return best;
}

/* world_to_view of a camera at `eye` looking along `dir` with `up` (column-major). */
static void look_at(const double eye[3], const double dir[3], const double up[3], double m[16])
{
  double z[3] = { -dir[0], -dir[1], -dir[2] };
  double zn = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
  for (int k = 0; k < 3; ++k)
  {
    z[k] /= zn;
  }
  double x[3] = { up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0] };
  double xn = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (int k = 0; k < 3; ++k)
  {
    x[k] /= xn;
  }
  const double y[3] = { z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0] };
  const double* rows[3] = { x, y, z };
  for (int r = 0; r < 3; ++r)
  {
    m[r] = rows[r][0];
    m[4 + r] = rows[r][1];
    m[8 + r] = rows[r][2];
    m[12 + r] = -(rows[r][0] * eye[0] + rows[r][1] * eye[1] + rows[r][2] * eye[2]);
  }
  m[3] = m[7] = m[11] = 0.0;
  m[15] = 1.0;
}

/* Ray-cast the view's positions (the view's matrix is rigid: rows are the axes). */
static void render_view(mrgi_direct_shadow_view* view, const scene* sc, float* positions)
{
  const double* m = view->world_to_view;
  /* eye = -R^T t */
  double eye[3];
  for (int k = 0; k < 3; ++k)
  {
    eye[k] = -(m[4 * k + 0] * m[12] + m[4 * k + 1] * m[13] + m[4 * k + 2] * m[14]);
  }
  for (int j = 0; j < view->size; ++j)
  {
    for (int i = 0; i < view->size; ++i)
    {
      const double cx = (i + 0.5) / view->size * 2.0 - 1.0, cy = (j + 0.5) / view->size * 2.0 - 1.0;
      double ov[3], dv[3];
      if (view->perspective)
      {
        ov[0] = ov[1] = ov[2] = 0.0;
        dv[0] = cx / view->scale[0];
        dv[1] = cy / view->scale[1];
        dv[2] = -1.0;
      }
      else
      {
        ov[0] = cx / view->scale[0];
        ov[1] = cy / view->scale[1];
        ov[2] = 0.0;
        dv[0] = dv[1] = 0.0;
        dv[2] = -1.0;
      }
      double o[3], d[3];
      for (int k = 0; k < 3; ++k)
      {
        /* view -> world: R^T v (+ eye for points) */
        o[k] = m[4 * k + 0] * ov[0] + m[4 * k + 1] * ov[1] + m[4 * k + 2] * ov[2] + eye[k];
        d[k] = m[4 * k + 0] * dv[0] + m[4 * k + 1] * dv[1] + m[4 * k + 2] * dv[2];
      }
      const double t = scene_hit(sc, o, d);
      float* q = positions + 4 * ((size_t)j * view->size + i);
      q[0] = (float)(o[0] + t * d[0]);
      q[1] = (float)(o[1] + t * d[1]);
      q[2] = (float)(o[2] + t * d[2]);
      q[3] = t > 0.0 ? MRGI_GBUFFER_VALID : 0.0f;
    }
  }
  view->positions = positions;
}

/* A spot-like view from (0, 0, 4 scale) looking down -z, 90 degrees. */
static void spot_view(mrgi_direct_shadow_view* view, double scale)
{
  const double eye[3] = { 0, 0, 4 * scale }, dir[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  look_at(eye, dir, up, view->world_to_view);
  view->perspective = 1;
  view->scale[0] = view->scale[1] = 1.0;
  view->near_plane = 0.01 * scale;
  view->size = S;
}

/* A directional light straight down: orthographic, half-width 2 scale. */
static void sun_view(mrgi_direct_shadow_view* view, double scale)
{
  const double eye[3] = { 0, 0, 4 * scale }, dir[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  look_at(eye, dir, up, view->world_to_view);
  view->perspective = 0;
  view->scale[0] = view->scale[1] = 1.0 / (2.0 * scale);
  view->near_plane = 0.0;
  view->size = S;
}

static float* g_positions;
static float* g_depth;

static double factor_at(const mrgi_direct_shadow_view* view, const mrgi_direct_shadow_params* p,
  double x, double y, double z, const double n[3], mrgi_direct_shadow_stats* stats)
{
  const double pt[3] = { x, y, z };
  const float* maps[1] = { g_depth };
  return mrgi_direct_shadow_factor(view, maps, 1, p, pt, n, stats);
}

static void setup(mrgi_direct_shadow_view* view, const scene* sc)
{
  if (!g_positions)
  {
    g_positions = (float*)malloc(sizeof(float) * 4 * S * S);
    g_depth = (float*)malloc(sizeof(float) * S * S);
  }
  render_view(view, sc, g_positions);
  MRGI_CHECK(mrgi_direct_shadow_depth_map(view, g_depth, (size_t)S * S, NULL) == MRGI_OK);
}

static const double up_normal[3] = { 0, 0, 1 };

/* Umbra where the segment to the light is blocked, lit well outside, both modes, both kinds of view. */
static void test_umbra_and_lit(void)
{
  for (int kind = 0; kind < 2; ++kind)
  {
    mrgi_direct_shadow_view view;
    kind == 0 ? spot_view(&view, 1.0) : sun_view(&view, 1.0);
    const scene sc = { 1.0, 1, 1, 0.5, 1.0, 0, { 0, 0, 0 } };
    setup(&view, &sc);
    for (int mode = 0; mode < 2; ++mode)
    {
      mrgi_direct_shadow_params p;
      mrgi_direct_shadow_params_default(&p);
      p.mode = mode;
      p.light_radius = 0.05;
      mrgi_direct_shadow_stats st = { 0, 0, 0 };
      MRGI_CHECK_NEAR(factor_at(&view, &p, 0, 0, 0, up_normal, &st), 0.0, 0.0);
      MRGI_CHECK_NEAR(factor_at(&view, &p, 0.3, -0.2, 0, up_normal, &st), 0.0, 0.0);
      MRGI_CHECK_NEAR(factor_at(&view, &p, 1.5, 0, 0, up_normal, &st), 1.0, 0.0);
      MRGI_CHECK_NEAR(factor_at(&view, &p, -1.2, 1.0, 0, up_normal, &st), 1.0, 0.0);
      /* the occluder's top is lit */
      MRGI_CHECK_NEAR(factor_at(&view, &p, 0.1, 0.1, 1.0, up_normal, &st), 1.0, 0.0);
      MRGI_CHECK(st.invalid_receivers == 0 && st.invalid_views == 0 && st.outside == 0);
    }
  }
}

/* Width (world) of the region along +x at y = 0 where 0.02 < factor < 0.98. */
static double penumbra_width(const mrgi_direct_shadow_view* view, double radius, int side)
{
  mrgi_direct_shadow_params p;
  mrgi_direct_shadow_params_default(&p);
  p.light_radius = radius;
  p.samples_side = side;
  const int steps = 2000;
  const double x0 = 0.2, x1 = 1.4;
  int inside = 0;
  double previous = 0.0;
  for (int k = 0; k <= steps; ++k)
  {
    const double x = x0 + (x1 - x0) * k / steps;
    const double f = factor_at(view, &p, x, 0.0, 0.0, up_normal, NULL);
    MRGI_CHECK(f >= 0.0 && f <= 1.0);
    /* the factor rises monotonically out of the shadow (within one tap) */
    MRGI_CHECK(f >= previous - 1.0 / (side * side) - 1e-12);
    previous = f > previous ? f : previous;
    inside += f > 0.02 && f < 0.98;
  }
  return inside * (x1 - x0) / steps;
}

/* The penumbra grows with the light radius, is near the analytic width, and vanishes with it. */
static void test_penumbra_width(void)
{
  mrgi_direct_shadow_view view;
  spot_view(&view, 1.0);
  const scene sc = { 1.0, 1, 1, 0.5, 1.0, 0, { 0, 0, 0 } };
  setup(&view, &sc);
  const double radii[4] = { 1e-6, 0.05, 0.15, 0.3 };
  double widths[4];
  for (int k = 0; k < 4; ++k)
  {
    widths[k] = penumbra_width(&view, radii[k], MRGI_DIRECT_SHADOW_MAX_SIDE);
    printf("light radius %g: penumbra width %.4f (analytic, disc light: %.4f)\n", radii[k],
      widths[k], 2.0 * radii[k] / 3.0);
  }
  const double footprint = 4.0 * 2.0 / S; /* texel footprint at the plane */
  MRGI_CHECK(widths[0] <= 2.0 * footprint);
  MRGI_CHECK(widths[1] < widths[2] && widths[2] < widths[3]);
  for (int k = 1; k < 4; ++k)
  {
    const double analytic = 2.0 * radii[k] / 3.0;
    MRGI_CHECK(widths[k] > 0.5 * analytic && widths[k] < 1.5 * analytic + 2.0 * footprint);
  }
  /* a directional light: width grows with the angular radius too */
  sun_view(&view, 1.0);
  setup(&view, &sc);
  const double w1 = penumbra_width(&view, 0.05, 8), w2 = penumbra_width(&view, 0.2, 8);
  printf("directional: radius 0.05 -> %.4f, 0.2 -> %.4f\n", w1, w2);
  MRGI_CHECK(w1 < w2);
}

/* The same scene scaled by 1e-3 and 1e3 gives the same factors. */
static void test_scale_invariance(void)
{
  const double scales[2] = { 1e-3, 1e3 };
  for (int kind = 0; kind < 2; ++kind)
  {
    for (int mode = 0; mode < 2; ++mode)
    {
      double reference[400];
      for (int s = -1; s < 2; ++s)
      {
        const double scale = s < 0 ? 1.0 : scales[s];
        mrgi_direct_shadow_view view;
        kind == 0 ? spot_view(&view, scale) : sun_view(&view, scale);
        const scene sc = { scale, 1, 1, 0.5, 1.0, 0, { 0, 0, 0 } };
        setup(&view, &sc);
        mrgi_direct_shadow_params p;
        mrgi_direct_shadow_params_default(&p);
        p.mode = mode;
        p.light_radius = 0.1 * scale;
        int differ = 0;
        double worst = 0.0;
        for (int k = 0; k < 400; ++k)
        {
          const double x = (0.3 + 1.0 * (k % 20) / 20.0) * scale, y = (0.02 * (k / 20)) * scale;
          const double f = factor_at(&view, &p, x, y, 0.0, up_normal, NULL);
          if (s < 0)
          {
            reference[k] = f;
            continue;
          }
          const double e = fabs(f - reference[k]);
          differ += e > 1e-9;
          worst = e > worst ? e : worst;
        }
        if (s >= 0)
        {
          printf("kind %d mode %d scale %g: %d of 400 differ, worst %g\n", kind, mode, scale,
            differ, worst);
          /* float positions round differently at other scales: a tap may flip at a texel boundary */
          MRGI_CHECK(differ <= 8);
          MRGI_CHECK(worst <= 2.0 / 9.0 + 1e-12);
        }
      }
    }
  }
}

/* A plane at 85 degrees to the light does not shadow itself (perspective and orthographic, both modes). */
static void test_grazing_plane(void)
{
  const double a = 85.0 * 3.14159265358979323846 / 180.0;
  const scene sc = { 1.0, 0, 0, 0, 0, 1, { sin(a), 0.0, cos(a) } };
  const double n[3] = { sin(a), 0.0, cos(a) };
  for (int kind = 0; kind < 2; ++kind)
  {
    mrgi_direct_shadow_view view;
    kind == 0 ? spot_view(&view, 1.0) : sun_view(&view, 1.0);
    setup(&view, &sc);
    for (int mode = 0; mode < 2; ++mode)
    {
      mrgi_direct_shadow_params p;
      mrgi_direct_shadow_params_default(&p);
      p.mode = mode;
      p.light_radius = 0.2;
      p.samples_side = MRGI_DIRECT_SHADOW_MAX_SIDE;
      double worst = 1.0;
      for (int k = 0; k < 200; ++k)
      {
        /* points on the plane near the light's axis: y free, x z on the plane's line */
        const double y = -0.3 + 0.6 * (k % 20) / 19.0;
        const double s = -0.05 + 0.1 * (k / 20) / 9.0; /* along the plane's slope direction */
        const double x = s * cos(a), z = -s * sin(a);
        const double f = factor_at(&view, &p, x, y, z, n, NULL);
        worst = f < worst ? f : worst;
      }
      printf("85 degrees, kind %d mode %d: smallest factor %g\n", kind, mode, worst);
      MRGI_CHECK(worst == 1.0);
    }
  }
}

/* Receivers nearly edge-on to the light: under an occluder the umbra fades
 * out below twice the clamp's cosine and is gone below it (no stripes of
 * self-shadowing on lit grazing faces); a receiver facing the light keeps it. */
static void test_grazing_fade(void)
{
  const double c0 =
    1.0 / sqrt(1.0 + MRGI_DIRECT_SHADOW_MAX_SLOPE * MRGI_DIRECT_SHADOW_MAX_SLOPE);
  MRGI_CHECK(mrgi_direct_shadow_grazing_weight(0.0) == 0.0);
  MRGI_CHECK(mrgi_direct_shadow_grazing_weight(c0) == 0.0);
  MRGI_CHECK_NEAR(mrgi_direct_shadow_grazing_weight(1.5 * c0), 0.5, 1e-12);
  MRGI_CHECK(mrgi_direct_shadow_grazing_weight(2.0 * c0) == 1.0);
  MRGI_CHECK(mrgi_direct_shadow_grazing_weight(1.0) == 1.0);
  mrgi_direct_shadow_view view;
  sun_view(&view, 1.0);
  const scene sc = { 1.0, 1, 1, 0.5, 1.0, 0, { 0, 0, 0 } };
  setup(&view, &sc);
  const double cosines[3] = { 0.5 * c0, 1.5 * c0, 0.2 };
  const double expected[3] = { 1.0, 0.5, 0.0 };
  for (int mode = 0; mode < 2; ++mode)
  {
    mrgi_direct_shadow_params p;
    mrgi_direct_shadow_params_default(&p);
    p.mode = mode;
    p.light_radius = 0.05;
    for (int k = 0; k < 3; ++k)
    {
      const double n[3] = { sqrt(1.0 - cosines[k] * cosines[k]), 0.0, cosines[k] };
      const double f = factor_at(&view, &p, 0.0, 0.0, 0.0, n, NULL);
      printf("grazing cosine %.4f, mode %d: factor %g\n", cosines[k], mode, f);
      MRGI_CHECK_NEAR(f, expected[k], 1e-9);
    }
  }
}

/* An occluder 3 texel footprints above the plane still casts its umbra (no peter panning beyond ~2 texels). */
static void test_contact(void)
{
  mrgi_direct_shadow_view view;
  spot_view(&view, 1.0);
  const double footprint = 4.0 * 2.0 / S;
  const scene sc = { 1.0, 1, 1, 0.5, 3.0 * footprint, 0, { 0, 0, 0 } };
  setup(&view, &sc);
  mrgi_direct_shadow_params p;
  mrgi_direct_shadow_params_default(&p);
  p.mode = MRGI_DIRECT_SHADOW_HARD;
  MRGI_CHECK(factor_at(&view, &p, 0.0, 0.0, 0.0, up_normal, NULL) == 0.0);
  /* the shadow reaches the occluder's edge to within 2 footprints */
  MRGI_CHECK(factor_at(&view, &p, 0.5 - 2.0 * footprint, 0.0, 0.0, up_normal, NULL) == 0.0);
}

/* Invalid texels (w = 0, NaN or Inf positions) never shadow. */
static void test_invalid_texels(void)
{
  mrgi_direct_shadow_view view;
  spot_view(&view, 1.0);
  const scene sc = { 1.0, 1, 1, 0.5, 1.0, 0, { 0, 0, 0 } };
  for (int variant = 0; variant < 3; ++variant)
  {
    render_view(&view, &sc, g_positions);
    for (size_t t = 0; t < (size_t)S * S; ++t)
    {
      float* q = g_positions + 4 * t;
      if (q[2] > 0.5f) /* the occluder's texels */
      {
        if (variant == 0)
        {
          q[3] = 0.0f;
        }
        else
        {
          q[variant == 1 ? 0 : 2] = variant == 1 ? NAN : INFINITY;
        }
      }
    }
    MRGI_CHECK(mrgi_direct_shadow_depth_map(&view, g_depth, (size_t)S * S, NULL) == MRGI_OK);
    for (int mode = 0; mode < 2; ++mode)
    {
      mrgi_direct_shadow_params p;
      mrgi_direct_shadow_params_default(&p);
      p.mode = mode;
      p.light_radius = 0.1;
      MRGI_CHECK(factor_at(&view, &p, 0.0, 0.0, 0.0, up_normal, NULL) == 1.0);
      MRGI_CHECK(factor_at(&view, &p, 0.6, 0.1, 0.0, up_normal, NULL) == 1.0);
    }
  }
}

/* The six cube faces (as vtkMRGIReflectiveShadowMapPass builds them) partition every direction. */
static void test_cube_faces(void)
{
  static const double faces[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 },
    { 0, 0, 1 }, { 0, 0, -1 } };
  static const float dummy[4] = { 0, 0, 0, 0 };
  mrgi_direct_shadow_view views[6];
  const double light[3] = { 0.25, -0.5, 2.0 };
  for (int v = 0; v < 6; ++v)
  {
    const double y[3] = { 0, 1, 0 }, x[3] = { 1, 0, 0 };
    look_at(light, faces[v], fabs(faces[v][1]) < 0.9 ? y : x, views[v].world_to_view);
    views[v].perspective = 1;
    views[v].scale[0] = views[v].scale[1] = 1.0; /* 90 degrees */
    views[v].near_plane = 1e-3;
    views[v].size = 16;
    views[v].positions = dummy; /* only the selection is tested */
  }
  unsigned seed = 12345u;
  int counts[6] = { 0, 0, 0, 0, 0, 0 };
  for (int k = 0; k < 20000; ++k)
  {
    double d[3];
    if (k < 26)
    {
      /* the axes, edges and corners of the cube: exact ties */
      const int code = k < 13 ? k : k + 1; /* skip (0,0,0) */
      d[0] = code % 3 - 1;
      d[1] = (code / 3) % 3 - 1;
      d[2] = code / 9 - 1;
    }
    else
    {
      for (int c = 0; c < 3; ++c)
      {
        seed = seed * 1664525u + 1013904223u;
        d[c] = (seed >> 8) / 8388608.0 - 1.0;
      }
    }
    const double p[3] = { light[0] + 3 * d[0], light[1] + 3 * d[1], light[2] + 3 * d[2] };
    const int v = mrgi_direct_shadow_select_view(views, 6, p, NULL);
    MRGI_CHECK(v >= 0 && v < 6);
    counts[v]++;
    /* the chosen face is the one of the (first) largest component */
    int major = 0;
    double m = -1.0;
    for (int c = 0; c < 3; ++c)
    {
      if (fabs(d[c]) > m + 1e-12)
      {
        m = fabs(d[c]);
        major = c;
      }
    }
    if (k >= 26)
    {
      MRGI_CHECK(v == 2 * major + (d[major] < 0 ? 1 : 0));
    }
    /* exactly one: no other face holds it with a smaller or equal c at a lower index */
    MRGI_CHECK(mrgi_direct_shadow_select_view(views + v, 1, p, NULL) == 0);
  }
  for (int v = 0; v < 6; ++v)
  {
    MRGI_CHECK(counts[v] > 2000);
  }
}

/* NaN receivers, degenerate views and bad parameters: factor 1, counted, or a clear error. */
static void test_degenerate(void)
{
  mrgi_direct_shadow_view view;
  spot_view(&view, 1.0);
  const scene sc = { 1.0, 1, 1, 0.5, 1.0, 0, { 0, 0, 0 } };
  setup(&view, &sc);
  mrgi_direct_shadow_params p;
  mrgi_direct_shadow_params_default(&p);
  mrgi_direct_shadow_stats st = { 0, 0, 0 };
  const double zero[3] = { 0, 0, 0 }, nan3[3] = { NAN, 0, 1 };
  MRGI_CHECK(factor_at(&view, &p, NAN, 0, 0, up_normal, &st) == 1.0);
  MRGI_CHECK(factor_at(&view, &p, 0, 0, INFINITY, up_normal, &st) == 1.0);
  MRGI_CHECK(factor_at(&view, &p, 0, 0, 0, zero, &st) == 1.0);
  MRGI_CHECK(factor_at(&view, &p, 0, 0, 0, nan3, &st) == 1.0);
  MRGI_CHECK(st.invalid_receivers == 4);
  /* outside the frustum, behind the light */
  MRGI_CHECK(factor_at(&view, &p, 0, 0, 10, up_normal, &st) == 1.0);
  MRGI_CHECK(factor_at(&view, &p, 100, 0, 0, up_normal, &st) == 1.0);
  MRGI_CHECK(st.outside == 2);
  mrgi_direct_shadow_view bad[4] = { view, view, view, view };
  bad[0].size = 0;
  bad[1].world_to_view[5] = NAN;
  bad[2].scale[0] = 0.0;
  bad[3].near_plane = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    MRGI_CHECK(!mrgi_direct_shadow_view_usable(&bad[k]));
    st.invalid_views = 0;
    MRGI_CHECK(factor_at(&bad[k], &p, 0, 0, 0, up_normal, &st) == 1.0);
    MRGI_CHECK(st.invalid_views == 1);
    MRGI_CHECK(mrgi_direct_shadow_depth_map(&bad[k], g_depth, (size_t)S * S, NULL) ==
      MRGI_ERR_INVALID_ARGUMENT);
  }
  MRGI_CHECK(mrgi_direct_shadow_depth_map(&view, g_depth, 10, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_error err;
  p.samples_side = MRGI_DIRECT_SHADOW_MAX_SIDE + 1;
  MRGI_CHECK(mrgi_direct_shadow_params_check(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "samples side") != NULL);
  p.samples_side = 4;
  p.light_radius = NAN;
  MRGI_CHECK(mrgi_direct_shadow_params_check(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.light_radius = -1.0;
  MRGI_CHECK(mrgi_direct_shadow_params_check(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  p.light_radius = 0.0;
  p.mode = 7;
  MRGI_CHECK(mrgi_direct_shadow_params_check(&p, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mode 7") != NULL);
  /* the G-buffer form: 2 pixels, one without geometry, one in the umbra */
  mrgi_direct_shadow_params_default(&p);
  p.mode = MRGI_DIRECT_SHADOW_HARD;
  const float pos[8] = { 0, 0, 0, 1, 5, 5, 5, 0 }, nor[8] = { 0, 0, 1, 1, 0, 0, 1, 1 };
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  float out[2] = { -1, -1 };
  MRGI_CHECK(mrgi_direct_shadow_gbuffer(2, 1, pos, nor, identity, &view, 1, &p, out, NULL, &err) == MRGI_OK);
  MRGI_CHECK(out[0] == 0.0f && out[1] == 1.0f);
  MRGI_CHECK(mrgi_direct_shadow_gbuffer(2, 1, pos, nor, identity, &view, 7, &p, out, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_direct_shadow_gbuffer(0, 1, pos, nor, identity, &view, 1, &p, out, NULL, &err) ==
    MRGI_ERR_INVALID_ARGUMENT);
  /* no views: everything lit */
  MRGI_CHECK(mrgi_direct_shadow_gbuffer(2, 1, pos, nor, identity, NULL, 0, &p, out, NULL, &err) == MRGI_OK);
  MRGI_CHECK(out[0] == 1.0f && out[1] == 1.0f);
}

/* BMR levels (mrgi_direct_shadow_level): on a random G-buffer (receivers on
 * the plane, some under the occluder, some without geometry, odd sizes),
 * level k texel (i, j) is 1 - the full-resolution factor of its block's
 * centre pixel, 0 without geometry; level 0 is 1 - the factors. */
static void test_levels(void)
{
  mrgi_direct_shadow_view view;
  spot_view(&view, 1.0);
  const scene sc = { 1.0, 1, 1, 0.5, 1.0, 0, { 0, 0, 0 } };
  setup(&view, &sc);
  enum { W = 45, H = 29 };
  static float pos[4 * W * H], nor[4 * W * H], full[W * H], level[W * H];
  unsigned state = 12345u;
  for (int t = 0; t < W * H; ++t)
  {
    double r[4];
    for (int k = 0; k < 4; ++k)
    {
      state = state * 1664525u + 1013904223u;
      r[k] = (double)(state >> 8) / (double)(1u << 24);
    }
    pos[4 * t + 0] = (float)(3.0 * r[0] - 1.5);
    pos[4 * t + 1] = (float)(3.0 * r[1] - 1.5);
    pos[4 * t + 2] = 0.0f;
    pos[4 * t + 3] = r[2] < 0.15 ? 0.0f : MRGI_GBUFFER_VALID;
    nor[4 * t + 0] = (float)(0.2 * (r[3] - 0.5));
    nor[4 * t + 1] = 0.0f;
    nor[4 * t + 2] = 1.0f;
    nor[4 * t + 3] = 1.0f;
  }
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  mrgi_error err;
  for (int mode = 0; mode < 2; ++mode)
  {
    mrgi_direct_shadow_params p;
    mrgi_direct_shadow_params_default(&p);
    p.mode = mode;
    p.light_radius = 0.05;
    MRGI_CHECK(mrgi_direct_shadow_gbuffer(W, H, pos, nor, identity, &view, 1, &p, full, NULL, &err) ==
      MRGI_OK);
    for (int k = 0; k <= 3; ++k)
    {
      MRGI_CHECK(mrgi_direct_shadow_level(W, H, k, pos, nor, identity, &view, 1, &p, level, NULL,
                   &err) == MRGI_OK);
      const int side = 1 << k, w = (W + side - 1) / side, h = (H + side - 1) / side;
      int shadowed = 0, lit = 0, empty = 0, bad = 0;
      for (int j = 0; j < h; ++j)
      {
        for (int i = 0; i < w; ++i)
        {
          const int x = i * side + side / 2 < W - 1 ? i * side + side / 2 : W - 1;
          const int y = j * side + side / 2 < H - 1 ? j * side + side / 2 : H - 1;
          const int t = y * W + x;
          const float got = level[j * w + i];
          const int valid = pos[4 * t + 3] > MRGI_GBUFFER_VALID_THRESHOLD;
          const double want = valid ? 1.0 - (double)full[t] : 0.0;
          bad += !(fabs(got - want) <= 1e-6);
          empty += !valid;
          shadowed += valid && got > 0.5f;
          lit += valid && got == 0.0f;
        }
      }
      MRGI_CHECK(bad == 0);
      MRGI_CHECK(shadowed > 0 && lit > 0 && (k > 1 || empty > 0));
    }
  }
  /* Levels out of range: a clear error. */
  mrgi_direct_shadow_params p;
  mrgi_direct_shadow_params_default(&p);
  MRGI_CHECK(mrgi_direct_shadow_level(W, H, -1, pos, nor, identity, &view, 1, &p, level, NULL,
               &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "level -1") != NULL);
  MRGI_CHECK(mrgi_direct_shadow_level(W, H, MRGI_DIRECT_SHADOW_MAX_LEVEL + 1, pos, nor, identity,
               &view, 1, &p, level, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_umbra_and_lit),
    MRGI_TEST_CASE(test_penumbra_width),
    MRGI_TEST_CASE(test_scale_invariance),
    MRGI_TEST_CASE(test_grazing_plane),
    MRGI_TEST_CASE(test_grazing_fade), MRGI_TEST_CASE(test_contact),
    MRGI_TEST_CASE(test_invalid_texels),
    MRGI_TEST_CASE(test_cube_faces),
    MRGI_TEST_CASE(test_degenerate),
    MRGI_TEST_CASE(test_levels),
  };
  const int status = MRGI_TEST_MAIN(argc, argv, cases);
  free(g_positions);
  free(g_depth);
  return status;
}
