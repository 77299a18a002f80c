/* pn_mcsm_frame.h - the Monte Carlo shadow maps' frame (Curtis 2009), written once for every
 * port (src/pn_mcsm.c) over the passes of kernels/pn_passes.h:
 *
 *   pools; the light view's axes (pn_light_view)
 *   [row bounds of the lit origins] -> centre of projection, window (host, pn_lview_window),
 *                                      narrowed to the occluders' box (pn_lview_fit_occluders)
 *   [rows per triangle] [bands: near and far layers of the occluders]      layers
 *   [N-buffer levels 1 .. top, a row per item]                             N-buffer
 *   [pixel: classification, n x n hashed rays through the layers]          rays
 *   [pixel: blur across] [pixel: blur down]                                blur
 *
 * Each pixel's rays and each blur tap are summed in a fixed order, so every pixel's float
 * operations are the same on every port and schedule. Not installed. */
#ifndef PN_MCSM_FRAME_H
#define PN_MCSM_FRAME_H

#include "pn_internal.h"

#if PN_ENABLE_MCSM
/* The shadow pass of PN_ALGO_MCSM on fs->port. */
pn_status pn_mcsm_frame(pn_frame_state *fs);
#endif

#endif
