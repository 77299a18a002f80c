/* pn_passes_exact.h - the reference's and per-sample ray tracing's passes (one item a pixel):
 * their per-work-item entries and their part of
 * the pass list (PN_PASSES_*), composed by pn_passes.h, which includes this file after
 * the kernels it calls; see there for the entry signature and the list's columns. */
#ifndef PN_PASSES_EXACT_H
#define PN_PASSES_EXACT_H

/* ---- Shadow passes of one item per pixel: the reference and per-sample ray tracing ----- */

/* Pixel of item i (in tiles: pn_pix_tiled): its mask through the BVH (pn_reference.h), or
 * with `rays` its k^2 single shadow rays (pn_raytrace.h); its counters into its tile's
 * slot (pn_pix_slot). */
PN_KFN void pn_pixel_shadow(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t i, int rays)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t pix = pn_pix_tiled(i, K->view.width, K->view.height), id = PN_POOL(const uint32_t, tri_id)[pix];
    pn_v3 pos, nrm;
    float v;
    if (id == PN_NO_PIXEL_TRIANGLE) {
        PN_POOL(float, vis)[pix] = 1.0f;
        return;
    }
    pn_pix_surf(A, P, K, pix, &pos, &nrm);
#if PN_ENABLE_RAYTRACE
    if (rays)
        v = pn_raytrace_pixel(pos, nrm, id, PN_POOL(const float, tris), PN_POOL(const pn_kbvh4, wnodes),
                              PN_POOL(const uint32_t, index), &K->light, &c);
    else
#endif
        v = pn_reference_pixel(pos, nrm, id, PN_POOL(const float, tris), PN_POOL(const pn_kbvh4, wnodes),
                               PN_POOL(const uint32_t, index), &K->light, &c);
    (void)rays;
    PN_POOL(float, vis)[pix] = v;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[pn_pix_slot(i, K->view.height)].c, &c);
}

#if PN_ENABLE_REFERENCE
PN_KFN void pn_e_reference(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t i)
{
    pn_pixel_shadow(A, P, K, i, 0);
}
#endif
#if PN_ENABLE_RAYTRACE
PN_KFN void pn_e_raytrace(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t i)
{
    pn_pixel_shadow(A, P, K, i, 1);
}
#endif

/* Their part of the list. */
#if PN_ENABLE_REFERENCE
#define PN_PASSES_REFERENCE(X) X(REFERENCE, reference, 16, 1024)
#else
#define PN_PASSES_REFERENCE(X)
#endif
#if PN_ENABLE_RAYTRACE
#define PN_PASSES_RAYTRACE(X) X(RAYTRACE, raytrace, 16, 1024)
#else
#define PN_PASSES_RAYTRACE(X)
#endif

#endif
