/* good_min.h - every option at the low end of its documented range (the checks are not
 * off by one); must compile without a diagnostic under -Wundef -Werror. */
#define PN_ENABLE_REFERENCE 0
#define PN_MAX_TRIANGLES 1u
#define PN_MAX_VERTICES 3u
#define PN_MAX_WIDTH 1u
#define PN_MAX_HEIGHT 1u
#define PN_MASK_K_MAX 4u
#define PN_BVH_BINS 4u
#define PN_BVH_LEAF_MAX 1u
#define PN_BVH_STACK 48u
#define PN_BVH_SPLIT_DEPTH 0u
#define PN_BVH_SPLIT_REFS 0u
#define PN_DEBUG_ARENA 0
#define PN_SRT_MAP_MAX 8u
#define PN_OCCTEX_MAP_MAX 8u
