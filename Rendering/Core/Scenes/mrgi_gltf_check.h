/**
 * @file mrgi_gltf_check.h
 * @brief Structural check of a glTF 2.0 file (.gltf JSON or .glb binary)
 *        before VTK's importer reads it.
 *
 * VTK 9.1's vtkGLTFDocumentLoader trusts the document: an accessor beyond
 * its buffer view, a buffer longer than its data, a missing URI, an index to
 * an object that does not exist or a node that is its own ancestor crashes
 * it (SIGSEGV, or std::bad_alloc for huge counts).
 *
 * What is checked:
 * - GLB: magic "glTF", version 2, declared length within the file, a JSON
 *   chunk first and an optional BIN chunk, both within the file;
 * - the JSON parses (nesting at most 64 deep, strings and numbers well
 *   formed) and its top is an object;
 * - buffers: byteLength >= 1; the data exist and hold byteLength bytes: a
 *   base64 data URI (decoded size), an external file (a regular file next to
 *   the glTF file, read with mrgi_input_check_regular), or for a GLB's first
 *   buffer without URI the BIN chunk; a missing URI elsewhere is an error;
 * - bufferViews: an existing buffer, byteOffset + byteLength within it,
 *   byteStride 4..252;
 * - accessors: known componentType and type, count >= 1, the last element
 *   within its bufferView (with the view's stride), sparse parts within
 *   theirs; without a bufferView, count * element size at most 2^28 bytes;
 * - at least one mesh; every mesh has primitives with a POSITION attribute;
 *   every index (attributes, indices, material, morph targets, node mesh,
 *   children, skin, scene nodes, the default scene, textures, images,
 *   samplers, skins' joints, animations' samplers and targets) names an
 *   existing object; images have a readable URI or a bufferView;
 * - the node graph has no cycle.
 * Values inside buffers (vertex indices, coordinates) are not read: the
 * caller validates what the importer returns.
 */
#ifndef MRGI_GLTF_CHECK_H
#define MRGI_GLTF_CHECK_H

#include "mrgi_error.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Deepest JSON nesting the check accepts. */
#define MRGI_GLTF_MAX_DEPTH 64

/** What the document declared. */
typedef struct mrgi_gltf_info
{
  int64_t mesh_count;
  int64_t node_count;
  int64_t accessor_count;
  int32_t binary; /**< 1 for GLB. */
} mrgi_gltf_info;

/**
 * @brief Check a glTF or GLB file held in memory (GLB when it starts with "glTF").
 * @param data The file's bytes; may be NULL when size is 0.
 * @param name Name used in messages; NULL reads "glTF data".
 * @param base_dir Folder that relative URIs are resolved in; NULL refuses
 *        every external URI (data URIs and GLB chunks still work).
 * @param info Receives counts on success; may be NULL.
 * @return ::MRGI_OK; ::MRGI_ERR_FORMAT naming the first problem found.
 */
mrgi_status mrgi_gltf_check_buffer(const void* data, size_t size, const char* name,
  const char* base_dir, mrgi_gltf_info* info, mrgi_error* err);

/** @brief mrgi_gltf_check_buffer() on the file at `path`, URIs relative to its folder. */
mrgi_status mrgi_gltf_check(const char* path, mrgi_gltf_info* info, mrgi_error* err);

#ifdef __cplusplus
}
#endif

#endif
