/* Tests of the scaling scene: exact triangle counts, determinism (also
 * against a golden hash, so a platform that computes different bits fails),
 * layout independent of the triangle count, resting objects, outward
 * winding, framing, and rejection of bad arguments. */
#include "mrgi_scene_scaling.h"
#include "mrgi_test.h"

#include <inttypes.h>
#include <string.h>

/* FNV-1a of hash_scene() for mrgi_scene_scaling(16, 1000, 1). */
#define MRGI_TEST_GOLDEN_HASH 0x322029163B38D84BULL

static int message_has(const mrgi_error* err, const char* text)
{
  if (!strstr(err->message, text))
  {
    fprintf(stderr, "message '%s' lacks '%s'\n", err->message, text);
    return 0;
  }
  return 1;
}

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* FNV-1a over every mesh's arrays, in mesh order. */
static uint64_t hash_bytes(uint64_t h, const void* data, size_t size)
{
  const unsigned char* bytes = data;
  for (size_t i = 0; i < size; ++i)
  {
    h = (h ^ bytes[i]) * 0x100000001B3ULL;
  }
  return h;
}

static uint64_t hash_scene(const mrgi_scene* scene)
{
  uint64_t h = 0xCBF29CE484222325ULL;
  for (int32_t m = 0; m < scene->mesh_count; ++m)
  {
    const mrgi_mesh* mesh = &scene->meshes[m];
    h = hash_bytes(h, mesh->positions, 3 * (size_t)mesh->vertex_count * sizeof(float));
    h = hash_bytes(h, mesh->normals, 3 * (size_t)mesh->vertex_count * sizeof(float));
    h = hash_bytes(h, mesh->indices, 3 * (size_t)mesh->triangle_count * sizeof(uint32_t));
    h = hash_bytes(h, mesh->albedo, sizeof(mesh->albedo));
    h = hash_bytes(h, mesh->name, strlen(mesh->name));
  }
  return h;
}

static void build(int64_t objects, int64_t triangles, uint64_t seed, mrgi_scene* scene)
{
  mrgi_error err;
  const mrgi_status status = mrgi_scene_scaling(objects, triangles, seed, scene, &err);
  if (status != MRGI_OK)
  {
    fprintf(stderr, "mrgi_scene_scaling(%" PRId64 ", %" PRId64 "): %s\n", objects, triangles,
            err.message);
  }
  MRGI_CHECK(status == MRGI_OK);
}

static void test_exact_counts_and_validity(void)
{
  const int64_t cases[][2] = { { 1, 26 },        { 1, 27 },         { 1, 1000 },
                               { 16, 1000 },     { 16, 1001 },      { 7, 12345 },
                               { 100, 100000 },  { 4096, 98306 },   { 4096, 100001 },
                               { 3, 999999 },    { 256, 1000000 } };
  for (size_t c = 0; c < sizeof(cases) / sizeof(cases[0]); ++c)
  {
    mrgi_error err;
    mrgi_scene scene;
    build(cases[c][0], cases[c][1], 12345, &scene);
    MRGI_CHECK(scene.mesh_count == cases[c][0] + 1);
    MRGI_CHECK(mrgi_scene_triangle_count(&scene) == cases[c][1]);
    MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_OK);
    MRGI_CHECK(strcmp(scene.meshes[0].name, "ground") == 0);
    /* The ground only absorbs what the objects' grids cannot: a few triangles. */
    MRGI_CHECK(scene.meshes[0].triangle_count <= 2 + 64);
    for (int32_t m = 1; m < scene.mesh_count; ++m)
    {
      MRGI_CHECK(scene.meshes[m].triangle_count >= MRGI_SCALING_MIN_TRIANGLES_PER_OBJECT);
    }
    mrgi_scene_destroy(&scene);
  }
}

static void test_determinism(void)
{
  mrgi_scene a, b, c;
  build(16, 20000, 7, &a);
  build(16, 20000, 7, &b);
  build(16, 20000, 8, &c);
  MRGI_CHECK(a.mesh_count == b.mesh_count);
  int seeds_differ = 0;
  for (int32_t m = 0; m < a.mesh_count; ++m)
  {
    const mrgi_mesh* ma = &a.meshes[m];
    const mrgi_mesh* mb = &b.meshes[m];
    MRGI_CHECK(ma->vertex_count == mb->vertex_count && ma->triangle_count == mb->triangle_count);
    MRGI_CHECK(memcmp(ma->positions, mb->positions, 3 * (size_t)ma->vertex_count * sizeof(float)) == 0);
    MRGI_CHECK(memcmp(ma->normals, mb->normals, 3 * (size_t)ma->vertex_count * sizeof(float)) == 0);
    MRGI_CHECK(memcmp(ma->indices, mb->indices, 3 * (size_t)ma->triangle_count * sizeof(uint32_t)) == 0);
    MRGI_CHECK(memcmp(ma->albedo, mb->albedo, sizeof(ma->albedo)) == 0);
    MRGI_CHECK(strcmp(ma->name, mb->name) == 0);
    const mrgi_mesh* mc = &c.meshes[m];
    if (mc->vertex_count != ma->vertex_count || strcmp(mc->name, ma->name) != 0 ||
        memcmp(mc->positions, ma->positions, 3 * (size_t)ma->vertex_count * sizeof(float)) != 0)
    {
      ++seeds_differ;
    }
  }
  MRGI_CHECK(memcmp(&a.camera, &b.camera, sizeof(a.camera)) == 0);
  MRGI_CHECK(memcmp(a.lights, b.lights, sizeof(a.lights)) == 0);
  /* Another seed moves every object (jitter), not just some. */
  MRGI_CHECK(seeds_differ == a.mesh_count - 1);
  mrgi_scene_destroy(&a);
  mrgi_scene_destroy(&b);
  mrgi_scene_destroy(&c);
}

/* Golden value: the same bits on every IEEE-754 platform (see the header).
 * If this fails on a new platform, the scene is not portable there; if it
 * fails after a deliberate change to the scene, update the value. */
static void test_golden_hash(void)
{
  mrgi_scene golden;
  build(16, 1000, 1, &golden);
  const uint64_t h = hash_scene(&golden);
  if (h != MRGI_TEST_GOLDEN_HASH)
  {
    fprintf(stderr, "scaling scene hash 0x%016" PRIx64 "\n", h);
  }
  MRGI_CHECK(h == MRGI_TEST_GOLDEN_HASH);
  mrgi_scene_destroy(&golden);
}

/* Projected area of a closed mesh along unit direction d, overlaps counted:
 * 1/2 sum |n . d| A (exact for convex meshes, a smooth proxy for tori). */
static double projected_area(const mrgi_mesh* mesh, const double d[3])
{
  mrgi_error err;
  double sum = 0.0;
  for (int64_t t = 0; t < mesh->triangle_count; ++t)
  {
    double normal[3], area;
    MRGI_CHECK(mrgi_mesh_triangle_geometry(mesh, t, normal, NULL, &area, &err) == MRGI_OK);
    sum += fabs(dot3(normal, d)) * area;
  }
  return 0.5 * sum;
}

/* Same seed and object count, 100x the triangles: the same objects in the
 * same places covering nearly the same screen area. */
static void test_layout_independent_of_triangle_count(void)
{
  mrgi_error err;
  mrgi_scene coarse, fine;
  build(16, 1000, 3, &coarse); /* about 60 triangles per object */
  build(16, 100000, 3, &fine);
  MRGI_CHECK(coarse.mesh_count == fine.mesh_count);
  double view[3];
  for (int a = 0; a < 3; ++a)
  {
    view[a] = fine.camera.focal_point[a] - fine.camera.position[a];
  }
  const double view_length = sqrt(dot3(view, view));
  for (int a = 0; a < 3; ++a)
  {
    view[a] /= view_length;
  }
  int spheres = 0, tori = 0;
  double coarse_total = 0.0, fine_total = 0.0;
  for (int32_t m = 1; m < coarse.mesh_count; ++m)
  {
    const mrgi_mesh* mc = &coarse.meshes[m];
    const mrgi_mesh* mf = &fine.meshes[m];
    MRGI_CHECK(strcmp(mc->name, mf->name) == 0);
    MRGI_CHECK(mf->triangle_count > 50 * mc->triangle_count);
    MRGI_CHECK(memcmp(mc->albedo, mf->albedo, sizeof(mc->albedo)) == 0);
    const int is_sphere = strncmp(mf->name, "sphere", 6) == 0;
    spheres += is_sphere;
    tori += !is_sphere;
    double bc[6], bf[6];
    MRGI_CHECK(mrgi_mesh_bounds(mc, bc, &err) == MRGI_OK);
    MRGI_CHECK(mrgi_mesh_bounds(mf, bf, &err) == MRGI_OK);
    for (int i = 0; i < 6; ++i)
    {
      /* Objects are 0.36..0.76 m wide; 5 cm of facet at 60 triangles. */
      MRGI_CHECK_NEAR(bc[i], bf[i], 0.05);
    }
    const double ac = projected_area(mc, view), af = projected_area(mf, view);
    coarse_total += ac;
    fine_total += af;
    /* Spheres are convex, so this is their true projected area. */
    MRGI_CHECK(fabs(ac / af - 1.0) < (is_sphere ? 0.05 : 0.20));
  }
  MRGI_CHECK(spheres > 0 && tori > 0);
  /* What the screen sees in total: within 5 % (unscaled facets lost 11 %). */
  MRGI_CHECK(fabs(coarse_total / fine_total - 1.0) < 0.05);
  /* Camera and lights do not depend on the triangle count at all. */
  MRGI_CHECK(memcmp(&coarse.camera, &fine.camera, sizeof(coarse.camera)) == 0);
  MRGI_CHECK(memcmp(coarse.lights, fine.lights, sizeof(coarse.lights)) == 0);
  mrgi_scene_destroy(&coarse);
  mrgi_scene_destroy(&fine);
}

/* At the coarsest tessellation, where facets are scaled most, objects still
 * stay inside their cells and barely dip into the ground. */
static void test_coarsest_objects_stay_in_cells(void)
{
  mrgi_error err;
  const int64_t objects = 100, columns = 10, rows = 10;
  for (uint64_t seed = 0; seed < 8; ++seed)
  {
    mrgi_scene scene;
    build(objects, mrgi_scene_scaling_min_triangles(objects), seed, &scene);
    MRGI_CHECK(mrgi_scene_validate(&scene, &err) == MRGI_OK);
    for (int32_t m = 1; m < scene.mesh_count; ++m)
    {
      const int64_t i = m - 1;
      const double cell_x = (double)(i % columns) + 0.5 - 0.5 * (double)columns;
      const double cell_z = (double)(i / columns) + 0.5 - 0.5 * (double)rows;
      double b[6];
      MRGI_CHECK(mrgi_mesh_bounds(&scene.meshes[m], b, &err) == MRGI_OK);
      MRGI_CHECK(b[0] > cell_x - 0.5 && b[1] < cell_x + 0.5);
      MRGI_CHECK(b[4] > cell_z - 0.5 && b[5] < cell_z + 0.5);
      MRGI_CHECK(b[2] > -0.08 && b[2] < 0.05);
    }
    mrgi_scene_destroy(&scene);
  }
}

/* Objects rest on the ground inside their own cells; triangles face out
 * (agree with the analytic vertex normals); sphere vertices lie on the sphere. */
static void test_objects(void)
{
  mrgi_error err;
  mrgi_scene scene;
  const int64_t objects = 10; /* a 4 x 3 grid with two empty cells */
  build(objects, 50000, 99, &scene);
  const int64_t columns = 4, rows = 3;
  for (int32_t m = 1; m < scene.mesh_count; ++m)
  {
    const mrgi_mesh* mesh = &scene.meshes[m];
    const int64_t i = m - 1;
    const double cell_x = (double)(i % columns) + 0.5 - 0.5 * (double)columns;
    const double cell_z = (double)(i / columns) + 0.5 - 0.5 * (double)rows;
    double b[6];
    MRGI_CHECK(mrgi_mesh_bounds(mesh, b, &err) == MRGI_OK);
    MRGI_CHECK(b[0] > cell_x - 0.5 && b[1] < cell_x + 0.5);
    MRGI_CHECK(b[4] > cell_z - 0.5 && b[5] < cell_z + 0.5);
    MRGI_CHECK(b[2] > -0.002 && b[2] < 0.002); /* resting on y = 0 */
    /* Tallest: a torus on edge, 2 (0.26 + 0.117) m; flattest: a lying torus, 2 * 0.054 m. */
    MRGI_CHECK(b[3] > 0.10 && b[3] <= 0.76);

    const int is_sphere = strncmp(mesh->name, "sphere", 6) == 0;
    const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
    const double radius = 0.5 * (b[3] - b[2]);
    for (int64_t v = 0; v < mesh->vertex_count; ++v)
    {
      const double n[3] = { mesh->normals[3 * v], mesh->normals[3 * v + 1], mesh->normals[3 * v + 2] };
      MRGI_CHECK_NEAR(sqrt(dot3(n, n)), 1.0, 1e-6);
      if (is_sphere)
      {
        const double d[3] = { mesh->positions[3 * v] - centre[0],
                              mesh->positions[3 * v + 1] - centre[1],
                              mesh->positions[3 * v + 2] - centre[2] };
        MRGI_CHECK_NEAR(sqrt(dot3(d, d)), radius, 0.002 * radius); /* silhouette scale */
        MRGI_CHECK(dot3(d, n) > 0.999 * radius);
      }
    }
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      double normal[3], area;
      MRGI_CHECK(mrgi_mesh_triangle_geometry(mesh, t, normal, NULL, &area, &err) == MRGI_OK);
      MRGI_CHECK(area > 0.0);
      double corner_sum[3] = { 0, 0, 0 };
      for (int k = 0; k < 3; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          corner_sum[a] += mesh->normals[3 * mesh->indices[3 * t + k] + a];
        }
      }
      MRGI_CHECK(dot3(normal, corner_sum) > 0.0);
    }
  }
  /* The ground faces up and spans the grid plus one cell. */
  double b[6];
  MRGI_CHECK(mrgi_mesh_bounds(&scene.meshes[0], b, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(b[0], -3.0, 1e-6);
  MRGI_CHECK_NEAR(b[1], 3.0, 1e-6);
  MRGI_CHECK_NEAR(b[4], -2.5, 1e-6);
  MRGI_CHECK_NEAR(b[5], 2.5, 1e-6);
  MRGI_CHECK(b[2] == 0.0 && b[3] == 0.0);
  double area = 0.0;
  MRGI_CHECK(mrgi_mesh_total_area(&scene.meshes[0], &area, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(area, 30.0, 1e-4);
  for (int64_t t = 0; t < scene.meshes[0].triangle_count; ++t)
  {
    double normal[3];
    MRGI_CHECK(mrgi_mesh_triangle_geometry(&scene.meshes[0], t, normal, NULL, NULL, &err) == MRGI_OK);
    MRGI_CHECK_NEAR(normal[1], 1.0, 0.0);
  }
  mrgi_scene_destroy(&scene);
}

/* The camera sees every object (square viewport, vertical angle = horizontal),
 * from about 35 degrees up; the spot light covers the ground. */
static void test_camera_and_lights(void)
{
  const int64_t counts[] = { 1, 2, 17, 4096 };
  for (size_t c = 0; c < sizeof(counts) / sizeof(counts[0]); ++c)
  {
    mrgi_error err;
    mrgi_scene scene;
    build(counts[c], mrgi_scene_scaling_min_triangles(counts[c]) + 1000, 5, &scene);
    const mrgi_camera* camera = &scene.camera;
    double forward[3], right[3], up[3];
    for (int a = 0; a < 3; ++a)
    {
      forward[a] = camera->focal_point[a] - camera->position[a];
    }
    const double distance = sqrt(dot3(forward, forward));
    for (int a = 0; a < 3; ++a)
    {
      forward[a] /= distance;
    }
    MRGI_CHECK_NEAR(asin(-forward[1]) * 180.0 / 3.14159265358979, 35.0, 0.5);
    right[0] = forward[1] * camera->view_up[2] - forward[2] * camera->view_up[1];
    right[1] = forward[2] * camera->view_up[0] - forward[0] * camera->view_up[2];
    right[2] = forward[0] * camera->view_up[1] - forward[1] * camera->view_up[0];
    const double right_length = sqrt(dot3(right, right));
    for (int a = 0; a < 3; ++a)
    {
      right[a] /= right_length;
    }
    up[0] = right[1] * forward[2] - right[2] * forward[1];
    up[1] = right[2] * forward[0] - right[0] * forward[2];
    up[2] = right[0] * forward[1] - right[1] * forward[0];
    const double half_tan = tan(0.5 * camera->view_angle_deg * 3.14159265358979 / 180.0);
    for (int32_t m = 1; m < scene.mesh_count; ++m)
    {
      double b[6];
      MRGI_CHECK(mrgi_mesh_bounds(&scene.meshes[m], b, &err) == MRGI_OK);
      for (int k = 0; k < 8; ++k)
      {
        const double corner[3] = { b[k & 1], b[2 + ((k >> 1) & 1)], b[4 + ((k >> 2) & 1)] };
        const double d[3] = { corner[0] - camera->position[0], corner[1] - camera->position[1],
                              corner[2] - camera->position[2] };
        const double z = dot3(d, forward);
        MRGI_CHECK(z > 0.0);
        MRGI_CHECK(fabs(dot3(d, right)) < half_tan * z);
        MRGI_CHECK(fabs(dot3(d, up)) < half_tan * z);
      }
    }
    MRGI_CHECK(scene.light_count == 2);
    const mrgi_light* spot = &scene.lights[0];
    MRGI_CHECK(spot->type == MRGI_LIGHT_SPOT);
    MRGI_CHECK(scene.lights[1].type == MRGI_LIGHT_DIRECTIONAL);
    double ground[6];
    MRGI_CHECK(mrgi_mesh_bounds(&scene.meshes[0], ground, &err) == MRGI_OK);
    for (int k = 0; k < 4; ++k)
    {
      const double d[3] = { ground[k & 1] - spot->position[0], -spot->position[1],
                            ground[4 + (k >> 1)] - spot->position[2] };
      const double angle = acos(-d[1] / sqrt(dot3(d, d))) * 180.0 / 3.14159265358979;
      MRGI_CHECK(angle < spot->cone_angle_deg);
    }
    mrgi_scene_destroy(&scene);
  }
}

static void test_bad_arguments(void)
{
  mrgi_error err;
  mrgi_scene scene;
  static const mrgi_scene zero;
  const int64_t bad_objects[] = { 0, -1, INT64_MIN, MRGI_SCALING_MAX_OBJECTS + 1, INT64_MAX };
  for (size_t i = 0; i < sizeof(bad_objects) / sizeof(bad_objects[0]); ++i)
  {
    memset(&scene, 0x33, sizeof(scene));
    MRGI_CHECK(mrgi_scene_scaling(bad_objects[i], 100000, 1, &scene, &err) ==
               MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(message_has(&err, "object_count"));
    MRGI_CHECK(memcmp(&scene, &zero, sizeof(zero)) == 0);
    MRGI_CHECK(mrgi_scene_scaling_min_triangles(bad_objects[i]) == -1);
  }
  const int64_t bad_triangles[] = { 0, -1, 11, 25, INT64_MIN, MRGI_SCALING_MAX_TRIANGLES + 1,
                                    INT64_MAX };
  for (size_t i = 0; i < sizeof(bad_triangles) / sizeof(bad_triangles[0]); ++i)
  {
    MRGI_CHECK(mrgi_scene_scaling(1, bad_triangles[i], 1, &scene, &err) ==
               MRGI_ERR_INVALID_ARGUMENT);
    MRGI_CHECK(message_has(&err, "triangle_count"));
    MRGI_CHECK(memcmp(&scene, &zero, sizeof(zero)) == 0);
  }
  /* Too few triangles for many objects: the message gives the minimum. */
  MRGI_CHECK(mrgi_scene_scaling_min_triangles(4096) == 98306);
  MRGI_CHECK(mrgi_scene_scaling(4096, 1000, 1, &scene, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(message_has(&err, "98306"));
  MRGI_CHECK(mrgi_scene_scaling(4096, 98305, 1, &scene, NULL) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(mrgi_scene_scaling(1, 1000, 1, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_bad_arguments),
    MRGI_TEST_CASE(test_exact_counts_and_validity),
    MRGI_TEST_CASE(test_determinism),
    MRGI_TEST_CASE(test_layout_independent_of_triangle_count),
    MRGI_TEST_CASE(test_coarsest_objects_stay_in_cells),
    MRGI_TEST_CASE(test_objects),
    MRGI_TEST_CASE(test_camera_and_lights),
    /* Last: the checks above say what went wrong, this only that something did. */
    MRGI_TEST_CASE(test_golden_hash),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
