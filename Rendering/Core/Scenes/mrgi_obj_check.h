/**
 * @file mrgi_obj_check.h
 * @brief Structural check of a Wavefront OBJ file before VTK's reader parses it.
 *
 * VTK 9.1's vtkOBJReader indexes its point, texture-coordinate and normal
 * arrays with the face indices as written: an index out of range, 0, a
 * relative (negative) index reaching before the first vertex, or a "1/1"
 * reference when the file has no "vt" crashes it (SIGSEGV/SIGABRT).
 *
 * What is checked, line by line (lines at most ::MRGI_INPUT_MAX_LINE bytes):
 * - "v", "vt", "vn" lines hold at least 3, 1 and 3 numbers (strtod; "nan"
 *   and "inf" parse; whether they are finite is left to the caller);
 * - "f" (at least 3 references), "l" (2) and "p" (1) lines: every reference
 *   is v, v/t, v//n or v/t/n with integer indices that are not 0, not
 *   beyond the vertices (texture coordinates, normals) declared so far when
 *   negative (relative) and not beyond those of the whole file when positive;
 * - the file declares at least one vertex.
 * Other lines (g, o, s, usemtl, mtllib, comments) are not checked.
 */
#ifndef MRGI_OBJ_CHECK_H
#define MRGI_OBJ_CHECK_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** What the file declared. */
typedef struct mrgi_obj_info
{
  int64_t vertex_count; /**< "v" lines. */
  int64_t face_count;   /**< "f" lines. */
} mrgi_obj_info;

/**
 * @brief Check an OBJ file held in memory.
 * @param data The file's bytes (need not be NUL-terminated); may be NULL when size is 0.
 * @param name Name used in messages (e.g. the path); NULL reads "OBJ data".
 * @param info Receives the counts on success; may be NULL.
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT naming the line and problem.
 */
mrgi_status mrgi_obj_check_buffer(
  const void* data, size_t size, const char* name, mrgi_obj_info* info, mrgi_error* err);

/** @brief mrgi_obj_check_buffer() on the file at `path` (see mrgi_input_map()). */
mrgi_status mrgi_obj_check(const char* path, mrgi_obj_info* info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
