/* Point normals and radii: see mrgi_point_normals.h. */
#include "mrgi_point_normals.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MRGI_PI 3.14159265358979323846

/* Neighbourhoods whose middle eigenvalue is below this fraction of the
 * largest are lines, not planes (1e-6: a 1e-3 relative width). */
#define COLLINEAR_RATIO 1e-6

void mrgi_point_normals_default_options(mrgi_point_normals_options* options)
{
  if (!options)
  {
    return;
  }
  memset(options, 0, sizeof(*options));
  options->k = MRGI_NORMALS_DEFAULT_K;
  options->radius_scale = 1.0;
  options->orientation = MRGI_ORIENT_OUTWARD;
  options->up[2] = 1.0;
}

/* Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi
 * rotations: values ascending, vectors[i] the unit eigenvector of values[i]. */
static void eigen_symmetric3(const double m[9], double values[3], double vectors[3][3])
{
  double a[3][3] = { { m[0], m[1], m[2] }, { m[1], m[4], m[5] }, { m[2], m[5], m[8] } };
  double v[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
    const double diag = fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2]);
    if (off == 0.0 || off <= 1e-300 || off < 1e-15 * diag)
    {
      break;
    }
    for (int p = 0; p < 2; ++p)
    {
      for (int q = p + 1; q < 3; ++q)
      {
        if (a[p][q] == 0.0)
        {
          continue;
        }
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
        const double c = 1.0 / sqrt(t * t + 1.0);
        const double s = t * c;
        for (int k = 0; k < 3; ++k)
        {
          /* columns p, q of A */
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k)
        {
          /* rows p, q of A */
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int order[3] = { 0, 1, 2 };
  for (int i = 0; i < 2; ++i)
  {
    for (int j = i + 1; j < 3; ++j)
    {
      if (a[order[j]][order[j]] < a[order[i]][order[i]])
      {
        const int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    values[i] = a[order[i]][order[i]];
    double len = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      vectors[i][k] = v[k][order[i]];
      len += vectors[i][k] * vectors[i][k];
    }
    len = sqrt(len);
    for (int k = 0; k < 3; ++k)
    {
      vectors[i][k] = len > 0.0 ? vectors[i][k] / len : (k == i ? 1.0 : 0.0);
    }
  }
}

void mrgi_point_normals_smallest_eigenvector(
  const double covariance[9], double eigenvalues[3], double normal[3])
{
  double values[3], vectors[3][3];
  eigen_symmetric3(covariance, values, vectors);
  if (eigenvalues)
  {
    memcpy(eigenvalues, values, sizeof(values));
  }
  memcpy(normal, vectors[0], sizeof(vectors[0]));
}

static int finite3(const float* p)
{
  return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static int normalize3(double v[3])
{
  const double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(len > 1e-300) || !isfinite(len))
  {
    return 0;
  }
  v[0] /= len;
  v[1] /= len;
  v[2] /= len;
  return 1;
}

/* The uniform search grid over the finite points. */
typedef struct grid
{
  double origin[3];
  double h;        /* cell edge */
  int64_t dims[3]; /* cells per axis, >= 1 */
  uint32_t* start; /* cells + 1 offsets into order */
  uint32_t* order; /* finite point indices sorted by cell */
} grid;

static int64_t cell_coord(const grid* g, double x, int axis)
{
  if (g->h <= 0.0)
  {
    return 0;
  }
  double c = floor((x - g->origin[axis]) / g->h);
  if (c < 0.0)
  {
    c = 0.0;
  }
  if (c > (double)(g->dims[axis] - 1))
  {
    c = (double)(g->dims[axis] - 1);
  }
  return (int64_t)c;
}

/* Cells of a grid with edge h over extents e (doubles: no overflow). */
static double cells_for(const double e[3], double h)
{
  double n = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    const double c = ceil(e[a] / h);
    n *= c < 1.0 ? 1.0 : c;
  }
  return n;
}

/* Marks a non-finite point in cell_of. */
#define NO_CELL 0xFFFFFFFFu

/* The grid with cell edge h over extents e (dims >= 1 each). */
static void set_grid_size_edge(grid* g, const double e[3], double h)
{
  g->h = h;
  for (int a = 0; a < 3; ++a)
  {
    const double c = h > 0.0 ? ceil(e[a] / h) : 1.0;
    g->dims[a] = c < 1.0 ? 1 : (int64_t)c;
  }
}

/* The grid with the smallest cell edge giving at most `target` cells. */
static void set_grid_size(grid* g, const double e[3], double target)
{
  double emax = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    emax = e[a] > emax ? e[a] : emax;
  }
  if (!(emax > 0.0))
  {
    set_grid_size_edge(g, e, 0.0);
    return;
  }
  double h_lo = emax / (target + 1.0), h_hi = emax * 1.000001;
  for (int it = 0; it < 64 && target > 1.0; ++it)
  {
    const double mid = 0.5 * (h_lo + h_hi);
    if (cells_for(e, mid) > target)
    {
      h_lo = mid;
    }
    else
    {
      h_hi = mid;
    }
  }
  set_grid_size_edge(g, e, h_hi);
}

/* Each finite point's cell (NO_CELL for the others) and the cells' starts
 * as prefix sums (start[c] = first slot of cell c); returns how many cells
 * hold a point. */
static int64_t count_cells(grid* g, const float* positions, int64_t count, uint32_t* cell_of)
{
  const int64_t cells = g->dims[0] * g->dims[1] * g->dims[2];
  memset(g->start, 0, sizeof(uint32_t) * ((size_t)cells + 1));
  for (int64_t i = 0; i < count; ++i)
  {
    const float* p = positions + 3 * i;
    if (!finite3(p))
    {
      cell_of[i] = NO_CELL;
      continue;
    }
    const int64_t cell =
      (cell_coord(g, p[2], 2) * g->dims[1] + cell_coord(g, p[1], 1)) * g->dims[0] +
      cell_coord(g, p[0], 0);
    cell_of[i] = (uint32_t)cell;
    ++g->start[cell + 1];
  }
  int64_t occupied = 0;
  for (int64_t c = 0; c < cells; ++c)
  {
    occupied += g->start[c + 1] > 0 ? 1 : 0;
    g->start[c + 1] += g->start[c];
  }
  return occupied;
}

/* The k nearest finite points of the point in slot i (itself excluded),
 * sorted by distance: d2[0..found), their slots idx[0..found). `sorted`
 * holds the finite points in slot (cell) order: neighbours are read from
 * nearby memory. */
static int knn(const grid* g, const float* sorted, uint32_t i, int k, double* d2, uint32_t* idx)
{
  const float* p = sorted + 3 * (size_t)i;
  const double px = p[0], py = p[1], pz = p[2];
  const int64_t c[3] = { cell_coord(g, px, 0), cell_coord(g, py, 1), cell_coord(g, pz, 2) };
  /* Distance from p to the nearest face of its own cell: every point in a
   * cell of ring r + 1 is at least r * h + this far. */
  double face = INFINITY;
  for (int a = 0; a < 3; ++a)
  {
    if (g->dims[a] > 1)
    {
      const double lo = g->origin[a] + (double)c[a] * g->h;
      const double x = a == 0 ? px : a == 1 ? py : pz;
      double f = x - lo;
      if (g->h - f < f)
      {
        f = g->h - f;
      }
      if (f < face)
      {
        face = f;
      }
    }
  }
  if (!(face >= 0.0) || face == INFINITY)
  {
    face = 0.0;
  }
  int found = 0;
  for (int64_t r = 0;; ++r)
  {
    const int64_t z0 = c[2] - r < 0 ? 0 : c[2] - r;
    const int64_t z1 = c[2] + r > g->dims[2] - 1 ? g->dims[2] - 1 : c[2] + r;
    const int64_t y0 = c[1] - r < 0 ? 0 : c[1] - r;
    const int64_t y1 = c[1] + r > g->dims[1] - 1 ? g->dims[1] - 1 : c[1] + r;
    const int64_t x0 = c[0] - r < 0 ? 0 : c[0] - r;
    const int64_t x1 = c[0] + r > g->dims[0] - 1 ? g->dims[0] - 1 : c[0] + r;
    for (int64_t z = z0; z <= z1; ++z)
    {
      for (int64_t y = y0; y <= y1; ++y)
      {
        const int full = (z == c[2] - r || z == c[2] + r || y == c[1] - r || y == c[1] + r);
        /* Inside the shell only the two end cells of the row are new. */
        const int64_t step = full ? 1 : 2 * r;
        for (int64_t x = full ? x0 : c[0] - r; x <= (full ? x1 : c[0] + r); x += step)
        {
          if (x < 0 || x >= g->dims[0])
          {
            continue;
          }
          const int64_t cell = (z * g->dims[1] + y) * g->dims[0] + x;
          for (uint32_t s = g->start[cell]; s < g->start[cell + 1]; ++s)
          {
            const uint32_t j = s;
            if (j == i)
            {
              continue;
            }
            const float* q = sorted + 3 * (size_t)j;
            const double dx = q[0] - px, dy = q[1] - py, dz = q[2] - pz;
            const double d = dx * dx + dy * dy + dz * dz;
            if (found == k && d >= d2[k - 1])
            {
              continue;
            }
            int at = found < k ? found++ : k - 1;
            while (at > 0 && d2[at - 1] > d)
            {
              d2[at] = d2[at - 1];
              idx[at] = idx[at - 1];
              --at;
            }
            d2[at] = d;
            idx[at] = j;
          }
        }
      }
    }
    const int covered = x0 == 0 && y0 == 0 && z0 == 0 && x1 == g->dims[0] - 1 &&
      y1 == g->dims[1] - 1 && z1 == g->dims[2] - 1;
    if (covered)
    {
      break;
    }
    if (found == k)
    {
      const double bound = (double)r * g->h + face;
      if (d2[k - 1] <= bound * bound)
      {
        break;
      }
    }
  }
  return found;
}

static mrgi_status check_options(const mrgi_point_normals_options* o, mrgi_error* err)
{
  if (o->k < MRGI_NORMALS_MIN_K || o->k > MRGI_NORMALS_MAX_K)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "point normals: k = %d is outside [%d, %d]", (int)o->k, MRGI_NORMALS_MIN_K,
      MRGI_NORMALS_MAX_K);
  }
  if (!isfinite(o->radius_scale) || !(o->radius_scale > 0.0))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "point normals: radius_scale = %g must be finite and > 0", o->radius_scale);
  }
  switch (o->orientation)
  {
    case MRGI_ORIENT_VIEWPOINT:
      if (!isfinite(o->viewpoint[0]) || !isfinite(o->viewpoint[1]) || !isfinite(o->viewpoint[2]))
      {
        return mrgi_error_set(
          err, MRGI_ERR_INVALID_ARGUMENT, "point normals: the viewpoint is not finite");
      }
      break;
    case MRGI_ORIENT_UP:
    {
      double up[3] = { o->up[0], o->up[1], o->up[2] };
      if (!isfinite(up[0]) || !isfinite(up[1]) || !isfinite(up[2]) || !normalize3(up))
      {
        return mrgi_error_set(
          err, MRGI_ERR_INVALID_ARGUMENT, "point normals: the up vector is zero or not finite");
      }
      break;
    }
    case MRGI_ORIENT_OUTWARD:
      break;
    default:
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "point normals: unknown orientation %d",
        (int)o->orientation);
  }
  return MRGI_OK;
}

/* The direction used when a neighbourhood has no plane. */
static void fallback_direction(const mrgi_point_normals_options* o, const float* p, double out[3])
{
  out[0] = 0.0;
  out[1] = 0.0;
  out[2] = 1.0;
  if (o->orientation == MRGI_ORIENT_VIEWPOINT && finite3(p))
  {
    double v[3] = { o->viewpoint[0] - p[0], o->viewpoint[1] - p[1], o->viewpoint[2] - p[2] };
    if (normalize3(v))
    {
      memcpy(out, v, sizeof(v));
    }
  }
  else if (o->orientation == MRGI_ORIENT_UP)
  {
    double v[3] = { o->up[0], o->up[1], o->up[2] };
    if (normalize3(v))
    {
      memcpy(out, v, sizeof(v));
    }
  }
}

mrgi_status mrgi_point_normals_compute(const float* positions, int64_t count,
  const mrgi_point_normals_options* options, float* normals, float* radii, uint8_t* flags,
  mrgi_point_normals_stats* stats, mrgi_error* err)
{
  mrgi_point_normals_options o;
  if (options)
  {
    o = *options;
  }
  else
  {
    mrgi_point_normals_default_options(&o);
  }
  if (stats)
  {
    memset(stats, 0, sizeof(*stats));
  }
  if (count < 0 || count > MRGI_NORMALS_MAX_POINTS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "point normals: count = %lld is outside [0, %lld]", (long long)count,
      (long long)MRGI_NORMALS_MAX_POINTS);
  }
  if (!positions && count > 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "point normals: positions is NULL");
  }
  const mrgi_status checked = check_options(&o, err);
  if (checked != MRGI_OK)
  {
    return checked;
  }
  if (count == 0)
  {
    return MRGI_OK;
  }

  /* Bounds and centroid of the finite points. */
  double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  double centroid[3] = { 0, 0, 0 };
  int64_t finite = 0;
  for (int64_t i = 0; i < count; ++i)
  {
    const float* p = positions + 3 * i;
    if (!finite3(p))
    {
      continue;
    }
    ++finite;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = p[a] < lo[a] ? p[a] : lo[a];
      hi[a] = p[a] > hi[a] ? p[a] : hi[a];
      centroid[a] += p[a];
    }
  }
  grid g;
  memset(&g, 0, sizeof(g));
  double e[3] = { 0.0, 0.0, 0.0 };
  if (finite > 0)
  {
    for (int a = 0; a < 3; ++a)
    {
      centroid[a] /= (double)finite;
      g.origin[a] = lo[a];
      e[a] = hi[a] - lo[a];
    }
  }
  /* First about one cell per two points over the bounding box; max_cells
   * (cell indices stay below NO_CELL) bounds the refinement below. */
  const int64_t max_cells =
    4 * finite + 1 < (int64_t)0xFFFFFFF0 ? 4 * finite + 1 : (int64_t)0xFFFFFFF0;
  set_grid_size(&g, e, finite / 2 > 1 ? (double)(finite / 2) : 1.0);

  /* One allocation: per point its cell, the sorted order, the cell starts. */
  const size_t words = (size_t)count * 2 + (size_t)max_cells + 1;
  void* memory = malloc(words * sizeof(uint32_t) + (size_t)finite * 3 * sizeof(float));
  if (!memory)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
      "point normals: cannot allocate the search grid for %lld points", (long long)count);
  }
  uint32_t* cell_of = (uint32_t*)memory;
  g.order = cell_of + count;
  g.start = cell_of + 2 * count;
  float* sorted = (float*)(cell_of + words);
  int64_t occupied = count_cells(&g, positions, count, cell_of);
  /* Points on a surface fill few cells of a volume grid, each with many
   * points: refine once so that occupied cells hold about 3 points (the
   * occupancy of a surface grid falls with the square of the edge). */
  if (occupied > 0 && (double)finite / (double)occupied > 6.0)
  {
    const double shrink = sqrt(((double)finite / (double)occupied) / 3.0);
    const double before = g.h;
    set_grid_size(&g, e, (double)max_cells);
    if (g.h < before / shrink)
    {
      set_grid_size_edge(&g, e, before / shrink);
    }
    occupied = count_cells(&g, positions, count, cell_of);
  }
  const int64_t cells = g.dims[0] * g.dims[1] * g.dims[2];
  /* Counting sort: start[c] runs over cell c's slots while filling; the
   * non-finite points take the slots after the finite ones. */
  uint32_t tail = (uint32_t)finite;
  for (int64_t i = 0; i < count; ++i)
  {
    if (cell_of[i] != NO_CELL)
    {
      const uint32_t slot = g.start[cell_of[i]]++;
      g.order[slot] = (uint32_t)i;
      memcpy(sorted + 3 * (size_t)slot, positions + 3 * i, 3 * sizeof(float));
    }
    else
    {
      g.order[tail++] = (uint32_t)i;
    }
  }
  /* The loop above advanced each start to the next cell's: shift back. */
  for (int64_t c = cells; c > 0; --c)
  {
    g.start[c] = g.start[c - 1];
  }
  g.start[0] = 0;

  mrgi_point_normals_stats st;
  memset(&st, 0, sizeof(st));
  st.finite = finite;
  st.non_finite = count - finite;
  st.grid_cells = cells;
  double radius_sum = 0.0;
  int64_t radius_count = 0;
  double d2[MRGI_NORMALS_MAX_K];
  uint32_t idx[MRGI_NORMALS_MAX_K];
  /* In slot order (cell by cell: neighbourhoods stay in cache). */
  for (int64_t slot = 0; slot < count; ++slot)
  {
    const int64_t i = g.order[slot];
    const float* p = positions + 3 * i;
    uint8_t flag = 0;
    double n[3];
    double radius = 0.0;
    fallback_direction(&o, p, n);
    if (slot >= finite)
    {
      flag = MRGI_POINT_NON_FINITE | MRGI_POINT_NO_SPACING;
    }
    else
    {
      const int found = knn(&g, sorted, (uint32_t)slot, o.k, d2, idx);
      /* Covariance about p (small numbers: no cancellation), then moved to
       * the neighbourhood's mean. */
      double mean[3] = { 0, 0, 0 }, c[9] = { 0 };
      for (int j = 0; j < found; ++j)
      {
        const float* q = sorted + 3 * (size_t)idx[j];
        const double d[3] = { (double)q[0] - p[0], (double)q[1] - p[1], (double)q[2] - p[2] };
        for (int a = 0; a < 3; ++a)
        {
          mean[a] += d[a];
          for (int b = a; b < 3; ++b)
          {
            c[3 * a + b] += d[a] * d[b];
          }
        }
      }
      const double m = (double)(found + 1);
      for (int a = 0; a < 3; ++a)
      {
        mean[a] /= m;
      }
      for (int a = 0; a < 3; ++a)
      {
        for (int b = a; b < 3; ++b)
        {
          c[3 * a + b] = c[3 * a + b] / m - mean[a] * mean[b];
        }
      }
      double values[3], vectors[3][3];
      eigen_symmetric3(c, values, vectors);
      if (found >= 2 && values[2] > 0.0 && values[1] > COLLINEAR_RATIO * values[2])
      {
        memcpy(n, vectors[0], sizeof(n));
      }
      else
      {
        flag |= MRGI_POINT_DEGENERATE;
        if (found >= 1 && values[2] > 0.0)
        {
          /* A line: the fallback made perpendicular to it. */
          const double* l = vectors[2];
          const double dot = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
          double t[3] = { n[0] - dot * l[0], n[1] - dot * l[1], n[2] - dot * l[2] };
          if (fabs(dot) > 0.999 || !normalize3(t))
          {
            /* Fallback along the line: the axis least aligned with it. */
            int axis = 0;
            for (int a = 1; a < 3; ++a)
            {
              axis = fabs(l[a]) < fabs(l[axis]) ? a : axis;
            }
            double u[3] = { 0, 0, 0 };
            u[axis] = 1.0;
            const double du = l[axis];
            t[0] = u[0] - du * l[0];
            t[1] = u[1] - du * l[1];
            t[2] = u[2] - du * l[2];
            normalize3(t);
          }
          memcpy(n, t, sizeof(t));
        }
      }
      if (found > 0 && d2[found - 1] > 0.0)
      {
        radius = o.radius_scale * sqrt(d2[found - 1]) * sqrt(MRGI_PI / (double)found);
      }
      if (!(radius > 0.0) || !isfinite(radius))
      {
        radius = 0.0;
        flag |= MRGI_POINT_NO_SPACING;
      }
      /* Orientation. */
      double ref[3];
      switch (o.orientation)
      {
        case MRGI_ORIENT_VIEWPOINT:
          ref[0] = o.viewpoint[0] - p[0];
          ref[1] = o.viewpoint[1] - p[1];
          ref[2] = o.viewpoint[2] - p[2];
          break;
        case MRGI_ORIENT_UP:
          memcpy(ref, o.up, sizeof(ref));
          break;
        default:
          ref[0] = p[0] - centroid[0];
          ref[1] = p[1] - centroid[1];
          ref[2] = p[2] - centroid[2];
          break;
      }
      if (n[0] * ref[0] + n[1] * ref[1] + n[2] * ref[2] < 0.0)
      {
        n[0] = -n[0];
        n[1] = -n[1];
        n[2] = -n[2];
      }
    }
    if (flag & MRGI_POINT_DEGENERATE)
    {
      ++st.degenerate;
    }
    if (flag & MRGI_POINT_NO_SPACING)
    {
      if (!(flag & MRGI_POINT_NON_FINITE))
      {
        ++st.no_spacing;
      }
    }
    else
    {
      radius_sum += radius;
      ++radius_count;
    }
    if (normals)
    {
      normals[3 * i + 0] = (float)n[0];
      normals[3 * i + 1] = (float)n[1];
      normals[3 * i + 2] = (float)n[2];
    }
    if (radii)
    {
      radii[i] = (float)radius;
    }
    if (flags)
    {
      flags[i] = flag;
    }
  }
  free(memory);
  st.mean_radius = radius_count > 0 ? radius_sum / (double)radius_count : 0.0;
  if (stats)
  {
    *stats = st;
  }
  return MRGI_OK;
}
