// pn_gltf_model.cpp - the glTF loader's work on the parsed model (see pn_gltf.cpp): the node
// graph walked into world-space instances, every accessor and buffer view range-checked
// against its buffer, and the triangles baked into one pn_mesh.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "pn_gltf.h"
#include "pn_gltf_internal.h"

namespace pn_gltf_impl {

namespace {

// ---- node hierarchy ----

struct pn_instance {
    int node;
    int mesh;
    double m[16];  // world matrix, column-major
};

void pn_mat_identity(double m[16])
{
    for (int i = 0; i < 16; i++) {
        m[i] = (i % 5 == 0) ? 1.0 : 0.0;
    }
}

bool pn_mat_is_identity(const double m[16])
{
    for (int i = 0; i < 16; i++) {
        if (m[i] != ((i % 5 == 0) ? 1.0 : 0.0)) {
            return false;
        }
    }
    return true;
}

void pn_mat_mul(const double a[16], const double b[16], double r[16])
{
    for (int c = 0; c < 4; c++) {
        for (int row = 0; row < 4; row++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) {
                s += a[k * 4 + row] * b[c * 4 + k];
            }
            r[c * 4 + row] = s;
        }
    }
}

bool pn_all_finite(const std::vector<double> &v)
{
    for (double x : v) {
        if (!std::isfinite(x)) {
            return false;
        }
    }
    return true;
}

bool pn_node_local(const tinygltf::Node &n, int idx, double m[16], std::string *why)
{
    if (!pn_all_finite(n.matrix) || !pn_all_finite(n.translation) ||
        !pn_all_finite(n.rotation) || !pn_all_finite(n.scale)) {
        *why = pn_strf("node %d: transform has a non-finite number", idx);
        return false;
    }
    if (!n.matrix.empty()) {
        // The spec forbids matrix together with TRS; if both appear, the matrix wins.
        if (n.matrix.size() != 16) {
            *why = pn_strf("node %d: matrix has %zu numbers, need 16", idx, n.matrix.size());
            return false;
        }
        for (int i = 0; i < 16; i++) {
            m[i] = n.matrix[(size_t)i];
        }
        return true;
    }
    if ((!n.translation.empty() && n.translation.size() != 3) ||
        (!n.rotation.empty() && n.rotation.size() != 4) ||
        (!n.scale.empty() && n.scale.size() != 3)) {
        *why = pn_strf("node %d: translation/rotation/scale need 3/4/3 numbers", idx);
        return false;
    }
    double t[3] = {0.0, 0.0, 0.0}, s[3] = {1.0, 1.0, 1.0};
    double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
    if (!n.translation.empty()) {
        for (int i = 0; i < 3; i++) t[i] = n.translation[(size_t)i];
    }
    if (!n.scale.empty()) {
        for (int i = 0; i < 3; i++) s[i] = n.scale[(size_t)i];
    }
    if (!n.rotation.empty()) {
        x = n.rotation[0];
        y = n.rotation[1];
        z = n.rotation[2];
        w = n.rotation[3];
        // Exporters write unit quaternions to float precision; renormalise so the rotation
        // part stays orthonormal, and refuse a zero quaternion (no rotation at all).
        double len = std::sqrt(x * x + y * y + z * z + w * w);
        if (!(len > 1e-12) || !std::isfinite(len)) {
            *why = pn_strf("node %d: rotation quaternion has length %g", idx, len);
            return false;
        }
        x /= len;
        y /= len;
        z /= len;
        w /= len;
    }
    // M = T * R * S, column-major.
    double r[9] = {1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + z * w), 2.0 * (x * z - y * w),
                   2.0 * (x * y - z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + x * w),
                   2.0 * (x * z + y * w), 2.0 * (y * z - x * w), 1.0 - 2.0 * (x * x + y * y)};
    for (int c = 0; c < 3; c++) {
        for (int row = 0; row < 3; row++) {
            m[c * 4 + row] = r[c * 3 + row] * s[c];
        }
        m[c * 4 + 3] = 0.0;
    }
    m[12] = t[0];
    m[13] = t[1];
    m[14] = t[2];
    m[15] = 1.0;
    return true;
}

// Depth-first, pre-order walk with an explicit stack (no recursion: depth follows the file).
// Each node may be visited once: the spec requires disjoint strict trees, and visiting once
// both rejects cycles and bounds the work by the node count.
bool pn_collect_instances(const tinygltf::Model &model, std::vector<pn_instance> *out,
                          std::string *why)
{
    const size_t n = model.nodes.size();
    std::vector<int> roots;
    if (model.defaultScene >= 0) {
        if ((size_t)model.defaultScene >= model.scenes.size()) {
            *why = pn_strf("default scene %d does not exist (%zu scenes)", model.defaultScene,
                           model.scenes.size());
            return false;
        }
        roots = model.scenes[(size_t)model.defaultScene].nodes;
    } else if (model.defaultScene == -1) {
        std::vector<unsigned char> is_child(n, 0);
        for (size_t i = 0; i < n; i++) {
            for (int c : model.nodes[i].children) {
                if (c < 0 || (size_t)c >= n) {
                    *why = pn_strf("node %zu has child %d, but there are %zu nodes", i, c, n);
                    return false;
                }
                is_child[(size_t)c] = 1;
            }
        }
        for (size_t i = 0; i < n; i++) {
            if (!is_child[i]) {
                roots.push_back((int)i);
            }
        }
    } else {
        *why = pn_strf("invalid default scene index %d", model.defaultScene);
        return false;
    }

    struct frame {
        int node;
        int parent;  // -1 for a scene root
        double m[16];
    };
    std::vector<frame> stack;
    std::vector<unsigned char> visited(n, 0);
    frame f;
    pn_mat_identity(f.m);
    f.parent = -1;
    for (size_t i = roots.size(); i-- > 0;) {
        f.node = roots[i];
        stack.push_back(f);
    }
    while (!stack.empty()) {
        f = stack.back();
        stack.pop_back();
        if (f.node < 0 || (size_t)f.node >= n) {
            if (f.parent < 0) {
                *why = pn_strf("scene references node %d, but there are %zu nodes", f.node, n);
            } else {
                *why = pn_strf("node %d has child %d, but there are %zu nodes", f.parent,
                               f.node, n);
            }
            return false;
        }
        if (visited[(size_t)f.node]) {
            *why = pn_strf("node %d is reached twice (a cycle, or a node with two parents)",
                           f.node);
            return false;
        }
        visited[(size_t)f.node] = 1;
        const tinygltf::Node &node = model.nodes[(size_t)f.node];
        double local[16], world[16];
        if (!pn_node_local(node, f.node, local, why)) {
            return false;
        }
        pn_mat_mul(f.m, local, world);
        for (int i = 0; i < 16; i++) {
            if (!std::isfinite(world[i])) {
                *why = pn_strf("node %d: world transform overflows", f.node);
                return false;
            }
        }
        if (node.mesh >= 0) {
            if ((size_t)node.mesh >= model.meshes.size()) {
                *why = pn_strf("node %d references mesh %d, but there are %zu meshes", f.node,
                               node.mesh, model.meshes.size());
                return false;
            }
            pn_instance inst;
            inst.node = f.node;
            inst.mesh = node.mesh;
            std::memcpy(inst.m, world, sizeof world);
            out->push_back(inst);
        } else if (node.mesh != -1) {
            *why = pn_strf("node %d references mesh %d", f.node, node.mesh);
            return false;
        }
        frame child;
        child.parent = f.node;
        std::memcpy(child.m, world, sizeof world);
        for (size_t i = node.children.size(); i-- > 0;) {
            child.node = node.children[i];
            stack.push_back(child);
        }
    }
    return true;
}

// ---- accessors ----

struct pn_view {
    const unsigned char *base;  // first element
    size_t stride;              // bytes between elements
    size_t count;
    int component_type;
};

// Resolves an accessor to bytes inside its buffer, checking every offset and length.
bool pn_accessor_view(const tinygltf::Model &model, int index, int want_type, size_t comp_size,
                      pn_view *v, const char *what, std::string *why)
{
    if (index < 0 || (size_t)index >= model.accessors.size()) {
        *why = pn_strf("%s accessor %d does not exist (%zu accessors)", what, index,
                       model.accessors.size());
        return false;
    }
    const tinygltf::Accessor &a = model.accessors[(size_t)index];
    if (a.sparse.isSparse) {
        *why = pn_strf("%s accessor %d is sparse (not supported)", what, index);
        return false;
    }
    if (a.type != want_type) {
        *why = pn_strf("%s accessor %d has type %d, need %s", what, index, a.type,
                       want_type == TINYGLTF_TYPE_VEC3 ? "VEC3" : "SCALAR");
        return false;
    }
    if (a.bufferView < 0 || (size_t)a.bufferView >= model.bufferViews.size()) {
        *why = pn_strf("%s accessor %d has no valid bufferView (%d)", what, index, a.bufferView);
        return false;
    }
    const tinygltf::BufferView &bv = model.bufferViews[(size_t)a.bufferView];
    if (bv.buffer < 0 || (size_t)bv.buffer >= model.buffers.size()) {
        *why = pn_strf("bufferView %d references buffer %d, but there are %zu buffers",
                       a.bufferView, bv.buffer, model.buffers.size());
        return false;
    }
    const size_t buf_size = model.buffers[(size_t)bv.buffer].data.size();
    if (bv.byteOffset > buf_size || bv.byteLength > buf_size - bv.byteOffset) {
        *why = pn_strf("bufferView %d (offset %zu, length %zu) lies outside buffer %d "
                       "(%zu bytes)",
                       a.bufferView, bv.byteOffset, bv.byteLength, bv.buffer, buf_size);
        return false;
    }
    const size_t ncomp = want_type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
    const size_t elem = ncomp * comp_size;
    const size_t stride = bv.byteStride ? bv.byteStride : elem;
    if (stride < elem || stride > 252) {
        *why = pn_strf("bufferView %d has byteStride %zu (element is %zu bytes, maximum 252)",
                       a.bufferView, bv.byteStride, elem);
        return false;
    }
    // count <= byteLength keeps stride * count far from overflow (stride <= 252).
    if (a.byteOffset > bv.byteLength || a.count > bv.byteLength) {
        *why = pn_strf("%s accessor %d (offset %zu, %zu elements) runs past the end of "
                       "bufferView %d (%zu bytes)",
                       what, index, a.byteOffset, a.count, a.bufferView, bv.byteLength);
        return false;
    }
    if (a.count > 0) {
        uint64_t span = (uint64_t)stride * (uint64_t)(a.count - 1) + elem;
        if (span > (uint64_t)(bv.byteLength - a.byteOffset)) {
            *why = pn_strf("%s accessor %d (offset %zu, %zu elements of %zu bytes, stride %zu) "
                           "runs past the end of bufferView %d (%zu bytes)",
                           what, index, a.byteOffset, a.count, elem, stride, a.bufferView,
                           bv.byteLength);
            return false;
        }
    }
    v->base = model.buffers[(size_t)bv.buffer].data.data() + bv.byteOffset + a.byteOffset;
    v->stride = stride;
    v->count = a.count;
    v->component_type = a.componentType;
    return true;
}

size_t pn_index_size(int component_type)
{
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return 4;
    default: return 0;
    }
}

struct pn_prim_views {
    pn_view pos;
    bool pos_normalized;  // integer positions (KHR_mesh_quantization) mapped to [-1, 1] or [0, 1]
    pn_view idx;
    bool indexed;
    int mode;             // 4 triangles, 5 strip, 6 fan
    size_t triangles;
};

// Bytes per component of a POSITION accessor: float, or with KHR_mesh_quantization (used by
// the file) a signed or unsigned byte or short; 0 for anything else.
size_t pn_position_size(int component_type, bool quantized)
{
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return quantized ? 1 : 0;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return quantized ? 2 : 0;
    default: return 0;
    }
}

// The triangles of a list of n elements in mode 4 (triangles), 5 (strip) or 6 (fan).
size_t pn_mode_triangles(int mode, size_t n)
{
    if (mode == TINYGLTF_MODE_TRIANGLES) return n / 3;
    return n >= 3 ? n - 2 : 0;
}

// Validates one primitive's accessors (modes 4, 5 and 6; the caller filters).
bool pn_prim_views_get(const tinygltf::Model &model, int mesh, size_t p, bool quantized,
                       pn_prim_views *pv, std::string *why)
{
    const tinygltf::Primitive &prim = model.meshes[(size_t)mesh].primitives[p];
    char what[96];
    auto it = prim.attributes.find("POSITION");
    if (it == prim.attributes.end()) {
        *why = pn_strf("mesh %d primitive %zu has no POSITION attribute", mesh, p);
        return false;
    }
    std::snprintf(what, sizeof what, "mesh %d primitive %zu POSITION", mesh, p);
    size_t psz = 4;
    pv->pos_normalized = false;
    if (it->second >= 0 && (size_t)it->second < model.accessors.size()) {
        const tinygltf::Accessor &a = model.accessors[(size_t)it->second];
        psz = pn_position_size(a.componentType, quantized);
        if (psz == 0) {
            *why = pn_strf("%s accessor %d has componentType %d, need float (5126)%s", what,
                           it->second, a.componentType,
                           quantized ? " or a byte or short (5120-5123)"
                                     : " (integer positions need KHR_mesh_quantization)");
            return false;
        }
        pv->pos_normalized = psz < 4 && a.normalized;
    }
    if (!pn_accessor_view(model, it->second, TINYGLTF_TYPE_VEC3, psz, &pv->pos, what, why)) {
        return false;
    }
    pv->mode = prim.mode;
    pv->indexed = prim.indices >= 0;
    if (pv->indexed) {
        std::snprintf(what, sizeof what, "mesh %d primitive %zu indices", mesh, p);
        if ((size_t)prim.indices >= model.accessors.size()) {
            *why = pn_strf("%s accessor %d does not exist (%zu accessors)", what, prim.indices,
                           model.accessors.size());
            return false;
        }
        int ct = model.accessors[(size_t)prim.indices].componentType;
        size_t isz = pn_index_size(ct);
        if (isz == 0) {
            *why = pn_strf("%s accessor %d has componentType %d, need unsigned byte, short "
                           "or int (5121/5123/5125)",
                           what, prim.indices, ct);
            return false;
        }
        if (!pn_accessor_view(model, prim.indices, TINYGLTF_TYPE_SCALAR, isz, &pv->idx, what,
                              why)) {
            return false;
        }
        if (prim.mode == TINYGLTF_MODE_TRIANGLES && pv->idx.count % 3 != 0) {
            *why = pn_strf("%s: %zu indices is not a multiple of 3", what, pv->idx.count);
            return false;
        }
        pv->triangles = pn_mode_triangles(prim.mode, pv->idx.count);
    } else {
        if (prim.indices != -1) {
            *why = pn_strf("mesh %d primitive %zu has indices %d", mesh, p, prim.indices);
            return false;
        }
        if (prim.mode == TINYGLTF_MODE_TRIANGLES && pv->pos.count % 3 != 0) {
            *why = pn_strf("mesh %d primitive %zu is not indexed and has %zu vertices, not a "
                           "multiple of 3",
                           mesh, p, pv->pos.count);
            return false;
        }
        pv->triangles = pn_mode_triangles(prim.mode, pv->pos.count);
    }
    return true;
}

float pn_read_f32(const unsigned char *p)
{
    uint32_t u = pn_le32(p);
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

// Component k of a POSITION element: a float as stored, or an integer of
// KHR_mesh_quantization, normalized as the glTF specification maps it (signed: c / max,
// at least -1; unsigned: c / max).
double pn_read_position(const unsigned char *e, int component_type, bool normalized, int k)
{
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        double c = (double)(int8_t)e[k];
        return normalized ? std::fmax(c / 127.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        double c = (double)e[k];
        return normalized ? c / 255.0 : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const unsigned char *q = e + 2 * k;
        double c = (double)(int16_t)(uint16_t)((uint32_t)q[0] | ((uint32_t)q[1] << 8));
        return normalized ? std::fmax(c / 32767.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const unsigned char *q = e + 2 * k;
        double c = (double)((uint32_t)q[0] | ((uint32_t)q[1] << 8));
        return normalized ? c / 65535.0 : c;
    }
    default: return (double)pn_read_f32(e + 4 * k);
    }
}

uint32_t pn_read_index(const unsigned char *p, size_t size)
{
    if (size == 1) return p[0];
    if (size == 2) return (uint32_t)p[0] | ((uint32_t)p[1] << 8);
    return pn_le32(p);
}

// Element j of a primitive's list: its index, or j where it has none.
uint32_t pn_prim_element(const pn_prim_views &pv, size_t j)
{
    if (!pv.indexed) return (uint32_t)j;
    return pn_read_index(pv.idx.base + j * pv.idx.stride, pn_index_size(pv.idx.component_type));
}

// The elements of triangle t of the primitive's mode, as the glTF specification orders them
// (strip: t even (t, t+1, t+2), t odd (t, t+2, t+1); fan: (t+1, t+2, 0)).
void pn_prim_triangle(int mode, size_t t, size_t e[3])
{
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        e[0] = t;
        e[1] = t + 1 + (t & 1u);
        e[2] = t + 2 - (t & 1u);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        e[0] = t + 1;
        e[1] = t + 2;
        e[2] = 0;
    } else {
        e[0] = 3 * t;
        e[1] = 3 * t + 1;
        e[2] = 3 * t + 2;
    }
}

// Whether the world matrix mirrors (the determinant of its 3 x 3 part is negative): the
// glTF specification then makes the triangles' front faces clockwise, so their winding is
// reversed to keep the counter-clockwise front the library's approximations read.
bool pn_mat_mirrors(const double m[16])
{
    double det = m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
                 m[8] * (m[1] * m[6] - m[5] * m[2]);
    return det < 0.0;
}


// Required extensions that only affect appearance are harmless for shadows, and
// KHR_mesh_quantization's integer positions are read; anything else (compression, ...)
// changes how geometry is stored and is refused.
bool pn_extension_ok(const std::string &e)
{
    static const char *const prefixes[] = {"KHR_materials_", "KHR_texture_", "KHR_lights_",
                                           "EXT_texture_", "KHR_mesh_quantization"};
    for (const char *pre : prefixes) {
        if (e.compare(0, std::strlen(pre), pre) == 0) {
            return true;
        }
    }
    return false;
}

}  // namespace

// Model -> mesh. Two passes: validate and count everything first (so limits are enforced
// before anything big is allocated), then allocate once and fill.
bool pn_model_to_mesh(const tinygltf::Model &model, uint32_t max_tris, pn_mesh *out,
                      std::string *why)
{
    const uint64_t max_verts = 3ull * max_tris;
    for (const std::string &e : model.extensionsRequired) {
        if (!pn_extension_ok(e)) {
            bool packed = e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression" ||
                          e == "KHR_draco_mesh_compression";
            *why = pn_strf("requires unsupported extension '%s'%s", e.c_str(),
                           packed ? " (compressed geometry: write the file without it, e.g. "
                                    "gltfpack without -c)"
                                  : "");
            return false;
        }
    }
    bool quantized = false;
    for (const std::string &e : model.extensionsUsed) {
        quantized = quantized || e == "KHR_mesh_quantization";
    }
    std::vector<pn_instance> inst;
    if (!pn_collect_instances(model, &inst, why)) {
        return false;
    }

    // Each instanced mesh is validated once; only its triangle primitives with at least one
    // triangle are kept, so the fill pass below does work proportional to the output (a
    // file of many empty or non-triangle primitives times many nodes costs nothing).
    struct mesh_info {
        bool done = false;
        uint64_t tris = 0, verts = 0;
        std::vector<std::pair<size_t, pn_prim_views>> prims;
    };
    std::vector<mesh_info> info(model.meshes.size());
    uint64_t total_tris = 0, total_verts = 0;
    for (const pn_instance &in : inst) {
        mesh_info &mi = info[(size_t)in.mesh];
        if (!mi.done) {
            const tinygltf::Mesh &mesh = model.meshes[(size_t)in.mesh];
            for (size_t p = 0; p < mesh.primitives.size(); p++) {
                pn_prim_views pv;
                const int mode = mesh.primitives[p].mode;
                if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                    mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                    continue; // points and lines cast no shadow
                }
                if (!pn_prim_views_get(model, in.mesh, p, quantized, &pv, why)) {
                    return false;
                }
                if (pv.triangles == 0) {
                    continue;
                }
                mi.tris += pv.triangles;
                mi.verts += pv.pos.count;
                // Stop before per-mesh sums could overflow (counts are bounded by buffer
                // sizes, but a mesh can list the same accessors many times).
                if (mi.tris > max_tris || mi.verts > max_verts) {
                    break;
                }
                mi.prims.emplace_back(p, pv);
            }
            mi.done = true;
        }
        total_tris += mi.tris;
        total_verts += mi.verts;
        if (total_tris > max_tris) {
            *why = pn_strf("more than %u triangles (reached at node %d, mesh %d)", max_tris,
                           in.node, in.mesh);
            return false;
        }
        if (total_verts > max_verts) {
            *why = pn_strf("more than %llu vertices (reached at node %d, mesh %d)",
                           (unsigned long long)max_verts, in.node, in.mesh);
            return false;
        }
    }
    if (total_tris == 0) {
        *why = "no triangles: no triangle, strip or fan primitive with triangles is reachable "
               "from the scene";
        return false;
    }

    out->positions = (float *)std::malloc((size_t)total_verts * 3 * sizeof(float));
    out->indices = (uint32_t *)std::malloc((size_t)total_tris * 3 * sizeof(uint32_t));
    if (out->positions == nullptr || out->indices == nullptr) {
        *why = pn_strf("out of memory for %llu vertices and %llu triangles",
                       (unsigned long long)total_verts, (unsigned long long)total_tris);
        return false;
    }

    float *pos = out->positions;
    uint32_t *idx = out->indices;
    uint32_t base = 0;
    for (const pn_instance &in : inst) {
        const bool identity = pn_mat_is_identity(in.m), mirrors = pn_mat_mirrors(in.m);
        const double *m = in.m;
        for (const auto &entry : info[(size_t)in.mesh].prims) {
            const size_t p = entry.first;
            const pn_prim_views &pv = entry.second;
            for (size_t i = 0; i < pv.pos.count; i++) {
                const unsigned char *e = pv.pos.base + i * pv.pos.stride;
                const int ct = pv.pos.component_type;
                const double qx = pn_read_position(e, ct, pv.pos_normalized, 0);
                const double qy = pn_read_position(e, ct, pv.pos_normalized, 1);
                const double qz = pn_read_position(e, ct, pv.pos_normalized, 2);
                float x = (float)qx, y = (float)qy, z = (float)qz;
                if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
                    *why = pn_strf("mesh %d primitive %zu: vertex %zu has a non-finite "
                                   "position (%g, %g, %g)",
                                   in.mesh, p, i, (double)x, (double)y, (double)z);
                    return false;
                }
                if (!identity) {
                    // double keeps the composed transform exact enough that a unit-scale
                    // translation does not move vertices by more than float rounding.
                    double dx = qx, dy = qy, dz = qz;
                    x = (float)(m[0] * dx + m[4] * dy + m[8] * dz + m[12]);
                    y = (float)(m[1] * dx + m[5] * dy + m[9] * dz + m[13]);
                    z = (float)(m[2] * dx + m[6] * dy + m[10] * dz + m[14]);
                    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
                        *why = pn_strf("node %d: transformed vertex %zu of mesh %d primitive "
                                       "%zu is not finite",
                                       in.node, i, in.mesh, p);
                        return false;
                    }
                }
                pos[0] = x;
                pos[1] = y;
                pos[2] = z;
                pos += 3;
            }
            for (size_t t = 0; t < pv.triangles; t++) {
                size_t el[3];
                pn_prim_triangle(pv.mode, t, el);
                if (mirrors) {
                    std::swap(el[1], el[2]);
                }
                for (int c = 0; c < 3; c++) {
                    uint32_t v = pn_prim_element(pv, el[c]);
                    if (v >= pv.pos.count) {
                        *why = pn_strf("mesh %d primitive %zu: index %zu is %u, but there are "
                                       "only %zu vertices",
                                       in.mesh, p, el[c], v, pv.pos.count);
                        return false;
                    }
                    *idx++ = base + v;
                }
            }
            base += (uint32_t)pv.pos.count;
        }
    }
    out->vertex_count = (uint32_t)total_verts;
    out->triangle_count = (uint32_t)total_tris;
    pn_mesh_update_bbox(out);
    return true;
}

}  // namespace pn_gltf_impl
