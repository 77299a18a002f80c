/* pn_gears.h - GEARS (Wang, Wang, Shi, Popescu 2014): per-pixel potentially blocking
 * triangles from a light-aligned grid, then the shared predicate's masks ORed per pixel.
 *
 * Grid camera C (paper §4, A.1): image plane parallel to the light, axes along U and V,
 * eye on the line from the centre of the box of shadow-ray origins and light corners to
 * the light centre, one light diagonal behind the light; near plane the light plane, far
 * plane through the farthest box corner. A point X projects to
 *   g(X) = ((X - E).U^ / (X - E).N, (X - E).V^ / (X - E).N),
 * a central projection onto a plane parallel to the light.
 *
 * Conservativeness (paper Appendix A): if triangle T blocks a segment O -> S, with S on
 * the light and B on T, then O lies on the ray from S through B beyond B, so g(O) lies on
 * the segment from g(B) to the far-plane point F_B of line SB, which the proof shows is in
 * the 2-D AABB of g(B_i) and the 12 far-plane points F_ij of lines L_j B_i. Three things
 * make that hold for our predicate too:
 *   - the predicate is exact (pn_predicate.h): it blocks a sample only if the exact segment
 *     from O to the exact sample point meets the closed triangle, so the argument above
 *     applies to the real triangle as it stands; no margin for a crossing tolerance;
 *   - a triangle with a vertex within a band of 1e-3 of the light-to-far-plane height of
 *     the light plane, on either side, or crossing it, has extrusions that run off toward
 *     infinity: it gets the whole grid (never dropped); only triangles wholly behind the
 *     band are skipped. The band covers the rounding of the float light normal N (the
 *     exact light plane is spanned by U and V);
 *   - the box is widened by PN_GEARS_SLACK of the grid's extent, far above the relative
 *     rounding of the projections (~1e-6); fuzz/ checks the containment against the exact
 *     predicate.
 * A point light (paper §5.2) has no extrusion: C sits at the light and the triangle's own
 * projection bounds its shadow. Pixels whose origins are behind C's image plane cannot be
 * seen by one planar camera; the host then uses the six faces of a cube around the light,
 * each a grid of its own. */
#ifndef PN_GEARS_H
#define PN_GEARS_H

#include "pn_predicate.h"

#define PN_GEARS_SLACK 1e-4f
#define PN_CELL_NONE 0xFFFFFFFFu

/* Grid camera of one face, derived on the host. */
typedef struct pn_kgrid {
    float eye[3];
    float ax[3], ay[3], az[3]; /* image axes and viewing axis (unit) */
    float far_depth;           /* depth of the far plane along az */
    float near_depth;          /* depth below which projections are not trusted */
    float gx0, gy0;            /* grid origin (projected coordinates) */
    float inv_cell_x, inv_cell_y;
    uint32_t res_x, res_y;     /* cells per axis */
    uint32_t face;             /* face index (0 for an area light) */
    uint32_t is_point;
} pn_kgrid;

PN_KFN float pn_grid_depth(const pn_kgrid *g, pn_v3 X)
{
    pn_v3 d = pn_v3_sub(X, pn_v3_make(g->eye[0], g->eye[1], g->eye[2]));
    return pn_v3_dot(d, pn_v3_make(g->az[0], g->az[1], g->az[2]));
}

/* Projected coordinates of X (depth > 0 assumed). */
PN_KFN void pn_grid_project(const pn_kgrid *g, pn_v3 X, float *px, float *py)
{
    pn_v3 d = pn_v3_sub(X, pn_v3_make(g->eye[0], g->eye[1], g->eye[2]));
    float z = pn_v3_dot(d, pn_v3_make(g->az[0], g->az[1], g->az[2]));
    *px = pn_v3_dot(d, pn_v3_make(g->ax[0], g->ax[1], g->ax[2])) / z;
    *py = pn_v3_dot(d, pn_v3_make(g->ay[0], g->ay[1], g->ay[2])) / z;
}

/* Cell of a projected point, clamped to the grid. */
PN_KFN uint32_t pn_grid_cell(const pn_kgrid *g, float px, float py)
{
    int32_t cx = pn_kfloor_clamp((px - g->gx0) * g->inv_cell_x, 0, (int32_t)g->res_x - 1);
    int32_t cy = pn_kfloor_clamp((py - g->gy0) * g->inv_cell_y, 0, (int32_t)g->res_y - 1);
    return (uint32_t)cy * g->res_x + (uint32_t)cx;
}

/* Rectangle of cells [x0, x1] x [y0, y1] packed as x0 | x1 << 8 ... in two words:
 * lo = x0 | y0 << 16, hi = x1 | y1 << 16; empty when x0 > x1. */
typedef struct pn_cellrect {
    uint32_t lo, hi;
} pn_cellrect;

PN_KFN pn_cellrect pn_cellrect_empty(void)
{
    pn_cellrect r;
    r.lo = 1u;
    r.hi = 0u;
    return r;
}

PN_KFN int pn_cellrect_is_empty(pn_cellrect r) { return (r.lo & 0xFFFFu) > (r.hi & 0xFFFFu); }

PN_KFN pn_cellrect pn_cellrect_of_box(const pn_kgrid *g, float x0, float y0, float x1, float y1)
{
    pn_cellrect r;
    /* Slack in projected units, proportional to the grid's extent. */
    float sx = PN_GEARS_SLACK * (float)g->res_x / g->inv_cell_x;
    float sy = PN_GEARS_SLACK * (float)g->res_y / g->inv_cell_y;
    int32_t cx0 = pn_kfloor_clamp((x0 - sx - g->gx0) * g->inv_cell_x, -1, (int32_t)g->res_x);
    int32_t cx1 = pn_kfloor_clamp((x1 + sx - g->gx0) * g->inv_cell_x, -1, (int32_t)g->res_x);
    int32_t cy0 = pn_kfloor_clamp((y0 - sy - g->gy0) * g->inv_cell_y, -1, (int32_t)g->res_y);
    int32_t cy1 = pn_kfloor_clamp((y1 + sy - g->gy0) * g->inv_cell_y, -1, (int32_t)g->res_y);
    cx0 = pn_kmaxi(cx0, 0);
    cy0 = pn_kmaxi(cy0, 0);
    cx1 = pn_kmini(cx1, (int32_t)g->res_x - 1);
    cy1 = pn_kmini(cy1, (int32_t)g->res_y - 1);
    if (cx0 > cx1 || cy0 > cy1) return pn_cellrect_empty();
    r.lo = (uint32_t)cx0 | ((uint32_t)cy0 << 16);
    r.hi = (uint32_t)cx1 | ((uint32_t)cy1 << 16);
    return r;
}

PN_KFN pn_cellrect pn_cellrect_all(const pn_kgrid *g)
{
    pn_cellrect r;
    r.lo = 0u;
    r.hi = (g->res_x - 1u) | ((g->res_y - 1u) << 16);
    return r;
}

/* Cells the shadow volume of triangle ABC may touch (paper A.3, made robust as described
 * at the top of this file). */
/* Boxes as float arrays: 2-D (min x, min y, max x, max y) and 3-D (min xyz, max xyz). */
PN_KFN void pn_box2_empty(float *b)
{
    b[0] = b[1] = PN_KINF;
    b[2] = b[3] = -PN_KINF;
}

PN_KFN void pn_box2_add(float *b, float px, float py)
{
    b[0] = pn_kminf(b[0], px);
    b[1] = pn_kminf(b[1], py);
    b[2] = pn_kmaxf(b[2], px);
    b[3] = pn_kmaxf(b[3], py);
}

PN_KFN void pn_box3_empty(float *b)
{
    b[0] = b[1] = b[2] = PN_KINF;
    b[3] = b[4] = b[5] = -PN_KINF;
}

PN_KFN void pn_box3_add(float *b, pn_v3 p)
{
    b[0] = pn_kminf(b[0], p.x);
    b[1] = pn_kminf(b[1], p.y);
    b[2] = pn_kminf(b[2], p.z);
    b[3] = pn_kmaxf(b[3], p.x);
    b[4] = pn_kmaxf(b[4], p.y);
    b[5] = pn_kmaxf(b[5], p.z);
}

/* Joins box b (n = 4 or 6 floats) into acc. */
PN_KFN void pn_box_join_n(float *acc, const float *b, uint32_t n)
{
    uint32_t i, h = n / 2u;
    for (i = 0; i < h; i++) {
        acc[i] = pn_kminf(acc[i], b[i]);
        acc[h + i] = pn_kmaxf(acc[h + i], b[h + i]);
    }
}

PN_KFN void pn_box_add(const pn_kgrid *g, pn_v3 X, float *b)
{
    float px, py;
    pn_grid_project(g, X, &px, &py);
    pn_box2_add(b, px, py);
}

PN_KFN pn_cellrect pn_gears_tri_cells(const pn_kgrid *g, const pn_klight *L, pn_v3 A, pn_v3 B, pn_v3 C)
{
    pn_v3 in[3];
    float h[3], box[4], px, py;
    /* The box bounds the shadow volume of the triangle itself (the predicate is exact);
     * the rounding of the bound is PN_GEARS_SLACK's. */
    uint32_t i;
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    in[0] = A;
    in[1] = B;
    in[2] = C;
    pn_box2_empty(box);
    if (g->is_point) {
        /* The shadow of T from a point is the cone from c through T: an origin O is
         * blocked through B = c + s (O - c), so O and B project to the same cell of any
         * face that sees them in front. Parts of T nearer to c than near_depth project
         * unreliably: the whole face. Parts behind the face cannot appear on it. */
        float dmin = PN_KINF, dmax = -PN_KINF;
        for (i = 0; i < 3; i++) {
            h[i] = pn_grid_depth(g, in[i]);
            dmin = pn_kminf(dmin, h[i]);
            dmax = pn_kmaxf(dmax, h[i]);
        }
        if (dmax < -g->near_depth) return pn_cellrect_empty();
        if (!(dmin >= g->near_depth)) return pn_cellrect_all(g);
        for (i = 0; i < 3; i++) {
            pn_grid_project(g, in[i], &px, &py);
            pn_box2_add(box, px, py);
        }
    } else {
        pn_v3 N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
        pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
        pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
        float hfar = g->far_depth - g->near_depth; /* far plane height above the light */
        float band = 1e-3f * hfar, hmin = PN_KINF, hmax = -PN_KINF;
        uint32_t q;
        for (i = 0; i < 3; i++) {
            h[i] = pn_v3_dot(pn_v3_sub(in[i], c), N);
            hmin = pn_kminf(hmin, h[i]);
            hmax = pn_kmaxf(hmax, h[i]);
        }
        /* Wholly behind the light (by more than the band): no segment reaches it. Within
         * the band on either side, or across the plane, the extrusions run off toward
         * infinity and the float N's rounding matters: the whole grid. */
        if (hmax < -band) return pn_cellrect_empty();
        if (!(hmin >= band)) return pn_cellrect_all(g);
        for (i = 0; i < 3; i++) {
            pn_grid_project(g, in[i], &px, &py);
            pn_box2_add(box, px, py);
            for (q = 0; q < 4; q++) {
                /* Light corner L_q and the far-plane point of line L_q -> B:
                 * F = L_q + (B - L_q) * hfar / hb (h(L_q) = 0): the central projection of
                 * the triangle from L_q onto the far plane, which keeps it convex (every
                 * vertex has h > 0), whether B is before or beyond the far plane. */
                pn_v3 Lq = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, (q & 1u) ? 1.0f : -1.0f),
                                                  pn_v3_scale(V, (q & 2u) ? 1.0f : -1.0f)));
                pn_box_add(g, pn_v3_add(Lq, pn_v3_scale(pn_v3_sub(in[i], Lq), hfar / h[i])), box);
            }
        }
    }
    if (!(box[0] <= box[2]) || !(box[1] <= box[3])) return pn_cellrect_all(g); /* NaN: stay conservative */
    return pn_cellrect_of_box(g, box[0], box[1], box[2], box[3]);
}

/* Face and projected point of a shadow-ray origin (point light: the cube face of its
 * largest component around c, ties to the lower face; area light: face 0). */
PN_KFN uint32_t pn_gears_origin_face(const pn_klight *L, pn_v3 O)
{
    pn_v3 m;
    float ax, ay, az;
    if (!L->is_point) return 0u;
    m = pn_v3_sub(O, pn_v3_make(L->c[0], L->c[1], L->c[2]));
    ax = m.x < 0.0f ? -m.x : m.x;
    ay = m.y < 0.0f ? -m.y : m.y;
    az = m.z < 0.0f ? -m.z : m.z;
    if (ax >= ay && ax >= az) return m.x >= 0.0f ? 0u : 1u;
    if (ay >= az) return m.y >= 0.0f ? 2u : 3u;
    return m.z >= 0.0f ? 4u : 5u;
}

PN_KFN uint32_t pn_cellrect_count(pn_cellrect r)
{
    if (pn_cellrect_is_empty(r)) return 0u;
    return ((r.hi & 0xFFFFu) - (r.lo & 0xFFFFu) + 1u) * ((r.hi >> 16) - (r.lo >> 16) + 1u);
}

#endif
