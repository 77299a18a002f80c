/* pn_passes_occtex.h - the occlusion textures' passes:
 * their per-work-item entries and their part of
 * the pass list (PN_PASSES_*), composed by pn_passes.h, which includes this file after
 * the kernels it calls; see there for the entry signature and the list's columns. */
#ifndef PN_PASSES_OCCTEX_H
#define PN_PASSES_OCCTEX_H

/* ---- Occlusion textures (pn_occtex.h; the frame is src/pn_occtex.c) ---------------------- */

#if PN_ENABLE_OCCTEX
/* Band of texel rows: every fragment's slice bits, and the depth map (in the filter pool). */
PN_KFN void pn_e_occ_band(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t band)
{
    pn_occ_band(&K->lview, &K->occ, PN_POOL(const float, tris), PN_POOL(const uint32_t, rows),
                PN_POOL(const uint32_t, chunks), PN_POOL(const uint32_t, rindex), K->raster_tris, band,
                PN_POOL(uint32_t, occ_bits), PN_POOL(float, occ_filt), PN_POOL(uint32_t, occ_words));
}

/* Texel: level 0 of the N-buffer or mipmap, the slice's bit. */
PN_KFN void pn_e_occ_level0(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t i)
{
    pn_occ_level0(&K->occ, PN_POOL(const uint32_t, occ_bits), i, PN_POOL(uint32_t, occ_filt));
}

/* Row of N-buffer level K->occ.level. */
PN_KFN void pn_e_occ_nbuf(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_occ_nbuf_row(&K->occ, y, PN_POOL(uint32_t, occ_filt));
}

/* Row of mipmap level K->occ.level. */
PN_KFN void pn_e_occ_mip(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_occ_mip_row(&K->occ, y, PN_POOL(uint32_t, occ_filt));
}

/* Summed-area table: row j's prefix sums, then a block of PN_OCC_SAT_COLS columns'. */
PN_KFN void pn_e_occ_sat_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t j)
{
    pn_occ_sat_row(&K->occ, PN_POOL(const uint32_t, occ_bits), j, PN_POOL(uint32_t, occ_filt));
}
PN_KFN void pn_e_occ_sat_cols(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t c)
{
    pn_occ_sat_cols(&K->occ, c, PN_POOL(uint32_t, occ_filt));
}

/* Pixel: visibility 1 (lit or background) or 0 (facing away, behind the light), counted. */
PN_KFN void pn_e_occ_init(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    pn_v3 O, Ps, ns;
    uint32_t id = PN_POOL(const uint32_t, tri_id)[pix];
    int lit;
    pn_pix_surf(A, P, K, pix, &Ps, &ns);
    lit = id != PN_NO_PIXEL_TRIANGLE && pn_shadow_origin(Ps, ns, &K->light, &O);
    PN_POOL(float, vis)[pix] = (id == PN_NO_PIXEL_TRIANGLE || lit) ? 1.0f : 0.0f;
    c.lit = lit ? 1u : 0u;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}

/* Pixel: slice K->occ.slice's occlusion combined into its visibility; for PN_OCC_SLICE_DEPTH,
 * the depth map's (pn_occ_own; the filter pool holds the map until the first slice's filter). */
PN_KFN void pn_e_occ_lookup(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_v3 O, Ps, ns;
    float I;
    int in;
    if (PN_POOL(const uint32_t, tri_id)[pix] == PN_NO_PIXEL_TRIANGLE) return;
    pn_pix_surf(A, P, K, pix, &Ps, &ns);
    if (!pn_shadow_origin(Ps, ns, &K->light, &O)) return;
    if (K->occ.slice == PN_OCC_SLICE_DEPTH) {
        I = pn_occ_own(&K->lview, &K->light, &K->occ, PN_POOL(const float, occ_filt), Ps, O, K->lview_ha,
                       K->lview_hb);
        in = 1;
    } else {
        in = pn_occ_slice_occlusion(&K->lview, &K->light, &K->occ, PN_POOL(const uint32_t, occ_filt), O, &I);
    }
    if (in && I > 0.0f) PN_POOL(float, vis)[pix] = pn_occ_combine(K->occ.combine, PN_POOL(const float, vis)[pix], I);
}

/* Pixel: times the fraction of light samples in front of its own plane; its lookups (the
 * slices looked up that weighed in) counted as candidates. An origin no window holds
 * (pn_lview_outside: its occluders are not in the slices) takes the exact fallback
 * instead (counted as exact). */
PN_KFN void pn_e_occ_finish(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    uint32_t m[PN_MASK_WORDS_MAX], id = PN_POOL(const uint32_t, tri_id)[pix];
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    pn_v3 pos, nrm, O;
    pn_horizon H;
    if (id == PN_NO_PIXEL_TRIANGLE) return;
    pn_pix_surf(A, P, K, pix, &pos, &nrm);
    if (!pn_shadow_origin(pos, nrm, &K->light, &O)) return;
    if (pn_lview_outside(pn_lview_frame(&K->lview, &K->light, O), K->lview_ha, K->lview_hb)) {
        PN_POOL(float, vis)[pix] = pn_reference_fallback(pos, nrm, id, PN_POOL(const float, tris), PN_POOL(const pn_kbvh4, wnodes),
                                                         PN_POOL(const uint32_t, index), &K->light, &c);
        pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
        return;
    }
    pn_mask_clear(m);
    pn_horizon_of(pos, nrm, id, PN_POOL(const float, tris), &K->light, &H);
    if (pn_horizon_mask(&H, &K->light, m))
        PN_POOL(float, vis)[pix] = PN_POOL(const float, vis)[pix] * pn_mask_visibility(m, K->light.k);
    c.candidates = pn_occ_lookups(&K->lview, &K->light, &K->occ, O);
    if (c.candidates) pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}
#endif

/* Their part of the list. */
#if PN_ENABLE_OCCTEX
#define PN_PASSES_OCCTEX(X)                               \
    X(OCC_BAND, occ_band, 1, 1)                           \
    X(OCC_LEVEL0, occ_level0, 64, 4096)                   \
    X(OCC_NBUF, occ_nbuf, 4, 8)                           \
    X(OCC_MIP, occ_mip, 4, 8)                             \
    X(OCC_SAT_ROWS, occ_sat_rows, 1, 1)                   \
    X(OCC_SAT_COLS, occ_sat_cols, 1, 1)                   \
    X(OCC_INIT, occ_init, 64, 4096)                       \
    X(OCC_LOOKUP, occ_lookup, 64, 1024)                   \
    X(OCC_FINISH, occ_finish, 64, 1024)
#else
#define PN_PASSES_OCCTEX(X)
#endif

#endif
