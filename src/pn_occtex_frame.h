/* pn_occtex_frame.h - the occlusion textures' frame (Eisemann & Decoret 2006), written once
 * for every port (src/pn_occtex.c) over the passes of kernels/pn_passes.h:
 *
 *   pools; the light view's axes (pn_light_view)
 *   [row bounds of the lit origins] -> centre of projection, window, deepest origin (host)
 *   nearest geometry in front of the light (host, over the scene copy) -> the slice planes
 *   [rows per triangle] [bands: every fragment sets its slices' bits]     the slicing
 *   [init per pixel]
 *   per slice above some origin, holding any bit:
 *     [filter: N-buffer levels | summed-area rows, columns | mipmap levels]  pre-filtering
 *     [lookup per pixel: the slice's weighted occlusion combined in]      lookups
 *   [finish per pixel: times the horizon's visible fraction]
 *
 * Slices are combined in a fixed order (0 nearest the light first), one launch each, so
 * every pixel's sequence of float operations is the same on every port and schedule.
 * Not installed. */
#ifndef PN_OCCTEX_FRAME_H
#define PN_OCCTEX_FRAME_H

#include "pn_internal.h"

#if PN_ENABLE_OCCTEX
/* The shadow pass of PN_ALGO_OCCTEX on fs->port. */
pn_status pn_occtex_frame(pn_frame_state *fs);
#endif

#endif
