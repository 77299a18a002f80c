/* jobs.c - what penumbra_bench measures and how one measurement runs: the algorithms, the
 * ports and the baselines; a job (one timed thing inside a repetition) and the interleaved
 * repetitions; medians and number formats; a visibility buffer's accuracy against a
 * reference; a scene's set-up on a port. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#if PN_BENCH_OPENCL
#include "penumbra/opencl.h"
#include "pn_cl_host.h"
#endif
#include "bench.h"
#include "pn_image.h"

/* ---- What is measured: algorithms and ports ------------------------------------------- */

/* Every algorithm of the library, at its pn_algo index: the name the tables print and
 * --algos takes, and whether it must give the reference's bits. A new algorithm (its
 * registry line, src/pn_algorithms.h, raises NALGO) adds its line here, and its accuracy,
 * timing and gallery columns follow. */
const bench_algo algos[NALGO] = {
    [PN_ALGO_REFERENCE] = {"reference", PN_ALGO_REFERENCE, PN_BUILD_REFERENCE, 1, 1},
    [PN_ALGO_GEARS] = {"GEARS", PN_ALGO_GEARS, PN_BUILD_GEARS, 1, 1},
    [PN_ALGO_RAYTRACE] = {"raytrace", PN_ALGO_RAYTRACE, PN_BUILD_RAYTRACE, 1, 0},
    [PN_ALGO_SRT] = {"SRT", PN_ALGO_SRT, PN_BUILD_SRT, 0, 1},
    [PN_ALGO_OCCTEX] = {"occtex", PN_ALGO_OCCTEX, PN_BUILD_OCCTEX, 0, 1},
    [PN_ALGO_MCSM] = {"MCSM", PN_ALGO_MCSM, PN_BUILD_MCSM, 0, 1},
    [PN_ALGO_WEDGES] = {"wedges", PN_ALGO_WEDGES, PN_BUILD_WEDGES, 0, 1},
};

static pn_status scalar_render(pn_host *h, void *state, const pn_camera *cam, const pn_light *light,
                               const pn_frame_options *opt, pn_frame *out)
{
    (void)state;
    return pn_render(h->ctx, cam, light, opt, out);
}

/* Ports with a device of their own name it here, for the report's header. */
char port_devices[256];

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
const bench_port ports[] = {
    {"scalar", 0, NULL, scalar_render, NULL},
#if PN_BENCH_OPENCL
    {"opencl", 0, opencl_attach, opencl_render, opencl_detach},
#endif
    {"scalar", 1, NULL, scalar_render, NULL},
};
/* NPORT (bench.h) must count the lines above. */
typedef char bench_nport_check[(int)(sizeof(ports) / sizeof(ports[0])) == NPORT ? 1 : -1];


/* The baselines a user would pick instead of an approximate algorithm, measured beside
 * every algorithm at the main point: the exact reference with fewer light samples (the
 * cheap exact answer) and percentage-closer soft shadows (what engines ship;
 * tools/pn_bench_pcss.c). Their errors are against the main point's reference (k as in the
 * headline). */
const bench_baseline baselines[NBASE] = {{"reference k=4", 4, 9}, {"reference k=8", 8, 9}, {"PCSS", 0, 11}};

/* ---- Small helpers ---------------------------------------------------------------------- */

int in_list(const char *list, const char *name)
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

void fmt_ms(char *b, size_t n, double ms)
{
    if (!(ms == ms)) snprintf(b, n, "n/a");
    else if (ms >= 100.0) snprintf(b, n, "%.0f", ms);
    else if (ms >= 10.0) snprintf(b, n, "%.1f", ms);
    else snprintf(b, n, "%.2f", ms);
}

/* "12.3x" for a ratio a/b of two medians, "n/a" when either is missing. */
void fmt_ratio(char *b, size_t n, double num, double den)
{
    double r = num / den;
    if (!(num == num) || !(den == den) || !(den > 0.0)) snprintf(b, n, "n/a");
    else if (r >= 10.0) snprintf(b, n, "%.1fx", r);
    else snprintf(b, n, "%.2fx", r);
}

void progress(const char *fmt, ...)
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

void job_lib(job *j, int algo, const pn_frame_options *opt, int keep)
{
    memset(j, 0, sizeof(*j));
    j->kind = JOB_LIB;
    j->algo = algo;
    j->opt = *opt;
    j->opt.algo = algos[algo].algo;
    j->keep = keep;
    j->ok = 1;
}

void job_emb(job *j, pn_embree_api api, const pn_frame_options *opt, int keep)
{
    memset(j, 0, sizeof(*j));
    j->kind = JOB_EMBREE;
    j->api = api;
    j->opt = *opt;
    j->keep = keep;
    j->ok = 1;
}

void job_free(job *j)
{
    free(j->vis);
    free(j->rgba);
    j->vis = NULL;
    j->rgba = NULL;
}

double job_pass(const job *j) { return j->ok && j->n > 0 ? median(j->pass, j->n) : NAN; }
double job_total(const job *j) { return j->ok && j->n > 0 ? median(j->total, j->n) : NAN; }

/* Runs one job once; rep 0 of a keeping job stores its visibility. */
void job_run(scene_state *ss, job *j, const pn_light *light, int rep)
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
    if (j->kind == JOB_EMBREE_BUILD || j->kind == JOB_EMBREE_BUILD_HIGH) {
        double ms;
        int high = j->kind == JOB_EMBREE_BUILD_HIGH;
        if (!ss->emb) {
            snprintf(j->err, sizeof(j->err), "%s", ss->emb_err);
            j->ok = 0;
            return;
        }
        if (pn_embree_build(ss->emb, &ss->s.mesh, high ? PN_EMBREE_HIGH : 0, &ms, err, sizeof(err)) != 0) {
            snprintf(j->err, sizeof(j->err), "%s", err);
            j->ok = 0;
            return;
        }
        ss->emb_built = !high; /* the passes trace the default build's tree */
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
int run_jobs(const bench_opts *o, scene_state *ss, job *jobs, int njobs, const pn_light *light)
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
accuracy compare_vis(const float *a, const float *ref, size_t n)
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

/* ---- Per-scene work ----------------------------------------------------------------------- */

/* A signed per-pixel map as a PNG next to RESULTS.md (OUT/<file>_<scene>.png): where |d[i]| >
 * tol, the colour pos (d > 0) or neg (channel weights 0 or 1), brighter with |d| (full at
 * 0.25, as in the gallery's error maps); elsewhere the shaded k = 32 reference in grey (its
 * visibility without one), so the coloured pixels can be placed in the scene. */
int heat_png(const bench_opts *o, const scene_state *ss, const char *file, const float *d, const float *ref,
             uint32_t w, uint32_t h, double tol, const uint8_t pos[3], const uint8_t neg[3])
{
    size_t n = (size_t)w * h, i;
    uint8_t *img = (uint8_t *)malloc(n * 4);
    char path[1400], err[256];
    int rc, c;
    if (!img || !d || !ref) {
        free(img);
        return 1;
    }
    if (!ss->ref32_rgba) pn_vis_to_rgba(ref, n, img);
    for (i = 0; i < n; i++) {
        double t = fabs((double)d[i]) * 4.0 > 1.0 ? 1.0 : fabs((double)d[i]) * 4.0;
        uint8_t *p = img + 4 * i;
        if (d[i] > tol || d[i] < -tol) {
            uint8_t v = (uint8_t)(96.0 + 159.0 * t + 0.5);
            for (c = 0; c < 3; c++) p[c] = (d[i] > 0.0f ? pos[c] : neg[c]) ? v : 0;
        } else if (ss->ref32_rgba) {
            const uint8_t *q = ss->ref32_rgba + 4 * i;
            p[0] = p[1] = p[2] = (uint8_t)(0.299 * q[0] + 0.587 * q[1] + 0.114 * q[2] + 0.5);
        }
        p[3] = 255;
    }
    snprintf(path, sizeof(path), "%s/%s_%s.png", o->out_dir, file, ss->s.name);
    rc = pn_write_png(path, img, w, h, err, sizeof(err));
    if (rc != 0) progress("    heat map %s: %s", file, err);
    free(img);
    return rc;
}

/* A frame's signed error against the k = 32 reference as a heat map (heat_png: red brighter,
 * blue darker, any difference above 1/255), OUT/<file>_<scene>.png, and its line in section
 * s of the report (what: whose frame, "the default"). */
void error_heat(const bench_opts *o, report *r, int s, const scene_state *ss, const char *file, const char *what,
                const float *vis, const float *ref, uint32_t w, uint32_t h)
{
    static const uint8_t red[3] = {1, 0, 0}, blue[3] = {0, 0, 1};
    size_t n = (size_t)w * h, p;
    float *d;
    if (!vis || !ref) return;
    d = (float *)malloc(n * sizeof(float));
    if (!d) return;
    for (p = 0; p < n; p++) d[p] = vis[p] - ref[p];
    if (heat_png(o, ss, file, d, ref, w, h, 1.0 / 255.0, red, blue) == 0)
        sec(r, s, "**%s**, %s\n\n![%s: %s's error, red brighter, blue darker](%s_%s.png)\n\n", ss->s.name, what,
            ss->s.name, what, file, ss->s.name);
    free(d);
}

void write_data(const bench_opts *o, const char *name, const char *scene, const char *text)
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

void scaled_light(const pn_light *l, float s, pn_light *out)
{
    int a;
    *out = *l;
    for (a = 0; a < 3; a++) {
        out->u[a] = l->u[a] * s;
        out->v[a] = l->v[a] * s;
    }
}

int scene_open(const bench_opts *o, scene_state *ss, const char *source, int builtin, const bench_port *port,
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

void scene_close(scene_state *ss)
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

void base_options(const bench_opts *o, const scene_state *ss, pn_frame_options *opt)
{
    pn_frame_options_default(opt);
    opt->width = opt->height = o->size;
    opt->k = o->k;
    opt->gears.grid = o->grid;
    opt->eps = ss->s.eps;
}
