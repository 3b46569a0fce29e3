/* Tests of the Cornell box builder against the published data: every
 * reference vertex present, bounds, winding, albedos, camera and the three
 * light variants. The reference table below is typed again on purpose (from
 * Cornell's "Cornell Box Data" page), independently of the builder's. */
#include "mrgi_scene_cornell.h"
#include "mrgi_test.h"

#include <string.h>

typedef struct reference_surface
{
  const char* mesh;
  int quad_count;
  float quads[5][4][3];
} reference_surface;

static const reference_surface reference[] = {
  { "floor", 1, { { { 552.8f, 0, 0 }, { 0, 0, 0 }, { 0, 0, 559.2f }, { 549.6f, 0, 559.2f } } } },
  { "ceiling", 1,
    { { { 556, 548.8f, 0 }, { 556, 548.8f, 559.2f }, { 0, 548.8f, 559.2f }, { 0, 548.8f, 0 } } } },
  { "back_wall", 1,
    { { { 549.6f, 0, 559.2f }, { 0, 0, 559.2f }, { 0, 548.8f, 559.2f }, { 556, 548.8f, 559.2f } } } },
  { "right_wall", 1,
    { { { 0, 0, 559.2f }, { 0, 0, 0 }, { 0, 548.8f, 0 }, { 0, 548.8f, 559.2f } } } },
  { "left_wall", 1,
    { { { 552.8f, 0, 0 }, { 549.6f, 0, 559.2f }, { 556, 548.8f, 559.2f }, { 556, 548.8f, 0 } } } },
  { "short_block", 5,
    { { { 130, 165, 65 }, { 82, 165, 225 }, { 240, 165, 272 }, { 290, 165, 114 } },
      { { 290, 0, 114 }, { 290, 165, 114 }, { 240, 165, 272 }, { 240, 0, 272 } },
      { { 130, 0, 65 }, { 130, 165, 65 }, { 290, 165, 114 }, { 290, 0, 114 } },
      { { 82, 0, 225 }, { 82, 165, 225 }, { 130, 165, 65 }, { 130, 0, 65 } },
      { { 240, 0, 272 }, { 240, 165, 272 }, { 82, 165, 225 }, { 82, 0, 225 } } } },
  { "tall_block", 5,
    { { { 423, 330, 247 }, { 265, 330, 296 }, { 314, 330, 456 }, { 472, 330, 406 } },
      { { 423, 0, 247 }, { 423, 330, 247 }, { 472, 330, 406 }, { 472, 0, 406 } },
      { { 472, 0, 406 }, { 472, 330, 406 }, { 314, 330, 456 }, { 314, 0, 456 } },
      { { 314, 0, 456 }, { 314, 330, 456 }, { 265, 330, 296 }, { 265, 0, 296 } },
      { { 265, 0, 296 }, { 265, 330, 296 }, { 423, 330, 247 }, { 423, 0, 247 } } } },
};
static const float reference_light[4][3] = {
  { 343, 548.8f, 227 }, { 343, 548.8f, 332 }, { 213, 548.8f, 332 }, { 213, 548.8f, 227 }
};
static const float white[3] = { 0.725f, 0.71f, 0.68f };
static const float red[3] = { 0.63f, 0.065f, 0.05f };
static const float green[3] = { 0.14f, 0.45f, 0.091f };

static const mrgi_cornell_variant variants[3] = { MRGI_CORNELL_POINT, MRGI_CORNELL_SPOT,
                                                  MRGI_CORNELL_AREA };

static const mrgi_mesh* find(const mrgi_scene* scene, const char* name)
{
  const int32_t i = mrgi_scene_find_mesh(scene, name);
  if (i < 0)
  {
    fprintf(stderr, "no mesh named '%s'\n", name);
  }
  MRGI_CHECK(i >= 0);
  return &scene->meshes[i];
}

static int has_vertex(const mrgi_mesh* mesh, const float p[3], float y_offset)
{
  for (int64_t v = 0; v < mesh->vertex_count; ++v)
  {
    const float* q = mesh->positions + 3 * v;
    if (fabs(q[0] - p[0]) <= 1e-4 && fabs(q[1] - (p[1] - y_offset)) <= 1e-4 &&
        fabs(q[2] - p[2]) <= 1e-4)
    {
      return 1;
    }
  }
  fprintf(stderr, "mesh '%s' lacks vertex (%g, %g, %g)\n", mesh->name, (double)p[0],
          (double)(p[1] - y_offset), (double)p[2]);
  return 0;
}

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void check_geometry(const mrgi_scene* scene)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_scene_validate(scene, &err) == MRGI_OK);
  for (size_t s = 0; s < sizeof(reference) / sizeof(reference[0]); ++s)
  {
    const mrgi_mesh* mesh = find(scene, reference[s].mesh);
    MRGI_CHECK(mesh->triangle_count == 2 * reference[s].quad_count);
    MRGI_CHECK(mesh->vertex_count == 4 * reference[s].quad_count);
    MRGI_CHECK(mesh->normals != NULL);
    /* Each published quad is 4 consecutive vertices, in the published order. */
    for (int q = 0; q < reference[s].quad_count; ++q)
    {
      for (int k = 0; k < 4; ++k)
      {
        const float* expected = reference[s].quads[q][k];
        const float* actual = mesh->positions + 3 * (4 * q + k);
        if (memcmp(expected, actual, 3 * sizeof(float)) != 0)
        {
          fprintf(stderr, "mesh '%s' quad %d corner %d: (%g, %g, %g), published (%g, %g, %g)\n",
                  mesh->name, q, k, (double)actual[0], (double)actual[1], (double)actual[2],
                  (double)expected[0], (double)expected[1], (double)expected[2]);
        }
        MRGI_CHECK(memcmp(expected, actual, 3 * sizeof(float)) == 0);
      }
    }
    const float* albedo = strcmp(mesh->name, "left_wall") == 0    ? red
                          : strcmp(mesh->name, "right_wall") == 0 ? green
                                                                  : white;
    MRGI_CHECK(memcmp(mesh->albedo, albedo, sizeof(mesh->albedo)) == 0);
    MRGI_CHECK(mesh->emission[0] == 0.0f && mesh->emission[1] == 0.0f && mesh->emission[2] == 0.0f);
  }
  /* The tall block's top vertex quoted in the brief, found exactly. */
  const float tall_top[3] = { 423.0f, 330.0f, 247.0f };
  MRGI_CHECK(has_vertex(find(scene, "tall_block"), tall_top, 0.0f));

  double bounds[6];
  MRGI_CHECK(mrgi_scene_bounds(scene, bounds, &err) == MRGI_OK);
  const double expected[6] = { 0.0, 556.0, 0.0, 548.8, 0.0, 559.2 };
  for (int i = 0; i < 6; ++i)
  {
    MRGI_CHECK_NEAR(bounds[i], expected[i], 1e-4);
  }
}

/* Walls (and floor, ceiling) face the box's centre; block faces face away
 * from their block's centre; vertex normals agree with the faces. */
static void check_winding(const mrgi_scene* scene)
{
  mrgi_error err;
  const double box_centre[3] = { 278.0, 274.4, 279.6 };
  for (int32_t m = 0; m < scene->mesh_count; ++m)
  {
    const mrgi_mesh* mesh = &scene->meshes[m];
    const int is_block = strstr(mesh->name, "block") != NULL;
    const int is_light = strcmp(mesh->name, "light") == 0;
    double block_centre[3] = { 0, 0, 0 };
    for (int64_t v = 0; v < mesh->vertex_count; ++v)
    {
      for (int a = 0; a < 3; ++a)
      {
        block_centre[a] += mesh->positions[3 * v + a] / (double)mesh->vertex_count;
      }
    }
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      double normal[3], centroid[3], area;
      MRGI_CHECK(mrgi_mesh_triangle_geometry(mesh, t, normal, centroid, &area, &err) == MRGI_OK);
      MRGI_CHECK(area > 100.0);
      double towards[3];
      for (int a = 0; a < 3; ++a)
      {
        towards[a] = is_block ? centroid[a] - block_centre[a] : box_centre[a] - centroid[a];
      }
      if (is_light)
      {
        MRGI_CHECK_NEAR(normal[1], -1.0, 1e-9); /* the emitter faces down */
      }
      else
      {
        if (dot3(normal, towards) <= 0.0)
        {
          fprintf(stderr, "mesh '%s' triangle %lld faces the wrong way\n", mesh->name,
                  (long long)t);
        }
        MRGI_CHECK(dot3(normal, towards) > 0.0);
      }
      /* Flat shading: each corner's normal is the face's (within the
       * ~0.3 degree warp of the published left wall). */
      for (int corner = 0; corner < 3; ++corner)
      {
        const float* n = mesh->normals + 3 * mesh->indices[3 * t + corner];
        const double nd[3] = { n[0], n[1], n[2] };
        MRGI_CHECK_NEAR(sqrt(dot3(nd, nd)), 1.0, 1e-6);
        MRGI_CHECK(dot3(nd, normal) > 0.9999);
      }
    }
  }
  /* Blocks are open at the bottom: no face looks down. */
  const char* blocks[2] = { "short_block", "tall_block" };
  for (int b = 0; b < 2; ++b)
  {
    const mrgi_mesh* mesh = find(scene, blocks[b]);
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      double normal[3];
      MRGI_CHECK(mrgi_mesh_triangle_geometry(mesh, t, normal, NULL, NULL, &err) == MRGI_OK);
      MRGI_CHECK(normal[1] > -0.5);
    }
  }
  /* Walls are inside-facing by name as well: the red wall is at large x and
   * faces -x, the green one at x = 0 faces +x, the floor faces up. */
  double normal[3];
  MRGI_CHECK(mrgi_mesh_triangle_geometry(find(scene, "left_wall"), 0, normal, NULL, NULL, &err) ==
             MRGI_OK);
  MRGI_CHECK(normal[0] < -0.99);
  MRGI_CHECK(mrgi_mesh_triangle_geometry(find(scene, "right_wall"), 0, normal, NULL, NULL, &err) ==
             MRGI_OK);
  MRGI_CHECK(normal[0] > 0.99);
  MRGI_CHECK(mrgi_mesh_triangle_geometry(find(scene, "floor"), 1, normal, NULL, NULL, &err) ==
             MRGI_OK);
  MRGI_CHECK_NEAR(normal[1], 1.0, 1e-12);
}

static void check_camera(const mrgi_scene* scene)
{
  const mrgi_camera* camera = &scene->camera;
  MRGI_CHECK_NEAR(camera->view_angle_deg, 39.3, 0.05);
  MRGI_CHECK_NEAR(camera->view_angle_deg, 2.0 * atan(12.5 / 35.0) * 180.0 / 3.14159265358979, 1e-9);
  MRGI_CHECK_NEAR(camera->position[0], 278.0, 0.0);
  MRGI_CHECK_NEAR(camera->position[1], 273.0, 0.0);
  MRGI_CHECK_NEAR(camera->position[2], -800.0, 0.0);
  /* Looking along +z with +y up: x = 0 (green) appears on the right. */
  MRGI_CHECK(camera->focal_point[2] > camera->position[2]);
  MRGI_CHECK_NEAR(camera->focal_point[0], camera->position[0], 0.0);
  MRGI_CHECK_NEAR(camera->focal_point[1], camera->position[1], 0.0);
  MRGI_CHECK(camera->view_up[1] > 0.0 && camera->view_up[0] == 0.0 && camera->view_up[2] == 0.0);
}

static void test_point_variant(void)
{
  mrgi_error err;
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_POINT, &scene, &err) == MRGI_OK);
  MRGI_CHECK(scene.mesh_count == 7);
  MRGI_CHECK(mrgi_scene_find_mesh(&scene, "light") == -1);
  MRGI_CHECK(scene.light_count == 1 && scene.area_light_count == 0);
  const mrgi_light* light = &scene.lights[0];
  MRGI_CHECK(light->type == MRGI_LIGHT_POSITIONAL);
  MRGI_CHECK_NEAR(light->cone_angle_deg, 90.0, 0.0);
  MRGI_CHECK_NEAR(light->position[0], 278.0, 0.0);
  MRGI_CHECK_NEAR(light->position[1], 548.0, 0.0);
  MRGI_CHECK_NEAR(light->position[2], 279.5, 0.0);
  MRGI_CHECK_NEAR(light->intensity, 1.0, 0.0);
  MRGI_CHECK(light->color[0] == 1.0 && light->color[1] == 1.0 && light->color[2] == 1.0);
  /* Inside the box, below the ceiling. */
  MRGI_CHECK(light->position[1] < 548.8);
  mrgi_scene_destroy(&scene);
}

static void test_spot_variant(void)
{
  mrgi_error err;
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_SPOT, &scene, &err) == MRGI_OK);
  MRGI_CHECK(scene.light_count == 1 && scene.area_light_count == 0);
  const mrgi_light* light = &scene.lights[0];
  MRGI_CHECK(light->type == MRGI_LIGHT_SPOT);
  MRGI_CHECK(light->cone_angle_deg > 0.0 && light->cone_angle_deg < 90.0);
  MRGI_CHECK_NEAR(light->position[1], 548.0, 0.0);
  MRGI_CHECK_NEAR(light->intensity, 1.0, 0.0);
  double axis[3];
  for (int a = 0; a < 3; ++a)
  {
    axis[a] = light->focal_point[a] - light->position[a];
  }
  const double axis_length = sqrt(dot3(axis, axis));
  MRGI_CHECK_NEAR(axis[1] / axis_length, -1.0, 0.0); /* straight down */
  /* Every floor corner is inside the cone, and so is the middle of each side
   * wall (the variant lights walls and floor directly). */
  double widest = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    const float* corner = reference[0].quads[0][k];
    const double to_corner[3] = { corner[0] - light->position[0], corner[1] - light->position[1],
                                  corner[2] - light->position[2] };
    const double angle =
      acos(dot3(axis, to_corner) / (axis_length * sqrt(dot3(to_corner, to_corner)))) * 180.0 /
      3.14159265358979;
    MRGI_CHECK(angle < light->cone_angle_deg);
    widest = angle > widest ? angle : widest;
  }
  MRGI_CHECK_NEAR(widest, 35.74, 0.01);
  const double wall_middles[2][3] = { { 554.0, 274.4, 279.6 }, { 0.0, 274.4, 279.6 } };
  for (int k = 0; k < 2; ++k)
  {
    const double to_wall[3] = { wall_middles[k][0] - light->position[0],
                                wall_middles[k][1] - light->position[1],
                                wall_middles[k][2] - light->position[2] };
    const double angle = acos(dot3(axis, to_wall) / (axis_length * sqrt(dot3(to_wall, to_wall)))) *
      180.0 / 3.14159265358979;
    MRGI_CHECK(angle < light->cone_angle_deg);
  }
  MRGI_CHECK(light->cone_angle_deg < 90.0);
  mrgi_scene_destroy(&scene);
}

static void test_area_variant(void)
{
  mrgi_error err;
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_AREA, &scene, &err) == MRGI_OK);
  MRGI_CHECK(scene.mesh_count == 8);
  MRGI_CHECK(scene.light_count == 0 && scene.area_light_count == 1);
  const mrgi_area_light* light = &scene.area_lights[0];
  MRGI_CHECK_NEAR(mrgi_area_light_area(light), 130.0 * 105.0, 1e-9);
  double normal[3];
  MRGI_CHECK(mrgi_area_light_normal(light, normal, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(normal[1], -1.0, 0.0);
  MRGI_CHECK(light->two_sided == 0);
  MRGI_CHECK(light->color[0] == 17.0 && light->color[1] == 12.0 && light->color[2] == 4.0);
  MRGI_CHECK(light->intensity == 1.0 && light->texture == NULL);
  MRGI_CHECK_NEAR(light->center[0], 278.0, 1e-9);
  MRGI_CHECK_NEAR(light->center[2], 279.5, 1e-9);
  MRGI_CHECK_NEAR(light->center[1], 548.8 - MRGI_CORNELL_EMITTER_DROP_MM, 1e-4);
  /* Below the ceiling, clearly: no coplanar surfaces. */
  MRGI_CHECK(light->center[1] < 548.8 - 0.1);

  const mrgi_mesh* emitter = find(&scene, "light");
  MRGI_CHECK(emitter->triangle_count == 2);
  MRGI_CHECK(emitter->albedo[0] == 0.0f && emitter->albedo[1] == 0.0f && emitter->albedo[2] == 0.0f);
  MRGI_CHECK(emitter->emission[0] == 17.0f && emitter->emission[1] == 12.0f &&
             emitter->emission[2] == 4.0f);
  for (int k = 0; k < 4; ++k)
  {
    MRGI_CHECK(has_vertex(emitter, reference_light[k], (float)MRGI_CORNELL_EMITTER_DROP_MM));
  }
  /* The area light and the emitter mesh are the same rectangle. */
  double corners[4][3];
  MRGI_CHECK(mrgi_area_light_corners(light, corners, &err) == MRGI_OK);
  for (int k = 0; k < 4; ++k)
  {
    const float corner[3] = { (float)corners[k][0], (float)corners[k][1], (float)corners[k][2] };
    MRGI_CHECK(has_vertex(emitter, corner, 0.0f));
  }
  double area = 0.0;
  MRGI_CHECK(mrgi_mesh_total_area(emitter, &area, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(area, 13650.0, 1e-6);
  mrgi_scene_destroy(&scene);
}

static void test_names_and_bad_input(void)
{
  mrgi_error err;
  for (int i = 0; i < 3; ++i)
  {
    const char* name = mrgi_cornell_variant_name(variants[i]);
    MRGI_CHECK(name != NULL);
    mrgi_cornell_variant parsed = (mrgi_cornell_variant)-1;
    MRGI_CHECK(mrgi_cornell_variant_parse(name, &parsed, &err) == MRGI_OK);
    MRGI_CHECK(parsed == variants[i]);
  }
  MRGI_CHECK(strcmp(mrgi_cornell_variant_name(MRGI_CORNELL_POINT), "cornell") == 0);
  MRGI_CHECK(strcmp(mrgi_cornell_variant_name(MRGI_CORNELL_SPOT), "cornell-spot") == 0);
  MRGI_CHECK(strcmp(mrgi_cornell_variant_name(MRGI_CORNELL_AREA), "cornell-area") == 0);
  MRGI_CHECK(mrgi_cornell_variant_name((mrgi_cornell_variant)3) == NULL);

  mrgi_cornell_variant parsed;
  MRGI_CHECK(mrgi_cornell_variant_parse("cornell-disco", &parsed, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "cornell-disco") && strstr(err.message, "cornell-area"));
  MRGI_CHECK(mrgi_cornell_variant_parse(NULL, &parsed, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_cornell_variant_parse("cornell", NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);

  mrgi_scene scene;
  static const mrgi_scene zero;
  memset(&scene, 0x77, sizeof(scene));
  MRGI_CHECK(mrgi_scene_cornell_box((mrgi_cornell_variant)42, &scene, &err) ==
             MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "variant 42") != NULL);
  MRGI_CHECK(memcmp(&scene, &zero, sizeof(zero)) == 0);
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_POINT, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_scene_cornell_box(MRGI_CORNELL_POINT, NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/* Runs `check` on the scene of each variant. */
static void for_each_variant(void (*check)(const mrgi_scene*))
{
  for (int i = 0; i < 3; ++i)
  {
    mrgi_error err;
    mrgi_scene scene;
    MRGI_CHECK(mrgi_scene_cornell_box(variants[i], &scene, &err) == MRGI_OK);
    check(&scene);
    mrgi_scene_destroy(&scene);
  }
}

static void test_geometry(void)
{
  for_each_variant(check_geometry);
}

static void test_winding(void)
{
  for_each_variant(check_winding);
}

static void test_camera(void)
{
  for_each_variant(check_camera);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_geometry),
    MRGI_TEST_CASE(test_winding),
    MRGI_TEST_CASE(test_camera),
    MRGI_TEST_CASE(test_point_variant),
    MRGI_TEST_CASE(test_spot_variant),
    MRGI_TEST_CASE(test_area_variant),
    MRGI_TEST_CASE(test_names_and_bad_input),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
