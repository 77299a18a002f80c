/* pn_lview.c - the light view's frame, shared by the light-space algorithms (selective ray
 * tracing's map, the occlusion textures' slices; kernels/pn_lview.h has its passes). */
#include <string.h>

#include "pn_internal.h"
#include "pn_kmath.h"
#include "pn_lview.h"

typedef char pn_lview_box_agrees[PN_LVIEW_BOX_FLOATS == 8u ? 1 : -1];

static void pn_set3(float *d, pn_v3 v)
{
    d[0] = v.x;
    d[1] = v.y;
    d[2] = v.z;
}

void pn_light_view(const pn_context *ctx, const pn_klight *L, uint32_t res, pn_kview *lv)
{
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]), f, r, u;
    memset(lv, 0, sizeof(*lv));
    pn_set3(lv->eye, c);
    if (!L->is_point) {
        f = pn_v3_make(L->N[0], L->N[1], L->N[2]);
        r = pn_v3_normalize(pn_v3_make(L->U[0], L->U[1], L->U[2]));
        u = pn_v3_normalize(pn_v3_make(L->V[0], L->V[1], L->V[2]));
    } else {
        pn_v3 mid = pn_v3_make(0.5f * (ctx->scene_min[0] + ctx->scene_max[0]), 0.5f * (ctx->scene_min[1] + ctx->scene_max[1]),
                               0.5f * (ctx->scene_min[2] + ctx->scene_max[2]));
        pn_v3 up = pn_v3_make(0.0f, 1.0f, 0.0f);
        f = pn_v3_normalize(pn_v3_sub(mid, c));
        if (!(pn_v3_dot(f, f) > 0.5f)) f = pn_v3_make(0.0f, -1.0f, 0.0f);
        if (f.y > 0.9f || f.y < -0.9f) up = pn_v3_make(1.0f, 0.0f, 0.0f);
        r = pn_v3_normalize(pn_v3_cross(f, up));
        u = pn_v3_cross(r, f);
    }
    pn_set3(lv->f, f);
    pn_set3(lv->r, r);
    pn_set3(lv->u, u);
    lv->tan_half = 1.0f;
    lv->aspect = 1.0f;
    lv->znear = 1e-5f * ctx->scene_diag;
    if (!(lv->znear > 0.0f)) lv->znear = 1e-30f;
    lv->width = res;
    lv->height = res;
}

void pn_light_halves(const pn_klight *L, float *ha, float *hb)
{
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]), V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    *ha = L->is_point ? 0.0f : pn_ksqrt(pn_v3_dot(U, U));
    *hb = L->is_point ? 0.0f : pn_ksqrt(pn_v3_dot(V, V));
}

int pn_lview_window(const pn_context *ctx, const float *box, uint32_t height, uint32_t res, const pn_klight *L, float ha,
                    float hb, pn_kview *lv, pn_lwin *w)
{
    float mx = 0.0f, my = 0.0f, zmax = 0.0f, tx, ty, d, grow = 1.0f + 4.0f / (float)res, diag = ctx->scene_diag;
    uint32_t y;
    for (y = 0; y < height; y++) {
        const float *b = box + (size_t)y * PN_LVIEW_BOX_FLOATS;
        mx = pn_kmaxf(mx, b[0]);
        my = pn_kmaxf(my, b[1]);
        zmax = pn_kmaxf(zmax, b[3]);
    }
    if (!(zmax > 0.0f)) return 0;
    if (!L->is_point) {
        float inv_d = pn_kmaxf(mx / ha, my / hb) * grow;
        float lo = 1.0f / (2.0f * diag), hi = PN_LVIEW_TAN_MAX / pn_kmaxf(ha, hb);
        if (!(inv_d >= lo)) inv_d = lo;
        if (!(inv_d <= hi)) inv_d = hi;
        d = 1.0f / inv_d;
        tx = ha * inv_d;
        ty = hb * inv_d;
    } else {
        tx = pn_kminf(pn_kmaxf(mx * grow, 1e-6f), PN_LVIEW_TAN_MAX);
        ty = pn_kminf(pn_kmaxf(my * grow, 1e-6f), PN_LVIEW_TAN_MAX);
        d = 0.0f;
    }
    {
        pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]), f = pn_v3_make(lv->f[0], lv->f[1], lv->f[2]);
        pn_v3 eye = pn_v3_sub(c, pn_v3_scale(f, d));
        pn_set3(lv->eye, eye);
    }
    lv->tan_half = ty;
    lv->aspect = tx / ty;
    lv->znear = d + 1e-5f * diag;
    if (!(lv->znear > 0.0f)) lv->znear = 1e-30f;
    w->d = d;
    w->zmax = zmax;
    w->tx = tx;
    w->ty = ty;
    return 1;
}

void pn_lview_fit_occluders(const pn_context *ctx, uint32_t res, const pn_klight *L, pn_kview *lv, pn_lwin *w)
{
    /* The box's corners in the light frame, then the polytope box n {z >= 0}: the corners in
     * front and the edges' crossings of the light plane. |x| / (z + d) is quasi-convex (its
     * sublevel sets are wedges), so its largest value over the polytope is at a vertex. */
    pn_v3 P[8];
    float mx = 0.0f, my = 0.0f, grow = 1.0f + 4.0f / (float)res, tx, ty;
    uint32_t i, b, any = 0u;
    if (L->is_point || !(w->d > 0.0f) || !(ctx->occ_min[0] <= ctx->occ_max[0])) return;
    for (i = 0; i < 8u; i++)
        P[i] = pn_lview_frame(lv, L, pn_v3_make((i & 1u) ? ctx->occ_max[0] : ctx->occ_min[0],
                                                (i & 2u) ? ctx->occ_max[1] : ctx->occ_min[1],
                                                (i & 4u) ? ctx->occ_max[2] : ctx->occ_min[2]));
    for (i = 0; i < 8u; i++) {
        if (P[i].z >= 0.0f) {
            mx = pn_kmaxf(mx, pn_kfabs(P[i].x) / (P[i].z + w->d));
            my = pn_kmaxf(my, pn_kfabs(P[i].y) / (P[i].z + w->d));
            any = 1u;
        }
        for (b = 1u; b < 8u; b <<= 1) {
            pn_v3 Q = P[i ^ b];
            if (P[i].z < 0.0f && Q.z >= 0.0f) {
                /* The edge's crossing of z = 0, depth d from the centre of projection. */
                float s = P[i].z / (P[i].z - Q.z);
                mx = pn_kmaxf(mx, pn_kfabs(P[i].x + s * (Q.x - P[i].x)) / w->d);
                my = pn_kmaxf(my, pn_kfabs(P[i].y + s * (Q.y - P[i].y)) / w->d);
            }
        }
    }
    if (!any) return; /* no occluder in front of the light (no corner in front, no crossing) */
    /* At most 256 times narrower than the window the origins asked for (which holds the
     * light's image: kernels/pn_mcsm.h PN_MC_CLIP_TEXELS counts on it). */
    tx = pn_kmaxf(mx * grow, w->tx * (1.0f / 256.0f));
    ty = pn_kmaxf(my * grow, w->ty * (1.0f / 256.0f));
    if (tx < w->tx) w->tx = tx;
    if (ty < w->ty) w->ty = ty;
    lv->tan_half = w->ty;
    lv->aspect = w->tx / w->ty;
}
