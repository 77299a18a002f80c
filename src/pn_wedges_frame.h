/* pn_wedges_frame.h - the penumbra wedges' frame (Akenine-Moller and Assarsson 2002, with
 * the overlap blending of Forest et al. 2006), written once for every port
 * (src/pn_wedges.c) over the passes of kernels/pn_passes.h:
 *
 *   pools (the connectivity of src/pn_connect.c is persistent, built at pn_scene_set)
 *   [triangle: how it casts, seen from the light centre]
 *   [edge: non-zero net winding -> 1]  scan -> silhouette slots      silhouettes
 *   [edge: silhouette record, its wedge's screen tiles, its pair count]  scan
 *   [silhouette: (tile, silhouette) pairs]  sort by tile              binning
 *   [pixel: centre ray, then its tile's wedges object by object]      wedges and blending
 *
 * A point light has no penumbra: no silhouettes, and each pixel's centre ray decides.
 * Each pixel sums its tile's silhouettes in ascending order, so the result is the same on
 * every port and schedule. Not installed. */
#ifndef PN_WEDGES_FRAME_H
#define PN_WEDGES_FRAME_H

#include "pn_internal.h"

#if PN_ENABLE_WEDGES
/* The shadow pass of PN_ALGO_WEDGES on fs->port. */
pn_status pn_wedges_frame(pn_frame_state *fs);
#endif


#endif
