#include "mrgi_vpl_tree.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int32_t mrgi_vpl_tree_side(int32_t rsm_size)
{
  if (rsm_size < 1 || rsm_size > MRGI_RSM_MAX_SIZE)
  {
    return 0;
  }
  int32_t side = 1;
  while (side < rsm_size)
  {
    side *= 2;
  }
  return side;
}

mrgi_status mrgi_rsm_view_camera_check(const mrgi_rsm_view_camera* camera, mrgi_error* err)
{
  if (!camera)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM view camera is NULL");
  }
  mrgi_status status = mrgi_gather_check_transform(camera->world_to_view, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  float coefficients[2];
  return mrgi_multires_pixel_size_coefficients(&camera->projection, 1, coefficients, err);
}

/* Common checks of the RSM, the view and its camera. */
static mrgi_status mrgi_vpl_tree_check_view(const mrgi_rsm* rsm, int32_t view,
                                            const mrgi_rsm_view_camera* camera, mrgi_error* err)
{
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (view < 0 || view >= rsm->view_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM view %d is outside 0..%d", view,
                          rsm->view_count - 1);
  }
  return mrgi_rsm_view_camera_check(camera, err);
}

/* y = M x for a column-major rigid M (point: w = 1, direction: w = 0), in double. */
static void mrgi_transform(const float m[16], const float x[3], double w, double y[3])
{
  for (int r = 0; r < 3; ++r)
  {
    y[r] = (double)m[r] * x[0] + (double)m[4 + r] * x[1] + (double)m[8 + r] * x[2] +
           (double)m[12 + r] * w;
  }
}

mrgi_status mrgi_rsm_view_receivers(const mrgi_rsm* rsm, int32_t view,
                                    const mrgi_rsm_view_camera* camera, float* position,
                                    float* normal, size_t count, mrgi_gather_receivers* out,
                                    mrgi_error* err)
{
  mrgi_status status = mrgi_vpl_tree_check_view(rsm, view, camera, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!position || !normal || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "light-space receiver %s is NULL",
                          !position ? "position array" : (!normal ? "normal array" : "output"));
  }
  const int32_t size = rsm->size;
  const int32_t side = mrgi_vpl_tree_side(size);
  const size_t needed = 4 * (size_t)side * (size_t)side;
  if (count < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "light-space receiver arrays hold %zu floats but a %dx%d view needs %zu",
                          count, side, side, needed);
  }
  memset(position, 0, sizeof(float) * needed);
  memset(normal, 0, sizeof(float) * needed);
  for (int32_t y = 0; y < size; ++y)
  {
    for (int32_t x = 0; x < size; ++x)
    {
      const int64_t texel = ((int64_t)view * size + y) * size + x;
      if (!mrgi_rsm_texel_usable(rsm, texel))
      {
        continue;
      }
      const size_t target = 4 * ((size_t)y * (size_t)side + (size_t)x);
      double p[3];
      double n[3];
      mrgi_transform(camera->world_to_view, rsm->position + 4 * texel, 1.0, p);
      mrgi_transform(camera->world_to_view, rsm->normal + 4 * texel, 0.0, n);
      for (int c = 0; c < 3; ++c)
      {
        position[target + (size_t)c] = (float)p[c];
        normal[target + (size_t)c] = (float)n[c];
      }
      position[target + 3] = MRGI_GBUFFER_VALID;
    }
  }
  out->width = side;
  out->height = side;
  out->position = position;
  out->normal = normal;
  return MRGI_OK;
}

void mrgi_vpl_tree_destroy(mrgi_vpl_tree* tree)
{
  if (!tree)
  {
    return;
  }
  free(tree->nodes);
  free(tree->sums);
  memset(tree, 0, sizeof(*tree));
}

/* The smallest float >= v (v finite, >= 0). */
static float mrgi_round_up(double v)
{
  if (v >= (double)FLT_MAX)
  {
    return FLT_MAX;
  }
  float f = (float)v;
  if ((double)f < v)
  {
    f = nextafterf(f, FLT_MAX);
  }
  return f;
}

/* R_P and Dmax_P of a block whose representative is texel `best` (section 3). */
static void mrgi_vpl_tree_extent(const mrgi_rsm* rsm, const mrgi_rsm_view_camera* camera,
                                 int32_t view, int32_t x0, int32_t x1, int32_t y0, int32_t y1,
                                 int64_t best, mrgi_vpl* node)
{
  const int64_t size = rsm->size;
  const float* rep = rsm->position + 4 * best;
  double radius2 = 0.0;
  double depth = 0.0;
  const int perspective = !camera->projection.parallel;
  for (int32_t y = y0; y < y1; ++y)
  {
    for (int32_t x = x0; x < x1; ++x)
    {
      const int64_t index = ((int64_t)view * size + y) * size + x;
      if (!mrgi_rsm_texel_usable(rsm, index))
      {
        continue;
      }
      const float* p = rsm->position + 4 * index;
      const double dx = (double)p[0] - rep[0];
      const double dy = (double)p[1] - rep[1];
      const double dz = (double)p[2] - rep[2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      radius2 = d2 > radius2 ? d2 : radius2;
      double v[3];
      mrgi_transform(camera->world_to_view, p, 1.0, v);
      const double distance = perspective ? sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) : -v[2];
      depth = distance > depth ? distance : depth;
    }
  }
  node->pad0 = mrgi_round_up(sqrt(radius2));
  node->pad1 = mrgi_round_up(depth);
}

mrgi_status mrgi_vpl_tree_build(const mrgi_rsm* rsm, const mrgi_rsm_view_camera* cameras,
                                mrgi_vpl_tree* out, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VPL tree output is NULL");
  }
  memset(out, 0, sizeof(*out));
  mrgi_status status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!cameras)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "RSM view cameras are NULL");
  }
  for (int32_t v = 0; v < rsm->view_count; ++v)
  {
    status = mrgi_rsm_view_camera_check(cameras + v, err);
    if (status != MRGI_OK)
    {
      return status;
    }
  }
  mrgi_vpl_tree tree;
  memset(&tree, 0, sizeof(tree));
  tree.rsm_size = rsm->size;
  tree.side = mrgi_vpl_tree_side(rsm->size);
  tree.view_count = rsm->view_count;
  status = mrgi_multires_layout_init(&tree.layout, tree.side, tree.side, MRGI_VPL_TREE_ROOT_SIDE,
                                     err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const int32_t levels = tree.layout.level_count;
  int64_t first = 0;
  for (int32_t level = levels - 1; level >= 0; --level)
  {
    tree.level_first[level] = first;
    const int64_t w = tree.layout.level_width[level];
    first += (int64_t)tree.view_count * w * w;
  }
  tree.node_count = first;
  tree.nodes = (mrgi_vpl*)calloc((size_t)tree.node_count, sizeof(mrgi_vpl));
  tree.sums = (double*)calloc(4 * (size_t)tree.node_count, sizeof(double));
  if (!tree.nodes || !tree.sums)
  {
    mrgi_vpl_tree_destroy(&tree);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "cannot allocate a VPL tree of %lld nodes", (long long)tree.node_count);
  }
  const int32_t size = rsm->size;
  for (int32_t level = 0; level < levels; ++level)
  {
    const int32_t w = tree.layout.level_width[level];
    const int32_t span = tree.side / w; /* 2^level texels per node side */
    int64_t usable = 0;
    int64_t rejected = 0;
    for (int32_t view = 0; view < tree.view_count; ++view)
    {
      for (int32_t y = 0; y < w; ++y)
      {
        const int32_t y0 = y * span;
        const int32_t y1 = y0 + span < size ? y0 + span : size;
        for (int32_t x = 0; x < w; ++x)
        {
          const int64_t index = mrgi_vpl_tree_index(&tree, level, view, x, y);
          const int32_t x0 = x * span;
          const int32_t x1 = x0 + span < size ? x0 + span : size;
          if (x0 >= size || y0 >= size)
          {
            continue; /* all padding: stays zero */
          }
          mrgi_vpl* node = tree.nodes + index;
          const int64_t best = mrgi_vpl_from_rsm_block(rsm, view, x0, x1, y0, y1, node,
                                                       tree.sums + 4 * index, &usable, &rejected);
          if (best >= 0)
          {
            ++tree.nonempty_node_count;
            mrgi_vpl_tree_extent(rsm, cameras + view, view, x0, x1, y0, y1, best, node);
          }
        }
      }
    }
    if (level == 0)
    {
      tree.usable_texel_count = usable;
      tree.rejected_texel_count = rejected;
    }
  }
  *out = tree;
  return MRGI_OK;
}
