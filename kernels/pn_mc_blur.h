/* pn_mc_blur.h - Monte Carlo shadow maps, the depth- and normal-aware blur. Part of pn_mcsm.h, which
 * includes it after the constants it uses; see there. */
#ifndef PN_MC_BLUR_H
#define PN_MC_BLUR_H

/* ---- Blur ------------------------------------------------------------------------------------ */

/* Pixels of a row the blur takes at a time (pn_mc_blur_row). */
#define PN_MC_BLUR_RUN 64u

/* Tap q of one pixel of the blur (centre normal nc, depth dc, depth factor k, value vc; wi:
 * the tap's binomial weight), added to its sums: a tap in the image (in), not background,
 * within PN_MC_BLUR_COS of the centre's normal (the thesis' "robust implementation": no
 * blur across a crease) and within PN_MC_BLUR_JUMP of its value (no blur across a hard
 * shadow edge) adds w src[q] and w, w = wi / (1 + |depth[q] - dc| k); any other adds +0 to
 * each (the sums start at +0 and only grow: the same bytes as adding nothing). The centre
 * tap counts whenever its own normal and depth do. */
PN_KFN void pn_mc_blur_tap(float wi, size_t q, int in, float ncx, float ncy, float ncz, float dc, float k, float vc,
                           const pn_ksurf *S, PN_CONST float *src, float *sum, float *wsum)
{
    PN_CONST uint32_t *ids = S->tri_id;
    PN_CONST float *depth = S->depth;
    pn_v3 nq = pn_surf_normal(S, q);
    /* & rather than &&: every load made (q is in the image), no branch on any of them */
    int inc = in & (ids[q] != 0xFFFFFFFFu) & (pn_v3_dot(pn_v3_make(ncx, ncy, ncz), nq) >= PN_MC_BLUR_COS) &
              (pn_kfabs(src[q] - vc) <= PN_MC_BLUR_JUMP);
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
                           const pn_ksurf *S, PN_CONST float *src, PN_GLOBAL float *dst)
{
    PN_CONST uint32_t *ids = S->tri_id;
    PN_CONST float *depth = S->depth;
    int32_t r = (int32_t)mc->blur, i;
    uint32_t x0;
    for (x0 = 0; x0 < W; x0 += PN_MC_BLUR_RUN) {
        uint32_t n = pn_kminu(PN_MC_BLUR_RUN, W - x0), l;
        float sum[PN_MC_BLUR_RUN], wsum[PN_MC_BLUR_RUN], k[PN_MC_BLUR_RUN], dc[PN_MC_BLUR_RUN];
        float ncx[PN_MC_BLUR_RUN], ncy[PN_MC_BLUR_RUN], ncz[PN_MC_BLUR_RUN], vc[PN_MC_BLUR_RUN];
        size_t pix0 = (size_t)y * W + x0;
        for (l = 0; l < n; l++) {
            pn_v3 nc = pn_surf_normal(S, pix0 + l);
            ncx[l] = nc.x;
            ncy[l] = nc.y;
            ncz[l] = nc.z;
            dc[l] = depth[pix0 + l];
            vc[l] = src[pix0 + l];
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
                    pn_mc_blur_tap(wi, base + l, 1, ncx[l], ncy[l], ncz[l], dc[l], k[l], vc[l], S, src, &sum[l],
                                   &wsum[l]);
            } else if ((int32_t)x0 + i >= 0 && (int32_t)(x0 + n) + i <= (int32_t)W) {
                size_t base = (size_t)y * W + (size_t)((int32_t)x0 + i);
                for (l = 0; l < n; l++)
                    pn_mc_blur_tap(wi, base + l, 1, ncx[l], ncy[l], ncz[l], dc[l], k[l], vc[l], S, src, &sum[l],
                                   &wsum[l]);
            } else {
                for (l = 0; l < n; l++) {
                    int32_t xx = (int32_t)(x0 + l) + i;
                    int in = xx >= 0 && xx < (int32_t)W;
                    pn_mc_blur_tap(wi, (size_t)y * W + (in ? (uint32_t)xx : x0 + l), in, ncx[l], ncy[l], ncz[l],
                                   dc[l], k[l], vc[l], S, src, &sum[l], &wsum[l]);
                }
            }
        }
        for (l = 0; l < n; l++) dst[pix0 + l] = ids[pix0 + l] == 0xFFFFFFFFu ? src[pix0 + l] : sum[l] / wsum[l];
    }
}

#endif
