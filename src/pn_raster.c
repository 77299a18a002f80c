/* pn_raster.c - the rasterizer's per-frame set-up, shared by the G-buffer (src/pn_frame.c)
 * and every light-space map (SRT's shadow map, the occlusion textures' slices, the Monte
 * Carlo layers): a file of its own so that the algorithms' frames, which pn_frame.c
 * dispatches to, do not call back into it. */
#include "pn_device.h"
#include "pn_passes.h"

/* The rows pass given (each triangle's set-up and row range, groups of eight), then the
 * chunks pass (the boxes of the BVH-ordered triangle chunks the bands walk). */
pn_status pn_raster_setup(pn_frame_state *fs, uint32_t rows_pass)
{
    pn_status st = pn_dev_run(fs, rows_pass, PN_RASTER_GROUPS(fs->ctx->tri_count));
    if (st != PN_OK) return st;
    return pn_dev_run(fs, PN_K_RASTER_CHUNKS, PN_RASTER_CHUNKS(fs->K.raster_tris));
}
