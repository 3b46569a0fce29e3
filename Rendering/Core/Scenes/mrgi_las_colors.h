/**
 * @file mrgi_las_colors.h
 * @brief Display colours of LAS points: their RGB, the ASPRS classes'
 *        colours, or an intensity grey ramp.
 *
 * ASPRS defines class numbers (LAS 1.4 R15, table 17), not colours. The
 * palette here follows the usage of common LiDAR viewers: ground brown,
 * vegetation greens from light (low) to dark (high), buildings red, water
 * blue, noise magenta, roads dark grey; "never classified" (0) and
 * "unclassified" (1) are light greys; reserved and user classes (23..255)
 * are mid grey.
 *
 * The intensity ramp maps the 2nd..98th percentile of the cloud's
 * intensities linearly to grey 38..255 (0.15..1: the darkest points stay
 * visible on a black background) and clamps outside, so that a few
 * saturated returns do not darken the rest. A cloud whose intensities
 * are all equal (files that record none) is uniform grey 204 (0.8, the
 * colour MRGI gives uncoloured geometry).
 *
 * Automatic choice (::MRGI_LAS_COLOR_AUTO): RGB when the point format has
 * it; else the classes when any point has a class other than 0 and 1 (the
 * file is classified); else intensity.
 */
#ifndef MRGI_LAS_COLORS_H
#define MRGI_LAS_COLORS_H

#include "mrgi_error.h"
#include "mrgi_las.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** What the colours show. */
typedef enum mrgi_las_color_mode
{
  MRGI_LAS_COLOR_AUTO = 0,           /**< RGB, else classification, else intensity. */
  MRGI_LAS_COLOR_RGB = 1,            /**< The file's RGB (formats 2, 3, 5, 7, 8, 10). */
  MRGI_LAS_COLOR_CLASSIFICATION = 2, /**< mrgi_las_classification_color(). */
  MRGI_LAS_COLOR_INTENSITY = 3       /**< The grey ramp of the file documentation. */
} mrgi_las_color_mode;

/** @brief The display colour of ASPRS class `classification` (any value; others are grey). */
void mrgi_las_classification_color(int classification, uint8_t rgb[3]);

/** @brief What ::MRGI_LAS_COLOR_AUTO picks for `points` (never AUTO); RGB for NULL. */
mrgi_las_color_mode mrgi_las_auto_color_mode(const mrgi_las_points* points);

/**
 * @brief 8-bit display colours of every point.
 * @param points A successful mrgi_las_read() result (count > 0).
 * @param mode   What to show; AUTO resolves by mrgi_las_auto_color_mode().
 * @param rgb    3 * points->count bytes, written on success only.
 * @param used   Receives the mode applied (never AUTO); may be NULL.
 * @return ::MRGI_OK; ::MRGI_ERR_INVALID_ARGUMENT for NULL or empty points,
 *         a NULL `rgb`, a mode outside the enum, or RGB asked of a point
 *         format without RGB (the message says so);
 *         ::MRGI_ERR_OUT_OF_MEMORY (the intensity histogram, 256 KiB).
 */
mrgi_status mrgi_las_colorize(const mrgi_las_points* points, mrgi_las_color_mode mode, uint8_t* rgb,
  mrgi_las_color_mode* used, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
