/* bad_bvh_stack_range.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_BVH_STACK must be in 48 .. 256 */
#define PN_BVH_STACK 512u
