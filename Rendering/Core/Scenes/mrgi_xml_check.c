#include "mrgi_xml_check.h"

#include "mrgi_input.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The value of attribute `key` in the tag text [t, t + n) into `out`; 0 when absent. */
static int xml_attribute(const char* t, size_t n, const char* key, char* out, size_t cap)
{
  const size_t k = strlen(key);
  for (size_t i = 0; i + k + 2 < n; ++i)
  {
    const int boundary =
      i > 0 && (t[i - 1] == ' ' || t[i - 1] == '\t' || t[i - 1] == '\n' || t[i - 1] == '\r');
    if (!boundary || memcmp(t + i, key, k) != 0)
      continue;
    size_t j = i + k;
    while (j < n && (t[j] == ' ' || t[j] == '\t'))
      ++j;
    if (j >= n || t[j] != '=')
      continue;
    ++j;
    while (j < n && (t[j] == ' ' || t[j] == '\t'))
      ++j;
    if (j >= n || (t[j] != '"' && t[j] != '\''))
      continue;
    const char q = t[j++];
    size_t e = j;
    while (e < n && t[e] != q)
      ++e;
    if (e >= n)
      return 0;
    size_t len = e - j;
    if (len >= cap)
      len = cap - 1;
    memcpy(out, t + j, len);
    out[len] = '\0';
    return 1;
  }
  return 0;
}

/* Parses up to `count` integers of `text`; returns how many. */
static int xml_integers(const char* text, int64_t* v, int count)
{
  int n = 0;
  const char* p = text;
  while (n < count)
  {
    char* end = NULL;
    errno = 0;
    const long long x = strtoll(p, &end, 10);
    if (end == p || errno == ERANGE)
      break;
    v[n++] = x;
    p = end;
  }
  while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
    ++p;
  return *p ? -1 : n;
}

static int tag_is(const char* t, size_t n, const char* name)
{
  const size_t k = strlen(name);
  return n > k && memcmp(t, name, k) == 0 &&
    (t[k] == ' ' || t[k] == '\t' || t[k] == '\n' || t[k] == '\r' || t[k] == '/' || t[k] == '>');
}

typedef struct appended_ref
{
  int64_t offset;
  size_t tag_start;
} appended_ref;

mrgi_status mrgi_xml_check_buffer(const void* data, size_t size, const char* name, mrgi_error* err)
{
  const char* d = (const char*)data;
  if (!name)
    name = "VTK XML data";
  if (!d || size == 0)
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is empty", name);
  char value[256];
  int depth = 0, has_vtkfile = 0, header64 = 0, big = 0, compressed = 0;
  int64_t max_offset = -1, appended_start = -1;
  int appended_raw = 0;
  int64_t offsets_seen = 0;
  size_t pos = 0;
  while (pos < size)
  {
    const char* lt = memchr(d + pos, '<', size - pos);
    if (!lt)
      break;
    const size_t start = (size_t)(lt - d) + 1;
    if (size - start >= 3 && memcmp(d + start, "!--", 3) == 0)
    {
      size_t e = start + 3;
      while (e + 2 < size && memcmp(d + e, "-->", 3) != 0)
        ++e;
      pos = e + 3;
      continue;
    }
    const char* gt = memchr(d + start, '>', size - start);
    if (!gt)
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is truncated: an XML tag never ends", name);
    const size_t n = (size_t)(gt - (d + start));
    if (n > MRGI_XML_MAX_TAG)
      return mrgi_error_set(
        err, MRGI_ERR_FORMAT, "'%s': an XML tag longer than %d bytes", name, MRGI_XML_MAX_TAG);
    const char* t = d + start;
    pos = start + n + 1;
    if (n > 0 && (t[0] == '?' || t[0] == '!'))
      continue;
    if (n > 0 && t[0] == '/')
    {
      --depth;
      continue;
    }
    const int closed = n > 0 && t[n - 1] == '/';
    if (!closed && ++depth > MRGI_XML_MAX_DEPTH)
      return mrgi_error_set(
        err, MRGI_ERR_FORMAT, "'%s': XML elements nest deeper than %d", name, MRGI_XML_MAX_DEPTH);
    if (tag_is(t, n, "VTKFile"))
    {
      has_vtkfile = 1;
      if (!xml_attribute(t, n, "type", value, sizeof(value)))
        return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': the VTKFile element has no type", name);
      if (xml_attribute(t, n, "header_type", value, sizeof(value)))
      {
        if (strcmp(value, "UInt64") == 0)
          header64 = 1;
        else if (strcmp(value, "UInt32") != 0)
          return mrgi_error_set(
            err, MRGI_ERR_FORMAT, "'%s': unknown header_type '%s'", name, value);
      }
      if (xml_attribute(t, n, "byte_order", value, sizeof(value)))
      {
        if (strcmp(value, "BigEndian") == 0)
          big = 1;
        else if (strcmp(value, "LittleEndian") != 0)
          return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': unknown byte_order '%s'", name, value);
      }
      compressed = xml_attribute(t, n, "compressor", value, sizeof(value));
    }
    else if (tag_is(t, n, "Piece") || tag_is(t, n, "ImageData") ||
      tag_is(t, n, "RectilinearGrid") || tag_is(t, n, "StructuredGrid"))
    {
      static const char* const counts[] = { "NumberOfPoints", "NumberOfCells", "NumberOfVerts",
        "NumberOfLines", "NumberOfStrips", "NumberOfPolys" };
      for (size_t k = 0; k < sizeof(counts) / sizeof(counts[0]); ++k)
      {
        int64_t v = 0;
        if (xml_attribute(t, n, counts[k], value, sizeof(value)) &&
          (xml_integers(value, &v, 1) != 1 || v < 0 || v > MRGI_XML_MAX_ITEMS))
          return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': %s=\"%s\" is not a count in [0, %lld]",
            name, counts[k], value, (long long)MRGI_XML_MAX_ITEMS);
      }
      static const char* const extents[] = { "Extent", "WholeExtent" };
      for (size_t k = 0; k < 2; ++k)
      {
        int64_t e[6];
        if (!xml_attribute(t, n, extents[k], value, sizeof(value)))
          continue;
        double points = 1;
        int ok = xml_integers(value, e, 6) == 6;
        for (int a = 0; ok && a < 3; ++a)
        {
          ok = e[2 * a + 1] >= e[2 * a] - 1 && e[2 * a] >= INT32_MIN && e[2 * a + 1] <= INT32_MAX;
          points *= (double)(e[2 * a + 1] - e[2 * a] + 1);
        }
        if (!ok || points > (double)MRGI_XML_MAX_ITEMS)
          return mrgi_error_set(err, MRGI_ERR_FORMAT,
            "'%s': %s=\"%s\" is not 6 increasing integers spanning at most %lld points", name,
            extents[k], value, (long long)MRGI_XML_MAX_ITEMS);
      }
    }
    else if (tag_is(t, n, "DataArray"))
    {
      static const char* const types[] = { "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32",
        "Int64", "UInt64", "Float32", "Float64", "String", "Bit", "Char", "IdType" };
      int known = 0;
      if (xml_attribute(t, n, "type", value, sizeof(value)))
        for (size_t k = 0; k < sizeof(types) / sizeof(types[0]); ++k)
          known |= strcmp(value, types[k]) == 0;
      if (!known)
        return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': a DataArray of unknown type", name);
      int64_t v = 0;
      if (xml_attribute(t, n, "NumberOfComponents", value, sizeof(value)) &&
        (xml_integers(value, &v, 1) != 1 || v < 1 || v > 4096))
        return mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s': NumberOfComponents=\"%s\" is not in [1, 4096]", name, value);
      if (xml_attribute(t, n, "NumberOfTuples", value, sizeof(value)) &&
        (xml_integers(value, &v, 1) != 1 || v < 0 || v > MRGI_XML_MAX_ITEMS))
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s': NumberOfTuples=\"%s\" is not a count in [0, %lld]", name, value,
          (long long)MRGI_XML_MAX_ITEMS);
      if (xml_attribute(t, n, "format", value, sizeof(value)))
      {
        if (strcmp(value, "appended") == 0)
        {
          if (!xml_attribute(t, n, "offset", value, sizeof(value)) ||
            xml_integers(value, &v, 1) != 1 || v < 0)
            return mrgi_error_set(
              err, MRGI_ERR_FORMAT, "'%s': an appended DataArray without a valid offset", name);
          ++offsets_seen;
          if (v > max_offset)
            max_offset = v;
        }
        else if (strcmp(value, "ascii") != 0 && strcmp(value, "binary") != 0)
          return mrgi_error_set(
            err, MRGI_ERR_FORMAT, "'%s': unknown DataArray format '%s'", name, value);
      }
    }
    else if (tag_is(t, n, "AppendedData"))
    {
      appended_raw =
        !xml_attribute(t, n, "encoding", value, sizeof(value)) || strcmp(value, "raw") == 0;
      const char* underscore = memchr(d + pos, '_', size - pos);
      if (!underscore)
        return mrgi_error_set(
          err, MRGI_ERR_FORMAT, "'%s': AppendedData without its '_' marker", name);
      appended_start = (int64_t)(underscore - d) + 1;
      break; /* binary data follow: stop scanning tags */
    }
  }
  if (!has_vtkfile)
    return mrgi_error_set(
      err, MRGI_ERR_FORMAT, "'%s' is not a VTK XML file (no VTKFile element)", name);
  if (offsets_seen > 0)
  {
    if (appended_start < 0)
      return mrgi_error_set(
        err, MRGI_ERR_FORMAT, "'%s': appended DataArrays but no AppendedData", name);
    const int64_t available = (int64_t)size - appended_start;
    const int64_t header = header64 ? 8 : 4;
    if (max_offset + (appended_raw ? header : 1) > available)
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "'%s' is truncated or corrupt: an appended DataArray starts at offset %lld, the appended "
        "data hold %lld bytes",
        name, (long long)max_offset, (long long)available);
    if (appended_raw && !compressed)
    {
      /* Each raw block: a header with its byte count, then the bytes. Check the last one declared.
       */
      const unsigned char* h = (const unsigned char*)d + appended_start + max_offset;
      uint64_t bytes = 0;
      for (int64_t i = 0; i < header; ++i)
        bytes |= (uint64_t)h[big ? header - 1 - i : i] << (8 * i);
      if (bytes > (uint64_t)(available - max_offset - header))
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "'%s' is truncated or corrupt: an appended block declares %llu bytes, %lld follow", name,
          (unsigned long long)bytes, (long long)(available - max_offset - header));
    }
  }
  return MRGI_OK;
}

mrgi_status mrgi_xml_check(const char* path, mrgi_error* err)
{
  mrgi_input in;
  mrgi_status status = mrgi_input_map(path, &in, err);
  if (status == MRGI_OK)
  {
    status = mrgi_xml_check_buffer(in.data, in.size, path, err);
    mrgi_input_unmap(&in);
  }
  return status;
}
