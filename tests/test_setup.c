/* test_setup.c - the tools' set-up beside the core tests (issue 46):
 *
 *   scenes       the core tests' scenes (tests/pn_test_scene.h, pn_test_scene_load, on the
 *                pn_scenes library alone) are what the tools' set-up loads for every
 *                built-in (pn_setup_load): the same vertices and triangles to the byte,
 *                receiver range, bounding box, view, light, diagonal and eps
 *   upload       pn_setup_upload: NULL arguments; the scene, then its receiver range (the
 *                reference's bytes as with pn_scene_set alone); the range's status when only
 *                it fails (the scene set by then), pn_scene_set's when the scene fails
 *                (moved here from test_validation, which links no tools) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"
#include "pn_test_scene.h"

static void test_scenes_match(void)
{
    const char *const *names = pn_builtin_scene_names();
    int i;
    for (i = 0; names[i] != NULL; i++) {
        const char *name = names[i];
        pn_setup s;
        pn_test_scene t;
        char err[256];
        REQUIRE(pn_setup_load(&s, name, 1, -1, err, sizeof(err)) == 0);
        REQUIRE(pn_test_scene_load(&t, name) == 0);
        CHECK_MSG(t.mesh.vertex_count == s.mesh.vertex_count && t.mesh.triangle_count == s.mesh.triangle_count,
                  "%s: %u vertices, %u triangles; the tools' %u, %u", name, t.mesh.vertex_count, t.mesh.triangle_count,
                  s.mesh.vertex_count, s.mesh.triangle_count);
        if (t.mesh.vertex_count == s.mesh.vertex_count && t.mesh.triangle_count == s.mesh.triangle_count) {
            CHECK_MSG(memcmp(t.mesh.positions, s.mesh.positions, (size_t)s.mesh.vertex_count * 3u * sizeof(float)) == 0,
                      "%s: other vertex positions than the tools'", name);
            CHECK_MSG(memcmp(t.mesh.indices, s.mesh.indices, (size_t)s.mesh.triangle_count * 3u * sizeof(uint32_t)) == 0,
                      "%s: other triangles than the tools'", name);
        }
        CHECK_MSG(t.mesh.receiver_first == s.mesh.receiver_first && t.mesh.receiver_count == s.mesh.receiver_count,
                  "%s: receivers %u+%u, the tools' %u+%u", name, t.mesh.receiver_first, t.mesh.receiver_count,
                  s.mesh.receiver_first, s.mesh.receiver_count);
        CHECK_MSG(memcmp(t.mesh.bbox_min, s.mesh.bbox_min, sizeof(t.mesh.bbox_min)) == 0 &&
                      memcmp(t.mesh.bbox_max, s.mesh.bbox_max, sizeof(t.mesh.bbox_max)) == 0,
                  "%s: bounding box", name);
        CHECK_MSG(memcmp(&t.camera, &s.camera, sizeof(t.camera)) == 0, "%s: camera", name);
        CHECK_MSG(memcmp(&t.light, &s.light, sizeof(t.light)) == 0, "%s: light", name);
        CHECK_MSG(t.diag == s.diag && t.eps == s.eps, "%s: diagonal %.9g eps %.9g, the tools' %.9g, %.9g", name,
                  (double)t.diag, (double)t.eps, (double)s.diag, (double)s.eps);
        CHECK(s.ground == 0 && strcmp(t.name, s.name) == 0);
        pn_test_scene_free(&t);
        pn_setup_free(&s);
    }
}

static int reference_frame(pn_context *ctx, const pn_setup *s, float *vis)
{
    pn_frame_options o;
    pn_frame fr;
    pn_frame_options_default(&o);
    o.width = 64;
    o.height = 64;
    o.k = 4;
    o.eps = s->eps;
    if (pn_render(ctx, &s->camera, &s->light, &o, &fr) != PN_OK) {
        fprintf(stderr, "render: %s\n", pn_last_error(ctx));
        return 0;
    }
    memcpy(vis, fr.visibility, sizeof(float) * 64u * 64u);
    return 1;
}

static void test_upload(void)
{
    static float before[64 * 64], after[64 * 64];
    pn_setup sq, bad;
    pn_host h;
    pn_stats st;
    char err[256];
    uint32_t n;
    REQUIRE(pn_setup_load(&sq, "square", 1, -1, err, sizeof(err)) == 0);
    n = sq.mesh.triangle_count;
    CHECK(n == 4u && sq.mesh.receiver_first == 2u && sq.mesh.receiver_count == 2u);
    REQUIRE(pn_host_open(&h, n, 64, 64, 1, err, sizeof(err)) == 0);
    CHECK(pn_setup_upload(NULL, &sq) == PN_E_INVALID_ARG);
    CHECK(pn_setup_upload(h.ctx, NULL) == PN_E_INVALID_ARG);
    REQUIRE(pn_scene_set(h.ctx, sq.mesh.positions, sq.mesh.vertex_count, sq.mesh.indices, n) == PN_OK);
    REQUIRE(reference_frame(h.ctx, &sq, before));
    CHECK(pn_setup_upload(h.ctx, &sq) == PN_OK);
    CHECK(pn_get_stats(h.ctx, &st) == PN_OK && st.triangles == n);
    if (reference_frame(h.ctx, &sq, after)) CHECK(memcmp(before, after, sizeof(before)) == 0);
    bad = sq;
    bad.mesh.receiver_first = 3u;
    bad.mesh.receiver_count = 2u;
    CHECK(pn_setup_upload(h.ctx, &bad) == PN_E_INDEX_RANGE);
    CHECK(strstr(pn_last_error(h.ctx), "pn_scene_set_receivers") != NULL);
    CHECK(pn_get_stats(h.ctx, &st) == PN_OK && st.triangles == n);
    bad.mesh.indices = NULL;
    CHECK(pn_setup_upload(h.ctx, &bad) == PN_E_INVALID_ARG);
    CHECK(strstr(pn_last_error(h.ctx), "pn_scene_set") != NULL);
    CHECK(pn_get_stats(h.ctx, &st) == PN_OK && st.triangles == n);
    pn_host_close(&h);
    pn_setup_free(&sq);
}

int main(void)
{
    RUN(test_scenes_match);
    RUN(test_upload);
    return pn_test_summary();
}
