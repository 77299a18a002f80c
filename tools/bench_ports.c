/* bench_ports - the ports side by side: the scalar port on 1 and on 2 threads (the
 * pthread parallel-for, tools/pn_threads.h) and the OpenCL port, for the G-buffer, the
 * reference and GEARS, on every scene of the shared set, in one run, so the ratios are
 * measured under the same conditions. Also the OpenCL kernel build time with an empty
 * kernel cache and with a warm one.
 *
 *   bench_ports [--scenes DIR] [--size WxH] [--k K] [--reps N] [--only TEXT] [--cache DIR]
 *
 * Times are the library's per-pass times (pn_stats.pass_ns; the OpenCL port's include
 * reading the pass's results back into the arena), medians of N repetitions; the ports
 * take turns within each repetition. Every OpenCL and 2-thread frame is compared with the
 * 1-thread frame byte for byte ("same" column). Build times come from two child processes
 * started before this one touches OpenCL: the first with an empty PoCL cache directory
 * (a new one under --cache), the second with the one the first filled. */
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
#define MAX_SCENES 32

enum { P_SCALAR1, P_SCALAR2, P_OPENCL, P_COUNT };
static const char *const port_names[P_COUNT] = {"scalar-1t", "scalar-2t", "opencl"};

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* ---- kernel build time ------------------------------------------------------------------ */

/* In a child: create the port on a tiny context with POCL_CACHE_DIR=dir and report
 * build_ms and warmup_ms through the pipe. */
static int build_time(const char *dir, double *build_ms, double *warmup_ms)
{
    int fd[2];
    pid_t pid;
    double v[2] = {-1.0, -1.0};
    if (pipe(fd) != 0) return 1;
    fflush(NULL);
    pid = fork();
    if (pid == 0) {
        pn_limits lim = {16, 16, 16, 1024, 16, 0, 0, 0, 0, 0};
        size_t bytes;
        void *mem;
        pn_context *ctx;
        pn_opencl *cl;
        pn_opencl_info info;
        close(fd[0]);
        setenv("POCL_CACHE_DIR", dir, 1);
        if (pn_arena_size(&lim, &bytes) == PN_OK && (mem = malloc(bytes)) != NULL &&
            pn_init(&ctx, mem, bytes, &lim) == PN_OK) {
            if (pn_cl_open(ctx, NULL, &cl) == PN_OK && pn_opencl_get_info(cl, &info) == PN_OK) {
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

typedef struct row {
    double ms[P_COUNT];
    int same;
} row;

/* Pass times of every port: rows[0] G-buffer, rows[1] reference, rows[2] GEARS. */
static int bench_scene(const char *path, uint32_t w, uint32_t h, uint32_t k, int reps, row rows[3], uint32_t *tris,
                       char *device, size_t device_cap)
{
    pn_setup s;
    pn_host host;
    pn_opencl *cl = NULL;
    char err[512];
    double g[P_COUNT][2 * MAX_REPS], sh[2][P_COUNT][MAX_REPS];
    size_t n = (size_t)w * h;
    float *keep = (float *)malloc(2u * n * sizeof(float));
    int r, p, a, rc = 0, ng[P_COUNT] = {0, 0, 0};
    pn_frame_options opt;
    static const pn_algo algos[2] = {PN_ALGO_REFERENCE, PN_ALGO_GEARS};
    if (!keep || pn_setup_load(&s, path, 0, -1, err, sizeof(err)) != 0) {
        fprintf(stderr, "bench_ports: %s: %s\n", path, keep ? err : "out of memory");
        free(keep);
        return 1;
    }
    *tris = s.mesh.triangle_count;
    if (pn_host_open(&host, s.mesh.triangle_count, w, h, 2, err, sizeof(err)) != 0 ||
        pn_setup_upload(host.ctx, &s) != PN_OK ||
        pn_cl_open(host.ctx, NULL, &cl) != PN_OK) {
        fprintf(stderr, "bench_ports: %s: %s\n", path, host.ctx ? pn_last_error(host.ctx) : err);
        pn_setup_free(&s);
        free(keep);
        return 1;
    }
    snprintf(device, device_cap, "%s", pn_opencl_device_name(cl));
    pn_frame_options_default(&opt);
    opt.width = w;
    opt.height = h;
    opt.k = k;
    opt.eps = s.eps;
    for (a = 0; a < 3; a++) rows[a].same = 1;
    for (r = 0; r < reps && rc == 0; r++)
        for (a = 0; a < 2 && rc == 0; a++)
            for (p = 0; p < P_COUNT && rc == 0; p++) {
                pn_frame fr;
                pn_stats st;
                pn_status rs;
                opt.algo = algos[a];
                host.threads.count = p == P_SCALAR1 ? 1 : 2;
                rs = p == P_OPENCL ? pn_opencl_render(cl, &s.camera, &s.light, &opt, &fr)
                                   : pn_render(host.ctx, &s.camera, &s.light, &opt, &fr);
                if (rs != PN_OK) {
                    fprintf(stderr, "bench_ports: %s %s: %s\n", s.name, port_names[p], pn_last_error(host.ctx));
                    rc = 1;
                    break;
                }
                pn_get_stats(host.ctx, &st);
                g[p][ng[p]++] = st.pass_ns[PN_PASS_GBUFFER] / 1e6;
                sh[a][p][r] = st.pass_ns[PN_PASS_SHADOW] / 1e6;
                if (p == P_SCALAR1) {
                    memcpy(keep, fr.visibility, n * sizeof(float));
                    memcpy(keep + n, fr.depth, n * sizeof(float));
                } else {
                    rows[1 + a].same &= memcmp(keep, fr.visibility, n * sizeof(float)) == 0;
                    rows[0].same &= memcmp(keep + n, fr.depth, n * sizeof(float)) == 0;
                }
                fprintf(stderr, "  %s %s %s: G-buffer %.1f ms, shadow %.1f ms\n", s.name,
                        a ? "gears" : "reference", port_names[p], g[p][ng[p] - 1], sh[a][p][r]);
            }
    if (rc == 0)
        for (p = 0; p < P_COUNT; p++) {
            rows[0].ms[p] = median(g[p], ng[p]);
            for (a = 0; a < 2; a++) rows[1 + a].ms[p] = median(sh[a][p], reps);
        }
    pn_cl_close(cl);
    pn_host_close(&host);
    pn_setup_free(&s);
    free(keep);
    return rc;
}

int main(int argc, char **argv)
{
    const char *scenes = PN_SCENES_DIR, *only = NULL, *cache = getenv("POCL_CACHE_DIR");
    uint32_t w = 512, h = 512, k = 16;
    int reps = 3, i, n = 0, rc = 0;
    char cold[1024], device[512] = "?";
    double cold_build, cold_warm, hot_build, hot_warm;
    struct dirent **list;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) {
            fprintf(stderr, "bench_ports: %s needs a value\n", a);
            return 2;
        }
        i++;
        if (strcmp(a, "--scenes") == 0) scenes = v;
        else if (strcmp(a, "--size") == 0) {
            if (pn_parse_size(v, &w, &h)) return 2;
        } else if (strcmp(a, "--k") == 0) k = (uint32_t)strtoul(v, NULL, 10);
        else if (strcmp(a, "--reps") == 0) reps = atoi(v);
        else if (strcmp(a, "--only") == 0) only = v;
        else if (strcmp(a, "--cache") == 0) cache = v;
        else {
            fprintf(stderr, "usage: bench_ports [--scenes DIR] [--size WxH] [--k K] [--reps N] [--only TEXT] "
                            "[--cache DIR]\n");
            return 2;
        }
    }
    if (reps < 1 || reps > MAX_REPS) {
        fprintf(stderr, "bench_ports: --reps must be 1 .. %d\n", MAX_REPS);
        return 2;
    }
    if (!cache) cache = "pocl-cache";

    /* Build times first: the children must not inherit an initialised OpenCL runtime. */
    mkdir(cache, 0777);
    snprintf(cold, sizeof(cold), "%s/bench-cold-%ld-%ld", cache, (long)getpid(), (long)time(NULL));
    if (mkdir(cold, 0777) != 0 || build_time(cold, &cold_build, &cold_warm) != 0 ||
        build_time(cold, &hot_build, &hot_warm) != 0) {
        fprintf(stderr, "bench_ports: cannot measure the kernel build (%s)\n", cold);
        return 1;
    }
    nftw(cold, rm_entry, 16, FTW_DEPTH | FTW_PHYS); /* the measurement's cache, not the build's */

    printf("penumbra ports benchmark: %ux%u, k = %u, %d repetitions (medians), %d cores\n", w, h, k, reps,
           pn_threads_cores());
    printf("kernel build (clBuildProgram + first launch of every kernel): cold %.0f ms (%.0f + %.0f), "
           "cached %.0f ms (%.0f + %.0f)\n",
           cold_build + cold_warm, cold_build, cold_warm, hot_build + hot_warm, hot_build, hot_warm);
    printf("\n%-26s %8s %-9s %11s %11s %11s %8s %8s %5s\n", "scene", "tris", "pass", "scalar-1t", "scalar-2t",
           "opencl", "1t/2t", "2t/ocl", "same");
    fflush(stdout);
    n = scandir(scenes, &list, NULL, alphasort);
    if (n < 0) {
        fprintf(stderr, "bench_ports: cannot list %s\n", scenes);
        return 1;
    }
    for (i = 0; i < n; i++) {
        const char *name = list[i]->d_name;
        size_t len = strlen(name);
        char path[2048];
        row rows[3];
        uint32_t tris = 0;
        int a;
        static const char *const pass[3] = {"G-buffer", "reference", "GEARS"};
        if (len < 5 || strcmp(name + len - 4, ".glb") != 0 || (only && !strstr(name, only))) {
            free(list[i]);
            continue;
        }
        snprintf(path, sizeof(path), "%s/%s", scenes, name);
        fprintf(stderr, "%s\n", name);
        if (bench_scene(path, w, h, k, reps, rows, &tris, device, sizeof(device)) != 0) {
            rc = 1;
            free(list[i]);
            continue;
        }
        for (a = 0; a < 3; a++) {
            char tri_text[16];
            snprintf(tri_text, sizeof(tri_text), "%u", tris);
            printf("%-26s %8s %-9s %8.1f ms %8.1f ms %8.1f ms %8.2f %8.2f %5s\n", a == 0 ? name : "",
                   a == 0 ? tri_text : "", pass[a],
                   rows[a].ms[P_SCALAR1], rows[a].ms[P_SCALAR2], rows[a].ms[P_OPENCL],
                   rows[a].ms[P_SCALAR1] / rows[a].ms[P_SCALAR2], rows[a].ms[P_SCALAR2] / rows[a].ms[P_OPENCL],
                   rows[a].same ? "yes" : "NO");
            if (!rows[a].same) rc = 1;
        }
        fflush(stdout);
        free(list[i]);
    }
    free(list);
    printf("\nOpenCL device: %s. 1t/2t: scalar speed-up from the second thread; 2t/ocl: OpenCL speed-up over the\n"
           "2-thread scalar port (> 1: OpenCL faster). same: every frame byte-identical to the 1-thread frame.\n",
           device);
    return rc;
}
