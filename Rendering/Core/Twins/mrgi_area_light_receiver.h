/* Private to the area-light twins (mrgi_area_light.c and
 * mrgi_area_light_specular.c): the float per-receiver helpers both files use,
 * written as a GLSL 1.50 shader writes them (dot, cross, normalize) so the
 * twins round as the shaders do. Not installed, not part of the contract in
 * mrgi_area_light.h. */
#ifndef mrgi_area_light_receiver_h
#define mrgi_area_light_receiver_h

#include "mrgi_area_light.h"
#include "mrgi_gather.h" /* MRGI_PI */

#include <float.h>
#include <math.h>

/* ---- float helpers (per-receiver code; GLSL's dot, cross, length) ---- */

static inline float al_dotf(const float a[3], const float b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void al_crossf(const float a[3], const float b[3], float out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* normalize(v) into out; 0 (out zeroed) when v has no length. */
static inline int al_normalizef(const float v[3], float out[3])
{
  const float length2 = al_dotf(v, v);
  if (!(length2 > 0.0f) || !(length2 < FLT_MAX))
  {
    out[0] = out[1] = out[2] = 0.0f;
    return 0;
  }
  const float inverse_length = 1.0f / sqrtf(length2);
  out[0] = v[0] * inverse_length;
  out[1] = v[1] * inverse_length;
  out[2] = v[2] * inverse_length;
  return 1;
}


/* Early-outs 1 and 2 of the header: 1 when the receiver gets no light. */
static inline int al_culled_behind(const mrgi_area_light_uniforms* light, const float position[3])
{
  const float to_receiver[3] = { position[0] - light->center[0], position[1] - light->center[1],
                                 position[2] - light->center[2] };
  const float side = al_dotf(light->normal, to_receiver);
  return light->two_sided ? side == 0.0f : !(side > 0.0f);
}

static inline int al_culled_facing(const mrgi_area_light_uniforms* light, const float position[3],
                                   const float normal[3])
{
  for (int k = 0; k < 4; ++k)
  {
    const float to_corner[3] = { light->corners[k][0] - position[0],
                                 light->corners[k][1] - position[1],
                                 light->corners[k][2] - position[2] };
    if (al_dotf(normal, to_corner) > 0.0f)
    {
      return 0;
    }
  }
  return 1;
}

/* The form-factor term T of one emitter patch (header): A (cos_i cos_j / r^2)
 * / (pi r^2 + A), 0 when skipped. `d` = patch - receiver; cos_i_r is
 * returned for the lobe. */
static inline float al_transfer(const mrgi_area_light_uniforms* light, const float d[3],
                         const float patch_normal[3], float patch_area, const float normal[3],
                         float* r2_out)
{
  const float r2 = al_dotf(d, d);
  *r2_out = r2;
  if (!(r2 > 0.0f))
  {
    return 0.0f; /* on the patch: direction undefined */
  }
  const float cos_i_r = al_dotf(normal, d);
  float cos_j_r = -al_dotf(patch_normal, d);
  if (light->two_sided)
  {
    cos_j_r = fabsf(cos_j_r);
  }
  if (!(cos_i_r > 0.0f) || !(cos_j_r > 0.0f))
  {
    return 0.0f; /* receiver facing away, or behind the (one-sided) light */
  }
  return patch_area * (cos_i_r * cos_j_r / r2) / ((float)MRGI_PI * r2 + patch_area);
}

#endif /* mrgi_area_light_receiver_h */
