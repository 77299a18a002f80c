/* bad_enable_mcsm.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_ENABLE_MCSM must be 0 or 1 */
#define PN_ENABLE_MCSM 2
