/* pn_srt_frame.h - selective ray tracing's frame (Lauterbach et al. 2009), written once for
 * every port (src/pn_srt.c) over the passes of kernels/pn_passes.h:
 *
 *   pools; the light view's axes (area light: U, V, N; point light: toward the scene)
 *   [row bounds of the lit origins in the light frame] -> the map window (host)
 *   [map clear] [map rows per triangle] [map bands]      the G-buffer's rasterizer
 *   [conservative rasterization of thin triangles]       unless PN_SRT_NO_CONSERVATIVE
 *   area light: [tile weights] -> largest weight (host) -> [tile mask]
 *   [classify per pixel: PIP flag, the map's answer]
 *   prefix sum of the flags -> PIP count (host); [dense PIP list]; [exact mask per PIP]
 *
 * Not installed. */
#ifndef PN_SRT_FRAME_H
#define PN_SRT_FRAME_H

#include "pn_internal.h"

#if PN_ENABLE_SRT
/* The shadow pass of PN_ALGO_SRT on fs->port. */
pn_status pn_srt_frame(pn_frame_state *fs);
#endif

#endif
