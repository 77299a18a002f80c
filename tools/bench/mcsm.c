/* mcsm.c - Monte Carlo shadow maps (Curtis 2009): the thesis' claims against a k = 32
 * reference, the convergence with the rays per pixel, light leaks on closed-box, the cost
 * against the depth-layer resolution and the image size (thesis Tables 4.1-4.4), the
 * issue's goal. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* ---- Monte Carlo shadow maps (Curtis 2009) ---------------------------------------------------- */

/* A configuration: 0 in a field is the library's default (penumbra.h: 3 layers, hierarchical
 * search, 3x3 rays, its blur radius, map 512, adaptive bias). */
typedef struct mc_cfg {
    const char *name;
    uint32_t layers, search, rays, blur, flags, map;
} mc_cfg;

/* The claims table: the default (what --algo mcsm renders) and one change of it per row; the
 * thesis' preferred version is the two-layer row, its other version three layers with
 * linear/binary search. */
#define MC_CFGS 10
#define MC_CFG_LAYERS_ALONE 9 /* its heat map beside the default's */
static const mc_cfg mc_cfgs[MC_CFGS] = {
    {"default (3 layers, hierarchical, 3x3 rays, default blur)", 0u, 0u, 0u, 0u, 0u, 0u},
    {"2 layers, hierarchical", 2u, 0u, 0u, 0u, 0u, 0u},
    {"1 layer, linear", 1u, PN_MC_SEARCH_LINEAR, 0u, 0u, 0u, 0u},
    {"2 layers, linear/binary", 2u, PN_MC_SEARCH_LINEAR, 0u, 0u, 0u, 0u},
    {"3 layers, linear/binary", 3u, PN_MC_SEARCH_LINEAR, 0u, 0u, 0u, 0u},
    {"2x2 rays", 0u, 0u, 2u, 0u, 0u, 0u},
    {"4x4 rays", 0u, 0u, 4u, 0u, 0u, 0u},
    {"blur off (3 layers, hierarchical)", 0u, 0u, 0u, PN_MC_BLUR_OFF, 0u, 0u},
    {"blur radius 2", 0u, 0u, 0u, 2u, 0u, 0u},
    {"stacked texels as the layers say (no exact rays)", 0u, 0u, 0u, 0u, PN_MC_NO_STACKED, 0u},
};
/* The leak table on closed-box (hierarchical search, 3x3 rays, the default blur throughout). */
#define MC_LEAK_CFGS 5
static const mc_cfg mc_leak_cfgs[MC_LEAK_CFGS] = {
    {"1 layer", 1u, 0u, 0u, 0u, 0u, 0u},
    {"2 layers", 2u, 0u, 0u, 0u, 0u, 0u},
    {"3 layers (default)", 3u, 0u, 0u, 0u, 0u, 0u},
    {"2 layers, no bias", 2u, 0u, 0u, 0u, PN_MC_NO_BIAS, 0u},
    {"1 layer, no bias", 1u, 0u, 0u, 0u, PN_MC_NO_BIAS, 0u},
};
#define MC_RAYS_MAX 8 /* mcsm.rays: n x n rays, n in 1 .. 8 (penumbra.h) */
#define MC_GOAL_RMSE 0.05
#define MC_GOAL_SPEED 5.0

static void mc_job(job *j, int a_mc, const pn_frame_options *opt, const mc_cfg *c, int keep)
{
    job_lib(j, a_mc, opt, keep);
    j->opt.mcsm.layers = c->layers;
    j->opt.mcsm.search = c->search;
    j->opt.mcsm.rays = c->rays;
    j->opt.mcsm.blur = c->blur;
    j->opt.mcsm.flags = c->flags;
    j->opt.mcsm.map = c->map;
}

static void mc_stages(char *b, size_t n, const job *j)
{
    char c[4][20];
    fmt_ms(c[0], sizeof(c[0]), j->st.mcsm.ns_layers / 1e6);
    fmt_ms(c[1], sizeof(c[1]), j->st.mcsm.ns_nbuffer / 1e6);
    fmt_ms(c[2], sizeof(c[2]), j->st.mcsm.ns_rays / 1e6);
    fmt_ms(c[3], sizeof(c[3]), j->st.mcsm.ns_blur / 1e6);
    snprintf(b, n, "%s / %s / %s / %s", c[0], c[1], c[2], c[3]);
}

/* A speed cell: "ms (layers / N-buffer / rays / blur)". */
static void mc_cell(char *b, size_t n, const job *j)
{
    char ms[32], st[96];
    if (!j->ok) {
        snprintf(b, n, "n/a (%.200s)", j->err);
        return;
    }
    fmt_ms(ms, sizeof(ms), job_pass(j));
    mc_stages(st, sizeof(st), j);
    snprintf(b, n, "%s (%s)", ms, st);
}

/* Claims: every configuration against the k = 32 reference, with its leaks, over-dark pixels
 * and statistics; its points on the time-vs-error chart. Runs before occ_section so that
 * both sections judge the chart's front on the same points. The frame of PN_ALGO_MCSM does
 * not depend on k (it computes no mask): the frames rendered at the main point's k are its
 * frames at k = 32, compared with both references. */
void mc_claims(const bench_opts *o, report *r, scene_state *ss)
{
    pn_frame_options opt;
    job jobs[MC_CFGS];
    const float *ref;
    int i, a_mc = section_algo(o, PN_ALGO_MCSM);
    size_t n;
    char c[2][96];
    ss->mc_ok = 0;
    if (a_mc < 0) return;
    base_options(o, ss, &opt);
    n = (size_t)opt.width * opt.height;
    ref = ref32(o, ss);
    for (i = 0; i < MC_CFGS; i++) mc_job(&jobs[i], a_mc, &opt, &mc_cfgs[i], 1);
    progress("  %s: MCSM, %d configurations", ss->s.name, MC_CFGS);
    run_jobs(o, ss, jobs, MC_CFGS, &ss->s.light);
    for (i = 0; i < MC_CFGS; i++) {
        const job *j = &jobs[i];
        accuracy acc = compare_vis(j->vis, ref, n);
        if (!j->ok || !acc.ok) {
            sec(r, SEC_MC_CLAIMS, "| %s | %s | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | %s |\n", ss->s.name,
                mc_cfgs[i].name, j->ok ? ss->ref32_err : j->err);
            continue;
        }
        fmt_ms(c[0], sizeof(c[0]), job_pass(j));
        mc_stages(c[1], sizeof(c[1]), j);
        sec(r, SEC_MC_CLAIMS,
            "| %s | %s | %.5f | %.4f | %zu | %zu | %s | %s | %u / %u / %u | %u / %u (%.0f%% / %.0f%%) | %llu | %.1f | %u |\n",
            ss->s.name, mc_cfgs[i].name, acc.rmse, acc.max_err, px_brighter(j->vis, ref, n), px_brighter(ref, j->vis, n),
            c[0], c[1], j->st.mcsm.lit, j->st.mcsm.umbra, j->st.mcsm.penumbra, j->st.mcsm.penumbra_open, j->st.mcsm.penumbra_shut,
            j->st.mcsm.penumbra ? 100.0 * j->st.mcsm.penumbra_open / j->st.mcsm.penumbra : 0.0,
            j->st.mcsm.penumbra ? 100.0 * j->st.mcsm.penumbra_shut / j->st.mcsm.penumbra : 0.0, (unsigned long long)j->st.mcsm.rays,
            j->st.mcsm.rays ? (double)j->st.mcsm.steps / (double)j->st.mcsm.rays : 0.0, j->st.mcsm.capped);
    }
    /* Where the default errs: its error against the k = 32 reference as a heat map. */
    if (jobs[0].ok) error_heat(o, r, SEC_MC_MAPS, ss, "mc_heat", "the default", jobs[0].vis, ref, opt.width, opt.height);
    if (jobs[MC_CFG_LAYERS_ALONE].ok)
        error_heat(o, r, SEC_MC_MAPS, ss, "mc_heat_layers_alone", "the layers alone (PN_MC_NO_STACKED)",
                   jobs[MC_CFG_LAYERS_ALONE].vis, ref, opt.width, opt.height);
    for (i = 0; i < MC_CFGS; i++) chart_point(ss, "MCSM", mc_cfgs[i].name, &jobs[i], 15);
    if (jobs[0].ok && jobs[0].vis && ss->ref_vis) {
        ss->mc_ok = 1;
        ss->mc_ms = job_pass(&jobs[0]);
        ss->mc_rmse = compare_vis(jobs[0].vis, ss->ref_vis, n).rmse;
        ss->mc_st = jobs[0].st;
    }
    for (i = 0; i < MC_CFGS; i++) job_free(&jobs[i]);
}

/* Least-squares slope of log y against log rays over points [0, m) (point i: (i + 1)^2 rays). */
static double loglog_slope(const double *y, int m)
{
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    int i;
    for (i = 0; i < m; i++) {
        double x = log((double)(i + 1) * (i + 1)), ly = log(y[i]);
        sx += x;
        sy += ly;
        sxx += x * x;
        sxy += x * ly;
    }
    return m >= 2 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : NAN;
}

/* Convergence: blur off, default layers and search, n x n rays for n = 1 .. 8, against the
 * k = 32 reference; one frame each (only the error is reported). */
static void mc_convergence(const bench_opts *o, report *r, scene_state *ss, int a_mc)
{
    pn_frame_options opt;
    const float *ref = ref32(o, ss);
    double rmse[MC_RAYS_MAX], ex[MC_RAYS_MAX], lo = NAN;
    char data[2048], row[1024];
    int dl = 0, len, i, fl = -1, m = 0, me = 0;
    size_t npx;
    base_options(o, ss, &opt);
    npx = (size_t)opt.width * opt.height;
    progress("  %s: MCSM convergence, 1 .. %d rays per pixel", ss->s.name, MC_RAYS_MAX * MC_RAYS_MAX);
    dl += snprintf(data + dl, sizeof(data) - (size_t)dl,
                   "# mc_convergence %s: n rays rmse (blur off, 3 layers, hierarchical; k = 32 reference)\n", ss->s.name);
    len = snprintf(row, sizeof(row), "| %s |", ss->s.name);
    for (i = 0; i < MC_RAYS_MAX; i++) {
        mc_cfg cfg = {"", 0u, 0u, (uint32_t)(i + 1), PN_MC_BLUR_OFF, 0u, 0u};
        job j;
        accuracy acc;
        mc_job(&j, a_mc, &opt, &cfg, 1);
        job_run(ss, &j, &ss->s.light, 0);
        acc = compare_vis(j.vis, ref, npx);
        rmse[i] = j.ok && acc.ok ? acc.rmse : NAN;
        if (!j.ok) progress("    %d rays: %s", (i + 1) * (i + 1), j.err);
        job_free(&j);
        if (rmse[i] == rmse[i]) {
            len += snprintf(row + len, sizeof(row) - (size_t)len, " %.5f |", rmse[i]);
            dl += snprintf(data + dl, sizeof(data) - (size_t)dl, "%d %d %.6g\n", i + 1, (i + 1) * (i + 1), rmse[i]);
            if (!(lo <= rmse[i])) {
                lo = rmse[i];
                fl = i;
            }
            if (rmse[i] > r->mc_conv_top) r->mc_conv_top = rmse[i];
        } else {
            len += snprintf(row + len, sizeof(row) - (size_t)len, " n/a |");
        }
    }
    /* Before the floor: from one ray on, the points still over twice the floor (there the
     * floor flattens the local slope by at most a quarter). The excess over the floor,
     * sqrt(RMSE^2 - floor^2) (independent errors add in quadrature), from one ray on while
     * the RMSE is over 1.1 floors: the sampling error's own slope where the floor hides it. */
    while (fl >= 0 && m < MC_RAYS_MAX && rmse[m] == rmse[m] && rmse[m] > 2.0 * lo) m++;
    for (; fl >= 0 && me < MC_RAYS_MAX && rmse[me] == rmse[me] && rmse[me] > 1.1 * lo; me++)
        ex[me] = sqrt(rmse[me] * rmse[me] - lo * lo);
    if (m >= 2)
        len += snprintf(row + len, sizeof(row) - (size_t)len, " %.2f (1 .. %d rays) |", loglog_slope(rmse, m), m * m);
    else if (fl >= 0)
        len += snprintf(row + len, sizeof(row) - (size_t)len, " n/a (under twice the floor from %d rays) |", (m + 1) * (m + 1));
    else len += snprintf(row + len, sizeof(row) - (size_t)len, " n/a |");
    if (me >= 2)
        len += snprintf(row + len, sizeof(row) - (size_t)len, " %.2f (1 .. %d rays) |", loglog_slope(ex, me), me * me);
    else len += snprintf(row + len, sizeof(row) - (size_t)len, " n/a |");
    if (fl >= 0) snprintf(row + len, sizeof(row) - (size_t)len, " %.5f (%d rays) |", lo, (fl + 1) * (fl + 1));
    else snprintf(row + len, sizeof(row) - (size_t)len, " n/a |");
    sec(r, SEC_MC_CONV, "%s\n", row);
    write_data(o, "mc_convergence", ss->s.name, data);
    if (fl >= 0 && r->mc_conv_scenes < MAX_SCENES)
        snprintf(r->mc_conv_names[r->mc_conv_scenes++], sizeof(r->mc_conv_names[0]), "%s", ss->s.name);
}

/* The speed tables (thesis Tables 4.1-4.4 as analogues) and the goal's row. */
void mcsm_section(const bench_opts *o, report *r, scene_state *ss)
{
    static const uint32_t search[2] = {PN_MC_SEARCH_HIER, PN_MC_SEARCH_LINEAR};
    static const char *search_name[2] = {"hierarchical", "linear/binary"};
    pn_frame_options opt;
    job jobs[2 * 2 * 6];
    int a_mc = section_algo(o, PN_ALGO_MCSM), fastest, s, n, v, nj, i, front;
    char cell[256], row[2048], c[6][64], fr[512];
    double ratio;
    if (a_mc < 0) return;
    base_options(o, ss, &opt);
    mc_convergence(o, r, ss, a_mc);

    /* (a) depth-layer resolution x rays x search at the main point's size. */
    nj = 0;
    for (s = 0; s < 2; s++)
        for (n = 2; n <= 3; n++)
            for (v = 0; v < (int)o->n_mc_map; v++) {
                mc_cfg cfg = {"", 0u, search[s], (uint32_t)n, 0u, 0u, o->mc_map[v]};
                mc_job(&jobs[nj++], a_mc, &opt, &cfg, 0);
            }
    progress("  %s: MCSM, %d map resolutions x rays x search", ss->s.name, (int)o->n_mc_map);
    run_jobs(o, ss, jobs, nj, &ss->s.light);
    for (s = 0, i = 0; s < 2; s++)
        for (n = 2; n <= 3; n++) {
            int rl = snprintf(row, sizeof(row), "| %s | %s | %dx%d |", s == 0 && n == 2 ? ss->s.name : "", search_name[s], n, n);
            for (v = 0; v < (int)o->n_mc_map; v++, i++) {
                mc_cell(cell, sizeof(cell), &jobs[i]);
                rl += snprintf(row + rl, sizeof(row) - (size_t)rl, " %s |", cell);
            }
            sec(r, SEC_MC_MAP, "%s\n", row);
        }
    for (i = 0; i < nj; i++) job_free(&jobs[i]);

    /* (b) image size x rays, hierarchical, at the default map (512). */
    nj = 0;
    for (n = 2; n <= 3; n++)
        for (v = 0; v < (int)o->n_mc_screen; v++) {
            mc_cfg cfg = {"", 0u, PN_MC_SEARCH_HIER, (uint32_t)n, 0u, 0u, 0u};
            pn_frame_options os = opt;
            os.width = os.height = o->mc_screen[v];
            mc_job(&jobs[nj++], a_mc, &os, &cfg, 0);
        }
    progress("  %s: MCSM, %d image sizes x rays", ss->s.name, (int)o->n_mc_screen);
    run_jobs(o, ss, jobs, nj, &ss->s.light);
    for (n = 2, i = 0; n <= 3; n++) {
        int rl = snprintf(row, sizeof(row), "| %s | hierarchical | %dx%d |", n == 2 ? ss->s.name : "", n, n);
        for (v = 0; v < (int)o->n_mc_screen; v++, i++) {
            mc_cell(cell, sizeof(cell), &jobs[i]);
            rl += snprintf(row + rl, sizeof(row) - (size_t)rl, " %s |", cell);
        }
        sec(r, SEC_MC_SCREEN, "%s\n", row);
    }
    for (i = 0; i < nj; i++) job_free(&jobs[i]);

    /* The goal: the default (its claims run) against the fastest exact algorithm at the main
     * point, its RMSE against the main point's reference, and the chart's front. */
    fastest = fastest_exact(ss->pt_ms);
    if (!ss->mc_ok) {
        sec(r, SEC_MC_GOAL, "| %s | %u | %ux%u | %s | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a |\n", ss->s.name,
            ss->s.mesh.triangle_count, opt.width, opt.height, fastest >= 0 ? algos[fastest].name : "none");
        return;
    }
    ratio = fastest >= 0 ? ss->pt_ms[fastest] / ss->mc_ms : NAN;
    front = chart_front(ss, a_mc, "MCSM", ss->mc_ms, ss->mc_rmse, fr, sizeof(fr));
    fmt_ms(c[0], sizeof(c[0]), fastest >= 0 ? ss->pt_ms[fastest] : NAN);
    fmt_ms(c[1], sizeof(c[1]), ss->mc_ms);
    {
        job t;
        memset(&t, 0, sizeof(t));
        t.st = ss->mc_st;
        mc_stages(c[2], sizeof(c[2]), &t);
    }
    fmt_ratio(c[3], sizeof(c[3]), fastest >= 0 ? ss->pt_ms[fastest] : NAN, ss->mc_ms);
    sec(r, SEC_MC_GOAL, "| %s | %u | %ux%u | %s | %s | %s | %s | %s | %.4f | %s | %s | %s | %s |\n", ss->s.name,
        ss->s.mesh.triangle_count, opt.width, opt.height, fastest >= 0 ? algos[fastest].name : "none", c[0], c[1], c[2],
        c[3], ss->mc_rmse, fr, ss->mc_rmse <= MC_GOAL_RMSE ? "yes" : "no",
        ratio >= MC_GOAL_SPEED ? "yes" : ratio == ratio ? "no" : "n/a", front ? "yes" : "no");
    if (!ss->s.builtin) {
        r->mc_goal_n++;
        r->mc_goal[0] += ss->mc_rmse <= MC_GOAL_RMSE;
        r->mc_goal[1] += ratio >= MC_GOAL_SPEED;
        r->mc_goal[2] += front;
    }
}

/* Light leaks on the built-in closed-box (a closed thick box, one hole under the light; not
 * one of pn_builtin_scene_names(), so it appears in this table only): the MCSM layer
 * configurations, and the occlusion textures' and SRT's defaults, against the k = 32
 * reference at the main point's size. */
void mcsm_leaks(const bench_opts *o, report *r)
{
    scene_state ss;
    pn_frame_options opt;
    job jobs[MC_LEAK_CFGS + 2];
    const char *algo_name[MC_LEAK_CFGS + 2], *cfg_name[MC_LEAK_CFGS + 2];
    const float *ref;
    int a_mc = section_algo(o, PN_ALGO_MCSM), a_occ = section_algo(o, PN_ALGO_OCCTEX), a_srt = section_algo(o, PN_ALGO_SRT);
    int i, nj = 0;
    size_t n;
    char c[32];
    if (a_mc < 0) return;
    progress("[closed-box] MCSM light leaks");
    if (scene_open(o, &ss, "closed-box", 1, &ports[0], o->size) != 0) {
        sec(r, SEC_MC_LEAKS, "| closed-box | MCSM | n/a | n/a | n/a | n/a | n/a | n/a (the scene did not load) |\n");
        scene_close(&ss);
        return;
    }
    base_options(o, &ss, &opt);
    n = (size_t)opt.width * opt.height;
    ref = ref32(o, &ss);
    for (i = 0; i < MC_LEAK_CFGS; i++) {
        algo_name[nj] = algos[a_mc].name;
        cfg_name[nj] = mc_leak_cfgs[i].name;
        mc_job(&jobs[nj++], a_mc, &opt, &mc_leak_cfgs[i], 1);
    }
    if (a_occ >= 0) {
        algo_name[nj] = algos[a_occ].name;
        cfg_name[nj] = "default";
        job_lib(&jobs[nj++], a_occ, &opt, 1);
    }
    if (a_srt >= 0) {
        algo_name[nj] = algos[a_srt].name;
        cfg_name[nj] = "default";
        job_lib(&jobs[nj++], a_srt, &opt, 1);
    }
    run_jobs(o, &ss, jobs, nj, &ss.s.light);
    for (i = 0; i < nj; i++) {
        const job *j = &jobs[i];
        accuracy acc = compare_vis(j->vis, ref, n);
        if (!j->ok || !acc.ok) {
            sec(r, SEC_MC_LEAKS, "| closed-box | %s | %s | n/a | n/a | n/a | n/a | n/a (%s) |\n", algo_name[i], cfg_name[i],
                j->ok ? ss.ref32_err : j->err);
            continue;
        }
        fmt_ms(c, sizeof(c), job_pass(j));
        sec(r, SEC_MC_LEAKS, "| closed-box | %s | %s | %zu | %zu | %.5f | %.4f | %s |\n", algo_name[i], cfg_name[i],
            px_brighter(j->vis, ref, n), px_brighter(ref, j->vis, n), acc.rmse, acc.max_err, c);
    }
    for (i = 0; i < nj; i++) job_free(&jobs[i]);
    scene_close(&ss);
}

/* MCSM's convergence: every scene's RMSE against rays per pixel, log-log, with the slopes of
 * plain (-1/2) and stratified (-3/4) sampling through the largest error for scale. */
void plot_mc_convergence(report *r)
{
    int i;
    if (r->mc_conv_scenes == 0) return;
    fprintf(r->plots,
            "\n# MCSM convergence\nset terminal pngcairo noenhanced size 900,560 font 'sans,10'\n"
            "set output 'mc_convergence.png'\nset title 'MCSM: RMSE against rays per pixel (blur off, k = 32 "
            "reference)'\nset xlabel 'rays per pixel (log scale)'\nset ylabel 'RMSE (log scale)'\nset logscale xy\n"
            "set xrange [0.8:80]\nset grid\nset key outside right top\nplot ");
    for (i = 0; i < r->mc_conv_scenes; i++)
        fprintf(r->plots, "'data/mc_convergence_%s.dat' using 2:3 with linespoints lw 2 pt 7 lc %d title '%s', \\\n     ",
                r->mc_conv_names[i], i + 1, r->mc_conv_names[i]);
    fprintf(r->plots,
            "%g * x**-0.5 with lines dt 2 lc rgb 'black' title 'slope -1/2', %g * x**-0.75 with lines dt 3 "
            "lc rgb 'gray40' title 'slope -3/4'\nunset logscale xy\nset xrange [*:*]\nreset\n",
            r->mc_conv_top, r->mc_conv_top);
}

/* The header rows of the MCSM tables. */
void mcsm_headers(report *r, const bench_opts *o)
{
    int v;
    sec(r, SEC_MC_CLAIMS,
        "| scene | configuration | RMSE | max error | leaks (pixels >= 0.25 brighter) | over-dark (>= 0.25 darker) | ms | "
        "layers / N-buffer / rays / blur ms | lit / umbra / penumbra pixels | penumbra: no ray blocked / every ray "
        "blocked (%% of penumbra) | rays searched | steps per ray | capped searches |\n"
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_MC_CONV, "| scene |");
    for (v = 1; v <= MC_RAYS_MAX; v++) sec(r, SEC_MC_CONV, " %d ray%s |", v * v, v > 1 ? "s" : "");
    sec(r, SEC_MC_CONV, " slope before the floor | slope of the excess over the floor | floor |\n| --- |");
    for (v = 0; v < MC_RAYS_MAX + 3; v++) sec(r, SEC_MC_CONV, " ---: |");
    sec(r, SEC_MC_CONV, "\n");
    sec(r, SEC_MC_LEAKS,
        "| scene | algorithm | configuration | leaks (pixels >= 0.25 brighter) | over-dark (>= 0.25 darker) | RMSE | "
        "max error | ms |\n"
        "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_MC_MAP, "| scene | search | rays |");
    for (v = 0; v < (int)o->n_mc_map; v++)
        sec(r, SEC_MC_MAP, " map %ux%u: ms (layers / N-buffer / rays / blur) |", o->mc_map[v], o->mc_map[v]);
    sec(r, SEC_MC_MAP, "\n| --- | --- | --- |");
    for (v = 0; v < (int)o->n_mc_map; v++) sec(r, SEC_MC_MAP, " ---: |");
    sec(r, SEC_MC_MAP, "\n");
    sec(r, SEC_MC_SCREEN, "| scene | search | rays |");
    for (v = 0; v < (int)o->n_mc_screen; v++)
        sec(r, SEC_MC_SCREEN, " %ux%u: ms (layers / N-buffer / rays / blur) |", o->mc_screen[v], o->mc_screen[v]);
    sec(r, SEC_MC_SCREEN, "\n| --- | --- | --- |");
    for (v = 0; v < (int)o->n_mc_screen; v++) sec(r, SEC_MC_SCREEN, " ---: |");
    sec(r, SEC_MC_SCREEN, "\n");
    sec(r, SEC_MC_GOAL,
        "| scene | triangles | size | fastest exact | its ms | MCSM ms | layers / N-buffer / rays / blur ms | "
        "MCSM vs fastest exact | RMSE (k = %u) | on the chart's front | RMSE <= %.2f | >= %.0fx the fastest exact | "
        "on the front |\n"
        "| --- | ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | --- | --- | --- | --- |\n",
        o->k, MC_GOAL_RMSE, MC_GOAL_SPEED);
}

static const bench_note mc_notes[] = {
    {SEC_MC_CLAIMS, "## Monte Carlo shadow maps (Curtis 2009): the thesis' claims",
     "Every configuration against a k = 32 reference at the main point's size (area light): the default (what "
     "`--algo mcsm` renders: near and far depth layers of 512x512 texels seen from behind the light and the eye's "
     "depth as the third, hierarchical search through their N-buffer, 3x3 jittered rays per pixel, the depth-aware blur at its default radius "
     "(`mcsm.blur` = 0, penumbra.h)) and one change of "
     "it per row; three layers with linear/binary search (texel-spaced steps, bisection on a transition) is the "
     "thesis' other version. ms: the shadow pass's median; the stages are the last repetition's (layers: window and "
     "rasterization of the occluders; N-buffer: its levels; rays: classification and search; blur). Leaks: pixels "
     "at least 0.25 brighter than the reference; over-dark: at least 0.25 darker (the over-extended umbrae of the "
     "thesis' §4.1). Lit / umbra / penumbra: lit pixels the classification (eq. 3.3) called fully lit, umbra, or "
     "potentially in penumbra (only these trace rays); of the penumbra pixels, those whose rays no layer blocked "
     "(the classification could have called them lit: the thesis' claim that two iterations give \"a tight bound "
     "around penumbrae\" (§3.6) is what this measures) and those whose every ray in front of the surface was "
     "blocked; rays searched: rays traced through the layers after the early-outs; steps per ray: N-buffer boxes or linear samples per searched ray; capped: searches stopped by the "
     "step cap, taken as unblocked (each a possible leak). The frame does not depend on k: the same frames against "
     "the main point's reference are MCSM's points on the time-vs-error chart."},
    {SEC_MC_CONV, "### MCSM: convergence with the rays per pixel",
     "RMSE against the k = 32 reference with the blur off (three layers, hierarchical search), n x n jittered rays "
     "per pixel for n = 1 .. 8; one frame each. Floor: the smallest RMSE (normally at 64 rays), the error more rays "
     "do not remove (the layers' model of the occluders, their resolution, the bias). Slope: the least-squares "
     "slope of log RMSE against log rays over the points before the floor (from one ray on, those with an RMSE more "
     "than twice the floor, where the floor flattens the slope by at most a quarter). Where the floor comes early "
     "that leaves fewer than two points; the excess over the floor, sqrt(RMSE^2 - floor^2) (independent errors add "
     "in quadrature), fitted from one ray on while the RMSE is over 1.1 floors, is the sampling error's own slope "
     "there. A slope of -1/2 is plain Monte Carlo: independent samples, whose error falls as one "
     "over the square root of their number. These rays are jittered, one in each cell of an n x n grid on the "
     "light, and stratified samples can fall faster: down to -3/4 where a shadow edge crosses the light (the "
     "pixel's variance then falls as rays^-3/2), faster still where the visibility varies smoothly over it."},
    {SEC_MC_LEAKS, "### MCSM: light leaks on closed-box",
     "The built-in `closed-box` (a closed box with walls 0.25 thick, one 0.5 x 0.5 hole in its top under the "
     "light, the eye inside; in this table only) at the main point's size against its k = 32 reference: inside, "
     "everything is dark but what the hole lets through, so a pixel at least 0.25 brighter than the reference is a "
     "leak. The MCSM rows use the hierarchical search, 3x3 rays and the default blur; no bias: without the adaptive bias of "
     "eq. 3.2. The occlusion textures' and SRT's defaults on the same frame for comparison."},
    {SEC_MC_MAP, "### MCSM: cost against the depth-layer resolution (thesis Tables 4.1 and 4.2)",
     "Shadow pass ms (median) at the main point's size with the default blur, per search and rays per pixel, and the stages "
     "of the last repetition. The thesis measured frames per second on a GPU at 1024x768 (hierarchical 3x3: 37, 34, "
     "21 fps on the dragon at 256, 512, 1024; linear/binary 3x3: 12, 11, 10): hierarchical search faster than "
     "linear/binary at every resolution and more sensitive to it, the N-buffer's construction \"likely the largest "
     "component\" of that sensitivity."},
    {SEC_MC_SCREEN, "### MCSM: cost against the image size (thesis Tables 4.3 and 4.4)",
     "Shadow pass ms (median), hierarchical search, 512x512 layers, the default blur, square images; the stages of the last "
     "repetition. The thesis: \"the screen resolution directly affects the number of rays that must be traced\", "
     "so the rays and blur stages should grow with the pixels, the layers and N-buffer not."},
    {SEC_MC_MAPS, "### MCSM: where the default errs", HEAT_NOTE},
    {SEC_MC_GOAL, "### MCSM: the issue's goal",
     "The default (its run of the claims table) against the fastest exact algorithm of the main point (of reference, "
     "GEARS and raytrace), its RMSE against the main point's reference, and the chart's front judged as for the "
     "occlusion textures (no point of the time-vs-error chart but MCSM's own configurations is both faster and "
     "more accurate; otherwise the points that are). The issue's goal: with 3x3 rays and three hierarchical layers, "
     "an RMSE of at most 0.05 against the reference and at least 5x faster than the fastest exact algorithm on "
     "every shared scene, and on the chart's front on at least half of the shared scenes."},
};

/* The MCSM tables with their headings and notes (print_report), the convergence plot, what
 * the map table left out and the goal over the shared scenes. */
void mcsm_print(const report *r, const bench_opts *o, FILE *out)
{
    int i;
    for (i = 0; i < (int)(sizeof(mc_notes) / sizeof(mc_notes[0])); i++) {
        int sw = mc_notes[i].sec;
        print_table(out, r, sw, mc_notes[i].heading, mc_notes[i].note);
        if (sw == SEC_MC_CONV && r->mc_conv_scenes)
            fprintf(out, "![MCSM: RMSE against rays per pixel](mc_convergence.png)\n\n");
        if (sw == SEC_MC_MAP && o->mc_map_cut && section_algo(o, PN_ALGO_MCSM) >= 0)
            fprintf(out, "Larger maps (the thesis' 1024; 2048) need a build with PN_MCSM_MAP_MAX raised "
                         "(include/penumbra/config.h; pn_arena_size refuses them in this build, whose largest here is "
                         "%u; the N-buffer takes 132 MiB at 1024).\n\n",
                    o->mc_map_max);
        if (sw == SEC_MC_GOAL && r->mc_goal_n)
            fprintf(out, "Over the %d shared scene%s of this run: RMSE at most %.2f on %d, at least %.0fx on %d (the "
                         "goal: all); on the front on %d (the goal: at least %d).\n\n",
                    r->mc_goal_n, r->mc_goal_n > 1 ? "s" : "", MC_GOAL_RMSE, r->mc_goal[0], MC_GOAL_SPEED,
                    r->mc_goal[1], r->mc_goal[2], (r->mc_goal_n + 1) / 2);
    }
}
