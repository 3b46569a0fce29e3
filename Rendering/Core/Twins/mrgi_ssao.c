#include "mrgi_ssao.h"

#include "mrgi_buffers.h"
#include "mrgi_finite.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* libstdc++'s std::minstd_rand0 (std::default_random_engine): Park-Miller. */
static uint32_t mrgi_ssao_minstd_next(uint32_t* state)
{
  *state = (uint32_t)(((uint64_t)*state * 16807u) % 2147483647u);
  return *state;
}

/*
 * std::uniform_real_distribution<float>(0, 1) over minstd_rand0 in libstdc++:
 * generate_canonical<float, 24> takes one draw (the engine gives 31 bits),
 * (float)(x - min) / (float)(max - min + 1), the divisor 2147483646 rounding
 * to 2^31 in float; a result that rounds to 1 becomes the float below 1.
 */
static float mrgi_ssao_uniform(uint32_t* state)
{
  const float x = (float)(mrgi_ssao_minstd_next(state) - 1u);
  float u = x / 2147483648.0f;
  if (u >= 1.0f)
  {
    u = nextafterf(1.0f, 0.0f);
  }
  return u * (1.0f - 0.0f) + 0.0f;
}

mrgi_status mrgi_ssao_kernel(int32_t size, float* out, mrgi_error* err)
{
  if (size < 1 || size > MRGI_SSAO_MAX_KERNEL_SIZE || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "SSAO kernel: size %d is outside 1..%d (or no output)", (int)size, MRGI_SSAO_MAX_KERNEL_SIZE);
  }
  uint32_t state = 1u; /* a default-constructed engine */
  for (int32_t i = 0; i < size;)
  {
    /* The three draws in the order of the initializer list (C++ evaluates
     * braced initializers left to right). */
    float s[3];
    s[0] = mrgi_ssao_uniform(&state) * 2.f - 1.f;
    s[1] = mrgi_ssao_uniform(&state) * 2.f - 1.f;
    s[2] = mrgi_ssao_uniform(&state);
    /* vtkMath::Norm(const float*): the sum in float, then sqrt. */
    const float norm = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    if ((double)norm > 1.0)
    {
      continue; /* outside the unit ball: drawn again for the same i */
    }
    float scale = (float)i / (float)size;
    scale = 0.1f + 0.9f * scale * scale;
    out[3 * i] = s[0] * scale;
    out[3 * i + 1] = s[1] * scale;
    out[3 * i + 2] = s[2] * scale;
    ++i;
  }
  return MRGI_OK;
}

mrgi_status mrgi_ssao_params_validate(const mrgi_ssao_params* params, mrgi_error* err)
{
  if (!params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: no parameters");
  }
  if (params->kernel_size < 1 || params->kernel_size > MRGI_SSAO_MAX_KERNEL_SIZE || !params->kernel)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "SSAO: kernel size %d is outside 1..%d (or no kernel)", (int)params->kernel_size,
      MRGI_SSAO_MAX_KERNEL_SIZE);
  }
  if (!mrgi_floats_finite(params->kernel, 3 * (size_t)params->kernel_size))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: the kernel holds a non-finite value");
  }
  if (!(params->radius > 0.0f) || !isfinite(params->radius))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: radius %g must be finite and > 0",
      (double)params->radius);
  }
  if (!isfinite(params->bias))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: bias must be finite");
  }
  if (!mrgi_floats_finite(params->projection, 16))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: the projection is not finite");
  }
  if (!params->noise ||
    !mrgi_floats_finite(params->noise, (size_t)MRGI_SSAO_NOISE_SIZE * MRGI_SSAO_NOISE_SIZE))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: no noise tile, or a non-finite one");
  }
  return MRGI_OK;
}

/* GLSL's mat4 * vec4(v, 1) for a column-major m, summed in GLSL's order. */
static void mrgi_ssao_project(const float m[16], const float v[3], float out[4])
{
  for (int r = 0; r < 4; ++r)
  {
    out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r];
  }
}

static float mrgi_ssao_smoothstep01(float x)
{
  const float t = x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
  return t * t * (3.0f - 2.0f * t);
}

/* floor(u * n) clamped to [0, n - 1], NaN to 0 (clamp to edge, nearest);
 * `margin` takes the distance to the nearest inner texel edge. */
static int32_t mrgi_ssao_texel(float u, int32_t n, float* margin)
{
  const float f = u * (float)n;
  const float nearest = roundf(f);
  if (nearest >= 1.0f && nearest <= (float)(n - 1) && fabsf(f - nearest) < *margin)
  {
    *margin = fabsf(f - nearest);
  }
  if (!(f >= 1.0f))
  {
    return 0;
  }
  if (f >= (float)(n - 1))
  {
    return n - 1;
  }
  return (int32_t)floorf(f);
}

float mrgi_ssao_receiver(const mrgi_ssao_params* params, const mrgi_image* position,
  const mrgi_image* normal, int32_t x, int32_t y, float* margin)
{
  float m = FLT_MAX;
  if (margin)
  {
    *margin = FLT_MAX;
  }
  const float* p = mrgi_image_at(position, x, y);
  const float* nv = mrgi_image_at(normal, x, y);
  if (!(p[3] > MRGI_GBUFFER_VALID_THRESHOLD) || !mrgi_floats_finite(p, 3) ||
    !mrgi_floats_finite(nv, 3) || !(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2] > 0.0f))
  {
    return 1.0f; /* background, non-finite or zero normal: no receiver */
  }
  const int32_t w = position->width, h = position->height;
  float d[4];
  mrgi_ssao_project(params->projection, p, d);
  const float depth = d[2] / d[3] * 0.5f + 0.5f;
  if (!(depth > 0.0f && depth < 1.0f))
  {
    return 1.0f; /* vtkSSAOPass's "depth > 0 && depth < 1" */
  }
  if (params->depth)
  {
    /* vtkSSAOPass's test against its depth buffer, in its order. */
    const float buffer = params->depth[(size_t)y * (size_t)w + (size_t)x];
    if (!(buffer > 0.0f && buffer < 1.0f) || !(depth - buffer < 0.0001f))
    {
      return 1.0f;
    }
  }
  /* The noise texel, as vtkSSAOPass's nearest, repeated lookup. */
  const int32_t shiftx = w / MRGI_SSAO_NOISE_SIZE, shifty = h / MRGI_SSAO_NOISE_SIZE;
  const float cx = ((float)x + 0.5f) / (float)w * (float)shiftx;
  const float cy = ((float)y + 0.5f) / (float)h * (float)shifty;
  const float nx = cx * (float)MRGI_SSAO_NOISE_SIZE, ny = cy * (float)MRGI_SSAO_NOISE_SIZE;
  const int32_t tx = ((int32_t)floorf(nx)) % MRGI_SSAO_NOISE_SIZE;
  const int32_t ty = ((int32_t)floorf(ny)) % MRGI_SSAO_NOISE_SIZE;
  /* A lookup on a noise texel edge: a GPU's interpolated texture coordinate
   * may land on either side (vtkSSAOPass at sizes not multiples of 64). */
  if (shiftx > 0)
  {
    m = fminf(m, fabsf(nx - roundf(nx)));
  }
  if (shifty > 0) /* a shift of 0 gives coordinate 0 exactly */
  {
    m = fminf(m, fabsf(ny - roundf(ny)));
  }
  const float angle = 6.283185f * params->noise[ty * MRGI_SSAO_NOISE_SIZE + tx];
  const float v[3] = { cosf(angle), sinf(angle), 0.0f };
  const float vn = v[0] * nv[0] + v[1] * nv[1] + v[2] * nv[2];
  float t[3] = { v[0] - nv[0] * vn, v[1] - nv[1] * vn, v[2] - nv[2] * vn };
  const float t2 = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
  if (!(t2 > 0.0f) || !isfinite(t2))
  {
    return 1.0f; /* n parallel to v: no tangent frame */
  }
  const float inv = 1.0f / sqrtf(t2);
  t[0] *= inv;
  t[1] *= inv;
  t[2] *= inv;
  const float b[3] = { nv[1] * t[2] - nv[2] * t[1], nv[2] * t[0] - nv[0] * t[2],
    nv[0] * t[1] - nv[1] * t[0] };
  const float r = params->radius;
  float occlusion = 0.0f;
  for (int32_t i = 0; i < params->kernel_size; ++i)
  {
    const float* k = params->kernel + 3 * i;
    float s[3];
    for (int c = 0; c < 3; ++c)
    {
      s[c] = p[c] + (t[c] * k[0] + b[c] * k[1] + nv[c] * k[2]) * r;
    }
    float sc[4];
    mrgi_ssao_project(params->projection, s, sc);
    const float u = sc[0] / sc[3] * 0.5f + 0.5f;
    const float vv = sc[1] / sc[3] * 0.5f + 0.5f;
    const int32_t qx = mrgi_ssao_texel(u, w, &m);
    const int32_t qy = mrgi_ssao_texel(vv, h, &m);
    const float* q = mrgi_image_at(position, qx, qy);
    if (!(q[3] > MRGI_GBUFFER_VALID_THRESHOLD) || !isfinite(q[2]))
    {
      continue; /* the background never occludes */
    }
    const float sampleDepth = q[2];
    const float range = mrgi_ssao_smoothstep01(r / fabsf(p[2] - sampleDepth));
    const float limit = s[2] + params->bias;
    const float dm = fabsf(sampleDepth - limit) / fmaxf(fabsf(s[2]), 1e-30f);
    if (dm < m)
    {
      m = dm;
    }
    occlusion += (sampleDepth >= limit ? 1.0f : 0.0f) * range;
  }
  if (margin)
  {
    *margin = m;
  }
  const float ao = 1.0f - occlusion / (float)params->kernel_size;
  return ao < 0.0f ? 0.0f : (ao > 1.0f ? 1.0f : ao);
}

mrgi_status mrgi_ssao_compute(const mrgi_ssao_params* params, const mrgi_image* position,
  const mrgi_image* normal, int32_t level, mrgi_image* out, mrgi_error* err)
{
  if (out)
  {
    memset(out, 0, sizeof(*out));
  }
  mrgi_status status = mrgi_ssao_params_validate(params, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!out || mrgi_image_validate(position, err) != MRGI_OK ||
    mrgi_image_validate(normal, err) != MRGI_OK)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: invalid G-buffer or no output");
  }
  if (position->channels != 4 || normal->channels != 4 || normal->width != position->width ||
    normal->height != position->height)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "SSAO: position (%dx%dx%d) and normal (%dx%dx%d) must be equal-sized 4-channel images",
      (int)position->width, (int)position->height, (int)position->channels, (int)normal->width,
      (int)normal->height, (int)normal->channels);
  }
  if (level < 0 || level > MRGI_SSAO_MAX_LEVEL)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "SSAO: level %d is outside 0..%d",
      (int)level, MRGI_SSAO_MAX_LEVEL);
  }
  const int32_t side = (int32_t)1 << level;
  const int32_t centre = side / 2;
  const int32_t w = (position->width + side - 1) / side;
  const int32_t h = (position->height + side - 1) / side;
  status = mrgi_image_create(out, w, h, 2, err);
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
      o[0] = mrgi_ssao_receiver(params, position, normal, x, y, &o[1]);
    }
  }
  return MRGI_OK;
}
