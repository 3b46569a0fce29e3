/**
 * @file mrgi_vtk_check.h
 * @brief Structural check of a legacy VTK file (.vtk) before VTK's reader parses it.
 *
 * VTK 9.1's legacy readers trust the counts they read: a cell list whose
 * sizes disagree with its declared total, a cell type that does not match
 * its point count, an unknown cell type or a point id out of range crashes
 * the reader or the filters after it; a huge declared count allocates (and
 * aborts) or reads for minutes.
 *
 * What is checked (ASCII and BINARY; every section header line is at most
 * 255 bytes per token):
 * - the header: "# vtk DataFile Version X.Y", a title line, ASCII|BINARY,
 *   DATASET POLYDATA | UNSTRUCTURED_GRID | STRUCTURED_POINTS |
 *   STRUCTURED_GRID | RECTILINEAR_GRID;
 * - POINTS n: n >= 0, the 3n values present (ASCII: numbers) within the file;
 * - VERTICES/LINES/POLYGONS/TRIANGLE_STRIPS/CELLS n size: in the legacy
 *   layout (version < 5) n cells whose lengths add up to exactly `size`, no
 *   negative length; in the version 5 layout (OFFSETS, CONNECTIVITY) offsets
 *   start at 0, never decrease and end at the connectivity's length; every
 *   point id in [0, points);
 * - CELL_TYPES n: n equals the cells' count; every type is one that VTK
 *   knows with a fixed point count (or a variable one: poly-vertex, poly-line,
 *   strip, polygon) and each cell has that many points; polyhedra (42) are
 *   refused;
 * - DIMENSIONS nx ny nz >= 1 with nx*ny*nz < 2^31 and an outer surface of at
 *   most ::MRGI_VTK_MAX_SURFACE_POINTS points; SPACING/ORIGIN finite;
 *   STRUCTURED_GRID's POINTS count equals nx*ny*nz, RECTILINEAR_GRID's
 *   coordinate counts equal nx, ny and nz;
 * - POINT_DATA / CELL_DATA n: n equals the points (cells); SCALARS (1 to 4
 *   components), COLOR_SCALARS, LOOKUP_TABLE, VECTORS, NORMALS,
 *   TEXTURE_COORDINATES, TENSORS, GLOBAL_IDS, PEDIGREE_IDS and FIELD arrays
 *   hold all their values within the file.
 * Checking stops, accepting the rest, at a METADATA block, at data of type
 * "bit" or "string", and at keywords it does not know; the caller must still
 * validate what the reader returns.
 */
#ifndef MRGI_VTK_CHECK_H
#define MRGI_VTK_CHECK_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Largest outer surface (points) of a structured data set the check accepts. */
#define MRGI_VTK_MAX_SURFACE_POINTS (INT64_C(1) << 27)

/** What the file declared. */
typedef struct mrgi_vtk_info
{
  int64_t point_count; /**< Points (for structured data: nx*ny*nz); 0 when none are declared. */
  int64_t cell_count;  /**< Cells of all cell sections. */
  int32_t binary;      /**< 1 for BINARY files. */
} mrgi_vtk_info;

/**
 * @brief Check a legacy VTK file held in memory.
 * @param data The file's bytes (need not be NUL-terminated); may be NULL when size is 0.
 * @param name Name used in messages; NULL reads "VTK data".
 * @param info Receives the counts on success; may be NULL.
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT naming the first problem found.
 */
mrgi_status mrgi_vtk_check_buffer(
  const void* data, size_t size, const char* name, mrgi_vtk_info* info, mrgi_error* err);

/** @brief mrgi_vtk_check_buffer() on the file at `path` (see mrgi_input_map()). */
mrgi_status mrgi_vtk_check(const char* path, mrgi_vtk_info* info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
