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
        pn_wg_facing(&K->light, K->wg.front_g, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), PN_POOL(const uint32_t, wg_tcomp), t);
}

/* Edge run: 1 when it is a silhouette (scanned next into slots). */
PN_KFN void pn_e_wg_sil_flag(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    (void)K;
    PN_POOL(uint32_t, wg_soff)[r] = pn_wg_run_winding(PN_POOL(const uint32_t, wg_hedge), PN_POOL(const uint32_t, wg_run),
                                                      PN_POOL(const uint32_t, wg_tcast), r) != 0;
}

/* Edge run, in a band of silhouettes (the band of tiles wg.b*): 1 when it is a silhouette a
 * tile of the band lists (pn_wg_sil_tiles); scanned next into slots as the flag pass's. */
PN_KFN void pn_e_wg_sil_band(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    pn_wsil e;
    PN_POOL(uint32_t, wg_soff)[r] =
        pn_wg_sil_rec(&K->view, &K->light, K->wg.hmax, PN_POOL(const float, tris), PN_POOL(const uint32_t, wg_hedge),
                      PN_POOL(const uint32_t, wg_run), PN_POOL(const uint32_t, wg_tcast), PN_POOL(const uint32_t, wg_tcomp), r,
                      &e) &&
        pn_wg_sil_tiles(&K->view, &K->light, &K->wg, PN_POOL(const float, tris), PN_POOL(const float, wg_tbox), &e,
                        (PN_GLOBAL uint32_t *)0) != 0u;
}

/* Edge run that is a silhouette: one added to the list length (wg_toff, zeroed first) of
 * every tile of the band wg.b* that lists it. */
PN_KFN void pn_e_wg_tile_count(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    pn_wsil e;
    if (pn_wg_sil_rec(&K->view, &K->light, K->wg.hmax, PN_POOL(const float, tris), PN_POOL(const uint32_t, wg_hedge),
                      PN_POOL(const uint32_t, wg_run), PN_POOL(const uint32_t, wg_tcast), PN_POOL(const uint32_t, wg_tcomp),
                      r, &e))
        (void)pn_wg_sil_tiles(&K->view, &K->light, &K->wg, PN_POOL(const float, tris), PN_POOL(const float, wg_tbox), &e,
                              PN_POOL(uint32_t, wg_toff));
}

/* Edge run that is a silhouette: its record and wedge tiles at its slot. */
PN_KFN void pn_e_wg_sil_make(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    PN_CONST uint32_t *off = PN_POOL(const uint32_t, wg_soff);
    if (off[r + 1u] == off[r]) return;
    pn_wg_sil_make(&K->view, &K->light, K->wg.hmax, PN_POOL(const float, tris), PN_POOL(const uint32_t, wg_hedge),
                   PN_POOL(const uint32_t, wg_run), PN_POOL(const uint32_t, wg_tcast), PN_POOL(const uint32_t, wg_tcomp), r,
                   off[r], PN_POOL(pn_wsil, wg_sil));
}

/* Silhouette: its object's box, written by the object's first silhouette (under
 * PN_WG_NO_CULL one no test passes: pn_wg_sil_box). */
PN_KFN void pn_e_wg_obj_box(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t s)
{
    pn_wg_obj_box(PN_POOL(pn_wsil, wg_sil), K->wg.sils, s, K->wg.no_cull);
}

/* Block of PN_WG_BLOCK silhouettes: the light-space box of their end points. */
PN_KFN void pn_e_wg_block_box(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t k)
{
    pn_wg_block_box(PN_POOL(const pn_wsil, wg_sil), K->wg.sils, k, PN_WG_BLOCK, K->wg.no_cull, PN_POOL(float, wg_bbox));
}

/* Superblock of PN_WG_SBLOCK silhouettes: the same. */
PN_KFN void pn_e_wg_sblock_box(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t k)
{
    pn_wg_block_box(PN_POOL(const pn_wsil, wg_sil), K->wg.sils, k, PN_WG_SBLOCK, K->wg.no_cull, PN_POOL(float, wg_sbox));
}

/* Screen tile: the light-space box of its pixels' shadow origins and whether its centre
 * segments are clear. */
PN_KFN void pn_e_wg_tile_box(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_wg_tile_box(&K->view, &K->light, t % K->wg.tiles_x, t / K->wg.tiles_x, &S, PN_POOL(const float, tris),
                   PN_POOL(const pn_kbvh4, wnodes), PN_POOL(const uint32_t, index), K->wg.no_cull,
                   PN_POOL(float, wg_tbox) + (size_t)t * PN_WG_BOX);
}

/* Silhouette: the count of its (tile, silhouette) pairs in the band (with wg.count_rows,
 * also added to each tile row's: wg_rowc, zeroed first), its tiles kept in the tile-list
 * pool (free until the sort) from the cursor past the kept words (zeroed first). */
PN_KFN void pn_e_wg_count(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t s)
{
    PN_POOL(uint32_t, wg_poff)[s] =
        pn_wg_bin(&K->view, &K->light, &K->wg, PN_POOL(const float, tris), PN_POOL(const pn_wsil, wg_sil),
                  PN_POOL(const float, wg_tbox), s, 0u, 0u, PN_WG_BIN_COUNT, PN_POOL(uint32_t, wg_rowc),
                  PN_POOL(uint32_t, wg_kept) + 2u * (size_t)s, PN_POOL(uint32_t, wg_sorted),
                  PN_POOL(uint32_t, wg_kept) + 2u * (size_t)K->wg.sils, K->wg.keep_cap);
}

/* Silhouette: its (tile, silhouette) pairs in the band from its prefix-summed offset (none
 * when it counted none: the same reach and tests would find none again), copied from the
 * tiles its count kept when it kept them. */
PN_KFN void pn_e_wg_scatter(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t s)
{
    PN_CONST uint32_t *poff = PN_POOL(const uint32_t, wg_poff);
    if (poff[s + 1u] == poff[s]) return;
    (void)pn_wg_bin(&K->view, &K->light, &K->wg, PN_POOL(const float, tris), PN_POOL(const pn_wsil, wg_sil),
                    PN_POOL(const float, wg_tbox), s, poff[s], poff[s + 1u] - poff[s], PN_WG_BIN_WRITE,
                    PN_POOL(uint32_t, wg_pairs), PN_POOL(uint32_t, wg_kept) + 2u * (size_t)s,
                    PN_POOL(uint32_t, wg_sorted), PN_POOL(uint32_t, wg_kept) + 2u * (size_t)K->wg.sils, K->wg.keep_cap);
}

/* Screen tile: the ends of its list's runs and objects (into the pair pool, free after the
 * sort). */
PN_KFN void pn_e_wg_runs(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    PN_CONST uint32_t *toff = PN_POOL(const uint32_t, wg_toff);
    (void)K;
    pn_wg_runs(PN_POOL(const pn_wsil, wg_sil), PN_POOL(const uint32_t, wg_sorted), toff[t], toff[t + 1u],
               PN_POOL(uint32_t, wg_pairs));
}

/* Pixel i of the band's rows, in tiles (pix0 + pn_pix_tiled; the band's columns only): its
 * centre ray (none in a clear tile; the tiles' boxes are made only when there are
 * silhouettes) and its tile's wedges, blended object by object, times its horizon's
 * fraction; or, in its own object's self-shadow penumbra (PN_WG_EXACT), the reference's
 * visibility over at most PN_REF_FALLBACK_K^2 samples (pn_reference_fallback); or, in a
 * tile marked PN_WG_FULL, the reference's visibility at the frame's k. */
PN_KFN void pn_e_wg_pixel(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t i)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t W = K->view.width, y1 = pn_kminu(K->wg.by1 * PN_WG_TILE, K->view.height), tx, tile, id;
    uint32_t pix = K->wg.pix0 + pn_pix_tiled(i, W, y1 - K->wg.by0 * PN_WG_TILE);
    tx = (pix % W) / PN_WG_TILE;
    PN_CONST uint32_t *toff = PN_POOL(const uint32_t, wg_toff);
    pn_v3 pos, nrm, O;
    float v;
    int full;
    if (tx < K->wg.bx0 || tx >= K->wg.bx1) return; /* another band's */
    id = PN_POOL(const uint32_t, tri_id)[pix];
    if (id == PN_NO_PIXEL_TRIANGLE) {
        PN_POOL(float, vis)[pix] = 1.0f;
        return;
    }
    pn_pix_surf(A, P, K, pix, &pos, &nrm);
    if (!pn_shadow_origin(pos, nrm, &K->light, &O)) {
        PN_POOL(float, vis)[pix] = 0.0f;
        return;
    }
    tile = (pix / W / PN_WG_TILE) * K->wg.tiles_x + tx;
    full = K->wg.full && PN_POOL(const float, wg_tbox)[(size_t)tile * PN_WG_BOX + PN_WG_CLEAR] == PN_WG_FULL;
    v = full ? PN_WG_EXACT : pn_wg_pixel(O, id, &K->light, K->wg.mode, PN_POOL(const float, tris), PN_POOL(const pn_kbvh4, wnodes),
                    PN_POOL(const uint32_t, index), PN_POOL(const uint32_t, wg_tcomp), PN_POOL(const uint32_t, wg_tcast), PN_POOL(const pn_wsil, wg_sil),
                    K->wg.sils, PN_POOL(const float, wg_bbox), PN_POOL(const float, wg_sbox), PN_POOL(const uint32_t, wg_sorted), PN_POOL(const uint32_t, wg_pairs), toff[tile], toff[tile + 1u],
                    K->wg.sils > 0u && PN_POOL(const float, wg_tbox)[(size_t)tile * PN_WG_BOX + PN_WG_CLEAR] > 0.0f, &c);
    if (v == PN_WG_EXACT) {
        v = pn_reference_fallback_k(pos, nrm, id, PN_POOL(const float, tris), PN_POOL(const pn_kbvh4, wnodes),
                                    PN_POOL(const uint32_t, index), &K->light, full ? K->light.k : PN_REF_FALLBACK_K, &c);
    } else if (v > 0.0f && !(PN_POOL(const uint32_t, wg_tcast)[id] & PN_WG_LIT_FRONT)) {
        uint32_t m[PN_MASK_WORDS_MAX];
        pn_horizon H;
        pn_mask_clear(m);
        pn_horizon_of(pos, nrm, id, PN_POOL(const float, tris), &K->light, &H);
        if (pn_horizon_mask(&H, &K->light, m)) v = v * pn_mask_visibility(m, K->light.k);
    }
    PN_POOL(float, vis)[pix] = v;
    c.lit = 1u;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pn_pix_slot(i, K->view.height)].c, &c);
}
#endif

/* Their part of the list. */
#if PN_ENABLE_WEDGES
#define PN_PASSES_WEDGES(X)                               \
    X(WG_CAST, wg_cast, 64, 4096)                         \
    X(WG_SIL_FLAG, wg_sil_flag, 64, 4096)                 \
    X(WG_SIL_BAND, wg_sil_band, 64, 1024)                 \
    X(WG_TILE_COUNT, wg_tile_count, 64, 1024)             \
    X(WG_SIL_MAKE, wg_sil_make, 64, 1024)                 \
    X(WG_OBJ_BOX, wg_obj_box, 64, 1024)                   \
    X(WG_BLOCK_BOX, wg_block_box, 64, 1024)               \
    X(WG_SBLOCK_BOX, wg_sblock_box, 64, 64)               \
    X(WG_TILE_BOX, wg_tile_box, 64, 16)                   \
    X(WG_COUNT, wg_count, 64, 1024)                       \
    X(WG_SCATTER, wg_scatter, 64, 1024)                   \
    X(WG_RUNS, wg_runs, 64, 16)                           \
    X(WG_PIXEL, wg_pixel, 16, 1024)
#else
#define PN_PASSES_WEDGES(X)
#endif

#endif
