/* bad_bvh_stack.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_BVH_SAH_DEPTH + 27 must not exceed PN_BVH_STACK */
#define PN_BVH_STACK 8u
#define PN_BVH_SAH_DEPTH 32u
