/* Rectangular area lights: validation, texture pyramid, light samples and
 * the diffuse per-receiver gather twin. The contract is in mrgi_area_light.h;
 * this file follows its order up to the diffuse gather, and
 * mrgi_area_light_specular.c holds the rest. The per-receiver functions use
 * float math only, in the order a GLSL 1.50 shader writes it. */
#include "mrgi_area_light.h"
#include "mrgi_area_light_receiver.h"

#include "mrgi_gather.h" /* MRGI_PI */

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* The record must be exactly its MRGI_AREA_LIGHT_SAMPLE_TEXELS RGBA texels, in order. */
_Static_assert(sizeof(mrgi_area_light_sample) == MRGI_AREA_LIGHT_SAMPLE_FLOATS * sizeof(float),
               "mrgi_area_light_sample must be MRGI_AREA_LIGHT_SAMPLE_FLOATS packed floats");
_Static_assert(MRGI_AREA_LIGHT_SAMPLE_FLOATS == 4 * MRGI_AREA_LIGHT_SAMPLE_TEXELS,
               "a sample texel is 4 floats");
_Static_assert(offsetof(mrgi_area_light_sample, position) ==
                 4 * MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION * sizeof(float),
               "position starts texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION");
_Static_assert(offsetof(mrgi_area_light_sample, area) ==
                 (4 * MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION + 3) * sizeof(float),
               "area is the w of texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_POSITION");
_Static_assert(offsetof(mrgi_area_light_sample, normal) ==
                 4 * MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL * sizeof(float),
               "normal starts texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_NORMAL");
_Static_assert(offsetof(mrgi_area_light_sample, radiance) ==
                 4 * MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE * sizeof(float),
               "radiance starts texel MRGI_AREA_LIGHT_SAMPLE_TEXEL_RADIANCE");
/* 1 + log2(MRGI_IMAGE_MAX_DIMENSION) levels at most. */
_Static_assert(MRGI_IMAGE_MAX_DIMENSION == 1 << (MRGI_AREA_LIGHT_MAX_LEVELS - 1),
               "MRGI_AREA_LIGHT_MAX_LEVELS must match MRGI_IMAGE_MAX_DIMENSION");

/* ---- double helpers (setup code) ---- */

static double al_dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void al_cross(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* ---- validation ---- */

static mrgi_status al_check_texture(const mrgi_image* texture, mrgi_error* err)
{
  mrgi_status status = mrgi_image_validate(texture, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "area light texture: ");
    return status;
  }
  if (texture->channels != 3 && texture->channels != 4)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light texture has %d channels; 3 (RGB) or 4 (RGBA) are needed",
                          (int)texture->channels);
  }
  for (int32_t y = 0; y < texture->height; ++y)
  {
    for (int32_t x = 0; x < texture->width; ++x)
    {
      const float* texel = mrgi_image_at(texture, x, y);
      for (int c = 0; c < 3; ++c)
      {
        if (!(isfinite(texel[c]) && texel[c] >= 0.0f))
        {
          return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                                "area light texture texel (%d, %d) channel %d = %g is not "
                                "finite and >= 0",
                                (int)x, (int)y, c, (double)texel[c]);
        }
      }
    }
  }
  return MRGI_OK;
}

mrgi_status mrgi_area_light_check(const mrgi_area_light* light, mrgi_error* err)
{
  if (!light)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "area light is NULL");
  }
  const char* names[3] = { "center", "edge_u", "edge_v" };
  const double* vectors[3] = { light->center, light->edge_u, light->edge_v };
  for (int v = 0; v < 3; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (!isfinite(vectors[v][c]))
      {
        return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                              "area light %s[%d] = %g is non-finite", names[v], c,
                              vectors[v][c]);
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!(isfinite(light->color[c]) && light->color[c] >= 0.0))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "area light color[%d] = %g is not finite and >= 0", c,
                            light->color[c]);
    }
  }
  if (!(isfinite(light->intensity) && light->intensity >= 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light intensity = %g is not finite and >= 0", light->intensity);
  }
  for (int c = 0; c < 3; ++c)
  {
    const double scale = light->intensity * light->color[c];
    if (!(scale <= FLT_MAX))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "area light intensity * color[%d] = %g exceeds the float range", c,
                            scale);
    }
  }
  const double uu = al_dot(light->edge_u, light->edge_u);
  const double vv = al_dot(light->edge_v, light->edge_v);
  if (!(uu > 0.0) || !(vv > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light %s is a zero-length edge: the light has no area",
                          !(uu > 0.0) ? "edge_u" : "edge_v");
  }
  double cross[3];
  al_cross(light->edge_u, light->edge_v, cross);
  const double area = sqrt(al_dot(cross, cross));
  if (!(area > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light edge_u and edge_v are parallel: the light has no area");
  }
  const double cosine = fabs(al_dot(light->edge_u, light->edge_v)) / sqrt(uu * vv);
  if (!(cosine <= MRGI_AREA_LIGHT_PERPENDICULAR_TOLERANCE))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light edge_u and edge_v are not perpendicular (|cos| = %g): "
                          "not a rectangle",
                          cosine);
  }
  if (!(area <= FLT_MAX) || !((float)area > 0.0f) || !(0.5 * sqrt(uu) <= FLT_MAX) ||
      !(0.5 * sqrt(vv) <= FLT_MAX))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light area |edge_u x edge_v| = %g is outside the float range",
                          area);
  }
  if (light->texture)
  {
    return al_check_texture(light->texture, err);
  }
  return MRGI_OK;
}

static double al_clamp01(double x)
{
  return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; /* NaN -> 0 */
}

void mrgi_area_light_emitted(const mrgi_area_light* light, double s, double t, double rgb[3])
{
  double texel[3] = { 1.0, 1.0, 1.0 };
  const mrgi_image* texture = light->texture;
  if (texture)
  {
    /* Column x covers s in [x/W, (x+1)/W); row y (0 = top) covers t in (1-(y+1)/H, 1-y/H]. */
    int32_t x = (int32_t)floor(al_clamp01(s) * texture->width);
    int32_t y = (int32_t)floor((1.0 - al_clamp01(t)) * texture->height);
    x = x < texture->width ? x : texture->width - 1;
    y = y < texture->height ? y : texture->height - 1;
    const float* value = mrgi_image_at(texture, x, y);
    texel[0] = value[0];
    texel[1] = value[1];
    texel[2] = value[2];
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = light->intensity * light->color[c] * texel[c];
  }
}

/* ---- texture pyramid ---- */

/* Level sizes of a W x H texture (OpenGL's mip chain); the level count. */
static int32_t al_pyramid_sizes(int32_t width, int32_t height,
                                int32_t widths[MRGI_AREA_LIGHT_MAX_LEVELS],
                                int32_t heights[MRGI_AREA_LIGHT_MAX_LEVELS])
{
  int32_t count = 0;
  int32_t w = width, h = height;
  for (;;)
  {
    widths[count] = w;
    heights[count] = h;
    ++count;
    if ((w == 1 && h == 1) || count == MRGI_AREA_LIGHT_MAX_LEVELS)
    {
      break;
    }
    w = w / 2 > 1 ? w / 2 : 1;
    h = h / 2 > 1 ? h / 2 : 1;
  }
  return count;
}

size_t mrgi_area_light_texture_pyramid_float_count(int64_t width, int64_t height)
{
  if (width < 1 || width > MRGI_IMAGE_MAX_DIMENSION || height < 1 ||
      height > MRGI_IMAGE_MAX_DIMENSION)
  {
    return 0;
  }
  int32_t widths[MRGI_AREA_LIGHT_MAX_LEVELS], heights[MRGI_AREA_LIGHT_MAX_LEVELS];
  const int32_t levels = al_pyramid_sizes((int32_t)width, (int32_t)height, widths, heights);
  size_t total = 0;
  for (int32_t k = 0; k < levels; ++k)
  {
    total += 3 * (size_t)widths[k] * (size_t)heights[k];
  }
  return total;
}

/* Fraction of source texel i (covering [i, i+1)) inside [lo, hi). */
static double al_overlap(int32_t i, double lo, double hi)
{
  const double a = lo > (double)i ? lo : (double)i;
  const double b = hi < (double)(i + 1) ? hi : (double)(i + 1);
  return b > a ? b - a : 0.0;
}

/* Level k+1 from level k: exact box average over each texel's footprint. */
static void al_pyramid_reduce(const float* src, int32_t w0, int32_t h0, float* dst, int32_t w1,
                              int32_t h1)
{
  const double rx = (double)w0 / (double)w1, ry = (double)h0 / (double)h1;
  const double norm = 1.0 / (rx * ry);
  for (int32_t y = 0; y < h1; ++y)
  {
    const double lo_y = y * ry, hi_y = (y + 1) * ry;
    int32_t j1 = (int32_t)ceil(hi_y);
    j1 = j1 < h0 ? j1 : h0;
    for (int32_t x = 0; x < w1; ++x)
    {
      const double lo_x = x * rx, hi_x = (x + 1) * rx;
      int32_t i1 = (int32_t)ceil(hi_x);
      i1 = i1 < w0 ? i1 : w0;
      double sum[3] = { 0.0, 0.0, 0.0 };
      for (int32_t j = (int32_t)floor(lo_y); j < j1; ++j)
      {
        const double wy = al_overlap(j, lo_y, hi_y);
        for (int32_t i = (int32_t)floor(lo_x); i < i1; ++i)
        {
          const double weight = wy * al_overlap(i, lo_x, hi_x);
          const float* texel = src + 3 * ((size_t)j * (size_t)w0 + (size_t)i);
          sum[0] += weight * texel[0];
          sum[1] += weight * texel[1];
          sum[2] += weight * texel[2];
        }
      }
      float* out = dst + 3 * ((size_t)y * (size_t)w1 + (size_t)x);
      out[0] = (float)(sum[0] * norm);
      out[1] = (float)(sum[1] * norm);
      out[2] = (float)(sum[2] * norm);
    }
  }
}

mrgi_status mrgi_area_light_texture_pyramid_init(mrgi_area_light_texture_pyramid* out,
                                                 const mrgi_image* texture, float* storage,
                                                 size_t storage_count, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "texture pyramid output is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (!storage)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "texture pyramid storage is NULL");
  }
  if (texture)
  {
    const mrgi_status status = al_check_texture(texture, err);
    if (status != MRGI_OK)
    {
      return status;
    }
  }
  const int32_t width = texture ? texture->width : 1;
  const int32_t height = texture ? texture->height : 1;
  const size_t needed = mrgi_area_light_texture_pyramid_float_count(width, height);
  if (storage_count < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "texture pyramid storage holds %zu floats but a %dx%d texture needs %zu "
                          "(mrgi_area_light_texture_pyramid_float_count())",
                          storage_count, (int)width, (int)height, needed);
  }
  mrgi_area_light_texture_pyramid p;
  memset(&p, 0, sizeof(p));
  p.level_count = al_pyramid_sizes(width, height, p.width, p.height);
  size_t offset = 0;
  for (int32_t k = 0; k < p.level_count; ++k)
  {
    p.offset[k] = offset;
    offset += 3 * (size_t)p.width[k] * (size_t)p.height[k];
  }
  p.texels = storage;
  p.float_count = offset;
  if (texture)
  {
    for (int32_t y = 0; y < height; ++y)
    {
      for (int32_t x = 0; x < width; ++x)
      {
        memcpy(storage + 3 * ((size_t)y * (size_t)width + (size_t)x), mrgi_image_at(texture, x, y),
               3 * sizeof(float));
      }
    }
  }
  else
  {
    storage[0] = storage[1] = storage[2] = 1.0f;
  }
  for (int32_t k = 0; k + 1 < p.level_count; ++k)
  {
    al_pyramid_reduce(storage + p.offset[k], p.width[k], p.height[k], storage + p.offset[k + 1],
                      p.width[k + 1], p.height[k + 1]);
  }
  *out = p;
  return MRGI_OK;
}

mrgi_status mrgi_area_light_texture_pyramid_create(mrgi_area_light_texture_pyramid* out,
                                                   const mrgi_image* texture, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "texture pyramid output is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (texture)
  {
    const mrgi_status status = al_check_texture(texture, err);
    if (status != MRGI_OK)
    {
      return status;
    }
  }
  const size_t count = mrgi_area_light_texture_pyramid_float_count(texture ? texture->width : 1,
                                                                   texture ? texture->height : 1);
  float* storage = (float*)malloc(count * sizeof(float));
  if (!storage)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "cannot allocate %zu floats for a texture pyramid", count);
  }
  const mrgi_status status = mrgi_area_light_texture_pyramid_init(out, texture, storage, count, err);
  if (status != MRGI_OK)
  {
    free(storage);
    return status;
  }
  out->owned = 1;
  return MRGI_OK;
}

void mrgi_area_light_texture_pyramid_destroy(mrgi_area_light_texture_pyramid* pyramid)
{
  if (!pyramid)
  {
    return;
  }
  if (pyramid->owned)
  {
    free(pyramid->texels);
  }
  memset(pyramid, 0, sizeof(*pyramid));
}

static int32_t al_clampi(int32_t value, int32_t lo, int32_t hi)
{
  return value < lo ? lo : (value > hi ? hi : value);
}

/* Bilinear read of one level at GL coordinates (s, t_gl): texel centres at
 * (x + 1/2) / W, clamp to edge (OpenGL 3.2 core, 3.8.8). */
static void al_bilinear(const mrgi_area_light_texture_pyramid* pyramid, int32_t level, float s,
                        float t_gl, float rgb[3])
{
  const int32_t w = pyramid->width[level], h = pyramid->height[level];
  const float* base = pyramid->texels + pyramid->offset[level];
  /* Clamped before floor so that the int conversion is always defined. */
  const float x = fminf(fmaxf(s * (float)w - 0.5f, -1.0f), (float)w);
  const float y = fminf(fmaxf(t_gl * (float)h - 0.5f, -1.0f), (float)h);
  const float x0f = floorf(x), y0f = floorf(y);
  const float fx = x - x0f, fy = y - y0f;
  const int32_t x0 = al_clampi((int32_t)x0f, 0, w - 1), x1 = al_clampi((int32_t)x0f + 1, 0, w - 1);
  const int32_t y0 = al_clampi((int32_t)y0f, 0, h - 1), y1 = al_clampi((int32_t)y0f + 1, 0, h - 1);
  const float* t00 = base + 3 * ((size_t)y0 * (size_t)w + (size_t)x0);
  const float* t10 = base + 3 * ((size_t)y0 * (size_t)w + (size_t)x1);
  const float* t01 = base + 3 * ((size_t)y1 * (size_t)w + (size_t)x0);
  const float* t11 = base + 3 * ((size_t)y1 * (size_t)w + (size_t)x1);
  for (int c = 0; c < 3; ++c)
  {
    /* GLSL: mix(mix(t00, t10, fx), mix(t01, t11, fx), fy) */
    const float bottom = t00[c] * (1.0f - fx) + t10[c] * fx;
    const float top = t01[c] * (1.0f - fx) + t11[c] * fx;
    rgb[c] = bottom * (1.0f - fy) + top * fy;
  }
}

void mrgi_area_light_texture_sample(const mrgi_area_light_texture_pyramid* pyramid, float s,
                                    float t, float lod, float rgb[3])
{
  const float last = (float)(pyramid->level_count - 1);
  const float l = lod > 0.0f ? (lod < last ? lod : last) : 0.0f; /* NaN -> 0 */
  const float k0f = floorf(l);
  const int32_t k0 = (int32_t)k0f;
  const int32_t k1 = k0 + 1 < pyramid->level_count ? k0 + 1 : k0;
  const float f = l - k0f;
  const float t_gl = 1.0f - t; /* GL's first row is the picture's top row */
  float a[3], b[3];
  al_bilinear(pyramid, k0, s, t_gl, a);
  al_bilinear(pyramid, k1, s, t_gl, b);
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = a[c] * (1.0f - f) + b[c] * f;
  }
}

/* Whether `pyramid` may stand for light->texture (see the header). */
static mrgi_status al_check_pyramid(const mrgi_area_light* light,
                                    const mrgi_area_light_texture_pyramid* pyramid,
                                    mrgi_error* err)
{
  if (light->texture)
  {
    if (!pyramid)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "the area light has a texture but no texture pyramid was given");
    }
    if (pyramid->level_count < 1 || !pyramid->texels || pyramid->width[0] != light->texture->width ||
        pyramid->height[0] != light->texture->height)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "texture pyramid (%dx%d, %d levels) is not the pyramid of the area "
                            "light's %dx%d texture",
                            (int)pyramid->width[0], (int)pyramid->height[0],
                            (int)pyramid->level_count, (int)light->texture->width,
                            (int)light->texture->height);
    }
    return MRGI_OK;
  }
  if (pyramid && (pyramid->level_count != 1 || !pyramid->texels || pyramid->width[0] != 1 ||
                  pyramid->height[0] != 1))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "the area light has no texture: its pyramid must be NULL or the 1x1 "
                          "one of mrgi_area_light_texture_pyramid_create(NULL), not %dx%d",
                          (int)pyramid->width[0], (int)pyramid->height[0]);
  }
  return MRGI_OK;
}

/* ---- light samples ---- */

static mrgi_status al_layout(const mrgi_area_light* light, int32_t requested_count, int32_t* sx,
                             int32_t* sy, mrgi_error* err)
{
  if (requested_count < MRGI_AREA_LIGHT_MIN_SAMPLES ||
      requested_count > MRGI_AREA_LIGHT_MAX_SAMPLES)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light sample count %d is outside %d..%d", (int)requested_count,
                          MRGI_AREA_LIGHT_MIN_SAMPLES, MRGI_AREA_LIGHT_MAX_SAMPLES);
  }
  const double length_u = sqrt(al_dot(light->edge_u, light->edge_u));
  const double length_v = sqrt(al_dot(light->edge_v, light->edge_v));
  const double ideal = floor(sqrt((double)requested_count * length_u / length_v) + 0.5);
  const int32_t x = ideal < 1.0 ? 1 : (ideal > requested_count ? requested_count : (int32_t)ideal);
  const int32_t y = requested_count / x > 1 ? requested_count / x : 1;
  *sx = x;
  *sy = y;
  return MRGI_OK;
}

mrgi_status mrgi_area_light_sample_layout(const mrgi_area_light* light, int32_t requested_count,
                                          int32_t* out_sx, int32_t* out_sy, int32_t* out_count,
                                          mrgi_error* err)
{
  mrgi_status status = mrgi_area_light_check(light, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  int32_t sx = 0, sy = 0;
  status = al_layout(light, requested_count, &sx, &sy, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (out_sx)
  {
    *out_sx = sx;
  }
  if (out_sy)
  {
    *out_sy = sy;
  }
  if (out_count)
  {
    *out_count = sx * sy;
  }
  return MRGI_OK;
}

/* SplitMix64 (Steele, Lea and Flood 2014), as a stream: uniform in [0, 1). */
static double al_random(uint64_t* state)
{
  *state += 0x9E3779B97F4A7C15ull;
  uint64_t z = *state;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

mrgi_status mrgi_area_light_make_samples(const mrgi_area_light* light,
                                         const mrgi_area_light_texture_pyramid* pyramid,
                                         int32_t requested_count, int32_t jitter, uint64_t seed,
                                         mrgi_area_light_sample* samples, int32_t capacity,
                                         int32_t* out_count, mrgi_error* err)
{
  int32_t sx = 0, sy = 0, count = 0;
  mrgi_status status = mrgi_area_light_sample_layout(light, requested_count, &sx, &sy, &count, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = al_check_pyramid(light, pyramid, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (jitter != 0 && jitter != 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "area light jitter flag %d is not 0 or 1",
                          (int)jitter);
  }
  if (!samples)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "area light sample array is NULL");
  }
  if (capacity < count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "area light sample capacity %d is below the %d samples (%d x %d) of "
                          "the request",
                          (int)capacity, (int)count, (int)sx, (int)sy);
  }
  double normal[3];
  al_cross(light->edge_u, light->edge_v, normal);
  const double area = sqrt(al_dot(normal, normal));
  for (int k = 0; k < 3; ++k)
  {
    normal[k] /= area;
  }
  const float cell_area = (float)(area / ((double)sx * (double)sy));
  const int32_t texture_width = pyramid ? pyramid->width[0] : 1;
  const int32_t texture_height = pyramid ? pyramid->height[0] : 1;
  /* The level whose texel footprint matches a cell (as GLSL would compute it). */
  const float lod = log2f(fmaxf((float)texture_width / (float)sx, (float)texture_height / (float)sy));
  uint64_t state = seed;
  for (int32_t j = 0; j < sy; ++j)
  {
    for (int32_t i = 0; i < sx; ++i)
    {
      mrgi_area_light_sample* sample = samples + (size_t)j * (size_t)sx + (size_t)i;
      memset(sample, 0, sizeof(*sample));
      const double ju = jitter ? al_random(&state) : 0.5;
      const double jv = jitter ? al_random(&state) : 0.5;
      const double a = ((double)i + ju) / (double)sx - 0.5;
      const double b = ((double)j + jv) / (double)sy - 0.5;
      for (int k = 0; k < 3; ++k)
      {
        sample->position[k] =
          (float)(light->center[k] + a * light->edge_u[k] + b * light->edge_v[k]);
        sample->normal[k] = (float)normal[k];
      }
      sample->area = cell_area;
      float texel[3] = { 1.0f, 1.0f, 1.0f };
      if (pyramid)
      {
        const float s = ((float)i + 0.5f) / (float)sx;
        const float t = ((float)j + 0.5f) / (float)sy;
        mrgi_area_light_texture_sample(pyramid, s, t, lod, texel);
      }
      for (int c = 0; c < 3; ++c)
      {
        sample->radiance[c] = (float)(light->intensity * light->color[c] * (double)texel[c]);
      }
    }
  }
  if (out_count)
  {
    *out_count = count;
  }
  return MRGI_OK;
}

/* ---- per-receiver functions ---- */

mrgi_status mrgi_area_light_uniforms_init(const mrgi_area_light* light,
                                          const mrgi_area_light_texture_pyramid* pyramid,
                                          mrgi_area_light_uniforms* out, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "area light uniforms output is NULL");
  }
  mrgi_status status = mrgi_area_light_check(light, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = al_check_pyramid(light, pyramid, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  mrgi_area_light_uniforms u;
  memset(&u, 0, sizeof(u));
  double normal[3];
  al_cross(light->edge_u, light->edge_v, normal);
  const double area = sqrt(al_dot(normal, normal));
  const double length_u = sqrt(al_dot(light->edge_u, light->edge_u));
  const double length_v = sqrt(al_dot(light->edge_v, light->edge_v));
  static const double corner_signs[4][2] = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
  for (int k = 0; k < 3; ++k)
  {
    u.center[k] = (float)light->center[k];
    u.normal[k] = (float)(normal[k] / area);
    u.axis_u[k] = (float)(light->edge_u[k] / length_u);
    u.axis_v[k] = (float)(light->edge_v[k] / length_v);
    u.scale[k] = (float)(light->intensity * light->color[k]);
    for (int c = 0; c < 4; ++c)
    {
      u.corners[c][k] = (float)(light->center[k] + 0.5 * corner_signs[c][0] * light->edge_u[k] +
                                0.5 * corner_signs[c][1] * light->edge_v[k]);
    }
  }
  u.half_u = (float)(0.5 * length_u);
  u.half_v = (float)(0.5 * length_v);
  u.area = (float)area;
  u.two_sided = light->two_sided ? 1 : 0;
  u.texture_width = pyramid ? pyramid->width[0] : 1;
  u.texture_height = pyramid ? pyramid->height[0] : 1;
  u.texture_levels = pyramid ? pyramid->level_count : 1;
  *out = u;
  return MRGI_OK;
}


void mrgi_area_light_diffuse(const mrgi_area_light_uniforms* light,
                             const mrgi_area_light_sample* samples, int32_t count,
                             const float position[3], const float normal[3], float out[3])
{
  out[0] = out[1] = out[2] = 0.0f;
  float n[3];
  if (!al_normalizef(normal, n) || al_culled_behind(light, position) ||
      al_culled_facing(light, position, n))
  {
    return;
  }
  float sum[3] = { 0.0f, 0.0f, 0.0f };
  for (int32_t j = 0; j < count; ++j)
  {
    const mrgi_area_light_sample* sample = samples + j;
    const float d[3] = { sample->position[0] - position[0], sample->position[1] - position[1],
                         sample->position[2] - position[2] };
    float r2;
    const float transfer = al_transfer(light, d, sample->normal, sample->area, n, &r2);
    sum[0] += sample->radiance[0] * transfer;
    sum[1] += sample->radiance[1] * transfer;
    sum[2] += sample->radiance[2] * transfer;
  }
  out[0] = sum[0];
  out[1] = sum[1];
  out[2] = sum[2];
}

