/* pn_gears.c - host side of GEARS: the grid cameras (paper §4 A.1), grid bounds, and the
 * plan that splits a frame's (triangle, cell) pairs into tiles the pair pool can hold.
 * Port-independent: a port runs the per-pixel and per-triangle kernels of
 * kernels/pn_gears.h between these steps. */
#include <string.h>

#include "pn_gears_host.h"
#include "pn_kmath.h"

#if PN_ENABLE_GEARS

static void pn_set3(float *d, pn_v3 v)
{
    d[0] = v.x;
    d[1] = v.y;
    d[2] = v.z;
}

/* Area light: eye on the line from the centre of the box of origins and light corners to
 * the light centre, one light diagonal behind the light; axes U^, V^, N. */
uint32_t pn_gears_faces(const pn_klight *L, const float obox[6], float scene_diag, pn_kgrid faces[6])
{
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    uint32_t f;
    memset(faces, 0, 6u * sizeof(pn_kgrid));
    if (L->is_point) {
        /* A cube around the light: face f looks along +-x, +-y, +-z. */
        static const float axes[6][9] = {
            {0, 0, -1, 0, 1, 0, 1, 0, 0},  {0, 0, 1, 0, 1, 0, -1, 0, 0}, {1, 0, 0, 0, 0, -1, 0, 1, 0},
            {1, 0, 0, 0, 0, 1, 0, -1, 0},  {1, 0, 0, 0, 1, 0, 0, 0, 1},  {-1, 0, 0, 0, 1, 0, 0, 0, -1}};
        for (f = 0; f < 6; f++) {
            pn_kgrid *g = faces + f;
            pn_set3(g->eye, c);
            memcpy(g->ax, axes[f], 3u * sizeof(float));
            memcpy(g->ay, axes[f] + 3, 3u * sizeof(float));
            memcpy(g->az, axes[f] + 6, 3u * sizeof(float));
            g->near_depth = 1e-4f * scene_diag;
            if (!(g->near_depth > 0.0f)) g->near_depth = 1e-30f;
            g->face = f;
            g->is_point = 1;
        }
        return 6;
    } else {
        pn_kgrid *g = faces;
        pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
        pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
        pn_v3 N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
        pn_v3 lo = pn_v3_make(obox[0], obox[1], obox[2]), hi = pn_v3_make(obox[3], obox[4], obox[5]);
        pn_v3 mid, dir, E;
        float diag = 2.0f * pn_ksqrt(pn_v3_dot(U, U) + pn_v3_dot(V, V)), far = 0.0f, dn;
        uint32_t q;
        for (q = 0; q < 4; q++) { /* the light corners join the box */
            pn_v3 Lq = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, (q & 1u) ? 1.0f : -1.0f),
                                              pn_v3_scale(V, (q & 2u) ? 1.0f : -1.0f)));
            lo = pn_v3_make(pn_kminf(lo.x, Lq.x), pn_kminf(lo.y, Lq.y), pn_kminf(lo.z, Lq.z));
            hi = pn_v3_make(pn_kmaxf(hi.x, Lq.x), pn_kmaxf(hi.y, Lq.y), pn_kmaxf(hi.z, Lq.z));
        }
        mid = pn_v3_scale(pn_v3_add(lo, hi), 0.5f);
        dir = pn_v3_normalize(pn_v3_sub(c, mid));
        /* The eye must stay well behind the light plane so that the light plane has a
         * depth of at least a quarter diagonal (the paper's line can run almost parallel
         * to the light when the scene is off to its side). */
        dn = -pn_v3_dot(dir, N);
        if (!(dn >= 0.25f)) dir = pn_v3_normalize(pn_v3_sub(pn_v3_scale(dir, 1.0f), pn_v3_scale(N, 0.25f - dn + 0.01f)));
        if (!(-pn_v3_dot(dir, N) >= 0.2f)) dir = pn_v3_scale(N, -1.0f);
        E = pn_v3_add(c, pn_v3_scale(dir, diag));
        for (q = 0; q < 8; q++) {
            pn_v3 k = pn_v3_make((q & 1u) ? hi.x : lo.x, (q & 2u) ? hi.y : lo.y, (q & 4u) ? hi.z : lo.z);
            far = pn_kmaxf(far, pn_v3_dot(pn_v3_sub(k, E), N));
        }
        pn_set3(g->eye, E);
        pn_set3(g->ax, pn_v3_normalize(U));
        pn_set3(g->ay, pn_v3_normalize(V));
        pn_set3(g->az, N);
        g->far_depth = far;
        g->near_depth = pn_v3_dot(pn_v3_sub(c, E), N);
        return 1;
    }
}

/* Grid of `res` cells per axis over a projected box, widened a little so every origin
 * is strictly inside. */
void pn_gears_bounds(pn_kgrid *g, float x0, float y0, float x1, float y1, uint32_t res)
{
    float ex = x1 - x0, ey = y1 - y0, m;
    if (!(ex >= 0.0f) || !(ey >= 0.0f)) {
        x0 = y0 = -1.0f;
        ex = ey = 2.0f;
    }
    m = pn_kmaxf(pn_kmaxf(ex, ey), 1e-6f * pn_kmaxf(pn_kmaxf(x0 < 0 ? -x0 : x0, y0 < 0 ? -y0 : y0), 1.0f));
    ex = pn_kmaxf(ex, 1e-3f * m);
    ey = pn_kmaxf(ey, 1e-3f * m);
    g->gx0 = x0 - 1e-3f * ex;
    g->gy0 = y0 - 1e-3f * ey;
    g->inv_cell_x = (float)res / (ex * 1.002f);
    g->inv_cell_y = (float)res / (ey * 1.002f);
    g->res_x = res;
    g->res_y = res;
}

/* Tiles: runs of global grid rows (face * res + row) whose pairs fit the pool; a row that
 * alone exceeds it is split into runs of its cells by pn_gears_split_row. */
uint32_t pn_gears_next_tile(const uint64_t *row_pairs, uint32_t rows, uint32_t start, uint64_t pool,
                            uint32_t *end_out)
{
    uint64_t sum = 0;
    uint32_t r = start;
    while (r < rows && sum + row_pairs[r] <= pool) {
        sum += row_pairs[r];
        r++;
    }
    *end_out = r; /* == start: row `start` alone exceeds the pool */
    return r > start;
}

#endif
