/* occtex.c - occlusion textures (issue 17): the paper's claims against a k = 32 reference,
 * speed against the other algorithms, cost against the light's size. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* ---- Occlusion textures (issue 17) ---------------------------------------------------------- */

/* The configurations measured: the default (what --algo occtex renders; on `square` it is
 * the paper's exact case set-up) and one change of it at a time. */
#define OCC_CFGS 9
#define OCC_CFG_8 6 /* the speed goal is for 8 slices */
static const struct {
    const char *name;
    uint32_t filter, combine, slices, flags;
} occ_cfgs[OCC_CFGS] = {
    {"default (summed-area table, product, 16 slices, depth map, no leak fix)", 0u, 0u, 0u, 0u},
    {"max", 0u, PN_OCC_COMBINE_MAX, 0u, 0u},
    {"clamped sum", 0u, PN_OCC_COMBINE_SUM, 0u, 0u},
    {"N-buffer", PN_OCC_FILTER_NBUFFER, 0u, 0u, 0u},
    {"mipmap", PN_OCC_FILTER_MIPMAP, 0u, 0u, 0u},
    {"4 slices", 0u, 0u, 4u, 0u},
    {"8 slices", 0u, 0u, 8u, 0u},
    {"leak fix", 0u, 0u, 0u, PN_OCC_LEAK_FIX},
    {"fade alone, no depth map (the paper)", 0u, 0u, 0u, PN_OCC_PAPER_FADE},
};
#define OCC_LIGHTS 5
static const float occ_light_scale[OCC_LIGHTS] = {0.25f, 0.5f, 1.0f, 2.0f, 4.0f};

static void occ_stages(char *b, size_t n, const job *j)
{
    char c[3][20];
    fmt_ms(c[0], sizeof(c[0]), j->st.occtex.ns_slice / 1e6);
    fmt_ms(c[1], sizeof(c[1]), j->st.occtex.ns_filter / 1e6);
    fmt_ms(c[2], sizeof(c[2]), j->st.occtex.ns_lookup / 1e6);
    snprintf(b, n, "%s / %s / %s", c[0], c[1], c[2]);
}

void occ_section(const bench_opts *o, report *r, scene_state *ss)
{
    pn_frame_options opt;
    job jobs[OCC_CFGS], cfg16[OCC_CFGS], big, lights[OCC_LIGHTS];
    int i, a, a_occ = section_algo(o, PN_ALGO_OCCTEX), fastest;
    size_t n;
    double occ_ms, occ_rmse;
    const float *ref;
    char c[8][64];
    base_options(o, ss, &opt);
    n = (size_t)opt.width * opt.height;
    if (a_occ < 0) return;

    /* Claims: every configuration against a k = 32 reference (the paper's claims are about
     * the filtered occlusion; a finer reference shows its error, not the reference's). */
    ref = ref32(o, ss);
    for (i = 0; i < OCC_CFGS; i++) {
        job_lib(&jobs[i], a_occ, &opt, 1);
        jobs[i].opt.k = 32;
        jobs[i].opt.occtex.filter = occ_cfgs[i].filter;
        jobs[i].opt.occtex.combine = occ_cfgs[i].combine;
        jobs[i].opt.occtex.slices = occ_cfgs[i].slices;
        jobs[i].opt.occtex.flags = occ_cfgs[i].flags;
        cfg16[i] = jobs[i];
        cfg16[i].opt.k = opt.k;
    }
    progress("  %s: occlusion textures, %d configurations at k = 32", ss->s.name, OCC_CFGS);
    run_jobs(o, ss, jobs, OCC_CFGS, &ss->s.light);
    for (i = 0; i < OCC_CFGS; i++) {
        const job *j = &jobs[i];
        accuracy acc = compare_vis(j->vis, ref, n);
        if (!j->ok || !acc.ok) {
            sec(r, SEC_OCC_CLAIMS, "| %s | %s | n/a | n/a | n/a | n/a | n/a | %s |\n", ss->s.name, occ_cfgs[i].name,
                j->ok ? ss->ref32_err : j->err);
            continue;
        }
        fmt_ms(c[0], sizeof(c[0]), job_pass(j));
        occ_stages(c[1], sizeof(c[1]), j);
        sec(r, SEC_OCC_CLAIMS, "| %s | %s | %.5f | %.4f | %zu | %s | %s | %llu / %llu |\n", ss->s.name,
            occ_cfgs[i].name, acc.rmse, acc.max_err, px_brighter(j->vis, ref, n), c[0], c[1],
            (unsigned long long)j->st.occtex.texels_set, (unsigned long long)j->st.occtex.lookups);
    }
    /* Where the default errs: its error against the k = 32 reference as a heat map. */
    if (jobs[0].ok) error_heat(o, r, SEC_OCC_MAPS, ss, "occ_heat", "the default", jobs[0].vis, ref, opt.width, opt.height);
    for (i = 0; i < OCC_CFGS; i++) job_free(&jobs[i]);

    /* The configurations at the main point's k against its reference: the chart's points. */
    progress("  %s: occlusion textures, %d configurations at k = %u", ss->s.name, OCC_CFGS, opt.k);
    run_jobs(o, ss, cfg16, OCC_CFGS, &ss->s.light);
    for (i = 0; i < OCC_CFGS; i++) chart_point(ss, "occtex", occ_cfgs[i].name, &cfg16[i], 11);

    /* Speed at the main point: against the fastest exact algorithm of the same run, and
     * whether anything on the chart is both faster and more accurate. */
    fastest = fastest_exact(ss->pt_ms);
    occ_ms = job_pass(&cfg16[0]);
    occ_rmse = compare_vis(cfg16[0].vis, ss->ref_vis, n).rmse;
    {
        char front[512];
        chart_front(ss, a_occ, "occtex", occ_ms, occ_rmse, front, sizeof(front));
        fmt_ms(c[0], sizeof(c[0]), fastest >= 0 ? ss->pt_ms[fastest] : NAN);
        fmt_ms(c[1], sizeof(c[1]), occ_ms);
        occ_stages(c[2], sizeof(c[2]), &cfg16[0]);
        fmt_ratio(c[3], sizeof(c[3]), fastest >= 0 ? ss->pt_ms[fastest] : NAN, occ_ms);
        {
            double best_other = NAN;
            const char *bo = "none";
            for (a = 0; a < NALGO; a++)
                if (a != a_occ && ss->pt_ms[a] == ss->pt_ms[a] && !(best_other <= ss->pt_ms[a])) {
                    best_other = ss->pt_ms[a];
                    bo = algos[a].name;
                }
            fmt_ratio(c[4], sizeof(c[4]), best_other, occ_ms);
            fmt_ms(c[5], sizeof(c[5]), job_pass(&cfg16[OCC_CFG_8]));
            fmt_ratio(c[6], sizeof(c[6]), best_other, job_pass(&cfg16[OCC_CFG_8]));
            sec(r, SEC_OCC_SPEED, "| %s | %u | %ux%u | %s | %s | %s | %s | %s | %s (%s) | %s / %s | %.4f | %s |\n",
                ss->s.name, ss->s.mesh.triangle_count, opt.width, opt.height, fastest >= 0 ? algos[fastest].name : "none",
                c[0], c[1], c[2], c[3], c[4], bo, c[5], c[6], occ_rmse, front);
        }
    }
    for (i = 0; i < OCC_CFGS; i++) job_free(&cfg16[i]);

    /* The second size against the SRT section's fastest exact algorithm there. */
    if (o->srt_big) {
        pn_frame_options ob = opt;
        ob.width = ob.height = o->srt_big;
        job_lib(&big, a_occ, &ob, 0);
        progress("  %s: occlusion textures, %ux%u", ss->s.name, ob.width, ob.height);
        run_jobs(o, ss, &big, 1, &ss->s.light);
        fmt_ms(c[0], sizeof(c[0]), ss->big_ms);
        fmt_ms(c[1], sizeof(c[1]), job_pass(&big));
        occ_stages(c[2], sizeof(c[2]), &big);
        fmt_ratio(c[3], sizeof(c[3]), ss->big_ms, job_pass(&big));
        sec(r, SEC_OCC_SPEED, "| %s | %u | %ux%u | %s | %s | %s | %s | %s | n/a | n/a | n/a | n/a |\n", ss->s.name,
            ss->s.mesh.triangle_count, ob.width, ob.height, ss->big_name ? ss->big_name : "n/a", c[0], c[1], c[2], c[3]);
        job_free(&big);
    }

    /* Light size: the default at the main point with the light scaled. */
    for (i = 0; i < OCC_LIGHTS; i++) job_lib(&lights[i], a_occ, &opt, 0);
    {
        int len;
        char row[1024];
        len = snprintf(row, sizeof(row), "| %s |", ss->s.name);
        for (i = 0; i < OCC_LIGHTS; i++) {
            pn_light L;
            scaled_light(&ss->s.light, occ_light_scale[i], &L);
            run_jobs(o, ss, &lights[i], 1, &L);
            fmt_ms(c[0], sizeof(c[0]), job_pass(&lights[i]));
            occ_stages(c[1], sizeof(c[1]), &lights[i]);
            len += snprintf(row + len, sizeof(row) - (size_t)len, " %s (%s) |", c[0], c[1]);
        }
        sec(r, SEC_OCC_LIGHT, "%s\n", row);
    }
}

/* The header rows of the occlusion-texture tables. */
void occ_headers(report *r, const bench_opts *o)
{
    int v;
    sec(r, SEC_OCC_CLAIMS,
        "| scene | configuration | RMSE | max error | light leaks (pixels >= 0.25 brighter) | ms | "
        "slice / filter / lookup ms | bits set / lookups |\n"
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_OCC_SPEED,
        "| scene | triangles | size | fastest exact | its ms | occtex ms | slice / filter / lookup ms | "
        "occtex vs fastest exact | occtex vs fastest other | 8 slices: ms / vs fastest other | RMSE (k = %u) | "
        "on the chart's front |\n"
        "| --- | ---: | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n",
        o->k);
    sec(r, SEC_OCC_LIGHT, "| scene |");
    for (v = 0; v < OCC_LIGHTS; v++) sec(r, SEC_OCC_LIGHT, " light x %g: ms (slice / filter / lookup) |", occ_light_scale[v]);
    sec(r, SEC_OCC_LIGHT, "\n| --- |");
    for (v = 0; v < OCC_LIGHTS; v++) sec(r, SEC_OCC_LIGHT, " ---: |");
    sec(r, SEC_OCC_LIGHT, "\n");
}

static const bench_note occ_notes[] = {
    {SEC_OCC_CLAIMS, "## Occlusion textures (issue 17): the paper's claims",
     "Every configuration against a k = 32 reference at the main point's size (area light): the default (what "
     "`--algo occtex` renders; on `square`, one planar occluder parallel to the light, it is the paper's exact "
     "case, §3.1) and one change of it per row. ms: the shadow pass's median; the stages are the last repetition's "
     "(slice: window, planes, rasterization of every triangle into the slices; filter: every slice's N-buffer, "
     "table or mipmap; lookup: every slice's lookups and the combination). Light leaks: pixels at least 0.25 "
     "brighter than the reference."},
    {SEC_OCC_SPEED, "### Occlusion textures: speed against the other algorithms",
     "The default configuration at the main point (k as in the headline) and at the SRT section's second size. "
     "Fastest exact: of reference, GEARS and raytrace in this run; fastest other: of every other algorithm of the "
     "library. On the chart's front: no point of the time-vs-error chart (every algorithm, Embree, the SRT, "
     "occlusion-texture, MCSM and penumbra-wedge configurations) is both faster and more accurate; otherwise the "
     "points that are. The issue's goal: faster than every other algorithm on every shared scene, on the front on "
     "half of the scenes."},
    {SEC_OCC_LIGHT, "### Occlusion textures: cost against light size",
     "The default at the main point with the light's half-edges scaled (1: the scene's light). The paper claims "
     "the cost does not depend on the light's size."},
    {SEC_OCC_MAPS, "### Occlusion textures: where the default errs", HEAT_NOTE},
};

/* The occlusion-texture tables with their headings and notes (print_report). */
void occ_print(const report *r, FILE *out)
{
    print_tables(out, r, occ_notes, (int)(sizeof(occ_notes) / sizeof(occ_notes[0])));
}
