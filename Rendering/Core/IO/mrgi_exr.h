/**
 * @file mrgi_exr.h
 * @brief OpenEXR reading and writing through the OpenEXRCore C API.
 *
 * Images follow mrgi_image.h: interleaved floats, row 0 = top row, which is
 * also the first scanline of the EXR data window. Files are single-part
 * scanline images without compression: OpenEXR 3.1.5's C encoder (Debian
 * 12) wrote corrupt ZIP and ZIPS chunks for some real images (non-finite
 * and negative values read back, by OpenEXR's C++ reader too; TestEXR keeps
 * such a block). Files are larger (12 bytes per RGB pixel), never wrong.
 *
 * Writing never stores NaN or infinity: NaN becomes 0 and values are clamped
 * to the finite range of the stored type. Half floats hold at most
 * ::MRGI_EXR_HALF_MAX (65504), so a HALF file clamps to [-65504, 65504]
 * where OpenEXR's own conversion would produce infinity; their precision is
 * 11 significant bits (relative error up to 2^-11, about 4.9e-4).
 */
#ifndef MRGI_EXR_H
#define MRGI_EXR_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest finite half-float value; HALF writes clamp to +-this. */
#define MRGI_EXR_HALF_MAX 65504.0f
/** Size of one channel-name slot, NUL included: names have 1..31 characters. */
#define MRGI_EXR_CHANNEL_NAME_SIZE 32

/** Storage type of the channels of a written file. */
typedef enum mrgi_exr_pixel_type
{
  MRGI_EXR_HALF = 0, /**< 16-bit float: half the size, ~3 decimal digits, |v| <= 65504. */
  MRGI_EXR_FLOAT = 1 /**< 32-bit float: exact copy of the image values (after NaN/inf removal). */
} mrgi_exr_pixel_type;

/**
 * @brief Write `img` to `path` atomically (see mrgi_atomic_file.h).
 *
 * @param path          Output file; any existing file is replaced only on success.
 * @param img           Valid image, 1..MRGI_IMAGE_MAX_CHANNELS channels.
 * @param channel_names NULL for the defaults (1 channel: "Y"; 3: "R","G","B";
 *                      4: "R","G","B","A"; other counts need names), or
 *                      `img->channels` distinct names of 1..31 characters, in
 *                      image channel order.
 * @param pixel_type    ::MRGI_EXR_HALF or ::MRGI_EXR_FLOAT.
 * @return ::MRGI_ERR_INVALID_ARGUMENT (bad image, names or type), ::MRGI_ERR_IO
 *         (directory missing, disk full, ...), ::MRGI_ERR_OUT_OF_MEMORY,
 *         ::MRGI_ERR_FORMAT (the library refused to encode).
 */
mrgi_status mrgi_exr_write(const char* path, const mrgi_image* img,
                           const char* const* channel_names, mrgi_exr_pixel_type pixel_type,
                           mrgi_error* err);

/**
 * @brief Read the first part of a scanline EXR file into a new float image.
 *
 * The image covers the data window (the display window is ignored). HALF,
 * FLOAT and UINT channels are all converted to float; values are returned as
 * stored (NaN and infinity included: see mrgi_image_count_nonfinite()).
 * Channel order of the image: whichever of "R", "G", "B", "A", "Y" exist, in
 * that order, then every other channel in file order (alphabetical).
 *
 * @param out Receives a new image; zeroed on failure.
 * @return ::MRGI_ERR_IO (missing/unreadable file), ::MRGI_ERR_FORMAT (not an
 *         EXR, truncated, corrupt, implausible data window),
 *         ::MRGI_ERR_UNSUPPORTED (tiled or deep parts, subsampled channels,
 *         more than MRGI_IMAGE_MAX_CHANNELS channels or a side longer than
 *         MRGI_IMAGE_MAX_DIMENSION).
 */
mrgi_status mrgi_exr_read(const char* path, mrgi_image* out, mrgi_error* err);

/**
 * @brief mrgi_exr_read() that also reports the channel names, in image channel order.
 *
 * @param names     NULL, or room for `max_names` names; names[i] names image channel i.
 *                  Only the first min(max_names, out->channels) slots are written.
 * @param max_names Number of slots in `names`, >= 0.
 * @return As mrgi_exr_read(); ::MRGI_ERR_UNSUPPORTED also when a reported name
 *         is longer than 31 characters.
 */
mrgi_status mrgi_exr_read_channels(const char* path, mrgi_image* out,
                                   char names[][MRGI_EXR_CHANNEL_NAME_SIZE], int32_t max_names,
                                   mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
