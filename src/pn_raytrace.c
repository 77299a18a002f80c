/* pn_raytrace.c - per-sample ray tracing: each pixel's k^2 single shadow rays through the BVH (kernels/pn_raytrace.h), the reference's bits.
 * Its frame is one pass over the pixels; it has no options of its own. */
#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_passes.h"

#if PN_ENABLE_RAYTRACE

pn_status pn_raytrace_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    (void)fs;
    (void)opt;
    return PN_OK;
}

PN_ALGO_NO_POOLS(raytrace)

pn_status pn_raytrace_frame(pn_frame_state *fs) { return pn_dev_run(fs, PN_K_RAYTRACE, fs->width * fs->height); }
PN_ALGO_NO_SCENE(raytrace)
#else
PN_ALGO_STUBS(RAYTRACE, raytrace)
#endif
