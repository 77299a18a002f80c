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
 *   test_golden --update F   write the table the current build renders to F */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"

#define GOLDEN_W 64u
#define GOLDEN_H 48u
#define GOLDEN_K 8u
#define MAX_LINES 512
#define MAX_SCENES 32

static const struct {
    const char *name;
    pn_algo algo;
    uint32_t build_flag;
} algos[] = {
    {"reference", PN_ALGO_REFERENCE, PN_BUILD_REFERENCE},
    {"gears", PN_ALGO_GEARS, PN_BUILD_GEARS},
    {"raytrace", PN_ALGO_RAYTRACE, PN_BUILD_RAYTRACE},
    /* The approximate algorithms with their defaults: their bytes are their own, pinned so
     * that a change meant to keep them (a faster binning, a cheaper reject) is checked. */
    {"srt", PN_ALGO_SRT, PN_BUILD_SRT},
    {"occtex", PN_ALGO_OCCTEX, PN_BUILD_OCCTEX},
    {"mcsm", PN_ALGO_MCSM, PN_BUILD_MCSM},
    {"wedges", PN_ALGO_WEDGES, PN_BUILD_WEDGES},
};

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

static void one_scene(const char *source, int builtin)
{
    pn_setup s;
    pn_host h;
    char err[256];
    int li;
    size_t a;
    uint32_t built = pn_build_info();
    if (pn_setup_load_viewed(&s, source, builtin, PN_SCENES_DIR, err, sizeof(err)) != 0) {
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
    for (li = 0; li < 2; li++) {
        pn_light light = s.light;
        if (li == 1) memset(light.u, 0, sizeof(light.u)), memset(light.v, 0, sizeof(light.v));
        for (a = 0; a < sizeof(algos) / sizeof(algos[0]); a++) {
            pn_frame_options opt;
            pn_frame fr;
            pn_status rs;
            char key[256], hash[64];
            uint64_t hv = 1469598103934665603ull, hc;
            line *l;
            if (!(built & algos[a].build_flag)) continue;
            pn_frame_options_default(&opt);
            opt.width = GOLDEN_W;
            opt.height = GOLDEN_H;
            opt.k = GOLDEN_K;
            opt.eps = s.eps;
            opt.algo = algos[a].algo;
            opt.gears_grid = 32;
            rs = pn_render(h.ctx, &s.camera, &light, &opt, &fr);
            CHECK_MSG(rs == PN_OK, "%s %s: %s", s.name, algos[a].name, pn_last_error(h.ctx));
            if (rs != PN_OK) continue;
            hc = fnv1a(hv, fr.rgba, (size_t)GOLDEN_W * GOLDEN_H * 4u);
            hv = fnv1a(hv, fr.visibility, (size_t)GOLDEN_W * GOLDEN_H * sizeof(float));
            snprintf(key, sizeof(key), "%s %s %s %ux%u k%u", s.name, li ? "point" : "area", algos[a].name, GOLDEN_W,
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
    pn_host_close(&h);
    pn_setup_free(&s);
}

int main(int argc, char **argv)
{
    const char *const *names = pn_builtin_scene_names();
    char *glbs[MAX_SCENES];
    int nglb = 0, i;
    DIR *d;
    struct dirent *e;
    if (argc == 3 && strcmp(argv[1], "--update") == 0) {
        update_out = fopen(argv[2], "w");
        if (!update_out) {
            fprintf(stderr, "cannot write %s\n", argv[2]);
            return 1;
        }
        fprintf(update_out, "# test_golden: FNV-1a 64 of visibility:rgba, scalar port, 2 threads.\n"
                            "# Regenerate with: build/tests/test_golden --update tests/golden/frames.txt\n");
    } else if (!load_table(PN_GOLDEN_FILE)) {
        fprintf(stderr, "cannot read %s\n", PN_GOLDEN_FILE);
        return 1;
    }
    for (i = 0; names[i]; i++) one_scene(names[i], 1);
    d = opendir(PN_SCENES_DIR);
    CHECK_MSG(d != NULL, "scene directory %s", PN_SCENES_DIR);
    while (d && (e = readdir(d)) && nglb < MAX_SCENES) {
        size_t n = strlen(e->d_name);
        if (n > 4 && strcmp(e->d_name + n - 4, ".glb") == 0) {
            glbs[nglb] = (char *)malloc(strlen(PN_SCENES_DIR) + n + 2);
            sprintf(glbs[nglb], "%s/%s", PN_SCENES_DIR, e->d_name);
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
    for (i = 0; i < table_n; i++) CHECK_MSG(table[i].seen, "golden line '%s' was not rendered", table[i].key);
    return pn_test_summary();
}
