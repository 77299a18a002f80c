/* srt.c - selective ray tracing (issue 15): accuracy against the reference, speed against the
 * fastest exact algorithm, and what it can save (the reference's cost by pixel class). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* ---- Selective ray tracing (issue 15): accuracy, speed, what it can save ------------------ */

/* The configurations measured: the default (what --algo srt renders) and the main
 * alternatives. Corner maps (the paper's union over the light's corners) are not
 * implemented. */
#define SRT_CFGS 4
static const struct {
    const char *name;
    uint32_t flags, map;
} srt_cfgs[SRT_CFGS] = {
    {"default (map 2048, conservative)", 0u, 0u},
    {"no conservative rasterization", PN_SRT_NO_CONSERVATIVE, 0u},
    {"map 1024", 0u, 1024u},
    {"map 512", 0u, 512u},
};

/* Pixels brighter than the reference (a missing shadow) and darker (an extra one). */
static void srt_signs(const float *a, const float *ref, size_t n, size_t *missing, size_t *extra)
{
    size_t i;
    *missing = *extra = 0;
    if (!a || !ref) return;
    for (i = 0; i < n; i++) {
        if (a[i] > ref[i]) (*missing)++;
        else if (a[i] < ref[i]) (*extra)++;
    }
}

static void srt_row(report *r, const scene_state *ss, const char *light, uint32_t size, const char *cfg, const job *j,
                    const float *ref, double exact_ms, const char *exact_name)
{
    size_t n = (size_t)size * size, missing, extra;
    accuracy acc = compare_vis(j->vis, ref, n);
    char c[4][48];
    if (!j->ok || !acc.ok) {
        sec(r, SEC_SRT_ACC, "| %s | %s | %u | %s | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | n/a | %s |\n", ss->s.name,
            light, size, cfg, j->ok ? "no reference" : j->err);
        return;
    }
    srt_signs(j->vis, ref, n, &missing, &extra);
    fmt_ms(c[0], sizeof(c[0]), job_pass(j));
    fmt_ms(c[1], sizeof(c[1]), exact_ms);
    fmt_ratio(c[2], sizeof(c[2]), exact_ms, job_pass(j));
    sec(r, SEC_SRT_ACC, "| %s | %s | %u | %s | %.2f%% | %u / %u | %.4f%% | %zu | %zu | %.6f | %.4f | %s | %s (%s) | %s |\n",
        ss->s.name, light, size, cfg, j->st.lit_pixels ? 100.0 * j->st.srt.pip / (double)j->st.lit_pixels : 0.0,
        j->st.srt.thin, j->st.srt.cons_texels,
        100.0 * acc.wrong_frac, missing, extra, acc.rmse, acc.max_err, c[0], c[1], exact_name, c[2]);
}

static void srt_speed_row(report *r, const scene_state *ss, const char *light, uint32_t size, const job *srt,
                          const float *ref, double exact_ms, const char *exact_name)
{
    size_t n = (size_t)size * size;
    accuracy acc = compare_vis(srt->vis, ref, n);
    char c[7][48];
    fmt_ms(c[0], sizeof(c[0]), exact_ms);
    fmt_ms(c[1], sizeof(c[1]), job_pass(srt));
    fmt_ms(c[2], sizeof(c[2]), srt->st.srt.ns_map / 1e6);
    fmt_ms(c[3], sizeof(c[3]), srt->st.srt.ns_classify / 1e6);
    fmt_ms(c[4], sizeof(c[4]), srt->st.srt.ns_exact / 1e6);
    fmt_ratio(c[5], sizeof(c[5]), exact_ms, job_pass(srt));
    if (acc.ok) snprintf(c[6], sizeof(c[6]), "%.4f%%", 100.0 * acc.wrong_frac);
    else snprintf(c[6], sizeof(c[6]), "n/a");
    if (!srt->ok) {
        sec(r, SEC_SRT_SPEED, "| %s | %s | %ux%u | %s | %s | n/a | n/a | n/a | n/a | %s |\n", ss->s.name, light, size,
            size, exact_name, c[0], srt->err);
        return;
    }
    sec(r, SEC_SRT_SPEED, "| %s | %s | %ux%u | %s | %s | %s | %s / %s / %s | %.2f%% | %s | %s |\n", ss->s.name, light,
        size, size, exact_name, c[0], c[1], c[2], c[3], c[4],
        srt->st.lit_pixels ? 100.0 * srt->st.srt.pip / (double)srt->st.lit_pixels : 0.0, c[6], c[5]);
}

void srt_section(const bench_opts *o, report *r, scene_state *ss)
{
    static const char *light_name[2] = {"area, k = 16", "point"};
    pn_frame_options opt;
    pn_light lights[2];
    job jobs[NALGO + SRT_CFGS], big[2];
    int li, i, a, nj, a_srt = section_algo(o, PN_ALGO_SRT);
    base_options(o, ss, &opt);
    if (a_srt < 0) return;
    lights[0] = ss->s.light;
    lights[1] = ss->s.light;
    memset(lights[1].u, 0, sizeof(lights[1].u));
    memset(lights[1].v, 0, sizeof(lights[1].v));
    for (li = 0; li < 2; li++) {
        const float *ref;
        double exact_ms;
        const char *exact_name;
        double ms[NALGO];
        int fastest_algo;
        nj = 0;
        /* The point light's exact algorithms here (the area light's ran at the main point,
         * in this run); then every SRT configuration. */
        if (li == 1)
            for (a = 0; a < NALGO; a++)
                if (algos[a].exact && (pn_build_info() & algos[a].build_flag) && in_list(o->algos, algos[a].name)) {
                    job_lib(&jobs[nj], a, &opt, 1);
                    nj++;
                }
        for (i = 0; i < SRT_CFGS; i++) {
            job_lib(&jobs[nj], a_srt, &opt, 1);
            jobs[nj].opt.srt.flags = srt_cfgs[i].flags;
            jobs[nj].opt.srt.map = srt_cfgs[i].map;
            nj++;
        }
        progress("  %s: SRT, %s light, %ux%u", ss->s.name, li ? "point" : "area", opt.width, opt.height);
        run_jobs(o, ss, jobs, nj, &lights[li]);
        /* The exact algorithms' medians: the main point's for the area light, this
         * section's for the point light. */
        for (a = 0; a < NALGO; a++) ms[a] = li == 0 ? ss->pt_ms[a] : NAN;
        for (i = 0; i < nj - SRT_CFGS; i++) ms[jobs[i].algo] = job_pass(&jobs[i]);
        ref = li == 0 ? ss->ref_vis : jobs[0].algo == A_REF ? jobs[0].vis : NULL;
        fastest_algo = fastest_exact(ms);
        exact_ms = fastest_algo >= 0 ? ms[fastest_algo] : NAN;
        exact_name = fastest_algo >= 0 ? algos[fastest_algo].name : "none";
        for (i = 0; i < SRT_CFGS; i++)
            srt_row(r, ss, light_name[li], opt.width, srt_cfgs[i].name, &jobs[nj - SRT_CFGS + i], ref, exact_ms,
                    exact_name);
        srt_speed_row(r, ss, light_name[li], opt.width, &jobs[nj - SRT_CFGS], ref, exact_ms, exact_name);

        if (li == 0) {
            /* The time-vs-error chart's points (tradeoff_chart): the SRT configurations. */
            for (i = 0; i < SRT_CFGS; i++) chart_point(ss, "SRT", srt_cfgs[i].name, &jobs[nj - SRT_CFGS + i], 9);

            /* What SRT can save: the reference's per-pixel cost by class. */
            if (ss->g.pos && ref) {
                pn_class_cost cc;
                char err[256], cb[4][48];
                double wt = 0.0, nt = 0.0;
                uint64_t lit = 0;
                const job *d = &jobs[nj - SRT_CFGS];
                if (pn_reference_class_cost(&ss->s.mesh, &ss->g, &lights[0], o->k, ss->s.eps, ss->cull_tol, &ss->h.threads,
                                            ref, &cc, err, sizeof(err)) == 0) {
                    for (i = 0; i < 3; i++) {
                        wt += cc.work[i];
                        nt += cc.ns[i];
                        lit += cc.pixels[i];
                    }
                    fmt_ratio(cb[0], sizeof(cb[0]), wt, cc.work[2]);
                    fmt_ratio(cb[1], sizeof(cb[1]), nt, cc.ns[2]);
                    fmt_ratio(cb[2], sizeof(cb[2]), exact_ms, job_pass(d));
                    fmt_ratio(cb[3], sizeof(cb[3]), ss->pt_ms[A_REF], d->st.srt.ns_exact / 1e6);
                    sec(r, SEC_SRT_BOUND,
                        "| %s | %llu | %.2f%% | %.2f%% | %.1f%% / %.1f%% / %.1f%% | %.1f%% / %.1f%% / %.1f%% | %s | %s | %s | %s | %s |\n",
                        ss->s.name, (unsigned long long)lit, lit ? 100.0 * cc.pixels[2] / (double)lit : 0.0,
                        d->st.lit_pixels ? 100.0 * d->st.srt.pip / (double)d->st.lit_pixels : 0.0,
                        wt > 0 ? 100.0 * cc.work[0] / wt : 0.0, wt > 0 ? 100.0 * cc.work[1] / wt : 0.0,
                        wt > 0 ? 100.0 * cc.work[2] / wt : 0.0, nt > 0 ? 100.0 * cc.ns[0] / nt : 0.0,
                        nt > 0 ? 100.0 * cc.ns[1] / nt : 0.0, nt > 0 ? 100.0 * cc.ns[2] / nt : 0.0, cb[0], cb[1], cb[3],
                        cb[2], cc.vis_agrees ? "yes" : "**no**");
                } else {
                    progress("    class cost: %s", err);
                }
            }
        }

        /* The second size: the fastest exact algorithm of this light and the default SRT. */
        if (o->srt_big && fastest_algo >= 0) {
            pn_frame_options ob = opt;
            ob.width = ob.height = o->srt_big;
            job_lib(&big[0], fastest_algo, &ob, 1);
            job_lib(&big[1], a_srt, &ob, 1);
            progress("  %s: SRT, %s light, %ux%u", ss->s.name, li ? "point" : "area", ob.width, ob.height);
            run_jobs(o, ss, big, 2, &lights[li]);
            if (li == 0) {
                ss->big_ms = job_pass(&big[0]);
                ss->big_name = exact_name;
            }
            srt_row(r, ss, light_name[li], ob.width, srt_cfgs[0].name, &big[1], big[0].vis, job_pass(&big[0]), exact_name);
            srt_speed_row(r, ss, light_name[li], ob.width, &big[1], big[0].vis, job_pass(&big[0]), exact_name);
            job_free(&big[0]);
            job_free(&big[1]);
        }
        for (i = 0; i < nj; i++) job_free(&jobs[i]);
    }
}

/* The header rows of the SRT tables. */
void srt_headers(report *r)
{
    sec(r, SEC_SRT_ACC,
        "| scene | light | size | configuration | PIP (%% of lit pixels) | thin triangles / texels marked | "
        "differing pixels (%% of all) | missing shadow | extra shadow | RMSE | max error | SRT ms | fastest exact ms | "
        "SRT vs fastest exact |\n"
        "| --- | --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_SRT_SPEED,
        "| scene | light | size | fastest exact | its ms | SRT ms | map / classify / exact ms | PIP (%% of lit) | "
        "differing pixels | SRT vs fastest exact |\n"
        "| --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_SRT_BOUND,
        "| scene | lit pixels | penumbra (%% of lit) | SRT's PIP (%% of lit) | reference work: lit / umbra / penumbra | "
        "reference time: lit / umbra / penumbra | bound (work) | bound (time) | reference vs SRT's exact stage | "
        "SRT vs fastest exact, measured | host kernel = reference |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n");
}

static const bench_note srt_notes[] = {
    {SEC_SRT_ACC, "## Selective ray tracing (issue 15): accuracy against the reference",
     "Every configuration's visibility against the reference's (area light: the main point's reference frame; point "
     "light: a reference frame of this section). Missing shadow: brighter than the reference; extra: darker. PIP pixels "
     "take the reference's own per-pixel path, so every differing pixel lies outside the PIP set (with the PIP set "
     "forced to every pixel the frame is byte-identical to the reference: tests/test_srt.c). The goal: at most 0.1% "
     "of pixels differing. Corner maps (the paper's union of masks from the light's corners) are not implemented. "
     "Fastest exact: the fastest of reference, GEARS and raytrace for that light in this run (at the second size, the "
     "one that was fastest at the first)."},
    {SEC_SRT_SPEED, "### SRT's speed against the fastest exact algorithm",
     "The default configuration. SRT ms is the median over the repetitions; the stages are the last "
     "repetition's, from `pn_stats` (srt.ns_map: window, shadow map, conservative marks, penumbra "
     "tiles; srt.ns_classify: classification and the PIP list; srt.ns_exact: the PIP pixels' exact masks). The issue's "
     "goal: at least 5x on every shared scene for soft shadows."},
    {SEC_SRT_BOUND, "### What SRT can save: the reference's cost by pixel class (area light)",
     "The library's per-pixel kernel (`pn_reference_pixel`) over a host BVH, each lit pixel timed alone and classed "
     "by its own visibility: lit (1), umbra (0), penumbra (in between). Work: BVH nodes tested + triangles handed to "
     "the predicate (deterministic); time: wall clock (noisy). Bound: with exact masks for the penumbra pixels only "
     "(a perfect PIP set) and a free shadow map, a selective ray tracer built on the reference's per-pixel path "
     "cannot be faster than all pixels' cost over the penumbra pixels' cost. The last column checks the host "
     "kernel's visibility against the library's reference frame."},
};

/* The SRT tables with their headings and notes (print_report). */
void srt_print(const report *r, FILE *out)
{
    print_tables(out, r, srt_notes, (int)(sizeof(srt_notes) / sizeof(srt_notes[0])));
}
