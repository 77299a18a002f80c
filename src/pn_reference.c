/* pn_reference.c - the exact reference: each pixel's k x k mask through the BVH (kernels/pn_reference.h).
 * Its frame is one pass over the pixels; it has no options of its own. */
#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_passes.h"

#if PN_ENABLE_REFERENCE

pn_status pn_reference_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    (void)fs;
    (void)opt;
    return PN_OK;
}

PN_ALGO_NO_POOLS(reference)

pn_status pn_reference_frame(pn_frame_state *fs) { return pn_dev_run(fs, PN_K_REFERENCE, fs->width * fs->height); }
PN_ALGO_NO_SCENE(reference)
#else
PN_ALGO_STUBS(REFERENCE, reference)
#endif
