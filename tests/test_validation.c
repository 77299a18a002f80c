/* Hostile input: every invalid case gets its specific status and a message, out-parameters
 * and caller data stay untouched, and a rejected scene leaves the previous one in place. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_raster.h" /* pn_tri_cross, pn_normal_ok: the G-buffer normal (kernels/) */
#include "pn_test.h"
#include "pn_test_scene.h"

static pn_test_host H;
static pn_test_scene S;
static pn_frame_options OPT;

static uint64_t checksum(const void *p, size_t n)
{
    const uint8_t *b = (const uint8_t *)p;
    uint64_t h = 1469598103934665603ull;
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

static int has_message(void) { return strlen(pn_last_error(H.ctx)) > 8; }

static pn_status scene_with(const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt)
{
    uint64_t cp = pos ? checksum(pos, (size_t)nv * 12u) : 0, ci = idx ? checksum(idx, (size_t)nt * 12u) : 0;
    pn_status st = pn_scene_set(H.ctx, pos, nv, idx, nt);
    /* Caller data is never modified, whatever the outcome. */
    if (pos) CHECK(checksum(pos, (size_t)nv * 12u) == cp);
    if (idx) CHECK(checksum(idx, (size_t)nt * 12u) == ci);
    if (st != PN_OK) CHECK_MSG(has_message(), "status %d without a message", (int)st);
    return st;
}

static void test_scene_input(void)
{
    float pos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    uint32_t idx[6] = {0, 1, 2, 1, 3, 2};
    float bad[12];
    uint32_t badi[6];
    CHECK(pn_scene_set(NULL, pos, 4, idx, 2) == PN_E_INVALID_ARG);
    CHECK(scene_with(NULL, 4, idx, 2) == PN_E_INVALID_ARG);
    CHECK(scene_with(pos, 4, NULL, 2) == PN_E_INVALID_ARG);
    CHECK(scene_with(pos, 4, idx, 0) == PN_E_INVALID_ARG);
    memcpy(bad, pos, sizeof(pos));
    bad[4] = NAN;
    CHECK(scene_with(bad, 4, idx, 2) == PN_E_NONFINITE);
    bad[4] = INFINITY;
    CHECK(scene_with(bad, 4, idx, 2) == PN_E_NONFINITE);
    bad[4] = -INFINITY;
    CHECK(scene_with(bad, 4, idx, 2) == PN_E_NONFINITE);
    bad[4] = 3e12f; /* beyond 2^40: the predicate's cubic terms would overflow */
    CHECK(scene_with(bad, 4, idx, 2) == PN_E_LIMIT);
    memcpy(badi, idx, sizeof(idx));
    badi[5] = 4;
    CHECK(scene_with(pos, 4, badi, 2) == PN_E_INDEX_RANGE);
    badi[5] = 0xFFFFFFFFu;
    CHECK(scene_with(pos, 4, badi, 2) == PN_E_INDEX_RANGE);
    CHECK(strstr(pn_last_error(H.ctx), "triangle 1") != NULL);
    /* More triangles than the context holds. */
    {
        uint32_t n = S.mesh.triangle_count + 1u, t;
        uint32_t *many = (uint32_t *)calloc((size_t)n * 3u, sizeof(uint32_t));
        REQUIRE(many != NULL);
        for (t = 0; t < n; t++) {
            many[t * 3] = 0;
            many[t * 3 + 1] = 1;
            many[t * 3 + 2] = 2;
        }
        CHECK(scene_with(pos, 4, many, n) == PN_E_LIMIT);
        free(many);
    }
    /* Rejected before any vertex is read (the array is only 4 vertices long). */
    CHECK(pn_scene_set(H.ctx, pos, PN_MAX_VERTICES + 1u, idx, 2) == PN_E_LIMIT);
}

/* A rejected scene does not replace the one already set. */
static void test_previous_scene_kept(void)
{
    float pos[9] = {0, 0, 0, 1, 0, 0, NAN, 1, 0};
    uint32_t idx[3] = {0, 1, 2};
    pn_frame fr;
    pn_stats st;
    REQUIRE(pn_scene_set(H.ctx, S.mesh.positions, S.mesh.vertex_count, S.mesh.indices, S.mesh.triangle_count) == PN_OK);
    CHECK(scene_with(pos, 3, idx, 1) == PN_E_NONFINITE);
    CHECK(pn_get_stats(H.ctx, &st) == PN_OK);
    CHECK(st.triangles == S.mesh.triangle_count);
    CHECK(pn_render(H.ctx, &S.camera, &S.light, &OPT, &fr) == PN_OK);
}

/* Degenerate triangles are counted and skipped, not errors. */
static void test_degenerate_counted(void)
{
    float pos[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0};
    uint32_t idx[12] = {0, 1, 2, /* real */ 0, 0, 1, /* repeated index */ 0, 1, 3, /* collinear */ 1, 3, 4};
    pn_stats st;
    CHECK(scene_with(pos, 5, idx, 4) == PN_OK);
    CHECK(pn_get_stats(H.ctx, &st) == PN_OK);
    CHECK(st.triangles == 4);
    CHECK(st.degenerate_triangles == 3);
    /* Only degenerate triangles: valid, renders background/lit. */
    CHECK(scene_with(pos, 5, idx + 3, 3) == PN_OK);
    {
        pn_frame fr;
        pn_frame_options o = OPT;
        o.width = 16;
        o.height = 16;
        CHECK(pn_render(H.ctx, &S.camera, &S.light, &o, &fr) == PN_OK);
        CHECK(fr.tri_id[0] == PN_NO_TRIANGLE && fr.visibility[0] == 1.0f);
    }
}

static pn_status render_with(const pn_camera *cam, const pn_light *light, const pn_frame_options *opt)
{
    pn_frame fr, keep;
    pn_camera c0;
    pn_light l0;
    pn_frame_options o0;
    pn_status st;
    memset(&fr, 0x77, sizeof(fr));
    keep = fr;
    if (cam) c0 = *cam;
    if (light) l0 = *light;
    if (opt) o0 = *opt;
    st = pn_render(H.ctx, cam, light, opt, &fr);
    if (st != PN_OK) {
        CHECK(memcmp(&fr, &keep, sizeof(fr)) == 0);
        CHECK_MSG(has_message(), "status %d without a message", (int)st);
    }
    if (cam) CHECK(memcmp(cam, &c0, sizeof(c0)) == 0);
    if (light) CHECK(memcmp(light, &l0, sizeof(l0)) == 0);
    if (opt) CHECK(memcmp(opt, &o0, sizeof(o0)) == 0);
    return st;
}

static void test_frame_input(void)
{
    pn_camera c;
    pn_light l;
    pn_frame_options o;
    pn_frame fr;
    REQUIRE(pn_scene_set(H.ctx, S.mesh.positions, S.mesh.vertex_count, S.mesh.indices, S.mesh.triangle_count) == PN_OK);
    CHECK(render_with(&S.camera, &S.light, &OPT) == PN_OK);
    CHECK(pn_render(NULL, &S.camera, &S.light, &OPT, &fr) == PN_E_INVALID_ARG);
    CHECK(render_with(NULL, &S.light, &OPT) == PN_E_INVALID_ARG);
    CHECK(render_with(&S.camera, NULL, &OPT) == PN_E_INVALID_ARG);
    CHECK(render_with(&S.camera, &S.light, NULL) == PN_E_INVALID_ARG);
    CHECK(pn_render(H.ctx, &S.camera, &S.light, &OPT, NULL) == PN_E_INVALID_ARG);

    /* Light: one zero edge, non-orthogonal, NaN; both zero is a point light. */
    l = S.light;
    memset(l.u, 0, sizeof(l.u));
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_DEGENERATE);
    l = S.light;
    memset(l.v, 0, sizeof(l.v));
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_DEGENERATE);
    l = S.light;
    l.v[0] = l.v[2] * 0.1f; /* 0.1 rad off: not orthogonal */
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_NOT_ORTHO);
    l = S.light;
    l.v[0] = l.u[0];
    l.v[1] = l.u[1];
    l.v[2] = l.u[2]; /* parallel */
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_NOT_ORTHO);
    l = S.light;
    l.center[1] = NAN;
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_NONFINITE);
    l = S.light;
    l.u[0] = INFINITY;
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_NONFINITE);
    l = S.light;
    memset(l.u, 0, sizeof(l.u));
    memset(l.v, 0, sizeof(l.v));
    CHECK(render_with(&S.camera, &l, &OPT) == PN_OK);

    /* Camera. */
    c = S.camera;
    memcpy(c.target, c.eye, sizeof(c.eye));
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c = S.camera;
    c.up[0] = c.target[0] - c.eye[0];
    c.up[1] = c.target[1] - c.eye[1];
    c.up[2] = c.target[2] - c.eye[2];
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c = S.camera;
    memset(c.up, 0, sizeof(c.up));
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c = S.camera;
    c.fov_deg = 0.0f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c.fov_deg = 180.0f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c.fov_deg = NAN;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_NONFINITE);
    c = S.camera;
    c.eye[2] = -INFINITY;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_NONFINITE);

    /* Options. */
    o = OPT;
    o.width = 0;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_IMAGE_SIZE);
    o = OPT;
    o.height = 0;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_IMAGE_SIZE);
    o = OPT;
    o.width = H.ctx ? 65u : 0u; /* the context was opened for 64x64 */
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_LIMIT);
    o = OPT;
    o.k = 12;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    o.k = 64;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    o = OPT;
    o.eps = NAN;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_NONFINITE);
    o = OPT;
    o.eps = -1.0f;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    o = OPT;
    o.albedo = 2.0f;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    o = OPT;
    o.algo = (pn_algo)99;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
}

/* GEARS' grid: 0 is the default, 128 cells per axis or the context's gears_grid_max if
 * smaller (the same bytes as asking for it); above the limit is PN_E_INVALID_ARG naming
 * gears.grid. */
static int render_vis(pn_context *ctx, const pn_frame_options *o, float *vis)
{
    pn_frame fr;
    if (pn_render(ctx, &S.camera, &S.light, o, &fr) != PN_OK) return 0;
    memcpy(vis, fr.visibility, sizeof(float) * 64u * 64u);
    return 1;
}

static void test_gears_grid_default(void)
{
    static float a[64 * 64], b[64 * 64];
    pn_frame_options o = OPT;
    pn_test_host h2;
    pn_limits lim;
    if (!(pn_build_info() & PN_BUILD_GEARS)) return;
    REQUIRE(pn_scene_set(H.ctx, S.mesh.positions, S.mesh.vertex_count, S.mesh.indices, S.mesh.triangle_count) == PN_OK);
    o.algo = PN_ALGO_GEARS;
    CHECK(OPT.gears.grid == 0u); /* pn_frame_options_default */
    o.gears.grid = 0;
    CHECK_MSG(render_vis(H.ctx, &o, a), "grid 0: %s", pn_last_error(H.ctx));
    o.gears.grid = 128;
    CHECK(render_vis(H.ctx, &o, b));
    CHECK(memcmp(a, b, sizeof(a)) == 0);
    o.gears.grid = PN_GEARS_GRID_MAX + 1u;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    CHECK(strstr(pn_last_error(H.ctx), "gears.grid") != NULL);
    o.gears.grid = PN_GEARS_GRID_MAX;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_OK);

    /* A limit below 128: 0 is the limit. */
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = S.mesh.triangle_count;
    lim.max_width = 64;
    lim.max_height = 64;
    lim.gears_grid_max = 40;
    REQUIRE(pn_test_open_limits(&h2, &lim) == 0);
    REQUIRE(pn_scene_set(h2.ctx, S.mesh.positions, S.mesh.vertex_count, S.mesh.indices,
                         S.mesh.triangle_count) == PN_OK);
    o.gears.grid = 0;
    CHECK_MSG(render_vis(h2.ctx, &o, a), "grid 0, limit 40: %s", pn_last_error(h2.ctx));
    o.gears.grid = 40;
    CHECK(render_vis(h2.ctx, &o, b));
    CHECK(memcmp(a, b, sizeof(a)) == 0);
    o.gears.grid = 41;
    CHECK(!render_vis(h2.ctx, &o, b) && strstr(pn_last_error(h2.ctx), "gears.grid = 41") != NULL);
    pn_test_close(&h2);
}

/* Issue 20: frames and normals that cannot be formed in float. A triangle whose cross
 * product has no component of at least FLT_MIN (2^-126) is degenerate; a camera or light
 * whose frame would need a subnormal square, or a fov whose pixels' rays coincide, gets
 * its status. Boundaries are tested on both sides. */
static int frame_normals_unit(const pn_frame *fr)
{
    uint32_t i, bad = 0;
    for (i = 0; i < fr->width * fr->height; i++) {
        const float *n = fr->normal + 3u * i;
        if (fr->tri_id[i] == PN_NO_TRIANGLE) continue;
        if (!(fabsf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0f) < 1e-3f)) bad++;
    }
    return bad == 0;
}

static void test_subnormal_triangles(void)
{
    const float e = 0x1p-63f, s = 1e-20f;
    /* 0..2: big triangle; 3..5 edges 2^-63 (cross 2^-126: normal); 3, 6, 7 edges 2^-63 and
     * 2^-64 (cross 2^-127: subnormal); 8..10 edge 1e-20 (cross 1e-40); 11..13 a 1 x 1e-39
     * sliver (the fuzzer's shape); 14..16 edge 1e-18 (cross 1e-36: fine). */
    float pos[17 * 3] = {-1, -1, 0, 1, -1, 0, 0, 1, 0,
                         0, 0, 0.5f, e, 0, 0.5f, 0, e, 0.5f,
                         0.5f * e, 0, 0.5f, 0, 0.5f * e, 0.5f,
                         0, 0, 0.25f, s, 0, 0.25f, 0, s, 0.25f,
                         -1, 0.25f, 0.5f, 1, 0.25f, 0.5f, 0, 0.25f + 1e-39f, 0.5f,
                         0, 0, 0.75f, 1e-18f, 0, 0.75f, 0, 1e-18f, 0.75f};
    uint32_t idx[6 * 3] = {0, 1, 2, 3, 4, 5, 3, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    pn_stats st;
    pn_frame fr;
    CHECK(scene_with(pos, 17, idx, 6) == PN_OK);
    CHECK(pn_get_stats(H.ctx, &st) == PN_OK);
    CHECK(st.triangles == 6);
    CHECK_MSG(st.degenerate_triangles == 3, "%u degenerate, expected 3 (2^-127, 1e-40, sliver)",
              st.degenerate_triangles);
    /* Only the 2^-126 triangle: not degenerate, its normal is unit where it is drawn. */
    CHECK(scene_with(pos, 17, idx + 3, 1) == PN_OK);
    CHECK(pn_get_stats(H.ctx, &st) == PN_OK && st.degenerate_triangles == 0);
    CHECK(scene_with(pos, 17, idx + 6, 1) == PN_OK);
    CHECK(pn_get_stats(H.ctx, &st) == PN_OK && st.degenerate_triangles == 1);
    /* Drawing them is no test: at a distance where a triangle this small covers a pixel,
     * its depth n.(A - eye) underflows to 0 and nothing is drawn. The normalization itself
     * is the point (the G-buffer normal is pn_v3_normalize(pn_tri_cross(A, B, C))). */
    {
        pn_v3 A = pn_v3_make(0, 0, 0), B = pn_v3_make(e, 0, 0), C = pn_v3_make(0, e, 0), n;
        n = pn_tri_cross(A, B, C); /* (0, 0, 2^-126) */
        CHECK(pn_normal_ok(n) && n.z == 0x1p-126f);
        n = pn_v3_normalize(n);
        CHECK(n.x == 0.0f && n.y == 0.0f && n.z == 1.0f);
        B = pn_v3_make(0.5f * e, 0, 0);
        n = pn_tri_cross(A, B, C); /* (0, 0, 2^-127): subnormal, so its bits are not all there */
        CHECK(!pn_normal_ok(n) && n.z == 0x1p-127f);
        n = pn_v3_make(0, 1e-41f, 0); /* the fuzzer's magnitude: 1/m overflows, NaN */
        CHECK(!pn_normal_ok(n));
        n = pn_v3_normalize(n);
        CHECK_MSG(!(n.y == n.y), "pn_v3_normalize of a 1e-41 vector gave %g, not NaN: "
                  "the reason for pn_normal_ok is gone, revisit it", (double)n.y);
        n = pn_v3_make(1e-41f, 2e-38f, 0); /* subnormal components beside a normal one */
        CHECK(pn_normal_ok(n));
        n = pn_v3_normalize(n);
        CHECK(fabsf(n.x * n.x + n.y * n.y + n.z * n.z - 1.0f) < 1e-6f);
    }
    /* All six together under the spheres' camera: every drawn normal unit. */
    CHECK(scene_with(pos, 17, idx, 6) == PN_OK);
    CHECK(pn_render(H.ctx, &S.camera, &S.light, &OPT, &fr) == PN_OK);
    CHECK(frame_normals_unit(&fr));
}

static void test_float_frames(void)
{
    pn_camera c;
    pn_light l;
    pn_frame_options o = OPT;
    REQUIRE(pn_scene_set(H.ctx, S.mesh.positions, S.mesh.vertex_count, S.mesh.indices, S.mesh.triangle_count) == PN_OK);
    /* fov: the fuzzer's 7.6e-41 degrees (tan(fov/2) subnormal), 1e-30, and both sides of
     * 2 tan(fov/2) / rows = 2^-23 for 64 rows (fov = 4.37e-4 degrees). */
    c = S.camera;
    c.fov_deg = 7.6e-41f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    CHECK(strstr(pn_last_error(H.ctx), "fov is too small for 64 image rows") != NULL);
    c.fov_deg = 1e-30f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c.fov_deg = 3e-4f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c.fov_deg = 6e-4f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_OK);
    o.height = 32; /* the bound scales with the rows: 3e-4 degrees is enough for 32 */
    c.fov_deg = 3e-4f;
    CHECK(render_with(&c, &S.light, &o) == PN_OK);
    /* Eye and target 1e-20 apart (f.f subnormal), 1e-18 apart (fine). */
    c = S.camera;
    memcpy(c.target, c.eye, sizeof(c.eye));
    c.target[0] = 0.0f;
    c.eye[0] = 1e-20f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    CHECK(strstr(pn_last_error(H.ctx), "too close") != NULL);
    c.eye[0] = 1e-18f;
    c.up[0] = 0.0f, c.up[1] = 1.0f, c.up[2] = 0.0f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_OK);
    /* up of length 1e-20 (|f x up|^2 subnormal) and 1e-18. */
    c = S.camera;
    c.up[0] = 0.0f, c.up[1] = 1e-20f, c.up[2] = 0.0f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_E_CAMERA);
    c.up[1] = 1e-18f;
    CHECK(render_with(&c, &S.light, &OPT) == PN_OK);
    /* Light: tiny non-zero half-edges were a point light before (their lengths rounded to
     * 0); now only u = v = 0 exactly is. */
    l = S.light;
    memset(l.u, 0, sizeof(l.u));
    memset(l.v, 0, sizeof(l.v));
    l.u[0] = 1e-30f;
    l.v[2] = 1e-30f;
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_DEGENERATE);
    CHECK(strstr(pn_last_error(H.ctx), "too short") != NULL);
    l.u[0] = 1e-20f; /* |u| 1e-20: u.u subnormal */
    l.v[2] = 1.0f;
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_DEGENERATE);
    l.u[0] = 1.0f;
    l.v[2] = 1e-20f;
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_DEGENERATE);
    /* Both squares normal, but u x v = (8.8e-39, -8.8e-39, 0) cannot be normalized. */
    l.u[0] = 8e-20f, l.u[1] = 8e-20f, l.u[2] = 0.0f;
    l.v[0] = 0.0f, l.v[1] = 0.0f, l.v[2] = 1.1e-19f;
    CHECK(render_with(&S.camera, &l, &OPT) == PN_E_LIGHT_DEGENERATE);
    CHECK(strstr(pn_last_error(H.ctx), "u x v") != NULL);
    /* u, v of 1e-18: u x v = 1e-36, a (tiny) area light. */
    l.u[0] = 1e-18f, l.u[1] = 0.0f;
    l.v[2] = 1e-18f;
    CHECK(render_with(&S.camera, &l, &OPT) == PN_OK);
}

static void test_no_scene(void)
{
    pn_test_host h2;
    pn_frame fr;
    REQUIRE(pn_test_open(&h2, 16, 8, 8) == 0);
    CHECK(pn_render(h2.ctx, &S.camera, &S.light, &OPT, &fr) == PN_E_NO_SCENE);
    CHECK(strlen(pn_last_error(h2.ctx)) > 0);
    pn_test_close(&h2);
}

/* pn_scene_set_receivers: its statuses, and no effect on any algorithm but MCSM. The
 * marking itself has no public getter: that a failed call leaves it alone can only be
 * seen through MCSM frames; here every other algorithm's bytes must not move whatever
 * the marking, and the scene (its counts and BVH) must not either. */
static const struct {
    pn_algo algo;
    uint32_t build;
    const char *name;
} RECV_ALGOS[] = {{PN_ALGO_REFERENCE, PN_BUILD_REFERENCE, "reference"},
                  {PN_ALGO_GEARS, PN_BUILD_GEARS, "gears"},
                  {PN_ALGO_RAYTRACE, PN_BUILD_RAYTRACE, "raytrace"},
                  {PN_ALGO_SRT, PN_BUILD_SRT, "srt"},
                  {PN_ALGO_OCCTEX, PN_BUILD_OCCTEX, "occtex"}};
#define RECV_N (sizeof(RECV_ALGOS) / sizeof(RECV_ALGOS[0]))
#define RECV_PIXELS (64u * 64u)

/* Every built algorithm's visibility into vis[a]; 0 if one could not render. */
static int recv_frames(const pn_test_scene *s, float vis[RECV_N][RECV_PIXELS])
{
    size_t a;
    for (a = 0; a < RECV_N; a++) {
        pn_frame_options o = OPT;
        pn_frame fr;
        pn_status st;
        memset(vis[a], 0, sizeof(vis[a]));
        if (!(pn_build_info() & RECV_ALGOS[a].build)) continue;
        o.algo = RECV_ALGOS[a].algo;
        o.eps = s->eps;
        o.gears.grid = 32;
        st = pn_render(H.ctx, &s->camera, &s->light, &o, &fr);
        CHECK_MSG(st == PN_OK, "%s: %s", RECV_ALGOS[a].name, pn_last_error(H.ctx));
        if (st != PN_OK) return 0;
        CHECK(fr.width * fr.height == RECV_PIXELS);
        if (fr.width * fr.height != RECV_PIXELS) return 0;
        memcpy(vis[a], fr.visibility, sizeof(vis[a]));
    }
    return 1;
}

static int recv_range_error(uint32_t first, uint32_t count)
{
    pn_status st = pn_scene_set_receivers(H.ctx, first, count);
    CHECK_MSG(st == PN_E_INDEX_RANGE, "(%u, %u): status %d", (unsigned)first, (unsigned)count, (int)st);
    CHECK_MSG(strstr(pn_last_error(H.ctx), "pn_scene_set_receivers") != NULL, "(%u, %u): message '%s'",
              (unsigned)first, (unsigned)count, pn_last_error(H.ctx));
    return st == PN_E_INDEX_RANGE;
}

static void test_receivers(void)
{
    static float before[RECV_N][RECV_PIXELS], after[RECV_N][RECV_PIXELS];
    pn_test_scene sq, bad;
    pn_test_host h2;
    pn_stats s0, s1;
    uint32_t n;
    size_t a;

    CHECK(pn_scene_set_receivers(NULL, 0, 0) == PN_E_INVALID_ARG);
    /* No scene yet: PN_E_NO_SCENE, with a message, whatever the range. */
    REQUIRE(pn_test_open(&h2, 16, 8, 8) == 0);
    CHECK(pn_scene_set_receivers(h2.ctx, 0, 0) == PN_E_NO_SCENE);
    CHECK(strstr(pn_last_error(h2.ctx), "pn_scene_set_receivers") != NULL);
    CHECK(pn_scene_set_receivers(h2.ctx, 5, 0xFFFFFFFFu) == PN_E_NO_SCENE);
    pn_test_close(&h2);

    /* A small scene (the square: occluder 0..1, ground 2..3), set without the marking. */
    REQUIRE(pn_test_scene_load(&sq, "square") == 0);
    n = sq.mesh.triangle_count;
    CHECK(n == 4u && sq.mesh.receiver_first == 2u && sq.mesh.receiver_count == 2u);
    REQUIRE(pn_scene_set(H.ctx, sq.mesh.positions, sq.mesh.vertex_count, sq.mesh.indices, n) == PN_OK);
    CHECK(pn_get_stats(H.ctx, &s0) == PN_OK);
    if (!recv_frames(&sq, before)) {
        pn_test_scene_free(&sq);
        return;
    }
    {
        /* The comparisons below mean something: the first algorithm's frame has shadow
         * (the reference's; a build without it, the first of the list it has). */
        uint32_t i, dark = 0, part = 0;
        size_t a = 0;
        while (a < RECV_N && !(pn_build_info() & RECV_ALGOS[a].build)) a++;
        if (a < RECV_N) {
            for (i = 0; i < RECV_PIXELS; i++) {
                dark += before[a][i] == 0.0f;
                part += before[a][i] > 0.0f && before[a][i] < 1.0f;
            }
            /* Umbra and penumbra for the exact algorithms; an approximation's umbra may be
             * penumbra (occtex never reaches 0 here). */
            int exact = RECV_ALGOS[a].algo == PN_ALGO_REFERENCE || RECV_ALGOS[a].algo == PN_ALGO_GEARS ||
                        RECV_ALGOS[a].algo == PN_ALGO_RAYTRACE;
            CHECK_MSG(exact ? dark > 0u && part > 0u : dark + part > 0u, "%s: dark %u, penumbra %u",
                      RECV_ALGOS[a].name, dark, part);
        }
    }

    /* Out of range: first beyond the scene, first + count past it by one, and sums that
     * wrap around uint32. Each leaves the scene as it was. */
    recv_range_error(n + 1u, 0);
    recv_range_error(0xFFFFFFFFu, 0);
    recv_range_error(0, n + 1u);
    recv_range_error(1, n);
    recv_range_error(n, 1);
    recv_range_error(1, 0xFFFFFFFFu);
    recv_range_error(0xFFFFFFFFu, 1);
    recv_range_error(2, 0xFFFFFFFEu);
    CHECK(pn_get_stats(H.ctx, &s1) == PN_OK);
    CHECK(s1.triangles == s0.triangles && s1.degenerate_triangles == s0.degenerate_triangles &&
          s1.bvh_nodes == s0.bvh_nodes && s1.bvh_depth == s0.bvh_depth);

    /* In range: up to the last triangle, empty ranges anywhere up to the end. */
    CHECK(pn_scene_set_receivers(H.ctx, 0, n) == PN_OK);
    CHECK(pn_scene_set_receivers(H.ctx, n, 0) == PN_OK);
    CHECK(pn_scene_set_receivers(H.ctx, 0, 0) == PN_OK);
    CHECK(pn_scene_set_receivers(H.ctx, n - 1u, 1) == PN_OK);
    CHECK(pn_scene_set_receivers(H.ctx, 2, 2) == PN_OK); /* the ground */
    CHECK(pn_get_stats(H.ctx, &s1) == PN_OK);
    CHECK(s1.triangles == s0.triangles && s1.degenerate_triangles == s0.degenerate_triangles &&
          s1.bvh_nodes == s0.bvh_nodes && s1.bvh_depth == s0.bvh_depth);

    /* The ground marked: no algorithm but MCSM sees it, to the byte. */
    if (recv_frames(&sq, after)) {
        for (a = 0; a < RECV_N; a++)
            CHECK_MSG(memcmp(before[a], after[a], sizeof(before[a])) == 0, "%s: visibility changed by the marking",
                      RECV_ALGOS[a].name);
    }
    /* A failed call after a marking, then everything marked: the same bytes again. */
    recv_range_error(3, 2);
    CHECK(pn_scene_set_receivers(H.ctx, 0, n) == PN_OK);
    if (recv_frames(&sq, after)) {
        for (a = 0; a < RECV_N; a++)
            CHECK_MSG(memcmp(before[a], after[a], sizeof(before[a])) == 0, "%s: visibility changed by marking all",
                      RECV_ALGOS[a].name);
    }

    /* The scene, then its range (pn_test_scene_upload, as the tools' pn_setup_upload, which
     * tests/test_setup.c checks): the range's status when only it fails (the scene is set
     * by then), pn_scene_set's when the scene fails. */
    CHECK(pn_test_scene_upload(H.ctx, &sq) == PN_OK);
    if (recv_frames(&sq, after)) CHECK(memcmp(before[0], after[0], sizeof(before[0])) == 0);
    bad = sq;
    bad.mesh.receiver_first = 3u;
    bad.mesh.receiver_count = 2u;
    CHECK(pn_test_scene_upload(H.ctx, &bad) == PN_E_INDEX_RANGE);
    CHECK(has_message());
    CHECK(pn_get_stats(H.ctx, &s1) == PN_OK && s1.triangles == n);
    bad.mesh.indices = NULL;
    CHECK(pn_test_scene_upload(H.ctx, &bad) == PN_E_INVALID_ARG);
    CHECK(strstr(pn_last_error(H.ctx), "pn_scene_set") != NULL);
    CHECK(pn_get_stats(H.ctx, &s1) == PN_OK && s1.triangles == n);
    pn_test_scene_free(&sq);
}

static void test_status_strings(void)
{
    int s;
    for (s = 0; s <= (int)PN_E_INTERNAL; s++) {
        const char *t = pn_status_str((pn_status)s);
        CHECK(t != NULL && strncmp(t, "PN_", 3) == 0);
    }
    CHECK(pn_status_str((pn_status)1000) != NULL);
    CHECK(pn_last_error(NULL) != NULL);
    /* The registry's names (src/pn_algorithms.h): one per pn_algo, distinct, NULL outside. */
    for (s = 0; s < PN_ALGO_COUNT; s++) {
        int t;
        CHECK(pn_algo_name((pn_algo)s) != NULL);
        for (t = 0; t < s; t++)
            CHECK(pn_algo_name((pn_algo)t) && pn_algo_name((pn_algo)s) &&
                  strcmp(pn_algo_name((pn_algo)t), pn_algo_name((pn_algo)s)) != 0);
    }
    CHECK(pn_algo_name((pn_algo)PN_ALGO_COUNT) == NULL && pn_algo_name((pn_algo)-1) == NULL);
    CHECK(strcmp(pn_algo_name(PN_ALGO_REFERENCE), "reference") == 0 && strcmp(pn_algo_name(PN_ALGO_MCSM), "mcsm") == 0 &&
          strcmp(pn_algo_name(PN_ALGO_WEDGES), "wedges") == 0);
    CHECK((pn_build_info() & PN_BUILD_PORT_SCALAR) != 0u);
    CHECK(pn_get_stats(NULL, NULL) == PN_E_INVALID_ARG);
    CHECK(pn_set_parallel_for(NULL, NULL, NULL) == PN_E_INVALID_ARG);
}

/* pn_last_error (penumbra.h): "" on a fresh context, the failing call's message after a
 * failure, untouched by a call that succeeds, replaced by the next failure. */
static void test_error_contract(void)
{
    static const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, nan_pos[9] = {0, 0, 0, 1, NAN, 0, 0, 1, 0};
    static const uint32_t idx[3] = {0, 1, 2}, bad_idx[3] = {0, 1, 7};
    pn_test_host h;
    char first[256];
    REQUIRE(pn_test_open(&h, 16, 8, 8) == 0);
    CHECK(strcmp(pn_last_error(h.ctx), "") == 0);
    CHECK(pn_scene_set(h.ctx, nan_pos, 3, idx, 1) == PN_E_NONFINITE);
    snprintf(first, sizeof(first), "%s", pn_last_error(h.ctx));
    CHECK_MSG(strstr(first, "vertex 1") != NULL || strstr(first, "finite") != NULL, "message: '%s'", first);
    CHECK(pn_scene_set(h.ctx, pos, 3, idx, 1) == PN_OK);
    CHECK_MSG(strcmp(pn_last_error(h.ctx), first) == 0, "a successful call changed the message to '%s'",
              pn_last_error(h.ctx));
    CHECK(pn_scene_set(h.ctx, pos, 3, bad_idx, 1) == PN_E_INDEX_RANGE);
    CHECK_MSG(strcmp(pn_last_error(h.ctx), first) != 0 && strstr(pn_last_error(h.ctx), "7") != NULL,
              "the second failure's message is '%s'", pn_last_error(h.ctx));
    pn_test_close(&h);
}

/* ---- The caller's G-buffer, output buffers and points (issue 52) ---- */

typedef struct kept_frame {
    float vis[64 * 64], depth[64 * 64], pos[64 * 64 * 3], nrm[64 * 64 * 3];
    uint32_t ids[64 * 64];
    uint8_t rgba[64 * 64 * 4];
} kept_frame;
static kept_frame K0, K1;

static void keep(kept_frame *k, const pn_frame *fr)
{
    memcpy(k->vis, fr->visibility, sizeof(k->vis));
    memcpy(k->depth, fr->depth, sizeof(k->depth));
    memcpy(k->pos, fr->position, sizeof(k->pos));
    memcpy(k->nrm, fr->normal, sizeof(k->nrm));
    memcpy(k->ids, fr->tri_id, sizeof(k->ids));
    if (fr->rgba) memcpy(k->rgba, fr->rgba, sizeof(k->rgba));
}

static void test_caller_gbuffer(void)
{
    static float vis_out[64 * 64], depth[64 * 64];
    static uint8_t rgba_out[64 * 64 * 4];
    static uint32_t ids[64 * 64];
    pn_frame_options o = OPT;
    pn_gbuffer g;
    pn_frame fr;
    uint64_t cd, ci;
    uint32_t a, lit = 0, i;
    REQUIRE(pn_scene_set(H.ctx, S.mesh.positions, S.mesh.vertex_count, S.mesh.indices, S.mesh.triangle_count) == PN_OK);
    REQUIRE(pn_render(H.ctx, &S.camera, &S.light, &OPT, &fr) == PN_OK);
    keep(&K0, &fr);
    for (i = 0; i < 64u * 64u; i++) lit += K0.ids[i] != PN_NO_TRIANGLE;
    REQUIRE(lit > 100u && lit < 64u * 64u); /* both triangles and background */

    /* Output buffers: the same bytes as the frame's; without RGBA no image and the same
     * visibility; an output in the arena, or RGBA asked for and turned off, refused. */
    memset(vis_out, 0xAB, sizeof(vis_out));
    o.visibility_out = vis_out;
    o.rgba_out = rgba_out;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_OK);
    CHECK(memcmp(vis_out, K0.vis, sizeof(vis_out)) == 0 && memcmp(rgba_out, K0.rgba, sizeof(rgba_out)) == 0);
    o = OPT;
    o.no_rgba = 1;
    REQUIRE(pn_render(H.ctx, &S.camera, &S.light, &o, &fr) == PN_OK);
    CHECK(fr.rgba == NULL && memcmp(fr.visibility, K0.vis, sizeof(K0.vis)) == 0);
    o.rgba_out = rgba_out;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    o = OPT;
    o.no_rgba = 2;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    REQUIRE(pn_render(H.ctx, &S.camera, &S.light, &OPT, &fr) == PN_OK);
    o = OPT;
    o.visibility_out = (float *)(uintptr_t)fr.depth; /* the arena's */
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    o = OPT;
    o.rgba_out = (uint8_t *)(uintptr_t)fr.tri_id;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);

    /* The frame's own depth and ids handed back: the same bytes, every algorithm. */
    memcpy(depth, K0.depth, sizeof(depth));
    memcpy(ids, K0.ids, sizeof(ids));
    g.depth = depth;
    g.tri_id = ids;
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        if (!(pn_build_info() & (1u << a))) continue;
        o = OPT;
        o.algo = (pn_algo)a;
        REQUIRE(pn_render(H.ctx, &S.camera, &S.light, &o, &fr) == PN_OK);
        keep(&K0, &fr);
        o.gbuffer = &g;
        REQUIRE(pn_render(H.ctx, &S.camera, &S.light, &o, &fr) == PN_OK);
        keep(&K1, &fr);
        CHECK_MSG(memcmp(&K0, &K1, sizeof(K0)) == 0, "%s: the caller's G-buffer gives other bytes",
                  pn_algo_name((pn_algo)a));
    }

    /* Hostile G-buffers: each refused before anything is written, the caller's arrays
     * untouched; a background pixel's depth is not read. */
    cd = checksum(depth, sizeof(depth));
    ci = checksum(ids, sizeof(ids));
    o = OPT;
    o.gbuffer = &g;
    for (i = 0; ids[i] != PN_NO_TRIANGLE; i++) {}
    depth[i] = NAN;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_OK);
    depth[i] = K0.depth[i];
    for (i = 0; ids[i] == PN_NO_TRIANGLE; i++) {}
    {
        const struct { uint32_t id; float d; pn_status st; } bad[] = {
            {0xFFFFFFF0u, 1.0f, PN_E_INDEX_RANGE}, {0u, NAN, PN_E_NONFINITE}, {0u, INFINITY, PN_E_NONFINITE},
            {0u, 0.0f, PN_E_INVALID_ARG}, {0u, -1.0f, PN_E_INVALID_ARG}, {0u, 3e12f, PN_E_LIMIT}};
        uint32_t b, id0 = ids[i];
        float d0 = depth[i];
        for (b = 0; b < sizeof(bad) / sizeof(bad[0]); b++) {
            ids[i] = bad[b].id == 0u ? id0 : S.mesh.triangle_count + bad[b].id - 0xFFFFFFF0u;
            depth[i] = bad[b].d;
            CHECK_MSG(render_with(&S.camera, &S.light, &o) == bad[b].st, "hostile G-buffer %u: %s", b,
                      pn_last_error(H.ctx));
        }
        ids[i] = id0;
        depth[i] = d0;
        CHECK(checksum(depth, sizeof(depth)) == cd && checksum(ids, sizeof(ids)) == ci);
    }
    g.depth = NULL;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    g.depth = depth;
    g.tri_id = NULL;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    g.tri_id = ids;
    /* Any triangle at any depth in front of the eye is a G-buffer the frame takes: every
     * pixel on triangle 0, at depths the raster would never give. */
    for (i = 0; i < 64u * 64u; i++) {
        ids[i] = (i * 7u) % S.mesh.triangle_count;
        depth[i] = 0.001f + (float)(i % 97u) * 0.1f;
    }
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        if (!(pn_build_info() & (1u << a))) continue;
        o.algo = (pn_algo)a;
        CHECK_MSG(render_with(&S.camera, &S.light, &o) == PN_OK, "%s on an arbitrary G-buffer: %s",
                  pn_algo_name((pn_algo)a), pn_last_error(H.ctx));
    }
}

/* A degenerate triangle's id in a G-buffer or a point: refused (nothing draws it). */
static void test_caller_degenerate(void)
{
    float pos[12] = {-1, -1, 0, 1, -1, 0, 0, 1, 0, 2, 0, 0};
    uint32_t idx[6] = {0, 1, 2, 0, 0, 1};
    static float depth[64 * 64];
    static uint32_t ids[64 * 64];
    float pt[3] = {0, 0, 0}, nm[3] = {0, 0, 1}, out = -1.0f;
    uint32_t id = 1;
    pn_gbuffer g;
    pn_frame_options o = OPT;
    uint32_t i;
    REQUIRE(scene_with(pos, 4, idx, 2) == PN_OK);
    for (i = 0; i < 64u * 64u; i++) {
        ids[i] = PN_NO_TRIANGLE;
        depth[i] = 1.0f;
    }
    ids[100] = 1;
    g.depth = depth;
    g.tri_id = ids;
    o.gbuffer = &g;
    CHECK(render_with(&S.camera, &S.light, &o) == PN_E_INVALID_ARG);
    if (OPT.algo == PN_ALGO_WEDGES) return; /* no point query */
    CHECK(pn_visibility_points(H.ctx, &S.light, &OPT, pt, nm, &id, 1, &out) == PN_E_INVALID_ARG && out == -1.0f);
    id = 0;
    CHECK(pn_visibility_points(H.ctx, &S.light, &OPT, pt, nm, &id, 1, &out) == PN_OK && out >= 0.0f);
}

static void test_points_input(void)
{
    static float pts[64 * 64 * 3], nrm[64 * 64 * 3], out[64 * 64];
    static uint32_t ids[64 * 64];
    pn_frame_options o = OPT;
    pn_frame fr;
    uint32_t a, n = 64u * 64u;
    uint64_t cp, cn, ci;
    REQUIRE(pn_scene_set(H.ctx, S.mesh.positions, S.mesh.vertex_count, S.mesh.indices, S.mesh.triangle_count) == PN_OK);
    /* The frame's pixels as points: the frame's visibility; for an exact algorithm in any
     * batch shape (here 64 batches of 16 x 4). */
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        pn_status st;
        if (!(pn_build_info() & (1u << a))) continue;
        o = OPT;
        o.algo = (pn_algo)a;
        o.mcsm.blur = PN_MC_BLUR_OFF;
        o.mcsm.layers = 2u; /* a point's default: it has no eye for the third layer */
        REQUIRE(pn_render(H.ctx, &S.camera, &S.light, &o, &fr) == PN_OK);
        keep(&K0, &fr);
        o.mcsm.layers = 0u;
        memset(out, 0xAB, sizeof(out));
        st = pn_visibility_points(H.ctx, &S.light, &o, K0.pos, K0.nrm, K0.ids, n, out);
        if (a == PN_ALGO_WEDGES) {
            CHECK(st == PN_E_UNSUPPORTED && has_message());
            continue;
        }
        CHECK_MSG(st == PN_OK && memcmp(out, K0.vis, sizeof(out)) == 0, "%s: points differ from the frame (%s)",
                  pn_algo_name((pn_algo)a), pn_last_error(H.ctx));
        if (a == PN_ALGO_REFERENCE || a == PN_ALGO_GEARS || a == PN_ALGO_RAYTRACE) {
            o.width = 16;
            o.height = 4;
            memset(out, 0xAB, sizeof(out));
            CHECK_MSG(pn_visibility_points(H.ctx, &S.light, &o, K0.pos, K0.nrm, K0.ids, n, out) == PN_OK &&
                          memcmp(out, K0.vis, sizeof(out)) == 0,
                      "%s: points in batches differ from the frame", pn_algo_name((pn_algo)a));
        }
    }
    if (pn_build_info() & PN_BUILD_MCSM) {
        o = OPT;
        o.algo = PN_ALGO_MCSM;
        o.mcsm.layers = 3;
        CHECK(pn_visibility_points(H.ctx, &S.light, &o, K0.pos, K0.nrm, K0.ids, n, out) == PN_E_UNSUPPORTED);
    }

    /* Hostile points: refused before anything is written; the caller's arrays untouched.
     * (A build with the wedges alone refuses every point query first.) */
    if (OPT.algo == PN_ALGO_WEDGES) {
        CHECK(pn_visibility_points(H.ctx, &S.light, &OPT, NULL, NULL, NULL, 0, NULL) == PN_E_UNSUPPORTED);
        return;
    }
    memcpy(pts, K0.pos, sizeof(pts));
    memcpy(nrm, K0.nrm, sizeof(nrm));
    memcpy(ids, K0.ids, sizeof(ids));
    cp = checksum(pts, sizeof(pts));
    cn = checksum(nrm, sizeof(nrm));
    ci = checksum(ids, sizeof(ids));
    o = OPT;
    memset(out, 0xAB, sizeof(out));
    CHECK(pn_visibility_points(NULL, &S.light, &o, pts, nrm, ids, n, out) == PN_E_INVALID_ARG);
    CHECK(pn_visibility_points(H.ctx, NULL, &o, pts, nrm, ids, n, out) == PN_E_INVALID_ARG);
    CHECK(pn_visibility_points(H.ctx, &S.light, NULL, pts, nrm, ids, n, out) == PN_E_INVALID_ARG);
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, NULL, nrm, ids, n, out) == PN_E_INVALID_ARG);
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, pts, nrm, ids, n, NULL) == PN_E_INVALID_ARG);
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, NULL, NULL, NULL, 0, NULL) == PN_OK);
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, pts, nrm, ids, n, (float *)(uintptr_t)K0.vis) == PN_OK);
    REQUIRE(pn_render(H.ctx, &S.camera, &S.light, &o, &fr) == PN_OK);
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, pts, nrm, ids, n, (float *)(uintptr_t)fr.visibility) ==
          PN_E_INVALID_ARG);
    o.width = 0;
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, pts, nrm, ids, n, out) == PN_E_IMAGE_SIZE);
    o.width = 65;
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, pts, nrm, ids, n, out) == PN_E_LIMIT);
    o = OPT;
    o.k = 5;
    CHECK(pn_visibility_points(H.ctx, &S.light, &o, pts, nrm, ids, n, out) == PN_E_INVALID_ARG);
    o = OPT;
    {
        uint32_t j = 0, b;
        while (ids[j] == PN_NO_TRIANGLE) j++;
        for (b = 0; b < 6u; b++) {
            float keep_p = pts[j * 3u], keep_n = nrm[j * 3u + 1u];
            uint32_t keep_i = ids[j];
            pn_status want = PN_E_NONFINITE;
            if (b == 0u) pts[j * 3u] = NAN;
            if (b == 1u) nrm[j * 3u + 1u] = INFINITY;
            if (b == 2u) pts[j * 3u] = 3e12f, want = PN_E_LIMIT;
            if (b == 3u) nrm[j * 3u + 1u] = keep_n * 0.5f + 0.5f, want = PN_E_INVALID_ARG;
            if (b == 4u) ids[j] = S.mesh.triangle_count, want = PN_E_INDEX_RANGE;
            if (b == 5u) nrm[j * 3u + 1u] = keep_n + 0.01f, want = PN_E_INVALID_ARG;
            if (b == 3u && fabsf(keep_n * 0.5f + 0.5f - keep_n) < 0.01f) nrm[j * 3u + 1u] = keep_n + 0.5f;
            CHECK_MSG(pn_visibility_points(H.ctx, &S.light, &o, pts, nrm, ids, n, out) == want && has_message(),
                      "hostile point %u: %s", b, pn_last_error(H.ctx));
            pts[j * 3u] = keep_p;
            nrm[j * 3u + 1u] = keep_n;
            ids[j] = keep_i;
        }
        CHECK(checksum(pts, sizeof(pts)) == cp && checksum(nrm, sizeof(nrm)) == cn && checksum(ids, sizeof(ids)) == ci);
        for (b = 0; b < n; b++) CHECK((((const uint32_t *)(const void *)out)[b]) == 0xABABABABu);
    }
}

int main(void)
{
    if (pn_test_scene_load(&S, "spheres") != 0 || pn_test_open(&H, S.mesh.triangle_count, 64, 64) != 0) return 1;
    pn_frame_options_default(&OPT);
    OPT.width = 64;
    OPT.height = 64;
    OPT.k = 4;
    OPT.eps = S.eps;
    RUN(test_scene_input);
    RUN(test_previous_scene_kept);
    RUN(test_degenerate_counted);
    RUN(test_frame_input);
    RUN(test_gears_grid_default);
    RUN(test_subnormal_triangles);
    RUN(test_float_frames);
    RUN(test_no_scene);
    RUN(test_receivers);
    RUN(test_status_strings);
    RUN(test_error_contract);
    RUN(test_caller_gbuffer);
    RUN(test_points_input);
    RUN(test_caller_degenerate);
    pn_test_close(&H);
    pn_test_scene_free(&S);
    return pn_test_summary();
}
