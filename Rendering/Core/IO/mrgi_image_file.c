#include "mrgi_image_file.h"

#include "mrgi_exr.h"
#include "mrgi_png.h"

#include <string.h>
#include <strings.h>

int mrgi_image_file_has_extension(const char* path, const char* extension)
{
  if (!path || !extension)
  {
    return 0;
  }
  const size_t n = strlen(path), e = strlen(extension);
  return n > e && strcasecmp(path + n - e, extension) == 0;
}

mrgi_status mrgi_image_file_read(const char* path, mrgi_image* out, mrgi_error* err)
{
  if (!path)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "image file: the path is NULL");
  }
  if (mrgi_image_file_has_extension(path, ".exr"))
  {
    return mrgi_exr_read(path, out, err);
  }
  if (mrgi_image_file_has_extension(path, ".png"))
  {
    return mrgi_png_read(path, out, err);
  }
  return mrgi_error_set(
    err, MRGI_ERR_INVALID_ARGUMENT, "'%s': the file name must end in .exr or .png", path);
}
