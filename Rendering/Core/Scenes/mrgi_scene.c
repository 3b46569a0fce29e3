#include "mrgi_scene.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void mrgi_scene_cross(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static double mrgi_scene_dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int mrgi_scene_finite3(const double v[3])
{
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

mrgi_status mrgi_scene_create(mrgi_scene* out, int32_t mesh_count, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_scene_create: out is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (mesh_count < 1 || mesh_count > MRGI_SCENE_MAX_MESHES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_scene_create: mesh_count %d is outside 1..%d", (int)mesh_count,
                          MRGI_SCENE_MAX_MESHES);
  }
  out->meshes = calloc((size_t)mesh_count, sizeof(mrgi_mesh));
  if (!out->meshes)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "mrgi_scene_create: cannot allocate %d meshes",
                          (int)mesh_count);
  }
  out->mesh_count = mesh_count;
  return MRGI_OK;
}

mrgi_status mrgi_scene_create_images(mrgi_scene* scene, int32_t image_count, mrgi_error* err)
{
  if (!scene)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_scene_create_images: scene is NULL");
  }
  if (image_count < 1 || image_count > MRGI_SCENE_MAX_IMAGES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_scene_create_images: image_count %d is outside 1..%d",
                          (int)image_count, MRGI_SCENE_MAX_IMAGES);
  }
  if (scene->images || scene->image_count != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_scene_create_images: the scene already has images");
  }
  scene->images = calloc((size_t)image_count, sizeof(mrgi_image));
  if (!scene->images)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "mrgi_scene_create_images: cannot allocate %d images", (int)image_count);
  }
  scene->image_count = image_count;
  return MRGI_OK;
}

void mrgi_scene_destroy(mrgi_scene* scene)
{
  if (!scene)
  {
    return;
  }
  if (scene->meshes)
  {
    for (int32_t i = 0; i < scene->mesh_count; ++i)
    {
      mrgi_mesh_destroy(&scene->meshes[i]);
    }
    free(scene->meshes);
  }
  if (scene->images)
  {
    for (int32_t i = 0; i < scene->image_count; ++i)
    {
      mrgi_image_destroy(&scene->images[i]);
    }
    free(scene->images);
  }
  memset(scene, 0, sizeof(*scene));
}

/* Direction from `from` to `to` must exist. */
static int mrgi_scene_distinct(const double from[3], const double to[3])
{
  return from[0] != to[0] || from[1] != to[1] || from[2] != to[2];
}

static mrgi_status mrgi_scene_validate_camera(const mrgi_camera* camera, mrgi_error* err)
{
  static const char* caller = "mrgi_scene_validate";
  if (!mrgi_scene_finite3(camera->position) || !mrgi_scene_finite3(camera->focal_point) ||
      !mrgi_scene_finite3(camera->view_up))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: camera has a non-finite vector", caller);
  }
  if (!(camera->view_angle_deg > 0.0 && camera->view_angle_deg < 180.0))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: camera view_angle_deg %g is outside (0, 180)",
                          caller, camera->view_angle_deg);
  }
  if (!mrgi_scene_distinct(camera->position, camera->focal_point))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: camera position equals its focal point",
                          caller);
  }
  const double view[3] = { camera->focal_point[0] - camera->position[0],
                           camera->focal_point[1] - camera->position[1],
                           camera->focal_point[2] - camera->position[2] };
  double side[3];
  mrgi_scene_cross(view, camera->view_up, side);
  /* Relative test: |view x up| against |view| |up|, so units do not matter. */
  const double scale = sqrt(mrgi_scene_dot(view, view) * mrgi_scene_dot(camera->view_up, camera->view_up));
  if (!(sqrt(mrgi_scene_dot(side, side)) > 1e-9 * scale))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
                          "%s: camera view_up is zero or parallel to the view direction", caller);
  }
  return MRGI_OK;
}

static mrgi_status mrgi_scene_validate_light(const mrgi_light* light, int32_t index,
                                             mrgi_error* err)
{
  static const char* caller = "mrgi_scene_validate";
  if (light->type != MRGI_LIGHT_POSITIONAL && light->type != MRGI_LIGHT_SPOT &&
      light->type != MRGI_LIGHT_DIRECTIONAL)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: light %d has unknown type %d", caller,
                          (int)index, (int)light->type);
  }
  if (!mrgi_scene_finite3(light->position) || !mrgi_scene_finite3(light->focal_point))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: light %d has a non-finite position", caller,
                          (int)index);
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!(light->color[c] >= 0.0 && isfinite(light->color[c])))
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: light %d color[%d] = %g is not finite and >= 0",
                            caller, (int)index, c, light->color[c]);
    }
  }
  if (!(light->intensity >= 0.0 && isfinite(light->intensity)))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: light %d intensity %g is not finite and >= 0",
                          caller, (int)index, light->intensity);
  }
  if (!(light->exponent >= 0.0 && isfinite(light->exponent)))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: light %d exponent %g is not finite and >= 0",
                          caller, (int)index, light->exponent);
  }
  if (light->type != MRGI_LIGHT_POSITIONAL &&
      !mrgi_scene_distinct(light->position, light->focal_point))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
                          "%s: light %d position equals its focal point, so it has no direction",
                          caller, (int)index);
  }
  if (light->type == MRGI_LIGHT_SPOT &&
      !(light->cone_angle_deg > 0.0 && light->cone_angle_deg < 90.0))
  {
    /* VTK treats a cone of 90 degrees or more as "not a spot light". */
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
                          "%s: spot light %d cone_angle_deg %g is outside (0, 90)", caller,
                          (int)index, light->cone_angle_deg);
  }
  return MRGI_OK;
}

static mrgi_status mrgi_scene_validate_area_light(const mrgi_area_light* light, int32_t index,
                                                  mrgi_error* err)
{
  /* One set of rules for every area light: mrgi_area_light_check()'s
   * (finite, perpendicular non-zero edges, colour and intensity >= 0, a
   * well-formed texture); a scene reports them as a format error. */
  if (mrgi_area_light_check(light, err) != MRGI_OK)
  {
    mrgi_error_prefix(err, "mrgi_scene_validate: area light %d: ", (int)index);
    if (err)
    {
      err->status = MRGI_ERR_FORMAT;
    }
    return MRGI_ERR_FORMAT;
  }
  return MRGI_OK;
}

mrgi_status mrgi_scene_validate(const mrgi_scene* scene, mrgi_error* err)
{
  static const char* caller = "mrgi_scene_validate";
  if (!scene)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: scene is NULL", caller);
  }
  if (scene->mesh_count < 0 || scene->mesh_count > MRGI_SCENE_MAX_MESHES ||
      (scene->mesh_count > 0 && !scene->meshes))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: mesh_count %d is outside 0..%d or meshes is NULL",
                          caller, (int)scene->mesh_count, MRGI_SCENE_MAX_MESHES);
  }
  if (scene->light_count < 0 || scene->light_count > MRGI_SCENE_MAX_LIGHTS)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: light_count %d is outside 0..%d", caller,
                          (int)scene->light_count, MRGI_SCENE_MAX_LIGHTS);
  }
  if (scene->area_light_count < 0 || scene->area_light_count > MRGI_SCENE_MAX_AREA_LIGHTS)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: area_light_count %d is outside 0..%d", caller,
                          (int)scene->area_light_count, MRGI_SCENE_MAX_AREA_LIGHTS);
  }
  if (scene->image_count < 0 || scene->image_count > MRGI_SCENE_MAX_IMAGES ||
      (scene->image_count > 0 && !scene->images))
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: image_count %d is outside 0..%d or images is NULL",
                          caller, (int)scene->image_count, MRGI_SCENE_MAX_IMAGES);
  }
  for (int32_t i = 0; i < scene->image_count; ++i)
  {
    if (mrgi_image_validate(&scene->images[i], err) != MRGI_OK)
    {
      mrgi_error_prefix(err, "%s: image %d: ", caller, (int)i);
      if (err)
      {
        err->status = MRGI_ERR_FORMAT;
      }
      return MRGI_ERR_FORMAT;
    }
  }
  for (int32_t i = 0; i < scene->mesh_count; ++i)
  {
    const mrgi_status status = mrgi_mesh_validate(&scene->meshes[i], err);
    if (status != MRGI_OK)
    {
      mrgi_error_prefix(err, "mesh %d: ", (int)i);
      return status;
    }
  }
  mrgi_status status = mrgi_scene_validate_camera(&scene->camera, err);
  for (int32_t i = 0; status == MRGI_OK && i < scene->light_count; ++i)
  {
    status = mrgi_scene_validate_light(&scene->lights[i], i, err);
  }
  for (int32_t i = 0; status == MRGI_OK && i < scene->area_light_count; ++i)
  {
    status = mrgi_scene_validate_area_light(&scene->area_lights[i], i, err);
  }
  return status;
}

int64_t mrgi_scene_triangle_count(const mrgi_scene* scene)
{
  if (!scene || !scene->meshes)
  {
    return 0;
  }
  int64_t total = 0;
  for (int32_t i = 0; i < scene->mesh_count; ++i)
  {
    total += scene->meshes[i].triangle_count;
  }
  return total;
}

mrgi_status mrgi_scene_bounds(const mrgi_scene* scene, double bounds[6], mrgi_error* err)
{
  if (!scene || !bounds)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_scene_bounds: %s is NULL",
                          scene ? "bounds" : "scene");
  }
  if (scene->mesh_count < 1 || !scene->meshes)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_scene_bounds: scene has no meshes");
  }
  double result[6];
  for (int32_t i = 0; i < scene->mesh_count; ++i)
  {
    double mesh_bounds[6];
    const mrgi_status status = mrgi_mesh_bounds(&scene->meshes[i], mesh_bounds, err);
    if (status != MRGI_OK)
    {
      return status;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      const double lo = mesh_bounds[2 * axis], hi = mesh_bounds[2 * axis + 1];
      result[2 * axis] = (i == 0 || lo < result[2 * axis]) ? lo : result[2 * axis];
      result[2 * axis + 1] = (i == 0 || hi > result[2 * axis + 1]) ? hi : result[2 * axis + 1];
    }
  }
  memcpy(bounds, result, sizeof(result));
  return MRGI_OK;
}

int32_t mrgi_scene_find_mesh(const mrgi_scene* scene, const char* name)
{
  if (!scene || !scene->meshes || !name)
  {
    return -1;
  }
  for (int32_t i = 0; i < scene->mesh_count; ++i)
  {
    if (strncmp(scene->meshes[i].name, name, MRGI_MESH_NAME_SIZE) == 0)
    {
      return i;
    }
  }
  return -1;
}

double mrgi_area_light_area(const mrgi_area_light* light)
{
  if (!light)
  {
    return 0.0;
  }
  double cross[3];
  mrgi_scene_cross(light->edge_u, light->edge_v, cross);
  return sqrt(mrgi_scene_dot(cross, cross));
}

mrgi_status mrgi_area_light_normal(const mrgi_area_light* light, double normal[3], mrgi_error* err)
{
  if (!light || !normal)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_area_light_normal: %s is NULL",
                          light ? "normal" : "light");
  }
  double cross[3];
  mrgi_scene_cross(light->edge_u, light->edge_v, cross);
  const double length = sqrt(mrgi_scene_dot(cross, cross));
  if (!(length > 0.0) || !isfinite(length))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_area_light_normal: area light has zero or non-finite area");
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    normal[axis] = cross[axis] / length;
  }
  return MRGI_OK;
}

mrgi_status mrgi_area_light_corners(const mrgi_area_light* light, double corners[4][3],
                                    mrgi_error* err)
{
  if (!light || !corners)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_area_light_corners: %s is NULL",
                          light ? "corners" : "light");
  }
  /* Signs of (u, v) per corner, counter-clockwise around edge_u x edge_v. */
  static const double su[4] = { -0.5, 0.5, 0.5, -0.5 };
  static const double sv[4] = { -0.5, -0.5, 0.5, 0.5 };
  for (int k = 0; k < 4; ++k)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      corners[k][axis] =
        light->center[axis] + su[k] * light->edge_u[axis] + sv[k] * light->edge_v[axis];
    }
  }
  return MRGI_OK;
}
