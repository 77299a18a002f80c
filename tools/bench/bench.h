/* bench.h - what the files of penumbra_bench (tools/bench/, the benchmark of issue 5: main.c
 * says what it measures and how) share: the options, the jobs and the scene state they run
 * on, the report's sections, the tables of algorithms, ports and baselines (jobs.c), and
 * the functions one file calls in another. Everything else stays static in its file.
 *
 * The files, by what they hold:
 *   main.c        the options, the scene loop, writing RESULTS.md and plots.gp
 *   jobs.c        what is measured (algorithms, ports, baselines), jobs and their repetitions,
 *                 medians and number formats, accuracy against a reference, a scene's set-up
 *   report.c      the report's sections and its frame (print_report: the header, the headline,
 *                 the gallery; the order of the sections), and the summary
 *   main_point.c  the main point: the per-port, Embree, headline, grid-efficiency, memory,
 *                 accuracy and mask tables, the gallery, the headline plot
 *   sweeps.c      GEARS' sweeps (paper Tables 1-4) and their plots
 *   chart.c       what the approximate algorithms' sections share, the time-vs-error chart and
 *                 its front
 *   srt.c, occtex.c, mcsm.c, wedges.c: one approximate algorithm's section each
 * A file that fills a table owns it: it writes the table's header rows (its *_headers, called
 * by report_open), its rows scene by scene, and its heading and note (its *_print, called by
 * print_report in the report's order). */
#ifndef PN_TOOLS_BENCH_BENCH_H
#define PN_TOOLS_BENCH_BENCH_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "penumbra/penumbra.h"
#include "pn_bench.h"
#include "pn_setup.h"

/* ---- What is measured: algorithms and ports ------------------------------------------- */

typedef struct bench_algo {
    const char *name;
    pn_algo algo;
    uint32_t build_flag;
    int exact;     /* must match the reference bit for bit */
    int all_ports; /* 0: measured on the first port only (a baseline, not a product) */
} bench_algo;

/* Every algorithm of the library (jobs.c), indexed by pn_algo (the registry's order,
 * src/pn_algorithms.h): the table adds what the benchmark prints and measures of each. */
extern const bench_algo algos[];
#define NALGO PN_ALGO_COUNT
#define A_REF PN_ALGO_REFERENCE
#define A_GEARS PN_ALGO_GEARS
#define A_RT PN_ALGO_RAYTRACE

/* A port renders a frame on a context that already holds the scene. The scalar port is
 * pn_render with the host's parallel-for at `threads`; a port with a device of its own
 * (the OpenCL port: pn_opencl_create in attach, pn_opencl_render in render,
 * pn_opencl_destroy in detach) adds its three functions and one line to `ports`. */
typedef struct bench_port {
    const char *name;
    int threads; /* host threads for the port and for Embree beside it; 0: all cores */
    int (*attach)(pn_host *h, void **state, char *err, size_t err_size);
    pn_status (*render)(pn_host *h, void *state, const pn_camera *cam, const pn_light *light,
                        const pn_frame_options *opt, pn_frame *out);
    void (*detach)(void *state);
} bench_port;

/* jobs.c; NPORT entries. */
extern const bench_port ports[];
#if PN_BENCH_OPENCL
#define NPORT 3
#else
#define NPORT 2
#endif

/* Ports with a device of their own name it here, for the report's header. */
extern char port_devices[256]; /* jobs.c */

/* ---- Options ---------------------------------------------------------------------------- */

#define MAX_REPS 15
#define MAX_SCENES 64

typedef struct bench_opts {
    const char *out_dir;
    const char *scenes_dir;
    const char *only;         /* comma list, NULL: all */
    const char *sweep_scenes; /* comma list */
    const char *label;
    const char *algos;        /* comma list of algorithm names and "embree"; NULL: all */
    int nports;               /* the first nports entries of ports[] */
    int lean;                 /* no exact-statistics frame, masks or gallery (profiling) */
    int quick;
    int threads; /* all cores when 0 */
    int reps, reps_slow;  /* repetitions; reps_slow when one repetition takes > slow_s */
    double slow_s;
    uint32_t size, k, grid;
    uint32_t srt_big; /* the SRT section's second image size (0: no SRT section) */
    uint32_t mc_map[6], n_mc_map;       /* the MCSM speed table's depth-layer resolutions */
    uint32_t mc_screen[4], n_mc_screen; /* ...and its image sizes */
    uint32_t mc_map_max;                /* the largest of them this build allows */
    int mc_map_cut;                     /* map sizes left out: pn_limits do not allow them */
    uint32_t sweep_res[8], n_res, sweep_k[8], n_k, sweep_grid[8], n_grid;
    float sweep_light[8];
    uint32_t n_light;
    uint32_t wg_spheres[9], n_wg_spheres; /* the wedges' triangle sweep: spheres kept of 81 */
} bench_opts;

/* ---- Jobs: one timed thing inside a repetition ------------------------------------------ */

/* JOB_EMBREE_BUILD_HIGH: Embree's build at RTC_BUILD_QUALITY_HIGH (issue 51's bar for the
 * build's time); the passes trace the default build's tree, which the jobs build after it. */
enum { JOB_LIB, JOB_EMBREE, JOB_SCENE_SET, JOB_EMBREE_BUILD, JOB_EMBREE_BUILD_HIGH, JOB_PCSS };
/* The baselines a user would pick instead of an approximate algorithm, measured beside
 * every algorithm at the main point (jobs.c: baselines[] says which). */
enum { BL_REF4, BL_REF8, BL_PCSS, NBASE };
typedef struct bench_baseline {
    const char *name;
    uint32_t k; /* reference samples per side; 0: PCSS */
    int pt;     /* the chart's point type */
} bench_baseline;
extern const bench_baseline baselines[NBASE];

/* The summary's rows: every algorithm, then the baselines, then Embree. */
#define NSUM (NALGO + NBASE + 1)
#define XPT_MAX 40

typedef struct job {
    int kind;
    int algo;              /* JOB_LIB: index into algos */
    pn_embree_api api;     /* JOB_EMBREE */
    pn_frame_options opt;  /* JOB_LIB, and k for JOB_EMBREE */
    int keep;              /* keep the first repetition's visibility (and image) */
    /* results */
    double pass[MAX_REPS], total[MAX_REPS];
    int n, ok;
    char err[256];
    pn_stats st;           /* of the last repetition */
    float *vis;
    uint8_t *rgba;
} job;

/* A visibility buffer against the reference's. Gross: off by more than 0.25 (a missing or
 * invented shadow, not a penumbra's slope), brighter or darker than the reference; p99: the
 * 99th percentile of |error| (from a histogram of 2^16 bins over [0, 1]: within 2^-16). */
typedef struct accuracy {
    double rmse, max_err, mae, wrong_frac; /* mae: mean absolute error */
    double p99, gross_brighter, gross_darker; /* fractions of all pixels */
    int identical;
    int ok;
} accuracy;

typedef struct scene_state {
    pn_setup s;
    pn_host h;
    const bench_port *port;
    void *port_state;
    pn_embree *emb;        /* NULL when Embree is absent or failed */
    char emb_err[256];
    int emb_built;         /* scene built into emb */
    pn_gbuf g;             /* G-buffer of the current point, from its first frame */
    int need_gbuf;
    uint32_t threads;
    /* from the main point, for the sweeps and the headline plot */
    pn_embree_api best_api;
    double gears_vs_ref, gears_vs_emb, gears_vs_rt;
    /* from the main point (area light, first port), for the SRT section: every
     * algorithm's shadow pass median and RMSE, Embree's best, the reference's visibility */
    double pt_ms[NALGO], pt_rmse[NALGO], emb_ms, emb_rmse;
    /* ...and every algorithm's, the baselines' and Embree's errors in full, and the
     * baselines' times, for the accuracy table and the summary */
    accuracy pt_acc[NALGO], bl_acc[NBASE], emb_acc;
    double bl_ms[NBASE];
    /* the status of an algorithm that was selected and compiled in but failed ("" if none) */
    char pt_fail[NALGO][48];
    const char *emb_api;
    float *ref_vis;
    float cull_tol;
    /* the fastest exact algorithm at the SRT section's second size (area light) */
    double big_ms;
    const char *big_name;
    /* the time-vs-error chart's points beyond the main point's algorithms and Embree:
     * configurations of the approximate algorithms (same size, k and reference) */
    struct {
        char label[96];
        double ms, rmse;
        int pt;
    } xpt[XPT_MAX];
    int nxpt;
    /* the reference at k = 32 (main point's size, area light), rendered once on demand; its
     * shaded image is the penumbra wedges' heat map's background */
    float *ref32_vis;
    uint8_t *ref32_rgba;
    int ref32_done;
    char ref32_err[256];
    /* the MCSM default of its claims run, for its goal table */
    double mc_ms, mc_rmse;
    pn_stats mc_st;
    int mc_ok;
    /* the penumbra wedges' claims run (wg_claims), for their table (wg_section): per mode
     * (blended, additive) the median at the main point's k and the RMSE against its
     * reference; the errors of one frame per mode at k = 32 against the k = 32 reference */
    struct {
        int ok;
        char err[256];
        double ms[2], rmse[2], rmse32[2], max32[2], mae32;
        pn_stats st;   /* blended, last repetition */
        size_t differ; /* pixels where the two modes differ (k = 32 frames) */
        size_t closer, farther; /* ...of which blending is closer to / farther from the reference */
        size_t over;   /* pixels where blended is off by more than WG_TOL (wedges.c) */
        int heat;      /* the heat map was written */
    } wg;
} scene_state;

/* ---- Sections: each is a memory stream filled scene by scene, printed in order at the end */

enum {
    SEC_HEADLINE,
    SEC_PORTS,
    SEC_EMBREE,
    SEC_RES,
    SEC_K,
    SEC_LIGHT,
    SEC_GRID,
    SEC_GRIDEFF,
    SEC_MEMORY,
    SEC_ACCURACY,
    SEC_MASKS,
    SEC_SRT_ACC,
    SEC_SRT_SPEED,
    SEC_SRT_BOUND,
    SEC_SRT_CHART,
    SEC_OCC_CLAIMS,
    SEC_OCC_SPEED,
    SEC_OCC_LIGHT,
    SEC_OCC_MAPS,
    SEC_MC_CLAIMS,
    SEC_MC_CONV,
    SEC_MC_LEAKS,
    SEC_MC_MAP,
    SEC_MC_SCREEN,
    SEC_MC_GOAL,
    SEC_MC_MAPS,
    SEC_WG_MODES,
    SEC_WG_MAPS,
    SEC_WG_GOAL,
    SEC_WG_SWEEP,
    SEC_GALLERY,
    SEC_COUNT
};

typedef struct report {
    FILE *sec[SEC_COUNT];
    char *buf[SEC_COUNT];
    size_t len[SEC_COUNT];
    FILE *plots; /* gnuplot program */
    char *plots_buf;
    size_t plots_len;
    double hmin, hmax; /* range of the headline ratios */
    int hcol[3];       /* the headline's columns with a point (vs reference, Embree, raytrace) */
    int sweep_scenes;
    char sweep_names[MAX_SCENES][128];
    int mc_conv_scenes;                  /* scenes with an MCSM convergence data file */
    char mc_conv_names[MAX_SCENES][128];
    double mc_conv_top;                  /* largest RMSE of the convergence plot */
    int mc_goal_n, mc_goal[3];           /* shared scenes; of which meet each part of the goal */
    /* The summary (summary_scene): per algorithm, baseline and Embree (NSUM rows) over the
     * scenes of the run, the worst RMSE and gross fraction, the slowest ratio to the fastest
     * exact algorithm, and the scenes where it is on the time-vs-error front */
    struct {
        int n, front;
        double rmse, gross, gross_b, gross_d, speed;
        char rmse_at[128], gross_at[128], speed_at[128], off_front[600], failed[400];
    } sum[NSUM];
    int wg_goal_rows;                    /* rows of the wedges' `square` check */
    int wg_sweep_ran, wg_sweep;          /* the wedges' sweep ran; it has a wedges time */
    int wg_sweep_exact;                  /* ...and an exact algorithm's */
} report;

/* A table's heading and the note that explains its columns, in the order printed (each file
 * that owns tables has its own list). */
typedef struct bench_note {
    int sec;
    const char *heading, *note;
} bench_note;

/* ---- jobs.c ---------------------------------------------------------------------------- */

int in_list(const char *list, const char *name);
void fmt_ms(char *b, size_t n, double ms);
void fmt_ratio(char *b, size_t n, double num, double den);
void progress(const char *fmt, ...);
void job_lib(job *j, int algo, const pn_frame_options *opt, int keep);
void job_emb(job *j, pn_embree_api api, const pn_frame_options *opt, int keep);
void job_free(job *j);
double job_pass(const job *j);
double job_total(const job *j);
void job_run(scene_state *ss, job *j, const pn_light *light, int rep);
int run_jobs(const bench_opts *o, scene_state *ss, job *jobs, int njobs, const pn_light *light);
accuracy compare_vis(const float *a, const float *ref, size_t n);
void write_data(const bench_opts *o, const char *name, const char *scene, const char *text);
int heat_png(const bench_opts *o, const scene_state *ss, const char *file, const float *d, const float *ref,
             uint32_t w, uint32_t h, double tol, const uint8_t pos[3], const uint8_t neg[3]);
void error_heat(const bench_opts *o, report *r, int s, const scene_state *ss, const char *file, const char *what,
                const float *vis, const float *ref, uint32_t w, uint32_t h);
/* The note of an error_heat section. */
#define HEAT_NOTE                                                                                                      \
    "Per scene, the default's visibility minus the k = 32 reference: red where it is brighter (a shadow "             \
    "missing), blue where darker, full at 0.25; elsewhere the shaded reference in grey."
void scaled_light(const pn_light *l, float s, pn_light *out);
int scene_open(const bench_opts *o, scene_state *ss, const char *source, int builtin, const bench_port *port,
               uint32_t max_size);
void scene_close(scene_state *ss);
void base_options(const bench_opts *o, const scene_state *ss, pn_frame_options *opt);

/* ---- report.c -------------------------------------------------------------------------- */

void sec(report *r, int s, const char *fmt, ...);
void print_table(FILE *out, const report *r, int s, const char *heading, const char *note);
void print_tables(FILE *out, const report *r, const bench_note *notes, int n);
void report_open(report *r, const bench_opts *o);
void summary_scene(report *r, const scene_state *ss);
void print_report(report *r, const bench_opts *o, FILE *out, const char *mach, const char *emb_info, int threads,
                  double minutes);
void report_close(report *r);

/* ---- main_point.c ---------------------------------------------------------------------- */

void main_point_headers(report *r);
void main_point(const bench_opts *o, report *r, scene_state *ss, int first_port);
void headline_data(FILE *f, report *r, const scene_state *ss);
void plot_headline(report *r, const bench_opts *o);
void main_point_print(const report *r, const bench_opts *o, FILE *out, int first, int last);

/* ---- sweeps.c -------------------------------------------------------------------------- */

void sweep_headers(report *r, const bench_opts *o);
void sweep(const bench_opts *o, report *r, scene_state *ss, int kind, pn_embree_api api);
void plot_sweeps(report *r, const bench_opts *o);
void sweeps_print(const report *r, FILE *out, int threads);

/* ---- chart.c --------------------------------------------------------------------------- */

int section_algo(const bench_opts *o, pn_algo algo);
int fastest_exact(const double *ms);
const float *ref32(const bench_opts *o, scene_state *ss);
size_t px_brighter(const float *a, const float *ref, size_t n);
int chart_front(const scene_state *ss, int self, const char *own, double ms, double rmse, char *b, size_t n);
void chart_point(scene_state *ss, const char *algo, const char *cfg, const job *j, int pt);
void tradeoff_chart(const bench_opts *o, report *r, scene_state *ss);
void chart_print(const report *r, const bench_opts *o, FILE *out);

/* ---- srt.c, occtex.c, mcsm.c, wedges.c: the approximate algorithms' sections ------------- */

void srt_headers(report *r);
void srt_section(const bench_opts *o, report *r, scene_state *ss);
void srt_print(const report *r, FILE *out);

void occ_headers(report *r, const bench_opts *o);
void occ_section(const bench_opts *o, report *r, scene_state *ss);
void occ_print(const report *r, FILE *out);

void mcsm_headers(report *r, const bench_opts *o);
void mc_claims(const bench_opts *o, report *r, scene_state *ss);
void mcsm_section(const bench_opts *o, report *r, scene_state *ss);
void mcsm_leaks(const bench_opts *o, report *r);
void plot_mc_convergence(report *r);
void mcsm_print(const report *r, const bench_opts *o, FILE *out);

void wg_headers(report *r);
void wg_claims(const bench_opts *o, scene_state *ss);
void wg_section(const bench_opts *o, report *r, scene_state *ss);
void wg_sweep(const bench_opts *o, report *r);
void plot_wg_sweep(report *r, const bench_opts *o);
void wg_print(const report *r, const bench_opts *o, FILE *out);

#endif
