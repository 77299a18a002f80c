/* bad_max_vertices.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_MAX_VERTICES must be in 3 .. 2^31 */
#define PN_MAX_VERTICES 2u
