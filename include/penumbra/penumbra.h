/* penumbra.h - soft shadows from rectangular area lights in a fixed amount of memory.
 *
 * WHAT IT IS
 *   A C99 library that renders, for a triangle scene seen from a pinhole camera, the
 *   fraction of a rectangular area light visible from the surface point behind every
 *   pixel (1 = lit, 0 = umbra), and a shaded RGBA8 image. Several published algorithms
 *   sit behind one API; PN_ALGO_REFERENCE is the exact ground truth (k x k light samples,
 *   watertight segment/triangle predicate, BVH).
 *
 * MEMORY MODEL
 *   The library never allocates. The caller asks how many bytes a set of limits needs
 *   (pn_arena_size), hands one block of at least that size to pn_init, and every pool
 *   (context, scene copy, BVH, G-buffer, outputs, scratch) is carved from it, aligned to
 *   64 bytes. PN_ARENA_BYTES_MAX(...) gives the same bound as a constant expression, so
 *   the block may be a static array. The library keeps pointers into the block until the
 *   caller stops using the context; there is no "destroy".
 *
 * TRUST MODEL
 *   Everything the caller passes is validated: NULL pointers, NaN/Inf, indices out of
 *   range, degenerate lights and cameras, sizes beyond the limits, and coordinates beyond
 *   2^40 in magnitude (PN_E_LIMIT: the predicate's triple products must stay far from
 *   float overflow). Bad input returns a
 *   specific pn_status, stores a message (pn_last_error), writes no out-parameter and
 *   modifies no caller memory. Scene data is *copied* into the arena by pn_scene_set, so
 *   the caller may free or change its arrays afterwards. Degenerate triangles are not
 *   errors: they are counted (pn_stats) and never rasterized or blocking. A triangle is
 *   degenerate when its normal (B - A) x (C - A) cannot be normalized in float: no
 *   component of at least FLT_MIN (2^-126), which includes zero area and triangles at
 *   subnormal scale. Cameras and lights whose frame cannot be formed in float (vectors
 *   shorter than about 1.1e-19, a fov too narrow for the image) are rejected the same way
 *   as exactly degenerate ones (PN_E_CAMERA, PN_E_LIGHT_DEGENERATE).
 *
 * THREADS
 *   The library starts no threads. Passes are split into work items (a frame's passes, and
 *   pn_scene_set's BVH build: its subtrees); by default they run in a loop on the calling
 *   thread. pn_set_parallel_for installs the caller's job system. Results never depend on
 *   how work items are scheduled (the BVH is the same tree for any schedule). A context is not re-entrant:
 *   one call at a time per context.
 *
 * USAGE
 *   pn_limits lim = { 100000, 512, 512, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 };  // max triangles, width, height; 0: default
 *   size_t bytes; pn_arena_size(&lim, &bytes);
 *   void *mem = my_alloc(bytes);             // or static uint8_t mem[PN_ARENA_BYTES_MAX(...)]
 *   pn_context *ctx; pn_init(&ctx, mem, bytes, &lim);
 *   pn_scene_set(ctx, positions, vertex_count, indices, triangle_count);
 *   pn_camera cam = { {0,1,3}, {0,0,0}, {0,1,0}, 45.0f };
 *   pn_light light = { {0,3,0}, {0.5f,0,0}, {0,0,0.5f} };
 *   pn_frame_options opt; pn_frame_options_default(&opt);   // 512x512, k = 16, reference
 *   pn_frame out; if (pn_render(ctx, &cam, &light, &opt, &out) != PN_OK) puts(pn_last_error(ctx));
 *   use(out.visibility, out.rgba);           // valid until the next render or scene call
 *
 * CONVENTIONS (shared with the CLI and every test; see docs/conventions.md)
 *   Right-handed, Y up. Camera: f = normalize(target - eye), r = normalize(f x up),
 *   u = r x f. Pixel (x, y), y = 0 the top row, looks along
 *   normalize(f + sx*tan(fov/2)*(W/H)*r + sy*tan(fov/2)*u), sx = 2(x+0.5)/W - 1,
 *   sy = 1 - 2(y+0.5)/H; fov is vertical, in degrees.
 *   Light: centre c, half-edges U and V (corners c +- U +- V), N = normalize(U x V); it
 *   emits toward +N only: a surface point P with (P - c).N <= 0 gets visibility 0.
 *   U = V = 0 (every component exactly 0) is a point light at c, shining in every
 *   direction: one sample. A non-zero U or V must be at least about 1.1e-19 long.
 *   Light sample (i, j) of k x k is c + ((2i+1)/k - 1) U + ((2j+1)/k - 1) V, mask bit j*k + i.
 *   A sample is blocked when it lies on or behind the plane of P's own triangle (on the
 *   side away from n, the geometric normal turned toward c: below P's horizon), or when
 *   the open segment from O = P + eps*n to the sample meets a closed triangle other than
 *   P's own. Every sign in that is decided exactly for the float inputs (a float filter,
 *   then exact expansion arithmetic in float where rounding could decide it: the same
 *   bits on every port; exact whenever no nonzero coordinate of a test is below 2^-63
 *   times its largest: kernels/pn_expansion.h).
 *   Visibility = unblocked samples / k^2. Background pixels: visibility 1, id PN_NO_TRIANGLE.
 */
#ifndef PENUMBRA_H
#define PENUMBRA_H

#include <stddef.h>
#include <stdint.h>

#include "penumbra/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Status ------------------------------------------------------------------------- */

typedef enum pn_status {
    PN_OK = 0,
    PN_E_INVALID_ARG = 1,      /* NULL pointer or an option out of its documented range */
    PN_E_ARENA_TOO_SMALL = 2,  /* the block given to pn_init is smaller than pn_arena_size */
    PN_E_LIMIT = 3,            /* a count or size exceeds pn_limits or a PN_MAX_* */
    PN_E_NONFINITE = 4,        /* NaN or infinite coordinate */
    PN_E_INDEX_RANGE = 5,      /* a triangle index >= vertex_count */
    PN_E_LIGHT_DEGENERATE = 6, /* exactly one light half-edge is zero, or a non-zero one is
                                  too short (under 1.1e-19) or U x V too small to be
                                  normalized in float */
    PN_E_LIGHT_NOT_ORTHO = 7,  /* light half-edges are not orthogonal */
    PN_E_CAMERA = 8,           /* eye == target, up parallel to view, fov outside (0,180);
                                  or a frame that cannot be formed in float: |target - eye|
                                  or |f x up| under 1.1e-19, or tan(fov/2) below
                                  height * 2^-24 (neighbouring pixels' rays coincide) */
    PN_E_IMAGE_SIZE = 9,       /* zero width or height */
    PN_E_NO_SCENE = 10,        /* pn_render before a successful pn_scene_set */
    PN_E_UNSUPPORTED = 11,     /* algorithm or port not compiled in, or not offered for the
                                  request (pn_visibility_points with the wedges) */
    PN_E_POOL_EXHAUSTED = 12,  /* a pool is too small for this frame; message names it */
    PN_E_DEVICE = 13,          /* a port's device failed (OpenCL port) */
    PN_E_INTERNAL = 14         /* a broken invariant; please report */
} pn_status;

/* Static text for any status ("PN_E_LIMIT: count or size exceeds a limit"). Never NULL. */
const char *pn_status_str(pn_status status);

/* ---- Arena and context -------------------------------------------------------------- */

typedef struct pn_context pn_context;

/* The run-time limits a context is sized for. Each must be >= 1 and <= its PN_MAX_*. An
 * algorithm's own fields (gears_*, srt_*, occ_*, mc_*, wg_*) are ignored in a build
 * without it. */
typedef struct pn_limits {
    uint32_t max_triangles;
    uint32_t max_width;
    uint32_t max_height;
    uint32_t gears_pairs;    /* GEARS (triangle, cell) pair pool; 0: 4 max_triangles +
                                max_width x max_height + gears_grid_max^2, at most 16 a
                                pixel, at least max_triangles, at most PN_GEARS_PAIRS (a
                                frame that needs more runs in tiles, same bytes) */
    uint32_t gears_grid_max; /* largest GEARS grid resolution; 0: PN_GEARS_GRID_MAX */
    uint32_t srt_map_max;    /* largest SRT shadow map per axis; 0: PN_SRT_MAP_MAX */
    uint32_t occ_map_max;    /* largest occlusion texture per axis; 0: PN_OCCTEX_MAP_MAX */
    uint32_t mc_map_max;     /* largest Monte Carlo depth layer per axis; 0: PN_MCSM_MAP_MAX */
    uint32_t wg_pairs;       /* penumbra wedges' (screen tile, wedge) pair pool, at most
                                PN_WEDGES_PAIRS; 0: a 32nd of every 16x16 tile of
                                max_width x max_height with every silhouette slot
                                (wg_silhouettes), at least 6 a slot,
                                at most PN_WEDGES_PAIRS. A frame needing more is binned in
                                bands of tiles (the same bytes); a 16x16 tile needing more
                                is full: its pixels take the reference's visibility at the
                                frame's k (pn_stats.wedges.full_tiles) */
    uint32_t bvh_refs;       /* BVH references (47 bytes of arena each, and 72 of the
                                frame region while the tree is built); beyond one a
                                triangle, split slivers (config.h PN_BVH_SPLIT_DEPTH; frames
                                are the same bits with or without; a scene of long thin
                                triangles traces faster with them). 0: max_triangles, no
                                splitting; at most max_triangles + PN_BVH_SPLIT_EXTRA
                                (PN_BVH_SPLIT_REFS, at most 2^depth - 1 a triangle, 2^26
                                in all) */
    uint32_t algos;          /* the algorithms the context will run, PN_BUILD_<ALGO> flags:
                                the frame region is sized for these alone, and a frame of
                                another fails PN_E_LIMIT. 0: every algorithm compiled in.
                                A flag of one not compiled in: PN_E_UNSUPPORTED */
    uint32_t flags;          /* PN_LIMITS_* (0: none) */
    uint32_t wg_silhouettes; /* penumbra wedges' silhouette pool (96 bytes a slot), 64 ..
                                PN_WEDGES_SIL_MAX; 0: 3 a triangle, at most
                                PN_WEDGES_SIL_MAX. A frame with more silhouettes makes them
                                in bands of tiles, each band only those its tiles list
                                (the same bytes); a tile listing more is full, as above.
                                Last, so that positional initializers of the fields above
                                still hold */
} pn_limits;

/* pn_limits.flags. PN_LIMITS_NO_SURFACE: frames keep no per-pixel position and normal (24
 * of a frame's 40 bytes a pixel): the passes recompute them from depth and tri_id where
 * they read them, by the functions that would have stored them, so every frame's
 * visibility, RGBA, depth and tri_id are the same bytes; pn_frame.position and .normal are
 * NULL. pn_visibility_points then takes its points in batches of width x ceil(height / 4)
 * (not width x height), which the approximate algorithms' light-space maps are fit to. */
#define PN_LIMITS_NO_SURFACE 0x1u
/* PN_LIMITS_SPARSE_NBUFFER: the Monte Carlo shadow maps' N-buffer keeps levels 0, 3, 6, ...
 * only, and a lookup of another level rebuilds its box from the 4 or 16 texels of the
 * level kept below, in the order the level would have been built: the same bytes in every
 * frame, 0.40x the N-buffer's memory at a map of 128 (423,000 bytes instead of 1,070,196),
 * slower searches (docs/bench/MEMORY.md). For targets where memory, not time, is short. */
#define PN_LIMITS_SPARSE_NBUFFER 0x2u

/* Limits equal to the compile-time maxima. */
void pn_limits_max(pn_limits *limits);

/* Bytes of arena that pn_init needs for `limits` (the same carve routine pn_init runs,
 * against a NULL base; plus PN_ARENA_ALIGN - 1 bytes so that any base address works).
 * Returns PN_OK, PN_E_INVALID_ARG (NULL), PN_E_LIMIT (a limit out of range, or the total
 * does not fit size_t) or PN_E_UNSUPPORTED (limits.algos names an algorithm not compiled
 * in). *out_bytes is written only on PN_OK. */
pn_status pn_arena_size(const pn_limits *limits, size_t *out_bytes);

/* Upper bound of pn_arena_size() for limits (t, w, h) with every other field 0 (the
 * defaults: every algorithm compiled in, no split BVH references) as a constant expression,
 * for static declaration: static uint8_t arena[PN_ARENA_BYTES_MAX(1000, 160, 120)]. It is
 * the carve written as arithmetic, pool by pool (each rounded up to PN_ARENA_ALIGN): the
 * persistent pools, then a frame region holding the largest of the frame's own pools plus
 * one algorithm's set and the scene-time scratch (BVH build; the connectivity of the wedges
 * and MCSM, with its pools when the wedges are not compiled in).
 * test_arena checks pn_arena_size <= it <= 1.25 pn_arena_size over a grid of limits, in
 * every single-algorithm build. Split references (limits.bvh_refs above t) cost
 * PN_BVH_SPLIT_REF_BYTES more each (the bound holds a spare four-wide node and 3
 * PN_ARENA_ALIGN for the three pools whose rounding they can lengthen beyond that: the
 * tree, the leaf order and the build scratch). */
#define PN_ARENA_BYTES_MAX(t, w, h)                                                          \
    (PN_PERSIST_BYTES_MAX(t) +                                                                \
     PN_MAX_(PN_FRAME_BYTES_MAX(t, w, h) +                                                    \
                 PN_MAX_(PN_MAX_(PN_GEARS_BYTES_MAX(t, w, h), PN_SRT_BYTES_MAX(t, w, h)),     \
                         PN_MAX_(PN_MAX_(PN_OCCTEX_BYTES_MAX(t, w, h), PN_MCSM_BYTES_MAX(t, w, h)), \
                                 PN_WEDGES_BYTES_MAX(t, w, h))),                              \
             PN_MAX_(PN_POOL_(PN_POOL_((size_t)(t) * 40u + ((size_t)(t) / 32u + 1u) * 4u + 2048u) + \
                             (size_t)(t) * 32u),                                              \
                     PN_ENABLE_WEDGES ? PN_POOL_((size_t)(t) * 24u)                              \
                     : PN_ENABLE_MCSM ? PN_POOL_((size_t)(t) * 52u + 4u) : 0u)) +                \
     (size_t)PN_ARENA_ALIGN - 1u + 3u * (size_t)PN_ARENA_ALIGN)
/* The split BVH references a context of t triangles may reserve (limits.bvh_refs up to t
 * plus these): PN_BVH_SPLIT_REFS, at most 2^PN_BVH_SPLIT_DEPTH - 1 a triangle (and t plus
 * them at most 2^26, which only lowers it). Each costs PN_BVH_SPLIT_REF_BYTES beyond
 * PN_ARENA_BYTES_MAX: a third of a four-wide node and an index entry (43 + 4), and its
 * build scratch (40, and a binary node: 32). */
#define PN_BVH_SPLIT_EXTRA(t)                                                                \
    ((size_t)((unsigned long long)PN_BVH_SPLIT_REFS <                                         \
                      ((1ull << PN_BVH_SPLIT_DEPTH) - 1ull) * (unsigned long long)(t)         \
                  ? (unsigned long long)PN_BVH_SPLIT_REFS                                     \
                  : ((1ull << PN_BVH_SPLIT_DEPTH) - 1ull) * (unsigned long long)(t)))
#define PN_BVH_SPLIT_REF_BYTES 119u
/* Helpers of the bounds: largest, smallest, a pool of n bytes as carved. */
#define PN_MAX_(a, b) ((a) > (b) ? (a) : (b))
#define PN_MIN_(a, b) ((a) < (b) ? (a) : (b))
#define PN_POOL_(n) (((size_t)(n) + PN_ARENA_ALIGN - 1u) / PN_ARENA_ALIGN * PN_ARENA_ALIGN)
/* Persistent pools, no split references: the context (at most 1536 bytes, checked in
 * src/pn_arena.c), per triangle its copy (36), flags (1), a third of a four-wide BVH node
 * (128 / 3, and one spare), its leaf-order and raster-order entries (4 + 4), port scratch
 * (1 KB); with the wedges their connectivity (12 + 12 + 4). */
#define PN_PERSIST_BYTES_MAX(t)                                                               \
    (PN_POOL_(1536u) + PN_POOL_((size_t)(t) * 36u) + PN_POOL_(t) +                               \
     PN_POOL_(((size_t)(t) / 3u + 2u) * 128u) + 2u * PN_POOL_((size_t)(t) * 4u) + PN_POOL_(1024u) + \
     (PN_ENABLE_WEDGES ? PN_POOL_((size_t)(t) * 12u) + PN_POOL_((size_t)(t) * 12u + 4u) +          \
                             PN_POOL_((size_t)(t) * 4u)                                          \
                       : 0u))
/* The frame's own pools: per pixel depth, triangle (4 + 4), position, normal (12 + 12),
 * visibility, RGBA (4 + 4); per triangle its raster rows (4), a chunk per 32 (4); per row
 * the shadow counters (64). */
#define PN_PX_(w, h) ((size_t)(w) * (size_t)(h))
#define PN_FRAME_BYTES_MAX(t, w, h)                                                           \
    (4u * PN_POOL_(PN_PX_(w, h) * 4u) + 2u * PN_POOL_(PN_PX_(w, h) * 12u) +                    \
     PN_POOL_((size_t)(t) * 4u) + PN_POOL_(((size_t)(t) + 31u) / 32u * 4u) + PN_POOL_((size_t)(h) * 64u))
/* floor(log2 r) + 1: the levels of an r^2 N-buffer or mipmap (8 <= r <= 8192). */
#define PN_LEVELS_(r)                                                                         \
    ((r) >= 8192u ? 14u : (r) >= 4096u ? 13u : (r) >= 2048u ? 12u : (r) >= 1024u ? 11u :           \
     (r) >= 512u ? 10u : (r) >= 256u ? 9u : (r) >= 128u ? 8u : (r) >= 64u ? 7u : (r) >= 32u ? 6u :  \
     (r) >= 16u ? 5u : 4u)
/* The default wedge pair pool (pn_limits.wg_pairs): the larger of a PN_WG_PAIRS_SHARE-th of
 * every tile with every silhouette slot and PN_WG_PAIRS_PER_SIL pairs a slot. */
#define PN_WG_PAIRS_SHARE 32u
#define PN_WG_PAIRS_PER_SIL 6u
#if PN_ENABLE_WEDGES
/* Penumbra-wedge frame pools: per triangle its casting (4) and silhouette slots (12); per
 * silhouette (at most 3 a triangle and PN_WEDGES_SIL_MAX) 96 + 4 + 8, and 4; per (16 x 16 tile,
 * silhouette) pair, at most PN_WEDGES_PAIRS, 8 + 4; per tile 4 + 4 and its box, 24. */
#define PN_WG_SIL_(t) PN_MIN_((size_t)(t) * 3u, (size_t)PN_WEDGES_SIL_MAX)
#define PN_WG_TILES_(w, h) ((((size_t)(w) + 15u) / 16u) * (((size_t)(h) + 15u) / 16u))
#define PN_WG_PAIRS_(t, w, h)                                                                 \
    PN_MIN_(PN_WG_TILES_(w, h) * PN_WG_SIL_(t),                                                \
            PN_MIN_(PN_MAX_(PN_WG_TILES_(w, h) * PN_WG_SIL_(t) / PN_WG_PAIRS_SHARE,                \
                            PN_WG_SIL_(t) * PN_WG_PAIRS_PER_SIL),                                  \
                    (size_t)PN_WEDGES_PAIRS))
#define PN_WEDGES_BYTES_MAX(t, w, h)                                                          \
    (PN_POOL_((size_t)(t) * 4u) + PN_POOL_((size_t)(t) * 12u + 4u) + PN_POOL_(PN_WG_SIL_(t) * 96u) + \
     PN_POOL_((PN_WG_SIL_(t) / 16u + 1u) * 24u) + PN_POOL_((PN_WG_SIL_(t) / 128u + 1u) * 24u) + \
     PN_POOL_(PN_WG_SIL_(t) * 4u + 4u) + PN_POOL_(PN_WG_PAIRS_(t, w, h) * 8u) +                 \
     PN_POOL_(PN_WG_PAIRS_(t, w, h) * 4u) + PN_POOL_(PN_WG_TILES_(w, h) * 4u + 4u) +              \
     PN_POOL_((((size_t)(h) + 15u) / 16u) * 4u) +                                                \
     PN_POOL_(PN_WG_TILES_(w, h) * 4u) + PN_POOL_(PN_WG_TILES_(w, h) * 28u) + PN_POOL_(PN_WG_SIL_(t) * 8u + 4u))
#else
#define PN_WEDGES_BYTES_MAX(t, w, h) ((size_t)0)
#endif
#if PN_ENABLE_MCSM
/* Monte Carlo shadow-map frame pools at the default map maximum r: per row its bounds
 * (32) and counters (64); 12 bytes a texel of the N-buffer, r^2 at level 0 and
 * (r + 1 - 2^l)^2 at levels l = 1 .. L - 1 (L = PN_LEVELS_(r)), whose sum is
 * (L - 1)(r + 1)^2 + (4^L - 4) / 3 - 2 (r + 1)(2^L - 2); per pixel the blur's buffer (4). */
#define PN_MC_NB_TEXELS_(r, L)                                                                \
    ((size_t)(r) * (r) + ((size_t)(L) - 1u) * ((size_t)(r) + 1u) * ((size_t)(r) + 1u) +          \
     (((size_t)1 << (2u * (L))) - 4u) / 3u - 2u * ((size_t)(r) + 1u) * (((size_t)1 << (L)) - 2u))
#define PN_MCSM_BYTES_MAX(t, w, h)                                                            \
    (PN_POOL_((size_t)(h) * 32u) +                                                             \
     PN_POOL_(PN_MC_NB_TEXELS_(PN_MCSM_MAP_MAX, PN_LEVELS_(PN_MCSM_MAP_MAX)) * 12u) +            \
     PN_POOL_(PN_PX_(w, h) * 4u) + PN_POOL_((size_t)(h) * 64u))
#else
#define PN_MCSM_BYTES_MAX(t, w, h) ((size_t)0)
#endif
#if PN_ENABLE_OCCTEX
/* Occlusion-texture frame pools at the default map maximum r: per row its bounds (32);
 * per texel the slice bits (4); one filter of 4 bytes a texel per N-buffer level (or
 * (r + 1)^2 words for a tiny map's summed-area table); 128 bytes of counters. */
#define PN_OCCTEX_BYTES_MAX(t, w, h)                                                          \
    (PN_POOL_((size_t)(h) * 32u) + PN_POOL_((size_t)PN_OCCTEX_MAP_MAX * (size_t)PN_OCCTEX_MAP_MAX * 4u) + \
     PN_POOL_(PN_MAX_((size_t)PN_OCCTEX_MAP_MAX * (size_t)PN_OCCTEX_MAP_MAX * PN_LEVELS_(PN_OCCTEX_MAP_MAX), \
                      ((size_t)PN_OCCTEX_MAP_MAX + 1u) * ((size_t)PN_OCCTEX_MAP_MAX + 1u)) * 4u) + \
     PN_POOL_(128u))
#else
#define PN_OCCTEX_BYTES_MAX(t, w, h) ((size_t)0)
#endif
#if PN_ENABLE_SRT
/* SRT frame pools at the default map maximum r: per row its bounds (32); per texel depth,
 * triangle and thin mark (3 x 4); per 8 x 8 tile three words; 16 bytes of counters; per
 * pixel its PIP flag and list entry (4 + 4, and one more word). */
#define PN_SRT_TL_ (((size_t)PN_SRT_MAP_MAX + 7u) / 8u * (((size_t)PN_SRT_MAP_MAX + 7u) / 8u))
#define PN_SRT_BYTES_MAX(t, w, h)                                                             \
    (PN_POOL_((size_t)(h) * 32u) + 3u * PN_POOL_((size_t)PN_SRT_MAP_MAX * (size_t)PN_SRT_MAP_MAX * 4u) + \
     3u * PN_POOL_(PN_SRT_TL_ * 4u) + PN_POOL_(16u) + PN_POOL_(PN_PX_(w, h) * 4u + 4u) +         \
     PN_POOL_(PN_PX_(w, h) * 4u))
#else
#define PN_SRT_BYTES_MAX(t, w, h) ((size_t)0)
#endif
#if PN_ENABLE_GEARS
/* GEARS frame pools at the default pair pool p (4 t + pixels + g^2, at most 16 a pixel,
 * at least t, at most PN_GEARS_PAIRS) and grid maximum g: the grid cameras (at
 * most 576 bytes); per triangle a cell rectangle (8); per pixel its
 * cell (4); per row an origin box (32); per cell of one face (g^2) offsets, counts and
 * cursors (12); per grid row of six faces (6 g) W = ceil(g / 32) words of occupancy bits,
 * W + 1 prefixes (4 each) and its pair count (8); per pair 4, a 24-byte box per 8 pairs
 * and per 64 (src/pn_gears.c's chunk and superchunk boxes), plus one of each. */
#define PN_GEARS_C_ ((size_t)PN_GEARS_GRID_MAX * (size_t)PN_GEARS_GRID_MAX)
#define PN_GEARS_R_ (6u * (size_t)PN_GEARS_GRID_MAX)
#define PN_GEARS_W_ (((size_t)PN_GEARS_GRID_MAX + 31u) / 32u)
#define PN_GEARS_P_(t, w, h)                                                                  \
    PN_MIN_(PN_MAX_(PN_MIN_((size_t)(t) * 4u + PN_PX_(w, h) + PN_GEARS_C_, PN_PX_(w, h) * 16u), (size_t)(t)), \
            (size_t)PN_GEARS_PAIRS)
#define PN_GEARS_BYTES_MAX(t, w, h)                                                           \
    (PN_POOL_(576u) + PN_POOL_((size_t)(t) * 8u) +                                               \
     PN_POOL_(PN_PX_(w, h) * 4u) + PN_POOL_((size_t)(h) * 32u) + PN_POOL_(PN_GEARS_R_ * PN_GEARS_W_ * 4u) + \
     PN_POOL_(PN_GEARS_R_ * (PN_GEARS_W_ + 1u) * 4u) + PN_POOL_(PN_GEARS_C_ * 4u + 4u) +             \
     2u * PN_POOL_(PN_GEARS_C_ * 4u) + PN_POOL_(PN_GEARS_R_ * 8u) +                             \
     PN_POOL_(PN_GEARS_P_(t, w, h) * 4u) + PN_POOL_((PN_GEARS_P_(t, w, h) / 8u + 1u) * 24u) +                  \
     PN_POOL_((PN_GEARS_P_(t, w, h) / 64u + 1u) * 24u))
#else
#define PN_GEARS_BYTES_MAX(t, w, h) ((size_t)0)
#endif

/* Wraps `memory` (bytes long, any alignment, caller-owned, must outlive the context) and
 * carves every pool. On PN_OK *out_ctx points into `memory`. On failure nothing in
 * `memory` is written and *out_ctx is untouched. Statuses: PN_E_INVALID_ARG,
 * PN_E_LIMIT, PN_E_UNSUPPORTED (as pn_arena_size), PN_E_ARENA_TOO_SMALL. There is no global state: contexts are independent. */
pn_status pn_init(pn_context **out_ctx, void *memory, size_t bytes, const pn_limits *limits);

/* The message of the most recent call on this context that failed ("" before any call has
 * failed). A call that succeeds leaves it as it was, so read it right after a call returned
 * a status other than PN_OK, as errno. Messages say what was wrong and the value or size
 * involved. Never NULL; "pn_last_error: NULL context" for a NULL ctx. */
const char *pn_last_error(const pn_context *ctx);

/* Work distribution. The library calls `parallel_for(user, count, fn, task)` and expects
 * fn(task, begin, end) to be called for disjoint ranges covering [0, count) exactly once,
 * from any threads, in any order, returning after all have finished. NULL restores the
 * serial loop. Work items write disjoint memory; results do not depend on the schedule. */
typedef void (*pn_task_fn)(void *task, uint32_t begin, uint32_t end);
typedef void (*pn_parallel_for_fn)(void *user, uint32_t count, pn_task_fn fn, void *task);
pn_status pn_set_parallel_for(pn_context *ctx, pn_parallel_for_fn parallel_for, void *user);

/* Optional clock for per-pass timings in pn_stats (nanoseconds, any epoch). NULL: none. */
typedef uint64_t (*pn_clock_fn)(void *user);
pn_status pn_set_clock(pn_context *ctx, pn_clock_fn clock, void *user);

/* ---- Scene -------------------------------------------------------------------------- */

/* Copies a triangle soup into the arena and builds its BVH. `positions` holds
 * vertex_count xyz float triples, `indices` triangle_count index triples; both are read,
 * never written, and may be freed after the call. Replaces the previous scene.
 * Statuses: PN_E_INVALID_ARG (NULL, zero triangles), PN_E_LIMIT (counts over the
 * limits, or a coordinate beyond 2^40), PN_E_NONFINITE (any vertex not finite),
 * PN_E_INDEX_RANGE. Zero-area triangles
 * are kept (their ids stay valid) but never drawn nor blocking; pn_stats counts them.
 * Winding: a triangle's front is the side it is counter-clockwise from. The exact
 * algorithms do not read it; MCSM and the wedges do for closed solids (a face turned from
 * the light is in its solid's shadow), and read a solid of negative volume reversed in a
 * frame whose light centre is outside its box (an inside-out solid; with the light inside,
 * a cavity such as a room wound inward), the six largest so, every smaller one always.
 * Open surfaces are lit on the light's side.
 * Validation reads everything before anything is written: on failure the previous scene
 * stays in place. */
pn_status pn_scene_set(pn_context *ctx, const float *positions, uint32_t vertex_count,
                       const uint32_t *indices, uint32_t triangle_count);

/* Moves the current scene's vertices: the same arguments as pn_scene_set, for a scene of
 * the same triangle count (its triangles in the same order, typically the same index
 * buffer with new positions). Instead of a new BVH the current one is refitted (its
 * boxes recomputed bottom-up, its order kept) and every algorithm's own scene data is
 * recomputed; the receiver marking is kept. Every frame afterwards has the same bytes as
 * after pn_scene_set of the moved scene (only the BVH's shape, and so pn_stats' node
 * counts, differ). When the set of degenerate triangles changes, or the current BVH holds
 * split references (limits.bvh_refs above max_triangles, and a scene of long thin
 * triangles), the BVH is built anew instead.
 * Statuses: those of pn_scene_set, PN_E_NO_SCENE, and PN_E_INVALID_ARG when
 * triangle_count is not the current scene's; on failure the current scene stays. */
pn_status pn_scene_update_positions(pn_context *ctx, const float *positions, uint32_t vertex_count,
                                    const uint32_t *indices, uint32_t triangle_count);

/* Marks triangles [first, first + count) of the current scene as receivers only: they
 * cast no shadow into the depth layers of PN_ALGO_MCSM (Curtis 2009 requires "pure
 * receivers", such as a ground plane, to stay out of the layers, which model occluders as
 * solids). Every other algorithm, the reference included, treats them like any triangle.
 * Replaces the previous marking; count = 0 clears it; pn_scene_set clears it too.
 * Statuses: PN_E_INVALID_ARG (NULL ctx), PN_E_NO_SCENE, PN_E_INDEX_RANGE (first + count
 * beyond the scene's triangles; nothing is changed). */
pn_status pn_scene_set_receivers(pn_context *ctx, uint32_t first, uint32_t count);

/* ---- Frame -------------------------------------------------------------------------- */

typedef struct pn_camera {
    float eye[3];
    float target[3];
    float up[3];
    float fov_deg; /* vertical, in (0, 180) */
} pn_camera;

typedef struct pn_light {
    float center[3];
    float u[3]; /* half-edge; u = v = 0 makes a point light */
    float v[3]; /* half-edge, orthogonal to u */
} pn_light;

typedef enum pn_algo {
    PN_ALGO_REFERENCE = 0,
    PN_ALGO_GEARS = 1,
    PN_ALGO_RAYTRACE = 2, /* k^2 single shadow rays per pixel; same bits as the reference */
    PN_ALGO_SRT = 3,      /* selective ray tracing: a shadow map, exact masks only for the
                             potentially incorrect pixels (approximate) */
    PN_ALGO_OCCTEX = 4,   /* occlusion textures: slices parallel to the light, box-filtered
                             and combined by probability (approximate) */
    PN_ALGO_MCSM = 5,     /* Monte Carlo shadow maps: hashed jittered rays traced through
                             depth layers with an N-buffer, then blurred (approximate) */
    PN_ALGO_WEDGES = 6    /* penumbra wedges: soft shadow volumes from the silhouettes seen
                             by the light centre, overlaps blended (approximate) */
} pn_algo;
#define PN_ALGO_COUNT 7 /* pn_algo values are 0 .. PN_ALGO_COUNT - 1 */

/* Each algorithm's own options, a sub-struct of pn_frame_options named after its module
 * (opt.srt, opt.mcsm, ...): all zero is every default of that algorithm. */
typedef struct pn_gears_options {
    uint32_t grid;         /* GEARS grid cells per axis, 1 .. limits.gears_grid_max; 0: the
                              smaller of PN_GEARS_GRID_DEFAULT (64) and the limit */
} pn_gears_options;

typedef struct pn_srt_options { /* PN_ALGO_SRT (0 everywhere is the recommended configuration) */
    uint32_t map;          /* shadow-map texels per axis, 8 .. limits.srt_map_max; 0: the
                              smaller of 2048 and the limit */
    float delta;           /* depth-discontinuity threshold, fraction of the scene diagonal;
                              0: 1e-3 */
    uint32_t flags;        /* PN_SRT_NO_CONSERVATIVE: no conservative rasterization of thin
                              triangles; PN_SRT_FORCE_PIP: every pixel exact (= reference) */
} pn_srt_options;

typedef struct pn_occtex_options { /* PN_ALGO_OCCTEX (0 everywhere is the recommended
                                      configuration) */
    uint32_t slices;       /* slices, 2 .. 16; 0: 16 */
    uint32_t map;          /* occlusion-texture texels per axis, 8 .. limits.occ_map_max; 0:
                              the smaller of 512 and the limit */
    uint32_t filter;       /* PN_OCC_FILTER_*; 0: PN_OCC_FILTER_SAT */
    uint32_t combine;      /* PN_OCC_COMBINE_*; 0: PN_OCC_COMBINE_PRODUCT */
    uint32_t flags;        /* PN_OCC_LEAK_FIX: a fragment marks the next slice too (paper
                              §3.4; off by default: measured, it does not reduce leaks here
                              and doubles planar occluders); PN_OCC_PAPER_FADE */
} pn_occtex_options;

typedef struct pn_mcsm_options { /* PN_ALGO_MCSM (0 everywhere is the recommended
                                    configuration) */
    uint32_t layers;       /* depth layers: 1 (near only), 2 (near, far) or 3 (near, far and
                              the eye's depth, Algorithm 1); 0: 3 for a frame, 2 for
                              pn_visibility_points */
    uint32_t search;       /* PN_MC_SEARCH_*; 0: PN_MC_SEARCH_HIER */
    uint32_t rays;         /* n: n x n jittered rays per pixel, 1 .. 8; 0: 3 */
    uint32_t blur;         /* depth-, normal- and edge-aware blur radius in pixels, 1 .. 8, or
                              PN_MC_BLUR_OFF; 0: 1 */
    uint32_t map;          /* depth-layer texels per axis, 8 .. limits.mc_map_max; 0: the
                              smaller of 512 and the limit */
    uint32_t flags;        /* PN_MC_NO_BIAS: no adaptive bias (eq. 3.2); PN_MC_NO_CLASSIFY:
                              no penumbra classification, early-outs or ray shortening
                              (every ray searched whole); PN_MC_NO_STACKED: a ray blocked
                              in a texel holding two solids or more along the light's ray
                              stays blocked (the layers' own answer; by default the
                              pixel's rays are then traced exactly: pn_mcsm_stats.stacked) */
    uint32_t seed;         /* frame key of the sample hash (Appendix A's key) */
} pn_mcsm_options;

typedef struct pn_wedges_options { /* PN_ALGO_WEDGES (0 is the recommended configuration) */
    uint32_t mode;         /* PN_WG_MODE_BLEND (Forest et al. 2006's overlap blending) or
                              PN_WG_MODE_ADDITIVE (the classic sum); 0: PN_WG_MODE_BLEND */
    uint32_t flags;        /* PN_WG_NO_CULL: every silhouette in every screen tile, every
                              object's and block's edges evaluated, every centre ray walked:
                              the same bytes, slower (what fuzz_culls checks the culls by) */
} pn_wedges_options;

typedef struct pn_frame_options {
    uint32_t width, height; /* >= 1, <= the context's limits */
    uint32_t k;             /* 4, 8, 16 or 32, <= PN_MASK_K_MAX (checked even for a point
                               light, which then uses one sample) */
    pn_algo algo;
    float eps;      /* shadow-ray offset in scene units (the CLI uses 1e-4 * scene diagonal);
                       finite, >= 0 */
    float albedo;   /* shading: rgb = albedo * (ambient + visibility * cos) ; [0, 1] */
    float ambient;  /* [0, 1] */
    uint8_t background[4]; /* RGBA8 of pixels that see no triangle */
    uint32_t exact_stats;  /* 1: no early exit on a full mask, so pn_stats counts every
                              candidate's predicate ("necessary" assignments, paper Table 6) */
    /* each algorithm's own options (only the frame's algo reads its own) */
    pn_gears_options gears;
    pn_srt_options srt;
    pn_occtex_options occtex;
    pn_mcsm_options mcsm;
    pn_wedges_options wedges;
    /* An engine's own G-buffer and its own output buffers (all NULL / 0 by default): */
    const struct pn_gbuffer *gbuffer; /* NULL: the library rasterizes the camera's view;
                                         else the caller's (pn_gbuffer), read, never written */
    float *visibility_out; /* NULL, or width*height floats: the visibility is also written here */
    uint8_t *rgba_out;     /* NULL, or width*height*4 bytes: the RGBA image is also written here */
    uint32_t no_rgba;      /* 1: no shading pass, pn_frame.rgba is NULL (rgba_out must be NULL) */
} pn_frame_options;

/* A G-buffer the caller drew with the frame's camera (pn_frame_options.gbuffer): two
 * arrays of width*height, row-major, top row first, as pn_frame returns them. The library
 * recomputes each pixel's position and normal from them exactly as its own rasterizer
 * does (position = eye + depth * the pixel's ray direction of CONVENTIONS, normal = the
 * triangle's unit geometric normal), so handing back pn_frame's own depth and tri_id gives
 * the same bytes as rasterizing, on every port. Per pixel, tri_id is PN_NO_TRIANGLE
 * (background: depth is not read) or a non-degenerate triangle of the scene, and depth is
 * finite, > 0, and puts the point within 2^40 of the origin; else the frame fails before
 * anything is written: PN_E_INDEX_RANGE (an id beyond the scene), PN_E_INVALID_ARG (a
 * degenerate triangle's id, a depth <= 0), PN_E_NONFINITE, PN_E_LIMIT, the message naming
 * the pixel. An engine's depth buffer holds view-space z or a projected depth: convert it
 * to the distance along the ray (z / cos of the ray's angle to the view direction). */
typedef struct pn_gbuffer {
    const float *depth;     /* distance from the eye along the pixel's primary ray */
    const uint32_t *tri_id; /* the triangle seen (scene order), or PN_NO_TRIANGLE */
} pn_gbuffer;

#define PN_WG_MODE_BLEND 1u
#define PN_WG_MODE_ADDITIVE 2u
#define PN_WG_NO_CULL 0x1u

#define PN_SRT_NO_CONSERVATIVE 0x1u
#define PN_SRT_FORCE_PIP 0x2u
/* Box filters of an occlusion texture (paper §3.2). */
#define PN_OCC_FILTER_NBUFFER 1u /* means of 2^l x 2^l boxes, interpolated between levels */
#define PN_OCC_FILTER_SAT 2u     /* summed-area table: the exact box integral */
#define PN_OCC_FILTER_MIPMAP 3u  /* dyadic means, trilinear */
/* How the slices' occlusions I_k combine into visibility (paper §3.3). */
#define PN_OCC_COMBINE_PRODUCT 1u /* prod (1 - I_k), eq. 5 */
#define PN_OCC_COMBINE_MAX 2u     /* 1 - max I_k */
#define PN_OCC_COMBINE_SUM 3u     /* max(0, 1 - sum I_k) */
#define PN_OCC_LEAK_FIX 0x1u
#define PN_OCC_PAPER_FADE 0x2u /* the paper's fade alone: no depth map for the slice holding a
                                  point and the one above it */
/* How a Monte Carlo ray is traced through the depth layers (Curtis 2009 §3.3, §3.5). */
#define PN_MC_SEARCH_LINEAR 1u /* texel-spaced steps, binary refinement on transitions */
#define PN_MC_SEARCH_HIER 2u   /* hierarchical search through the N-buffer (Algorithm 2) */
#define PN_MC_BLUR_OFF 0xFFFFFFFFu
#define PN_MC_NO_BIAS 0x1u
#define PN_MC_NO_CLASSIFY 0x2u
#define PN_MC_NO_STACKED 0x4u

/* 512x512, k = 16, the reference (in a build without it, the first algorithm compiled in,
 * in pn_algo order), eps = 1e-4, albedo 0.8, ambient 0.1, dark blue background; every
 * algorithm's sub-struct zero (its defaults: GEARS' grid PN_GEARS_GRID_DEFAULT, 64, at most the limit). */
void pn_frame_options_default(pn_frame_options *opt);

#define PN_NO_TRIANGLE 0xFFFFFFFFu

/* Results of one pn_render. All pointers point into the arena and stay valid until the
 * next pn_render, pn_visibility_points or scene call on the context. Arrays are
 * width*height, row-major, top row first. */
typedef struct pn_frame {
    uint32_t width, height;
    const float *visibility;  /* [0, 1] */
    const uint8_t *rgba;      /* 4 bytes per pixel; NULL when the options set no_rgba */
    const uint32_t *tri_id;   /* triangle index (scene order) or PN_NO_TRIANGLE */
    const float *depth;       /* distance along the pixel's primary ray; +inf background */
    const float *position;    /* 3 floats per pixel: world position on the triangle (NULL:
                                 the context's limits set PN_LIMITS_NO_SURFACE) */
    const float *normal;      /* 3 floats per pixel: unit geometric normal (winding order;
                                 NULL as position) */
} pn_frame;

/* Renders one frame: G-buffer (rasterized, or the caller's opt->gbuffer, checked as
 * pn_gbuffer says), shadow pass of opt->algo, shading (unless opt->no_rgba); then the
 * visibility and the image also into opt->visibility_out and opt->rgba_out when set
 * (PN_E_INVALID_ARG for one inside the arena, or rgba_out with no_rgba).
 * Statuses: PN_E_INVALID_ARG, PN_E_NO_SCENE, PN_E_NONFINITE (camera or light),
 * PN_E_CAMERA, PN_E_LIGHT_DEGENERATE, PN_E_LIGHT_NOT_ORTHO, PN_E_IMAGE_SIZE, PN_E_LIMIT
 * (sizes over the limits, coordinates or eps beyond 2^40), PN_E_UNSUPPORTED,
 * PN_E_POOL_EXHAUSTED (GEARS: a single grid cell needs more pairs than the pair pool;
 * the message names the pool and the count). *out is written only on PN_OK. */
pn_status pn_render(pn_context *ctx, const pn_camera *camera, const pn_light *light,
                    const pn_frame_options *opt, pn_frame *out);

/* Visibility of the light at n arbitrary surface points (light maps, probes, texture-space
 * shading): out[i] for the point points[3i..3i+2] on triangle tri_ids[i] with unit
 * geometric normal normals[3i..3i+2] (the triangle's, wound as the scene winds it; |n|
 * within 1e-3 of 1), or 1 for tri_ids[i] = PN_NO_TRIANGLE, computed as a frame computes a
 * pixel's. opt gives the algorithm, k, eps and the algorithm's options, and the shape of a
 * batch: the points are taken width x height at a time (width x ceil(height / 4) in a
 * context whose limits set PN_LIMITS_NO_SURFACE), point i of a batch standing where pixel
 * (i % width, i / width) stands in a frame (within the context's limits; G-buffer, output
 * and shading fields are not read). So at a frame's own pixels (its position, normal and
 * tri_id, in order, with the frame's options) out is the frame's visibility bit for bit
 * (for a map-based algorithm, when one batch holds them all); a map-based algorithm fits
 * its maps to each batch's points. Algorithms: the
 * reference, GEARS, ray tracing, SRT, the occlusion textures and MCSM (its screen-space
 * blur is not run; layers 1 or 2, by default 2); the wedges, which work in a camera's screen tiles, and
 * MCSM's third layer (the eye's depth) return PN_E_UNSUPPORTED. Statuses: those of
 * pn_render for the light and the options, PN_E_INVALID_ARG (NULL pointers when n > 0, a
 * normal not unit, a degenerate triangle's id), PN_E_INDEX_RANGE (an id beyond the scene),
 * PN_E_NONFINITE, PN_E_LIMIT (a coordinate beyond 2^40), the message naming the point:
 * every point is checked before anything is written. The frame's buffers in the arena are
 * reused (a pn_frame from before is no longer valid). out is written batch by batch: on a
 * failure after the checks (PN_E_POOL_EXHAUSTED, PN_E_DEVICE) it may hold the batches
 * done. */
pn_status pn_visibility_points(pn_context *ctx, const pn_light *light, const pn_frame_options *opt,
                               const float *points, const float *normals, const uint32_t *tri_ids, uint32_t n,
                               float *out);

/* ---- Introspection ------------------------------------------------------------------ */

/* pn_stats.pass_ns: the last pn_scene_set or pn_scene_update_positions (its copy, its BVH
 * build or refit, and every algorithm's own scene work: the wedges' and MCSM's
 * connectivity), and the last frame's passes (a point query: its shadow pass). */
enum { PN_PASS_SCENE_COPY, PN_PASS_BVH_BUILD, PN_PASS_GBUFFER, PN_PASS_SHADOW, PN_PASS_SHADE,
       PN_PASS_SCENE_ALGOS, PN_PASS_COUNT };

/* Each algorithm's own statistics, a sub-struct of pn_stats named after its module
 * (stats.gears, stats.mcsm, ...), as the last frame that ran that algorithm left them. */
typedef struct pn_gears_stats { /* GEARS (paper Tables 5 and 6), last frame */
    uint64_t pairs;              /* (triangle, cell) pairs generated, over all tiles */
    uint64_t assignments;        /* triangle-to-pixel assignments: sum over cells of
                                    triangles x pixels */
    uint32_t tiles;              /* passes the pair pool needed */
    uint32_t faces;              /* 1 for an area light, 6 for a point light (cube) */
    uint32_t cells_used;         /* cells with at least one pixel */
    uint32_t max_tris_per_cell, max_pixels_per_cell;
    float mean_tris_per_cell, mean_pixels_per_cell; /* over cells with pixels */
    uint32_t pairs_high_water;   /* most pairs held at once */
    uint32_t grid;               /* cells per axis the frame used (gears.grid, or its default) */
} pn_gears_stats;

typedef struct pn_srt_stats { /* Selective ray tracing, last frame */
    uint32_t map;                /* shadow-map texels per axis */
    uint32_t pip;                /* pixels in the PIP set (exact masks computed) */
    uint32_t thin;               /* thin triangles conservatively rasterized into the map */
    uint32_t tiles_masked;       /* penumbra-mask tiles (8x8 texels) set (area light) */
    uint32_t cons_texels;        /* map texels the thin triangles marked (each counted once) */
    /* ...and its stages' share of pass_ns[PN_PASS_SHADOW] (0 without a clock): the map
     * (window, rasterization, conservative marks, penumbra tiles), the classification
     * with the PIP list, and the exact masks of the PIP pixels */
    uint64_t ns_map, ns_classify, ns_exact;
} pn_srt_stats;

typedef struct pn_occtex_stats { /* Occlusion textures, last frame */
    uint32_t map;                /* texels per axis */
    uint32_t slices;             /* slices */
    uint32_t outside;            /* lit pixels whose shadow-ray origin the slicing view cannot
                                    hold (closer to the light's plane, or further off its axis,
                                    than 76 degrees): no slice holds their occluders, so they
                                    take the reference's visibility over min(k, 4)^2 samples */
    uint64_t texels_set;         /* (texel, slice) bits set, over all slices */
    uint64_t lookups;            /* filtered lookups: slices weighted > 0, over lit pixels */
    /* ...and its stages' share of pass_ns[PN_PASS_SHADOW]: slicing (window, depth range,
     * rasterization), pre-filtering (every slice), lookups and combination */
    uint64_t ns_slice, ns_filter, ns_lookup;
} pn_occtex_stats;

typedef struct pn_mcsm_stats { /* Monte Carlo shadow maps, last frame */
    uint32_t map;                /* depth-layer texels per axis */
    uint32_t lit, umbra, penumbra; /* lit pixels the classification called fully lit,
                                    umbra (with those whose surface faces away from the
                                    light centre), or potentially in penumbra (rays traced) */
    uint32_t penumbra_open;      /* ...of the penumbra pixels, those whose rays no layer
                                    blocked (the classification could have called them lit) */
    uint32_t penumbra_shut;      /* ...and those with samples in front of their surface, every
                                    one of them blocked by the layers (the rest: mixed) */
    uint64_t rays;               /* rays searched through the layers (after the early-outs) */
    uint64_t steps;              /* search steps: N-buffer boxes or linear samples looked up */
    uint32_t capped;             /* searches stopped by the step cap (taken as unblocked) */
    uint32_t outside;            /* lit pixels whose shadow-ray origin no layer window can hold
                                    (as occtex.outside): the reference's visibility over
                                    min(k, 4)^2 samples, not the layers' */
    uint32_t grazing;            /* pixels the classification left in penumbra whose surface
                                    makes a cosine below 0.2 with the light centre (there no
                                    bias of eq. 3.2 covers a texel's depth range without
                                    leaking): the same exact fallback */
    uint32_t stacked;            /* pixels whose rays the layers blocked in a texel holding
                                    two solids or more along the light's ray (two leaves,
                                    two flights of stairs: the layers' one interval fills
                                    the gap between them, which depth layers cannot
                                    represent): their rays traced exactly instead */
    /* ...and its stages' share of pass_ns[PN_PASS_SHADOW]: layers (window, rasterization),
     * N-buffer, rays (classification and search; the exact fallback's pass), blur */
    uint64_t ns_layers, ns_nbuffer, ns_rays, ns_blur;
} pn_mcsm_stats;

typedef struct pn_wedges_stats { /* Penumbra wedges: the scene's connectivity (at
                                    pn_scene_set) */
    uint32_t vertices;           /* distinct vertex positions after welding */
    uint32_t edges;              /* edges (distinct vertex pairs of non-degenerate triangles) */
    uint32_t open_edges;         /* edges with one triangle: silhouettes from every view */
    uint32_t nonmanifold_edges;  /* edges with three or more triangles, or two winding
                                    the same way */
    uint32_t objects;            /* triangles joined by shared vertices */
    uint32_t closed_objects;     /* objects cast as solids: closed, or but for small holes
                                    and seams (the others are sheets) */
    uint32_t duplicates;         /* triangles on the vertices of another (a double-sided
                                    sheet's back): they cast nothing */
    /* ...and the last frame */
    uint32_t inverted_objects;   /* closed objects wound inside out (negative volume, the
                                    light centre outside their box): MCSM and the wedges
                                    read their fronts reversed */
    uint32_t silhouettes;        /* silhouette edges seen from the light centre (= wedges) */
    uint64_t pairs;              /* (screen tile, wedge) pairs binned */
    uint32_t bands;              /* binning passes: bands of tiles whose pairs fit the pair
                                    pool (1 when the whole screen's do) */
    uint32_t sil_bands;          /* silhouette passes: bands of tile rows whose silhouettes
                                    fit the silhouette pool (1 when the frame's do) */
    uint64_t evaluated;          /* (pixel, wedge) pairs evaluated */
    uint64_t touched;            /* ...of which the edge covered some of the light: the pixels
                                    touched per wedge are touched / silhouettes */
    uint64_t hard_blockers;      /* triangles found blocking the pixels' centre rays */
    uint32_t hard_overflow;      /* pixels with more than 16 objects (or casting triangles)
                                    blocking the centre whose wedges reach them, more than
                                    a pixel keeps track of: resolved exactly, as below */
    uint32_t exact_pixels;       /* pixels in their own object's self-shadow penumbra or
                                    past that cap, resolved with the reference's exact
                                    predicate (over at most 4 x 4 samples), and the pixels
                                    of full tiles (at the frame's k) */
    uint32_t full_tiles;         /* 16 x 16 screen tiles whose wedges outgrew the silhouette
                                    or pair pool (pn_limits.wg_silhouettes, wg_pairs):
                                    their pixels took the reference's visibility */
    /* ...and its stages' share of pass_ns[PN_PASS_SHADOW]: silhouettes, binning, pixels */
    uint64_t ns_silhouettes, ns_binning, ns_pixels;
} pn_wedges_stats;

typedef struct pn_stats {
    size_t arena_bytes;          /* size of the block given to pn_init */
    size_t arena_carved;         /* bytes the carve routine laid out (persistent + frame) */
    size_t arena_persistent;     /* context, scene copy, BVH */
    size_t arena_high_water;     /* most bytes ever in use, from the aligned base */
    uint32_t triangles;          /* in the current scene */
    uint32_t degenerate_triangles;
    uint32_t bvh_nodes;          /* nodes of the binary tree the build makes (scratch) */
    uint32_t bvh_depth;          /* its depth, at most PN_BVH_DEPTH_MAX (src/pn_internal.h) */
    uint32_t bvh_max_leaf;
    uint32_t bvh_refs;           /* BVH references: triangles, a split one counted once per
                                    part (config.h PN_BVH_SPLIT_DEPTH) */
    uint32_t bvh_wide_nodes;     /* nodes of the four-wide tree it is folded into: the one
                                    kept, which the walks use */
    uint64_t pass_ns[PN_PASS_COUNT]; /* 0 without a clock; last scene set / last frame */
    uint64_t shadow_candidates;  /* triangles handed to the predicate in the last frame
                                    (PN_ALGO_RAYTRACE: ray-triangle tests; PN_ALGO_OCCTEX:
                                    its filtered lookups, = occtex.lookups) */
    uint64_t shadow_blocking;    /* ...of which blocked at least one sample (per pixel;
                                    PN_ALGO_RAYTRACE: blocked rays) */
    uint64_t shadow_nodes;       /* BVH nodes whose boxes the shadow pass tested (GEARS,
                                    which walks no BVH: its cell lists' superchunk and chunk
                                    boxes tested against a pixel's light frustum) */
    uint32_t lit_pixels;         /* pixels that see a triangle facing the light */
    float cull_tol;              /* last frame, scene units: slack of the conservative culls
                                    (their own rounding; the predicate is exact) */
    /* each algorithm's own statistics, as the last frame that ran it left them (the
     * wedges' connectivity: as the last pn_scene_set left it) */
    pn_gears_stats gears;
    pn_srt_stats srt;
    pn_occtex_stats occtex;
    pn_mcsm_stats mcsm;
    pn_wedges_stats wedges;
} pn_stats;

/* Copies the context's statistics into *out: the arena's sizes and high-water mark, the
 * last pn_scene_set's counts and times, the last frame's per-pass times and shadow
 * counters, and each algorithm's own sub-struct (gears, srt, occtex, mcsm, wedges) as
 * the last frame that ran that algorithm left them. Every time is 0 without a clock (pn_set_clock).
 * Cheap: no pass runs. ctx and out must not be NULL
 * (PN_E_INVALID_ARG, *out untouched, no message: there may be no context to hold one);
 * otherwise PN_OK. */
pn_status pn_get_stats(const pn_context *ctx, pn_stats *out);

/* Which algorithms and ports this build holds, as flags: PN_BUILD_<ALGO> is
 * 1u << PN_ALGO_<ALGO>, so `pn_build_info() & (1u << a)` tests pn_algo a. */
#define PN_BUILD_REFERENCE 0x1u
#define PN_BUILD_GEARS 0x2u
#define PN_BUILD_RAYTRACE 0x4u
#define PN_BUILD_SRT 0x8u
#define PN_BUILD_OCCTEX 0x10u
#define PN_BUILD_MCSM 0x20u
#define PN_BUILD_WEDGES 0x40u
#define PN_BUILD_PORT_SCALAR 0x100u
uint32_t pn_build_info(void);
/* The algorithms of the configuration this file is compiled with (config.h, PN_ALGORITHMS):
 * a program compiled against the library's configuration has
 * (pn_build_info() & 0xFFu) == PN_BUILD_ALGORITHMS (the installed package and pkg-config
 * carry it; tests/consumer checks it). */
#define PN_BUILD_ALGORITHMS                                                                     \
    ((PN_ENABLE_REFERENCE ? PN_BUILD_REFERENCE : 0u) | (PN_ENABLE_GEARS ? PN_BUILD_GEARS : 0u) |   \
     (PN_ENABLE_RAYTRACE ? PN_BUILD_RAYTRACE : 0u) | (PN_ENABLE_SRT ? PN_BUILD_SRT : 0u) |         \
     (PN_ENABLE_OCCTEX ? PN_BUILD_OCCTEX : 0u) | (PN_ENABLE_MCSM ? PN_BUILD_MCSM : 0u) |           \
     (PN_ENABLE_WEDGES ? PN_BUILD_WEDGES : 0u))

/* An algorithm's name: "reference", "gears", "raytrace", "srt", "occtex", "mcsm",
 * "wedges" (what the CLI's --algo takes and the golden frames are keyed by), whether or not
 * it is compiled in; NULL for a value outside 0 .. PN_ALGO_COUNT - 1. Static storage. */
const char *pn_algo_name(pn_algo algo);

#ifdef __cplusplus
}
#endif
#endif
