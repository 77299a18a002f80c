/* bad_bvh_sah_depth.h - a configuration from before the BVH's depth followed its stack;
 * check_config.h must reject it rather than ignore it.
 * expect-error: PN_BVH_SAH_DEPTH is gone */
#define PN_BVH_SAH_DEPTH 32u
