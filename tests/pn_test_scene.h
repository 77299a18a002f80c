/* pn_test_scene.h - what the core tests need from a host, without the tools (issue 46: the
 * library's tests link only the library):
 *
 *   a triangle list on the heap (pn_test_mesh) and shapes to fill it: quads, boxes, ramps,
 *   the 762-triangle sphere, a ground square that is the scene's receiver range;
 *   the built-in scenes the core tests render (pn_test_scene_load: square, spheres,
 *   elongated-cube, thin, room), rebuilt from their definitions in tools/pn_scenes*.c
 *   vertex for vertex, with the same views, lights and eps (1e-4 of the bounding-box
 *   diagonal, tools/pn_setup.h); tests/test_setup.c holds them to the tools' bytes;
 *   the square scene's closed form (tools/pn_scenes.c pn_square_closed_form);
 *   a library context on the heap opened through the public API alone (pn_test_open), and
 *   serial parallel-fors that hand the work items out in other orders than the library's
 *   own loop (pn_test_parallel_for), for determinism checks without threads.
 *
 * Header-only, C99, static functions. Tests may allocate; the library may not. Include after
 * penumbra.h. Positions are computed in double and rounded to float once, as the tools do. */
#ifndef PN_TEST_SCENE_H
#define PN_TEST_SCENE_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"

#define PN_TEST_PI 3.14159265358979323846

/* ---- The triangle list ------------------------------------------------------------------ */

typedef struct pn_test_mesh {
    float *positions;        /* vertex_count * 3 floats */
    uint32_t vertex_count;
    uint32_t *indices;       /* triangle_count * 3, each < vertex_count */
    uint32_t triangle_count;
    float bbox_min[3];       /* over referenced vertices (pn_test_mesh_update_bbox) */
    float bbox_max[3];
    /* Triangles [receiver_first, receiver_first + receiver_count): pure receivers (a
     * ground), for pn_scene_set_receivers; count 0: none. */
    uint32_t receiver_first, receiver_count;
    uint32_t cap_v, cap_t; /* allocated vertices and triangles */
    int failed;            /* an allocation failed: the mesh is incomplete */
} pn_test_mesh;

static inline void pn_test_mesh_free(pn_test_mesh *m)
{
    free(m->positions);
    free(m->indices);
    memset(m, 0, sizeof(*m));
}

/* Room for at least nv more vertices and nt more triangles. 0 on success. */
static inline int pn_test_mesh_reserve(pn_test_mesh *m, uint32_t nv, uint32_t nt)
{
    if (m->failed) return 1;
    if (m->vertex_count + nv > m->cap_v) {
        uint32_t cap = m->cap_v ? m->cap_v : 64u;
        float *p;
        while (cap < m->vertex_count + nv) cap *= 2u;
        p = (float *)realloc(m->positions, (size_t)cap * 3u * sizeof(float));
        if (!p) return m->failed = 1;
        m->positions = p;
        m->cap_v = cap;
    }
    if (m->triangle_count + nt > m->cap_t) {
        uint32_t cap = m->cap_t ? m->cap_t : 64u;
        uint32_t *x;
        while (cap < m->triangle_count + nt) cap *= 2u;
        x = (uint32_t *)realloc(m->indices, (size_t)cap * 3u * sizeof(uint32_t));
        if (!x) return m->failed = 1;
        m->indices = x;
        m->cap_t = cap;
    }
    return 0;
}

static inline uint32_t pn_test_vertex(pn_test_mesh *m, double x, double y, double z)
{
    uint32_t v = m->vertex_count;
    if (pn_test_mesh_reserve(m, 1u, 0u) != 0) return 0;
    m->positions[(size_t)v * 3u + 0u] = (float)x;
    m->positions[(size_t)v * 3u + 1u] = (float)y;
    m->positions[(size_t)v * 3u + 2u] = (float)z;
    m->vertex_count++;
    return v;
}

/* (a, b, c) counter-clockwise seen from the side the normal (b - a) x (c - a) points to. */
static inline void pn_test_tri(pn_test_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t t = m->triangle_count;
    if (pn_test_mesh_reserve(m, 0u, 1u) != 0) return;
    m->indices[(size_t)t * 3u + 0u] = a;
    m->indices[(size_t)t * 3u + 1u] = b;
    m->indices[(size_t)t * 3u + 2u] = c;
    m->triangle_count++;
}

/* The next `count` triangles added are the mesh's receivers. */
static inline void pn_test_receivers_next(pn_test_mesh *m, uint32_t count)
{
    m->receiver_first = m->triangle_count;
    m->receiver_count = count;
}

static inline void pn_test_mesh_update_bbox(pn_test_mesh *m)
{
    float lo[3] = {0.0f, 0.0f, 0.0f}, hi[3] = {0.0f, 0.0f, 0.0f};
    uint64_t i, n = (uint64_t)m->triangle_count * 3u;
    int k, any = 0;
    for (i = 0; m->positions && m->indices && i < n; i++) {
        const float *p;
        if (m->indices[i] >= m->vertex_count) continue;
        p = m->positions + (size_t)m->indices[i] * 3u;
        for (k = 0; k < 3; k++) {
            if (!any || p[k] < lo[k]) lo[k] = p[k];
            if (!any || p[k] > hi[k]) hi[k] = p[k];
        }
        any = 1;
    }
    memcpy(m->bbox_min, lo, sizeof(lo));
    memcpy(m->bbox_max, hi, sizeof(hi));
}

/* Bounding-box diagonal, summed in double (tools/pn_mesh.c pn_mesh_diag). */
static inline float pn_test_mesh_diag(const pn_test_mesh *m)
{
    double s = 0.0;
    int k;
    for (k = 0; k < 3; k++) {
        double d = (double)m->bbox_max[k] - (double)m->bbox_min[k];
        s += d * d;
    }
    return (float)sqrt(s);
}

/* ---- Shapes (tools/pn_scenes_build.c) ---------------------------------------------------- */

/* Quad a-b-c-d, counter-clockwise seen from outside, split along a-c. */
static inline void pn_test_quad(pn_test_mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    pn_test_tri(m, a, b, c);
    pn_test_tri(m, a, c, d);
}

/* Quad a-b-c-d (convex, planar, either winding) wound so its normal has a positive
 * component along dir. */
static inline void pn_test_quad_toward(pn_test_mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d,
                                       const double dir[3])
{
    double p[3][3], e1[3], e2[3], n[3];
    const uint32_t q[3] = {a, b, c};
    int i, k;
    if (m->failed) return;
    for (i = 0; i < 3; i++)
        for (k = 0; k < 3; k++) p[i][k] = (double)m->positions[(size_t)q[i] * 3u + (size_t)k];
    for (k = 0; k < 3; k++) {
        e1[k] = p[1][k] - p[0][k];
        e2[k] = p[2][k] - p[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    if (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2] > 0.0)
        pn_test_quad(m, a, b, c, d);
    else
        pn_test_quad(m, a, d, c, b);
}

/* Horizontal square |x - cx|, |z - cz| <= h at height y, facing +y: two triangles split
 * along the (-x,-z)-(+x,+z) diagonal. */
static inline void pn_test_hsquare(pn_test_mesh *m, double cx, double y, double cz, double h)
{
    uint32_t v0 = pn_test_vertex(m, cx - h, y, cz - h);
    uint32_t v1 = pn_test_vertex(m, cx - h, y, cz + h);
    uint32_t v2 = pn_test_vertex(m, cx + h, y, cz + h);
    uint32_t v3 = pn_test_vertex(m, cx + h, y, cz - h);
    pn_test_quad(m, v0, v1, v2, v3);
}

/* The ground: a horizontal square facing up, the mesh's receivers. */
static inline void pn_test_ground(pn_test_mesh *m, double cx, double y, double cz, double h)
{
    pn_test_receivers_next(m, 2u);
    pn_test_hsquare(m, cx, y, cz, h);
}

/* Closed axis-aligned box [lo, hi]: 8 shared vertices (corner c: x = hi iff bit 0, y iff
 * bit 1, z iff bit 2), 12 triangles, outward normals. rise != 0 shears it into a ramp
 * climbing toward -z (every corner's y raised by rise * (hi.z - z)); inside != 0 makes a
 * room's shell: faces wound inward, no -y face. */
static inline void pn_test_box_ex(pn_test_mesh *m, const double lo[3], const double hi[3], double rise, int inside)
{
    static const uint8_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                        {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    uint32_t base = m->vertex_count;
    int c, f;
    for (c = 0; c < 8; c++) {
        double z = (c & 4) ? hi[2] : lo[2], y = (c & 2) ? hi[1] : lo[1];
        pn_test_vertex(m, (c & 1) ? hi[0] : lo[0], y + rise * (hi[2] - z), z);
    }
    for (f = 0; f < 6; f++) {
        const uint8_t *q = faces[f];
        if (!inside)
            pn_test_quad(m, base + q[0], base + q[1], base + q[2], base + q[3]);
        else if (f != 2)
            pn_test_quad(m, base + q[0], base + q[3], base + q[2], base + q[1]);
    }
}

static inline void pn_test_block(pn_test_mesh *m, double x0, double y0, double z0, double x1, double y1, double z1)
{
    const double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
    pn_test_box_ex(m, lo, hi, 0.0, 0);
}

/* The 762-triangle sphere of Forest et al. 2006 (383 vertices: two poles, 17 rings at
 * polar angles of 10-degree steps, ring sizes proportional to sin theta, odd rings turned
 * half a step; zipper strips between rings, fans at the poles). */
#define PN_TEST_SPHERE_RINGS 17
static inline void pn_test_sphere(pn_test_mesh *m, double cx, double cy, double cz, double r)
{
    static const uint32_t ring_count[PN_TEST_SPHERE_RINGS] = {6, 11, 17, 21, 26, 29, 31, 33, 33,
                                                              33, 31, 29, 26, 21, 17, 11, 6};
    uint32_t ring_base[PN_TEST_SPHERE_RINGS], north, south, j;
    int i;
    north = pn_test_vertex(m, cx, cy + r, cz);
    for (i = 0; i < PN_TEST_SPHERE_RINGS; i++) {
        uint32_t n = ring_count[i];
        double theta = (double)(i + 1) * PN_TEST_PI / (double)(PN_TEST_SPHERE_RINGS + 1);
        double st = sin(theta), ct = cos(theta);
        ring_base[i] = m->vertex_count;
        for (j = 0; j < n; j++) {
            double phi = 2.0 * PN_TEST_PI * ((double)j + 0.5 * (i & 1)) / (double)n;
            pn_test_vertex(m, cx + r * st * cos(phi), cy + r * ct, cz + r * st * sin(phi));
        }
    }
    south = pn_test_vertex(m, cx, cy - r, cz);
    for (j = 0; j < ring_count[0]; j++) pn_test_tri(m, north, ring_base[0] + (j + 1u) % ring_count[0], ring_base[0] + j);
    for (i = 0; i + 1 < PN_TEST_SPHERE_RINGS; i++) {
        uint32_t na = ring_count[i], nb = ring_count[i + 1], a0 = ring_base[i], b0 = ring_base[i + 1], ia = 0, ib = 0;
        /* azimuths in units of 2 pi / (2 na nb): integer comparisons, no float ties */
        uint64_t oa = (uint64_t)(i & 1), ob = (uint64_t)((i + 1) & 1);
        while (ia < na || ib < nb) {
            int advance_a = ia == na ? 0
                            : ib == nb ? 1
                                       : (2u * (uint64_t)(ia + 1u) + oa) * nb <= (2u * (uint64_t)(ib + 1u) + ob) * na;
            if (advance_a) {
                pn_test_tri(m, a0 + ia % na, a0 + (ia + 1u) % na, b0 + ib % nb);
                ia++;
            } else {
                pn_test_tri(m, a0 + ia % na, b0 + (ib + 1u) % nb, b0 + ib % nb);
                ib++;
            }
        }
    }
    {
        uint32_t n = ring_count[PN_TEST_SPHERE_RINGS - 1], a0 = ring_base[PN_TEST_SPHERE_RINGS - 1];
        for (j = 0; j < n; j++) pn_test_tri(m, a0 + j, a0 + (j + 1u) % n, south);
    }
}

/* ---- Randomness (tools/pn_mesh.c pn_hash32, tools/pn_scenes_build.c pn_sc_rand01) ---------- */

/* lowbias32 (C. Wellons). */
static inline uint32_t pn_test_hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* Uniform in [0, 1) with 24 bits. */
static inline double pn_test_rand01(uint32_t seed, uint32_t counter)
{
    return (double)(pn_test_hash32(seed ^ pn_test_hash32(counter)) >> 8) * (1.0 / 16777216.0);
}

/* ---- The square scene's closed form (tools/pn_scenes.c) ------------------------------------ *
 * Light: centre (0, light_y, 0), half-edges (light_half, 0, 0), (0, 0, light_half), emitting
 * down. Occluder: |x|, |z| <= occluder_half at y = occluder_y. Receiver: |x|, |z| <= ground_half
 * at y = ground_y. Every value exact in float. */
typedef struct pn_test_square_params {
    float light_y, light_half, occluder_y, occluder_half, ground_y, ground_half;
} pn_test_square_params;

static inline void pn_test_square_scene_params(pn_test_square_params *p)
{
    /* The occluder at half the light's height: umbra |x|, |z| <= 0.5, penumbra to 1.5. */
    p->light_y = 4.0f;
    p->light_half = 0.5f;
    p->occluder_y = 2.0f;
    p->occluder_half = 0.5f;
    p->ground_y = 0.0f;
    p->ground_half = 4.0f;
}

/* Fraction of the light's extent hidden along one axis for receiver coordinate x: the
 * segment to light coordinate s crosses the occluder's plane at x + f (s - x), f the
 * occluder's height over the light's, both above the receiver. k >= 1: of the k sample
 * columns; k = 0: of the continuous extent. */
static inline double pn_test_square_axis_hidden(const pn_test_square_params *p, double x, int k)
{
    double f = ((double)p->occluder_y - (double)p->ground_y) / ((double)p->light_y - (double)p->ground_y);
    double L = (double)p->light_half, h = (double)p->occluder_half;
    if (k <= 0) {
        double lo = (-h - (1.0 - f) * x) / f, hi = (h - (1.0 - f) * x) / f;
        double a = lo > -L ? lo : -L, c = hi < L ? hi : L;
        return c > a ? (c - a) / (2.0 * L) : 0.0;
    } else {
        int i, n = 0;
        for (i = 0; i < k; i++) {
            double s = ((double)(2 * i + 1) / (double)k - 1.0) * L;
            if (fabs(x + f * (s - x)) <= h) n++;
        }
        return (double)n / (double)k;
    }
}

/* Fraction of the light NOT hidden from receiver point (x, p->ground_y, z), in double: of the
 * k x k samples c + ((2i+1)/k - 1) u + ((2j+1)/k - 1) v (the occluder's boundary hides), or of
 * the area for k = 0. To model an origin lifted by eps, pass ground_y + eps. */
static inline double pn_test_square_closed_form(const pn_test_square_params *p, double x, double z, int k)
{
    return 1.0 - pn_test_square_axis_hidden(p, x, k) * pn_test_square_axis_hidden(p, z, k);
}

/* Smallest distance, in light-plane units, between a sample and the boundary of the
 * occluder projected from (x, p->ground_y, z) onto the light plane (HUGE_VAL for k <= 0):
 * where it is tiny, float rounding decides the sample. */
static inline double pn_test_square_min_edge_distance(const pn_test_square_params *p, double x, double z, int k)
{
    double f, L, h, lox, hix, loz, hiz, best = HUGE_VAL;
    int i, j;
    if (k <= 0) return HUGE_VAL;
    f = ((double)p->occluder_y - (double)p->ground_y) / ((double)p->light_y - (double)p->ground_y);
    L = (double)p->light_half;
    h = (double)p->occluder_half;
    lox = (-h - (1.0 - f) * x) / f;
    hix = (h - (1.0 - f) * x) / f;
    loz = (-h - (1.0 - f) * z) / f;
    hiz = (h - (1.0 - f) * z) / f;
    for (j = 0; j < k; j++) {
        double t = ((double)(2 * j + 1) / (double)k - 1.0) * L;
        for (i = 0; i < k; i++) {
            double s = ((double)(2 * i + 1) / (double)k - 1.0) * L, d;
            if (s >= lox && s <= hix && t >= loz && t <= hiz) {
                d = s - lox;
                if (hix - s < d) d = hix - s;
                if (t - loz < d) d = t - loz;
                if (hiz - t < d) d = hiz - t;
            } else {
                double dx = s < lox ? lox - s : (s > hix ? s - hix : 0.0);
                double dz = t < loz ? loz - t : (t > hiz ? t - hiz : 0.0);
                d = sqrt(dx * dx + dz * dz);
            }
            if (d < best) best = d;
        }
    }
    return best;
}

/* ---- The built-in scenes (tools/pn_scenes_objects.c, tools/pn_scenes_sets.c) ---------------- */

typedef struct pn_test_scene {
    pn_test_mesh mesh;
    pn_camera camera;
    pn_light light;
    float diag; /* bounding-box diagonal */
    float eps;  /* 1e-4 * diag, the tools' convention */
    char name[128];
} pn_test_scene;

static inline void pn_test_set3(float d[3], float x, float y, float z)
{
    d[0] = x;
    d[1] = y;
    d[2] = z;
}

/* Camera at e looking at (0, ty, 0), up +y; square light of half size lh centred at
 * (0, ly, 0), u = +x, v = +z (u x v = -y: emits down). */
static inline void pn_test_view(pn_test_scene *s, float ex, float ey, float ez, float ty, float fov, float ly, float lh)
{
    pn_test_set3(s->camera.eye, ex, ey, ez);
    pn_test_set3(s->camera.target, 0.0f, ty, 0.0f);
    pn_test_set3(s->camera.up, 0.0f, 1.0f, 0.0f);
    s->camera.fov_deg = fov;
    pn_test_set3(s->light.center, 0.0f, ly, 0.0f);
    pn_test_set3(s->light.u, lh, 0.0f, 0.0f);
    pn_test_set3(s->light.v, 0.0f, 0.0f, lh);
}

/* square: occluder (triangles 0, 1), ground (2, 3). */
static inline void pn_test_build_square(pn_test_scene *s)
{
    pn_test_square_params p;
    pn_test_square_scene_params(&p);
    pn_test_hsquare(&s->mesh, 0.0, p.occluder_y, 0.0, p.occluder_half);
    pn_test_ground(&s->mesh, 0.0, p.ground_y, 0.0, p.ground_half);
    pn_test_view(s, 0.0f, 9.0f, 9.0f, -0.5f, 50.0f, p.light_y, p.light_half);
}

/* spheres: 9 x 9 spheres of radius 0.4 on a unit grid at height 1.5 (row-major, z outer),
 * sphere s = triangles [762 s, 762 (s + 1)); the ground last. */
static inline void pn_test_build_spheres(pn_test_scene *s)
{
    int ix, iz;
    for (iz = 0; iz < 9; iz++)
        for (ix = 0; ix < 9; ix++) pn_test_sphere(&s->mesh, (double)(ix - 4), 1.5, (double)(iz - 4), 0.4);
    pn_test_ground(&s->mesh, 0.0, 0.0, 0.0, 7.0);
    pn_test_view(s, 0.0f, 14.0f, 15.0f, -0.5f, 52.0f, 8.0f, 2.0f);
}

/* elongated-cube (Curtis 2009, Fig. 4.2): a 0.6 x 3 x 0.6 box, y in [1, 4], under a 2 x 2
 * light at y = 7; box (12 triangles), ground (2). */
static inline void pn_test_build_elongated_cube(pn_test_scene *s)
{
    static const double lo[3] = {-0.3, 1.0, -0.3}, hi[3] = {0.3, 4.0, 0.3};
    pn_test_box_ex(&s->mesh, lo, hi, 0.0, 0);
    pn_test_ground(&s->mesh, 0.0, 0.0, 0.0, 5.0);
    pn_test_view(s, 0.0f, 5.0f, 15.0f, 1.0f, 52.0f, 7.0f, 1.0f);
}

/* thin: 2000 needles 2 long and 0.002 wide at the base, centres in [-3, 3] x [1, 1.6] x
 * [-3, 3], yaw uniform, pitch within 10 degrees, facing up; sliver s is triangle s; the
 * ground last. */
static inline void pn_test_build_thin(pn_test_scene *s)
{
    const double half_len = 1.0, half_w = 0.001, max_pitch = 10.0 * PN_TEST_PI / 180.0;
    const uint32_t seed = 0x7411u;
    uint32_t i;
    pn_test_mesh *m = &s->mesh;
    for (i = 0; i < 2000u; i++) {
        uint32_t c = i * 8u, a0, a1, a2;
        double px = -3.0 + 6.0 * pn_test_rand01(seed, c + 0u);
        double py = 1.0 + 0.6 * pn_test_rand01(seed, c + 1u);
        double pz = -3.0 + 6.0 * pn_test_rand01(seed, c + 2u);
        double yaw = 2.0 * PN_TEST_PI * pn_test_rand01(seed, c + 3u);
        double pitch = max_pitch * (2.0 * pn_test_rand01(seed, c + 4u) - 1.0);
        double d[3], w[3];
        d[0] = cos(yaw) * cos(pitch);
        d[1] = sin(pitch);
        d[2] = sin(yaw) * cos(pitch);
        w[0] = -sin(yaw);
        w[1] = 0.0;
        w[2] = cos(yaw);
        a0 = pn_test_vertex(m, px - half_len * d[0] - half_w * w[0], py - half_len * d[1],
                            pz - half_len * d[2] - half_w * w[2]);
        a1 = pn_test_vertex(m, px - half_len * d[0] + half_w * w[0], py - half_len * d[1],
                            pz - half_len * d[2] + half_w * w[2]);
        a2 = pn_test_vertex(m, px + half_len * d[0], py + half_len * d[1], pz + half_len * d[2]);
        pn_test_tri(m, a0, a1, a2);
    }
    pn_test_ground(m, 0.0, 0.0, 0.0, 6.0);
    pn_test_view(s, 0.0f, 12.0f, 13.0f, -0.5f, 52.0f, 6.0f, 0.25f);
}

/* room's chairs: the back toward axis (ax, az); four legs 0.04 square and 0.45 high. */
static inline void pn_test_chair_legs(pn_test_mesh *m, double cx, double cz, double ax, double az)
{
    static const double legs[4][2] = {{-0.17, -0.17}, {-0.17, 0.17}, {0.1, -0.17}, {0.1, 0.17}};
    double px = -az, pz = ax;
    int i;
    for (i = 0; i < 4; i++) {
        double x = cx + legs[i][0] * ax + legs[i][1] * px, z = cz + legs[i][0] * az + legs[i][1] * pz;
        pn_test_block(m, x - 0.02, 0.0, z - 0.02, x + 0.02, 0.45, z + 0.02);
    }
}

/* Point i (0..10) of a chair shell's profile in the chair's (back, y) plane and its unit
 * normal: the flat seat (4 quads), a bend of radius 0.08 (3), the back leaning back (3). */
static inline void pn_test_chair_profile(uint32_t i, double p[2], double n[2])
{
    const double R = 0.08;
    if (i <= 4u) {
        p[0] = -0.21 + 0.0825 * (double)i;
        p[1] = 0.46;
        n[0] = 0.0;
        n[1] = 1.0;
    } else if (i <= 7u) {
        double a = (double)(i - 4u) * (PN_TEST_PI / 6.0);
        p[0] = 0.12 + R * sin(a);
        p[1] = 0.46 + R - R * cos(a);
        n[0] = -sin(a);
        n[1] = cos(a);
    } else {
        double f = (double)(i - 7u) / 3.0, l = sqrt(0.03 * 0.03 + 0.41 * 0.41);
        p[0] = 0.2 + 0.03 * f;
        p[1] = 0.54 + 0.41 * f;
        n[0] = -0.41 / l;
        n[1] = 0.03 / l;
    }
}

/* A chair's seat and back: one open dished sheet of 10 x 8 quads, 0.42 wide (99 vertices,
 * 160 triangles), facing the sitter. */
static inline void pn_test_chair_shell(pn_test_mesh *m, double cx, double cz, double ax, double az)
{
    const double px = -az, pz = ax, half = 0.21, dish = 0.02;
    const uint32_t along = 10u, across = 8u;
    uint32_t base = m->vertex_count, i, j;
    for (i = 0; i <= along; i++) {
        double p[2], n[2];
        pn_test_chair_profile(i, p, n);
        for (j = 0; j <= across; j++) {
            double c = -half + 2.0 * half * (double)j / (double)across;
            double d = dish * (1.0 - (c / half) * (c / half));
            double bb = p[0] - d * n[0], y = p[1] - d * n[1];
            pn_test_vertex(m, cx + bb * ax + c * px, y, cz + bb * az + c * pz);
        }
    }
    for (i = 0; i < along; i++) {
        double p0[2], n0[2], p1[2], n1[2], dir[3];
        pn_test_chair_profile(i, p0, n0);
        pn_test_chair_profile(i + 1u, p1, n1);
        dir[0] = (n0[0] + n1[0]) * ax;
        dir[1] = n0[1] + n1[1];
        dir[2] = (n0[0] + n1[0]) * az;
        for (j = 0; j < across; j++) {
            uint32_t v00 = base + i * (across + 1u) + j, v10 = v00 + across + 1u;
            pn_test_quad_toward(m, v00, v10, v10 + 1u, v00 + 1u, dir);
        }
    }
}

/* room: a closed 6 x 3 x 6 interior under a 1 x 1 ceiling panel 1/16 below the ceiling: a
 * table, six chairs (legs, then open shells), a bookcase of hashed books, an open stair
 * with balusters, stringer and handrail, three spheres; then the shell (ceiling and walls,
 * wound inward) and the floor (the receivers) last. 4674 triangles. */
static inline void pn_test_build_room(pn_test_scene *s)
{
    static const double chairs[6][4] = {{0.4, 0.85, 0, 1},   {-0.4, 0.85, 0, 1}, {0.4, -0.85, 0, -1},
                                        {-0.4, -0.85, 0, -1}, {1.15, 0, 1, 0},   {-1.15, 0, -1, 0}};
    static const double shell_lo[3] = {-3.0, 0.0, -3.0}, shell_hi[3] = {3.0, 3.0, 3.0};
    const double rise = 2.0 / 3.0; /* the stair: 0.2 up per 0.3 toward -z */
    const uint32_t books = 14u, seed = 0x600du;
    pn_test_mesh *m = &s->mesh;
    int i, j;
    pn_test_block(m, -0.8, 0.72, -0.5, 0.8, 0.76, 0.5);
    for (i = 0; i < 4; i++) {
        double x = (i & 1) ? 0.71 : -0.71, z = (i & 2) ? 0.41 : -0.41;
        pn_test_block(m, x - 0.03, 0.0, z - 0.03, x + 0.03, 0.72, z + 0.03);
    }
    for (i = 0; i < 6; i++) pn_test_chair_legs(m, chairs[i][0], chairs[i][1], chairs[i][2], chairs[i][3]);
    pn_test_block(m, -1.6, 0.0, -2.98, -1.57, 2.09, -2.63);
    pn_test_block(m, 0.57, 0.0, -2.98, 0.6, 2.09, -2.63);
    for (i = 0; i < 5; i++) pn_test_block(m, -1.57, 0.06 + 0.5 * i, -2.98, 0.57, 0.09 + 0.5 * i, -2.63);
    for (i = 0; i < 4; i++) {
        double x = -1.55, y = 0.09 + 0.5 * i;
        for (j = 0; j < (int)books; j++) {
            uint32_t c = (uint32_t)(i * (int)books + j) * 4u;
            double w = 0.04 + 0.05 * pn_test_rand01(seed, c);
            double h = 0.2 + 0.12 * pn_test_rand01(seed, c + 1u);
            double d = 0.2 + 0.1 * pn_test_rand01(seed, c + 2u);
            pn_test_block(m, x, y, -2.96, x + w, y + h, -2.96 + d);
            x += w + 0.008;
        }
    }
    for (i = 0; i < 8; i++) {
        double z1 = 0.6 - 0.3 * i, top = 0.2 * (i + 1);
        pn_test_block(m, -2.98, top - 0.04, z1 - 0.3, -2.1, top, z1);
        for (j = 0; j < 2; j++) {
            double z = z1 - 0.075 - 0.15 * j;
            pn_test_block(m, -2.16, top, z - 0.015, -2.13, rise * (0.6 - z) + 1.02, z + 0.015);
        }
    }
    {
        const double lo[3] = {-2.1, 0.0, -1.8}, hi[3] = {-2.06, 0.25, 0.6};
        const double rlo[3] = {-2.165, rise * 0.075 + 1.0, -1.725}, rhi[3] = {-2.125, rise * 0.075 + 1.05, 0.525};
        pn_test_box_ex(m, lo, hi, rise, 0);
        pn_test_box_ex(m, rlo, rhi, rise, 0);
    }
    for (i = 0; i < 6; i++) pn_test_chair_shell(m, chairs[i][0], chairs[i][1], chairs[i][2], chairs[i][3]);
    pn_test_sphere(m, 0.35, 0.96, -0.1, 0.2);
    pn_test_sphere(m, -0.5, 2.24, -2.8, 0.15);
    pn_test_sphere(m, -1.5, 0.25, 0.9, 0.25);
    pn_test_box_ex(m, shell_lo, shell_hi, 0.0, 1);
    pn_test_ground(m, 0.0, 0.0, 0.0, 3.0);
    pn_test_view(s, 2.6f, 1.8f, 2.6f, 0.6f, 56.0f, 2.9375f, 0.5f);
    pn_test_set3(s->camera.target, -0.85f, 0.6f, -0.95f);
}

/* Names pn_test_scene_load knows (NULL-terminated). */
static const char *const pn_test_scene_names[] = {"square", "spheres", "elongated-cube", "thin", "room", NULL};

/* Builds built-in scene `name` with its view, light, diagonal and eps. 0 on success; else
 * a message on stderr and *s empty. */
static inline int pn_test_scene_load(pn_test_scene *s, const char *name)
{
    memset(s, 0, sizeof(*s));
    if (strcmp(name, "square") == 0) pn_test_build_square(s);
    else if (strcmp(name, "spheres") == 0) pn_test_build_spheres(s);
    else if (strcmp(name, "elongated-cube") == 0) pn_test_build_elongated_cube(s);
    else if (strcmp(name, "thin") == 0) pn_test_build_thin(s);
    else if (strcmp(name, "room") == 0) pn_test_build_room(s);
    else {
        fprintf(stderr, "pn_test_scene_load: no test scene '%s' (tests/pn_test_scene.h)\n", name);
        return 1;
    }
    if (s->mesh.failed) {
        fprintf(stderr, "pn_test_scene_load: %s: out of memory\n", name);
        pn_test_mesh_free(&s->mesh);
        return 1;
    }
    snprintf(s->name, sizeof(s->name), "%s", name);
    pn_test_mesh_update_bbox(&s->mesh);
    s->diag = pn_test_mesh_diag(&s->mesh);
    s->eps = 1e-4f * s->diag;
    return 0;
}

static inline void pn_test_scene_free(pn_test_scene *s)
{
    pn_test_mesh_free(&s->mesh);
    memset(s, 0, sizeof(*s));
}

/* pn_scene_set with the scene's mesh, then pn_scene_set_receivers with its receiver range. */
static inline pn_status pn_test_scene_upload(pn_context *ctx, const pn_test_scene *s)
{
    pn_status st = pn_scene_set(ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count);
    if (st != PN_OK) return st;
    return pn_scene_set_receivers(ctx, s->mesh.receiver_first, s->mesh.receiver_count);
}

/* ---- A context on the heap, through the public API ----------------------------------------- */

typedef struct pn_test_host {
    void *memory;
    size_t bytes;
    pn_context *ctx;
} pn_test_host;

/* Sizes (pn_arena_size), allocates and initializes (pn_init) a context for *limits; the
 * library's own serial loop, no clock. 0 on success; else a message on stderr, *h empty. */
static inline int pn_test_open_limits(pn_test_host *h, const pn_limits *limits)
{
    pn_status st;
    memset(h, 0, sizeof(*h));
    st = pn_arena_size(limits, &h->bytes);
    if (st != PN_OK) {
        fprintf(stderr, "pn_arena_size: %s\n", pn_status_str(st));
        return 1;
    }
    h->memory = malloc(h->bytes);
    if (!h->memory) {
        fprintf(stderr, "cannot allocate %zu bytes of arena\n", h->bytes);
        return 1;
    }
    st = pn_init(&h->ctx, h->memory, h->bytes, limits);
    if (st != PN_OK) {
        fprintf(stderr, "pn_init: %s\n", pn_status_str(st));
        free(h->memory);
        memset(h, 0, sizeof(*h));
        return 1;
    }
    return 0;
}

static inline int pn_test_open(pn_test_host *h, uint32_t max_triangles, uint32_t max_w, uint32_t max_h)
{
    pn_limits lim;
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = max_triangles;
    lim.max_width = max_w;
    lim.max_height = max_h;
    return pn_test_open_limits(h, &lim);
}

static inline void pn_test_close(pn_test_host *h)
{
    free(h->memory);
    memset(h, 0, sizeof(*h));
}

/* ---- Serial schedules for pn_set_parallel_for ---------------------------------------------- *
 * The library may have its ranges run in any order (penumbra.h, "Work distribution"); these
 * run them on the calling thread in orders unlike its own loop (one call over [0, count)),
 * so a result that depends on the order shows without threads. */
typedef enum pn_test_order {
    PN_TEST_ITEMS_FORWARD,  /* one item a call, 0 up */
    PN_TEST_ITEMS_BACKWARD, /* one item a call, count - 1 down */
    PN_TEST_ITEMS_SHUFFLED, /* one item a call, in a fixed permutation (a stride coprime to count) */
    PN_TEST_CHUNKS_UNEVEN   /* ranges of 1, 2, 3, ... items taken from the end */
} pn_test_order;

typedef struct pn_test_schedule {
    pn_test_order order;
    uint32_t jobs;   /* parallel-for calls so far */
    uint64_t ranges; /* task calls so far */
} pn_test_schedule;

static inline uint32_t pn_test_gcd(uint32_t a, uint32_t b)
{
    while (b) {
        uint32_t t = a % b;
        a = b;
        b = t;
    }
    return a;
}

/* Matches pn_parallel_for_fn; user points to a pn_test_schedule. */
static inline void pn_test_parallel_for(void *user, uint32_t count, pn_task_fn fn, void *task)
{
    pn_test_schedule *sc = (pn_test_schedule *)user;
    uint32_t i;
    sc->jobs++;
    if (sc->order == PN_TEST_ITEMS_FORWARD) {
        for (i = 0; i < count; i++) fn(task, i, i + 1u);
        sc->ranges += count;
    } else if (sc->order == PN_TEST_ITEMS_BACKWARD) {
        for (i = count; i > 0u; i--) fn(task, i - 1u, i);
        sc->ranges += count;
    } else if (sc->order == PN_TEST_ITEMS_SHUFFLED) {
        uint32_t step = count / 2u + 1u;
        while (count > 1u && pn_test_gcd(step, count) != 1u) step++;
        for (i = 0; i < count; i++) {
            uint32_t it = (uint32_t)(((uint64_t)i * step + 7u) % count);
            fn(task, it, it + 1u);
        }
        sc->ranges += count;
    } else {
        uint32_t end = count, n = 1u;
        while (end > 0u) {
            uint32_t begin = end > n ? end - n : 0u;
            fn(task, begin, end);
            sc->ranges++;
            end = begin;
            n++;
        }
    }
}

#endif
