/* bad_max_triangles_big.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_MAX_TRIANGLES must be in 1 .. 2^26 */
#define PN_MAX_TRIANGLES ((1u << 26) + 1u)
