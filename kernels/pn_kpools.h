/* pn_kpools.h - where the arena's pools sit, as byte offsets from its 64-byte aligned
 * base, for a port that holds the whole arena as one buffer (the OpenCL port mirrors it
 * on the device: the same pools at the same offsets). One struct instead of one kernel
 * argument per pool; 0 for a pool the frame does not carve. */
#ifndef PN_KPOOLS_H
#define PN_KPOOLS_H

#include "pn_kernel.h"

typedef struct pn_kpools {
    /* persistent: the scene */
    uint64_t tris, flags, nodes, index;
    /* frame: G-buffer, outputs, scratch */
    uint64_t depth, tri_id, pos, nrm, vis, rgba, rows, counters;
    /* frame: GEARS (pn_gears_frame in src/pn_gears_host.h) */
    uint64_t rects, tri_off, pix_cell, row_box, cell_off, cell_pix, cell_cur, row_pairs, pairs, sorted;
} pn_kpools;

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
/* Typed pointer to pool `name` of arena A (kernel arguments A and P). */
#define PN_POOL(type, name) ((__global type *)(A + P.name))
#endif

#endif
