/* Hostile input: every invalid case gets its specific status and a message, out-parameters
 * and caller data stay untouched, and a rejected scene leaves the previous one in place. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_setup.h"
#include "pn_test.h"

static pn_host H;
static pn_setup S;
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

static void test_no_scene(void)
{
    pn_host h2;
    char err[128];
    pn_frame fr;
    REQUIRE(pn_host_open(&h2, 16, 8, 8, 1, err, sizeof(err)) == 0);
    CHECK(pn_render(h2.ctx, &S.camera, &S.light, &OPT, &fr) == PN_E_NO_SCENE);
    CHECK(strlen(pn_last_error(h2.ctx)) > 0);
    pn_host_close(&h2);
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
    CHECK(pn_get_stats(NULL, NULL) == PN_E_INVALID_ARG);
    CHECK(pn_set_parallel_for(NULL, NULL, NULL) == PN_E_INVALID_ARG);
}

int main(void)
{
    char err[256];
    if (pn_setup_load(&S, "spheres", 1, -1, err, sizeof(err)) != 0 ||
        pn_host_open(&H, S.mesh.triangle_count, 64, 64, 1, err, sizeof(err)) != 0) {
        fprintf(stderr, "setup: %s\n", err);
        return 1;
    }
    pn_frame_options_default(&OPT);
    OPT.width = 64;
    OPT.height = 64;
    OPT.k = 4;
    OPT.eps = S.eps;
    RUN(test_scene_input);
    RUN(test_previous_scene_kept);
    RUN(test_degenerate_counted);
    RUN(test_frame_input);
    RUN(test_no_scene);
    RUN(test_status_strings);
    pn_host_close(&H);
    pn_setup_free(&S);
    return pn_test_summary();
}
