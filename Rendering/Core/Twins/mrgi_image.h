/**
 * @file mrgi_image.h
 * @brief Owned float images: the one pixel container of the core.
 *
 * Layout: `pixels` holds `width * height * channels` floats, interleaved
 * (all channels of a pixel are adjacent), rows stored top to bottom:
 * row 0 is the TOP row of the picture, as in EXR and PNG files. VTK and
 * OpenGL read-backs are bottom-up; pass them through mrgi_image_flip_rows()
 * before handing them to the core.
 *
 * Ownership: an image made by mrgi_image_create() (or any core function
 * documented as creating one) owns `pixels` and must be released with
 * mrgi_image_destroy(). Output parameters are treated as uninitialized:
 * passing an image that still owns pixels as an output leaks them.
 */
#ifndef MRGI_IMAGE_H
#define MRGI_IMAGE_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest accepted width or height, in pixels. */
#define MRGI_IMAGE_MAX_DIMENSION (1 << 20)
/** Largest accepted number of channels per pixel. */
#define MRGI_IMAGE_MAX_CHANNELS 64

/** Interleaved float image, row 0 = top. Plain struct; see the file comment for ownership. */
typedef struct mrgi_image
{
  int32_t width;    /**< Pixels per row, 1..MRGI_IMAGE_MAX_DIMENSION. */
  int32_t height;   /**< Rows, 1..MRGI_IMAGE_MAX_DIMENSION. */
  int32_t channels; /**< Values per pixel, 1..MRGI_IMAGE_MAX_CHANNELS. */
  float* pixels;    /**< width*height*channels values; NULL in an empty image. */
} mrgi_image;

/**
 * @brief Allocate a zero-filled image.
 * @param out      Receives the image; zeroed on failure (so destroying it is safe).
 * @param width    Pixels per row, 1..MRGI_IMAGE_MAX_DIMENSION.
 * @param height   Rows, 1..MRGI_IMAGE_MAX_DIMENSION.
 * @param channels Values per pixel, 1..MRGI_IMAGE_MAX_CHANNELS.
 * @return ::MRGI_ERR_INVALID_ARGUMENT for NULL `out` or a size out of range
 *         (also when the byte count overflows size_t), ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_image_create(mrgi_image* out, int64_t width, int64_t height, int64_t channels,
                              mrgi_error* err);

/** @brief Free the pixels and zero the struct. NULL-safe and idempotent. */
void mrgi_image_destroy(mrgi_image* img);

/** @brief width * height, or 0 for NULL or a non-positive size. */
int64_t mrgi_image_pixel_count(const mrgi_image* img);

/** @brief width * height * channels (number of floats), or 0 for NULL or a non-positive size. */
size_t mrgi_image_value_count(const mrgi_image* img);

/**
 * @brief Pointer to the first channel of pixel (x, y), y = 0 being the top row.
 *
 * No checks (hot loops): the caller guarantees a valid image,
 * 0 <= x < width and 0 <= y < height.
 */
static inline float* mrgi_image_at(const mrgi_image* img, int32_t x, int32_t y)
{
  return img->pixels + ((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels;
}

/**
 * @brief Check that `img` is usable: not NULL, sizes in range, pixels allocated.
 * @return ::MRGI_OK or ::MRGI_ERR_INVALID_ARGUMENT naming the bad field.
 */
mrgi_status mrgi_image_validate(const mrgi_image* img, mrgi_error* err);

/**
 * @brief Deep copy.
 * @param dst Receives a new image (treated as uninitialized); zeroed on failure.
 * @param src Valid image; must not be `dst`.
 */
mrgi_status mrgi_image_copy(mrgi_image* dst, const mrgi_image* src, mrgi_error* err);

/**
 * @brief Count values that are NaN or +-infinity.
 * @param out_count Receives the count (0..width*height*channels).
 */
mrgi_status mrgi_image_count_nonfinite(const mrgi_image* img, int64_t* out_count, mrgi_error* err);

/** @brief Reverse the row order in place (bottom-up GL read-back <-> top-down core image). */
mrgi_status mrgi_image_flip_rows(mrgi_image* img, mrgi_error* err);

/** @brief sRGB transfer function: linear [0,1] -> encoded [0,1]. Input is clamped to [0,1]; NaN -> 0. */
float mrgi_srgb_encode(float linear);

/** @brief Inverse sRGB transfer function: encoded [0,1] -> linear [0,1]. Input is clamped; NaN -> 0. */
float mrgi_srgb_decode(float encoded);

/**
 * @brief Make a float image from 8-bit interleaved pixels (row 0 = top).
 *
 * "rgba8" means one to four 8-bit channels: gray, gray+alpha, RGB or RGBA.
 * Values map to [0,1] (v / 255). With `srgb_decode` the colour channels are
 * converted from sRGB to linear; alpha (channel 1 of 2, channel 3 of 4) stays linear.
 *
 * @param out         Receives a new image; zeroed on failure.
 * @param pixels      width*height*channels bytes.
 * @param pixels_size Size of `pixels` in bytes; must be at least width*height*channels.
 * @param channels    1..4.
 */
mrgi_status mrgi_image_from_rgba8(mrgi_image* out, const uint8_t* pixels, size_t pixels_size,
                                  int64_t width, int64_t height, int64_t channels,
                                  int srgb_decode, mrgi_error* err);

/**
 * @brief Convert a float image (1..4 channels) to 8-bit, same channel count and row order.
 *
 * Each colour value is multiplied by `exposure`, NaN becomes 0, the result
 * is clamped to [0,1], optionally sRGB-encoded, then rounded to 0..255.
 * Alpha (channel 1 of 2, channel 3 of 4) is clamped and rounded only.
 *
 * @param out      Destination of width*height*channels bytes.
 * @param out_size Size of `out` in bytes.
 * @param exposure Linear multiplier, finite and > 0 (1 = as is; use exp2f(stops) for stops).
 * @return ::MRGI_ERR_UNSUPPORTED for more than 4 channels, ::MRGI_ERR_INVALID_ARGUMENT
 *         for a NULL/short buffer or bad exposure.
 */
mrgi_status mrgi_image_to_rgba8(const mrgi_image* img, uint8_t* out, size_t out_size,
                                int srgb_encode, float exposure, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
