/**
 * @file mrgi_pcd_check.h
 * @brief Structural check of a PCL PCD file before PCL's reader parses it.
 *
 * PCL 1.13's pcl::PCDReader crashes (SIGSEGV) on an empty file and on a
 * header without FIELDS; it allocates WIDTH x HEIGHT x record bytes before
 * reading a body (a header declaring 2e9 points asks for 24 GB, a
 * binary_compressed body declaring 4 GiB uncompressed asks for 4 GiB), and
 * it returns success with silently wrong data for ASCII bodies with missing
 * or non-numeric values, unknown TYPE letters and SIZEs that do not fit
 * their TYPE. MRGI checks a file with this function first and reports what
 * is wrong in one line (probed case by case: Documentation/reliability/pcl.md).
 *
 * What is checked:
 * - header lines (comments "#..." and empty lines skipped) are at most
 *   MRGI_PCD_MAX_LINE bytes, the header ends with a DATA line within
 *   MRGI_PCD_MAX_HEADER_BYTES; keys other than VERSION FIELDS SIZE TYPE
 *   COUNT WIDTH HEIGHT VIEWPOINT POINTS DATA are refused;
 * - FIELDS names 1..MRGI_PCD_MAX_FIELDS fields; SIZE, TYPE and (optional,
 *   default 1 each) COUNT give one value per field; TYPE is F, I or U; SIZE
 *   is 4 or 8 for F and 1, 2, 4 or 8 for I and U; COUNT is in
 *   [1, MRGI_PCD_MAX_COUNT]; a point record is at most MRGI_PCD_MAX_RECORD
 *   bytes;
 * - fields x, y and z exist, each TYPE F with COUNT 1;
 * - WIDTH and POINTS are decimal integers in [1, max_points], HEIGHT
 *   (optional, default 1) in [1, max_points], WIDTH x HEIGHT = POINTS;
 * - VIEWPOINT, when present, is 7 finite numbers (translation, quaternion
 *   w x y z);
 * - DATA is ascii, binary or binary_compressed, and the body holds the
 *   points: ASCII has exactly POINTS non-empty lines, each with one number
 *   per value (the sum of the COUNTs; nan and inf are numbers), and nothing
 *   but white space after them; binary has POINTS x record bytes after the
 *   header; binary_compressed has its two 32-bit sizes, a compressed size
 *   in [1, rest of the file], an uncompressed size equal to POINTS x record
 *   and at most MRGI_PCD_MAX_LZF_RATIO times the compressed size (LZF cannot
 *   expand more), so PCL's allocation is bounded by the file's size.
 *   The LZF stream itself is left to PCL, which refuses a corrupt one.
 *
 * mrgi_pcd_check() maps the file with mrgi_input_map() (regular files only)
 * and calls mrgi_pcd_check_buffer(), which a fuzzer can call directly.
 */
#ifndef MRGI_PCD_CHECK_H
#define MRGI_PCD_CHECK_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest header (bytes up to and including the DATA line). */
#define MRGI_PCD_MAX_HEADER_BYTES (1 << 20)
/** Longest header line. */
#define MRGI_PCD_MAX_LINE 65536
/** Most fields a point may have. */
#define MRGI_PCD_MAX_FIELDS 256
/** Largest COUNT of one field. */
#define MRGI_PCD_MAX_COUNT 65536
/** Largest point record in bytes. */
#define MRGI_PCD_MAX_RECORD (1 << 20)
/** Largest uncompressed / compressed size of a binary_compressed body. */
#define MRGI_PCD_MAX_LZF_RATIO 100

/** How the body is stored. */
typedef enum mrgi_pcd_data
{
  MRGI_PCD_ASCII = 0,
  MRGI_PCD_BINARY = 1,
  MRGI_PCD_BINARY_COMPRESSED = 2
} mrgi_pcd_data;

/** What the header declared. */
typedef struct mrgi_pcd_info
{
  int64_t width;         /**< WIDTH. */
  int64_t height;        /**< HEIGHT (1: unorganized). */
  int64_t points;        /**< POINTS = width * height. */
  mrgi_pcd_data data;    /**< DATA. */
  int32_t field_count;   /**< Number of FIELDS. */
  int32_t record_size;   /**< Bytes per point (binary layouts). */
  int32_t has_viewpoint; /**< 1 when a VIEWPOINT line was present. */
  double viewpoint[7];   /**< tx ty tz qw qx qy qz; 0 0 0 1 0 0 0 when absent. */
  int64_t header_size;   /**< Offset of the body in bytes. */
} mrgi_pcd_info;

/**
 * @brief Check that `path` is a structurally sound PCD file.
 * @param max_points Refuse files declaring more points (memory bound), >= 1.
 * @param info       Receives what the header declared; may be NULL.
 * @return ::MRGI_OK; ::MRGI_ERR_IO when the file cannot be opened or read;
 *         ::MRGI_ERR_FORMAT naming the file and the first problem found;
 *         ::MRGI_ERR_INVALID_ARGUMENT for a NULL path or max_points < 1.
 */
mrgi_status mrgi_pcd_check(
  const char* path, int64_t max_points, mrgi_pcd_info* info, mrgi_error* err);

/**
 * @brief The same check on a PCD file held in memory.
 * @param data The file's bytes (need not be NUL-terminated); may be NULL when size is 0.
 * @param name Name used in messages; NULL reads "PCD data".
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT naming the first problem found;
 *         ::MRGI_ERR_INVALID_ARGUMENT for max_points < 1;
 *         ::MRGI_ERR_OUT_OF_MEMORY.
 */
mrgi_status mrgi_pcd_check_buffer(const void* data, size_t size, const char* name,
  int64_t max_points, mrgi_pcd_info* info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
