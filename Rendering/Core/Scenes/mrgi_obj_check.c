#include "mrgi_obj_check.h"

#include "mrgi_input.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* Skips blanks; returns the next token's start (or the terminating NUL). */
static char* skip_blanks(char* s)
{
  while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\f' || *s == '\v')
    ++s;
  return s;
}

/* Counts the numbers at the start of `s` (strtod), up to `want`. */
static int count_numbers(char* s, int want)
{
  int n = 0;
  while (n < want)
  {
    s = skip_blanks(s);
    char* end = NULL;
    errno = 0;
    (void)strtod(s, &end);
    if (end == s)
      break;
    s = end;
    ++n;
  }
  return n;
}

/* Parses one index of a reference; 0 when absent (empty). Returns -1 on a bad one. */
static int parse_index(char** s, int64_t* value)
{
  char* p = *s;
  if (*p == '/' || *p == '\0' || *p == ' ' || *p == '\t')
  {
    *value = 0;
    return 0;
  }
  char* end = NULL;
  errno = 0;
  const long long v = strtoll(p, &end, 10);
  if (end == p || errno == ERANGE || (*end != '/' && *end != '\0' && *end != ' ' && *end != '\t'))
    return -1;
  *value = v;
  *s = end;
  return 1;
}

/* Whether index `v` (1-based, or negative relative to `so_far`) is valid. */
static int index_ok(int64_t v, int64_t so_far, int64_t* max_positive)
{
  if (v > 0)
  {
    if (v > *max_positive)
      *max_positive = v;
    return 1;
  }
  return v < 0 && -v <= so_far;
}

mrgi_status mrgi_obj_check_buffer(
  const void* data, size_t size, const char* name, mrgi_obj_info* info, mrgi_error* err)
{
  if (!name)
    name = "OBJ data";
  char* line = (char*)malloc(MRGI_INPUT_MAX_LINE + 1);
  if (!line)
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "'%s': out of memory", name);
  mrgi_line_cursor c;
  mrgi_line_cursor_init(&c, data, size);
  int64_t counts[3] = { 0, 0, 0 };    /* v, vt, vn so far */
  int64_t max_index[3] = { 0, 0, 0 }; /* largest positive index used */
  int64_t max_line[3] = { 0, 0, 0 };  /* where it was used */
  int64_t faces = 0;
  mrgi_status status = MRGI_OK;
  int r = 0;
  while ((r = mrgi_line_next(&c, line, MRGI_INPUT_MAX_LINE + 1)) > 0)
  {
    char* s = skip_blanks(line);
    const int64_t ln = c.line_number;
    if (s[0] == 'v' && (s[1] == ' ' || s[1] == '\t'))
    {
      if (count_numbers(s + 1, 3) < 3)
      {
        status = mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s' line %lld: a vertex needs 3 numbers", name, (long long)ln);
        break;
      }
      ++counts[0];
    }
    else if (s[0] == 'v' && s[1] == 't' && (s[2] == ' ' || s[2] == '\t'))
    {
      if (count_numbers(s + 2, 1) < 1)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: a texture coordinate needs a number", name, (long long)ln);
        break;
      }
      ++counts[1];
    }
    else if (s[0] == 'v' && s[1] == 'n' && (s[2] == ' ' || s[2] == '\t'))
    {
      if (count_numbers(s + 2, 3) < 3)
      {
        status = mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s' line %lld: a normal needs 3 numbers", name, (long long)ln);
        break;
      }
      ++counts[2];
    }
    else if ((s[0] == 'f' || s[0] == 'l' || s[0] == 'p') &&
      (s[1] == ' ' || s[1] == '\t' || s[1] == '\0'))
    {
      const char kind = s[0];
      const int need = kind == 'f' ? 3 : kind == 'l' ? 2 : 1;
      int refs = 0;
      s = skip_blanks(s + 1);
      while (*s && status == MRGI_OK)
      {
        for (int k = 0; k < 3; ++k)
        {
          int64_t v = 0;
          const int got = parse_index(&s, &v);
          if (got < 0 || (k == 0 && got == 0))
          {
            status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' line %lld: bad index in '%c' line",
              name, (long long)ln, kind);
            break;
          }
          if (got > 0 && !index_ok(v, counts[k], &max_index[k]))
          {
            static const char* const what[3] = { "vertex", "texture coordinate", "normal" };
            status = mrgi_error_set(err, MRGI_ERR_FORMAT,
              "'%s' line %lld: %s index %lld out of range (%lld declared so far)", name,
              (long long)ln, what[k], (long long)v, (long long)counts[k]);
            break;
          }
          if (got > 0 && v == max_index[k])
            max_line[k] = ln;
          if (*s != '/')
            break;
          ++s;
        }
        if (status != MRGI_OK)
          break;
        if (*s != '\0' && *s != ' ' && *s != '\t')
        {
          status = mrgi_error_set(err, MRGI_ERR_FORMAT,
            "'%s' line %lld: bad reference in '%c' line", name, (long long)ln, kind);
          break;
        }
        ++refs;
        s = skip_blanks(s);
      }
      if (status != MRGI_OK)
        break;
      if (refs < need)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' line %lld: a '%c' line needs at least %d vertices, it has %d", name, (long long)ln,
          kind, need, refs);
        break;
      }
      faces += kind == 'f';
    }
  }
  if (status == MRGI_OK && r < 0)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' line %lld is longer than %d bytes", name,
      (long long)c.line_number + 1, MRGI_INPUT_MAX_LINE);
  }
  for (int k = 0; k < 3 && status == MRGI_OK; ++k)
  {
    if (max_index[k] > counts[k])
    {
      static const char* const what[3] = { "vertex", "texture coordinate", "normal" };
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s' line %lld: %s index %lld out of range (the file has %lld)", name,
        (long long)max_line[k], what[k], (long long)max_index[k], (long long)counts[k]);
    }
  }
  if (status == MRGI_OK && counts[0] == 0)
  {
    status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' holds no vertices ('v' lines)", name);
  }
  if (status == MRGI_OK && info)
  {
    info->vertex_count = counts[0];
    info->face_count = faces;
  }
  free(line);
  return status;
}

mrgi_status mrgi_obj_check(const char* path, mrgi_obj_info* info, mrgi_error* err)
{
  mrgi_input in;
  mrgi_status status = mrgi_input_map(path, &in, err);
  if (status == MRGI_OK)
  {
    status = mrgi_obj_check_buffer(in.data, in.size, path, info, err);
    mrgi_input_unmap(&in);
  }
  return status;
}
