/* pn_reference.h - PN_ALGO_REFERENCE: exact k x k visibility of one pixel: the horizon of
 * its own triangle ORed with the masks of every other triangle the BVH cannot rule out.
 *
 * Culling is conservative: a node is skipped only when its box is farther than fr->tol
 * outside the light frustum (the pyramid from O over the light rectangle, or the segment
 * O-c for a point light). The predicate is exact (pn_predicate.h): a sample is blocked by
 * a triangle only if its exact segment from O to the exact sample point meets the closed
 * triangle, at a point X of the triangle, hence of its box. X lies in the exact frustum (the
 * convex hull of O and the light rectangle), so a box holding X is outside the float
 * frustum only by the rounding of the float planes: their normals from rounded corners
 * and differences, each a few u of the magnitudes involved. The slack is cull_tol = 1e-5 of
 * the scene diagonal (src/pn_frame.c pn_setup_light) plus 1e-5 of this origin's distance to
 * the light, orders of magnitude above that rounding; no crossing tolerance is needed any
 * more. tests/test_reference.c checks the reference bit for bit against all-triangles brute
 * force, tests/test_exact.c against an exact arbiter, and fuzz/fuzz_gears.c checks the
 * frustum test against the exact predicate on hostile configurations. */
#ifndef PN_REFERENCE_H
#define PN_REFERENCE_H

#include "pn_footprint.h"
#include "pn_predicate.h"
#include "pn_rayfilter.h"

/* A triangle whose footprint holds at most this many open samples is decided ray by ray
 * (pn_ray_tri: the same exact answer per sample as the predicate's mask) instead of by the
 * predicate's forms over the grid: on the dense scanned scenes two thirds of the
 * reference's predicate calls had a single open sample left, each paying the forms'
 * set-up over the whole grid for it. Measured (callgrind, reference pass, 64x64, k = 16): dragon
 * 512 M with no rays, 411 M with up to 2, 404 M with 4, 402 M with 8, 407 M with 16; room
 * 190.5 M, 191.2 M, 191.3 M, 193.7 M, 204.8 M. Since a leaf's rays stop at their first
 * blocker and come from the pixel's cache (pn_ray_cache), 8 beats 4 (wall, -march=native,
 * 256x256, one thread, medians of 5 alternated: spheres -6.7%, buddha -3.3%, bunny -4.2%,
 * dragon -1.4%, room +1.9%) and 16 is no better than 8 (spheres +1.0%, dragon -0.2%,
 * buddha -1.3%). */
#define PN_REF_RAYS 8u

/* A wide node whose rectangle holds at most this many open samples picks its children by
 * those samples' rays (pn_ray_box4, the per-ray walk's slab test) instead of the frustum
 * test and the four footprints. Measured (wall, -march=native, 512x512, 2 threads, medians
 * of 5, alternated with the frustum and footprints everywhere): dragon -6.4%, buddha -7.6%,
 * spheres +0.3%, bunny +1.8%; up to 4 samples is no better than 2 (dragon -1.1%, buddha
 * -1.0%, spheres +1.0%), up to 8 (PN_REF_RAYS) worse on spheres (+7.6%). */
#define PN_REF_NODE_RAYS 2u

/* ORs into m the samples of rectangle r (which holds every sample triangle ABC can block
 * from O: its footprint, or the whole grid) that the triangle blocks and m has not; p is
 * its 9 floats, X the rays' set-up for O (pn_ray_origin_make), RC the rays already built
 * from it. Returns 1 if it blocked one. Up to PN_REF_RAYS open samples: a ray each
 * (pn_ray_tri, the filter's bound from the triangle's own box); more: pn_tri_mask_in over
 * r's rows. Either way each sample gets the
 * predicate's exact answer, so m is the same. nf, si, sj: r's open samples as
 * pn_rect_few(m, k, r, PN_REF_RAYS, si, sj) finds them (r not empty), which the caller has
 * just looked for to skip a triangle with none. */
PN_KFN uint32_t pn_tri_block(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, PN_CONST float *p, const pn_klight *L,
                             const pn_ray_origin *X, pn_ray_cache *RC, uint32_t *m, pn_rect r, uint32_t nf,
                             const int32_t *si, const int32_t *sj)
{
    uint32_t k = L->k, s, hit = 0u;
    if (nf > PN_REF_RAYS) return pn_tri_mask_in(O, A, B, C, L, m, r.i0, r.i1, r.j0, r.j1);
    for (s = 0; s < nf; s++) {
        const pn_ray *R = &RC->r[pn_ray_cache_get(RC, X, L, si[s], sj[s])];
        if (pn_ray_tri(R, L, p, pn_ray_tri_bound(R, p))) {
            pn_mask_set(m, k, si[s], sj[s]);
            hit = 1u;
        }
    }
    return hit;
}

/* The rays' set-up for origin O over the BVH's box (no chain: the callers of
 * pn_tri_block do not walk rays; a ray walk adds it, pn_ray_chain). */
PN_KFN void pn_tri_block_origin(pn_v3 O, const pn_klight *L, PN_CONST pn_kbvh4 *wnodes, pn_ray_origin *X)
{
    float lo[3], hi[3];
    pn_w4_root_box(wnodes, lo, hi);
    pn_ray_origin_make(O, L, lo, hi, X);
}

/* The light frustum of one shadow-ray origin: planes n.X <= d (already moved out by the
 * slack), or for a point light the segment O + t (c - O), t in [0, 1]. */
typedef struct pn_frustum {
    pn_v3 n[6];
    float d[6];
    pn_v3 seg_o, seg_d;
    uint32_t is_point;
    float tol;
} pn_frustum;

PN_KFN void pn_frustum_make(pn_v3 O, const pn_klight *L, pn_frustum *fr)
{
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    /* cull_tol (1e-5 of the scene diagonal: the rounding of coordinates of the scene's
     * size), plus 1e-5 of this origin's distance to the light for the rounding of the
     * planes through O, which grows with that distance, not with the scene. */
    fr->tol = L->cull_tol + 1e-5f * (pn_v3_l1(pn_v3_sub(c, O)) + pn_v3_l1(pn_v3_make(L->U[0], L->U[1], L->U[2])) +
                                     pn_v3_l1(pn_v3_make(L->V[0], L->V[1], L->V[2])));
    fr->is_point = L->is_point;
    fr->seg_o = O;
    fr->seg_d = pn_v3_sub(c, O);
    if (L->is_point) {
        uint32_t q;
        for (q = 0; q < 6; q++) { /* unused by a point light; defined all the same */
            fr->n[q] = pn_v3_make(0.0f, 0.0f, 0.0f);
            fr->d[q] = 0.0f;
        }
    } else {
        pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
        pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
        pn_v3 N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
        pn_v3 corner[4];
        uint32_t q;
        corner[0] = pn_v3_sub(pn_v3_sub(c, U), V);
        corner[1] = pn_v3_sub(pn_v3_add(c, U), V);
        corner[2] = pn_v3_add(pn_v3_add(c, U), V);
        corner[3] = pn_v3_add(pn_v3_sub(c, U), V);
        for (q = 0; q < 4; q++) {
            /* (corner_q - O) x (corner_q+1 - corner_q): the plane through O and the light
             * edge. Not (corner_q - O) x (corner_q+1 - O), which cancels when the light is
             * small and far: for a 5e-3 light 14 units away the cull put a blocking
             * triangle's box 1.4e-5 beyond a plane already moved out by 1.8e-3
             * (fuzz/corpus/gears/crash-frustum-small-far-light.bin). */
            pn_v3 a = pn_v3_sub(corner[q], O), e = pn_v3_sub(corner[(q + 1u) & 3u], corner[q]);
            pn_v3 n = pn_v3_normalize(pn_v3_cross(a, e));
            /* Outward: the light centre is inside, n.(c - O) <= 0. */
            if (pn_v3_dot(n, fr->seg_d) > 0.0f) n = pn_v3_scale(n, -1.0f);
            fr->n[q] = n;
            fr->d[q] = pn_v3_dot(n, O) + fr->tol;
        }
        /* Light plane: the segments end on it; nothing behind it is crossed. */
        fr->n[4] = pn_v3_scale(N, -1.0f);
        fr->d[4] = -pn_v3_dot(N, c) + fr->tol;
        /* O's plane parallel to the light: nothing beyond O is crossed. */
        fr->n[5] = N;
        fr->d[5] = pn_v3_dot(N, O) + fr->tol;
    }
}

PN_KFN_HOT int pn_slab(float o, float d, float lo, float hi, float *t0, float *t1)
{
    if (d == 0.0f) return o >= lo && o <= hi;
    {
        float a = (lo - o) / d, b = (hi - o) / d;
        float tn = pn_kminf(a, b), tf = pn_kmaxf(a, b);
        if (tn > *t0) *t0 = tn;
        if (tf < *t1) *t1 = tf;
    }
    return *t0 <= *t1;
}

/* 0 when the box [lo, hi] certainly holds nothing the frustum's segments can cross. The
 * box comes by value so that a box in private memory (GEARS' per-triangle box) and a BVH
 * node in the arena take the same test (OpenCL C 1.2 has no generic address space). */
PN_KFN_HOT int pn_frustum_aabb(const pn_frustum *fr, pn_v3 lo, pn_v3 hi)
{
    if (fr->is_point) {
        float t0 = 0.0f, t1 = 1.0f, tol = fr->tol;
        return pn_slab(fr->seg_o.x, fr->seg_d.x, lo.x - tol, hi.x + tol, &t0, &t1) &&
               pn_slab(fr->seg_o.y, fr->seg_d.y, lo.y - tol, hi.y + tol, &t0, &t1) &&
               pn_slab(fr->seg_o.z, fr->seg_d.z, lo.z - tol, hi.z + tol, &t0, &t1);
    } else {
        uint32_t q;
        for (q = 0; q < 6; q++) {
            pn_v3 n = fr->n[q];
            pn_v3 v = pn_v3_make(n.x >= 0.0f ? lo.x : hi.x, n.y >= 0.0f ? lo.y : hi.y, n.z >= 0.0f ? lo.z : hi.z);
            if (pn_v3_dot(n, v) > fr->d[q]) return 0;
        }
        return 1;
    }
}

/* pn_frustum_aabb on four boxes in private memory (a wide node's children copied out of
 * their pn_kbvh4; GEARS' chunks and triangles), box c being lo[a * 4 + c], hi[a * 4 + c]
 * over axes a: bit c set when box c may hold a crossing. For an area light each plane's
 * term is min(n lo, n hi) per axis, the same float as the corner pn_frustum_aabb picks
 * (n >= 0: n lo <= n hi, rounding being monotone), in loops without a branch that a
 * compiler runs four lanes at a time; a point light's segment test lane by lane. */
PN_KFN uint32_t pn_frustum_box4p(const pn_frustum *fr, const float *lo, const float *hi)
{
    uint32_t c, q, bits = 0u;
    int32_t out[4];
    if (fr->is_point) {
        for (c = 0; c < 4u; c++)
            bits |= (uint32_t)pn_frustum_aabb(fr, pn_v3_make(lo[c], lo[4u + c], lo[8u + c]),
                                              pn_v3_make(hi[c], hi[4u + c], hi[8u + c]))
                    << c;
        return bits;
    }
    for (c = 0; c < 4u; c++) { /* lanes outside, planes inside: the lane loop vectorizes */
        int32_t o = 0;
        for (q = 0; q < 6u; q++) {
            pn_v3 n = fr->n[q];
            float v = pn_kminf(n.x * lo[c], n.x * hi[c]) + pn_kminf(n.y * lo[4u + c], n.y * hi[4u + c]) +
                      pn_kminf(n.z * lo[8u + c], n.z * hi[8u + c]);
            o |= v > fr->d[q];
        }
        out[c] = o;
    }
    for (c = 0; c < 4u; c++) bits |= (uint32_t)(out[c] == 0) << c;
    return bits;
}

PN_KFN void pn_tri_load(PN_CONST float *tris, uint32_t t, pn_v3 *A, pn_v3 *B, pn_v3 *C)
{
    PN_CONST float *p = tris + (size_t)t * 9u;
    *A = pn_v3_make(p[0], p[1], p[2]);
    *B = pn_v3_make(p[3], p[4], p[5]);
    *C = pn_v3_make(p[6], p[7], p[8]);
}

/* Per-work-item counters, summed by the host (integer adds: order-independent). */
typedef struct pn_shadow_counters {
    uint32_t candidates; /* triangles handed to the predicate (pn_tri_block: rays or forms) */
    uint32_t blocking;   /* ...that blocked at least one sample (a leaf decided ray by ray: each blocked ray) */
    uint32_t lit;        /* pixels in front of the light */
    uint32_t overflow;   /* traversal stack overflows (must stay 0) */
    uint32_t nodes;      /* BVH nodes whose boxes were tested */
    uint32_t capped;     /* pixels a pass decided at one of its documented caps (the wedges'
                            PN_WG_HARD_MAX objects on the centre ray): a statistic in
                            pn_stats, never an error */
    uint32_t exact;      /* pixels an approximation resolved with the exact predicate (the
                            wedges' self-shadow penumbrae) */
} pn_shadow_counters;

/* One slot of the counters pool (a row's, or for the passes in tiles a tile's:
 * pn_pix_slot): pn_shadow_counters padded to 64 bytes, a cache line, so that threads
 * adding into neighbouring slots do not share one. Measured with
 * MCSM's per-row words padded alike (PN_MC_ROW_WORDS): its rays stage on spot, 512x512, 2
 * threads, medians of alternating runs 46.7 -> 42.2 .. 43.5 ms. */
#define PN_ROW_COUNTERS_PAD 9
typedef struct pn_row_counters {
    pn_shadow_counters c;
    uint32_t pad[PN_ROW_COUNTERS_PAD];
} pn_row_counters;

/* The triangles of a list (index entries list[0 .. n), PN_REF_TRI masking the id; a BVH
 * leaf's or a GEARS chunk's) into mask m, four at a time: with `cull`, their boxes against
 * the frustum (the conservative test pn_frustum_box4p); their boxes' footprints
 * (pn_foot_box4; with `exact`, the whole light: GEARS' statistics compute every
 * assignment's whole mask), then pn_tri_block on each whose rectangle still holds an open
 * sample (every one with `exact`, each on a mask of its own, ORed into m). Sets *any when
 * a triangle blocks; returns 1 when the mask is full (never with `exact`). */
PN_KFN_HOT uint32_t pn_tris_block4(PN_CONST uint32_t *list, uint32_t n, uint32_t own, uint32_t cull, uint32_t exact,
                                   PN_CONST float *tris, const pn_frustum *fr, const pn_foot *fp, pn_v3 O,
                                   const pn_klight *L, const pn_ray_origin *X, pn_ray_cache *RC, uint32_t *m,
                                   uint32_t *any, pn_shadow_counters *cnt)
{
    uint32_t k = L->k, e = 0u, ts[4], nt, l, bits, tm[PN_MASK_WORDS_MAX];
    float lo[12], hi[12]; /* the boxes of up to four triangles, as lanes (pn_lanes_put) */
    pn_rect r[4];
    while (e < n) {
        for (nt = 0; nt < 4u && e < n; e++) {
            uint32_t t = list[e] & PN_REF_TRI;
            pn_v3 A, B, C;
            if (t == own) continue;
            pn_tri_load(tris, t, &A, &B, &C);
            pn_lanes_put_tri(lo, hi, nt, A, B, C);
            ts[nt++] = t;
        }
        if (!nt) continue;
        bits = (cull ? pn_frustum_box4p(fr, lo, hi) : 0xFu) & ((1u << nt) - 1u);
        if (!bits) continue;
        if (exact) {
            for (l = 0; l < 4u; l++) r[l] = pn_rect_full(k);
        } else {
            pn_foot_box4(fp, lo, hi, r);
        }
        for (l = 0; l < nt; l++) {
            pn_v3 A, B, C;
            int32_t si[PN_REF_RAYS], sj[PN_REF_RAYS];
            uint32_t nf, hit;
            if (!((bits >> l) & 1u) || pn_rect_empty(r[l])) continue;
            /* With `exact`, the triangle's whole mask on its own (tm), ORed into m:
             * "blocking" then counts the triangles that block any sample (paper Table 6's
             * necessary assignments), whatever the others blocked before them. */
            if (exact) pn_mask_clear(tm);
            /* r[l]'s open samples, looked for once: none, and the triangle is skipped; a
             * few, and pn_tri_block takes them as they are */
            nf = pn_rect_few(exact ? tm : m, k, r[l], PN_REF_RAYS, si, sj);
            if (nf == 0u) continue;
            pn_tri_load(tris, ts[l], &A, &B, &C);
            cnt->candidates++;
            hit = pn_tri_block(O, A, B, C, tris + (size_t)ts[l] * 9u, L, X, RC, exact ? tm : m, r[l], nf, si, sj);
            if (hit) {
                cnt->blocking++;
                *any = 1u;
                if (exact)
                    pn_mask_or(m, tm, k);
                else if (pn_mask_full(m, k))
                    return 1u; /* only a block grows the mask */
            }
        }
    }
    return 0u;
}

/* Visibility of one G-buffer pixel (P, unit geometric normal nrm, own triangle id).
 *
 * The walk (over the four-wide tree, pn_kbvh4) keeps the mask m of samples found blocked
 * so far and visits a child only while its footprint on the light (pn_footprint.h) still
 * holds a sample m has not blocked: the test runs when a child is pushed and again when it
 * is popped, since m may have grown in between. A wide node's children are first tested
 * against the light frustum together (pn_frustum_box4p), then their footprints, four at a
 * time (pn_foot_box4), or, when the node's rectangle holds at most PN_REF_NODE_RAYS open
 * samples, by those samples' rays (pn_ray_box4: a child's rectangle is then the one around
 * the samples whose segments may meet its box); the survivors go on the stack in
 * pn_foot_order(): the child whose centre lies farther from the light toward O is walked
 * first (near occluders have the large footprints that fill a mask soonest). At a leaf (a binary leaf node) whose box
 * holds at most PN_REF_RAYS open samples, each one's ray meets the leaf's triangles until
 * one blocks it (pn_ray_tri; the rays from the pixel's cache, the filter's bound from the
 * leaf's box once per ray: a footprint per triangle costs more than the few rays it would
 * spare). At any other leaf (pn_tris_block4, GEARS' chunk step too), the footprints of its
 * triangles' boxes, four at a time, and a triangle whose rectangle holds no open sample is
 * skipped before any of the predicate's set-up; pn_tri_block decides the open samples it
 * holds (a few: a ray each; more: the forms over its rows). Measured (callgrind, reference pass, 128x128,
 * k = 16, one thread, default x86-64 target) against building each ray where it is
 * tested, bounding it by the triangle's box and taking each triangle's own footprint
 * (its projected vertices): dragon 1,233 M -> 1,144 M, buddha 1,261 -> 1,190, spheres
 * 1,168 -> 1,032, bunny 751 -> 700, room 762 -> 725. The result
 * is the OR over every triangle that can block an open sample, so it is the same mask in
 * any order and over any tree; only the counters depend on them. */
PN_KFN float pn_reference_pixel(pn_v3 P, pn_v3 nrm, uint32_t own, PN_CONST float *tris,
                                PN_CONST pn_kbvh4 *wnodes, PN_CONST uint32_t *tri_index, const pn_klight *L,
                                pn_shadow_counters *cnt)
{
    uint32_t m[PN_MASK_WORDS_MAX], stack[PN_BVH_STACK], rects[PN_BVH_STACK];
    uint32_t k = L->k, sp = 0u, any, n;
    pn_ray_origin X;
    pn_ray_cache RC;
    pn_frustum fr;
    pn_foot fp;
    pn_horizon H;
    pn_rect r;
    pn_v3 O;

    if (!pn_shadow_origin(P, nrm, L, &O)) return 0.0f;
    cnt->lit++;
    pn_mask_clear(m);
    pn_horizon_of(P, nrm, own, tris, L, &H);
    n = pn_horizon_mask(&H, L, m);
    if (n == k * k) return 0.0f;
    any = n != 0u;
    pn_frustum_make(O, L, &fr);
    pn_foot_make(O, L, &fp);
    pn_tri_block_origin(O, L, wnodes, &X);
    pn_ray_cache_clear(&RC);
    stack[0] = 0u; /* the root: its children are tested when it is popped */
    rects[0] = pn_rect_pack(pn_rect_full(k));
    sp = 1u;
    while (sp > 0u) {
        uint32_t e;
        pn_rect rb;
        sp--;
        rb = pn_rect_unpack(rects[sp]);
        e = stack[sp];
        if (pn_rect_empty(rb)) continue;
        if (!(e & PN_W4_LEAF)) { /* wide node: its children, O's side last pushed */
            PN_CONST pn_kbvh4 *w = wnodes + e;
            int32_t si[PN_REF_NODE_RAYS], sj[PN_REF_NODE_RAYS];
            uint32_t bits, c, j, n_in = 0u, id[4], pk[4], nf;
            float key[4], blo[12], bhi[12];
            pn_rect r4[4];
            /* its rectangle's open samples, looked for once (none: blocked since the push) */
            nf = any ? pn_rect_few(m, k, rb, PN_REF_NODE_RAYS, si, sj) : PN_REF_NODE_RAYS + 1u;
            if (nf == 0u) continue;
            cnt->nodes += w->n;
            for (c = 0; c < 12u; c++) {
                blo[c] = w->lo[c >> 2][c & 3u];
                bhi[c] = w->hi[c >> 2][c & 3u];
            }
            if (nf <= PN_REF_NODE_RAYS) {
                /* A few open samples: their rays' slab tests (the per-ray walk's, from the
                 * pixel's cache) pick the children, and a child's rectangle is the one
                 * around the samples whose segments may meet its box: a sample outside
                 * rb, blocked, or whose segment misses the box is none the child can
                 * block. */
                uint32_t s;
                bits = 0u;
                for (c = 0; c < 4u; c++) r4[c] = pn_rect_make((int32_t)k, -1, (int32_t)k, -1);
                for (s = 0; s < nf; s++) {
                    float tn[4];
                    uint32_t h = pn_ray_box4(&RC.r[pn_ray_cache_get(&RC, &X, L, si[s], sj[s])], w, tn);
                    bits |= h;
                    for (c = 0; c < 4u; c++) {
                        if (!((h >> c) & 1u)) continue;
                        r4[c].i0 = si[s] < r4[c].i0 ? si[s] : r4[c].i0;
                        r4[c].i1 = si[s] > r4[c].i1 ? si[s] : r4[c].i1;
                        r4[c].j0 = sj[s] < r4[c].j0 ? sj[s] : r4[c].j0;
                        r4[c].j1 = sj[s] > r4[c].j1 ? sj[s] : r4[c].j1;
                    }
                }
            } else {
                bits = pn_frustum_box4p(&fr, blo, bhi) & ((1u << w->n) - 1u);
                /* While nothing is blocked, a box's footprint can only be empty between
                 * samples, which a box large enough to be an interior node seldom is: the
                 * whole light. */
                if (bits && any) pn_foot_box4(&fp, blo, bhi, r4);
            }
            if (!bits) continue;
            for (c = 0; c < 4u; c++) {
                pn_v3 lo, hi;
                float kc;
                if (!((bits >> c) & 1u)) continue;
                lo = pn_v3_make(blo[c], blo[4u + c], blo[8u + c]);
                hi = pn_v3_make(bhi[c], bhi[4u + c], bhi[8u + c]);
                r = any ? r4[c] : pn_rect_full(k);
                if (any && !pn_rect_open(m, k, r)) continue;
                kc = pn_foot_order(&fp, lo, hi);
                /* insertion, smallest key first: the largest goes on top */
                for (j = n_in++; j > 0u && key[j - 1u] > kc; j--) {
                    key[j] = key[j - 1u];
                    id[j] = id[j - 1u];
                    pk[j] = pk[j - 1u];
                }
                key[j] = kc;
                id[j] = pn_w4_entry(w, e, c);
                pk[j] = pn_rect_pack(r);
            }
            for (c = 0; c < n_in; c++) {
                if (sp < PN_BVH_STACK) {
                    stack[sp] = id[c];
                    rects[sp] = pk[c];
                    sp++;
                } else {
                    cnt->overflow++;
                }
            }
        } else {
            int32_t si[PN_REF_RAYS], sj[PN_REF_RAYS];
            uint32_t first, count, q, nf = pn_rect_few(m, k, rb, PN_REF_RAYS, si, sj);
            if (nf == 0u) continue; /* blocked since the push */
            count = pn_w4_leaf_refs(wnodes, e, &first);
            if (nf <= PN_REF_RAYS) {
                /* A few open samples in the leaf's rectangle: each one's ray (from the
                 * pixel's cache) against the leaf's triangles until one blocks it, with
                 * the filter's bound from the leaf's box (a split triangle's from its own). */
                uint32_t s;
                float lo[3], hi[3];
                pn_w4_leaf_box(wnodes, e, lo, hi);
                /* nf >= 1: rb held an open sample when popped */
                for (q = 0; q < count; q++) cnt->candidates += (tri_index[first + q] & PN_REF_TRI) != own;
                for (s = 0; s < nf; s++) {
                    const pn_ray *R = &RC.r[pn_ray_cache_get(&RC, &X, L, si[s], sj[s])];
                    float eb = pn_ray_bound(R, lo, hi);
                    for (q = 0; q < count; q++) {
                        uint32_t ref = tri_index[first + q], t = ref & PN_REF_TRI;
                        PN_CONST float *p = tris + (size_t)t * 9u;
                        if (t == own) continue;
                        if (pn_ray_tri(R, L, p, (ref & PN_REF_SPLIT) ? pn_ray_tri_bound(R, p) : eb)) {
                            pn_mask_set(m, k, si[s], sj[s]);
                            cnt->blocking++;
                            any = 1u;
                            break;
                        }
                    }
                }
            } else if (pn_tris_block4(tri_index + first, count, own, 0u, 0u, tris, &fr, &fp, O, L, &X, &RC, m,
                                      &any, cnt)) {
                break; /* the mask is full */
            }
            if (any && pn_mask_full(m, k)) break;
        }
    }
    return pn_mask_visibility(m, k);
}

/* The approximations' exact fallback: a pixel that an approximation cannot represent (the
 * wedges' self-shadow penumbrae; for the light-space algorithms, an origin that no window of
 * the light's view holds, pn_lview_outside) takes the reference's visibility over at most
 * PN_REF_FALLBACK_K^2 samples (all k^2 when k is smaller). k = 4: on the 15 scenes the
 * wedges' self-shadow penumbrae at k = 4 gave the RMSE of k = 16 to the third decimal
 * (0.0698 for 0.0697 on the Buddha, the most of them) for 0.47 G instructions more than
 * none there instead of 1.89 G (callgrind, 256 x 256). Counted in cnt->exact. */
#define PN_REF_FALLBACK_K 4u
/* The same over at most kmax^2 samples (the wedges' tiles whose lists outgrow their pools
 * take the frame's k). */
PN_KFN float pn_reference_fallback_k(pn_v3 P, pn_v3 nrm, uint32_t own, PN_CONST float *tris, PN_CONST pn_kbvh4 *wnodes,
                                     PN_CONST uint32_t *tri_index, const pn_klight *L, uint32_t kmax,
                                     pn_shadow_counters *cnt)
{
    pn_shadow_counters ce = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    pn_klight Lk = *L;
    if (Lk.k > kmax) Lk.k = kmax;
    cnt->exact++;
    return pn_reference_pixel(P, nrm, own, tris, wnodes, tri_index, &Lk, &ce);
}

PN_KFN float pn_reference_fallback(pn_v3 P, pn_v3 nrm, uint32_t own, PN_CONST float *tris, PN_CONST pn_kbvh4 *wnodes,
                                   PN_CONST uint32_t *tri_index, const pn_klight *L, pn_shadow_counters *cnt)
{
    return pn_reference_fallback_k(P, nrm, own, tris, wnodes, tri_index, L, PN_REF_FALLBACK_K, cnt);
}

#endif
