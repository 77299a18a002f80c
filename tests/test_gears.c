/* GEARS: byte-identical to the reference (same predicate, so any difference is a culling
 * bug), for area and point lights, every k, several grids; exact through tiling when the
 * pair pool is too small for one pass; PN_E_POOL_EXHAUSTED when one cell cannot fit.
 *
 * usage: test_gears            the built-in scenes and spot.glb, small images
 *        test_gears --full     every scene in ../shared/scenes at 256x256 (the dragon at
 *                              512x512), k = 8, 16, 32: the acceptance run */
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"
#include "pn_test_render.h"

static uint32_t count_diff(const float *a, const float *b, size_t n, const char *what)
{
    size_t i;
    uint32_t d = 0;
    for (i = 0; i < n; i++)
        if (memcmp(a + i, b + i, sizeof(float)) != 0) {
            if (d < 3) fprintf(stderr, "%s: pixel %zu reference %.9g gears %.9g\n", what, i, a[i], b[i]);
            d++;
        }
    return d;
}

/* Reference vs GEARS on one scene for each k, with the area light and a point light. */
static void exact_scene(const char *src, int builtin, uint32_t w, uint32_t hh, const uint32_t *ks, int nk,
                        const uint32_t *grids, int ngrid)
{
    pn_setup s;
    pn_host h;
    char err[256];
    float *ref, *gears;
    size_t n = (size_t)w * hh;
    int q, g;
    REQUIRE(pn_setup_load(&s, src, builtin, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_host_open(&h, s.mesh.triangle_count, w, hh, 0, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    ref = (float *)malloc(n * sizeof(float));
    gears = (float *)malloc(n * sizeof(float));
    REQUIRE(ref && gears);
    for (q = 0; q <= nk; q++) {
        pn_light light = s.light;
        uint32_t k = q < nk ? ks[q] : 8u;
        char what[256];
        pn_stats st;
        if (q == nk) { /* point light at the centre: hard shadows through the cube of grids */
            memset(light.u, 0, sizeof(light.u));
            memset(light.v, 0, sizeof(light.v));
        }
        REQUIRE(render_vis(&h, &s, &light, PN_ALGO_REFERENCE, w, hh, k, 128, ref, NULL) == 0);
        for (g = 0; g < ngrid; g++) {
            REQUIRE(render_vis(&h, &s, &light, PN_ALGO_GEARS, w, hh, k, grids[g], gears, &st) == 0);
            snprintf(what, sizeof(what), "%s %ux%u %s k=%u grid=%u", s.name, w, hh, q == nk ? "point" : "area", k, grids[g]);
            {
                uint32_t d = count_diff(ref, gears, n, what);
                fprintf(stderr, "%s: %u differing pixels; pairs %llu, assignments %llu, necessary share %.1f%%\n", what, d,
                        (unsigned long long)st.gears.pairs, (unsigned long long)st.gears.assignments,
                        st.gears.assignments ? 100.0 * (double)st.shadow_blocking / (double)st.gears.assignments : 0.0);
                CHECK_MSG(d == 0u, "%s", what);
                CHECK(st.gears.faces == (q == nk ? 6u : 1u));
                /* Boxes tested (shadow_nodes): a pixel whose cell holds n entries meets at
                 * most n/64 + 2 superchunks and n/8 + 2 chunks, and some when n > 0. */
                CHECK_MSG(st.shadow_nodes <= st.gears.assignments * 9u / 64u + 4u * (uint64_t)st.lit_pixels,
                          "%s: %llu boxes", what, (unsigned long long)st.shadow_nodes);
                CHECK_MSG(st.gears.assignments == 0u || st.shadow_nodes > 0u, "%s: no box tested", what);
            }
        }
    }
    free(ref);
    free(gears);
    pn_host_close(&h);
    pn_setup_free(&s);
}

static void test_exact_builtins(void)
{
    static const uint32_t ks[3] = {4, 16, 32};
    static const uint32_t grids[3] = {1, 37, 128};
    const char *const *names = pn_builtin_scene_names();
    for (; *names; names++) exact_scene(*names, 1, 72, 64, ks, 3, grids, 3);
    exact_scene(PN_SCENES_DIR "/spot.glb", 0, 96, 96, ks, 3, grids + 1, 2);
}

/* A pair pool far too small for one pass: many tiles (rows split into runs of cells),
 * the same bytes. */
static void test_tiling(void)
{
    pn_setup s;
    pn_host h, small;
    pn_limits lim;
    char err[256];
    float *a, *b;
    pn_stats st;
    const uint32_t w = 64, hh = 64;
    REQUIRE(pn_setup_load(&s, "spheres", 1, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_host_open(&h, s.mesh.triangle_count, w, hh, 0, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    a = (float *)malloc(w * hh * sizeof(float));
    b = (float *)malloc(w * hh * sizeof(float));
    REQUIRE(a && b);
    REQUIRE(render_vis(&h, &s, &s.light, PN_ALGO_GEARS, w, hh, 16, 64, a, &st) == 0);
    CHECK(st.gears.tiles == 1u);
    CHECK(st.gears.grid == 64u);
    {
        /* grid 0: the default (PN_GEARS_GRID_DEFAULT, at most the context's limit, here
         * PN_GEARS_GRID_MAX), named in the stats; the same bytes as any grid */
        pn_stats s0;
        REQUIRE(render_vis(&h, &s, &s.light, PN_ALGO_GEARS, w, hh, 16, 0, b, &s0) == 0);
        CHECK(s0.gears.grid == (PN_GEARS_GRID_MAX < PN_GEARS_GRID_DEFAULT ? PN_GEARS_GRID_MAX : PN_GEARS_GRID_DEFAULT));
        CHECK(count_diff(a, b, (size_t)w * hh, "default grid") == 0u);
    }
    fprintf(stderr, "spheres: %llu pairs in one pass; most triangles in a cell %u\n", (unsigned long long)st.gears.pairs,
            st.gears.max_tris_per_cell);
    /* Pool: a fifth of the frame's pairs, but at least the largest cell. */
    memset(&small, 0, sizeof(small));
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = s.mesh.triangle_count;
    lim.max_width = w;
    lim.max_height = hh;
    lim.gears_pairs = (uint32_t)(st.gears.pairs / 5u);
    {
        size_t bytes;
        pn_context *ctx;
        void *mem;
        REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
        mem = malloc(bytes);
        REQUIRE(mem && pn_init(&ctx, mem, bytes, &lim) == PN_OK);
        small.ctx = ctx;
        small.memory = mem;
        REQUIRE(pn_scene_set(ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
        {
            pn_stats st2;
            REQUIRE(render_vis(&small, &s, &s.light, PN_ALGO_GEARS, w, hh, 16, 64, b, &st2) == 0);
            fprintf(stderr, "pool %u pairs: %u tiles, %llu pairs, high water %u\n", lim.gears_pairs, st2.gears.tiles,
                    (unsigned long long)st2.gears.pairs, st2.gears.pairs_high_water);
            CHECK(st2.gears.tiles >= 5u);
            CHECK(st2.gears.pairs == st.gears.pairs);
            CHECK(st2.gears.pairs_high_water <= lim.gears_pairs);
            CHECK(count_diff(a, b, (size_t)w * hh, "tiled") == 0u);
        }
        free(mem);
    }
    /* A pool smaller than the largest cell: no silent drop, a named error. */
    lim.gears_pairs = st.gears.max_tris_per_cell - 1u;
    {
        size_t bytes;
        pn_context *ctx;
        void *mem;
        pn_frame_options opt;
        pn_frame fr;
        REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
        mem = malloc(bytes);
        REQUIRE(mem && pn_init(&ctx, mem, bytes, &lim) == PN_OK);
        REQUIRE(pn_scene_set(ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
        pn_frame_options_default(&opt);
        opt.width = w;
        opt.height = hh;
        opt.algo = PN_ALGO_GEARS;
        opt.gears.grid = 64;
        opt.eps = s.eps;
        CHECK(pn_render(ctx, &s.camera, &s.light, &opt, &fr) == PN_E_POOL_EXHAUSTED);
        fprintf(stderr, "message: %s\n", pn_last_error(ctx));
        CHECK(strstr(pn_last_error(ctx), "gears pairs") != NULL);
        {
            char need[32];
            snprintf(need, sizeof(need), "needs %u", st.gears.max_tris_per_cell);
            CHECK(strstr(pn_last_error(ctx), need) != NULL);
        }
        free(mem);
    }
    free(a);
    free(b);
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* The dragon with a pair pool too small for one pass at 512x512: exact through tiling. */
static void test_dragon_tiled(void)
{
    pn_setup s;
    pn_host h;
    pn_limits lim;
    char err[256];
    float *ref, *g;
    pn_stats st;
    size_t bytes, n = 512u * 512u;
    void *mem;
    pn_context *ctx;
    REQUIRE(pn_setup_load(&s, PN_SCENES_DIR "/stanford_dragon.glb", 0, 1, err, sizeof(err)) == 0);
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = s.mesh.triangle_count;
    lim.max_width = 512;
    lim.max_height = 512;
    lim.gears_pairs = 1u << 20; /* the frame needs several times this */
    REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
    mem = malloc(bytes);
    REQUIRE(mem && pn_init(&ctx, mem, bytes, &lim) == PN_OK);
    memset(&h, 0, sizeof(h));
    h.ctx = ctx;
    h.threads.count = pn_threads_cores();
    pn_set_parallel_for(ctx, pn_threads_parallel_for, &h.threads);
    REQUIRE(pn_scene_set(ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    ref = (float *)malloc(n * sizeof(float));
    g = (float *)malloc(n * sizeof(float));
    REQUIRE(ref && g);
    REQUIRE(render_vis(&h, &s, &s.light, PN_ALGO_GEARS, 512, 512, 16, 128, g, &st) == 0);
    fprintf(stderr, "dragon 512x512 k=16, pool 2^20 pairs: %u tiles, %llu pairs\n", st.gears.tiles,
            (unsigned long long)st.gears.pairs);
    CHECK(st.gears.tiles > 1u);
    REQUIRE(render_vis(&h, &s, &s.light, PN_ALGO_REFERENCE, 512, 512, 16, 128, ref, NULL) == 0);
    CHECK(count_diff(ref, g, n, "dragon tiled") == 0u);
    free(ref);
    free(g);
    free(mem);
    pn_setup_free(&s);
}

static void test_full(void)
{
    static const uint32_t ks[3] = {8, 16, 32};
    static const uint32_t grid[1] = {128};
    static const char *files[] = {"spot", "stanford_bunny", "chess_set", "happy_buddha_100k", "cad_infineon_easypim2b"};
    const char *const *names = pn_builtin_scene_names();
    char path[512];
    size_t i;
    for (; *names; names++) exact_scene(*names, 1, 256, 256, ks, 3, grid, 1);
    for (i = 0; i < sizeof(files) / sizeof(files[0]); i++) {
        snprintf(path, sizeof(path), "%s/%s.glb", PN_SCENES_DIR, files[i]);
        exact_scene(path, 0, 256, 256, ks, 3, grid, 1);
    }
    exact_scene(PN_SCENES_DIR "/stanford_dragon.glb", 0, 512, 512, ks, 3, grid, 1);
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--full") == 0) {
        RUN(test_full);
    } else {
        RUN(test_exact_builtins);
        RUN(test_tiling);
        if (argc > 1 && strcmp(argv[1], "--dragon") == 0) RUN(test_dragon_tiled);
    }
    return pn_test_summary();
}
