#include "mrgi_image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* a * b without wrap-around; returns 0 when the product does not fit. */
static int mrgi_image_mul_size(size_t a, size_t b, size_t* out)
{
  if (a != 0 && b > SIZE_MAX / a)
  {
    return 0;
  }
  *out = a * b;
  return 1;
}

static int mrgi_image_is_alpha_channel(int32_t channel, int32_t channels)
{
  return (channels == 2 && channel == 1) || (channels == 4 && channel == 3);
}

static mrgi_status mrgi_image_check_size(int64_t width, int64_t height, int64_t channels,
                                         size_t* out_bytes, mrgi_error* err)
{
  if (width < 1 || width > MRGI_IMAGE_MAX_DIMENSION)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "image width %lld is outside [1, %d]", (long long)width,
                          MRGI_IMAGE_MAX_DIMENSION);
  }
  if (height < 1 || height > MRGI_IMAGE_MAX_DIMENSION)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "image height %lld is outside [1, %d]", (long long)height,
                          MRGI_IMAGE_MAX_DIMENSION);
  }
  if (channels < 1 || channels > MRGI_IMAGE_MAX_CHANNELS)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "image channel count %lld is outside [1, %d]", (long long)channels,
                          MRGI_IMAGE_MAX_CHANNELS);
  }
  size_t bytes = 0;
  if (!mrgi_image_mul_size((size_t)width, (size_t)height, &bytes) ||
      !mrgi_image_mul_size(bytes, (size_t)channels, &bytes) ||
      !mrgi_image_mul_size(bytes, sizeof(float), &bytes))
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "image size %lldx%lldx%lld overflows the addressable byte count",
                          (long long)width, (long long)height, (long long)channels);
  }
  *out_bytes = bytes;
  return MRGI_OK;
}

mrgi_status mrgi_image_create(mrgi_image* out, int64_t width, int64_t height, int64_t channels,
                              mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output image pointer is NULL");
  }
  memset(out, 0, sizeof(*out));
  size_t bytes = 0;
  mrgi_status status = mrgi_image_check_size(width, height, channels, &bytes, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  /* calloc: images start black, and large zero pages come cheaply from the OS. */
  float* pixels = (float*)calloc(bytes / sizeof(float), sizeof(float));
  if (!pixels)
  {
    return mrgi_error_set(err, MRGI_ERR_OUT_OF_MEMORY,
                          "cannot allocate %zu bytes for a %lldx%lldx%lld image", bytes,
                          (long long)width, (long long)height, (long long)channels);
  }
  out->width = (int32_t)width;
  out->height = (int32_t)height;
  out->channels = (int32_t)channels;
  out->pixels = pixels;
  return MRGI_OK;
}

void mrgi_image_destroy(mrgi_image* img)
{
  if (img)
  {
    free(img->pixels);
    memset(img, 0, sizeof(*img));
  }
}

int64_t mrgi_image_pixel_count(const mrgi_image* img)
{
  if (!img || img->width <= 0 || img->height <= 0)
  {
    return 0;
  }
  return (int64_t)img->width * (int64_t)img->height;
}

size_t mrgi_image_value_count(const mrgi_image* img)
{
  if (!img || img->width <= 0 || img->height <= 0 || img->channels <= 0)
  {
    return 0;
  }
  return (size_t)img->width * (size_t)img->height * (size_t)img->channels;
}

mrgi_status mrgi_image_validate(const mrgi_image* img, mrgi_error* err)
{
  if (!img)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "image pointer is NULL");
  }
  size_t bytes = 0;
  mrgi_status status = mrgi_image_check_size(img->width, img->height, img->channels, &bytes, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (!img->pixels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "image %dx%dx%d has no pixel buffer (pixels is NULL)", img->width,
                          img->height, img->channels);
  }
  return MRGI_OK;
}

mrgi_status mrgi_image_copy(mrgi_image* dst, const mrgi_image* src, mrgi_error* err)
{
  if (!dst)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "copy destination pointer is NULL");
  }
  if (dst == src)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "copy destination and source are the same image");
  }
  mrgi_status status = mrgi_image_validate(src, err);
  if (status != MRGI_OK)
  {
    memset(dst, 0, sizeof(*dst));
    mrgi_error_prefix(err, "copy source: ");
    return status;
  }
  status = mrgi_image_create(dst, src->width, src->height, src->channels, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  memcpy(dst->pixels, src->pixels, mrgi_image_value_count(src) * sizeof(float));
  return MRGI_OK;
}

mrgi_status mrgi_image_count_nonfinite(const mrgi_image* img, int64_t* out_count, mrgi_error* err)
{
  if (!out_count)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output count pointer is NULL");
  }
  *out_count = 0;
  mrgi_status status = mrgi_image_validate(img, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t n = mrgi_image_value_count(img);
  int64_t count = 0;
  for (size_t i = 0; i < n; ++i)
  {
    count += !isfinite(img->pixels[i]);
  }
  *out_count = count;
  return MRGI_OK;
}

mrgi_status mrgi_image_flip_rows(mrgi_image* img, mrgi_error* err)
{
  mrgi_status status = mrgi_image_validate(img, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  /* Swapping value by value needs no row buffer, so flipping never allocates. */
  const size_t row_values = (size_t)img->width * (size_t)img->channels;
  for (int32_t top = 0, bottom = img->height - 1; top < bottom; ++top, --bottom)
  {
    float* a = img->pixels + (size_t)top * row_values;
    float* b = img->pixels + (size_t)bottom * row_values;
    for (size_t i = 0; i < row_values; ++i)
    {
      const float t = a[i];
      a[i] = b[i];
      b[i] = t;
    }
  }
  return MRGI_OK;
}

static float mrgi_clamp01(float v)
{
  /* The negated comparison also maps NaN to 0. */
  if (!(v > 0.0f))
  {
    return 0.0f;
  }
  return v < 1.0f ? v : 1.0f;
}

float mrgi_srgb_encode(float linear)
{
  const float v = mrgi_clamp01(linear);
  if (v <= 0.0031308f)
  {
    return 12.92f * v;
  }
  return 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
}

float mrgi_srgb_decode(float encoded)
{
  const float v = mrgi_clamp01(encoded);
  if (v <= 0.04045f)
  {
    return v / 12.92f;
  }
  return powf((v + 0.055f) / 1.055f, 2.4f);
}

mrgi_status mrgi_image_from_rgba8(mrgi_image* out, const uint8_t* pixels, size_t pixels_size,
                                  int64_t width, int64_t height, int64_t channels,
                                  int srgb_decode, mrgi_error* err)
{
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "output image pointer is NULL");
  }
  memset(out, 0, sizeof(*out));
  if (!pixels)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "8-bit pixel pointer is NULL");
  }
  if (channels < 1 || channels > 4)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "8-bit channel count %lld is outside [1, 4]", (long long)channels);
  }
  mrgi_image img;
  mrgi_status status = mrgi_image_create(&img, width, height, channels, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  const size_t n = mrgi_image_value_count(&img);
  if (pixels_size < n)
  {
    mrgi_image_destroy(&img);
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "8-bit buffer holds %zu bytes but a %lldx%lldx%lld image needs %zu",
                          pixels_size, (long long)width, (long long)height,
                          (long long)channels, n);
  }
  /* A 256-entry table keeps powf out of the per-pixel loop. */
  float colour_table[256];
  float alpha_table[256];
  for (int i = 0; i < 256; ++i)
  {
    alpha_table[i] = (float)i / 255.0f;
    colour_table[i] = srgb_decode ? mrgi_srgb_decode(alpha_table[i]) : alpha_table[i];
  }
  const int32_t c_count = img.channels;
  for (size_t i = 0; i < n; ++i)
  {
    const int32_t c = (int32_t)(i % (size_t)c_count);
    img.pixels[i] =
      mrgi_image_is_alpha_channel(c, c_count) ? alpha_table[pixels[i]] : colour_table[pixels[i]];
  }
  *out = img;
  return MRGI_OK;
}

static uint8_t mrgi_quantize8(float v01)
{
  return (uint8_t)(v01 * 255.0f + 0.5f);
}

mrgi_status mrgi_image_to_rgba8(const mrgi_image* img, uint8_t* out, size_t out_size,
                                int srgb_encode, float exposure, mrgi_error* err)
{
  mrgi_status status = mrgi_image_validate(img, err);
  if (status != MRGI_OK)
  {
    return status;
  }
  if (img->channels > 4)
  {
    return mrgi_error_set(err, MRGI_ERR_UNSUPPORTED,
                          "8-bit conversion handles 1 to 4 channels, the image has %d",
                          img->channels);
  }
  if (!out)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT, "8-bit output pointer is NULL");
  }
  if (!isfinite(exposure) || exposure <= 0.0f)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "exposure %g must be finite and greater than 0", (double)exposure);
  }
  const size_t n = mrgi_image_value_count(img);
  if (out_size < n)
  {
    return mrgi_error_set(err, MRGI_ERR_INVALID_ARGUMENT,
                          "8-bit output buffer holds %zu bytes but the %dx%dx%d image needs %zu",
                          out_size, img->width, img->height, img->channels, n);
  }
  const int32_t c_count = img->channels;
  for (size_t i = 0; i < n; ++i)
  {
    const int32_t c = (int32_t)(i % (size_t)c_count);
    const float v = img->pixels[i];
    if (mrgi_image_is_alpha_channel(c, c_count))
    {
      out[i] = mrgi_quantize8(mrgi_clamp01(v));
    }
    else
    {
      const float scaled = mrgi_clamp01(v * exposure);
      out[i] = mrgi_quantize8(srgb_encode ? mrgi_srgb_encode(scaled) : scaled);
    }
  }
  return MRGI_OK;
}
