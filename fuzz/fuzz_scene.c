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
 *   penumbra-wedge builds: 12 % 4 the mode (3 invalid), 13 x 16 the pair pool (0: default),
 *   11 bits 5..7 the flags (bit 5 PN_WG_NO_CULL, the others invalid);
 *   algo 6 is PN_ALGO_WEDGES
 *   then floats: eye[3] target[3] up[3] fov, light c[3] u[3] v[3], eps albedo ambient;
 *   4 background bytes; vertex count * 3 floats; triangle count * 3 uint32 indices;
 *   then (issue 52) a byte of the caller-side entry points to try after a valid frame:
 *   1 a hostile G-buffer (width x height depth floats, then ids: raw, or with 8 also set
 *   taken modulo the triangle count + 1, which stands for PN_NO_TRIANGLE) with output
 *   buffers, 2 hostile points (a count byte % 33, then per point position[3] normal[3]
 *   and an id, raw or with 8 modulo as above; with 16 the normals normalized),
 *   4 moved vertices (vertex count * 3 floats for pn_scene_update_positions).
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
 * caller's arrays and under a reversed work-item schedule, gives the same bytes. The
 * frame's own depth and ids handed back as the caller's G-buffer give its bytes again;
 * its pixels as points give its visibility (every algorithm but the wedges, which refuse,
 * and MCSM with a blur, which points do not run); a hostile G-buffer or point set is
 * refused exactly when a pixel or point is invalid (penumbra.h's pn_gbuffer and
 * pn_visibility_points), and when taken gives a frame within the invariants above with
 * the output buffers equal to the frame's; after pn_scene_update_positions a frame has
 * the bytes of the same frame after pn_scene_set of the moved scene. Within
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

/* The arena's bound at the maxima, the split references, and a GEARS pair pool of up to
 * 65,535 (limits.gears_pairs, 16 bits of the input) above the default (8 bytes a pair at
 * most, three pools: the bound below). */
#define GEARS_POOL_EXTRA (PN_ENABLE_GEARS ? 65535u * 8u + 3u * PN_ARENA_ALIGN : 0u)
static uint8_t block[GUARD + 64u + PN_ARENA_BYTES_MAX(MAX_T, MAX_W, MAX_H) +
                     PN_BVH_SPLIT_EXTRA(MAX_T) * PN_BVH_SPLIT_REF_BYTES + GEARS_POOL_EXTRA + GUARD];

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

/* A triangle whose normal the library may find degenerate (its float cross product near
 * or below FLT_MIN, or tiny against its edges): 2 surely, 1 perhaps, 0 not. */
static int degenerate_tri(const float *pos, const uint32_t *idx, uint32_t t)
{
    const float *A = pos + 3u * idx[3u * t], *B = pos + 3u * idx[3u * t + 1u], *C = pos + 3u * idx[3u * t + 2u];
    double e1[3], e2[3], c[3], m, l1, l2;
    int i;
    for (i = 0; i < 3; i++) e1[i] = (double)B[i] - A[i], e2[i] = (double)C[i] - A[i];
    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
    m = fmax(fabs(c[0]), fmax(fabs(c[1]), fabs(c[2])));
    l1 = len3(e1), l2 = len3(e2);
    if (m == 0.0) return 2;
    return m < 1e-36 || m < 1e-5 * l1 * l2 ? 1 : 0;
}

/* The causes triangle id gives a G-buffer pixel or a point: must (surely) and may (near
 * the degenerate threshold) bits. */
static void point_causes(const float *pos, const uint32_t *idx, uint32_t tc, uint32_t id, unsigned *must,
                         unsigned *may)
{
    int d;
    if (id == PN_NO_TRIANGLE) return;
    if (id >= tc) {
        *must |= BIT(PN_E_INDEX_RANGE);
        return;
    }
    d = degenerate_tri(pos, idx, id);
    if (d == 2) *must |= BIT(PN_E_INVALID_ARG);
    if (d == 1) *may |= BIT(PN_E_INVALID_ARG);
}

/* A valid frame's buffers, kept. */
typedef struct kept_frame {
    const float *vis, *depth, *pos, *nrm;
    const uint32_t *ids;
    const uint8_t *rgba;
} kept_frame;

/* The frame invariants of pixel i (the top comment): visibility in [0, 1]; a background
 * pixel at 1, +inf depth and the background colour (when there is an image); otherwise a
 * triangle of the tc, a finite depth and position and a unit normal. */
static void check_pixel(const pn_frame *out, const pn_frame_options *opt, uint32_t tc, size_t i)
{
    const float *nr = out->normal + 3u * i;
    float vi = out->visibility[i];
    FUZZ_CHECK(vi >= 0.0f && vi <= 1.0f, "pixel %zu visibility %g", i, vi);
    if (out->tri_id[i] == PN_NO_TRIANGLE) {
        FUZZ_CHECK(vi == 1.0f && out->depth[i] == INFINITY && (!out->rgba || !memcmp(out->rgba + 4u * i, opt->background, 4u)),
                   "background pixel %zu: visibility %g depth %g", i, vi, out->depth[i]);
        return;
    }
    FUZZ_CHECK(out->tri_id[i] < tc, "pixel %zu triangle %u of %u", i, out->tri_id[i], tc);
    FUZZ_CHECK(out->depth[i] >= 0.0f && isfinite(out->depth[i]) && isfinite(out->position[3u * i]) &&
                   isfinite(out->position[3u * i + 1u]) && isfinite(out->position[3u * i + 2u]),
               "pixel %zu depth %g", i, out->depth[i]);
    FUZZ_CHECK(fabsf(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2] - 1.0f) < 1e-3f,
               "pixel %zu (triangle %u) normal (%g %g %g) is not unit", i, out->tri_id[i], nr[0], nr[1], nr[2]);
}

/* After a valid frame f of opt0: the caller-side entry points (issue 52; the top comment). */
static void caller_side(pn_context *ctx, reader *r, unsigned api, const pn_camera *cam, const pn_light *light,
                        const pn_frame_options *opt0, const float *pos, const uint32_t *idx, uint32_t vc, uint32_t tc,
                        int receivers, const kept_frame *f)
{
    static float gdepth[MAX_W * MAX_H], gdepth0[MAX_W * MAX_H], vis_out[MAX_W * MAX_H], pvis[MAX_W * MAX_H];
    static float ppos[32u * 3u], pnrm[32u * 3u], moved[MAX_T * 3u], moved0[MAX_T * 3u], vis2[MAX_W * MAX_H];
    static uint32_t gids[MAX_W * MAX_H], gids0[MAX_W * MAX_H], pids[32u], ids2[MAX_W * MAX_H];
    static uint8_t rgba_out[MAX_W * MAX_H * 4u], rgba2[MAX_W * MAX_H * 4u];
    size_t n = (size_t)opt0->width * opt0->height, i;
    pn_frame_options opt = *opt0;
    pn_gbuffer g;
    pn_frame out;
    pn_status st;
    unsigned must = 0u, may = 0u;
    double eye = fmax(fabs(cam->eye[0]), fmax(fabs(cam->eye[1]), fabs(cam->eye[2])));
    int near_limit = 0, blurred = opt0->algo == PN_ALGO_MCSM && opt0->mcsm.blur != PN_MC_BLUR_OFF;

    /* The frame's own depth and ids back: its bytes (a point the rasterizer put a rounding
     * beyond 2^40 may be refused). */
    for (i = 0; i < n * 3u; i++) near_limit |= fabsf(f->pos[i]) > 0x1.fcp39f;
    g.depth = f->depth;
    g.tri_id = f->ids;
    opt.gbuffer = &g;
    st = pn_render(ctx, cam, light, &opt, &out);
    expect("pn_render (its own G-buffer)", st, 0u, near_limit ? BIT(PN_E_LIMIT) : 0u, ctx);
    if (st == PN_OK)
        FUZZ_CHECK(!memcmp(f->vis, out.visibility, n * 4u) && !memcmp(f->ids, out.tri_id, n * 4u) &&
                       !memcmp(f->depth, out.depth, n * 4u) && !memcmp(f->rgba, out.rgba, n * 4u) &&
                       !memcmp(f->pos, out.position, n * 12u) && !memcmp(f->nrm, out.normal, n * 12u),
                   "the frame's own G-buffer gives other bytes");
    /* Its pixels as points: its visibility. */
    st = pn_visibility_points(ctx, light, opt0, f->pos, f->nrm, f->ids, (uint32_t)n, pvis);
    must = opt0->algo == PN_ALGO_WEDGES || (opt0->algo == PN_ALGO_MCSM && opt0->mcsm.layers == 3u)
               ? BIT(PN_E_UNSUPPORTED) : 0u;
    expect("pn_visibility_points (its pixels)", st, must, (near_limit ? BIT(PN_E_LIMIT) : 0u) | BIT(PN_E_POOL_EXHAUSTED),
           ctx);
    if (st == PN_OK && !blurred)
        FUZZ_CHECK(!memcmp(pvis, f->vis, n * 4u), "the frame's pixels as points give another visibility");

    if (api & 1u) { /* a hostile G-buffer, with output buffers */
        take(r, gdepth, n * 4u);
        take(r, gids, n * 4u);
        for (i = 0; (api & 8u) && i < n; i++) gids[i] = gids[i] % (tc + 1u) == tc ? PN_NO_TRIANGLE : gids[i] % (tc + 1u);
        memcpy(gdepth0, gdepth, n * 4u);
        memcpy(gids0, gids, n * 4u);
        must = may = 0u;
        for (i = 0; i < n; i++) {
            double d = gdepth[i];
            unsigned m0 = 0u;
            point_causes(pos, idx, tc, gids[i], &m0, &may);
            must |= m0;
            if (gids[i] >= tc || m0) continue;
            if (!isfinite(d)) must |= BIT(PN_E_NONFINITE);
            else if (!(d > 0.0)) must |= BIT(PN_E_INVALID_ARG);
            else if (d / 1.7320508 - eye > 0x1p40 * 1.01) must |= BIT(PN_E_LIMIT);
            else if (d + eye > 0x1p40 * 0.99) may |= BIT(PN_E_LIMIT);
        }
        g.depth = gdepth;
        g.tri_id = gids;
        opt.visibility_out = vis_out;
        opt.rgba_out = (api & 32u) ? NULL : rgba_out;
        opt.no_rgba = (api & 32u) ? 1u : 0u;
        st = pn_render(ctx, cam, light, &opt, &out);
        expect("pn_render (a hostile G-buffer)", st, must, may | BIT(PN_E_POOL_EXHAUSTED), ctx);
        FUZZ_CHECK(!memcmp(gdepth, gdepth0, n * 4u) && !memcmp(gids, gids0, n * 4u), "pn_render changed the G-buffer");
        if (st == PN_OK) {
            FUZZ_CHECK(!memcmp(gids, out.tri_id, n * 4u), "the frame's ids are not the G-buffer's");
            FUZZ_CHECK(!memcmp(vis_out, out.visibility, n * 4u), "visibility_out is not the frame's");
            FUZZ_CHECK((api & 32u) ? out.rgba == NULL : !memcmp(rgba_out, out.rgba, n * 4u), "rgba_out is not the frame's");
            for (i = 0; i < n; i++) check_pixel(&out, &opt, tc, i);
        }
    }
    if (api & 2u) { /* hostile points */
        uint8_t m8 = 0;
        uint32_t m, j;
        take(r, &m8, 1u);
        m = m8 % 33u;
        for (j = 0; j < m; j++) {
            take(r, ppos + 3u * j, 12u);
            take(r, pnrm + 3u * j, 12u);
            take(r, pids + j, 4u);
            if (api & 8u) pids[j] = pids[j] % (tc + 1u) == tc ? PN_NO_TRIANGLE : pids[j] % (tc + 1u);
            if (api & 16u) {
                float *q = pnrm + 3u * j, l = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
                if (isfinite(l) && l > 1e-18f) q[0] /= l, q[1] /= l, q[2] /= l;
            }
        }
        must = may = 0u;
        for (j = 0; j < m; j++) {
            unsigned m0 = 0u, c, pc, nc;
            double nn = 0.0;
            point_causes(pos, idx, tc, pids[j], &m0, &may);
            must |= m0;
            if (pids[j] >= tc || m0) continue;
            for (c = 0; c < 3u; c++) nn += (double)pnrm[3u * j + c] * pnrm[3u * j + c];
            pc = vec_causes(ppos + 3u * j, 3u);
            nc = vec_causes(pnrm + 3u * j, 3u) & BIT(PN_E_NONFINITE);
            if (pc | nc) {
                must |= pc | nc; /* the components are checked before the length */
            } else if (fabs(nn - 1.0) > 0.0025) {
                must |= BIT(PN_E_INVALID_ARG);
            } else if (fabs(nn - 1.0) > 0.0015) {
                may |= BIT(PN_E_INVALID_ARG);
            }
        }
        if (opt0->algo == PN_ALGO_WEDGES || (opt0->algo == PN_ALGO_MCSM && opt0->mcsm.layers == 3u))
            must = BIT(PN_E_UNSUPPORTED), may = 0u; /* before any point is read */
        memset(pvis, 0x5A, sizeof pvis);
        st = pn_visibility_points(ctx, light, opt0, ppos, pnrm, pids, m, pvis);
        expect("pn_visibility_points (hostile points)", st, must, may | BIT(PN_E_POOL_EXHAUSTED), ctx);
        for (j = 0; st == PN_OK && j < m; j++)
            FUZZ_CHECK(pvis[j] >= 0.0f && pvis[j] <= 1.0f && (pids[j] != PN_NO_TRIANGLE || pvis[j] == 1.0f),
                       "point %u (triangle %u): visibility %g", j, pids[j], pvis[j]);
        for (j = 0; st != PN_OK && st != PN_E_POOL_EXHAUSTED && j < m; j++)
            FUZZ_CHECK(((const uint32_t *)(const void *)pvis)[j] == 0x5A5A5A5Au, "failed pn_visibility_points wrote out");
    }
    if (api & 4u) { /* moved vertices: refitted, the frame of a new scene's */
        pn_status s1, s2;
        take(r, moved, vc * 12u);
        memcpy(moved0, moved, vc * 12u);
        st = pn_scene_update_positions(ctx, moved, vc, idx, tc);
        expect("pn_scene_update_positions", st, vec_causes(moved, vc * 3u), 0u, ctx);
        FUZZ_CHECK(!memcmp(moved, moved0, vc * 12u), "pn_scene_update_positions changed its input");
        if (st != PN_OK) return;
        s1 = pn_render(ctx, cam, light, opt0, &out);
        if (s1 == PN_OK) {
            memcpy(vis2, out.visibility, n * 4u);
            memcpy(ids2, out.tri_id, n * 4u);
            memcpy(rgba2, out.rgba, n * 4u);
        }
        st = pn_scene_set(ctx, moved, vc, idx, tc);
        FUZZ_CHECK(st == PN_OK, "pn_scene_set of the moved scene: %s", pn_last_error(ctx));
        if (receivers) FUZZ_CHECK(pn_scene_set_receivers(ctx, tc / 2u, tc - tc / 2u) == PN_OK, "receivers");
        s2 = pn_render(ctx, cam, light, opt0, &out);
        FUZZ_CHECK(s1 == s2, "after the move: refit %s, rebuilt %s", pn_status_str(s1), pn_status_str(s2));
        if (s1 == PN_OK && s2 == PN_OK)
            FUZZ_CHECK(!memcmp(vis2, out.visibility, n * 4u) && !memcmp(ids2, out.tri_id, n * 4u) &&
                           !memcmp(rgba2, out.rgba, n * 4u),
                       "the refitted scene's frame differs from the rebuilt one's");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static float pos[MAX_T * 3u], pos_copy[MAX_T * 3u], vis1[MAX_W * MAX_H], depth1[MAX_W * MAX_H];
    static uint32_t idx[MAX_T * 3u], idx_copy[MAX_T * 3u], id1[MAX_W * MAX_H];
    static uint8_t rgba1[MAX_W * MAX_H * 4u];
    static float pos1[MAX_W * MAX_H * 3u], nrm1[MAX_W * MAX_H * 3u];
    uint8_t api = 0;
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
    opt.occtex.flags = h[14] & 7u;
#endif
#ifdef PN_BUILD_MCSM
    lim.mc_map_max = 8u + (uint32_t)(h[15] >> 1) % 57u;
    opt.mcsm.layers = h[11] % 5u;
    opt.mcsm.search = h[12] % 4u;
    opt.mcsm.rays = h[13] % 10u;
    opt.mcsm.flags = h[14] & 15u; /* bit 3 unknown */
    opt.mcsm.blur = (h[14] >> 3) == 31u ? PN_MC_BLUR_OFF : (uint32_t)(h[14] >> 3) % 11u;
    opt.mcsm.seed = h[15];
#endif
#ifdef PN_BUILD_WEDGES
    opt.wedges.mode = h[12] % 4u; /* 3: invalid */
    opt.wedges.flags = (uint32_t)(h[11] >> 5); /* bit 0 PN_WG_NO_CULL, the others invalid */
    lim.wg_pairs = (uint32_t)h[13] * 16u; /* below a frame's pairs now and then */
    /* below a frame's silhouettes now and then (at most 3 of its 64 triangles' each) */
    lim.wg_silhouettes = (h[14] & 1u) ? 64u + (uint32_t)(h[14] >> 1) : 0u;
#endif
    take(&r, &cam, sizeof cam);
    take(&r, &light, sizeof light);
    take(&r, shade, sizeof shade);
    opt.eps = shade[0], opt.albedo = shade[1], opt.ambient = shade[2];
    take(&r, opt.background, 4u);
    take(&r, pos, vc * 3u * sizeof(float));
    take(&r, idx, tc * 3u * sizeof(uint32_t));
    for (i = 0; (h[6] & 16u) && i < tc * 3u; i++) idx[i] = vc ? idx[i] % vc : 0u;
    take(&r, &api, 1u);
    memcpy(pos_copy, pos, sizeof pos);
    memcpy(idx_copy, idx, sizeof idx);
    cam0 = cam, light0 = light, opt0 = opt;

    /* Arena: exactly the queried size, at a chosen misalignment, fenced by FILL bytes. */
    FUZZ_CHECK(pn_arena_size(&lim, &bytes) == PN_OK, "pn_arena_size failed");
    /* The bound of limits (t, w, h), plus each split reference the limits reserve, each
     * wedge pair above the default pool (12 bytes, in two pools that may each round one
     * PN_ARENA_ALIGN further) and each GEARS pair above the default pool (4 bytes and its
     * share of a 24-byte box per 8 and per 64, at most 8, in three pools; every other pool
     * at most its default), and what the static block holds. */
    {
        size_t wg_extra = 0u, gears_extra = 0u;
#if PN_ENABLE_WEDGES
        size_t wg_default = PN_WG_PAIRS_(lim.max_triangles, lim.max_width, lim.max_height);
        if (lim.wg_pairs > wg_default) wg_extra = (lim.wg_pairs - wg_default) * 12u + 2u * PN_ARENA_ALIGN;
#endif
#if PN_ENABLE_GEARS
        size_t gears_default = PN_GEARS_P_(lim.max_triangles, lim.max_width, lim.max_height);
        if (lim.gears_pairs > gears_default) gears_extra = (lim.gears_pairs - gears_default) * 8u + 3u * PN_ARENA_ALIGN;
#endif
        FUZZ_CHECK(bytes <= PN_ARENA_BYTES_MAX(lim.max_triangles, lim.max_width, lim.max_height) +
                                (lim.bvh_refs > lim.max_triangles ? (size_t)(lim.bvh_refs - lim.max_triangles) : 0u) *
                                    PN_BVH_SPLIT_REF_BYTES + wg_extra + gears_extra,
                   "pn_arena_size %zu above PN_ARENA_BYTES_MAX", bytes);
    }
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
    } else if (opt.algo != PN_ALGO_REFERENCE && opt.algo != PN_ALGO_WEDGES) {
        /* The wedges bin in bands of tiles that fit their pair and silhouette pools, and a
         * tile whose list outgrows a pool (a caller's small pool) takes the reference: they
         * never run out. */
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
                                       opt.occtex.combine > 3u ||
                                       (opt.occtex.flags & ~(PN_OCC_LEAK_FIX | PN_OCC_PAPER_FADE))))
        must |= BIT(PN_E_INVALID_ARG);
#endif
#ifdef PN_BUILD_WEDGES
    if (opt.algo == PN_ALGO_WEDGES && (opt.wedges.mode > PN_WG_MODE_ADDITIVE || (opt.wedges.flags & ~PN_WG_NO_CULL)))
        must |= BIT(PN_E_INVALID_ARG);
#endif
#ifdef PN_BUILD_MCSM
    if (opt.algo == PN_ALGO_MCSM && (opt.mcsm.layers > 3u || opt.mcsm.search > 2u || opt.mcsm.rays > 8u ||
                                     (opt.mcsm.blur > 8u && opt.mcsm.blur != PN_MC_BLUR_OFF) || (opt.mcsm.flags & 8u)))
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
            FUZZ_CHECK(opt.algo == PN_ALGO_OCCTEX || opt.algo == PN_ALGO_MCSM || opt.algo == PN_ALGO_WEDGES || (point ? vi == 0.0f || vi == 1.0f : vi * kk == floorf(vi * kk)),
                       "pixel %zu visibility %g: not a multiple of 1/k^2 (k %u)", i, vi, k);
            check_pixel(&out, &opt, tc, i);
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
        memcpy(pos1, out.position, n * 3u * sizeof(float));
        memcpy(nrm1, out.normal, n * 3u * sizeof(float));
        memcpy(pos, pos_copy, sizeof pos);
        memcpy(idx, idx_copy, sizeof idx);
        {
            const kept_frame f = {vis1, depth1, pos1, nrm1, id1, rgba1};
            caller_side(ctx, &r, api, &cam, &light, &opt, pos, idx, vc, tc, (h[6] & 128u) != 0, &f);
        }
    }
    for (i = 0; i < fill; i++) FUZZ_CHECK(block[i] == FILL, "byte %td before the arena was written", block + i - mem);
    for (i = 0; i < GUARD; i++) FUZZ_CHECK(end[i] == FILL, "byte %zu after the arena was written", i);
    return 0;
}
