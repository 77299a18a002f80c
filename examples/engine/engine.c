/* engine.c - penumbra inside an engine that rasterizes for itself (issue 52).
 *
 * The engine here is a few dozen lines: a procedural scene (a floor, a field of pillars and
 * a box that slides over them), its own z-buffer rasterizer, its own output buffers and one
 * static arena. Per frame it
 *   1. moves the box's vertices and hands the library the new positions
 *      (pn_scene_update_positions: the BVH refitted, not rebuilt);
 *   2. rasterizes the camera's view itself and hands over depth and triangle ids
 *      (pn_frame_options.gbuffer): the library rasterizes nothing;
 *   3. gets the visibility written into its own buffer (visibility_out), no RGBA image;
 * and once bakes a light map of the floor: visibility at every texel centre
 * (pn_visibility_points). Everything is checked against the library's own path: the same
 * frame with the library's G-buffer (the rasterizers agree but for pixels on triangle edges)
 * and the light map's texels against the same points rendered one by one.
 *
 * Build and run (make test builds it and runs it as ctest example_engine):
 *   build/tests/example_engine [lightmap.pgm] */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "penumbra/penumbra.h"

#define W 320u
#define H 180u
#define PILLARS 6u                            /* per side */
#define TRIS (2u + (PILLARS * PILLARS + 1u) * 12u) /* floor, pillars, the sliding box */
#define VERTS (4u + (PILLARS * PILLARS + 1u) * 8u)
#define LM 64u                                /* light-map texels per side */

static float positions[VERTS * 3u];
static uint32_t indices[TRIS * 3u];
/* The engine's own buffers. */
static float zbuf[W * H], depth[W * H], visibility[W * H], lightmap[LM * LM];
static uint32_t ids[W * H];
/* One static arena: every pool of the library comes from here (the bound for every
 * algorithm compiled in; pn_arena_size gives the exact need at run time). */
static uint8_t arena[PN_ARENA_BYTES_MAX(TRIS, W, H)];

static void put_box(uint32_t b, float cx, float cz, float half, float height)
{
    static const uint32_t faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                          {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    uint32_t v0 = 4u + b * 8u, i;
    for (i = 0; i < 8u; i++) {
        float *p = positions + (size_t)(v0 + i) * 3u;
        p[0] = cx + ((i & 1u) ^ ((i >> 1) & 1u) ? half : -half);
        p[1] = i < 4u ? 0.0f : height;
        p[2] = cz + (i & 2u ? half : -half);
    }
    for (i = 0; i < 12u; i++) {
        uint32_t *t = indices + (size_t)(2u + b * 12u + i) * 3u;
        t[0] = v0 + faces[i][0];
        t[1] = v0 + faces[i][1];
        t[2] = v0 + faces[i][2];
    }
}

static void build_scene(float box_x)
{
    static const float floor_v[12] = {-6, 0, -6, 6, 0, -6, 6, 0, 6, -6, 0, 6};
    static const uint32_t floor_t[6] = {0, 3, 2, 0, 2, 1};
    uint32_t i, j;
    memcpy(positions, floor_v, sizeof(floor_v));
    memcpy(indices, floor_t, sizeof(floor_t));
    for (i = 0; i < PILLARS; i++)
        for (j = 0; j < PILLARS; j++)
            put_box(i * PILLARS + j, -3.0f + 1.2f * (float)i, -3.0f + 1.2f * (float)j, 0.15f, 1.0f + 0.3f * (float)((i + j) % 3u));
    /* The sliding box, lifted above the pillars: its vertices are what moves. */
    put_box(PILLARS * PILLARS, box_x, 0.0f, 0.6f, 0.4f);
    for (i = 0; i < 8u; i++) positions[(size_t)(4u + PILLARS * PILLARS * 8u + i) * 3u + 1u] += 2.0f;
}

/* ---- the engine's rasterizer: the camera of penumbra.h's CONVENTIONS, a z-buffer of
 * view-space z, and the depth the library takes: the distance along the pixel's ray ---- */
typedef struct view {
    float eye[3], f[3], r[3], u[3], t, aspect;
} view;

static void normalize3(float *v)
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l, v[1] /= l, v[2] /= l;
}

static view make_view(const pn_camera *c)
{
    view v;
    int k;
    for (k = 0; k < 3; k++) v.eye[k] = c->eye[k], v.f[k] = c->target[k] - c->eye[k];
    normalize3(v.f);
    v.r[0] = v.f[1] * c->up[2] - v.f[2] * c->up[1];
    v.r[1] = v.f[2] * c->up[0] - v.f[0] * c->up[2];
    v.r[2] = v.f[0] * c->up[1] - v.f[1] * c->up[0];
    normalize3(v.r);
    v.u[0] = v.r[1] * v.f[2] - v.r[2] * v.f[1];
    v.u[1] = v.r[2] * v.f[0] - v.r[0] * v.f[2];
    v.u[2] = v.r[0] * v.f[1] - v.r[1] * v.f[0];
    v.t = tanf(c->fov_deg * 3.14159265f / 360.0f);
    v.aspect = (float)W / (float)H;
    return v;
}

static void rasterize(const view *v)
{
    uint32_t t, i;
    for (i = 0; i < W * H; i++) zbuf[i] = INFINITY, ids[i] = PN_NO_TRIANGLE;
    for (t = 0; t < TRIS; t++) {
        float sx[3], sy[3], iz[3], area;
        int x0 = (int)W, x1 = -1, y0 = (int)H, y1 = -1, x, y, k, ok = 1;
        for (k = 0; k < 3; k++) {
            const float *p = positions + (size_t)indices[t * 3u + (uint32_t)k] * 3u;
            float d[3] = {p[0] - v->eye[0], p[1] - v->eye[1], p[2] - v->eye[2]};
            float z = d[0] * v->f[0] + d[1] * v->f[1] + d[2] * v->f[2];
            float a = d[0] * v->r[0] + d[1] * v->r[1] + d[2] * v->r[2];
            float b = d[0] * v->u[0] + d[1] * v->u[1] + d[2] * v->u[2];
            if (!(z > 1e-3f)) ok = 0; /* no near-plane clipping in this engine */
            sx[k] = (a / (z * v->t * v->aspect) + 1.0f) * 0.5f * (float)W;
            sy[k] = (1.0f - b / (z * v->t)) * 0.5f * (float)H;
            iz[k] = 1.0f / z;
            if ((int)floorf(sx[k]) < x0) x0 = (int)floorf(sx[k]);
            if ((int)ceilf(sx[k]) > x1) x1 = (int)ceilf(sx[k]);
            if ((int)floorf(sy[k]) < y0) y0 = (int)floorf(sy[k]);
            if ((int)ceilf(sy[k]) > y1) y1 = (int)ceilf(sy[k]);
        }
        area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
        if (!ok || area == 0.0f) continue; /* both windings are drawn: shadows need back faces too */
        if (x0 < 0) x0 = 0;
        if (y0 < 0) y0 = 0;
        if (x1 > (int)W - 1) x1 = (int)W - 1;
        if (y1 > (int)H - 1) y1 = (int)H - 1;
        for (y = y0; y <= y1; y++)
            for (x = x0; x <= x1; x++) {
                float px = (float)x + 0.5f, py = (float)y + 0.5f, w[3], z;
                for (k = 0; k < 3; k++) {
                    int a = (k + 1) % 3, b = (k + 2) % 3;
                    w[k] = ((sx[b] - sx[a]) * (py - sy[a]) - (px - sx[a]) * (sy[b] - sy[a])) / area;
                }
                if (w[0] < 0.0f || w[1] < 0.0f || w[2] < 0.0f) continue;
                z = 1.0f / (w[0] * iz[0] + w[1] * iz[1] + w[2] * iz[2]);
                if (z < zbuf[(size_t)y * W + (size_t)x]) {
                    zbuf[(size_t)y * W + (size_t)x] = z;
                    ids[(size_t)y * W + (size_t)x] = t;
                }
            }
    }
    /* View-space z to the distance along the pixel's ray: z |f + a r + b u|. */
    for (i = 0; i < W * H; i++) {
        float sxp = 2.0f * ((float)(i % W) + 0.5f) / (float)W - 1.0f, syp = 1.0f - 2.0f * ((float)(i / W) + 0.5f) / (float)H;
        float a = sxp * v->t * v->aspect, b = syp * v->t;
        depth[i] = zbuf[i] * sqrtf(1.0f + a * a + b * b);
    }
}

static int check(pn_context *ctx, pn_status st, const char *what)
{
    if (st == PN_OK) return 0;
    fprintf(stderr, "engine: %s: %s (%s)\n", what, pn_last_error(ctx), pn_status_str(st));
    return 1;
}

int main(int argc, char **argv)
{
    pn_limits lim;
    pn_context *ctx = NULL;
    pn_camera cam = {{0.0f, 5.0f, 8.0f}, {0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
    pn_light light = {{1.0f, 6.0f, 1.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.5f}}; /* emits down: u x v = -y */
    pn_frame_options opt;
    pn_gbuffer gb = {depth, ids};
    pn_frame fr;
    view v = make_view(&cam);
    size_t bytes, i, same_id = 0;
    double diff = 0.0, lm_err = 0.0;
    uint32_t frame, x, y;
    int fail = 0;

    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = TRIS;
    lim.max_width = W;
    lim.max_height = H;
    if (check(ctx, pn_arena_size(&lim, &bytes), "pn_arena_size") || bytes > sizeof(arena) ||
        check(ctx, pn_init(&ctx, arena, sizeof(arena), &lim), "pn_init"))
        return 1;
    build_scene(-2.0f);
    if (check(ctx, pn_scene_set(ctx, positions, VERTS, indices, TRIS), "pn_scene_set")) return 1;
    pn_frame_options_default(&opt);
    opt.width = W;
    opt.height = H;
    opt.k = 8;
    opt.eps = 1e-4f * 17.0f;
    opt.gbuffer = &gb;            /* the engine's G-buffer */
    opt.visibility_out = visibility; /* into the engine's buffer */
    opt.no_rgba = 1;              /* the engine shades */

    for (frame = 0; frame < 5u; frame++) {
        build_scene(-2.0f + (float)frame);
        if (frame > 0u && check(ctx, pn_scene_update_positions(ctx, positions, VERTS, indices, TRIS), "update"))
            return 1;
        rasterize(&v);
        if (check(ctx, pn_render(ctx, &cam, &light, &opt, &fr), "pn_render with the engine's G-buffer")) return 1;
        {
            double mean = 0.0;
            for (i = 0; i < W * H; i++) mean += visibility[i];
            printf("frame %u: box at x = %.1f, mean visibility %.4f\n", frame, -2.0 + frame, mean / (W * H));
        }
    }

    /* The same frame with the library's own G-buffer: the two rasterizers agree on the
     * triangle of nearly every pixel, and there the visibility is nearly the same (the
     * points differ by the rasterizers' rounding). */
    {
        pn_frame_options own = opt;
        own.gbuffer = NULL;
        own.visibility_out = NULL;
        if (check(ctx, pn_render(ctx, &cam, &light, &own, &fr), "pn_render")) return 1;
        for (i = 0; i < W * H; i++)
            if (fr.tri_id[i] == ids[i]) {
                same_id++;
                diff += fabs((double)fr.visibility[i] - visibility[i]);
            }
        printf("engine G-buffer against the library's: %.2f%% of pixels on the same triangle, mean |visibility "
               "difference| there %.5f\n", 100.0 * same_id / (W * H), diff / (double)(same_id ? same_id : 1u));
        fail |= same_id < W * H * 98u / 100u || diff / (double)same_id > 0.01;
    }

    /* A light map of the floor (triangles 0 and 1): LM x LM texel centres, one batch of
     * LM x LM points; each texel again alone (a one-point batch) must give the same bits:
     * the reference is exact. */
    {
        static float pts[LM * LM * 3u], nrm[LM * LM * 3u];
        static uint32_t tri[LM * LM];
        pn_frame_options bake;
        pn_frame_options_default(&bake);
        bake.width = LM;
        bake.height = LM;
        bake.k = 8;
        bake.eps = opt.eps;
        for (y = 0; y < LM; y++)
            for (x = 0; x < LM; x++) {
                size_t t = (size_t)y * LM + x;
                float px = -6.0f + 12.0f * ((float)x + 0.5f) / LM, pz = -6.0f + 12.0f * ((float)y + 0.5f) / LM;
                pts[t * 3u] = px, pts[t * 3u + 1u] = 0.0f, pts[t * 3u + 2u] = pz;
                nrm[t * 3u] = 0.0f, nrm[t * 3u + 1u] = 1.0f, nrm[t * 3u + 2u] = 0.0f;
                tri[t] = pz >= px ? 0u : 1u; /* floor triangles (0, 3, 2) and (0, 2, 1) */
            }
        if (check(ctx, pn_visibility_points(ctx, &light, &bake, pts, nrm, tri, LM * LM, lightmap), "bake")) return 1;
        bake.width = bake.height = 1;
        for (i = 0; i < LM * LM; i += 97u) {
            float one;
            if (check(ctx, pn_visibility_points(ctx, &light, &bake, pts + i * 3u, nrm + i * 3u, tri + i, 1, &one),
                      "one texel"))
                return 1;
            lm_err += fabs((double)one - lightmap[i]);
        }
        printf("light map %ux%u baked; texels alone differ by %.6f in all\n", LM, LM, lm_err);
        fail |= lm_err != 0.0;
        if (argc > 1) {
            FILE *f = fopen(argv[1], "wb");
            if (!f) return 1;
            fprintf(f, "P5\n%u %u\n255\n", LM, LM);
            for (i = 0; i < LM * LM; i++) fputc((int)(lightmap[i] * 255.0f + 0.5f), f);
            fclose(f);
        }
    }
    printf("%s\n", fail ? "engine: FAILED" : "engine: ok");
    return fail;
}
