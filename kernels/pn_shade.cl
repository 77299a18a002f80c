/* pn_shade.cl - OpenCL entry point of the shading pass (kernels/pn_shade.h). */
#pragma OPENCL FP_CONTRACT OFF
#include "pn_kpools.h"
#include "pn_shade.h"

__kernel void pn_k_shade(pn_kview view, pn_klight L, pn_kshade sh, __global uchar *A, pn_kpools P, uint npix)
{
    size_t pix = get_global_id(0);
    uint c, b;
    if (pix >= npix) return;
    c = pn_shade_pixel(&view, &L, &sh, PN_POOL(const uint, tri_id)[pix],
                       pn_v3_load(PN_POOL(const float, pos) + pix * 3u), pn_v3_load(PN_POOL(const float, nrm) + pix * 3u),
                       PN_POOL(const float, vis)[pix]);
    /* Bytes r g b a, whatever the device's endianness. */
    for (b = 0; b < 4u; b++) PN_POOL(uchar, rgba)[pix * 4u + b] = (uchar)(c >> (8u * b));
}
