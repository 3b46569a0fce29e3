/* The HISR VPL-tree gather (NSW09 3.5.1), the C twin of the GPU tree gather.
 * Contract, bound and traversal order: mrgi_vpl_tree_gather.h. The per-VPL
 * term and its guards are mrgi_gather_full()'s own (mrgi_gather_term.h). */
#include "mrgi_vpl_tree_gather.h"

#include "mrgi_gather_term.h"

#include <math.h>
#include <string.h>

/* Levels below the roots (L) of a built tree; -1 when the tree is not usable. */
static int32_t mrgi_vpl_tree_gather_levels(const mrgi_vpl_tree* tree)
{
  if (!tree || !tree->nodes || tree->node_count <= 0 || tree->layout.level_count < 1 ||
      tree->layout.level_count > MRGI_MULTIRES_MAX_LEVELS)
  {
    return -1;
  }
  return tree->layout.level_count - 1;
}

/* N_sub = (4^(L+1) - 1) / 3: the nodes of one root's subtree. */
static int64_t mrgi_vpl_tree_subtree_nodes(int32_t levels)
{
  int64_t nodes = 0;
  int64_t per_level = 1;
  for (int32_t i = 0; i <= levels; ++i)
  {
    nodes += per_level;
    per_level *= 4;
  }
  return nodes;
}

int32_t mrgi_vpl_tree_roots_per_batch(const mrgi_vpl_tree* tree)
{
  const int32_t levels = mrgi_vpl_tree_gather_levels(tree);
  if (levels < 0)
  {
    return 0;
  }
  const int64_t k = MRGI_VPL_TREE_MAX_LOOP_ITERATIONS / mrgi_vpl_tree_subtree_nodes(levels);
  return (int32_t)k; /* 0 when one root's subtree alone exceeds the limit (S > 2048) */
}

int32_t mrgi_vpl_tree_root_count(const mrgi_vpl_tree* tree)
{
  const int32_t levels = mrgi_vpl_tree_gather_levels(tree);
  if (levels < 0)
  {
    return 0;
  }
  const int32_t w = tree->layout.level_width[levels];
  return tree->view_count * w * w;
}

mrgi_status mrgi_vpl_tree_texture_size(const mrgi_vpl_tree* tree, int32_t* out_width,
                                       int32_t* out_height, mrgi_error* err)
{
  if (!out_width || !out_height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "tree texture size output is NULL");
  }
  *out_width = 0;
  *out_height = 0;
  if (mrgi_vpl_tree_gather_levels(tree) < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree is %s", !tree ? "NULL" : "not built (no nodes)");
  }
  const int64_t rows =
    (tree->node_count + MRGI_VPL_TREE_RECORDS_PER_ROW - 1) / MRGI_VPL_TREE_RECORDS_PER_ROW;
  if (rows > INT32_MAX)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree of %lld nodes needs %lld texture rows",
                          (long long)tree->node_count, (long long)rows);
  }
  *out_width = MRGI_VPL_TREE_RECORDS_PER_ROW * MRGI_VPL_TEXELS;
  *out_height = (int32_t)rows;
  return MRGI_OK;
}

/* B_P (header, section 1) for a representative at `c`, area A_P, radius
 * R_P and a receiver at `x`, both in the same rigid space. A not-a-number
 * distance gives d_min = 0, B_P = 1: refine (conservative). */
static double mrgi_vpl_tree_bound(const double c[3], double area, double radius,
                                  const double x[3])
{
  if (!(area > 0.0))
  {
    return 0.0; /* A_P = 0: no area, nothing to bound (header, section 1) */
  }
  const double d[3] = { c[0] - x[0], c[1] - x[1], c[2] - x[2] };
  double d_min = sqrt(mrgi_gather_dot3(d, d)) - radius;
  if (!(d_min > 0.0))
  {
    d_min = 0.0; /* inside the bounding sphere */
  }
  return area / (MRGI_PI * d_min * d_min + area);
}

double mrgi_vpl_tree_refinement_bound(const mrgi_vpl* node, const double receiver[3])
{
  if (!node || !receiver)
  {
    return 1.0; /* conservative: refine */
  }
  const double c[3] = { node->position[0], node->position[1], node->position[2] };
  return mrgi_vpl_tree_bound(c, node->area, node->pad0, receiver);
}

/* One stack entry: a node of `level` at (x, y) of the current root's view. */
typedef struct mrgi_vpl_tree_stack_entry
{
  int32_t level;
  int32_t x;
  int32_t y;
} mrgi_vpl_tree_stack_entry;

/* What one receiver's traversal produced. */
typedef struct mrgi_vpl_tree_receiver_result
{
  double irradiance[3];
  int64_t vpls;
  int64_t visited;
  int32_t max_depth;
} mrgi_vpl_tree_receiver_result;

/* The traversal of header section 2 for one well-formed receiver (position
 * and unit normal in receiver space). `stack` is the caller's
 * MRGI_VPL_TREE_STACK_SIZE entries: no allocation per receiver. */
static void mrgi_vpl_tree_gather_receiver(const mrgi_vpl_tree* tree, double threshold,
                                          const float* world_to_receiver, const double x[3],
                                          const double n[3], const float gbuffer_normal[3],
                                          const mrgi_gather_visibility* visibility,
                                          mrgi_vpl_tree_stack_entry* stack,
                                          mrgi_vpl_tree_receiver_result* result)
{
  memset(result, 0, sizeof(*result));
  float receiver_world[3] = { 0.0f, 0.0f, 0.0f };
  if (visibility->mode == MRGI_GATHER_VISIBILITY_ISM)
  {
    mrgi_gather_receiver_to_world(world_to_receiver, x, receiver_world);
  }
  const int32_t root_level = tree->layout.level_count - 1;
  const int32_t w_root = tree->layout.level_width[root_level];
  for (int32_t view = 0; view < tree->view_count; ++view)
  {
    for (int32_t ry = 0; ry < w_root; ++ry)
    {
      for (int32_t rx = 0; rx < w_root; ++rx)
      {
        /* Section 4: root r's ISM tile and record serve its whole subtree;
         * V is computed at the first contributing node (-1: not yet). */
        const int64_t root = mrgi_vpl_tree_index(tree, root_level, view, rx, ry);
        double root_visibility = -1.0;
        int32_t depth = 0;
        stack[depth++] = (mrgi_vpl_tree_stack_entry){ root_level, rx, ry };
        result->max_depth = depth > result->max_depth ? depth : result->max_depth;
        while (depth > 0)
        {
          const mrgi_vpl_tree_stack_entry entry = stack[--depth];
          ++result->visited;
          const mrgi_vpl* node =
            tree->nodes + mrgi_vpl_tree_index(tree, entry.level, view, entry.x, entry.y);
          mrgi_gather_vpl vpl;
          /* 1. zero flux (empty, or all descendants zero): skip. A malformed
           * record (never built by mrgi_vpl_tree_build) is skipped too. */
          if (mrgi_gather_vpl_prepare(node, world_to_receiver, &vpl) != MRGI_GATHER_VPL_USABLE)
          {
            continue;
          }
          /* 2. exact cull: the whole bounding sphere behind the receiver's plane. */
          const double radius = node->pad0;
          const double d[3] = { vpl.position[0] - x[0], vpl.position[1] - x[1],
                                vpl.position[2] - x[2] };
          if (mrgi_gather_dot3(n, d) + radius <= 0.0)
          {
            continue;
          }
          /* 3. refine where the form-factor bound exceeds tau (NSW09 eq. 7-8). */
          if (entry.level > 0 && mrgi_vpl_tree_bound(vpl.position, vpl.area, radius, x) > threshold)
          {
            const int32_t level = entry.level - 1;
            const int32_t cx = 2 * entry.x;
            const int32_t cy = 2 * entry.y;
            /* Pushed so that they pop in scan order, (2x, 2y) first. The
             * stack bound 3 L + 1 <= MRGI_VPL_TREE_STACK_SIZE was checked. */
            stack[depth++] = (mrgi_vpl_tree_stack_entry){ level, cx + 1, cy + 1 };
            stack[depth++] = (mrgi_vpl_tree_stack_entry){ level, cx, cy + 1 };
            stack[depth++] = (mrgi_vpl_tree_stack_entry){ level, cx + 1, cy };
            stack[depth++] = (mrgi_vpl_tree_stack_entry){ level, cx, cy };
            result->max_depth = depth > result->max_depth ? depth : result->max_depth;
            continue;
          }
          /* 4. the node as one VPL: mrgi_gather_full()'s term. */
          double transfer = mrgi_gather_transfer(x, n, &vpl);
          if (transfer > 0.0)
          {
            if (visibility->mode == MRGI_GATHER_VISIBILITY_ISM)
            {
              if (root_visibility < 0.0)
              {
                root_visibility = mrgi_gather_ism_weight(visibility, (int32_t)root,
                                                         tree->nodes + root, receiver_world);
              }
              transfer *= root_visibility;
            }
            else if (visibility->mode == MRGI_GATHER_VISIBILITY_VOXELS)
            {
              transfer *= mrgi_gather_voxel_weight(visibility->voxels, x, gbuffer_normal, &vpl);
            }
            result->irradiance[0] += vpl.flux[0] * transfer;
            result->irradiance[1] += vpl.flux[1] * transfer;
            result->irradiance[2] += vpl.flux[2] * transfer;
          }
          ++result->vpls;
        }
      }
    }
  }
}

static void mrgi_vpl_tree_gather_clear(mrgi_image* image)
{
  if (image)
  {
    memset(image, 0, sizeof(*image));
  }
}

/* Every check of the header's Errors section except the image sizes. */
static mrgi_status mrgi_vpl_tree_gather_check(const mrgi_gather_receivers* receivers,
                                              const mrgi_vpl_tree* tree, double threshold,
                                              const float* world_to_receiver, mrgi_error* err)
{
  mrgi_status status = mrgi_gather_receivers_check(receivers, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!tree)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VPL tree is NULL");
  }
  const int32_t levels = mrgi_vpl_tree_gather_levels(tree);
  if (levels < 0 || tree->view_count < 1 || tree->view_count > MRGI_RSM_MAX_VIEWS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree is not built (no nodes, or bad levels or views); build it "
                          "with mrgi_vpl_tree_build()");
  }
  if (tree->rsm_size < 1 || tree->rsm_size > MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree was built from a %dx%d RSM; the tree gather takes at most "
                          "%dx%d (MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE)",
                          tree->rsm_size, tree->rsm_size, MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE,
                          MRGI_VPL_TREE_GATHER_MAX_RSM_SIZE);
  }
  /* A tree that mrgi_vpl_tree_build() made: its layout and record ranges
   * agree, so every index the traversal forms is inside `nodes`. */
  int64_t first = 0;
  int consistent = mrgi_multires_layout_check(&tree->layout, NULL) == MRGI_OK &&
                   tree->side == mrgi_vpl_tree_side(tree->rsm_size) &&
                   tree->layout.width == tree->side && tree->layout.height == tree->side &&
                   tree->layout.coarsest_side == MRGI_VPL_TREE_ROOT_SIDE;
  for (int32_t level = levels; consistent && level >= 0; --level)
  {
    const int64_t w = tree->layout.level_width[level];
    consistent = tree->level_first[level] == first;
    first += (int64_t)tree->view_count * w * w;
  }
  if (!consistent || first != tree->node_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree's layout, levels or node count do not match its %dx%d RSM; "
                          "build it with mrgi_vpl_tree_build()",
                          tree->rsm_size, tree->rsm_size);
  }
  if (3 * levels + 1 > MRGI_VPL_TREE_STACK_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree has %d levels below its roots; its traversal needs %d stack "
                          "entries but MRGI_VPL_TREE_STACK_SIZE is %d",
                          levels, 3 * levels + 1, MRGI_VPL_TREE_STACK_SIZE);
  }
  if (isnan(threshold) || threshold < 0.0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "tree threshold tau is %g; it must be >= 0 (+inf means no refinement)",
                          threshold);
  }
  if (world_to_receiver)
  {
    return mrgi_gather_check_transform(world_to_receiver, err);
  }
  return MRGI_OK;
}

mrgi_status mrgi_vpl_tree_gather(const mrgi_gather_receivers* receivers, const mrgi_vpl_tree* tree,
                                 double threshold, const float* world_to_receiver,
                                 mrgi_image* out_irradiance, mrgi_image* out_vpls_per_pixel,
                                 mrgi_vpl_tree_gather_info* out_info, mrgi_error* err)
{
  return mrgi_vpl_tree_gather_visibility(receivers, tree, threshold, world_to_receiver, NULL,
                                         out_irradiance, out_vpls_per_pixel, out_info, err);
}

mrgi_status mrgi_vpl_tree_gather_visibility(const mrgi_gather_receivers* receivers,
                                            const mrgi_vpl_tree* tree, double threshold,
                                            const float* world_to_receiver,
                                            const mrgi_gather_visibility* visibility,
                                            mrgi_image* out_irradiance,
                                            mrgi_image* out_vpls_per_pixel,
                                            mrgi_vpl_tree_gather_info* out_info, mrgi_error* err)
{
  static const mrgi_gather_visibility none = { MRGI_GATHER_VISIBILITY_NONE, NULL, NULL,
                                               { 0.0f, 0.0f, 0, 0.0f }, NULL };
  mrgi_vpl_tree_gather_clear(out_irradiance);
  mrgi_vpl_tree_gather_clear(out_vpls_per_pixel);
  if (out_info)
  {
    memset(out_info, 0, sizeof(*out_info));
  }
  if (!out_irradiance)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output irradiance image is NULL");
  }
  mrgi_status status = mrgi_vpl_tree_gather_check(receivers, tree, threshold, world_to_receiver,
                                                  err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_gather_visibility_check(visibility, mrgi_vpl_tree_root_count(tree), err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!visibility)
  {
    visibility = &none;
  }
  status = mrgi_image_create(out_irradiance, receivers->width, receivers->height, 3, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "irradiance image: ");
    return status;
  }
  if (out_vpls_per_pixel)
  {
    status = mrgi_image_create(out_vpls_per_pixel, receivers->width, receivers->height, 1, err);
    if (status != MRGI_OK)
    {
      mrgi_image_destroy(out_irradiance);
      mrgi_error_prefix(err, "VPLs-per-pixel image: ");
      return status;
    }
  }

  mrgi_vpl_tree_stack_entry stack[MRGI_VPL_TREE_STACK_SIZE];
  mrgi_vpl_tree_gather_info info;
  memset(&info, 0, sizeof(info));
  const size_t pixel_count = (size_t)receivers->width * (size_t)receivers->height;
  for (size_t p = 0; p < pixel_count; ++p)
  {
    double x[3];
    double n[3];
    const int receiver = mrgi_gather_receiver_prepare(receivers, p, x, n);
    if (receiver == 0)
    {
      ++info.receivers_invalid;
      continue; /* the images are zero-filled */
    }
    if (receiver < 0)
    {
      ++info.receivers_malformed;
      continue;
    }
    ++info.receivers_gathered;
    mrgi_vpl_tree_receiver_result result;
    mrgi_vpl_tree_gather_receiver(tree, threshold, world_to_receiver, x, n,
                                  receivers->normal + 4 * p, visibility, stack, &result);
    float* out = out_irradiance->pixels + 3 * p; /* same (bottom-up) order as the input */
    out[0] = mrgi_gather_store(result.irradiance[0]);
    out[1] = mrgi_gather_store(result.irradiance[1]);
    out[2] = mrgi_gather_store(result.irradiance[2]);
    if (out_vpls_per_pixel)
    {
      out_vpls_per_pixel->pixels[p] = (float)result.vpls;
    }
    info.vpls_used += result.vpls;
    info.nodes_visited += result.visited;
    if (result.vpls > info.max_vpls_per_pixel)
    {
      info.max_vpls_per_pixel = (int32_t)result.vpls;
    }
    if (result.max_depth > info.max_stack_depth)
    {
      info.max_stack_depth = result.max_depth;
    }
  }
  info.mean_vpls_per_pixel =
    info.receivers_gathered > 0 ? (double)info.vpls_used / (double)info.receivers_gathered : 0.0;
  if (out_info)
  {
    *out_info = info;
  }
  return MRGI_OK;
}
