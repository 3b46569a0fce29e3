#include "mrgi_up_axis.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

static int mrgi_up_finite3(const double v[3])
{
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

mrgi_status mrgi_up_evidence_init(mrgi_up_evidence* ev, const double bounds[6], mrgi_error* err)
{
  if (!ev || !bounds)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_up_evidence_init: NULL argument");
  }
  for (int k = 0; k < 3; ++k)
  {
    if (!isfinite(bounds[2 * k]) || !isfinite(bounds[2 * k + 1]) ||
      bounds[2 * k] > bounds[2 * k + 1])
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "mrgi_up_evidence_init: bounds of axis %d are not finite or inverted", k);
    }
  }
  memset(ev, 0, sizeof(*ev));
  memcpy(ev->bounds, bounds, sizeof(ev->bounds));
  return MRGI_OK;
}

void mrgi_up_add_triangle(
  mrgi_up_evidence* ev, const double a[3], const double b[3], const double c[3])
{
  if (!ev || !a || !b || !c || !mrgi_up_finite3(a) || !mrgi_up_finite3(b) || !mrgi_up_finite3(c))
  {
    return;
  }
  double e1[3], e2[3], n[3];
  for (int k = 0; k < 3; ++k)
  {
    e1[k] = b[k] - a[k];
    e2[k] = c[k] - a[k];
  }
  n[0] = 0.5 * (e1[1] * e2[2] - e1[2] * e2[1]);
  n[1] = 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]);
  n[2] = 0.5 * (e1[0] * e2[1] - e1[1] * e2[0]);
  const double area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(area > 0.0) || !isfinite(area))
  {
    return;
  }
  ev->total_area += area;
  const double flat = cos(MRGI_UP_FLAT_DEG * 3.14159265358979323846 / 180.0);
  for (int k = 0; k < 3; ++k)
  {
    ev->area_vector[k] += n[k];
    if (fabs(n[k]) < flat * area)
    {
      continue;
    }
    const double lo = ev->bounds[2 * k];
    const double extent = ev->bounds[2 * k + 1] - lo;
    const double centroid = (a[k] + b[k] + c[k]) / 3.0;
    const double band = MRGI_UP_BASE_BAND * extent;
    if (centroid - lo <= band)
    {
      ev->base_area[2 * k] += area;
    }
    else if (ev->bounds[2 * k + 1] - centroid <= band)
    {
      ev->base_area[2 * k + 1] += area;
    }
  }
}

void mrgi_up_add_point(mrgi_up_evidence* ev, const double p[3])
{
  if (!ev || !p || !mrgi_up_finite3(p))
  {
    return;
  }
  ev->point_count += 1.0;
  for (int k = 0; k < 3; ++k)
  {
    const double band = MRGI_UP_BASE_BAND * (ev->bounds[2 * k + 1] - ev->bounds[2 * k]);
    if (p[k] - ev->bounds[2 * k] <= band)
    {
      ev->point_base[2 * k] += 1.0;
    }
    else if (ev->bounds[2 * k + 1] - p[k] <= band)
    {
      ev->point_base[2 * k + 1] += 1.0;
    }
  }
}

void mrgi_up_add_boundary_edge(mrgi_up_evidence* ev, const double a[3], const double b[3])
{
  if (!ev || !a || !b || !mrgi_up_finite3(a) || !mrgi_up_finite3(b))
  {
    return;
  }
  const double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double length = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!isfinite(length))
  {
    return;
  }
  ev->boundary_length += length;
  for (int k = 0; k < 3; ++k)
  {
    ev->boundary_sum[k] += 0.5 * (a[k] + b[k]) * length;
  }
}

/* The direction pointing away from end `end` (0 = low, 1 = high) of axis k. */
static mrgi_axis mrgi_up_away_from(int k, int end)
{
  return (mrgi_axis)(2 * k + (end ? 1 : 0));
}

mrgi_status mrgi_up_decide(const mrgi_up_evidence* ev, mrgi_up_decision* out, mrgi_error* err)
{
  if (!ev || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_up_decide: NULL argument");
  }
  out->up = MRGI_AXIS_POS_Y;
  out->reason = MRGI_UP_REASON_DEFAULT;
  const double total = ev->total_area;

  /* 1. A flat base: one end of one axis holds a large, dominant flat area. */
  if (total > 0.0)
  {
    int best = 0;
    for (int i = 1; i < 6; ++i)
    {
      if (ev->base_area[i] > ev->base_area[best])
      {
        best = i;
      }
    }
    int dominant = ev->base_area[best] >= MRGI_UP_BASE_MIN_FRACTION * total;
    for (int i = 0; i < 6 && dominant; ++i)
    {
      if (i != best && ev->base_area[best] < MRGI_UP_BASE_DOMINANCE * ev->base_area[i])
      {
        dominant = 0;
      }
    }
    if (dominant)
    {
      out->up = mrgi_up_away_from(best / 2, best % 2);
      out->reason = MRGI_UP_REASON_FLAT_BASE;
      return MRGI_OK;
    }
  }

  /* 2. An open base: the holes' area vector along one axis, the boundary at
   * one end of it. */
  if (total > 0.0 && ev->boundary_length > 0.0)
  {
    int k = 0;
    for (int i = 1; i < 3; ++i)
    {
      if (fabs(ev->area_vector[i]) > fabs(ev->area_vector[k]))
      {
        k = i;
      }
    }
    const double s = fabs(ev->area_vector[k]);
    int dominant = s >= MRGI_UP_OPEN_MIN_FRACTION * total;
    for (int i = 0; i < 3 && dominant; ++i)
    {
      if (i != k && s < MRGI_UP_BASE_DOMINANCE * fabs(ev->area_vector[i]))
      {
        dominant = 0;
      }
    }
    const double extent = ev->bounds[2 * k + 1] - ev->bounds[2 * k];
    if (dominant && extent > 0.0)
    {
      const double where = (ev->boundary_sum[k] / ev->boundary_length - ev->bounds[2 * k]) / extent;
      if (where <= MRGI_UP_OPEN_END_BAND || where >= 1.0 - MRGI_UP_OPEN_END_BAND)
      {
        out->up = mrgi_up_away_from(k, where >= 0.5);
        out->reason = MRGI_UP_REASON_OPEN_BASE;
        return MRGI_OK;
      }
    }
  }

  /* 3. A point base: clouds only (triangles say more when there are any). */
  if (!(total > 0.0) && ev->point_count > 0.0)
  {
    int best = 0;
    for (int i = 1; i < 6; ++i)
    {
      if (ev->point_base[i] > ev->point_base[best])
      {
        best = i;
      }
    }
    int dominant = ev->point_base[best] >= MRGI_UP_POINT_BASE_MIN_FRACTION * ev->point_count;
    for (int i = 0; i < 6 && dominant; ++i)
    {
      if (i != best && ev->point_base[best] < MRGI_UP_BASE_DOMINANCE * ev->point_base[i])
      {
        dominant = 0;
      }
    }
    if (dominant)
    {
      out->up = mrgi_up_away_from(best / 2, best % 2);
      out->reason = MRGI_UP_REASON_POINT_BASE;
      return MRGI_OK;
    }
  }

  /* 4. A thin extent. */
  double size[3];
  int order[3] = { 0, 1, 2 };
  for (int k = 0; k < 3; ++k)
  {
    size[k] = ev->bounds[2 * k + 1] - ev->bounds[2 * k];
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = i + 1; j < 3; ++j)
    {
      if (size[order[j]] < size[order[i]])
      {
        const int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
    }
  }
  if (size[order[1]] > 0.0 && size[order[0]] <= MRGI_UP_THIN_RATIO * size[order[1]])
  {
    out->up = (mrgi_axis)(2 * order[0]);
    out->reason = MRGI_UP_REASON_THIN_EXTENT;
  }
  return MRGI_OK;
}

void mrgi_axis_vector(mrgi_axis axis, double out[3])
{
  out[0] = out[1] = out[2] = 0.0;
  if ((int)axis >= 0 && (int)axis < 6)
  {
    out[(int)axis / 2] = ((int)axis % 2) ? -1.0 : 1.0;
  }
}

static const char* const mrgi_axis_names[6] = { "+x", "-x", "+y", "-y", "+z", "-z" };

const char* mrgi_axis_name(mrgi_axis axis)
{
  return ((int)axis >= 0 && (int)axis < 6) ? mrgi_axis_names[(int)axis] : "?";
}

mrgi_status mrgi_axis_parse(const char* text, mrgi_axis* out, mrgi_error* err)
{
  if (!text || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_axis_parse: NULL argument");
  }
  const char* p = text;
  int negative = 0;
  if (*p == '+' || *p == '-')
  {
    negative = *p == '-';
    ++p;
  }
  int k = -1;
  if (p[0] != '\0' && p[1] == '\0')
  {
    switch (p[0])
    {
      case 'x':
      case 'X':
        k = 0;
        break;
      case 'y':
      case 'Y':
        k = 1;
        break;
      case 'z':
      case 'Z':
        k = 2;
        break;
      default:
        break;
    }
  }
  if (k < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "'%.40s' is not an axis (expected x, y, z, -x, -y or -z)", text);
  }
  *out = (mrgi_axis)(2 * k + negative);
  return MRGI_OK;
}

const char* mrgi_up_reason_name(mrgi_up_reason reason)
{
  switch (reason)
  {
    case MRGI_UP_REASON_FLAT_BASE:
      return "flat base";
    case MRGI_UP_REASON_OPEN_BASE:
      return "open base";
    case MRGI_UP_REASON_THIN_EXTENT:
      return "thin extent";
    case MRGI_UP_REASON_DEFAULT:
      return "default";
    case MRGI_UP_REASON_POINT_BASE:
      return "point base";
  }
  return "?";
}
