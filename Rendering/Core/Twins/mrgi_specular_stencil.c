#include "mrgi_specular_stencil.h"

#include "mrgi_buffers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

mrgi_status mrgi_specular_material_build(const mrgi_multires_layout* layout,
                                         const float* position, const float* specular,
                                         const float* shininess, size_t pixels, float* material,
                                         size_t material_floats, mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t texels = (size_t)mrgi_multires_texel_count(layout);
  const size_t needed = (size_t)layout->width * (size_t)layout->height;
  if (!position || !specular || !shininess || pixels < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "G-buffer arrays are NULL or hold %zu pixels; the layout needs %zu",
                          pixels, needed);
  }
  if (!material || material_floats < 4 * texels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "material is NULL or holds %zu floats; the layout needs %zu",
                          material_floats, 4 * texels);
  }
  memset(material, 0, 4 * texels * sizeof(float));
  for (int32_t y = 0; y < layout->height; ++y)
  {
    for (int32_t x = 0; x < layout->width; ++x)
    {
      const size_t p = (size_t)y * (size_t)layout->width + (size_t)x;
      const float* ks = specular + 4 * p;
      const float k = fmaxf(ks[0], fmaxf(ks[1], ks[2]));
      const int spec = position[4 * p + 3] > MRGI_GBUFFER_VALID_THRESHOLD && k > 0.0f;
      float* m = material + 4 * mrgi_multires_index(layout, 0, x, y);
      m[0] = spec ? k : 0.0f;
      m[1] = spec ? shininess[4 * p] : 0.0f;
      m[2] = spec ? shininess[4 * p] : MRGI_MULTIRES_FLT_MAX;
      m[3] = 0.0f;
    }
  }
  for (int32_t i = 1; i < layout->level_count; ++i)
  {
    const int32_t cw = layout->level_width[i - 1];
    const int32_t ch = layout->level_height[i - 1];
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        float r[3] = { 0.0f, 0.0f, MRGI_MULTIRES_FLT_MAX };
        for (int32_t b = 0; b < 2; ++b)
        {
          for (int32_t a = 0; a < 2; ++a)
          {
            const int32_t cx = 2 * x + a < cw ? 2 * x + a : cw - 1;
            const int32_t cy = 2 * y + b < ch ? 2 * y + b : ch - 1;
            const float* c = material + 4 * mrgi_multires_index(layout, i - 1, cx, cy);
            r[0] = fmaxf(r[0], c[0]);
            r[1] = fmaxf(r[1], c[1]);
            r[2] = fminf(r[2], c[2]);
          }
        }
        float* m = material + 4 * mrgi_multires_index(layout, i, x, y);
        m[0] = r[0];
        m[1] = r[1];
        m[2] = r[2];
        m[3] = 0.0f;
      }
    }
  }
  return MRGI_OK;
}

/* M (x, y, z, w) with M column-major, in float in GLSL's order. */
static void ss_transform(const float m[16], const float v[3], float w, float out[3])
{
  for (int r = 0; r < 3; ++r)
  {
    out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * w;
  }
}

float mrgi_specular_stencil_metric(const mrgi_area_light_uniforms* light,
                                   const mrgi_specular_stencil_view* view,
                                   const float receiver_position[4],
                                   const float receiver_normal[3], float power, int32_t level)
{
  const float* p = receiver_position;
  const float* n = receiver_normal;
  if (!(p[3] > MRGI_GBUFFER_VALID_THRESHOLD) || !isfinite(p[0]) || !isfinite(p[1]) ||
      !isfinite(p[2]) || !isfinite(n[0]) || !isfinite(n[1]) || !isfinite(n[2]) ||
      n[0] * n[0] + n[1] * n[1] + n[2] * n[2] == 0.0f)
  {
    return 0.0f;
  }
  float P[3];
  float N[3];
  float V[3];
  ss_transform(view->view_to_world, p, 1.0f, P);
  ss_transform(view->view_to_world, n, 0.0f, N);
  const float toward[3] = { view->parallel ? 0.0f : -p[0], view->parallel ? 0.0f : -p[1],
                            view->parallel ? 1.0f : -p[2] };
  ss_transform(view->view_to_world, toward, 0.0f, V);
  mrgi_area_light_lobe lobe;
  mrgi_area_light_phong_lobe(light, P, N, V, power, &lobe);
  const float e =
    view->parallel ? MRGI_MULTIRES_FLT_MAX : sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  const float s = (float)(1 << level) *
                  fmaxf(view->pixel_size[0] * fabsf(p[2]) + view->pixel_size[1],
                        MRGI_MULTIRES_MIN_PIXEL_SIZE);
  return mrgi_area_light_phong_refinement(&lobe, e, s);
}

mrgi_status mrgi_specular_stencil_build(
  const mrgi_multires_layout* layout, int32_t finest_level, const uint8_t* flags,
  const float* material, size_t material_floats, const float* receiver_position,
  const float* receiver_normal, size_t receiver_floats, const mrgi_area_light_uniforms* light,
  const mrgi_specular_stencil_view* view, uint8_t* refine, uint8_t* selection, size_t texel_bytes,
  mrgi_specular_stencil_stats* stats, mrgi_error* err)
{
  mrgi_status status = mrgi_multires_layout_check(layout, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t texels = (size_t)mrgi_multires_texel_count(layout);
  if ((status = mrgi_multires_check_array(layout, flags, texel_bytes, 1, "flags", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, selection, texel_bytes, 1, "selection", err)) !=
        MRGI_OK ||
      (status = mrgi_multires_check_array(layout, material, material_floats, 4, "material", err)) !=
        MRGI_OK ||
      (status = mrgi_multires_check_array(layout, receiver_position, receiver_floats, 4,
                                          "receiver positions", err)) != MRGI_OK ||
      (status = mrgi_multires_check_array(layout, receiver_normal, receiver_floats, 4,
                                          "receiver normals", err)) != MRGI_OK)
  {
    return status;
  }
  if (!light || !view)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "light or view is NULL");
  }
  if (view->lobe && !(view->lobe_threshold > 0.0f && isfinite(view->lobe_threshold)))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "lobe threshold %g must be finite and > 0", (double)view->lobe_threshold);
  }
  if (finest_level < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "finest level %d is negative",
                          finest_level);
  }
  const int32_t coarsest = layout->level_count - 1;
  const int32_t finest = finest_level < coarsest ? finest_level : coarsest;
  mrgi_specular_stencil_stats counts;
  memset(&counts, 0, sizeof(counts));
  uint8_t* bits = refine;
  uint8_t* scratch = NULL;
  if (!bits)
  {
    scratch = (uint8_t*)calloc(texels, 1);
    if (!scratch)
    {
      return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "specular stencil: out of memory");
    }
    bits = scratch;
  }
  memset(bits, 0, texels);
  memset(selection, 0, texels);
  /* Q of every texel at or above f. */
  for (int32_t j = finest; j <= coarsest; ++j)
  {
    for (int32_t y = 0; y < layout->level_height[j]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[j]; ++x)
      {
        const size_t u = mrgi_multires_index(layout, j, x, y);
        if (!(flags[u] & MRGI_MULTIRES_FLAG_NONEMPTY))
        {
          continue;
        }
        const float* m = material + 4 * u;
        const int k = m[0] > 0.0f;
        uint8_t b = k ? MRGI_SPECULAR_STENCIL_SPECULAR : 0;
        if (j > finest)
        {
          int q = (flags[u] & MRGI_MULTIRES_FLAG_REFINE) != 0;
          if (k)
          {
            q = q || m[2] < m[1];
            if (view->lobe &&
                mrgi_specular_stencil_metric(light, view, receiver_position + 4 * u,
                                             receiver_normal + 4 * u, m[1], j) > view->lobe_threshold)
            {
              b |= MRGI_SPECULAR_STENCIL_LOBE;
              ++counts.lobe[j];
              q = 1;
            }
          }
          b |= q ? MRGI_SPECULAR_STENCIL_REFINE : 0;
        }
        bits[u] = b;
      }
    }
  }
  /* The top-down walk and the selection. */
  for (int32_t i = finest; i <= coarsest; ++i)
  {
    for (int32_t y = 0; y < layout->level_height[i]; ++y)
    {
      for (int32_t x = 0; x < layout->level_width[i]; ++x)
      {
        const size_t t = mrgi_multires_index(layout, i, x, y);
        if (!(bits[t] & MRGI_SPECULAR_STENCIL_SPECULAR) || (bits[t] & MRGI_SPECULAR_STENCIL_REFINE))
        {
          continue;
        }
        int ancestors = 1;
        for (int32_t j = i + 1; j <= coarsest && ancestors; ++j)
        {
          const int32_t d = j - i;
          ancestors = (bits[mrgi_multires_index(layout, j, x >> d, y >> d)] &
                       MRGI_SPECULAR_STENCIL_REFINE) != 0;
        }
        if (ancestors)
        {
          selection[t] = 1;
          ++counts.selected[i];
          ++counts.selected_total;
        }
      }
    }
  }
  free(scratch);
  if (stats)
  {
    *stats = counts;
  }
  return MRGI_OK;
}
