/* pn_bench_embree.c - the outside baseline of issue 5: Embree 3 occlusion rays through the
 * same G-buffer points, from the same origins to the same light samples as the library
 * (see pn_bench.h). Built only when CMake finds Embree (PN_BENCH_EMBREE=1); otherwise every
 * entry point reports that it is absent. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pn_bench.h"
#include "pn_bench_kernels.h"

#if PN_BENCH_EMBREE
#include <embree3/rtcore.h>

struct pn_embree {
    RTCDevice device;
    RTCScene scene;
    char info[256];
};

/* Per-pixel query context: Embree hands the context to the filter, which rejects hits on
 * the pixel's own triangle exactly as the reference skips it (t == own). */
typedef struct pn_emb_ctx {
    struct RTCIntersectContext rc; /* first: the filter casts the context back */
    unsigned int own;
} pn_emb_ctx;

/* The primID lane of a hit packet: Embree's RTCHitN_primID, which its header defines for
 * C++ only (RTCHitN is Ng_x, Ng_y, Ng_z, u, v, primID, ... arrays of N each). */
static unsigned int pn_hitn_primid(const struct RTCHitN *hit, unsigned int N, unsigned int i)
{
    return ((const unsigned int *)hit)[5u * N + i];
}

static void pn_emb_filter(const struct RTCFilterFunctionNArguments *a)
{
    const pn_emb_ctx *c = (const pn_emb_ctx *)a->context;
    unsigned int i;
    for (i = 0; i < a->N; i++)
        if (a->valid[i] == -1 && pn_hitn_primid(a->hit, a->N, i) == c->own) a->valid[i] = 0;
}

int pn_embree_compiled(void) { return 1; }

int pn_embree_open(pn_embree **out, int threads, char *err, size_t err_size)
{
    pn_embree *e = (pn_embree *)calloc(1, sizeof(*e));
    char cfg[64];
    if (!e) {
        pn_tools_err(err, err_size, "Embree: out of memory");
        return 1;
    }
    snprintf(cfg, sizeof(cfg), "threads=%d", threads);
    e->device = rtcNewDevice(cfg);
    if (!e->device) {
        pn_tools_err(err, err_size, "rtcNewDevice(\"%s\") failed (error %d)", cfg, (int)rtcGetDeviceError(NULL));
        free(e);
        return 1;
    }
    if (!rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) ||
        rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED)) {
        /* Without filters the own triangle cannot be skipped; with culling, back faces
         * would not block: neither is the predicate. */
        pn_tools_err(err, err_size, "this Embree build lacks filter functions or culls back faces");
        rtcReleaseDevice(e->device);
        free(e);
        return 1;
    }
    snprintf(e->info, sizeof(e->info), "Embree %d.%d.%d (native packets: ray4 %s, ray8 %s, ray16 %s)",
             (int)rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
             (int)rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_VERSION_MINOR),
             (int)rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_VERSION_PATCH),
             rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED) ? "yes" : "no",
             rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) ? "yes" : "no",
             rtcGetDeviceProperty(e->device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) ? "yes" : "no");
    *out = e;
    return 0;
}

const char *pn_embree_info(const pn_embree *e) { return e ? e->info : "Embree: not open"; }

void pn_embree_close(pn_embree *e)
{
    if (!e) return;
    if (e->scene) rtcReleaseScene(e->scene);
    rtcReleaseDevice(e->device);
    free(e);
}

int pn_embree_build(pn_embree *e, const pn_mesh *mesh, int flags, double *build_ms, char *err,
                    size_t err_size)
{
    RTCGeometry geom;
    float *vb;
    unsigned int *ib;
    uint64_t t0;
    if (e->scene) rtcReleaseScene(e->scene);
    e->scene = rtcNewScene(e->device);
    rtcSetSceneFlags(e->scene, (flags & PN_EMBREE_ROBUST) ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    if (flags & PN_EMBREE_HIGH) rtcSetSceneBuildQuality(e->scene, RTC_BUILD_QUALITY_HIGH);
    geom = rtcNewGeometry(e->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    vb = (float *)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                          mesh->vertex_count);
    ib = (unsigned int *)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                 3 * sizeof(unsigned int), mesh->triangle_count);
    if (!vb || !ib) {
        pn_tools_err(err, err_size, "Embree: cannot allocate geometry buffers (error %d)",
                     (int)rtcGetDeviceError(e->device));
        rtcReleaseGeometry(geom);
        return 1;
    }
    memcpy(vb, mesh->positions, (size_t)mesh->vertex_count * 3 * sizeof(float));
    memcpy(ib, mesh->indices, (size_t)mesh->triangle_count * 3 * sizeof(unsigned int));
    rtcSetGeometryOccludedFilterFunction(geom, pn_emb_filter);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(e->scene, geom);
    rtcReleaseGeometry(geom);
    t0 = pn_threads_now_ns(NULL);
    rtcCommitScene(e->scene);
    *build_ms = (double)(pn_threads_now_ns(NULL) - t0) / 1e6;
    if (rtcGetDeviceError(e->device) != RTC_ERROR_NONE) {
        pn_tools_err(err, err_size, "Embree: scene commit failed");
        return 1;
    }
    return 0;
}

typedef struct pn_emb_task {
    pn_embree *e;
    pn_embree_api api;
    const pn_gbuf *g;
    pn_klight light;
    float tfar;
    float *vis;
    pn_masks *masks;
} pn_emb_task;

/* Sample (i, j) as the predicate places it: c + a_i U + b_j V (pn_sample_coord). */
static pn_v3 pn_emb_sample(const pn_klight *L, uint32_t i, uint32_t j)
{
    float a = pn_sample_coord((int32_t)i, L->k), b = pn_sample_coord((int32_t)j, L->k);
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]), V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    return pn_v3_add(pn_v3_add(c, pn_v3_scale(U, a)), pn_v3_scale(V, b));
}

/* k^2 rays of one pixel, one rtcOccluded1 each. */
static void pn_emb_pixel1(pn_emb_task *tk, pn_emb_ctx *ctx, pn_v3 O, uint32_t *m)
{
    uint32_t k = tk->light.k, s;
    for (s = 0; s < k * k; s++) {
        struct RTCRay ray;
        pn_v3 D = pn_v3_sub(pn_emb_sample(&tk->light, s % k, s / k), O);
        ray.org_x = O.x;
        ray.org_y = O.y;
        ray.org_z = O.z;
        ray.tnear = 0.0f;
        ray.dir_x = D.x;
        ray.dir_y = D.y;
        ray.dir_z = D.z;
        ray.time = 0.0f;
        ray.tfar = tk->tfar;
        ray.mask = 0xFFFFFFFFu;
        ray.id = s;
        ray.flags = 0;
        rtcOccluded1(tk->e->scene, &ctx->rc, &ray);
        if (ray.tfar < 0.0f) m[s >> 5] |= 1u << (s & 31u); /* occluded: tfar = -inf */
    }
}

/* The same rays, 16 per rtcOccluded16 packet (k^2 is a multiple of 16 for k >= 4). */
static void pn_emb_pixel16(pn_emb_task *tk, pn_emb_ctx *ctx, pn_v3 O, uint32_t *m)
{
    uint32_t k = tk->light.k, base, l;
    struct RTCRay16 ray;
    int valid[16] __attribute__((aligned(64)));
    for (base = 0; base < k * k; base += 16u) {
        for (l = 0; l < 16u; l++) {
            uint32_t s = base + l;
            pn_v3 D = pn_v3_sub(pn_emb_sample(&tk->light, s % k, s / k), O);
            valid[l] = -1;
            ray.org_x[l] = O.x;
            ray.org_y[l] = O.y;
            ray.org_z[l] = O.z;
            ray.tnear[l] = 0.0f;
            ray.dir_x[l] = D.x;
            ray.dir_y[l] = D.y;
            ray.dir_z[l] = D.z;
            ray.time[l] = 0.0f;
            ray.tfar[l] = tk->tfar;
            ray.mask[l] = 0xFFFFFFFFu;
            ray.id[l] = s;
            ray.flags[l] = 0;
        }
        rtcOccluded16(valid, tk->e->scene, &ctx->rc, &ray);
        for (l = 0; l < 16u; l++)
            if (ray.tfar[l] < 0.0f) m[(base + l) >> 5] |= 1u << ((base + l) & 31u);
    }
}

/* Pixel pix: its k^2 rays (the shadow origin as the library places it). */
static void pn_emb_pixel(pn_emb_task *tk, pn_emb_ctx *ctx, size_t pix)
{
    const pn_gbuf *g = tk->g;
    uint32_t m[PN_MASK_WORDS_MAX];
    pn_v3 O;
    if (g->tri[pix] == PN_NO_TRIANGLE) {
        tk->vis[pix] = 1.0f;
        return;
    }
    if (!pn_shadow_origin(pn_v3_load(g->pos + pix * 3u), pn_v3_load(g->nrm + pix * 3u), &tk->light, &O)) {
        tk->vis[pix] = 0.0f;
        return;
    }
    pn_mask_clear(m);
    /* The receiver's own triangle is not excluded (issue 13): a sample behind its
     * plane is blocked by it, as our horizon blocks it. The filter stays for the
     * exclusion experiment; PN_NO_TRIANGLE matches no primID. */
    ctx->own = PN_NO_TRIANGLE;
    if (tk->api == PN_EMBREE_OCCLUDED16) pn_emb_pixel16(tk, ctx, O, m);
    else pn_emb_pixel1(tk, ctx, O, m);
    tk->vis[pix] = pn_mask_visibility(m, tk->light.k);
    if (tk->masks) {
        tk->masks->lit[pix] = 1;
        memcpy(tk->masks->bits + pix * tk->masks->words, m, tk->masks->words * sizeof(uint32_t));
    }
}

/* Screen tiles [begin, end) (PN_PIX_TILE square, row-major over the image), each tile's
 * pixels row by row: the order the library's per-pixel passes take (pn_pix_tiled), so
 * that both sides meet the same locality. */
static void pn_emb_tiles(void *task, uint32_t begin, uint32_t end)
{
    pn_emb_task *tk = (pn_emb_task *)task;
    const pn_gbuf *g = tk->g;
    uint32_t t, x, y, tw = (g->width + PN_PIX_TILE - 1u) / PN_PIX_TILE;
    pn_emb_ctx ctx;
    rtcInitIntersectContext(&ctx.rc);
    if (tk->api == PN_EMBREE_OCCLUDED16) ctx.rc.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (t = begin; t < end; t++) {
        uint32_t x0 = t % tw * PN_PIX_TILE, y0 = t / tw * PN_PIX_TILE;
        for (y = y0; y < y0 + PN_PIX_TILE && y < g->height; y++)
            for (x = x0; x < x0 + PN_PIX_TILE && x < g->width; x++) pn_emb_pixel(tk, &ctx, (size_t)y * g->width + x);
    }
}

int pn_embree_shadow(pn_embree *e, pn_embree_api api, const pn_gbuf *g, const pn_light *light,
                     uint32_t k, float eps, pn_threads *threads, float *vis, pn_masks *masks,
                     double *ms, char *err, size_t err_size)
{
    pn_emb_task tk;
    uint64_t t0;
    if (!e->scene || k * k < 16u) {
        pn_tools_err(err, err_size, "Embree: no scene, or k = %u below 4", k);
        return 1;
    }
    memset(&tk, 0, sizeof(tk));
    tk.e = e;
    tk.api = api;
    tk.g = g;
    tk.vis = vis;
    tk.masks = masks;
    /* The open segment (O, S): stop a relative 1e-6 short of the sample, the scale of the
     * predicate's own plane tolerance (pn_tri_mask). */
    tk.tfar = 1.0f - 1e-6f;
    pn_bench_klight(light, k, eps, 0.0f, &tk.light);
    t0 = pn_threads_now_ns(NULL);
    pn_threads_parallel_for(threads,
                            ((g->width + PN_PIX_TILE - 1u) / PN_PIX_TILE) * ((g->height + PN_PIX_TILE - 1u) / PN_PIX_TILE),
                            pn_emb_tiles, &tk);
    *ms = (double)(pn_threads_now_ns(NULL) - t0) / 1e6;
    if (rtcGetDeviceError(e->device) != RTC_ERROR_NONE) {
        pn_tools_err(err, err_size, "Embree: occlusion queries failed");
        return 1;
    }
    return 0;
}

#else /* !PN_BENCH_EMBREE */

int pn_embree_compiled(void) { return 0; }

int pn_embree_open(pn_embree **e, int threads, char *err, size_t err_size)
{
    (void)e;
    (void)threads;
    pn_tools_err(err, err_size, "built without Embree (Debian: apt install libembree-dev, then reconfigure)");
    return 1;
}

const char *pn_embree_info(const pn_embree *e)
{
    (void)e;
    return "Embree: not built in";
}

void pn_embree_close(pn_embree *e) { (void)e; }

int pn_embree_build(pn_embree *e, const pn_mesh *mesh, int flags, double *build_ms, char *err,
                    size_t err_size)
{
    (void)e;
    (void)mesh;
    (void)flags;
    (void)build_ms;
    pn_tools_err(err, err_size, "built without Embree");
    return 1;
}

int pn_embree_shadow(pn_embree *e, pn_embree_api api, const pn_gbuf *g, const pn_light *light,
                     uint32_t k, float eps, pn_threads *threads, float *vis, pn_masks *masks,
                     double *ms, char *err, size_t err_size)
{
    (void)e, (void)api, (void)g, (void)light, (void)k, (void)eps, (void)threads, (void)vis, (void)masks, (void)ms;
    pn_tools_err(err, err_size, "built without Embree");
    return 1;
}

#endif

const char *pn_embree_api_name(pn_embree_api api)
{
    return api == PN_EMBREE_OCCLUDED16 ? "rtcOccluded16" : "rtcOccluded1";
}
