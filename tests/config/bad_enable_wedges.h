/* bad_enable_wedges.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_ENABLE_WEDGES must be 0 or 1 */
#define PN_ENABLE_WEDGES 2
