/* Tests of mrgi_png: 8-bit round trips, float conversion, 16-bit and palette
 * reading (from PNG files built by hand here), atomic writes, and rejection of
 * missing, foreign, truncated, corrupt and oversized files. */
#define _POSIX_C_SOURCE 200809L
#include "mrgi_png.h"
#include "mrgi_test.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- file helpers -------------------------------------------------------- */

/* ---- a minimal PNG encoder (stored deflate blocks), for files our writer
 *      does not produce: 16-bit, palette, hostile headers --------------------- */

typedef struct byte_buffer
{
  uint8_t data[4096];
  size_t size;
} byte_buffer;

static void put_bytes(byte_buffer* b, const void* bytes, size_t n)
{
  MRGI_CHECK(b->size + n <= sizeof(b->data));
  memcpy(b->data + b->size, bytes, n);
  b->size += n;
}

static void put_be32(byte_buffer* b, uint32_t v)
{
  const uint8_t bytes[4] = { (uint8_t)(v >> 24), (uint8_t)(v >> 16), (uint8_t)(v >> 8),
                             (uint8_t)v };
  put_bytes(b, bytes, 4);
}

static uint32_t crc32_of(const uint8_t* p, size_t n)
{
  uint32_t crc = 0xffffffffu;
  for (size_t i = 0; i < n; ++i)
  {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k)
    {
      crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
  }
  return crc ^ 0xffffffffu;
}

static void put_chunk(byte_buffer* b, const char type[4], const uint8_t* payload, size_t n)
{
  put_be32(b, (uint32_t)n);
  const size_t start = b->size;
  put_bytes(b, type, 4);
  if (n)
  {
    put_bytes(b, payload, n);
  }
  put_be32(b, crc32_of(b->data + start, n + 4));
}

/* zlib stream of one stored (uncompressed) deflate block. */
static void zlib_stored(const uint8_t* raw, size_t n, byte_buffer* out)
{
  MRGI_CHECK(n <= 65535);
  const uint8_t header[2] = { 0x78, 0x01 };
  put_bytes(out, header, 2);
  const uint8_t block[5] = { 0x01, (uint8_t)(n & 0xff), (uint8_t)(n >> 8),
                             (uint8_t)(~n & 0xff), (uint8_t)((~n >> 8) & 0xff) };
  put_bytes(out, block, 5);
  put_bytes(out, raw, n);
  uint32_t a = 1, s = 0;
  for (size_t i = 0; i < n; ++i)
  {
    a = (a + raw[i]) % 65521u;
    s = (s + a) % 65521u;
  }
  put_be32(out, (s << 16) | a);
}

/* PNG with the given header and raw scanlines (each starting with filter byte 0). */
static void build_png(byte_buffer* png, uint32_t width, uint32_t height, uint8_t depth,
                      uint8_t color_type, const uint8_t* raw, size_t raw_size,
                      const uint8_t* palette, size_t palette_size, const uint8_t* trns,
                      size_t trns_size)
{
  static const uint8_t signature[8] = { 137, 80, 78, 71, 13, 10, 26, 10 };
  png->size = 0;
  put_bytes(png, signature, 8);
  byte_buffer ihdr = { { 0 }, 0 };
  put_be32(&ihdr, width);
  put_be32(&ihdr, height);
  const uint8_t rest[5] = { depth, color_type, 0, 0, 0 };
  put_bytes(&ihdr, rest, 5);
  put_chunk(png, "IHDR", ihdr.data, ihdr.size);
  if (palette)
  {
    put_chunk(png, "PLTE", palette, palette_size);
  }
  if (trns)
  {
    put_chunk(png, "tRNS", trns, trns_size);
  }
  byte_buffer idat = { { 0 }, 0 };
  zlib_stored(raw, raw_size, &idat);
  put_chunk(png, "IDAT", idat.data, idat.size);
  put_chunk(png, "IEND", NULL, 0);
}

static void expect_read_fails(const char* path, mrgi_status expected, const char* fragment)
{
  mrgi_error err;
  mrgi_image img = { 3, 3, 3, (float*)&img }; /* garbage: must be zeroed */
  const mrgi_status s = mrgi_png_read(path, &img, &err);
  if (s != expected || !strstr(err.message, fragment))
  {
    fprintf(stderr, "reading '%s': got %s '%s', expected %s with '%s'\n", path,
            mrgi_status_name(s), err.message, mrgi_status_name(expected), fragment);
  }
  MRGI_CHECK(s == expected);
  MRGI_CHECK(strstr(err.message, fragment));
  MRGI_CHECK(img.pixels == NULL && img.width == 0);
}

/* ---- round trips --------------------------------------------------------- */

static void test_rgba8_round_trip_all_channel_counts(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_round_trip.png", path, sizeof(path));
  const int32_t w = 7, h = 5;
  uint8_t pixels[7 * 5 * 4];
  for (size_t i = 0; i < sizeof(pixels); ++i)
  {
    pixels[i] = (uint8_t)(i * 37u + 11u);
  }
  for (int32_t channels = 1; channels <= 4; ++channels)
  {
    MRGI_CHECK(mrgi_png_write_rgba8(path, pixels, w, h, channels, NULL) == MRGI_OK);
    mrgi_image img;
    MRGI_CHECK(mrgi_png_read(path, &img, NULL) == MRGI_OK);
    MRGI_CHECK(img.width == w && img.height == h && img.channels == channels);
    const size_t n = (size_t)(w * h * channels);
    for (size_t i = 0; i < n; ++i)
    {
      MRGI_CHECK(img.pixels[i] == (float)pixels[i] / 255.0f);
    }
    /* Row 0 = top: pixel (2, 4) of the file is pixel (2, 4) of the buffer. */
    MRGI_CHECK(mrgi_image_at(&img, 2, 4)[0] == (float)pixels[(4 * w + 2) * channels] / 255.0f);
    mrgi_image_destroy(&img);
  }
}

static void test_write_image_converts_floats(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_float.png", path, sizeof(path));
  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 2, 1, 4, NULL) == MRGI_OK);
  const float values[8] = { 0.5f, NAN, 3.0f, 0.5f, 0.25f, -1.0f, 0.0f, 1.0f };
  memcpy(img.pixels, values, sizeof(values));
  MRGI_CHECK(mrgi_png_write_image(path, &img, 0, 1.0f, NULL) == MRGI_OK);
  mrgi_image back;
  MRGI_CHECK(mrgi_png_read(path, &back, NULL) == MRGI_OK);
  const int expected[8] = { 128, 0, 255, 128, 64, 0, 0, 255 };
  for (int i = 0; i < 8; ++i)
  {
    MRGI_CHECK(back.pixels[i] == (float)expected[i] / 255.0f);
  }
  mrgi_image_destroy(&back);

  /* sRGB plus exposure 2: 0.25 -> 0.5 -> sRGB 188; alpha untouched. */
  MRGI_CHECK(mrgi_png_write_image(path, &img, 1, 2.0f, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_png_read(path, &back, NULL) == MRGI_OK);
  MRGI_CHECK(back.pixels[4] == 188.0f / 255.0f);
  MRGI_CHECK(back.pixels[3] == 128.0f / 255.0f);
  mrgi_image_destroy(&back);
  mrgi_image_destroy(&img);
}

/* ---- files made by hand ------------------------------------------------------ */

static void test_read_16bit_gray_alpha(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_16bit.png", path, sizeof(path));
  /* 2x2 gray+alpha, 16 bit big-endian: each row = filter byte + 2 px * 4 bytes. */
  const uint8_t raw[2 * 9] = { 0, 0x00, 0x00, 0xff, 0xff, 0x80, 0x00, 0x12, 0x34,
                               0, 0xff, 0xff, 0x00, 0x01, 0x00, 0x01, 0xab, 0xcd };
  byte_buffer png;
  build_png(&png, 2, 2, 16, 4, raw, sizeof(raw), NULL, 0, NULL, 0);
  mrgi_test_write_file(path, png.data, png.size);
  mrgi_image img;
  mrgi_error err;
  MRGI_CHECK(mrgi_png_read(path, &img, &err) == MRGI_OK);
  MRGI_CHECK(img.width == 2 && img.height == 2 && img.channels == 2);
  const uint32_t codes[8] = { 0x0000, 0xffff, 0x8000, 0x1234, 0xffff, 0x0001, 0x0001, 0xabcd };
  for (int i = 0; i < 8; ++i)
  {
    MRGI_CHECK(img.pixels[i] == (float)codes[i] / 65535.0f);
  }
  mrgi_image_destroy(&img);
}

static void test_read_palette_with_transparency(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_palette.png", path, sizeof(path));
  const uint8_t palette[6] = { 255, 0, 0, 0, 0, 255 }; /* red, blue */
  const uint8_t trns[1] = { 51 };                      /* red is 20% opaque */
  const uint8_t raw[2] = { 0, 0x40 };                  /* 2x1 at 1 bit: 0, 1 */
  byte_buffer png;
  build_png(&png, 2, 1, 1, 3, raw, sizeof(raw), palette, sizeof(palette), trns, sizeof(trns));
  mrgi_test_write_file(path, png.data, png.size);
  mrgi_image img;
  MRGI_CHECK(mrgi_png_read(path, &img, NULL) == MRGI_OK);
  MRGI_CHECK(img.width == 2 && img.height == 1 && img.channels == 4);
  const float expected[8] = { 1.0f, 0.0f, 0.0f, 0.2f, 0.0f, 0.0f, 1.0f, 1.0f };
  for (int i = 0; i < 8; ++i)
  {
    MRGI_CHECK(img.pixels[i] == expected[i]);
  }
  mrgi_image_destroy(&img);
}

static void test_read_rejects_oversized_header(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_huge.png", path, sizeof(path));
  const uint8_t raw[2] = { 0, 0 };
  byte_buffer png;
  build_png(&png, 1u << 30, 1, 8, 0, raw, sizeof(raw), NULL, 0, NULL, 0);
  mrgi_test_write_file(path, png.data, png.size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "width exceeds user limit");
}

/* A header whose sides pass the limit but whose rows no file this small can
 * hold (found by fuzz.PNG: the reader allocated 144 GiB for 88 bytes). */
static void test_read_rejects_more_rows_than_the_file_holds(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_more_rows.png", path, sizeof(path));
  const uint8_t raw[7] = { 0, 1, 2, 3, 4, 5, 6 };
  byte_buffer png;
  /* 131072 x 196608 16-bit RGB: 144 GiB of rows declared, 7 bytes present. */
  build_png(&png, 1u << 17, 3u << 16, 16, 2, raw, sizeof(raw), NULL, 0, NULL, 0);
  mrgi_test_write_file(path, png.data, png.size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "more pixel data than the file can hold");
  /* The largest image a file can hold at all still gets to the pixel data:
   * rows of 1032 bytes per file byte are allowed, then found missing. */
  const uint32_t height = (uint32_t)(png.size * 1032u / 3u);
  build_png(&png, 1, height, 8, 2, raw, sizeof(raw), NULL, 0, NULL, 0);
  mrgi_test_write_file(path, png.data, png.size);
  mrgi_image img;
  mrgi_error err;
  MRGI_CHECK(mrgi_png_read(path, &img, &err) == MRGI_ERR_FORMAT);
  MRGI_CHECK(strstr(err.message, "more pixel data") == NULL);
  MRGI_CHECK(img.pixels == NULL);
}

/* ---- bad input on write -------------------------------------------------- */

static void test_write_rejects_bad_input(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_bad_write.png", path, sizeof(path));
  unlink(path);
  const uint8_t pixels[16] = { 0 };
  mrgi_error err;
  MRGI_CHECK(mrgi_png_write_rgba8(NULL, pixels, 2, 2, 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "path is NULL"));
  MRGI_CHECK(mrgi_png_write_rgba8(path, NULL, 2, 2, 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "pixel pointer is NULL"));
  MRGI_CHECK(mrgi_png_write_rgba8(path, pixels, 0, 2, 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "size 0x2"));
  MRGI_CHECK(mrgi_png_write_rgba8(path, pixels, 2, -1, 4, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "size 2x-1"));
  MRGI_CHECK(mrgi_png_write_rgba8(path, pixels, 2, 2, 5, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "channel count 5"));

  mrgi_image img;
  MRGI_CHECK(mrgi_image_create(&img, 2, 2, 5, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_png_write_image(path, &img, 0, 1.0f, &err) == MRGI_ERR_UNSUPPORTED);
  MRGI_CHECK(strstr(err.message, "the image has 5"));
  mrgi_image_destroy(&img);
  MRGI_CHECK(mrgi_image_create(&img, 2, 2, 3, NULL) == MRGI_OK);
  MRGI_CHECK(mrgi_png_write_image(path, &img, 0, NAN, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "exposure"));
  MRGI_CHECK(mrgi_png_write_image(path, NULL, 0, 1.0f, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "image pointer is NULL"));
  MRGI_CHECK(!mrgi_test_file_exists(path));
  mrgi_image_destroy(&img);
}

static void test_write_to_missing_directory_leaves_nothing(void)
{
  char dir[1024];
  char path[1024];
  mrgi_test_tmp_path("png_no_such_dir", dir, sizeof(dir));
  mrgi_test_tmp_path("png_no_such_dir/out.png", path, sizeof(path));
  rmdir(dir);
  const uint8_t pixels[4] = { 1, 2, 3, 4 };
  mrgi_error err;
  MRGI_CHECK(mrgi_png_write_rgba8(path, pixels, 1, 1, 4, &err) == MRGI_ERR_IO);
  MRGI_CHECK(strstr(err.message, "No such file or directory"));
  MRGI_CHECK(!mrgi_test_file_exists(path));
  MRGI_CHECK(!mrgi_test_file_exists(dir));
}

/* ---- bad input on read --------------------------------------------------- */

static void test_read_rejects_missing_and_foreign_files(void)
{
  char path[1024];
  mrgi_test_tmp_path("png_missing.png", path, sizeof(path));
  unlink(path);
  expect_read_fails(path, MRGI_ERR_IO, "No such file or directory");

  mrgi_test_tmp_path("png_text.png", path, sizeof(path));
  const char* text = "GIF89a pretending to be a PNG";
  mrgi_test_write_file(path, (const uint8_t*)text, strlen(text));
  expect_read_fails(path, MRGI_ERR_FORMAT, "not a PNG file");

  mrgi_test_tmp_path("png_empty.png", path, sizeof(path));
  mrgi_test_write_file(path, NULL, 0);
  expect_read_fails(path, MRGI_ERR_FORMAT, "not a PNG file");

  mrgi_test_tmp_path("", path, sizeof(path));
  expect_read_fails(path, MRGI_ERR_IO, "cannot read");

  mrgi_error err;
  mrgi_image img;
  MRGI_CHECK(mrgi_png_read(NULL, &img, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "path is NULL"));
  MRGI_CHECK(mrgi_png_read(path, NULL, &err) == MRGI_ERR_INVALID_ARGUMENT);
  MRGI_CHECK(strstr(err.message, "output image pointer is NULL"));
}

static void test_read_rejects_truncated_files(void)
{
  char source[1024];
  char path[1024];
  mrgi_test_tmp_path("png_truncate_source.png", source, sizeof(source));
  mrgi_test_tmp_path("png_truncated.png", path, sizeof(path));
  uint8_t pixels[9 * 6 * 3];
  for (size_t i = 0; i < sizeof(pixels); ++i)
  {
    pixels[i] = (uint8_t)(i * 101u);
  }
  MRGI_CHECK(mrgi_png_write_rgba8(source, pixels, 9, 6, 3, NULL) == MRGI_OK);
  size_t size = 0;
  uint8_t* data = mrgi_test_read_file(source, &size);

  mrgi_test_write_file(path, data, size / 2);
  expect_read_fails(path, MRGI_ERR_FORMAT, "corrupt or truncated");

  for (size_t length = 0; length < size; ++length)
  {
    mrgi_test_write_file(path, data, length);
    mrgi_error err;
    mrgi_image img;
    const mrgi_status s = mrgi_png_read(path, &img, &err);
    if (s == MRGI_OK)
    {
      fprintf(stderr, "a PNG truncated to %zu of %zu bytes was accepted\n", length, size);
    }
    MRGI_CHECK(s == MRGI_ERR_FORMAT);
    MRGI_CHECK(err.message[0] != '\0');
    MRGI_CHECK(img.pixels == NULL);
  }
  free(data);
}

static void test_read_rejects_corrupt_files(void)
{
  char source[1024];
  char path[1024];
  mrgi_test_tmp_path("png_corrupt_source.png", source, sizeof(source));
  mrgi_test_tmp_path("png_corrupt.png", path, sizeof(path));
  uint8_t pixels[8 * 8 * 4];
  for (size_t i = 0; i < sizeof(pixels); ++i)
  {
    pixels[i] = (uint8_t)(i * 13u);
  }
  MRGI_CHECK(mrgi_png_write_rgba8(source, pixels, 8, 8, 4, NULL) == MRGI_OK);
  size_t size = 0;
  uint8_t* data = mrgi_test_read_file(source, &size);
  uint8_t* copy = (uint8_t*)malloc(size);
  MRGI_CHECK(copy != NULL);

  long at = -1;
  for (size_t i = 8; i + 4 <= size; ++i)
  {
    if (memcmp(data + i, "IDAT", 4) == 0)
    {
      at = (long)i;
      break;
    }
  }
  MRGI_CHECK(at > 0);
  /* Damaged compressed pixels: zlib's own check fails. */
  memcpy(copy, data, size);
  copy[at + 10] ^= 0x44;
  mrgi_test_write_file(path, copy, size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "IDAT");

  /* Intact pixels but a damaged chunk checksum. */
  const size_t idat_length = ((size_t)data[at - 4] << 24) | ((size_t)data[at - 3] << 16) |
                             ((size_t)data[at - 2] << 8) | (size_t)data[at - 1];
  memcpy(copy, data, size);
  copy[(size_t)at + 4 + idat_length] ^= 0x01;
  mrgi_test_write_file(path, copy, size);
  expect_read_fails(path, MRGI_ERR_FORMAT, "CRC error");

  /* Flip each byte in turn: never a crash, a leak or a half-made image. */
  int rejected = 0;
  for (size_t i = 0; i < size; ++i)
  {
    memcpy(copy, data, size);
    copy[i] ^= 0xa5;
    mrgi_test_write_file(path, copy, size);
    mrgi_error err;
    mrgi_image img;
    const mrgi_status s = mrgi_png_read(path, &img, &err);
    if (s == MRGI_OK)
    {
      MRGI_CHECK(mrgi_image_validate(&img, NULL) == MRGI_OK);
      mrgi_image_destroy(&img);
    }
    else
    {
      MRGI_CHECK(err.message[0] != '\0');
      MRGI_CHECK(img.pixels == NULL);
      ++rejected;
    }
  }
  MRGI_CHECK(rejected > (int)size / 2);
  free(copy);
  free(data);
}

int main(int argc, char** argv)
{
  static const mrgi_test_case cases[] = {
    MRGI_TEST_CASE(test_rgba8_round_trip_all_channel_counts),
    MRGI_TEST_CASE(test_write_image_converts_floats),
    MRGI_TEST_CASE(test_read_16bit_gray_alpha),
    MRGI_TEST_CASE(test_read_palette_with_transparency),
    MRGI_TEST_CASE(test_read_rejects_oversized_header),
    MRGI_TEST_CASE(test_read_rejects_more_rows_than_the_file_holds),
    MRGI_TEST_CASE(test_write_rejects_bad_input),
    MRGI_TEST_CASE(test_write_to_missing_directory_leaves_nothing),
    MRGI_TEST_CASE(test_read_rejects_missing_and_foreign_files),
    MRGI_TEST_CASE(test_read_rejects_truncated_files),
    MRGI_TEST_CASE(test_read_rejects_corrupt_files),
  };
  return MRGI_TEST_MAIN(argc, argv, cases);
}
