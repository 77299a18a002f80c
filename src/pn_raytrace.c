/* pn_raytrace.c - per-sample ray tracing: each pixel's k^2 single shadow rays through the BVH (kernels/pn_raytrace.h), the reference's bits.
 * Its frame is one pass over the pixels; it has no options of its own. */
#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_passes.h"

#if PN_ENABLE_RAYTRACE

/* No limits of its own. */
int pn_raytrace_limits_ok(const pn_limits *l)
{
    (void)l;
    return 1;
}
pn_status pn_raytrace_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    (void)fs;
    (void)opt;
    return PN_OK;
}

/* No pools of its own. */
void pn_raytrace_query(pn_carver *c, const pn_limits *l)
{
    (void)c;
    (void)l;
}

pn_status pn_raytrace_frame(pn_frame_state *fs) { return pn_dev_run(fs, PN_K_RAYTRACE, fs->width * fs->height); }
PN_ALGO_NO_SCENE(raytrace)
#else
PN_ALGO_STUBS(RAYTRACE, raytrace)
#endif
