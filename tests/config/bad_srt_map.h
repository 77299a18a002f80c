/* bad_srt_map.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_SRT_MAP_MAX must be in 8 .. 8192 */
#define PN_SRT_MAP_MAX 4u
