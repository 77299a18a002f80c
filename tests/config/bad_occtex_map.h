/* bad_occtex_map.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_OCCTEX_MAP_MAX must be in 8 .. 4096 */
#define PN_OCCTEX_MAP_MAX 8192u
