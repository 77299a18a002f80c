/* pn_mcsm.c - the Monte Carlo shadow maps' whole frame (sequence in pn_mcsm_frame.h): the
 * layers' view, then the passes of kernels/pn_mcsm.h between them, run on the frame's port.
 * Written once: both ports run this sequence. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_mcsm_frame.h"
#include "pn_passes.h"

#if PN_ENABLE_MCSM

/* The context's largest depth layer: 0 (PN_MCSM_MAP_MAX) or 8 .. PN_MCSM_MAP_MAX. */
int pn_mcsm_limits_ok(const pn_limits *l) { return l->mc_map_max == 0u || (l->mc_map_max >= 8u && l->mc_map_max <= PN_MCSM_MAP_MAX); }
static uint32_t pn_mc_map_max(const pn_limits *l) { return l->mc_map_max ? l->mc_map_max : PN_MCSM_MAP_MAX; }

/* PN_ALGO_MCSM's options (pn_algorithms.h): checked, then the frame's parameters, 0 meaning
 * the default. */
pn_status pn_mcsm_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    pn_context *ctx = fs->ctx;
    if (opt->mcsm.layers > 3u)
        return pn_fail(ctx, PN_E_INVALID_ARG, "mcsm.layers = %u; it must be 0 or in 1 .. 3", opt->mcsm.layers);
    if (opt->mcsm.search > PN_MC_SEARCH_HIER)
        return pn_fail(ctx, PN_E_INVALID_ARG, "mcsm.search = %u; it must be 0 or a PN_MC_SEARCH_*", opt->mcsm.search);
    if (opt->mcsm.rays > 8u)
        return pn_fail(ctx, PN_E_INVALID_ARG, "mcsm.rays = %u; it must be 0 or in 1 .. 8 (n x n rays)", opt->mcsm.rays);
    if (opt->mcsm.blur > 8u && opt->mcsm.blur != PN_MC_BLUR_OFF)
        return pn_fail(ctx, PN_E_INVALID_ARG, "mcsm.blur = %u; it must be 0, 1 .. 8 or PN_MC_BLUR_OFF", opt->mcsm.blur);
    if (opt->mcsm.map != 0u && (opt->mcsm.map < 8u || opt->mcsm.map > pn_mc_map_max(&ctx->limits)))
        return pn_fail(ctx, PN_E_INVALID_ARG, "mcsm.map = %u; it must be 0 or in 8 .. %u (pn_limits.mc_map_max)",
                       opt->mcsm.map, pn_mc_map_max(&ctx->limits));
    if (opt->mcsm.flags & ~(PN_MC_NO_BIAS | PN_MC_NO_CLASSIFY | PN_MC_NO_STACKED))
        return pn_fail(ctx, PN_E_INVALID_ARG, "mcsm.flags = %u has unknown bits", opt->mcsm.flags);
    /* Defaults: the configuration docs/algorithms/mcsm.md recommends: three layers (two
     * for a point query, which has no eye), hierarchical search, 3 x 3 rays, blur radius
     * 1, 512^2 layers. */
    fs->res = opt->mcsm.map ? opt->mcsm.map : pn_mc_map_max(&ctx->limits);
    if (!opt->mcsm.map && fs->res > 512u) fs->res = 512u;
    fs->K.mc.layers = opt->mcsm.layers ? opt->mcsm.layers : fs->points ? 2u : 3u;
    fs->K.mc.search = opt->mcsm.search ? opt->mcsm.search : PN_MC_SEARCH_HIER;
    fs->K.mc.rays = opt->mcsm.rays ? opt->mcsm.rays : 3u;
    /* A point query has no screen to blur over, nor the eye's depth for a third layer. */
    if (fs->points && fs->K.mc.layers == 3u)
        return pn_fail(ctx, PN_E_UNSUPPORTED, "mcsm.layers = 3 needs the eye's depth: no point query");
    fs->K.mc.blur = fs->points || opt->mcsm.blur == PN_MC_BLUR_OFF ? 0u : opt->mcsm.blur ? opt->mcsm.blur : 1u;
    fs->K.mc.flags = opt->mcsm.flags;
    fs->K.mc.seed = opt->mcsm.seed;
    return PN_OK;
}

/* The kernels' copies of the public constants (kernels/ does not include penumbra.h). */
typedef char pn_mc_consts_agree[PN_MC_S_LINEAR == PN_MC_SEARCH_LINEAR && PN_MC_S_HIER == PN_MC_SEARCH_HIER &&
                                        PN_MC_F_NO_BIAS == PN_MC_NO_BIAS && PN_MC_F_NO_CLASSIFY == PN_MC_NO_CLASSIFY &&
                                        PN_MC_F_NO_STACKED == PN_MC_NO_STACKED && PN_MC_CLASS_STACKED == PN_MC_WORD_STACKED + 1u &&
                                        PN_MC_RAYS_MAX == 8u && PN_MC_BLUR_MAX + 1u <= 12u &&
                                        PN_LVIEW_BOX == PN_LVIEW_BOX_FLOATS && PN_MC_WORDS == 8u && PN_MC_CLASS_GRAZING == PN_MC_WORD_GRAZING + 1u &&
                                        PN_MC_ROW_WORDS == 16u /* 64 bytes a row (pn_mc_carve) */
                                        && PN_MCSM_MAP_MAX <= 2048u /* N-buffer offsets in 32 bits, 12 levels (pn_nb_mm_lay) */
                                    ? 1
                                    : -1];

typedef struct pn_mc_pools {
    float *box;      /* [height * PN_LVIEW_BOX]: row bounds (kernels/pn_lview.h) */
    float *nb;       /* [kept texels * PN_NB_MM]: the N-buffer (pn_nb_mm_lay_init), level 0 the layers */
    float *tmp;      /* [width * height]: the blur's other buffer */
    uint32_t *words; /* [height * PN_MC_ROW_WORDS]: class counters per row */
} pn_mc_pools;

/* The N-buffer keeps every level, or every third with PN_LIMITS_SPARSE_NBUFFER. */
static uint32_t pn_mc_nb_step(const pn_limits *l) { return (l->flags & PN_LIMITS_SPARSE_NBUFFER) ? 3u : 1u; }

/* The frame's pools at w x h with a res^2 map: run by the frame on the frame region and
 * by pn_mcsm_query at the limits' maxima. */
static void pn_mc_carve(pn_carver *c, const pn_limits *l, uint32_t w, uint32_t h, uint32_t res, pn_mc_pools *s)
{
    pn_kmc mc;
    pn_nb_mm_lay ly;
    uint32_t texels;
    mc.res = res;
    mc.levels = pn_nb_levels(res);
    mc.nb_step = pn_mc_nb_step(l);
    texels = pn_nb_mm_lay_init(&mc, &ly);
    s->box = (float *)pn_pool(c, h, 4u * PN_LVIEW_BOX_FLOATS, "mcsm row bounds");
    s->nb = (float *)pn_pool(c, texels, 4u * PN_NB_MM, "mcsm N-buffer");
    s->tmp = (float *)pn_pool(c, (uint64_t)w * h, 4u, "mcsm blur buffer");
    s->words = (uint32_t *)pn_pool(c, h, 4u * PN_MC_ROW_WORDS, "mcsm counters");
}

void pn_mcsm_query(pn_carver *c, const pn_limits *l)
{
    pn_mc_pools s;
    pn_mc_carve(c, l, l->max_width, l->max_height, pn_mc_map_max(l), &s);
}

static pn_status pn_mc_begin(pn_frame_state *fs, pn_mc_pools *s, uint32_t res)
{
    pn_context *ctx = fs->ctx;
    pn_kpools *P = &fs->P;
    pn_carver c;
    pn_carver_frame(&c, ctx);
    pn_mc_carve(&c, &ctx->limits, fs->width, fs->height, res, s);
    if (!c.ok) return PN_E_POOL_EXHAUSTED;
    P->lview_box = pn_dev_off(ctx, s->box);
    P->mc_nb = pn_dev_off(ctx, s->nb);
    P->mc_tmp = pn_dev_off(ctx, s->tmp);
    P->mc_words = pn_dev_off(ctx, s->words);
    memset(&ctx->stats.mcsm, 0, sizeof(ctx->stats.mcsm));
    return PN_OK;
}

/* The N-buffer's bound over the whole map, which every pixel's classification starts from:
 * pn_nb_mm_rect's boxes, read back once a frame instead of looked up per pixel (their
 * texels, or the kept level they are rebuilt from). */
static pn_status pn_mc_whole(pn_frame_state *fs, const float *nb, pn_kmc *mc)
{
    pn_nb_mm_lay ly;
    uint32_t at[4], i, l, n;
    pn_status st;
    (void)pn_nb_mm_lay_init(mc, &ly);
    n = pn_nb_mm_rect_at(&ly, 0, 0, (int32_t)mc->res, (int32_t)mc->res, at, &l);
    if (ly.src[l] != l) {
        if ((st = pn_dev_to_host(fs, nb + ly.off[l], (size_t)ly.w[l] * ly.w[l] * 4u * PN_NB_MM)) != PN_OK) return st;
    } else {
        for (i = 0; i < n; i++)
            if ((st = pn_dev_to_host(fs, nb + at[i], 4u * PN_NB_MM)) != PN_OK) return st;
    }
    pn_nb_mm_rect_get(nb, &ly, at, n, l, mc->whole);
    return PN_OK;
}

/* Binomial blur weights C(2r, r + i), i = 0 .. r, as floats (exact: at most C(16, 8)). */
static void pn_mc_weights(pn_kmc *mc)
{
    uint32_t r = mc->blur, i, row[2u * PN_MC_BLUR_MAX + 1u], n, k;
    for (i = 0; i < 12u; i++) mc->blur_w[i] = 0.0f;
    if (r == 0u) return;
    /* Pascal's row 2r, built in place. */
    for (k = 0; k <= 2u * r; k++) row[k] = 0u;
    row[0] = 1u;
    for (n = 1; n <= 2u * r; n++)
        for (k = n; k > 0u; k--) row[k] += row[k - 1u];
    for (i = 0; i <= r; i++) mc->blur_w[i] = (float)row[r + i];
}

pn_status pn_mcsm_frame(pn_frame_state *fs)
{
    pn_context *ctx = fs->ctx;
    pn_kparams *K = &fs->K;
    pn_kmc *mc = &K->mc;
    pn_mc_pools s;
    pn_lwin w;
    uint32_t res = fs->res, l, y;
    uint64_t t0 = pn_dev_timestamp(fs), t1;
    int front;
    pn_status st;

    if ((st = pn_mc_begin(fs, &s, res)) != PN_OK) return st;
    pn_light_view(ctx, &K->light, res, &K->lview);
    pn_light_halves(&K->light, &K->lview_ha, &K->lview_hb);
    mc->res = res;
    mc->nb_step = pn_mc_nb_step(&ctx->limits);
    mc->levels = pn_nb_levels(res);
    mc->blur_depth = 100.0f; /* 1% of the centre's depth away: half the weight */
    pn_mc_weights(mc);
    ctx->stats.mcsm.map = res;

    if ((st = pn_dev_fill(fs, s.words, fs->height * PN_MC_ROW_WORDS, 0u)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_LVIEW_BOUNDS, fs->height)) != PN_OK ||
        (st = pn_dev_to_host(fs, s.box, (size_t)fs->height * 4u * PN_LVIEW_BOX)) != PN_OK)
        return st;
    front = pn_lview_window(ctx, s.box, fs->height, res, &K->light, K->lview_ha, K->lview_hb, &K->lview, &w);
    if (front) {
        /* The layers need only hold the occluders: beyond their box's image a ray meets none. */
        pn_lview_fit_occluders(ctx, res, &K->light, &K->lview, &w);
        mc->d = w.d;
        mc->sfac = K->light.is_point ? 0.0f : (float)res * K->lview_ha / w.tx;
        mc->sfac_y = K->light.is_point ? 0.0f : (float)res * K->lview_hb / w.ty;
        /* eq. 3.2: half a texel's diagonal at depth z + d, sqrt(2) z tan(fov / 2) / w. */
        mc->bias_k = 1.41421356f * pn_kmaxf(w.tx, w.ty) / (float)res;
        /* Layers, then the N-buffer above them. */
        if ((st = pn_dev_run(fs, PN_K_MC_CLEAR, res)) != PN_OK || (st = pn_raster_setup(fs, PN_K_MC_ROWS)) != PN_OK ||
            (st = pn_dev_run(fs, PN_K_MC_BAND, (res + PN_RASTER_BAND - 1u) / PN_RASTER_BAND)) != PN_OK)
            return st;
        t1 = pn_dev_timestamp(fs);
        ctx->stats.mcsm.ns_layers = t1 - t0;
        t0 = t1;
        for (l = mc->nb_step; l < mc->levels; l += mc->nb_step) {
            mc->level = l;
            if ((st = pn_dev_run(fs, PN_K_MC_NBUF, pn_nb_mm_w(res, l))) != PN_OK) return st;
        }
        if ((st = pn_mc_whole(fs, s.nb, mc)) != PN_OK) return st;
        t1 = pn_dev_timestamp(fs);
        ctx->stats.mcsm.ns_nbuffer = t1 - t0;
        t0 = t1;
    }
    /* Without an origin in front of the light no pixel reads the layers: every pixel is
     * background (1), unlit (0) or one whose origin no window holds (the exact fallback's
     * pass, whose time counts with the rays'). */
    if ((st = pn_dev_run(fs, PN_K_MC_PIXEL, fs->height)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_MC_OUTSIDE, fs->height)) != PN_OK)
        return st;
    t1 = pn_dev_timestamp(fs);
    ctx->stats.mcsm.ns_rays = t1 - t0;
    t0 = t1;
    if (front && mc->blur > 0u) {
        if ((st = pn_dev_run(fs, PN_K_MC_BLUR_H, fs->height)) != PN_OK ||
            (st = pn_dev_run(fs, PN_K_MC_BLUR_V, fs->height)) != PN_OK)
            return st;
        ctx->stats.mcsm.ns_blur = pn_dev_timestamp(fs) - t0;
    }
    if ((st = pn_dev_to_host(fs, s.words, (size_t)fs->height * 4u * PN_MC_ROW_WORDS)) != PN_OK ||
        (st = pn_dev_to_host(fs, fs->counters, (size_t)fs->height * sizeof(pn_row_counters))) != PN_OK)
        return st;
    for (y = 0; y < fs->height; y++) {
        const uint32_t *wd = s.words + (size_t)y * PN_MC_ROW_WORDS;
        const pn_shadow_counters *c = &((const pn_row_counters *)fs->counters)[y].c;
        ctx->stats.mcsm.lit += wd[PN_MC_WORD_LIT];
        ctx->stats.mcsm.umbra += wd[PN_MC_WORD_UMBRA];
        ctx->stats.mcsm.penumbra += wd[PN_MC_WORD_PENUMBRA] + wd[PN_MC_WORD_PENUMBRA_OPEN] + wd[PN_MC_WORD_PENUMBRA_SHUT];
        ctx->stats.mcsm.penumbra_open += wd[PN_MC_WORD_PENUMBRA_OPEN];
        ctx->stats.mcsm.penumbra_shut += wd[PN_MC_WORD_PENUMBRA_SHUT];
        ctx->stats.mcsm.capped += wd[PN_MC_WORD_CAPPED];
        ctx->stats.mcsm.rays += c->candidates;
        ctx->stats.mcsm.steps += c->nodes;
        ctx->stats.mcsm.grazing += wd[PN_MC_WORD_GRAZING];
        ctx->stats.mcsm.stacked += wd[PN_MC_WORD_STACKED];
        ctx->stats.mcsm.outside += c->exact - wd[PN_MC_WORD_GRAZING]; /* the fallback's pass counts both */
    }
    return PN_OK;
}

/* The scene: which triangles are sheets (PN_TRI_SHEET, pn_connect.c; pn_mc_run reads it).
 * A context that runs the wedges too has it from their connectivity; otherwise the
 * connectivity is built in the frame region and dropped. */
static int pn_mc_with_wedges(const pn_limits *l) { return PN_ENABLE_WEDGES && (pn_limits_algos(l) & (1u << PN_ALGO_WEDGES)); }

void pn_mcsm_persist(pn_carver *c, const pn_limits *l)
{
    (void)c;
    (void)l;
}

uint64_t pn_mcsm_scene_scratch(const pn_limits *l)
{
    return pn_mc_with_wedges(l) ? 0u : (PN_CONNECT_SCRATCH + PN_CONNECT_POOLS) * (uint64_t)l->max_triangles + 4u;
}

pn_status pn_mcsm_scene(pn_context *ctx)
{
    uint32_t T = ctx->tri_count, *pools = (uint32_t *)(void *)ctx->frame + (size_t)(PN_CONNECT_SCRATCH / 4u) * T;
    if (!pn_mc_with_wedges(&ctx->limits)) pn_connect_build(ctx, pools, pools + 3u * (size_t)T, pools + 6u * (size_t)T + 1u);
    return PN_OK;
}

pn_status pn_mcsm_upload(pn_frame_state *fs)
{
    (void)fs;
    return PN_OK;
}
#else
PN_ALGO_STUBS(MCSM, mcsm)
#endif
