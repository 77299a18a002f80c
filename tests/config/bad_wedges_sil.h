/* bad_wedges_sil.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_WEDGES_SIL_MAX must be in 64 .. 2^24 */
#define PN_WEDGES_SIL_MAX 63u
