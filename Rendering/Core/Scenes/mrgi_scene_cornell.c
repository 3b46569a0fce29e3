#include "mrgi_scene_cornell.h"

#include <math.h>
#include <string.h>

/*
 * Source of every coordinate below: Cornell University Program of Computer
 * Graphics, "Cornell Box Data", https://www.graphics.cornell.edu/online/box/data.html
 * (millimetres, y up; each quad counter-clockwise as seen from inside the box).
 * Typed as published, including the skew of the left wall and floor.
 */
static const float mrgi_cornell_quads[][4][3] = {
  /* 0: floor */
  { { 552.8f, 0.0f, 0.0f }, { 0.0f, 0.0f, 0.0f }, { 0.0f, 0.0f, 559.2f }, { 549.6f, 0.0f, 559.2f } },
  /* 1: ceiling */
  { { 556.0f, 548.8f, 0.0f }, { 556.0f, 548.8f, 559.2f }, { 0.0f, 548.8f, 559.2f }, { 0.0f, 548.8f, 0.0f } },
  /* 2: back wall */
  { { 549.6f, 0.0f, 559.2f }, { 0.0f, 0.0f, 559.2f }, { 0.0f, 548.8f, 559.2f }, { 556.0f, 548.8f, 559.2f } },
  /* 3: left wall (red) */
  { { 552.8f, 0.0f, 0.0f }, { 549.6f, 0.0f, 559.2f }, { 556.0f, 548.8f, 559.2f }, { 556.0f, 548.8f, 0.0f } },
  /* 4: right wall (green) */
  { { 0.0f, 0.0f, 559.2f }, { 0.0f, 0.0f, 0.0f }, { 0.0f, 548.8f, 0.0f }, { 0.0f, 548.8f, 559.2f } },
  /* 5..9: short block, top then four sides */
  { { 130.0f, 165.0f, 65.0f }, { 82.0f, 165.0f, 225.0f }, { 240.0f, 165.0f, 272.0f }, { 290.0f, 165.0f, 114.0f } },
  { { 290.0f, 0.0f, 114.0f }, { 290.0f, 165.0f, 114.0f }, { 240.0f, 165.0f, 272.0f }, { 240.0f, 0.0f, 272.0f } },
  { { 130.0f, 0.0f, 65.0f }, { 130.0f, 165.0f, 65.0f }, { 290.0f, 165.0f, 114.0f }, { 290.0f, 0.0f, 114.0f } },
  { { 82.0f, 0.0f, 225.0f }, { 82.0f, 165.0f, 225.0f }, { 130.0f, 165.0f, 65.0f }, { 130.0f, 0.0f, 65.0f } },
  { { 240.0f, 0.0f, 272.0f }, { 240.0f, 165.0f, 272.0f }, { 82.0f, 165.0f, 225.0f }, { 82.0f, 0.0f, 225.0f } },
  /* 10..14: tall block, top then four sides */
  { { 423.0f, 330.0f, 247.0f }, { 265.0f, 330.0f, 296.0f }, { 314.0f, 330.0f, 456.0f }, { 472.0f, 330.0f, 406.0f } },
  { { 423.0f, 0.0f, 247.0f }, { 423.0f, 330.0f, 247.0f }, { 472.0f, 330.0f, 406.0f }, { 472.0f, 0.0f, 406.0f } },
  { { 472.0f, 0.0f, 406.0f }, { 472.0f, 330.0f, 406.0f }, { 314.0f, 330.0f, 456.0f }, { 314.0f, 0.0f, 456.0f } },
  { { 314.0f, 0.0f, 456.0f }, { 314.0f, 330.0f, 456.0f }, { 265.0f, 330.0f, 296.0f }, { 265.0f, 0.0f, 296.0f } },
  { { 265.0f, 0.0f, 296.0f }, { 265.0f, 330.0f, 296.0f }, { 423.0f, 330.0f, 247.0f }, { 423.0f, 0.0f, 247.0f } },
  /* 15: light (emitter, faces down); lowered by MRGI_CORNELL_EMITTER_DROP_MM when built */
  { { 343.0f, 548.8f, 227.0f }, { 343.0f, 548.8f, 332.0f }, { 213.0f, 548.8f, 332.0f }, { 213.0f, 548.8f, 227.0f } },
};

enum
{
  MRGI_CORNELL_FLOOR_QUAD = 0,
  MRGI_CORNELL_LIGHT_QUAD = 15
};

/* RGB reflectances in wide use by physically based renderers for the
 * published spectral ones. */
static const float mrgi_cornell_white[3] = { 0.725f, 0.71f, 0.68f };
static const float mrgi_cornell_red[3] = { 0.63f, 0.065f, 0.05f };
static const float mrgi_cornell_green[3] = { 0.14f, 0.45f, 0.091f };
static const float mrgi_cornell_black[3] = { 0.0f, 0.0f, 0.0f };
/* Customary RGB radiance of the emitter. */
static const float mrgi_cornell_emitter_radiance[3] = { 17.0f, 12.0f, 4.0f };

typedef struct mrgi_cornell_surface
{
  const char* name;
  const float* albedo;
  int first_quad;
  int quad_count;
} mrgi_cornell_surface;

static const mrgi_cornell_surface mrgi_cornell_surfaces[] = {
  { "floor", mrgi_cornell_white, 0, 1 },
  { "ceiling", mrgi_cornell_white, 1, 1 },
  { "back_wall", mrgi_cornell_white, 2, 1 },
  { "left_wall", mrgi_cornell_red, 3, 1 },
  { "right_wall", mrgi_cornell_green, 4, 1 },
  { "short_block", mrgi_cornell_white, 5, 5 },
  { "tall_block", mrgi_cornell_white, 10, 5 },
  { "light", mrgi_cornell_black, MRGI_CORNELL_LIGHT_QUAD, 1 },
};
enum
{
  MRGI_CORNELL_SURFACES_WITHOUT_LIGHT = 7,
  MRGI_CORNELL_SURFACES_WITH_LIGHT = 8
};

/* Point and spot lights stand just under the emitter's centre (278, 548.8,
 * 279.5), as the reference notes suggest for RSM-based methods. */
static const double mrgi_cornell_light_position[3] = { 278.0, 548.0, 279.5 };

/* Camera of the published data: 35 mm focal length, 25 x 25 mm film. */
static const double mrgi_cornell_focal_length_m = 0.035;
static const double mrgi_cornell_film_size_m = 0.025;

const char* mrgi_cornell_variant_name(mrgi_cornell_variant variant)
{
  switch (variant)
  {
    case MRGI_CORNELL_POINT:
      return "cornell";
    case MRGI_CORNELL_SPOT:
      return "cornell-spot";
    case MRGI_CORNELL_AREA:
      return "cornell-area";
  }
  return NULL;
}

mrgi_status mrgi_cornell_variant_parse(const char* name, mrgi_cornell_variant* out,
                                       mrgi_error* err)
{
  if (!name || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_cornell_variant_parse: %s is NULL",
                          name ? "out" : "name");
  }
  static const mrgi_cornell_variant all[] = { MRGI_CORNELL_POINT, MRGI_CORNELL_SPOT,
                                              MRGI_CORNELL_AREA };
  for (size_t i = 0; i < sizeof(all) / sizeof(all[0]); ++i)
  {
    if (strcmp(name, mrgi_cornell_variant_name(all[i])) == 0)
    {
      *out = all[i];
      return MRGI_OK;
    }
  }
  return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                        "mrgi_cornell_variant_parse: unknown Cornell box variant '%.64s' "
                        "(known: cornell, cornell-spot, cornell-area)",
                        name);
}

static const double mrgi_cornell_pi = 3.14159265358979323846;

static mrgi_status mrgi_cornell_build_mesh(const mrgi_cornell_surface* surface, mrgi_mesh* mesh,
                                           mrgi_error* err)
{
  mrgi_status status = mrgi_mesh_create(mesh, surface->name, 4 * surface->quad_count,
                                        2 * surface->quad_count, 1, err);
  mrgi_mesh_cursor cursor = { 0, 0 };
  const int is_emitter = surface->first_quad == MRGI_CORNELL_LIGHT_QUAD;
  for (int q = 0; status == MRGI_OK && q < surface->quad_count; ++q)
  {
    float quad[4][3];
    memcpy(quad, mrgi_cornell_quads[surface->first_quad + q], sizeof(quad));
    if (is_emitter)
    {
      for (int k = 0; k < 4; ++k)
      {
        quad[k][1] -= (float)MRGI_CORNELL_EMITTER_DROP_MM;
      }
    }
    status = mrgi_mesh_put_polygon(mesh, &cursor, (const float(*)[3])quad, 4, err);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_mesh_cursor_finish(mesh, &cursor, err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  memcpy(mesh->albedo, surface->albedo, sizeof(mesh->albedo));
  if (is_emitter)
  {
    memcpy(mesh->emission, mrgi_cornell_emitter_radiance, sizeof(mesh->emission));
  }
  return MRGI_OK;
}

/* The published emitter quad as a rectangle: edges from its first corner. */
static void mrgi_cornell_area_light(mrgi_area_light* light)
{
  const float(*q)[3] = mrgi_cornell_quads[MRGI_CORNELL_LIGHT_QUAD];
  for (int axis = 0; axis < 3; ++axis)
  {
    /* Corner 0 -> 1 and 0 -> 3: (0, 0, 105) x (-130, 0, 0) = (0, -13650, 0),
     * so the emitting side (edge_u x edge_v) faces down, as published. */
    light->edge_u[axis] = (double)q[1][axis] - (double)q[0][axis];
    light->edge_v[axis] = (double)q[3][axis] - (double)q[0][axis];
    light->center[axis] = 0.25 * ((double)q[0][axis] + q[1][axis] + q[2][axis] + q[3][axis]);
    light->color[axis] = mrgi_cornell_emitter_radiance[axis];
  }
  light->center[1] -= MRGI_CORNELL_EMITTER_DROP_MM;
  light->intensity = 1.0; /* radiance = intensity * color = the emitter's (mrgi_area_light.h) */
  light->texture = NULL;
  light->two_sided = 0;
}

static void mrgi_cornell_point_light(mrgi_light* light, mrgi_light_type type)
{
  memset(light, 0, sizeof(*light));
  light->type = type;
  memcpy(light->position, mrgi_cornell_light_position, sizeof(light->position));
  memcpy(light->focal_point, mrgi_cornell_light_position, sizeof(light->focal_point));
  light->focal_point[1] = 0.0; /* straight down, onto the floor */
  light->color[0] = light->color[1] = light->color[2] = 1.0;
  light->intensity = 1.0;
  light->exponent = 1.0;
  light->cone_angle_deg = type == MRGI_LIGHT_SPOT ? MRGI_CORNELL_SPOT_CONE_DEG : 90.0;
}

mrgi_status mrgi_scene_cornell_box(mrgi_cornell_variant variant, mrgi_scene* out, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_scene_cornell_box: out is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (!mrgi_cornell_variant_name(variant))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "mrgi_scene_cornell_box: unknown variant %d", (int)variant);
  }
  const int32_t mesh_count = variant == MRGI_CORNELL_AREA ? MRGI_CORNELL_SURFACES_WITH_LIGHT
                                                          : MRGI_CORNELL_SURFACES_WITHOUT_LIGHT;
  mrgi_status status = mrgi_scene_create(out, mesh_count, err);
  for (int32_t i = 0; status == MRGI_OK && i < mesh_count; ++i)
  {
    status = mrgi_cornell_build_mesh(&mrgi_cornell_surfaces[i], &out->meshes[i], err);
  }
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "mrgi_scene_cornell_box: ");
    mrgi_scene_destroy(out);
    return status;
  }

  mrgi_camera* camera = &out->camera;
  camera->position[0] = 278.0;
  camera->position[1] = 273.0;
  camera->position[2] = -800.0;
  camera->focal_point[0] = 278.0;
  camera->focal_point[1] = 273.0;
  camera->focal_point[2] = 0.0;
  camera->view_up[1] = 1.0;
  camera->view_angle_deg =
    2.0 * atan(0.5 * mrgi_cornell_film_size_m / mrgi_cornell_focal_length_m) * 180.0 / mrgi_cornell_pi;

  switch (variant)
  {
    case MRGI_CORNELL_POINT:
      mrgi_cornell_point_light(&out->lights[0], MRGI_LIGHT_POSITIONAL);
      out->light_count = 1;
      break;
    case MRGI_CORNELL_SPOT:
      mrgi_cornell_point_light(&out->lights[0], MRGI_LIGHT_SPOT);
      out->light_count = 1;
      break;
    case MRGI_CORNELL_AREA:
      mrgi_cornell_area_light(&out->area_lights[0]);
      out->area_light_count = 1;
      break;
  }
  return MRGI_OK;
}
