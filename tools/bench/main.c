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
 * See tools/bench.sh (make bench / make bench-quick) for how it is run, and bench.h for what
 * each file of tools/bench/ holds. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "pn_image.h"
#include "pn_scenes.h"

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
    o.grid = PN_GEARS_GRID_DEFAULT;
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
