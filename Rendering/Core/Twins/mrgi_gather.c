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

/* E_i of one receiver (file comment of the header), accumulated in double. */
static void mrgi_gather_receiver(const double receiver_position[3],
                                 const double receiver_normal[3], const mrgi_gather_vpl* vpls,
                                 int32_t vpl_count, double irradiance[3])
{
  double sum[3] = { 0.0, 0.0, 0.0 };
  for (int32_t j = 0; j < vpl_count; ++j)
  {
    const mrgi_gather_vpl* vpl = vpls + j;
    const double transfer = mrgi_gather_transfer(receiver_position, receiver_normal, vpl);
    if (transfer > 0.0)
    {
      sum[0] += vpl->flux[0] * transfer;
      sum[1] += vpl->flux[1] * transfer;
      sum[2] += vpl->flux[2] * transfer;
    }
  }
  irradiance[0] = sum[0];
  irradiance[1] = sum[1];
  irradiance[2] = sum[2];
}

mrgi_status mrgi_gather_full(const mrgi_gather_receivers* receivers, const mrgi_vpl* vpls,
                             int32_t vpl_count, const float* world_to_receiver,
                             mrgi_image* out_irradiance, mrgi_gather_info* out_info,
                             mrgi_error* err)
{
  if (!out_irradiance)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output irradiance image is NULL");
  }
  out_irradiance->width = 0;
  out_irradiance->height = 0;
  out_irradiance->channels = 0;
  out_irradiance->pixels = NULL;
  if (!receivers)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "receivers pointer is NULL");
  }
  if (!receivers->position || !receivers->normal)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "receiver %s array is NULL",
                          !receivers->position ? "position" : "normal");
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
  mrgi_status status = MRGI_OK;
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
  if (!prepared)
  {
    mrgi_image_destroy(out_irradiance);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "cannot allocate %d prepared VPLs",
                          vpl_count);
  }

  mrgi_gather_info info = { 0, 0, 0, 0, 0, 0 };
  int32_t used = 0;
  for (int32_t j = 0; j < vpl_count; ++j)
  {
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
    mrgi_gather_receiver(receiver_position, receiver_normal, prepared, used, irradiance);
    out[0] = mrgi_gather_store(irradiance[0]);
    out[1] = mrgi_gather_store(irradiance[1]);
    out[2] = mrgi_gather_store(irradiance[2]);
  }
  free(prepared);
  if (out_info)
  {
    *out_info = info;
  }
  return MRGI_OK;
}
