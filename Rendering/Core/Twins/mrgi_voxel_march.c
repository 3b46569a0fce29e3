#include "mrgi_voxel_march.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void mrgi_voxel_march_params_default(mrgi_voxel_march_params* params)
{
  if (!params)
  {
    return;
  }
  params->max_steps = MRGI_VOXEL_DEFAULT_MAX_STEPS;
  params->normal_offset = MRGI_VOXEL_DEFAULT_NORMAL_OFFSET;
  params->skip_radius = MRGI_VOXEL_DEFAULT_SKIP_RADIUS;
  params->offset_along_ray = MRGI_VOXEL_OFFSET_NORMALS;
}

mrgi_status mrgi_voxel_march_params_validate(const mrgi_voxel_march_params* params,
                                             mrgi_error* err)
{
  if (!params)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel march params are NULL");
  }
  if (params->max_steps < 1 || params->max_steps > MRGI_VOXEL_MAX_STEPS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel march max_steps %d is outside 1..%d", params->max_steps,
                          MRGI_VOXEL_MAX_STEPS);
  }
  if (!(params->normal_offset >= 0.0f && params->normal_offset <= MRGI_VOXEL_MAX_NORMAL_OFFSET))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel march normal_offset %g is outside [0, %g] voxel sizes",
                          (double)params->normal_offset, (double)MRGI_VOXEL_MAX_NORMAL_OFFSET);
  }
  if (params->skip_radius < 0 || params->skip_radius > MRGI_VOXEL_MAX_SKIP_RADIUS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel march skip_radius %d is outside 0..%d voxels",
                          params->skip_radius, MRGI_VOXEL_MAX_SKIP_RADIUS);
  }
  if (params->offset_along_ray < MRGI_VOXEL_OFFSET_NORMALS ||
      params->offset_along_ray > MRGI_VOXEL_OFFSET_RAY_AT_BOTH)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel march offset_along_ray %d is outside %d..%d",
                          (int)params->offset_along_ray, MRGI_VOXEL_OFFSET_NORMALS,
                          MRGI_VOXEL_OFFSET_RAY_AT_BOTH);
  }
  return MRGI_OK;
}

mrgi_status mrgi_voxel_view_check(const mrgi_voxel_view* view, mrgi_error* err)
{
  if (!view)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel view is NULL");
  }
  mrgi_status status = mrgi_voxel_grid_check(&view->grid, err);
  if (status == MRGI_OK)
  {
    status = mrgi_voxel_projection_check(&view->projection, err);
  }
  if (status == MRGI_OK)
  {
    status = mrgi_voxel_march_params_validate(&view->params, err);
  }
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!view->projection.parallel && !(view->grid.near_depth > 0.0f))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel depth range starts at %g but a perspective projection needs "
                          "near > 0",
                          (double)view->grid.near_depth);
  }
  if (!view->voxels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel buffer is NULL");
  }
  const size_t needed = mrgi_voxel_buffer_words(&view->grid);
  if (view->voxel_words < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel buffer holds %zu words but a %d x %d grid needs %zu",
                          view->voxel_words, view->grid.width, view->grid.height, needed);
  }
  return MRGI_OK;
}

float mrgi_voxel_size_at(const mrgi_voxel_view* view, float depth)
{
  const float w = view->projection.parallel ? 1.0f : fabsf(depth);
  const float sx = 2.0f * w / (view->projection.scale_x * (float)view->grid.width);
  const float sy = 2.0f * w / (view->projection.scale_y * (float)view->grid.height);
  const float sz = 1.0f / view->grid.slice_scale;
  return fmaxf(fmaxf(sx, sy), sz);
}

static float mrgi_dot3(const float a[3], const float b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The six frustum half-spaces f(X) >= 0 (step 4), X = (x, y, z) eye space. */
static void mrgi_voxel_frustum(const mrgi_voxel_view* view, const float X[3], float f[6])
{
  const mrgi_voxel_projection* p = &view->projection;
  const float d = -X[2];
  const float w = p->parallel ? 1.0f : d;
  f[0] = d - view->grid.near_depth;
  f[1] = view->grid.far_depth - d;
  f[2] = p->scale_x * X[0] + (1.0f + p->offset_x) * w;
  f[3] = -p->scale_x * X[0] + (1.0f - p->offset_x) * w;
  f[4] = p->scale_y * X[1] + (1.0f + p->offset_y) * w;
  f[5] = -p->scale_y * X[1] + (1.0f - p->offset_y) * w;
}

/* A skip box (step 7): centre voxel, active flag. */
typedef struct mrgi_voxel_box
{
  int32_t active;
  int32_t x;
  int32_t y;
  int32_t slice;
} mrgi_voxel_box;

/* floor(u) clamped to 0..size-1, computed in float first (GLSL: clamp(int(floor(u)), 0, size-1)). */
static int32_t mrgi_voxel_pixel(float u, int32_t size)
{
  const float c = fminf(fmaxf(floorf(u), 0.0f), (float)(size - 1)); /* NaN -> 0 */
  return (int32_t)c;
}

static mrgi_voxel_box mrgi_voxel_skip_box(const mrgi_voxel_view* view, const float X[3])
{
  mrgi_voxel_box box = { 0, 0, 0, 0 };
  float f[6];
  mrgi_voxel_frustum(view, X, f);
  for (int k = 0; k < 6; ++k)
  {
    if (!(f[k] >= 0.0f))
    {
      return box;
    }
  }
  float uvd[3];
  if (!mrgi_voxel_project(&view->grid, &view->projection, X, uvd))
  {
    return box;
  }
  box.active = view->params.skip_radius > 0;
  box.x = mrgi_voxel_pixel(uvd[0], view->grid.width);
  box.y = mrgi_voxel_pixel(uvd[1], view->grid.height);
  box.slice = mrgi_voxel_slice(&view->grid, uvd[2]);
  return box;
}

/* The box's slices are removed from layer `layer`'s mask (its slices
 * 128 layer .. 128 layer + 127, mrgi_voxel.h section 1). */
static void mrgi_voxel_apply_box(const mrgi_voxel_box* box, int32_t radius, int32_t px, int32_t py,
  int32_t layer, uint32_t mask[MRGI_VOXEL_CHANNELS])
{
  if (box->active && abs(px - box->x) <= radius && abs(py - box->y) <= radius)
  {
    uint32_t skip[MRGI_VOXEL_CHANNELS];
    const int32_t base = MRGI_VOXEL_LAYER_SLICES * layer;
    mrgi_voxel_range_mask(box->slice - radius - base, box->slice + radius - base, skip);
    for (int c = 0; c < MRGI_VOXEL_CHANNELS; ++c)
    {
      mask[c] &= ~skip[c];
    }
  }
}

/* Outcome of the shared march. */
typedef enum mrgi_voxel_outcome
{
  MRGI_VOXEL_CLEAR,    /* no step hit (or nothing to march) */
  MRGI_VOXEL_HORIZON,  /* below a horizon (step 2) */
  MRGI_VOXEL_HIT       /* a step hit; *hit_fraction set (from_light only) */
} mrgi_voxel_outcome;

/* Step 3 at one end X (in place): the offset of height h above X's plane,
 * along the ray where the ray leaves at cosine c >= FULL_COS to the normal n,
 * along n below MIN_COS, blended between; the part along the ray at most
 * MAX_SHARE of the segment (then the rest of the height along n).
 * toward: the segment from X to the other end, of length `length` > 0;
 * n2 = |n|^2 > 0 and dot(n, toward) > 0 (the horizon test passed). */
static void mrgi_voxel_offset_end(float X[3], const float* n, float n2, const float toward[3],
                                  float length, float h, int along_ray)
{
  const float inv_n = 1.0f / sqrtf(n2);
  const float unit_n[3] = { n[0] * inv_n, n[1] * inv_n, n[2] * inv_n };
  if (!along_ray)
  {
    for (int k = 0; k < 3; ++k)
    {
      X[k] += h * unit_n[k];
    }
    return;
  }
  const float u[3] = { toward[0] / length, toward[1] / length, toward[2] / length };
  const float c = mrgi_dot3(unit_n, u);
  const float w = fminf(fmaxf((c - MRGI_VOXEL_ALONG_RAY_MIN_COS) /
                                (MRGI_VOXEL_ALONG_RAY_FULL_COS - MRGI_VOXEL_ALONG_RAY_MIN_COS),
                              0.0f),
                        1.0f);
  const float along = fminf(w * h / c, MRGI_VOXEL_ALONG_RAY_MAX_SHARE * length);
  const float up = fmaxf(h - along * c, 0.0f);
  for (int k = 0; k < 3; ++k)
  {
    X[k] += along * u[k] + up * unit_n[k];
  }
}

/* Steps 1-9. from_light: walk k = n-1..0 and compute the hit's fraction. */
static mrgi_voxel_outcome mrgi_voxel_march_core(const mrgi_voxel_view* view, const float P[3],
                                                const float* Np, const float L[3],
                                                const float* Nl, int from_light,
                                                float* hit_fraction)
{
  /* 1. */
  const float D[3] = { L[0] - P[0], L[1] - P[1], L[2] - P[2] };
  const float length2 = mrgi_dot3(D, D);
  if (length2 == 0.0f)
  {
    return MRGI_VOXEL_CLEAR;
  }
  /* 2. */
  const float np2 = Np ? mrgi_dot3(Np, Np) : 0.0f;
  const float nl2 = Nl ? mrgi_dot3(Nl, Nl) : 0.0f;
  if (np2 > 0.0f && mrgi_dot3(Np, D) <= 0.0f)
  {
    return MRGI_VOXEL_HORIZON;
  }
  if (nl2 > 0.0f && mrgi_dot3(Nl, D) >= 0.0f) /* dot(Nl, -D) <= 0 */
  {
    return MRGI_VOXEL_HORIZON;
  }
  /* 3. */
  float O[3] = { P[0], P[1], P[2] };
  float E[3] = { L[0], L[1], L[2] };
  const float length = sqrtf(length2);
  if (np2 > 0.0f)
  {
    mrgi_voxel_offset_end(O, Np, np2, D, length,
                          view->params.normal_offset * mrgi_voxel_size_at(view, -P[2]),
                          view->params.offset_along_ray != MRGI_VOXEL_OFFSET_NORMALS);
  }
  if (nl2 > 0.0f)
  {
    const float back[3] = { -D[0], -D[1], -D[2] };
    mrgi_voxel_offset_end(E, Nl, nl2, back, length,
                          view->params.normal_offset * mrgi_voxel_size_at(view, -L[2]),
                          view->params.offset_along_ray == MRGI_VOXEL_OFFSET_RAY_AT_BOTH);
  }
  /* 4. */
  float fO[6], fE[6];
  mrgi_voxel_frustum(view, O, fO);
  mrgi_voxel_frustum(view, E, fE);
  float t0 = 0.0f;
  float t1 = 1.0f;
  for (int k = 0; k < 6; ++k)
  {
    if (fO[k] < 0.0f && fE[k] < 0.0f)
    {
      return MRGI_VOXEL_CLEAR;
    }
    if (fO[k] < 0.0f)
    {
      t0 = fmaxf(t0, fO[k] / (fO[k] - fE[k]));
    }
    else if (fE[k] < 0.0f)
    {
      t1 = fminf(t1, fO[k] / (fO[k] - fE[k]));
    }
  }
  if (t0 > t1)
  {
    return MRGI_VOXEL_CLEAR;
  }
  float A[3], B[3];
  for (int c = 0; c < 3; ++c)
  {
    A[c] = O[c] + t0 * (E[c] - O[c]);
    B[c] = O[c] + t1 * (E[c] - O[c]);
  }
  /* 5. Both ends are inside [near, far] (up to rounding), so d > 0 for perspective. */
  float a[3], b[3];
  mrgi_voxel_project(&view->grid, &view->projection, A, a);
  mrgi_voxel_project(&view->grid, &view->projection, B, b);
  const int perspective = !view->projection.parallel;
  const float ia = perspective ? 1.0f / a[2] : 0.0f;
  const float ib = perspective ? 1.0f / b[2] : 0.0f;
  /* 6. */
  const float du = b[0] - a[0];
  const float dv = b[1] - a[1];
  const float span = fmaxf(fabsf(du), fabsf(dv));
  const int32_t n = (int32_t)fminf(fmaxf(ceilf(span), 1.0f), (float)view->params.max_steps);
  const float inv_n = 1.0f / (float)n;
  /* 7. */
  const int32_t radius = view->params.skip_radius;
  const mrgi_voxel_box box_p = mrgi_voxel_skip_box(view, P);
  const mrgi_voxel_box box_l = mrgi_voxel_skip_box(view, L);
  /* 8. */
  for (int32_t j = 0; j < n; ++j)
  {
    const int32_t k = from_light ? n - 1 - j : j;
    const float s0 = (float)k * inv_n;
    const float s1 = (float)(k + 1) * inv_n;
    const float sm = ((float)k + 0.5f) * inv_n;
    const int32_t px = mrgi_voxel_pixel(a[0] + du * sm, view->grid.width);
    const int32_t py = mrgi_voxel_pixel(a[1] + dv * sm, view->grid.height);
    float d0, d1;
    if (perspective)
    {
      d0 = 1.0f / (ia + (ib - ia) * s0);
      d1 = 1.0f / (ia + (ib - ia) * s1);
    }
    else
    {
      d0 = a[2] + (b[2] - a[2]) * s0;
      d1 = a[2] + (b[2] - a[2]) * s1;
    }
    const int32_t lo = mrgi_voxel_slice(&view->grid, fminf(d0, d1));
    const int32_t hi = mrgi_voxel_slice(&view->grid, fmaxf(d0, d1));
    const uint32_t* pixel = view->voxels + mrgi_voxel_index(&view->grid, px, py);
    /* Only the layers the interval reaches are read (one texel fetch each
     * on the GPU; almost always one). */
    uint32_t overlap = 0u;
    for (int32_t layer = lo / MRGI_VOXEL_LAYER_SLICES; layer <= hi / MRGI_VOXEL_LAYER_SLICES;
         ++layer)
    {
      const int32_t base = MRGI_VOXEL_LAYER_SLICES * layer;
      uint32_t mask[MRGI_VOXEL_CHANNELS];
      mrgi_voxel_range_mask(lo - base, hi - base, mask);
      mrgi_voxel_apply_box(&box_p, radius, px, py, layer, mask);
      mrgi_voxel_apply_box(&box_l, radius, px, py, layer, mask);
      const uint32_t* texel = pixel + MRGI_VOXEL_CHANNELS * layer;
      overlap |=
        (texel[0] & mask[0]) | (texel[1] & mask[1]) | (texel[2] & mask[2]) | (texel[3] & mask[3]);
    }
    if (overlap != 0u)
    {
      if (from_light)
      {
        const float tau = perspective ? sm * ib / (ia + (ib - ia) * sm) : sm;
        float X[3];
        for (int c = 0; c < 3; ++c)
        {
          X[c] = A[c] + tau * (B[c] - A[c]);
        }
        const float LX[3] = { L[0] - X[0], L[1] - X[1], L[2] - X[2] };
        const float z = sqrtf(mrgi_dot3(LX, LX) / length2);
        *hit_fraction = fminf(fmaxf(z, 0.0f), 1.0f);
      }
      return MRGI_VOXEL_HIT;
    }
  }
  /* 9. */
  return MRGI_VOXEL_CLEAR;
}

int mrgi_voxel_march(const mrgi_voxel_view* view, const float receiver[3],
                     const float* receiver_normal, const float sample[3],
                     const float* sample_normal)
{
  return mrgi_voxel_march_core(view, receiver, receiver_normal, sample, sample_normal, 0, NULL) ==
         MRGI_VOXEL_CLEAR;
}

float mrgi_voxel_march_occluder_fraction(const mrgi_voxel_view* view, const float receiver[3],
                                         const float* receiver_normal, const float sample[3],
                                         const float* sample_normal)
{
  float fraction = 1.0f;
  const mrgi_voxel_outcome outcome = mrgi_voxel_march_core(view, receiver, receiver_normal,
                                                           sample, sample_normal, 1, &fraction);
  if (outcome == MRGI_VOXEL_HORIZON)
  {
    return 0.0f;
  }
  return outcome == MRGI_VOXEL_HIT ? fraction : 1.0f;
}

int32_t mrgi_voxel_step_bound(const mrgi_voxel_grid* grid, int32_t max_steps)
{
  const int32_t cap = max_steps > 0 ? max_steps : 1;
  if (!grid || grid->width < 1 || grid->height < 1)
  {
    return cap;
  }
  const int64_t side = (int64_t)(grid->width > grid->height ? grid->width : grid->height) + 2;
  return side < cap ? (int32_t)side : cap;
}

/* A step's loop iterations in the GLSL march: the step and one per layer. */
_Static_assert(1 + MRGI_VOXEL_MAX_LAYERS <= MRGI_VOXEL_ITERATIONS_PER_STEP,
               "MRGI_VOXEL_ITERATIONS_PER_STEP must cover the step and its layer loop");

int32_t mrgi_voxel_samples_per_batch(int32_t max_steps)
{
  const int64_t steps = max_steps > 0 ? max_steps : 1;
  const int64_t per_march = steps * MRGI_VOXEL_ITERATIONS_PER_STEP + MRGI_VOXEL_ITERATIONS_PER_MARCH;
  const int64_t batch = MRGI_VOXEL_ITERATION_BUDGET / per_march;
  return (int32_t)(batch > 1 ? batch : 1);
}
