/* pn_wedges.c - the penumbra wedges' whole frame (sequence in pn_wedges_frame.h), run on
 * the frame's port. Written once: both ports run this sequence. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_passes.h"
#include "pn_wedges_frame.h"

#if PN_ENABLE_WEDGES

/* The scene's connectivity (pn_connect.c builds it at pn_scene_set, kernels/pn_wedges.h
 * reads it every frame): half-edges by edge, the first half-edge of each edge, each
 * triangle's object. Persistent, in the module's block of the arena. */
typedef struct pn_wg_conn {
    uint32_t *hedge; /* [3 T] */
    uint32_t *run;   /* [3 T + 1] */
    uint32_t *tcomp; /* [T] */
} pn_wg_conn;

static void pn_wg_conn_carve(pn_carver *c, uint32_t tris, pn_wg_conn *w)
{
    w->hedge = (uint32_t *)pn_pool(c, 3u * (uint64_t)tris, 4u, "wedges half-edges");
    w->run = (uint32_t *)pn_pool(c, 3u * (uint64_t)tris + 1u, 4u, "wedges edges");
    w->tcomp = (uint32_t *)pn_pool(c, tris, 4u, "wedges triangle objects");
}

void pn_wedges_persist(pn_carver *c, const pn_limits *l)
{
    pn_wg_conn w;
    pn_wg_conn_carve(c, l->max_triangles, &w);
}

/* The connectivity's pools in the context's arena (the offsets pn_carve gave). */
static void pn_wg_conn_at(const pn_context *ctx, pn_wg_conn *w)
{
    pn_carver c;
    pn_carver_at(&c, ctx->base, ctx->layout.algo[PN_ALGO_WEDGES]);
    pn_wg_conn_carve(&c, ctx->limits.max_triangles, w);
}

/* pn_connect_build's vertex ids and union-find: 6 words a triangle of the frame region. */
uint64_t pn_wedges_scene_scratch(const pn_limits *l) { return PN_CONNECT_SCRATCH * (uint64_t)l->max_triangles; }

pn_status pn_wedges_scene(pn_context *ctx)
{
    pn_wg_conn w;
    pn_wg_conn_at(ctx, &w);
    pn_connect_build(ctx, w.hedge, w.run, w.tcomp);
    return PN_OK;
}

pn_status pn_wedges_upload(pn_frame_state *fs)
{
    const pn_context *ctx = fs->ctx;
    pn_wg_conn w;
    pn_status st;
    pn_wg_conn_at(ctx, &w);
    if ((st = pn_dev_to_device(fs, w.hedge, (size_t)w.run[ctx->stats.wedges.edges] * sizeof(uint32_t))) != PN_OK ||
        (st = pn_dev_to_device(fs, w.run, ((size_t)ctx->stats.wedges.edges + 1u) * sizeof(uint32_t))) != PN_OK)
        return st;
    return pn_dev_to_device(fs, w.tcomp, (size_t)ctx->tri_count * sizeof(uint32_t));
}

/* The context's pair pool: 0 (PN_WEDGES_PAIRS) or at most it. */
int pn_wedges_limits_ok(const pn_limits *l)
{
    return l->wg_pairs <= PN_WEDGES_PAIRS &&
           (l->wg_silhouettes == 0u || (l->wg_silhouettes >= 64u && l->wg_silhouettes <= PN_WEDGES_SIL_MAX));
}
/* Screen tiles of a frame; silhouettes a context holds (an edge per triangle side, at most
 * limits.wg_silhouettes, by default PN_WEDGES_SIL_MAX); (tile, silhouette) pairs: limits.wg_pairs, or by default the larger
 * of a 32nd of every tile with every silhouette slot (PN_WG_PAIRS_SHARE) and 6 pairs a slot
 * (PN_WG_PAIRS_PER_SIL: small frames, where a wedge's few tiles are a larger share), at most
 * PN_WEDGES_PAIRS; never more than every tile with every slot. On the 15 built-in and
 * shared scenes at 64^2, 128^2, 256^2 and 512^2 every frame fits: the most a frame needs is
 * thin's, a 41st of the product at 256^2 (3.6 pairs a slot at 128^2); the tree needs a
 * 182nd at 512^2. At least the slots, so a tile, which needs at most a pair a silhouette,
 * always fits. */
static uint32_t pn_wg_tiles_of(uint32_t width, uint32_t height) { return PN_WG_TILES(width) * PN_WG_TILES(height); }
static uint32_t pn_wg_sil_max(const pn_limits *l)
{
    uint64_t edges = 3u * (uint64_t)l->max_triangles;
    uint32_t most = l->wg_silhouettes ? l->wg_silhouettes : PN_WEDGES_SIL_MAX;
    return edges < most ? (uint32_t)edges : most;
}
static uint32_t pn_wg_pairs_max(const pn_limits *l)
{
    uint64_t most = (uint64_t)pn_wg_tiles_of(l->max_width, l->max_height) * pn_wg_sil_max(l);
    uint64_t cap = most / PN_WG_PAIRS_SHARE;
    if (cap < (uint64_t)PN_WG_PAIRS_PER_SIL * pn_wg_sil_max(l)) cap = (uint64_t)PN_WG_PAIRS_PER_SIL * pn_wg_sil_max(l);
    if (cap > PN_WEDGES_PAIRS) cap = PN_WEDGES_PAIRS;
    if (l->wg_pairs) cap = l->wg_pairs;
    return most < cap ? (uint32_t)most : (uint32_t)cap;
}

/* PN_ALGO_WEDGES's options (pn_algorithms.h): checked, then the frame's parameters, 0 meaning
 * the default. */
pn_status pn_wedges_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    pn_context *ctx = fs->ctx;
    if (opt->wedges.mode > PN_WG_MODE_ADDITIVE)
        return pn_fail(ctx, PN_E_INVALID_ARG, "wedges.mode = %u; it must be 0 or a PN_WG_MODE_*", opt->wedges.mode);
    if (opt->wedges.flags & ~PN_WG_NO_CULL)
        return pn_fail(ctx, PN_E_INVALID_ARG, "wedges.flags = %u has unknown bits", opt->wedges.flags);
    if (fs->points)
        return pn_fail(ctx, PN_E_UNSUPPORTED, "the penumbra wedges work in a camera's screen tiles: no point query");
    fs->K.wg.mode = opt->wedges.mode ? opt->wedges.mode : PN_WG_MODE_BLEND;
    fs->K.wg.no_cull = (opt->wedges.flags & PN_WG_NO_CULL) != 0u;
    return PN_OK;
}

typedef char pn_wg_consts_agree[PN_WG_M_BLEND == PN_WG_MODE_BLEND && PN_WG_M_ADD == PN_WG_MODE_ADDITIVE ? 1 : -1];
/* PN_WEDGES_BYTES_MAX (penumbra.h) counts these sizes. */
typedef char pn_wg_sizes_agree[sizeof(pn_wsil) == 96u && PN_WG_BOX == 7u && PN_WG_TILE == 16u && PN_WG_BLOCK == 16u &&
                                        PN_WG_SBLOCK == 128u ? 1 : -1];

typedef struct pn_wg_pools {
    uint32_t *tcast;  /* [T] how each triangle casts */
    uint32_t *soff;   /* [runs + 1] silhouette flags -> slots */
    pn_wsil *sil;     /* [sil_cap] */
    float *bbox;      /* [(sil_cap / PN_WG_BLOCK + 1) * 6] the blocks' boxes */
    float *sbox;      /* [(sil_cap / PN_WG_SBLOCK + 1) * 6] the superblocks' */
    float *tbox;      /* [tiles * PN_WG_BOX] the tiles' boxes in depth */
    uint32_t *poff;   /* [sil_cap + 1] pair counts -> offsets */
    uint32_t *pairs;  /* [pair_cap * 2] (tile, silhouette); after the sort, the tile lists'
                         runs (pn_wg_runs) */
    uint32_t *sorted; /* [pair_cap] silhouettes by tile */
    uint32_t *toff;   /* [tiles + 1] */
    uint32_t *tscr;   /* [tiles] sort scratch */
    uint32_t *rowc;   /* [tile rows] pairs a tile row needs (the band planner's) */
    uint32_t *kept;   /* [sil_cap * 2 + 1] where each silhouette's count kept its tiles, in
                         the tile-list pool (pn_wg_bin), and the cursor there */
} pn_wg_pools;

/* The frame's pools at w x h for `tris` triangles of `edges` edges: run by the frame on
 * the frame region and by pn_wedges_query at the limits' maxima (an edge per triangle side). */
static void pn_wg_carve(pn_carver *c, const pn_limits *l, uint32_t w, uint32_t h, uint32_t tris, uint64_t edges,
                        pn_wg_pools *s)
{
    uint32_t tiles = pn_wg_tiles_of(w, h);
    s->tcast = (uint32_t *)pn_pool(c, tris, 4u, "wedges triangle casting");
    s->soff = (uint32_t *)pn_pool(c, edges + 1u, 4u, "wedges silhouette slots");
    s->sil = (pn_wsil *)pn_pool(c, pn_wg_sil_max(l), sizeof(pn_wsil), "wedges silhouettes");
    s->bbox = (float *)pn_pool(c, pn_wg_sil_max(l) / PN_WG_BLOCK + 1u, 6u * sizeof(float), "wedges silhouette blocks");
    s->sbox = (float *)pn_pool(c, pn_wg_sil_max(l) / PN_WG_SBLOCK + 1u, 6u * sizeof(float), "wedges silhouette superblocks");
    s->tbox = (float *)pn_pool(c, tiles, PN_WG_BOX * sizeof(float), "wedges tile boxes");
    s->poff = (uint32_t *)pn_pool(c, (uint64_t)pn_wg_sil_max(l) + 1u, 4u, "wedges pair offsets");
    s->pairs = (uint32_t *)pn_pool(c, pn_wg_pairs_max(l), 8u, "wedges tile pairs");
    s->sorted = (uint32_t *)pn_pool(c, pn_wg_pairs_max(l), 4u, "wedges tile lists");
    s->toff = (uint32_t *)pn_pool(c, (uint64_t)tiles + 1u, 4u, "wedges tile offsets");
    s->tscr = (uint32_t *)pn_pool(c, tiles, 4u, "wedges sort scratch");
    s->rowc = (uint32_t *)pn_pool(c, PN_WG_TILES(h), 4u, "wedges tile row pairs");
    s->kept = (uint32_t *)pn_pool(c, 2u * (uint64_t)pn_wg_sil_max(l) + 1u, 4u, "wedges kept tiles");
}

void pn_wedges_query(pn_carver *c, const pn_limits *l)
{
    pn_wg_pools s;
    pn_wg_carve(c, l, l->max_width, l->max_height, l->max_triangles, 3u * (uint64_t)l->max_triangles, &s);
}

static pn_status pn_wg_begin(pn_frame_state *fs, pn_wg_pools *s)
{
    pn_context *ctx = fs->ctx;
    pn_kpools *P = &fs->P;
    pn_carver c;
    pn_wg_conn w;
    pn_carver_frame(&c, ctx);
    pn_wg_carve(&c, &ctx->limits, fs->width, fs->height, ctx->tri_count, ctx->stats.wedges.edges, s);
    if (!c.ok) return PN_E_POOL_EXHAUSTED;
    pn_wg_conn_at(ctx, &w);
    P->wg_hedge = pn_dev_off(ctx, w.hedge);
    P->wg_run = pn_dev_off(ctx, w.run);
    P->wg_tcomp = pn_dev_off(ctx, w.tcomp);
    P->wg_tcast = pn_dev_off(ctx, s->tcast);
    P->wg_soff = pn_dev_off(ctx, s->soff);
    P->wg_sil = pn_dev_off(ctx, s->sil);
    P->wg_bbox = pn_dev_off(ctx, s->bbox);
    P->wg_sbox = pn_dev_off(ctx, s->sbox);
    P->wg_tbox = pn_dev_off(ctx, s->tbox);
    P->wg_poff = pn_dev_off(ctx, s->poff);
    P->wg_pairs = pn_dev_off(ctx, s->pairs);
    P->wg_sorted = pn_dev_off(ctx, s->sorted);
    P->wg_toff = pn_dev_off(ctx, s->toff);
    P->wg_rowc = pn_dev_off(ctx, s->rowc);
    P->wg_kept = pn_dev_off(ctx, s->kept);
    ctx->stats.wedges.silhouettes = 0;
    ctx->stats.wedges.pairs = 0;
    ctx->stats.wedges.bands = 0;
    ctx->stats.wedges.sil_bands = 0;
    ctx->stats.wedges.touched = 0;
    ctx->stats.wedges.evaluated = 0;
    ctx->stats.wedges.hard_blockers = 0;
    ctx->stats.wedges.hard_overflow = 0;
    ctx->stats.wedges.exact_pixels = 0;
    ctx->stats.wedges.full_tiles = 0;
    ctx->stats.wedges.ns_silhouettes = 0;
    ctx->stats.wedges.ns_binning = 0;
    ctx->stats.wedges.ns_pixels = 0;
    return PN_OK;
}

/* A band's pixels: the rows of tile rows [by0, by1), the pass skipping columns outside
 * [bx0, bx1). */
static pn_status pn_wg_pixels(pn_frame_state *fs)
{
    const pn_kwg *G = &fs->K.wg;
    uint32_t y0 = G->by0 * PN_WG_TILE, y1 = G->by1 * PN_WG_TILE;
    if (y1 > fs->height) y1 = fs->height;
    fs->K.wg.pix0 = y0 * fs->width;
    return pn_dev_run(fs, PN_K_WG_PIXEL, (y1 - y0) * fs->width);
}

/* Bins the silhouettes to the tiles of band K->wg.b* and shades its pixels; *need: the
 * band's pairs, and nothing else done when they exceed the pool's cap. */
static pn_status pn_wg_band(pn_frame_state *fs, const pn_wg_pools *s, uint32_t tiles, uint32_t cap, uint32_t *need)
{
    pn_context *ctx = fs->ctx;
    uint32_t nsil = fs->K.wg.sils, npairs;
    uint64_t t0 = pn_dev_timestamp(fs), t1;
    pn_status st;
    if (nsil > 0u && ((fs->K.wg.count_rows && (st = pn_dev_fill(fs, s->rowc, PN_WG_TILES(fs->height), 0u)) != PN_OK) ||
                      (st = pn_dev_fill(fs, s->kept + 2u * (size_t)nsil, 1u, 0u)) != PN_OK ||
                      (st = pn_dev_run(fs, PN_K_WG_COUNT, nsil)) != PN_OK || (st = pn_dev_scan(fs, s->poff, nsil)) != PN_OK ||
                      (st = pn_dev_to_host(fs, s->poff + nsil, 4u)) != PN_OK))
        return st;
    *need = npairs = nsil > 0u ? s->poff[nsil] : 0u;
    if (npairs > cap) return PN_OK;
    /* Pairs are scattered in silhouette order, so each tile's silhouettes ascend: the sort
     * by tile is the one stable order on every port. */
    if (npairs > 0u && ((st = pn_dev_run(fs, PN_K_WG_SCATTER, nsil)) != PN_OK ||
                        (st = pn_dev_sort_pairs(fs, s->pairs, npairs, tiles, s->sorted, s->toff, s->tscr)) != PN_OK ||
                        (st = pn_dev_run(fs, PN_K_WG_RUNS, tiles)) != PN_OK))
        return st;
    if (npairs == 0u && (st = pn_dev_fill(fs, s->toff, tiles + 1u, 0u)) != PN_OK) return st;
    ctx->stats.wedges.pairs += npairs;
    ctx->stats.wedges.bands++;
    t1 = pn_dev_timestamp(fs);
    ctx->stats.wedges.ns_binning += t1 - t0;
    st = pn_wg_pixels(fs);
    ctx->stats.wedges.ns_pixels += pn_dev_timestamp(fs) - t1;
    return st;
}

/* n tiles of a band that needed `need` > cap pairs, cut to fit a pool of `cap`: divided by
 * the ratio rounded up, and at least one fewer (32-bit arithmetic: no division helper on
 * a bare-metal target). */
static uint32_t pn_wg_shrink(uint32_t n, uint32_t need, uint32_t cap)
{
    uint32_t m = n / ((need - 1u) / cap + 1u);
    return m < 1u ? 1u : (m >= n ? n - 1u : m);
}

/* A band of rows x cols tiles that needed `need` > cap: cut, its rows first, then the tiles
 * of its one row; 0 when it is one tile. */
static int pn_wg_cut(uint32_t *rows, uint32_t *cols, uint32_t need, uint32_t cap)
{
    if (*rows > 1u)
        *rows = pn_wg_shrink(*rows, need, cap);
    else if (*cols > 1u)
        *cols = pn_wg_shrink(*cols, need, cap);
    else
        return 0;
    return 1;
}

/* The pixels of tiles [tx0, tx1) x [ty0, ty1), binned in bands of whole rows of those tiles
 * (of tiles of one row when a row alone needs more pairs than the pool holds) whose pairs
 * fit the pool, in order; a band that does not fit is cut and binned again. When the
 * tiles' pairs do not fit at once, their count gave each tile row's pairs (pn_wg_bin) and
 * every band takes the most rows that fit, so only a row that alone needs more is cut
 * again. Each pixel takes its tile's silhouettes in the same order whatever the bands, so
 * the bands change no byte. */
static pn_status pn_wg_tiles(pn_frame_state *fs, const pn_wg_pools *s, uint32_t tiles, uint32_t cap, uint32_t tx0,
                             uint32_t ty0, uint32_t tx1, uint32_t ty1)
{
    pn_context *ctx = fs->ctx;
    pn_kparams *K = &fs->K;
    uint32_t rows = ty1 - ty0, cols = tx1 - tx0, need, planned = 0u;
    pn_status st;
    K->wg.count_rows = rows > 1u; /* the first (all rows') count: the rows a plan needs */
    K->wg.bx0 = tx0;
    K->wg.by0 = ty0;
    while (K->wg.by0 < ty1) {
        if (planned && cols == tx1 - tx0) { /* the most whole rows from by0 whose pairs fit */
            uint32_t r = K->wg.by0, sum = 0u;
            while (r < ty1 && (r == K->wg.by0 || (sum <= cap && s->rowc[r] <= cap - sum))) sum += s->rowc[r++];
            rows = r - K->wg.by0;
        }
        K->wg.by1 = K->wg.by0 + rows < ty1 ? K->wg.by0 + rows : ty1;
        K->wg.bx1 = K->wg.bx0 + cols < tx1 ? K->wg.bx0 + cols : tx1;
        if ((st = pn_wg_band(fs, s, tiles, cap, &need)) != PN_OK) return st;
        if (need > cap && !planned && rows > 1u) {
            /* Every tile row's pairs, from the count of all rows; no later count touches
             * them. */
            planned = 1u;
            K->wg.count_rows = 0u;
            if ((st = pn_dev_to_host(fs, s->rowc, (size_t)PN_WG_TILES(fs->height) * sizeof(uint32_t))) != PN_OK)
                return st;
            continue;
        }
        if (need > cap) {
            if (!pn_wg_cut(&rows, &cols, need, cap)) /* pn_wedges_frame checked every tile */
                return pn_fail(ctx, PN_E_INTERNAL, "wedges: one screen tile needs %u pairs, above the pool's %u", need, cap);
            continue;
        }
        if (K->wg.bx1 < tx1) { /* the rest of this row of tiles next */
            K->wg.bx0 = K->wg.bx1;
            continue;
        }
        K->wg.bx0 = tx0;
        cols = tx1 - tx0;
        K->wg.by0 = K->wg.by1;
        if (!planned && need <= cap / 2u && rows < ty1 - ty0) rows *= 2u; /* sparser rows: try more at once */
    }
    return PN_OK;
}

/* The frame's pixels in bands of tiles whose silhouettes fit the silhouette pool (scap):
 * the whole frame when its nsil silhouettes do; else bands of whole tile rows (of tiles of
 * one row when a row alone needs more), each flagging again only the silhouettes a tile of
 * the band lists (pn_wg_sil_tiles), in the same order, so each pixel takes its tile's
 * silhouettes as it would in one band: the bands change no byte. A band whose silhouettes
 * do not fit is cut and flagged again. */
static pn_status pn_wg_sil_bands(pn_frame_state *fs, const pn_wg_pools *s, uint32_t tiles, uint32_t cap, uint32_t scap,
                                 uint32_t nsil)
{
    pn_context *ctx = fs->ctx;
    pn_kparams *K = &fs->K;
    uint32_t R = ctx->stats.wedges.edges, tw = PN_WG_TILES(fs->width), th = PN_WG_TILES(fs->height);
    uint32_t rows = th, cols = tw, n = nsil, sx0 = 0u, sy0 = 0u, sx1, sy1;
    uint64_t t0 = pn_dev_timestamp(fs), t1;
    pn_status st;
    while (sy0 < th) {
        sy1 = sy0 + rows < th ? sy0 + rows : th;
        sx1 = sx0 + cols < tw ? sx0 + cols : tw;
        if (nsil > scap) {
            /* the band pass reads the band where the binning reads its own */
            K->wg.bx0 = sx0;
            K->wg.by0 = sy0;
            K->wg.bx1 = sx1;
            K->wg.by1 = sy1;
            if ((st = pn_dev_run(fs, PN_K_WG_SIL_BAND, R)) != PN_OK || (st = pn_dev_scan(fs, s->soff, R)) != PN_OK ||
                (st = pn_dev_to_host(fs, s->soff + R, 4u)) != PN_OK)
                return st;
            n = s->soff[R];
            if (n > scap) {
                if (!pn_wg_cut(&rows, &cols, n, scap)) /* pn_wedges_frame checked every tile */
                    return pn_fail(ctx, PN_E_INTERNAL, "wedges: one screen tile lists %u silhouettes, above the pool's %u", n,
                                   scap);
                continue;
            }
        }
        K->wg.sils = n;
        if (n > 0u && ((st = pn_dev_run(fs, PN_K_WG_SIL_MAKE, R)) != PN_OK ||
                       (st = pn_dev_run(fs, PN_K_WG_OBJ_BOX, n)) != PN_OK ||
                       (st = pn_dev_run(fs, PN_K_WG_BLOCK_BOX, (n - 1u) / PN_WG_BLOCK + 1u)) != PN_OK ||
                       (st = pn_dev_run(fs, PN_K_WG_SBLOCK_BOX, (n - 1u) / PN_WG_SBLOCK + 1u)) != PN_OK))
            return st;
        ctx->stats.wedges.sil_bands++;
        t1 = pn_dev_timestamp(fs);
        ctx->stats.wedges.ns_silhouettes += t1 - t0;
        if ((st = pn_wg_tiles(fs, s, tiles, cap, sx0, sy0, sx1, sy1)) != PN_OK) return st;
        t0 = pn_dev_timestamp(fs);
        if (sx1 < tw) { /* the rest of this row of tiles next */
            sx0 = sx1;
            continue;
        }
        sx0 = 0u;
        cols = tw;
        sy0 = sy1;
        if (n <= scap / 2u && rows < th) rows *= 2u; /* sparser rows: try more at once */
    }
    ctx->stats.wedges.ns_silhouettes += pn_dev_timestamp(fs) - t0;
    return PN_OK;
}

pn_status pn_wedges_frame(pn_frame_state *fs)
{
    pn_context *ctx = fs->ctx;
    pn_kparams *K = &fs->K;
    pn_wg_pools s;
    uint32_t T = ctx->tri_count, R = ctx->stats.wedges.edges, y, nsil = 0;
    uint32_t tiles = pn_wg_tiles_of(fs->width, fs->height), tw = PN_WG_TILES(fs->width);
    uint32_t cap = pn_wg_pairs_max(&ctx->limits), scap = pn_wg_sil_max(&ctx->limits);
    uint64_t t0 = pn_dev_timestamp(fs);
    pn_status st;

    if ((st = pn_wg_begin(fs, &s)) != PN_OK) return st;
    K->wg.runs = R;
    {
        /* The highest point of the scene box above the light plane, widened by the shadow
         * origins' offset and a relative margin for the rounding of the heights. */
        float hm = 0.0f, e = 0.0f;
        float r = pn_kmaxf(pn_v3_linf(pn_v3_load(ctx->scene_min)), pn_v3_linf(pn_v3_load(ctx->scene_max)));
        uint32_t q;
        /* pn_wg_front's magnitudes, for any vertex A in the box (|A|inf <= r), rounded up. */
        K->wg.front_g = (3.0f * r + 2.0f * pn_v3_linf(pn_v3_load(K->light.c)) + pn_v3_linf(pn_v3_load(K->light.U)) +
                         pn_v3_linf(pn_v3_load(K->light.V)) + pn_v3_linf(pn_v3_load(K->view.eye))) *
                        1.001f;
        for (q = 0; q < 8u; q++) {
            float x = (q & 1u) ? ctx->scene_max[0] : ctx->scene_min[0], yy = (q & 2u) ? ctx->scene_max[1] : ctx->scene_min[1];
            float z = (q & 4u) ? ctx->scene_max[2] : ctx->scene_min[2];
            float h = (x - K->light.c[0]) * K->light.N[0] + (yy - K->light.c[1]) * K->light.N[1] +
                      (z - K->light.c[2]) * K->light.N[2];
            float m = (x < 0.0f ? -x : x) + (yy < 0.0f ? -yy : yy) + (z < 0.0f ? -z : z);
            if (h > hm) hm = h;
            if (m > e) e = m;
        }
        K->wg.hmax = hm + 2.0f * K->light.eps + 1e-5f * (hm + e);
    }
    K->wg.tiles_x = tw;
    K->wg.sils = 0u;
    K->wg.full = 0u;
    K->wg.keep_cap = cap; /* the tile-list pool's words: the count's kept tiles */
    /* Every frame's: the pixel pass reads a pixel's triangle's PN_WG_LIT_FRONT, a point
     * light's and a scene without edges' too (they read the previous frame's words when
     * only an area light's frame wrote them: fuzz_culls, a point light's frame after
     * another scene's). */
    if (T > 0u && (st = pn_dev_run(fs, PN_K_WG_CAST, T)) != PN_OK) return st;
    if (!K->light.is_point && R > 0u) {
        if ((st = pn_dev_run(fs, PN_K_WG_SIL_FLAG, R)) != PN_OK ||
            (st = pn_dev_scan(fs, s.soff, R)) != PN_OK || (st = pn_dev_to_host(fs, s.soff + R, 4u)) != PN_OK)
            return st;
        nsil = s.soff[R];
        ctx->stats.wedges.silhouettes = nsil;
        if (nsil > 0u && (st = pn_dev_run(fs, PN_K_WG_TILE_BOX, tiles)) != PN_OK) return st;
    }
    ctx->stats.wedges.ns_silhouettes = pn_dev_timestamp(fs) - t0;
    /* A band needs its tiles' lists in the pools: a tile's silhouettes in the silhouette
     * pool, its pairs (one a silhouette) in the pair pool. A list holds at most every
     * silhouette; where the pools could be short of one (silhouettes in bands, or a pair
     * pool smaller than the silhouette pool), every tile's list length is counted first
     * (pn_wg_sil_tiles, into the tile offsets, free until the first band's sort). A tile
     * whose list outgrows a pool (a view through a forest's crowns: hundreds of thousands
     * of leaves' wedges over 16 x 16 pixels) is marked PN_WG_FULL: it lists nothing and its
     * pixels take the reference at the frame's k (pn_stats.wedges.full_tiles), so no valid
     * scene fails for the pools' sake and no tile's pixels pay for more wedges than they
     * could use. */
    if (nsil > 0u && (nsil > scap || cap < scap)) {
        uint32_t i, most = scap < cap ? scap : cap, full = 0u;
        K->wg.bx0 = 0u;
        K->wg.by0 = 0u;
        K->wg.bx1 = tw;
        K->wg.by1 = PN_WG_TILES(fs->height);
        if ((st = pn_dev_fill(fs, s.toff, tiles, 0u)) != PN_OK || (st = pn_dev_run(fs, PN_K_WG_TILE_COUNT, R)) != PN_OK ||
            (st = pn_dev_to_host(fs, s.toff, (size_t)tiles * sizeof(uint32_t))) != PN_OK)
            return st;
        for (i = 0; i < tiles; i++) full += s.toff[i] > most;
        if (full > 0u) {
            if ((st = pn_dev_to_host(fs, s.tbox, (size_t)tiles * PN_WG_BOX * sizeof(float))) != PN_OK) return st;
            for (i = 0; i < tiles; i++)
                if (s.toff[i] > most) pn_wg_box_full(s.tbox + (size_t)i * PN_WG_BOX);
            if ((st = pn_dev_to_device(fs, s.tbox, (size_t)tiles * PN_WG_BOX * sizeof(float))) != PN_OK) return st;
            K->wg.full = 1u;
            ctx->stats.wedges.full_tiles = full;
        }
    }
    if ((st = pn_wg_sil_bands(fs, &s, tiles, cap, scap, nsil)) != PN_OK) return st;
    if ((st = pn_dev_to_host(fs, fs->counters, (size_t)fs->height * sizeof(pn_row_counters))) != PN_OK) return st;
    for (y = 0; y < fs->height; y++) {
        const pn_shadow_counters *c = &((const pn_row_counters *)fs->counters)[y].c;
        ctx->stats.wedges.evaluated += c->candidates;
        ctx->stats.wedges.touched += c->blocking;
        ctx->stats.wedges.hard_blockers += c->nodes;
        ctx->stats.wedges.hard_overflow += c->capped;
        ctx->stats.wedges.exact_pixels += c->exact;
    }
    return PN_OK;
}

#else
PN_ALGO_STUBS(WEDGES, wedges)
#endif
