/* pn_scenes.c - built-in procedural scenes (see pn_scenes.h).
 *
 * Layout of every mesh: the scene's own geometry first, in the order described at each
 * builder, then the ground (two triangles, four vertices) last. Tests rely on it. The
 * receiver range (pn_mesh.receiver_*) ends at the last triangle: the ground, and for
 * closed-box the box's inner floor just before it (pn_sc_receivers_next before them).
 *
 * Determinism: all randomness comes from an integer hash (lowbias32) of (seed, counter);
 * positions are computed in double and rounded to float once. The sphere and sliver
 * builders call libm sin/cos (spheres, thin, room, canopy, colonnade), so bit-exact positions across
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

/* Closed n-sided prism (a frustum when r0 != r1) from a to e: ring 0 of n vertices around
 * a at radius r0, ring 1 around e at radius r1, vertex i of each at angle
 * phase + 2 pi i / n in the frame (f1, f2) across the axis d = (e - a)/|e - a|, where
 * f1 is x (z when d is near x) made orthogonal to d and f2 = d x f1; then the n side
 * quads and the two caps as fans from vertex 0. (f1, f2, d) is right-handed, so the angle
 * grows counter-clockwise seen from e: side quad (a_i, a_i+1, e_i+1, e_i) faces out, the
 * cap fans (e_0, e_i, e_i+1) face +d and (a_0, a_i+1, a_i) face -d. 2n vertices,
 * 4n - 4 triangles. */
static void pn_sc_prism(pn_sc_builder *b, const double a[3], const double e[3], double r0,
                        double r1, uint32_t n, double phase)
{
    double d[3], f1[3], f2[3], l, dot;
    uint32_t base = b->nv, i;
    int k;
    for (k = 0; k < 3; k++) d[k] = e[k] - a[k];
    l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (k = 0; k < 3; k++) d[k] /= l;
    f1[0] = fabs(d[0]) < 0.9 ? 1.0 : 0.0;
    f1[1] = 0.0;
    f1[2] = fabs(d[0]) < 0.9 ? 0.0 : 1.0;
    dot = f1[0] * d[0] + f1[2] * d[2];
    for (k = 0; k < 3; k++) f1[k] -= dot * d[k];
    l = sqrt(f1[0] * f1[0] + f1[1] * f1[1] + f1[2] * f1[2]);
    for (k = 0; k < 3; k++) f1[k] /= l;
    f2[0] = d[1] * f1[2] - d[2] * f1[1];
    f2[1] = d[2] * f1[0] - d[0] * f1[2];
    f2[2] = d[0] * f1[1] - d[1] * f1[0];
    for (k = 0; k < 2; k++) {
        const double *o = k ? e : a;
        double r = k ? r1 : r0;
        for (i = 0; i < n; i++) {
            double t = phase + 2.0 * PN_SC_PI * (double)i / (double)n;
            double cs = r * cos(t), sn = r * sin(t);
            pn_sc_vertex(b, o[0] + cs * f1[0] + sn * f2[0], o[1] + cs * f1[1] + sn * f2[1],
                         o[2] + cs * f1[2] + sn * f2[2]);
        }
    }
    for (i = 0; i < n; i++) {
        uint32_t j = (i + 1u) % n;
        pn_sc_quad(b, base + i, base + j, base + n + j, base + n + i);
    }
    for (i = 1; i + 1u < n; i++) {
        pn_sc_tri(b, base + n, base + n + i, base + n + i + 1u);
        pn_sc_tri(b, base, base + i + 1u, base + i);
    }
}

/* Closed hexahedron on corners c[8] indexed like pn_sc_box_ex's (corner k is the image of
 * the unit cube's corner with x = bit 0, y = bit 1, z = bit 2 under an orientation-
 * preserving map, each face planar): 8 vertices, 12 triangles, outward normals. */
static void pn_sc_hex(pn_sc_builder *b, const double c[8][3])
{
    static const uint8_t faces[6][4] = {
        {0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6},
    };
    uint32_t base = b->nv;
    int k;
    for (k = 0; k < 8; k++) pn_sc_vertex(b, c[k][0], c[k][1], c[k][2]);
    for (k = 0; k < 6; k++) {
        const uint8_t *q = faces[k];
        pn_sc_quad(b, base + q[0], base + q[1], base + q[2], base + q[3]);
    }
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
 * other 0). In the chair's frame: b = offset toward the back, c = offset across (toward
 * (-az, ax)). Four legs (boxes 0.04 square, y in [0, 0.45]) under the seat at b in
 * {-0.17, 0.1}, c = +-0.17; the seat and back are one open shell (pn_sc_chair_shell). */
static void pn_sc_chair_legs(pn_sc_builder *b, double cx, double cz, double ax, double az)
{
    static const double legs[4][2] = {{-0.17, -0.17}, {-0.17, 0.17}, {0.1, -0.17}, {0.1, 0.17}};
    double px = -az, pz = ax; /* across */
    int i;
    for (i = 0; i < 4; i++) {
        double x = cx + legs[i][0] * ax + legs[i][1] * px, z = cz + legs[i][0] * az + legs[i][1] * pz;
        pn_sc_block(b, x - 0.02, 0.0, z - 0.02, x + 0.02, 0.45, z + 0.02);
    }
}

#define PN_SC_CHAIR_ALONG 10u  /* quads along the profile: seat 4, bend 3, back 3 */
#define PN_SC_CHAIR_ACROSS 8u  /* quads across */
#define PN_SC_CHAIR_VERTS ((PN_SC_CHAIR_ALONG + 1u) * (PN_SC_CHAIR_ACROSS + 1u))
#define PN_SC_CHAIR_TRIS (2u * PN_SC_CHAIR_ALONG * PN_SC_CHAIR_ACROSS)

/* Point i (0..10) of the shell's centre-line profile in the chair's (b, y) plane, and the
 * unit normal on its top/front side: the seat flat at y = 0.46 from b = -0.21 to 0.12
 * (4 quads), a quarter circle of radius 0.08 bending up into the back (3 quads), the back
 * rising to y = 0.95 leaning back to b = 0.23 (3 quads). */
static void pn_sc_chair_profile(uint32_t i, double p[2], double n[2])
{
    const double R = 0.08;
    if (i <= 4u) {
        p[0] = -0.21 + 0.0825 * (double)i;
        p[1] = 0.46;
        n[0] = 0.0;
        n[1] = 1.0;
    } else if (i <= 7u) {
        double a = (double)(i - 4u) * (PN_SC_PI / 6.0);
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

/* The seat and back of a chair (see pn_sc_chair_legs): one single-layer open sheet, a
 * 10 x 8 grid of quads over the profile, 0.42 wide (c in [-0.21, 0.21]), dished: the
 * middle pushed 0.02 behind the profile (down in the seat, back in the back), falling to
 * 0 at the side edges. Vertex (i, j) is base + i * 9 + j (i along the profile from the
 * seat's front edge, j across); quads wound so that the seat's top faces up and the
 * back's front faces the sitter (the profile normal's side). 99 vertices, 160 triangles. */
static void pn_sc_chair_shell(pn_sc_builder *b, double cx, double cz, double ax, double az)
{
    const double px = -az, pz = ax, half = 0.21, dish = 0.02;
    uint32_t base = b->nv, i, j;
    for (i = 0; i <= PN_SC_CHAIR_ALONG; i++) {
        double p[2], n[2];
        pn_sc_chair_profile(i, p, n);
        for (j = 0; j <= PN_SC_CHAIR_ACROSS; j++) {
            double c = -half + 2.0 * half * (double)j / (double)PN_SC_CHAIR_ACROSS;
            double d = dish * (1.0 - (c / half) * (c / half));
            double bb = p[0] - d * n[0], y = p[1] - d * n[1];
            pn_sc_vertex(b, cx + bb * ax + c * px, y, cz + bb * az + c * pz);
        }
    }
    for (i = 0; i < PN_SC_CHAIR_ALONG; i++) {
        double p0[2], n0[2], p1[2], n1[2], dir[3];
        pn_sc_chair_profile(i, p0, n0);
        pn_sc_chair_profile(i + 1u, p1, n1);
        dir[0] = (n0[0] + n1[0]) * ax;
        dir[1] = n0[1] + n1[1];
        dir[2] = (n0[0] + n1[0]) * az;
        for (j = 0; j < PN_SC_CHAIR_ACROSS; j++) {
            uint32_t v00 = base + i * (PN_SC_CHAIR_ACROSS + 1u) + j;
            uint32_t v10 = v00 + PN_SC_CHAIR_ACROSS + 1u;
            pn_sc_quad_toward(b, v00, v10, v10 + 1u, v00 + 1u, dir);
        }
    }
}

#define PN_SC_ROOM_BOOKS 14 /* per shelf, 4 shelves */
#define PN_SC_ROOM_STEPS 8
#define PN_SC_ROOM_SEED 0x600du
#define PN_SC_ROOM_CHAIRS 6u
/* table 5, chair legs 6 x 4, bookcase 7, books, stair: treads, stringer, 2 balusters a
 * tread, handrail */
#define PN_SC_ROOM_BOXES                                                                    \
    (5u + 4u * PN_SC_ROOM_CHAIRS + 7u + 4u * PN_SC_ROOM_BOOKS + 3u * PN_SC_ROOM_STEPS + 2u)

/* An interior: a closed 6 x 3 x 6 room (x, z in [-3, 3], y in [0, 3]) lit by a 1 x 1
 * ceiling panel hanging 1/16 below the ceiling, so the ceiling and the walls' top strip
 * lie behind the light (dark). Under the light a table with a globe lamp and six chairs,
 * each on four thin legs with its seat and back one open, single-layer, dished shell
 * (pn_sc_chair_shell: no thickness, so a shadow algorithm cannot rely on closed solids);
 * a bookcase of four shelves of books along the back wall (z = -3) with a vase on top; an
 * open stair along the left wall (x = -3) with a stringer, a sloped handrail and two thin
 * balusters a tread; a ball on the floor. The furniture stands on the floor, 2 cm off the
 * walls (no face on a wall). Seen from the light and from the camera in the opposite
 * corner, occluders stand behind one another: globe over table over chairs over floor,
 * handrail and balusters over treads over treads, books between boards.
 * Triangles: furniture (boxes: table, chair legs, bookcase, books, stair; then the six
 * chair shells, 160 triangles on 99 vertices each; then the three spheres), the room's
 * shell (ceiling and four walls, 10 triangles on 8 shared corners, wound inward), the
 * floor (ground) last. */
static int pn_sc_build_room(pn_sc_builder *b, pn_scene_view *v)
{
    static const double chairs[PN_SC_ROOM_CHAIRS][4] = {{0.4, 0.85, 0, 1}, {-0.4, 0.85, 0, 1},
                                        {0.4, -0.85, 0, -1}, {-0.4, -0.85, 0, -1},
                                        {1.15, 0, 1, 0}, {-1.15, 0, -1, 0}};
    static const double shell_lo[3] = {-3.0, 0.0, -3.0}, shell_hi[3] = {3.0, 3.0, 3.0};
    const double rise = 2.0 / 3.0; /* stair: 0.2 up per 0.3 toward -z */
    int i, j;
    if (pn_sc_builder_init(b,
                           PN_SC_ROOM_BOXES * 8u + PN_SC_ROOM_CHAIRS * PN_SC_CHAIR_VERTS +
                               3u * PN_SC_SPHERE_VERTS + 12u,
                           PN_SC_ROOM_BOXES * 12u + PN_SC_ROOM_CHAIRS * PN_SC_CHAIR_TRIS +
                               3u * PN_SC_SPHERE_TRIS + 12u) != 0) {
        return 1;
    }
    pn_sc_block(b, -0.8, 0.72, -0.5, 0.8, 0.76, 0.5);
    for (i = 0; i < 4; i++) {
        double x = (i & 1) ? 0.71 : -0.71, z = (i & 2) ? 0.41 : -0.41;
        pn_sc_block(b, x - 0.03, 0.0, z - 0.03, x + 0.03, 0.72, z + 0.03);
    }
    for (i = 0; i < (int)PN_SC_ROOM_CHAIRS; i++) {
        pn_sc_chair_legs(b, chairs[i][0], chairs[i][1], chairs[i][2], chairs[i][3]);
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
    for (i = 0; i < (int)PN_SC_ROOM_CHAIRS; i++) {
        pn_sc_chair_shell(b, chairs[i][0], chairs[i][1], chairs[i][2], chairs[i][3]);
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

/* ---- canopy ---------------------------------------------------------------------------- */

#define PN_SC_CANOPY_LEAVES 3000u
#define PN_SC_CANOPY_CLUSTERS 40u /* of 75 leaves */
#define PN_SC_CANOPY_BRANCHES 6u
#define PN_SC_CANOPY_SEED 0x1eafu
#define PN_SC_CANOPY_TRUNK_SIDES 8u
#define PN_SC_CANOPY_BRANCH_SIDES 6u

/* Is p inside the crown ellipsoid (centre (0, 4.2, 0), semi-axes 2.6, 1.6, 2.6) scaled
 * by s? */
static int pn_sc_in_crown(const double p[3], double s)
{
    double x = p[0] / (2.6 * s), y = (p[1] - 4.2) / (1.3 * s), z = p[2] / (2.6 * s);
    return x * x + y * y + z * z < 1.0;
}

/* A hashed point uniform in the ball of radius r around c, drawn (rejection, counters
 * from *ctr) until pn_sc_in_crown(p, s); c itself after 64 misses (c must be inside). */
static void pn_sc_crown_point(double p[3], const double c[3], double r, double s, uint32_t *ctr)
{
    int tries, k;
    for (tries = 0; tries < 64; tries++) {
        double q[3];
        for (k = 0; k < 3; k++) {
            q[k] = 2.0 * pn_sc_rand01(PN_SC_CANOPY_SEED, (*ctr)++) - 1.0;
        }
        if (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] >= 1.0) continue;
        for (k = 0; k < 3; k++) p[k] = c[k] + r * q[k];
        if (pn_sc_in_crown(p, s)) return;
    }
    for (k = 0; k < 3; k++) p[k] = c[k];
}

/* A tree over a ground. The crown: 3000 leaves in 40 clumps of 75 (clump centres uniform
 * in the crown ellipsoid - centre (0, 4.2, 0), semi-axes 2.6, 1.3, 2.6 - shrunk to 0.8,
 * leaves uniform within 0.4 of their clump's centre and inside the crown: dense clumps
 * with gaps between them dapple the light), each leaf a rhombus 0.11 long and 0.07 wide
 * (about 1/50 and 1/75 of the crown's 5.2 width) with a hashed normal uniform on the
 * sphere and a hashed spin about it, made double-sided the way foliage models are: two
 * coincident quads of opposite winding on the same four vertices (base, side, tip, side),
 * split along the same diagonal. Under it an octagonal trunk (radius 0.24 tapering to
 * 0.16, y in [0, 3.6]) and six hexagonal branches from its axis at y in [2.4, 3.3] to
 * points inside the crown; under everything a 10 x 10 ground. Light: 1.2 x 1.2 at y = 14
 * over the trunk, so a leaf 4 above the ground casts a penumbra about 0.5 wide: single
 * leaves blur away, clumps and the gaps between them do not.
 * Vertices: leaf l's 4 at 4l, trunk 16, branches 12 each, ground 4. Triangles: leaf l
 * is [4l, 4l + 4) (front quad, then the back quad on the same vertices), trunk (28),
 * branches (20 each), ground (2): 12000 + 28 + 120 + 2 = 12150. */
static int pn_sc_build_canopy(pn_sc_builder *b, pn_scene_view *v)
{
    uint32_t c, l, ctr = 0u;
    const double len = 0.11, wid = 0.07;
    if (pn_sc_builder_init(b,
                           4u * PN_SC_CANOPY_LEAVES + 2u * PN_SC_CANOPY_TRUNK_SIDES +
                               PN_SC_CANOPY_BRANCHES * 2u * PN_SC_CANOPY_BRANCH_SIDES + 4u,
                           4u * PN_SC_CANOPY_LEAVES + (4u * PN_SC_CANOPY_TRUNK_SIDES - 4u) +
                               PN_SC_CANOPY_BRANCHES * (4u * PN_SC_CANOPY_BRANCH_SIDES - 4u) +
                               2u) != 0) {
        return 1;
    }
    for (c = 0; c < PN_SC_CANOPY_CLUSTERS; c++) {
        static const double centre[3] = {0.0, 4.2, 0.0};
        double cc[3];
        pn_sc_crown_point(cc, centre, 2.6, 0.8, &ctr);
        for (l = 0; l < PN_SC_CANOPY_LEAVES / PN_SC_CANOPY_CLUSTERS; l++) {
            double p[3], n[3], f1[3], d[3], w[3], ny, phi, spin, rxz, fl;
            uint32_t v0, v1, v2, v3;
            int k;
            pn_sc_crown_point(p, cc, 0.4, 1.0, &ctr);
            ny = 2.0 * pn_sc_rand01(PN_SC_CANOPY_SEED, ctr++) - 1.0;
            phi = 2.0 * PN_SC_PI * pn_sc_rand01(PN_SC_CANOPY_SEED, ctr++);
            spin = 2.0 * PN_SC_PI * pn_sc_rand01(PN_SC_CANOPY_SEED, ctr++);
            rxz = sqrt(1.0 - ny * ny);
            n[0] = rxz * cos(phi);
            n[1] = ny;
            n[2] = rxz * sin(phi);
            /* f1: a unit vector across n (x or z made orthogonal to n); d = f1 spun by
             * `spin` about n; w = n x d. */
            f1[0] = fabs(n[0]) < 0.9 ? 1.0 : 0.0;
            f1[1] = 0.0;
            f1[2] = fabs(n[0]) < 0.9 ? 0.0 : 1.0;
            fl = f1[0] * n[0] + f1[2] * n[2];
            for (k = 0; k < 3; k++) f1[k] -= fl * n[k];
            fl = sqrt(f1[0] * f1[0] + f1[1] * f1[1] + f1[2] * f1[2]);
            for (k = 0; k < 3; k++) f1[k] /= fl;
            w[0] = n[1] * f1[2] - n[2] * f1[1];
            w[1] = n[2] * f1[0] - n[0] * f1[2];
            w[2] = n[0] * f1[1] - n[1] * f1[0];
            for (k = 0; k < 3; k++) d[k] = cos(spin) * f1[k] + sin(spin) * w[k];
            w[0] = n[1] * d[2] - n[2] * d[1];
            w[1] = n[2] * d[0] - n[0] * d[2];
            w[2] = n[0] * d[1] - n[1] * d[0];
            v0 = pn_sc_vertex(b, p[0] - 0.5 * len * d[0], p[1] - 0.5 * len * d[1],
                              p[2] - 0.5 * len * d[2]);
            v1 = pn_sc_vertex(b, p[0] + 0.5 * wid * w[0], p[1] + 0.5 * wid * w[1],
                              p[2] + 0.5 * wid * w[2]);
            v2 = pn_sc_vertex(b, p[0] + 0.5 * len * d[0], p[1] + 0.5 * len * d[1],
                              p[2] + 0.5 * len * d[2]);
            v3 = pn_sc_vertex(b, p[0] - 0.5 * wid * w[0], p[1] - 0.5 * wid * w[1],
                              p[2] - 0.5 * wid * w[2]);
            /* (v1 - v0) x (v2 - v0) = (len d/2 + wid w/2) x (len d) = (len wid / 2) w x d,
             * = -(len wid / 2) n: the front quad faces -n, the back quad +n. */
            pn_sc_quad(b, v0, v1, v2, v3);
            pn_sc_quad(b, v0, v3, v2, v1);
        }
    }
    {
        static const double base[3] = {0.0, 0.0, 0.0}, top[3] = {0.0, 3.6, 0.0};
        pn_sc_prism(b, base, top, 0.24, 0.16, PN_SC_CANOPY_TRUNK_SIDES, PN_SC_PI / 8.0);
    }
    for (c = 0; c < PN_SC_CANOPY_BRANCHES; c++) {
        double yaw = 2.0 * PN_SC_PI * ((double)c + 0.6 * pn_sc_rand01(PN_SC_CANOPY_SEED, ctr++)) /
                     (double)PN_SC_CANOPY_BRANCHES;
        double h = 2.4 + 0.9 * pn_sc_rand01(PN_SC_CANOPY_SEED, ctr++);
        double reach = 1.3 + 0.5 * pn_sc_rand01(PN_SC_CANOPY_SEED, ctr++);
        double a[3], e[3];
        a[0] = 0.0;
        a[1] = h;
        a[2] = 0.0;
        e[0] = reach * cos(yaw);
        e[1] = h + 0.8 + 0.4 * pn_sc_rand01(PN_SC_CANOPY_SEED, ctr++);
        e[2] = reach * sin(yaw);
        pn_sc_prism(b, a, e, 0.08, 0.035, PN_SC_CANOPY_BRANCH_SIDES, 0.0);
    }
    pn_sc_receivers_next(b, 2u);
    pn_sc_hsquare(b, 0.0, 0.0, 0.0, 5.0);
    pn_sc_view(v, 0.0f, 10.0f, 12.0f, 1.3f, 50.0f, 14.0f, 0.6f);
    return 0;
}

/* ---- colonnade ------------------------------------------------------------------------- */

#define PN_SC_COL_PER_ROW 8u
#define PN_SC_COL_SIDES 12u
#define PN_SC_COL_VOUSSOIRS 11u
#define PN_SC_COL_ARCHES (2u * (PN_SC_COL_PER_ROW - 1u))
#define PN_SC_COL_COLUMNS (2u * PN_SC_COL_PER_ROW)

/* Two facing arcades along x (rows at z = -1.6 and z = +1.6), 8 columns a row 1.5 apart
 * (x = -5.25 .. 5.25). A column: a square plinth 0.5 x 0.2 x 0.5, a 12-sided shaft of
 * radius 0.17 from y = 0.2 to 2.6, a square capital 0.5 x 0.2 x 0.5 up to y = 2.8.
 * Between neighbouring capitals a semicircular arch springs at y = 2.8: inner radius 0.5
 * (the 1.0 opening between the capitals), outer 0.8, 0.4 deep, built of 11 wedge-shaped
 * voussoirs (each a closed hexahedron, 20/11 of a right angle wide, the middle one the
 * keystone); an entablature beam 0.5 deep, 0.35 high, resting on the keystones' tops runs
 * the length of each row. Floor 18 x 12. Light: 1 x 1 at y = 16, offset to (4, 16, -3.5)
 * from the middle (N = -y), so the arches cast curved shadows on the floor toward +z (the
 * -z row's between the rows, the +z row's in front of it) and the columns' shadows slant
 * along the row across their neighbours'.
 * Vertices and triangles, in order: columns (row -z first, then +z; x ascending), each
 * plinth (8, 12), shaft (24, 44), capital (8, 12); arches (row -z, then +z; x ascending),
 * voussoirs from the -x springing (8, 12 each); the two beams (8, 12); floor (4, 2).
 * 16 * 68 + 14 * 132 + 24 + 2 = 2962 triangles. */
static int pn_sc_build_colonnade(pn_sc_builder *b, pn_scene_view *v)
{
    const double spacing = 1.5, half_w = 0.25, r_shaft = 0.17, y_plinth = 0.2, y_cap0 = 2.6;
    const double y_spring = 2.8, r_in = 0.5, r_out = 0.8, arch_half = 0.2, beam_half = 0.25;
    const double x0 = -0.5 * spacing * (double)(PN_SC_COL_PER_ROW - 1u);
    const double step = PN_SC_PI / (double)PN_SC_COL_VOUSSOIRS;
    const double y_beam = y_spring + r_out * cos(0.5 * step);
    uint32_t row, i, j;
    if (pn_sc_builder_init(b,
                           PN_SC_COL_COLUMNS * (16u + 2u * PN_SC_COL_SIDES) +
                               PN_SC_COL_ARCHES * PN_SC_COL_VOUSSOIRS * 8u + 16u + 4u,
                           PN_SC_COL_COLUMNS * (24u + 4u * PN_SC_COL_SIDES - 4u) +
                               PN_SC_COL_ARCHES * PN_SC_COL_VOUSSOIRS * 12u + 24u + 2u) != 0) {
        return 1;
    }
    for (row = 0; row < 2u; row++) {
        double z = row ? 1.6 : -1.6;
        for (i = 0; i < PN_SC_COL_PER_ROW; i++) {
            double x = x0 + spacing * (double)i;
            const double a[3] = {x, y_plinth, z}, e[3] = {x, y_cap0, z};
            pn_sc_block(b, x - half_w, 0.0, z - half_w, x + half_w, y_plinth, z + half_w);
            pn_sc_prism(b, a, e, r_shaft, r_shaft, PN_SC_COL_SIDES, PN_SC_PI / (double)PN_SC_COL_SIDES);
            pn_sc_block(b, x - half_w, y_cap0, z - half_w, x + half_w, y_spring, z + half_w);
        }
    }
    for (row = 0; row < 2u; row++) {
        double z = row ? 1.6 : -1.6;
        for (i = 0; i + 1u < PN_SC_COL_PER_ROW; i++) {
            double cx = x0 + spacing * ((double)i + 0.5);
            for (j = 0; j < PN_SC_COL_VOUSSOIRS; j++) {
                /* Voussoir j spans angles [pi - (j + 1) step, pi - j step] (j = 0 at the
                 * -x springing). Corner k: bit 0 outer radius, bit 1 the larger angle,
                 * bit 2 the +z face: (radial, d/d angle, z) is right-handed (radial x
                 * tangential = +z), so pn_sc_hex's faces are outward. */
                double c[8][3];
                int k;
                for (k = 0; k < 8; k++) {
                    double ang = PN_SC_PI - step * (double)(j + 1u - (uint32_t)((k >> 1) & 1));
                    double r = (k & 1) ? r_out : r_in;
                    c[k][0] = cx + r * cos(ang);
                    c[k][1] = y_spring + r * sin(ang);
                    c[k][2] = z + ((k & 4) ? arch_half : -arch_half);
                }
                pn_sc_hex(b, c);
            }
        }
    }
    for (row = 0; row < 2u; row++) {
        double z = row ? 1.6 : -1.6;
        pn_sc_block(b, x0 - half_w, y_beam, z - beam_half, -x0 + half_w, y_beam + 0.35,
                    z + beam_half);
    }
    pn_sc_receivers_next(b, 2u);
    {
        /* Floor 20 x 16: not a square, so four explicit corners (hsquare's order). */
        uint32_t g0 = pn_sc_vertex(b, -9.0, 0.0, -6.0), g1 = pn_sc_vertex(b, -9.0, 0.0, 6.0);
        uint32_t g2 = pn_sc_vertex(b, 9.0, 0.0, 6.0), g3 = pn_sc_vertex(b, 9.0, 0.0, -6.0);
        pn_sc_quad(b, g0, g1, g2, g3);
    }
    /* From above the +z side, looking across both rows at the floor between and before
     * them, where the shadows fall (the light is behind the rows). */
    pn_sc_view(v, 2.0f, 14.0f, 14.0f, 0.0f, 62.0f, 16.0f, 0.5f);
    pn_sc_set3(v->target, -0.5f, 0.0f, 0.0f);
    pn_sc_set3(v->light_center, 4.0f, 16.0f, -3.5f);
    return 0;
}

/* ---- Public entry points -------------------------------------------------------------- */

typedef int (*pn_sc_build_fn)(pn_sc_builder *b, pn_scene_view *v);

/* pn_sc_all_names indexes pn_sc_builders; pn_sc_names is its first PN_SC_SHARED entries
 * (the set every frame test, the demo and the benchmark iterate). */
#define PN_SC_SHARED 7
static const char *const pn_sc_names[] = {"square", "spheres",  "elongated-cube", "thin",
                                           "room",   "canopy",   "colonnade",      NULL};
static const char *const pn_sc_all_names[] = {"square", "spheres",   "elongated-cube",
                                               "thin",   "room",      "canopy",
                                               "colonnade", "closed-box", NULL};
static const pn_sc_build_fn pn_sc_builders[] = {
    pn_sc_build_square,
    pn_sc_build_spheres,
    pn_sc_build_elongated_cube,
    pn_sc_build_thin,
    pn_sc_build_room,
    pn_sc_build_canopy,
    pn_sc_build_colonnade,
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
                      "thin, room, canopy, colonnade, closed-box)",
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
