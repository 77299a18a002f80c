/* main_point.c - the main point (512x512, k = 16, grid 128; --quick: 128x128) of every scene
 * on every port: every algorithm, the baselines, both Embree APIs and both BVH builds,
 * interleaved. Its tables: per port, Embree, the headline row, GEARS' grid efficiency,
 * memory, accuracy against the reference and the mask agreement with Embree; the gallery
 * panels; the headline plot's data and program. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "pn_image.h"

/* The header rows of the tables filled here (the headline's: report_open). */
void main_point_headers(report *r)
{
    int v;
    char a[NALGO][64];
    for (v = 0; v < NALGO; v++) snprintf(a[v], sizeof(a[v]), "%s", algos[v].name);
    sec(r, SEC_PORTS, "| scene | port | threads |");
    for (v = 0; v < NALGO; v++) sec(r, SEC_PORTS, " %s ms (pass / total) |", a[v]);
    sec(r, SEC_PORTS, " Embree ms (API) |");
    for (v = 0; v < NALGO; v++) sec(r, SEC_PORTS, " %s speed-up over Embree |", a[v]);
    sec(r, SEC_PORTS, " reps |\n| --- | --- | ---: |");
    for (v = 0; v < 2 * NALGO + 2; v++) sec(r, SEC_PORTS, " ---: |");
    sec(r, SEC_PORTS, "\n");
    sec(r, SEC_EMBREE,
        "| scene | port | threads | Embree BVH build ms | Embree BVH build ms (high quality) | our BVH build ms | "
        "ours vs Embree's high-quality build | rtcOccluded1 ms | rtcOccluded16 ms | "
        "rtcOccluded16 vs rtcOccluded1 | faster | GEARS vs Embree (static: pass only) | GEARS vs Embree (dynamic: build + pass) |\n"
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: |\n");
    sec(r, SEC_GRIDEFF,
        "| scene | grid | cells with pixels | tris per cell max | tris per cell mean | pixels per cell max | "
        "pixels per cell mean | pairs | assignments (x1000) | after frustum cull (x1000) | necessary (x1000) | "
        "after cull / total | necessary / total | tiles |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_MEMORY,
        "| scene | triangles | arena MiB, 512x512 (default pools) | arena MiB, 512x512, 2^18 pairs, grid <= 128 | "
        "arena MiB, 1280x1280 | persistent MiB (scene copy, BVH) | high-water MiB | GEARS pairs high water | GEARS tiles |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_ACCURACY, "| scene | algorithm | RMSE | p99 error | max error | gross brighter | gross darker | "
                         "wrong pixels | note |\n"
                         "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n");
    sec(r, SEC_MASKS,
        "| scene | k | mask bits compared | bits that differ | fraction | blocked by Embree only | blocked by us only | "
        "pixels with a difference | our masks reproduce the reference |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n");
}

static void emb_cell(char *b, size_t n, const job *j1, const job *j16, double *best, const char **api)
{
    double a = job_pass(j1), c = job_pass(j16);
    char m[32];
    *best = NAN;
    *api = "";
    if (a == a && (!(c == c) || a <= c)) {
        *best = a;
        *api = "1";
    } else if (c == c) {
        *best = c;
        *api = "16";
    }
    fmt_ms(m, sizeof(m), *best);
    if (*best == *best) snprintf(b, n, "%s (%s)", m, *api);
    else snprintf(b, n, "n/a");
}

/* ---- The main point --------------------------------------------------------------------- */

/* Gallery panels of one scene: written as PNGs under OUT/work/gallery, composed with
 * titles by gnuplot (plots.gp). */
#define GALLERY_MAX 18
static void gallery(const bench_opts *o, report *r, scene_state *ss, job *lib, int nlib, const job *emb,
                    const job *pcss, uint32_t w, uint32_t h)
{
    char dir[1200], path[1400], err[256], title[160];
    size_t n = (size_t)w * h;
    uint8_t *tmp = (uint8_t *)malloc(n * 4);
    const float *ref = lib[A_REF].vis;
    int a, panels = 0;
    char list[GALLERY_MAX][2][1400];
    if (!tmp || !ref) {
        free(tmp);
        return;
    }
    snprintf(dir, sizeof(dir), "%s/work/gallery/%s", o->out_dir, ss->s.name);
    pn_mkdir_p(dir);
#define PANEL(file, img, ...)                                                               \
    do {                                                                                    \
        snprintf(path, sizeof(path), "%s/%s.png", dir, file);                               \
        if (pn_write_png(path, img, w, h, err, sizeof(err)) == 0 && panels < GALLERY_MAX) { \
            snprintf(list[panels][0], sizeof(list[0][0]), "work/gallery/%s/%s.png", ss->s.name, file); \
            snprintf(list[panels][1], sizeof(list[0][1]), __VA_ARGS__);                      \
            panels++;                                                                       \
        }                                                                                   \
    } while (0)
    for (a = 0; a < nlib; a++) {
        char ms[32];
        if (!lib[a].rgba || !lib[a].vis) continue;
        fmt_ms(ms, sizeof(ms), job_pass(&lib[a]));
        PANEL(algos[a].name, lib[a].rgba, "%s, %s ms", algos[a].name, ms);
        if (a == A_REF) {
            pn_vis_to_rgba(ref, n, tmp);
            PANEL("reference_vis", tmp, "reference visibility");
        } else {
            accuracy acc = compare_vis(lib[a].vis, ref, n);
            pn_err_to_rgba(lib[a].vis, ref, n, tmp);
            snprintf(title, sizeof(title), "%s error", algos[a].name);
            PANEL(title, tmp, "%s |error| x4 (%s)", algos[a].name, acc.identical ? "identical" : "differs");
        }
    }
    if (emb && emb->vis) {
        char ms[32];
        accuracy acc = compare_vis(emb->vis, ref, n);
        fmt_ms(ms, sizeof(ms), job_pass(emb));
        pn_vis_to_rgba(emb->vis, n, tmp);
        PANEL("embree_vis", tmp, "Embree visibility, %s ms", ms);
        pn_err_to_rgba(emb->vis, ref, n, tmp);
        PANEL("embree_error", tmp, "Embree |error| x4 (%.4f%% px)", 100.0 * acc.wrong_frac);
    }
    if (pcss && pcss->vis) {
        char ms[32];
        fmt_ms(ms, sizeof(ms), job_pass(pcss));
        pn_vis_to_rgba(pcss->vis, n, tmp);
        PANEL("pcss_vis", tmp, "PCSS visibility, %s ms", ms);
        pn_err_to_rgba(pcss->vis, ref, n, tmp);
        PANEL("pcss_error", tmp, "PCSS |error| x4");
    }
#undef PANEL
    free(tmp);
    /* gnuplot: one row of panels with titles. */
    fprintf(r->plots, "\n# gallery: %s\n", ss->s.name);
    fprintf(r->plots, "set terminal pngcairo noenhanced size %d,%d font 'sans,9'\nset output 'gallery/%s.png'\n",
            panels * 240, 262, ss->s.name);
    fprintf(r->plots, "set multiplot layout 1,%d margins 0.005,0.995,0.02,0.9 spacing 0.004,0\n"
                      "unset border; unset tics; unset key; unset colorbox\nset size ratio -1\n",
            panels);
    for (a = 0; a < panels; a++)
        fprintf(r->plots, "set title \"%s\"\nplot '%s' binary filetype=png with rgbimage\n", list[a][1],
                list[a][0]);
    fprintf(r->plots, "unset multiplot\nunset title\nset size noratio\nset border; set tics\n");
    sec(r, SEC_GALLERY, "### %s\n\n![%s: reference, GEARS and the other algorithms with error heat maps](gallery/%s.png)\n\n",
        ss->s.name, ss->s.name, ss->s.name);
}

/* Bit-level agreement of our masks (the library's predicate, recomputed in the tool and
 * checked against the reference's visibility) with Embree's rtcOccluded1 masks. */
static void mask_agreement(report *r, scene_state *ss, const pn_frame_options *opt, const float *ref_vis)
{
    size_t n = (size_t)opt->width * opt->height;
    pn_masks ours, theirs;
    pn_mask_diff d;
    float *our_vis = (float *)malloc(n * sizeof(float)), *emb_vis = (float *)malloc(n * sizeof(float));
    char err[256];
    double ms;
    pn_stats st;
    int ok = our_vis && emb_vis && pn_get_stats(ss->h.ctx, &st) == PN_OK;
    memset(&ours, 0, sizeof(ours));
    memset(&theirs, 0, sizeof(theirs));
    ok = ok && pn_masks_alloc(&ours, opt->width, opt->height, opt->k) == 0 &&
         pn_masks_alloc(&theirs, opt->width, opt->height, opt->k) == 0;
    snprintf(err, sizeof(err), "out of memory");
    progress("    masks: ours (kernels/ predicate, host BVH) and Embree's, bit by bit");
    ok = ok &&
         pn_our_masks(&ss->s.mesh, &ss->g, &ss->s.light, opt->k, opt->eps, st.cull_tol, &ss->h.threads, &ours, our_vis, err,
                      sizeof(err)) == 0 &&
         pn_embree_shadow(ss->emb, PN_EMBREE_OCCLUDED1, &ss->g, &ss->s.light, opt->k, opt->eps, &ss->h.threads,
                          emb_vis, &theirs, &ms, err, sizeof(err)) == 0;
    if (ok) {
        accuracy self = compare_vis(our_vis, ref_vis, n);
        pn_masks_compare(&ours, &theirs, &d);
        sec(r, SEC_MASKS, "| %s | %u | %llu | %llu | %.3g | %llu | %llu | %llu | %s |\n", ss->s.name, opt->k,
            (unsigned long long)d.bits, (unsigned long long)d.differ, d.bits ? (double)d.differ / (double)d.bits : 0.0,
            (unsigned long long)d.only_b, (unsigned long long)d.only_a, (unsigned long long)d.pixels_differ,
            self.identical ? "yes" : "**no**");
    } else {
        sec(r, SEC_MASKS, "| %s | %u | n/a | n/a | n/a | n/a | n/a | n/a | %s |\n", ss->s.name, opt->k, err);
    }
    pn_masks_free(&ours);
    pn_masks_free(&theirs);
    free(our_vis);
    free(emb_vis);
}

/* The main point: 512x512, k = 16, grid 128 on one port: every algorithm, both Embree APIs,
 * both BVH builds, interleaved. On the first port it also produces the accuracy, mask
 * agreement, grid-efficiency (exact stats), memory and gallery rows. */
static void acc_row(report *r, const char *scene, const char *name, const accuracy *acc, const char *note)
{
    sec(r, SEC_ACCURACY, "| %s | %s | %.6f | %.4f | %.6f | %.3f%% | %.3f%% | %.4f%% | %s |\n", scene, name, acc->rmse,
        acc->p99, acc->max_err, 100.0 * acc->gross_brighter, 100.0 * acc->gross_darker, 100.0 * acc->wrong_frac, note);
}

void main_point(const bench_opts *o, report *r, scene_state *ss, int first_port)
{
    pn_frame_options opt;
    job lib[NALGO], emb[PN_EMBREE_API_COUNT], bset, ebuild, ehigh, base[NBASE];
    int a, reps, i, b;
    size_t n;
    pn_stats ref_only;
    char c[12][64];
    double emb_best;
    const char *emb_api;
    job all[NALGO + NBASE + PN_EMBREE_API_COUNT + 3];
    int nall = 0;

    base_options(o, ss, &opt);
    n = (size_t)opt.width * opt.height;
    memset(&bset, 0, sizeof(bset));
    bset.kind = JOB_SCENE_SET;
    bset.ok = 1;
    memset(&ebuild, 0, sizeof(ebuild));
    ebuild.kind = JOB_EMBREE_BUILD;
    ebuild.ok = ss->emb != NULL;
    snprintf(ebuild.err, sizeof(ebuild.err), "%s", ss->emb_err);
    ehigh = ebuild;
    ehigh.kind = JOB_EMBREE_BUILD_HIGH;
    for (a = 0; a < NALGO; a++) job_lib(&lib[a], a, &opt, first_port);
    for (i = 0; i < PN_EMBREE_API_COUNT; i++) job_emb(&emb[i], (pn_embree_api)i, &opt, first_port);
    if (!ss->emb)
        for (i = 0; i < PN_EMBREE_API_COUNT; i++) {
            emb[i].ok = 0;
            snprintf(emb[i].err, sizeof(emb[i].err), "%s", ss->emb_err);
        }
    for (a = 0; a < NALGO; a++)
        if (!(pn_build_info() & algos[a].build_flag)) {
            lib[a].ok = 0;
            snprintf(lib[a].err, sizeof(lib[a].err), "not compiled in");
        } else if (!first_port && !algos[a].all_ports) {
            lib[a].ok = 0;
            snprintf(lib[a].err, sizeof(lib[a].err), "first port only");
        } else if (!in_list(o->algos, algos[a].name)) {
            lib[a].ok = 0;
            snprintf(lib[a].err, sizeof(lib[a].err), "not selected (--algos)");
        }
    /* The baselines: on the first port, beside the algorithms (--algos: "baselines"). */
    for (b = 0; b < NBASE; b++) {
        job_lib(&base[b], A_REF, &opt, 1);
        if (baselines[b].k) base[b].opt.k = baselines[b].k;
        else base[b].kind = JOB_PCSS;
        if (!first_port || o->lean || !in_list(o->algos, "baselines")) {
            base[b].ok = 0;
            snprintf(base[b].err, sizeof(base[b].err), "not run");
        } else if (baselines[b].k && !(pn_build_info() & algos[A_REF].build_flag)) {
            base[b].ok = 0;
            snprintf(base[b].err, sizeof(base[b].err), "not compiled in");
        }
    }
    if (!in_list(o->algos, "embree")) {
        ebuild.ok = ehigh.ok = 0;
        for (i = 0; i < PN_EMBREE_API_COUNT; i++) {
            emb[i].ok = 0;
            snprintf(emb[i].err, sizeof(emb[i].err), "not selected (--algos)");
        }
    }
    /* One array so that run_jobs interleaves them: builds (Embree's default last: its
     * passes trace that tree), then the algorithms (reference first: it provides the
     * G-buffer), then Embree. */
    all[nall++] = bset;
    all[nall++] = ehigh;
    all[nall++] = ebuild;
    for (a = 0; a < NALGO; a++) all[nall++] = lib[a];
    for (b = 0; b < NBASE; b++) all[nall++] = base[b];
    for (i = 0; i < PN_EMBREE_API_COUNT; i++) all[nall++] = emb[i];
    progress("  %s/%s x%u: main point %ux%u k=%u", ss->s.name, ss->port->name, ss->threads, opt.width, opt.height,
             opt.k);
    reps = run_jobs(o, ss, all, nall, &ss->s.light);
    bset = all[0];
    ehigh = all[1];
    ebuild = all[2];
    for (a = 0; a < NALGO; a++) lib[a] = all[3 + a];
    for (b = 0; b < NBASE; b++) base[b] = all[3 + NALGO + b];
    for (i = 0; i < PN_EMBREE_API_COUNT; i++) emb[i] = all[3 + NALGO + NBASE + i];
    for (a = 0; a < NALGO; a++)
        if (!lib[a].ok && (first_port || algos[a].all_ports)) progress("    %s: %s", algos[a].name, lib[a].err);
    for (i = 0; i < PN_EMBREE_API_COUNT; i++)
        if (!emb[i].ok && ss->emb) progress("    Embree %s: %s", pn_embree_api_name((pn_embree_api)i), emb[i].err);
    for (b = 0; b < NBASE; b++)
        if (!base[b].ok && strcmp(base[b].err, "not run") != 0) progress("    %s: %s", baselines[b].name, base[b].err);

    emb_cell(c[9], sizeof(c[9]), &emb[0], &emb[1], &emb_best, &emb_api);
    ss->best_api = strcmp(emb_api, "1") == 0 ? PN_EMBREE_OCCLUDED1 : PN_EMBREE_OCCLUDED16;
    /* ---- Table 1 (issue 5): per port, ms and speed-up over Embree ---- */
    {
        char row[1024];
        int len = snprintf(row, sizeof(row), "| %s | %s | %u |", ss->s.name, ss->port->name, ss->threads);
        for (a = 0; a < NALGO; a++) {
            fmt_ms(c[0], sizeof(c[0]), job_pass(&lib[a]));
            fmt_ms(c[1], sizeof(c[1]), job_total(&lib[a]));
            len += snprintf(row + len, sizeof(row) - (size_t)len, " %s / %s |", c[0], c[1]);
        }
        len += snprintf(row + len, sizeof(row) - (size_t)len, " %s |", c[9]);
        for (a = 0; a < NALGO; a++) {
            fmt_ratio(c[0], sizeof(c[0]), emb_best, job_pass(&lib[a]));
            len += snprintf(row + len, sizeof(row) - (size_t)len, " %s |", c[0]);
        }
        sec(r, SEC_PORTS, "%s %d |\n", row, reps);
    }
    /* ---- Embree details ---- */
    {
        double gears = job_pass(&lib[A_GEARS]);
        double dyn_ours = job_total(&bset) + gears, dyn_emb = job_pass(&ebuild) + emb_best;
        fmt_ms(c[0], sizeof(c[0]), job_pass(&ebuild));
        fmt_ms(c[1], sizeof(c[1]), job_pass(&bset));
        fmt_ms(c[7], sizeof(c[7]), job_pass(&ehigh));
        fmt_ratio(c[8], sizeof(c[8]), job_pass(&ehigh), job_pass(&bset));
        fmt_ms(c[2], sizeof(c[2]), job_pass(&emb[0]));
        fmt_ms(c[3], sizeof(c[3]), job_pass(&emb[1]));
        fmt_ratio(c[4], sizeof(c[4]), emb_best, gears);
        fmt_ratio(c[5], sizeof(c[5]), dyn_emb, dyn_ours);
        fmt_ratio(c[6], sizeof(c[6]), job_pass(&emb[0]), job_pass(&emb[1]));
        sec(r, SEC_EMBREE, "| %s | %s | %u | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", ss->s.name,
            ss->port->name, ss->threads, c[0], c[7], c[1], c[8], c[2], c[3], c[6],
            emb_best == emb_best ? (emb_api[0] == '1' && emb_api[1] == '6' ? "rtcOccluded16" : "rtcOccluded1") : "n/a",
            c[4], c[5]);
    }
    if (first_port && !o->lean) {
        pn_stats gst = lib[A_GEARS].st, xst;
        job exact;
        int have_exact = 0;
        double gears = job_pass(&lib[A_GEARS]);
        /* Headline row */
        fmt_ms(c[0], sizeof(c[0]), job_pass(&lib[A_REF]));
        fmt_ms(c[1], sizeof(c[1]), gears);
        if (A_RT >= 0) fmt_ms(c[2], sizeof(c[2]), job_pass(&lib[A_RT]));
        else snprintf(c[2], sizeof(c[2]), "not in this build");
        fmt_ratio(c[3], sizeof(c[3]), job_pass(&lib[A_REF]), gears);
        if (A_RT >= 0) fmt_ratio(c[4], sizeof(c[4]), job_pass(&lib[A_RT]), gears);
        else snprintf(c[4], sizeof(c[4]), "n/a");
        fmt_ratio(c[5], sizeof(c[5]), emb_best, gears);
        ss->gears_vs_ref = job_pass(&lib[A_REF]) / gears;
        ss->gears_vs_emb = emb_best / gears;
        ss->gears_vs_rt = A_RT >= 0 ? job_pass(&lib[A_RT >= 0 ? A_RT : 0]) / gears : NAN;

        /* GEARS with exact statistics (no early exit): paper Table 6's "necessary". */
        job_lib(&exact, A_GEARS, &opt, 0);
        exact.opt.exact_stats = 1;
        job_run(ss, &exact, &ss->s.light, 1);
        if (exact.ok) {
            xst = exact.st;
            have_exact = 1;
        } else {
            memset(&xst, 0, sizeof(xst));
        }
        if (have_exact && xst.gears.assignments > 0)
            snprintf(c[6], sizeof(c[6]), "%.1f%%", 100.0 * (double)xst.shadow_blocking / (double)xst.gears.assignments);
        else snprintf(c[6], sizeof(c[6]), "n/a");
        sec(r, SEC_HEADLINE, "| %s | %u | %u | %s | %s | %s | %s | %s | %s | %s | %s |\n", ss->s.name,
            lib[A_REF].st.triangles, lib[A_REF].st.lit_pixels, c[0], c[1], c[2], c[9], c[3], c[4], c[5], c[6]);

        /* Grid efficiency at the main point (paper Tables 5 and 6). */
        if (have_exact)
            sec(r, SEC_GRIDEFF, "| %s | %u | %u | %u | %.1f | %u | %.1f | %llu | %.0f | %.0f | %.0f | %.1f%% | %.1f%% | %u |\n",
                ss->s.name, o->grid, xst.gears.cells_used, xst.gears.max_tris_per_cell, xst.gears.mean_tris_per_cell,
                xst.gears.max_pixels_per_cell, xst.gears.mean_pixels_per_cell, (unsigned long long)xst.gears.pairs,
                xst.gears.assignments / 1e3, xst.shadow_candidates / 1e3, xst.shadow_blocking / 1e3,
                xst.gears.assignments ? 100.0 * (double)xst.shadow_candidates / (double)xst.gears.assignments : 0.0,
                xst.gears.assignments ? 100.0 * (double)xst.shadow_blocking / (double)xst.gears.assignments : 0.0,
                xst.gears.tiles);

        /* Memory: the size query for this scene at a few configurations, and what the
         * frames actually used. */
        {
            pn_limits lim;
            size_t b512 = 0, b1280 = 0, bsmall = 0;
            memset(&lim, 0, sizeof(lim));
            lim.max_triangles = ss->s.mesh.triangle_count;
            lim.max_width = lim.max_height = 512;
            pn_arena_size(&lim, &b512);
            lim.max_width = lim.max_height = 1280;
            pn_arena_size(&lim, &b1280);
            lim.max_width = lim.max_height = 512;
            lim.gears_pairs = 1u << 18;
            lim.gears_grid_max = 128;
            pn_arena_size(&lim, &bsmall);
            pn_get_stats(ss->h.ctx, &ref_only);
            sec(r, SEC_MEMORY, "| %s | %u | %.1f | %.1f | %.1f | %.1f | %.1f | %u | %u |\n", ss->s.name,
                ss->s.mesh.triangle_count, b512 / 1048576.0, bsmall / 1048576.0, b1280 / 1048576.0,
                ref_only.arena_persistent / 1048576.0, ref_only.arena_high_water / 1048576.0,
                gst.gears.pairs_high_water, gst.gears.tiles);
        }

        /* Accuracy of every algorithm against the reference, of the baselines and of Embree. */
        for (a = 1; a < NALGO; a++) {
            accuracy acc = compare_vis(lib[a].vis, lib[A_REF].vis, n);
            if (!acc.ok) {
                sec(r, SEC_ACCURACY, "| %s | %s | n/a | n/a | n/a | n/a | n/a | n/a | %s |\n", ss->s.name, algos[a].name,
                    lib[a].err);
                continue;
            }
            acc_row(r, ss->s.name, algos[a].name, &acc,
                    algos[a].exact ? (acc.identical ? "exact: byte-identical" : "exact: **DIFFERS**") : "approximate");
        }
        for (b = 0; b < NBASE; b++) {
            accuracy acc = compare_vis(base[b].vis, lib[A_REF].vis, n);
            if (acc.ok) acc_row(r, ss->s.name, baselines[b].name, &acc, baselines[b].k ? "cheap exact baseline" : "engine baseline");
            else sec(r, SEC_ACCURACY, "| %s | %s | n/a | n/a | n/a | n/a | n/a | n/a | %s |\n", ss->s.name,
                     baselines[b].name, base[b].err);
        }
        if (emb[0].vis) {
            accuracy acc = compare_vis(emb[0].vis, lib[A_REF].vis, n);
            accuracy same = compare_vis(emb[1].vis, emb[0].vis, n);
            acc_row(r, ss->s.name, "Embree", &acc,
                    !same.ok ? "outside baseline"
                    : same.identical ? "outside baseline; rtcOccluded16 = rtcOccluded1"
                                     : "outside baseline; rtcOccluded16 differs from rtcOccluded1");
            mask_agreement(r, ss, &opt, lib[A_REF].vis);
        } else {
            sec(r, SEC_ACCURACY, "| %s | Embree | n/a | n/a | n/a | n/a | n/a | n/a | %s |\n", ss->s.name,
                ss->emb ? emb[0].err : ss->emb_err);
        }
        /* For the SRT section and the time-vs-error chart. */
        for (a = 0; a < NALGO; a++) {
            accuracy acc = compare_vis(lib[a].vis, lib[A_REF].vis, n);
            ss->pt_ms[a] = job_pass(&lib[a]);
            if (!lib[a].ok && lib[a].kind == JOB_LIB && strncmp(lib[a].err, "PN_", 3) == 0)
                snprintf(ss->pt_fail[a], sizeof(ss->pt_fail[a]), "%.*s", (int)strcspn(lib[a].err, ":"), lib[a].err);
            ss->pt_rmse[a] = acc.ok ? acc.rmse : NAN;
            ss->pt_acc[a] = acc;
        }
        for (b = 0; b < NBASE; b++) {
            ss->bl_ms[b] = job_pass(&base[b]);
            ss->bl_acc[b] = compare_vis(base[b].vis, lib[A_REF].vis, n);
            if (ss->bl_acc[b].ok && ss->nxpt < XPT_MAX) {
                snprintf(ss->xpt[ss->nxpt].label, sizeof(ss->xpt[0].label), "%s", baselines[b].name);
                ss->xpt[ss->nxpt].ms = ss->bl_ms[b];
                ss->xpt[ss->nxpt].rmse = ss->bl_acc[b].rmse;
                ss->xpt[ss->nxpt].pt = baselines[b].pt;
                ss->nxpt++;
            }
        }
        ss->emb_ms = emb_best;
        ss->emb_api = emb_api;
        ss->emb_acc = compare_vis(emb[ss->best_api].vis, lib[A_REF].vis, n);
        ss->emb_rmse = emb[ss->best_api].vis ? ss->emb_acc.rmse : NAN;
        ss->cull_tol = lib[A_REF].st.cull_tol;
        if (lib[A_REF].vis && (ss->ref_vis = (float *)malloc(n * sizeof(float))) != NULL)
            memcpy(ss->ref_vis, lib[A_REF].vis, n * sizeof(float));
        gallery(o, r, ss, lib, NALGO, &emb[0], &base[BL_PCSS], opt.width, opt.height);
        job_free(&exact);
    }
    for (a = 0; a < NALGO; a++) job_free(&lib[a]);
    for (b = 0; b < NBASE; b++) job_free(&base[b]);
    for (i = 0; i < PN_EMBREE_API_COUNT; i++) job_free(&emb[i]);
}

void plot_headline(report *r, const bench_opts *o)
{
    fprintf(r->plots,
            "\n# headline speed-ups\nset terminal pngcairo noenhanced size 1000,520 font 'sans,10'\nset output 'speedup.png'\n"
            "set title 'GEARS shadow pass speed-up, %ux%u, k = %u (above 1: GEARS faster; medians of one run)'\n"
            "set style data histogram\nset style histogram cluster gap 1\nset style fill solid 0.8 border -1\n"
            "set logscale y\nset ylabel 'speed-up'\nunset xlabel\nset xtics rotate by -30\nset grid ytics\n"
            "set key inside top right\nset yrange [%g:%g]\nset arrow 1 from graph 0, first 1 to graph 1, first 1 nohead dt 2\n"
            "set arrow 2 from graph 0, first 10 to graph 1, first 10 nohead dt 3 lc rgb 'red'\n"
            "set label 1 'goal 10x' at graph 0.01, first 10 offset 0,0.6 tc rgb 'red'\n"
            "plot 'data/headline.dat' using 2:xtic(1) title 'vs reference'%s%s\n"
            "unset arrow 1\nunset arrow 2\nunset label 1\nunset logscale y\nset xtics norotate\nset yrange [*:*]\n",
            o->size, o->size, o->k, r->hmin / 1.5, r->hmax * 1.5,
            /* A column with no point (Embree absent, raytrace compiled out or not selected)
             * stops gnuplot. */
            r->hcol[1] ? ", '' using 3 title 'vs Embree'" : "", r->hcol[2] ? ", '' using 4 title 'vs raytrace'" : "");
}

void headline_data(FILE *f, report *r, const scene_state *ss)
{
    double v[3];
    int i;
    v[0] = ss->gears_vs_ref;
    v[1] = ss->gears_vs_emb;
    v[2] = ss->gears_vs_rt;
    for (i = 0; i < 3; i++)
        if (v[i] > 0.0) {
            if (v[i] < r->hmin) r->hmin = v[i];
            if (v[i] > r->hmax) r->hmax = v[i];
            r->hcol[i] = 1;
        }
    /* gnuplot reads NaN as a missing point. */
    fprintf(f, "%s %.4g %.4g %.4g\n", ss->s.name, ss->gears_vs_ref, ss->gears_vs_emb, ss->gears_vs_rt);
}

/* The headings and notes of the tables filled here, in the report's order (the sweeps come
 * between SEC_EMBREE and SEC_GRIDEFF; the accuracy heading is built in main_point_print). */
static const bench_note main_notes[] = {
    {SEC_PORTS, "## Per port: milliseconds and speed-up over Embree (issue 5, table 1)",
     "Embree runs with the same thread count as the port on its row. The per-sample ray tracer is a baseline, "
     "measured on the first row of each scene only. A port added to `ports[]` in tools/bench/jobs.c gets its rows "
     "here."},
    {SEC_EMBREE, "## Embree 3 baseline",
     "Static: shadow pass against shadow pass (paper Table 7, column B). Dynamic: Embree's BVH build plus its pass "
     "against our scene copy and BVH build plus GEARS' pass (column C: a scene that changes every frame)."},
    {SEC_GRIDEFF, "## GEARS grid efficiency (paper Tables 5 and 6)",
     "Per cell: over the cells that hold at least one pixel. Assignments: triangles x pixels summed over cells. "
     "\"After frustum cull\": assignments that survive the pixel's light-frustum test and reach the predicate. "
     "Necessary: those that block at least one sample (exact statistics, no early exit)."},
    {SEC_MEMORY, "## Memory",
     "Arena columns: `pn_arena_size` for the scene's triangle count at that image size and GEARS pool "
     "configuration. Persistent and high-water: `pn_stats` after the main-point frames (the context was sized for "
     "the largest image of the run). GEARS tiles: passes the pair pool needed."},
    {SEC_ACCURACY, NULL,
     "Every algorithm's default, the baselines and Embree against the reference of the same run. p99: the 99th "
     "percentile of the absolute error (within 2^-16). Gross: pixels off by more than 0.25 (a missing or invented "
     "shadow, not a penumbra's slope), counted apart when brighter (light where the reference has shadow: a leak) and "
     "darker than the reference, in % of all pixels. Wrong pixels: visibility not bit-identical to the reference's. "
     "Exact algorithms must show zero. The baselines: the reference itself at k = 4 and k = 8 (the cheap exact "
     "answer: its error is the sampling's alone) and percentage-closer soft shadows (Fernando 2005, what engines "
     "ship: tools/pn_bench_pcss.c)."},
    {SEC_MASKS, "### Embree against our predicate, bit by bit",
     "Our masks are recomputed in the tool by the library's kernels (`pn_tri_mask` over a host BVH with the "
     "reference's frustum cull); the last column checks that their visibility is byte-identical to the reference's "
     "frame. Embree's masks come from rtcOccluded1. Compared: every mask bit of every pixel that has a shadow-ray "
     "origin."},
};

/* Prints the tables of main_notes from first to last. */
void main_point_print(const report *r, const bench_opts *o, FILE *out, int first, int last)
{
    int i;
    for (i = 0; i < (int)(sizeof(main_notes) / sizeof(main_notes[0])); i++) {
        int sw = main_notes[i].sec;
        if (sw < first || sw > last) continue;
        if (sw == SEC_ACCURACY) fprintf(out, "## Accuracy against the reference (%ux%u, k = %u)\n\n", o->size, o->size, o->k);
        print_table(out, r, sw, main_notes[i].heading, main_notes[i].note);
    }
}
