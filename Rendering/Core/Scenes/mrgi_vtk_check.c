#include "mrgi_vtk_check.h"

#include "mrgi_input.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* A reader over the file: ASCII tokens or big-endian binary values. */
typedef struct vtk_reader
{
  const unsigned char* d;
  size_t n;
  size_t pos;
  int binary;
  const char* name;
  mrgi_error* err;
  char tok[256];
} vtk_reader;

/* Stops the check and accepts the rest of the file. */
#define VTK_STOP 1000

static int is_space(unsigned char c)
{
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v' || c == '\0';
}

/* Reads the next token into r->tok; 0 at the end, -1 when too long. */
static int vtk_token(vtk_reader* r)
{
  while (r->pos < r->n && is_space(r->d[r->pos]))
    ++r->pos;
  if (r->pos >= r->n)
    return 0;
  size_t k = 0;
  while (r->pos < r->n && !is_space(r->d[r->pos]))
  {
    if (k + 1 >= sizeof(r->tok))
      return -1;
    r->tok[k++] = (char)r->d[r->pos++];
  }
  r->tok[k] = '\0';
  return 1;
}

static mrgi_status vtk_fail(vtk_reader* r, const char* what)
{
  return mrgi_error_set(r->err, MRGI_ERR_FORMAT, "'%s': %s", r->name, what);
}

static mrgi_status vtk_truncated(vtk_reader* r, const char* section)
{
  return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
    "'%s' is truncated or malformed: %s data missing or not numbers", r->name, section);
}

/* Reads a token that must be there; an error naming `what` otherwise. */
static mrgi_status vtk_need_token(vtk_reader* r, const char* what)
{
  const int t = vtk_token(r);
  if (t < 0)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
      "'%s': a word longer than 255 bytes where %s belongs", r->name, what);
  if (t == 0)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT, "'%s' is truncated: %s missing", r->name, what);
  return MRGI_OK;
}

static mrgi_status vtk_need_int(vtk_reader* r, const char* what, int64_t* v)
{
  mrgi_status s = vtk_need_token(r, what);
  if (s)
    return s;
  char* end = NULL;
  errno = 0;
  const long long x = strtoll(r->tok, &end, 10);
  if (end == r->tok || *end || errno == ERANGE)
    return mrgi_error_set(
      r->err, MRGI_ERR_FORMAT, "'%s': %s is not an integer ('%s')", r->name, what, r->tok);
  *v = x;
  return MRGI_OK;
}

/* In a binary file, data starts after the newline ending the keyword's line. */
static mrgi_status vtk_end_line(vtk_reader* r)
{
  if (!r->binary)
    return MRGI_OK;
  while (r->pos < r->n && r->d[r->pos] != '\n')
  {
    if (!is_space(r->d[r->pos]))
    {
      /* Words after the last expected one (e.g. a type's extra name): keep going to the newline. */
    }
    ++r->pos;
  }
  if (r->pos >= r->n)
    return vtk_fail(r, "binary data missing after a section line");
  ++r->pos;
  return MRGI_OK;
}

/* Bytes of a value of a VTK type name; 0 for unknown, -1 for "bit"/"string" (not checked). */
static int vtk_type_size(const char* t)
{
  static const struct
  {
    const char* name;
    int size;
  } types[] = { { "unsigned_char", 1 }, { "char", 1 }, { "signed_char", 1 }, { "short", 2 },
    { "unsigned_short", 2 }, { "int", 4 }, { "unsigned_int", 4 }, { "long", 8 },
    { "unsigned_long", 8 }, { "vtktypeint64", 8 }, { "vtktypeuint64", 8 }, { "vtktypeint32", 4 },
    { "vtktypeuint32", 4 }, { "vtkidtype", 4 }, { "float", 4 }, { "double", 8 }, { "bit", -1 },
    { "string", -1 }, { "utf8_string", -1 }, { "variant", -1 } };
  for (size_t i = 0; i < sizeof(types) / sizeof(types[0]); ++i)
    if (strcasecmp(types[i].name, t) == 0)
      return types[i].size;
  return 0;
}

/* Reads one integer value (ASCII token or binary of `size` bytes, signed unless `uns`). */
static int vtk_get_int(vtk_reader* r, int size, int uns, int64_t* v)
{
  if (!r->binary)
  {
    if (vtk_token(r) <= 0)
      return 0;
    char* end = NULL;
    errno = 0;
    const long long x = strtoll(r->tok, &end, 10);
    if (end == r->tok || *end || errno == ERANGE)
      return 0;
    *v = x;
    return 1;
  }
  if (r->n - r->pos < (size_t)size)
    return 0;
  uint64_t u = 0;
  for (int i = 0; i < size; ++i)
    u = (u << 8) | r->d[r->pos + (size_t)i];
  r->pos += (size_t)size;
  if (uns || size == 8)
    *v = (int64_t)u;
  else
  {
    const int shift = 64 - 8 * size;
    *v = (int64_t)(u << shift) >> shift;
  }
  return 1;
}

/* Skips `count` values of `size` bytes; ASCII values must be numbers. Returns 1 when all present.
 */
static int vtk_skip_values(vtk_reader* r, int64_t count, int size, double* first_bad_finite)
{
  if (count < 0)
    return 0;
  if (r->binary)
  {
    if ((uint64_t)count > (r->n - r->pos) / (uint64_t)size)
      return 0;
    r->pos += (size_t)count * (size_t)size;
    return 1;
  }
  /* Each ASCII value takes at least 2 bytes (a digit and a separator), but the last one. */
  if ((uint64_t)count > (r->n - r->pos) / 2 + 1)
    return 0;
  for (int64_t i = 0; i < count; ++i)
  {
    if (vtk_token(r) <= 0)
      return 0;
    char* end = NULL;
    const double x = strtod(r->tok, &end);
    if (end == r->tok || *end)
      return 0;
    if (first_bad_finite && !isfinite(x))
      *first_bad_finite = x;
  }
  return 1;
}

typedef struct vtk_state
{
  double version;
  int kind;       /* 0 polydata, 1 ugrid, 2 structured points, 3 structured grid, 4 rectilinear */
  int64_t points; /* -1 until known */
  int64_t cells;
  int64_t dims[3];
  int has_dims;
  int32_t* cell_sizes; /* UNSTRUCTURED_GRID: points of each cell */
  int64_t cell_sizes_count;
} vtk_state;

/* Reads a legacy (version < 5) or new (OFFSETS/CONNECTIVITY) cell section. */


/* The line "NAME TYPE" that opens a version-5 cell array (OFFSETS or
 * CONNECTIVITY); `size` receives the byte size of TYPE. */
static mrgi_status vtk_v5_array_header(vtk_reader* r, const char* name, int* size)
{
  mrgi_status s = vtk_need_token(r, name);
  if (s)
    return s;
  if (strcasecmp(r->tok, name) != 0)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
      "'%s': a cell section without %s (version 5 layout)", r->name, name);
  char what[64];
  snprintf(what, sizeof(what), "the %s type", name);
  if ((s = vtk_need_token(r, what)))
    return s;
  *size = vtk_type_size(r->tok);
  if (*size <= 0)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT, "'%s': bad %s type '%s'", r->name, name, r->tok);
  return vtk_end_line(r);
}

/* The sizes of `n` unstructured-grid cells, for CELL_TYPES to check against
 * (n is bounded by the file's size before this is called). */
static mrgi_status vtk_alloc_cell_sizes(vtk_reader* r, vtk_state* st, int64_t n)
{
  free(st->cell_sizes);
  st->cell_sizes = (int32_t*)malloc(sizeof(int32_t) * (size_t)(n > 0 ? n : 1));
  if (!st->cell_sizes)
    return mrgi_error_set(r->err, MRGI_ERR_OUT_OF_MEMORY, "'%s': out of memory", r->name);
  st->cell_sizes_count = n;
  return MRGI_OK;
}

static mrgi_status vtk_cells(vtk_reader* r, vtk_state* st, const char* kw)
{
  int64_t n = 0, size = 0;
  mrgi_status s = vtk_need_int(r, "a cell count", &n);
  if (!s)
    s = vtk_need_int(r, "a cell list size", &size);
  if (s)
    return s;
  if (n < 0 || size < 0)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT, "'%s': %s has a negative count", r->name, kw);
  if (st->points < 0)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT, "'%s': %s before POINTS", r->name, kw);
  const uint64_t bound = r->binary ? (r->n - r->pos) / 4 : (r->n - r->pos) / 2 + 1;
  const int ugrid = strcasecmp(kw, "CELLS") == 0;
  if (st->version < 5.0)
  {
    if ((uint64_t)size > bound || (uint64_t)n > (uint64_t)size)
      return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
        "'%s': %s declares %lld cells in %lld values, more than the file holds", r->name, kw,
        (long long)n, (long long)size);
    if ((s = vtk_end_line(r)))
      return s;
    if (ugrid && (s = vtk_alloc_cell_sizes(r, st, n)))
      return s;
    int64_t used = 0;
    for (int64_t c = 0; c < n; ++c)
    {
      int64_t k = 0;
      if (!vtk_get_int(r, 4, 0, &k))
        return vtk_truncated(r, kw);
      if (k < 0 || k > size - used - 1)
        return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
          "'%s': %s cell %lld has %lld points, which does not fit the declared size %lld", r->name,
          kw, (long long)c, (long long)k, (long long)size);
      if (ugrid)
        st->cell_sizes[c] = (int32_t)k;
      for (int64_t i = 0; i < k; ++i)
      {
        int64_t id = 0;
        if (!vtk_get_int(r, 4, 0, &id))
          return vtk_truncated(r, kw);
        if (id < 0 || id >= st->points)
          return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
            "'%s': %s cell %lld refers to point %lld, outside [0, %lld)", r->name, kw, (long long)c,
            (long long)id, (long long)st->points);
      }
      used += k + 1;
    }
    if (used != size)
      return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
        "'%s': %s declares a size of %lld values, its %lld cells use %lld", r->name, kw,
        (long long)size, (long long)n, (long long)used);
    st->cells += n;
    return MRGI_OK;
  }
  /* Version 5: "KW nOffsets nConnectivity", OFFSETS type, CONNECTIVITY type. */
  const int64_t noff = n, nconn = size;
  if ((uint64_t)noff > bound || (uint64_t)nconn > bound)
    return mrgi_error_set(
      r->err, MRGI_ERR_FORMAT, "'%s': %s declares more values than the file holds", r->name, kw);
  int osize = 0;
  if ((s = vtk_v5_array_header(r, "OFFSETS", &osize)))
    return s;
  const int64_t ncells = noff > 0 ? noff - 1 : 0;
  if (ugrid && (s = vtk_alloc_cell_sizes(r, st, ncells)))
    return s;
  int64_t prev = 0;
  for (int64_t i = 0; i < noff; ++i)
  {
    int64_t o = 0;
    if (!vtk_get_int(r, osize, 0, &o))
      return vtk_truncated(r, "OFFSETS");
    if ((i == 0 && o != 0) || o < prev || o > nconn || (i == noff - 1 && o != nconn))
      return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
        "'%s': %s offset %lld is %lld: offsets must start at 0, never decrease and end at %lld",
        r->name, kw, (long long)i, (long long)o, (long long)nconn);
    if (i > 0 && ugrid)
      st->cell_sizes[i - 1] = (int32_t)(o - prev > INT32_MAX ? INT32_MAX : o - prev);
    prev = o;
  }
  if (noff == 0 && nconn != 0)
    return vtk_fail(r, "connectivity without offsets");
  int csize = 0;
  if ((s = vtk_v5_array_header(r, "CONNECTIVITY", &csize)))
    return s;
  for (int64_t i = 0; i < nconn; ++i)
  {
    int64_t id = 0;
    if (!vtk_get_int(r, csize, 0, &id))
      return vtk_truncated(r, "CONNECTIVITY");
    if (id < 0 || id >= st->points)
      return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
        "'%s': %s refers to point %lld, outside [0, %lld)", r->name, kw, (long long)id,
        (long long)st->points);
  }
  st->cells += ncells;
  return MRGI_OK;
}

/* Points of a VTK cell type: >0 fixed, -k variable with at least k, 0 unknown/unsupported. */
static int vtk_cell_points(int64_t type)
{
  switch (type)
  {
    case 0:
      return -0; /* empty cell: handled by the caller */
    case 1:
      return 1;
    case 2:
      return -1;
    case 3:
      return 2;
    case 4:
      return -2;
    case 5:
      return 3;
    case 6:
      return -3;
    case 7:
      return -3;
    case 8:
    case 9:
    case 10:
      return 4;
    case 11:
    case 12:
      return 8;
    case 13:
      return 6;
    case 14:
      return 5;
    case 15:
      return 10;
    case 16:
      return 12;
    case 21:
      return 3;
    case 22:
      return 6;
    case 23:
      return 8;
    case 24:
      return 10;
    case 25:
      return 20;
    case 26:
      return 15;
    case 27:
      return 13;
    case 28:
      return 9;
    case 29:
      return 27;
    case 30:
      return 6;
    case 31:
      return 12;
    case 32:
      return 18;
    case 33:
      return 24;
    case 34:
      return 7;
    case 35:
      return 4;
    default:
      return 0;
  }
}

static mrgi_status vtk_cell_types(vtk_reader* r, vtk_state* st)
{
  int64_t n = 0;
  mrgi_status s = vtk_need_int(r, "the CELL_TYPES count", &n);
  if (s)
    return s;
  if (!st->cell_sizes || n != st->cell_sizes_count)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
      "'%s': CELL_TYPES declares %lld types for %lld cells", r->name, (long long)n,
      (long long)(st->cell_sizes ? st->cell_sizes_count : 0));
  if ((s = vtk_end_line(r)))
    return s;
  for (int64_t c = 0; c < n; ++c)
  {
    int64_t t = 0;
    if (!vtk_get_int(r, 4, 0, &t))
      return vtk_truncated(r, "CELL_TYPES");
    const int need = vtk_cell_points(t);
    const int32_t have = st->cell_sizes[c];
    if (t == 0 && have == 0)
      continue;
    if (need == 0)
      return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
        "'%s': cell %lld has type %lld, which MRGI does not read%s", r->name, (long long)c,
        (long long)t, t == 42 ? " (polyhedron)" : "");
    if ((need > 0 && have != need) || (need < 0 && have < -need))
      return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
        "'%s': cell %lld of type %lld has %d points, it needs %s%d", r->name, (long long)c,
        (long long)t, (int)have, need < 0 ? "at least " : "", need < 0 ? -need : need);
  }
  return MRGI_OK;
}

/* Reads the values of one attribute array: `count` tuples of `ncomp` values of type `t`. */
static mrgi_status vtk_array(
  vtk_reader* r, const char* kw, int64_t count, int64_t ncomp, const char* t)
{
  const int size = vtk_type_size(t);
  if (size == 0)
    return mrgi_error_set(
      r->err, MRGI_ERR_FORMAT, "'%s': %s has an unknown type '%s'", r->name, kw, t);
  if (size < 0)
    return VTK_STOP;
  if (ncomp < 1 || count < 0 || ncomp > INT32_MAX || count > INT64_MAX / ncomp)
    return mrgi_error_set(r->err, MRGI_ERR_FORMAT, "'%s': %s has a bad size", r->name, kw);
  mrgi_status s = vtk_end_line(r);
  if (s)
    return s;
  if (!vtk_skip_values(r, count * ncomp, size, NULL))
    return vtk_truncated(r, kw);
  return MRGI_OK;
}

static mrgi_status vtk_attributes(vtk_reader* r, vtk_state* st, int64_t count)
{
  mrgi_status s = MRGI_OK;
  for (;;)
  {
    const size_t mark = r->pos;
    const int t = vtk_token(r);
    if (t == 0)
      return MRGI_OK;
    if (t < 0)
      return vtk_fail(r, "a word longer than 255 bytes where a section keyword belongs");
    char kw[256];
    snprintf(kw, sizeof(kw), "%s", r->tok);
    if (strcasecmp(kw, "POINT_DATA") == 0 || strcasecmp(kw, "CELL_DATA") == 0)
    {
      r->pos = mark;
      return MRGI_OK;
    }
    char type[256];
    int64_t ncomp = 1;
    if (strcasecmp(kw, "SCALARS") == 0)
    {
      if ((s = vtk_need_token(r, "a SCALARS name")) || (s = vtk_need_token(r, "a SCALARS type")))
        return s;
      snprintf(type, sizeof(type), "%s", r->tok);
      /* An optional component count on the same line. */
      size_t p = r->pos;
      while (p < r->n && (r->d[p] == ' ' || r->d[p] == '\t'))
        ++p;
      if (p < r->n && r->d[p] >= '0' && r->d[p] <= '9')
      {
        if ((s = vtk_need_int(r, "a SCALARS component count", &ncomp)))
          return s;
        if (ncomp < 1 || ncomp > 4)
          return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
            "'%s': SCALARS with %lld components (1 to 4 allowed)", r->name, (long long)ncomp);
      }
      if ((s = vtk_end_line(r)))
        return s;
      /* "LOOKUP_TABLE name" line (optional for MRGI). */
      p = r->pos;
      while (p < r->n && is_space(r->d[p]))
        ++p;
      if (r->n - p >= 12 && strncasecmp((const char*)r->d + p, "LOOKUP_TABLE", 12) == 0)
      {
        r->pos = p + 12;
        if ((s = vtk_need_token(r, "a LOOKUP_TABLE name")))
          return s;
      }

      s = vtk_array(r, kw, count, ncomp, type);
    }
    else if (strcasecmp(kw, "LOOKUP_TABLE") == 0)
    {
      int64_t n = 0;
      if ((s = vtk_need_token(r, "a LOOKUP_TABLE name")) ||
        (s = vtk_need_int(r, "a LOOKUP_TABLE size", &n)))
        return s;
      s = vtk_array(r, kw, n, 4, r->binary ? "unsigned_char" : "float");
    }
    else if (strcasecmp(kw, "COLOR_SCALARS") == 0)
    {
      if ((s = vtk_need_token(r, "a COLOR_SCALARS name")) ||
        (s = vtk_need_int(r, "a component count", &ncomp)))
        return s;
      s = vtk_array(r, kw, count, ncomp, r->binary ? "unsigned_char" : "float");
    }
    else if (strcasecmp(kw, "VECTORS") == 0 || strcasecmp(kw, "NORMALS") == 0 ||
      strcasecmp(kw, "TENSORS") == 0 || strcasecmp(kw, "TENSORS6") == 0 ||
      strcasecmp(kw, "GLOBAL_IDS") == 0 || strcasecmp(kw, "PEDIGREE_IDS") == 0)
    {
      if ((s = vtk_need_token(r, "an array name")) || (s = vtk_need_token(r, "an array type")))
        return s;
      ncomp = strcasecmp(kw, "TENSORS") == 0                                 ? 9
        : strcasecmp(kw, "TENSORS6") == 0                                    ? 6
        : (strcasecmp(kw, "VECTORS") == 0 || strcasecmp(kw, "NORMALS") == 0) ? 3
                                                                             : 1;
      snprintf(type, sizeof(type), "%s", r->tok);
      s = vtk_array(r, kw, count, ncomp, type);
    }
    else if (strcasecmp(kw, "TEXTURE_COORDINATES") == 0)
    {
      if ((s = vtk_need_token(r, "a name")) || (s = vtk_need_int(r, "a dimension", &ncomp)) ||
        (s = vtk_need_token(r, "a type")))
        return s;
      if (ncomp < 1 || ncomp > 3)
        return vtk_fail(r, "TEXTURE_COORDINATES of a dimension outside 1..3");
      snprintf(type, sizeof(type), "%s", r->tok);
      s = vtk_array(r, kw, count, ncomp, type);
    }
    else if (strcasecmp(kw, "FIELD") == 0)
    {
      int64_t arrays = 0;
      if ((s = vtk_need_token(r, "a FIELD name")) ||
        (s = vtk_need_int(r, "a FIELD array count", &arrays)))
        return s;
      if (arrays < 0 || (uint64_t)arrays > r->n - r->pos)
        return vtk_fail(r, "a FIELD with a bad array count");
      for (int64_t a = 0; a < arrays && !s; ++a)
      {
        int64_t tuples = 0;
        if ((s = vtk_need_token(r, "a FIELD array name")))
          return s;
        if (strcasecmp(r->tok, "NULL_ARRAY") == 0)
          continue;
        if ((s = vtk_need_int(r, "a component count", &ncomp)) ||
          (s = vtk_need_int(r, "a tuple count", &tuples)) ||
          (s = vtk_need_token(r, "an array type")))
          return s;
        snprintf(type, sizeof(type), "%s", r->tok);
        s = vtk_array(r, "FIELD", tuples, ncomp, type);
      }
    }
    else
    {
      return VTK_STOP; /* METADATA, INFORMATION or a keyword this check does not know */
    }
    if (s)
      return s;
    (void)st;
  }
}

static mrgi_status vtk_check(vtk_reader* r, vtk_state* st)
{
  mrgi_line_cursor c;
  mrgi_line_cursor_init(&c, r->d, r->n);
  char line[512];
  if (mrgi_line_next(&c, line, sizeof(line)) != 1 ||
    strncmp(line, "# vtk DataFile Version", 22) != 0)
    return vtk_fail(r, "not a legacy VTK file (no '# vtk DataFile Version' line)");
  st->version = atof(line + 22);
  if (!(st->version > 0) || st->version > 100)
    return vtk_fail(r, "bad legacy VTK version");
  if (mrgi_line_next(&c, line, sizeof(line)) != 1)
    return vtk_fail(r, "the title line is missing or longer than 511 bytes");
  r->pos = c.pos;
  mrgi_status s = vtk_need_token(r, "ASCII or BINARY");
  if (s)
    return s;
  if (strcasecmp(r->tok, "ASCII") == 0)
    r->binary = 0;
  else if (strcasecmp(r->tok, "BINARY") == 0)
    r->binary = 1;
  else
    return vtk_fail(r, "the third line is neither ASCII nor BINARY");
  if ((s = vtk_need_token(r, "DATASET")))
    return s;
  if (strcasecmp(r->tok, "DATASET") != 0)
    return VTK_STOP; /* a FIELD file or other: nothing to draw, the reader says so */
  if ((s = vtk_need_token(r, "the data set type")))
    return s;
  static const char* const kinds[] = { "POLYDATA", "UNSTRUCTURED_GRID", "STRUCTURED_POINTS",
    "STRUCTURED_GRID", "RECTILINEAR_GRID" };
  st->kind = -1;
  for (int k = 0; k < 5; ++k)
    if (strcasecmp(r->tok, kinds[k]) == 0)
      st->kind = k;
  if (st->kind < 0)
    return mrgi_error_set(
      r->err, MRGI_ERR_FORMAT, "'%s': unsupported data set type '%s'", r->name, r->tok);
  st->points = st->kind == 2 ? 0 : -1;
  for (;;)
  {
    const int t = vtk_token(r);
    if (t == 0)
      return MRGI_OK;
    if (t < 0)
      return vtk_fail(r, "a word longer than 255 bytes where a section keyword belongs");
    char kw[256];
    snprintf(kw, sizeof(kw), "%s", r->tok);
    if (strcasecmp(kw, "POINTS") == 0)
    {
      int64_t n = 0;
      if ((s = vtk_need_int(r, "the POINTS count", &n)) ||
        (s = vtk_need_token(r, "the POINTS type")))
        return s;
      if (n < 0)
        return vtk_fail(r, "a negative POINTS count");
      if (st->has_dims && st->kind == 3 && n != st->dims[0] * st->dims[1] * st->dims[2])
        return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
          "'%s': POINTS %lld does not match DIMENSIONS (%lld points)", r->name, (long long)n,
          (long long)(st->dims[0] * st->dims[1] * st->dims[2]));
      const int size = vtk_type_size(r->tok);
      if (size <= 0)
        return mrgi_error_set(
          r->err, MRGI_ERR_FORMAT, "'%s': bad POINTS type '%s'", r->name, r->tok);
      if (n > INT64_MAX / 3 || (s = vtk_end_line(r)))
        return s ? s : vtk_fail(r, "a POINTS count too large");
      if (!vtk_skip_values(r, 3 * n, size, NULL))
        return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
          "'%s' is truncated or malformed: POINTS declares %lld points, the file does not hold "
          "them as numbers",
          r->name, (long long)n);
      st->points = n;
    }
    else if (strcasecmp(kw, "VERTICES") == 0 || strcasecmp(kw, "LINES") == 0 ||
      strcasecmp(kw, "POLYGONS") == 0 || strcasecmp(kw, "TRIANGLE_STRIPS") == 0 ||
      strcasecmp(kw, "CELLS") == 0)
    {
      if ((s = vtk_cells(r, st, kw)))
        return s;
    }
    else if (strcasecmp(kw, "CELL_TYPES") == 0)
    {
      if ((s = vtk_cell_types(r, st)))
        return s;
    }
    else if (strcasecmp(kw, "DIMENSIONS") == 0)
    {
      int64_t prod = 1;
      for (int k = 0; k < 3; ++k)
      {
        if ((s = vtk_need_int(r, "a dimension", &st->dims[k])))
          return s;
        if (st->dims[k] < 1 || st->dims[k] > INT32_MAX)
          return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
            "'%s': DIMENSIONS must be at least 1 (got %lld)", r->name, (long long)st->dims[k]);
        prod = prod > INT32_MAX ? prod : prod * st->dims[k];
      }
      const int64_t* d = st->dims;
      if (prod > INT32_MAX ||
        2 * (d[0] * d[1] + d[1] * d[2] + d[0] * d[2]) > MRGI_VTK_MAX_SURFACE_POINTS)
        return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
          "'%s': DIMENSIONS %lld x %lld x %lld is too large to draw (more than %lld surface "
          "points)",
          r->name, (long long)d[0], (long long)d[1], (long long)d[2],
          (long long)MRGI_VTK_MAX_SURFACE_POINTS);
      st->has_dims = 1;
      if (st->kind == 2)
        st->points = prod;
      st->cells = (d[0] > 1 ? d[0] - 1 : 1) * (d[1] > 1 ? d[1] - 1 : 1) * (d[2] > 1 ? d[2] - 1 : 1);
    }
    else if (strcasecmp(kw, "ORIGIN") == 0 || strcasecmp(kw, "SPACING") == 0 ||
      strcasecmp(kw, "ASPECT_RATIO") == 0)
    {
      for (int k = 0; k < 3; ++k)
      {
        if ((s = vtk_need_token(r, kw)))
          return s;
        char* end = NULL;
        const double v = strtod(r->tok, &end);
        if (end == r->tok || *end || !isfinite(v))
          return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
            "'%s': %s value '%s' is not a finite number", r->name, kw, r->tok);
      }
    }
    else if (strcasecmp(kw, "X_COORDINATES") == 0 || strcasecmp(kw, "Y_COORDINATES") == 0 ||
      strcasecmp(kw, "Z_COORDINATES") == 0)
    {
      int64_t n = 0;
      if ((s = vtk_need_int(r, "a coordinate count", &n)) ||
        (s = vtk_need_token(r, "a coordinate type")))
        return s;
      const int axis = kw[0] == 'X' || kw[0] == 'x' ? 0 : kw[0] == 'Y' || kw[0] == 'y' ? 1 : 2;
      if (!st->has_dims || n != st->dims[axis])
        return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
          "'%s': %s count %lld does not match DIMENSIONS", r->name, kw, (long long)n);
      char type[256];
      snprintf(type, sizeof(type), "%s", r->tok);
      if ((s = vtk_array(r, kw, n, 1, type)))
        return s;
      if (axis == 2)
        st->points = st->dims[0] * st->dims[1] * st->dims[2];
    }
    else if (strcasecmp(kw, "POINT_DATA") == 0 || strcasecmp(kw, "CELL_DATA") == 0)
    {
      int64_t n = 0;
      if ((s = vtk_need_int(r, kw, &n)))
        return s;
      const int pointData = kw[0] == 'P' || kw[0] == 'p';
      const int64_t expect = pointData ? st->points : st->cells;
      if (n != expect)
        return mrgi_error_set(r->err, MRGI_ERR_FORMAT,
          "'%s': %s %lld, but the data set has %lld %s", r->name, kw, (long long)n,
          (long long)expect, pointData ? "points" : "cells");
      if ((s = vtk_attributes(r, st, n)))
        return s;
    }
    else if (strcasecmp(kw, "FIELD") == 0)
    {
      r->pos -= 5;
      if ((s = vtk_attributes(r, st, 0)))
        return s;
    }
    else
    {
      return VTK_STOP;
    }
  }
}

mrgi_status mrgi_vtk_check_buffer(
  const void* data, size_t size, const char* name, mrgi_vtk_info* info, mrgi_error* err)
{
  vtk_reader r;
  memset(&r, 0, sizeof(r));
  r.d = (const unsigned char*)data;
  r.n = data ? size : 0;
  r.name = name ? name : "VTK data";
  r.err = err;
  vtk_state st;
  memset(&st, 0, sizeof(st));
  if (r.n == 0)
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is empty", r.name);
  mrgi_status s = vtk_check(&r, &st);
  free(st.cell_sizes);
  if ((int)s == VTK_STOP)
    s = MRGI_OK;
  if (s == MRGI_OK && info)
  {
    /* A file that stops (an unknown keyword) before POINTS declared none. */
    info->point_count = st.points < 0 ? 0 : st.points;
    info->cell_count = st.cells;
    info->binary = r.binary;
  }
  return s;
}

mrgi_status mrgi_vtk_check(const char* path, mrgi_vtk_info* info, mrgi_error* err)
{
  mrgi_input in;
  mrgi_status status = mrgi_input_map(path, &in, err);
  if (status == MRGI_OK)
  {
    status = mrgi_vtk_check_buffer(in.data, in.size, path, info, err);
    mrgi_input_unmap(&in);
  }
  return status;
}
