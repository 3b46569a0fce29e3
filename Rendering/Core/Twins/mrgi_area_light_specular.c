/* Rectangular area lights, specular part: the Phong lobe's bounds, the lobe
 * grid cells and the specular gather twins (mrgi_area_light.h, "Specular").
 * Float math only, in the order a GLSL 1.50 shader writes it. Split from
 * mrgi_area_light.c; the shared per-receiver helpers are in
 * mrgi_area_light_receiver.h. */
#include "mrgi_area_light.h"
#include "mrgi_area_light_receiver.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

/* Largest cos(R, y - P) over the edge from corner a to corner b (points
 * relative to P): at an end, or where R's projection on the plane of the
 * two rays falls between them. */
static float al_edge_max_cos(const float r[3], const float a[3], const float b[3])
{
  const float la = sqrtf(al_dotf(a, a)), lb = sqrtf(al_dotf(b, b));
  float best = -1.0f;
  if (la > 0.0f)
  {
    best = fmaxf(best, al_dotf(r, a) / la);
  }
  if (lb > 0.0f)
  {
    best = fmaxf(best, al_dotf(r, b) / lb);
  }
  float m[3];
  al_crossf(a, b, m);
  const float lm2 = al_dotf(m, m);
  if (lm2 > 0.0f)
  {
    const float rm = al_dotf(r, m) / lm2;
    const float q[3] = { r[0] - rm * m[0], r[1] - rm * m[1], r[2] - rm * m[2] };
    float aq[3], qb[3];
    al_crossf(a, q, aq);
    al_crossf(q, b, qb);
    if (al_dotf(aq, m) > 0.0f && al_dotf(qb, m) > 0.0f)
    {
      best = fmaxf(best, sqrtf(al_dotf(q, q)));
    }
  }
  return best;
}

void mrgi_area_light_phong_lobe(const mrgi_area_light_uniforms* light, const float position[3],
                                const float normal[3], const float view[3], float power,
                                mrgi_area_light_lobe* out)
{
  memset(out, 0, sizeof(*out));
  out->width = FLT_MAX;
  /* Half-maximum cone: cos(theta_h)^n = 1/2. */
  const float cos_half = power > 0.0f ? exp2f(-1.0f / power) : 0.0f;
  out->tan_half = cos_half > 0.0f ? sqrtf(fmaxf(0.0f, 1.0f - cos_half * cos_half)) / cos_half
                                  : FLT_MAX;
  float n[3], v[3];
  if (!al_normalizef(normal, n) || !al_normalizef(view, v))
  {
    return;
  }
  const float nv = al_dotf(n, v);
  const float reflected[3] = { 2.0f * nv * n[0] - v[0], 2.0f * nv * n[1] - v[1],
                               2.0f * nv * n[2] - v[2] };
  float r[3];
  if (!al_normalizef(reflected, r))
  {
    return;
  }
  out->reflect[0] = r[0];
  out->reflect[1] = r[1];
  out->reflect[2] = r[2];
  /* Where R meets the light's plane. */
  const float to_center[3] = { light->center[0] - position[0], light->center[1] - position[1],
                               light->center[2] - position[2] };
  const float denominator = al_dotf(r, light->normal);
  const float t = denominator != 0.0f ? al_dotf(to_center, light->normal) / denominator : 0.0f;
  if (t > 0.0f && t < FLT_MAX)
  {
    out->reaches_plane = 1;
    out->distance = t;
    out->inverse_distance = 1.0f / t;
    const float width = 2.0f * t * out->tan_half;
    out->width = width < FLT_MAX ? width : FLT_MAX;
    out->hit_u = t * al_dotf(r, light->axis_u) - al_dotf(to_center, light->axis_u);
    out->hit_v = t * al_dotf(r, light->axis_v) - al_dotf(to_center, light->axis_v);
    out->hits_light = fabsf(out->hit_u) <= light->half_u && fabsf(out->hit_v) <= light->half_v;
  }
  float peak_cos = 1.0f;
  if (!out->hits_light)
  {
    peak_cos = -1.0f;
    for (int k = 0; k < 4; ++k)
    {
      const float* ca = light->corners[k];
      const float* cb = light->corners[(k + 1) % 4];
      const float a[3] = { ca[0] - position[0], ca[1] - position[1], ca[2] - position[2] };
      const float b[3] = { cb[0] - position[0], cb[1] - position[1], cb[2] - position[2] };
      peak_cos = fmaxf(peak_cos, al_edge_max_cos(r, a, b));
    }
    peak_cos = fminf(peak_cos, 1.0f);
  }
  out->peak = peak_cos > 0.0f ? powf(peak_cos, power) : 0.0f;
}

float mrgi_area_light_phong_refinement(const mrgi_area_light_lobe* lobe, float eye_distance,
                                       float texel_size)
{
  if (!(eye_distance > 0.0f))
  {
    return FLT_MAX;
  }
  if (!(lobe->tan_half < FLT_MAX))
  {
    return 0.0f; /* n = 0: the lobe is the hemisphere, nothing to resolve */
  }
  if (!(lobe->tan_half > 0.0f))
  {
    return FLT_MAX; /* a lobe too sharp for float: always refine */
  }
  const float metric =
    texel_size * (1.0f / eye_distance + lobe->inverse_distance) / (2.0f * lobe->tan_half);
  return metric < FLT_MAX ? metric : FLT_MAX;
}

int mrgi_area_light_lobe_grid_cells(const mrgi_area_light_uniforms* light,
                                    const mrgi_area_light_lobe* lobe,
                                    mrgi_area_light_lobe_grid* grid)
{
  memset(grid, 0, sizeof(*grid));
  const float* r = lobe->reflect;
  const float rn = al_dotf(r, light->normal);
  const float c = fmaxf(fabsf(rn), MRGI_AREA_LIGHT_MIN_COS);
  const float along[3] = { r[0] - rn * light->normal[0], r[1] - rn * light->normal[1],
                           r[2] - rn * light->normal[2] };
  float e1[3];
  if (!(sqrtf(al_dotf(along, along)) > MRGI_AREA_LIGHT_MIN_ALONG) || !al_normalizef(along, e1))
  {
    e1[0] = light->axis_u[0];
    e1[1] = light->axis_u[1];
    e1[2] = light->axis_u[2];
  }
  float e2[3];
  al_crossf(light->normal, e1, e2);
  /* Semi-axes of the half-maximum ellipse; its half extents along u and v. */
  const float half_width = lobe->distance * lobe->tan_half;
  const float a1 = half_width / c, a2 = half_width;
  const float pu1 = a1 * al_dotf(e1, light->axis_u), pu2 = a2 * al_dotf(e2, light->axis_u);
  const float pv1 = a1 * al_dotf(e1, light->axis_v), pv2 = a2 * al_dotf(e2, light->axis_v);
  const float hu = sqrtf(pu1 * pu1 + pu2 * pu2), hv = sqrtf(pv1 * pv1 + pv2 * pv2);
  if (!(hu > 0.0f && hu < FLT_MAX && hv > 0.0f && hv < FLT_MAX))
  {
    return 0;
  }
  grid->spacing_u = hu;
  grid->spacing_v = hv;
  grid->lod = log2f(fmaxf(hu * (float)light->texture_width / (2.0f * light->half_u),
                          hv * (float)light->texture_height / (2.0f * light->half_v)));
  const int32_t half_grid = MRGI_AREA_LIGHT_LOBE_GRID / 2;
  for (int32_t b = -half_grid; b <= half_grid; ++b)
  {
    const float lo_v = fmaxf(lobe->hit_v + ((float)b - 0.5f) * hv, -light->half_v);
    const float hi_v = fminf(lobe->hit_v + ((float)b + 0.5f) * hv, light->half_v);
    if (!(hi_v > lo_v))
    {
      continue;
    }
    for (int32_t a = -half_grid; a <= half_grid; ++a)
    {
      const float lo_u = fmaxf(lobe->hit_u + ((float)a - 0.5f) * hu, -light->half_u);
      const float hi_u = fminf(lobe->hit_u + ((float)a + 0.5f) * hu, light->half_u);
      if (!(hi_u > lo_u))
      {
        continue;
      }
      const int32_t cell = (b + half_grid) * MRGI_AREA_LIGHT_LOBE_GRID + (a + half_grid);
      const float cu = 0.5f * (lo_u + hi_u), cv = 0.5f * (lo_v + hi_v);
      ++grid->cells;
      grid->on_light[cell] = 1;
      grid->area[cell] = (hi_u - lo_u) * (hi_v - lo_v);
      grid->u[cell] = cu;
      grid->v[cell] = cv;
      for (int k = 0; k < 3; ++k)
      {
        grid->position[cell][k] =
          light->center[k] + cu * light->axis_u[k] + cv * light->axis_v[k];
      }
    }
  }
  return 1;
}

/* Visibility of lobe grid cell `cell` (header, "Shadowed highlights"): its
 * query's, the dropped corner the mean of its two edge neighbours. */
static float al_cell_visibility(const float* query_visibility, int32_t cell)
{
  const int32_t corner = MRGI_AREA_LIGHT_LOBE_CELLS - 1;
  if (cell < corner)
  {
    return query_visibility[cell];
  }
  return 0.5f * (query_visibility[corner - 1] + query_visibility[corner - MRGI_AREA_LIGHT_LOBE_GRID]);
}

/* The lobe grid's sum (header): every cell on the light acts as a sample. */
static void al_lobe_grid_sum(const mrgi_area_light_uniforms* light,
                             const mrgi_area_light_texture_pyramid* pyramid,
                             const float position[3], const float n[3], const float r[3],
                             const mrgi_area_light_lobe_grid* grid, float power,
                             float normalisation, const float* query_visibility, float sum[3])
{
  for (int32_t cell = 0; cell < MRGI_AREA_LIGHT_LOBE_CELLS; ++cell)
  {
    if (!grid->on_light[cell])
    {
      continue;
    }
    float texel[3] = { 1.0f, 1.0f, 1.0f };
    if (pyramid)
    {
      mrgi_area_light_texture_sample(pyramid, grid->u[cell] / (2.0f * light->half_u) + 0.5f,
                                     grid->v[cell] / (2.0f * light->half_v) + 0.5f, grid->lod,
                                     texel);
    }
    const float d[3] = { grid->position[cell][0] - position[0],
                         grid->position[cell][1] - position[1],
                         grid->position[cell][2] - position[2] };
    float r2;
    const float transfer = al_transfer(light, d, light->normal, grid->area[cell], n, &r2);
    const float rw = al_dotf(r, d);
    if (!(transfer > 0.0f) || !(rw > 0.0f))
    {
      continue;
    }
    float weight = normalisation * powf(rw / sqrtf(r2), power) * transfer;
    if (query_visibility)
    {
      weight *= al_cell_visibility(query_visibility, cell);
    }
    sum[0] += light->scale[0] * texel[0] * weight;
    sum[1] += light->scale[1] * texel[1] * weight;
    sum[2] += light->scale[2] * texel[2] * weight;
  }
}

/* Early-outs, lobe, the count of samples in the lobe and the path (header);
 * `n` receives the unit normal, `grid` the lobe grid on that path. */
/* Sample j's terms at receiver P with unit normal n and reflection r: the
 * transfer T_j, r . d and |d|^2 (d = y_j - P); 0 when it sends nothing
 * along the lobe's half-space (T_j <= 0 or r . d <= 0). The sample loops of
 * the classification and the sum share it, in this order. */
static int al_sample_in_front(const mrgi_area_light_uniforms* light,
                              const mrgi_area_light_sample* sample, const float position[3],
                              const float n[3], const float r[3], float* transfer, float* rw,
                              float* r2)
{
  const float d[3] = { sample->position[0] - position[0], sample->position[1] - position[1],
                       sample->position[2] - position[2] };
  *transfer = al_transfer(light, d, sample->normal, sample->area, n, r2);
  *rw = al_dotf(r, d);
  return *transfer > 0.0f && *rw > 0.0f;
}

static void al_specular_classify(const mrgi_area_light_uniforms* light,
                                 const mrgi_area_light_sample* samples, int32_t count,
                                 const float position[3], const float normal[3],
                                 const float view[3], float power, float n[3],
                                 mrgi_area_light_lobe_grid* grid,
                                 mrgi_area_light_specular_info* info)
{
  memset(info, 0, sizeof(*info));
  float v[3];
  if (!al_normalizef(normal, n) || !al_normalizef(view, v))
  {
    info->path = MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY;
    return;
  }
  if (al_culled_behind(light, position))
  {
    info->path = MRGI_AREA_LIGHT_SPECULAR_BEHIND;
    return;
  }
  if (al_culled_facing(light, position, n))
  {
    info->path = MRGI_AREA_LIGHT_SPECULAR_FACING_AWAY;
    return;
  }
  mrgi_area_light_phong_lobe(light, position, n, v, power, &info->lobe);
  if (!(info->lobe.peak >= MRGI_AREA_LIGHT_LOBE_DISCARD))
  {
    info->path = MRGI_AREA_LIGHT_SPECULAR_LOBE_MISS;
    return;
  }
  /* Every sample inside the half-maximum cone counts, visible or not. */
  const float* r = info->lobe.reflect;
  for (int32_t j = 0; j < count; ++j)
  {
    float transfer, rw, r2;
    if (!al_sample_in_front(light, samples + j, position, n, r, &transfer, &rw, &r2))
    {
      continue;
    }
    if (powf(rw / sqrtf(r2), power) >= MRGI_AREA_LIGHT_LOBE_CUTOFF)
    {
      ++info->samples_in_lobe;
    }
  }
  info->path = MRGI_AREA_LIGHT_SPECULAR_SAMPLES;
  if (info->samples_in_lobe < MRGI_AREA_LIGHT_LOBE_MIN_SAMPLES && info->lobe.reaches_plane &&
      mrgi_area_light_lobe_grid_cells(light, &info->lobe, grid))
  {
    info->path = MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID;
    info->grid_cells = grid->cells;
  }
}

void mrgi_area_light_specular_classify(const mrgi_area_light_uniforms* light,
                                       const mrgi_area_light_sample* samples, int32_t count,
                                       const float position[3], const float normal[3],
                                       const float view[3], float power,
                                       mrgi_area_light_specular_info* info)
{
  float n[3];
  mrgi_area_light_lobe_grid grid;
  al_specular_classify(light, samples, count, position, normal, view, power, n, &grid, info);
}

void mrgi_area_light_specular_visible(const mrgi_area_light_uniforms* light,
                                      const mrgi_area_light_sample* samples, int32_t count,
                                      const mrgi_area_light_texture_pyramid* pyramid,
                                      const float position[3], const float normal[3],
                                      const float view[3], float power, const uint32_t* sample_mask,
                                      const float* query_visibility, float out[3],
                                      mrgi_area_light_specular_info* info)
{
  mrgi_area_light_specular_info local;
  mrgi_area_light_lobe_grid grid;
  float n[3];
  al_specular_classify(light, samples, count, position, normal, view, power, n, &grid, &local);
  out[0] = out[1] = out[2] = 0.0f;
  /* Normalised Phong: (n + 2) / (2 pi) times the pi of cos dw = pi T. */
  const float normalisation = 0.5f * (power + 2.0f);
  const float* r = local.lobe.reflect;
  float sum[3] = { 0.0f, 0.0f, 0.0f };
  if (local.path == MRGI_AREA_LIGHT_SPECULAR_LOBE_GRID)
  {
    al_lobe_grid_sum(light, pyramid, position, n, r, &grid, power, normalisation,
                     query_visibility, sum);
  }
  else if (local.path == MRGI_AREA_LIGHT_SPECULAR_SAMPLES)
  {
    for (int32_t j = 0; j < count; ++j)
    {
      float transfer, rw, r2;
      if (!al_sample_in_front(light, samples + j, position, n, r, &transfer, &rw, &r2))
      {
        continue;
      }
      if (sample_mask && !((sample_mask[j >> 5] >> (uint32_t)(j & 31)) & 1u))
      {
        continue; /* occluded */
      }
      const float weight = normalisation * powf(rw / sqrtf(r2), power) * transfer;
      sum[0] += samples[j].radiance[0] * weight;
      sum[1] += samples[j].radiance[1] * weight;
      sum[2] += samples[j].radiance[2] * weight;
    }
  }
  out[0] = sum[0];
  out[1] = sum[1];
  out[2] = sum[2];
  if (info)
  {
    *info = local;
  }
}

void mrgi_area_light_specular(const mrgi_area_light_uniforms* light,
                              const mrgi_area_light_sample* samples, int32_t count,
                              const mrgi_area_light_texture_pyramid* pyramid,
                              const float position[3], const float normal[3], const float view[3],
                              float power, float out[3], mrgi_area_light_specular_info* info)
{
  mrgi_area_light_specular_visible(light, samples, count, pyramid, position, normal, view, power,
                                   NULL, NULL, out, info);
}
