/* pn_test_render.h - one frame's visibility buffer into caller memory, for tests that
 * compare algorithms pixel by pixel; an algorithm's stage times checked against its shadow
 * pass; boxes for small scenes, and the light-space algorithms' exact fallback checked on
 * one. Include after penumbra.h, pn_setup.h, pn_test.h, <stddef.h> and <string.h>. */
#ifndef PN_TEST_RENDER_H
#define PN_TEST_RENDER_H

/* Renders with opt as given except eps (the setup's); copies the visibility buffer and,
 * if not NULL, the image and the stats. 0 on success. */
static inline int render_opt(pn_host *h, const pn_setup *s, const pn_light *light, const pn_frame_options *o,
                             float *vis, uint8_t *rgba, pn_stats *st)
{
    pn_frame_options opt = *o;
    pn_frame fr;
    pn_status rs;
    size_t n = (size_t)opt.width * opt.height;
    opt.eps = s->eps;
    rs = pn_render(h->ctx, &s->camera, light, &opt, &fr);
    if (rs != PN_OK) {
        fprintf(stderr, "render %s: %s\n", s->name, pn_last_error(h->ctx));
        return (int)rs;
    }
    memcpy(vis, fr.visibility, n * sizeof(float));
    if (rgba) memcpy(rgba, fr.rgba, n * 4u);
    if (st) pn_get_stats(h->ctx, st);
    return 0;
}

/* Renders with opt's defaults except size, k, eps (the setup's), algo and GEARS grid;
 * copies the visibility buffer to out and, if st is not NULL, the stats. 0 on success. */
static inline int render_vis(pn_host *h, const pn_setup *s, const pn_light *light, pn_algo algo, uint32_t w, uint32_t hh,
                             uint32_t k, uint32_t grid, float *out, pn_stats *st)
{
    pn_frame_options opt;
    pn_frame_options_default(&opt);
    opt.width = w;
    opt.height = hh;
    opt.k = k;
    opt.algo = algo;
    opt.gears.grid = grid;
    return render_opt(h, s, light, &opt, out, NULL, st);
}

/* A box of half-extents (hx, hy, hz) about (x, y, z), wound outward (flip: inward), as six
 * quads at vertices 4 q0 .. and triangles 2 q0 ..; or a horizontal square (hy = 0) facing up
 * (flip: down), one quad. Returns the quads written. */
static inline uint32_t pn_test_box(float *pos, uint32_t *idx, uint32_t q0, const float *c, const float *hf, int flip)
{
    static const int8_t f[6][4][3] = {{{-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}},     /* +y */
                                      {{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}}, /* -y */
                                      {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}},     /* +x */
                                      {{-1, -1, -1}, {-1, -1, 1}, {-1, 1, 1}, {-1, 1, -1}}, /* -x */
                                      {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},     /* +z */
                                      {{-1, -1, -1}, {-1, 1, -1}, {1, 1, -1}, {1, -1, -1}}}; /* -z */
    static const uint32_t q[6] = {0u, 1u, 2u, 0u, 2u, 3u}, qf[6] = {0u, 2u, 1u, 0u, 3u, 2u};
    uint32_t n = hf[1] > 0.0f ? 6u : 1u, i, j, k;
    for (i = 0; i < n; i++) {
        for (j = 0; j < 4u; j++)
            for (k = 0; k < 3u; k++) pos[12u * (q0 + i) + 3u * j + k] = c[k] + (float)f[i][j][k] * hf[k];
        for (j = 0; j < 6u; j++) idx[6u * (q0 + i) + j] = 4u * (q0 + i) + (flip ? qf[j] : q[j]);
    }
    return n;
}

/* The light-space algorithms' exact fallback (kernels/pn_lview.h, pn_lview_outside): a
 * lamp at y = 1 emitting down, a wall at x = 6 from y = 0.5 to 0.99 and a block at x = 4 to
 * 4.5 just below the lamp's plane, which shadows the wall. Every origin the camera sees lies
 * further off the lamp's axis than PN_LVIEW_TAN_MAX (tan 4, 76 degrees), so no window of the
 * light's view holds any. The frame with options o (PN_ALGO_OCCTEX or PN_ALGO_MCSM; its
 * size and k are set here) must give the reference's bytes at k = 4 on every pixel and count
 * every lit pixel in its stats' outside; the reference's pixels in penumbra (0 < v < 1, the
 * block's on the wall, which a frame that left these origins to the light's view lit) must
 * be there for the check to mean something. */
static inline void pn_test_check_outside(const pn_frame_options *o)
{
    enum { OW = 64, OH = 48 };
    static const float wall[3] = {6.05f, 0.745f, 0.0f}, wh[3] = {0.05f, 0.245f, 1.0f};
    static const float block[3] = {4.25f, 0.9f, 0.0f}, bh[3] = {0.25f, 0.05f, 0.3f};
    static float va[OW * OH], vr[OW * OH];
    float pos[12u * 12u];
    uint32_t idx[12u * 6u], nq, p, shadowed = 0u, outside;
    pn_frame_options opt = *o;
    pn_light light;
    pn_stats st;
    pn_setup s;
    pn_host h;
    char err[256];
    long diff = 0;
    if (pn_setup_load(&s, "square", 1, -1, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading square: %s", err);
        return;
    }
    if (pn_host_open(&h, 24u, OW, OH, 2, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "context: %s", err);
        pn_setup_free(&s);
        return;
    }
    nq = pn_test_box(pos, idx, 0u, wall, wh, 0);
    nq += pn_test_box(pos, idx, nq, block, bh, 0);
    memset(&light, 0, sizeof(light));
    light.center[1] = 1.0f;
    light.u[0] = 0.5f;
    light.v[2] = 0.5f;
    s.camera.eye[0] = 3.0f;
    s.camera.eye[1] = 0.75f;
    s.camera.eye[2] = 0.6f;
    s.camera.target[0] = 6.0f;
    s.camera.target[1] = 0.75f;
    s.camera.target[2] = 0.0f;
    s.camera.up[0] = s.camera.up[2] = 0.0f;
    s.camera.up[1] = 1.0f;
    s.camera.fov_deg = 25.0f;
    s.eps = 1e-4f * 8.0f;
    opt.width = OW;
    opt.height = OH;
    opt.k = 16u;
    if (pn_scene_set(h.ctx, pos, 4u * nq, idx, 2u * nq) != PN_OK || render_opt(&h, &s, &light, &opt, va, NULL, &st) != 0 ||
        render_vis(&h, &s, &light, PN_ALGO_REFERENCE, OW, OH, 4u, 0u, vr, NULL) != 0) {
        CHECK_MSG(0, "a frame failed");
    } else {
        for (p = 0; p < OW * OH; p++) {
            diff += memcmp(va + p, vr + p, sizeof(float)) != 0;
            shadowed += vr[p] > 0.0f && vr[p] < 1.0f;
        }
        outside = o->algo == PN_ALGO_MCSM ? st.mcsm.outside : st.occtex.outside;
        fprintf(stderr, "origins outside the window: %ld pixels differ from the reference at k = 4; %u outside, %u lit, "
                "%u in penumbra\n", diff, outside, st.lit_pixels, shadowed);
        CHECK_MSG(diff == 0, "%ld pixels differ from the reference at k = 4", diff);
        CHECK_MSG(outside > 0u && outside == st.lit_pixels, "outside %u, lit %u", outside, st.lit_pixels);
        CHECK_MSG(shadowed >= 20u, "only %u pixels in the block's penumbra: the scene does not test the fallback",
                  shadowed);
    }
    pn_host_close(&h);
    pn_setup_free(&s);
}

static uint64_t g_pn_test_ticks;
static inline uint64_t pn_test_tick(void *user)
{
    (void)user;
    return ++g_pn_test_ticks;
}

/* An algorithm's three stage times (the uint64_t fields of pn_stats at offsets off[0..2]):
 * a frame on ctx without a clock leaves them 0; with a clock that ticks once a call
 * (installed here, for good) each has taken at least one tick and together they lie inside
 * the shadow pass. *st: the stats of the first frame (no clock). */
static inline void check_stage_times(pn_context *ctx, const pn_camera *cam, const pn_light *light, const pn_frame_options *opt,
                                     const size_t off[3], pn_stats *st)
{
    pn_frame fr;
    pn_stats t;
    uint64_t v[3], w[3];
    int i;
    CHECK_MSG(pn_render(ctx, cam, light, opt, &fr) == PN_OK, "%s", pn_last_error(ctx));
    CHECK(pn_get_stats(ctx, st) == PN_OK);
    REQUIRE(pn_set_clock(ctx, pn_test_tick, NULL) == PN_OK);
    CHECK_MSG(pn_render(ctx, cam, light, opt, &fr) == PN_OK, "%s", pn_last_error(ctx));
    CHECK(pn_get_stats(ctx, &t) == PN_OK);
    for (i = 0; i < 3; i++) {
        memcpy(&v[i], (const char *)st + off[i], sizeof(uint64_t));
        memcpy(&w[i], (const char *)&t + off[i], sizeof(uint64_t));
        CHECK_MSG(v[i] == 0u && w[i] >= 1u, "stage %d: %llu without a clock, %llu ticks with one", i,
                  (unsigned long long)v[i], (unsigned long long)w[i]);
    }
    CHECK_MSG(w[0] + w[1] + w[2] <= t.pass_ns[PN_PASS_SHADOW], "stages %llu + %llu + %llu, shadow pass %llu",
              (unsigned long long)w[0], (unsigned long long)w[1], (unsigned long long)w[2],
              (unsigned long long)t.pass_ns[PN_PASS_SHADOW]);
}

#endif
