/* pn_kpools.h - what every pass entry (kernels/pn_passes.h) receives besides its item
 * index: where the arena's pools sit, as byte offsets from its 64-byte aligned base, and
 * the frame's parameter block. A port holds the arena as one buffer (the scalar port: the
 * caller's memory itself; the OpenCL port: a device buffer mirroring it, the same pools at
 * the same offsets), so one struct of offsets replaces one argument per pool; 0 for a pool
 * the frame does not carve. Fixed-width fields only: C and OpenCL C lay both structs out
 * alike, and the OpenCL port passes them as kernel arguments verbatim. */
#ifndef PN_KPOOLS_H
#define PN_KPOOLS_H

#include "pn_ktypes.h"

typedef struct pn_kpools {
    /* persistent: the scene (index: the BVH's leaf order; rindex: the raster order) */
    uint64_t tris, flags, wnodes, index, rindex;
    /* frame: G-buffer, outputs, scratch */
    uint64_t depth, tri_id, pos, nrm, vis, rgba, rows, chunks, counters;
    /* frame: GEARS (src/pn_gears.c) */
    uint64_t faces, rects, pix_cell, row_box, cell_off, cell_pix, cell_bits, cell_rank, cell_cur, row_pairs, sorted, chunk_box, super_box;
    /* frame: the light view's row bounds (SRT, occlusion textures) */
    uint64_t lview_box;
    /* frame: occlusion textures (src/pn_occtex.c) */
    uint64_t occ_bits, occ_filt, occ_words;
    /* frame: Monte Carlo shadow maps (src/pn_mcsm.c) */
    uint64_t mc_nb, mc_tmp, mc_words;
    /* frame: selective ray tracing (src/pn_srt.c) */
    uint64_t lmap_depth, lmap_id, lmap_cons, srt_tile_w, srt_tile_h, srt_tile_mask, srt_words, pip_off, pip_list;
    /* persistent: the scene's connectivity (src/pn_connect.c); frame: penumbra wedges */
    uint64_t wg_hedge, wg_run, wg_tcomp;
    uint64_t wg_tcast, wg_soff, wg_sil, wg_bbox, wg_sbox, wg_tbox, wg_poff, wg_pairs, wg_sorted, wg_toff, wg_rowc, wg_kept;
} pn_kpools;

/* A tile of GEARS grid cells: grid rows [r0, r1] and columns [x0, x1] of one face. */
typedef struct pn_ktile {
    uint32_t face, r0, r1, x0, x1;
    uint32_t pairs; /* the tile's pairs, once counted (the chunk-box pass reads it) */
    uint32_t pad1, pad2;
} pn_ktile;

/* The parameters of one launch: the frame's camera, light and shading constants, and the
 * few per-launch values some passes read. Written by src/ before each launch. */
typedef struct pn_kparams {
    pn_kview view;
    pn_klight light;
    pn_kshade shade;
    pn_ktile tile;        /* GEARS: the tile a pass works on (grid row r0 for a row count) */
    uint32_t tri_count;   /* scene triangles */
    uint32_t raster_tris; /* entries of the raster order (rindex): the triangles a rasterizer walks */
    uint32_t exact_stats; /* GEARS masks: 1 = do not stop at a full mask (exact counters) */
    /* the light-space view (SRT: at the light centre; occlusion textures: at the centre of
     * projection behind it) and the offsets of its row bounds (pn_lview.h) */
    pn_kview lview;
    float lview_ha, lview_hb;
    pn_kocc occ;
    pn_kmc mc;
    pn_kwg wg;
    /* selective ray tracing: the classification's constants */
    float srt_delta, srt_alpha, srt_reach_u, srt_reach_v; /* reach: texels per unit splat weight */
    float srt_wmax; /* largest splat weight 1/z of the map's edge texels */
    uint32_t srt_flags, srt_tiles;
} pn_kparams;

/* Typed pointer to pool `name` of arena A (the entries' arguments A and P). */
#define PN_POOL(type, name) ((PN_GLOBAL type *)(A + P->name))

#endif
