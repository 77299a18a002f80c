/* pn_passes_mcsm.h - the Monte Carlo shadow maps' passes:
 * their per-work-item entries and their part of
 * the pass list (PN_PASSES_*), composed by pn_passes.h, which includes this file after
 * the kernels it calls; see there for the entry signature and the list's columns. */
#ifndef PN_PASSES_MCSM_H
#define PN_PASSES_MCSM_H

/* ---- Monte Carlo shadow maps (pn_mcsm.h; the frame is src/pn_mcsm.c) ------------------------ */

#if PN_ENABLE_MCSM
/* Texel row of the layers (N-buffer level 0): emptied. */
PN_KFN void pn_e_mc_clear(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_mc_clear_row(&K->lview, y, PN_POOL(float, mc_nb));
}

/* Group of triangles: the layers' rows pass; a small occluder's fragments go straight into
 * the layers. */
PN_KFN void pn_e_mc_rows(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t g)
{
    pn_mc_rows(&K->lview, &K->mc, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags), K->tri_count, g,
               PN_POOL(uint32_t, rows), PN_POOL(float, mc_nb));
}

/* Band of texel rows: the near and far layers (N-buffer level 0). */
PN_KFN void pn_e_mc_band(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t band)
{
    pn_mc_band(&K->lview, &K->mc, PN_POOL(const float, tris), PN_POOL(const uint8_t, flags),
               PN_POOL(const uint32_t, rows), PN_POOL(const uint32_t, chunks), PN_POOL(const uint32_t, rindex),
               K->raster_tris, band, PN_POOL(float, mc_nb));
}

/* Row of N-buffer level K->mc.level. */
PN_KFN void pn_e_mc_nbuf(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_nb_mm_lay ly;
    (void)pn_nb_mm_lay_init(&K->mc, &ly);
    pn_nb_mm_row(&ly, K->mc.level, y, PN_POOL(float, mc_nb));
}

/* Pixel row y: each pixel's rays through the layers, its visibility and class; the row's
 * counters added once. Rows, not pixels, as for the blur: a pixel item made two to four
 * atomic adds and divided its index by the width, where most pixels (lit ones) do little
 * else than one or two region lookups. The row goes in runs of PN_MC_RUN pixels
 * (pn_mc_run: their origins once, and one lookup that may find the whole run lit). A pixel
 * whose origin no window holds is marked PN_MC_VIS_OUTSIDE for the next pass. */
PN_KFN void pn_e_mc_pixel(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t W = K->view.width, x0, i, k, n[PN_MC_WORDS] = {0u, 0u, 0u, 0u, 0u, 0u};
    PN_GLOBAL uint32_t *words = PN_POOL(uint32_t, mc_words) + (size_t)y * PN_MC_ROW_WORDS;
    pn_mc_ctx m;
    pn_mc_px px[PN_MC_RUN];
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_mc_ctx_init(&m, &K->view, &K->lview, &K->light, K->lview_ha, K->lview_hb, &K->mc, PN_POOL(const float, mc_nb),
                   PN_POOL(const float, depth), PN_POOL(const uint8_t, flags));
    for (x0 = 0; x0 < W; x0 += PN_MC_RUN) {
        uint32_t count = pn_kminu(PN_MC_RUN, W - x0);
        size_t pix0 = (size_t)y * W + x0;
        int run_lit = pn_mc_run(&m, &S, pix0, count, px);
        for (i = 0; i < count; i++) {
            uint32_t cls, rays;
            if (px[i].kind == PN_MC_PX_LIT) {
                /* pn_mc_pixel's answer for most pixels, without its set-up */
                PN_POOL(float, vis)[pix0 + i] = 1.0f;
                c.lit++;
                n[PN_MC_CLASS_LIT - 1u]++;
                continue;
            }
            if (px[i].kind == PN_MC_PX_OUTSIDE) { /* for pn_e_mc_outside */
                PN_POOL(float, vis)[pix0 + i] = PN_MC_VIS_OUTSIDE;
                c.lit++;
                continue;
            }
            if (px[i].kind != PN_MC_PX_SURFACE) {
                PN_POOL(float, vis)[pix0 + i] = px[i].kind == PN_MC_PX_NONE ? 1.0f : 0.0f;
                continue;
            }
            PN_POOL(float, vis)[pix0 + i] = pn_mc_pixel(&m, x0 + i, y, px + i, run_lit, &cls, &rays);
            c.lit++;
            c.candidates += rays;
            if (cls != PN_MC_CLASS_NONE) n[cls - 1u]++;
        }
    }
    c.nodes = m.steps;
    n[PN_MC_WORD_CAPPED] = m.capped;
    pn_counters_add(&PN_POOL(pn_row_counters, counters)[y].c, &c);
    for (k = 0; k < PN_MC_WORDS; k++)
        if (n[k]) pn_katomic_add(words + k, n[k]);
}

/* A stacked pixel's visibility (PN_MC_VIS_STACKED: the layers blocked one of its rays in a
 * texel holding more than one solid along the light's ray, pn_mc_band): each of its n x n
 * jittered rays (pn_mc_sample, the pixel pass's samples; one to the centre for a point
 * light) to the sample of the light's k x k grid nearest it, decided exactly: behind the
 * surface's own plane (the horizon), or blocked by a triangle (the per-sample ray tracer's
 * walk, pn_raytrace.h). The fraction open, as the rays' own answer is. Only the walk's lost
 * stack entries are counted (none: the tree's depth is bounded). */
PN_KFN float pn_mc_exact_rays(pn_v3 P, pn_v3 nrm, uint32_t own, uint32_t x, uint32_t y, PN_CONST float *tris,
                              PN_CONST pn_kbvh4 *wnodes, PN_CONST uint32_t *tri_index, const pn_klight *L,
                              const pn_kmc *mc, pn_shadow_counters *cnt)
{
    pn_shadow_counters cw = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    uint32_t n = L->is_point ? 1u : mc->rays, k = L->k, i, j, open = 0u;
    pn_horizon H;
    pn_ray_origin X;
    pn_v3 O;
    if (!pn_shadow_origin(P, nrm, L, &O)) return 0.0f;
    pn_horizon_of(P, nrm, own, tris, L, &H);
    pn_tri_block_origin(O, L, wnodes, &X);
    pn_ray_chain(&X, wnodes);
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            float a, b;
            int32_t si, sj;
            pn_ray R;
            pn_ray_walk W;
            pn_mc_sample(x, y, i, j, n, mc->seed, &a, &b);
            si = pn_kfloor_clamp((a + 1.0f) * 0.5f * (float)k, 0, (int32_t)k - 1);
            sj = pn_kfloor_clamp((b + 1.0f) * 0.5f * (float)k, 0, (int32_t)k - 1);
            if (pn_horizon_at(&H, L, pn_sample_coord(si, k), pn_sample_coord(sj, k))) continue;
            pn_ray_make(&X, L, si, sj, &R);
            pn_ray_walk_begin(&W, &X, &R, wnodes);
            open += pn_ray_walk_next(&W, &R, own, tris, wnodes, tri_index, L, &cw) == PN_RAY_NONE;
        }
    cnt->overflow += cw.overflow;
    return (float)open / (float)(n * n);
}

/* Row y: each pixel the pixel pass marked PN_MC_VIS_OUTSIDE (its origin no window holds, so
 * the layers hold none of its occluders, or its surface the light centre grazes:
 * PN_MC_COS_MIN) takes the exact fallback, counted as exact, and each it marked
 * PN_MC_VIS_STACKED its rays traced exactly (pn_mc_exact_rays); before the blur. A pass of
 * its own: within the pixel pass's frame the reference's stack went over the library's
 * budget (check_callgraph). */
PN_KFN void pn_e_mc_outside(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_shadow_counters c = {0u, 0u, 0u, 0u, 0u, 0u, 0u};
    size_t row = (size_t)y * K->view.width, pix = row, end = pix + K->view.width;
    pn_ksurf S = pn_surf_of(A, P, K);
    for (; pix < end; pix++) {
        float v = PN_POOL(const float, vis)[pix];
        uint32_t id = PN_POOL(const uint32_t, tri_id)[pix];
        pn_v3 Ps, ns;
        if (!(v == PN_MC_VIS_OUTSIDE) && !(v == PN_MC_VIS_STACKED)) continue;
        pn_surf_at(&S, pix, &Ps, &ns);
        if (v == PN_MC_VIS_STACKED)
            v = pn_mc_exact_rays(Ps, ns, id, (uint32_t)(pix - row), y, PN_POOL(const float, tris),
                                 PN_POOL(const pn_kbvh4, wnodes), PN_POOL(const uint32_t, index), &K->light, &K->mc, &c);
        else
            v = pn_reference_fallback(Ps, ns, id, PN_POOL(const float, tris), PN_POOL(const pn_kbvh4, wnodes),
                                      PN_POOL(const uint32_t, index), &K->light, &c);
        PN_POOL(float, vis)[pix] = v;
    }
    if (c.exact || c.overflow) pn_counters_add(&PN_POOL(pn_row_counters, counters)[y].c, &c);
}

/* Row: the blur across (visibility into the other buffer), then down (back). Rows, not
 * pixels: a pixel item's division of its index by the width cost about as much as its blur
 * (spot, 512x512, 2 threads: 3.3 -> 2.1 ms for both directions). */
PN_KFN void pn_e_mc_blur_h(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_mc_blur_row(&K->mc, K->view.width, K->view.height, y, 0u, &S, PN_POOL(const float, vis), PN_POOL(float, mc_tmp));
}
PN_KFN void pn_e_mc_blur_v(PN_GLOBAL uint8_t *A, const pn_kpools *P, const pn_kparams *K, uint32_t y)
{
    pn_ksurf S = pn_surf_of(A, P, K);
    pn_mc_blur_row(&K->mc, K->view.width, K->view.height, y, 1u, &S, PN_POOL(const float, mc_tmp), PN_POOL(float, vis));
}
#endif

/* Their part of the list. */
#if PN_ENABLE_MCSM
#define PN_PASSES_MCSM(X)                                 \
    X(MC_CLEAR, mc_clear, 4, 8)                           \
    X(MC_ROWS, mc_rows, 64, 512)                         \
    X(MC_BAND, mc_band, 1, 1)                             \
    X(MC_NBUF, mc_nbuf, 4, 8)                             \
    X(MC_PIXEL, mc_pixel, 4, 2)                           \
    X(MC_OUTSIDE, mc_outside, 4, 8)                       \
    X(MC_BLUR_H, mc_blur_h, 4, 8)                         \
    X(MC_BLUR_V, mc_blur_v, 4, 8)
#else
#define PN_PASSES_MCSM(X)
#endif

#endif
