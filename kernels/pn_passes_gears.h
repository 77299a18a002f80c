/* pn_passes_gears.h - GEARS' passes:
 * their per-work-item entries and their part of
 * the pass list (PN_PASSES_*), composed by pn_passes.h, which includes this file after
 * the kernels it calls; see there for the entry signature and the list's columns. */
#ifndef PN_PASSES_GEARS_H
#define PN_PASSES_GEARS_H

/* ---- GEARS (pn_gears_pass.h; the frame is src/pn_gears.c) ------------------------------- */

#if PN_ENABLE_GEARS
/* Row: final visibility of pixels that need no mask, lit count, box of origins. */
PN_KFN void pn_e_gears_origins(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_gears_origins_row(&K->light, K->view.width, y, &S, PN_POOL(float, vis), PN_POOL(float, row_box),
                         PN_POOL(pn_row_counters, counters));
}

/* Row: the box of its origins projected by the area light's grid camera (face 0). */
PN_KFN void pn_e_gears_project(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_kgrid g = PN_POOL(const pn_kfaces, faces)->f[0];
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_gears_project_row(&K->light, &g, K->view.width, y, &S, PN_POOL(float, row_box));
}

/* Pixel: its global cell, and that cell's occupancy bit (cell_bits zeroed first). */
PN_KFN void pn_e_gears_pixel_cells(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_gears_pixel_cell(&K->light, PN_POOL(const pn_kfaces, faces), &S, pix, PN_POOL(uint32_t, pix_cell),
                        PN_POOL(uint32_t, cell_bits));
}

/* Pixel on face tile.face: one more pixel in its cell (the face's cell_pix zeroed first). */
PN_KFN void pn_e_gears_face_pixels(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_gears_face_pixel(PN_POOL(const uint32_t, pix_cell), PN_POOL(const pn_kfaces, faces)->res, K->tile.face, pix,
                        PN_POOL(uint32_t, cell_pix));
}

/* Global grid row: the prefix counts of its occupancy bits (cell_rank). */
PN_KFN void pn_e_gears_row_prefix(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    (void)K;
    pn_gears_row_prefix(PN_POOL(const uint32_t, cell_bits), PN_POOL(const pn_kfaces, faces)->res, r,
                        PN_POOL(uint32_t, cell_rank));
}

/* Triangle: its rectangle of cells on the plan's face (tile.face). */
PN_KFN void pn_e_gears_tri_rects(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    pn_gears_tri_rects(PN_POOL(const pn_kfaces, faces), &K->light, PN_POOL(const float, tris),
                       PN_POOL(const uint8_t, flags), K->tile.face, t, PN_POOL(pn_cellrect, rects));
}

/* Triangle: its pairs added to every grid row of the plan's face it covers (row_pairs
 * zeroed first). */
PN_KFN void pn_e_gears_row_pairs(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    pn_gears_tri_row_pairs(PN_POOL(const pn_kfaces, faces)->res, PN_POOL(const pn_cellrect, rects),
                           PN_POOL(const uint32_t, cell_bits), PN_POOL(const uint32_t, cell_rank), K->tile.face, t,
                           PN_POOL(uint32_t, row_pairs));
}

/* Raster position r (the BVH's leaf order, kernels/pn_raster.h; r < K->raster_tris): its
 * triangle's rectangle in the tile as differences per grid row, into cell_cur (zeroed
 * first). */
PN_KFN void pn_e_gears_count(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    pn_gears_tri_diff(PN_POOL(const pn_cellrect, rects), PN_POOL(const pn_kfaces, faces)->res, &K->tile,
                      PN_POOL(const uint32_t, rindex)[r], PN_POOL(uint32_t, cell_cur));
}

/* Grid row tile.r0 + i: its cells' pairs from the differences, in cell_cur. */
PN_KFN void pn_e_gears_cell_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t i)
{
    pn_gears_cell_row(PN_POOL(const uint32_t, cell_bits), PN_POOL(const pn_kfaces, faces)->res, &K->tile,
                      K->tile.r0 + i, PN_POOL(uint32_t, cell_cur));
}

/* Raster position r: r into the next slot of each cell of the tile its triangle covers
 * (cell_cur: the cells' starts, then their cursors). */
PN_KFN void pn_e_gears_scatter(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    pn_gears_tri_scatter(PN_POOL(const pn_cellrect, rects), PN_POOL(const uint32_t, cell_bits),
                         PN_POOL(const pn_kfaces, faces)->res, &K->tile, PN_POOL(const uint32_t, rindex)[r], r,
                         PN_POOL(uint32_t, cell_cur), PN_POOL(uint32_t, sorted));
}

/* Superchunk: its entries' raster positions turned into triangle ids, the boxes of its
 * chunks and its own box. */
PN_KFN void pn_e_gears_chunks(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t s)
{
    pn_gears_chunk_boxes(PN_POOL(uint32_t, sorted), K->tile.pairs, PN_POOL(const uint32_t, rindex),
                         PN_POOL(const float, tris), s,
                         PN_POOL(float, chunk_box), PN_POOL(float, super_box));
}

/* Pixel whose cell is in the tile: the mask of the cell's triangles. */
PN_KFN void pn_e_gears_masks(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    float v;
    pn_ksurf S = pn_surf_of(A, P, K);
    if (!pn_gears_pixel_mask(&K->light, K->exact_stats, &K->tile, PN_POOL(const pn_kfaces, faces)->res, &S,
                             PN_POOL(const uint32_t, pix_cell), PN_POOL(const uint32_t, cell_off),
                             PN_POOL(const uint32_t, sorted), PN_POOL(const float, chunk_box),
                             PN_POOL(const float, super_box), PN_POOL(const float, tris),
                             PN_POOL(const pn_kbvh4, wnodes), pix, &c, &v))
        return;
    PN_POOL(float, vis)[pix] = v;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}
#endif

/* Their part of the list. */
#if PN_ENABLE_GEARS
#define PN_PASSES_GEARS(X)                          \
    X(GEARS_ORIGINS, gears_origins, 1, 1)           \
    X(GEARS_PROJECT, gears_project, 1, 1)           \
    X(GEARS_PIXEL_CELLS, gears_pixel_cells, 64, 1024) \
    X(GEARS_FACE_PIXELS, gears_face_pixels, 64, 4096) \
    X(GEARS_ROW_PREFIX, gears_row_prefix, 64, 16)   \
    X(GEARS_TRI_RECTS, gears_tri_rects, 64, 4096)   \
    X(GEARS_ROW_PAIRS, gears_row_pairs, 64, 4096)   \
    X(GEARS_COUNT, gears_count, 64, 4096)           \
    X(GEARS_CELL_ROWS, gears_cell_rows, 64, 16)     \
    X(GEARS_SCATTER, gears_scatter, 64, PN_ONE_TASK) \
    X(GEARS_CHUNKS, gears_chunks, 64, 4096)         \
    X(GEARS_MASKS, gears_masks, 16, 1024)
#else
#define PN_PASSES_GEARS(X)
#endif

#endif
