/* pn_test_render.h - one frame's visibility buffer into caller memory, for tests that
 * compare algorithms pixel by pixel; an algorithm's stage times checked against its shadow
 * pass. Include after penumbra.h, pn_setup.h, pn_test.h, <stddef.h> and <string.h>. */
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
