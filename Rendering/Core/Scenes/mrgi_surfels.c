/* Points to surfels: see mrgi_surfels.h for the contract. */
#include "mrgi_surfels.h"

#include <inttypes.h>
#include <math.h>
#include <stddef.h>

#define MRGI_SURFEL_PI 3.14159265358979323846

/* A normal shorter than this carries no direction worth trusting. */
#define MRGI_SURFEL_MIN_NORMAL_LENGTH 1e-12

double mrgi_surfel_circumradius_factor(mrgi_surfel_shape shape)
{
  switch (shape)
  {
    case MRGI_SURFEL_SQUARE:
      /* side s with s^2 = pi r^2; corners at s / sqrt(2). */
      return sqrt(MRGI_SURFEL_PI / 2.0);
    case MRGI_SURFEL_HEXAGON:
      /* area (3 sqrt(3) / 2) R^2 = pi r^2. */
      return sqrt(2.0 * MRGI_SURFEL_PI / (3.0 * sqrt(3.0)));
  }
  return 0.0;
}

int32_t mrgi_surfel_fan(mrgi_surfel_shape shape, uint32_t* triangles)
{
  if (!triangles || (shape != MRGI_SURFEL_SQUARE && shape != MRGI_SURFEL_HEXAGON))
  {
    return 0;
  }
  const int32_t count = (int32_t)shape - 2;
  for (int32_t t = 0; t < count; ++t)
  {
    triangles[3 * t] = 0;
    triangles[3 * t + 1] = (uint32_t)(t + 1);
    triangles[3 * t + 2] = (uint32_t)(t + 2);
  }
  return count;
}

void mrgi_surfel_basis(const float n[3], float t1[3], float t2[3])
{
  /* Duff et al. 2017, listing 3: copysign keeps it branchless and exact at n = -z. */
  const float sign = copysignf(1.0f, n[2]);
  const float a = -1.0f / (sign + n[2]);
  const float b = n[0] * n[1] * a;
  t1[0] = 1.0f + sign * n[0] * n[0] * a;
  t1[1] = sign * b;
  t1[2] = -sign * n[0];
  t2[0] = b;
  t2[1] = sign + n[1] * n[1] * a;
  t2[2] = -n[1];
}

static int mrgi_surfel_finite3(const float* v)
{
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* 0 = kept; 1 = position, 2 = normal, 3 = radius. Writes the unit normal and radius when kept. */
static int mrgi_surfel_classify(
  const mrgi_surfel_input* input, float scale, int64_t i, float unit_normal[3], float* radius)
{
  const float* p = input->positions + 3 * i;
  if (!mrgi_surfel_finite3(p))
  {
    return 1;
  }
  const float* n = input->normals + 3 * i;
  if (!mrgi_surfel_finite3(n))
  {
    return 2;
  }
  const double length = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
  if (!(length > MRGI_SURFEL_MIN_NORMAL_LENGTH) || !isfinite(length))
  {
    return 2;
  }
  const float r = (input->radii ? input->radii[i] : input->radius) * scale;
  if (!isfinite(r) || !(r > 0.0f))
  {
    return 3;
  }
  for (int c = 0; c < 3; ++c)
  {
    unit_normal[c] = (float)(n[c] / length);
  }
  *radius = r;
  return 0;
}

static mrgi_status mrgi_surfel_check_input(
  const mrgi_surfel_input* input, const char* caller, mrgi_error* err)
{
  if (!input)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: input is NULL", caller);
  }
  if (input->count < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: point count %" PRId64 " is negative",
      caller, input->count);
  }
  if (input->count > 0 && (!input->positions || !input->normals))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: %s is NULL", caller,
      input->positions ? "normals" : "positions");
  }
  if (!input->radii && !(isfinite(input->radius) && input->radius > 0.0f))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "%s: no radii array and the radius %g is not a positive number", caller,
      (double)input->radius);
  }
  if (input->stride < 0)
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "%s: stride %" PRId64 " is negative", caller, input->stride);
  }
  if (!isfinite(input->radius_scale) || input->radius_scale < 0.0f)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "%s: radius_scale %g is not a number >= 0", caller, (double)input->radius_scale);
  }
  return MRGI_OK;
}

static int64_t mrgi_surfel_stride(const mrgi_surfel_input* input)
{
  return input->stride > 1 ? input->stride : 1;
}

/* The radius factor: the scale, and sqrt(stride) for the points a stride leaves out. */
static float mrgi_surfel_scale(const mrgi_surfel_input* input)
{
  const double scale = input->radius_scale == 0.0f ? 1.0 : (double)input->radius_scale;
  return (float)(scale * sqrt((double)mrgi_surfel_stride(input)));
}

mrgi_status mrgi_surfels_count(
  const mrgi_surfel_input* input, mrgi_surfel_counts* counts, mrgi_error* err)
{
  static const char* caller = "mrgi_surfels_count";
  if (!counts)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: counts is NULL", caller);
  }
  const mrgi_status status = mrgi_surfel_check_input(input, caller, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const float scale = mrgi_surfel_scale(input);
  const int64_t stride = mrgi_surfel_stride(input);
  mrgi_surfel_counts c = { 0, 0, 0, 0, 0 };
  c.strided_out = input->count - (input->count + stride - 1) / stride;
  for (int64_t i = 0; i < input->count; i += stride)
  {
    float n[3], r;
    switch (mrgi_surfel_classify(input, scale, i, n, &r))
    {
      case 0:
        ++c.kept;
        break;
      case 1:
        ++c.bad_position;
        break;
      case 2:
        ++c.bad_normal;
        break;
      default:
        ++c.bad_radius;
        break;
    }
  }
  *counts = c;
  return MRGI_OK;
}

mrgi_status mrgi_surfels_build(const mrgi_surfel_input* input, mrgi_surfel_shape shape,
  const mrgi_surfel_output* output, mrgi_surfel_counts* counts, mrgi_error* err)
{
  static const char* caller = "mrgi_surfels_build";
  if (shape != MRGI_SURFEL_SQUARE && shape != MRGI_SURFEL_HEXAGON)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "%s: shape %d is neither MRGI_SURFEL_SQUARE (4) nor MRGI_SURFEL_HEXAGON (6)", caller,
      (int)shape);
  }
  if (!output || !output->positions || !output->normals)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: %s is NULL", caller,
      !output                ? "output"
        : !output->positions ? "output positions"
                             : "output normals");
  }
  mrgi_status status = mrgi_surfels_count(input, counts, err);
  if (status != MRGI_OK)
  {
    if (err)
    {
      mrgi_error_prefix(err, "%s: ", caller);
    }
    return status;
  }
  const int64_t vertices = (int64_t)shape;
  const int64_t kept = counts->kept;
  /* kept <= count fits easily; 3 * 6 * kept overflows only past 5e17 points. */
  const int64_t floats = 3 * vertices * kept;
  if (output->positions_capacity < floats || output->normals_capacity < floats ||
    (output->source && output->source_capacity < kept))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "%s: %" PRId64 " surfels of %d vertices need %" PRId64
      " floats of positions and of normals and %" PRId64
      " source entries; the output holds %" PRId64 ", %" PRId64 " and %" PRId64,
      caller, kept, (int)shape, floats, kept, output->positions_capacity, output->normals_capacity,
      output->source ? output->source_capacity : 0);
  }

  /* Unit-circle corners, computed once in double. */
  float corner_cos[6], corner_sin[6];
  const double factor = mrgi_surfel_circumradius_factor(shape);
  for (int k = 0; k < (int)vertices; ++k)
  {
    const double angle = 2.0 * MRGI_SURFEL_PI * k / (double)vertices;
    corner_cos[k] = (float)(factor * cos(angle));
    corner_sin[k] = (float)(factor * sin(angle));
  }

  const float scale = mrgi_surfel_scale(input);
  const int64_t stride = mrgi_surfel_stride(input);
  int64_t j = 0;
  for (int64_t i = 0; i < input->count; i += stride)
  {
    float n[3], r;
    if (mrgi_surfel_classify(input, scale, i, n, &r) != 0)
    {
      continue;
    }
    float t1[3], t2[3];
    mrgi_surfel_basis(n, t1, t2);
    const float* p = input->positions + 3 * i;
    float* out_p = output->positions + 3 * vertices * j;
    float* out_n = output->normals + 3 * vertices * j;
    for (int64_t k = 0; k < vertices; ++k)
    {
      const float u = r * corner_cos[k], v = r * corner_sin[k];
      for (int c = 0; c < 3; ++c)
      {
        out_p[3 * k + c] = p[c] + u * t1[c] + v * t2[c];
        out_n[3 * k + c] = n[c];
      }
    }
    if (output->source)
    {
      output->source[j] = i;
    }
    ++j;
  }
  return MRGI_OK;
}
