/* bad_mask_k.h - an inconsistent configuration; check_config.h must reject it.
 * expect-error: PN_MASK_K_MAX must be 4, 8, 16 or 32 */
#define PN_MASK_K_MAX 12u
