/* bad_split_depth.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_BVH_SPLIT_DEPTH must be in 0 .. 6 */
#define PN_BVH_SPLIT_DEPTH 7u
