/* pn_test_scene.h - what the core tests need from a host, without the tools' libraries
 * (issue 46: the library's tests link the library and nothing with a dependency: no glTF
 * loader, no image writer, no threads):
 *
 *   the built-in scenes the core tests render (pn_test_scene_load: square, spheres,
 *   elongated-cube, thin, room, ...), built by the pn_scenes library (tools/pn_scenes*.c,
 *   tools/pn_mesh.c: plain C, no dependency), with their views, lights and eps (1e-4 of
 *   the bounding-box diagonal, as tools/pn_setup.h); tests/test_setup.c holds them to
 *   what the tools' set-up loads;
 *   the square scene's closed form (tools/pn_scenes.h pn_square_closed_form);
 *   a library context on the heap opened through the public API alone (pn_test_open), and
 *   serial parallel-fors that hand the work items out in other orders than the library's
 *   own loop (pn_test_parallel_for), for determinism checks without threads.
 *
 * Header-only, C99, static functions. Tests may allocate; the library may not. Include after
 * penumbra.h. */
#ifndef PN_TEST_SCENE_H
#define PN_TEST_SCENE_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_scenes.h" /* tools/: the built-in scenes and pn_mesh (the pn_scenes library) */

/* ---- The scenes: the tools' built-ins, from the pn_scenes library ---------------------------- */

/* The triangle list (tools/pn_mesh.h: positions, indices, bounding box, receiver range). */
typedef pn_mesh pn_test_mesh;
static inline void pn_test_mesh_free(pn_test_mesh *m) { pn_mesh_free(m); }
static inline void pn_test_mesh_update_bbox(pn_test_mesh *m) { pn_mesh_update_bbox(m); }

/* The square scene's parameters and closed forms (tools/pn_scenes.h). */
typedef pn_square_params pn_test_square_params;
static inline void pn_test_square_scene_params(pn_test_square_params *p) { pn_square_scene_params(p); }
static inline double pn_test_square_closed_form(const pn_test_square_params *p, double x, double z, int k)
{
    return pn_square_closed_form(p, x, z, k);
}
static inline double pn_test_square_min_edge_distance(const pn_test_square_params *p, double x, double z, int k)
{
    return pn_square_min_edge_distance(p, x, z, k);
}

typedef struct pn_test_scene {
    pn_test_mesh mesh;
    pn_camera camera;
    pn_light light;
    float diag; /* bounding-box diagonal */
    float eps;  /* 1e-4 * diag, the tools' convention */
    char name[128];
} pn_test_scene;

/* Builds built-in scene `name` (pn_builtin_scene: square, spheres, elongated-cube, thin,
 * room, ...) with its view, light, diagonal and eps. 0 on success; else a message on
 * stderr and *s empty. */
static inline int pn_test_scene_load(pn_test_scene *s, const char *name)
{
    pn_scene_view v;
    char err[256];
    memset(s, 0, sizeof(*s));
    if (pn_builtin_scene(name, &s->mesh, &v, err, sizeof(err)) != 0) {
        fprintf(stderr, "pn_test_scene_load: %s\n", err);
        return 1;
    }
    pn_scene_view_apply(&v, &s->camera, &s->light);
    snprintf(s->name, sizeof(s->name), "%s", name);
    pn_mesh_update_bbox(&s->mesh);
    s->diag = pn_mesh_diag(&s->mesh);
    s->eps = 1e-4f * s->diag;
    return 0;
}

static inline void pn_test_scene_free(pn_test_scene *s)
{
    pn_test_mesh_free(&s->mesh);
    memset(s, 0, sizeof(*s));
}

/* pn_scene_set with the scene's mesh, then pn_scene_set_receivers with its receiver range. */
static inline pn_status pn_test_scene_upload(pn_context *ctx, const pn_test_scene *s)
{
    pn_status st = pn_scene_set(ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count);
    if (st != PN_OK) return st;
    return pn_scene_set_receivers(ctx, s->mesh.receiver_first, s->mesh.receiver_count);
}

/* ---- A context on the heap, through the public API ----------------------------------------- */

typedef struct pn_test_host {
    void *memory;
    size_t bytes;
    pn_context *ctx;
} pn_test_host;

/* Sizes (pn_arena_size), allocates and initializes (pn_init) a context for *limits; the
 * library's own serial loop, no clock. 0 on success; else a message on stderr, *h empty. */
static inline int pn_test_open_limits(pn_test_host *h, const pn_limits *limits)
{
    pn_status st;
    memset(h, 0, sizeof(*h));
    st = pn_arena_size(limits, &h->bytes);
    if (st != PN_OK) {
        fprintf(stderr, "pn_arena_size: %s\n", pn_status_str(st));
        return 1;
    }
    h->memory = malloc(h->bytes);
    if (!h->memory) {
        fprintf(stderr, "cannot allocate %zu bytes of arena\n", h->bytes);
        return 1;
    }
    st = pn_init(&h->ctx, h->memory, h->bytes, limits);
    if (st != PN_OK) {
        fprintf(stderr, "pn_init: %s\n", pn_status_str(st));
        free(h->memory);
        memset(h, 0, sizeof(*h));
        return 1;
    }
    return 0;
}

/* A context of max_triangles, max_w x max_h and bvh_refs BVH references (0: the
 * library's default, no split references). */
static inline int pn_test_open_refs(pn_test_host *h, uint32_t max_triangles, uint32_t max_w, uint32_t max_h,
                                    uint32_t bvh_refs)
{
    pn_limits lim;
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = max_triangles;
    lim.max_width = max_w;
    lim.max_height = max_h;
    lim.bvh_refs = bvh_refs;
    return pn_test_open_limits(h, &lim);
}

static inline int pn_test_open(pn_test_host *h, uint32_t max_triangles, uint32_t max_w, uint32_t max_h)
{
    return pn_test_open_refs(h, max_triangles, max_w, max_h, 0u);
}

static inline void pn_test_close(pn_test_host *h)
{
    free(h->memory);
    memset(h, 0, sizeof(*h));
}

/* The options of a core test's small frame of every algorithm: w x h, k = 8, a GEARS grid
 * of 16 and, when maps is not 0, light-space maps of that many texels (the defaults, 512
 * to 2048, cost far more than such a frame). */
static inline void pn_test_frame_opts(pn_frame_options *opt, uint32_t w, uint32_t h, uint32_t algo, float eps,
                                      uint32_t maps)
{
    pn_frame_options_default(opt);
    opt->width = w;
    opt->height = h;
    opt->k = 8;
    opt->eps = eps;
    opt->algo = (pn_algo)algo;
    opt->gears.grid = 16;
    opt->srt.map = maps;
    opt->occtex.map = maps;
    opt->mcsm.map = maps;
}

/* ---- Serial schedules for pn_set_parallel_for ---------------------------------------------- *
 * The library may have its ranges run in any order (penumbra.h, "Work distribution"); these
 * run them on the calling thread in orders unlike its own loop (one call over [0, count)),
 * so a result that depends on the order shows without threads. */
typedef enum pn_test_order {
    PN_TEST_ITEMS_FORWARD,  /* one item a call, 0 up */
    PN_TEST_ITEMS_BACKWARD, /* one item a call, count - 1 down */
    PN_TEST_ITEMS_SHUFFLED, /* one item a call, in a fixed permutation (a stride coprime to count) */
    PN_TEST_CHUNKS_UNEVEN   /* ranges of 1, 2, 3, ... items taken from the end */
} pn_test_order;

typedef struct pn_test_schedule {
    pn_test_order order;
    uint32_t jobs;   /* parallel-for calls so far */
    uint64_t ranges; /* task calls so far */
} pn_test_schedule;

static inline uint32_t pn_test_gcd(uint32_t a, uint32_t b)
{
    while (b) {
        uint32_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* Matches pn_parallel_for_fn; user points to a pn_test_schedule. */
static inline void pn_test_parallel_for(void *user, uint32_t count, pn_task_fn fn, void *task)
{
    pn_test_schedule *sc = (pn_test_schedule *)user;
    uint32_t i;
    sc->jobs++;
    if (sc->order == PN_TEST_ITEMS_FORWARD) {
        for (i = 0; i < count; i++) fn(task, i, i + 1u);
        sc->ranges += count;
    } else if (sc->order == PN_TEST_ITEMS_BACKWARD) {
        for (i = count; i > 0u; i--) fn(task, i - 1u, i);
        sc->ranges += count;
    } else if (sc->order == PN_TEST_ITEMS_SHUFFLED) {
        uint32_t step = count / 2u + 1u;
        while (count > 1u && pn_test_gcd(step, count) != 1u) step++;
        for (i = 0; i < count; i++) {
            uint32_t it = (uint32_t)(((uint64_t)i * step + 7u) % count);
            fn(task, it, it + 1u);
        }
        sc->ranges += count;
    } else {
        uint32_t end = count, n = 1u;
        while (end > 0u) {
            uint32_t begin = end > n ? end - n : 0u;
            fn(task, begin, end);
            sc->ranges++;
            end = begin;
            n++;
        }
    }
}

#endif
