#include "mrgi_ply_check.h"

#include "mrgi_input.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Size in bytes of a PLY scalar type name; 0 when the name is unknown. */
static int32_t ply_type_size(const char* name)
{
  static const struct
  {
    const char* name;
    int32_t size;
  } types[] = { { "char", 1 }, { "uchar", 1 }, { "int8", 1 }, { "uint8", 1 }, { "short", 2 },
    { "ushort", 2 }, { "int16", 2 }, { "uint16", 2 }, { "int", 4 }, { "uint", 4 }, { "int32", 4 },
    { "uint32", 4 }, { "float", 4 }, { "float32", 4 }, { "double", 8 }, { "float64", 8 } };
  for (size_t i = 0; i < sizeof(types) / sizeof(types[0]); ++i)
  {
    if (strcmp(types[i].name, name) == 0)
    {
      return types[i].size;
    }
  }
  return 0;
}

static int ply_is_float_type(const char* name)
{
  return strncmp(name, "float", 5) == 0 || strcmp(name, "double") == 0;
}

static int ply_is_unsigned_type(const char* name)
{
  return name[0] == 'u';
}

static int ply_is_integer_type(const char* name)
{
  return ply_type_size(name) > 0 && !ply_is_float_type(name);
}

/* One property of an element. */
typedef struct ply_property
{
  int32_t size;     /* bytes of the scalar, or of a list's items */
  int32_t is_float; /* scalar or list items are floating point */
  int32_t is_unsigned;
  int32_t is_list;
  int32_t count_size; /* bytes of a list's count */
  int32_t count_unsigned;
  int32_t is_index; /* the face element's vertex_indices / vertex_index */
} ply_property;

#define PLY_MAX_ELEMENTS 32
#define PLY_MAX_PROPERTIES 64
#define PLY_MAX_HEADER_LINE 4096

typedef struct ply_element
{
  char name[64];
  int64_t count;
  int32_t property_count;
  ply_property properties[PLY_MAX_PROPERTIES];
  int32_t has_x, has_y, has_z;
} ply_element;

typedef struct ply_header
{
  ply_element elements[PLY_MAX_ELEMENTS];
  int32_t element_count;
  int32_t binary; /* -1 none, 0 ascii, 1 little endian, 2 big endian */
  size_t body;    /* offset of the first byte after end_header */
} ply_header;

static mrgi_status ply_parse_header(
  const void* data, size_t size, const char* name, ply_header* h, mrgi_error* err)
{
  mrgi_line_cursor c;
  mrgi_line_cursor_init(&c, data, size);
  char line[PLY_MAX_HEADER_LINE];
  int ended = 0;
  h->element_count = 0;
  h->binary = -1;
  if (size == 0)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is empty", name);
  }
  while (!ended && c.pos < MRGI_PLY_MAX_HEADER_BYTES)
  {
    const int r = mrgi_line_next(&c, line, sizeof(line));
    if (r == 0)
      break;
    if (r < 0)
    {
      if (c.line_number == 0)
        return mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s' is not a PLY file (no 'ply' magic line)", name);
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s': PLY header line %lld is longer than %d bytes", name, (long long)c.line_number + 1,
        PLY_MAX_HEADER_LINE - 1);
    }
    size_t n = strlen(line);
    while (n > 0 && (line[n - 1] == ' ' || line[n - 1] == '\t'))
      line[--n] = '\0';
    char word[64] = "", a[64] = "", b[64] = "", cc[64] = "", d[64] = "";
    const int fields = sscanf(line, "%63s %63s %63s %63s %63s", word, a, b, cc, d);
    if (c.line_number == 1)
    {
      if (strcmp(line, "ply") != 0)
        return mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s' is not a PLY file (no 'ply' magic line)", name);
      continue;
    }
    if (fields <= 0 || strcmp(word, "comment") == 0 || strcmp(word, "obj_info") == 0)
      continue;
    if (strcmp(word, "format") == 0)
    {
      if (fields < 3 || strcmp(b, "1.0") != 0)
        return mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s': unsupported PLY format line '%s'", name, line);
      if (strcmp(a, "ascii") == 0)
        h->binary = 0;
      else if (strcmp(a, "binary_little_endian") == 0)
        h->binary = 1;
      else if (strcmp(a, "binary_big_endian") == 0)
        h->binary = 2;
      else
        return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': unknown PLY format '%s'", name, a);
    }
    else if (strcmp(word, "element") == 0)
    {
      char* end = NULL;
      const long long count = fields >= 3 ? strtoll(b, &end, 10) : -1;
      if (fields < 3 || !end || *end != '\0' || count < 0 || count >= INT32_MAX)
        return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': bad element line '%s'", name, line);
      if (h->element_count == PLY_MAX_ELEMENTS)
        return mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s': more than %d PLY elements", name, PLY_MAX_ELEMENTS);
      ply_element* e = &h->elements[h->element_count++];
      memset(e, 0, sizeof(*e));
      snprintf(e->name, sizeof(e->name), "%s", a);
      e->count = count;
    }
    else if (strcmp(word, "property") == 0)
    {
      if (h->element_count == 0)
        return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': property before any element", name);
      ply_element* e = &h->elements[h->element_count - 1];
      if (e->property_count == PLY_MAX_PROPERTIES)
        return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': more than %d properties in element '%s'",
          name, PLY_MAX_PROPERTIES, e->name);
      ply_property* p = &e->properties[e->property_count++];
      memset(p, 0, sizeof(*p));
      const char* pname = NULL;
      if (strcmp(a, "list") == 0)
      {
        if (fields < 5 || !ply_is_integer_type(b) || ply_type_size(cc) == 0)
          return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': bad list property '%s'", name, line);
        p->is_list = 1;
        p->count_size = ply_type_size(b);
        p->count_unsigned = ply_is_unsigned_type(b);
        p->size = ply_type_size(cc);
        p->is_float = ply_is_float_type(cc);
        p->is_unsigned = ply_is_unsigned_type(cc);
        pname = d;
        if (strcmp(e->name, "face") == 0 &&
          (strcmp(pname, "vertex_indices") == 0 || strcmp(pname, "vertex_index") == 0))
        {
          if (p->is_float)
            return mrgi_error_set(err, MRGI_ERR_FORMAT,
              "'%s': face indices of a floating-point type ('%s')", name, line);
          p->is_index = 1;
        }
      }
      else
      {
        if (fields < 3 || ply_type_size(a) == 0)
          return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': bad property '%s'", name, line);
        p->size = ply_type_size(a);
        p->is_float = ply_is_float_type(a);
        p->is_unsigned = ply_is_unsigned_type(a);
        pname = b;
        e->has_x |= strcmp(pname, "x") == 0;
        e->has_y |= strcmp(pname, "y") == 0;
        e->has_z |= strcmp(pname, "z") == 0;
      }
    }
    else if (strcmp(word, "end_header") == 0)
    {
      ended = 1;
    }
    else
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': unknown PLY header line '%s'", name, line);
    }
  }
  if (!ended)
    return mrgi_error_set(
      err, MRGI_ERR_FORMAT, "'%s': the PLY header never ends (no end_header)", name);
  if (h->binary < 0)
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the PLY header has no format line", name);
  h->body = c.pos;
  return MRGI_OK;
}

/* Reads a binary scalar of `size` bytes at p (byte order: big when `big`). */
static double ply_read_binary(
  const unsigned char* p, int32_t size, int32_t is_float, int32_t is_unsigned, int big)
{
  unsigned char b[8];
  for (int32_t i = 0; i < size; ++i)
    b[i] = big ? p[size - 1 - i] : p[i];
  /* b is little endian now; assemble without alignment assumptions. */
  uint64_t u = 0;
  for (int32_t i = size - 1; i >= 0; --i)
    u = (u << 8) | b[i];
  if (is_float)
  {
    if (size == 4)
    {
      const uint32_t u32 = (uint32_t)u;
      float f;
      memcpy(&f, &u32, 4);
      return (double)f;
    }
    double dv;
    memcpy(&dv, &u, 8);
    return dv;
  }
  if (is_unsigned)
    return (double)u;
  const int shift = 64 - 8 * size;
  return (double)((int64_t)(u << shift) >> shift);
}

static mrgi_status ply_check_binary(const unsigned char* data, size_t size, const char* name,
  const ply_header* h, int64_t nv, mrgi_error* err)
{
  size_t pos = h->body;
  const int big = h->binary == 2;
  for (int32_t ei = 0; ei < h->element_count; ++ei)
  {
    const ply_element* e = &h->elements[ei];
    for (int64_t i = 0; i < e->count; ++i)
    {
      for (int32_t pi = 0; pi < e->property_count; ++pi)
      {
        const ply_property* p = &e->properties[pi];
        if (!p->is_list)
        {
          if (size - pos < (size_t)p->size)
            goto truncated;
          pos += (size_t)p->size;
          continue;
        }
        if (size - pos < (size_t)p->count_size)
          goto truncated;
        const double count = ply_read_binary(data + pos, p->count_size, 0, p->count_unsigned, big);
        pos += (size_t)p->count_size;
        if (count < 0)
          return mrgi_error_set(err, MRGI_ERR_FORMAT,
            "'%s': element '%s' %lld has a negative list count (%.0f)", name, e->name, (long long)i,
            count);
        if (count > (double)((size - pos) / (size_t)p->size))
          goto truncated;
        const size_t items = (size_t)count;
        if (p->is_index)
        {
          for (size_t k = 0; k < items; ++k)
          {
            const double v =
              ply_read_binary(data + pos + k * (size_t)p->size, p->size, 0, p->is_unsigned, big);
            if (v < 0 || v >= (double)nv)
              return mrgi_error_set(err, MRGI_ERR_FORMAT,
                "'%s': face %lld refers to vertex %.0f, outside [0, %lld)", name, (long long)i, v,
                (long long)nv);
          }
        }
        pos += items * (size_t)p->size;
      }
    }
  }
  return MRGI_OK;
truncated:
  return mrgi_error_set(err, MRGI_ERR_FORMAT,
    "'%s' is truncated: the PLY header declares more data than the file's %lld bytes", name,
    (long long)size);
}

/* Next blank-separated token of `*s`, NUL-terminated in place; NULL when none. */
static char* ply_token(char** s)
{
  char* p = *s;
  while (*p == ' ' || *p == '\t' || *p == '\r')
    ++p;
  if (*p == '\0')
  {
    *s = p;
    return NULL;
  }
  char* start = p;
  while (*p && *p != ' ' && *p != '\t' && *p != '\r')
    ++p;
  if (*p)
    *p++ = '\0';
  *s = p;
  return start;
}

static int ply_number(const char* token, double* value)
{
  char* end = NULL;
  errno = 0;
  *value = strtod(token, &end);
  return end != token && *end == '\0';
}

static mrgi_status ply_check_ascii(const unsigned char* data, size_t size, const char* name,
  const ply_header* h, int64_t nv, mrgi_error* err)
{
  char* line = (char*)malloc(MRGI_INPUT_MAX_LINE + 1);
  if (!line)
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "'%s': out of memory", name);
  mrgi_line_cursor c;
  mrgi_line_cursor_init(&c, data + h->body, size - h->body);
  mrgi_status status = MRGI_OK;
  int64_t need_lines = 0, lines = 0;
  for (int32_t ei = 0; ei < h->element_count; ++ei)
    need_lines += h->elements[ei].count;
  for (int32_t ei = 0; ei < h->element_count && status == MRGI_OK; ++ei)
  {
    const ply_element* e = &h->elements[ei];
    for (int64_t i = 0; i < e->count && status == MRGI_OK; ++i)
    {
      int r = 0;
      char* s = NULL;
      while ((r = mrgi_line_next(&c, line, MRGI_INPUT_MAX_LINE + 1)) > 0)
      {
        s = line;
        while (*s == ' ' || *s == '\t')
          ++s;
        if (*s)
          break;
      }
      if (r < 0)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s': a PLY data line is longer than %d bytes", name, MRGI_INPUT_MAX_LINE);
        break;
      }
      if (r == 0)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' is truncated: the PLY header declares %lld data lines, the file has %lld", name,
          (long long)need_lines, (long long)lines);
        break;
      }
      ++lines;
      for (int32_t pi = 0; pi < e->property_count && status == MRGI_OK; ++pi)
      {
        const ply_property* p = &e->properties[pi];
        double v = 0;
        char* t = ply_token(&s);
        if (!t || !ply_number(t, &v))
        {
          status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': element '%s' %lld: %s", name,
            e->name, (long long)i, t ? "a value is not a number" : "too few values on its line");
          break;
        }
        if (!p->is_list)
          continue;
        if (!(v >= 0) || v != floor(v))
        {
          status = mrgi_error_set(err, MRGI_ERR_FORMAT,
            "'%s': element '%s' %lld: bad list count '%s'", name, e->name, (long long)i, t);
          break;
        }
        for (double k = 0; k < v; ++k)
        {
          double item = 0;
          t = ply_token(&s);
          if (!t || !ply_number(t, &item))
          {
            status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': element '%s' %lld: %s", name,
              e->name, (long long)i,
              t ? "a list item is not a number" : "fewer list items than its count");
            break;
          }
          if (p->is_index && (!(item >= 0) || item >= (double)nv || item != floor(item)))
          {
            status = mrgi_error_set(err, MRGI_ERR_FORMAT,
              "'%s': face %lld refers to vertex %s, outside [0, %lld)", name, (long long)i, t,
              (long long)nv);
            break;
          }
        }
      }
    }
  }
  free(line);
  return status;
}

mrgi_status mrgi_ply_check_buffer(
  const void* data, size_t size, const char* name, mrgi_ply_info* info, mrgi_error* err)
{
  if (!name)
    name = "PLY data";
  ply_header* h = (ply_header*)malloc(sizeof(ply_header));
  if (!h)
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "'%s': out of memory", name);
  mrgi_status status = ply_parse_header(data, size, name, h, err);
  const ply_element* vertex = NULL;
  int64_t faces = 0;
  for (int32_t i = 0; status == MRGI_OK && i < h->element_count; ++i)
  {
    if (strcmp(h->elements[i].name, "vertex") == 0)
    {
      if (vertex)
        status =
          mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the PLY file has two vertex elements", name);
      vertex = &h->elements[i];
    }
    if (strcmp(h->elements[i].name, "face") == 0)
      faces = h->elements[i].count;
  }
  if (status == MRGI_OK && !vertex)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the PLY file has no vertex element", name);
  }
  if (status == MRGI_OK && (!vertex->has_x || !vertex->has_y || !vertex->has_z))
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT,
      "'%s': the PLY vertex element lacks %s%s%s (x, y and z are required)", name,
      vertex->has_x ? "" : "x ", vertex->has_y ? "" : "y ", vertex->has_z ? "" : "z");
  }
  if (status == MRGI_OK)
  {
    status = h->binary
      ? ply_check_binary((const unsigned char*)data, size, name, h, vertex->count, err)
      : ply_check_ascii((const unsigned char*)data, size, name, h, vertex->count, err);
  }
  if (status == MRGI_OK && info)
  {
    info->vertex_count = vertex->count;
    info->face_count = faces;
    info->binary = h->binary ? 1 : 0;
  }
  free(h);
  return status;
}

mrgi_status mrgi_ply_check(const char* path, mrgi_ply_info* info, mrgi_error* err)
{
  if (!path)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PLY check: no file name given");
  }
  mrgi_input in;
  mrgi_status status = mrgi_input_map(path, &in, err);
  if (status == MRGI_OK)
  {
    status = mrgi_ply_check_buffer(in.data, in.size, path, info, err);
    mrgi_input_unmap(&in);
  }
  return status;
}
