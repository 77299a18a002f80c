/* pn_gears_frame.h - GEARS' frame (paper §3-4), written once for every port
 * (src/pn_gears.c) as a sequence of the passes in kernels/pn_passes.h and host steps:
 *
 *   pools, statistics reset
 *   [origins per row]                    -> row boxes and lit counts to the host
 *   grid cameras                         nothing lit: the frame is done
 *   [projected box per row]              area light only, then the grid bounds
 *   [pixel cells and occupancy bits, cell_bits zeroed first] [their prefixes per grid row]
 *   [cell rectangles per triangle] [pairs per grid row, row_pairs zeroed first]
 *   tile plan, step by step:
 *     a new face   [pixels per cell of that face, cell_pix zeroed first] -> to the host
 *     count a row  pairs per cell of grid row (face, r0), as a tile's below -> to the host
 *     tile         pairs per cell of its rows: [differences per triangle, cell_cur zeroed
 *                  first] [running sums per grid row] -> prefix sum: cell offsets -> to
 *                  the host; [each triangle into its cells' next slots] [each cell's run
 *                  sorted] [chunk boxes] [masks per pixel]
 *   statistics into the context
 *
 * The host reads back only what its steps read (row boxes and counters, a face's pixels per cell,
 * pairs per grid row, the counts of a row being split, a tile's cell offsets and their
 * total); the large pools stay on the device. Not installed. */
#ifndef PN_GEARS_FRAME_H
#define PN_GEARS_FRAME_H

#include "pn_internal.h"

#if PN_ENABLE_GEARS
#include "pn_gears_pass.h"

/* Grid cameras for a frame: 1 face for an area light, 6 (a cube) for a point light.
 * obox: min xyz, max xyz of the shadow-ray origins of lit pixels. */
uint32_t pn_gears_faces(const pn_klight *L, const float obox[6], float scene_diag, pn_kgrid faces[6]);
void pn_gears_bounds(pn_kgrid *g, float x0, float y0, float x1, float y1, uint32_t res);

/* The shadow pass of PN_ALGO_GEARS on fs->port. */
pn_status pn_gears_frame(pn_frame_state *fs);
#endif

#endif
