/* bench_ports - the ports side by side: the scalar port on N threads (the pthread
 * parallel-for, tools/pn_threads.h) and the OpenCL port on one device, for the G-buffer and
 * every algorithm the build has, on the scenes of the shared set, in one run, so the ratios
 * are measured under the same conditions. Also the OpenCL kernel build time with an empty
 * kernel cache and with a warm one.
 *
 *   bench_ports [--scenes DIR] [--only TEXT[,TEXT...]] [--algos NAME[,NAME...]]
 *               [--size WxH] [--k K] [--reps N] [--threads N] [--cl-device SPEC]
 *               [--cache DIR] [--no-build-time] [--no-warmup]
 *
 *   --only      scenes whose file name contains one of the texts (default: every .glb)
 *   --algos     reference gears raytrace srt occtex mcsm wedges (default: all built)
 *   --threads   the scalar port's threads (default: every core)
 *   --cl-device the OpenCL device (penumbra/opencl.h, DEVICE CHOICE: gpu, cpu, P:D, part of
 *               the name; default PN_OPENCL_DEVICE, else the first PoCL CPU device)
 *
 * Scenes are rendered with their views (views.json in the scene folder), at --size.
 * Times are the library's per-pass times (pn_stats.pass_ns; the OpenCL port's include
 * reading the pass's results back into the arena), medians of N repetitions: the G-buffer
 * row is the median over every frame of the scene, an algorithm's row its shadow pass. The
 * ports take turns: each (repetition, algorithm) renders on the scalar port, then on the
 * OpenCL port, and the OpenCL frame's visibility, RGBA image and depth are compared with the
 * scalar frame's byte for byte ("same"). A frame that fails (say PN_E_POOL_EXHAUSTED: a
 * pool too small for the size) must fail with the same status and message on both ports;
 * its row shows the status. The last line says whether every frame was the same.
 *
 * Before the first scene's repetitions, every algorithm renders once on the OpenCL port,
 * untimed (--no-warmup: not): PoCL compiles specialised kernel variants at their first
 * launches, which would otherwise land in the first scene's times.
 *
 * Build times come from two child processes started before this one touches OpenCL: the
 * first with an empty kernel cache directory (a new one under --cache, as POCL_CACHE_DIR
 * and CUDA_CACHE_PATH), the second with the one the first filled. --no-build-time skips
 * them. */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "penumbra/opencl.h"
#include "pn_cl_host.h"
#include "penumbra/penumbra.h"
#include "pn_setup.h"

#define MAX_REPS 15

enum { P_SCALAR, P_OPENCL, P_COUNT };
static const char *const port_names[P_COUNT] = {"scalar", "opencl"};

/* Every algorithm: pn_algo 0 .. PN_ALGO_COUNT - 1 (the registry), named by pn_algo_name,
 * compiled in when pn_build_info() has bit 1u << algo. */
#define ALGO_COUNT PN_ALGO_COUNT

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    if (n <= 0) return 0.0;
    qsort(v, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* 1 when `name` contains one of the comma-separated texts of `list`. */
static int matches_any(const char *name, const char *list)
{
    char buf[256];
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        if (n > 0 && n < sizeof(buf)) {
            memcpy(buf, p, n);
            buf[n] = 0;
            if (strstr(name, buf)) return 1;
        }
        p += n;
        if (*p == ',') p++;
    }
    return 0;
}

/* 1 when `name` is one of the comma-separated names of `list`. */
static int listed(const char *name, const char *list)
{
    size_t len = strlen(name);
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        if (n == len && strncmp(p, name, n) == 0) return 1;
        p += n;
        if (*p == ',') p++;
    }
    return 0;
}

/* ---- kernel build time ------------------------------------------------------------------ */

/* In a child: create the port on a tiny context with its kernel caches in dir and report
 * build_ms and warmup_ms through the pipe. */
static int build_time(const char *dir, const char *device, double *build_ms, double *warmup_ms)
{
    int fd[2];
    pid_t pid;
    double v[2] = {-1.0, -1.0};
    if (pipe(fd) != 0) return 1;
    fflush(NULL);
    pid = fork();
    if (pid == 0) {
        pn_limits lim = {16, 16, 16, 1024, 16, 0, 0, 0, 0, 0, 0, 0, 0};
        size_t bytes;
        void *mem;
        pn_context *ctx;
        pn_opencl *cl;
        pn_opencl_info info;
        pn_opencl_options o;
        close(fd[0]);
        setenv("POCL_CACHE_DIR", dir, 1);
        setenv("CUDA_CACHE_PATH", dir, 1); /* NVIDIA's OpenCL keeps its compiled kernels there */
        pn_opencl_options_default(&o);
        o.device = device;
        if (pn_arena_size(&lim, &bytes) == PN_OK && (mem = malloc(bytes)) != NULL &&
            pn_init(&ctx, mem, bytes, &lim) == PN_OK) {
            if (pn_cl_open(ctx, &o, &cl) == PN_OK && pn_opencl_get_info(cl, &info) == PN_OK) {
                v[0] = info.build_ms;
                v[1] = info.warmup_ms;
            } else {
                fprintf(stderr, "bench_ports: %s\n", pn_last_error(ctx));
            }
        }
        if (write(fd[1], v, sizeof(v)) != (ssize_t)sizeof(v)) _exit(1);
        _exit(0);
    }
    close(fd[1]);
    if (pid < 0 || read(fd[0], v, sizeof(v)) != (ssize_t)sizeof(v)) v[0] = -1.0;
    close(fd[0]);
    if (pid > 0) waitpid(pid, NULL, 0);
    *build_ms = v[0];
    *warmup_ms = v[1];
    return v[0] < 0.0;
}

static int rm_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    return remove(path);
}

/* ---- one scene -------------------------------------------------------------------------- */

typedef struct bench_cfg {
    const char *scenes;
    uint32_t w, h, k;
    int reps, threads;
    int warm; /* an untimed OpenCL frame of every algorithm first (the first scene) */
    const char *device;
    int use[ALGO_COUNT];
} bench_cfg;

/* One row of the table: row 0 the G-buffer, row 1 + a algorithm a. */
typedef struct row {
    double ms[P_COUNT];
    int same, failed; /* failed: the frames failed (the same way on both ports) */
    pn_status status;
} row;

typedef struct keep {
    size_t n;
    float *vis, *depth;
    uint8_t *rgba;
    pn_status status;
    char message[256];
} keep;

static void keep_frame(keep *k, const pn_frame *fr, pn_status st, const char *msg)
{
    k->status = st;
    snprintf(k->message, sizeof(k->message), "%s", msg);
    if (st != PN_OK) return;
    memcpy(k->vis, fr->visibility, k->n * sizeof(float));
    memcpy(k->depth, fr->depth, k->n * sizeof(float));
    memcpy(k->rgba, fr->rgba, k->n * 4u);
}

/* Frame (st, fr) of the OpenCL port against the kept scalar frame: *vis_same for the
 * visibility and the image, *gbuf_same for the depth. */
static void compare_frame(const keep *k, const pn_frame *fr, pn_status st, const char *msg, int *vis_same,
                          int *gbuf_same)
{
    if (st != k->status || (st != PN_OK && strcmp(msg, k->message) != 0)) {
        *vis_same = 0;
        return;
    }
    if (st != PN_OK) return;
    if (memcmp(k->vis, fr->visibility, k->n * sizeof(float)) != 0 || memcmp(k->rgba, fr->rgba, k->n * 4u) != 0)
        *vis_same = 0;
    if (memcmp(k->depth, fr->depth, k->n * sizeof(float)) != 0) *gbuf_same = 0;
}

static int bench_scene(const bench_cfg *c, const char *path, row rows[1 + ALGO_COUNT], uint32_t *tris,
                       char *device, size_t device_cap)
{
    pn_setup s;
    pn_host host;
    pn_opencl *cl = NULL;
    pn_opencl_options o;
    char err[512];
    double g[P_COUNT][ALGO_COUNT * MAX_REPS], sh[ALGO_COUNT][P_COUNT][MAX_REPS];
    keep kp;
    int r, p, rc = 0, ng[P_COUNT] = {0, 0};
    size_t a;
    pn_frame_options opt;
    memset(&kp, 0, sizeof(kp));
    kp.n = (size_t)c->w * c->h;
    kp.vis = (float *)malloc(kp.n * sizeof(float));
    kp.depth = (float *)malloc(kp.n * sizeof(float));
    kp.rgba = (uint8_t *)malloc(kp.n * 4u);
    if (!kp.vis || !kp.depth || !kp.rgba || pn_setup_load_viewed(&s, path, 0, c->scenes, err, sizeof(err)) != 0) {
        fprintf(stderr, "bench_ports: %s: %s\n", path, kp.vis && kp.depth && kp.rgba ? err : "out of memory");
        free(kp.vis);
        free(kp.depth);
        free(kp.rgba);
        return 1;
    }
    *tris = s.mesh.triangle_count;
    pn_opencl_options_default(&o);
    o.device = c->device;
    memset(&host, 0, sizeof(host));
    if (pn_host_open(&host, s.mesh.triangle_count, c->w, c->h, c->threads, err, sizeof(err)) != 0 ||
        pn_setup_upload(host.ctx, &s) != PN_OK || pn_cl_open(host.ctx, &o, &cl) != PN_OK) {
        fprintf(stderr, "bench_ports: %s: %s\n", path, host.ctx ? pn_last_error(host.ctx) : err);
        pn_host_close(&host);
        pn_setup_free(&s);
        free(kp.vis);
        free(kp.depth);
        free(kp.rgba);
        return 1;
    }
    snprintf(device, device_cap, "%s", pn_opencl_device_name(cl));
    pn_frame_options_default(&opt);
    opt.width = c->w;
    opt.height = c->h;
    opt.k = c->k;
    opt.eps = s.eps;
    for (a = 0; a <= ALGO_COUNT; a++) {
        memset(&rows[a], 0, sizeof(rows[a]));
        rows[a].same = 1;
    }
    /* The first scene: one untimed frame of every algorithm on the OpenCL port first, so that
     * implementations that compile kernel variants at their first launches (PoCL specialises
     * work-group functions; its cache keeps them) do it outside the timing. */
    if (c->warm)
        for (a = 0; a < ALGO_COUNT; a++) {
            pn_frame fr;
            if (!c->use[a]) continue;
            opt.algo = (pn_algo)(a);
            (void)pn_opencl_render(cl, &s.camera, &s.light, &opt, &fr);
        }
    for (r = 0; r < c->reps; r++)
        for (a = 0; a < ALGO_COUNT; a++) {
            if (!c->use[a]) continue;
            for (p = 0; p < P_COUNT; p++) {
                pn_frame fr;
                pn_stats st;
                pn_status rs;
                const char *msg;
                opt.algo = (pn_algo)(a);
                rs = p == P_OPENCL ? pn_opencl_render(cl, &s.camera, &s.light, &opt, &fr)
                                   : pn_render(host.ctx, &s.camera, &s.light, &opt, &fr);
                msg = rs == PN_OK ? "" : pn_last_error(host.ctx);
                if (p == P_SCALAR) keep_frame(&kp, &fr, rs, msg);
                else compare_frame(&kp, &fr, rs, msg, &rows[1 + a].same, &rows[0].same);
                if (rs != PN_OK) {
                    rows[1 + a].failed = 1;
                    rows[1 + a].status = rs;
                    fprintf(stderr, "  %s %s %s: %s: %s\n", s.name, pn_algo_name((pn_algo)(a)), port_names[p], pn_status_str(rs),
                            msg);
                    continue;
                }
                pn_get_stats(host.ctx, &st);
                g[p][ng[p]++] = st.pass_ns[PN_PASS_GBUFFER] / 1e6;
                sh[a][p][r] = st.pass_ns[PN_PASS_SHADOW] / 1e6;
                fprintf(stderr, "  %s %s %s: G-buffer %.1f ms, shadow %.1f ms\n", s.name, pn_algo_name((pn_algo)(a)),
                        port_names[p], g[p][ng[p] - 1], sh[a][p][r]);
            }
        }
    for (p = 0; p < P_COUNT; p++) {
        rows[0].ms[p] = median(g[p], ng[p]);
        for (a = 0; a < ALGO_COUNT; a++)
            if (c->use[a] && !rows[1 + a].failed) rows[1 + a].ms[p] = median(sh[a][p], c->reps);
    }
    pn_cl_close(cl);
    pn_host_close(&host);
    pn_setup_free(&s);
    free(kp.vis);
    free(kp.depth);
    free(kp.rgba);
    return rc;
}

static int usage(void)
{
    fprintf(stderr, "usage: bench_ports [--scenes DIR] [--only TEXT[,TEXT...]] [--algos NAME[,NAME...]] "
                    "[--size WxH] [--k K]\n"
                    "                   [--reps N] [--threads N] [--cl-device SPEC] [--cache DIR] "
                    "[--no-build-time] [--no-warmup]\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *only = NULL, *algo_list = NULL, *cache = getenv("POCL_CACHE_DIR");
    bench_cfg c;
    int i, n = 0, rc = 0, frames_differ = 0, scenes_done = 0, no_build_time = 0, no_warmup = 0;
    size_t a;
    char cold[1024], device[512] = "?";
    double cold_build = 0, cold_warm = 0, hot_build = 0, hot_warm = 0;
    struct dirent **list;
    memset(&c, 0, sizeof(c));
    c.scenes = PN_SCENES_DIR;
    c.w = c.h = 512;
    c.k = 16;
    c.reps = 3;
    c.threads = pn_threads_cores();
    for (i = 1; i < argc; i++) {
        const char *arg = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(arg, "--no-build-time") == 0) {
            no_build_time = 1;
            continue;
        }
        if (strcmp(arg, "--no-warmup") == 0) {
            no_warmup = 1;
            continue;
        }
        if (!v) {
            fprintf(stderr, "bench_ports: %s needs a value\n", arg);
            return usage();
        }
        i++;
        if (strcmp(arg, "--scenes") == 0) c.scenes = v;
        else if (strcmp(arg, "--size") == 0) {
            if (pn_parse_size(v, &c.w, &c.h)) return usage();
        } else if (strcmp(arg, "--k") == 0) c.k = (uint32_t)strtoul(v, NULL, 10);
        else if (strcmp(arg, "--reps") == 0) c.reps = atoi(v);
        else if (strcmp(arg, "--threads") == 0) c.threads = atoi(v);
        else if (strcmp(arg, "--only") == 0) only = v;
        else if (strcmp(arg, "--algos") == 0) algo_list = v;
        else if (strcmp(arg, "--cl-device") == 0) c.device = v;
        else if (strcmp(arg, "--cache") == 0) cache = v;
        else return usage();
    }
    if (c.reps < 1 || c.reps > MAX_REPS) {
        fprintf(stderr, "bench_ports: --reps must be 1 .. %d\n", MAX_REPS);
        return 2;
    }
    if (c.threads < 1 || c.threads > 1024) {
        fprintf(stderr, "bench_ports: --threads must be 1 .. 1024\n");
        return 2;
    }
    for (a = 0; a < ALGO_COUNT; a++) {
        c.use[a] = (pn_build_info() & (1u << (a))) != 0 && (!algo_list || listed(pn_algo_name((pn_algo)(a)), algo_list));
        if (algo_list && listed(pn_algo_name((pn_algo)(a)), algo_list) && !c.use[a]) {
            fprintf(stderr, "bench_ports: %s is not built\n", pn_algo_name((pn_algo)(a)));
            return 2;
        }
    }
    if (algo_list) {
        /* every name of the list must be an algorithm */
        const char *p = algo_list;
        while (*p) {
            size_t len = strcspn(p, ","), k;
            int known = 0;
            for (k = 0; k < ALGO_COUNT; k++)
                known |= strlen(pn_algo_name((pn_algo)(k))) == len && strncmp(p, pn_algo_name((pn_algo)(k)), len) == 0;
            if (!known) {
                fprintf(stderr, "bench_ports: --algos: unknown algorithm '%.*s'\n", (int)len, p);
                return 2;
            }
            p += len;
            if (*p == ',') p++;
        }
    }
    if (!cache) cache = "pocl-cache";

    /* Build times first: the children must not inherit an initialised OpenCL runtime. */
    if (!no_build_time) {
        mkdir(cache, 0777);
        snprintf(cold, sizeof(cold), "%s/bench-cold-%ld-%ld", cache, (long)getpid(), (long)time(NULL));
        if (mkdir(cold, 0777) != 0 || build_time(cold, c.device, &cold_build, &cold_warm) != 0 ||
            build_time(cold, c.device, &hot_build, &hot_warm) != 0) {
            fprintf(stderr, "bench_ports: cannot measure the kernel build (%s)\n", cold);
            return 1;
        }
        nftw(cold, rm_entry, 16, FTW_DEPTH | FTW_PHYS); /* the measurement's cache, not the build's */
    }

    printf("penumbra ports benchmark: %ux%u, k = %u, %d repetition%s (medians), scalar port on %d thread%s "
           "(%d cores)\n",
           c.w, c.h, c.k, c.reps, c.reps == 1 ? "" : "s", c.threads, c.threads == 1 ? "" : "s", pn_threads_cores());
    if (no_build_time) printf("kernel build: not measured (--no-build-time)\n");
    else
        printf("kernel build (clBuildProgram + first launch of every kernel): cold %.0f ms (%.0f + %.0f), "
               "cached %.0f ms (%.0f + %.0f)\n",
               cold_build + cold_warm, cold_build, cold_warm, hot_build + hot_warm, hot_build, hot_warm);
    printf("\n%-26s %8s %-10s %12s %12s %10s %5s\n", "scene", "tris", "pass", "scalar", "opencl", "scalar/ocl",
           "same");
    fflush(stdout);
    n = scandir(c.scenes, &list, NULL, alphasort);
    if (n < 0) {
        fprintf(stderr, "bench_ports: cannot list %s\n", c.scenes);
        return 1;
    }
    for (i = 0; i < n; i++) {
        const char *name = list[i]->d_name;
        size_t len = strlen(name);
        char path[2048];
        row rows[1 + ALGO_COUNT];
        uint32_t tris = 0;
        int first = 1;
        if (len < 5 || strcmp(name + len - 4, ".glb") != 0 || (only && !matches_any(name, only))) {
            free(list[i]);
            continue;
        }
        snprintf(path, sizeof(path), "%s/%s", c.scenes, name);
        fprintf(stderr, "%s\n", name);
        c.warm = scenes_done == 0 && !no_warmup;
        if (bench_scene(&c, path, rows, &tris, device, sizeof(device)) != 0) {
            rc = 1;
            free(list[i]);
            continue;
        }
        scenes_done++;
        for (a = 0; a <= ALGO_COUNT; a++) {
            char tri_text[16], times[64];
            const row *rw = &rows[a];
            if (a > 0 && !c.use[a - 1]) continue;
            snprintf(tri_text, sizeof(tri_text), "%u", tris);
            if (rw->failed) { /* the status's name in place of the three columns */
                const char *text = pn_status_str(rw->status);
                snprintf(times, sizeof(times), "failed: %-28.*s", (int)strcspn(text, ":"), text);
            }
            else
                snprintf(times, sizeof(times), "%9.1f ms %9.1f ms %10.2f", rw->ms[P_SCALAR], rw->ms[P_OPENCL],
                         rw->ms[P_OPENCL] > 0.0 ? rw->ms[P_SCALAR] / rw->ms[P_OPENCL] : 0.0);
            printf("%-26s %8s %-10s %s %5s\n", first ? name : "", first ? tri_text : "",
                   a == 0 ? "G-buffer" : pn_algo_name((pn_algo)(a - 1)), times, rw->same ? "yes" : "NO");
            first = 0;
            if (!rw->same) frames_differ++;
        }
        fflush(stdout);
        free(list[i]);
    }
    free(list);
    if (scenes_done == 0) {
        fprintf(stderr, "bench_ports: no scene rendered (--scenes %s, --only %s)\n", c.scenes, only ? only : "-");
        rc = 1;
    }
    printf("\nOpenCL device: %s. scalar/ocl: OpenCL speed-up over the scalar port on %d thread%s (> 1: OpenCL\n"
           "faster). same: every OpenCL frame's visibility, image and depth byte-identical to the scalar frame's\n"
           "(a failed frame: the same status and message on both ports).\n",
           device, c.threads, c.threads == 1 ? "" : "s");
    printf("all frames byte-identical: %s\n", frames_differ == 0 && scenes_done > 0 ? "yes" : "NO");
    return rc || frames_differ ? 1 : 0;
}
