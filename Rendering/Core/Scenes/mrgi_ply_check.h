/**
 * @file mrgi_ply_check.h
 * @brief Structural check of a PLY file before a PLY reader parses it.
 *
 * VTK 9.1's vtkPLYReader crashes on some malformed headers (a "vertex"
 * element without y or z dereferences a missing property) and silently
 * returns partial data for truncated bodies. MRGI checks a file with this
 * function first and reports what is wrong in one line.
 *
 * What is checked:
 * - the magic line "ply" and a "format ascii|binary_little_endian|
 *   binary_big_endian 1.0" line;
 * - every "element NAME COUNT" has a count in [0, 2^31) and every property a
 *   known type (char uchar short ushort int uint float double and their
 *   int8..float64 aliases; lists with an integer count type);
 * - a "vertex" element exists and has x, y and z properties;
 * - the header ends with "end_header" within MRGI_PLY_MAX_HEADER_BYTES;
 * - header lines are at most 4096 bytes (a file without newlines, such as
 *   /dev/zero's contents, is refused, not read forever);
 * - the body is read element by element: every value is present (ASCII: one
 *   non-empty line per instance holding numbers for every property, lists
 *   included; binary: the bytes of every property, lists by their count,
 *   within the file), list counts are not negative, and every entry of the
 *   face element's "vertex_indices" (or "vertex_index") lists lies in
 *   [0, vertex count): VTK 9.1's reader and the filters after it crash on
 *   out-of-range indices and on list counts beyond the data.
 *
 * mrgi_ply_check() maps the file with mrgi_input_map() (regular files only)
 * and calls mrgi_ply_check_buffer(), which a fuzzer can call directly.
 */
#ifndef MRGI_PLY_CHECK_H
#define MRGI_PLY_CHECK_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest header the check reads before giving up on "end_header". */
#define MRGI_PLY_MAX_HEADER_BYTES (1 << 20)

/** What the header declared, for messages and statistics. */
typedef struct mrgi_ply_info
{
  int64_t vertex_count; /**< Instances of the "vertex" element. */
  int64_t face_count;   /**< Instances of the "face" element, 0 when absent. */
  int32_t binary;       /**< 0 = ascii, 1 = binary (either byte order). */
} mrgi_ply_info;

/**
 * @brief Check that `path` is a structurally sound PLY file.
 * @param path Path of the file; must not be NULL.
 * @param info Receives the declared counts; may be NULL.
 * @return ::MRGI_OK; ::MRGI_ERR_IO when the file cannot be opened or read;
 *         ::MRGI_ERR_FORMAT naming the first problem found;
 *         ::MRGI_ERR_INVALID_ARGUMENT for a NULL path.
 */
mrgi_status mrgi_ply_check(const char* path, mrgi_ply_info* info, mrgi_error* err);

/**
 * @brief The same check on a PLY file held in memory.
 * @param data The file's bytes (need not be NUL-terminated); may be NULL when size is 0.
 * @param name Name used in messages; NULL reads "PLY data".
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT naming the first problem found.
 */
mrgi_status mrgi_ply_check_buffer(
  const void* data, size_t size, const char* name, mrgi_ply_info* info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
