/* Cross-port harness (issue 4): every algorithm (pn_algo_name) on the scalar port and on
 * the OpenCL port, compared with memcmp: visibility, RGBA image and the whole G-buffer
 * (depth, triangle ids, positions, normals), plus the statuses, the messages and the
 * counters of pn_stats (the same work in the same order gives the same counts).
 *
 * Scenes: every built-in scene and every .glb in PN_SCENES_DIR (../shared/scenes), each
 * with its area light and with a point light at the light's centre, at sizes that keep
 * the run within a couple of minutes on two cores. Then: k = 4 .. 32, GEARS grids and
 * exact statistics, GEARS tiles from small pair pools (whole grid rows and rows split into
 * runs of cells) and PN_E_POOL_EXHAUSTED, errors and the API's promises (device choice,
 * one scene upload per scene, results in the caller's arena, buffer creation failure).
 *
 * A later algorithm is in by its registry line (src/pn_algorithms.h) and its kernels. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <string.h>

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include "penumbra/opencl.h"
#include "pn_cl_host.h"
#include "penumbra/penumbra.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"

/* Every algorithm: pn_algo 0 .. PN_ALGO_COUNT - 1, named by pn_algo_name, compiled in when
 * pn_build_info() has bit 1u << algo (the registry, src/pn_algorithms.h). */

/* ---- one frame, kept ----------------------------------------------------------------- */

typedef struct pn_xframe {
    size_t n;
    int surface; /* positions and normals kept (the frame has them: not PN_LIMITS_NO_SURFACE) */
    float *vis, *depth, *pos, *nrm;
    uint32_t *ids;
    uint8_t *rgba;
    pn_stats st;
} pn_xframe;

static int xframe_init(pn_xframe *f, size_t n)
{
    f->n = n;
    f->vis = (float *)malloc(n * sizeof(float));
    f->depth = (float *)malloc(n * sizeof(float));
    f->pos = (float *)malloc(n * 3u * sizeof(float));
    f->nrm = (float *)malloc(n * 3u * sizeof(float));
    f->ids = (uint32_t *)malloc(n * sizeof(uint32_t));
    f->rgba = (uint8_t *)malloc(n * 4u);
    return f->vis && f->depth && f->pos && f->nrm && f->ids && f->rgba;
}

static void xframe_free(pn_xframe *f)
{
    free(f->vis);
    free(f->depth);
    free(f->pos);
    free(f->nrm);
    free(f->ids);
    free(f->rgba);
    memset(f, 0, sizeof(*f));
}

static void xframe_keep(pn_xframe *f, const pn_frame *fr, pn_context *ctx)
{
    size_t n = (size_t)fr->width * fr->height;
    memcpy(f->vis, fr->visibility, n * sizeof(float));
    memcpy(f->depth, fr->depth, n * sizeof(float));
    f->surface = fr->position != NULL;
    if (f->surface) {
        memcpy(f->pos, fr->position, n * 3u * sizeof(float));
        memcpy(f->nrm, fr->normal, n * 3u * sizeof(float));
    }
    memcpy(f->ids, fr->tri_id, n * sizeof(uint32_t));
    memcpy(f->rgba, fr->rgba, n * 4u);
    pn_get_stats(ctx, &f->st);
}

/* Pixels whose `size`-byte records differ. */
static size_t count_diff(const void *a, const void *b, size_t n, size_t size)
{
    size_t i, d = 0;
    for (i = 0; i < n; i++) d += memcmp((const uint8_t *)a + i * size, (const uint8_t *)b + i * size, size) != 0;
    return d;
}

static int same_buffer(const char *what, const char *buf, const void *a, const void *b, size_t n, size_t size)
{
    int same = memcmp(a, b, n * size) == 0;
    CHECK_MSG(same, "%s: %s differs in %zu of %zu pixels", what, buf, count_diff(a, b, n, size), n);
    return same;
}

/* Everything of frame b (OpenCL) against kept frame a (scalar): the positions and normals
 * where both have them. */
static int same_frame(const char *what, const pn_xframe *a, const pn_xframe *b)
{
    int ok = 1;
    size_t n = a->n;
    ok &= same_buffer(what, "visibility", a->vis, b->vis, n, sizeof(float));
    ok &= same_buffer(what, "rgba", a->rgba, b->rgba, n, 4u);
    ok &= same_buffer(what, "depth", a->depth, b->depth, n, sizeof(float));
    ok &= same_buffer(what, "tri_id", a->ids, b->ids, n, sizeof(uint32_t));
    if (a->surface && b->surface) {
        ok &= same_buffer(what, "position", a->pos, b->pos, n, 3u * sizeof(float));
        ok &= same_buffer(what, "normal", a->nrm, b->nrm, n, 3u * sizeof(float));
    }
#define SAME_STAT(field)                                                                                   \
    CHECK_MSG(a->st.field == b->st.field, "%s: stats." #field " scalar %llu opencl %llu", what,         \
              (unsigned long long)a->st.field, (unsigned long long)b->st.field)
    SAME_STAT(shadow_candidates);
    SAME_STAT(shadow_blocking);
    SAME_STAT(lit_pixels);
    SAME_STAT(gears.pairs);
    SAME_STAT(gears.assignments);
    SAME_STAT(gears.tiles);
    SAME_STAT(gears.faces);
    SAME_STAT(gears.cells_used);
    SAME_STAT(gears.max_tris_per_cell);
    SAME_STAT(gears.max_pixels_per_cell);
    SAME_STAT(gears.pairs_high_water);
    SAME_STAT(gears.grid);
    SAME_STAT(shadow_nodes);
    SAME_STAT(srt.map);
    SAME_STAT(srt.pip);
    SAME_STAT(srt.thin);
    SAME_STAT(srt.cons_texels);
    SAME_STAT(srt.tiles_masked);
    SAME_STAT(occtex.map);
    SAME_STAT(occtex.slices);
    SAME_STAT(occtex.texels_set);
    SAME_STAT(occtex.outside);
    SAME_STAT(occtex.lookups);
    SAME_STAT(mcsm.map);
    SAME_STAT(mcsm.lit);
    SAME_STAT(mcsm.umbra);
    SAME_STAT(mcsm.penumbra);
    SAME_STAT(mcsm.penumbra_open);
    SAME_STAT(mcsm.penumbra_shut);
    SAME_STAT(mcsm.rays);
    SAME_STAT(mcsm.steps);
    SAME_STAT(mcsm.capped);
    SAME_STAT(mcsm.outside);
    SAME_STAT(mcsm.grazing);
    SAME_STAT(wedges.silhouettes);
    SAME_STAT(wedges.pairs);
    SAME_STAT(wedges.bands);
    SAME_STAT(wedges.sil_bands);
    SAME_STAT(wedges.evaluated);
    SAME_STAT(wedges.touched);
    SAME_STAT(wedges.hard_blockers);
    SAME_STAT(wedges.hard_overflow);
    SAME_STAT(wedges.exact_pixels);
#undef SAME_STAT
    CHECK_MSG(memcmp(&a->st.gears.mean_tris_per_cell, &b->st.gears.mean_tris_per_cell, sizeof(float)) == 0 &&
                  memcmp(&a->st.gears.mean_pixels_per_cell, &b->st.gears.mean_pixels_per_cell, sizeof(float)) == 0,
              "%s: GEARS means differ", what);
    return ok;
}

/* ---- both ports on one configuration --------------------------------------------------- */

typedef struct pn_xrig {
    pn_host h;
    pn_opencl *cl;
    pn_xframe a, b; /* scalar, OpenCL */
    size_t cap;     /* pixels a and b hold */
    int surface;    /* the context's frames keep positions and normals */
} pn_xrig;

static int in_arena(const pn_xrig *r, const void *p, size_t bytes)
{
    const uint8_t *lo = (const uint8_t *)r->h.memory, *q = (const uint8_t *)p;
    return q >= lo && q + bytes <= lo + r->h.bytes;
}

/* Renders opt on both ports; statuses and messages must agree, and on PN_OK everything.
 * Returns the status. */
static pn_status cross(pn_xrig *r, const pn_camera *cam, const pn_light *light, const pn_frame_options *opt,
                       const char *what)
{
    pn_frame fa, fb;
    pn_status sa, sb;
    char msg_a[256];
    size_t n = (size_t)opt->width * opt->height;
    sa = pn_render(r->h.ctx, cam, light, opt, &fa);
    snprintf(msg_a, sizeof(msg_a), "%s", pn_last_error(r->h.ctx));
    if (sa == PN_OK && n > r->cap) { /* the context's limits are the harness's too */
        CHECK_MSG(0, "%s: harness holds %zu pixels, the frame has %zu", what, r->cap, n);
        return PN_E_INTERNAL;
    }
    if (sa == PN_OK) xframe_keep(&r->a, &fa, r->h.ctx);
    sb = pn_opencl_render(r->cl, cam, light, opt, &fb);
    CHECK_MSG(sa == sb, "%s: scalar %s (%s), opencl %s (%s)", what, pn_status_str(sa), msg_a, pn_status_str(sb),
              pn_last_error(r->h.ctx));
    if (sa != PN_OK || sb != PN_OK) {
        if (sa == sb) CHECK_MSG(strcmp(msg_a, pn_last_error(r->h.ctx)) == 0, "%s: messages differ", what);
        return sa != PN_OK ? sa : sb;
    }
    /* The frame points into the caller's arena, as pn_render's does. */
    CHECK_MSG(in_arena(r, fb.visibility, n * 4u) && in_arena(r, fb.rgba, n * 4u) && in_arena(r, fb.tri_id, n * 4u) &&
                  in_arena(r, fb.depth, n * 4u) &&
                  (r->surface ? in_arena(r, fb.position, n * 12u) && in_arena(r, fb.normal, n * 12u)
                              : fb.position == NULL && fb.normal == NULL && fa.position == NULL && fa.normal == NULL),
              "%s: the OpenCL frame does not point into the arena (or has positions it must not)", what);
    CHECK(fb.visibility == fa.visibility && fb.rgba == fa.rgba && fb.width == opt->width && fb.height == opt->height);
    r->b.n = r->a.n = n;
    xframe_keep(&r->b, &fb, r->h.ctx);
    return same_frame(what, &r->a, &r->b) ? PN_OK : PN_E_INTERNAL;
}

static int rig_open(pn_xrig *r, const pn_limits *lim, const pn_opencl_options *opt)
{
    size_t bytes;
    pn_status st;
    memset(r, 0, sizeof(*r));
    r->cap = (size_t)lim->max_width * lim->max_height;
    r->surface = !(lim->flags & PN_LIMITS_NO_SURFACE);
    if (!xframe_init(&r->a, r->cap) || !xframe_init(&r->b, r->cap) || pn_arena_size(lim, &bytes) != PN_OK) return 1;
    r->h.bytes = bytes;
    r->h.memory = malloc(bytes);
    if (!r->h.memory || pn_init(&r->h.ctx, r->h.memory, bytes, lim) != PN_OK) return 1;
    r->h.threads.count = pn_threads_cores();
    pn_set_parallel_for(r->h.ctx, pn_threads_parallel_for, &r->h.threads);
    st = pn_cl_open(r->h.ctx, opt, &r->cl);
    if (st != PN_OK) fprintf(stderr, "pn_opencl_create: %s: %s\n", pn_status_str(st), pn_last_error(r->h.ctx));
    return st != PN_OK;
}

static void rig_close(pn_xrig *r)
{
    pn_cl_close(r->cl);
    xframe_free(&r->a);
    xframe_free(&r->b);
    pn_host_close(&r->h);
}

static pn_light point_light(const pn_light *l)
{
    pn_light p = *l;
    memset(p.u, 0, sizeof(p.u));
    memset(p.v, 0, sizeof(p.v));
    return p;
}

static void opts(pn_frame_options *o, const pn_setup *s, uint32_t w, uint32_t h, uint32_t k, pn_algo algo)
{
    pn_frame_options_default(o);
    o->width = w;
    o->height = h;
    o->k = k;
    o->eps = s->eps;
    o->algo = algo;
}

/* ---- scenes ------------------------------------------------------------------------------ */

typedef struct pn_xscene {
    char src[512];
    int builtin;
    uint32_t w, h, k;
} pn_xscene;

#define PN_X_MAX_SCENES 32

/* Every built-in of pn_builtin_scene_names() (sizes and k chosen per scene where it is dense
 * in shadow rays or has thin features; 48x40, k = 8 otherwise), then every .glb of the shared
 * set in name order, with its view where views.json has one. */
static int list_scenes(pn_xscene *out)
{
    static const pn_xscene sized[] = {{"square", 1, 96, 72, 32}, {"elongated-cube", 1, 80, 64, 16}, {"thin", 1, 64, 48, 4}};
    const char *const *bn = pn_builtin_scene_names();
    struct dirent **names;
    int n = 0, i, m;
    for (; *bn && n < PN_X_MAX_SCENES; bn++) {
        pn_xscene *s = out + n++;
        snprintf(s->src, sizeof(s->src), "%s", *bn);
        s->builtin = 1;
        s->w = 48;
        s->h = 40;
        s->k = 8;
        for (i = 0; i < (int)(sizeof(sized) / sizeof(sized[0])); i++)
            if (strcmp(sized[i].src, *bn) == 0) *s = sized[i];
    }
    m = scandir(PN_SCENES_DIR, &names, NULL, alphasort);
    for (i = 0; i < m; i++) {
        size_t len = strlen(names[i]->d_name);
        if (len > 4 && strcmp(names[i]->d_name + len - 4, ".glb") == 0 && n < PN_X_MAX_SCENES) {
            pn_xscene *s = out + n++;
            snprintf(s->src, sizeof(s->src), "%s/%s", PN_SCENES_DIR, names[i]->d_name);
            s->builtin = 0;
            s->w = 48;
            s->h = 40;
            s->k = 16;
        }
        free(names[i]);
    }
    if (m >= 0) free(names);
    return n;
}

static pn_xrig g_rig;
static pn_xrig g_lean;   /* the same limits with PN_LIMITS_NO_SURFACE | PN_LIMITS_SPARSE_NBUFFER */
static pn_xframe g_kept; /* a frame kept while the rig renders others */

/* The rig's scalar frame of n pixels into g_kept. */
static void keep_frame(size_t n)
{
    g_kept.n = n;
    g_kept.surface = g_rig.a.surface;
    memcpy(g_kept.vis, g_rig.a.vis, n * sizeof(float));
    memcpy(g_kept.depth, g_rig.a.depth, n * sizeof(float));
    memcpy(g_kept.pos, g_rig.a.pos, n * 3u * sizeof(float));
    memcpy(g_kept.nrm, g_rig.a.nrm, n * 3u * sizeof(float));
    memcpy(g_kept.ids, g_rig.a.ids, n * sizeof(uint32_t));
    memcpy(g_kept.rgba, g_rig.a.rgba, n * 4u);
    g_kept.st = g_rig.a.st;
}

/* Frame b (no surface) against frame a of the same options on the other context: every
 * buffer both have, the shadow counters and the frame's own algorithm's stats (another
 * algorithm's stats are whatever each context last ran). */
static void same_lean(const char *what, const pn_xframe *a, const pn_xframe *b, pn_algo algo)
{
    pn_xframe c = *b;
    c.st = a->st;
    c.st.shadow_candidates = b->st.shadow_candidates;
    c.st.shadow_blocking = b->st.shadow_blocking;
    c.st.shadow_nodes = b->st.shadow_nodes;
    c.st.lit_pixels = b->st.lit_pixels;
    switch (algo) {
    case PN_ALGO_GEARS: c.st.gears = b->st.gears; break;
    case PN_ALGO_SRT: c.st.srt = b->st.srt; break;
    case PN_ALGO_OCCTEX: c.st.occtex = b->st.occtex; break;
    case PN_ALGO_MCSM: c.st.mcsm = b->st.mcsm; break;
    case PN_ALGO_WEDGES: c.st.wedges = b->st.wedges; break;
    default: break;
    }
    same_frame(what, a, &c);
}

/* The frame just rendered on both ports (kept in g_kept) again on a context whose frames keep no
 * positions and normals and whose MCSM N-buffer keeps every third level, on both ports: the
 * same visibility, RGBA, depth, ids and stats;
 * with the caller's G-buffer too. Its points (batches of a quarter of the rows) agree
 * across the ports, and for the exact algorithms, whose answer per point does not depend
 * on the batch, with the frame. (va, vb: room for the points' answers) */
static void lean_same(const pn_camera *cam, const pn_light *light, const pn_frame_options *o, const char *what,
                      float *va, float *vb)
{
    pn_frame_options g = *o;
    pn_gbuffer gb;
    pn_status sa, sb;
    size_t n = g_kept.n;
    char w2[300];
    snprintf(w2, sizeof(w2), "%s, no surface", what);
    if (cross(&g_lean, cam, light, o, w2) == PN_OK) same_lean(w2, &g_kept, &g_lean.a, o->algo);
    gb.depth = g_kept.depth;
    gb.tri_id = g_kept.ids;
    g.gbuffer = &gb;
    snprintf(w2, sizeof(w2), "%s, no surface, caller G-buffer", what);
    if (cross(&g_lean, cam, light, &g, w2) == PN_OK) same_lean(w2, &g_kept, &g_lean.a, o->algo);
    if (o->algo == PN_ALGO_WEDGES) return; /* the wedges refuse points (gbuffer_and_points) */
    snprintf(w2, sizeof(w2), "%s, no surface, points", what);
    sa = pn_visibility_points(g_lean.h.ctx, light, o, g_kept.pos, g_kept.nrm, g_kept.ids, (uint32_t)n, va);
    sb = pn_opencl_visibility_points(g_lean.cl, light, o, g_kept.pos, g_kept.nrm, g_kept.ids, (uint32_t)n, vb);
    CHECK_MSG(sa == PN_OK && sb == PN_OK, "%s: scalar %s, opencl %s (%s)", w2, pn_status_str(sa), pn_status_str(sb),
              pn_last_error(g_lean.h.ctx));
    if (sa != PN_OK || sb != PN_OK) return;
    same_buffer(w2, "visibility across the ports", va, vb, n, sizeof(float));
    if (o->algo == PN_ALGO_REFERENCE || o->algo == PN_ALGO_GEARS || o->algo == PN_ALGO_RAYTRACE)
        same_buffer(w2, "visibility against the frame", g_kept.vis, va, n, sizeof(float));
}

/* The frame just rendered on both ports (g_rig.a), again from its own depth and triangle
 * ids handed back as the caller's G-buffer: the same bytes, stats included, on both ports.
 * Then its pixels' points through pn_visibility_points on both ports: the frame's
 * visibility bit for bit (MCSM's against a frame without its screen-space blur and its
 * third layer, which a point query does not run); the wedges refuse points. With `lean`, first lean_same. */
static void gbuffer_and_points(const pn_camera *cam, const pn_light *light, const pn_frame_options *o,
                               const char *what, int lean)
{
    pn_frame_options g = *o;
    pn_gbuffer gb;
    pn_status sa, sb;
    size_t n = (size_t)o->width * o->height;
    float *va = (float *)malloc(n * sizeof(float)), *vb = (float *)malloc(n * sizeof(float));
    char w2[300];
    REQUIRE(va && vb);
    keep_frame(n);
    if (lean) lean_same(cam, light, o, what, va, vb);
    gb.depth = g_kept.depth;
    gb.tri_id = g_kept.ids;
    g.gbuffer = &gb;
    snprintf(w2, sizeof(w2), "%s, caller G-buffer", what);
    if (cross(&g_rig, cam, light, &g, w2) == PN_OK) same_frame(w2, &g_kept, &g_rig.a);

    g = *o;
    if (g.algo == PN_ALGO_MCSM) {
        /* the points' defaults: no blur, and two layers where the frame's default is three
         * (a point has no eye for the third) */
        g.mcsm.blur = PN_MC_BLUR_OFF;
        if (g.mcsm.layers == 0u) g.mcsm.layers = 2u;
        snprintf(w2, sizeof(w2), "%s, no blur", what);
        if (cross(&g_rig, cam, light, &g, w2) != PN_OK) goto done;
        memcpy(g_kept.vis, g_rig.a.vis, n * sizeof(float));
    }
    snprintf(w2, sizeof(w2), "%s, points", what);
    sa = pn_visibility_points(g_rig.h.ctx, light, o, g_kept.pos, g_kept.nrm, g_kept.ids, (uint32_t)n, va);
    sb = pn_opencl_visibility_points(g_rig.cl, light, o, g_kept.pos, g_kept.nrm, g_kept.ids, (uint32_t)n, vb);
    CHECK_MSG(sa == sb, "%s: scalar %s, opencl %s (%s)", w2, pn_status_str(sa), pn_status_str(sb),
              pn_last_error(g_rig.h.ctx));
    if (o->algo == PN_ALGO_WEDGES) {
        CHECK_MSG(sa == PN_E_UNSUPPORTED, "%s: %s, not PN_E_UNSUPPORTED", w2, pn_status_str(sa));
    } else if (sa == PN_OK && sb == PN_OK) {
        same_buffer(w2, "scalar visibility", g_kept.vis, va, n, sizeof(float));
        same_buffer(w2, "opencl visibility", g_kept.vis, vb, n, sizeof(float));
    } else {
        CHECK_MSG(0, "%s: %s (%s)", w2, pn_status_str(sa), pn_last_error(g_rig.h.ctx));
    }
done:
    free(va);
    free(vb);
}

/* Moving geometry on both ports: after pn_scene_update_positions the OpenCL port takes the
 * moved scene (its version changed) and both ports give the bytes of a pn_scene_set of it. */
static void test_update_positions(void)
{
    pn_setup s;
    char err[256];
    float *moved;
    uint32_t v, a;
    REQUIRE(pn_setup_load(&s, "spheres", 1, -1, err, sizeof(err)) == 0);
    moved = (float *)malloc((size_t)s.mesh.vertex_count * 12u);
    REQUIRE(moved != NULL);
    for (v = 0; v < s.mesh.vertex_count; v++) {
        const float *p = s.mesh.positions + (size_t)v * 3u;
        float lift = v % 3u == 0u ? 0.05f * s.diag : 0.0f; /* every third vertex: shapes change too */
        moved[v * 3u] = p[0] + 0.02f * s.diag;
        moved[v * 3u + 1u] = p[1] + lift;
        moved[v * 3u + 2u] = p[2];
    }
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        pn_frame_options o;
        char what[128];
        if (!(pn_build_info() & (1u << a))) continue;
        opts(&o, &s, 48, 40, 8, (pn_algo)a);
        snprintf(what, sizeof(what), "spheres moved, %s", pn_algo_name((pn_algo)a));
        REQUIRE(pn_setup_upload(g_rig.h.ctx, &s) == PN_OK);
        CHECK(cross(&g_rig, &s.camera, &s.light, &o, what) == PN_OK); /* the port holds the first scene */
        REQUIRE(pn_scene_update_positions(g_rig.h.ctx, moved, s.mesh.vertex_count, s.mesh.indices,
                                          s.mesh.triangle_count) == PN_OK);
        if (cross(&g_rig, &s.camera, &s.light, &o, what) != PN_OK) continue;
        g_kept.n = g_rig.a.n;
        memcpy(g_kept.vis, g_rig.a.vis, g_kept.n * 4u);
        memcpy(g_kept.rgba, g_rig.a.rgba, g_kept.n * 4u);
        /* pn_scene_set clears the receiver marking the update kept: marked again */
        REQUIRE(pn_scene_set(g_rig.h.ctx, moved, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
        REQUIRE(pn_scene_set_receivers(g_rig.h.ctx, s.mesh.receiver_first, s.mesh.receiver_count) == PN_OK);
        if (cross(&g_rig, &s.camera, &s.light, &o, what) != PN_OK) continue;
        CHECK_MSG(memcmp(g_kept.vis, g_rig.a.vis, g_kept.n * 4u) == 0 && memcmp(g_kept.rgba, g_rig.a.rgba, g_kept.n * 4u) == 0,
                  "%s: the refitted scene's frame is not the rebuilt one's", what);
    }
    free(moved);
    pn_setup_free(&s);
}

static pn_xscene g_scenes[PN_X_MAX_SCENES];
static pn_setup g_setups[PN_X_MAX_SCENES];
static int g_loaded[PN_X_MAX_SCENES], g_nscenes;

static void test_scenes(void)
{
    int i, glbs = 0, lean;
    for (i = 0; i < g_nscenes; i++) {
        const pn_setup *s = &g_setups[i];
        int q;
        size_t a;
        glbs += !g_scenes[i].builtin;
        if (!g_loaded[i]) continue;
        CHECK_MSG(pn_scene_set(g_rig.h.ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices,
                               s->mesh.triangle_count) == PN_OK,
                  "%s: %s", s->name, pn_last_error(g_rig.h.ctx));
        lean = pn_scene_set(g_lean.h.ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices,
                            s->mesh.triangle_count) == PN_OK;
        CHECK_MSG(lean, "%s, no surface: %s", s->name, pn_last_error(g_lean.h.ctx));
        for (q = 0; q < 2; q++) {
            pn_light light = q ? point_light(&s->light) : s->light;
            for (a = 0; a < PN_ALGO_COUNT; a++) {
                pn_frame_options o;
                char what[256];
                if (!(pn_build_info() & (1u << a))) continue;
                opts(&o, s, g_scenes[i].w, g_scenes[i].h, g_scenes[i].k, (pn_algo)a);
                snprintf(what, sizeof(what), "%s %ux%u k=%u %s light, %s", s->name, o.width, o.height, o.k,
                         q ? "point" : "area", pn_algo_name((pn_algo)a));
                if (cross(&g_rig, &s->camera, &light, &o, what) == PN_OK) {
                    fprintf(stderr, "same: %s (%u lit pixels, %llu candidates)\n", what, g_rig.a.st.lit_pixels,
                            (unsigned long long)g_rig.a.st.shadow_candidates);
                    gbuffer_and_points(&s->camera, &light, &o, what, lean);
                }
            }
        }
    }
    /* The shared set is there (a missing ../shared would otherwise pass vacuously). */
    CHECK_MSG(glbs >= 1, "no .glb scene in %s", PN_SCENES_DIR);
}

/* k = 4 .. 32 on spot; GEARS grids 1 and 37 and exact statistics on spheres. */
static void test_options(void)
{
    static const uint32_t ks[4] = {4, 8, 16, 32};
    pn_setup s;
    char err[256], what[256];
    size_t a;
    int i;
    pn_frame_options o;
    REQUIRE(pn_setup_load(&s, PN_SCENES_DIR "/spot.glb", 0, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(g_rig.h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) ==
            PN_OK);
    for (i = 0; i < 4; i++)
        for (a = 0; a < PN_ALGO_COUNT; a++) {
            if (!(pn_build_info() & (1u << a))) continue;
            opts(&o, &s, 40, 32, ks[i], (pn_algo)a);
            snprintf(what, sizeof(what), "spot k=%u %s", ks[i], pn_algo_name((pn_algo)a));
            CHECK(cross(&g_rig, &s.camera, &s.light, &o, what) == PN_OK);
        }
    /* Without a clock the frame takes no timestamps, and the OpenCL port then never waits
     * for the device between passes (pn_dev_timestamp): the same bytes all the same. */
    REQUIRE(pn_set_clock(g_rig.h.ctx, NULL, NULL) == PN_OK);
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        pn_stats st;
        if (!(pn_build_info() & (1u << a))) continue;
        opts(&o, &s, 40, 32, 16, (pn_algo)a);
        snprintf(what, sizeof(what), "spot k=16 %s, no clock", pn_algo_name((pn_algo)a));
        CHECK(cross(&g_rig, &s.camera, &s.light, &o, what) == PN_OK);
        CHECK(pn_get_stats(g_rig.h.ctx, &st) == PN_OK && st.pass_ns[PN_PASS_SHADOW] == 0u);
    }
    REQUIRE(pn_set_clock(g_rig.h.ctx, pn_threads_now_ns, NULL) == PN_OK);
    pn_setup_free(&s);
    REQUIRE(pn_setup_load(&s, "spheres", 1, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(g_rig.h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) ==
            PN_OK);
    for (i = 0; i < 3 && (pn_build_info() & PN_BUILD_GEARS); i++) {
        opts(&o, &s, 40, 40, 16, PN_ALGO_GEARS);
        o.gears.grid = i == 0 ? 1u : 37u;
        o.exact_stats = i == 2;
        snprintf(what, sizeof(what), "spheres GEARS grid %u exact_stats %u", o.gears.grid, o.exact_stats);
        CHECK(cross(&g_rig, &s.camera, &s.light, &o, what) == PN_OK);
    }
    /* Occlusion textures: every filter, combination and slice count at the extremes, the
     * leak fix on, an odd map size (mipmap levels with partial blocks), a point light. */
    if (pn_build_info() & PN_BUILD_OCCTEX) {
        static const uint32_t slices[3] = {2u, 5u, 16u}, maps[3] = {64u, 37u, 512u};
        for (i = 0; i < 3 * 3 * 3; i++) {
            pn_light light = i % 9 == 4 ? point_light(&s.light) : s.light;
            opts(&o, &s, 40, 40, 16, PN_ALGO_OCCTEX);
            o.occtex.filter = 1u + (uint32_t)i % 3u;
            o.occtex.combine = 1u + (uint32_t)(i / 3) % 3u;
            o.occtex.slices = slices[(i / 9) % 3];
            o.occtex.map = maps[(i + i / 9) % 3];
            o.occtex.flags = ((i & 1) ? PN_OCC_LEAK_FIX : 0u) | (i % 4 == 2 ? PN_OCC_PAPER_FADE : 0u);
            snprintf(what, sizeof(what), "spheres occtex filter %u combine %u slices %u map %u flags %u%s",
                     o.occtex.filter, o.occtex.combine, o.occtex.slices, o.occtex.map, o.occtex.flags, i % 9 == 4 ? " point light" : "");
            CHECK(cross(&g_rig, &s.camera, &light, &o, what) == PN_OK);
        }
    }
    /* Monte Carlo shadow maps: every layer count and search, 1 .. 8 rays, blur off / 1 / 8,
     * an odd map size, no bias, no classification, another frame key, a point light; the
     * ground marked receiver-only half the time. */
    if (pn_build_info() & PN_BUILD_MCSM) {
        static const uint32_t maps[3] = {64u, 37u, 256u}, rays[4] = {1u, 2u, 3u, 8u},
                              blurs[3] = {PN_MC_BLUR_OFF, 1u, 8u};
        for (i = 0; i < 24; i++) {
            pn_light light = i % 7 == 3 ? point_light(&s.light) : s.light;
            REQUIRE(pn_scene_set_receivers(g_rig.h.ctx, s.mesh.receiver_first, (i & 1) ? s.mesh.receiver_count : 0u) ==
                    PN_OK);
            opts(&o, &s, 40, 40, 16, PN_ALGO_MCSM);
            o.mcsm.layers = 1u + (uint32_t)i % 3u;
            o.mcsm.search = 1u + (uint32_t)(i / 3) % 2u;
            o.mcsm.rays = rays[(i / 2) % 4];
            o.mcsm.blur = blurs[(i / 4) % 3];
            o.mcsm.map = maps[(i + i / 6) % 3];
            o.mcsm.flags = (i % 5 == 2 ? PN_MC_NO_BIAS : 0u) | (i % 6 == 5 ? PN_MC_NO_CLASSIFY : 0u) |
                           (i % 4 == 1 ? PN_MC_NO_STACKED : 0u);
            o.mcsm.seed = (uint32_t)i * 2654435761u;
            snprintf(what, sizeof(what), "spheres mcsm layers %u search %u rays %u blur %u map %u flags %u%s%s",
                     o.mcsm.layers, o.mcsm.search, o.mcsm.rays, o.mcsm.blur, o.mcsm.map, o.mcsm.flags,
                     i % 7 == 3 ? " point light" : "", (i & 1) ? " receivers" : "");
            CHECK(cross(&g_rig, &s.camera, &light, &o, what) == PN_OK);
        }
        REQUIRE(pn_scene_set_receivers(g_rig.h.ctx, 0u, 0u) == PN_OK);
    }
    /* Penumbra wedges: blended and additive, area and point light. */
    if (pn_build_info() & PN_BUILD_WEDGES) {
        for (i = 0; i < 4; i++) {
            pn_light light = i >= 2 ? point_light(&s.light) : s.light;
            opts(&o, &s, 40, 40, 16, PN_ALGO_WEDGES);
            o.wedges.mode = (i & 1) ? PN_WG_MODE_ADDITIVE : PN_WG_MODE_BLEND;
            snprintf(what, sizeof(what), "spheres wedges mode %u%s", o.wedges.mode, i >= 2 ? " point light" : "");
            CHECK(cross(&g_rig, &s.camera, &light, &o, what) == PN_OK);
        }
    }
    pn_setup_free(&s);
}

/* A rig for scene s at w x h whose GEARS and wedge pair pools are gears_pairs and wg_pairs
 * and whose wedge silhouette pool is wg_sils (0: the default), the scene set; 0, or 1 after
 * a failed check (the rig closed). */
static int small_rig(pn_xrig *r, const pn_setup *s, uint32_t w, uint32_t h, uint32_t gears_pairs, uint32_t wg_pairs,
                     uint32_t wg_sils)
{
    pn_limits lim;
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = s->mesh.triangle_count;
    lim.max_width = w;
    lim.max_height = h;
    lim.gears_pairs = gears_pairs;
    lim.wg_pairs = wg_pairs;
    lim.wg_silhouettes = wg_sils;
    if (rig_open(r, &lim, NULL) != 0 ||
        pn_scene_set(r->h.ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) !=
            PN_OK) {
        CHECK_MSG(0, "small-pool rig: %s", r->h.ctx ? pn_last_error(r->h.ctx) : "no context");
        rig_close(r);
        return 1;
    }
    return 0;
}

/* The wedges through bands of one pool (sil: 0 the pair pool, 1 the silhouette pool),
 * against the one-band frame `one` (pairs pairs), on both ports (cross: the same bytes): a
 * pool of a third of the frame's pairs (half its silhouettes: bands of tile rows), the same
 * bytes as one band; the least pool (2 pairs, 64 silhouettes), where tiles whose lists
 * outgrow it are full (their pixels the reference's: test_wedges checks which); and, found
 * by bisection, the least pool without a full tile (the fullest tile's list), the same bytes
 * as one band in rows cut into runs of tiles (more bands than the five tile rows), and one
 * less, a full tile. */
static pn_status wedge_pool(const pn_setup *s, const pn_frame_options *o, uint32_t pool, int sil, pn_wedges_stats *ws,
                            int *same, const float *one)
{
    pn_xrig small;
    pn_status st;
    char what[256];
    if (small_rig(&small, s, 96, 72, 0u, sil ? 0u : pool, sil ? pool : 0u) != 0) return PN_E_INTERNAL;
    snprintf(what, sizeof(what), "spheres wedges, %s pool %u", sil ? "silhouette" : "pair", pool);
    st = cross(&small, &s->camera, &s->light, o, what);
    CHECK_MSG(st == PN_OK, "%s: %s", what, pn_status_str(st));
    *ws = small.b.st.wedges;
    *same = memcmp(small.b.vis, one, 96u * 72u * sizeof(float)) == 0;
    rig_close(&small);
    return st;
}

static void wedge_pools(const pn_setup *s, const pn_frame_options *o, const float *one, uint64_t pairs, int sil)
{
    uint32_t pool = sil ? g_rig.a.st.wedges.silhouettes / 2u : (uint32_t)(pairs / 3u), lo = sil ? 64u : 2u, hi;
    pn_wedges_stats ws;
    int same;
    if (wedge_pool(s, o, pool, sil, &ws, &same, one) != PN_OK) return;
    CHECK_MSG((sil ? ws.sil_bands : ws.bands) >= (sil ? 2u : 3u) && ws.pairs == pairs && ws.full_tiles == 0u && same,
              "%s pool %u: %u bands, %u full tiles, %s", sil ? "silhouette" : "pair", pool, sil ? ws.sil_bands : ws.bands,
              ws.full_tiles, same ? "the same bytes" : "other bytes");
    if (wedge_pool(s, o, lo, sil, &ws, &same, one) != PN_OK) return;
    fprintf(stderr, "%s pool %u: %u full tiles of %u, %u exact pixels\n", sil ? "silhouette" : "pair", lo, ws.full_tiles,
            6u * 5u, ws.exact_pixels);
    CHECK(ws.full_tiles > 0u && ws.exact_pixels > 0u && !same);
    /* the least pool without a full tile lies in (lo, pool] */
    hi = pool;
    while (hi - lo > 1u) {
        uint32_t mid = lo + (hi - lo) / 2u;
        if (wedge_pool(s, o, mid, sil, &ws, &same, one) != PN_OK) return;
        if (ws.full_tiles > 0u)
            lo = mid;
        else
            hi = mid;
    }
    if (wedge_pool(s, o, hi, sil, &ws, &same, one) != PN_OK) return;
    fprintf(stderr, "the least %s pool without a full tile: %u, %u bands\n", sil ? "silhouette" : "pair", hi,
            sil ? ws.sil_bands : ws.bands);
    CHECK_MSG(ws.full_tiles == 0u && same && ws.pairs == pairs && (sil ? ws.sil_bands : ws.bands) >= 6u,
              "%s pool %u: %u full tiles, %u bands", sil ? "silhouette" : "pair", hi, ws.full_tiles,
              sil ? ws.sil_bands : ws.bands);
    if (wedge_pool(s, o, hi - 1u, sil, &ws, &same, one) != PN_OK) return;
    CHECK(ws.full_tiles > 0u);
}

/* The wedges through bands of their pair pool and of their silhouette pool (wedge_pools),
 * against the one-band frame, on both ports. */
static void test_wedge_bands(void)
{
    pn_setup s;
    char err[256];
    pn_frame_options o;
    pn_xframe one;
    uint64_t pairs;
    if (!(pn_build_info() & PN_BUILD_WEDGES)) return;
    REQUIRE(pn_setup_load(&s, "spheres", 1, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(g_rig.h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) ==
            PN_OK);
    REQUIRE(xframe_init(&one, 96u * 72u));
    opts(&o, &s, 96, 72, 16, PN_ALGO_WEDGES);
    REQUIRE(cross(&g_rig, &s.camera, &s.light, &o, "spheres wedges one band") == PN_OK);
    CHECK(g_rig.a.st.wedges.bands == 1u);
    pairs = g_rig.a.st.wedges.pairs;
    memcpy(one.vis, g_rig.a.vis, 96u * 72u * sizeof(float));
    wedge_pools(&s, &o, one.vis, pairs, 0);
    wedge_pools(&s, &o, one.vis, pairs, 1);
    xframe_free(&one);
    pn_setup_free(&s);
}

/* GEARS through tiles: pair pools of a fifth of the frame's pairs (runs of grid rows) and
 * far below one grid row (rows split into runs of cells), against the one-pass frame;
 * and a pool below the largest cell: PN_E_POOL_EXHAUSTED on both ports. */
static void test_tiling(void)
{
    pn_setup s;
    char err[256], what[256];
    pn_frame_options o;
    pn_xframe one;
    uint64_t pairs;
    uint32_t max_cell, pools[3], i, q;
    if (!(pn_build_info() & PN_BUILD_GEARS)) return; /* GEARS' pair pool */
    REQUIRE(pn_setup_load(&s, "spheres", 1, -1, err, sizeof(err)) == 0);
    REQUIRE(pn_scene_set(g_rig.h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) ==
            PN_OK);
    REQUIRE(xframe_init(&one, 48u * 48u));
    for (q = 0; q < 2; q++) {
        pn_light light = q ? point_light(&s.light) : s.light;
        opts(&o, &s, 48, 48, 16, PN_ALGO_GEARS);
        o.gears.grid = 32;
        snprintf(what, sizeof(what), "spheres GEARS one pass, %s light", q ? "point" : "area");
        REQUIRE(cross(&g_rig, &s.camera, &light, &o, what) == PN_OK);
        CHECK(q ? g_rig.a.st.gears.tiles <= g_rig.a.st.gears.faces : g_rig.a.st.gears.tiles == 1u);
        pairs = g_rig.a.st.gears.pairs;
        max_cell = g_rig.a.st.gears.max_tris_per_cell;
        memcpy(one.vis, g_rig.a.vis, 48u * 48u * sizeof(float));
        pools[0] = (uint32_t)(pairs / 5u);
        pools[1] = max_cell + max_cell / 2u; /* below a grid row of 32 cells: split rows */
        pools[2] = max_cell - 1u;            /* below the largest cell */
        for (i = 0; i < 3; i++) {
            pn_xrig small;
            pn_status st;
            if (small_rig(&small, &s, 48, 48, pools[i], 0u, 0u) != 0) continue;
            snprintf(what, sizeof(what), "spheres GEARS %s light, pool %u of %llu pairs (largest cell %u)",
                     q ? "point" : "area", pools[i], (unsigned long long)pairs, max_cell);
            st = cross(&small, &s.camera, &light, &o, what);
            if (i < 2) {
                CHECK_MSG(st == PN_OK, "%s", what);
                CHECK_MSG(small.b.st.gears.tiles > 1u, "%s: %u tiles", what, small.b.st.gears.tiles);
                CHECK_MSG(i == 0 || small.b.st.gears.tiles > (uint32_t)(pairs / pools[1]),
                          "%s: %u tiles, no row split?", what, small.b.st.gears.tiles);
                CHECK_MSG(memcmp(small.b.vis, one.vis, 48u * 48u * sizeof(float)) == 0, "%s: differs from one pass",
                          what);
                fprintf(stderr, "same: %s: %u tiles\n", what, small.b.st.gears.tiles);
            } else {
                CHECK_MSG(st == PN_E_POOL_EXHAUSTED, "%s: %s", what, pn_status_str(st));
                CHECK(strstr(pn_last_error(small.h.ctx), "gears pairs") != NULL);
            }
            rig_close(&small);
        }
    }
    xframe_free(&one);
    pn_setup_free(&s);
}

/* ---- the API's promises ------------------------------------------------------------------ */

static void test_api(void)
{
    pn_setup s;
    char err[256];
    pn_opencl *cl = NULL, *other = NULL;
    pn_opencl_options o;
    pn_opencl_info info, info2;
    pn_frame_options fo;
    pn_frame fr;
    pn_status st;
    const char *env = getenv("PN_OPENCL_DEVICE");
    char saved_env[256] = "";
    if (env) snprintf(saved_env, sizeof(saved_env), "%s", env);

    CHECK(pn_cl_open(NULL, NULL, &cl) == PN_E_INVALID_ARG);
    CHECK(pn_cl_open(g_rig.h.ctx, NULL, NULL) == PN_E_INVALID_ARG);
    CHECK(pn_opencl_render(NULL, NULL, NULL, NULL, NULL) == PN_E_INVALID_ARG);
    CHECK(pn_opencl_get_info(NULL, &info) == PN_E_INVALID_ARG);
    CHECK(pn_opencl_get_info(g_rig.cl, NULL) == PN_E_INVALID_ARG);
    CHECK(strcmp(pn_opencl_device_name(NULL), "") == 0);
    pn_cl_close(NULL);
    CHECK(strlen(pn_opencl_device_name(g_rig.cl)) > 0);
    fprintf(stderr, "device: %s\n", pn_opencl_device_name(g_rig.cl));

    /* The port's state lives in caller memory: NULL and short blocks are refused before
     * anything is written; a static block of PN_OPENCL_BYTES at any alignment works, and
     * destroy hands the block back. */
    {
        static unsigned char block[PN_OPENCL_BYTES + 64u];
        size_t need = pn_opencl_size(), mis;
        CHECK(need > 0u && need <= PN_OPENCL_BYTES);
        CHECK(pn_opencl_create(g_rig.h.ctx, NULL, NULL, need, &cl) == PN_E_INVALID_ARG);
        memset(block, 0x5A, sizeof(block));
        cl = NULL;
        CHECK(pn_opencl_create(g_rig.h.ctx, NULL, block, need - 1u, &cl) == PN_E_ARENA_TOO_SMALL && cl == NULL);
        CHECK(strstr(pn_last_error(g_rig.h.ctx), "needs") != NULL);
        for (mis = 0; mis < sizeof(block) && block[mis] == 0x5A; mis++) {
        }
        CHECK(mis == sizeof(block));
        for (mis = 0; mis < 64u; mis += 21u) {
            st = pn_opencl_create(g_rig.h.ctx, NULL, block + mis, PN_OPENCL_BYTES, &cl);
            CHECK_MSG(st == PN_OK, "block at +%zu: %s", mis, pn_last_error(g_rig.h.ctx));
            if (st == PN_OK) CHECK(pn_opencl_destroy(cl) == (void *)(block + mis));
        }
        CHECK(pn_opencl_destroy(NULL) == NULL);
        cl = NULL;
    }

    /* Device strings: an option, then the environment; no match is PN_E_DEVICE. */
    pn_opencl_options_default(&o);
    o.device = "no-such-opencl-device";
    cl = NULL;
    CHECK(pn_cl_open(g_rig.h.ctx, &o, &cl) == PN_E_DEVICE && cl == NULL);
    CHECK(strstr(pn_last_error(g_rig.h.ctx), "no-such-opencl-device") != NULL);
    o.device = "0:999";
    CHECK(pn_cl_open(g_rig.h.ctx, &o, &cl) == PN_E_DEVICE && cl == NULL);
    setenv("PN_OPENCL_DEVICE", "no-such-opencl-device", 1);
    CHECK(pn_cl_open(g_rig.h.ctx, NULL, &cl) == PN_E_DEVICE && cl == NULL);
    /* The option wins over the environment: the device the harness runs on (the caller's
     * PN_OPENCL_DEVICE, e.g. "gpu" on a GPU machine; else the default, a CPU device). */
    o.device = env ? saved_env : "cpu";
    st = pn_cl_open(g_rig.h.ctx, &o, &other);
    CHECK_MSG(st == PN_OK, "%s", pn_last_error(g_rig.h.ctx));
    setenv("PN_OPENCL_DEVICE", "0:0", 1);
    st = pn_cl_open(g_rig.h.ctx, NULL, &cl);
    CHECK_MSG(st == PN_OK, "%s", pn_last_error(g_rig.h.ctx));
    if (env) setenv("PN_OPENCL_DEVICE", saved_env, 1);
    else unsetenv("PN_OPENCL_DEVICE");

    /* Validation and statuses as pn_render's: no scene yet on a fresh context. */
    {
        pn_xrig fresh;
        pn_limits lim = {64, 16, 16, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        pn_camera cam = {{0, 1, 3}, {0, 0, 0}, {0, 1, 0}, 45.0f};
        pn_light light = {{0, 3, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}};
        static const float quad[12] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
        static const uint32_t idx[6] = {0, 2, 1, 0, 3, 2};
        REQUIRE(rig_open(&fresh, &lim, NULL) == 0);
        pn_frame_options_default(&fo);
        fo.width = fo.height = 16;
        CHECK(cross(&fresh, &cam, &light, &fo, "no scene") == PN_E_NO_SCENE);
        REQUIRE(pn_scene_set(fresh.h.ctx, quad, 4, idx, 2) == PN_OK);
        fo.k = 3;
        CHECK(cross(&fresh, &cam, &light, &fo, "k = 3") == PN_E_INVALID_ARG);
        fo.k = 16;
        fo.width = 17;
        CHECK(cross(&fresh, &cam, &light, &fo, "17 wide") == PN_E_LIMIT);
        fo.width = 16;
        fo.algo = (pn_algo)77;
        CHECK(cross(&fresh, &cam, &light, &fo, "algo 77") == PN_E_INVALID_ARG);
        pn_frame_options_default(&fo); /* the reference, or what the build has */
        fo.width = fo.height = 16;
        light.v[0] = 0.25f;
        CHECK(cross(&fresh, &cam, &light, &fo, "skewed light") == PN_E_LIGHT_NOT_ORTHO);
        light.v[0] = 0.0f;
        cam.fov_deg = 180.0f;
        CHECK(cross(&fresh, &cam, &light, &fo, "fov 180") == PN_E_CAMERA);
        cam.fov_deg = 45.0f;
        CHECK(cross(&fresh, &cam, &light, &fo, "quad") == PN_OK);
        rig_close(&fresh);
    }

    /* One upload per scene: frames alone upload nothing, a new scene once. */
    REQUIRE(pn_setup_load(&s, "square", 1, -1, err, sizeof(err)) == 0);
    if (cl) {
        REQUIRE(pn_scene_set(g_rig.h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) ==
                PN_OK);
        uint32_t last = PN_ALGO_COUNT;
        while (last > 0 && !(pn_build_info() & (1u << (last - 1)))) last--;
        pn_frame_options_default(&fo);
        opts(&fo, &s, 32, 32, 8, fo.algo); /* the reference, or what the build has */
        REQUIRE(pn_opencl_get_info(cl, &info) == PN_OK);
        CHECK(pn_opencl_render(cl, &s.camera, &s.light, &fo, &fr) == PN_OK);
        CHECK(pn_opencl_render(cl, &s.camera, &s.light, &fo, &fr) == PN_OK);
        fo.algo = (pn_algo)(last - 1); /* another algorithm where the build has one */
        CHECK(pn_opencl_render(cl, &s.camera, &s.light, &fo, &fr) == PN_OK);
        REQUIRE(pn_opencl_get_info(cl, &info2) == PN_OK);
        CHECK_MSG(info2.scene_uploads == info.scene_uploads + 1u, "uploads %u -> %u", info.scene_uploads,
                  info2.scene_uploads);
        CHECK(pn_render(g_rig.h.ctx, &s.camera, &s.light, &fo, &fr) == PN_OK); /* scalar: no upload either */
        CHECK(pn_scene_set(g_rig.h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) ==
              PN_OK);
        CHECK(pn_opencl_render(cl, &s.camera, &s.light, &fo, &fr) == PN_OK);
        CHECK(pn_opencl_render(cl, &s.camera, &s.light, &fo, &fr) == PN_OK);
        REQUIRE(pn_opencl_get_info(cl, &info) == PN_OK);
        CHECK_MSG(info.scene_uploads == info2.scene_uploads + 1u, "uploads %u -> %u", info2.scene_uploads,
                  info.scene_uploads);
        CHECK(info.buffer_bytes > 0u && info.kernels > 0u && info.build_ms > 0.0);
        fprintf(stderr, "kernel build %.1f ms, first launches %.1f ms, %u kernels, buffer %llu bytes\n", info.build_ms,
                info.warmup_ms, info.kernels, (unsigned long long)info.buffer_bytes);
    }
    pn_cl_close(cl);
    pn_cl_close(other);
    pn_setup_free(&s);
}

/* The device buffer mirrors the arena: an arena the device cannot hold in one buffer
 * fails pn_opencl_create with PN_E_DEVICE naming the OpenCL error and its code, and the
 * context stays usable. */
static void test_buffer_failure(void)
{
    cl_platform_id plat;
    cl_device_id dev;
    cl_ulong max_alloc = 0;
    pn_limits lim;
    size_t bytes;
    void *mem;
    pn_context *ctx;
    pn_opencl *cl = NULL;
    pn_status st;
    const char *msg;
    REQUIRE(clGetPlatformIDs(1, &plat, NULL) == CL_SUCCESS);
    REQUIRE(clGetDeviceIDs(plat, CL_DEVICE_TYPE_ALL, 1, &dev, NULL) == CL_SUCCESS);
    REQUIRE(clGetDeviceInfo(dev, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof(max_alloc), &max_alloc, NULL) == CL_SUCCESS);
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = 1024;
    lim.max_width = 64;
    lim.max_height = 64;
    /* Pairs cost 12 bytes each: a pool just past the device's largest buffer. */
    lim.gears_pairs = max_alloc / 12u + 1024u < (1u << 28) ? (uint32_t)(max_alloc / 12u + 1024u) : (1u << 28);
    REQUIRE(pn_arena_size(&lim, &bytes) == PN_OK);
    /* Address space only: pn_init writes the context, nothing else is touched, and
     * MAP_NORESERVE keeps the kernel from charging gigabytes this machine may not have. */
    mem = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    REQUIRE(mem != MAP_FAILED);
    REQUIRE(pn_init(&ctx, mem, bytes, &lim) == PN_OK);
    st = pn_cl_open(ctx, NULL, &cl);
    msg = pn_last_error(ctx);
    fprintf(stderr, "arena %zu bytes, device buffers up to %llu: %s %s\n", bytes, (unsigned long long)max_alloc,
            pn_status_str(st), msg);
    if ((cl_ulong)bytes > max_alloc) {
        CHECK(st == PN_E_DEVICE && cl == NULL);
        CHECK(strstr(msg, "clCreateBuffer") != NULL && strstr(msg, "CL_") != NULL && strstr(msg, "(-") != NULL);
    } else { /* a device with buffers above 3 GiB: the arena fits, so creation works */
        CHECK(st == PN_OK);
        pn_cl_close(cl);
    }
    /* The scalar port still works on the context the failed creation was given. */
    {
        static const float tri[9] = {-1, 0, -1, 1, 0, -1, 0, 0, 1};
        static const uint32_t idx[3] = {0, 1, 2};
        pn_camera cam = {{0, 2, 3}, {0, 0, 0}, {0, 1, 0}, 45.0f};
        pn_light light = {{0, 3, 0}, {0.5f, 0, 0}, {0, 0, 0.5f}};
        pn_frame_options fo;
        pn_frame fr;
        pn_frame_options_default(&fo);
        fo.width = fo.height = 16;
        CHECK(pn_scene_set(ctx, tri, 3, idx, 1) == PN_OK);
        CHECK(pn_render(ctx, &cam, &light, &fo, &fr) == PN_OK);
    }
    munmap(mem, bytes);
}

int main(void)
{
    pn_limits lim;
    int i;
    memset(&lim, 0, sizeof(lim));
    /* One context for every scene: the largest scene and image of the list. */
    g_nscenes = list_scenes(g_scenes);
    lim.max_triangles = 1;
    lim.max_width = 96;
    lim.max_height = 72;
    for (i = 0; i < g_nscenes; i++) {
        char err[256];
        g_loaded[i] = pn_setup_load_viewed(&g_setups[i], g_scenes[i].src, g_scenes[i].builtin, PN_SCENES_DIR, err,
                                           sizeof(err)) == 0;
        CHECK_MSG(g_loaded[i], "%s: %s", g_scenes[i].src, err);
        if (g_loaded[i] && g_setups[i].mesh.triangle_count > lim.max_triangles)
            lim.max_triangles = g_setups[i].mesh.triangle_count;
    }
    if (!xframe_init(&g_kept, (size_t)lim.max_width * lim.max_height) || rig_open(&g_rig, &lim, NULL) != 0) {
        CHECK_MSG(0, "cannot open the OpenCL port (see above)");
        return pn_test_summary();
    }
    lim.flags = PN_LIMITS_NO_SURFACE | PN_LIMITS_SPARSE_NBUFFER;
    if (rig_open(&g_lean, &lim, NULL) != 0) {
        CHECK_MSG(0, "cannot open the OpenCL port on a context without surfaces (see above)");
        return pn_test_summary();
    }
    RUN(test_api);
    RUN(test_buffer_failure);
    RUN(test_options);
    RUN(test_tiling);
    RUN(test_wedge_bands);
    RUN(test_scenes);
    RUN(test_update_positions);
    rig_close(&g_rig);
    rig_close(&g_lean);
    xframe_free(&g_kept);
    for (i = 0; i < g_nscenes; i++)
        if (g_loaded[i]) pn_setup_free(&g_setups[i]);
    return pn_test_summary();
}
