/* Fuzzes mrgi_las_read_buffer(), the LAS point-cloud reader: any bytes give
 * MRGI_OK with finite, recentred points inside their bounds, or an error
 * with a message; nothing is read outside the buffer (ASan). The points
 * read are then coloured in every mode (mrgi_las_colors.h): RGB succeeds
 * exactly when the format has it, the others always do. */
#include "mrgi_fuzz.h"
#include "mrgi_las.h"
#include "mrgi_las_colors.h"

#include <math.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  mrgi_las_points points;
  mrgi_error err;
  memset(&err, 0, sizeof(err));
  const mrgi_status status = mrgi_las_read_buffer(data, size, 1 << 16, &points, &err);
  if (status == MRGI_OK)
  {
    MRGI_FUZZ_REQUIRE(points.count > 0 && points.count <= (1 << 16));
    for (int64_t i = 0; i < 3 * points.count; ++i)
    {
      MRGI_FUZZ_REQUIRE(isfinite(points.positions[i]));
    }
    for (int c = 0; c < 3; ++c)
    {
      MRGI_FUZZ_REQUIRE(points.bounds[2 * c] <= points.bounds[2 * c + 1]);
    }
    uint8_t* rgb = (uint8_t*)malloc(3 * (size_t)points.count);
    MRGI_FUZZ_REQUIRE(rgb != NULL);
    for (int mode = MRGI_LAS_COLOR_AUTO; mode <= MRGI_LAS_COLOR_INTENSITY; ++mode)
    {
      mrgi_las_color_mode used = MRGI_LAS_COLOR_AUTO;
      const mrgi_status colored =
        mrgi_las_colorize(&points, (mrgi_las_color_mode)mode, rgb, &used, &err);
      const int expect_ok = mode != MRGI_LAS_COLOR_RGB || points.colors != NULL;
      MRGI_FUZZ_REQUIRE((colored == MRGI_OK) == expect_ok);
      MRGI_FUZZ_REQUIRE(colored != MRGI_OK || used != MRGI_LAS_COLOR_AUTO);
    }
    free(rgb);
    mrgi_las_points_destroy(&points);
  }
  else
  {
    MRGI_FUZZ_REQUIRE(status == MRGI_ERR_FORMAT || status == MRGI_ERR_UNSUPPORTED ||
      status == MRGI_ERR_OUT_OF_MEMORY);
    MRGI_FUZZ_REQUIRE_ERROR(status, err);
    MRGI_FUZZ_REQUIRE(points.positions == NULL);
  }
  return 0;
}
