// pn_gltf.cpp - glTF 2.0 -> pn_mesh, a C interface over tinygltf (see pn_gltf.h).
//
// tinygltf does the JSON/GLB/data-URI parsing; everything the geometry depends on is
// re-validated here because tinygltf 2.7 trusts much of its input: it does not check that
// buffer views and accessors lie inside their buffer, its GLB chunk check lets the BIN chunk
// run 8 bytes past the declared length, it converts JSON recursively (stack depth follows the
// file), and it throws on some malformed inputs. So: the GLB header and JSON nesting are
// checked before tinygltf sees the bytes, every call into tinygltf is inside try/catch, and
// every accessor read is range-checked here.
#include "pn_gltf.h"

#include <tiny_gltf.h>

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

namespace {

std::string pn_strf(const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return std::string(buf);
}

void pn_copy_err(char *err, size_t err_size, const std::string &msg)
{
    if (err == nullptr || err_size == 0) {
        return;
    }
    std::snprintf(err, err_size, "%s", msg.c_str());
}

// tinygltf messages are newline-separated and end with a newline; fold them onto one line.
std::string pn_tidy(const std::string &s)
{
    std::string out;
    bool pending_sep = false;
    for (char c : s) {
        if (c == '\n' || c == '\r') {
            pending_sep = !out.empty();
        } else {
            if (pending_sep) {
                out += "; ";
                pending_sep = false;
            }
            out += c;
        }
    }
    return out.empty() ? std::string("unknown error") : out;
}

uint32_t pn_le32(const unsigned char *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

const uint32_t PN_GLB_MAGIC = 0x46546C67u;  // "glTF"
const uint32_t PN_GLB_JSON = 0x4E4F534Au;   // "JSON"
const uint32_t PN_GLB_BIN = 0x004E4942u;    // "BIN\0"

// Checks the 20-byte GLB header against the real size. On success *json_len is the JSON
// chunk length and *length the declared total length.
bool pn_glb_check_header(const unsigned char *h, uint64_t size, uint32_t *json_len,
                         uint32_t *length, std::string *why)
{
    if (size < 20) {
        *why = pn_strf("truncated: %llu bytes, a GLB header needs 20",
                       (unsigned long long)size);
        return false;
    }
    if (pn_le32(h) != PN_GLB_MAGIC) {
        *why = pn_strf("wrong magic %02x %02x %02x %02x: not a binary glTF (.glb)", h[0], h[1],
                       h[2], h[3]);
        return false;
    }
    if (pn_le32(h + 4) != 2) {
        *why = pn_strf("unsupported GLB version %u (need 2)", pn_le32(h + 4));
        return false;
    }
    // tinygltf takes the size as unsigned int.
    if (size > UINT32_MAX) {
        *why = pn_strf("%llu bytes: GLB larger than 4 GiB", (unsigned long long)size);
        return false;
    }
    *length = pn_le32(h + 8);
    if (*length > size) {
        *why = pn_strf("truncated: header says %u bytes, only %llu present", *length,
                       (unsigned long long)size);
        return false;
    }
    *json_len = pn_le32(h + 12);
    if (pn_le32(h + 16) != PN_GLB_JSON) {
        *why = "first GLB chunk is not JSON";
        return false;
    }
    if (*json_len == 0 || 20ull + *json_len > *length) {
        *why = pn_strf("JSON chunk of %u bytes does not fit the GLB length %u", *json_len,
                       *length);
        return false;
    }
    return true;
}

// Checks the optional BIN chunk header (8 bytes at offset json_end, NULL if absent).
bool pn_glb_check_bin(const unsigned char *c, uint64_t json_end, uint32_t length,
                      std::string *why)
{
    if (json_end == length) {
        return true;  // no BIN chunk
    }
    if (json_end + 8u > length || c == nullptr) {
        *why = "truncated: BIN chunk header cut off";
        return false;
    }
    uint32_t bin_len = pn_le32(c);
    if (pn_le32(c + 4) != PN_GLB_BIN) {
        *why = "second GLB chunk is not BIN";
        return false;
    }
    // The chunk payload starts after its 8-byte header (tinygltf 2.7 forgets those 8 bytes).
    if (json_end + 8u + bin_len > length) {
        *why = pn_strf("truncated: BIN chunk of %u bytes runs past the GLB length %u", bin_len,
                       length);
        return false;
    }
    return true;
}

// Nesting depth of JSON arrays/objects, strings skipped. tinygltf turns "extras" into Values
// recursively, so unbounded nesting would be unbounded recursion.
bool pn_json_depth_ok(const unsigned char *s, size_t n, std::string *why)
{
    int depth = 0;
    bool in_str = false, esc = false;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = s[i];
        if (in_str) {
            if (esc) {
                esc = false;
            } else if (c == '\\') {
                esc = true;
            } else if (c == '"') {
                in_str = false;
            }
        } else if (c == '"') {
            in_str = true;
        } else if (c == '{' || c == '[') {
            if (++depth > PN_GLTF_MAX_JSON_DEPTH) {
                *why = pn_strf("JSON nested deeper than %d levels", PN_GLTF_MAX_JSON_DEPTH);
                return false;
            }
        } else if ((c == '}' || c == ']') && depth > 0) {
            depth--;
        }
    }
    return true;
}

// We only need geometry: never decode images (stb_image on hostile data is avoidable attack
// surface, and image bufferView offsets are not range-checked by tinygltf before the call).
bool pn_skip_image(tinygltf::Image *, const int, std::string *, std::string *, int, int,
                   const unsigned char *, int, void *)
{
    return true;
}

// File system callbacks for in-memory loading: nothing outside the given bytes is read.
bool pn_fs_exists(const std::string &, void *) { return false; }
std::string pn_fs_expand(const std::string &p, void *) { return p; }
bool pn_fs_read(std::vector<unsigned char> *, std::string *e, const std::string &, void *)
{
    if (e) {
        *e = "external files are not read when loading from memory";
    }
    return false;
}
bool pn_fs_write(std::string *e, const std::string &, const std::vector<unsigned char> &,
                 void *)
{
    if (e) {
        *e = "writing is disabled";
    }
    return false;
}

// File system callbacks for loading from a file: external buffers/images may only come
// from the glTF file's own directory or below it (relative URI, no ".." segment). That
// rules out absolute paths, escapes from the directory, and tinygltf's fallback of looking
// in the current directory.
struct pn_fs_scope {
    std::string main_path;  // the file being loaded (always allowed)
    std::string base_dir;   // as tinygltf computes it: main_path up to the last separator
};

bool pn_fs_path_allowed(const std::string &path, const pn_fs_scope *sc, std::string *why)
{
    if (path == sc->main_path) {
        return true;
    }
    std::string rel;
    if (sc->base_dir.empty()) {
        rel = path;
    } else if (path.size() > sc->base_dir.size() + 1 &&
               path.compare(0, sc->base_dir.size(), sc->base_dir) == 0 &&
               (path[sc->base_dir.size()] == '/' || path[sc->base_dir.size()] == '\\')) {
        rel = path.substr(sc->base_dir.size() + 1);
    } else {
        *why = "refusing '" + path + "': not in the glTF file's directory";
        return false;
    }
    if (rel.empty() || rel[0] == '/' || rel[0] == '\\' || rel.find(':') != std::string::npos) {
        *why = "refusing '" + path + "': external URIs must be relative paths";
        return false;
    }
    size_t start = 0;
    while (start <= rel.size()) {
        size_t end = rel.find_first_of("/\\", start);
        if (end == std::string::npos) {
            end = rel.size();
        }
        if (rel.compare(start, end - start, "..") == 0 && end - start == 2) {
            *why = "refusing '" + path + "': external URIs may not contain '..'";
            return false;
        }
        start = end + 1;
    }
    return true;
}

// A refused path is reported as existing so that the read below gives the reason.
bool pn_fs_scoped_exists(const std::string &path, void *ud)
{
    std::string why;
    if (!pn_fs_path_allowed(path, static_cast<const pn_fs_scope *>(ud), &why)) {
        return true;
    }
    return tinygltf::FileExists(path, nullptr);
}

bool pn_fs_scoped_read(std::vector<unsigned char> *out, std::string *err,
                       const std::string &path, void *ud)
{
    std::string why;
    if (!pn_fs_path_allowed(path, static_cast<const pn_fs_scope *>(ud), &why)) {
        if (err) {
            *err = why;
        }
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

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
    pn_view idx;
    bool indexed;
    size_t triangles;
};

// Validates one primitive's accessors (mode 4 only; the caller filters).
bool pn_prim_views_get(const tinygltf::Model &model, int mesh, size_t p, pn_prim_views *pv,
                       std::string *why)
{
    const tinygltf::Primitive &prim = model.meshes[(size_t)mesh].primitives[p];
    char what[96];
    auto it = prim.attributes.find("POSITION");
    if (it == prim.attributes.end()) {
        *why = pn_strf("mesh %d primitive %zu has no POSITION attribute", mesh, p);
        return false;
    }
    std::snprintf(what, sizeof what, "mesh %d primitive %zu POSITION", mesh, p);
    if (it->second >= 0 && (size_t)it->second < model.accessors.size() &&
        model.accessors[(size_t)it->second].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        *why = pn_strf("%s accessor %d has componentType %d, need float (5126)", what,
                       it->second, model.accessors[(size_t)it->second].componentType);
        return false;
    }
    if (!pn_accessor_view(model, it->second, TINYGLTF_TYPE_VEC3, 4, &pv->pos, what, why)) {
        return false;
    }
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
        if (pv->idx.count % 3 != 0) {
            *why = pn_strf("%s: %zu indices is not a multiple of 3", what, pv->idx.count);
            return false;
        }
        pv->triangles = pv->idx.count / 3;
    } else {
        if (prim.indices != -1) {
            *why = pn_strf("mesh %d primitive %zu has indices %d", mesh, p, prim.indices);
            return false;
        }
        if (pv->pos.count % 3 != 0) {
            *why = pn_strf("mesh %d primitive %zu is not indexed and has %zu vertices, not a "
                           "multiple of 3",
                           mesh, p, pv->pos.count);
            return false;
        }
        pv->triangles = pv->pos.count / 3;
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

uint32_t pn_read_index(const unsigned char *p, size_t size)
{
    if (size == 1) return p[0];
    if (size == 2) return (uint32_t)p[0] | ((uint32_t)p[1] << 8);
    return pn_le32(p);
}

// Required extensions that only affect appearance are harmless for shadows; anything else
// (compression, quantization, ...) changes how geometry is stored and is refused.
bool pn_extension_ok(const std::string &e)
{
    static const char *const prefixes[] = {"KHR_materials_", "KHR_texture_", "KHR_lights_",
                                           "EXT_texture_"};
    for (const char *pre : prefixes) {
        if (e.compare(0, std::strlen(pre), pre) == 0) {
            return true;
        }
    }
    return false;
}

// Model -> mesh. Two passes: validate and count everything first (so limits are enforced
// before anything big is allocated), then allocate once and fill.
bool pn_model_to_mesh(const tinygltf::Model &model, uint32_t max_tris, pn_mesh *out,
                      std::string *why)
{
    const uint64_t max_verts = 3ull * max_tris;
    for (const std::string &e : model.extensionsRequired) {
        if (!pn_extension_ok(e)) {
            *why = pn_strf("requires unsupported extension '%s'", e.c_str());
            return false;
        }
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
                if (mesh.primitives[p].mode != TINYGLTF_MODE_TRIANGLES) {
                    continue;
                }
                if (!pn_prim_views_get(model, in.mesh, p, &pv, why)) {
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
        *why = "no triangles: no mode-4 primitive with triangles is reachable from the scene";
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
        const bool identity = pn_mat_is_identity(in.m);
        const double *m = in.m;
        for (const auto &entry : info[(size_t)in.mesh].prims) {
            const size_t p = entry.first;
            const pn_prim_views &pv = entry.second;
            for (size_t i = 0; i < pv.pos.count; i++) {
                const unsigned char *e = pv.pos.base + i * pv.pos.stride;
                float x = pn_read_f32(e), y = pn_read_f32(e + 4), z = pn_read_f32(e + 8);
                if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
                    *why = pn_strf("mesh %d primitive %zu: vertex %zu has a non-finite "
                                   "position (%g, %g, %g)",
                                   in.mesh, p, i, (double)x, (double)y, (double)z);
                    return false;
                }
                if (!identity) {
                    // double keeps the composed transform exact enough that a unit-scale
                    // translation does not move vertices by more than float rounding.
                    double dx = x, dy = y, dz = z;
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
            const size_t n_idx = pv.triangles * 3;
            if (pv.indexed) {
                const size_t isz = pn_index_size(pv.idx.component_type);
                for (size_t i = 0; i < n_idx; i++) {
                    uint32_t v = pn_read_index(pv.idx.base + i * pv.idx.stride, isz);
                    if (v >= pv.pos.count) {
                        *why = pn_strf("mesh %d primitive %zu: index %zu is %u, but there are "
                                       "only %zu vertices",
                                       in.mesh, p, i, v, pv.pos.count);
                        return false;
                    }
                    *idx++ = base + v;
                }
            } else {
                for (size_t i = 0; i < n_idx; i++) {
                    *idx++ = base + (uint32_t)i;
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

// Reads exactly n bytes at offset off; false on a short read.
bool pn_read_at(FILE *f, uint64_t off, unsigned char *dst, size_t n)
{
    if (off > (uint64_t)LONG_MAX || std::fseek(f, (long)off, SEEK_SET) != 0) {
        return false;
    }
    return std::fread(dst, 1, n, f) == n;
}

bool pn_ends_with_ci(const std::string &s, const char *suffix)
{
    size_t n = std::strlen(suffix);
    if (s.size() < n) {
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        char a = s[s.size() - n + i], b = suffix[i];
        if (a >= 'A' && a <= 'Z') a = (char)(a - 'A' + 'a');
        if (a != b) {
            return false;
        }
    }
    return true;
}

// Pre-checks an open file before tinygltf reads it: size, GLB layout (if binary) and JSON
// nesting. *binary says which tinygltf entry point to use.
bool pn_precheck_stream(FILE *f, const std::string &path, bool *binary, std::string *why)
{
    long end = -1;
    if (std::fseek(f, 0, SEEK_END) != 0 || (end = std::ftell(f)) < 0) {
        *why = "cannot read (not a regular file?)";
        return false;
    }
    const uint64_t size = (uint64_t)end;
    unsigned char hdr[20];
    if (pn_ends_with_ci(path, ".glb")) {
        *binary = true;
    } else if (pn_ends_with_ci(path, ".gltf")) {
        *binary = false;
    } else {
        *binary = size >= 4 && pn_read_at(f, 0, hdr, 4) && pn_le32(hdr) == PN_GLB_MAGIC;
    }
    std::vector<unsigned char> buf;
    if (!*binary) {
        if (size == 0) {
            *why = "empty file";
            return false;
        }
        // tinygltf takes the JSON length as unsigned int.
        if (size >= UINT32_MAX) {
            *why = pn_strf("%llu bytes: glTF JSON larger than 4 GiB", (unsigned long long)size);
            return false;
        }
        buf.resize((size_t)size);
        if (!pn_read_at(f, 0, buf.data(), buf.size())) {
            *why = "cannot read (I/O error or not a regular file)";
            return false;
        }
        return pn_json_depth_ok(buf.data(), buf.size(), why);
    }
    uint32_t json_len = 0, length = 0;
    if (size >= 20 && !pn_read_at(f, 0, hdr, 20)) {
        *why = "cannot read (I/O error or not a regular file)";
        return false;
    }
    if (!pn_glb_check_header(hdr, size, &json_len, &length, why)) {
        return false;
    }
    buf.resize(json_len);
    if (!pn_read_at(f, 20, buf.data(), json_len)) {
        *why = "cannot read the JSON chunk";
        return false;
    }
    if (!pn_json_depth_ok(buf.data(), buf.size(), why)) {
        return false;
    }
    unsigned char c[8];
    const uint64_t json_end = 20ull + json_len;
    const bool have = json_end + 8 <= length && pn_read_at(f, json_end, c, 8);
    return pn_glb_check_bin(have ? c : nullptr, json_end, length, why);
}

bool pn_precheck_file(const std::string &path, bool *binary, std::string *why)
{
    FILE *f = std::fopen(path.c_str(), "rb");
    if (f == nullptr) {
        *why = pn_strf("cannot open: %s", std::strerror(errno));
        return false;
    }
    bool ok = pn_precheck_stream(f, path, binary, why);
    std::fclose(f);
    return ok;
}

int pn_finish(bool ok, const std::string &why, const char *where, pn_mesh *out, char *err,
              size_t err_size)
{
    if (ok) {
        return 0;
    }
    pn_mesh_free(out);
    pn_copy_err(err, err_size, where ? pn_strf("%s: ", where) + why : why);
    return 1;
}

// Runs load(), turning every exception tinygltf or the conversion can throw into a message.
template <class Load>
bool pn_guarded(Load load, std::string *why)
{
    try {
        return load();
    } catch (const std::bad_alloc &) {
        *why = "out of memory";
    } catch (const std::exception &e) {
        *why = std::string("glTF parse error: ") + e.what();
    } catch (...) {
        *why = "glTF parse error: unknown exception";
    }
    return false;
}

// File callbacks (scoped or refusing) and no image decoding.
void pn_prepare_loader(tinygltf::TinyGLTF *loader, tinygltf::FileExistsFunction exists,
                       tinygltf::ReadWholeFileFunction read, void *user)
{
    tinygltf::FsCallbacks fs;
    fs.FileExists = exists;
    fs.ExpandFilePath = pn_fs_expand;
    fs.ReadWholeFile = read;
    fs.WriteWholeFile = pn_fs_write;
    fs.user_data = user;
    loader->SetFsCallbacks(fs);
    loader->SetImageLoader(pn_skip_image, nullptr);
}

}  // namespace

extern "C" int pn_gltf_load(const char *path, pn_mesh *out, char *err, size_t err_size)
{
    if (err != nullptr && err_size > 0) {
        err[0] = '\0';
    }
    if (out == nullptr) {
        pn_copy_err(err, err_size, "pn_gltf_load: out is NULL");
        return 1;
    }
    std::memset(out, 0, sizeof *out);
    if (path == nullptr || path[0] == '\0') {
        pn_copy_err(err, err_size, "pn_gltf_load: no path given");
        return 1;
    }
    std::string why;
    bool ok = pn_guarded(
        [&]() {
            const std::string p(path);
            bool binary = false;
            if (!pn_precheck_file(p, &binary, &why)) return false;
            tinygltf::TinyGLTF loader;
            tinygltf::Model model;
            std::string terr, twarn;
            pn_fs_scope scope;
            scope.main_path = p;
            size_t sep = p.find_last_of("/\\");
            scope.base_dir = sep == std::string::npos ? std::string() : p.substr(0, sep);
            pn_prepare_loader(&loader, pn_fs_scoped_exists, pn_fs_scoped_read, &scope);
            bool loaded = binary ? loader.LoadBinaryFromFile(&model, &terr, &twarn, p)
                                 : loader.LoadASCIIFromFile(&model, &terr, &twarn, p);
            if (!loaded) {
                why = "glTF parse error: " + pn_tidy(terr);
                return false;
            }
            return pn_model_to_mesh(model, PN_GLTF_MAX_TRIANGLES, out, &why);
        },
        &why);
    return pn_finish(ok, why, path, out, err, err_size);
}

extern "C" int pn_gltf_load_memory(const unsigned char *data, size_t size, pn_mesh *out,
                                   char *err, size_t err_size)
{
    return pn_gltf_load_memory_limit(data, size, PN_GLTF_MAX_TRIANGLES, out, err, err_size);
}

extern "C" int pn_gltf_load_memory_limit(const unsigned char *data, size_t size,
                                         uint32_t max_triangles, pn_mesh *out, char *err,
                                         size_t err_size)
{
    if (err != nullptr && err_size > 0) {
        err[0] = '\0';
    }
    if (out == nullptr) {
        pn_copy_err(err, err_size, "pn_gltf_load_memory: out is NULL");
        return 1;
    }
    std::memset(out, 0, sizeof *out);
    if (data == nullptr && size > 0) {
        pn_copy_err(err, err_size, "pn_gltf_load_memory: data is NULL");
        return 1;
    }
    if (max_triangles == 0 || max_triangles > PN_GLTF_MAX_TRIANGLES) {
        pn_copy_err(err, err_size,
                    pn_strf("pn_gltf_load_memory: max_triangles %u outside 1..%u",
                            max_triangles, PN_GLTF_MAX_TRIANGLES));
        return 1;
    }
    std::string why;
    bool ok = pn_guarded(
        [&]() {
            uint32_t json_len = 0, length = 0;
            static const unsigned char zeros[20] = {0};
            if (!pn_glb_check_header(size >= 20 ? data : zeros, size, &json_len, &length, &why) ||
                !pn_json_depth_ok(data + 20, json_len, &why) ||
                !pn_glb_check_bin(20ull + json_len + 8 <= length ? data + 20 + json_len : nullptr,
                                  20ull + json_len, length, &why))
                return false;
            tinygltf::TinyGLTF loader;
            tinygltf::Model model;
            std::string terr, twarn;
            pn_prepare_loader(&loader, pn_fs_exists, pn_fs_read, nullptr);
            // Only the declared length is handed over: bytes past it are not part of the GLB.
            if (!loader.LoadBinaryFromMemory(&model, &terr, &twarn, data, length, "")) {
                why = "glTF parse error: " + pn_tidy(terr);
                return false;
            }
            return pn_model_to_mesh(model, max_triangles, out, &why);
        },
        &why);
    return pn_finish(ok, why, "glb in memory", out, err, err_size);
}
