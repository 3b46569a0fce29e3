#include "mrgi_irradiance_stencil.h"

#include "mrgi_buffers.h"
#include "mrgi_gather.h" /* MRGI_PI */

#include <math.h>
#include <string.h>

float mrgi_irradiance_stencil_estimate(const mrgi_area_light_uniforms* light, const float P[3],
                                       const float N[3])
{
  const float side = light->normal[0] * (P[0] - light->center[0]) +
                     light->normal[1] * (P[1] - light->center[1]) +
                     light->normal[2] * (P[2] - light->center[2]);
  if (light->two_sided ? side == 0.0f : !(side > 0.0f))
  {
    return 0.0f;
  }
  const float g = (float)MRGI_IRRADIANCE_STENCIL_GRID;
  const float cell = light->area / (g * g);
  float U[3], V[3];
  for (int k = 0; k < 3; ++k)
  {
    U[k] = light->corners[1][k] - light->corners[0][k];
    V[k] = light->corners[3][k] - light->corners[0][k];
  }
  float E = 0.0f;
  for (int b = 0; b < MRGI_IRRADIANCE_STENCIL_GRID; ++b)
  {
    const float sv = ((float)b + 0.5f) / g;
    for (int a = 0; a < MRGI_IRRADIANCE_STENCIL_GRID; ++a)
    {
      const float su = ((float)a + 0.5f) / g;
      float d[3];
      for (int k = 0; k < 3; ++k)
      {
        d[k] = (light->corners[0][k] + su * U[k] + sv * V[k]) - P[k];
      }
      const float r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (!(r2 > 0.0f))
      {
        continue;
      }
      const float ci = N[0] * d[0] + N[1] * d[1] + N[2] * d[2];
      float cj = -(light->normal[0] * d[0] + light->normal[1] * d[1] + light->normal[2] * d[2]);
      if (light->two_sided)
      {
        cj = fabsf(cj);
      }
      if (!(ci > 0.0f) || !(cj > 0.0f))
      {
        continue;
      }
      E += cell * (ci * cj / r2) / ((float)MRGI_PI * r2 + cell);
    }
  }
  return E;
}

/* The world-space receiver of flattened texel t; 0 when it is none. */
static int mrgi_irradiance_receiver(const float* position, const float* normal, size_t t,
                                    const float M[16], float P[3], float N[3])
{
  const float* p = position + 4 * t;
  const float* n = normal + 4 * t;
  if (!(p[3] > MRGI_GBUFFER_VALID_THRESHOLD) || !isfinite(p[0]) || !isfinite(p[1]) ||
      !isfinite(p[2]) || !isfinite(n[0]) || !isfinite(n[1]) || !isfinite(n[2]))
  {
    return 0;
  }
  float m[3];
  for (int k = 0; k < 3; ++k)
  {
    P[k] = M[k] * p[0] + M[4 + k] * p[1] + M[8 + k] * p[2] + M[12 + k];
    m[k] = M[k] * n[0] + M[4 + k] * n[1] + M[8 + k] * n[2];
  }
  const float len2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
  if (!(len2 > 0.0f))
  {
    return 0;
  }
  const float inv = 1.0f / sqrtf(len2);
  N[0] = m[0] * inv;
  N[1] = m[1] * inv;
  N[2] = m[2] * inv;
  return 1;
}

/* V_level(x, y) of the file comment. */
static int mrgi_irradiance_varies(const mrgi_multires_layout* layout, int32_t level, int32_t x,
                                  int32_t y, const float* position, const float* normal,
                                  const float M[16], const mrgi_area_light_uniforms* light,
                                  float tolerance)
{
  float lo = 0.0f, hi = 0.0f;
  int any = 0;
  for (int32_t dy = -1; dy <= 1; ++dy)
  {
    for (int32_t dx = -1; dx <= 1; ++dx)
    {
      float P[3], N[3];
      if (!mrgi_irradiance_receiver(position, normal,
                                    mrgi_multires_clamped_index(layout, level, x, y, dx, dy), M, P,
                                    N))
      {
        continue;
      }
      const float E = mrgi_irradiance_stencil_estimate(light, P, N);
      lo = any ? (E < lo ? E : lo) : E;
      hi = any ? (E > hi ? E : hi) : E;
      any = 1;
    }
  }
  return any && hi > 0.0f && hi - lo > tolerance * hi;
}

mrgi_status mrgi_irradiance_stencil_add(
  const mrgi_multires_layout* layout, int32_t finest_level, const uint8_t* flags,
  size_t texel_bytes, const float* receiver_position, const float* receiver_normal,
  size_t receiver_floats, const float view_to_world[16], const mrgi_area_light_uniforms* light,
  float tolerance, uint8_t* rendered, size_t rendered_size,
  int64_t added[MRGI_MULTIRES_MAX_LEVELS], mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if ((status = mrgi_multires_check_array(layout, flags, texel_bytes, 1, "flags", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, receiver_position, receiver_floats, 4,
                                          "receiver positions", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, receiver_normal, receiver_floats, 4,
                                          "receiver normals", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, rendered, rendered_size, 1, "rendered mask",
                                          err)) != MRGI_OK)
  {
    return status;
  }
  if (!view_to_world || !light)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "the irradiance stencil needs a view-to-world matrix and a light");
  }
  if (!(tolerance >= 0.0f && tolerance <= 1.0f))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "irradiance tolerance %g is outside [0, 1]", (double)tolerance);
  }
  if (finest_level < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "finest level %d is negative",
                          finest_level);
  }
  int64_t counts[MRGI_MULTIRES_MAX_LEVELS];
  memset(counts, 0, sizeof(counts));
  const int32_t coarsest = layout->level_count - 1;
  const int32_t finest = finest_level < coarsest ? finest_level : coarsest;
  for (int32_t i = finest; i < coarsest && tolerance > 0.0f; ++i)
  {
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        if (rendered[t] || !(flags[t] & MRGI_MULTIRES_FLAG_NONEMPTY) ||
            (i != finest && (flags[t] & MRGI_MULTIRES_FLAG_REFINE)))
        {
          continue;
        }
        if (mrgi_irradiance_varies(layout, i + 1, x / 2, y / 2, receiver_position,
                                   receiver_normal, view_to_world, light, tolerance))
        {
          rendered[t] = 1;
          ++counts[i];
        }
      }
    }
  }
  if (added)
  {
    memcpy(added, counts, sizeof(counts));
  }
  return MRGI_OK;
}
