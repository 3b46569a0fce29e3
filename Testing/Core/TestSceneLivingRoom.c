/* Tests of the living-room builder: the scene validates; the screen is a
 * valid one-sided area light with its 64 x 36 texture, facing the sofa,
 * just in front of the TV set and matched by the emitter mesh; walls face
 * into the room and furniture out of its boxes; the camera sees the screen
 * unobstructed; the build is deterministic; destroy frees and zeroes. */
#include "mrgi_scene_living_room.h"
#include "mrgi_test.h"

#include <string.h>

static const char* const walls[6] = { "floor",     "ceiling",   "tv_wall",
                                      "back_wall", "left_wall", "right_wall" };
static const char* const furniture[6] = { "tv_stand", "tv_set", "sofa", "table", "shelf", "books" };

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

static int is_one_of(const char* name, const char* const* names, int count)
{
  for (int i = 0; i < count; ++i)
  {
    if (strcmp(name, names[i]) == 0)
    {
      return 1;
    }
  }
  return 0;
}

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize3(double v[3])
{
  const double n = sqrt(dot3(v, v));
  for (int a = 0; a < 3; ++a)
  {
    v[a] /= n;
  }
}

/* Möller-Trumbore: distance t > 0 along `dir` from `origin` to triangle
 * `t` of `mesh`, or -1 when the ray misses it. */
static double ray_triangle(const mrgi_mesh* mesh, int64_t t, const double origin[3],
                           const double dir[3])
{
  double p[3][3];
  for (int k = 0; k < 3; ++k)
  {
    const float* q = mesh->positions + 3 * mesh->indices[3 * t + k];
    p[k][0] = q[0];
    p[k][1] = q[1];
    p[k][2] = q[2];
  }
  const double e1[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
  const double e2[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
  double h[3], q[3];
  cross3(dir, e2, h);
  const double det = dot3(e1, h);
  if (fabs(det) < 1e-14)
  {
    return -1.0;
  }
  const double s[3] = { origin[0] - p[0][0], origin[1] - p[0][1], origin[2] - p[0][2] };
  const double u = dot3(s, h) / det;
  if (u < 0.0 || u > 1.0)
  {
    return -1.0;
  }
  cross3(s, e1, q);
  const double v = dot3(dir, q) / det;
  if (v < 0.0 || u + v > 1.0)
  {
    return -1.0;
  }
  const double distance = dot3(e2, q) / det;
  return distance > 0.0 ? distance : -1.0;
}

/* Crossings of `mesh` by the ray from `origin` going up (tilted off the
 * axes so that it meets no edge): odd inside a piece of furniture (boxes on
 * the floor lack only their bottom, which an upward ray never needs). */
static int crossings_up(const mrgi_mesh* mesh, const double origin[3])
{
  double dir[3] = { 0.01234, 1.0, 0.00789 };
  normalize3(dir);
  int n = 0;
  for (int64_t t = 0; t < mesh->triangle_count; ++t)
  {
    n += ray_triangle(mesh, t, origin, dir) > 0.0;
  }
  return n;
}

static void check_geometry(const mrgi_scene* scene)
{
  mrgi_error err;
  MRGI_CHECK(mrgi_scene_validate(scene, &err) == MRGI_OK);
  MRGI_CHECK(scene->mesh_count == 13);
  MRGI_CHECK(scene->light_count == 0 && scene->area_light_count == 1);

  /* Bounds: the room, in metres. */
  double bounds[6];
  MRGI_CHECK(mrgi_scene_bounds(scene, bounds, &err) == MRGI_OK);
  const double expected[6] = { -0.5 * MRGI_LIVING_ROOM_WIDTH_M, 0.5 * MRGI_LIVING_ROOM_WIDTH_M,
                               0.0, MRGI_LIVING_ROOM_HEIGHT_M, 0.0, MRGI_LIVING_ROOM_DEPTH_M };
  for (int i = 0; i < 6; ++i)
  {
    MRGI_CHECK_NEAR(bounds[i], expected[i], 1e-6);
  }
  const double room_centre[3] = { 0.0, 0.5 * MRGI_LIVING_ROOM_HEIGHT_M,
                                  0.5 * MRGI_LIVING_ROOM_DEPTH_M };

  for (int i = 0; i < 6; ++i)
  {
    const mrgi_mesh* wall = find(scene, walls[i]);
    MRGI_CHECK(wall->triangle_count == 2);
    double area = 0.0;
    MRGI_CHECK(mrgi_mesh_total_area(wall, &area, &err) == MRGI_OK);
    MRGI_CHECK(area > 10.0);
  }
  for (int i = 0; i < 6; ++i)
  {
    MRGI_CHECK(find(scene, furniture[i])->triangle_count >= 10);
  }

  for (int32_t m = 0; m < scene->mesh_count; ++m)
  {
    const mrgi_mesh* mesh = &scene->meshes[m];
    const int is_wall = is_one_of(mesh->name, walls, 6);
    const int is_screen = strcmp(mesh->name, "screen") == 0;
    MRGI_CHECK(is_wall || is_screen || is_one_of(mesh->name, furniture, 6));
    MRGI_CHECK(mesh->normals != NULL);
    /* Plausible albedos: neither black nor white, except the emitter's 0. */
    for (int c = 0; c < 3; ++c)
    {
      MRGI_CHECK(is_screen ? mesh->albedo[c] == 0.0f
                           : (mesh->albedo[c] >= 0.02f && mesh->albedo[c] <= 0.85f));
      MRGI_CHECK(is_screen || mesh->emission[c] == 0.0f);
    }
    for (int64_t t = 0; t < mesh->triangle_count; ++t)
    {
      double normal[3], centroid[3], area;
      MRGI_CHECK(mrgi_mesh_triangle_geometry(mesh, t, normal, centroid, &area, &err) == MRGI_OK);
      MRGI_CHECK(area > 1e-4);
      /* Flat shading: vertex normals are the face's. */
      for (int corner = 0; corner < 3; ++corner)
      {
        const float* n = mesh->normals + 3 * mesh->indices[3 * t + corner];
        const double nd[3] = { n[0], n[1], n[2] };
        MRGI_CHECK(dot3(nd, normal) > 0.99999);
      }
      /* Axis-aligned boxes: every face normal is a coordinate axis. */
      MRGI_CHECK(fabs(normal[0]) > 0.99999 || fabs(normal[1]) > 0.99999 || fabs(normal[2]) > 0.99999);
      const double out[3] = { centroid[0] + 0.005 * normal[0], centroid[1] + 0.005 * normal[1],
                              centroid[2] + 0.005 * normal[2] };
      const double in[3] = { centroid[0] - 0.005 * normal[0], centroid[1] - 0.005 * normal[1],
                             centroid[2] - 0.005 * normal[2] };
      /* Every face faces into the room: the point just in front of it is inside. */
      for (int a = 0; a < 3; ++a)
      {
        MRGI_CHECK(out[a] > bounds[2 * a] && out[a] < bounds[2 * a + 1]);
      }
      if (is_wall)
      {
        const double towards[3] = { room_centre[0] - centroid[0], room_centre[1] - centroid[1],
                                    room_centre[2] - centroid[2] };
        if (dot3(normal, towards) <= 0.0)
        {
          fprintf(stderr, "wall '%s' triangle %lld faces out of the room\n", mesh->name,
                  (long long)t);
        }
        MRGI_CHECK(dot3(normal, towards) > 0.0);
      }
      else if (!is_screen)
      {
        /* Furniture faces out of its solid: the point just behind the face
         * is inside the piece (odd crossings). */
        const int n = crossings_up(mesh, in);
        if (n % 2 != 1)
        {
          fprintf(stderr, "'%s' triangle %lld (normal %g %g %g) faces into its box\n", mesh->name,
                  (long long)t, normal[0], normal[1], normal[2]);
        }
        MRGI_CHECK(n % 2 == 1);
      }
    }
  }
}

static void check_light(const mrgi_scene* scene)
{
  mrgi_error err;
  const mrgi_area_light* light = &scene->area_lights[0];
  MRGI_CHECK(mrgi_area_light_check(light, &err) == MRGI_OK);
  MRGI_CHECK(light->two_sided == 0);
  MRGI_CHECK_NEAR(mrgi_area_light_area(light),
                  MRGI_LIVING_ROOM_SCREEN_WIDTH_M * MRGI_LIVING_ROOM_SCREEN_HEIGHT_M, 1e-12);
  MRGI_CHECK_NEAR(sqrt(dot3(light->edge_u, light->edge_u)), MRGI_LIVING_ROOM_SCREEN_WIDTH_M, 1e-12);
  MRGI_CHECK_NEAR(light->edge_v[1], MRGI_LIVING_ROOM_SCREEN_HEIGHT_M, 1e-12); /* v is up */
  MRGI_CHECK_NEAR(light->intensity, MRGI_LIVING_ROOM_SCREEN_INTENSITY, 0.0);
  MRGI_CHECK(light->color[0] == 1.0 && light->color[1] == 1.0 && light->color[2] == 1.0);

  /* Faces the sofa and the camera (+z). */
  double normal[3];
  MRGI_CHECK(mrgi_area_light_normal(light, normal, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(normal[2], 1.0, 0.0);
  const mrgi_mesh* sofa = find(scene, "sofa");
  double sofa_bounds[6];
  MRGI_CHECK(mrgi_mesh_bounds(sofa, sofa_bounds, &err) == MRGI_OK);
  MRGI_CHECK(sofa_bounds[4] > light->center[2] + 2.0);

  /* Just in front of the TV set's front face, inside its outline. */
  double set_bounds[6];
  MRGI_CHECK(mrgi_mesh_bounds(find(scene, "tv_set"), set_bounds, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(light->center[2] - set_bounds[5], MRGI_LIVING_ROOM_SCREEN_OFFSET_M, 1e-6);
  double corners[4][3];
  MRGI_CHECK(mrgi_area_light_corners(light, corners, &err) == MRGI_OK);
  for (int k = 0; k < 4; ++k)
  {
    MRGI_CHECK(corners[k][0] > set_bounds[0] && corners[k][0] < set_bounds[1]);
    MRGI_CHECK(corners[k][1] > set_bounds[2] && corners[k][1] < set_bounds[3]);
  }

  /* The texture: owned by the scene, 64 x 36 RGB, finite in [0, 1], with
   * several distinct colours, and with fine detail (the checkerboard). */
  const mrgi_image* texture = light->texture;
  MRGI_CHECK(texture != NULL);
  MRGI_CHECK(scene->image_count == 1 && texture == &scene->images[0]);
  MRGI_CHECK(texture->width == MRGI_LIVING_ROOM_TEXTURE_WIDTH);
  MRGI_CHECK(texture->height == MRGI_LIVING_ROOM_TEXTURE_HEIGHT);
  MRGI_CHECK(texture->width == 64 && texture->height == 36 && texture->channels == 3);
  float distinct[64][3];
  int distinct_count = 0;
  double mean[3] = { 0.0, 0.0, 0.0 };
  for (int32_t y = 0; y < texture->height; ++y)
  {
    for (int32_t x = 0; x < texture->width; ++x)
    {
      const float* p = mrgi_image_at(texture, x, y);
      int known = 0;
      for (int c = 0; c < 3; ++c)
      {
        MRGI_CHECK(isfinite(p[c]) && p[c] >= 0.0f && p[c] <= 1.0f);
        mean[c] += p[c] / (double)(texture->width * texture->height);
      }
      for (int d = 0; d < distinct_count && !known; ++d)
      {
        known = memcmp(distinct[d], p, sizeof(distinct[d])) == 0;
      }
      if (!known && distinct_count < 64)
      {
        memcpy(distinct[distinct_count++], p, sizeof(distinct[0]));
      }
    }
  }
  MRGI_CHECK(distinct_count >= 8);
  /* Top-left: the white bar; top-right: blue; row 0 is the top. */
  const float* top_left = mrgi_image_at(texture, 0, 0);
  const float* top_right = mrgi_image_at(texture, texture->width - 1, 0);
  MRGI_CHECK(top_left[0] == 0.75f && top_left[1] == 0.75f && top_left[2] == 0.75f);
  MRGI_CHECK(top_right[0] == 0.0f && top_right[1] == 0.0f && top_right[2] == 0.75f);
  const float* a = mrgi_image_at(texture, texture->width - 1, texture->height - 1);
  const float* b = mrgi_image_at(texture, texture->width - 2, texture->height - 1);
  MRGI_CHECK(fabs(a[0] - b[0]) == 1.0f);

  /* Mean radiance of the order of the Cornell emitter's, at most the intensity. */
  for (int c = 0; c < 3; ++c)
  {
    const double radiance = light->intensity * light->color[c] * mean[c];
    MRGI_CHECK(radiance > 10.0 && radiance < 25.0);
  }
  const double bar = 0.75 * MRGI_LIVING_ROOM_SCREEN_INTENSITY;
  double rgb[3];
  mrgi_area_light_emitted(light, 0.01, 0.99, rgb); /* top left of the picture: white bar */
  MRGI_CHECK_NEAR(rgb[0], bar, 1e-6);
  MRGI_CHECK_NEAR(rgb[2], bar, 1e-6);
  mrgi_area_light_emitted(light, 0.99, 0.99, rgb); /* top right: blue bar */
  MRGI_CHECK_NEAR(rgb[0], 0.0, 0.0);
  MRGI_CHECK_NEAR(rgb[2], bar, 1e-6);

  /* Its pyramid builds (what the GPU uploads). */
  mrgi_area_light_texture_pyramid pyramid;
  MRGI_CHECK(mrgi_area_light_texture_pyramid_create(&pyramid, texture, &err) == MRGI_OK);
  MRGI_CHECK(pyramid.level_count == 7); /* 64 x 36 ... 1 x 1 */
  mrgi_area_light_texture_pyramid_destroy(&pyramid);

  /* The emitter mesh: the light's rectangle, showing the mean radiance. */
  const mrgi_mesh* screen = find(scene, "screen");
  MRGI_CHECK(screen->triangle_count == 2 && screen->vertex_count == 4);
  for (int k = 0; k < 4; ++k)
  {
    int found = 0;
    for (int64_t v = 0; v < screen->vertex_count && !found; ++v)
    {
      const float* q = screen->positions + 3 * v;
      found = fabs(q[0] - corners[k][0]) < 1e-6 && fabs(q[1] - corners[k][1]) < 1e-6 &&
              fabs(q[2] - corners[k][2]) < 1e-6;
    }
    MRGI_CHECK(found);
  }
  double screen_normal[3];
  MRGI_CHECK(mrgi_mesh_triangle_geometry(screen, 0, screen_normal, NULL, NULL, &err) == MRGI_OK);
  MRGI_CHECK_NEAR(screen_normal[2], 1.0, 1e-12);
  for (int c = 0; c < 3; ++c)
  {
    MRGI_CHECK_NEAR(screen->emission[c], light->intensity * light->color[c] * mean[c], 1e-5);
  }
  printf("screen: %.2f x %.2f m at (%g, %g, %g), intensity %g, mean radiance (%.3f, %.3f, %.3f), "
         "%d distinct texel colours\n",
         MRGI_LIVING_ROOM_SCREEN_WIDTH_M, MRGI_LIVING_ROOM_SCREEN_HEIGHT_M, light->center[0],
         light->center[1], light->center[2], light->intensity, (double)screen->emission[0],
         (double)screen->emission[1], (double)screen->emission[2], distinct_count);
}

/* The camera sees the screen: its centre and corners project inside the
 * image (square aspect, the narrowest a landscape window has), and nothing
 * stands between the eye and them. */
static void check_camera(const mrgi_scene* scene)
{
  mrgi_error err;
  const mrgi_camera* camera = &scene->camera;
  double forward[3], right[3], up[3];
  for (int a = 0; a < 3; ++a)
  {
    forward[a] = camera->focal_point[a] - camera->position[a];
  }
  normalize3(forward);
  cross3(forward, camera->view_up, right);
  normalize3(right);
  cross3(right, forward, up);
  const double tan_half = tan(0.5 * camera->view_angle_deg * 3.14159265358979323846 / 180.0);

  const mrgi_area_light* light = &scene->area_lights[0];
  double corners[4][3];
  MRGI_CHECK(mrgi_area_light_corners(light, corners, &err) == MRGI_OK);
  double points[5][3];
  memcpy(points[0], light->center, sizeof(points[0]));
  for (int k = 0; k < 4; ++k)
  {
    /* 2 % inside each corner, so the check is about the light, not its edge. */
    for (int a = 0; a < 3; ++a)
    {
      points[k + 1][a] = corners[k][a] + 0.02 * (light->center[a] - corners[k][a]);
    }
  }
  double light_normal[3];
  MRGI_CHECK(mrgi_area_light_normal(light, light_normal, &err) == MRGI_OK);
  for (int i = 0; i < 5; ++i)
  {
    double d[3];
    for (int a = 0; a < 3; ++a)
    {
      d[a] = points[i][a] - camera->position[a];
    }
    const double depth = dot3(d, forward);
    MRGI_CHECK(depth > 0.0);
    const double sx = dot3(d, right) / (depth * tan_half);
    const double sy = dot3(d, up) / (depth * tan_half);
    if (i == 0)
    {
      printf("screen centre at normalized image position (%.3f, %.3f)\n", sx, sy);
    }
    MRGI_CHECK(fabs(sx) < 1.0 && fabs(sy) < 1.0);
    /* The camera is on the emitting side. */
    MRGI_CHECK(dot3(d, light_normal) < 0.0);
    /* Unobstructed: no triangle but the screen's own before the light. */
    const double length = sqrt(dot3(d, d));
    for (int a = 0; a < 3; ++a)
    {
      d[a] /= length;
    }
    for (int32_t m = 0; m < scene->mesh_count; ++m)
    {
      const mrgi_mesh* mesh = &scene->meshes[m];
      if (strcmp(mesh->name, "screen") == 0)
      {
        continue;
      }
      for (int64_t t = 0; t < mesh->triangle_count; ++t)
      {
        const double hit = ray_triangle(mesh, t, camera->position, d);
        if (hit > 0.0 && hit < length - 1e-4)
        {
          fprintf(stderr, "'%s' triangle %lld hides screen point %d\n", mesh->name, (long long)t, i);
        }
        MRGI_CHECK(!(hit > 0.0 && hit < length - 1e-4));
      }
    }
  }
  /* Behind the sofa, inside the room. */
  double sofa_bounds[6];
  MRGI_CHECK(mrgi_mesh_bounds(find(scene, "sofa"), sofa_bounds, &err) == MRGI_OK);
  MRGI_CHECK(camera->position[2] > sofa_bounds[5] && camera->position[2] < MRGI_LIVING_ROOM_DEPTH_M);
  MRGI_CHECK(camera->position[1] > sofa_bounds[3] && camera->position[1] < MRGI_LIVING_ROOM_HEIGHT_M);
}

/* Shadows: the sofa, the table and the shelf block some lines from the
 * screen's centre to the floor and walls. */
static void check_occluders(const mrgi_scene* scene)
{
  const mrgi_area_light* light = &scene->area_lights[0];
  const char* occluders[3] = { "table", "sofa", "shelf" };
  /* Floor behind the table, the back wall behind the sofa, the right wall behind the shelf. */
  const double targets[3][3] = { { 0.0, 0.0, 2.9 }, { 0.0, 0.3, 5.2 }, { 2.4, 0.9, 2.6 } };
  for (int i = 0; i < 3; ++i)
  {
    double d[3];
    for (int a = 0; a < 3; ++a)
    {
      d[a] = targets[i][a] - light->center[a];
    }
    const double length = sqrt(dot3(d, d));
    for (int a = 0; a < 3; ++a)
    {
      d[a] /= length;
    }
    const mrgi_mesh* mesh = find(scene, occluders[i]);
    int blocked = 0;
    for (int64_t t = 0; t < mesh->triangle_count && !blocked; ++t)
    {
      const double hit = ray_triangle(mesh, t, light->center, d);
      blocked = hit > 0.0 && hit < length;
    }
    if (!blocked)
    {
      fprintf(stderr, "'%s' casts no shadow on (%g, %g, %g)\n", occluders[i], targets[i][0],
              targets[i][1], targets[i][2]);
    }
    MRGI_CHECK(blocked);
  }
}

static int same_scene(const mrgi_scene* a, const mrgi_scene* b)
{
  if (a->mesh_count != b->mesh_count || a->image_count != b->image_count)
  {
    return 0;
  }
  for (int32_t m = 0; m < a->mesh_count; ++m)
  {
    const mrgi_mesh* x = &a->meshes[m];
    const mrgi_mesh* y = &b->meshes[m];
    if (x->vertex_count != y->vertex_count || x->triangle_count != y->triangle_count ||
        memcmp(x->positions, y->positions, sizeof(float) * 3 * (size_t)x->vertex_count) != 0 ||
        memcmp(x->normals, y->normals, sizeof(float) * 3 * (size_t)x->vertex_count) != 0 ||
        memcmp(x->indices, y->indices, sizeof(uint32_t) * 3 * (size_t)x->triangle_count) != 0 ||
        memcmp(x->albedo, y->albedo, sizeof(x->albedo)) != 0 ||
        memcmp(x->emission, y->emission, sizeof(x->emission)) != 0 || strcmp(x->name, y->name) != 0)
    {
      return 0;
    }
  }
  return memcmp(a->images[0].pixels, b->images[0].pixels,
                sizeof(float) * mrgi_image_value_count(&a->images[0])) == 0 &&
         memcmp(&a->camera, &b->camera, sizeof(a->camera)) == 0;
}

static void test_lifetime(void)
{
  mrgi_error err;
  static const mrgi_scene zero;
  mrgi_scene a, b;
  memset(&a, 0x77, sizeof(a));
  MRGI_CHECK(mrgi_scene_living_room(&a, &err) == MRGI_OK);
  MRGI_CHECK(mrgi_scene_living_room(&b, NULL) == MRGI_OK);
  MRGI_CHECK(same_scene(&a, &b)); /* deterministic */
  MRGI_CHECK(a.area_lights[0].texture != b.area_lights[0].texture); /* each owns its own */

  /* Moving the struct keeps the light's texture valid (the images are on the heap). */
  mrgi_scene moved = a;
  memset(&a, 0, sizeof(a));
  MRGI_CHECK(mrgi_scene_validate(&moved, &err) == MRGI_OK);
  MRGI_CHECK(moved.area_lights[0].texture == &moved.images[0]);

  mrgi_scene_destroy(&moved);
  MRGI_CHECK(memcmp(&moved, &zero, sizeof(zero)) == 0);
  mrgi_scene_destroy(&moved); /* idempotent */
  mrgi_scene_destroy(&b);

  MRGI_CHECK(mrgi_scene_living_room(NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "mrgi_scene_living_room") != NULL);
  MRGI_CHECK(mrgi_scene_living_room(NULL, NULL) == MRGI_ERR_INVALID_ARGUMENT);
}

/* Runs `check` on a freshly built living room. */
static void with_living_room(void (*check)(const mrgi_scene*))
{
  mrgi_error err;
  mrgi_scene scene;
  MRGI_CHECK(mrgi_scene_living_room(&scene, &err) == MRGI_OK);
  check(&scene);
  mrgi_scene_destroy(&scene);
}

static void print_counts(const mrgi_scene* scene)
{
  printf("living room: %d meshes, %lld triangles\n", (int)scene->mesh_count,
         (long long)mrgi_scene_triangle_count(scene));
}

static void test_geometry(void)
{
  with_living_room(print_counts);
  with_living_room(check_geometry);
}

static void test_light(void)
{
  with_living_room(check_light);
}

static void test_camera(void)
{
  with_living_room(check_camera);
}

static void test_occluders(void)
{
  with_living_room(check_occluders);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_geometry),
    MRGI_TEST_CASE(test_light),
    MRGI_TEST_CASE(test_camera),
    MRGI_TEST_CASE(test_occluders),
    MRGI_TEST_CASE(test_lifetime),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
