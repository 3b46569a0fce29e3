/* PCD structure check: see mrgi_pcd_check.h. The format is PCL's (PCD
 * v0.7, pointclouds.org/documentation/tutorials/pcd_file_format.html). */
#include "mrgi_pcd_check.h"

#include "mrgi_input.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct pcd_fields
{
  int32_t n;
  int32_t x, y, z; /* field indices, -1 when absent */
  char type[MRGI_PCD_MAX_FIELDS];
  int32_t size[MRGI_PCD_MAX_FIELDS];
  int32_t count[MRGI_PCD_MAX_FIELDS];
  int have_size, have_type, have_count;
} pcd_fields;

static int is_space(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* The next white-space separated token of *s (NUL-terminated), or NULL. */
static char* next_token(char** s)
{
  char* p = *s;
  while (*p && is_space(*p))
  {
    ++p;
  }
  if (!*p)
  {
    *s = p;
    return NULL;
  }
  char* t = p;
  while (*p && !is_space(*p))
  {
    ++p;
  }
  if (*p)
  {
    *p++ = '\0';
  }
  *s = p;
  return t;
}

/* A decimal integer in [lo, hi]; 0 when it is not one. */
static int parse_int(const char* t, int64_t lo, int64_t hi, int64_t* out)
{
  if (!t || !*t)
  {
    return 0;
  }
  int64_t v = 0;
  for (const char* p = t; *p; ++p)
  {
    if (*p < '0' || *p > '9' || v > hi)
    {
      return 0;
    }
    v = v * 10 + (*p - '0');
  }
  if (v < lo || v > hi)
  {
    return 0;
  }
  *out = v;
  return 1;
}

/* A whole token that strtod reads as a number (nan and inf included). */
static int parse_number(const char* t, size_t len, double* out)
{
  char buf[96];
  if (len == 0 || len >= sizeof(buf))
  {
    return 0;
  }
  memcpy(buf, t, len);
  buf[len] = '\0';
  char* end = NULL;
  const double v = strtod(buf, &end);
  if (end != buf + len)
  {
    return 0;
  }
  *out = v;
  return 1;
}

/* One value per field on a SIZE, TYPE or COUNT line. */
static mrgi_status parse_per_field(
  char* rest, const char* key, const char* name, pcd_fields* f, int64_t line, mrgi_error* err)
{
  if (f->n == 0)
  {
    return mrgi_error_set(
      err, MRGI_ERR_FORMAT, "'%s' line %lld: %s before FIELDS", name, (long long)line, key);
  }
  int32_t i = 0;
  for (char* t = next_token(&rest); t; t = next_token(&rest), ++i)
  {
    if (i >= f->n)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s' line %lld: %s has more values than the %d FIELDS", name, (long long)line, key,
        (int)f->n);
    }
    int64_t v = 0;
    if (key[0] == 'T')
    {
      if ((t[0] != 'F' && t[0] != 'I' && t[0] != 'U') || t[1] != '\0')
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: TYPE '%.16s' of field %d is not F, I or U", name, (long long)line, t,
          (int)i + 1);
      }
      f->type[i] = t[0];
    }
    else if (key[0] == 'S')
    {
      if (!parse_int(t, 1, 8, &v) || (v != 1 && v != 2 && v != 4 && v != 8))
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: SIZE '%.16s' of field %d is not 1, 2, 4 or 8", name, (long long)line, t,
          (int)i + 1);
      }
      f->size[i] = (int32_t)v;
    }
    else
    {
      if (!parse_int(t, 1, MRGI_PCD_MAX_COUNT, &v))
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: COUNT '%.16s' of field %d is not in [1, %d]", name, (long long)line, t,
          (int)i + 1, MRGI_PCD_MAX_COUNT);
      }
      f->count[i] = (int32_t)v;
    }
  }
  if (i != f->n)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' line %lld: %s has %d values for %d FIELDS",
      name, (long long)line, key, (int)i, (int)f->n);
  }
  return MRGI_OK;
}

static uint32_t read_u32(const unsigned char* p)
{
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* The ASCII body: exactly `points` non-empty lines of `values` numbers. */
static mrgi_status check_ascii_body(const unsigned char* b, size_t size, int64_t points,
  int64_t values, int64_t first_line, const char* name, mrgi_error* err)
{
  int64_t line = first_line, rows = 0;
  size_t pos = 0;
  while (pos < size)
  {
    ++line;
    size_t end = pos;
    while (end < size && b[end] != '\n')
    {
      ++end;
    }
    int64_t tokens = 0;
    size_t p = pos;
    while (p < end)
    {
      while (p < end && (is_space((char)b[p]) || b[p] == '\0'))
      {
        ++p;
      }
      if (p >= end)
      {
        break;
      }
      const size_t t = p;
      while (p < end && !is_space((char)b[p]) && b[p] != '\0')
      {
        ++p;
      }
      double v;
      if (!parse_number((const char*)b + t, p - t, &v))
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' line %lld: '%.*s' is not a number", name,
          (long long)line, (int)(p - t < 24 ? p - t : 24), (const char*)b + t);
      }
      ++tokens;
    }
    if (tokens > 0)
    {
      if (rows == points)
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: more data lines than the %lld POINTS", name, (long long)line,
          (long long)points);
      }
      if (tokens != values)
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: point %lld has %lld values, the header declares %lld", name,
          (long long)line, (long long)rows + 1, (long long)tokens, (long long)values);
      }
      ++rows;
    }
    pos = end + 1;
  }
  if (rows != points)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': truncated: %lld data lines for %lld POINTS",
      name, (long long)rows, (long long)points);
  }
  return MRGI_OK;
}

mrgi_status mrgi_pcd_check_buffer(const void* data, size_t size, const char* name,
  int64_t max_points, mrgi_pcd_info* info, mrgi_error* err)
{
  name = name ? name : "PCD data";
  if (max_points < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PCD check: max_points < 1");
  }
  if (!data || size == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': empty file", name);
  }
  mrgi_pcd_info out;
  memset(&out, 0, sizeof(out));
  out.viewpoint[3] = 1.0;
  out.height = -1;
  out.width = -1;
  out.points = -1;
  pcd_fields* f = (pcd_fields*)calloc(1, sizeof(pcd_fields));
  char* line = (char*)malloc(MRGI_PCD_MAX_LINE + 1);
  if (!f || !line)
  {
    free(f);
    free(line);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "'%s': PCD check: out of memory", name);
  }
  f->x = f->y = f->z = -1;
  mrgi_status status = MRGI_OK;
  mrgi_line_cursor c;
  mrgi_line_cursor_init(&c, data, size);
  int have_data = 0;
  while (!have_data)
  {
    if (c.pos > MRGI_PCD_MAX_HEADER_BYTES)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': no DATA line in the first %d bytes (not a PCD file?)", name,
        MRGI_PCD_MAX_HEADER_BYTES);
      goto done;
    }
    const int got = mrgi_line_next(&c, line, MRGI_PCD_MAX_LINE + 1);
    if (got < 0)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s' line %lld: header line longer than %d bytes (not a PCD file?)", name,
        (long long)c.line_number + 1, MRGI_PCD_MAX_LINE);
      goto done;
    }
    if (got == 0)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': the header ends without a DATA line (not a PCD file, or truncated)", name);
      goto done;
    }
    char* rest = line;
    char* key = next_token(&rest);
    if (!key || key[0] == '#')
    {
      continue;
    }
    const int64_t ln = c.line_number;
    if (strcmp(key, "VERSION") == 0)
    {
      continue;
    }
    if (strcmp(key, "FIELDS") == 0)
    {
      if (f->n > 0)
      {
        status = mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s' line %lld: a second FIELDS", name, (long long)ln);
        goto done;
      }
      for (char* t = next_token(&rest); t; t = next_token(&rest))
      {
        if (f->n == MRGI_PCD_MAX_FIELDS)
        {
          status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' line %lld: more than %d FIELDS", name,
            (long long)ln, MRGI_PCD_MAX_FIELDS);
          goto done;
        }
        if (t[1] == '\0' && (t[0] == 'x' || t[0] == 'y' || t[0] == 'z'))
        {
          int32_t* slot = t[0] == 'x' ? &f->x : t[0] == 'y' ? &f->y : &f->z;
          if (*slot >= 0)
          {
            status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' line %lld: field '%s' named twice",
              name, (long long)ln, t);
            goto done;
          }
          *slot = f->n;
        }
        f->count[f->n] = 1;
        ++f->n;
      }
      if (f->n == 0)
      {
        status = mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s' line %lld: FIELDS names no field", name, (long long)ln);
        goto done;
      }
    }
    else if (strcmp(key, "SIZE") == 0 || strcmp(key, "TYPE") == 0 || strcmp(key, "COUNT") == 0)
    {
      int* have = key[0] == 'S' ? &f->have_size : key[0] == 'T' ? &f->have_type : &f->have_count;
      if (*have)
      {
        status = mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s' line %lld: a second %s", name, (long long)ln, key);
        goto done;
      }
      status = parse_per_field(rest, key, name, f, ln, err);
      if (status != MRGI_OK)
      {
        goto done;
      }
      *have = 1;
    }
    else if (strcmp(key, "WIDTH") == 0 || strcmp(key, "HEIGHT") == 0 || strcmp(key, "POINTS") == 0)
    {
      int64_t* slot = key[0] == 'W' ? &out.width : key[0] == 'H' ? &out.height : &out.points;
      const char* t = next_token(&rest);
      int64_t v = 0;
      if (!parse_int(t, 0, INT64_C(1) << 40, &v) || next_token(&rest) != NULL)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: %s is not a non-negative integer", name, (long long)ln, key);
        goto done;
      }
      if (v < 1)
      {
        status =
          mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' line %lld: %s %lld: the file holds no points",
            name, (long long)ln, key, (long long)v);
        goto done;
      }
      if (v > max_points)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: %s %lld is more than the %lld points this reader accepts", name,
          (long long)ln, key, (long long)v, (long long)max_points);
        goto done;
      }
      *slot = v;
    }
    else if (strcmp(key, "VIEWPOINT") == 0)
    {
      int i = 0;
      for (char* t = next_token(&rest); t; t = next_token(&rest), ++i)
      {
        double v;
        if (i >= 7 || !parse_number(t, strlen(t), &v) || !isfinite(v))
        {
          status = mrgi_error_set(err, MRGI_ERR_FORMAT,
            "'%s' line %lld: VIEWPOINT needs 7 finite numbers", name, (long long)ln);
          goto done;
        }
        out.viewpoint[i] = v;
      }
      if (i != 7)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: VIEWPOINT needs 7 finite numbers, it has %d", name, (long long)ln, i);
        goto done;
      }
      out.has_viewpoint = 1;
    }
    else if (strcmp(key, "DATA") == 0)
    {
      const char* t = next_token(&rest);
      if (t && strcmp(t, "ascii") == 0)
      {
        out.data = MRGI_PCD_ASCII;
      }
      else if (t && strcmp(t, "binary") == 0)
      {
        out.data = MRGI_PCD_BINARY;
      }
      else if (t && strcmp(t, "binary_compressed") == 0)
      {
        out.data = MRGI_PCD_BINARY_COMPRESSED;
      }
      else
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: DATA '%.24s' is not ascii, binary or binary_compressed", name,
          (long long)ln, t ? t : "");
        goto done;
      }
      have_data = 1;
    }
    else
    {
      int printable = 1;
      for (const char* p = key; *p; ++p)
      {
        printable = printable && (unsigned char)*p >= 0x20 && (unsigned char)*p < 0x7F;
      }
      status = printable
        ? mrgi_error_set(err, MRGI_ERR_FORMAT,
            "'%s' line %lld: unknown header key '%.32s' (not a PCD file?)", name, (long long)ln,
            key)
        : mrgi_error_set(err, MRGI_ERR_FORMAT,
            "'%s' line %lld: binary data in the header (not a PCD file)", name, (long long)ln);
      goto done;
    }
  }
  out.header_size = (int64_t)c.pos;

  /* The header as a whole. */
  if (f->n == 0 || !f->have_size || !f->have_type)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the header lacks %s", name,
      f->n == 0         ? "FIELDS"
        : !f->have_size ? "SIZE"
                        : "TYPE");
    goto done;
  }
  if (out.width < 0 || out.points < 0)
  {
    status = mrgi_error_set(
      err, MRGI_ERR_FORMAT, "'%s': the header lacks %s", name, out.width < 0 ? "WIDTH" : "POINTS");
    goto done;
  }
  if (out.height < 0)
  {
    out.height = 1;
  }
  /* Each is at most 2^40 (parse_int): compare without overflowing. */
  if (out.width > out.points / out.height || out.width * out.height != out.points)
  {
    status =
      mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': WIDTH %lld x HEIGHT %lld is not POINTS %lld",
        name, (long long)out.width, (long long)out.height, (long long)out.points);
    goto done;
  }
  int64_t record = 0, values = 0;
  for (int32_t i = 0; i < f->n; ++i)
  {
    if (f->type[i] == 'F' && f->size[i] != 4 && f->size[i] != 8)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': field %d is TYPE F with SIZE %d (floats are 4 or 8 bytes)", name, (int)i + 1,
        (int)f->size[i]);
      goto done;
    }
    record += (int64_t)f->size[i] * f->count[i];
    values += f->count[i];
  }
  if (record > MRGI_PCD_MAX_RECORD)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': a point takes %lld bytes, more than %d",
      name, (long long)record, MRGI_PCD_MAX_RECORD);
    goto done;
  }
  const int32_t xyz[3] = { f->x, f->y, f->z };
  for (int a = 0; a < 3; ++a)
  {
    if (xyz[a] < 0)
    {
      status = mrgi_error_set(
        err, MRGI_ERR_FORMAT, "'%s': no field '%c' (FIELDS needs x y z)", name, "xyz"[a]);
      goto done;
    }
    if (f->type[xyz[a]] != 'F' || f->count[xyz[a]] != 1)
    {
      status = mrgi_error_set(
        err, MRGI_ERR_FORMAT, "'%s': field '%c' must be TYPE F with COUNT 1", name, "xyz"[a]);
      goto done;
    }
  }
  out.field_count = f->n;
  out.record_size = (int32_t)record;

  /* The body. */
  const unsigned char* b = (const unsigned char*)data + c.pos;
  const size_t body = size - c.pos;
  const uint64_t bytes = (uint64_t)out.points * (uint64_t)record;
  if (out.data == MRGI_PCD_ASCII)
  {
    status = check_ascii_body(b, body, out.points, values, c.line_number, name, err);
  }
  else if (out.data == MRGI_PCD_BINARY)
  {
    if ((uint64_t)body < bytes)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': truncated: the binary body has %llu bytes, %lld points of %lld bytes need %llu",
        name, (unsigned long long)body, (long long)out.points, (long long)record,
        (unsigned long long)bytes);
    }
  }
  else
  {
    if (body < 8)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': truncated: the binary_compressed body lacks its two sizes", name);
      goto done;
    }
    const uint64_t compressed = read_u32(b), uncompressed = read_u32(b + 4);
    if (compressed == 0 || compressed > (uint64_t)body - 8)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': truncated: the compressed body declares %llu bytes, the file has %llu after its "
        "sizes",
        name, (unsigned long long)compressed, (unsigned long long)(body - 8));
    }
    else if (uncompressed != bytes)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': the compressed body declares %llu bytes uncompressed, %lld points of %lld bytes "
        "are %llu",
        name, (unsigned long long)uncompressed, (long long)out.points, (long long)record,
        (unsigned long long)bytes);
    }
    else if (uncompressed > (uint64_t)MRGI_PCD_MAX_LZF_RATIO * compressed)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': %llu compressed bytes cannot expand to %llu (LZF expands at most %dx)", name,
        (unsigned long long)compressed, (unsigned long long)uncompressed, MRGI_PCD_MAX_LZF_RATIO);
    }
  }

done:
  free(line);
  free(f);
  if (status == MRGI_OK && info)
  {
    *info = out;
  }
  return status;
}

mrgi_status mrgi_pcd_check(
  const char* path, int64_t max_points, mrgi_pcd_info* info, mrgi_error* err)
{
  if (!path)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PCD check: no file name given");
  }
  if (max_points < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PCD check: max_points < 1");
  }
  mrgi_input in;
  mrgi_status status = mrgi_input_map(path, &in, err);
  if (status == MRGI_OK)
  {
    status = mrgi_pcd_check_buffer(in.data, in.size, path, max_points, info, err);
    mrgi_input_unmap(&in);
  }
  return status;
}
