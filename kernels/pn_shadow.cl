/* pn_shadow.cl - OpenCL entry point of the per-pixel shadow passes, one work item per
 * pixel: PN_ALGO_REFERENCE (kernels/pn_reference.h: the pixel's mask) or, with
 * per_sample, PN_ALGO_RAYTRACE (kernels/pn_raytrace.h: k^2 single rays). A pixel's
 * counters go to its row's with integer atomic adds. */
#pragma OPENCL FP_CONTRACT OFF
#include "pn_kpools.h"
#include "pn_raytrace.h"
#include "pn_kcl.h"

__kernel void pn_k_per_pixel(pn_klight L, uint per_sample, __global uchar *A, pn_kpools P, uint width, uint npix)
{
    size_t pix = get_global_id(0);
    pn_shadow_counters c = {0u, 0u, 0u, 0u};
    uint id;
    pn_v3 pos, nrm;
    if (pix >= npix) return;
    id = PN_POOL(const uint, tri_id)[pix];
    pos = pn_v3_load(PN_POOL(const float, pos) + pix * 3u);
    nrm = pn_v3_load(PN_POOL(const float, nrm) + pix * 3u);
    if (id == 0xFFFFFFFFu)
        PN_POOL(float, vis)[pix] = 1.0f;
    else if (per_sample)
        PN_POOL(float, vis)[pix] = pn_raytrace_pixel(pos, nrm, id, PN_POOL(const float, tris),
                                                     PN_POOL(const pn_kbvh_node, nodes), PN_POOL(const uint, index), &L, &c);
    else
        PN_POOL(float, vis)[pix] = pn_reference_pixel(pos, nrm, id, PN_POOL(const float, tris),
                                                      PN_POOL(const pn_kbvh_node, nodes), PN_POOL(const uint, index), &L, &c);
    pn_counters_add(PN_POOL(pn_shadow_counters, counters) + pix / width, &c);
}
