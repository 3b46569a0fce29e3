/* ISM point sets: see mrgi_ism_points.h (RGK08 3, RIHKS11 5.1-5.3). */
#include "mrgi_ism_points.h"

#include <math.h>

/* 32-bit integer hash (lowbias32); no state, so records are independent. */
static uint32_t ism_hash(uint32_t x)
{
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

static double ism_unit(uint32_t h)
{
  return (double)(h >> 8) * (1.0 / 16777216.0);
}

static mrgi_status check_mesh(
  const float* pos, int32_t nv, const int32_t* tris, int32_t nt, mrgi_error* err)
{
  if (!pos || !tris)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: NULL mesh arrays");
  if (nt <= 0 || nv <= 0)
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: empty mesh (%d vertices, %d triangles)", nv, nt);
  for (int64_t i = 0; i < 3 * (int64_t)nv; ++i)
    if (!isfinite(pos[i]))
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "ISM points: vertex %lld has a non-finite coordinate", (long long)(i / 3));
  for (int64_t i = 0; i < 3 * (int64_t)nt; ++i)
    if (tris[i] < 0 || tris[i] >= nv)
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "ISM points: triangle %lld has vertex index %d outside 0..%d", (long long)(i / 3), tris[i],
        nv - 1);
  return MRGI_OK;
}

/* Area, centroid and (unnormalized, length 2A) normal of triangle t. */
static double tri_geometry(
  const float* pos, const int32_t* tris, int32_t t, double c[3], double n[3])
{
  const float* a = pos + 3 * tris[3 * t];
  const float* b = pos + 3 * tris[3 * t + 1];
  const float* d = pos + 3 * tris[3 * t + 2];
  const double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double e2[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  for (int k = 0; k < 3; ++k)
    c[k] = ((double)a[k] + b[k] + d[k]) / 3.0;
  return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* Solid angle of triangle t seen from v: Van Oosterom and Strackee 1983,
 * tan(W/2) = |a.(b x c)| / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|);
 * lengths clamped below at MRGI_ISM_MIN_VIEW_DISTANCE. */
static double tri_solid_angle(const float* pos, const int32_t* tris, int32_t t, const double v[3])
{
  double r[3][3], len[3];
  for (int j = 0; j < 3; ++j)
  {
    const float* p = pos + 3 * tris[3 * t + j];
    for (int k = 0; k < 3; ++k)
      r[j][k] = p[k] - v[k];
    len[j] = sqrt(r[j][0] * r[j][0] + r[j][1] * r[j][1] + r[j][2] * r[j][2]);
    len[j] = len[j] > MRGI_ISM_MIN_VIEW_DISTANCE ? len[j] : MRGI_ISM_MIN_VIEW_DISTANCE;
  }
  const double bc[3] = { r[1][1] * r[2][2] - r[1][2] * r[2][1],
    r[1][2] * r[2][0] - r[1][0] * r[2][2], r[1][0] * r[2][1] - r[1][1] * r[2][0] };
  const double num = fabs(r[0][0] * bc[0] + r[0][1] * bc[1] + r[0][2] * bc[2]);
  const double ab = r[0][0] * r[1][0] + r[0][1] * r[1][1] + r[0][2] * r[1][2];
  const double ac = r[0][0] * r[2][0] + r[0][1] * r[2][1] + r[0][2] * r[2][2];
  const double bcd = r[1][0] * r[2][0] + r[1][1] * r[2][1] + r[1][2] * r[2][2];
  const double den = len[0] * len[1] * len[2] + ab * len[2] + ac * len[1] + bcd * len[0];
  return 2.0 * atan2(num, den);
}

static mrgi_status check_views(
  mrgi_ism_mode mode, const double* views, int32_t count, mrgi_error* err)
{
  if (mode == MRGI_ISM_UNIFORM)
    return MRGI_OK;
  if (mode != MRGI_ISM_ADAPTIVE_1 && mode != MRGI_ISM_ADAPTIVE_8)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: unknown mode %d", (int)mode);
  if (!views || count < 1 || count > MRGI_ISM_MAX_VIEW_POOL)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM points: adaptive mode needs 1..%d view samples, got %d", MRGI_ISM_MAX_VIEW_POOL,
      views ? count : 0);
  for (int32_t i = 0; i < 3 * count; ++i)
    if (!isfinite(views[i]))
      return mrgi_error_set(
        err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: view sample %d is not finite", i / 3);
  return MRGI_OK;
}

mrgi_status mrgi_ism_triangle_weights(const float* positions, int32_t vertex_count,
  const int32_t* triangles, int32_t triangle_count, mrgi_ism_mode mode, const double* view_samples,
  int32_t view_count, uint32_t seed, double* weights, mrgi_error* err)
{
  mrgi_status s = check_mesh(positions, vertex_count, triangles, triangle_count, err);
  if (s)
    return s;
  if ((s = check_views(mode, view_samples, view_count, err)))
    return s;
  if (!weights)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: NULL weights");
  double area_sum = 0.0, sa_sum = 0.0;
  for (int32_t t = 0; t < triangle_count; ++t)
  {
    double c[3], n[3];
    const double area = tri_geometry(positions, triangles, t, c, n);
    area_sum += area;
    double sa = 0.0;
    if (mode != MRGI_ISM_UNIFORM && area > 0.0)
    {
      const int32_t k_count = mode == MRGI_ISM_ADAPTIVE_1 ? 1 : MRGI_ISM_VIEW_SAMPLES_PER_TRIANGLE;
      for (int32_t k = 0; k < k_count; ++k)
      {
        /* RIHKS11 5.2: each triangle its own random view samples from the pool. */
        const uint32_t h = ism_hash(seed ^ ism_hash((uint32_t)t * 8u + (uint32_t)k));
        const double* v =
          view_samples + 3 * (int64_t)(view_count == 1 ? 0 : h % (uint32_t)view_count);
        sa += tri_solid_angle(positions, triangles, t, v);
      }
      sa /= k_count;
    }
    weights[t] = mode == MRGI_ISM_UNIFORM ? area : sa;
    sa_sum += weights[t];
  }
  if (!(area_sum > 0.0) || !isfinite(area_sum))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM points: the mesh has total area %g (all triangles degenerate?)", area_sum);
  if (mode == MRGI_ISM_UNIFORM)
  {
    for (int32_t t = 0; t < triangle_count; ++t)
      weights[t] /= area_sum;
    return MRGI_OK;
  }
  /* Second pass for the uniform share: recompute areas (no scratch buffer). */
  for (int32_t t = 0; t < triangle_count; ++t)
  {
    double c[3], n[3];
    const double area = tri_geometry(positions, triangles, t, c, n);
    const double share = sa_sum > 0.0 ? MRGI_ISM_UNIFORM_SHARE : 1.0;
    weights[t] =
      (sa_sum > 0.0 ? (1.0 - share) * weights[t] / sa_sum : 0.0) + share * area / area_sum;
  }
  return MRGI_OK;
}

mrgi_status mrgi_ism_cloud_weights(const float* positions, int32_t point_count, mrgi_ism_mode mode,
  const double* view_samples, int32_t view_count, double* weights, mrgi_error* err)
{
  if (!positions || !weights)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: NULL cloud arrays");
  if (point_count <= 0)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: empty point cloud");
  mrgi_status s = check_views(mode, view_samples, view_count, err);
  if (s)
    return s;
  double q_sum = 0.0;
  for (int32_t p = 0; p < point_count; ++p)
  {
    const float* x = positions + 3 * (int64_t)p;
    if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
      return mrgi_error_set(
        err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: cloud point %d is not finite", p);
    double q = 1.0;
    if (mode != MRGI_ISM_UNIFORM)
    {
      q = 0.0;
      for (int32_t k = 0; k < view_count; ++k)
      {
        const double* v = view_samples + 3 * k;
        const double d[3] = { v[0] - x[0], v[1] - x[1], v[2] - x[2] };
        double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        const double m2 = MRGI_ISM_MIN_VIEW_DISTANCE * MRGI_ISM_MIN_VIEW_DISTANCE;
        q += 1.0 / (r2 > m2 ? r2 : m2);
      }
      q /= view_count;
    }
    weights[p] = q;
    q_sum += q;
  }
  if (mode == MRGI_ISM_UNIFORM)
  {
    for (int32_t p = 0; p < point_count; ++p)
      weights[p] = 1.0 / point_count;
    return MRGI_OK;
  }
  for (int32_t p = 0; p < point_count; ++p)
    weights[p] =
      (1.0 - MRGI_ISM_UNIFORM_SHARE) * weights[p] / q_sum + MRGI_ISM_UNIFORM_SHARE / point_count;
  return MRGI_OK;
}

mrgi_status mrgi_ism_cdf_build(const double* weights, int32_t count, double* cdf, mrgi_error* err)
{
  if (!weights || !cdf)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: NULL CDF arrays");
  if (count <= 0)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: CDF of %d weights", count);
  double sum = 0.0;
  for (int32_t i = 0; i < count; ++i)
  {
    if (!(weights[i] >= 0.0) || !isfinite(weights[i]))
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "ISM points: weight %d is %g (must be finite, >= 0)", i, weights[i]);
    sum += weights[i];
  }
  if (!(sum > 0.0))
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: weights sum to 0");
  double acc = 0.0;
  cdf[0] = 0.0;
  for (int32_t i = 0; i < count; ++i)
  {
    acc += weights[i];
    cdf[i + 1] = acc / sum;
  }
  cdf[count] = 1.0;
  return MRGI_OK;
}

mrgi_status mrgi_ism_sample(const double* cdf, int32_t count, uint32_t seed, uint32_t generation,
  int32_t total, int32_t begin, int32_t end, mrgi_ism_point* points, mrgi_error* err)
{
  if (!cdf || !points)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: NULL sample arrays");
  if (count <= 0)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: empty CDF");
  if (total <= 0 || total > MRGI_ISM_MAX_POINTS)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM points: point count P = %d outside 1..%d", total, MRGI_ISM_MAX_POINTS);
  if (begin < 0 || end < begin || end > total)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "ISM points: record range [%d, %d) outside [0, %d)", begin, end, total);
  const uint32_t key = ism_hash(seed ^ ism_hash(generation * 0x9e3779b9U + 0x85ebca6bU));
  for (int32_t i = begin; i < end; ++i)
  {
    const uint32_t h = ism_hash(key ^ ism_hash((uint32_t)i));
    const double xi = ((double)i + ism_unit(h)) / total; /* stratified */
    int32_t lo = 0, hi = count - 1;                      /* last t with cdf[t] <= xi */
    while (lo < hi)
    {
      const int32_t mid = lo + (hi - lo + 1) / 2;
      if (cdf[mid] <= xi)
        lo = mid;
      else
        hi = mid - 1;
    }
    while (lo < count - 1 && !(cdf[lo + 1] > cdf[lo])) /* skip weight-0 entries */
      ++lo;
    while (lo > 0 && !(cdf[lo + 1] > cdf[lo]))
      --lo;
    const double a = sqrt(ism_unit(ism_hash(h ^ 0x68e31da4U)));
    const double b = ism_unit(ism_hash(h ^ 0xb5297a4dU));
    points[i].index = lo;
    points[i].u = (float)(1.0 - a);
    points[i].v = (float)(b * a);
  }
  return MRGI_OK;
}

void mrgi_ism_lazy_range_n(
  int32_t total, int64_t frame, int32_t lazy_frames, int32_t* begin, int32_t* end)
{
  const int64_t n = lazy_frames >= 1 ? lazy_frames : 1;
  int64_t j = frame % n;
  if (j < 0)
    j += n;
  const int64_t p = total > 0 ? total : 0;
  if (begin)
    *begin = (int32_t)(j * p / n);
  if (end)
    *end = (int32_t)((j + 1) * p / n);
}

uint32_t mrgi_ism_lazy_generation_n(int64_t frame, int32_t lazy_frames)
{
  const int64_t n = lazy_frames >= 1 ? lazy_frames : 1;
  return (uint32_t)(frame / n + 1);
}

void mrgi_ism_lazy_range(int32_t total, int64_t frame, int32_t* begin, int32_t* end)
{
  mrgi_ism_lazy_range_n(total, frame, MRGI_ISM_LAZY_FRAMES, begin, end);
}

uint32_t mrgi_ism_lazy_generation(int64_t frame)
{
  return mrgi_ism_lazy_generation_n(frame, MRGI_ISM_LAZY_FRAMES);
}

mrgi_status mrgi_ism_points_evaluate(const float* positions, int32_t vertex_count,
  const int32_t* triangles, int32_t triangle_count, const mrgi_ism_point* points,
  int32_t point_count, float* out_positions, float* out_normals, mrgi_error* err)
{
  mrgi_status s = check_mesh(positions, vertex_count, triangles, triangle_count, err);
  if (s)
    return s;
  if (!points || point_count < 0)
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "ISM points: NULL or negative records");
  for (int32_t i = 0; i < point_count; ++i)
  {
    const mrgi_ism_point r = points[i];
    if (r.index < 0 || r.index >= triangle_count || !(r.u >= 0.0f) || !(r.v >= 0.0f) ||
      r.u + r.v > 1.0f + 1e-6f)
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "ISM points: record %d (triangle %d, u %g, v %g) is outside the mesh", i, r.index,
        (double)r.u, (double)r.v);
    const float* a = positions + 3 * triangles[3 * r.index];
    const float* b = positions + 3 * triangles[3 * r.index + 1];
    const float* c = positions + 3 * triangles[3 * r.index + 2];
    const double w = 1.0 - r.u - r.v;
    double cc[3], n[3];
    const double area = tri_geometry(positions, triangles, r.index, cc, n);
    for (int k = 0; k < 3; ++k)
    {
      if (out_positions)
        out_positions[3 * (int64_t)i + k] = (float)(w * a[k] + r.u * b[k] + r.v * c[k]);
      if (out_normals)
        out_normals[3 * (int64_t)i + k] = area > 0.0 ? (float)(n[k] / (2.0 * area)) : 0.0f;
    }
  }
  return MRGI_OK;
}
