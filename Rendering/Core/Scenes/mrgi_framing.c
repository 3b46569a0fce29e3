#include "mrgi_framing.h"

#include <math.h>
#include <stddef.h>

#define MRGI_FRAMING_PI 3.14159265358979323846

static double mrgi_framing_dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void mrgi_framing_cross(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Unit direction, right and up vectors; 0 when the input is unusable. */
static int mrgi_framing_basis(
  const double direction[3], const double view_up[3], double d[3], double right[3], double up[3])
{
  const double dn = sqrt(mrgi_framing_dot(direction, direction));
  if (!(dn > 0.0) || !isfinite(dn))
  {
    return 0;
  }
  for (int k = 0; k < 3; ++k)
  {
    d[k] = direction[k] / dn;
  }
  const double along = mrgi_framing_dot(view_up, d);
  for (int k = 0; k < 3; ++k)
  {
    up[k] = view_up[k] - along * d[k];
  }
  const double un = sqrt(mrgi_framing_dot(up, up));
  const double vn = sqrt(mrgi_framing_dot(view_up, view_up));
  if (!isfinite(vn) || !(un > 1e-6 * vn))
  {
    return 0;
  }
  for (int k = 0; k < 3; ++k)
  {
    up[k] /= un;
  }
  mrgi_framing_cross(d, up, right);
  return 1;
}

static mrgi_status mrgi_framing_check(const double* points, int64_t count,
  const double direction[3], const double view_up[3], double view_angle_deg, double aspect,
  const char* who, mrgi_error* err)
{
  if (!points || !direction || !view_up)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: NULL argument", who);
  }
  if (count < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: no points", who);
  }
  if (!(view_angle_deg > 0.0 && view_angle_deg < 180.0))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "%s: view angle must be in (0, 180) degrees", who);
  }
  if (!(aspect > 0.0) || !isfinite(aspect))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "%s: aspect must be > 0", who);
  }
  for (int64_t i = 0; i < 3 * count; ++i)
  {
    if (!isfinite(points[i]))
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "%s: point %lld has a coordinate that is not finite", who, (long long)(i / 3));
    }
  }
  double d[3], r[3], u[3];
  if (!mrgi_framing_basis(direction, view_up, d, r, u))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "%s: direction and view_up must be finite, non-zero and not parallel", who);
  }
  return MRGI_OK;
}

/* Fill and centre without checks; the basis is given. */
static double mrgi_framing_fill_raw(const double* points, int64_t count, const double p[3],
  const double d[3], const double r[3], const double u[3], double tan_h, double aspect,
  double center[2])
{
  double lo[2] = { INFINITY, INFINITY };
  double hi[2] = { -INFINITY, -INFINITY };
  for (int64_t i = 0; i < count; ++i)
  {
    const double* x = points + 3 * i;
    const double v[3] = { x[0] - p[0], x[1] - p[1], x[2] - p[2] };
    const double z = mrgi_framing_dot(v, d);
    if (!(z > 0.0))
    {
      if (center)
      {
        center[0] = center[1] = 0.0;
      }
      return INFINITY;
    }
    const double s[2] = { mrgi_framing_dot(v, r) / (z * tan_h * aspect),
      mrgi_framing_dot(v, u) / (z * tan_h) };
    for (int k = 0; k < 2; ++k)
    {
      lo[k] = s[k] < lo[k] ? s[k] : lo[k];
      hi[k] = s[k] > hi[k] ? s[k] : hi[k];
    }
  }
  if (center)
  {
    center[0] = 0.5 * (lo[0] + hi[0]);
    center[1] = 0.5 * (lo[1] + hi[1]);
  }
  const double fx = 0.5 * (hi[0] - lo[0]);
  const double fy = 0.5 * (hi[1] - lo[1]);
  return fx > fy ? fx : fy;
}

mrgi_status mrgi_frame_fill(const double* points, int64_t count, const double position[3],
  const double direction[3], const double view_up[3], double view_angle_deg, double aspect,
  double* fill, double center[2], mrgi_error* err)
{
  mrgi_status status = mrgi_framing_check(
    points, count, direction, view_up, view_angle_deg, aspect, "mrgi_frame_fill", err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!position || !fill || !isfinite(position[0]) || !isfinite(position[1]) ||
    !isfinite(position[2]))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_frame_fill: position or fill is NULL or not finite");
  }
  double d[3], r[3], u[3];
  mrgi_framing_basis(direction, view_up, d, r, u);
  const double tan_h = tan(0.5 * view_angle_deg * MRGI_FRAMING_PI / 180.0);
  *fill = mrgi_framing_fill_raw(points, count, position, d, r, u, tan_h, aspect, center);
  return MRGI_OK;
}

mrgi_status mrgi_frame_points(const double* points, int64_t count, const double direction[3],
  const double view_up[3], double view_angle_deg, double aspect, double fill, mrgi_framing* out,
  mrgi_error* err)
{
  mrgi_status status = mrgi_framing_check(
    points, count, direction, view_up, view_angle_deg, aspect, "mrgi_frame_points", err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_frame_points: out is NULL");
  }
  if (!(fill > 0.0 && fill <= 1.0))
  {
    return mrgi_error_set(
      err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_frame_points: fill must be in (0, 1]");
  }
  double d[3], r[3], u[3];
  mrgi_framing_basis(direction, view_up, d, r, u);
  const double tan_h = tan(0.5 * view_angle_deg * MRGI_FRAMING_PI / 180.0);

  /* The centre and radius of the points' bounding box. */
  double lo[3] = { points[0], points[1], points[2] };
  double hi[3] = { points[0], points[1], points[2] };
  for (int64_t i = 1; i < count; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double x = points[3 * i + k];
      lo[k] = x < lo[k] ? x : lo[k];
      hi[k] = x > hi[k] ? x : hi[k];
    }
  }
  double focal[3], radius = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    focal[k] = 0.5 * (lo[k] + hi[k]);
    radius += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
  }
  radius = sqrt(radius);
  for (int k = 0; k < 3; ++k)
  {
    out->view_up[k] = u[k];
  }
  if (!(radius > 0.0))
  {
    for (int k = 0; k < 3; ++k)
    {
      out->focal[k] = focal[k];
      out->position[k] = focal[k] - d[k];
    }
    out->fill = 0.0;
    return MRGI_OK;
  }

  double distance = radius;
  double position[3];
  for (int round = 0; round < 16; ++round)
  {
    /* Bisection on the distance: nearest with every point in front (and a
     * margin), farthest where the fill is below the target. */
    double nearest = 0.0;
    for (int64_t i = 0; i < count; ++i)
    {
      const double* x = points + 3 * i;
      const double v[3] = { x[0] - focal[0], x[1] - focal[1], x[2] - focal[2] };
      const double ahead = -mrgi_framing_dot(v, d); /* depth before the focal plane */
      nearest = ahead > nearest ? ahead : nearest;
    }
    double near_d = nearest + 1e-6 * radius;
    double far_d = near_d + radius;
    for (int grow = 0; grow < 200; ++grow)
    {
      for (int k = 0; k < 3; ++k)
      {
        position[k] = focal[k] - far_d * d[k];
      }
      if (mrgi_framing_fill_raw(points, count, position, d, r, u, tan_h, aspect, NULL) < fill)
      {
        break;
      }
      far_d *= 2.0;
    }
    for (int step = 0; step < 80; ++step)
    {
      const double mid = 0.5 * (near_d + far_d);
      for (int k = 0; k < 3; ++k)
      {
        position[k] = focal[k] - mid * d[k];
      }
      if (mrgi_framing_fill_raw(points, count, position, d, r, u, tan_h, aspect, NULL) > fill)
      {
        near_d = mid;
      }
      else
      {
        far_d = mid;
      }
    }
    distance = far_d;
    for (int k = 0; k < 3; ++k)
    {
      position[k] = focal[k] - distance * d[k];
    }
    double center[2];
    mrgi_framing_fill_raw(points, count, position, d, r, u, tan_h, aspect, center);
    if (fabs(center[0]) < 1e-4 && fabs(center[1]) < 1e-4)
    {
      break;
    }
    /* Move the camera sideways so that the rectangle's centre comes to the
     * image centre (exact for points at the focal depth). */
    for (int k = 0; k < 3; ++k)
    {
      focal[k] += distance * tan_h * (center[0] * aspect * r[k] + center[1] * u[k]);
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    out->focal[k] = focal[k];
    out->position[k] = focal[k] - distance * d[k];
  }
  out->fill = mrgi_framing_fill_raw(points, count, out->position, d, r, u, tan_h, aspect, NULL);
  return MRGI_OK;
}
