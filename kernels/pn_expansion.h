/* pn_expansion.h - exact signs of the predicate's values by adaptive expansion arithmetic in
 * float (Shewchuk 1997, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
 * Geometric Predicates"): two-sum, two-product by Dekker splitting, expansion sum and
 * scaling with zero elimination. No FMA, no double, no libm: the same bits on every IEEE
 * single-precision unit with round-to-nearest-even and no contraction (-ffp-contract=off,
 * FP_CONTRACT OFF), OpenCL devices without fp64 included.
 *
 * An expansion is an array of floats, smallest magnitude first, nonoverlapping, whose exact
 * (real) sum is the value; its sign is the sign of its last (largest) component once zeros
 * are eliminated.
 *
 * Range in which every result here is exact (Shewchuk's proofs assume neither overflow nor
 * underflow). pn_x_sign_dot first scales all its coordinates by one power of two (exact,
 * and it leaves the sign of a degree-3 homogeneous value unchanged) so that the largest
 * magnitude M among them lies in (2^38, 2^39].
 *   - overflow: the values are degree-3 polynomials in coordinate differences. With every
 *     scaled coordinate at most 2^39 in magnitude, a difference is at most 2^40, a
 *     cross-product component at most 2^81, a component of P0 - Q + a U + b V at most 2^41
 *     and a value below 3 * 2^41 * 2^81 < 2^124; Dekker's split multiplies by 4097 only
 *     operands below 2^82. Nothing overflows. (The inputs themselves stay within about
 *     2^41: vertices and light within PN_MAX_COORD = 2^40, src/pn_internal.h, O = P +
 *     eps n with eps <= 2^40; scaling those down by at most 4 is exact for every
 *     coordinate in the range below.)
 *   - underflow: two-sum is exact even among subnormals; two-product is exact when the
 *     exact product of its operands is a multiple of 2^-149 (its rounding error is then
 *     representable, subnormal or not). After the scaling, every nonzero coordinate of
 *     magnitude >= 2^-25 is a multiple of 2^-48, so every product is a multiple of
 *     2^-48 * 2^-48 * 2^-48 * 2^-5 (a_i = (2i+1)/k - 1 is a multiple of 1/k >= 2^-5) =
 *     2^-149: exact. That holds whenever every nonzero coordinate entering the test is at
 *     least 2^-63 times the largest one (M scaled above 2^38). Outside that range (say a
 *     vertex coordinate of 1e-25 beside coordinates of 1) a product's last bits below
 *     2^-149 can be lost, so a value within about 2^-140 M^3 of zero (an exact degeneracy
 *     involving such a coordinate) could get the wrong sign; the result is still
 *     deterministic and the same on both ports as long as the device keeps subnormals
 *     (the scalar port and PoCL do; OpenCL lets single-precision devices flush them).
 * tests/test_exact.c checks the signs against an independent exact (big-integer) arbiter. */
#ifndef PN_EXPANSION_H
#define PN_EXPANSION_H

#include "pn_kmath.h"

/* 2^12 + 1: splits a 24-bit significand into two halves of at most 12 bits. */
#define PN_XSPLITTER 4097.0f

/* Capacities (floats) of the work arrays of pn_x_sign_dot, from the structure of the
 * computation: a difference 2 terms, a cross-product component 2 * (4 + 4) = 16, a
 * component of the first factor 6, their product 6 * 2 * 16 = 192, the dot 3 * 192 = 576.
 * About 4.7 KB of stack in all (tests/check_callgraph.c bounds every public function). */
#define PN_XCROSS 16
#define PN_XDOT 584 /* 576, and the leading zero of the accumulator */

/* x + y = a + b exactly, x = fl(a + b). */
PN_KFN void pn_x_two_sum(float a, float b, float *x, float *y)
{
    float s = a + b, bv = s - a, av = s - bv, br = b - bv, ar = a - av;
    *x = s;
    *y = ar + br;
}

/* x + y = a - b exactly. */
PN_KFN void pn_x_two_diff(float a, float b, float *x, float *y)
{
    float s = a - b, bv = a - s, av = s + bv, br = bv - b, ar = a - av;
    *x = s;
    *y = ar + br;
}

/* x + y = a + b, |a| >= |b| (or a == 0). */
PN_KFN void pn_x_fast_two_sum(float a, float b, float *x, float *y)
{
    float s = a + b, bv = s - a;
    *x = s;
    *y = b - bv;
}

PN_KFN void pn_x_split(float a, float *hi, float *lo)
{
    float c = PN_XSPLITTER * a, abig = c - a;
    *hi = c - abig;
    *lo = a - *hi;
}

/* x + y = a * b exactly (Dekker), b already split into bhi + blo. */
PN_KFN void pn_x_two_product_presplit(float a, float b, float bhi, float blo, float *x, float *y)
{
    float p = a * b, ahi, alo, e1, e2, e3;
    pn_x_split(a, &ahi, &alo);
    e1 = p - ahi * bhi;
    e2 = e1 - alo * bhi;
    e3 = e2 - ahi * blo;
    *x = p;
    *y = alo * blo - e3;
}

PN_KFN void pn_x_two_product(float a, float b, float *x, float *y)
{
    float bhi, blo;
    pn_x_split(b, &bhi, &blo);
    pn_x_two_product_presplit(a, b, bhi, blo, x, y);
}

/* h = e + f (Shewchuk's fast_expansion_sum_zeroelim, without its reads past the ends);
 * returns the length of h, >= 1 (a zero expansion is {0}). elen, flen >= 1; h must hold
 * elen + flen floats and may not alias e or f. */
PN_KFN int32_t pn_x_sum(int32_t elen, const float *e, int32_t flen, const float *f, float *h)
{
    float Q, Qn, hh, en = e[0], fn = f[0];
    int32_t ei = 0, fi = 0, hi = 0;
    if ((fn > en) == (fn > -en)) {
        Q = en;
        ei++;
        en = ei < elen ? e[ei] : 0.0f;
    } else {
        Q = fn;
        fi++;
        fn = fi < flen ? f[fi] : 0.0f;
    }
    if (ei < elen && fi < flen) {
        if ((fn > en) == (fn > -en)) {
            pn_x_fast_two_sum(en, Q, &Qn, &hh);
            ei++;
            en = ei < elen ? e[ei] : 0.0f;
        } else {
            pn_x_fast_two_sum(fn, Q, &Qn, &hh);
            fi++;
            fn = fi < flen ? f[fi] : 0.0f;
        }
        Q = Qn;
        if (hh != 0.0f) h[hi++] = hh;
        while (ei < elen && fi < flen) {
            if ((fn > en) == (fn > -en)) {
                pn_x_two_sum(Q, en, &Qn, &hh);
                ei++;
                en = ei < elen ? e[ei] : 0.0f;
            } else {
                pn_x_two_sum(Q, fn, &Qn, &hh);
                fi++;
                fn = fi < flen ? f[fi] : 0.0f;
            }
            Q = Qn;
            if (hh != 0.0f) h[hi++] = hh;
        }
    }
    while (ei < elen) {
        pn_x_two_sum(Q, en, &Qn, &hh);
        ei++;
        en = ei < elen ? e[ei] : 0.0f;
        Q = Qn;
        if (hh != 0.0f) h[hi++] = hh;
    }
    while (fi < flen) {
        pn_x_two_sum(Q, fn, &Qn, &hh);
        fi++;
        fn = fi < flen ? f[fi] : 0.0f;
        Q = Qn;
        if (hh != 0.0f) h[hi++] = hh;
    }
    if (Q != 0.0f || hi == 0) h[hi++] = Q;
    return hi;
}

/* h = b * e (scale_expansion_zeroelim); h holds 2 * elen floats, no aliasing. */
PN_KFN int32_t pn_x_scale(int32_t elen, const float *e, float b, float *h)
{
    float bhi, blo, Q, hh, p1, p0, s;
    int32_t i, hi = 0;
    pn_x_split(b, &bhi, &blo);
    pn_x_two_product_presplit(e[0], b, bhi, blo, &Q, &hh);
    if (hh != 0.0f) h[hi++] = hh;
    for (i = 1; i < elen; i++) {
        pn_x_two_product_presplit(e[i], b, bhi, blo, &p1, &p0);
        pn_x_two_sum(Q, p0, &s, &hh);
        if (hh != 0.0f) h[hi++] = hh;
        pn_x_fast_two_sum(p1, s, &Q, &hh);
        if (hh != 0.0f) h[hi++] = hh;
    }
    if (Q != 0.0f || hi == 0) h[hi++] = Q;
    return hi;
}

/* Sign (-1, 0, 1) of a zero-eliminated expansion: that of its largest component. */
PN_KFN int32_t pn_x_sign(int32_t n, const float *e)
{
    float t = e[n - 1];
    return t > 0.0f ? 1 : (t < 0.0f ? -1 : 0);
}

/* Exact (x1 + x0) * (y1 + y0) - (z1 + z0) * (w1 + w0) into h (PN_XCROSS floats): one
 * cross-product component of two vectors whose components are exact differences. */
PN_KFN int32_t pn_x_cross1(float x1, float x0, float y1, float y0, float z1, float z0, float w1, float w0, float *h)
{
    float a[2], b[2], s0[4], s1[4], p[8], q[8];
    int32_t n0, n1, np, nq, i;
    a[0] = x0;
    a[1] = x1;
    n0 = pn_x_scale(2, a, y0, s0);
    n1 = pn_x_scale(2, a, y1, s1);
    np = pn_x_sum(n0, s0, n1, s1, p);
    b[0] = -z0;
    b[1] = -z1;
    n0 = pn_x_scale(2, b, w0, s0);
    n1 = pn_x_scale(2, b, w1, s1);
    nq = pn_x_sum(n0, s0, n1, s1, q);
    i = pn_x_sum(np, p, nq, q, h);
    return i;
}

/* Exact sign of (P0 - Q + a U + b V) . ((e1a - e1b) x (e2a - e2b)) for float inputs, the
 * real value with no rounding (see the range above). Every exact decision of the predicate
 * is one of these: a sample's side of a plane, O's side, an edge value, the horizon. */
PN_KFN int32_t pn_x_sign_dot(pn_v3 P0, pn_v3 Q, pn_v3 U, pn_v3 V, float a, float b, pn_v3 e1a, pn_v3 e1b,
                             pn_v3 e2a, pn_v3 e2b)
{
    float d1[3][2], d2[3][2], m[3][PN_XCROSS], acc[PN_XDOT], tmp[PN_XDOT], sc[2 * PN_XCROSS], D[6], t[6];
    float x8[8][3], M = 0.0f;
    int32_t mn[3], c, r, na = 1, nd, ns, nt, i;
    /* Components as arrays (no address-of on the vector's fields: OpenCL C 1.2 and C alike):
     * 0 P0, 1 Q, 2 U, 3 V, 4 e1a, 5 e1b, 6 e2a, 7 e2b. */
    x8[0][0] = P0.x; x8[0][1] = P0.y; x8[0][2] = P0.z;
    x8[1][0] = Q.x; x8[1][1] = Q.y; x8[1][2] = Q.z;
    x8[2][0] = U.x; x8[2][1] = U.y; x8[2][2] = U.z;
    x8[3][0] = V.x; x8[3][1] = V.y; x8[3][2] = V.z;
    x8[4][0] = e1a.x; x8[4][1] = e1a.y; x8[4][2] = e1a.z;
    x8[5][0] = e1b.x; x8[5][1] = e1b.y; x8[5][2] = e1b.z;
    x8[6][0] = e2a.x; x8[6][1] = e2a.y; x8[6][2] = e2a.z;
    x8[7][0] = e2b.x; x8[7][1] = e2b.y; x8[7][2] = e2b.z;
    for (i = 0; i < 8; i++)
        for (c = 0; c < 3; c++) M = pn_kmaxf(M, x8[i][c] < 0.0f ? -x8[i][c] : x8[i][c]);
    if (!(M > 0.0f)) return 0;
    /* Scale by a power of two to M in (2^38, 2^39] (see the range above): exact. */
    while (M > 549755813888.0f) { /* 2^39 */
        for (i = 0; i < 8; i++)
            for (c = 0; c < 3; c++) x8[i][c] *= 0.5f;
        M *= 0.5f;
    }
    while (M <= 1073741824.0f) { /* 2^30 */
        for (i = 0; i < 8; i++)
            for (c = 0; c < 3; c++) x8[i][c] *= 256.0f;
        M *= 256.0f;
    }
    while (M <= 274877906944.0f) { /* 2^38 */
        for (i = 0; i < 8; i++)
            for (c = 0; c < 3; c++) x8[i][c] *= 2.0f;
        M *= 2.0f;
    }
    for (c = 0; c < 3; c++) {
        pn_x_two_diff(x8[4][c], x8[5][c], &d1[c][1], &d1[c][0]);
        pn_x_two_diff(x8[6][c], x8[7][c], &d2[c][1], &d2[c][0]);
    }
    for (c = 0; c < 3; c++) {
        int32_t c1 = c == 2 ? 0 : c + 1, c2 = c == 0 ? 2 : c - 1;
        /* (d1 x d2)_c = d1_c1 d2_c2 - d1_c2 d2_c1 */
        mn[c] = pn_x_cross1(d1[c1][1], d1[c1][0], d2[c2][1], d2[c2][0], d1[c2][1], d1[c2][0], d2[c1][1], d2[c1][0],
                            m[c]);
    }
    acc[0] = 0.0f;
    for (c = 0; c < 3; c++) {
        float x[2], y[2], z[2];
        /* The first factor's component: (P0 - Q) + a U + b V, exact in 6 terms. */
        pn_x_two_diff(x8[0][c], x8[1][c], &x[1], &x[0]);
        pn_x_two_product(a, x8[2][c], &y[1], &y[0]);
        pn_x_two_product(b, x8[3][c], &z[1], &z[0]);
        nt = pn_x_sum(2, x, 2, y, t);
        nd = pn_x_sum(nt, t, 2, z, D);
        for (r = 0; r < nd; r++) {
            if (D[r] == 0.0f) continue;
            ns = pn_x_scale(mn[c], m[c], D[r], sc);
            nt = pn_x_sum(na, acc, ns, sc, tmp);
            for (i = 0; i < nt; i++) acc[i] = tmp[i];
            na = nt;
        }
    }
    return pn_x_sign(na, acc);
}

#endif
