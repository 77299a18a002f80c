/* pn_passes_srt.h - selective ray tracing's passes:
 * their per-work-item entries and their part of
 * the pass list (PN_PASSES_*), composed by pn_passes.h, which includes this file after
 * the kernels it calls; see there for the entry signature and the list's columns. */
#ifndef PN_PASSES_SRT_H
#define PN_PASSES_SRT_H

/* ---- Selective ray tracing (pn_srt.h; the frame is src/pn_srt.c) ------------------------- */

#if PN_ENABLE_SRT

/* Texel: empty map (depth +inf, no triangle, no thin triangle). */
PN_KFN void pn_e_lmap_clear(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    (void)K;
    PN_POOL(float, lmap_depth)[t] = PN_KINF;
    PN_POOL(uint32_t, lmap_id)[t] = PN_NO_PIXEL_TRIANGLE;
    PN_POOL(uint32_t, lmap_cons)[t] = 0u;
}

/* Band of map rows: the G-buffer's rasterizer on the light view. */
PN_KFN void pn_e_lmap_band(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t band)
{
    pn_band(&K->lview, A, P, K, band, PN_POOL(float, lmap_depth), PN_POOL(uint32_t, lmap_id));
}

/* Triangle: conservative rasterization when thin. */
PN_KFN void pn_e_srt_conservative(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    pn_srt_conservative(&K->lview, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), t,
                        PN_POOL(uint32_t, lmap_cons), PN_POOL(uint32_t, srt_words) + PN_SRT_WORD_THIN,
                        PN_POOL(uint32_t, srt_words) + PN_SRT_WORD_CONS);
}

/* Tile: the largest splat weight of its edge texels. */
PN_KFN void pn_e_srt_tiles(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t tile)
{
    pn_srt_tile(&K->lview, K->srt_delta, K->srt_alpha, PN_POOL(const float, lmap_depth), PN_POOL(const uint32_t, lmap_id),
                PN_POOL(const float, tris), PN_POOL(const uint32_t, lmap_cons), tile, K->srt_tiles,
                PN_POOL(uint32_t, srt_tile_w), PN_POOL(uint32_t, srt_words) + PN_SRT_WORD_WMAX);
}

/* Tile row: the largest weight whose horizontal reach covers each tile (srt_tile_h). */
PN_KFN void pn_e_srt_tile_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t row)
{
    pn_srt_sweep(PN_POOL(const uint32_t, srt_tile_w), PN_POOL(uint32_t, srt_tile_h), row * K->srt_tiles, 1u,
                 K->srt_tiles, K->srt_reach_u);
}

/* Tile column: then vertically, into the penumbra mask (non-zero: covered). */
PN_KFN void pn_e_srt_tile_cols(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t col)
{
    uint32_t y, n = 0u;
    pn_srt_sweep(PN_POOL(const uint32_t, srt_tile_h), PN_POOL(uint32_t, srt_tile_mask), col, K->srt_tiles, K->srt_tiles,
                 K->srt_reach_v);
    for (y = 0; y < K->srt_tiles; y++) n += PN_POOL(const uint32_t, srt_tile_mask)[y * K->srt_tiles + col] != 0u;
    if (n) pn_katomic_add(PN_POOL(uint32_t, srt_words) + PN_SRT_WORD_TILES, n);
}

/* Pixel: PIP flag into pip_off (scanned next), the map's answer into vis. */
PN_KFN void pn_e_srt_classify(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_srt_args a;
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    float v;
    uint32_t lit;
    a.delta = K->srt_delta;
    a.alpha = K->srt_alpha;
    a.reach_u = K->srt_reach_u;
    a.reach_v = K->srt_reach_v;
    a.wmax = K->srt_wmax;
    a.flags = K->srt_flags;
    a.tiles = K->srt_tiles;
    pn_ksurf S = pn_surf_of(A, P, K);
    PN_POOL(uint32_t, pip_off)[pix] =
        pn_srt_classify(&K->lview, &K->light, &a, &S, PN_POOL(const float, tris), PN_POOL(const float, lmap_depth), PN_POOL(const uint32_t, lmap_id),
                        PN_POOL(const uint32_t, lmap_cons), PN_POOL(const uint32_t, srt_tile_w),
                        PN_POOL(const uint32_t, srt_tile_mask), pix, &v, &lit);
    PN_POOL(float, vis)[pix] = v;
    c.lit = lit;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}

/* Pixel: its place in the dense PIP list (pip_off is the flags' exclusive prefix sum). */
PN_KFN void pn_e_srt_pip_list(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    PN_CONST uint32_t *off = PN_POOL(const uint32_t, pip_off);
    (void)K;
    if (off[pix + 1u] != off[pix]) PN_POOL(uint32_t, pip_list)[off[pix]] = pix;
}

/* PIP item: the reference's exact mask for its pixel. */
PN_KFN void pn_e_srt_exact(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t i)
{
    uint32_t pix = PN_POOL(const uint32_t, pip_list)[i];
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    pn_v3 Ps, ns;
    pn_pix_surf(A, P, K, pix, &Ps, &ns);
    PN_POOL(float, vis)[pix] = pn_reference_pixel(Ps, ns, PN_POOL(const uint32_t, tri_id)[pix], PN_POOL(const float, tris), PN_POOL(const pn_kbvh4, wnodes),
        PN_POOL(const uint32_t, index), &K->light, &c);
    c.lit = 0u; /* counted by the classification */
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}
#endif

/* Their part of the list. */
#if PN_ENABLE_SRT
#define PN_PASSES_SRT(X)                                  \
    X(LMAP_CLEAR, lmap_clear, 64, 4096)                   \
    X(LMAP_BAND, lmap_band, 1, 1)                         \
    X(SRT_CONSERVATIVE, srt_conservative, 64, 1024)       \
    X(SRT_TILES, srt_tiles, 16, 64)                       \
    X(SRT_TILE_ROWS, srt_tile_rows, 1, 1)                 \
    X(SRT_TILE_COLS, srt_tile_cols, 1, 1)                 \
    X(SRT_CLASSIFY, srt_classify, 64, 1024)               \
    X(SRT_PIP_LIST, srt_pip_list, 64, 4096)               \
    X(SRT_EXACT, srt_exact, 16, 16)
#else
#define PN_PASSES_SRT(X)
#endif

#endif
