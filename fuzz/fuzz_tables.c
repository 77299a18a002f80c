/* fuzz_tables.c - the integer and min / max tables the approximations look their layers up in
 * (issue 53) against brute force over the same texels, on random small textures.
 *
 * Input (bytes past the end read as zero):
 *   0 res 1 .. 64   1 bit 0: the Monte Carlo N-buffer keeps every third level
 *   (PN_LIMITS_SPARSE_NBUFFER), bits 4-7: the occlusion-texture slice looked at
 *   then two bytes a texel (res^2 of them, row by row): a 16-bit word of slice bits for the
 *   occlusion textures, and the same two bytes as the texel of a Monte Carlo layer: the
 *   first below 40 an empty texel (near +inf, far -inf), below 60 a signed zero (near +0 or
 *   -0 by its parity), else near = first / 256 and far = near + second / 256 (ties, equal
 *   depths and zeros are common: the min / max order must not matter)
 *   then queries, 5 bytes each (at most 64): a texel rectangle's corners x0, y0, x1, y1 in
 *   [-8, res + 8) (an empty one too) and a level byte.
 *
 * - The Monte Carlo shadow maps' min / max N-buffer (kernels/pn_nbuffer.h; levels built by
 *   pn_nb_mm_row, kept every level and every third): a rectangle's lookup (pn_nb_mm_rect)
 *   bounds its texels inside the map (min near no larger, max far and max near no smaller);
 *   a box of a level (pn_nb_mm_box) bounds its texels inside the map and, when it lies
 *   inside, holds exactly their bounds; the sparse levels give the same bits as the kept.
 * - The occlusion textures' counts of one slice: the summed-area table (pn_occ_sat_row,
 *   pn_occ_sat_cols) gives every rectangle's count exactly; the N-buffer level l (the
 *   centred layout, pn_nb_sum_row) holds at texel x the count of [x + 1 - 2^(l-1),
 *   x + 1 + 2^(l-1)) per axis when that box lies inside, no more than its part inside when
 *   it reaches beyond an edge; the mipmap level l (pn_occ_mip_row) the count of its 2^l box
 *   exactly. */
#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "pn_internal.h"
#include "pn_mcsm.h"
#include "pn_occtex.h"

#define RMAX 64u
#define LMAX 7u /* pn_nb_levels(64) */
#define QMAX 64u

static float nb_dense[LMAX * RMAX * RMAX * PN_NB_MM], nb_sparse[LMAX * RMAX * RMAX * PN_NB_MM];
static uint32_t bits[RMAX * RMAX], nbuf[LMAX * RMAX * RMAX], mip[2u * RMAX * RMAX], sat[(RMAX + 1u) * (RMAX + 1u)];

/* The bounds {min near, max far, max near} of the layer texels of [x0, x1) x [y0, y1) inside
 * the map (+inf, -inf, -inf when none), and the count of slice bits there. */
static void brute(uint32_t res, uint32_t slice, int32_t x0, int32_t y0, int32_t x1, int32_t y1, float *v, uint32_t *count)
{
    int32_t x, y, R = (int32_t)res;
    v[0] = PN_KINF;
    v[1] = -PN_KINF;
    v[2] = -PN_KINF;
    *count = 0u;
    for (y = y0 < 0 ? 0 : y0; y < y1 && y < R; y++)
        for (x = x0 < 0 ? 0 : x0; x < x1 && x < R; x++) {
            const float *T = nb_dense + ((size_t)y * res + (size_t)x) * PN_NB_MM;
            v[0] = pn_kminf(v[0], -T[0]);
            v[1] = pn_kmaxf(v[1], T[1]);
            v[2] = pn_kmaxf(v[2], T[2]);
            *count += (bits[(size_t)y * res + (size_t)x] >> slice) & 1u;
        }
}

static int bounds(const float *v, const float *b) { return v[0] <= b[0] && v[1] >= b[1] && v[2] >= b[2]; }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_rd r = {data, size, 0};
    uint32_t res = 1u + fuzz_byte(&r) % RMAX, flags = fuzz_byte(&r), slice = flags >> 4, i, l;
    uint32_t nq;
    pn_kmc mc;
    pn_kocc oc;
    pn_nb_mm_lay D, S;

    memset(&mc, 0, sizeof(mc));
    mc.res = res;
    mc.levels = pn_nb_levels(res);
    FUZZ_CHECK(mc.levels <= LMAX, "levels %u", mc.levels);
    mc.nb_step = 1u;
    (void)pn_nb_mm_lay_init(&mc, &D);
    mc.nb_step = 3u;
    (void)pn_nb_mm_lay_init(&mc, &S);
    memset(&oc, 0, sizeof(oc));
    oc.res = res;
    oc.slice = slice;
    oc.levels = mc.levels;

    for (i = 0; i < res * res; i++) {
        uint32_t a = fuzz_byte(&r), b = fuzz_byte(&r);
        float *T = nb_dense + (size_t)i * PN_NB_MM, near, far;
        bits[i] = a | b << 8;
        if (a < 40u) {
            near = PN_KINF;
            far = -PN_KINF;
        } else if (a < 60u) {
            near = (a & 1u) ? -0.0f : 0.0f;
            far = -near;
        } else {
            near = (float)a / 256.0f;
            far = near + (float)b / 256.0f;
        }
        T[0] = -near; /* stored as the layers' pass leaves it */
        T[1] = far;
        T[2] = near;
        memcpy(nb_sparse + (size_t)i * PN_NB_MM, T, sizeof(float) * PN_NB_MM);
    }
    pn_nb_mm_build(&D, nb_dense);
    pn_nb_mm_build(&S, nb_sparse);

    /* The occlusion textures' tables of the slice: level 0, the N-buffer's levels, the
     * mipmap's first two, the summed-area table. */
    for (i = 0; i < res * res; i++) pn_occ_level0(&oc, bits, i, nbuf);
    memcpy(mip, nbuf, sizeof(uint32_t) * res * res);
    for (l = 1; l < oc.levels; l++) {
        oc.level = l;
        for (i = 0; i < res; i++) pn_occ_nbuf_row(&oc, i, nbuf);
    }
    for (l = 1; l < 3u && l < oc.levels; l++) {
        oc.level = l;
        for (i = 0; i < pn_occ_mip_dim(res, l); i++) pn_occ_mip_row(&oc, i, mip);
    }
    for (i = 0; i <= res; i++) pn_occ_sat_row(&oc, bits, i, sat);
    for (i = 0; i * PN_OCC_SAT_COLS < res + 1u; i++) pn_occ_sat_cols(&oc, i, sat);

    nq = (uint32_t)(size > r.i ? (size - r.i) / 5u : 0u);
    if (nq > QMAX) nq = QMAX;
    for (i = 0; i < nq; i++) {
        uint32_t span = res + 16u;
        int32_t x0 = (int32_t)(fuzz_byte(&r) % span) - 8, y0 = (int32_t)(fuzz_byte(&r) % span) - 8;
        int32_t x1 = (int32_t)(fuzz_byte(&r) % span) - 8, y1 = (int32_t)(fuzz_byte(&r) % span) - 8;
        uint32_t lq = fuzz_byte(&r) % mc.levels, count, B = 1u << lq;
        int32_t R = (int32_t)res;
        float v[PN_NB_MM], w[PN_NB_MM], b[PN_NB_MM];

        /* A rectangle's min / max lookup. */
        brute(res, slice, x0, y0, x1, y1, b, &count);
        pn_nb_mm_rect(nb_dense, &D, x0, y0, x1, y1, v);
        pn_nb_mm_rect(nb_sparse, &S, x0, y0, x1, y1, w);
        FUZZ_CHECK(bounds(v, b), "res %u rect [%d, %d) x [%d, %d): %g %g %g, its texels %g %g %g", res, x0, x1, y0, y1,
                   (double)v[0], (double)v[1], (double)v[2], (double)b[0], (double)b[1], (double)b[2]);
        FUZZ_CHECK(memcmp(v, w, sizeof(v)) == 0, "res %u rect [%d, %d) x [%d, %d): the sparse levels differ", res, x0, x1,
                   y0, y1);
        /* Its count from the summed-area table (a rectangle inside the map). */
        {
            int32_t a0 = x0 < 0 ? 0 : (x0 > R ? R : x0), b0 = y0 < 0 ? 0 : (y0 > R ? R : y0);
            int32_t a1 = x1 < a0 ? a0 : (x1 > R ? R : x1), b1 = y1 < b0 ? b0 : (y1 > R ? R : y1);
            uint32_t W = res + 1u;
            uint32_t s = sat[(size_t)b1 * W + (uint32_t)a1] - sat[(size_t)b0 * W + (uint32_t)a1] -
                         sat[(size_t)b1 * W + (uint32_t)a0] + sat[(size_t)b0 * W + (uint32_t)a0];
            FUZZ_CHECK(s == count, "res %u slice %u rect [%d, %d) x [%d, %d): summed-area table %u, texels %u", res, slice,
                       a0, a1, b0, b1, s, count);
        }
        /* A box of level lq at (x0, y0) (searches ask from 2^l - 1 before the map on). */
        {
            int32_t X = x0 < 1 - (int32_t)B ? 1 - (int32_t)B : x0, Y = y0 < 1 - (int32_t)B ? 1 - (int32_t)B : y0;
            int inside;
            if (X >= R) X = R - 1;
            if (Y >= R) Y = R - 1;
            inside = X >= 0 && Y >= 0 && X + (int32_t)B <= R && Y + (int32_t)B <= R;
            brute(res, slice, X, Y, X + (int32_t)B, Y + (int32_t)B, b, &count);
            pn_nb_mm_box(nb_dense, &D, lq, X, Y, v);
            pn_nb_mm_box(nb_sparse, &S, lq, X, Y, w);
            FUZZ_CHECK(bounds(v, b), "res %u level %u box (%d, %d): %g %g %g, its texels %g %g %g", res, lq, X, Y,
                       (double)v[0], (double)v[1], (double)v[2], (double)b[0], (double)b[1], (double)b[2]);
            FUZZ_CHECK(!inside || (v[0] == b[0] && v[1] == b[1] && v[2] == b[2]),
                       "res %u level %u box (%d, %d) inside the map: %g %g %g, its texels %g %g %g", res, lq, X, Y,
                       (double)v[0], (double)v[1], (double)v[2], (double)b[0], (double)b[1], (double)b[2]);
            FUZZ_CHECK(memcmp(v, w, sizeof(v)) == 0, "res %u level %u box (%d, %d): the sparse levels differ", res, lq, X, Y);
        }
        /* The occlusion N-buffer's texel (x, y) of level lq, centred layout. */
        if (x0 >= 0 && y0 >= 0 && x0 < R && y0 < R) {
            int32_t h = lq == 0u ? 0 : (int32_t)(B >> 1), lo_x = lq == 0u ? x0 : x0 + 1 - h, lo_y = lq == 0u ? y0 : y0 + 1 - h;
            uint32_t got = nbuf[(size_t)lq * res * res + (size_t)y0 * res + (uint32_t)x0];
            int inside = lo_x >= 0 && lo_y >= 0 && lo_x + (int32_t)B <= R && lo_y + (int32_t)B <= R;
            brute(res, slice, lo_x, lo_y, lo_x + (int32_t)B, lo_y + (int32_t)B, b, &count);
            FUZZ_CHECK(inside ? got == count : got <= count, "res %u slice %u N-buffer level %u texel (%d, %d): %u, its box %u%s",
                       res, slice, lq, x0, y0, got, count, inside ? "" : " (beyond an edge)");
        }
        /* The mipmap's texel of levels 1 and 2 holding (x0, y0). */
        if (x0 >= 0 && y0 >= 0 && x0 < R && y0 < R) {
            uint32_t m;
            for (m = 1u; m < 3u && m < oc.levels; m++) {
                uint32_t d = pn_occ_mip_dim(res, m), mx = (uint32_t)x0 >> m, my = (uint32_t)y0 >> m;
                uint32_t got = mip[pn_occ_mip_off(res, m) + (size_t)my * d + mx];
                brute(res, slice, (int32_t)(mx << m), (int32_t)(my << m), (int32_t)((mx + 1u) << m), (int32_t)((my + 1u) << m), b,
                      &count);
                FUZZ_CHECK(got == count, "res %u slice %u mipmap level %u texel (%u, %u): %u, its box %u", res, slice, m, mx,
                           my, got, count);
            }
        }
    }
    return 0;
}
