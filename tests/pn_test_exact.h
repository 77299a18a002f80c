/* pn_test_exact.h - an exact arbiter of visibility (DESIGN.md invariant 6), independent of
 * the library's predicate: its own formulation (edges as (S - O).((P1 - O) x (P2 - O)) in
 * winding order, no canonical order, no linear forms over the grid), a double-precision
 * filter with a verified error bound, and, inside the bound, exact big-integer arithmetic
 * (every float is an integer multiple of 2^-149, so every value here, scaled by 2^447 k, is
 * an integer: no rounding at all, whatever the exponents). Host-only test code: double,
 * libc and all are fine here.
 *
 * Sample (i, j) of k x k is the exact point c + a U + b V, a = (2i+1-k)/k, b = (2j+1-k)/k.
 * It is blocked from O when it lies on or behind the plane of P's own triangle (the side
 * away from P's normal turned toward c), or when some other triangle has O and the sample
 * strictly on opposite sides of its plane and the three edge values of one sign (zero
 * counts as either). */
#ifndef PN_TEST_EXACT_H
#define PN_TEST_EXACT_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- Signed big integers: 24 limbs of 32 bits (768 bits; the values need < 600) -------- */

#define AB_N 24
typedef struct ab_int {
    int neg;
    uint32_t w[AB_N]; /* little-endian magnitude */
} ab_int;

static inline ab_int ab_zero(void)
{
    ab_int r;
    memset(&r, 0, sizeof(r));
    return r;
}

/* f * 2^149, an integer for every finite float. */
static inline ab_int ab_from_float(float f)
{
    ab_int r = ab_zero();
    uint32_t bits, e, m, s;
    memcpy(&bits, &f, 4);
    e = (bits >> 23) & 0xFFu;
    m = bits & 0x7FFFFFu;
    if (e == 0xFFu) abort(); /* not finite */
    if (e != 0u) {
        m |= 0x800000u;
        s = e - 1u; /* (m * 2^(e-150)) * 2^149 = m << (e - 1) */
    } else {
        s = 0u;
    }
    {
        uint64_t v = (uint64_t)m << (s & 31u);
        r.w[s >> 5] = (uint32_t)v;
        if ((s >> 5) + 1u < AB_N) r.w[(s >> 5) + 1u] = (uint32_t)(v >> 32);
    }
    r.neg = (bits >> 31) && m != 0u;
    return r;
}

static inline ab_int ab_from_int(int64_t v)
{
    ab_int r = ab_zero();
    uint64_t a = v < 0 ? (uint64_t)(-v) : (uint64_t)v;
    r.w[0] = (uint32_t)a;
    r.w[1] = (uint32_t)(a >> 32);
    r.neg = v < 0;
    return r;
}

static inline int ab_is_zero(const ab_int *a)
{
    int i;
    for (i = 0; i < AB_N; i++)
        if (a->w[i]) return 0;
    return 1;
}

static inline int ab_cmp_mag(const ab_int *a, const ab_int *b)
{
    int i;
    for (i = AB_N - 1; i >= 0; i--)
        if (a->w[i] != b->w[i]) return a->w[i] < b->w[i] ? -1 : 1;
    return 0;
}

static inline ab_int ab_add(ab_int a, ab_int b)
{
    ab_int r = ab_zero();
    int i;
    if (a.neg == b.neg) {
        uint64_t c = 0;
        for (i = 0; i < AB_N; i++) {
            c += (uint64_t)a.w[i] + b.w[i];
            r.w[i] = (uint32_t)c;
            c >>= 32;
        }
        if (c) abort(); /* overflow: never with these magnitudes */
        r.neg = a.neg;
    } else {
        const ab_int *x = &a, *y = &b;
        int64_t br = 0;
        if (ab_cmp_mag(&a, &b) < 0) {
            x = &b;
            y = &a;
        }
        for (i = 0; i < AB_N; i++) {
            int64_t d = (int64_t)x->w[i] - y->w[i] - br;
            br = d < 0;
            r.w[i] = (uint32_t)(d + (br ? ((int64_t)1 << 32) : 0));
        }
        r.neg = x->neg;
    }
    if (ab_is_zero(&r)) r.neg = 0;
    return r;
}

static inline ab_int ab_neg(ab_int a)
{
    if (!ab_is_zero(&a)) a.neg = !a.neg;
    return a;
}

static inline ab_int ab_sub(ab_int a, ab_int b) { return ab_add(a, ab_neg(b)); }

static inline ab_int ab_mul(ab_int a, ab_int b)
{
    uint32_t t[2 * AB_N];
    ab_int r = ab_zero();
    int i, j;
    memset(t, 0, sizeof(t));
    for (i = 0; i < AB_N; i++) {
        uint64_t c = 0;
        if (!a.w[i]) continue;
        for (j = 0; j < AB_N; j++) {
            c += (uint64_t)a.w[i] * b.w[j] + t[i + j];
            t[i + j] = (uint32_t)c;
            c >>= 32;
        }
        t[i + AB_N] = (uint32_t)c;
    }
    for (i = AB_N; i < 2 * AB_N; i++)
        if (t[i]) abort(); /* overflow: never with these magnitudes */
    memcpy(r.w, t, sizeof(r.w));
    r.neg = a.neg != b.neg && !ab_is_zero(&r);
    return r;
}

static inline int ab_sign(const ab_int *a) { return ab_is_zero(a) ? 0 : (a->neg ? -1 : 1); }

/* ---- The arbiter's one value --------------------------------------------------------------- */

/* Calls that needed the big integers (for the test's report). */
static unsigned long arb_exact_calls;

/* Exact sign of (P0 - Q + (ai/k) U + (bi/k) V) . ((X1 - Y1) x (X2 - Y2)), big integers only. */
static inline int arb_sign_exact(const float P0[3], const float Q[3], const float U[3], const float V[3], int ai, int bi,
                                 int k, const float X1[3], const float Y1[3], const float X2[3], const float Y2[3])
{
    ab_int acc = ab_zero(), kk = ab_from_int(k), A = ab_from_int(ai), B = ab_from_int(bi);
    int c;
    arb_exact_calls++;
    for (c = 0; c < 3; c++) {
        int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        /* k D_c, exactly, as an integer times 2^-149; the cross product times 2^-298 */
        ab_int d = ab_add(ab_add(ab_mul(ab_sub(ab_from_float(P0[c]), ab_from_float(Q[c])), kk), ab_mul(A, ab_from_float(U[c]))),
                          ab_mul(B, ab_from_float(V[c])));
        ab_int m = ab_sub(ab_mul(ab_sub(ab_from_float(X1[c1]), ab_from_float(Y1[c1])),
                                 ab_sub(ab_from_float(X2[c2]), ab_from_float(Y2[c2]))),
                          ab_mul(ab_sub(ab_from_float(X1[c2]), ab_from_float(Y1[c2])),
                                 ab_sub(ab_from_float(X2[c1]), ab_from_float(Y2[c1]))));
        acc = ab_add(acc, ab_mul(d, m));
    }
    return ab_sign(&acc);
}

/* The second factor (X1 - Y1) x (X2 - Y2) in double and a bound on its magnitudes, for the
 * filter; the float inputs kept for the exact fallback. */
typedef struct arb_form {
    double M[3], Mm[3];
    const float *X1, *Y1, *X2, *Y2;
} arb_form;

static inline void arb_form_make(arb_form *f, const float X1[3], const float Y1[3], const float X2[3], const float Y2[3])
{
    int c;
    for (c = 0; c < 3; c++) {
        int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        double e1a = (double)X1[c1] - Y1[c1], e2b = (double)X2[c2] - Y2[c2];
        double e1b = (double)X1[c2] - Y1[c2], e2a = (double)X2[c1] - Y2[c1];
        f->M[c] = e1a * e2b - e1b * e2a;
        f->Mm[c] = (fabs(X1[c1]) + fabs(Y1[c1])) * (fabs(X2[c2]) + fabs(Y2[c2])) +
                   (fabs(X1[c2]) + fabs(Y1[c2])) * (fabs(X2[c1]) + fabs(Y2[c1]));
    }
    f->X1 = X1;
    f->Y1 = Y1;
    f->X2 = X2;
    f->Y2 = Y2;
}

/* The first factor P0 - Q + a U + b V in double (D) and its magnitudes (Dm). */
static inline void arb_first(const float P0[3], const float Q[3], const float U[3], const float V[3], int ai, int bi,
                             int k, double D[3], double Dm[3])
{
    double a = (double)ai / k, b = (double)bi / k;
    int c;
    for (c = 0; c < 3; c++) {
        D[c] = (((double)P0[c] - Q[c]) + a * U[c]) + b * V[c];
        Dm[c] = fabs(P0[c]) + fabs(Q[c]) + fabs(a * U[c]) + fabs(b * V[c]);
    }
}

/* Sign of D . M: the double filter, then the big integers. Each double value passes through
 * at most 12 roundings (each relative 2^-53, on magnitudes bounded by Dm . Mm; no double here
 * can underflow, products of three floats being >= 2^-447): 2^-48 Dm . Mm bounds the error
 * with room to spare. */
static inline int arb_form_sign(const arb_form *f, const double D[3], const double Dm[3], const float P0[3],
                                const float Q[3], const float U[3], const float V[3], int ai, int bi, int k)
{
    double v = D[0] * f->M[0] + D[1] * f->M[1] + D[2] * f->M[2];
    double mag = Dm[0] * f->Mm[0] + Dm[1] * f->Mm[1] + Dm[2] * f->Mm[2];
    if (v > 0x1p-48 * mag) return 1;
    if (v < -0x1p-48 * mag) return -1;
    return arb_sign_exact(P0, Q, U, V, ai, bi, k, f->X1, f->Y1, f->X2, f->Y2);
}

/* Sign of (P0 - Q + (ai/k) U + (bi/k) V) . ((X1 - Y1) x (X2 - Y2)) for float inputs. */
static inline int arb_sign_dot(const float P0[3], const float Q[3], const float U[3], const float V[3], int ai, int bi,
                               int k, const float X1[3], const float Y1[3], const float X2[3], const float Y2[3])
{
    arb_form f;
    double D[3], Dm[3];
    arb_form_make(&f, X1, Y1, X2, Y2);
    arb_first(P0, Q, U, V, ai, bi, k, D, Dm);
    return arb_form_sign(&f, D, Dm, P0, Q, U, V, ai, bi, k);
}

/* ---- Blocking -------------------------------------------------------------------------- */

typedef struct arb_light {
    float c[3], U[3], V[3];
    int k;
} arb_light;

static const float arb_zero3[3] = {0.0f, 0.0f, 0.0f};

/* Sign of O's side of triangle ABC's plane (0: in it). */
static inline int arb_side_O(const float O[3], const float *A, const float *B, const float *C)
{
    return arb_sign_dot(O, A, arb_zero3, arb_zero3, 0, 0, 1, B, A, C, A);
}

/* Triangle ABC seen from O, prepared: its plane and edge factors, O's side s0. */
typedef struct arb_tri {
    arb_form plane, e[3];
    int s0;
} arb_tri;

static inline void arb_tri_make(arb_tri *T, const float O[3], const float *A, const float *B, const float *C)
{
    arb_form_make(&T->plane, B, A, C, A);
    arb_form_make(&T->e[0], A, O, B, O);
    arb_form_make(&T->e[1], B, O, C, O);
    arb_form_make(&T->e[2], C, O, A, O);
    T->s0 = arb_side_O(O, A, B, C);
}

/* 1 if prepared triangle T (vertex A) blocks sample (i, j) from O. */
static inline int arb_tri_blocks_p(const arb_tri *T, const float O[3], const float *A, const arb_light *L, int i, int j)
{
    int ai = 2 * i + 1 - L->k, bi = 2 * j + 1 - L->k, sp, e0, e1, e2;
    double DA[3], DAm[3], DO[3], DOm[3];
    if (T->s0 == 0) return 0;
    arb_first(L->c, A, L->U, L->V, ai, bi, L->k, DA, DAm);
    sp = arb_form_sign(&T->plane, DA, DAm, L->c, A, L->U, L->V, ai, bi, L->k);
    if (sp == 0 || sp == T->s0) return 0;
    arb_first(L->c, O, L->U, L->V, ai, bi, L->k, DO, DOm);
    e0 = arb_form_sign(&T->e[0], DO, DOm, L->c, O, L->U, L->V, ai, bi, L->k);
    e1 = arb_form_sign(&T->e[1], DO, DOm, L->c, O, L->U, L->V, ai, bi, L->k);
    if (e0 * e1 < 0) return 0;
    e2 = arb_form_sign(&T->e[2], DO, DOm, L->c, O, L->U, L->V, ai, bi, L->k);
    return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

/* Sign that orients own triangle ABC's normal (B - A) x (C - A) to P's front: the side of
 * the normal nrm turned toward c (the turn decided in float, as the library decides it:
 * part of the definition of O). */
static inline int arb_front(const float P[3], const float nrm[3], const float *A, const float *B, const float *C,
                     const arb_light *L)
{
    float t = nrm[0] * (L->c[0] - P[0]) + nrm[1] * (L->c[1] - P[1]) + nrm[2] * (L->c[2] - P[2]);
    double e1[3], e2[3], n[3], d;
    int q;
    for (q = 0; q < 3; q++) {
        e1[q] = (double)B[q] - A[q];
        e2[q] = (double)C[q] - A[q];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    d = n[0] * nrm[0] + n[1] * nrm[1] + n[2] * nrm[2];
    if (t < 0.0f) d = -d;
    return d < 0.0 ? -1 : 1;
}

/* 1 if sample (i, j) is on or behind the plane of the own triangle ABC (front: sgn). */
static inline int arb_horizon(const float *A, const float *B, const float *C, int sgn, const arb_light *L, int i, int j)
{
    return sgn * arb_sign_dot(L->c, A, L->U, L->V, 2 * i + 1 - L->k, 2 * j + 1 - L->k, L->k, B, A, C, A) <= 0;
}

/* Could triangle ABC block any sample from O? A cheap exact-safe reject: O's side s0 != 0
 * and every light corner certainly on O's side (the samples lie in the rectangle, and the
 * plane value is affine in it). */
static inline int arb_tri_may_block(const float *A, const float *B, const float *C, const arb_light *L, int s0)
{
    int q;
    if (s0 == 0) return 0;
    for (q = 0; q < 4; q++) {
        int ai = (q & 1) ? L->k : -L->k, bi = (q & 2) ? L->k : -L->k; /* a, b = +-1 */
        if (arb_sign_dot(L->c, A, L->U, L->V, ai, bi, L->k, B, A, C, A) != s0) return 1;
    }
    return 0;
}

/* 1 if triangle a (9 floats) certainly blocks no sample from O: a triangle that meets a
 * segment from O to a point of the light rectangle meets the convex hull of O and the
 * light's corners, so its box meets the hull's box (the corners in double, widened by far
 * more than their rounding). An exact-safe reject, independent of the library's culls. */
static inline int arb_box_out(const float O[3], const float *a, const arb_light *L)
{
    int q;
    for (q = 0; q < 3; q++) {
        double u = fabs((double)L->U[q]) + fabs((double)L->V[q]), r = 1e-9 * (fabs((double)L->c[q]) + u);
        double lo = fmin((double)O[q], (double)L->c[q] - u) - r, hi = fmax((double)O[q], (double)L->c[q] + u) + r;
        if (fmin(a[q], fmin(a[3 + q], a[6 + q])) > hi || fmax(a[q], fmax(a[3 + q], a[6 + q])) < lo) return 1;
    }
    return 0;
}

/* The exact mask of one pixel (bit j*k + i), every triangle of tris[0 .. nt) tried except
 * own, the horizon of own included. */
static inline void arb_pixel_mask(const float P[3], const float nrm[3], const float O[3], uint32_t own, const float *tris,
                           uint32_t nt, const arb_light *L, uint32_t *mask, uint32_t words)
{
    const float *A = tris + 9u * own, *B = A + 3, *C = A + 6;
    int sgn = arb_front(P, nrm, A, B, C, L), i, j;
    uint32_t t;
    memset(mask, 0, words * sizeof(uint32_t));
    for (j = 0; j < L->k; j++)
        for (i = 0; i < L->k; i++)
            if (arb_horizon(A, B, C, sgn, L, i, j)) mask[(j * L->k + i) >> 5] |= 1u << ((j * L->k + i) & 31);
    for (t = 0; t < nt; t++) {
        const float *a = tris + 9u * t;
        int s0;
        if (t == own || arb_box_out(O, a, L)) continue;
        s0 = arb_side_O(O, a, a + 3, a + 6);
        if (!arb_tri_may_block(a, a + 3, a + 6, L, s0)) continue;
        {
            arb_tri T;
            arb_tri_make(&T, O, a, a + 3, a + 6);
            for (j = 0; j < L->k; j++)
                for (i = 0; i < L->k; i++) {
                    uint32_t bit = (uint32_t)(j * L->k + i);
                    if (mask[bit >> 5] >> (bit & 31u) & 1u) continue;
                    if (arb_tri_blocks_p(&T, O, a, L, i, j)) mask[bit >> 5] |= 1u << (bit & 31u);
                }
        }
    }
}

#endif
