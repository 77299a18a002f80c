/* pn_cl_host.h - host programs' shorthand for the OpenCL port: its state block from the
 * heap (the library itself takes caller memory, penumbra/opencl.h). Host code only;
 * include after penumbra/opencl.h. */
#ifndef PN_TOOLS_CL_HOST_H
#define PN_TOOLS_CL_HOST_H

#include <stdlib.h>

#include "penumbra/opencl.h"

/* pn_opencl_create on a malloc'd block of pn_opencl_size() bytes, freed on failure. */
static inline pn_status pn_cl_open(pn_context *ctx, const pn_opencl_options *opt, pn_opencl **out)
{
    void *mem = malloc(pn_opencl_size());
    pn_status st;
    if (!mem) return PN_E_DEVICE;
    st = pn_opencl_create(ctx, opt, mem, pn_opencl_size(), out);
    if (st != PN_OK) free(mem);
    return st;
}

/* pn_opencl_destroy, then frees its block. NULL is allowed. */
static inline void pn_cl_close(pn_opencl *cl) { free(pn_opencl_destroy(cl)); }

#endif
