/* Exact means exact (issue 13): every mask bit against an exact arbiter.
 *
 * The arbiter (tests/pn_test_exact.h) decides invariant 6 with its own formulation, a
 * verified double filter and exact big integers; the library's predicate decides it with
 * float linear forms, rigorous bounds and float expansion arithmetic. Zero differing bits
 * are required on:
 *   1. hostile single triangles: coordinates on a coarse dyadic grid (exact coplanarity of
 *      O with the triangle, segments exactly through vertices and edges, samples exactly in
 *      planes), slivers, O a few ulps off the plane, near-coplanar neighbours sharing an
 *      edge, some configurations scaled by 2^-40 or 2^30; pn_tri_mask() and pn_tri_sample()
 *      against the arbiter, k = 1 (point) to 32;
 *   2. horizons: own triangles whose plane passes through (or within ulps of) the light,
 *      pn_horizon_mask() and pn_horizon_at() against the arbiter;
 *   3. hostile random scenes (a dyadic grid of shared edges, slivers, near-coplanar
 *      neighbours, receivers whose plane straddles the light): the kernel's brute-force
 *      mask of whole pixels (horizon + every other triangle) against the arbiter's, and
 *      the reference's frustum cull against every triangle the arbiter says blocks;
 *   4. frames of the built-in scenes and spot.glb at small sizes, area and point light:
 *      the reference's, GEARS' and the ray tracer's visibility against the arbiter's, and
 *      the kernel's per-pixel masks bit for bit.
 * Built twice (tests/CMakeLists.txt): test_exact, linked to the library alone, runs 1 to 4
 * on the scenes of tests/pn_test_scene.h; test_exact_models (PN_TEST_MODELS=1), linked to the
 * tools, runs 4 on spot.glb.
 * The counts of values that reached the exact arithmetic are printed and required to be
 * non-zero: the hostile inputs must exercise the slow path, not only the filter. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "penumbra/penumbra.h"
static unsigned long exact_calls[4];
#define PN_EXACT_HOOK(kind) (exact_calls[kind]++)
#include "pn_reference.h"
#include "pn_test.h"
#include "pn_test_exact.h"
#include "pn_test_scene.h"

/* 0: test_exact, the library alone (tests/pn_test_scene.h); 1: test_exact_models, the frames
 * of spot.glb through the tools' glTF loader (tests/CMakeLists.txt). */
#ifndef PN_TEST_MODELS
#define PN_TEST_MODELS 0
#endif
#if PN_TEST_MODELS
#include "pn_test_tools.h"
#endif

static pn_klight klight_from(const arb_light *a, float eps)
{
    pn_klight kl;
    memset(&kl, 0, sizeof(kl));
    memcpy(kl.c, a->c, sizeof(kl.c));
    memcpy(kl.U, a->U, sizeof(kl.U));
    memcpy(kl.V, a->V, sizeof(kl.V));
    kl.eps = eps;
    kl.cull_tol = 1e-5f;
    kl.k = (uint32_t)a->k;
    kl.is_point = a->k == 1 && a->U[0] == 0.0f && a->U[1] == 0.0f && a->U[2] == 0.0f;
    if (!kl.is_point) {
        pn_v3 N = pn_v3_normalize(pn_v3_cross(pn_v3_make(a->U[0], a->U[1], a->U[2]), pn_v3_make(a->V[0], a->V[1], a->V[2])));
        kl.N[0] = N.x;
        kl.N[1] = N.y;
        kl.N[2] = N.z;
    }
    return kl;
}

static void set3(float *d, pn_v3 v)
{
    d[0] = v.x;
    d[1] = v.y;
    d[2] = v.z;
}
static pn_v3 v3(const float *p) { return pn_v3_make(p[0], p[1], p[2]); }

#if !PN_TEST_MODELS

static uint32_t rng = 20261201u;
static uint32_t rndu(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}
static float rndf(void) { return (float)(rndu() >> 8) / 16777216.0f; } /* [0, 1) */
static float rnds(void) { return rndf() * 2.0f - 1.0f; }
/* A dyadic coordinate: a multiple of 1/8 in [-2, 2]: exact degeneracies are common. */
static float grid(void) { return (float)((int)(rndu() % 33u) - 16) / 8.0f; }
static float nudge(float v, int ulps)
{
    while (ulps > 0) { v = nextafterf(v, INFINITY); ulps--; }
    while (ulps < 0) { v = nextafterf(v, -INFINITY); ulps++; }
    return v;
}

static void random_light(arb_light *L, int dyadic)
{
    static const int ks[5] = {1, 4, 8, 16, 32};
    int k = ks[rndu() % 5u], q;
    L->k = k;
    for (q = 0; q < 3; q++) {
        L->c[q] = dyadic ? grid() : rnds() * 2.0f;
        L->U[q] = 0.0f;
        L->V[q] = 0.0f;
    }
    L->c[1] = dyadic ? 2.0f + grid() * 0.25f : 2.0f + rnds() * 0.5f;
    if (k == 1) return;
    if (rndu() % 2u) { /* axis-aligned, facing down */
        L->U[0] = dyadic ? 0.5f : 0.25f + 0.5f * rndf();
        L->V[2] = dyadic ? -0.25f : -(0.05f + 0.5f * rndf());
    } else { /* tilted: U and V orthogonal by construction */
        float a = rnds(), b = rnds(), s = 0.3f + 0.4f * rndf();
        L->U[0] = s * a;
        L->U[1] = s * b * 0.5f;
        L->U[2] = s * 0.25f;
        L->V[0] = -b * 0.25f * s;
        L->V[1] = a * 0.25f * s;
        L->V[2] = 0.0f;
        L->V[2] = -(L->U[0] * L->V[0] + L->U[1] * L->V[1]) / L->U[2];
    }
}

static uint32_t mask_bit(const uint32_t *m, uint32_t bit) { return m[bit >> 5] >> (bit & 31u) & 1u; }

/* ---- 1. hostile single triangles ---------------------------------------------------------- */

static void test_triangles(void)
{
    uint32_t trial, diff_mask = 0, diff_sample = 0, blocked = 0, checked = 0;
    unsigned long x0[4], arb0 = arb_exact_calls;
    memcpy(x0, exact_calls, sizeof(x0));
    for (trial = 0; trial < 12000u; trial++) {
        arb_light L;
        pn_klight kl;
        float O[3], T[9], S[3];
        uint32_t m[PN_MASK_WORDS_MAX], i, j, style = trial % 6u;
        int q, si, sj;
        random_light(&L, style < 3u);
        kl = klight_from(&L, 0.0f);
        si = (int)(rndu() % (uint32_t)L.k);
        sj = (int)(rndu() % (uint32_t)L.k);
        for (q = 0; q < 3; q++) {
            O[q] = style < 3u ? grid() : rnds();
            S[q] = L.c[q] + pn_sample_coord(si, kl.k) * L.U[q] + pn_sample_coord(sj, kl.k) * L.V[q];
        }
        O[1] = style < 3u ? grid() * 0.125f : rnds() * 0.1f;
        if (style == 0u) {
            /* Dyadic: every vertex on the grid between O and the light. */
            for (q = 0; q < 9; q++) T[q] = grid();
            for (q = 0; q < 3; q++) T[3 * q + 1] = 0.5f + grid() * 0.125f;
        } else if (style == 1u) {
            /* A vertex exactly (dyadic midpoint) on the segment O -> S, others on the grid. */
            for (q = 0; q < 3; q++) T[q] = 0.5f * (O[q] + S[q]);
            for (q = 3; q < 9; q++) T[q] = grid();
            if (rndu() % 2u) /* and the second too: the segment runs along edge AB's line */
                for (q = 0; q < 3; q++) T[3 + q] = 0.25f * (3.0f * O[q] + S[q]);
        } else if (style == 2u) {
            /* O in the plane of the triangle (dyadic, exactly), or a few ulps off it. */
            for (q = 0; q < 9; q++) T[q] = grid();
            for (q = 0; q < 3; q++) O[q] = 0.5f * T[q] + 0.25f * T[3 + q] + 0.25f * T[6 + q];
            if (rndu() % 2u) O[rndu() % 3u] = nudge(O[rndu() % 3u], (int)(rndu() % 7u) - 3);
        } else if (style == 3u) {
            /* Sliver along a segment through the light. */
            float t = 0.2f + 0.6f * rndf(), w = powf(10.0f, -7.0f + 5.0f * rndf());
            for (q = 0; q < 3; q++) {
                T[q] = O[q] + t * (S[q] - O[q]) + rnds() * 0.3f;
                T[3 + q] = O[q] + t * (S[q] - O[q]) - rnds() * 0.3f;
            }
            for (q = 0; q < 3; q++) T[6 + q] = T[q] + rndf() * (T[3 + q] - T[q]) + rnds() * w;
        } else if (style == 4u) {
            /* O a few ulps off a random triangle's plane. */
            float u = rndf(), v = rndf() * (1.0f - u);
            for (q = 0; q < 3; q++) {
                T[q] = rnds();
                T[3 + q] = rnds();
                T[6 + q] = rnds();
            }
            for (q = 0; q < 3; q++) T[3 * 0 + 1] = 0.3f + rndf();
            for (q = 0; q < 3; q++) O[q] = T[q] + u * (T[3 + q] - T[q]) + v * (T[6 + q] - T[q]);
            O[rndu() % 3u] = nudge(O[rndu() % 3u], (int)(rndu() % 9u) - 4);
        } else {
            /* Near-coplanar neighbours: the segment O -> S nearly in the plane. */
            float t = 0.1f + 0.8f * rndf(), e = powf(10.0f, -8.0f + 6.0f * rndf());
            for (q = 0; q < 3; q++) {
                T[q] = O[q] + t * (S[q] - O[q]);
                T[3 + q] = T[q] + rnds() * 0.5f;
                T[6 + q] = O[q] + (t + 0.3f * rnds()) * (S[q] - O[q]) + rnds() * e;
            }
        }
        if (trial % 12u == 6u || trial % 12u == 11u) {
            /* The whole configuration scaled by 2^-40 or 2^30 (exact): the same answer; at
             * 2^-40 the float values underflow and every sign goes to the expansions, which
             * scale their inputs back up (pn_expansion.h). */
            float f = trial % 12u == 6u ? 0x1p-40f : 0x1p30f;
            for (q = 0; q < 3; q++) {
                O[q] *= f;
                L.c[q] *= f;
                L.U[q] *= f;
                L.V[q] *= f;
            }
            for (q = 0; q < 9; q++) T[q] *= f;
            kl = klight_from(&L, 0.0f);
        }
        pn_mask_clear(m);
        pn_tri_mask(v3(O), v3(T), v3(T + 3), v3(T + 6), &kl, m);
        {
            arb_tri at;
            arb_tri_make(&at, O, T, T + 3, T + 6);
            for (j = 0; j < kl.k; j++)
                for (i = 0; i < kl.k; i++) {
                    uint32_t bit = j * kl.k + i, a = (uint32_t)arb_tri_blocks_p(&at, O, T, &L, (int)i, (int)j);
                    uint32_t sb = pn_tri_sample(v3(O), v3(T), v3(T + 3), v3(T + 6), &kl, (int32_t)i, (int32_t)j);
                    checked++;
                    blocked += a;
                    if (mask_bit(m, bit) != a) {
                        if (diff_mask < 5)
                            fprintf(stderr, "trial %u style %u k=%d sample %u,%u: mask %u, arbiter %u\n", trial, style, L.k,
                                    i, j, mask_bit(m, bit), a);
                        diff_mask++;
                    }
                    diff_sample += sb != a;
                }
        }
        (void)set3;
    }
    fprintf(stderr,
            "triangles: %u samples, %u blocked; exact fallbacks: %lu O sides, %lu plane values, %lu edge values "
            "(arbiter: %lu big-integer values); %u mask bits and %u single samples differ from the arbiter\n",
            checked, blocked, exact_calls[0] - x0[0], exact_calls[1] - x0[1], exact_calls[2] - x0[2],
            arb_exact_calls - arb0, diff_mask, diff_sample);
    CHECK(blocked > 50000u);
    CHECK(exact_calls[0] - x0[0] > 100u);
    CHECK(exact_calls[1] - x0[1] > 100u);
    CHECK(exact_calls[2] - x0[2] > 100u);
    CHECK(diff_mask == 0u);
    CHECK(diff_sample == 0u);
}

/* ---- 2. horizons ---------------------------------------------------------------------------- */

static void test_horizons(void)
{
    uint32_t trial, diff = 0, diff_at = 0, blocked = 0, partial = 0;
    unsigned long x0 = exact_calls[3];
    for (trial = 0; trial < 8000u; trial++) {
        arb_light L;
        pn_klight kl;
        float T[9], P[3], nrm[3];
        uint32_t m[PN_MASK_WORDS_MAX], i, j, n = 0;
        pn_horizon H;
        int q, dy = trial % 2u == 0u, sgn;
        random_light(&L, dy);
        if (L.k == 1) L.k = 8, L.U[0] = 0.5f, L.V[2] = -0.5f;
        kl = klight_from(&L, 1e-4f);
        /* A vertical board whose plane passes through the light centre (exactly when dyadic,
         * or within ulps), tilted a little at random. */
        for (q = 0; q < 9; q++) T[q] = dy ? grid() : rnds();
        T[0] = L.c[0];
        T[3] = L.c[0];
        T[6] = L.c[0];
        if (!dy) {
            T[3] = nudge(T[3], (int)(rndu() % 5u) - 2);
            T[6] += rnds() * 1e-3f;
        } else if (trial % 4u == 1u) {
            T[6] += 0.125f; /* a tilted plane through the light */
        }
        {
            pn_v3 cr = pn_v3_cross(pn_v3_sub(v3(T + 3), v3(T)), pn_v3_sub(v3(T + 6), v3(T)));
            pn_v3 nn = pn_v3_normalize(cr), Pp;
            float u = rndf(), v = rndf() * (1.0f - u);
            if (cr.x == 0.0f && cr.y == 0.0f && cr.z == 0.0f) continue;
            Pp = pn_v3_add(v3(T), pn_v3_add(pn_v3_scale(pn_v3_sub(v3(T + 3), v3(T)), u),
                                              pn_v3_scale(pn_v3_sub(v3(T + 6), v3(T)), v)));
            set3(P, Pp);
            if (rndu() % 2u) nn = pn_v3_scale(nn, -1.0f);
            set3(nrm, nn);
        }
        pn_mask_clear(m);
        pn_horizon_make(v3(P), v3(nrm), v3(T), v3(T + 3), v3(T + 6), &kl, &H);
        pn_horizon_mask(&H, &kl, m);
        sgn = arb_front(P, nrm, T, T + 3, T + 6, &L);
        for (j = 0; j < kl.k; j++)
            for (i = 0; i < kl.k; i++) {
                uint32_t bit = j * kl.k + i, a = (uint32_t)arb_horizon(T, T + 3, T + 6, sgn, &L, (int)i, (int)j);
                n += a;
                if (mask_bit(m, bit) != a) {
                    if (diff < 5) fprintf(stderr, "horizon trial %u sample %u,%u: mask %u, arbiter %u\n", trial, i, j, mask_bit(m, bit), a);
                    diff++;
                }
                diff_at += pn_horizon_at(&H, &kl, pn_sample_coord((int32_t)i, kl.k), pn_sample_coord((int32_t)j, kl.k)) != a;
            }
        blocked += n;
        partial += n > 0u && n < kl.k * kl.k;
    }
    fprintf(stderr, "horizons: %u samples below, %u partly; %lu exact fallbacks; %u mask bits and %u samples differ\n",
            blocked, partial, exact_calls[3] - x0, diff, diff_at);
    CHECK(partial > 500u);
    CHECK(exact_calls[3] - x0 > 100u);
    CHECK(diff == 0u);
    CHECK(diff_at == 0u);
}

/* ---- 3. hostile random scenes ------------------------------------------------------------- */

#define SC_T 96

static void test_scenes_random(void)
{
    uint32_t scene, diff = 0, pixels = 0, blocked = 0, cull_fail = 0;
    unsigned long x0[4];
    memcpy(x0, exact_calls, sizeof(x0));
    for (scene = 0; scene < 60u; scene++) {
        float tris[SC_T * 9];
        uint32_t nt = 0, p, q;
        arb_light L;
        pn_klight kl;
        int dy = scene % 2u == 0u;
        random_light(&L, 1);
        if (L.k == 1 && scene % 3u) L.k = 16, L.U[0] = 0.5f, L.V[2] = -0.5f;
        kl = klight_from(&L, scene % 4u == 0u ? 0.0f : 1e-4f);
        /* A receiver: a 4 x 4 grid of quads (shared edges), tilted, dyadic when dy. */
        {
            float tilt = dy ? 0.125f * (float)(int)(rndu() % 5u) : 0.3f * rnds();
            uint32_t gx, gz;
            for (gz = 0; gz < 4u; gz++)
                for (gx = 0; gx < 4u; gx++) {
                    float x0 = -1.0f + 0.5f * (float)gx, z0 = -1.0f + 0.5f * (float)gz;
                    float X[4] = {x0, x0 + 0.5f, x0 + 0.5f, x0}, Z[4] = {z0, z0, z0 + 0.5f, z0 + 0.5f};
                    uint32_t c;
                    float V4[12];
                    for (c = 0; c < 4u; c++) {
                        V4[3 * c] = X[c];
                        V4[3 * c + 1] = tilt * X[c];
                        V4[3 * c + 2] = Z[c];
                    }
                    memcpy(tris + 9 * nt, V4, 9 * sizeof(float));
                    nt++;
                    memcpy(tris + 9 * nt, V4, 3 * sizeof(float));
                    memcpy(tris + 9 * nt + 3, V4 + 6, 6 * sizeof(float));
                    nt++;
                }
        }
        /* A vertical board through the light centre (its plane straddles the light). */
        {
            float b[9] = {L.c[0], 0.0f, -0.5f, L.c[0], 0.0f, 0.5f, L.c[0], 0.75f, 0.0f};
            memcpy(tris + 9 * nt, b, sizeof(b));
            nt++;
        }
        /* Occluders: a dyadic fan with shared edges, slivers, near-coplanar neighbours. */
        while (nt + 2u <= SC_T - 8u) {
            uint32_t kind = rndu() % 3u;
            float *t = tris + 9 * nt;
            if (kind == 0u) {
                for (q = 0; q < 9; q++) t[q] = grid() * 0.5f;
                for (q = 0; q < 3; q++) t[3 * q + 1] = 0.5f + fabsf(grid()) * 0.25f;
                nt++;
                /* its neighbour across edge AB */
                memcpy(t + 9, t, 6 * sizeof(float));
                for (q = 0; q < 3; q++) t[15 + q] = grid() * 0.5f;
                t[16] = 0.5f + fabsf(grid()) * 0.25f;
                nt++;
            } else if (kind == 1u) {
                float w = powf(10.0f, -7.0f + 4.0f * rndf());
                for (q = 0; q < 6; q++) t[q] = rnds();
                t[1] = 0.4f + rndf();
                t[4] = 0.4f + rndf();
                for (q = 0; q < 3; q++) t[6 + q] = t[q] + rndf() * (t[3 + q] - t[q]) + rnds() * w;
                nt++;
            } else {
                float e = powf(10.0f, -7.0f + 5.0f * rndf());
                for (q = 0; q < 9; q++) t[q] = rnds();
                for (q = 0; q < 3; q++) t[3 * q + 1] = 0.5f + 0.5f * rndf();
                nt++;
                /* neighbour sharing edge BC, nearly coplanar: its apex near the mirror of A */
                memcpy(t + 9, t + 3, 6 * sizeof(float));
                for (q = 0; q < 3; q++) t[15 + q] = t[3 + q] + t[6 + q] - t[q] + rnds() * e;
                nt++;
            }
        }
        /* Pixels: points on the receiver and on the board, with their float normals. */
        for (p = 0; p < 48u; p++) {
            uint32_t own = p % 6u == 5u ? 32u : rndu() % 32u, words = pn_mask_words(kl.k), w, t;
            const float *A = tris + 9 * own;
            float P[3], nrm[3], Of[3];
            uint32_t mk[PN_MASK_WORDS_MAX], ma[PN_MASK_WORDS_MAX];
            pn_v3 O;
            pn_horizon H;
            float u = rndf(), v = rndf() * (1.0f - u);
            pn_v3 nn = pn_v3_normalize(pn_v3_cross(pn_v3_sub(v3(A + 3), v3(A)), pn_v3_sub(v3(A + 6), v3(A))));
            set3(P, pn_v3_add(v3(A), pn_v3_add(pn_v3_scale(pn_v3_sub(v3(A + 3), v3(A)), u),
                                                 pn_v3_scale(pn_v3_sub(v3(A + 6), v3(A)), v))));
            if (p % 7u == 0u) set3(P, v3(A + 3)); /* on a vertex shared by six triangles */
            set3(nrm, nn);
            if (!pn_shadow_origin(v3(P), v3(nrm), &kl, &O)) continue;
            set3(Of, O);
            pn_mask_clear(mk);
            pn_horizon_make(v3(P), v3(nrm), v3(A), v3(A + 3), v3(A + 6), &kl, &H);
            pn_horizon_mask(&H, &kl, mk);
            for (t = 0; t < nt; t++)
                if (t != own) pn_tri_mask(O, v3(tris + 9 * t), v3(tris + 9 * t + 3), v3(tris + 9 * t + 6), &kl, mk);
            arb_pixel_mask(P, nrm, Of, own, tris, nt, &L, ma, words);
            pixels++;
            for (w = 0; w < words; w++) {
                uint32_t d = (mk[w] ^ ma[w]) & (kl.k * kl.k >= 32u ? 0xFFFFFFFFu : ((1u << (kl.k * kl.k)) - 1u));
                if (d && diff < 5) fprintf(stderr, "scene %u pixel %u word %u: kernel %08x arbiter %08x\n", scene, p, w, mk[w], ma[w]);
                diff += pn_kpopcount(d);
                blocked += pn_kpopcount(ma[w]);
            }
            /* The reference's cull: every triangle that blocks a sample (arbiter) must pass
             * the frustum test of its box. */
            {
                pn_frustum fr;
                pn_frustum_make(O, &kl, &fr);
                for (t = 0; t < nt; t++) {
                    const float *a = tris + 9 * t;
                    int s0, i, j, any = 0;
                    if (t == own) continue;
                    s0 = arb_side_O(Of, a, a + 3, a + 6);
                    if (!arb_tri_may_block(a, a + 3, a + 6, &L, s0)) continue;
                    arb_tri at;
                    arb_tri_make(&at, Of, a, a + 3, a + 6);
                    for (j = 0; j < L.k && !any; j++)
                        for (i = 0; i < L.k && !any; i++) any = arb_tri_blocks_p(&at, Of, a, &L, i, j);
                    if (any && !pn_frustum_aabb(&fr,
                                                pn_v3_make(fminf(a[0], fminf(a[3], a[6])), fminf(a[1], fminf(a[4], a[7])),
                                                           fminf(a[2], fminf(a[5], a[8]))),
                                                pn_v3_make(fmaxf(a[0], fmaxf(a[3], a[6])), fmaxf(a[1], fmaxf(a[4], a[7])),
                                                           fmaxf(a[2], fmaxf(a[5], a[8])))))
                        cull_fail++;
                }
            }
        }
    }
    fprintf(stderr,
            "random scenes: %u pixels, %u blocked bits; exact fallbacks %lu/%lu/%lu/%lu (O side, plane, edge, "
            "horizon); %u bits differ from the arbiter; %u blocking triangles culled\n",
            pixels, blocked, exact_calls[0] - x0[0], exact_calls[1] - x0[1], exact_calls[2] - x0[2],
            exact_calls[3] - x0[3], diff, cull_fail);
    CHECK(pixels > 800u);
    CHECK(blocked > 10000u);
    CHECK(diff == 0u);
    CHECK(cull_fail == 0u);
}

#endif

/* ---- 4. frames of the built-in scenes and spot.glb --------------------------------------- */

static int render_algo(pn_context *ctx, const pn_test_scene *s, const pn_light *light, pn_algo algo, uint32_t w,
                       uint32_t hh, uint32_t k, pn_frame *fr)
{
    pn_frame_options opt;
    pn_frame_options_default(&opt);
    opt.width = w;
    opt.height = hh;
    opt.k = k;
    opt.eps = s->eps;
    opt.algo = algo;
    if (pn_render(ctx, &s->camera, light, &opt, fr) != PN_OK) {
        fprintf(stderr, "render %s: %s\n", s->name, pn_last_error(ctx));
        return 1;
    }
    return 0;
}

static void frame_vs_arbiter(const char *name, const pn_test_scene *s, const pn_light *light, uint32_t w, uint32_t hh,
                             uint32_t k)
{
    static const pn_algo algos[3] = {PN_ALGO_REFERENCE, PN_ALGO_GEARS, PN_ALGO_RAYTRACE};
    static const char *anames[3] = {"reference", "GEARS", "raytrace"};
    pn_test_host h;
    size_t n = (size_t)w * hh, px;
    float *arb_vis = (float *)malloc(n * sizeof(float)), *tris = (float *)malloc((size_t)s->mesh.triangle_count * 36u);
    uint32_t t, bits_diff = 0, shadowed = 0, horizon_bits = 0, a;
    arb_light L;
    pn_klight kl;
    pn_frame fr;
    clock_t c0 = clock();
    REQUIRE(arb_vis && tris);
    for (t = 0; t < s->mesh.triangle_count; t++) {
        uint32_t c;
        for (c = 0; c < 3u; c++) memcpy(tris + 9u * t + 3u * c, s->mesh.positions + 3u * s->mesh.indices[3u * t + c], 12);
    }
    memcpy(L.c, light->center, 12);
    memcpy(L.U, light->u, 12);
    memcpy(L.V, light->v, 12);
    L.k = (light->u[0] == 0.0f && light->u[1] == 0.0f && light->u[2] == 0.0f) ? 1 : (int)k;
    kl = klight_from(&L, s->eps);
    REQUIRE(pn_test_open(&h, s->mesh.triangle_count, w, hh) == 0);
    REQUIRE(pn_scene_set(h.ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) == PN_OK);
    REQUIRE(render_algo(h.ctx, s, light, PN_ALGO_REFERENCE, w, hh, k, &fr) == 0);
    for (px = 0; px < n; px++) {
        /* (a point light: k = 1 for the arbiter and the kernel, as the library sets it) */
        float P[3], nrm[3], Of[3];
        uint32_t own = fr.tri_id[px], ma[PN_MASK_WORDS_MAX], mk[PN_MASK_WORDS_MAX], words = pn_mask_words(kl.k), wd;
        pn_v3 O;
        pn_horizon H;
        if (own == PN_NO_TRIANGLE) {
            arb_vis[px] = 1.0f;
            continue;
        }
        memcpy(P, fr.position + 3 * px, 12);
        memcpy(nrm, fr.normal + 3 * px, 12);
        if (!pn_shadow_origin(v3(P), v3(nrm), &kl, &O)) {
            arb_vis[px] = 0.0f;
            continue;
        }
        set3(Of, O);
        arb_pixel_mask(P, nrm, Of, own, tris, s->mesh.triangle_count, &L, ma, words);
        /* The kernel's brute-force mask of the same pixel, bit for bit. */
        pn_mask_clear(mk);
        pn_horizon_of(v3(P), v3(nrm), own, tris, &kl, &H);
        pn_horizon_mask(&H, &kl, mk);
        horizon_bits += pn_mask_count(mk, kl.k);
        /* (triangles the arbiter's exact box test rules out are left out of both: on a
         * 60k-triangle scene they are most of the time and none of the interest) */
        for (t = 0; t < s->mesh.triangle_count; t++)
            if (t != own && !arb_box_out(Of, tris + 9 * t, &L))
                pn_tri_mask(O, v3(tris + 9 * t), v3(tris + 9 * t + 3), v3(tris + 9 * t + 6), &kl, mk);
        for (wd = 0; wd < words; wd++) bits_diff += pn_kpopcount(mk[wd] ^ ma[wd]);
        arb_vis[px] = pn_mask_visibility(ma, kl.k);
        shadowed += arb_vis[px] < 1.0f;
    }
    fprintf(stderr,
            "%s (%u triangles) k=%u %ux%u: %u shadowed pixels, %u horizon bits, %u kernel mask bits differ from the "
            "arbiter\n",
            name, s->mesh.triangle_count, kl.k, w, hh, shadowed, horizon_bits, bits_diff);
    fprintf(stderr, "  (arbiter and kernel brute force: %.1f s cpu)\n", (double)(clock() - c0) / CLOCKS_PER_SEC);
    CHECK(shadowed > 0u);
    CHECK_MSG(bits_diff == 0u, "%s", name);
    for (a = 0; a < 3u; a++) {
        uint32_t d = 0;
        REQUIRE(render_algo(h.ctx, s, light, algos[a], w, hh, k, &fr) == 0);
        for (px = 0; px < n; px++) d += memcmp(&arb_vis[px], &fr.visibility[px], sizeof(float)) != 0;
        fprintf(stderr, "  %s: %u pixels differ from the arbiter\n", anames[a], d);
        CHECK_MSG(d == 0u, "%s %s", name, anames[a]);
    }
    pn_test_close(&h);
    free(arb_vis);
    free(tris);
}

#if !PN_TEST_MODELS
static void test_frames(void)
{
    static const char *builtins[4] = {"square", "spheres", "elongated-cube", "thin"};
    pn_test_scene s;
    int i;
    for (i = 0; i < 4; i++) {
        pn_light pt;
        REQUIRE(pn_test_scene_load(&s, builtins[i]) == 0);
        /* spheres has 62k triangles, most of them inside the light's hull: smaller */
        frame_vs_arbiter(builtins[i], &s, &s.light, i == 1 ? 16u : 32u, i == 1 ? 16u : 32u, 8);
        pt = s.light;
        memset(pt.u, 0, sizeof(pt.u));
        memset(pt.v, 0, sizeof(pt.v));
        frame_vs_arbiter(builtins[i], &s, &pt, 24, 24, 4); /* the library takes k = 4, uses 1 */
        pn_test_scene_free(&s);
    }
}
#else
static void test_frames_spot(void)
{
    pn_test_scene s;
    REQUIRE(pn_test_scene_load_tools(&s, PN_SCENES_DIR "/spot.glb", 0, -1) == 0);
    frame_vs_arbiter("spot.glb", &s, &s.light, 24, 20, 4);
    {
        pn_light big = s.light; /* a large, low light: the ground's plane nearer the light */
        big.u[0] *= 6.0f;
        big.v[2] *= 3.0f;
        big.center[1] -= 0.4f * s.diag;
        frame_vs_arbiter("spot.glb big light", &s, &big, 24, 20, 8);
    }
    pn_test_scene_free(&s);
}
#endif

/* ---- how often the exact arithmetic runs (a measurement, not a test) ---------------------
 * PN_EXACT_COUNT=1 ./test_exact builtin... (square, spheres, elongated-cube, thin, room), or
 * ./test_exact_models [scene.glb|builtin]... (any file the tools load, any of their
 * built-ins): for each scene at 64x64, k = 16,
 * the reference's predicate calls (every triangle whose box passes the pixel's frustum, in
 * BVH-free order, stopping at a full mask as the reference does) with the counts of values
 * and of distinct (pixel, sample) pairs that reached the exact fallback. */
static int count_load(pn_test_scene *s, const char *src)
{
#if PN_TEST_MODELS
    return pn_test_scene_load_tools(s, src, strchr(src, '/') == NULL, -1);
#else
    if (strchr(src, '/') != NULL) {
        fprintf(stderr, "%s: files load through the tools: PN_EXACT_COUNT=1 test_exact_models %s\n", src, src);
        return 1;
    }
    return pn_test_scene_load(s, src);
#endif
}

static void count_scene(const char *src)
{
    pn_test_scene s;
    pn_test_host h;
    pn_frame fr;
    uint32_t w = 64, hh = 64, k = 16, t, lit = 0;
    size_t px;
    unsigned long x0[4], samples_exact = 0, calls = 0;
    float *tris;
    arb_light L;
    pn_klight kl;
    REQUIRE(count_load(&s, src) == 0);
    tris = (float *)malloc((size_t)s.mesh.triangle_count * 36u);
    REQUIRE(tris);
    for (t = 0; t < s.mesh.triangle_count; t++) {
        uint32_t c;
        for (c = 0; c < 3u; c++) memcpy(tris + 9u * t + 3u * c, s.mesh.positions + 3u * s.mesh.indices[3u * t + c], 12);
    }
    memcpy(L.c, s.light.center, 12);
    memcpy(L.U, s.light.u, 12);
    memcpy(L.V, s.light.v, 12);
    L.k = (int)k;
    kl = klight_from(&L, s.eps);
    REQUIRE(pn_test_open(&h, s.mesh.triangle_count, w, hh) == 0);
    REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    REQUIRE(render_algo(h.ctx, &s, &s.light, PN_ALGO_REFERENCE, w, hh, k, &fr) == 0);
    {
        pn_stats st;
        REQUIRE(pn_get_stats(h.ctx, &st) == PN_OK);
        kl.cull_tol = st.cull_tol;
    }
    memcpy(x0, exact_calls, sizeof(x0));
    for (px = 0; px < (size_t)w * hh; px++) {
        uint32_t own = fr.tri_id[px], m[PN_MASK_WORDS_MAX];
        pn_v3 O, P = v3(fr.position + 3 * px), N = v3(fr.normal + 3 * px);
        pn_horizon H;
        pn_frustum fu;
        unsigned long before;
        if (own == PN_NO_TRIANGLE || !pn_shadow_origin(P, N, &kl, &O)) continue;
        lit++;
        pn_mask_clear(m);
        before = exact_calls[1] + exact_calls[2] + exact_calls[3];
        pn_horizon_of(P, N, own, tris, &kl, &H);
        pn_horizon_mask(&H, &kl, m);
        pn_frustum_make(O, &kl, &fu);
        for (t = 0; t < s.mesh.triangle_count && !pn_mask_full(m, k); t++) {
            const float *a = tris + 9 * t;
            if (t == own ||
                !pn_frustum_aabb(&fu, pn_v3_make(fminf(a[0], fminf(a[3], a[6])), fminf(a[1], fminf(a[4], a[7])), fminf(a[2], fminf(a[5], a[8]))),
                                 pn_v3_make(fmaxf(a[0], fmaxf(a[3], a[6])), fmaxf(a[1], fmaxf(a[4], a[7])), fmaxf(a[2], fmaxf(a[5], a[8])))))
                continue;
            calls++;
            pn_tri_mask(O, v3(a), v3(a + 3), v3(a + 6), &kl, m);
        }
        samples_exact += exact_calls[1] + exact_calls[2] + exact_calls[3] - before;
    }
    fprintf(stderr,
            "count %s 64x64 k=16: %u lit pixels (%u samples), %lu predicate calls; exact fallbacks: %lu O sides, %lu "
            "plane values, %lu edge values, %lu horizon values (%.2e exact values per light sample)\n",
            s.name, lit, lit * k * k, calls, exact_calls[0] - x0[0], exact_calls[1] - x0[1], exact_calls[2] - x0[2],
            exact_calls[3] - x0[3], (double)samples_exact / ((double)lit * k * k));
    pn_test_close(&h);
    free(tris);
    pn_test_scene_free(&s);
}

int main(int argc, char **argv)
{
    if (getenv("PN_EXACT_COUNT")) {
        int i;
        for (i = 1; i < argc; i++) count_scene(argv[i]);
        return 0;
    }
    clock_t t0 = clock();
#if PN_TEST_MODELS
    RUN(test_frames_spot);
    fprintf(stderr, "  (%.1f s cpu)\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
#else
    RUN(test_triangles);
    fprintf(stderr, "  (%.1f s cpu)\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
    RUN(test_horizons);
    fprintf(stderr, "  (%.1f s cpu)\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
    RUN(test_scenes_random);
    fprintf(stderr, "  (%.1f s cpu)\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
    RUN(test_frames);
    fprintf(stderr, "  (%.1f s cpu)\n", (double)(clock() - t0) / CLOCKS_PER_SEC);
#endif
    fprintf(stderr, "arbiter: %lu values needed the big integers\n", arb_exact_calls);
    return pn_test_summary();
}
