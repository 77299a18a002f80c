/* pn_passes.h - the pass table: every pass of every algorithm as one per-work-item entry
 * function with the one signature both ports call,
 *
 *   void pn_e_<name>(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t item)
 *
 * (A the arena's aligned base, P the pool offsets, K the launch's parameters, item in
 * [0, n) of the launch), and the one list of them, PN_PASSES. From the list come the
 * pass ids src/ launches by (PN_K_<ID>), the OpenCL __kernel wrappers (kernels/pn_passes.cl)
 * and the scalar port's dispatch (ports/scalar/pn_scalar.c). A new pass is an entry here
 * and a line in the list; no port changes (docs/architecture.md).
 *
 * List columns: X(ID, name, local, grain)
 *   local  the OpenCL work-group size it is launched with (small for items that loop over
 *          a whole row or band, so that rows spread over the cores);
 *   grain  items per task on the scalar port (the parallel-for hands out tasks): many for
 *          cheap items, few for items that walk a BVH or a cell list. The per-pixel shadow
 *          passes take 1024 pixels a task (two rows at 512 wide): each pixel adds into its
 *          row's counters atomically, and two threads in one row fight over that row's cache
 *          line (pn_row_counters gives every row its own). Measured at 512x512 on 2 threads
 *          against 64 a task: MCSM's pixel pass 16% faster on chess_set; the reference 1%
 *          and GEARS 3% faster there, 7-8% on square, where a pixel costs least.
 *
 * Items write disjoint memory or add integers atomically (pn_katomic_add), so no result
 * depends on the order they run in. */
#ifndef PN_PASSES_H
#define PN_PASSES_H

#include "pn_kpools.h"
#include "pn_raster.h"
#include "pn_raytrace.h"
#include "pn_reference.h"
#include "pn_shade.h"
#if PN_ENABLE_GEARS
#include "pn_gears_pass.h"
#endif
#define PN_LIGHT_VIEW (PN_ENABLE_SRT || PN_ENABLE_OCCTEX || PN_ENABLE_MCSM)
#if PN_LIGHT_VIEW
#include "pn_lview.h"
#endif
#if PN_ENABLE_SRT
#include "pn_srt.h"
#endif
#if PN_ENABLE_OCCTEX
#include "pn_occtex.h"
#endif
#if PN_ENABLE_MCSM
#include "pn_mcsm.h"
#endif
#if PN_ENABLE_WEDGES
#include "pn_wedges.h"
#endif

#define PN_NO_PIXEL_TRIANGLE 0xFFFFFFFFu

/* A work item's counters into its row's: integer atomic adds, the same sums in any order. */
PN_KFN void pn_counters_add(PN_GLOBAL pn_shadow_counters *row, const pn_shadow_counters *c)
{
    if (c->candidates) pn_katomic_add(&row->candidates, c->candidates);
    if (c->blocking) pn_katomic_add(&row->blocking, c->blocking);
    if (c->lit) pn_katomic_add(&row->lit, c->lit);
    if (c->overflow) pn_katomic_add(&row->overflow, c->overflow);
    if (c->nodes) pn_katomic_add(&row->nodes, c->nodes);
    if (c->capped) pn_katomic_add(&row->capped, c->capped);
}

/* ---- G-buffer (pn_raster.h) ------------------------------------------------------------ */

/* Group of PN_RASTER_GROUP triangles: the pixel rows each may cover. */
PN_KFN void pn_e_raster_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t g)
{
    pn_raster_rows_item(&K->view, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), K->tri_count, g,
                        PN_POOL(uint32_t, rows));
}

/* Chunk of the band walk (pn_raster.h): the rows its triangles may cover, in whichever view
 * the rows pass before it set up. */
PN_KFN void pn_e_raster_chunks(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t c)
{
    PN_POOL(uint32_t, chunks)[c] =
        pn_raster_chunk(PN_POOL(const uint32_t, rows), PN_POOL(const uint32_t, rindex), K->raster_tris, c);
}

/* Band `band` of PN_RASTER_BAND rows of view v: owns its pixels and walks the triangles
 * whose chunks meet it (the G-buffer and the light-space maps alike). depth/ids of its rows
 * must be empty (+inf, no triangle) on entry. */
PN_KFN void pn_band(const pn_kview *v, PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t band,
                    PN_GLOBAL float *depth, PN_GLOBAL uint32_t *ids)
{
    uint32_t y0 = band * PN_RASTER_BAND, y1 = y0 + PN_RASTER_BAND - 1u;
    if (y1 >= v->height) y1 = v->height - 1u;
    pn_raster_band(v, PN_POOL(const float, tris), PN_POOL(const uint32_t, rows), PN_POOL(const uint32_t, chunks),
                   PN_POOL(const uint32_t, rindex), K->raster_tris, y0, y1, depth, ids);
}

/* Band of the G-buffer: its rows cleared, rasterized, then resolved (position, normal),
 * in one item so that they stay in cache. */
PN_KFN void pn_e_raster_band(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t band)
{
    uint32_t y0 = band * PN_RASTER_BAND, y1 = y0 + PN_RASTER_BAND, W = K->view.width, x, y;
    PN_GLOBAL float *depth = PN_POOL(float, depth);
    PN_GLOBAL uint32_t *ids = PN_POOL(uint32_t, tri_id);
    if (y1 > K->view.height) y1 = K->view.height;
    for (y = y0; y < y1; y++)
        for (x = 0; x < W; x++) {
            depth[(size_t)y * W + x] = PN_KINF;
            ids[(size_t)y * W + x] = PN_NO_PIXEL_TRIANGLE;
        }
    pn_band(&K->view, A, P, K, band, depth, ids);
    for (y = y0; y < y1; y++)
        for (x = 0; x < W; x++)
            pn_gbuffer_resolve(&K->view, PN_POOL(const float, tris), x, y, depth, ids, PN_POOL(float, pos),
                               PN_POOL(float, nrm));
}

/* ---- Shadow passes of one item per pixel: the reference and per-sample ray tracing ----- */

/* Pixel: its mask through the BVH (pn_reference.h), or with `rays` its k^2 single shadow
 * rays (pn_raytrace.h); its counters into its row's. */
PN_KFN void pn_pixel_shadow(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix, int rays)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t id = PN_POOL(const uint32_t, tri_id)[pix];
    pn_v3 pos, nrm;
    float v;
    if (id == PN_NO_PIXEL_TRIANGLE) {
        PN_POOL(float, vis)[pix] = 1.0f;
        return;
    }
    pos = pn_v3_load(PN_POOL(const float, pos) + (size_t)pix * 3u);
    nrm = pn_v3_load(PN_POOL(const float, nrm) + (size_t)pix * 3u);
#if PN_ENABLE_RAYTRACE
    if (rays)
        v = pn_raytrace_pixel(pos, nrm, id, PN_POOL(const float, tris), PN_POOL(const pn_kbvh_node, nodes),
                              PN_POOL(const pn_kbvh4, wnodes), PN_POOL(const uint32_t, index), &K->light, &c);
    else
#endif
        v = pn_reference_pixel(pos, nrm, id, PN_POOL(const float, tris), PN_POOL(const pn_kbvh_node, nodes),
                               PN_POOL(const pn_kbvh4, wnodes), PN_POOL(const uint32_t, index), &K->light, &c);
    (void)rays;
    PN_POOL(float, vis)[pix] = v;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}

#if PN_ENABLE_REFERENCE
PN_KFN void pn_e_reference(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_pixel_shadow(A, P, K, pix, 0);
}
#endif
#if PN_ENABLE_RAYTRACE
PN_KFN void pn_e_raytrace(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_pixel_shadow(A, P, K, pix, 1);
}
#endif

/* ---- GEARS (pn_gears_pass.h; the frame is src/pn_gears.c) ------------------------------- */

#if PN_ENABLE_GEARS
/* Row: final visibility of pixels that need no mask, lit count, box of origins. */
PN_KFN void pn_e_gears_origins(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_gears_origins_row(&K->light, K->view.width, y, PN_POOL(const uint32_t, tri_id), PN_POOL(const float, pos),
                         PN_POOL(const float, nrm), PN_POOL(float, vis), PN_POOL(float, row_box),
                         PN_POOL(pn_row_counters, counters));
}

/* Row: the box of its origins projected by the area light's grid camera (face 0). */
PN_KFN void pn_e_gears_project(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_kgrid g = PN_POOL(const pn_kfaces, faces)->f[0];
    pn_gears_project_row(&K->light, &g, K->view.width, y, PN_POOL(const uint32_t, tri_id), PN_POOL(const float, pos),
                         PN_POOL(const float, nrm), PN_POOL(float, row_box));
}

/* Pixel: its global cell, and one more pixel in that cell (cell_pix zeroed first). */
PN_KFN void pn_e_gears_pixel_cells(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_gears_pixel_cell(&K->light, PN_POOL(const pn_kfaces, faces), PN_POOL(const uint32_t, tri_id),
                        PN_POOL(const float, pos), PN_POOL(const float, nrm), pix, PN_POOL(uint32_t, pix_cell),
                        PN_POOL(uint32_t, cell_pix));
}

/* Global grid row: its prefix count of cells with pixels (row_pre). */
PN_KFN void pn_e_gears_row_prefix(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    (void)K;
    pn_gears_row_prefix(PN_POOL(const uint32_t, cell_pix), PN_POOL(const pn_kfaces, faces)->res, r,
                        PN_POOL(uint32_t, row_pre));
}

/* Triangle: its rectangle of cells on every face. */
PN_KFN void pn_e_gears_tri_rects(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    pn_gears_tri_rects(PN_POOL(const pn_kfaces, faces), &K->light, PN_POOL(const float, tris),
                       PN_POOL(const uint8_t, flags), t, PN_POOL(pn_cellrect, rects));
}

/* Triangle: its pairs added to every global grid row it covers (row_pairs zeroed first). */
PN_KFN void pn_e_gears_row_pairs(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    (void)K;
    pn_gears_tri_row_pairs(PN_POOL(const pn_kfaces, faces), PN_POOL(const pn_cellrect, rects),
                           PN_POOL(const uint32_t, row_pre), t, PN_POOL(uint32_t, row_pairs));
}

/* Triangle: its pairs per cell of grid row (tile.face, tile.r0), into cell_cur[0 .. res). */
PN_KFN void pn_e_gears_row_cells(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t t)
{
    pn_gears_tri_row_cells(PN_POOL(const pn_cellrect, rects), PN_POOL(const uint32_t, cell_pix),
                           PN_POOL(const pn_kfaces, faces)->res, K->tile.face, K->tile.r0, t,
                           PN_POOL(uint32_t, cell_cur));
}

/* Raster position r (the BVH's leaf order, kernels/pn_raster.h; r < K->raster_tris): how
 * many pairs its triangle makes in the tile, into tri_off[r]. */
PN_KFN void pn_e_gears_count(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    PN_POOL(uint32_t, tri_off)[r] = pn_gears_tri_count(PN_POOL(const pn_cellrect, rects), PN_POOL(const uint32_t, row_pre),
                                                       PN_POOL(const pn_kfaces, faces)->res, &K->tile,
                                                       PN_POOL(const uint32_t, rindex)[r]);
}

/* Raster position r: its triangle's pairs (cell, r) from tri_off[r] (the prefix-summed
 * counts) on. */
PN_KFN void pn_e_gears_scatter(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t r)
{
    pn_gears_tri_scatter(PN_POOL(const pn_cellrect, rects), PN_POOL(const uint32_t, cell_pix),
                         PN_POOL(const pn_kfaces, faces)->res, &K->tile, PN_POOL(const uint32_t, rindex)[r], r,
                         PN_POOL(const uint32_t, tri_off)[r], PN_POOL(uint32_t, pairs));
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
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    float v;
    if (!pn_gears_pixel_mask(&K->light, K->exact_stats, &K->tile, PN_POOL(const pn_kfaces, faces)->res,
                             PN_POOL(const uint32_t, tri_id), PN_POOL(const float, pos), PN_POOL(const float, nrm),
                             PN_POOL(const uint32_t, pix_cell), PN_POOL(const uint32_t, cell_off),
                             PN_POOL(const uint32_t, sorted), PN_POOL(const float, chunk_box),
                             PN_POOL(const float, super_box), PN_POOL(const float, tris),
                             PN_POOL(const pn_kbvh_node, nodes), pix, &c, &v))
        return;
    PN_POOL(float, vis)[pix] = v;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}
#endif

/* ---- The light-space view (pn_lview.h): SRT's map and the occlusion textures' slices ---- */

#if PN_LIGHT_VIEW
/* Row: the light-frame extent of its lit origins. */
PN_KFN void pn_e_lview_bounds(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_lview_bounds_row(&K->lview, &K->light, K->lview_ha, K->lview_hb, K->view.width, y,
                        PN_POOL(const uint32_t, tri_id), PN_POOL(const float, pos), PN_POOL(const float, nrm),
                        PN_POOL(float, lview_box));
}

/* Group of triangles: the light-view rows each may cover (the G-buffer's set-up on the
 * light view). */
PN_KFN void pn_e_lmap_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t g)
{
    pn_raster_rows_item(&K->lview, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), K->tri_count, g,
                        PN_POOL(uint32_t, rows));
}
#endif

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
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    float v;
    uint32_t lit;
    a.delta = K->srt_delta;
    a.alpha = K->srt_alpha;
    a.reach_u = K->srt_reach_u;
    a.reach_v = K->srt_reach_v;
    a.wmax = K->srt_wmax;
    a.flags = K->srt_flags;
    a.tiles = K->srt_tiles;
    PN_POOL(uint32_t, pip_off)[pix] =
        pn_srt_classify(&K->lview, &K->light, &a, PN_POOL(const uint32_t, tri_id), PN_POOL(const float, pos),
                        PN_POOL(const float, nrm), PN_POOL(const float, tris), PN_POOL(const float, lmap_depth), PN_POOL(const uint32_t, lmap_id),
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
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    PN_POOL(float, vis)[pix] = pn_reference_pixel(
        pn_v3_load(PN_POOL(const float, pos) + (size_t)pix * 3u), pn_v3_load(PN_POOL(const float, nrm) + (size_t)pix * 3u),
        PN_POOL(const uint32_t, tri_id)[pix], PN_POOL(const float, tris), PN_POOL(const pn_kbvh_node, nodes),
        PN_POOL(const pn_kbvh4, wnodes), PN_POOL(const uint32_t, index), &K->light, &c);
    c.lit = 0u; /* counted by the classification */
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}
#endif

/* ---- Occlusion textures (pn_occtex.h; the frame is src/pn_occtex.c) ---------------------- */

#if PN_ENABLE_OCCTEX
/* Band of texel rows: every fragment's slice bits. */
PN_KFN void pn_e_occ_band(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t band)
{
    pn_occ_band(&K->lview, &K->occ, PN_POOL(const float, tris), PN_POOL(const uint32_t, rows),
                PN_POOL(const uint32_t, chunks), PN_POOL(const uint32_t, rindex), K->raster_tris, band,
                PN_POOL(uint32_t, occ_bits), PN_POOL(uint32_t, occ_words));
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
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    pn_v3 O;
    uint32_t id = PN_POOL(const uint32_t, tri_id)[pix];
    int lit = id != PN_NO_PIXEL_TRIANGLE &&
              pn_shadow_origin(pn_v3_load(PN_POOL(const float, pos) + (size_t)pix * 3u),
                               pn_v3_load(PN_POOL(const float, nrm) + (size_t)pix * 3u), &K->light, &O);
    PN_POOL(float, vis)[pix] = (id == PN_NO_PIXEL_TRIANGLE || lit) ? 1.0f : 0.0f;
    c.lit = lit ? 1u : 0u;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}

/* Pixel: slice K->occ.slice's occlusion combined into its visibility. */
PN_KFN void pn_e_occ_lookup(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_v3 O;
    float I;
    if (PN_POOL(const uint32_t, tri_id)[pix] == PN_NO_PIXEL_TRIANGLE ||
        !pn_shadow_origin(pn_v3_load(PN_POOL(const float, pos) + (size_t)pix * 3u),
                          pn_v3_load(PN_POOL(const float, nrm) + (size_t)pix * 3u), &K->light, &O))
        return;
    if (pn_occ_slice_occlusion(&K->lview, &K->light, &K->occ, PN_POOL(const uint32_t, occ_filt), O, &I) && I > 0.0f)
        PN_POOL(float, vis)[pix] = pn_occ_combine(K->occ.combine, PN_POOL(const float, vis)[pix], I);
}

/* Pixel: times the fraction of light samples in front of its own plane; its lookups (the
 * slices looked up that weighed in) counted as candidates. */
PN_KFN void pn_e_occ_finish(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    uint32_t m[PN_MASK_WORDS_MAX], id = PN_POOL(const uint32_t, tri_id)[pix];
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    pn_v3 pos, nrm, O;
    pn_horizon H;
    if (id == PN_NO_PIXEL_TRIANGLE) return;
    pos = pn_v3_load(PN_POOL(const float, pos) + (size_t)pix * 3u);
    nrm = pn_v3_load(PN_POOL(const float, nrm) + (size_t)pix * 3u);
    if (!pn_shadow_origin(pos, nrm, &K->light, &O)) return;
    pn_mask_clear(m);
    pn_horizon_of(pos, nrm, id, PN_POOL(const float, tris), &K->light, &H);
    pn_horizon_mask(&H, &K->light, m);
    PN_POOL(float, vis)[pix] = PN_POOL(const float, vis)[pix] * pn_mask_visibility(m, K->light.k);
    c.candidates = pn_occ_lookups(&K->lview, &K->light, &K->occ, O);
    if (c.candidates) pn_counters_add(&PN_POOL(pn_row_counters, counters)[pix / K->view.width].c, &c);
}
#endif

/* ---- Monte Carlo shadow maps (pn_mcsm.h; the frame is src/pn_mcsm.c) ------------------------ */

#if PN_ENABLE_MCSM
/* Texel row of the layers (N-buffer level 0): emptied. */
PN_KFN void pn_e_mc_clear(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_mc_clear_row(&K->lview, y, PN_POOL(float, mc_nb));
}

/* Group of triangles: the layers' rows pass; a small occluder's fragments go straight into
 * the layers. */
PN_KFN void pn_e_mc_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t g)
{
    pn_mc_rows(&K->lview, &K->mc, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), K->tri_count, g,
               PN_POOL(uint32_t, rows), PN_POOL(float, mc_nb));
}

/* Band of texel rows: the near and far layers (N-buffer level 0). */
PN_KFN void pn_e_mc_band(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t band)
{
    pn_mc_band(&K->lview, &K->mc, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags),
               PN_POOL(const uint32_t, rows), PN_POOL(const uint32_t, chunks), PN_POOL(const uint32_t, rindex),
               K->raster_tris, band, PN_POOL(float, mc_nb));
}

/* Row of N-buffer level K->mc.level. */
PN_KFN void pn_e_mc_nbuf(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_nb_mm_row(K->mc.res, K->mc.level, y, PN_POOL(float, mc_nb));
}

/* Pixel row y: each pixel's rays through the layers, its visibility and class; the row's
 * counters added once. Rows, not pixels, as for the blur: a pixel item made two to four
 * atomic adds and divided its index by the width, where most pixels (lit ones) do little
 * else than one or two region lookups. The row goes in runs of PN_MC_RUN pixels
 * (pn_mc_run: their origins once, and one lookup that may find the whole run lit). */
PN_KFN void pn_e_mc_pixel(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t W = K->view.width, x0, i, k, n[PN_MC_WORDS] = {0u, 0u, 0u, 0u, 0u, 0u};
    PN_GLOBAL uint32_t *words = PN_POOL(uint32_t, mc_words) + (size_t)y * PN_MC_ROW_WORDS;
    pn_mc_ctx m;
    pn_mc_px px[PN_MC_RUN];
    pn_mc_ctx_init(&m, &K->view, &K->lview, &K->light, &K->mc, PN_POOL(const float, mc_nb), PN_POOL(const float, depth));
    for (x0 = 0; x0 < W; x0 += PN_MC_RUN) {
        uint32_t count = pn_kminu(PN_MC_RUN, W - x0);
        size_t pix0 = (size_t)y * W + x0;
        int run_lit = pn_mc_run(&m, PN_POOL(const uint32_t, tri_id), PN_POOL(const float, pos), PN_POOL(const float, nrm),
                                pix0, count, px);
        for (i = 0; i < count; i++) {
            uint32_t cls, rays;
            if (px[i].kind == PN_MC_PX_LIT) {
                /* pn_mc_pixel's answer for most pixels, without its set-up */
                PN_POOL(float, vis)[pix0 + i] = 1.0f;
                c.lit++;
                n[PN_MC_CLASS_LIT - 1u]++;
                continue;
            }
            if (px[i].kind != PN_MC_PX_SURFACE) {
                PN_POOL(float, vis)[pix0 + i] = px[i].kind == PN_MC_PX_NONE ? 1.0f : 0.0f;
                continue;
            }
            PN_POOL(float, vis)[pix0 + i] = pn_mc_pixel(&m, x0 + i, y, px + i, run_lit, &cls, &rays);
            c.lit++;
            c.candidates += rays;
            if (cls != PN_MC_CLASS_NONE) n[cls - 1u]++;
        }
    }
    c.nodes = m.steps;
    n[PN_MC_WORD_CAPPED] = m.capped;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[y].c, &c);
    for (k = 0; k < PN_MC_WORDS; k++)
        if (n[k]) pn_katomic_add(words + k, n[k]);
}

/* Row: the blur across (visibility into the other buffer), then down (back). Rows, not
 * pixels: a pixel item's division of its index by the width cost about as much as its blur
 * (spot, 512x512, 2 threads: 3.3 -> 2.1 ms for both directions). */
PN_KFN void pn_e_mc_blur_h(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_mc_blur_row(&K->mc, K->view.width, K->view.height, y, 0u, PN_POOL(const uint32_t, tri_id),
                   PN_POOL(const float, depth), PN_POOL(const float, nrm), PN_POOL(const float, vis), PN_POOL(float, mc_tmp));
}
PN_KFN void pn_e_mc_blur_v(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_mc_blur_row(&K->mc, K->view.width, K->view.height, y, 1u, PN_POOL(const uint32_t, tri_id),
                   PN_POOL(const float, depth), PN_POOL(const float, nrm), PN_POOL(const float, mc_tmp), PN_POOL(float, vis));
}
#endif

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

/* ---- Shading (pn_shade.h) --------------------------------------------------------------- */

/* Pixel: RGBA8 bytes r g b a, whatever the device's endianness. */
PN_KFN void pn_e_shade(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    uint32_t c = pn_shade_pixel(&K->view, &K->light, &K->shade, PN_POOL(const uint32_t, tri_id)[pix],
                                pn_v3_load(PN_POOL(const float, pos) + (size_t)pix * 3u),
                                pn_v3_load(PN_POOL(const float, nrm) + (size_t)pix * 3u), PN_POOL(const float, vis)[pix]);
    PN_GLOBAL uint8_t *o = PN_POOL(uint8_t, rgba) + (size_t)pix * 4u;
    o[0] = (uint8_t)(c & 0xFFu);
    o[1] = (uint8_t)((c >> 8) & 0xFFu);
    o[2] = (uint8_t)((c >> 16) & 0xFFu);
    o[3] = (uint8_t)(c >> 24);
}

/* ---- The list ------------------------------------------------------------------------------ */

#if PN_ENABLE_REFERENCE
#define PN_PASSES_REFERENCE(X) X(REFERENCE, reference, 16, 1024)
#else
#define PN_PASSES_REFERENCE(X)
#endif
#if PN_ENABLE_RAYTRACE
#define PN_PASSES_RAYTRACE(X) X(RAYTRACE, raytrace, 16, 1024)
#else
#define PN_PASSES_RAYTRACE(X)
#endif
#if PN_ENABLE_GEARS
#define PN_PASSES_GEARS(X)                          \
    X(GEARS_ORIGINS, gears_origins, 1, 1)           \
    X(GEARS_PROJECT, gears_project, 1, 1)           \
    X(GEARS_PIXEL_CELLS, gears_pixel_cells, 64, 1024) \
    X(GEARS_ROW_PREFIX, gears_row_prefix, 64, 16)   \
    X(GEARS_TRI_RECTS, gears_tri_rects, 64, 4096)   \
    X(GEARS_ROW_PAIRS, gears_row_pairs, 64, 4096)   \
    X(GEARS_ROW_CELLS, gears_row_cells, 64, 4096)   \
    X(GEARS_COUNT, gears_count, 64, 4096)           \
    X(GEARS_SCATTER, gears_scatter, 64, 4096)       \
    X(GEARS_CHUNKS, gears_chunks, 64, 4096)         \
    X(GEARS_MASKS, gears_masks, 16, 1024)
#else
#define PN_PASSES_GEARS(X)
#endif

#if PN_LIGHT_VIEW
#define PN_PASSES_LVIEW(X)                                \
    X(LVIEW_BOUNDS, lview_bounds, 1, 1)                   \
    X(LMAP_ROWS, lmap_rows, 64, 512)
#else
#define PN_PASSES_LVIEW(X)
#endif

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

#if PN_ENABLE_MCSM
#define PN_PASSES_MCSM(X)                                 \
    X(MC_CLEAR, mc_clear, 4, 8)                           \
    X(MC_ROWS, mc_rows, 64, 512)                         \
    X(MC_BAND, mc_band, 1, 1)                             \
    X(MC_NBUF, mc_nbuf, 4, 8)                             \
    X(MC_PIXEL, mc_pixel, 4, 2)                           \
    X(MC_BLUR_H, mc_blur_h, 4, 8)                         \
    X(MC_BLUR_V, mc_blur_v, 4, 8)
#else
#define PN_PASSES_MCSM(X)
#endif

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

#define PN_PASSES(X)                                \
    X(RASTER_ROWS, raster_rows, 64, 512)           \
    X(RASTER_CHUNKS, raster_chunks, 64, 1024)       \
    X(RASTER_BAND, raster_band, 1, 1)               \
    PN_PASSES_REFERENCE(X)                          \
    PN_PASSES_RAYTRACE(X)                           \
    PN_PASSES_GEARS(X)                              \
    PN_PASSES_LVIEW(X)                              \
    PN_PASSES_SRT(X)                                \
    PN_PASSES_OCCTEX(X)                             \
    PN_PASSES_MCSM(X)                               \
    PN_PASSES_WEDGES(X)                             \
    X(SHADE, shade, 64, 1024)

#define PN_PASS_ENUM(id, name, local, grain) PN_K_##id,
enum { PN_PASSES(PN_PASS_ENUM) PN_K_PASSES };
#undef PN_PASS_ENUM

#endif
