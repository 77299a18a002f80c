/* pn_gears.cl - OpenCL entry points of GEARS (kernels/pn_gears_pass.h): one work item per
 * row, pixel, triangle, pair or cell. The host steps between them are src/pn_gears.c; the
 * sequence is in src/pn_gears_host.h and ports/opencl/pn_opencl_gears.c.
 *
 * Sorting pairs by cell: a histogram (atomic increments), its prefix sum (pn_scan.cl),
 * then every pair takes the next slot of its cell with an atomic increment, which puts a
 * cell's triangles in whatever order the work items ran; sorting each cell's run of
 * distinct ids then gives the one ascending order the scalar port's stable counting sort
 * produces. */
#pragma OPENCL FP_CONTRACT OFF
#include "pn_kpools.h"
#include "pn_gears_pass.h"
#include "pn_sort.h"
#include "pn_kcl.h"

__kernel void pn_k_gears_origins(pn_klight L, __global uchar *A, pn_kpools P, uint width, uint height)
{
    uint y = (uint)get_global_id(0);
    if (y >= height) return;
    pn_gears_origins_row(&L, width, y, PN_POOL(const uint, tri_id), PN_POOL(const float, pos),
                         PN_POOL(const float, nrm), PN_POOL(float, vis), PN_POOL(float, row_box),
                         PN_POOL(pn_shadow_counters, counters));
}

__kernel void pn_k_gears_project(pn_klight L, pn_kgrid g, __global uchar *A, pn_kpools P, uint width, uint height)
{
    uint y = (uint)get_global_id(0);
    if (y >= height) return;
    pn_gears_project_row(&L, &g, width, y, PN_POOL(const uint, tri_id), PN_POOL(const float, pos),
                         PN_POOL(const float, nrm), PN_POOL(float, row_box));
}

__kernel void pn_k_gears_pixel_cells(pn_klight L, pn_kfaces F, __global uchar *A, pn_kpools P, uint npix)
{
    size_t pix = get_global_id(0);
    if (pix >= npix) return;
    pn_gears_pixel_cell(&L, &F, PN_POOL(const uint, tri_id), PN_POOL(const float, pos), PN_POOL(const float, nrm),
                        pix, PN_POOL(uint, pix_cell), PN_POOL(uint, cell_pix));
}

__kernel void pn_k_gears_tri_rects(pn_kfaces F, pn_klight L, __global uchar *A, pn_kpools P, uint tri_count)
{
    uint t = (uint)get_global_id(0);
    if (t >= tri_count) return;
    pn_gears_tri_rects(&F, &L, PN_POOL(const float, tris), PN_POOL(const uchar, flags), t,
                       PN_POOL(pn_cellrect, rects));
}

__kernel void pn_k_gears_row_pairs(pn_kfaces F, __global uchar *A, pn_kpools P, uint tri_count)
{
    uint t = (uint)get_global_id(0);
    if (t >= tri_count) return;
    pn_gears_tri_row_pairs(&F, PN_POOL(const pn_cellrect, rects), PN_POOL(const uint, cell_pix), t,
                           PN_POOL(uint, row_pairs));
}

/* The per-cell counts of grid row tile.r0 of tile.face go to cell_cur[0 .. res). */
__kernel void pn_k_gears_row_cells(pn_ktile tile, uint res, __global uchar *A, pn_kpools P, uint tri_count)
{
    uint t = (uint)get_global_id(0);
    if (t >= tri_count) return;
    pn_gears_tri_row_cells(PN_POOL(const pn_cellrect, rects), PN_POOL(const uint, cell_pix), res, tile.face, tile.r0,
                           t, PN_POOL(uint, cell_cur));
}

__kernel void pn_k_gears_count(pn_ktile tile, uint res, __global uchar *A, pn_kpools P, uint tri_count)
{
    uint t = (uint)get_global_id(0);
    if (t >= tri_count) return;
    PN_POOL(uint, tri_off)[t] =
        pn_gears_tri_count(PN_POOL(const pn_cellrect, rects), PN_POOL(const uint, cell_pix), res, &tile, t);
}

__kernel void pn_k_gears_scatter(pn_ktile tile, uint res, __global uchar *A, pn_kpools P, uint tri_count)
{
    uint t = (uint)get_global_id(0);
    if (t >= tri_count) return;
    pn_gears_tri_scatter(PN_POOL(const pn_cellrect, rects), PN_POOL(const uint, cell_pix), res, &tile, t,
                         PN_POOL(const uint, tri_off)[t], PN_POOL(uint, pairs));
}

/* Pairs per cell into cell_cur (zeroed beforehand). */
__kernel void pn_k_gears_cell_hist(__global uchar *A, pn_kpools P, uint npairs)
{
    uint p = (uint)get_global_id(0);
    if (p >= npairs) return;
    atomic_inc(PN_POOL(uint, cell_cur) + PN_POOL(const uint, pairs)[(size_t)p * 2u]);
}

/* Each pair's triangle into the next free slot of its cell (cell_cur: the cells' starts). */
__kernel void pn_k_gears_cell_fill(__global uchar *A, pn_kpools P, uint npairs)
{
    uint p = (uint)get_global_id(0), slot;
    if (p >= npairs) return;
    slot = atomic_inc(PN_POOL(uint, cell_cur) + PN_POOL(const uint, pairs)[(size_t)p * 2u]);
    PN_POOL(uint, sorted)[slot] = PN_POOL(const uint, pairs)[(size_t)p * 2u + 1u];
}

__kernel void pn_k_gears_cell_sort(__global uchar *A, pn_kpools P, uint cells)
{
    uint c = (uint)get_global_id(0), e0;
    if (c >= cells) return;
    e0 = PN_POOL(const uint, cell_off)[c];
    pn_sort_u32(PN_POOL(uint, sorted) + e0, PN_POOL(const uint, cell_off)[c + 1u] - e0);
}

__kernel void pn_k_gears_masks(pn_klight L, pn_ktile tile, uint res, uint exact, __global uchar *A, pn_kpools P,
                               uint width, uint npix)
{
    size_t pix = get_global_id(0);
    pn_shadow_counters c = {0u, 0u, 0u, 0u};
    float v;
    if (pix >= npix) return;
    if (!pn_gears_pixel_mask(&L, exact, &tile, res, PN_POOL(const uint, tri_id), PN_POOL(const float, pos),
                             PN_POOL(const float, nrm), PN_POOL(const uint, pix_cell), PN_POOL(const uint, cell_off),
                             PN_POOL(const uint, sorted), PN_POOL(const float, tris), pix, &c, &v))
        return;
    PN_POOL(float, vis)[pix] = v;
    pn_counters_add(PN_POOL(pn_shadow_counters, counters) + pix / width, &c);
}
