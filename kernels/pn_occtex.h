/* pn_occtex.h - occlusion textures (Eisemann & Decoret 2006): the work items of the frame
 * in src/pn_occtex.c.
 *
 * Frame of reference. The light frame has its origin at the light centre, axes lview's
 * r, u, f (an area light: U^, V^, N); "depth" z is the coordinate along f. The slicing
 * view lview is a perspective view from a centre of projection (COP) d behind the light
 * centre, its frustum through the light rectangle's edges (tan_x = |U| / d, tan_y =
 * |V| / d), d chosen so that the frustum holds every lit shadow-ray origin (paper §3.4,
 * Fig. 5); a point light has d = 0 and a window fitted to the origins. Because the frustum
 * is fitted to the light, the light's image seen from any point P through a plane parallel
 * to the light is a square of texels: its side is
 *
 *     s(P, z_b) = res d (z_P - z_b) / (z_P (d + z_b))      (paper eq. 4 in texels)
 *
 * centred where the segment from P to the light centre crosses the plane.
 *
 * Slices. n bottom planes at depths z_b[k] = zmin + k h, h = (zmax - zmin) / (n - 1):
 * zmin the nearest geometry in front of the light, zmax the deepest lit origin, so the
 * scene's two ends lie on bottom planes (a planar occluder nearest the light, the paper's
 * exact case §3.1, is its slice's plane). Slice k holds the geometry of depths
 * (z_b[k-1], z_b[k]], projected through the COP onto z_b[k] (paper §3.4): every fragment of
 * every triangle, no depth test, sets bit k of its texel's word; with the leak fix (paper
 * Fig. 6, an option) also bit k + 1.
 *
 * Shading (paper §3.3, §3.5). A point at depth z_P takes from slice k the filtered mean
 * occupancy I_k of its kernel, weighted w_k = clamp((z_P - z_b[k]) / h, 0, 1): slices
 * wholly above the slice holding P count fully, the slice holding P not at all (its own
 * surface is in it, Fig. 7), and the one just above it fades in with P's distance below
 * its lower plane, so that the shadow is continuous where geometry crosses a plane.
 * What the fade leaves out - the slice holding P above P, and 1 - w of the slice above -
 * comes by default from a depth map of the slicing view (pn_occ_own; the paper's fade
 * alone with PN_OCC_FLAG_PAPER_FADE). Visibility = the combination of the w_k I_k
 * (product, eq. 5; or max, or clamped sum) and the depth map's occlusion, times the
 * fraction of light samples in front of P's own plane (the horizon of invariant 6, the
 * same mask every algorithm uses).
 *
 * Filters (paper §3.2), of one slice at a time, over integer occupancy counts (so every
 * table is exact, and the ports agree):
 *   N-buffer: level l holds the count of the 2^l x 2^l box centred on lattice point i
 *     (i + 0.5 at level 0, i + 1 above), from level l - 1 by 4 lookups; a kernel of side s
 *     takes levels floor(log2 s) and the next, bilinear in position, linear in size;
 *   summed-area table: the exact integral of the box over the texels, from 9 integer
 *     block counts weighted by the box's fractional overlaps;
 *   mipmap: counts of aligned 2^l blocks, trilinear.
 * Texels outside the texture are unoccupied; means are over the whole kernel. */
#ifndef PN_OCCTEX_H
#define PN_OCCTEX_H

#include "pn_lview.h"
#include "pn_nbuffer.h"
#include "pn_predicate.h"
#include "pn_raster.h"

#define PN_OCC_SLICES_MAX 16u
/* Filters and combinations: the values of penumbra.h's PN_OCC_FILTER_* / PN_OCC_COMBINE_*
 * (src/pn_occtex.c checks they agree). */
#define PN_OCC_F_NBUFFER 1u
#define PN_OCC_F_SAT 2u
#define PN_OCC_F_MIPMAP 3u
#define PN_OCC_C_PRODUCT 1u
#define PN_OCC_C_MAX 2u
#define PN_OCC_C_SUM 3u
#define PN_OCC_FLAG_LEAK_FIX 1u
#define PN_OCC_FLAG_PAPER_FADE 2u
/* pn_kocc.slice of the depth map's lookup pass (pn_occ_own). */
#define PN_OCC_SLICE_DEPTH 0xFFFFFFFFu
/* Counter words (pool occ_words, PN_OCC_WORDS): bits set, then per slice its bits. */
#define PN_OCC_WORD_TEXELS 0u
#define PN_OCC_WORD_SLICE0 2u
#define PN_OCC_WORDS 32u
/* A fragment within this fraction of a slice thickness below a bottom plane belongs to the
 * plane's slice (the rounding of its depth must not move a planar occluder on a plane to
 * the next slice). */
#define PN_OCC_PLANE_TOL 1e-3f
/* Smallest kernel side of the summed-area table, texels (a point sample below it). */
#define PN_OCC_SAT_MIN 1e-3f

/* Slice k's bottom plane's light depth. */
PN_KFN float pn_occ_plane(const pn_kocc *o, uint32_t k) { return o->zmin + (float)k * o->h; }

/* Slice of a fragment at light depth z: the k with z_b[k-1] < z <= z_b[k] (within the
 * tolerance), or -1 behind the light plane. */
PN_KFN int32_t pn_occ_slice_of(const pn_kocc *o, float z)
{
    if (!(z > 0.0f)) return -1;
    return pn_kceil_clamp((z - o->zmin) / o->h - PN_OCC_PLANE_TOL, 0, (int32_t)o->slices - 1);
}

/* The depth map's pool: three planes of res^2 floats, the nearest fragment's light depth
 * (+inf: none) and its plane's slopes, the normal's components across the light axis over
 * its component along it (the plane is z = z_t + gx (x - x_t) + gy (y - y_t) in the light
 * frame, slopes bounded by PN_OCC_SLOPE_MAX). */
#define PN_OCC_DEPTH_PLANES 3u
#define PN_OCC_SLOPE_MAX 1e6f

/* Band `band` of PN_RASTER_BAND texel rows: its words and depth map cleared, then every
 * triangle's fragments set their slices' bits and keep the nearest fragment (the G-buffer's
 * set-up, band walk and coverage on the slicing view); the bits the band holds added to
 * words (all, and per slice). */
PN_KFN void pn_occ_band(const pn_kview *v, const pn_kocc *o, PN_CONST float *tris, PN_CONST uint32_t *rows,
                        PN_CONST uint32_t *chunks, PN_CONST uint32_t *index, uint32_t tri_n, uint32_t band,
                        PN_GLOBAL uint32_t *bits, PN_GLOBAL float *depth, PN_GLOBAL uint32_t *words)
{
    uint32_t y0 = band * PN_RASTER_BAND, y1 = y0 + PN_RASTER_BAND - 1u, t, y, x, n = 0u, k;
    pn_band_walk bw;
    uint32_t per[PN_OCC_SLICES_MAX];
    uint32_t last = o->slices - 1u;
    size_t plane = (size_t)v->width * v->height;
    pn_v3 f = pn_v3_make(v->f[0], v->f[1], v->f[2]);
    /* Depths beyond it fall in the deepest slice (pn_occ_slice_of), with a margin of a
     * hundredth of a slice for the rounding of the fragments' depths. */
    float zdeep = o->zmin + ((float)last - 1.0f + PN_OCC_PLANE_TOL + 1e-2f) * o->h;
    if (y1 >= v->height) y1 = v->height - 1u;
    for (y = y0; y <= y1; y++)
        for (x = 0; x < v->width; x++) {
            size_t i = (size_t)y * v->width + x;
            bits[i] = 0u;
            depth[i] = PN_KINF;
            depth[plane + i] = 0.0f;
            depth[2u * plane + i] = 0.0f;
        }
    pn_band_walk_begin(&bw, tri_n);
    while (pn_band_next(chunks, index, y0, y1, &bw, &t)) {
        pn_raster_tri rt;
        float gx, gy;
        int marks;
        if (rows[t] == PN_RASTER_EMPTY) continue;
        /* Behind the light plane: nothing. Wholly within the deepest slice (a receiver
         * below every occluder: a ground plane): no bit, only the depth map (none with the
         * paper's fade alone). */
        {
            PN_CONST float *p = tris + (size_t)t * 9u;
            pn_v3 eye = pn_view_eye(v);
            float z0 = pn_v3_dot(pn_v3_sub(pn_v3_make(p[0], p[1], p[2]), eye), f);
            float z1 = pn_v3_dot(pn_v3_sub(pn_v3_make(p[3], p[4], p[5]), eye), f);
            float z2 = pn_v3_dot(pn_v3_sub(pn_v3_make(p[6], p[7], p[8]), eye), f);
            float lo = pn_kminf(z0, pn_kminf(z1, z2)) - o->d, hi = pn_kmaxf(z0, pn_kmaxf(z1, z2)) - o->d;
            marks = !(lo > zdeep);
            if (!(hi > 0.0f) || (!marks && (o->flags & PN_OCC_FLAG_PAPER_FADE))) continue;
        }
        if (!pn_raster_tri_setup(v, tris, rows, t, y0, y1, &rt)) continue;
        {
            float nx = pn_v3_dot(rt.n, pn_v3_make(v->r[0], v->r[1], v->r[2]));
            float ny = pn_v3_dot(rt.n, pn_v3_make(v->u[0], v->u[1], v->u[2])), nz = pn_v3_dot(rt.n, f);
            float lim = PN_OCC_SLOPE_MAX * pn_kfabs(nz);
            gx = pn_kfabs(nx) < lim ? nx / nz : (nx * nz < 0.0f ? -PN_OCC_SLOPE_MAX : PN_OCC_SLOPE_MAX);
            gy = pn_kfabs(ny) < lim ? ny / nz : (ny * nz < 0.0f ? -PN_OCC_SLOPE_MAX : PN_OCC_SLOPE_MAX);
        }
        for (y = rt.y0; y <= rt.y1; y++) {
            int32_t xi, xa = rt.x0, xb = rt.x1;
            int run = pn_raster_span(&rt, y, &xa, &xb);
            for (xi = xa; xi <= xb; xi++) {
                float z;
                int32_t sl;
                uint32_t m;
                size_t i = (size_t)y * v->width + (uint32_t)xi;
                if (!pn_raster_tri_axial(v, &rt, run, (uint32_t)xi, y, &z)) continue;
                z -= o->d;
                if (z > 0.0f && z < depth[i] && !(o->flags & PN_OCC_FLAG_PAPER_FADE)) {
                    depth[i] = z;
                    depth[plane + i] = gx;
                    depth[2u * plane + i] = gy;
                }
                if (!marks) continue;
                sl = pn_occ_slice_of(o, z);
                /* The deepest slice holds receivers only: no point lies below its plane. */
                if (sl < 0 || (uint32_t)sl >= last) continue;
                m = 1u << (uint32_t)sl;
                if ((o->flags & PN_OCC_FLAG_LEAK_FIX) && (uint32_t)sl + 1u < last) m |= m << 1;
                bits[i] |= m;
            }
        }
    }
    for (k = 0; k < PN_OCC_SLICES_MAX; k++) per[k] = 0u;
    for (y = y0; y <= y1; y++)
        for (x = 0; x < v->width; x++) {
            uint32_t w = bits[(size_t)y * v->width + x];
            while (w) {
                per[pn_kctz(w)]++;
                n++;
                w &= w - 1u;
            }
        }
    if (n) pn_katomic_add(words + PN_OCC_WORD_TEXELS, n);
    for (k = 0; k < PN_OCC_SLICES_MAX; k++)
        if (per[k]) pn_katomic_add(words + PN_OCC_WORD_SLICE0 + k, per[k]);
}

/* ---- Filters of slice o->slice ---------------------------------------------------------- */

/* Texel i of level 0 (N-buffer and mipmap alike): the slice's bit. */
PN_KFN void pn_occ_level0(const pn_kocc *o, PN_CONST uint32_t *bits, uint32_t i, PN_GLOBAL uint32_t *filt)
{
    filt[i] = (bits[i] >> o->slice) & 1u;
}

PN_KFN uint32_t pn_occ_at(PN_CONST uint32_t *lvl, uint32_t dim, int32_t i, int32_t j)
{
    if (i < 0 || j < 0 || i >= (int32_t)dim || j >= (int32_t)dim) return 0u;
    return lvl[(size_t)j * dim + (uint32_t)i];
}

/* Row y of N-buffer level o->level >= 1 from the level below (pool: levels of res^2; the
 * library's one N-buffer builder, kernels/pn_nbuffer.h, summing counts). */
PN_KFN void pn_occ_nbuf_row(const pn_kocc *o, uint32_t y, PN_GLOBAL uint32_t *filt)
{
    pn_nb_sum_row(o->res, o->level, y, filt);
}

/* Mipmap level l: side and offset in the pool (levels one after another). */
PN_KFN uint32_t pn_occ_mip_dim(uint32_t res, uint32_t l) { return (res + (1u << l) - 1u) >> l; }
PN_KFN size_t pn_occ_mip_off(uint32_t res, uint32_t l)
{
    size_t off = 0u;
    uint32_t m;
    for (m = 0; m < l; m++) off += (size_t)pn_occ_mip_dim(res, m) * pn_occ_mip_dim(res, m);
    return off;
}

/* Row y of mipmap level o->level >= 1: each texel its four children's counts. */
PN_KFN void pn_occ_mip_row(const pn_kocc *o, uint32_t y, PN_GLOBAL uint32_t *filt)
{
    uint32_t l = o->level, dl = pn_occ_mip_dim(o->res, l - 1u), d = pn_occ_mip_dim(o->res, l), x;
    PN_CONST uint32_t *lo = filt + pn_occ_mip_off(o->res, l - 1u);
    PN_GLOBAL uint32_t *out = filt + pn_occ_mip_off(o->res, l) + (size_t)y * d;
    for (x = 0; x < d; x++) {
        int32_t cx = 2 * (int32_t)x, cy = 2 * (int32_t)y;
        out[x] = pn_occ_at(lo, dl, cx, cy) + pn_occ_at(lo, dl, cx + 1, cy) + pn_occ_at(lo, dl, cx, cy + 1) +
                 pn_occ_at(lo, dl, cx + 1, cy + 1);
    }
}

/* Summed-area table ((res + 1)^2, S[j][i] = bits of the slice in [0, i) x [0, j)): row j's
 * prefix sums (row 0 is zero), then the columns' (pn_occ_sat_cols). */
PN_KFN void pn_occ_sat_row(const pn_kocc *o, PN_CONST uint32_t *bits, uint32_t j, PN_GLOBAL uint32_t *sat)
{
    uint32_t res = o->res, i, acc = 0u;
    PN_GLOBAL uint32_t *row = sat + (size_t)j * (res + 1u);
    row[0] = 0u;
    for (i = 0; i < res; i++) {
        if (j > 0u) acc += (bits[(size_t)(j - 1u) * res + i] >> o->slice) & 1u;
        row[i + 1u] = acc;
    }
}
/* Columns [PN_OCC_SAT_COLS * c, + PN_OCC_SAT_COLS) of the table: each row's run of them
 * added to the row below it, row after row (a run is contiguous in memory). */
#define PN_OCC_SAT_COLS 16u
PN_KFN void pn_occ_sat_cols(const pn_kocc *o, uint32_t c, PN_GLOBAL uint32_t *sat)
{
    uint32_t res = o->res, W = res + 1u, i0 = c * PN_OCC_SAT_COLS, i1 = i0 + PN_OCC_SAT_COLS, i, j;
    if (i1 > W) i1 = W;
    for (j = 1; j <= res; j++) {
        PN_GLOBAL uint32_t *row = sat + (size_t)j * W;
        PN_CONST uint32_t *up = sat + (size_t)(j - 1u) * W;
        for (i = i0; i < i1; i++) row[i] += up[i];
    }
}

/* ---- Lookups ------------------------------------------------------------------------------ */

/* Bilinear value of a level (dim x dim counts) at continuous lattice coordinates q
 * (lattice point i at q = i), clamped to the edge. */
PN_KFN float pn_occ_bilerp(PN_CONST uint32_t *lvl, uint32_t dim, float qx, float qy)
{
    int32_t i, j, i1, j1, last = (int32_t)dim - 1;
    float fx, fy, a, b, c, d;
    if (!(qx >= 0.0f)) qx = 0.0f;
    if (!(qy >= 0.0f)) qy = 0.0f;
    if (!(qx <= (float)last)) qx = (float)last;
    if (!(qy <= (float)last)) qy = (float)last;
    i = pn_kfloor_clamp(qx, 0, last);
    j = pn_kfloor_clamp(qy, 0, last);
    fx = qx - (float)i;
    fy = qy - (float)j;
    i1 = pn_kmini(i + 1, last);
    j1 = pn_kmini(j + 1, last);
    a = (float)lvl[(size_t)j * dim + (uint32_t)i];
    b = (float)lvl[(size_t)j * dim + (uint32_t)i1];
    c = (float)lvl[(size_t)j1 * dim + (uint32_t)i];
    d = (float)lvl[(size_t)j1 * dim + (uint32_t)i1];
    return (1.0f - fy) * ((1.0f - fx) * a + fx * b) + fy * ((1.0f - fx) * c + fx * d);
}

/* 4^-l, exactly. */
PN_KFN float pn_occ_inv_area(uint32_t l)
{
    float v = 1.0f;
    uint32_t m;
    for (m = 0; m < l; m++) v *= 0.25f;
    return v;
}

/* Mean occupancy of level l (N-buffer or mipmap) around (px, py) (texel units). */
PN_KFN float pn_occ_level_mean(const pn_kocc *o, PN_CONST uint32_t *filt, uint32_t l, float px, float py)
{
    uint32_t res = o->res;
    if (o->filter == PN_OCC_F_MIPMAP) {
        float inv = 1.0f;
        uint32_t m;
        for (m = 0; m < l; m++) inv *= 0.5f;
        return pn_occ_bilerp(filt + pn_occ_mip_off(res, l), pn_occ_mip_dim(res, l), px * inv - 0.5f,
                             py * inv - 0.5f) *
               pn_occ_inv_area(l);
    }
    {
        float off = l == 0u ? 0.5f : 1.0f;
        return pn_occ_bilerp(filt + (size_t)l * res * res, res, px - off, py - off) * pn_occ_inv_area(l);
    }
}

/* N-buffer / mipmap: the mean over a square kernel of side s. */
PN_KFN float pn_occ_pyramid(const pn_kocc *o, PN_CONST uint32_t *filt, float px, float py, float s)
{
    uint32_t l = 0u;
    float size = 1.0f, t;
    if (!(s > 1.0f)) return pn_occ_level_mean(o, filt, 0u, px, py);
    while (l + 1u < o->levels && 2.0f * size <= s) {
        l++;
        size *= 2.0f;
    }
    if (l + 1u >= o->levels) { /* wider than the top box: its count spread over the kernel */
        t = size / s;
        return pn_occ_level_mean(o, filt, l, px, py) * t * t;
    }
    t = (s - size) / size;
    return (1.0f - t) * pn_occ_level_mean(o, filt, l, px, py) + t * pn_occ_level_mean(o, filt, l + 1u, px, py);
}

/* The columns (or rows) interval [a, b] (0 <= a <= b <= res) overlaps: up to 3 runs r of
 * texels lo[r] .. lo[r + 1] - 1 with overlap weights w[r] (the first and last partial, the
 * middle whole, possibly empty); returns the run count. */
PN_KFN uint32_t pn_occ_runs(float a, float b, uint32_t res, uint32_t *lo, float *w)
{
    int32_t ia = pn_kfloor_clamp(a, 0, (int32_t)res - 1), ib = pn_kfloor_clamp(b, 0, (int32_t)res - 1);
    if (ia == ib) {
        lo[0] = (uint32_t)ia;
        lo[1] = (uint32_t)ia + 1u;
        w[0] = b - a;
        return 1u;
    }
    lo[0] = (uint32_t)ia;
    lo[1] = (uint32_t)ia + 1u;
    lo[2] = (uint32_t)ib;
    lo[3] = (uint32_t)ib + 1u;
    w[0] = (float)(ia + 1) - a;
    w[1] = 1.0f;
    w[2] = b - (float)ib;
    return 3u;
}

/* Summed-area table: the exact mean occupancy of the box of sides sx, sy around (px, py). */
PN_KFN float pn_occ_sat_mean(const pn_kocc *o, PN_CONST uint32_t *sat, float px, float py, float sx, float sy)
{
    uint32_t res = o->res, W = res + 1u, lx[4] = {0u, 0u, 0u, 0u}, ly[4] = {0u, 0u, 0u, 0u}, nx, ny, a, b;
    float wx[3] = {0.0f, 0.0f, 0.0f}, wy[3] = {0.0f, 0.0f, 0.0f}, x0, x1, y0, y1, sum = 0.0f, R = (float)res, v;
    if (!(sx >= PN_OCC_SAT_MIN)) sx = PN_OCC_SAT_MIN;
    if (!(sy >= PN_OCC_SAT_MIN)) sy = PN_OCC_SAT_MIN;
    x0 = pn_kmaxf(px - 0.5f * sx, 0.0f);
    x1 = pn_kminf(px + 0.5f * sx, R);
    y0 = pn_kmaxf(py - 0.5f * sy, 0.0f);
    y1 = pn_kminf(py + 0.5f * sy, R);
    if (!(x1 > x0 && y1 > y0)) return 0.0f;
    nx = pn_occ_runs(x0, x1, res, lx, wx);
    ny = pn_occ_runs(y0, y1, res, ly, wy);
    for (b = 0; b < ny; b++) {
        uint32_t j0 = ly[b], j1 = ly[b + 1u];
        float row = 0.0f;
        for (a = 0; a < nx; a++) {
            uint32_t i0 = lx[a], i1 = lx[a + 1u];
            uint32_t cnt = sat[(size_t)j1 * W + i1] - sat[(size_t)j0 * W + i1] - sat[(size_t)j1 * W + i0] +
                           sat[(size_t)j0 * W + i0];
            row += wx[a] * (float)cnt;
        }
        sum += wy[b] * row;
    }
    v = sum / (sx * sy);
    return v > 1.0f ? 1.0f : v;
}

/* The weight of slice k for an origin at light depth z > 0 (<= 0: the slice is not above). */
PN_KFN float pn_occ_weight(const pn_kocc *o, uint32_t k, float z) { return (z - pn_occ_plane(o, k)) / o->h; }

/* Slice o->slice's occlusion of origin O, weighted, into *I; 0 when the slice does not
 * weigh in (not above O). */
PN_KFN int pn_occ_slice_occlusion(const pn_kview *lv, const pn_klight *L, const pn_kocc *o, PN_CONST uint32_t *filt,
                                  pn_v3 O, float *I)
{
    pn_v3 c = pn_lview_frame(lv, L, O);
    float x = c.x, y = c.y, z = c.z;
    float zb = pn_occ_plane(o, o->slice), w, fr, q, sx, sy, px, py, v;
    *I = 0.0f;
    if (!(z > 0.0f)) return 0;
    w = pn_occ_weight(o, o->slice, z);
    if (!(w > 0.0f)) return 0;
    if (w > 1.0f) w = 1.0f;
    /* Where the segment from O to the light centre crosses the plane, in texels. */
    fr = zb / z;
    pn_project_camera(lv, pn_v3_make(x * fr, y * fr, zb + o->d), &px, &py);
    q = (z - zb) / (z * (zb + o->d));
    sx = o->sfac_x * q;
    sy = o->sfac_y * q;
    if (o->filter == PN_OCC_F_SAT)
        v = pn_occ_sat_mean(o, filt, px, py, sx, sy);
    else
        v = pn_occ_pyramid(o, filt, px, py, pn_kmaxf(sx, sy));
    *I = w * v;
    return 1;
}

/* The lookups origin O took: the slices looked up (o->live) that weighed in. */
PN_KFN uint32_t pn_occ_lookups(const pn_kview *lv, const pn_klight *L, const pn_kocc *o, pn_v3 O)
{
    float z = pn_lview_frame(lv, L, O).z;
    uint32_t k, n = 0u;
    if (!(z > 0.0f)) return 0u;
    for (k = 0; k < o->slices; k++) n += ((o->live >> k) & 1u) && pn_occ_weight(o, k, z) > 0.0f;
    return n;
}

/* The depth map's occlusion of origin O (P: its surface point, O = P + eps n): what the
 * fade of the slices leaves out (pn_occ_weight), the part of the slice holding O above O,
 * wholly, and the slice above it with weight 1 - w, w that slice's fade. The texels of the
 * rays from O to the light between those depths are walked (the box around O's texel and
 * the light's image on the slice above's top plane; above PN_OCC_OWN_TAPS texels a side, a
 * tap stands for a block of texels at its centre's depth - but a block over O's own texel
 * for its tap's texel alone, times the block's area, unless O's texel holds an occluder in
 * the range: the rest of such a block may be O's own surface). A texel whose nearest fragment
 * X lies in that depth range and in front of the plane through O parallel to P's tangent
 * plane is a small occluder: the square of its footprint at X's depth, projected from O
 * onto the light plane, hides the part of the light rectangle it covers, times how much
 * of the fragment's plane the square stands for as seen from O (|n . (X - O)| over the
 * flat square's, at most PN_OCC_TILT_MAX: a patch O sees edge-on, a neighbour on O's own
 * surface, hides nothing). A point light: 1 when a square holds the light centre. The
 * parts of both ranges are summed, each at most 1, and combined as a product. */
#define PN_OCC_OWN_TAPS 16
#define PN_OCC_TILT_MAX 4.0f
PN_KFN float pn_occ_own(const pn_kview *lv, const pn_klight *L, const pn_kocc *o, PN_CONST float *depth, pn_v3 P,
                        pn_v3 O, float ha, float hb)
{
    pn_v3 oc = pn_lview_frame(lv, L, O), nl = pn_v3_sub(oc, pn_lview_frame(lv, L, P));
    float oz = oc.z, zlo, zmid, wup, pox, poy, cx, cy, sx, sy, own = 0.0f, up = 0.0f, area = 4.0f * ha * hb;
    float tx = lv->tan_half * lv->aspect, ty = lv->tan_half, W = (float)lv->width, H = (float)lv->height;
    int32_t k, last = (int32_t)o->res - 1, ix0, ix1, iy0, iy1, stx, sty, i, j, own_covered;
    size_t pl = (size_t)o->res * o->res;
    if (!(oz > 0.0f)) return 0.0f;
    k = pn_occ_slice_of(o, oz);
    zmid = k > 0 ? pn_occ_plane(o, (uint32_t)k - 1u) : 0.0f;
    zlo = k > 1 ? pn_occ_plane(o, (uint32_t)k - 2u) : 0.0f;
    wup = k > 0 ? 1.0f - pn_kclampf(pn_occ_weight(o, (uint32_t)k - 1u, oz), 0.0f, 1.0f) : 0.0f;
    if (!(zlo < oz)) return 0.0f;
    pn_project_camera(lv, pn_v3_make(oc.x, oc.y, oz + o->d), &pox, &poy);
    if (L->is_point || !(zlo + o->d > 0.0f)) {
        cx = pox;
        cy = poy;
        sx = sy = 0.0f;
    } else {
        float fr = zlo / oz, q = (oz - zlo) / (oz * (zlo + o->d));
        pn_project_camera(lv, pn_v3_make(oc.x * fr, oc.y * fr, zlo + o->d), &cx, &cy);
        sx = 0.5f * o->sfac_x * q;
        sy = 0.5f * o->sfac_y * q;
    }
    ix0 = pn_kfloor_clamp(pn_kminf(pox, cx - sx), 0, last);
    ix1 = pn_kfloor_clamp(pn_kmaxf(pox, cx + sx), 0, last);
    iy0 = pn_kfloor_clamp(pn_kminf(poy, cy - sy), 0, last);
    iy1 = pn_kfloor_clamp(pn_kmaxf(poy, cy + sy), 0, last);
    {
        /* Whether O's own texel holds an occluder in range (then a block over it is one). */
        float zo = depth[(size_t)pn_kfloor_clamp(poy, 0, last) * o->res + (uint32_t)pn_kfloor_clamp(pox, 0, last)];
        own_covered = zo > zlo && zo < oz;
    }
    stx = (ix1 - ix0 + PN_OCC_OWN_TAPS) / PN_OCC_OWN_TAPS;
    sty = (iy1 - iy0 + PN_OCC_OWN_TAPS) / PN_OCC_OWN_TAPS;
    for (j = iy0; j <= iy1; j += sty) {
        int32_t bh = pn_kmini(sty, iy1 + 1 - j), tj = j + bh / 2;
        for (i = ix0; i <= ix1; i += stx) {
            int32_t bw = pn_kmini(stx, ix1 + 1 - i), ti = i + bw / 2;
            size_t at = (size_t)tj * o->res + (uint32_t)ti;
            float zt = depth[at], zc, t, X0, X1, Y0, Y1, cover_x, cover_y, scale;
            pn_v3 X;
            if (!(zt > zlo && zt < oz)) continue;
            zc = zt + o->d;
            X = pn_v3_make((2.0f * ((float)ti + 0.5f) / W - 1.0f) * tx * zc,
                           (1.0f - 2.0f * ((float)tj + 0.5f) / H) * ty * zc, zt);
            if (!(pn_v3_dot(pn_v3_sub(X, oc), nl) > 0.0f)) continue;
            /* The block [i, i + bw) x [j, j + bh) at depth zt, seen from O on the light plane. */
            t = oz / (oz - zt);
            {
                /* A block over O's own texel: only the tap's texel, standing for the block's
                 * area (its other texels may be O's own surface). */
                int over = (bw > 1 || bh > 1) && pox >= (float)i && pox < (float)(i + bw) && poy >= (float)j &&
                           poy < (float)(j + bh) && !own_covered;
                int32_t a0 = over ? ti : i, a1 = over ? ti + 1 : i + bw, b0 = over ? tj : j, b1 = over ? tj + 1 : j + bh;
                scale = over ? (float)(bw * bh) : 1.0f;
                X0 = oc.x + ((2.0f * (float)a0 / W - 1.0f) * tx * zc - oc.x) * t;
                X1 = oc.x + ((2.0f * (float)a1 / W - 1.0f) * tx * zc - oc.x) * t;
                Y0 = oc.y + ((1.0f - 2.0f * (float)b1 / H) * ty * zc - oc.y) * t;
                Y1 = oc.y + ((1.0f - 2.0f * (float)b0 / H) * ty * zc - oc.y) * t;
            }
            if (L->is_point) {
                if (X0 <= 0.0f && 0.0f <= X1 && Y0 <= 0.0f && 0.0f <= Y1) {
                    if (zt > zmid) return 1.0f;
                    up = wup;
                }
                continue;
            }
            cover_x = pn_kminf(X1, ha) - pn_kmaxf(X0, -ha);
            cover_y = pn_kminf(Y1, hb) - pn_kmaxf(Y0, -hb);
            if (cover_x > 0.0f && cover_y > 0.0f) {
                float gx = depth[pl + at], gy = depth[2u * pl + at], dz = zt - oz;
                float num = pn_kfabs(gx * (X.x - oc.x) + gy * (X.y - oc.y) + dz);
                float den = pn_kfabs(gx * X.x / zc + gy * X.y / zc + 1.0f) * pn_kfabs(dz);
                float tilt = num < PN_OCC_TILT_MAX * den ? num / den : PN_OCC_TILT_MAX, a = cover_x * cover_y * tilt * scale;
                if (zt > zmid) own += a;
                else up += a;
            }
        }
    }
    if (!L->is_point) {
        own = pn_kminf(own / area, 1.0f);
        up = pn_kminf(up / area, 1.0f) * wup;
    }
    return 1.0f - (1.0f - own) * (1.0f - up);
}

/* One combination step: visibility v so far and one slice's occlusion I. */
PN_KFN float pn_occ_combine(uint32_t how, float v, float I)
{
    if (how == PN_OCC_C_MAX) return pn_kminf(v, 1.0f - I);
    if (how == PN_OCC_C_SUM) {
        v -= I;
        return v > 0.0f ? v : 0.0f;
    }
    return v * (1.0f - I);
}

#endif
