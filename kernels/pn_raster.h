/* pn_raster.h - primary visibility: a software rasterizer into the G-buffer.
 *
 * Geometry. Vertices go to camera space (x along r, y along u, z along f), are clipped
 * against z >= znear (Sutherland-Hodgman, one plane, at most 4 vertices out), then
 * projected to continuous pixel coordinates px = (x/(z*tan*aspect) + 1) W/2,
 * py = (1 - y/(z*tan)) H/2, in which pixel (x, y) has its centre at (x + 0.5, y + 0.5).
 * That is exactly where the primary ray of pixel (x, y) (pn_ray_dir) pierces the image.
 *
 * Fill rule (watertight). A pixel centre is covered when every edge function is positive
 * on the polygon's inside, or zero on an edge that owns its centres: an edge owns them
 * when its inside-facing direction d (the edge direction with the polygon interior on its
 * left in pixel coordinates, y down) has d.y > 0, or d.y == 0 and d.x < 0. Two polygons
 * sharing an edge see it with opposite d, so exactly one owns a centre lying on it. Edge
 * functions and clip points are computed from their endpoints in canonical (lexicographic)
 * order, so shared edges give identical floats in both polygons: no gaps, no double hits.
 *
 * Depth. For a covered pixel, t = n.(A - eye) / n.d along the unit primary ray d, with n
 * the triangle's plane normal: the same value a ray caster gets. Ties in t go to the
 * smaller triangle id, so the result does not depend on drawing order. */
#ifndef PN_RASTER_H
#define PN_RASTER_H

#include "pn_kmath.h"
#include "pn_ktypes.h"

#define PN_RASTER_EMPTY 0xFFFFFFFFu
/* Pixel centres up to which the rows pass tests a triangle's coverage itself
 * (pn_raster_rows_small). */
#define PN_RASTER_ROWS_TEST 4u

/* Primary ray direction of pixel (x, y) (CLI conventions) scaled to unit depth along the
 * view axis f, and the unit one. */
PN_KFN pn_v3 pn_ray_dir_axial(const pn_kview *v, uint32_t x, uint32_t y)
{
    float sx = 2.0f * ((float)x + 0.5f) / (float)v->width - 1.0f;
    float sy = 1.0f - 2.0f * ((float)y + 0.5f) / (float)v->height;
    float a = sx * v->tan_half * v->aspect;
    float b = sy * v->tan_half;
    return pn_v3_make(v->f[0] + a * v->r[0] + b * v->u[0], v->f[1] + a * v->r[1] + b * v->u[1],
                      v->f[2] + a * v->r[2] + b * v->u[2]);
}

PN_KFN pn_v3 pn_ray_dir(const pn_kview *v, uint32_t x, uint32_t y) { return pn_v3_normalize(pn_ray_dir_axial(v, x, y)); }

PN_KFN pn_v3 pn_view_eye(const pn_kview *v) { return pn_v3_make(v->eye[0], v->eye[1], v->eye[2]); }

/* The plane normal of triangle ABC, unnormalized: (B - A) x (C - A). One expression for
 * pn_scene_set's degenerate test, the depth and the G-buffer normal, so they cannot drift. */
PN_KFN pn_v3 pn_tri_cross(pn_v3 A, pn_v3 B, pn_v3 C)
{
    return pn_v3_cross(pn_v3_sub(B, A), pn_v3_sub(C, A));
}

/* FLT_MIN (2^-126), written out for OpenCL C and freestanding C alike. */
#define PN_NORMAL_MIN 1.17549435e-38f

/* Whether normal n can be normalized in float. pn_v3_normalize divides by the largest
 * component m: 1/m overflows to inf for m < 2^-128 (issue 20: subnormal vertices gave a
 * cross product of 1e-41 and the G-buffer a NaN normal), and a subnormal m has too few
 * significant bits to give a direction at all. A triangle whose cross product has no
 * component of at least FLT_MIN is degenerate like one of zero area (pn_scene_set flags
 * it PN_TRI_DEGENERATE: counted, never drawn, never blocking). With m >= FLT_MIN, 1/m
 * <= 2^126 and the scaled vector has a largest component of 1: the result is unit. */
PN_KFN int pn_normal_ok(pn_v3 n) { return pn_v3_linf(n) >= PN_NORMAL_MIN; }

PN_KFN pn_v3 pn_to_camera(const pn_kview *v, pn_v3 X)
{
    pn_v3 rel = pn_v3_sub(X, pn_view_eye(v));
    return pn_v3_make(rel.x * v->r[0] + rel.y * v->r[1] + rel.z * v->r[2],
                      rel.x * v->u[0] + rel.y * v->u[1] + rel.z * v->u[2],
                      rel.x * v->f[0] + rel.y * v->f[1] + rel.z * v->f[2]);
}

typedef struct pn_poly {
    float x[4], y[4];
    uint32_t n;
} pn_poly;

/* Continuous pixel coordinates of a camera-space point with z > 0: where the primary ray
 * of pixel (x, y) pierces the image, pixel centres at (x + 0.5, y + 0.5). */
PN_KFN void pn_project_camera(const pn_kview *v, pn_v3 c, float *px, float *py)
{
    float sxs = v->tan_half * v->aspect, sys = v->tan_half;
    float hw = 0.5f * (float)v->width, hh = 0.5f * (float)v->height;
    *px = (c.x / (c.z * sxs) + 1.0f) * hw;
    *py = (1.0f - c.y / (c.z * sys)) * hh;
}

/* Clips the triangle (world space) to z >= znear in camera space and projects what is
 * left into poly (n may be below 3: nothing left), in traversal order, whatever its area;
 * *zmin: the smallest camera z of the clipped polygon. */
PN_KFN void pn_poly_project(const pn_kview *v, pn_v3 A, pn_v3 B, pn_v3 C, pn_poly *poly, float *zmin)
{
    pn_v3 in[3], out[4];
    uint32_t i, n = 0;
    float zn = v->znear;
    in[0] = pn_to_camera(v, A);
    in[1] = pn_to_camera(v, B);
    in[2] = pn_to_camera(v, C);
    for (i = 0; i < 3; i++) {
        pn_v3 p = in[i], q = in[(i + 1u) % 3u];
        int pin = p.z >= zn, qin = q.z >= zn;
        if (pin) out[n++] = p;
        if (pin != qin) {
            /* Canonical order: both triangles sharing PQ compute the same point. */
            pn_v3 a = pn_v3_less(p, q) ? p : q, b = pn_v3_less(p, q) ? q : p;
            float t = (zn - a.z) / (b.z - a.z);
            pn_v3 x = pn_v3_add(a, pn_v3_scale(pn_v3_sub(b, a), t));
            x.z = zn;
            out[n++] = x;
        }
    }
    poly->n = n;
    *zmin = PN_KINF;
    for (i = 0; i < n; i++) {
        pn_project_camera(v, out[i], &poly->x[i], &poly->y[i]);
        *zmin = pn_kminf(*zmin, out[i].z);
    }
}

/* Clips the camera-space triangle to z >= znear and projects it. n = 0 when nothing is
 * left or the projection has zero area. */
PN_KFN void pn_poly_make(const pn_kview *v, pn_v3 A, pn_v3 B, pn_v3 C, pn_poly *poly)
{
    uint32_t i, n;
    float zmin;
    pn_poly_project(v, A, B, C, poly, &zmin);
    n = poly->n;
    poly->n = 0;
    if (n < 3) return;
    {
        float area = 0.0f;
        for (i = 0; i < n; i++) {
            uint32_t j = (i + 1u) % n;
            area += poly->x[i] * poly->y[j] - poly->x[j] * poly->y[i];
        }
        if (area == 0.0f || !(area == area)) return;
        poly->n = n;
        if (area < 0.0f) { /* make the interior lie left of each edge (y down) */
            for (i = 0; i < n / 2u; i++) {
                float tx = poly->x[i], ty = poly->y[i];
                poly->x[i] = poly->x[n - 1u - i];
                poly->y[i] = poly->y[n - 1u - i];
                poly->x[n - 1u - i] = tx;
                poly->y[n - 1u - i] = ty;
            }
        }
    }
}

/* Edge function of polygon edge i at (px, py): > 0 inside; with ownership of zeros. */
typedef struct pn_edge2 {
    float ax, ay, bx, by; /* canonical endpoints */
    float sign;           /* +1 if the polygon traverses a -> b, else -1 */
    uint32_t owns;        /* centres exactly on the edge are inside */
    uint32_t skip;        /* zero-length edge (a clip point on a vertex) */
} pn_edge2;

/* The edge from (x0, y0) to (x1, y1) of a polygon traversed with its interior on the left. */
PN_KFN_HOT void pn_edge_make(float x0, float y0, float x1, float y1, pn_edge2 *e)
{
    int flip = (x1 < x0) | ((x1 == x0) & (y1 < y0));
    float dx = x1 - x0, dy = y1 - y0;
    e->ax = flip ? x1 : x0;
    e->ay = flip ? y1 : y0;
    e->bx = flip ? x0 : x1;
    e->by = flip ? y0 : y1;
    e->sign = flip ? -1.0f : 1.0f;
    /* Interior on the left in y-down coordinates is where the cross product
     * (b - a) x (p - a) is positive for the traversal direction; the inside-facing
     * direction is the traversal direction itself. */
    e->owns = (uint32_t)((dy > 0.0f) | ((dy == 0.0f) & (dx < 0.0f)));
    e->skip = (uint32_t)((dx == 0.0f) & (dy == 0.0f));
}

PN_KFN void pn_edges_make(const pn_poly *p, pn_edge2 *e)
{
    uint32_t i;
    for (i = 0; i < p->n; i++) {
        uint32_t j = (i + 1u) % p->n;
        pn_edge_make(p->x[i], p->y[i], p->x[j], p->y[j], &e[i]);
    }
}

/* Whether (px, py) lies on the inside of edge e (not skipped). */
PN_KFN_HOT int pn_edge_in(const pn_edge2 *e, float px, float py)
{
    float w = e->sign * ((e->bx - e->ax) * (py - e->ay) - (e->by - e->ay) * (px - e->ax));
    return !((w < 0.0f) | ((w == 0.0f) & !e->owns));
}

PN_KFN int pn_edges_inside(const pn_edge2 *e, uint32_t n, float px, float py)
{
    uint32_t i;
    for (i = 0; i < n; i++)
        if (!e[i].skip && !pn_edge_in(&e[i], px, py)) return 0;
    return 1;
}

/* The pixel centres a small triangle covers, as pn_raster_rows_small found them: bit
 * (y - y0) w + (x - x0) of mask for centre (x, y); w = 0 when the triangle was not small
 * (or covers nothing: then mask is 0 too). */
typedef struct pn_raster_small {
    int32_t x0, y0, w;
    uint32_t mask;
} pn_raster_small;

/* Triangle set-up: the range of pixel rows whose centres the triangle may cover, packed
 * y0 | y1 << 16, or PN_RASTER_EMPTY; *sm: the centres it covers, if it is small. */
PN_KFN uint32_t pn_raster_rows_small(const pn_kview *v, PN_CONST float *tris, PN_CONST uint8_t *flags, uint32_t t,
                                     pn_raster_small *sm)
{
    PN_CONST float *p = tris + (size_t)t * 9u;
    pn_poly poly;
    float lo, hi, xlo, xhi;
    uint32_t i;
    int32_t y0, y1, x0, x1;
    sm->w = 0;
    sm->mask = 0u;
    if (flags[t] & PN_TRI_DEGENERATE) return PN_RASTER_EMPTY;
    pn_poly_make(v, pn_v3_make(p[0], p[1], p[2]), pn_v3_make(p[3], p[4], p[5]),
                 pn_v3_make(p[6], p[7], p[8]), &poly);
    if (poly.n == 0u) return PN_RASTER_EMPTY;
    lo = poly.y[0];
    hi = poly.y[0];
    xlo = poly.x[0];
    xhi = poly.x[0];
    for (i = 1; i < poly.n; i++) {
        lo = pn_kminf(lo, poly.y[i]);
        hi = pn_kmaxf(hi, poly.y[i]);
        xlo = pn_kminf(xlo, poly.x[i]);
        xhi = pn_kmaxf(xhi, poly.x[i]);
    }
    /* Centre y + 0.5 in [lo, hi]; and some column's centre in [xlo, xhi]: the columns
     * pn_raster_tri_setup draws (a triangle between two column centres, common among
     * the dense meshes' sub-texel triangles, is set up nowhere). */
    y0 = pn_kceil_clamp(lo - 0.5f, 0, (int32_t)v->height);
    y1 = pn_kfloor_clamp(hi - 0.5f, -1, (int32_t)v->height - 1);
    if (y0 > y1) return PN_RASTER_EMPTY;
    x0 = pn_kceil_clamp(xlo - 0.5f, 0, (int32_t)v->width);
    x1 = pn_kfloor_clamp(xhi - 0.5f, -1, (int32_t)v->width - 1);
    if (x0 > x1) return PN_RASTER_EMPTY;
    if ((x1 - x0 + 1) * (y1 - y0 + 1) <= (int32_t)PN_RASTER_ROWS_TEST) {
        /* A few centres to look at (a small triangle): test them with the set-up's own
         * polygon and edge functions, and keep only the rows of those it covers, or none:
         * every band then skips it, or sets it up once. */
        pn_edge2 e[4];
        int32_t x, y, c0 = y1 + 1, c1 = y0 - 1;
        pn_edges_make(&poly, e);
        sm->x0 = x0;
        sm->y0 = y0;
        sm->w = x1 - x0 + 1;
        for (y = y0; y <= y1; y++)
            for (x = x0; x <= x1; x++)
                if (pn_edges_inside(e, poly.n, (float)x + 0.5f, (float)y + 0.5f)) {
                    c0 = pn_kmini(c0, y);
                    c1 = pn_kmaxi(c1, y);
                    sm->mask |= 1u << (uint32_t)((y - y0) * sm->w + (x - x0));
                }
        if (c0 > c1) return PN_RASTER_EMPTY;
        y0 = c0;
        y1 = c1;
    }
    return (uint32_t)y0 | ((uint32_t)y1 << 16);
}

/* Triangles a rows pass item sets up side by side (pn_raster_rows_group). */
#define PN_RASTER_GROUP 8u

/* Centre k (bit k of *mask) of a small triangle's dx x dy candidates from (x0, y0), the
 * centre (x0 + k % dx, y0 + k / dx), tested against the triangle's three edges as
 * pn_edges_inside does; *c0, *c1: the rows of the covered ones. Selects only. */
PN_KFN_HOT void pn_raster_centre(const pn_edge2 *e0, const pn_edge2 *e1, const pn_edge2 *e2, int small, int32_t x0,
                                 int32_t y0, int32_t dx, int32_t dy, int32_t k, uint32_t *mask, int32_t *c0, int32_t *c1)
{
    int32_t ky = (k >= dx) + (k >= 2 * dx) + (k >= 3 * dx), kx = k - ky * dx; /* dx >= 1 */
    float px = (float)(x0 + kx) + 0.5f, py = (float)(y0 + ky) + 0.5f;
    int in = small & (k < dx * dy) & ((int)e0->skip | pn_edge_in(e0, px, py)) & ((int)e1->skip | pn_edge_in(e1, px, py)) &
             ((int)e2->skip | pn_edge_in(e2, px, py));
    *mask |= (uint32_t)in << (uint32_t)k;
    *c0 = in ? pn_kmini(*c0, y0 + ky) : *c0;
    *c1 = in ? pn_kmaxi(*c1, y0 + ky) : *c1;
}

/* pn_raster_rows_small for triangles t0 .. t0 + count - 1 (count <= PN_RASTER_GROUP) into
 * rows[i], sm[i]; those whose flags have a bit of skip or PN_TRI_DEGENERATE are
 * PN_RASTER_EMPTY. All eight go through one loop with no branch, which the compilers
 * vectorize: camera transform, projection, area, the polygon as pn_poly_make leaves it
 * (reversed when the area is negative), its box and pixel ranges, and a small triangle's
 * centre tests with pn_edge_make's edges: each triangle's float operations are those of
 * pn_raster_rows_small when the near plane leaves it whole, in the same order, so the
 * same bytes (test_raster checks them against it). A triangle the near plane cuts goes
 * through pn_raster_rows_small itself. (Chess, 512x512 layers: of 77k occluders a third
 * have no centre in their box, a third are small, 4% are drawn by the bands.) */
PN_KFN void pn_raster_rows_group(const pn_kview *v, PN_CONST float *tris, PN_CONST uint8_t *flags, uint32_t t0,
                                 uint32_t count, uint32_t skip, uint32_t *rows, pn_raster_small *sm)
{
    uint32_t r[PN_RASTER_GROUP], mk[PN_RASTER_GROUP], l;
    float V[9][PN_RASTER_GROUP];
    int32_t sx0[PN_RASTER_GROUP], sy0[PN_RASTER_GROUP], sw[PN_RASTER_GROUP];
    int whole[PN_RASTER_GROUP];
    float zn = v->znear;
    int32_t W = (int32_t)v->width, H = (int32_t)v->height;
    /* The vertices by coordinate, lane by lane (a loop over lanes then reads them in a row;
     * lanes beyond count repeat the first triangle, their results unread). */
    for (l = 0; l < PN_RASTER_GROUP; l++) {
        PN_CONST float *p = tris + (size_t)(t0 + (l < count ? l : 0u)) * 9u;
        uint32_t k;
        for (k = 0; k < 9u; k++) V[k][l] = p[k];
    }
    for (l = 0; l < PN_RASTER_GROUP; l++) {
        pn_v3 a = pn_to_camera(v, pn_v3_make(V[0][l], V[1][l], V[2][l]));
        pn_v3 b = pn_to_camera(v, pn_v3_make(V[3][l], V[4][l], V[5][l]));
        pn_v3 c = pn_to_camera(v, pn_v3_make(V[6][l], V[7][l], V[8][l]));
        float ax, ay, bx, by, cx, cy, s = 0.0f, p0x, p0y, p2x, p2y, lo, hi, xlo, xhi;
        int32_t x0, x1, y0, y1, dx, dy, c0 = H, c1 = -1;
        int neg, ok, small;
        uint32_t mask = 0u;
        pn_edge2 e0, e1, e2;
        pn_project_camera(v, a, &ax, &ay);
        pn_project_camera(v, b, &bx, &by);
        pn_project_camera(v, c, &cx, &cy);
        whole[l] = (a.z >= zn) & (b.z >= zn) & (c.z >= zn);
        /* pn_poly_make: the area in the vertices' order, then the polygon turned so that
         * its interior lies on the left (a, b, c or c, b, a) */
        s += ax * by - bx * ay;
        s += bx * cy - cx * by;
        s += cx * ay - ax * cy;
        neg = s < 0.0f;
        p0x = neg ? cx : ax;
        p0y = neg ? cy : ay;
        p2x = neg ? ax : cx;
        p2y = neg ? ay : cy;
        /* pn_raster_rows_small's box and ranges */
        lo = pn_kminf(pn_kminf(p0y, by), p2y);
        hi = pn_kmaxf(pn_kmaxf(p0y, by), p2y);
        xlo = pn_kminf(pn_kminf(p0x, bx), p2x);
        xhi = pn_kmaxf(pn_kmaxf(p0x, bx), p2x);
        y0 = pn_kceil_clamp(lo - 0.5f, 0, H);
        y1 = pn_kfloor_clamp(hi - 0.5f, -1, H - 1);
        x0 = pn_kceil_clamp(xlo - 0.5f, 0, W);
        x1 = pn_kfloor_clamp(xhi - 0.5f, -1, W - 1);
        ok = (s != 0.0f) & (s == s) & (y0 <= y1) & (x0 <= x1);
        dx = x1 - x0 + 1;
        dy = y1 - y0 + 1;
        small = ok & (dx <= 4) & (dy <= 4) & (dx * dy <= (int32_t)PN_RASTER_ROWS_TEST);
        /* A small triangle's centres: bit k is centre (x0 + k % dx, y0 + k / dx). */
        pn_edge_make(p0x, p0y, bx, by, &e0);
        pn_edge_make(bx, by, p2x, p2y, &e1);
        pn_edge_make(p2x, p2y, p0x, p0y, &e2);
        /* PN_RASTER_ROWS_TEST (4) centres, written out: a loop inside keeps the compilers
         * from vectorizing this one. */
        pn_raster_centre(&e0, &e1, &e2, small, x0, y0, dx, dy, 0, &mask, &c0, &c1);
        pn_raster_centre(&e0, &e1, &e2, small, x0, y0, dx, dy, 1, &mask, &c0, &c1);
        pn_raster_centre(&e0, &e1, &e2, small, x0, y0, dx, dy, 2, &mask, &c0, &c1);
        pn_raster_centre(&e0, &e1, &e2, small, x0, y0, dx, dy, 3, &mask, &c0, &c1);
        {
            /* flat selects (nested ones keep a branch in the loop) */
            uint32_t rs = (uint32_t)c0 | ((uint32_t)c1 << 16), rb = (uint32_t)y0 | ((uint32_t)y1 << 16);
            int none = (ok == 0) | (small & (mask == 0u));
            r[l] = none ? PN_RASTER_EMPTY : (small ? rs : rb);
        }
        mk[l] = mask;
        sx0[l] = x0;
        sy0[l] = y0;
        sw[l] = small ? dx : 0;
    }
    for (l = 0; l < count; l++) {
        uint32_t t = t0 + l;
        sm[l].w = 0;
        sm[l].mask = 0u;
        if (flags[t] & (skip | PN_TRI_DEGENERATE)) {
            rows[l] = PN_RASTER_EMPTY;
        } else if (!whole[l]) { /* the near plane cuts it */
            rows[l] = pn_raster_rows_small(v, tris, flags, t, &sm[l]);
        } else {
            rows[l] = r[l];
            sm[l].x0 = sx0[l];
            sm[l].y0 = sy0[l];
            sm[l].w = sw[l];
            sm[l].mask = mk[l];
        }
    }
}

/* Rows pass item g of the n triangles (PN_RASTER_GROUPS(n) items): rows[t] for its group. */
#define PN_RASTER_GROUPS(n) (((n) + PN_RASTER_GROUP - 1u) / PN_RASTER_GROUP)
PN_KFN void pn_raster_rows_item(const pn_kview *v, PN_CONST float *tris, PN_CONST uint8_t *flags, uint32_t n, uint32_t g,
                                PN_GLOBAL uint32_t *rows)
{
    uint32_t r[PN_RASTER_GROUP], t0 = g * PN_RASTER_GROUP, count = pn_kminu(PN_RASTER_GROUP, n - t0), i;
    pn_raster_small sm[PN_RASTER_GROUP];
    pn_raster_rows_group(v, tris, flags, t0, count, 0u, r, sm);
    for (i = 0; i < count; i++) rows[t0 + i] = r[i];
}

/* The band walk. A band of rows looks at the triangles that may cover them, not at every
 * triangle: the walk goes through the BVH's raster order (`rindex`, its n entries: every
 * triangle that is not degenerate, which are the only ones the rows pass draws, once, in
 * the leaf order where it first appears, so grouped in space by the build) in chunks of PN_RASTER_CHUNK entries, and skips a chunk whose rows,
 * the union of its triangles' (pn_raster_chunk, one item per chunk after the rows pass),
 * miss the band. Every rasterizer here combines fragments in a way that does not depend
 * on their order (nearest depth with ties to the smaller id, OR of bits, min and max), so
 * this order gives the bytes that id order gives. */
PN_KFN uint32_t pn_raster_chunk(PN_CONST uint32_t *rows, PN_CONST uint32_t *index, uint32_t n, uint32_t c)
{
    uint32_t i = c * PN_RASTER_CHUNK, e = i + PN_RASTER_CHUNK, lo = 0xFFFFu, hi = 0u;
    if (e > n) e = n;
    for (; i < e; i++) {
        uint32_t r = rows[index[i]];
        if (r == PN_RASTER_EMPTY) continue;
        lo = pn_kminu(lo, r & 0xFFFFu);
        hi = pn_kmaxu(hi, r >> 16);
    }
    return lo > hi ? PN_RASTER_EMPTY : lo | (hi << 16);
}

/* A band's walk over n entries: the next chunk of nc, and the entries [i, end) left of the
 * current one. */
typedef struct pn_band_walk {
    uint32_t n, nc, chunk, i, end;
} pn_band_walk;

PN_KFN void pn_band_walk_begin(pn_band_walk *w, uint32_t n)
{
    w->n = n;
    w->nc = PN_RASTER_CHUNKS(n);
    w->chunk = 0u;
    w->i = 0u;
    w->end = 0u;
}

/* The next triangle *t of the chunks whose rows meet [row0, row1]; 0 at the end. The
 * triangle's own rows may still miss the band (pn_raster_tri_setup tests them). */
PN_KFN_HOT int pn_band_next(PN_CONST uint32_t *chunks, PN_CONST uint32_t *index, uint32_t row0, uint32_t row1,
                            pn_band_walk *w, uint32_t *t)
{
    while (w->i >= w->end) {
        uint32_t r;
        if (w->chunk >= w->nc) return 0;
        r = chunks[w->chunk++];
        if (r == PN_RASTER_EMPTY || (r & 0xFFFFu) > row1 || (r >> 16) < row0) continue;
        w->i = (w->chunk - 1u) * PN_RASTER_CHUNK;
        w->end = pn_kminu(w->i + PN_RASTER_CHUNK, w->n);
    }
    *t = index[w->i++];
    return 1;
}

/* One triangle set up for the rows [row0, row1] of view v: its projected polygon and edge
 * functions, the pixel columns and rows it may cover there, and its plane (n, n.(A - eye))
 * for the depth along a pixel's primary ray. The one set-up of every rasterizer here (the
 * G-buffer, the light-space maps, the occlusion-texture slices), so they cover the same
 * pixel centres. */
typedef struct pn_raster_tri {
    pn_poly poly;
    pn_edge2 e[4];
    int32_t x0, x1;
    uint32_t y0, y1;
    pn_v3 n;
    float nA;
    uint32_t span; /* rows are wide enough, and the edges tame enough, for pn_raster_span */
} pn_raster_tri;

/* Columns a row must have before pn_raster_span looks for its run of covered centres, and
 * the largest coordinate magnitude it takes (2^30). */
#define PN_RASTER_SPAN_MIN 8
#define PN_RASTER_SPAN_LIM 1073741824.0f

/* Triangle ABC's plane for the depth along a pixel's ray: *n and the returned n.(A - eye). */
PN_KFN float pn_raster_plane(const pn_kview *v, pn_v3 A, pn_v3 B, pn_v3 C, pn_v3 *n)
{
    *n = pn_tri_cross(A, B, C);
    return pn_v3_dot(*n, pn_v3_sub(A, pn_view_eye(v)));
}

/* 0 when triangle t covers nothing in rows [row0, row1] (rows[t]: the rows pass, pn_raster_rows_item). */
PN_KFN int pn_raster_tri_setup(const pn_kview *v, PN_CONST float *tris, PN_CONST uint32_t *rows, uint32_t t,
                               uint32_t row0, uint32_t row1, pn_raster_tri *rt)
{
    uint32_t r = rows[t], i;
    PN_CONST float *p;
    pn_v3 A, B, C;
    float xlo, xhi;
    if (r == PN_RASTER_EMPTY) return 0;
    rt->y0 = r & 0xFFFFu;
    rt->y1 = r >> 16;
    if (rt->y1 < row0 || rt->y0 > row1) return 0;
    if (rt->y0 < row0) rt->y0 = row0;
    if (rt->y1 > row1) rt->y1 = row1;
    p = tris + (size_t)t * 9u;
    A = pn_v3_make(p[0], p[1], p[2]);
    B = pn_v3_make(p[3], p[4], p[5]);
    C = pn_v3_make(p[6], p[7], p[8]);
    pn_poly_make(v, A, B, C, &rt->poly);
    if (rt->poly.n == 0u) return 0;
    pn_edges_make(&rt->poly, rt->e);
    xlo = rt->poly.x[0];
    xhi = rt->poly.x[0];
    for (i = 1; i < rt->poly.n; i++) {
        xlo = pn_kminf(xlo, rt->poly.x[i]);
        xhi = pn_kmaxf(xhi, rt->poly.x[i]);
    }
    rt->x0 = pn_kceil_clamp(xlo - 0.5f, 0, (int32_t)v->width);
    rt->x1 = pn_kfloor_clamp(xhi - 0.5f, -1, (int32_t)v->width - 1);
    rt->nA = pn_raster_plane(v, A, B, C, &rt->n);
    rt->span = rt->x1 - rt->x0 + 1 >= PN_RASTER_SPAN_MIN;
    for (i = 0; rt->span && i < rt->poly.n; i++) /* also false for not-a-number */
        rt->span = pn_kfabs(rt->poly.x[i]) <= PN_RASTER_SPAN_LIM && pn_kfabs(rt->poly.y[i]) <= PN_RASTER_SPAN_LIM;
    return 1;
}

/* The columns [*xa, *xb] of row y whose centres the set-up triangle covers (none: *xa >
 * *xb), the same centres as testing each (pn_edges_inside): 0 when the row is to be
 * tested centre by centre instead (narrow, or edges beyond PN_RASTER_SPAN_LIM).
 *
 * Along a row an edge's test is monotonic in x. Its value is sign ((bx - ax)(py - ay) -
 * (by - ay)(px - ax)), each operation rounded: the first product is fixed along the row;
 * px - ax rounded is non-decreasing in px, and so the second product, rounded, is monotonic
 * (its direction that of by - ay); the difference of two floats is zero exactly when they
 * are equal and otherwise has their order's sign, and the sign is exact. So each edge keeps
 * a run of columns that reaches one end of [x0, x1] (or all, or none, when by = ay), found
 * by bisection with the test itself, and the covered run is their intersection. With every
 * coordinate within 2^30 no operation overflows, so none is infinite or not a number. */
PN_KFN int pn_raster_span(const pn_raster_tri *rt, uint32_t y, int32_t *xa, int32_t *xb)
{
    float py = (float)y + 0.5f;
    int32_t lo = rt->x0, hi = rt->x1;
    uint32_t i;
    if (!rt->span) return 0;
    for (i = 0; i < rt->poly.n && lo <= hi; i++) {
        const pn_edge2 *e = &rt->e[i];
        float dir;
        int32_t a, b;
        int left;
        if (e->skip) continue;
        dir = e->sign * (e->by - e->ay);
        if (dir == 0.0f) {
            if (!pn_edge_in(e, (float)lo + 0.5f, py)) hi = lo - 1;
            continue;
        }
        /* left: inside up to some column (dir > 0), else from some column on. */
        left = dir > 0.0f;
        if (pn_edge_in(e, (float)(left ? hi : lo) + 0.5f, py)) continue; /* all of [lo, hi] */
        if (!pn_edge_in(e, (float)(left ? lo : hi) + 0.5f, py)) {       /* none */
            hi = lo - 1;
            continue;
        }
        a = lo; /* inside when left */
        b = hi; /* inside when not */
        while (b - a > 1) {
            int32_t m = a + (b - a) / 2;
            if (pn_edge_in(e, (float)m + 0.5f, py) == left)
                a = m;
            else
                b = m;
        }
        if (left)
            hi = a;
        else
            lo = b;
    }
    *xa = lo;
    *xb = hi;
    return 1;
}

/* Whether the set-up triangle covers the centre of pixel (x, y) in front of the eye (run:
 * the centre is in the row's covered run, pn_raster_span, so known to be covered), and then
 * *t: its distance along the pixel's unit primary ray *dir. */
PN_KFN_HOT int pn_raster_tri_hit(const pn_kview *v, const pn_raster_tri *rt, int run, uint32_t x, uint32_t y, float *t,
                                 pn_v3 *dir)
{
    float den;
    if (!run && !pn_edges_inside(rt->e, rt->poly.n, (float)x + 0.5f, (float)y + 0.5f)) return 0;
    *dir = pn_ray_dir(v, x, y);
    den = pn_v3_dot(rt->n, *dir);
    if (den == 0.0f) return 0;
    *t = rt->nA / den;
    return *t > 0.0f;
}

/* The depth along the view axis f (the light-space maps' depth) of the point of plane
 * (n, nA) at the centre of pixel (x, y), from the pixel's ray scaled to unit depth: no square
 * root; 0 when that point is not in front of the eye. pn_raster_tri_axial: the same where
 * the set-up triangle covers the centre (the test of pn_raster_tri_hit; run: the centre is
 * in the row's covered run, pn_raster_span, so known to be covered). */
PN_KFN_HOT int pn_raster_axial(const pn_kview *v, pn_v3 n, float nA, uint32_t x, uint32_t y, float *z)
{
    float den = pn_v3_dot(n, pn_ray_dir_axial(v, x, y));
    if (den == 0.0f) return 0;
    *z = nA / den;
    return *z > 0.0f;
}
PN_KFN_HOT int pn_raster_tri_axial(const pn_kview *v, const pn_raster_tri *rt, int run, uint32_t x, uint32_t y, float *z)
{
    if (!run && !pn_edges_inside(rt->e, rt->poly.n, (float)x + 0.5f, (float)y + 0.5f)) return 0;
    return pn_raster_axial(v, rt->n, rt->nA, x, y, z);
}

/* Rasterizes the band walk's triangles into rows [row0, row1] of the G-buffer. depth and
 * tri_id of those rows must hold +inf / PN_NO_TRIANGLE on entry. */
PN_KFN void pn_raster_band(const pn_kview *v, PN_CONST float *tris, PN_CONST uint32_t *rows, PN_CONST uint32_t *chunks,
                           PN_CONST uint32_t *index, uint32_t n, uint32_t row0, uint32_t row1, PN_GLOBAL float *depth,
                           PN_GLOBAL uint32_t *tri_id)
{
    pn_band_walk w;
    uint32_t t;
    pn_band_walk_begin(&w, n);
    while (pn_band_next(chunks, index, row0, row1, &w, &t)) {
        pn_raster_tri rt;
        uint32_t y;
        if (!pn_raster_tri_setup(v, tris, rows, t, row0, row1, &rt)) continue;
        for (y = rt.y0; y <= rt.y1; y++) {
            int32_t x, xa = rt.x0, xb = rt.x1;
            int run = pn_raster_span(&rt, y, &xa, &xb);
            for (x = xa; x <= xb; x++) {
                size_t pix = (size_t)y * v->width + (size_t)x;
                float tt;
                pn_v3 dir;
                if (!pn_raster_tri_hit(v, &rt, run, (uint32_t)x, y, &tt, &dir)) continue;
                if (tt < depth[pix] || (tt == depth[pix] && t < tri_id[pix])) {
                    depth[pix] = tt;
                    tri_id[pix] = t;
                }
            }
        }
    }
}

/* The unit geometric normal of triangle t (drawn, so not degenerate: pn_normal_ok holds). */
PN_KFN pn_v3 pn_tri_unit_normal(PN_CONST float *tris, uint32_t t)
{
    PN_CONST float *p = tris + (size_t)t * 9u;
    return pn_v3_normalize(pn_tri_cross(pn_v3_make(p[0], p[1], p[2]), pn_v3_make(p[3], p[4], p[5]),
                                        pn_v3_make(p[6], p[7], p[8])));
}

/* The point at distance d along the primary ray of pixel (x, y). */
PN_KFN pn_v3 pn_view_point(const pn_kview *v, uint32_t x, uint32_t y, float d)
{
    return pn_v3_add(pn_view_eye(v), pn_v3_scale(pn_ray_dir(v, x, y), d));
}

/* Fills position and normal of one pixel from its depth and triangle. */
PN_KFN void pn_gbuffer_resolve(const pn_kview *v, PN_CONST float *tris, uint32_t x, uint32_t y,
                               PN_GLOBAL const float *depth, PN_GLOBAL const uint32_t *tri_id,
                               PN_GLOBAL float *pos, PN_GLOBAL float *nrm)
{
    size_t pix = (size_t)y * v->width + (size_t)x;
    uint32_t t = tri_id[pix];
    pn_v3 P = pn_v3_make(0.0f, 0.0f, 0.0f), n = P;
    if (t != 0xFFFFFFFFu) {
        n = pn_tri_unit_normal(tris, t);
        P = pn_view_point(v, x, y, depth[pix]);
    }
    pos[pix * 3u + 0u] = P.x;
    pos[pix * 3u + 1u] = P.y;
    pos[pix * 3u + 2u] = P.z;
    nrm[pix * 3u + 0u] = n.x;
    nrm[pix * 3u + 1u] = n.y;
    nrm[pix * 3u + 2u] = n.z;
}

/* The G-buffer as the shadow passes read it: each pixel's triangle, and its position and
 * normal either stored (pos, nrm: the rasterizer's resolve above, or a point query's own)
 * or, for a context whose limits set PN_LIMITS_NO_SURFACE (pos = 0), recomputed from its
 * depth and triangle by the same functions: the same bits either way. */
typedef struct pn_ksurf {
    const pn_kview *v;
    PN_CONST float *tris;
    PN_CONST float *depth;
    PN_CONST uint32_t *tri_id;
    PN_CONST float *pos; /* 0: recomputed */
    PN_CONST float *nrm;
} pn_ksurf;

/* Pixel pix's position and unit normal from its depth and triangle (zero for a background
 * pixel): the path of a frame that keeps none, out of line so that the stored path below
 * stays small where it is inlined. */
PN_KFN_COLD void pn_surf_resolve(const pn_ksurf *S, size_t pix, pn_v3 *P, pn_v3 *n)
{
    uint32_t t = S->tri_id[pix];
    if (t == 0xFFFFFFFFu) {
        *P = *n = pn_v3_make(0.0f, 0.0f, 0.0f);
        return;
    }
    *n = pn_tri_unit_normal(S->tris, t);
    *P = pn_view_point(S->v, (uint32_t)(pix % S->v->width), (uint32_t)(pix / S->v->width), S->depth[pix]);
}

/* Pixel pix's position and unit normal (zero for a background pixel). */
PN_KFN_HOT void pn_surf_at(const pn_ksurf *S, size_t pix, pn_v3 *P, pn_v3 *n)
{
    if (S->pos) {
        *P = pn_v3_load(S->pos + pix * 3u);
        *n = pn_v3_load(S->nrm + pix * 3u);
    } else {
        pn_surf_resolve(S, pix, P, n);
    }
}

/* Pixel pix's unit normal (zero for a background pixel). */
PN_KFN_HOT pn_v3 pn_surf_normal(const pn_ksurf *S, size_t pix)
{
    uint32_t t;
    if (S->pos) return pn_v3_load(S->nrm + pix * 3u);
    t = S->tri_id[pix];
    return t == 0xFFFFFFFFu ? pn_v3_make(0.0f, 0.0f, 0.0f) : pn_tri_unit_normal(S->tris, t);
}

#endif
