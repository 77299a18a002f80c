/* pn_nbuffer.h - the N-buffer (Decoret 2005), the one builder and lookup of the library:
 * the occlusion textures pre-filter a slice with it (integer counts, summed), the Monte
 * Carlo shadow maps search their depth layers with it (min / max per channel).
 *
 * Layout. Level l of a res x res texture holds, at texel x (per axis), the reduction over
 * the box of level-0 texels [x, x + 1) (l = 0) or [x + 1 - 2^(l-1), x + 1 + 2^(l-1))
 * (l >= 1): boxes of side 2^l centred on lattice point x + 1 (Curtis 2009 §3.5 moves
 * Decoret's lower-left texels to the centre, which keeps information near the edges).
 * Level l >= 1 is built from level l - 1 by four lookups at offsets a, b per axis
 * (pn_nb_offsets); lookups at texels outside the texture give the reduction's identity.
 * Levels are stored one after another, res^2 texels each.
 *
 * Edges. A texel whose box lies inside the texture holds exactly that box. One whose box
 * reaches beyond an edge holds less than the texture's part of it: a lower box whose index
 * lies outside is skipped though its box may reach in (level 2's texel 0 holds [1, 3), not
 * column 0; texel res - 2 of level 3 misses column res - 1). The Monte Carlo shadow maps
 * read boxes inside the texture only (pn_nb_mm_box, pn_nb_mm_rect_at); the occlusion
 * textures' N-buffer filter reads the edge texels as they are, so within 2^(l-1) texels of
 * an edge its level-l means count less than the kernel holds (an approximation of that
 * filter, on top of its bilinear one).
 *
 * Lookups. pn_nb_index gives the texel of level l whose box starts at level-0 texel X,
 * exact for boxes inside the texture. pn_nb_mm_rect_at bounds any rectangle with four
 * boxes inside the texture, pn_nb_mm_box any box by the one inside against the edge. */
#ifndef PN_NBUFFER_H
#define PN_NBUFFER_H

#include "pn_kmath.h"

/* Offsets of the four level-(l-1) boxes that make the level-l box of texel x (l >= 1). */
PN_KFN void pn_nb_offsets(uint32_t l, int32_t *a, int32_t *b)
{
    *a = l == 1u ? 0 : -(int32_t)(1u << (l - 2u));
    *b = l == 1u ? 1 : (int32_t)(1u << (l - 2u));
}

/* Level l's texel whose box starts at level-0 texel X, clamped to [0, res). Texel i of
 * level l >= 1 holds the box [i + 1 - 2^(l-1), i + 1 + 2^(l-1)) where that box lies inside
 * the texture; nearer the edges it holds less than the texture's part of it (the builder
 * skips lower boxes whose index lies outside, though their boxes reach in: texel 0 of
 * level 2 holds [1, 3), not column 0). Exact for 0 <= X <= res - 2^l, the boxes inside. */
PN_KFN int32_t pn_nb_index(uint32_t l, int32_t X, uint32_t res)
{
    int32_t i = l == 0u ? X : X - 1 + (int32_t)(1u << (l - 1u));
    return pn_kmaxi(0, pn_kmini(i, (int32_t)res - 1));
}

/* Row y of summed level l >= 1 (uint32 counts, levels of res^2 in lv). */
PN_KFN void pn_nb_sum_row(uint32_t res, uint32_t l, uint32_t y, PN_GLOBAL uint32_t *lv)
{
    int32_t a, b, ya, yb;
    uint32_t x;
    PN_CONST uint32_t *lo = lv + (size_t)(l - 1u) * res * res;
    PN_GLOBAL uint32_t *out = lv + (size_t)l * res * res + (size_t)y * res;
    pn_nb_offsets(l, &a, &b);
    ya = (int32_t)y + a;
    yb = (int32_t)y + b;
    for (x = 0; x < res; x++) {
        int32_t xa = (int32_t)x + a, xb = (int32_t)x + b;
        uint32_t v = 0u;
        if (ya >= 0 && ya < (int32_t)res) {
            PN_CONST uint32_t *r = lo + (size_t)ya * res;
            if (xa >= 0) v += r[xa];
            if (xb < (int32_t)res) v += r[xb];
        }
        if (yb >= 0 && yb < (int32_t)res) {
            PN_CONST uint32_t *r = lo + (size_t)yb * res;
            if (xa >= 0) v += r[xa];
            if (xb < (int32_t)res) v += r[xb];
        }
        out[x] = v;
    }
}

/* Min / max texels: three floats, {min of channel 0, max of channel 1, max of channel 2}
 * (the Monte Carlo shadow maps: min near, max far, max near), stored as maxima only:
 * {-min 0, max 1, max 2}. Then every channel is a max, and a level's row is one max over a
 * flat float array (pn_nb_mm_row: the compilers vectorize it). The same bytes as a min:
 * -(a < b ? a : b) is (-a > -b ? -a : -b) for every pair, signed zeros and NaN included,
 * so a sequence of maxima of negated values is the negated sequence of minima. Stored
 * identity: {-inf, -inf, -inf}; pn_nb_mm_get turns a stored texel into the bounds. */
#define PN_NB_MM 3u

PN_KFN void pn_nb_mm_empty(float *v)
{
    v[0] = -PN_KINF;
    v[1] = -PN_KINF;
    v[2] = -PN_KINF;
}

PN_KFN void pn_nb_mm_add(float *v, PN_CONST float *t)
{
    v[0] = pn_kmaxf(v[0], t[0]);
    v[1] = pn_kmaxf(v[1], t[1]);
    v[2] = pn_kmaxf(v[2], t[2]);
}

/* The bounds {min near, max far, max near} of stored texel (or accumulation) t. */
PN_KFN void pn_nb_mm_get(PN_CONST float *t, float *v)
{
    v[0] = -t[0];
    v[1] = t[1];
    v[2] = t[2];
}

/* Floats [0, n) of a level row's run of columns: out[i] the max, in order, of the k
 * sources' (k = 0: the identity). Loops with no test inside (the compilers vectorize them). */
PN_KFN void pn_nb_mm_run(PN_GLOBAL float *out, size_t n, PN_CONST float *s0, PN_CONST float *s1, PN_CONST float *s2,
                         PN_CONST float *s3, uint32_t k)
{
    size_t i;
    if (k == 0u)
        for (i = 0; i < n; i++) out[i] = -PN_KINF;
    else if (k == 1u)
        for (i = 0; i < n; i++) out[i] = s0[i];
    else if (k == 2u)
        for (i = 0; i < n; i++) out[i] = pn_kmaxf(s0[i], s1[i]);
    else if (k == 3u)
        for (i = 0; i < n; i++) out[i] = pn_kmaxf(pn_kmaxf(s0[i], s1[i]), s2[i]);
    else
        for (i = 0; i < n; i++) out[i] = pn_kmaxf(pn_kmaxf(pn_kmaxf(s0[i], s1[i]), s2[i]), s3[i]);
}

/* Row y of min / max level l >= 1 (levels of res^2 texels of PN_NB_MM floats in lv). Texel
 * x is the max of the level below at rows y + a, y + b and columns x + a, x + b, in that
 * order (row a's two columns, then row b's), of those inside the texture. The row splits
 * at columns -a and res - b into runs where the same lookups are inside, and each run is
 * one max over a flat float array (every channel a max): a first max with the identity
 * -inf gives the lookup itself, NaN included, so a run starts from its first lookup. */
PN_KFN void pn_nb_mm_row(uint32_t res, uint32_t l, uint32_t y, PN_GLOBAL float *lv)
{
    int32_t a, b, ya, yb, R = (int32_t)res, cut[4], i;
    PN_CONST float *lo = lv + (size_t)(l - 1u) * res * res * PN_NB_MM;
    PN_GLOBAL float *out = lv + ((size_t)l * res * res + (size_t)y * res) * PN_NB_MM;
    PN_CONST float *ra, *rb;
    pn_nb_offsets(l, &a, &b);
    ya = (int32_t)y + a;
    yb = (int32_t)y + b;
    ra = ya >= 0 && ya < R ? lo + (size_t)ya * res * PN_NB_MM : 0;
    rb = yb >= 0 && yb < R ? lo + (size_t)yb * res * PN_NB_MM : 0;
    /* Runs [cut[i], cut[i + 1]): x + a >= 0 from -a on, x + b < res up to res - b. */
    cut[0] = 0;
    cut[1] = pn_kmaxi(0, pn_kmini(-a, R - b));
    cut[2] = pn_kmini(R, pn_kmaxi(-a, R - b));
    cut[3] = R;
    for (i = 0; i < 3; i++) {
        int32_t x0 = cut[i], x1 = pn_kmaxi(cut[i + 1], x0);
        PN_CONST float *s[4];
        uint32_t k = 0u;
        if (x1 <= x0) continue;
        s[0] = s[1] = s[2] = s[3] = lo;
        if (ra && x0 + a >= 0) s[k++] = ra + (size_t)(x0 + a) * PN_NB_MM;
        if (ra && x0 + b < R) s[k++] = ra + (size_t)(x0 + b) * PN_NB_MM;
        if (rb && x0 + a >= 0) s[k++] = rb + (size_t)(x0 + a) * PN_NB_MM;
        if (rb && x0 + b < R) s[k++] = rb + (size_t)(x0 + b) * PN_NB_MM;
        pn_nb_mm_run(out + (size_t)x0 * PN_NB_MM, (size_t)(x1 - x0) * PN_NB_MM, s[0], s[1], s[2], s[3], k);
    }
}

/* Bounds of the min / max box of level l starting at level-0 texel (X, Y), of its part
 * inside the texture: a box reaching beyond an edge is looked up as the one of its size
 * inside against that edge, which holds that part (pn_nb_index is exact only inside: with
 * the index clamped instead, MCSM's search skipped occluders on the map's first and last
 * columns and rows: room, 512x512, 3 pixels). */
PN_KFN void pn_nb_mm_box(PN_CONST float *lv, uint32_t res, uint32_t l, int32_t X, int32_t Y, float *v)
{
    int32_t hi = (int32_t)res - (1 << l);
    size_t i = (size_t)l * res * res + (size_t)pn_nb_index(l, pn_kmaxi(0, pn_kmini(Y, hi)), res) * res +
               (size_t)pn_nb_index(l, pn_kmaxi(0, pn_kmini(X, hi)), res);
    pn_nb_mm_get(lv + i * PN_NB_MM, v);
}

/* The four boxes that bound the texel rectangle [x0, x1) x [y0, y1) (clamped to the
 * texture): offsets in floats of their texels in lv, those of the smallest level l with
 * 2^(l+1) >= the longer side (at most the top level, whose four boxes cover the texture);
 * 0 when the clamped rectangle is empty, else 4 (the offsets are then of some texels, not
 * to be read). A superset, so the bounds are conservative; exact when both sides are
 * 2^l .. 2^(l+1). The level from the exponent of a float, the boxes' two columns and two
 * rows indexed once, and no branch: the searches' hot path, which the Monte Carlo pixel
 * pass computes for eight rays at once in a loop the compilers vectorize. Offsets in 32
 * bits: levels res^2 PN_NB_MM floats fit for res up to 9000 (PN_MCSM_MAP_MAX is at most
 * 2048). */
PN_KFN uint32_t pn_nb_mm_rect_at(uint32_t res, uint32_t levels, int32_t x0, int32_t y0, int32_t x1, int32_t y1,
                                 uint32_t *at)
{
    int32_t m, s, R = (int32_t)res;
    uint32_t l, n, ca, cb, ra, rb, L;
    x0 = pn_kmaxi(x0, 0);
    y0 = pn_kmaxi(y0, 0);
    x1 = pn_kmini(x1, R);
    y1 = pn_kmini(y1, R);
    n = ((x1 > x0) & (y1 > y0)) ? 4u : 0u;
    m = pn_kmaxi(x1 - x0, y1 - y0);
    /* The smallest l with 2 << l >= m: 0 up to m = 2, else floor(log2(m - 1)), the
     * exponent of m - 1 as a float (exact: m <= res < 2^24). */
    l = m <= 2 ? 0u : (pn_kfbits((float)(m - 1)) >> 23) - 127u;
    l = pn_kminu(l, levels - 1u);
    s = 1 << l;
    /* Boxes inside the texture, where pn_nb_index is exact: a first box starting after
     * res - s moves back to it (it still holds [x0, x1)'s start; the second its end). */
    x0 = pn_kmini(x0, R - s);
    y0 = pn_kmini(y0, R - s);
    ca = (uint32_t)pn_nb_index(l, x0, res) * PN_NB_MM;
    cb = (uint32_t)pn_nb_index(l, pn_kmaxi(x1 - s, x0), res) * PN_NB_MM;
    ra = (uint32_t)pn_nb_index(l, y0, res) * res * PN_NB_MM;
    rb = (uint32_t)pn_nb_index(l, pn_kmaxi(y1 - s, y0), res) * res * PN_NB_MM;
    L = l * res * res * PN_NB_MM;
    at[0] = L + ra + ca;
    at[1] = L + ra + cb;
    at[2] = L + rb + ca;
    at[3] = L + rb + cb;
    return n;
}

/* Bounds {min near, max far, max near} of the n boxes at (pn_nb_mm_rect_at; empty:
 * {+inf, -inf, -inf}). */
PN_KFN void pn_nb_mm_rect_get(PN_CONST float *lv, const uint32_t *at, uint32_t n, float *v)
{
    uint32_t i;
    float s[PN_NB_MM]; /* a local sum: through v, the compilers store and reload at each box */
    pn_nb_mm_empty(s);
    for (i = 0; i < n; i++) pn_nb_mm_add(s, lv + at[i]);
    v[0] = -s[0]; /* the bounds, as pn_nb_mm_get's */
    v[1] = s[1];
    v[2] = s[2];
}

/* Bounds over the texel rectangle [x0, x1) x [y0, y1) from pn_nb_mm_rect_at's boxes. */
PN_KFN void pn_nb_mm_rect(PN_CONST float *lv, uint32_t res, uint32_t levels, int32_t x0, int32_t y0, int32_t x1,
                          int32_t y1, float *v)
{
    uint32_t at[4], n = pn_nb_mm_rect_at(res, levels, x0, y0, x1, y1, at);
    pn_nb_mm_rect_get(lv, at, n, v);
}

#endif
