/* pn_gears_host.h - the host side of a GEARS frame, shared by the ports (src/pn_gears.c).
 *
 * A port runs a frame as this sequence, doing the work items of kernels/pn_gears_pass.h
 * its own way (loops, kernels) between the host steps:
 *
 *   pn_gears_begin                       pools, statistics reset
 *   [origins per row]
 *   pn_gears_cameras                     0: nothing lit, the frame is done
 *   [projected box per row]              area light only, then pn_gears_grid
 *   [pixel cells, cell_pix zeroed first] [cell rectangles per triangle]
 *   [pairs per grid row, row_pairs zeroed first]
 *   loop pn_gears_plan_next:
 *     PN_GEARS_PLAN_COUNT_ROW  [pairs per cell of grid row (face, r0) into cell_cur[0 .. res)]
 *     PN_GEARS_PLAN_TILE       [count per triangle, exclusive prefix sum into tri_off]
 *                              pn_gears_tile_pairs(need)
 *                              [scatter, sort by cell: cell_off, sorted]
 *                              pn_gears_tile_cells
 *                              [masks per pixel]
 *   pn_gears_end                         statistics into the context
 *
 * Everything the host steps read must be in host memory when they run: row_box and the
 * row counters after the row steps, cell_pix, row_pairs, cell_cur[0 .. res) and cell_off
 * (the OpenCL port reads those few back; the large pools stay on the device). */
#ifndef PN_GEARS_HOST_H
#define PN_GEARS_HOST_H

#include "pn_internal.h"
#include "pn_gears_pass.h"

#if PN_ENABLE_GEARS
/* Grid cameras for a frame: 1 face for an area light, 6 (a cube) for a point light.
 * obox: min xyz, max xyz of the shadow-ray origins of lit pixels. */
uint32_t pn_gears_faces(const pn_klight *L, const float obox[6], float scene_diag, pn_kgrid faces[6]);
void pn_gears_bounds(pn_kgrid *g, float x0, float y0, float x1, float y1, uint32_t res);

/* One frame's pools (addresses in the arena, carved in the order of pn_frame_pools() in
 * pn_arena.c), grid, tile plan and statistics. */
typedef struct pn_gears_frame {
    pn_kfaces faces;
    pn_cellrect *rects;  /* [max_triangles * 6]: rectangle of triangle t on face f at t * 6 + f */
    uint32_t *tri_off;   /* [max_triangles + 1]: pairs per triangle, then their prefix sum */
    uint32_t *pix_cell;  /* [pixels]: global cell or PN_CELL_NONE */
    float *row_box;      /* [height * 8]: box of a row's origins (3-D, then projected 2-D) */
    uint32_t *cell_off;  /* [cells + 1]: a tile's pairs per cell, prefix-summed */
    uint32_t *cell_pix;  /* [cells]: pixels per cell */
    uint32_t *cell_cur;  /* [cells]: sort cursors; the counts of a grid row being split */
    uint32_t *row_pairs; /* [rows * 2]: pairs per global grid row, low and high word */
    uint32_t *pairs;     /* [pool * 2]: (global cell, triangle) */
    uint32_t *sorted;    /* [pool]: triangles by cell, ascending within a cell */
    uint32_t cells_max;  /* capacity of the per-cell pools */
    uint32_t cells;      /* faces * res^2 */
    uint32_t rows;       /* faces * res: global grid rows */
    uint32_t pool;       /* pairs one tile may hold */
    uint64_t lit;
    /* tile plan: runs of global rows [start, end) handed out face by face from s0; a row
     * too big for the pool (split) handed out as runs of cells from xs */
    uint32_t plan_start, plan_end, plan_s0, plan_split, plan_xs, plan_counted;
    /* statistics over all tiles */
    uint64_t total_pairs, assignments, sum_tris_cell;
    uint32_t tiles, pairs_high, max_tris_cell;
} pn_gears_frame;

enum { PN_GEARS_PLAN_DONE = 0, PN_GEARS_PLAN_TILE = 1, PN_GEARS_PLAN_COUNT_ROW = 2 };

pn_status pn_gears_begin(pn_context *ctx, const pn_frame_state *fs, pn_gears_frame *g);
/* Joins the row boxes and lit counts of the origins step; returns 0 when no pixel is lit
 * (nothing can be shadowed: the frame is done), else sets up the grid cameras (and, for a
 * point light, their bounds) and returns 1. */
uint32_t pn_gears_cameras(pn_context *ctx, const pn_frame_state *fs, pn_gears_frame *g);
/* Area light: the grid bounds from the projected row boxes. */
void pn_gears_grid(const pn_frame_state *fs, pn_gears_frame *g);
/* The next step of the tile plan into *action; *tile is the tile to run, or for
 * PN_GEARS_PLAN_COUNT_ROW the grid row (face, r0) whose per-cell pair counts the port must
 * put into cell_cur[0 .. res) before calling again. PN_E_POOL_EXHAUSTED when one cell
 * alone needs more pairs than the pool. */
pn_status pn_gears_plan_next(pn_context *ctx, pn_gears_frame *g, pn_ktile *tile, uint32_t *action);
/* A tile needs `need` pairs (tri_off[tri_count]); PN_E_INTERNAL if the plan was wrong. */
pn_status pn_gears_tile_pairs(pn_context *ctx, pn_gears_frame *g, uint64_t need);
/* Statistics of a sorted tile, from cell_off and cell_pix. */
void pn_gears_tile_cells(pn_gears_frame *g);
void pn_gears_end(pn_context *ctx, const pn_gears_frame *g);
#endif

#endif
