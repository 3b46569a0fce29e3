/**
 * @file mrgi_png.h
 * @brief PNG reading and writing through libpng.
 *
 * Row order follows mrgi_image.h: row 0 = top row, as stored in PNG files.
 * Written files are 8-bit, non-interlaced, with 1 to 4 channels (gray,
 * gray+alpha, RGB, RGBA) and no colour-space chunk (viewers assume sRGB).
 * Writes are atomic (see mrgi_atomic_file.h): a failed write leaves neither a
 * partial file nor a temporary file behind.
 */
#ifndef MRGI_PNG_H
#define MRGI_PNG_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Write 8-bit interleaved pixels.
 * @param pixels   width*height*channels bytes, row 0 = top.
 * @param width    1..MRGI_IMAGE_MAX_DIMENSION.
 * @param height   1..MRGI_IMAGE_MAX_DIMENSION.
 * @param channels 1 (gray), 2 (gray+alpha), 3 (RGB) or 4 (RGBA).
 * @return ::MRGI_ERR_INVALID_ARGUMENT, ::MRGI_ERR_IO (directory missing, disk full).
 */
mrgi_status mrgi_png_write_rgba8(const char* path, const uint8_t* pixels, int32_t width,
                                 int32_t height, int32_t channels, mrgi_error* err);

/**
 * @brief Convert a 1..4-channel float image to 8 bits (mrgi_image_to_rgba8()) and write it.
 * @param srgb_encode Non-zero: colour channels are sRGB-encoded (for linear images).
 * @param exposure    Linear multiplier of colour channels, finite and > 0.
 * @return ::MRGI_ERR_UNSUPPORTED for more than 4 channels, else as mrgi_png_write_rgba8().
 */
mrgi_status mrgi_png_write_image(const char* path, const mrgi_image* img, int srgb_encode,
                                 float exposure, mrgi_error* err);

/**
 * @brief Read a PNG file into a new float image with values in [0,1].
 *
 * 8-bit samples map as v/255, 16-bit as v/65535; no colour-space conversion
 * is applied (values are the stored, usually sRGB-encoded, codes). Channels
 * are as stored: 1 gray, 2 gray+alpha, 3 RGB, 4 RGBA; palette images become
 * RGB, a tRNS chunk adds an alpha channel, 1/2/4-bit gray is scaled to 8 bits.
 *
 * @param out Receives a new image; zeroed on failure.
 * @return ::MRGI_ERR_IO (missing/unreadable), ::MRGI_ERR_FORMAT (not a PNG,
 *         truncated, bad CRC, corrupt data, a side above MRGI_IMAGE_MAX_DIMENSION),
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_png_read(const char* path, mrgi_image* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
