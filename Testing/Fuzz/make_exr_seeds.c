/* Writes the EXR fuzz seeds (Seeds/EXR) with the core's own writer: the
 * layouts mrgi-render and the tests write (HALF and FLOAT; 1, 3, 4 and 5
 * channels; one and two chunks). Not part of the build; to rerun:
 *   cc -I Rendering/Core/Twins -I Rendering/Core/IO Testing/Fuzz/make_exr_seeds.c \
 *      -L build/lib -lMRGICoreIO -lMRGICore -Wl,-rpath,build/lib -o /tmp/make_exr_seeds
 *   /tmp/make_exr_seeds Testing/Fuzz/Seeds/EXR
 */
#include "mrgi_exr.h"

#include <stdio.h>

static int write_seed(const char* dir, const char* name, int w, int h, int c,
  const char* const* names, mrgi_exr_pixel_type type)
{
  mrgi_image img;
  if (mrgi_image_create(&img, w, h, c, NULL) != MRGI_OK)
    return 1;
  for (int i = 0; i < w * h * c; ++i)
    img.pixels[i] = (float)(i % 17) * 0.37f - 1.0f;
  char path[4096];
  snprintf(path, sizeof(path), "%s/%s", dir, name);
  mrgi_error err;
  const int failed = mrgi_exr_write(path, &img, names, type, &err) != MRGI_OK;
  if (failed)
    fprintf(stderr, "%s: %s\n", path, err.message);
  mrgi_image_destroy(&img);
  return failed;
}

int main(int argc, char** argv)
{
  const char* dir = argc > 1 ? argv[1] : ".";
  static const char* const five[] = { "depth", "B", "normal.x", "R", "id" };
  int failed = 0;
  failed |= write_seed(dir, "rgb-float-3x2.exr", 3, 2, 3, NULL, MRGI_EXR_FLOAT);
  failed |= write_seed(dir, "rgba-half-5x3.exr", 5, 3, 4, NULL, MRGI_EXR_HALF);
  failed |= write_seed(dir, "y-half-4x1.exr", 4, 1, 1, NULL, MRGI_EXR_HALF);
  failed |= write_seed(dir, "five-float-2x2.exr", 2, 2, 5, five, MRGI_EXR_FLOAT);
  failed |= write_seed(dir, "rgb-half-2x20.exr", 2, 20, 3, NULL, MRGI_EXR_HALF);
  return failed;
}
