#include "mrgi_ply_check.h"

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

static int ply_is_integer_type(const char* name)
{
  return ply_type_size(name) > 0 && strncmp(name, "float", 5) != 0 && strcmp(name, "double") != 0;
}

/* Reads one header line (without the newline) into `line`; returns its length or -1 at EOF. */
static int64_t ply_read_line(FILE* file, char* line, size_t size, int64_t* consumed)
{
  size_t n = 0;
  int c = 0;
  while ((c = fgetc(file)) != EOF)
  {
    ++*consumed;
    if (c == '\n')
    {
      break;
    }
    if (n + 1 < size)
    {
      line[n++] = (char)c;
    }
  }
  if (c == EOF && n == 0)
  {
    return -1;
  }
  while (n > 0 && (line[n - 1] == '\r' || line[n - 1] == ' ' || line[n - 1] == '\t'))
  {
    --n;
  }
  line[n] = '\0';
  return (int64_t)n;
}

typedef struct ply_element
{
  char name[64];
  int64_t count;
  int64_t fixed_bytes; /* bytes per instance from scalar properties and list counts */
  int32_t has_x, has_y, has_z;
} ply_element;

#define PLY_MAX_ELEMENTS 32

mrgi_status mrgi_ply_check(const char* path, mrgi_ply_info* info, mrgi_error* err)
{
  if (!path)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PLY check: no file name given");
  }
  FILE* file = fopen(path, "rb");
  if (!file)
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot open '%s'", path);
  }

  ply_element elements[PLY_MAX_ELEMENTS];
  int32_t element_count = 0;
  int32_t binary = -1;
  int32_t ended = 0;
  int64_t consumed = 0;
  int64_t line_number = 0;
  char line[512];
  mrgi_status status = MRGI_OK;

  while (!ended && consumed < MRGI_PLY_MAX_HEADER_BYTES)
  {
    if (ply_read_line(file, line, sizeof(line), &consumed) < 0)
    {
      break;
    }
    ++line_number;
    char word[64] = "", a[64] = "", b[64] = "", c[64] = "", d[64] = "";
    const int fields = sscanf(line, "%63s %63s %63s %63s %63s", word, a, b, c, d);
    if (line_number == 1)
    {
      if (strcmp(line, "ply") != 0)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is not a PLY file (no 'ply' magic line)", path);
        goto done;
      }
      continue;
    }
    if (fields <= 0 || strcmp(word, "comment") == 0 || strcmp(word, "obj_info") == 0)
    {
      continue;
    }
    if (strcmp(word, "format") == 0)
    {
      if (fields < 3 || strcmp(b, "1.0") != 0)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': unsupported PLY format line '%s'", path, line);
        goto done;
      }
      if (strcmp(a, "ascii") == 0)
        binary = 0;
      else if (strcmp(a, "binary_little_endian") == 0 || strcmp(a, "binary_big_endian") == 0)
        binary = 1;
      else
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': unknown PLY format '%s'", path, a);
        goto done;
      }
    }
    else if (strcmp(word, "element") == 0)
    {
      char* end = NULL;
      const long long count = fields >= 3 ? strtoll(b, &end, 10) : -1;
      if (fields < 3 || !end || *end != '\0' || count < 0 || count >= INT32_MAX)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': bad element line '%s'", path, line);
        goto done;
      }
      if (element_count == PLY_MAX_ELEMENTS)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': more than %d PLY elements", path, PLY_MAX_ELEMENTS);
        goto done;
      }
      ply_element* e = &elements[element_count++];
      memset(e, 0, sizeof(*e));
      snprintf(e->name, sizeof(e->name), "%s", a);
      e->count = count;
    }
    else if (strcmp(word, "property") == 0)
    {
      if (element_count == 0)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': property before any element", path);
        goto done;
      }
      ply_element* e = &elements[element_count - 1];
      const char* name = NULL;
      if (strcmp(a, "list") == 0)
      {
        if (fields < 5 || !ply_is_integer_type(b) || ply_type_size(c) == 0)
        {
          status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': bad list property '%s'", path, line);
          goto done;
        }
        e->fixed_bytes += ply_type_size(b);
        name = d;
      }
      else
      {
        if (fields < 3 || ply_type_size(a) == 0)
        {
          status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': bad property '%s'", path, line);
          goto done;
        }
        e->fixed_bytes += ply_type_size(a);
        name = b;
      }
      e->has_x |= strcmp(name, "x") == 0;
      e->has_y |= strcmp(name, "y") == 0;
      e->has_z |= strcmp(name, "z") == 0;
    }
    else if (strcmp(word, "end_header") == 0)
    {
      ended = 1;
    }
    else
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': unknown PLY header line '%s'", path, line);
      goto done;
    }
  }

  if (line_number == 0)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is empty", path);
    goto done;
  }
  if (!ended)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the PLY header never ends (no end_header)", path);
    goto done;
  }
  if (binary < 0)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the PLY header has no format line", path);
    goto done;
  }

  const ply_element* vertex = NULL;
  int64_t faces = 0;
  int64_t need_bytes = 0;
  int64_t need_lines = 0;
  for (int32_t i = 0; i < element_count; ++i)
  {
    if (strcmp(elements[i].name, "vertex") == 0)
      vertex = &elements[i];
    if (strcmp(elements[i].name, "face") == 0)
      faces = elements[i].count;
    need_bytes += elements[i].count * elements[i].fixed_bytes;
    need_lines += elements[i].count;
  }
  if (!vertex)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the PLY file has no vertex element", path);
    goto done;
  }
  if (!vertex->has_x || !vertex->has_y || !vertex->has_z)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT,
      "'%s': the PLY vertex element lacks %s%s%s (x, y and z are required)", path,
      vertex->has_x ? "" : "x ", vertex->has_y ? "" : "y ", vertex->has_z ? "" : "z");
    goto done;
  }

  if (binary)
  {
    if (fseek(file, 0, SEEK_END) != 0)
    {
      status = mrgi_error_set(err, MRGI_ERR_IO, "'%s': cannot seek", path);
      goto done;
    }
    const int64_t body = (int64_t)ftell(file) - consumed;
    if (body < need_bytes)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s' is truncated: the PLY header declares at least %lld bytes of data, the file has %lld",
        path, (long long)need_bytes, (long long)body);
      goto done;
    }
  }
  else
  {
    int64_t lines = 0;
    int in_line = 0;
    int ch = 0;
    while ((ch = fgetc(file)) != EOF && lines < need_lines)
    {
      if (ch == '\n')
      {
        lines += in_line;
        in_line = 0;
      }
      else if (ch != ' ' && ch != '\t' && ch != '\r')
      {
        in_line = 1;
      }
    }
    lines += in_line;
    if (lines < need_lines)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s' is truncated: the PLY header declares %lld data lines, the file has %lld", path,
        (long long)need_lines, (long long)lines);
      goto done;
    }
  }
  if (info)
  {
    info->vertex_count = vertex->count;
    info->face_count = faces;
    info->binary = binary;
  }

done:
  fclose(file);
  return status;
}
