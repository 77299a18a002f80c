/* pn_frame.c - per-frame validation, derivation of the kernel parameters, and the frame:
 * the G-buffer, the chosen algorithm's shadow sequence, shading, each a sequence of port
 * commands (pn_device.h) written once for every port. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_kmath.h"
#include "pn_passes.h"

void pn_frame_options_default(pn_frame_options *opt)
{
    if (!opt) return;
    memset(opt, 0, sizeof(*opt));
    opt->width = 512;
    opt->height = 512;
    opt->k = 16;
    /* The reference, or in a build without it the first algorithm compiled in. */
    opt->algo = PN_ALGO_REFERENCE;
    while ((uint32_t)opt->algo + 1u < PN_ALGO_COUNT && !(pn_build_info() & (1u << opt->algo)))
        opt->algo = (pn_algo)(opt->algo + 1);
    opt->eps = 1e-4f;
    opt->albedo = 0.8f;
    opt->ambient = 0.1f;
    opt->background[0] = 20;
    opt->background[1] = 24;
    opt->background[2] = 40;
    opt->background[3] = 255;
    opt->exact_stats = 0;
}

static pn_status pn_check_vec(pn_context *ctx, const float *v, const char *what)
{
    int c;
    for (c = 0; c < 3; c++) {
        if (!pn_finite(v[c]))
            return pn_fail(ctx, PN_E_NONFINITE, "%s component %u is NaN or infinite", what, (uint32_t)c);
        if (v[c] > PN_MAX_COORD || v[c] < -PN_MAX_COORD)
            return pn_fail(ctx, PN_E_LIMIT, "%s component %u exceeds 2^40 in magnitude", what,
                           (uint32_t)c);
    }
    return PN_OK;
}

static pn_v3 pn_v3_arr(const float *v) { return pn_v3_make(v[0], v[1], v[2]); }

static pn_status pn_setup_view(pn_context *ctx, const pn_camera *cam, uint32_t w, uint32_t h,
                               pn_kview *kv)
{
    pn_status st;
    pn_v3 eye, f, r, u;
    float len;
    if ((st = pn_check_vec(ctx, cam->eye, "camera eye")) != PN_OK) return st;
    if ((st = pn_check_vec(ctx, cam->target, "camera target")) != PN_OK) return st;
    if ((st = pn_check_vec(ctx, cam->up, "camera up")) != PN_OK) return st;
    if (!pn_finite(cam->fov_deg)) return pn_fail(ctx, PN_E_NONFINITE, "camera fov is NaN or infinite");
    if (!(cam->fov_deg > 0.0f && cam->fov_deg < 180.0f))
        return pn_fail(ctx, PN_E_CAMERA, "camera fov must be in (0, 180) degrees");
    eye = pn_v3_arr(cam->eye);
    f = pn_v3_sub(pn_v3_arr(cam->target), eye);
    len = pn_ksqrt(pn_v3_dot(f, f));
    if (!(len > 0.0f) || !pn_finite(len))
        return pn_fail(ctx, PN_E_CAMERA, "camera eye and target coincide");
    /* Issue 20: frames that cannot be formed in float. f.f below FLT_MIN (2^-126) is
     * subnormal: its root has lost bits and f / len is not a unit vector. */
    if (!(pn_v3_dot(f, f) >= 1.17549435e-38f))
        return pn_fail(ctx, PN_E_CAMERA,
                       "camera eye and target are too close (under 1.1e-19 apart) to form a view direction in float");
    f = pn_v3_scale(f, 1.0f / len);
    r = pn_v3_cross(f, pn_v3_arr(cam->up));
    len = pn_ksqrt(pn_v3_dot(r, r));
    /* |f x up| relative to |up|: below ~1e-6 the right vector is noise. */
    if (!(len > 1e-6f * pn_ksqrt(pn_v3_dot(pn_v3_arr(cam->up), pn_v3_arr(cam->up)))) || !(len > 0.0f))
        return pn_fail(ctx, PN_E_CAMERA, "camera up is zero or parallel to the view direction");
    if (!(pn_v3_dot(r, r) >= 1.17549435e-38f)) /* the same for r = f x up */
        return pn_fail(ctx, PN_E_CAMERA,
                       "camera up is too short (|f x up| under 1.1e-19) to form the right vector in float");
    r = pn_v3_scale(r, 1.0f / len);
    u = pn_v3_cross(r, f);
    {
        /* Whatever the route: f, r and u must come out unit (to 1e-3, the tolerance the
         * fuzz targets check normals with). */
        float ef = pn_v3_dot(f, f) - 1.0f, er = pn_v3_dot(r, r) - 1.0f, eu = pn_v3_dot(u, u) - 1.0f;
        if (!(ef * ef < 1e-6f && er * er < 1e-6f && eu * eu < 1e-6f))
            return pn_fail(ctx, PN_E_CAMERA, "camera frame (view, right, up) is not orthonormal in float");
    }
    memcpy(kv->eye, cam->eye, sizeof(kv->eye));
    kv->f[0] = f.x; kv->f[1] = f.y; kv->f[2] = f.z;
    kv->r[0] = r.x; kv->r[1] = r.y; kv->r[2] = r.z;
    kv->u[0] = u.x; kv->u[1] = u.y; kv->u[2] = u.z;
    kv->tan_half = pn_tan_half_deg(cam->fov_deg);
    /* Neighbouring pixels' rays are 2 tan_half / h apart in the image plane, on both axes
     * (square pixels). Below FLT_EPSILON (2^-23, the spacing of floats at |f| = 1) they
     * round to the same direction; a subnormal or zero tan_half (fov under about 1e-36
     * degrees) also makes the projection divide by zero. */
    if (!(kv->tan_half * 2.0f >= 1.1920929e-7f * (float)h))
        return pn_fail(ctx, PN_E_CAMERA,
                       "camera fov is too small for %u image rows: neighbouring pixels' rays coincide in float "
                       "(tan(fov/2) must be at least rows * 2^-24)", h);
    kv->aspect = (float)w / (float)h;
    /* Geometry nearer than this along f is clipped: far below any pixel footprint for a
     * camera outside the scene, and far above float noise. */
    kv->znear = 1e-5f * ctx->scene_diag;
    if (!(kv->znear > 0.0f)) kv->znear = 1e-30f;
    kv->width = w;
    kv->height = h;
    return PN_OK;
}

static pn_status pn_setup_light(pn_context *ctx, const pn_light *l, uint32_t k, float eps, pn_klight *kl)
{
    pn_status st;
    pn_v3 U, V, N;
    float lu, lv, dot;
    if ((st = pn_check_vec(ctx, l->center, "light center")) != PN_OK) return st;
    if ((st = pn_check_vec(ctx, l->u, "light u")) != PN_OK) return st;
    if ((st = pn_check_vec(ctx, l->v, "light v")) != PN_OK) return st;
    U = pn_v3_arr(l->u);
    V = pn_v3_arr(l->v);
    lu = pn_ksqrt(pn_v3_dot(U, U));
    lv = pn_ksqrt(pn_v3_dot(V, V));
    /* Issue 20: only u = v = 0 exactly is a point light. A non-zero half-edge whose square
     * is below FLT_MIN (shorter than 1.1e-19) cannot be normalized in float. */
    if ((U.x != 0.0f || U.y != 0.0f || U.z != 0.0f) && !(pn_v3_dot(U, U) >= 1.17549435e-38f))
        return pn_fail(ctx, PN_E_LIGHT_DEGENERATE,
                       "light half-edge u is too short (under 1.1e-19) to form the light's frame in float "
                       "(u = v = 0 exactly is a point light)");
    if ((V.x != 0.0f || V.y != 0.0f || V.z != 0.0f) && !(pn_v3_dot(V, V) >= 1.17549435e-38f))
        return pn_fail(ctx, PN_E_LIGHT_DEGENERATE,
                       "light half-edge v is too short (under 1.1e-19) to form the light's frame in float "
                       "(u = v = 0 exactly is a point light)");
    memset(kl, 0, sizeof(*kl));
    memcpy(kl->c, l->center, sizeof(kl->c));
    kl->eps = eps;
    /* Culls: 1e-5 of the diagonal for their own rounding. The predicate is exact, so a
     * blocked sample's segment really meets the triangle and no crossing tolerance is
     * added (kernels/pn_reference.h, kernels/pn_gears.h). */
    kl->cull_tol = 1e-5f * ctx->scene_diag;
    if (lu == 0.0f && lv == 0.0f) {
        kl->k = 1;
        kl->is_point = 1;
        return PN_OK;
    }
    if (lu == 0.0f || lv == 0.0f)
        return pn_fail(ctx, PN_E_LIGHT_DEGENERATE,
                       "light half-edge %s is zero while the other is not (both zero: point light)",
                       lu == 0.0f ? "u" : "v");
    dot = pn_v3_dot(U, V);
    if (dot < 0.0f) dot = -dot;
    if (dot > 1e-4f * lu * lv)
        return pn_fail(ctx, PN_E_LIGHT_NOT_ORTHO,
                       "light half-edges u and v must be orthogonal (|u.v| <= 1e-4 |u||v|)");
    /* N: u x v must be normalizable (largest component at least FLT_MIN, as for triangle
     * normals, pn_normal_ok in pn_raster.h), else normalizing it gives NaN. */
    if (!(pn_v3_linf(pn_v3_cross(U, V)) >= 1.17549435e-38f))
        return pn_fail(ctx, PN_E_LIGHT_DEGENERATE,
                       "light u x v is too small (|u| |v| under about 2e-38) to form the light's normal in float");
    N = pn_v3_normalize(pn_v3_cross(U, V));
    memcpy(kl->U, l->u, sizeof(kl->U));
    memcpy(kl->V, l->v, sizeof(kl->V));
    kl->N[0] = N.x;
    kl->N[1] = N.y;
    kl->N[2] = N.z;
    kl->k = k;
    return PN_OK;
}

/* The options every frame and point query reads (not the image size). */
static pn_status pn_check_common(pn_context *ctx, const pn_frame_options *o)
{
    if (!(o->k == 4u || o->k == 8u || o->k == 16u || o->k == 32u) || o->k > PN_MASK_K_MAX)
        return pn_fail(ctx, PN_E_INVALID_ARG, "k = %u; k must be 4, 8, 16 or 32 and <= PN_MASK_K_MAX (%u)",
                       o->k, (uint32_t)PN_MASK_K_MAX);
    if (!pn_finite(o->eps) || !pn_finite(o->albedo) || !pn_finite(o->ambient))
        return pn_fail(ctx, PN_E_NONFINITE, "eps, albedo or ambient is NaN or infinite");
    if (!(o->eps >= 0.0f)) return pn_fail(ctx, PN_E_INVALID_ARG, "eps must be >= 0");
    if (o->eps > PN_MAX_COORD) return pn_fail(ctx, PN_E_LIMIT, "eps exceeds 2^40");
    if (!(o->albedo >= 0.0f && o->albedo <= 1.0f && o->ambient >= 0.0f && o->ambient <= 1.0f))
        return pn_fail(ctx, PN_E_INVALID_ARG, "albedo and ambient must be in [0, 1]");
    if (o->exact_stats > 1u) return pn_fail(ctx, PN_E_INVALID_ARG, "exact_stats must be 0 or 1");
    return PN_OK;
}

/* Whether [p, p + bytes) meets the context's arena block (a caller buffer must not). */
static int pn_in_arena(const pn_context *ctx, const void *p, size_t bytes)
{
    uintptr_t a = (uintptr_t)p, lo = (uintptr_t)ctx->base, hi = lo + ctx->bytes;
    return a < hi && a + bytes > lo;
}

/* A frame's image, or a point query's batch (what: "image" or "batch"), within the limits. */
static pn_status pn_check_size(pn_context *ctx, const pn_frame_options *o, const char *what)
{
    if (o->width == 0u || o->height == 0u)
        return pn_fail(ctx, PN_E_IMAGE_SIZE, "%s size %ux%u has a zero side", what, o->width, o->height);
    if (o->width > ctx->limits.max_width || o->height > ctx->limits.max_height)
        return pn_fail(ctx, PN_E_LIMIT, "%s %ux%u exceeds the context's limits %ux%u", what, o->width, o->height,
                       ctx->limits.max_width, ctx->limits.max_height);
    return PN_OK;
}

static pn_status pn_check_options(pn_context *ctx, const pn_frame_options *o)
{
    size_t px;
    pn_status st;
    if ((st = pn_check_size(ctx, o, "image")) != PN_OK) return st;
    if (o->no_rgba > 1u) return pn_fail(ctx, PN_E_INVALID_ARG, "no_rgba = %u; it must be 0 or 1", o->no_rgba);
    if (o->no_rgba && o->rgba_out)
        return pn_fail(ctx, PN_E_INVALID_ARG, "rgba_out is set but no_rgba turns the RGBA image off");
    px = (size_t)o->width * o->height;
    if ((o->visibility_out && pn_in_arena(ctx, o->visibility_out, px * sizeof(float))) ||
        (o->rgba_out && pn_in_arena(ctx, o->rgba_out, px * 4u)))
        return pn_fail(ctx, PN_E_INVALID_ARG, "%s lies in the context's arena; an output buffer must be the caller's own",
                       o->visibility_out && pn_in_arena(ctx, o->visibility_out, px * sizeof(float)) ? "visibility_out"
                                                                                                     : "rgba_out");
    if (o->gbuffer && (!o->gbuffer->depth || !o->gbuffer->tri_id))
        return pn_fail(ctx, PN_E_INVALID_ARG, "gbuffer: depth and tri_id must not be NULL");
    return pn_check_common(ctx, o);
}

/* A pixel's point of the caller's G-buffer must be one a frame can hold: on a triangle the
 * scene draws, in front of the eye, within 2^40 (computed as the G-buffer pass computes
 * it). Every pixel is read before anything is written. */
static pn_status pn_check_gbuffer(pn_context *ctx, const pn_kview *kv, const pn_gbuffer *g)
{
    uint32_t x, y;
    for (y = 0; y < kv->height; y++)
        for (x = 0; x < kv->width; x++) {
            size_t pix = (size_t)y * kv->width + x;
            uint32_t t = g->tri_id[pix];
            float d;
            pn_v3 P;
            if (t == PN_NO_TRIANGLE) continue;
            if (t >= ctx->tri_count)
                return pn_fail(ctx, PN_E_INDEX_RANGE, "gbuffer pixel (%u, %u) names triangle %u; the scene has %u", x, y,
                               t, ctx->tri_count);
            if (ctx->flags[t] & PN_TRI_DEGENERATE)
                return pn_fail(ctx, PN_E_INVALID_ARG,
                               "gbuffer pixel (%u, %u) names triangle %u, which is degenerate (never drawn)", x, y, t);
            d = g->depth[pix];
            if (!pn_finite(d))
                return pn_fail(ctx, PN_E_NONFINITE, "gbuffer pixel (%u, %u): depth is NaN or infinite", x, y);
            if (!(d > 0.0f))
                return pn_fail(ctx, PN_E_INVALID_ARG, "gbuffer pixel (%u, %u): depth %g must be > 0", x, y, (double)d);
            P = pn_v3_add(pn_view_eye(kv), pn_v3_scale(pn_ray_dir(kv, x, y), d));
            if (!(pn_v3_linf(P) <= PN_MAX_COORD))
                return pn_fail(ctx, PN_E_LIMIT, "gbuffer pixel (%u, %u): its point lies beyond 2^40 (depth %g)", x, y,
                               (double)d);
        }
    return PN_OK;
}

/* The chosen algorithm's own options and parameters (its module's prepare). */
static pn_status pn_prepare_algo(pn_frame_state *fs, const pn_frame_options *o)
{
    if ((uint32_t)o->algo < PN_ALGO_COUNT && (pn_build_info() & (1u << o->algo)) &&
        !(pn_limits_algos(&fs->ctx->limits) & (1u << o->algo)))
        return pn_fail(fs->ctx, PN_E_LIMIT, "algorithm %s is not among the context's pn_limits.algos (flags %u)",
                       pn_algo_name(o->algo), pn_limits_algos(&fs->ctx->limits));
    switch (o->algo) {
#define PN_ALGO_PREPARE(ID, name)                                                              \
    case PN_ALGO_##ID:                                                                         \
        return pn_##name##_prepare(fs, o);
        PN_ALGORITHMS(PN_ALGO_PREPARE)
#undef PN_ALGO_PREPARE
    }
    return pn_fail(fs->ctx, PN_E_INVALID_ARG, "unknown algorithm %u", (uint32_t)o->algo);
}

/* The scene's pools on the port (only when pn_scene_set changed them since). */
static pn_status pn_scene_to_device(pn_frame_state *fs)
{
    pn_context *ctx = fs->ctx;
    pn_port_scene *sc = fs->port->scene;
    pn_status st;
    if (fs->port->host_memory || (sc->valid && sc->version == ctx->scene_version)) return PN_OK;
    sc->valid = 0;
    if ((st = pn_dev_to_device(fs, ctx->tris, (size_t)ctx->tri_count * 9u * sizeof(float))) != PN_OK ||
        (st = pn_dev_to_device(fs, ctx->flags, ctx->tri_count)) != PN_OK ||
        (st = pn_dev_to_device(fs, ctx->wnodes, (size_t)ctx->bvh_wide * sizeof(pn_kbvh4))) != PN_OK ||
        (st = pn_dev_to_device(fs, ctx->tri_index, (size_t)ctx->bvh_refs * sizeof(uint32_t))) != PN_OK ||
        (st = pn_dev_to_device(fs, ctx->raster_index, (size_t)ctx->bvh_tris * sizeof(uint32_t))) != PN_OK)
        return st;
#define PN_ALGO_UPLOAD(ID, name)                                                               \
    if ((pn_limits_algos(&ctx->limits) & (1u << PN_ALGO_##ID)) && (st = pn_##name##_upload(fs)) != PN_OK) return st;
    PN_ALGORITHMS(PN_ALGO_UPLOAD)
#undef PN_ALGO_UPLOAD
    sc->version = ctx->scene_version;
    sc->valid = 1;
    sc->uploads++;
    return PN_OK;
}

/* The positions and normals the resolve wrote, when the frame keeps them. */
static pn_status pn_surface_to_host(pn_frame_state *fs)
{
    size_t px = (size_t)fs->width * fs->height;
    pn_status st;
    if (!fs->pos) return PN_OK;
    if ((st = pn_dev_to_host(fs, fs->pos, px * 3u * sizeof(float))) != PN_OK) return st;
    return pn_dev_to_host(fs, fs->nrm, px * 3u * sizeof(float));
}

/* Primary visibility: per-triangle row ranges, then bands (clear, raster, resolve). */
static pn_status pn_gbuffer_raster(pn_frame_state *fs)
{
    uint32_t npix = fs->width * fs->height;
    size_t px = npix;
    pn_status st;
    if ((st = pn_scene_to_device(fs)) != PN_OK || (st = pn_raster_setup(fs, PN_K_RASTER_ROWS)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_RASTER_BAND, (fs->height + PN_RASTER_BAND - 1u) / PN_RASTER_BAND)) != PN_OK ||
        (st = pn_dev_to_host(fs, fs->depth, px * sizeof(float))) != PN_OK ||
        (st = pn_dev_to_host(fs, fs->tri_id, px * sizeof(uint32_t))) != PN_OK)
        return st;
    return pn_surface_to_host(fs);
}

/* The caller's G-buffer (checked): depth and ids copied in, positions and normals
 * resolved as the rasterizer's band pass resolves its own (PN_K_GBUFFER_RESOLVE). */
static pn_status pn_gbuffer_caller(pn_frame_state *fs, const pn_gbuffer *g)
{
    size_t px = (size_t)fs->width * fs->height, i;
    pn_status st;
    for (i = 0; i < px; i++) {
        fs->tri_id[i] = g->tri_id[i];
        fs->depth[i] = g->tri_id[i] == PN_NO_TRIANGLE ? PN_KINF : g->depth[i];
    }
    if ((st = pn_scene_to_device(fs)) != PN_OK || (st = pn_dev_to_device(fs, fs->depth, px * sizeof(float))) != PN_OK ||
        (st = pn_dev_to_device(fs, fs->tri_id, px * sizeof(uint32_t))) != PN_OK)
        return st;
    if (!fs->pos) return PN_OK; /* recomputed where read */
    if ((st = pn_dev_run(fs, PN_K_GBUFFER_RESOLVE, fs->height)) != PN_OK) return st;
    return pn_surface_to_host(fs);
}

/* The shadow pass of the frame's algorithm. Every algorithm leaves the visibility buffer
 * and one pn_row_counters per row (zeroed here first) for the host. Kept out of line and
 * under its own name (one call a frame): the profiling scripts (tools/bench_profile.sh,
 * tools/exact_profile.sh) switch callgrind's collection on by it, and GCC's clone of it
 * (pn_shadow.constprop.0) left them collecting nothing. */
#if defined(__clang__)
__attribute__((noinline))
#elif defined(__GNUC__)
__attribute__((noinline, noclone))
#endif
static pn_status pn_shadow(pn_frame_state *fs)
{
    uint32_t npix = fs->width * fs->height;
    pn_status st;
    if ((st = pn_dev_fill(fs, fs->counters, fs->height * (uint32_t)(sizeof(pn_row_counters) / 4u), 0u)) != PN_OK)
        return st;
    switch (fs->algo) {
#define PN_ALGO_FRAME(ID, name)                                                                \
    case PN_ALGO_##ID:                                                                         \
        st = pn_##name##_frame(fs);                                                            \
        break;
        PN_ALGORITHMS(PN_ALGO_FRAME)
#undef PN_ALGO_FRAME
    default: return pn_fail(fs->ctx, PN_E_UNSUPPORTED, "algorithm %u not available", fs->algo);
    }
    if (st != PN_OK || (st = pn_dev_to_host(fs, fs->vis, (size_t)npix * sizeof(float))) != PN_OK) return st;
    return pn_dev_to_host(fs, fs->counters, (size_t)fs->height * sizeof(pn_row_counters));
}

static pn_status pn_shade(pn_frame_state *fs)
{
    uint32_t npix = fs->width * fs->height;
    pn_status st;
    if ((st = pn_dev_run(fs, PN_K_SHADE, npix)) != PN_OK) return st;
    return pn_dev_to_host(fs, fs->rgba, (size_t)npix * 4u);
}

void pn_frame_carve(pn_carver *c, uint32_t w, uint32_t h, uint32_t tris, int surface, pn_frame_state *fs)
{
    uint64_t px = (uint64_t)w * h;
    fs->depth = (float *)pn_pool(c, px, sizeof(float), "depth");
    fs->tri_id = (uint32_t *)pn_pool(c, px, sizeof(uint32_t), "tri_id");
    fs->pos = fs->nrm = NULL;
    if (surface) {
        fs->pos = (float *)pn_pool(c, px * 3u, sizeof(float), "position");
        fs->nrm = (float *)pn_pool(c, px * 3u, sizeof(float), "normal");
    }
    fs->vis = (float *)pn_pool(c, px, sizeof(float), "visibility");
    fs->rgba = (uint8_t *)pn_pool(c, px, 4u, "rgba");
    fs->rows = (uint32_t *)pn_pool(c, tris, sizeof(uint32_t), "raster rows");
    fs->chunks = (uint32_t *)pn_pool(c, PN_RASTER_CHUNKS(tris), sizeof(uint32_t), "raster chunks");
    fs->counters = pn_pool(c, h, sizeof(pn_row_counters), "shadow counters");
}

static void pn_frame_pool_offsets(pn_frame_state *fs)
{
    const pn_context *ctx = fs->ctx;
    pn_kpools *P = &fs->P;
    memset(P, 0, sizeof(*P));
    P->tris = pn_dev_off(ctx, ctx->tris);
    P->flags = pn_dev_off(ctx, ctx->flags);
    P->wnodes = pn_dev_off(ctx, ctx->wnodes);
    P->index = pn_dev_off(ctx, ctx->tri_index);
    P->rindex = pn_dev_off(ctx, ctx->raster_index);
    P->depth = pn_dev_off(ctx, fs->depth);
    P->tri_id = pn_dev_off(ctx, fs->tri_id);
    if (fs->pos) { /* else 0: the passes recompute them (pn_surf_of) */
        P->pos = pn_dev_off(ctx, fs->pos);
        P->nrm = pn_dev_off(ctx, fs->nrm);
    }
    P->vis = pn_dev_off(ctx, fs->vis);
    P->rgba = pn_dev_off(ctx, fs->rgba);
    P->rows = pn_dev_off(ctx, fs->rows);
    P->chunks = pn_dev_off(ctx, fs->chunks);
    P->counters = pn_dev_off(ctx, fs->counters);
}

/* What a frame and a point query share, before any pool: the algorithm's prepare, the
 * view (the camera's, or for points a view that only sets the batch's shape), the light,
 * the kernel parameters. */
static pn_status pn_frame_begin(pn_frame_state *fs, pn_context *ctx, const pn_port *port, const pn_camera *camera,
                                const pn_light *light, const pn_frame_options *opt, uint32_t points)
{
    pn_status st;
    memset(fs, 0, sizeof(*fs));
    fs->ctx = ctx;
    fs->port = port;
    fs->points = points;
    if ((st = pn_prepare_algo(fs, opt)) != PN_OK) return st;
    if (camera) {
        if ((st = pn_setup_view(ctx, camera, opt->width, opt->height, &fs->K.view)) != PN_OK) return st;
    } else {
        fs->K.view.width = opt->width;
        fs->K.view.height = opt->height;
    }
    if ((st = pn_setup_light(ctx, light, opt->k, opt->eps, &fs->K.light)) != PN_OK) return st;
#if PN_ENABLE_WEDGES || PN_ENABLE_MCSM
    /* The algorithms that read the winding: which closed objects this light says are
     * inside out. */
    if (opt->algo == PN_ALGO_MCSM || opt->algo == PN_ALGO_WEDGES) pn_connect_light(ctx, &fs->K.light);
#endif
    fs->K.shade.albedo = opt->albedo;
    fs->K.shade.ambient = opt->ambient;
    fs->K.shade.background = (uint32_t)opt->background[0] | ((uint32_t)opt->background[1] << 8) |
                             ((uint32_t)opt->background[2] << 16) | ((uint32_t)opt->background[3] << 24);
    fs->K.tri_count = ctx->tri_count;
    fs->K.raster_tris = ctx->bvh_tris;
    fs->K.exact_stats = opt->exact_stats;
    fs->algo = (uint32_t)opt->algo;
    fs->width = opt->width;
    fs->height = opt->height;
    return PN_OK;
}

/* The frame region carved for the frame's size: the G-buffer and output pools first. */
static pn_status pn_frame_pools(pn_frame_state *fs)
{
    pn_carver c;
    pn_frame_reset(fs->ctx);
    pn_carver_frame(&c, fs->ctx);
    pn_frame_carve(&c, fs->width, fs->height, fs->ctx->tri_count, fs->points || pn_limits_surface(&fs->ctx->limits),
                   fs);
    if (!c.ok) return PN_E_POOL_EXHAUSTED;
    pn_frame_pool_offsets(fs);
    return PN_OK;
}

/* The shadow pass on the G-buffer in place, and its counters into the context's stats. */
static pn_status pn_frame_shadow(pn_frame_state *fs)
{
    pn_context *ctx = fs->ctx;
    const pn_row_counters *cnt = (const pn_row_counters *)fs->counters;
    uint64_t t0 = pn_dev_timestamp(fs);
    uint32_t y;
    pn_status st;
    fs->candidates = fs->blocking = fs->nodes = 0u; /* a point query's batches run one after another */
    fs->lit = fs->overflow = 0u;
    if ((st = pn_shadow(fs)) != PN_OK) return st;
    ctx->pass_ns[PN_PASS_SHADOW] = pn_dev_timestamp(fs) - t0;
    /* Integer sums of the rows' counters: any port, any schedule alike. */
    for (y = 0; y < fs->height; y++) {
        fs->candidates += cnt[y].c.candidates;
        fs->blocking += cnt[y].c.blocking;
        fs->nodes += cnt[y].c.nodes;
        fs->lit += cnt[y].c.lit;
        fs->overflow += cnt[y].c.overflow;
    }
    if (fs->overflow) return pn_fail(ctx, PN_E_INTERNAL, "BVH traversal stack overflowed %u times", fs->overflow);
    ctx->shadow_candidates = fs->candidates;
    ctx->shadow_blocking = fs->blocking;
    ctx->shadow_nodes = fs->nodes;
    ctx->lit_pixels = fs->lit;
    ctx->cull_tol = fs->K.light.cull_tol;
    return PN_OK;
}

pn_status pn_render_with(pn_context *ctx, const pn_port *port, const pn_camera *camera,
                         const pn_light *light, const pn_frame_options *opt, pn_frame *out)
{
    pn_frame_state fs;
    pn_status st;
    size_t px;
    uint64_t t0;
    if (!ctx) return PN_E_INVALID_ARG;
    if (!camera || !light || !opt || !out)
        return pn_fail(ctx, PN_E_INVALID_ARG, "pn_render: camera, light, options and output must not be NULL");
    if (!ctx->has_scene) return pn_fail(ctx, PN_E_NO_SCENE, "pn_render: no scene (call pn_scene_set first)");
    if ((st = pn_check_options(ctx, opt)) != PN_OK) return st;
    if ((st = pn_frame_begin(&fs, ctx, port, camera, light, opt, 0u)) != PN_OK) return st;
    if (opt->gbuffer && (st = pn_check_gbuffer(ctx, &fs.K.view, opt->gbuffer)) != PN_OK) return st;
    if ((st = pn_frame_pools(&fs)) != PN_OK) return st;

    t0 = pn_dev_timestamp(&fs);
    if ((st = opt->gbuffer ? pn_gbuffer_caller(&fs, opt->gbuffer) : pn_gbuffer_raster(&fs)) != PN_OK) return st;
    ctx->pass_ns[PN_PASS_GBUFFER] = pn_dev_timestamp(&fs) - t0;
    if ((st = pn_frame_shadow(&fs)) != PN_OK) return st;
    t0 = pn_dev_timestamp(&fs);
    if (!opt->no_rgba && (st = pn_shade(&fs)) != PN_OK) return st;
    ctx->pass_ns[PN_PASS_SHADE] = pn_dev_timestamp(&fs) - t0;

    px = (size_t)opt->width * opt->height;
    if (opt->visibility_out) memcpy(opt->visibility_out, fs.vis, px * sizeof(float));
    if (opt->rgba_out) memcpy(opt->rgba_out, fs.rgba, px * 4u);
    out->width = opt->width;
    out->height = opt->height;
    out->visibility = fs.vis;
    out->rgba = opt->no_rgba ? NULL : fs.rgba;
    out->tri_id = fs.tri_id;
    out->depth = fs.depth;
    out->position = fs.pos;
    out->normal = fs.nrm;
    return PN_OK;
}

/* The caller's points must be ones a frame could hold: finite, within 2^40, on a triangle
 * the scene draws, with a unit normal. Every point is read before anything is written. */
static pn_status pn_check_points(pn_context *ctx, const float *points, const float *normals, const uint32_t *ids,
                                 uint32_t n)
{
    uint32_t i, c;
    for (i = 0; i < n; i++) {
        uint32_t t = ids[i];
        float nn;
        if (t == PN_NO_TRIANGLE) continue;
        if (t >= ctx->tri_count)
            return pn_fail(ctx, PN_E_INDEX_RANGE, "point %u names triangle %u; the scene has %u", i, t, ctx->tri_count);
        if (ctx->flags[t] & PN_TRI_DEGENERATE)
            return pn_fail(ctx, PN_E_INVALID_ARG, "point %u names triangle %u, which is degenerate", i, t);
        for (c = 0; c < 6u; c++) {
            float v = c < 3u ? points[(size_t)i * 3u + c] : normals[(size_t)i * 3u + c - 3u];
            if (!pn_finite(v))
                return pn_fail(ctx, PN_E_NONFINITE, "point %u: %s component %u is NaN or infinite", i,
                               c < 3u ? "position" : "normal", c % 3u);
            if (c < 3u && (v > PN_MAX_COORD || v < -PN_MAX_COORD))
                return pn_fail(ctx, PN_E_LIMIT, "point %u: position component %u exceeds 2^40 in magnitude", i, c);
        }
        nn = pn_v3_dot(pn_v3_arr(normals + (size_t)i * 3u), pn_v3_arr(normals + (size_t)i * 3u));
        if (!(nn > 0.998f && nn < 1.002f))
            return pn_fail(ctx, PN_E_INVALID_ARG, "point %u: its normal is not unit (|n|^2 = %g)", i, (double)nn);
    }
    return PN_OK;
}

pn_status pn_points_with(pn_context *ctx, const pn_port *port, const pn_light *light, const pn_frame_options *opt,
                         const float *points, const float *normals, const uint32_t *tri_ids, uint32_t n, float *out)
{
    pn_frame_state fs;
    pn_status st;
    uint32_t done;
    if (!ctx) return PN_E_INVALID_ARG;
    if (!light || !opt)
        return pn_fail(ctx, PN_E_INVALID_ARG, "pn_visibility_points: light and options must not be NULL");
    if (n > 0u && (!points || !normals || !tri_ids || !out))
        return pn_fail(ctx, PN_E_INVALID_ARG, "pn_visibility_points: points, normals, tri_ids and out must not be NULL");
    if (!ctx->has_scene) return pn_fail(ctx, PN_E_NO_SCENE, "pn_visibility_points: no scene (call pn_scene_set first)");
    if ((st = pn_check_size(ctx, opt, "batch")) != PN_OK || (st = pn_check_common(ctx, opt)) != PN_OK) return st;
    if (n > 0u && pn_in_arena(ctx, out, (size_t)n * sizeof(float)))
        return pn_fail(ctx, PN_E_INVALID_ARG, "out lies in the context's arena; it must be the caller's own");
    if ((st = pn_frame_begin(&fs, ctx, port, NULL, light, opt, 1u)) != PN_OK) return st;
    if ((st = pn_check_points(ctx, points, normals, tri_ids, n)) != PN_OK) return st;
    /* A batch holds its points' positions and normals: fewer rows where frames keep none. */
    fs.height = fs.K.view.height = pn_points_rows(&ctx->limits, opt->height);
    for (done = 0; done < n;) {
        uint32_t batch = fs.width * fs.height, m = n - done < batch ? n - done : batch, i;
        size_t px = batch;
        if ((st = pn_frame_pools(&fs)) != PN_OK) return st;
        for (i = 0; i < batch; i++) {
            uint32_t t = i < m ? tri_ids[done + i] : PN_NO_TRIANGLE;
            int c;
            fs.tri_id[i] = t;
            fs.depth[i] = t == PN_NO_TRIANGLE ? PN_KINF : 0.0f;
            for (c = 0; c < 3; c++) {
                fs.pos[(size_t)i * 3u + c] = t == PN_NO_TRIANGLE ? 0.0f : points[(size_t)(done + i) * 3u + c];
                fs.nrm[(size_t)i * 3u + c] = t == PN_NO_TRIANGLE ? 0.0f : normals[(size_t)(done + i) * 3u + c];
            }
        }
        if ((st = pn_scene_to_device(&fs)) != PN_OK || (st = pn_dev_to_device(&fs, fs.depth, px * 4u)) != PN_OK ||
            (st = pn_dev_to_device(&fs, fs.tri_id, px * 4u)) != PN_OK ||
            (st = pn_dev_to_device(&fs, fs.pos, px * 12u)) != PN_OK ||
            (st = pn_dev_to_device(&fs, fs.nrm, px * 12u)) != PN_OK || (st = pn_frame_shadow(&fs)) != PN_OK)
            return st;
        memcpy(out + done, fs.vis, (size_t)m * sizeof(float));
        done += m;
    }
    return PN_OK;
}
