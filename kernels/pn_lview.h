/* pn_lview.h - the light-space view the light-space algorithms share (selective ray
 * tracing's shadow map, the occlusion textures' slices): a pn_kview (K->lview) with the
 * light's frame as axes, rasterized by the G-buffer's own code (pn_raster.h), and the row
 * bounds of the G-buffer's shadow-ray origins in that frame, from which src/ sizes the
 * view's window. */
#ifndef PN_LVIEW_H
#define PN_LVIEW_H

#include "pn_raster.h"
#include "pn_reference.h"

/* Largest window half-extent in tan units (76 degrees off the axis); origins beyond it
 * are left out of the window (and counted). */
#define PN_LVIEW_TAN_MAX 4.0f
/* Floats per row of the bounds pool. */
#define PN_LVIEW_BOX 8u
/* Pixels per run of pn_lview_bounds_row. */
#define PN_LVIEW_RUN 16u

/* Point X in the light frame: relative to the light centre, along lv's axes r, u, f. */
PN_KFN pn_v3 pn_lview_frame(const pn_kview *lv, const pn_klight *L, pn_v3 X)
{
    pn_v3 rel = pn_v3_sub(X, pn_v3_make(L->c[0], L->c[1], L->c[2]));
    return pn_v3_make(pn_v3_dot(rel, pn_v3_make(lv->r[0], lv->r[1], lv->r[2])),
                      pn_v3_dot(rel, pn_v3_make(lv->u[0], lv->u[1], lv->u[2])),
                      pn_v3_dot(rel, pn_v3_make(lv->f[0], lv->f[1], lv->f[2])));
}

/* Whether a window can hold an origin at light-frame depth z (relative to the light centre)
 * whose tans off the axis, past the light's half-extents, are tx = (|x| - ha) / z and
 * ty = (|y| - hb) / z: in front of the light plane and within PN_LVIEW_TAN_MAX. */
PN_KFN int pn_lview_held(float tx, float ty, float z) { return z > 0.0f && tx <= PN_LVIEW_TAN_MAX && ty <= PN_LVIEW_TAN_MAX; }

/* Whether no window holds origin E (in the light frame, pn_lview_frame; ha, hb the light's
 * half-extents): the light-space algorithms see no occluder of it, and resolve it exactly
 * (pn_reference_fallback). The same tans as pn_lview_bounds_row, which counts them. */
PN_KFN int pn_lview_outside(pn_v3 E, float ha, float hb)
{
    return !pn_lview_held(((E.x < 0.0f ? -E.x : E.x) - ha) / E.z, ((E.y < 0.0f ? -E.y : E.y) - hb) / E.z, E.z);
}

/* Row y of the G-buffer: over its lit pixels (origins in front of the light), with (x, y,
 * z) an origin in lv's frame relative to the light centre lc (so the view's eye may sit
 * behind it): the largest (|x| - ha) / z and (|y| - hb) / z (ha = hb = 0: the tan of the
 * angle off the axis) and the smallest z over the origins a window can hold
 * (pn_lview_held), and the largest z over all with z > 0:
 * box[y * PN_LVIEW_BOX ..] = {x, y, min z, max z}. */
PN_KFN void pn_lview_bounds_row(const pn_kview *lv, const pn_klight *L, float ha, float hb, uint32_t width, uint32_t y,
                                const pn_ksurf *S, PN_GLOBAL float *box)
{
    float ax = 0.0f, ay = 0.0f, zmin = PN_KINF, zmax = 0.0f;
    pn_v3 lc = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    pn_v3 r = pn_v3_make(lv->r[0], lv->r[1], lv->r[2]), u = pn_v3_make(lv->u[0], lv->u[1], lv->u[2]);
    pn_v3 f = pn_v3_make(lv->f[0], lv->f[1], lv->f[2]);
    uint32_t x0;
    /* Runs of PN_LVIEW_RUN pixels: every pixel's origin and its tans in a loop with no
     * branch (vectorized), then the bounds taken in pixel order, as one loop would. */
    for (x0 = 0; x0 < width; x0 += PN_LVIEW_RUN) {
        uint32_t n = width - x0 < PN_LVIEW_RUN ? width - x0 : PN_LVIEW_RUN, i;
        float lx[PN_LVIEW_RUN], ly[PN_LVIEW_RUN], lz[PN_LVIEW_RUN];
        int sees[PN_LVIEW_RUN];
        size_t pix = (size_t)y * width + x0;
        for (i = 0; i < n; i++) {
            pn_v3 O, rel, P, nv;
            float cx, cy, cz;
            pn_surf_at(S, pix + i, &P, &nv);
            sees[i] = pn_shadow_origin(P, nv, L, &O);
            rel = pn_v3_sub(O, lc);
            cx = pn_v3_dot(rel, r);
            cy = pn_v3_dot(rel, u);
            cz = pn_v3_dot(rel, f);
            lx[i] = ((cx < 0.0f ? -cx : cx) - ha) / cz;
            ly[i] = ((cy < 0.0f ? -cy : cy) - hb) / cz;
            lz[i] = cz;
        }
        for (i = 0; i < n; i++) {
            float cz = lz[i], tx = lx[i], ty = ly[i];
            if (S->tri_id[pix + i] == 0xFFFFFFFFu || !sees[i]) continue;
            if (!(cz > 0.0f)) continue;
            zmax = pn_kmaxf(zmax, cz);
            if (!pn_lview_held(tx, ty, cz)) continue;
            ax = pn_kmaxf(ax, tx);
            ay = pn_kmaxf(ay, ty);
            zmin = pn_kminf(zmin, cz);
        }
    }
    box[(size_t)y * PN_LVIEW_BOX + 0u] = ax;
    box[(size_t)y * PN_LVIEW_BOX + 1u] = ay;
    box[(size_t)y * PN_LVIEW_BOX + 2u] = zmin;
    box[(size_t)y * PN_LVIEW_BOX + 3u] = zmax;
}

#endif
