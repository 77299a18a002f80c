/* pn_scenes.c - built-in procedural scenes (see pn_scenes.h).
 *
 * Layout of every mesh: the scene's own geometry first, in the order described at each
 * builder, then the ground (two triangles, four vertices) last. Tests rely on it. The
 * receiver range (pn_mesh.receiver_*) ends at the last triangle: the ground, and for
 * closed-box the box's inner floor just before it (pn_sc_receivers_next before them).
 *
 * Determinism: all randomness comes from an integer hash (lowbias32) of (seed, counter);
 * positions are computed in double and rounded to float once. The sphere and sliver
 * builders call libm sin/cos (spheres, thin, room), so bit-exact positions across
 * different libms are not promised (glibc's are correctly rounded in practice); the square
 * and box scenes use only exactly representable constants. */
#include "pn_scenes.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PN_SC_PI 3.14159265358979323846

/* ---- Errors and the mesh builder ------------------------------------------------------ */


/* Exact-capacity builder: every scene knows its vertex and triangle counts up front, so
 * one allocation per array and no realloc. The counters are checked against the
 * capacity on every push; a mismatch is a bug in this file and fails the build call. */
typedef struct pn_sc_builder {
    float *pos;
    uint32_t *idx;
    uint32_t nv, nt, cap_v, cap_t;
    uint32_t recv_first, recv_count; /* the mesh's receiver range (pn_mesh.h) */
    int overflow;
} pn_sc_builder;

static int pn_sc_builder_init(pn_sc_builder *b, uint32_t cap_v, uint32_t cap_t)
{
    memset(b, 0, sizeof(*b));
    b->pos = (float *)malloc((size_t)cap_v * 3u * sizeof(float));
    b->idx = (uint32_t *)malloc((size_t)cap_t * 3u * sizeof(uint32_t));
    b->cap_v = cap_v;
    b->cap_t = cap_t;
    if (b->pos == NULL || b->idx == NULL) {
        free(b->pos);
        free(b->idx);
        memset(b, 0, sizeof(*b));
        return 1;
    }
    return 0;
}

static uint32_t pn_sc_vertex(pn_sc_builder *b, double x, double y, double z)
{
    uint32_t v = b->nv;
    if (v >= b->cap_v) {
        b->overflow = 1;
        return 0;
    }
    b->pos[(size_t)v * 3u + 0u] = (float)x;
    b->pos[(size_t)v * 3u + 1u] = (float)y;
    b->pos[(size_t)v * 3u + 2u] = (float)z;
    b->nv++;
    return v;
}

/* (a, b, c) counter-clockwise seen from the side the normal (b - a) x (c - a) points to. */
static void pn_sc_tri(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2)
{
    uint32_t t = b->nt;
    if (t >= b->cap_t) {
        b->overflow = 1;
        return;
    }
    b->idx[(size_t)t * 3u + 0u] = a;
    b->idx[(size_t)t * 3u + 1u] = c1;
    b->idx[(size_t)t * 3u + 2u] = c2;
    b->nt++;
}

/* The next `count` triangles pushed are the scene's receivers (pn_mesh.receiver_*). */
static void pn_sc_receivers_next(pn_sc_builder *b, uint32_t count)
{
    b->recv_first = b->nt;
    b->recv_count = count;
}

/* Quad a-b-c-d in CCW order seen from outside, split along a-c. */
static void pn_sc_quad(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2, uint32_t d)
{
    pn_sc_tri(b, a, c1, c2);
    pn_sc_tri(b, a, c2, d);
}

/* Horizontal square |x - cx|, |z - cz| <= h at height y, facing +y. Two triangles split
 * along the (-x,-z)-(+x,+z) diagonal. */
static void pn_sc_hsquare(pn_sc_builder *b, double cx, double y, double cz, double h)
{
    uint32_t v0 = pn_sc_vertex(b, cx - h, y, cz - h);
    uint32_t v1 = pn_sc_vertex(b, cx - h, y, cz + h);
    uint32_t v2 = pn_sc_vertex(b, cx + h, y, cz + h);
    uint32_t v3 = pn_sc_vertex(b, cx + h, y, cz - h);
    /* (v1 - v0) x (v2 - v0) = (0,0,2h) x (2h,0,2h) = (0, 4h^2, 0): faces +y. */
    pn_sc_quad(b, v0, v1, v2, v3);
}

/* Closed axis-aligned box [lo, hi], 8 shared vertices, 12 triangles, outward normals.
 * Corner c has x = hi iff bit 0, y = hi iff bit 1, z = hi iff bit 2. rise != 0 shears it
 * into a ramp: every corner's y is raised by rise * (hi[2] - z), i.e. the box climbs
 * toward -z (a shear has determinant 1: the winding stays outward). inside != 0 builds a
 * room's shell instead: the faces wound inward and no -y face (the ground is the floor). */
static void pn_sc_box_ex(pn_sc_builder *b, const double lo[3], const double hi[3], double rise,
                         int inside)
{
    /* Each face's corners CCW seen from outside; checked by (p1-p0) x (p2-p0) = outward. */
    static const uint8_t faces[6][4] = {
        {0, 4, 6, 2}, /* -x */
        {1, 3, 7, 5}, /* +x */
        {0, 1, 5, 4}, /* -y */
        {2, 6, 7, 3}, /* +y */
        {0, 2, 3, 1}, /* -z */
        {4, 5, 7, 6}, /* +z */
    };
    uint32_t base = b->nv;
    int c, f;
    for (c = 0; c < 8; c++) {
        double z = (c & 4) ? hi[2] : lo[2], y = (c & 2) ? hi[1] : lo[1];
        pn_sc_vertex(b, (c & 1) ? hi[0] : lo[0], y + rise * (hi[2] - z), z);
    }
    for (f = 0; f < 6; f++) {
        const uint8_t *q = faces[f];
        if (!inside) {
            pn_sc_quad(b, base + q[0], base + q[1], base + q[2], base + q[3]);
        } else if (f != 2) {
            pn_sc_quad(b, base + q[0], base + q[3], base + q[2], base + q[1]);
        }
    }
}

static void pn_sc_box(pn_sc_builder *b, const double lo[3], const double hi[3])
{
    pn_sc_box_ex(b, lo, hi, 0.0, 0);
}

/* ---- The 762-triangle sphere ---------------------------------------------------------- *
 *
 * Forest et al. 2006 (section 5.2) discretize each sphere "by 762 triangles". A closed
 * genus-0 triangle mesh has V - E + F = 2 with E = 3F/2, so F = 762 needs V = 383, which is
 * prime. The usual latitude-longitude sphere (S slices, R - 1 rings of S vertices, two
 * pole fans) has V = S(R - 1) + 2, i.e. S(R - 1) = 381 = 3 * 127: only 3 or 127 slices.
 * Icospheres (20 * 4^n), subdivided octahedra (8n^2) and cube spheres (12n^2) miss 762
 * too. So: two poles and 17 latitude rings at polar angles theta_i = (i + 1) * 10 degrees,
 * ring i holding n_i vertices with n_i proportional to sin(theta_i) (largest-remainder
 * apportionment of 381, kept symmetric about the equator). That keeps the vertex spacing
 * along a ring (about 0.19 rad at the equator) close to the spacing between rings
 * (10 degrees = 0.175 rad) everywhere, so triangles are near-equilateral instead of
 * collapsing into slivers at the poles. Adjacent rings with n_a and n_b vertices are
 * joined by a "zipper" strip of n_a + n_b triangles; each pole is a fan of n triangles.
 * Total F = n_0 + n_16 + sum over the 16 strips of (n_i + n_{i+1}) = 2 * 381 = 762. */
#define PN_SC_SPHERE_RINGS 17
#define PN_SC_SPHERE_VERTS 383u
#define PN_SC_SPHERE_TRIS 762u

static const uint32_t pn_sc_ring_count[PN_SC_SPHERE_RINGS] = {
    6, 11, 17, 21, 26, 29, 31, 33, 33, 33, 31, 29, 26, 21, 17, 11, 6,
};

/* Odd rings are rotated by half a step so that no meridian of aligned vertices forms. */
static int pn_sc_ring_offset2(int ring) { return ring & 1; } /* offset in half-steps */

/* Vertices: north pole, rings 0..16 (ring i's vertex j at azimuth
 * 2*pi*(j + offset_i/2)/n_i), south pole. Triangles in order: north fan, strips, south fan. */
static void pn_sc_sphere(pn_sc_builder *b, double cx, double cy, double cz, double r)
{
    uint32_t ring_base[PN_SC_SPHERE_RINGS];
    uint32_t north, south, j;
    int i;

    north = pn_sc_vertex(b, cx, cy + r, cz);
    for (i = 0; i < PN_SC_SPHERE_RINGS; i++) {
        uint32_t n = pn_sc_ring_count[i];
        double theta = (double)(i + 1) * PN_SC_PI / (double)(PN_SC_SPHERE_RINGS + 1);
        double st = sin(theta), ct = cos(theta);
        ring_base[i] = b->nv;
        for (j = 0; j < n; j++) {
            double phi = 2.0 * PN_SC_PI * ((double)j + 0.5 * pn_sc_ring_offset2(i)) / (double)n;
            pn_sc_vertex(b, cx + r * st * cos(phi), cy + r * ct, cz + r * st * sin(phi));
        }
    }
    south = pn_sc_vertex(b, cx, cy - r, cz);

    /* Orientation: with x = cos(phi), z = sin(phi), azimuth grows counter-clockwise seen
     * from -y, so for an upper vertex A, the next one along its ring A' and a lower vertex
     * B the outward triangle is (A, A', B), and for lower B, B' it is (A, B', B). */
    {
        uint32_t n = pn_sc_ring_count[0];
        for (j = 0; j < n; j++) {
            pn_sc_tri(b, north, ring_base[0] + (j + 1u) % n, ring_base[0] + j);
        }
    }
    for (i = 0; i + 1 < PN_SC_SPHERE_RINGS; i++) {
        uint32_t na = pn_sc_ring_count[i], nb = pn_sc_ring_count[i + 1];
        uint32_t a0 = ring_base[i], b0 = ring_base[i + 1];
        uint32_t ia = 0, ib = 0;
        /* Azimuths in units of 2*pi/(2*na*nb): integer comparisons, no float ties. */
        uint64_t oa = (uint64_t)pn_sc_ring_offset2(i), ob = (uint64_t)pn_sc_ring_offset2(i + 1);
        while (ia < na || ib < nb) {
            int advance_a;
            if (ia == na) {
                advance_a = 0;
            } else if (ib == nb) {
                advance_a = 1;
            } else {
                uint64_t next_a = (2u * (uint64_t)(ia + 1u) + oa) * nb;
                uint64_t next_b = (2u * (uint64_t)(ib + 1u) + ob) * na;
                advance_a = next_a <= next_b;
            }
            if (advance_a) {
                pn_sc_tri(b, a0 + ia % na, a0 + (ia + 1u) % na, b0 + ib % nb);
                ia++;
            } else {
                pn_sc_tri(b, a0 + ia % na, b0 + (ib + 1u) % nb, b0 + ib % nb);
                ib++;
            }
        }
    }
    {
        uint32_t n = pn_sc_ring_count[PN_SC_SPHERE_RINGS - 1];
        uint32_t a0 = ring_base[PN_SC_SPHERE_RINGS - 1];
        for (j = 0; j < n; j++) {
            pn_sc_tri(b, a0 + j, a0 + (j + 1u) % n, south);
        }
    }
}

/* ---- Views ---------------------------------------------------------------------------- */

static void pn_sc_set3(float d[3], float x, float y, float z)
{
    d[0] = x;
    d[1] = y;
    d[2] = z;
}

/* Square light of half-size h centred at (0, y, 0): u = +x, v = +z, u x v = -y. */
static void pn_sc_view(pn_scene_view *v, float ex, float ey, float ez, float ty, float fov,
                       float light_y, float light_half)
{
    pn_sc_set3(v->eye, ex, ey, ez);
    pn_sc_set3(v->target, 0.0f, ty, 0.0f);
    pn_sc_set3(v->up, 0.0f, 1.0f, 0.0f);
    v->fov_deg = fov;
    pn_sc_set3(v->light_center, 0.0f, light_y, 0.0f);
    pn_sc_set3(v->light_u, light_half, 0.0f, 0.0f);
    pn_sc_set3(v->light_v, 0.0f, 0.0f, light_half);
}

/* ---- Scenes --------------------------------------------------------------------------- */

void pn_square_scene_params(pn_square_params *p)
{
    /* Occluder at half the light height: seen from the receiver its projection onto the
     * light plane is twice its size, so the umbra is |x|, |z| <= 2*0.5 - 0.5 = 0.5 and the
     * penumbra reaches |x| or |z| = 2*0.5 + 0.5 = 1.5. All values exact in float. */
    p->light_y = 4.0f;
    p->light_half = 0.5f;
    p->occluder_y = 2.0f;
    p->occluder_half = 0.5f;
    p->ground_y = 0.0f;
    p->ground_half = 4.0f;
}

/* Triangles: occluder (2), ground (2). */
static int pn_sc_build_square(pn_sc_builder *b, pn_scene_view *v)
{
    pn_square_params p;
    pn_square_scene_params(&p);
    if (pn_sc_builder_init(b, 8u, 4u) != 0) {
        return 1;
    }
    pn_sc_hsquare(b, 0.0, p.occluder_y, 0.0, p.occluder_half);
    pn_sc_receivers_next(b, 2u);
    pn_sc_hsquare(b, 0.0, p.ground_y, 0.0, p.ground_half);
    /* From (0, 9, 9) the occluder hides the ground at z in about [-3.2, -1.9], beyond the
     * whole shadow (|x|, |z| < 1.5); the whole ground is in frame. */
    pn_sc_view(v, 0.0f, 9.0f, 9.0f, -0.5f, 50.0f, p.light_y, p.light_half);
    return 0;
}

/* 9 x 9 spheres, radius 0.4, on a unit grid at height 1.5 (centres x, z in -4..4): the gap
 * between neighbours (0.2) is far smaller than the penumbra width the 4 x 4 light casts
 * at that height (about 2 * 2 * 1.1/6.5 = 0.7 at the sphere bottoms), so every shadow
 * overlaps its neighbours' penumbrae - the blending case of Forest et al. 2006, Fig. 1.
 * Triangles: sphere s (row-major, z outer, x inner) is [762 s, 762 (s + 1)); ground last. */
static int pn_sc_build_spheres(pn_sc_builder *b, pn_scene_view *v)
{
    int ix, iz;
    if (pn_sc_builder_init(b, 81u * PN_SC_SPHERE_VERTS + 4u, 81u * PN_SC_SPHERE_TRIS + 2u) != 0) {
        return 1;
    }
    for (iz = 0; iz < 9; iz++) {
        for (ix = 0; ix < 9; ix++) {
            pn_sc_sphere(b, (double)(ix - 4), 1.5, (double)(iz - 4), 0.4);
        }
    }
    pn_sc_receivers_next(b, 2u);
    pn_sc_hsquare(b, 0.0, 0.0, 0.0, 7.0);
    pn_sc_view(v, 0.0f, 14.0f, 15.0f, -0.5f, 52.0f, 8.0f, 2.0f);
    return 0;
}

/* Curtis 2009, Monte Carlo shadow maps, Fig. 4.2 and section 4: "the darkening of the
 * shadow directly beneath the elongated cube ... is a difficult case for other shadowing
 * algorithms, since the shadow is a result of the object's extent perpendicular to the
 * light, which cannot be determined with a single shadow map" (and section 3.3: the far
 * depth layer is there "to measure the sizes of objects"). The paper gives no dimensions,
 * so: a box long along the light's axis (0.6 x 3 x 0.6, y in [1, 4]) floating over the
 * ground, under a 2 x 2 light at y = 7 centred above it. From the ground point beneath
 * it, the top face alone (what the near depth map sees) projects to a 1.05 x 1.05 square
 * on the light plane, hiding about 28% of the light, but the bottom face projects to
 * 8.4 x 8.4: the true answer is full umbra, produced entirely by the long side walls.
 * Triangles: box (12, 8 shared vertices), ground (2). */
static int pn_sc_build_elongated_cube(pn_sc_builder *b, pn_scene_view *v)
{
    static const double lo[3] = {-0.3, 1.0, -0.3};
    static const double hi[3] = {0.3, 4.0, 0.3};
    if (pn_sc_builder_init(b, 12u, 14u) != 0) {
        return 1;
    }
    pn_sc_box(b, lo, hi);
    pn_sc_receivers_next(b, 2u);
    pn_sc_hsquare(b, 0.0, 0.0, 0.0, 5.0);
    /* Low enough (about 18 degrees above the ground at the box) that the line of sight to
     * the ground point beneath the box passes under it, through the 1-unit gap. */
    pn_sc_view(v, 0.0f, 5.0f, 15.0f, 1.0f, 52.0f, 7.0f, 1.0f);
    return 0;
}

/* lowbias32 (C. Wellons, "Prospecting for hash functions"): a full-avalanche integer
 * hash; the generator is hash(seed ^ hash(counter)), stateless and order-independent. */
static uint32_t pn_sc_hash(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/* Uniform in [0, 1) with 24 bits, exact in float and double. */
static double pn_sc_rand01(uint32_t seed, uint32_t counter)
{
    return (double)(pn_sc_hash(seed ^ pn_sc_hash(counter)) >> 8) * (1.0 / 16777216.0);
}

#define PN_SC_THIN_COUNT 2000u
#define PN_SC_THIN_SEED 0x7411u

/* 2000 needles: apex at one end, a base 0.002 wide at the other, 2 long; centres uniform
 * in x, z in [-3, 3], y in [1, 1.6]; yaw uniform, pitch within +-10 degrees; the width
 * direction is horizontal, so each sliver's shadow is as thin as it can be. A 512-texel
 * shadow map over this 10-unit scene has texels of 0.02, ten times a sliver's width.
 * Triangles: sliver s is triangle s (vertices 3s..3s+2, facing up); ground last. */
static int pn_sc_build_thin(pn_sc_builder *b, pn_scene_view *v)
{
    const double half_len = 1.0, half_w = 0.001;
    const double max_pitch = 10.0 * PN_SC_PI / 180.0;
    uint32_t s;
    if (pn_sc_builder_init(b, 3u * PN_SC_THIN_COUNT + 4u, PN_SC_THIN_COUNT + 2u) != 0) {
        return 1;
    }
    for (s = 0; s < PN_SC_THIN_COUNT; s++) {
        uint32_t c = s * 8u;
        double px = -3.0 + 6.0 * pn_sc_rand01(PN_SC_THIN_SEED, c + 0u);
        double py = 1.0 + 0.6 * pn_sc_rand01(PN_SC_THIN_SEED, c + 1u);
        double pz = -3.0 + 6.0 * pn_sc_rand01(PN_SC_THIN_SEED, c + 2u);
        double yaw = 2.0 * PN_SC_PI * pn_sc_rand01(PN_SC_THIN_SEED, c + 3u);
        double pitch = max_pitch * (2.0 * pn_sc_rand01(PN_SC_THIN_SEED, c + 4u) - 1.0);
        double d[3], w[3];
        uint32_t a0, a1, a2;
        d[0] = cos(yaw) * cos(pitch);
        d[1] = sin(pitch);
        d[2] = sin(yaw) * cos(pitch);
        w[0] = -sin(yaw);
        w[1] = 0.0;
        w[2] = cos(yaw);
        /* Base corners (centre - L d -+ W w) and apex (centre + L d). The normal
         * (a1 - a0) x (a2 - a0) = (2W w) x (2L d + W w) = 4WL (w x d), whose y component
         * is 4WL cos(pitch) > 0: every sliver faces up. */
        a0 = pn_sc_vertex(b, px - half_len * d[0] - half_w * w[0], py - half_len * d[1],
                          pz - half_len * d[2] - half_w * w[2]);
        a1 = pn_sc_vertex(b, px - half_len * d[0] + half_w * w[0], py - half_len * d[1],
                          pz - half_len * d[2] + half_w * w[2]);
        a2 = pn_sc_vertex(b, px + half_len * d[0], py + half_len * d[1], pz + half_len * d[2]);
        pn_sc_tri(b, a0, a1, a2);
    }
    pn_sc_receivers_next(b, 2u);
    pn_sc_hsquare(b, 0.0, 0.0, 0.0, 6.0);
    pn_sc_view(v, 0.0f, 12.0f, 13.0f, -0.5f, 52.0f, 6.0f, 0.25f);
    return 0;
}

/* Axis-aligned box [x0, x1] x [y0, y1] x [z0, z1]. */
static void pn_sc_block(pn_sc_builder *b, double x0, double y0, double z0, double x1, double y1,
                        double z1)
{
    const double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
    pn_sc_box(b, lo, hi);
}

/* Chair at (cx, cz) whose back is toward the axis direction (ax, az) (one of them +-1, the
 * other 0): seat, 4 legs, 2 back posts, back panel. Parts as {offset toward the back,
 * offset across, half extent toward the back, half extent across, y0, y1}. */
static void pn_sc_chair(pn_sc_builder *b, double cx, double cz, double ax, double az)
{
    static const double parts[8][6] = {
        {0.0, 0.0, 0.21, 0.21, 0.43, 0.47},     {0.18, 0.18, 0.02, 0.02, 0.0, 0.43},
        {0.18, -0.18, 0.02, 0.02, 0.0, 0.43},   {-0.18, 0.18, 0.02, 0.02, 0.0, 0.43},
        {-0.18, -0.18, 0.02, 0.02, 0.0, 0.43},  {0.18, 0.18, 0.02, 0.02, 0.47, 0.95},
        {0.18, -0.18, 0.02, 0.02, 0.47, 0.95},  {0.18, 0.0, 0.015, 0.16, 0.68, 0.92},
    };
    double px = -az, pz = ax; /* across */
    int i;
    for (i = 0; i < 8; i++) {
        const double *q = parts[i];
        double x = cx + q[0] * ax + q[1] * px, z = cz + q[0] * az + q[1] * pz;
        double hx = fabs(ax) * q[2] + fabs(px) * q[3], hz = fabs(az) * q[2] + fabs(pz) * q[3];
        pn_sc_block(b, x - hx, q[4], z - hz, x + hx, q[5], z + hz);
    }
}

#define PN_SC_ROOM_BOOKS 14 /* per shelf, 4 shelves */
#define PN_SC_ROOM_STEPS 8
#define PN_SC_ROOM_SEED 0x600du
/* table 5, chairs 6 x 8, bookcase 7, books, stair: treads, stringer, 2 balusters a tread,
 * handrail */
#define PN_SC_ROOM_BOXES (5u + 48u + 7u + 4u * PN_SC_ROOM_BOOKS + 3u * PN_SC_ROOM_STEPS + 2u)

/* An interior: a closed 6 x 3 x 6 room (x, z in [-3, 3], y in [0, 3]) lit by a 1 x 1
 * ceiling panel hanging 1/16 below the ceiling, so the ceiling and the walls' top strip
 * lie behind the light (dark). Under the light a table with a globe lamp and six chairs;
 * a bookcase of four shelves of books along the back wall (z = -3) with a vase on top; an
 * open stair along the left wall (x = -3) with a stringer, a sloped handrail and two thin
 * balusters a tread; a ball on the floor. The furniture stands on the floor, 2 cm off the
 * walls (no face on a wall). Seen from the light and from the camera in the opposite
 * corner, occluders stand behind one another: globe over table over chairs over floor,
 * handrail and balusters over treads over treads, books between boards.
 * Triangles: furniture (boxes, then the three spheres), the shell (ceiling and four walls,
 * 10 triangles on 8 shared corners, wound inward), the floor (ground) last. */
static int pn_sc_build_room(pn_sc_builder *b, pn_scene_view *v)
{
    static const double chairs[6][4] = {{0.4, 0.85, 0, 1}, {-0.4, 0.85, 0, 1},
                                        {0.4, -0.85, 0, -1}, {-0.4, -0.85, 0, -1},
                                        {1.15, 0, 1, 0}, {-1.15, 0, -1, 0}};
    static const double shell_lo[3] = {-3.0, 0.0, -3.0}, shell_hi[3] = {3.0, 3.0, 3.0};
    const double rise = 2.0 / 3.0; /* stair: 0.2 up per 0.3 toward -z */
    int i, j;
    if (pn_sc_builder_init(b, PN_SC_ROOM_BOXES * 8u + 3u * PN_SC_SPHERE_VERTS + 12u,
                           PN_SC_ROOM_BOXES * 12u + 3u * PN_SC_SPHERE_TRIS + 12u) != 0) {
        return 1;
    }
    pn_sc_block(b, -0.8, 0.72, -0.5, 0.8, 0.76, 0.5);
    for (i = 0; i < 4; i++) {
        double x = (i & 1) ? 0.71 : -0.71, z = (i & 2) ? 0.41 : -0.41;
        pn_sc_block(b, x - 0.03, 0.0, z - 0.03, x + 0.03, 0.72, z + 0.03);
    }
    for (i = 0; i < 6; i++) {
        pn_sc_chair(b, chairs[i][0], chairs[i][1], chairs[i][2], chairs[i][3]);
    }
    /* Bookcase: two sides, five boards; books of hashed size standing on the lower four. */
    pn_sc_block(b, -1.6, 0.0, -2.98, -1.57, 2.09, -2.63);
    pn_sc_block(b, 0.57, 0.0, -2.98, 0.6, 2.09, -2.63);
    for (i = 0; i < 5; i++) {
        pn_sc_block(b, -1.57, 0.06 + 0.5 * i, -2.98, 0.57, 0.09 + 0.5 * i, -2.63);
    }
    for (i = 0; i < 4; i++) {
        double x = -1.55, y = 0.09 + 0.5 * i;
        for (j = 0; j < PN_SC_ROOM_BOOKS; j++) {
            uint32_t c = (uint32_t)(i * PN_SC_ROOM_BOOKS + j) * 4u;
            double w = 0.04 + 0.05 * pn_sc_rand01(PN_SC_ROOM_SEED, c);
            double h = 0.2 + 0.12 * pn_sc_rand01(PN_SC_ROOM_SEED, c + 1u);
            double d = 0.2 + 0.1 * pn_sc_rand01(PN_SC_ROOM_SEED, c + 2u);
            pn_sc_block(b, x, y, -2.96, x + w, y + h, -2.96 + d);
            x += w + 0.008;
        }
    }
    /* Stair from z = 0.6 up to z = -1.8: tread i's top at 0.2 (i + 1); stringer and handrail
     * are ramps, the handrail 0.9 above the line through the treads' centres. */
    for (i = 0; i < PN_SC_ROOM_STEPS; i++) {
        double z1 = 0.6 - 0.3 * i, top = 0.2 * (i + 1);
        pn_sc_block(b, -2.98, top - 0.04, z1 - 0.3, -2.1, top, z1);
        for (j = 0; j < 2; j++) {
            double z = z1 - 0.075 - 0.15 * j;
            pn_sc_block(b, -2.16, top, z - 0.015, -2.13, rise * (0.6 - z) + 1.02, z + 0.015);
        }
    }
    {
        const double lo[3] = {-2.1, 0.0, -1.8}, hi[3] = {-2.06, 0.25, 0.6};
        const double rlo[3] = {-2.165, rise * 0.075 + 1.0, -1.725};
        const double rhi[3] = {-2.125, rise * 0.075 + 1.05, 0.525};
        pn_sc_box_ex(b, lo, hi, rise, 0);
        pn_sc_box_ex(b, rlo, rhi, rise, 0);
    }
    pn_sc_sphere(b, 0.35, 0.96, -0.1, 0.2);
    pn_sc_sphere(b, -0.5, 2.24, -2.8, 0.15);
    pn_sc_sphere(b, -1.5, 0.25, 0.9, 0.25);
    pn_sc_box_ex(b, shell_lo, shell_hi, 0.0, 1);
    pn_sc_receivers_next(b, 2u);
    pn_sc_hsquare(b, 0.0, 0.0, 0.0, 3.0);
    /* From the front-right corner toward the back-left one: every furniture vertex in frame
     * (not the shell, which surrounds the eye). */
    pn_sc_view(v, 2.6f, 1.8f, 2.6f, 0.6f, 56.0f, 2.9375f, 0.5f);
    pn_sc_set3(v->target, -0.85f, 0.6f, -0.95f);
    return 0;
}

/* Quad a-b-c-d (a convex planar polygon in either winding), split along a-c, wound so
 * that its normal has a positive component along dir. */
static void pn_sc_quad_toward(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2, uint32_t d,
                              const double dir[3])
{
    double p[3][3], e1[3], e2[3], n[3];
    const uint32_t q[3] = {a, c1, c2};
    int i, k;
    if (b->overflow) {
        return;
    }
    for (i = 0; i < 3; i++) {
        for (k = 0; k < 3; k++) p[i][k] = (double)b->pos[(size_t)q[i] * 3u + (size_t)k];
    }
    for (k = 0; k < 3; k++) {
        e1[k] = p[1][k] - p[0][k];
        e2[k] = p[2][k] - p[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    if (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2] > 0.0) {
        pn_sc_quad(b, a, c1, c2, d);
    } else {
        pn_sc_quad(b, a, d, c2, c1);
    }
}

/* Four vertices at height y on the square |x|, |z| = h, in cyclic order around y. */
static void pn_sc_ring(pn_sc_builder *b, uint32_t out[4], double y, double h)
{
    static const double sx[4] = {-1.0, 1.0, 1.0, -1.0}, sz[4] = {-1.0, -1.0, 1.0, 1.0};
    int i;
    for (i = 0; i < 4; i++) out[i] = pn_sc_vertex(b, sx[i] * h, y, sz[i] * h);
}

/* The four side quads between two rings of pn_sc_ring (same cyclic order), each wound to
 * face away from the y axis (sign > 0) or toward it (sign < 0). */
static void pn_sc_ring_sides(pn_sc_builder *b, const uint32_t lo[4], const uint32_t hi[4],
                             double sign)
{
    int i;
    for (i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        const float *p = b->pos + (size_t)lo[i] * 3u, *q = b->pos + (size_t)lo[j] * 3u;
        double dir[3];
        dir[0] = sign * ((double)p[0] + (double)q[0]);
        dir[1] = 0.0;
        dir[2] = sign * ((double)p[2] + (double)q[2]);
        pn_sc_quad_toward(b, lo[i], lo[j], hi[j], hi[i], dir);
    }
}

/* The flat square annulus between two concentric rings at one height, facing +y (up > 0)
 * or -y: four trapezoids, eight triangles. */
static void pn_sc_ring_annulus(pn_sc_builder *b, const uint32_t outer[4], const uint32_t inner[4],
                               double up)
{
    const double dir[3] = {0.0, up, 0.0};
    int i;
    for (i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        pn_sc_quad_toward(b, outer[i], outer[j], inner[j], inner[i], dir);
    }
}

/* closed-box: light leaks of shadow maps. A hollow box, walls 0.25 thick, outer
 * [-2, 2] x [0.5, 3.5] x [-2, 2], cavity [-1.75, 1.75] x [0.75, 3.25] x [-1.75, 1.75],
 * floating 0.5 over the ground, with one 0.5 x 0.5 square hole (|x|, |z| <= 0.25) through
 * its top straight under the 1 x 1 light at y = 7.5. The box is a solid: one closed,
 * consistently wound surface (the outside, the hole's four walls, the cavity), every
 * normal pointing out of the material (into the cavity on the cavity's faces), so the
 * only light inside comes through the hole: a soft spot on the cavity floor around
 * (0, 0.75, 0), part of it shadowed by a 0.5 cube standing on the floor beside the centre
 * ([0.25, 0.75] x [0.75, 1.25] x [-0.5, 0]). Everything else inside is dark (visibility 0
 * in the exact algorithms); a lit pixel there is a leak. The eye is inside the cavity,
 * high in one corner, looking down at the floor: every pixel is the cavity's floor, its
 * walls or the cube.
 * Vertices: cube 8, cavity 8 (the floor's ring, then the ceiling's), the hole's rings at
 * the cavity ceiling (y = 3.25) and at the top (y = 3.5), the outside 8 (bottom ring, top
 * ring), the ground 4. Triangles: cube (12), the box surface without the cavity floor
 * (outside: sides 8, bottom 2, top 8; hole walls 8; cavity: walls 8, ceiling 8), the
 * cavity floor (2), the ground (2); the receivers are the cavity floor and the ground. */
static int pn_sc_build_closed_box(pn_sc_builder *b, pn_scene_view *v)
{
    static const double cube_lo[3] = {0.25, 0.75, -0.5}, cube_hi[3] = {0.75, 1.25, 0.0};
    static const double up[3] = {0.0, 1.0, 0.0}, down[3] = {0.0, -1.0, 0.0};
    uint32_t cav_lo[4], cav_hi[4], hole_lo[4], hole_hi[4], out_lo[4], out_hi[4];
    if (pn_sc_builder_init(b, 8u + 8u + 8u + 8u + 4u, 12u + 18u + 8u + 18u + 2u) != 0) {
        return 1;
    }
    pn_sc_box(b, cube_lo, cube_hi);
    pn_sc_ring(b, cav_lo, 0.75, 1.75);
    pn_sc_ring(b, cav_hi, 3.25, 1.75);
    pn_sc_ring(b, hole_lo, 3.25, 0.25);
    pn_sc_ring(b, hole_hi, 3.5, 0.25);
    pn_sc_ring(b, out_lo, 0.5, 2.0);
    pn_sc_ring(b, out_hi, 3.5, 2.0);
    /* Outside: four sides, the bottom, the top around the hole. */
    pn_sc_ring_sides(b, out_lo, out_hi, 1.0);
    pn_sc_quad_toward(b, out_lo[0], out_lo[1], out_lo[2], out_lo[3], down);
    pn_sc_ring_annulus(b, out_hi, hole_hi, 1.0);
    /* The hole's walls face its axis; the cavity's faces face its inside. */
    pn_sc_ring_sides(b, hole_lo, hole_hi, -1.0);
    pn_sc_ring_sides(b, cav_lo, cav_hi, -1.0);
    pn_sc_ring_annulus(b, cav_hi, hole_lo, -1.0);
    pn_sc_receivers_next(b, 4u);
    pn_sc_quad_toward(b, cav_lo[0], cav_lo[1], cav_lo[2], cav_lo[3], up);
    pn_sc_hsquare(b, 0.0, 0.0, 0.0, 5.0);
    pn_sc_view(v, 1.5f, 3.0f, 1.5f, 0.75f, 70.0f, 7.5f, 0.5f);
    pn_sc_set3(v->target, -0.5f, 0.75f, -0.5f);
    return 0;
}

/* ---- Public entry points -------------------------------------------------------------- */

typedef int (*pn_sc_build_fn)(pn_sc_builder *b, pn_scene_view *v);

/* pn_sc_all_names indexes pn_sc_builders; pn_sc_names is its first PN_SC_SHARED entries
 * (the set every frame test, the demo and the benchmark iterate). */
#define PN_SC_SHARED 5
static const char *const pn_sc_names[] = {"square", "spheres", "elongated-cube", "thin", "room",
                                           NULL};
static const char *const pn_sc_all_names[] = {"square", "spheres", "elongated-cube", "thin",
                                               "room", "closed-box", NULL};
static const pn_sc_build_fn pn_sc_builders[] = {
    pn_sc_build_square,
    pn_sc_build_spheres,
    pn_sc_build_elongated_cube,
    pn_sc_build_thin,
    pn_sc_build_room,
    pn_sc_build_closed_box,
};
/* Compile-time checks of the three tables' lengths (a negative array size fails). */
#define PN_SC_LEN(a) (sizeof(a) / sizeof((a)[0]))
typedef char pn_sc_check_shared[PN_SC_LEN(pn_sc_names) == PN_SC_SHARED + 1 ? 1 : -1];
typedef char
    pn_sc_check_builders[PN_SC_LEN(pn_sc_builders) + 1 == PN_SC_LEN(pn_sc_all_names) ? 1 : -1];

const char *const *pn_builtin_scene_names(void) { return pn_sc_names; }

const char *const *pn_builtin_scene_names_all(void) { return pn_sc_all_names; }

int pn_builtin_scene(const char *name, pn_mesh *out, pn_scene_view *view, char *err,
                     size_t err_size)
{
    pn_sc_builder b;
    pn_scene_view v;
    size_t i;

    if (out == NULL) {
        pn_tools_err(err, err_size, "pn_builtin_scene: out is NULL");
        return 1;
    }
    memset(out, 0, sizeof(*out));
    if (name == NULL) {
        pn_tools_err(err, err_size, "pn_builtin_scene: name is NULL");
        return 1;
    }
    for (i = 0; pn_sc_all_names[i] != NULL; i++) {
        if (strcmp(name, pn_sc_all_names[i]) == 0) {
            break;
        }
    }
    if (pn_sc_all_names[i] == NULL) {
        pn_tools_err(err, err_size,
                      "unknown built-in scene '%s' (known: square, spheres, elongated-cube, "
                      "thin, room, closed-box)",
                      name);
        return 2;
    }
    memset(&v, 0, sizeof(v));
    if (pn_sc_builders[i](&b, &v) != 0) {
        pn_tools_err(err, err_size, "built-in scene '%s': out of memory", name);
        return 3;
    }
    if (b.overflow || b.nv != b.cap_v || b.nt != b.cap_t) {
        /* Unreachable unless a builder's counts drift from its capacity. */
        free(b.pos);
        free(b.idx);
        pn_tools_err(err, err_size,
                      "built-in scene '%s': internal error (%u/%u vertices, %u/%u triangles)",
                      name, (unsigned)b.nv, (unsigned)b.cap_v, (unsigned)b.nt,
                      (unsigned)b.cap_t);
        return 4;
    }
    out->positions = b.pos;
    out->vertex_count = b.nv;
    out->indices = b.idx;
    out->triangle_count = b.nt;
    out->receiver_first = b.recv_first;
    out->receiver_count = b.recv_count;
    pn_mesh_update_bbox(out);
    if (view != NULL) {
        *view = v;
    }
    return 0;
}

/* ---- Closed form of the square scene -------------------------------------------------- *
 *
 * Both squares are axis-aligned and parallel to the light, so a light point (s, t) (light
 * coordinates along x and z) is hidden from receiver point (x, z) iff the segment crosses
 * y = occluder_y inside the square, and the crossing is, per axis, the linear blend
 * x + f (s - x) with f = (occluder_y - ground_y) / (light_y - ground_y). The hidden set is
 * therefore a product of two intervals and every fraction factors per axis. */

/* Fraction of the light's extent hidden along one axis, for receiver coordinate x. */
static double pn_sc_axis_hidden(const pn_square_params *p, double x, int k)
{
    double f = ((double)p->occluder_y - (double)p->ground_y) /
               ((double)p->light_y - (double)p->ground_y);
    double L = (double)p->light_half, h = (double)p->occluder_half;
    if (k <= 0) {
        /* Hidden light coordinates: |x + f (s - x)| <= h  <=>  s in [lo, hi]. */
        double lo = (-h - (1.0 - f) * x) / f, hi = (h - (1.0 - f) * x) / f;
        double a = lo > -L ? lo : -L, c = hi < L ? hi : L;
        return c > a ? (c - a) / (2.0 * L) : 0.0;
    } else {
        int i, n = 0;
        for (i = 0; i < k; i++) {
            double s = ((double)(2 * i + 1) / (double)k - 1.0) * L;
            double cross = x + f * (s - x);
            if (fabs(cross) <= h) {
                n++;
            }
        }
        return (double)n / (double)k;
    }
}

double pn_square_closed_form(const pn_square_params *p, double x, double z, int k)
{
    return 1.0 - pn_sc_axis_hidden(p, x, k) * pn_sc_axis_hidden(p, z, k);
}

double pn_square_min_edge_distance(const pn_square_params *p, double x, double z, int k)
{
    double f, L, h, lox, hix, loz, hiz, best = HUGE_VAL;
    int i, j;
    if (k <= 0) {
        return HUGE_VAL;
    }
    f = ((double)p->occluder_y - (double)p->ground_y) /
        ((double)p->light_y - (double)p->ground_y);
    L = (double)p->light_half;
    h = (double)p->occluder_half;
    /* Occluder square projected from the receiver point onto the light plane. */
    lox = (-h - (1.0 - f) * x) / f;
    hix = (h - (1.0 - f) * x) / f;
    loz = (-h - (1.0 - f) * z) / f;
    hiz = (h - (1.0 - f) * z) / f;
    for (j = 0; j < k; j++) {
        double t = ((double)(2 * j + 1) / (double)k - 1.0) * L;
        for (i = 0; i < k; i++) {
            double s = ((double)(2 * i + 1) / (double)k - 1.0) * L;
            double d;
            if (s >= lox && s <= hix && t >= loz && t <= hiz) {
                /* Inside: nearest of the four edges. */
                d = s - lox;
                if (hix - s < d) d = hix - s;
                if (t - loz < d) d = t - loz;
                if (hiz - t < d) d = hiz - t;
            } else {
                double dx = s < lox ? lox - s : (s > hix ? s - hix : 0.0);
                double dz = t < loz ? loz - t : (t > hiz ? t - hiz : 0.0);
                d = sqrt(dx * dx + dz * dz);
            }
            if (d < best) {
                best = d;
            }
        }
    }
    return best;
}
