/* fuzz_scene.c - pn_init, pn_scene_set and pn_render on a hostile scene and frame.
 *
 * Input: a 16-byte header, then raw little-endian payload read straight from the bytes
 * (so NaN, Inf, huge, subnormal values and out-of-range indices all occur); bytes past
 * the end read as zero.
 *   0 vertex count % 65     1 triangle count % 65    2 width % 25    3 height % 25
 *   4 k (raw)               5 arena misalignment & 63; bits 6..7 the BVH's split
 *     reserve (limits.bvh_refs): 0 the default, 1 none (max_triangles), 2 max_triangles
 *     + 1 + byte 9 % 64, at most the default (short: the build drops its cap), 3 one
 *     above the default (pn_arena_size and pn_init refuse it: PN_E_LIMIT)
 *   6 flags: 1 positions NULL, 2 indices NULL, 4 skip pn_scene_set, 8 arena 1 byte
 *     short, 16 indices taken modulo the vertex count, 32 limits from bytes 8..10,
 *     64 first render under the reversed schedule (the second always uses the other)
 *   7 algo: low 3 bits below 0xF0, else the raw byte   8..10 limits - 1 (% 64, % 24, % 24)
 *   GEARS builds: 11 gears.grid, 12..13 limits.gears_pairs (u16), 14 limits.gears_grid_max,
 *   15 bit 0 exact_stats (0 in a limit means the default); SRT builds: bits 1..7 the map limit
 *   8 + n % 57; occlusion-texture builds: the same bits the texture limit, and 11 slices
 *   % 18, 12 filter % 5, 13 combination % 5, 14 flags & 3 (out-of-range values included);
 *   Monte Carlo builds: the same bits the layers' limit, 11 layers % 5, 12 search % 4, 13 rays
 *   % 10, 14 bits 0..2 flags, bits 3..7 blur % 11 (31: off); 6 bit 128: the second half of
 *   the triangles receiver-only (pn_scene_set_receivers), and a call out of range first;
 *   penumbra-wedge builds: 12 % 4 the mode (3 invalid), 13 x 16 the pair pool (0: default);
 *   algo 6 is PN_ALGO_WEDGES
 *   then floats: eye[3] target[3] up[3] fov, light c[3] u[3] v[3], eps albedo ambient;
 *   4 background bytes; vertex count * 3 floats; triangle count * 3 uint32 indices.
 *
 * Invariants (penumbra.h trust model): a status is PN_OK exactly when the input is
 * valid, and otherwise names a cause present in the input (never PN_E_INTERNAL or a
 * status the function does not document; PN_E_POOL_EXHAUSTED only for algorithms whose
 * pools may not fit a frame, never the wedges with their default pair pool); failures leave a message and do not touch out-parameters;
 * the library writes only inside the block it was given; caller arrays
 * are unchanged; a frame has visibility in {0, 1/k^2, ..., 1} (occlusion textures, Monte
 * Carlo shadow maps and penumbra wedges: in [0, 1]), background pixels at
 * visibility 1 / PN_NO_TRIANGLE / +inf depth / the background colour, ids below the
 * triangle count and unit normals; and rendering again, after scribbling over the
 * caller's arrays and under a reversed work-item schedule, gives the same bytes. Within
 * a few ulps of a numeric threshold (degenerate camera or light) either answer passes. */
#include <math.h>
#include <string.h>

#include "fuzz_check.h"
#include "penumbra/penumbra.h"

#define MAX_T 64u
#define MAX_W 24u
#define MAX_H 24u
#define GUARD 4096u
#define SHORT_CHECK 65536u /* bytes of a rejected arena checked for writes */
#define FILL 0xCD
#define BIT(s) (1u << (s))

static uint8_t block[GUARD + 64u + PN_ARENA_BYTES_MAX(MAX_T, MAX_W, MAX_H) +
                     PN_BVH_SPLIT_EXTRA(MAX_T) * PN_BVH_SPLIT_REF_BYTES + GUARD];

typedef struct reader { const uint8_t *p; size_t n; } reader;
static void take(reader *r, void *dst, size_t n)
{
    size_t k = n < r->n ? n : r->n;
    memset(dst, 0, n);
    memcpy(dst, r->p, k);
    r->p += k;
    r->n -= k;
}

/* A vector's status causes: NaN/Inf, then |x| > 2^40 (PN_MAX_COORD, pn_internal.h). */
static unsigned vec_causes(const float *v, unsigned n)
{
    unsigned c = 0, i;
    for (i = 0; i < n; i++)
        c |= !isfinite(v[i]) ? BIT(PN_E_NONFINITE) : fabsf(v[i]) > 0x1p40f ? BIT(PN_E_LIMIT) : 0u;
    return c;
}
static double len3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
static int eq3(const float *a, const float *b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }
static int zero3(const float *a) { return eq3(a, (const float[3]){0.0f, 0.0f, 0.0f}); }

/* Checks a status against the causes that must (some status required) and may (the only
 * statuses allowed) be reported. */
static void expect(const char *call, pn_status st, unsigned must, unsigned may, pn_context *ctx)
{
    FUZZ_CHECK(st != PN_OK || must == 0u, "%s returned PN_OK on invalid input (causes 0x%x)", call, must);
    FUZZ_CHECK(st == PN_OK || ((unsigned)st < 32u && ((may | must) & BIT(st))),
               "%s returned %s; allowed causes 0x%x", call, pn_status_str(st), may | must);
    FUZZ_CHECK(st == PN_OK || !ctx || pn_last_error(ctx)[0] != '\0', "%s failed without a message", call);
}

static void reverse_for(void *user, uint32_t count, pn_task_fn fn, void *task)
{
    (void)user;
    while (count-- > 0u) fn(task, count, count + 1u);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static float pos[MAX_T * 3u], pos_copy[MAX_T * 3u], vis1[MAX_W * MAX_H], depth1[MAX_W * MAX_H];
    static uint32_t idx[MAX_T * 3u], idx_copy[MAX_T * 3u], id1[MAX_W * MAX_H];
    static uint8_t rgba1[MAX_W * MAX_H * 4u];
    reader r = {data, size};
    uint8_t h[16];
    pn_limits lim = {.max_triangles = MAX_T, .max_width = MAX_W, .max_height = MAX_H};
    pn_camera cam, cam0;
    pn_light light, light0;
    pn_frame_options opt, opt0;
    pn_frame out, out0;
    float shade[3];
    pn_context *ctx = NULL;
    pn_status st;
    size_t bytes, fill, i;
    uint8_t *mem, *end;
    uint32_t vc, tc, k;
    unsigned must = 0, may = 0;
    double f[3], up[3], u[3], v[3], s, lu, lv;
    int point, maybe_point, rev;

    take(&r, h, sizeof h);
    vc = h[0] % 65u;
    tc = h[1] % 65u;
    if (h[6] & 32u) {
        lim.max_triangles = 1u + h[8] % MAX_T;
        lim.max_width = 1u + h[9] % MAX_W;
        lim.max_height = 1u + h[10] % MAX_H;
    }
    {
        /* the default reserve (penumbra.h; max_triangles <= 64 here, far below 2^26) */
        uint32_t dflt = lim.max_triangles + (uint32_t)PN_BVH_SPLIT_EXTRA(lim.max_triangles);
        switch (h[5] >> 6) {
        case 1: lim.bvh_refs = lim.max_triangles; break;
        case 2: lim.bvh_refs = lim.max_triangles + 1u + h[9] % 64u; break;
        case 3: lim.bvh_refs = dflt + 1u; break;
        default: break;
        }
        if (lim.bvh_refs > dflt && (h[5] >> 6) == 2u) lim.bvh_refs = dflt;
        if ((h[5] >> 6) == 3u) {
            pn_context *none = NULL;
            static uint8_t small[64];
            FUZZ_CHECK(pn_arena_size(&lim, &bytes) == PN_E_LIMIT, "a reserve above the default was accepted");
            FUZZ_CHECK(pn_init(&none, small, sizeof small, &lim) == PN_E_LIMIT && none == NULL,
                       "pn_init took a reserve above the default");
            return 0;
        }
    }
    pn_frame_options_default(&opt);
    opt.width = h[2] % 25u;
    opt.height = h[3] % 25u;
    opt.k = k = h[4];
    opt.algo = (pn_algo)(h[7] < 0xF0u ? h[7] & 7u : h[7]);
#ifdef PN_BUILD_GEARS
    lim.gears_pairs = (uint32_t)h[12] | (uint32_t)h[13] << 8;
    lim.gears_grid_max = h[14] % (PN_GEARS_GRID_MAX + 1u); /* at most the default: the block's bound */
    opt.gears.grid = h[11];
    opt.exact_stats = h[15] & 1u;
#endif
#ifdef PN_BUILD_SRT
    /* SRT maps of 8 .. 64 texels a side: every SRT code path, at a fuzzing pace. */
    lim.srt_map_max = 8u + (uint32_t)(h[15] >> 1) % 57u;
#endif
#ifdef PN_BUILD_OCCTEX
    lim.occ_map_max = 8u + (uint32_t)(h[15] >> 1) % 57u;
    opt.occtex.slices = h[11] % 18u;
    opt.occtex.filter = h[12] % 5u;
    opt.occtex.combine = h[13] % 5u;
    opt.occtex.flags = h[14] & 3u;
#endif
#ifdef PN_BUILD_MCSM
    lim.mc_map_max = 8u + (uint32_t)(h[15] >> 1) % 57u;
    opt.mcsm.layers = h[11] % 5u;
    opt.mcsm.search = h[12] % 4u;
    opt.mcsm.rays = h[13] % 10u;
    opt.mcsm.flags = h[14] & 7u;
    opt.mcsm.blur = (h[14] >> 3) == 31u ? PN_MC_BLUR_OFF : (uint32_t)(h[14] >> 3) % 11u;
    opt.mcsm.seed = h[15];
#endif
#ifdef PN_BUILD_WEDGES
    opt.wedges.mode = h[12] % 4u; /* 3: invalid */
    lim.wg_pairs = (uint32_t)h[13] * 16u; /* below a frame's pairs now and then */
#endif
    take(&r, &cam, sizeof cam);
    take(&r, &light, sizeof light);
    take(&r, shade, sizeof shade);
    opt.eps = shade[0], opt.albedo = shade[1], opt.ambient = shade[2];
    take(&r, opt.background, 4u);
    take(&r, pos, vc * 3u * sizeof(float));
    take(&r, idx, tc * 3u * sizeof(uint32_t));
    for (i = 0; (h[6] & 16u) && i < tc * 3u; i++) idx[i] = vc ? idx[i] % vc : 0u;
    memcpy(pos_copy, pos, sizeof pos);
    memcpy(idx_copy, idx, sizeof idx);
    cam0 = cam, light0 = light, opt0 = opt;

    /* Arena: exactly the queried size, at a chosen misalignment, fenced by FILL bytes. */
    FUZZ_CHECK(pn_arena_size(&lim, &bytes) == PN_OK, "pn_arena_size failed");
    /* The bound of limits (t, w, h), plus each split reference the limits reserve (every
     * other pool at most its default), and what the static block holds. */
    FUZZ_CHECK(bytes <= PN_ARENA_BYTES_MAX(lim.max_triangles, lim.max_width, lim.max_height) +
                            (lim.bvh_refs > lim.max_triangles ? (size_t)(lim.bvh_refs - lim.max_triangles) : 0u) *
                                PN_BVH_SPLIT_REF_BYTES,
               "pn_arena_size %zu above PN_ARENA_BYTES_MAX", bytes);
    FUZZ_CHECK(bytes <= sizeof(block) - 2u * GUARD - 64u, "pn_arena_size %zu beyond the fuzz block", bytes);
    mem = block + GUARD + (h[5] & 63u);
    end = mem + bytes;
    fill = (size_t)(mem - block) + ((h[6] & 8u) ? (bytes < SHORT_CHECK ? bytes : SHORT_CHECK) : 0u);
    memset(block, FILL, fill);
    memset(end, FILL, GUARD);
    st = pn_init(&ctx, mem, bytes - ((h[6] & 8u) ? 1u : 0u), &lim);
    if (h[6] & 8u) {
        FUZZ_CHECK(st == PN_E_ARENA_TOO_SMALL && ctx == NULL, "short arena gave %s", pn_status_str(st));
        for (i = 0; i < fill; i++) FUZZ_CHECK(block[i] == FILL, "failed pn_init wrote byte %td", block + i - mem);
        return 0;
    }
    FUZZ_CHECK(st == PN_OK && (uint8_t *)ctx >= mem && (uint8_t *)ctx < mem + bytes, "pn_init: %s",
               pn_status_str(st));

    /* Scene: valid exactly when pointers are set, 1 <= tc <= limit, coordinates finite
     * and within 2^40, indices < vc. */
    if (h[6] & 4u) {
        tc = 0u; /* no scene */
    } else {
        const float *P = (h[6] & 1u) ? NULL : pos;
        const uint32_t *I = (h[6] & 2u) ? NULL : idx;
        must = (!P || !I || tc == 0u) ? BIT(PN_E_INVALID_ARG) : 0u;
        must |= tc > lim.max_triangles ? BIT(PN_E_LIMIT) : 0u;
        must |= P ? vec_causes(pos, vc * 3u) : 0u;
        for (i = 0; I && i < tc * 3u; i++) must |= idx[i] >= vc ? BIT(PN_E_INDEX_RANGE) : 0u;
        st = pn_scene_set(ctx, P, vc, I, tc);
        expect("pn_scene_set", st, must, 0u, ctx);
        if (st != PN_OK) tc = 0u;
        if (h[6] & 128u) {
            /* Out of range: refused, nothing marked; then the second half marked. */
            expect("pn_scene_set_receivers", pn_scene_set_receivers(ctx, tc / 2u, tc - tc / 2u + 1u),
                   tc ? BIT(PN_E_INDEX_RANGE) : BIT(PN_E_NO_SCENE), 0u, ctx);
            expect("pn_scene_set_receivers", pn_scene_set_receivers(ctx, tc / 2u, tc - tc / 2u),
                   tc ? 0u : BIT(PN_E_NO_SCENE), 0u, ctx);
        }
    }
    FUZZ_CHECK(!memcmp(pos, pos_copy, sizeof pos) && !memcmp(idx, idx_copy, sizeof idx), "caller arrays changed");

    /* Frame. Camera: eye == target or up == 0 must fail; near-parallel may. */
    must = tc == 0u ? BIT(PN_E_NO_SCENE) : 0u;
    must |= (opt.width == 0u || opt.height == 0u) ? BIT(PN_E_IMAGE_SIZE) : 0u;
    must |= (opt.width > lim.max_width || opt.height > lim.max_height) ? BIT(PN_E_LIMIT) : 0u;
    /* Algorithm id a is compiled in when pn_build_info() has bit a (PN_BUILD_REFERENCE is
     * 1 << PN_ALGO_REFERENCE, ...). Only the reference never runs out of pool. */
    if ((unsigned)opt.algo >= 8u || !(pn_build_info() & (1u << opt.algo))) {
        must |= BIT(PN_E_INVALID_ARG);
        may |= BIT(PN_E_UNSUPPORTED);
    } else if (opt.algo != PN_ALGO_REFERENCE && (opt.algo != PN_ALGO_WEDGES || lim.wg_pairs != 0u)) {
        /* The wedges bin in bands of tiles that fit their pair pool: with the default pool
         * (PN_WEDGES_PAIRS >= PN_WEDGES_SIL_MAX, the most silhouettes one tile can list,
         * and the fuzzer's scenes hold fewer triangles than a third of that) they never run
         * out; a caller's smaller pool may hold less than one tile's pairs. */
        may |= BIT(PN_E_POOL_EXHAUSTED);
    }
#ifdef PN_BUILD_GEARS
    if (opt.gears.grid > (lim.gears_grid_max ? lim.gears_grid_max : PN_GEARS_GRID_MAX)) {
        must |= opt.algo == PN_ALGO_GEARS ? BIT(PN_E_INVALID_ARG) : 0u;
        may |= BIT(PN_E_INVALID_ARG);
    }
#endif
#ifdef PN_BUILD_OCCTEX
    if (opt.algo == PN_ALGO_OCCTEX && (opt.occtex.slices == 1u || opt.occtex.slices > 16u || opt.occtex.filter > 3u ||
                                       opt.occtex.combine > 3u || (opt.occtex.flags & ~PN_OCC_LEAK_FIX)))
        must |= BIT(PN_E_INVALID_ARG);
#endif
#ifdef PN_BUILD_WEDGES
    if (opt.algo == PN_ALGO_WEDGES && opt.wedges.mode > PN_WG_MODE_ADDITIVE) must |= BIT(PN_E_INVALID_ARG);
#endif
#ifdef PN_BUILD_MCSM
    if (opt.algo == PN_ALGO_MCSM && (opt.mcsm.layers > 3u || opt.mcsm.search > 2u || opt.mcsm.rays > 8u ||
                                     (opt.mcsm.blur > 8u && opt.mcsm.blur != PN_MC_BLUR_OFF) || (opt.mcsm.flags & 4u)))
        must |= BIT(PN_E_INVALID_ARG);
#endif
    must |= vec_causes(shade, 3u) & BIT(PN_E_NONFINITE);
    must |= (opt.eps < 0.0f || opt.albedo < 0.0f || opt.albedo > 1.0f || opt.ambient < 0.0f ||
             opt.ambient > 1.0f) ? BIT(PN_E_INVALID_ARG) : 0u;
    must |= opt.eps > 0x1p40f ? BIT(PN_E_LIMIT) : 0u; /* eps beyond the coordinate limit */
    must |= vec_causes(cam.eye, 3u) | vec_causes(cam.target, 3u) | vec_causes(cam.up, 3u);
    must |= vec_causes(light.center, 3u) | vec_causes(light.u, 3u) | vec_causes(light.v, 3u);
    must |= !isfinite(cam.fov_deg) ? BIT(PN_E_NONFINITE)
            : !(cam.fov_deg > 0.0f && cam.fov_deg < 180.0f) ? BIT(PN_E_CAMERA) : 0u;
    for (i = 0; i < 3; i++) {
        f[i] = (double)cam.target[i] - cam.eye[i];
        up[i] = cam.up[i];
        u[i] = light.u[i];
        v[i] = light.v[i];
    }
    must |= (zero3(cam.up) || eq3(cam.eye, cam.target)) ? BIT(PN_E_CAMERA) : 0u;
    s = len3((double[3]){f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]});
    may |= !(len3(f) > 1e-15 && len3(up) > 1e-15 && s > 1e-5 * len3(f) * len3(up)) ? BIT(PN_E_CAMERA) : 0u;
    /* Frames that cannot be formed in float (issue 20): |f| or |up| below 1.1e-19 (f.f or
     * (f x up).(f x up) subnormal), and a fov whose neighbouring pixels' rays coincide,
     * 2 tan(fov/2) / h below 2^-23. A factor of 2 either side of each threshold may go
     * either way. */
    must |= len3(f) < 5e-20 || len3(up) < 5e-20 ? BIT(PN_E_CAMERA) : 0u;
    if (isfinite(cam.fov_deg) && cam.fov_deg > 0.0f && cam.fov_deg < 180.0f && opt.height > 0u) {
        double th = tan((double)cam.fov_deg * 3.14159265358979323846 / 360.0), need = opt.height * 0x1p-24;
        must |= th < 0.5 * need ? BIT(PN_E_CAMERA) : 0u;
        may |= th < 2.0 * need ? BIT(PN_E_CAMERA) : 0u;
    }
    /* Light: both half-edges zero is a point light, one zero is degenerate, |u.v| above
     * 1e-4 |u||v| is not orthogonal; lengths below 1e-15 may underflow to zero. */
    lu = len3(u), lv = len3(v);
    point = zero3(light.u) && zero3(light.v);
    maybe_point = lu < 1e-15 && lv < 1e-15;
    must |= (zero3(light.u) != zero3(light.v) && (lu >= 1e-15 || lv >= 1e-15)) ? BIT(PN_E_LIGHT_DEGENERATE) : 0u;
    may |= (lu < 1e-15 || lv < 1e-15) && !point ? BIT(PN_E_LIGHT_DEGENERATE) | BIT(PN_E_LIGHT_NOT_ORTHO) : 0u;
    /* Only u = v = 0 exactly is a point light; a non-zero half-edge shorter than 1.1e-19
     * cannot be normalized in float (issue 20). */
    must |= (!zero3(light.u) && lu < 5e-20) || (!zero3(light.v) && lv < 5e-20) ? BIT(PN_E_LIGHT_DEGENERATE) : 0u;
    s = lu >= 1e-15 && lv >= 1e-15 ? fabs(u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / (lu * lv) : 0.0;
    must |= s > 1e-3 ? BIT(PN_E_LIGHT_NOT_ORTHO) : 0u;
    may |= s > 1e-5 ? BIT(PN_E_LIGHT_NOT_ORTHO) : 0u;
    /* k: 4, 8, 16 or 32; penumbra.h says it is ignored for a point light. */
    if (!(k == 4u || k == 8u || k == 16u || k == 32u)) {
        must |= maybe_point ? 0u : BIT(PN_E_INVALID_ARG);
        may |= BIT(PN_E_INVALID_ARG);
    }

    memset(&out, 0x5A, sizeof out);
    out0 = out;
    rev = (h[6] & 64u) != 0;
    pn_set_parallel_for(ctx, rev ? reverse_for : NULL, NULL);
    st = pn_render(ctx, &cam, &light, &opt, &out);
    expect("pn_render", st, must, may, ctx);
    FUZZ_CHECK(!memcmp(&cam, &cam0, sizeof cam) && !memcmp(&light, &light0, sizeof light) &&
                   !memcmp(&opt, &opt0, sizeof opt), "pn_render changed its inputs");
    FUZZ_CHECK(st == PN_OK || !memcmp(&out, &out0, sizeof out), "failed pn_render wrote *out");
    if (st == PN_OK) {
        size_t n = (size_t)opt.width * opt.height;
        float kk = (float)k * (float)k;
        pn_stats stats;
        FUZZ_CHECK(out.width == opt.width && out.height == opt.height, "frame size %ux%u", out.width, out.height);
        for (i = 0; i < n; i++) {
            float vi = out.visibility[i];
            const float *nr = out.normal + 3u * i;
            FUZZ_CHECK(vi >= 0.0f && vi <= 1.0f, "pixel %zu visibility %g", i, vi);
            FUZZ_CHECK(opt.algo == PN_ALGO_OCCTEX || opt.algo == PN_ALGO_MCSM || opt.algo == PN_ALGO_WEDGES || (point ? vi == 0.0f || vi == 1.0f : vi * kk == floorf(vi * kk)),
                       "pixel %zu visibility %g: not a multiple of 1/k^2 (k %u)", i, vi, k);
            if (out.tri_id[i] == PN_NO_TRIANGLE) {
                FUZZ_CHECK(vi == 1.0f && out.depth[i] == INFINITY && !memcmp(out.rgba + 4u * i, opt.background, 4u),
                           "background pixel %zu: visibility %g depth %g", i, vi, out.depth[i]);
                continue;
            }
            FUZZ_CHECK(out.tri_id[i] < tc, "pixel %zu triangle %u of %u", i, out.tri_id[i], tc);
            FUZZ_CHECK(out.depth[i] >= 0.0f && isfinite(out.depth[i]) && isfinite(out.position[3u * i]) &&
                           isfinite(out.position[3u * i + 1u]) && isfinite(out.position[3u * i + 2u]),
                       "pixel %zu depth %g", i, out.depth[i]);
            FUZZ_CHECK(fabsf(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2] - 1.0f) < 1e-3f,
                       "pixel %zu (triangle %u) normal (%g %g %g) is not unit", i, out.tri_id[i], nr[0],
                       nr[1], nr[2]);
        }
        FUZZ_CHECK(pn_get_stats(ctx, &stats) == PN_OK && stats.triangles == tc &&
                       stats.arena_high_water <= stats.arena_carved && stats.arena_carved < bytes,
                   "stats: %u triangles, high water %zu, carved %zu", stats.triangles,
                   stats.arena_high_water, stats.arena_carved);
        memcpy(vis1, out.visibility, n * sizeof(float));
        memcpy(depth1, out.depth, n * sizeof(float));
        memcpy(id1, out.tri_id, n * sizeof(uint32_t));
        memcpy(rgba1, out.rgba, n * 4u);
        /* The scene is a copy; the schedule does not matter. */
        memset(pos, 0xFF, sizeof pos);
        memset(idx, 0xFF, sizeof idx);
        pn_set_parallel_for(ctx, rev ? NULL : reverse_for, NULL);
        st = pn_render(ctx, &cam, &light, &opt, &out);
        FUZZ_CHECK(st == PN_OK, "second pn_render: %s", pn_last_error(ctx));
        FUZZ_CHECK(!memcmp(vis1, out.visibility, n * sizeof(float)) && !memcmp(id1, out.tri_id, n * 4u) &&
                       !memcmp(depth1, out.depth, n * sizeof(float)) && !memcmp(rgba1, out.rgba, n * 4u),
                   "second render differs");
    }
    for (i = 0; i < fill; i++) FUZZ_CHECK(block[i] == FILL, "byte %td before the arena was written", block + i - mem);
    for (i = 0; i < GUARD; i++) FUZZ_CHECK(end[i] == FILL, "byte %zu after the arena was written", i);
    return 0;
}
