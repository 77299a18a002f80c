/* PN_ALGO_RAYTRACE: k^2 single rays per pixel give the reference's bits.
 *
 * 1. Predicate: for random triangles (every scale, nearly edge-on, straddling the light
 *    plane and O's plane, slivers, segments exactly through a vertex), every bit of
 *    pn_tri_mask() equals pn_tri_sample() for that sample, for k = 4, 8, 16, 32 and a
 *    point light. This pins the mask's row narrowing and band classification to the
 *    per-sample definition: any shortcut that changes one bit fails here (both are exact,
 *    tests/test_exact.c compares them with an exact arbiter).
 * 2. Frames: the raytraced visibility buffer is byte-identical to the reference's on the
 *    built-in scenes and spot.glb, area and point light. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
/* Counts the values the filter leaves to the exact arithmetic (coverage of that path). */
static unsigned long exact_calls[4];
#define PN_EXACT_HOOK(kind) (exact_calls[kind]++)
#include "pn_predicate.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"
#include "pn_test_render.h"

static uint32_t rng_state = 987654321u;
static float rndf(void) /* [0, 1) */
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (float)(rng_state >> 8) / 16777216.0f;
}
static float rnds(void) { return rndf() * 2.0f - 1.0f; }

static pn_klight make_light(uint32_t k, int point)
{
    pn_klight L;
    memset(&L, 0, sizeof(L));
    L.c[1] = 1.0f;
    if (!point) {
        L.U[0] = 0.25f + 0.5f * rndf();
        L.V[2] = 0.25f * (0.02f + rndf()); /* aspect up to 1:40 */
        L.N[1] = -1.0f;
    }
    L.k = point ? 1u : k;
    L.is_point = (uint32_t)point;
    return L;
}

static void test_mask_equals_samples(void)
{
    static const uint32_t ks[5] = {4, 8, 16, 32, 1};
    uint32_t trial, mismatches = 0, blocked = 0, partial = 0;
    unsigned long band0[4];
    memcpy(band0, exact_calls, sizeof(band0));
    for (trial = 0; trial < 40000u; trial++) {
        uint32_t k = ks[trial % 5u];
        pn_klight L = make_light(k, k == 1u);
        pn_v3 O = pn_v3_make(rnds() * 0.3f, rndf() * 0.05f, rnds() * 0.3f), A, B, C, ctr;
        float size = powf(10.0f, -4.0f + 4.0f * rndf()), h;
        uint32_t m[PN_MASK_WORDS_MAX], i, j, n = 0;
        int style = (int)(trial / 5u % 5u);
        /* A point on a random segment O -> light, or (style 3) near the light plane or
         * O's plane, and a triangle around it. */
        h = style == 3 ? (rndf() < 0.5f ? 1.0f : 0.0f) + rnds() * 1e-3f : 0.05f + 0.9f * rndf();
        {
            pn_v3 S = pn_v3_make(L.c[0] + rnds() * L.U[0], 1.0f, L.c[2] + rnds() * L.V[2]);
            ctr = pn_v3_add(O, pn_v3_scale(pn_v3_sub(S, O), h));
        }
        A = pn_v3_add(ctr, pn_v3_scale(pn_v3_make(rnds(), rnds(), rnds()), size));
        B = pn_v3_add(ctr, pn_v3_scale(pn_v3_make(rnds(), rnds(), rnds()), size));
        if (style == 4) { /* A on the segment to a sample: that sample lies on edges AB and CA */
            uint32_t si = (uint32_t)(rndf() * (float)L.k) % L.k, sj = (uint32_t)(rndf() * (float)L.k) % L.k;
            pn_v3 S = pn_v3_make(L.c[0] + pn_sample_coord((int32_t)si, L.k) * L.U[0], L.c[1],
                                 L.c[2] + pn_sample_coord((int32_t)sj, L.k) * L.V[2]);
            A = pn_v3_add(O, pn_v3_scale(pn_v3_sub(S, O), h));
        }
        if (style == 1) /* nearly edge-on: C close to the plane through O, A, B */
            C = pn_v3_add(pn_v3_add(A, pn_v3_scale(pn_v3_sub(A, O), rnds() * 0.5f)),
                          pn_v3_scale(pn_v3_make(rnds(), rnds(), rnds()), size * 1e-4f));
        else if (style == 2) /* sliver */
            C = pn_v3_add(pn_v3_add(A, pn_v3_scale(pn_v3_sub(B, A), rndf())), pn_v3_scale(pn_v3_make(rnds(), rnds(), rnds()), size * 1e-3f));
        else
            C = pn_v3_add(ctr, pn_v3_scale(pn_v3_make(rnds(), rnds(), rnds()), size * 30.0f));
        L.cull_tol = 1e-5f;
        pn_mask_clear(m);
        pn_tri_mask(O, A, B, C, &L, m);
        for (j = 0; j < L.k; j++)
            for (i = 0; i < L.k; i++) {
                uint32_t bit = j * L.k + i;
                uint32_t mb = (m[bit >> 5] >> (bit & 31u)) & 1u;
                uint32_t sb = pn_tri_sample(O, A, B, C, &L, (int32_t)i, (int32_t)j);
                n += mb;
                if (mb != sb) {
                    if (mismatches < 5)
                        fprintf(stderr, "trial %u k=%u sample %u,%u: mask %u, single sample %u\n", trial, L.k, i, j, mb, sb);
                    mismatches++;
                }
            }
        blocked += n;
        partial += n > 0u && n < L.k * L.k;
    }
    fprintf(stderr,
            "mask vs single samples: 40000 triangles, %u blocked samples, %u partly blocking, exact fallbacks: %lu "
            "O sides, %lu plane values, %lu edge values; %u mismatches\n",
            blocked, partial, exact_calls[0] - band0[0], exact_calls[1] - band0[1], exact_calls[2] - band0[2],
            mismatches);
    CHECK(blocked > 100000u);
    CHECK(partial > 4000u);                   /* coverage: the generator must exercise partial masks */
    CHECK(exact_calls[2] - band0[2] > 100u);  /* ...and the exact edge decisions of band samples */
    CHECK(mismatches == 0u);
}

static void frames_equal(const char *src, int builtin, uint32_t w, uint32_t hh, const uint32_t *ks, int nk)
{
    pn_setup s;
    pn_host h;
    char err[256];
    size_t n = (size_t)w * hh, p;
    float *ref = (float *)malloc(n * sizeof(float)), *rt = (float *)malloc(n * sizeof(float));
    int q;
    REQUIRE(ref && rt);
    REQUIRE(pn_setup_load(&s, src, builtin, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_host_open(&h, s.mesh.triangle_count, w, hh, 2, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    for (q = 0; q <= nk; q++) {
        pn_light light = s.light;
        uint32_t k = q < nk ? ks[q] : 4u, d = 0, shadowed = 0;
        if (q == nk) {
            memset(light.u, 0, sizeof(light.u));
            memset(light.v, 0, sizeof(light.v));
        }
        REQUIRE(render_vis(&h, &s, &light, PN_ALGO_REFERENCE, w, hh, k, 128, ref, NULL) == 0);
        REQUIRE(render_vis(&h, &s, &light, PN_ALGO_RAYTRACE, w, hh, k, 128, rt, NULL) == 0);
        for (p = 0; p < n; p++) {
            d += memcmp(ref + p, rt + p, sizeof(float)) != 0;
            shadowed += ref[p] < 1.0f;
        }
        fprintf(stderr, "%s %ux%u %s k=%u: %u shadowed pixels, %u differ\n", s.name, w, hh, q == nk ? "point" : "area",
                k, shadowed, d);
        CHECK(shadowed > 0u);
        CHECK_MSG(d == 0u, "%s k=%u %s", s.name, k, q == nk ? "point" : "area");
    }
    pn_host_close(&h);
    pn_setup_free(&s);
    free(ref);
    free(rt);
}

static void test_frames(void)
{
    static const uint32_t ks[3] = {4, 16, 32};
    const char *const *names = pn_builtin_scene_names();
    for (; *names; names++) frames_equal(*names, 1, 56, 48, ks, 3);
    frames_equal(PN_SCENES_DIR "/spot.glb", 0, 64, 64, ks, 2);
}

int main(void)
{
    RUN(test_mask_equals_samples);
    RUN(test_frames);
    return pn_test_summary();
}
