#include "mrgi_vpl_clusters.h"

#include "mrgi_multires.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void mrgi_vpl_cluster_params_default(mrgi_vpl_cluster_params* params)
{
  if (!params)
  {
    return;
  }
  params->depth_threshold = MRGI_MULTIRES_DEFAULT_DEPTH_THRESHOLD;
  params->normal_threshold = MRGI_MULTIRES_DEFAULT_NORMAL_THRESHOLD;
  params->finest_level = MRGI_VPL_CLUSTER_FINEST_AUTO;
  params->max_count = MRGI_VPL_CLUSTER_MAX;
}

int32_t mrgi_vpl_cluster_finest_level(const mrgi_vpl_tree* tree, int32_t requested)
{
  if (!tree || tree->layout.level_count < 1)
  {
    return -1;
  }
  const int32_t levels = tree->layout.level_count;
  if (requested == MRGI_VPL_CLUSTER_FINEST_AUTO)
  {
    int32_t level = 0;
    while (level + 1 < levels &&
           tree->layout.level_width[level] > MRGI_VPL_CLUSTER_DEFAULT_FINEST_SIDE)
    {
      ++level;
    }
    return level;
  }
  return requested >= 0 && requested < levels ? requested : -1;
}

/* Checks shared by the flag and selection steps. */
static mrgi_status mrgi_vpl_cluster_check(const mrgi_vpl_tree* tree,
                                          const mrgi_vpl_cluster_params* params,
                                          int32_t* finest_level, mrgi_error* err)
{
  if (!tree || !params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "cluster %s is NULL",
                          !tree ? "VPL tree" : "parameters");
  }
  if (!tree->nodes || !tree->sums ||
      mrgi_multires_layout_check(&tree->layout, NULL) != MRGI_OK)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree was not built by mrgi_vpl_tree_build()");
  }
  *finest_level = mrgi_vpl_cluster_finest_level(tree, params->finest_level);
  if (*finest_level < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "cluster finest level %d is outside 0..%d (or %d for automatic)",
                          params->finest_level, tree->layout.level_count - 1,
                          MRGI_VPL_CLUSTER_FINEST_AUTO);
  }
  if (isnan(params->depth_threshold) || params->depth_threshold < 0.0 ||
      isnan(params->normal_threshold) || params->normal_threshold < 0.0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "cluster %s threshold %g must be >= 0 (+inf turns it off)",
                          (isnan(params->depth_threshold) || params->depth_threshold < 0.0)
                            ? "depth"
                            : "normal",
                          (isnan(params->depth_threshold) || params->depth_threshold < 0.0)
                            ? params->depth_threshold
                            : params->normal_threshold);
  }
  return MRGI_OK;
}

mrgi_status mrgi_vpl_cluster_flags(const mrgi_rsm* rsm, const mrgi_rsm_view_camera* cameras,
                                   const mrgi_vpl_tree* tree,
                                   const mrgi_vpl_cluster_params* params, uint8_t* flags,
                                   size_t flags_size, mrgi_error* err)
{
  int32_t finest = 0;
  mrgi_status status = mrgi_vpl_cluster_check(tree, params, &finest, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_rsm_validate(rsm, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (rsm->size != tree->rsm_size || rsm->view_count != tree->view_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL tree was built for %d view(s) of %d texels, the RSM has %d of %d",
                          tree->view_count, tree->rsm_size, rsm->view_count, rsm->size);
  }
  if (!cameras || !flags)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "cluster %s is NULL",
                          !cameras ? "camera array" : "flags array");
  }
  const size_t per_view = (size_t)mrgi_multires_texel_count(&tree->layout);
  if (flags_size < per_view * (size_t)tree->view_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "cluster flags hold %zu bytes but %d view(s) need %zu", flags_size,
                          tree->view_count, per_view * (size_t)tree->view_count);
  }
  const size_t floats = 4 * (size_t)tree->side * (size_t)tree->side;
  float* position = (float*)malloc(sizeof(float) * floats);
  float* normal = (float*)malloc(sizeof(float) * floats);
  if (!position || !normal)
  {
    free(position);
    free(normal);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "cannot allocate light-space receivers of %dx%d texels", tree->side,
                          tree->side);
  }
  const mrgi_multires_params multires = { params->depth_threshold, params->normal_threshold,
                                          finest, 0 };
  for (int32_t view = 0; view < tree->view_count && status == MRGI_OK; ++view)
  {
    mrgi_gather_receivers receivers;
    status = mrgi_rsm_view_receivers(rsm, view, cameras + view, position, normal, floats,
                                     &receivers, err);
    float coefficients[2] = { 0.0f, 0.0f };
    if (status == MRGI_OK)
    {
      status = mrgi_multires_pixel_size_coefficients(&cameras[view].projection, rsm->size,
                                                     coefficients, err);
    }
    mrgi_multires_mipmap mipmap;
    memset(&mipmap, 0, sizeof(mipmap));
    if (status == MRGI_OK)
    {
      status = mrgi_multires_mipmap_build(&tree->layout, &receivers, coefficients, &mipmap, err);
    }
    if (status == MRGI_OK)
    {
      status = mrgi_multires_flags_compute(&mipmap, &multires, flags + per_view * (size_t)view,
                                           per_view, err);
    }
    mrgi_multires_mipmap_destroy(&mipmap);
  }
  free(position);
  free(normal);
  return status;
}

mrgi_status mrgi_vpl_clusters_from_flags(const mrgi_vpl_tree* tree, const uint8_t* flags,
                                         size_t flags_size, const mrgi_vpl_cluster_params* params,
                                         uint8_t* selected, size_t selected_size, mrgi_vpl* vpls,
                                         int32_t capacity, mrgi_vpl_cluster_info* out_info,
                                         mrgi_error* err)
{
  int32_t finest = 0;
  mrgi_status status = mrgi_vpl_cluster_check(tree, params, &finest, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!flags || !selected || !vpls)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "cluster %s is NULL",
                          !flags ? "flags array" : (!selected ? "selection array" : "VPL array"));
  }
  const mrgi_multires_layout* layout = &tree->layout;
  const size_t per_view = (size_t)mrgi_multires_texel_count(layout);
  if (flags_size < per_view * (size_t)tree->view_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "cluster flags hold %zu bytes but %d view(s) need %zu", flags_size,
                          tree->view_count, per_view * (size_t)tree->view_count);
  }
  if (selected_size < (size_t)tree->node_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "cluster selection holds %zu bytes but the tree has %lld nodes",
                          selected_size, (long long)tree->node_count);
  }
  const int32_t coarsest = layout->level_count - 1;
  const int32_t root_side = layout->level_width[coarsest];
  const int64_t roots = (int64_t)tree->view_count * root_side * root_side;
  if (params->max_count < roots || params->max_count > MRGI_VPL_CLUSTER_MAX)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "cluster cap %d is outside %lld..%d (%d view(s) of %dx%d roots)",
                          params->max_count, (long long)roots, MRGI_VPL_CLUSTER_MAX,
                          tree->view_count, root_side, root_side);
  }
  if (capacity < params->max_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VPL array holds %d records but the cluster cap is %d", capacity,
                          params->max_count);
  }

  /* Iterative refinement with the cap (section 2). */
  memset(selected, 0, (size_t)tree->node_count);
  memset(selected + tree->level_first[coarsest], 1, (size_t)roots);
  int64_t count = roots;
  mrgi_vpl_cluster_info info;
  memset(&info, 0, sizeof(info));
  info.finest_level = finest;
  for (int32_t level = coarsest; level > finest; --level)
  {
    const int32_t w = layout->level_width[level];
    for (int32_t view = 0; view < tree->view_count; ++view)
    {
      const uint8_t* view_flags = flags + per_view * (size_t)view;
      for (int32_t y = 0; y < w; ++y)
      {
        for (int32_t x = 0; x < w; ++x)
        {
          const int64_t node = mrgi_vpl_tree_index(tree, level, view, x, y);
          if (!selected[node] ||
              !(view_flags[mrgi_multires_index(layout, level, x, y)] & MRGI_MULTIRES_FLAG_REFINE))
          {
            continue;
          }
          int64_t children = 0;
          for (int32_t b = 0; b < 2; ++b)
          {
            for (int32_t a = 0; a < 2; ++a)
            {
              children += (view_flags[mrgi_multires_index(layout, level - 1, 2 * x + a,
                                                          2 * y + b)] &
                           MRGI_MULTIRES_FLAG_NONEMPTY) != 0;
            }
          }
          if (count - 1 + children > params->max_count)
          {
            ++info.capped;
            continue;
          }
          selected[node] = 0;
          for (int32_t b = 0; b < 2; ++b)
          {
            for (int32_t a = 0; a < 2; ++a)
            {
              if (view_flags[mrgi_multires_index(layout, level - 1, 2 * x + a, 2 * y + b)] &
                  MRGI_MULTIRES_FLAG_NONEMPTY)
              {
                selected[mrgi_vpl_tree_index(tree, level - 1, view, 2 * x + a, 2 * y + b)] = 1;
              }
            }
          }
          count += children - 1;
        }
      }
    }
  }

  /* Output in record order: coarse levels first. */
  int32_t written = 0;
  for (int32_t level = coarsest; level >= 0; --level)
  {
    const int64_t first = tree->level_first[level];
    const int64_t end = level == 0 ? tree->node_count : tree->level_first[level - 1];
    for (int64_t node = first; node < end; ++node)
    {
      if (!selected[node])
      {
        continue;
      }
      mrgi_vpl* vpl = vpls + written++;
      *vpl = tree->nodes[node];
      vpl->pad0 = 0.0f;
      vpl->pad1 = 0.0f;
      ++info.per_level[level];
      info.empty_vpl_count += vpl->flux[0] == 0.0f && vpl->flux[1] == 0.0f &&
                              vpl->flux[2] == 0.0f;
    }
  }
  info.vpl_count = written;
  info.usable_texel_count = tree->usable_texel_count;
  info.rejected_texel_count = tree->rejected_texel_count;
  if (out_info)
  {
    *out_info = info;
  }
  return MRGI_OK;
}

mrgi_status mrgi_vpl_select_clusters(const mrgi_rsm* rsm, const mrgi_rsm_view_camera* cameras,
                                     const mrgi_vpl_cluster_params* params, mrgi_vpl* vpls,
                                     int32_t capacity, mrgi_vpl_cluster_info* out_info,
                                     mrgi_error* err)
{
  mrgi_vpl_tree tree;
  mrgi_status status = mrgi_vpl_tree_build(rsm, cameras, &tree, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t flags_size =
    (size_t)mrgi_multires_texel_count(&tree.layout) * (size_t)tree.view_count;
  uint8_t* flags = (uint8_t*)malloc(flags_size);
  uint8_t* selected = (uint8_t*)malloc((size_t)tree.node_count);
  if (!flags || !selected)
  {
    status = mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                            "cannot allocate cluster flags for %lld nodes",
                            (long long)tree.node_count);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_vpl_cluster_flags(rsm, cameras, &tree, params, flags, flags_size, err);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_vpl_clusters_from_flags(&tree, flags, flags_size, params, selected,
                                          (size_t)tree.node_count, vpls, capacity, out_info,
                                          err);
  }
  free(flags);
  free(selected);
  mrgi_vpl_tree_destroy(&tree);
  return status;
}
