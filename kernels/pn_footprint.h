/* pn_footprint.h - the footprint of a box on the light, as a rectangle of sample indices,
 * and the test "does that rectangle still hold a sample the pixel has not found blocked".
 *
 * A sample S_ij is blocked by a triangle only if the exact segment from O to S_ij meets
 * it (pn_predicate.h), at a point X = O + t (S_ij - O), t in (0, 1), of the triangle and so
 * of any box that holds the triangle. Going back from X: S_ij is the central projection of
 * X from O onto the light plane. With N the light's unit normal (pointing to O's side),
 * w(X) = (O - X).N the height of X below O toward the light and D = (O - c).N the height of
 * O above the light, t = w(X) / D, so X lies in the slab 0 < w(X) < D, and S_ij's light
 * coordinates (S = c + a U + b V) are
 *
 *     a = a_O + D g_a(X) / w(X),   g_a(X) = (X - O).U*,   a_O = (O - c).U*,
 *
 * and the same for b with V*; (U*, V*) is the dual basis of (U, V) in the light plane
 * (U* . U = 1, U* . V = 0; U and V are orthogonal to 1e-4, not exactly). Over a box, g and
 * w are linear, so their ranges come from the box's corners componentwise; the ratio's
 * range is interval arithmetic on g / w with w clipped to (0, min(w_max, D)]: for w > 0
 * bounded below, the four corner quotients; a box reaching O's plane (w_min <= 0) leaves
 * the side where g can change sign unbounded. The rectangle is then the sample indices
 * whose a_i, b_j fall in the ranges. A rectangle that misses every sample not yet blocked
 * can hold no new blocked sample: the box is skipped. A point light (k = 1) has no
 * footprint: its rectangle is the one sample, which still makes a node worthless once that
 * sample is blocked.
 *
 * Conservative in the real geometry, with every rounding bounded (u = 2^-24, standard
 * model, |N_i| <= 1 and N within 4u of unit in each component):
 *   - D, and every w over the box: a dot product with the float N of a vector d whose
 *     components are differences rounded by u: error <= 16 u |d|_1 (dot 3u, differences
 *     1u, N's own rounding against the exact normal of the plane spanned by U and V 4u,
 *     doubled), with |d|_1 bounded over the box by the largest corner magnitudes;
 *   - g and a_O: a dot product with the float dual vector, itself within 10 u of the exact
 *     one relative to |U*|inf (two products, a difference, a division): error
 *     <= 32 u |d|_1 |U*|inf;
 *   - the inputs of the interval arithmetic are widened by those bounds first, so the
 *     ranges it forms hold the exact quotients; its own divisions, products and the sum
 *     with a_O round by a few u relative: 1e-6 relative (16 u) is added at the end, and
 *     1e-5 of an index step before the rounding to indices (their own rounding is below
 *     2 k u < 2e-6 for k <= 32);
 *   - NaN anywhere (overflow of hostile coordinates) gives the whole light, and O within
 *     its error of the light plane gives the whole light as well.
 * fuzz/fuzz_gears.c checks on hostile configurations that every sample the exact arbiter
 * finds blocked lies in the rectangle of the blocking triangle's box. */
#ifndef PN_FOOTPRINT_H
#define PN_FOOTPRINT_H

#include "pn_predicate.h" /* PN_KU, PN_KTINY */

/* Per shadow-ray origin. on = 0: every box gets the whole light. */
typedef struct pn_foot {
    pn_v3 O, Ua, Va, N;
    pn_v3 dir;            /* O - c: the walk's order (pn_foot_order) */
    float aO, bO, ea, eb; /* O's light coordinates and their error bounds */
    float D, eD;          /* O's height above the light and its error bound */
    float ua_inf, va_inf; /* |U*|inf, |V*|inf */
    uint32_t k, on;
} pn_foot;

/* Sample indices [i0, i1] x [j0, j1] (columns i along U, rows j along V; the mask bit of
 * sample (i, j) is j k + i). Empty when i0 > i1 or j0 > j1. */
typedef struct pn_rect {
    int32_t i0, i1, j0, j1;
} pn_rect;

PN_KFN pn_rect pn_rect_make(int32_t i0, int32_t i1, int32_t j0, int32_t j1)
{
    pn_rect r;
    r.i0 = i0;
    r.i1 = i1;
    r.j0 = j0;
    r.j1 = j1;
    return r;
}

PN_KFN pn_rect pn_rect_full(uint32_t k) { return pn_rect_make(0, (int32_t)k - 1, 0, (int32_t)k - 1); }

PN_KFN int pn_rect_empty(pn_rect r) { return r.i0 > r.i1 || r.j0 > r.j1; }

/* Sample rectangles pack into one word for a traversal stack: 8 bits per bound (k <= 32). */
PN_KFN uint32_t pn_rect_pack(pn_rect r)
{
    return (uint32_t)r.i0 | ((uint32_t)r.i1 << 8) | ((uint32_t)r.j0 << 16) | ((uint32_t)r.j1 << 24);
}

PN_KFN pn_rect pn_rect_unpack(uint32_t p)
{
    return pn_rect_make((int32_t)(p & 0xFFu), (int32_t)((p >> 8) & 0xFFu), (int32_t)((p >> 16) & 0xFFu),
                        (int32_t)(p >> 24));
}

PN_KFN void pn_foot_make(pn_v3 O, const pn_klight *L, pn_foot *fp)
{
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
    pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    pn_v3 dO = pn_v3_sub(O, pn_v3_make(L->c[0], L->c[1], L->c[2]));
    float uu = pn_v3_dot(U, U), vv = pn_v3_dot(V, V), uv = pn_v3_dot(U, V), det = uu * vv - uv * uv, l1;
    fp->k = L->k;
    fp->O = O;
    fp->dir = dO;
    fp->on = 0u;
    if (L->is_point || !(det > 0.0f)) return;
    fp->N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
    fp->Ua = pn_v3_scale(pn_v3_sub(pn_v3_scale(U, vv), pn_v3_scale(V, uv)), 1.0f / det);
    fp->Va = pn_v3_scale(pn_v3_sub(pn_v3_scale(V, uu), pn_v3_scale(U, uv)), 1.0f / det);
    fp->ua_inf = pn_v3_linf(fp->Ua);
    fp->va_inf = pn_v3_linf(fp->Va);
    l1 = pn_v3_l1(dO);
    fp->aO = pn_v3_dot(dO, fp->Ua);
    fp->bO = pn_v3_dot(dO, fp->Va);
    fp->ea = 32.0f * PN_KU * l1 * fp->ua_inf + PN_KTINY;
    fp->eb = 32.0f * PN_KU * l1 * fp->va_inf + PN_KTINY;
    fp->D = pn_v3_dot(dO, fp->N);
    fp->eD = 16.0f * PN_KU * l1 + PN_KTINY;
    /* O within twice its error of the light plane (or NaN): no useful footprint. */
    fp->on = fp->D > 2.0f * fp->eD && fp->aO == fp->aO && fp->bO == fp->bO;
}

/* Lanes c < 4: sample indices [n0, n1][c] whose coordinate (2 i + 1) / k - 1 can lie in
 * [lo, hi][c]; NaN in either bound: all. Loops of selects, no branch, so that the four
 * lanes (pn_foot_box4) run side by side. */
PN_KFN_HOT void pn_foot_index(const float *lo, const float *hi, uint32_t k, int32_t *n0, int32_t *n1)
{
    float fk = (float)k, a[4], b[4];
    int32_t nan[4], ia[4], ib[4];
    uint32_t c;
    for (c = 0; c < 4u; c++) {
        nan[c] = !(lo[c] == lo[c]) | !(hi[c] == hi[c]);
        a[c] = pn_kclampf(((lo[c] + 1.0f) * fk - 1.0f) * 0.5f - 1e-5f, 0, (int32_t)k);
        b[c] = pn_kclampf(((hi[c] + 1.0f) * fk - 1.0f) * 0.5f + 1e-5f, -1, (int32_t)k - 1);
    }
    for (c = 0; c < 4u; c++) { /* pn_kceil_clamp and pn_kfloor_clamp, in two loops */
        ia[c] = pn_kceil_in(a[c]);
        ib[c] = pn_kfloor_in(b[c]);
    }
    for (c = 0; c < 4u; c++) {
        n0[c] = nan[c] ? 0 : ia[c];
        n1[c] = nan[c] ? (int32_t)k - 1 : ib[c];
    }
}

/* Lanes c < 4 of four boxes: the range [lo[c], hi[c]] of the linear function
 * X -> (X - O).n over box c, with d = X - O given per axis a as [dl, dh][a * 4 + c]. */
PN_KFN_HOT void pn_lin_range4(pn_v3 n, const float *dl, const float *dh, float *lo, float *hi)
{
    uint32_t c;
    for (c = 0; c < 4u; c++) {
        float x0 = n.x * dl[c], x1 = n.x * dh[c], y0 = n.y * dl[4u + c], y1 = n.y * dh[4u + c];
        float z0 = n.z * dl[8u + c], z1 = n.z * dh[8u + c];
        lo[c] = (pn_kminf(x0, x1) + pn_kminf(y0, y1)) + pn_kminf(z0, z1);
        hi[c] = (pn_kmaxf(x0, x1) + pn_kmaxf(y0, y1)) + pn_kmaxf(z0, z1);
    }
}

/* Lanes c < 4: sample indices [n0, n1][c] whose coordinate (2n + 1) / k - 1 can lie in
 * [o + r_lo, o + r_hi], r = D g / w over g in [glo, ghi][c] widened by e_g = eu mag[c] +
 * PN_KTINY, w in [wlo, whi][c] (whi > 0, D in [dlo, dhi], dlo > 0), o within eo of O's
 * coordinate. For w > 0 bounded below, the extreme quotients over the corners; else only
 * g / whi, on the side where g cannot change sign. Every division is used on every path
 * (w0 is wlo or whi, so for wlo <= 0 the min and max are of two equal quotients): the
 * lanes then run side by side without a branch. */
PN_KFN_HOT void pn_foot_axis4(float o, float eo, float eu, const float *glo, const float *ghi, const float *mag,
                              const float *wlo, const float *whi, float dlo, float dhi, uint32_t k, int32_t *n0,
                              int32_t *n1)
{
    float gl[4], gh[4], a0[4], a1[4], b0[4], b1[4];
    int32_t bl[4], bh[4];
    uint32_t c;
    /* The comparisons and the quotients first, in loops of their own, so that none is
     * left behind a branch (a compiler would sink a quotient used on one side only). */
    for (c = 0; c < 4u; c++) {
        float eg = eu * mag[c] + PN_KTINY;
        gl[c] = glo[c] - eg;
        gh[c] = ghi[c] + eg;
        bl[c] = (wlo[c] > 0.0f) | (gl[c] >= 0.0f);
        bh[c] = (wlo[c] > 0.0f) | (gh[c] <= 0.0f);
    }
    for (c = 0; c < 4u; c++) {
        float wl = wlo[c], wh = whi[c], w0 = wl > 0.0f ? wl : wh;
        a0[c] = gl[c] / w0;
        a1[c] = gl[c] / wh;
        b0[c] = gh[c] / w0;
        b1[c] = gh[c] / wh;
    }
    for (c = 0; c < 4u; c++) { /* the quotient range, and the D that maximises it */
        a0[c] = bl[c] ? pn_kminf(a0[c], a1[c]) : -PN_KINF;
        b0[c] = bh[c] ? pn_kmaxf(b0[c], b1[c]) : PN_KINF;
        a1[c] = a0[c] >= 0.0f ? dlo : dhi;
        b1[c] = b0[c] >= 0.0f ? dhi : dlo;
    }
    for (c = 0; c < 4u; c++) {
        float rlo = a0[c] * a1[c], rhi = b0[c] * b1[c];
        gl[c] = (o + rlo) - (eo + 1e-6f * (pn_kfabs(o) + pn_kfabs(rlo)));
        gh[c] = (o + rhi) + (eo + 1e-6f * (pn_kfabs(o) + pn_kfabs(rhi)));
    }
    pn_foot_index(gl, gh, k, n0, n1);
}

/* Box [lo, hi] into lane c of four-lane arrays (l4[a * 4 + c], h4[a * 4 + c] over axes a)
 * and into every lane after it, so that lanes no box fills hold a copy, not garbage. */
PN_KFN void pn_lanes_put(float *l4, float *h4, uint32_t c, pn_v3 lo, pn_v3 hi)
{
    for (; c < 4u; c++) {
        l4[c] = lo.x;
        l4[4u + c] = lo.y;
        l4[8u + c] = lo.z;
        h4[c] = hi.x;
        h4[4u + c] = hi.y;
        h4[8u + c] = hi.z;
    }
}

/* pn_lanes_put with the box of triangle ABC. */
PN_KFN void pn_lanes_put_tri(float *l4, float *h4, uint32_t c, pn_v3 A, pn_v3 B, pn_v3 C)
{
    pn_lanes_put(l4, h4, c,
                 pn_v3_make(pn_kminf(A.x, pn_kminf(B.x, C.x)), pn_kminf(A.y, pn_kminf(B.y, C.y)),
                            pn_kminf(A.z, pn_kminf(B.z, C.z))),
                 pn_v3_make(pn_kmaxf(A.x, pn_kmaxf(B.x, C.x)), pn_kmaxf(A.y, pn_kmaxf(B.y, C.y)),
                            pn_kmaxf(A.z, pn_kmaxf(B.z, C.z))));
}

/* The samples whose segments from O can meet each of four boxes, box c being
 * lo[a * 4 + c], hi[a * 4 + c] over axes a (a wide node's children, copied out of its
 * pn_kbvh4), into out[c]. Branch-free over the lanes, so a compiler may run the four
 * boxes at once (SSE on x86-64, the work-item's own lanes in OpenCL). */
PN_KFN void pn_foot_box4(const pn_foot *fp, const float *lo, const float *hi, pn_rect *out)
{
    float o[3], dl[12], dh[12], mag[4], wlo[4], whi[4], glo[4], ghi[4], hlo[4], hhi[4];
    float dtop = fp->D + fp->eD, dlo = fp->D - fp->eD;
    int32_t i0[4], i1[4], j0[4], j1[4], empty[4];
    uint32_t a, c;
    if (!fp->on) {
        for (c = 0; c < 4u; c++) out[c] = pn_rect_full(fp->k);
        return;
    }
    o[0] = fp->O.x;
    o[1] = fp->O.y;
    o[2] = fp->O.z;
    for (a = 0; a < 3u; a++)
        for (c = 0; c < 4u; c++) {
            dl[a * 4u + c] = lo[a * 4u + c] - o[a];
            dh[a * 4u + c] = hi[a * 4u + c] - o[a];
        }
    for (c = 0; c < 4u; c++)
        mag[c] = (pn_kmaxf(pn_kfabs(dl[c]), pn_kfabs(dh[c])) + pn_kmaxf(pn_kfabs(dl[4u + c]), pn_kfabs(dh[4u + c]))) +
                 pn_kmaxf(pn_kfabs(dl[8u + c]), pn_kfabs(dh[8u + c]));
    /* w = -(X - O).N */
    pn_lin_range4(fp->N, dl, dh, hlo, hhi);
    for (c = 0; c < 4u; c++) {
        float ew = 16.0f * PN_KU * mag[c] + PN_KTINY;
        wlo[c] = -hhi[c] - ew;
        whi[c] = pn_kminf(-hlo[c] + ew, dtop);
        /* Wholly behind O's plane or beyond the light plane: no segment reaches it. NaN
         * falls through to the axes, which then give the whole light. */
        empty[c] = (whi[c] <= 0.0f) | (wlo[c] > dtop);
    }
    pn_lin_range4(fp->Ua, dl, dh, glo, ghi);
    pn_foot_axis4(fp->aO, fp->ea, 32.0f * PN_KU * fp->ua_inf, glo, ghi, mag, wlo, whi, dlo, dtop, fp->k, i0, i1);
    pn_lin_range4(fp->Va, dl, dh, glo, ghi);
    pn_foot_axis4(fp->bO, fp->eb, 32.0f * PN_KU * fp->va_inf, glo, ghi, mag, wlo, whi, dlo, dtop, fp->k, j0, j1);
    for (c = 0; c < 4u; c++) {
        int e = empty[c] | (i0[c] > i1[c]);
        out[c] = e ? pn_rect_make(0, -1, 0, -1) : pn_rect_make(i0[c], i1[c], j0[c], j1[c]);
    }
}

/* The samples whose segments from O can meet the box [lo, hi]: pn_foot_box4 with the box
 * in every lane. */
PN_KFN pn_rect pn_foot_box(const pn_foot *fp, pn_v3 lo, pn_v3 hi)
{
    float l[12], h[12];
    pn_rect r[4];
    pn_lanes_put(l, h, 0u, lo, hi);
    pn_foot_box4(fp, l, h, r);
    return r[0];
}

/* The order a walk visits two boxes in: the one whose centre lies farther from the light
 * toward O first (larger key), the axis a ray tracer sorts children by. Boxes near O have
 * the large footprints that fill a mask soonest; measured against nearest-to-O's-plane
 * and the builder's order, it is as good or better on every scene tried. Only the order
 * (and so the counters) depends on it, never the mask. */
PN_KFN float pn_foot_order(const pn_foot *fp, pn_v3 lo, pn_v3 hi) { return pn_v3_dot(pn_v3_add(lo, hi), fp->dir); }

/* The samples of rectangle r that mask m (bit j k + i) has not blocked yet, row by row:
 * up to `most` of them into (si, sj); returns their count, or most + 1 when there are
 * more (r not empty). With most = 0 it writes nothing and stops at the first. */
PN_KFN uint32_t pn_rect_few(const uint32_t *m, uint32_t k, pn_rect r, uint32_t most, int32_t *si, int32_t *sj)
{
    uint32_t n = (uint32_t)(r.i1 - r.i0 + 1), cols, bit, open, c = 0u;
    int32_t j;
    cols = (n >= 32u ? 0xFFFFFFFFu : ((1u << n) - 1u)) << (uint32_t)r.i0;
    for (j = r.j0; j <= r.j1; j++) {
        bit = (uint32_t)j * k; /* a row never straddles two words (k divides 32 or is 32) */
        open = ~(m[bit >> 5] >> (bit & 31u)) & cols;
        while (open) {
            if (c == most) return most + 1u;
            si[c] = (int32_t)pn_kctz(open);
            sj[c] = j;
            c++;
            open &= open - 1u;
        }
    }
    return c;
}

/* 1 if rectangle r holds a sample that mask m (bit j k + i) has not blocked yet. */
PN_KFN int pn_rect_open(const uint32_t *m, uint32_t k, pn_rect r)
{
    return !pn_rect_empty(r) && pn_rect_few(m, k, r, 0u, 0, 0) != 0u;
}

#endif
