// pn_gltf_container.cpp - the glTF loader's checks of the container, before tinygltf sees
// the bytes (see pn_gltf.cpp): the GLB header and its JSON and BIN chunks against the real
// size, the JSON's nesting depth, and the pre-check of a file on disk.
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "pn_gltf.h"
#include "pn_gltf_internal.h"

namespace pn_gltf_impl {

namespace {

const uint32_t PN_GLB_MAGIC = 0x46546C67u;  // "glTF"
const uint32_t PN_GLB_JSON = 0x4E4F534Au;   // "JSON"
const uint32_t PN_GLB_BIN = 0x004E4942u;    // "BIN\0"

}  // namespace

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

namespace {

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

}  // namespace

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

}  // namespace pn_gltf_impl
