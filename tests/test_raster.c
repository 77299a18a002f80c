/* The G-buffer rasterizer against an independent double-precision ray caster through the
 * pixel centres (the CLI conventions' primary rays). Every disagreement must be explained
 * by a pixel centre within 1e-4 (barycentric) of an edge or by two surfaces within 1e-4
 * of each other in depth; on closed meshes no pixel whose neighbourhood is covered may
 * show background (watertight fill rule). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_passes.h" /* pn_pix_tiled */
#include "pn_raster.h"
#include "pn_test.h"
#include "pn_test_geom.h"
#include "pn_test_scene.h"

/* 0: test_raster, the library alone (tests/pn_test_scene.h); 1: test_raster_models, the
 * same comparison on spot.glb through the tools' glTF loader (tests/CMakeLists.txt). */
#ifndef PN_TEST_MODELS
#define PN_TEST_MODELS 0
#endif
#if PN_TEST_MODELS
#include "pn_test_tools.h"
#endif

#define EDGE_TOL 1e-4
#define DEPTH_TOL 1e-4

typedef struct ray_cam {
    double eye[3], f[3], r[3], u[3], th, aspect;
    uint32_t w, h;
} ray_cam;

static void norm3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

static void cam_make(ray_cam *c, const pn_camera *pc, uint32_t w, uint32_t h)
{
    int a;
    for (a = 0; a < 3; a++) {
        c->eye[a] = pc->eye[a];
        c->f[a] = (double)pc->target[a] - pc->eye[a];
    }
    norm3(c->f);
    c->r[0] = c->f[1] * pc->up[2] - c->f[2] * pc->up[1];
    c->r[1] = c->f[2] * pc->up[0] - c->f[0] * pc->up[2];
    c->r[2] = c->f[0] * pc->up[1] - c->f[1] * pc->up[0];
    norm3(c->r);
    c->u[0] = c->r[1] * c->f[2] - c->r[2] * c->f[1];
    c->u[1] = c->r[2] * c->f[0] - c->r[0] * c->f[2];
    c->u[2] = c->r[0] * c->f[1] - c->r[1] * c->f[0];
    c->th = tan(pc->fov_deg * M_PI / 360.0);
    c->aspect = (double)w / h;
    c->w = w;
    c->h = h;
}

static void cam_ray(const ray_cam *c, double px, double py, double d[3])
{
    double sx = 2.0 * px / c->w - 1.0, sy = 1.0 - 2.0 * py / c->h;
    int a;
    for (a = 0; a < 3; a++) d[a] = c->f[a] + sx * c->th * c->aspect * c->r[a] + sy * c->th * c->u[a];
    norm3(d);
}

/* Nearest hit (smallest t > 0, ties to the smaller id). */
static uint32_t cast(const pn_test_mesh *m, const double o[3], const double d[3], double *t_out, double *margin_out)
{
    uint32_t t, best = PN_NO_TRIANGLE;
    double bt = INFINITY, bm = 0.0;
    for (t = 0; t < m->triangle_count; t++) {
        const uint32_t *x = m->indices + 3u * t;
        double mg, tt = pn_test_ray_tri(o, d, m->positions + 3u * x[0], m->positions + 3u * x[1],
                                        m->positions + 3u * x[2], &mg);
        if (tt > 0.0 && tt < bt) {
            bt = tt;
            best = t;
            bm = mg;
        }
    }
    *t_out = bt;
    *margin_out = bm;
    return best;
}

static double tri_t(const pn_test_mesh *m, uint32_t t, const double o[3], const double d[3], double *margin)
{
    const uint32_t *x = m->indices + 3u * t;
    return pn_test_ray_tri(o, d, m->positions + 3u * x[0], m->positions + 3u * x[1], m->positions + 3u * x[2], margin);
}

static void compare(const char *name, const pn_test_mesh *m, const pn_camera *cam, uint32_t w, uint32_t h, int closed,
                    uint32_t max_explained)
{
    pn_test_host host;
    pn_frame_options opt;
    pn_frame fr;
    pn_light light = {{0, 100, 0}, {0, 0, 0}, {0, 0, 0}};
    ray_cam rc;
    uint32_t x, y, matched = 0, explained = 0, unexplained = 0, holes = 0, bad_depth = 0, hits = 0;
    REQUIRE(pn_test_open(&host, m->triangle_count, w, h) == 0);
    REQUIRE(pn_scene_set(host.ctx, m->positions, m->vertex_count, m->indices, m->triangle_count) == PN_OK);
    pn_frame_options_default(&opt);
    opt.width = w;
    opt.height = h;
    opt.k = 4;
    REQUIRE(pn_render(host.ctx, cam, &light, &opt, &fr) == PN_OK);
    cam_make(&rc, cam, w, h);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t pix = (size_t)y * w + x;
            double d[3], tc, mc;
            uint32_t r = fr.tri_id[pix], c;
            cam_ray(&rc, x + 0.5, y + 0.5, d);
            c = cast(m, rc.eye, d, &tc, &mc);
            hits += c != PN_NO_TRIANGLE;
            if (r == c) {
                matched++;
                if (c != PN_NO_TRIANGLE) {
                    double P[3];
                    int a, ok = fabs(fr.depth[pix] - tc) <= DEPTH_TOL * tc;
                    for (a = 0; a < 3; a++) {
                        P[a] = rc.eye[a] + tc * d[a];
                        ok = ok && fabs(fr.position[pix * 3 + a] - P[a]) <= DEPTH_TOL * tc;
                    }
                    if (!ok) {
                        bad_depth++;
                        if (bad_depth < 5)
                            fprintf(stderr, "%s: pixel %u,%u depth %.9g vs %.9g\n", name, x, y, fr.depth[pix], tc);
                    }
                }
                continue;
            }
            {
                int ok = 0;
                double mr = -1.0, tr = -1.0;
                if (c != PN_NO_TRIANGLE && mc < EDGE_TOL) ok = 1; /* caster's hit is on an edge */
                if (r != PN_NO_TRIANGLE) {
                    tr = tri_t(m, r, rc.eye, d, &mr);
                    if (mr > -EDGE_TOL && mr < EDGE_TOL) ok = 1; /* raster's triangle has the centre on an edge */
                    if (c != PN_NO_TRIANGLE && tr > 0.0 && fabs(tr - tc) <= DEPTH_TOL * tc) ok = 1; /* depth tie */
                }
                if (ok)
                    explained++;
                else {
                    unexplained++;
                    if (unexplained < 5)
                        fprintf(stderr, "%s: pixel %u,%u raster %u caster %u (margin %.3g/%.3g, t %.6g/%.6g)\n", name,
                                x, y, r, c, mr, mc, tr, tc);
                }
            }
            if (closed && r == PN_NO_TRIANGLE && c != PN_NO_TRIANGLE) {
                /* A hole if every nearby ray hits: not a silhouette pixel. */
                static const double off[4][2] = {{1e-3, 0}, {-1e-3, 0}, {0, 1e-3}, {0, -1e-3}};
                int q, all = 1;
                for (q = 0; q < 4; q++) {
                    double dq[3], tq, mq;
                    cam_ray(&rc, x + 0.5 + off[q][0], y + 0.5 + off[q][1], dq);
                    all = all && cast(m, rc.eye, dq, &tq, &mq) != PN_NO_TRIANGLE;
                }
                holes += all;
            }
        }
    fprintf(stderr, "%s: %ux%u, %u hit pixels, %u agree, %u on edges/depth ties, %u unexplained, %u holes\n", name,
            w, h, hits, matched, explained, unexplained, holes);
    CHECK(hits > w * h / 10u); /* the view really shows the mesh */
    CHECK(unexplained == 0);
    CHECK(holes == 0);
    CHECK(bad_depth == 0);
    CHECK(explained <= max_explained);
    pn_test_close(&host);
}

#if PN_TEST_MODELS
static void test_spot(void)
{
    pn_test_scene s;
    REQUIRE(pn_test_scene_load_tools(&s, PN_SCENES_DIR "/spot.glb", 0, 1) == 0);
    compare("spot.glb", &s.mesh, &s.camera, 96, 80, 0, 96 * 80 / 100);
    pn_test_scene_free(&s);
}

int main(void)
{
    RUN(test_spot);
    return pn_test_summary();
}
#else
static void test_spheres(void)
{
    pn_test_scene s;
    REQUIRE(pn_test_scene_load(&s, "spheres") == 0);
    compare("spheres", &s.mesh, &s.camera, 64, 64, 0, 64 * 64 / 100);
    pn_test_scene_free(&s);
}

/* A closed sphere filling the view: the fill rule must leave no holes. */
static void test_closed_sphere(void)
{
    pn_test_mesh m;
    pn_camera cam = {{0.3f, 0.2f, 3.0f}, {0, 0, 0}, {0, 1, 0}, 45.0f};
    REQUIRE(pn_test_uv_sphere(&m, 0, 0, 0, 1.0, 48, 24) == 0);
    compare("uv-sphere", &m, &cam, 96, 96, 1, 96 * 96 / 100);
    /* Looking down the pole with an odd image: the centre row and column of pixel centres
     * lie exactly on meridian edges, so up to 2 x 63 pixels legitimately differ by which of
     * two triangles owns them; what matters is that none is a hole. */
    {
        pn_camera top = {{0, 3.0f, 0}, {0, 0, 0}, {0, 0, 1}, 40.0f};
        compare("uv-sphere-pole", &m, &top, 63, 63, 1, 2 * 63);
    }
    pn_test_mesh_free(&m);
}

/* Triangles crossing the near plane (a ground plane seen from just above it) are clipped,
 * not dropped or mirrored. */
static void test_near_clip(void)
{
    pn_test_scene s;
    pn_camera cam = {{0.3f, 0.05f, 3.9f}, {0.0f, 0.0f, -4.0f}, {0, 1, 0}, 70.0f};
    REQUIRE(pn_test_scene_load(&s, "square") == 0);
    compare("square-grazing", &s.mesh, &cam, 80, 60, 0, 80 * 60 / 100);
    pn_test_scene_free(&s);
}

/* The band walk (kernels/pn_raster.h) visits triangles in the BVH's leaf order, chunk by
 * chunk, not in id order: the result must not depend on it. 48 copies of one quad (exact
 * depth ties everywhere it covers) spread over the triangle list among 400 small quads
 * elsewhere, so that the copies fall in different chunks and leaves: every pixel the quad
 * covers must go to copy 0 (ids 0 and 1), the smallest ids. */
static void test_band_walk_ties(void)
{
    enum { COPIES = 48, SMALL = 400 };
    uint32_t nt = 2u * (COPIES + SMALL), nv = 4u * (COPIES + SMALL), q, c = 0, s = 0, x, y, covered = 0, bad = 0;
    unsigned char is_big[COPIES + SMALL];
    pn_test_mesh m;
    pn_camera cam = {{0.0f, 0.0f, 4.0f}, {0, 0, 0}, {0, 1, 0}, 50.0f};
    pn_test_host host;
    pn_frame_options opt;
    pn_frame fr;
    pn_light light = {{0, 0, 10}, {0, 0, 0}, {0, 0, 0}};
    memset(&m, 0, sizeof(m));
    m.positions = (float *)calloc(3u * nv, sizeof(float));
    m.indices = (uint32_t *)calloc(3u * nt, sizeof(uint32_t));
    REQUIRE(m.positions && m.indices);
    m.vertex_count = nv;
    m.triangle_count = nt;
    for (q = 0; q < COPIES + SMALL; q++) {
        /* Quad q: a copy of the big one at every tenth position (and the rest after the
         * small ones), else a small one. */
        float *p = m.positions + 12u * q;
        uint32_t *ix = m.indices + 6u * q, v;
        int big = (q % 10u == 0u && c < COPIES) || s >= SMALL;
        float x0, y0, w;
        is_big[q] = (unsigned char)big;
        if (big) {
            x0 = -1.0f;
            y0 = -1.0f;
            w = 1.25f;
            c++;
        } else {
            x0 = 0.5f + 0.05f * (float)(s % 20u);
            y0 = -1.5f + 0.15f * (float)(s / 20u);
            w = 0.03f;
            s++;
        }
        p[0] = x0, p[1] = y0, p[2] = 0.0f;
        p[3] = x0 + w, p[4] = y0, p[5] = 0.0f;
        p[6] = x0 + w, p[7] = y0 + w, p[8] = 0.0f;
        p[9] = x0, p[10] = y0 + w, p[11] = 0.0f;
        v = 4u * q;
        ix[0] = v, ix[1] = v + 1u, ix[2] = v + 2u;
        ix[3] = v, ix[4] = v + 2u, ix[5] = v + 3u;
    }
    REQUIRE(c == COPIES && s == SMALL);
    REQUIRE(pn_test_open(&host, nt, 96, 72) == 0);
    REQUIRE(pn_scene_set(host.ctx, m.positions, m.vertex_count, m.indices, m.triangle_count) == PN_OK);
    pn_frame_options_default(&opt);
    opt.width = 96;
    opt.height = 72;
    opt.k = 4;
    REQUIRE(pn_render(host.ctx, &cam, &light, &opt, &fr) == PN_OK);
    for (y = 0; y < opt.height; y++)
        for (x = 0; x < opt.width; x++) {
            uint32_t id = fr.tri_id[(size_t)y * opt.width + x];
            if (id == PN_NO_TRIANGLE) continue;
            if (is_big[id / 2u]) {
                covered++;
                bad += id > 1u;
            }
        }
    fprintf(stderr, "band walk ties: %u pixels on the quad, %u not given to copy 0\n", covered, bad);
    CHECK(covered > 500u);
    CHECK(bad == 0u);
    pn_test_close(&host);
    pn_test_mesh_free(&m);
}

/* The rows pass (pn_raster_rows_small) against every pixel centre: the rows it gives a triangle
 * hold every centre the set-up's polygon and edge functions cover, and a triangle with at
 * most PN_RASTER_ROWS_TEST candidate centres (those in its box) gets exactly the rows of
 * those it covers, PN_RASTER_EMPTY for none. Random triangles from sub-pixel to a few pixels wide, some crossing
 * the near plane. */
/* A W x H view from the origin looking down -z. */
static void test_view(pn_kview *v, uint32_t W, uint32_t H)
{
    memset(v, 0, sizeof(*v));
    v->f[2] = -1.0f;
    v->r[0] = 1.0f;
    v->u[1] = 1.0f;
    v->tan_half = 0.5f;
    v->aspect = (float)W / (float)H;
    v->znear = 0.05f;
    v->width = W;
    v->height = H;
}

static void test_rows_pass(void)
{
    enum { W = 40, H = 30, N = 20000 };
    pn_kview v;
    float tri[9];
    uint8_t flag = 0u;
    uint32_t n, emptied = 0u, tightened = 0u, drawn = 0u, bad = 0u;
    test_view(&v, W, H);
    srand(7);
    for (n = 0; n < N; n++) {
        float cx = ((float)rand() / (float)RAND_MAX - 0.5f) * 2.4f, cy = ((float)rand() / (float)RAND_MAX - 0.5f) * 1.8f;
        float sz = n % 4u == 3u ? 0.3f : 0.02f + 0.06f * (float)(n % 3u), z = -1.0f - (float)(n % 5u) * 0.5f;
        uint32_t k, rows, x, y, y0 = H, y1 = 0, cx0 = W, cx1 = 0, cy0 = H, cy1 = 0, covered = 0;
        pn_poly poly;
        pn_edge2 e[4];
        pn_raster_small sm;
        for (k = 0; k < 3u; k++) {
            tri[3u * k + 0u] = cx + sz * ((float)rand() / (float)RAND_MAX - 0.5f);
            tri[3u * k + 1u] = cy + sz * ((float)rand() / (float)RAND_MAX - 0.5f);
            tri[3u * k + 2u] = n % 7u == 6u && k == 0u ? 0.5f : z; /* one vertex behind the eye */
        }
        rows = pn_raster_rows_small(&v, tri, &flag, 0u, &sm);
        pn_poly_make(&v, pn_v3_make(tri[0], tri[1], tri[2]), pn_v3_make(tri[3], tri[4], tri[5]),
                     pn_v3_make(tri[6], tri[7], tri[8]), &poly);
        if (poly.n > 0u) {
            float xlo = poly.x[0], xhi = poly.x[0], ylo = poly.y[0], yhi = poly.y[0];
            pn_edges_make(&poly, e);
            for (k = 1; k < poly.n; k++) {
                xlo = poly.x[k] < xlo ? poly.x[k] : xlo;
                xhi = poly.x[k] > xhi ? poly.x[k] : xhi;
                ylo = poly.y[k] < ylo ? poly.y[k] : ylo;
                yhi = poly.y[k] > yhi ? poly.y[k] : yhi;
            }
            for (y = 0; y < H; y++)
                for (x = 0; x < W; x++) {
                    float px = (float)x + 0.5f, py = (float)y + 0.5f;
                    if (px >= xlo && px <= xhi && py >= ylo && py <= yhi) {
                        cx0 = x < cx0 ? x : cx0;
                        cx1 = x > cx1 ? x : cx1;
                        cy0 = y < cy0 ? y : cy0;
                        cy1 = y > cy1 ? y : cy1;
                    }
                    if (!pn_edges_inside(e, poly.n, px, py)) continue;
                    covered++;
                    y0 = y < y0 ? y : y0;
                    y1 = y > y1 ? y : y1;
                }
        }
        if (covered == 0u) {
            /* Beyond PN_RASTER_ROWS_TEST candidates the rows pass may keep it (the bands'
             * set-up then finds no centre). */
            if (cx0 <= cx1 && cy0 <= cy1 && (cx1 - cx0 + 1u) * (cy1 - cy0 + 1u) <= PN_RASTER_ROWS_TEST) {
                bad += rows != PN_RASTER_EMPTY;
                emptied += rows == PN_RASTER_EMPTY; /* centres in its box, none covered */
            }
            continue;
        }
        drawn++;
        if (rows == PN_RASTER_EMPTY || (rows & 0xFFFFu) > y0 || (rows >> 16) < y1) {
            bad++;
            continue;
        }
        if ((cx1 - cx0 + 1u) * (cy1 - cy0 + 1u) <= PN_RASTER_ROWS_TEST) {
            bad += (rows & 0xFFFFu) != y0 || (rows >> 16) != y1;
            tightened += cy0 != y0 || cy1 != y1;
        }
    }
    fprintf(stderr, "rows pass: %u of %u triangles drawn, %u with centres in their box but none covered (empty), "
                    "%u with rows narrowed to the covered ones, %u wrong\n",
            drawn, N, emptied, tightened, bad);
    CHECK(bad == 0u);
    CHECK(drawn > 1000u);
    CHECK(emptied > 100u);
    CHECK(tightened > 100u);
}

/* The rows pass's eight-at-once form (pn_raster_rows_group) against one triangle at a time
 * (pn_raster_rows_small): the same rows and the same small-triangle centres, for groups
 * of 1 to 8 triangles mixing every case: sub-pixel and small ones, ones a few pixels wide,
 * ones the near plane cuts or that lie wholly behind it, zero-area ones (a repeated vertex,
 * three collinear points), horizontal and vertical edges, vertices on the view's edge, and
 * flags it must skip (degenerate, or the caller's skip bits). */
static void test_rows_group(void)
{
    enum { W = 40, H = 30, GROUPS = 6000 };
    pn_kview v;
    float tris[9u * PN_RASTER_GROUP];
    uint8_t flags[PN_RASTER_GROUP];
    uint32_t g, total = 0u, small = 0u, drawn = 0u, cut = 0u, bad = 0u;
    test_view(&v, W, H);
    srand(11);
    for (g = 0; g < GROUPS; g++) {
        uint32_t count = 1u + g % PN_RASTER_GROUP, skip = g % 3u == 0u ? PN_TRI_RECEIVER : 0u, i, k;
        uint32_t rows[PN_RASTER_GROUP];
        pn_raster_small sm[PN_RASTER_GROUP];
        for (i = 0; i < count; i++) {
            uint32_t kind = (uint32_t)rand() % 10u;
            float cx = ((float)rand() / (float)RAND_MAX - 0.5f) * 2.4f, cy = ((float)rand() / (float)RAND_MAX - 0.5f) * 1.8f;
            float sz = kind < 4u ? 0.01f + 0.02f * (float)kind : (kind < 7u ? 0.3f : 0.08f);
            float z = -1.0f - (float)(rand() % 5) * 0.5f;
            float *t = tris + 9u * i;
            for (k = 0; k < 3u; k++) {
                t[3u * k + 0u] = cx + sz * ((float)rand() / (float)RAND_MAX - 0.5f);
                t[3u * k + 1u] = cy + sz * ((float)rand() / (float)RAND_MAX - 0.5f);
                t[3u * k + 2u] = z;
            }
            if (kind == 7u) t[2] = 0.5f;                      /* one vertex behind the eye */
            if (kind == 8u) t[2] = t[5] = t[8] = 0.5f;        /* all behind */
            if (kind == 9u) {
                switch (rand() % 4) {
                case 0: t[6] = t[0], t[7] = t[1]; break;       /* a repeated vertex */
                case 1: t[6] = 2.0f * t[3] - t[0], t[7] = 2.0f * t[4] - t[1]; break; /* collinear */
                case 2: t[4] = t[1]; break;                    /* a horizontal edge */
                default: t[3] = t[0]; break;                   /* a vertical edge */
                }
            }
            if (rand() % 16 == 0) t[0] = t[2] * (-0.5f * v.aspect); /* on the view's left edge */
            flags[i] = (uint8_t)(rand() % 12 == 0 ? PN_TRI_DEGENERATE : (rand() % 8 == 0 ? PN_TRI_RECEIVER : 0u));
        }
        pn_raster_rows_group(&v, tris, flags, 0u, count, skip, rows, sm);
        for (i = 0; i < count; i++) {
            pn_raster_small one;
            uint32_t r = (flags[i] & skip) ? PN_RASTER_EMPTY : pn_raster_rows_small(&v, tris, flags, i, &one);
            if (flags[i] & skip) one.w = 0, one.mask = 0u;
            total++;
            cut += tris[9u * i + 2u] > 0.0f;
            drawn += r != PN_RASTER_EMPTY;
            small += one.w != 0;
            bad += rows[i] != r || sm[i].w != one.w || sm[i].mask != one.mask ||
                   (one.w != 0 && (sm[i].x0 != one.x0 || sm[i].y0 != one.y0));
        }
    }
    fprintf(stderr, "rows in groups: %u triangles, %u drawn, %u small, %u with a vertex behind the eye, %u differ\n",
            total, drawn, small, cut, bad);
    CHECK(bad == 0u);
    CHECK(drawn > 5000u);
    CHECK(small > 2000u);
    CHECK(cut > 2000u);
}

/* A row's covered run (pn_raster_span) against testing each of its centres
 * (pn_edges_inside): the same columns, on polygons made to be hard for it (vertices on
 * pixel centres, so edges through centres and the ownership rule decides; edges within a
 * millionth of horizontal or vertical; slivers; coordinates up to 1e7 beyond the image),
 * and on triangles through the set-up itself. */
static uint32_t span_rows(const pn_raster_tri *rt, uint32_t H, uint32_t *rows)
{
    uint32_t y, bad = 0u;
    for (y = 0; y < H; y++) {
        int32_t xa = rt->x0, xb = rt->x1, x;
        if (!pn_raster_span(rt, y, &xa, &xb)) continue;
        (*rows)++;
        for (x = rt->x0; x <= rt->x1; x++) {
            int in = pn_edges_inside(rt->e, rt->poly.n, (float)x + 0.5f, (float)y + 0.5f);
            bad += in != (x >= xa && x <= xb);
        }
    }
    return bad;
}

static float span_coord(uint32_t k, float lim)
{
    float r = (float)rand() / (float)RAND_MAX;
    switch (k % 4u) {
    case 0: return (float)(int)(r * lim) + 0.5f;           /* a pixel centre */
    case 1: return r * lim;                                /* anywhere */
    case 2: return (float)(int)(r * lim);                  /* a pixel corner */
    default: return (r - 0.5f) * 2e7f;                     /* far beyond the image */
    }
}

static void test_span(void)
{
    enum { W = 96, H = 24, N = 40000 };
    pn_kview v;
    uint32_t n, rows = 0u, bad = 0u, set_rows = 0u, set_bad = 0u;
    srand(11);
    for (n = 0; n < N; n++) {
        pn_raster_tri rt;
        float xlo, xhi;
        uint32_t i;
        memset(&rt, 0, sizeof(rt));
        rt.poly.n = 3u + n % 2u;
        for (i = 0; i < rt.poly.n; i++) {
            rt.poly.x[i] = span_coord(n / 2u + i, (float)W);
            rt.poly.y[i] = span_coord(n / 3u + 2u * i, (float)H);
        }
        if (n % 5u == 1u) rt.poly.y[1] = rt.poly.y[0] + ((n & 8u) ? 1e-6f : -1e-6f) * rt.poly.y[0]; /* near horizontal */
        if (n % 5u == 2u) rt.poly.x[2] = rt.poly.x[1] * (1.0f + 1e-6f);                           /* near vertical */
        if (n % 5u == 3u) { /* sliver along a diagonal */
            rt.poly.x[2] = rt.poly.x[0] + (rt.poly.x[1] - rt.poly.x[0]) * 0.5f + 0.01f;
            rt.poly.y[2] = rt.poly.y[0] + (rt.poly.y[1] - rt.poly.y[0]) * 0.5f;
        }
        if (rt.poly.n == 4u) { /* keep the quad convex: a triangle with a point on one edge */
            rt.poly.x[3] = 0.5f * (rt.poly.x[2] + rt.poly.x[0]);
            rt.poly.y[3] = 0.5f * (rt.poly.y[2] + rt.poly.y[0]);
        }
        pn_edges_make(&rt.poly, rt.e);
        xlo = xhi = rt.poly.x[0];
        for (i = 1; i < rt.poly.n; i++) {
            xlo = rt.poly.x[i] < xlo ? rt.poly.x[i] : xlo;
            xhi = rt.poly.x[i] > xhi ? rt.poly.x[i] : xhi;
        }
        rt.x0 = pn_kceil_clamp(xlo - 0.5f, 0, W);
        rt.x1 = pn_kfloor_clamp(xhi - 0.5f, -1, W - 1);
        rt.span = 1u; /* every width, so narrow rows are searched too */
        bad += span_rows(&rt, H, &rows);
    }
    /* Through the set-up: small to large triangles, some across the eye plane. */
    test_view(&v, W, H);
    for (n = 0; n < N / 4u; n++) {
        float tri[9], cx = ((float)rand() / (float)RAND_MAX - 0.5f) * 4.0f, sz = 0.05f + 2.0f * (float)(n % 5u);
        uint8_t flag = 0u;
        uint32_t rr, k;
        pn_raster_small sm;
        pn_raster_tri rt;
        for (k = 0; k < 3u; k++) {
            tri[3u * k + 0u] = cx + sz * ((float)rand() / (float)RAND_MAX - 0.5f);
            tri[3u * k + 1u] = sz * ((float)rand() / (float)RAND_MAX - 0.5f);
            tri[3u * k + 2u] = n % 7u == 6u && k == 0u ? 0.5f : -1.0f - (float)(n % 3u);
        }
        rr = pn_raster_rows_small(&v, tri, &flag, 0u, &sm);
        if (rr == PN_RASTER_EMPTY || !pn_raster_tri_setup(&v, tri, &rr, 0u, 0u, H - 1u, &rt)) continue;
        set_bad += span_rows(&rt, H, &set_rows);
    }
    fprintf(stderr, "span: %u rows of hard polygons, %u wrong columns; %u rows through the set-up, %u wrong\n", rows, bad,
            set_rows, set_bad);
    CHECK(bad == 0u && set_bad == 0u);
    CHECK(rows > 100000u && set_rows > 10000u);
}

/* pn_pix_tiled: for every image of 1..40 columns and 1..40 rows, and a few large ones
 * (the wedges' bands: a multiple of PN_PIX_TILE rows but the last), item i runs over
 * every pixel exactly once, and the items of one tile (each PN_PIX_TILE^2 run, the
 * last tiles of a row and the last tile row narrower) stay in one tile. */
static void test_pixel_order(void)
{
    static uint8_t seen[1000u * 1000u];
    const uint32_t big[][2] = {{512u, 512u}, {1000u, 37u}, {17u, 1000u}, {1920u, 16u}, {129u, 257u}};
    uint32_t cases = 0u, bad = 0u, W, R, c, i;
    for (c = 0; c < 40u * 40u + 5u; c++) {
        W = c < 1600u ? c % 40u + 1u : big[c - 1600u][0];
        R = c < 1600u ? c / 40u + 1u : big[c - 1600u][1];
        memset(seen, 0, (size_t)W * R);
        for (i = 0; i < W * R; i++) {
            uint32_t p = pn_pix_tiled(i, W, R), x = p % W, y = p / W;
            if (p >= W * R || seen[p]++) {
                bad++;
                continue;
            }
            /* the tile of item i: its tile row from i alone, its column from the items
             * before it in that tile row (full tiles hold PN_PIX_TILE x h) */
            {
                uint32_t y0 = i / (PN_PIX_TILE * W) * PN_PIX_TILE, h = R - y0 < PN_PIX_TILE ? R - y0 : PN_PIX_TILE;
                uint32_t tx = (i - y0 * W) / (PN_PIX_TILE * h);
                if (y / PN_PIX_TILE != y0 / PN_PIX_TILE || x / PN_PIX_TILE != (tx < W / PN_PIX_TILE ? tx : W / PN_PIX_TILE))
                    bad++;
            }
        }
        cases++;
    }
    fprintf(stderr, "pixel order: %u images, %u wrong items\n", cases, bad);
    CHECK(bad == 0u && cases == 1605u);
}

int main(void)
{
    RUN(test_pixel_order);
    RUN(test_spheres);
    RUN(test_closed_sphere);
    RUN(test_near_clip);
    RUN(test_band_walk_ties);
    RUN(test_rows_pass);
    RUN(test_rows_group);
    RUN(test_span);
    return pn_test_summary();
}
#endif
