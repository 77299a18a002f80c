/* PN_ALGO_SRT (selective ray tracing): what it promises and how close it comes.
 *
 * 1. Conservative by construction: with the PIP set forced to every pixel
 *    (PN_SRT_FORCE_PIP) the visibility buffer and image are byte-identical to the
 *    reference's, on every built-in scene and spot.glb, area and point light, and the PIP
 *    count equals the lit pixels.
 * 2. Accuracy: with the defaults, the fraction of pixels differing from the reference on
 *    every built-in scene and spot.glb, area (k = 16) and point light, is at most 0.1% (the
 *    issue's goal), and on `thin` no pixel is brighter than the reference (no
 *    missing shadow). Every pixel that differs lies outside the PIP set by construction (PIP pixels
 *    take the reference's own path), so the measured rates are the classification's misses.
 *    The same with conservative rasterization off is printed, not asserted.
 * 4. Property over random scenes (test_random): a ground plane under boxes, boards (one
 *    side a fraction of a percent of the scene) and slivers at random, an area (k = 16)
 *    and a point light: forced PIP is the reference byte for byte on every one, and the
 *    defaults' differing pixels are counted. A scene/light over the 0.1% goal is a
 *    documented case (g_cases: the misses the paper admits, regular light-space sampling
 *    missing what falls between texel centres) and may not grow; every other one must
 *    meet the goal. The whole rate is printed.
 * 3. Options and pools: srt.map outside 8 .. the limit and unknown flags are
 *    PN_E_INVALID_ARG; a context whose srt_map_max is 64 renders, with its map size in the
 *    stats, and with a clock its stage timings lie inside the shadow pass. */
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

static frame g_ref, g_srt;

static int render(pn_host *h, const pn_setup *s, const pn_light *light, pn_algo algo, uint32_t k, uint32_t flags,
                  uint32_t map, frame *out)
{
    pn_frame_options opt;
    pn_frame_options_default(&opt);
    opt.width = W;
    opt.height = H;
    opt.k = k;
    opt.algo = algo;
    opt.srt.flags = flags;
    opt.srt.map = map;
    return render_opt(h, s, light, &opt, out->vis, out->rgba, &out->st);
}

static void one_scene(const char *source, int builtin)
{
    pn_setup s;
    pn_host h;
    char err[256];
    int li;
    if (pn_setup_load(&s, source, builtin, -1, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading %s: %s", source, err);
        return;
    }
    if (pn_host_open(&h, s.mesh.triangle_count, W, H, 2, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "context: %s", err);
        pn_setup_free(&s);
        return;
    }
    CHECK(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    for (li = 0; li < 2; li++) {
        pn_light light = s.light;
        uint32_t k = li ? 1u : 16u, i, diff = 0, brighter = 0, diff_nc = 0, n = W * H;
        if (li) memset(light.u, 0, sizeof(light.u)), memset(light.v, 0, sizeof(light.v));
        if (li) k = 4u; /* k is checked for a point light too; it uses one sample */
        if (render(&h, &s, &light, PN_ALGO_REFERENCE, k, 0u, 0u, &g_ref) != 0) continue;
        /* 1. Forced PIP: the reference, byte for byte. */
        REQUIRE(render(&h, &s, &light, PN_ALGO_SRT, k, PN_SRT_FORCE_PIP, 0u, &g_srt) == 0);
        CHECK_MSG(memcmp(g_ref.vis, g_srt.vis, sizeof(g_ref.vis)) == 0, "%s %s: forced PIP differs from the reference",
                  s.name, li ? "point" : "area");
        CHECK(memcmp(g_ref.rgba, g_srt.rgba, sizeof(g_ref.rgba)) == 0);
        CHECK_MSG(g_srt.st.srt.pip == g_srt.st.lit_pixels, "%s: forced PIP %u, lit %u", s.name, g_srt.st.srt.pip,
                  g_srt.st.lit_pixels);
        /* 2. The defaults against the reference. */
        REQUIRE(render(&h, &s, &light, PN_ALGO_SRT, k, 0u, 0u, &g_srt) == 0);
        for (i = 0; i < n; i++) {
            diff += g_srt.vis[i] != g_ref.vis[i];
            brighter += g_srt.vis[i] > g_ref.vis[i];
        }
        CHECK(g_srt.st.srt.pip <= g_srt.st.lit_pixels);
        /* A thin triangle marks at least one texel (its extent is widened by a texel). */
        CHECK_MSG((g_srt.st.srt.thin > 0u) == (g_srt.st.srt.cons_texels > 0u), "%s: %u thin triangles, %u texels marked",
                  s.name, g_srt.st.srt.thin, g_srt.st.srt.cons_texels);
        fprintf(stderr, "%-24s %-5s map %4u  PIP %5.1f%% of lit  thin %6u (%u texels)  differing %u (%.3f%%), brighter %u\n",
                s.name, li ? "point" : "area", g_srt.st.srt.map,
                g_srt.st.lit_pixels ? 100.0 * g_srt.st.srt.pip / g_srt.st.lit_pixels : 0.0, g_srt.st.srt.thin,
                g_srt.st.srt.cons_texels, diff, 100.0 * diff / n, brighter);
        /* room's point light missed 21 shadow pixels (0.17%) until the classification sent
         * pixels lit only by the slope bias to the PIP set (kernels/pn_srt.h); now 1. */
        CHECK_MSG(diff * 1000u <= n, "%s %s: %u of %u pixels differ from the reference (goal: at most 0.1%%)", s.name,
                  li ? "point" : "area", diff, n);
        if (strcmp(s.name, "thin") == 0)
            CHECK_MSG(brighter == 0u, "thin %s: %u pixels miss a shadow", li ? "point" : "area", brighter);
        /* Without conservative rasterization: printed for the record. */
        if (render(&h, &s, &light, PN_ALGO_SRT, k, PN_SRT_NO_CONSERVATIVE, 0u, &g_srt) == 0) {
            CHECK(g_srt.st.srt.thin == 0u && g_srt.st.srt.cons_texels == 0u);
            for (i = 0; i < n; i++) diff_nc += g_srt.vis[i] != g_ref.vis[i];
            fprintf(stderr, "%-24s %-5s without conservative rasterization: PIP %5.1f%%, differing %u (%.3f%%)\n",
                    s.name, li ? "point" : "area",
                    g_srt.st.lit_pixels ? 100.0 * g_srt.st.srt.pip / g_srt.st.lit_pixels : 0.0, diff_nc,
                    100.0 * diff_nc / n);
        }
    }
    pn_host_close(&h);
    pn_setup_free(&s);
}

static void test_scenes(void)
{
    const char *const *names = pn_builtin_scene_names();
    int i;
    for (i = 0; names[i]; i++) one_scene(names[i], 1);
    one_scene(PN_SCENES_DIR "/spot.glb", 0);
}

/* ---- 4. random scenes ---------------------------------------------------------------------- */

#define RT_MAX 640u /* triangles of a random scene at most */
static float g_pos[RT_MAX * 9u];
static uint32_t g_idx[RT_MAX * 3u];

static uint32_t g_rs;
static float rnd01(void)
{
    g_rs ^= g_rs << 13;
    g_rs ^= g_rs >> 17;
    g_rs ^= g_rs << 5;
    return (float)(g_rs >> 8) * (1.0f / 16777216.0f);
}

static uint32_t put_tri(uint32_t t, const float *a, const float *b, const float *c)
{
    memcpy(g_pos + t * 9u, a, 12);
    memcpy(g_pos + t * 9u + 3u, b, 12);
    memcpy(g_pos + t * 9u + 6u, c, 12);
    g_idx[t * 3u] = t * 3u;
    g_idx[t * 3u + 1u] = t * 3u + 1u;
    g_idx[t * 3u + 2u] = t * 3u + 2u;
    return t + 1u;
}

/* An axis-aligned box (12 triangles, outward winding not needed: the light sees both sides). */
static uint32_t put_box(uint32_t t, const float lo[3], const float hi[3])
{
    static const int f[6][4][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                                   {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
                                   {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}};
    int q, v, a;
    for (q = 0; q < 6; q++) {
        float c[4][3];
        for (v = 0; v < 4; v++)
            for (a = 0; a < 3; a++) c[v][a] = f[q][v][a] ? hi[a] : lo[a];
        t = put_tri(t, c[0], c[1], c[2]);
        t = put_tri(t, c[0], c[2], c[3]);
    }
    return t;
}

/* Scene `seed`: a 4 x 4 ground quad at y = 0 and up to 40 boxes, boards and slivers above it
 * (y up to 1.2), seen from above at an angle, lit from above. */
static uint32_t random_scene(uint32_t seed, pn_setup *s)
{
    uint32_t t = 0, n, i;
    float g[4][3] = {{-2, 0, -2}, {2, 0, -2}, {2, 0, 2}, {-2, 0, 2}};
    g_rs = 0x9E3779B9u ^ (seed * 2654435761u);
    if (!g_rs) g_rs = 1u;
    t = put_tri(t, g[0], g[1], g[2]);
    t = put_tri(t, g[0], g[2], g[3]);
    n = 8u + (uint32_t)(rnd01() * 32.0f);
    for (i = 0; i < n && t + 12u <= RT_MAX; i++) {
        float lo[3], hi[3], size[3], kind = rnd01();
        int a;
        for (a = 0; a < 3; a++) {
            lo[a] = (a == 1 ? 0.02f + 1.0f * rnd01() : -1.6f + 3.2f * rnd01());
            size[a] = 0.05f + 0.5f * rnd01();
        }
        if (kind < 0.35f) size[(uint32_t)(rnd01() * 3.0f) % 3u] = 0.002f + 0.01f * rnd01(); /* a board */
        if (kind > 0.85f) { /* a sliver: one long thin triangle */
            float a0[3], b0[3], c0[3];
            for (a = 0; a < 3; a++) {
                a0[a] = lo[a];
                b0[a] = lo[a] + (a == 1 ? 0.0f : 2.0f * size[a]);
                c0[a] = b0[a] + (a == 1 ? 0.004f : 0.003f);
            }
            t = put_tri(t, a0, b0, c0);
            continue;
        }
        for (a = 0; a < 3; a++) hi[a] = lo[a] + size[a];
        t = put_box(t, lo, hi);
    }
    memset(s, 0, sizeof(*s));
    snprintf(s->name, sizeof(s->name), "random %u", seed);
    s->camera.eye[0] = 3.2f * (rnd01() - 0.5f);
    s->camera.eye[1] = 3.0f + rnd01();
    s->camera.eye[2] = 4.0f;
    s->camera.up[1] = 1.0f;
    s->camera.fov_deg = 50.0f;
    s->light.center[0] = 1.5f * (rnd01() - 0.5f);
    s->light.center[1] = 2.5f + rnd01();
    s->light.center[2] = 1.5f * (rnd01() - 0.5f);
    s->light.u[0] = 0.1f + 0.3f * rnd01();
    s->light.v[2] = 0.1f + 0.3f * rnd01();
    s->diag = 6.0f;
    s->eps = 1e-4f * s->diag;
    return t;
}

/* Scene/light pairs over the goal, as measured: {seed, light (0 area, 1 point), differing
 * pixels at most}. When this test was written (49083e4) none of the 48 was: 6 of 589,824
 * pixels differed (seeds 16, 20, 24 point: 1 each; seed 21 area: 3), so the list holds only
 * its end marker (seed 0 is not a scene). */
static const struct {
    uint32_t seed, light, diff;
} g_cases[] = {
    {0u, 0u, 0u},
};

static void test_random(void)
{
    pn_host h;
    char err[256];
    uint32_t seed, total = 0, px = 0, over = 0, pip = 0, lit = 0, shadowed = 0;
    REQUIRE(pn_host_open(&h, RT_MAX, W, H, 2, err, sizeof(err)) == 0);
    for (seed = 1; seed <= 24u; seed++) {
        pn_setup s;
        uint32_t tris = random_scene(seed, &s), li;
        REQUIRE(pn_scene_set(h.ctx, g_pos, tris * 3u, g_idx, tris) == PN_OK);
        for (li = 0; li < 2u; li++) {
            pn_light light = s.light;
            uint32_t k = li ? 4u : 16u, i, diff = 0, q, allowed = W * H / 1000u;
            int documented = 0;
            if (li) memset(light.u, 0, sizeof(light.u)), memset(light.v, 0, sizeof(light.v));
            REQUIRE(render(&h, &s, &light, PN_ALGO_REFERENCE, k, 0u, 0u, &g_ref) == 0);
            REQUIRE(render(&h, &s, &light, PN_ALGO_SRT, k, PN_SRT_FORCE_PIP, 8u, &g_srt) == 0);
            CHECK_MSG(memcmp(g_ref.vis, g_srt.vis, sizeof(g_ref.vis)) == 0 && memcmp(g_ref.rgba, g_srt.rgba, sizeof(g_ref.rgba)) == 0,
                      "%s %s: forced PIP differs from the reference", s.name, li ? "point" : "area");
            REQUIRE(render(&h, &s, &light, PN_ALGO_SRT, k, 0u, 0u, &g_srt) == 0);
            for (i = 0; i < W * H; i++) {
                diff += g_srt.vis[i] != g_ref.vis[i];
                shadowed += g_ref.vis[i] < 1.0f;
            }
            for (q = 0; q < sizeof(g_cases) / sizeof(g_cases[0]); q++)
                if (g_cases[q].seed == seed && g_cases[q].light == li) {
                    allowed = g_cases[q].diff;
                    documented = 1;
                }
            CHECK_MSG(diff <= allowed, "%s %s (%u triangles): %u pixels differ from the reference, %s %u", s.name,
                      li ? "point" : "area", tris, diff, documented ? "documented case at most" : "goal at most", allowed);
            if (diff) fprintf(stderr, "  %s %-5s: %u differing pixels (%.3f%%)\n", s.name, li ? "point" : "area", diff,
                              100.0 * diff / (W * H));
            total += diff;
            px += W * H;
            over += diff * 1000u > W * H;
            pip += g_srt.st.srt.pip;
            lit += g_srt.st.lit_pixels;
        }
    }
    fprintf(stderr,
            "random scenes: %u of %u pixels differ (%.4f%%), %u scene/light pairs over 0.1%%; PIP %.1f%% of lit; %.1f%% of "
            "pixels not fully lit in the reference\n",
            total, px, 100.0 * total / px, over, lit ? 100.0 * pip / lit : 0.0, 100.0 * shadowed / px);
    /* Not vacuous: the scenes cast shadows (about a tenth of all pixels, background
     * included, is not fully lit) and SRT had pixels to classify. */
    CHECK(shadowed * 20u > px && pip < lit);
    pn_host_close(&h);
}

static void test_options(void)
{
    pn_setup s;
    pn_host h;
    char err[256];
    pn_limits lim = {64, 32, 32, 1000, 16, 64, 0, 8, 0, 0, 0, 0, 0};
    size_t bytes;
    void *mem;
    pn_context *ctx;
    pn_frame_options opt;
    pn_frame fr;
    pn_stats st;
    REQUIRE(pn_setup_load(&s, "square", 1, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_host_open(&h, s.mesh.triangle_count, 32, 32, 1, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    pn_frame_options_default(&opt);
    opt.width = opt.height = 32;
    opt.algo = PN_ALGO_SRT;
    opt.srt.map = 7;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.srt.map = PN_SRT_MAP_MAX + 1u;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.srt.map = 0;
    opt.srt.flags = 4u;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.srt.flags = 0;
    opt.srt.delta = -1.0f;
    CHECK(pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.srt.delta = 0.0f;
    pn_host_close(&h);

    /* A small map limit: a smaller arena, and frames at that map size. */
    REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
    {
        pn_limits big = lim;
        size_t big_bytes;
        big.srt_map_max = 0;
        REQUIRE(pn_arena_size(&big, &big_bytes) == PN_OK);
        CHECK(bytes < big_bytes);
        big.srt_map_max = PN_SRT_MAP_MAX + 1u;
        CHECK(pn_arena_size(&big, &big_bytes) == PN_E_LIMIT);
    }
    mem = malloc(bytes);
    REQUIRE(mem != NULL);
    REQUIRE(pn_init(&ctx, mem, bytes, &lim) == PN_OK);
    REQUIRE(pn_scene_set(ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    opt.srt.map = 65;
    CHECK(pn_render(ctx, &s.camera, &s.light, &opt, &fr) == PN_E_INVALID_ARG);
    opt.srt.map = 0;
    {
        /* Stage timings: none without a clock; with one, inside the shadow pass. */
        static const size_t off[3] = {offsetof(pn_stats, srt.ns_map), offsetof(pn_stats, srt.ns_classify),
                                      offsetof(pn_stats, srt.ns_exact)};
        check_stage_times(ctx, &s.camera, &s.light, &opt, off, &st);
    }
    CHECK(st.srt.map == 64u);
    free(mem);
    pn_setup_free(&s);
}

int main(void)
{
    RUN(test_options);
    RUN(test_scenes);
    RUN(test_random);
    return pn_test_summary();
}
