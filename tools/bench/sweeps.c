/* sweeps.c - GEARS' paper Tables 1-4 as analogues: on the sweep scenes (--sweep-scenes), the
 * cost of GEARS, the reference and Embree against the output resolution, the mask
 * resolution k, the light's size and GEARS' grid resolution; their tables, data files and
 * plots. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench.h"

/* ---- Sweeps: GEARS' paper Tables 1-4 as analogues -------------------------------------- */

enum { SW_RES, SW_K, SW_LIGHT, SW_GRID };

static const char *sweep_file[] = {"sweep_resolution", "sweep_k", "sweep_light", "sweep_grid"};

/* Rows of a sweep table, one cell per swept value. */
typedef struct rowset {
    char text[6][2048];
    int len[6];
} rowset;

static void row_add(rowset *rs, int i, const char *cell)
{
    rs->len[i] += snprintf(rs->text[i] + rs->len[i], sizeof(rs->text[i]) - (size_t)rs->len[i], " %s |", cell);
}

static void row_ms(rowset *rs, int i, double ms)
{
    char c[64];
    fmt_ms(c, sizeof(c), ms);
    row_add(rs, i, c);
}

static void row_ratio(rowset *rs, int i, double num, double den)
{
    char c[64];
    fmt_ratio(c, sizeof(c), num, den);
    row_add(rs, i, c);
}

/* One sweep over one scene: per value, GEARS, the reference and Embree (the API that won
 * at the main point), interleaved; the grid sweep runs every grid in one set of jobs
 * (reference and Embree do not depend on it) plus one exact-statistics GEARS frame per
 * grid for the necessary/total column. */
void sweep(const bench_opts *o, report *r, scene_state *ss, int kind, pn_embree_api api)
{
    char data[8192], cell[64];
    rowset rs;
    int dl = 0, v, nv, i;
    const char *labels[6];
    int nrows = 3;
    pn_frame_options base;
    memset(&rs, 0, sizeof(rs));
    base_options(o, ss, &base);
    nv = kind == SW_RES ? (int)o->n_res : kind == SW_K ? (int)o->n_k : kind == SW_LIGHT ? (int)o->n_light : (int)o->n_grid;
    dl += snprintf(data + dl, sizeof(data) - (size_t)dl, "# %s %s: value gears_ms reference_ms embree_ms%s\n",
                   sweep_file[kind], ss->s.name, kind == SW_GRID ? " necessary_pct" : "");
    labels[0] = "GEARS ms";
    labels[1] = "reference ms";
    labels[2] = "Embree ms";
    if (kind == SW_GRID) {
        labels[3] = "necessary / total";
        labels[4] = "tris per cell, max / mean";
        labels[5] = "GEARS vs Embree";
        nrows = 6;
    } else {
        labels[3] = "GEARS vs reference";
        labels[4] = "GEARS vs Embree";
        nrows = 5;
    }
    if (kind == SW_GRID) {
        job jobs[10];
        int nj = 0, reps;
        pn_stats xs[8];
        for (v = 0; v < nv; v++) {
            job_lib(&jobs[nj], A_GEARS, &base, 0);
            jobs[nj].opt.gears.grid = o->sweep_grid[v];
            nj++;
        }
        /* The reference first in the array would give the G-buffer before Embree needs it. */
        job_lib(&jobs[nj++], A_REF, &base, 0);
        job_emb(&jobs[nj++], api, &base, 0);
        {
            job t = jobs[0];
            jobs[0] = jobs[nv];
            jobs[nv] = t;
        }
        progress("  %s: grid sweep", ss->s.name);
        reps = run_jobs(o, ss, jobs, nj, &ss->s.light);
        (void)reps;
        for (v = 0; v < nv; v++) {
            job x;
            job_lib(&x, A_GEARS, &base, 0);
            x.opt.gears.grid = o->sweep_grid[v];
            x.opt.exact_stats = 1;
            job_run(ss, &x, &ss->s.light, 1);
            if (x.ok) xs[v] = x.st;
            else memset(&xs[v], 0, sizeof(xs[v]));
        }
        for (v = 0; v < nv; v++) {
            const job *g = v == 0 ? &jobs[nv] : &jobs[v];
            double gm = job_pass(g), rm = job_pass(&jobs[0]), em = job_pass(&jobs[nv + 1]);
            double pct = xs[v].gears.assignments ? 100.0 * (double)xs[v].shadow_blocking / (double)xs[v].gears.assignments : NAN;
            row_ms(&rs, 0, gm);
            row_ms(&rs, 1, rm);
            row_ms(&rs, 2, em);
            if (pct == pct) snprintf(cell, sizeof(cell), "%.1f%%", pct);
            else snprintf(cell, sizeof(cell), "n/a");
            row_add(&rs, 3, cell);
            snprintf(cell, sizeof(cell), "%u / %.1f", xs[v].gears.max_tris_per_cell, xs[v].gears.mean_tris_per_cell);
            row_add(&rs, 4, cell);
            row_ratio(&rs, 5, em, gm);
            dl += snprintf(data + dl, sizeof(data) - (size_t)dl, "%u %.4f %.4f %.4f %.3f\n", o->sweep_grid[v], gm, rm,
                           em, pct);
        }
        for (i = 0; i < nj; i++) job_free(&jobs[i]);
    } else {
        for (v = 0; v < nv; v++) {
            job jobs[3];
            pn_frame_options opt = base;
            pn_light light = ss->s.light;
            double gm, rm, em;
            float value = 0.0f;
            if (kind == SW_RES) {
                opt.width = opt.height = o->sweep_res[v];
                value = (float)o->sweep_res[v];
            } else if (kind == SW_K) {
                opt.k = o->sweep_k[v];
                value = (float)o->sweep_k[v];
            } else {
                /* Relative diagonal d: half-edges x d/2, so d = 2 is the default light (the
                 * paper's default column too). */
                scaled_light(&ss->s.light, o->sweep_light[v] * 0.5f, &light);
                value = o->sweep_light[v];
            }
            job_lib(&jobs[0], A_REF, &opt, 0);
            job_lib(&jobs[1], A_GEARS, &opt, 0);
            job_emb(&jobs[2], api, &opt, 0);
            progress("  %s: %s = %g", ss->s.name, sweep_file[kind], value);
            run_jobs(o, ss, jobs, 3, &light);
            rm = job_pass(&jobs[0]);
            gm = job_pass(&jobs[1]);
            em = job_pass(&jobs[2]);
            row_ms(&rs, 0, gm);
            row_ms(&rs, 1, rm);
            row_ms(&rs, 2, em);
            row_ratio(&rs, 3, rm, gm);
            row_ratio(&rs, 4, em, gm);
            dl += snprintf(data + dl, sizeof(data) - (size_t)dl, "%g %.4f %.4f %.4f\n", value, gm, rm, em);
            for (i = 0; i < 3; i++) {
                if (!jobs[i].ok) progress("    %s", jobs[i].err);
                job_free(&jobs[i]);
            }
        }
    }
    for (i = 0; i < nrows; i++)
        sec(r, SEC_RES + kind, "| %s | %s |%s\n", i == 0 ? ss->s.name : "", labels[i], rs.text[i]);
    write_data(o, sweep_file[kind], ss->s.name, data);
}

/* The header rows: one column per swept value. */
void sweep_headers(report *r, const bench_opts *o)
{
    int s, v;
    for (s = SEC_RES; s <= SEC_GRID; s++) {
        const uint32_t *vals = s == SEC_RES ? o->sweep_res : s == SEC_K ? o->sweep_k : o->sweep_grid;
        int nv = s == SEC_RES ? (int)o->n_res : s == SEC_K ? (int)o->n_k : s == SEC_LIGHT ? (int)o->n_light : (int)o->n_grid;
        sec(r, s, "| scene | |");
        for (v = 0; v < nv; v++) {
            if (s == SEC_RES) sec(r, s, " %ux%u |", vals[v], vals[v]);
            else if (s == SEC_K) sec(r, s, " %ux%u |", vals[v], vals[v]);
            else if (s == SEC_LIGHT) sec(r, s, " %g |", o->sweep_light[v]);
            else sec(r, s, " %ux%u |", vals[v], vals[v]);
        }
        sec(r, s, "\n| --- | --- |");
        for (v = 0; v < nv; v++) sec(r, s, " ---: |");
        sec(r, s, "\n");
    }
}

void plot_sweeps(report *r, const bench_opts *o)
{
    static const char *xlabel[] = {"output resolution (pixels per side)", "mask resolution k (k x k samples)",
                                   "relative light diagonal (2 = default light)", "GEARS grid resolution (cells per side)"};
    int kind, i;
    if (r->sweep_scenes == 0) return;
    for (kind = 0; kind < 4; kind++) {
        char title[160];
        if (kind == SW_RES) snprintf(title, sizeof(title), "cost vs output resolution (k = %u, grid %u)", o->k, o->grid);
        else if (kind == SW_K) snprintf(title, sizeof(title), "cost vs mask resolution (%ux%u, grid %u)", o->size, o->size, o->grid);
        else if (kind == SW_LIGHT)
            snprintf(title, sizeof(title), "cost vs light size (%ux%u, k = %u, grid %u)", o->size, o->size, o->k, o->grid);
        else snprintf(title, sizeof(title), "cost vs GEARS grid resolution (%ux%u, k = %u)", o->size, o->size, o->k);
        fprintf(r->plots, "\n# %s\nset terminal pngcairo noenhanced size 900,560 font 'sans,10'\nset output '%s.png'\n",
                sweep_file[kind], sweep_file[kind]);
        fprintf(r->plots, "set title '%s'\nset xlabel '%s'\nset ylabel 'shadow pass ms (median)'\nset logscale y\n"
                          "set grid\nset key outside right top\n%s",
                title, xlabel[kind], kind == SW_K || kind == SW_GRID ? "set logscale x 2\n" : "unset logscale x\n");
        fprintf(r->plots, "plot ");
        for (i = 0; i < r->sweep_scenes; i++) {
            const char *s = r->sweep_names[i];
            fprintf(r->plots,
                    "%s'data/%s_%s.dat' using 1:2 with linespoints lw 2 pt 7 lc %d title '%s GEARS', "
                    "'' using 1:3 with linespoints dt 2 pt 6 lc %d title '%s reference', "
                    "'' using 1:4 with linespoints dt 3 pt 4 lc %d title '%s Embree'",
                    i ? ", \\\n     " : "", sweep_file[kind], s, i + 1, s, i + 1, s, i + 1, s);
        }
        fprintf(r->plots, "\nunset logscale x\nunset logscale y\n");
    }
}

/* The four tables, each with its plot (print_report, after the Embree table). */
void sweeps_print(const report *r, FILE *out, int threads)
{
    static const char *sweep_title[] = {"Cost vs output resolution (paper Table 1)", "Cost vs mask resolution k (paper Table 2)",
                                        "Cost vs light size (paper Table 3)", "Cost vs GEARS grid resolution (paper Table 4)"};
    int kind;
    for (kind = SW_RES; kind <= SW_GRID; kind++) {
        int sw = SEC_RES + kind;
        fprintf(out, "## %s\n\n", sweep_title[kind]);
        if (r->sweep_scenes)
            fprintf(out, "%s\n![%s](%s.png)\n\n", r->buf[sw], sweep_title[kind], sweep_file[kind]);
        else fprintf(out, "(no sweep scenes in this run)\n\n");
        if (sw == SEC_GRID)
            fprintf(out, "Shadow pass ms, medians; %d threads. Light diagonal d scales the default light's "
                         "half-edges by d / 2, so 2 is the default light (as in the paper, whose default column "
                         "is 2).\n\n",
                    threads);
    }
}
