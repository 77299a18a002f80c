/* bad_enable_raytrace.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_ENABLE_RAYTRACE must be 0 or 1 */
#define PN_ENABLE_RAYTRACE -1
