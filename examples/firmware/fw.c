/* fw.c - penumbra as firmware links it: one static arena, a scene built in code, a frame
 * per configuration, a checksum of the bytes. Nothing here needs more of the C library
 * than memcpy/memset (which the compiler may call for struct copies); no heap, no files,
 * no printf: the platform hands in a function that writes a string.
 *
 * The same source runs on the host (host_main.c) and on a Cortex-M7 under QEMU
 * (m7/startup.c); ctest firmware_same_bytes requires the two to print the same lines. */
#include <stddef.h>
#include <stdint.h>

#include "fw.h"
#include "penumbra/penumbra.h"

/* ---- The scene: a 4 x 4 tiled ground, a square occluder and a box (46 triangles) ---- */

#define FW_WIDTH 32u
#define FW_HEIGHT 32u
#define FW_GRID 4u                                   /* ground quads per side */
#define FW_GROUND_VERTS ((FW_GRID + 1u) * (FW_GRID + 1u))
#define FW_VERTS (FW_GROUND_VERTS + 4u + 8u)
#define FW_TRIS (2u * FW_GRID * FW_GRID + 2u + 12u)

/* Everything penumbra carves (context, scene copy, BVH, G-buffer, outputs, GEARS pools)
 * lives here: the size is a constant expression of the limits in fw_config.h. */
static uint8_t arena[PN_ARENA_BYTES_MAX(PN_MAX_TRIANGLES, FW_WIDTH, FW_HEIGHT)];

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

int fw_run(fw_write_fn write)
{
    static const uint32_t ks[] = {4u, 8u};
    const pn_limits lim = {PN_MAX_TRIANGLES, FW_WIDTH, FW_HEIGHT, 0u, 0u, 0u, 0u, 0u, 0u, 0u};
    const pn_camera cam = {{0.0f, 2.5f, 3.5f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
    /* The area light faces down (u x v = -y); the point light sits at its centre. */
    const pn_light area = {{0.3f, 3.0f, -0.2f}, {0.6f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.6f}};
    const pn_light point = {{0.3f, 3.0f, -0.2f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    uint32_t info = pn_build_info();
    uint32_t frames = 0, a, ki, li;
    size_t need = 0;
    pn_context *ctx = NULL;
    pn_status st;
    pn_stats stats;

    out = write;
    build_scene();

    st = pn_arena_size(&lim, &need);
    if (st != PN_OK)
        return fail("pn_arena_size", st, NULL);
    put_str("arena ");
    put_u32((uint32_t)sizeof arena);
    put_str(" bytes static (PN_ARENA_BYTES_MAX), pn_arena_size ");
    put_u32((uint32_t)need);
    end_line();
    st = pn_init(&ctx, arena, sizeof arena, &lim);
    if (st != PN_OK)
        return fail("pn_init", st, NULL);
    st = pn_scene_set(ctx, positions, FW_VERTS, indices, FW_TRIS);
    if (st != PN_OK)
        return fail("pn_scene_set", st, ctx);
    put_str("scene ");
    put_u32(FW_TRIS);
    put_str(" triangles, image ");
    put_u32(FW_WIDTH);
    put_str("x");
    put_u32(FW_HEIGHT);
    end_line();

    /* Every algorithm compiled in (pn_build_info has bit 1u << algo), in pn_algo order. */
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        if ((info & (1u << a)) == 0u)
            continue;
        for (ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
            for (li = 0; li < 2u; li++) {
                pn_frame_options opt;
                pn_frame frame;
                uint32_t umbra = 0, p;
                pn_frame_options_default(&opt);
                opt.width = FW_WIDTH;
                opt.height = FW_HEIGHT;
                opt.k = ks[ki];
                opt.algo = (pn_algo)a;
                opt.gears.grid = PN_GEARS_GRID_MAX;
                st = pn_render(ctx, &cam, li == 0u ? &area : &point, &opt, &frame);
                if (st != PN_OK)
                    return fail(pn_algo_name((pn_algo)a), st, ctx);
                for (p = 0; p < FW_WIDTH * FW_HEIGHT; p++)
                    umbra += frame.visibility[p] == 0.0f;
                put_str("frame ");
                put_str(pn_algo_name((pn_algo)a));
                put_str(" k=");
                put_u32(opt.k);
                put_str(li == 0u ? " area" : " point");
                put_str(" visibility=");
                put_hex(fnv1a(frame.visibility, sizeof(float) * FW_WIDTH * FW_HEIGHT));
                put_str(" rgba=");
                put_hex(fnv1a(frame.rgba, 4u * FW_WIDTH * FW_HEIGHT));
                /* The G-buffer's floats too: visibility is a count of exactly decided
                 * samples and rarely moves when a product is rounded differently; depth,
                 * position and normal change in their last bits (FMA contraction shows
                 * here first). */
                put_str(" gbuffer=");
                put_hex(fnv1a(frame.depth, sizeof(float) * FW_WIDTH * FW_HEIGHT) ^
                        fnv1a(frame.position, 3u * sizeof(float) * FW_WIDTH * FW_HEIGHT) ^
                        fnv1a(frame.normal, 3u * sizeof(float) * FW_WIDTH * FW_HEIGHT));
                put_str(" umbra_pixels=");
                put_u32(umbra);
                end_line();
                frames++;
            }
    }
    if (pn_get_stats(ctx, &stats) == PN_OK) {
        put_str("arena high water ");
        put_u32((uint32_t)stats.arena_high_water);
        put_str(" bytes");
        end_line();
    }
    put_str("done ");
    put_u32(frames);
    put_str(" frames");
    end_line();
    return frames > 0u ? 0 : 1;
}
