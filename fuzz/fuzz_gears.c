/* fuzz_gears - the predicate is exact and GEARS and the reference's culls are conservative
 * for it: for every shadow-ray origin and triangle, the predicate's mask equals the exact
 * arbiter's bit for bit (tests/pn_test_exact.h: its own formulation, double filter, big
 * integers), and every triangle the arbiter says blocks a sample passes the per-pixel
 * frustum cull and has a cell rectangle that contains that origin's cell. The per-ray
 * ray tracer's filter (kernels/pn_raytrace.h) gives that mask's bit for every sample, with
 * its bound from the triangle's own box, and its slab test passes the box of every
 * triangle that blocks the ray's sample.
 *
 * The bytes make a small hostile configuration: a light of any orientation and aspect (or
 * a point light), up to 24 triangles at scales from 1e-4 to 1e4 with vertices snapped onto,
 * just in front of or just behind the light plane, slivers, and origins that include points
 * whose segments to light samples run exactly through triangle vertices. The grid is built
 * by the same functions the ports use (src/pn_gears.c, kernels/pn_gears.h). */
#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "pn_gears_frame.h"
#include "pn_raytrace.h"
#include "pn_test_exact.h"

typedef struct pn_bytes {
    const uint8_t *p;
    size_t n, i;
} pn_bytes;

static uint32_t take(pn_bytes *b)
{
    uint32_t v = b->i < b->n ? b->p[b->i] : (uint32_t)(b->i * 2654435761u >> 24);
    b->i++;
    return v & 0xFFu;
}

/* A coordinate in [-1, 1) * scale, 16 bits of resolution. */
static float coord(pn_bytes *b, float scale)
{
    uint32_t hi = take(b), lo = take(b); /* two statements: operand order is unspecified */
    int32_t v = (int32_t)((hi << 8) | lo) - 32768;
    return (float)v / 32768.0f * scale;
}

/* Three coordinates x, y, z taken in that order. Not pn_v3_make(coord(), coord(), coord()):
 * argument evaluation order is unspecified (GCC goes right to left, clang left to right), and
 * the replay build (gcc) must decode the bytes exactly as the libFuzzer build (clang) did. */
static pn_v3 coord3(pn_bytes *b, float scale)
{
    float x = coord(b, scale);
    float y = coord(b, scale);
    float z = coord(b, scale);
    return pn_v3_make(x, y, z);
}

#define MAX_T 24
#define MAX_O 48

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const float scales[6] = {1e-4f, 1e-2f, 1.0f, 1.0f, 1e2f, 1e4f};
    pn_bytes b = {data, size, 0};
    float scale = scales[take(&b) % 6u], tris[MAX_T * 9];
    uint32_t nt = 1u + take(&b) % MAX_T, no = 1u + take(&b) % MAX_O, k = 4u << (take(&b) % 4u), t, o, f;
    uint32_t G = 1u + take(&b) % 64u, mode = take(&b);
    pn_klight L;
    pn_v3 c, U, V, N, origins[MAX_O];
    pn_kgrid faces[6];
    uint32_t nfaces;
    float obox[6] = {PN_KINF, PN_KINF, PN_KINF, -PN_KINF, -PN_KINF, -PN_KINF};
    float tbox[6] = {PN_KINF, PN_KINF, PN_KINF, -PN_KINF, -PN_KINF, -PN_KINF}; /* the triangles' */

    memset(&L, 0, sizeof(L));
    c = coord3(&b, scale);
    if (mode & 1u) { /* point light */
        U = V = N = pn_v3_make(0, 0, 0);
        L.k = 1;
        L.is_point = 1;
    } else {
        pn_v3 a = coord3(&b, 1.0f);
        pn_v3 r = coord3(&b, 1.0f);
        float lu = scale * (0.001f + (float)take(&b) / 64.0f), lv = lu * (0.01f + (float)take(&b) / 16.0f);
        if (pn_v3_dot(a, a) < 1e-6f) a = pn_v3_make(1, 0, 0);
        a = pn_v3_normalize(a);
        N = pn_v3_cross(a, r);
        if (pn_v3_dot(N, N) < 1e-6f) N = pn_v3_cross(a, pn_v3_make(a.y, a.z, a.x + 1.0f));
        N = pn_v3_normalize(N);
        U = pn_v3_scale(a, lu);
        V = pn_v3_scale(pn_v3_normalize(pn_v3_cross(N, a)), lv);
        N = pn_v3_normalize(pn_v3_cross(U, V));
        L.k = k;
    }
    L.c[0] = c.x; L.c[1] = c.y; L.c[2] = c.z;
    L.U[0] = U.x; L.U[1] = U.y; L.U[2] = U.z;
    L.V[0] = V.x; L.V[1] = V.y; L.V[2] = V.z;
    L.N[0] = N.x; L.N[1] = N.y; L.N[2] = N.z;

    /* Triangles in front of the light, some vertices pulled onto or across its plane. */
    for (t = 0; t < nt; t++) {
        uint32_t q, how = take(&b);
        float sz = (how & 0x80u) ? 1e-3f : 1.0f;
        pn_v3 base = pn_v3_add(c, coord3(&b, scale));
        for (q = 0; q < 3; q++) {
            pn_v3 p = q == 0 ? base : pn_v3_add(base, coord3(&b, scale * sz));
            if (!L.is_point) {
                float h = pn_v3_dot(pn_v3_sub(p, c), N);
                if (h < 0.0f) p = pn_v3_sub(p, pn_v3_scale(N, 2.0f * h)); /* mirror in front */
                if (((how >> (2 * q)) & 3u) == 1u) p = pn_v3_sub(p, pn_v3_scale(N, pn_v3_dot(pn_v3_sub(p, c), N))); /* onto */
                if (((how >> (2 * q)) & 3u) == 2u) p = pn_v3_sub(p, pn_v3_scale(N, pn_v3_dot(pn_v3_sub(p, c), N) * 1.0001f));
            }
            tris[t * 9 + q * 3 + 0] = p.x;
            tris[t * 9 + q * 3 + 1] = p.y;
            tris[t * 9 + q * 3 + 2] = p.z;
        }
    }
    /* Origins: random points in front, or the extension of a sample->vertex segment beyond
     * the vertex (its segment to that sample runs exactly through the vertex). */
    for (o = 0; o < no; o++) {
        uint32_t how = take(&b);
        pn_v3 O = pn_v3_add(c, coord3(&b, scale));
        if (how & 1u) {
            uint32_t tt = take(&b) % nt, q = take(&b) % 3u, i = take(&b) % L.k, j = take(&b) % L.k;
            pn_v3 vtx = pn_v3_make(tris[tt * 9 + q * 3], tris[tt * 9 + q * 3 + 1], tris[tt * 9 + q * 3 + 2]);
            pn_v3 S = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, pn_sample_coord((int32_t)i, L.k)),
                                             pn_v3_scale(V, pn_sample_coord((int32_t)j, L.k))));
            O = pn_v3_add(vtx, pn_v3_scale(pn_v3_sub(vtx, S), 0.25f + (float)take(&b) / 32.0f));
        }
        if (!L.is_point && !(pn_v3_dot(pn_v3_sub(O, c), N) > 0.0f)) O = pn_v3_sub(O, pn_v3_scale(N, 2.0f * pn_v3_dot(pn_v3_sub(O, c), N) - scale * 1e-3f));
        if (!L.is_point && !(pn_v3_dot(pn_v3_sub(O, c), N) > 0.0f)) O = pn_v3_add(c, pn_v3_scale(N, scale));
        origins[o] = O;
        pn_box3_add(obox, O);
    }

    /* The cull slack as src/pn_frame.c sets it, from the diagonal of the box of the
     * triangles (the library's scene box) and the origins (which a render puts on them). */
    {
        float sb[6];
        pn_v3 d;
        for (t = 0; t < nt * 3u; t++) pn_box3_add(tbox, pn_v3_make(tris[t * 3], tris[t * 3 + 1], tris[t * 3 + 2]));
        memcpy(sb, tbox, sizeof(sb));
        pn_box_join_n(sb, obox, 6u);
        d = pn_v3_make(sb[3] - sb[0], sb[4] - sb[1], sb[5] - sb[2]);
        L.cull_tol = 1e-5f * pn_ksqrt(pn_v3_dot(d, d));
    }

    /* The grid, as the ports build it. */
    nfaces = pn_gears_faces(&L, obox, scale, faces);
    if (L.is_point) {
        for (f = 0; f < 6; f++) pn_gears_bounds(&faces[f], -1.0f, -1.0f, 1.0f, 1.0f, G);
    } else {
        float pb[4];
        pn_box2_empty(pb);
        for (o = 0; o < no; o++) pn_box_add(&faces[0], origins[o], pb);
        pn_gears_bounds(&faces[0], pb[0], pb[1], pb[2], pb[3], G);
    }
    FUZZ_CHECK(nfaces == (L.is_point ? 6u : 1u), "faces %u", nfaces);

    for (o = 0; o < no; o++) {
        uint32_t face = pn_gears_origin_face(&L, origins[o]), cell, cx, cy;
        float px, py;
        pn_grid_project(&faces[face], origins[o], &px, &py);
        cell = pn_grid_cell(&faces[face], px, py);
        cx = cell % G;
        cy = cell / G;
        for (t = 0; t < nt; t++) {
            uint32_t m[PN_MASK_WORDS_MAX];
            pn_v3 A = pn_v3_make(tris[t * 9], tris[t * 9 + 1], tris[t * 9 + 2]);
            pn_v3 B = pn_v3_make(tris[t * 9 + 3], tris[t * 9 + 4], tris[t * 9 + 5]);
            pn_v3 C = pn_v3_make(tris[t * 9 + 6], tris[t * 9 + 7], tris[t * 9 + 8]);
            pn_cellrect r;
            pn_frustum fr;
            arb_light al;
            float Of[3] = {origins[o].x, origins[o].y, origins[o].z}, *T = tris + t * 9;
            uint32_t i, j, words = pn_mask_words(L.k), w, ma[PN_MASK_WORDS_MAX];
            int s0;
            memcpy(al.c, L.c, sizeof(al.c));
            memcpy(al.U, L.U, sizeof(al.U));
            memcpy(al.V, L.V, sizeof(al.V));
            al.k = (int)L.k;
            memset(ma, 0, sizeof(ma));
            s0 = arb_side_O(Of, T, T + 3, T + 6);
            if (!arb_box_out(Of, T, &al) && arb_tri_may_block(T, T + 3, T + 6, &al, s0)) {
                arb_tri at;
                arb_tri_make(&at, Of, T, T + 3, T + 6);
                for (j = 0; j < L.k; j++)
                    for (i = 0; i < L.k; i++)
                        if (arb_tri_blocks_p(&at, Of, T, &al, (int)i, (int)j))
                            ma[(j * L.k + i) >> 5] |= 1u << ((j * L.k + i) & 31u);
            }
            pn_mask_clear(m);
            pn_tri_mask(origins[o], A, B, C, &L, m);
            for (w = 0; w < words; w++)
                FUZZ_CHECK(m[w] == ma[w], "triangle %u, origin %u, k %u: mask word %u is %08x, the exact arbiter's %08x",
                           t, o, L.k, w, m[w], ma[w]);
            {
                /* The ray tracer's per-ray filter (bounds from the triangle's box and from the
                 * triangles' box, as the BVH's leaves and root give them) and slab test. */
                pn_ray_origin X;
                float nlo[3], nhi[3];
                uint32_t q;
                for (q = 0; q < 3; q++) {
                    nlo[q] = pn_kminf(T[q], pn_kminf(T[3 + q], T[6 + q]));
                    nhi[q] = pn_kmaxf(T[q], pn_kmaxf(T[3 + q], T[6 + q]));
                }
                pn_ray_origin_make(origins[o], &L, tbox, tbox + 3, &X);
                for (j = 0; j < L.k; j++)
                    for (i = 0; i < L.k; i++) {
                        uint32_t bit = j * L.k + i, mb = (m[bit >> 5] >> (bit & 31u)) & 1u;
                        pn_ray R;
                        float tn;
                        pn_ray_make(&X, &L, (int32_t)i, (int32_t)j, &R);
                        FUZZ_CHECK(pn_ray_tri(&R, &L, T, pn_ray_bound(&R, nlo, nhi)) == mb &&
                                       pn_ray_tri(&R, &L, T, R.ebr) == mb,
                                   "triangle %u, origin %u, k %u, sample %u,%u: the ray filter disagrees with the mask's %u",
                                   t, o, L.k, i, j, mb);
                        FUZZ_CHECK(!mb || pn_ray_box(&R, nlo, nhi, &tn),
                                   "triangle %u blocks sample %u,%u from origin %u but the ray's slab test rejects its box",
                                   t, i, j, o);
                    }
            }
            if (!pn_mask_count(ma, L.k)) continue;
            /* The per-pixel cull before the predicate (pn_gears_pixel_mask, the reference's
             * BVH walk) must pass it too. */
            pn_frustum_make(origins[o], &L, &fr);
            FUZZ_CHECK(pn_frustum_aabb(&fr, pn_v3_make(pn_kminf(A.x, pn_kminf(B.x, C.x)), pn_kminf(A.y, pn_kminf(B.y, C.y)),
                                                       pn_kminf(A.z, pn_kminf(B.z, C.z))),
                                       pn_v3_make(pn_kmaxf(A.x, pn_kmaxf(B.x, C.x)), pn_kmaxf(A.y, pn_kmaxf(B.y, C.y)),
                                                  pn_kmaxf(A.z, pn_kmaxf(B.z, C.z)))),
                       "triangle %u blocks %u samples from origin %u but the frustum cull rejects its box", t,
                       pn_mask_count(m, L.k), o);
            {
                /* The same cull four boxes at a time (GEARS' chunks and triangle groups):
                 * every lane holds the triangle's box, grown by a lane-dependent amount. */
                float l4[12], h4[12];
                uint32_t c, a;
                for (c = 0; c < 4u; c++) {
                    float g = (float)c * (float)c * 0.21f * (float)(o + 1u);
                    for (a = 0; a < 3u; a++) {
                        l4[a * 4u + c] = pn_kminf(T[a], pn_kminf(T[3 + a], T[6 + a])) - g * (float)(a + 1u);
                        h4[a * 4u + c] = pn_kmaxf(T[a], pn_kmaxf(T[3 + a], T[6 + a])) + g * (float)(3u - a);
                    }
                }
                FUZZ_CHECK(pn_frustum_box4p(&fr, l4, h4) == 0xFu,
                           "triangle %u blocks %u samples from origin %u but the four-box frustum cull rejects a box "
                           "holding it (bits %x)",
                           t, pn_mask_count(m, L.k), o, pn_frustum_box4p(&fr, l4, h4));
            }
            {
                /* The footprints (pn_footprint.h) the reference's walk and GEARS' per-pixel
                 * step skip by: of its box (a leaf's triangles and GEARS' take it) and of
                 * a box around it grown by a hostile amount (a BVH node), must hold every
                 * sample the arbiter finds blocked. */
                pn_foot fp;
                pn_rect rb, rg;
                float grow = (float)(t % 7u) * 0.37f * (float)(o + 1u);
                pn_v3 lo = pn_v3_make(pn_kminf(A.x, pn_kminf(B.x, C.x)), pn_kminf(A.y, pn_kminf(B.y, C.y)),
                                      pn_kminf(A.z, pn_kminf(B.z, C.z)));
                pn_v3 hi = pn_v3_make(pn_kmaxf(A.x, pn_kmaxf(B.x, C.x)), pn_kmaxf(A.y, pn_kmaxf(B.y, C.y)),
                                      pn_kmaxf(A.z, pn_kmaxf(B.z, C.z)));
                pn_foot_make(origins[o], &L, &fp);
                rb = pn_foot_box(&fp, lo, hi);
                rg = pn_foot_box(&fp, pn_v3_sub(lo, pn_v3_make(grow, grow * 0.5f, grow * 0.25f)),
                                 pn_v3_add(hi, pn_v3_make(grow * 0.25f, grow, grow * 0.5f)));
                for (j = 0; j < L.k; j++)
                    for (i = 0; i < L.k; i++) {
                        uint32_t b = j * L.k + i;
                        if (!((ma[b >> 5] >> (b & 31u)) & 1u)) continue;
                        FUZZ_CHECK((int32_t)i >= rb.i0 && (int32_t)i <= rb.i1 && (int32_t)j >= rb.j0 &&
                                       (int32_t)j <= rb.j1,
                                   "triangle %u blocks sample (%u, %u) from origin %u outside its box's footprint "
                                   "[%d..%d] x [%d..%d]",
                                   t, i, j, o, rb.i0, rb.i1, rb.j0, rb.j1);
                        FUZZ_CHECK((int32_t)i >= rg.i0 && (int32_t)i <= rg.i1 && (int32_t)j >= rg.j0 &&
                                       (int32_t)j <= rg.j1,
                                   "triangle %u blocks sample (%u, %u) from origin %u outside the footprint "
                                   "[%d..%d] x [%d..%d] of a box grown by %g",
                                   t, i, j, o, rg.i0, rg.i1, rg.j0, rg.j1, (double)grow);
                    }
            }
            r = pn_gears_tri_cells(&faces[face], &L, A, B, C);
            FUZZ_CHECK(!pn_cellrect_is_empty(r) && cx >= (r.lo & 0xFFFFu) && cx <= (r.hi & 0xFFFFu) &&
                           cy >= (r.lo >> 16) && cy <= (r.hi >> 16),
                       "triangle %u blocks %u samples from origin %u (face %u, cell %u,%u) but its cells are "
                       "[%u..%u] x [%u..%u]",
                       t, pn_mask_count(m, L.k), o, face, cx, cy, r.lo & 0xFFFFu, r.hi & 0xFFFFu, r.lo >> 16, r.hi >> 16);
        }
    }
    return 0;
}
