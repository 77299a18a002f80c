/* bad_wedges_pairs.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_WEDGES_PAIRS must be in 1024 .. 2^28 */
#define PN_WEDGES_PAIRS ((1u << 28) + 1u)
