/* Tests of mrgi_scene: lifetime, validation of cameras, lights and area
 * lights, and the area-light helpers. */
#include "mrgi_scene.h"
#include "mrgi_test.h"

#include <string.h>

static int message_has(const mrgi_error* err, const char* text)
{
  if (!strstr(err->message, text))
  {
    fprintf(stderr, "message '%s' lacks '%s'\n", err->message, text);
    return 0;
  }
  return 1;
}

/* A valid scene: one triangle, a camera on -z looking at the origin, a spot
 * light and a 2 x 1 area light facing down. */
static void make_scene(mrgi_scene* scene)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_scene_create(scene, 2, &err) == MRGI_OK);
  const char* names[2] = { "first", "second" };
  for (int i = 0; i < 2; ++i)
  {
    mrgi_mesh* mesh = &scene->meshes[i];
    MRGI_CHECK(mrgi_mesh_create(mesh, names[i], 3, 1, 0, &err) == MRGI_OK);
    const float triangle[3][3] = { { 0, 0, (float)i }, { 1, 0, (float)i }, { 0, 1, (float)i } };
    memcpy(mesh->positions, triangle, sizeof(triangle));
    mesh->indices[1] = 1;
    mesh->indices[2] = 2;
    mesh->albedo[0] = mesh->albedo[1] = mesh->albedo[2] = 0.5f;
  }
  scene->camera.position[2] = -5.0;
  scene->camera.view_up[1] = 1.0;
  scene->camera.view_angle_deg = 30.0;

  mrgi_light* spot = &scene->lights[0];
  spot->type = MRGI_LIGHT_SPOT;
  spot->position[1] = 3.0;
  spot->color[0] = spot->color[1] = spot->color[2] = 1.0;
  spot->intensity = 1.0;
  spot->cone_angle_deg = 30.0;
  spot->exponent = 1.0;
  scene->light_count = 1;

  mrgi_area_light* area = &scene->area_lights[0];
  area->center[1] = 2.0;
  area->edge_u[2] = 1.0; /* (0,0,1) x (2,0,0) = (0,2,0): faces up */
  area->edge_v[0] = 2.0;
  area->color[0] = area->color[1] = area->color[2] = 4.0;
  area->intensity = 1.0;
  scene->area_light_count = 1;
}

static void test_lifetime(void)
{
  mrgi_error err;
  mrgi_scene scene;
  static const mrgi_scene zero;
  MRGI_CHECK(mrgi_scene_create(NULL, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  const int32_t bad_counts[] = { 0, -1, MRGI_SCENE_MAX_MESHES + 1, INT32_MIN };
  for (size_t i = 0; i < sizeof(bad_counts) / sizeof(bad_counts[0]); ++i)
  {
    memset(&scene, 0x5A, sizeof(scene));
    MRGI_CHECK(mrgi_scene_create(&scene, bad_counts[i], &err) == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(message_has(&err, "mesh_count"));
    MRGI_CHECK(memcmp(&scene, &zero, sizeof(zero)) == 0);
  }
  make_scene(&scene);
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_scene_triangle_count(&scene) == 2);
  MRGI_CHECK(mrgi_scene_find_mesh(&scene, "second") == 1);
  MRGI_CHECK(mrgi_scene_find_mesh(&scene, "third") == -1);
  MRGI_CHECK(mrgi_scene_find_mesh(&scene, NULL) == -1);
  MRGI_CHECK(mrgi_scene_find_mesh(NULL, "first") == -1);
  double bounds[6];
  MRGI_CHECK(mrgi_scene_bounds(&scene, bounds, &err) == MRGI_OK);
  const double expected[6] = { 0, 1, 0, 1, 0, 1 };
  for (int i = 0; i < 6; ++i)
  {
    MRGI_CHECK_NEAR(bounds[i], expected[i], 0.0);
  }
  mrgi_scene_destroy(&scene);
  MRGI_CHECK(memcmp(&scene, &zero, sizeof(zero)) == 0);
  mrgi_scene_destroy(&scene); /* idempotent */
  mrgi_scene_destroy(NULL);   /* NULL-safe */
  MRGI_CHECK(mrgi_scene_triangle_count(&scene) == 0);
  MRGI_CHECK(mrgi_scene_triangle_count(NULL) == 0);
  MRGI_CHECK(mrgi_scene_bounds(&scene, bounds, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_scene_validate(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  /* An empty scene is valid only if its camera is; the zero camera is not. */
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_ERR_FORMAT);

  /* A scene whose meshes were never created: destroy copes. */
  MRGI_CHECK(mrgi_scene_create(&scene, 3, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "mesh 0: "));
  mrgi_scene_destroy(&scene);
}

/* Make one change to a valid scene and expect validation to reject it with
 * a message containing `text`. The mesh array is restored before the scene
 * is destroyed, so a corrupted mesh_count does not leak it. */
#define EXPECT_REJECTED(change, text)                                       \
  do {                                                                      \
    mrgi_scene s_;                                                          \
    mrgi_error e_;                                                          \
    make_scene(&s_);                                                        \
    const int32_t mesh_count_ = s_.mesh_count;                              \
    mrgi_scene* scene = &s_;                                                \
    change;                                                                 \
    MRGI_CHECK(mrgi_scene_validate(scene, &e_) != MRGI_OK);                 \
    MRGI_CHECK(message_has(&e_, text));                                     \
    s_.mesh_count = mesh_count_;                                            \
    mrgi_scene_destroy(&s_);                                                \
  } while (0)

static void test_validation(void)
{
  EXPECT_REJECTED(scene->meshes[1].indices[2] = 3, "mesh 1: ");
  EXPECT_REJECTED(scene->meshes[0].positions[0] = NAN, "position is not finite");
  EXPECT_REJECTED(scene->mesh_count = -1, "mesh_count");
  EXPECT_REJECTED(scene->light_count = MRGI_SCENE_MAX_LIGHTS + 1, "light_count");
  EXPECT_REJECTED(scene->area_light_count = -2, "area_light_count");

  EXPECT_REJECTED(scene->camera.view_angle_deg = 0.0, "view_angle_deg");
  EXPECT_REJECTED(scene->camera.view_angle_deg = 180.0, "view_angle_deg");
  EXPECT_REJECTED(scene->camera.view_angle_deg = NAN, "view_angle_deg");
  EXPECT_REJECTED(scene->camera.position[0] = INFINITY, "non-finite");
  EXPECT_REJECTED(scene->camera.position[2] = 0.0, "equals its focal point");
  EXPECT_REJECTED((scene->camera.view_up[1] = 0.0, scene->camera.view_up[2] = 3.0), "parallel");
  EXPECT_REJECTED(scene->camera.view_up[1] = 0.0, "parallel");

  EXPECT_REJECTED(scene->lights[0].type = (mrgi_light_type)7, "unknown type");
  EXPECT_REJECTED(scene->lights[0].cone_angle_deg = 90.0, "cone_angle_deg");
  EXPECT_REJECTED(scene->lights[0].cone_angle_deg = 0.0, "cone_angle_deg");
  EXPECT_REJECTED(scene->lights[0].color[1] = -0.1, "color[1]");
  EXPECT_REJECTED(scene->lights[0].intensity = NAN, "intensity");
  EXPECT_REJECTED(scene->lights[0].exponent = -1.0, "exponent");
  EXPECT_REJECTED(scene->lights[0].position[1] = 0.0, "no direction");
  EXPECT_REJECTED(scene->lights[0].focal_point[2] = NAN, "non-finite");

  EXPECT_REJECTED(scene->area_lights[0].edge_v[0] = 0.0, "zero-length edge");
  EXPECT_REJECTED(scene->area_lights[0].edge_v[2] = 0.5, "not perpendicular");
  EXPECT_REJECTED(scene->area_lights[0].color[2] = -1.0, "color[2]");
  EXPECT_REJECTED(scene->area_lights[0].center[0] = NAN, "non-finite");

  /* The valid variants of the fields above pass. */
  mrgi_scene scene;
  mrgi_error err;
  make_scene(&scene);
  scene.lights[0].type = MRGI_LIGHT_POSITIONAL;
  scene.lights[0].cone_angle_deg = 90.0;
  scene.lights[0].position[1] = 0.0; /* a point light needs no direction */
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_OK);
  scene.lights[0].type = MRGI_LIGHT_DIRECTIONAL;
  scene.lights[0].position[1] = 1.0;
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_OK);
  mrgi_scene_destroy(&scene);
}

static void test_area_light_helpers(void)
{
  mrgi_error err;
  mrgi_area_light light;
  memset(&light, 0, sizeof(light));
  light.center[0] = 10.0;
  light.center[1] = 5.0;
  light.edge_u[2] = 3.0;  /* +z */
  light.edge_v[0] = -2.0; /* -x: (0,0,3) x (-2,0,0) = (0,-6,0), faces down */
  MRGI_CHECK_NEAR(mrgi_area_light_area(&light), 6.0, 0.0);
  MRGI_CHECK_NEAR(mrgi_area_light_area(NULL), 0.0, 0.0);
  double normal[3];
  MRGI_CHECK(mrgi_area_light_normal(&light, normal, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(normal[0], 0.0, 0.0);
  MRGI_CHECK_NEAR(normal[1], -1.0, 0.0);
  MRGI_CHECK_NEAR(normal[2], 0.0, 0.0);

  double corners[4][3];
  MRGI_CHECK(mrgi_area_light_corners(&light, corners, &err) == MRGI_OK);
  const double expected[4][3] = { { 11, 5, -1.5 }, { 11, 5, 1.5 }, { 9, 5, 1.5 }, { 9, 5, -1.5 } };
  for (int k = 0; k < 4; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      MRGI_CHECK_NEAR(corners[k][a], expected[k][a], 1e-12);
    }
  }
  /* Corners are counter-clockwise around the normal: their Newell normal
   * points the same way. */
  double newell[3] = { 0, 0, 0 };
  for (int k = 0; k < 4; ++k)
  {
    const double* p = corners[k];
    const double* q = corners[(k + 1) % 4];
    newell[0] += p[1] * q[2] - p[2] * q[1];
    newell[1] += p[2] * q[0] - p[0] * q[2];
    newell[2] += p[0] * q[1] - p[1] * q[0];
  }
  MRGI_CHECK(newell[0] * normal[0] + newell[1] * normal[1] + newell[2] * normal[2] > 0.0);
  MRGI_CHECK_NEAR(0.5 * sqrt(newell[0] * newell[0] + newell[1] * newell[1] + newell[2] * newell[2]),
                  6.0, 1e-9);

  MRGI_CHECK(mrgi_area_light_corners(NULL, corners, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_area_light_normal(&light, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  light.edge_v[0] = 0.0;
  MRGI_CHECK(mrgi_area_light_normal(&light, normal, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "zero"));
}

/* Owned images (area-light textures): creation, validation, destruction. */
static void test_images(void)
{
  mrgi_error err;
  mrgi_scene scene;
  static const mrgi_scene zero;
  make_scene(&scene);
  MRGI_CHECK(scene.images == NULL && scene.image_count == 0);
  MRGI_CHECK(mrgi_scene_create_images(NULL, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  const int32_t bad_counts[] = { 0, -1, MRGI_SCENE_MAX_IMAGES + 1 };
  for (size_t i = 0; i < sizeof(bad_counts) / sizeof(bad_counts[0]); ++i)
  {
    MRGI_CHECK(mrgi_scene_create_images(&scene, bad_counts[i], &err) == MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(message_has(&err, "image_count"));
    MRGI_CHECK(scene.images == NULL && scene.image_count == 0);
  }
  MRGI_CHECK(mrgi_scene_create_images(&scene, 2, &err) == MRGI_OK);
  MRGI_CHECK(scene.image_count == 2 && scene.images != NULL);
  MRGI_CHECK(mrgi_scene_create_images(&scene, 1, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "already has images"));
  /* Images not made yet are not valid. */
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "image 0: "));
  MRGI_CHECK(mrgi_image_create(&scene.images[0], 4, 2, 3, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "image 1: "));
  MRGI_CHECK(mrgi_image_create(&scene.images[1], 1, 1, 4, &err) == MRGI_OK);
  /* An area light borrows one as its texture. */
  for (size_t i = 0; i < mrgi_image_value_count(&scene.images[0]); ++i)
  {
    scene.images[0].pixels[i] = 0.25f * (float)(i % 5);
  }
  scene.area_lights[0].texture = &scene.images[0];
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_OK);
  const int32_t count = scene.image_count;
  scene.image_count = MRGI_SCENE_MAX_IMAGES + 1;
  MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(message_has(&err, "image_count"));
  scene.image_count = count;
  mrgi_scene_destroy(&scene); /* frees both images (valgrind: no leak) */
  MRGI_CHECK(memcmp(&scene, &zero, sizeof(zero)) == 0);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_lifetime),
    MRGI_TEST_CASE(test_validation),
    MRGI_TEST_CASE(test_area_light_helpers),
    MRGI_TEST_CASE(test_images),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
