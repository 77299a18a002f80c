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

static void test_size_equals_carve(void)
{
    pn_limits lims[4] = {{1, 1, 1, 0, 0, 0, 0, 0, 0, 0}, {100, 64, 48, 1000, 16, 0, 0, 0, 0, 0}, {1u << 20, 512, 512, 0, 0, 0, 0, 0, 0, 0},
                         {PN_MAX_TRIANGLES, PN_MAX_WIDTH, PN_MAX_HEIGHT, 0, 0, 0, 0, 0, 0, 0}};
    int i;
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
    {
        size_t bytes = 0;
        pn_limits l = {1u << 20, 512, 512, 0, 0, 0, 0, 0, 0, 0};
        CHECK(pn_arena_size(&l, &bytes) == PN_OK);
        fprintf(stderr, "arena for 512x512, 2^20 triangles: %zu bytes\n", bytes);
    }
}

static void test_bad_limits(void)
{
    size_t bytes = 12345;
    pn_limits l0 = {0, 10, 10, 0, 0, 0, 0, 0, 0, 0}, l1 = {10, 0, 10, 0, 0, 0, 0, 0, 0, 0}, l2 = {10, 10, PN_MAX_HEIGHT + 1u, 0, 0, 0, 0, 0, 0, 0},
              l3 = {PN_MAX_TRIANGLES + 1u, 1, 1, 0, 0, 0, 0, 0, 0, 0}, l4 = {10, 10, 10, (1u << 28) + 1u, 0, 0, 0, 0, 0, 0},
              l5 = {10, 10, 10, 0, 1025, 0, 0, 0, 0, 0}, l6 = {10, 10, 10, 0, 0, 0, 0, PN_MCSM_MAP_MAX + 1u, 0, 0},
              l7 = {10, 10, 10, 0, 0, 0, 0, 7, 0, 0}, l8 = {10, 10, 10, 0, 0, 0, 0, 0, PN_WEDGES_PAIRS + 1u, 0};
    CHECK(pn_arena_size(NULL, &bytes) == PN_E_INVALID_ARG);
    CHECK(pn_arena_size(&l0, NULL) == PN_E_INVALID_ARG);
    CHECK(pn_arena_size(&l0, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l1, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l2, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l3, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l4, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l5, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l6, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l7, &bytes) == PN_E_LIMIT);
    CHECK(pn_arena_size(&l8, &bytes) == PN_E_LIMIT);
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
    pn_limits lim = {64, 16, 16, 0, 0, 0, 0, 0, 0, 0};
    pn_context *ctx;
    size_t bytes;
    CHECK(pn_arena_size(&lim, &bytes) == PN_OK);
    CHECK(bytes <= sizeof(static_arena));
    CHECK(pn_init(&ctx, static_arena, sizeof(static_arena), &lim) == PN_OK);
}

/* Two contexts in one process are independent (no hidden global state). */
static void test_two_contexts(void)
{
    pn_limits lim = {16, 8, 8, 0, 0, 0, 0, 0, 0, 0};
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
    RUN(test_bad_limits);
    RUN(test_too_small_and_guard);
    RUN(test_static_arena);
    RUN(test_two_contexts);
    return pn_test_summary();
}
