#include "mrgi_variance_shadow.h"

#include "mrgi_buffers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void mrgi_voxel_vsm_query_cell(int32_t query, int32_t* cell_x, int32_t* cell_y)
{
  *cell_x = query % MRGI_AREA_LIGHT_LOBE_GRID - MRGI_AREA_LIGHT_LOBE_GRID / 2;
  *cell_y = query / MRGI_AREA_LIGHT_LOBE_GRID - MRGI_AREA_LIGHT_LOBE_GRID / 2;
}

void mrgi_voxel_vsm_moments(const mrgi_voxel_view* view, const mrgi_voxel_samples* queries,
                            const float receiver[3], const float* normal, uint32_t phase_set,
                            float* moments)
{
  for (int32_t j = 0; j < queries->count; ++j)
  {
    if (!((phase_set >> (uint32_t)(j & 3)) & 1u))
    {
      moments[2 * j] = 0.0f;
      moments[2 * j + 1] = 0.0f;
      continue;
    }
    const float* n = queries->normal ? queries->normal + 3 * j : NULL;
    const float z =
      mrgi_voxel_march_occluder_fraction(view, receiver, normal, queries->position + 3 * j, n);
    moments[2 * j] = z;
    moments[2 * j + 1] = z * z;
  }
}

float mrgi_voxel_vsm_chebyshev(float mean, float mean_sq, float min_variance)
{
  if (mean >= 1.0f)
  {
    return 1.0f;
  }
  const float variance = fmaxf(mean_sq - mean * mean, min_variance);
  const float d = 1.0f - mean;
  const float p = variance / (variance + d * d);
  return fminf(fmaxf(p, 0.0f), 1.0f); /* 0/0 (variance 0, mean < 1) -> 0 */
}

mrgi_status mrgi_voxel_vsm_resolve(int32_t width, int32_t height, int32_t query_count,
                                   const float* moments, const uint8_t* phase_sets,
                                   int32_t radius, float min_variance, float* visibility,
                                   mrgi_error* err)
{
  if (!moments || !phase_sets || !visibility)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s is NULL",
                          !moments ? "moments" : (!phase_sets ? "phase sets" : "visibility"));
  }
  if (width < 1 || width > MRGI_VOXEL_MAX_SIZE || height < 1 || height > MRGI_VOXEL_MAX_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VSM image size %d x %d is outside 1..%d per side", width, height,
                          MRGI_VOXEL_MAX_SIZE);
  }
  if (query_count < 1 || query_count > MRGI_VOXEL_MAX_SAMPLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VSM query count %d is outside 1..%d",
                          query_count, MRGI_VOXEL_MAX_SAMPLES);
  }
  if (radius < 0 || radius > MRGI_VOXEL_VSM_MAX_RADIUS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "VSM blur radius %d is outside 0..%d",
                          radius, MRGI_VOXEL_VSM_MAX_RADIUS);
  }
  if (!(min_variance >= 0.0f) || !isfinite(min_variance))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "VSM minimum variance %g must be finite and >= 0",
                          (double)min_variance);
  }
  const size_t q = (size_t)query_count;
  for (int32_t y = 0; y < height; ++y)
  {
    for (int32_t x = 0; x < width; ++x)
    {
      const size_t p = (size_t)y * (size_t)width + (size_t)x;
      float* out = visibility + p * q;
      if (!phase_sets[p])
      {
        memset(out, 0, q * sizeof(float));
        continue;
      }
      for (int32_t j = 0; j < query_count; ++j)
      {
        float m1 = 0.0f;
        float m2 = 0.0f;
        int32_t n = 0;
        for (int32_t dy = -radius; dy <= radius; ++dy)
        {
          for (int32_t dx = -radius; dx <= radius; ++dx)
          {
            const int32_t sx = x + dx;
            const int32_t sy = y + dy;
            if (sx < 0 || sy < 0 || sx >= width || sy >= height)
            {
              continue;
            }
            const size_t s = (size_t)sy * (size_t)width + (size_t)sx;
            if (!((phase_sets[s] >> (j & 3)) & 1))
            {
              continue;
            }
            m1 += moments[(s * q + (size_t)j) * 2];
            m2 += moments[(s * q + (size_t)j) * 2 + 1];
            ++n;
          }
        }
        out[j] = n == 0 ? 1.0f
                        : mrgi_voxel_vsm_chebyshev(m1 / (float)n, m2 / (float)n, min_variance);
      }
    }
  }
  return MRGI_OK;
}

_Static_assert(MRGI_VOXEL_VSM_QUERIES == MRGI_AREA_LIGHT_LOBE_CELLS - 1,
               "VSM query j is lobe grid cell j; the last cell (a corner) is dropped");

int mrgi_voxel_vsm_specular_moments(const mrgi_voxel_view* view,
                                    const mrgi_area_light_uniforms* light,
                                    const mrgi_area_light_sample* samples, int32_t count,
                                    const float world_to_eye[16], const float position[3],
                                    const float normal[3], const float view_dir[3], float power,
                                    const float receiver_eye[3], const float normal_eye[3],
                                    uint32_t phase_set, float* moments)
{
  memset(moments, 0, 2 * MRGI_VOXEL_VSM_QUERIES * sizeof(float));
  mrgi_area_light_specular_info info;
  mrgi_area_light_specular_classify(light, samples, count, position, normal, view_dir, power,
                                    &info);
  if (info.path != MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
  {
    return 0;
  }
  mrgi_area_light_lobe_grid grid;
  mrgi_area_light_lobe_grid_cells(light, &info.lobe, &grid);
  const float* m = world_to_eye;
  const float* ln = light->normal;
  const float light_normal[3] = { m[0] * ln[0] + m[4] * ln[1] + m[8] * ln[2],
                                  m[1] * ln[0] + m[5] * ln[1] + m[9] * ln[2],
                                  m[2] * ln[0] + m[6] * ln[1] + m[10] * ln[2] };
  for (int32_t j = 0; j < MRGI_VOXEL_VSM_QUERIES; ++j)
  {
    if (!((phase_set >> (uint32_t)(j & 3)) & 1u))
    {
      continue;
    }
    float z = 1.0f; /* a cell off the light: no light there to hide */
    if (grid.on_light[j])
    {
      const float* y = grid.position[j];
      float L[3], NL[3], PL[3];
      for (int c = 0; c < 3; ++c)
      {
        L[c] = m[c] * y[0] + m[4 + c] * y[1] + m[8 + c] * y[2] + m[12 + c];
        NL[c] = light_normal[c];
        PL[c] = receiver_eye[c] - L[c];
      }
      if (light->two_sided && NL[0] * PL[0] + NL[1] * PL[1] + NL[2] * PL[2] < 0.0f)
      {
        NL[0] = -NL[0];
        NL[1] = -NL[1];
        NL[2] = -NL[2];
      }
      z = mrgi_voxel_march_occluder_fraction(view, receiver_eye, normal_eye, L, NL);
    }
    moments[2 * j] = z;
    moments[2 * j + 1] = z * z;
  }
  return 1;
}
