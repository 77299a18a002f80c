/* pn_nbuffer.h - the N-buffer (Decoret 2005), the one builder and lookup of the library:
 * the occlusion textures pre-filter a slice with it (integer counts, summed), the Monte
 * Carlo shadow maps search their depth layers with it (min / max per channel).
 *
 * Counts (the occlusion textures). Level l of a res x res texture holds, at texel x (per
 * axis), the sum over the box of level-0 texels [x, x + 1) (l = 0) or
 * [x + 1 - 2^(l-1), x + 1 + 2^(l-1)) (l >= 1): boxes of side 2^l centred on lattice point
 * x + 1 (Curtis 2009 §3.5 moves Decoret's lower-left texels to the centre, which keeps
 * information near the edges). Level l >= 1 is built from level l - 1 by four lookups at
 * offsets a, b per axis (pn_nb_offsets); lookups at texels outside the texture give 0.
 * Levels are stored one after another, res^2 texels each. A texel whose box lies inside
 * the texture holds exactly that box; one whose box reaches beyond an edge holds less than
 * the texture's part of it (a lower box whose index lies outside is skipped though its box
 * may reach in: level 2's texel 0 holds [1, 3), not column 0), so within 2^(l-1) texels of
 * an edge the N-buffer filter's level-l means count less than the kernel holds (an
 * approximation of that filter, on top of its bilinear one).
 *
 * Min / max (the Monte Carlo shadow maps), which read boxes inside the texture only
 * (pn_nb_mm_box, pn_nb_mm_rect_at): each level keeps those boxes alone, at their lower
 * left texel, and a context may keep every third level only (see pn_nb_mm_w). */
#ifndef PN_NBUFFER_H
#define PN_NBUFFER_H

#include "pn_kmath.h"
#include "pn_ktypes.h"

/* Offsets of the four level-(l-1) boxes that make the level-l box of texel x (l >= 1). */
PN_KFN void pn_nb_offsets(uint32_t l, int32_t *a, int32_t *b)
{
    *a = l == 1u ? 0 : -(int32_t)(1u << (l - 2u));
    *b = l == 1u ? 1 : (int32_t)(1u << (l - 2u));
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

/* The same max of a texel in private memory (an accumulation). */
PN_KFN void pn_nb_mm_add_p(float *v, const float *t)
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

/* Min / max layout (the Monte Carlo shadow maps: the searches read boxes inside the map
 * only). Level l keeps the boxes that lie inside: W_l = res + 1 - 2^l texels per axis
 * (W_0 = res), texel X holding the box [X, X + 2^l) (Decoret's lower-left corner; the same
 * boxes as the centred layout above keeps inside, 0.74x its texels at a map of 512). Level
 * l >= 1 is the max of the four level-(l-1) boxes at X, X + 2^(l-1) per axis: row Y's two
 * columns, then row Y + 2^(l-1)'s. A context may keep every third level only (mc->nb_step
 * 3, pn_limits.flags PN_LIMITS_SPARSE_NBUFFER: levels 0, 3, 6, 9): a lookup of another
 * level rebuilds its box from the level kept below it in that same order (pn_nb_mm_tree),
 * so every lookup gives the same bits either way. The kept levels lie one after another. */
PN_KFN uint32_t pn_nb_mm_w(uint32_t res, uint32_t l) { return l == 0u ? res : res + 1u - (1u << l); }

/* Where each level's lookups read, worked out once per work item (private memory; the
 * frame's parameters have no room for tables): for level l the kept level src[l] at or
 * below it, its width w[l] and its first float off[l]. At most 12 levels (res <= 2048,
 * PN_MCSM_MAP_MAX; offsets then fit 32 bits). */
typedef struct pn_nb_mm_lay {
    uint32_t res, levels;
    uint32_t src[12], w[12], off[12];
} pn_nb_mm_lay;

/* The layout of mc's map (mc->res, mc->levels, mc->nb_step: 1 or 3); returns the kept
 * texels. */
PN_KFN uint32_t pn_nb_mm_lay_init(const pn_kmc *mc, pn_nb_mm_lay *ly)
{
    uint32_t l, n = 0u, L = mc->levels;
    ly->res = mc->res;
    ly->levels = L;
    for (l = 0; l < L; l++) {
        uint32_t s = l - l % mc->nb_step;
        ly->src[l] = s;
        ly->w[l] = pn_nb_mm_w(mc->res, s);
        if (s == l) {
            ly->off[l] = n * PN_NB_MM;
            n += ly->w[l] * ly->w[l];
        } else {
            ly->off[l] = ly->off[s];
        }
    }
    return n;
}

/* Into acc (private, stored form), the max of the four texels at float at, at + dx,
 * at + dy, at + dy + dx of lv, in that order: a level's box from its four halves' boxes
 * (row Y's two columns, then the next row's) as the builder folds them. */
PN_KFN void pn_nb_mm_fold4(PN_CONST float *lv, uint32_t at, uint32_t dx, uint32_t dy, float *acc)
{
    PN_CONST float *a = lv + at, *b = a + dx, *c = a + dy, *d = c + dx;
    acc[0] = pn_kmaxf(acc[0], pn_kmaxf(pn_kmaxf(pn_kmaxf(a[0], b[0]), c[0]), d[0]));
    acc[1] = pn_kmaxf(acc[1], pn_kmaxf(pn_kmaxf(pn_kmaxf(a[1], b[1]), c[1]), d[1]));
    acc[2] = pn_kmaxf(acc[2], pn_kmaxf(pn_kmaxf(pn_kmaxf(a[2], b[2]), c[2]), d[2]));
}

/* Into acc (stored form), the level-l box whose first level-(l - d) texel is at float `at`
 * of a level w texels wide (1 <= d <= 3): its 4^d texels folded in the builder's order,
 * each box the max of its four halves' boxes (pn_nb_mm_fold4 at the bottom, a fold of
 * four such folds a level above, a fold starting from the identity, which gives the first
 * value itself, NaN included), then one max into acc: the bits a kept level l's texel
 * gives. Written out per depth (no recursion). */
PN_KFN_COLD void pn_nb_mm_tree(PN_CONST float *lv, uint32_t at, uint32_t w, uint32_t l, uint32_t d, float *acc)
{
    uint32_t h = 1u << (l - 1u), dx = h * PN_NB_MM, dy = dx * w, i, j;
    float top[PN_NB_MM];
    pn_nb_mm_empty(top);
    if (d == 1u) {
        pn_nb_mm_fold4(lv, at, dx, dy, top);
    } else {
        for (i = 0; i < 4u; i++) { /* the four halves, level l - 1 */
            uint32_t a1 = at + (i >> 1u) * dy + (i & 1u) * dx;
            float mid[PN_NB_MM];
            pn_nb_mm_empty(mid);
            if (d == 2u) {
                pn_nb_mm_fold4(lv, a1, dx >> 1u, dy >> 1u, mid);
            } else {
                for (j = 0; j < 4u; j++) { /* their halves, level l - 2, from level l - 3 */
                    float low[PN_NB_MM];
                    pn_nb_mm_empty(low);
                    pn_nb_mm_fold4(lv, a1 + (j >> 1u) * (dy >> 1u) + (j & 1u) * (dx >> 1u), dx >> 2u, dy >> 2u, low);
                    pn_nb_mm_add_p(mid, low);
                }
            }
            pn_nb_mm_add_p(top, mid);
        }
    }
    pn_nb_mm_add_p(acc, top);
}

/* Row Y < W_l of kept level l >= 1 (ly's layout, lv the levels). From the kept level just
 * below (d = 1: each texel one max over a flat float array, which the compilers vectorize),
 * else by pn_nb_mm_tree from the kept level step below. */
PN_KFN void pn_nb_mm_row(const pn_nb_mm_lay *ly, uint32_t l, uint32_t Y, PN_GLOBAL float *lv)
{
    uint32_t s = ly->src[l - 1u], ws = ly->w[l - 1u], w = ly->w[l], X;
    PN_GLOBAL float *out = lv + ly->off[l] + (size_t)Y * w * PN_NB_MM;
    if (l - s == 1u) {
        size_t i, h = (size_t)1u << (l - 1u), n = (size_t)w * PN_NB_MM;
        PN_CONST float *r0 = lv + ly->off[s] + (size_t)Y * ws * PN_NB_MM;
        PN_CONST float *r1 = r0 + h * ws * PN_NB_MM, *r0b = r0 + h * PN_NB_MM, *r1b = r1 + h * PN_NB_MM;
        for (i = 0; i < n; i++) out[i] = pn_kmaxf(pn_kmaxf(pn_kmaxf(r0[i], r0b[i]), r1[i]), r1b[i]);
        return;
    }
    for (X = 0; X < w; X++) {
        float v[PN_NB_MM];
        pn_nb_mm_empty(v);
        pn_nb_mm_tree(lv, ly->off[s] + (Y * ws + X) * PN_NB_MM, ws, l, l - s, v);
        out[X * PN_NB_MM] = v[0];
        out[X * PN_NB_MM + 1u] = v[1];
        out[X * PN_NB_MM + 2u] = v[2];
    }
}

/* Every kept level above 0 of ly's layout from level 0, row by row in one work item (a
 * frame runs each level's rows as a pass, src/pn_mcsm.c; the tests and fuzz_tables build
 * with this). */
PN_KFN void pn_nb_mm_build(const pn_nb_mm_lay *ly, PN_GLOBAL float *lv)
{
    uint32_t l, y;
    for (l = 1; l < ly->levels; l++)
        if (ly->src[l] == l)
            for (y = 0; y < pn_nb_mm_w(ly->res, l); y++) pn_nb_mm_row(ly, l, y, lv);
}

/* Into acc, the level-l box whose texel in kept level ly->src[l] is at float `at`. */
PN_KFN void pn_nb_mm_box_add(PN_CONST float *lv, const pn_nb_mm_lay *ly, uint32_t l, uint32_t at, float *acc)
{
    if (ly->src[l] == l)
        pn_nb_mm_add(acc, lv + at);
    else
        pn_nb_mm_tree(lv, at, ly->w[l], l, l - ly->src[l], acc);
}

/* Bounds of the min / max box of level l starting at level-0 texel (X, Y), of its part
 * inside the texture: a box reaching beyond an edge is looked up as the one of its size
 * inside against that edge, which holds that part (with the index clamped instead, MCSM's
 * search skipped occluders on the map's first and last columns and rows: room, 512x512,
 * 3 pixels). */
PN_KFN void pn_nb_mm_box(PN_CONST float *lv, const pn_nb_mm_lay *ly, uint32_t l, int32_t X, int32_t Y, float *v)
{
    int32_t hi = (int32_t)ly->res - (1 << l);
    float a[PN_NB_MM];
    pn_nb_mm_empty(a);
    pn_nb_mm_box_add(lv, ly, l,
                     ly->off[l] + ((uint32_t)pn_kmaxi(0, pn_kmini(Y, hi)) * ly->w[l] +
                                   (uint32_t)pn_kmaxi(0, pn_kmini(X, hi))) * PN_NB_MM,
                     a);
    v[0] = -a[0]; /* the bounds, as pn_nb_mm_get's */
    v[1] = a[1];
    v[2] = a[2];
}

/* The four boxes that bound the texel rectangle [x0, x1) x [y0, y1) (clamped to the
 * texture): offsets in floats of their texels in lv (in the kept level a lookup of their
 * level reads), their level in *lev: the smallest level l with 2^(l+1) >= the longer side
 * (at most the top level, whose four boxes cover the texture); 0 when the clamped rectangle
 * is empty, else 4 (the offsets are then of some texels, not to be read). A superset, so
 * the bounds are conservative; exact when both sides are 2^l .. 2^(l+1). The level from
 * the exponent of a float, the boxes' two columns and two rows indexed once, and no
 * branch: the searches' hot path, which the Monte Carlo pixel pass computes for eight
 * rays at once in a loop the compilers vectorize. */
PN_KFN uint32_t pn_nb_mm_rect_at(const pn_nb_mm_lay *ly, int32_t x0, int32_t y0, int32_t x1, int32_t y1,
                                 uint32_t *at, uint32_t *lev)
{
    int32_t m, s, R = (int32_t)ly->res;
    uint32_t l, n, ca, cb, ra, rb, L, w;
    x0 = pn_kmaxi(x0, 0);
    y0 = pn_kmaxi(y0, 0);
    x1 = pn_kmini(x1, R);
    y1 = pn_kmini(y1, R);
    n = ((x1 > x0) & (y1 > y0)) ? 4u : 0u;
    m = pn_kmaxi(x1 - x0, y1 - y0);
    /* The smallest l with 2 << l >= m: 0 up to m = 2, else floor(log2(m - 1)), the
     * exponent of m - 1 as a float (exact: m <= res < 2^24). */
    l = m <= 2 ? 0u : (pn_kfbits((float)(m - 1)) >> 23) - 127u;
    l = pn_kminu(l, ly->levels - 1u);
    s = 1 << l;
    w = ly->w[l];
    /* Boxes inside the texture: a first box starting after res - s moves back to it (it
     * still holds [x0, x1)'s start; the second its end). */
    x0 = pn_kmini(x0, R - s);
    y0 = pn_kmini(y0, R - s);
    ca = (uint32_t)x0 * PN_NB_MM;
    cb = (uint32_t)pn_kmaxi(x1 - s, x0) * PN_NB_MM;
    ra = (uint32_t)y0 * w * PN_NB_MM;
    rb = (uint32_t)pn_kmaxi(y1 - s, y0) * w * PN_NB_MM;
    L = ly->off[l];
    at[0] = L + ra + ca;
    at[1] = L + ra + cb;
    at[2] = L + rb + ca;
    at[3] = L + rb + cb;
    *lev = l;
    return n;
}

/* Bounds {min near, max far, max near} of the n boxes of level l at (pn_nb_mm_rect_at;
 * empty: {+inf, -inf, -inf}). */
PN_KFN void pn_nb_mm_rect_get(PN_CONST float *lv, const pn_nb_mm_lay *ly, const uint32_t *at, uint32_t n,
                              uint32_t l, float *v)
{
    uint32_t i;
    float s[PN_NB_MM]; /* a local sum: through v, the compilers store and reload at each box */
    pn_nb_mm_empty(s);
    if (ly->src[l] == l)
        for (i = 0; i < n; i++) pn_nb_mm_add(s, lv + at[i]);
    else
        for (i = 0; i < n; i++) pn_nb_mm_box_add(lv, ly, l, at[i], s);
    v[0] = -s[0]; /* the bounds, as pn_nb_mm_get's */
    v[1] = s[1];
    v[2] = s[2];
}

/* Bounds over the texel rectangle [x0, x1) x [y0, y1) from pn_nb_mm_rect_at's boxes. */
PN_KFN void pn_nb_mm_rect(PN_CONST float *lv, const pn_nb_mm_lay *ly, int32_t x0, int32_t y0, int32_t x1, int32_t y1,
                          float *v)
{
    uint32_t at[4], l, n = pn_nb_mm_rect_at(ly, x0, y0, x1, y1, at, &l);
    pn_nb_mm_rect_get(lv, ly, at, n, l, v);
}

#endif
