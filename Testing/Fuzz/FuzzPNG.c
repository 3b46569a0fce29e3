/* Fuzzes mrgi_png_read(): any bytes give an image of the documented shape
 * with values in [0, 1], or a documented error with a message and a zeroed
 * image.
 *
 * Each input is read twice: as it is, and with every chunk's CRC made right.
 * libpng rejects a chunk whose CRC is wrong, so without the second read
 * nearly every mutation would stop at the first changed chunk, and libpng
 * (not instrumented: Debian's) gives the fuzzer no coverage to find the way. */
#include "mrgi_fuzz.h"
#include "mrgi_png.h"

/* CRC-32 of PNG (ISO 3309), bitwise: inputs are small. */
static uint32_t png_crc(const uint8_t* bytes, size_t count)
{
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < count; ++i)
  {
    crc ^= bytes[i];
    for (int k = 0; k < 8; ++k)
    {
      crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
  }
  return crc ^ 0xFFFFFFFFu;
}

/* Rewrites the CRC of every complete chunk after the 8-byte signature. */
static void fix_crcs(uint8_t* bytes, size_t size)
{
  size_t at = 8;
  while (at + 12 <= size)
  {
    const uint32_t length = ((uint32_t)bytes[at] << 24) | ((uint32_t)bytes[at + 1] << 16) |
      ((uint32_t)bytes[at + 2] << 8) | (uint32_t)bytes[at + 3];
    if (length > size - at - 12)
    {
      break;
    }
    const uint32_t crc = png_crc(bytes + at + 4, (size_t)length + 4);
    uint8_t* out = bytes + at + 8 + length;
    out[0] = (uint8_t)(crc >> 24);
    out[1] = (uint8_t)(crc >> 16);
    out[2] = (uint8_t)(crc >> 8);
    out[3] = (uint8_t)crc;
    at += (size_t)length + 12;
  }
}

static void read_and_check(const uint8_t* data, size_t size)
{
  const char* path = mrgi_fuzz_file(data, size, ".png");
  mrgi_image img;
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_png_read(path, &img, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(img.pixels != NULL);
    MRGI_FUZZ_REQUIRE(img.width >= 1 && img.width <= MRGI_IMAGE_MAX_DIMENSION);
    MRGI_FUZZ_REQUIRE(img.height >= 1 && img.height <= MRGI_IMAGE_MAX_DIMENSION);
    MRGI_FUZZ_REQUIRE(img.channels >= 1 && img.channels <= 4);
    const size_t values = (size_t)img.width * (size_t)img.height * (size_t)img.channels;
    for (size_t i = 0; i < values; ++i)
    {
      MRGI_FUZZ_REQUIRE(img.pixels[i] >= 0.0f && img.pixels[i] <= 1.0f);
    }
    mrgi_image_destroy(&img);
  }
  else
  {
    MRGI_FUZZ_REQUIRE(
      status == MRGI_ERR_FORMAT || status == MRGI_ERR_IO || status == MRGI_ERR_OUT_OF_MEMORY);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
    MRGI_FUZZ_REQUIRE(img.pixels == NULL && img.width == 0 && img.height == 0);
  }
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  read_and_check(data, size);
  if (size > 8)
  {
    uint8_t* fixed = (uint8_t*)malloc(size);
    MRGI_FUZZ_REQUIRE(fixed != NULL);
    memcpy(fixed, data, size);
    fix_crcs(fixed, size);
    if (memcmp(fixed, data, size) != 0)
    {
      read_and_check(fixed, size);
    }
    free(fixed);
  }
  return 0;
}
