/* wedges.c - penumbra wedges with overlap blending (Forest et al. 2006): additive against
 * blended per scene, where blending helped (heat maps), the goal on `square`, and
 * time against triangles on cuts of the built-in spheres (the paper's Fig. 12). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* ---- Penumbra wedges with overlap blending (Forest et al. 2006) ------------------------------ */

/* The two ways the objects' occluded areas combine: the default (what --algo wedges renders:
 * the paper's blending, section 3.2) and the classic sum of the penumbra-wedges algorithm
 * (Akenine-Moller and Assarsson 2002), which counts overlapping occluders twice. */
#define WG_MODES 2
static const struct {
    const char *name;
    uint32_t mode;
} wg_modes[WG_MODES] = {
    {"blended (default)", 0u},
    {"additive", PN_WG_MODE_ADDITIVE},
};
#define WG_TOL (1.0 / 255.0) /* one step of an 8-bit image: the "nearly exact" */
#define WG_SPHERE_TRIS 762u  /* the built-in spheres' triangles per sphere (tools/pn_scenes_objects.c) */
#define WG_SPHERES 81u       /* ...and spheres */

static void wg_stages(char *b, size_t n, const pn_stats *st)
{
    char c[3][20];
    fmt_ms(c[0], sizeof(c[0]), st->wedges.ns_silhouettes / 1e6);
    fmt_ms(c[1], sizeof(c[1]), st->wedges.ns_binning / 1e6);
    fmt_ms(c[2], sizeof(c[2]), st->wedges.ns_pixels / 1e6);
    snprintf(b, n, "%s / %s / %s", c[0], c[1], c[2]);
}

/* Where blending helped, as a PNG next to RESULTS.md (heat_png): per pixel d = |additive -
 * ref| - |blended - ref| against the k = 32 reference; green where d > WG_TOL, red where
 * d < -WG_TOL. */
static int wg_heat(const bench_opts *o, const scene_state *ss, const float *blend, const float *add, const float *ref,
                   uint32_t w, uint32_t h)
{
    static const uint8_t green[3] = {0, 1, 0}, red[3] = {1, 0, 0};
    size_t n = (size_t)w * h, i;
    float *d = (float *)malloc(n * sizeof(float));
    int rc;
    if (!d || !blend || !add || !ref) {
        free(d);
        return 1;
    }
    for (i = 0; i < n; i++) d[i] = (float)(fabs((double)add[i] - ref[i]) - fabs((double)blend[i] - ref[i]));
    rc = heat_png(o, ss, "wg_heat", d, ref, w, h, WG_TOL, green, red);
    free(d);
    return rc;
}

/* Claims: both modes at the main point's k, interleaved (their medians, and their points on
 * the time-vs-error chart against the main point's reference); then one frame of each at
 * k = 32 against the k = 32 reference (the horizon term of the frame samples k x k), for the
 * errors, the per-pixel comparison of the modes and the heat map. Runs before occ_section,
 * as mc_claims does, so that every section judges the chart's front on the same points. */
void wg_claims(const bench_opts *o, scene_state *ss)
{
    pn_frame_options opt;
    job jobs[WG_MODES], x[WG_MODES];
    const float *ref;
    int a_wg = section_algo(o, PN_ALGO_WEDGES), m;
    size_t n, i;
    memset(&ss->wg, 0, sizeof(ss->wg));
    if (a_wg < 0) return;
    base_options(o, ss, &opt);
    n = (size_t)opt.width * opt.height;
    for (m = 0; m < WG_MODES; m++) {
        job_lib(&jobs[m], a_wg, &opt, 1);
        jobs[m].opt.wedges.mode = wg_modes[m].mode;
    }
    progress("  %s: wedges, blended and additive", ss->s.name);
    run_jobs(o, ss, jobs, WG_MODES, &ss->s.light);
    for (m = 0; m < WG_MODES; m++) chart_point(ss, "wedges", wg_modes[m].name, &jobs[m], 12);
    ref = ref32(o, ss);
    for (m = 0; m < WG_MODES; m++) {
        job_lib(&x[m], a_wg, &opt, 1);
        x[m].opt.k = 32;
        x[m].opt.wedges.mode = wg_modes[m].mode;
        job_run(ss, &x[m], &ss->s.light, 0);
    }
    for (m = 0; m < WG_MODES && !ss->wg.err[0]; m++)
        if (!jobs[m].ok || !x[m].ok)
            snprintf(ss->wg.err, sizeof(ss->wg.err), "%s: %.200s", wg_modes[m].name, !jobs[m].ok ? jobs[m].err : x[m].err);
    if (!ss->wg.err[0] && !ref) snprintf(ss->wg.err, sizeof(ss->wg.err), "k = 32 reference: %.200s", ss->ref32_err);
    if (!ss->wg.err[0] && (!x[0].vis || !x[1].vis))
        snprintf(ss->wg.err, sizeof(ss->wg.err), "out of memory");
    if (!ss->wg.err[0]) {
        ss->wg.ok = 1;
        ss->wg.st = jobs[0].st;
        for (m = 0; m < WG_MODES; m++) {
            accuracy a32 = compare_vis(x[m].vis, ref, n), a16 = compare_vis(jobs[m].vis, ss->ref_vis, n);
            ss->wg.ms[m] = job_pass(&jobs[m]);
            ss->wg.rmse[m] = a16.ok ? a16.rmse : NAN; /* no main-point reference: not selected */
            ss->wg.rmse32[m] = a32.rmse;
            ss->wg.max32[m] = a32.max_err;
            if (m == 0) ss->wg.mae32 = a32.mae;
        }
        for (i = 0; i < n; i++) {
            double eb = fabs((double)x[0].vis[i] - ref[i]), ea = fabs((double)x[1].vis[i] - ref[i]);
            ss->wg.over += eb > WG_TOL;
            if (x[0].vis[i] == x[1].vis[i]) continue;
            ss->wg.differ++;
            ss->wg.closer += eb < ea;
            ss->wg.farther += eb > ea;
        }
        ss->wg.heat = wg_heat(o, ss, x[0].vis, x[1].vis, ref, opt.width, opt.height) == 0;
    } else {
        progress("    wedges: %s", ss->wg.err);
    }
    for (m = 0; m < WG_MODES; m++) {
        job_free(&jobs[m]);
        job_free(&x[m]);
    }
}

/* The table's row (after mcsm_section: the chart holds every section's points by then), the
 * heat map's link and, on `square`, the check of the goal. */
void wg_section(const bench_opts *o, report *r, scene_state *ss)
{
    int a_wg = section_algo(o, PN_ALGO_WEDGES), fastest;
    double exact_ms;
    char c[6][96], link[192], fr[512];
    const pn_stats *st = &ss->wg.st;
    if (a_wg < 0) return;
    fastest = fastest_exact(ss->pt_ms);
    exact_ms = fastest >= 0 ? ss->pt_ms[fastest] : NAN;
    if (!ss->wg.ok) {
        sec(r, SEC_WG_MODES,
            "| %s | %u | n/a | n/a | n/a | n/a | n/a | n/a | n/a | %s | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | "
            "n/a | n/a | n/a | n/a (%s) |\n",
            ss->s.name, ss->s.mesh.triangle_count, fastest >= 0 ? algos[fastest].name : "none", ss->wg.err);
        return;
    }
    chart_front(ss, a_wg, "wedges", ss->wg.ms[0], ss->wg.rmse[0], fr, sizeof(fr));
    fmt_ms(c[0], sizeof(c[0]), ss->wg.ms[0]);
    wg_stages(c[1], sizeof(c[1]), st);
    fmt_ms(c[2], sizeof(c[2]), ss->wg.ms[1]);
    fmt_ratio(c[3], sizeof(c[3]), ss->wg.ms[0], ss->wg.ms[1]);
    fmt_ms(c[4], sizeof(c[4]), exact_ms);
    fmt_ratio(c[5], sizeof(c[5]), exact_ms, ss->wg.ms[0]);
    if (ss->wg.heat) snprintf(link, sizeof(link), "[map](wg_heat_%s.png)", ss->s.name);
    else snprintf(link, sizeof(link), "n/a");
    sec(r, SEC_WG_MODES,
        "| %s | %u | %u | %u | %llu | %s | %s | %s | %s | %s | %s | %s | %.5f | %.4f | %.5f | %.5f | %.4f | %zu | %zu | "
        "%zu | %s | %s |\n",
        ss->s.name, ss->s.mesh.triangle_count, st->wedges.silhouettes, st->wedges.objects, (unsigned long long)st->wedges.pairs, c[0],
        c[1], c[2], c[3], fastest >= 0 ? algos[fastest].name : "none", c[4], c[5], ss->wg.rmse32[0], ss->wg.max32[0],
        ss->wg.mae32, ss->wg.rmse32[1], ss->wg.max32[1], ss->wg.differ, ss->wg.closer, ss->wg.farther, link, fr);
    if (ss->wg.heat)
        sec(r, SEC_WG_MAPS, "**%s**\n\n![%s: where blending helped (green) and hurt (red)](wg_heat_%s.png)\n\n",
            ss->s.name, ss->s.name, ss->s.name);
    if (ss->s.builtin && strcmp(ss->s.name, "square") == 0) {
        size_t n = (size_t)o->size * o->size;
        sec(r, SEC_WG_GOAL, "| %s | %.6f | %.6f | %s | %.5f | %.4f | %zu (%.3f%%) |\n", ss->s.name, ss->wg.mae32, WG_TOL,
            ss->wg.mae32 < WG_TOL ? "yes" : "no", ss->wg.rmse32[0], ss->wg.max32[0], ss->wg.over,
            100.0 * (double)ss->wg.over / (double)n);
        r->wg_goal_rows++;
    }
}

/* The first n spheres of the built-in `spheres` and its ground (receiver marks kept), the
 * vertices no kept triangle uses left out (the scene's box, and so the wedges' reach above
 * the light plane, is that of what is kept). The layout is pn_sc_build_spheres': sphere s
 * is triangles [762 s, 762 (s + 1)), the 2-triangle ground last; checked, not assumed. */
static int wg_spheres_mesh(const pn_mesh *full, uint32_t n, pn_mesh *out, char *err, size_t err_size)
{
    uint32_t keep = WG_SPHERE_TRIS * n, t, v, nv = 0, *remap;
    memset(out, 0, sizeof(*out));
    if (full->triangle_count != WG_SPHERE_TRIS * WG_SPHERES + 2u || full->receiver_count != 2u ||
        full->receiver_first != WG_SPHERE_TRIS * WG_SPHERES) {
        snprintf(err, err_size, "the spheres mesh is not 81 x 762 triangles and a 2-triangle ground (pn_scenes.c changed)");
        return 1;
    }
    remap = (uint32_t *)malloc((size_t)full->vertex_count * sizeof(uint32_t));
    out->indices = (uint32_t *)malloc(((size_t)keep + 2u) * 3u * sizeof(uint32_t));
    out->positions = (float *)malloc((size_t)full->vertex_count * 3u * sizeof(float));
    if (!remap || !out->indices || !out->positions) {
        free(remap);
        pn_mesh_free(out);
        snprintf(err, err_size, "out of memory");
        return 1;
    }
    out->triangle_count = keep + 2u;
    for (t = 0; t < out->triangle_count; t++) {
        uint32_t src = t < keep ? t : full->receiver_first + (t - keep);
        memcpy(out->indices + 3u * t, full->indices + 3u * src, 3u * sizeof(uint32_t));
    }
    for (v = 0; v < full->vertex_count; v++) remap[v] = UINT32_MAX;
    for (t = 0; t < 3u * out->triangle_count; t++) remap[out->indices[t]] = 0u;
    for (v = 0; v < full->vertex_count; v++)
        if (remap[v] == 0u) {
            memcpy(out->positions + 3u * nv, full->positions + 3u * v, 3u * sizeof(float));
            remap[v] = nv++;
        }
    for (t = 0; t < 3u * out->triangle_count; t++) out->indices[t] = remap[out->indices[t]];
    out->vertex_count = nv;
    out->receiver_first = keep;
    out->receiver_count = 2u;
    pn_mesh_update_bbox(out);
    free(remap);
    return 0;
}

/* Forest et al. 2006, Fig. 12: time against triangles on 1 .. 81 of the spheres (the same
 * camera, light and eps as the whole scene), both modes and the faster of the reference and
 * GEARS interleaved at the main point's size and k; each mode's RMSE from one frame at k = 32
 * against that mesh's k = 32 reference. */
void wg_sweep(const bench_opts *o, report *r)
{
    scene_state ss;
    pn_mesh full;
    char data[4096], c[8][64], err[256];
    int a_wg = section_algo(o, PN_ALGO_WEDGES), dl = 0, a, m;
    uint32_t v;
    if (a_wg < 0 || o->n_wg_spheres == 0) return;
    r->wg_sweep_ran = 1;
    progress("[spheres] wedges: time against triangles");
    if (scene_open(o, &ss, "spheres", 1, &ports[0], o->size) != 0) {
        sec(r, SEC_WG_SWEEP, "| n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a (the scene did not load) |\n");
        scene_close(&ss);
        return;
    }
    full = ss.s.mesh;
    dl += snprintf(data + dl, sizeof(data) - (size_t)dl,
                   "# wg_sweep spheres: spheres triangles silhouettes blended_ms additive_ms exact_ms rmse_blended "
                   "rmse_additive (%ux%u, k = %u; RMSE at k = 32)\n",
                   o->size, o->size, o->k);
    for (v = 0; v < o->n_wg_spheres; v++) {
        uint32_t ns = o->wg_spheres[v];
        pn_mesh part;
        pn_frame_options opt;
        job jobs[2 + WG_MODES], x;
        double ms[NALGO], rmse[WG_MODES];
        const float *ref;
        int fastest, nj = 0;
        size_t n;
        if (ns < 1 || ns > WG_SPHERES) {
            progress("    %u spheres: the scene has 1 .. %u", ns, WG_SPHERES);
            continue;
        }
        if (wg_spheres_mesh(&full, ns, &part, err, sizeof(err)) != 0) {
            sec(r, SEC_WG_SWEEP, "| %u | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a (%s) |\n", ns, err);
            continue;
        }
        ss.s.mesh = part;
        free(ss.ref32_vis);
        free(ss.ref32_rgba);
        ss.ref32_vis = NULL;
        ss.ref32_rgba = NULL;
        ss.ref32_done = 0;
        if (pn_setup_upload(ss.h.ctx, &ss.s) != PN_OK) {
            sec(r, SEC_WG_SWEEP, "| %u | %u | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a (pn_scene_set: %s) |\n",
                ns, part.triangle_count, pn_last_error(ss.h.ctx));
            ss.s.mesh = full;
            pn_mesh_free(&part);
            continue;
        }
        base_options(o, &ss, &opt);
        n = (size_t)opt.width * opt.height;
        /* The exact algorithms of this run among the reference and GEARS, then both modes. */
        for (a = A_REF; a <= A_GEARS; a++)
            if ((pn_build_info() & algos[a].build_flag) && in_list(o->algos, algos[a].name)) job_lib(&jobs[nj++], a, &opt, 0);
        for (m = 0; m < WG_MODES; m++) {
            job_lib(&jobs[nj], a_wg, &opt, 0);
            jobs[nj++].opt.wedges.mode = wg_modes[m].mode;
        }
        progress("  spheres: %u of %u spheres, %u triangles", ns, WG_SPHERES, part.triangle_count);
        run_jobs(o, &ss, jobs, nj, &ss.s.light);
        for (a = 0; a < NALGO; a++) ms[a] = NAN;
        for (a = 0; a < nj - WG_MODES; a++) ms[jobs[a].algo] = job_pass(&jobs[a]);
        fastest = fastest_exact(ms);
        ref = ref32(o, &ss);
        if (!ref) progress("    k = 32 reference: %s", ss.ref32_err);
        for (m = 0; m < WG_MODES; m++) {
            accuracy acc;
            job_lib(&x, a_wg, &opt, 1);
            x.opt.k = 32;
            x.opt.wedges.mode = wg_modes[m].mode;
            job_run(&ss, &x, &ss.s.light, 0);
            acc = compare_vis(x.vis, ref, n);
            rmse[m] = x.ok && acc.ok ? acc.rmse : NAN;
            if (!x.ok) progress("    %s at k = 32: %s", wg_modes[m].name, x.err);
            job_free(&x);
        }
        for (a = 0; a < nj; a++)
            if (!jobs[a].ok) progress("    %s: %s", algos[jobs[a].algo].name, jobs[a].err);
        {
            const job *b = &jobs[nj - WG_MODES], *ad = &jobs[nj - WG_MODES + 1];
            double exact_ms = fastest >= 0 ? ms[fastest] : NAN;
            fmt_ms(c[0], sizeof(c[0]), job_pass(b));
            fmt_ms(c[1], sizeof(c[1]), job_pass(ad));
            fmt_ratio(c[2], sizeof(c[2]), job_pass(b), job_pass(ad));
            fmt_ms(c[3], sizeof(c[3]), exact_ms);
            fmt_ratio(c[4], sizeof(c[4]), exact_ms, job_pass(b));
            if (rmse[0] == rmse[0]) snprintf(c[5], sizeof(c[5]), "%.5f", rmse[0]);
            else snprintf(c[5], sizeof(c[5]), "n/a");
            if (rmse[1] == rmse[1]) snprintf(c[6], sizeof(c[6]), "%.5f", rmse[1]);
            else snprintf(c[6], sizeof(c[6]), "n/a");
            if (b->ok) snprintf(c[7], sizeof(c[7]), "%u", b->st.wedges.silhouettes);
            else snprintf(c[7], sizeof(c[7]), "n/a");
            sec(r, SEC_WG_SWEEP, "| %u | %u | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", ns, part.triangle_count,
                c[7], c[0], c[1], c[2], fastest >= 0 ? algos[fastest].name : "none", c[3], c[4], c[5], c[6],
                b->ok && ad->ok ? "" : b->ok ? ad->err : b->err);
            dl += snprintf(data + dl, sizeof(data) - (size_t)dl, "%u %u %u %.4f %.4f %.4f %.6g %.6g\n", ns,
                           part.triangle_count, b->ok ? b->st.wedges.silhouettes : 0u, job_pass(b), job_pass(ad), exact_ms,
                           rmse[0], rmse[1]);
            if (exact_ms == exact_ms) r->wg_sweep_exact = 1;
            if (b->ok || ad->ok) r->wg_sweep = 1;
        }
        for (a = 0; a < nj; a++) job_free(&jobs[a]);
        ss.s.mesh = full;
        pn_mesh_free(&part);
    }
    write_data(o, "wg_sweep", "spheres", data);
    scene_close(&ss);
}

/* The sweep's plot: shadow pass ms against triangles, log-log (the paper's Fig. 12 plots
 * frames per second against triangles). */
void plot_wg_sweep(report *r, const bench_opts *o)
{
    if (!r->wg_sweep) return;
    fprintf(r->plots,
            "\n# penumbra wedges: time against triangles (Forest et al. 2006, Fig. 12)\n"
            "set terminal pngcairo noenhanced size 900,560 font 'sans,10'\nset output 'wg_sweep.png'\n"
            "set title 'spheres: shadow pass time against triangles (%ux%u, k = %u)'\n"
            "set xlabel 'triangles (log scale)'\nset ylabel 'shadow pass ms (median, log scale)'\nset logscale xy\n"
            "set grid\nset key outside right top\n"
            "plot 'data/wg_sweep_spheres.dat' using 2:4 with linespoints lw 2 pt 7 lc 1 title 'wedges blended (default)', "
            "'' using 2:5 with linespoints dt 2 pt 6 lc 2 title 'wedges additive'%s\nunset logscale xy\nreset\n",
            o->size, o->size, o->k,
            /* A column with no point stops gnuplot (as in plot_headline). */
            r->wg_sweep_exact ? ", '' using 2:6 with linespoints dt 3 pt 4 lc 3 title 'fastest exact'" : "");
}

/* The header rows of the penumbra-wedge tables (the heat maps' section has none). */
void wg_headers(report *r)
{
    sec(r, SEC_WG_MODES,
        "| scene | triangles | silhouette edges | objects | (tile, wedge) pairs | wedges ms (blended) | "
        "silhouettes / binning / pixels ms | additive ms | additive vs blended | fastest exact | its ms | "
        "wedges vs fastest exact | RMSE blended (k = 32) | max error blended | MAE blended | RMSE additive (k = 32) | "
        "max error additive | pixels where the modes differ | blending closer | blending farther | heat map | "
        "blended on the chart's front |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | "
        "---: | ---: | ---: | ---: | --- | --- |\n");
    sec(r, SEC_WG_GOAL,
        "| scene | MAE (blended, k = 32 reference) | goal (1/255) | below the goal | RMSE | max error | "
        "pixels off by more than 1/255 |\n"
        "| --- | ---: | ---: | --- | ---: | ---: | ---: |\n");
    sec(r, SEC_WG_SWEEP,
        "| spheres | triangles | silhouette edges | wedges ms (blended) | additive ms | additive vs blended | "
        "fastest exact | its ms | wedges vs fastest exact | RMSE blended (k = 32) | RMSE additive (k = 32) | note |\n"
        "| ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | --- |\n");
}

static const bench_note wg_notes[] = {
    {SEC_WG_MODES, "## Penumbra wedges (Forest et al. 2006): additive against blended",
     "Per scene at the main point's size and k (area light), run interleaved: the default (what `--algo wedges` "
     "renders: the objects' occluded areas combined by the paper's overlap blending, §3.2) and the classic sum of "
     "the penumbra-wedges algorithm (`wedges.mode` = PN_WG_MODE_ADDITIVE). ms: the shadow pass's median; the stages "
     "are the blended frame's last repetition, from `pn_stats` (silhouettes: how each triangle casts and the silhouette "
     "edges seen from the light centre; binning: each wedge's screen tiles, sorted by tile; pixels: each pixel's "
     "centre ray and its tile's wedges, with the blending). Silhouette edges: the wedges built (`wedges.silhouettes`); "
     "objects: triangles joined by shared vertices (`wedges.objects`, what the blending combines); pairs: (screen tile, "
     "wedge) pairs binned (`wedges.pairs`). \"Additive vs blended\": blended's median over additive's (above 1: the "
     "blending costs that factor; the paper's Fig. 12(b)). Fastest exact: of reference, GEARS and raytrace at the "
     "main point (its medians, this run); \"wedges vs fastest exact\": its median over blended's (above 1: wedges "
     "faster). RMSE, max error and MAE (mean absolute error): one frame of each mode at k = 32 against the k = 32 "
     "reference (the frame's horizon term samples the light k x k). The modes differ: pixels whose visibility is "
     "not the same in the two k = 32 frames; of those, blending closer: blended's error smaller than additive's, "
     "blending farther: larger. Heat map: the next subsection. On the chart's front: no point of the time-vs-error "
     "chart but the wedges' own two (every algorithm at the main point, Embree, the SRT, occlusion-texture and MCSM "
     "configurations) is both faster and more accurate than blended (there, its RMSE is against the main point's "
     "reference); otherwise the points that are."},
    {SEC_WG_MAPS, "### Penumbra wedges: where blending helped and where it hurt",
     "Per scene, from the k = 32 frames of the table above: d = |additive - reference| - |blended - reference| per "
     "pixel against the k = 32 reference. Green: d > 1/255 (blending brought the pixel closer to the reference); "
     "red: d < -1/255 (blending moved it away); brighter with |d|, full at 0.25 and above; elsewhere the shaded "
     "k = 32 reference in grey."},
    {SEC_WG_GOAL, "### Penumbra wedges: the issue's goal on `square`",
     "`square` (one planar square occluder parallel to the light over a ground plane: no penumbrae overlap, the case "
     "where the issue expects the method to be nearly exact): the mean absolute error of the default (blended) "
     "frame at k = 32 against the k = 32 reference, against the goal of 1/255 (one step of an 8-bit image). RMSE, "
     "max error and the pixels off by more than 1/255: the same frame."},
    {SEC_WG_SWEEP, "### Penumbra wedges: time against triangles (paper Fig. 12)",
     "The built-in `spheres` cut to its first n spheres (762 triangles each, row by row) and its ground, with the "
     "whole scene's camera, light and eps, at the main point's size and k: both modes, the reference and GEARS run "
     "interleaved (ms: medians; fastest exact: the faster of the reference and GEARS). Silhouette edges: the "
     "blended frame's. \"Additive vs blended\" and \"wedges vs fastest exact\" as in the table above. RMSE: one "
     "frame of each mode at k = 32 against the k = 32 reference of the same cut scene. The paper measured frame "
     "rates on a GPU at 800x600 with a growing number of these spheres: with 762 triangles the additive algorithm "
     "ran twice as fast as the blended one, and with more triangles its frame rate fell faster than the blended "
     "one's (its wedges were built on the CPU, which became the limit first)."},
};

/* The penumbra-wedge tables with their headings and notes (print_report). */
void wg_print(const report *r, const bench_opts *o, FILE *out)
{
    int i;
    /* Not run (wedges not selected or not compiled in, or --lean): no empty tables. */
    if (section_algo(o, PN_ALGO_WEDGES) < 0 || o->lean) return;
    for (i = 0; i < (int)(sizeof(wg_notes) / sizeof(wg_notes[0])); i++) {
        int sw = wg_notes[i].sec;
        fprintf(out, "%s\n\n", wg_notes[i].heading);
        if (sw == SEC_WG_MAPS)
            fprintf(out, "%s\n\n%s", wg_notes[i].note, r->len[sw] ? r->buf[sw] : "(no heat map in this run)\n\n");
        else if (sw == SEC_WG_GOAL && !r->wg_goal_rows) fprintf(out, "(`square` is not in this run)\n\n");
        else if (sw == SEC_WG_SWEEP && !r->wg_sweep_ran)
            fprintf(out, "(`spheres` is not in this run: it runs when --only names it or is absent, and with --quick)\n\n");
        else fprintf(out, "%s\n%s\n\n", r->buf[sw], wg_notes[i].note);
        if (sw == SEC_WG_SWEEP && r->wg_sweep)
            fprintf(out, "![Penumbra wedges: time against triangles](wg_sweep.png)\n\n");
    }
}
