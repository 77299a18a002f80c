/* penumbra_api_bench - what the caller-side entry points of issue 52 buy, on every built-in
 * and shared scene (each with its view), in one run, as Markdown tables
 * (docs/bench/RESULTS.md, "The caller-side entry points"):
 *
 *   1. a frame of the reference with the library's G-buffer against the same frame from the
 *      caller's G-buffer (its own depth and ids handed back): wall time and the G-buffer
 *      pass (pn_stats.pass_ns);
 *   2. pn_scene_update_positions (BVH refit) against pn_scene_set (BVH build), per triangle,
 *      on a context of the default limits (the other tables use the tools' context, which
 *      reserves split BVH references), the scene moved (every vertex shifted by 1% of the
 *      diagonal), whole and its BVH pass alone; a context runs every algorithm by default,
 *      so both include the
 *      algorithms' scene work (the wedges' and MCSM's connectivity, pass_ns
 *      PN_PASS_SCENE_ALGOS), shown apart;
 *   3. pn_visibility_points per algorithm: points a second, the frame's lit pixels as the
 *      points, beside the frame's own shadow pass in pixels a second.
 *
 *   penumbra_api_bench [--scenes DIR] [--size WxH] [--k K] [--reps N] [--threads N] [--tables 1,2,3]
 *
 * Medians of N repetitions (default 3), 2 threads by default, 256 x 256, k = 16. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_scenes.h"
#include "pn_setup.h"

#define MAX_SCENES 32
#define MAX_REPS 15

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
static double ms_since(uint64_t t0) { return (double)(pn_threads_now_ns(NULL) - t0) / 1e6; }

typedef struct row {
    char name[128];
    uint32_t tris;
    double own_ms, own_gb, caller_ms, caller_gb;   /* table 1 */
    double set_ms, update_ms, set_bvh, update_bvh, algos_ms; /* table 2 */
    double pts_s[PN_ALGO_COUNT], px_s[PN_ALGO_COUNT]; /* table 3; < 0: refused */
} row;

static int g_tables = 7; /* bit t - 1: table t */

static int bench_scene(const pn_setup *s, uint32_t w, uint32_t h, uint32_t k, int reps, int threads, row *r)
{
    pn_host host;
    pn_frame_options opt;
    pn_frame fr;
    pn_gbuffer gb;
    pn_stats st;
    char err[256];
    size_t n = (size_t)w * h, i, lit = 0;
    float *depth = malloc(n * 4u), *pos = malloc(n * 12u), *nrm = malloc(n * 12u), *vis = malloc(n * 4u);
    float *moved = malloc((size_t)s->mesh.vertex_count * 12u);
    uint32_t *ids = malloc(n * 4u), *lit_ids = malloc(n * 4u);
    double t[5][MAX_REPS];
    int rep, a, ok = 0;
    if (!depth || !pos || !nrm || !vis || !moved || !ids || !lit_ids) goto done;
    if (pn_host_open(&host, s->mesh.triangle_count, w, h, threads, err, sizeof(err)) != 0) {
        fprintf(stderr, "%s: %s\n", s->name, err);
        goto done;
    }
    pn_set_clock(host.ctx, pn_threads_now_ns, NULL);
    snprintf(r->name, sizeof(r->name), "%s", s->name);
    r->tris = s->mesh.triangle_count;
    if (pn_setup_upload(host.ctx, s) != PN_OK) goto close;
    pn_frame_options_default(&opt);
    opt.width = w;
    opt.height = h;
    opt.k = k;
    opt.eps = s->eps;

    if (!(g_tables & 1)) goto points;
    /* 1. own G-buffer against the caller's */
    if (pn_render(host.ctx, &s->camera, &s->light, &opt, &fr) != PN_OK) goto close;
    memcpy(depth, fr.depth, n * 4u);
    memcpy(ids, fr.tri_id, n * 4u);
    gb.depth = depth;
    gb.tri_id = ids;
    for (rep = 0; rep < reps; rep++) {
        pn_frame_options c = opt;
        uint64_t t0 = pn_threads_now_ns(NULL);
        if (pn_render(host.ctx, &s->camera, &s->light, &opt, &fr) != PN_OK) goto close;
        t[0][rep] = ms_since(t0);
        pn_get_stats(host.ctx, &st);
        t[1][rep] = (double)st.pass_ns[PN_PASS_GBUFFER] / 1e6;
        c.gbuffer = &gb;
        t0 = pn_threads_now_ns(NULL);
        if (pn_render(host.ctx, &s->camera, &s->light, &c, &fr) != PN_OK) goto close;
        t[2][rep] = ms_since(t0);
        pn_get_stats(host.ctx, &st);
        t[3][rep] = (double)st.pass_ns[PN_PASS_GBUFFER] / 1e6;
    }
    r->own_ms = median(t[0], reps);
    r->own_gb = median(t[1], reps);
    r->caller_ms = median(t[2], reps);
    r->caller_gb = median(t[3], reps);

points:
    if (!(g_tables & 4)) goto refit;
    /* The frame's lit pixels, as points. */
    if (pn_render(host.ctx, &s->camera, &s->light, &opt, &fr) != PN_OK) goto close;
    for (i = 0; i < n; i++)
        if (fr.tri_id[i] != PN_NO_TRIANGLE) {
            memcpy(pos + lit * 3u, fr.position + i * 3u, 12u);
            memcpy(nrm + lit * 3u, fr.normal + i * 3u, 12u);
            lit_ids[lit++] = fr.tri_id[i];
        }

    /* 3. points a second, per algorithm, beside the frame's shadow pass */
    for (a = 0; a < (int)PN_ALGO_COUNT; a++) {
        pn_frame_options o = opt;
        r->pts_s[a] = r->px_s[a] = -1.0;
        if (!(pn_build_info() & (1u << a))) continue;
        o.algo = (pn_algo)a;
        for (rep = 0; rep < reps; rep++) {
            uint64_t t0;
            if (pn_render(host.ctx, &s->camera, &s->light, &o, &fr) != PN_OK) break;
            pn_get_stats(host.ctx, &st);
            t[0][rep] = (double)st.pass_ns[PN_PASS_SHADOW] / 1e6;
            t0 = pn_threads_now_ns(NULL);
            if (pn_visibility_points(host.ctx, &s->light, &o, pos, nrm, lit_ids, (uint32_t)lit, vis) != PN_OK) break;
            t[1][rep] = ms_since(t0);
        }
        if (rep == reps) {
            r->px_s[a] = (double)n / (median(t[0], reps) * 1e-3);
            r->pts_s[a] = (double)lit / (median(t[1], reps) * 1e-3);
        } else if (rep == 0 && pn_render(host.ctx, &s->camera, &s->light, &o, &fr) == PN_OK) {
            pn_get_stats(host.ctx, &st);
            r->px_s[a] = (double)n / ((double)st.pass_ns[PN_PASS_SHADOW] * 1e-9);
        }
    }

refit:
    if (!(g_tables & 2)) goto measured;
    /* 2. refit against rebuild: the scene moved by 1% of its diagonal, then back, on a context
     * of the library's default limits (no split BVH references: a tree with split ones is
     * built anew at every update), as an engine would open it */
    pn_host_close(&host);
    {
        pn_limits lim;
        memset(&lim, 0, sizeof(lim));
        lim.max_triangles = s->mesh.triangle_count;
        lim.max_width = w;
        lim.max_height = h;
        if (pn_host_open_limits(&host, &lim, threads, err, sizeof(err)) != 0) goto done;
        pn_set_clock(host.ctx, pn_threads_now_ns, NULL);
    }
    for (i = 0; i < (size_t)s->mesh.vertex_count * 3u; i++) moved[i] = s->mesh.positions[i] + 0.01f * s->diag;
    for (rep = 0; rep < reps; rep++) {
        uint64_t t0 = pn_threads_now_ns(NULL);
        if (pn_scene_set(host.ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) !=
            PN_OK)
            goto close;
        t[0][rep] = ms_since(t0);
        pn_get_stats(host.ctx, &st);
        t[4][rep] = (double)st.pass_ns[PN_PASS_BVH_BUILD] / 1e6;
        t0 = pn_threads_now_ns(NULL);
        if (pn_scene_update_positions(host.ctx, rep % 2 ? s->mesh.positions : moved, s->mesh.vertex_count,
                                      s->mesh.indices, s->mesh.triangle_count) != PN_OK)
            goto close;
        t[1][rep] = ms_since(t0);
        pn_get_stats(host.ctx, &st);
        t[3][rep] = (double)st.pass_ns[PN_PASS_BVH_BUILD] / 1e6;
        t[2][rep] = (double)st.pass_ns[PN_PASS_SCENE_ALGOS] / 1e6;
    }
    r->set_ms = median(t[0], reps);
    r->update_ms = median(t[1], reps);
    r->update_bvh = median(t[3], reps);
    r->set_bvh = median(t[4], reps);
    r->algos_ms = median(t[2], reps);
measured:
    ok = 1;
close:
    if (!ok) fprintf(stderr, "%s: %s\n", s->name, pn_last_error(host.ctx));
    pn_host_close(&host);
done:
    free(depth), free(pos), free(nrm), free(vis), free(moved), free(ids), free(lit_ids);
    return ok;
}

int main(int argc, char **argv)
{
    const char *dir = PN_SCENES_DIR;
    uint32_t w = 256, h = 256, k = 16;
    int reps = 3, threads = 2, i, n = 0, a;
    static row rows[MAX_SCENES];
    const char *const *bn = pn_builtin_scene_names();
    struct dirent **names = NULL;
    int m;
    for (i = 1; i < argc; i++) {
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) break;
        if (strcmp(argv[i], "--scenes") == 0) dir = v, i++;
        else if (strcmp(argv[i], "--size") == 0) { if (pn_parse_size(v, &w, &h)) return 2; i++; }
        else if (strcmp(argv[i], "--k") == 0) k = (uint32_t)atoi(v), i++;
        else if (strcmp(argv[i], "--reps") == 0) reps = atoi(v), i++;
        else if (strcmp(argv[i], "--threads") == 0) threads = atoi(v), i++;
        else if (strcmp(argv[i], "--tables") == 0) {
            const char *c;
            for (g_tables = 0, c = v; *c; c++)
                if (*c >= '1' && *c <= '3') g_tables |= 1 << (*c - '1');
            i++;
        }
        else break;
    }
    if (i < argc || reps < 1 || reps > MAX_REPS || threads < 1) {
        fprintf(stderr, "usage: penumbra_api_bench [--scenes DIR] [--size WxH] [--k K] [--reps N<=15] [--threads N]\n");
        return 2;
    }
    m = scandir(dir, &names, NULL, alphasort);
    for (i = -1; n < MAX_SCENES;) {
        pn_setup s;
        char err[256], src[1024];
        int builtin = *bn != NULL;
        if (builtin) {
            snprintf(src, sizeof(src), "%s", *bn++);
        } else {
            size_t len;
            if (++i >= m) break;
            len = strlen(names[i]->d_name);
            if (len < 5 || strcmp(names[i]->d_name + len - 4, ".glb") != 0) continue;
            snprintf(src, sizeof(src), "%s/%s", dir, names[i]->d_name);
        }
        if (pn_setup_load_viewed(&s, src, builtin, dir, err, sizeof(err)) != 0) {
            fprintf(stderr, "%s: %s\n", src, err);
            continue;
        }
        fprintf(stderr, "%s ...\n", s.name);
        n += bench_scene(&s, w, h, k, reps, threads, &rows[n]);
        pn_setup_free(&s);
    }
    for (i = 0; i < m; i++) free(names[i]);
    free(names);

    printf("## The caller-side entry points\n\n`penumbra_api_bench --size %ux%u --k %u --threads %d --reps %d`: every "
           "built-in and shared scene with its view, medians of %d.\n\n", w, h, k, threads, reps, reps);
    if (g_tables & 1) {
        printf("### A frame of the reference from the library's G-buffer and from the caller's\n\n");
        printf("| scene | triangles | own G-buffer: frame ms | its G-buffer pass ms | caller's: frame ms | its G-buffer pass ms "
               "| frame time saved |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (i = 0; i < n; i++)
            printf("| %s | %u | %.2f | %.2f | %.2f | %.2f | %.1f%% |\n", rows[i].name, rows[i].tris, rows[i].own_ms,
                   rows[i].own_gb, rows[i].caller_ms, rows[i].caller_gb,
                   100.0 * (rows[i].own_ms - rows[i].caller_ms) / rows[i].own_ms);
    }
    if (g_tables & 2) {
        printf("\n### Moving geometry: pn_scene_update_positions (refit) against pn_scene_set (build)\n\n");
        printf("| scene | triangles | pn_scene_set ns / triangle | update ns / triangle | set / update | BVH build "
               "ns / triangle | BVH refit ns / triangle | build / refit | algorithms' scene work ns / triangle |\n"
               "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (i = 0; i < n; i++)
            printf("| %s | %u | %.0f | %.0f | %.2fx | %.0f | %.1f | %.1fx | %.0f |\n", rows[i].name, rows[i].tris,
                   rows[i].set_ms * 1e6 / rows[i].tris, rows[i].update_ms * 1e6 / rows[i].tris,
                   rows[i].set_ms / rows[i].update_ms, rows[i].set_bvh * 1e6 / rows[i].tris,
                   rows[i].update_bvh * 1e6 / rows[i].tris, rows[i].set_bvh / rows[i].update_bvh,
                   rows[i].algos_ms * 1e6 / rows[i].tris);
    }
    if (g_tables & 4) {
        printf("\n### pn_visibility_points: million points a second (the frame's lit pixels), and the frame's shadow "
               "pass in million pixels a second\n\n| scene |");
        for (a = 0; a < (int)PN_ALGO_COUNT; a++)
            if (pn_build_info() & (1u << a)) printf(" %s points | pixels |", pn_algo_name((pn_algo)a));
        printf("\n| --- |");
        for (a = 0; a < (int)PN_ALGO_COUNT; a++)
            if (pn_build_info() & (1u << a)) printf(" ---: | ---: |");
        printf("\n");
        for (i = 0; i < n; i++) {
            printf("| %s |", rows[i].name);
            for (a = 0; a < (int)PN_ALGO_COUNT; a++) {
                if (!(pn_build_info() & (1u << a))) continue;
                if (rows[i].pts_s[a] < 0.0) printf(" - |");
                else printf(" %.3f |", rows[i].pts_s[a] / 1e6);
                if (rows[i].px_s[a] < 0.0) printf(" - |");
                else printf(" %.3f |", rows[i].px_s[a] / 1e6);
            }
            printf("\n");
        }
    }
    return 0;
}
