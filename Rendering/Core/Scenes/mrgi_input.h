/**
 * @file mrgi_input.h
 * @brief Reading untrusted input files safely: regular files only, mapped
 *        whole, and a line cursor whose lines are bounded.
 *
 * The structure checks of the file formats (mrgi_ply_check, mrgi_obj_check,
 * mrgi_vtk_check, mrgi_xml_check, mrgi_gltf_check) work on a memory buffer,
 * so that a fuzzer can call them, and on a path through mrgi_input_map().
 * A path that names a directory, a FIFO, a device (/dev/zero) or a socket is
 * refused before anything is read: reading one would hang or never end.
 */
#ifndef MRGI_INPUT_H
#define MRGI_INPUT_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Longest line any check accepts (bytes, without the newline). */
#define MRGI_INPUT_MAX_LINE (1 << 20)

/** A file mapped read-only into memory. */
typedef struct mrgi_input
{
  const unsigned char* data; /**< The file's bytes; NULL for an empty file. */
  size_t size;               /**< Its size in bytes. */
} mrgi_input;

/**
 * @brief Check that `path` names a readable, non-empty regular file (symbolic
 *        links are followed) and map it.
 * @return ::MRGI_OK; ::MRGI_ERR_IO when it does not exist, cannot be read,
 *         is a directory, FIFO, device or socket ("is a directory", ...);
 *         ::MRGI_ERR_FORMAT when it is empty; ::MRGI_ERR_INVALID_ARGUMENT for NULL arguments. The
 * message names the path. On failure `in` is left empty.
 */
mrgi_status mrgi_input_map(const char* path, mrgi_input* in, mrgi_error* err);

/** @brief Unmap what mrgi_input_map() mapped; NULL or empty is a no-op. */
void mrgi_input_unmap(mrgi_input* in);

/**
 * @brief mrgi_input_map() without keeping the mapping: only the checks that
 *        the path names a non-empty regular file.
 */
mrgi_status mrgi_input_check_regular(const char* path, mrgi_error* err);

/** A cursor over the lines of a buffer. */
typedef struct mrgi_line_cursor
{
  const unsigned char* data;
  size_t size;
  size_t pos;          /**< Offset of the next unread byte. */
  int64_t line_number; /**< Number of the line last returned (1-based). */
} mrgi_line_cursor;

/** @brief Start a cursor at the beginning of `data` (`size` bytes). */
void mrgi_line_cursor_init(mrgi_line_cursor* c, const void* data, size_t size);

/**
 * @brief Copy the next line into `line` (NUL-terminated, without "\n" and a
 *        trailing "\r"); NUL bytes in it become spaces.
 * @param capacity Size of `line`; a line longer than `capacity - 1` is an error.
 * @return 1 with a line, 0 at the end of the buffer, -1 for a line too long
 *         (the cursor is then left at that line).
 */
int mrgi_line_next(mrgi_line_cursor* c, char* line, size_t capacity);

#ifdef __cplusplus
}
#endif

#endif
