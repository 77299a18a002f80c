/* bad_split_refs.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_BVH_SPLIT_REFS must be in 0 .. 2^26 */
#define PN_BVH_SPLIT_REFS ((1u << 26) + 1u)
