/* pn_mesh.h - host-side triangle mesh shared by the CLI, the glTF loader, the built-in
 * scenes, tests and benchmarks. Not part of the library: firmware never sees it.
 *
 * Memory: positions and indices are heap-allocated by whoever fills the mesh; release
 * them with pn_mesh_free(). All functions here return 0 on success and a non-zero code
 * with a message in err (if err != NULL) on failure; on failure *mesh is left empty. */
#ifndef PN_TOOLS_MESH_H
#define PN_TOOLS_MESH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pn_mesh {
    float *positions;        /* vertex_count * 3 floats, xyz, world space */
    uint32_t vertex_count;
    uint32_t *indices;       /* triangle_count * 3, each < vertex_count */
    uint32_t triangle_count;
    float bbox_min[3];       /* over referenced vertices; all zero for an empty mesh */
    float bbox_max[3];
    /* Triangles [receiver_first, receiver_first + receiver_count) are pure receivers:
     * ground planes and floors, with nothing beneath them but the underside of the solid
     * they top, if any, so they shadow nothing. pn_setup_upload() hands the range to
     * pn_scene_set_receivers(), which keeps them out of the Monte Carlo shadow maps' depth
     * layers (every other algorithm ignores it). receiver_count = 0: none (what the glTF
     * loader gives, and any zeroed mesh). Set by the built-in scenes (pn_scenes.h) and by
     * pn_mesh_add_ground(); first + count <= triangle_count whenever count > 0. */
    uint32_t receiver_first, receiver_count;
} pn_mesh;

/* Formats a message into err (if err != NULL and err_size > 0); shared by the tools. */
void pn_tools_err(char *err, size_t err_size, const char *fmt, ...);

/* lowbias32 (C. Wellons): a full-avalanche integer hash, the tools' one source of
 * deterministic pseudo-randomness (built-in scenes, the PCSS baseline's tap rotation). */
uint32_t pn_hash32(uint32_t x);

/* Frees the arrays and zeroes the struct. NULL and an empty mesh are fine. */
void pn_mesh_free(pn_mesh *mesh);

/* Recomputes bbox_min/bbox_max from the vertices referenced by indices. */
void pn_mesh_update_bbox(pn_mesh *mesh);

/* Appends the ground plane of the CLI conventions: two triangles at
 * y = bbox_min.y - 1e-3*diag spanning centre +- 2*diag in x and z, where diag is the
 * bounding-box diagonal of the mesh *before* the call. Their normals face +y (CCW seen
 * from above). bbox is not updated (the ground is not part of the scene bounds).
 * The receiver range becomes the two new triangles; if the mesh already had a non-empty
 * range ending at its last triangle (a built-in scene's own ground), the range is
 * extended over the two new ones instead, so both planes stay receivers.
 * Returns 0, or non-zero on allocation failure / empty mesh. */
int pn_mesh_add_ground(pn_mesh *mesh, char *err, size_t err_size);

/* Bounding-box diagonal length. */
float pn_mesh_diag(const pn_mesh *mesh);

#ifdef __cplusplus
}
#endif
#endif
