/* fw_config.h - the firmware example's penumbra configuration (PN_CONFIG_FILE).
 *
 * The library and every file that includes penumbra.h must see the same configuration:
 * examples/firmware/CMakeLists.txt puts PN_CONFIG_FILE="fw_config.h" and this folder on
 * the penumbra target's PUBLIC interface, so both get it.
 *
 * The defaults are sized for desktop scenes (GEARS alone reserves 4.5 MiB of grid and
 * 48 MiB of pairs in PN_ARENA_BYTES_MAX). A firmware build states what it renders. Here:
 * spot (5,856 triangles and the CLI's two ground triangles, 2,934 vertices) at 160 x 120
 * with the reference and 64 x 64 Monte Carlo depth layers, and a 46-triangle scene at
 * 32 x 32 with every algorithm (fw.c); masks up to k = 8. The maxima below bound what a
 * context may ask for; each context's pn_limits asks for what its scene needs (fw.c), and
 * pn_arena_size sizes it. For the small scene's algorithms: a GEARS grid of at most 16
 * cells per axis and 4096 (triangle, cell) pairs per pass (more pairs are tiled, so the
 * result does not depend on it); a 64 x 64 shadow map for selective ray tracing (its
 * default 2048 x 2048 alone would reserve 48 MiB); 64 x 64 occlusion textures; penumbra
 * wedges with room for every edge of 64 triangles as a silhouette (192) and every (tile,
 * wedge) pair of a 32 x 32 image (4 tiles: 768 of the 1024 pairs reserved; the default
 * 2^22 pairs alone would be 48 MiB); no split BVH references (the default reserve would
 * be 960 of them, 188 KB). */
#ifndef FW_CONFIG_H
#define FW_CONFIG_H

#define PN_MAX_TRIANGLES 6144u
#define PN_MAX_VERTICES 8192u
#define PN_MAX_WIDTH 160u
#define PN_MAX_HEIGHT 120u
#define PN_MASK_K_MAX 8u
#define PN_GEARS_GRID_MAX 16u
#define PN_GEARS_PAIRS 4096u
#define PN_SRT_MAP_MAX 64u
#define PN_OCCTEX_MAP_MAX 64u
#define PN_MCSM_MAP_MAX 64u
#define PN_WEDGES_SIL_MAX 192u
#define PN_WEDGES_PAIRS 1024u
#define PN_BVH_SPLIT_REFS 0u

#endif
