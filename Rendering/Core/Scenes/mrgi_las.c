/* LAS reader: see mrgi_las.h. Field offsets are the ASPRS LAS 1.4 R15
 * specification's (public header block, point data record formats 0-10). */
#include "mrgi_las.h"

#include "mrgi_input.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Public header block: bytes every version has (1.0-1.2), and 1.3's, 1.4's. */
#define LAS_HEADER_12 227
#define LAS_HEADER_13 235
#define LAS_HEADER_14 375

static uint16_t read_u16(const unsigned char* p)
{
  return (uint16_t)(p[0] | (p[1] << 8));
}

static uint32_t read_u32(const unsigned char* p)
{
  return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static uint64_t read_u64(const unsigned char* p)
{
  return (uint64_t)read_u32(p) | ((uint64_t)read_u32(p + 4) << 32);
}

static int32_t read_i32(const unsigned char* p)
{
  const uint32_t u = read_u32(p);
  int32_t v;
  memcpy(&v, &u, sizeof(v));
  return v;
}

static double read_f64(const unsigned char* p)
{
  const uint64_t u = read_u64(p);
  double v;
  memcpy(&v, &u, sizeof(v));
  return v;
}

int32_t mrgi_las_record_length(int32_t format)
{
  static const int32_t lengths[11] = { 20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67 };
  return (format >= 0 && format <= 10) ? lengths[format] : 0;
}

/* Where RGB lives in a record of `format`, or -1. */
static int rgb_offset(int32_t format)
{
  switch (format)
  {
    case 2:
      return 20;
    case 3:
    case 5:
      return 28;
    case 7:
    case 8:
    case 10:
      return 30;
    default:
      return -1;
  }
}

mrgi_status mrgi_las_read_header_buffer(
  const void* data, size_t size, mrgi_las_header* header, mrgi_error* err)
{
  if (!data || !header)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "LAS: no data or no header given");
  }
  const unsigned char* b = (const unsigned char*)data;
  memset(header, 0, sizeof(*header));
  if (size < 4 || memcmp(b, "LASF", 4) != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "LAS: no 'LASF' signature (not a LAS file)");
  }
  if (size < LAS_HEADER_12)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
      "LAS: the file (%zu bytes) is shorter than a LAS header (%d bytes)", size, LAS_HEADER_12);
  }
  header->version_major = b[24];
  header->version_minor = b[25];
  if (header->version_major != 1 || header->version_minor > 4)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "LAS: version %d.%d is not 1.0-1.4",
      (int)header->version_major, (int)header->version_minor);
  }
  header->header_size = read_u16(b + 94);
  const int32_t needed = header->version_minor >= 4 ? LAS_HEADER_14
    : header->version_minor == 3                     ? LAS_HEADER_13
                                                     : LAS_HEADER_12;
  if (header->header_size < needed)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
      "LAS: header size %d is smaller than the %d bytes of a version 1.%d header",
      (int)header->header_size, (int)needed, (int)header->version_minor);
  }
  if ((size_t)header->header_size > size)
  {
    /* A file cut inside its header: say so, not "outside 375..307". */
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
      "LAS: the file (%zu bytes) ends inside its %d-byte header (truncated?)", size,
      (int)header->header_size);
  }
  header->offset_to_points = (int64_t)read_u32(b + 96);
  const int32_t format_byte = b[104];
  if ((format_byte & 0x80) != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
      "LAS: compressed LAZ is not supported (point format byte %d); decompress it first, "
      "e.g. with laszip",
      (int)format_byte);
  }
  header->point_format = format_byte & 0x3F;
  header->point_record_length = read_u16(b + 105);
  const int32_t minimum = mrgi_las_record_length(header->point_format);
  if (minimum == 0)
  {
    return mrgi_error_set(
      err, MRGI_ERR_FORMAT, "LAS: point format %d is not 0-10", (int)header->point_format);
  }
  if (header->point_record_length < minimum)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
      "LAS: point record length %d is shorter than point format %d's %d bytes",
      (int)header->point_record_length, (int)header->point_format, (int)minimum);
  }
  header->point_count = (int64_t)read_u32(b + 107);
  if (header->version_minor >= 4)
  {
    const uint64_t count64 = read_u64(b + 247);
    if (count64 > (uint64_t)INT64_MAX)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "LAS: point count %llu is absurd",
        (unsigned long long)count64);
    }
    if (count64 != 0)
    {
      header->point_count = (int64_t)count64;
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    header->scale[c] = read_f64(b + 131 + 8 * c);
    header->offset[c] = read_f64(b + 155 + 8 * c);
    header->header_max[c] = read_f64(b + 179 + 16 * c);
    header->header_min[c] = read_f64(b + 187 + 16 * c);
    if (!isfinite(header->scale[c]) || header->scale[c] == 0.0)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "LAS: %c scale factor %g is zero or not finite",
        "xyz"[c], header->scale[c]);
    }
    if (!isfinite(header->offset[c]))
    {
      return mrgi_error_set(
        err, MRGI_ERR_FORMAT, "LAS: %c offset is not finite", "xyz"[c]);
    }
  }
  if (header->offset_to_points < header->header_size || (uint64_t)header->offset_to_points > size)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
      "LAS: point data offset %lld is outside the file (header %d bytes, file %zu bytes)",
      (long long)header->offset_to_points, (int)header->header_size, size);
  }
  if (header->point_count <= 0)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "LAS: the file has no points");
  }
  const uint64_t available = (uint64_t)(size - (size_t)header->offset_to_points);
  if ((uint64_t)header->point_count > available / (uint64_t)header->point_record_length)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
      "LAS: the header says %lld points of %d bytes, but the file holds %llu bytes of point "
      "data (truncated?)",
      (long long)header->point_count, (int)header->point_record_length,
      (unsigned long long)available);
  }
  mrgi_error_clear(err);
  return MRGI_OK;
}

void mrgi_las_points_destroy(mrgi_las_points* points)
{
  if (!points)
  {
    return;
  }
  free(points->positions);
  free(points->intensity);
  free(points->classification);
  free(points->return_number);
  free(points->number_of_returns);
  free(points->colors);
  memset(points, 0, sizeof(*points));
}

mrgi_status mrgi_las_read_buffer(
  const void* data, size_t size, int64_t max_points, mrgi_las_points* out, mrgi_error* err)
{
  if (!out || max_points < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "LAS: no output or max_points < 1");
  }
  memset(out, 0, sizeof(*out));
  mrgi_las_header h;
  mrgi_status status = mrgi_las_read_header_buffer(data, size, &h, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (h.point_count > max_points)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "LAS: %lld points exceed the limit of %lld",
      (long long)h.point_count, (long long)max_points);
  }
  const size_t n = (size_t)h.point_count;
  if (n > SIZE_MAX / (3 * sizeof(float)))
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "LAS: %zu points do not fit in memory", n);
  }
  const int rgb = rgb_offset(h.point_format);
  const int extended = h.point_format >= 6;
  out->positions = (float*)malloc(3 * n * sizeof(float));
  out->intensity = (uint16_t*)malloc(n * sizeof(uint16_t));
  out->classification = (uint8_t*)malloc(n);
  out->return_number = (uint8_t*)malloc(n);
  out->number_of_returns = (uint8_t*)malloc(n);
  out->colors = rgb >= 0 ? (float*)malloc(3 * n * sizeof(float)) : NULL;
  if (!out->positions || !out->intensity || !out->classification || !out->return_number ||
    !out->number_of_returns || (rgb >= 0 && !out->colors))
  {
    mrgi_las_points_destroy(out);
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "LAS: cannot allocate %zu points", n);
  }

  /* First pass: world bounds in double (the header's may be stale), the
   * attributes, and whether RGB is 8- or 16-bit. */
  const unsigned char* records = (const unsigned char*)data + h.offset_to_points;
  const size_t stride = (size_t)h.point_record_length;
  double lo[3] = { INFINITY, INFINITY, INFINITY };
  double hi[3] = { -INFINITY, -INFINITY, -INFINITY };
  uint16_t rgb_max = 0;
  for (size_t i = 0; i < n; ++i)
  {
    const unsigned char* r = records + i * stride;
    for (int c = 0; c < 3; ++c)
    {
      const double v = (double)read_i32(r + 4 * c) * h.scale[c] + h.offset[c];
      lo[c] = v < lo[c] ? v : lo[c];
      hi[c] = v > hi[c] ? v : hi[c];
    }
    out->intensity[i] = read_u16(r + 12);
    if (extended)
    {
      out->return_number[i] = (uint8_t)(r[14] & 0x0F);
      out->number_of_returns[i] = (uint8_t)(r[14] >> 4);
      out->classification[i] = r[16];
    }
    else
    {
      out->return_number[i] = (uint8_t)(r[14] & 0x07);
      out->number_of_returns[i] = (uint8_t)((r[14] >> 3) & 0x07);
      out->classification[i] = (uint8_t)(r[15] & 0x1F);
    }
    for (int c = 0; rgb >= 0 && c < 3; ++c)
    {
      const uint16_t v = read_u16(r + rgb + 2 * c);
      rgb_max = v > rgb_max ? v : rgb_max;
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!isfinite(lo[c]) || !isfinite(hi[c]))
    {
      mrgi_las_points_destroy(out);
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "LAS: %c coordinates overflow a double with scale %g and offset %g", "xyz"[c],
        h.scale[c], h.offset[c]);
    }
    /* Recentred float positions must stay finite (and meaningful): a cloud
     * wider than 1e30 units is a corrupt scale or offset, not data. */
    const double extent = hi[c] - lo[c];
    if (!(extent <= 1e30))
    {
      mrgi_las_points_destroy(out);
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "LAS: the points span %g units in %c: too wide to recentre (corrupt scale or offset?)",
        extent, "xyz"[c]);
    }
    out->origin[c] = lo[c] + 0.5 * extent;
    out->bounds[2 * c] = lo[c];
    out->bounds[2 * c + 1] = hi[c];
  }

  /* Second pass: positions relative to the origin, in double, then float. */
  const double rgb_scale = rgb_max > 255 ? 1.0 / 65535.0 : 1.0 / 255.0;
  for (size_t i = 0; i < n; ++i)
  {
    const unsigned char* r = records + i * stride;
    for (int c = 0; c < 3; ++c)
    {
      const double v = (double)read_i32(r + 4 * c) * h.scale[c] + h.offset[c];
      out->positions[3 * i + (size_t)c] = (float)(v - out->origin[c]);
      if (rgb >= 0)
      {
        out->colors[3 * i + (size_t)c] = (float)(read_u16(r + rgb + 2 * c) * rgb_scale);
      }
    }
  }
  out->count = h.point_count;
  mrgi_error_clear(err);
  return MRGI_OK;
}

mrgi_status mrgi_las_read(
  const char* path, int64_t max_points, mrgi_las_points* out, mrgi_error* err)
{
  if (!path || !out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "LAS: no file name or no output given");
  }
  memset(out, 0, sizeof(*out));
  mrgi_input in;
  mrgi_status status = mrgi_input_map(path, &in, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  status = mrgi_las_read_buffer(in.data, in.size, max_points, out, err);
  mrgi_input_unmap(&in);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "'%s': ", path);
  }
  return status;
}
