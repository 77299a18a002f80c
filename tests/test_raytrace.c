/* PN_ALGO_RAYTRACE: k^2 single rays per pixel give the reference's bits.
 *
 * 1. Predicate: for random triangles (every scale, nearly edge-on, straddling the light
 *    plane and O's plane, slivers, segments exactly through a vertex), every bit of
 *    pn_tri_mask() equals pn_tri_sample() for that sample, for k = 4, 8, 16, 32 and a
 *    point light. This pins the mask's row narrowing and band classification to the
 *    per-sample definition: any shortcut that changes one bit fails here (both are exact,
 *    tests/test_exact.c compares them with an exact arbiter).
 * 2. The per-ray filter (kernels/pn_raytrace.h): on hostile triangles (random, edge-on,
 *    slivers, segments exactly through a vertex or along an edge, pairs sharing an edge the
 *    segment crosses, triangles a hair from O or from the light plane (both ends of the
 *    segment), dyadic coordinates with exact degeneracies, O a few ulps off the
 *    plane, tiny and huge scales, far from the origin) and lights of any orientation,
 *    pn_ray_tri() equals pn_tri_sample() for every sample, with its bound taken from the
 *    triangle's own box and from a larger one (a BVH leaf's); the slab test never rejects
 *    the box of a triangle that blocks; the fallbacks to pn_tri_sample are counted. And
 *    pn_tri_block (a few open samples: a ray each, from a cache the trials share) sets the
 *    same bits and returns the same answer as pn_tri_mask_in from the same partial mask.
 * 3. Frames: the raytraced visibility buffer is byte-identical to the reference's on the
 *    built-in scenes and spot.glb, area and point light. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
/* Counts the values the filter leaves to the exact arithmetic (coverage of that path). */
static unsigned long exact_calls[4];
#define PN_EXACT_HOOK(kind) (exact_calls[kind]++)
/* ...and the triangles the ray filter leaves to pn_tri_sample (kind 0) or its plane test
 * (kind 1). */
static unsigned long ray_fallbacks, ray_plane_fallbacks;
#define PN_RAY_FALLBACK_HOOK(kind) ((kind) ? ray_plane_fallbacks++ : ray_fallbacks++)
#include "pn_raytrace.h"
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

/* ---- 2. the per-ray filter ------------------------------------------------------------ */

static pn_v3 rnd3(void) { return pn_v3_make(rnds(), rnds(), rnds()); }

/* A light of any orientation and aspect around c (k = 1: a point light). */
static pn_klight any_light(pn_v3 c, float size, uint32_t k)
{
    pn_klight L;
    memset(&L, 0, sizeof(L));
    L.c[0] = c.x;
    L.c[1] = c.y;
    L.c[2] = c.z;
    if (k > 1u) {
        pn_v3 a = pn_v3_normalize(rnd3()), r = rnd3(), N, U, V;
        if (!(pn_v3_dot(a, a) > 0.5f)) a = pn_v3_make(1, 0, 0);
        N = pn_v3_normalize(pn_v3_cross(a, r));
        if (!(pn_v3_dot(N, N) > 0.5f)) N = pn_v3_normalize(pn_v3_cross(a, pn_v3_make(a.y, a.z, a.x + 1.0f)));
        U = pn_v3_scale(a, size * (0.1f + rndf()));
        V = pn_v3_scale(pn_v3_normalize(pn_v3_cross(N, a)), size * (0.02f + rndf()));
        N = pn_v3_normalize(pn_v3_cross(U, V));
        L.U[0] = U.x; L.U[1] = U.y; L.U[2] = U.z;
        L.V[0] = V.x; L.V[1] = V.y; L.V[2] = V.z;
        L.N[0] = N.x; L.N[1] = N.y; L.N[2] = N.z;
    } else {
        L.is_point = 1u;
    }
    L.k = k;
    L.cull_tol = 1e-5f * size;
    return L;
}

/* The float sample point as a caller would aim at it. */
static pn_v3 sample_point(const pn_klight *L, uint32_t i, uint32_t j)
{
    return pn_v3_add(pn_v3_add(pn_light_c(L), pn_v3_scale(pn_light_U(L), pn_sample_coord((int32_t)i, L->k))),
                     pn_v3_scale(pn_light_V(L), pn_sample_coord((int32_t)j, L->k)));
}

static void tri_box(const float *T, float grow, float *lo, float *hi)
{
    int q;
    for (q = 0; q < 3; q++) {
        float a = pn_kminf(T[q], pn_kminf(T[3 + q], T[6 + q])), b = pn_kmaxf(T[q], pn_kmaxf(T[3 + q], T[6 + q]));
        lo[q] = a - grow * (b - a + 1e-3f * (a < 0.0f ? -a : a));
        hi[q] = b + grow * (b - a + 1e-3f * (b < 0.0f ? -b : b));
        if (lo[q] > a) lo[q] = a; /* grow * huge could round the wrong way: keep the box around T */
        if (hi[q] < b) hi[q] = b;
    }
}

typedef struct ray_stats {
    unsigned long tests, blocked, disagree, cull_misses;
    unsigned long block_tests, block_rays, block_hits, block_disagree; /* pn_tri_block */
} ray_stats;

/* Every sample of triangle T seen from O: pn_ray_tri (bounds from T's box, from a box
 * `grow` times larger as a leaf's, and the scene bound from that box as the scene's)
 * against pn_tri_sample; the slab test against T's box. */
static void ray_check(pn_v3 O, const float *T, const pn_klight *L, float grow, ray_stats *st)
{
    pn_ray_origin X;
    pn_v3 A = pn_v3_make(T[0], T[1], T[2]), B = pn_v3_make(T[3], T[4], T[5]), C = pn_v3_make(T[6], T[7], T[8]);
    float lo[3], hi[3], blo[3], bhi[3];
    uint32_t i, j;
    tri_box(T, 0.0f, lo, hi);
    tri_box(T, grow, blo, bhi);
    pn_ray_origin_make(O, L, blo, bhi, &X);
    for (j = 0; j < L->k; j++)
        for (i = 0; i < L->k; i++) {
            pn_ray R;
            float tn;
            uint32_t want = pn_tri_sample(O, A, B, C, L, (int32_t)i, (int32_t)j), got0, got1, got2;
            pn_ray_make(&X, L, (int32_t)i, (int32_t)j, &R);
            got0 = pn_ray_tri(&R, L, T, pn_ray_bound(&R, lo, hi));
            got1 = pn_ray_tri(&R, L, T, pn_ray_bound(&R, blo, bhi));
            got2 = pn_ray_tri(&R, L, T, R.ebr);
            st->tests += 3u;
            st->blocked += want;
            if (got0 != want || got1 != want || got2 != want) {
                if (st->disagree < 5u)
                    fprintf(stderr, "ray filter: O (%a %a %a) T (%a %a %a, %a %a %a, %a %a %a) k %u sample %u,%u: "
                                    "pn_tri_sample %u, pn_ray_tri %u (own box) %u (grown) %u (scene)\n",
                            O.x, O.y, O.z, T[0], T[1], T[2], T[3], T[4], T[5], T[6], T[7], T[8], L->k, i, j, want, got0,
                            got1, got2);
                st->disagree++;
            }
            if (want && !pn_ray_box(&R, lo, hi, &tn)) st->cull_misses++;
        }
    /* pn_tri_block (the reference's and GEARS' per-triangle step) against pn_tri_mask_in
     * from the same partial mask: up to 2 PN_REF_RAYS draws of an open sample (rays up to
     * PN_REF_RAYS open, the forms beyond), the rest blocked; the same bits and answer. */
    {
        uint32_t trial, n = L->k * L->k;
        pn_ray_cache RC; /* shared by the trials, as by a pixel's triangles */
        pn_ray_cache_clear(&RC);
        for (trial = 0; trial < 4u; trial++) {
            uint32_t m1[PN_MASK_WORDS_MAX], m2[PN_MASK_WORDS_MAX], w, q, h1, h2;
            uint32_t open = 1u + (uint32_t)(rndf() * (float)(2u * PN_REF_RAYS));
            pn_rect full = pn_rect_full(L->k);
            pn_mask_clear(m1);
            for (q = 0; q < n; q++) m1[q >> 5] |= 1u << (q & 31u);
            for (q = 0; q < open && q < n; q++) {
                uint32_t b = (uint32_t)(rndf() * (float)n) % n;
                m1[b >> 5] &= ~(1u << (b & 31u));
            }
            memcpy(m2, m1, sizeof(m1));
            st->block_rays += n - pn_mask_count(m1, L->k) <= PN_REF_RAYS;
            {
                int32_t si[PN_REF_RAYS], sj[PN_REF_RAYS];
                uint32_t nf = pn_rect_few(m1, L->k, full, PN_REF_RAYS, si, sj);
                h1 = pn_tri_block(O, A, B, C, T, L, &X, &RC, m1, full, nf, si, sj);
            }
            h2 = pn_tri_mask_in(O, A, B, C, L, m2, full.i0, full.i1, full.j0, full.j1);
            st->block_tests++;
            st->block_hits += h2;
            for (w = 0; w < PN_MASK_WORDS_MAX; w++)
                if (m1[w] != m2[w]) h1 = 2u;
            if (h1 != h2) st->block_disagree++;
        }
    }
}

static void nudge_vertex(float *P, int ulps)
{
    int q;
    for (q = 0; q < 3; q++) {
        int n = ulps;
        while (n > 0) { P[q] = nextafterf(P[q], INFINITY); n--; }
        while (n < 0) { P[q] = nextafterf(P[q], -INFINITY); n++; }
    }
}

static void put(float *T, int v, pn_v3 P)
{
    T[3 * v] = P.x;
    T[3 * v + 1] = P.y;
    T[3 * v + 2] = P.z;
}
static pn_v3 vtx(const float *T, int v) { return pn_v3_make(T[3 * v], T[3 * v + 1], T[3 * v + 2]); }
/* A + s (B - A) + t (C - A): a point of T's plane (exactly, on dyadic coordinates). */
static pn_v3 in_plane(const float *T, float s, float t)
{
    pn_v3 A = vtx(T, 0);
    return pn_v3_add(A, pn_v3_add(pn_v3_scale(pn_v3_sub(vtx(T, 1), A), s), pn_v3_scale(pn_v3_sub(vtx(T, 2), A), t)));
}

static void test_ray_filter(void)
{
    static const uint32_t ks[5] = {1, 4, 8, 16, 32};
    static const float scales[6] = {1.0f, 1.0f, 1e-6f, 1e5f, 9.094947e-13f /* 2^-40 */, 1.0f};
    ray_stats st = {0, 0, 0, 0, 0, 0, 0, 0};
    unsigned long fb0 = ray_fallbacks, pf0 = ray_plane_fallbacks, pairs_blocked = 0;
    uint32_t trial;
    for (trial = 0; trial < 12000u; trial++) {
        uint32_t k = ks[trial % 5u], style = trial / 5u % 10u, si, sj, q;
        float scale = scales[trial / 45u % 6u];
        /* Far from the origin for one scale in six: the rounding of every difference grows. */
        pn_v3 off = (trial / 45u % 6u) == 5u ? pn_v3_scale(rnd3(), 3e4f) : pn_v3_make(0, 0, 0);
        pn_klight L = any_light(pn_v3_add(off, pn_v3_scale(rnd3(), scale)), scale * (0.05f + rndf()), k);
        pn_v3 N = L.is_point ? pn_v3_normalize(rnd3()) : pn_v3_make(L.N[0], L.N[1], L.N[2]);
        pn_v3 O = pn_v3_add(pn_light_c(&L),
                            pn_v3_scale(pn_v3_add(N, pn_v3_scale(rnd3(), 0.7f)), scale * (0.2f + 2.0f * rndf())));
        float size = scale * powf(10.0f, -4.0f + 4.5f * rndf()), T[9], T2[9], h = 0.05f + 0.9f * rndf();
        /* Style 9: at either end of the segment, a hair from O or from the light plane. */
        if (style == 9) h = rndf() < 0.5f ? 1.0f - powf(10.0f, -1.0f - 6.0f * rndf()) : powf(10.0f, -1.0f - 6.0f * rndf());
        pn_v3 S, X, d;
        si = (uint32_t)(rndf() * (float)k) % k;
        sj = (uint32_t)(rndf() * (float)k) % k;
        S = sample_point(&L, si, sj);
        X = pn_v3_add(O, pn_v3_scale(pn_v3_sub(S, O), h)); /* on (or a rounding off) segment (O, S_ij) */
        for (q = 0; q < 3; q++) put(T, (int)q, pn_v3_add(X, pn_v3_scale(rnd3(), size)));
        d = pn_v3_scale(rnd3(), size);
        switch (style) {
        case 0: /* random around the segment, up to 30 times larger */
            put(T, 2, pn_v3_add(X, pn_v3_scale(rnd3(), size * 30.0f)));
            break;
        case 1: /* edge-on: C near the plane through O, A, B */
            d = pn_v3_add(pn_v3_scale(pn_v3_sub(vtx(T, 0), O), rnds() * 0.5f), pn_v3_scale(rnd3(), size * 1e-5f));
            put(T, 2, pn_v3_add(vtx(T, 0), d));
            break;
        case 2: /* sliver: C near edge AB */
            put(T, 2, pn_v3_add(pn_v3_add(vtx(T, 0), pn_v3_scale(pn_v3_sub(vtx(T, 1), vtx(T, 0)), rndf())),
                                pn_v3_scale(rnd3(), size * 1e-4f)));
            break;
        case 3: /* the segment through vertex A */
            put(T, 0, X);
            break;
        case 4: /* the segment through edge AB (X on it, up to rounding), and a second
                 * triangle ABD on the other side of the edge: a shared edge */
            put(T, 0, pn_v3_add(X, d));
            put(T, 1, pn_v3_sub(X, d));
            break;
        case 5: /* dyadic coordinates: exact degeneracies (O in the plane, samples on edges) */
            for (q = 0; q < 3; q++)
                put(T, (int)q, pn_v3_add(off, pn_v3_scale(pn_v3_make((float)((int)(rndf() * 17.0f) - 8),
                                                                     (float)((int)(rndf() * 17.0f) - 8),
                                                                     (float)((int)(rndf() * 17.0f) - 8)),
                                                          0.125f * scale)));
            if (rndf() < 0.5f) O = in_plane(T, 0.5f, -0.25f);
            break;
        case 6: /* O a few ulps off the triangle's plane */
            O = in_plane(T, 0.3f, 0.4f);
            O.x = nextafterf(O.x, rndf() < 0.5f ? INFINITY : -INFINITY);
            break;
        case 7: /* a vertex a few ulps from the segment through it */
            put(T, 0, X);
            nudge_vertex(T, (int)(rndf() * 7.0f) - 3);
            break;
        case 9: /* small, at an end of the segment (h above), or A at the sample point, or the
                 * whole triangle on the light plane (up to rounding) around the sample */
            d.x = rndf();
            if (d.x < 0.3f) put(T, 0, S);
            if (d.x > 0.6f && !L.is_point)
                for (q = 0; q < 3; q++)
                    put(T, (int)q, pn_v3_add(pn_v3_add(pn_light_c(&L), pn_v3_scale(pn_light_U(&L), 1.2f * rnds())),
                                             pn_v3_scale(pn_light_V(&L), 1.2f * rnds())));
            break;
        default: /* huge triangle around the segment, vertices far away */
            put(T, 2, pn_v3_add(X, pn_v3_scale(rnd3(), size * 1e4f)));
            put(T, 1, pn_v3_add(X, pn_v3_scale(rnd3(), size * 1e3f)));
            break;
        }
        ray_check(O, T, &L, (float)(trial % 4u) * 0.75f, &st);
        if (style == 4) {
            /* BAD, D mirroring C through the edge's midpoint X: the two flank the edge. */
            put(T2, 0, vtx(T, 1));
            put(T2, 1, vtx(T, 0));
            put(T2, 2, pn_v3_sub(pn_v3_scale(X, 2.0f), vtx(T, 2)));
            {
                unsigned long b0 = st.blocked;
                ray_check(O, T2, &L, 1.5f, &st);
                pairs_blocked += st.blocked - b0;
            }
        }
    }
    fprintf(stderr,
            "ray filter vs pn_tri_sample: %lu tests, %lu blocked (%lu by shared-edge partners), %lu to pn_tri_sample "
            "(%.3g%%), %lu to its plane test (%.3g%% of the blocked), %lu disagreements, %lu blocked samples culled\n",
            st.tests, st.blocked, pairs_blocked, ray_fallbacks - fb0,
            100.0 * (double)(ray_fallbacks - fb0) / (double)(st.tests ? st.tests : 1u), ray_plane_fallbacks - pf0,
            100.0 * (double)(ray_plane_fallbacks - pf0) / (double)(st.blocked ? st.blocked : 1u), st.disagree,
            st.cull_misses);
    CHECK(st.blocked > 100000u);
    CHECK(pairs_blocked > 1000u);
    CHECK(ray_fallbacks - fb0 > 1000u); /* coverage: the hostile cases must reach the fallbacks */
    CHECK(ray_plane_fallbacks - pf0 > 100u);
    CHECK(st.disagree == 0u);
    CHECK(st.cull_misses == 0u);
    CHECK_MSG(st.block_disagree == 0u, "pn_tri_block differs from pn_tri_mask_in %lu times of %lu", st.block_disagree,
              st.block_tests);
    /* not vacuous: many masks decided by rays, many by the forms, and many blocked samples */
    CHECK_MSG(st.block_rays > 1000u && st.block_tests - st.block_rays > 1000u && st.block_hits > 1000u,
              "pn_tri_block: %lu tests, %lu by rays, %lu blocking",
              st.block_tests, st.block_rays, st.block_hits);
}

/* ---- 3. frames ------------------------------------------------------------------------ */

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
    RUN(test_ray_filter);
    RUN(test_frames);
    return pn_test_summary();
}
