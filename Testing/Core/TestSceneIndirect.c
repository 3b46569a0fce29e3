/* Tests of the indirect-light scenes (mrgi_scene_indirect.h): they build and
 * validate; winding agrees with the normals, walls face the inside and the
 * statue faces out; the corridors and the U are closed and the corner is
 * open (seen by the ground truth's rays from the camera in six directions);
 * the corridor's statue gets no direct light but indirect light (geometry,
 * and the ground truth with secondary visibility); the u-shape camera sees
 * no directly lit surface; names round-trip and unknown names are refused. */
#include "mrgi_reference.h"
#include "mrgi_scene_indirect.h"
#include "mrgi_test.h"

#include <math.h>
#include <string.h>

static const mrgi_indirect_scene all[4] = { MRGI_INDIRECT_CORRIDOR, MRGI_INDIRECT_CORRIDOR_LARGE,
                                            MRGI_INDIRECT_CORNER, MRGI_INDIRECT_U_SHAPE };

static void build(mrgi_indirect_scene which, mrgi_scene* scene)
{
  mrgi_error err;
  const mrgi_status s = mrgi_scene_indirect(which, scene, &err);
  if (s)
  {
    fprintf(stderr, "%s: %s\n", mrgi_indirect_scene_name(which), err.message);
  }
  MRGI_CHECK(s == MRGI_OK);
  MRGI_CHECK(mrgi_scene_validate(scene, &err) == MRGI_OK);
}

static void sub3(const float* a, const float* b, double out[3])
{
  for (int i = 0; i < 3; ++i)
  {
    out[i] = (double)a[i] - (double)b[i];
  }
}

static void cross3(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Whether p lies in the open space the scene's camera stands in. */
static int inside(mrgi_indirect_scene which, const double p[3])
{
  switch (which)
  {
    case MRGI_INDIRECT_CORRIDOR:
    case MRGI_INDIRECT_CORRIDOR_LARGE:
    {
      const double length = which == MRGI_INDIRECT_CORRIDOR ? 12.0 : 120.0;
      return fabs(p[0]) < 1.0 && p[1] > 0.0 && p[1] < 2.5 && p[2] > 0.0 && p[2] < length;
    }
    case MRGI_INDIRECT_CORNER:
      return p[0] > 0.0 && p[1] > 0.0 && p[2] < 4.0;
    case MRGI_INDIRECT_U_SHAPE:
      return p[0] > 0.0 && p[0] < 6.0 && p[1] > 0.0 && p[1] < 2.5 && p[2] > 0.0 && p[2] < 6.0 &&
        !(p[0] > 2.0 && p[0] < 4.0 && p[2] < 4.0);
  }
  return 0;
}

static void test_build(void)
{
  double length[2] = { 0, 0 };
  for (int k = 0; k < 4; ++k)
  {
    mrgi_scene scene;
    build(all[k], &scene);
    double b[6];
    MRGI_CHECK(mrgi_scene_bounds(&scene, b, NULL) == MRGI_OK);
    printf("%-15s %d meshes, %lld triangles, bounds x %.2f..%.2f y %.2f..%.2f z %.2f..%.2f\n",
           mrgi_indirect_scene_name(all[k]), (int)scene.mesh_count,
           (long long)mrgi_scene_triangle_count(&scene), b[0], b[1], b[2], b[3], b[4], b[5]);
    MRGI_CHECK(scene.light_count == 1 && scene.lights[0].type == MRGI_LIGHT_SPOT);
    MRGI_CHECK(scene.lights[0].cone_angle_deg > 0.0 && scene.lights[0].cone_angle_deg < 90.0);
    MRGI_CHECK(scene.area_light_count == 0);
    if (k < 2)
    {
      length[k] = b[5] - b[4];
      MRGI_CHECK(mrgi_scene_find_mesh(&scene, "statue") >= 0);
      MRGI_CHECK(mrgi_scene_find_mesh(&scene, "near_wall") >= 0);
    }
    /* Every tile is at most MRGI_INDIRECT_TILE_M on a side: triangle areas
     * stay <= half a tile. */
    for (int32_t m = 0; m < scene.mesh_count; ++m)
    {
      const mrgi_mesh* mesh = &scene.meshes[m];
      for (int64_t t = 0; t < mesh->triangle_count; ++t)
      {
        double n[3], area = 0.0;
        MRGI_CHECK(mrgi_mesh_triangle_geometry(mesh, t, n, NULL, &area, NULL) == MRGI_OK);
        MRGI_CHECK(area > 0.0 && area <= 0.5 * MRGI_INDIRECT_TILE_M * MRGI_INDIRECT_TILE_M + 1e-6);
      }
    }
    mrgi_scene_destroy(&scene);
  }
  MRGI_CHECK_NEAR(length[0], 12.0, 1e-6);
  MRGI_CHECK_NEAR(length[1], 120.0, 1e-6);
}

/* Winding (counter-clockwise = front) agrees with the vertex normals; walls
 * face the camera's space; the statue's normals point out of it. */
static void test_facing(void)
{
  for (int k = 0; k < 4; ++k)
  {
    mrgi_scene scene;
    build(all[k], &scene);
    for (int32_t m = 0; m < scene.mesh_count; ++m)
    {
      const mrgi_mesh* mesh = &scene.meshes[m];
      const int statue = strcmp(mesh->name, "statue") == 0;
      MRGI_CHECK(mesh->normals != NULL);
      for (int64_t t = 0; t < mesh->triangle_count; ++t)
      {
        const uint32_t* i = mesh->indices + 3 * t;
        const float* p0 = mesh->positions + 3 * (size_t)i[0];
        double e1[3], e2[3], g[3], c[3], n[3];
        sub3(mesh->positions + 3 * (size_t)i[1], p0, e1);
        sub3(mesh->positions + 3 * (size_t)i[2], p0, e2);
        cross3(e1, e2, g);
        for (int a = 0; a < 3; ++a)
        {
          c[a] = ((double)p0[a] + mesh->positions[3 * (size_t)i[1] + a] +
                  mesh->positions[3 * (size_t)i[2] + a]) / 3.0;
          n[a] = (double)mesh->normals[3 * (size_t)i[0] + a];
        }
        if (dot3(g, n) <= 0.0)
        {
          MRGI_FAIL("%s %s triangle %lld: winding against its normal",
                    mrgi_indirect_scene_name(all[k]), mesh->name, (long long)t);
        }
        double front[3], back[3];
        for (int a = 0; a < 3; ++a)
        {
          front[a] = c[a] + 1e-3 * n[a];
          back[a] = c[a] - 1e-3 * n[a];
        }
        /* Walls: the front is the open space, the back is not. The statue
         * stands in the open space: its front is open, its back is not. */
        const int ok = statue ? inside(all[k], front) : inside(all[k], front) && !inside(all[k], back);
        if (!ok)
        {
          MRGI_FAIL("%s %s triangle %lld faces the wrong way", mrgi_indirect_scene_name(all[k]),
                    mesh->name, (long long)t);
        }
      }
    }
    mrgi_scene_destroy(&scene);
  }
}

static mrgi_reference_options options(int32_t size)
{
  mrgi_reference_options o;
  mrgi_reference_options_default(&o);
  o.width = o.height = size;
  o.indirect_samples = 0;
  o.max_passes = 1;
  o.target_relative_error = 0.0;
  o.secondary_visibility = 1;
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
}

/* Pixels without a surface in six 90-degree views from the camera. */
static int64_t background_around_camera(mrgi_scene* scene)
{
  static const double dirs[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 },
                                     { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
  const mrgi_camera saved = scene->camera;
  int64_t open = 0;
  for (int d = 0; d < 6; ++d)
  {
    mrgi_camera* c = &scene->camera;
    for (int a = 0; a < 3; ++a)
    {
      c->focal_point[a] = c->position[a] + dirs[d][a];
    }
    c->view_up[0] = 0.0;
    c->view_up[1] = dirs[d][1] != 0.0 ? 0.0 : 1.0;
    c->view_up[2] = dirs[d][1] != 0.0 ? 1.0 : 0.0;
    c->view_angle_deg = 90.0;
    mrgi_reference_options o = options(24);
    mrgi_reference_result r;
    render(scene, &o, &r);
    for (int64_t p = 0; p < 24 * 24; ++p)
    {
      open += r.background[p];
    }
    mrgi_reference_result_destroy(&r);
    scene->camera = saved;
  }
  return open;
}

static void test_closed(void)
{
  for (int k = 0; k < 4; ++k)
  {
    mrgi_scene scene;
    build(all[k], &scene);
    const int64_t open = background_around_camera(&scene);
    /* The same from the light's position. */
    const mrgi_camera camera = scene.camera;
    memcpy(scene.camera.position, scene.lights[0].position, sizeof(camera.position));
    const int64_t open_light = background_around_camera(&scene);
    scene.camera = camera;
    printf("%s: %lld of %d rays from the camera escape, %lld from the light\n",
           mrgi_indirect_scene_name(all[k]), (long long)open, 6 * 24 * 24, (long long)open_light);
    if (all[k] == MRGI_INDIRECT_CORNER)
    {
      MRGI_CHECK(open > 0); /* open by design: two walls and a floor */
    }
    else
    {
      MRGI_CHECK(open == 0 && open_light == 0);
    }
    mrgi_scene_destroy(&scene);
  }
}

/* The statue (its albedo made unique to find its pixels in the truth's
 * albedo image) gets no direct light and clearly some indirect light. */
static void check_statue(mrgi_indirect_scene which)
{
  mrgi_scene scene;
  build(which, &scene);
  const int32_t s = mrgi_scene_find_mesh(&scene, "statue");
  MRGI_CHECK(s >= 0);
  /* Geometry: every statue vertex (the ball's 24 x 12 grid, the pedestal's
   * tile corners) is more than 10 degrees outside the spot's cone. */
  const mrgi_light* light = &scene.lights[0];
  double axis[3];
  for (int a = 0; a < 3; ++a)
  {
    axis[a] = light->focal_point[a] - light->position[a];
  }
  const mrgi_mesh* statue = &scene.meshes[s];
  double nearest = 180.0;
  for (int64_t v = 0; v < statue->vertex_count; ++v)
  {
    double d[3];
    for (int a = 0; a < 3; ++a)
    {
      d[a] = statue->positions[3 * v + a] - light->position[a];
    }
    const double angle =
      acos(dot3(d, axis) / sqrt(dot3(d, d) * dot3(axis, axis))) * 180.0 / 3.14159265358979323846;
    nearest = angle < nearest ? angle : nearest;
  }
  printf("%s: statue at least %.1f deg off the spot's axis (cone %.1f)\n",
         mrgi_indirect_scene_name(which), nearest, light->cone_angle_deg);
  MRGI_CHECK(nearest > light->cone_angle_deg + 10.0);

  /* The truth with secondary visibility. */
  const float tag[3] = { 0.123f, 0.456f, 0.789f };
  memcpy(scene.meshes[s].albedo, tag, sizeof(tag));
  mrgi_reference_options o = options(48);
  o.indirect_samples = 16;
  o.max_passes = 4;
  mrgi_reference_result r;
  render(&scene, &o, &r);
  int64_t pixels = 0;
  double direct = 0.0, indirect = 0.0, wall_indirect = 0.0;
  int64_t wall = 0;
  for (int32_t y = 0; y < 48; ++y)
  {
    for (int32_t x = 0; x < 48; ++x)
    {
      const float* albedo = mrgi_image_at(&r.albedo, x, y);
      const int on_statue = fabsf(albedo[0] - tag[0]) < 1e-6f && fabsf(albedo[2] - tag[2]) < 1e-6f;
      if (on_statue)
      {
        ++pixels;
        direct += mrgi_image_at(&r.direct, x, y)[2];
        indirect += mrgi_image_at(&r.indirect, x, y)[2] / tag[2];
      }
      else if (!r.background[y * 48 + x] && mrgi_image_at(&r.direct, x, y)[1] == 0.0f)
      {
        ++wall;
        wall_indirect += mrgi_image_at(&r.indirect, x, y)[1] / albedo[1];
      }
    }
  }
  printf("%s: statue %lld pixels, direct %.3g, mean irradiance factor %.4g (unlit rest %.4g)\n",
         mrgi_indirect_scene_name(which), (long long)pixels, direct, indirect / (double)pixels,
         wall_indirect / (double)(wall ? wall : 1));
  MRGI_CHECK(pixels >= 20);
  MRGI_CHECK(direct == 0.0);
  MRGI_CHECK(indirect / (double)pixels > 0.1 * wall_indirect / (double)(wall ? wall : 1));
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

static void test_statue_lit_only_indirectly(void)
{
  check_statue(MRGI_INDIRECT_CORRIDOR);
  check_statue(MRGI_INDIRECT_CORRIDOR_LARGE);
}

/* u-shape: the camera sees no directly lit surface (RIHKS11 figure 10: the
 * light is in the other arm), but indirect light. */
static void test_u_shape_view(void)
{
  mrgi_scene scene;
  build(MRGI_INDIRECT_U_SHAPE, &scene);
  mrgi_reference_options o = options(32);
  o.indirect_samples = 16;
  o.max_passes = 2;
  mrgi_reference_result r;
  render(&scene, &o, &r);
  int64_t lit = 0, bright = 0;
  for (int32_t y = 0; y < 32; ++y)
  {
    for (int32_t x = 0; x < 32; ++x)
    {
      MRGI_CHECK(r.background[y * 32 + x] == 0);
      lit += mrgi_image_at(&r.direct, x, y)[0] > 0.0f;
      bright += mrgi_image_at(&r.indirect, x, y)[0] > 0.0f;
    }
  }
  printf("u-shape view: %lld directly lit pixels, %lld with indirect light of 1024\n",
         (long long)lit, (long long)bright);
  MRGI_CHECK(lit == 0);
  MRGI_CHECK(bright > 100);
  mrgi_reference_result_destroy(&r);
  mrgi_scene_destroy(&scene);
}

static void test_names_and_bad_input(void)
{
  for (int k = 0; k < 4; ++k)
  {
    mrgi_indirect_scene parsed = MRGI_INDIRECT_CORRIDOR;
    MRGI_CHECK(mrgi_indirect_scene_parse(mrgi_indirect_scene_name(all[k]), &parsed, NULL) == MRGI_OK);
    MRGI_CHECK(parsed == all[k]);
  }
  mrgi_error err;
  mrgi_indirect_scene parsed;
  MRGI_CHECK(mrgi_indirect_scene_parse("corridor-huge", &parsed, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "corridor-huge") && strstr(err.message, "u-shape"));
  MRGI_CHECK(mrgi_indirect_scene_parse("cornell", &parsed, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_indirect_scene_parse(NULL, &parsed, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_indirect_scene_parse("corner", NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_indirect_scene_name((mrgi_indirect_scene)42) == NULL);
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_indirect((mrgi_indirect_scene)42, &scene, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(scene.mesh_count == 0 && scene.meshes == NULL);
  MRGI_CHECK(mrgi_scene_indirect(MRGI_INDIRECT_CORNER, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_build),
    MRGI_TEST_CASE(test_facing),
    MRGI_TEST_CASE(test_closed),
    MRGI_TEST_CASE(test_statue_lit_only_indirectly),
    MRGI_TEST_CASE(test_u_shape_view),
    MRGI_TEST_CASE(test_names_and_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
