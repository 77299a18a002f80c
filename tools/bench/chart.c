/* chart.c - what the approximate algorithms' sections share (which algorithm a section is
 * for, the fastest exact algorithm, the k = 32 reference, light leaks) and the
 * time-vs-error chart: its points, its front, its plot and its place in the report. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

/* ---- Shared by the approximate algorithms' sections ---------------------------------------- */

/* Index in algos[] of the algorithm whose section this is, or -1 when it is not compiled in
 * or not selected (--algos): then its section is left out. */
int section_algo(const bench_opts *o, pn_algo algo)
{
    int a;
    for (a = 0; a < NALGO; a++)
        if (algos[a].algo == algo)
            return (pn_build_info() & algos[a].build_flag) && in_list(o->algos, algos[a].name) ? a : -1;
    return -1;
}

/* The fastest exact algorithm among per-algorithm shadow-pass medians (NaN: not run);
 * -1: none. */
int fastest_exact(const double *ms)
{
    int a, best = -1;
    for (a = 0; a < NALGO; a++)
        if (algos[a].exact && ms[a] == ms[a] && (best < 0 || ms[a] < ms[best])) best = a;
    return best;
}

/* The reference's visibility at k = 32, the main point's size, area light: rendered once per
 * scene (one frame: only its bits are used) for the sections that measure an approximate
 * algorithm's own error, not the k = 16 reference's. NULL when it failed (ss->ref32_err). */
const float *ref32(const bench_opts *o, scene_state *ss)
{
    pn_frame_options opt;
    job j;
    if (ss->ref32_done) return ss->ref32_vis;
    ss->ref32_done = 1;
    base_options(o, ss, &opt);
    job_lib(&j, A_REF, &opt, 1);
    j.opt.k = 32;
    progress("  %s: reference at k = 32", ss->s.name);
    job_run(ss, &j, &ss->s.light, 0);
    if (!j.ok) snprintf(ss->ref32_err, sizeof(ss->ref32_err), "%s", j.err);
    ss->ref32_vis = j.vis;
    ss->ref32_rgba = j.rgba;
    j.vis = NULL;
    j.rgba = NULL;
    job_free(&j);
    return ss->ref32_vis;
}

/* Pixels of a at least 0.25 brighter than ref: light leaks (a shadow that light shines
 * through, not a penumbra's slope); with the arguments swapped, pixels 0.25 too dark. */
size_t px_brighter(const float *a, const float *ref, size_t n)
{
    size_t i, c = 0;
    if (!a || !ref) return 0;
    for (i = 0; i < n; i++) c += a[i] > ref[i] + 0.25f;
    return c;
}

static void front_add(char *b, size_t n, size_t *len, const char *name)
{
    int w;
    if (*len >= n) return;
    w = snprintf(b + *len, n - *len, "%s%s", *len ? ", " : "no: ", name);
    if (w > 0) *len += (size_t)w;
}

/* Whether (ms, rmse) lies on the front of the time-vs-error chart: no algorithm at the main
 * point but `self`, not Embree, and no configuration point (ss->xpt) whose label does not
 * start with `own` is both faster and more accurate. b: "yes", or "no: " and the points that
 * are ("n/a" without a time or an error). */
int chart_front(const scene_state *ss, int self, const char *own, double ms, double rmse, char *b, size_t n)
{
    size_t len = 0, lo = strlen(own);
    int a, i;
    if (!(ms == ms) || !(rmse == rmse)) {
        snprintf(b, n, "n/a");
        return 0;
    }
    for (a = 0; a < NALGO; a++)
        if (a != self && ss->pt_ms[a] == ss->pt_ms[a] && ss->pt_ms[a] < ms && (a == A_REF ? 0.0 : ss->pt_rmse[a]) < rmse)
            front_add(b, n, &len, algos[a].name);
    if (ss->emb_ms == ss->emb_ms && ss->emb_ms < ms && ss->emb_rmse < rmse) front_add(b, n, &len, "Embree");
    for (i = 0; i < ss->nxpt; i++)
        if (strncmp(ss->xpt[i].label, own, lo) != 0 && ss->xpt[i].ms < ms && ss->xpt[i].rmse < rmse)
            front_add(b, n, &len, ss->xpt[i].label);
    if (len == 0) snprintf(b, n, "yes");
    return len == 0;
}

/* Adds a configuration's point to the time-vs-error chart (its RMSE against the main point's
 * reference). */
void chart_point(scene_state *ss, const char *algo, const char *cfg, const job *j, int pt)
{
    size_t n = (size_t)j->opt.width * j->opt.height;
    accuracy acc = compare_vis(j->vis, ss->ref_vis, n);
    if (!j->ok || !acc.ok || ss->nxpt >= (int)(sizeof(ss->xpt) / sizeof(ss->xpt[0]))) return;
    snprintf(ss->xpt[ss->nxpt].label, sizeof(ss->xpt[ss->nxpt].label), "%s %s", algo, cfg);
    ss->xpt[ss->nxpt].ms = job_pass(j);
    ss->xpt[ss->nxpt].rmse = acc.rmse;
    ss->xpt[ss->nxpt].pt = pt;
    ss->nxpt++;
}

/* ---- The time-vs-error chart: every algorithm at the main point, Embree, and the extra
 * configurations the sections added (ss->xpt) ----------------------------------------------- */

void tradeoff_chart(const bench_opts *o, report *r, scene_state *ss)
{
    char *text = NULL, label[NALGO + 1 + XPT_MAX][96];
    int pt[NALGO + 1 + XPT_MAX], np = 0, a, i;
    size_t tl = 0;
    FILE *t;
    if (!ss->ref_vis) return;
    t = open_memstream(&text, &tl);
    if (!t) return;
    /* One point a line; the plot gives each its own colour, symbol (exact: circle, Embree:
     * square, configurations: their section's) and legend entry. */
    fprintf(t, "# label shadow_ms rmse (%ux%u, k = %u, area light)\n", o->size, o->size, o->k);
    for (a = 0; a < NALGO; a++)
        if (ss->pt_ms[a] == ss->pt_ms[a] && algos[a].algo != PN_ALGO_SRT && algos[a].algo != PN_ALGO_OCCTEX &&
            algos[a].algo != PN_ALGO_MCSM && algos[a].algo != PN_ALGO_WEDGES) {
            fprintf(t, "\"%s\" %.6g %.6g\n", algos[a].name, ss->pt_ms[a], a == A_REF ? 0.0 : ss->pt_rmse[a]);
            snprintf(label[np], sizeof(label[np]), "%s", algos[a].name);
            pt[np++] = algos[a].exact ? 7 : 13;
        }
    if (ss->emb_ms == ss->emb_ms) {
        fprintf(t, "\"Embree rtcOccluded%s\" %.6g %.6g\n", ss->emb_api, ss->emb_ms, ss->emb_rmse);
        snprintf(label[np], sizeof(label[np]), "Embree rtcOccluded%s", ss->emb_api);
        pt[np++] = 5;
    }
    for (i = 0; i < ss->nxpt; i++) {
        fprintf(t, "\"%s\" %.6g %.6g\n", ss->xpt[i].label, ss->xpt[i].ms, ss->xpt[i].rmse);
        snprintf(label[np], sizeof(label[np]), "%s", ss->xpt[i].label);
        pt[np++] = ss->xpt[i].pt;
    }
    fclose(t);
    write_data(o, "tradeoff", ss->s.name, text);
    free(text);
    fprintf(r->plots,
            "\n# time against error: %s\nset terminal pngcairo noenhanced size 1280,560 font 'sans,9'\n"
            "set output 'tradeoff_%s.png'\nset title '%s: shadow pass time against error (%ux%u, k = %u, "
            "area light)'\nset xlabel 'shadow pass ms (median, log scale)'\nset logscale x\n"
            "set ylabel 'RMSE of the visibility against the reference'\nset yrange [0:*]\n"
            "set offsets graph 0.1, graph 0.1, graph 0.1, graph 0.04\nset grid\n"
            "set key outside right top\nplot",
            ss->s.name, ss->s.name, ss->s.name, o->size, o->size, o->k);
    for (i = 0; i < np; i++)
        fprintf(r->plots, "%s 'data/tradeoff_%s.dat' every ::%d::%d using 2:3 with points pt %d ps 1.6 lc %d "
                          "title '%s'",
                i ? ", \\\n    " : "", ss->s.name, i, i, pt[i], i + 1, label[i]);
    /* Nothing of the chart's settings may reach the plots after it (the next scene's gallery). */
    fprintf(r->plots, "\nunset logscale x\nset yrange [*:*]\nset offsets 0,0,0,0\nreset\n");
    sec(r, SEC_SRT_CHART, "![%s: time against error](tradeoff_%s.png)\n", ss->s.name, ss->s.name);
}

/* The charts' section (print_report, after the approximate algorithms' sections). */
void chart_print(const report *r, const bench_opts *o, FILE *out)
{
    fprintf(out, "## Time against error\n\nPer scene, %ux%u, k = %u, area light: each algorithm's shadow pass "
                 "(median, this run) against the RMSE of its visibility to the reference's. Exact algorithms sit at 0; "
                 "Embree traces the same samples and differs only in its arithmetic. Every algorithm and its main "
                 "configurations is a point: the picture to choose an algorithm from.\n\n%s\n",
            o->size, o->size, o->k, r->len[SEC_SRT_CHART] ? r->buf[SEC_SRT_CHART] : "(no SRT section in this run)\n");
}
