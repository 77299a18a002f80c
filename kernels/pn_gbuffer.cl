/* pn_gbuffer.cl - OpenCL entry points of the G-buffer pass (kernels/pn_raster.h): clear,
 * per-triangle row set-up, per-band rasterization (each band owns its rows and walks
 * every triangle in id order, as the scalar port does), per-pixel resolve. */
#pragma OPENCL FP_CONTRACT OFF
#include "pn_kpools.h"
#include "pn_raster.h"

__kernel void pn_k_gbuffer_clear(__global uchar *A, pn_kpools P, uint npix)
{
    size_t pix = get_global_id(0);
    if (pix >= npix) return;
    PN_POOL(float, depth)[pix] = PN_KINF;
    PN_POOL(uint, tri_id)[pix] = 0xFFFFFFFFu;
}

__kernel void pn_k_raster_rows(pn_kview view, __global uchar *A, pn_kpools P, uint tri_count)
{
    uint t = (uint)get_global_id(0);
    if (t >= tri_count) return;
    PN_POOL(uint, rows)[t] = pn_raster_rows(&view, PN_POOL(const float, tris), PN_POOL(const uchar, flags), t);
}

__kernel void pn_k_raster_band(pn_kview view, __global uchar *A, pn_kpools P, uint tri_count)
{
    uint y0 = (uint)get_global_id(0) * PN_RASTER_BAND;
    if (y0 >= view.height) return;
    pn_raster_band(&view, PN_POOL(const float, tris), PN_POOL(const uint, rows), tri_count, y0,
                   min(y0 + PN_RASTER_BAND - 1u, view.height - 1u), PN_POOL(float, depth), PN_POOL(uint, tri_id));
}

__kernel void pn_k_gbuffer_resolve(pn_kview view, __global uchar *A, pn_kpools P)
{
    size_t pix = get_global_id(0);
    if (pix >= (size_t)view.width * view.height) return;
    pn_gbuffer_resolve(&view, PN_POOL(const float, tris), (uint)(pix % view.width), (uint)(pix / view.width),
                       PN_POOL(const float, depth), PN_POOL(const uint, tri_id), PN_POOL(float, pos),
                       PN_POOL(float, nrm));
}
