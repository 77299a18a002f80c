/* memory_table.c - what a context costs, per algorithm, printed as Markdown (issue 47): bytes
 * a triangle and a pixel, persistent and per frame, from contexts the library carves itself
 * (pn_arena_size, pn_init, pn_get_stats), and the arena for 1k .. 1M triangles at three
 * resolutions with the default limits, each algorithm alone (pn_limits.algos) and all of
 * them. Links only the library; compiled against a library without pn_limits.algos (before
 * issue 47) it prints the "all" rows alone.
 *   usage: penumbra_memory > MEMORY.md */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"

#ifdef PN_BUILD_ALGORITHMS
#define ALGOS_FIELD 1
#else
#define ALGOS_FIELD 0
#endif

static pn_limits limits(uint32_t t, uint32_t w, uint32_t h, int algo)
{
    pn_limits l;
    memset(&l, 0, sizeof(l));
    l.max_triangles = t;
    l.max_width = w;
    l.max_height = h;
#if ALGOS_FIELD
    if (algo >= 0) l.algos = 1u << algo;
#else
    (void)algo;
#endif
    return l;
}

/* Persistent bytes and the whole carve of a context; 0 when it cannot be made. */
static int carve(const pn_limits *l, double *persistent, double *carved)
{
    size_t bytes;
    void *mem;
    pn_context *ctx;
    pn_stats st;
    if (pn_arena_size(l, &bytes) != PN_OK || !(mem = malloc(bytes))) return 0;
    if (pn_init(&ctx, mem, bytes, l) != PN_OK || pn_get_stats(ctx, &st) != PN_OK) {
        free(mem);
        return 0;
    }
    *persistent = (double)st.arena_persistent;
    *carved = (double)st.arena_carved;
    free(mem);
    return 1;
}

/* One table cell: the arena in MiB for limits (t, w, h) of algorithm algo (-1: all). */
static void print_arena_mib(uint32_t t, uint32_t w, uint32_t h, int algo)
{
    pn_limits l = limits(t, w, h, algo);
    size_t bytes;
    if (pn_arena_size(&l, &bytes) == PN_OK)
        printf(" %.1f |", (double)bytes / 1048576.0);
    else
        printf(" - |");
}

static const char *name_of(int a) { return a < 0 ? "all (default)" : pn_algo_name((pn_algo)a); }

int main(void)
{
    static const uint32_t tris[4] = {1000, 10000, 100000, 1000000};
    static const uint32_t res[3][2] = {{320, 240}, {512, 512}, {1920, 1080}};
    int a, first = ALGOS_FIELD ? 0 : PN_ALGO_COUNT, i, j;
    printf("## Memory per algorithm\n\n");
    printf("Bytes of arena a context needs, from the library's own carve (pn_arena_size, pn_init, "
           "pn_get_stats), default limits (maps and pools at their defaults, no split BVH references)%s. "
           "Persistent pools hold the scene and its BVH; the frame region is reused by every frame "
           "and holds the G-buffer, the outputs and one algorithm's pools.\n\n",
           ALGOS_FIELD ? ", each algorithm alone (pn_limits.algos) and all of them" : "");
    printf("| algorithm | persistent B / triangle | frame B / triangle | frame B / pixel | frame, fixed (maps, grids) "
           "| MiB: 1k tris, 320x240 | 10k, 512x512 | 100k, 512x512 | 1M, 1920x1080 |\n");
    printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (a = first; a <= PN_ALGO_COUNT; a++) {
        int algo = a == PN_ALGO_COUNT ? -1 : a;
        pn_limits l1 = limits(1000, 64, 64, algo), l2 = limits(2000, 64, 64, algo), l3 = limits(1000, 128, 128, algo);
        double p1, c1, p2, c2, p3, c3, ptri, ftri, fpx;
        if (algo >= 0 && !(pn_build_info() & (1u << algo))) continue;
        if (!carve(&l1, &p1, &c1) || !carve(&l2, &p2, &c2) || !carve(&l3, &p3, &c3)) {
            printf("| %s | (no context) | | | |\n", name_of(algo));
            continue;
        }
        ptri = (p2 - p1) / 1000.0;
        ftri = ((c2 - p2) - (c1 - p1)) / 1000.0;
        fpx = ((c3 - p3) - (c1 - p1)) / (128.0 * 128.0 - 64.0 * 64.0);
        printf("| %s | %.1f | %.1f | %.1f | %.2f MiB |", name_of(algo), ptri, ftri, fpx,
               ((c1 - p1) - ftri * 1000.0 - fpx * 4096.0) / 1048576.0);
        for (i = 0; i < 4; i++) {
            /* The arena at four workloads, as the README's table shows them. */
            static const uint32_t at[4][3] = {{1000, 320, 240}, {10000, 512, 512}, {100000, 512, 512}, {1000000, 1920, 1080}};
            print_arena_mib(at[i][0], at[i][1], at[i][2], algo);
        }
        printf("\n");
    }
    printf("\nArena (MiB, pn_arena_size):\n\n| algorithm | triangles |");
    for (j = 0; j < 3; j++) printf(" %ux%u |", res[j][0], res[j][1]);
    printf("\n| --- | ---: |");
    for (j = 0; j < 3; j++) printf(" ---: |");
    printf("\n");
    for (a = first; a <= PN_ALGO_COUNT; a++) {
        int algo = a == PN_ALGO_COUNT ? -1 : a;
        if (algo >= 0 && !(pn_build_info() & (1u << algo))) continue;
        for (i = 0; i < 4; i++) {
            printf("| %s | %u |", name_of(algo), tris[i]);
            for (j = 0; j < 3; j++) print_arena_mib(tris[i], res[j][0], res[j][1], algo);
            printf("\n");
        }
    }
    {
        /* A microcontroller's workload: 1,000 triangles, 160x120, the maps' and the GEARS
         * grid's limits at 128 (k = 8 costs no arena); then with frames that keep no
         * positions and normals (PN_LIMITS_NO_SURFACE), and with that and MCSM's N-buffer
         * keeping every third level (PN_LIMITS_SPARSE_NBUFFER; the same bytes). */
        printf("\nA microcontroller's workload: 1,000 triangles, 160x120, the maps' and GEARS grid's limits at 128 "
               "(bytes, pn_arena_size); then with `flags = PN_LIMITS_NO_SURFACE`; then with "
               "`flags = PN_LIMITS_NO_SURFACE | PN_LIMITS_SPARSE_NBUFFER`:\n\n"
               "| algorithm | bytes | of 1 MiB | no surface | of 1 MiB | no surface, sparse N-buffer | of 1 MiB |\n"
               "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for (a = first; a <= PN_ALGO_COUNT; a++) {
            int algo = a == PN_ALGO_COUNT ? -1 : a, v;
            if (algo >= 0 && !(pn_build_info() & (1u << algo))) continue;
            printf("| %s |", name_of(algo));
            for (v = 0; v < 3; v++) {
                pn_limits l = limits(1000, 160, 120, algo);
                size_t bytes;
                l.srt_map_max = l.occ_map_max = l.mc_map_max = l.gears_grid_max = 128;
#ifdef PN_LIMITS_NO_SURFACE
                if (v > 0) l.flags = PN_LIMITS_NO_SURFACE;
#else
                if (v > 0) break;
#endif
#ifdef PN_LIMITS_SPARSE_NBUFFER
                if (v > 1) l.flags |= PN_LIMITS_SPARSE_NBUFFER;
#else
                if (v > 1) break;
#endif
                if (pn_arena_size(&l, &bytes) == PN_OK)
                    printf(" %zu | %.2f |", bytes, (double)bytes / 1048576.0);
                else
                    printf(" - | - |");
            }
            printf("\n");
        }
    }
    return 0;
}
