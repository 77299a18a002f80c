/* pn_srt.c - selective ray tracing's whole frame (sequence in pn_srt_frame.h): the light
 * view, the map window, and the passes of kernels/pn_srt.h between them, run on the
 * frame's port. Written once: both ports run this sequence. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_passes.h"
#include "pn_srt_frame.h"

#if PN_ENABLE_SRT

/* The context's largest map: 0 (PN_SRT_MAP_MAX) or 8 .. PN_SRT_MAP_MAX. */
int pn_srt_limits_ok(const pn_limits *l) { return l->srt_map_max == 0u || (l->srt_map_max >= 8u && l->srt_map_max <= PN_SRT_MAP_MAX); }
static uint32_t pn_srt_map_max(const pn_limits *l) { return l->srt_map_max ? l->srt_map_max : PN_SRT_MAP_MAX; }

/* PN_ALGO_SRT's options (pn_algorithms.h): checked, then the frame's parameters, 0 meaning
 * the default. */
pn_status pn_srt_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    pn_context *ctx = fs->ctx;
    if (opt->srt.map != 0u && (opt->srt.map < 8u || opt->srt.map > pn_srt_map_max(&ctx->limits)))
        return pn_fail(ctx, PN_E_INVALID_ARG, "srt.map = %u; it must be 0 or in 8 .. %u (pn_limits.srt_map_max)",
                       opt->srt.map, pn_srt_map_max(&ctx->limits));
    if (opt->srt.flags & ~(PN_SRT_NO_CONSERVATIVE | PN_SRT_FORCE_PIP))
        return pn_fail(ctx, PN_E_INVALID_ARG, "srt.flags = %u has unknown bits", opt->srt.flags);
    if (!pn_finite(opt->srt.delta) || !(opt->srt.delta >= 0.0f) || opt->srt.delta > 1.0f)
        return pn_fail(ctx, PN_E_INVALID_ARG, "srt.delta must be in [0, 1] (0: the default 1e-3)");
    /* Default map: the paper's 2048^2, at most the limit (a coarser map marks far more
     * pixels: test_srt at 256^2 marks 61-100% of the lit pixels, at 2048^2 7-72%). */
    fs->res = opt->srt.map ? opt->srt.map : pn_srt_map_max(&ctx->limits);
    if (!opt->srt.map && fs->res > 2048u) fs->res = 2048u;
    fs->K.srt_flags = opt->srt.flags;
    fs->K.srt_delta = (opt->srt.delta > 0.0f ? opt->srt.delta : 1e-3f) * ctx->scene_diag;
    return PN_OK;
}

/* The kernels' copy of the public flag (kernels/ does not include penumbra.h). */
typedef char pn_srt_flag_agrees[PN_SRT_FLAG_FORCE_PIP == PN_SRT_FORCE_PIP ? 1 : -1];

typedef struct pn_srt_pools {
    float *box;          /* [height * PN_LVIEW_BOX]: row bounds (kernels/pn_lview.h) */
    float *depth;        /* [res^2]: map depth (distance from the light centre) */
    uint32_t *id;        /* [res^2]: map triangle */
    uint32_t *cons;      /* [res^2]: 1/z bits of the nearest thin triangle touching the texel */
    uint32_t *tile_w;    /* [tiles^2]: largest splat weight of a tile's edge texels */
    uint32_t *tile_h;    /* [tiles^2]: ...of those whose horizontal reach covers the tile */
    uint32_t *tile_mask; /* [tiles^2]: non-zero = in the penumbra mask */
    uint32_t *words;     /* [4]: largest weight bits, thin triangles, masked tiles, marked texels */
    uint32_t *pip_off;   /* [pixels + 1]: PIP flags, then their exclusive prefix sum */
    uint32_t *pip_list;  /* [pixels]: the PIP pixels, dense */
} pn_srt_pools;

/* The frame's pools at w x h with a res^2 map: run by the frame on the frame region and
 * by pn_srt_query at the limits' maxima. */
static void pn_srt_carve(pn_carver *c, uint32_t w, uint32_t h, uint32_t res, pn_srt_pools *s)
{
    uint64_t px = (uint64_t)w * h, texels = (uint64_t)res * res, tiles = (res + PN_SRT_TILE - 1u) / PN_SRT_TILE;
    uint64_t tl = tiles * tiles;
    s->box = (float *)pn_pool(c, h, 4u * PN_LVIEW_BOX_FLOATS, "srt row bounds");
    s->depth = (float *)pn_pool(c, texels, 4u, "srt map depth");
    s->id = (uint32_t *)pn_pool(c, texels, 4u, "srt map triangle ids");
    s->cons = (uint32_t *)pn_pool(c, texels, 4u, "srt thin-triangle marks");
    s->tile_w = (uint32_t *)pn_pool(c, tl, 4u, "srt tile weights");
    s->tile_h = (uint32_t *)pn_pool(c, tl, 4u, "srt tile row weights");
    s->tile_mask = (uint32_t *)pn_pool(c, tl, 4u, "srt tile mask");
    s->words = (uint32_t *)pn_pool(c, 4u, 4u, "srt counters");
    s->pip_off = (uint32_t *)pn_pool(c, px + 1u, 4u, "srt PIP offsets");
    s->pip_list = (uint32_t *)pn_pool(c, px, 4u, "srt PIP list");
}

void pn_srt_query(pn_carver *c, const pn_limits *l)
{
    pn_srt_pools s;
    pn_srt_carve(c, l->max_width, l->max_height, pn_srt_map_max(l), &s);
}

static pn_status pn_srt_begin(pn_frame_state *fs, pn_srt_pools *s, uint32_t res)
{
    pn_context *ctx = fs->ctx;
    pn_kpools *P = &fs->P;
    pn_carver c;
    pn_carver_frame(&c, ctx);
    pn_srt_carve(&c, fs->width, fs->height, res, s);
    if (!c.ok) return PN_E_POOL_EXHAUSTED;
    P->lview_box = pn_dev_off(ctx, s->box);
    P->lmap_depth = pn_dev_off(ctx, s->depth);
    P->lmap_id = pn_dev_off(ctx, s->id);
    P->lmap_cons = pn_dev_off(ctx, s->cons);
    P->srt_tile_w = pn_dev_off(ctx, s->tile_w);
    P->srt_tile_h = pn_dev_off(ctx, s->tile_h);
    P->srt_tile_mask = pn_dev_off(ctx, s->tile_mask);
    P->srt_words = pn_dev_off(ctx, s->words);
    P->pip_off = pn_dev_off(ctx, s->pip_off);
    P->pip_list = pn_dev_off(ctx, s->pip_list);
    memset(&ctx->stats.srt, 0, sizeof(ctx->stats.srt));
    return PN_OK;
}

/* The map window from the row bounds: the lit origins' extent, widened for occluders off
 * to the side (an occluder at depth z shifts by up to |U|/z in the map as seen from the
 * light's points; occluders nearer than a quarter of the nearest receiver's depth are
 * taken as covered by that margin), and by two texels for rounding. */
static void pn_srt_window(pn_frame_state *fs, const pn_srt_pools *s, uint32_t res)
{
    const pn_klight *L = &fs->K.light;
    float ext = 0.0f, zmin = PN_KINF, margin = 0.0f, t;
    uint32_t y;
    for (y = 0; y < fs->height; y++) {
        ext = pn_kmaxf(ext, pn_kmaxf(s->box[(size_t)y * PN_LVIEW_BOX], s->box[(size_t)y * PN_LVIEW_BOX + 1u]));
        zmin = pn_kminf(zmin, s->box[(size_t)y * PN_LVIEW_BOX + 2u]);
    }
    if (!L->is_point && zmin < PN_KINF) {
        pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]), V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
        float rho = pn_kmaxf(pn_ksqrt(pn_v3_dot(U, U)), pn_ksqrt(pn_v3_dot(V, V)));
        margin = rho / (0.25f * zmin);
    }
    t = (ext + margin) * (1.0f + 4.0f / (float)res);
    if (!(t > 1e-6f)) t = 1e-6f;
    if (!(t <= PN_SRT_TAN_MAX)) t = PN_SRT_TAN_MAX;
    fs->K.lview.tan_half = t;
    fs->K.srt_alpha = 2.0f * t / (float)res;
}

pn_status pn_srt_frame(pn_frame_state *fs)
{
    pn_context *ctx = fs->ctx;
    pn_kparams *K = &fs->K;
    pn_srt_pools s;
    uint32_t res = fs->res, tiles = (res + PN_SRT_TILE - 1u) / PN_SRT_TILE, T = ctx->tri_count;
    uint32_t npix = fs->width * fs->height, npip;
    uint64_t t0 = pn_dev_timestamp(fs), t1, t2;
    pn_status st;

    if ((st = pn_srt_begin(fs, &s, res)) != PN_OK) return st;
    pn_light_view(ctx, &K->light, res, &K->lview);
    K->lview_ha = 0.0f;
    K->lview_hb = 0.0f;
    K->srt_tiles = tiles;

    /* The map window. */
    if ((st = pn_dev_run(fs, PN_K_LVIEW_BOUNDS, fs->height)) != PN_OK ||
        (st = pn_dev_to_host(fs, s.box, (size_t)fs->height * 4u * PN_LVIEW_BOX)) != PN_OK)
        return st;
    pn_srt_window(fs, &s, res);

    /* The shadow map: the G-buffer's rasterizer on the light view. */
    if ((st = pn_dev_run(fs, PN_K_LMAP_CLEAR, res * res)) != PN_OK || (st = pn_raster_setup(fs, PN_K_LMAP_ROWS)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_LMAP_BAND, (res + PN_RASTER_BAND - 1u) / PN_RASTER_BAND)) != PN_OK ||
        (st = pn_dev_fill(fs, s.words, 4u, 0u)) != PN_OK)
        return st;
    if (!(K->srt_flags & PN_SRT_NO_CONSERVATIVE) && (st = pn_dev_run(fs, PN_K_SRT_CONSERVATIVE, T)) != PN_OK) return st;

    /* Area light: the penumbra mask, per tile: the union of every edge tile's splat, by
     * rows then columns (the reach along both axes grows with the same weight). */
    if (!K->light.is_point) {
        pn_v3 U = pn_v3_make(K->light.U[0], K->light.U[1], K->light.U[2]);
        pn_v3 V = pn_v3_make(K->light.V[0], K->light.V[1], K->light.V[2]);
        K->srt_reach_u = pn_ksqrt(pn_v3_dot(U, U)) / K->srt_alpha;
        K->srt_reach_v = pn_ksqrt(pn_v3_dot(V, V)) / K->srt_alpha;
        if ((st = pn_dev_run(fs, PN_K_SRT_TILES, tiles * tiles)) != PN_OK ||
            (st = pn_dev_to_host(fs, s.words, 4u)) != PN_OK)
            return st;
        K->srt_wmax = pn_kbitsf(s.words[PN_SRT_WORD_WMAX]);
        if ((st = pn_dev_run(fs, PN_K_SRT_TILE_ROWS, tiles)) != PN_OK ||
            (st = pn_dev_run(fs, PN_K_SRT_TILE_COLS, tiles)) != PN_OK)
            return st;
    }

    /* Classification, the dense PIP list, and the exact masks. */
    t1 = pn_dev_timestamp(fs);
    if ((st = pn_dev_run(fs, PN_K_SRT_CLASSIFY, npix)) != PN_OK || (st = pn_dev_scan(fs, s.pip_off, npix)) != PN_OK ||
        (st = pn_dev_to_host(fs, s.pip_off + npix, 4u)) != PN_OK)
        return st;
    npip = s.pip_off[npix];
    if ((st = pn_dev_run(fs, PN_K_SRT_PIP_LIST, npix)) != PN_OK) return st;
    t2 = pn_dev_timestamp(fs);
    if ((st = pn_dev_run(fs, PN_K_SRT_EXACT, npip)) != PN_OK || (st = pn_dev_to_host(fs, s.words, 16u)) != PN_OK)
        return st;
    ctx->stats.srt.ns_map = t1 - t0;
    ctx->stats.srt.ns_classify = t2 - t1;
    ctx->stats.srt.ns_exact = pn_dev_timestamp(fs) - t2;
    ctx->stats.srt.map = res;
    ctx->stats.srt.pip = npip;
    ctx->stats.srt.thin = s.words[PN_SRT_WORD_THIN];
    ctx->stats.srt.tiles_masked = s.words[PN_SRT_WORD_TILES];
    ctx->stats.srt.cons_texels = s.words[PN_SRT_WORD_CONS];
    return PN_OK;
}

PN_ALGO_NO_SCENE(srt)
#else
PN_ALGO_STUBS(SRT, srt)
#endif
