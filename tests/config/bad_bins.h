/* bad_bins.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_BVH_BINS must be in 4 .. 64 */
#define PN_BVH_BINS 2u
