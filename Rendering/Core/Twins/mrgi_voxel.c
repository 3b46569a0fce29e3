#include "mrgi_voxel.h"

#include "mrgi_gather.h"

#include <float.h>
#include <math.h>
#include <string.h>

mrgi_status mrgi_voxel_grid_init(mrgi_voxel_grid* grid, int32_t width, int32_t height,
  int32_t slices, double near_depth, double far_depth, mrgi_error* err)
{
  if (!grid)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel grid pointer is NULL");
  }
  memset(grid, 0, sizeof(*grid));
  if (width < 1 || width > MRGI_VOXEL_MAX_SIZE || height < 1 || height > MRGI_VOXEL_MAX_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel buffer size %d x %d is outside 1..%d per side", width, height,
                          MRGI_VOXEL_MAX_SIZE);
  }
  if (slices < MRGI_VOXEL_LAYER_SLICES || slices > MRGI_VOXEL_MAX_SLICES ||
    slices % MRGI_VOXEL_LAYER_SLICES != 0)
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "voxel slice count %d is not 128, 256, 384 or 512", slices);
  }
  const float near_f = (float)near_depth;
  const float far_f = (float)far_depth;
  if (!isfinite(near_f) || !isfinite(far_f))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel depth range [%g, %g] is not finite (as floats)", near_depth,
                          far_depth);
  }
  if (near_f == far_f)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel depth range [%g, %g] is empty (near == far as floats)",
                          near_depth, far_depth);
  }
  if (far_f < near_f)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel depth range is reversed: far %g < near %g", far_depth,
                          near_depth);
  }
  const double scale = (double)slices / ((double)far_f - (double)near_f);
  const float scale_f = (float)scale;
  if (!isfinite(scale_f) || !(scale_f > 0.0f))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel depth range [%g, %g] gives a slice scale %g that a float "
                          "cannot hold",
                          near_depth, far_depth, scale);
  }
  grid->width = width;
  grid->height = height;
  grid->slices = slices;
  grid->near_depth = near_f;
  grid->far_depth = far_f;
  grid->slice_scale = scale_f;
  return MRGI_OK;
}

mrgi_status mrgi_voxel_grid_check(const mrgi_voxel_grid* grid, mrgi_error* err)
{
  if (!grid)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel grid is NULL");
  }
  mrgi_voxel_grid expected;
  if (mrgi_voxel_grid_init(&expected, grid->width, grid->height, grid->slices, grid->near_depth,
        grid->far_depth, NULL) != MRGI_OK ||
    memcmp(&expected, grid, sizeof(expected)) != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel grid was not made by mrgi_voxel_grid_init() (or was modified)");
  }
  return MRGI_OK;
}

mrgi_status mrgi_voxel_fit_depth_range(const double world_to_eye[16], const double bounds[6],
                                       const double clip[2], double range[2], mrgi_error* err)
{
  if (!world_to_eye || !bounds || !clip || !range)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel depth fit: a NULL %s",
                          !world_to_eye ? "matrix" : !bounds ? "box" : !clip ? "clipping range"
                                                                            : "output");
  }
  for (int k = 8; k < 12; ++k)
  {
    if (!isfinite(world_to_eye[k]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "voxel depth fit: matrix element (2, %d) is not finite", k - 8);
    }
  }
  if (!isfinite(clip[0]) || !isfinite(clip[1]) || !(clip[0] < clip[1]))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel depth fit: clipping range [%g, %g] is not finite and increasing",
                          clip[0], clip[1]);
  }
  range[0] = clip[0];
  range[1] = clip[1];
  for (int k = 0; k < 6; ++k)
  {
    if (!isfinite(bounds[k]))
    {
      return MRGI_OK; /* no usable box: the clipping range */
    }
  }
  if (bounds[0] > bounds[1] || bounds[2] > bounds[3] || bounds[4] > bounds[5])
  {
    return MRGI_OK;
  }
  double dmin = INFINITY;
  double dmax = -INFINITY;
  for (int corner = 0; corner < 8; ++corner)
  {
    const double x = bounds[corner & 1];
    const double y = bounds[2 + ((corner >> 1) & 1)];
    const double z = bounds[4 + ((corner >> 2) & 1)];
    const double d = -(world_to_eye[8] * x + world_to_eye[9] * y + world_to_eye[10] * z +
                       world_to_eye[11]);
    dmin = d < dmin ? d : dmin;
    dmax = d > dmax ? d : dmax;
  }
  const double margin = MRGI_VOXEL_FIT_MARGIN * (dmax - dmin);
  const double lo = fmax(dmin - margin, clip[0]);
  const double hi = fmin(dmax + margin, clip[1]);
  if (isfinite(lo) && isfinite(hi) && hi - lo > 1e-6 * (clip[1] - clip[0]))
  {
    range[0] = lo;
    range[1] = hi;
  }
  return MRGI_OK;
}

size_t mrgi_voxel_buffer_words(const mrgi_voxel_grid* grid)
{
  if (!grid || grid->width < 1 || grid->height < 1 || grid->slices < MRGI_VOXEL_LAYER_SLICES)
  {
    return 0;
  }
  return (size_t)grid->width * (size_t)grid->height * (size_t)mrgi_voxel_pixel_words(grid);
}

int32_t mrgi_voxel_slice(const mrgi_voxel_grid* grid, float depth)
{
  /* GLSL: int(clamp((d - near) * scale, 0.0, float(S - 1))) */
  const float x = (depth - grid->near_depth) * grid->slice_scale;
  return (int32_t)fminf(fmaxf(x, 0.0f), (float)(grid->slices - 1));
}

double mrgi_voxel_slice_center(const mrgi_voxel_grid* grid, int32_t slice)
{
  return (double)grid->near_depth + ((double)slice + 0.5) / (double)grid->slice_scale;
}

void mrgi_voxel_range_mask(int32_t lo, int32_t hi, uint32_t mask[MRGI_VOXEL_CHANNELS])
{
  lo = lo > 0 ? lo : 0;
  hi = hi < MRGI_VOXEL_LAYER_SLICES - 1 ? hi : MRGI_VOXEL_LAYER_SLICES - 1;
  for (int32_t c = 0; c < MRGI_VOXEL_CHANNELS; ++c)
  {
    const int32_t a = lo - MRGI_VOXEL_CHANNEL_BITS * c > 0 ? lo - MRGI_VOXEL_CHANNEL_BITS * c : 0;
    const int32_t b = hi - MRGI_VOXEL_CHANNEL_BITS * c < MRGI_VOXEL_CHANNEL_BITS - 1
                        ? hi - MRGI_VOXEL_CHANNEL_BITS * c
                        : MRGI_VOXEL_CHANNEL_BITS - 1;
    mask[c] = a <= b ? ((0xFFFFFFFFu >> (uint32_t)(31 - b)) & (0xFFFFFFFFu << (uint32_t)a)) : 0u;
  }
}

mrgi_status mrgi_voxel_projection_check(const mrgi_voxel_projection* projection,
                                        mrgi_error* err)
{
  if (!projection)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel projection is NULL");
  }
  if (projection->parallel != 0 && projection->parallel != 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel projection 'parallel' is %d, not 0 or 1", projection->parallel);
  }
  if (!isfinite(projection->scale_x) || !(projection->scale_x > 0.0f) ||
      !isfinite(projection->scale_y) || !(projection->scale_y > 0.0f))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel projection scales (%g, %g) must be finite and > 0",
                          (double)projection->scale_x, (double)projection->scale_y);
  }
  if (!isfinite(projection->offset_x) || !isfinite(projection->offset_y))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel projection offsets (%g, %g) must be finite",
                          (double)projection->offset_x, (double)projection->offset_y);
  }
  return MRGI_OK;
}

/* One side of mrgi_voxel_isotropic_size(): span / thickness rounded to the
 * step and clamped (span: the eye-space extent of the whole buffer along the
 * axis at the reference depth). */
static int32_t isotropic_side(double span, double thickness)
{
  const double ideal = span / thickness;
  if (!(ideal < (double)MRGI_VOXEL_AUTO_MAX_SIZE)) /* also NaN and infinity */
  {
    return isnan(ideal) ? MRGI_VOXEL_AUTO_MIN_SIZE : MRGI_VOXEL_AUTO_MAX_SIZE;
  }
  const int32_t rounded =
    (int32_t)floor(ideal / MRGI_VOXEL_AUTO_STEP + 0.5) * MRGI_VOXEL_AUTO_STEP;
  return rounded < MRGI_VOXEL_AUTO_MIN_SIZE ? MRGI_VOXEL_AUTO_MIN_SIZE
    : rounded > MRGI_VOXEL_AUTO_MAX_SIZE    ? MRGI_VOXEL_AUTO_MAX_SIZE
                                            : rounded;
}

mrgi_status mrgi_voxel_isotropic_size(const mrgi_voxel_projection* projection, int32_t slices,
  double near_depth, double far_depth, int32_t size[2], mrgi_error* err)
{
  if (!size)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel isotropic size: NULL output");
  }
  const mrgi_status checked = mrgi_voxel_projection_check(projection, err);
  if (checked != MRGI_OK)
  {
    return checked;
  }
  if (!isfinite(near_depth) || !isfinite(far_depth) || !(near_depth < far_depth))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel isotropic size: depth range [%g, %g] is not finite and increasing",
                          near_depth, far_depth);
  }
  const double middle = projection->parallel ? 1.0 : 0.5 * (near_depth + far_depth);
  if (!(middle > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel isotropic size: the middle of [%g, %g] is not in front of the eye",
                          near_depth, far_depth);
  }
  if (slices < MRGI_VOXEL_LAYER_SLICES || slices > MRGI_VOXEL_MAX_SLICES ||
    slices % MRGI_VOXEL_LAYER_SLICES != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "voxel isotropic size: slice count %d is not 128, 256, 384 or 512", slices);
  }
  const double thickness = (far_depth - near_depth) / slices;
  size[0] = isotropic_side(2.0 * middle / (double)projection->scale_x, thickness);
  size[1] = isotropic_side(2.0 * middle / (double)projection->scale_y, thickness);
  return MRGI_OK;
}

mrgi_status mrgi_voxel_projection_from_camera(mrgi_voxel_projection* projection,
                                              const mrgi_multires_projection* camera,
                                              double aspect, mrgi_error* err)
{
  if (!projection || !camera)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s is NULL",
                          !projection ? "voxel projection" : "camera");
  }
  memset(projection, 0, sizeof(*projection));
  if (!(aspect > 0.0) || !isfinite(aspect))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "window aspect %g must be finite and > 0", aspect);
  }
  double scale_y;
  if (camera->parallel)
  {
    if (!(camera->parallel_scale > 0.0) || !isfinite(camera->parallel_scale))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "parallel scale %g must be finite and > 0", camera->parallel_scale);
    }
    scale_y = 1.0 / camera->parallel_scale;
  }
  else
  {
    if (!(camera->view_angle_deg > 0.0 && camera->view_angle_deg < 180.0))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "perspective view angle %g degrees is outside (0, 180)",
                            camera->view_angle_deg);
    }
    scale_y = 1.0 / tan(camera->view_angle_deg * (MRGI_PI / 360.0));
  }
  mrgi_voxel_projection p;
  p.parallel = camera->parallel ? 1 : 0;
  p.scale_x = (float)(scale_y / aspect);
  p.scale_y = (float)scale_y;
  p.offset_x = 0.0f;
  p.offset_y = 0.0f;
  const mrgi_status status = mrgi_voxel_projection_check(&p, err);
  if (status == MRGI_OK)
  {
    *projection = p;
  }
  return status;
}

mrgi_status mrgi_voxel_projection_from_matrix(mrgi_voxel_projection* projection,
                                              const double matrix[16], mrgi_error* err)
{
  if (!projection || !matrix)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s is NULL",
                          !projection ? "voxel projection" : "projection matrix");
  }
  memset(projection, 0, sizeof(*projection));
  for (int k = 0; k < 16; ++k)
  {
    if (!isfinite(matrix[k]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "projection matrix element %d is not finite", k);
    }
  }
  /* element (row, col) at matrix[4 col + row]; last row = (m3, m7, m11, m15) */
  const int perspective =
    matrix[3] == 0.0 && matrix[7] == 0.0 && matrix[11] == -1.0 && matrix[15] == 0.0;
  const int parallel =
    matrix[3] == 0.0 && matrix[7] == 0.0 && matrix[11] == 0.0 && matrix[15] == 1.0;
  if (!perspective && !parallel)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "projection matrix last row (%g, %g, %g, %g) is neither "
                          "perspective (0, 0, -1, 0) nor parallel (0, 0, 0, 1)",
                          matrix[3], matrix[7], matrix[11], matrix[15]);
  }
  mrgi_voxel_projection p;
  p.parallel = parallel;
  p.scale_x = (float)matrix[0];
  p.scale_y = (float)matrix[5];
  /* perspective: ndc_x = (P00 x + P02 z) / (-z) = P00 x / d - P02;
   * parallel:    ndc_x = P00 x + P03 */
  p.offset_x = (float)(perspective ? -matrix[8] : matrix[12]);
  p.offset_y = (float)(perspective ? -matrix[9] : matrix[13]);
  const mrgi_status status = mrgi_voxel_projection_check(&p, err);
  if (status == MRGI_OK)
  {
    *projection = p;
  }
  return status;
}

int mrgi_voxel_project(const mrgi_voxel_grid* grid, const mrgi_voxel_projection* projection,
                       const float point[3], float uvd[3])
{
  const float d = -point[2];
  const float w = projection->parallel ? 1.0f : d;
  if (!(w > 0.0f))
  {
    uvd[0] = 0.0f;
    uvd[1] = 0.0f;
    uvd[2] = d;
    return 0;
  }
  const float ndc_x = projection->scale_x * point[0] / w + projection->offset_x;
  const float ndc_y = projection->scale_y * point[1] / w + projection->offset_y;
  uvd[0] = (ndc_x + 1.0f) * 0.5f * (float)grid->width;
  uvd[1] = (ndc_y + 1.0f) * 0.5f * (float)grid->height;
  uvd[2] = d;
  return 1;
}

void mrgi_voxel_fragment_mask(const mrgi_voxel_grid* grid, float depth, float half_span,
  float depth_min, float depth_max, uint32_t mask[MRGI_VOXEL_MAX_WORDS])
{
  const int32_t layers = mrgi_voxel_layers(grid);
  /* GLSL: if (!(d >= near && d <= far)) discard;  (clipped by the near/far planes) */
  if (!(depth >= grid->near_depth && depth <= grid->far_depth))
  {
    memset(mask, 0, (size_t)layers * MRGI_VOXEL_CHANNELS * sizeof(uint32_t));
    return;
  }
  const float h = half_span > 0.0f ? half_span : 0.0f; /* NaN -> 0 */
  const float lo = fminf(fmaxf(depth - h, depth_min), depth);
  const float hi = fmaxf(fminf(depth + h, depth_max), depth);
  const int32_t slice_lo = mrgi_voxel_slice(grid, lo);
  const int32_t slice_hi = mrgi_voxel_slice(grid, hi);
  /* One render target per layer (section 1): each gets its own 128 slices. */
  for (int32_t l = 0; l < layers; ++l)
  {
    mrgi_voxel_range_mask(slice_lo - MRGI_VOXEL_LAYER_SLICES * l,
      slice_hi - MRGI_VOXEL_LAYER_SLICES * l, mask + MRGI_VOXEL_CHANNELS * l);
  }
}

/* One Sutherland-Hodgman pass: keep the side where sign * (coord - edge) >= 0.
 * p: n vertices (u, v, a = d / w, b = 1 / w); writes at most n + 1 into q. */
static int mrgi_voxel_clip_pass(const float p[][4], int n, int axis, float edge, float sign,
                                float q[][4])
{
  int m = 0;
  for (int i = 0; i < n; ++i)
  {
    const float* s0 = p[i];
    const float* s1 = p[i + 1 < n ? i + 1 : 0];
    const float f0 = sign * (s0[axis] - edge);
    const float f1 = sign * (s1[axis] - edge);
    if (f0 >= 0.0f)
    {
      for (int c = 0; c < 4; ++c)
      {
        q[m][c] = s0[c];
      }
      ++m;
    }
    if ((f0 >= 0.0f) != (f1 >= 0.0f))
    {
      const float t = f0 / (f0 - f1);
      for (int c = 0; c < 4; ++c)
      {
        q[m][c] = s0[c] + t * (s1[c] - s0[c]);
      }
      ++m;
    }
  }
  return m;
}

int mrgi_voxel_triangle_pixel_range(const float u[3], const float v[3], const float depth[3],
                                    const float w[3], int32_t x, int32_t y, float range[2])
{
  if (!(w[0] > 0.0f && w[1] > 0.0f && w[2] > 0.0f))
  {
    return 0; /* a vertex at or behind the eye: its (u, v) mean nothing */
  }
  float a[8][4], b[8][4];
  for (int i = 0; i < 3; ++i)
  {
    a[i][0] = u[i];
    a[i][1] = v[i];
    a[i][2] = depth[i] / w[i];
    a[i][3] = 1.0f / w[i];
  }
  int n = 3;
  n = mrgi_voxel_clip_pass((const float(*)[4])a, n, 0, (float)x, 1.0f, b);
  n = mrgi_voxel_clip_pass((const float(*)[4])b, n, 0, (float)(x + 1), -1.0f, a);
  n = mrgi_voxel_clip_pass((const float(*)[4])a, n, 1, (float)y, 1.0f, b);
  n = mrgi_voxel_clip_pass((const float(*)[4])b, n, 1, (float)(y + 1), -1.0f, a);
  if (n < 1)
  {
    return 0;
  }
  float lo = a[0][2] / a[0][3];
  float hi = lo;
  for (int i = 1; i < n; ++i)
  {
    const float d = a[i][2] / a[i][3];
    lo = fminf(lo, d);
    hi = fmaxf(hi, d);
  }
  range[0] = lo;
  range[1] = hi;
  return 1;
}

/* Shared argument checks of the functions that write a voxel buffer. */
static mrgi_status mrgi_voxel_check_buffer(const mrgi_voxel_grid* grid, const uint32_t* voxels,
                                           size_t voxel_words, mrgi_error* err)
{
  mrgi_status status = mrgi_voxel_grid_check(grid, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!voxels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "voxel buffer is NULL");
  }
  const size_t needed = mrgi_voxel_buffer_words(grid);
  if (voxel_words < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "voxel buffer holds %zu words but a %d x %d grid needs %zu",
                          voxel_words, grid->width, grid->height, needed);
  }
  return MRGI_OK;
}

mrgi_status mrgi_voxel_clear(const mrgi_voxel_grid* grid, uint32_t* voxels, size_t voxel_words,
                             mrgi_error* err)
{
  const mrgi_status status = mrgi_voxel_check_buffer(grid, voxels, voxel_words, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  memset(voxels, 0, mrgi_voxel_buffer_words(grid) * sizeof(uint32_t));
  return MRGI_OK;
}

/* OR one fragment's mask into its texel; 1 when something was written. */
static int mrgi_voxel_splat(const mrgi_voxel_grid* grid, uint32_t* voxels, int32_t x, int32_t y,
                            float depth, float half_span, float depth_min, float depth_max)
{
  uint32_t mask[MRGI_VOXEL_MAX_WORDS];
  mrgi_voxel_fragment_mask(grid, depth, half_span, depth_min, depth_max, mask);
  const int32_t words = mrgi_voxel_pixel_words(grid);
  uint32_t any = 0u;
  for (int32_t c = 0; c < words; ++c)
  {
    any |= mask[c];
  }
  if (any == 0u)
  {
    return 0;
  }
  uint32_t* texel = voxels + mrgi_voxel_index(grid, x, y);
  for (int32_t c = 0; c < words; ++c)
  {
    texel[c] |= mask[c];
  }
  return 1;
}

mrgi_status mrgi_voxel_voxelize(const mrgi_voxel_grid* grid, const mrgi_voxel_fragment* fragments,
                                size_t count, uint32_t* voxels, size_t voxel_words,
                                mrgi_voxel_info* info, mrgi_error* err)
{
  const mrgi_status status = mrgi_voxel_check_buffer(grid, voxels, voxel_words, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (count > 0 && !fragments)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "fragment list is NULL but holds %zu fragments", count);
  }
  for (size_t k = 0; k < count; ++k)
  {
    const mrgi_voxel_fragment* f = fragments + k;
    if (f->x < 0 || f->x >= grid->width || f->y < 0 || f->y >= grid->height)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                            "fragment %zu at voxel pixel (%d, %d) lies outside the %d x %d grid",
                            k, f->x, f->y, grid->width, grid->height);
    }
  }
  mrgi_voxel_info counts = { 0, 0 };
  for (size_t k = 0; k < count; ++k)
  {
    const mrgi_voxel_fragment* f = fragments + k;
    if (mrgi_voxel_splat(grid, voxels, f->x, f->y, f->depth, f->half_span, f->depth_min,
                         f->depth_max))
    {
      ++counts.fragments_written;
    }
    else
    {
      ++counts.fragments_clipped;
    }
  }
  if (info)
  {
    *info = counts;
  }
  return MRGI_OK;
}

/* min(|d(x+1) - d(x)|, |d(x) - d(x-1)|) over the neighbours holding a depth. */
static float mrgi_voxel_one_sided(float center, float before, int has_before, float after,
                                  int has_after)
{
  float g = -1.0f;
  if (has_before)
  {
    g = fabsf(center - before);
  }
  if (has_after)
  {
    const float a = fabsf(after - center);
    g = g < 0.0f || a < g ? a : g;
  }
  return g < 0.0f ? 0.0f : g;
}

mrgi_status mrgi_voxel_voxelize_depth(const mrgi_voxel_grid* grid, const float* depth,
                                      int32_t width, int32_t height, int32_t conservative,
                                      uint32_t* voxels, size_t voxel_words,
                                      mrgi_voxel_info* info, mrgi_error* err)
{
  const mrgi_status status = mrgi_voxel_check_buffer(grid, voxels, voxel_words, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!depth)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "depth buffer is NULL");
  }
  if (width < 1 || width > MRGI_VOXEL_MAX_SIZE || height < 1 || height > MRGI_VOXEL_MAX_SIZE)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "depth buffer size %d x %d is outside 1..%d per side", width, height,
                          MRGI_VOXEL_MAX_SIZE);
  }
  if (conservative != 0 && conservative != 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "'conservative' is %d, not 0 or 1", conservative);
  }
  mrgi_voxel_info counts = { 0, 0 };
  for (int32_t y = 0; y < height; ++y)
  {
    const int32_t vy = mrgi_voxel_pixel_from_window(y, height, grid->height);
    for (int32_t x = 0; x < width; ++x)
    {
      const float* row = depth + (size_t)y * (size_t)width;
      const float d = row[x];
      if (!isfinite(d))
      {
        continue; /* background: no fragment */
      }
      float h = 0.0f;
      if (conservative)
      {
        const float* below = y > 0 ? row - width : NULL;
        const float* above = y + 1 < height ? row + width : NULL;
        const float gx = mrgi_voxel_one_sided(d, x > 0 ? row[x - 1] : 0.0f,
                                              x > 0 && isfinite(row[x - 1]),
                                              x + 1 < width ? row[x + 1] : 0.0f,
                                              x + 1 < width && isfinite(row[x + 1]));
        const float gy =
          mrgi_voxel_one_sided(d, below ? below[x] : 0.0f, below && isfinite(below[x]),
                               above ? above[x] : 0.0f, above && isfinite(above[x]));
        h = 0.5f * (gx + gy);
      }
      const int32_t vx = mrgi_voxel_pixel_from_window(x, width, grid->width);
      if (mrgi_voxel_splat(grid, voxels, vx, vy, d, h, -FLT_MAX, FLT_MAX))
      {
        ++counts.fragments_written;
      }
      else
      {
        ++counts.fragments_clipped;
      }
    }
  }
  if (info)
  {
    *info = counts;
  }
  return MRGI_OK;
}
