/* penumbra_bench - the measuring instrument every algorithm reports through (issue 5).
 *
 * Prints Markdown tables (and writes them to OUT/RESULTS.md), data files and a gnuplot
 * program for the plots (OUT/plots.gp), and the gallery panels. Method: every number is
 * the median of several repetitions; within a repetition the algorithms, the Embree
 * baseline and the BVH builds run one after the other, so every ratio compares
 * measurements taken side by side in the same run. The machine, core count and thread
 * count are printed with the tables. Timing lives here, never in tests.
 *
 * usage: penumbra_bench [--out DIR] [--scenes DIR] [--quick] [--only a,b] [--reps N]
 *                       [--threads N] [--sweep-scenes a,b] [--label TEXT] (usage() has all)
 * See tools/bench.sh (make bench / make bench-quick) for how it is run. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "penumbra/penumbra.h"
#if PN_BENCH_OPENCL
#include "penumbra/opencl.h"
#include "pn_cl_host.h"
#endif
#include "pn_bench.h"
#include "pn_image.h"
#include "pn_scenes.h"
#include "pn_setup.h"

/* ---- What is measured: algorithms and ports ------------------------------------------- */

typedef struct bench_algo {
    const char *name;
    pn_algo algo;
    uint32_t build_flag;
    int exact;     /* must match the reference bit for bit */
    int all_ports; /* 0: measured on the first port only (a baseline, not a product) */
} bench_algo;

/* Every algorithm of the library; a new one is one line here (and its accuracy, timing
 * and gallery columns follow). */
static const bench_algo algos[] = {
    {"reference", PN_ALGO_REFERENCE, PN_BUILD_REFERENCE, 1, 1},
    {"GEARS", PN_ALGO_GEARS, PN_BUILD_GEARS, 1, 1},
#ifdef PN_BUILD_RAYTRACE
    {"raytrace", PN_ALGO_RAYTRACE, PN_BUILD_RAYTRACE, 1, 0},
#endif
    {"SRT", PN_ALGO_SRT, PN_BUILD_SRT, 0, 1},
    {"occtex", PN_ALGO_OCCTEX, PN_BUILD_OCCTEX, 0, 1},
    {"MCSM", PN_ALGO_MCSM, PN_BUILD_MCSM, 0, 1},
    {"wedges", PN_ALGO_WEDGES, PN_BUILD_WEDGES, 0, 1},
};
#define NALGO ((int)(sizeof(algos) / sizeof(algos[0])))
#define A_REF 0
#define A_GEARS 1
#ifdef PN_BUILD_RAYTRACE
#define A_RT 2
#else
#define A_RT (-1)
#endif

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

static pn_status scalar_render(pn_host *h, void *state, const pn_camera *cam, const pn_light *light,
                               const pn_frame_options *opt, pn_frame *out)
{
    (void)state;
    return pn_render(h->ctx, cam, light, opt, out);
}

/* Ports with a device of their own name it here, for the report's header. */
static char port_devices[256];

#if PN_BENCH_OPENCL
/* The OpenCL port (PoCL on the CPU by default; PN_OPENCL_DEVICE picks another device). */
static int opencl_attach(pn_host *h, void **state, char *err, size_t err_size)
{
    pn_opencl *cl;
    pn_status st = pn_cl_open(h->ctx, NULL, &cl);
    if (st != PN_OK) {
        pn_tools_err(err, err_size, "pn_opencl_create: %s (%s)", pn_last_error(h->ctx), pn_status_str(st));
        return 1;
    }
    *state = cl;
    if (!port_devices[0]) snprintf(port_devices, sizeof(port_devices), "OpenCL port: %s", pn_opencl_device_name(cl));
    return 0;
}

static pn_status opencl_render(pn_host *h, void *state, const pn_camera *cam, const pn_light *light,
                               const pn_frame_options *opt, pn_frame *out)
{
    (void)h;
    return pn_opencl_render((pn_opencl *)state, cam, light, opt, out);
}

static void opencl_detach(void *state) { pn_cl_close((pn_opencl *)state); }
#endif

/* make bench measures the first two (--ports 3 adds the scalar port on one thread). */
static const bench_port ports[] = {
    {"scalar", 0, NULL, scalar_render, NULL},
#if PN_BENCH_OPENCL
    {"opencl", 0, opencl_attach, opencl_render, opencl_detach},
#endif
    {"scalar", 1, NULL, scalar_render, NULL},
};
#define NPORT ((int)(sizeof(ports) / sizeof(ports[0])))

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

static int in_list(const char *list, const char *name)
{
    size_t n = strlen(name);
    const char *p = list;
    if (!list) return 1;
    while (*p) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && strncasecmp(p, name, n) == 0) return 1;
        if (!e) break;
        p = e + 1;
    }
    return 0;
}

/* ---- Small helpers ---------------------------------------------------------------------- */

static double median(const double *v, int n)
{
    double s[MAX_REPS];
    int i, j;
    if (n <= 0) return NAN;
    memcpy(s, v, (size_t)n * sizeof(double));
    for (i = 1; i < n; i++)
        for (j = i; j > 0 && s[j - 1] > s[j]; j--) {
            double t = s[j];
            s[j] = s[j - 1];
            s[j - 1] = t;
        }
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

static void fmt_ms(char *b, size_t n, double ms)
{
    if (!(ms == ms)) snprintf(b, n, "n/a");
    else if (ms >= 100.0) snprintf(b, n, "%.0f", ms);
    else if (ms >= 10.0) snprintf(b, n, "%.1f", ms);
    else snprintf(b, n, "%.2f", ms);
}

/* "12.3x" for a ratio a/b of two medians, "n/a" when either is missing. */
static void fmt_ratio(char *b, size_t n, double num, double den)
{
    double r = num / den;
    if (!(num == num) || !(den == den) || !(den > 0.0)) snprintf(b, n, "n/a");
    else if (r >= 10.0) snprintf(b, n, "%.1fx", r);
    else snprintf(b, n, "%.2fx", r);
}

static void progress(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    fflush(stderr);
}

static int port_threads(const bench_opts *o, const bench_port *p)
{
    int t = p->threads > 0 ? p->threads : (o->threads > 0 ? o->threads : pn_threads_cores());
    return t;
}

/* ---- Jobs: one timed thing inside a repetition ------------------------------------------ */

enum { JOB_LIB, JOB_EMBREE, JOB_SCENE_SET, JOB_EMBREE_BUILD, JOB_PCSS };

/* The baselines a user would pick instead of an approximate algorithm, measured beside
 * every algorithm at the main point: the exact reference with fewer light samples (the
 * cheap exact answer) and percentage-closer soft shadows (what engines ship;
 * tools/pn_bench_pcss.c). Their errors are against the main point's reference (k as in the
 * headline). */
enum { BL_REF4, BL_REF8, BL_PCSS, NBASE };
static const struct {
    const char *name;
    uint32_t k; /* reference samples per side; 0: PCSS */
    int pt;     /* the chart's point type */
} baselines[NBASE] = {{"reference k=4", 4, 9}, {"reference k=8", 8, 9}, {"PCSS", 0, 11}};

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
        size_t over;   /* pixels where blended is off by more than WG_TOL */
        int heat;      /* the heat map was written */
    } wg;
} scene_state;

static void job_lib(job *j, int algo, const pn_frame_options *opt, int keep)
{
    memset(j, 0, sizeof(*j));
    j->kind = JOB_LIB;
    j->algo = algo;
    j->opt = *opt;
    j->opt.algo = algos[algo].algo;
    j->keep = keep;
    j->ok = 1;
}

static void job_emb(job *j, pn_embree_api api, const pn_frame_options *opt, int keep)
{
    memset(j, 0, sizeof(*j));
    j->kind = JOB_EMBREE;
    j->api = api;
    j->opt = *opt;
    j->keep = keep;
    j->ok = 1;
}

static void job_free(job *j)
{
    free(j->vis);
    free(j->rgba);
    j->vis = NULL;
    j->rgba = NULL;
}

static double job_pass(const job *j) { return j->ok && j->n > 0 ? median(j->pass, j->n) : NAN; }
static double job_total(const job *j) { return j->ok && j->n > 0 ? median(j->total, j->n) : NAN; }

/* Runs one job once; rep 0 of a keeping job stores its visibility. */
static void job_run(scene_state *ss, job *j, const pn_light *light, int rep)
{
    char err[256];
    size_t npx;
    if (!j->ok) return;
    if (j->kind == JOB_SCENE_SET) {
        pn_stats st;
        pn_setup *s = &ss->s;
        if (pn_setup_upload(ss->h.ctx, s) != PN_OK) {
            snprintf(j->err, sizeof(j->err), "pn_scene_set: %s", pn_last_error(ss->h.ctx));
            j->ok = 0;
            return;
        }
        pn_get_stats(ss->h.ctx, &st);
        j->pass[j->n] = st.pass_ns[PN_PASS_BVH_BUILD] / 1e6;
        j->total[j->n] = (st.pass_ns[PN_PASS_BVH_BUILD] + st.pass_ns[PN_PASS_SCENE_COPY]) / 1e6;
        j->n++;
        return;
    }
    if (j->kind == JOB_EMBREE_BUILD) {
        double ms;
        if (!ss->emb) {
            snprintf(j->err, sizeof(j->err), "%s", ss->emb_err);
            j->ok = 0;
            return;
        }
        if (pn_embree_build(ss->emb, &ss->s.mesh, 0, &ms, err, sizeof(err)) != 0) {
            snprintf(j->err, sizeof(j->err), "%s", err);
            j->ok = 0;
            return;
        }
        ss->emb_built = 1;
        j->pass[j->n] = j->total[j->n] = ms;
        j->n++;
        return;
    }
    npx = (size_t)j->opt.width * j->opt.height;
    if (j->kind == JOB_EMBREE || j->kind == JOB_PCSS) {
        /* The outside baselines trace from the point's G-buffer. */
        double ms;
        float *vis;
        int rc;
        if ((j->kind == JOB_EMBREE && !ss->emb) || !ss->g.pos) {
            snprintf(j->err, sizeof(j->err), "%s", j->kind == JOB_EMBREE && !ss->emb ? ss->emb_err : "no G-buffer");
            j->ok = 0;
            return;
        }
        if (j->kind == JOB_EMBREE && !ss->emb_built) {
            if (pn_embree_build(ss->emb, &ss->s.mesh, 0, &ms, err, sizeof(err)) != 0) {
                snprintf(j->err, sizeof(j->err), "%s", err);
                j->ok = 0;
                return;
            }
            ss->emb_built = 1;
        }
        vis = (float *)malloc(npx * sizeof(float));
        rc = !vis ? 1
             : j->kind == JOB_EMBREE
                 ? pn_embree_shadow(ss->emb, j->api, &ss->g, light, j->opt.k, j->opt.eps, &ss->h.threads, vis, NULL,
                                    &ms, err, sizeof(err))
                 : pn_pcss_shadow(&ss->s.mesh, &ss->g, light, j->opt.k, j->opt.eps, &ss->h.threads, vis, &ms, err,
                                  sizeof(err));
        if (rc != 0) {
            snprintf(j->err, sizeof(j->err), "%s", vis ? err : "out of memory");
            j->ok = 0;
            free(vis);
            return;
        }
        j->pass[j->n] = j->total[j->n] = ms;
        j->n++;
        if (rep == 0 && j->keep) j->vis = vis;
        else free(vis);
        return;
    }
    {
        pn_frame fr;
        pn_status st;
        uint64_t t0 = pn_threads_now_ns(NULL);
        st = ss->port->render(&ss->h, ss->port_state, &ss->s.camera, light, &j->opt, &fr);
        if (st != PN_OK) {
            snprintf(j->err, sizeof(j->err), "%s: %s", pn_status_str(st), pn_last_error(ss->h.ctx));
            j->ok = 0;
            return;
        }
        j->total[j->n] = (pn_threads_now_ns(NULL) - t0) / 1e6;
        pn_get_stats(ss->h.ctx, &j->st);
        j->pass[j->n] = j->st.pass_ns[PN_PASS_SHADOW] / 1e6;
        j->n++;
        if (ss->need_gbuf) {
            /* Every baseline traces from the point's G-buffer (the same for every
             * algorithm: the rasterizer does not depend on it). */
            ss->need_gbuf = 0;
            pn_gbuf_free(&ss->g);
            if (pn_gbuf_copy(&ss->g, &fr) != 0) progress("warning: out of memory copying the G-buffer");
        }
        if (rep == 0 && j->keep) {
            j->vis = (float *)malloc(npx * sizeof(float));
            j->rgba = (uint8_t *)malloc(npx * 4);
            if (j->vis) memcpy(j->vis, fr.visibility, npx * sizeof(float));
            if (j->rgba) memcpy(j->rgba, fr.rgba, npx * 4);
        }
    }
}

/* Runs the jobs interleaved: rep 0 of all, then rep 1 of all, ... The number of
 * repetitions is o->reps, or o->reps_slow when the first repetition took longer than
 * o->slow_s seconds (the dragon at 512x512 takes a minute per repetition). Returns the
 * repetitions made. */
static int run_jobs(const bench_opts *o, scene_state *ss, job *jobs, int njobs, const pn_light *light)
{
    int rep, i, reps = o->reps;
    ss->need_gbuf = 1;
    for (rep = 0; rep < reps; rep++) {
        uint64_t t0 = pn_threads_now_ns(NULL);
        for (i = 0; i < njobs; i++) job_run(ss, &jobs[i], light, rep);
        if (rep == 0 && (pn_threads_now_ns(NULL) - t0) / 1e9 > o->slow_s && o->reps_slow < reps)
            reps = o->reps_slow;
    }
    return reps;
}

/* ---- Accuracy ----------------------------------------------------------------------------- */


#define ACC_BINS 65536u
static accuracy compare_vis(const float *a, const float *ref, size_t n)
{
    accuracy r;
    double se = 0.0, sa = 0.0;
    size_t i, wrong = 0, hi = 0, lo = 0, below = 0;
    static uint32_t hist[ACC_BINS];
    uint32_t b;
    memset(&r, 0, sizeof(r));
    if (!a || !ref || n == 0) return r;
    r.ok = 1;
    memset(hist, 0, sizeof(hist));
    for (i = 0; i < n; i++) {
        double d = (double)a[i] - (double)ref[i], e = fabs(d);
        se += e * e;
        sa += e;
        if (e > r.max_err) r.max_err = e;
        if (a[i] != ref[i]) wrong++;
        hi += d > 0.25;
        lo += d < -0.25;
        hist[e >= 1.0 ? ACC_BINS - 1u : (uint32_t)(e * ACC_BINS)]++;
    }
    /* 0 when at least 99% of the pixels are exact; else the upper edge of the bin in which
     * the cumulative count reaches 99% (at most the largest error). */
    if ((double)(n - wrong) >= 0.99 * (double)n) {
        r.p99 = 0.0;
    } else {
        for (b = 0; b + 1u < ACC_BINS && (double)(below + hist[b]) < 0.99 * (double)n; b++) below += hist[b];
        r.p99 = fmin((double)(b + 1u) / ACC_BINS, r.max_err);
    }
    r.rmse = sqrt(se / (double)n);
    r.mae = sa / (double)n;
    r.wrong_frac = (double)wrong / (double)n;
    r.gross_brighter = (double)hi / (double)n;
    r.gross_darker = (double)lo / (double)n;
    r.identical = memcmp(a, ref, n * sizeof(float)) == 0;
    return r;
}

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
    SEC_MC_CLAIMS,
    SEC_MC_CONV,
    SEC_MC_LEAKS,
    SEC_MC_MAP,
    SEC_MC_SCREEN,
    SEC_MC_GOAL,
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

static void sec(report *r, int s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(r->sec[s], fmt, ap);
    va_end(ap);
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

/* ---- Per-scene work ----------------------------------------------------------------------- */

static void write_data(const bench_opts *o, const char *name, const char *scene, const char *text)
{
    char path[1400];
    FILE *f;
    snprintf(path, sizeof(path), "%s/data/%s_%s.dat", o->out_dir, name, scene);
    f = fopen(path, "w");
    if (!f) {
        progress("warning: cannot write %s: %s", path, strerror(errno));
        return;
    }
    fputs(text, f);
    fclose(f);
}

static void scaled_light(const pn_light *l, float s, pn_light *out)
{
    int a;
    *out = *l;
    for (a = 0; a < 3; a++) {
        out->u[a] = l->u[a] * s;
        out->v[a] = l->v[a] * s;
    }
}

static int scene_open(const bench_opts *o, scene_state *ss, const char *source, int builtin, const bench_port *port,
                      uint32_t max_size)
{
    char err[512];
    memset(ss, 0, sizeof(*ss));
    if (pn_setup_load_viewed(&ss->s, source, builtin, o->scenes_dir, err, sizeof(err)) != 0) {
        progress("%s: %s", source, err);
        return 1;
    }
    ss->port = port;
    ss->threads = (uint32_t)port_threads(o, port);
    if (pn_host_open(&ss->h, ss->s.mesh.triangle_count, max_size, max_size, (int)ss->threads, err, sizeof(err)) != 0 ||
        pn_setup_upload(ss->h.ctx, &ss->s) != PN_OK) {
        progress("%s: %s", source, ss->h.ctx ? pn_last_error(ss->h.ctx) : err);
        return 1;
    }
    if (port->attach && port->attach(&ss->h, &ss->port_state, err, sizeof(err)) != 0) {
        progress("%s: port %s: %s", source, port->name, err);
        return 1;
    }
    if (pn_embree_open(&ss->emb, (int)ss->threads, ss->emb_err, sizeof(ss->emb_err)) != 0) ss->emb = NULL;
    return 0;
}

static void scene_close(scene_state *ss)
{
    if (ss->port && ss->port->detach) ss->port->detach(ss->port_state);
    pn_embree_close(ss->emb);
    pn_gbuf_free(&ss->g);
    free(ss->ref_vis);
    free(ss->ref32_vis);
    free(ss->ref32_rgba);
    pn_host_close(&ss->h);
    pn_setup_free(&ss->s);
}

static void base_options(const bench_opts *o, const scene_state *ss, pn_frame_options *opt)
{
    pn_frame_options_default(opt);
    opt->width = opt->height = o->size;
    opt->k = o->k;
    opt->gears_grid = o->grid;
    opt->eps = ss->s.eps;
}

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

static void main_point(const bench_opts *o, report *r, scene_state *ss, int first_port)
{
    pn_frame_options opt;
    job lib[NALGO], emb[PN_EMBREE_API_COUNT], bset, ebuild, base[NBASE];
    int a, reps, i, b;
    size_t n;
    pn_stats ref_only;
    char c[12][64];
    double emb_best;
    const char *emb_api;
    job all[NALGO + NBASE + PN_EMBREE_API_COUNT + 2];
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
        ebuild.ok = 0;
        for (i = 0; i < PN_EMBREE_API_COUNT; i++) {
            emb[i].ok = 0;
            snprintf(emb[i].err, sizeof(emb[i].err), "not selected (--algos)");
        }
    }
    /* One array so that run_jobs interleaves them: builds, then the algorithms (reference
     * first: it provides the G-buffer), then Embree. */
    all[nall++] = bset;
    all[nall++] = ebuild;
    for (a = 0; a < NALGO; a++) all[nall++] = lib[a];
    for (b = 0; b < NBASE; b++) all[nall++] = base[b];
    for (i = 0; i < PN_EMBREE_API_COUNT; i++) all[nall++] = emb[i];
    progress("  %s/%s x%u: main point %ux%u k=%u", ss->s.name, ss->port->name, ss->threads, opt.width, opt.height,
             opt.k);
    reps = run_jobs(o, ss, all, nall, &ss->s.light);
    bset = all[0];
    ebuild = all[1];
    for (a = 0; a < NALGO; a++) lib[a] = all[2 + a];
    for (b = 0; b < NBASE; b++) base[b] = all[2 + NALGO + b];
    for (i = 0; i < PN_EMBREE_API_COUNT; i++) emb[i] = all[2 + NALGO + NBASE + i];
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
        fmt_ms(c[2], sizeof(c[2]), job_pass(&emb[0]));
        fmt_ms(c[3], sizeof(c[3]), job_pass(&emb[1]));
        fmt_ratio(c[4], sizeof(c[4]), emb_best, gears);
        fmt_ratio(c[5], sizeof(c[5]), dyn_emb, dyn_ours);
        fmt_ratio(c[6], sizeof(c[6]), job_pass(&emb[0]), job_pass(&emb[1]));
        sec(r, SEC_EMBREE, "| %s | %s | %u | %s | %s | %s | %s | %s | %s | %s | %s |\n", ss->s.name, ss->port->name,
            ss->threads, c[0], c[1], c[2], c[3], c[6],
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
        if (have_exact && xst.gears_assignments > 0)
            snprintf(c[6], sizeof(c[6]), "%.1f%%", 100.0 * (double)xst.shadow_blocking / (double)xst.gears_assignments);
        else snprintf(c[6], sizeof(c[6]), "n/a");
        sec(r, SEC_HEADLINE, "| %s | %u | %u | %s | %s | %s | %s | %s | %s | %s | %s |\n", ss->s.name,
            lib[A_REF].st.triangles, lib[A_REF].st.lit_pixels, c[0], c[1], c[2], c[9], c[3], c[4], c[5], c[6]);

        /* Grid efficiency at the main point (paper Tables 5 and 6). */
        if (have_exact)
            sec(r, SEC_GRIDEFF, "| %s | %u | %u | %u | %.1f | %u | %.1f | %llu | %.0f | %.0f | %.0f | %.1f%% | %.1f%% | %u |\n",
                ss->s.name, o->grid, xst.gears_cells_used, xst.gears_max_tris_per_cell, xst.gears_mean_tris_per_cell,
                xst.gears_max_pixels_per_cell, xst.gears_mean_pixels_per_cell, (unsigned long long)xst.gears_pairs,
                xst.gears_assignments / 1e3, xst.shadow_candidates / 1e3, xst.shadow_blocking / 1e3,
                xst.gears_assignments ? 100.0 * (double)xst.shadow_candidates / (double)xst.gears_assignments : 0.0,
                xst.gears_assignments ? 100.0 * (double)xst.shadow_blocking / (double)xst.gears_assignments : 0.0,
                xst.gears_tiles);

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
                gst.gears_pairs_high_water, gst.gears_tiles);
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
static void sweep(const bench_opts *o, report *r, scene_state *ss, int kind, pn_embree_api api)
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
            jobs[nj].opt.gears_grid = o->sweep_grid[v];
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
            x.opt.gears_grid = o->sweep_grid[v];
            x.opt.exact_stats = 1;
            job_run(ss, &x, &ss->s.light, 1);
            if (x.ok) xs[v] = x.st;
            else memset(&xs[v], 0, sizeof(xs[v]));
        }
        for (v = 0; v < nv; v++) {
            const job *g = v == 0 ? &jobs[nv] : &jobs[v];
            double gm = job_pass(g), rm = job_pass(&jobs[0]), em = job_pass(&jobs[nv + 1]);
            double pct = xs[v].gears_assignments ? 100.0 * (double)xs[v].shadow_blocking / (double)xs[v].gears_assignments : NAN;
            row_ms(&rs, 0, gm);
            row_ms(&rs, 1, rm);
            row_ms(&rs, 2, em);
            if (pct == pct) snprintf(cell, sizeof(cell), "%.1f%%", pct);
            else snprintf(cell, sizeof(cell), "n/a");
            row_add(&rs, 3, cell);
            snprintf(cell, sizeof(cell), "%u / %.1f", xs[v].gears_max_tris_per_cell, xs[v].gears_mean_tris_per_cell);
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

/* ---- The report ----------------------------------------------------------------------- */

/* ---- Shared by the approximate algorithms' sections ---------------------------------------- */

/* Index in algos[] of the algorithm whose section this is, or -1 when it is not compiled in
 * or not selected (--algos): then its section is left out. */
static int section_algo(const bench_opts *o, pn_algo algo)
{
    int a;
    for (a = 0; a < NALGO; a++)
        if (algos[a].algo == algo)
            return (pn_build_info() & algos[a].build_flag) && in_list(o->algos, algos[a].name) ? a : -1;
    return -1;
}

/* The fastest exact algorithm among per-algorithm shadow-pass medians (NaN: not run);
 * -1: none. */
static int fastest_exact(const double *ms)
{
    int a, best = -1;
    for (a = 0; a < NALGO; a++)
        if (algos[a].exact && ms[a] == ms[a] && (best < 0 || ms[a] < ms[best])) best = a;
    return best;
}

/* The reference's visibility at k = 32, the main point's size, area light: rendered once per
 * scene (one frame: only its bits are used) for the sections that measure an approximate
 * algorithm's own error, not the k = 16 reference's. NULL when it failed (ss->ref32_err). */
static const float *ref32(const bench_opts *o, scene_state *ss)
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
static size_t px_brighter(const float *a, const float *ref, size_t n)
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
static int chart_front(const scene_state *ss, int self, const char *own, double ms, double rmse, char *b, size_t n)
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
static void chart_point(scene_state *ss, const char *algo, const char *cfg, const job *j, int pt)
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
        ss->s.name, light, size, cfg, j->st.lit_pixels ? 100.0 * j->st.srt_pip / (double)j->st.lit_pixels : 0.0,
        j->st.srt_thin, j->st.srt_cons_texels,
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
    fmt_ms(c[2], sizeof(c[2]), srt->st.srt_ns_map / 1e6);
    fmt_ms(c[3], sizeof(c[3]), srt->st.srt_ns_classify / 1e6);
    fmt_ms(c[4], sizeof(c[4]), srt->st.srt_ns_exact / 1e6);
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
        srt->st.lit_pixels ? 100.0 * srt->st.srt_pip / (double)srt->st.lit_pixels : 0.0, c[6], c[5]);
}

static void srt_section(const bench_opts *o, report *r, scene_state *ss)
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
            jobs[nj].opt.srt_flags = srt_cfgs[i].flags;
            jobs[nj].opt.srt_map = srt_cfgs[i].map;
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
                    fmt_ratio(cb[3], sizeof(cb[3]), ss->pt_ms[A_REF], d->st.srt_ns_exact / 1e6);
                    sec(r, SEC_SRT_BOUND,
                        "| %s | %llu | %.2f%% | %.2f%% | %.1f%% / %.1f%% / %.1f%% | %.1f%% / %.1f%% / %.1f%% | %s | %s | %s | %s | %s |\n",
                        ss->s.name, (unsigned long long)lit, lit ? 100.0 * cc.pixels[2] / (double)lit : 0.0,
                        d->st.lit_pixels ? 100.0 * d->st.srt_pip / (double)d->st.lit_pixels : 0.0,
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

/* ---- The time-vs-error chart: every algorithm at the main point, Embree, and the extra
 * configurations the sections added (ss->xpt) ----------------------------------------------- */

static void tradeoff_chart(const bench_opts *o, report *r, scene_state *ss)
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

/* ---- The summary: every algorithm's worst scene ---------------------------------------------- */

static void summary_scene(report *r, const scene_state *ss)
{
    int e, fe = fastest_exact(ss->pt_ms);
    double fast = fe >= 0 ? ss->pt_ms[fe] : NAN;
    for (e = 0; e < NSUM; e++) {
        double ms, rmse, gross, speed;
        const accuracy *acc;
        const char *own;
        int self = -1;
        char fb[512];
        if (e < NALGO) {
            ms = ss->pt_ms[e];
            acc = &ss->pt_acc[e];
            own = algos[e].name;
            self = e;
        } else if (e < NALGO + NBASE) {
            ms = ss->bl_ms[e - NALGO];
            acc = &ss->bl_acc[e - NALGO];
            own = baselines[e - NALGO].name;
        } else {
            ms = ss->emb_ms;
            acc = &ss->emb_acc;
            own = "Embree";
        }
        if (e < NALGO && ss->pt_fail[e][0]) {
            size_t l = strlen(r->sum[e].failed);
            snprintf(r->sum[e].failed + l, sizeof(r->sum[e].failed) - l, "%s%s (%s)", l ? ", " : "", ss->s.name,
                     ss->pt_fail[e]);
        }
        if (!(ms == ms) || !acc->ok) continue;
        rmse = e == A_REF ? 0.0 : acc->rmse;
        gross = acc->gross_brighter + acc->gross_darker;
        speed = fast / ms;
        if (r->sum[e].n == 0 || rmse > r->sum[e].rmse) {
            r->sum[e].rmse = rmse;
            snprintf(r->sum[e].rmse_at, sizeof(r->sum[e].rmse_at), "%s", ss->s.name);
        }
        if (r->sum[e].n == 0 || gross > r->sum[e].gross) {
            r->sum[e].gross = gross;
            r->sum[e].gross_b = acc->gross_brighter;
            r->sum[e].gross_d = acc->gross_darker;
            snprintf(r->sum[e].gross_at, sizeof(r->sum[e].gross_at), "%s", ss->s.name);
        }
        if (speed == speed && (r->sum[e].n == 0 || !(r->sum[e].speed <= speed))) {
            r->sum[e].speed = speed;
            snprintf(r->sum[e].speed_at, sizeof(r->sum[e].speed_at), "%s", ss->s.name);
        }
        r->sum[e].n++;
        if (chart_front(ss, self, own, ms, rmse, fb, sizeof(fb))) {
            r->sum[e].front++;
        } else {
            size_t l = strlen(r->sum[e].off_front);
            snprintf(r->sum[e].off_front + l, sizeof(r->sum[e].off_front) - l, "%s%s", l ? ", " : "", ss->s.name);
        }
    }
}

static void summary_print(const report *r, FILE *out, const bench_opts *o)
{
    int e;
    fprintf(out, "## Summary: every algorithm on every scene of this run\n\n"
                 "| algorithm | scenes | worst RMSE | worst gross (brighter / darker) | slowest vs fastest exact | "
                 "on the time-vs-error front | off the front on | failed on |\n"
                 "| --- | ---: | ---: | ---: | ---: | ---: | --- | --- |\n");
    for (e = 0; e < NSUM; e++) {
        const char *name = e < NALGO ? algos[e].name : e < NALGO + NBASE ? baselines[e - NALGO].name : "Embree";
        if (r->sum[e].n == 0 && !r->sum[e].failed[0]) continue;
        fprintf(out, "| %s | %d | %.4f (%s) | %.2f%% (%.2f / %.2f; %s) | %.2fx (%s) | %d of %d | %s | %s |\n", name,
                r->sum[e].n, r->sum[e].rmse, r->sum[e].rmse > 0.0 ? r->sum[e].rmse_at : "all",
                100.0 * r->sum[e].gross, 100.0 * r->sum[e].gross_b, 100.0 * r->sum[e].gross_d,
                r->sum[e].gross > 0.0 ? r->sum[e].gross_at : "all", r->sum[e].speed, r->sum[e].speed_at,
                r->sum[e].front, r->sum[e].n, r->sum[e].off_front[0] ? r->sum[e].off_front : "-",
                r->sum[e].failed[0] ? r->sum[e].failed : "-");
    }
    fprintf(out, "\nEach algorithm with its default options (the baselines and Embree as in the accuracy table), at "
                 "%ux%u, k = %u, area light, on every scene of the run. Worst RMSE and worst gross fraction (pixels "
                 "off by more than 0.25, brighter and darker than the reference, %% of all pixels): the largest over "
                 "the scenes, and where. Slowest vs fastest exact: the smallest ratio of the fastest exact "
                 "algorithm's shadow pass (of reference, GEARS and raytrace at k = %u, this run) to this one's (above "
                 "1: faster). On the front: scenes where no other point of that scene's time-vs-error chart (every "
                 "algorithm, every configuration the sections measured, the baselines, Embree) is both faster and "
                 "more accurate. Failed on: scenes where the frame returned an error status (not counted in the "
                 "other columns).\n\n",
            o->size, o->size, o->k, o->k);
}

/* ---- Occlusion textures (issue 17) ---------------------------------------------------------- */

/* The configurations measured: the default (what --algo occtex renders; on `square` it is
 * the paper's exact case set-up) and one change of it at a time. */
#define OCC_CFGS 8
#define OCC_CFG_8 6 /* the issue's speed goal is for 8 slices */
static const struct {
    const char *name;
    uint32_t filter, combine, slices, flags;
} occ_cfgs[OCC_CFGS] = {
    {"default (summed-area table, product, 16 slices, no leak fix)", 0u, 0u, 0u, 0u},
    {"max", 0u, PN_OCC_COMBINE_MAX, 0u, 0u},
    {"clamped sum", 0u, PN_OCC_COMBINE_SUM, 0u, 0u},
    {"N-buffer", PN_OCC_FILTER_NBUFFER, 0u, 0u, 0u},
    {"mipmap", PN_OCC_FILTER_MIPMAP, 0u, 0u, 0u},
    {"4 slices", 0u, 0u, 4u, 0u},
    {"8 slices", 0u, 0u, 8u, 0u},
    {"leak fix", 0u, 0u, 0u, PN_OCC_LEAK_FIX},
};
#define OCC_LIGHTS 5
static const float occ_light_scale[OCC_LIGHTS] = {0.25f, 0.5f, 1.0f, 2.0f, 4.0f};

static void occ_stages(char *b, size_t n, const job *j)
{
    char c[3][20];
    fmt_ms(c[0], sizeof(c[0]), j->st.occ_ns_slice / 1e6);
    fmt_ms(c[1], sizeof(c[1]), j->st.occ_ns_filter / 1e6);
    fmt_ms(c[2], sizeof(c[2]), j->st.occ_ns_lookup / 1e6);
    snprintf(b, n, "%s / %s / %s", c[0], c[1], c[2]);
}

static void occ_section(const bench_opts *o, report *r, scene_state *ss)
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
        jobs[i].opt.occ_filter = occ_cfgs[i].filter;
        jobs[i].opt.occ_combine = occ_cfgs[i].combine;
        jobs[i].opt.occ_slices = occ_cfgs[i].slices;
        jobs[i].opt.occ_flags = occ_cfgs[i].flags;
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
            (unsigned long long)j->st.occ_texels_set, (unsigned long long)j->st.occ_lookups);
    }
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

/* ---- Monte Carlo shadow maps (Curtis 2009) ---------------------------------------------------- */

/* A configuration: 0 in a field is the library's default (penumbra.h: 2 layers, hierarchical
 * search, 3x3 rays, its blur radius, map 512, adaptive bias). */
typedef struct mc_cfg {
    const char *name;
    uint32_t layers, search, rays, blur, flags, map;
} mc_cfg;

/* The claims table: the default (what --algo mcsm renders; the thesis' preferred version) and
 * one change of it per row; the thesis' other version is three layers with linear/binary
 * search. "Two layers, hierarchical, blur off" is the blur-off row. */
#define MC_CFGS 8
static const mc_cfg mc_cfgs[MC_CFGS] = {
    {"default (2 layers, hierarchical, 3x3 rays, default blur)", 0u, 0u, 0u, 0u, 0u, 0u},
    {"1 layer, linear", 1u, PN_MC_SEARCH_LINEAR, 0u, 0u, 0u, 0u},
    {"2 layers, linear/binary", 2u, PN_MC_SEARCH_LINEAR, 0u, 0u, 0u, 0u},
    {"3 layers, linear/binary", 3u, PN_MC_SEARCH_LINEAR, 0u, 0u, 0u, 0u},
    {"2x2 rays", 0u, 0u, 2u, 0u, 0u, 0u},
    {"4x4 rays", 0u, 0u, 4u, 0u, 0u, 0u},
    {"blur off (2 layers, hierarchical)", 0u, 0u, 0u, PN_MC_BLUR_OFF, 0u, 0u},
    {"blur radius 2", 0u, 0u, 0u, 2u, 0u, 0u},
};
/* The leak table on closed-box (hierarchical search, 3x3 rays, the default blur throughout). */
#define MC_LEAK_CFGS 5
static const mc_cfg mc_leak_cfgs[MC_LEAK_CFGS] = {
    {"1 layer", 1u, 0u, 0u, 0u, 0u, 0u},
    {"2 layers (default)", 2u, 0u, 0u, 0u, 0u, 0u},
    {"3 layers", 3u, 0u, 0u, 0u, 0u, 0u},
    {"2 layers, no bias", 2u, 0u, 0u, 0u, PN_MC_NO_BIAS, 0u},
    {"1 layer, no bias", 1u, 0u, 0u, 0u, PN_MC_NO_BIAS, 0u},
};
#define MC_RAYS_MAX 8 /* mc_rays: n x n rays, n in 1 .. 8 (penumbra.h) */
#define MC_GOAL_RMSE 0.05
#define MC_GOAL_SPEED 5.0

static void mc_job(job *j, int a_mc, const pn_frame_options *opt, const mc_cfg *c, int keep)
{
    job_lib(j, a_mc, opt, keep);
    j->opt.mc_layers = c->layers;
    j->opt.mc_search = c->search;
    j->opt.mc_rays = c->rays;
    j->opt.mc_blur = c->blur;
    j->opt.mc_flags = c->flags;
    j->opt.mc_map = c->map;
}

static void mc_stages(char *b, size_t n, const job *j)
{
    char c[4][20];
    fmt_ms(c[0], sizeof(c[0]), j->st.mc_ns_layers / 1e6);
    fmt_ms(c[1], sizeof(c[1]), j->st.mc_ns_nbuffer / 1e6);
    fmt_ms(c[2], sizeof(c[2]), j->st.mc_ns_rays / 1e6);
    fmt_ms(c[3], sizeof(c[3]), j->st.mc_ns_blur / 1e6);
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
static void mc_claims(const bench_opts *o, report *r, scene_state *ss)
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
            c[0], c[1], j->st.mc_lit, j->st.mc_umbra, j->st.mc_penumbra, j->st.mc_penumbra_open, j->st.mc_penumbra_shut,
            j->st.mc_penumbra ? 100.0 * j->st.mc_penumbra_open / j->st.mc_penumbra : 0.0,
            j->st.mc_penumbra ? 100.0 * j->st.mc_penumbra_shut / j->st.mc_penumbra : 0.0, (unsigned long long)j->st.mc_rays,
            j->st.mc_rays ? (double)j->st.mc_steps / (double)j->st.mc_rays : 0.0, j->st.mc_capped);
    }
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
                   "# mc_convergence %s: n rays rmse (blur off, 2 layers, hierarchical; k = 32 reference)\n", ss->s.name);
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
static void mcsm_section(const bench_opts *o, report *r, scene_state *ss)
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
static void mcsm_leaks(const bench_opts *o, report *r)
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
#define WG_TOL (1.0 / 255.0) /* one step of an 8-bit image: the issue's "nearly exact" */
#define WG_SPHERE_TRIS 762u  /* the built-in spheres' triangles per sphere (tools/pn_scenes.c) */
#define WG_SPHERES 81u       /* ...and spheres */

static void wg_stages(char *b, size_t n, const pn_stats *st)
{
    char c[3][20];
    fmt_ms(c[0], sizeof(c[0]), st->wg_ns_silhouettes / 1e6);
    fmt_ms(c[1], sizeof(c[1]), st->wg_ns_binning / 1e6);
    fmt_ms(c[2], sizeof(c[2]), st->wg_ns_pixels / 1e6);
    snprintf(b, n, "%s / %s / %s", c[0], c[1], c[2]);
}

/* Where blending helped, as a PNG next to RESULTS.md: per pixel d = |additive - ref| -
 * |blended - ref| against the k = 32 reference; green where d > WG_TOL, red where d < -WG_TOL
 * (brighter with |d|, full at 0.25 as in the gallery's error maps), elsewhere the shaded
 * reference in grey, so the coloured pixels can be placed in the scene. */
static int wg_heat(const bench_opts *o, const scene_state *ss, const float *blend, const float *add, const float *ref,
                   uint32_t w, uint32_t h)
{
    size_t n = (size_t)w * h, i;
    uint8_t *img = (uint8_t *)malloc(n * 4);
    char path[1400], err[256];
    int rc;
    if (!img || !blend || !add || !ref) {
        free(img);
        return 1;
    }
    if (!ss->ref32_rgba) pn_vis_to_rgba(ref, n, img);
    for (i = 0; i < n; i++) {
        double d = fabs((double)add[i] - ref[i]) - fabs((double)blend[i] - ref[i]);
        double t = fabs(d) * 4.0 > 1.0 ? 1.0 : fabs(d) * 4.0;
        uint8_t *p = img + 4 * i;
        if (d > WG_TOL || d < -WG_TOL) {
            uint8_t v = (uint8_t)(96.0 + 159.0 * t + 0.5);
            p[0] = d > 0.0 ? 0 : v;
            p[1] = d > 0.0 ? v : 0;
            p[2] = 0;
        } else if (ss->ref32_rgba) {
            const uint8_t *q = ss->ref32_rgba + 4 * i;
            p[0] = p[1] = p[2] = (uint8_t)(0.299 * q[0] + 0.587 * q[1] + 0.114 * q[2] + 0.5);
        }
        p[3] = 255;
    }
    snprintf(path, sizeof(path), "%s/wg_heat_%s.png", o->out_dir, ss->s.name);
    rc = pn_write_png(path, img, w, h, err, sizeof(err));
    if (rc != 0) progress("    wedges heat map: %s", err);
    free(img);
    return rc;
}

/* Claims: both modes at the main point's k, interleaved (their medians, and their points on
 * the time-vs-error chart against the main point's reference); then one frame of each at
 * k = 32 against the k = 32 reference (the horizon term of the frame samples k x k), for the
 * errors, the per-pixel comparison of the modes and the heat map. Runs before occ_section,
 * as mc_claims does, so that every section judges the chart's front on the same points. */
static void wg_claims(const bench_opts *o, scene_state *ss)
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
        jobs[m].opt.wg_mode = wg_modes[m].mode;
    }
    progress("  %s: wedges, blended and additive", ss->s.name);
    run_jobs(o, ss, jobs, WG_MODES, &ss->s.light);
    for (m = 0; m < WG_MODES; m++) chart_point(ss, "wedges", wg_modes[m].name, &jobs[m], 12);
    ref = ref32(o, ss);
    for (m = 0; m < WG_MODES; m++) {
        job_lib(&x[m], a_wg, &opt, 1);
        x[m].opt.k = 32;
        x[m].opt.wg_mode = wg_modes[m].mode;
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
 * heat map's link and, on `square`, the check of the issue's goal. */
static void wg_section(const bench_opts *o, report *r, scene_state *ss)
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
        ss->s.name, ss->s.mesh.triangle_count, st->wg_silhouettes, st->wg_objects, (unsigned long long)st->wg_pairs, c[0],
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
static void wg_sweep(const bench_opts *o, report *r)
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
            jobs[nj++].opt.wg_mode = wg_modes[m].mode;
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
            x.opt.wg_mode = wg_modes[m].mode;
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
            if (b->ok) snprintf(c[7], sizeof(c[7]), "%u", b->st.wg_silhouettes);
            else snprintf(c[7], sizeof(c[7]), "n/a");
            sec(r, SEC_WG_SWEEP, "| %u | %u | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", ns, part.triangle_count,
                c[7], c[0], c[1], c[2], fastest >= 0 ? algos[fastest].name : "none", c[3], c[4], c[5], c[6],
                b->ok && ad->ok ? "" : b->ok ? ad->err : b->err);
            dl += snprintf(data + dl, sizeof(data) - (size_t)dl, "%u %u %u %.4f %.4f %.4f %.6g %.6g\n", ns,
                           part.triangle_count, b->ok ? b->st.wg_silhouettes : 0u, job_pass(b), job_pass(ad), exact_ms,
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
static void plot_wg_sweep(report *r, const bench_opts *o)
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

static void machine(char *b, size_t n)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512], model[256] = "unknown CPU", fam[32] = "", mod[32] = "";
    if (f) {
        while (fgets(line, sizeof(line), f)) {
            char *v = strchr(line, ':');
            if (!v) continue;
            v++;
            while (*v == ' ') v++;
            v[strcspn(v, "\n")] = '\0';
            if (strncmp(line, "model name", 10) == 0 && strcmp(model, "unknown CPU") == 0)
                snprintf(model, sizeof(model), "%s", v);
            else if (strncmp(line, "cpu family", 10) == 0 && !fam[0]) snprintf(fam, sizeof(fam), "%s", v);
            else if (strncmp(line, "model\t", 6) == 0 && !mod[0]) snprintf(mod, sizeof(mod), "%s", v);
        }
        fclose(f);
    }
    snprintf(b, n, "%s (family %s, model %s), %d cores online", model, fam[0] ? fam : "?", mod[0] ? mod : "?",
             pn_threads_cores());
}

static void report_open(report *r, const bench_opts *o)
{
    int s, v;
    char a[NALGO][64];
    memset(r, 0, sizeof(*r));
    for (s = 0; s < SEC_COUNT; s++) r->sec[s] = open_memstream(&r->buf[s], &r->len[s]);
    r->plots = open_memstream(&r->plots_buf, &r->plots_len);
    r->hmin = 0.5;
    r->hmax = 20.0;
    for (v = 0; v < NALGO; v++) snprintf(a[v], sizeof(a[v]), "%s", algos[v].name);

    sec(r, SEC_HEADLINE,
        "| scene | triangles | lit pixels | reference ms | GEARS ms | raytrace ms | Embree ms (API) | GEARS vs reference | "
        "GEARS vs raytrace | GEARS vs Embree | necessary / total |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    sec(r, SEC_PORTS, "| scene | port | threads |");
    for (v = 0; v < NALGO; v++) sec(r, SEC_PORTS, " %s ms (pass / total) |", a[v]);
    sec(r, SEC_PORTS, " Embree ms (API) |");
    for (v = 0; v < NALGO; v++) sec(r, SEC_PORTS, " %s speed-up over Embree |", a[v]);
    sec(r, SEC_PORTS, " reps |\n| --- | --- | ---: |");
    for (v = 0; v < 2 * NALGO + 2; v++) sec(r, SEC_PORTS, " ---: |");
    sec(r, SEC_PORTS, "\n");
    sec(r, SEC_EMBREE,
        "| scene | port | threads | Embree BVH build ms | our BVH build ms | rtcOccluded1 ms | rtcOccluded16 ms | "
        "rtcOccluded16 vs rtcOccluded1 | faster | GEARS vs Embree (static: pass only) | GEARS vs Embree (dynamic: build + pass) |\n"
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: |\n");
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
    fprintf(r->plots, "# Generated by penumbra_bench: run `gnuplot plots.gp` in this directory (tools/bench.sh does).\n"
                      "# The gallery panels it reads from work/ are removed afterwards; make bench recreates them.\n");
}

static void plot_sweeps(report *r, const bench_opts *o)
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

/* MCSM's convergence: every scene's RMSE against rays per pixel, log-log, with the slopes of
 * plain (-1/2) and stratified (-3/4) sampling through the largest error for scale. */
static void plot_mc_convergence(report *r)
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

static void plot_headline(report *r, const bench_opts *o)
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

/* The sections after the headline, in order: heading and the note that explains the
 * columns (the sweeps and the accuracy heading are built in print_report). */
static const struct {
    int sec;
    const char *heading, *note;
} notes[] = {
    {SEC_PORTS, "## Per port: milliseconds and speed-up over Embree (issue 5, table 1)",
     "Embree runs with the same thread count as the port on its row. The per-sample ray tracer is a baseline, "
     "measured on the first row of each scene only. A port added to `ports[]` in tools/penumbra_bench.c gets its "
     "rows here."},
    {SEC_EMBREE, "## Embree 3 baseline",
     "Static: shadow pass against shadow pass (paper Table 7, column B). Dynamic: Embree's BVH build plus its pass "
     "against our scene copy and BVH build plus GEARS' pass (column C: a scene that changes every frame)."},
    {SEC_RES, NULL, NULL},
    {SEC_K, NULL, NULL},
    {SEC_LIGHT, NULL, NULL},
    {SEC_GRID, NULL, NULL},
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
     "repetition's, from `pn_stats` (srt_ns_map: window, shadow map, conservative marks, penumbra "
     "tiles; srt_ns_classify: classification and the PIP list; srt_ns_exact: the PIP pixels' exact masks). The issue's "
     "goal: at least 5x on every shared scene for soft shadows."},
    {SEC_SRT_BOUND, "### What SRT can save: the reference's cost by pixel class (area light)",
     "The library's per-pixel kernel (`pn_reference_pixel`) over a host BVH, each lit pixel timed alone and classed "
     "by its own visibility: lit (1), umbra (0), penumbra (in between). Work: BVH nodes tested + triangles handed to "
     "the predicate (deterministic); time: wall clock (noisy). Bound: with exact masks for the penumbra pixels only "
     "(a perfect PIP set) and a free shadow map, a selective ray tracer built on the reference's per-pixel path "
     "cannot be faster than all pixels' cost over the penumbra pixels' cost. The last column checks the host "
     "kernel's visibility against the library's reference frame."},
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
    {SEC_MC_CLAIMS, "## Monte Carlo shadow maps (Curtis 2009): the thesis' claims",
     "Every configuration against a k = 32 reference at the main point's size (area light): the default (what "
     "`--algo mcsm` renders: near and far depth layers of 512x512 texels seen from behind the light, hierarchical "
     "search through their N-buffer, 3x3 jittered rays per pixel, the depth-aware blur at its default radius "
     "(`mc_blur` = 0, penumbra.h)) and one change of "
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
     "RMSE against the k = 32 reference with the blur off (two layers, hierarchical search), n x n jittered rays "
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
    {SEC_MC_GOAL, "### MCSM: the issue's goal",
     "The default (its run of the claims table) against the fastest exact algorithm of the main point (of reference, "
     "GEARS and raytrace), its RMSE against the main point's reference, and the chart's front judged as for the "
     "occlusion textures (no point of the time-vs-error chart but MCSM's own configurations is both faster and "
     "more accurate; otherwise the points that are). The issue's goal: with 3x3 rays and two hierarchical layers, "
     "an RMSE of at most 0.05 against the reference and at least 5x faster than the fastest exact algorithm on "
     "every shared scene, and on the chart's front on at least half of the shared scenes."},
    {SEC_WG_MODES, "## Penumbra wedges (Forest et al. 2006): additive against blended",
     "Per scene at the main point's size and k (area light), run interleaved: the default (what `--algo wedges` "
     "renders: the objects' occluded areas combined by the paper's overlap blending, §3.2) and the classic sum of "
     "the penumbra-wedges algorithm (`wg_mode` = PN_WG_MODE_ADDITIVE). ms: the shadow pass's median; the stages are "
     "the blended frame's last repetition, from `pn_stats` (silhouettes: how each triangle casts and the silhouette "
     "edges seen from the light centre; binning: each wedge's screen tiles, sorted by tile; pixels: each pixel's "
     "centre ray and its tile's wedges, with the blending). Silhouette edges: the wedges built (`wg_silhouettes`); "
     "objects: triangles joined by shared vertices (`wg_objects`, what the blending combines); pairs: (screen tile, "
     "wedge) pairs binned (`wg_pairs`). \"Additive vs blended\": blended's median over additive's (above 1: the "
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

static void print_report(report *r, const bench_opts *o, FILE *out, const char *mach, const char *emb_info, int threads,
                         double minutes)
{
    static const char *sweep_title[] = {"Cost vs output resolution (paper Table 1)", "Cost vs mask resolution k (paper Table 2)",
                                        "Cost vs light size (paper Table 3)", "Cost vs GEARS grid resolution (paper Table 4)"};
    char date[64];
    time_t now = time(NULL);
    int s;
    for (s = 0; s < SEC_COUNT; s++) fflush(r->sec[s]);
    strftime(date, sizeof(date), "%Y-%m-%d %H:%M UTC", gmtime(&now));
    fprintf(out, "# penumbra benchmark results\n\n");
    fprintf(out, "Generated by `%s` (tools/penumbra_bench.c) on %s%s%s; the whole run took %.1f minutes. "
                 "Every number below is what that run printed.\n\n",
            o->quick ? "make bench-quick" : "make bench", date, o->label ? ", " : "", o->label ? o->label : "", minutes);
    fprintf(out, "- Machine: %s. Threads: %d (the scalar port's parallel-for and Embree's `threads=N`); the per-port "
                 "table measures %s (a port with a device of its own: its threads column is Embree's).\n",
            mach, threads, o->nports >= 3 || NPORT < 3 ? "every port and the scalar port on 1 thread" : "every port");
    if (port_devices[0]) fprintf(out, "- %s.\n", port_devices);
    fprintf(out, "- Build: %s, compiler %s, library compiled for %s. %s.\n", PN_BENCH_BUILD_TYPE, __VERSION__,
            PN_BENCH_TARGET_ARCH[0] ? "-march=" PN_BENCH_TARGET_ARCH : "the compiler's default target", emb_info);
    fprintf(out, "- Method: medians of %d repetitions (%d when one repetition took over %.0f s; the `reps` column says "
                 "which); within a repetition every algorithm, both Embree APIs and both BVH builds run one after the "
                 "other, so each ratio compares medians measured side by side in the same run. \"X vs Y\" is Y's median "
                 "over X's: above 1 means X is faster.\n",
            o->reps, o->reps_slow, o->slow_s);
    fprintf(out, "- Shadow pass: `pn_get_stats` `pass_ns[PN_PASS_SHADOW]`; total: the wall time of `pn_render` "
                 "(G-buffer, shadow pass, shading). Embree's pass starts from the reference's G-buffer and computes "
                 "the same origins O (kernels/pn_predicate.h `pn_shadow_origin`) and the same k x k samples, traces "
                 "k^2 occlusion rays per pixel (tnear 0, tfar 1 - 1e-6, direction S - O); the pixel's own triangle is "
                 "not excluded (it blocks the samples behind its plane, as our horizon does).\n");
    fprintf(out, "- Defaults: %ux%u, k = %u, GEARS grid %u, eps = 1e-4 x scene diagonal; for a glTF scene its view "
                 "in the scenes directory's views.json (camera, light, ground) where it has one, else the CLI's "
                 "automatic view and light with the ground plane; each built-in scene's own view.\n\n",
            o->size, o->size, o->k, o->grid);
    if (!o->lean) summary_print(r, out, o);
    fprintf(out, "## Headline: per scene, %ux%u, k = %u, %d threads\n\n%s\n", o->size, o->size, o->k, threads,
            r->buf[SEC_HEADLINE]);
    if (A_RT < 0)
        fprintf(out, "The raytrace column (PN_ALGO_RAYTRACE, k^2 single rays per pixel through the BVH) stays empty "
                     "until that algorithm is in the build.\n\n");
    fprintf(out, "\"necessary / total\" is paper Table 6: triangle-to-pixel assignments that block at least one "
                 "sample, over all assignments the grid made (a GEARS frame with `exact_stats = 1`).\n\n");
    fprintf(out, "Why GEARS is not faster than the reference (issue 14), in instructions, boxes and predicate calls "
                 "per lit pixel: [docs/gears-vs-reference.md](../gears-vs-reference.md) (tools/exact_profile.sh, run by "
                 "hand).\n\n");
    fprintf(out, "![GEARS speed-ups](speedup.png)\n\n");
    if (!o->quick)
        fprintf(out, "Where the time goes: the callgrind section at the end of this page (tools/bench_profile.sh).\n\n");
    for (s = 0; s < (int)(sizeof(notes) / sizeof(notes[0])); s++) {
        int sw = notes[s].sec;
        if (sw >= SEC_RES && sw <= SEC_GRID) {
            fprintf(out, "## %s\n\n", sweep_title[sw - SEC_RES]);
            if (r->sweep_scenes)
                fprintf(out, "%s\n![%s](%s.png)\n\n", r->buf[sw], sweep_title[sw - SEC_RES], sweep_file[sw - SEC_RES]);
            else fprintf(out, "(no sweep scenes in this run)\n\n");
            if (sw == SEC_GRID)
                fprintf(out, "Shadow pass ms, medians; %d threads. Light diagonal d scales the default light's "
                             "half-edges by d / 2, so 2 is the default light (as in the paper, whose default column "
                             "is 2).\n\n",
                        threads);
            continue;
        }
        if (sw >= SEC_WG_MODES && sw <= SEC_WG_SWEEP) {
            /* Not run (wedges not selected or not compiled in, or --lean): no empty tables. */
            if (section_algo(o, PN_ALGO_WEDGES) < 0 || o->lean) continue;
            fprintf(out, "%s\n\n", notes[s].heading);
            if (sw == SEC_WG_MAPS)
                fprintf(out, "%s\n\n%s", notes[s].note, r->len[sw] ? r->buf[sw] : "(no heat map in this run)\n\n");
            else if (sw == SEC_WG_GOAL && !r->wg_goal_rows) fprintf(out, "(`square` is not in this run)\n\n");
            else if (sw == SEC_WG_SWEEP && !r->wg_sweep_ran)
                fprintf(out, "(`spheres` is not in this run: it runs when --only names it or is absent, and with --quick)\n\n");
            else fprintf(out, "%s\n%s\n\n", r->buf[sw], notes[s].note);
            if (sw == SEC_WG_SWEEP && r->wg_sweep)
                fprintf(out, "![Penumbra wedges: time against triangles](wg_sweep.png)\n\n");
            continue;
        }
        if (sw == SEC_ACCURACY) fprintf(out, "## Accuracy against the reference (%ux%u, k = %u)\n\n", o->size, o->size, o->k);
        else fprintf(out, "%s\n\n", notes[s].heading);
        fprintf(out, "%s\n%s\n\n", r->buf[sw], notes[s].note);
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
    fprintf(out, "## Time against error\n\nPer scene, %ux%u, k = %u, area light: each algorithm's shadow pass "
                 "(median, this run) against the RMSE of its visibility to the reference's. Exact algorithms sit at 0; "
                 "Embree traces the same samples and differs only in its arithmetic. Every algorithm and its main "
                 "configurations is a point: the picture to choose an algorithm from.\n\n%s\n",
            o->size, o->size, o->k, r->len[SEC_SRT_CHART] ? r->buf[SEC_SRT_CHART] : "(no SRT section in this run)\n");
    fprintf(out, "## Gallery\n\nPer scene: the shaded reference, its visibility, each algorithm's image and its "
                 "error heat map against the reference (|error| x 4, black = identical), Embree's visibility and "
                 "error, and PCSS's.\n\n%s",
            r->len[SEC_GALLERY] ? r->buf[SEC_GALLERY] : "(no scenes in this run)\n");
}

static void report_close(report *r)
{
    int s;
    for (s = 0; s < SEC_COUNT; s++) {
        fclose(r->sec[s]);
        free(r->buf[s]);
    }
    fclose(r->plots);
    free(r->plots_buf);
}

static void headline_data(FILE *f, report *r, const scene_state *ss)
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

/* ---- main ---------------------------------------------------------------------------- */

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static int parse_list(const char *s, uint32_t *out, uint32_t max)
{
    uint32_t n = 0;
    char *end;
    while (*s && n < max) {
        out[n++] = (uint32_t)strtoul(s, &end, 10);
        if (*end != ',') break;
        s = end + 1;
    }
    return (int)n;
}

static void usage(void)
{
    fprintf(stderr,
            "usage: penumbra_bench [--out DIR] [--scenes DIR] [--quick] [--only a,b] [--sweep-scenes a,b]\n"
            "                      [--algos reference,GEARS,raytrace,SRT,occtex,MCSM,wedges,embree] [--ports N]\n"
            "                      [--lean] [--reps N] [--reps-slow N] [--slow-seconds S] [--threads N] [--size N]\n"
            "                      [--k K] [--sweep-res a,b] [--sweep-k a,b] [--sweep-grid a,b] [--srt-size N]\n"
            "                      [--mc-maps a,b] [--mc-screens a,b] [--wg-spheres a,b] [--label TEXT]\n"
            "Prints Markdown tables and writes DIR/RESULTS.md, DIR/data/*.dat, DIR/plots.gp (gnuplot) and\n"
            "the gallery panels under DIR/work/. Scenes: the built-ins and every .glb in --scenes\n"
            "(default: $PN_SCENES_DIR); the MCSM leak table's closed-box when --only names it or is absent;\n"
            "the wedges' sweep over 1 .. 81 of the spheres (--wg-spheres) when --only names spheres or is\n"
            "absent, and with --quick.\n");
}

int main(int argc, char **argv)
{
    bench_opts o;
    report r;
    char *names[MAX_SCENES];
    int builtin[MAX_SCENES], nscenes = 0, i, p, threads;
    const char *const *bn = pn_builtin_scene_names();
    char mach[512], emb_info[400], path[1400];
    uint64_t t_start = pn_threads_now_ns(NULL);
    FILE *f;

    memset(&o, 0, sizeof(o));
    o.out_dir = "bench-out";
    o.scenes_dir = getenv("PN_SCENES_DIR");
    o.reps = 5;
    o.reps_slow = 3;
    o.slow_s = 30.0;
    o.nports = 2;
    o.size = 512;
    o.k = 16;
    o.grid = 128;
    o.sweep_scenes = "thin,chess_set,cad_infineon_easypim2b";
    o.srt_big = 1024;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--quick") == 0) o.quick = 1;
        else if (strcmp(a, "--lean") == 0) o.lean = 1;
        else if (!v) {
            usage();
            return 2;
        } else if (strcmp(a, "--out") == 0) o.out_dir = argv[++i];
        else if (strcmp(a, "--scenes") == 0) o.scenes_dir = argv[++i];
        else if (strcmp(a, "--only") == 0) o.only = argv[++i];
        else if (strcmp(a, "--sweep-scenes") == 0) o.sweep_scenes = argv[++i];
        else if (strcmp(a, "--label") == 0) o.label = argv[++i];
        else if (strcmp(a, "--algos") == 0) o.algos = argv[++i];
        else if (strcmp(a, "--ports") == 0) o.nports = atoi(argv[++i]);
        else if (strcmp(a, "--reps") == 0) o.reps = atoi(argv[++i]);
        else if (strcmp(a, "--reps-slow") == 0) o.reps_slow = atoi(argv[++i]);
        else if (strcmp(a, "--slow-seconds") == 0) o.slow_s = atof(argv[++i]);
        else if (strcmp(a, "--threads") == 0) o.threads = atoi(argv[++i]);
        else if (strcmp(a, "--size") == 0) o.size = (uint32_t)atoi(argv[++i]);
        else if (strcmp(a, "--k") == 0) o.k = (uint32_t)atoi(argv[++i]);
        else if (strcmp(a, "--srt-size") == 0) o.srt_big = (uint32_t)atoi(argv[++i]);
        else if (strcmp(a, "--sweep-res") == 0) o.n_res = (uint32_t)parse_list(argv[++i], o.sweep_res, 8);
        else if (strcmp(a, "--sweep-k") == 0) o.n_k = (uint32_t)parse_list(argv[++i], o.sweep_k, 8);
        else if (strcmp(a, "--sweep-grid") == 0) o.n_grid = (uint32_t)parse_list(argv[++i], o.sweep_grid, 8);
        else if (strcmp(a, "--mc-maps") == 0) o.n_mc_map = (uint32_t)parse_list(argv[++i], o.mc_map, 6);
        else if (strcmp(a, "--mc-screens") == 0) o.n_mc_screen = (uint32_t)parse_list(argv[++i], o.mc_screen, 4);
        else if (strcmp(a, "--wg-spheres") == 0) o.n_wg_spheres = (uint32_t)parse_list(argv[++i], o.wg_spheres, 9);
        else {
            usage();
            return 2;
        }
    }
    if (o.quick) {
        /* A small subset that still runs every code path: CI-friendly (well under two
         * minutes on two cores). */
        if (!o.only) o.only = "square,elongated-cube,room,canopy,colonnade,spot,grey_white_room,copper_beech,closed-box";
        o.sweep_scenes = "spot";
        o.size = 128;
        o.srt_big = 256;
        o.reps = o.reps_slow = 3;
        if (!o.n_res) o.n_res = (uint32_t)parse_list("64,128,192", o.sweep_res, 8);
        if (!o.n_k) o.n_k = (uint32_t)parse_list("4,16", o.sweep_k, 8);
        if (!o.n_grid) o.n_grid = (uint32_t)parse_list("32,128", o.sweep_grid, 8);
        o.n_light = 2;
        o.sweep_light[0] = 1.0f;
        o.sweep_light[1] = 4.0f;
        if (!o.n_mc_map) o.n_mc_map = (uint32_t)parse_list("128,256", o.mc_map, 6);
        if (!o.n_mc_screen) o.n_mc_screen = (uint32_t)parse_list("128,256", o.mc_screen, 4);
        if (!o.n_wg_spheres) o.n_wg_spheres = (uint32_t)parse_list("1,4", o.wg_spheres, 9);
    } else {
        if (!o.n_res) o.n_res = (uint32_t)parse_list("256,512,1024,1280", o.sweep_res, 8);
        if (!o.n_k) o.n_k = (uint32_t)parse_list("4,8,16,32", o.sweep_k, 8);
        if (!o.n_grid) o.n_grid = (uint32_t)parse_list("32,64,128,256", o.sweep_grid, 8);
        o.n_light = 5;
        for (i = 0; i < 5; i++) o.sweep_light[i] = (float)(i + 1);
        if (!o.n_mc_map) o.n_mc_map = (uint32_t)parse_list("128,256,512,1024,2048", o.mc_map, 6);
        if (!o.n_mc_screen) o.n_mc_screen = (uint32_t)parse_list("256,512,1024", o.mc_screen, 4);
        if (!o.n_wg_spheres) o.n_wg_spheres = (uint32_t)parse_list("1,4,9,16,25,36,49,64,81", o.wg_spheres, 9);
    }
    {
        /* MCSM maps that this build's pn_limits do not allow (pn_arena_size refuses an
         * mc_map_max over PN_MCSM_MAP_MAX) are left out; the report says so. */
        pn_limits lim;
        size_t bytes;
        uint32_t v, nm = 0;
        memset(&lim, 0, sizeof(lim));
        lim.max_triangles = 1;
        lim.max_width = lim.max_height = 8;
        for (v = 0; v < o.n_mc_map; v++) {
            lim.mc_map_max = o.mc_map[v];
            if (o.mc_map[v] >= 8u && pn_arena_size(&lim, &bytes) == PN_OK) {
                o.mc_map[nm++] = o.mc_map[v];
                if (o.mc_map[v] > o.mc_map_max) o.mc_map_max = o.mc_map[v];
            } else {
                o.mc_map_cut = 1;
            }
        }
        o.n_mc_map = nm;
    }
    if (o.reps < 1 || o.reps > MAX_REPS || o.reps_slow < 1 || o.reps_slow > MAX_REPS) {
        fprintf(stderr, "penumbra_bench: --reps must be 1..%d\n", MAX_REPS);
        return 2;
    }
    threads = o.threads > 0 ? o.threads : pn_threads_cores();

    /* Scenes: built-ins, then the shared glTF files in name order. */
    for (; *bn && nscenes < MAX_SCENES; bn++)
        if (in_list(o.only, *bn)) {
            names[nscenes] = strdup(*bn);
            builtin[nscenes++] = 1;
        }
    if (o.scenes_dir) {
        DIR *d = opendir(o.scenes_dir);
        struct dirent *e;
        int first = nscenes;
        if (!d) progress("warning: cannot open scenes directory %s: %s", o.scenes_dir, strerror(errno));
        while (d && (e = readdir(d)) != NULL && nscenes < MAX_SCENES) {
            size_t len = strlen(e->d_name);
            char stem[256];
            if (len < 5 || strcmp(e->d_name + len - 4, ".glb") != 0 || len - 4 >= sizeof(stem)) continue;
            memcpy(stem, e->d_name, len - 4);
            stem[len - 4] = '\0';
            if (!in_list(o.only, stem)) continue;
            snprintf(path, sizeof(path), "%s/%s", o.scenes_dir, e->d_name);
            names[nscenes] = strdup(path);
            builtin[nscenes++] = 0;
        }
        if (d) closedir(d);
        qsort(names + first, (size_t)(nscenes - first), sizeof(char *), cmp_str);
    } else {
        progress("note: no scenes directory (--scenes or PN_SCENES_DIR): built-in scenes only");
    }

    snprintf(path, sizeof(path), "%s/data", o.out_dir);
    if (pn_mkdir_p(path) != 0) {
        fprintf(stderr, "penumbra_bench: cannot create %s\n", path);
        return 1;
    }
    snprintf(path, sizeof(path), "%s/gallery", o.out_dir);
    pn_mkdir_p(path);
    machine(mach, sizeof(mach));
    {
        pn_embree *e = NULL;
        char err[256];
        if (pn_embree_open(&e, threads, err, sizeof(err)) == 0) {
            snprintf(emb_info, sizeof(emb_info), "%s", pn_embree_info(e));
            pn_embree_close(e);
        } else {
            snprintf(emb_info, sizeof(emb_info), "Embree baseline unavailable: %s", err);
        }
    }
    progress("penumbra_bench: %s; %d threads; %s; %d scenes", mach, threads, emb_info, nscenes);
    report_open(&r, &o);

    {
        FILE *hd;
        snprintf(path, sizeof(path), "%s/data/headline.dat", o.out_dir);
        hd = fopen(path, "w");
        if (hd) fprintf(hd, "# scene gears_vs_reference gears_vs_embree gears_vs_raytrace\n");
        for (i = 0; i < nscenes; i++) {
            const char *nm = builtin[i] ? names[i] : strrchr(names[i], '/') + 1;
            char stem[256];
            int sweepable;
            pn_embree_api best_api = PN_EMBREE_OCCLUDED16;
            snprintf(stem, sizeof(stem), "%s", nm);
            if (!builtin[i]) stem[strlen(stem) - 4] = '\0';
            sweepable = in_list(o.sweep_scenes, stem);
            progress("[%d/%d] %s", i + 1, nscenes, stem);
            for (p = 0; p < NPORT && p < o.nports; p++) {
                scene_state ss;
                uint32_t max_size = o.size;
                if (p == 0 && !o.lean && o.srt_big > max_size) max_size = o.srt_big;
                if (p == 0 && !o.lean && section_algo(&o, PN_ALGO_MCSM) >= 0)
                    for (uint32_t v = 0; v < o.n_mc_screen; v++)
                        if (o.mc_screen[v] > max_size) max_size = o.mc_screen[v];
                if (p == 0 && sweepable)
                    for (uint32_t v = 0; v < o.n_res; v++)
                        if (o.sweep_res[v] > max_size) max_size = o.sweep_res[v];
                if (scene_open(&o, &ss, names[i], builtin[i], &ports[p], max_size) != 0) {
                    scene_close(&ss);
                    continue;
                }
                main_point(&o, &r, &ss, p == 0);
                if (p == 0 && hd) headline_data(hd, &r, &ss);
                if (p == 0 && !o.lean) {
                    srt_section(&o, &r, &ss);
                    mc_claims(&o, &r, &ss); /* before occ_section: its points are on the front's chart */
                    wg_claims(&o, &ss);     /* the same */
                    occ_section(&o, &r, &ss);
                    mcsm_section(&o, &r, &ss);
                    wg_section(&o, &r, &ss);
                    tradeoff_chart(&o, &r, &ss);
                    summary_scene(&r, &ss);
                }
                if (p == 0 && sweepable) {
                    int kind;
                    best_api = ss.best_api;
                    for (kind = 0; kind < 4; kind++) sweep(&o, &r, &ss, kind, best_api);
                    if (r.sweep_scenes < MAX_SCENES) snprintf(r.sweep_names[r.sweep_scenes++], 128, "%s", ss.s.name);
                }
                scene_close(&ss);
            }
            free(names[i]);
        }
        if (hd) fclose(hd);
    }
    if (!o.lean && in_list(o.only, "closed-box")) mcsm_leaks(&o, &r);
    /* In --quick too (two small cuts, 1 and 4 spheres) so that the quick run covers it. */
    if (!o.lean && (o.quick || in_list(o.only, "spheres"))) wg_sweep(&o, &r);
    plot_sweeps(&r, &o);
    plot_headline(&r, &o);
    plot_mc_convergence(&r);
    plot_wg_sweep(&r, &o);

    snprintf(path, sizeof(path), "%s/RESULTS.md", o.out_dir);
    f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "penumbra_bench: cannot write %s: %s\n", path, strerror(errno));
        report_close(&r);
        return 1;
    }
    {
        double minutes = (pn_threads_now_ns(NULL) - t_start) / 6e10;
        print_report(&r, &o, f, mach, emb_info, threads, minutes);
        print_report(&r, &o, stdout, mach, emb_info, threads, minutes);
    }
    fclose(f);
    fflush(r.plots);
    snprintf(path, sizeof(path), "%s/plots.gp", o.out_dir);
    f = fopen(path, "w");
    if (f) {
        fwrite(r.plots_buf, 1, r.plots_len, f);
        fclose(f);
    }
    report_close(&r);
    return 0;
}
