/* PN_ALGO_REFERENCE: the closed form of the square scene, culling against brute force,
 * watertightness of the shared predicate, point and one-sided lights, determinism.
 *
 * Built twice (tests/CMakeLists.txt): test_reference links the library and the built-in
 * scenes (pn_scenes) alone and renders
 * the scenes of tests/pn_test_scene.h, its determinism check running the work items in
 * other orders on one thread; test_reference_models (PN_TEST_MODELS=1) links the tools and
 * runs the culling and watertightness checks on spot.glb and the determinism check on the
 * tools' thread pool (1, 2 and 7 threads). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_footprint.h"
#include "pn_predicate.h" /* the kernel predicate itself, for brute force and mask checks */
#include "pn_test.h"
#include "pn_test_geom.h"
#include "pn_test_scene.h"

#ifndef PN_TEST_MODELS
#define PN_TEST_MODELS 0
#endif
#if PN_TEST_MODELS
#include "pn_test_tools.h"
#endif

/* A frame of `algo` (exact_stats as given) at the scene's eps. */
static int render_algo(pn_context *ctx, const pn_test_scene *s, const pn_camera *cam, const pn_light *light, uint32_t w,
                       uint32_t hh, uint32_t k, pn_algo algo, uint32_t exact_stats, pn_frame *fr)
{
    pn_frame_options opt;
    pn_frame_options_default(&opt);
    opt.width = w;
    opt.height = hh;
    opt.k = k;
    opt.eps = s->eps;
    opt.algo = algo;
    opt.exact_stats = exact_stats;
    if (pn_render(ctx, cam, light, &opt, fr) != PN_OK) {
        fprintf(stderr, "render: %s\n", pn_last_error(ctx));
        return 1;
    }
    return 0;
}

static int render(pn_context *ctx, const pn_test_scene *s, const pn_camera *cam, const pn_light *light, uint32_t w,
                  uint32_t hh, uint32_t k, pn_frame *fr)
{
    return render_algo(ctx, s, cam, light, w, hh, k, PN_ALGO_REFERENCE, 0u, fr);
}

/* ---- square: closed form --------------------------------------------------------------- */

#if !PN_TEST_MODELS
static void test_square_closed_form(void)
{
    pn_test_scene s;
    pn_test_host h;
    pn_test_square_params sp;
    static const uint32_t ks[4] = {4, 8, 16, 32};
    int q;
    REQUIRE(pn_test_scene_load(&s, "square") == 0);
    REQUIRE(pn_test_open(&h, s.mesh.triangle_count, 160, 160) == 0);
    REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    pn_test_square_scene_params(&sp);
    for (q = 0; q < 4; q++) {
        pn_frame fr;
        uint32_t k = ks[q], px, compared = 0, skipped = 0, mismatched = 0, penumbra = 0;
        double worst_area = 0.0;
        REQUIRE(render(h.ctx, &s, &s.camera, &s.light, 160, 160, k, &fr) == 0);
        for (px = 0; px < 160u * 160u; px++) {
            pn_test_square_params at = sp;
            float ox, oy, oz;
            double closed, area, dist, got;
            /* Triangles 0, 1: occluder; 2, 3: receiver (the ground is last). */
            if (fr.tri_id[px] != 2u && fr.tri_id[px] != 3u) continue;
            /* The library's shadow-ray origin: P + eps * (0, 1, 0), in float. */
            ox = fr.position[px * 3];
            oy = fr.position[px * 3 + 1] + s.eps;
            oz = fr.position[px * 3 + 2];
            at.ground_y = oy;
            dist = pn_test_square_min_edge_distance(&at, ox, oz, (int)k);
            if (dist < 1e-4) {
                skipped++;
                continue;
            }
            compared++;
            closed = pn_test_square_closed_form(&at, ox, oz, (int)k);
            area = pn_test_square_closed_form(&at, ox, oz, 0);
            got = fr.visibility[px];
            if (got > 0.0 && got < 1.0) penumbra++;
            if (lround(got * k * k) != lround(closed * k * k) || got * k * k != (double)lround(got * k * k)) {
                if (mismatched < 5)
                    fprintf(stderr, "k=%u pixel %u: visibility %.9g, closed form %.9g\n", k, px, got, closed);
                mismatched++;
            }
            if (fabs(got - area) > worst_area) worst_area = fabs(got - area);
        }
        fprintf(stderr,
                "square k=%u: %u receiver pixels compared (%u in penumbra), %u skipped near a projected edge, "
                "%u mismatches; max |vis - area fraction| = %.5f (1/k = %.5f)\n",
                k, compared, penumbra, skipped, mismatched, worst_area, 1.0 / k);
        CHECK(compared > 5000u);
        CHECK(penumbra > 500u);
        CHECK(mismatched == 0u);
        CHECK(worst_area <= 1.0 / k);
    }
    pn_test_close(&h);
    pn_test_scene_free(&s);
}
#endif

/* ---- culling is conservative: BVH reference == all-triangles brute force ---------------- */

static pn_klight klight_of(const pn_light *l, uint32_t k, float eps, float diag)
{
    pn_klight kl;
    float lu = sqrtf(l->u[0] * l->u[0] + l->u[1] * l->u[1] + l->u[2] * l->u[2]);
    memset(&kl, 0, sizeof(kl));
    memcpy(kl.c, l->center, sizeof(kl.c));
    memcpy(kl.U, l->u, sizeof(kl.U));
    memcpy(kl.V, l->v, sizeof(kl.V));
    kl.eps = eps;
    kl.cull_tol = 1e-5f * diag; /* as src/pn_frame.c sets it */
    if (lu == 0.0f) {
        kl.k = 1;
        kl.is_point = 1;
    } else {
        pn_v3 n = pn_v3_normalize(pn_v3_cross(pn_v3_make(l->u[0], l->u[1], l->u[2]), pn_v3_make(l->v[0], l->v[1], l->v[2])));
        kl.N[0] = n.x;
        kl.N[1] = n.y;
        kl.N[2] = n.z;
        kl.k = k;
    }
    return kl;
}

static pn_v3 tri_v(const pn_test_mesh *m, uint32_t t, int c)
{
    const float *p = m->positions + 3u * m->indices[3u * t + (uint32_t)c];
    return pn_v3_make(p[0], p[1], p[2]);
}

/* Brute-force visibility of pixel px with every triangle tried, each on a mask of its own
 * ORed into the pixel's; *blocking: how many of them block a sample (paper Table 6's
 * necessary assignments of the pixel; 0 without an origin). */
static float brute_pixel(const pn_test_mesh *m, const pn_frame *fr, size_t px, const pn_klight *kl, uint32_t *blocking)
{
    uint32_t mask[PN_MASK_WORDS_MAX], one[PN_MASK_WORDS_MAX], t;
    pn_v3 P = pn_v3_make(fr->position[px * 3], fr->position[px * 3 + 1], fr->position[px * 3 + 2]);
    pn_v3 n = pn_v3_make(fr->normal[px * 3], fr->normal[px * 3 + 1], fr->normal[px * 3 + 2]);
    pn_v3 O;
    pn_horizon H;
    *blocking = 0u;
    if (fr->tri_id[px] == PN_NO_TRIANGLE) return 1.0f;
    if (!pn_shadow_origin(P, n, kl, &O)) return 0.0f;
    pn_mask_clear(mask);
    pn_horizon_make(P, n, tri_v(m, fr->tri_id[px], 0), tri_v(m, fr->tri_id[px], 1), tri_v(m, fr->tri_id[px], 2), kl, &H);
    pn_horizon_mask(&H, kl, mask);
    for (t = 0; t < m->triangle_count; t++) {
        pn_v3 A = tri_v(m, t, 0), B = tri_v(m, t, 1), C = tri_v(m, t, 2);
        pn_v3 cr = pn_v3_cross(pn_v3_sub(B, A), pn_v3_sub(C, A));
        if (t == fr->tri_id[px] || (cr.x == 0.0f && cr.y == 0.0f && cr.z == 0.0f)) continue;
        pn_mask_clear(one);
        pn_tri_mask(O, A, B, C, kl, one);
        *blocking += pn_mask_count(one, kl->k) != 0u;
        pn_mask_or(mask, one, kl->k);
    }
    return pn_mask_visibility(mask, kl->k);
}

static void brute_compare(const char *name, const pn_test_scene *s, const pn_light *light, uint32_t w, uint32_t hh,
                          uint32_t k)
{
    pn_test_host h;
    pn_frame fr;
    pn_klight kl = klight_of(light, k, s->eps, 0.0f);
    size_t px;
    uint32_t diff = 0, partial = 0, lit = 0;
    uint64_t necessary = 0;
    REQUIRE(pn_test_open(&h, s->mesh.triangle_count, w, hh) == 0);
    REQUIRE(pn_scene_set(h.ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) == PN_OK);
    REQUIRE(render(h.ctx, s, &s->camera, light, w, hh, k, &fr) == 0);
    {
        /* The brute force has no culling; the frame's slack is the culls' own rounding. */
        pn_stats st;
        REQUIRE(pn_get_stats(h.ctx, &st) == PN_OK);
        CHECK(st.cull_tol > 0.0f);
    }
    for (px = 0; px < (size_t)w * hh; px++) {
        uint32_t nb;
        float b = brute_pixel(&s->mesh, &fr, px, &kl, &nb);
        necessary += nb;
        if (memcmp(&b, &fr.visibility[px], sizeof(float)) != 0) {
            if (diff < 5) fprintf(stderr, "%s: pixel %zu: reference %.9g, brute force %.9g\n", name, px, fr.visibility[px], b);
            diff++;
        }
        partial += b > 0.0f && b < 1.0f;
        lit += b > 0.0f;
    }
    fprintf(stderr, "%s k=%u: %ux%u, %u partially lit, %u lit, %u differ from brute force\n", name, kl.k, w, hh,
            partial, lit, diff);
    CHECK(diff == 0u);
    CHECK(lit > 0u);
    if (!kl.is_point) CHECK(partial > 0u);
#if PN_ENABLE_GEARS
    {
        /* GEARS with exact statistics counts, per pixel, the triangles of its cell that
         * block a sample: with a conservative grid that is every triangle that does, in
         * any order of the cell's list. */
        pn_frame gf;
        pn_stats st;
        REQUIRE(render_algo(h.ctx, s, &s->camera, light, w, hh, k, PN_ALGO_GEARS, 1u, &gf) == 0);
        REQUIRE(pn_get_stats(h.ctx, &st) == PN_OK);
        fprintf(stderr, "%s k=%u: GEARS necessary assignments %llu, brute force %llu\n", name, kl.k,
                (unsigned long long)st.shadow_blocking, (unsigned long long)necessary);
        CHECK(st.shadow_blocking == necessary);
        CHECK(necessary > 0u);
        /* With exact statistics no superchunk is skipped but by the frustum test, which
         * runs on all of them: a pixel whose cell holds n entries tests at least
         * ceil(n / 64) superchunk boxes (shadow_nodes counts them with the chunks'). */
        CHECK_MSG(st.shadow_nodes * 64u >= st.gears.assignments, "%s: %llu boxes for %llu assignments", name,
                  (unsigned long long)st.shadow_nodes, (unsigned long long)st.gears.assignments);
    }
#endif
    pn_test_close(&h);
}

#if PN_TEST_MODELS
static void test_culling_vs_brute_force_spot(void)
{
    pn_test_scene s;
    REQUIRE(pn_test_scene_load_tools(&s, PN_SCENES_DIR "/spot.glb", 0, 1) == 0);
    brute_compare("spot.glb", &s, &s.light, 40, 32, 8);
    {
        pn_light pt = s.light; /* point light: hard shadows */
        memset(pt.u, 0, sizeof(pt.u));
        memset(pt.v, 0, sizeof(pt.v));
        brute_compare("spot.glb point", &s, &pt, 40, 32, 8);
        pt = s.light; /* a large, low light: wide penumbrae, long frusta */
        pt.u[0] *= 6.0f;
        pt.v[2] *= 3.0f;
        pt.center[1] -= 0.4f * s.diag;
        brute_compare("spot.glb big light", &s, &pt, 40, 32, 16);
    }
    pn_test_scene_free(&s);
}
#else
static void test_culling_vs_brute_force(void)
{
    static const char *builtins[3] = {"thin", "elongated-cube", "square"};
    pn_test_scene s;
    int i;
    for (i = 0; i < 3; i++) {
        REQUIRE(pn_test_scene_load(&s, builtins[i]) == 0);
        brute_compare(builtins[i], &s, &s.light, 48, 48, i == 0 ? 4u : 32u);
        pn_test_scene_free(&s);
    }
}
#endif

/* ---- watertightness -------------------------------------------------------------------- */

/* Does the segment P -> S cross some triangle of m (double precision)? */
static int seg_hits(const pn_test_mesh *m, const double P[3], const double S[3])
{
    double d[3] = {S[0] - P[0], S[1] - P[1], S[2] - P[2]};
    uint32_t t;
    for (t = 0; t < m->triangle_count; t++) {
        const uint32_t *x = m->indices + 3u * t;
        double mg, tt = pn_test_ray_tri(P, d, m->positions + 3u * x[0], m->positions + 3u * x[1], m->positions + 3u * x[2], &mg);
        if (tt > 0.0 && tt < 1.0) return 1;
    }
    return 0;
}

/* For shadow-ray origins O under the mesh, every sample whose segment robustly crosses the
 * mesh (the segments to four neighbours of the sample, 1e-4 light half-edges away, all
 * hit: the sample is not on the silhouette) must be blocked by the predicate. Samples
 * whose segments run exactly through shared edges and vertices are the point. */
static uint32_t leaks(const pn_test_mesh *m, const pn_klight *kl, const pn_v3 *origins, int n_origins, uint32_t *covered_out)
{
    uint32_t leaked = 0, covered = 0, k = kl->k;
    int o;
    for (o = 0; o < n_origins; o++) {
        uint32_t mask[PN_MASK_WORDS_MAX], t, i, j;
        pn_v3 O = origins[o];
        double P[3] = {O.x, O.y, O.z};
        pn_mask_clear(mask);
        for (t = 0; t < m->triangle_count; t++) pn_tri_mask(O, tri_v(m, t, 0), tri_v(m, t, 1), tri_v(m, t, 2), kl, mask);
        for (j = 0; j < k; j++)
            for (i = 0; i < k; i++) {
                double a = (double)(2 * i + 1) / k - 1.0, b = (double)(2 * j + 1) / k - 1.0;
                static const double off[4][2] = {{1e-4, 0}, {-1e-4, 0}, {0, 1e-4}, {0, -1e-4}};
                int q, robust = 1;
                for (q = 0; q < 4 && robust; q++) {
                    double S[3];
                    int c;
                    for (c = 0; c < 3; c++)
                        S[c] = kl->c[c] + (a + off[q][0]) * kl->U[c] + (b + off[q][1]) * kl->V[c];
                    robust = seg_hits(m, P, S);
                }
                if (!robust) continue;
                covered++;
                if (!(mask[(j * k + i) >> 5] >> ((j * k + i) & 31u) & 1u)) leaked++;
            }
    }
    *covered_out = covered;
    return leaked;
}

#if !PN_TEST_MODELS
static void test_watertight(void)
{
    pn_test_mesh sphere;
    pn_v3 origins[64];
    pn_light l;
    pn_klight kl;
    uint32_t covered, leaked;
    int n = 0, i, j;
    /* Sphere on the y axis; 32 slices put meridians in the planes x = 0 and z = 0. */
    REQUIRE(pn_test_uv_sphere(&sphere, 0, 2, 0, 0.75, 32, 16) == 0);
    for (i = 0; i < (int)sphere.vertex_count * 3; i++)
        if (fabsf(sphere.positions[i]) < 1e-6f) sphere.positions[i] = 0.0f;
    /* k = 8, half-edge 0.5: samples at x = c.x + (2i+1)/16 - 0.5; c.x = 1/16 puts column 3
     * exactly on x = 0, and likewise row 3 on z = 0, and sample (3, 3) on the pole axis. */
    l.center[0] = 0.0625f;
    l.center[1] = 4.0f;
    l.center[2] = 0.0625f;
    l.u[0] = 0.5f; l.u[1] = 0.0f; l.u[2] = 0.0f;
    l.v[0] = 0.0f; l.v[1] = 0.0f; l.v[2] = -0.5f;
    kl = klight_of(&l, 8, 0.0f, 4.0f);
    CHECK(kl.N[1] == 1.0f || kl.N[1] == -1.0f);
    for (i = -3; i <= 3; i++)
        for (j = -3; j <= 3; j++) origins[n++] = pn_v3_make(0.125f * (float)i, 0.0f, 0.125f * (float)j);
    leaked = leaks(&sphere, &kl, origins, n, &covered);
    fprintf(stderr, "uv-sphere: %u robustly covered samples, %u leaked\n", covered, leaked);
    CHECK(covered > 1000u);
    CHECK(leaked == 0u);
    kl = klight_of(&l, 32, 0.0f, 4.0f);
    leaked = leaks(&sphere, &kl, origins, 9, &covered);
    fprintf(stderr, "uv-sphere k=32: %u robustly covered samples, %u leaked\n", covered, leaked);
    CHECK(covered > 1000u);
    CHECK(leaked == 0u);
    pn_test_mesh_free(&sphere);
}
#else
/* spot.glb: origins on its ground plane inside its shadow. */
static void test_watertight_spot(void)
{
    pn_test_scene s;
    pn_v3 origins[64];
    pn_klight kl;
    uint32_t covered, leaked;
    int n = 0, i, j;
    REQUIRE(pn_test_scene_load_tools(&s, PN_SCENES_DIR "/spot.glb", 0, 0) == 0);
    {
        float cx = 0.5f * (s.mesh.bbox_min[0] + s.mesh.bbox_max[0]), cz = 0.5f * (s.mesh.bbox_min[2] + s.mesh.bbox_max[2]);
        float y = s.mesh.bbox_min[1] - 0.01f * s.diag;
        pn_light sl;
        n = 0;
        for (i = -3; i <= 3; i++)
            for (j = -3; j <= 3; j++) origins[n++] = pn_v3_make(cx + 0.06f * (float)i * s.diag, y, cz + 0.06f * (float)j * s.diag);
        sl.center[0] = cx;
        sl.center[1] = s.mesh.bbox_max[1] + 0.5f * s.diag;
        sl.center[2] = cz;
        sl.u[0] = 0.15f * s.diag; sl.u[1] = 0.0f; sl.u[2] = 0.0f;
        sl.v[0] = 0.0f; sl.v[1] = 0.0f; sl.v[2] = 0.15f * s.diag;
        kl = klight_of(&sl, 16, 0.0f, s.diag);
        leaked = leaks(&s.mesh, &kl, origins, n, &covered);
        fprintf(stderr, "spot.glb: %u robustly covered samples, %u leaked\n", covered, leaked);
        CHECK(covered > 1000u);
        CHECK(leaked == 0u);
    }
    pn_test_scene_free(&s);
}
#endif

/* ---- the predicate against double precision ----------------------------------------------
 * Random triangles of every scale, many tiny and far from O, many nearly edge-on (O close
 * to their plane): the configurations where float cancellation bites. A sample the
 * predicate blocks must have a segment that, moved by at most 1e-4 light half-edges, hits
 * the triangle in double precision (no false blocks), and, the predicate being exact, a
 * segment that misses the triangle in double precision by no more than double rounding;
 * a sample whose four moved segments all hit must be blocked (there is no certainty test
 * any more). tests/test_exact.c compares every bit with an exact arbiter. */
#if !PN_TEST_MODELS
static uint32_t rng_state = 12345u;
static double rnd(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (double)(rng_state >> 8) / 16777216.0;
}

static int dbl_hit(const double P[3], const double S[3], const float *A, const float *B, const float *C)
{
    double d[3] = {S[0] - P[0], S[1] - P[1], S[2] - P[2]}, mg, t = pn_test_ray_tri(P, d, A, B, C, &mg);
    return t > 0.0 && t < 1.0;
}

static void test_predicate_vs_double(void)
{
    pn_light l = {{0.0f, 1.0f, 0.0f}, {0.25f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.25f}};
    pn_klight kl = klight_of(&l, 16, 0.0f, 1.0f);
    uint32_t trial, false_blocks = 0, misses = 0, blocked_total = 0, far_blocks = 0, foot_out = 0, foot_area = 0;
    double worst = 0.0;
    static const double off[4][2] = {{1e-4, 0}, {-1e-4, 0}, {0, 1e-4}, {0, -1e-4}};
    kl.N[0] = 0.0f;
    kl.N[1] = -1.0f; /* emits down: u x v = -y */
    kl.N[2] = 0.0f;
    for (trial = 0; trial < 20000u; trial++) {
        float tri[9];
        uint32_t m[PN_MASK_WORDS_MAX], i, j;
        pn_v3 O = pn_v3_make((float)(rnd() - 0.5) * 0.2f, (float)(rnd() * 0.05), (float)(rnd() - 0.5) * 0.2f);
        double P[3] = {O.x, O.y, O.z}, size = pow(10.0, -6.0 + 5.0 * rnd()), ctr[3], e1[3], e2[3];
        double h = 0.1 + 0.8 * rnd(); /* height of the triangle between O and the light */
        int q;
        /* A point on a random segment O -> light sample, then a triangle around it whose
         * plane nearly contains O in half of the trials. */
        {
            double a = rnd() * 2.0 - 1.0, b = rnd() * 2.0 - 1.0, S[3] = {0.25 * a, 1.0, 0.25 * b};
            for (q = 0; q < 3; q++) ctr[q] = P[q] + h * (S[q] - P[q]);
        }
        for (q = 0; q < 3; q++) e1[q] = rnd() - 0.5;
        if (trial & 1u) {
            for (q = 0; q < 3; q++) e2[q] = (ctr[q] - P[q]) + (rnd() - 0.5) * 1e-4; /* edge-on */
        } else {
            for (q = 0; q < 3; q++) e2[q] = rnd() - 0.5;
        }
        {
            double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
            double l2 = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
            for (q = 0; q < 3; q++) {
                tri[q] = (float)(ctr[q] - size * e1[q] / l1);
                tri[3 + q] = (float)(ctr[q] + size * e1[q] / l1);
                tri[6 + q] = (float)(ctr[q] + size * (trial % 3u == 0 ? 30.0 : 1.0) * e2[q] / l2);
            }
        }
        pn_mask_clear(m);
        pn_tri_mask(O, pn_v3_make(tri[0], tri[1], tri[2]), pn_v3_make(tri[3], tri[4], tri[5]),
                    pn_v3_make(tri[6], tri[7], tri[8]), &kl, m);
        {
            /* The footprints the walks skip by (pn_footprint.h) hold every blocked sample:
             * the triangle's box's, alone (pn_foot_box) and as one of four lanes
             * (pn_foot_box4, as a leaf's triangles take it). */
            pn_foot fp;
            pn_rect rb, r4[4];
            float l4[12], h4[12];
            pn_v3 A = pn_v3_make(tri[0], tri[1], tri[2]), B = pn_v3_make(tri[3], tri[4], tri[5]),
                  C = pn_v3_make(tri[6], tri[7], tri[8]);
            uint32_t lane = trial & 3u;
            pn_foot_make(O, &kl, &fp);
            pn_lanes_put_tri(l4, h4, 0u, A, B, O); /* the lanes before: another box */
            pn_lanes_put_tri(l4, h4, lane, A, B, C);
            pn_foot_box4(&fp, l4, h4, r4);
            rb = pn_foot_box(&fp, pn_v3_make(l4[lane], l4[4u + lane], l4[8u + lane]),
                             pn_v3_make(h4[lane], h4[4u + lane], h4[8u + lane]));
            if (memcmp(&rb, &r4[lane], sizeof(rb)) != 0) foot_out++; /* one box or four: the same rectangle */
            if (!pn_rect_empty(rb)) foot_area += (uint32_t)((rb.i1 - rb.i0 + 1) * (rb.j1 - rb.j0 + 1));
            for (j = 0; j < 16; j++)
                for (i = 0; i < 16; i++)
                    if ((m[(j * 16 + i) >> 5] >> ((j * 16 + i) & 31u)) & 1u) {
                        int in_b = (int)i >= rb.i0 && (int)i <= rb.i1 && (int)j >= rb.j0 && (int)j <= rb.j1;
                        if (!in_b) {
                            if (foot_out < 3)
                                fprintf(stderr, "trial %u: blocked sample %u,%u outside the footprint of the box\n",
                                        trial, i, j);
                            foot_out++;
                        }
                    }
        }
        for (j = 0; j < 16; j++)
            for (i = 0; i < 16; i++) {
                int bit = (int)(m[(j * 16 + i) >> 5] >> ((j * 16 + i) & 31u) & 1u), any = 0, all = 1;
                double a = (2.0 * i + 1) / 16 - 1, b = (2.0 * j + 1) / 16 - 1;
                for (q = 0; q < 5; q++) {
                    double S[3];
                    int c, hit;
                    for (c = 0; c < 3; c++)
                        S[c] = kl.c[c] + (a + (q < 4 ? off[q][0] : 0.0)) * kl.U[c] + (b + (q < 4 ? off[q][1] : 0.0)) * kl.V[c];
                    hit = dbl_hit(P, S, tri, tri + 3, tri + 6);
                    any |= hit;
                    if (q < 4) all &= hit;
                }
                blocked_total += (uint32_t)bit;
                if (bit && !any) {
                    if (false_blocks < 3) fprintf(stderr, "trial %u: sample %u,%u blocked in float, missed in double\n", trial, i, j);
                    false_blocks++;
                }
                if (bit) {
                    /* Exact: the exact segment meets the triangle, so the double one misses
                     * it by no more than double rounding. */
                    double S[3], miss;
                    int c;
                    for (c = 0; c < 3; c++) S[c] = kl.c[c] + a * kl.U[c] + b * kl.V[c];
                    miss = pn_test_seg_miss(P, S, tri, tri + 3, tri + 6);
                    if (miss > worst) worst = miss;
                    if (miss > 1e-9) {
                        if (far_blocks < 3) fprintf(stderr, "trial %u: sample %u,%u blocked, misses by %.3g\n", trial, i, j, miss);
                        far_blocks++;
                    }
                }
                if (!bit && all) {
                    /* No certainty test any more: a robust hit is always blocked. */
                    if (misses < 3) fprintf(stderr, "trial %u: sample %u,%u hit in double, missed in float\n", trial, i, j);
                    misses++;
                }
            }
    }
    fprintf(stderr,
            "predicate vs double: 20000 triangles, %u blocked samples, %u false blocks, %u misses; %u blocked "
            "samples miss by more than 1e-9 (largest miss %.3g)\n",
            blocked_total, false_blocks, misses, far_blocks, worst);
    CHECK(blocked_total > 1000u);
    CHECK(false_blocks == 0u);
    CHECK(misses == 0u);
    CHECK(far_blocks == 0u);
    fprintf(stderr, "footprints: %u blocked samples outside them; %u samples inside the triangles' footprints in all\n",
            foot_out, foot_area);
    CHECK(foot_out == 0u);
    CHECK(foot_area >= blocked_total);
}

/* ---- point light, one-sided light, determinism ------------------------------------------- */

static void test_point_and_one_sided(void)
{
    pn_test_scene s;
    pn_test_host h;
    pn_frame fr;
    pn_light l;
    size_t px;
    uint32_t zeros = 0, ones = 0, other = 0, ground_lit = 0;
    REQUIRE(pn_test_scene_load(&s, "square") == 0);
    REQUIRE(pn_test_open(&h, s.mesh.triangle_count, 64, 64) == 0);
    REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
    l = s.light;
    memset(l.u, 0, sizeof(l.u));
    memset(l.v, 0, sizeof(l.v));
    REQUIRE(render(h.ctx, &s, &s.camera, &l, 64, 64, 16, &fr) == 0);
    for (px = 0; px < 64u * 64u; px++) {
        if (fr.tri_id[px] == PN_NO_TRIANGLE) continue;
        zeros += fr.visibility[px] == 0.0f;
        ones += fr.visibility[px] == 1.0f;
        other += fr.visibility[px] != 0.0f && fr.visibility[px] != 1.0f;
    }
    fprintf(stderr, "point light: %u lit, %u shadowed, %u other\n", ones, zeros, other);
    CHECK(other == 0u && zeros > 20u && ones > 200u);
    /* Flip the light to emit upward: everything below it is behind it and gets 0. */
    l = s.light;
    l.v[2] = -l.v[2];
    REQUIRE(render(h.ctx, &s, &s.camera, &l, 64, 64, 8, &fr) == 0);
    for (px = 0; px < 64u * 64u; px++)
        if (fr.tri_id[px] != PN_NO_TRIANGLE) ground_lit += fr.visibility[px] != 0.0f;
    CHECK(ground_lit == 0u);
    pn_test_close(&h);
    pn_test_scene_free(&s);
}

/* The same bytes whatever order the work items run in: the library's own serial loop
 * against one item a call forward, backward and shuffled, and uneven ranges from the end
 * (pn_test_parallel_for; test_reference_models runs it on 1, 2 and 7 threads). The
 * reference, and GEARS in tiles of a small pair pool: its cells' entries take their slots
 * by atomic cursors in the order the items run, and each cell's run is sorted after, so
 * the chunks' boxes, the boxes a pixel tests (shadow_nodes) and the triangles it hands to
 * the predicate are the same too (its visibility alone would not show a wrong order: the
 * masks are a union). */
static void test_schedule_determinism(void)
{
    pn_test_schedule schedules[4] = {{PN_TEST_ITEMS_FORWARD, 0, 0}, {PN_TEST_ITEMS_BACKWARD, 0, 0},
                                     {PN_TEST_ITEMS_SHUFFLED, 0, 0}, {PN_TEST_CHUNKS_UNEVEN, 0, 0}};
    static const pn_algo algos[2] = {PN_ALGO_REFERENCE, PN_ALGO_GEARS};
    pn_test_scene s;
    float *vis0;
    uint8_t *rgba0;
    int r, a;
    const size_t n = 96u * 72u;
    REQUIRE(pn_test_scene_load(&s, "spheres") == 0);
    vis0 = (float *)malloc(n * sizeof(float));
    rgba0 = (uint8_t *)malloc(n * 4u);
    REQUIRE(vis0 && rgba0);
    for (a = 0; a < 2; a++) {
        pn_test_host h;
        pn_limits lim;
        pn_stats st0;
        if (!(pn_build_info() & (1u << algos[a]))) continue;
        memset(&lim, 0, sizeof(lim));
        lim.max_triangles = s.mesh.triangle_count;
        lim.max_width = 96;
        lim.max_height = 72;
        lim.gears_pairs = 20000; /* the frame needs several times this */
        REQUIRE(pn_test_open_limits(&h, &lim) == 0);
        REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) ==
                PN_OK);
        for (r = 0; r <= 4; r++) {
            pn_frame fr;
            pn_stats st;
            if (r > 0) {
                schedules[r - 1].jobs = 0u;
                schedules[r - 1].ranges = 0u;
                REQUIRE(pn_set_parallel_for(h.ctx, pn_test_parallel_for, &schedules[r - 1]) == PN_OK);
            }
            REQUIRE(render_algo(h.ctx, &s, &s.camera, &s.light, 96, 72, 8, algos[a], 0u, &fr) == 0);
            REQUIRE(pn_get_stats(h.ctx, &st) == PN_OK);
            if (r > 0) /* the schedule ran the frame's passes, split into several ranges */
                CHECK_MSG(schedules[r - 1].jobs > 0u && schedules[r - 1].ranges > 2u * schedules[r - 1].jobs,
                          "schedule %d: %u jobs, %llu ranges", r - 1, schedules[r - 1].jobs,
                          (unsigned long long)schedules[r - 1].ranges);
            if (r == 0) {
                memcpy(vis0, fr.visibility, n * sizeof(float));
                memcpy(rgba0, fr.rgba, n * 4u);
                st0 = st;
                if (algos[a] == PN_ALGO_GEARS) CHECK_MSG(st.gears.tiles > 1u, "GEARS: %u tiles", st.gears.tiles);
                continue;
            }
            CHECK_MSG(memcmp(vis0, fr.visibility, n * sizeof(float)) == 0, "%s, schedule %d: other visibility",
                      pn_algo_name(algos[a]), r - 1);
            CHECK_MSG(memcmp(rgba0, fr.rgba, n * 4u) == 0, "%s, schedule %d: other image", pn_algo_name(algos[a]), r - 1);
            CHECK_MSG(st.shadow_nodes == st0.shadow_nodes && st.shadow_candidates == st0.shadow_candidates,
                      "%s, schedule %d: %llu boxes and %llu candidates, %llu and %llu in order", pn_algo_name(algos[a]),
                      r - 1, (unsigned long long)st.shadow_nodes, (unsigned long long)st.shadow_candidates,
                      (unsigned long long)st0.shadow_nodes, (unsigned long long)st0.shadow_candidates);
        }
        pn_test_close(&h);
    }
    free(vis0);
    free(rgba0);
    pn_test_scene_free(&s);
}

int main(void)
{
    RUN(test_square_closed_form);
    RUN(test_culling_vs_brute_force);
    RUN(test_watertight);
    RUN(test_predicate_vs_double);
    RUN(test_point_and_one_sided);
    RUN(test_schedule_determinism);
    return pn_test_summary();
}
#else
/* The same bytes from the library's own serial loop and from the tools' thread pool on 2 and
 * 7 threads. */
static void test_thread_determinism(void)
{
    pn_test_scene s;
    char err[256];
    float *vis[3];
    uint8_t *rgba[3];
    int r;
    const size_t n = 96u * 72u;
    REQUIRE(pn_test_scene_load(&s, "spheres") == 0);
    for (r = 0; r < 3; r++) {
        pn_host h;
        pn_frame fr;
        REQUIRE(pn_host_open(&h, s.mesh.triangle_count, 96, 72, r == 0 ? 1 : r == 1 ? 2 : 7, err, sizeof(err)) == 0);
        if (r == 0) pn_set_parallel_for(h.ctx, NULL, NULL); /* the library's own serial loop */
        REQUIRE(pn_scene_set(h.ctx, s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count) == PN_OK);
        REQUIRE(render(h.ctx, &s, &s.camera, &s.light, 96, 72, 8, &fr) == 0);
        vis[r] = (float *)malloc(n * sizeof(float));
        rgba[r] = (uint8_t *)malloc(n * 4u);
        REQUIRE(vis[r] && rgba[r]);
        memcpy(vis[r], fr.visibility, n * sizeof(float));
        memcpy(rgba[r], fr.rgba, n * 4u);
        pn_host_close(&h);
    }
    CHECK(memcmp(vis[0], vis[1], n * sizeof(float)) == 0);
    CHECK(memcmp(vis[0], vis[2], n * sizeof(float)) == 0);
    CHECK(memcmp(rgba[0], rgba[1], n * 4u) == 0);
    CHECK(memcmp(rgba[0], rgba[2], n * 4u) == 0);
    for (r = 0; r < 3; r++) {
        free(vis[r]);
        free(rgba[r]);
    }
    pn_test_scene_free(&s);
}

int main(void)
{
    RUN(test_culling_vs_brute_force_spot);
    RUN(test_watertight_spot);
    RUN(test_thread_determinism);
    return pn_test_summary();
}
#endif
