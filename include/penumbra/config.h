/* penumbra/config.h - compile-time configuration, documented defaults.
 *
 * Put overrides in your own header and build with -DPN_CONFIG_FILE='"my_config.h"'; it is
 * included first, and every option below only takes its default when still undefined.
 * Options are numbers or 0/1, never "defined or not": build with -Wundef so that a
 * misspelt option fails the build instead of silently taking a default.
 * check_config.h (included at the end) rejects inconsistent settings with #error. */
#ifndef PN_CONFIG_H
#define PN_CONFIG_H

#ifdef PN_CONFIG_FILE
#include PN_CONFIG_FILE
#endif

/* ---- Algorithms compiled in (0 or 1). ------------------------------------------------
 * A disabled algorithm costs no code; asking for it at run time gives PN_E_UNSUPPORTED. */

/* Exact k x k visibility through a BVH: the ground truth. Required by the tests. */
#ifndef PN_ENABLE_REFERENCE
#define PN_ENABLE_REFERENCE 1
#endif

/* GEARS (Wang et al. 2014): exact k x k visibility from per-pixel potentially blocking
 * triangle sets on a light-aligned grid. Costs the GEARS frame pools below. */
#ifndef PN_ENABLE_GEARS
#define PN_ENABLE_GEARS 1
#endif

/* Per-sample ray tracing: k^2 shadow segments per pixel, each traced alone through the
 * BVH to its first blocker, with the reference's predicate (so the same bits). The
 * baseline GEARS is measured against; costs no arena. */
#ifndef PN_ENABLE_RAYTRACE
#define PN_ENABLE_RAYTRACE 1
#endif

/* Selective ray tracing (Lauterbach et al. 2009): a shadow map from the light centre
 * everywhere, the exact reference path only for the pixels the map may get wrong.
 * Approximate (rare misses, measured against the reference in docs/bench/RESULTS.md).
 * Costs the SRT frame pools below. */
#ifndef PN_ENABLE_SRT
#define PN_ENABLE_SRT 1
#endif

/* Largest SRT shadow-map resolution per axis (the frame option srt.map, default the
 * smaller of 2048 and this, may be any value from 8 up to it; pn_limits.srt_map_max lowers
 * it per context). Costs 12 bytes of frame arena per texel (depth 4, triangle id 4, thin-
 * triangle mark 4; 48 MiB at 2048) plus 8 per 64 texels (penumbra tiles), plus 8 bytes per
 * pixel (PIP list). Range 8 .. 8192. */
#ifndef PN_SRT_MAP_MAX
#define PN_SRT_MAP_MAX 2048u
#endif

/* Occlusion textures (Eisemann & Decoret 2006): the scene cut into slices parallel to the
 * light, one binary occlusion texture per slice, box-filtered by an N-buffer, a summed-area
 * table or a mipmap and combined by probability. Approximate (no exact path at all; its
 * error against the reference is in docs/bench/RESULTS.md). Costs the pools below. */
#ifndef PN_ENABLE_OCCTEX
#define PN_ENABLE_OCCTEX 1
#endif

/* Largest occlusion-texture resolution per axis (frame option occtex.map, default the smaller
 * of 512 and this; pn_limits.occ_map_max lowers it per context). Costs 4 bytes per texel
 * (the slices' bits, 16 in a word) plus the filter of one slice at a time: 4 bytes per
 * texel per N-buffer level (floor(log2 res) + 1 levels: 10 MiB at 512), which covers the
 * summed-area table and the mipmap; plus 16 bytes per row and 64. Range 8 .. 4096. */
#ifndef PN_OCCTEX_MAP_MAX
#define PN_OCCTEX_MAP_MAX 512u
#endif

/* Monte Carlo shadow maps (Curtis 2009): near / far depth layers seen from behind the light,
 * an N-buffer of them, and n x n hashed jittered rays per pixel traced through the layers,
 * then a depth-aware blur. Approximate (its error against the reference is in
 * docs/bench/RESULTS.md). Costs the pools below. */
#ifndef PN_ENABLE_MCSM
#define PN_ENABLE_MCSM 1
#endif

/* Largest depth-layer resolution per axis (frame option mcsm.map, default the smaller of 512
 * and this; pn_limits.mc_map_max lowers it per context). The N-buffer is the method's main
 * memory cost (the thesis says so, and limits its maps to 1024): 12 bytes per texel per
 * level (min near, max far, max near as floats), floor(log2 res) + 1 levels, level 0 being
 * the layers themselves: 30 MiB at 512, 132 MiB at 1024. Plus 4 bytes per pixel (the
 * blur's other buffer) and 64 per row. Range 8 .. 2048. */
#ifndef PN_MCSM_MAP_MAX
#define PN_MCSM_MAP_MAX 512u
#endif

/* Penumbra wedges (Akenine-Moller and Assarsson 2002) with the overlap blending of Forest
 * et al. 2006: silhouette edges seen from the light centre, their wedges binned to screen
 * tiles, per pixel the occluded light area of each object blended over the light's four
 * quadrants. Approximate. Costs per triangle of persistent arena 28 bytes (half-edges,
 * edge runs, objects) and, at pn_scene_set, 24 bytes of the frame region for the welding;
 * per frame the pools below. */
#ifndef PN_ENABLE_WEDGES
#define PN_ENABLE_WEDGES 1
#endif

/* The silhouette pool's largest size (96 + 4 + 8 bytes a slot, and its share of the pair
 * pool; a context holds at most 3 x max_triangles, every edge, or pn_limits.wg_silhouettes).
 * A frame with more silhouettes makes them in bands of screen tiles (the same bytes); only
 * a tile that lists more fails PN_E_POOL_EXHAUSTED, naming it. Range 64 .. 2^24. */
#ifndef PN_WEDGES_SIL_MAX
#define PN_WEDGES_SIL_MAX (1u << 18)
#endif

/* Largest (screen tile, wedge) pair count of one binning pass (12 bytes each; a context
 * holds at most tiles x silhouettes, tiles being 16 x 16 pixels, and by default a 32nd of
 * that, at least 6 a silhouette: pn_limits.wg_pairs). A frame with more is binned and
 * shaded in bands of tiles, the same bytes; only a tile needing more fails
 * PN_E_POOL_EXHAUSTED, naming it. Range 1024 .. 2^28. */
#ifndef PN_WEDGES_PAIRS
#define PN_WEDGES_PAIRS (1u << 22)
#endif

/* ---- Limits (they size the arena; see pn_arena_size()). ------------------------------ */

/* Largest triangle count a scene may have, including any ground plane the caller adds.
 * Costs about 88 bytes per triangle of persistent arena (triangle copy 36, flags 1,
 * four-wide BVH nodes up to 128 / 3, leaf and raster orders 4 + 4), and the BVH's split
 * references (PN_BVH_SPLIT_REFS) 47 bytes each. Range 1 .. 2^26. */
#ifndef PN_MAX_TRIANGLES
#define PN_MAX_TRIANGLES (1u << 22)
#endif

/* Largest vertex count accepted by pn_scene_set(). Vertices are validated and read while
 * copying triangles, never stored, so this costs no arena. Range 3 .. 2^31. */
#ifndef PN_MAX_VERTICES
#define PN_MAX_VERTICES (1u << 24)
#endif

/* Largest output image. Costs 40 bytes of frame arena per pixel (G-buffer 32,
 * visibility 4, RGBA8 4). Range 1 .. 16384 each. */
#ifndef PN_MAX_WIDTH
#define PN_MAX_WIDTH 2048u
#endif
#ifndef PN_MAX_HEIGHT
#define PN_MAX_HEIGHT 2048u
#endif

/* Largest light-mask resolution k (k x k light samples per pixel). Run-time k may be any
 * of 4, 8, 16, 32 up to this value. Must be 4, 8, 16 or 32. The mask lives on the stack
 * of a work item: k*k/8 bytes (128 bytes for 32). */
#ifndef PN_MASK_K_MAX
#define PN_MASK_K_MAX 32u
#endif

/* ---- GEARS ---------------------------------------------------------------------------- */

/* Largest grid resolution per axis a context reserves by default (pn_limits.gears_grid_max
 * 0; a context may ask for up to 1024). The frame option gears.grid, default
 * PN_GEARS_GRID_DEFAULT, may be any value up to the context's. Costs res^2 x 12 bytes of frame arena (one face's cell
 * offsets, pixel counts and cursors: a point light's cube of 6 grids is done a face at a
 * time) and 6 x res x (res / 4 + 12) bytes for every face's grid rows (occupancy bits,
 * their prefix counts, pairs per row): 0.22 MiB at 128. Range 1 .. 1024. */
#ifndef PN_GEARS_GRID_MAX
#define PN_GEARS_GRID_MAX 128u
#endif

/* The grid GEARS renders with when the frame option gears.grid is 0 (at most the
 * context's gears_grid_max). A cost, never a result: the frames are the same bytes at
 * any grid. Chosen from every built-in and shared scene (tools/gears_grid_sweep.sh,
 * 512x512 and 256x256, k = 16, 2 threads): 64 is within 5% of the fastest of 32, 64,
 * 128 and 256 on every scene at 512x512 (128 was up to 1.16x slower: the living room;
 * the dragon 1.07x) and within 7% at 256x256 but on elongated-cube, a 3 ms frame
 * (docs/gears-vs-reference.md). Range 1 .. 1024. */
#ifndef PN_GEARS_GRID_DEFAULT
#define PN_GEARS_GRID_DEFAULT 64u
#endif

/* Most (triangle, cell) pairs one pass can hold. A context reserves by default
 * (pn_limits.gears_pairs 0) 4 a triangle + 1 a pixel of its largest frame + the cells of
 * its largest grid, at most 16 a pixel, at least one a triangle, at most this; a frame
 * that needs more is split into tiles of cells processed in turn (the result stays
 * exact); a single cell needing more returns PN_E_POOL_EXHAUSTED. Costs 7.4 bytes a pair
 * (the cell-sorted entry 4, chunk and superchunk boxes). Range 1 .. 2^28. */
#ifndef PN_GEARS_PAIRS
#define PN_GEARS_PAIRS (1u << 22)
#endif

/* ---- BVH ------------------------------------------------------------------------------ */

/* Binned SAH: number of bins per axis (4 .. 64). More bins, better trees, slower builds. */
#ifndef PN_BVH_BINS
#define PN_BVH_BINS 16u
#endif

/* A node with at most this many references may become a leaf (1 .. 16); one with more is
 * split. Every leaf holds at least two (a node of three or fewer is always a leaf, and a
 * split leaves two or more a side), which bounds the four-wide tree at a third of a node
 * a reference. */
#ifndef PN_BVH_LEAF_MAX
#define PN_BVH_LEAF_MAX 4u
#endif

/* Split references (early split clipping, Ernst and Greiner 2007): a triangle whose box is
 * far larger than the triangle (a long sliver lying diagonal to the axes) is entered into
 * the BVH as up to 2^PN_BVH_SPLIT_DEPTH references, each with the box of the part of the
 * triangle inside one piece of its box, halved along the longest axis while halving
 * shrinks the boxes' surface area to under 5/8 of the parent's. Only the boxes change: a
 * leaf still names whole triangles and every walk still tests the whole triangle, so the
 * bits of every frame are the same; a ray just meets fewer boxes it then misses.
 * A context reserves split references only on request: pn_limits.bvh_refs above
 * max_triangles, at most PN_BVH_SPLIT_REFS beyond one per triangle (and at most
 * (2^depth - 1) per triangle, the total at most 2^26), 47 bytes each of persistent arena
 * (a third of a four-wide node, an index entry; pn_scene_set's build also borrows 72
 * bytes a reference of the frame region); when a scene wants more than the
 * context holds, every triangle is split one level less until it fits. 0 for either: no
 * splitting. Depth 0 .. 6; references 0 .. 2^26. */
#ifndef PN_BVH_SPLIT_DEPTH
#define PN_BVH_SPLIT_DEPTH 4u
#endif
#ifndef PN_BVH_SPLIT_REFS
#define PN_BVH_SPLIT_REFS 65536u
#endif

/* Entries of the BVH walks' stacks (48 .. 256, 4 bytes each on the stack of each work
 * item). The builder keeps the tree shallow enough for any walk to fit: binary depth at
 * most 2 (PN_BVH_STACK - 4) / 3 + 1 (41 at 64), switching from SAH to median splits
 * where only halving still gets there (src/pn_bvh_build.c). */
#ifndef PN_BVH_STACK
#define PN_BVH_STACK 64u
#endif

/* ---- Shadow-ray predicate --------------------------------------------------------------- */

/* There is no tolerance to configure: the predicate decides every sign exactly for the
 * float inputs (kernels/pn_predicate.h, kernels/pn_expansion.h), and the culls' slack
 * (1e-5 of the scene diagonal, pn_stats.cull_tol) covers only their own rounding.
 * PN_CROSS_TOL, the crossing tolerance of the certainty test this replaced, is gone;
 * defining it is an error so that a build configured for it does not silently differ. */
#ifdef PN_CROSS_TOL
#error "PN_CROSS_TOL was removed: the predicate is exact (kernels/pn_predicate.h), no crossing tolerance is used"
#endif

/* ---- Debugging ------------------------------------------------------------------------ */

/* 1: memory rewound to an arena mark is filled with 0xA5 and mark order is checked, as
 * LVGL's LV_MEM_ADD_JUNK does. Costs a memset per rewind. */
#ifndef PN_DEBUG_ARENA
#define PN_DEBUG_ARENA 0
#endif

/* ---- Derived values (do not override). ----------------------------------------------- */

#define PN_ARENA_ALIGN 64u
#define PN_MASK_WORDS_MAX ((PN_MASK_K_MAX * PN_MASK_K_MAX + 31u) / 32u)

#include "penumbra/check_config.h"

#endif
