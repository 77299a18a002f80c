/* bad_debug.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_DEBUG_ARENA must be 0 or 1 */
#define PN_DEBUG_ARENA 2
