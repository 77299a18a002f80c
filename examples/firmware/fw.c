/* fw.c - penumbra as firmware links it: one static arena, two scenes, a frame per
 * configuration, a checksum of the bytes. The small scene is built in code (46 triangles,
 * 32 x 32, every algorithm compiled in); with FW_SPOT, spot (5,856 triangles and the
 * ground, embedded as C arrays that tools/pn_mesh_to_c generated from the glTF) renders at
 * 160 x 120 with one exact and one approximate algorithm. Both contexts are carved from
 * the same arena, one after the other. Nothing here needs more of the C library than
 * memcpy/memset (which the compiler may call for struct copies); no heap, no files, no
 * printf: the platform hands in a function that writes a string.
 *
 * The same source runs on the host (host_main.c) and on a Cortex-M7 under QEMU
 * (m7/startup.c); ctest firmware_same_bytes requires the two to print the same "frame"
 * lines (the arena and stack lines differ: pointers are 8 bytes on the host). */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "fw.h"
#include "penumbra/penumbra.h"

/* ---- The scene: a 4 x 4 tiled ground, a square occluder and a box (46 triangles) ---- */

#define FW_WIDTH 32u
#define FW_HEIGHT 32u
#define FW_GRID 4u                                   /* ground quads per side */
#define FW_GROUND_VERTS ((FW_GRID + 1u) * (FW_GRID + 1u))
#define FW_VERTS (FW_GROUND_VERTS + 4u + 8u)
#define FW_TRIS (2u * FW_GRID * FW_GRID + 2u + 12u)

#ifndef FW_SPOT
#define FW_SPOT 0
#endif

#if FW_SPOT
/* spot as the CLI loads it (tools/pn_mesh_to_c: the ground appended, the automatic view
 * and light, eps = 1e-4 x diagonal), from the generated file CMake adds (PN_FW_SCENE_C). */
extern const uint32_t pn_fw_spot_vertex_count, pn_fw_spot_triangle_count;
extern const uint32_t pn_fw_spot_receiver_first, pn_fw_spot_receiver_count;
extern const float pn_fw_spot_eps;
extern const pn_camera pn_fw_spot_camera;
extern const pn_light pn_fw_spot_light;
extern const float pn_fw_spot_positions[];
extern const uint32_t pn_fw_spot_indices[];

#define FW_SPOT_WIDTH 160u
#define FW_SPOT_HEIGHT 120u
#define FW_SPOT_K 8u
#define FW_SPOT_MC_MAP 64u /* the Monte Carlo depth layers' limit (PN_MCSM_MAP_MAX) */
#endif

/* Everything penumbra carves (context, scene copy, BVH, G-buffer, outputs, each
 * algorithm's pools) lives here, for one context at a time: the small scene's, then
 * spot's on the same bytes. The size is a constant expression of the limits in
 * fw_config.h: with spot, PN_ARENA_BYTES_MAX at fw_config.h's maxima (6144 triangles,
 * 160 x 120), a bound on what pn_arena_size asks for (open_context checks it against the
 * array anyway and prints both). It sits in the board's 4 MiB SSRAM 2&3 beside .data,
 * .bss and the stack (m7/mps2_an500.ld). Without spot, the bound for the small scene
 * alone. */
#if FW_SPOT
#define FW_ARENA_BYTES PN_ARENA_BYTES_MAX(PN_MAX_TRIANGLES, PN_MAX_WIDTH, PN_MAX_HEIGHT)
#else
#define FW_ARENA_BYTES PN_ARENA_BYTES_MAX(FW_TRIS, FW_WIDTH, FW_HEIGHT)
#endif
/* Its own section, placed by the linker script (m7/mps2_an500.ld).
 * A ".bss." name keeps it zero-initialized and out of the image (NOBITS) with GCC and
 * Clang on ELF targets, the host included; elsewhere it is a plain static array. */
#if defined(__GNUC__) && defined(__ELF__)
#define FW_ARENA_SECTION __attribute__((section(".bss.fw_arena")))
#else
#define FW_ARENA_SECTION
#endif
static uint8_t arena[FW_ARENA_BYTES] FW_ARENA_SECTION;

static float positions[3u * FW_VERTS];
static uint32_t indices[3u * FW_TRIS];

static uint32_t put_vertex(uint32_t v, float x, float y, float z)
{
    positions[3u * v + 0u] = x;
    positions[3u * v + 1u] = y;
    positions[3u * v + 2u] = z;
    return v + 1u;
}

static uint32_t put_tri(uint32_t t, uint32_t a, uint32_t b, uint32_t c)
{
    indices[3u * t + 0u] = a;
    indices[3u * t + 1u] = b;
    indices[3u * t + 2u] = c;
    return t + 1u;
}

/* Two triangles of quad a-b-c-d (counter-clockwise seen from the side it faces). */
static uint32_t put_quad(uint32_t t, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    t = put_tri(t, a, b, c);
    return put_tri(t, a, c, d);
}

static void build_scene(void)
{
    /* Box corners: bit 0 x, bit 1 y, bit 2 z; faces as corner quadruples, outward. */
    static const uint8_t box_faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                            {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    uint32_t v = 0, t = 0, i, j, occ, box;

    /* Ground: y = 0, x and z in [-2, 2]; integer steps of 1 make every vertex exact. */
    for (j = 0; j <= FW_GRID; j++)
        for (i = 0; i <= FW_GRID; i++)
            v = put_vertex(v, (float)i - 2.0f, 0.0f, (float)j - 2.0f);
    for (j = 0; j < FW_GRID; j++)
        for (i = 0; i < FW_GRID; i++) {
            uint32_t a = j * (FW_GRID + 1u) + i;
            t = put_quad(t, a, a + FW_GRID + 1u, a + FW_GRID + 2u, a + 1u); /* faces +y */
        }

    /* A square occluder at y = 1 (the README's analytic case), slightly off centre. */
    occ = v;
    v = put_vertex(v, -0.75f, 1.0f, -0.5f);
    v = put_vertex(v, 0.25f, 1.0f, -0.5f);
    v = put_vertex(v, 0.25f, 1.0f, 0.5f);
    v = put_vertex(v, -0.75f, 1.0f, 0.5f);
    t = put_quad(t, occ, occ + 3u, occ + 2u, occ + 1u); /* faces +y, like the ground */

    /* A 0.5-unit box standing on the ground, partly in the occluder's penumbra. */
    box = v;
    for (i = 0; i < 8u; i++)
        v = put_vertex(v, 0.5f + 0.5f * (float)(i & 1u), 0.5f * (float)((i >> 1) & 1u),
                       0.25f + 0.5f * (float)((i >> 2) & 1u));
    for (i = 0; i < 6u; i++)
        t = put_quad(t, box + box_faces[i][0], box + box_faces[i][1], box + box_faces[i][2],
                     box + box_faces[i][3]);
}

/* ---- Output without printf ---------------------------------------------------------- */

static fw_write_fn out;
static char line[160];
static size_t line_len;

static void put_str(const char *s)
{
    while (*s != '\0' && line_len + 1u < sizeof line)
        line[line_len++] = *s++;
}

static void put_u32(uint32_t x)
{
    char digits[10];
    int n = 0;
    do {
        digits[n++] = (char)('0' + (int)(x % 10u));
        x /= 10u;
    } while (x != 0u);
    while (n > 0 && line_len + 1u < sizeof line)
        line[line_len++] = digits[--n];
}

static void put_hex(uint32_t x)
{
    static const char hex[] = "0123456789abcdef";
    int shift;
    put_str("0x");
    for (shift = 28; shift >= 0 && line_len + 1u < sizeof line; shift -= 4)
        line[line_len++] = hex[(x >> shift) & 0xFu];
}

static void end_line(void)
{
    line[line_len++] = '\n';
    line[line_len] = '\0';
    out(line);
    line_len = 0;
}

/* The same writer for the platform's own lines after fw_run (m7/startup.c). */
void fw_line_str(const char *s) { put_str(s); }
void fw_line_u32(uint32_t x) { put_u32(x); }
void fw_line_end(void) { end_line(); }

/* FNV-1a, 32 bits: enough to tell two byte strings apart, and no library needed. */
static uint32_t fnv1a(const void *data, size_t bytes)
{
    const uint8_t *p = (const uint8_t *)data;
    uint32_t h = 2166136261u;
    size_t i;
    for (i = 0; i < bytes; i++) {
        h ^= p[i];
        h *= 16777619u;
    }
    return h;
}

static int fail(const char *what, pn_status st, const pn_context *ctx)
{
    put_str("FAIL ");
    put_str(what);
    put_str(": ");
    put_str(pn_status_str(st));
    if (ctx != NULL) {
        put_str(" - ");
        put_str(pn_last_error(ctx));
    }
    end_line();
    return 1;
}

/* ---- The frames --------------------------------------------------------------------- */

/* One "frame ..." line: the FNV-1a checksums of the frame's visibility, RGBA and G-buffer
 * bytes, and the count of umbra pixels. `scene` is "" for the small scene (whose lines
 * keep the form they had before spot was added) or "spot ". */
static void put_frame(const char *scene, const pn_frame_options *opt, const char *light,
                      const pn_frame *frame)
{
    const uint32_t pixels = opt->width * opt->height;
    uint32_t umbra = 0, p;
    for (p = 0; p < pixels; p++)
        umbra += frame->visibility[p] == 0.0f;
    put_str("frame ");
    put_str(scene);
    put_str(pn_algo_name(opt->algo));
    put_str(" k=");
    put_u32(opt->k);
    put_str(light);
    put_str(" visibility=");
    put_hex(fnv1a(frame->visibility, sizeof(float) * pixels));
    put_str(" rgba=");
    put_hex(fnv1a(frame->rgba, 4u * pixels));
    /* The G-buffer's floats too: visibility is a count of exactly decided samples and
     * rarely moves when a product is rounded differently; depth, position and normal
     * change in their last bits (FMA contraction shows here first). */
    put_str(" gbuffer=");
    put_hex(fnv1a(frame->depth, sizeof(float) * pixels) ^
            (frame->position ? fnv1a(frame->position, 3u * sizeof(float) * pixels) ^
                                   fnv1a(frame->normal, 3u * sizeof(float) * pixels)
                             : 0u)); /* none: PN_LIMITS_NO_SURFACE */
    put_str(" umbra_pixels=");
    put_u32(umbra);
    end_line();
}

/* pn_arena_size for `lim`, checked against the static arena, then pn_init on it. The
 * line says both sizes; it is not compared between host and target (8-byte pointers). */
static int open_context(const char *scene, const pn_limits *lim, pn_context **ctx)
{
    size_t need = 0;
    pn_status st = pn_arena_size(lim, &need);
    if (st != PN_OK)
        return fail("pn_arena_size", st, NULL);
    put_str("arena ");
    put_str(scene);
    put_str(": pn_arena_size ");
    put_u32((uint32_t)need);
    put_str(" of ");
    put_u32((uint32_t)sizeof arena);
    put_str(" bytes static");
    end_line();
    if (need > sizeof arena) {
        put_str("FAIL the static arena is too small for the ");
        put_str(scene);
        put_str(" limits: raise fw_config.h's maxima");
        end_line();
        return 1;
    }
    st = pn_init(ctx, arena, sizeof arena, lim);
    return st == PN_OK ? 0 : fail("pn_init", st, NULL);
}

static void put_high_water(const char *scene, const pn_context *ctx)
{
    pn_stats stats;
    if (pn_get_stats(ctx, &stats) != PN_OK)
        return;
    put_str("arena high water ");
    put_str(scene);
    put_str(": ");
    put_u32((uint32_t)stats.arena_high_water);
    put_str(" bytes");
    end_line();
}

static void put_scene(const char *scene, uint32_t triangles, uint32_t width, uint32_t height)
{
    put_str("scene ");
    put_str(scene);
    put_str(": ");
    put_u32(triangles);
    put_str(" triangles, image ");
    put_u32(width);
    put_str("x");
    put_u32(height);
    end_line();
}

/* The small scene: every algorithm compiled in (pn_build_info has bit 1u << algo), in
 * pn_algo order, k = 4 and 8, an area and a point light, 32 x 32. Returns the frame count,
 * or -1 after writing what failed. */
static int run_small(void)
{
    static const uint32_t ks[] = {4u, 8u};
    const pn_camera cam = {{0.0f, 2.5f, 3.5f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
    /* The area light faces down (u x v = -y); the point light sits at its centre. */
    const pn_light area = {{0.3f, 3.0f, -0.2f}, {0.6f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.6f}};
    const pn_light point = {{0.3f, 3.0f, -0.2f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    uint32_t info = pn_build_info();
    uint32_t a, ki, li;
    int frames = 0;
    pn_context *ctx = NULL;
    pn_limits lim;
    pn_status st;

    /* Field by field: pn_limits may grow, and 0 is every other field's default (the
     * maxima of fw_config.h). The Monte Carlo layers stay at 32 x 32 texels, the map these
     * frames were first checked with (fw_config.h's maximum is spot's 64). */
    memset(&lim, 0, sizeof lim);
    lim.max_triangles = FW_TRIS;
    lim.max_width = FW_WIDTH;
    lim.max_height = FW_HEIGHT;
    lim.mc_map_max = 32u;
    lim.bvh_refs = FW_TRIS;

    build_scene();
    if (open_context("small", &lim, &ctx) != 0)
        return -1;
    st = pn_scene_set(ctx, positions, FW_VERTS, indices, FW_TRIS);
    if (st != PN_OK) {
        fail("pn_scene_set", st, ctx);
        return -1;
    }
    put_scene("small", FW_TRIS, FW_WIDTH, FW_HEIGHT);

    for (a = 0; a < PN_ALGO_COUNT; a++) {
        if ((info & (1u << a)) == 0u)
            continue;
        for (ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
            for (li = 0; li < 2u; li++) {
                pn_frame_options opt;
                pn_frame frame;
                pn_frame_options_default(&opt);
                opt.width = FW_WIDTH;
                opt.height = FW_HEIGHT;
                opt.k = ks[ki];
                opt.algo = (pn_algo)a;
                opt.gears.grid = PN_GEARS_GRID_MAX;
                st = pn_render(ctx, &cam, li == 0u ? &area : &point, &opt, &frame);
                if (st != PN_OK) {
                    fail(pn_algo_name((pn_algo)a), st, ctx);
                    return -1;
                }
                put_frame("", &opt, li == 0u ? " area" : " point", &frame);
                frames++;
            }
    }
    put_high_water("small", ctx);
    return frames;
}

#if FW_SPOT
/* spot at 160 x 120, k = 8, its area light: the reference (exact) and Monte Carlo shadow
 * maps (approximate, 64 x 64 depth layers), each only if compiled in. The same frames
 * as `penumbra render spot.glb --size 160x120 --k 8 --algo reference` and `--algo mcsm
 * --mc-map 64`. A new context on the same arena: the small scene's is not used again. */
static int run_spot(void)
{
    static const pn_algo algos[] = {PN_ALGO_REFERENCE, PN_ALGO_MCSM};
    uint32_t info = pn_build_info();
    uint32_t a;
    int frames = 0;
    pn_context *ctx = NULL;
    pn_limits lim;
    pn_status st;

    /* Sized for this scene and these frames: the two algorithms it runs (limits.algos: no
     * other algorithm's pools, no wedge connectivity), no split BVH references (the
     * default), frames that keep no positions and normals (24 bytes a pixel: the passes
     * recompute them, the same bytes). */
    memset(&lim, 0, sizeof lim);
    lim.max_triangles = pn_fw_spot_triangle_count;
    lim.max_width = FW_SPOT_WIDTH;
    lim.max_height = FW_SPOT_HEIGHT;
    lim.mc_map_max = FW_SPOT_MC_MAP;
    lim.algos = PN_BUILD_REFERENCE | PN_BUILD_MCSM;
    lim.flags = PN_LIMITS_NO_SURFACE;

    if (open_context("spot", &lim, &ctx) != 0)
        return -1;
    st = pn_scene_set(ctx, pn_fw_spot_positions, pn_fw_spot_vertex_count, pn_fw_spot_indices,
                      pn_fw_spot_triangle_count);
    if (st != PN_OK) {
        fail("pn_scene_set spot", st, ctx);
        return -1;
    }
    /* The ground is a pure receiver (kept out of the Monte Carlo depth layers), as
     * pn_setup_upload marks it for the CLI. */
    st = pn_scene_set_receivers(ctx, pn_fw_spot_receiver_first, pn_fw_spot_receiver_count);
    if (st != PN_OK) {
        fail("pn_scene_set_receivers spot", st, ctx);
        return -1;
    }
    put_scene("spot", pn_fw_spot_triangle_count, FW_SPOT_WIDTH, FW_SPOT_HEIGHT);

    for (a = 0; a < sizeof algos / sizeof algos[0]; a++) {
        pn_frame_options opt;
        pn_frame frame;
        if ((info & (1u << (uint32_t)algos[a])) == 0u)
            continue;
        pn_frame_options_default(&opt);
        opt.width = FW_SPOT_WIDTH;
        opt.height = FW_SPOT_HEIGHT;
        opt.k = FW_SPOT_K;
        opt.algo = algos[a];
        opt.eps = pn_fw_spot_eps;
        opt.mcsm.map = FW_SPOT_MC_MAP;
        st = pn_render(ctx, &pn_fw_spot_camera, &pn_fw_spot_light, &opt, &frame);
        if (st != PN_OK) {
            fail(pn_algo_name(algos[a]), st, ctx);
            return -1;
        }
        put_frame("spot ", &opt, " area", &frame);
        frames++;
    }
    put_high_water("spot", ctx);
    return frames;
}
#endif

int fw_run(fw_write_fn write)
{
    int small, spot = 0;

    out = write;
    small = run_small();
    if (small < 0)
        return 1;
#if FW_SPOT
    spot = run_spot();
    if (spot < 0)
        return 1;
#endif
    put_str("done ");
    put_u32((uint32_t)(small + spot));
    put_str(" frames");
    end_line();
    return small + spot > 0 ? 0 : 1;
}
