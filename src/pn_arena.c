/* pn_arena.c - the carve routine, shared by the size query and init (clay's
 * Clay_MinMemorySize idea: the query cannot drift from what init does), and the frame
 * allocator. */
#include <string.h>

#include "pn_internal.h"
#include "pn_reference.h" /* pn_row_counters */
#if PN_ENABLE_GEARS
#include "pn_gears_pass.h" /* pn_kfaces */
#endif
#if PN_ENABLE_WEDGES
#include "pn_wedges.h" /* pn_wsil */
#endif

/* Appends a pool of count * elem bytes at the next 64-byte boundary. Sizes are checked in
 * 64-bit arithmetic, then against SIZE_MAX (a 32-bit target must not wrap). */
static int pn_bump(uint64_t *off, uint64_t count, uint64_t elem, size_t *out)
{
    uint64_t start = (*off + (PN_ARENA_ALIGN - 1u)) & ~(uint64_t)(PN_ARENA_ALIGN - 1u);
    uint64_t bytes;
    if (elem != 0u && count > UINT64_MAX / elem) return 0;
    bytes = count * elem;
    if (start > (uint64_t)SIZE_MAX || bytes > (uint64_t)SIZE_MAX - start) return 0;
    *out = (size_t)start;
    *off = start + bytes;
    return 1;
}

/* A row's counters fill one cache line (kernels/pn_reference.h). */
typedef char pn_row_counters_is_64[sizeof(pn_row_counters) == 64u ? 1 : -1];

/* The frame pools, in allocation order; pn_frame.c allocates exactly these (any frame
 * within the limits fits, because each is at most its size here). */
static int pn_frame_pools_common(const pn_limits *l, uint64_t *off)
{
    uint64_t px = (uint64_t)l->max_width * l->max_height;
    size_t dummy;
    if (!(pn_bump(off, px, sizeof(float), &dummy) &&          /* depth */
          pn_bump(off, px, sizeof(uint32_t), &dummy) &&       /* tri_id */
          pn_bump(off, px * 3u, sizeof(float), &dummy) &&     /* position */
          pn_bump(off, px * 3u, sizeof(float), &dummy) &&     /* normal */
          pn_bump(off, px, sizeof(float), &dummy) &&          /* visibility */
          pn_bump(off, px, 4u, &dummy) &&                     /* rgba */
          pn_bump(off, l->max_triangles, sizeof(uint32_t), &dummy) && /* raster rows */
          pn_bump(off, PN_RASTER_CHUNKS(l->max_triangles), sizeof(uint32_t), &dummy) && /* chunks */
          pn_bump(off, l->max_height, sizeof(pn_row_counters), &dummy)))
        return 0;
    return 1;
}

/* PN_GEARS_BYTES_MAX (include/penumbra/penumbra.h) counts a 24-byte chunk box per 8 pairs
 * and a superchunk box per 64. */
typedef char pn_gears_chunk_is_8[(PN_GEARS_CHUNK == 8u && PN_GEARS_SUPER == 8u) ? 1 : -1];

/* GEARS' frame pools, after the common ones. */
static int pn_gears_pools(const pn_limits *l, uint64_t *off)
{
#if PN_ENABLE_GEARS
    uint64_t px = (uint64_t)l->max_width * l->max_height;
    size_t dummy;
    {
        /* pn_gears_begin() in src/pn_gears.c allocates exactly these, in this order. */
        uint64_t g = pn_gears_grid_max(l), cells = 6u * g * g;
        return pn_bump(off, 1u, sizeof(pn_kfaces), &dummy) &&              /* grid cameras */
               pn_bump(off, l->max_triangles, 6u * 8u, &dummy) &&         /* cell rects */
               pn_bump(off, (uint64_t)l->max_triangles + 1u, 4u, &dummy) && /* pair offsets */
               pn_bump(off, px, 4u, &dummy) &&                            /* pixel cells */
               pn_bump(off, l->max_height, 32u, &dummy) &&                /* row boxes */
               pn_bump(off, cells + 1u, 4u, &dummy) &&                    /* cell offsets */
               pn_bump(off, cells, 4u, &dummy) &&                         /* pixels per cell */
               pn_bump(off, 6u * g * (g + 1u), 4u, &dummy) &&             /* row prefixes */
               pn_bump(off, cells, 4u, &dummy) &&                         /* cell cursors */
               pn_bump(off, 6u * g, 8u, &dummy) &&                        /* pairs per grid row */
               pn_bump(off, pn_gears_pairs_max(l), 8u, &dummy) &&         /* pairs */
               pn_bump(off, pn_gears_pairs_max(l), 4u, &dummy) &&         /* cell-sorted */
               pn_bump(off, pn_gears_pairs_max(l) / PN_GEARS_CHUNK + 1u, 24u, &dummy) && /* chunk boxes */
               pn_bump(off, pn_gears_pairs_max(l) / (PN_GEARS_CHUNK * PN_GEARS_SUPER) + 1u, 24u, &dummy); /* superchunks */
    }
#else
    (void)l;
    (void)off;
    return 1;
#endif
}

/* The SRT frame pools, after the GEARS ones (a frame carves one algorithm's pools, so the
 * region holds the larger of the two sets; both are laid out to keep the query simple). */
static int pn_srt_pools(const pn_limits *l, uint64_t *off)
{
#if PN_ENABLE_SRT
    uint64_t px = (uint64_t)l->max_width * l->max_height, r = pn_srt_map_max(l), tl = r / 8u + 1u;
    size_t dummy;
    /* pn_srt_frame() in src/pn_srt.c allocates exactly these, in this order. */
    return pn_bump(off, l->max_height, 4u * PN_LVIEW_BOX_FLOATS, &dummy) && /* row bounds */
           pn_bump(off, r * r, 4u, &dummy) &&              /* map depth */
           pn_bump(off, r * r, 4u, &dummy) &&              /* map triangle ids */
           pn_bump(off, r * r, 4u, &dummy) &&              /* thin-triangle marks */
           pn_bump(off, tl * tl, 4u, &dummy) &&            /* tile weights */
           pn_bump(off, tl * tl, 4u, &dummy) &&            /* tile row weights */
           pn_bump(off, tl * tl, 4u, &dummy) &&            /* tile mask */
           pn_bump(off, 4u, 4u, &dummy) &&                 /* largest weight, counters */
           pn_bump(off, px + 1u, 4u, &dummy) &&            /* PIP offsets */
           pn_bump(off, px, 4u, &dummy);                   /* PIP list */
#else
    (void)l;
    (void)off;
    return 1;
#endif
}

/* The occlusion-texture frame pools (one filter pool: the largest of N-buffer levels^2,
 * summed-area table and mipmap is the N-buffer, or the table for a tiny map). */
static int pn_occ_pools(const pn_limits *l, uint64_t *off)
{
#if PN_ENABLE_OCCTEX
    uint64_t r = pn_occ_map_max(l);
    size_t dummy;
    /* pn_occtex_frame() in src/pn_occtex.c allocates exactly these, in this order. */
    return pn_bump(off, l->max_height, 4u * PN_LVIEW_BOX_FLOATS, &dummy) && /* row bounds */
           pn_bump(off, r * r, 4u, &dummy) &&                               /* slice bits */
           pn_bump(off, pn_occ_filter_words((uint32_t)r), 4u, &dummy) &&    /* one slice's filter */
           pn_bump(off, 32u, 4u, &dummy);                                   /* counters */
#else
    (void)l;
    (void)off;
    return 1;
#endif
}

/* The Monte Carlo shadow maps' frame pools. */
static int pn_mc_pools(const pn_limits *l, uint64_t *off)
{
#if PN_ENABLE_MCSM
    uint64_t r = pn_mc_map_max(l), px = (uint64_t)l->max_width * l->max_height;
    size_t dummy;
    /* pn_mcsm_frame() in src/pn_mcsm.c allocates exactly these, in this order. */
    return pn_bump(off, l->max_height, 4u * PN_LVIEW_BOX_FLOATS, &dummy) &&     /* row bounds */
           pn_bump(off, (uint64_t)pn_occ_levels((uint32_t)r) * r * r, 12u, &dummy) && /* N-buffer */
           pn_bump(off, px, 4u, &dummy) &&                                     /* blur buffer */
           pn_bump(off, l->max_height, 64u, &dummy);                           /* counters */
#else
    (void)l;
    (void)off;
    return 1;
#endif
}

/* The penumbra wedges' frame pools; the frame region also holds pn_connect_build's
 * scratch (24 bytes a triangle) at pn_scene_set. */
static int pn_wg_pools(const pn_limits *l, uint64_t *off)
{
#if PN_ENABLE_WEDGES
    uint64_t weld = *off, tiles = pn_wg_tiles_of(l->max_width, l->max_height);
    size_t dummy;
    /* pn_wedges_frame() in src/pn_wedges.c allocates exactly these, in this order. */
    if (!(pn_bump(off, l->max_triangles, 4u, &dummy) &&                        /* casting */
          pn_bump(off, 3u * (uint64_t)l->max_triangles + 1u, 4u, &dummy) &&    /* silhouette slots */
          pn_bump(off, pn_wg_sil_max(l), sizeof(pn_wsil), &dummy) &&          /* silhouettes */
          pn_bump(off, (uint64_t)pn_wg_sil_max(l) + 1u, 4u, &dummy) &&         /* pair offsets */
          pn_bump(off, pn_wg_pairs_max(l), 8u, &dummy) &&                      /* pairs */
          pn_bump(off, pn_wg_pairs_max(l), 4u, &dummy) &&                      /* tile lists */
          pn_bump(off, tiles + 1u, 4u, &dummy) &&                              /* tile offsets */
          pn_bump(off, tiles, 4u, &dummy) &&                                   /* sort scratch */
          pn_bump(&weld, 6u * (uint64_t)l->max_triangles, 4u, &dummy)))         /* welding */
        return 0;
    if (weld > *off) *off = weld;
    return 1;
#else
    (void)l;
    (void)off;
    return 1;
#endif
}

pn_status pn_carve(const pn_limits *l, pn_layout *out)
{
    uint64_t off = 0, frame_start;
    pn_layout lay;
    if (l->max_triangles < 1u || l->max_triangles > PN_MAX_TRIANGLES || l->max_width < 1u ||
        l->max_width > PN_MAX_WIDTH || l->max_height < 1u || l->max_height > PN_MAX_HEIGHT ||
        l->gears_pairs > (1u << 28) || l->gears_grid_max > 1024u || l->srt_map_max > PN_SRT_MAP_MAX ||
        (l->srt_map_max != 0u && l->srt_map_max < 8u) || l->occ_map_max > PN_OCCTEX_MAP_MAX ||
        (l->occ_map_max != 0u && l->occ_map_max < 8u) || l->mc_map_max > PN_MCSM_MAP_MAX ||
        (l->mc_map_max != 0u && l->mc_map_max < 8u) || l->wg_pairs > PN_WEDGES_PAIRS ||
        (l->bvh_refs != 0u && (l->bvh_refs < l->max_triangles || l->bvh_refs > pn_bvh_refs_default(l))))
        return PN_E_LIMIT;
    if (!pn_bump(&off, 1u, sizeof(pn_context), &lay.ctx) ||
        !pn_bump(&off, l->max_triangles, 9u * sizeof(float), &lay.tris) ||
        !pn_bump(&off, l->max_triangles, 1u, &lay.flags) ||
        !pn_bump(&off, 2u * (uint64_t)pn_bvh_refs_max(l), sizeof(pn_kbvh_node), &lay.nodes) ||
        !pn_bump(&off, pn_bvh_refs_max(l), sizeof(pn_kbvh4), &lay.wnodes) ||
        !pn_bump(&off, pn_bvh_refs_max(l), sizeof(uint32_t), &lay.index) ||
        !pn_bump(&off, l->max_triangles, sizeof(uint32_t), &lay.rindex) ||
        !pn_bump(&off, PN_PORT_SCRATCH_WORDS, sizeof(uint32_t), &lay.scratch) ||
        !pn_bump(&off, PN_ENABLE_WEDGES ? 3u * (uint64_t)l->max_triangles : 0u, sizeof(uint32_t), &lay.wg_hedge) ||
        !pn_bump(&off, PN_ENABLE_WEDGES ? 3u * (uint64_t)l->max_triangles + 1u : 0u, sizeof(uint32_t), &lay.wg_run) ||
        !pn_bump(&off, PN_ENABLE_WEDGES ? (uint64_t)l->max_triangles : 0u, sizeof(uint32_t), &lay.wg_tcomp) ||
        !pn_bump(&off, 0u, 1u, &lay.frame))
        return PN_E_LIMIT;
    frame_start = off;
    {
        /* The common pools, then the largest of GEARS', SRT's and the occlusion textures'
         * (one algorithm a frame). */
        uint64_t common = off, a, b, c, m, w;
        if (!pn_frame_pools_common(l, &common)) return PN_E_LIMIT;
        a = common;
        b = common;
        c = common;
        m = common;
        w = common;
        if (!pn_gears_pools(l, &a) || !pn_srt_pools(l, &b) || !pn_occ_pools(l, &c) || !pn_mc_pools(l, &m) ||
            !pn_wg_pools(l, &w))
            return PN_E_LIMIT;
        off = a > b ? a : b;
        off = off > c ? off : c;
        off = off > m ? off : m;
        off = off > w ? off : w;
        /* pn_scene_set's BVH build uses the region as scratch too. */
        if (pn_bvh_scratch_bytes(l) > off - frame_start) off = frame_start + pn_bvh_scratch_bytes(l);
    }
    /* Round the end so the last pool's alignment padding is inside the region. */
    if (!pn_bump(&off, 0u, 1u, &lay.end)) return PN_E_LIMIT;
    lay.frame_cap = (size_t)(off - frame_start);
    if ((uint64_t)lay.end > (uint64_t)SIZE_MAX - (PN_ARENA_ALIGN - 1u)) return PN_E_LIMIT;
    *out = lay;
    return PN_OK;
}

void pn_frame_reset(pn_context *ctx) { ctx->frame_top = 0; }

void *pn_frame_alloc(pn_context *ctx, size_t count, size_t elem, const char *pool)
{
    uint64_t off = ctx->frame_top;
    size_t start = 0;
    if (!pn_bump(&off, count, elem, &start) || off > ctx->layout.frame_cap) {
        pn_fail(ctx, PN_E_POOL_EXHAUSTED,
                "frame pool '%s' needs %z bytes at offset %z; the frame region holds %z", pool,
                (unsigned long long)((uint64_t)count * elem), (unsigned long long)start,
                (unsigned long long)ctx->layout.frame_cap);
        return NULL;
    }
    ctx->frame_top = (size_t)off;
    if (ctx->frame_top > ctx->frame_high) ctx->frame_high = ctx->frame_top;
    return ctx->frame + start;
}

size_t pn_frame_mark(const pn_context *ctx) { return ctx->frame_top; }

void pn_frame_rewind(pn_context *ctx, size_t mark)
{
#if PN_DEBUG_ARENA
    /* LIFO order: a mark above the top means marks were rewound out of order. */
    if (mark > ctx->frame_top) {
        pn_fail(ctx, PN_E_INTERNAL, "arena mark %z rewound after a lower one (top %z)",
                (unsigned long long)mark, (unsigned long long)ctx->frame_top);
        return;
    }
    memset(ctx->frame + mark, 0xA5, ctx->frame_top - mark);
#endif
    ctx->frame_top = mark;
}

void pn_limits_max(pn_limits *limits)
{
    if (!limits) return;
    limits->max_triangles = PN_MAX_TRIANGLES;
    limits->max_width = PN_MAX_WIDTH;
    limits->max_height = PN_MAX_HEIGHT;
    limits->gears_pairs = 0;
    limits->gears_grid_max = 0;
    limits->srt_map_max = 0;
    limits->occ_map_max = 0;
    limits->mc_map_max = 0;
    limits->wg_pairs = 0;
    limits->bvh_refs = 0;
}

uint32_t pn_gears_pairs_max(const pn_limits *l) { return l->gears_pairs ? l->gears_pairs : PN_GEARS_PAIRS; }
uint32_t pn_srt_map_max(const pn_limits *l) { return l->srt_map_max ? l->srt_map_max : PN_SRT_MAP_MAX; }
uint32_t pn_occ_map_max(const pn_limits *l) { return l->occ_map_max ? l->occ_map_max : PN_OCCTEX_MAP_MAX; }
uint32_t pn_mc_map_max(const pn_limits *l) { return l->mc_map_max ? l->mc_map_max : PN_MCSM_MAP_MAX; }
uint32_t pn_bvh_refs_default(const pn_limits *l)
{
    uint64_t n = l->max_triangles, extra = PN_BVH_SPLIT_EXTRA(l->max_triangles);
    if (n + extra > (1u << 26)) extra = n < (1u << 26) ? (1u << 26) - n : 0u;
    return (uint32_t)(n + extra);
}
uint32_t pn_bvh_refs_max(const pn_limits *l) { return l->bvh_refs ? l->bvh_refs : pn_bvh_refs_default(l); }
uint64_t pn_bvh_scratch_bytes(const pn_limits *l)
{
    return (uint64_t)pn_bvh_refs_max(l) * PN_BVH_REF_BYTES + ((uint64_t)l->max_triangles / 32u + 1u) * 4u;
}
uint32_t pn_wg_tiles_of(uint32_t width, uint32_t height)
{
    return PN_WG_TILES(width) * PN_WG_TILES(height);
}
uint32_t pn_wg_sil_max(const pn_limits *l)
{
    uint64_t edges = 3u * (uint64_t)l->max_triangles;
    return edges < PN_WEDGES_SIL_MAX ? (uint32_t)edges : PN_WEDGES_SIL_MAX;
}
uint32_t pn_wg_pairs_max(const pn_limits *l)
{
    uint64_t most = (uint64_t)pn_wg_tiles_of(l->max_width, l->max_height) * pn_wg_sil_max(l);
    uint32_t cap = l->wg_pairs ? l->wg_pairs : PN_WEDGES_PAIRS;
    return most < cap ? (uint32_t)most : cap;
}
uint32_t pn_occ_levels(uint32_t res)
{
    uint32_t l = 1u;
    while ((2u << (l - 1u)) <= res) l++;
    return l;
}
uint64_t pn_occ_filter_words(uint32_t res)
{
    uint64_t nb = (uint64_t)pn_occ_levels(res) * res * res, sat = ((uint64_t)res + 1u) * (res + 1u);
    return nb > sat ? nb : sat;
}
uint32_t pn_gears_grid_max(const pn_limits *l) { return l->gears_grid_max ? l->gears_grid_max : PN_GEARS_GRID_MAX; }

pn_status pn_arena_size(const pn_limits *limits, size_t *out_bytes)
{
    pn_layout lay;
    pn_status st;
    if (!limits || !out_bytes) return PN_E_INVALID_ARG;
    st = pn_carve(limits, &lay);
    if (st != PN_OK) return st;
    *out_bytes = lay.end + (PN_ARENA_ALIGN - 1u);
    return PN_OK;
}

pn_status pn_init(pn_context **out_ctx, void *memory, size_t bytes, const pn_limits *limits)
{
    pn_layout lay;
    pn_status st;
    size_t need, pad;
    uint8_t *base;
    pn_context *ctx;
    if (!out_ctx || !memory || !limits) return PN_E_INVALID_ARG;
    st = pn_carve(limits, &lay);
    if (st != PN_OK) return st;
    need = lay.end + (PN_ARENA_ALIGN - 1u);
    /* The requirement does not depend on the block's alignment, so a size that works
     * once works for any block. */
    if (bytes < need) return PN_E_ARENA_TOO_SMALL;
    pad = (size_t)((PN_ARENA_ALIGN - ((uintptr_t)memory & (PN_ARENA_ALIGN - 1u))) &
                   (PN_ARENA_ALIGN - 1u));
    base = (uint8_t *)memory + pad;
    ctx = (pn_context *)(void *)(base + lay.ctx);
    memset(ctx, 0, sizeof(*ctx));
    ctx->limits = *limits;
    ctx->layout = lay;
    ctx->base = base;
    ctx->bytes = bytes;
    ctx->tris = (float *)(void *)(base + lay.tris);
    ctx->flags = base + lay.flags;
    ctx->nodes = (pn_kbvh_node *)(void *)(base + lay.nodes);
    ctx->wnodes = (pn_kbvh4 *)(void *)(base + lay.wnodes);
    ctx->tri_index = (uint32_t *)(void *)(base + lay.index);
    ctx->raster_index = (uint32_t *)(void *)(base + lay.rindex);
    ctx->scratch = (uint32_t *)(void *)(base + lay.scratch);
#if PN_ENABLE_WEDGES
    ctx->wg_hedge = (uint32_t *)(void *)(base + lay.wg_hedge);
    ctx->wg_run = (uint32_t *)(void *)(base + lay.wg_run);
    ctx->wg_tcomp = (uint32_t *)(void *)(base + lay.wg_tcomp);
#endif
    ctx->frame = base + lay.frame;
    *out_ctx = ctx;
    return PN_OK;
}
