/* pn_predicate.h - the one definition of "light sample blocked" (DESIGN.md invariant 6).
 *
 * Sample (i, j) of k x k sits at S = c + a_i U + b_j V with a_i = (2i+1)/k - 1 (exact in
 * float for k a power of two). It is blocked from the shadow-ray origin O by triangle
 * ABC when the open segment (O, S) meets the closed triangle:
 *
 *   plane:  O and S lie strictly on opposite sides of the triangle's plane, i.e. the
 *           segment crosses it at some t in (0, 1); "strictly" means by more than a
 *           rigorous bound on the rounding of each side value. This is the "clip to the
 *           slab between O's plane and the light plane" of the issue, done per sample: a
 *           triangle part behind O or behind the sample can never be crossed by (O, S);
 *   edges:  the three triple products (S - O) . ((P1 - O) x (P2 - O)) over the edges
 *           P1P2 all have the same sign (zero counts as either). This is the edge-function
 *           test of the triangle projected from O onto the light plane, written without
 *           the division so that no vertex needs to be projected to infinity;
 *   certainty: a sample whose edge values are within rounding of zero counts only if
 *           its crossing (S - O).n is large enough that rounding cannot have put the
 *           crossing point more than L->cross_tol off the triangle (pn_tri_graze). Only
 *           segments at an edge and nearly in the triangle's plane, whose crossing point
 *           is rounding noise, are dropped; this is what makes every cull widened by
 *           cross_tol conservative for the float predicate.
 *
 * Every test is a linear form in (a_i, b_j): h(i, j) = (h0 + b_j*hv) + a_i*hu, always
 * evaluated in exactly that order. Consequences, relied on below and by GEARS:
 *   - watertight: an edge's form is computed from its endpoints in canonical
 *     (lexicographic) order, so the two triangles sharing it get the very same float h and
 *     see it with opposite signs; with zero counted as inside by both, a sample can never
 *     slip between them (unless its segment nearly lies in both triangles' planes, where
 *     the certainty test drops it from both);
 *   - monotone: IEEE multiply and add are monotone, so for a fixed row h is monotone in i,
 *     and for fixed i monotone in j. Each form passes on a prefix or suffix of a row,
 *     and the extreme value over the grid is at a corner. So the rows where every form
 *     can pass are found exactly by walking h itself along the best column (an
 *     estimate only picks the starting point); within them every sample is evaluated
 *     in one branch-free, vectorizable loop per row (pn_row_bits). The mask is the
 *     per-sample answer exactly: tests/test_raytrace.c compares every bit with
 *     pn_tri_sample().
 * A point light is the case k = 1, U = V = 0. */
#ifndef PN_PREDICATE_H
#define PN_PREDICATE_H

#include "pn_kmath.h"
#include "pn_ktypes.h"

/* ---- Linear forms over the sample grid ------------------------------------------------ */

typedef struct pn_lin {
    float h0, hu, hv;
} pn_lin;

PN_KFN float pn_sample_coord(int32_t i, uint32_t k)
{
    return (float)(2 * i + 1) / (float)k - 1.0f;
}

PN_KFN pn_lin pn_lin_neg(pn_lin a)
{
    /* Round-to-nearest is symmetric, so evaluating the negated form gives exactly the
     * negated value: orientation flips never change which samples are on an edge. */
    pn_lin r;
    r.h0 = -a.h0;
    r.hu = -a.hu;
    r.hv = -a.hv;
    return r;
}

/* Edge form of edge P1P2 seen from O; positive on the left of P1 -> P2 as the caller
 * wound it. cO = light centre - O. */
PN_KFN pn_lin pn_edge_form(pn_v3 P1, pn_v3 P2, pn_v3 O, pn_v3 cO, pn_v3 U, pn_v3 V)
{
    pn_lin r;
    int flip = pn_v3_less(P2, P1);
    pn_v3 a = flip ? P2 : P1;
    pn_v3 b = flip ? P1 : P2;
    /* (a - O) x (b - O) written as (a - O) x (b - a): the same vector, but b - a of two
     * nearby floats is exact, so a small triangle far from O keeps an accurate edge plane
     * (the first form cancels to noise when |a - O| / |b - a| is large, and then blocks
     * samples its exact segment misses by a wide margin: found on the dragon). Both
     * triangles sharing the edge still compute the same floats. */
    pn_v3 m = pn_v3_cross(pn_v3_sub(a, O), pn_v3_sub(b, a));
    r.h0 = pn_v3_dot(cO, m);
    r.hu = pn_v3_dot(U, m);
    r.hv = pn_v3_dot(V, m);
    return flip ? pn_lin_neg(r) : r;
}

/* Largest value of the form over the k x k grid (at the corner its slopes point to). */
PN_KFN float pn_lin_max(pn_lin f, uint32_t k)
{
    float lo = pn_sample_coord(0, k), hi = pn_sample_coord((int32_t)k - 1, k);
    float b = f.hv > 0.0f ? hi : lo;
    float a = f.hu > 0.0f ? hi : lo;
    return (f.h0 + b * f.hv) + a * f.hu;
}

/* Samples i of one row (row base rb = h0 + b_j*hv) where rb + a_i*hu >= 0 (> 0 if
 * strict), as [*lo, *hi] narrowed in place. */
/* strict = 0: passes when v >= 0 (edges: zero counts as inside). strict = 1: passes when
 * v > thr, thr >= 0 (the plane: a crossing closer than float noise to the sample is not a
 * crossing of the open segment). Both are monotone in v, so in i and j. */
PN_KFN int pn_pass_v(float v, int strict, float thr) { return strict ? v > thr : v >= 0.0f; }

PN_KFN int pn_row_pass(float rb, float hu, int32_t i, uint32_t k, int strict, float thr)
{
    return pn_pass_v(rb + pn_sample_coord(i, k) * hu, strict, thr);
}

/* The same walk along a column: v(j) = (h0 + b_j*hv) + cst, the evaluation order of a
 * sample's value with the i term fixed (cst = a_i*hu). */
PN_KFN int pn_col_pass(float h0, float hv, float cst, int32_t j, uint32_t k, int strict, float thr)
{
    return pn_pass_v((h0 + pn_sample_coord(j, k) * hv) + cst, strict, thr);
}

/* Narrows [*lo, *hi] to the indices n where rb + a_n*slope (+ cst, for columns) passes.
 * col = 0: a row, rb is the row base, cst unused; col = 1: a column, rb is h0. */
PN_KFN int pn_pass_at(int col, float rb, float slope, float cst, int32_t n, uint32_t k, int strict, float thr)
{
    return col ? pn_col_pass(rb, slope, cst, n, k, strict, thr) : pn_row_pass(rb, slope, n, k, strict, thr);
}

/* rs is 1/slope (any value when slope is 0): it only places the starting point of the
 * walk, so its rounding never matters; precomputing it saves a division per row. */
PN_KFN void pn_narrow(int col, float rb, float slope, float cst, float rs, uint32_t k, int strict, float thr,
                      int32_t *lo, int32_t *hi)
{
    int32_t kk = (int32_t)k;
    if (*lo > *hi) return;
    if (slope == 0.0f) {
        if (!pn_pass_at(col, rb, slope, cst, 0, k, strict, thr)) *hi = *lo - 1;
        return;
    }
    {
        /* Real root as a sample index; only a starting point for the exact walk. */
        float est = ((-(rb + cst) * rs + 1.0f) * (float)k - 1.0f) * 0.5f;
        if (slope > 0.0f) { /* increasing: passes on [first, k-1] */
            int32_t i = pn_kceil_clamp(est, 0, kk);
            while (i > 0 && pn_pass_at(col, rb, slope, cst, i - 1, k, strict, thr)) i--;
            while (i < kk && !pn_pass_at(col, rb, slope, cst, i, k, strict, thr)) i++;
            if (i > *lo) *lo = i;
        } else { /* decreasing: passes on [0, last] */
            int32_t i = pn_kfloor_clamp(est, -1, kk - 1);
            while (i < kk - 1 && pn_pass_at(col, rb, slope, cst, i + 1, k, strict, thr)) i++;
            while (i >= 0 && !pn_pass_at(col, rb, slope, cst, i, k, strict, thr)) i--;
            if (i < *hi) *hi = i;
        }
    }
}

PN_KFN float pn_recip(float v) { return v != 0.0f ? 1.0f / v : 0.0f; }

/* Rows j that can hold a passing sample: where the form's largest value in the row (at
 * the end column its slope hu points to) passes. That value is monotone in j, so this is
 * exact as a necessary condition: rows outside the range have no passing sample. */
PN_KFN void pn_rows_narrow(pn_lin f, uint32_t k, int strict, float thr, int32_t *lo, int32_t *hi)
{
    float a = pn_sample_coord(f.hu > 0.0f ? (int32_t)k - 1 : 0, k);
    pn_narrow(1, f.h0, f.hv, a * f.hu, pn_recip(f.hv), k, strict, thr, lo, hi);
}

PN_KFN void pn_mask_set_run(uint32_t *m, uint32_t k, int32_t j, int32_t lo, int32_t hi)
{
    uint32_t bit = (uint32_t)j * k + (uint32_t)lo;
    uint32_t n = (uint32_t)(hi - lo + 1);
    uint32_t run = n >= 32u ? 0xFFFFFFFFu : ((1u << n) - 1u);
    /* k divides 32 or equals it, so a row never straddles two words. */
    m[bit >> 5] |= run << (bit & 31u);
}

/* ---- The predicate -------------------------------------------------------------------- */

/* Unit roundoff of float, 2^-24. */
#define PN_KU 5.9604645e-8f

/* The four linear forms of triangle ABC seen from O: the plane form (oriented so that a
 * sample passes when its value is > plane_thr) and the three edge forms. pn_tri_mask() and
 * pn_tri_sample() both evaluate exactly these floats in exactly the same order, so the
 * mask of a whole pixel and a single ray agree bit for bit. err_p, err_d and d0_abs are
 * the plane's rounding bounds and |O's side value|, kept for pn_tri_graze(). */
typedef struct pn_tri_forms {
    pn_lin plane;
    float plane_thr;
    float err_p, err_d, d0_abs;
    float graze_thr, e_err[3]; /* pn_tri_graze() */
    pn_lin e[3];
} pn_tri_forms;

/* The plane form; returns 0 when O's side of the triangle's plane is within rounding (then
 * no sample is blocked).
 *
 * Rounding bounds (u = 2^-24; |x|1 and |x|inf the L1 and max norms; standard model, every
 * operation correctly rounded, no underflow). n = (B - A) x (C - A) computed is within
 * 4.01 u Pn of the exact normal in L1, Pn = |B - A|1 |C - A|1. O's side value
 * d0 = (O - A).n then errs by at most 8.01 u |O - A|inf Pn (dot 3u, O - A 1u, n 4.01u):
 * err_d = 12 u |O - A|inf Pn, the slack above paying for the rounding of pn_tri_graze().
 * A sample's plane value (h0 + b hv) + a hu, |a|, |b| <= 1, errs from the exact (S - A).n
 * by at most 11.01 u (|c - A|inf + |U|inf + |V|inf) Pn (evaluation 3u, the three dots
 * 3u, c - A 1u, n 4.01u): err_p, 12 u times that. With err_d and err_p as the thresholds,
 * "O and S strictly on opposite sides" holds of the exact geometry whenever it holds of
 * the floats. (Bounds of 1e-6 of |n|1 used before were not bounds for slivers, whose
 * n cancels: fuzz/known-failures/README.md.) */
PN_KFN int pn_tri_plane(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, pn_tri_forms *F)
{
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
    pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    pn_v3 BA = pn_v3_sub(B, A), CA = pn_v3_sub(C, A);
    pn_v3 n = pn_v3_cross(BA, CA);
    pn_v3 cA = pn_v3_sub(c, A), OA = pn_v3_sub(O, A);
    float pn = pn_v3_l1(BA) * pn_v3_l1(CA);
    float d0 = pn_v3_dot(OA, n);
    float err_d = 12.0f * PN_KU * pn_v3_linf(OA) * pn;
    if (!(d0 > err_d || d0 < -err_d)) return 0;
    F->err_d = err_d;
    F->d0_abs = d0 < 0.0f ? -d0 : d0;
    F->plane.h0 = pn_v3_dot(cA, n);
    F->plane.hu = pn_v3_dot(U, n);
    F->plane.hv = pn_v3_dot(V, n);
    F->err_p = 12.0f * PN_KU * (pn_v3_linf(cA) + pn_v3_linf(U) + pn_v3_linf(V)) * pn;
    F->plane_thr = F->err_p;
    if (d0 > 0.0f) F->plane = pn_lin_neg(F->plane); /* S must be on the other side: > thr */
    return 1;
}

/* Rounding bound of edge P1P2's value at any sample, componentwise: with p = a - O and
 * e = b - a over the canonical endpoints (as pn_edge_form takes them), each component of
 * the cross product errs by at most 4.01 u M_i, M = (|p_y||e_z| + |p_z||e_y|, ...), and
 * the dots and the evaluation by 7 u sum_i W_i |m_i| <= 7 u W.M, W = |c - O| + |U| + |V|
 * componentwise: 11.01 u W.M in all; 12 u W.M returned. */
PN_KFN float pn_edge_err(pn_v3 P1, pn_v3 P2, pn_v3 O, pn_v3 W)
{
    int flip = pn_v3_less(P2, P1);
    pn_v3 p = pn_v3_abs(pn_v3_sub(flip ? P2 : P1, O)), e = pn_v3_abs(pn_v3_sub(P2, P1));
    pn_v3 M = pn_v3_make(p.y * e.z + p.z * e.y, p.z * e.x + p.x * e.z, p.x * e.y + p.y * e.x);
    return 12.0f * PN_KU * pn_v3_dot(W, M);
}

/* Certainty of a blocked sample, which is what lets every cull widened by L->cross_tol
 * (GEARS' boxes, the frustum tests of all algorithms) be conservative for this float
 * predicate and not only for exact geometry.
 *
 * Each computed edge value errs from the exact (S - O).((P1 - O) x (P2 - P1)) by at most
 * E_q (pn_edge_err: cross product 4.01u, three dots 3u, c - O 1u, evaluation 3u, each
 * component weighted by its own magnitudes); e_err[q] is that bound with 12u for 11.01u.
 * A sample whose three values are all >= e_err (or all <= -e_err), and whose plane
 * values pass the rigorous plane thresholds, is certainly blocked: its exact segment
 * crosses the closed triangle. The others that pass have some value within an edge's
 * rounding band, where watertightness needs zero to count as inside. There the crossing
 * point can be off the triangle: the edge forms sum to the crossing size X = (S - O).n
 * exactly, X h_q / sum are the crossing's barycentric coordinates, each >= -E_q / X, so
 * the crossing lies within (sum E_q) diam(T) / X of the triangle. Such a sample counts
 * only when X > G = (sum E_q) diam / cross_tol, i.e. (X >= plane value - err_p + |d0| -
 * err_d) when its plane value exceeds graze_thr = G + err_p + err_d - |d0|. What this
 * drops is a sample at an edge of a triangle whose plane its segment nearly lies in: the
 * crossing point is then rounding noise (fuzz/ found GEARS disagreeing with the reference
 * on exactly such samples before); and, because a barycentric error of a sliver moves the
 * point along its length, some samples inside slivers whose long edges' rounding bands
 * cover most of their width (docs/bench/RESULTS.md: the thin scene against Embree). Both
 * pn_tri_mask() and pn_tri_sample() call this. cross_tol <= 0 switches the test off
 * (every band sample counts). */
PN_KFN void pn_tri_graze(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, pn_tri_forms *F)
{
    float tol = L->cross_tol;
    F->e_err[0] = F->e_err[1] = F->e_err[2] = 0.0f;
    F->graze_thr = F->plane_thr;
    if (tol > 0.0f) {
        pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
        pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
        pn_v3 cO = pn_v3_sub(pn_v3_make(L->c[0], L->c[1], L->c[2]), O);
        pn_v3 W = pn_v3_add(pn_v3_add(pn_v3_abs(cO), pn_v3_abs(U)), pn_v3_abs(V));
        float diam = pn_kmaxf(pn_v3_l1(pn_v3_sub(B, A)), pn_kmaxf(pn_v3_l1(pn_v3_sub(C, B)), pn_v3_l1(pn_v3_sub(A, C))));
        float g;
        F->e_err[0] = pn_edge_err(A, B, O, W);
        F->e_err[1] = pn_edge_err(B, C, O, W);
        F->e_err[2] = pn_edge_err(C, A, O, W);
        g = (F->e_err[0] + F->e_err[1] + F->e_err[2]) * diam / tol;
        F->graze_thr = pn_kmaxf(F->plane_thr, ((g + F->err_p) + F->err_d) - F->d0_abs);
    }
}

PN_KFN void pn_tri_edges(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, pn_tri_forms *F)
{
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
    pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    pn_v3 cO = pn_v3_sub(pn_v3_make(L->c[0], L->c[1], L->c[2]), O);
    F->e[0] = pn_edge_form(A, B, O, cO, U, V);
    F->e[1] = pn_edge_form(B, C, O, cO, U, V);
    F->e[2] = pn_edge_form(C, A, O, cO, U, V);
}

/* Value of a form at sample (a, b), in the one evaluation order (see the top). */
PN_KFN float pn_lin_at(pn_lin f, float a, float b) { return (f.h0 + b * f.hv) + a * f.hu; }

/* Sample (i, j) alone: 1 if triangle ABC blocks it from O. The per-ray form of
 * pn_tri_mask(), for PN_ALGO_RAYTRACE: the same forms, the same value for each sample,
 * the same comparisons (an edge value v passes the negated orientation when -v >= 0,
 * and negation is exact). */
PN_KFN uint32_t pn_tri_sample(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, int32_t i, int32_t j)
{
    pn_tri_forms F;
    float a = pn_sample_coord(i, L->k), b = pn_sample_coord(j, L->k), v0, v1, v2;
    float vp;
    if (!pn_tri_plane(O, A, B, C, L, &F)) return 0u;
    vp = pn_lin_at(F.plane, a, b);
    if (!pn_pass_v(vp, 1, F.plane_thr)) return 0u;
    pn_tri_edges(O, A, B, C, L, &F);
    v0 = pn_lin_at(F.e[0], a, b);
    v1 = pn_lin_at(F.e[1], a, b);
    v2 = pn_lin_at(F.e[2], a, b);
    if (!((v0 >= 0.0f && v1 >= 0.0f && v2 >= 0.0f) || (-v0 >= 0.0f && -v1 >= 0.0f && -v2 >= 0.0f))) return 0u;
    pn_tri_graze(O, A, B, C, L, &F);
    /* Certain, or in a rounding band with a crossing large enough (pn_tri_graze). */
    return (uint32_t)(vp > F.graze_thr || (v0 >= F.e_err[0] && v1 >= F.e_err[1] && v2 >= F.e_err[2]) ||
                      (-v0 >= F.e_err[0] && -v1 >= F.e_err[1] && -v2 >= F.e_err[2]));
}

/* Bits i < n4 (k rounded up to a multiple of 4) of one row where the plane value
 * pb + a_i*phu passes (> thr) and the three edge values b_q + a_i*h_q are all >= 0 or all
 * <= 0 (-v >= 0 is v <= 0, so this is both orientations of pn_tri_sample()). No branches
 * and no variable shifts (pw[i] = 1 << i), in groups of four lanes: GCC 12 vectorizes the
 * group loop at -O2 (SSE2) and the outer loop at -O3; PoCL picks its own widths. The row is
 * most of the predicate's cost (issue 5 profile). Measured with callgrind (reference pass,
 * bunny 64x64): lanes written out by hand with a shift per group, as before, stayed scalar
 * (842 M instructions at -O3); one flat loop to n: 478 M at -O3, but GCC 12 -O2 left it
 * scalar (-fopt-info-vec on the loop alone); this form: 489 M at -O3, vectorized at -O2 too.
 * Building pw costs one store per lane per call; hoisting it and av out of the call would
 * change every caller's signature for about 1% (GEARS profile), so it stays here. */
PN_KFN uint32_t pn_row_bits(const float *av, const uint32_t *pw, int32_t n4, float pb, float phu, float thr,
                            float b0, float h0, float b1, float h1, float b2, float h2)
{
    uint32_t bits = 0u;
    int32_t i0, l;
    for (i0 = 0; i0 < n4; i0 += 4) {
        for (l = 0; l < 4; l++) {
            float a = av[i0 + l];
            float vp = pb + a * phu, v0 = b0 + a * h0, v1 = b1 + a * h1, v2 = b2 + a * h2;
            int32_t pos = (v0 >= 0.0f) & (v1 >= 0.0f) & (v2 >= 0.0f);
            int32_t neg = (v0 <= 0.0f) & (v1 <= 0.0f) & (v2 <= 0.0f);
            int32_t ok = (vp > thr) & (pos | neg);
            bits |= (0u - (uint32_t)ok) & pw[i0 + l];
        }
    }
    return bits;
}

/* pn_row_bits() for a triangle some of whose samples can fall under the certainty test
 * (pn_tri_graze): a lane that passes the plane (> thr) and the edges (all >= 0 or all
 * <= 0) counts when its plane value also exceeds gthr or its edge values clear the
 * rounding bounds r_q (all >= r_q or all <= -r_q): pn_tri_sample()'s expression. A copy
 * of pn_row_bits()'s loop with three more tests, kept separate so that the hot loop
 * (every row of every candidate) carries none of them. */
PN_KFN uint32_t pn_row_bits_band(const float *av, const uint32_t *pw, int32_t n4, float pb, float phu, float thr,
                                 float gthr, float b0, float h0, float b1, float h1, float b2, float h2, float r0,
                                 float r1, float r2)
{
    uint32_t bits = 0u;
    int32_t i0, l;
    for (i0 = 0; i0 < n4; i0 += 4) {
        for (l = 0; l < 4; l++) {
            float a = av[i0 + l];
            float vp = pb + a * phu, v0 = b0 + a * h0, v1 = b1 + a * h1, v2 = b2 + a * h2;
            int32_t pos = (v0 >= 0.0f) & (v1 >= 0.0f) & (v2 >= 0.0f);
            int32_t neg = (v0 <= 0.0f) & (v1 <= 0.0f) & (v2 <= 0.0f);
            int32_t cpos = (v0 >= r0) & (v1 >= r1) & (v2 >= r2);
            int32_t cneg = (-v0 >= r0) & (-v1 >= r1) & (-v2 >= r2);
            int32_t ok = (vp > thr) & (pos | neg) & ((vp > gthr) | cpos | cneg);
            bits |= (0u - (uint32_t)ok) & pw[i0 + l];
        }
    }
    return bits;
}

/* ORs into m (PN_MASK_WORDS_MAX words, bit j*k + i) the samples of light L that triangle
 * ABC blocks from O. Returns 1 if it blocks at least one sample, else 0. */
PN_KFN uint32_t pn_tri_mask(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, uint32_t *m)
{
    uint32_t k = L->k;
    pn_tri_forms F;
    pn_lin plane, e[3], ne[3];
    float plane_thr;
    int pos_ok, neg_ok, band;
    uint32_t any = 0;
    int32_t j, row_lo, row_hi;

    if (!pn_tri_plane(O, A, B, C, L, &F)) return 0;
    plane = F.plane;
    plane_thr = F.plane_thr;
    if (!(pn_lin_max(plane, k) > plane_thr)) return 0;

    pn_tri_edges(O, A, B, C, L, &F);
    e[0] = F.e[0];
    e[1] = F.e[1];
    e[2] = F.e[2];
    ne[0] = pn_lin_neg(e[0]);
    ne[1] = pn_lin_neg(e[1]);
    ne[2] = pn_lin_neg(e[2]);
    pos_ok = pn_lin_max(e[0], k) >= 0.0f && pn_lin_max(e[1], k) >= 0.0f &&
             pn_lin_max(e[2], k) >= 0.0f;
    neg_ok = pn_lin_max(ne[0], k) >= 0.0f && pn_lin_max(ne[1], k) >= 0.0f &&
             pn_lin_max(ne[2], k) >= 0.0f;
    if (!pos_ok && !neg_ok) return 0;

    {
        /* Rows where the plane and, for some orientation, all three edges can pass. */
        int32_t plo = 0, phi = (int32_t)k - 1, jlo = (int32_t)k, jhi = -1, s, q;
        pn_rows_narrow(plane, k, 1, plane_thr, &plo, &phi);
        for (s = 0; s < 2; s++) {
            int32_t lo = plo, hi = phi;
            if (!(s == 0 ? pos_ok : neg_ok)) continue;
            for (q = 0; q < 3; q++) pn_rows_narrow(s == 0 ? e[q] : ne[q], k, 0, 0.0f, &lo, &hi);
            if (lo > hi) {
                if (s == 0) pos_ok = 0; else neg_ok = 0;
                continue;
            }
            jlo = pn_kmini(jlo, lo);
            jhi = pn_kmaxi(jhi, hi);
        }
        row_lo = jlo;
        row_hi = jhi;
    }
    {
        /* Every sample of the candidate rows, evaluated branch-free (the row loop
         * vectorizes): the same value and comparisons as pn_tri_sample().
         * a_i = (2i+1)*(1/k) - 1 equals pn_sample_coord() exactly: k is a power of two. */
        float rk = 1.0f / (float)k, av[32]; /* k <= 32 */
        uint32_t keep = k >= 32u ? 0xFFFFFFFFu : ((1u << k) - 1u), pw[32], rows[32], bits, bit;
        int32_t n4 = ((int32_t)k + 3) & ~3, i;
        for (i = 0; i < n4; i++) {
            av[i] = (float)(2 * i + 1) * rk - 1.0f;
            pw[i] = 1u << (uint32_t)i;
        }
        for (j = row_lo; j <= row_hi; j++) {
            float b = av[j];
            float pb = plane.h0 + b * plane.hv;
            float b0 = e[0].h0 + b * e[0].hv, b1 = e[1].h0 + b * e[1].hv, b2 = e[2].h0 + b * e[2].hv;
            bit = (uint32_t)j * k;
            rows[j] = 0u;
            if (((m[bit >> 5] >> (bit & 31u)) & keep) == keep) continue; /* row already blocked */
            rows[j] = keep & pn_row_bits(av, pw, n4, pb, plane.hu, plane_thr, b0, e[0].hu, b1, e[1].hu, b2, e[2].hu);
            any |= rows[j];
        }
        if (!any) return 0;
        /* Samples that pass: the certainty test (pn_tri_graze) can only drop some of them,
         * and only if graze_thr is above plane_thr and some sample's plane value is at
         * most graze_thr (the smallest over the grid is at a corner). Computed only now,
         * for the few triangles that block something. */
        pn_tri_graze(O, A, B, C, L, &F);
        band = F.graze_thr > plane_thr && !(-pn_lin_max(pn_lin_neg(plane), k) > F.graze_thr);
        any = 0;
        for (j = row_lo; j <= row_hi; j++) {
            bits = rows[j];
            if (bits && band) {
                float b = av[j];
                float pb = plane.h0 + b * plane.hv;
                float b0 = e[0].h0 + b * e[0].hv, b1 = e[1].h0 + b * e[1].hv, b2 = e[2].h0 + b * e[2].hv;
                bits &= pn_row_bits_band(av, pw, n4, pb, plane.hu, plane_thr, F.graze_thr, b0, e[0].hu, b1, e[1].hu,
                                         b2, e[2].hu, F.e_err[0], F.e_err[1], F.e_err[2]);
            }
            if (bits) {
                bit = (uint32_t)j * k;
                m[bit >> 5] |= bits << (bit & 31u);
                any = 1;
            }
        }
    }
    return any;
}

/* ---- Per-pixel set-up shared by every exact algorithm --------------------------------- */

/* From the G-buffer point P and unit geometric normal nrm, the shadow-ray origin
 * O = P + eps*n with n turned toward the light centre. Returns 0 when P cannot see the
 * light at all (behind a one-sided area light: (P - c).N <= 0), else 1. */
PN_KFN int pn_shadow_origin(pn_v3 P, pn_v3 nrm, const pn_klight *L, pn_v3 *O)
{
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    pn_v3 toc = pn_v3_sub(c, P);
    if (!L->is_point) {
        pn_v3 N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
        if (!(pn_v3_dot(pn_v3_sub(P, c), N) > 0.0f)) return 0;
    }
    if (pn_v3_dot(nrm, toc) < 0.0f) nrm = pn_v3_scale(nrm, -1.0f);
    *O = pn_v3_add(P, pn_v3_scale(nrm, L->eps));
    return 1;
}

PN_KFN uint32_t pn_mask_words(uint32_t k) { return (k * k + 31u) >> 5; }

PN_KFN void pn_mask_clear(uint32_t *m)
{
    uint32_t w;
    for (w = 0; w < PN_MASK_WORDS_MAX; w++) m[w] = 0u;
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
