/* pn_scalar_gears.c - GEARS on the scalar port (paper §3-4): the work items of
 * kernels/pn_gears_pass.h looped over rows, pixels and triangle chunks, between the host
 * steps of src/pn_gears.c (see pn_gears_host.h for the sequence).
 * Work items write disjoint memory or add integers atomically; the prefix sums and the
 * stable counting sort run on the calling thread, so the result and every statistic are
 * independent of the schedule. */
#include <string.h>

#include "pn_gears_host.h"
#include "pn_scalar.h"

#if PN_ENABLE_GEARS

#define PN_TRI_CHUNK 4096u

typedef struct pn_gears_run {
    pn_context *ctx;
    pn_frame_state *fs;
    pn_gears_frame g;
    pn_ktile tile;
    uint32_t chunks;
} pn_gears_run;

/* Triangles [t0, t1) of chunk c. */
static void pn_chunk(const pn_gears_run *r, uint32_t c, uint32_t *t0, uint32_t *t1)
{
    uint32_t n = r->ctx->tri_count;
    *t0 = c * PN_TRI_CHUNK;
    *t1 = (c + 1u) * PN_TRI_CHUNK < n ? (c + 1u) * PN_TRI_CHUNK : n;
}

static void pn_task_origins(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    uint32_t y;
    for (y = begin; y < end; y++)
        pn_gears_origins_row(&fs->light, fs->width, y, fs->tri_id, fs->pos, fs->nrm, fs->vis, r->g.row_box,
                             (pn_shadow_counters *)fs->counters);
}

static void pn_task_project(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    uint32_t y;
    for (y = begin; y < end; y++)
        pn_gears_project_row(&fs->light, &r->g.faces.f[0], fs->width, y, fs->tri_id, fs->pos, fs->nrm, r->g.row_box);
}

static void pn_task_pixel_cells(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    uint32_t y, x;
    for (y = begin; y < end; y++)
        for (x = 0; x < fs->width; x++)
            pn_gears_pixel_cell(&fs->light, &r->g.faces, fs->tri_id, fs->pos, fs->nrm, (size_t)y * fs->width + x,
                                r->g.pix_cell, r->g.cell_pix);
}

static void pn_task_tri_rects(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t c, t, t1;
    for (c = begin; c < end; c++)
        for (pn_chunk(r, c, &t, &t1); t < t1; t++)
            pn_gears_tri_rects(&r->g.faces, &r->fs->light, r->ctx->tris, r->ctx->flags, t, r->g.rects);
}

static void pn_task_row_pairs(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t c, t, t1;
    for (c = begin; c < end; c++)
        for (pn_chunk(r, c, &t, &t1); t < t1; t++)
            pn_gears_tri_row_pairs(&r->g.faces, r->g.rects, r->g.cell_pix, t, r->g.row_pairs);
}

static void pn_task_row_cells(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t c, t, t1;
    for (c = begin; c < end; c++)
        for (pn_chunk(r, c, &t, &t1); t < t1; t++)
            pn_gears_tri_row_cells(r->g.rects, r->g.cell_pix, r->g.faces.res, r->tile.face, r->tile.r0, t,
                                   r->g.cell_cur);
}

static void pn_task_count(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t c, t, t1;
    for (c = begin; c < end; c++)
        for (pn_chunk(r, c, &t, &t1); t < t1; t++)
            r->g.tri_off[t] = pn_gears_tri_count(r->g.rects, r->g.cell_pix, r->g.faces.res, &r->tile, t);
}

static void pn_task_scatter(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t c, t, t1;
    for (c = begin; c < end; c++)
        for (pn_chunk(r, c, &t, &t1); t < t1; t++)
            pn_gears_tri_scatter(r->g.rects, r->g.cell_pix, r->g.faces.res, &r->tile, t, r->g.tri_off[t], r->g.pairs);
}

static void pn_task_masks(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    uint32_t y, x;
    for (y = begin; y < end; y++) {
        pn_shadow_counters *cnt = (pn_shadow_counters *)fs->counters + y;
        for (x = 0; x < fs->width; x++) {
            size_t pix = (size_t)y * fs->width + x;
            float v;
            if (pn_gears_pixel_mask(&fs->light, fs->exact_stats, &r->tile, r->g.faces.res, fs->tri_id, fs->pos,
                                    fs->nrm, r->g.pix_cell, r->g.cell_off, r->g.sorted, r->ctx->tris, pix, cnt, &v))
                fs->vis[pix] = v;
        }
    }
}

/* One tile: count -> exclusive prefix sum -> scatter -> stable counting sort by cell ->
 * masks. */
static pn_status pn_gears_tile(pn_gears_run *r)
{
    pn_context *ctx = r->ctx;
    pn_gears_frame *g = &r->g;
    uint32_t T = ctx->tri_count, t, c, acc = 0;
    uint64_t need = 0;
    pn_status st;
    pn_run(ctx, r->chunks, pn_task_count, r);
    for (t = 0; t < T; t++) {
        uint32_t n = g->tri_off[t];
        g->tri_off[t] = (uint32_t)need;
        need += n;
    }
    g->tri_off[T] = (uint32_t)need;
    if ((st = pn_gears_tile_pairs(ctx, g, need)) != PN_OK) return st;
    pn_run(ctx, r->chunks, pn_task_scatter, r);
    memset(g->cell_cur, 0, (size_t)g->cells * 4u);
    for (t = 0; t < (uint32_t)need; t++) g->cell_cur[g->pairs[(size_t)t * 2u]]++;
    for (c = 0; c < g->cells; c++) {
        uint32_t n = g->cell_cur[c];
        g->cell_off[c] = acc;
        g->cell_cur[c] = acc;
        acc += n;
    }
    g->cell_off[g->cells] = acc;
    /* Stable: pairs are in triangle order, so each cell lists its triangles ascending. */
    for (t = 0; t < (uint32_t)need; t++) g->sorted[g->cell_cur[g->pairs[(size_t)t * 2u]]++] = g->pairs[(size_t)t * 2u + 1u];
    pn_gears_tile_cells(g);
    pn_run(ctx, r->fs->height, pn_task_masks, r);
    return PN_OK;
}

pn_status pn_scalar_gears(pn_context *ctx, pn_frame_state *fs)
{
    pn_gears_run r;
    uint32_t action;
    pn_status st;

    memset(&r, 0, sizeof(r));
    r.ctx = ctx;
    r.fs = fs;
    r.chunks = (ctx->tri_count + PN_TRI_CHUNK - 1u) / PN_TRI_CHUNK;
    if ((st = pn_gears_begin(ctx, fs, &r.g)) != PN_OK) return st;

    /* A.1/A.2: origins, cameras, grid bounds, pixel cells. */
    pn_run(ctx, fs->height, pn_task_origins, &r);
    if (!pn_gears_cameras(ctx, fs, &r.g)) return PN_OK;
    if (!fs->light.is_point) {
        pn_run(ctx, fs->height, pn_task_project, &r);
        pn_gears_grid(fs, &r.g);
    }
    memset(r.g.cell_pix, 0, (size_t)r.g.cells * 4u);
    pn_run(ctx, fs->height, pn_task_pixel_cells, &r);

    /* A.3: every triangle's rectangle of cells on every face; pairs per grid row. */
    pn_run(ctx, r.chunks, pn_task_tri_rects, &r);
    memset(r.g.row_pairs, 0, (size_t)r.g.rows * 8u);
    pn_run(ctx, r.chunks, pn_task_row_pairs, &r);

    for (;;) {
        if ((st = pn_gears_plan_next(ctx, &r.g, &r.tile, &action)) != PN_OK) return st;
        if (action == PN_GEARS_PLAN_DONE) break;
        if (action == PN_GEARS_PLAN_COUNT_ROW) {
            memset(r.g.cell_cur, 0, (size_t)r.g.faces.res * 4u);
            pn_run(ctx, r.chunks, pn_task_row_cells, &r);
        } else if ((st = pn_gears_tile(&r)) != PN_OK) {
            return st;
        }
    }
    pn_gears_end(ctx, &r.g);
    return PN_OK;
}

#endif
