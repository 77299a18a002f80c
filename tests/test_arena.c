/* Arena: the size query equals what init carves, one byte less fails without writing,
 * nothing is written past the block while rendering, PN_ARENA_BYTES_MAX bounds the query,
 * any alignment works. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_test.h"
#include "pn_test_scene.h"

#define GUARD 4096u

static int all_bytes(const uint8_t *p, size_t n, uint8_t v)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (p[i] != v) return 0;
    return 1;
}

/* Limits (t, w, h), every other field 0. */
static pn_limits lim3(uint32_t t, uint32_t w, uint32_t h)
{
    pn_limits l;
    memset(&l, 0, sizeof(l));
    l.max_triangles = t;
    l.max_width = w;
    l.max_height = h;
    return l;
}

static void test_size_equals_carve(void)
{
    pn_limits lims[4];
    int i;
    lims[0] = lim3(1, 1, 1);
    lims[1] = lim3(100, 64, 48);
    lims[1].gears_pairs = 1000;
    lims[1].gears_grid_max = 16;
    lims[2] = lim3(1u << 20, 512, 512);
    lims[3] = lim3(PN_MAX_TRIANGLES, PN_MAX_WIDTH, PN_MAX_HEIGHT);
    for (i = 0; i < 4; i++) {
        size_t bytes = 0;
        REQUIRE(pn_arena_size(&lims[i], &bytes) == PN_OK);
        CHECK_MSG(bytes <= PN_ARENA_BYTES_MAX(lims[i].max_triangles, lims[i].max_width, lims[i].max_height),
                  "limits %d: size %zu > PN_ARENA_BYTES_MAX", i, bytes);
        if (i < 3) {
            uint8_t *mem = (uint8_t *)malloc(bytes);
            pn_context *ctx = NULL;
            pn_stats st;
            REQUIRE(mem != NULL);
            CHECK(pn_init(&ctx, mem, bytes, &lims[i]) == PN_OK);
            CHECK(pn_get_stats(ctx, &st) == PN_OK);
            /* The query is the carve plus the alignment allowance, exactly. */
            CHECK_MSG(st.arena_carved + PN_ARENA_ALIGN - 1u == bytes, "carved %zu, size %zu", st.arena_carved, bytes);
            CHECK(st.arena_bytes == bytes);
            CHECK(st.arena_persistent < st.arena_carved);
            free(mem);
        }
    }
}

/* PN_ARENA_BYTES_MAX takes the largest frame set where the carve does: over a grid of
 * limits it is at least pn_arena_size and at most 1.25 times it (issue 47). Every
 * single-algorithm build runs this too (ctest single_algorithm_<name>). */
static void test_bytes_max_tight(void)
{
    static const uint32_t tris[6] = {1, 100, 1000, 10000, 100000, 1000000};
    static const uint32_t dims[5][2] = {{1, 1}, {160, 120}, {320, 240}, {512, 512}, {1920, 1080}};
    double worst = 0.0;
    int i, j;
    for (i = 0; i < 6; i++)
        for (j = 0; j < 5; j++) {
            pn_limits l = lim3(tris[i], dims[j][0], dims[j][1]);
            size_t bytes = 0, bound = PN_ARENA_BYTES_MAX(tris[i], dims[j][0], dims[j][1]);
            double r;
            REQUIRE(pn_arena_size(&l, &bytes) == PN_OK);
            r = (double)bound / (double)bytes;
            if (r > worst) worst = r;
            CHECK_MSG(bytes <= bound && r <= 1.25, "%u triangles %ux%u: pn_arena_size %zu, PN_ARENA_BYTES_MAX %zu (%.3f)",
                      tris[i], dims[j][0], dims[j][1], bytes, bound, r);
        }
    fprintf(stderr, "PN_ARENA_BYTES_MAX / pn_arena_size: at most %.3f over 30 limits (build 0x%x)\n", worst,
            (unsigned)pn_build_info());
}

/* limits.algos: the frame region for those algorithms alone; a frame of another fails
 * PN_E_LIMIT naming the field; a flag outside the registry PN_E_LIMIT, one not compiled in
 * PN_E_UNSUPPORTED; 0 is every algorithm compiled in. */
static void test_algos(void)
{
    pn_limits l = lim3(64, 32, 32), all;
    size_t every = 0, bytes = 0;
    uint32_t a, built = pn_build_info() & ((1u << PN_ALGO_COUNT) - 1u);
    REQUIRE(pn_arena_size(&l, &every) == PN_OK);
    all = l;
    all.algos = built;
    CHECK(pn_arena_size(&all, &bytes) == PN_OK && bytes == every);
    l.algos = 1u << PN_ALGO_COUNT;
    CHECK(pn_arena_size(&l, &bytes) == PN_E_LIMIT);
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        l.algos = 1u << a;
        if (!(built & l.algos)) {
            CHECK(pn_arena_size(&l, &bytes) == PN_E_UNSUPPORTED);
            continue;
        }
        REQUIRE(pn_arena_size(&l, &bytes) == PN_OK);
        CHECK_MSG(bytes <= every, "%s alone: %zu > %zu", pn_algo_name((pn_algo)a), bytes, every);
        {
            /* It renders its own frames and refuses the others'. */
            static const float pos[12] = {-1, 1, -1, 1, 1, -1, 0, 1, 1, -4, 0, -4};
            static const uint32_t idx[6] = {0, 2, 1, 0, 1, 3};
            pn_camera cam = {{0, 1, 3}, {0, 0, 0}, {0, 1, 0}, 45.0f};
            pn_light light = {{0, 3, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}};
            pn_frame_options o;
            pn_frame fr;
            pn_context *ctx;
            uint32_t b;
            uint8_t *mem = (uint8_t *)malloc(bytes);
            REQUIRE(mem != NULL);
            REQUIRE(pn_init(&ctx, mem, bytes, &l) == PN_OK);
            REQUIRE(pn_scene_set(ctx, pos, 4, idx, 2) == PN_OK);
            pn_frame_options_default(&o);
            o.width = o.height = 32;
            o.k = 8;
            for (b = 0; b < PN_ALGO_COUNT; b++) {
                pn_status st;
                if (!(built & (1u << b))) continue;
                o.algo = (pn_algo)b;
                st = pn_render(ctx, &cam, &light, &o, &fr);
                if (b == a)
                    CHECK_MSG(st == PN_OK, "%s alone: %s", pn_algo_name((pn_algo)a), pn_last_error(ctx));
                else
                    CHECK_MSG(st == PN_E_LIMIT && strstr(pn_last_error(ctx), "pn_limits.algos"),
                              "%s in a context for %s: status %d", pn_algo_name((pn_algo)b), pn_algo_name((pn_algo)a),
                              (int)st);
            }
            free(mem);
        }
    }
}

/* A scene of more than 2^20 triangles (the limit before PN_MAX_TRIANGLES was raised to
 * 2^22): a floor of 1,049,800 small triangles under a square occluder and a square light
 * sets and renders (the reference, k = 4), with the occluder's shadow on it. */
static void test_over_a_million(void)
{
    enum { Q = 725, R = 724 }; /* quads along x and z: 2 Q R = 1,049,800 triangles */
    uint32_t nv = (Q + 1u) * (R + 1u) + 4u, nt = 2u * Q * R + 2u, x, z, i = 0, lit = 0, dark = 0;
    float *pos = (float *)malloc((size_t)nv * 3u * sizeof(float));
    uint32_t *idx = (uint32_t *)malloc((size_t)nt * 3u * sizeof(uint32_t));
    pn_camera cam = {{0, 5, 5}, {0, 0, -1}, {0, 1, 0}, 60.0f};
    pn_light light = {{2, 8, -2}, {0.5f, 0, 0}, {0, 0, 0.5f}};
    pn_limits l = lim3(nt, 32, 32);
    pn_frame_options o;
    pn_frame fr;
    pn_context *ctx;
    size_t bytes;
    uint8_t *mem;
    CHECK(nt > (1u << 20) && nt <= PN_MAX_TRIANGLES);
    if (!(pn_build_info() & PN_BUILD_REFERENCE)) { /* a build without it (single_algorithm_*) */
        free(pos);
        free(idx);
        return;
    }
    l.algos = PN_BUILD_REFERENCE;
    REQUIRE(pos && idx && pn_arena_size(&l, &bytes) == PN_OK && (mem = (uint8_t *)malloc(bytes)) != NULL);
    for (z = 0; z <= R; z++)
        for (x = 0; x <= Q; x++, i++) {
            pos[3u * i] = -4.0f + 8.0f * (float)x / Q;
            pos[3u * i + 1u] = 0.0f;
            pos[3u * i + 2u] = -4.0f + 8.0f * (float)z / R;
        }
    for (i = 0; i < 4u; i++) { /* the occluder, 1 x 1 at height 2 */
        pos[3u * (nv - 4u + i)] = (i & 1u) ? 0.5f : -0.5f;
        pos[3u * (nv - 4u + i) + 1u] = 2.0f;
        pos[3u * (nv - 4u + i) + 2u] = (i & 2u) ? 0.5f : -0.5f;
    }
    for (z = 0, i = 0; z < R; z++)
        for (x = 0; x < Q; x++) {
            uint32_t a = z * (Q + 1u) + x, b = a + 1u, c = a + Q + 1u, d = c + 1u;
            idx[i++] = a, idx[i++] = c, idx[i++] = b;
            idx[i++] = b, idx[i++] = c, idx[i++] = d;
        }
    idx[i++] = nv - 4u, idx[i++] = nv - 2u, idx[i++] = nv - 3u;
    idx[i++] = nv - 3u, idx[i++] = nv - 2u, idx[i++] = nv - 1u;
    REQUIRE(pn_init(&ctx, mem, bytes, &l) == PN_OK);
    CHECK_MSG(pn_scene_set(ctx, pos, nv, idx, nt) == PN_OK, "%s", pn_last_error(ctx));
    pn_frame_options_default(&o);
    o.width = o.height = 32;
    o.k = 4;
    CHECK_MSG(pn_render(ctx, &cam, &light, &o, &fr) == PN_OK, "%s", pn_last_error(ctx));
    for (i = 0; i < 32u * 32u; i++) {
        lit += fr.visibility[i] == 1.0f;
        dark += fr.visibility[i] < 0.5f;
    }
    fprintf(stderr, "%u triangles: %u of 1024 pixels lit, %u below half\n", nt, lit, dark);
    CHECK(lit > 300u && dark > 4u);
    free(mem);
    free(pos);
    free(idx);
}

/* PN_LIMITS_NO_SURFACE: each algorithm's context costs at least 20 of the 24 bytes a pixel
 * of positions and normals less (a point query's batch, a quarter of the rows with its
 * surfaces, fits in what is left). */
static void test_no_surface(void)
{
    uint32_t a, built = pn_build_info() & ((1u << PN_ALGO_COUNT) - 1u);
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        pn_limits l = lim3(1000, 64, 64), lean;
        size_t full = 0, less = 0;
        if (!(built & (1u << a))) continue;
        l.algos = 1u << a;
        lean = l;
        lean.flags = PN_LIMITS_NO_SURFACE;
        REQUIRE(pn_arena_size(&l, &full) == PN_OK && pn_arena_size(&lean, &less) == PN_OK);
        CHECK_MSG(less + 20u * 64u * 64u <= full, "%s: %zu without surfaces, %zu with", pn_algo_name((pn_algo)a), less,
                  full);
    }
}

/* A microcontroller's workload (issue 47): one algorithm, 1,000 triangles, 160x120, the
 * maps' and GEARS grid's limits at 128, frames without surfaces and MCSM's N-buffer
 * sparse: pn_arena_size at most 1 MiB for every algorithm. Then each renders `thin`
 * (2,002 triangles) in such a context, k = 8, maps of 128, GEARS in tiles of its default
 * pool: the same visibility as in a context of default limits. */
static pn_limits mcu_limits(uint32_t t, uint32_t a)
{
    pn_limits l = lim3(t, 160, 120);
    l.algos = 1u << a;
    l.srt_map_max = l.occ_map_max = l.mc_map_max = l.gears_grid_max = 128;
    l.flags = PN_LIMITS_NO_SURFACE | PN_LIMITS_SPARSE_NBUFFER;
    return l;
}

static void test_microcontroller(void)
{
    uint32_t a, built = pn_build_info() & ((1u << PN_ALGO_COUNT) - 1u);
    pn_test_scene sc;
    REQUIRE(pn_test_scene_load(&sc, "thin") == 0);
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        pn_limits l = mcu_limits(1000, a), big;
        size_t bytes = 0, px = 160u * 120u;
        pn_test_host small, full;
        pn_frame_options o;
        pn_frame fs, ff;
        pn_stats st;
        float *vis;
        if (!(built & (1u << a))) continue;
        REQUIRE(pn_arena_size(&l, &bytes) == PN_OK);
        fprintf(stderr, "%s: %zu bytes\n", pn_algo_name((pn_algo)a), bytes);
        CHECK_MSG(bytes <= 1048576u, "%s: %zu bytes for 1,000 triangles at 160x120", pn_algo_name((pn_algo)a), bytes);
        l = mcu_limits(sc.mesh.triangle_count, a);
        big = lim3(sc.mesh.triangle_count, 160, 120);
        REQUIRE(pn_test_open_limits(&small, &l) == 0);
        REQUIRE(pn_test_open_limits(&full, &big) == 0);
        REQUIRE(pn_test_scene_upload(small.ctx, &sc) == PN_OK && pn_test_scene_upload(full.ctx, &sc) == PN_OK);
        pn_frame_options_default(&o);
        o.width = 160;
        o.height = 120;
        o.k = 8;
        o.eps = sc.eps;
        o.algo = (pn_algo)a;
        o.srt.map = o.occtex.map = o.mcsm.map = 128;
        CHECK_MSG(pn_render(small.ctx, &sc.camera, &sc.light, &o, &fs) == PN_OK, "%s: %s", pn_algo_name((pn_algo)a),
                  pn_last_error(small.ctx));
        vis = (float *)malloc(px * sizeof(float));
        REQUIRE(vis != NULL);
        memcpy(vis, fs.visibility, px * sizeof(float));
        CHECK(pn_render(full.ctx, &sc.camera, &sc.light, &o, &ff) == PN_OK);
        CHECK_MSG(memcmp(vis, ff.visibility, px * sizeof(float)) == 0, "%s: the small context's frame differs",
                  pn_algo_name((pn_algo)a));
        if (a == PN_ALGO_GEARS) {
            REQUIRE(pn_get_stats(small.ctx, &st) == PN_OK);
            CHECK_MSG(st.gears.tiles > 1u, "GEARS: %u tiles, the default pool held the frame", st.gears.tiles);
        }
        free(vis);
        pn_test_close(&small);
        pn_test_close(&full);
    }
    pn_test_scene_free(&sc);
}

static void test_bad_limits(void)
{
    size_t bytes = 12345;
    pn_limits l[10];
    int i;
    for (i = 0; i < 10; i++) l[i] = lim3(10, 10, 10);
    l[0].max_triangles = 0;
    l[1].max_width = 0;
    l[2].max_height = PN_MAX_HEIGHT + 1u;
    l[3] = lim3(PN_MAX_TRIANGLES + 1u, 1, 1);
    l[4].gears_pairs = (1u << 28) + 1u;
    l[5].gears_grid_max = 1025;
    l[6].mc_map_max = PN_MCSM_MAP_MAX + 1u;
    l[7].mc_map_max = 7;
    l[8].wg_pairs = PN_WEDGES_PAIRS + 1u;
    l[9].flags = PN_LIMITS_SPARSE_NBUFFER << 1; /* a flag the library does not know */
    static const uint32_t owner[10] = {0, 0, 0, 0, PN_BUILD_GEARS, PN_BUILD_GEARS, PN_BUILD_MCSM, PN_BUILD_MCSM,
                                       PN_BUILD_WEDGES, 0};
    CHECK(pn_arena_size(NULL, &bytes) == PN_E_INVALID_ARG);
    CHECK(pn_arena_size(&l[0], NULL) == PN_E_INVALID_ARG);
    for (i = 0; i < 10; i++) {
        /* An algorithm's own field is checked by its module, and ignored in a build
         * without it. */
        if (owner[i] && !(pn_build_info() & owner[i])) {
            size_t ignored = 0;
            CHECK_MSG(pn_arena_size(&l[i], &ignored) == PN_OK, "limits %d, its algorithm not built", i);
            continue;
        }
        CHECK_MSG(pn_arena_size(&l[i], &bytes) == PN_E_LIMIT, "limits %d", i);
    }
    CHECK(bytes == 12345); /* out-parameter untouched on failure */
}

/* One byte short fails and writes nothing; the exact size renders real frames of every
 * algorithm in the build (SRT, the occlusion textures and the Monte Carlo layers on the context's largest maps) with a guard region behind the
 * block that stays intact; every misalignment works. */
static void test_too_small_and_guard(void)
{
    pn_test_scene s;
    pn_limits lim;
    size_t bytes;
    unsigned off;
    REQUIRE(pn_test_scene_load(&s, "spheres") == 0);
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = s.mesh.triangle_count;
    lim.max_width = 64;
    lim.max_height = 48;
    lim.srt_map_max = 128;
    lim.occ_map_max = 128;
    lim.mc_map_max = 128;
    REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
    for (off = 0; off < 64; off += 13) {
        uint8_t *raw = (uint8_t *)malloc(bytes + GUARD + 64);
        uint8_t *mem;
        pn_context *ctx = (pn_context *)(uintptr_t)0x1234, *keep;
        pn_frame_options opt;
        pn_algo first;
        pn_frame fr;
        int f;
        REQUIRE(raw != NULL);
        mem = raw + off;
        memset(raw, 0x5A, bytes + GUARD + 64);
        keep = ctx;
        CHECK(pn_init(&ctx, mem, bytes - 1u, &lim) == PN_E_ARENA_TOO_SMALL);
        CHECK(ctx == keep);
        CHECK(all_bytes(raw, bytes + GUARD + 64, 0x5A));
        REQUIRE(pn_init(&ctx, mem, bytes, &lim) == PN_OK);
        CHECK((uint8_t *)ctx >= mem && (uint8_t *)ctx < mem + bytes);
        CHECK(pn_scene_set(ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
        pn_frame_options_default(&opt);
        opt.k = 8;
        /* Three frames of the default algorithm (the reference, or what the build has),
         * then one of each algorithm compiled in. */
        first = opt.algo;
        for (f = 0; f < 3 + (int)PN_ALGO_COUNT; f++) {
            opt.width = f == 1 ? 32u : 64u;
            opt.height = f == 1 ? 17u : 48u;
            opt.algo = f < 3 ? first : (pn_algo)(f - 3);
            if (!(pn_build_info() & (1u << opt.algo))) continue;
            CHECK_MSG(pn_render(ctx, &s.camera, &s.light, &opt, &fr) == PN_OK, "algorithm %d: %s", (int)opt.algo,
                      pn_last_error(ctx));
            CHECK((const uint8_t *)fr.visibility >= mem &&
                  (const uint8_t *)(fr.visibility + opt.width * opt.height) <= mem + bytes);
        }
        CHECK_MSG(all_bytes(mem + bytes, GUARD, 0x5A), "guard region after the arena was written (offset %u)", off);
        CHECK(all_bytes(raw, off, 0x5A));
        {
            pn_stats st;
            CHECK(pn_get_stats(ctx, &st) == PN_OK);
            CHECK(st.arena_high_water <= st.arena_carved);
            CHECK(st.arena_high_water > st.arena_persistent);
        }
        free(raw);
    }
    pn_test_scene_free(&s);
}

/* A static block of PN_ARENA_BYTES_MAX works (the firmware way), with small limits. */
static uint8_t static_arena[PN_ARENA_BYTES_MAX(64, 16, 16)];
static void test_static_arena(void)
{
    pn_limits lim = lim3(64, 16, 16);
    pn_context *ctx;
    size_t bytes;
    CHECK(pn_arena_size(&lim, &bytes) == PN_OK);
    CHECK(bytes <= sizeof(static_arena));
    CHECK(pn_init(&ctx, static_arena, sizeof(static_arena), &lim) == PN_OK);
}

/* Two contexts in one process are independent (no hidden global state). */
static void test_two_contexts(void)
{
    pn_limits lim = lim3(16, 8, 8);
    size_t bytes;
    uint8_t *a, *b;
    pn_context *ca, *cb;
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[3] = {0, 1, 3};
    REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
    a = (uint8_t *)malloc(bytes);
    b = (uint8_t *)malloc(bytes);
    REQUIRE(a && b);
    REQUIRE(pn_init(&ca, a, bytes, &lim) == PN_OK);
    REQUIRE(pn_init(&cb, b, bytes, &lim) == PN_OK);
    CHECK(pn_scene_set(ca, pos, 3, idx, 1) == PN_E_INDEX_RANGE);
    CHECK(strlen(pn_last_error(ca)) > 0);
    CHECK(strlen(pn_last_error(cb)) == 0);
    free(a);
    free(b);
}

int main(void)
{
    RUN(test_size_equals_carve);
    RUN(test_bytes_max_tight);
    RUN(test_algos);
    RUN(test_bad_limits);
    RUN(test_no_surface);
    RUN(test_microcontroller);
    RUN(test_too_small_and_guard);
    RUN(test_static_arena);
    RUN(test_two_contexts);
    RUN(test_over_a_million);
    return pn_test_summary();
}
