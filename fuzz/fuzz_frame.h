/* fuzz_frame.h - a small random scene and frame from a fuzzer's bytes: the input format of
 * fuzz_crossport and fuzz_culls (so each can seed the other's corpus).
 *
 * Input (bytes past the end read as zero):
 *   0 algorithm (any pn_algo; fuzz_culls reads it as its step)  1 bit 0 point light, bit 1
 *     exact_stats, bit 7 occlusion textures' leak fix and the Monte Carlo blur off,
 *     bit 2 ground quad, bits 3-4 GEARS pair pool (default, 64, 12, 3: tiles, split rows,
 *     PN_E_POOL_EXHAUSTED; fuzz_crossport's), bit 5 unit-grid scene scale 1e-3, bit 6 scale 1e3
 *   2 k (4 << n)   3 GEARS grid 1 .. 64 (also the occlusion textures' and Monte Carlo options;
 *     an odd grid with the ground quad marks the quad receiver-only)   4 width 1 .. 24
 *   5 height 1 .. 24
 *   6 vertex count 3 .. 34   7 triangle count 1 .. 32
 *   then 16-bit numbers: camera eye (3), fov; light centre (3), half-edge lengths (2) and
 *   the angle of U about the vertical; vertices (3 each, in [-1, 1)); then one byte per
 *   triangle corner: a vertex index (indices repeat, so edges are shared).
 * The ground quad, when on, is two triangles under the scene; the light is above it and
 * faces down, the camera looks at the origin. */
#ifndef FUZZ_FRAME_H
#define FUZZ_FRAME_H

#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "penumbra/penumbra.h"

#define FUZZ_MAX_V 34u
#define FUZZ_MAX_T 34u
#define FUZZ_MAX_W 24u
#define FUZZ_MAX_H 24u

typedef struct fuzz_frame {
    uint32_t algo, flags, grid, nv, nt;
    float pos[(FUZZ_MAX_V + 4u) * 3u];
    uint32_t idx[FUZZ_MAX_T * 3u];
    int receivers; /* the ground quad (the last two triangles) receiver-only */
    pn_camera cam;
    pn_light light;
    pn_frame_options opt; /* every algorithm's options set from the grid byte */
} fuzz_frame;

/* [-1, 1) in steps of 2^-15. */
static float fuzz_num(fuzz_rd *r)
{
    uint32_t hi = fuzz_byte(r), lo = fuzz_byte(r); /* two statements: operand order is unspecified */
    return (float)((int32_t)((hi << 8) | lo) - 32768) / 32768.0f;
}

static void fuzz_frame_decode(const uint8_t *data, size_t size, fuzz_frame *f)
{
    fuzz_rd r = {data, size, 0};
    uint32_t k, w, h, i, q, grid, flags;
    float scale, ang, su, sv;
    f->algo = fuzz_byte(&r);
    flags = f->flags = fuzz_byte(&r);
    k = 4u << (fuzz_byte(&r) % 4u);
    grid = f->grid = 1u + fuzz_byte(&r) % 64u;
    w = 1u + fuzz_byte(&r) % FUZZ_MAX_W;
    h = 1u + fuzz_byte(&r) % FUZZ_MAX_H;
    f->nv = 3u + fuzz_byte(&r) % (FUZZ_MAX_V - 2u);
    f->nt = 1u + fuzz_byte(&r) % (FUZZ_MAX_T - 2u);
    scale = (flags & 32u) ? 1e-3f : (flags & 64u) ? 1e3f : 1.0f;

    /* Camera around the origin, light above, both scaled with the scene. */
    for (q = 0; q < 3; q++) f->cam.eye[q] = scale * 3.0f * fuzz_num(&r);
    f->cam.eye[1] = scale * (1.0f + 2.0f * (fuzz_num(&r) + 1.0f));
    memset(f->cam.target, 0, sizeof(f->cam.target));
    f->cam.up[0] = 0.0f;
    f->cam.up[1] = 1.0f;
    f->cam.up[2] = 0.0f;
    f->cam.fov_deg = 20.0f + 40.0f * (fuzz_num(&r) + 1.0f);
    f->light.center[0] = scale * fuzz_num(&r);
    f->light.center[1] = scale * (1.5f + fuzz_num(&r) + 1.0f);
    f->light.center[2] = scale * fuzz_num(&r);
    su = scale * (0.01f + 0.5f * (fuzz_num(&r) + 1.0f));
    sv = scale * (0.01f + 0.5f * (fuzz_num(&r) + 1.0f));
    ang = 3.0f * fuzz_num(&r);
    {
        /* U rotated about y by about ang radians (a cubic, no libm); V = N x U with N down. */
        float c = 1.0f - ang * ang / 2.0f, s = ang - ang * ang * ang / 6.0f, len;
        len = c * c + s * s;
        c /= len;
        s /= len;
        f->light.u[0] = su * c;
        f->light.u[1] = 0.0f;
        f->light.u[2] = su * s;
        f->light.v[0] = -sv * s; /* (0,-1,0) x (c,0,s) = (-s, 0, c) */
        f->light.v[1] = 0.0f;
        f->light.v[2] = sv * c;
    }
    if (flags & 1u) {
        memset(f->light.u, 0, sizeof(f->light.u));
        memset(f->light.v, 0, sizeof(f->light.v));
    }
    for (i = 0; i < f->nv * 3u; i++) f->pos[i] = scale * fuzz_num(&r);
    for (i = 0; i < f->nt * 3u; i++) f->idx[i] = fuzz_byte(&r) % f->nv;
    f->receivers = 0;
    if (flags & 4u) { /* ground quad below everything */
        static const float gq[12] = {-3, -1.5f, -3, 3, -1.5f, -3, 3, -1.5f, 3, -3, -1.5f, 3};
        static const uint32_t gi[6] = {0, 2, 1, 0, 3, 2};
        for (i = 0; i < 12u; i++) f->pos[f->nv * 3u + i] = scale * gq[i];
        for (i = 0; i < 6u; i++) f->idx[f->nt * 3u + i] = f->nv + gi[i];
        f->nv += 4u;
        f->nt += 2u;
        f->receivers = (grid & 1u) != 0u;
    }

    pn_frame_options_default(&f->opt);
    f->opt.width = w;
    f->opt.height = h;
    f->opt.k = k;
    f->opt.algo = (pn_algo)(f->algo % PN_ALGO_COUNT);
    f->opt.gears.grid = grid;
    f->opt.exact_stats = (flags >> 1) & 1u;
    /* Occlusion textures: every filter, combination and slice count from the grid byte. */
    f->opt.occtex.filter = 1u + (grid - 1u) % 3u;
    f->opt.occtex.combine = 1u + ((grid - 1u) / 3u) % 3u;
    f->opt.occtex.slices = 2u + ((grid - 1u) / 9u) % 15u;
    f->opt.occtex.flags = ((flags >> 7) ? PN_OCC_LEAK_FIX : 0u) | (((grid - 1u) / 135u) & 1u ? PN_OCC_PAPER_FADE : 0u);
    /* Monte Carlo shadow maps: every layer count, search and ray count, blur radius and flag. */
    f->opt.mcsm.layers = 1u + (grid - 1u) % 3u;
    f->opt.mcsm.search = 1u + ((grid - 1u) / 3u) % 2u;
    f->opt.mcsm.rays = 1u + ((grid - 1u) / 6u) % 8u;
    f->opt.mcsm.blur = (flags >> 7) ? PN_MC_BLUR_OFF : 1u + (grid - 1u) % 8u;
    f->opt.mcsm.flags = ((grid - 1u) / 2u) % 8u; /* PN_MC_NO_BIAS, _NO_CLASSIFY, _NO_STACKED */
    f->opt.mcsm.seed = grid;
    /* Penumbra wedges: both modes, with and without the culls (PN_WG_NO_CULL). */
    f->opt.wedges.mode = 1u + (grid & 1u);
    f->opt.wedges.flags = ((grid >> 1) & 1u) ? PN_WG_NO_CULL : 0u;
    f->opt.eps = 1e-4f * scale;
}

/* The frame's scene into ctx (and its receivers); the status of the first call that fails. */
static pn_status fuzz_frame_scene(pn_context *ctx, const fuzz_frame *f)
{
    pn_status st = pn_scene_set(ctx, f->pos, f->nv, f->idx, f->nt);
    if (st == PN_OK && f->receivers) st = pn_scene_set_receivers(ctx, f->nt - 2u, 2u);
    return st;
}

#endif
