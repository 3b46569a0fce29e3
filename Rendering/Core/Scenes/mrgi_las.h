/**
 * @file mrgi_las.h
 * @brief LAS point clouds (ASPRS LAS 1.0-1.4, point formats 0-10,
 *        uncompressed): header, positions, intensity, returns,
 *        classification and RGB.
 *
 * Written from the public ASPRS LAS specification (1.4 R15); Debian has no
 * LAS library. Coordinates are stored as 32-bit integers with a scale and
 * an offset in double: x = X * scale_x + offset_x. Real files carry
 * UTM-sized values (x ~ 5e5, y ~ 5e6 m), where a float keeps only ~0.5 m,
 * so the reader applies scale and offset in double, then recentres: it
 * returns float positions relative to `origin` (double), the centre of the
 * points' bounding box, which keeps millimetres for clouds up to tens of
 * kilometres across.
 *
 * Compressed LAZ files (LASzip sets bit 7 of the point format) are refused
 * with ::MRGI_ERR_UNSUPPORTED, "compressed LAZ is not supported".
 * Extra bytes after a format's standard fields (record length larger than
 * the format's) are skipped. RGB is 16-bit per channel in the file; values
 * all <= 255 are taken as 8-bit (common writers), otherwise divided by
 * 65535.
 *
 * Errors (::MRGI_ERR_FORMAT, message naming the field): no "LASF"
 * signature, a version other than 1.0-1.4, a header shorter than its
 * version's, point data outside the file, a point format above 10, a
 * record length shorter than the format's, a scale that is zero or not
 * finite, an offset that is not finite, no points, more points than the
 * file holds or than `max_points`, points spanning more than 1e30 units
 * (they could not be recentred in float). The buffer entry points never read
 * outside `size` bytes (fuzzed: fuzz.LAS).
 */
#ifndef MRGI_LAS_H
#define MRGI_LAS_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** What the header says, as read (no point is read). */
typedef struct mrgi_las_header
{
  int32_t version_major;       /**< 1. */
  int32_t version_minor;       /**< 0..4. */
  int32_t header_size;         /**< Bytes of the public header block. */
  int32_t point_format;        /**< 0..10. */
  int32_t point_record_length; /**< Bytes per point record (>= the format's). */
  int64_t point_count;         /**< Points in the file (1.4's 64-bit count when set). */
  int64_t offset_to_points;    /**< Byte offset of the first point record. */
  double scale[3];             /**< Coordinate scale factors, finite, non-zero. */
  double offset[3];            /**< Coordinate offsets, finite. */
  double header_min[3];        /**< The header's bounds (not trusted by the reader). */
  double header_max[3];
} mrgi_las_header;

/** The points of a LAS file, recentred; the arrays are owned (malloc). */
typedef struct mrgi_las_points
{
  int64_t count;             /**< Number of points, > 0 after a successful read. */
  double origin[3];          /**< World position of the local origin (bounding-box centre). */
  float* positions;          /**< 3 * count: world position - origin. */
  uint16_t* intensity;       /**< count. */
  uint8_t* classification;   /**< count: class (0..31 for formats 0-5, 0..255 for 6-10). */
  uint8_t* return_number;    /**< count: 1-based return of the pulse (0 if the file says so). */
  uint8_t* number_of_returns;/**< count. */
  float* colors;             /**< 3 * count linear [0, 1], or NULL: the format has no RGB. */
  double bounds[6];          /**< World bounds of the points: xmin, xmax, ymin, ymax, zmin, zmax. */
} mrgi_las_points;

/** Bytes of a point record of `format` (0..10) without extra bytes; 0 for others. */
int32_t mrgi_las_record_length(int32_t format);

/**
 * @brief Read and check a LAS header from memory.
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT (see the file documentation);
 *         ::MRGI_ERR_UNSUPPORTED for LAZ; ::MRGI_ERR_INVALID_ARGUMENT for
 *         NULL arguments.
 */
mrgi_status mrgi_las_read_header_buffer(
  const void* data, size_t size, mrgi_las_header* header, mrgi_error* err);

/**
 * @brief Read every point of a LAS file held in memory.
 * @param max_points Refuse files with more points (memory bound), >= 1.
 * @param out        Receives the points; zeroed on failure. Release with
 *                   mrgi_las_points_destroy().
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT; ::MRGI_ERR_UNSUPPORTED (LAZ);
 *         ::MRGI_ERR_OUT_OF_MEMORY;
 *         ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments or max_points < 1.
 */
mrgi_status mrgi_las_read_buffer(const void* data, size_t size, int64_t max_points,
  mrgi_las_points* out, mrgi_error* err);

/**
 * @brief mrgi_las_read_buffer() on a file (regular files only,
 *        mrgi_input_map()); the message names the path.
 * @return as mrgi_las_read_buffer(), and ::MRGI_ERR_IO when it cannot be read.
 */
mrgi_status mrgi_las_read(
  const char* path, int64_t max_points, mrgi_las_points* out, mrgi_error* err);

/** @brief Free the arrays and zero the struct; NULL is a no-op. */
void mrgi_las_points_destroy(mrgi_las_points* points);

#ifdef __cplusplus
}
#endif

#endif
