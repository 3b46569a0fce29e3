#include "mrgi_png.h"

#include "mrgi_atomic_file.h"

#include <png.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* libpng reports errors by calling our handler, which must not return:
 * it records the message and longjmps back to the setjmp in the function
 * that drives libpng. Every resource is kept in a struct owned by the
 * caller of that function, so cleanup after a longjmp sees current values
 * (only automatic variables of the setjmp caller are unreliable). */

typedef struct mrgi_png_message
{
  char text[256];    /* the error that stopped libpng */
  char warning[192]; /* the first warning before it, "" if none */
} mrgi_png_message;

static void mrgi_png_on_error(png_structp png, png_const_charp msg)
{
  mrgi_png_message* message = (mrgi_png_message*)png_get_error_ptr(png);
  if (message)
  {
    /* libpng often explains a fatal error in a warning just before it
     * ("Image width exceeds user limit in IHDR", then "Invalid IHDR data"). */
    const char* text = msg ? msg : "unknown libpng error";
    if (message->warning[0])
    {
      snprintf(message->text, sizeof(message->text), "%s (%s)", text, message->warning);
    }
    else
    {
      snprintf(message->text, sizeof(message->text), "%s", text);
    }
  }
  png_longjmp(png, 1);
}

static void mrgi_png_on_warning(png_structp png, png_const_charp msg)
{
  /* Warnings are kept, not printed: a warning alone (e.g. a bad CRC in an
   * ancillary chunk that libpng then skips) does not affect the pixels. */
  mrgi_png_message* message = (mrgi_png_message*)png_get_error_ptr(png);
  if (message && msg && message->warning[0] == '\0')
  {
    snprintf(message->warning, sizeof(message->warning), "%s", msg);
  }
}

/* The most a deflate stream can expand (bytes out per byte in, rounded up). */
#define MRGI_PNG_MAX_EXPANSION ((size_t)1032)

static int mrgi_png_mul_size(size_t a, size_t b, size_t* out)
{
  if (a != 0 && b > SIZE_MAX / a)
  {
    return 0;
  }
  *out = a * b;
  return 1;
}

/* ---------------------------------------------------------------------------
 * Writing.
 * ------------------------------------------------------------------------- */

typedef struct mrgi_png_writer
{
  FILE* file;
  png_structp png;
  png_infop info;
  mrgi_png_message message;
} mrgi_png_writer;

/* Drives libpng; returns 0 on success, 1 after a libpng error. */
static int mrgi_png_encode(mrgi_png_writer* w, const uint8_t* pixels, int32_t width,
                           int32_t height, int32_t channels)
{
  if (setjmp(png_jmpbuf(w->png)))
  {
    return 1;
  }
  static const int color_types[5] = { 0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                      PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA };
  png_init_io(w->png, w->file);
  png_set_IHDR(w->png, w->info, (png_uint_32)width, (png_uint_32)height, 8,
               color_types[channels], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(w->png, w->info);
  const size_t row_bytes = (size_t)width * (size_t)channels;
  /* Row by row: libpng copies each row, so no row-pointer table is needed. */
  for (int32_t y = 0; y < height; ++y)
  {
    png_write_row(w->png, (png_const_bytep)(pixels + (size_t)y * row_bytes));
  }
  png_write_end(w->png, NULL);
  return 0;
}

mrgi_status mrgi_png_write_rgba8(const char* path, const uint8_t* pixels, int32_t width,
                                 int32_t height, int32_t channels, mrgi_error* err)
{
  if (!path || path[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PNG output path is NULL or empty");
  }
  if (!pixels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "writing '%s': pixel pointer is NULL",
                          path);
  }
  if (width < 1 || width > MRGI_IMAGE_MAX_DIMENSION || height < 1 ||
      height > MRGI_IMAGE_MAX_DIMENSION)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "writing '%s': size %dx%d is outside [1, %d] per side", path, width,
                          height, MRGI_IMAGE_MAX_DIMENSION);
  }
  if (channels < 1 || channels > 4)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "writing '%s': channel count %d is outside [1, 4]", path, channels);
  }
  char temp_path[MRGI_ATOMIC_FILE_PATH_MAX];
  mrgi_status status = mrgi_atomic_file_begin(path, temp_path, sizeof(temp_path), err);
  if (status != MRGI_OK)
  {
    return status;
  }
  mrgi_png_writer writer;
  memset(&writer, 0, sizeof(writer));
  writer.file = fopen(temp_path, "wb");
  if (!writer.file)
  {
    status = mrgi_error_set(err, MRGI_ERR_IO, "writing '%s': cannot open '%s': %s", path,
                            temp_path, strerror(errno));
  }
  if (status == MRGI_OK)
  {
    writer.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &writer.message,
                                         mrgi_png_on_error, mrgi_png_on_warning);
    writer.info = writer.png ? png_create_info_struct(writer.png) : NULL;
    if (!writer.png || !writer.info)
    {
      status = mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                              "writing '%s': cannot create the libpng writer", path);
    }
  }
  if (status == MRGI_OK && mrgi_png_encode(&writer, pixels, width, height, channels) != 0)
  {
    status = mrgi_error_set(err, MRGI_ERR_IO, "writing '%s': %s", path, writer.message.text);
  }
  if (writer.png)
  {
    png_destroy_write_struct(&writer.png, writer.info ? &writer.info : NULL);
  }
  if (writer.file)
  {
    /* fclose flushes: a full disk shows up here. */
    const int stream_failed = ferror(writer.file);
    const int close_failed = fclose(writer.file) != 0;
    if ((stream_failed || close_failed) && status == MRGI_OK)
    {
      status = mrgi_error_set(err, MRGI_ERR_IO, "writing '%s': %s", path, strerror(errno));
    }
  }
  if (status != MRGI_OK)
  {
    mrgi_atomic_file_abort(temp_path);
    return status;
  }
  return mrgi_atomic_file_commit(temp_path, path, err);
}

mrgi_status mrgi_png_write_image(const char* path, const mrgi_image* img, int srgb_encode,
                                 float exposure, mrgi_error* err)
{
  if (!path || path[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PNG output path is NULL or empty");
  }
  mrgi_status status = mrgi_image_validate(img, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "writing '%s': ", path);
    return status;
  }
  const size_t size = mrgi_image_value_count(img);
  uint8_t* bytes = (uint8_t*)malloc(size);
  if (!bytes)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "writing '%s': cannot allocate %zu bytes for 8-bit pixels", path, size);
  }
  status = mrgi_image_to_rgba8(img, bytes, size, srgb_encode, exposure, err);
  if (status != MRGI_OK)
  {
    mrgi_error_prefix(err, "writing '%s': ", path);
  }
  else
  {
    status = mrgi_png_write_rgba8(path, bytes, img->width, img->height, img->channels, err);
  }
  free(bytes);
  return status;
}

/* ---------------------------------------------------------------------------
 * Reading.
 * ------------------------------------------------------------------------- */

typedef struct mrgi_png_reader
{
  FILE* file;
  png_structp png;
  png_infop info;
  uint8_t* data;       /* decoded rows, height * row_bytes */
  png_bytep* rows;     /* row pointers into data */
  uint32_t width;
  uint32_t height;
  int32_t channels;    /* after expansion: 1..4 */
  int32_t bit_depth;   /* after expansion: 8 or 16 */
  size_t row_bytes;
  long file_size;      /* bytes in the file, -1 when it cannot be told (a pipe) */
  int out_of_memory;   /* set before a longjmp caused by a failed allocation */
  mrgi_png_message message;
} mrgi_png_reader;

/* Drives libpng; returns 0 on success, 1 after a libpng error. */
static int mrgi_png_decode(mrgi_png_reader* r)
{
  if (setjmp(png_jmpbuf(r->png)))
  {
    return 1;
  }
  png_init_io(r->png, r->file);
  png_set_sig_bytes(r->png, 8);
  /* Refuse absurd headers before libpng sizes anything from them. */
  png_set_user_limits(r->png, MRGI_IMAGE_MAX_DIMENSION, MRGI_IMAGE_MAX_DIMENSION);
  png_read_info(r->png, r->info);

  /* Deflate expands at most 1032:1 (a 258-byte match in two bits), so a file
   * of N bytes holds at most about 1032 N bytes of rows as stored (before
   * any expansion). A header that declares more is corrupt or the file is
   * truncated: refuse it before allocating rows for it (an 88-byte file
   * declaring 131072 x 196608 16-bit RGB pixels asked for 144 GiB). */
  const size_t stored_row_bytes = png_get_rowbytes(r->png, r->info);
  const uint32_t declared_height = png_get_image_height(r->png, r->info);
  if (r->file_size >= 0 && stored_row_bytes > 0 &&
    (size_t)declared_height >
      (MRGI_PNG_MAX_EXPANSION * ((size_t)r->file_size + 1)) / stored_row_bytes)
  {
    png_error(r->png, "the header declares more pixel data than the file can hold");
  }

  const int color_type = png_get_color_type(r->png, r->info);
  const int depth = png_get_bit_depth(r->png, r->info);
  if (color_type == PNG_COLOR_TYPE_PALETTE)
  {
    png_set_palette_to_rgb(r->png);
  }
  if (color_type == PNG_COLOR_TYPE_GRAY && depth < 8)
  {
    png_set_expand_gray_1_2_4_to_8(r->png);
  }
  if (png_get_valid(r->png, r->info, PNG_INFO_tRNS))
  {
    png_set_tRNS_to_alpha(r->png);
  }
  (void)png_set_interlace_handling(r->png);
  png_read_update_info(r->png, r->info);

  r->width = png_get_image_width(r->png, r->info);
  r->height = png_get_image_height(r->png, r->info);
  r->channels = png_get_channels(r->png, r->info);
  r->bit_depth = png_get_bit_depth(r->png, r->info);
  r->row_bytes = png_get_rowbytes(r->png, r->info);
  if (r->channels < 1 || r->channels > 4 || (r->bit_depth != 8 && r->bit_depth != 16) ||
      r->row_bytes != (size_t)r->width * (size_t)r->channels * (size_t)(r->bit_depth / 8))
  {
    png_error(r->png, "unexpected pixel layout after expansion");
  }
  size_t data_size = 0;
  if (!mrgi_png_mul_size(r->row_bytes, r->height, &data_size))
  {
    png_error(r->png, "image byte size overflows");
  }
  r->data = (uint8_t*)malloc(data_size);
  r->rows = (png_bytep*)malloc(sizeof(png_bytep) * (size_t)r->height);
  if (!r->data || !r->rows)
  {
    r->out_of_memory = 1;
    png_error(r->png, "cannot allocate the decoded rows");
  }
  for (uint32_t y = 0; y < r->height; ++y)
  {
    r->rows[y] = r->data + (size_t)y * r->row_bytes;
  }
  png_read_image(r->png, r->rows);
  /* Reading up to IEND makes a file truncated after the pixel data fail too. */
  png_read_end(r->png, NULL);
  return 0;
}

static void mrgi_png_reader_release(mrgi_png_reader* r)
{
  if (r->png)
  {
    png_destroy_read_struct(&r->png, r->info ? &r->info : NULL, NULL);
  }
  if (r->file)
  {
    fclose(r->file);
    r->file = NULL;
  }
  free(r->rows);
  r->rows = NULL;
  free(r->data);
  r->data = NULL;
}

mrgi_status mrgi_png_read(const char* path, mrgi_image* out, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output image pointer is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (!path || path[0] == '\0')
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "PNG input path is NULL or empty");
  }
  mrgi_png_reader reader;
  memset(&reader, 0, sizeof(reader));
  mrgi_status status = MRGI_OK;
  reader.file = fopen(path, "rb");
  if (!reader.file)
  {
    return mrgi_error_set(err, MRGI_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
  }
  uint8_t signature[8];
  const size_t got = fread(signature, 1, sizeof(signature), reader.file);
  if (got != sizeof(signature) || png_sig_cmp(signature, 0, sizeof(signature)) != 0)
  {
    status = ferror(reader.file)
               ? mrgi_error_set(err, MRGI_ERR_IO, "cannot read '%s': %s", path, strerror(errno))
               : mrgi_error_set(err, MRGI_ERR_FORMAT, "'%s' is not a PNG file (bad signature)",
                                path);
  }
  reader.file_size = -1;
  if (status == MRGI_OK && fseek(reader.file, 0, SEEK_END) == 0)
  {
    reader.file_size = ftell(reader.file);
    if (fseek(reader.file, (long)sizeof(signature), SEEK_SET) != 0)
    {
      status = mrgi_error_set(err, MRGI_ERR_IO, "cannot seek in '%s': %s", path, strerror(errno));
    }
  }
  if (status == MRGI_OK)
  {
    reader.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &reader.message,
                                        mrgi_png_on_error, mrgi_png_on_warning);
    reader.info = reader.png ? png_create_info_struct(reader.png) : NULL;
    if (!reader.png || !reader.info)
    {
      status = mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                              "reading '%s': cannot create the libpng reader", path);
    }
  }
  if (status == MRGI_OK && mrgi_png_decode(&reader) != 0)
  {
    status = reader.out_of_memory
               ? mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY, "reading '%s': %s", path,
                                reader.message.text)
               : mrgi_error_set(err, MRGI_ERR_FORMAT,
                                "'%s' is not a valid PNG file (corrupt or truncated): %s", path,
                                reader.message.text);
  }
  mrgi_image img;
  memset(&img, 0, sizeof(img));
  if (status == MRGI_OK)
  {
    status = mrgi_image_create(&img, reader.width, reader.height, reader.channels, err);
    if (status != MRGI_OK)
    {
      mrgi_error_prefix(err, "reading '%s': ", path);
    }
  }
  if (status == MRGI_OK)
  {
    const size_t values_per_row = (size_t)reader.width * (size_t)reader.channels;
    for (uint32_t y = 0; y < reader.height; ++y)
    {
      const uint8_t* src = reader.rows[y];
      float* dst = mrgi_image_at(&img, 0, (int32_t)y);
      if (reader.bit_depth == 16)
      {
        for (size_t i = 0; i < values_per_row; ++i)
        {
          /* PNG stores 16-bit samples big-endian. */
          const uint32_t v = ((uint32_t)src[2 * i] << 8) | (uint32_t)src[2 * i + 1];
          dst[i] = (float)v / 65535.0f;
        }
      }
      else
      {
        for (size_t i = 0; i < values_per_row; ++i)
        {
          dst[i] = (float)src[i] / 255.0f;
        }
      }
    }
  }
  mrgi_png_reader_release(&reader);
  if (status != MRGI_OK)
  {
    mrgi_image_destroy(&img);
    return status;
  }
  *out = img;
  return MRGI_OK;
}
