/* test_golden.c - golden hashes of whole frames (LVGL-style reference results, stored as
 * hashes): every built-in scene and every .glb of PN_SCENES_DIR (with its view from
 * PN_SCENES_DIR/views.json where it has one, else the automatic framing), with its area light and
 * with a point light at the light's centre, through every algorithm compiled in (the
 * exact ones and, with their default options, the approximate ones), on the scalar port
 * with two threads. Each frame's visibility buffer and RGBA image are hashed (FNV-1a 64
 * over their bytes) and compared with tests/golden/frames.txt.
 *
 * The table is what the library rendered when it was last regenerated; a change of the
 * visibility definition, or of an approximate algorithm's method or defaults, regenerates
 * it on purpose (and says so in its commit), any other change must leave every line as it
 * is:
 *
 *   test_golden              compare (every line must match, no scene or frame missing)
 *   test_golden --update F   write the table the current build renders to F
 *
 * and, for the OpenCL port (the same hashes, byte for byte, on any device it accepts):
 *
 *   test_golden --port opencl [--cl-device SPEC]   render every frame with pn_opencl_render
 *                                                  on that device (penumbra/opencl.h, DEVICE
 *                                                  CHOICE; default: PN_OPENCL_DEVICE, else
 *                                                  the first PoCL CPU device)
 *   test_golden --scenes DIR                       the .glb files (and views.json) of DIR
 *                                                  instead of the configured scene folder
 *   test_golden --only TEXT                        only the scenes whose name contains TEXT
 *                                                  (and only their lines must be rendered) */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#if PN_GOLDEN_OPENCL
#include "penumbra/opencl.h"
#include "pn_cl_host.h"
#endif
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"

#ifndef PN_GOLDEN_OPENCL
#define PN_GOLDEN_OPENCL 0
#endif

#define GOLDEN_W 64u
#define GOLDEN_H 48u
#define GOLDEN_K 8u
#define MAX_LINES 512
#define MAX_SCENES 32

/* Every algorithm (the registry: pn_algo 0 .. PN_ALGO_COUNT - 1, pn_algo_name), the exact
 * ones and, with their default options, the approximate ones, whose bytes are their own,
 * pinned so that a change meant to keep them (a faster binning, a cheaper reject) is checked. */

typedef struct line {
    char key[256];
    char hash[64];
    int seen;
} line;

static line table[MAX_LINES];
static int table_n;

static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= b[i];
        h *= 1099511628211ull;
    }
    return h;
}

static int load_table(const char *path)
{
    FILE *f = fopen(path, "r");
    char buf[256];
    if (!f) return 0;
    while (fgets(buf, sizeof(buf), f) && table_n < MAX_LINES) {
        char *sp;
        if (buf[0] == '#' || buf[0] == '\n') continue;
        buf[strcspn(buf, "\n")] = 0;
        sp = strrchr(buf, ' ');
        if (!sp) continue;
        *sp = 0;
        snprintf(table[table_n].key, sizeof(table[table_n].key), "%s", buf);
        snprintf(table[table_n].hash, sizeof(table[table_n].hash), "%s", sp + 1);
        table_n++;
    }
    fclose(f);
    return 1;
}

static line *find(const char *key)
{
    int i;
    for (i = 0; i < table_n; i++)
        if (strcmp(table[i].key, key) == 0) return &table[i];
    return NULL;
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(const char *const *)a, *(const char *const *)b); }

static FILE *update_out;
static const char *scenes_dir = PN_SCENES_DIR;
static const char *only;         /* --only */
static int use_opencl;           /* --port opencl */
static const char *cl_device;    /* --cl-device */
static char cl_device_name[512]; /* what the port picked, for the closing line */
static int frames_rendered;

static void one_scene(const char *source, int builtin)
{
    pn_setup s;
    pn_host h;
    char err[256];
    int li;
    size_t a;
    uint32_t built = pn_build_info();
#if PN_GOLDEN_OPENCL
    pn_opencl *cl = NULL;
#endif
    if (pn_setup_load_viewed(&s, source, builtin, scenes_dir, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading %s: %s", source, err);
        return;
    }
    if (pn_host_open(&h, s.mesh.triangle_count, GOLDEN_W, GOLDEN_H, 2, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "context for %s: %s", s.name, err);
        pn_setup_free(&s);
        return;
    }
    /* As the CLI uploads it: the ground marked receiver-only, which the light-space
     * algorithms read (the exact ones do not). */
    CHECK(pn_setup_upload(h.ctx, &s) == PN_OK);
#if PN_GOLDEN_OPENCL
    if (use_opencl) {
        pn_opencl_options o;
        pn_status st;
        pn_opencl_options_default(&o);
        o.device = cl_device;
        st = pn_cl_open(h.ctx, &o, &cl);
        CHECK_MSG(st == PN_OK, "%s: OpenCL port: %s (%s)", s.name, pn_last_error(h.ctx), pn_status_str(st));
        if (st != PN_OK) {
            pn_host_close(&h);
            pn_setup_free(&s);
            return;
        }
        snprintf(cl_device_name, sizeof(cl_device_name), "%s", pn_opencl_device_name(cl));
    }
#endif
    for (li = 0; li < 2; li++) {
        pn_light light = s.light;
        if (li == 1) memset(light.u, 0, sizeof(light.u)), memset(light.v, 0, sizeof(light.v));
        for (a = 0; a < PN_ALGO_COUNT; a++) {
            pn_frame_options opt;
            pn_frame fr;
            pn_status rs;
            char key[256], hash[64];
            uint64_t hv = 1469598103934665603ull, hc;
            line *l;
            if (!(built & (1u << a))) continue;
            pn_frame_options_default(&opt);
            opt.width = GOLDEN_W;
            opt.height = GOLDEN_H;
            opt.k = GOLDEN_K;
            opt.eps = s.eps;
            opt.algo = (pn_algo)a;
            opt.gears.grid = 32;
#if PN_GOLDEN_OPENCL
            if (cl) rs = pn_opencl_render(cl, &s.camera, &light, &opt, &fr);
            else
#endif
                rs = pn_render(h.ctx, &s.camera, &light, &opt, &fr);
            CHECK_MSG(rs == PN_OK, "%s %s: %s", s.name, pn_algo_name((pn_algo)a), pn_last_error(h.ctx));
            if (rs != PN_OK) continue;
            frames_rendered++;
            hc = fnv1a(hv, fr.rgba, (size_t)GOLDEN_W * GOLDEN_H * 4u);
            hv = fnv1a(hv, fr.visibility, (size_t)GOLDEN_W * GOLDEN_H * sizeof(float));
            snprintf(key, sizeof(key), "%s %s %s %ux%u k%u", s.name, li ? "point" : "area", pn_algo_name((pn_algo)a), GOLDEN_W,
                     GOLDEN_H, GOLDEN_K);
            snprintf(hash, sizeof(hash), "%016llx:%016llx", (unsigned long long)hv, (unsigned long long)hc);
            if (update_out) {
                fprintf(update_out, "%s %s\n", key, hash);
                continue;
            }
            l = find(key);
            CHECK_MSG(l != NULL, "no golden line for '%s' (rendered %s)", key, hash);
            if (!l) continue;
            l->seen = 1;
            CHECK_MSG(strcmp(l->hash, hash) == 0, "'%s': rendered %s, golden %s", key, hash, l->hash);
        }
    }
#if PN_GOLDEN_OPENCL
    pn_cl_close(cl);
#endif
    pn_host_close(&h);
    pn_setup_free(&s);
}

static int usage(void)
{
    fprintf(stderr, "usage: test_golden [--update FILE] [--port scalar|opencl] [--cl-device SPEC] [--scenes DIR]\n"
                    "                   [--only TEXT]\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *const *names = pn_builtin_scene_names();
    char *glbs[MAX_SCENES];
    int nglb = 0, i;
    DIR *d;
    struct dirent *e;
    const char *update = NULL;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) return usage();
        i++;
        if (strcmp(a, "--update") == 0) update = v;
        else if (strcmp(a, "--scenes") == 0) scenes_dir = v;
        else if (strcmp(a, "--only") == 0) only = v;
        else if (strcmp(a, "--cl-device") == 0) cl_device = v;
        else if (strcmp(a, "--port") == 0) {
            if (strcmp(v, "opencl") == 0) use_opencl = 1;
            else if (strcmp(v, "scalar") != 0) return usage();
        } else
            return usage();
    }
    if ((use_opencl || cl_device) && !PN_GOLDEN_OPENCL) {
        fprintf(stderr, "test_golden: the OpenCL port is not built\n");
        return 2;
    }
    if (update && (use_opencl || only)) {
        fprintf(stderr, "test_golden: --update writes the whole table, from the scalar port (no --port opencl, "
                        "no --only)\n");
        return 2;
    }
    if (cl_device && !use_opencl) return usage();
    if (update) {
        update_out = fopen(update, "w");
        if (!update_out) {
            fprintf(stderr, "cannot write %s\n", update);
            return 1;
        }
        fprintf(update_out, "# test_golden: FNV-1a 64 of visibility:rgba, scalar port, 2 threads.\n"
                            "# Regenerate with: build/tests/test_golden --update tests/golden/frames.txt\n");
    } else if (!load_table(PN_GOLDEN_FILE)) {
        fprintf(stderr, "cannot read %s\n", PN_GOLDEN_FILE);
        return 1;
    }
    for (i = 0; names[i]; i++)
        if (!only || strstr(names[i], only)) one_scene(names[i], 1);
    d = opendir(scenes_dir);
    CHECK_MSG(d != NULL, "scene directory %s", scenes_dir);
    while (d && (e = readdir(d)) && nglb < MAX_SCENES) {
        size_t n = strlen(e->d_name);
        if (n > 4 && strcmp(e->d_name + n - 4, ".glb") == 0 && (!only || strstr(e->d_name, only))) {
            glbs[nglb] = (char *)malloc(strlen(scenes_dir) + n + 2);
            if (!glbs[nglb]) break;
            sprintf(glbs[nglb], "%s/%s", scenes_dir, e->d_name);
            nglb++;
        }
    }
    if (d) closedir(d);
    qsort(glbs, (size_t)nglb, sizeof(glbs[0]), cmp_str);
    for (i = 0; i < nglb; i++) {
        one_scene(glbs[i], 0);
        free(glbs[i]);
    }
    if (update_out) {
        fclose(update_out);
        return 0;
    }
    for (i = 0; i < table_n; i++) {
        char scene[sizeof(table[i].key)], algo[sizeof(table[i].key)];
        size_t n = strcspn(table[i].key, " "); /* a line's scene: its key's first word */
        int a, built = 0;
        memcpy(scene, table[i].key, n);
        scene[n] = 0;
        /* Its algorithm, the third word: a build without it renders none of its lines
         * (PN_ALGORITHMS), one with it every one. */
        algo[0] = 0;
        sscanf(table[i].key, "%*s %*s %255s", algo);
        for (a = 0; a < (int)PN_ALGO_COUNT; a++)
            if (strcmp(algo, pn_algo_name((pn_algo)a)) == 0) built = (pn_build_info() >> a) & 1u;
        if (only && !strstr(scene, only)) continue;
        if (built)
            CHECK_MSG(table[i].seen, "golden line '%s' was not rendered", table[i].key);
        else
            CHECK_MSG(!table[i].seen, "golden line '%s' was rendered by a build without its algorithm", table[i].key);
    }
    if (use_opencl)
        printf("test_golden: %d frames on the OpenCL port, device %s\n", frames_rendered,
               cl_device_name[0] ? cl_device_name : "(none opened)");
    return pn_test_summary();
}
