/* pn_shade.h - RGBA8 shading: albedo * (ambient + visibility * cos), cos taken toward the
 * light centre from the normal turned toward the eye; a gamma of 2 (square root, the one
 * correctly rounded transcendental both ports have) maps it to bytes. */
#ifndef PN_SHADE_H
#define PN_SHADE_H

#include "pn_kmath.h"
#include "pn_ktypes.h"
#include "pn_raster.h" /* pn_normal_ok */

PN_KFN uint32_t pn_to_byte(float v)
{
    float s;
    if (!(v > 0.0f)) return 0u;
    if (v >= 1.0f) return 255u;
    s = pn_ksqrt(v) * 255.0f + 0.5f;
    return (uint32_t)s > 255u ? 255u : (uint32_t)s;
}

PN_KFN uint32_t pn_shade_pixel(const pn_kview *v, const pn_klight *L, const pn_kshade *sh,
                               uint32_t tri, pn_v3 P, pn_v3 nrm, float vis)
{
    pn_v3 c, toL, toE;
    float cosl, rad;
    uint32_t g;
    if (tri == 0xFFFFFFFFu) return sh->background;
    c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    toE = pn_v3_sub(pn_v3_make(v->eye[0], v->eye[1], v->eye[2]), P);
    if (pn_v3_dot(nrm, toE) < 0.0f) nrm = pn_v3_scale(nrm, -1.0f);
    toL = pn_v3_sub(c, P);
    /* A point within ~2^-126 of the light centre has no direction to it in float. */
    toL = pn_normal_ok(toL) ? pn_v3_normalize(toL) : pn_v3_make(0.0f, 0.0f, 0.0f);
    cosl = pn_kmaxf(0.0f, pn_v3_dot(nrm, toL));
    rad = sh->albedo * (sh->ambient + vis * cosl);
    g = pn_to_byte(rad);
    return g | (g << 8) | (g << 16) | (0xFFu << 24);
}

#endif
