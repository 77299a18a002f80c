/* good_max.h - every option at the high end of its documented range (the checks are not
 * off by one); must compile without a diagnostic under -Wundef -Werror. */
#define PN_ENABLE_REFERENCE 1
#define PN_MAX_TRIANGLES (1u << 26)
#define PN_MAX_VERTICES (1u << 31)
#define PN_MAX_WIDTH 16384u
#define PN_MAX_HEIGHT 16384u
#define PN_MASK_K_MAX 32u
#define PN_BVH_BINS 64u
#define PN_BVH_LEAF_MAX 16u
#define PN_BVH_STACK 256u
#define PN_BVH_SPLIT_DEPTH 6u
#define PN_BVH_SPLIT_REFS (1u << 26)
#define PN_DEBUG_ARENA 1
#define PN_SRT_MAP_MAX 8192u
#define PN_OCCTEX_MAP_MAX 4096u
