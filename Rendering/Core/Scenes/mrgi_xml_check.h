/**
 * @file mrgi_xml_check.h
 * @brief Structural check of a VTK XML file (.vtp .vtu .vti .vts .vtr .vtm)
 *        before VTK's XML readers parse it.
 *
 * VTK 9.1's XML readers allocate what the attributes declare (points,
 * cells, extents, components) and read appended data at the offsets given:
 * huge declarations abort (std::bad_alloc) or run for minutes, and offsets
 * beyond the file read garbage.
 *
 * What is checked, tag by tag (no full XML parse: tags are scanned, text
 * between them is skipped):
 * - a VTKFile element exists; header_type, if given, is UInt32 or UInt64;
 *   byte_order, if given, is LittleEndian or BigEndian;
 * - tags are at most ::MRGI_XML_MAX_TAG bytes and nest at most
 *   ::MRGI_XML_MAX_DEPTH deep;
 * - Piece: NumberOfPoints/Cells/Verts/Lines/Strips/Polys are integers in
 *   [0, ::MRGI_XML_MAX_ITEMS]; Extent and WholeExtent are 6 integers, each
 *   range non-negative in length (or empty by one), with at most
 *   ::MRGI_XML_MAX_ITEMS points;
 * - DataArray: a known type, NumberOfComponents in [1, 4096],
 *   NumberOfTuples in [0, ::MRGI_XML_MAX_ITEMS], format ascii, binary or
 *   appended; appended arrays need an AppendedData element, their offset
 *   lies within its data and, for raw uncompressed data, the block's
 *   declared size (its header) fits in what follows.
 * Values (inline or appended) are not decoded: the caller validates what
 * the reader returns (point ids, offsets, NaN coordinates).
 */
#ifndef MRGI_XML_CHECK_H
#define MRGI_XML_CHECK_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Longest tag (from '<' to '>') the check accepts. */
#define MRGI_XML_MAX_TAG (1 << 16)
/** Deepest nesting of elements the check accepts. */
#define MRGI_XML_MAX_DEPTH 256
/** Most points, cells or tuples one piece or array may declare. */
#define MRGI_XML_MAX_ITEMS (INT64_C(1) << 28)

/**
 * @brief Check a VTK XML file held in memory.
 * @param data The file's bytes; may be NULL when size is 0.
 * @param name Name used in messages; NULL reads "VTK XML data".
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT naming the first problem found.
 */
mrgi_status mrgi_xml_check_buffer(const void* data, size_t size, const char* name, mrgi_error* err);

/** @brief mrgi_xml_check_buffer() on the file at `path` (see mrgi_input_map()). */
mrgi_status mrgi_xml_check(const char* path, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
