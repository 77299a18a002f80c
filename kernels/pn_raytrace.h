/* pn_raytrace.h - PN_ALGO_RAYTRACE: exact k x k visibility of one pixel by tracing the
 * k^2 shadow segments O -> S_ij one at a time through the BVH, stopping each at its
 * first blocker. It is the per-sample ray tracer of the GEARS paper's comparison (their
 * OptiX baseline) and the single-ray query selective ray tracing needs.
 *
 * A sample below the horizon of the pixel's own triangle is blocked without a ray
 * (pn_horizon_at, the very decision pn_horizon_mask makes). Every other ray decides each
 * triangle exactly as pn_tri_sample() does (pn_predicate.h), so the result equals
 * PN_ALGO_REFERENCE bit for bit (tests/test_raytrace.c), but at the cost of a ray/triangle
 * test: a float filter in the watertight model of Woop, Benthin and Wald (2013) with a
 * rigorous rounding bound, and pn_tri_sample() itself only where that filter cannot tell.
 * The ray, its filter and its slab test are pn_rayfilter.h's; here the BVH walk and the
 * pixel. */
#ifndef PN_RAYTRACE_H
#define PN_RAYTRACE_H

#include "pn_rayfilter.h"
#include "pn_reference.h"

/* A walk of one ray through the BVH that can stop at each blocker and go on: the one BVH
 * walk of the per-ray queries (per-sample ray tracing stops at the first blocker; the
 * penumbra wedges' centre ray goes on to the next, to learn which objects block it). */
#define PN_RAY_NONE 0xFFFFFFFFu

typedef struct pn_ray_walk {
    uint32_t stack[PN_BVH_STACK]; /* entries (pn_w4_entry): wide node indices and leaves */
    uint32_t sp, node, done;
    uint32_t q;    /* the next triangle of the current node when it is a leaf left at a blocker */
    uint32_t lost; /* entries the stack had no room for (must stay 0: pn_bvh_fold) */
} pn_ray_walk;

/* The chain first: each of its nodes is entered at t = 0 through the child that holds O;
 * its other children are tested and pushed. The walk starts at the chain's end. The
 * pushes are those a walk down the same path could leave, which pn_bvh_fold keeps
 * within PN_BVH_STACK. */
PN_KFN_HOT void pn_ray_walk_begin(pn_ray_walk *W, const pn_ray_origin *X, const pn_ray *R, PN_CONST pn_kbvh4 *wnodes)
{
    uint32_t cd;
    W->sp = 0u;
    W->q = 0u;
    W->done = 0u;
    W->lost = 0u;
    for (cd = 0u; cd + 1u < X->chain_len; cd++) {
        PN_CONST pn_kbvh4 *w = wnodes + X->chain[cd];
        float tn[4];
        uint32_t hit = pn_ray_box4(R, w, tn) & ~(1u << X->slot[cd]), c;
        for (c = 0; c < 4u; c++)
            if ((hit >> c) & 1u) {
                if (W->sp < PN_BVH_STACK)
                    W->stack[W->sp++] = pn_w4_entry(w, X->chain[cd], c);
                else
                    W->lost++;
            }
    }
    W->node = X->chain[X->chain_len - 1u];
}

/* The next triangle other than `own` that blocks the ray's sample, or PN_RAY_NONE. At a
 * wide node the children the segment may meet are visited nearest entry first (the others
 * pushed, farthest first); a leaf's box (its lane of its parent) gives the filter's
 * bound. */
PN_KFN_HOT uint32_t pn_ray_walk_next(pn_ray_walk *W, const pn_ray *R, uint32_t own, PN_CONST float *tris,
                                     PN_CONST pn_kbvh4 *wnodes, PN_CONST uint32_t *tri_index,
                                     const pn_klight *L, pn_shadow_counters *cnt)
{
    uint32_t cur = W->node, sp = W->sp, tests = 0u;
    cnt->overflow += W->lost;
    W->lost = 0u;
    if (W->done) return PN_RAY_NONE;
    for (;;) {
        if (!(cur & PN_W4_LEAF)) {
            PN_CONST pn_kbvh4 *wn = wnodes + cur;
            float tn[4], ks[4];
            uint32_t hit = pn_ray_box4(R, wn, tn), ids[4], m = 0u, c, j;
            if (hit) {
                for (c = 0; c < 4u; c++) {
                    if (!((hit >> c) & 1u)) continue;
                    /* insertion by entry parameter, largest first */
                    for (j = m++; j > 0u && ks[j - 1u] < tn[c]; j--) {
                        ks[j] = ks[j - 1u];
                        ids[j] = ids[j - 1u];
                    }
                    ks[j] = tn[c];
                    ids[j] = pn_w4_entry(wn, cur, c);
                }
                for (j = 0; j + 1u < m; j++) {
                    if (sp < PN_BVH_STACK)
                        W->stack[sp++] = ids[j];
                    else
                        cnt->overflow++;
                }
                cur = ids[m - 1u];
                continue;
            }
        } else {
            /* The scene box's bound first; the leaf's, finer, computed once where needed,
             * or a split triangle's own box's (its leaf's box need not hold it). */
            uint32_t first, count = pn_w4_leaf_refs(wnodes, cur, &first), q;
            float eb = -1.0f, e[3], eu;
            for (q = W->q; q < count; q++) {
                uint32_t ref = tri_index[first + q], t = ref & PN_REF_TRI;
                PN_CONST float *p = tris + (size_t)t * 9u;
                int32_t s;
                if (t == own) continue;
                tests++;
                pn_ray_edges(R, p, e);
                eu = R->ebr;
                s = pn_ray_signs(e, eu);
                if (s == 2) {
                    if (ref & PN_REF_SPLIT) {
                        eu = pn_ray_tri_bound(R, p);
                    } else {
                        if (eb < 0.0f) {
                            float lo[3], hi[3];
                            pn_w4_leaf_box(wnodes, cur, lo, hi);
                            eb = pn_ray_bound(R, lo, hi);
                        }
                        eu = eb;
                    }
                    s = pn_ray_signs(e, eu);
                }
                if (s != 0 && pn_ray_decide(R, L, p, s, e, eu)) {
                    W->node = cur;
                    W->sp = sp;
                    W->q = q + 1u;
                    cnt->candidates += tests;
                    cnt->blocking++;
                    return t;
                }
            }
            W->q = 0u;
        }
        if (sp == 0u) break;
        cur = W->stack[--sp];
    }
    W->done = 1u;
    cnt->candidates += tests;
    return PN_RAY_NONE;
}

/* Visibility of one G-buffer pixel (P, unit geometric normal nrm, own triangle id).
 * Counters: candidates = ray-triangle tests, blocking = blocked rays.
 *
 * Neighbouring samples are mostly blocked by the same triangle, so a ray first tests the
 * last triangle the walk found blocking one (a shadow cache: pn_ray_tri is the walk's own
 * exact test, with the scene box's bound), and walks only when that one does not block it.
 * A ray is blocked when some triangle blocks it, whichever is found: the same bits. */
PN_KFN float pn_raytrace_pixel(pn_v3 P, pn_v3 nrm, uint32_t own, PN_CONST float *tris,
                               PN_CONST pn_kbvh4 *wnodes, PN_CONST uint32_t *tri_index, const pn_klight *L,
                               pn_shadow_counters *cnt)
{
    uint32_t k = L->k, blocked = 0, last = PN_RAY_NONE;
    int32_t i, j;
    pn_horizon H;
    pn_ray_origin X;
    pn_ray R;
    pn_v3 O, U = pn_light_U(L);
    float av[32]; /* the sample coordinates, k <= 32 */
    if (!pn_shadow_origin(P, nrm, L, &O)) return 0.0f;
    cnt->lit++;
    pn_horizon_of(P, nrm, own, tris, L, &H);
    pn_tri_block_origin(O, L, wnodes, &X);
    pn_ray_chain(&X, wnodes);
    for (i = 0; i < (int32_t)k; i++) av[i] = pn_sample_coord(i, k);
    for (j = 0; j < (int32_t)k; j++) {
        pn_v3 row = pn_ray_row(&X, L, av[j]);
        for (i = 0; i < (int32_t)k; i++) {
            if (pn_horizon_at(&H, L, av[i], av[j])) {
                blocked++;
                continue;
            }
            pn_ray_set(&X, pn_v3_add(row, pn_v3_scale(U, av[i])), av[i], av[j], i, j, &R);
            if (last != PN_RAY_NONE) {
                cnt->candidates++;
                if (pn_ray_tri(&R, L, tris + (size_t)last * 9u, R.ebr)) {
                    cnt->blocking++;
                    blocked++;
                    continue;
                }
            }
            {
                pn_ray_walk W;
                uint32_t t;
                pn_ray_walk_begin(&W, &X, &R, wnodes);
                t = pn_ray_walk_next(&W, &R, own, tris, wnodes, tri_index, L, cnt);
                if (t != PN_RAY_NONE) {
                    last = t;
                    blocked++;
                }
            }
        }
    }
    /* The same quotient as pn_mask_visibility(). */
    return (float)(k * k - blocked) / (float)(k * k);
}

#endif
