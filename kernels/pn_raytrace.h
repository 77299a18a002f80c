/* pn_raytrace.h - PN_ALGO_RAYTRACE: exact k x k visibility of one pixel by tracing the
 * k^2 shadow segments O -> S_ij one at a time through the BVH, stopping each at its
 * first blocker. It is the per-sample ray tracer of the GEARS paper's comparison (their
 * OptiX baseline) and the single-ray query selective ray tracing needs.
 *
 * A sample below the horizon of the pixel's own triangle is blocked without a ray
 * (pn_horizon_at, the very decision pn_horizon_mask makes); every other ray asks
 * pn_tri_sample(), which decides exactly what pn_tri_mask() decides, so the result equals
 * PN_ALGO_REFERENCE bit for bit (tests/test_raytrace.c). Culling: a node is skipped only
 * when the segment from O to the float sample point misses its box grown by cull_tol (1e-5
 * of the scene diagonal). A blocked sample's exact segment meets the triangle (the
 * predicate is exact); it differs from the float segment by the rounding of
 * c + a U + b V (a few u of |c| + |U| + |V|) at the far end and the slab test rounds by a
 * few u of the coordinates, both far below cull_tol for coordinates within 10^4 scene
 * diagonals of the origin. */
#ifndef PN_RAYTRACE_H
#define PN_RAYTRACE_H

#include "pn_reference.h"

/* 1 if some triangle other than `own` blocks sample (i, j) from O. */
PN_KFN uint32_t pn_raytrace_sample(pn_v3 O, uint32_t own, int32_t i, int32_t j, PN_CONST float *tris,
                                   PN_CONST pn_kbvh_node *nodes, PN_CONST uint32_t *tri_index,
                                   const pn_klight *L, pn_shadow_counters *cnt)
{
    pn_bvh_walk w;
    pn_frustum seg;
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
    pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    pn_v3 S = pn_v3_add(pn_v3_add(c, pn_v3_scale(U, pn_sample_coord(i, L->k))),
                        pn_v3_scale(V, pn_sample_coord(j, L->k)));
    uint32_t q, leaf;
    /* A segment "frustum": the point-light form of pn_frustum with the end at S. */
    for (q = 0; q < 6; q++) {
        seg.n[q] = pn_v3_make(0.0f, 0.0f, 0.0f);
        seg.d[q] = 0.0f;
    }
    seg.is_point = 1u;
    seg.tol = L->cull_tol;
    seg.seg_o = O;
    seg.seg_d = pn_v3_sub(S, O);
    pn_bvh_walk_init(&w);
    while ((leaf = pn_bvh_next_leaf(&w, &seg, nodes, cnt)) != PN_BVH_DONE) {
        PN_CONST pn_kbvh_node *nd = nodes + leaf;
        uint32_t e;
        for (e = 0; e < nd->count; e++) {
            uint32_t t = tri_index[nd->first + e];
            pn_v3 A, B, C;
            if (t == own) continue;
            pn_tri_load(tris, t, &A, &B, &C);
            cnt->candidates++;
            if (pn_tri_sample(O, A, B, C, L, i, j)) {
                cnt->blocking++;
                return 1u;
            }
        }
    }
    return 0u;
}

/* Visibility of one G-buffer pixel (P, unit geometric normal nrm, own triangle id).
 * Counters: candidates = ray-triangle tests, blocking = blocked rays. */
PN_KFN float pn_raytrace_pixel(pn_v3 P, pn_v3 nrm, uint32_t own, PN_CONST float *tris,
                               PN_CONST pn_kbvh_node *nodes, PN_CONST uint32_t *tri_index,
                               const pn_klight *L, pn_shadow_counters *cnt)
{
    uint32_t k = L->k, blocked = 0;
    int32_t i, j;
    pn_horizon H;
    pn_v3 O;
    if (!pn_shadow_origin(P, nrm, L, &O)) return 0.0f;
    cnt->lit++;
    pn_horizon_of(P, nrm, own, tris, L, &H);
    for (j = 0; j < (int32_t)k; j++)
        for (i = 0; i < (int32_t)k; i++)
            blocked += pn_horizon_at(&H, L, pn_sample_coord(i, k), pn_sample_coord(j, k)) ||
                       pn_raytrace_sample(O, own, i, j, tris, nodes, tri_index, L, cnt);
    /* The same quotient as pn_mask_visibility(). */
    return (float)(k * k - blocked) / (float)(k * k);
}

#endif
