/* PN_ALGO_WEDGES (penumbra wedges with overlap blending): what it promises and what it is
 * built from.
 *
 * 1. Connectivity (src/pn_connect.c): a cube with split vertices welds to 8 vertices and
 *    18 edges, closed; an open quad has 4 open edges; three triangles on one edge make a
 *    non-manifold edge; two cubes are two objects.
 * 2. Where the method should be nearly exact, one convex occluder whose penumbra does not
 *    overlap itself (`square`): mean absolute error against the reference (k = 32) below
 *    1/255, blended and additive alike (one object: nothing to blend), and no gap between
 *    umbra and penumbra (no pixel off by more than a tenth).
 * 3. The hard shadow does not depend on where the eye is: with the camera inside the
 *    square's shadow volume (between the occluder and the ground, looking down) the same
 *    bounds hold.
 * 4. A point light has no penumbra: the frame is the reference's, bit for bit (the centre
 *    ray is the exact predicate).
 * 5. Blending (Forest et al. 2006): two squares stacked under the light hide overlapping
 *    parts of it from the ground below both; there the blended RMSE and MAE are below the
 *    classic sum's.
 * 6. Determinism and options: the same bytes from 1 and 2 threads; an unknown mode is
 *    PN_E_INVALID_ARG; the stats add up.
 * 7. A (tile, wedge) pair or silhouette pool too small for the frame (pn_limits.wg_pairs,
 *    wg_silhouettes): the frame bins in bands with the same bytes in a smaller arena, and
 *    a tile whose list outgrows the pool is full (its pixels the reference's), never a
 *    failure; nothing is written outside the arena.
 * 8. A wedge's screen reach (pn_wg_reach, pn_wg_row: the tiles it is binned to) holds every
 *    pixel its edge covers light from: random edges, lights and receiver planes, every
 *    pixel of a screen whose size is no multiple of the tile, the pixel's point taken where
 *    its centre's ray meets the plane; and it is tighter than its tile box.
 * 9. The culls of tiles in depth and of objects lose no edge that reaches the light.
 * 10. A tile's centre cone (pn_wg_cone_clear: the tile's pixels skip their centre rays)
 *    is clear only when no segment from one of its origins to the light centre meets a
 *    triangle, and it is clear of the receivers' own plane.
 * 11. A pixel whose shadow origin lies inside its own solid is dark without the exact
 *    fallback; one beyond a solid thinner than eps is not taken for inside, and one under
 *    its own solid's overhang still takes the fallback.
 * 12. The culls lose nothing: on every built-in scene, blended and additive, the frame is
 *    the same bytes as with PN_WG_NO_CULL (every silhouette in every tile, no box test, no
 *    clear tile; fuzz_culls asks the same of random small scenes), which lists every
 *    silhouette in every one of the frame's tiles; an unknown flag is PN_E_INVALID_ARG. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"
#include "pn_test_render.h"
#include "pn_wedges.h"

#define W 128u
#define H 96u

static float g_ref[W * H], g_a[W * H], g_b[W * H];

/* ---- 1. Connectivity ---------------------------------------------------------------------- */

/* Quad i (vertices 4i .. 4i + 3, in order round it) as two triangles. */
static void quad_tris(uint32_t *idx, uint32_t i)
{
    static const uint32_t q[6] = {0u, 1u, 2u, 0u, 2u, 3u};
    uint32_t j;
    for (j = 0; j < 6u; j++) idx[i * 6u + j] = i * 4u + q[j];
}

static void cube(float *pos, uint32_t *idx, float ox)
{
    /* 6 faces, 4 vertices each (split, as glTF exporters write them), 2 triangles each. */
    static const int f[6][4][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                                   {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
                                   {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
    uint32_t i, j;
    for (i = 0; i < 6u; i++) {
        for (j = 0; j < 4u; j++) {
            pos[(i * 4u + j) * 3u] = (float)f[i][j][0] + ox;
            pos[(i * 4u + j) * 3u + 1u] = (float)f[i][j][1];
            pos[(i * 4u + j) * 3u + 2u] = (float)f[i][j][2];
        }
        quad_tris(idx, i);
    }
}

static void connect_case(const char *what, const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt, uint32_t verts,
                         uint32_t edges, uint32_t open, uint32_t nonman, uint32_t objects, uint32_t closed)
{
    pn_limits lim;
    pn_context *ctx;
    pn_stats st;
    size_t need;
    void *mem;
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = 4233u;
    lim.max_width = 16u;
    lim.max_height = 16u;
    lim.gears_pairs = 4096u;
    lim.gears_grid_max = 16u;
    lim.srt_map_max = 64u;
    lim.occ_map_max = 64u;
    lim.mc_map_max = 64u;
    REQUIRE(pn_arena_size(&lim, &need) == PN_OK);
    mem = malloc(need);
    REQUIRE(mem != NULL);
    REQUIRE(pn_init(&ctx, mem, need, &lim) == PN_OK);
    REQUIRE(pn_scene_set(ctx, pos, nv, idx, nt) == PN_OK);
    REQUIRE(pn_get_stats(ctx, &st) == PN_OK);
    fprintf(stderr, "%s: %u vertices, %u edges (%u open, %u non-manifold), %u objects (%u closed)\n", what, st.wedges.vertices,
            st.wedges.edges, st.wedges.open_edges, st.wedges.nonmanifold_edges, st.wedges.objects, st.wedges.closed_objects);
    CHECK_MSG(st.wedges.vertices == verts && st.wedges.edges == edges && st.wedges.open_edges == open &&
                  st.wedges.nonmanifold_edges == nonman && st.wedges.objects == objects && st.wedges.closed_objects == closed,
              "%s: want %u vertices, %u edges (%u open, %u non-manifold), %u objects (%u closed)", what, verts, edges, open,
              nonman, objects, closed);
    free(mem);
}

static void test_connect(void)
{
    static float pos[2 * 24 * 3];
    static uint32_t idx[2 * 36];
    static const float quad[4 * 3] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
    static const uint32_t qi[6] = {0, 1, 2, 0, 2, 3};
    /* A fin: three triangles on edge (0,0,0)-(1,0,0), one winding it the same way as another. */
    static const float fin[5 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1};
    static const uint32_t fi[9] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    uint32_t i;
    cube(pos, idx, 0.0f);
    /* -0 welds with +0. */
    pos[0] = -0.0f;
    connect_case("split cube", pos, 24u, idx, 12u, 8u, 18u, 0u, 0u, 1u, 1u);
    cube(pos + 72, idx + 36, 3.0f);
    for (i = 36u; i < 72u; i++) idx[i] += 24u;
    connect_case("two cubes", pos, 48u, idx, 24u, 16u, 36u, 0u, 0u, 2u, 2u);
    /* Two long bars touching along a long edge (a stair's steps, stacked boxes): one
     * object, its shared edge non-manifold with two pairs of half-edges winding it opposite
     * ways, so the union is closed there: a solid. Taken for a boundary, the edge made it a
     * sheet (H = 0.79), whose faces MCSM lit through their own bar. */
    cube(pos + 72, idx + 36, 1.0f);
    for (i = 36u; i < 72u; i++) idx[i] += 24u;
    for (i = 0; i < 48u; i++) {
        pos[3u * i + 1u] += i >= 24u ? 1.0f : 0.0f;
        pos[3u * i] *= 0.1f;
        pos[3u * i + 1u] *= 0.1f;
        pos[3u * i + 2u] *= 4.0f;
    }
    connect_case("two bars on an edge", pos, 48u, idx, 24u, 14u, 35u, 0u, 1u, 1u, 1u);
    connect_case("open quad", quad, 4u, qi, 2u, 4u, 5u, 4u, 0u, 1u, 0u);
    connect_case("fin", fin, 5u, fi, 3u, 5u, 7u, 6u, 1u, 1u, 0u);
    /* A triangle and its back: the back is a duplicate, so the object is a sheet (cast as a
     * solid, the front alone would cast only while it faces the light). */
    {
        static const uint32_t ti[6] = {0, 1, 2, 0, 2, 1};
        connect_case("double-sided triangle", quad, 4u, ti, 2u, 3u, 3u, 0u, 0u, 1u, 0u);
    }
    /* An open tube (12 sides, no caps): its ends' vector areas cancel, but their rims are
     * long beside its area (H = 0.99), so it is a sheet: cast as a solid, light would pass
     * where the light sees its inside. */
    {
        static float tp[24 * 3];
        static uint32_t tt[24 * 3];
        for (i = 0; i < 12u; i++) {
            float a = 6.2831853f * (float)i / 12.0f;
            uint32_t n = (i + 1u) % 12u;
            tp[6u * i] = tp[6u * i + 3u] = 0.5f * cosf(a);
            tp[6u * i + 2u] = tp[6u * i + 5u] = 0.5f * sinf(a);
            tp[6u * i + 1u] = 0.0f;
            tp[6u * i + 4u] = 1.0f;
            tt[6u * i] = 2u * i, tt[6u * i + 1u] = 2u * i + 1u, tt[6u * i + 2u] = 2u * n;
            tt[6u * i + 3u] = 2u * n, tt[6u * i + 4u] = 2u * i + 1u, tt[6u * i + 5u] = 2u * n + 1u;
        }
        connect_case("open tube", tp, 24u, tt, 24u, 24u, 48u, 24u, 0u, 1u, 0u);
    }
    /* Grids of g x g quads, each quad with its own four corners (4 g^2 positions, (g + 1)^2
     * distinct), 1e-5 across beside a triangle 1e3 across: the weld's Morton cells are the
     * scene box's 1024th, so all the grid's corners share one code and the weld's sort of a
     * run by position alone tells its vertices apart: 5 x 5 (100 corners) by a heap, 46 x 46
     * (8,464) by radix. */
    for (i = 5u; i <= 46u; i += 41u) {
        static float gp[(8464 + 3) * 3];
        static uint32_t gt[(4232 + 1) * 3];
        uint32_t x, z, c, g = i, nq = i * i;
        for (z = 0; z < g; z++)
            for (x = 0; x < g; x++) {
                static const uint32_t q[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                uint32_t k = z * g + x;
                for (c = 0; c < 4u; c++) {
                    gp[(4u * k + c) * 3u] = 1e-5f * (float)(x + q[c][0]);
                    /* y in one byte: an odd count of byte passes, so the radix sort ends
                     * in its scratch */
                    gp[(4u * k + c) * 3u + 1u] = 1.0f + (float)(z + q[c][1]) / 2097152.0f;
                    gp[(4u * k + c) * 3u + 2u] = 1e-5f * (float)(z + q[c][1]);
                }
                quad_tris(gt, k);
            }
        gp[12u * nq] = 10.0f, gp[12u * nq + 1u] = 0.0f, gp[12u * nq + 2u] = 0.0f;
        gp[12u * nq + 3u] = 1010.0f, gp[12u * nq + 4u] = 0.0f, gp[12u * nq + 5u] = 0.0f;
        gp[12u * nq + 6u] = 10.0f, gp[12u * nq + 7u] = 0.0f, gp[12u * nq + 8u] = 1000.0f;
        gt[6u * nq] = 4u * nq, gt[6u * nq + 1u] = 4u * nq + 1u, gt[6u * nq + 2u] = 4u * nq + 2u;
        /* (g + 1)^2 + 3 vertices; 2 g (g + 1) + g^2 + 3 edges, 4 g + 3 of them open; 2 sheets */
        connect_case(g == 5u ? "5 x 5 grid in one Morton cell" : "46 x 46 grid in one Morton cell", gp, 4u * nq + 3u, gt,
                     2u * nq + 1u, (g + 1u) * (g + 1u) + 3u, 2u * g * (g + 1u) + nq + 3u, 4u * g + 3u, 0u, 2u, 0u);
    }
    /* A fan of 40 triangles (each with its own corners) round a hub at the scene box's least
     * corner, so the hub has the least vertex id and is the lower vertex of all 80 spoke
     * half-edges, given in a shuffled triangle order: the edges' sort of one vertex's
     * half-edges by higher vertex (a heap beyond 16) alone pairs them into 41 spokes. */
    {
        static float fp[40 * 9];
        static uint32_t ft[40 * 3];
        for (i = 0; i < 40u; i++) {
            uint32_t f = (17u * i) % 40u; /* the fan's triangle in slot i */
            float a0 = 1.5707963f * (float)f / 40.0f, a1 = 1.5707963f * (float)(f + 1u) / 40.0f;
            fp[9u * i] = fp[9u * i + 1u] = fp[9u * i + 2u] = 0.0f;
            fp[9u * i + 3u] = cosf(a0), fp[9u * i + 4u] = 0.0f, fp[9u * i + 5u] = sinf(a0);
            fp[9u * i + 6u] = cosf(a1), fp[9u * i + 7u] = 0.0f, fp[9u * i + 8u] = sinf(a1);
            ft[3u * i] = 3u * i, ft[3u * i + 1u] = 3u * i + 1u, ft[3u * i + 2u] = 3u * i + 2u;
        }
        /* 42 vertices; 41 spokes and 40 rim edges, the 2 end spokes and the rim open */
        connect_case("fan round the least vertex", fp, 120u, ft, 40u, 42u, 81u, 42u, 0u, 1u, 0u);
    }
}

/* ---- 2 .. 6. Frames ------------------------------------------------------------------------ */

static int open_scene(const char *name, pn_setup *s, pn_host *h, int threads)
{
    char err[256];
    if (pn_setup_load(s, name, 1, -1, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading %s: %s", name, err);
        return 0;
    }
    if (pn_host_open(h, s->mesh.triangle_count, W, H, threads, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "context: %s", err);
        pn_setup_free(s);
        return 0;
    }
    if (pn_scene_set(h->ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) != PN_OK) {
        CHECK_MSG(0, "%s: %s", name, pn_last_error(h->ctx));
        pn_host_close(h);
        pn_setup_free(s);
        return 0;
    }
    return 1;
}

static void wg_opts(pn_frame_options *o, uint32_t mode)
{
    pn_frame_options_default(o);
    o->width = W;
    o->height = H;
    o->k = 32;
    o->algo = PN_ALGO_WEDGES;
    o->wedges.mode = mode;
}

static void errors(const float *a, const float *b, double *mae, double *rmse, double *mx)
{
    double s1 = 0.0, s2 = 0.0, m = 0.0;
    size_t i;
    for (i = 0; i < (size_t)W * H; i++) {
        double e = fabs((double)a[i] - b[i]);
        s1 += e;
        s2 += e * e;
        if (e > m) m = e;
    }
    *mae = s1 / (double)(W * H);
    *rmse = sqrt(s2 / (double)(W * H));
    *mx = m;
}

static void square_case(pn_host *h, pn_setup *s, const char *what, int mae_goal)
{
    pn_frame_options o;
    double mae, rmse, mx;
    uint32_t mode;
    REQUIRE(render_vis(h, s, &s->light, PN_ALGO_REFERENCE, W, H, 32, 1, g_ref, NULL) == 0);
    for (mode = PN_WG_MODE_BLEND; mode <= PN_WG_MODE_ADDITIVE; mode++) {
        wg_opts(&o, mode);
        REQUIRE(render_opt(h, s, &s->light, &o, g_a, NULL, NULL) == 0);
        errors(g_a, g_ref, &mae, &rmse, &mx);
        fprintf(stderr, "square %s, %s: MAE %.5f (1/255 = %.5f), RMSE %.5f, max %.4f\n", what,
                mode == PN_WG_MODE_BLEND ? "blended" : "additive", mae, 1.0 / 255.0, rmse, mx);
        if (mae_goal) CHECK_MSG(mae < 1.0 / 255.0, "square %s: MAE %.5f not below 1/255", what, mae);
        CHECK_MSG(mx < 0.1, "square %s: a pixel off by %.4f (a gap or a capping error)", what, mx);
    }
}

static void test_square(void)
{
    pn_setup s;
    pn_host h;
    pn_camera inside;
    if (!open_scene("square", &s, &h, 2)) return;
    square_case(&h, &s, "default camera", 1);
    /* The eye inside the occluder's shadow volume: under the square, above the ground,
     * looking down across the umbra and the penumbra. */
    inside = s.camera;
    inside.eye[0] = s.light.center[0] + 0.05f;
    inside.eye[1] = 0.35f * s.light.center[1];
    inside.eye[2] = s.light.center[2] + 0.03f;
    inside.target[0] = inside.eye[0] + 0.4f;
    inside.target[1] = 0.0f;
    inside.target[2] = inside.eye[2] + 0.3f;
    inside.up[0] = 0.0f;
    inside.up[1] = 0.0f;
    inside.up[2] = 1.0f;
    inside.fov_deg = 70.0f;
    s.camera = inside;
    {
        /* The eye is in the square's umbra: its segment to each light corner crosses the
         * occluder's plane inside the square (the premise of this case). */
        pn_square_params p;
        int c, in = 0;
        pn_square_scene_params(&p);
        for (c = 0; c < 4; c++) {
            float lx = s.light.center[0] + ((c & 1) ? 1.0f : -1.0f) * s.light.u[0] + ((c & 2) ? 1.0f : -1.0f) * s.light.v[0];
            float ly = s.light.center[1] + ((c & 1) ? 1.0f : -1.0f) * s.light.u[1] + ((c & 2) ? 1.0f : -1.0f) * s.light.v[1];
            float lz = s.light.center[2] + ((c & 1) ? 1.0f : -1.0f) * s.light.u[2] + ((c & 2) ? 1.0f : -1.0f) * s.light.v[2];
            float t = (p.occluder_y - inside.eye[1]) / (ly - inside.eye[1]);
            float x = inside.eye[0] + t * (lx - inside.eye[0]), z = inside.eye[2] + t * (lz - inside.eye[2]);
            in += t > 0.0f && t < 1.0f && fabsf(x) < p.occluder_half && fabsf(z) < p.occluder_half;
        }
        CHECK_MSG(in == 4, "the eye (%g, %g, %g) sees %d of the light's corners past the square", inside.eye[0],
                  inside.eye[1], inside.eye[2], 4 - in);
    }
    /* The MAE goal is for the default view; here the frame is mostly penumbra seen
     * from close by, and what must hold is that no region's hard shadow flips. */
    square_case(&h, &s, "camera inside the shadow volume", 0);
    pn_host_close(&h);
    pn_setup_free(&s);
}

static void test_point_light(void)
{
    static const char *const scenes[3] = {"spheres", "thin", "room"};
    int i;
    for (i = 0; i < 3; i++) {
        pn_setup s;
        pn_host h;
        pn_light pl;
        pn_frame_options o;
        size_t p, diff = 0;
        if (!open_scene(scenes[i], &s, &h, 2)) return;
        pl = s.light;
        memset(pl.u, 0, sizeof(pl.u));
        memset(pl.v, 0, sizeof(pl.v));
        REQUIRE(render_vis(&h, &s, &pl, PN_ALGO_REFERENCE, W, H, 16, 1, g_ref, NULL) == 0);
        wg_opts(&o, 0u);
        o.k = 16;
        REQUIRE(render_opt(&h, &s, &pl, &o, g_a, NULL, NULL) == 0);
        for (p = 0; p < (size_t)W * H; p++) diff += g_a[p] != g_ref[p];
        CHECK_MSG(diff == 0u, "%s point light: %zu pixels differ from the reference", scenes[i], diff);
        pn_host_close(&h);
        pn_setup_free(&s);
    }
}

static void test_blend_spheres(void)
{
    pn_setup s;
    pn_host h1, h2;
    pn_frame_options o;
    pn_stats st;
    double mae_b, rmse_b, mx_b, mae_a, rmse_a, mx_a;
    if (!open_scene("spheres", &s, &h1, 1)) return;
    pn_setup_free(&s);
    if (!open_scene("spheres", &s, &h2, 2)) return;
    REQUIRE(render_vis(&h2, &s, &s.light, PN_ALGO_REFERENCE, W, H, 32, 1, g_ref, NULL) == 0);
    wg_opts(&o, 0u);
    REQUIRE(render_opt(&h2, &s, &s.light, &o, g_a, NULL, &st) == 0);
    errors(g_a, g_ref, &mae_b, &rmse_b, &mx_b);
    /* Determinism: one thread, the same bytes. */
    REQUIRE(render_opt(&h1, &s, &s.light, &o, g_b, NULL, NULL) == 0);
    CHECK_MSG(memcmp(g_a, g_b, sizeof(g_a)) == 0, "spheres: 1 and 2 threads differ");
    wg_opts(&o, PN_WG_MODE_ADDITIVE);
    REQUIRE(render_opt(&h2, &s, &s.light, &o, g_b, NULL, NULL) == 0);
    errors(g_b, g_ref, &mae_a, &rmse_a, &mx_a);
    fprintf(stderr, "spheres: blended RMSE %.4f (max %.3f), additive %.4f (max %.3f); %u silhouette edges, %llu pairs, "
                    "%.1f pixels touched per wedge\n",
            rmse_b, mx_b, rmse_a, mx_a, st.wedges.silhouettes, (unsigned long long)st.wedges.pairs,
            st.wedges.silhouettes ? (double)st.wedges.touched / st.wedges.silhouettes : 0.0);
    /* Neighbouring spheres mostly hide different parts of the light, so the two modes differ
     * on few pixels (the benchmark's table and heat map say where); the stacked test below is
     * the overlap the blending is for. Here: the objects are the 81 spheres and the ground. */
    /* The spheres' terminators: their origins lie inside the spheres (test_inside_solid). */
    CHECK_MSG(st.wedges.exact_pixels == 0u && rmse_b < 0.01, "spheres: %u pixels resolved exactly, RMSE %.4f",
              st.wedges.exact_pixels, rmse_b);
    CHECK_MSG(st.wedges.objects == 82u && st.wedges.closed_objects == 81u && st.wedges.silhouettes > 0u &&
                  st.wedges.touched > 0u && st.wedges.touched <= st.wedges.evaluated,
              "spheres stats: %u objects, %u silhouettes, %llu touched of %llu evaluated", st.wedges.objects,
              st.wedges.silhouettes, (unsigned long long)st.wedges.touched, (unsigned long long)st.wedges.evaluated);
    /* Options. */
    wg_opts(&o, 3u);
    o.eps = s.eps;
    {
        pn_frame fr;
        CHECK(pn_render(h2.ctx, &s.camera, &s.light, &o, &fr) == PN_E_INVALID_ARG);
        CHECK(strstr(pn_last_error(h2.ctx), "wedges.mode") != NULL);
    }
    pn_host_close(&h1);
    pn_host_close(&h2);
    pn_setup_free(&s);
}

/* The square scene's camera and light in a context for `tris` triangles (1: done). */
static int open_square_host(pn_setup *s, pn_host *h, uint32_t tris)
{
    char err[256];
    if (pn_setup_load(s, "square", 1, -1, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading square: %s", err);
        return 0;
    }
    if (pn_host_open(h, tris, W, H, 2, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "context: %s", err);
        pn_setup_free(s);
        return 0;
    }
    return 1;
}

/* Square i of sq = {x, y, z, half-size}, horizontal: its 4 vertices and 2 triangles. */
static void put_square(float *pos, uint32_t *idx, const float *sq, uint32_t i)
{
    float x = sq[0], y = sq[1], z = sq[2], r = sq[3], *p = pos + i * 12u;
    p[0] = x - r, p[1] = y, p[2] = z - r;
    p[3] = x - r, p[4] = y, p[5] = z + r;
    p[6] = x + r, p[7] = y, p[8] = z + r;
    p[9] = x + r, p[10] = y, p[11] = z - r;
    quad_tris(idx, i);
}

/* Two squares stacked under the light, the upper one shifted: from the ground under both
 * they hide overlapping parts of the light, which the classic sum counts twice. */
static void test_blend_stacked(void)
{
    static const float sq[4][4] = {{0.0f, 2.0f, 0.0f, 0.5f}, {0.35f, 2.6f, 0.2f, 0.5f}, {0.0f, 0.0f, 0.0f, 4.0f},
                                   {0.0f, 0.0f, 0.0f, 0.0f}};
    float pos[12 * 3];
    uint32_t idx[6 * 3], i;
    pn_setup s;
    pn_host h;
    pn_frame_options o;
    pn_stats st;
    double mae_b, rmse_b, mx_b, mae_a, rmse_a, mx_a;
    if (!open_square_host(&s, &h, 6u)) return;
    for (i = 0; i < 3u; i++) put_square(pos, idx, sq[i], i);
    REQUIRE(pn_scene_set(h.ctx, pos, 12u, idx, 6u) == PN_OK);
    REQUIRE(render_vis(&h, &s, &s.light, PN_ALGO_REFERENCE, W, H, 32, 1, g_ref, NULL) == 0);
    wg_opts(&o, PN_WG_MODE_BLEND);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_a, NULL, &st) == 0);
    errors(g_a, g_ref, &mae_b, &rmse_b, &mx_b);
    wg_opts(&o, PN_WG_MODE_ADDITIVE);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_b, NULL, NULL) == 0);
    errors(g_b, g_ref, &mae_a, &rmse_a, &mx_a);
    fprintf(stderr, "stacked squares: blended RMSE %.4f MAE %.5f (max %.3f), additive RMSE %.4f MAE %.5f (max %.3f); "
                    "%u objects, %u silhouette edges\n",
            rmse_b, mae_b, mx_b, rmse_a, mae_a, mx_a, st.wedges.objects, st.wedges.silhouettes);
    CHECK_MSG(st.wedges.objects == 3u, "%u objects, want 3", st.wedges.objects);
    CHECK_MSG(rmse_b < rmse_a && mae_b < mae_a, "stacked squares: blended RMSE %.4f / MAE %.5f not below additive %.4f / %.5f",
              rmse_b, mae_b, rmse_a, mae_a);
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* Two squares at one height whose x ranges (and z ranges) are disjoint: from any point
 * of the ground their images on the light are disjoint, so blending has nothing to take
 * away, and it must give the classic sum's bytes. The boxes bound each square's occluded
 * region (its edges' end points); the paper's boxes of the regions behind the outer edges
 * reach the light's border, overlapped here, and blending lit pixels the squares share
 * (the spheres: 51 pixels brighter than the reference by more than 0.02 where additive was
 * right). */
static void test_blend_disjoint(void)
{
    static const float sq[3][4] = {{0.3f, 2.0f, 0.1f, 0.05f}, {0.45f, 2.0f, 0.25f, 0.05f}, {0.0f, 0.0f, 0.0f, 4.0f}};
    float pos[12 * 3];
    uint32_t idx[6 * 3], i, p, differ = 0u;
    pn_setup s;
    pn_host h;
    pn_frame_options o;
    if (!open_square_host(&s, &h, 6u)) return;
    for (i = 0; i < 3u; i++) put_square(pos, idx, sq[i], i);
    REQUIRE(pn_scene_set(h.ctx, pos, 12u, idx, 6u) == PN_OK);
    wg_opts(&o, PN_WG_MODE_BLEND);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_a, NULL, NULL) == 0);
    wg_opts(&o, PN_WG_MODE_ADDITIVE);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_b, NULL, NULL) == 0);
    for (p = 0; p < W * H; p++) differ += g_a[p] != g_b[p];
    fprintf(stderr, "disjoint squares: %u pixels blended differently from the sum\n", differ);
    CHECK_MSG(differ == 0u, "disjoint squares: %u pixels blended differently from the classic sum", differ);
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* One open object of two layers: two squares under the light (the upper one shifted) joined
 * by a sliver, over the ground. The centre ray crosses both layers; where the upper layer's
 * silhouette still covers the light and the lower one's no longer does, an object counted
 * once at the centre came out lit (a bright ring inside the shadow: the grey-white room's
 * table). Counting the casting layers the centre ray crosses keeps it dark. */
static void test_two_layers(void)
{
    static const float sq[3][4] = {{0.0f, 2.0f, 0.0f, 0.5f}, {0.2f, 2.5f, 0.15f, 0.5f}, {0.0f, 0.0f, 0.0f, 4.0f}};
    float pos[15 * 3];
    uint32_t idx[7 * 3], i, bright = 0u, p;
    pn_setup s;
    pn_host h;
    pn_frame_options o;
    pn_stats st;
    double mae, rmse, mx;
    if (!open_square_host(&s, &h, 7u)) return;
    for (i = 0; i < 3u; i++) put_square(pos, idx, sq[i], i);
    /* The sliver: a corner of each square and a point beside the lower one's. */
    memcpy(pos + 36, pos + 0, 3u * sizeof(float));
    memcpy(pos + 39, pos + 12, 3u * sizeof(float));
    pos[42] = pos[0] + 0.01f, pos[43] = pos[1], pos[44] = pos[2];
    idx[18] = 12u, idx[19] = 13u, idx[20] = 14u;
    REQUIRE(pn_scene_set(h.ctx, pos, 15u, idx, 7u) == PN_OK);
    REQUIRE(render_vis(&h, &s, &s.light, PN_ALGO_REFERENCE, W, H, 32, 1, g_ref, NULL) == 0);
    wg_opts(&o, PN_WG_MODE_BLEND);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_a, NULL, &st) == 0);
    errors(g_a, g_ref, &mae, &rmse, &mx);
    for (p = 0; p < W * H; p++) bright += g_a[p] > g_ref[p] + 0.25f;
    fprintf(stderr, "two layers: RMSE %.4f (max %.3f), %u pixels brighter by more than 0.25; %u objects\n", rmse, mx, bright,
            st.wedges.objects);
    CHECK_MSG(st.wedges.objects == 2u, "%u objects, want 2 (the layers and the ground)", st.wedges.objects);
    CHECK_MSG(bright == 0u, "%u pixels lit inside the two layers' shadow", bright);
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* A double-sided sheet (a square and its back on the same vertices, as foliage is often
 * modelled) casts as the square alone: the back is a duplicate and casts nothing (counted
 * twice, its penumbra was twice as dark: the canopy's leaves). The same bytes as the
 * single-sided square. */
static void test_double_sided(void)
{
    static const float sq[2][4] = {{0.1f, 2.0f, 0.0f, 0.6f}, {0.0f, 0.0f, 0.0f, 4.0f}};
    float pos[8 * 3];
    uint32_t idx[6 * 3], i;
    pn_setup s;
    pn_host h;
    pn_frame_options o;
    pn_stats st;
    if (!open_square_host(&s, &h, 6u)) return;
    for (i = 0; i < 2u; i++) put_square(pos, idx, sq[i], i);
    wg_opts(&o, PN_WG_MODE_BLEND);
    REQUIRE(pn_scene_set(h.ctx, pos, 8u, idx, 4u) == PN_OK);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_ref, NULL, NULL) == 0);
    /* The back: the first square's triangles again, wound the other way. */
    for (i = 0; i < 2u; i++) {
        idx[12u + 3u * i] = idx[3u * i];
        idx[12u + 3u * i + 1u] = idx[3u * i + 2u];
        idx[12u + 3u * i + 2u] = idx[3u * i + 1u];
    }
    REQUIRE(pn_scene_set(h.ctx, pos, 8u, idx, 6u) == PN_OK);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_a, NULL, &st) == 0);
    fprintf(stderr, "double-sided: %u duplicate triangles, %u non-manifold edges\n", st.wedges.duplicates,
            st.wedges.nonmanifold_edges);
    CHECK_MSG(st.wedges.duplicates == 2u, "%u duplicates, want the back's 2", st.wedges.duplicates);
    CHECK_MSG(memcmp(g_a, g_ref, sizeof(g_ref)) == 0, "the double-sided square casts differently from the square");
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* A UV sphere (centre c, radius r; 16 slices, 8 stacks: 114 vertices, 224 triangles wound
 * outward) from vertex v0 into pos / idx; returns its triangles. The first 16 are the
 * fan round the lower pole. */
#define SPH_SLICES 16u
#define SPH_STACKS 8u
#define SPH_VERTS (2u + (SPH_STACKS - 1u) * SPH_SLICES)
#define SPH_TRIS (2u * SPH_SLICES * (SPH_STACKS - 1u))
static uint32_t uv_sphere(float *pos, uint32_t *idx, uint32_t v0, const float *c, float r)
{
    uint32_t i, j, n = 0u, top = v0 + SPH_VERTS - 1u;
    pos[3u * v0] = c[0], pos[3u * v0 + 1u] = c[1] - r, pos[3u * v0 + 2u] = c[2];
    pos[3u * top] = c[0], pos[3u * top + 1u] = c[1] + r, pos[3u * top + 2u] = c[2];
    for (j = 1u; j < SPH_STACKS; j++)
        for (i = 0; i < SPH_SLICES; i++) {
            float th = 3.14159265f * (float)j / (float)SPH_STACKS, ph = 6.2831853f * (float)i / (float)SPH_SLICES;
            float *p = pos + 3u * (v0 + 1u + (j - 1u) * SPH_SLICES + i);
            p[0] = c[0] + r * sinf(th) * cosf(ph);
            p[1] = c[1] - r * cosf(th);
            p[2] = c[2] + r * sinf(th) * sinf(ph);
        }
#define SPH_V(j, i) (v0 + 1u + ((j) - 1u) * SPH_SLICES + (i) % SPH_SLICES)
    for (i = 0; i < SPH_SLICES; i++, n++) /* x z turn from +x to +z: wound outward seen from below */
        idx[3u * n] = v0, idx[3u * n + 1u] = SPH_V(1u, i), idx[3u * n + 2u] = SPH_V(1u, i + 1u);
    for (j = 1u; j + 1u < SPH_STACKS; j++)
        for (i = 0; i < SPH_SLICES; i++) {
            idx[3u * n] = SPH_V(j, i), idx[3u * n + 1u] = SPH_V(j + 1u, i), idx[3u * n + 2u] = SPH_V(j + 1u, i + 1u);
            n++;
            idx[3u * n] = SPH_V(j, i), idx[3u * n + 1u] = SPH_V(j + 1u, i + 1u), idx[3u * n + 2u] = SPH_V(j, i + 1u);
            n++;
        }
    for (i = 0; i < SPH_SLICES; i++, n++)
        idx[3u * n] = top, idx[3u * n + 1u] = SPH_V(SPH_STACKS - 1u, i + 1u), idx[3u * n + 2u] = SPH_V(SPH_STACKS - 1u, i);
#undef SPH_V
    return n;
}

/* A closed mesh with a hole (a sphere with one triangle of its lower fan missing, as scans
 * and exported models have holes and seams) casts as the solid it nearly is: the same
 * bytes as the closed sphere, whose missing triangle faced away from the light anyway.
 * Cast as a sheet (all its triangles, turned to the light), every crossing of it counted
 * twice and its penumbra came out twice as dark (here 246 pixels darker than the reference
 * by more than 0.1, none now; the Buddha: 0.74 % of its pixels darker by more than 0.25). */
static void test_holed_solid(void)
{
    static const float ground[4] = {0.0f, 0.0f, 0.0f, 4.0f}, c[3] = {0.1f, 2.0f, 0.0f};
    static float pos[(SPH_VERTS + 4u) * 3u];
    static uint32_t idx[(SPH_TRIS + 2u) * 3u];
    uint32_t n, p, dark = 0u;
    pn_setup s;
    pn_host h;
    pn_frame_options o;
    pn_stats st;
    if (!open_square_host(&s, &h, SPH_TRIS + 2u)) return;
    put_square(pos, idx, ground, 0u);
    n = 2u + uv_sphere(pos, idx + 6u, 4u, c, 0.6f);
    wg_opts(&o, PN_WG_MODE_BLEND);
    REQUIRE(pn_scene_set(h.ctx, pos, SPH_VERTS + 4u, idx, n) == PN_OK);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_ref, NULL, &st) == 0);
    CHECK_MSG(st.wedges.closed_objects == 1u && st.wedges.open_edges == 4u, "closed sphere: %u solid objects, %u open edges",
              st.wedges.closed_objects, st.wedges.open_edges);
    /* The hole: the lower fan's first triangle moved to the end and left off. */
    memcpy(idx + 6u, idx + 3u * n - 3u, 3u * sizeof(uint32_t));
    REQUIRE(pn_scene_set(h.ctx, pos, SPH_VERTS + 4u, idx, n - 1u) == PN_OK);
    REQUIRE(render_opt(&h, &s, &s.light, &o, g_a, NULL, &st) == 0);
    REQUIRE(render_vis(&h, &s, &s.light, PN_ALGO_REFERENCE, W, H, 32, 1, g_b, NULL) == 0);
    for (p = 0; p < W * H; p++) dark += g_a[p] < g_b[p] - 0.1f;
    fprintf(stderr, "holed sphere: %u open edges, %u solid objects, %u pixels darker than the reference by more than 0.1\n",
            st.wedges.open_edges, st.wedges.closed_objects, dark);
    CHECK_MSG(st.wedges.closed_objects == 1u && st.wedges.open_edges == 7u, "holed sphere: %u solid objects, %u open edges",
              st.wedges.closed_objects, st.wedges.open_edges);
    CHECK_MSG(memcmp(g_a, g_ref, sizeof(g_ref)) == 0, "the holed sphere casts differently from the closed one");
    CHECK_MSG(dark == 0u, "holed sphere: %u pixels darker than the reference by more than 0.1", dark);
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* The frame of o (its stats into st) against the reference at k = 32: its pixels darker and
 * brighter than the reference's by more than d. 0 on success. */
static int off_reference(pn_host *h, const pn_setup *s, const pn_frame_options *o, float d, pn_stats *st, uint32_t *dark,
                         uint32_t *bright)
{
    uint32_t p;
    if (render_opt(h, s, &s->light, o, g_a, NULL, st) != 0) return 1;
    if (render_vis(h, s, &s->light, PN_ALGO_REFERENCE, W, H, 32, 1, g_ref, NULL) != 0) return 1;
    *dark = *bright = 0u;
    for (p = 0; p < W * H; p++) {
        *dark += g_a[p] < g_ref[p] - d;
        *bright += g_a[p] > g_ref[p] + d;
    }
    return 0;
}

/* Where the light centre lies behind a solid's face, the shadow origin (pushed eps off the
 * face, to the centre's side) lies inside the solid, and no sample reaches the light: the
 * centre segment leaves the solid once more than it enters it, and the pixel is dark without
 * the exact fallback (which a closed sphere's terminator took before: exact_pixels > 0).
 * A "leaf" (a closed box thinner than eps, standing before the sphere with its face to the
 * camera turned away from the light centre) is the counter-case: its origins lie beyond
 * it, on its lit side, and must not be taken for inside (the reference's light). */
static void test_inside_solid(void)
{
    static const float ground[4] = {0.0f, 0.0f, 0.0f, 4.0f}, c[3] = {0.1f, 2.0f, 0.0f};
    static float pos[(SPH_VERTS + 4u + 24u) * 3u];
    static uint32_t idx[(SPH_TRIS + 2u + 12u) * 3u];
    const float P0[3] = {-0.8f, 0.4f, 2.6f}, A[3] = {1.6f, 0.0f, 0.0f}, B[3] = {0.0f, 1.2f, -0.36f};
    float nl[3] = {0.0f, 0.3f, 1.0f}, t;
    uint32_t n, p, v, dark, bright;
    pn_setup s;
    pn_host h;
    pn_frame_options o;
    pn_stats st;
    if (!open_square_host(&s, &h, SPH_TRIS + 2u + 12u)) return;
    put_square(pos, idx, ground, 0u);
    n = 2u + uv_sphere(pos, idx + 6u, 4u, c, 0.6f);
    /* The leaf: the unit cube (wound outward) mapped to P0 + x A + y B + z t nl. */
    t = 0.2f * s.eps;
    {
        float l = sqrtf(nl[1] * nl[1] + nl[2] * nl[2]), q[24 * 3];
        uint32_t ci[12 * 3];
        nl[1] /= l, nl[2] /= l;
        cube(q, ci, 0.0f);
        for (v = 0; v < 24u; v++)
            for (p = 0; p < 3u; p++)
                pos[3u * (4u + SPH_VERTS + v) + p] = P0[p] + q[3u * v] * A[p] + q[3u * v + 1u] * B[p] + q[3u * v + 2u] * t * nl[p];
        for (p = 0; p < 36u; p++) idx[3u * n + p] = ci[p] + 4u + SPH_VERTS;
        n += 12u;
    }
    wg_opts(&o, PN_WG_MODE_BLEND);
    REQUIRE(pn_scene_set(h.ctx, pos, SPH_VERTS + 4u + 24u, idx, n) == PN_OK);
    REQUIRE(off_reference(&h, &s, &o, 0.1f, &st, &dark, &bright) == 0);
    fprintf(stderr, "inside a solid: %u solid objects, %u pixels resolved exactly, %u darker and %u brighter than the "
                    "reference by more than 0.1\n",
            st.wedges.closed_objects, st.wedges.exact_pixels, dark, bright);
    CHECK_MSG(st.wedges.closed_objects == 2u, "%u solid objects, want the sphere and the leaf", st.wedges.closed_objects);
    CHECK_MSG(st.wedges.exact_pixels == 0u, "%u pixels took the exact fallback", st.wedges.exact_pixels);
    CHECK_MSG(dark == 0u && bright == 0u, "%u pixels darker, %u brighter than the reference by more than 0.1", dark, bright);
    /* An L standing beside the sphere's place, its arm over the face the camera sees: from
     * that face the arm hides the light centre, the segment enters the L and leaves it
     * (outside), and its penumbra on the face takes the exact fallback. */
    {
        static const float L[12 * 3] = {1.4f, 0.0f, -1.5f, 1.4f, 0.0f, -1.3f, 1.4f, 2.0f, -1.3f, 1.4f, 2.0f, -0.9f,
                                        1.4f, 2.2f, -0.9f, 1.4f, 2.2f, -1.5f, 2.6f, 0.0f, -1.5f, 2.6f, 0.0f, -1.3f,
                                        2.6f, 2.0f, -1.3f, 2.6f, 2.0f, -0.9f, 2.6f, 2.2f, -0.9f, 2.6f, 2.2f, -1.5f};
        static const uint32_t Li[20 * 3] = {0u, 1u, 2u, 6u, 8u, 7u, 0u, 2u, 5u, 6u, 11u, 8u, 2u, 3u, 4u, 8u, 10u, 9u,
                                            2u, 4u, 5u, 8u, 11u, 10u, 0u, 7u, 1u, 0u, 6u, 7u, 1u, 8u, 2u, 1u, 7u, 8u,
                                            2u, 9u, 3u, 2u, 8u, 9u, 3u, 10u, 4u, 3u, 9u, 10u, 4u, 11u, 5u, 4u, 10u, 11u,
                                            5u, 6u, 0u, 5u, 11u, 6u};
        memcpy(pos + 12u, L, sizeof(L));
        for (p = 0; p < 60u; p++) idx[6u + p] = Li[p] + 4u;
        REQUIRE(pn_scene_set(h.ctx, pos, 16u, idx, 22u) == PN_OK);
        REQUIRE(off_reference(&h, &s, &o, 0.25f, &st, &dark, &bright) == 0);
        fprintf(stderr, "overhang: %u solid objects, %u pixels resolved exactly, %u darker and %u brighter than the "
                        "reference by more than 0.25\n",
                st.wedges.closed_objects, st.wedges.exact_pixels, dark, bright);
        CHECK_MSG(st.wedges.closed_objects == 1u && st.wedges.exact_pixels > 0u,
                  "overhang: %u solid objects, %u pixels resolved exactly", st.wedges.closed_objects, st.wedges.exact_pixels);
        CHECK_MSG(dark == 0u && bright == 0u, "overhang: %u pixels darker, %u brighter than the reference by more than 0.25",
                  dark, bright);
    }
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* More objects on a pixel's centre ray than the blending lists (PN_WG_HARD_MAX): 24 strips
 * along x (half-length 0.8, half-width 0.05), each its own object, stacked at heights
 * 1.0 .. 3.3 under the square scene's light, over their ground. From the ground under
 * their middle line every strip hides the light centre and a band of the light about it,
 * the lowest strip's the widest (0.4 of the light's side): most of the light is seen (the
 * reference's answer). Such a pixel takes the exact fallback (counted in
 * wedges.hard_overflow and exact_pixels); it was taken as umbra before, 0 where the
 * reference sees more than half of the light. Never PN_E_INTERNAL, which is reserved for
 * broken invariants (the copper beech's view failed with it before: the cap was counted
 * as a traversal stack overflow). */
static void test_many_blockers(void)
{
    enum { STRIPS = 24 };
    float pos[(STRIPS + 1) * 12];
    uint32_t idx[(STRIPS + 1) * 6], i, dark, bright;
    pn_setup s;
    pn_host h;
    pn_frame_options o;
    pn_stats st;
    if (!open_square_host(&s, &h, STRIPS * 2u + 2u)) return;
    for (i = 0; i <= STRIPS; i++) {
        float *p = pos + i * 12u, y = i < STRIPS ? 1.0f + 0.1f * (float)i : 0.0f;
        float lx = i < STRIPS ? 0.8f : 4.0f, lz = i < STRIPS ? 0.05f : 4.0f;
        p[0] = -lx, p[1] = y, p[2] = -lz; /* wound as put_square's */
        p[3] = -lx, p[4] = y, p[5] = lz;
        p[6] = lx, p[7] = y, p[8] = lz;
        p[9] = lx, p[10] = y, p[11] = -lz;
        quad_tris(idx, i);
    }
    REQUIRE(pn_scene_set(h.ctx, pos, (STRIPS + 1u) * 4u, idx, (STRIPS + 1u) * 2u) == PN_OK);
    wg_opts(&o, PN_WG_MODE_BLEND);
    CHECK_MSG(off_reference(&h, &s, &o, 0.25f, &st, &dark, &bright) == 0, "wedges on %d strips: %s", STRIPS,
              pn_last_error(h.ctx));
    fprintf(stderr, "stacked strips: %u objects, %u pixels past the cap of %u objects (%u resolved exactly); %u darker, "
                    "%u brighter than the reference by more than 0.25\n",
            st.wedges.objects, st.wedges.hard_overflow, (unsigned)PN_WG_HARD_MAX, st.wedges.exact_pixels, dark, bright);
    CHECK_MSG(st.wedges.objects == STRIPS + 1u, "%u objects, want %u", st.wedges.objects, STRIPS + 1u);
    CHECK_MSG(st.wedges.hard_overflow > 0u, "no pixel passed the cap: the test does not exercise it");
    CHECK_MSG(st.wedges.exact_pixels >= st.wedges.hard_overflow, "%u pixels past the cap, %u resolved exactly",
              st.wedges.hard_overflow, st.wedges.exact_pixels);
    CHECK_MSG(dark == 0u && bright == 0u, "%u pixels darker, %u brighter than the reference by more than 0.25", dark, bright);
    pn_host_close(&h);
    pn_setup_free(&s);
}

/* One wedges frame in a fresh arena of limits lim with GUARD bytes after it that must stay
 * untouched; its status, visibility into vis (on PN_OK) and statistics; the reference's
 * frame at the same k into g_b. */
static pn_status short_pool_frame(const pn_setup *s, const pn_limits *lim, float *vis, pn_stats *st, size_t *bytes,
                                  char *err, size_t errlen)
{
    enum { GUARD = 4096 };
    pn_context *ctx;
    pn_frame_options o;
    pn_frame fr, fr2;
    pn_status r;
    uint8_t *raw;
    size_t i;
    int guard_ok = 1;
    if (pn_arena_size(lim, bytes) != PN_OK || !(raw = (uint8_t *)malloc(*bytes + GUARD))) return PN_E_INTERNAL;
    memset(raw, 0x5A, *bytes + GUARD);
    if (pn_init(&ctx, raw, *bytes, lim) != PN_OK ||
        pn_scene_set(ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) != PN_OK) {
        free(raw);
        return PN_E_INTERNAL;
    }
    wg_opts(&o, 0u);
    o.eps = s->eps;
    /* A frame of another algorithm first: a failing frame must leave its buffers alone. It
     * is the reference at the wedges' k (g_b), what a full tile's pixels take. */
    o.algo = PN_ALGO_REFERENCE;
    o.k = 16;
    if (pn_render(ctx, &s->camera, &s->light, &o, &fr) != PN_OK) {
        free(raw);
        return PN_E_INTERNAL;
    }
    memcpy(g_b, fr.visibility, sizeof(g_b));
    o.algo = PN_ALGO_WEDGES;
    o.k = 16;
    fr2 = fr;
    r = pn_render(ctx, &s->camera, &s->light, &o, &fr2);
    if (r == PN_OK) {
        memcpy(vis, fr2.visibility, sizeof(float) * W * H);
    } else {
        CHECK_MSG(memcmp(&fr2, &fr, sizeof(fr)) == 0, "the frame out-parameter was written on failure");
        CHECK_MSG(memcmp(g_b, fr.visibility, sizeof(g_b)) == 0, "the previous frame's visibility changed on failure");
    }
    snprintf(err, errlen, "%s", pn_last_error(ctx));
    CHECK(pn_get_stats(ctx, st) == PN_OK && st->arena_high_water <= st->arena_carved);
    for (i = 0; i < GUARD; i++) guard_ok &= raw[*bytes + i] == 0x5A;
    CHECK_MSG(guard_ok, "bytes after the arena were written");
    free(raw);
    return r;
}

/* The count's kept tiles (pn_wg_bin): a silhouette that counts at most PN_WG_KEEP tiles
 * keeps them for its scatter, one that counts more builds its reach again. At 512x512 seven
 * of room's wedges count more than 64 (an instrumented build of 0f42e31 printed them) and
 * take the second way. With a pair pool of a 64th of the frame's pairs (a tile alone can
 * hold more than 64) the bands are parts of a tile row of 32 tiles or a few sparse rows,
 * and the counts in them keep their tiles. The same bytes both ways (a fallback writing
 * each pair one tile to the left fails here). */
static pn_status kept_frame(const pn_setup *s, uint32_t wg_pairs, float *vis, pn_stats *st)
{
    enum { KW = 512, KH = 512 };
    pn_limits lim;
    pn_context *ctx;
    pn_frame_options o;
    pn_frame fr;
    pn_status r = PN_E_INTERNAL;
    uint8_t *raw;
    size_t bytes;
    pn_limits_max(&lim);
    lim.max_triangles = s->mesh.triangle_count;
    lim.max_width = KW;
    lim.max_height = KH;
    lim.algos = PN_BUILD_WEDGES;
    lim.wg_pairs = wg_pairs;
    if (pn_arena_size(&lim, &bytes) != PN_OK || !(raw = (uint8_t *)malloc(bytes))) return PN_E_INTERNAL;
    if (pn_init(&ctx, raw, bytes, &lim) == PN_OK &&
        pn_scene_set(ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count) == PN_OK) {
        wg_opts(&o, 0u);
        o.width = KW;
        o.height = KH;
        o.k = 16;
        o.eps = s->eps;
        r = pn_render(ctx, &s->camera, &s->light, &o, &fr);
        if (r == PN_OK) memcpy(vis, fr.visibility, sizeof(float) * KW * KH);
        CHECK(pn_get_stats(ctx, st) == PN_OK);
    }
    free(raw);
    return r;
}

static void test_kept_tiles(void)
{
    static float full[512 * 512], cut[512 * 512];
    pn_setup s;
    pn_stats st_full, st_cut;
    char err[256];
    if (pn_setup_load(&s, "room", 1, -1, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading room: %s", err);
        return;
    }
    REQUIRE(kept_frame(&s, 0u, full, &st_full) == PN_OK);
    CHECK(st_full.wedges.bands == 1u && st_full.wedges.pairs > 6400u);
    REQUIRE(kept_frame(&s, (uint32_t)(st_full.wedges.pairs / 64u), cut, &st_cut) == PN_OK);
    fprintf(stderr, "kept tiles: %llu pairs in one band; in %u bands of at most %llu\n",
            (unsigned long long)st_full.wedges.pairs, st_cut.wedges.bands, (unsigned long long)(st_full.wedges.pairs / 64u));
    CHECK(st_cut.wedges.bands >= 64u && st_cut.wedges.pairs == st_full.wedges.pairs);
    CHECK_MSG(memcmp(full, cut, sizeof(full)) == 0, "the scatter's two ways gave different bytes");
    pn_setup_free(&s);
}

/* spheres, and limits for it at W x H with the other algorithms' pools small; 0 when
 * loaded. */
static int short_limits(pn_setup *s, pn_limits *big)
{
    char err[256];
    if (pn_setup_load(s, "spheres", 1, -1, err, sizeof(err)) != 0) {
        CHECK_MSG(0, "loading spheres: %s", err);
        return 1;
    }
    pn_limits_max(big);
    big->max_triangles = s->mesh.triangle_count;
    big->max_width = W;
    big->max_height = H;
    big->gears_pairs = 4096u;
    big->gears_grid_max = 16u;
    big->srt_map_max = 64u;
    big->occ_map_max = 64u;
    big->mc_map_max = 64u;
    return 0;
}

/* Tile by tile, frame a against the one-band frame g_ref and the reference's at the same
 * k, g_b: every pixel of a tile g_ref's, or every one g_b's; *full: the tiles that are
 * g_b's and not g_ref's. The number of tiles that are neither. */
static uint32_t tiles_from(const float *a, uint32_t *full)
{
    uint32_t tx, ty, x, y, bad = 0u;
    *full = 0u;
    for (ty = 0; ty < (H + 15u) / 16u; ty++)
        for (tx = 0; tx < (W + 15u) / 16u; tx++) {
            int as_w = 1, as_r = 1;
            for (y = ty * 16u; y < ty * 16u + 16u && y < H; y++)
                for (x = tx * 16u; x < tx * 16u + 16u && x < W; x++) {
                    size_t p = (size_t)y * W + x;
                    as_w &= memcmp(&a[p], &g_ref[p], sizeof(float)) == 0;
                    as_r &= memcmp(&a[p], &g_b[p], sizeof(float)) == 0;
                }
            bad += !as_w && !as_r;
            *full += as_r && !as_w;
        }
    return bad;
}

/* A pool (*pool of lim, the least `least`) smaller than some tiles' lists: no failure;
 * those tiles are full (pn_stats.wedges.full_tiles), list nothing, and their pixels are the
 * reference's at the frame's k, every other pixel the one-band frame's; the least pool
 * without a full tile (bisection) gives the one-band frame's bytes, one less a full tile. */
static void full_pools(const pn_setup *s, pn_limits *lim, uint32_t *pool, uint32_t least, const char *what)
{
    pn_stats st;
    size_t bytes;
    char err[256];
    uint32_t full, bad, lo = least, hi = *pool;
    *pool = least;
    CHECK_MSG(short_pool_frame(s, lim, g_a, &st, &bytes, err, sizeof(err)) == PN_OK, "%s pool of %u: %s", what, least, err);
    bad = tiles_from(g_a, &full);
    fprintf(stderr, "%s pool of %u: %u full tiles (%u tiles the reference's and not the one band's), %u exact pixels\n", what,
            least, st.wedges.full_tiles, full, st.wedges.exact_pixels);
    CHECK_MSG(bad == 0u, "%s pool of %u: %u tiles neither the one band's nor the reference's", what, least, bad);
    CHECK(st.wedges.full_tiles > 0u && full > 0u && full <= st.wedges.full_tiles && st.wedges.exact_pixels > 0u);
    while (hi - lo > 1u) {
        uint32_t mid = lo + (hi - lo) / 2u;
        *pool = mid;
        REQUIRE(short_pool_frame(s, lim, g_a, &st, &bytes, err, sizeof(err)) == PN_OK);
        CHECK(tiles_from(g_a, &full) == 0u);
        if (st.wedges.full_tiles > 0u)
            lo = mid;
        else
            hi = mid;
    }
    *pool = hi;
    REQUIRE(short_pool_frame(s, lim, g_a, &st, &bytes, err, sizeof(err)) == PN_OK);
    fprintf(stderr, "the least %s pool without a full tile: %u, in %u bands (%u silhouette bands, %u tile rows)\n", what, hi,
            st.wedges.bands, st.wedges.sil_bands, (H + 15u) / 16u);
    CHECK(st.wedges.full_tiles == 0u && st.wedges.bands * st.wedges.sil_bands > (H + 15u) / 16u);
    CHECK_MSG(memcmp(g_a, g_ref, sizeof(g_ref)) == 0, "the least %s pool without a full tile changed the frame's bytes", what);
    *pool = hi - 1u;
    REQUIRE(short_pool_frame(s, lim, g_a, &st, &bytes, err, sizeof(err)) == PN_OK);
    CHECK(st.wedges.full_tiles > 0u && tiles_from(g_a, &full) == 0u && full > 0u);
}

/* A pair pool smaller than the frame's pairs: the frame bins and shades the screen in bands
 * of tiles whose pairs fit, with the same bytes as in one band, in a smaller arena. A pool
 * smaller than one tile's pairs makes that tile full (full_pools), nothing written outside
 * the arena. */
static void test_short_pool(void)
{
    pn_setup s;
    pn_limits big, lim;
    pn_stats st_big, st;
    size_t bytes_big, bytes;
    char err[256];
    if (short_limits(&s, &big) != 0) return;
    REQUIRE(short_pool_frame(&s, &big, g_ref, &st_big, &bytes_big, err, sizeof(err)) == PN_OK);
    CHECK(st_big.wedges.bands == 1u && st_big.wedges.pairs > 1000u);
    lim = big;
    lim.wg_pairs = (uint32_t)(st_big.wedges.pairs / 5u);
    CHECK_MSG(short_pool_frame(&s, &lim, g_a, &st, &bytes, err, sizeof(err)) == PN_OK, "a fifth of the pairs: %s", err);
    fprintf(stderr, "short pair pool: %llu pairs in %u bands of at most %u (one band: %u); arena %zu, default %zu\n",
            (unsigned long long)st.wedges.pairs, st.wedges.bands, lim.wg_pairs, st_big.wedges.bands, bytes, bytes_big);
    CHECK(st.wedges.bands >= 5u && st.wedges.pairs == st_big.wedges.pairs);
    CHECK_MSG(memcmp(g_a, g_ref, sizeof(g_ref)) == 0, "bands changed the frame's bytes");
    CHECK_MSG(bytes < bytes_big, "wg_pairs %u: arena %zu, not below the default's %zu", lim.wg_pairs, bytes, bytes_big);
    full_pools(&s, &lim, &lim.wg_pairs, 2u, "pair");
    pn_setup_free(&s);
}

/* A silhouette pool smaller than the frame's silhouettes (pn_limits.wg_silhouettes): the
 * frame makes them in bands of tiles, each only the silhouettes a tile of the band lists
 * (pn_wg_sil_tiles), with the same bytes as in one band and the same pairs, in a smaller
 * arena; rows that alone need more are cut into tiles of the row. Only a pool smaller than
 * one tile's list makes that tile full (full_pools), nothing written outside the arena. */
static void test_short_silhouettes(void)
{
    pn_setup s;
    pn_limits big, lim;
    pn_stats st_big, st;
    size_t bytes_big, bytes;
    char err[256];
    if (short_limits(&s, &big) != 0) return;
    REQUIRE(short_pool_frame(&s, &big, g_ref, &st_big, &bytes_big, err, sizeof(err)) == PN_OK);
    CHECK(st_big.wedges.sil_bands == 1u && st_big.wedges.silhouettes > 3000u);
    lim = big;
    lim.wg_silhouettes = st_big.wedges.silhouettes / 2u;
    CHECK_MSG(short_pool_frame(&s, &lim, g_a, &st, &bytes, err, sizeof(err)) == PN_OK, "half the silhouettes: %s", err);
    fprintf(stderr, "short silhouette pool: %u silhouettes in %u bands of at most %u (pair bands %u); arena %zu, "
            "default %zu\n", st.wedges.silhouettes, st.wedges.sil_bands, lim.wg_silhouettes, st.wedges.bands, bytes,
            bytes_big);
    CHECK(st.wedges.sil_bands >= 2u && st.wedges.pairs == st_big.wedges.pairs &&
          st.wedges.silhouettes == st_big.wedges.silhouettes);
    CHECK_MSG(memcmp(g_a, g_ref, sizeof(g_ref)) == 0, "silhouette bands changed the frame's bytes");
    CHECK_MSG(bytes < bytes_big, "wg_silhouettes %u: arena %zu, not below the default's %zu", lim.wg_silhouettes, bytes,
              bytes_big);
    /* The least pool (64): full tiles; the least without one: bands of tiles of a row. */
    full_pools(&s, &lim, &lim.wg_silhouettes, 64u, "silhouette");
    lim.wg_silhouettes = 63u; /* below the least pool */
    CHECK(pn_arena_size(&lim, &bytes) == PN_E_LIMIT);
    pn_setup_free(&s);
}

/* ---- 8. The wedge's screen reach ------------------------------------------------------------ */

static float frand(uint32_t *st, float lo, float hi)
{
    *st = *st * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(*st >> 8) * (1.0f / 16777216.0f);
}

static pn_v3 unit(pn_v3 a) { return pn_v3_scale(a, 1.0f / sqrtf(pn_v3_dot(a, a))); }

/* A random light: a rectangle 5 above the ground plane y = 0, facing down (N = U x V),
 * half-sizes 0.1 .. 1.5; its centre. */
static pn_v3 random_light(uint32_t *st, pn_klight *L)
{
    pn_v3 c = pn_v3_make(frand(st, -1.0f, 1.0f), 5.0f, frand(st, -1.0f, 1.0f));
    memset(L, 0, sizeof(*L));
    L->c[0] = c.x, L->c[1] = c.y, L->c[2] = c.z;
    L->U[0] = frand(st, 0.1f, 1.5f);
    L->V[2] = frand(st, 0.1f, 1.5f);
    L->N[1] = -1.0f;
    L->k = 16u;
    return c;
}

/* The tiles reach R covers, row by row as the binning takes them. */
static uint32_t reach_tiles_of(const pn_kview *v, const pn_wreach *R)
{
    uint32_t y, n = 0u, x0, x1;
    if (R->x0 > R->x1) return 0u;
    for (y = R->y0; y <= R->y1; y++) {
        pn_wg_row(v, R, y, &x0, &x1);
        if (x0 <= x1) n += x1 - x0 + 1u;
    }
    return n;
}

static void test_reach(void)
{
    enum { RW = 200, RH = 136, CASES = 300 };
    uint32_t st = 12345u, cs, covered = 0u, reach_tiles = 0u, box_tiles = 0u, missed = 0u, x, y;
    for (cs = 0; cs < CASES; cs++) {
        pn_kview v;
        pn_klight L;
        pn_wsil e;
        pn_wreach R;
        pn_v3 eye, f, r, u, a, b, c, n;
        float hmax, ground, tanh_, h;
        memset(&v, 0, sizeof(v));
        memset(&e, 0, sizeof(e));
        c = random_light(&st, &L);
        hmax = 5.0f;
        a = pn_v3_make(frand(&st, -2.0f, 2.0f), frand(&st, 0.2f, 4.0f), frand(&st, -2.0f, 2.0f));
        b = pn_v3_add(a, pn_v3_make(frand(&st, -1.5f, 1.5f), frand(&st, -1.0f, 1.0f), frand(&st, -1.5f, 1.5f)));
        if (!(b.y > 0.1f && b.y < 4.5f)) b.y = 0.5f;
        /* Eye: above and beside the scene, looking at a point near the origin. */
        eye = pn_v3_make(frand(&st, -6.0f, 6.0f), frand(&st, 1.0f, 7.0f), frand(&st, 4.0f, 9.0f));
        f = unit(pn_v3_sub(pn_v3_make(frand(&st, -1.0f, 1.0f), 0.0f, frand(&st, -1.0f, 1.0f)), eye));
        r = unit(pn_v3_cross(f, pn_v3_make(0.0f, 1.0f, 0.0f)));
        u = pn_v3_cross(r, f);
        v.eye[0] = eye.x, v.eye[1] = eye.y, v.eye[2] = eye.z;
        v.f[0] = f.x, v.f[1] = f.y, v.f[2] = f.z;
        v.r[0] = r.x, v.r[1] = r.y, v.r[2] = r.z;
        v.u[0] = u.x, v.u[1] = u.y, v.u[2] = u.z;
        tanh_ = tanf(0.5f * frand(&st, 0.6f, 1.4f));
        v.tan_half = tanh_;
        v.width = RW;
        v.height = RH;
        v.aspect = (float)RW / (float)RH;
        v.znear = 0.01f;
        pn_wg_light(&L, a, &e.ua, &e.va, &e.ha);
        pn_wg_light(&L, b, &e.ub, &e.vb, &e.hb);
        n = pn_v3_cross(pn_v3_sub(a, c), pn_v3_sub(b, c));
        e.nx = n.x, e.ny = n.y, e.nz = n.z;
        e.w = 1u;
        pn_wg_reach(&v, &L, hmax, a, b, 1, &R);
        /* Receivers: the ground, or a plane below the edge's lower end. */
        ground = (cs & 1u) ? 0.0f : frand(&st, 0.0f, 0.9f) * (a.y < b.y ? a.y : b.y);
        if (R.x0 <= R.x1) {
            box_tiles += (R.x1 - R.x0 + 1u) * (R.y1 - R.y0 + 1u);
            reach_tiles += reach_tiles_of(&v, &R);
        }
        for (y = 0; y < RH; y++)
            for (x = 0; x < RW; x++) {
                float sx = (2.0f * ((float)x + 0.5f) / (float)RW - 1.0f) * tanh_ * v.aspect;
                float sy = (1.0f - 2.0f * ((float)y + 0.5f) / (float)RH) * tanh_, p[4], sg, t;
                pn_v3 d = pn_v3_add(f, pn_v3_add(pn_v3_scale(r, sx), pn_v3_scale(u, sy))), O;
                pn_wframe F;
                pn_wpart parts[4];
                uint32_t tx = x / PN_WG_TILE, ty = y / PN_WG_TILE, x0, x1;
                int in;
                if (!(d.y < 0.0f)) continue;
                t = (ground - eye.y) / d.y;
                O = pn_v3_add(eye, pn_v3_scale(d, t));
                pn_wg_frame(&L, O, &F);
                h = F.ho;
                if (!(h > 0.0f && h <= hmax)) continue;
                if (!pn_wg_project(&F, &e, p, &sg)) continue;
                pn_wg_parts_init(parts, 0.0f);
                if (!pn_wg_edge_parts(p, sg, 1.0f, parts)) continue;
                covered++;
                in = R.x0 <= R.x1 && ty >= R.y0 && ty <= R.y1;
                if (in) {
                    pn_wg_row(&v, &R, ty, &x0, &x1);
                    in = x0 <= x1 && tx >= x0 && tx <= x1;
                }
                if (!in) missed++;
            }
    }
    fprintf(stderr, "reach: %u pixels covered by their edge, %u outside its reach; %u tiles in the reaches, %u in their boxes\n",
            covered, missed, reach_tiles, box_tiles);
    CHECK(covered > 10000u);
    CHECK_MSG(missed == 0u, "a pixel an edge covers light from lies outside the edge's binned tiles");
    CHECK(reach_tiles < box_tiles);
}

/* ---- 9. Tiles in depth and objects: the culls lose nothing ----------------------------- */

/* Random edges and objects against random clusters of shadow origins: where the tile box
 * (pn_wg_box_misses) or the object box (pn_wg_obj_misses) says an edge reaches the light
 * from none of them, pn_wg_project returns 0 for every one; and the culls do cull. */
static void test_culls(void)
{
    enum { CASES = 4000, PTS = 24, EDGES = 4 };
    uint32_t st = 777u, cs, i, j, box_culls = 0u, obj_culls = 0u, box_wrong = 0u, obj_wrong = 0u, reach = 0u, block_wrong = 0u;
    for (cs = 0; cs < CASES; cs++) {
        pn_klight L;
        pn_wsil e[EDGES];
        pn_v3 c, O[PTS], cen;
        float B[PN_WG_BOX], ob[6], spread = frand(&st, 0.01f, 3.0f);
        memset(e, 0, sizeof(e));
        c = random_light(&st, &L);
        /* An object: a few edges around one point (some crossing the origins' heights). */
        cen = pn_v3_make(frand(&st, -4.0f, 4.0f), frand(&st, 0.05f, 4.9f), frand(&st, -4.0f, 4.0f));
        for (j = 0; j < 6u; j += 2u) ob[j] = PN_KINF, ob[j + 1u] = -PN_KINF;
        for (i = 0; i < EDGES; i++) {
            pn_v3 a = pn_v3_add(cen, pn_v3_make(frand(&st, -0.4f, 0.4f), frand(&st, -0.3f, 0.3f), frand(&st, -0.4f, 0.4f)));
            pn_v3 b = pn_v3_add(cen, pn_v3_make(frand(&st, -0.4f, 0.4f), frand(&st, -0.3f, 0.3f), frand(&st, -0.4f, 0.4f)));
            pn_v3 n = pn_v3_cross(pn_v3_sub(a, c), pn_v3_sub(b, c));
            pn_wg_light(&L, a, &e[i].ua, &e[i].va, &e[i].ha);
            pn_wg_light(&L, b, &e[i].ub, &e[i].vb, &e[i].hb);
            e[i].nx = n.x, e[i].ny = n.y, e[i].nz = n.z;
            e[i].w = 1u;
            ob[0] = fminf(ob[0], fminf(e[i].ua, e[i].ub)), ob[1] = fmaxf(ob[1], fmaxf(e[i].ua, e[i].ub));
            ob[2] = fminf(ob[2], fminf(e[i].va, e[i].vb)), ob[3] = fmaxf(ob[3], fmaxf(e[i].va, e[i].vb));
            ob[4] = fminf(ob[4], fminf(e[i].ha, e[i].hb)), ob[5] = fmaxf(ob[5], fmaxf(e[i].ha, e[i].hb));
        }
        /* The object's box and margins as the frame makes them (one object: comp 0), and a
         * block of these edges has the same box (the pixel's run cull tests it). */
        pn_wg_obj_box(e, EDGES, 0u, 0u);
        {
            float bb[6];
            pn_wg_block_box(e, EDGES, 0u, PN_WG_BLOCK, 0u, bb);
            block_wrong += (uint32_t)(memcmp(bb, ob, sizeof(bb)) != 0);
            block_wrong += (uint32_t)(memcmp(e[EDGES - 1u].ob, ob, sizeof(bb)) != 0);
            block_wrong += (uint32_t)(e[0].ob[6] != fmaxf(fabsf(ob[0]), fabsf(ob[1])) ||
                                      e[0].ob[7] != fmaxf(fabsf(ob[2]), fabsf(ob[3])));
        }
        /* Origins: a cluster (a tile's points), some on the edges' own heights. */
        {
            /* Half of the clusters below the object as seen from the light, half anywhere. */
            pn_v3 oc = (cs & 1u) ? pn_v3_add(cen, pn_v3_scale(pn_v3_sub(cen, c), frand(&st, 0.0f, 1.2f)))
                                 : pn_v3_make(frand(&st, -5.0f, 5.0f), frand(&st, 0.0f, 4.5f), frand(&st, -5.0f, 5.0f));
            if (oc.y < 0.0f) oc.y = 0.0f;
            for (j = 0; j < 6u; j += 2u) B[j] = PN_KINF, B[j + 1u] = -PN_KINF;
            for (i = 0; i < PTS; i++) {
                float u, v, h;
                O[i] = pn_v3_add(oc, pn_v3_make(frand(&st, -spread, spread), frand(&st, -spread, spread) * 0.3f,
                                                frand(&st, -spread, spread)));
                if (O[i].y > 4.99f) O[i].y = 4.99f;
                pn_wg_light(&L, O[i], &u, &v, &h);
                B[0] = fminf(B[0], u), B[1] = fmaxf(B[1], u);
                B[2] = fminf(B[2], v), B[3] = fmaxf(B[3], v);
                B[4] = fminf(B[4], h), B[5] = fmaxf(B[5], h);
            }
        }
        for (i = 0; i < PTS; i++) {
            pn_wframe F;
            int any = 0, om;
            pn_wg_frame(&L, O[i], &F);
            om = pn_wg_obj_misses(&F, e[0].ob, e[0].ob[6], e[0].ob[7]);
            obj_wrong += (uint32_t)(om != pn_wg_box6_misses(&F, ob));
            obj_culls += (uint32_t)om;
            for (j = 0; j < EDGES; j++) {
                float p[4], sg;
                int r = pn_wg_project(&F, e + j, p, &sg);
                any |= r;
                reach += (uint32_t)r;
                box_wrong += (uint32_t)(r && pn_wg_box_misses(B, e + j));
            }
            obj_wrong += (uint32_t)(om && any);
        }
        for (j = 0; j < EDGES; j++) box_culls += (uint32_t)pn_wg_box_misses(B, e + j);
    }
    fprintf(stderr, "culls: %u of %u (box, edge) culled, %u of %u (origin, object); %u (origin, edge) reach the light\n",
            box_culls, CASES * EDGES, obj_culls, CASES * PTS, reach);
    CHECK_MSG(box_wrong == 0u, "%u (origin, edge) pairs reach the light through a box said to miss", box_wrong);
    CHECK_MSG(obj_wrong == 0u, "%u origins see an edge of an object said to miss", obj_wrong);
    CHECK_MSG(block_wrong == 0u, "%u blocks' or objects' boxes differ from their edges' box", block_wrong);
    CHECK(box_culls > CASES * EDGES / 10u && box_culls < CASES * EDGES * 9u / 10u);
    CHECK(obj_culls > CASES * PTS / 10u && reach > CASES);
}

/* ---- 10. A tile's centre cone: clear only when no segment to the centre is blocked ------- */

/* Whether segment o -> c meets triangle p (double precision, edges included). */
/* ---- 12. The culls against PN_WG_NO_CULL ---------------------------------------------------- */

static void test_no_cull(void)
{
    const char *const *names = pn_builtin_scene_names();
    uint32_t i, m, tiles = PN_WG_TILES(W) * PN_WG_TILES(H);
    for (i = 0; names[i]; i++) {
        pn_setup s;
        pn_host h;
        if (!open_scene(names[i], &s, &h, 2)) continue;
        for (m = PN_WG_MODE_BLEND; m <= PN_WG_MODE_ADDITIVE; m++) {
            pn_frame_options o;
            pn_stats a, b;
            uint32_t differ = 0u, p;
            wg_opts(&o, m);
            o.k = 16u;
            REQUIRE(render_opt(&h, &s, &s.light, &o, g_a, NULL, &a) == 0);
            o.wedges.flags = PN_WG_NO_CULL;
            REQUIRE(render_opt(&h, &s, &s.light, &o, g_b, NULL, &b) == 0);
            for (p = 0; p < W * H; p++) differ += memcmp(&g_a[p], &g_b[p], sizeof(float)) != 0;
            if (m == PN_WG_MODE_BLEND)
                fprintf(stderr, "%s: %u silhouettes, pairs %llu -> %llu, edges evaluated %llu -> %llu without the culls\n",
                        names[i], a.wedges.silhouettes, (unsigned long long)a.wedges.pairs,
                        (unsigned long long)b.wedges.pairs, (unsigned long long)a.wedges.evaluated,
                        (unsigned long long)b.wedges.evaluated);
            CHECK_MSG(differ == 0u, "%s, mode %u: %u pixels differ without the culls", names[i], m, differ);
            CHECK_MSG(b.wedges.silhouettes == a.wedges.silhouettes &&
                          b.wedges.pairs == (uint64_t)a.wedges.silhouettes * tiles && b.wedges.evaluated >= a.wedges.evaluated,
                      "%s: %u / %u silhouettes, %llu pairs without the culls (%u tiles)", names[i], a.wedges.silhouettes,
                      b.wedges.silhouettes, (unsigned long long)b.wedges.pairs, tiles);
        }
        {
            pn_frame_options o;
            pn_frame fr;
            wg_opts(&o, 0u);
            o.eps = s.eps;
            o.wedges.flags = 2u;
            CHECK(pn_render(h.ctx, &s.camera, &s.light, &o, &fr) == PN_E_INVALID_ARG);
            CHECK(strstr(pn_last_error(h.ctx), "wedges.flags") != NULL);
        }
        pn_host_close(&h);
        pn_setup_free(&s);
    }
}

static int seg_hits(pn_v3 o, pn_v3 c, const float *p)
{
    double e1[3], e2[3], d[3], s[3], q[3], h[3], a, f, u, v, t;
    int k;
    for (k = 0; k < 3; k++) {
        e1[k] = (double)p[3 + k] - p[k];
        e2[k] = (double)p[6 + k] - p[k];
        d[k] = (double)(k == 0 ? c.x - o.x : k == 1 ? c.y - o.y : c.z - o.z);
        s[k] = (double)(k == 0 ? o.x : k == 1 ? o.y : o.z) - p[k];
    }
    h[0] = d[1] * e2[2] - d[2] * e2[1], h[1] = d[2] * e2[0] - d[0] * e2[2], h[2] = d[0] * e2[1] - d[1] * e2[0];
    a = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabs(a) < 1e-300) return 0;
    f = 1.0 / a;
    u = f * (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]);
    q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
    v = f * (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]);
    t = f * (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]);
    return u >= -1e-9 && v >= -1e-9 && u + v <= 1.0 + 1e-9 && t >= -1e-9 && t <= 1.0 + 1e-9;
}

/* Random lights, receiver patches on random planes (a tile's points) and triangles near
 * their centre segments, on the receivers' plane and anywhere, each alone in a one-leaf
 * BVH, and a quarter of the patches curved (normals tilted apart): a cone said clear
 * (pn_wg_cone_clear) meets no segment from an origin to the light centre; and the receivers' own plane, eps behind the origins, is clear of almost every
 * cone (what lets a floor's tiles skip their centre rays). */
static void test_cone(void)
{
    enum { CASES = 3000, PTS = 16, TRIS = 12 };
    uint32_t st = 4242u, cs, i, j, wrong = 0u, clear = 0u, blocked = 0u, plane = 0u, plane_clear = 0u, cones = 0u, mixed;
    for (cs = 0; cs < CASES; cs++) {
        pn_klight L;
        pn_v3 c = random_light(&st, &L), n, P0, t1, t2, O[PTS];
        pn_wcone C;
        pn_frustum fr;
        float spread = frand(&st, 0.01f, 1.0f);
        L.eps = frand(&st, 1e-3f, 1e-2f); /* the frame's: 1e-4 of the scene's diagonal (about 20 here) and up */
        L.cull_tol = 2e-4f;                 /* the frame's: 1e-5 of that diagonal */
        /* The receivers' plane: through P0, normal n (tilted up to nearly edge-on). */
        n = unit(pn_v3_make(frand(&st, -1.0f, 1.0f), frand(&st, 0.05f, 1.0f), frand(&st, -1.0f, 1.0f)));
        P0 = pn_v3_make(frand(&st, -5.0f, 5.0f), frand(&st, 0.0f, 3.0f), frand(&st, -5.0f, 5.0f));
        t1 = unit(pn_v3_cross(n, pn_v3_make(0.3f, 0.1f, 1.0f)));
        t2 = pn_v3_cross(n, t1);
        /* Every fourth case a curved receiver: each point's normal tilted from the plane's
         * (the cap takes the first point's, which then is no plane of the others). */
        mixed = cs % 4u == 3u;
        pn_wg_cone_init(&C);
        for (i = 0; i < PTS; i++) {
            pn_v3 P = pn_v3_add(P0, pn_v3_add(pn_v3_scale(t1, frand(&st, -spread, spread)), pn_v3_scale(t2, frand(&st, -spread, spread))));
            pn_v3 ni = mixed ? unit(pn_v3_add(n, pn_v3_make(frand(&st, -0.6f, 0.6f), frand(&st, -0.6f, 0.6f), frand(&st, -0.6f, 0.6f)))) : n;
            if (!pn_shadow_origin(P, ni, &L, &O[i])) O[i] = pn_v3_make(0.0f, 99.0f, 0.0f);
            pn_wg_cone_add(&C, &L, O[i], P, ni);
        }
        if (!pn_wg_cone_frustum(&C, &L, &fr)) continue;
        cones++;
        for (j = 0; j < TRIS; j++) {
            float tri[9];
            pn_kbvh4 node;
            uint32_t idx = 0u, k, hit = 0u, a, ok;
            pn_v3 cen;
            if (j < 2u) { /* on the receivers' plane, around the patch */
                cen = pn_v3_add(P0, pn_v3_add(pn_v3_scale(t1, frand(&st, -spread, spread)), pn_v3_scale(t2, frand(&st, -spread, spread))));
                for (k = 0; k < 3u; k++) {
                    pn_v3 q = pn_v3_add(cen, pn_v3_add(pn_v3_scale(t1, frand(&st, -3.0f, 3.0f) * spread),
                                                       pn_v3_scale(t2, frand(&st, -3.0f, 3.0f) * spread)));
                    tri[3 * k] = q.x, tri[3 * k + 1] = q.y, tri[3 * k + 2] = q.z;
                }
            } else {
                float sz = frand(&st, 0.001f, 1.0f);
                if (j < 8u) { /* near a segment */
                    pn_v3 o = O[j % PTS];
                    cen = pn_v3_add(o, pn_v3_scale(pn_v3_sub(c, o), frand(&st, -0.05f, 1.05f)));
                } else {
                    cen = pn_v3_make(frand(&st, -6.0f, 6.0f), frand(&st, -1.0f, 6.0f), frand(&st, -6.0f, 6.0f));
                }
                for (k = 0; k < 9u; k++) tri[k] = (k % 3u == 0u ? cen.x : k % 3u == 1u ? cen.y : cen.z) + frand(&st, -sz, sz);
            }
            memset(&node, 0, sizeof(node));
            node.n = 1u;
            node.child[0] = PN_W4_LEAF;
            for (a = 0; a < 3u; a++) {
                node.lo[a][0] = fminf(tri[a], fminf(tri[3 + a], tri[6 + a]));
                node.hi[a][0] = fmaxf(tri[a], fmaxf(tri[3 + a], tri[6 + a]));
            }
            for (i = 0; i < PTS; i++) hit |= (uint32_t)seg_hits(O[i], c, tri);
            ok = (uint32_t)pn_wg_cone_clear(&fr, tri, &node, &idx);
            wrong += ok & hit;
            clear += ok;
            blocked += hit;
            if (j < 2u && !mixed) plane++, plane_clear += ok;
        }
    }
    fprintf(stderr, "cone: %u cones; %u of %u triangles clear, %u block a segment; the receivers' plane clear %u of %u\n",
            cones, clear, cones * TRIS, blocked, plane_clear, plane);
    CHECK_MSG(wrong == 0u, "%u triangles meet a centre segment of a cone said clear", wrong);
    CHECK(cones > CASES / 2u && blocked > cones && clear > cones * 3u);
    CHECK_MSG(plane_clear * 100u >= plane * 95u, "the receivers' own plane is clear of only %u of %u cones", plane_clear, plane);
}

int main(void)
{
    if (!(pn_build_info() & PN_BUILD_WEDGES)) {
        fprintf(stderr, "PN_ALGO_WEDGES not compiled in\n");
        return 0;
    }
    RUN(test_connect);
    RUN(test_square);
    RUN(test_point_light);
    RUN(test_blend_spheres);
    RUN(test_blend_stacked);
    RUN(test_blend_disjoint);
    RUN(test_two_layers);
    RUN(test_double_sided);
    RUN(test_holed_solid);
    RUN(test_inside_solid);
    RUN(test_many_blockers);
    RUN(test_short_pool);
    RUN(test_short_silhouettes);
    RUN(test_kept_tiles);
    RUN(test_reach);
    RUN(test_culls);
    RUN(test_cone);
    RUN(test_no_cull);
    return pn_test_summary();
}
