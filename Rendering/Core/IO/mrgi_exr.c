/* OpenEXR reading (mrgi_exr.h) and the stream shared with mrgi_exr_write.c
 * (mrgi_exr_stream.h). pread/fstat are POSIX; the core builds with -std=c11. */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_exr.h"

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
 * Stream shared with OpenEXRCore (mrgi_exr_stream.h says why).
 * ------------------------------------------------------------------------- */

void mrgi_exr_on_error(exr_const_context_t ctxt, exr_result_t code, const char* msg)
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

int64_t mrgi_exr_stream_read(exr_const_context_t ctxt, void* user_data, void* buffer, uint64_t size,
  uint64_t offset, exr_stream_error_func_ptr_t error_cb)
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

int64_t mrgi_exr_stream_size(exr_const_context_t ctxt, void* user_data)
{
  (void)ctxt;
  return ((const mrgi_exr_stream*)user_data)->size;
}

int64_t mrgi_exr_stream_write(exr_const_context_t ctxt, void* user_data, const void* buffer,
  uint64_t size, uint64_t offset, exr_stream_error_func_ptr_t error_cb)
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

const char* mrgi_exr_reason(const mrgi_exr_stream* stream, exr_result_t code)
{
  return stream->message[0] ? stream->message : exr_get_default_error_message(code);
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

static mrgi_status mrgi_exr_read_layout(
  mrgi_exr_reader* r, const char* path, mrgi_exr_layout* layout, mrgi_error* err)
{
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  exr_result_t rv = exr_get_storage(r->context, 0, &storage);
  if (rv != EXR_ERR_SUCCESS)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': %s", path, mrgi_exr_reason(&r->stream, rv));
  }
  if (storage != EXR_STORAGE_SCANLINE)
  {
    const char* kind = storage == EXR_STORAGE_TILED ? "tiled"
      : storage == EXR_STORAGE_DEEP_SCANLINE        ? "deep scanline"
      : storage == EXR_STORAGE_DEEP_TILED           ? "deep tiled"
                                                    : "unknown-storage";
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
      "'%s' is a %s OpenEXR file; only flat scanline files are supported", path, kind);
  }
  exr_attr_box2i_t window;
  rv = exr_get_data_window(r->context, 0, &window);
  if (rv != EXR_ERR_SUCCESS)
  {
    return mrgi_error_set(
      err, MRGI_ERR_FORMAT, "'%s': no data window: %s", path, mrgi_exr_reason(&r->stream, rv));
  }
  /* int64 so that a hostile window (min = INT32_MIN, max = INT32_MAX) cannot overflow. */
  const int64_t width = (int64_t)window.max.x - (int64_t)window.min.x + 1;
  const int64_t height = (int64_t)window.max.y - (int64_t)window.min.y + 1;
  if (width < 1 || height < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s': data window (%d,%d)-(%d,%d) is empty", path,
      window.min.x, window.min.y, window.max.x, window.max.y);
  }
  if (width > MRGI_IMAGE_MAX_DIMENSION || height > MRGI_IMAGE_MAX_DIMENSION)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
      "'%s': data window %lldx%lld exceeds the supported %d pixels per side", path,
      (long long)width, (long long)height, MRGI_IMAGE_MAX_DIMENSION);
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
      path, (long long)width, (long long)height, (long long)chunk_count, (long long)r->stream.size);
  }
  const exr_attr_chlist_t* list = NULL;
  rv = exr_get_channels(r->context, 0, &list);
  if (rv != EXR_ERR_SUCCESS || !list)
  {
    return mrgi_error_set(
      err, MRGI_ERR_FORMAT, "'%s': no channel list: %s", path, mrgi_exr_reason(&r->stream, rv));
  }
  if (list->num_channels < 1)
  {
    return mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' has no channels", path);
  }
  if (list->num_channels > MRGI_IMAGE_MAX_CHANNELS)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
      "'%s' has %d channels; at most %d are supported", path, list->num_channels,
      MRGI_IMAGE_MAX_CHANNELS);
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
      path, (long long)width, (long long)height, list->num_channels, (long long)pixel_bytes,
      (long long)r->stream.size);
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
      "'%s': a %d-pixel row is too long for the OpenEXR decoder", path, img->width);
  }
  float* planes = (float*)malloc(plane_values * (size_t)img->channels * sizeof(float));
  if (!planes)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
      "'%s': cannot allocate a %d-line decode buffer", path, (int)layout->lines_per_chunk);
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
      status =
        mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is corrupt or truncated at scanline %d: %s",
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
        "'%s' is corrupt or truncated: cannot decode scanline %d: %s", path, y,
        mrgi_exr_reason(&r->stream, rv));
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
  char names[][MRGI_EXR_CHANNEL_NAME_SIZE], int32_t max_names, mrgi_error* err)
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
      "reading '%s': %d channel-name slots requested but names is %s", path, max_names,
      names ? "given" : "NULL");
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
          "'%s': channel name '%.40s...' is longer than %d characters", path, name,
          MRGI_EXR_CHANNEL_NAME_SIZE - 1);
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
