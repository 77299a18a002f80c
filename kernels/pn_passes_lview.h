/* pn_passes_lview.h - the light-space view's passes (SRT, the occlusion textures, MCSM):
 * their per-work-item entries and their part of
 * the pass list (PN_PASSES_*), composed by pn_passes.h, which includes this file after
 * the kernels it calls; see there for the entry signature and the list's columns. */
#ifndef PN_PASSES_LVIEW_H
#define PN_PASSES_LVIEW_H

/* ---- The light-space view (pn_lview.h): SRT's map and the occlusion textures' slices ---- */

#if PN_LIGHT_VIEW
/* Row: the light-frame extent of its lit origins. */
PN_KFN void pn_e_lview_bounds(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_lview_bounds_row(&K->lview, &K->light, K->lview_ha, K->lview_hb, K->view.width, y,
                        &S, PN_POOL(float, lview_box));
}

/* Group of triangles: the light-view rows each may cover (the G-buffer's set-up on the
 * light view). */
PN_KFN void pn_e_lmap_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t g)
{
    pn_raster_rows_item(&K->lview, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), K->tri_count, g,
                        PN_POOL(uint32_t, rows));
}
#endif

/* Their part of the list. */
#if PN_LIGHT_VIEW
#define PN_PASSES_LVIEW(X)                                \
    X(LVIEW_BOUNDS, lview_bounds, 1, 1)                   \
    X(LMAP_ROWS, lmap_rows, 64, 512)
#else
#define PN_PASSES_LVIEW(X)
#endif

#endif
