#include "mrgi_box_filter.h"

#include <string.h>

mrgi_status mrgi_box_downsample(
  const mrgi_image* src, int32_t factor, mrgi_image* dst, mrgi_error* err)
{
  if (!dst)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "mrgi_box_downsample: no output image");
  }
  memset(dst, 0, sizeof(*dst));
  mrgi_status status = mrgi_image_validate(src, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (factor < 1 || factor > MRGI_BOX_FILTER_MAX_FACTOR)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "mrgi_box_downsample: factor %d is outside 1..%d", (int)factor, MRGI_BOX_FILTER_MAX_FACTOR);
  }
  if (src->width % factor != 0 || src->height % factor != 0)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
      "mrgi_box_downsample: %dx%d is not a multiple of the factor %d", (int)src->width,
      (int)src->height, (int)factor);
  }
  status = mrgi_image_create(dst, src->width / factor, src->height / factor, src->channels, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const int32_t channels = src->channels;
  const double inverse = 1.0 / ((double)factor * (double)factor);
  double sum[MRGI_IMAGE_MAX_CHANNELS];
  for (int32_t y = 0; y < dst->height; ++y)
  {
    for (int32_t x = 0; x < dst->width; ++x)
    {
      for (int32_t c = 0; c < channels; ++c)
      {
        sum[c] = 0.0;
      }
      for (int32_t j = 0; j < factor; ++j)
      {
        const float* row = mrgi_image_at(src, x * factor, y * factor + j);
        for (int32_t i = 0; i < factor * channels; ++i)
        {
          sum[i % channels] += row[i];
        }
      }
      float* out = mrgi_image_at(dst, x, y);
      for (int32_t c = 0; c < channels; ++c)
      {
        out[c] = (float)(sum[c] * inverse);
      }
    }
  }
  return MRGI_OK;
}
