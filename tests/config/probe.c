/* probe.c - compiled (-fsyntax-only) against each tests/config/ header by the config
 * tests: the public header with the chosen PN_CONFIG_FILE, and the static arena bound
 * as a constant expression, as firmware would declare it. */
#include "penumbra/penumbra.h"

typedef char pn_probe_arena_bound[PN_ARENA_BYTES_MAX(PN_MAX_TRIANGLES, PN_MAX_WIDTH, PN_MAX_HEIGHT) > 0u ? 1 : -1];
typedef char pn_probe_mask_words[PN_MASK_WORDS_MAX >= 1u ? 1 : -1];
