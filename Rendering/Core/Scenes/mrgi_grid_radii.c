/* Splat radii from an organized cloud's grid: see mrgi_grid_radii.h. */
#include "mrgi_grid_radii.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MRGI_SQRT_PI 1.77245385090551602730

static int finite3(const float* p)
{
  return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static double range_of(const float* p, const double origin[3])
{
  const double dx = p[0] - origin[0], dy = p[1] - origin[1], dz = p[2] - origin[2];
  return sqrt(dx * dx + dy * dy + dz * dz);
}

mrgi_status mrgi_grid_radii_apply(const float* positions, const int64_t* pixels, int64_t count,
  int64_t width, int64_t height, const double origin[3], double range_step, double scale,
  float* radii, mrgi_grid_radii_stats* stats, mrgi_error* err)
{
  mrgi_grid_radii_stats s;
  memset(&s, 0, sizeof(s));
  if (stats)
  {
    memset(stats, 0, sizeof(*stats));
  }
  if (count < 0 || count > MRGI_GRID_RADII_MAX_POINTS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "count %lld is outside [0, %lld]",
      (long long)count, (long long)MRGI_GRID_RADII_MAX_POINTS);
  }
  if (count > 0 && (!positions || !pixels || !radii))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s is NULL with count %lld",
      !positions  ? "positions"
        : !pixels ? "pixels"
                  : "radii",
      (long long)count);
  }
  if (width < 1 || height < 1 || width > MRGI_GRID_RADII_MAX_PIXELS / height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "grid %lld x %lld: each side must be >= 1 and the grid at most %lld pixels", (long long)width,
      (long long)height, (long long)MRGI_GRID_RADII_MAX_PIXELS);
  }
  if (!origin || !isfinite(origin[0]) || !isfinite(origin[1]) || !isfinite(origin[2]))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "the origin is NULL or not finite");
  }
  if (!isfinite(range_step) || !(range_step > 0.0))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "range_step %g must be finite and > 0", range_step);
  }
  if (!isfinite(scale) || !(scale > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "scale %g must be finite and > 0", scale);
  }
  if (count == 0)
  {
    return MRGI_OK;
  }

  const int64_t n_pixels = width * height;
  int32_t* grid = (int32_t*)malloc((size_t)n_pixels * sizeof(int32_t));
  if (!grid)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "cannot allocate the %lld x %lld grid",
      (long long)width, (long long)height);
  }
  /* -1: empty; -2: claimed twice (left out, with both claimants). */
  for (int64_t q = 0; q < n_pixels; ++q)
  {
    grid[q] = -1;
  }
  for (int64_t i = 0; i < count; ++i)
  {
    const int64_t q = pixels[i];
    if (!finite3(positions + 3 * i) || q < 0 || q >= n_pixels)
    {
      continue;
    }
    grid[q] = grid[q] == -1 ? (int32_t)i : -2;
  }
  for (int64_t i = 0; i < count; ++i)
  {
    const float* p = positions + 3 * i;
    if (!finite3(p))
    {
      continue;
    }
    const int64_t q = pixels[i];
    if (q < 0 || q >= n_pixels || grid[q] != (int32_t)i)
    {
      ++s.unplaced;
      continue;
    }
    ++s.placed;
    const int64_t x = q % width, y = q / width;
    const double ri = range_of(p, origin);
    double d2 = 0.0;
    int neighbours = 0;
    for (int64_t dy = -1; dy <= 1; ++dy)
    {
      for (int64_t dx = -1; dx <= 1; ++dx)
      {
        const int64_t nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width || ny >= height)
        {
          continue;
        }
        const int32_t j = grid[ny * width + nx];
        if (j < 0)
        {
          continue;
        }
        const float* o = positions + 3 * (int64_t)j;
        const double rj = range_of(o, origin);
        if (fabs(ri - rj) > range_step * (ri < rj ? ri : rj))
        {
          continue; /* a depth discontinuity: another surface */
        }
        const double ex = (double)o[0] - p[0], ey = (double)o[1] - p[1], ez = (double)o[2] - p[2];
        const double e2 = ex * ex + ey * ey + ez * ez;
        d2 = e2 > d2 ? e2 : d2;
        ++neighbours;
      }
    }
    if (neighbours == 0)
    {
      ++s.isolated;
      continue;
    }
    const double wanted = scale * sqrt(d2) / MRGI_SQRT_PI;
    const double had = isfinite(radii[i]) && radii[i] > 0.0f ? (double)radii[i] : 0.0;
    if (wanted > had && isfinite(wanted))
    {
      radii[i] = (float)wanted;
      ++s.raised;
    }
  }
  free(grid);
  if (stats)
  {
    *stats = s;
  }
  return MRGI_OK;
}
