/* pn_mc_search.h - Monte Carlo shadow maps, one ray: the per-pixel context, lookups, the
 * linear/binary and hierarchical searches, regions, clipping, the bias. Part of pn_mcsm.h, which
 * includes it after the constants it uses; see there. */
#ifndef PN_MC_SEARCH_H
#define PN_MC_SEARCH_H

/* ---- One pixel's rays ----------------------------------------------------------------------- */

/* What the per-pixel work reads. */
typedef struct pn_mc_ctx {
    const pn_kview *view, *lv;
    const pn_klight *L;
    const pn_kmc *mc;
    PN_CONST float *nb;    /* N-buffer levels */
    pn_nb_mm_lay nb_lay;   /* their layout */
    PN_CONST float *depth; /* G-buffer depth (third layer) */
    PN_CONST uint8_t *flags; /* triangle flags (PN_TRI_SHEET) */
    float tx, ty;          /* the layers' window half-tans (pn_project_camera's factors) */
    float hw, hh;          /* half the layers' size in texels */
    float ha, hb;          /* the light's half-extents (pn_lview_outside) */
    pn_v3 corner[4];       /* the light's corners c -+ U -+ V (bit 0: +U, bit 1: +V) */
    uint32_t steps;        /* search steps so far */
    uint32_t capped;       /* searches stopped at the cap */
    uint32_t stacked;      /* the pixel's rays: one blocked in a stacked texel (pn_mc_stacked_texel) */
} pn_mc_ctx;

/* A ray in the light frame from (xs, ys, 0) to (xe, ye, ze). */
typedef struct pn_mc_ray {
    float xs, ys, xe, ye, ze;
} pn_mc_ray;

PN_KFN pn_v3 pn_mc_at(const pn_mc_ray *r, float t)
{
    return pn_v3_make(r->xs + t * (r->xe - r->xs), r->ys + t * (r->ye - r->ys), t * r->ze);
}

/* The per-pixel context over view, light view lv, light L, parameters mc, the N-buffer nb
 * and the G-buffer's depth. */
PN_KFN void pn_mc_ctx_init(pn_mc_ctx *m, const pn_kview *view, const pn_kview *lv, const pn_klight *L, float ha,
                           float hb, const pn_kmc *mc, PN_CONST float *nb, PN_CONST float *depth,
                           PN_CONST uint8_t *flags)
{
    uint32_t k;
    m->view = view;
    m->lv = lv;
    m->L = L;
    m->mc = mc;
    m->nb = nb;
    (void)pn_nb_mm_lay_init(mc, &m->nb_lay);
    m->depth = depth;
    m->flags = flags;
    m->tx = lv->tan_half * lv->aspect;
    m->ty = lv->tan_half;
    m->hw = 0.5f * (float)lv->width;
    m->hh = 0.5f * (float)lv->height;
    m->ha = ha;
    m->hb = hb;
    m->steps = 0u;
    m->capped = 0u;
    m->stacked = 0u;
    for (k = 0; k < 4u; k++)
        m->corner[k] = pn_v3_add(pn_v3_make(L->c[0], L->c[1], L->c[2]),
                                 pn_v3_add(pn_v3_scale(pn_v3_make(L->U[0], L->U[1], L->U[2]), (k & 1u) ? 1.0f : -1.0f),
                                           pn_v3_scale(pn_v3_make(L->V[0], L->V[1], L->V[2]), (k & 2u) ? 1.0f : -1.0f)));
}

/* Image of a light-frame point in the layers, continuous texel coordinates:
 * pn_project_camera of (p.x, p.y, p.z + d) in lv, the same operations on factors
 * computed once. */
PN_KFN void pn_mc_proj(const pn_mc_ctx *m, pn_v3 p, float *px, float *py)
{
    float z = p.z + m->mc->d;
    *px = (p.x / (z * m->tx) + 1.0f) * m->hw;
    *py = (1.0f - p.y / (z * m->ty)) * m->hh;
}

/* Level-0 texel holding a light-frame point (clamped to the map), as stored (its bounds:
 * pn_nb_mm_get); *outside: the point's image lies beyond the map (the window left it out:
 * nothing is known there). */
PN_KFN uint32_t pn_mc_texel_at(const pn_mc_ctx *m, float px, float py, int *outside)
{
    float R = (float)m->mc->res;
    int32_t last = (int32_t)m->mc->res - 1;
    *outside = !((px >= 0.0f) & (py >= 0.0f) & (px < R) & (py < R));
    return ((uint32_t)pn_kfloor_clamp(py, 0, last) * m->mc->res + (uint32_t)pn_kfloor_clamp(px, 0, last)) * PN_NB_MM;
}
PN_KFN PN_CONST float *pn_mc_texel_img(const pn_mc_ctx *m, float px, float py, int *outside)
{
    return m->nb + pn_mc_texel_at(m, px, py, outside);
}
PN_KFN PN_CONST float *pn_mc_texel(const pn_mc_ctx *m, pn_v3 p, int *outside)
{
    float px, py;
    pn_mc_proj(m, p, &px, &py);
    return pn_mc_texel_img(m, px, py, outside);
}

/* Whether level-0 texel T is stacked: not empty, its max near +inf (pn_mc_band: two
 * entries or more along its ray, so its one interval [near, far] may hold gaps between
 * solids that the layers take as solid). */
PN_KFN int pn_mc_stacked_texel(PN_CONST float *T) { return T[2] == PN_KINF && T[0] > -PN_KINF; }

/* A ray blocked at light-frame point p: marks the pixel when p's texel is stacked. */
PN_KFN void pn_mc_block_at(pn_mc_ctx *m, pn_v3 p)
{
    int out;
    PN_CONST float *T = pn_mc_texel(m, p, &out);
    if (!out && pn_mc_stacked_texel(T)) m->stacked = 1u;
}

/* Third layer (Algorithm 1): whether the light-frame point p, inside a texel's interval
 * [near, far] of depth thickness `thick`, is empty space as the eye sees it: in front of
 * the G-buffer's depth at every pixel of the 3 x 3 around its image (or over the
 * background). Two guards keep it from clearing an occluder. The neighbourhood: an occluder
 * thinner than a pixel, or its edge between p and p's pixel centre, still counts. The
 * thickness: an interval thinner than its texel is wide at p's depth is never cleared. A
 * sheet's depth there is the one at the texel's centre; where the ray crosses the sheet
 * within the texel, p may stand in front of the surface the eye sees by less than that
 * rounding (the built-in room's chair shells, thin's slivers). */
PN_KFN int pn_mc_seen(const pn_mc_ctx *m, pn_v3 p, float thick)
{
    const pn_kview *v = m->view;
    pn_v3 X, cam, rel;
    float px, py, dd = PN_KINF;
    uint32_t ix, iy, x0, x1, y0, y1, xx, yy;
    if (!(thick >= 2.0f * (p.z + m->mc->d) * pn_kmaxf(m->tx, m->ty) / (float)m->mc->res)) return 0;
    X = pn_v3_make(m->L->c[0] + p.x * m->lv->r[0] + p.y * m->lv->u[0] + p.z * m->lv->f[0],
                   m->L->c[1] + p.x * m->lv->r[1] + p.y * m->lv->u[1] + p.z * m->lv->f[1],
                   m->L->c[2] + p.x * m->lv->r[2] + p.y * m->lv->u[2] + p.z * m->lv->f[2]);
    cam = pn_to_camera(v, X);
    if (!(cam.z > v->znear)) return 0;
    pn_project_camera(v, cam, &px, &py);
    if (!(px >= 0.0f && py >= 0.0f && px < (float)v->width && py < (float)v->height)) return 0;
    ix = (uint32_t)pn_kfloor_clamp(px, 0, (int32_t)v->width - 1);
    iy = (uint32_t)pn_kfloor_clamp(py, 0, (int32_t)v->height - 1);
    x0 = ix > 0u ? ix - 1u : 0u;
    x1 = ix + 1u < v->width ? ix + 1u : ix;
    y0 = iy > 0u ? iy - 1u : 0u;
    y1 = iy + 1u < v->height ? iy + 1u : iy;
    for (yy = y0; yy <= y1; yy++)
        for (xx = x0; xx <= x1; xx++) dd = pn_kminf(dd, m->depth[(size_t)yy * v->width + xx]);
    rel = pn_v3_sub(X, pn_view_eye(v));
    return pn_v3_dot(rel, rel) < dd * dd * 0.9998f;
}

/* Where a point stands against its texel's interval. */
#define PN_MC_FRONT 0
#define PN_MC_INSIDE 1
#define PN_MC_BEHIND 2
/* ...of the level-0 texel at offset `at` (pn_mc_texel_at; out: beyond the map) */
PN_KFN int pn_mc_state_at(const pn_mc_ctx *m, pn_v3 p, uint32_t at, int out)
{
    float T[PN_NB_MM];
    pn_nb_mm_get(m->nb + at, T);
    if (out) return PN_MC_FRONT;
    if (m->mc->layers == 1u) return p.z >= T[0] ? PN_MC_INSIDE : PN_MC_FRONT;
    if (p.z < T[0]) return PN_MC_FRONT;
    if (p.z > T[1]) return PN_MC_BEHIND;
    if (m->mc->layers == 3u && pn_mc_seen(m, p, T[1] - T[0])) return PN_MC_FRONT;
    return PN_MC_INSIDE;
}
/* ...of the texel holding image (px, py) */
PN_KFN int pn_mc_state_img(const pn_mc_ctx *m, pn_v3 p, float px, float py)
{
    int out;
    uint32_t at = pn_mc_texel_at(m, px, py, &out);
    return pn_mc_state_at(m, p, at, out);
}
PN_KFN int pn_mc_state(const pn_mc_ctx *m, pn_v3 p)
{
    float px, py;
    pn_mc_proj(m, p, &px, &py);
    return pn_mc_state_img(m, p, px, py);
}

PN_KFN int pn_mc_same_texel(const pn_mc_ctx *m, pn_v3 a, pn_v3 b)
{
    int oa, ob;
    return pn_mc_texel(m, a, &oa) == pn_mc_texel(m, b, &ob) && !oa && !ob;
}

/* Linear search over [t0, t1] (§3.3): 1 when blocked. */
PN_KFN int pn_mc_linear(pn_mc_ctx *m, const pn_mc_ray *r, float t0, float t1)
{
    float ax, ay, bx, by, w0 = t0 * r->ze + m->mc->d, w1 = t1 * r->ze + m->mc->d, tp = t0;
    uint32_t n, i, k;
    int sp = PN_MC_FRONT;
    pn_mc_proj(m, pn_mc_at(r, t0), &ax, &ay);
    pn_mc_proj(m, pn_mc_at(r, t1), &bx, &by);
    n = (uint32_t)pn_kceil_clamp(pn_kmaxf(pn_kfabs(bx - ax), pn_kfabs(by - ay)), 1, (int32_t)PN_MC_STEP_CAP(m->mc->res));
    for (i = 0; i <= n; i++) {
        /* Texel-uniform steps: the fraction q of the image segment is the fraction
         * q w0 / (q w0 + (1 - q) w1) of the ray (w: depth from the centre of projection). */
        float q = (float)i / (float)n, den = q * w0 + (1.0f - q) * w1;
        float t = den > 0.0f ? t0 + (t1 - t0) * (q * w0 / den) : t0 + (t1 - t0) * q;
        int s = pn_mc_state(m, pn_mc_at(r, t));
        m->steps++;
        if (s == PN_MC_INSIDE) {
            pn_mc_block_at(m, pn_mc_at(r, t));
            return 1;
        }
        if (i > 0u && s != sp) {
            /* Refine the transition (in front <-> behind). */
            float ta = tp, tb = t;
            for (k = 0; k < PN_MC_BISECT; k++) {
                float tm = 0.5f * (ta + tb);
                int sm = pn_mc_state(m, pn_mc_at(r, tm));
                m->steps++;
                if (sm == PN_MC_INSIDE) {
                    pn_mc_block_at(m, pn_mc_at(r, tm));
                    return 1;
                }
                if (sm == sp)
                    ta = tm;
                else
                    tb = tm;
            }
            if (sp == PN_MC_FRONT && pn_mc_same_texel(m, pn_mc_at(r, ta), pn_mc_at(r, tb))) {
                pn_mc_block_at(m, pn_mc_at(r, ta));
                return 1;
            }
        }
        sp = s;
        tp = t;
    }
    return 0;
}

/* The ray parameter where its image crosses texel column X (row Y): the image's x is
 * (x / ((z + d) tx) + 1) res / 2 and y is (1 - y / ((z + d) ty)) res / 2. +inf if never. */
PN_KFN float pn_mc_t_col(const pn_mc_ctx *m, const pn_mc_ray *r, float X)
{
    float k = (2.0f * X / (float)m->mc->res - 1.0f) * m->tx, den = (r->xe - r->xs) - k * r->ze;
    return den != 0.0f ? (k * m->mc->d - r->xs) / den : PN_KINF;
}
PN_KFN float pn_mc_t_row(const pn_mc_ctx *m, const pn_mc_ray *r, float Y)
{
    float k = (1.0f - 2.0f * Y / (float)m->mc->res) * m->ty, den = (r->ye - r->ys) - k * r->ze;
    return den != 0.0f ? (k * m->mc->d - r->ys) / den : PN_KINF;
}

/* Hierarchical search over [t0, t1] (Algorithm 2): 1 when blocked. */
PN_KFN int pn_mc_hier(pn_mc_ctx *m, const pn_mc_ray *r, float t0, float t1)
{
    const pn_kmc *mc = m->mc;
    float ax, ay, bx, by, dx, dy, t = t0;
    float on_edge = (float)mc->res * PN_MC_ON_EDGE_REL;
    uint32_t l = 0u, iter, cap = PN_MC_STEP_CAP(mc->res);
    pn_mc_proj(m, pn_mc_at(r, t0), &ax, &ay);
    pn_mc_proj(m, pn_mc_at(r, t1), &bx, &by);
    dx = bx - ax;
    dy = by - ay;
    /* One level below a box that holds the whole image (the early-out looked that up). */
    while (l + 1u < mc->levels && (float)(1u << l) < pn_kmaxf(pn_kfabs(dx), pn_kfabs(dy))) l++;
    if (l > 0u) l--;
    if (!(t0 < t1)) return pn_mc_state(m, pn_mc_at(r, t0)) == PN_MC_INSIDE; /* one point */
    for (iter = 0; iter < cap; iter++) {
        float px, py, te, zlo, zhi, step, v[PN_NB_MM];
        int32_t B, X0, Y0;
        int hit;
        if (!(t < t1)) return 0;
        pn_mc_proj(m, pn_mc_at(r, t), &px, &py);
        B = 1 << l;
        /* The box of side B holding the current point and reaching toward the ray's end.
         * The point's texel is floor(p) in either direction: toward -x, a point exactly on
         * x = 40 is still in texel 40 (its exit below says whether it has left it); as the
         * box [40 - B, 40) it left texel 40 out where a descent put the point there by
         * rounding before the texel's exit (fuzz_culls: crash-mcsm-texel-side-1). A point
         * within the on-edge band past the side it entered that texel by, whose crossing
         * of that side (from the ray's parameter, as its exits below) is still ahead, is
         * in the texel behind: a descent to depth 1.1371279 put a point 3e-6 texels before
         * row 57 on it, and the search skipped row 56, where the ray reaches the near
         * depth (crash-mcsm-texel-side-behind). */
        X0 = pn_kfloor_clamp(px, -(1 << 24), 1 << 24);
        Y0 = pn_kfloor_clamp(py, -(1 << 24), 1 << 24);
        if (dx > 0.0f && px - (float)X0 < on_edge && pn_mc_t_col(m, r, (float)X0) > t) X0--;
        if (dx < 0.0f && (float)(X0 + 1) - px < on_edge && pn_mc_t_col(m, r, (float)(X0 + 1)) > t) X0++;
        if (dy > 0.0f && py - (float)Y0 < on_edge && pn_mc_t_row(m, r, (float)Y0) > t) Y0--;
        if (dy < 0.0f && (float)(Y0 + 1) - py < on_edge && pn_mc_t_row(m, r, (float)(Y0 + 1)) > t) Y0++;
        X0 += dx >= 0.0f ? 0 : 1 - B;
        Y0 += dy >= 0.0f ? 0 : 1 - B;
        /* Where the ray leaves the box. A point rounded onto the box's far side (its exit
         * not after it) belongs to the next box along that axis; if rounding still leaves
         * no exit after it, the search moves on by a step that float can represent. */
        step = pn_kmaxf((t1 - t0) * PN_MC_T_STEP, t * PN_MC_T_SLACK);
        te = t1;
        if (dx != 0.0f) {
            float xb = (float)(dx > 0.0f ? X0 + B : X0), tc = pn_mc_t_col(m, r, xb);
            if (!(tc > t) && pn_kfabs(px - xb) < on_edge) {
                X0 += dx > 0.0f ? 1 : -1;
                tc = pn_mc_t_col(m, r, (float)(dx > 0.0f ? X0 + B : X0));
            } else if (!(tc > t)) {
                tc = PN_KINF; /* the image never reaches that side (it tends to a vanishing point) */
            }
            te = pn_kminf(te, tc > t ? tc : t + step);
        }
        if (dy != 0.0f) {
            float yb = (float)(dy > 0.0f ? Y0 + B : Y0), tr = pn_mc_t_row(m, r, yb);
            if (!(tr > t) && pn_kfabs(py - yb) < on_edge) {
                Y0 += dy > 0.0f ? 1 : -1;
                tr = pn_mc_t_row(m, r, (float)(dy > 0.0f ? Y0 + B : Y0));
            } else if (!(tr > t)) {
                tr = PN_KINF;
            }
            te = pn_kminf(te, tr > t ? tr : t + step);
        }
        pn_nb_mm_box(m->nb, &m->nb_lay, l, X0, Y0, v);
        m->steps++;
        zlo = t * r->ze;
        zhi = te * r->ze;
        hit = mc->layers == 1u ? zhi >= v[0] : (zhi >= v[0] && zlo <= v[1]);
        if (hit && l == 0u && (X0 < 0 || Y0 < 0 || X0 >= (int32_t)mc->res || Y0 >= (int32_t)mc->res))
            hit = 0; /* a texel beyond the map: nothing is known there */
        if (hit) {
            if (l == 0u) {
                if (mc->layers == 3u) {
                    /* The ray's part inside the interval, at its ends and middle: the eye
                     * must see all three as empty (its middle alone let the tree's leaves
                     * leak) */
                    float a = pn_kmaxf(t, v[0] / r->ze), b = pn_kminf(te, v[1] / r->ze), th = v[1] - v[0];
                    if (pn_mc_seen(m, pn_mc_at(r, 0.5f * (a + b)), th) && pn_mc_seen(m, pn_mc_at(r, a), th) &&
                        pn_mc_seen(m, pn_mc_at(r, b), th)) {
                        t = te;
                        if (l + 1u < mc->levels) l++;
                        continue;
                    }
                }
                if (pn_mc_stacked_texel(m->nb + ((uint32_t)Y0 * mc->res + (uint32_t)X0) * PN_NB_MM)) m->stacked = 1u;
                return 1;
            }
            /* No point of the ray before depth min near can be inside. */
            t = pn_kmaxf(t, v[0] / r->ze * (1.0f - PN_MC_T_SLACK));
            l--;
        } else {
            t = te;
            if (l + 1u < mc->levels) l++;
        }
    }
    m->capped++;
    return 0;
}

/* Bounds of the layers over the texel box around two image points (one texel of margin
 * for rounding). Texels beyond the map are empty (the window holds every occluder): they
 * leave the smallest near and largest far depths as they are and make the largest near
 * depth +inf, as an empty texel of the map does. pn_mc_region_at: where the lookup reads
 * (pn_nb_mm_rect_at's boxes and their level) and whether the box reaches beyond the map. The image
 * coordinates are clamped to [-(res + 2), res + 2] before their conversion: a side beyond
 * the map only counts as beyond it (*beyond compares with 0 and res, pn_nb_mm_rect_at
 * clamps to [0, res], a box wholly beyond is empty either way), so every bound past res + 1
 * gives the same lookup; one the compiler cannot fold to a constant keeps GCC's loop over
 * eight rays vectorized (with constant bounds it keeps a branch there). */
PN_KFN uint32_t pn_mc_region_at(const pn_mc_ctx *m, float ax, float ay, float bx, float by, uint32_t *at, uint32_t *lev,
                                int *beyond)
{
    int32_t R = (int32_t)m->mc->res, lim = R + 2;
    int32_t x0 = pn_kfloor_clamp(pn_kminf(ax, bx), -lim, lim) - 1, y0 = pn_kfloor_clamp(pn_kminf(ay, by), -lim, lim) - 1;
    int32_t x1 = pn_kceil_clamp(pn_kmaxf(ax, bx), -lim, lim) + 1, y1 = pn_kceil_clamp(pn_kmaxf(ay, by), -lim, lim) + 1;
    *beyond = (x0 < 0) | (y0 < 0) | (x1 > R) | (y1 > R);
    return pn_nb_mm_rect_at(&m->nb_lay, x0, y0, x1, y1, at, lev);
}
/* The bounds of a region whose boxes pn_mc_region_at gave. */
PN_KFN void pn_mc_region_get(const pn_mc_ctx *m, const uint32_t *at, uint32_t n, uint32_t lev, int beyond, float *v)
{
    pn_nb_mm_rect_get(m->nb, &m->nb_lay, at, n, lev, v);
    if (beyond) v[2] = PN_KINF;
}
PN_KFN void pn_mc_region(const pn_mc_ctx *m, float ax, float ay, float bx, float by, float *v)
{
    uint32_t at[4], n, lev;
    int beyond;
    n = pn_mc_region_at(m, ax, ay, bx, by, at, &lev, &beyond);
    pn_mc_region_get(m, at, n, lev, beyond, v);
}

/* The box, in continuous texel coordinates b = {x0, y0, x1, y1}, that the images of the
 * rays from every point of the light to the light-frame point E (image ex, ey) stay in from
 * depth zb on (0 <= zb < E.z): eq. 3.3's region, the light's section at zb, sfac
 * (ze - zb) / (ze (zb + d)) by sfac_y (ze - zb) / (ze (zb + d)) texels around the image of
 * E's segment to the light centre at that depth, and E's image. A ray's image is a segment
 * from its point at zb to E's image, so the rays fill the hull of the two. The section
 * holds E's image when E lies in eq. 3.1's frustum (|E.x| / (ze + d) <= ha / d, and so for
 * y); an origin the window had to leave out (beyond PN_LVIEW_TAN_MAX) does not, and its
 * image widens the box. The two sides differ: the window fitted to the occluders narrows
 * tx and ty apart (one side for both let rays out of a region: 8 of bunny's pixels at
 * 512x512, one layer, lit where its rays are blocked; test_mcsm checks the box over random
 * windows and rays). */
PN_KFN void pn_mc_reach(const pn_mc_ctx *m, pn_v3 E, float ex, float ey, float zb, float *b)
{
    const pn_kmc *mc = m->mc;
    float ze = E.z, den = ze * (zb + mc->d), sx = mc->sfac * (ze - zb) / den, sy = mc->sfac_y * (ze - zb) / den;
    float cx, cy, fr = zb / ze;
    pn_mc_proj(m, pn_v3_make(E.x * fr, E.y * fr, zb), &cx, &cy);
    b[0] = pn_kminf(cx - 0.5f * sx, ex);
    b[1] = pn_kminf(cy - 0.5f * sy, ey);
    b[2] = pn_kmaxf(cx + 0.5f * sx, ex);
    b[3] = pn_kmaxf(cy + 0.5f * sy, ey);
}

/* Narrows [t0, t1] to the part of ray r whose image lies within the map widened by
 * PN_MC_CLIP_TEXELS on each side: beyond the map lies no occluder (the window holds their
 * box), so the searches need not walk there. Per side, x(t) - k (t z_E + d) <= 0 with
 * k = +-tx (+-ty) is linear in t. Empty: t0 > t1. */
PN_KFN void pn_mc_clip_side(float a, float b, float *t0, float *t1)
{
    /* Selects, not branches (the pixel pass sets up eight rays in one loop the compilers
     * vectorize): b > 0 bounds t1, b < 0 bounds t0, and b = 0 (or NaN) with a > 0 leaves
     * nothing. The quotient is computed on every path and used on the first two. */
    float q = -a / b, lo = pn_kmaxf(*t0, q), hi = pn_kminf(*t1, q);
    int pos = b > 0.0f, neg = b < 0.0f, shut = !pos & !neg & (a > 0.0f);
    *t1 = pos ? hi : *t1;
    *t0 = neg ? lo : (shut ? PN_KINF : *t0);
}
PN_KFN void pn_mc_clip(const pn_mc_ctx *m, const pn_mc_ray *r, float *t0, float *t1)
{
    float g = 1.0f + 2.0f * PN_MC_CLIP_TEXELS / (float)m->mc->res, kx = m->tx * g, ky = m->ty * g, d = m->mc->d;
    float dx = r->xe - r->xs, dy = r->ye - r->ys;
    pn_mc_clip_side(r->xs - kx * d, dx - kx * r->ze, t0, t1);
    pn_mc_clip_side(-r->xs - kx * d, -dx - kx * r->ze, t0, t1);
    pn_mc_clip_side(r->ys - ky * d, dy - ky * r->ze, t0, t1);
    pn_mc_clip_side(-r->ys - ky * d, -dy - ky * r->ze, t0, t1);
}

/* The cosine of the angle between unit normal nrm and toc, the origin to the light centre
 * (1 for an origin at the centre). */
PN_KFN float pn_mc_cos(pn_v3 nrm, pn_v3 toc)
{
    float lt = pn_ksqrt(pn_v3_dot(toc, toc));
    return lt > 0.0f ? pn_v3_dot(nrm, toc) / lt : 1.0f;
}

/* The adaptive bias of eq. 3.2 for an origin at light depth ze with unit normal nrm and
 * toc, the origin to the light centre: half a texel's diagonal at the origin's depth
 * (bias_k (ze + d)), over the cosine of the angle to the light; -1 when that cosine is below
 * PN_MC_COS_MIN (the surface is grazed: no bias covers its texels; the exact fallback's). */
PN_KFN float pn_mc_bias(const pn_kmc *mc, pn_v3 nrm, pn_v3 toc, float ze)
{
    float cosv = pn_mc_cos(nrm, toc);
    if (cosv < PN_MC_COS_MIN) return -1.0f;
    if (mc->flags & PN_MC_F_NO_BIAS) return 0.0f;
    return mc->bias_k * (ze + mc->d) / pn_kmaxf(cosv, PN_MC_COS_MIN); /* the floor for a NaN cosine */
}

#endif
