/* OpenEXR writing (mrgi_exr.h, mrgi_exr_write()): channel names, the
 * conversion to half or float, and the atomic write through the stream of
 * mrgi_exr_stream.h. Split from mrgi_exr.c, which keeps the stream and the
 * reader. pwrite/open are POSIX; the core builds with -std=c11. */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_exr.h"

#include "mrgi_atomic_file.h"
#include "mrgi_exr_stream.h"

#include <openexr.h>

#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---------------------------------------------------------------------------
 * Value conversion for writing.
 * ------------------------------------------------------------------------- */

/* IEEE binary16 bits of `f`, rounded to nearest even. `f` must be finite with
 * |f| <= MRGI_EXR_HALF_MAX (the caller clamps), so no result is infinite. */
static uint16_t mrgi_exr_half_bits(float f)
{
  uint32_t bits;
  memcpy(&bits, &f, sizeof(bits));
  const uint32_t sign = (bits >> 16) & 0x8000u;
  const uint32_t magnitude = bits & 0x7fffffffu;
  if (magnitude >= 0x38800000u) /* >= 2^-14: a normal half */
  {
    /* Add just under half an output ulp, plus the kept lsb, to round to
     * nearest even; then drop 13 mantissa bits and rebias 127 -> 15. */
    const uint32_t rounded = magnitude + 0x0fffu + ((magnitude >> 13) & 1u);
    return (uint16_t)(sign | ((rounded - 0x38000000u) >> 13));
  }
  if (magnitude < 0x33000000u) /* < 2^-25: rounds to zero */
  {
    return (uint16_t)sign;
  }
  /* Subnormal half: value = m * 2^-24. */
  const uint32_t exponent = magnitude >> 23;
  const uint32_t mantissa = (magnitude & 0x7fffffu) | 0x800000u;
  const uint32_t shift = 126u - exponent; /* 14..24 */
  const uint32_t halfway = 1u << (shift - 1);
  const uint32_t remainder = mantissa & ((1u << shift) - 1u);
  uint32_t half_mantissa = mantissa >> shift;
  if (remainder > halfway || (remainder == halfway && (half_mantissa & 1u)))
  {
    ++half_mantissa;
  }
  return (uint16_t)(sign | half_mantissa);
}

/* NaN -> 0, then clamp into [-limit, limit] (infinities included). */
static float mrgi_exr_sanitize(float v, float limit)
{
  if (isnan(v))
  {
    return 0.0f;
  }
  if (v > limit)
  {
    return limit;
  }
  if (v < -limit)
  {
    return -limit;
  }
  return v;
}

/* ---------------------------------------------------------------------------
 * Writing.
 * ------------------------------------------------------------------------- */

static const char* const mrgi_exr_default_names_1[1] = { "Y" };
static const char* const mrgi_exr_default_names_3[3] = { "R", "G", "B" };
static const char* const mrgi_exr_default_names_4[4] = { "R", "G", "B", "A" };

static mrgi_status mrgi_exr_resolve_names(const mrgi_image* img, const char* const* channel_names,
  const char* const** out_names, mrgi_error* err)
{
  if (!channel_names)
  {
    switch (img->channels)
    {
      case 1:
        *out_names = mrgi_exr_default_names_1;
        return MRGI_OK;
      case 3:
        *out_names = mrgi_exr_default_names_3;
        return MRGI_OK;
      case 4:
        *out_names = mrgi_exr_default_names_4;
        return MRGI_OK;
      default:
        return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
          "no default channel names for a %d-channel image "
          "(defaults exist for 1, 3 and 4); pass channel_names",
          img->channels);
    }
  }
  for (int32_t c = 0; c < img->channels; ++c)
  {
    const char* name = channel_names[c];
    if (!name || name[0] == '\0')
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "channel name %d is NULL or empty", c);
    }
    if (strlen(name) >= MRGI_EXR_CHANNEL_NAME_SIZE)
    {
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
        "channel name %d '%.40s...' is longer than %d characters", c, name,
        MRGI_EXR_CHANNEL_NAME_SIZE - 1);
    }
    for (int32_t other = 0; other < c; ++other)
    {
      if (strcmp(channel_names[other], name) == 0)
      {
        return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
          "channel name '%s' is used twice (channels %d and %d)", name, other, c);
      }
    }
  }
  *out_names = channel_names;
  return MRGI_OK;
}

/* Everything the write needs to release, in one place. */
typedef struct mrgi_exr_writer
{
  mrgi_exr_stream stream;
  exr_context_t context;
  exr_encode_pipeline_t encoder;
  int encoder_ready;
  void* staging;             /* one chunk of converted values, allocated once */
  int32_t* image_channel_of; /* encoder channel index -> image channel index */
} mrgi_exr_writer;

static void mrgi_exr_writer_release(mrgi_exr_writer* w)
{
  if (w->encoder_ready)
  {
    exr_encoding_destroy(w->context, &w->encoder);
    w->encoder_ready = 0;
  }
  if (w->context)
  {
    exr_finish(&w->context);
    w->context = NULL;
  }
  if (w->stream.fd >= 0)
  {
    close(w->stream.fd);
    w->stream.fd = -1;
  }
  free(w->staging);
  w->staging = NULL;
  free(w->image_channel_of);
  w->image_channel_of = NULL;
}

/* Convert rows [y0, y0 + rows) of `img` into the staging buffer, same
 * interleaved layout, stored type. */
static void mrgi_exr_stage_rows(
  const mrgi_image* img, int32_t y0, int32_t rows, mrgi_exr_pixel_type type, void* staging)
{
  const size_t count = (size_t)rows * (size_t)img->width * (size_t)img->channels;
  const float* src = mrgi_image_at(img, 0, y0);
  if (type == MRGI_EXR_HALF)
  {
    uint16_t* dst = (uint16_t*)staging;
    for (size_t i = 0; i < count; ++i)
    {
      dst[i] = mrgi_exr_half_bits(mrgi_exr_sanitize(src[i], MRGI_EXR_HALF_MAX));
    }
  }
  else
  {
    float* dst = (float*)staging;
    for (size_t i = 0; i < count; ++i)
    {
      dst[i] = mrgi_exr_sanitize(src[i], FLT_MAX);
    }
  }
}

/* Encode all scanlines of `img` into the open context. */
static mrgi_status mrgi_exr_write_pixels(mrgi_exr_writer* w, const mrgi_image* img,
  const char* const* names, mrgi_exr_pixel_type type, const char* path, mrgi_error* err)
{
  const exr_pixel_type_t exr_type = type == MRGI_EXR_HALF ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
  const int32_t value_size = type == MRGI_EXR_HALF ? 2 : 4;
  int32_t lines_per_chunk = 0;
  exr_result_t rv = exr_get_scanlines_per_chunk(w->context, 0, &lines_per_chunk);
  if (rv != EXR_ERR_SUCCESS || lines_per_chunk < 1)
  {
    return mrgi_error_set(
      err, MRGI_ERR_FORMAT, "writing '%s': %s", path, mrgi_exr_reason(&w->stream, rv));
  }
  const size_t row_values = (size_t)img->width * (size_t)img->channels;
  w->staging = malloc(row_values * (size_t)lines_per_chunk * (size_t)value_size);
  w->image_channel_of = (int32_t*)malloc(sizeof(int32_t) * (size_t)img->channels);
  if (!w->staging || !w->image_channel_of)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
      "writing '%s': cannot allocate a %d-line staging buffer", path, lines_per_chunk);
  }
  const int32_t pixel_stride = img->channels * value_size;
  const int32_t line_stride = (int32_t)((size_t)pixel_stride * (size_t)img->width);
  for (int32_t y = 0; y < img->height; y += lines_per_chunk)
  {
    exr_chunk_info_t chunk;
    rv = exr_write_scanline_chunk_info(w->context, 0, y, &chunk);
    if (rv == EXR_ERR_SUCCESS)
    {
      rv = w->encoder_ready ? exr_encoding_update(w->context, 0, &chunk, &w->encoder)
                            : exr_encoding_initialize(w->context, 0, &chunk, &w->encoder);
    }
    if (rv != EXR_ERR_SUCCESS)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "writing '%s', scanline %d: %s", path, y,
        mrgi_exr_reason(&w->stream, rv));
    }
    const int first_chunk = !w->encoder_ready;
    w->encoder_ready = 1;
    /* The staging buffer holds lines_per_chunk rows; never trust more. */
    if (chunk.start_y != y || chunk.height < 1 || chunk.height > lines_per_chunk ||
      chunk.height > img->height - y)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT,
        "writing '%s': the library planned an unexpected chunk at scanline %d", path, y);
    }
    if (first_chunk)
    {
      /* The library lists channels alphabetically; map each back to ours. */
      if (w->encoder.channel_count != img->channels)
      {
        return mrgi_error_set(err, MRGI_ERR_FORMAT,
          "writing '%s': the library reports %d channels, expected %d", path,
          (int)w->encoder.channel_count, img->channels);
      }
      for (int16_t e = 0; e < w->encoder.channel_count; ++e)
      {
        w->image_channel_of[e] = -1;
        for (int32_t c = 0; c < img->channels; ++c)
        {
          if (strcmp(w->encoder.channels[e].channel_name, names[c]) == 0)
          {
            w->image_channel_of[e] = c;
          }
        }
        if (w->image_channel_of[e] < 0)
        {
          return mrgi_error_set(err, MRGI_ERR_FORMAT,
            "writing '%s': the library reports an unknown channel '%s'", path,
            w->encoder.channels[e].channel_name);
        }
      }
    }
    mrgi_exr_stage_rows(img, chunk.start_y, chunk.height, type, w->staging);
    for (int16_t e = 0; e < w->encoder.channel_count; ++e)
    {
      exr_coding_channel_info_t* channel = &w->encoder.channels[e];
      channel->encode_from_ptr =
        (const uint8_t*)w->staging + (size_t)w->image_channel_of[e] * (size_t)value_size;
      channel->user_pixel_stride = pixel_stride;
      channel->user_line_stride = line_stride;
      channel->user_bytes_per_element = (int16_t)value_size;
      channel->user_data_type = (uint16_t)exr_type;
    }
    if (first_chunk)
    {
      rv = exr_encoding_choose_default_routines(w->context, 0, &w->encoder);
    }
    if (rv == EXR_ERR_SUCCESS)
    {
      rv = exr_encoding_run(w->context, 0, &w->encoder);
    }
    if (rv != EXR_ERR_SUCCESS)
    {
      return mrgi_error_set(err, rv == EXR_ERR_WRITE_IO ? MRGI_ERR_IO : MRGI_ERR_FORMAT,
        "writing '%s', scanline %d: %s", path, y, mrgi_exr_reason(&w->stream, rv));
    }
  }
  return MRGI_OK;
}

/* Create the context, declare the header and write it, into temp_path. */
static mrgi_status mrgi_exr_write_header(mrgi_exr_writer* w, const mrgi_image* img,
  const char* const* names, mrgi_exr_pixel_type type, const char* temp_path, const char* path,
  mrgi_error* err)
{
  w->stream.fd = open(temp_path, O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (w->stream.fd < 0)
  {
    return mrgi_error_set(
      err, MRGI_ERR_IO, "writing '%s': cannot open '%s': %s", path, temp_path, strerror(errno));
  }
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = mrgi_exr_on_error;
  init.user_data = &w->stream;
  init.write_fn = mrgi_exr_stream_write;
  exr_result_t rv = exr_start_write(&w->context, temp_path, EXR_WRITE_FILE_DIRECTLY, &init);
  int part = 0;
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_add_part(w->context, NULL, EXR_STORAGE_SCANLINE, &part);
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_initialize_required_attr_simple(
      w->context, part, img->width, img->height, EXR_COMPRESSION_NONE);
  }
  const exr_pixel_type_t exr_type = type == MRGI_EXR_HALF ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
  for (int32_t c = 0; rv == EXR_ERR_SUCCESS && c < img->channels; ++c)
  {
    rv = exr_add_channel(w->context, part, names[c], exr_type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
  }
  if (rv == EXR_ERR_SUCCESS)
  {
    rv = exr_write_header(w->context);
  }
  if (rv != EXR_ERR_SUCCESS)
  {
    return mrgi_error_set(err, rv == EXR_ERR_WRITE_IO ? MRGI_ERR_IO : MRGI_ERR_FORMAT,
      "writing '%s': cannot write the header: %s", path, mrgi_exr_reason(&w->stream, rv));
  }
  return MRGI_OK;
}

mrgi_status mrgi_exr_write(const char* path, const mrgi_image* img,
  const char* const* channel_names, mrgi_exr_pixel_type pixel_type, mrgi_error* err)
{
  if (!path || path[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "EXR output path is NULL or empty");
  }
  mrgi_status status = mrgi_image_validate(img, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "writing '%s': ", path);
    return status;
  }
  if (pixel_type != MRGI_EXR_HALF && pixel_type != MRGI_EXR_FLOAT)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "writing '%s': unknown EXR pixel type %d (use MRGI_EXR_HALF or "
      "MRGI_EXR_FLOAT)",
      path, (int)pixel_type);
  }
  const char* const* names = NULL;
  status = mrgi_exr_resolve_names(img, channel_names, &names, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "writing '%s': ", path);
    return status;
  }

  char temp_path[MRGI_ATOMIC_FILE_PATH_MAX];
  status = mrgi_atomic_file_begin(path, temp_path, sizeof(temp_path), err);
  if (status != MRGI_OK)
  {
    return status;
  }
  mrgi_exr_writer writer;
  memset(&writer, 0, sizeof(writer));
  writer.stream.fd = -1;
  writer.stream.size = -1;

  status = mrgi_exr_write_header(&writer, img, names, pixel_type, temp_path, path, err);
  if (status == MRGI_OK)
  {
    status = mrgi_exr_write_pixels(&writer, img, names, pixel_type, path, err);
  }
  if (status == MRGI_OK)
  {
    /* exr_finish writes the chunk offset table: its result matters. */
    if (writer.encoder_ready)
    {
      exr_encoding_destroy(writer.context, &writer.encoder);
      writer.encoder_ready = 0;
    }
    const exr_result_t rv = exr_finish(&writer.context);
    writer.context = NULL;
    if (rv != EXR_ERR_SUCCESS)
    {
      status = mrgi_error_set(err, MRGI_ERR_IO, "writing '%s': cannot finish the file: %s", path,
        mrgi_exr_reason(&writer.stream, rv));
    }
  }
  if (status == MRGI_OK)
  {
    /* close() can report a deferred write error (e.g. a full disk). */
    const int fd = writer.stream.fd;
    writer.stream.fd = -1;
    if (close(fd) != 0)
    {
      status = mrgi_error_set(err, MRGI_ERR_IO, "writing '%s': %s", path, strerror(errno));
    }
  }
  mrgi_exr_writer_release(&writer);
  if (status != MRGI_OK)
  {
    mrgi_atomic_file_abort(temp_path);
    return status;
  }
  return mrgi_atomic_file_commit(temp_path, path, err);
}
