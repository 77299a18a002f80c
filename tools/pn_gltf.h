/* pn_gltf.h - glTF 2.0 loading into a pn_mesh (host tools only; C interface over a C++
 * shim around tinygltf).
 *
 * What is loaded: every primitive with mode 4 (triangles) of every mesh reachable from
 * the default scene's node hierarchy, or from all root nodes (nodes that are nobody's
 * child) when the file names no default scene. Node transforms (matrix, or
 * translation * rotation * scale) are composed down the hierarchy and applied, so
 * positions come out in world space. Other primitive modes are skipped. Triangles are
 * appended in depth-first node order (a node before its children, children and scene
 * roots in file order), then primitive order; that order defines the triangle ids. Every
 * (node, primitive) pair gets its own copy of the vertices, so a mesh used by two nodes
 * appears twice; a primitive with no triangles contributes no vertices either.
 *
 * Trust model: the file is hostile input. Missing or unreadable files, wrong magic,
 * truncated or inconsistent GLB chunks, JSON errors, nesting deeper than
 * PN_GLTF_MAX_JSON_DEPTH, required extensions, sparse accessors, accessors or buffer
 * views outside their buffer, index types other than u8/u16/u32, POSITION that is not
 * float VEC3, indices >= the primitive's vertex count, NaN/Inf positions (before or after
 * the transform), node cycles or shared nodes, invalid transforms, more than
 * PN_GLTF_MAX_TRIANGLES triangles or PN_GLTF_MAX_VERTICES vertices, and a result with no
 * triangles all return non-zero with a message in err. The loader never crashes or leaks
 * on such input.
 *
 * Memory: on success *out owns malloc'd arrays (release with pn_mesh_free) and its bbox
 * is current. On failure *out is zeroed. err may be NULL; otherwise it receives a
 * NUL-terminated message, truncated to err_size. */
#ifndef PN_TOOLS_GLTF_H
#define PN_TOOLS_GLTF_H

#include <stddef.h>
#include <stdint.h>

#include "pn_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Same bound as the library's PN_MAX_TRIANGLES range (BVH indices fit 32 bits). */
#define PN_GLTF_MAX_TRIANGLES (1u << 26)
/* More vertices than three per triangle cannot all be referenced. */
#define PN_GLTF_MAX_VERTICES (3u << 26)
/* tinygltf converts JSON values recursively; deeper nesting than this is refused before
 * parsing so hostile input cannot exhaust the stack. */
#define PN_GLTF_MAX_JSON_DEPTH 64

/* Loads a .glb (binary) or .gltf (JSON, external or data-URI buffers relative to the
 * file's directory). The kind is chosen by extension (case-insensitive), or by the
 * "glTF" magic when the extension is neither. Returns 0 on success. */
int pn_gltf_load(const char *path, pn_mesh *out, char *err, size_t err_size);

/* Loads a binary glTF (.glb) from memory, for fuzzing. External file references (buffer or
 * image URIs that are not data: URIs) are refused: nothing outside `data` is read.
 * Returns 0 on success. */
int pn_gltf_load_memory(const unsigned char *data, size_t size, pn_mesh *out, char *err,
                        size_t err_size);

/* pn_gltf_load_memory with a lower triangle limit (1 .. PN_GLTF_MAX_TRIANGLES; the vertex
 * limit becomes 3 * max_triangles). Node instancing lets a file of a few hundred KB expand
 * to the full 2^26 triangles (gigabytes of mesh); fuzz targets use this to stay fast. */
int pn_gltf_load_memory_limit(const unsigned char *data, size_t size, uint32_t max_triangles,
                              pn_mesh *out, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif
#endif
