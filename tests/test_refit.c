/* test_refit.c - pn_scene_update_positions: the same triangles moved, the BVH refitted
 * (src/pn_bvh_build.c pn_bvh_refit) instead of built:
 *
 *   frames       on every built-in scene, animated over a few steps (a block of vertices
 *                turned and moved and two scaled about their centres; a triangle made
 *                degenerate; everything moved far with the camera and light; other
 *                blocks moved, the triangle whole again), every algorithm compiled in
 *                renders the same bytes (visibility, RGBA, depth, triangle ids, positions,
 *                normals) after the update in one context as after pn_scene_set of the
 *                moved scene in another; without receivers, with the scene's receivers
 *                marked (kept by the update), and on contexts that split BVH references
 *                (a tree with split references, thin's, is built anew; one that split
 *                nothing, colonnade's, is refitted)
 *   tree         a refit keeps the tree (pn_get_stats' node counts, the wide nodes' shape,
 *                the leaf and raster orders) unless the set of degenerate triangles
 *                changed, and its boxes are conservative and tight: every leaf's box is
 *                the smallest holding its triangles' vertices, every interior lane the
 *                union of its node's lanes; where the update builds anew, the tree is the one pn_scene_set builds
 *   errors       NULL context, no scene (PN_E_NO_SCENE), another triangle count
 *                (PN_E_INVALID_ARG), NULL arrays, a NaN vertex (PN_E_NONFINITE), a
 *                coordinate beyond 2^40 (PN_E_LIMIT), an index out of range
 *                (PN_E_INDEX_RANGE): each leaves the scene as it was (the next frames have
 *                the bytes of the frames before); the update times its copy and its refit
 *                in pass_ns */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_internal.h"
#include "pn_test.h"
#include "pn_test_scene.h"

#define FRAME_W 64u
#define FRAME_H 48u
#define NPIX ((size_t)FRAME_W * FRAME_H)

/* One frame's outputs, copied out of the arena. */
typedef struct frame_copy {
    float *vis, *depth, *pos, *nrm;
    uint8_t *rgba;
    uint32_t *tri;
} frame_copy;

static int frame_alloc(frame_copy *f)
{
    f->vis = (float *)malloc(NPIX * sizeof(float));
    f->depth = (float *)malloc(NPIX * sizeof(float));
    f->pos = (float *)malloc(NPIX * 3u * sizeof(float));
    f->nrm = (float *)malloc(NPIX * 3u * sizeof(float));
    f->rgba = (uint8_t *)malloc(NPIX * 4u);
    f->tri = (uint32_t *)malloc(NPIX * sizeof(uint32_t));
    return f->vis && f->depth && f->pos && f->nrm && f->rgba && f->tri;
}

static void frame_free(frame_copy *f)
{
    free(f->vis);
    free(f->depth);
    free(f->pos);
    free(f->nrm);
    free(f->rgba);
    free(f->tri);
}

static int render_copy(pn_context *ctx, uint32_t algo, const pn_camera *cam, const pn_light *light, float eps,
                       frame_copy *out)
{
    pn_frame_options opt;
    pn_frame fr;
    pn_test_frame_opts(&opt, FRAME_W, FRAME_H, algo, eps, 64u);
    if (pn_render(ctx, cam, light, &opt, &fr) != PN_OK) {
        fprintf(stderr, "render %s: %s\n", pn_algo_name((pn_algo)algo), pn_last_error(ctx));
        return 1;
    }
    memcpy(out->vis, fr.visibility, NPIX * sizeof(float));
    memcpy(out->depth, fr.depth, NPIX * sizeof(float));
    memcpy(out->pos, fr.position, NPIX * 3u * sizeof(float));
    memcpy(out->nrm, fr.normal, NPIX * 3u * sizeof(float));
    memcpy(out->rgba, fr.rgba, NPIX * 4u);
    memcpy(out->tri, fr.tri_id, NPIX * sizeof(uint32_t));
    return 0;
}

/* The first buffer in which two frames differ, or NULL. */
static const char *frame_diff(const frame_copy *a, const frame_copy *b)
{
    if (memcmp(a->vis, b->vis, NPIX * sizeof(float))) return "visibility";
    if (memcmp(a->rgba, b->rgba, NPIX * 4u)) return "rgba";
    if (memcmp(a->depth, b->depth, NPIX * sizeof(float))) return "depth";
    if (memcmp(a->tri, b->tri, NPIX * sizeof(uint32_t))) return "tri_id";
    if (memcmp(a->pos, b->pos, NPIX * 3u * sizeof(float))) return "position";
    if (memcmp(a->nrm, b->nrm, NPIX * 3u * sizeof(float))) return "normal";
    return NULL;
}

/* Renders every algorithm compiled in on ctx into fr[algo]; 0 on success. */
static int render_all(pn_context *ctx, const pn_camera *cam, const pn_light *light, float eps, frame_copy *fr)
{
    uint32_t a, built = pn_build_info();
    for (a = 0; a < PN_ALGO_COUNT; a++)
        if ((built & (1u << a)) && render_copy(ctx, a, cam, light, eps, fr + a) != 0) return 1;
    return 0;
}

/* Every algorithm compiled in renders the same bytes on ctx as in fr (or, when fr_b is not
 * NULL, ctx's frames into fr and ctx_b's into fr_b, compared). */
static void frames_same(const char *label, pn_context *ctx, pn_context *ctx_b, const pn_camera *cam,
                        const pn_light *light, float eps, frame_copy *fr, frame_copy *fr_b)
{
    uint32_t a, built = pn_build_info();
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        const char *d;
        if (!(built & (1u << a))) continue;
        if (ctx_b) {
            if (render_copy(ctx, a, cam, light, eps, fr + a) != 0 ||
                render_copy(ctx_b, a, cam, light, eps, fr_b + a) != 0) {
                CHECK_MSG(0, "%s %s: a frame failed", label, pn_algo_name((pn_algo)a));
                continue;
            }
            d = frame_diff(fr + a, fr_b + a);
        } else {
            frame_copy now;
            if (!frame_alloc(&now) || render_copy(ctx, a, cam, light, eps, &now) != 0) {
                CHECK_MSG(0, "%s %s: a frame failed", label, pn_algo_name((pn_algo)a));
                frame_free(&now);
                continue;
            }
            d = frame_diff(fr + a, &now);
            frame_free(&now);
        }
        CHECK_MSG(d == NULL, "%s %s: %s differs", label, pn_algo_name((pn_algo)a), d ? d : "");
    }
}

/* The wide tree's boxes against the triangles in the arena: every leaf's box (its lane) is
 * the smallest holding its triangles' vertices, every interior lane the union of its
 * node's lanes. Only for a tree of whole references (no split). */
static void check_boxes(const char *label, const pn_context *ctx)
{
    uint32_t n, i, a, c, d, bad_leaf = 0, bad_inner = 0;
    if (ctx->bvh_refs == 0u) return;
    for (n = 0; n < ctx->bvh_wide; n++) {
        const pn_kbvh4 *w = ctx->wnodes + n;
        for (c = 0; c < w->n && c < 4u; c++) {
            uint32_t ch = w->child[c];
            float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            if (ch & PN_W4_LEAF) {
                uint32_t first, count = pn_w4_leaf_refs(ctx->wnodes, PN_W4_LEAF | n << 2 | c, &first);
                for (i = first; i < first + count; i++) {
                    const float *p = ctx->tris + (size_t)(ctx->tri_index[i] & PN_REF_TRI) * 9u;
                    if (ctx->tri_index[i] & PN_REF_SPLIT) bad_leaf++;
                    for (d = 0; d < 9u; d++) {
                        lo[d % 3u] = fminf(lo[d % 3u], p[d]);
                        hi[d % 3u] = fmaxf(hi[d % 3u], p[d]);
                    }
                }
                for (a = 0; a < 3u; a++) bad_leaf += w->lo[a][c] != lo[a] || w->hi[a][c] != hi[a];
            } else {
                const pn_kbvh4 *cw = ctx->wnodes + ch;
                if (ch <= n || ch >= ctx->bvh_wide) {
                    bad_inner++;
                    continue;
                }
                for (d = 0; d < cw->n && d < 4u; d++)
                    for (a = 0; a < 3u; a++) {
                        lo[a] = fminf(lo[a], cw->lo[a][d]);
                        hi[a] = fmaxf(hi[a], cw->hi[a][d]);
                    }
                for (a = 0; a < 3u; a++) bad_inner += w->lo[a][c] != lo[a] || w->hi[a][c] != hi[a];
            }
        }
    }
    CHECK_MSG(bad_leaf == 0u && bad_inner == 0u,
              "%s: %u leaf bounds not their triangles' box, %u interior bounds not their node's lanes'", label,
              bad_leaf, bad_inner);
}

/* ---- The animation ------------------------------------------------------------------- */

/* Vertices [v0, v1) of p (from src) turned by ang radians about the y axis through their
 * centre, scaled by s about it and moved by d. */
static void move_block(float *p, const float *src, uint32_t v0, uint32_t v1, double ang, double s, const double d[3])
{
    double cen[3] = {0, 0, 0}, ca = cos(ang), sa = sin(ang);
    uint32_t v;
    int a;
    if (v1 <= v0) return;
    for (v = v0; v < v1; v++)
        for (a = 0; a < 3; a++) cen[a] += src[(size_t)v * 3u + (uint32_t)a];
    for (a = 0; a < 3; a++) cen[a] /= (double)(v1 - v0);
    for (v = v0; v < v1; v++) {
        const float *q = src + (size_t)v * 3u;
        double x = (q[0] - cen[0]) * s, y = (q[1] - cen[1]) * s, z = (q[2] - cen[2]) * s;
        p[(size_t)v * 3u + 0u] = (float)(cen[0] + ca * x + sa * z + d[0]);
        p[(size_t)v * 3u + 1u] = (float)(cen[1] + y + d[1]);
        p[(size_t)v * 3u + 2u] = (float)(cen[2] - sa * x + ca * z + d[2]);
    }
}

/* The steps, each on the scene as built: blocks moved (a refit); the same and a triangle
 * made degenerate (the set of degenerate triangles changes: built anew); the same moved far
 * (a refit after a build, at other roundings); other blocks moved, the degenerate triangle
 * whole again (built anew). */
enum { STEP_MOVE, STEP_DEGENERATE, STEP_FAR, STEP_OTHER, STEP_COUNT };
static const char *const step_names[STEP_COUNT] = {"move", "degenerate", "far", "other move"};

/* Step `step` of the animation of scene s (as built: p0) into p, the camera and light
 * (moved along with a far move). */
static void animate(const pn_test_scene *s, const float *p0, float *p, int step, pn_camera *cam, pn_light *light)
{
    const pn_mesh *m = &s->mesh;
    uint32_t V = m->vertex_count, v;
    double D = s->diag, none[3] = {0, 0, 0};
    double d[3] = {0.05 * D, 0.02 * D, -0.03 * D}, far[3] = {40.0 * D, 3.0 * D, -25.0 * D};
    int a, other = step == STEP_OTHER;
    const uint32_t *ix = m->indices + (size_t)(m->triangle_count / 3u) * 3u;
    memcpy(p, p0, (size_t)V * 3u * sizeof(float));
    *cam = s->camera;
    *light = s->light;
    /* a block turned and moved, two others scaled about their centres (and turned) */
    move_block(p, p0, V / 4u, V / 2u, other ? -1.1 : 0.35, 1.0, d);
    move_block(p, p0, V / 2u, V / 2u + V / 8u, 0.0, other ? 0.8 : 1.3, none);
    move_block(p, p0, V / 8u, V / 4u, other ? 0.2 : 0.0, other ? 1.5 : 0.6, none);
    if (step != STEP_DEGENERATE && step != STEP_FAR) return;
    /* one triangle's third corner onto its first: zero area */
    for (a = 0; a < 3; a++) p[(size_t)ix[2] * 3u + (uint32_t)a] = p[(size_t)ix[0] * 3u + (uint32_t)a];
    if (step != STEP_FAR) return;
    /* everything, the camera and light along, far off the origin (the degenerate triangle's
     * two corners stay equal) */
    for (v = 0; v < V * 3u; v++) p[v] = (float)(p[v] + far[v % 3u]);
    for (a = 0; a < 3; a++) {
        cam->eye[a] = (float)(cam->eye[a] + far[a]);
        cam->target[a] = (float)(cam->target[a] + far[a]);
        light->center[a] = (float)(light->center[a] + far[a]);
    }
}

/* The BVH's shape and orders, to tell a refit (kept) from a build. */
typedef struct tree_copy {
    uint32_t nodes, wide, refs, tris;
    uint32_t *shape; /* children and child words of every wide node */
    uint32_t *index, *raster;
    uint8_t *degenerate;
} tree_copy;

static void tree_save(const pn_context *ctx, tree_copy *t)
{
    uint32_t i;
    t->nodes = ctx->bvh_nodes;
    t->wide = ctx->bvh_wide;
    t->refs = ctx->bvh_refs;
    t->tris = ctx->bvh_tris;
    t->shape = (uint32_t *)malloc((size_t)t->wide * 5u * sizeof(uint32_t) + 4u);
    t->index = (uint32_t *)malloc((size_t)t->refs * sizeof(uint32_t) + 4u);
    t->raster = (uint32_t *)malloc((size_t)t->tris * sizeof(uint32_t) + 4u);
    t->degenerate = (uint8_t *)malloc((size_t)ctx->tri_count + 1u);
    for (i = 0; i < t->wide; i++) {
        t->shape[5u * i] = ctx->wnodes[i].n;
        memcpy(t->shape + 5u * i + 1u, ctx->wnodes[i].child, 4u * sizeof(uint32_t));
    }
    memcpy(t->index, ctx->tri_index, (size_t)t->refs * sizeof(uint32_t));
    memcpy(t->raster, ctx->raster_index, (size_t)t->tris * sizeof(uint32_t));
    for (i = 0; i < ctx->tri_count; i++) t->degenerate[i] = ctx->flags[i] & PN_TRI_DEGENERATE;
}

static void tree_free(tree_copy *t)
{
    free(t->shape);
    free(t->index);
    free(t->raster);
    free(t->degenerate);
}

static int tree_kept(const pn_context *ctx, const tree_copy *t)
{
    uint32_t i;
    if (ctx->bvh_nodes != t->nodes || ctx->bvh_wide != t->wide || ctx->bvh_refs != t->refs || ctx->bvh_tris != t->tris)
        return 0;
    for (i = 0; i < t->wide; i++)
        if (ctx->wnodes[i].n != t->shape[5u * i] || memcmp(ctx->wnodes[i].child, t->shape + 5u * i + 1u, 16u) != 0)
            return 0;
    return memcmp(ctx->tri_index, t->index, (size_t)t->refs * sizeof(uint32_t)) == 0 &&
           memcmp(ctx->raster_index, t->raster, (size_t)t->tris * sizeof(uint32_t)) == 0;
}

static int degenerates_same(const pn_context *ctx, const tree_copy *t)
{
    uint32_t i;
    for (i = 0; i < ctx->tri_count; i++)
        if ((ctx->flags[i] & PN_TRI_DEGENERATE) != t->degenerate[i]) return 0;
    return 1;
}

static uint32_t g_refits, g_rebuilds;

static pn_context *open_ctx(pn_test_host *h, uint32_t tris, int split)
{
    if (pn_test_open_refs(h, tris, FRAME_W, FRAME_H, split ? tris + (uint32_t)PN_BVH_SPLIT_EXTRA(tris) : 0u) != 0) {
        CHECK_MSG(0, "context for %u triangles", tris);
        return NULL;
    }
    return h->ctx;
}

/* Scene `name` animated through the steps in mask (bits 1 << STEP_*): context A updates,
 * context B sets the moved scene anew; receivers: the scene's range marked (A once, B after
 * every set); split: contexts that split BVH references. */
static void animate_scene(const char *name, uint32_t mask, int receivers, int split)
{
    pn_test_scene s;
    pn_test_host ha, hb;
    pn_context *A, *B;
    frame_copy fa[PN_ALGO_COUNT], fb[PN_ALGO_COUNT];
    float *p = NULL;
    uint32_t a, alloc_ok = 1;
    int step;
    char label[160];
    REQUIRE(pn_test_scene_load(&s, name) == 0);
    for (a = 0; a < PN_ALGO_COUNT; a++) alloc_ok &= (uint32_t)frame_alloc(fa + a) & (uint32_t)frame_alloc(fb + a);
    p = (float *)malloc((size_t)s.mesh.vertex_count * 3u * sizeof(float));
    A = open_ctx(&ha, s.mesh.triangle_count, split);
    B = open_ctx(&hb, s.mesh.triangle_count, split);
    if (alloc_ok && p && A && B) {
        const pn_mesh *m = &s.mesh;
        CHECK_MSG(pn_scene_set(A, m->positions, m->vertex_count, m->indices, m->triangle_count) == PN_OK, "%s: %s",
                  name, pn_last_error(A));
        if (receivers) CHECK(pn_scene_set_receivers(A, m->receiver_first, m->receiver_count) == PN_OK);
        for (step = 0; step < STEP_COUNT; step++) {
            pn_camera cam;
            pn_light light;
            pn_stats sa, sb, s0;
            tree_copy before;
            pn_status st;
            if (!(mask & (1u << step))) continue;
            snprintf(label, sizeof(label), "%s%s%s, %s", name, receivers ? " (receivers)" : "",
                     split ? " (split references)" : "", step_names[step]);
            animate(&s, m->positions, p, step, &cam, &light);
            tree_save(A, &before);
            CHECK(pn_get_stats(A, &s0) == PN_OK);
            st = pn_scene_update_positions(A, p, m->vertex_count, m->indices, m->triangle_count);
            CHECK_MSG(st == PN_OK, "%s: update: %s", label, pn_last_error(A));
            st = pn_scene_set(B, p, m->vertex_count, m->indices, m->triangle_count);
            CHECK_MSG(st == PN_OK, "%s: set: %s", label, pn_last_error(B));
            if (receivers) CHECK(pn_scene_set_receivers(B, m->receiver_first, m->receiver_count) == PN_OK);
            CHECK(pn_get_stats(A, &sa) == PN_OK && pn_get_stats(B, &sb) == PN_OK);
            CHECK_MSG(memcmp(A->flags, B->flags, m->triangle_count) == 0, "%s: the triangle flags differ", label);
            /* refitted unless the tree held split references or the degenerate set changed */
            if (s0.bvh_refs == s0.triangles - s0.degenerate_triangles && degenerates_same(A, &before)) {
                /* a refit: the tree kept, its boxes tight */
                g_refits++;
                CHECK_MSG(sa.bvh_nodes == s0.bvh_nodes && sa.bvh_depth == s0.bvh_depth &&
                              sa.bvh_max_leaf == s0.bvh_max_leaf && sa.bvh_refs == s0.bvh_refs,
                          "%s: refit: %u nodes (%u before), depth %u (%u), largest leaf %u (%u)", label,
                          sa.bvh_nodes, s0.bvh_nodes, sa.bvh_depth, s0.bvh_depth, sa.bvh_max_leaf, s0.bvh_max_leaf);
                CHECK_MSG(tree_kept(A, &before), "%s: the refit changed the tree's shape or order", label);
                check_boxes(label, A);
            } else {
                /* built anew: the tree pn_scene_set builds */
                g_rebuilds++;
                CHECK_MSG(sa.bvh_nodes == sb.bvh_nodes && sa.bvh_refs == sb.bvh_refs && A->bvh_wide == B->bvh_wide &&
                              memcmp(A->wnodes, B->wnodes, (size_t)A->bvh_wide * sizeof(pn_kbvh4)) == 0 &&
                              memcmp(A->tri_index, B->tri_index, (size_t)sa.bvh_refs * sizeof(uint32_t)) == 0,
                          "%s: rebuilt tree (%u nodes) is not pn_scene_set's (%u)", label, sa.bvh_nodes,
                          sb.bvh_nodes);
            }
            if (step == STEP_DEGENERATE)
                CHECK_MSG(!degenerates_same(A, &before), "%s: no triangle became degenerate", label);
            tree_free(&before);
            frames_same(label, A, B, &cam, &light, s.eps, fa, fb);
        }
    }
    if (A) pn_test_close(&ha);
    if (B) pn_test_close(&hb);
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        frame_free(fa + a);
        frame_free(fb + a);
    }
    free(p);
    pn_test_scene_free(&s);
}

/* Every step without receivers; with them (only the occluders' box and MCSM's layers read
 * them), a refit and a build. */
static void test_scenes(void)
{
    const char *const *names = pn_builtin_scene_names();
    uint32_t all = (1u << STEP_COUNT) - 1u, some = 1u << STEP_MOVE | 1u << STEP_DEGENERATE;
    int i;
    for (i = 0; names[i]; i++) {
        animate_scene(names[i], all, 0, 0);
        animate_scene(names[i], some, 1, 0);
    }
    CHECK_MSG(g_refits > 0u && g_rebuilds > 0u, "%u refits, %u rebuilds: both paths should run", g_refits,
              g_rebuilds);
}

/* A context that splits references: a tree with split references (thin's slivers) is
 * built anew at every update; one whose scene split nothing (colonnade) is refitted. */
static void test_split(void)
{
    uint32_t refits = g_refits;
    animate_scene("thin", 1u << STEP_MOVE | 1u << STEP_DEGENERATE, 1, 1);
    CHECK_MSG(g_refits == refits, "thin's split tree was refitted");
    animate_scene("colonnade", 1u << STEP_MOVE, 0, 1);
    CHECK_MSG(g_refits > refits, "colonnade, which splits nothing, was not refitted in a splitting context");
}

/* ---- Errors --------------------------------------------------------------------------- */

static uint64_t g_ticks;
static uint64_t tick(void *user)
{
    (void)user;
    return ++g_ticks;
}

static void test_errors(void)
{
    pn_test_scene s;
    pn_test_host h;
    pn_context *ctx;
    frame_copy fr[PN_ALGO_COUNT];
    float *p;
    uint32_t *ix, a, alloc_ok = 1;
    pn_stats st;
    REQUIRE(pn_test_scene_load(&s, "colonnade") == 0);
    for (a = 0; a < PN_ALGO_COUNT; a++) alloc_ok &= (uint32_t)frame_alloc(fr + a);
    p = (float *)malloc((size_t)s.mesh.vertex_count * 3u * sizeof(float));
    ix = (uint32_t *)malloc((size_t)s.mesh.triangle_count * 3u * sizeof(uint32_t));
    ctx = open_ctx(&h, s.mesh.triangle_count, 0);
    if (alloc_ok && p && ix && ctx) {
        const pn_mesh *m = &s.mesh;
        pn_camera cam;
        pn_light light;
        CHECK(pn_scene_update_positions(NULL, m->positions, m->vertex_count, m->indices, m->triangle_count) ==
              PN_E_INVALID_ARG);
        CHECK(pn_scene_update_positions(ctx, m->positions, m->vertex_count, m->indices, m->triangle_count) ==
              PN_E_NO_SCENE);
        CHECK(pn_test_scene_upload(ctx, &s) == PN_OK);
        /* a moved scene: what each failure below must keep */
        animate(&s, m->positions, p, STEP_MOVE, &cam, &light);
        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, m->indices, m->triangle_count) == PN_OK);
        REQUIRE(render_all(ctx, &cam, &light, s.eps, fr) == 0);
        memcpy(ix, m->indices, (size_t)m->triangle_count * 3u * sizeof(uint32_t));
        animate(&s, m->positions, p, STEP_OTHER, &cam, &light);

        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, ix, m->triangle_count - 1u) == PN_E_INVALID_ARG);
        CHECK_MSG(strstr(pn_last_error(ctx), "pn_scene_update_positions") != NULL, "%s", pn_last_error(ctx));
        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, ix, m->triangle_count + 1u) == PN_E_INVALID_ARG);
        CHECK(pn_scene_update_positions(ctx, NULL, m->vertex_count, ix, m->triangle_count) == PN_E_INVALID_ARG);
        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, NULL, m->triangle_count) == PN_E_INVALID_ARG);
        p[(size_t)(m->vertex_count - 1u) * 3u + 1u] = NAN;
        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, ix, m->triangle_count) == PN_E_NONFINITE);
        p[(size_t)(m->vertex_count - 1u) * 3u + 1u] = 2199023255552.0f; /* 2^41 */
        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, ix, m->triangle_count) == PN_E_LIMIT);
        p[(size_t)(m->vertex_count - 1u) * 3u + 1u] = m->positions[(size_t)(m->vertex_count - 1u) * 3u + 1u];
        ix[(size_t)m->triangle_count * 3u - 1u] = m->vertex_count;
        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, ix, m->triangle_count) == PN_E_INDEX_RANGE);
        animate(&s, m->positions, p, STEP_MOVE, &cam, &light);
        frames_same("colonnade after failed updates", ctx, NULL, &cam, &light, s.eps, fr, NULL);

        /* a successful update times its copy and its refit */
        REQUIRE(pn_set_clock(ctx, tick, NULL) == PN_OK);
        animate(&s, m->positions, p, STEP_OTHER, &cam, &light);
        CHECK(pn_scene_update_positions(ctx, p, m->vertex_count, m->indices, m->triangle_count) == PN_OK);
        CHECK(pn_get_stats(ctx, &st) == PN_OK);
        CHECK_MSG(st.pass_ns[PN_PASS_SCENE_COPY] >= 1u && st.pass_ns[PN_PASS_BVH_BUILD] >= 1u,
                  "update times: copy %llu, BVH %llu ticks", (unsigned long long)st.pass_ns[PN_PASS_SCENE_COPY],
                  (unsigned long long)st.pass_ns[PN_PASS_BVH_BUILD]);
    }
    if (ctx) pn_test_close(&h);
    for (a = 0; a < PN_ALGO_COUNT; a++) frame_free(fr + a);
    free(p);
    free(ix);
    pn_test_scene_free(&s);
}

int main(void)
{
    RUN(test_errors);
    RUN(test_scenes);
    RUN(test_split);
    return pn_test_summary();
}
