/* good_small.h - a small firmware-sized configuration; must compile without a diagnostic
 * under -Wundef -Werror. */
#define PN_MAX_TRIANGLES 1024u
#define PN_MAX_VERTICES 3072u
#define PN_MAX_WIDTH 320u
#define PN_MAX_HEIGHT 240u
#define PN_MASK_K_MAX 8u
#define PN_BVH_BINS 8u
#define PN_BVH_LEAF_MAX 2u
#define PN_BVH_STACK 48u
#define PN_DEBUG_ARENA 1
