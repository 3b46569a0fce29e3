/**
 * @file mrgi_image_file.h
 * @brief Read an image file chosen by its extension: `.exr` through
 *        mrgi_exr_read(), `.png` through mrgi_png_read() (case-insensitive).
 *        The command-line tools (mrgi-compare, mrgi-flicker) read their
 *        inputs this way.
 */
#ifndef MRGI_IMAGE_FILE_H
#define MRGI_IMAGE_FILE_H

#include "mrgi_error.h"
#include "mrgi_image.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief 1 when `path` ends in `extension` (e.g. ".exr"), compared without
 *        case, and is longer than it; 0 otherwise (NULL arguments included).
 */
int mrgi_image_file_has_extension(const char* path, const char* extension);

/**
 * @brief Read `path` into `out` (row 0 = top, as mrgi_image.h).
 * @return What mrgi_exr_read() or mrgi_png_read() returns;
 *         ::MRGI_ERR_INVALID_ARGUMENT for a NULL path or a name that ends
 *         in neither `.exr` nor `.png` (the message names the file).
 */
mrgi_status mrgi_image_file_read(const char* path, mrgi_image* out, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
