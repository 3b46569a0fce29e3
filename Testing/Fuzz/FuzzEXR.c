/* Fuzzes mrgi_exr_read_channels(): any bytes give an image of the documented
 * shape with a terminated name per channel, or a documented error with a
 * message and a zeroed image. Values may be NaN or infinite (the reader
 * returns them as stored); every value is read so that ASan sees the whole
 * buffer. */
#include "mrgi_exr.h"
#include "mrgi_fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const char* path = mrgi_fuzz_file(data, size, ".exr");
  mrgi_image img;
  char names[MRGI_IMAGE_MAX_CHANNELS][MRGI_EXR_CHANNEL_NAME_SIZE];
  memset(names, 0x7f, sizeof(names));
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status =
    mrgi_exr_read_channels(path, &img, names, MRGI_IMAGE_MAX_CHANNELS, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(img.pixels != NULL);
    MRGI_FUZZ_REQUIRE(img.width >= 1 && img.width <= MRGI_IMAGE_MAX_DIMENSION);
    MRGI_FUZZ_REQUIRE(img.height >= 1 && img.height <= MRGI_IMAGE_MAX_DIMENSION);
    MRGI_FUZZ_REQUIRE(img.channels >= 1 && img.channels <= MRGI_IMAGE_MAX_CHANNELS);
    for (int32_t c = 0; c < img.channels; ++c)
    {
      const char* end = (const char*)memchr(names[c], '\0', MRGI_EXR_CHANNEL_NAME_SIZE);
      MRGI_FUZZ_REQUIRE(end != NULL && end != names[c]);
    }
    const size_t values = (size_t)img.width * (size_t)img.height * (size_t)img.channels;
    volatile float sum = 0.0f;
    for (size_t i = 0; i < values; ++i)
    {
      sum += img.pixels[i];
    }
    (void)sum;
    mrgi_image_destroy(&img);
  }
  else
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT || status == MRGI_ERR_IO ||
      status == MRGI_ERR_UNSUPPORTED || status == MRGI_ERR_OUT_OF_MEMORY);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
    MRGI_FUZZ_REQUIRE(img.pixels == NULL && img.width == 0 && img.height == 0);
  }
  return 0;
}
