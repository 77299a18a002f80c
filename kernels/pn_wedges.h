/* pn_wedges.h - PN_ALGO_WEDGES: soft shadow volumes by penumbra wedges (Akenine-Moller and
 * Assarsson 2002) with the overlap blending of Forest, Barthe and Paulin 2006 (the frame is
 * src/pn_wedges.c; connectivity is built at pn_scene_set by src/pn_connect.c).
 *
 * ---- What a pixel computes --------------------------------------------------------------
 * Light coordinates: a point X has u = (X - c).U / |U|^2, v = (X - c).V / |V|^2 (the light is
 * [-1, 1]^2, its centre the origin) and height h = (X - c).N. Seen from the pixel's shadow
 * origin O, an occluder covers the region S of the light that its silhouette loop projects
 * to. With f the indicator of S, the covered area is
 *     A = f(0) |L| + sum over silhouette edges e of s_e area(L behind e from the centre),
 * where "behind e from the centre" is the set of light points x whose segment from the
 * centre crosses the projected edge, and s_e = +1 when that crossing enters S (O is on the
 * outer side of the plane through the centre and e: the outer half-wedge), -1 when it
 * leaves (the inner half-wedge). f(0), the hard shadow of the centre, is what the paper's
 * shadow-volume stencil computes: a count, the silhouette loops around the centre, not a
 * flag; here it is the exact centre sample (pn_predicate.h) of a BVH walk from O
 * (pn_ray_walk), one per pixel, counting per object the distinct casting triangles it
 * crosses (an object of two layers, both around the centre, counts 2: counted once, the
 * band where one layer's loop leaves the light and the other's does not came out lit, a
 * bright ring inside the shadow).
 *
 * Silhouettes are those seen from the light centre (the method's approximation): an edge
 * whose adjacent "casting" triangles do not cancel. A solid object (closed, or but for
 * small holes and seams: src/pn_connect.c) casts with its triangles facing the centre; a
 * sheet with all of them, each turned to face the centre. An edge's
 * weight is the net count of casting triangles winding along it (1 on a closed mesh).
 *
 * Blending (the paper's section 3): the light is cut radially into its four quadrants; per
 * object ("silhouette") and quadrant, its occluded area A_s and a rectangle B_s bounding
 * the occluded region; per pixel the final A_f, B_f take each object in turn:
 *     eps = (A_f / |B_f|) (A_s / |B_s|) |B_f n B_s|,  A_f += A_s - eps,  B_f = box(B_f u B_s).
 * The classic combination (PN_WG_MODE_ADDITIVE) adds the A_s. Visibility is
 * 1 - sum of A_f / |L|, clamped to [0, 1], times the fraction of the k x k light samples in
 * front of the pixel's own plane (the horizon, as every algorithm applies).
 *
 * Bounds of an object's occluded region in a quadrant (reflected to Q = [0,1]^2, the centre
 * at its corner): the region is bounded by the object's edges and Q's sides, so its box
 * is that of the edges' end points (clipped to Q), with the centre when the centre is
 * occluded and the far corner (1, 1) when that is (the count there: the centre's plus the
 * signed weights of the edges crossing the segment to it). The paper bounds the regions
 * behind the outer edges, which reach the light's border: a sphere's shadow there had a box
 * from its near side to the border, and blending took neighbours' disjoint penumbrae for
 * overlapping ones (the spheres: 51 pixels blended worse than additive by more than 0.02,
 * none better).
 *
 * Order: each pixel takes the silhouette edges of its screen tile (PN_WG_TILE^2 pixels) in
 * ascending edge order, which groups them by object (edges are numbered object by object),
 * so its sums run in one order on every port. */
#ifndef PN_WEDGES_H
#define PN_WEDGES_H

#include "pn_raster.h"
#include "pn_raytrace.h"

#define PN_WG_REV 0x80000000u    /* half-edge: traverses its edge from the higher vertex id */
#define PN_WG_CLOSED 0x80000000u /* triangle's object: a solid (pn_connect.c's pn_cn_solids) */
#define PN_WG_DUP 0x40000000u    /* triangle: on the vertices of an earlier one (casts nothing) */
#define PN_WG_OBJ 0x3FFFFFFFu    /* triangle's object id */
#define PN_WG_HARD_MAX 16u       /* objects blocking the centre a pixel keeps track of */
#define PN_WG_TNEAR (1.0f / 1024.0f) /* the local near plane: a tenth of a percent of O's height */
#define PN_WG_EXACT (-1.0f) /* pn_wg_pixel: resolve this pixel exactly (pn_reference_fallback) */
#define PN_WG_M_BLEND 1u
#define PN_WG_M_ADD 2u
/* Casting codes per triangle (pn_wg_facing), in the low bits of its word... */
#define PN_WG_CAST_NONE 0u
#define PN_WG_CAST_AS_IS 1u
#define PN_WG_CAST_FLIPPED 2u
#define PN_WG_CAST_CODE 3u
/* ...and a flag: the whole light lies in front of the triangle's plane (pn_wg_front), so
 * the horizon of each of its pixels is empty. */
#define PN_WG_LIT_FRONT 4u

/* A silhouette edge a -> b: half-edge h (triangle h / 3, its edge h % 3 from vertex h % 3
 * to the next) | PN_WG_REV when the silhouette runs the other way; weight; object; its
 * wedge's screen tiles [x0, x1] x [y0, y1] (x0 > x1: none); and what every pixel needs of
 * it, computed once: a and b in light coordinates (u, v, h: pn_wg_light), the normal
 * (a - c) x (b - c) of the plane through the light centre and the edge, and the box in
 * light coordinates of its object's silhouette end points (ob: u0, u1, v0, v1, h0, h1;
 * the same in every silhouette of the object). */
typedef struct pn_wsil {
    uint32_t h, w, comp, x0, y0, x1, y1;
    float ua, va, ha, ub, vb, hb, nx, ny, nz;
    float ob[8]; /* its object's box (pn_wg_sil_box), then max(|u0|, |u1|), max(|v0|, |v1|) */
} pn_wsil;

/* Light coordinates of X: u = (X - c).U / |U|^2, v = (X - c).V / |V|^2, h = (X - c).N. */
PN_KFN void pn_wg_light(const pn_klight *L, pn_v3 X, float *u, float *v, float *h)
{
    pn_v3 U = pn_light_U(L), V = pn_light_V(L), xc = pn_v3_sub(X, pn_light_c(L));
    *u = pn_v3_dot(xc, U) * (1.0f / pn_v3_dot(U, U));
    *v = pn_v3_dot(xc, V) * (1.0f / pn_v3_dot(V, V));
    *h = pn_v3_dot(xc, pn_v3_make(L->N[0], L->N[1], L->N[2]));
}

/* ---- Per triangle and per edge ----------------------------------------------------------- */

/* PN_WG_LIT_FRONT when every point of the light lies on one side of triangle A B C's plane
 * (the light centre's), by far more than any rounding: then a pixel on it, whose horizon
 * (pn_horizon_of) keeps the samples on the side of its normal turned toward the centre,
 * finds every sample's plane value (pn_plane_form's, h0 + a hu + b hv with the same n =
 * (B - A) x (C - A), h0 = (c - A).n) above its bound and sets none (pn_horizon_mask returns
 * 0), so the pixel need not build its horizon. The values at the light's four corners
 * (a, b = +-1: the form's own bits there) bound those at its samples (an affine form); the
 * margin, a thousandth of |B - A|1 |C - A|1 times g (pn_kwg.front_g, which bounds |c - A|inf
 * + |U|inf + |V|inf + |A|inf + |c|inf + |e - A|inf for any A in the scene box), dwarfs the
 * form's bound (12 u of the first three), the normal's rounding and the G-buffer point's
 * distance from the plane (its depth's rounding, relative to the eye's distance e, counted
 * in). */
PN_KFN uint32_t pn_wg_front(const pn_klight *L, float g, pn_v3 A, pn_v3 B, pn_v3 C, pn_v3 n, float h0)
{
    float hu = pn_v3_dot(pn_light_U(L), n), hv = pn_v3_dot(pn_light_V(L), n), lo = PN_KINF, hi = -PN_KINF, m;
    uint32_t q;
    m = 1e-3f * (pn_v3_l1(pn_v3_sub(B, A)) * pn_v3_l1(pn_v3_sub(C, A))) * g + 4.0f * PN_KTINY;
    for (q = 0; q < 4u; q++) {
        float x = h0 + ((q & 1u) ? hu : -hu) + ((q & 2u) ? hv : -hv);
        lo = pn_kminf(lo, x);
        hi = pn_kmaxf(hi, x);
    }
    return lo > m || -hi > m ? PN_WG_LIT_FRONT : 0u;
}

/* How triangle t casts: PN_WG_CAST_AS_IS (it faces the centre), _FLIPPED (an open object's
 * triangle facing away: it casts turned round) or _NONE; with PN_WG_LIT_FRONT (pn_wg_front)
 * for a triangle the G-buffer can show. */
PN_KFN uint32_t pn_wg_facing(const pn_klight *L, float g, PN_CONST float *tris, PN_CONST uint8_t *flags,
                             PN_CONST uint32_t *tcomp, uint32_t t)
{
    PN_CONST float *p = tris + (size_t)t * 9u;
    pn_v3 A = pn_v3_make(p[0], p[1], p[2]), B = pn_v3_make(p[3], p[4], p[5]), C = pn_v3_make(p[6], p[7], p[8]), n;
    uint32_t front;
    float s;
    if (flags[t] & PN_TRI_DEGENERATE) return PN_WG_CAST_NONE;
    n = pn_tri_cross(A, B, C);
    s = pn_v3_dot(pn_v3_sub(pn_light_c(L), A), n);
    front = pn_wg_front(L, g, A, B, C, n, s);
    if (tcomp[t] & PN_WG_DUP) return PN_WG_CAST_NONE | front;
    /* A solid wound inside out casts from the faces its winding turns away, turned round. */
    if (flags[t] & PN_TRI_INVERTED) return (s < 0.0f ? PN_WG_CAST_FLIPPED : PN_WG_CAST_NONE) | front;
    if (s > 0.0f) return PN_WG_CAST_AS_IS | front;
    if (s < 0.0f && !(tcomp[t] & PN_WG_CLOSED)) return PN_WG_CAST_FLIPPED | front;
    return PN_WG_CAST_NONE | front;
}

/* Net winding of edge run r's casting triangles: > 0 along the run's canonical direction
 * (lower vertex id first), < 0 against it, 0 when they cancel (no silhouette). */
PN_KFN int32_t pn_wg_run_winding(PN_CONST uint32_t *hedge, PN_CONST uint32_t *run, PN_CONST uint32_t *tcast, uint32_t r)
{
    int32_t m = 0;
    uint32_t i;
    for (i = run[r]; i < run[r + 1u]; i++) {
        uint32_t h = hedge[i], cast = tcast[(h & ~PN_WG_REV) / 3u] & PN_WG_CAST_CODE;
        int32_t s = (h & PN_WG_REV) ? -1 : 1;
        if (cast == PN_WG_CAST_NONE) continue;
        m += cast == PN_WG_CAST_FLIPPED ? -s : s;
    }
    return m;
}

/* The silhouette's end points in its direction. */
PN_KFN void pn_wg_ends(PN_CONST float *tris, uint32_t h, pn_v3 *a, pn_v3 *b)
{
    uint32_t he = h & ~PN_WG_REV, t = he / 3u, e = he % 3u, f = e == 2u ? 0u : e + 1u;
    PN_CONST float *p = tris + (size_t)t * 9u;
    pn_v3 x = pn_v3_make(p[3u * e], p[3u * e + 1u], p[3u * e + 2u]), y = pn_v3_make(p[3u * f], p[3u * f + 1u], p[3u * f + 2u]);
    *a = (h & PN_WG_REV) ? y : x;
    *b = (h & PN_WG_REV) ? x : y;
}

/* Screen position of eye-relative point or direction d; 0 when it is not in front. */
PN_KFN int pn_wg_screen(const pn_kview *v, pn_v3 d, float *px, float *py)
{
    pn_v3 f = pn_v3_make(v->f[0], v->f[1], v->f[2]), r = pn_v3_make(v->r[0], v->r[1], v->r[2]);
    pn_v3 u = pn_v3_make(v->u[0], v->u[1], v->u[2]);
    float z = pn_v3_dot(d, f);
    if (!(z > 1e-6f * pn_v3_l1(d))) return 0;
    *px = (pn_v3_dot(d, r) / (z * v->tan_half * v->aspect) + 1.0f) * 0.5f * (float)v->width;
    *py = (1.0f - pn_v3_dot(d, u) / (z * v->tan_half)) * 0.5f * (float)v->height;
    return 1;
}

/* The screen reach of the wedge of edge a b. The wedge is the set of points
 * y + s (y - l), y on the edge, l on the light, s >= 0. A point at height h above the
 * light plane has h(y + s (y - l)) = (1 + s) h(y), so the part of the wedge no higher than
 * hmax ends on that plane at l + (hmax / h(y)) (y - l): for a fixed l a segment between the
 * images of a and b (a central projection), affine in l for a fixed y, so every such point
 * lies in the hull of the eight images of a and b from the light's corners. The wedge's
 * reach is in the hull of those and a, b; its image in the hull of their screen images (a
 * perspective keeps convex sets convex in front of the eye), when all ten are in front of
 * the eye (else the whole screen, as for an edge not wholly in front of the light).
 *
 * The reach keeps that hull when want_hull (counter-clockwise, n vertices; n = 0: no hull,
 * every tile of the box) and its tile box [x0, x1] x [y0, y1] (x0 > x1: none), both widened by two
 * pixels. The widening covers rounding: the hull is built only while every point is within
 * 2^20 pixels of the screen (else n = 0), where a float carries a sixteenth of a pixel, so
 * an orientation or an edge's crossing of a row (pn_wg_row) is off by under a pixel,
 * and a point taken off the hull as collinear lies that close to it. */
#define PN_WG_REACH_PTS 10u /* the edge's two ends and their images from the four corners */
#define PN_WG_REACH_MAX 1048576.0f
#define PN_WG_WIDEN 2.0f

typedef struct pn_wreach {
    float hx[PN_WG_REACH_PTS], hy[PN_WG_REACH_PTS];
    uint32_t n, x0, y0, x1, y1;
} pn_wreach;

/* The tile (of nt) holding screen coordinate p, clamped to the screen. */
PN_KFN uint32_t pn_wg_tile(float p, uint32_t nt) { return (uint32_t)pn_kfloor_clamp(p / (float)PN_WG_TILE, 0, (int32_t)nt - 1); }

PN_KFN float pn_wg_turn(float ax, float ay, float bx, float by, float cx, float cy)
{
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

PN_KFN void pn_wg_reach(const pn_kview *v, const pn_klight *L, float hmax, pn_v3 a, pn_v3 b, int want_hull, pn_wreach *R)
{
    pn_v3 eye = pn_view_eye(v), c = pn_light_c(L), U = pn_light_U(L), V = pn_light_V(L), d[PN_WG_REACH_PTS];
    pn_v3 N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
    float lo_x = PN_KINF, lo_y = PN_KINF, hi_x = -PN_KINF, hi_y = -PN_KINF, sx[PN_WG_REACH_PTS], sy[PN_WG_REACH_PTS];
    float ha = pn_v3_dot(pn_v3_sub(a, c), N), hb = pn_v3_dot(pn_v3_sub(b, c), N);
    uint32_t tw = PN_WG_TILES(v->width), th = PN_WG_TILES(v->height), i, j, m;
    int all = ha > 0.0f && hb > 0.0f && hmax >= ha && hmax >= hb, hull = 1;
    R->n = 0u;
    d[0] = pn_v3_sub(a, eye);
    d[1] = pn_v3_sub(b, eye);
    for (i = 0; all && i < 4u; i++) {
        pn_v3 l = pn_v3_add(pn_v3_add(c, pn_v3_scale(U, (i & 1u) ? 1.0f : -1.0f)), pn_v3_scale(V, (i & 2u) ? 1.0f : -1.0f));
        d[2u + 2u * i] = pn_v3_sub(pn_v3_add(l, pn_v3_scale(pn_v3_sub(a, l), hmax / ha)), eye);
        d[3u + 2u * i] = pn_v3_sub(pn_v3_add(l, pn_v3_scale(pn_v3_sub(b, l), hmax / hb)), eye);
    }
    for (i = 0; all && i < PN_WG_REACH_PTS; i++) {
        if (!pn_wg_screen(v, d[i], sx + i, sy + i)) {
            all = 0;
            break;
        }
        lo_x = pn_kminf(lo_x, sx[i]);
        lo_y = pn_kminf(lo_y, sy[i]);
        hi_x = pn_kmaxf(hi_x, sx[i]);
        hi_y = pn_kmaxf(hi_y, sy[i]);
    }
    if (!all) {
        R->x0 = 0u;
        R->y0 = 0u;
        R->x1 = tw - 1u;
        R->y1 = th - 1u;
        return;
    }
    lo_x -= PN_WG_WIDEN;
    lo_y -= PN_WG_WIDEN;
    hi_x += PN_WG_WIDEN;
    hi_y += PN_WG_WIDEN;
    if (!(hi_x >= 0.0f && hi_y >= 0.0f && lo_x < (float)v->width && lo_y < (float)v->height)) {
        R->x0 = 1u;
        R->x1 = 0u;
        R->y0 = 1u;
        R->y1 = 0u;
        return;
    }
    R->x0 = pn_wg_tile(lo_x, tw);
    R->y0 = pn_wg_tile(lo_y, th);
    R->x1 = pn_wg_tile(hi_x, tw);
    R->y1 = pn_wg_tile(hi_y, th);
    for (i = 0; i < PN_WG_REACH_PTS; i++)
        hull &= pn_kfabs(sx[i]) <= PN_WG_REACH_MAX && pn_kfabs(sy[i]) <= PN_WG_REACH_MAX;
    /* A box one tile wide or high, or two by two, has no tile the hull could leave out
     * that matters: every tile of the box (n = 0). */
    if (!want_hull || !hull || R->x0 == R->x1 || R->y0 == R->y1 || (R->x1 - R->x0 < 2u && R->y1 - R->y0 < 2u)) return;
    /* Andrew's monotone chain: points by x then y (insertion sort), lower chain then upper. */
    for (i = 1; i < PN_WG_REACH_PTS; i++) {
        float x = sx[i], y = sy[i];
        for (j = i; j > 0u && (sx[j - 1u] > x || (sx[j - 1u] == x && sy[j - 1u] > y)); j--) {
            sx[j] = sx[j - 1u];
            sy[j] = sy[j - 1u];
        }
        sx[j] = x;
        sy[j] = y;
    }
    {
        float cx[2u * PN_WG_REACH_PTS], cy[2u * PN_WG_REACH_PTS];
        m = 0u;
        for (i = 0; i < PN_WG_REACH_PTS; i++) {
            while (m >= 2u && pn_wg_turn(cx[m - 2u], cy[m - 2u], cx[m - 1u], cy[m - 1u], sx[i], sy[i]) <= 0.0f) m--;
            cx[m] = sx[i];
            cy[m] = sy[i];
            m++;
        }
        for (i = PN_WG_REACH_PTS - 1u, j = m + 1u; i-- > 0u;) {
            while (m >= j && pn_wg_turn(cx[m - 2u], cy[m - 2u], cx[m - 1u], cy[m - 1u], sx[i], sy[i]) <= 0.0f) m--;
            cx[m] = sx[i];
            cy[m] = sy[i];
            m++;
        }
        m = m > 1u ? m - 1u : m; /* the last point repeats the first */
        for (i = 0; i < m && i < PN_WG_REACH_PTS; i++) {
            R->hx[i] = cx[i];
            R->hy[i] = cy[i];
        }
        R->n = m < PN_WG_REACH_PTS ? m : PN_WG_REACH_PTS;
    }
}

/* The tile columns [*x0, *x1] of row ty the reach R covers (*x0 > *x1: none): those within
 * two pixels of the hull's part in the row's band (two pixels beyond the row each way),
 * whose extent in x is reached at a hull vertex in the band or where a hull edge crosses
 * one of the band's lines. */
PN_KFN void pn_wg_row(const pn_kview *v, const pn_wreach *R, uint32_t ty, uint32_t *x0, uint32_t *x1)
{
    float ya = (float)(ty * PN_WG_TILE) - PN_WG_WIDEN, yb = (float)((ty + 1u) * PN_WG_TILE) + PN_WG_WIDEN;
    float lo = PN_KINF, hi = -PN_KINF, lines[2];
    uint32_t tw = PN_WG_TILES(v->width), i, k;
    if (R->n == 0u) {
        *x0 = R->x0;
        *x1 = R->x1;
        return;
    }
    lines[0] = ya;
    lines[1] = yb;
    for (i = 0; i < R->n; i++) {
        uint32_t nx = i + 1u == R->n ? 0u : i + 1u;
        float px = R->hx[i], py = R->hy[i], qx = R->hx[nx], qy = R->hy[nx];
        if (py >= ya && py <= yb) {
            lo = pn_kminf(lo, px);
            hi = pn_kmaxf(hi, px);
        }
        for (k = 0; k < 2u; k++) {
            float Y = lines[k], x;
            if ((py < Y) == (qy < Y)) continue;
            x = px + (Y - py) * ((qx - px) / (qy - py));
            x = pn_kminf(pn_kmaxf(x, pn_kminf(px, qx)), pn_kmaxf(px, qx));
            lo = pn_kminf(lo, x);
            hi = pn_kmaxf(hi, x);
        }
    }
    lo -= PN_WG_WIDEN;
    hi += PN_WG_WIDEN;
    if (!(lo <= hi && hi >= 0.0f && lo < (float)v->width)) {
        *x0 = 1u;
        *x1 = 0u;
        return;
    }
    *x0 = pn_wg_tile(lo, tw);
    *x1 = pn_wg_tile(hi, tw);
    if (*x0 < R->x0) *x0 = R->x0;
    if (*x1 > R->x1) *x1 = R->x1;
}

/* The silhouette half-edge of a run whose first half-edge is h0 and whose net winding is
 * m (non-zero): the run's edge in the direction the silhouette runs. */
PN_KFN uint32_t pn_wg_sil_h(uint32_t h0, int32_t m)
{
    uint32_t rev0 = (h0 & PN_WG_REV) != 0u;
    /* The silhouette runs along the canonical direction iff m > 0; the half-edge does iff
     * it is not reversed. */
    return (h0 & ~PN_WG_REV) | (((m > 0) == (rev0 != 0u)) ? PN_WG_REV : 0u);
}

/* Edge run r: 0 when its winding is zero (not a silhouette); else 1 and its silhouette
 * record in *s, with its wedge's tile box (the reach's). */
PN_KFN int pn_wg_sil_rec(const pn_kview *v, const pn_klight *L, float hmax, PN_CONST float *tris, PN_CONST uint32_t *hedge,
                         PN_CONST uint32_t *run, PN_CONST uint32_t *tcast, PN_CONST uint32_t *tcomp, uint32_t r, pn_wsil *s)
{
    int32_t m = pn_wg_run_winding(hedge, run, tcast, r);
    uint32_t h0 = hedge[run[r]];
    pn_wreach R;
    pn_v3 a, b;
    uint32_t i;
    if (m == 0) return 0;
    s->h = pn_wg_sil_h(h0, m);
    s->w = (uint32_t)(m > 0 ? m : -m);
    s->comp = tcomp[(h0 & ~PN_WG_REV) / 3u] & PN_WG_OBJ;
    pn_wg_ends(tris, s->h, &a, &b);
    pn_wg_reach(v, L, hmax, a, b, 0, &R); /* its box: the hull is built where it is binned */
    {
        pn_v3 c = pn_light_c(L), n = pn_v3_cross(pn_v3_sub(a, c), pn_v3_sub(b, c));
        float u, vv, h;
        pn_wg_light(L, a, &u, &vv, &h);
        s->ua = u;
        s->va = vv;
        s->ha = h;
        pn_wg_light(L, b, &u, &vv, &h);
        s->ub = u;
        s->vb = vv;
        s->hb = h;
        s->nx = n.x;
        s->ny = n.y;
        s->nz = n.z;
        for (i = 0; i < 8u; i++) s->ob[i] = 0.0f; /* pn_wg_obj_box's */
    }
    s->x0 = R.x0;
    s->y0 = R.y0;
    s->x1 = R.x1;
    s->y1 = R.y1;
    return 1;
}

/* Edge run r: its silhouette record at slot (when its winding is non-zero). */
PN_KFN void pn_wg_sil_make(const pn_kview *v, const pn_klight *L, float hmax, PN_CONST float *tris, PN_CONST uint32_t *hedge,
                           PN_CONST uint32_t *run, PN_CONST uint32_t *tcast, PN_CONST uint32_t *tcomp, uint32_t r,
                           uint32_t slot, PN_GLOBAL pn_wsil *sil)
{
    pn_wsil s;
    if (pn_wg_sil_rec(v, L, hmax, tris, hedge, run, tcast, tcomp, r, &s)) sil[slot] = s;
}

/* The box in light coordinates (u0, u1, v0, v1, h0, h1) of the end points of silhouettes
 * [j0, j1) that are of object c (any object: c = PN_WG_ANY), from j0 on. With no_cull
 * (PN_WG_NO_CULL) its h0 is -infinity: no box test passes (pn_wg_obj_misses and
 * pn_wg_box6_misses ask for a box above the light plane). */
#define PN_WG_ANY 0xFFFFFFFFu
PN_KFN void pn_wg_sil_box(PN_CONST pn_wsil *sil, uint32_t j0, uint32_t j1, uint32_t c, uint32_t no_cull, float *b)
{
    uint32_t j;
    b[0] = b[2] = b[4] = PN_KINF;
    b[1] = b[3] = b[5] = -PN_KINF;
    for (j = j0; j < j1 && (c == PN_WG_ANY || sil[j].comp == c); j++) {
        PN_CONST pn_wsil *e = sil + j;
        b[0] = pn_kminf(b[0], pn_kminf(e->ua, e->ub));
        b[1] = pn_kmaxf(b[1], pn_kmaxf(e->ua, e->ub));
        b[2] = pn_kminf(b[2], pn_kminf(e->va, e->vb));
        b[3] = pn_kmaxf(b[3], pn_kmaxf(e->va, e->vb));
        b[4] = pn_kminf(b[4], pn_kminf(e->ha, e->hb));
        b[5] = pn_kmaxf(b[5], pn_kmaxf(e->ha, e->hb));
    }
    if (no_cull) b[4] = -PN_KINF;
}

/* Silhouette s, the first of its object's (silhouettes are numbered object by object):
 * the object's box (pn_wsil.ob) into each of its silhouettes. */
PN_KFN void pn_wg_obj_box(PN_GLOBAL pn_wsil *sil, uint32_t nsil, uint32_t s, uint32_t no_cull)
{
    uint32_t c = sil[s].comp, j, i;
    float b[6];
    if (s > 0u && sil[s - 1u].comp == c) return;
    pn_wg_sil_box(sil, s, nsil, c, no_cull, b);
    for (j = s; j < nsil && sil[j].comp == c; j++) {
        for (i = 0; i < 6u; i++) sil[j].ob[i] = b[i];
        sil[j].ob[6] = pn_kmaxf(pn_kfabs(b[0]), pn_kfabs(b[1]));
        sil[j].ob[7] = pn_kmaxf(pn_kfabs(b[2]), pn_kfabs(b[3]));
    }
}

/* Block k of silhouettes (PN_WG_BLOCK of them from k PN_WG_BLOCK on, of any objects): the
 * box of their end points (bb[6 k ..], as pn_wsil.ob). Edges are numbered by their
 * vertices, welded in the Morton order of their positions (src/pn_connect.c), so a block's
 * edges lie near one another: a pixel skips the run of its tile's list in a block whose
 * box no edge of which can project onto the light (pn_wg_obj_misses), most of a list
 * where wedges are thin beside the light's size. */
#define PN_WG_BLOCK 16u
#define PN_WG_BLOCK_RUN 2u /* the least run a pixel tests its block's box for */
/* A superblock: PN_WG_SBLOCK silhouettes (a tree's few dozen neighbouring leaves, objects
 * numbered in Morton order too), whose box a pixel tests before its objects'. */
#define PN_WG_SBLOCK 128u

/* Block k of n silhouettes each (PN_WG_BLOCK or PN_WG_SBLOCK): its box into bb[6 k ..]. */
PN_KFN void pn_wg_block_box(PN_CONST pn_wsil *sil, uint32_t nsil, uint32_t k, uint32_t n, uint32_t no_cull,
                            PN_GLOBAL float *bb)
{
    uint32_t j, end = (k + 1u) * n < nsil ? (k + 1u) * n : nsil;
    float b[6];
    pn_wg_sil_box(sil, k * n, end, PN_WG_ANY, no_cull, b);
    for (j = 0; j < 6u; j++) bb[(size_t)k * 6u + j] = b[j];
}

/* ---- Tiles in depth: the light-space box of a tile's shadow origins ---------------------- */

/* A tile's box (PN_WG_BOX floats): the least and greatest u, v and h (pn_wg_light) of the
 * shadow origins O of its pixels that have one, the very values pn_wg_pixel computes; u0 > u1
 * when no pixel of the tile has one. Then PN_WG_CLEAR: 1 when no triangle meets a segment
 * from one of those origins to the light centre (pn_wg_cone_clear), so that its pixels need
 * no centre ray; else 0. */
#define PN_WG_BOX 7u
#define PN_WG_CLEAR 6u
/* PN_WG_CLEAR of a tile whose list holds more silhouettes or pairs than the frame's pools
 * (src/pn_wedges.c): it lists nothing (its box is empty) and its pixels take the reference's
 * visibility at the frame's k. */
#define PN_WG_FULL (-1.0f)

/* Marks tile box B PN_WG_FULL (the host, between the tile boxes and the binning). */
PN_KFN void pn_wg_box_full(PN_GLOBAL float *B)
{
    B[0] = B[2] = B[4] = PN_KINF;
    B[1] = B[3] = B[5] = -PN_KINF;
    B[PN_WG_CLEAR] = PN_WG_FULL;
}

/* The cone of a tile's centre segments: with apex the light centre c (light coordinates
 * (u, v, h) = (0, 0, 0)), a segment from origin O to c is the points s O, s in [0, 1], along
 * which u / h and v / h stay O's; so every such segment of the tile lies in
 *     h >= 0,  a0 h <= u <= a1 h,  b0 h <= v <= b1 h,  m . (X - c) <= D,
 * [a0, a1] x [b0, b1] the box of the origins' u / h and v / h, and the last (the cap) a
 * plane facing away from the light, m the normal of the tile's first receiver turned away
 * from it and D the origins' greatest m . (O - c) (c is inside: that receiver faces it, so
 * D > 0; any m would do, the cap only holds all of the segments). Where the receivers lie
 * on one plane (a floor, a wall) the cap is that plane moved eps toward the light: their
 * own triangles, behind it, are outside. The six planes make a pn_frustum (unit normals,
 * moved out by its slack), which the reference's culls test boxes against. */

/* A cone in the making: its ratios' box, the cap's normal m (the first receiver's, once
 * has_m; every origin's m . (O - c) enters D, so a zero first normal leaves no cone) and
 * offset D, and the origins' greatest L1 distance to c (the slack's). Each origin O (of
 * receiver point P, normal n) is added once (pn_wg_cone_add); pn_wg_cone_frustum makes the
 * frustum, or says 0 when an origin is not below the light plane (h <= 0) or there is none. */
typedef struct pn_wcone {
    float r[4], D, l1;
    pn_v3 m;
    int ok, has_m;
} pn_wcone;

PN_KFN void pn_wg_cone_init(pn_wcone *C)
{
    C->r[0] = C->r[2] = PN_KINF;
    C->r[1] = C->r[3] = -PN_KINF;
    C->D = -PN_KINF;
    C->l1 = 0.0f;
    C->m = pn_v3_make(0.0f, 0.0f, 0.0f);
    C->ok = 1;
    C->has_m = 0;
}

PN_KFN void pn_wg_cone_add(pn_wcone *C, const pn_klight *L, pn_v3 O, pn_v3 P, pn_v3 n)
{
    float u, v, h;
    pn_wg_light(L, O, &u, &v, &h);
    if (!(h > 0.0f)) C->ok = 0;
    C->r[0] = pn_kminf(C->r[0], u / h);
    C->r[1] = pn_kmaxf(C->r[1], u / h);
    C->r[2] = pn_kminf(C->r[2], v / h);
    C->r[3] = pn_kmaxf(C->r[3], v / h);
    C->l1 = pn_kmaxf(C->l1, pn_v3_l1(pn_v3_sub(pn_light_c(L), O)));
    if (!C->has_m) {
        C->m = pn_v3_dot(n, pn_v3_sub(pn_light_c(L), P)) < 0.0f ? n : pn_v3_scale(n, -1.0f);
        C->has_m = 1;
    }
    C->D = pn_kmaxf(C->D, pn_v3_dot(C->m, pn_v3_sub(O, pn_light_c(L))));
}

/* Plane q of fr: n . (X - c) <= d in world coordinates, n = A U / |U|^2 + B V / |V|^2 + C N
 * (a bound in light coordinates) or given; as a unit normal and an offset moved out by
 * fr->tol. */
PN_KFN void pn_wg_cone_plane(const pn_klight *L, pn_v3 n, float d, uint32_t q, pn_frustum *fr)
{
    float len = pn_ksqrt(pn_v3_dot(n, n));
    fr->n[q] = pn_v3_scale(n, 1.0f / len);
    fr->d[q] = pn_v3_dot(fr->n[q], pn_light_c(L)) + d / len + fr->tol;
}

PN_KFN pn_v3 pn_wg_light_dir(const pn_klight *L, float A, float B, float C)
{
    pn_v3 U = pn_light_U(L), V = pn_light_V(L), N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
    return pn_v3_add(pn_v3_add(pn_v3_scale(U, A * (1.0f / pn_v3_dot(U, U))), pn_v3_scale(V, B * (1.0f / pn_v3_dot(V, V)))),
                     pn_v3_scale(N, C));
}

PN_KFN int pn_wg_cone_frustum(const pn_wcone *C, const pn_klight *L, pn_frustum *fr)
{
    if (!C->ok || L->is_point || !(C->D >= 0.0f) || !(pn_v3_dot(C->m, C->m) > 0.0f) ||
        !(C->r[0] > -PN_KINF && C->r[1] < PN_KINF && C->r[2] > -PN_KINF && C->r[3] < PN_KINF))
        return 0;
    /* pn_frustum_make's slack, with the tile's farthest origin. */
    fr->tol = L->cull_tol + 1e-5f * (C->l1 + pn_v3_l1(pn_light_U(L)) + pn_v3_l1(pn_light_V(L)));
    fr->is_point = 0u;
    fr->seg_o = pn_light_c(L);
    fr->seg_d = pn_v3_make(0.0f, 0.0f, 0.0f);
    pn_wg_cone_plane(L, pn_wg_light_dir(L, 0.0f, 0.0f, -1.0f), 0.0f, 0u, fr);
    pn_wg_cone_plane(L, pn_wg_light_dir(L, -1.0f, 0.0f, C->r[0]), 0.0f, 1u, fr);
    pn_wg_cone_plane(L, pn_wg_light_dir(L, 1.0f, 0.0f, -C->r[1]), 0.0f, 2u, fr);
    pn_wg_cone_plane(L, pn_wg_light_dir(L, 0.0f, -1.0f, C->r[2]), 0.0f, 3u, fr);
    pn_wg_cone_plane(L, pn_wg_light_dir(L, 0.0f, 1.0f, -C->r[3]), 0.0f, 4u, fr);
    pn_wg_cone_plane(L, C->m, C->D, 5u, fr);
    return 1;
}

/* Whether no triangle of the BVH meets frustum fr (an area light's six planes): a walk
 * that drops the boxes pn_frustum_box4p drops and the triangles whose three vertices lie
 * beyond one plane, and stops at the first triangle it keeps. A full stack says no (the
 * walk would lose a subtree). */
PN_KFN int pn_wg_cone_clear(const pn_frustum *fr, PN_CONST float *tris, PN_CONST pn_kbvh4 *wnodes, PN_CONST uint32_t *tri_index)
{
    uint32_t stack[PN_BVH_STACK], sp = 0u, cur = 0u, c, q, a, bits;
    for (;;) {
        PN_CONST pn_kbvh4 *w = wnodes + cur;
        float blo[12], bhi[12];
        for (a = 0; a < 3u; a++)
            for (c = 0; c < 4u; c++) {
                blo[a * 4u + c] = w->lo[a][c];
                bhi[a * 4u + c] = w->hi[a][c];
            }
        bits = pn_frustum_box4p(fr, blo, bhi) & ((1u << w->n) - 1u);
        for (c = 0; c < 4u; c++) {
            if (!((bits >> c) & 1u)) continue;
            if (w->child[c] & PN_W4_LEAF) {
                uint32_t first, count = pn_w4_word_refs(w->child[c], &first), t;
                for (t = 0; t < count; t++) {
                    PN_CONST float *p = tris + (size_t)(tri_index[first + t] & PN_REF_TRI) * 9u;
                    pn_v3 v0 = pn_v3_make(p[0], p[1], p[2]), v1 = pn_v3_make(p[3], p[4], p[5]), v2 = pn_v3_make(p[6], p[7], p[8]);
                    int out = 0;
                    for (q = 0; q < 6u && !out; q++)
                        out = pn_v3_dot(fr->n[q], v0) > fr->d[q] && pn_v3_dot(fr->n[q], v1) > fr->d[q] &&
                              pn_v3_dot(fr->n[q], v2) > fr->d[q];
                    if (!out) return 0;
                }
            } else {
                if (sp == PN_BVH_STACK) return 0;
                stack[sp++] = w->child[c];
            }
        }
        if (sp == 0u) return 1;
        cur = stack[--sp];
    }
}

PN_KFN void pn_wg_tile_box(const pn_kview *v, const pn_klight *L, uint32_t tx, uint32_t ty, const pn_ksurf *S,
                           PN_CONST float *tris, PN_CONST pn_kbvh4 *wnodes, PN_CONST uint32_t *tri_index, uint32_t no_cull,
                           PN_GLOBAL float *box)
{
    float b[PN_WG_BOX];
    pn_frustum fr;
    uint32_t x, y, x1 = (tx + 1u) * PN_WG_TILE, y1 = (ty + 1u) * PN_WG_TILE, i;
    pn_wcone C;
    if (no_cull) { /* PN_WG_NO_CULL: a box no test of pn_wg_box_misses_ends passes, not clear */
        box[0] = box[2] = box[4] = -PN_KINF;
        box[1] = box[3] = box[5] = PN_KINF;
        box[PN_WG_CLEAR] = 0.0f;
        return;
    }
    b[0] = b[2] = b[4] = PN_KINF;
    b[1] = b[3] = b[5] = -PN_KINF;
    pn_wg_cone_init(&C);
    if (x1 > v->width) x1 = v->width;
    if (y1 > v->height) y1 = v->height;
    for (y = ty * PN_WG_TILE; y < y1; y++)
        for (x = tx * PN_WG_TILE; x < x1; x++) {
            size_t pix = (size_t)y * v->width + x;
            pn_v3 O, P, n;
            float u, vv, h;
            if (S->tri_id[pix] == PN_NO_PIXEL_TRIANGLE) continue;
            pn_surf_at(S, pix, &P, &n);
            if (!pn_shadow_origin(P, n, L, &O)) continue;
            pn_wg_light(L, O, &u, &vv, &h);
            b[0] = pn_kminf(b[0], u);
            b[1] = pn_kmaxf(b[1], u);
            b[2] = pn_kminf(b[2], vv);
            b[3] = pn_kmaxf(b[3], vv);
            b[4] = pn_kminf(b[4], h);
            b[5] = pn_kmaxf(b[5], h);
            pn_wg_cone_add(&C, L, O, P, n);
        }
    for (i = 0; i < 6u; i++) box[i] = b[i];
    box[PN_WG_CLEAR] = pn_wg_cone_frustum(&C, L, &fr) && pn_wg_cone_clear(&fr, tris, wnodes, tri_index) ? 1.0f : 0.0f;
}

/* Whether silhouette e is nothing to every shadow origin in box B: pn_wg_project returns 0
 * for each (so the tile need not list it; the same bytes as when it does).
 * - No origin: nothing to evaluate.
 * - The edge wholly below every origin's local near plane (h_e >= (1 - PN_WG_TNEAR) h_O at
 *   both ends): clipped away.
 * - The edge wholly between the light plane and every origin's near plane (0 <= h_e <=
 *   (1 - PN_WG_TNEAR) h_O: no clipping) and both ends projecting beyond one side of the
 *   light from every origin. For side x = sg (x: u or v; sg = +-1) the pixel's test of end
 *   e, (x_e - x_O) sg >= (1 - x_O sg) t_e with t_e = 1 - h_e / h_O, is, times h_O > 0,
 *       g = (sg x_e - 1) h_O + (1 - sg x_O) h_e >= 0,
 *   affine in (x_O, h_O); its least value over the box is at one corner.
 * Each comparison keeps a margin of 1e-3 of its terms' magnitudes, far above the rounding
 * of either side (a few float operations), so the pixel reaches the same decision. */
PN_KFN int pn_wg_box_misses_ends(PN_CONST float *B, float ua, float va, float ha, float ub, float vb, float hb)
{
    const float near = 1.0f - PN_WG_TNEAR;
    float h0 = B[4], h1 = B[5], hlo = pn_kminf(ha, hb), hhi = pn_kmaxf(ha, hb);
    uint32_t q;
    if (!(B[0] <= B[1])) return 1;
    if (!(h0 > 0.0f)) return 0;
    if (hlo >= near * h1 * 1.001f) return 1;
    if (!(hlo >= 0.0f && hhi <= near * h0 * 0.999f)) return 0;
    for (q = 0; q < 4u; q++) {
        float sg = (q & 1u) ? 1.0f : -1.0f, x0 = B[(q >> 1) * 2u], x1 = B[(q >> 1) * 2u + 1u];
        float xo = sg > 0.0f ? x1 : x0, xm = pn_kmaxf(pn_kfabs(x0), pn_kfabs(x1));
        float xa = q < 2u ? ua : va, xb = q < 2u ? ub : vb;
        float ca = sg * xa - 1.0f, cb = sg * xb - 1.0f;
        float ga = ca * (ca >= 0.0f ? h0 : h1) + (1.0f - sg * xo) * ha;
        float gb = cb * (cb >= 0.0f ? h0 : h1) + (1.0f - sg * xo) * hb;
        if (ga > 1e-3f * (pn_kfabs(xa) + xm + 1.0f) * h1 && gb > 1e-3f * (pn_kfabs(xb) + xm + 1.0f) * h1) return 1;
    }
    return 0;
}

PN_KFN int pn_wg_box_misses(PN_CONST float *B, PN_CONST pn_wsil *e)
{
    return pn_wg_box_misses_ends(B, e->ua, e->va, e->ha, e->ub, e->vb, e->hb);
}

/* ---- Binning ------------------------------------------------------------------------------ */

/* The tile rows [*ya, *yb) of band G (G->bx0 .. by1) that a wedge's tile box x0, y0, x1, y1
 * reaches, and the wedge's reach (edge h) with its hull into R; 0 when the box misses the
 * band (nothing built). Under G->no_cull every row of the band (R not built: pn_wg_band_row
 * then gives every column). */
PN_KFN_HOT int pn_wg_band_reach(const pn_kview *v, const pn_klight *L, const pn_kwg *G, PN_CONST float *tris, uint32_t h,
                            uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, pn_wreach *R, uint32_t *ya, uint32_t *yb)
{
    pn_v3 a, b;
    if (G->no_cull) { /* every tile of the band */
        *ya = G->by0;
        *yb = G->by1;
        return 1;
    }
    if (x0 > x1) return 0;
    *ya = y0 > G->by0 ? y0 : G->by0;
    *yb = y1 + 1u < G->by1 ? y1 + 1u : G->by1;
    if (*ya >= *yb || x0 >= G->bx1 || x1 < G->bx0) return 0;
    pn_wg_ends(tris, h, &a, &b);
    pn_wg_reach(v, L, G->hmax, a, b, 1, R);
    return 1;
}

/* The tile columns [*x0, *x1] of row y that reach R covers (pn_wg_row), within band G's. */
PN_KFN_HOT void pn_wg_band_row(const pn_kview *v, const pn_wreach *R, const pn_kwg *G, uint32_t y, uint32_t *x0, uint32_t *x1)
{
    if (G->no_cull) {
        *x0 = G->bx0;
        *x1 = G->bx1 - 1u;
        return;
    }
    pn_wg_row(v, R, y, x0, x1);
    if (*x0 < G->bx0) *x0 = G->bx0;
    if (*x1 + 1u > G->bx1) *x1 = G->bx1 - 1u;
}

/* Silhouette s's (tile, s) pairs in the band [K->wg.bx0, bx1) x [by0, by1) of tiles: those
 * its reach covers and whose box (pn_wg_box_misses) it does not miss, in ascending tile
 * order. Counted (mode PN_WG_BIN_COUNT: returns the count and, with G->count_rows, adds
 * each tile row's into pairs[row], atomically: the band planner's counts) or written from
 * `at` on (PN_WG_BIN_WRITE; want: the count). A count of at most PN_WG_KEEP tiles keeps them:
 * it takes room for them in scratch (a pool of cap words) from *cursor, atomically, and
 * writes them there, with their place into kept[0] and their count into kept[1] (0: not
 * kept); the write then copies them, the same pairs in the same order without the reach
 * and the tests again (a leaf's wedge covers a few dozen tiles: the tree's scatter was as
 * costly as its count). Where a silhouette's tiles land in scratch depends on the threads;
 * what it copies does not. Otherwise both build the same reach with the same arithmetic,
 * so they agree. */
#define PN_WG_BIN_COUNT 0
#define PN_WG_BIN_WRITE 1
#define PN_WG_KEEP 64u
PN_KFN uint32_t pn_wg_bin(const pn_kview *v, const pn_klight *L, const pn_kwg *G, PN_CONST float *tris, PN_CONST pn_wsil *sil,
                          PN_CONST float *tbox, uint32_t s, uint32_t at, uint32_t want, int mode, PN_GLOBAL uint32_t *pairs,
                          PN_GLOBAL uint32_t *kept, PN_GLOBAL uint32_t *scratch, PN_GLOBAL uint32_t *cursor, uint32_t cap)
{
    uint32_t tw = PN_WG_TILES(v->width), x, y, x0, x1, ya, yb, n = 0u, keep[PN_WG_KEEP], i;
    PN_CONST pn_wsil *e = sil + s;
    pn_wreach R;
    if (mode == PN_WG_BIN_WRITE && kept[1] == want) {
        PN_CONST uint32_t *k = scratch + kept[0];
        for (i = 0; i < want; i++) {
            pairs[2u * (at + i)] = k[i];
            pairs[2u * (at + i) + 1u] = s;
        }
        return want;
    }
    if (mode == PN_WG_BIN_COUNT) kept[1] = 0u;
    if (!pn_wg_band_reach(v, L, G, tris, e->h, e->x0, e->y0, e->x1, e->y1, &R, &ya, &yb)) return 0u;
    for (y = ya; y < yb; y++) {
        uint32_t n0 = n;
        pn_wg_band_row(v, &R, G, y, &x0, &x1);
        for (x = x0; x <= x1 && x0 <= x1; x++) {
            if (pn_wg_box_misses(tbox + (size_t)(y * tw + x) * PN_WG_BOX, e)) continue;
            if (mode == PN_WG_BIN_WRITE) {
                pairs[2u * (at + n)] = y * tw + x;
                pairs[2u * (at + n) + 1u] = s;
            } else if (n < PN_WG_KEEP) {
                keep[n] = y * tw + x;
            }
            n++;
        }
        if (mode == PN_WG_BIN_COUNT && G->count_rows && n > n0) pn_katomic_add(&pairs[y], n - n0);
    }
    if (mode == PN_WG_BIN_COUNT && n > 0u && n <= PN_WG_KEEP) {
        uint32_t at0 = pn_katomic_add(cursor, n);
        if (at0 <= cap && n <= cap - at0) {
            for (i = 0; i < n; i++) scratch[at0 + i] = keep[i];
            kept[0] = at0;
            kept[1] = n;
        }
    }
    return n;
}

/* Silhouette e's (a record of pn_wg_sil_rec's) (tile, e) pairs in the tiles [G->bx0, bx1)
 * x [by0, by1): pn_wg_bin's count over them, the same reach and tests. Without counts (0),
 * 1 at the first: a band of silhouettes keeps these, every silhouette a tile of the band
 * lists. With counts, one added to each such tile's, atomically, and their number
 * returned: every tile's list length, which the frame checks against its pools before it
 * shades a band. The hull only for a box that reaches the band (most do not). */
PN_KFN uint32_t pn_wg_sil_tiles(const pn_kview *v, const pn_klight *L, const pn_kwg *G, PN_CONST float *tris,
                                PN_CONST float *tbox, const pn_wsil *e, PN_GLOBAL uint32_t *counts)
{
    uint32_t tw = PN_WG_TILES(v->width), x, y, x0, x1, ya, yb, n = 0u;
    pn_wreach R;
    if (!pn_wg_band_reach(v, L, G, tris, e->h, e->x0, e->y0, e->x1, e->y1, &R, &ya, &yb)) return 0u;
    for (y = ya; y < yb; y++) {
        pn_wg_band_row(v, &R, G, y, &x0, &x1);
        for (x = x0; x <= x1 && x0 <= x1; x++) {
            if (pn_wg_box_misses_ends(tbox + (size_t)(y * tw + x) * PN_WG_BOX, e->ua, e->va, e->ha, e->ub, e->vb, e->hb))
                continue;
            if (!counts) return 1u;
            (void)pn_katomic_add(&counts[y * tw + x], 1u);
            n++;
        }
    }
    return n;
}

/* Tile list[lo, hi) (ascending silhouettes, so grouped by object): for each run start i
 * (a run: silhouettes of one object and one block, PN_WG_BLOCK), next[2 i] = the end of
 * its run and next[2 i + 1] = the end of its object's. */
PN_KFN void pn_wg_runs(PN_CONST pn_wsil *sil, PN_CONST uint32_t *list, uint32_t lo, uint32_t hi, PN_GLOBAL uint32_t *next)
{
    uint32_t o = lo, i, j, oe;
    while (o < hi) {
        uint32_t c = sil[list[o]].comp;
        for (oe = o + 1u; oe < hi && sil[list[oe]].comp == c; oe++) {
        }
        for (i = o; i < oe; i = j) {
            uint32_t k = list[i] / PN_WG_BLOCK;
            for (j = i + 1u; j < oe && list[j] / PN_WG_BLOCK == k; j++) {
            }
            next[2u * (size_t)i] = j;
            next[2u * (size_t)i + 1u] = oe;
        }
        o = oe;
    }
}

/* The first i in [lo, hi) with list[i] >= v (list ascending), else hi. */
PN_KFN uint32_t pn_wg_lower_bound(PN_CONST uint32_t *list, uint32_t lo, uint32_t hi, uint32_t v)
{
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2u;
        if (list[mid] < v)
            lo = mid + 1u;
        else
            hi = mid;
    }
    return lo;
}

/* ---- Per pixel ----------------------------------------------------------------------------- */

/* A box in a quadrant's frame; empty when x0 > x1. */
typedef struct pn_wbox {
    float x0, y0, x1, y1;
} pn_wbox;

PN_KFN pn_wbox pn_wbox_empty(void)
{
    pn_wbox b;
    b.x0 = 2.0f;
    b.y0 = 2.0f;
    b.x1 = -1.0f;
    b.y1 = -1.0f;
    return b;
}

PN_KFN pn_wbox pn_wbox_full(void)
{
    pn_wbox b;
    b.x0 = 0.0f;
    b.y0 = 0.0f;
    b.x1 = 1.0f;
    b.y1 = 1.0f;
    return b;
}

PN_KFN void pn_wbox_add(pn_wbox *b, float x, float y)
{
    b->x0 = pn_kminf(b->x0, x);
    b->y0 = pn_kminf(b->y0, y);
    b->x1 = pn_kmaxf(b->x1, x);
    b->y1 = pn_kmaxf(b->y1, y);
}

PN_KFN pn_wbox pn_wbox_union(pn_wbox a, pn_wbox b)
{
    if (a.x0 > a.x1) return b;
    if (b.x0 > b.x1) return a;
    pn_wbox_add(&a, b.x0, b.y0);
    pn_wbox_add(&a, b.x1, b.y1);
    return a;
}

PN_KFN float pn_wbox_area(pn_wbox b) { return b.x0 > b.x1 ? 0.0f : (b.x1 - b.x0) * (b.y1 - b.y0); }

PN_KFN float pn_wbox_overlap(pn_wbox a, pn_wbox b)
{
    float w = pn_kminf(a.x1, b.x1) - pn_kmaxf(a.x0, b.x0), h = pn_kminf(a.y1, b.y1) - pn_kmaxf(a.y0, b.y0);
    if (a.x0 > a.x1 || b.x0 > b.x1 || !(w > 0.0f) || !(h > 0.0f)) return 0.0f;
    return w * h;
}

/* One object's state in one quadrant while its edges are summed. */
typedef struct pn_wpart {
    float a;      /* signed occluded area so far (the quadrant's area is 1) */
    pn_wbox box;  /* box of its edges' end points (clipped to the quadrant) */
    float f0, fc; /* its count at the centre; the signed weights of its edges crossing the
                     segment from the centre to the far corner (1, 1) */
} pn_wpart;

/* The boundary parameter of a point on Q's far boundary (x = 1 or y = 1): 0 at (1, 0),
 * 1 at the corner, 2 at (0, 1); increasing with the angle from the centre. */
PN_KFN float pn_wg_bparam(float x, float y) { return x >= y ? y : 2.0f - x; }

/* Clips segment p q to Q = [0, 1]^2 (Liang and Barsky); 0 when nothing is left. An end
 * the clip does not move is kept as it is (most projected edges lie inside Q: no division). */
PN_KFN int pn_wg_clip(float *px, float *py, float *qx, float *qy)
{
    float t0 = 0.0f, t1 = 1.0f, dx = *qx - *px, dy = *qy - *py, pk[4], qk[4], x0, y0;
    uint32_t i;
    if ((*px >= 0.0f) & (*px <= 1.0f) & (*py >= 0.0f) & (*py <= 1.0f) & (*qx >= 0.0f) & (*qx <= 1.0f) & (*qy >= 0.0f) &
        (*qy <= 1.0f))
        return 1;
    /* Both ends beyond a far side (the ends below 0 on an axis pn_wg_edge_parts leaves
     * out): nothing left. */
    if ((*px > 1.0f && *qx > 1.0f) || (*py > 1.0f && *qy > 1.0f)) return 0;
    pk[0] = -dx;
    qk[0] = *px;
    pk[1] = dx;
    qk[1] = 1.0f - *px;
    pk[2] = -dy;
    qk[2] = *py;
    pk[3] = dy;
    qk[3] = 1.0f - *py;
    for (i = 0; i < 4u; i++) {
        if (pk[i] == 0.0f) {
            if (qk[i] < 0.0f) return 0;
            continue;
        }
        /* p inside this side, entering it (r <= 0), or q inside it, leaving (r >= 1): the
         * bound would not move; no division. */
        if (pk[i] < 0.0f ? qk[i] >= 0.0f : qk[i] >= pk[i]) continue;
        {
            float r = qk[i] / pk[i];
            if (pk[i] < 0.0f)
                t0 = pn_kmaxf(t0, r);
            else
                t1 = pn_kminf(t1, r);
        }
    }
    if (!(t0 <= t1)) return 0;
    x0 = *px;
    y0 = *py;
    if (t0 > 0.0f) {
        *px = pn_kminf(pn_kmaxf(x0 + t0 * dx, 0.0f), 1.0f);
        *py = pn_kminf(pn_kmaxf(y0 + t0 * dy, 0.0f), 1.0f);
    }
    if (t1 < 1.0f) {
        *qx = pn_kminf(pn_kmaxf(x0 + t1 * dx, 0.0f), 1.0f);
        *qy = pn_kminf(pn_kmaxf(y0 + t1 * dy, 0.0f), 1.0f);
    }
    return 1;
}

/* Edge p q (in Q's frame) with sign sg (+1 outer, -1 inner) and weight w into part P.
 * Returns 1 when it covers a non-zero area of the quadrant. */
PN_KFN int pn_wg_part_edge(pn_wpart *P, float px, float py, float qx, float qy, float sg, float w)
{
    float cr, mp, mq, Px, Py, Qx, Qy, cone, area, sp, sq;
    int kin;
    if (!pn_wg_clip(&px, &py, &qx, &qy)) return 0;
    cr = px * qy - py * qx;
    if (cr == 0.0f) return 0; /* seen edge-on from the centre */
    if (cr < 0.0f) {          /* p at the smaller angle */
        float tx = px, ty = py;
        px = qx;
        py = qy;
        qx = tx;
        qy = ty;
        cr = -cr;
    }
    mp = pn_kmaxf(px, py);
    mq = pn_kmaxf(qx, qy);
    if (!(mp > 0.0f && mq > 0.0f)) return 0;
    /* The larger coordinate over itself is 1: one division a point (the same bits). */
    Px = px >= py ? 1.0f : px / mp;
    Py = py >= px ? 1.0f : py / mp;
    Qx = qx >= qy ? 1.0f : qx / mq;
    Qy = qy >= qx ? 1.0f : qy / mq;
    sp = pn_wg_bparam(Px, Py);
    sq = pn_wg_bparam(Qx, Qy);
    kin = sp < 1.0f && sq > 1.0f; /* the corner (1, 1) strictly inside the angle */
    cone = kin ? 0.5f * ((Px - Py) + (Qy - Qx)) : 0.5f * (Px * Qy - Py * Qx);
    area = pn_kmaxf(cone - 0.5f * cr, 0.0f);
    if (!(area > 0.0f)) return 0;
    P->a += sg * w * area;
    pn_wbox_add(&P->box, px, py);
    pn_wbox_add(&P->box, qx, qy);
    if (kin) P->fc += sg * w;
    return 1;
}

/* One object's occluded area (clamped to [0, 1]) and box in a quadrant. The occluded
 * region is bounded by its edges and by the quadrant's sides: its box is its edges' end
 * points', with the centre when the centre is occluded and the far corner when that is
 * (the count there, f0 + fc, positive); a side's other corners, (1, 0) and (0, 1), lie in
 * the box of the end points on the sides they join whenever the region reaches them. */
PN_KFN float pn_wg_part_end(const pn_wpart *P, pn_wbox *B)
{
    float a = pn_kminf(pn_kmaxf(P->a, 0.0f), 1.0f);
    pn_wbox b = P->box;
    if (P->f0 > 0.0f) pn_wbox_add(&b, 0.0f, 0.0f);
    if (P->f0 + P->fc > 0.0f) pn_wbox_add(&b, 1.0f, 1.0f);
    if (a > 0.0f && !(pn_wbox_area(b) > 0.0f)) b = pn_wbox_full(); /* rounding: keep it a bound */
    *B = b;
    return a;
}

/* The blend of an object's (as, bs) into the final (af, bf) of a quadrant. */
PN_KFN void pn_wg_blend(uint32_t mode, float as, pn_wbox bs, float *af, pn_wbox *bf)
{
    float ba, bb, ov, e;
    if (!(as > 0.0f)) return;
    if (mode == PN_WG_M_ADD || !(*af > 0.0f)) {
        *af += as;
        *bf = pn_wbox_union(*bf, bs);
        return;
    }
    ba = pn_wbox_area(*bf);
    bb = pn_wbox_area(bs);
    ov = pn_wbox_overlap(*bf, bs);
    e = (ba > 0.0f && bb > 0.0f) ? pn_kminf(*af / ba, 1.0f) * pn_kminf(as / bb, 1.0f) * ov : 0.0f;
    *af += as - e;
    *bf = pn_wbox_union(*bf, bs);
}

/* Per-pixel light frame: O in light coordinates, 1 / its height, O - c. */
typedef struct pn_wframe {
    float uo, vo, ho, iho;
    pn_v3 oc;
    float cu[2], cv[2], au, av; /* pn_wg_obj_misses': 1 -+ uo, 1 -+ vo, |uo| + 1, |vo| + 1 */
} pn_wframe;

/* The frame of shadow origin O: what pn_wg_project and pn_wg_obj_misses read of it. */
PN_KFN void pn_wg_frame(const pn_klight *L, pn_v3 O, pn_wframe *F)
{
    pn_wg_light(L, O, &F->uo, &F->vo, &F->ho);
    F->iho = 1.0f / F->ho;
    F->oc = pn_v3_sub(O, pn_light_c(L));
    F->cu[0] = 1.0f + F->uo;
    F->cu[1] = 1.0f - F->uo;
    F->cv[0] = 1.0f + F->vo;
    F->cv[1] = 1.0f - F->vo;
    F->au = pn_kfabs(F->uo) + 1.0f;
    F->av = pn_kfabs(F->vo) + 1.0f;
}

/* Silhouette e seen from O: its projection p q onto the light (p[0..3] = pu, pv, qu, qv)
 * and sign (+1 outer, -1 inner); 0 when it misses the light. */
PN_KFN int pn_wg_project(const pn_wframe *F, PN_CONST pn_wsil *e, float *p, float *sgn)
{
    float ta = 1.0f - e->ha * F->iho, tb = 1.0f - e->hb * F->iho, ua = e->ua, va = e->va, ub = e->ub, vb = e->vb;
    float l0 = 0.0f, l1 = 1.0f, dt = tb - ta, t0 = ta, t1 = tb, pu, pv, qu, qv, sg, ra, rb;
    /* The local near plane and the light plane: keep t in [PN_WG_TNEAR, 1] (most edges lie
     * wholly between them: no clipping). */
    if (!(ta >= PN_WG_TNEAR && tb >= PN_WG_TNEAR && ta <= 1.0f && tb <= 1.0f)) {
        if (dt != 0.0f) {
            float la = (PN_WG_TNEAR - ta) / dt, lb = (1.0f - ta) / dt;
            if (dt > 0.0f) {
                l0 = pn_kmaxf(l0, la);
                l1 = pn_kminf(l1, lb);
            } else {
                l0 = pn_kmaxf(l0, lb);
                l1 = pn_kminf(l1, la);
            }
        } else {
            return 0; /* parallel to the light, outside the slab */
        }
        if (!(l0 < l1)) return 0;
        t0 = pn_kmaxf(ta + l0 * dt, PN_WG_TNEAR);
        t1 = pn_kmaxf(ta + l1 * dt, PN_WG_TNEAR);
        ub = ua + l1 * (ub - ua);
        vb = va + l1 * (vb - va);
        ua = ua + l0 * (e->ub - ua);
        va = va + l0 * (e->vb - va);
    }
    {
        /* Most edges project beside the light: decide that without dividing, pu <= -1 being
         * ua - uo <= (-1 - uo) t0 for t0 > 0 (and so on). */
        float nua = ua - F->uo, nva = va - F->vo, nub = ub - F->uo, nvb = vb - F->vo;
        if ((nua <= (-1.0f - F->uo) * t0 && nub <= (-1.0f - F->uo) * t1) ||
            (nua >= (1.0f - F->uo) * t0 && nub >= (1.0f - F->uo) * t1) ||
            (nva <= (-1.0f - F->vo) * t0 && nvb <= (-1.0f - F->vo) * t1) ||
            (nva >= (1.0f - F->vo) * t0 && nvb >= (1.0f - F->vo) * t1))
            return 0;
        ra = 1.0f / t0;
        rb = 1.0f / t1;
        pu = F->uo + nua * ra;
        pv = F->vo + nva * ra;
        qu = F->uo + nub * rb;
        qv = F->vo + nvb * rb;
    }
    {
        /* The line through p q passes beside the light, its four corners (+-1, +-1) strictly
         * on one side: |(q - p) x p| > |qu - pu| + |qv - pv|, with a margin that dwarfs
         * the rounding of both sides (the clip then finds nothing in any quadrant). */
        float du = qu - pu, dv = qv - pv, g = dv * pu - du * pv;
        if (pn_kfabs(g) > (pn_kfabs(du) + pn_kfabs(dv)) * 1.0001f + 1e-4f * (pn_kfabs(dv * pu) + pn_kfabs(du * pv)))
            return 0;
    }
    /* Inner when O lies on the casting triangles' side of the plane through the centre and
     * the edge: the same sign det(a - c, b - c, v - c) < 0 their third vertex v gives. */
    sg = (e->nx * F->oc.x + e->ny * F->oc.y) + e->nz * F->oc.z < 0.0f ? -1.0f : 1.0f;
    p[0] = pu;
    p[1] = pv;
    p[2] = qu;
    p[3] = qv;
    *sgn = sg;
    return 1;
}

/* Whether pn_wg_project returns 0 from F for every silhouette of an object whose end
 * points lie in box ob (pn_wsil.ob): every end below F's local near plane, or every end
 * between the light plane and it and beyond one side of the light, the test of
 * pn_wg_box_misses with the box on the edges' side (g is affine in (x_e, h_e) too), with
 * the same margins. */
/* Side x = sg of the light (x: u or v, xo the origin's, [x0, x1] the box's): every end
 * in the box projects beyond it. Written for a constant sg, called with each (the
 * compiler folds it: this is the hottest test of a frame of small objects). */
PN_KFN int pn_wg_side_misses(float sg, float co, float ao, float x0, float x1, float xm, float h0, float h1, float ho)
{
    float xe = sg > 0.0f ? x0 : x1, he = co >= 0.0f ? h0 : h1;
    float g = (sg * xe - 1.0f) * ho + co * he;
    return g > 1e-3f * (xm + ao) * ho;
}

/* mu, mv: max(|u0|, |u1|) and max(|v0|, |v1|) of box ob (pn_wsil.ob holds its own). */
PN_KFN_HOT int pn_wg_obj_misses(const pn_wframe *F, PN_CONST float *ob, float mu, float mv)
{
    const float near = 1.0f - PN_WG_TNEAR;
    float ho = F->ho, h0 = ob[4], h1 = ob[5];
    if (h0 >= near * ho * 1.001f) return 1;
    if (!(h0 >= 0.0f && h1 <= near * ho * 0.999f)) return 0;
    return pn_wg_side_misses(-1.0f, F->cu[0], F->au, ob[0], ob[1], mu, h0, h1, ho) ||
           pn_wg_side_misses(1.0f, F->cu[1], F->au, ob[0], ob[1], mu, h0, h1, ho) ||
           pn_wg_side_misses(-1.0f, F->cv[0], F->av, ob[2], ob[3], mv, h0, h1, ho) ||
           pn_wg_side_misses(1.0f, F->cv[1], F->av, ob[2], ob[3], mv, h0, h1, ho);
}

/* The same for a block's box (six floats, no margins stored). */
PN_KFN int pn_wg_box6_misses(const pn_wframe *F, PN_CONST float *b)
{
    return pn_wg_obj_misses(F, b, pn_kmaxf(pn_kfabs(b[0]), pn_kfabs(b[1])), pn_kmaxf(pn_kfabs(b[2]), pn_kfabs(b[3])));
}

/* A projected edge (pn_wg_project) of weight w into the object's four parts. Returns 1
 * when it covers some of the light. */
PN_KFN int pn_wg_edge_parts(const float *p, float sg, float w, pn_wpart *parts)
{
    /* Both ends beside a quadrant on one axis: the clip would leave nothing, or a piece on
     * that axis, seen edge-on from the centre (pn_wg_part_edge returns 0). Quadrant q
     * mirrors x when q is 1 or 2 and y when q is 2 or 3. */
    int xn = p[0] < 0.0f && p[2] < 0.0f, xp = p[0] > 0.0f && p[2] > 0.0f;
    int yn = p[1] < 0.0f && p[3] < 0.0f, yp = p[1] > 0.0f && p[3] > 0.0f, any = 0;
    if (!xn && !yn) any |= pn_wg_part_edge(parts, p[0], p[1], p[2], p[3], sg, w);
    if (!xp && !yn) any |= pn_wg_part_edge(parts + 1, -p[0], p[1], -p[2], p[3], sg, w);
    if (!xp && !yp) any |= pn_wg_part_edge(parts + 2, -p[0], -p[1], -p[2], -p[3], sg, w);
    if (!xn && !yp) any |= pn_wg_part_edge(parts + 3, p[0], -p[1], p[2], -p[3], sg, w);
    return any;
}

/* An object's four parts before its first edge: its count at the centre a0 times the
 * quadrant (0 when the centre is seen). */
PN_KFN void pn_wg_parts_init(pn_wpart *parts, float a0)
{
    uint32_t q;
    for (q = 0; q < 4u; q++) {
        parts[q].a = a0;
        parts[q].box = pn_wbox_empty();
        parts[q].f0 = a0;
        parts[q].fc = 0.0f;
    }
}

/* Whether object s has an edge in list[lo, hi) (ascending edges, so ascending objects). */
PN_KFN int pn_wg_listed(PN_CONST pn_wsil *sil, PN_CONST uint32_t *list, uint32_t lo, uint32_t hi, uint32_t s)
{
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2u, c = sil[list[mid]].comp;
        if (c == s) return 1;
        if (c < s)
            lo = mid + 1u;
        else
            hi = mid;
    }
    return 0;
}

/* The place of v in set[0, *n) (at most PN_WG_HARD_MAX entries), v added at the end when
 * absent; PN_WG_HARD_MAX when absent from a full set. */
PN_KFN uint32_t pn_wg_place(uint32_t *set, uint32_t *n, uint32_t v)
{
    uint32_t i;
    for (i = 0; i < *n && set[i] != v; i++) {
    }
    if (i == *n) {
        if (*n == PN_WG_HARD_MAX) return PN_WG_HARD_MAX;
        set[(*n)++] = v;
    }
    return i;
}

/* Visibility of one lit pixel (shadow origin O, own triangle own, tile edges list[lo, hi),
 * their objects' runs next: pn_wg_runs).
 * PN_WG_EXACT for a receiver in its own object's self-shadow penumbra (its object hides
 * the centre and has an edge reaching the light), unless O lies inside its own solid: the
 * centre segment leaves the solid through more of its triangles than it enters it by
 * (distinct ones; a watertight solid: one more from inside, as many from outside). There
 * no sample sees the light (every segment from O must leave the solid; the samples on the
 * other side of the own triangle are below the horizon): 0, without the fallback. That is
 * where a solid's face turns from the light centre (O is pushed eps to the centre's side,
 * into the solid), the dark side of every closed object, whose terminator band took the
 * fallback before; one pushed through a solid thinner than eps (a modelled leaf) lies
 * outside, and its segment enters the solid as often as it leaves it, if it meets it.
 * Counters: candidates = edges evaluated, blocking = edges covering some of the light,
 * nodes = blockers of the centre ray, capped = more objects (or casting triangles) than
 * PN_WG_HARD_MAX listed in the tile block the centre (more than the pixel keeps track of:
 * PN_WG_EXACT, the exact fallback; reported as pn_stats.wedges.hard_overflow), overflow =
 * the centre ray's walk lost a stack entry (a broken invariant: pn_bvh_fold bounds the
 * stack). */
PN_KFN float pn_wg_pixel(pn_v3 O, uint32_t own, const pn_klight *L, uint32_t mode, PN_CONST float *tris,
                         PN_CONST pn_kbvh4 *wnodes, PN_CONST uint32_t *tri_index,
                         PN_CONST uint32_t *tcomp, PN_CONST uint32_t *tcast,
                         PN_CONST pn_wsil *sil, uint32_t nsil, PN_CONST float *bbox, PN_CONST float *sbox,
                         PN_CONST uint32_t *list, PN_CONST uint32_t *next, uint32_t lo, uint32_t hi, int clear,
                         pn_shadow_counters *cnt)
{
    uint32_t hard[PN_WG_HARD_MAX], hn[PN_WG_HARD_MAX], htri[PN_WG_HARD_MAX], nhard = 0u, ntri = 0u, t, i, q;
    uint32_t kb = PN_WG_ANY, hc = 0u, so = tcomp[own] & PN_WG_OBJ, ent[PN_WG_HARD_MAX], nent = 0u;
    int kmiss = 0, inside = (tcomp[own] & PN_WG_CLOSED) != 0u;
    float af[4];
    pn_wbox bf[4];
    pn_klight Lc = *L;
    pn_ray_origin X;
    pn_ray R;
    pn_ray_walk W;
    pn_wframe F;
    float occ;

    /* The centre: which objects block it (exactly); none in a tile whose cone is clear
     * (pn_wg_cone_clear: no triangle meets any of its centre segments). */
    Lc.k = 1u;
    if (!clear) {
        pn_tri_block_origin(O, &Lc, wnodes, &X);
        pn_ray_root(&X);
        pn_ray_make(&X, &Lc, 0, 0, &R);
        pn_ray_walk_begin(&W, &X, &R, wnodes);
    }
    while (!clear) {
        pn_shadow_counters rc = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
        uint32_t s, j, m;
        t = pn_ray_walk_next(&W, &R, own, tris, wnodes, tri_index, &Lc, &rc);
        cnt->overflow += rc.overflow;
        if (t == PN_RAY_NONE) break;
        cnt->nodes++;
        s = tcomp[t] & PN_WG_OBJ;
        /* An object whose wedges do not reach this tile covers the whole light. */
        if (L->is_point || !pn_wg_listed(sil, list, lo, hi, s)) return 0.0f;
        m = nhard;
        if ((j = pn_wg_place(hard, &nhard, s)) == PN_WG_HARD_MAX) {
            cnt->capped++;
            return PN_WG_EXACT;
        }
        if (nhard > m) hn[j] = 0u;
        if ((tcast[t] & PN_WG_CAST_CODE) != PN_WG_CAST_NONE) {
            m = ntri;
            if (pn_wg_place(htri, &ntri, t) == PN_WG_HARD_MAX) {
                cnt->capped++;
                return PN_WG_EXACT;
            }
            hn[j] += ntri - m;
        } else if (inside && s == so && !(tcomp[t] & PN_WG_DUP)) {
            if (pn_wg_place(ent, &nent, t) == PN_WG_HARD_MAX) inside = 0;
        }
    }
    /* O inside its own solid (the segment leaves it more often than it enters): no light.
     * The entries are the own solid's triangles that face away from the centre (casting
     * none), the exits its casting ones (hn); a segment crossing more than
     * PN_WG_HARD_MAX of them decides nothing here. Asked only where a walk ran: without
     * the !clear, PoCL 3.1's inliner laid out the program's other kernels differently and
     * ran the reference's pixel pass 1.5x slower (docs/wedges-time.md). */
    if (inside && !clear) {
        for (i = 0; i < nhard && hard[i] != so; i++) {
        }
        if (i < nhard && hn[i] > nent) return 0.0f;
    }
    if (L->is_point) return 1.0f;
    /* The blockers in ascending order (insertion sort, at most PN_WG_HARD_MAX): the list
     * visits objects in ascending order, so one cursor (hc) finds each in turn. */
    for (i = 1u; i < nhard; i++) {
        uint32_t hs = hard[i], hk = hn[i], m = i;
        for (; m > 0u && hard[m - 1u] > hs; m--) {
            hard[m] = hard[m - 1u];
            hn[m] = hn[m - 1u];
        }
        hard[m] = hs;
        hn[m] = hk;
    }

    pn_wg_frame(L, O, &F);
    for (q = 0; q < 4u; q++) {
        af[q] = 0.0f;
        bf[q] = pn_wbox_empty();
    }
    i = lo;
    while (i < hi) {
        PN_CONST pn_wsil *e0 = sil + list[i];
        uint32_t s = e0->comp, o0, oend, k = list[i] / PN_WG_SBLOCK;
        int h = 0, started = 0;
        float a0 = 0.0f;
        pn_wpart parts[4];
        /* Each superblock of the list once (they ascend with it), at an object's start: when
         * none of its edges reaches the light and none of its objects hides the centre, its
         * entries add nothing. The next entry past it starts a block, so a run: an object
         * cut there goes on as one, whose skipped edges added nothing. */
        if (k != kb) {
            kb = k;
            kmiss = pn_wg_box6_misses(&F, sbox + (size_t)k * 6u);
            if (kmiss && hc < nhard) { /* objects before c0 are behind the list's cursor */
                uint32_t c0 = sil[k * PN_WG_SBLOCK].comp;
                uint32_t c1 = sil[((k + 1u) * PN_WG_SBLOCK < nsil ? (k + 1u) * PN_WG_SBLOCK : nsil) - 1u].comp;
                while (hc < nhard && hard[hc] < c0) hc++;
                kmiss = hc == nhard || hard[hc] > c1;
            }
        }
        if (kmiss) {
            i = pn_wg_lower_bound(list, i, hi, (k + 1u) * PN_WG_SBLOCK);
            continue;
        }
        while (hc < nhard && hard[hc] < s) hc++;
        if (hc < nhard && hard[hc] == s) {
            h = 1;
            a0 = hn[hc] > 1u ? (float)hn[hc] : 1.0f;
        }
        if (!h && pn_wg_obj_misses(&F, e0->ob, e0->ob[6], e0->ob[7])) { /* none of its edges reaches the light */
            i = next[2u * (size_t)i + 1u];
            continue;
        }
        for (o0 = i, oend = next[2u * (size_t)i + 1u]; i < oend;) {
            uint32_t end = next[2u * (size_t)i];
            /* A run of a block none of whose edges reaches the light: nothing to add (not
             * asked of an object that is one run and passed its own box's test). */
            if (end - i >= PN_WG_BLOCK_RUN && (h || i != o0 || end != oend) &&
                pn_wg_box6_misses(&F, bbox + (size_t)(list[i] / PN_WG_BLOCK) * 6u)) {
                i = end;
                continue;
            }
            for (; i < end; i++) {
                PN_CONST pn_wsil *e = sil + list[i];
                float p[4], sg;
                cnt->candidates++;
                if (!pn_wg_project(&F, e, p, &sg)) continue;
                if (!started) {
                    pn_wg_parts_init(parts, a0);
                    started = 1;
                }
                if (pn_wg_edge_parts(p, sg, (float)e->w, parts)) cnt->blocking++;
            }
        }
        /* An object none of whose edges reaches the light from here: nothing to add when
         * its centre is seen, all of the light when it is blocked (as for an object whose
         * wedges no tile lists; so a tile need not list an edge that reaches no pixel of
         * it: pn_wg_box_misses). */
        if (!started) {
            if (h) return 0.0f;
            continue;
        }
        /* The receiver's own object hides the centre and its edges reach the light: a
         * self-shadow's penumbra, where the centre's silhouettes stand least for what the
         * receiver sees (they face the centre, and many are seen edge-on or from behind
         * from a point on the surface): the frame resolves it exactly. */
        if (h && s == (tcomp[own] & PN_WG_OBJ)) return PN_WG_EXACT;
        for (q = 0; q < 4u; q++) {
            pn_wbox bs;
            float as = pn_wg_part_end(parts + q, &bs);
            pn_wg_blend(mode, as, bs, af + q, bf + q);
        }
    }
    occ = (pn_kminf(af[0], 1.0f) + pn_kminf(af[1], 1.0f)) + (pn_kminf(af[2], 1.0f) + pn_kminf(af[3], 1.0f));
    return pn_kminf(pn_kmaxf(1.0f - 0.25f * occ, 0.0f), 1.0f);
}

#endif
