/* bad_mcsm_map.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_MCSM_MAP_MAX must be in 8 .. 2048 */
#define PN_MCSM_MAP_MAX 4096u
