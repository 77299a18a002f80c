/* pn_test_render.h - one frame's visibility buffer into caller memory, for tests that
 * compare algorithms pixel by pixel. Include after penumbra.h, pn_setup.h and <string.h>. */
#ifndef PN_TEST_RENDER_H
#define PN_TEST_RENDER_H

/* Renders with opt's defaults except size, k, eps (the setup's), algo and GEARS grid;
 * copies the visibility buffer to out and, if st is not NULL, the stats. 0 on success. */
static int render_vis(pn_host *h, const pn_setup *s, const pn_light *light, pn_algo algo, uint32_t w, uint32_t hh,
                      uint32_t k, uint32_t grid, float *out, pn_stats *st)
{
    pn_frame_options opt;
    pn_frame fr;
    pn_status rs;
    pn_frame_options_default(&opt);
    opt.width = w;
    opt.height = hh;
    opt.k = k;
    opt.eps = s->eps;
    opt.algo = algo;
    opt.gears_grid = grid;
    rs = pn_render(h->ctx, &s->camera, light, &opt, &fr);
    if (rs != PN_OK) {
        fprintf(stderr, "render %s: %s\n", s->name, pn_last_error(h->ctx));
        return (int)rs;
    }
    memcpy(out, fr.visibility, (size_t)w * hh * sizeof(float));
    if (st) pn_get_stats(h->ctx, st);
    return 0;
}

#endif
