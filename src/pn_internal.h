/* pn_internal.h - the context, the arena layout and the port interface. Not installed. */
#ifndef PN_INTERNAL_H
#define PN_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "penumbra/penumbra.h"
#include "pn_kpools.h"

/* Coordinates must satisfy |x| <= PN_MAX_COORD: the predicate's triple products are cubic
 * in coordinate differences and must stay far from float overflow ((2*2^40)^3 ~ 1e37). */
#define PN_MAX_COORD 1099511627776.0f /* 2^40 */

/* Byte offsets of every pool from the 64-byte aligned base. Computed by pn_carve() alone,
 * for the size query and for init alike. */
typedef struct pn_layout {
    size_t ctx;
    size_t tris;      /* max_triangles * 9 floats: the scene copy */
    size_t flags;     /* max_triangles bytes */
    size_t wnodes;    /* pn_bvh_wide_max four-wide BVH nodes (src/pn_bvh_build.c) */
    size_t index;     /* pn_bvh_refs_max uint32: BVH leaf order (references: triangle ids,
                         a split triangle's repeated) */
    size_t rindex;    /* max_triangles uint32: raster order (each triangle once, leaf order) */
    size_t scratch;   /* PN_PORT_SCRATCH_WORDS uint32: port scratch */
    size_t algo[PN_ALGO_COUNT]; /* each algorithm's persistent pools start here (its module
                                   carves them: pn_<name>_persist), in pn_algo order */
    size_t frame;     /* start of the per-frame region */
    size_t frame_cap; /* its size: the sum of the largest frame pools */
    size_t end;       /* frame + frame_cap */
} pn_layout;

typedef struct pn_port pn_port; /* pn_device.h */

/* One frame as the algorithms' sequences see it: the port that runs it, the pool offsets
 * and launch parameters its passes get, and the pools' host addresses. */
typedef struct pn_frame_state {
    pn_context *ctx;
    const pn_port *port;
    pn_kpools P;
    pn_kparams K;       /* K.view, K.light, K.shade: the frame's; K.tile per launch */
    uint32_t algo;
    uint32_t width, height;
    uint32_t points;    /* 1: a point query (pn_visibility_points): no camera, the G-buffer the
                           caller's points, width x height their batch */
    uint32_t res;       /* the algorithm's grid or map per axis (its prepare sets it) */
    float *depth;
    uint32_t *tri_id;
    float *pos;
    float *nrm;
    float *vis;
    uint8_t *rgba;      /* 4 bytes per pixel, r g b a */
    uint32_t *rows;     /* rasterizer set-up: pixel-row range per triangle */
    uint32_t *chunks;   /* the band walk's: pixel-row range per chunk of the BVH's leaf order */
    void *counters;     /* per-row shadow counters (pn_row_counters[height]) */
    uint64_t candidates, blocking, nodes;
    uint32_t lit, overflow;
} pn_frame_state;

/* Words of port scratch (a persistent pool): a device port's prefix sum keeps its block
 * partials there. */
#define PN_PORT_SCRATCH_WORDS 256u
/* Groups of closed objects of negative volume a context keeps track of (pn_connect_light):
 * the largest objects one each, and the last group the others (three bits of a triangle's
 * flags). */
#define PN_CN_NEG_MAX 7u

struct pn_context {
    pn_limits limits;
    pn_layout layout;
    uint8_t *base;       /* aligned base: the context itself sits here */
    size_t bytes;        /* as given to pn_init */
    /* persistent pools */
    float *tris;
    uint8_t *flags;
    pn_kbvh4 *wnodes;
    uint32_t *tri_index;    /* BVH leaf order: bvh_refs entries */
    uint32_t *raster_index; /* raster order: bvh_tris entries */
    uint32_t *scratch;
    /* frame region: a bump allocator rewound at every frame */
    uint8_t *frame;
    size_t frame_top;
    size_t frame_high;
    /* scene */
    uint32_t has_scene;
    uint32_t scene_version; /* changes whenever pn_scene_set replaces the scene (or
                               pn_scene_update_positions moves it, pn_scene_set_receivers
                               marks it) */
    uint32_t tri_count;
    uint32_t degenerate;
    uint32_t bvh_nodes, bvh_depth, bvh_max_leaf, bvh_tris, bvh_refs;
    uint32_t bvh_wide; /* four-wide nodes: the tree (bvh_nodes counts the binary one it
                          was folded from) */
    uint32_t bvh_depth_max; /* the builder's depth bound: PN_BVH_DEPTH_MAX (test_bvh lowers
                               it to see it act on a small scene) */
    float scene_min[3], scene_max[3], scene_diag;
    /* box of the occluders (every triangle not marked receiver-only: the triangles' box at
     * pn_scene_set, pn_occluder_box at pn_scene_set_receivers and, when some triangle is
     * a receiver, at pn_scene_update_positions),
     * empty (min > max) when every triangle is a receiver */
    float occ_min[3], occ_max[3];
    /* closed objects of negative volume (src/pn_connect.c, for MCSM and the wedges): each
     * group's box and objects (PN_TRI_NEGVOL), and the groups the last frame read reversed
     * (bit g - 1: group g) */
    struct {
        float lo[3], hi[3];
        uint32_t objects;
    } neg[PN_CN_NEG_MAX];
    uint32_t neg_groups, neg_mask;
    /* execution */
    pn_parallel_for_fn parallel_for;
    void *parallel_user;
    pn_clock_fn clock;
    void *clock_user;
    /* diagnostics */
    uint64_t pass_ns[PN_PASS_COUNT];
    uint64_t shadow_candidates, shadow_blocking, shadow_nodes;
    uint32_t lit_pixels;
    float cull_tol;
    /* each algorithm's public statistics: the sub-structs of pn_stats, written by its
     * module (the other fields of this copy are unused: pn_get_stats fills them) */
    pn_stats stats;
    char message[256];
};

/* pn_arena.c */
/* BVH references a context reserves: limits.bvh_refs, or max_triangles (no splitting);
 * at most the cap, max_triangles plus the split ones (config.h PN_BVH_SPLIT_REFS, at most
 * 2^PN_BVH_SPLIT_DEPTH - 1 a triangle), at most 2^26. */
uint32_t pn_bvh_refs_cap(const pn_limits *l);
uint32_t pn_bvh_refs_max(const pn_limits *l);
/* Every algorithm's PN_BUILD_ flag, and those a context runs (limits.algos, 0: every one
 * compiled in). */
#define PN_ALGO_FLAGS ((1u << PN_ALGO_COUNT) - 1u)
uint32_t pn_limits_algos(const pn_limits *l);
/* N-buffer / mipmap levels of a res^2 texture (floor(log2 res) + 1): the occlusion
 * textures' filters and the Monte Carlo layers' N-buffer. */
uint32_t pn_nb_levels(uint32_t res);
/* Floats per row of the light view's bounds pool (kernels/pn_lview.h PN_LVIEW_BOX). */
#define PN_LVIEW_BOX_FLOATS 8u
/* The light view's frame (SRT, occlusion textures): eye at the light centre; an area light
 * looks along N with axes U^, V^, a point light toward the scene's centre; square, res^2,
 * tan_half 1 until the caller fits its window. */
void pn_light_view(const pn_context *ctx, const pn_klight *L, uint32_t res, pn_kview *lv);
/* The window of a light view from a centre of projection d behind the light centre
 * (occlusion textures, Monte Carlo shadow maps): from the row bounds `box` of the lit
 * origins (height rows of PN_LVIEW_BOX_FLOATS, kernels/pn_lview.h, computed with the light's
 * half-sizes ha, hb), an area light's d = 1 / max over origins of (|x| - ha) / (ha z) and
 * (|y| - hb) / (hb z) (the frustum through the light's edges then holds every origin, and
 * so every segment from the light to one: Curtis 2009 eq. 3.1, Eisemann 2006 Fig. 5),
 * widened by two texels for rounding, at most twice the scene diagonal and at least such
 * that the frustum stays within PN_LVIEW_TAN_MAX; a point light's window fitted to the
 * origins' tans (d = 0). Sets lv's eye, tan_half, aspect and znear, and *w. Returns 0 when no lit origin lies in front of the light. */
/* The light's half-edge lengths |U|, |V| (0 for a point light): the window's ha, hb. */
void pn_light_halves(const pn_klight *L, float *ha, float *hb);
typedef struct pn_lwin {
    float d, zmax; /* centre of projection behind the light centre; deepest origin */
    float tx, ty;  /* the window's half-tans */
} pn_lwin;
int pn_lview_window(const pn_context *ctx, const float *box, uint32_t height, uint32_t res, const pn_klight *L, float ha,
                    float hb, pn_kview *lv, pn_lwin *w);
/* Narrows the window (*w, lv's tan_half and aspect) of an area light's view to the image
 * of the occluders' box (ctx->occ_min / occ_max, clipped to the light plane's front), widened
 * by two texels of res for rounding, where that is smaller: a point beyond it lies in no
 * occluder. */
void pn_lview_fit_occluders(const pn_context *ctx, uint32_t res, const pn_klight *L, pn_kview *lv, pn_lwin *w);
pn_status pn_carve(const pn_limits *limits, pn_layout *out);
void pn_frame_reset(pn_context *ctx);
void *pn_frame_alloc(pn_context *ctx, uint64_t count, uint64_t elem, const char *pool);

/* A pool set's carve runs twice: in the size query (pn_carve: no memory, the limits'
 * maxima) and in the frame (the frame region, the frame's sizes). Each pool goes at the
 * next 64-byte boundary; the query only counts and hands out NULL. After the first failure
 * (the region exhausted: pn_fail names the pool; or a size past SIZE_MAX) every pool is
 * NULL and ok is 0, so a carve is a list of pn_pool calls and one test of ok. */
typedef struct pn_carver {
    pn_context *ctx; /* the frame's context; NULL: the size query, or a persistent set */
    uint8_t *base;   /* a persistent set's: the arena's aligned base (NULL: the query) */
    uint64_t top;    /* the query's or the persistent set's offset from the base */
    int ok;
} pn_carver;
void pn_carver_query(pn_carver *c, uint64_t start);
/* A persistent set at offset `start` of the aligned base: the same offsets the query gave. */
void pn_carver_at(pn_carver *c, uint8_t *base, uint64_t start);
void pn_carver_frame(pn_carver *c, pn_context *ctx);
void *pn_pool(pn_carver *c, uint64_t count, uint64_t elem, const char *name);
/* The frame's own pools (G-buffer, visibility, RGBA, the rasterizer's set-up, the shadow
 * counters) for a w x h frame of `tris` triangles, into fs (pn_frame.c); the positions and
 * normals only with `surface` (else fs->pos and fs->nrm are NULL). */
void pn_frame_carve(pn_carver *c, uint32_t w, uint32_t h, uint32_t tris, int surface, pn_frame_state *fs);
/* Whether a context with limits l keeps positions and normals in its frames, and the rows
 * of its point queries' batches (pn_visibility_points) for frames of h rows. */
#define pn_limits_surface(l) (((l)->flags & PN_LIMITS_NO_SURFACE) == 0u)
#define pn_points_rows(l, h) (pn_limits_surface(l) ? (h) : ((h) + 3u) / 4u)
size_t pn_frame_mark(const pn_context *ctx);
void pn_frame_rewind(pn_context *ctx, size_t mark);

/* pn_context.c: records a message ("%s" string, "%u" uint32, "%z" size_t/uint64 as
 * unsigned long long) and returns status. No stdio: the core is freestanding. */
pn_status pn_fail(pn_context *ctx, pn_status status, const char *fmt, ...);
uint64_t pn_now(const pn_context *ctx);
void pn_run(pn_context *ctx, uint32_t count, pn_task_fn fn, void *task);


/* pn_bvh_build.c. The build's scratch sits in the frame region (call outside a frame):
 * PN_BVH_REF_BYTES per reference of pn_bvh_refs_max, then a bit per triangle, then the
 * subtrees' work items (PN_BVH_TASK_BYTES, kept off the stack: pn_run's items may be any
 * pass, so the build's frame adds to the deepest pass in the stack bound), then at
 * pn_bvh_nodes_at the binary tree, pn_bvh_refs_max nodes of PN_BVH_NODE_BYTES (R - 1 at
 * most: its leaves hold two references or more), which is folded into the four-wide tree
 * (the persistent one) at the end. */
#define PN_BVH_REF_BYTES 40u
#define PN_BVH_TASK_BYTES 2048u
#define PN_BVH_NODE_BYTES 32u
/* A node of that binary tree. Interior (count == 0): children at first and first + 1.
 * Leaf: references tri_index[first .. first + count). The root is node 0, so no child
 * index is ever 0: a root with count 0 and first 0 is the empty tree. */
typedef struct pn_bnode {
    float bmin[3];
    uint32_t first;
    float bmax[3];
    uint32_t count;
} pn_bnode;
/* The four-wide tree (kernels/pn_ktypes.h pn_kbvh4) of a binary one (root 0, every leaf
 * of 2 .. 16 references unless the root is the only one, depth at most PN_BVH_DEPTH_MAX)
 * into w, at most room nodes: their count (0 when more would be needed), *need the walk
 * stack it needs. height: every node's height, or NULL (see pn_bvh_build.c). */
uint32_t pn_bvh_fold(const pn_bnode *nodes, const uint8_t *height, pn_kbvh4 *w, uint32_t room, uint32_t *need);
uint64_t pn_bvh_nodes_at(const pn_limits *l);
uint64_t pn_bvh_scratch_bytes(const pn_limits *l);
/* Every leaf holds at least PN_BVH_LEAF_MIN references (a node of fewer than twice that
 * is a leaf; a split leaves at least that many a side), so a tree of R references has at
 * most R / 2 leaves and at most pn_bvh_wide_max(R) four-wide nodes (pn_bvh_fold). */
#define PN_BVH_LEAF_MIN 2u
#define pn_bvh_wide_max(refs) ((refs) / 3u + 1u)
/* The binary tree's depth is at most PN_BVH_DEPTH_MAX (the builder switches to median
 * splits where only halving still reaches it), so that a walk of the four-wide tree needs
 * at most 1.5 (depth - 1) + 4 <= PN_BVH_STACK entries (pn_bvh_fold). check_config.h keeps
 * it above the 25 levels 2^26 references need. */
#define PN_BVH_DEPTH_MAX ((2u * ((uint32_t)PN_BVH_STACK - 4u)) / 3u + 1u)
pn_status pn_bvh_build(pn_context *ctx);
/* The current tree's boxes recomputed from the triangles' new positions (its shape, leaf
 * and raster order kept; pn_scene_update_positions); the tree built anew instead when the
 * leaves no longer list exactly the non-degenerate triangles or the tree holds split
 * references. A refit uses no scratch. */
pn_status pn_bvh_refit(pn_context *ctx);

/* pn_frame.c: validates and derives the frame's parameters, carves its pools, and runs
 * the G-buffer, the chosen algorithm's sequence and shading on the port. */
pn_status pn_render_with(pn_context *ctx, const pn_port *port, const pn_camera *camera,
                         const pn_light *light, const pn_frame_options *opt, pn_frame *out);
/* pn_visibility_points on a port (src/pn_frame.c). */
pn_status pn_points_with(pn_context *ctx, const pn_port *port, const pn_light *light, const pn_frame_options *opt,
                         const float *points, const float *normals, const uint32_t *tri_ids, uint32_t n, float *out);
/* A rasterizer's set-up for the view of `rows_pass` (PN_K_RASTER_ROWS, PN_K_LMAP_ROWS):
 * every triangle's rows, then the band walk's chunks (kernels/pn_raster.h). */
pn_status pn_raster_setup(pn_frame_state *fs, uint32_t rows_pass);

/* pn_connect.c (the wedges and MCSM): the scene's welded vertices, objects and edges into
 * hedge [3 T], run [3 T + 1] and tcomp [T] (the wedges' persistent pools; for MCSM without
 * the wedges, the frame region after the scratch), and PN_TRI_SHEET into the triangle
 * flags. The first PN_CONNECT_SCRATCH bytes a triangle of the frame region are its
 * scratch: call outside a frame. */
#define PN_CONNECT_SCRATCH 24u
#define PN_CONNECT_POOLS 28u /* hedge, run and tcomp: 7 words a triangle, and one */
void pn_connect_build(pn_context *ctx, uint32_t *hedge, uint32_t *run, uint32_t *tcomp);
void pn_connect_light(pn_context *ctx, const pn_klight *L);

/* pn_math.c */
int pn_finite(float v);
float pn_tan_half_deg(float fov_deg);

#endif
