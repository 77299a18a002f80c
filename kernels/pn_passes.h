/* pn_passes.h - the pass table: every pass of every algorithm as one per-work-item entry
 * function with the one signature both ports call,
 *
 *   void pn_e_<name>(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t item)
 *
 * (A the arena's aligned base, P the pool offsets, K the launch's parameters, item in
 * [0, n) of the launch), and the one list of them, PN_PASSES. The G-buffer's and the
 * shading's entries are here; each algorithm's entries and its part of the list
 * (PN_PASSES_<ALGO>) are in kernels/pn_passes_<algo>.h, composed below. From the list come
 * the pass ids src/ launches by (PN_K_<ID>), the OpenCL __kernel wrappers
 * (kernels/pn_passes.cl) and the scalar port's dispatch (ports/scalar/pn_scalar.c). A new
 * pass is an entry and a line in its algorithm's file; no port changes
 * (docs/architecture.md).
 *
 * List columns: X(ID, name, local, grain)
 *   local  the OpenCL work-group size it is launched with (small for items that loop over
 *          a whole row or band, so that rows spread over the cores);
 *   grain  items per task on the scalar port (the parallel-for hands out tasks): many for
 *          cheap items, few for items that walk a BVH or a cell list. The per-pixel shadow
 *          passes take 1024 pixels a task (two rows at 512 wide; four tiles for the passes
 *          in tiles, pn_pix_tiled): each pixel adds into its row's or its tile's counters
 *          atomically, and two threads in one row fight over that row's cache line
 *          (pn_row_counters gives every slot its own). Measured at 512x512 on 2 threads
 *          against 64 a task: MCSM's pixel pass 16% faster on chess_set; the reference 1%
 *          and GEARS 3% faster there, 7-8% on square, where a pixel costs least.
 *
 *          PN_ONE_TASK: the whole pass one task, on one thread: GEARS' scatter, which then
 *          writes every cell's run in raster order, so that sorting the runs
 *          (PN_DEV_SORT_RUNS) is one pass over each; scattered from two threads the runs
 *          came out interleaved, and their heapsort cost the dragon's frame at 512x512 more
 *          than the scatter's second thread saved (2 threads: 2,380 ms; the scatter on one
 *          and the sort on both 1,390 ms).
 *
 * Items write disjoint memory or add integers atomically (pn_katomic_add), so no result
 * depends on the order they run in. */
#ifndef PN_PASSES_H
#define PN_PASSES_H

/* grain: the pass in one task (the list's columns, below; for passes of under 2^31 items) */
#define PN_ONE_TASK 0x40000000u

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

/* A work item's counters into its row's: integer atomic adds, the same sums in any order. */
PN_KFN void pn_counters_add(PN_GLOBAL pn_shadow_counters *row, const pn_shadow_counters *c)
{
    if (c->candidates) pn_katomic_add(&row->candidates, c->candidates);
    if (c->blocking) pn_katomic_add(&row->blocking, c->blocking);
    if (c->lit) pn_katomic_add(&row->lit, c->lit);
    if (c->overflow) pn_katomic_add(&row->overflow, c->overflow);
    if (c->nodes) pn_katomic_add(&row->nodes, c->nodes);
    if (c->capped) pn_katomic_add(&row->capped, c->capped);
    if (c->exact) pn_katomic_add(&row->exact, c->exact);
}

/* The pixel of item i of a per-pixel pass over `rows` rows of a W-wide image (pixel
 * y W + x), in screen tiles of PN_PIX_TILE^2 pixels: a tile row's tiles one after another,
 * each tile's pixels row by row (the last tile of a row, and the last tile row, as wide
 * and as high as the image leaves them). A bijection of [0, W rows) onto the pixels, so
 * only the order of the items changes, never a pixel's result. Items that run one after
 * another (a task of the scalar port, a work-group) then share a tile, and with it what
 * its pixels read: the BVH nodes around their shadow rays, a wedge tile's list. In rows,
 * 512 wide, one row ran through 32 tiles' data before its neighbour row came back to the
 * first. Measured (512x512, k = 16, one thread, the same bytes, medians of 3): the
 * reference on the dragon 1,671 -> 1,457 ms and on the tree 4,486 -> 4,316 ms, the
 * wedges' pixel pass on the tree 2,039 -> 1,811 ms; 8 or 32 pixel tiles no better than 16. */
PN_KFN uint32_t pn_pix_tiled(uint32_t i, uint32_t W, uint32_t rows)
{
    uint32_t T = PN_PIX_TILE, y0 = i / (T * W) * T, r = i - y0 * W, h = pn_kminu(T, rows - y0), full = W / T;
    uint32_t tx, w, tw;
    if (h == T && r < full * T * T) /* a whole tile: shifts, no division (T is 16) */
        return (y0 + (r % (T * T)) / T) * W + r / (T * T) * T + r % T;
    if (r < full * T * h) {
        tx = r / (T * h);
        w = r - tx * T * h;
        tw = T;
    } else { /* the last tile of the row, W - full T wide */
        tx = full;
        w = r - full * T * h;
        tw = W - full * T;
    }
    return (y0 + w / tw) * W + tx * T + w % tw;
}

/* The counters' slot of item i of a pass in tiles (pn_pix_tiled; rows: the counters pool's
 * rows): one a tile (the tile's first item's, taken modulo the rows), so that two threads
 * on two tiles of one tile row do not add into the same cache line, as they would into
 * the rows they share. Only sums are read, which any slot gives alike. */
PN_KFN uint32_t pn_pix_slot(uint32_t i, uint32_t rows) { return i / (PN_PIX_TILE * PN_PIX_TILE) % rows; }

/* The G-buffer as the shadow passes read it (pn_ksurf): a pos offset of 0 (no pool there:
 * offset 0 is the context) means the frame keeps no positions and normals. */
PN_KFN_HOT pn_ksurf pn_surf_of(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K)
{
    pn_ksurf S;
    S.v = &K->view;
    S.tris = PN_POOL(const float, tris);
    S.depth = PN_POOL(const float, depth);
    S.tri_id = PN_POOL(const uint32_t, tri_id);
    S.pos = P->pos ? PN_POOL(const float, pos) : 0;
    S.nrm = P->pos ? PN_POOL(const float, nrm) : 0;
    return S;
}

/* Pixel pix's position and unit normal, as pn_surf_at gives them: the per-pixel passes'
 * path, the context set up only where the frame keeps none. */
PN_KFN_HOT void pn_pix_surf(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, size_t pix, pn_v3 *Ps,
                            pn_v3 *n)
{
    if (P->pos) {
        *Ps = pn_v3_load(PN_POOL(const float, pos) + pix * 3u);
        *n = pn_v3_load(PN_POOL(const float, nrm) + pix * 3u);
    } else {
        pn_ksurf S = pn_surf_of(A, P, K);
        pn_surf_resolve(&S, pix, Ps, n);
    }
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

/* Row y of the G-buffer: positions and normals from its depths and ids (the rasterizer's
 * resolve; alone, the pass of a G-buffer the caller drew, pn_frame_options.gbuffer). */
PN_KFN void pn_e_gbuffer_resolve(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    uint32_t x;
    for (x = 0; x < K->view.width; x++)
        pn_gbuffer_resolve(&K->view, PN_POOL(const float, tris), x, y, PN_POOL(const float, depth),
                           PN_POOL(const uint32_t, tri_id), PN_POOL(float, pos), PN_POOL(float, nrm));
}

/* Band of the G-buffer: its rows cleared, rasterized, then resolved (position, normal;
 * unless the frame keeps none, pn_surf_of), in one item so that they stay in cache. */
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
    if (P->pos)
        for (y = y0; y < y1; y++) pn_e_gbuffer_resolve(A, P, K, y);
}

/* Each algorithm's entries and its part of the list, in the list's order. */
#include "pn_passes_exact.h"
#include "pn_passes_gears.h"
#include "pn_passes_lview.h"
#include "pn_passes_srt.h"
#include "pn_passes_occtex.h"
#include "pn_passes_mcsm.h"
#include "pn_passes_wedges.h"

/* ---- Shading (pn_shade.h) --------------------------------------------------------------- */

/* Pixel: RGBA8 bytes r g b a, whatever the device's endianness. */
PN_KFN void pn_e_shade(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t pix)
{
    pn_v3 Ps, ns;
    uint32_t c;
    PN_GLOBAL uint8_t *o = PN_POOL(uint8_t, rgba) + (size_t)pix * 4u;
    pn_pix_surf(A, P, K, pix, &Ps, &ns);
    c = pn_shade_pixel(&K->view, &K->light, &K->shade, PN_POOL(const uint32_t, tri_id)[pix], Ps, ns,
                       PN_POOL(const float, vis)[pix]);
    o[0] = (uint8_t)(c & 0xFFu);
    o[1] = (uint8_t)((c >> 8) & 0xFFu);
    o[2] = (uint8_t)((c >> 16) & 0xFFu);
    o[3] = (uint8_t)(c >> 24);
}

/* ---- The list ------------------------------------------------------------------------------ */

#define PN_PASSES(X)                                \
    X(RASTER_ROWS, raster_rows, 64, 512)           \
    X(RASTER_CHUNKS, raster_chunks, 64, 1024)       \
    X(RASTER_BAND, raster_band, 1, 1)               \
    X(GBUFFER_RESOLVE, gbuffer_resolve, 16, 8)      \
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
