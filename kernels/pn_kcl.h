/* pn_kcl.h - helpers for the OpenCL entry points (kernels/pn_*.cl) only. */
#ifndef PN_KCL_H
#define PN_KCL_H

#include "pn_reference.h"

/* A work item's counters into its row's: integer atomic adds, the same sums in any order. */
PN_KFN void pn_counters_add(__global pn_shadow_counters *row, const pn_shadow_counters *c)
{
    if (c->candidates) atomic_add(&row->candidates, c->candidates);
    if (c->blocking) atomic_add(&row->blocking, c->blocking);
    if (c->lit) atomic_add(&row->lit, c->lit);
    if (c->overflow) atomic_add(&row->overflow, c->overflow);
}

#endif
