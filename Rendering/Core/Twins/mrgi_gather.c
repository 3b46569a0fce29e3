#include "mrgi_gather.h"

#include "mrgi_gather_term.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

mrgi_status mrgi_gather_check_transform(const float world_to_receiver[16], mrgi_error* err)
{
  if (!world_to_receiver)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "world->receiver matrix is NULL");
  }
  const float* m = world_to_receiver;
  for (int k = 0; k < 16; ++k)
  {
    if (!isfinite(m[k]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "world->receiver matrix element %d (column-major) is not finite", k);
    }
  }
  if (m[3] != 0.0f || m[7] != 0.0f || m[11] != 0.0f || m[15] != 1.0f)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "world->receiver matrix has last row (%g, %g, %g, %g), not (0, 0, 0, "
                          "1): it must be rigid, not projective",
                          (double)m[3], (double)m[7], (double)m[11], (double)m[15]);
  }
  /* Columns of R at m[0..2], m[4..6], m[8..10]: R^T R must be I. */
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      const double dot = (double)m[4 * a] * m[4 * b] + (double)m[4 * a + 1] * m[4 * b + 1] +
                         (double)m[4 * a + 2] * m[4 * b + 2];
      const double expected = a == b ? 1.0 : 0.0;
      if (fabs(dot - expected) > MRGI_GATHER_RIGID_TOLERANCE)
      {
        return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                              "world->receiver matrix is not rigid: columns %d and %d of its "
                              "3x3 block have dot product %g instead of %g (scales and shears "
                              "would change VPL areas)",
                              a, b, dot, expected);
      }
    }
  }
  return MRGI_OK;
}

/* Bring VPL `in` into receiver space (mrgi_gather_term.h).
 * Returns 1 when usable, 0 when skipped; counts the reason in `info`. */
static int mrgi_gather_prepare_vpl(const mrgi_vpl* in, const float* m, mrgi_gather_vpl* out,
                                   mrgi_gather_info* info)
{
  switch (mrgi_gather_vpl_prepare(in, m, out))
  {
    case MRGI_GATHER_VPL_USABLE:
      ++info->vpls_used;
      return 1;
    case MRGI_GATHER_VPL_ZERO_FLUX:
      ++info->vpls_zero_flux;
      return 0;
    case MRGI_GATHER_VPL_MALFORMED:
    default:
      ++info->vpls_malformed;
      return 0;
  }
}

/* E_i of one receiver (file comment of the header), accumulated in double;
 * each term > 0 weighted by the visibility (header, "Visibility"). `source`
 * maps prepared VPL k to its index in the caller's array (its ISM tile). */
static void mrgi_gather_receiver(const double receiver_position[3],
                                 const double receiver_normal[3],
                                 const float receiver_gbuffer_normal[3],
                                 const mrgi_gather_vpl* vpls, const int32_t* source,
                                 int32_t vpl_count, const mrgi_vpl* world_vpls,
                                 const float* world_to_receiver,
                                 const mrgi_gather_visibility* visibility, double irradiance[3])
{
  double sum[3] = { 0.0, 0.0, 0.0 };
  float receiver_world[3] = { 0.0f, 0.0f, 0.0f };
  if (visibility->mode == MRGI_GATHER_VISIBILITY_ISM)
  {
    mrgi_gather_receiver_to_world(world_to_receiver, receiver_position, receiver_world);
  }
  for (int32_t j = 0; j < vpl_count; ++j)
  {
    const mrgi_gather_vpl* vpl = vpls + j;
    double transfer = mrgi_gather_transfer(receiver_position, receiver_normal, vpl);
    if (transfer > 0.0)
    {
      if (visibility->mode == MRGI_GATHER_VISIBILITY_ISM)
      {
        transfer *= mrgi_gather_ism_weight(visibility, source[j], world_vpls + source[j],
                                           receiver_world);
      }
      else if (visibility->mode == MRGI_GATHER_VISIBILITY_VOXELS)
      {
        transfer *= mrgi_gather_voxel_weight(visibility->voxels, receiver_position,
                                             receiver_gbuffer_normal, vpl);
      }
      sum[0] += vpl->flux[0] * transfer;
      sum[1] += vpl->flux[1] * transfer;
      sum[2] += vpl->flux[2] * transfer;
    }
  }
  irradiance[0] = sum[0];
  irradiance[1] = sum[1];
  irradiance[2] = sum[2];
}

mrgi_status mrgi_gather_visibility_check(const mrgi_gather_visibility* visibility,
                                         int32_t tile_count, mrgi_error* err)
{
  if (!visibility || visibility->mode == MRGI_GATHER_VISIBILITY_NONE)
  {
    return MRGI_OK;
  }
  if (visibility->mode == MRGI_GATHER_VISIBILITY_ISM)
  {
    if (!visibility->ism_layout || !visibility->ism_depth)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "ISM visibility: the atlas %s is missing",
                            !visibility->ism_layout ? "layout" : "depth array");
    }
    const mrgi_ism_atlas_layout* layout = visibility->ism_layout;
    if (layout->vpl_count != tile_count)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "ISM visibility: the atlas has %d tiles but the gather has %d VPLs "
                            "(tree: roots); rebuild the ISMs for this frame's VPLs",
                            layout->vpl_count, tile_count);
    }
    mrgi_ism_atlas_layout expected;
    if (mrgi_ism_atlas_layout_make(layout->vpl_count, layout->tile_size, &expected, err) !=
          MRGI_OK ||
        expected.width != layout->width || expected.height != layout->height ||
        expected.tiles_per_row != layout->tiles_per_row)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "ISM visibility: the atlas layout (%d tiles of %d, %dx%d) is not what "
                            "mrgi_ism_atlas_layout_make() makes",
                            layout->vpl_count, layout->tile_size, layout->width, layout->height);
    }
    mrgi_status status = mrgi_ism_lookup_params_validate(&visibility->ism_lookup, err);
    return status;
  }
  if (visibility->mode == MRGI_GATHER_VISIBILITY_VOXELS)
  {
    if (!visibility->voxels)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "voxel visibility: the voxel view is missing (not voxelized)");
    }
    mrgi_status status = mrgi_voxel_view_check(visibility->voxels, err);
    if (status != MRGI_OK)
    {
      mrgi_error_prefix(err, "voxel visibility: ");
    }
    return status;
  }
  return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                        "gather visibility mode %d is not NONE (0), ISM (1) or VOXELS (2)",
                        (int)visibility->mode);
}

mrgi_status mrgi_gather_full(const mrgi_gather_receivers* receivers, const mrgi_vpl* vpls,
                             int32_t vpl_count, const float* world_to_receiver,
                             mrgi_image* out_irradiance, mrgi_gather_info* out_info,
                             mrgi_error* err)
{
  return mrgi_gather_full_visibility(receivers, vpls, vpl_count, world_to_receiver, NULL,
                                     out_irradiance, out_info, err);
}

mrgi_status mrgi_gather_full_visibility(const mrgi_gather_receivers* receivers,
                                        const mrgi_vpl* vpls, int32_t vpl_count,
                                        const float* world_to_receiver,
                                        const mrgi_gather_visibility* visibility,
                                        mrgi_image* out_irradiance, mrgi_gather_info* out_info,
                                        mrgi_error* err)
{
  static const mrgi_gather_visibility none = { MRGI_GATHER_VISIBILITY_NONE, NULL, NULL,
                                               { 0.0f, 0.0f, 0, 0.0f }, NULL };
  if (!out_irradiance)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output irradiance image is NULL");
  }
  out_irradiance->width = 0;
  out_irradiance->height = 0;
  out_irradiance->channels = 0;
  out_irradiance->pixels = NULL;
  mrgi_status status = mrgi_gather_receivers_check(receivers, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!vpls)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VPL array is NULL");
  }
  if (vpl_count < MRGI_VPL_MIN_COUNT || vpl_count > MRGI_VPL_MAX_COUNT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VPL count %d is outside %d..%d",
                          vpl_count, MRGI_VPL_MIN_COUNT, MRGI_VPL_MAX_COUNT);
  }
  status = mrgi_gather_visibility_check(visibility, vpl_count, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!visibility)
  {
    visibility = &none;
  }
  if (world_to_receiver)
  {
    status = mrgi_gather_check_transform(world_to_receiver, err);
    if (status != MRGI_OK)
    {
      return status;
    }
  }
  status = mrgi_image_create(out_irradiance, receivers->width, receivers->height, 3, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "irradiance image: ");
    return status;
  }
  mrgi_gather_vpl* prepared = (mrgi_gather_vpl*)malloc(sizeof(mrgi_gather_vpl) * (size_t)vpl_count);
  int32_t* source = (int32_t*)malloc(sizeof(int32_t) * (size_t)vpl_count);
  if (!prepared || !source)
  {
    free(prepared);
    free(source);
    mrgi_image_destroy(out_irradiance);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "cannot allocate %d prepared VPLs",
                          vpl_count);
  }

  mrgi_gather_info info = { 0, 0, 0, 0, 0, 0 };
  int32_t used = 0;
  for (int32_t j = 0; j < vpl_count; ++j)
  {
    source[used] = j;
    used += mrgi_gather_prepare_vpl(vpls + j, world_to_receiver, prepared + used, &info);
  }

  const size_t pixel_count = (size_t)receivers->width * (size_t)receivers->height;
  for (size_t p = 0; p < pixel_count; ++p)
  {
    float* out = out_irradiance->pixels + 3 * p; /* same (bottom-up) order as the input */
    double receiver_position[3];
    double receiver_normal[3];
    const int receiver = mrgi_gather_receiver_prepare(receivers, p, receiver_position,
                                                      receiver_normal);
    if (receiver == 0)
    {
      ++info.receivers_invalid;
      continue; /* the image is zero-filled */
    }
    if (receiver < 0)
    {
      ++info.receivers_malformed;
      continue;
    }
    ++info.receivers_gathered;
    double irradiance[3];
    mrgi_gather_receiver(receiver_position, receiver_normal, receivers->normal + 4 * p, prepared,
                         source, used, vpls, world_to_receiver, visibility, irradiance);
    out[0] = mrgi_gather_store(irradiance[0]);
    out[1] = mrgi_gather_store(irradiance[1]);
    out[2] = mrgi_gather_store(irradiance[2]);
  }
  free(prepared);
  free(source);
  if (out_info)
  {
    *out_info = info;
  }
  return MRGI_OK;
}
