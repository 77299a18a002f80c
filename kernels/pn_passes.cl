/* pn_passes.cl - the OpenCL entry point of every pass of kernels/pn_passes.h, generated
 * from its list: item get_global_id(0) of n (the launch is rounded up to the work-group
 * size; the items past n do nothing). */
#pragma OPENCL FP_CONTRACT OFF
#include "pn_passes.h"

#define PN_CL_ENTRY(id, name, local, grain)                                                  \
    __kernel void pn_k_##name(__global uchar *A, pn_kpools P, pn_kparams K, uint n)         \
    {                                                                                        \
        uint i = (uint)get_global_id(0);                                                     \
        if (i < n) pn_e_##name(A, &P, &K, i);                                                \
    }
PN_PASSES(PN_CL_ENTRY)
