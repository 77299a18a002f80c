/* pn_gears_host.h - GEARS host helpers shared by the ports (src/pn_gears.c). */
#ifndef PN_GEARS_HOST_H
#define PN_GEARS_HOST_H

#include "pn_internal.h"
#include "pn_gears.h"

#if PN_ENABLE_GEARS
/* Grid cameras for a frame: 1 face for an area light, 6 (a cube) for a point light.
 * obox: min xyz, max xyz of the shadow-ray origins of lit pixels. */
uint32_t pn_gears_faces(const pn_klight *L, const float obox[6], float scene_diag, pn_kgrid faces[6]);
void pn_gears_bounds(pn_kgrid *g, float x0, float y0, float x1, float y1, uint32_t res);
uint32_t pn_gears_next_tile(const uint64_t *row_pairs, uint32_t rows, uint32_t start, uint64_t pool,
                            uint32_t *end_out);
#endif

#endif
