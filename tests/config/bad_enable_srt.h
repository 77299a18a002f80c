/* bad_enable_srt.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_ENABLE_SRT must be 0 or 1 */
#define PN_ENABLE_SRT 2
