/* pn_scene.c - scene input: validate everything first (read-only), then copy into the
 * arena and build the BVH (pn_scene_set) or refit it (pn_scene_update_positions: the same
 * triangles moved). Validation before any write keeps the previous scene intact when the
 * new one is rejected. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_kmath.h"
#include "pn_raster.h"

static int pn_coord_ok(float v) { return pn_finite(v) && v <= PN_MAX_COORD && v >= -PN_MAX_COORD; }

/* The box of every triangle not marked receiver-only (the light-space algorithms' occluders;
 * empty, min > max, when there is none). */
static void pn_occluder_box(pn_context *ctx)
{
    uint32_t t, k;
    for (k = 0; k < 3u; k++) {
        ctx->occ_min[k] = PN_MAX_COORD;
        ctx->occ_max[k] = -PN_MAX_COORD;
    }
    for (t = 0; t < ctx->tri_count; t++) {
        const float *p = ctx->tris + (size_t)t * 9u;
        if (ctx->flags[t] & PN_TRI_RECEIVER) continue;
        for (k = 0; k < 9u; k++) {
            ctx->occ_min[k % 3u] = pn_kminf(ctx->occ_min[k % 3u], p[k]);
            ctx->occ_max[k % 3u] = pn_kmaxf(ctx->occ_max[k % 3u], p[k]);
        }
    }
}

/* Everything pn_scene_set and pn_scene_update_positions (named by fn in the messages)
 * check of their input, before either writes anything. */
static pn_status pn_scene_check(pn_context *ctx, const char *fn, const float *positions, uint32_t vertex_count,
                                const uint32_t *indices, uint32_t triangle_count)
{
    uint32_t v, t;
    if (!positions || !indices)
        return pn_fail(ctx, PN_E_INVALID_ARG, "%s: positions and indices must not be NULL", fn);
    if (triangle_count == 0u) return pn_fail(ctx, PN_E_INVALID_ARG, "%s: the scene has no triangles", fn);
    if (triangle_count > ctx->limits.max_triangles)
        return pn_fail(ctx, PN_E_LIMIT, "scene has %u triangles; this context holds at most %u",
                       triangle_count, ctx->limits.max_triangles);
    if (vertex_count > PN_MAX_VERTICES)
        return pn_fail(ctx, PN_E_LIMIT, "scene has %u vertices; PN_MAX_VERTICES is %u",
                       vertex_count, (uint32_t)PN_MAX_VERTICES);
    for (v = 0; v < vertex_count; v++) {
        const float *p = positions + (size_t)v * 3u;
        int c;
        for (c = 0; c < 3; c++) {
            if (!pn_finite(p[c]))
                return pn_fail(ctx, PN_E_NONFINITE, "vertex %u coordinate %u is NaN or infinite", v,
                               (uint32_t)c);
            if (!pn_coord_ok(p[c]))
                return pn_fail(ctx, PN_E_LIMIT,
                               "vertex %u coordinate %u exceeds 2^40 in magnitude (PN_MAX_COORD)", v,
                               (uint32_t)c);
        }
    }
    for (t = 0; t < triangle_count; t++) {
        int c;
        for (c = 0; c < 3; c++) {
            uint32_t i = indices[(size_t)t * 3u + (size_t)c];
            if (i >= vertex_count)
                return pn_fail(ctx, PN_E_INDEX_RANGE,
                               "triangle %u index %u is %u; the scene has %u vertices", t,
                               (uint32_t)c, i, vertex_count);
        }
    }
    return PN_OK;
}

/* Valid input into the arena, replacing the current scene: the triangles' corners, their
 * degenerate flags (the flag bits in `keep` stay, the rest are cleared: the algorithms'
 * scene work sets its own again), the scene's box and diagonal and the occluders' box. */
static void pn_scene_copy(pn_context *ctx, const float *positions, const uint32_t *indices, uint32_t triangle_count,
                          uint8_t keep)
{
    uint64_t t0 = pn_now(ctx);
    uint32_t t, degenerate = 0, receivers = 0;
    float lo[3], hi[3];
    ctx->has_scene = 0;
    ctx->scene_version++;
    lo[0] = lo[1] = lo[2] = PN_MAX_COORD;
    hi[0] = hi[1] = hi[2] = -PN_MAX_COORD;
    for (t = 0; t < triangle_count; t++) {
        float *dst = ctx->tris + (size_t)t * 9u;
        const uint32_t *ix = indices + (size_t)t * 3u;
        pn_v3 A, B, C, n;
        int c;
        for (c = 0; c < 3; c++) {
            const float *p = positions + (size_t)ix[c] * 3u;
            int a;
            for (a = 0; a < 3; a++) {
                dst[c * 3 + a] = p[a];
                if (p[a] < lo[a]) lo[a] = p[a];
                if (p[a] > hi[a]) hi[a] = p[a];
            }
        }
        A = pn_v3_make(dst[0], dst[1], dst[2]);
        B = pn_v3_make(dst[3], dst[4], dst[5]);
        C = pn_v3_make(dst[6], dst[7], dst[8]);
        n = pn_tri_cross(A, B, C);
        /* Zero area in float, or a normal that cannot be normalized in float (largest
         * component of the cross product below FLT_MIN: a triangle at subnormal scale,
         * issue 20): no plane, no edges; it can neither be seen nor block. */
        ctx->flags[t] = (uint8_t)((ctx->flags[t] & keep) | (pn_normal_ok(n) ? 0u : PN_TRI_DEGENERATE));
        degenerate += ctx->flags[t] & PN_TRI_DEGENERATE;
        receivers += (ctx->flags[t] & PN_TRI_RECEIVER) != 0u;
    }
    ctx->tri_count = triangle_count;
    ctx->degenerate = degenerate;
    memcpy(ctx->scene_min, lo, sizeof(lo));
    memcpy(ctx->scene_max, hi, sizeof(hi));
    if (receivers) {
        pn_occluder_box(ctx); /* as pn_scene_set_receivers leaves it */
    } else {
        /* No triangle is receiver-only: the occluders' box is the triangles' box. */
        memcpy(ctx->occ_min, lo, sizeof(lo));
        memcpy(ctx->occ_max, hi, sizeof(hi));
    }
    {
        pn_v3 d = pn_v3_make(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
        ctx->scene_diag = pn_ksqrt(pn_v3_dot(d, d));
    }
    ctx->pass_ns[PN_PASS_SCENE_COPY] = pn_now(ctx) - t0;
}

/* After pn_scene_copy: the BVH, built anew or refitted (pn_bvh_refit, which builds when it
 * must), then each algorithm's own work on the scene (the wedges' connectivity, MCSM's
 * sheets), for those the context runs; the scene is usable only once all of it is done. */
static pn_status pn_scene_finish(pn_context *ctx, int refit)
{
    uint64_t t0 = pn_now(ctx);
    pn_status st = refit ? pn_bvh_refit(ctx) : pn_bvh_build(ctx);
    ctx->pass_ns[PN_PASS_BVH_BUILD] = pn_now(ctx) - t0;
    if (st != PN_OK) return st;
    t0 = pn_now(ctx);
#define PN_ALGO_SCENE(ID, name)                                                                \
    if ((pn_limits_algos(&ctx->limits) & (1u << PN_ALGO_##ID)) && (st = pn_##name##_scene(ctx)) != PN_OK) return st;
    PN_ALGORITHMS(PN_ALGO_SCENE)
#undef PN_ALGO_SCENE
    ctx->pass_ns[PN_PASS_SCENE_ALGOS] = pn_now(ctx) - t0;
    ctx->has_scene = 1;
    return PN_OK;
}

pn_status pn_scene_set(pn_context *ctx, const float *positions, uint32_t vertex_count,
                       const uint32_t *indices, uint32_t triangle_count)
{
    pn_status st;
    if (!ctx) return PN_E_INVALID_ARG;
    st = pn_scene_check(ctx, "pn_scene_set", positions, vertex_count, indices, triangle_count);
    if (st != PN_OK) return st;
    /* Valid: from here on the previous scene is replaced. */
    pn_scene_copy(ctx, positions, indices, triangle_count, 0u);
    return pn_scene_finish(ctx, 0);
}

pn_status pn_scene_update_positions(pn_context *ctx, const float *positions, uint32_t vertex_count,
                                    const uint32_t *indices, uint32_t triangle_count)
{
    pn_status st;
    if (!ctx) return PN_E_INVALID_ARG;
    if (!ctx->has_scene)
        return pn_fail(ctx, PN_E_NO_SCENE, "pn_scene_update_positions: no scene (call pn_scene_set first)");
    if (triangle_count != ctx->tri_count)
        return pn_fail(ctx, PN_E_INVALID_ARG, "pn_scene_update_positions: %u triangles; the current scene has %u",
                       triangle_count, ctx->tri_count);
    st = pn_scene_check(ctx, "pn_scene_update_positions", positions, vertex_count, indices, triangle_count);
    if (st != PN_OK) return st;
    /* Valid: the triangles move, their receiver marking stays; the tree keeps its shape
     * unless a refit cannot serve (pn_bvh_refit). */
    pn_scene_copy(ctx, positions, indices, triangle_count, (uint8_t)PN_TRI_RECEIVER);
    return pn_scene_finish(ctx, 1);
}

pn_status pn_scene_set_receivers(pn_context *ctx, uint32_t first, uint32_t count)
{
    uint32_t t;
    if (!ctx) return PN_E_INVALID_ARG;
    if (!ctx->has_scene) return pn_fail(ctx, PN_E_NO_SCENE, "pn_scene_set_receivers: no scene (call pn_scene_set first)");
    if (first > ctx->tri_count || count > ctx->tri_count - first)
        return pn_fail(ctx, PN_E_INDEX_RANGE, "pn_scene_set_receivers: triangles %u + %u exceed the scene's %u", first,
                       count, ctx->tri_count);
    /* Only the flag bytes and the occluders' box change: the BVH, the scene's bounds and
     * every exact algorithm's input stay as they were. A device port copies the flags again (the version changes). */
    for (t = 0; t < ctx->tri_count; t++) {
        uint8_t f = (uint8_t)(ctx->flags[t] & ~PN_TRI_RECEIVER);
        if (t >= first && t - first < count) f |= (uint8_t)PN_TRI_RECEIVER;
        ctx->flags[t] = f;
    }
    pn_occluder_box(ctx);
    ctx->scene_version++;
    return PN_OK;
}
