/* pn_arena.c - the carve routine, shared by the size query and init (clay's
 * Clay_MinMemorySize idea: the query cannot drift from what init does), and the frame
 * allocator. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_reference.h" /* pn_row_counters */

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

/* PN_ARENA_BYTES_MAX (include/penumbra/penumbra.h) counts at most 1536 bytes for the
 * context. */
typedef char pn_context_fits_bound[sizeof(pn_context) <= 1536u ? 1 : -1];

/* A row's counters fill one cache line (kernels/pn_reference.h). */
typedef char pn_row_counters_is_64[sizeof(pn_row_counters) == 64u ? 1 : -1];

void pn_carver_query(pn_carver *c, uint64_t start)
{
    c->ctx = NULL;
    c->base = NULL;
    c->top = start;
    c->ok = 1;
}

void pn_carver_at(pn_carver *c, uint8_t *base, uint64_t start)
{
    c->ctx = NULL;
    c->base = base;
    c->top = start;
    c->ok = 1;
}

void pn_carver_frame(pn_carver *c, pn_context *ctx)
{
    c->ctx = ctx;
    c->base = NULL;
    c->top = 0;
    c->ok = 1;
}

void *pn_pool(pn_carver *c, uint64_t count, uint64_t elem, const char *name)
{
    size_t start;
    void *p;
    if (!c->ok) return NULL;
    if (!c->ctx) {
        if (!pn_bump(&c->top, count, elem, &start)) {
            c->ok = 0;
            return NULL;
        }
        return c->base ? c->base + start : NULL;
    }
    p = pn_frame_alloc(c->ctx, count, elem, name);
    if (!p) c->ok = 0;
    return p;
}

pn_status pn_carve(const pn_limits *l, pn_layout *out)
{
    uint64_t off = 0, frame_start;
    pn_layout lay;
    pn_carver c;
    if (l->max_triangles < 1u || l->max_triangles > PN_MAX_TRIANGLES || l->max_width < 1u ||
        l->max_width > PN_MAX_WIDTH || l->max_height < 1u || l->max_height > PN_MAX_HEIGHT ||
        (l->bvh_refs != 0u && (l->bvh_refs < l->max_triangles || l->bvh_refs > pn_bvh_refs_cap(l))) ||
        (l->algos & ~PN_ALGO_FLAGS) != 0u || (l->flags & ~(PN_LIMITS_NO_SURFACE | PN_LIMITS_SPARSE_NBUFFER)) != 0u)
        return PN_E_LIMIT;
    /* Each algorithm's own fields (an algorithm not compiled in ignores its). */
#define PN_ALGO_LIMITS(ID, name)                                                               \
    if (!pn_##name##_limits_ok(l)) return PN_E_LIMIT;
    PN_ALGORITHMS(PN_ALGO_LIMITS)
#undef PN_ALGO_LIMITS
    if (l->algos & ~pn_build_info()) return PN_E_UNSUPPORTED;
    if (!pn_bump(&off, 1u, sizeof(pn_context), &lay.ctx) ||
        !pn_bump(&off, l->max_triangles, 9u * sizeof(float), &lay.tris) ||
        !pn_bump(&off, l->max_triangles, 1u, &lay.flags) ||
        !pn_bump(&off, pn_bvh_wide_max(pn_bvh_refs_max(l)), sizeof(pn_kbvh4), &lay.wnodes) ||
        !pn_bump(&off, pn_bvh_refs_max(l), sizeof(uint32_t), &lay.index) ||
        !pn_bump(&off, l->max_triangles, sizeof(uint32_t), &lay.rindex) ||
        !pn_bump(&off, PN_PORT_SCRATCH_WORDS, sizeof(uint32_t), &lay.scratch))
        return PN_E_LIMIT;
    /* Each algorithm's persistent pools, for the algorithms the context runs. */
#define PN_ALGO_PERSIST(ID, name)                                                              \
    lay.algo[PN_ALGO_##ID] = (size_t)off;                                                      \
    if (pn_limits_algos(l) & (1u << PN_ALGO_##ID)) {                                           \
        pn_carver_query(&c, off);                                                              \
        pn_##name##_persist(&c, l);                                                            \
        if (!c.ok) return PN_E_LIMIT;                                                          \
        off = c.top;                                                                           \
    }
    PN_ALGORITHMS(PN_ALGO_PERSIST)
#undef PN_ALGO_PERSIST
    if (!pn_bump(&off, 0u, 1u, &lay.frame)) return PN_E_LIMIT;
    frame_start = off;
    {
        /* The frame's own pools, then the largest of the algorithms' sets (one algorithm a
         * frame): each set's carve run at the limits' maxima; for a context whose frames
         * keep no positions and normals, also a point query's batch, which does. */
        pn_limits lq = *l;
        int pass;
        for (pass = 0; pass < (pn_limits_surface(l) ? 1 : 2); pass++) {
            pn_frame_state fs;
            uint64_t common;
            if (pass) lq.max_height = pn_points_rows(l, l->max_height);
            pn_carver_query(&c, frame_start);
            pn_frame_carve(&c, lq.max_width, lq.max_height, lq.max_triangles, pass || pn_limits_surface(l), &fs);
            if (!c.ok) return PN_E_LIMIT;
            common = c.top;
            if (common > off) off = common;
#define PN_ALGO_QUERY(ID, name)                                                                \
            if (pn_limits_algos(l) & (1u << PN_ALGO_##ID)) {                                   \
                pn_carver_query(&c, common);                                                   \
                pn_##name##_query(&c, &lq);                                                    \
                if (!c.ok) return PN_E_LIMIT;                                                  \
                if (c.top > off) off = c.top;                                                  \
            }
            PN_ALGORITHMS(PN_ALGO_QUERY)
#undef PN_ALGO_QUERY
        }
        /* pn_scene_set's BVH build uses the region as scratch too. */
        if (pn_bvh_scratch_bytes(l) > off - frame_start) off = frame_start + pn_bvh_scratch_bytes(l);
        /* ...and so may an algorithm's own work at pn_scene_set. */
#define PN_ALGO_SCENE_SCRATCH(ID, name)                                                        \
        if ((pn_limits_algos(l) & (1u << PN_ALGO_##ID)) && pn_##name##_scene_scratch(l) > off - frame_start) \
            off = frame_start + pn_##name##_scene_scratch(l);
        PN_ALGORITHMS(PN_ALGO_SCENE_SCRATCH)
#undef PN_ALGO_SCENE_SCRATCH
    }
    /* Round the end so the last pool's alignment padding is inside the region. */
    if (!pn_bump(&off, 0u, 1u, &lay.end)) return PN_E_LIMIT;
    lay.frame_cap = (size_t)(off - frame_start);
    if ((uint64_t)lay.end > (uint64_t)SIZE_MAX - (PN_ARENA_ALIGN - 1u)) return PN_E_LIMIT;
    *out = lay;
    return PN_OK;
}

void pn_frame_reset(pn_context *ctx) { ctx->frame_top = 0; }

void *pn_frame_alloc(pn_context *ctx, uint64_t count, uint64_t elem, const char *pool)
{
    uint64_t off = ctx->frame_top;
    size_t start = 0;
    if (!pn_bump(&off, count, elem, &start) || off > ctx->layout.frame_cap) {
        pn_fail(ctx, PN_E_POOL_EXHAUSTED,
                "frame pool '%s' needs %z bytes at offset %z; the frame region holds %z", pool,
                (unsigned long long)(count * elem), (unsigned long long)start,
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
    memset(limits, 0, sizeof(*limits));
    limits->max_triangles = PN_MAX_TRIANGLES;
    limits->max_width = PN_MAX_WIDTH;
    limits->max_height = PN_MAX_HEIGHT;
}

uint32_t pn_limits_algos(const pn_limits *l) { return l->algos ? l->algos : pn_build_info() & PN_ALGO_FLAGS; }
uint32_t pn_bvh_refs_cap(const pn_limits *l)
{
    uint64_t n = l->max_triangles, extra = PN_BVH_SPLIT_EXTRA(l->max_triangles);
    if (n + extra > (1u << 26)) extra = n < (1u << 26) ? (1u << 26) - n : 0u;
    return (uint32_t)(n + extra);
}
uint32_t pn_bvh_refs_max(const pn_limits *l) { return l->bvh_refs ? l->bvh_refs : l->max_triangles; }
uint64_t pn_bvh_nodes_at(const pn_limits *l)
{
    uint64_t at = (uint64_t)pn_bvh_refs_max(l) * PN_BVH_REF_BYTES + ((uint64_t)l->max_triangles / 32u + 1u) * 4u +
                  PN_BVH_TASK_BYTES;
    return (at + (PN_ARENA_ALIGN - 1u)) & ~(uint64_t)(PN_ARENA_ALIGN - 1u);
}
uint64_t pn_bvh_scratch_bytes(const pn_limits *l)
{
    return pn_bvh_nodes_at(l) + (uint64_t)pn_bvh_refs_max(l) * PN_BVH_NODE_BYTES;
}
uint32_t pn_nb_levels(uint32_t res)
{
    uint32_t l = 1u;
    while ((2u << (l - 1u)) <= res) l++;
    return l;
}

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
    ctx->wnodes = (pn_kbvh4 *)(void *)(base + lay.wnodes);
    ctx->bvh_depth_max = PN_BVH_DEPTH_MAX;
    ctx->tri_index = (uint32_t *)(void *)(base + lay.index);
    ctx->raster_index = (uint32_t *)(void *)(base + lay.rindex);
    ctx->scratch = (uint32_t *)(void *)(base + lay.scratch);
    ctx->frame = base + lay.frame;
    *out_ctx = ctx;
    return PN_OK;
}
