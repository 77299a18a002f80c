// pn_gltf_internal.h - what the glTF loader's files share (pn_gltf.cpp: the entry points and
// tinygltf's set-up; pn_gltf_container.cpp: the GLB/JSON checks before tinygltf parses;
// pn_gltf_model.cpp: the parsed model's validation and baking into a pn_mesh). C++ only,
// internal to those files; each function is documented at its definition.
#ifndef PN_TOOLS_GLTF_INTERNAL_H
#define PN_TOOLS_GLTF_INTERNAL_H

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "pn_mesh.h"

namespace pn_gltf_impl {

// pn_gltf.cpp: printf into a std::string (messages are at most 511 bytes).
std::string pn_strf(const char *fmt, ...);

// Little-endian 32-bit read (GLB fields, float and index data).
inline uint32_t pn_le32(const unsigned char *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

// pn_gltf_container.cpp
bool pn_glb_check_header(const unsigned char *h, uint64_t size, uint32_t *json_len,
                         uint32_t *length, std::string *why);
bool pn_glb_check_bin(const unsigned char *c, uint64_t json_end, uint32_t length,
                      std::string *why);
bool pn_json_depth_ok(const unsigned char *s, size_t n, std::string *why);
bool pn_precheck_file(const std::string &path, bool *binary, std::string *why);

// pn_gltf_model.cpp
bool pn_model_to_mesh(const tinygltf::Model &model, uint32_t max_tris, pn_mesh *out,
                      std::string *why);

}  // namespace pn_gltf_impl

#endif
