/**
 * @file mrgi_gather_term.h
 * @brief Internal (not installed): the per-VPL term of the gather and its
 *        guards, shared by mrgi_gather_full() (mrgi_gather.c) and the VPL-tree
 *        gather (mrgi_vpl_tree_gather.c) so that both sum exactly the same
 *        thing. The formula, spaces and guards are documented in
 *        mrgi_gather.h (NSW09 eq. 1 and 5); this header only moves the code.
 *
 * Every function is static inline and does no allocation: they run in the
 * innermost loops.
 */
#ifndef MRGI_GATHER_TERM_H
#define MRGI_GATHER_TERM_H

#include "mrgi_gather.h"
#include "mrgi_voxel_march.h"
#include "mrgi_vpl.h"

#include <float.h>
#include <math.h>

/* A VPL brought into receiver space, in double, ready for the inner loop. */
typedef struct mrgi_gather_vpl
{
  double position[3];
  double normal[3]; /* unit */
  double flux[3];
  double area;
} mrgi_gather_vpl;

/* What mrgi_gather_vpl_prepare() made of a record. */
typedef enum mrgi_gather_vpl_state
{
  MRGI_GATHER_VPL_USABLE = 0,
  MRGI_GATHER_VPL_ZERO_FLUX,
  MRGI_GATHER_VPL_MALFORMED
} mrgi_gather_vpl_state;

static inline double mrgi_gather_dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Scale `v` to unit length; 0 (and v untouched) if its length is 0 or not finite. */
static inline int mrgi_gather_normalize3(double v[3])
{
  const double length2 = mrgi_gather_dot3(v, v);
  if (!(length2 > 0.0) || !isfinite(length2))
  {
    return 0;
  }
  const double inverse_length = 1.0 / sqrt(length2);
  v[0] *= inverse_length;
  v[1] *= inverse_length;
  v[2] *= inverse_length;
  return 1;
}

/* Bring VPL `in` into receiver space (m = column-major rigid matrix or NULL:
 * P' = R P + t, N' = normalize(R N), in double). The pads are ignored.
 * `out` is complete only for MRGI_GATHER_VPL_USABLE. */
static inline mrgi_gather_vpl_state mrgi_gather_vpl_prepare(const mrgi_vpl* in, const float* m,
                                                            mrgi_gather_vpl* out)
{
  int finite = isfinite(in->area) && in->area >= 0.0f;
  for (int c = 0; c < 3; ++c)
  {
    finite = finite && isfinite(in->position[c]) && isfinite(in->normal[c]) &&
             isfinite(in->flux[c]) && in->flux[c] >= 0.0f;
  }
  if (!finite)
  {
    return MRGI_GATHER_VPL_MALFORMED;
  }
  if (in->flux[0] == 0.0f && in->flux[1] == 0.0f && in->flux[2] == 0.0f)
  {
    return MRGI_GATHER_VPL_ZERO_FLUX;
  }
  for (int row = 0; row < 3; ++row)
  {
    if (m)
    {
      out->position[row] = (double)m[row] * in->position[0] + (double)m[4 + row] * in->position[1] +
                           (double)m[8 + row] * in->position[2] + (double)m[12 + row];
      out->normal[row] = (double)m[row] * in->normal[0] + (double)m[4 + row] * in->normal[1] +
                         (double)m[8 + row] * in->normal[2];
    }
    else
    {
      out->position[row] = in->position[row];
      out->normal[row] = in->normal[row];
    }
    out->flux[row] = in->flux[row];
  }
  out->area = in->area;
  if (!mrgi_gather_normalize3(out->normal) ||
      !isfinite(mrgi_gather_dot3(out->position, out->position)))
  {
    return MRGI_GATHER_VPL_MALFORMED;
  }
  return MRGI_GATHER_VPL_USABLE;
}

/* Receiver p of the W x H arrays in double: 1 when valid and well formed
 * (normal made unit), 0 when its valid flag is not set, -1 when malformed
 * (non-finite position, zero or non-finite normal). */
static inline int mrgi_gather_receiver_prepare(const mrgi_gather_receivers* receivers, size_t p,
                                               double position[3], double normal[3])
{
  const float* pos = receivers->position + 4 * p;
  const float* nor = receivers->normal + 4 * p;
  if (!(pos[3] > MRGI_VALID_THRESHOLD))
  {
    return 0;
  }
  position[0] = pos[0];
  position[1] = pos[1];
  position[2] = pos[2];
  normal[0] = nor[0];
  normal[1] = nor[1];
  normal[2] = nor[2];
  if (!isfinite(mrgi_gather_dot3(position, position)) || !mrgi_gather_normalize3(normal))
  {
    return -1;
  }
  return 1;
}

/* The transfer of one prepared VPL to one receiver (unit normal):
 * (cos_i_r cos_j_r / r^2) / (pi r^2 + A_j), or 0 when coincident (r = 0),
 * back-facing or grazing. E_i += Phi_j * transfer (mrgi_gather.h). */
static inline double mrgi_gather_transfer(const double receiver_position[3],
                                          const double receiver_normal[3],
                                          const mrgi_gather_vpl* vpl)
{
  const double d[3] = { vpl->position[0] - receiver_position[0],
                        vpl->position[1] - receiver_position[1],
                        vpl->position[2] - receiver_position[2] };
  const double r2 = mrgi_gather_dot3(d, d);
  if (!(r2 > 0.0))
  {
    return 0.0; /* coincident: w_ij undefined, contribution 0 */
  }
  const double cos_i_r = mrgi_gather_dot3(receiver_normal, d); /* (N_i . w_ij) * r */
  const double cos_j_r = -mrgi_gather_dot3(vpl->normal, d);    /* (N_j . w_ji) * r */
  if (cos_i_r <= 0.0 || cos_j_r <= 0.0)
  {
    return 0.0; /* back-facing or grazing */
  }
  /* eq. 1 times Phi_j / A_j: Phi_j cos_i cos_j / (pi r^2 + A_j); the
   * denominator is > 0 since r2 > 0 and A_j >= 0. */
  return (cos_i_r * cos_j_r / r2) / (MRGI_PI * r2 + vpl->area);
}

/* The receiver argument checks every gather shares (sizes are checked by
 * mrgi_image_create() on the output). */
static inline mrgi_status mrgi_gather_receivers_check(const mrgi_gather_receivers* receivers,
                                                      mrgi_error* err)
{
  if (!receivers)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "receivers pointer is NULL");
  }
  if (!receivers->position || !receivers->normal)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "receiver %s array is NULL",
                          !receivers->position ? "position" : "normal");
  }
  return MRGI_OK;
}

/* Receiver x (receiver space) back in world space, rounded to float:
 * x_w = R^T (x - t) for the rigid column-major M = [R t] (NULL: identity).
 * R^T's row i is R's column i, m[4 i .. 4 i + 2]. */
static inline void mrgi_gather_receiver_to_world(const float* m, const double x[3], float out[3])
{
  if (!m)
  {
    out[0] = (float)x[0];
    out[1] = (float)x[1];
    out[2] = (float)x[2];
    return;
  }
  const double d[3] = { x[0] - m[12], x[1] - m[13], x[2] - m[14] };
  for (int i = 0; i < 3; ++i)
  {
    out[i] = (float)((double)m[4 * i] * d[0] + (double)m[4 * i + 1] * d[1] +
                     (double)m[4 * i + 2] * d[2]);
  }
}

/* ISM visibility (mrgi_gather.h "Visibility") of tile `tile`, looked up from
 * the WORLD-space record `world` (as stored: the GPU reads the same floats)
 * towards the world-space receiver. */
static inline double mrgi_gather_ism_weight(const mrgi_gather_visibility* visibility, int32_t tile,
                                            const mrgi_vpl* world, const float receiver_world[3])
{
  return (double)mrgi_ism_visibility(visibility->ism_layout, visibility->ism_depth, tile,
                                     world->position, world->normal, receiver_world,
                                     &visibility->ism_lookup);
}

/* Voxel visibility (NPW10 3.3.1): one march from the receiver (eye space,
 * its G-buffer normal as stored) to the VPL in eye space; 0 or 1. */
static inline double mrgi_gather_voxel_weight(const mrgi_voxel_view* view, const double x[3],
                                              const float receiver_normal[3],
                                              const mrgi_gather_vpl* vpl)
{
  const float receiver[3] = { (float)x[0], (float)x[1], (float)x[2] };
  const float position[3] = { (float)vpl->position[0], (float)vpl->position[1],
                              (float)vpl->position[2] };
  const float normal[3] = { (float)vpl->normal[0], (float)vpl->normal[1], (float)vpl->normal[2] };
  return mrgi_voxel_march(view, receiver, receiver_normal, position, normal) ? 1.0 : 0.0;
}

/* A double sum stored as the output float: clamped to [0, FLT_MAX], NaN -> 0. */
static inline float mrgi_gather_store(double value)
{
  if (!(value > 0.0))
  {
    return 0.0f;
  }
  return value < FLT_MAX ? (float)value : FLT_MAX;
}

#endif
