#include "mrgi_ssgi.h"

#include "mrgi_buffers.h"
#include "mrgi_finite.h"

#include <float.h>
#include <math.h>
#include <string.h>

static double mrgi_ssgi_radical_inverse(uint32_t m, uint32_t base)
{
  double inv = 1.0 / (double)base, f = inv, r = 0.0;
  while (m > 0u)
  {
    r += (double)(m % base) * f;
    m /= base;
    f *= inv;
  }
  return r;
}

mrgi_status mrgi_ssgi_kernel(int32_t count, float* out, mrgi_error* err)
{
  if (count < 1 || count > MRGI_SSGI_MAX_SAMPLES || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "SSGI kernel: sample count %d is outside 1..%d (or no output)", (int)count,
      MRGI_SSGI_MAX_SAMPLES);
  }
  const double pi = 3.14159265358979323846;
  for (int32_t i = 0; i < count; ++i)
  {
    const double c = mrgi_ssgi_radical_inverse((uint32_t)i + 1u, 2u);
    const double phi = 2.0 * pi * mrgi_ssgi_radical_inverse((uint32_t)i + 1u, 3u);
    const double s = cbrt(((double)i + 0.5) / (double)count);
    const double sn = sqrt(1.0 - c * c);
    out[3 * i] = (float)(s * sn * cos(phi));
    out[3 * i + 1] = (float)(s * sn * sin(phi));
    out[3 * i + 2] = (float)(s * c);
  }
  return MRGI_OK;
}

mrgi_status mrgi_ssgi_params_validate(const mrgi_ssgi_params* params, mrgi_error* err)
{
  if (!params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSGI: no parameters");
  }
  if (params->sample_count < 1 || params->sample_count > MRGI_SSGI_MAX_SAMPLES || !params->kernel)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "SSGI: sample count %d is outside 1..%d (or no kernel)", (int)params->sample_count,
      MRGI_SSGI_MAX_SAMPLES);
  }
  if (!mrgi_floats_finite(params->kernel, 3 * (size_t)params->sample_count))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "SSGI: the kernel holds a non-finite value");
  }
  for (int32_t i = 0; i < params->sample_count; ++i)
  {
    if (!(params->kernel[3 * i + 2] > 0.0f))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "SSGI: kernel sample %d is not above the tangent plane (z <= 0)", (int)i);
    }
  }
  if (!(params->radius > 0.0f) || !isfinite(params->radius))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSGI: radius %g must be finite and > 0",
      (double)params->radius);
  }
  if (!(params->bias >= 0.0f) || !isfinite(params->bias))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSGI: bias %g must be finite and >= 0",
      (double)params->bias);
  }
  if (!mrgi_floats_finite(params->projection, 16))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSGI: the projection is not finite");
  }
  return MRGI_OK;
}

/* GLSL's mat4 * vec4(v, 1), column-major, summed in GLSL's order. */
static void mrgi_ssgi_project(const float m[16], const float v[3], float out[4])
{
  for (int r = 0; r < 4; ++r)
  {
    out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r];
  }
}

/* Texel of coordinate u in [0, 1) over n texels, or -1 off screen; `margin`
 * takes the distance of u n to the nearest texel edge (borders included). */
static int32_t mrgi_ssgi_texel(float u, int32_t n, float* margin)
{
  const float f = u * (float)n;
  const float nearest = roundf(f);
  if (fabsf(f - nearest) < *margin)
  {
    *margin = fabsf(f - nearest);
  }
  if (!(f >= 0.0f) || !(f < (float)n))
  {
    return -1;
  }
  const int32_t t = (int32_t)floorf(f);
  return t < n ? t : n - 1;
}

static float mrgi_ssgi_dot(const float a[3], const float b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void mrgi_ssgi_receiver(const mrgi_ssgi_params* params, const mrgi_image* position,
  const mrgi_image* normal, const mrgi_image* direct, const float eye_position[3],
  const float normal_vector[3], const float albedo[3], mrgi_ssgi_result* out)
{
  memset(out, 0, sizeof(*out));
  out->visibility = 1.0f;
  out->margin = FLT_MAX;
  const float* p = eye_position;
  if (!mrgi_floats_finite(p, 3) || !mrgi_floats_finite(normal_vector, 3) ||
    !mrgi_floats_finite(albedo, 3))
  {
    return;
  }
  const float n2 = mrgi_ssgi_dot(normal_vector, normal_vector);
  if (!(n2 > 0.0f) || !isfinite(n2))
  {
    return; /* no normal: no hemisphere */
  }
  const float ninv = 1.0f / sqrtf(n2);
  const float n[3] = { normal_vector[0] * ninv, normal_vector[1] * ninv, normal_vector[2] * ninv };
  /* Duff et al. 2017: an orthonormal basis continuous except across n.z = 0. */
  const float sg = n[2] >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sg + n[2]);
  const float bb = n[0] * n[1] * a;
  const float t[3] = { 1.0f + sg * n[0] * n[0] * a, sg * bb, -sg * n[0] };
  const float b[3] = { bb, sg + n[1] * n[1] * a, -n[1] };

  const int32_t w = position->width, h = position->height;
  const int32_t count = params->sample_count;
  const float r = params->radius;
  const float range = (float)MRGI_SSGI_RANGE * r;
  const float area = r * r / (float)count; /* A / pi, A = pi R^2 / N */
  float total = 0.0f;
  for (int32_t i = 0; i < count; ++i)
  {
    const float* k = params->kernel + 3 * i;
    total += k[2] / sqrtf(mrgi_ssgi_dot(k, k));
  }
  float m = FLT_MAX;
  float blocked = 0.0f;
  float x[3] = { 0.0f, 0.0f, 0.0f };
  for (int32_t i = 0; i < count; ++i)
  {
    const float* k = params->kernel + 3 * i;
    const float c = k[2] / sqrtf(mrgi_ssgi_dot(k, k)) / total;
    float s[3];
    for (int j = 0; j < 3; ++j)
    {
      s[j] = p[j] + (t[j] * k[0] + b[j] * k[1] + n[j] * k[2]) * r;
    }
    float sc[4];
    mrgi_ssgi_project(params->projection, s, sc);
    const float u = sc[0] / sc[3] * 0.5f + 0.5f;
    const float v = sc[1] / sc[3] * 0.5f + 0.5f;
    const int32_t qx = mrgi_ssgi_texel(u, w, &m);
    const int32_t qy = mrgi_ssgi_texel(v, h, &m);
    if (qx < 0 || qy < 0 || !(sc[3] > 0.0f))
    {
      continue; /* off screen or behind the eye: unknown, taken as open */
    }
    const float* q = mrgi_image_at(position, qx, qy);
    if (!(q[3] > MRGI_GBUFFER_VALID_THRESHOLD) || !mrgi_floats_finite(q, 3))
    {
      continue; /* the background neither blocks nor sends */
    }
    const float limit = s[2] + params->bias;
    m = fminf(m, fabsf(q[2] - limit) / fmaxf(fabsf(s[2]), 1e-30f));
    const float dv[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
    const float d2 = mrgi_ssgi_dot(dv, dv);
    const float d = sqrtf(d2);
    m = fminf(m, fabsf(d - range) / range);
    const float height = mrgi_ssgi_dot(n, dv);
    m = fminf(m, fabsf(height - params->bias) / r);
    if (!(q[2] >= limit) || !(d <= range) || !(height > params->bias))
    {
      /* In front of the depth buffer, a far foreground, or a pixel of the
       * receiver's own plane (at grazing angles a pixel's footprint is
       * longer than the bias, and would block itself). */
      continue;
    }
    blocked += c;
    const float* nq = mrgi_image_at(normal, qx, qy);
    const float* lq = mrgi_image_at(direct, qx, qy);
    if (!(d > 0.0f) || !mrgi_floats_finite(nq, 3) || !mrgi_floats_finite(lq, 3))
    {
      continue; /* blocks, but cannot send */
    }
    const float cr = fmaxf(0.0f, mrgi_ssgi_dot(n, dv) / d);
    const float cs = fmaxf(0.0f, -mrgi_ssgi_dot(nq, dv) / d);
    const float f = fminf(area * cr * cs / (d2 + area), c);
    for (int j = 0; j < 3; ++j)
    {
      x[j] += f * lq[j];
    }
  }
  const float vis = 1.0f - blocked;
  out->visibility = vis < 0.0f ? 0.0f : (vis > 1.0f ? 1.0f : vis);
  for (int j = 0; j < 3; ++j)
  {
    out->irradiance[j] = x[j];
    out->radiance[j] = albedo[j] * x[j];
  }
  out->margin = m;
}

static mrgi_status mrgi_ssgi_check_image(const mrgi_image* img, const mrgi_image* like,
  int32_t channels, const char* name, mrgi_error* err)
{
  if (mrgi_image_validate(img, err) != MRGI_OK || img->width != like->width ||
    img->height != like->height || img->channels < channels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "SSGI: the %s image must be a valid %dx%d image of >= %d channels", name, (int)like->width,
      (int)like->height, (int)channels);
  }
  return MRGI_OK;
}

mrgi_status mrgi_ssgi_compute(const mrgi_ssgi_params* params, const mrgi_image* position,
  const mrgi_image* normal, const mrgi_image* albedo, const mrgi_image* direct, int32_t level,
  mrgi_image* out, mrgi_error* err)
{
  if (out)
  {
    memset(out, 0, sizeof(*out));
  }
  mrgi_status status = mrgi_ssgi_params_validate(params, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!out || !position || mrgi_image_validate(position, err) != MRGI_OK || position->channels != 4)
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "SSGI: invalid position image (4 channels) or no output");
  }
  if (!normal || !albedo || !direct ||
    (status = mrgi_ssgi_check_image(normal, position, 3, "normal", err)) != MRGI_OK ||
    (status = mrgi_ssgi_check_image(albedo, position, 3, "albedo", err)) != MRGI_OK ||
    (status = mrgi_ssgi_check_image(direct, position, 3, "direct", err)) != MRGI_OK)
  {
    return status != MRGI_OK ? status
                             : mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                                 "SSGI: missing normal, albedo or direct image");
  }
  if (level < 0 || level > MRGI_SSGI_MAX_LEVEL)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSGI: level %d is outside 0..%d",
      (int)level, MRGI_SSGI_MAX_LEVEL);
  }
  const int32_t side = (int32_t)1 << level;
  const int32_t centre = side / 2;
  const int32_t w = (position->width + side - 1) / side;
  const int32_t h = (position->height + side - 1) / side;
  status = mrgi_image_create(out, w, h, MRGI_SSGI_CHANNELS, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  for (int32_t j = 0; j < h; ++j)
  {
    for (int32_t i = 0; i < w; ++i)
    {
      int32_t x = i * side + centre, y = j * side + centre;
      x = x < position->width ? x : position->width - 1;
      y = y < position->height ? y : position->height - 1;
      float* o = mrgi_image_at(out, i, j);
      mrgi_ssgi_result res;
      const float* p = mrgi_image_at(position, x, y);
      if (p[3] > MRGI_GBUFFER_VALID_THRESHOLD)
      {
        mrgi_ssgi_receiver(params, position, normal, direct, p, mrgi_image_at(normal, x, y),
          mrgi_image_at(albedo, x, y), &res);
      }
      else
      {
        memset(&res, 0, sizeof(res));
        res.visibility = 1.0f;
        res.margin = FLT_MAX;
      }
      o[0] = res.radiance[0];
      o[1] = res.radiance[1];
      o[2] = res.radiance[2];
      o[3] = res.visibility;
      o[4] = res.margin;
    }
  }
  return MRGI_OK;
}
