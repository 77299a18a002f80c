/* pn_setup.h - what the CLI, the demo, the tests and the benchmarks share: loading a
 * scene (glTF file or built-in), the automatic view and light, the eps convention, and a
 * heap-backed library context. Host code only. */
#ifndef PN_TOOLS_SETUP_H
#define PN_TOOLS_SETUP_H

#include <stddef.h>
#include <stdint.h>

#include "penumbra/penumbra.h"
#include "pn_mesh.h"
#include "pn_threads.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pn_setup {
    pn_mesh mesh;      /* scene triangles, ground plane appended when on */
    pn_camera camera;
    pn_light light;
    float diag;        /* bbox diagonal without the ground plane */
    float eps_rel;     /* E: eps = E * diag (default 1e-4) */
    float eps;
    int ground;        /* 1 if the ground plane was appended */
    int builtin;       /* 1 for a built-in scene */
    char name[128];    /* file base name or built-in name */
    char view_source[16];  /* "auto", "builtin" or "user" (set by callers for stats) */
    char light_source[16];
} pn_setup;

/* Loads `source`: a built-in scene name when builtin is non-zero, else a .glb/.gltf path.
 * ground: 1 on, 0 off, -1 the default (on for glTF, off for built-ins, which carry their
 * own receiver). Fills the default view and light (the built-in's own, or framed from the
 * bounding box) and eps = 1e-4 * diag. Returns 0 or non-zero with a message. */
int pn_setup_load(pn_setup *s, const char *source, int builtin, int ground, char *err, size_t err_size);

/* Automatic framing of a bounding box: camera from the front-right-above looking at the
 * centre, fov 40; light above the centre (0.25, 1.0, 0.15) * diag away, a square of half
 * size 0.1 * diag emitting straight down. */
void pn_setup_auto_view(const float bmin[3], const float bmax[3], pn_camera *cam, pn_light *light);

void pn_setup_free(pn_setup *s);

/* ---- Views files (tools/pn_views.c) ---------------------------------------------------- *
 * A views file (../shared/scenes/views.json) is a JSON object keyed by scene name (a .glb's
 * file name without the extension); each view gives "size" [W, H] (optional), "eye",
 * "target", "up" (optional, default [0, 1, 0]), "fov" (vertical, degrees), "light_center",
 * "light_u", "light_v" (half-edges; the light emits toward normalize(u x v)) and "ground"
 * (optional, true/false). Other keys are ignored. */
typedef struct pn_view {
    char name[64];
    uint32_t width, height; /* 0 when the view gives no size */
    pn_camera camera;
    pn_light light;
    int ground;             /* 1 on, 0 off, -1 not given */
} pn_view;

/* Reads view `name` from the views file at `path`. Returns 0 and fills *v; 1 when the file
 * is valid but has no such view (err names the file, the key and the views it has); 2 for
 * any other error (unreadable file, bad JSON, a field missing or of the wrong type: err
 * names the file and the view or the byte). */
int pn_view_load(const char *path, const char *name, pn_view *v, char *err, size_t err_size);

/* The views file that goes with a scene: "views.json" beside scene_path (a glTF file) when
 * it exists, else PN_VIEWS_FALLBACK ("../shared/scenes/views.json", relative to the working
 * directory) when it exists. Writes the path into out and returns 0, or returns 1 (none). */
#define PN_VIEWS_FALLBACK "../shared/scenes/views.json"
int pn_views_file_for(const char *scene_path, char *out, size_t out_size);

/* The view of a scene loaded from a scene directory: views.json in `dir` holding a view
 * named s->name. Returns 0 and fills *v when there is one, 1 when there is none (no file,
 * or no such key), 2 when the file is there but broken (err says why). */
int pn_view_for_scene(const char *dir, const char *name, pn_view *v, char *err, size_t err_size);

/* Puts the view's camera and light on s (view_source and light_source "view"). The ground
 * is decided at load time: pass v->ground to pn_setup_load. */
void pn_setup_use_view(pn_setup *s, const pn_view *v);

/* pn_setup_load with the scene's own view: a glTF scene named in views_dir/views.json gets
 * that view's camera, light and ground; any other scene (a built-in, a glTF file without a
 * view, views_dir NULL) the defaults of pn_setup_load with ground -1. How the benchmark and
 * the tests render every scene. Returns 0, or non-zero with a message (a views file that is
 * there but broken is an error). */
int pn_setup_load_viewed(pn_setup *s, const char *source, int builtin, const char *views_dir, char *err,
                         size_t err_size);

/* Hands the setup's scene to the library: pn_scene_set with the mesh, then
 * pn_scene_set_receivers with the mesh's receiver range (count 0 marks none). Returns
 * PN_OK or the first failing status (pn_last_error(ctx) has its message; PN_E_INVALID_ARG
 * without one for a NULL ctx or s); after a failed pn_scene_set the receivers are not
 * touched. */
pn_status pn_setup_upload(pn_context *ctx, const pn_setup *s);

/* A library context on the heap, sized for the given limits, with the pthread
 * parallel-for (threads <= 0: all cores) and the monotonic clock installed. */
typedef struct pn_host {
    void *memory;
    size_t bytes;
    pn_context *ctx;
    pn_threads threads;
} pn_host;

/* A host's limits for max_triangles at max_w x max_h: the library's defaults but the split
 * BVH references reserved, GEARS grids up to 256 and GEARS' pair pool at PN_GEARS_PAIRS
 * (frames in one pass). pn_host_open opens a context with them. */
void pn_host_limits(pn_limits *lim, uint32_t max_triangles, uint32_t max_w, uint32_t max_h);
int pn_host_open(pn_host *h, uint32_t max_triangles, uint32_t max_w, uint32_t max_h, int threads,
                 char *err, size_t err_size);
/* The same with the caller's limits (every field). */
int pn_host_open_limits(pn_host *h, const pn_limits *limits, int threads, char *err, size_t err_size);
void pn_host_close(pn_host *h);

/* Parses "x,y,z" / "WxH". Return 0 on success. */
int pn_parse_vec3(const char *s, float out[3]);
int pn_parse_size(const char *s, uint32_t *w, uint32_t *h);

#ifdef __cplusplus
}
#endif
#endif
