/* pn_scalar.h - passes of the scalar port implemented outside pn_scalar.c. */
#ifndef PN_SCALAR_H
#define PN_SCALAR_H

#include "pn_internal.h"
#include "pn_reference.h"

#if PN_ENABLE_GEARS
pn_status pn_scalar_gears(pn_context *ctx, pn_frame_state *fs);
#endif

#endif
