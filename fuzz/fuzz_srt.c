/* fuzz_srt.c - selective ray tracing's conservative steps (issue 53) against brute force, on a
 * random light view, random triangles and a random map of at most 64^2 texels.
 *
 * Input (bytes past the end read as zero):
 *   0 map res 8 .. 64   1 bits 0-2: the view's tan_half 2^(b - 4); bits 3-7: the scale
 *   2^(3 e - 22) for e = b % 16 (tiny to huge scenes)
 *   2-4 the light axis (signed bytes; zero: straight down)   5-7 the light centre (signed
 *   bytes times the scale)   8 znear = the scale times 2^-(b % 24)
 *   9 triangles (b % 9), then 18 bytes each: nine coordinates, a 16-bit signed word each
 *   times the scale / 1024 (slivers, shared vertices and points on texel edges are cheap)
 *   then the map's parameters: the depth threshold b / 64 times the scale, the reaches
 *   along U and V (texels per unit weight) b times the scale / 8
 *   then two bytes a texel, row by row: the first below 40 an empty texel (+inf), below 44
 *   a zero depth, else depth ((first - 44) + second / 256) times the scale / 16; the second's
 *   low three bits a triangle id (for the slope allowance) when below the count, else none
 *   then receivers, 3 bytes each (at most 64): the texel, and depth (b + 1) / 16 times the
 *   scale.
 *
 * - The conservative raster (pn_srt_conservative): every texel a thin triangle
 *   (pn_srt_thin) touches holds a mark of at least its weight 1/zmin. Brute force: points
 *   on the triangle (a grid over it and along its edges) projected as the classification
 *   projects a shadow-ray origin (pn_to_camera, pn_project_camera), where that projection's
 *   own rounding stays under half a texel.
 * - The penumbra mask of an area light (pn_srt_tile, pn_srt_sweep by rows then columns, the
 *   largest weight, pn_srt_masked): a receiver at depth z in texel t is in the mask when
 *   any texel e of splat weight w (pn_srt_texel_weight: an edge texel or a thin mark)
 *   reaches it: w above the receiver's weight cz and, along each axis, |e - t| - 1 <=
 *   reach (w - cz) + 1 texels (the splat plus a texel each side for rounding). */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "pn_internal.h"
#include "pn_srt.h"

#define RMAX 64u
#define TMAX 8u
#define QMAX 64u
#define TILES_MAX ((RMAX + PN_SRT_TILE - 1u) / PN_SRT_TILE)

static float depth[RMAX * RMAX], wt[RMAX * RMAX], tris[TMAX * 9u];
static uint32_t ids[RMAX * RMAX], cons[RMAX * RMAX];
static uint32_t tile_w[TILES_MAX * TILES_MAX], tile_h[TILES_MAX * TILES_MAX], tile_mask[TILES_MAX * TILES_MAX];
static uint8_t flags[TMAX];

static float sbyte(fuzz_rd *r) { return (float)(int8_t)fuzz_byte(r); }

static float maxabs3(pn_v3 v) { return fmaxf(fabsf(v.x), fmaxf(fabsf(v.y), fabsf(v.z))); }

/* Point P of triangle t: its texel, when it projects into the map in front of the near
 * plane and the projection's own rounding (error bound eps on P and the eye) moves it less
 * than half a texel, must hold a mark of at least w. */
static void check_point(const pn_kview *lv, uint32_t t, pn_v3 P, float eps, float w)
{
    uint32_t res = lv->width;
    pn_v3 c = pn_to_camera(lv, P);
    float px, py, slack;
    uint32_t tx, ty, got;
    if (!(c.z >= lv->znear)) return;
    pn_project_camera(lv, c, &px, &py);
    if (!(px >= 0.0f && py >= 0.0f && px < (float)res && py < (float)res)) return;
    /* d(px) <= res / (2 tan z) (|dx| + |x / z| |dz|), |x / z| <= tan inside the map. */
    slack = (float)res / (2.0f * lv->tan_half * c.z) * eps * (1.0f + lv->tan_half);
    if (!(slack < 0.5f)) return;
    tx = (uint32_t)px;
    ty = (uint32_t)py;
    got = cons[(size_t)ty * res + tx];
    FUZZ_CHECK(pn_kbitsf(got) >= w, "res %u thin triangle %u: texel (%u, %u) at (%g, %g) holds %g, its weight %g", res, t,
               tx, ty, (double)px, (double)py, (double)pn_kbitsf(got), (double)w);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_rd r = {data, size, 0};
    uint32_t res = 8u + fuzz_byte(&r) % (RMAX - 7u), b1 = fuzz_byte(&r), ntri, tiles, i, x, y, nq, count = 0u, texels = 0u;
    uint32_t wmax_bits = 0u;
    float tan_half = ldexpf(1.0f, (int)(b1 & 7u) - 4), scale = ldexpf(1.0f, 3 * (int)((b1 >> 3) % 16u) - 22);
    pn_kview lv;
    pn_v3 f, rt, up, eye;
    pn_srt_args a;

    /* The light view: the frame's light_view with a random axis, centre, window and near plane. */
    f = pn_v3_make(sbyte(&r), sbyte(&r), sbyte(&r));
    f = pn_v3_dot(f, f) > 0.0f ? pn_v3_normalize(f) : pn_v3_make(0.0f, -1.0f, 0.0f);
    up = (f.y > 0.9f || f.y < -0.9f) ? pn_v3_make(1.0f, 0.0f, 0.0f) : pn_v3_make(0.0f, 1.0f, 0.0f);
    rt = pn_v3_normalize(pn_v3_cross(f, up));
    up = pn_v3_cross(rt, f);
    eye = pn_v3_make(sbyte(&r) * scale, sbyte(&r) * scale, sbyte(&r) * scale);
    memset(&lv, 0, sizeof(lv));
    lv.eye[0] = eye.x, lv.eye[1] = eye.y, lv.eye[2] = eye.z;
    lv.f[0] = f.x, lv.f[1] = f.y, lv.f[2] = f.z;
    lv.r[0] = rt.x, lv.r[1] = rt.y, lv.r[2] = rt.z;
    lv.u[0] = up.x, lv.u[1] = up.y, lv.u[2] = up.z;
    lv.tan_half = tan_half;
    lv.aspect = 1.0f;
    lv.znear = ldexpf(scale, -(int)(fuzz_byte(&r) % 24u));
    lv.width = res;
    lv.height = res;

    /* Triangles, flagged degenerate as pn_scene_set flags them. */
    ntri = fuzz_byte(&r) % (TMAX + 1u);
    for (i = 0; i < ntri * 9u; i++) {
        uint32_t lo = fuzz_byte(&r), hi = fuzz_byte(&r);
        tris[i] = (float)(int16_t)(uint16_t)(lo | hi << 8) * scale / 1024.0f;
    }
    for (i = 0; i < ntri; i++) {
        const float *p = tris + i * 9u;
        pn_v3 A = pn_v3_make(p[0], p[1], p[2]), B = pn_v3_make(p[3], p[4], p[5]), C = pn_v3_make(p[6], p[7], p[8]);
        flags[i] = pn_normal_ok(pn_tri_cross(A, B, C)) ? 0u : (uint8_t)PN_TRI_DEGENERATE;
    }

    /* The conservative raster, then every thin triangle's points against its marks. */
    memset(cons, 0, sizeof(cons));
    for (i = 0; i < ntri; i++) pn_srt_conservative(&lv, tris, flags, i, cons, &count, &texels);
    for (i = 0; i < ntri; i++) {
        const float *p = tris + i * 9u;
        pn_v3 A = pn_v3_make(p[0], p[1], p[2]), B = pn_v3_make(p[3], p[4], p[5]), C = pn_v3_make(p[6], p[7], p[8]);
        pn_v3 AB = pn_v3_sub(B, A), AC = pn_v3_sub(C, A), BC = pn_v3_sub(C, B);
        pn_poly poly;
        float w, eps;
        uint32_t u, v;
        const uint32_t N = 48u, E = 512u;
        if (!pn_srt_thin(&lv, tris, flags, i, &poly, &w)) continue;
        /* A sample's error: a few roundings of its largest coordinate or the eye's. */
        eps = ldexpf(fmaxf(fmaxf(maxabs3(A), maxabs3(B)), fmaxf(maxabs3(C), maxabs3(eye))), -20);
        for (u = 0; u <= N; u++)
            for (v = 0; u + v <= N; v++)
                check_point(&lv, i, pn_v3_add(A, pn_v3_add(pn_v3_scale(AB, (float)u / (float)N), pn_v3_scale(AC, (float)v / (float)N))),
                            eps, w);
        for (u = 0; u <= E; u++) {
            float s = (float)u / (float)E;
            check_point(&lv, i, pn_v3_add(A, pn_v3_scale(AB, s)), eps, w);
            check_point(&lv, i, pn_v3_add(A, pn_v3_scale(AC, s)), eps, w);
            check_point(&lv, i, pn_v3_add(B, pn_v3_scale(BC, s)), eps, w);
        }
    }

    /* The map: random depths and triangles, the thin marks above. */
    memset(&a, 0, sizeof(a));
    a.delta = (float)fuzz_byte(&r) / 64.0f * scale;
    a.alpha = 2.0f * tan_half / (float)res;
    a.reach_u = (float)fuzz_byte(&r) * scale / 8.0f;
    a.reach_v = (float)fuzz_byte(&r) * scale / 8.0f;
    tiles = (res + PN_SRT_TILE - 1u) / PN_SRT_TILE;
    a.tiles = tiles;
    for (i = 0; i < res * res; i++) {
        uint32_t d0 = fuzz_byte(&r), d1 = fuzz_byte(&r);
        depth[i] = d0 < 40u ? PN_KINF : d0 < 44u ? 0.0f : ((float)(d0 - 44u) + (float)d1 / 256.0f) * scale / 16.0f;
        ids[i] = (d1 & 7u) < ntri && depth[i] < PN_KINF ? (d1 & 7u) : 0xFFFFFFFFu;
    }

    /* The penumbra mask as the frame builds it. */
    for (i = 0; i < tiles * tiles; i++)
        pn_srt_tile(&lv, a.delta, a.alpha, depth, ids, tris, cons, i, tiles, tile_w, &wmax_bits);
    a.wmax = pn_kbitsf(wmax_bits);
    for (i = 0; i < tiles; i++) pn_srt_sweep(tile_w, tile_h, i * tiles, 1u, tiles, a.reach_u);
    for (i = 0; i < tiles; i++) pn_srt_sweep(tile_h, tile_mask, i, tiles, tiles, a.reach_v);
    for (i = 0; i < res * res; i++) wt[i] = pn_srt_texel_weight(&lv, a.delta, a.alpha, depth, ids, tris, cons, i % res, i / res);

    nq = (uint32_t)(size > r.i ? (size - r.i) / 3u : 0u);
    if (nq > QMAX) nq = QMAX;
    for (i = 0; i < nq; i++) {
        uint32_t tx = fuzz_byte(&r) % res, ty = fuzz_byte(&r) % res;
        float z = (float)(fuzz_byte(&r) + 1u) / 16.0f * scale, cz = pn_srt_receiver_w(z);
        uint32_t masked = pn_srt_masked(&a, tile_w, tile_mask, tx, ty, z);
        if (masked) continue;
        for (y = 0; y < res; y++)
            for (x = 0; x < res; x++) {
                float w = wt[(size_t)y * res + x];
                float gx = (float)(x > tx ? x - tx : tx - x) - 1.0f, gy = (float)(y > ty ? y - ty : ty - y) - 1.0f;
                if (!(w > cz)) continue;
                FUZZ_CHECK(!(gx <= a.reach_u * (w - cz) + 1.0f && gy <= a.reach_v * (w - cz) + 1.0f),
                           "res %u receiver texel (%u, %u) depth %g outside the mask, reached by texel (%u, %u) of weight %g "
                           "(reach %g, %g)",
                           res, tx, ty, (double)z, x, y, (double)w, (double)a.reach_u, (double)a.reach_v);
            }
    }
    return 0;
}
