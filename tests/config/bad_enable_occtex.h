/* bad_enable_occtex.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_ENABLE_OCCTEX must be 0 or 1 */
#define PN_ENABLE_OCCTEX 2
