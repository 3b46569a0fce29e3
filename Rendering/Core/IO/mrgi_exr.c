/* pread/pwrite/fstat are POSIX; the core builds with -std=c11. */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_exr.h"

#include "mrgi_atomic_file.h"

#include <openexr.h>

#include <errno.h>
#include <fcntl.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

/* ---------------------------------------------------------------------------
 * Stream shared with OpenEXRCore.
 *
 * We hand the library our own read/write callbacks instead of letting it open
 * the file, for two reasons: the library's default file handler takes over
 * the context's user_data, and we need user_data to collect its error
 * messages (which it would otherwise print to stderr); and owning the file
 * descriptor lets us check the magic number and file size before parsing.
 * ------------------------------------------------------------------------- */

typedef struct mrgi_exr_stream
{
  int fd;
  int64_t size;      /* file size in bytes (reading), -1 when unknown */
  char message[256]; /* first error the library reported, "" if none */
} mrgi_exr_stream;

static void mrgi_exr_on_error(exr_const_context_t ctxt, exr_result_t code, const char* msg)
{
  void* user_data = NULL;
  if (exr_get_user_data(ctxt, &user_data) != EXR_ERR_SUCCESS || !user_data)
  {
    return;
  }
  mrgi_exr_stream* stream = (mrgi_exr_stream*)user_data;
  /* Keep the first report: later ones are usually consequences of it. */
  if (stream->message[0] == '\0')
  {
    const char* text = msg ? msg : exr_get_default_error_message(code);
    size_t length = strlen(text);
    if (length >= sizeof(stream->message))
    {
      length = sizeof(stream->message) - 1;
    }
    memcpy(stream->message, text, length);
    stream->message[length] = '\0';
  }
}

static int64_t mrgi_exr_stream_read(exr_const_context_t ctxt, void* user_data, void* buffer,
                                    uint64_t size, uint64_t offset,
                                    exr_stream_error_func_ptr_t error_cb)
{
  const mrgi_exr_stream* stream = (const mrgi_exr_stream*)user_data;
  uint8_t* out = (uint8_t*)buffer;
  uint64_t done = 0;
  while (done < size)
  {
    const ssize_t n = pread(stream->fd, out + done, (size_t)(size - done), (off_t)(offset + done));
    if (n < 0)
    {
      if (errno == EINTR)
      {
        continue;
      }
      if (error_cb)
      {
        error_cb(ctxt, EXR_ERR_READ_IO, "read failed: %s", strerror(errno));
      }
      return -1;
    }
    if (n == 0)
    {
      break; /* end of file: the library reports the short read */
    }
    done += (uint64_t)n;
  }
  return (int64_t)done;
}

static int64_t mrgi_exr_stream_size(exr_const_context_t ctxt, void* user_data)
{
  (void)ctxt;
  return ((const mrgi_exr_stream*)user_data)->size;
}

static int64_t mrgi_exr_stream_write(exr_const_context_t ctxt, void* user_data,
                                     const void* buffer, uint64_t size, uint64_t offset,
                                     exr_stream_error_func_ptr_t error_cb)
{
  const mrgi_exr_stream* stream = (const mrgi_exr_stream*)user_data;
  const uint8_t* in = (const uint8_t*)buffer;
  uint64_t done = 0;
  while (done < size)
  {
    const ssize_t n = pwrite(stream->fd, in + done, (size_t)(size - done), (off_t)(offset + done));
    if (n < 0)
    {
      if (errno == EINTR)
      {
        continue;
      }
      if (error_cb)
      {
        error_cb(ctxt, EXR_ERR_WRITE_IO, "write failed: %s", strerror(errno));
      }
      return -1;
    }
    done += (uint64_t)n;
  }
  return (int64_t)done;
}

static const char* mrgi_exr_reason(const mrgi_exr_stream* stream, exr_result_t code)
{
  return stream->message[0] ? stream->message : exr_get_default_error_message(code);
}

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

static mrgi_status mrgi_exr_resolve_names(const mrgi_image* img,
                                          const char* const* channel_names,
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
      return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "channel name %d is NULL or empty",
                            c);
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
                              "channel name '%s' is used twice (channels %d and %d)", name,
                              other, c);
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
  void* staging; /* one chunk of converted values, allocated once */
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
static void mrgi_exr_stage_rows(const mrgi_image* img, int32_t y0, int32_t rows,
                                mrgi_exr_pixel_type type, void* staging)
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
                                         const char* const* names, mrgi_exr_pixel_type type,
                                         const char* path, mrgi_error* err)
{
  const exr_pixel_type_t exr_type = type == MRGI_EXR_HALF ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
  const int32_t value_size = type == MRGI_EXR_HALF ? 2 : 4;
  int32_t lines_per_chunk = 0;
  exr_result_t rv = exr_get_scanlines_per_chunk(w->context, 0, &lines_per_chunk);
  if (rv != EXR_ERR_SUCCESS || lines_per_chunk < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "writing '%s': %s", path,
                          mrgi_exr_reason(&w->stream, rv));
  }
  const size_t row_values = (size_t)img->width * (size_t)img->channels;
  w->staging = malloc(row_values * (size_t)lines_per_chunk * (size_t)value_size);
  w->image_channel_of = (int32_t*)malloc(sizeof(int32_t) * (size_t)img->channels);
  if (!w->staging || !w->image_channel_of)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "writing '%s': cannot allocate a %d-line staging buffer", path,
                          lines_per_chunk);
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
                            "writing '%s': the library planned an unexpected chunk at scanline %d",
                            path, y);
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
                                "writing '%s': the library reports an unknown channel '%s'",
                                path, w->encoder.channels[e].channel_name);
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
                            "writing '%s', scanline %d: %s", path, y,
                            mrgi_exr_reason(&w->stream, rv));
    }
  }
  return MRGI_OK;
}

/* Create the context, declare the header and write it, into temp_path. */
static mrgi_status mrgi_exr_write_header(mrgi_exr_writer* w, const mrgi_image* img,
                                         const char* const* names, mrgi_exr_pixel_type type,
                                         const char* temp_path, const char* path,
                                         mrgi_error* err)
{
  w->stream.fd = open(temp_path, O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (w->stream.fd < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "writing '%s': cannot open '%s': %s", path,
                          temp_path, strerror(errno));
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
    rv = exr_initialize_required_attr_simple(w->context, part, img->width, img->height,
                                             EXR_COMPRESSION_NONE);
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
                          "writing '%s': cannot write the header: %s", path,
                          mrgi_exr_reason(&w->stream, rv));
  }
  return MRGI_OK;
}

mrgi_status mrgi_exr_write(const char* path, const mrgi_image* img,
                           const char* const* channel_names, mrgi_exr_pixel_type pixel_type,
                           mrgi_error* err)
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
      status = mrgi_error_set(err, MRGI_ERR_IO, "writing '%s': cannot finish the file: %s",
                              path, mrgi_exr_reason(&writer.stream, rv));
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

/* ---------------------------------------------------------------------------
 * Reading.
 * ------------------------------------------------------------------------- */

/* Position of a well-known channel name in the output order, or -1. */
static int32_t mrgi_exr_known_rank(const char* name)
{
  static const char* const known[5] = { "R", "G", "B", "A", "Y" };
  for (int32_t i = 0; i < 5; ++i)
  {
    if (strcmp(name, known[i]) == 0)
    {
      return i;
    }
  }
  return -1;
}

typedef struct mrgi_exr_reader
{
  mrgi_exr_stream stream;
  exr_context_t context;
  exr_decode_pipeline_t decoder;
  int decoder_ready;
} mrgi_exr_reader;

static void mrgi_exr_reader_release(mrgi_exr_reader* r)
{
  if (r->decoder_ready)
  {
    exr_decoding_destroy(r->context, &r->decoder);
    r->decoder_ready = 0;
  }
  if (r->context)
  {
    exr_finish(&r->context);
    r->context = NULL;
  }
  if (r->stream.fd >= 0)
  {
    close(r->stream.fd);
    r->stream.fd = -1;
  }
}

/* Open the file, check it is a regular file that starts like an EXR. */
static mrgi_status mrgi_exr_open_for_read(mrgi_exr_reader* r, const char* path, mrgi_error* err)
{
  r->stream.fd = open(path, O_RDONLY | O_CLOEXEC);
  if (r->stream.fd < 0)
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
  }
  struct stat info;
  if (fstat(r->stream.fd, &info) != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot stat '%s': %s", path, strerror(errno));
  }
  if (!S_ISREG(info.st_mode))
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "'%s' is not a regular file", path);
  }
  r->stream.size = (int64_t)info.st_size;
  static const uint8_t magic[4] = { 0x76, 0x2f, 0x31, 0x01 };
  uint8_t head[4] = { 0, 0, 0, 0 };
  const ssize_t n = r->stream.size >= 4 ? pread(r->stream.fd, head, sizeof(head), 0) : 0;
  if (n != (ssize_t)sizeof(head) || memcmp(head, magic, sizeof(magic)) != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
                          "'%s' is not an OpenEXR file (bad magic number, %lld bytes)", path,
                          (long long)r->stream.size);
  }
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = mrgi_exr_on_error;
  init.user_data = &r->stream;
  init.read_fn = mrgi_exr_stream_read;
  init.size_fn = mrgi_exr_stream_size;
  /* A damaged file is an error, not something to guess around. */
  init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
  const exr_result_t rv = exr_start_read(&r->context, path, &init);
  if (rv != EXR_ERR_SUCCESS)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is not a readable OpenEXR file: %s", path,
                          mrgi_exr_reason(&r->stream, rv));
  }
  return MRGI_OK;
}

/* The most pixel data one byte of an OpenEXR file can decode to, with margin.
 * Deflate (ZIP, ZIPS, PXR24) expands at most 1032:1; RLE 64:1; B44 about
 * 11:1; DWAA/DWAB store one DC coefficient per 8x8 block, deflated, so a
 * flat image reaches about 64 x 1032 = 66048:1. 2^17 is above all of them. */
#define MRGI_EXR_MAX_EXPANSION ((int64_t)1 << 17)

/* Layout facts gathered from the header before any pixel is read. */
typedef struct mrgi_exr_layout
{
  int32_t min_x, min_y;
  int32_t width, height;
  int32_t channels;
  int32_t lines_per_chunk;
  const exr_attr_chlist_t* channel_list;
  int32_t output_of[MRGI_IMAGE_MAX_CHANNELS]; /* file channel index -> image channel */
} mrgi_exr_layout;

static mrgi_status mrgi_exr_read_layout(mrgi_exr_reader* r, const char* path,
                                        mrgi_exr_layout* layout, mrgi_error* err)
{
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  exr_result_t rv = exr_get_storage(r->context, 0, &storage);
  if (rv != EXR_ERR_SUCCESS)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': %s", path, mrgi_exr_reason(&r->stream, rv));
  }
  if (storage != EXR_STORAGE_SCANLINE)
  {
    const char* kind = storage == EXR_STORAGE_TILED           ? "tiled"
                       : storage == EXR_STORAGE_DEEP_SCANLINE ? "deep scanline"
                       : storage == EXR_STORAGE_DEEP_TILED    ? "deep tiled"
                                                              : "unknown-storage";
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                          "'%s' is a %s OpenEXR file; only flat scanline files are supported",
                          path, kind);
  }
  exr_attr_box2i_t window;
  rv = exr_get_data_window(r->context, 0, &window);
  if (rv != EXR_ERR_SUCCESS)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': no data window: %s", path,
                          mrgi_exr_reason(&r->stream, rv));
  }
  /* int64 so that a hostile window (min = INT32_MIN, max = INT32_MAX) cannot overflow. */
  const int64_t width = (int64_t)window.max.x - (int64_t)window.min.x + 1;
  const int64_t height = (int64_t)window.max.y - (int64_t)window.min.y + 1;
  if (width < 1 || height < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': data window (%d,%d)-(%d,%d) is empty",
                          path, window.min.x, window.min.y, window.max.x, window.max.y);
  }
  if (width > MRGI_IMAGE_MAX_DIMENSION || height > MRGI_IMAGE_MAX_DIMENSION)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                          "'%s': data window %lldx%lld exceeds the supported %d pixels per side",
                          path, (long long)width, (long long)height, MRGI_IMAGE_MAX_DIMENSION);
  }
  rv = exr_get_scanlines_per_chunk(r->context, 0, &layout->lines_per_chunk);
  if (rv != EXR_ERR_SUCCESS || layout->lines_per_chunk < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': bad scanlines per chunk: %s", path,
                          mrgi_exr_reason(&r->stream, rv));
  }
  /* Each chunk costs at least 8 bytes of offset table and 8 of chunk header;
   * a window needing more than the file holds is a corrupt header, and
   * rejecting it here avoids allocating an image for it. */
  const int64_t chunk_count = (height + layout->lines_per_chunk - 1) / layout->lines_per_chunk;
  if (r->stream.size >= 0 && chunk_count > r->stream.size / 16)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
                          "'%s': data window %lldx%lld needs %lld chunks, more than a file of "
                          "%lld bytes can hold (corrupt or truncated header)",
                          path, (long long)width, (long long)height, (long long)chunk_count,
                          (long long)r->stream.size);
  }
  const exr_attr_chlist_t* list = NULL;
  rv = exr_get_channels(r->context, 0, &list);
  if (rv != EXR_ERR_SUCCESS || !list)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': no channel list: %s", path,
                          mrgi_exr_reason(&r->stream, rv));
  }
  if (list->num_channels < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' has no channels", path);
  }
  if (list->num_channels > MRGI_IMAGE_MAX_CHANNELS)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED, "'%s' has %d channels; at most %d are supported",
                          path, list->num_channels, MRGI_IMAGE_MAX_CHANNELS);
  }
  for (int32_t c = 0; c < list->num_channels; ++c)
  {
    const exr_attr_chlist_entry_t* entry = &list->entries[c];
    if (entry->x_sampling != 1 || entry->y_sampling != 1)
    {
      return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                            "'%s': channel '%s' is subsampled (%d x %d); only full-resolution "
                            "channels are supported",
                            path, entry->name.str, entry->x_sampling, entry->y_sampling);
    }
    if (entry->pixel_type != EXR_PIXEL_UINT && entry->pixel_type != EXR_PIXEL_HALF &&
        entry->pixel_type != EXR_PIXEL_FLOAT)
    {
      return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': channel '%s' has unknown pixel type %d",
                            path, entry->name.str, (int)entry->pixel_type);
    }
  }
  /* No OpenEXR codec expands its data more than MRGI_EXR_MAX_EXPANSION
   * times, so a header that declares more pixel data than that many times
   * the file size is corrupt (or the file truncated): refused here, before
   * the image is allocated (a 597-byte file declaring a 1048576 x 592 data
   * window asked for 7 GiB). */
  int64_t bytes_per_pixel = 0;
  for (int32_t c = 0; c < list->num_channels; ++c)
  {
    bytes_per_pixel += list->entries[c].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
  }
  /* width, height <= 2^20 and bytes_per_pixel <= 256: no overflow in int64. */
  const int64_t pixel_bytes = width * height * bytes_per_pixel;
  if (r->stream.size >= 0 && pixel_bytes / MRGI_EXR_MAX_EXPANSION > r->stream.size)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT,
                          "'%s': data window %lldx%lld of %d channels declares %lld bytes of "
                          "pixel data, more than a file of %lld bytes can hold (corrupt or "
                          "truncated header)",
                          path, (long long)width, (long long)height, list->num_channels,
                          (long long)pixel_bytes, (long long)r->stream.size);
  }
  /* Known names first (R, G, B, A, Y), then the rest in file order. */
  int32_t next = 0;
  for (int32_t rank = 0; rank < 5; ++rank)
  {
    for (int32_t c = 0; c < list->num_channels; ++c)
    {
      if (mrgi_exr_known_rank(list->entries[c].name.str) == rank)
      {
        layout->output_of[c] = next++;
      }
    }
  }
  for (int32_t c = 0; c < list->num_channels; ++c)
  {
    if (mrgi_exr_known_rank(list->entries[c].name.str) < 0)
    {
      layout->output_of[c] = next++;
    }
  }
  layout->min_x = window.min.x;
  layout->min_y = window.min.y;
  layout->width = (int32_t)width;
  layout->height = (int32_t)height;
  layout->channels = list->num_channels;
  layout->channel_list = list;
  return MRGI_OK;
}

/* Decode every chunk of the data window into `img` (already allocated).
 *
 * Each channel is decoded into its own plane of a one-chunk scratch buffer and
 * then scattered into the interleaved image. Decoding straight into the
 * interleaved image is not safe with OpenEXR 3.1: its specialised unpackers for
 * four HALF channels ignore the per-channel destinations and write the
 * channels in file order (A, B, G, R), which swapped R and A in our tests. */
static mrgi_status mrgi_exr_read_pixels(mrgi_exr_reader* r, const mrgi_exr_layout* layout,
                                        mrgi_image* img, const char* path, mrgi_error* err)
{
  const size_t plane_values = (size_t)img->width * (size_t)layout->lines_per_chunk;
  const int32_t line_stride = (int32_t)((size_t)img->width * sizeof(float));
  if ((size_t)line_stride != (size_t)img->width * sizeof(float))
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                          "'%s': a %d-pixel row is too long for the OpenEXR decoder", path,
                          img->width);
  }
  float* planes = (float*)malloc(plane_values * (size_t)img->channels * sizeof(float));
  if (!planes)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "'%s': cannot allocate a %d-line decode buffer", path,
                          (int)layout->lines_per_chunk);
  }
  mrgi_status status = MRGI_OK;
  for (int64_t row = 0; row < layout->height && status == MRGI_OK; row += layout->lines_per_chunk)
  {
    const int32_t y = (int32_t)(layout->min_y + row);
    exr_chunk_info_t chunk;
    exr_result_t rv = exr_read_scanline_chunk_info(r->context, 0, y, &chunk);
    if (rv == EXR_ERR_SUCCESS)
    {
      rv = r->decoder_ready ? exr_decoding_update(r->context, 0, &chunk, &r->decoder)
                            : exr_decoding_initialize(r->context, 0, &chunk, &r->decoder);
    }
    if (rv != EXR_ERR_SUCCESS)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is corrupt or truncated at scanline %d: %s",
                              path, y, mrgi_exr_reason(&r->stream, rv));
      break;
    }
    const int first_chunk = !r->decoder_ready;
    r->decoder_ready = 1;
    const int64_t first_row = (int64_t)chunk.start_y - layout->min_y;
    if (chunk.start_x != layout->min_x || chunk.width != layout->width || first_row < 0 ||
        chunk.height < 1 || chunk.height > layout->lines_per_chunk ||
        first_row + chunk.height > layout->height || r->decoder.channel_count != layout->channels)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
                              "'%s': chunk for scanline %d does not match the data window", path, y);
      break;
    }
    for (int16_t c = 0; c < r->decoder.channel_count; ++c)
    {
      exr_coding_channel_info_t* channel = &r->decoder.channels[c];
      if (channel->height != chunk.height || channel->width != chunk.width)
      {
        status = mrgi_error_set(err, MRGI_ERR_FORMAT,
                                "'%s': channel '%s' has an unexpected size in the chunk at "
                                "scanline %d",
                                path, channel->channel_name, y);
        break;
      }
      /* The library converts half and uint to float on the way. */
      channel->decode_to_ptr = (uint8_t*)(planes + (size_t)c * plane_values);
      channel->user_pixel_stride = (int32_t)sizeof(float);
      channel->user_line_stride = line_stride;
      channel->user_bytes_per_element = (int16_t)sizeof(float);
      channel->user_data_type = (uint16_t)EXR_PIXEL_FLOAT;
    }
    if (status != MRGI_OK)
    {
      break;
    }
    if (first_chunk)
    {
      rv = exr_decoding_choose_default_routines(r->context, 0, &r->decoder);
    }
    if (rv == EXR_ERR_SUCCESS)
    {
      rv = exr_decoding_run(r->context, 0, &r->decoder);
    }
    if (rv != EXR_ERR_SUCCESS)
    {
      status = mrgi_error_set(err, MRGI_ERR_FORMAT,
                              "'%s' is corrupt or truncated: cannot decode scanline %d: %s", path,
                              y, mrgi_exr_reason(&r->stream, rv));
      break;
    }
    for (int16_t c = 0; c < r->decoder.channel_count; ++c)
    {
      const float* plane = planes + (size_t)c * plane_values;
      const int32_t out_channel = layout->output_of[c];
      for (int32_t line = 0; line < chunk.height; ++line)
      {
        float* dst = mrgi_image_at(img, 0, (int32_t)first_row + line) + out_channel;
        const float* src = plane + (size_t)line * (size_t)img->width;
        for (int32_t x = 0; x < img->width; ++x)
        {
          dst[(size_t)x * (size_t)img->channels] = src[x];
        }
      }
    }
  }
  free(planes);
  return status;
}

mrgi_status mrgi_exr_read_channels(const char* path, mrgi_image* out,
                                   char names[][MRGI_EXR_CHANNEL_NAME_SIZE], int32_t max_names,
                                   mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output image pointer is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (!path || path[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "EXR input path is NULL or empty");
  }
  if (max_names < 0 || (max_names > 0 && !names))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "reading '%s': %d channel-name slots requested but names is %s", path,
                          max_names, names ? "given" : "NULL");
  }
  mrgi_exr_reader reader;
  memset(&reader, 0, sizeof(reader));
  reader.stream.fd = -1;
  reader.stream.size = -1;

  mrgi_exr_layout layout;
  memset(&layout, 0, sizeof(layout));
  mrgi_image img;
  memset(&img, 0, sizeof(img));

  mrgi_status status = mrgi_exr_open_for_read(&reader, path, err);
  if (status == MRGI_OK)
  {
    status = mrgi_exr_read_layout(&reader, path, &layout, err);
  }
  if (status == MRGI_OK && names)
  {
    for (int32_t c = 0; c < layout.channels; ++c)
    {
      const int32_t slot = layout.output_of[c];
      const char* name = layout.channel_list->entries[c].name.str;
      if (slot >= max_names)
      {
        continue;
      }
      if (strlen(name) >= MRGI_EXR_CHANNEL_NAME_SIZE)
      {
        status = mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                                "'%s': channel name '%.40s...' is longer than %d characters",
                                path, name, MRGI_EXR_CHANNEL_NAME_SIZE - 1);
        break;
      }
    }
  }
  if (status == MRGI_OK)
  {
    status = mrgi_image_create(&img, layout.width, layout.height, layout.channels, err);
    if (status != MRGI_OK)
    {
      mrgi_error_prefix(err, "reading '%s': ", path);
    }
  }
  if (status == MRGI_OK)
  {
    status = mrgi_exr_read_pixels(&reader, &layout, &img, path, err);
  }
  if (status == MRGI_OK && names)
  {
    for (int32_t c = 0; c < layout.channels; ++c)
    {
      const int32_t slot = layout.output_of[c];
      if (slot < max_names)
      {
        /* Length checked above, so this copy keeps the whole name. */
        const char* name = layout.channel_list->entries[c].name.str;
        const size_t length = strlen(name);
        memcpy(names[slot], name, length + 1);
      }
    }
  }
  /* The channel list belongs to the context: done with it before release. */
  mrgi_exr_reader_release(&reader);
  if (status != MRGI_OK)
  {
    mrgi_image_destroy(&img);
    return status;
  }
  *out = img;
  return MRGI_OK;
}

mrgi_status mrgi_exr_read(const char* path, mrgi_image* out, mrgi_error* err)
{
  return mrgi_exr_read_channels(path, out, NULL, 0, err);
}
