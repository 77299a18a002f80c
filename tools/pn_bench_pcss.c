/* pn_bench_pcss.c - percentage-closer soft shadows (Fernando 2005) as a game engine ships
 * them: the approximate, shadow-map baseline of the benchmark (see pn_bench.h). Host code,
 * not the library: it allocates, and its arithmetic is plain float C.
 *
 * One pass, all of it timed (the light moves every frame in an engine):
 *   1. Frustum fit. The map is a perspective projection from the light centre c looking
 *      along the light normal N (x along u, y along v, depth z = (X - c).N), in tangent
 *      coordinates (x/z, y/z). Its window is fitted to the G-buffer points in front of the
 *      light plane (how engines fit cascades to what the camera sees), each bound capped
 *      at PN_PCSS_TAN_MAX (76 degrees: a lamp under a ceiling sees a hemisphere), and
 *      padded by PN_PCSS_PAD of its width. The near plane is the nearest point of any
 *      triangle inside that window (after clipping), at least PN_PCSS_NEAR_MIN times the
 *      farthest receiver depth; triangles wholly beyond the farthest receiver or behind
 *      the light plane are skipped.
 *   2. Depth map, PN_PCSS_MAP x PN_PCSS_MAP floats of light-space depth z. Every triangle
 *      is clipped against the near plane and the window's four side planes (a guard band
 *      of PN_PCSS_GUARD texels), so triangles crossing the light plane are drawn where
 *      they are in front; the polygon is fanned into triangles, binned by bands of
 *      PN_PCSS_BAND rows, and each band is rasterized by one job (edge functions at texel
 *      centres, 1/z interpolated linearly in screen space, min depth per texel): the
 *      result does not depend on the thread count.
 *   3. Per pixel, from the shadow-ray origin O = P + eps*n of the exact algorithms
 *      (pn_shadow_origin), at depth z_r and map position t:
 *      - blocker search over the rectangle the light subtends from O on the near plane,
 *        half-extents |u| (z_r - near) / (z_r near) and |v| (...) in tangent units, with
 *        PN_PCSS_SEARCH_TAPS point-sampled taps; a tap blocks when its depth is below the
 *        receiver's by more than the bias (below); z_avg = mean depth of the blocking
 *        taps; none: the pixel is lit by the map;
 *      - penumbra w = (z_r - z_avg) |u| / z_avg (and |v|) at the receiver, i.e. a filter
 *        half-extent on the map of w near / z_r on the near plane (w / z_r in tangent
 *        units), clamped to at most the search region and at least one texel;
 *      - PCF: PN_PCSS_PCF_TAPS taps, each a bilinear 2x2 depth comparison (what a
 *        hardware comparison sampler returns), fraction not occluded.
 *      Taps are a Hammersley set over the square (stratified in every elementary
 *      interval), mapped onto the light's rectangle (u and v extents separately: the
 *      light is a rectangle, so the exact filter of a planar blocker is a box). Per pixel
 *      the set is shifted toroidally (Cranley-Patterson rotation) by an integer hash of the
 *      pixel index, the rectangle's equivalent of rotating a Poisson disk: deterministic,
 *      and it trades banding for noise as the rotation does.
 *      Bias: a texel blocks when depth < min(z_r, z_plane) - (PN_PCSS_BIAS_CONST z_r +
 *      PN_PCSS_BIAS_SLOPE dz), where z_plane is the depth of the receiver's own plane
 *      (through O, normal n) along the texel centre's light ray - receiver-plane depth
 *      bias (Isidoro 2006), what engines use for wide PCF kernels, capped at z_r since no
 *      blocker of a ray from O to the light lies deeper than O - and dz is the plane's depth
 *      change across one texel (slope-scaled, capped at PN_PCSS_SLOPE_MAX z_r).
 *   4. vis = PCF x the fraction of the k x k light samples in front of the plane of the
 *      pixel's own triangle: the horizon of every exact algorithm, computed by the same
 *      kernel (pn_horizon_make / pn_horizon_mask), so an unoccluded pixel gets exactly the
 *      reference's value. Background pixels get 1 and pixels on or behind the light plane
 *      0, the convention of pn_our_masks and the Embree baseline.
 *
 * Outside the map (a receiver beyond the capped window, e.g. nearly in the light plane, or
 * a tap outside it) there is no depth: such receivers are unshadowed by the map (vis = the
 * horizon alone) and such taps neither block in the search nor occlude in PCF.
 *
 * Known artifacts, kept (they are PCSS's): contact shadows too soft and blockers that
 * overlap in depth averaged into one (light leaks); and, since PCF filters the whole light
 * while the horizon is a separate factor, a receiver whose plane cuts the light (a wall or
 * a sphere past its terminator, whose normal the library turns toward the light centre)
 * gets PCF x horizon where the reference has the blocked samples and the horizon's
 * overlapping: too bright there. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pn_bench.h"
#include "pn_bench_kernels.h"

#define PN_PCSS_MAP 2048u         /* shadow-map texels per axis */
#define PN_PCSS_BAND 16u          /* rows per rasterization job */
#define PN_PCSS_CHUNKS 256u       /* triangle chunks of the set-up passes */
#define PN_PCSS_SEARCH_TAPS 16u   /* blocker-search taps */
#define PN_PCSS_PCF_TAPS 32u      /* PCF taps (each a bilinear 2x2 comparison) */
#define PN_PCSS_TAN_MAX 4.0f      /* frustum half-angle cap: tan <= 4 (~76 degrees) */
#define PN_PCSS_PAD 0.01f         /* window padding, fraction of its width per side */
#define PN_PCSS_GUARD 2.0f        /* guard band of the side-plane clip, texels */
#define PN_PCSS_NEAR_MIN 1e-3f    /* near plane >= this x the farthest receiver depth */
#define PN_PCSS_BIAS_CONST 1e-3f  /* constant depth bias, fraction of the receiver depth */
#define PN_PCSS_BIAS_SLOPE 1.0f   /* slope-scaled bias, texels of the receiver's slope */
#define PN_PCSS_SLOPE_MAX 0.005f  /* cap of the slope term, fraction of the receiver depth */

#define PN_PCSS_POLY_MAX 8        /* a triangle clipped by 5 planes: at most 8 vertices */

/* One rasterizable triangle: texel-space x, y and 1/z of its three corners. */
typedef struct pn_pcss_tri {
    float x[3], y[3], iz[3];
} pn_pcss_tri;

typedef struct pn_pcss {
    /* light frame */
    pn_v3 c, Uh, Vh, N;
    float ulen, vlen;
    pn_klight kl;
    const pn_mesh *mesh;
    const pn_gbuf *g;
    float *vis;
    /* window (tangent units), its texel size, depth range */
    float sx0, sx1, sy0, sy1, dsx, dsy;
    float gx0, gx1, gy0, gy1; /* guard-banded clip window */
    float zfar, znear_clip, near;
    int have_map;
    /* frustum fit, per image row */
    float *row_fit; /* 5 per row: min sx, max sx, min sy, max sy, max z (-1: none) */
    /* set-up */
    uint32_t chunk_size;
    float chunk_minz[PN_PCSS_CHUNKS];
    uint32_t chunk_subs[PN_PCSS_CHUNKS], chunk_sub_off[PN_PCSS_CHUNKS];
    uint32_t nbands;
    uint32_t *band_count; /* PN_PCSS_CHUNKS * nbands, then the write cursors */
    uint32_t *band_start; /* nbands + 1 */
    pn_pcss_tri *subs;
    uint32_t *bins;
    float *map;
    /* tap patterns in [0, 1)^2 */
    float search_pat[PN_PCSS_SEARCH_TAPS][2];
    float pcf_pat[PN_PCSS_PCF_TAPS][2];
} pn_pcss;

static float pn_pcss_minf(float a, float b) { return a < b ? a : b; }
static float pn_pcss_maxf(float a, float b) { return a > b ? a : b; }

static pn_v3 pn_pcss_to_light(const pn_pcss *s, pn_v3 X)
{
    pn_v3 d = pn_v3_sub(X, s->c);
    return pn_v3_make(pn_v3_dot(d, s->Uh), pn_v3_dot(d, s->Vh), pn_v3_dot(d, s->N));
}

/* ---- 1. frustum fit ------------------------------------------------------------------- */

static void pn_pcss_fit_rows(void *task, uint32_t begin, uint32_t end)
{
    pn_pcss *s = (pn_pcss *)task;
    const pn_gbuf *g = s->g;
    uint32_t y, x;
    for (y = begin; y < end; y++) {
        float *f = s->row_fit + (size_t)y * 5u;
        f[0] = PN_PCSS_TAN_MAX;
        f[1] = -PN_PCSS_TAN_MAX;
        f[2] = PN_PCSS_TAN_MAX;
        f[3] = -PN_PCSS_TAN_MAX;
        f[4] = -1.0f;
        for (x = 0; x < g->width; x++) {
            size_t pix = (size_t)y * g->width + x;
            pn_v3 L;
            float sx, sy;
            if (g->tri[pix] == PN_NO_TRIANGLE) continue;
            L = pn_pcss_to_light(s, pn_v3_load(g->pos + pix * 3u));
            if (!(L.z > 0.0f)) continue; /* behind the light: vis 0 by convention */
            sx = pn_pcss_maxf(-PN_PCSS_TAN_MAX, pn_pcss_minf(PN_PCSS_TAN_MAX, L.x / L.z));
            sy = pn_pcss_maxf(-PN_PCSS_TAN_MAX, pn_pcss_minf(PN_PCSS_TAN_MAX, L.y / L.z));
            f[0] = pn_pcss_minf(f[0], sx);
            f[1] = pn_pcss_maxf(f[1], sx);
            f[2] = pn_pcss_minf(f[2], sy);
            f[3] = pn_pcss_maxf(f[3], sy);
            f[4] = pn_pcss_maxf(f[4], L.z);
        }
    }
}

/* ---- 2. clipping, binning, rasterization ---------------------------------------------- */

/* Sutherland-Hodgman against a*x + b*y + cz*z + d >= 0. Returns the new vertex count. */
static int pn_pcss_clip(const pn_v3 *in, int n, pn_v3 *out, float a, float b, float cz, float d)
{
    int i, m = 0;
    for (i = 0; i < n; i++) {
        pn_v3 p = in[i], q = in[(i + 1) % n];
        float fp = a * p.x + b * p.y + cz * p.z + d, fq = a * q.x + b * q.y + cz * q.z + d;
        if (fp >= 0.0f) out[m++] = p;
        if ((fp >= 0.0f) != (fq >= 0.0f)) {
            float t = fp / (fp - fq);
            out[m++] = pn_v3_add(p, pn_v3_scale(pn_v3_sub(q, p), t));
        }
    }
    return m;
}

/* Triangle t clipped to the guard-banded window in front of znear_clip: the polygon in
 * light space, its vertex count (0: nothing in front / inside, or beyond zfar). */
static int pn_pcss_clip_tri(const pn_pcss *s, uint32_t t, pn_v3 *poly)
{
    pn_v3 tmp[PN_PCSS_POLY_MAX];
    const uint32_t *ix = s->mesh->indices + (size_t)t * 3u;
    int n = 3, v;
    float zmin, zmax;
    for (v = 0; v < 3; v++) poly[v] = pn_pcss_to_light(s, pn_v3_load(s->mesh->positions + (size_t)ix[v] * 3u));
    zmin = pn_pcss_minf(poly[0].z, pn_pcss_minf(poly[1].z, poly[2].z));
    zmax = pn_pcss_maxf(poly[0].z, pn_pcss_maxf(poly[1].z, poly[2].z));
    if (!(zmax > s->znear_clip) || !(zmin < s->zfar)) return 0; /* behind, or beyond every receiver */
    n = pn_pcss_clip(poly, n, tmp, 0.0f, 0.0f, 1.0f, -s->znear_clip);
    if (n < 3) return 0;
    n = pn_pcss_clip(tmp, n, poly, 1.0f, 0.0f, -s->gx0, 0.0f); /* x >= gx0 z */
    if (n < 3) return 0;
    n = pn_pcss_clip(poly, n, tmp, -1.0f, 0.0f, s->gx1, 0.0f); /* x <= gx1 z */
    if (n < 3) return 0;
    n = pn_pcss_clip(tmp, n, poly, 0.0f, 1.0f, -s->gy0, 0.0f);
    if (n < 3) return 0;
    n = pn_pcss_clip(poly, n, tmp, 0.0f, -1.0f, s->gy1, 0.0f);
    if (n < 3) return 0;
    memcpy(poly, tmp, (size_t)n * sizeof(pn_v3));
    return n;
}

/* Pass A: nearest clipped point and sub-triangle count per chunk. */
static void pn_pcss_count(void *task, uint32_t begin, uint32_t end)
{
    pn_pcss *s = (pn_pcss *)task;
    uint32_t ch, t;
    for (ch = begin; ch < end; ch++) {
        uint32_t t0 = ch * s->chunk_size, t1 = t0 + s->chunk_size, subs = 0;
        float zmin = PN_KINF;
        if (t1 > s->mesh->triangle_count) t1 = s->mesh->triangle_count;
        for (t = t0; t < t1; t++) {
            pn_v3 poly[PN_PCSS_POLY_MAX];
            int n = pn_pcss_clip_tri(s, t, poly), v;
            if (n < 3) continue;
            for (v = 0; v < n; v++) zmin = pn_pcss_minf(zmin, poly[v].z);
            subs += (uint32_t)(n - 2);
        }
        s->chunk_minz[ch] = zmin;
        s->chunk_subs[ch] = subs;
    }
}

static void pn_pcss_rows_of(const pn_pcss_tri *q, uint32_t *r0, uint32_t *r1)
{
    float ymin = pn_pcss_minf(q->y[0], pn_pcss_minf(q->y[1], q->y[2]));
    float ymax = pn_pcss_maxf(q->y[0], pn_pcss_maxf(q->y[1], q->y[2]));
    float a = ceilf(ymin - 0.5f), b = floorf(ymax - 0.5f);
    if (a < 0.0f) a = 0.0f;
    if (b > (float)(PN_PCSS_MAP - 1u)) b = (float)(PN_PCSS_MAP - 1u);
    if (a > b) {
        *r0 = 1u;
        *r1 = 0u;
        return;
    }
    *r0 = (uint32_t)a;
    *r1 = (uint32_t)b;
}

/* Pass B: the sub-triangles in texel space, and how many land in each band. */
static void pn_pcss_emit(void *task, uint32_t begin, uint32_t end)
{
    pn_pcss *s = (pn_pcss *)task;
    uint32_t ch, t;
    for (ch = begin; ch < end; ch++) {
        uint32_t t0 = ch * s->chunk_size, t1 = t0 + s->chunk_size, o = s->chunk_sub_off[ch];
        uint32_t *cnt = s->band_count + (size_t)ch * s->nbands;
        if (t1 > s->mesh->triangle_count) t1 = s->mesh->triangle_count;
        for (t = t0; t < t1; t++) {
            pn_v3 poly[PN_PCSS_POLY_MAX];
            float px[PN_PCSS_POLY_MAX], py[PN_PCSS_POLY_MAX], pz[PN_PCSS_POLY_MAX];
            int n = pn_pcss_clip_tri(s, t, poly), v;
            for (v = 0; v < n; v++) {
                px[v] = (poly[v].x / poly[v].z - s->sx0) / s->dsx;
                py[v] = (poly[v].y / poly[v].z - s->sy0) / s->dsy;
                pz[v] = 1.0f / poly[v].z;
            }
            for (v = 1; v + 1 < n; v++) {
                pn_pcss_tri *q = s->subs + o++;
                uint32_t r0, r1, b;
                q->x[0] = px[0], q->y[0] = py[0], q->iz[0] = pz[0];
                q->x[1] = px[v], q->y[1] = py[v], q->iz[1] = pz[v];
                q->x[2] = px[v + 1], q->y[2] = py[v + 1], q->iz[2] = pz[v + 1];
                pn_pcss_rows_of(q, &r0, &r1);
                if (r0 > r1) continue;
                for (b = r0 / PN_PCSS_BAND; b <= r1 / PN_PCSS_BAND; b++) cnt[b]++;
            }
        }
    }
}

/* Pass C: sub-triangle indices into the bands' lists (band-major, chunks in order). */
static void pn_pcss_bin(void *task, uint32_t begin, uint32_t end)
{
    pn_pcss *s = (pn_pcss *)task;
    uint32_t ch, i;
    for (ch = begin; ch < end; ch++) {
        uint32_t *cur = s->band_count + (size_t)ch * s->nbands; /* cursors after the scan */
        uint32_t i0 = s->chunk_sub_off[ch], i1 = i0 + s->chunk_subs[ch];
        for (i = i0; i < i1; i++) {
            uint32_t r0, r1, b;
            pn_pcss_rows_of(s->subs + i, &r0, &r1);
            if (r0 > r1) continue;
            for (b = r0 / PN_PCSS_BAND; b <= r1 / PN_PCSS_BAND; b++) s->bins[cur[b]++] = i;
        }
    }
}

/* Pass D: each band clears and rasterizes its rows (min depth per texel). */
static void pn_pcss_raster(void *task, uint32_t begin, uint32_t end)
{
    pn_pcss *s = (pn_pcss *)task;
    uint32_t b, i, x, y;
    for (b = begin; b < end; b++) {
        uint32_t y0 = b * PN_PCSS_BAND, y1 = y0 + PN_PCSS_BAND;
        if (y1 > PN_PCSS_MAP) y1 = PN_PCSS_MAP;
        for (i = (size_t)y0 * PN_PCSS_MAP; i < (size_t)y1 * PN_PCSS_MAP; i++) s->map[i] = PN_KINF;
        for (i = s->band_start[b]; i < s->band_start[b + 1u]; i++) {
            const pn_pcss_tri *q = s->subs + s->bins[i];
            float area = (q->x[1] - q->x[0]) * (q->y[2] - q->y[0]) - (q->y[1] - q->y[0]) * (q->x[2] - q->x[0]);
            float xmin = pn_pcss_minf(q->x[0], pn_pcss_minf(q->x[1], q->x[2]));
            float xmax = pn_pcss_maxf(q->x[0], pn_pcss_maxf(q->x[1], q->x[2]));
            float sgn, inv, ca, cb;
            uint32_t r0, r1, c0, c1;
            if (!(area != 0.0f)) continue; /* degenerate in the map (edge-on) */
            sgn = area > 0.0f ? 1.0f : -1.0f;
            inv = 1.0f / (area * sgn);
            pn_pcss_rows_of(q, &r0, &r1);
            if (r0 > r1) continue;
            if (r0 < y0) r0 = y0;
            if (r1 > y1 - 1u) r1 = y1 - 1u;
            ca = ceilf(xmin - 0.5f);
            cb = floorf(xmax - 0.5f);
            if (ca < 0.0f) ca = 0.0f;
            if (cb > (float)(PN_PCSS_MAP - 1u)) cb = (float)(PN_PCSS_MAP - 1u);
            if (ca > cb) continue;
            c0 = (uint32_t)ca;
            c1 = (uint32_t)cb;
            for (y = r0; y <= r1 && r0 <= r1; y++) {
                float py = (float)y + 0.5f;
                float *row = s->map + (size_t)y * PN_PCSS_MAP;
                for (x = c0; x <= c1; x++) {
                    float px = (float)x + 0.5f;
                    /* edge functions, each >= 0 inside whatever the winding */
                    float e0 = sgn * ((q->x[2] - q->x[1]) * (py - q->y[1]) - (q->y[2] - q->y[1]) * (px - q->x[1]));
                    float e1 = sgn * ((q->x[0] - q->x[2]) * (py - q->y[2]) - (q->y[0] - q->y[2]) * (px - q->x[2]));
                    float e2 = sgn * ((q->x[1] - q->x[0]) * (py - q->y[0]) - (q->y[1] - q->y[0]) * (px - q->x[0]));
                    float iz, z;
                    if (e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) continue;
                    iz = (e0 * q->iz[0] + e1 * q->iz[1] + e2 * q->iz[2]) * inv;
                    if (!(iz > 0.0f)) continue;
                    z = 1.0f / iz;
                    if (z < row[x]) row[x] = z;
                }
            }
        }
    }
}

/* ---- 3. per pixel --------------------------------------------------------------------- */


/* Hammersley point i of n in [0, 1)^2, cell-centred. */
static void pn_pcss_hammersley(uint32_t i, uint32_t n, float *a, float *b)
{
    uint32_t r = i;
    r = (r << 16) | (r >> 16);
    r = ((r & 0x55555555u) << 1) | ((r & 0xAAAAAAAAu) >> 1);
    r = ((r & 0x33333333u) << 2) | ((r & 0xCCCCCCCCu) >> 2);
    r = ((r & 0x0F0F0F0Fu) << 4) | ((r & 0xF0F0F0F0u) >> 4);
    r = ((r & 0x00FF00FFu) << 8) | ((r & 0xFF00FF00u) >> 8);
    *a = ((float)i + 0.5f) / (float)n;
    *b = (float)r * (1.0f / 4294967296.0f) + 0.5f / (float)n;
}


/* The receiver: depth, map position (texels), and its plane for the bias. */
typedef struct pn_pcss_rcv {
    float zr, tx, ty;
    float na, nb, nc, d0; /* plane: n_l . X = d0 in light space, n_l turned toward c */
    float bias;
} pn_pcss_rcv;

/* Depth of the receiver's plane along the light ray through texel centre (i, j), capped
 * at the receiver depth, minus the bias: a texel nearer than this blocks. */
static float pn_pcss_limit(const pn_pcss *s, const pn_pcss_rcv *r, uint32_t i, uint32_t j)
{
    float sx = s->sx0 + ((float)i + 0.5f) * s->dsx, sy = s->sy0 + ((float)j + 0.5f) * s->dsy;
    float den = r->na * sx + r->nb * sy + r->nc, zp = r->zr;
    /* The ray z (sx, sy, 1) leaves the front side of the plane at z = d0 / den when den < 0
     * (d0 < 0: c is in front); den >= 0, never. */
    if (den < 0.0f) zp = pn_pcss_minf(zp, r->d0 / den);
    return zp - r->bias;
}

static float pn_pcss_depth(const pn_pcss *s, int32_t i, int32_t j)
{
    if (i < 0 || j < 0 || i >= (int32_t)PN_PCSS_MAP || j >= (int32_t)PN_PCSS_MAP) return PN_KINF;
    return s->map[(size_t)j * PN_PCSS_MAP + (size_t)i];
}

/* 1 if texel (i, j) occludes the receiver (outside the map: no). */
static float pn_pcss_cmp(const pn_pcss *s, const pn_pcss_rcv *r, int32_t i, int32_t j)
{
    float d = pn_pcss_depth(s, i, j);
    if (d == PN_KINF) return 0.0f;
    return d < pn_pcss_limit(s, r, (uint32_t)i, (uint32_t)j) ? 1.0f : 0.0f;
}

static float pn_pcss_pixel_pcf(const pn_pcss *s, size_t pix, pn_v3 O, pn_v3 n)
{
    pn_pcss_rcv r;
    pn_v3 L = pn_pcss_to_light(s, O), nl;
    float sx, sy, hu, hv, ru, rv, zsum = 0.0f, occ = 0.0f, dz, zavg, au, bu;
    uint32_t h, t, nb = 0;
    if (!(L.z > s->near)) return 1.0f; /* at or before the near plane: nothing can block */
    r.zr = L.z;
    sx = L.x / L.z;
    sy = L.y / L.z;
    if (!(sx >= s->sx0 && sx <= s->sx1 && sy >= s->sy0 && sy <= s->sy1)) return 1.0f; /* outside the map */
    r.tx = (sx - s->sx0) / s->dsx;
    r.ty = (sy - s->sy0) / s->dsy;
    /* the receiver's plane in light space, normal turned toward the light centre */
    nl = pn_v3_make(pn_v3_dot(n, s->Uh), pn_v3_dot(n, s->Vh), pn_v3_dot(n, s->N));
    r.d0 = pn_v3_dot(nl, L);
    if (r.d0 > 0.0f) {
        nl = pn_v3_scale(nl, -1.0f);
        r.d0 = -r.d0;
    }
    r.na = nl.x;
    r.nb = nl.y;
    r.nc = nl.z;
    /* depth change of the plane across one texel: |dz/dsx| dsx + |dz/dsy| dsy, where
     * dz/dsx = -z a / den at the receiver (den = d0 / z) */
    {
        float den = r.d0 / r.zr;
        dz = den < 0.0f ? r.zr * (fabsf(nl.x) * s->dsx + fabsf(nl.y) * s->dsy) / -den : PN_KINF;
        dz = pn_pcss_minf(dz, PN_PCSS_SLOPE_MAX * r.zr);
    }
    r.bias = PN_PCSS_BIAS_CONST * r.zr + PN_PCSS_BIAS_SLOPE * dz;

    /* blocker search: the light's rectangle seen from O, on the near plane */
    hu = s->ulen * (r.zr - s->near) / (r.zr * s->near) / s->dsx;
    hv = s->vlen * (r.zr - s->near) / (r.zr * s->near) / s->dsy;
    hu = pn_pcss_minf(hu, 2.0f * (float)PN_PCSS_MAP); /* beyond the map either way */
    hv = pn_pcss_minf(hv, 2.0f * (float)PN_PCSS_MAP);
    h = pn_hash32((uint32_t)pix * 2u + 1u);
    au = (float)(h & 0xFFFFu) * (1.0f / 65536.0f);
    bu = (float)(h >> 16) * (1.0f / 65536.0f);
    for (t = 0; t < PN_PCSS_SEARCH_TAPS; t++) {
        float a = s->search_pat[t][0] + au, b = s->search_pat[t][1] + bu, d;
        int32_t i, j;
        if (a >= 1.0f) a -= 1.0f;
        if (b >= 1.0f) b -= 1.0f;
        i = (int32_t)floorf(r.tx + (2.0f * a - 1.0f) * hu);
        j = (int32_t)floorf(r.ty + (2.0f * b - 1.0f) * hv);
        d = pn_pcss_depth(s, i, j);
        if (d != PN_KINF && d < pn_pcss_limit(s, &r, (uint32_t)i, (uint32_t)j)) {
            zsum += d;
            nb++;
        }
    }
    if (nb == 0u) return 1.0f;
    zavg = zsum / (float)nb;

    /* penumbra width at the receiver, w = (z_r - z_avg) |u| / z_avg, as a filter
     * half-extent on the map: w near / z_r on the near plane = w / z_r tangent units */
    ru = s->ulen * (r.zr - zavg) / (zavg * r.zr) / s->dsx;
    rv = s->vlen * (r.zr - zavg) / (zavg * r.zr) / s->dsy;
    ru = pn_pcss_maxf(1.0f, pn_pcss_minf(ru, hu));
    rv = pn_pcss_maxf(1.0f, pn_pcss_minf(rv, hv));

    /* PCF: bilinear 2x2 comparisons */
    h = pn_hash32((uint32_t)pix * 2u + 2u);
    au = (float)(h & 0xFFFFu) * (1.0f / 65536.0f);
    bu = (float)(h >> 16) * (1.0f / 65536.0f);
    for (t = 0; t < PN_PCSS_PCF_TAPS; t++) {
        float a = s->pcf_pat[t][0] + au, b = s->pcf_pat[t][1] + bu;
        float fx, fy, x0f, y0f, wx, wy, o;
        int32_t i, j;
        if (a >= 1.0f) a -= 1.0f;
        if (b >= 1.0f) b -= 1.0f;
        fx = r.tx + (2.0f * a - 1.0f) * ru - 0.5f;
        fy = r.ty + (2.0f * b - 1.0f) * rv - 0.5f;
        x0f = floorf(fx);
        y0f = floorf(fy);
        wx = fx - x0f;
        wy = fy - y0f;
        i = (int32_t)x0f;
        j = (int32_t)y0f;
        o = (1.0f - wy) * ((1.0f - wx) * pn_pcss_cmp(s, &r, i, j) + wx * pn_pcss_cmp(s, &r, i + 1, j)) +
            wy * ((1.0f - wx) * pn_pcss_cmp(s, &r, i, j + 1) + wx * pn_pcss_cmp(s, &r, i + 1, j + 1));
        occ += o;
    }
    if (occ == 0.0f) return 1.0f;
    return pn_pcss_maxf(0.0f, 1.0f - occ / (float)PN_PCSS_PCF_TAPS);
}

static void pn_pcss_rows(void *task, uint32_t begin, uint32_t end)
{
    pn_pcss *s = (pn_pcss *)task;
    const pn_gbuf *g = s->g;
    uint32_t y, x;
    for (y = begin; y < end; y++)
        for (x = 0; x < g->width; x++) {
            size_t pix = (size_t)y * g->width + x;
            uint32_t m[PN_MASK_WORDS_MAX], own = g->tri[pix];
            pn_v3 P, n, O;
            float pcf = 1.0f;
            if (own == PN_NO_TRIANGLE) {
                s->vis[pix] = 1.0f;
                continue;
            }
            P = pn_v3_load(g->pos + pix * 3u);
            n = pn_v3_load(g->nrm + pix * 3u);
            if (!pn_shadow_origin(P, n, &s->kl, &O)) {
                s->vis[pix] = 0.0f;
                continue;
            }
            pn_mask_clear(m);
            {
                /* the horizon of the own triangle, as pn_horizon_of applies it */
                const uint32_t *ix = s->mesh->indices + (size_t)own * 3u;
                pn_horizon H;
                pn_horizon_make(P, n, pn_v3_load(s->mesh->positions + (size_t)ix[0] * 3u),
                                pn_v3_load(s->mesh->positions + (size_t)ix[1] * 3u),
                                pn_v3_load(s->mesh->positions + (size_t)ix[2] * 3u), &s->kl, &H);
                pn_horizon_mask(&H, &s->kl, m);
            }
            if (s->have_map) pcf = pn_pcss_pixel_pcf(s, pix, O, n);
            s->vis[pix] = pcf == 1.0f ? pn_mask_visibility(m, s->kl.k) : pcf * pn_mask_visibility(m, s->kl.k);
        }
}

/* ---- the pass ------------------------------------------------------------------------- */

static void pn_pcss_free(pn_pcss *s)
{
    free(s->row_fit);
    free(s->band_count);
    free(s->band_start);
    free(s->subs);
    free(s->bins);
    free(s->map);
}

/* Builds the map (fit, near plane, clip, bin, raster). Returns 0, 1 on allocation failure. */
static int pn_pcss_build(pn_pcss *s, pn_threads *threads)
{
    const pn_gbuf *g = s->g;
    uint32_t y, ch, b, nch, total = 0;
    float fit[5] = {PN_PCSS_TAN_MAX, -PN_PCSS_TAN_MAX, PN_PCSS_TAN_MAX, -PN_PCSS_TAN_MAX, -1.0f};
    float w, h, zmin;
    pn_threads_parallel_for(threads, g->height, pn_pcss_fit_rows, s);
    for (y = 0; y < g->height; y++) {
        const float *f = s->row_fit + (size_t)y * 5u;
        fit[0] = pn_pcss_minf(fit[0], f[0]);
        fit[1] = pn_pcss_maxf(fit[1], f[1]);
        fit[2] = pn_pcss_minf(fit[2], f[2]);
        fit[3] = pn_pcss_maxf(fit[3], f[3]);
        fit[4] = pn_pcss_maxf(fit[4], f[4]);
    }
    if (!(fit[4] > 0.0f) || s->mesh->triangle_count == 0u) return 0; /* no receiver in front: no map */
    w = pn_pcss_maxf(fit[1] - fit[0], 1e-4f);
    h = pn_pcss_maxf(fit[3] - fit[2], 1e-4f);
    s->sx0 = fit[0] - PN_PCSS_PAD * w;
    s->sx1 = fit[1] + PN_PCSS_PAD * w;
    s->sy0 = fit[2] - PN_PCSS_PAD * h;
    s->sy1 = fit[3] + PN_PCSS_PAD * h;
    s->dsx = (s->sx1 - s->sx0) / (float)PN_PCSS_MAP;
    s->dsy = (s->sy1 - s->sy0) / (float)PN_PCSS_MAP;
    s->gx0 = s->sx0 - PN_PCSS_GUARD * s->dsx;
    s->gx1 = s->sx1 + PN_PCSS_GUARD * s->dsx;
    s->gy0 = s->sy0 - PN_PCSS_GUARD * s->dsy;
    s->gy1 = s->sy1 + PN_PCSS_GUARD * s->dsy;
    /* O may lie eps deeper than the farthest G-buffer point */
    s->zfar = fit[4] * 1.01f;
    s->znear_clip = PN_PCSS_NEAR_MIN * fit[4];

    s->chunk_size = (s->mesh->triangle_count + PN_PCSS_CHUNKS - 1u) / PN_PCSS_CHUNKS;
    nch = (s->mesh->triangle_count + s->chunk_size - 1u) / s->chunk_size;
    pn_threads_parallel_for(threads, nch, pn_pcss_count, s);
    zmin = PN_KINF;
    for (ch = 0; ch < nch; ch++) {
        s->chunk_sub_off[ch] = total;
        total += s->chunk_subs[ch];
        zmin = pn_pcss_minf(zmin, s->chunk_minz[ch]);
    }
    s->near = zmin == PN_KINF ? s->znear_clip : pn_pcss_maxf(zmin, s->znear_clip);

    s->nbands = (PN_PCSS_MAP + PN_PCSS_BAND - 1u) / PN_PCSS_BAND;
    s->band_count = (uint32_t *)calloc((size_t)nch * s->nbands, sizeof(uint32_t));
    s->band_start = (uint32_t *)calloc((size_t)s->nbands + 1u, sizeof(uint32_t));
    s->subs = (pn_pcss_tri *)malloc((size_t)(total ? total : 1u) * sizeof(pn_pcss_tri));
    if (!s->band_count || !s->band_start || !s->subs) return 1;
    pn_threads_parallel_for(threads, nch, pn_pcss_emit, s);
    /* band-major scan; the counts become each (chunk, band)'s write cursor */
    {
        uint64_t run = 0;
        for (b = 0; b < s->nbands; b++) {
            s->band_start[b] = (uint32_t)run;
            for (ch = 0; ch < nch; ch++) {
                uint32_t c = s->band_count[(size_t)ch * s->nbands + b];
                s->band_count[(size_t)ch * s->nbands + b] = (uint32_t)run;
                run += c;
            }
        }
        if (run > 0xFFFFFFFFu) return 1;
        s->band_start[s->nbands] = (uint32_t)run;
        s->bins = (uint32_t *)malloc((size_t)(run ? run : 1u) * sizeof(uint32_t));
        if (!s->bins) return 1;
    }
    pn_threads_parallel_for(threads, nch, pn_pcss_bin, s);
    pn_threads_parallel_for(threads, s->nbands, pn_pcss_raster, s);
    s->have_map = 1;
    return 0;
}

int pn_pcss_shadow(const pn_mesh *mesh, const pn_gbuf *g, const pn_light *light, uint32_t k, float eps,
                   pn_threads *threads, float *vis, double *ms, char *err, size_t err_size)
{
    pn_pcss s;
    pn_v3 U, V, X;
    uint64_t t0;
    uint32_t t;
    int rc;
    if (k < 1u || k > PN_MASK_K_MAX) {
        pn_tools_err(err, err_size, "PCSS: k = %u outside 1..%u", k, (unsigned)PN_MASK_K_MAX);
        return 1;
    }
    U = pn_v3_make(light->u[0], light->u[1], light->u[2]);
    V = pn_v3_make(light->v[0], light->v[1], light->v[2]);
    X = pn_v3_cross(U, V);
    if (!(pn_v3_dot(X, X) > 0.0f) || !isfinite(pn_v3_dot(X, X)) || !isfinite(light->center[0] + light->center[1] + light->center[2])) {
        pn_tools_err(err, err_size, "PCSS: degenerate light (a point light has no penumbra to estimate)");
        return 1;
    }
    memset(&s, 0, sizeof(s));
    for (t = 0; t < PN_PCSS_SEARCH_TAPS; t++)
        pn_pcss_hammersley(t, PN_PCSS_SEARCH_TAPS, &s.search_pat[t][0], &s.search_pat[t][1]);
    for (t = 0; t < PN_PCSS_PCF_TAPS; t++)
        pn_pcss_hammersley(t, PN_PCSS_PCF_TAPS, &s.pcf_pat[t][0], &s.pcf_pat[t][1]);
    s.mesh = mesh;
    s.g = g;
    s.vis = vis;
    pn_bench_klight(light, k, eps, 0.0f, &s.kl);
    s.c = pn_v3_make(light->center[0], light->center[1], light->center[2]);
    s.N = pn_v3_make(s.kl.N[0], s.kl.N[1], s.kl.N[2]);
    s.ulen = sqrtf(pn_v3_dot(U, U));
    s.vlen = sqrtf(pn_v3_dot(V, V));
    s.Uh = pn_v3_scale(U, 1.0f / s.ulen);
    s.Vh = pn_v3_scale(V, 1.0f / s.vlen);
    s.row_fit = (float *)malloc((size_t)(g->height ? g->height : 1u) * 5u * sizeof(float));
    s.map = (float *)malloc((size_t)PN_PCSS_MAP * PN_PCSS_MAP * sizeof(float));
    if (!s.row_fit || !s.map) {
        pn_pcss_free(&s);
        pn_tools_err(err, err_size, "PCSS: out of memory");
        return 1;
    }
    t0 = pn_threads_now_ns(NULL);
    rc = pn_pcss_build(&s, threads);
    if (rc == 0) pn_threads_parallel_for(threads, g->height, pn_pcss_rows, &s);
    *ms = (double)(pn_threads_now_ns(NULL) - t0) / 1e6;
    pn_pcss_free(&s);
    if (rc != 0) {
        pn_tools_err(err, err_size, "PCSS: out of memory (shadow-map triangle lists)");
        return 1;
    }
    return 0;
}
