/* fuzz_culls.c - the steps of the algorithms that are meant to lose nothing (issue 53) give
 * the same bytes as the same frame without them, on random small scenes.
 *
 * Input: fuzz_frame.h's. Its algorithm byte picks the step (modulo the steps below), its
 * flags bits 3-4 the culled frame's wedge pair pool (default, 64, 12, 3: bands of tiles,
 * full tiles); everything else is the frame's.
 *
 * - wedges: the binning of wedges to screen tiles (their reach and the tiles' light-space
 *   boxes), the superblock, object and block box tests of a pixel and the clear tiles'
 *   skipped centre rays, against PN_WG_NO_CULL (every silhouette listed in every tile, no
 *   box test passing, every centre ray walked): the same status and, on PN_OK, the same
 *   visibility and RGBA; the no-cull frame, on the default pools, never fails, and lists
 *   at least the culled frame's pairs.
 * - mcsm: the Monte Carlo shadow maps' penumbra classification, early-outs and ray
 *   shortening, against PN_MC_NO_CLASSIFY, with the one layer and hierarchical search in
 *   which every one of them is exact for the layers' model (test_mcsm), blur off: the same
 *   status and, on PN_OK, the same visibility and RGBA, with no more rays traced.
 * - reference, gears: the exact algorithms' culls, the reference's walk culled by each
 *   pixel's light frustum and by the samples still open, GEARS' cells and their chunk boxes,
 *   against per-sample ray tracing (one ray per sample through the BVH, no pixel-wide
 *   cull): the same status and bytes (the exact algorithms agree bit for bit). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_check.h"
#include "fuzz_frame.h"
#include "penumbra/penumbra.h"

/* One context per wedge pair pool (the first: every pool at its default), made on first use.
 * The first's arena starts as zeros, the others' as ones: a frame that reads a word no pass
 * of its own wrote (the previous frame's, or nothing's) differs between the culled frame of
 * a small pool and the frame without the culls (crash-wedges-point-light-stale-cast: a point
 * light's wedges read their triangles' PN_WG_LIT_FRONT, which only an area light's frame
 * wrote). */
static pn_context *get_ctx(uint32_t pool_sel)
{
    static pn_context *ctx[4];
    static void *mem[4];
    static const uint32_t pools[4] = {0u, 64u, 12u, 3u};
    if (!ctx[pool_sel]) {
        pn_limits lim = {FUZZ_MAX_T, FUZZ_MAX_W, FUZZ_MAX_H, 0u, 64u, 64u, 64u, 64u, pools[pool_sel], 0u, 0u, 0u, 0u};
        size_t bytes;
        FUZZ_CHECK(pn_arena_size(&lim, &bytes) == PN_OK, "arena size");
        mem[pool_sel] = malloc(bytes);
        FUZZ_CHECK(mem[pool_sel] != NULL, "malloc");
        memset(mem[pool_sel], pool_sel ? 0xFF : 0x00, bytes);
        FUZZ_CHECK(pn_init(&ctx[pool_sel], mem[pool_sel], bytes, &lim) == PN_OK, "pn_init");
    }
    return ctx[pool_sel];
}

/* A step: the algorithm and options of the frame with it (on) and of the frame without it
 * (off). */
static void same(pn_frame_options *o) { (void)o; }
static void wedges_on(pn_frame_options *o) { o->wedges.flags = 0u; }
static void wedges_off(pn_frame_options *o) { o->wedges.flags = PN_WG_NO_CULL; }
static void mcsm_on(pn_frame_options *o)
{
    o->mcsm.layers = 1u;
    o->mcsm.search = PN_MC_SEARCH_HIER;
    o->mcsm.blur = PN_MC_BLUR_OFF;
    o->mcsm.flags &= PN_MC_NO_BIAS;
}
static void mcsm_off(pn_frame_options *o)
{
    mcsm_on(o);
    o->mcsm.flags |= PN_MC_NO_CLASSIFY;
}

static const struct step {
    const char *name;
    pn_algo algo, algo_off;
    void (*on)(pn_frame_options *);
    void (*off)(pn_frame_options *);
} steps[] = {
    {"the wedges' binning and box culls", PN_ALGO_WEDGES, PN_ALGO_WEDGES, wedges_on, wedges_off},
    {"MCSM's classification and early-outs", PN_ALGO_MCSM, PN_ALGO_MCSM, mcsm_on, mcsm_off},
    {"the reference's frustum and footprint culls", PN_ALGO_REFERENCE, PN_ALGO_RAYTRACE, same, same},
    {"GEARS' cells", PN_ALGO_GEARS, PN_ALGO_RAYTRACE, same, same},
};
#define NSTEPS (sizeof(steps) / sizeof(steps[0]))

/* The culled frame's bytes. */
static float k_vis[FUZZ_MAX_W * FUZZ_MAX_H];
static uint8_t k_rgba[FUZZ_MAX_W * FUZZ_MAX_H * 4];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fuzz_frame ff;
    const struct step *sp;
    pn_context *ca, *cb = get_ctx(0u);
    pn_frame_options oa, ob;
    pn_frame fa, fb;
    pn_stats sa_st, sb_st;
    pn_status sa, sb;
    char msg[256];
    size_t n;

    fuzz_frame_decode(data, size, &ff);
    sp = &steps[ff.algo % NSTEPS];
    ca = get_ctx((ff.flags >> 3) & 3u);
    FUZZ_CHECK(fuzz_frame_scene(ca, &ff) == PN_OK, "the scene: %s", pn_last_error(ca));
    if (cb != ca) FUZZ_CHECK(fuzz_frame_scene(cb, &ff) == PN_OK, "the scene: %s", pn_last_error(cb));
    oa = ff.opt;
    oa.algo = sp->algo;
    ob = oa;
    ob.algo = sp->algo_off;
    sp->on(&oa);
    sp->off(&ob);
    n = (size_t)oa.width * oa.height;

    sa = pn_render(ca, &ff.cam, &ff.light, &oa, &fa);
    memcpy(msg, pn_last_error(ca), sizeof(msg));
    if (sa == PN_OK) {
        memcpy(k_vis, fa.visibility, n * 4u);
        memcpy(k_rgba, fa.rgba, n * 4u);
        pn_get_stats(ca, &sa_st);
    }
    sb = pn_render(cb, &ff.cam, &ff.light, &ob, &fb);
    if (getenv("PN_FUZZ_VERBOSE"))
        fprintf(stderr, "%s, %ux%u k=%u %s light, %u triangles: %s / %s\n", sp->name, oa.width, oa.height, oa.k,
                (ff.flags & 1u) ? "point" : "area", ff.nt, pn_status_str(sa), pn_status_str(sb));
    /* The culled frame's small pair pool may leave tiles full (their pixels the
     * reference's, not the no-cull frame's): nothing to compare. It never fails. */
    if (sa == PN_OK && ca != cb && sa_st.wedges.full_tiles > 0u) return 0;
    FUZZ_CHECK(sa == sb, "%s: with it %s (%s), without %s (%s)", sp->name, pn_status_str(sa), msg, pn_status_str(sb),
               pn_last_error(cb));
    if (sa != PN_OK) {
        FUZZ_CHECK(sa == PN_E_CAMERA, "%s: unexpected %s: %s", sp->name, pn_status_str(sa), msg);
        return 0;
    }
    pn_get_stats(cb, &sb_st);
    if (getenv("PN_FUZZ_VERBOSE")) {
        size_t i, d = 0;
        for (i = 0; i < n; i++)
            if (memcmp(&k_vis[i], &fb.visibility[i], 4u) != 0 && d++ < 8u)
                fprintf(stderr, "  pixel %zu (%zu, %zu): %.9g with it, %.9g without\n", i, i % oa.width, i / oa.width,
                        (double)k_vis[i], (double)fb.visibility[i]);
        fprintf(stderr, "  %zu of %zu pixels differ\n", d, n);
        if (sp->algo == PN_ALGO_MCSM)
            fprintf(stderr, "  searches capped %u with it, %u without\n", sa_st.mcsm.capped, sb_st.mcsm.capped);
    }
    FUZZ_CHECK(memcmp(k_vis, fb.visibility, n * 4u) == 0, "%s: visibility differs without it", sp->name);
    FUZZ_CHECK(memcmp(k_rgba, fb.rgba, n * 4u) == 0, "%s: rgba differs without it", sp->name);
    if (sp->algo == PN_ALGO_WEDGES)
        FUZZ_CHECK(sb_st.wedges.pairs >= sa_st.wedges.pairs, "%s: %llu pairs without the culls, %llu with", sp->name,
                   (unsigned long long)sb_st.wedges.pairs, (unsigned long long)sa_st.wedges.pairs);
    else if (sp->algo == PN_ALGO_MCSM)
        FUZZ_CHECK(sb_st.mcsm.rays >= sa_st.mcsm.rays, "%s: %llu rays without it, %llu with", sp->name,
                   (unsigned long long)sb_st.mcsm.rays, (unsigned long long)sa_st.mcsm.rays);
    return 0;
}
