/* penumbra/check_config.h - rejects inconsistent configuration at compile time.
 * Included by config.h after all defaults are set; never include it on its own. */
#ifndef PN_CHECK_CONFIG_H
#define PN_CHECK_CONFIG_H

#if PN_ENABLE_REFERENCE != 0 && PN_ENABLE_REFERENCE != 1
#error "PN_ENABLE_REFERENCE must be 0 or 1"
#endif

#if PN_ENABLE_GEARS != 0 && PN_ENABLE_GEARS != 1
#error "PN_ENABLE_GEARS must be 0 or 1"
#endif

#if PN_ENABLE_RAYTRACE != 0 && PN_ENABLE_RAYTRACE != 1
#error "PN_ENABLE_RAYTRACE must be 0 or 1"
#endif

#if PN_ENABLE_SRT != 0 && PN_ENABLE_SRT != 1
#error "PN_ENABLE_SRT must be 0 or 1"
#endif

#if !(PN_ENABLE_REFERENCE || PN_ENABLE_GEARS || PN_ENABLE_RAYTRACE || PN_ENABLE_SRT || PN_ENABLE_OCCTEX || \
      PN_ENABLE_MCSM || PN_ENABLE_WEDGES)
#error "PN_ALGORITHMS names no algorithm: compile in at least one (CMake -DPN_ALGORITHMS=reference;mcsm, or PN_ENABLE_<NAME> 1 in PN_CONFIG_FILE)"
#endif

#if PN_SRT_MAP_MAX < 8 || PN_SRT_MAP_MAX > 8192
#error "PN_SRT_MAP_MAX must be in 8 .. 8192"
#endif

#if PN_ENABLE_OCCTEX != 0 && PN_ENABLE_OCCTEX != 1
#error "PN_ENABLE_OCCTEX must be 0 or 1"
#endif

#if PN_OCCTEX_MAP_MAX < 8 || PN_OCCTEX_MAP_MAX > 4096
#error "PN_OCCTEX_MAP_MAX must be in 8 .. 4096"
#endif

#if PN_ENABLE_MCSM != 0 && PN_ENABLE_MCSM != 1
#error "PN_ENABLE_MCSM must be 0 or 1"
#endif

#if PN_MCSM_MAP_MAX < 8 || PN_MCSM_MAP_MAX > 2048
#error "PN_MCSM_MAP_MAX must be in 8 .. 2048"
#endif

#if PN_ENABLE_WEDGES != 0 && PN_ENABLE_WEDGES != 1
#error "PN_ENABLE_WEDGES must be 0 or 1"
#endif

#if PN_WEDGES_SIL_MAX < 64 || PN_WEDGES_SIL_MAX > (1 << 24)
#error "PN_WEDGES_SIL_MAX must be in 64 .. 2^24"
#endif

#if PN_WEDGES_PAIRS < 1024 || PN_WEDGES_PAIRS > (1 << 28)
#error "PN_WEDGES_PAIRS must be in 1024 .. 2^28"
#endif

#if PN_GEARS_GRID_MAX < 1 || PN_GEARS_GRID_MAX > 1024
#error "PN_GEARS_GRID_MAX must be in 1 .. 1024"
#endif
#if PN_GEARS_GRID_DEFAULT < 1 || PN_GEARS_GRID_DEFAULT > 1024
#error "PN_GEARS_GRID_DEFAULT must be in 1 .. 1024"
#endif

#if PN_GEARS_PAIRS < 1 || PN_GEARS_PAIRS > (1u << 28)
#error "PN_GEARS_PAIRS must be in 1 .. 2^28"
#endif

#if PN_MASK_K_MAX != 4 && PN_MASK_K_MAX != 8 && PN_MASK_K_MAX != 16 && PN_MASK_K_MAX != 32
#error "PN_MASK_K_MAX must be 4, 8, 16 or 32 (the light mask is k x k bits in 32-bit words)"
#endif

#if PN_MAX_TRIANGLES < 1 || PN_MAX_TRIANGLES > (1u << 26)
#error "PN_MAX_TRIANGLES must be in 1 .. 2^26 (BVH node indices and sizes must fit 32 bits)"
#endif

#if PN_MAX_VERTICES < 3 || PN_MAX_VERTICES > (1u << 31)
#error "PN_MAX_VERTICES must be in 3 .. 2^31"
#endif

#if PN_MAX_WIDTH < 1 || PN_MAX_WIDTH > 16384 || PN_MAX_HEIGHT < 1 || PN_MAX_HEIGHT > 16384
#error "PN_MAX_WIDTH and PN_MAX_HEIGHT must be in 1 .. 16384"
#endif

#if PN_BVH_BINS < 4 || PN_BVH_BINS > 64
#error "PN_BVH_BINS must be in 4 .. 64"
#endif

#if PN_BVH_LEAF_MAX < 1 || PN_BVH_LEAF_MAX > 16
#error "PN_BVH_LEAF_MAX must be in 1 .. 16"
#endif

#if PN_BVH_SPLIT_DEPTH > 6
#error "PN_BVH_SPLIT_DEPTH must be in 0 .. 6 (a triangle becomes at most 2^depth BVH references)"
#endif

#if PN_BVH_SPLIT_REFS > (1u << 26)
#error "PN_BVH_SPLIT_REFS must be in 0 .. 2^26"
#endif

/* The builder keeps the tree within 2 (PN_BVH_STACK - 4) / 3 + 1 binary levels, which
 * must leave room for the 25 levels of median splits that 2^26 references need: 48 gives
 * 30. */
#if PN_BVH_STACK < 48 || PN_BVH_STACK > 256
#error "PN_BVH_STACK must be in 48 .. 256"
#endif
#ifdef PN_BVH_SAH_DEPTH
#error "PN_BVH_SAH_DEPTH is gone: the BVH's depth follows PN_BVH_STACK (config.h)"
#endif

#if PN_DEBUG_ARENA != 0 && PN_DEBUG_ARENA != 1
#error "PN_DEBUG_ARENA must be 0 or 1"
#endif

#endif
