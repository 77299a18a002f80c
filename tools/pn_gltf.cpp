// pn_gltf.cpp - glTF 2.0 -> pn_mesh, a C interface over tinygltf (see pn_gltf.h).
//
// tinygltf does the JSON/GLB/data-URI parsing; everything the geometry depends on is
// re-validated here because tinygltf 2.7 trusts much of its input: it does not check that
// buffer views and accessors lie inside their buffer, its GLB chunk check lets the BIN chunk
// run 8 bytes past the declared length, it converts JSON recursively (stack depth follows the
// file), and it throws on some malformed inputs. So: the GLB header and JSON nesting are
// checked before tinygltf sees the bytes, every call into tinygltf is inside try/catch, and
// every accessor read is range-checked here.
//
// Files: pn_gltf.cpp (this one: the C entry points, tinygltf's file callbacks and
// exception guard, the message helpers), pn_gltf_container.cpp (the GLB header and chunks
// and the JSON nesting, checked before tinygltf sees the bytes), pn_gltf_model.cpp (the
// parsed model: node graph, accessors and buffer views, baking into the pn_mesh), and
// pn_gltf_internal.h (what they share).
#include "pn_gltf.h"

#include <tiny_gltf.h>

#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "pn_gltf_internal.h"

namespace pn_gltf_impl {

std::string pn_strf(const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    std::vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return std::string(buf);
}

namespace {

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

}  // namespace pn_gltf_impl

using namespace pn_gltf_impl;

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
