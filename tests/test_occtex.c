/* PN_ALGO_OCCTEX (occlusion textures): what it promises and what it is built from.
 *
 * 1. The paper's exact case (§3.1): `square`, one planar occluder parallel to the light,
 *    is its slice's bottom plane; with the summed-area table (the exact box integral) and
 *    the leak fix off (the defaults), its shadow matches the reference (k = 32) to the texture's
 *    quantization: mean absolute error below 1/255, no pixel off by more than two of the
 *    reference's sample steps (1/32 each) plus nothing; the N-buffer (approximate sizes
 *    between levels) is less accurate there than the table, the mipmap less than both;
 *    the leak fix doubles the occluder's bits and only darkens.
 * 2. Combinations: per pixel, clamped sum <= product <= max visibility (1 - sum I <=
 *    prod (1 - I) <= min (1 - I) for I in [0, 1]), up to float rounding, with the
 *    inequalities strict somewhere (spheres: overlapping penumbrae).
 * 3. Determinism: the same bytes from 1 and 2 threads and from two runs.
 * 4. Options and pools: occtex.slices, .map, .filter, .combine, .flags outside
 *    their ranges are PN_E_INVALID_ARG; a context whose occ_map_max is 64 has a smaller
 *    arena and renders at that size; the stats hold the slices, map, bits and lookups
 *    (= shadow_candidates), and with a clock the stage times lie inside the shadow pass.
 * 5. Origins no window holds take the reference's bytes at k = 4 (test_outside_exact).
 * The error against the reference on every scene is the benchmark's (RESULTS.md). */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"
#include "pn_test_render.h"

#define W 128u
#define H 96u

typedef struct frame {
    float vis[W * H];
    uint8_t rgba[W * H * 4u];
    pn_stats st;
} frame;

static frame g_a, g_b, g_c;

static int render(pn_host *h, const pn_setup *s, const pn_light *light, pn_algo algo, uint32_t k, uint32_t filter,
                  uint32_t combine, uint32_t flags, frame *out)
{
    pn_frame_options opt;
    pn_frame_options_default(&opt);
    opt.width = W;
    opt.height = H;
    opt.k = k;
    opt.algo = algo;
    opt.occtex.filter = filter;
    opt.occtex.combine = combine;
    opt.occtex.flags = flags;
    return render_opt(h, s, light, &opt, out->vis, out->rgba, &out->st);
}

static int open_scene(const char *name, pn_setup *s, pn_host *h, int threads)
{
    char err[256];
    if (pn_setup_load(s, name, 1, -1, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading %s: %s", name, err);
        return 0;
    }
    if (pn_host_open(h, s->mesh.triangle_count, W, H, threads, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "context: %s", err);
        pn_setup_free(s);
        return 0;
    }
    if (pn_scene_set(h->ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) !=
        PN_OK) {
        CHECK_MSG(0, "%s: %s", name, pn_last_error(h->ctx));
        pn_host_close(h);
        pn_setup_free(s);
        return 0;
    }
    return 1;
}

/* The frame's error against ref: mean and largest |error|, RMSE, and the fraction of pixels
 * more than 0.25 brighter. */
typedef struct frame_error {
    double mean, max, rmse, brighter;
} frame_error;

static frame_error error_of(const frame *ref, const frame *f)
{
    size_t i, hi = 0;
    double sum = 0.0, se = 0.0;
    frame_error e = {0.0, 0.0, 0.0, 0.0};
    for (i = 0; i < W * H; i++) {
        double d = (double)f->vis[i] - (double)ref->vis[i], a = fabs(d);
        sum += a;
        se += d * d;
        hi += d > 0.25;
        if (a > e.max) e.max = a;
    }
    e.mean = sum / (double)(W * H);
    e.rmse = sqrt(se / (double)(W * H));
    e.brighter = (double)hi / (double)(W * H);
    return e;
}

static void test_exact_case(void)
{
    pn_setup s;
    pn_host h;
    frame_error sat, nb, mip;
    if (!open_scene("square", &s, &h, 2)) return;
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_REFERENCE, 32, 0, 0, 0, &g_a) == 0);
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 32, PN_OCC_FILTER_SAT, 0, 0, &g_b) == 0);
    sat = error_of(&g_a, &g_b);
    fprintf(stderr, "square, summed-area table: mean |error| %.5f, max %.4f\n", sat.mean, sat.max);
    CHECK_MSG(sat.mean < 1.0 / 255.0, "mean |error| %.5f", sat.mean);
    CHECK_MSG(sat.max <= 2.0 / 32.0, "max |error| %.4f", sat.max);
    /* The slicing did its work: the occluder's bits and lookups are there. */
    CHECK(g_b.st.occtex.texels_set > 0u && g_b.st.occtex.lookups > 0u && g_b.st.occtex.lookups == g_b.st.shadow_candidates);
    CHECK(g_b.st.occtex.slices == 16u && g_b.st.occtex.map == 512u);
    CHECK(g_b.st.occtex.outside == 0u); /* every origin well inside the light's frustum */
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 32, PN_OCC_FILTER_NBUFFER, 0, 0, &g_c) == 0);
    nb = error_of(&g_a, &g_c);
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 32, PN_OCC_FILTER_MIPMAP, 0, 0, &g_c) == 0);
    mip = error_of(&g_a, &g_c);
    {
        /* The leak fix marks each fragment's next slice too: the square's one slice is
         * doubled (its bits exactly), and the ground under it gets darker, not lighter. */
        pn_stats plain = g_c.st;
        size_t i, lighter = 0;
        REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 32, PN_OCC_FILTER_MIPMAP, 0, PN_OCC_LEAK_FIX, &g_b) == 0);
        CHECK_MSG(g_b.st.occtex.texels_set == 2u * plain.occtex.texels_set, "leak fix: %llu bits, without %llu",
                  (unsigned long long)g_b.st.occtex.texels_set, (unsigned long long)plain.occtex.texels_set);
        for (i = 0; i < W * H; i++) lighter += g_b.vis[i] > g_c.vis[i];
        CHECK_MSG(lighter == 0u, "%zu pixels lighter with the leak fix", lighter);
    }
    fprintf(stderr, "square, N-buffer: mean |error| %.5f, max %.4f; mipmap: %.5f, %.4f\n", nb.mean, nb.max, mip.mean,
            mip.max);
    CHECK_MSG(sat.mean < nb.mean && nb.mean < mip.mean, "mean |error| SAT %.5f, N-buffer %.5f, mipmap %.5f", sat.mean,
              nb.mean, mip.mean);
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* 5. The depth map (the default) against the paper's fade alone (PN_OCC_PAPER_FADE): the
 *    same slices (bits and lookups), and in `room` - every surface an occluder and a
 *    receiver, contact shadows under chairs, shelves and the table - a smaller error and
 *    fewer pixels lit where the reference is dark (the measured all-scene table is
 *    RESULTS.md's). */
static void test_depth_map(void)
{
    pn_setup s;
    pn_host h;
    frame_error map, fade;
    if (!open_scene("room", &s, &h, 2)) return;
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_REFERENCE, 16, 0, 0, 0, &g_a) == 0);
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 16, 0, 0, 0, &g_b) == 0);
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 16, 0, 0, PN_OCC_PAPER_FADE, &g_c) == 0);
    map = error_of(&g_a, &g_b);
    fade = error_of(&g_a, &g_c);
    fprintf(stderr, "room: RMSE %.4f with the depth map, %.4f with the fade alone; brighter by 0.25: %.2f%% and %.2f%%\n",
            map.rmse, fade.rmse, 100.0 * map.brighter, 100.0 * fade.brighter);
    CHECK(g_b.st.occtex.texels_set == g_c.st.occtex.texels_set && g_b.st.occtex.lookups == g_c.st.occtex.lookups);
    /* The walls' tops, beside the ceiling's light, lie beyond any slicing window: counted. */
    CHECK_MSG(g_b.st.occtex.outside > 0u && g_b.st.occtex.outside < g_b.st.lit_pixels, "outside %u of %u lit",
              g_b.st.occtex.outside, (unsigned)g_b.st.lit_pixels);
    CHECK_MSG(map.rmse < 0.75 * fade.rmse, "RMSE %.4f vs %.4f", map.rmse, fade.rmse);
    CHECK_MSG(map.brighter < 0.5 * fade.brighter, "brighter %.4f vs %.4f", map.brighter, fade.brighter);
    pn_host_close(&h);
    pn_setup_free(&s);
}

static void test_combinations(void)
{
    pn_setup s;
    pn_host h;
    size_t i, below = 0, above = 0, bad = 0;
    if (!open_scene("spheres", &s, &h, 2)) return;
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 16, 0, PN_OCC_COMBINE_SUM, 0, &g_a) == 0);
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 16, 0, PN_OCC_COMBINE_PRODUCT, 0, &g_b) == 0);
    REQUIRE(render(&h, &s, &s.light, PN_ALGO_OCCTEX, 16, 0, PN_OCC_COMBINE_MAX, 0, &g_c) == 0);
    for (i = 0; i < W * H; i++) {
        /* Rounding: each of at most 15 steps rounds once (relative 2^-24). */
        if (g_a.vis[i] > g_b.vis[i] + 1e-6f || g_b.vis[i] > g_c.vis[i] + 1e-6f) bad++;
        below += g_a.vis[i] < g_b.vis[i] - 0.01f;
        above += g_b.vis[i] < g_c.vis[i] - 0.01f;
    }
    fprintf(stderr, "spheres: sum < product - 0.01 at %zu pixels, product < max - 0.01 at %zu\n", below, above);
    CHECK_MSG(bad == 0u, "%zu pixels break sum <= product <= max", bad);
    CHECK(below > 100u && above > 100u);
    pn_host_close(&h);
    pn_setup_free(&s);
}

static void test_determinism(void)
{
    pn_setup s;
    pn_host h1, h2;
    pn_light point;
    int li;
    if (!open_scene("room", &s, &h1, 1)) return;
    if (!open_scene("room", &s, &h2, 2)) {
        pn_host_close(&h1);
        return;
    }
    memset(&point, 0, sizeof(point));
    memcpy(point.center, s.light.center, sizeof(point.center));
    for (li = 0; li < 2; li++) {
        const pn_light *L = li ? &point : &s.light;
        REQUIRE(render(&h1, &s, L, PN_ALGO_OCCTEX, 16, 0, 0, 0, &g_a) == 0);
        REQUIRE(render(&h2, &s, L, PN_ALGO_OCCTEX, 16, 0, 0, 0, &g_b) == 0);
        REQUIRE(render(&h2, &s, L, PN_ALGO_OCCTEX, 16, 0, 0, 0, &g_c) == 0);
        CHECK_MSG(memcmp(g_a.vis, g_b.vis, sizeof(g_a.vis)) == 0 && memcmp(g_a.rgba, g_b.rgba, sizeof(g_a.rgba)) == 0,
                  "room %s light: 1 and 2 threads differ", li ? "point" : "area");
        CHECK(memcmp(g_b.vis, g_c.vis, sizeof(g_b.vis)) == 0);
        CHECK(g_a.st.occtex.texels_set == g_b.st.occtex.texels_set && g_a.st.occtex.lookups == g_b.st.occtex.lookups);
    }
    pn_host_close(&h1);
    pn_host_close(&h2);
    pn_setup_free(&s);
}

static void test_options(void)
{
    pn_setup s;
    pn_host h;
    pn_limits lim = {64, 32, 32, 1000, 16, 8, 64, 8, 0, 0, 0, 0, 0}; /* the others small: the frame region holds the largest */
    size_t bytes;
    void *mem;
    pn_context *ctx;
    pn_frame_options opt;
    pn_frame fr;
    pn_stats st;
    if (!open_scene("square", &s, &h, 1)) return;
    pn_frame_options_default(&opt);
    opt.width = opt.height = 32;
    opt.algo = PN_ALGO_OCCTEX;
    opt.occtex.slices = 1;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.occtex.slices = 17;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.occtex.slices = 0;
    opt.occtex.map = 7;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.occtex.map = PN_OCCTEX_MAP_MAX + 1u;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.occtex.map = 0;
    opt.occtex.filter = 4;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.occtex.filter = 0;
    opt.occtex.combine = 4;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.occtex.combine = 0;
    opt.occtex.flags = 4;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    CHECK(strstr(pn_last_error(h.ctx), "occtex.flags") != NULL);
    opt.occtex.flags = 0;
    opt.occtex.slices = 2; /* one occluder slice and the receivers' */
    CHECK_MSG(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_OK, "%s", pn_last_error(h.ctx));
    CHECK(pn_get_stats(h.ctx, &st) == PN_OK && st.occtex.slices == 2u && st.occtex.texels_set > 0u);
    opt.occtex.slices = 0;
    pn_host_close(&h);

    /* A small map limit: a smaller arena, and frames at that map size. */
    REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
    {
        pn_limits big = lim;
        size_t big_bytes;
        big.occ_map_max = 0;
        REQUIRE(pn_arena_size(&big, &big_bytes) == PN_OK);
        CHECK(bytes < big_bytes);
        big.occ_map_max = PN_OCCTEX_MAP_MAX + 1u;
        CHECK(pn_arena_size(&big, &big_bytes) == PN_E_LIMIT);
        big.occ_map_max = 7u;
        CHECK(pn_arena_size(&big, &big_bytes) == PN_E_LIMIT);
    }
    mem = malloc(bytes);
    REQUIRE(mem != NULL);
    REQUIRE(pn_init(&ctx, mem, bytes, &lim) == PN_OK);
    REQUIRE(pn_scene_set(ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    opt.occtex.map = 65;
    CHECK(pn_render(ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.occtex.map = 0;
    {
        /* Stage timings: none without a clock; with one, inside the shadow pass. */
        static const size_t off[3] = {offsetof(pn_stats, occtex.ns_slice), offsetof(pn_stats, occtex.ns_filter),
                                      offsetof(pn_stats, occtex.ns_lookup)};
        check_stage_times(ctx, &s.camera, &s.light, &opt, off, &st);
    }
    CHECK(st.occtex.map == 64u);
    free(mem);
    pn_setup_free(&s);
}

/* 5. Origins no window holds: the reference's bytes at k = 4 (pn_test_check_outside); a
 *    frame that left them to the slices (as before) lit the block's penumbra on the wall. */
static void test_outside_exact(void)
{
    pn_frame_options o;
    pn_frame_options_default(&o);
    o.algo = PN_ALGO_OCCTEX;
    pn_test_check_outside(&o);
}

int main(void)
{
    if (!(pn_build_info() & PN_BUILD_OCCTEX)) {
        fprintf(stderr, "PN_ENABLE_OCCTEX is 0 in this build\n");
        return 1;
    }
    RUN(test_options);
    RUN(test_exact_case);
    RUN(test_combinations);
    RUN(test_determinism);
    RUN(test_depth_map);
    RUN(test_outside_exact);
    return pn_test_summary();
}
