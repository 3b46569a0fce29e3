/* Area-uniform samples of a mesh: see mrgi_mesh_sample.h for the contract. */
#include "mrgi_mesh_sample.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>

#define MRGI_SAMPLE_PI 3.14159265358979323846

/* splitmix64 (Steele, Lea & Flood 2014): one 64-bit state, portable, good enough to place points.
 */
static uint64_t mrgi_sample_next(uint64_t* state)
{
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* Uniform in [0, 1) with 53 random bits. */
static double mrgi_sample_uniform(uint64_t* state)
{
  return (double)(mrgi_sample_next(state) >> 11) * (1.0 / 9007199254740992.0);
}

mrgi_status mrgi_mesh_sample(const mrgi_mesh* mesh, int64_t count, uint64_t seed,
  double radius_factor, const mrgi_mesh_samples* out, double* radius, mrgi_error* err)
{
  static const char* caller = "mrgi_mesh_sample";
  if (!out || !out->positions || !out->normals)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: %s is NULL", caller,
      !out                ? "out"
        : !out->positions ? "out->positions"
                          : "out->normals");
  }
  if (count < 1 || count > out->capacity)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "%s: count %" PRId64 " is outside 1..capacity %" PRId64, caller, count, out->capacity);
  }
  if (!isfinite(radius_factor) || !(radius_factor > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "%s: radius_factor %g is not a positive number", caller, radius_factor);
  }
  mrgi_status status = mrgi_mesh_validate(mesh, err);
  if (status != MRGI_OK)
  {
    if (err)
    {
      mrgi_error_prefix(err, "%s: ", caller);
    }
    return status;
  }
  double* prefix = malloc((size_t)mesh->triangle_count * sizeof(double));
  if (!prefix)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
      "%s: no memory for the areas of %" PRId64 " triangles", caller, mesh->triangle_count);
  }
  double total = 0.0;
  for (int64_t t = 0; t < mesh->triangle_count; ++t)
  {
    double area = 0.0;
    status = mrgi_mesh_triangle_geometry(mesh, t, NULL, NULL, &area, err);
    if (status != MRGI_OK)
    {
      free(prefix);
      return status;
    }
    total += area;
    prefix[t] = total;
  }
  if (!(total > 0.0) || !isfinite(total))
  {
    free(prefix);
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "%s: mesh '%s' has area %g: nothing to sample",
      caller, mesh->name, total);
  }

  uint64_t state = seed;
  for (int64_t i = 0; i < count; ++i)
  {
    /* The first triangle whose prefix sum exceeds the target; zero-area ones are never it. */
    const double target = mrgi_sample_uniform(&state) * total;
    int64_t lo = 0, hi = mesh->triangle_count - 1;
    while (lo < hi)
    {
      const int64_t mid = lo + (hi - lo) / 2;
      if (prefix[mid] > target)
      {
        hi = mid;
      }
      else
      {
        lo = mid + 1;
      }
    }
    double normal[3];
    (void)mrgi_mesh_triangle_geometry(mesh, lo, normal, NULL, NULL, NULL);
    const uint32_t* tri = mesh->indices + 3 * lo;
    const float* a = mesh->positions + 3 * (int64_t)tri[0];
    const float* b = mesh->positions + 3 * (int64_t)tri[1];
    const float* c = mesh->positions + 3 * (int64_t)tri[2];
    const double su = sqrt(mrgi_sample_uniform(&state));
    const double v = mrgi_sample_uniform(&state);
    const double wa = 1.0 - su, wb = su * (1.0 - v), wc = su * v;
    for (int k = 0; k < 3; ++k)
    {
      out->positions[3 * i + k] = (float)(wa * a[k] + wb * b[k] + wc * c[k]);
      out->normals[3 * i + k] = (float)normal[k];
    }
  }
  free(prefix);

  const double r = radius_factor * sqrt(total / (MRGI_SAMPLE_PI * (double)count));
  if (out->radii)
  {
    for (int64_t i = 0; i < count; ++i)
    {
      out->radii[i] = (float)r;
    }
  }
  if (radius)
  {
    *radius = r;
  }
  return MRGI_OK;
}
