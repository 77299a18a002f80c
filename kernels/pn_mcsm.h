/* pn_mcsm.h - Monte Carlo shadow maps (Curtis 2009, "Real-time soft shadows on the GPU via
 * Monte Carlo sampling"): the work items of the frame in src/pn_mcsm.c.
 *
 * Frame of reference. The light frame of pn_lview.h: origin at the light centre c, axes
 * lview's r, u, f (an area light: U^, V^, N), depth z along f. The depth layers are seen
 * from a centre of projection d behind the light centre whose frustum passes through the
 * light's edges and holds every lit shadow-ray origin (pn_lview_window; the thesis' eq. 3.1
 * places the projection point so that "the entire light fits within the view frustum"):
 * then every segment from a point of the light to an origin projects inside that frustum
 * (§3, "every point along the ray projects to a point in the interior of the depth map").
 * The map's window is then narrowed to the image of the occluders' box
 * (pn_lview_fit_occluders): where the receivers reach far beyond the occluders (a ground
 * to the horizon) the thesis' window spends most texels where no occluder is. A point whose
 * image lies beyond the narrowed map lies in no occluder; each ray's search is clipped to
 * the map (pn_mc_clip) and a region reaching beyond it counts those texels empty.
 * A point light has d = 0: its one ray projects to a single texel (a shadow-map test).
 *
 * Layers (§3.3). Over the fragments of every triangle not marked receiver-only
 * (pn_scene_set_receivers; §3.3 requires pure receivers to stay out), in front of the light
 * plane, each texel keeps the nearest depth (near layer) and the farthest (far layer).
 * The thesis renders the far layer from back faces with the depth test reversed; keeping
 * the farthest fragment of any facing is the same for closed meshes and keeps a single
 * open sheet (a quad occluder) an occluder of zero thickness instead of none. A texel's
 * occupied interval is [near, far]: the volume between the layers is taken as solid.
 * Empty texels: near = +inf, far = -inf.
 *
 * N-buffer (§3.5; kernels/pn_nbuffer.h). Three channels per texel and level: min near,
 * max far, max near (stored with min near negated, so that every channel is a max:
 * pn_nb_mm_get); level 0 is the layers (max near = near).
 *
 * Rays (§3, §3.1). Ray i of pixel (x, y) goes from a point S of the light, jittered in cell
 * i of an n x n grid by the reduced 16-step MD5 of Appendix A (pn_md5r, seeded by the pixel
 * coordinates and the ray index, keyed by the frame key), to the pixel's shadow-ray origin
 * E (pn_shadow_origin), pulled back toward S by the adaptive bias of eq. 3.2. On the ray,
 * X(t) = S + t (E - S), its depth is t z_E (S is at depth 0), and its image in the layers is
 * a straight segment. A ray is blocked when
 *   one layer:  some point of it lies at or behind the near layer of its texel;
 *   two layers: some point lies in its texel's [near, far];
 *   three layers: the same, unless that point is seen from the eye (in front of the
 *     G-buffer's depth at its pixel: empty space, Algorithm 1).
 * Its end point counts (the thesis' "endpoint inside a solid object" test, one lookup): the
 * searches walk half-open steps and would miss an end lying exactly on a solid texel's edge.
 * Visibility = unblocked rays / n^2, then the screen-space blur.
 *
 * Early-outs and shortening (§3.6, §3.7), all but the umbra test consistent with the
 * model above: a pixel whose surface, as its winding orients it, faces away from the light
 * centre is umbra (the thesis' first early-out, per fragment; for a closed mesh the exact
 * algorithms' convention gives the same, and the layers cannot show a surface its own back
 * side), and a ray toward a light point behind the surface's plane is blocked (the horizon
 * of invariant 6); a pixel whose origin lies no
 * deeper than the smallest near depth of the region every ray can reach (eq. 3.3, refined
 * twice from the whole map's minimum; pn_mc_reach) is lit; with one or two layers, a pixel
 * whose every ray ends behind the largest near depth of that region is umbra (the thesis'
 * test; with two layers it assumes solid occluders, with three it is off, as the thesis
 * says); a ray whose own region has no near depth before its end is unblocked; rays start
 * at the region's smallest near depth and, with two or more layers, end at its largest far
 * depth. With one layer every one of them gives the model's answer: test_mcsm renders
 * the same bytes with and without them (at 512x512 on thin and the bunny; every built-in
 * and shared scene at 512x512 and 333x257 does too, and at 256x192 all but one bunny
 * pixel, where a ray grazes a near depth by one ulp at a texel's edge and the search's
 * point rounds onto the next texel).
 *
 * Searches. Linear (§3.3): samples one texel apart in the layers' image, each in front of,
 * inside or behind its texel's interval; a change between in front and behind is refined
 * by bisection (PN_MC_BISECT steps), and a bracket that ends within one texel, in front at
 * its start and behind at its end, crossed that texel's interval: blocked. Hierarchical
 * (Algorithm 2): a box of 2^l texels placed at the current point toward the ray's end; if
 * the ray's depths inside the box meet the box's [min near, max far], step to the depth
 * min near and descend (at level 0: blocked), else step past the box and ascend. Every
 * search is capped at PN_MC_STEP_CAP(res) steps (counted; the ray then counts as
 * unblocked). Points whose image lies beyond the map (origins the window had to leave out,
 * beyond PN_LVIEW_TAN_MAX) see no occluder.
 *
 * Blur (§3). A separable filter over the visibility buffer, binomial weights C(2r, r + i)
 * (a Gaussian of variance r / 2 in integers, so no exp), each neighbour's weight divided
 * by 1 + |its depth - the centre's| blur_depth / centre depth (the thesis' depth-sensitive
 * filter, "inversely proportional to the difference ... plus 1", in relative depth);
 * background neighbours and neighbours across a crease (normals more than about 37
 * degrees apart: the normal sensitivity the thesis recommends) take no part. Taps summed in a fixed order.
 *
 * Every float operation is the same on both ports (no contraction, correctly rounded
 * divide and sqrt, integer hashing and exact int-to-float conversions for the samples). */
#ifndef PN_MCSM_H
#define PN_MCSM_H

#include "pn_lview.h"
#include "pn_nbuffer.h"
#include "pn_predicate.h"
#include "pn_raster.h"

#define PN_MC_S_LINEAR 1u
#define PN_MC_S_HIER 2u
#define PN_MC_F_NO_BIAS 1u
#define PN_MC_F_NO_CLASSIFY 2u
#define PN_MC_RAYS_MAX 8u
#define PN_MC_BLUR_MAX 8u
/* Bisection steps of the linear search's refinement (1/256 of a texel). */
#define PN_MC_BISECT 8u
/* Steps one search may take. */
#define PN_MC_STEP_CAP(res) (8u * (res) + 64u)
/* The smallest cosine the adaptive bias divides by (eq. 3.2: "n . l must be limited to
 * some small, non-zero value"): at most ten times the bias facing the light. Measured on the
 * shared scenes (512x512, RMSE against the k = 32 reference, blur radius 1): 0.25 left
 * grazing surfaces self-shadowed (spot 0.038, bunny 0.035); 0.1 gives spot 0.023, bunny
 * 0.030, CAD 0.014, buddha 0.047, dragon 0.041, chess 0.045; 0.05 starts to leak (chess,
 * CAD and buddha worse again). */
#define PN_MC_COS_MIN 0.1f
/* Relative slack of a depth bound turned into a ray parameter (t = z / z_E): the rounding
 * of t z_E must not move a ray's crossing of a plane occluder (near = far) out of the
 * searched range. */
#define PN_MC_T_SLACK 2.4e-7f
/* The smallest step of the hierarchical search, as a fraction of the searched range (taken
 * only where rounding leaves no exit after the current point). */
#define PN_MC_T_STEP 2.44140625e-4f
/* Texels from a box side within which a point whose exit rounds to before it is taken to
 * lie on that side. */
#define PN_MC_ON_EDGE 1e-2f
/* Neighbours whose normal is more than about 37 degrees off the centre's take no part in
 * its blur. */
#define PN_MC_BLUR_COS 0.8f
/* Texels beyond each side of the map that a ray's search still walks (pn_mc_clip): room
 * for the rounding of the clip's parameters (the window is at most 256 times narrower than
 * the light's image, so a relative error of 1e-6 moves an image point by well under one). */
#define PN_MC_CLIP_TEXELS 4.0f
/* Per-row class counters (pool mc_words, PN_MC_WORDS used of PN_MC_ROW_WORDS per row: a
 * row's words fill a cache line of their own, like pn_row_counters). */
#define PN_MC_WORD_LIT 0u
#define PN_MC_WORD_UMBRA 1u
#define PN_MC_WORD_PENUMBRA 2u      /* penumbra pixels whose rays came back mixed */
#define PN_MC_WORD_PENUMBRA_OPEN 3u /* ...that no layer blocked (lit as far as the layers say) */
#define PN_MC_WORD_PENUMBRA_SHUT 4u /* ...whose every sample in front was blocked */
#define PN_MC_WORD_CAPPED 5u
#define PN_MC_WORDS 6u
#define PN_MC_ROW_WORDS 16u

/* ---- The sample hash: Appendix A's reduced MD5 ------------------------------------------- */

/* One of the sixteen steps as the appendix writes them: F of the working state t (the
 * appendix's tD), message word m, constant c, rotation s; then the state rotates
 * (tD = tD.yzwx) and is added into the digest. */
PN_KFN void pn_md5r_step(uint32_t *t, uint32_t *dg, uint32_t F, uint32_t m, uint32_t c, uint32_t s)
{
    uint32_t r = t[0] + F + m + c, x = t[1] + ((r << s) + (r >> (32u - s)));
    t[0] = t[1];
    t[1] = t[2];
    t[2] = t[3];
    t[3] = x;
    dg[0] += t[0];
    dg[1] += t[1];
    dg[2] += t[2];
    dg[3] += t[3];
}

/* The round functions of t0, t1, t2. */
#define PN_MD5R_G1(a, b, c) (((a) & (b)) | (~(a) & (c)))
#define PN_MD5R_G2(a, b, c) (((c) & (a)) | (~(c) & (b)))
#define PN_MD5R_G3(a, b, c) ((a) ^ (b) ^ (c))
#define PN_MD5R_G4(a, b, c) ((b) ^ ((a) | ~(c)))
#define PN_MD5R_F1(t) PN_MD5R_G1((t)[0], (t)[1], (t)[2])
#define PN_MD5R_F2(t) PN_MD5R_G2((t)[0], (t)[1], (t)[2])
#define PN_MD5R_F3(t) PN_MD5R_G3((t)[0], (t)[1], (t)[2])
#define PN_MD5R_F4(t) PN_MD5R_G4((t)[0], (t)[1], (t)[2])

/* md5rand(seed, key) of Appendix A: 16 steps (four per round function); the message words
 * the appendix leaves commented out are zero. */
PN_KFN void pn_md5r(const uint32_t *seed, uint32_t key, uint32_t *out)
{
    uint32_t d0 = seed[0] ^ key, d1 = seed[1] ^ key, d2 = seed[2] ^ key, d3 = seed[3] ^ key, t[4];
    out[0] = 0x01234567u;
    out[1] = 0x89ABCDEFu;
    out[2] = 0xFEDCBA98u;
    out[3] = 0x76543210u;
    t[0] = out[0];
    t[1] = out[1];
    t[2] = out[2];
    t[3] = out[3];
    pn_md5r_step(t, out, PN_MD5R_F1(t), d0, 0xD76AA478u, 7u);
    pn_md5r_step(t, out, PN_MD5R_F1(t), d1, 0xE8C7B757u, 12u);
    pn_md5r_step(t, out, PN_MD5R_F1(t), d2, 0x242070DBu, 17u);
    pn_md5r_step(t, out, PN_MD5R_F1(t), d3, 0xC1BDCEEFu, 22u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), d1, 0xF61E2562u, 5u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), 0u, 0xC040B341u, 9u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), 0u, 0x265E5A52u, 14u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), d0, 0xE9B6C7ABu, 20u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0xFFFA3942u, 4u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0x8771F681u, 11u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0x6D9D6122u, 16u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0xFDE5380Cu, 23u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), d0, 0xF4292244u, 6u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), 0u, 0x432AFF98u, 10u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), 0u, 0xAB9423A7u, 15u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), 0u, 0xFC93A039u, 21u);
}

/* The digest's first two words of pn_md5r({s0, s1, s2 + l, s3}, key) for the lanes
 * l = 0 .. PN_MD5R_LANES - 1 (the rays k .. k + 7 of a pixel): the same sixteen steps, each
 * a loop over the lanes with no test (the compilers vectorize it), the state's rotation
 * (tD = tD.yzwx) done by naming: a step with roles (A, B, C, D) = (t0, t1, t2, t3) writes
 * its new t3 into A, and the next step's roles are (B, C, D, A). The digest's other two
 * words, which the samples do not read, are not kept. tests/test_mcsm.c checks every lane
 * against pn_md5r. */
#define PN_MD5R_LANES 8u
#define PN_MD5R_LSTEP(G, A, B, C, D, M, K, S)                                  \
    for (l = 0; l < PN_MD5R_LANES; l++) {                                      \
        uint32_t r_ = A[l] + G(A[l], B[l], C[l]) + (M) + (K);                  \
        A[l] = B[l] + ((r_ << (S)) + (r_ >> (32u - (S))));                      \
        g0[l] += B[l];                                                         \
        g1[l] += C[l];                                                         \
    }
PN_KFN void pn_md5r_lanes(uint32_t s0, uint32_t s1, uint32_t s2, uint32_t s3, uint32_t key, uint32_t *g0,
                          uint32_t *g1)
{
    uint32_t d0 = s0 ^ key, d1 = s1 ^ key, d3 = s3 ^ key, d2[PN_MD5R_LANES], A[PN_MD5R_LANES], B[PN_MD5R_LANES];
    uint32_t C[PN_MD5R_LANES], D[PN_MD5R_LANES], l;
    (void)D;
    for (l = 0; l < PN_MD5R_LANES; l++) {
        d2[l] = (s2 + l) ^ key;
        A[l] = 0x01234567u;
        B[l] = 0x89ABCDEFu;
        C[l] = 0xFEDCBA98u;
        D[l] = 0x76543210u;
        g0[l] = 0x01234567u;
        g1[l] = 0x89ABCDEFu;
    }
    PN_MD5R_LSTEP(PN_MD5R_G1, A, B, C, D, d0, 0xD76AA478u, 7u)
    PN_MD5R_LSTEP(PN_MD5R_G1, B, C, D, A, d1, 0xE8C7B757u, 12u)
    PN_MD5R_LSTEP(PN_MD5R_G1, C, D, A, B, d2[l], 0x242070DBu, 17u)
    PN_MD5R_LSTEP(PN_MD5R_G1, D, A, B, C, d3, 0xC1BDCEEFu, 22u)
    PN_MD5R_LSTEP(PN_MD5R_G2, A, B, C, D, d1, 0xF61E2562u, 5u)
    PN_MD5R_LSTEP(PN_MD5R_G2, B, C, D, A, 0u, 0xC040B341u, 9u)
    PN_MD5R_LSTEP(PN_MD5R_G2, C, D, A, B, 0u, 0x265E5A52u, 14u)
    PN_MD5R_LSTEP(PN_MD5R_G2, D, A, B, C, d0, 0xE9B6C7ABu, 20u)
    PN_MD5R_LSTEP(PN_MD5R_G3, A, B, C, D, 0u, 0xFFFA3942u, 4u)
    PN_MD5R_LSTEP(PN_MD5R_G3, B, C, D, A, 0u, 0x8771F681u, 11u)
    PN_MD5R_LSTEP(PN_MD5R_G3, C, D, A, B, 0u, 0x6D9D6122u, 16u)
    PN_MD5R_LSTEP(PN_MD5R_G3, D, A, B, C, 0u, 0xFDE5380Cu, 23u)
    PN_MD5R_LSTEP(PN_MD5R_G4, A, B, C, D, d0, 0xF4292244u, 6u)
    PN_MD5R_LSTEP(PN_MD5R_G4, B, C, D, A, 0u, 0x432AFF98u, 10u)
    PN_MD5R_LSTEP(PN_MD5R_G4, C, D, A, B, 0u, 0xAB9423A7u, 15u)
    PN_MD5R_LSTEP(PN_MD5R_G4, D, A, B, C, 0u, 0xFC93A039u, 21u)
}
#undef PN_MD5R_LSTEP

/* The seed's last word of every ray's hash. */
#define PN_MC_SEED3 0x9E3779B9u

/* Jittered sample of ray (i, j) of the n x n grid from its hash's first two words h0, h1:
 * light coordinates (a, b) in [-1, 1)^2 (the light point c + a U + b V), 24 bits of each
 * word converted exactly. */
PN_KFN void pn_mc_jitter(uint32_t i, uint32_t j, uint32_t n, uint32_t h0, uint32_t h1, float *a, float *b)
{
    *a = 2.0f * (((float)i + (float)(h0 >> 8) * 5.9604644775390625e-8f) / (float)n) - 1.0f;
    *b = 2.0f * (((float)j + (float)(h1 >> 8) * 5.9604644775390625e-8f) / (float)n) - 1.0f;
}

/* Jittered sample of ray (i, j) of the n x n grid for pixel (x, y): pn_md5r seeded by
 * {x, y, j n + i, PN_MC_SEED3} and keyed by the frame key. (The pixel pass draws eight rays'
 * hashes at once, pn_md5r_lanes.) */
PN_KFN void pn_mc_sample(uint32_t x, uint32_t y, uint32_t i, uint32_t j, uint32_t n, uint32_t key, float *a, float *b)
{
    uint32_t seed[4], h[4];
    seed[0] = x;
    seed[1] = y;
    seed[2] = j * n + i;
    seed[3] = PN_MC_SEED3;
    pn_md5r(seed, key, h);
    pn_mc_jitter(i, j, n, h[0], h[1], a, b);
}

/* ---- Layers ------------------------------------------------------------------------------ */

/* Texel row y of level 0 of view v emptied: near +inf, far -inf. */
PN_KFN void pn_mc_clear_row(const pn_kview *v, uint32_t y, PN_GLOBAL float *nb)
{
    uint32_t x;
    for (x = 0; x < v->width; x++) {
        PN_GLOBAL float *T = nb + ((size_t)y * v->width + x) * PN_NB_MM;
        T[0] = PN_KINF;
        T[1] = -PN_KINF;
    }
}

/* The layers' rows pass for group g of the n triangles (pn_raster_rows_group): a
 * receiver-only triangle covers nothing; a small one puts its fragments into level 0 here,
 * as the band would (pn_raster_tri_setup's plane, pn_raster_axial, the same centres), by
 * atomic min and max, and is then drawn by no band: set up once, not again in every band
 * it meets (at 512², half of CAD's band set-ups and most of the dragon's: its bands' work
 * went from 132 M to 20 M instructions). rows[t]: what the bands draw of t. */
PN_KFN void pn_mc_rows(const pn_kview *v, const pn_kmc *mc, PN_CONST float *tris, PN_CONST uint8_t *flags, uint32_t n,
                       uint32_t g, PN_GLOBAL uint32_t *rows, PN_GLOBAL float *nb)
{
    uint32_t r[PN_RASTER_GROUP], t0 = g * PN_RASTER_GROUP, count = pn_kminu(PN_RASTER_GROUP, n - t0), i, k;
    pn_raster_small sm[PN_RASTER_GROUP];
    pn_raster_rows_group(v, tris, flags, t0, count, PN_TRI_RECEIVER, r, sm);
    for (i = 0; i < count; i++) {
        PN_CONST float *p = tris + (size_t)(t0 + i) * 9u;
        pn_v3 nv;
        float nA;
        if (r[i] == PN_RASTER_EMPTY || sm[i].w == 0) {
            rows[t0 + i] = r[i];
            continue;
        }
        rows[t0 + i] = PN_RASTER_EMPTY;
        nA = pn_raster_plane(v, pn_v3_make(p[0], p[1], p[2]), pn_v3_make(p[3], p[4], p[5]), pn_v3_make(p[6], p[7], p[8]),
                             &nv);
        for (k = 0; k < PN_RASTER_ROWS_TEST; k++) {
            uint32_t x = (uint32_t)(sm[i].x0 + (int32_t)k % sm[i].w), y = (uint32_t)(sm[i].y0 + (int32_t)k / sm[i].w);
            PN_GLOBAL int32_t *T;
            float z;
            if (!(sm[i].mask & (1u << k)) || !pn_raster_axial(v, nv, nA, x, y, &z)) continue;
            z -= mc->d;
            if (!(z > 0.0f)) continue;
            T = (PN_GLOBAL int32_t *)(nb + ((size_t)y * v->width + x) * PN_NB_MM);
            pn_katomic_imin(T, (int32_t)pn_kfbits(z)); /* near: the layers hold z > 0 or +-inf */
            pn_katomic_imax(T + 1, (int32_t)pn_kfbits(z));
        }
    }
}

/* Band `band` of PN_RASTER_BAND texel rows of level 0 (emptied, and holding the small
 * triangles' fragments, pn_mc_rows): every fragment of every other occluder (the band
 * walk's, pn_raster.h) in front of the light plane takes part in its texel's near and far;
 * then max near := near, and the texel is stored as the N-buffer's (near negated). */
PN_KFN void pn_mc_band(const pn_kview *v, const pn_kmc *mc, PN_CONST float *tris, PN_CONST uint8_t *flags,
                       PN_CONST uint32_t *rows, PN_CONST uint32_t *chunks, PN_CONST uint32_t *index, uint32_t tri_n,
                       uint32_t band, PN_GLOBAL float *nb)
{
    uint32_t y0 = band * PN_RASTER_BAND, y1 = y0 + PN_RASTER_BAND - 1u, t, y, x;
    pn_band_walk bw;
    if (y1 >= v->height) y1 = v->height - 1u;
    pn_band_walk_begin(&bw, tri_n);
    while (pn_band_next(chunks, index, y0, y1, &bw, &t)) {
        pn_raster_tri rt;
        if (flags[t] & PN_TRI_RECEIVER) continue;
        if (!pn_raster_tri_setup(v, tris, rows, t, y0, y1, &rt)) continue;
        for (y = rt.y0; y <= rt.y1; y++) {
            int32_t xi, xa = rt.x0, xb = rt.x1;
            int run = pn_raster_span(&rt, y, &xa, &xb);
            for (xi = xa; xi <= xb; xi++) {
                float z;
                PN_GLOBAL float *T;
                if (!pn_raster_tri_axial(v, &rt, run, (uint32_t)xi, y, &z)) continue;
                z -= mc->d;
                if (!(z > 0.0f)) continue;
                T = nb + ((size_t)y * v->width + (uint32_t)xi) * PN_NB_MM;
                T[0] = pn_kminf(T[0], z);
                T[1] = pn_kmaxf(T[1], z);
            }
        }
    }
    for (y = y0; y <= y1; y++)
        for (x = 0; x < v->width; x++) {
            PN_GLOBAL float *T = nb + ((size_t)y * v->width + x) * PN_NB_MM;
            T[2] = T[0];
            T[0] = -T[0]; /* stored as the N-buffer holds it (pn_nbuffer.h) */
        }
}

/* ---- One pixel's rays ----------------------------------------------------------------------- */

/* What the per-pixel work reads. */
typedef struct pn_mc_ctx {
    const pn_kview *view, *lv;
    const pn_klight *L;
    const pn_kmc *mc;
    PN_CONST float *nb;    /* N-buffer levels */
    PN_CONST float *depth; /* G-buffer depth (third layer) */
    float tx, ty;          /* the layers' window half-tans (pn_project_camera's factors) */
    float hw, hh;          /* half the layers' size in texels */
    pn_v3 corner[4];       /* the light's corners c -+ U -+ V (bit 0: +U, bit 1: +V) */
    uint32_t steps;        /* search steps so far */
    uint32_t capped;       /* searches stopped at the cap */
} pn_mc_ctx;

/* A ray in the light frame from (xs, ys, 0) to (xe, ye, ze). */
typedef struct pn_mc_ray {
    float xs, ys, xe, ye, ze;
} pn_mc_ray;

PN_KFN pn_v3 pn_mc_at(const pn_mc_ray *r, float t)
{
    return pn_v3_make(r->xs + t * (r->xe - r->xs), r->ys + t * (r->ye - r->ys), t * r->ze);
}

/* The per-pixel context over view, light view lv, light L, parameters mc, the N-buffer nb
 * and the G-buffer's depth. */
PN_KFN void pn_mc_ctx_init(pn_mc_ctx *m, const pn_kview *view, const pn_kview *lv, const pn_klight *L,
                           const pn_kmc *mc, PN_CONST float *nb, PN_CONST float *depth)
{
    uint32_t k;
    m->view = view;
    m->lv = lv;
    m->L = L;
    m->mc = mc;
    m->nb = nb;
    m->depth = depth;
    m->tx = lv->tan_half * lv->aspect;
    m->ty = lv->tan_half;
    m->hw = 0.5f * (float)lv->width;
    m->hh = 0.5f * (float)lv->height;
    m->steps = 0u;
    m->capped = 0u;
    for (k = 0; k < 4u; k++)
        m->corner[k] = pn_v3_add(pn_v3_make(L->c[0], L->c[1], L->c[2]),
                                 pn_v3_add(pn_v3_scale(pn_v3_make(L->U[0], L->U[1], L->U[2]), (k & 1u) ? 1.0f : -1.0f),
                                           pn_v3_scale(pn_v3_make(L->V[0], L->V[1], L->V[2]), (k & 2u) ? 1.0f : -1.0f)));
}

/* Image of a light-frame point in the layers, continuous texel coordinates:
 * pn_project_camera of (p.x, p.y, p.z + d) in lv, the same operations on factors
 * computed once. */
PN_KFN void pn_mc_proj(const pn_mc_ctx *m, pn_v3 p, float *px, float *py)
{
    float z = p.z + m->mc->d;
    *px = (p.x / (z * m->tx) + 1.0f) * m->hw;
    *py = (1.0f - p.y / (z * m->ty)) * m->hh;
}

/* Level-0 texel holding a light-frame point (clamped to the map), as stored (its bounds:
 * pn_nb_mm_get); *outside: the point's image lies beyond the map (the window left it out:
 * nothing is known there). */
PN_KFN uint32_t pn_mc_texel_at(const pn_mc_ctx *m, float px, float py, int *outside)
{
    float R = (float)m->mc->res;
    int32_t last = (int32_t)m->mc->res - 1;
    *outside = !((px >= 0.0f) & (py >= 0.0f) & (px < R) & (py < R));
    return ((uint32_t)pn_kfloor_clamp(py, 0, last) * m->mc->res + (uint32_t)pn_kfloor_clamp(px, 0, last)) * PN_NB_MM;
}
PN_KFN PN_CONST float *pn_mc_texel_img(const pn_mc_ctx *m, float px, float py, int *outside)
{
    return m->nb + pn_mc_texel_at(m, px, py, outside);
}
PN_KFN PN_CONST float *pn_mc_texel(const pn_mc_ctx *m, pn_v3 p, int *outside)
{
    float px, py;
    pn_mc_proj(m, p, &px, &py);
    return pn_mc_texel_img(m, px, py, outside);
}

/* Third layer: whether the light-frame point p is seen from the eye (in front of the
 * G-buffer's depth at its pixel, or over the background): empty space. */
PN_KFN int pn_mc_seen(const pn_mc_ctx *m, pn_v3 p)
{
    const pn_kview *v = m->view;
    pn_v3 X = pn_v3_make(m->L->c[0] + p.x * m->lv->r[0] + p.y * m->lv->u[0] + p.z * m->lv->f[0],
                         m->L->c[1] + p.x * m->lv->r[1] + p.y * m->lv->u[1] + p.z * m->lv->f[1],
                         m->L->c[2] + p.x * m->lv->r[2] + p.y * m->lv->u[2] + p.z * m->lv->f[2]);
    pn_v3 cam = pn_to_camera(v, X), rel;
    float px, py, dd;
    uint32_t ix, iy;
    if (!(cam.z > v->znear)) return 0;
    pn_project_camera(v, cam, &px, &py);
    if (!(px >= 0.0f && py >= 0.0f && px < (float)v->width && py < (float)v->height)) return 0;
    ix = (uint32_t)pn_kfloor_clamp(px, 0, (int32_t)v->width - 1);
    iy = (uint32_t)pn_kfloor_clamp(py, 0, (int32_t)v->height - 1);
    dd = m->depth[(size_t)iy * v->width + ix];
    rel = pn_v3_sub(X, pn_view_eye(v));
    return pn_v3_dot(rel, rel) < dd * dd * 0.9998f;
}

/* Where a point stands against its texel's interval. */
#define PN_MC_FRONT 0
#define PN_MC_INSIDE 1
#define PN_MC_BEHIND 2
/* ...of the level-0 texel at offset `at` (pn_mc_texel_at; out: beyond the map) */
PN_KFN int pn_mc_state_at(const pn_mc_ctx *m, pn_v3 p, uint32_t at, int out)
{
    float T[PN_NB_MM];
    pn_nb_mm_get(m->nb + at, T);
    if (out) return PN_MC_FRONT;
    if (m->mc->layers == 1u) return p.z >= T[0] ? PN_MC_INSIDE : PN_MC_FRONT;
    if (p.z < T[0]) return PN_MC_FRONT;
    if (p.z > T[1]) return PN_MC_BEHIND;
    if (m->mc->layers == 3u && pn_mc_seen(m, p)) return PN_MC_FRONT;
    return PN_MC_INSIDE;
}
/* ...of the texel holding image (px, py) */
PN_KFN int pn_mc_state_img(const pn_mc_ctx *m, pn_v3 p, float px, float py)
{
    int out;
    uint32_t at = pn_mc_texel_at(m, px, py, &out);
    return pn_mc_state_at(m, p, at, out);
}
PN_KFN int pn_mc_state(const pn_mc_ctx *m, pn_v3 p)
{
    float px, py;
    pn_mc_proj(m, p, &px, &py);
    return pn_mc_state_img(m, p, px, py);
}

PN_KFN int pn_mc_same_texel(const pn_mc_ctx *m, pn_v3 a, pn_v3 b)
{
    int oa, ob;
    return pn_mc_texel(m, a, &oa) == pn_mc_texel(m, b, &ob) && !oa && !ob;
}

/* Linear search over [t0, t1] (§3.3): 1 when blocked. */
PN_KFN int pn_mc_linear(pn_mc_ctx *m, const pn_mc_ray *r, float t0, float t1)
{
    float ax, ay, bx, by, w0 = t0 * r->ze + m->mc->d, w1 = t1 * r->ze + m->mc->d, tp = t0;
    uint32_t n, i, k;
    int sp = PN_MC_FRONT;
    pn_mc_proj(m, pn_mc_at(r, t0), &ax, &ay);
    pn_mc_proj(m, pn_mc_at(r, t1), &bx, &by);
    n = (uint32_t)pn_kceil_clamp(pn_kmaxf(pn_kfabs(bx - ax), pn_kfabs(by - ay)), 1, (int32_t)PN_MC_STEP_CAP(m->mc->res));
    for (i = 0; i <= n; i++) {
        /* Texel-uniform steps: the fraction q of the image segment is the fraction
         * q w0 / (q w0 + (1 - q) w1) of the ray (w: depth from the centre of projection). */
        float q = (float)i / (float)n, den = q * w0 + (1.0f - q) * w1;
        float t = den > 0.0f ? t0 + (t1 - t0) * (q * w0 / den) : t0 + (t1 - t0) * q;
        int s = pn_mc_state(m, pn_mc_at(r, t));
        m->steps++;
        if (s == PN_MC_INSIDE) return 1;
        if (i > 0u && s != sp) {
            /* Refine the transition (in front <-> behind). */
            float ta = tp, tb = t;
            for (k = 0; k < PN_MC_BISECT; k++) {
                float tm = 0.5f * (ta + tb);
                int sm = pn_mc_state(m, pn_mc_at(r, tm));
                m->steps++;
                if (sm == PN_MC_INSIDE) return 1;
                if (sm == sp)
                    ta = tm;
                else
                    tb = tm;
            }
            if (sp == PN_MC_FRONT && pn_mc_same_texel(m, pn_mc_at(r, ta), pn_mc_at(r, tb))) return 1;
        }
        sp = s;
        tp = t;
    }
    return 0;
}

/* The ray parameter where its image crosses texel column X (row Y): the image's x is
 * (x / ((z + d) tx) + 1) res / 2 and y is (1 - y / ((z + d) ty)) res / 2. +inf if never. */
PN_KFN float pn_mc_t_col(const pn_mc_ctx *m, const pn_mc_ray *r, float X)
{
    float k = (2.0f * X / (float)m->mc->res - 1.0f) * m->tx, den = (r->xe - r->xs) - k * r->ze;
    return den != 0.0f ? (k * m->mc->d - r->xs) / den : PN_KINF;
}
PN_KFN float pn_mc_t_row(const pn_mc_ctx *m, const pn_mc_ray *r, float Y)
{
    float k = (1.0f - 2.0f * Y / (float)m->mc->res) * m->ty, den = (r->ye - r->ys) - k * r->ze;
    return den != 0.0f ? (k * m->mc->d - r->ys) / den : PN_KINF;
}

/* Hierarchical search over [t0, t1] (Algorithm 2): 1 when blocked. */
PN_KFN int pn_mc_hier(pn_mc_ctx *m, const pn_mc_ray *r, float t0, float t1)
{
    const pn_kmc *mc = m->mc;
    float ax, ay, bx, by, dx, dy, t = t0;
    uint32_t l = 0u, iter, cap = PN_MC_STEP_CAP(mc->res);
    pn_mc_proj(m, pn_mc_at(r, t0), &ax, &ay);
    pn_mc_proj(m, pn_mc_at(r, t1), &bx, &by);
    dx = bx - ax;
    dy = by - ay;
    /* One level below a box that holds the whole image (the early-out looked that up). */
    while (l + 1u < mc->levels && (float)(1u << l) < pn_kmaxf(pn_kfabs(dx), pn_kfabs(dy))) l++;
    if (l > 0u) l--;
    if (!(t0 < t1)) return pn_mc_state(m, pn_mc_at(r, t0)) == PN_MC_INSIDE; /* one point */
    for (iter = 0; iter < cap; iter++) {
        float px, py, te, zlo, zhi, step, v[PN_NB_MM];
        int32_t B, X0, Y0;
        int hit;
        if (!(t < t1)) return 0;
        pn_mc_proj(m, pn_mc_at(r, t), &px, &py);
        B = 1 << l;
        /* The box of side B holding the current point and reaching toward the ray's end. */
        X0 = dx >= 0.0f ? pn_kfloor_clamp(px, -(1 << 24), 1 << 24) : pn_kceil_clamp(px, -(1 << 24), 1 << 24) - B;
        Y0 = dy >= 0.0f ? pn_kfloor_clamp(py, -(1 << 24), 1 << 24) : pn_kceil_clamp(py, -(1 << 24), 1 << 24) - B;
        /* Where the ray leaves the box. A point rounded onto the box's far side (its exit
         * not after it) belongs to the next box along that axis; if rounding still leaves
         * no exit after it, the search moves on by a step that float can represent. */
        step = pn_kmaxf((t1 - t0) * PN_MC_T_STEP, t * PN_MC_T_SLACK);
        te = t1;
        if (dx != 0.0f) {
            float xb = (float)(dx > 0.0f ? X0 + B : X0), tc = pn_mc_t_col(m, r, xb);
            if (!(tc > t) && pn_kfabs(px - xb) < PN_MC_ON_EDGE) {
                X0 += dx > 0.0f ? 1 : -1;
                tc = pn_mc_t_col(m, r, (float)(dx > 0.0f ? X0 + B : X0));
            } else if (!(tc > t)) {
                tc = PN_KINF; /* the image never reaches that side (it tends to a vanishing point) */
            }
            te = pn_kminf(te, tc > t ? tc : t + step);
        }
        if (dy != 0.0f) {
            float yb = (float)(dy > 0.0f ? Y0 + B : Y0), tr = pn_mc_t_row(m, r, yb);
            if (!(tr > t) && pn_kfabs(py - yb) < PN_MC_ON_EDGE) {
                Y0 += dy > 0.0f ? 1 : -1;
                tr = pn_mc_t_row(m, r, (float)(dy > 0.0f ? Y0 + B : Y0));
            } else if (!(tr > t)) {
                tr = PN_KINF;
            }
            te = pn_kminf(te, tr > t ? tr : t + step);
        }
        pn_nb_mm_box(m->nb, mc->res, l, X0, Y0, v);
        m->steps++;
        zlo = t * r->ze;
        zhi = te * r->ze;
        hit = mc->layers == 1u ? zhi >= v[0] : (zhi >= v[0] && zlo <= v[1]);
        if (hit && l == 0u && (X0 < 0 || Y0 < 0 || X0 >= (int32_t)mc->res || Y0 >= (int32_t)mc->res))
            hit = 0; /* a texel beyond the map: nothing is known there */
        if (hit) {
            if (l == 0u) {
                if (mc->layers == 3u) {
                    float a = pn_kmaxf(t, v[0] / r->ze), b = pn_kminf(te, v[1] / r->ze);
                    if (pn_mc_seen(m, pn_mc_at(r, 0.5f * (a + b)))) {
                        t = te;
                        if (l + 1u < mc->levels) l++;
                        continue;
                    }
                }
                return 1;
            }
            /* No point of the ray before depth min near can be inside. */
            t = pn_kmaxf(t, v[0] / r->ze * (1.0f - PN_MC_T_SLACK));
            l--;
        } else {
            t = te;
            if (l + 1u < mc->levels) l++;
        }
    }
    m->capped++;
    return 0;
}

/* Bounds of the layers over the texel box around two image points (one texel of margin
 * for rounding). Texels beyond the map are empty (the window holds every occluder): they
 * leave the smallest near and largest far depths as they are and make the largest near
 * depth +inf, as an empty texel of the map does. pn_mc_region_at: where the lookup reads
 * (pn_nb_mm_rect_at's boxes) and whether the box reaches beyond the map. The image
 * coordinates are clamped to [-(res + 2), res + 2] before their conversion: a side beyond
 * the map only counts as beyond it (*beyond compares with 0 and res, pn_nb_mm_rect_at
 * clamps to [0, res], a box wholly beyond is empty either way), so every bound past res + 1
 * gives the same lookup; one the compiler cannot fold to a constant keeps GCC's loop over
 * eight rays vectorized (with constant bounds it keeps a branch there). */
PN_KFN uint32_t pn_mc_region_at(const pn_mc_ctx *m, float ax, float ay, float bx, float by, uint32_t *at, int *beyond)
{
    int32_t R = (int32_t)m->mc->res, lim = R + 2;
    int32_t x0 = pn_kfloor_clamp(pn_kminf(ax, bx), -lim, lim) - 1, y0 = pn_kfloor_clamp(pn_kminf(ay, by), -lim, lim) - 1;
    int32_t x1 = pn_kceil_clamp(pn_kmaxf(ax, bx), -lim, lim) + 1, y1 = pn_kceil_clamp(pn_kmaxf(ay, by), -lim, lim) + 1;
    *beyond = (x0 < 0) | (y0 < 0) | (x1 > R) | (y1 > R);
    return pn_nb_mm_rect_at(m->mc->res, m->mc->levels, x0, y0, x1, y1, at);
}
/* The bounds of a region whose boxes pn_mc_region_at gave. */
PN_KFN void pn_mc_region_get(const pn_mc_ctx *m, const uint32_t *at, uint32_t n, int beyond, float *v)
{
    pn_nb_mm_rect_get(m->nb, at, n, v);
    if (beyond) v[2] = PN_KINF;
}
PN_KFN void pn_mc_region(const pn_mc_ctx *m, float ax, float ay, float bx, float by, float *v)
{
    uint32_t at[4], n;
    int beyond;
    n = pn_mc_region_at(m, ax, ay, bx, by, at, &beyond);
    pn_mc_region_get(m, at, n, beyond, v);
}

/* The box, in continuous texel coordinates b = {x0, y0, x1, y1}, that the images of the
 * rays from every point of the light to the light-frame point E (image ex, ey) stay in from
 * depth zb on (0 <= zb < E.z): eq. 3.3's region, the light's section at zb, sfac
 * (ze - zb) / (ze (zb + d)) by sfac_y (ze - zb) / (ze (zb + d)) texels around the image of
 * E's segment to the light centre at that depth, and E's image. A ray's image is a segment
 * from its point at zb to E's image, so the rays fill the hull of the two. The section
 * holds E's image when E lies in eq. 3.1's frustum (|E.x| / (ze + d) <= ha / d, and so for
 * y); an origin the window had to leave out (beyond PN_LVIEW_TAN_MAX) does not, and its
 * image widens the box. The two sides differ: the window fitted to the occluders narrows
 * tx and ty apart (one side for both let rays out of a region: 8 of bunny's pixels at
 * 512x512, one layer, lit where its rays are blocked; test_mcsm checks the box over random
 * windows and rays). */
PN_KFN void pn_mc_reach(const pn_mc_ctx *m, pn_v3 E, float ex, float ey, float zb, float *b)
{
    const pn_kmc *mc = m->mc;
    float ze = E.z, den = ze * (zb + mc->d), sx = mc->sfac * (ze - zb) / den, sy = mc->sfac_y * (ze - zb) / den;
    float cx, cy, fr = zb / ze;
    pn_mc_proj(m, pn_v3_make(E.x * fr, E.y * fr, zb), &cx, &cy);
    b[0] = pn_kminf(cx - 0.5f * sx, ex);
    b[1] = pn_kminf(cy - 0.5f * sy, ey);
    b[2] = pn_kmaxf(cx + 0.5f * sx, ex);
    b[3] = pn_kmaxf(cy + 0.5f * sy, ey);
}

/* Narrows [t0, t1] to the part of ray r whose image lies within the map widened by
 * PN_MC_CLIP_TEXELS on each side: beyond the map lies no occluder (the window holds their
 * box), so the searches need not walk there. Per side, x(t) - k (t z_E + d) <= 0 with
 * k = +-tx (+-ty) is linear in t. Empty: t0 > t1. */
PN_KFN void pn_mc_clip_side(float a, float b, float *t0, float *t1)
{
    /* Selects, not branches (the pixel pass sets up eight rays in one loop the compilers
     * vectorize): b > 0 bounds t1, b < 0 bounds t0, and b = 0 (or NaN) with a > 0 leaves
     * nothing. The quotient is computed on every path and used on the first two. */
    float q = -a / b, lo = pn_kmaxf(*t0, q), hi = pn_kminf(*t1, q);
    int pos = b > 0.0f, neg = b < 0.0f, shut = !pos & !neg & (a > 0.0f);
    *t1 = pos ? hi : *t1;
    *t0 = neg ? lo : (shut ? PN_KINF : *t0);
}
PN_KFN void pn_mc_clip(const pn_mc_ctx *m, const pn_mc_ray *r, float *t0, float *t1)
{
    float g = 1.0f + 2.0f * PN_MC_CLIP_TEXELS / (float)m->mc->res, kx = m->tx * g, ky = m->ty * g, d = m->mc->d;
    float dx = r->xe - r->xs, dy = r->ye - r->ys;
    pn_mc_clip_side(r->xs - kx * d, dx - kx * r->ze, t0, t1);
    pn_mc_clip_side(-r->xs - kx * d, -dx - kx * r->ze, t0, t1);
    pn_mc_clip_side(r->ys - ky * d, dy - ky * r->ze, t0, t1);
    pn_mc_clip_side(-r->ys - ky * d, -dy - ky * r->ze, t0, t1);
}

/* The adaptive bias of eq. 3.2 for an origin at light depth ze with unit normal nrm and
 * toc, the origin to the light centre: half a texel's diagonal at the origin's depth
 * (bias_k (ze + d)), over the cosine of the angle to the light, at least PN_MC_COS_MIN. */
PN_KFN float pn_mc_bias(const pn_kmc *mc, pn_v3 nrm, pn_v3 toc, float ze)
{
    float lt, cosv;
    if (mc->flags & PN_MC_F_NO_BIAS) return 0.0f;
    lt = pn_ksqrt(pn_v3_dot(toc, toc));
    cosv = lt > 0.0f ? pn_v3_dot(nrm, toc) / lt : 1.0f;
    return mc->bias_k * (ze + mc->d) / pn_kmaxf(cosv, PN_MC_COS_MIN);
}

/* Pixel classes (the counters: class c counts in word c - 1). A pixel the classification
 * left potentially in penumbra is then told apart by what its rays found: some blocked and
 * some not (PENUMBRA), none blocked by the layers (PENUMBRA_OPEN: the classification could
 * have called it lit; its visibility is the horizon's alone), or samples in front of its
 * surface and every one of them blocked by the layers (PENUMBRA_SHUT). The last two measure how tight the classification is (§3.6:
 * "two iterations are generally sufficient to produce a tight bound around penumbrae"). */
#define PN_MC_CLASS_NONE 0u
#define PN_MC_CLASS_LIT 1u
#define PN_MC_CLASS_UMBRA 2u
#define PN_MC_CLASS_PENUMBRA 3u
#define PN_MC_CLASS_PENUMBRA_OPEN 4u
#define PN_MC_CLASS_PENUMBRA_SHUT 5u

/* Pixels of a row that the classification first tests as one run (pn_mc_run). */
#define PN_MC_RUN 16u

/* 1: the pixel pass's ray lanes also compute where each ray's own region lies in the
 * N-buffer (pn_mc_region_at, eight rays in a loop of selects); 0: each ray that needs its
 * region computes it (pn_mc_region). The same lookups either way. The lanes pay where the
 * compiler vectorizes that loop, which takes 32-bit vector multiplies (SSE4.1, NEON): chess,
 * 512x512, callgrind: x86-64-v3 226.3 -> 218.8 M instructions with them; the baseline
 * x86-64 target (SSE2) 355.8 -> 385.9 M, every lane's region computed one by one. */
#ifndef PN_MC_LANE_REGIONS
#if defined(__SSE4_1__) || defined(__ARM_NEON)
#define PN_MC_LANE_REGIONS 1
#else
#define PN_MC_LANE_REGIONS 0
#endif
#endif

/* A G-buffer pixel as the pixel pass takes it (pn_mc_run). */
#define PN_MC_PX_NONE 0u     /* no surface: visibility 1 */
#define PN_MC_PX_NO_ORIGIN 1u /* no shadow-ray origin (pn_shadow_origin): visibility 0 */
#define PN_MC_PX_SURFACE 2u  /* the fields below hold */
#define PN_MC_PX_LIT 3u      /* a surface of a run found lit, facing the light centre, with the
                              * light's four corners in front of its plane: visibility 1, class
                              * lit (pn_mc_pixel's answer); no field below is set */
typedef struct pn_mc_px {
    pn_v3 nrm, O, E; /* unit normal, shadow-ray origin, O in the light frame */
    float ex, ey;    /* E's image, and */
    float b[4];      /* the classification's first region (pn_mc_reach at whole[0]): set
                      * when the classification looks at the pixel (faces, E beyond whole[0]) */
    uint32_t kind;   /* PN_MC_PX_* */
    uint32_t faces;  /* E in front of the light plane and the normal toward the light centre
                      * (else umbra before any classification, pn_mc_pixel) */
    uint32_t front;  /* the light's corners on the front side of its plane (0 .. 4) */
} pn_mc_px;

/* The run of count G-buffer pixels from pix on (ids, pos, nrm) into px[0 .. count), and
 * whether the classification may call every one lit at once. Each pixel that the
 * classification would look at has its first region, pn_mc_reach at the whole map's
 * nearest depth zb: the rays from every light point to it stay there from zb on. When no
 * occluder in the union of those regions is nearer than the farthest of their origins, no
 * ray of any of them meets a layer: each is lit, as its own first region would have told
 * (a region's lookup covers a superset of its box, pn_nb_mm_rect_at, and the union's can
 * miss part of one pixel's: that part holds none of the pixel's rays, so the pixel would
 * have traced them all unblocked, the same visibility). One lookup for the run instead of
 * one or two per lit pixel, most of a frame (chess, 512x512: the classification's 247,934
 * lookups become 84,290 and 16,384 runs'; its pass 6% fewer instructions, 11% less time).
 * Without the classification (point light, PN_MC_F_NO_CLASSIFY): 0. A surface of a lit run
 * that faces the light centre with the whole light in front of its plane comes back as
 * PN_MC_PX_LIT (most of a frame's pixels); the others get the fields pn_mc_pixel reads. */
PN_KFN int pn_mc_run(const pn_mc_ctx *m, PN_CONST uint32_t *ids, PN_CONST float *pos, PN_CONST float *nrm, size_t pix,
                     uint32_t count, pn_mc_px *px)
{
    const pn_kmc *mc = m->mc;
    const pn_klight *L = m->L;
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    float zb = mc->whole[0], zmax = 0.0f, u[4], q[PN_NB_MM];
    float Ox[PN_MC_RUN], Oy[PN_MC_RUN], Oz[PN_MC_RUN], Ex[PN_MC_RUN], Ey[PN_MC_RUN], Ez[PN_MC_RUN];
    float Nx[PN_MC_RUN], Ny[PN_MC_RUN], Nz[PN_MC_RUN];
    float ex[PN_MC_RUN], ey[PN_MC_RUN], b0[PN_MC_RUN], b1[PN_MC_RUN], b2[PN_MC_RUN], b3[PN_MC_RUN];
    int sees[PN_MC_RUN], faces[PN_MC_RUN], front[PN_MC_RUN], looks[PN_MC_RUN];
    uint32_t i, any = 0u;
    int lit;
    int classify = !(mc->flags & PN_MC_F_NO_CLASSIFY) && !L->is_point;
    /* Every pixel's origin, light-frame point, image and first region, in one loop with no
     * branch (the compilers vectorize it: seven divisions a pixel), whatever its kind; a
     * pixel with no surface has some point and normal in the G-buffer, whose results are
     * not read. */
    for (i = 0; i < count; i++) {
        pn_v3 n = pn_v3_load(nrm + (pix + i) * 3u), O, E;
        float b[4], x, y;
        sees[i] = pn_shadow_origin(pn_v3_load(pos + (pix + i) * 3u), n, L, &O);
        E = pn_lview_frame(m->lv, L, O);
        faces[i] = E.z > 0.0f && !(pn_v3_dot(n, pn_v3_sub(c, O)) < 0.0f);
        front[i] = (pn_v3_dot(pn_v3_sub(m->corner[0], O), n) > 0.0f) + (pn_v3_dot(pn_v3_sub(m->corner[1], O), n) > 0.0f) +
                   (pn_v3_dot(pn_v3_sub(m->corner[2], O), n) > 0.0f) + (pn_v3_dot(pn_v3_sub(m->corner[3], O), n) > 0.0f);
        pn_mc_proj(m, E, &x, &y);
        pn_mc_reach(m, E, x, y, zb, b);
        Nx[i] = n.x;
        Ny[i] = n.y;
        Nz[i] = n.z;
        Ox[i] = O.x;
        Oy[i] = O.y;
        Oz[i] = O.z;
        Ex[i] = E.x;
        Ey[i] = E.y;
        Ez[i] = E.z;
        ex[i] = x;
        ey[i] = y;
        b0[i] = b[0];
        b1[i] = b[1];
        b2[i] = b[2];
        b3[i] = b[3];
    }
    /* Each pixel's kind, and the union of the first regions the classification would look
     * at (a surface facing the light, beyond the whole map's nearest depth: else lit by that
     * alone), in pixel order. */
    u[0] = u[1] = PN_KINF;
    u[2] = u[3] = -PN_KINF;
    for (i = 0; i < count; i++) {
        px[i].kind = ids[pix + i] == 0xFFFFFFFFu ? PN_MC_PX_NONE /* PN_NO_PIXEL_TRIANGLE */
                                                 : (sees[i] ? PN_MC_PX_SURFACE : PN_MC_PX_NO_ORIGIN);
        looks[i] = px[i].kind == PN_MC_PX_SURFACE && classify && faces[i] && zb < Ez[i];
        if (!looks[i]) continue;
        u[0] = pn_kminf(u[0], b0[i]);
        u[1] = pn_kminf(u[1], b1[i]);
        u[2] = pn_kmaxf(u[2], b2[i]);
        u[3] = pn_kmaxf(u[3], b3[i]);
        zmax = pn_kmaxf(zmax, Ez[i]);
        any = 1u;
    }
    if (!classify) lit = 0;
    else if (!any) lit = 1;
    else {
        pn_mc_region(m, u[0], u[1], u[2], u[3], q);
        lit = !(pn_kmaxf(zb, q[0]) < zmax);
    }
    /* What pn_mc_pixel reads, for the surfaces it will see. */
    for (i = 0; i < count; i++) {
        pn_mc_px *p = px + i;
        if (p->kind != PN_MC_PX_SURFACE) continue;
        if (lit && faces[i] && front[i] == 4) {
            p->kind = PN_MC_PX_LIT;
            continue;
        }
        p->nrm = pn_v3_make(Nx[i], Ny[i], Nz[i]);
        p->O = pn_v3_make(Ox[i], Oy[i], Oz[i]);
        p->E = pn_v3_make(Ex[i], Ey[i], Ez[i]);
        p->front = (uint32_t)front[i];
        p->faces = (uint32_t)faces[i];
        if (!looks[i]) continue;
        p->ex = ex[i];
        p->ey = ey[i];
        p->b[0] = b0[i];
        p->b[1] = b1[i];
        p->b[2] = b2[i];
        p->b[3] = b3[i];
    }
    return lit;
}

/* The first two hash words of rays k .. of pixel (x, y) (n2 rays in all) into h0, h1 at
 * k % PN_MD5R_LANES: eight lanes at once, or the last ray alone (the ninth of 3x3: eight
 * lanes cost about what three single hashes do). The same words either way (test_mcsm). */
PN_KFN void pn_mc_hashes(uint32_t x, uint32_t y, uint32_t k, uint32_t n2, uint32_t key, uint32_t *h0, uint32_t *h1)
{
    uint32_t seed[4], h[4];
    if (n2 - k > 1u) {
        pn_md5r_lanes(x, y, k, PN_MC_SEED3, key, h0, h1);
        return;
    }
    seed[0] = x;
    seed[1] = y;
    seed[2] = k;
    seed[3] = PN_MC_SEED3;
    pn_md5r(seed, key, h);
    h0[0] = h[0];
    h1[0] = h[1];
}

/* Visibility of G-buffer pixel (x, y), a surface with a shadow-ray origin as pn_mc_run gave
 * it (p); run_lit: pn_mc_run said its run is lit. *cls: its class; *rays: rays searched. */
PN_KFN float pn_mc_pixel(pn_mc_ctx *m, uint32_t x, uint32_t y, const pn_mc_px *p, int run_lit, uint32_t *cls,
                         uint32_t *rays)
{
    const pn_kmc *mc = m->mc;
    const pn_klight *L = m->L;
    pn_v3 nrm = p->nrm, O = p->O, E = p->E;
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]), toc = pn_v3_sub(c, O);
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]), V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    /* q is set whenever it is read; GCC 12 for arm-none-eabi cannot tell and warns */
    float ze = E.z, bias = 0.0f, zlo = 0.0f, zhi = PN_KINF, q[PN_NB_MM] = {0.0f, 0.0f, 0.0f};
    uint32_t n = L->is_point ? 1u : mc->rays, i, j, k = 0u, open = 0u, ahead = 0u, h0[PN_MD5R_LANES], h1[PN_MD5R_LANES];
    int classify = !(mc->flags & PN_MC_F_NO_CLASSIFY);
    *rays = 0u;
    *cls = PN_MC_CLASS_PENUMBRA;
    /* A surface whose winding turns it away from the light centre is umbra: the thesis'
     * first early-out, "the surface normal faces opposite the ray", per fragment toward the
     * light centre (§3.7 allows it), which is what the exact algorithms' convention gives a
     * closed mesh (the normal turned toward the light puts the origin inside the solid,
     * whose own faces then block every sample). The layers cannot show a surface its own
     * back side, so without it such a face is lit through its own solid. Otherwise nrm
     * faces the light centre, and a ray toward a light point behind its plane is blocked
     * (invariant 6's horizon). An origin on or behind the light plane sees no light. */
    if (!p->faces) { /* pn_mc_run: !(E.z > 0) or the normal's dot with toc below 0 */
        *cls = PN_MC_CLASS_UMBRA;
        return 0.0f;
    }
    if (classify && !L->is_point && run_lit) {
        *cls = PN_MC_CLASS_LIT;
        n = 0u;
    } else if (classify && !L->is_point) {
        /* Penumbra classification (§3.6): the region every ray can reach from depth zb on
         * (pn_mc_reach), its smallest near depth the next zb, twice, from the whole map's. */
        uint32_t it;
        float zb = mc->whole[0], nz, b[4]; /* the whole map's, src/pn_mcsm.c */
        for (it = 0; it < 2u && zb < ze; it++) {
            /* the first region pn_mc_run's (it set it: the pixel faces, zb < ze here) */
            if (it == 0u) b[0] = p->b[0], b[1] = p->b[1], b[2] = p->b[2], b[3] = p->b[3];
            else pn_mc_reach(m, E, p->ex, p->ey, zb, b);
            pn_mc_region(m, b[0], b[1], b[2], b[3], q);
            nz = pn_kmaxf(zb, q[0]);
            if (nz == zb) break; /* zb stays: the next region would be this one */
            zb = nz;
        }
        if (!(zb < ze)) {
            *cls = PN_MC_CLASS_LIT;
            n = 0u; /* every ray unblocked but for the horizon (and no bias needed) */
        } else {
            bias = pn_mc_bias(mc, nrm, toc, ze);
            if (mc->layers <= 2u && ze - bias > q[2]) {
                *cls = PN_MC_CLASS_UMBRA;
                return 0.0f;
            }
            zlo = zb;
            if (mc->layers >= 2u) zhi = q[1];
        }
    } else {
        bias = pn_mc_bias(mc, nrm, toc, ze);
    }
    if (n == 0u) {
        /* Lit: only the horizon blocks. A light wholly in front of (behind) the surface
         * leaves every ray open (blocked): the sample points are convex combinations of the
         * corners. Otherwise the rays' light points, as they would be drawn. */
        uint32_t g = mc->rays, vis = 0u;
        if (p->front == 4u) return 1.0f; /* pn_mc_run counted the corners in front */
        if (p->front == 0u) return 0.0f;
        for (j = 0; j < g; j++)
            for (i = 0; i < g; i++, k++) {
                float a, b;
                pn_v3 S;
                if (k % PN_MD5R_LANES == 0u) pn_mc_hashes(x, y, k, g * g, mc->seed, h0, h1);
                pn_mc_jitter(i, j, g, h0[k % PN_MD5R_LANES], h1[k % PN_MD5R_LANES], &a, &b);
                S = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, a), pn_v3_scale(V, b)));
                vis += pn_v3_dot(pn_v3_sub(S, O), nrm) > 0.0f;
            }
        return (float)vis / (float)(g * g);
    }
    if (L->is_point) {
        /* One ray to the light's centre, and one texel holds it: a shadow-map test. */
        float len = pn_ksqrt(pn_v3_dot(pn_v3_sub(O, c), pn_v3_sub(O, c))), tend, zend, T[PN_NB_MM];
        pn_v3 Sl = pn_lview_frame(m->lv, L, c);
        pn_mc_ray r;
        int out, blocked;
        *cls = PN_MC_CLASS_PENUMBRA_OPEN; /* no sample blocked by a layer, on the two returns below */
        if (!(pn_v3_dot(toc, nrm) > 0.0f)) return 0.0f; /* behind P's own plane: no sample ahead */
        r.xs = Sl.x;
        r.ys = Sl.y;
        r.xe = E.x;
        r.ye = E.y;
        r.ze = ze;
        tend = len > bias ? 1.0f - bias / len : 0.0f;
        if (!(tend > 0.0f)) return 1.0f;
        zend = tend * ze;
        pn_nb_mm_get(pn_mc_texel(m, pn_mc_at(&r, tend), &out), T);
        blocked = !out && (mc->layers == 1u ? zend >= T[0] : zend >= T[0] && T[1] >= 0.0f);
        if (blocked && mc->layers == 3u) {
            float za = pn_kmaxf(T[0], 0.0f), zb2 = pn_kminf(T[1], zend);
            blocked = !pn_mc_seen(m, pn_mc_at(&r, 0.5f * (za + zb2) / ze));
        }
        *rays += 1u;
        m->steps++;
        *cls = blocked ? PN_MC_CLASS_PENUMBRA_SHUT : PN_MC_CLASS_PENUMBRA_OPEN;
        return blocked ? 0.0f : 1.0f;
    }
    for (k = 0; k < n * n; k += PN_MD5R_LANES) {
        /* Eight rays at a time: their set-up (sample, plane test, light-frame start, biased
         * end, the clip to the map, the images of the end and of the searched range's ends;
         * then where the end's texel, and with PN_MC_LANE_REGIONS the ray's own region, lie
         * in the N-buffer) in loops with no branch, which the compilers vectorize; then each
         * ray's lookups and search in order. Every ray's float operations are the ones it had
         * alone, in the same order. */
        uint32_t cnt = pn_kminu(PN_MD5R_LANES, n * n - k), l;
        uint32_t li[PN_MD5R_LANES], lj[PN_MD5R_LANES], eat[PN_MD5R_LANES];
        int ah[PN_MD5R_LANES], eout[PN_MD5R_LANES];
#if PN_MC_LANE_REGIONS
        uint32_t rn[PN_MD5R_LANES], ra[4][PN_MD5R_LANES]; /* box b of lane l's region at ra[b][l] */
        int rbey[PN_MD5R_LANES];
#endif
        float xs[PN_MD5R_LANES], ys[PN_MD5R_LANES], te[PN_MD5R_LANES], lt0[PN_MD5R_LANES], lt1[PN_MD5R_LANES];
        float epx[PN_MD5R_LANES], epy[PN_MD5R_LANES], ax[PN_MD5R_LANES], ay[PN_MD5R_LANES], bx[PN_MD5R_LANES],
            by[PN_MD5R_LANES];
        float t0s = zlo / ze * (1.0f - PN_MC_T_SLACK), t1s = zhi / ze * (1.0f + PN_MC_T_SLACK);
        pn_mc_hashes(x, y, k, n * n, mc->seed, h0, h1);
        for (l = 0, i = k % n, j = k / n; l < cnt; l++) {
            li[l] = i;
            lj[l] = j;
            if (++i == n) i = 0u, j++;
        }
        for (l = 0; l < cnt; l++) {
            float a, b, len, bl, tend, t0 = t0s, t1;
            pn_v3 S, Sl;
            pn_mc_ray r;
            pn_mc_jitter(li[l], lj[l], n, h0[l], h1[l], &a, &b);
            S = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, a), pn_v3_scale(V, b)));
            ah[l] = pn_v3_dot(pn_v3_sub(S, O), nrm) > 0.0f; /* else behind P's own plane */
            Sl = pn_lview_frame(m->lv, L, S);
            r.xs = Sl.x;
            r.ys = Sl.y;
            r.xe = E.x;
            r.ye = E.y;
            r.ze = ze;
            len = pn_ksqrt(pn_v3_dot(pn_v3_sub(O, S), pn_v3_sub(O, S)));
            bl = 1.0f - bias / len; /* on every path: a select, not a branch */
            tend = len > bias ? bl : 0.0f;
            t1 = pn_kminf(tend, t1s);
            pn_mc_clip(m, &r, &t0, &t1);
            pn_mc_proj(m, pn_mc_at(&r, tend), &epx[l], &epy[l]);
            pn_mc_proj(m, pn_mc_at(&r, t0), &ax[l], &ay[l]);
            pn_mc_proj(m, pn_mc_at(&r, t1), &bx[l], &by[l]);
            xs[l] = r.xs;
            ys[l] = r.ys;
            te[l] = tend;
            lt0[l] = t0;
            lt1[l] = t1;
        }
        for (l = 0; l < cnt; l++) {
            /* where the two lookups below read: the end's texel, the ray's own region (a
             * loop of its own: in the one above, GCC vectorizes neither) */
            eat[l] = pn_mc_texel_at(m, epx[l], epy[l], &eout[l]);
#if PN_MC_LANE_REGIONS
            {
                uint32_t at4[4], b;
                rn[l] = pn_mc_region_at(m, ax[l], ay[l], bx[l], by[l], at4, &rbey[l]);
                for (b = 0; b < 4u; b++) ra[b][l] = at4[b];
            }
#endif
        }
        for (l = 0; l < cnt; l++) {
            float t0 = lt0[l], t1 = lt1[l];
            pn_mc_ray r;
            if (!ah[l]) continue;
            ahead++;
            if (!(te[l] > 0.0f)) {
                open++;
                continue;
            }
            r.xs = xs[l];
            r.ys = ys[l];
            r.xe = E.x;
            r.ye = E.y;
            r.ze = ze;
            {
                /* The ray's end inside a texel's interval: blocked, with one lookup. Part of
                 * the model, not only an early-out: the searches walk [t0, t1) and leave out
                 * the end itself, and an end exactly on the edge of a solid texel (thin,
                 * 512x512: a ray whose image ends at x = 426.000) is blocked by this test
                 * and by no search step. */
                int st = pn_mc_state_at(m, pn_mc_at(&r, te[l]), eat[l], eout[l]);
                m->steps++;
                if (st == PN_MC_INSIDE) continue;
            }
            if (classify && t0 < t1) {
                /* The ray's own region (§3.7): nothing before its end, or shortened. */
#if PN_MC_LANE_REGIONS
                uint32_t at4[4], b;
                for (b = 0; b < 4u; b++) at4[b] = ra[b][l];
                pn_mc_region_get(m, at4, rn[l], rbey[l], q);
#else
                pn_mc_region(m, ax[l], ay[l], bx[l], by[l], q);
#endif
                m->steps++;
                t0 = pn_kmaxf(t0, q[0] / ze * (1.0f - PN_MC_T_SLACK));
                if (mc->layers >= 2u) t1 = pn_kminf(t1, q[1] / ze * (1.0f + PN_MC_T_SLACK));
            }
            if (!(t0 <= t1)) {
                open++;
                continue;
            }
            *rays += 1u;
            if (!(mc->search == PN_MC_S_LINEAR ? pn_mc_linear(m, &r, t0, t1) : pn_mc_hier(m, &r, t0, t1))) open++;
        }
    }
    /* open: the samples in front of P's plane (ahead) that no layer blocked */
    *cls = open == ahead ? PN_MC_CLASS_PENUMBRA_OPEN : (open == 0u ? PN_MC_CLASS_PENUMBRA_SHUT : PN_MC_CLASS_PENUMBRA);
    return (float)open / (float)(n * n);
}

/* ---- Blur ------------------------------------------------------------------------------------ */

/* Pixels of a row the blur takes at a time (pn_mc_blur_row). */
#define PN_MC_BLUR_RUN 64u

/* Tap q of one pixel of the blur (centre normal nc, depth dc, depth factor k; wi: the
 * tap's binomial weight), added to its sums: a tap in the image (in), not background, and
 * within PN_MC_BLUR_COS of the centre's normal (the thesis' "robust implementation": no
 * blur across a crease) adds w src[q] and w, w = wi / (1 + |depth[q] - dc| k); any other
 * adds +0 to each (the sums start at +0 and only grow: the same bytes as adding nothing). */
PN_KFN void pn_mc_blur_tap(float wi, size_t q, int in, float ncx, float ncy, float ncz, float dc, float k,
                           PN_CONST uint32_t *ids, PN_CONST float *depth, PN_CONST float *nrm, PN_CONST float *src,
                           float *sum, float *wsum)
{
    pn_v3 nq = pn_v3_load(nrm + q * 3u);
    /* & rather than &&: every load made (q is in the image), no branch on any of them */
    int inc = in & (ids[q] != 0xFFFFFFFFu) & (pn_v3_dot(pn_v3_make(ncx, ncy, ncz), nq) >= PN_MC_BLUR_COS);
    float w = wi / (1.0f + pn_kfabs(depth[q] - dc) * k), ws = w * src[q];
    *sum += inc ? ws : 0.0f;
    *wsum += inc ? w : 0.0f;
}

/* Row y of one direction of the separable blur (vertical: down the columns), src into dst.
 * A pixel's taps i = -r .. r in that order, each weighed by its binomial weight over
 * 1 + |depth difference| blur_depth / centre depth; its value sum / wsum, or its own for
 * background. Runs of PN_MC_BLUR_RUN pixels, tap by tap across the run, in loops with no
 * branch that the compilers vectorize (a tap's pixels are consecutive in memory but at the
 * row's two ends across, where the run takes the taps beyond the image as empty). A window
 * of one value v, 0 or 1, gives v: w v is w, or 0, so sum is wsum's own additions, or 0
 * (the centre tap counts, so wsum > 0); a run whose whole window is so is written v
 * without its sums. */
PN_KFN void pn_mc_blur_row(const pn_kmc *mc, uint32_t W, uint32_t H, uint32_t y, uint32_t vertical,
                           PN_CONST uint32_t *ids, PN_CONST float *depth, PN_CONST float *nrm, PN_CONST float *src,
                           PN_GLOBAL float *dst)
{
    int32_t r = (int32_t)mc->blur, i;
    uint32_t x0;
    for (x0 = 0; x0 < W; x0 += PN_MC_BLUR_RUN) {
        uint32_t n = pn_kminu(PN_MC_BLUR_RUN, W - x0), l;
        float sum[PN_MC_BLUR_RUN], wsum[PN_MC_BLUR_RUN], k[PN_MC_BLUR_RUN], dc[PN_MC_BLUR_RUN];
        float ncx[PN_MC_BLUR_RUN], ncy[PN_MC_BLUR_RUN], ncz[PN_MC_BLUR_RUN];
        size_t pix0 = (size_t)y * W + x0;
        for (l = 0; l < n; l++) {
            pn_v3 nc = pn_v3_load(nrm + (pix0 + l) * 3u);
            ncx[l] = nc.x;
            ncy[l] = nc.y;
            ncz[l] = nc.z;
            dc[l] = depth[pix0 + l];
            k[l] = mc->blur_depth / dc[l];
            sum[l] = 0.0f;
            wsum[l] = 0.0f;
        }
        {
            /* A run whose whole window holds one value v, 0 or 1 (background aside, no NaN
             * depth), and whose pixels all count their centre tap (k finite, the normal's
             * own test): every pixel gets v, which its sums would give (most of a frame:
             * lit and umbra regions; on a target without vector units this is most of the
             * blur's saving). Tests with &, no branch. */
            uint32_t u0 = 1u, u1 = 1u, ok = 1u;
            int32_t a, e;
            for (l = 0; l < n; l++) {
                uint32_t bg = ids[pix0 + l] == 0xFFFFFFFFu;
                pn_v3 nc = pn_v3_make(ncx[l], ncy[l], ncz[l]);
                ok &= bg | ((k[l] < PN_KINF) & (pn_v3_dot(nc, nc) >= PN_MC_BLUR_COS));
            }
            if (vertical) {
                for (i = -r; i <= r; i++) {
                    size_t base;
                    if ((int32_t)y + i < 0 || (int32_t)y + i >= (int32_t)H) continue;
                    base = (size_t)((int32_t)y + i) * W + x0;
                    for (l = 0; l < n; l++) {
                        size_t q = base + l;
                        uint32_t bg = ids[q] == 0xFFFFFFFFu, real = depth[q] == depth[q];
                        u0 &= bg | ((src[q] == 0.0f) & real);
                        u1 &= bg | ((src[q] == 1.0f) & real);
                    }
                }
            } else {
                a = pn_kmaxi((int32_t)x0 - r, 0);
                e = pn_kmini((int32_t)(x0 + n) + r, (int32_t)W);
                for (i = a; i < e; i++) {
                    size_t q = (size_t)y * W + (uint32_t)i;
                    uint32_t bg = ids[q] == 0xFFFFFFFFu, real = depth[q] == depth[q];
                    u0 &= bg | ((src[q] == 0.0f) & real);
                    u1 &= bg | ((src[q] == 1.0f) & real);
                }
            }
            if (ok & (u0 | u1)) {
                float v = u1 ? 1.0f : 0.0f; /* both: every pixel is background */
                for (l = 0; l < n; l++) dst[pix0 + l] = ids[pix0 + l] == 0xFFFFFFFFu ? src[pix0 + l] : v;
                continue;
            }
        }
        for (i = -r; i <= r; i++) {
            float wi = mc->blur_w[i < 0 ? -i : i];
            if (vertical) {
                size_t base;
                if ((int32_t)y + i < 0 || (int32_t)y + i >= (int32_t)H) continue; /* adds nothing */
                base = (size_t)((int32_t)y + i) * W + x0;
                for (l = 0; l < n; l++)
                    pn_mc_blur_tap(wi, base + l, 1, ncx[l], ncy[l], ncz[l], dc[l], k[l], ids, depth, nrm, src, &sum[l],
                                   &wsum[l]);
            } else if ((int32_t)x0 + i >= 0 && (int32_t)(x0 + n) + i <= (int32_t)W) {
                size_t base = (size_t)y * W + (size_t)((int32_t)x0 + i);
                for (l = 0; l < n; l++)
                    pn_mc_blur_tap(wi, base + l, 1, ncx[l], ncy[l], ncz[l], dc[l], k[l], ids, depth, nrm, src, &sum[l],
                                   &wsum[l]);
            } else {
                for (l = 0; l < n; l++) {
                    int32_t xx = (int32_t)(x0 + l) + i;
                    int in = xx >= 0 && xx < (int32_t)W;
                    pn_mc_blur_tap(wi, (size_t)y * W + (in ? (uint32_t)xx : x0 + l), in, ncx[l], ncy[l], ncz[l], dc[l],
                                   k[l], ids, depth, nrm, src, &sum[l], &wsum[l]);
                }
            }
        }
        for (l = 0; l < n; l++) dst[pix0 + l] = ids[pix0 + l] == 0xFFFFFFFFu ? src[pix0 + l] : sum[l] / wsum[l];
    }
}

#endif
