/* bad_leaf.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_BVH_LEAF_MAX must be in 1 .. 16 */
#define PN_BVH_LEAF_MAX 17u
