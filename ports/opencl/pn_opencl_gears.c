/* pn_opencl_gears.c - GEARS on the OpenCL port: the host sequence of src/pn_gears_host.h
 * with kernels/pn_gears.cl for the work items. Pools stay on the device; the host reads
 * back only what its steps read (row boxes and counters, pixels per cell, pairs per grid
 * row, the counts of a row being split, a tile's pair total and cell offsets).
 *
 * Per tile: count per triangle -> prefix sum (pn_scan.cl) -> scatter pairs -> histogram
 * of pairs per cell -> its prefix sum -> fill each cell's slots with atomic cursors ->
 * sort each cell's ids -> masks. Scratch for a prefix sum's block partials is a pool that
 * is idle at that moment: cell_cur while tri_off is summed, tri_off while cell_off is. */
#include <string.h>

#include "pn_gears_host.h"
#include "pn_opencl_internal.h"

#if PN_ENABLE_GEARS

typedef struct pn_cl_gears_run {
    pn_opencl *cl;
    pn_context *ctx;
    pn_frame_state *fs;
    pn_kpools *P;
    pn_gears_frame g;
    pn_ktile tile;
    cl_uint T, npix, res;
} pn_cl_gears_run;

static pn_status pn_cl_gears_tile(pn_cl_gears_run *r)
{
    pn_opencl *cl = r->cl;
    pn_gears_frame *g = &r->g;
    cl_uint need, cells = g->cells, exact = r->fs->exact_stats, width = r->fs->width;
    pn_status st;
    if ((st = PN_CL_RUN(cl, PN_CLK_GEARS_COUNT, r->T, &r->tile, &r->res, &cl->arena, r->P, &r->T)) != PN_OK ||
        (st = pn_cl_scan(cl, g->tri_off, r->T, g->cell_cur, g->cells_max)) != PN_OK ||
        (st = pn_cl_read(cl, g->tri_off + r->T, sizeof(uint32_t), "GEARS tile pair count")) != PN_OK)
        return st;
    need = g->tri_off[r->T];
    if ((st = pn_gears_tile_pairs(r->ctx, g, need)) != PN_OK) return st;
    if ((st = PN_CL_RUN(cl, PN_CLK_GEARS_SCATTER, r->T, &r->tile, &r->res, &cl->arena, r->P, &r->T)) != PN_OK ||
        (st = pn_cl_fill_u32(cl, g->cell_cur, cells, 0u, "clearing GEARS cell counts")) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_GEARS_CELL_HIST, need, &cl->arena, r->P, &need)) != PN_OK ||
        (st = pn_cl_copy(cl, g->cell_off, g->cell_cur, (size_t)cells * 4u, "GEARS cell counts")) != PN_OK ||
        (st = pn_cl_scan(cl, g->cell_off, cells, g->tri_off, r->ctx->limits.max_triangles + 1u)) != PN_OK ||
        (st = pn_cl_copy(cl, g->cell_cur, g->cell_off, (size_t)cells * 4u, "GEARS cell cursors")) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_GEARS_CELL_FILL, need, &cl->arena, r->P, &need)) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_GEARS_CELL_SORT, cells, &cl->arena, r->P, &cells)) != PN_OK ||
        (st = pn_cl_read(cl, g->cell_off, ((size_t)cells + 1u) * 4u, "GEARS cell offsets")) != PN_OK)
        return st;
    pn_gears_tile_cells(g);
    return PN_CL_RUN(cl, PN_CLK_GEARS_MASKS, r->npix, &r->fs->light, &r->tile, &r->res, &exact, &cl->arena, r->P,
                     &width, &r->npix);
}

/* The GEARS pools into the kernels' pool offsets. */
static void pn_cl_gears_pools(const pn_opencl *cl, const pn_gears_frame *g, pn_kpools *P)
{
    P->rects = pn_cl_off(cl, g->rects);
    P->tri_off = pn_cl_off(cl, g->tri_off);
    P->pix_cell = pn_cl_off(cl, g->pix_cell);
    P->row_box = pn_cl_off(cl, g->row_box);
    P->cell_off = pn_cl_off(cl, g->cell_off);
    P->cell_pix = pn_cl_off(cl, g->cell_pix);
    P->cell_cur = pn_cl_off(cl, g->cell_cur);
    P->row_pairs = pn_cl_off(cl, g->row_pairs);
    P->pairs = pn_cl_off(cl, g->pairs);
    P->sorted = pn_cl_off(cl, g->sorted);
}

pn_status pn_cl_gears(pn_opencl *cl, pn_context *ctx, pn_frame_state *fs, pn_kpools *P)
{
    pn_cl_gears_run r;
    pn_gears_frame *g = &r.g;
    cl_uint width = fs->width, height = fs->height;
    uint32_t action;
    pn_status st;
    memset(&r, 0, sizeof(r));
    r.cl = cl;
    r.ctx = ctx;
    r.fs = fs;
    r.P = P;
    r.T = ctx->tri_count;
    r.npix = width * height;
    if ((st = pn_gears_begin(ctx, fs, g)) != PN_OK) return st;
    pn_cl_gears_pools(cl, g, P);
    r.res = g->faces.res;

    /* A.1/A.2: origins, cameras, grid bounds, pixel cells. */
    if ((st = PN_CL_RUN(cl, PN_CLK_GEARS_ORIGINS, height, &fs->light, &cl->arena, P, &width, &height)) != PN_OK ||
        (st = pn_cl_read(cl, g->row_box, (size_t)height * 32u, "GEARS row boxes")) != PN_OK ||
        (st = pn_cl_read(cl, fs->counters, (size_t)height * sizeof(pn_shadow_counters), "GEARS lit counts")) != PN_OK)
        return st;
    if (!pn_gears_cameras(ctx, fs, g)) return PN_OK;
    if (!fs->light.is_point) {
        if ((st = PN_CL_RUN(cl, PN_CLK_GEARS_PROJECT, height, &fs->light, &g->faces.f[0], &cl->arena, P, &width,
                            &height)) != PN_OK ||
            (st = pn_cl_read(cl, g->row_box, (size_t)height * 32u, "GEARS projected row boxes")) != PN_OK)
            return st;
        pn_gears_grid(fs, g);
    }
    if ((st = pn_cl_fill_u32(cl, g->cell_pix, g->cells, 0u, "clearing GEARS pixels per cell")) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_GEARS_PIXEL_CELLS, r.npix, &fs->light, &g->faces, &cl->arena, P, &r.npix)) != PN_OK ||
        (st = pn_cl_read(cl, g->cell_pix, (size_t)g->cells * 4u, "GEARS pixels per cell")) != PN_OK)
        return st;

    /* A.3: every triangle's rectangle of cells on every face; pairs per grid row. */
    if ((st = PN_CL_RUN(cl, PN_CLK_GEARS_TRI_RECTS, r.T, &g->faces, &fs->light, &cl->arena, P, &r.T)) != PN_OK ||
        (st = pn_cl_fill_u32(cl, g->row_pairs, (size_t)g->rows * 2u, 0u, "clearing GEARS pairs per row")) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_GEARS_ROW_PAIRS, r.T, &g->faces, &cl->arena, P, &r.T)) != PN_OK ||
        (st = pn_cl_read(cl, g->row_pairs, (size_t)g->rows * 8u, "GEARS pairs per row")) != PN_OK)
        return st;

    for (;;) {
        if ((st = pn_gears_plan_next(ctx, g, &r.tile, &action)) != PN_OK) return st;
        if (action == PN_GEARS_PLAN_DONE) break;
        if (action == PN_GEARS_PLAN_COUNT_ROW)
            st = pn_cl_fill_u32(cl, g->cell_cur, r.res, 0u, "clearing GEARS row counts");
        if (st == PN_OK && action == PN_GEARS_PLAN_COUNT_ROW)
            st = PN_CL_RUN(cl, PN_CLK_GEARS_ROW_CELLS, r.T, &r.tile, &r.res, &cl->arena, P, &r.T);
        if (st == PN_OK && action == PN_GEARS_PLAN_COUNT_ROW)
            st = pn_cl_read(cl, g->cell_cur, (size_t)r.res * 4u, "GEARS row counts");
        if (st == PN_OK && action == PN_GEARS_PLAN_TILE) st = pn_cl_gears_tile(&r);
        if (st != PN_OK) return st;
    }
    pn_gears_end(ctx, g);
    return PN_OK;
}

#endif
