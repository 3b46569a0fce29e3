/* Tests of the ground-truth renderer (mrgi_reference) against closed forms:
 * direct light of directional, tilted and spot lights; exact shadows; one
 * bounce from a uniformly lit parallel rectangle (Hottel's view factor);
 * secondary visibility on and off; the Cornell box; determinism, convergence
 * and bad input; area lights: the closed-form rectangle-to-point form factor
 * (with an emitter quad on the light, with and without visibility), an
 * occluder's umbra and penumbra, the no-visibility mode against the C
 * sample sum of mrgi_area_light_diffuse(); the per-pixel stopping rule (its
 * quantile against a sort, synthetic accumulators, the Cornell box where the
 * image-mean rule would stop after two passes). Tolerances of noisy quantities come from the standard
 * errors the renderer reports. The camera math below is written again from
 * vtkCamera's definition, independently of the renderer's. */
#include "mrgi_reference.h"
#include "mrgi_scene_cornell.h"
#include "mrgi_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

static int message_has(const mrgi_error* err, const char* text)
{
  if (!strstr(err->message, text))
  {
    fprintf(stderr, "message '%s' lacks '%s'\n", err->message, text);
    return 0;
  }
  return 1;
}

/* A horizontal square at height y, centred on (cx, cz), half-size `half`,
 * front side up or down, no vertex normals. */
static void make_square(mrgi_mesh* mesh, const char* name, double cx, double y, double cz,
                        double half, int facing_up, float albedo)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_mesh_create(mesh, name, 4, 2, 0, &err) == MRGI_OK);
  const float x0 = (float)(cx - half), x1 = (float)(cx + half);
  const float z0 = (float)(cz - half), z1 = (float)(cz + half);
  const float fy = (float)y;
  /* (x0,z1) (x1,z1) (x1,z0) (x0,z0): counter-clockwise seen from +y. */
  const float corners[4][3] = { { x0, fy, z1 }, { x1, fy, z1 }, { x1, fy, z0 }, { x0, fy, z0 } };
  memcpy(mesh->positions, corners, sizeof(corners));
  const uint32_t up[6] = { 0, 1, 2, 0, 2, 3 };
  const uint32_t down[6] = { 0, 2, 1, 0, 3, 2 };
  memcpy(mesh->indices, facing_up ? up : down, sizeof(up));
  mesh->albedo[0] = mesh->albedo[1] = mesh->albedo[2] = albedo;
}

/* Camera at height `height` above the origin looking straight down, image
 * right = +x, image top = -z (view_up -z). */
static void camera_down(mrgi_scene* scene, double height, double view_angle_deg)
{
  memset(&scene->camera, 0, sizeof(scene->camera));
  scene->camera.position[1] = height;
  scene->camera.view_up[2] = -1.0;
  scene->camera.view_angle_deg = view_angle_deg;
}

static void directional(mrgi_light* light, double dx, double dy, double dz, double intensity)
{
  memset(light, 0, sizeof(*light));
  light->type = MRGI_LIGHT_DIRECTIONAL;
  /* travels from position to focal point (the origin) */
  light->position[0] = -dx;
  light->position[1] = -dy;
  light->position[2] = -dz;
  light->color[0] = light->color[1] = light->color[2] = 1.0;
  light->intensity = intensity;
  light->cone_angle_deg = 90.0;
}

/* A spot light 5 above the origin aiming straight down, cone 30 degrees,
 * exponent 2, intensity 2: X = 2 (5/d)^3 on the floor inside r < 5 tan 30. */
static void spot_down(mrgi_light* spot)
{
  memset(spot, 0, sizeof(*spot));
  spot->type = MRGI_LIGHT_SPOT;
  spot->position[1] = 5.0;
  spot->color[0] = spot->color[1] = spot->color[2] = 1.0;
  spot->intensity = 2.0;
  spot->cone_angle_deg = 30.0;
  spot->exponent = 2.0;
}

/* Ground (y = 0) point under continuous image coordinates (px, py) of the
 * straight-down camera: vertical field of view, aspect = width / height. */
static void ground_point(double px, double py, int32_t width, int32_t height, double half_height,
                         double* x, double* z)
{
  const double sx = 2.0 * px / width - 1.0, sy = 1.0 - 2.0 * py / height;
  const double aspect = (double)width / height;
  *x = sx * aspect * half_height;
  *z = -sy * half_height;
}

static mrgi_reference_options base_options(int32_t width, int32_t height)
{
  mrgi_reference_options o;
  mrgi_reference_options_default(&o);
  o.width = width;
  o.height = height;
  o.indirect_samples = 0;
  o.max_passes = 1;
  o.target_relative_error = 0.0;
  return o;
}

static void render(const mrgi_scene* scene, const mrgi_reference_options* o,
                   mrgi_reference_result* r)
{
  mrgi_error err;
  const mrgi_status s = mrgi_reference_render(scene, o, r, &err);
  if (s)
  {
    fprintf(stderr, "render failed: %s\n", err.message);
  }
  MRGI_CHECK(s == MRGI_OK);
  int64_t bad = -1;
  MRGI_CHECK(mrgi_image_count_nonfinite(&r->direct, &bad, NULL) == MRGI_OK && bad == 0);
  MRGI_CHECK(mrgi_image_count_nonfinite(&r->indirect, &bad, NULL) == MRGI_OK && bad == 0);
  MRGI_CHECK(mrgi_image_count_nonfinite(&r->albedo, &bad, NULL) == MRGI_OK && bad == 0);
  MRGI_CHECK(mrgi_image_count_nonfinite(&r->indirect_stderr, &bad, NULL) == MRGI_OK && bad == 0);
  const size_t n = mrgi_image_value_count(&r->direct);
  for (size_t i = 0; i < n; ++i)
  {
    MRGI_CHECK(r->direct.pixels[i] >= 0.0f && r->indirect.pixels[i] >= 0.0f);
  }
}

/* ---- 1. direct light ---- */

static void test_direct(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_create(&scene, 1, NULL) == MRGI_OK);
  /* front side DOWN, away from camera and light: two-sided lighting lights
   * the side looked at all the same */
  make_square(&scene.meshes[0], "floor", 0, 0, 0, 10, 0, 0.5f);
  camera_down(&scene, 10, 60);
  scene.light_count = 1;
  mrgi_reference_result r;

  /* straight down, intensity 2, albedo 0.5: exactly 1 everywhere */
  directional(&scene.lights[0], 0, -1, 0, 2.0);
  mrgi_reference_options o = base_options(48, 32);
  render(&scene, &o, &r);
  for (int64_t i = 0; i < 48 * 32; ++i)
  {
    MRGI_CHECK(r.background[i] == 0);
    MRGI_CHECK_NEAR(r.direct.pixels[3 * i], 1.0, 1e-6);
    MRGI_CHECK_NEAR(r.direct.pixels[3 * i + 2], 1.0, 1e-6);
    MRGI_CHECK_NEAR(r.albedo.pixels[3 * i + 1], 0.5, 1e-7);
    MRGI_CHECK(r.indirect.pixels[3 * i] == 0.0f);
  }
  MRGI_CHECK(r.passes == 1 && r.rays_traced == 2 * 48 * 32 && r.skipped_triangles == 0);
  mrgi_reference_result_destroy(&r);

  /* 60 degrees off the normal: 0.5 * 2 * cos 60 */
  directional(&scene.lights[0], sin(pi / 3), -cos(pi / 3), 0, 2.0);
  render(&scene, &o, &r);
  for (int64_t i = 0; i < 48 * 32; ++i)
  {
    MRGI_CHECK_NEAR(r.direct.pixels[3 * i + 1], 0.5 * 2.0 * cos(pi / 3), 1e-6);
  }
  mrgi_reference_result_destroy(&r);

  /* vertex normals (VTK shades with them): tilted 60 degrees from the front
   * normal (down), seen from above, so flipped: n.l = cos 60 with the light
   * straight down; the geometric normal gives 1 */
  {
    mrgi_mesh* floor_mesh = &scene.meshes[0];
    mrgi_mesh with_normals;
    MRGI_CHECK(mrgi_mesh_create(&with_normals, "floor", 4, 2, 1, NULL) == MRGI_OK);
    memcpy(with_normals.positions, floor_mesh->positions, 12 * sizeof(float));
    memcpy(with_normals.indices, floor_mesh->indices, 6 * sizeof(uint32_t));
    for (int v = 0; v < 4; ++v)
    {
      with_normals.normals[3 * v + 0] = (float)sin(pi / 3);
      with_normals.normals[3 * v + 1] = (float)-cos(pi / 3);
      with_normals.normals[3 * v + 2] = 0.0f;
    }
    with_normals.albedo[0] = with_normals.albedo[1] = with_normals.albedo[2] = 0.5f;
    mrgi_mesh_destroy(floor_mesh);
    *floor_mesh = with_normals;
    directional(&scene.lights[0], 0, -1, 0, 2.0);
    for (int shading = 0; shading < 2; ++shading)
    {
      o.shading_normals = shading;
      render(&scene, &o, &r);
      for (int64_t i = 0; i < 48 * 32; ++i)
      {
        MRGI_CHECK_NEAR(r.direct.pixels[3 * i], shading ? cos(pi / 3) : 1.0, 1e-6);
      }
      mrgi_reference_result_destroy(&r);
    }
    /* from here on: the flat front normal (down), flipped to the side seen */
    for (int v = 0; v < 4; ++v)
    {
      floor_mesh->normals[3 * v + 0] = 0.0f;
      floor_mesh->normals[3 * v + 1] = -1.0f;
    }
  }

  /* spot light 5 above the floor, cone 30 deg, exponent 2, intensity 2:
   * X = 2 * (5/d) * (5/d)^2 inside r < 5 tan 30, 0 outside. A 2:1 image
   * checks that the view angle is the vertical one. */
  spot_down(&scene.lights[0]);
  o = base_options(96, 48);
  o.pixel_samples = 4;
  render(&scene, &o, &r);
  const double cone_r = 5.0 * tan(pi / 6), half_h = 10.0 * tan(pi / 6);
  int inside = 0, outside = 0;
  for (int32_t y = 0; y < 48; ++y)
  {
    for (int32_t x = 0; x < 96; ++x)
    {
      double x0, z0, x1, z1;
      ground_point(x, y, 96, 48, half_h, &x0, &z0);
      ground_point(x + 1, y + 1, 96, 48, half_h, &x1, &z1);
      /* nearest and farthest points of the pixel's footprint from the axis */
      const double nx = (x0 < 0 && x1 > 0) ? 0 : fmin(fabs(x0), fabs(x1));
      const double nz = (z0 > 0 && z1 < 0) ? 0 : fmin(fabs(z0), fabs(z1));
      const double fx = fmax(fabs(x0), fabs(x1)), fz = fmax(fabs(z0), fabs(z1));
      const double r_min = sqrt(nx * nx + nz * nz), r_max = sqrt(fx * fx + fz * fz);
      const double v = mrgi_image_at(&r.direct, x, y)[0];
      if (r_max < cone_r)
      {
        const double lo = 0.5 * 2.0 * pow(5.0 / sqrt(25.0 + r_max * r_max), 3.0);
        const double hi = 0.5 * 2.0 * pow(5.0 / sqrt(25.0 + r_min * r_min), 3.0);
        MRGI_CHECK(v >= lo - 1e-6 && v <= hi + 1e-6);
        ++inside;
      }
      else if (r_min > cone_r)
      {
        MRGI_CHECK(v == 0.0);
        ++outside;
      }
    }
  }
  MRGI_CHECK(inside > 100 && outside > 1000);
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

/* ---- 2. shadows ---- */

/* A floor under a 2x2 occluder at height 2, seen from 10 above, lit by a
 * directional light travelling down and towards -x at 45 degrees: the
 * occluder's shadow is x in [-3, -1], z in [-1, 1]. */
static void make_shadow_scene(mrgi_scene* scene)
{
  MRGI_CHECK(mrgi_scene_create(scene, 2, NULL) == MRGI_OK);
  make_square(&scene->meshes[0], "floor", 0, 0, 0, 10, 1, 0.5f);
  make_square(&scene->meshes[1], "occluder", 0, 2, 0, 1, 1, 0.5f);
  camera_down(scene, 10, 60);
  scene->light_count = 1;
  directional(&scene->lights[0], -1, -1, 0, 2.0);
}

static void test_shadows(void)
{
  mrgi_scene scene;
  make_shadow_scene(&scene);
  const double lit = 0.5 * 2.0 * cos(pi / 4);
  const double half_h = 10.0 * tan(pi / 6);
  for (int shadows = 0; shadows < 2; ++shadows)
  {
    mrgi_reference_options o = base_options(64, 64);
    o.shadows = shadows;
    mrgi_reference_result r;
    render(&scene, &o, &r);
    int in_shadow = 0, on_floor = 0, on_occluder = 0;
    for (int32_t y = 0; y < 64; ++y)
    {
      for (int32_t x = 0; x < 64; ++x)
      {
        double x0, z0, x1, z1;
        ground_point(x, y, 64, 64, half_h, &x0, &z0);
        ground_point(x + 1, y + 1, 64, 64, half_h, &x1, &z1);
        const double lo_x = fmin(x0, x1), hi_x = fmax(x0, x1);
        const double lo_z = fmin(z0, z1), hi_z = fmax(z0, z1);
        const double v = mrgi_image_at(&r.direct, x, y)[0];
        /* the camera sees the occluder where the ground point scaled by 0.8 is inside it */
        const int hides = 0.8 * hi_x > -1.0 && 0.8 * lo_x < 1.0 && 0.8 * hi_z > -1.0 &&
                          0.8 * lo_z < 1.0;
        const int occluder = 0.8 * lo_x > -1.0 && 0.8 * hi_x < 1.0 && 0.8 * lo_z > -1.0 &&
                             0.8 * hi_z < 1.0;
        const int shadow = lo_x > -3.0 && hi_x < -1.0 && lo_z > -1.0 && hi_z < 1.0;
        const int shadow_touch = hi_x > -3.0 && lo_x < -1.0 && hi_z > -1.0 && lo_z < 1.0;
        if (occluder)
        {
          MRGI_CHECK_NEAR(v, lit, 1e-6);
          ++on_occluder;
        }
        else if (hides)
        {
          continue;
        }
        else if (shadow)
        {
          MRGI_CHECK_NEAR(v, shadows ? 0.0 : lit, 1e-6);
          ++in_shadow;
        }
        else if (!shadow_touch)
        {
          MRGI_CHECK_NEAR(v, lit, 1e-6);
          ++on_floor;
        }
      }
    }
    MRGI_CHECK(in_shadow > 40 && on_floor > 1000 && on_occluder > 50);
    mrgi_reference_result_destroy(&r);
  }
  mrgi_scene_destroy(&scene);
}

/* Centre-sampled pixels (pixel_filter MRGI_REFERENCE_PIXEL_CENTER): every
 * pixel is the exact value at its centre's ground point, whatever the seed;
 * the box filter averages the occluder's and the shadow's edges. */
static void test_pixel_center(void)
{
  mrgi_scene scene;
  make_shadow_scene(&scene);
  const double lit = 0.5 * 2.0 * cos(pi / 4);
  const double half_h = 10.0 * tan(pi / 6);
  const int32_t n = 61; /* odd: no pixel centre on x = 0 or z = 0 */
  int32_t partial[2] = { 0, 0 };
  mrgi_reference_result first;
  for (int filter = MRGI_REFERENCE_PIXEL_BOX; filter <= MRGI_REFERENCE_PIXEL_CENTER; ++filter)
  {
    for (uint64_t seed = 1; seed <= 2; ++seed)
    {
      mrgi_reference_options o = base_options(n, n);
      o.pixel_filter = filter;
      o.pixel_samples = 4;
      o.seed = seed;
      mrgi_reference_result r;
      render(&scene, &o, &r);
      int32_t checked = 0, shadowed = 0, edges = 0;
      for (int32_t y = 0; y < n; ++y)
      {
        for (int32_t x = 0; x < n; ++x)
        {
          const double v = mrgi_image_at(&r.direct, x, y)[0];
          if (v > 1e-6 && v < lit - 1e-6)
          {
            ++edges;
          }
          if (filter != MRGI_REFERENCE_PIXEL_CENTER)
          {
            continue;
          }
          double gx, gz;
          ground_point(x + 0.5, y + 0.5, n, n, half_h, &gx, &gz);
          /* the centre ray meets the occluder (height 2 of 10) at 0.8 x the ground point */
          const int on_occluder = fabs(0.8 * gx) < 1.0 && fabs(0.8 * gz) < 1.0;
          const int in_shadow = !on_occluder && gx > -3.0 && gx < -1.0 && fabs(gz) < 1.0;
          MRGI_CHECK_NEAR(v, in_shadow ? 0.0 : lit, 1e-6);
          shadowed += in_shadow;
          ++checked;
        }
      }
      partial[filter] += edges;
      if (filter == MRGI_REFERENCE_PIXEL_CENTER)
      {
        MRGI_CHECK(checked == n * n && shadowed > 20);
        if (seed == 1)
        {
          first = r;
          continue;
        }
        /* another seed draws other jitter, which the centre mode ignores */
        MRGI_CHECK(memcmp(first.direct.pixels, r.direct.pixels,
                          mrgi_image_value_count(&r.direct) * sizeof(float)) == 0);
        mrgi_reference_result_destroy(&first);
      }
      mrgi_reference_result_destroy(&r);
    }
  }
  /* the box filter's edge pixels are partly lit; the centre's never are */
  MRGI_CHECK(partial[MRGI_REFERENCE_PIXEL_BOX] > 20 && partial[MRGI_REFERENCE_PIXEL_CENTER] == 0);

  /* A spot light 5 above the floor (X = 2 (5/d)^3 inside its 30-degree
   * cone, as in test_direct) varies across every pixel: each centre-sampled
   * pixel is its centre's value, not a value of somewhere else in the pixel. */
  spot_down(&scene.lights[0]);
  {
    mrgi_reference_options o = base_options(n, n);
    o.pixel_filter = MRGI_REFERENCE_PIXEL_CENTER;
    mrgi_reference_result r;
    render(&scene, &o, &r);
    int32_t ring = 0;
    for (int32_t y = 0; y < n; ++y)
    {
      for (int32_t x = 0; x < n; ++x)
      {
        double gx, gz;
        ground_point(x + 0.5, y + 0.5, n, n, half_h, &gx, &gz);
        const double radius = sqrt(gx * gx + gz * gz);
        /* outside the occluder's shadow (|x|, |z| < 5/3) and inside the cone (2.89) */
        if (fmax(fabs(gx), fabs(gz)) > 1.8 && radius < 2.8)
        {
          const double expected = 0.5 * 2.0 * pow(5.0 / sqrt(25.0 + radius * radius), 3.0);
          MRGI_CHECK_NEAR(mrgi_image_at(&r.direct, x, y)[0], expected, 1e-5);
          ++ring;
        }
      }
    }
    MRGI_CHECK(ring > 100);
    mrgi_reference_result_destroy(&r);
  }

  mrgi_reference_options o = base_options(n, n);
  o.pixel_filter = 2;
  mrgi_reference_result r;
  mrgi_error err;
  MRGI_CHECK(mrgi_reference_render(&scene, &o, &r, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "pixel_filter"));
  mrgi_scene_destroy(&scene);
}

/* ---- 3 and 4. one bounce from a parallel rectangle ---- */

/* View factor from a differential area to a parallel rectangle at distance h
 * whose corner lies on the element's normal, sides a and b: Hottel's formula,
 * Howell's catalogue of configuration factors, case B-3 ("plane element to
 * plane parallel rectangle; normal to element passes through corner"). */
static double view_factor_corner(double a, double b, double h)
{
  const double A = a / h, B = b / h;
  const double sa = sqrt(1.0 + A * A), sb = sqrt(1.0 + B * B);
  return (A / sa * atan(B / sa) + B / sb * atan(A / sb)) / (2.0 * pi);
}

/* ...any parallel rectangle [x0, x1] x [z0, z1] (relative to the element),
 * by signed sums of corner rectangles. */
static double view_factor_rect(double x0, double x1, double z0, double z1, double h)
{
  const double xs[2] = { x0, x1 }, zs[2] = { z0, z1 };
  double f = 0.0;
  for (int i = 0; i < 2; ++i)
  {
    for (int j = 0; j < 2; ++j)
    {
      const double sign = ((i == j) ? 1.0 : -1.0) * (xs[i] < 0 ? -1.0 : 1.0) *
                          (zs[j] < 0 ? -1.0 : 1.0);
      f += sign * view_factor_corner(fabs(xs[i]), fabs(zs[j]), h);
    }
  }
  return f;
}

/* Floor patch (albedo 0.5, half-size 0.2) under a ceiling square (albedo
 * 0.8, half-size 1, at height 1). A directional light travels UP at 60
 * degrees from the vertical towards +x: it lights the ceiling's underside
 * with X = cos 60 and cannot light the floor's upper side (n.l < 0); the
 * floor's shadow lands at x > 1.5, beside the ceiling. Optionally a black
 * occluder (half-size 0.15, height 0.25) whose shadow lands at x > 1.14. */
static void make_bounce_scene(mrgi_scene* scene, int occluder, int duplicate_ceiling)
{
  MRGI_CHECK(mrgi_scene_create(scene, 2 + occluder + duplicate_ceiling, NULL) == MRGI_OK);
  make_square(&scene->meshes[0], "floor", 0, 0, 0, 0.2, 1, 0.5f);
  /* front side up, away from the floor: two-sided all the same */
  make_square(&scene->meshes[1], "ceiling", 0, 1, 0, 1, 1, 0.8f);
  if (occluder)
  {
    make_square(&scene->meshes[2], "occluder", 0, 0.25, 0, 0.15, 1, 0.0f);
  }
  if (duplicate_ceiling)
  {
    make_square(&scene->meshes[2 + occluder], "ceiling_copy", 0, 1, 0, 1, 0, 0.8f);
  }
  scene->light_count = 1;
  directional(&scene->lights[0], sin(pi / 3), cos(pi / 3), 0, 1.0);
}

/* Expected indirect at floor point (x, z): a_floor * L_ceiling * F, minus
 * the ceiling hidden behind the occluder, whose shadow from (x, 0, z) on the
 * plane y = 1 is the square of half-size 0.6 centred on -3 (x, z). */
static double expected_indirect(double x, double z, int visible_occluder)
{
  const double l_ceiling = 0.8 * cos(pi / 3);
  double f = view_factor_rect(-1.0 - x, 1.0 - x, -1.0 - z, 1.0 - z, 1.0);
  if (visible_occluder)
  {
    const double cx = -3.0 * x - x, cz = -3.0 * z - z; /* centre relative to the element */
    f -= view_factor_rect(cx - 0.6, cx + 0.6, cz - 0.6, cz + 0.6, 1.0);
  }
  return 0.5 * l_ceiling * f;
}

/* Mean of (indirect - expected) over the image against its standard error. */
static void check_bounce(const mrgi_reference_result* r, double half_h, int visible_occluder,
                         const char* what)
{
  const int32_t w = r->indirect.width, h = r->indirect.height;
  double diff = 0.0, expect = 0.0, var = 0.0;
  for (int32_t y = 0; y < h; ++y)
  {
    for (int32_t x = 0; x < w; ++x)
    {
      double gx, gz;
      ground_point(x + 0.5, y + 0.5, w, h, half_h, &gx, &gz);
      const double e = expected_indirect(gx, gz, visible_occluder);
      const float* v = mrgi_image_at(&r->indirect, x, y);
      const double se = mrgi_image_at(&r->indirect_stderr, x, y)[0];
      MRGI_CHECK(mrgi_image_at(&r->direct, x, y)[0] == 0.0f);
      MRGI_CHECK(v[0] == v[1] && v[1] == v[2]);
      /* per pixel: generous, the stderr is itself estimated from few passes */
      if (!(fabs(v[0] - e) <= 8.0 * se + 2e-3 * e))
      {
        fprintf(stderr, "%s: pixel (%d, %d) indirect %g, expected %g, stderr %g\n", what,
                (int)x, (int)y, v[0], e, se);
        MRGI_CHECK(0);
      }
      diff += v[0] - e;
      expect += e;
      var += se * se;
    }
  }
  const double n = (double)w * h;
  const double tol = 4.0 * sqrt(var) / n + 1e-3 * expect / n;
  printf("%s: mean indirect %.6f, expected %.6f, tolerance %.2g, %d passes, rel. error %.2g\n",
         what, (expect + diff) / n, expect / n, tol, (int)r->passes, r->relative_error);
  MRGI_CHECK(fabs(diff / n) <= tol);
}

static void test_bounce(void)
{
  mrgi_scene scene;
  /* 3. no occluder, perspective camera inside the gap, looking down */
  make_bounce_scene(&scene, 0, 0);
  camera_down(&scene, 0.5, 30);
  mrgi_reference_options o = base_options(24, 24);
  o.indirect_samples = 64;
  o.max_passes = 40;
  o.target_relative_error = 1e-3;
  mrgi_reference_result r;
  render(&scene, &o, &r);
  MRGI_CHECK(r.relative_error <= 1e-3 && r.passes >= 2);
  check_bounce(&r, 0.5 * tan(pi / 12), 0, "bounce");
  /* the whole-image value is the closed form, so the estimate is unbiased:
   * guard against a factor (pi, 2, cos) slipping in */
  const double centre = expected_indirect(0, 0, 0);
  MRGI_CHECK(centre > 0.10 && centre < 0.12);
  mrgi_reference_result_destroy(&r);

  /* same with the RSM assumption: nothing in the way, same value */
  o.secondary_visibility = 0;
  render(&scene, &o, &r);
  check_bounce(&r, 0.5 * tan(pi / 12), 0, "bounce, no visibility");
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);

  /* coincident copy of the ceiling (front side down): one surface to both modes */
  make_bounce_scene(&scene, 0, 1);
  camera_down(&scene, 0.5, 30);
  for (int vis = 0; vis < 2; ++vis)
  {
    o.secondary_visibility = vis;
    render(&scene, &o, &r);
    check_bounce(&r, 0.5 * tan(pi / 12), 0, vis ? "duplicate ceiling" : "duplicate ceiling, RSM");
    mrgi_reference_result_destroy(&r);
  }
  mrgi_scene_destroy(&scene);

  /* 4. black occluder; parallel camera between it and the floor */
  make_bounce_scene(&scene, 1, 0);
  camera_down(&scene, 0.2, 30);
  o = base_options(20, 20);
  o.parallel_projection = 1;
  o.parallel_scale = 0.1;
  o.indirect_samples = 64;
  o.max_passes = 40;
  o.target_relative_error = 1e-3;
  mrgi_reference_result visible, rsm;
  render(&scene, &o, &visible);
  check_bounce(&visible, 0.1, 1, "occluded bounce");
  o.secondary_visibility = 0;
  render(&scene, &o, &rsm);
  check_bounce(&rsm, 0.1, 0, "occluded bounce, no visibility");
  double sum_visible = 0.0, sum_rsm = 0.0;
  for (int64_t i = 0; i < 20 * 20; ++i)
  {
    sum_visible += visible.indirect.pixels[3 * i];
    sum_rsm += rsm.indirect.pixels[3 * i];
  }
  MRGI_CHECK(sum_visible < 0.6 * sum_rsm);
  mrgi_reference_result_destroy(&visible);
  mrgi_reference_result_destroy(&rsm);
  mrgi_scene_destroy(&scene);
}

/* ---- 5. Cornell box ---- */

/* Mean of channel c over a 3x3 block centred on (x, y). */
static double block(const mrgi_image* img, int32_t x, int32_t y, int c)
{
  double s = 0.0;
  for (int32_t dy = -1; dy <= 1; ++dy)
  {
    for (int32_t dx = -1; dx <= 1; ++dx)
    {
      s += mrgi_image_at(img, x + dx, y + dy)[c];
    }
  }
  return s / 9.0;
}

static void test_cornell(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_SPOT, &scene, NULL) == MRGI_OK);
  mrgi_reference_options o = base_options(64, 64);
  o.indirect_samples = 32;
  o.max_passes = 8; /* 7 degrees of freedom for the standard errors */
  mrgi_reference_result r;
  render(&scene, &o, &r);
  printf("cornell-spot 64x64: %d passes, %.3f s, %lld rays, rel. error %.3g (per pixel %.3g)\n",
         (int)r.passes, r.seconds, (long long)r.rays_traced, r.relative_error,
         r.pixel_relative_error);
  /* Ceiling: near the top of the image (rows at sy = 0.92 meet y = 548.8 at
   * z ~ 60 mm). The spot, aimed down, cannot light it directly. */
  const int32_t top = 2;
  double ceiling = 0.0, ceiling_var = 0.0;
  for (int32_t x = 24; x < 40; ++x)
  {
    MRGI_CHECK(r.background[top * 64 + x] == 0);
    MRGI_CHECK_NEAR(mrgi_image_at(&r.albedo, x, top)[0], 0.725, 1e-6); /* white ceiling */
    MRGI_CHECK(mrgi_image_at(&r.direct, x, top)[0] == 0.0f);
    const double se = mrgi_image_at(&r.indirect_stderr, x, top)[0];
    ceiling += mrgi_image_at(&r.indirect, x, top)[1];
    ceiling_var += se * se;
  }
  printf("cornell ceiling indirect (green) %.4f +- %.4f\n", ceiling / 16, sqrt(ceiling_var) / 16);
  MRGI_CHECK(ceiling > 5.0 * sqrt(ceiling_var) && ceiling / 16 > 0.01);
  /* Floor near the red wall (image left, x ~ 505 mm) and near the green one
   * (image right, x ~ 51 mm), rows at sy = -0.9 (z ~ 50 mm). */
  const int32_t row = 60, left = 8, right = 56;
  MRGI_CHECK_NEAR(block(&r.albedo, left, row, 0), 0.725, 1e-6);
  MRGI_CHECK_NEAR(block(&r.albedo, right, row, 0), 0.725, 1e-6);
  const double left_rg = block(&r.indirect, left, row, 0) / block(&r.indirect, left, row, 1);
  const double right_rg = block(&r.indirect, right, row, 0) / block(&r.indirect, right, row, 1);
  printf("cornell floor indirect red/green: near red wall %.3f, near green wall %.3f\n", left_rg,
         right_rg);
  MRGI_CHECK(left_rg > 1.5 * right_rg);
  MRGI_CHECK(r.background[0] == 1); /* the view's corner is outside the box */
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

/* ---- 6. determinism, convergence, bad input ---- */

static void test_determinism_and_convergence(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_SPOT, &scene, NULL) == MRGI_OK);
  mrgi_reference_options o = base_options(24, 16);
  o.indirect_samples = 8;
  o.pixel_samples = 2;
  o.max_passes = 3;
  o.threads = 2;
  mrgi_reference_result a, b, c;
  render(&scene, &o, &a);
  render(&scene, &o, &b);
  o.threads = 1;
  render(&scene, &o, &c);
  const size_t bytes = mrgi_image_value_count(&a.indirect) * sizeof(float);
  MRGI_CHECK(memcmp(a.indirect.pixels, b.indirect.pixels, bytes) == 0);
  MRGI_CHECK(memcmp(a.direct.pixels, b.direct.pixels, bytes) == 0);
  MRGI_CHECK(memcmp(a.indirect.pixels, c.indirect.pixels, bytes) == 0);
  MRGI_CHECK(memcmp(a.direct.pixels, c.direct.pixels, bytes) == 0);
  MRGI_CHECK(a.relative_error == c.relative_error && a.rays_traced == c.rays_traced);
  mrgi_reference_result_destroy(&c);
  o.threads = 2;
  o.seed = 2;
  render(&scene, &o, &c);
  MRGI_CHECK(memcmp(a.indirect.pixels, c.indirect.pixels, bytes) != 0);
  mrgi_reference_result_destroy(&a);
  mrgi_reference_result_destroy(&b);
  mrgi_reference_result_destroy(&c);

  /* one pass: error unknown (infinite, not NaN); then it falls as 1/sqrt(passes) */
  o.max_passes = 1;
  render(&scene, &o, &a);
  MRGI_CHECK(isinf(a.relative_error) && a.passes == 1);
  mrgi_reference_result_destroy(&a);
  o.max_passes = 2;
  render(&scene, &o, &a);
  o.max_passes = 16;
  render(&scene, &o, &b);
  printf("convergence: relative error %.4f after 2 passes, %.4f after 16\n", a.relative_error,
         b.relative_error);
  MRGI_CHECK(a.relative_error > 0.0 && isfinite(a.relative_error));
  MRGI_CHECK(b.relative_error < 0.6 * a.relative_error);
  MRGI_CHECK(b.passes == 16);
  /* the per-pixel statistic falls as 1/sqrt(passes) too (8x the passes: /2.8) */
  MRGI_CHECK(a.pixel_error > 0.0 && isfinite(a.pixel_error));
  MRGI_CHECK(b.pixel_error < 0.6 * a.pixel_error);
  /* the target stops early, on the per-pixel statistic */
  o.target_relative_error = 1.5 * b.pixel_error;
  o.max_passes = 1000;
  render(&scene, &o, &c);
  MRGI_CHECK(c.passes >= 2 && c.passes < 1000 && c.pixel_error <= o.target_relative_error);
  mrgi_reference_result_destroy(&a);
  mrgi_reference_result_destroy(&b);
  mrgi_reference_result_destroy(&c);
  mrgi_scene_destroy(&scene);
}

/* Progress: one report per pass with growing passes and a fraction in
 * (0, 1]; a non-zero return stops after that pass with the passes' images. */
typedef struct progress_log
{
  int32_t calls;
  int32_t cancel_after;
  int32_t last_passes;
  double last_fraction;
  int ok;
} progress_log;

static int log_progress(void* user_data, const mrgi_reference_progress* p)
{
  progress_log* log = (progress_log*)user_data;
  ++log->calls;
  log->ok = log->ok && p->passes == log->last_passes + 1 && p->fraction > 0.0 &&
    p->fraction <= 1.0 && p->passes_expected >= p->passes && p->passes_expected <= p->max_passes &&
    p->seconds_left >= 0.0 && isfinite(p->seconds_left) && p->seconds >= 0.0;
  log->last_passes = p->passes;
  log->last_fraction = p->fraction;
  return log->cancel_after > 0 && p->passes >= log->cancel_after;
}

static void test_progress_and_cancel(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_SPOT, &scene, NULL) == MRGI_OK);
  mrgi_reference_options o = base_options(24, 16);
  o.indirect_samples = 4;
  o.max_passes = 5;
  o.target_relative_error = 0.0; /* run every pass */
  progress_log log = { 0, 0, 0, 0.0, 1 };
  o.progress = log_progress;
  o.progress_user_data = &log;
  mrgi_reference_result r;
  render(&scene, &o, &r);
  MRGI_CHECK(log.ok && log.calls == 5 && r.passes == 5 && r.cancelled == 0);
  MRGI_CHECK_NEAR(log.last_fraction, 1.0, 1e-12);
  mrgi_reference_result_destroy(&r);

  /* cancelled after pass 2 of 50: two passes' images, finite, error known */
  progress_log cancel = { 0, 2, 0, 0.0, 1 };
  o.max_passes = 50;
  o.progress_user_data = &cancel;
  render(&scene, &o, &r);
  MRGI_CHECK(cancel.ok && cancel.calls == 2);
  MRGI_CHECK(r.cancelled == 1 && r.passes == 2 && isfinite(r.relative_error));
  MRGI_CHECK(cancel.last_fraction < 0.1); /* 2 of 50 passes expected */
  int64_t nonfinite = -1;
  MRGI_CHECK(
    mrgi_image_count_nonfinite(&r.indirect, &nonfinite, NULL) == MRGI_OK && nonfinite == 0);
  MRGI_CHECK(mrgi_image_count_nonfinite(&r.direct, &nonfinite, NULL) == MRGI_OK && nonfinite == 0);
  double sum = 0.0;
  for (size_t i = 0; i < mrgi_image_value_count(&r.indirect); ++i)
  {
    sum += r.indirect.pixels[i];
  }
  MRGI_CHECK(sum > 0.0); /* the passes run are in the image, scaled as passes */
  /* the same two passes without cancelling give the same image */
  mrgi_reference_result two;
  o.progress = NULL;
  o.max_passes = 2;
  render(&scene, &o, &two);
  MRGI_CHECK(memcmp(two.indirect.pixels, r.indirect.pixels,
               mrgi_image_value_count(&r.indirect) * sizeof(float)) == 0);
  mrgi_reference_result_destroy(&two);
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

/* ---- 5b. the per-pixel stopping rule (mrgi_reference_noise.h) ---- */

static int compare_doubles(const void* a, const void* b)
{
  const double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

/* The nearest-rank quantile equals the sorted array's element at
 * ceil(p * n) - 1, on random data with and without ties. */
static void test_quantile(void)
{
  enum
  {
    max_count = 1000
  };
  static double values[max_count], sorted[max_count];
  static const double percentiles[] = { 1e-6, 0.01, 0.25, 0.5, 0.9, 0.95, 0.999, 1.0 };
  uint64_t state = 12345;
  int checked = 0;
  for (size_t count = 1; count <= max_count; count = count * 3 + 1)
  {
    for (int ties = 0; ties < 2; ++ties)
    {
      for (size_t i = 0; i < count; ++i)
      {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const double u = (double)(state >> 11) / 9007199254740992.0;
        /* with ties: 5 distinct values, many zeros as in a dark image */
        sorted[i] = ties ? floor(5.0 * u * u) : u;
      }
      qsort(sorted, count, sizeof(double), compare_doubles);
      for (size_t p = 0; p < sizeof(percentiles) / sizeof(percentiles[0]); ++p)
      {
        /* shuffle from the sorted order so the input is not presorted */
        for (size_t i = 0; i < count; ++i)
        {
          values[i] = sorted[(i * 7919u) % count];
        }
        if (count % 7919u == 0)
        {
          memcpy(values, sorted, count * sizeof(double));
        }
        double q = -1.0;
        MRGI_CHECK(mrgi_reference_quantile(values, count, percentiles[p], &q, NULL) == MRGI_OK);
        size_t rank = (size_t)ceil(percentiles[p] * (double)count);
        rank = rank < 1 ? 1 : rank;
        MRGI_CHECK(q == sorted[rank - 1]);
        ++checked;
      }
    }
  }
  /* reverse-sorted and constant inputs */
  for (size_t i = 0; i < max_count; ++i)
  {
    values[i] = (double)(max_count - i);
  }
  double q = 0.0;
  MRGI_CHECK(mrgi_reference_quantile(values, max_count, 0.95, &q, NULL) == MRGI_OK && q == 950.0);
  for (size_t i = 0; i < max_count; ++i)
  {
    values[i] = 2.5;
  }
  MRGI_CHECK(mrgi_reference_quantile(values, max_count, 0.5, &q, NULL) == MRGI_OK && q == 2.5);
  printf("quantile: %d cases equal the sort\n", checked);
  /* bad input names the problem */
  mrgi_error err;
  MRGI_CHECK(mrgi_reference_quantile(values, 0, 0.5, &q, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "count"));
  MRGI_CHECK(mrgi_reference_quantile(values, 4, 0.0, &q, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "percentile"));
  MRGI_CHECK(mrgi_reference_quantile(values, 4, NAN, &q, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_reference_quantile(NULL, 4, 0.5, &q, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

/* mrgi_reference_pixel_error on synthetic accumulators. */
static void test_pixel_error(void)
{
  enum
  {
    n = 256 * 256
  };
  static double mean[n], m2[n], scratch[n];
  static uint8_t mask[n];
  /* Every pixel has mean 1 and a per-pixel relative standard error of 0.3
   * after 4 passes (m2 = s^2 (n-1) n): the image-mean rule (sqrt of the
   * summed variances over the summed means, mrgi_reference.h) says
   * 0.3 / 256 = 0.0012 and would stop at a target of 0.01; the per-pixel
   * rule says 0.3 and goes on. */
  const int32_t passes = 4;
  for (size_t i = 0; i < n; ++i)
  {
    mean[i] = 1.0;
    m2[i] = 0.3 * 0.3 * (double)(passes - 1) * (double)passes;
    mask[i] = 1;
  }
  double sum_var = 0.0, sum_mean = 0.0;
  for (size_t i = 0; i < n; ++i)
  {
    sum_var += m2[i] / ((double)(passes - 1) * (double)passes);
    sum_mean += mean[i];
  }
  const double image_mean_rule = sqrt(sum_var) / sum_mean;
  double e = -1.0;
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, passes, 0.95, scratch, &e, NULL) ==
             MRGI_OK);
  printf("synthetic: image-mean rule %.5f, per-pixel rule %.4f (target 0.01)\n", image_mean_rule,
         e);
  MRGI_CHECK(image_mean_rule <= 0.01);
  MRGI_CHECK_NEAR(e, 0.3, 1e-12);

  /* 10 % of the pixels noisy (0.5), the rest exact: the 0.95 quantile sees
   * them, the 0.5 quantile does not */
  for (size_t i = 0; i < n; ++i)
  {
    m2[i] = (i % 10 == 3) ? 0.5 * 0.5 * (double)(passes - 1) * (double)passes : 0.0;
  }
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, passes, 0.95, scratch, &e, NULL) ==
               MRGI_OK &&
             fabs(e - 0.5) < 1e-12);
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, passes, 0.5, scratch, &e, NULL) ==
               MRGI_OK &&
             e == 0.0);
  /* masked pixels do not count: mask out the noisy ones */
  for (size_t i = 0; i < n; ++i)
  {
    mask[i] = (i % 10 != 3);
  }
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, passes, 1.0, scratch, &e, NULL) ==
               MRGI_OK &&
             e == 0.0);

  /* the floor: a dark pixel (mean 0.01 of the image's ~1) is measured
   * against the image's mean pixel value, not its own */
  for (size_t i = 0; i < n; ++i)
  {
    mask[i] = 1;
    mean[i] = 1.0;
    m2[i] = 0.0;
  }
  mean[0] = 0.01;
  m2[0] = 0.05 * 0.05 * (double)(passes - 1) * (double)passes; /* stderr 0.05 */
  const double image_mean = (double)(n - 1) / (double)n + 0.01 / (double)n;
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, passes, 1.0, scratch, &e, NULL) ==
             MRGI_OK);
  MRGI_CHECK_NEAR(e, 0.05 / (MRGI_REFERENCE_NOISE_FLOOR * image_mean), 1e-12);
  /* a pixel brighter than the mean is held to its own value */
  mean[0] = 10.0;
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, passes, 1.0, scratch, &e, NULL) ==
             MRGI_OK);
  MRGI_CHECK_NEAR(e, 0.05 / 10.0, 1e-12);

  /* one pass: unknown, +inf; no light at all: 0, known exactly */
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, 1, 0.95, scratch, &e, NULL) ==
               MRGI_OK &&
             isinf(e) && e > 0.0);
  for (size_t i = 0; i < n; ++i)
  {
    mean[i] = 0.0;
    m2[i] = 0.0;
  }
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, 1, 0.95, scratch, &e, NULL) ==
               MRGI_OK &&
             e == 0.0);
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, 5, 0.95, scratch, &e, NULL) ==
               MRGI_OK &&
             e == 0.0);
  /* bad input names the problem */
  mrgi_error err;
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, 0, 0.95, scratch, &e, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "passes 0"));
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, 2, 1.5, scratch, &e, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "percentile 1.5"));
  MRGI_CHECK(mrgi_reference_pixel_error(mean, m2, mask, n, 2, 0.5, NULL, &e, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
}

/* The renderer stops on the per-pixel statistic: on the Cornell box the
 * image-mean rule would stop after two passes at a target it already meets,
 * the per-pixel rule runs on until the per-pixel statistic meets it. */
static void test_per_pixel_stopping_rule(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_SPOT, &scene, NULL) == MRGI_OK);
  mrgi_reference_options o = base_options(32, 32);
  o.indirect_samples = 4;
  o.max_passes = 2;
  mrgi_reference_result two, stopped;
  render(&scene, &o, &two);
  /* a target the image-mean statistic meets after two passes */
  const double target = 1.01 * two.relative_error;
  printf("stopping rule: after 2 passes image-mean %.4f, per-pixel %.4f, RMS per-pixel %.4f\n",
         two.relative_error, two.pixel_error, two.pixel_relative_error);
  MRGI_CHECK(two.relative_error <= target && two.pixel_error > 4.0 * target);
  o.target_relative_error = target;
  o.max_passes = 20000;
  render(&scene, &o, &stopped);
  printf("stopping rule: target %.4f reached after %d passes (per-pixel %.4f)\n", target,
         (int)stopped.passes, stopped.pixel_error);
  /* the statistic falls as 1/sqrt(passes): (4x)^2 = 16x the passes at least */
  MRGI_CHECK(stopped.passes > 16 * 2 && stopped.passes < o.max_passes);
  MRGI_CHECK(stopped.pixel_error <= target && stopped.relative_error < target);
  mrgi_reference_result_destroy(&two);
  mrgi_reference_result_destroy(&stopped);

  /* one pass: +inf (never NaN); no indirect light: 0 after one pass */
  o.max_passes = 1;
  render(&scene, &o, &two);
  MRGI_CHECK(two.passes == 1 && isinf(two.pixel_error) && two.direct_pixel_error == 0.0);
  mrgi_reference_result_destroy(&two);
  o.indirect_samples = 0;
  o.max_passes = 10;
  render(&scene, &o, &two);
  MRGI_CHECK(two.passes == 1 && two.pixel_error == 0.0);
  mrgi_reference_result_destroy(&two);

  /* a percentile outside (0, 1] is refused, naming the option */
  mrgi_error err;
  o.target_percentile = 0.0;
  MRGI_CHECK(mrgi_reference_render(&scene, &o, &two, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "target_percentile"));
  o.target_percentile = NAN;
  MRGI_CHECK(mrgi_reference_render(&scene, &o, &two, &err) == MRGI_ERR_INVALID_ARGUMENT);
  mrgi_scene_destroy(&scene);
}

static void expect_failure(const mrgi_scene* scene, const mrgi_reference_options* o,
                           mrgi_status status, const char* text)
{
  mrgi_error err;
  mrgi_reference_result r;
  memset(&r, 0xAB, sizeof(r));
  MRGI_CHECK(mrgi_reference_render(scene, o, &r, &err) == status);
  MRGI_CHECK(err.status == status);
  MRGI_CHECK(message_has(&err, text));
  MRGI_CHECK(r.direct.pixels == NULL && r.background == NULL); /* zeroed */
  mrgi_reference_result_destroy(&r);
}

static void test_bad_input(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_create(&scene, 1, NULL) == MRGI_OK);
  make_square(&scene.meshes[0], "floor", 0, 0, 0, 10, 1, 0.5f);
  camera_down(&scene, 10, 60);
  scene.light_count = 1;
  directional(&scene.lights[0], 0, -1, 0, 2.0);
  const mrgi_reference_options good = base_options(8, 8);
  mrgi_reference_options o = good;
  mrgi_error err;

  MRGI_CHECK(mrgi_reference_render(&scene, &o, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "out is NULL"));
  MRGI_CHECK(mrgi_reference_render(&scene, &o, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  expect_failure(NULL, &o, MRGI_ERR_INVALID_ARGUMENT, "scene is NULL");
  expect_failure(&scene, NULL, MRGI_ERR_INVALID_ARGUMENT, "options is NULL");
  o.width = 0;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "width = 0");
  o = good;
  o.height = 16385;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "height = 16385");
  o = good;
  o.target_relative_error = NAN;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "target_relative_error");
  o = good;
  o.indirect_samples = -1;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "indirect_samples = -1");
  o = good;
  o.pixel_samples = 0;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "pixel_samples = 0");
  o = good;
  o.max_passes = 0;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "max_passes = 0");
  o = good;
  o.parallel_projection = 1;
  o.parallel_scale = -1.0;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "parallel_scale");
  o = good;
  o.max_seconds = INFINITY;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "max_seconds");
  o = good;
  o.threads = -3;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "threads = -3");
  o = good;
  o.shadows = 2;
  expect_failure(&scene, &o, MRGI_ERR_INVALID_ARGUMENT, "shadows = 2");
  MRGI_CHECK(mrgi_reference_options_validate(&good, NULL) == MRGI_OK);

  /* invalid scene: named by mrgi_scene_validate, prefixed with the caller */
  scene.camera.view_angle_deg = 0.0;
  expect_failure(&scene, &good, MRGI_ERR_FORMAT, "mrgi_reference_render: ");
  camera_down(&scene, 10, 60);
  scene.meshes[0].albedo[0] = NAN;
  expect_failure(&scene, &good, MRGI_ERR_FORMAT, "albedo");
  scene.meshes[0].albedo[0] = 0.5f;
  /* camera looking along its up vector */
  scene.camera.view_up[2] = 0.0;
  scene.camera.view_up[1] = 1.0;
  {
    mrgi_reference_result r;
    const mrgi_status s = mrgi_reference_render(&scene, &good, &r, &err);
    MRGI_CHECK(s != MRGI_OK);
    mrgi_reference_result_destroy(&r);
  }
  camera_down(&scene, 10, 60);

  /* empty scene, and a scene whose only triangles are degenerate */
  mrgi_scene empty;
  memset(&empty, 0, sizeof(empty));
  empty.camera = scene.camera;
  expect_failure(&empty, &good, MRGI_ERR_INVALID_ARGUMENT, "no triangles");
  mrgi_scene flat;
  MRGI_CHECK(mrgi_scene_create(&flat, 1, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_mesh_create(&flat.meshes[0], "needle", 3, 1, 0, NULL) == MRGI_OK);
  flat.meshes[0].positions[3] = 1.0f;
  flat.meshes[0].positions[6] = 2.0f; /* three collinear points */
  flat.meshes[0].indices[1] = 1;
  flat.meshes[0].indices[2] = 2;
  flat.camera = scene.camera;
  expect_failure(&flat, &good, MRGI_ERR_INVALID_ARGUMENT, "no usable triangles");
  mrgi_scene_destroy(&flat);

  /* degenerate triangles among good ones are skipped, counted, harmless */
  mrgi_mesh* m = &scene.meshes[0];
  mrgi_mesh grown;
  MRGI_CHECK(mrgi_mesh_create(&grown, "floor", 4, 4, 0, NULL) == MRGI_OK);
  memcpy(grown.positions, m->positions, 12 * sizeof(float));
  memcpy(grown.indices, m->indices, 6 * sizeof(uint32_t));
  const uint32_t degenerate[6] = { 0, 0, 1, 2, 2, 2 };
  memcpy(grown.indices + 6, degenerate, sizeof(degenerate));
  grown.albedo[0] = grown.albedo[1] = grown.albedo[2] = 0.5f;
  mrgi_mesh_destroy(m);
  *m = grown;
  mrgi_reference_result r;
  render(&scene, &good, &r);
  MRGI_CHECK(r.skipped_triangles == 2);
  for (int64_t i = 0; i < 64; ++i)
  {
    MRGI_CHECK_NEAR(r.direct.pixels[3 * i], 1.0, 1e-6);
  }
  mrgi_reference_result_destroy(&r);
  mrgi_reference_result_destroy(NULL);

  /* background: a camera looking away from everything */
  scene.camera.position[1] = -1.0;
  scene.camera.focal_point[1] = -2.0;
  o = good;
  o.indirect_samples = 4;
  o.max_passes = 2;
  render(&scene, &o, &r);
  for (int64_t i = 0; i < 64; ++i)
  {
    MRGI_CHECK(r.background[i] == 1 && r.direct.pixels[3 * i] == 0.0f);
  }
  MRGI_CHECK(r.relative_error == 0.0);
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

/* ---- 7. area lights (mrgi_reference_render_area_lights) ---- */

/* A 2 x 2 light at height 2 over the origin, facing down: [-1, 1]^2 in x, z. */
static mrgi_area_light square_light(double intensity)
{
  mrgi_area_light light;
  memset(&light, 0, sizeof(light));
  light.center[1] = 2.0;
  light.edge_u[0] = 2.0;
  light.edge_v[2] = 2.0; /* (2,0,0) x (0,0,2) = (0,-4,0): faces down */
  light.color[0] = 1.0;
  light.color[1] = 0.5;
  light.color[2] = 0.25;
  light.intensity = intensity;
  return light;
}

/* Fraction F of the hemisphere (view factor) of floor point (x, 0, z) that
 * sees the light, minus, with `occluded`, the part hidden by the square of
 * half-size 0.75 at height 1: seen from the point, it covers the square
 * [-1.5 - x, 1.5 - x] x [-1.5 - z, 1.5 - z] of the light's plane. */
static double area_view_factor(double x, double z, int occluded)
{
  double f = view_factor_rect(-1.0 - x, 1.0 - x, -1.0 - z, 1.0 - z, 2.0);
  if (occluded)
  {
    const double x0 = fmax(-1.0, -1.5 - x), x1 = fmin(1.0, 1.5 - x);
    const double z0 = fmax(-1.0, -1.5 - z), z1 = fmin(1.0, 1.5 - z);
    if (x1 > x0 && z1 > z0)
    {
      f -= view_factor_rect(x0 - x, x1 - x, z0 - z, z1 - z, 2.0);
    }
  }
  return f;
}

/* The expectation over pixel (x, y): a 4 x 4 average of `value` (box filter). */
typedef double (*pixel_function)(double gx, double gz, const void* data);

static double pixel_mean(pixel_function value, const void* data, int32_t x, int32_t y,
                         int32_t w, int32_t h, double half_h)
{
  double sum = 0.0;
  for (int j = 0; j < 4; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      double gx, gz;
      ground_point(x + (i + 0.5) / 4.0, y + (j + 0.5) / 4.0, w, h, half_h, &gx, &gz);
      sum += value(gx, gz, data);
    }
  }
  return sum / 16.0;
}

static double analytic_value(double gx, double gz, const void* data)
{
  return area_view_factor(gx, gz, *(const int*)data);
}

/* Direct (green) against expectation * scale per pixel and on average, with
 * the standard errors the renderer reports; returns the number of pixels
 * whose expectation is exactly 0 (umbra) and checks they are exactly 0.
 * Per pixel, `floor` is allowed on top of 8 standard errors: a pixel at
 * the umbra's edge sees a sliver of light that 16 passes may all miss
 * (value and standard error 0). */
static int32_t check_direct(const mrgi_reference_result* r, pixel_function value, const void* data,
                            double scale, double half_h, double floor, const char* what)
{
  const int32_t w = r->direct.width, h = r->direct.height;
  double diff = 0.0, expect = 0.0, var = 0.0, worst = 0.0;
  int32_t umbra = 0;
  for (int32_t y = 0; y < h; ++y)
  {
    for (int32_t x = 0; x < w; ++x)
    {
      const double e = scale * pixel_mean(value, data, x, y, w, h, half_h);
      const double v = mrgi_image_at(&r->direct, x, y)[1];
      const double se = mrgi_image_at(&r->direct_stderr, x, y)[0];
      MRGI_CHECK(isfinite(se) && se >= 0.0);
      if (e == 0.0)
      {
        ++umbra;
        MRGI_CHECK(v == 0.0 && se == 0.0);
      }
      if (!(fabs(v - e) <= 8.0 * se + 3e-3 * e + floor))
      {
        fprintf(stderr, "%s: pixel (%d, %d) direct %g, expected %g, stderr %g\n", what, (int)x,
                (int)y, v, e, se);
        MRGI_CHECK(0);
      }
      worst = fmax(worst, se > 0.0 ? fabs(v - e) / se : 0.0);
      diff += v - e;
      expect += e;
      var += se * se;
    }
  }
  const double n = (double)w * h;
  const double tol = 4.0 * sqrt(var) / n + 5e-4 * expect / n;
  printf("%s: mean direct %.6f, expected %.6f (diff %.1e, tolerance %.1e), %d passes, direct "
         "rel. error %.2g, worst pixel %.1f stderr\n",
         what, (expect + diff) / n, expect / n, diff / n, tol, (int)r->passes,
         r->direct_relative_error, worst);
  MRGI_CHECK(fabs(diff / n) <= tol);
  return umbra;
}

/* Floor (albedo 0.5, half-size 10), optionally the black occluder (half
 * 0.75 at height 1) and an emitter quad lying exactly on the light; parallel
 * camera at height 0.5 looking down, 6 x 6 units. */
static void make_area_scene(mrgi_scene* scene, int occluder, int emitter_quad)
{
  MRGI_CHECK(mrgi_scene_create(scene, 1 + occluder + emitter_quad, NULL) == MRGI_OK);
  make_square(&scene->meshes[0], "floor", 0, 0, 0, 10, 1, 0.5f);
  if (occluder)
  {
    make_square(&scene->meshes[1], "occluder", 0, 1, 0, 0.75, 1, 0.0f);
  }
  if (emitter_quad)
  {
    mrgi_mesh* quad = &scene->meshes[1 + occluder];
    make_square(quad, "light", 0, 2, 0, 1, 0, 0.0f);
    quad->emission[0] = 3.0f;
    quad->emission[1] = 1.5f;
    quad->emission[2] = 0.75f;
  }
  camera_down(scene, 0.5, 30); /* below the occluder */
}

static mrgi_reference_options area_options(void)
{
  mrgi_reference_options o = base_options(32, 32);
  o.parallel_projection = 1;
  o.parallel_scale = 3.0;
  o.area_light_samples = 16;
  o.max_passes = 16; /* fixed: per-pixel standard errors with 15 degrees of freedom */
  o.target_relative_error = 0.0;
  return o;
}

static void render_area(const mrgi_scene* scene, const mrgi_reference_options* o,
                        const mrgi_area_light* lights, int32_t count, mrgi_reference_result* r)
{
  mrgi_error err;
  const mrgi_status s = mrgi_reference_render_area_lights(scene, o, lights, count, r, &err);
  if (s)
  {
    fprintf(stderr, "render failed: %s\n", err.message);
  }
  MRGI_CHECK(s == MRGI_OK);
  int64_t bad = -1;
  MRGI_CHECK(mrgi_image_count_nonfinite(&r->direct, &bad, NULL) == MRGI_OK && bad == 0);
  MRGI_CHECK(mrgi_image_count_nonfinite(&r->direct_stderr, &bad, NULL) == MRGI_OK && bad == 0);
  MRGI_CHECK(r->direct_stderr.width == o->width && r->direct_stderr.channels == 1);
}

static void test_area_unoccluded(void)
{
  /* light of radiance 3 * (1, 0.5, 0.25) over the albedo-0.5 floor: green
   * direct = 0.5 * 1.5 * F. The emitter quad drawn on the light must not
   * shadow it. */
  const mrgi_area_light light = square_light(3.0);
  const int unoccluded = 0;
  for (int quad = 0; quad < 2; ++quad)
  {
    for (int shadows = 1; shadows >= 0; --shadows)
    {
      mrgi_scene scene;
      make_area_scene(&scene, 0, quad);
      mrgi_reference_options o = area_options();
      o.shadows = shadows;
      mrgi_reference_result r;
      render_area(&scene, &o, &light, 1, &r);
      MRGI_CHECK(r.passes == 16 && r.direct_relative_error < 2e-3 && r.relative_error == 0.0);
      char what[96];
      snprintf(what, sizeof(what), "area light, unoccluded%s%s", quad ? ", emitter quad" : "",
               shadows ? "" : ", no visibility");
      MRGI_CHECK(check_direct(&r, analytic_value, &unoccluded, 0.75, 3.0, 0.0, what) == 0);
      /* channels follow the colour */
      const float* centre = mrgi_image_at(&r.direct, 16, 16);
      MRGI_CHECK_NEAR(centre[0], 2.0 * centre[1], 1e-6 * centre[0]);
      MRGI_CHECK_NEAR(centre[2], 0.5 * centre[1], 1e-6 * centre[0]);
      /* 16 shadow rays per pixel and pass, plus the primary ray */
      MRGI_CHECK(r.rays_traced == (int64_t)r.passes * 32 * 32 * (shadows ? 17 : 1));
      mrgi_reference_result_destroy(&r);
      mrgi_scene_destroy(&scene);
    }
  }
  /* the same rectangle turned over (u and v swapped: it faces up, away from
   * the floor): a two-sided light lights the floor all the same, a
   * one-sided one not at all */
  mrgi_area_light flipped = light;
  memset(flipped.edge_u, 0, sizeof(flipped.edge_u));
  memset(flipped.edge_v, 0, sizeof(flipped.edge_v));
  flipped.edge_u[2] = 2.0;
  flipped.edge_v[0] = 2.0;
  for (int two = 1; two >= 0; --two)
  {
    flipped.two_sided = two;
    mrgi_scene scene;
    make_area_scene(&scene, 0, 0);
    mrgi_reference_options o = area_options();
    mrgi_reference_result r;
    render_area(&scene, &o, &flipped, 1, &r);
    if (two)
    {
      check_direct(&r, analytic_value, &unoccluded, 0.75, 3.0, 0.0,
                   "area light, two-sided, seen from its back");
    }
    else
    {
      for (int64_t i = 0; i < 3 * 32 * 32; ++i)
      {
        MRGI_CHECK(r.direct.pixels[i] == 0.0f);
      }
      MRGI_CHECK(r.direct_relative_error == 0.0);
    }
    mrgi_reference_result_destroy(&r);
    mrgi_scene_destroy(&scene);
  }
}

static void test_area_penumbra(void)
{
  /* the occluder's umbra is |x|, |z| <= 0.5, its penumbra reaches |x| or
   * |z| = 2.5; the closed form gives every pixel */
  const mrgi_area_light light = square_light(3.0);
  mrgi_scene scene;
  make_area_scene(&scene, 1, 1);
  mrgi_reference_options o = area_options();
  mrgi_reference_result r;
  render_area(&scene, &o, &light, 1, &r);
  const int occluded = 1;
  /* per-pixel floor: 1 % of the brightest unoccluded value */
  const double floor = 0.01 * 0.75 * area_view_factor(0.0, 0.0, 0);
  const int32_t umbra =
    check_direct(&r, analytic_value, &occluded, 0.75, 3.0, floor, "area light, occluder");
  /* where the penumbra lies: along the row through z = 0, dark inside
   * |x| < 0.5, partly lit for 0.5 < |x| < 2.5, fully lit beyond (the
   * values themselves were checked against the closed form above) */
  const int32_t row = 15; /* ground z in [-0.1875, 0] */
  const int unoccluded = 0;
  int32_t dark = 0, rising = 0, flat = 0;
  for (int32_t x = 16; x < 32; ++x)
  {
    double x0, z0, x1, z1;
    ground_point(x, row, 32, 32, 3.0, &x0, &z0);
    ground_point(x + 1, row + 1, 32, 32, 3.0, &x1, &z1);
    const double v = mrgi_image_at(&r.direct, x, row)[1];
    const double se = mrgi_image_at(&r.direct_stderr, x, row)[0];
    const double lit = 0.75 * pixel_mean(analytic_value, &unoccluded, x, row, 32, 32, 3.0);
    if (x1 <= 0.5)
    {
      MRGI_CHECK(v == 0.0);
      ++dark;
    }
    else if (x0 >= 0.5 && x1 <= 2.25)
    {
      MRGI_CHECK(v > 0.0 && v < 0.96 * lit); /* partly shadowed (closed form: <= 94 %) */
      ++rising;
    }
    else if (x0 >= 2.5)
    {
      MRGI_CHECK(fabs(v - lit) <= 8.0 * se + 3e-3 * lit);
      ++flat;
    }
  }
  printf("area light penumbra: %d umbra pixels in the image; along z = 0: %d dark, %d partly "
         "lit, %d fully lit\n",
         (int)umbra, (int)dark, (int)rising, (int)flat);
  MRGI_CHECK(umbra >= 16 && dark >= 2 && rising >= 8 && flat >= 2);
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

/* No-visibility mode = the C sample sum of mrgi_area_light_diffuse(). */
typedef struct sample_sum_data
{
  mrgi_area_light_uniforms uniforms;
  const mrgi_area_light_sample* samples;
  int32_t count;
} sample_sum_data;

static double sample_sum_value(double gx, double gz, const void* data)
{
  const sample_sum_data* d = (const sample_sum_data*)data;
  const float p[3] = { (float)gx, 0.0f, (float)gz }, n[3] = { 0.0f, 1.0f, 0.0f };
  float x[3];
  mrgi_area_light_diffuse(&d->uniforms, d->samples, d->count, p, n, x);
  return x[1];
}

static void test_area_no_visibility(void)
{
  /* a textured (64 x 64), two-sided light; the occluder is ignored. The
   * texture is noise times ramps, bright at the light's +u edge (+x) and
   * dark at its -u edge, brighter at its bottom (t = 0, -v, -z) than at
   * its top, so that a misplaced, transposed or flipped texture shows */
  mrgi_image texture;
  MRGI_CHECK(mrgi_image_create(&texture, 64, 64, 3, NULL) == MRGI_OK);
  uint64_t state = 77;
  for (int32_t y = 0; y < 64; ++y)
  {
    for (int32_t x = 0; x < 64; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const double noise = (double)(state >> 40) / (double)(1ULL << 24);
        const double ramps = (x + 0.5) * (x + 0.5) / 1024.0 * (0.25 + (y + 0.5) / 32.0);
        mrgi_image_at(&texture, x, y)[c] = (float)(noise * ramps);
      }
    }
  }
  mrgi_area_light light = square_light(2.0);
  light.texture = &texture;
  light.two_sided = 1;
  mrgi_area_light_texture_pyramid pyramid;
  MRGI_CHECK(mrgi_area_light_texture_pyramid_create(&pyramid, &texture, NULL) == MRGI_OK);
  mrgi_area_light_sample* samples = malloc(4096 * sizeof(mrgi_area_light_sample));
  MRGI_CHECK(samples != NULL);
  sample_sum_data data;
  MRGI_CHECK(mrgi_area_light_make_samples(&light, &pyramid, 4096, 1, 3, samples, 4096, &data.count,
                                          NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_area_light_uniforms_init(&light, &pyramid, &data.uniforms, NULL) == MRGI_OK);
  data.samples = samples;

  mrgi_scene scene;
  make_area_scene(&scene, 1, 0);
  mrgi_reference_options o = area_options();
  o.shadows = 0;
  mrgi_reference_result r;
  render_area(&scene, &o, &light, 1, &r);
  check_direct(&r, sample_sum_value, &data, 0.5, 3.0, 0.0,
               "area light, no visibility vs C sample sum");
  /* with visibility the occluder matters: the centre is in its umbra */
  o.shadows = 1;
  mrgi_reference_result shadowed;
  render_area(&scene, &o, &light, 1, &shadowed);
  MRGI_CHECK(mrgi_image_at(&shadowed.direct, 16, 16)[1] == 0.0f);
  MRGI_CHECK(mrgi_image_at(&r.direct, 16, 16)[1] > 0.02f);
  mrgi_reference_result_destroy(&shadowed);
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
  free(samples);
  mrgi_area_light_texture_pyramid_destroy(&pyramid);
  mrgi_image_destroy(&texture);
}

/* The area light's one bounce (mrgi_reference.h: L(q) includes X_area(q)):
 * a two-sided 0.2 x 0.2 light of radiance 3 (1, 0.5, 0.25) at height 0.5
 * between the floor (albedo 0.5, half-size 0.5) and the ceiling (albedo
 * 0.8, half-size 1, height 1). The ceiling, lit by the light's upper side
 * with X_area(q) = L F(q) (Hottel's parallel-rectangle factor at distance
 * 0.5), sends the floor point p the VTK irradiance
 *     X_ind(p) = (1/pi) int_ceiling 0.8 X_area(q) h^2 / r^4 dA_q,  h = 1,
 * integrated here by the midpoint rule on 200 x 200 cells. No point light:
 * the floor's indirect light is the area light's bounce alone. */
static double area_bounce_expected(double px, double pz)
{
  const int cells = 200;
  const double size = 2.0 / cells;
  double sum = 0.0;
  for (int j = 0; j < cells; ++j)
  {
    for (int i = 0; i < cells; ++i)
    {
      const double qx = -1.0 + (i + 0.5) * size, qz = -1.0 + (j + 0.5) * size;
      const double f = view_factor_rect(-0.1 - qx, 0.1 - qx, -0.1 - qz, 0.1 - qz, 0.5);
      const double dx = qx - px, dz = qz - pz;
      const double r2 = dx * dx + dz * dz + 1.0;
      sum += f / (r2 * r2) * size * size;
    }
  }
  /* mean of the three channels: 0.5 * 0.8 * 3 * (1 + 0.5 + 0.25) / 3 */
  return 0.5 * 0.8 * 1.75 * sum / pi;
}

static void test_area_bounce(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_create(&scene, 2, NULL) == MRGI_OK);
  make_square(&scene.meshes[0], "floor", 0, 0, 0, 0.5, 1, 0.5f);
  make_square(&scene.meshes[1], "ceiling", 0, 1, 0, 1, 0, 0.8f);
  camera_down(&scene, 0.3, 60);
  mrgi_area_light light = square_light(3.0);
  light.center[1] = 0.5;
  light.edge_u[0] = 0.2;
  light.edge_v[2] = 0.2;
  light.two_sided = 1;
  mrgi_reference_options o = base_options(8, 8);
  o.indirect_samples = 64;
  o.area_light_samples = 16;
  o.max_passes = 16;
  mrgi_reference_result r;
  render_area(&scene, &o, &light, 1, &r);
  const double half_h = 0.3 * tan(pi / 6.0);
  double diff = 0.0, expect = 0.0, var = 0.0;
  for (int32_t y = 0; y < 8; ++y)
  {
    for (int32_t x = 0; x < 8; ++x)
    {
      double gx, gz;
      ground_point(x + 0.5, y + 0.5, 8, 8, half_h, &gx, &gz);
      const double e = area_bounce_expected(gx, gz);
      const float* v = mrgi_image_at(&r.indirect, x, y);
      const double m = ((double)v[0] + v[1] + v[2]) / 3.0;
      const double se = mrgi_image_at(&r.indirect_stderr, x, y)[0];
      MRGI_CHECK(fabs(m - e) <= 6.0 * se + 0.02 * e);
      diff += m - e;
      expect += e;
      var += se * se;
    }
  }
  const double tol = 4.0 * sqrt(var) / 64.0 + 0.01 * expect / 64.0;
  printf("area light bounce: mean indirect %.6f, numeric integral %.6f (diff %.1e, tolerance "
         "%.1e), %d passes\n",
         (expect + diff) / 64.0, expect / 64.0, diff / 64.0, tol, (int)r.passes);
  MRGI_CHECK(expect > 0.0 && fabs(diff / 64.0) <= tol);
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

static void test_area_determinism_and_input(void)
{
  /* area lights bounce (the indirect image changes), a black one leaves it
   * bit for bit unchanged (its points draw from streams of their own), the
   * same seed gives the same direct image, another seed another one */
  mrgi_scene scene;
  make_bounce_scene(&scene, 1, 0);
  camera_down(&scene, 0.2, 30);
  mrgi_reference_options o = base_options(12, 12);
  o.indirect_samples = 8;
  o.max_passes = 3;
  o.threads = 2;
  mrgi_area_light light = square_light(1.0);
  light.center[1] = 0.5; /* between the floor and the ceiling */
  light.two_sided = 1;
  mrgi_reference_result plain, lit, again, other;
  render(&scene, &o, &plain);
  render_area(&scene, &o, &light, 1, &lit);
  {
    /* same seed and threads as `plain` */
    mrgi_area_light black = light;
    black.intensity = 0.0;
    mrgi_reference_result dark;
    render_area(&scene, &o, &black, 1, &dark);
    const size_t n = mrgi_image_value_count(&plain.indirect) * sizeof(float);
    MRGI_CHECK(memcmp(plain.indirect.pixels, dark.indirect.pixels, n) == 0);
    MRGI_CHECK(memcmp(plain.direct.pixels, dark.direct.pixels, n) == 0);
    mrgi_reference_result_destroy(&dark);
  }
  o.threads = 1;
  render_area(&scene, &o, &light, 1, &again);
  o.seed = 9;
  render_area(&scene, &o, &light, 1, &other);
  const size_t bytes = mrgi_image_value_count(&plain.indirect) * sizeof(float);
  MRGI_CHECK(memcmp(plain.indirect.pixels, lit.indirect.pixels, bytes) != 0);
  MRGI_CHECK(memcmp(plain.direct.pixels, lit.direct.pixels, bytes) != 0);
  MRGI_CHECK(memcmp(lit.direct.pixels, again.direct.pixels, bytes) == 0);
  MRGI_CHECK(memcmp(lit.direct.pixels, other.direct.pixels, bytes) != 0);
  MRGI_CHECK(plain.direct_relative_error == 0.0 && lit.direct_relative_error > 0.0);
  MRGI_CHECK(isfinite(lit.direct_relative_error));
  for (int64_t i = 0; i < 12 * 12; ++i)
  {
    MRGI_CHECK(plain.direct_stderr.pixels[i] == 0.0f);
  }
  mrgi_reference_result_destroy(&plain);
  mrgi_reference_result_destroy(&lit);
  mrgi_reference_result_destroy(&again);
  mrgi_reference_result_destroy(&other);

  /* the stopping rule waits for the direct image too: no indirect here, so
   * only the area light's noise decides (one pass: unknown, infinite) */
  mrgi_reference_result r;
  mrgi_reference_options stop = base_options(12, 12);
  stop.max_passes = 1;
  render_area(&scene, &stop, &light, 1, &r);
  MRGI_CHECK(r.passes == 1 && isinf(r.direct_relative_error) && r.relative_error == 0.0);
  MRGI_CHECK(isinf(r.direct_pixel_error) && r.pixel_error == 0.0);
  mrgi_reference_result_destroy(&r);
  stop.max_passes = 1000;
  stop.target_relative_error = 0.03;
  render_area(&scene, &stop, &light, 1, &r);
  printf("area light stopping rule: %d passes to direct per-pixel error %.2g (target 0.03)\n",
         (int)r.passes, r.direct_pixel_error);
  MRGI_CHECK(r.passes >= 3 && r.passes < 1000 && r.direct_pixel_error <= 0.03);
  mrgi_reference_result_destroy(&r);

  /* bad input */
  mrgi_error err;
  memset(&r, 0xAB, sizeof(r));
  MRGI_CHECK(mrgi_reference_render_area_lights(&scene, &o, NULL, 1, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "area_light_count 1") && r.direct_stderr.pixels == NULL);
  MRGI_CHECK(mrgi_reference_render_area_lights(&scene, &o, &light, -1, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_reference_render_area_lights(&scene, &o, &light, 65, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  mrgi_area_light bad = light;
  bad.intensity = -1.0;
  MRGI_CHECK(mrgi_reference_render_area_lights(&scene, &o, &bad, 1, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "mrgi_reference_render: area light 0: area light intensity"));
  bad = light;
  bad.edge_v[0] = 0.5; /* not perpendicular */
  MRGI_CHECK(mrgi_reference_render_area_lights(&scene, &o, &bad, 1, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "not perpendicular"));
  o.area_light_samples = 0;
  MRGI_CHECK(mrgi_reference_render_area_lights(&scene, &o, &light, 1, &r, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "area_light_samples = 0"));
  render(&scene, &o, &r); /* 0 is fine without area lights */
  mrgi_reference_result_destroy(&r);
  o.area_light_samples = MRGI_REFERENCE_MAX_AREA_LIGHT_SAMPLES + 1;
  MRGI_CHECK(mrgi_reference_options_validate(&o, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "area_light_samples = 4097"));
  mrgi_reference_options d;
  mrgi_reference_options_default(&d);
  MRGI_CHECK(d.area_light_samples == 16);
  mrgi_scene_destroy(&scene);
}

/* The Cornell box's own area light and emitter quad (the same rectangle):
 * the quad does not shadow the light, the ceiling behind the one-sided light
 * gets nothing, the floor below it matches the closed form where nothing
 * stands in between. */
static void test_area_cornell(void)
{
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_AREA, &scene, NULL) == MRGI_OK);
  mrgi_reference_options o = base_options(48, 48);
  o.area_light_samples = 16;
  o.max_passes = 4;
  mrgi_reference_result r;
  render_area(&scene, &o, scene.area_lights, scene.area_light_count, &r);
  /* ceiling row next to the light: no direct light (behind the light) */
  MRGI_CHECK(mrgi_image_at(&r.albedo, 10, 1)[0] > 0.7f);
  MRGI_CHECK(mrgi_image_at(&r.direct, 10, 1)[0] == 0.0f);
  /* the back wall's upper middle, facing the light from the side: lit */
  const float* wall = mrgi_image_at(&r.direct, 24, 12);
  printf("cornell-area: back wall direct (%.3f, %.3f, %.3f), %d passes, direct rel. error %.3g\n",
         wall[0], wall[1], wall[2], (int)r.passes, r.direct_relative_error);
  MRGI_CHECK(wall[0] > 0.05f && wall[0] > wall[1] && wall[1] > wall[2]); /* (17, 12, 4) on white */
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_direct),
    MRGI_TEST_CASE(test_area_bounce),
    MRGI_TEST_CASE(test_shadows),
    MRGI_TEST_CASE(test_pixel_center),
    MRGI_TEST_CASE(test_bounce),
    MRGI_TEST_CASE(test_cornell),
    MRGI_TEST_CASE(test_determinism_and_convergence),
    MRGI_TEST_CASE(test_progress_and_cancel),
    MRGI_TEST_CASE(test_quantile),
    MRGI_TEST_CASE(test_pixel_error),
    MRGI_TEST_CASE(test_per_pixel_stopping_rule),
    MRGI_TEST_CASE(test_bad_input),
    MRGI_TEST_CASE(test_area_unoccluded),
    MRGI_TEST_CASE(test_area_penumbra),
    MRGI_TEST_CASE(test_area_no_visibility),
    MRGI_TEST_CASE(test_area_determinism_and_input),
    MRGI_TEST_CASE(test_area_cornell),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
