#include "mrgi_scene_living_room.h"

#include <string.h>

/* Faces of an axis-aligned box, bit 2 * axis + side (side 1 = the high one). */
enum
{
  LR_NX = 1 << 0,
  LR_PX = 1 << 1,
  LR_NY = 1 << 2,
  LR_PY = 1 << 3,
  LR_NZ = 1 << 4,
  LR_PZ = 1 << 5,
  LR_CLOSED = 0x3F,
  LR_ON_FLOOR = LR_CLOSED & ~LR_NY /* standing on the floor: no bottom */
};

/* An axis-aligned box (metres) and the faces it has. */
typedef struct lr_box
{
  float lo[3];
  float hi[3];
  unsigned faces;
} lr_box;

/* The room's shell; each wall is the face of this box on one side, facing in. */
static const float lr_room_lo[3] = { -2.4f, 0.0f, 0.0f };
static const float lr_room_hi[3] = { 2.4f, 2.6f, 5.2f };

/* The TV set: its front face is z = 0.16; the screen sits just in front. */
#define LR_SET_FRONT_Z 0.16
static const double lr_screen_center[3] = { 0.0, 0.95, LR_SET_FRONT_Z + MRGI_LIVING_ROOM_SCREEN_OFFSET_M };

static const lr_box lr_boxes[] = {
  /* 0: tv_stand */
  { { -1.0f, 0.0f, 0.03f }, { 1.0f, 0.45f, 0.48f }, LR_ON_FLOOR },
  /* 1: tv_set (wall-mounted, 8 cm off the wall, 10 cm above the cabinet) */
  { { -0.65f, 0.55f, 0.08f }, { 0.65f, 1.35f, (float)LR_SET_FRONT_Z }, LR_CLOSED },
  /* 2..5: sofa: seat, backrest, left arm, right arm */
  { { -1.1f, 0.0f, 3.0f }, { 1.1f, 0.42f, 3.9f }, LR_ON_FLOOR },
  { { -1.1f, 0.0f, 3.9f }, { 1.1f, 0.85f, 4.15f }, LR_ON_FLOOR },
  { { -1.3f, 0.0f, 3.0f }, { -1.1f, 0.62f, 4.15f }, LR_ON_FLOOR },
  { { 1.1f, 0.0f, 3.0f }, { 1.3f, 0.62f, 4.15f }, LR_ON_FLOOR },
  /* 6..10: table: top, then four legs */
  { { -0.6f, 0.38f, 1.75f }, { 0.6f, 0.43f, 2.35f }, LR_CLOSED },
  { { -0.57f, 0.0f, 1.78f }, { -0.52f, 0.38f, 1.83f }, LR_ON_FLOOR },
  { { 0.52f, 0.0f, 1.78f }, { 0.57f, 0.38f, 1.83f }, LR_ON_FLOOR },
  { { -0.57f, 0.0f, 2.27f }, { -0.52f, 0.38f, 2.32f }, LR_ON_FLOOR },
  { { 0.52f, 0.0f, 2.27f }, { 0.57f, 0.38f, 2.32f }, LR_ON_FLOOR },
  /* 11..16: shelf: side panels, plinth, three boards (between the panels) */
  { { 1.98f, 0.0f, 1.3f }, { 2.36f, 1.9f, 1.32f }, LR_ON_FLOOR },
  { { 1.98f, 0.0f, 2.28f }, { 2.36f, 1.9f, 2.3f }, LR_ON_FLOOR },
  { { 1.98f, 0.0f, 1.32f }, { 2.36f, 0.08f, 2.28f }, LR_ON_FLOOR },
  { { 1.98f, 0.6f, 1.32f }, { 2.36f, 0.62f, 2.28f }, LR_CLOSED },
  { { 1.98f, 1.2f, 1.32f }, { 2.36f, 1.22f, 2.28f }, LR_CLOSED },
  { { 1.98f, 1.88f, 1.32f }, { 2.36f, 1.9f, 2.28f }, LR_CLOSED },
  /* 17..19: books, standing on the plinth and two boards */
  { { 2.05f, 0.08f, 1.5f }, { 2.3f, 0.38f, 2.2f }, LR_CLOSED },
  { { 2.05f, 0.62f, 1.4f }, { 2.3f, 0.9f, 1.8f }, LR_CLOSED },
  { { 2.05f, 1.22f, 1.85f }, { 2.3f, 1.45f, 2.2f }, LR_CLOSED },
};

/* Albedos, linear RGB. */
static const float lr_oak[3] = { 0.42f, 0.28f, 0.16f };
static const float lr_ceiling_white[3] = { 0.80f, 0.80f, 0.78f };
static const float lr_grey_blue[3] = { 0.40f, 0.46f, 0.55f };
static const float lr_off_white[3] = { 0.72f, 0.68f, 0.60f };
static const float lr_walnut[3] = { 0.20f, 0.13f, 0.08f };
static const float lr_tv_black[3] = { 0.03f, 0.03f, 0.03f };
static const float lr_black[3] = { 0.0f, 0.0f, 0.0f };
static const float lr_red_fabric[3] = { 0.55f, 0.16f, 0.12f };
static const float lr_light_wood[3] = { 0.55f, 0.42f, 0.28f };
static const float lr_shelf_white[3] = { 0.65f, 0.62f, 0.58f };
static const float lr_book_blue[3] = { 0.18f, 0.32f, 0.55f };

typedef enum lr_kind
{
  LR_WALL,   /* one face of the room box, facing in */
  LR_BOXES,  /* boxes first_box .. first_box + box_count - 1 */
  LR_SCREEN  /* the emitter quad */
} lr_kind;

typedef struct lr_surface
{
  const char* name;
  const float* albedo;
  lr_kind kind;
  int first; /* LR_WALL: face bit index 2 * axis + side; LR_BOXES: first box */
  int count; /* LR_BOXES: box count */
} lr_surface;

static const lr_surface lr_surfaces[] = {
  { "floor", lr_oak, LR_WALL, 2, 0 },
  { "ceiling", lr_ceiling_white, LR_WALL, 3, 0 },
  { "tv_wall", lr_grey_blue, LR_WALL, 4, 0 },
  { "back_wall", lr_off_white, LR_WALL, 5, 0 },
  { "left_wall", lr_off_white, LR_WALL, 0, 0 },
  { "right_wall", lr_off_white, LR_WALL, 1, 0 },
  { "tv_stand", lr_walnut, LR_BOXES, 0, 1 },
  { "tv_set", lr_tv_black, LR_BOXES, 1, 1 },
  { "screen", lr_black, LR_SCREEN, 0, 0 },
  { "sofa", lr_red_fabric, LR_BOXES, 2, 4 },
  { "table", lr_light_wood, LR_BOXES, 6, 5 },
  { "shelf", lr_shelf_white, LR_BOXES, 11, 6 },
  { "books", lr_book_blue, LR_BOXES, 17, 3 },
};
enum
{
  LR_MESH_COUNT = (int)(sizeof(lr_surfaces) / sizeof(lr_surfaces[0]))
};

static int lr_bit_count(unsigned faces)
{
  int n = 0;
  for (; faces; faces >>= 1)
  {
    n += (int)(faces & 1u);
  }
  return n;
}

/*
 * The face of box [lo, hi] on `side` (0 low, 1 high) of `axis`, its normal
 * +e_axis when `positive`, else -e_axis. With b, c the next two axes
 * cyclically, the corners (lo_b, lo_c), (hi_b, lo_c), (hi_b, hi_c),
 * (lo_b, hi_c) run counter-clockwise around e_b x e_c = +e_axis.
 */
static mrgi_status lr_put_face(mrgi_mesh* mesh, mrgi_mesh_cursor* cursor, const float lo[3],
                               const float hi[3], int axis, int side, int positive,
                               mrgi_error* err)
{
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  const float at = side ? hi[axis] : lo[axis];
  static const int corner_b[4] = { 0, 1, 1, 0 };
  static const int corner_c[4] = { 0, 0, 1, 1 };
  float quad[4][3];
  for (int k = 0; k < 4; ++k)
  {
    const int slot = positive ? k : 3 - k;
    quad[slot][axis] = at;
    quad[slot][b] = corner_b[k] ? hi[b] : lo[b];
    quad[slot][c] = corner_c[k] ? hi[c] : lo[c];
  }
  return mrgi_mesh_put_polygon(mesh, cursor, (const float(*)[3])quad, 4, err);
}

/* The screen rectangle as the light: centre, full edges, facing +z. */
static void lr_screen_light(mrgi_area_light* light, const mrgi_image* texture)
{
  memset(light, 0, sizeof(*light));
  memcpy(light->center, lr_screen_center, sizeof(light->center));
  light->edge_u[0] = MRGI_LIVING_ROOM_SCREEN_WIDTH_M;  /* right, seen from the sofa */
  light->edge_v[1] = MRGI_LIVING_ROOM_SCREEN_HEIGHT_M; /* up: u x v = +z */
  light->color[0] = light->color[1] = light->color[2] = 1.0;
  light->intensity = MRGI_LIVING_ROOM_SCREEN_INTENSITY;
  light->texture = texture;
  light->two_sided = 0;
}

/* The test card of the header, row 0 = top. */
static void lr_fill_texture(mrgi_image* image)
{
  static const float bars[7][3] = {
    { 0.75f, 0.75f, 0.75f }, { 0.75f, 0.75f, 0.0f }, { 0.0f, 0.75f, 0.75f }, { 0.0f, 0.75f, 0.0f },
    { 0.75f, 0.0f, 0.75f },  { 0.75f, 0.0f, 0.0f },  { 0.0f, 0.0f, 0.75f },
  };
  static const float castellations[7][3] = {
    { 0.0f, 0.0f, 0.75f }, { 0.0f, 0.0f, 0.0f }, { 0.75f, 0.0f, 0.75f }, { 0.0f, 0.0f, 0.0f },
    { 0.0f, 0.75f, 0.75f }, { 0.0f, 0.0f, 0.0f }, { 0.75f, 0.75f, 0.75f },
  };
  const int32_t w = image->width, h = image->height;
  const int32_t bar_rows = h * 2 / 3;           /* 24 of 36 */
  const int32_t castellation_rows = h / 12;     /* 3 */
  const int32_t ramp_columns = w * 3 / 4;       /* 48 of 64 */
  for (int32_t y = 0; y < h; ++y)
  {
    for (int32_t x = 0; x < w; ++x)
    {
      float* p = mrgi_image_at(image, x, y);
      const int32_t bar = x * 7 / w;
      if (y < bar_rows)
      {
        memcpy(p, bars[bar], 3 * sizeof(float));
      }
      else if (y < bar_rows + castellation_rows)
      {
        memcpy(p, castellations[bar], 3 * sizeof(float));
      }
      else if (x < ramp_columns)
      {
        p[0] = p[1] = p[2] = ((float)x + 0.5f) / (float)ramp_columns;
      }
      else
      {
        p[0] = p[1] = p[2] = ((x + y) & 1) ? 1.0f : 0.0f;
      }
    }
  }
}

static mrgi_status lr_build_mesh(const lr_surface* surface, const mrgi_area_light* light,
                                 mrgi_mesh* mesh, mrgi_error* err)
{
  int quads = 0;
  switch (surface->kind)
  {
    case LR_WALL:
    case LR_SCREEN:
      quads = 1;
      break;
    case LR_BOXES:
      for (int i = 0; i < surface->count; ++i)
      {
        quads += lr_bit_count(lr_boxes[surface->first + i].faces);
      }
      break;
  }
  mrgi_status status = mrgi_mesh_create(mesh, surface->name, 4 * quads, 2 * quads, 1, err);
  mrgi_mesh_cursor cursor = { 0, 0 };
  if (status == MRGI_OK && surface->kind == LR_WALL)
  {
    /* The room box's face, facing in: on the low side along +e_axis. */
    const int axis = surface->first / 2, side = surface->first % 2;
    status = lr_put_face(mesh, &cursor, lr_room_lo, lr_room_hi, axis, side, !side, err);
  }
  else if (status == MRGI_OK && surface->kind == LR_SCREEN)
  {
    double corners[4][3];
    status = mrgi_area_light_corners(light, corners, err);
    float quad[4][3];
    for (int k = 0; k < 4; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        quad[k][a] = (float)corners[k][a];
      }
    }
    if (status == MRGI_OK)
    {
      status = mrgi_mesh_put_polygon(mesh, &cursor, (const float(*)[3])quad, 4, err);
    }
  }
  for (int i = 0; status == MRGI_OK && surface->kind == LR_BOXES && i < surface->count; ++i)
  {
    const lr_box* box = &lr_boxes[surface->first + i];
    for (int bit = 0; status == MRGI_OK && bit < 6; ++bit)
    {
      if (box->faces & (1u << bit))
      {
        /* Out of the box: the high side along +e_axis. */
        status = lr_put_face(mesh, &cursor, box->lo, box->hi, bit / 2, bit % 2, bit % 2, err);
      }
    }
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
  if (surface->kind == LR_SCREEN)
  {
    /* The mean radiance: intensity * color * (texture mean). */
    const mrgi_image* t = light->texture;
    const int64_t texels = mrgi_image_pixel_count(t);
    for (int ch = 0; ch < 3; ++ch)
    {
      double sum = 0.0;
      for (int64_t i = 0; i < texels; ++i)
      {
        sum += (double)t->pixels[(size_t)i * (size_t)t->channels + (size_t)ch];
      }
      mesh->emission[ch] = (float)(light->intensity * light->color[ch] * sum / (double)texels);
    }
  }
  return MRGI_OK;
}

mrgi_status mrgi_scene_living_room(mrgi_scene* out, mrgi_error* err)
{
  static const char* caller = "mrgi_scene_living_room";
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: out is NULL", caller);
  }
  memset(out, 0, sizeof(*out));
  mrgi_status status = mrgi_scene_create(out, LR_MESH_COUNT, err);
  if (status == MRGI_OK)
  {
    status = mrgi_scene_create_images(out, 1, err);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_image_create(&out->images[0], MRGI_LIVING_ROOM_TEXTURE_WIDTH,
                               MRGI_LIVING_ROOM_TEXTURE_HEIGHT, 3, err);
  }
  if (status == MRGI_OK)
  {
    lr_fill_texture(&out->images[0]);
    lr_screen_light(&out->area_lights[0], &out->images[0]);
    out->area_light_count = 1;
    out->light_count = 0;
  }
  for (int32_t i = 0; status == MRGI_OK && i < LR_MESH_COUNT; ++i)
  {
    status = lr_build_mesh(&lr_surfaces[i], &out->area_lights[0], &out->meshes[i], err);
  }
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "%s: ", caller);
    mrgi_scene_destroy(out);
    return status;
  }

  mrgi_camera* camera = &out->camera;
  camera->position[0] = 0.5;
  camera->position[1] = 1.45;
  camera->position[2] = 5.05;
  camera->focal_point[0] = 0.0;
  camera->focal_point[1] = 0.7;
  camera->focal_point[2] = 1.0;
  camera->view_up[1] = 1.0;
  camera->view_angle_deg = 55.0;
  return MRGI_OK;
}
