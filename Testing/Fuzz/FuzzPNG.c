/* Fuzzes mrgi_png_read(): any bytes give an image of the documented shape
 * with values in [0, 1], or a documented error with a message and a zeroed
 * image. */
#include "mrgi_fuzz.h"
#include "mrgi_png.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
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
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT || status == MRGI_ERR_IO ||
      status == MRGI_ERR_OUT_OF_MEMORY);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
    MRGI_FUZZ_REQUIRE(img.pixels == NULL && img.width == 0 && img.height == 0);
  }
  return 0;
}
