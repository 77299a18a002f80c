/* pn_srt.h - selective ray tracing (Lauterbach, Mo, Manocha 2009): a shadow map from the
 * light centre answers for most pixels; the pixels it may get wrong (the PIP set) get the
 * exact answer of the reference's per-pixel path (the same predicate, the same bits).
 * The frame is src/pn_srt.c; these are its work items.
 *
 * The light view is a pn_kview (K->lview) at the light centre looking along N (a point
 * light: toward the scene), rasterized by the G-buffer's own code (pn_raster.h: the same
 * watertight fill rule and depth), into lmap_depth / lmap_id. Map depth s is the distance
 * from the light centre along the texel's centre ray.
 *
 * Classification of a pixel with shadow-ray origin O at distance d from the light centre,
 * falling in texel S of depth s (paper §3.1, §3.2):
 *   hard (point light): PIP when the 3x3 depth discontinuity D = max |s - s'| exceeds the
 *     threshold and the receiver, within one texel's angle alpha of O, can reach depths
 *     [d^, d + (d - d^)] (d^ = d sin(b) / sin(a + b), sin(b) = n.L) that overlap
 *     [s - D, s + D] or lie on both sides of s; or when a thin triangle (narrower than a
 *     texel, three times longer than wide) was conservatively
 *     rasterized into S;
 *   soft (area light): PIP when S lies in the penumbra mask: every edge texel (D above the
 *     threshold, or touched by a thin triangle) splatted with the light's footprint, which
 *     for an occluder at depth z along N is |U|/z by |V|/z in map (tan) units -- exactly the
 *     largest displacement of its projection as seen from any light point (a bound, so the
 *     splat is conservative for the edges the map holds); or when the plane of the pixel's
 *     triangle comes within a tolerance of a light corner (invariant 6: part of the light
 *     may be behind the receiver). The mask is kept per tile of PN_SRT_TILE^2 texels.
 *   both: PIP when O is outside the map, and for every pixel with PN_SRT_FORCE_PIP; and
 *     when S holds another triangle in front of O (d > s (1 + 1e-4)) that only the slope
 *     bias below would call lit: an occluder within the bias of its receiver, too close for
 *     the discontinuity test (a board against a wall seen edge-on from the light: room's
 *     point light lost 21 shadow pixels of 12,288 so, 0.17%, before this test).
 * Outside the PIP set the map answers: lit when S holds the pixel's own triangle or
 * d <= s + (d - d^) + 1e-4 d (slope bias), else in shadow. */
#ifndef PN_SRT_H
#define PN_SRT_H

#include "pn_kpools.h"
#include "pn_lview.h"
#include "pn_raster.h"
#include "pn_reference.h"

#define PN_SRT_TILE 8u
/* = PN_SRT_FORCE_PIP of penumbra.h (kernels do not see it; src/pn_srt.c checks they agree). */
#define PN_SRT_FLAG_FORCE_PIP 2u
/* The frame's counter words (pool srt_words): the largest splat weight's bits, thin
 * triangles conservatively rasterized, penumbra-mask tiles set, texels the thin triangles
 * marked. */
#define PN_SRT_WORD_WMAX 0u
#define PN_SRT_WORD_THIN 1u
#define PN_SRT_WORD_TILES 2u
#define PN_SRT_WORD_CONS 3u
/* Largest map half-extent in tan units; beyond it: PIP. */
#define PN_SRT_TAN_MAX PN_LVIEW_TAN_MAX

/* Atomic max of a non-negative float stored as its bits (pn_katomic_imax), whatever order
 * work items run in. Returns the bits it replaced (or kept): 0 for exactly one caller per
 * word that starts at 0 and receives a positive value, whatever the order. */
PN_KFN uint32_t pn_srt_atomic_fmax(PN_GLOBAL uint32_t *p, float v)
{
    return (uint32_t)pn_katomic_imax((PN_GLOBAL int32_t *)p, (int32_t)pn_kfbits(v));
}

/* The polygon's x-extent within the horizontal strip [y0, y1] (pixel coordinates), for a
 * convex polygon in traversal order (any area, a segment included); 0 if it misses it. */
PN_KFN int pn_srt_strip(const pn_poly *p, float y0, float y1, float *xlo, float *xhi)
{
    uint32_t i;
    int hit = 0;
    float lo = PN_KINF, hi = -PN_KINF;
    for (i = 0; i < p->n; i++) {
        uint32_t j = (i + 1u) % p->n;
        float ax = p->x[i], ay = p->y[i], bx = p->x[j], by = p->y[j];
        float ymin = pn_kminf(ay, by), ymax = pn_kmaxf(ay, by);
        float c0, c1, t0, t1;
        if (ymax < y0 || ymin > y1) continue;
        if (ay == by) {
            lo = pn_kminf(lo, pn_kminf(ax, bx));
            hi = pn_kmaxf(hi, pn_kmaxf(ax, bx));
            hit = 1;
            continue;
        }
        /* The part of the edge inside the strip, at its two ends. */
        c0 = pn_kmaxf(ymin, y0);
        c1 = pn_kminf(ymax, y1);
        t0 = (c0 - ay) / (by - ay);
        t1 = (c1 - ay) / (by - ay);
        t0 = ax + (bx - ax) * t0;
        t1 = ax + (bx - ax) * t1;
        lo = pn_kminf(lo, pn_kminf(t0, t1));
        hi = pn_kmaxf(hi, pn_kmaxf(t0, t1));
        hit = 1;
    }
    *xlo = lo;
    *xhi = hi;
    return hit;
}

/* Triangle t in the light view: 1 when thin (it could slip between texel centres: narrower
 * than a texel, three times longer than wide, its longest edge at least a texel, in front of
 * the light), with its projected polygon in *poly and its weight 1/zmin (zmin: its nearest
 * depth along the light axis) in *w. Small but regular triangles (scanned meshes) are
 * covered by their neighbours and are not thin, as in the paper. */
PN_KFN int pn_srt_thin(const pn_kview *lv, PN_CONST float *tris, PN_CONST uint8_t *flags, uint32_t t, pn_poly *poly,
                       float *w)
{
    PN_CONST float *p = tris + (size_t)t * 9u;
    float zmin, area = 0.0f, longest = 0.0f;
    uint32_t i, n;
    if (flags[t] & PN_TRI_DEGENERATE) return 0;
    pn_poly_project(lv, pn_v3_make(p[0], p[1], p[2]), pn_v3_make(p[3], p[4], p[5]), pn_v3_make(p[6], p[7], p[8]),
                    poly, &zmin);
    n = poly->n;
    if (n < 2u) return 0;
    for (i = 0; i < n; i++) {
        uint32_t j = (i + 1u) % n;
        float dx = poly->x[j] - poly->x[i], dy = poly->y[j] - poly->y[i];
        area += poly->x[i] * poly->y[j] - poly->x[j] * poly->y[i];
        longest = pn_kmaxf(longest, dx * dx + dy * dy);
    }
    area = 0.5f * (area < 0.0f ? -area : area);
    longest = pn_ksqrt(longest);
    /* Narrower than a texel (2 area / longest edge), at least three times longer than wide. */
    if (!(longest >= 1.0f) || !(2.0f * area < longest) || !(6.0f * area < longest * longest) || !(zmin > 0.0f)) return 0;
    *w = 1.0f / zmin;
    return 1;
}

/* Triangle t: when thin (pn_srt_thin), every texel it touches gets its weight 1/zmin by
 * atomic max into cons (widened by a texel for the rounding of the projection); *count:
 * one more; *texels: one more for each texel it marked first. */
PN_KFN void pn_srt_conservative(const pn_kview *lv, PN_CONST float *tris, PN_CONST uint8_t *flags, uint32_t t,
                                PN_GLOBAL uint32_t *cons, PN_GLOBAL uint32_t *count, PN_GLOBAL uint32_t *texels)
{
    pn_poly poly;
    float ylo, yhi, w;
    uint32_t i, res = lv->width, first = 0u;
    int32_t y, y0, y1;
    if (!pn_srt_thin(lv, tris, flags, t, &poly, &w)) return;
    pn_katomic_add(count, 1u);
    ylo = poly.y[0];
    yhi = poly.y[0];
    for (i = 1; i < poly.n; i++) {
        ylo = pn_kminf(ylo, poly.y[i]);
        yhi = pn_kmaxf(yhi, poly.y[i]);
    }
    y0 = pn_kfloor_clamp(ylo - 1.0f, 0, (int32_t)res - 1);
    y1 = pn_kfloor_clamp(yhi + 1.0f, 0, (int32_t)res - 1);
    if (!(ylo - 1.0f < (float)res) || !(yhi + 1.0f >= 0.0f)) return;
    for (y = y0; y <= y1; y++) {
        float xlo, xhi;
        int32_t x, x0, x1;
        if (!pn_srt_strip(&poly, (float)y - 1.0f, (float)y + 2.0f, &xlo, &xhi)) continue;
        if (!(xlo - 1.0f < (float)res) || !(xhi + 1.0f >= 0.0f)) continue;
        x0 = pn_kfloor_clamp(xlo - 1.0f, 0, (int32_t)res - 1);
        x1 = pn_kfloor_clamp(xhi + 1.0f, 0, (int32_t)res - 1);
        for (x = x0; x <= x1; x++) first += pn_srt_atomic_fmax(cons + (size_t)y * res + (size_t)x, w) == 0u;
    }
    if (first) pn_katomic_add(texels, first);
}

/* Depth along the light axis of the surface a texel holds (map depth s is along the
 * texel's centre ray), rounded down a little so that 1/z bounds the true reciprocal. */
PN_KFN float pn_srt_texel_z(const pn_kview *lv, uint32_t tx, uint32_t ty, float s)
{
    float sx = (2.0f * ((float)tx + 0.5f) / (float)lv->width - 1.0f) * lv->tan_half;
    float sy = (1.0f - 2.0f * ((float)ty + 0.5f) / (float)lv->height) * lv->tan_half;
    return s / pn_ksqrt(1.0f + sx * sx + sy * sy) * 0.9999f;
}

/* |q - s| for two map depths, where +inf (background) against a surface is +inf and
 * against background 0. */
PN_KFN float pn_srt_ddiff(float s, float q)
{
    float d = q - s;
    d = d < 0.0f ? -d : d;
    return q == s ? 0.0f : (d == d ? d : PN_KINF);
}

/* Texel (tx, ty): its 3x3 depth discontinuity (neighbours off the map are the texel's own
 * depth); *near: the nearest depth around. */
PN_KFN float pn_srt_delta(PN_CONST float *depth, uint32_t res, int32_t tx, int32_t ty, float *near)
{
    int32_t xm = tx > 0 ? tx - 1 : 0, xp = tx + 1 < (int32_t)res ? tx + 1 : tx;
    int32_t ym = ty > 0 ? ty - 1 : 0, yp = ty + 1 < (int32_t)res ? ty + 1 : ty;
    PN_CONST float *r0 = depth + (size_t)ym * res, *r1 = depth + (size_t)ty * res, *r2 = depth + (size_t)yp * res;
    float s = r1[tx];
    float q0 = r0[xm], q1 = r0[tx], q2 = r0[xp], q3 = r1[xm], q4 = r1[xp], q5 = r2[xm], q6 = r2[tx], q7 = r2[xp];
    float D = pn_kmaxf(pn_kmaxf(pn_kmaxf(pn_srt_ddiff(s, q0), pn_srt_ddiff(s, q1)),
                                pn_kmaxf(pn_srt_ddiff(s, q2), pn_srt_ddiff(s, q3))),
                       pn_kmaxf(pn_kmaxf(pn_srt_ddiff(s, q4), pn_srt_ddiff(s, q5)),
                                pn_kmaxf(pn_srt_ddiff(s, q6), pn_srt_ddiff(s, q7))));
    *near = pn_kminf(pn_kminf(pn_kminf(s, q0), pn_kminf(q1, q2)),
                     pn_kminf(pn_kminf(q3, q4), pn_kminf(q5, pn_kminf(q6, q7))));
    return D;
}

/* How much a texel's depth may differ from its neighbours' on its own surface: three
 * texels' worth of the depth change of its triangle's plane along the map (s alpha tan of
 * the angle between the plane's normal and the texel's ray), so that sloped and gently
 * curved surfaces are not taken for occluder edges; +inf for a plane edge-on to the ray. */
PN_KFN float pn_srt_slope(const pn_kview *lv, float alpha, PN_CONST float *tris, uint32_t id, uint32_t tx, uint32_t ty,
                          float s)
{
    PN_CONST float *p = tris + (size_t)id * 9u;
    pn_v3 A = pn_v3_make(p[0], p[1], p[2]);
    pn_v3 n = pn_v3_normalize(pn_v3_cross(pn_v3_sub(pn_v3_make(p[3], p[4], p[5]), A), pn_v3_sub(pn_v3_make(p[6], p[7], p[8]), A)));
    pn_v3 d = pn_ray_dir(lv, tx, ty);
    float cs = pn_v3_dot(n, d), sn;
    cs = cs < 0.0f ? -cs : cs;
    if (!(cs > 1e-3f)) return PN_KINF;
    sn = pn_ksqrt(pn_kmaxf(0.0f, 1.0f - cs * cs));
    return 3.0f * s * alpha * sn / cs;
}

/* Texel (x, y) of the soft map: its splat weight, 1/z of the nearest depth around it when it
 * is an edge texel (its depth differs from a neighbour's by more than the threshold plus
 * its surface's slope allowance), at least the mark of a thin triangle touching it; 0:
 * none. */
PN_KFN float pn_srt_texel_weight(const pn_kview *lv, float delta, float alpha, PN_CONST float *depth,
                                 PN_CONST uint32_t *ids, PN_CONST float *tris, PN_CONST uint32_t *cons, uint32_t x,
                                 uint32_t y)
{
    uint32_t res = lv->width;
    size_t t = (size_t)y * res + x;
    float near, D = pn_srt_delta(depth, res, (int32_t)x, (int32_t)y, &near), w = pn_kbitsf(cons[t]);
    if (!(D > delta) || !(near < PN_KINF)) return w;
    if (D < PN_KINF && ids[t] != 0xFFFFFFFFu && !(D > delta + pn_srt_slope(lv, alpha, tris, ids[t], x, y, depth[t])))
        return w;
    return pn_kmaxf(w, 1.0f / pn_srt_texel_z(lv, x, y, near));
}

/* Tile (bx, by) of the soft map: the largest splat weight of its texels (0: none), into
 * tile_w, and into *wmax by atomic max. */
PN_KFN void pn_srt_tile(const pn_kview *lv, float delta, float alpha, PN_CONST float *depth, PN_CONST uint32_t *ids,
                        PN_CONST float *tris, PN_CONST uint32_t *cons, uint32_t tile, uint32_t tiles,
                        PN_GLOBAL uint32_t *tile_w, PN_GLOBAL uint32_t *wmax)
{
    uint32_t res = lv->width, bx = tile % tiles, by = tile / tiles, x, y;
    float w = 0.0f;
    for (y = by * PN_SRT_TILE; y < (by + 1u) * PN_SRT_TILE && y < res; y++)
        for (x = bx * PN_SRT_TILE; x < (bx + 1u) * PN_SRT_TILE && x < res; x++)
            w = pn_kmaxf(w, pn_srt_texel_weight(lv, delta, alpha, depth, ids, tris, cons, x, y));
    tile_w[tile] = pn_kfbits(w);
    if (w > 0.0f) pn_srt_atomic_fmax(wmax, w);
}

/* Tiles per map axis at most (the sweeps' private deque). */
#define PN_SRT_TILES_MAX (PN_SRT_MAP_MAX / PN_SRT_TILE + 1u)

/* Tiles an edge tile of weight w reaches along an axis whose reach is r texels per unit
 * weight: texels between two tiles' nearest texels, (|d| - 1) * TILE, at most r w + 1. */
PN_KFN int32_t pn_srt_reach_tiles(float r, float w)
{
    float t = (r * w + 1.0f) / (float)PN_SRT_TILE + 1.0f;
    return t < 16384.0f ? (int32_t)t : 16384;
}

/* One line of n tiles (stride apart from `first`): out[x] = the largest in[j] (float bits,
 * > 0) whose reach pn_srt_reach_tiles(r, in[j]) covers x, else 0: the union of splats along
 * one axis, as two sliding-window maxima (left to right, right to left) over a deque kept
 * in decreasing weight (a weight behind a larger one that reaches farther never matters).
 * O(n), the same result whatever order lines run in. */
PN_KFN void pn_srt_sweep(PN_CONST uint32_t *in, PN_GLOBAL uint32_t *out, uint32_t first, uint32_t stride, uint32_t n,
                         float r)
{
    uint32_t dq[PN_SRT_TILES_MAX];
    int32_t x, head, tail, pass;
    for (x = 0; x < (int32_t)n; x++) out[first + (uint32_t)x * stride] = 0u;
    for (pass = 0; pass < 2; pass++) {
        head = 0;
        tail = 0;
        for (x = 0; x < (int32_t)n; x++) {
            int32_t i = pass == 0 ? x : (int32_t)n - 1 - x;
            uint32_t wb = in[first + (uint32_t)i * stride];
            if (pn_kbitsf(wb) > 0.0f) {
                while (tail > head && in[first + dq[tail - 1] * stride] <= wb) tail--;
                dq[tail++] = (uint32_t)i;
            }
            while (tail > head) {
                int32_t j = (int32_t)dq[head], d = i > j ? i - j : j - i;
                if (d <= pn_srt_reach_tiles(r, pn_kbitsf(in[first + (uint32_t)j * stride]))) break;
                head++;
            }
            if (tail > head && in[first + dq[head] * stride] > out[first + (uint32_t)i * stride])
                out[first + (uint32_t)i * stride] = in[first + dq[head] * stride];
        }
    }
}

/* A receiver at depth z along the light axis: the weight an occluder must exceed to reach
 * it, 1/z for a z rounded up a little. */
PN_KFN float pn_srt_receiver_w(float z) { return 1.0f / (z * 1.0001f); }

/* A receiver of weight cz (pn_srt_receiver_w) in tile (bx, by): 1 if some edge tile's
 * splat reaches it. An occluder point at weight w = 1/z_e is seen from light point
 * c + a U + b V displaced in the map by (a |U|, b |V|) (1/z - w): for w > 1/z the shadow it
 * casts at the receiver's depth lies within |U| (w - 1/z) by |V| (w - 1/z) of it (exactly),
 * in texels reach_u (w - 1/z) by reach_v (w - 1/z), plus the tiles' own width. */
PN_KFN uint32_t pn_srt_refine(PN_CONST uint32_t *tile_w, uint32_t tiles, int32_t bx, int32_t by, float cz, float wmax,
                              float reach_u, float reach_v)
{
    int32_t rx, ry, x, y;
    if (!(wmax > cz)) return 0u;
    rx = pn_srt_reach_tiles(reach_u, wmax - cz);
    ry = pn_srt_reach_tiles(reach_v, wmax - cz);
    for (y = by - ry; y <= by + ry; y++) {
        if (y < 0 || y >= (int32_t)tiles) continue;
        for (x = bx - rx; x <= bx + rx; x++) {
            float w, gx, gy;
            if (x < 0 || x >= (int32_t)tiles) continue;
            w = pn_kbitsf(tile_w[(size_t)y * tiles + (size_t)x]);
            if (!(w > cz)) continue;
            gx = (float)((x > bx ? x - bx : bx - x) - 1) * (float)PN_SRT_TILE;
            gy = (float)((y > by ? y - by : by - y) - 1) * (float)PN_SRT_TILE;
            /* Reached unless shown out of reach: a NaN (an infinite weight, from an occluder at
             * depth 0, times a zero reach) reaches. */
            if (!(gx > reach_u * (w - cz) + 1.0f) && !(gy > reach_v * (w - cz) + 1.0f)) return 1u;
        }
    }
    return 0u;
}

/* The parameters the classification reads (from pn_kparams). */
typedef struct pn_srt_args {
    float delta;        /* depth-discontinuity threshold, scene units */
    float alpha;        /* a texel's size in tan units (2 tan_half / res) */
    float reach_u, reach_v, wmax; /* splat reach in texels per unit weight; largest weight */
    uint32_t flags;     /* PN_SRT_NO_CONSERVATIVE, PN_SRT_FLAG_FORCE_PIP */
    uint32_t tiles;     /* tiles per map row */
} pn_srt_args;

/* Texel (tx, ty) of a receiver at depth z along the light axis: 1 if it lies in the
 * penumbra mask: the coarse mask (every splat at its widest, for receivers at infinity)
 * first, then the splats at this receiver's depth. */
PN_KFN uint32_t pn_srt_masked(const pn_srt_args *a, PN_CONST uint32_t *tile_w, PN_CONST uint32_t *tile_mask, uint32_t tx,
                              uint32_t ty, float z)
{
    uint32_t bx = tx / PN_SRT_TILE, by = ty / PN_SRT_TILE;
    return tile_mask[by * a->tiles + bx] != 0u &&
           pn_srt_refine(tile_w, a->tiles, (int32_t)bx, (int32_t)by, pn_srt_receiver_w(z), a->wmax, a->reach_u, a->reach_v);
}

/* Pixel pix: 1 if it is in the PIP set, else 0 with its visibility from the map in
 * *vis (also for background and unlit pixels, which are final). *lit: 1 if it faces the
 * light. */
PN_KFN uint32_t pn_srt_classify(const pn_kview *lv, const pn_klight *L, const pn_srt_args *a, const pn_ksurf *S,
                                PN_CONST float *tris, PN_CONST float *depth,
                                PN_CONST uint32_t *lmap_id, PN_CONST uint32_t *cons, PN_CONST uint32_t *tile_w,
                                PN_CONST uint32_t *tile_mask, size_t pix, float *vis, uint32_t *lit)
{
    uint32_t own = S->tri_id[pix], res = lv->width;
    pn_v3 P, n, O, c, Lc, toL;
    float px, py, d, s, sinb, cosb, sina, cosa, dhat, bias;
    int32_t tx, ty;
    *lit = 0u;
    if (own == 0xFFFFFFFFu) {
        *vis = 1.0f;
        return 0u;
    }
    pn_surf_at(S, pix, &P, &n);
    if (!pn_shadow_origin(P, n, L, &O)) {
        *vis = 0.0f;
        return 0u;
    }
    *lit = 1u;
    *vis = 1.0f;
    if (a->flags & PN_SRT_FLAG_FORCE_PIP) return 1u;
    Lc = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    toL = pn_v3_sub(Lc, O);
    d = pn_ksqrt(pn_v3_dot(toL, toL));
    if (!(d > 0.0f)) return 1u;
    if (pn_v3_dot(n, pn_v3_sub(Lc, P)) < 0.0f) n = pn_v3_scale(n, -1.0f);
    if (!L->is_point) {
        /* Part of the light at or behind the receiver's plane (or within rounding of it). */
        uint32_t q;
        for (q = 0; q < 4u; q++) {
            pn_v3 corner = pn_v3_add(Lc, pn_v3_add(pn_v3_scale(pn_v3_make(L->U[0], L->U[1], L->U[2]), (q & 1u) ? 1.0f : -1.0f),
                                                   pn_v3_scale(pn_v3_make(L->V[0], L->V[1], L->V[2]), (q & 2u) ? 1.0f : -1.0f)));
            pn_v3 e = pn_v3_sub(corner, P);
            if (!(pn_v3_dot(n, e) > 1e-4f * pn_ksqrt(pn_v3_dot(e, e)))) return 1u;
        }
    }
    c = pn_to_camera(lv, O);
    if (!(c.z >= lv->znear)) return 1u;
    pn_project_camera(lv, c, &px, &py);
    if (!(px >= 0.0f && py >= 0.0f && px < (float)res && py < (float)res)) return 1u;
    tx = (int32_t)px;
    ty = (int32_t)py;
    if (tx >= (int32_t)res) tx = (int32_t)res - 1;
    if (ty >= (int32_t)res) ty = (int32_t)res - 1;
    s = depth[(size_t)ty * res + (size_t)tx];
    /* d^: the nearest depth the receiver's plane reaches within one texel's angle. */
    sinb = pn_v3_dot(n, toL) / d;
    /* A light centre on or near the receiver's plane: the horizon decides (invariant 6). */
    if (!(sinb > 1e-4f)) return 1u;
    sinb = pn_kminf(1.0f, sinb);
    cosb = pn_ksqrt(pn_kmaxf(0.0f, 1.0f - sinb * sinb));
    sina = a->alpha / pn_ksqrt(1.0f + a->alpha * a->alpha);
    cosa = 1.0f / pn_ksqrt(1.0f + a->alpha * a->alpha);
    dhat = d * sinb / (sina * cosb + cosa * sinb);
    if (!(dhat >= 0.0f)) dhat = 0.0f;
    if (L->is_point) {
        float near, D;
        if (cons[(size_t)ty * res + (size_t)tx] != 0u) return 1u;
        D = pn_srt_delta(depth, res, tx, ty, &near);
        if (D > a->delta && D < PN_KINF && lmap_id[(size_t)ty * res + (size_t)tx] != 0xFFFFFFFFu &&
            !(D > a->delta + pn_srt_slope(lv, a->alpha, tris, lmap_id[(size_t)ty * res + (size_t)tx], (uint32_t)tx,
                                          (uint32_t)ty, s)))
            D = 0.0f; /* the texel's own surface's slope explains the difference */
        if (D > a->delta) {
            float lo = dhat, hi = d + (d - dhat);
            if (!(hi < s - D || lo > s + D)) return 1u;
            if ((d - s) * (dhat - s) <= 0.0f) return 1u;
        }
    } else if (pn_srt_masked(a, tile_w, tile_mask, (uint32_t)tx, (uint32_t)ty, c.z)) {
        return 1u;
    }
    bias = (d - dhat) + 1e-4f * d;
    /* Another surface in front of O, lit only by the bias: the map cannot tell. */
    if (lmap_id[(size_t)ty * res + (size_t)tx] != own && d > s * (1.0f + 1e-4f) && !(d > s + bias)) return 1u;
    *vis = (lmap_id[(size_t)ty * res + (size_t)tx] == own || !(d > s + bias)) ? 1.0f : 0.0f;
    return 0u;
}

#endif
