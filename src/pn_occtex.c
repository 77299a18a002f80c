/* pn_occtex.c - the occlusion textures' whole frame (sequence in pn_occtex_frame.h): the
 * slicing view, the slice planes, and the passes of kernels/pn_occtex.h between them, run
 * on the frame's port. Written once: both ports run this sequence. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_occtex_frame.h"
#include "pn_passes.h"

#if PN_ENABLE_OCCTEX

/* The context's largest texture: 0 (PN_OCCTEX_MAP_MAX) or 8 .. PN_OCCTEX_MAP_MAX. */
int pn_occtex_limits_ok(const pn_limits *l)
{
    return l->occ_map_max == 0u || (l->occ_map_max >= 8u && l->occ_map_max <= PN_OCCTEX_MAP_MAX);
}
static uint32_t pn_occ_map_max(const pn_limits *l) { return l->occ_map_max ? l->occ_map_max : PN_OCCTEX_MAP_MAX; }
/* Words of the one-slice filter pool: the largest of the three filters (N-buffer levels,
 * summed-area table, mipmap); the depth map's PN_OCC_DEPTH_PLANES res^2 fit (res >= 8: at
 * least 4 levels). */
static uint64_t pn_occ_filter_words(uint32_t res)
{
    uint64_t nb = (uint64_t)pn_nb_levels(res) * res * res, sat = ((uint64_t)res + 1u) * (res + 1u);
    return nb > sat ? nb : sat;
}

/* PN_ALGO_OCCTEX's options (pn_algorithms.h): checked, then the frame's parameters, 0 meaning
 * the default. */
pn_status pn_occtex_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    pn_context *ctx = fs->ctx;
    if (opt->occtex.slices != 0u && (opt->occtex.slices < 2u || opt->occtex.slices > 16u))
        return pn_fail(ctx, PN_E_INVALID_ARG, "occtex.slices = %u; it must be 0 or in 2 .. 16", opt->occtex.slices);
    if (opt->occtex.map != 0u && (opt->occtex.map < 8u || opt->occtex.map > pn_occ_map_max(&ctx->limits)))
        return pn_fail(ctx, PN_E_INVALID_ARG, "occtex.map = %u; it must be 0 or in 8 .. %u (pn_limits.occ_map_max)",
                       opt->occtex.map, pn_occ_map_max(&ctx->limits));
    if (opt->occtex.filter > PN_OCC_FILTER_MIPMAP)
        return pn_fail(ctx, PN_E_INVALID_ARG, "occtex.filter = %u; it must be 0 or a PN_OCC_FILTER_*",
                       opt->occtex.filter);
    if (opt->occtex.combine > PN_OCC_COMBINE_SUM)
        return pn_fail(ctx, PN_E_INVALID_ARG, "occtex.combine = %u; it must be 0 or a PN_OCC_COMBINE_*",
                       opt->occtex.combine);
    if (opt->occtex.flags & ~(PN_OCC_LEAK_FIX | PN_OCC_PAPER_FADE))
        return pn_fail(ctx, PN_E_INVALID_ARG, "occtex.flags = %u has unknown bits", opt->occtex.flags);
    /* Defaults: the configuration docs/bench/RESULTS.md recommends ("Occlusion textures"). */
    fs->res = opt->occtex.map ? opt->occtex.map : pn_occ_map_max(&ctx->limits);
    if (!opt->occtex.map && fs->res > 512u) fs->res = 512u;
    fs->K.occ.slices = opt->occtex.slices ? opt->occtex.slices : 16u;
    fs->K.occ.filter = opt->occtex.filter ? opt->occtex.filter : PN_OCC_FILTER_SAT;
    fs->K.occ.combine = opt->occtex.combine ? opt->occtex.combine : PN_OCC_COMBINE_PRODUCT;
    fs->K.occ.flags = opt->occtex.flags;
    return PN_OK;
}

/* The kernels' copies of the public constants (kernels/ does not include penumbra.h). */
typedef char pn_occ_consts_agree[PN_OCC_F_NBUFFER == PN_OCC_FILTER_NBUFFER && PN_OCC_F_SAT == PN_OCC_FILTER_SAT &&
                                         PN_OCC_F_MIPMAP == PN_OCC_FILTER_MIPMAP &&
                                         PN_OCC_C_PRODUCT == PN_OCC_COMBINE_PRODUCT &&
                                         PN_OCC_C_MAX == PN_OCC_COMBINE_MAX && PN_OCC_C_SUM == PN_OCC_COMBINE_SUM &&
                                         PN_OCC_FLAG_LEAK_FIX == PN_OCC_LEAK_FIX &&
                                         PN_OCC_FLAG_PAPER_FADE == PN_OCC_PAPER_FADE && PN_LVIEW_BOX == PN_LVIEW_BOX_FLOATS &&
                                         PN_OCC_WORD_SLICE0 + PN_OCC_SLICES_MAX <= PN_OCC_WORDS &&
                                         PN_OCC_DEPTH_PLANES <= 3u /* <= the N-buffer's levels, res >= 8 */
                                     ? 1
                                     : -1];

typedef struct pn_occ_pools {
    float *box;      /* [height * PN_LVIEW_BOX]: row bounds (kernels/pn_lview.h) */
    uint32_t *bits;  /* [res^2]: bit k = the texel is covered in slice k */
    uint32_t *filt;  /* [pn_occ_filter_words(res)]: the depth map (PN_OCC_DEPTH_PLANES res^2
                        floats, kernels/pn_occtex.h), then one slice's filter at a time */
    uint32_t *words; /* [PN_OCC_WORDS]: bits set, and per slice */
} pn_occ_pools;

/* The frame's pools at height h with a res^2 map: run by the frame on the frame region
 * and by pn_occtex_query at the limits' maxima. */
static void pn_occ_carve(pn_carver *c, uint32_t h, uint32_t res, pn_occ_pools *s)
{
    s->box = (float *)pn_pool(c, h, 4u * PN_LVIEW_BOX_FLOATS, "occtex row bounds");
    s->bits = (uint32_t *)pn_pool(c, (uint64_t)res * res, 4u, "occtex slice bits");
    s->filt = (uint32_t *)pn_pool(c, pn_occ_filter_words(res), 4u, "occtex filter");
    s->words = (uint32_t *)pn_pool(c, PN_OCC_WORDS, 4u, "occtex counters");
}

void pn_occtex_query(pn_carver *c, const pn_limits *l)
{
    pn_occ_pools s;
    pn_occ_carve(c, l->max_height, pn_occ_map_max(l), &s);
}

static pn_status pn_occ_begin(pn_frame_state *fs, pn_occ_pools *s, uint32_t res)
{
    pn_context *ctx = fs->ctx;
    pn_kpools *P = &fs->P;
    pn_carver c;
    pn_carver_frame(&c, ctx);
    pn_occ_carve(&c, fs->height, res, s);
    if (!c.ok) return PN_E_POOL_EXHAUSTED;
    P->lview_box = pn_dev_off(ctx, s->box);
    P->occ_bits = pn_dev_off(ctx, s->bits);
    P->occ_filt = pn_dev_off(ctx, s->filt);
    P->occ_words = pn_dev_off(ctx, s->words);
    memset(&ctx->stats.occtex, 0, sizeof(ctx->stats.occtex));
    return PN_OK;
}

/* The nearest depth along the view axis f of any triangle part in front of the light
 * (>= 0), over the scene copy; +inf for none. The same floats on every port (host). */
static float pn_occ_nearest(const pn_context *ctx, const pn_klight *L, const pn_kview *lv)
{
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]), f = pn_v3_make(lv->f[0], lv->f[1], lv->f[2]);
    float best = PN_KINF;
    uint32_t t, i;
    for (t = 0; t < ctx->tri_count; t++) {
        const float *p = ctx->tris + (size_t)t * 9u;
        float lo = PN_KINF, hi = -PN_KINF;
        if (ctx->flags[t] & PN_TRI_DEGENERATE) continue;
        for (i = 0; i < 3u; i++) {
            float z = pn_v3_dot(pn_v3_sub(pn_v3_make(p[3u * i], p[3u * i + 1u], p[3u * i + 2u]), c), f);
            lo = pn_kminf(lo, z);
            hi = pn_kmaxf(hi, z);
        }
        if (!(hi > 0.0f)) continue;
        best = pn_kminf(best, pn_kmaxf(lo, 0.0f));
    }
    return best;
}

/* The slicing view (pn_lview_window: the centre of projection behind the light whose
 * frustum through the light's edges holds every lit origin) and the slice planes. Returns 0
 * when no lit origin lies in front of the light (nothing to slice). */
static int pn_occ_window(pn_frame_state *fs, const pn_occ_pools *s, uint32_t res, float *zmax_out)
{
    pn_context *ctx = fs->ctx;
    pn_kparams *K = &fs->K;
    const pn_klight *L = &K->light;
    pn_kview *lv = &K->lview;
    pn_kocc *o = &K->occ;
    float zmax, zmin, diag = ctx->scene_diag;
    pn_lwin w;
    if (!pn_lview_window(ctx, s->box, fs->height, res, L, K->lview_ha, K->lview_hb, lv, &w)) return 0;
    o->d = w.d;
    zmax = w.zmax;
    /* Kernel side in texels (pn_occtex.h): the light's half-edge over the window's half-tan,
     * times the texels. */
    o->sfac_x = L->is_point ? 0.0f : (float)res * K->lview_ha / w.tx;
    o->sfac_y = L->is_point ? 0.0f : (float)res * K->lview_hb / w.ty;
    /* Slice planes: nearest geometry to deepest origin. */
    zmin = pn_occ_nearest(ctx, L, lv);
    if (!(zmin <= zmax)) zmin = zmax;
    o->zmin = zmin;
    o->h = (zmax - zmin) / (float)(o->slices - 1u);
    if (!(o->h >= 1e-6f * diag)) o->h = pn_kmaxf(1e-6f * diag, 1e-30f);
    *zmax_out = zmax;
    return 1;
}

/* The highest N-buffer / mipmap level a lookup into slice k can touch: the kernel side
 * (pn_occ_slice_occlusion) grows with the origin's depth z, so it is largest at the
 * deepest origin zmax; lookups read levels floor(log2 s) and the next. One level of slack
 * for the rounding of s; every level above it is never read, so it is not built. */
static uint32_t pn_occ_top_level(const pn_kocc *o, uint32_t k, float zmax)
{
    float zb = o->zmin + (float)k * o->h, q = (zmax - zb) / (zmax * (zb + o->d));
    float s = pn_kmaxf(o->sfac_x * q, o->sfac_y * q), size = 1.0f;
    uint32_t l = 0u;
    if (!(s == s) || s > 1e30f) return o->levels - 1u;
    while (l + 1u < o->levels && 2.0f * size <= s) {
        l++;
        size *= 2.0f;
    }
    l += 2u;
    return l < o->levels ? l : o->levels - 1u;
}

/* The finish pass (the horizon, the exact fallback) and the lookups' count; its time from
 * t1 on is the lookups'. */
static pn_status pn_occ_finish(pn_frame_state *fs, uint64_t t1)
{
    pn_context *ctx = fs->ctx;
    uint64_t lookups = 0u;
    uint32_t y, outside = 0u;
    pn_status st;
    if ((st = pn_dev_run(fs, PN_K_OCC_FINISH, fs->width * fs->height)) != PN_OK ||
        (st = pn_dev_to_host(fs, fs->counters, (size_t)fs->height * sizeof(pn_row_counters))) != PN_OK)
        return st;
    ctx->stats.occtex.ns_lookup += pn_dev_timestamp(fs) - t1;
    for (y = 0; y < fs->height; y++) {
        lookups += ((const pn_row_counters *)fs->counters)[y].c.candidates;
        outside += ((const pn_row_counters *)fs->counters)[y].c.exact;
    }
    ctx->stats.occtex.lookups = lookups;
    ctx->stats.occtex.outside = outside;
    return PN_OK;
}

pn_status pn_occtex_frame(pn_frame_state *fs)
{
    pn_context *ctx = fs->ctx;
    pn_kparams *K = &fs->K;
    pn_kocc *o = &K->occ;
    pn_occ_pools s;
    uint32_t res = fs->res, npix = fs->width * fs->height, k, l;
    uint64_t t0 = pn_dev_timestamp(fs), t1, t2;
    float zmax = 0.0f;
    pn_status st;

    if ((st = pn_occ_begin(fs, &s, res)) != PN_OK) return st;
    pn_light_view(ctx, &K->light, res, &K->lview);
    pn_light_halves(&K->light, &K->lview_ha, &K->lview_hb);
    o->res = res;
    o->levels = pn_nb_levels(res);
    ctx->stats.occtex.map = res;
    ctx->stats.occtex.slices = o->slices;

    if ((st = pn_dev_run(fs, PN_K_OCC_INIT, npix)) != PN_OK) return st;
    if ((st = pn_dev_run(fs, PN_K_LVIEW_BOUNDS, fs->height)) != PN_OK ||
        (st = pn_dev_to_host(fs, s.box, (size_t)fs->height * 4u * PN_LVIEW_BOX)) != PN_OK)
        return st;
    if (!pn_occ_window(fs, &s, res, &zmax)) {
        /* No origin in front of the light: nothing to slice; every lit origin is one no
         * window holds, which the finish resolves exactly. */
        t1 = pn_dev_timestamp(fs);
        ctx->stats.occtex.ns_slice = t1 - t0;
        return pn_occ_finish(fs, t1);
    }

    /* Slicing. */
    if ((st = pn_dev_fill(fs, s.words, PN_OCC_WORDS, 0u)) != PN_OK ||
        (st = pn_raster_setup(fs, PN_K_LMAP_ROWS)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_OCC_BAND, (res + PN_RASTER_BAND - 1u) / PN_RASTER_BAND)) != PN_OK ||
        (st = pn_dev_to_host(fs, s.words, PN_OCC_WORDS * 4u)) != PN_OK)
        return st;
    t1 = pn_dev_timestamp(fs);
    ctx->stats.occtex.ns_slice = t1 - t0;
    ctx->stats.occtex.texels_set = s.words[PN_OCC_WORD_TEXELS];

    /* The depth map's occlusion (a lookup), while the filter pool holds the map. */
    if (!(o->flags & PN_OCC_FLAG_PAPER_FADE)) {
        o->slice = PN_OCC_SLICE_DEPTH;
        if ((st = pn_dev_run(fs, PN_K_OCC_LOOKUP, npix)) != PN_OK) return st;
        t2 = pn_dev_timestamp(fs);
        ctx->stats.occtex.ns_lookup += t2 - t1;
        t1 = t2;
    }

    /* Per slice: its filter, then its lookups. The deepest slice holds receivers only. */
    for (k = 0; k + 1u < o->slices; k++) {
        if (s.words[PN_OCC_WORD_SLICE0 + k] == 0u) continue; /* occlusion 0: no change */
        o->slice = k;
        o->live |= 1u << k;
        if (o->filter == PN_OCC_F_SAT) {
            if ((st = pn_dev_run(fs, PN_K_OCC_SAT_ROWS, res + 1u)) != PN_OK ||
                (st = pn_dev_run(fs, PN_K_OCC_SAT_COLS, (res + PN_OCC_SAT_COLS) / PN_OCC_SAT_COLS)) != PN_OK)
                return st;
        } else {
            uint32_t top = pn_occ_top_level(o, k, zmax);
            if ((st = pn_dev_run(fs, PN_K_OCC_LEVEL0, res * res)) != PN_OK) return st;
            for (l = 1; l <= top; l++) {
                o->level = l;
                if ((st = pn_dev_run(fs, o->filter == PN_OCC_F_MIPMAP ? PN_K_OCC_MIP : PN_K_OCC_NBUF,
                                     o->filter == PN_OCC_F_MIPMAP ? pn_occ_mip_dim(res, l) : res)) != PN_OK)
                    return st;
            }
        }
        t2 = pn_dev_timestamp(fs);
        ctx->stats.occtex.ns_filter += t2 - t1;
        if ((st = pn_dev_run(fs, PN_K_OCC_LOOKUP, npix)) != PN_OK) return st;
        t1 = pn_dev_timestamp(fs);
        ctx->stats.occtex.ns_lookup += t1 - t2;
    }
    return pn_occ_finish(fs, t1);
}

PN_ALGO_NO_SCENE(occtex)
#else
PN_ALGO_STUBS(OCCTEX, occtex)
#endif
