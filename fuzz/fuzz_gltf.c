/* fuzz_gltf.c - the glTF loader on hostile bytes (tools/pn_gltf.h trust model): it either
 * succeeds with a mesh pn_scene_set would accept index-wise, or fails with a message and
 * an all-zero mesh. Never a crash, a leak, or a half-filled mesh. */
#include <math.h>
#include <string.h>

#include "fuzz_check.h"
#include "pn_gltf.h"

#define FUZZ_MAX_TRIANGLES (1u << 16)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const pn_mesh zero;
    pn_mesh m;
    char err[256];
    uint32_t i;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    memset(&m, 0xA5, sizeof m); /* the loader must overwrite it either way */
    if (pn_gltf_load_memory_limit(data, size, FUZZ_MAX_TRIANGLES, &m, err, sizeof err) != 0) {
        FUZZ_CHECK(err[0] != '\0' && memchr(err, '\0', sizeof err), "empty or unterminated message");
        FUZZ_CHECK(memcmp(&m, &zero, sizeof m) == 0, "failed load left a non-empty mesh (%s)", err);
        return 0;
    }
    FUZZ_CHECK(m.positions && m.indices, "success with NULL arrays");
    FUZZ_CHECK(m.triangle_count >= 1 && m.triangle_count <= FUZZ_MAX_TRIANGLES, "%u triangles", m.triangle_count);
    FUZZ_CHECK(m.vertex_count >= 1 && m.vertex_count <= 3u * FUZZ_MAX_TRIANGLES, "%u vertices", m.vertex_count);
    for (i = 0; i < m.vertex_count * 3u; i++)
        FUZZ_CHECK(isfinite(m.positions[i]), "position float %u is %g", i, (double)m.positions[i]);
    for (i = 0; i < m.triangle_count * 3u; i++) {
        uint32_t v = m.indices[i], c;
        FUZZ_CHECK(v < m.vertex_count, "index %u is %u of %u vertices", i, v, m.vertex_count);
        for (c = 0; c < 3; c++) {
            lo[c] = fminf(lo[c], m.positions[v * 3u + c]);
            hi[c] = fmaxf(hi[c], m.positions[v * 3u + c]);
        }
    }
    /* bbox is "over referenced vertices": exactly their min and max (== so -0 matches 0). */
    FUZZ_CHECK(lo[0] == m.bbox_min[0] && lo[1] == m.bbox_min[1] && lo[2] == m.bbox_min[2] &&
                   hi[0] == m.bbox_max[0] && hi[1] == m.bbox_max[1] && hi[2] == m.bbox_max[2],
               "bbox (%g %g %g)-(%g %g %g) is not the referenced vertices' (%g %g %g)-(%g %g %g)",
               m.bbox_min[0], m.bbox_min[1], m.bbox_min[2], m.bbox_max[0], m.bbox_max[1], m.bbox_max[2],
               lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    pn_mesh_free(&m);
    FUZZ_CHECK(memcmp(&m, &zero, sizeof m) == 0, "pn_mesh_free did not zero the mesh");
    return 0;
}
