/* pn_passes_wedges.h - the penumbra wedges' passes:
 * their per-work-item entries and their part of
 * the pass list (PN_PASSES_*), composed by pn_passes.h, which includes this file after
 * the kernels it calls; see there for the entry signature and the list's columns. */
#ifndef PN_PASSES_WEDGES_H
#define PN_PASSES_WEDGES_H

/* ---- Penumbra wedges (pn_wedges.h; the frame is src/pn_wedges.c) -------------------------- */

#if PN_ENABLE_WEDGES
/* Triangle: how it casts, seen from the light centre. */
PN_KFN void pn_e_wg_cast(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    PN_POOL(uint32_t, wg_tcast)[t] =
        pn_wg_facing(&K->light, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), PN_POOL(const uint32_t, wg_tcomp), t);
}

/* Edge run: 1 when it is a silhouette (scanned next into slots). */
PN_KFN void pn_e_wg_sil_flag(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    (void)K;
    PN_POOL(uint32_t, wg_soff)[r] = pn_wg_run_winding(PN_POOL(const uint32_t, wg_hedge), PN_POOL(const uint32_t, wg_run),
                                                      PN_POOL(const uint32_t, wg_tcast), r) != 0;
}

/* Edge run that is a silhouette: its record, wedge tiles and pair count at its slot. */
PN_KFN void pn_e_wg_sil_make(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    PN_CONST uint32_t *off = PN_POOL(const uint32_t, wg_soff);
    if (off[r + 1u] == off[r]) return;
    pn_wg_sil_make(&K->view, &K->light, K->wg.hmax, PN_POOL(const float, tris), PN_POOL(const uint32_t, wg_hedge),
                   PN_POOL(const uint32_t, wg_run), PN_POOL(const uint32_t, wg_tcast), PN_POOL(const uint32_t, wg_tcomp), r,
                   off[r], PN_POOL(pn_wsil, wg_sil), PN_POOL(uint32_t, wg_poff));
}

/* Silhouette: its (tile, silhouette) pairs from its prefix-summed offset. */
PN_KFN void pn_e_wg_scatter(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t s)
{
    pn_wg_scatter(&K->view, &K->light, K->wg.hmax, PN_POOL(const float, tris), PN_POOL(const pn_wsil, wg_sil), s,
                  PN_POOL(const uint32_t, wg_poff)[s], PN_POOL(uint32_t, wg_pairs));
}

/* Pixel: its centre ray and its tile's wedges, blended object by object; times its
 * horizon's fraction. */
PN_KFN void pn_e_wg_pixel(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t id = PN_POOL(const uint32_t, tri_id)[pix], W = K->view.width, tile;
    PN_CONST uint32_t *toff = PN_POOL(const uint32_t, wg_toff);
    pn_v3 pos, nrm, O;
    float v;
    if (id == PN_NO_PIXEL_TRIANGLE) {
        PN_POOL(float, vis)[pix] = 1.0f;
        return;
    }
    pos = pn_v3_load(PN_POOL(const float, pos) + (size_t)pix * 3u);
    nrm = pn_v3_load(PN_POOL(const float, nrm) + (size_t)pix * 3u);
    if (!pn_shadow_origin(pos, nrm, &K->light, &O)) {
        PN_POOL(float, vis)[pix] = 0.0f;
        return;
    }
    tile = (pix / W / PN_WG_TILE) * K->wg.tiles_x + (pix % W) / PN_WG_TILE;
    v = pn_wg_pixel(O, id, &K->light, K->wg.mode, PN_POOL(const float, tris), PN_POOL(const pn_kbvh_node, nodes),
                    PN_POOL(const pn_kbvh4, wnodes), PN_POOL(const uint32_t, index), PN_POOL(const uint32_t, wg_tcomp), PN_POOL(const pn_wsil, wg_sil),
                    PN_POOL(const uint32_t, wg_sorted), toff[tile], toff[tile + 1u], &c);
    if (v > 0.0f) {
        uint32_t m[PN_MASK_WORDS_MAX];
        pn_horizon H;
        pn_mask_clear(m);
        pn_horizon_of(pos, nrm, id, PN_POOL(const float, tris), &K->light, &H);
        pn_horizon_mask(&H, &K->light, m);
        v = v * pn_mask_visibility(m, K->light.k);
    }
    PN_POOL(float, vis)[pix] = v;
    c.lit = 1u;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / W].c, &c);
}
#endif

/* Their part of the list. */
#if PN_ENABLE_WEDGES
#define PN_PASSES_WEDGES(X)                               \
    X(WG_CAST, wg_cast, 64, 4096)                         \
    X(WG_SIL_FLAG, wg_sil_flag, 64, 4096)                 \
    X(WG_SIL_MAKE, wg_sil_make, 64, 1024)                 \
    X(WG_SCATTER, wg_scatter, 64, 1024)                   \
    X(WG_PIXEL, wg_pixel, 16, 1024)
#else
#define PN_PASSES_WEDGES(X)
#endif

#endif
