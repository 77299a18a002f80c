/* pn_bench.h - the pieces of penumbra_bench (tools/bench/) that live in their own files: the
 * shadow-ray set-up shared with the library's kernels, the G-buffer snapshot every baseline
 * traces from, the Embree 3 baseline and our own per-pixel masks. Host code: may allocate.
 *
 * Everything here reproduces DESIGN.md invariant 6 from the outside: the same G-buffer
 * points, the same origin O = P + eps*n (kernels/pn_predicate.h pn_shadow_origin, compiled
 * into the tool), the same k x k sample positions, so a mask bit means the same light
 * sample whichever tracer produced it. */
#ifndef PN_TOOLS_BENCH_H
#define PN_TOOLS_BENCH_H

#include <stddef.h>
#include <stdint.h>

#include "penumbra/penumbra.h"
#include "pn_mesh.h"
#include "pn_threads.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What a shadow pass needs from a rendered frame, copied out of the arena (the frame's
 * pointers die at the next pn_render). */
typedef struct pn_gbuf {
    uint32_t width, height;
    float *pos;     /* 3 per pixel */
    float *nrm;     /* 3 per pixel */
    uint32_t *tri;  /* PN_NO_TRIANGLE: background */
} pn_gbuf;

int pn_gbuf_copy(pn_gbuf *g, const pn_frame *fr);
void pn_gbuf_free(pn_gbuf *g);

/* Per-pixel masks: words_per_pixel 32-bit words a pixel, bit j*k + i = sample (i, j)
 * blocked. Pixels without a triangle or behind the light have every word 0 and are not
 * counted by the comparison (their visibility, 1 or 0, is fixed by convention). */
typedef struct pn_masks {
    uint32_t width, height, k, words;
    uint32_t *bits;    /* width * height * words */
    uint8_t *lit;      /* 1 where the pixel has a shadow-ray origin */
} pn_masks;

int pn_masks_alloc(pn_masks *m, uint32_t w, uint32_t h, uint32_t k);
void pn_masks_free(pn_masks *m);

/* Bitwise comparison of two mask sets over the pixels lit in both. */
typedef struct pn_mask_diff {
    uint64_t bits;        /* compared bits: lit pixels x k^2 */
    uint64_t differ;      /* bits set in exactly one */
    uint64_t only_a;      /* blocked in a only */
    uint64_t only_b;      /* blocked in b only */
    uint64_t pixels_differ; /* lit pixels with at least one differing bit */
    uint64_t lit_pixels;
} pn_mask_diff;

void pn_masks_compare(const pn_masks *a, const pn_masks *b, pn_mask_diff *d);

/* Our exact masks, computed in the tool from the library's own kernels/ predicate
 * (pn_tri_mask) over the triangles a host-side BVH cannot rule out for the pixel's light
 * frustum (pn_frustum_aabb, the reference's conservative cull). This is what the reference
 * ORs per pixel; popcounts are checked against the reference's visibility by the caller.
 * vis (may be NULL) receives the visibility of each pixel, the horizon of the own triangle
 * included. cull_tol is the library's for the scene (pn_stats), so that the culls are the
 * same. */
int pn_our_masks(const pn_mesh *mesh, const pn_gbuf *g, const pn_light *light, uint32_t k, float eps,
                 float cull_tol, pn_threads *threads, pn_masks *out, float *vis, char *err,
                 size_t err_size);

/* Where the reference's shadow pass spends its work, by the class of the pixel in its own
 * result: 0 lit (visibility 1), 1 umbra (0), 2 penumbra (in between), over the pixels with
 * a shadow-ray origin. The library's per-pixel kernel (pn_reference_pixel: horizon,
 * frustum and footprint culls, the exact predicate) over the host BVH above, each pixel
 * timed alone: ns (wall, noisy) and work (BVH nodes tested + triangles handed to the
 * predicate, deterministic). What selective ray tracing can save is bounded by it: with
 * exact masks only for the penumbra pixels and a free shadow map, the shadow pass cannot
 * be faster than total / penumbra. *vis_agrees: 1 when the visibility equals ref_vis (the
 * library's frame) on every pixel. */
typedef struct pn_class_cost {
    double ns[3], work[3];
    uint64_t pixels[3];
    int vis_agrees;
} pn_class_cost;

int pn_reference_class_cost(const pn_mesh *mesh, const pn_gbuf *g, const pn_light *light, uint32_t k, float eps,
                            float cull_tol, pn_threads *threads, const float *ref_vis, pn_class_cost *out, char *err,
                            size_t err_size);

/* ---- Embree 3 baseline (tools/pn_bench_embree.c; a stub when Embree was not found) ------ */

typedef enum pn_embree_api {
    PN_EMBREE_OCCLUDED1 = 0,  /* rtcOccluded1, one ray at a time */
    PN_EMBREE_OCCLUDED16 = 1, /* rtcOccluded16, 16 rays of one pixel per packet */
    PN_EMBREE_API_COUNT = 2
} pn_embree_api;

const char *pn_embree_api_name(pn_embree_api api);

typedef struct pn_embree pn_embree;

/* 1 when the tool was built with Embree. */
int pn_embree_compiled(void);

/* A device with "threads=N" and the version/ISA in *info (static text until close). */
int pn_embree_open(pn_embree **e, int threads, char *err, size_t err_size);
const char *pn_embree_info(const pn_embree *e);
void pn_embree_close(pn_embree *e);

/* pn_embree_build's flags: RTC_SCENE_FLAG_ROBUST, and RTC_BUILD_QUALITY_HIGH (Embree's
 * SAH build with spatial splits) instead of the default quality (MEDIUM for a static
 * scene). */
#define PN_EMBREE_ROBUST 1
#define PN_EMBREE_HIGH 2

/* (Re)builds the scene from the mesh (one triangle geometry, default build quality and
 * scene flags unless flags say otherwise: PN_EMBREE_*). *build_ms is the commit alone
 * (the BVH build), not the buffer copy. */
int pn_embree_build(pn_embree *e, const pn_mesh *mesh, int flags, double *build_ms, char *err,
                    size_t err_size);

/* The shadow pass: per pixel, k^2 occlusion rays from O to the samples (tnear 0, tfar
 * just under 1, direction S - O unnormalised), the pixel's own triangle rejected by an
 * occlusion filter, spread over threads with pn_threads_parallel_for. Writes vis (w*h)
 * and, if masks != NULL, the blocked bits. *ms is the wall time of the pass. */
int pn_embree_shadow(pn_embree *e, pn_embree_api api, const pn_gbuf *g, const pn_light *light,
                     uint32_t k, float eps, pn_threads *threads, float *vis, pn_masks *masks,
                     double *ms, char *err, size_t err_size);

/* ---- PCSS baseline (tools/pn_bench_pcss.c) --------------------------------------------- */

/* Percentage-closer soft shadows (Fernando 2005) as an engine ships them: one 2048^2
 * perspective depth map from the light centre along N, fitted to the G-buffer points in
 * front of the light (half-angle capped at tan 4), near plane at the nearest clipped
 * triangle; per pixel, from the same origin O = P + eps*n, a 16-tap blocker search over the
 * light's rectangle on the near plane, the penumbra estimate, and 32 bilinear PCF taps
 * (receiver-plane, constant and slope-scaled depth bias), times the horizon of the own
 * triangle over the k x k samples (so an unoccluded pixel equals the reference). Receivers
 * outside the map are unshadowed by it. Background pixels get 1, pixels behind the light 0.
 * The map build is part of the pass: *ms is the wall time of both. Deterministic for any
 * thread count. Returns 0, or non-zero with a message (allocation failure, degenerate
 * light, k outside 1..PN_MASK_K_MAX). */
int pn_pcss_shadow(const pn_mesh *mesh, const pn_gbuf *g, const pn_light *light, uint32_t k, float eps,
                   pn_threads *threads, float *vis, double *ms, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif
#endif
