#include "mrgi_scene_indirect.h"

#include <math.h>
#include <string.h>

/*
 * The scenes of RIHKS11 figures 5, 7 and 10 (Ritschel et al. 2011, "Making
 * Imperfect Shadow Maps View-Adaptive"), rebuilt from the figures' captions
 * and the text of sections 4.2, 5.1 and 8.1; the paper publishes no
 * geometry, so every size below is ours (mrgi_scene_indirect.h).
 */

static const float mrgi_indirect_white[3] = { 0.725f, 0.71f, 0.68f };
static const float mrgi_indirect_grey[3] = { 0.5f, 0.5f, 0.5f };
static const float mrgi_indirect_warm[3] = { 0.75f, 0.5f, 0.3f };
static const float mrgi_indirect_end_wall[3] = { 0.8f, 0.7f, 0.55f };

/* Corridor: cross-section, length, statue. */
static const double mrgi_corridor_half_width = 1.0;
static const double mrgi_corridor_height = 2.5;
static const double mrgi_corridor_length = 12.0;
static const double mrgi_corridor_large_length = 120.0;
static const double mrgi_corridor_statue_x = -0.3;
static const double mrgi_corridor_statue_z = 4.0;
static const double mrgi_corridor_pedestal_half = 0.25;
static const double mrgi_corridor_pedestal_height = 0.7;
static const double mrgi_corridor_ball_radius = 0.3;
/* The spot, high by the right wall between camera and statue, aimed across
 * at the left wall. */
static const double mrgi_corridor_spot[3] = { -0.8, 2.3, 1.2 };
static const double mrgi_corridor_spot_target[3] = { 1.0, 1.0, 1.0 };

enum
{
  MRGI_INDIRECT_MAX_RECTS = 8,
  MRGI_INDIRECT_BALL_SLICES = 24,
  MRGI_INDIRECT_BALL_STACKS = 12
};

/* An axis-aligned rectangle on the plane x[axis] = at, spanning lo..hi on the
 * two other axes (in the order axis+1, axis+2), whose front faces
 * sign * e_axis. */
typedef struct mrgi_indirect_rect
{
  int axis;
  int sign;
  double at;
  double lo[2];
  double hi[2];
} mrgi_indirect_rect;

/* A mesh to build: rectangles cut into tiles, and optionally a ball. */
typedef struct mrgi_indirect_part
{
  const char* name;
  const float* albedo;
  mrgi_indirect_rect rects[MRGI_INDIRECT_MAX_RECTS];
  int rect_count;
  int has_ball;
  double ball_center[3];
  double ball_radius;
} mrgi_indirect_part;

const char* mrgi_indirect_scene_name(mrgi_indirect_scene which)
{
  switch (which)
  {
    case MRGI_INDIRECT_CORRIDOR:
      return "corridor";
    case MRGI_INDIRECT_CORRIDOR_LARGE:
      return "corridor-large";
    case MRGI_INDIRECT_CORNER:
      return "corner";
    case MRGI_INDIRECT_U_SHAPE:
      return "u-shape";
  }
  return NULL;
}

mrgi_status mrgi_indirect_scene_parse(const char* name, mrgi_indirect_scene* out,
                                      mrgi_error* err)
{
  if (!name || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_indirect_scene_parse: %s is NULL",
                          name ? "out" : "name");
  }
  static const mrgi_indirect_scene all[] = { MRGI_INDIRECT_CORRIDOR, MRGI_INDIRECT_CORRIDOR_LARGE,
                                             MRGI_INDIRECT_CORNER, MRGI_INDIRECT_U_SHAPE };
  for (size_t i = 0; i < sizeof(all) / sizeof(all[0]); ++i)
  {
    if (strcmp(name, mrgi_indirect_scene_name(all[i])) == 0)
    {
      *out = all[i];
      return MRGI_OK;
    }
  }
  return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                        "mrgi_indirect_scene_parse: unknown scene '%.64s' "
                        "(known: corridor, corridor-large, corner, u-shape)",
                        name);
}

static mrgi_indirect_rect mrgi_rect(int axis, int sign, double at, double lo0, double hi0,
                                    double lo1, double hi1)
{
  mrgi_indirect_rect r;
  r.axis = axis;
  r.sign = sign;
  r.at = at;
  r.lo[0] = lo0;
  r.hi[0] = hi0;
  r.lo[1] = lo1;
  r.hi[1] = hi1;
  return r;
}

static int mrgi_rect_tiles(const mrgi_indirect_rect* r, int side)
{
  const double n = ceil((r->hi[side] - r->lo[side]) / MRGI_INDIRECT_TILE_M - 1e-9);
  return n < 1.0 ? 1 : (int)n;
}

/* Tile (i, j) of `r` as a counter-clockwise quad seen from its front: with
 * b = axis+1, c = axis+2 (cyclic), e_b x e_c = e_axis, so corners running
 * +b then +c face +axis; the reverse order faces -axis. */
static void mrgi_rect_tile(const mrgi_indirect_rect* r, int i, int j, float quad[4][3])
{
  const int b = (r->axis + 1) % 3, c = (r->axis + 2) % 3;
  const int nb = mrgi_rect_tiles(r, 0), nc = mrgi_rect_tiles(r, 1);
  const double db = (r->hi[0] - r->lo[0]) / nb, dc = (r->hi[1] - r->lo[1]) / nc;
  /* Corner coordinates from the tile index, so that neighbouring tiles share
   * bit-identical edges (no cracks for the ray tracer). */
  const double b0 = i == 0 ? r->lo[0] : r->lo[0] + i * db;
  const double b1 = i + 1 == nb ? r->hi[0] : r->lo[0] + (i + 1) * db;
  const double c0 = j == 0 ? r->lo[1] : r->lo[1] + j * dc;
  const double c1 = j + 1 == nc ? r->hi[1] : r->lo[1] + (j + 1) * dc;
  const double corners[4][2] = { { b0, c0 }, { b1, c0 }, { b1, c1 }, { b0, c1 } };
  for (int k = 0; k < 4; ++k)
  {
    const int src = r->sign > 0 ? k : 3 - k;
    quad[k][r->axis] = (float)r->at;
    quad[k][b] = (float)corners[src][0];
    quad[k][c] = (float)corners[src][1];
  }
}

static mrgi_status mrgi_indirect_build_part(const mrgi_indirect_part* part, mrgi_mesh* mesh,
                                            mrgi_error* err)
{
  int64_t tiles = 0;
  for (int q = 0; q < part->rect_count; ++q)
  {
    tiles += (int64_t)mrgi_rect_tiles(&part->rects[q], 0) * mrgi_rect_tiles(&part->rects[q], 1);
  }
  const int slices = MRGI_INDIRECT_BALL_SLICES, stacks = MRGI_INDIRECT_BALL_STACKS;
  const int64_t ball_vertices = part->has_ball ? (int64_t)(stacks + 1) * (slices + 1) : 0;
  const int64_t ball_triangles = part->has_ball ? 2 * (int64_t)slices * (stacks - 1) : 0;
  mrgi_status status =
    mrgi_mesh_create(mesh, part->name, 4 * tiles + ball_vertices, 2 * tiles + ball_triangles, 1, err);
  mrgi_mesh_cursor cursor = { 0, 0 };
  for (int q = 0; status == MRGI_OK && q < part->rect_count; ++q)
  {
    const mrgi_indirect_rect* r = &part->rects[q];
    const int nb = mrgi_rect_tiles(r, 0), nc = mrgi_rect_tiles(r, 1);
    for (int j = 0; status == MRGI_OK && j < nc; ++j)
    {
      for (int i = 0; status == MRGI_OK && i < nb; ++i)
      {
        float quad[4][3];
        mrgi_rect_tile(r, i, j, quad);
        status = mrgi_mesh_put_polygon(mesh, &cursor, (const float(*)[3])quad, 4, err);
      }
    }
  }
  if (status == MRGI_OK && part->has_ball)
  {
    /* A UV sphere with smooth (radial) normals; rows run from the top pole
     * (theta = 0) down. The pole rows get one triangle per slice, the others
     * two, so no triangle is degenerate. */
    const double pi = 3.14159265358979323846;
    const int64_t base = cursor.vertex;
    for (int s = 0; s <= stacks; ++s)
    {
      const double theta = pi * s / stacks;
      for (int k = 0; k <= slices; ++k)
      {
        const double phi = 2.0 * pi * (k == slices ? 0 : k) / slices;
        const double n[3] = { sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi) };
        const size_t v = (size_t)(cursor.vertex++);
        for (int a = 0; a < 3; ++a)
        {
          mesh->positions[3 * v + a] = (float)(part->ball_center[a] + part->ball_radius * n[a]);
          mesh->normals[3 * v + a] = (float)n[a];
        }
      }
    }
    for (int s = 0; s < stacks; ++s)
    {
      for (int k = 0; k < slices; ++k)
      {
        const uint32_t a = (uint32_t)(base + s * (slices + 1) + k), b = a + 1;
        const uint32_t c = a + (uint32_t)(slices + 1), d = c + 1;
        /* Counter-clockwise seen from outside: a (upper), d, c (lower) and a, b, d. */
        if (s + 1 < stacks)
        {
          uint32_t* t = mesh->indices + 3 * (size_t)(cursor.triangle++);
          t[0] = a, t[1] = d, t[2] = c;
        }
        if (s > 0)
        {
          uint32_t* t = mesh->indices + 3 * (size_t)(cursor.triangle++);
          t[0] = a, t[1] = b, t[2] = d;
        }
      }
    }
  }
  if (status == MRGI_OK)
  {
    status = mrgi_mesh_cursor_finish(mesh, &cursor, err);
  }
  if (status == MRGI_OK)
  {
    memcpy(mesh->albedo, part->albedo, sizeof(mesh->albedo));
  }
  return status;
}

static void mrgi_set3(double out[3], double x, double y, double z)
{
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

static void mrgi_indirect_spot(mrgi_light* light, double px, double py, double pz, double fx,
                               double fy, double fz, double cone_deg, double intensity)
{
  memset(light, 0, sizeof(*light));
  light->type = MRGI_LIGHT_SPOT;
  mrgi_set3(light->position, px, py, pz);
  mrgi_set3(light->focal_point, fx, fy, fz);
  mrgi_set3(light->color, 1.0, 1.0, 1.0);
  light->intensity = intensity;
  light->cone_angle_deg = cone_deg;
  light->exponent = 1.0;
}

static void mrgi_indirect_camera(mrgi_camera* camera, double px, double py, double pz, double fx,
                                 double fy, double fz)
{
  memset(camera, 0, sizeof(*camera));
  mrgi_set3(camera->position, px, py, pz);
  mrgi_set3(camera->focal_point, fx, fy, fz);
  mrgi_set3(camera->view_up, 0.0, 1.0, 0.0);
  camera->view_angle_deg = 55.0;
}

/* Axis numbers. */
enum
{
  X = 0,
  Y = 1,
  Z = 2
};

/* Rectangles span (axis+1, axis+2): x-walls span (y, z), y-planes (z, x),
 * z-walls (x, y). */
static int mrgi_corridor_parts(double length, mrgi_indirect_part parts[7])
{
  const double w = mrgi_corridor_half_width, h = mrgi_corridor_height;
  memset(parts, 0, 7 * sizeof(parts[0]));
  parts[0] = (mrgi_indirect_part){ "floor", mrgi_indirect_grey, { mrgi_rect(Y, +1, 0.0, 0.0, length, -w, w) }, 1, 0, { 0 }, 0 };
  parts[1] = (mrgi_indirect_part){ "ceiling", mrgi_indirect_white, { mrgi_rect(Y, -1, h, 0.0, length, -w, w) }, 1, 0, { 0 }, 0 };
  parts[2] = (mrgi_indirect_part){ "left_wall", mrgi_indirect_white, { mrgi_rect(X, -1, w, 0.0, h, 0.0, length) }, 1, 0, { 0 }, 0 };
  parts[3] = (mrgi_indirect_part){ "right_wall", mrgi_indirect_white, { mrgi_rect(X, +1, -w, 0.0, h, 0.0, length) }, 1, 0, { 0 }, 0 };
  parts[4] = (mrgi_indirect_part){ "near_wall", mrgi_indirect_end_wall, { mrgi_rect(Z, +1, 0.0, -w, w, 0.0, h) }, 1, 0, { 0 }, 0 };
  parts[5] = (mrgi_indirect_part){ "far_wall", mrgi_indirect_white, { mrgi_rect(Z, -1, length, -w, w, 0.0, h) }, 1, 0, { 0 }, 0 };
  /* The statue: pedestal (four sides and the top; it stands on the floor) and ball. */
  const double sx = mrgi_corridor_statue_x, sz = mrgi_corridor_statue_z;
  const double p = mrgi_corridor_pedestal_half, ph = mrgi_corridor_pedestal_height;
  mrgi_indirect_part* statue = &parts[6];
  statue->name = "statue";
  statue->albedo = mrgi_indirect_white;
  statue->rects[0] = mrgi_rect(Y, +1, ph, sz - p, sz + p, sx - p, sx + p);
  statue->rects[1] = mrgi_rect(X, +1, sx + p, 0.0, ph, sz - p, sz + p);
  statue->rects[2] = mrgi_rect(X, -1, sx - p, 0.0, ph, sz - p, sz + p);
  statue->rects[3] = mrgi_rect(Z, +1, sz + p, sx - p, sx + p, 0.0, ph);
  statue->rects[4] = mrgi_rect(Z, -1, sz - p, sx - p, sx + p, 0.0, ph);
  statue->rect_count = 5;
  statue->has_ball = 1;
  mrgi_set3(statue->ball_center, sx, ph + mrgi_corridor_ball_radius, sz);
  statue->ball_radius = mrgi_corridor_ball_radius;
  return 7;
}

static int mrgi_corner_parts(mrgi_indirect_part parts[3])
{
  memset(parts, 0, 3 * sizeof(parts[0]));
  parts[0] = (mrgi_indirect_part){ "floor", mrgi_indirect_grey, { mrgi_rect(Y, +1, 0.0, 0.0, 4.0, 0.0, 4.0) }, 1, 0, { 0 }, 0 };
  parts[1] = (mrgi_indirect_part){ "back_wall", mrgi_indirect_white, { mrgi_rect(Z, -1, 4.0, 0.0, 4.0, 0.0, 3.0) }, 1, 0, { 0 }, 0 };
  parts[2] = (mrgi_indirect_part){ "side_wall", mrgi_indirect_warm, { mrgi_rect(X, +1, 0.0, 0.0, 3.0, 0.0, 4.0) }, 1, 0, { 0 }, 0 };
  return 3;
}

static int mrgi_u_shape_parts(mrgi_indirect_part parts[4])
{
  const double h = 2.5;
  memset(parts, 0, 4 * sizeof(parts[0]));
  /* Floor and ceiling: the two arms (x 0..2, x 4..6 over z 0..4) and the base (z 4..6). */
  for (int i = 0; i < 2; ++i)
  {
    mrgi_indirect_part* part = &parts[i];
    const int sign = i == 0 ? +1 : -1;
    const double at = i == 0 ? 0.0 : h;
    part->name = i == 0 ? "floor" : "ceiling";
    part->albedo = i == 0 ? mrgi_indirect_grey : mrgi_indirect_white;
    part->rects[0] = mrgi_rect(Y, sign, at, 0.0, 4.0, 0.0, 2.0);
    part->rects[1] = mrgi_rect(Y, sign, at, 0.0, 4.0, 4.0, 6.0);
    part->rects[2] = mrgi_rect(Y, sign, at, 4.0, 6.0, 0.0, 6.0);
    part->rect_count = 3;
  }
  mrgi_indirect_part* outer = &parts[2];
  outer->name = "outer_wall";
  outer->albedo = mrgi_indirect_white;
  outer->rects[0] = mrgi_rect(X, +1, 0.0, 0.0, h, 0.0, 6.0);
  outer->rects[1] = mrgi_rect(X, -1, 6.0, 0.0, h, 0.0, 6.0);
  outer->rects[2] = mrgi_rect(Z, -1, 6.0, 0.0, 6.0, 0.0, h);
  outer->rects[3] = mrgi_rect(Z, +1, 0.0, 0.0, 2.0, 0.0, h);
  outer->rects[4] = mrgi_rect(Z, +1, 0.0, 4.0, 6.0, 0.0, h);
  outer->rect_count = 5;
  mrgi_indirect_part* inner = &parts[3];
  inner->name = "inner_wall";
  inner->albedo = mrgi_indirect_white;
  inner->rects[0] = mrgi_rect(X, -1, 2.0, 0.0, h, 0.0, 4.0);
  inner->rects[1] = mrgi_rect(X, +1, 4.0, 0.0, h, 0.0, 4.0);
  inner->rects[2] = mrgi_rect(Z, +1, 4.0, 2.0, 4.0, 0.0, h);
  inner->rect_count = 3;
  return 4;
}

mrgi_status mrgi_scene_indirect(mrgi_indirect_scene which, mrgi_scene* out, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_scene_indirect: out is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (!mrgi_indirect_scene_name(which))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_scene_indirect: unknown scene %d",
                          (int)which);
  }
  mrgi_indirect_part parts[7];
  int count = 0;
  const int corridor = which == MRGI_INDIRECT_CORRIDOR || which == MRGI_INDIRECT_CORRIDOR_LARGE;
  const double length =
    which == MRGI_INDIRECT_CORRIDOR_LARGE ? mrgi_corridor_large_length : mrgi_corridor_length;
  if (corridor)
  {
    count = mrgi_corridor_parts(length, parts);
  }
  else if (which == MRGI_INDIRECT_CORNER)
  {
    count = mrgi_corner_parts(parts);
  }
  else
  {
    count = mrgi_u_shape_parts(parts);
  }

  mrgi_status status = mrgi_scene_create(out, count, err);
  for (int32_t i = 0; status == MRGI_OK && i < count; ++i)
  {
    status = mrgi_indirect_build_part(&parts[i], &out->meshes[i], err);
  }
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "mrgi_scene_indirect: ");
    mrgi_scene_destroy(out);
    return status;
  }

  out->light_count = 1;
  if (corridor)
  {
    /* RIHKS11 figure 7: the spot lights a wall, the statue gets only the
     * bounce. corridor-large adds length beyond them. */
    const double* p = mrgi_corridor_spot;
    const double* f = mrgi_corridor_spot_target;
    mrgi_indirect_spot(&out->lights[0], p[0], p[1], p[2], f[0], f[1], f[2],
                       MRGI_INDIRECT_CORRIDOR_CONE_DEG, MRGI_INDIRECT_CORRIDOR_INTENSITY);
    mrgi_indirect_camera(&out->camera, 0.0, 1.6, 0.3, 0.0, 0.6, 6.0);
  }
  else if (which == MRGI_INDIRECT_CORNER)
  {
    /* RIHKS11 figure 5: a spot into a corner, VPLs close to their receivers. */
    mrgi_indirect_spot(&out->lights[0], 2.2, 2.6, 1.8, 0.2, 0.3, 3.8,
                       MRGI_INDIRECT_CORNER_CONE_DEG, 1.0);
    mrgi_indirect_camera(&out->camera, 3.2, 1.7, -1.2, 1.2, 0.9, 3.0);
  }
  else
  {
    /* RIHKS11 figure 10: light in one arm, camera in the other. */
    mrgi_indirect_spot(&out->lights[0], 1.0, 2.2, 0.5, 1.3, 1.0, 6.0,
                       MRGI_INDIRECT_U_SHAPE_CONE_DEG, MRGI_INDIRECT_U_SHAPE_INTENSITY);
    mrgi_indirect_camera(&out->camera, 5.0, 1.6, 0.5, 4.6, 0.9, 6.0);
  }
  return MRGI_OK;
}
