/* bad_height.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_MAX_WIDTH and PN_MAX_HEIGHT must be in 1 .. 16384 */
#define PN_MAX_HEIGHT 16385u
