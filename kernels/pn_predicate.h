/* pn_predicate.h - the one definition of "light sample blocked" (DESIGN.md invariant 6).
 *
 * Sample (i, j) of k x k is the exact point S = c + a_i U + b_j V with a_i = (2i+1)/k - 1
 * (exact in float for k a power of two). It is blocked from the shadow-ray origin O when
 *
 *   horizon: S lies on or behind the plane of P's own triangle, on the side away from the
 *           geometric normal turned toward the light centre (it cannot light the front
 *           face; pn_horizon_*), or
 *   a triangle ABC other than P's own meets the open segment (O, S):
 *   plane:  O and S lie strictly on opposite sides of the triangle's plane, i.e. the
 *           segment crosses it at some t in (0, 1). A triangle part behind O or behind the
 *           sample can never be crossed by (O, S);
 *   edges:  the three triple products (S - O) . ((P1 - O) x (P2 - P1)) over the edges
 *           P1P2 all have the same sign (zero counts as either). This is the edge-function
 *           test of the triangle projected from O onto the light plane, written without
 *           the division so that no vertex needs to be projected to infinity.
 *
 * Every sign is the sign of the exact real value for the float inputs ("undecided" never
 * means "lit"). Each value is first a linear form in (a_i, b_j), h(i, j) = (h0 + b_j*hv) +
 * a_i*hu, evaluated in float in exactly that order, with a rigorous bound on its rounding
 * (the filter); only where the float value lies within its bound is the sign computed
 * again exactly from the float inputs (pn_expansion.h: Shewchuk's expansion arithmetic,
 * float only). The bounds cover every sample of the grid at once, so the fast path is the
 * old one: the rows where a form can pass are found by walking the float form itself, and
 * every sample of them is classified in one branch-free, vectorizable loop (pn_row_bits)
 * as certainly blocked, certainly not, or in a band; band samples are decided exactly one
 * by one (pn_tri_resolve).
 *
 * Consequences, relied on below and by GEARS and the culls:
 *   - watertight: an edge's value is formed from its endpoints in canonical
 *     (lexicographic) order, so the two triangles sharing it see the very same real number
 *     with opposite signs; its exact zero counts as inside for both, so a segment through
 *     a shared edge can never slip between them;
 *   - real geometry: a blocked sample's exact segment really crosses the closed triangle,
 *     so every cull needs slack only for its own rounding (pn_reference.h, pn_gears.h);
 *   - one answer: pn_tri_mask() (a whole pixel) and pn_tri_sample() (one ray) both return
 *     the exact answer, so they agree bit for bit (tests/test_raytrace.c), and both agree
 *     with an independent exact arbiter (tests/test_exact.c).
 * A point light is the case k = 1, U = V = 0. */
#ifndef PN_PREDICATE_H
#define PN_PREDICATE_H

#include "pn_expansion.h"
#include "pn_kmath.h"
#include "pn_ktypes.h"

/* Counting hook for tests and benchmarks: called once per value whose sign the filter
 * leaves to the exact arithmetic (kind 0 O's side, 1 a sample's side, 2 an edge value,
 * 3 the horizon). The library compiles it away. */
#ifndef PN_EXACT_HOOK
#define PN_EXACT_HOOK(kind) ((void)0)
#endif

/* ---- Linear forms over the sample grid ------------------------------------------------ */

typedef struct pn_lin {
    float h0, hu, hv;
} pn_lin;

/* (2i + 1) / k - 1. k is a power of two, so 1 / k and the product are exact: the same
 * float as the quotient, and a reciprocal a loop over samples computes once. */
PN_KFN float pn_sample_coord(int32_t i, uint32_t k)
{
    return (float)(2 * i + 1) * (1.0f / (float)k) - 1.0f;
}

PN_KFN pn_lin pn_lin_neg(pn_lin a)
{
    /* Round-to-nearest is symmetric, so evaluating the negated form gives exactly the
     * negated value. */
    pn_lin r;
    r.h0 = -a.h0;
    r.hu = -a.hu;
    r.hv = -a.hv;
    return r;
}

/* Canonical (lexicographic) endpoints of edge P1P2: *a, *b, and 1 if they are swapped. */
PN_KFN int pn_edge_canon(pn_v3 P1, pn_v3 P2, pn_v3 *a, pn_v3 *b)
{
    int flip = pn_v3_less(P2, P1);
    *a = flip ? P2 : P1;
    *b = flip ? P1 : P2;
    return flip;
}

/* Edge form of edge P1P2 seen from O; positive on the left of P1 -> P2 as the caller
 * wound it. cO = light centre - O. */
PN_KFN pn_lin pn_edge_form(pn_v3 P1, pn_v3 P2, pn_v3 O, pn_v3 cO, pn_v3 U, pn_v3 V)
{
    pn_lin r;
    pn_v3 a, b;
    int flip = pn_edge_canon(P1, P2, &a, &b);
    /* (a - O) x (b - O) written as (a - O) x (b - a): the same vector, but b - a of two
     * nearby floats is exact, so a small triangle far from O keeps an accurate edge plane
     * in float (fewer samples in the band). Both triangles sharing the edge compute the
     * same floats. */
    pn_v3 m = pn_v3_cross(pn_v3_sub(a, O), pn_v3_sub(b, a));
    r.h0 = pn_v3_dot(cO, m);
    r.hu = pn_v3_dot(U, m);
    r.hv = pn_v3_dot(V, m);
    return flip ? pn_lin_neg(r) : r;
}

/* Largest float value of the form over the k x k grid (at the corner its slopes point to:
 * IEEE multiply and add are monotone, so the float form is monotone along rows and
 * columns). */
PN_KFN float pn_lin_max(pn_lin f, uint32_t k)
{
    float lo = pn_sample_coord(0, k), hi = pn_sample_coord((int32_t)k - 1, k);
    float b = f.hv > 0.0f ? hi : lo;
    float a = f.hu > 0.0f ? hi : lo;
    return (f.h0 + b * f.hv) + a * f.hu;
}

/* A float value v "can pass" a form when v >= thr, thr = -(its rounding bound): the exact
 * value can then be >= 0. Monotone in v, so in i and j. */
PN_KFN int pn_pass_v(float v, float thr) { return v >= thr; }

PN_KFN int pn_row_pass(float rb, float hu, int32_t i, uint32_t k, float thr)
{
    return pn_pass_v(rb + pn_sample_coord(i, k) * hu, thr);
}

/* The same walk along a column: v(j) = (h0 + b_j*hv) + cst, the evaluation order of a
 * sample's value with the i term fixed (cst = a_i*hu). */
PN_KFN int pn_col_pass(float h0, float hv, float cst, int32_t j, uint32_t k, float thr)
{
    return pn_pass_v((h0 + pn_sample_coord(j, k) * hv) + cst, thr);
}

/* col = 0: a row, rb is the row base, cst unused; col = 1: a column, rb is h0. */
PN_KFN int pn_pass_at(int col, float rb, float slope, float cst, int32_t n, uint32_t k, float thr)
{
    return col ? pn_col_pass(rb, slope, cst, n, k, thr) : pn_row_pass(rb, slope, n, k, thr);
}

/* Narrows [*lo, *hi] to the indices n where the form can pass. rs is 1/slope (any value
 * when slope is 0): it only places the starting point of the walk, so its rounding never
 * matters; precomputing it saves a division per row. */
PN_KFN void pn_narrow(int col, float rb, float slope, float cst, float rs, uint32_t k, float thr, int32_t *lo,
                      int32_t *hi)
{
    int32_t kk = (int32_t)k;
    if (*lo > *hi) return;
    if (slope == 0.0f) {
        if (!pn_pass_at(col, rb, slope, cst, 0, k, thr)) *hi = *lo - 1;
        return;
    }
    {
        /* Real root as a sample index; only a starting point for the exact walk. */
        float est = (((thr - (rb + cst)) * rs + 1.0f) * (float)k - 1.0f) * 0.5f;
        if (slope > 0.0f) { /* increasing: passes on [first, k-1] */
            int32_t i = pn_kceil_clamp(est, 0, kk);
            while (i > 0 && pn_pass_at(col, rb, slope, cst, i - 1, k, thr)) i--;
            while (i < kk && !pn_pass_at(col, rb, slope, cst, i, k, thr)) i++;
            if (i > *lo) *lo = i;
        } else { /* decreasing: passes on [0, last] */
            int32_t i = pn_kfloor_clamp(est, -1, kk - 1);
            while (i < kk - 1 && pn_pass_at(col, rb, slope, cst, i + 1, k, thr)) i++;
            while (i >= 0 && !pn_pass_at(col, rb, slope, cst, i, k, thr)) i--;
            if (i < *hi) *hi = i;
        }
    }
}

PN_KFN float pn_recip(float v) { return v != 0.0f ? 1.0f / v : 0.0f; }

/* Rows j that can hold a passing sample: where the form's largest float value in the row
 * (at the end column its slope hu points to) can pass. That value is monotone in j, so
 * rows outside the range have no sample that can pass. */
PN_KFN void pn_rows_narrow(pn_lin f, uint32_t k, float thr, int32_t *lo, int32_t *hi)
{
    float a = pn_sample_coord(f.hu > 0.0f ? (int32_t)k - 1 : 0, k);
    pn_narrow(1, f.h0, f.hv, a * f.hu, pn_recip(f.hv), k, thr, lo, hi);
}

/* Sets sample (i, j)'s bit, j k + i. */
PN_KFN void pn_mask_set(uint32_t *m, uint32_t k, int32_t i, int32_t j)
{
    uint32_t bit = (uint32_t)j * k + (uint32_t)i;
    m[bit >> 5] |= 1u << (bit & 31u);
}

PN_KFN void pn_mask_set_run(uint32_t *m, uint32_t k, int32_t j, int32_t lo, int32_t hi)
{
    uint32_t bit = (uint32_t)j * k + (uint32_t)lo;
    uint32_t n = (uint32_t)(hi - lo + 1);
    uint32_t run = n >= 32u ? 0xFFFFFFFFu : ((1u << n) - 1u);
    /* k divides 32 or equals it, so a row never straddles two words. */
    m[bit >> 5] |= run << (bit & 31u);
}

/* Value of a form at sample (a, b), in the one evaluation order (see the top). */
PN_KFN float pn_lin_at(pn_lin f, float a, float b) { return (f.h0 + b * f.hv) + a * f.hu; }

/* ---- Rounding bounds (the filter) ----------------------------------------------------- */

/* Unit roundoff of float, 2^-24. */
#define PN_KU 5.9604645e-8f
/* Absolute slack added to every bound, 2^-96: the bounds below are derived in the standard
 * model (every operation correctly rounded with relative error u, no underflow); a product
 * that underflows errs instead by at most 2^-150 absolutely, which the later operations
 * multiply by at most 2^42 (coordinates <= 2^40) and a few dozen of which enter one value:
 * far below 2^-96. Values that small always go to the exact arithmetic. */
#define PN_KTINY 1.2621774e-29f

/* Plane form of triangle ABC over the sample grid, (S - A).n with n = (B - A) x (C - A),
 * and its rounding bound for every sample (|a|, |b| <= 1).
 *
 * Bounds (u = 2^-24; |x|1 and |x|inf the L1 and max norms). n computed is within 4.01 u Pn
 * of the exact normal in L1, Pn = |B - A|1 |C - A|1. A sample's plane value (h0 + b hv) +
 * a hu errs from the exact (S - A).n by at most 11.01 u (|c - A|inf + |U|inf + |V|inf) Pn
 * (evaluation 3u, the three dots 3u, c - A 1u, n 4.01u): *err, 12 u times that (the slack
 * pays for the rounding of the bound itself), plus PN_KTINY. (Bounds of 1e-6 of |n|1 used
 * long ago were not bounds for slivers, whose n cancels: fuzz/known-failures/README.md.) */
PN_KFN void pn_plane_form(pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, pn_lin *f, float *err, pn_v3 *nout,
                          float *pn_out)
{
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
    pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    pn_v3 BA = pn_v3_sub(B, A), CA = pn_v3_sub(C, A);
    pn_v3 n = pn_v3_cross(BA, CA);
    pn_v3 cA = pn_v3_sub(c, A);
    float pn = pn_v3_l1(BA) * pn_v3_l1(CA);
    f->h0 = pn_v3_dot(cA, n);
    f->hu = pn_v3_dot(U, n);
    f->hv = pn_v3_dot(V, n);
    *err = 12.0f * PN_KU * (pn_v3_linf(cA) + pn_v3_linf(U) + pn_v3_linf(V)) * pn + PN_KTINY;
    *nout = n;
    *pn_out = pn;
}

/* Rounding bound of edge P1P2's value at any sample, componentwise: with p = a - O and
 * e = b - a over the canonical endpoints (as pn_edge_form takes them), each component of
 * the cross product errs by at most 4.01 u M_i, M = (|p_y||e_z| + |p_z||e_y|, ...), and
 * the dots and the evaluation by 7 u sum_i W_i |m_i| <= 7 u W.M, W = |c - O| + |U| + |V|
 * componentwise: 11.01 u W.M in all; 12 u W.M + PN_KTINY returned. */
PN_KFN float pn_edge_err(pn_v3 P1, pn_v3 P2, pn_v3 O, pn_v3 W)
{
    int flip = pn_v3_less(P2, P1);
    pn_v3 p = pn_v3_abs(pn_v3_sub(flip ? P2 : P1, O)), e = pn_v3_abs(pn_v3_sub(P2, P1));
    pn_v3 M = pn_v3_make(p.y * e.z + p.z * e.y, p.z * e.x + p.x * e.z, p.x * e.y + p.y * e.x);
    return 12.0f * PN_KU * pn_v3_dot(W, M) + PN_KTINY;
}

/* ---- Exact signs (pn_expansion.h) ------------------------------------------------------ */

PN_KFN pn_v3 pn_light_U(const pn_klight *L) { return pn_v3_make(L->U[0], L->U[1], L->U[2]); }
PN_KFN pn_v3 pn_light_V(const pn_klight *L) { return pn_v3_make(L->V[0], L->V[1], L->V[2]); }
PN_KFN pn_v3 pn_light_c(const pn_klight *L) { return pn_v3_make(L->c[0], L->c[1], L->c[2]); }

/* Exact sign of (S - A) . ((B - A) x (C - A)), S the exact sample point (a, b). */
PN_KFN int32_t pn_exact_plane(pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, float a, float b)
{
    return pn_x_sign_dot(pn_light_c(L), A, pn_light_U(L), pn_light_V(L), a, b, B, A, C, A);
}

/* Exact sign of edge P1P2's value at sample (a, b): the sign of the float form's real
 * counterpart, (S - O) . ((a - O) x (b - a)) over the canonical endpoints, negated when
 * they were swapped (pn_edge_form). */
PN_KFN int32_t pn_exact_edge(pn_v3 P1, pn_v3 P2, pn_v3 O, const pn_klight *L, float a, float b)
{
    pn_v3 ca, cb;
    int flip = pn_edge_canon(P1, P2, &ca, &cb);
    int32_t s = pn_x_sign_dot(pn_light_c(L), O, pn_light_U(L), pn_light_V(L), a, b, ca, O, cb, ca);
    return flip ? -s : s;
}

/* ---- The predicate -------------------------------------------------------------------- */

/* The four linear forms of triangle ABC seen from O and their rounding bounds: the plane
 * form, oriented so that a sample passes when its exact value is > 0 (S on the side away
 * from O), and the three edge forms (a sample passes when all three exact values are >= 0
 * or all <= 0). pn_tri_mask() and pn_tri_sample() both evaluate exactly these floats in
 * the same order and decide every sign exactly. */
typedef struct pn_tri_forms {
    pn_lin plane;
    float err_p;     /* bound of every plane value's rounding */
    int32_t dsign;   /* exact sign of O's side value (O - A).n, nonzero */
    float e_err[3];  /* bounds of the edge values */
    pn_lin e[3];
} pn_tri_forms;

/* The plane form; returns 0 when O lies exactly in the triangle's plane (then no open
 * segment from O crosses it: no sample is blocked). O's side value d0 = (O - A).n errs by
 * at most 8.01 u |O - A|inf Pn (dot 3u, O - A 1u, n 4.01u): err_d = 12 u |O - A|inf Pn +
 * PN_KTINY; within it the sign is computed exactly. */
PN_KFN int pn_tri_plane(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, pn_tri_forms *F)
{
    pn_v3 n, OA = pn_v3_sub(O, A);
    float pn, d0, err_d;
    int32_t sd;
    pn_plane_form(A, B, C, L, &F->plane, &F->err_p, &n, &pn);
    d0 = pn_v3_dot(OA, n);
    err_d = 12.0f * PN_KU * pn_v3_linf(OA) * pn + PN_KTINY;
    if (d0 > err_d) {
        sd = 1;
    } else if (d0 < -err_d) {
        sd = -1;
    } else {
        PN_EXACT_HOOK(0);
        sd = pn_x_sign_dot(O, A, pn_v3_make(0.0f, 0.0f, 0.0f), pn_v3_make(0.0f, 0.0f, 0.0f), 0.0f, 0.0f, B, A, C, A);
        if (sd == 0) return 0;
    }
    F->dsign = sd;
    if (sd > 0) F->plane = pn_lin_neg(F->plane); /* S must be on the other side */
    return 1;
}

PN_KFN void pn_tri_edges(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, pn_tri_forms *F)
{
    pn_v3 U = pn_light_U(L), V = pn_light_V(L);
    pn_v3 cO = pn_v3_sub(pn_light_c(L), O);
    pn_v3 W = pn_v3_add(pn_v3_add(pn_v3_abs(cO), pn_v3_abs(U)), pn_v3_abs(V));
    F->e[0] = pn_edge_form(A, B, O, cO, U, V);
    F->e[1] = pn_edge_form(B, C, O, cO, U, V);
    F->e[2] = pn_edge_form(C, A, O, cO, U, V);
    F->e_err[0] = pn_edge_err(A, B, O, W);
    F->e_err[1] = pn_edge_err(B, C, O, W);
    F->e_err[2] = pn_edge_err(C, A, O, W);
}

/* Filter of one value against its bound r > 0: 1 or -1 when the float value v proves the
 * exact sign (|exact - v| < r), 2 when it cannot. */
PN_KFN int32_t pn_filter(float v, float r) { return v >= r ? 1 : (v <= -r ? -1 : 2); }

/* Exact decision of sample (a, b) of triangle ABC from O, given its float plane value vp
 * and edge values v0, v1, v2 (as pn_lin_at or pn_row_bits computes them): the filter
 * where it decides, the exact sign where it does not. Cheap signs first: the exact
 * arithmetic runs only for values whose sign can still change the answer. */
PN_KFN uint32_t pn_tri_resolve(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, const pn_tri_forms *F, float a,
                               float b, float vp, float v0, float v1, float v2)
{
    int32_t s0 = pn_filter(v0, F->e_err[0]), s1 = pn_filter(v1, F->e_err[1]), s2 = pn_filter(v2, F->e_err[2]), sp;
    int pos = s0 != -1 && s1 != -1 && s2 != -1, neg = s0 != 1 && s1 != 1 && s2 != 1;
    if (!pos && !neg) return 0u;
    sp = pn_filter(vp, F->err_p);
    if (sp == 2) {
        PN_EXACT_HOOK(1);
        sp = -F->dsign * pn_exact_plane(A, B, C, L, a, b);
    }
    if (sp <= 0) return 0u;
    if (s0 == 2) {
        PN_EXACT_HOOK(2);
        s0 = pn_exact_edge(A, B, O, L, a, b);
        if (s0 > 0) neg = 0;
        if (s0 < 0) pos = 0;
        if (!pos && !neg) return 0u;
    }
    if (s1 == 2) {
        PN_EXACT_HOOK(2);
        s1 = pn_exact_edge(B, C, O, L, a, b);
        if (s1 > 0) neg = 0;
        if (s1 < 0) pos = 0;
        if (!pos && !neg) return 0u;
    }
    if (s2 == 2) {
        PN_EXACT_HOOK(2);
        s2 = pn_exact_edge(C, A, O, L, a, b);
        if (s2 > 0) neg = 0;
        if (s2 < 0) pos = 0;
        if (!pos && !neg) return 0u;
    }
    return 1u;
}

/* Sample (i, j) alone: 1 if triangle ABC blocks it from O. The per-ray form of
 * pn_tri_mask(), for PN_ALGO_RAYTRACE: the same forms and the same float values, and the
 * same exact decision. */
PN_KFN uint32_t pn_tri_sample(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, int32_t i, int32_t j)
{
    pn_tri_forms F;
    float a = pn_sample_coord(i, L->k), b = pn_sample_coord(j, L->k), vp;
    if (!pn_tri_plane(O, A, B, C, L, &F)) return 0u;
    vp = pn_lin_at(F.plane, a, b);
    if (vp <= -F.err_p) return 0u; /* certainly on O's side or in the plane */
    pn_tri_edges(O, A, B, C, L, &F);
    return pn_tri_resolve(O, A, B, C, L, &F, a, b, vp, pn_lin_at(F.e[0], a, b), pn_lin_at(F.e[1], a, b),
                          pn_lin_at(F.e[2], a, b));
}

/* Bits s4 <= i < n4 (multiples of 4, n4 <= k rounded up to one) of one row that can pass: with plane value
 * vp = pb + a_i*phu (bound ep) and edge values v_q = b_q + a_i*h_q (bounds r_q), a lane can
 * pass when vp >= -ep and all v_q >= -r_q or all v_q <= r_q (pn_filter's tests; a lane that
 * fails them certainly does not pass). Four lanes at a time, no branches; coordinate
 * a_i = (2i+1)*(1/k) - 1, which equals pn_sample_coord() exactly (k is a power of two and
 * 2*i0 + 1, 3, 5, 7 are exact integers in float). The row is most of the predicate's cost
 * (issue 5 profile). In C on a SIMD target the lanes are a pn_f4 (PN_KVEC4): written as a
 * loop over lanes, GCC 12 at -O3 -march=native (AVX-512) vectorized the loop over groups
 * sixteen groups wide, more than a row of k <= 32 holds, and ran its scalar remainder (the
 * reference took 1.6x Clang's time on `thin`; at the default target it vectorized neither
 * loop). Elsewhere, and in OpenCL (PoCL vectorizes it across work items; float4 measured
 * slower there), the loop over lanes. The same operations on the same values: the same
 * bits either way (test_crossport, firmware_same_bytes). */
PN_KFN_HOT uint32_t pn_row_bits(float rk, int32_t s4, int32_t n4, float pb, float phu, float ep, float b0,
                                float h0, float b1, float h1, float b2, float h2, float r0, float r1, float r2)
{
    uint32_t bits = 0u;
    int32_t i0;
    for (i0 = s4; i0 < n4; i0 += 4) {
#if PN_KVEC4
        pn_f4 a = (pn_f4_splat((float)(2 * i0)) + pn_f4_make(1.0f, 3.0f, 5.0f, 7.0f)) * pn_f4_splat(rk) -
                  pn_f4_splat(1.0f);
        pn_f4 vp = pn_f4_splat(pb) + a * pn_f4_splat(phu), v0 = pn_f4_splat(b0) + a * pn_f4_splat(h0),
              v1 = pn_f4_splat(b1) + a * pn_f4_splat(h1), v2 = pn_f4_splat(b2) + a * pn_f4_splat(h2);
        pn_i4 pos = (v0 >= pn_f4_splat(-r0)) & (v1 >= pn_f4_splat(-r1)) & (v2 >= pn_f4_splat(-r2));
        pn_i4 neg = (v0 <= pn_f4_splat(r0)) & (v1 <= pn_f4_splat(r1)) & (v2 <= pn_f4_splat(r2));
        bits |= pn_i4_bits((vp >= pn_f4_splat(-ep)) & (pos | neg)) << (uint32_t)i0;
#else
        int32_t l;
        for (l = 0; l < 4; l++) {
            float a = (float)(2 * (i0 + l) + 1) * rk - 1.0f;
            float vp = pb + a * phu, v0 = b0 + a * h0, v1 = b1 + a * h1, v2 = b2 + a * h2;
            int32_t pos = (v0 >= -r0) & (v1 >= -r1) & (v2 >= -r2);
            int32_t neg = (v0 <= r0) & (v1 <= r1) & (v2 <= r2);
            int32_t ok = (vp >= -ep) & (pos | neg);
            bits |= (0u - (uint32_t)ok) & ((1u << (uint32_t)l) << (uint32_t)i0);
        }
#endif
    }
    return bits;
}

/* ORs into m (PN_MASK_WORDS_MAX words, bit j*k + i) the samples of light L that triangle
 * ABC blocks from O, given that they all lie in columns [i_lo, i_hi] and rows
 * [j_lo, j_hi] (its footprint, pn_footprint.h; the whole grid when nothing is known): only
 * those rows, and the groups of four lanes that hold those columns, are evaluated. Returns
 * 1 if it blocks at least one sample, else 0. */
PN_KFN uint32_t pn_tri_mask_in(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, uint32_t *m, int32_t i_lo,
                               int32_t i_hi, int32_t j_lo, int32_t j_hi)
{
    uint32_t k = L->k;
    pn_tri_forms F;
    pn_lin plane, e[3], ne[3];
    float ep;
    int pos_ok, neg_ok;
    uint32_t any = 0;
    int32_t j, row_lo, row_hi;

    if (!pn_tri_plane(O, A, B, C, L, &F)) return 0;
    plane = F.plane;
    ep = F.err_p;
    /* Every sample's exact plane value is below its float value + ep. */
    if (!(pn_lin_max(plane, k) > -ep)) return 0;

    pn_tri_edges(O, A, B, C, L, &F);
    e[0] = F.e[0];
    e[1] = F.e[1];
    e[2] = F.e[2];
    ne[0] = pn_lin_neg(e[0]);
    ne[1] = pn_lin_neg(e[1]);
    ne[2] = pn_lin_neg(e[2]);
    pos_ok = pn_lin_max(e[0], k) >= -F.e_err[0] && pn_lin_max(e[1], k) >= -F.e_err[1] &&
             pn_lin_max(e[2], k) >= -F.e_err[2];
    neg_ok = pn_lin_max(ne[0], k) >= -F.e_err[0] && pn_lin_max(ne[1], k) >= -F.e_err[1] &&
             pn_lin_max(ne[2], k) >= -F.e_err[2];
    if (!pos_ok && !neg_ok) return 0;

    {
        /* Rows where the plane and, for some orientation, all three edges can pass. */
        int32_t plo = 0, phi = (int32_t)k - 1, jlo = (int32_t)k, jhi = -1, s, q;
        pn_rows_narrow(plane, k, -ep, &plo, &phi);
        for (s = 0; s < 2; s++) {
            int32_t lo = plo, hi = phi;
            if (!(s == 0 ? pos_ok : neg_ok)) continue;
            for (q = 0; q < 3; q++) pn_rows_narrow(s == 0 ? e[q] : ne[q], k, -F.e_err[q], &lo, &hi);
            if (lo > hi) continue;
            jlo = pn_kmini(jlo, lo);
            jhi = pn_kmaxi(jhi, hi);
        }
        row_lo = pn_kmaxi(jlo, j_lo);
        row_hi = pn_kmini(jhi, j_hi);
    }
    {
        /* Every sample of the candidate rows, classified branch-free (the row loop
         * vectorizes); the few in a band decided one by one, exactly.
         * a_i = (2i+1)*(1/k) - 1 equals pn_sample_coord() exactly: k is a power of two. */
        float rk = 1.0f / (float)k;
        uint32_t keep = k >= 32u ? 0xFFFFFFFFu : ((1u << k) - 1u), bits, sure, bit, have;
        int32_t n4 = ((int32_t)k + 3) & ~3, s4 = i_lo & ~3, e4 = pn_kmini(n4, (i_hi + 4) & ~3);
        for (j = row_lo; j <= row_hi; j++) {
            float b = (float)(2 * j + 1) * rk - 1.0f;
            float pb = plane.h0 + b * plane.hv;
            float b0 = e[0].h0 + b * e[0].hv, b1 = e[1].h0 + b * e[1].hv, b2 = e[2].h0 + b * e[2].hv;
            bit = (uint32_t)j * k;
            have = (m[bit >> 5] >> (bit & 31u)) & keep;
            if (have == keep) continue; /* row already blocked */
            bits = keep & ~have &
                   pn_row_bits(rk, s4, e4, pb, plane.hu, ep, b0, e[0].hu, b1, e[1].hu, b2, e[2].hu, F.e_err[0], F.e_err[1],
                               F.e_err[2]);
            if (!bits) continue;
            /* The lanes that certainly pass: the same test with the bounds negated (vp >= ep
             * and all v_q >= r_q or all v_q <= -r_q), run only for the rows where some lane
             * can pass (a few percent of the rows on scanned models). */
            sure = bits & pn_row_bits(rk, s4, e4, pb, plane.hu, -ep, b0, e[0].hu, b1, e[1].hu, b2, e[2].hu,
                                      -F.e_err[0], -F.e_err[1], -F.e_err[2]);
            bits &= ~sure; /* band samples not already blocked */
            while (bits) {
                uint32_t lane = pn_kctz(bits);
                float a = (float)(2 * (int32_t)lane + 1) * rk - 1.0f;
                bits &= bits - 1u;
                if (pn_tri_resolve(O, A, B, C, L, &F, a, b, pb + a * plane.hu, b0 + a * e[0].hu, b1 + a * e[1].hu,
                                   b2 + a * e[2].hu))
                    sure |= 1u << lane;
            }
            if (sure) {
                m[bit >> 5] |= sure << (bit & 31u);
                any = 1;
            }
        }
    }
    return any;
}

/* The whole grid: every sample of the light may be blocked. */
PN_KFN uint32_t pn_tri_mask(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, uint32_t *m)
{
    return pn_tri_mask_in(O, A, B, C, L, m, 0, (int32_t)L->k - 1, 0, (int32_t)L->k - 1);
}

/* ---- The horizon (invariant 6) ---------------------------------------------------------- */

/* The plane of P's own triangle ABC as a form over the sample grid, oriented so that a
 * sample is visible when its exact value is > 0 and blocked when it is <= 0 (on or behind
 * the plane). The front is the side the geometric normal nrm points to once turned toward
 * the light centre, as pn_shadow_origin() turns it; the G-buffer normal is the unit
 * normal of (B - A) x (C - A) in winding order, so the sign of their dot product says
 * which way the plane's normal must point. */
typedef struct pn_horizon {
    pn_lin f;
    float err;
    int32_t sgn; /* +1: the front is the side of (B - A) x (C - A); -1: the other */
    pn_v3 A, B, C;
} pn_horizon;

PN_KFN void pn_horizon_make(pn_v3 P, pn_v3 nrm, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, pn_horizon *H)
{
    pn_v3 n;
    float pn;
    if (pn_v3_dot(nrm, pn_v3_sub(pn_light_c(L), P)) < 0.0f) nrm = pn_v3_scale(nrm, -1.0f);
    pn_plane_form(A, B, C, L, &H->f, &H->err, &n, &pn);
    H->sgn = pn_v3_dot(n, nrm) < 0.0f ? -1 : 1;
    if (H->sgn < 0) H->f = pn_lin_neg(H->f);
    H->A = A;
    H->B = B;
    H->C = C;
}

/* 1 if sample (a, b) is below the horizon. */
PN_KFN uint32_t pn_horizon_at(const pn_horizon *H, const pn_klight *L, float a, float b)
{
    float v = pn_lin_at(H->f, a, b);
    int32_t s = pn_filter(v, H->err);
    if (s == 2) {
        PN_EXACT_HOOK(3);
        s = H->sgn * pn_exact_plane(H->A, H->B, H->C, L, a, b);
    }
    return (uint32_t)(s <= 0);
}

/* ORs the samples below the horizon into m; returns the count it set (0: m untouched, so
 * a caller that multiplies by the mask's visibility may skip it: a factor of exactly 1).
 * Most pixels see the whole light in front: the form's smallest float value over the grid
 * (at a corner) above the bound. */
PN_KFN uint32_t pn_horizon_mask(const pn_horizon *H, const pn_klight *L, uint32_t *m)
{
    uint32_t k = L->k, i, j, n = 0u;
    if (-pn_lin_max(pn_lin_neg(H->f), k) >= H->err) return 0u;
    for (j = 0; j < k; j++)
        for (i = 0; i < k; i++)
            if (pn_horizon_at(H, L, pn_sample_coord((int32_t)i, k), pn_sample_coord((int32_t)j, k))) {
                pn_mask_set(m, k, (int32_t)i, (int32_t)j);
                n++;
            }
    return n;
}

/* The horizon of the pixel whose own triangle is `own` in tris (9 floats a triangle). */
PN_KFN void pn_horizon_of(pn_v3 P, pn_v3 nrm, uint32_t own, PN_CONST float *tris, const pn_klight *L,
                          pn_horizon *H)
{
    PN_CONST float *p = tris + (size_t)own * 9u;
    pn_horizon_make(P, nrm, pn_v3_make(p[0], p[1], p[2]), pn_v3_make(p[3], p[4], p[5]), pn_v3_make(p[6], p[7], p[8]),
                    L, H);
}

/* ---- Per-pixel set-up shared by every exact algorithm --------------------------------- */

/* From the G-buffer point P and unit geometric normal nrm, the shadow-ray origin
 * O = P + eps*n with n turned toward the light centre. Returns 0 when P cannot see the
 * light at all (behind a one-sided area light: (P - c).N <= 0; *O is then written but
 * means nothing), else 1. Selects, no branch: a loop over pixels that calls it can be
 * vectorized (MCSM's runs, pn_mc_run). */
PN_KFN int pn_shadow_origin(pn_v3 P, pn_v3 nrm, const pn_klight *L, pn_v3 *O)
{
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    pn_v3 toc = pn_v3_sub(c, P), N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
    int sees = pn_v3_dot(pn_v3_sub(P, c), N) > 0.0f;
    float s = pn_v3_dot(nrm, toc) < 0.0f ? -1.0f : 1.0f; /* n * -1 and n * 1 are exact */
    *O = pn_v3_add(P, pn_v3_scale(pn_v3_scale(nrm, s), L->eps));
    return L->is_point ? 1 : sees;
}

PN_KFN uint32_t pn_mask_words(uint32_t k) { return (k * k + 31u) >> 5; }

PN_KFN void pn_mask_clear(uint32_t *m)
{
    uint32_t w;
    for (w = 0; w < PN_MASK_WORDS_MAX; w++) m[w] = 0u;
}

/* m |= o over the words of k x k samples. */
PN_KFN void pn_mask_or(uint32_t *m, const uint32_t *o, uint32_t k)
{
    uint32_t w;
    for (w = 0; w < pn_mask_words(k); w++) m[w] |= o[w];
}

PN_KFN uint32_t pn_mask_count(const uint32_t *m, uint32_t k)
{
    uint32_t w, n = 0, words = pn_mask_words(k);
    for (w = 0; w < words; w++) n += pn_kpopcount(m[w]);
    return n;
}

PN_KFN int pn_mask_full(const uint32_t *m, uint32_t k)
{
    return pn_mask_count(m, k) == k * k;
}

/* Unblocked fraction; both operands are small integers, so the quotient is exact or
 * correctly rounded identically everywhere. */
PN_KFN float pn_mask_visibility(const uint32_t *m, uint32_t k)
{
    uint32_t total = k * k;
    return (float)(total - pn_mask_count(m, k)) / (float)total;
}

#endif
