/* pn_mc_layers.h - Monte Carlo shadow maps, the depth layers: cleared rows, the occluders' rows pass and bands. Part of pn_mcsm.h, which
 * includes it after the constants it uses; see there. */
#ifndef PN_MC_LAYERS_H
#define PN_MC_LAYERS_H

/* ---- Layers ------------------------------------------------------------------------------ */

/* Texel row y of level 0 of view v emptied: near +inf, far -inf, no entry (the third
 * float counts the texel's entries while the layers are drawn: pn_mc_entry). */
PN_KFN void pn_mc_clear_row(const pn_kview *v, uint32_t y, PN_GLOBAL float *nb)
{
    uint32_t x;
    for (x = 0; x < v->width; x++) {
        PN_GLOBAL float *T = nb + ((size_t)y * v->width + x) * PN_NB_MM;
        T[0] = PN_KINF;
        T[1] = -PN_KINF;
        T[2] = pn_kbitsf(0u);
    }
}

/* Whether a triangle whose plane gives nA = n.(A - eye) (n in winding order) is a back face
 * seen from the light's view: nA > 0, or nA < 0 for a solid wound inside out
 * (PN_TRI_INVERTED), as the solid wound outward would give. */
PN_KFN int pn_mc_back(float nA, uint8_t flag) { return (flag & PN_TRI_INVERTED) ? nA < 0.0f : nA > 0.0f; }

/* Whether a fragment enters a solid along its texel's ray from the light: a front face, or
 * either face of a sheet (PN_TRI_SHEET: a solid of no thickness). A texel with two entries
 * or more holds more than one solid interval along that ray (two leaves, two flights of
 * stairs, the folds of a statue), which the layers' one interval [near, far] fills: the
 * gap between them is taken as solid (pn_mc_band marks the texel stacked). */
PN_KFN uint32_t pn_mc_entry(float nA, uint8_t flag) { return (flag & PN_TRI_SHEET) || !pn_mc_back(nA, flag); }

/* The layers' rows pass for group g of the n triangles (pn_raster_rows_group): a
 * receiver-only triangle covers nothing; a small one puts its fragments into level 0 here,
 * as the band would (pn_raster_tri_setup's plane, pn_raster_axial, the same centres), by
 * atomic min and max, and is then drawn by no band: set up once, not again in every band
 * it meets (at 512², half of CAD's band set-ups and most of the dragon's: its bands' work
 * went from 132 M to 20 M instructions). rows[t]: what the bands draw of t. */
PN_KFN void pn_mc_rows(const pn_kview *v, const pn_kmc *mc, PN_CONST float *tris, PN_CONST uint8_t *flags, uint32_t n,
                       uint32_t g, PN_GLOBAL uint32_t *rows, PN_GLOBAL float *nb)
{
    uint32_t r[PN_RASTER_GROUP], t0 = g * PN_RASTER_GROUP, count = pn_kminu(PN_RASTER_GROUP, n - t0), i, k;
    pn_raster_small sm[PN_RASTER_GROUP];
    pn_raster_rows_group(v, tris, flags, t0, count, PN_TRI_RECEIVER, r, sm);
    for (i = 0; i < count; i++) {
        PN_CONST float *p = tris + (size_t)(t0 + i) * 9u;
        pn_v3 nv;
        float nA;
        if (r[i] == PN_RASTER_EMPTY || sm[i].w == 0) {
            rows[t0 + i] = r[i];
            continue;
        }
        rows[t0 + i] = PN_RASTER_EMPTY;
        nA = pn_raster_plane(v, pn_v3_make(p[0], p[1], p[2]), pn_v3_make(p[3], p[4], p[5]), pn_v3_make(p[6], p[7], p[8]),
                             &nv);
        for (k = 0; k < PN_RASTER_ROWS_TEST; k++) {
            uint32_t x = (uint32_t)(sm[i].x0 + (int32_t)k % sm[i].w), y = (uint32_t)(sm[i].y0 + (int32_t)k / sm[i].w);
            PN_GLOBAL int32_t *T;
            float z;
            if (!(sm[i].mask & (1u << k)) || !pn_raster_axial(v, nv, nA, x, y, &z)) continue;
            z -= mc->d;
            if (!(z > 0.0f)) continue;
            T = (PN_GLOBAL int32_t *)(nb + ((size_t)y * v->width + x) * PN_NB_MM);
            pn_katomic_imin(T, (int32_t)pn_kfbits(z)); /* near: the layers hold z > 0 or +-inf */
            if (pn_mc_back(nA, flags[t0 + i])) pn_katomic_imax(T + 1, (int32_t)pn_kfbits(z)); /* far: back faces */
            if (pn_mc_entry(nA, flags[t0 + i])) pn_katomic_add((PN_GLOBAL uint32_t *)(T + 2), 1u);
        }
    }
}

/* Band `band` of PN_RASTER_BAND texel rows of level 0 (emptied, and holding the small
 * triangles' fragments, pn_mc_rows): every fragment of every other occluder (the band
 * walk's, pn_raster.h) in front of the light plane takes part in its texel's near, and a
 * back face's in its far, and an entry (pn_mc_entry) is counted; then far := max(far,
 * near) where the texel is not empty, max near := near, or +inf where the texel is stacked
 * (two entries or more, with two layers or three, unless PN_MC_F_NO_STACKED), and the
 * texel is stored as the N-buffer's (near negated). A stacked texel's +inf keeps every
 * region holding it from the umbra class (the test that the receiver lies behind every
 * near texel), and marks a ray the layers block there (pn_mc_stacked_texel). */
PN_KFN void pn_mc_band(const pn_kview *v, const pn_kmc *mc, PN_CONST float *tris, PN_CONST uint8_t *flags,
                       PN_CONST uint32_t *rows, PN_CONST uint32_t *chunks, PN_CONST uint32_t *index, uint32_t tri_n,
                       uint32_t band, PN_GLOBAL float *nb)
{
    uint32_t y0 = band * PN_RASTER_BAND, y1 = y0 + PN_RASTER_BAND - 1u, t, y, x;
    pn_band_walk bw;
    if (y1 >= v->height) y1 = v->height - 1u;
    pn_band_walk_begin(&bw, tri_n);
    while (pn_band_next(chunks, index, y0, y1, &bw, &t)) {
        pn_raster_tri rt;
        if (flags[t] & PN_TRI_RECEIVER) continue;
        if (!pn_raster_tri_setup(v, tris, rows, t, y0, y1, &rt)) continue;
        for (y = rt.y0; y <= rt.y1; y++) {
            int32_t xi, xa = rt.x0, xb = rt.x1;
            int run = pn_raster_span(&rt, y, &xa, &xb);
            for (xi = xa; xi <= xb; xi++) {
                float z;
                PN_GLOBAL float *T;
                if (!pn_raster_tri_axial(v, &rt, run, (uint32_t)xi, y, &z)) continue;
                z -= mc->d;
                if (!(z > 0.0f)) continue;
                T = nb + ((size_t)y * v->width + (uint32_t)xi) * PN_NB_MM;
                T[0] = pn_kminf(T[0], z);
                if (pn_mc_back(rt.nA, flags[t])) T[1] = pn_kmaxf(T[1], z); /* a back face */
                if (pn_mc_entry(rt.nA, flags[t])) T[2] = pn_kbitsf(pn_kfbits(T[2]) + 1u);
            }
        }
    }
    for (y = y0; y <= y1; y++)
        for (x = 0; x < v->width; x++) {
            PN_GLOBAL float *T = nb + ((size_t)y * v->width + x) * PN_NB_MM;
            uint32_t entries = pn_kfbits(T[2]);
            if (T[0] < PN_KINF) T[1] = pn_kmaxf(T[1], T[0]); /* far at least near */
            T[2] = mc->layers >= 2u && !(mc->flags & PN_MC_F_NO_STACKED) && entries >= 2u ? PN_KINF : T[0];
            T[0] = -T[0]; /* stored as the N-buffer holds it (pn_nbuffer.h) */
        }
}

#endif
