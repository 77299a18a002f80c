/* pn_scenes_build.c - the built-in scenes' mesh builder and shared geometry helpers (see
 * pn_scenes_build.h): boxes, prisms, hexahedra, quads, the 762-triangle sphere, the hash
 * behind every scene's randomness, and the default views. */
#include "pn_scenes_build.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- The mesh builder and the shapes -------------------------------------------------- */

int pn_sc_builder_init(pn_sc_builder *b, uint32_t cap_v, uint32_t cap_t)
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

uint32_t pn_sc_vertex(pn_sc_builder *b, double x, double y, double z)
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
void pn_sc_tri(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2)
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
void pn_sc_receivers_next(pn_sc_builder *b, uint32_t count)
{
    b->recv_first = b->nt;
    b->recv_count = count;
}

/* Quad a-b-c-d in CCW order seen from outside, split along a-c. */
void pn_sc_quad(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2, uint32_t d)
{
    pn_sc_tri(b, a, c1, c2);
    pn_sc_tri(b, a, c2, d);
}

/* Horizontal square |x - cx|, |z - cz| <= h at height y, facing +y. Two triangles split
 * along the (-x,-z)-(+x,+z) diagonal. */
void pn_sc_hsquare(pn_sc_builder *b, double cx, double y, double cz, double h)
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
void pn_sc_box_ex(pn_sc_builder *b, const double lo[3], const double hi[3], double rise,
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

void pn_sc_box(pn_sc_builder *b, const double lo[3], const double hi[3])
{
    pn_sc_box_ex(b, lo, hi, 0.0, 0);
}

/* Axis-aligned box [x0, x1] x [y0, y1] x [z0, z1]. */
void pn_sc_block(pn_sc_builder *b, double x0, double y0, double z0, double x1, double y1,
                 double z1)
{
    const double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
    pn_sc_box(b, lo, hi);
}

/* Quad a-b-c-d (a convex planar polygon in either winding), split along a-c, wound so
 * that its normal has a positive component along dir. */
void pn_sc_quad_toward(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2, uint32_t d,
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
void pn_sc_prism(pn_sc_builder *b, const double a[3], const double e[3], double r0,
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
void pn_sc_hex(pn_sc_builder *b, const double c[8][3])
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

static const uint32_t pn_sc_ring_count[PN_SC_SPHERE_RINGS] = {
    6, 11, 17, 21, 26, 29, 31, 33, 33, 33, 31, 29, 26, 21, 17, 11, 6,
};

/* Odd rings are rotated by half a step so that no meridian of aligned vertices forms. */
static int pn_sc_ring_offset2(int ring) { return ring & 1; } /* offset in half-steps */

/* Vertices: north pole, rings 0..16 (ring i's vertex j at azimuth
 * 2*pi*(j + offset_i/2)/n_i), south pole. Triangles in order: north fan, strips, south fan. */
void pn_sc_sphere(pn_sc_builder *b, double cx, double cy, double cz, double r)
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

/* ---- Randomness ----------------------------------------------------------------------- */


/* Uniform in [0, 1) with 24 bits, exact in float and double. */
double pn_sc_rand01(uint32_t seed, uint32_t counter)
{
    return (double)(pn_hash32(seed ^ pn_hash32(counter)) >> 8) * (1.0 / 16777216.0);
}

/* ---- Views ---------------------------------------------------------------------------- */

void pn_sc_set3(float d[3], float x, float y, float z)
{
    d[0] = x;
    d[1] = y;
    d[2] = z;
}

/* Square light of half-size h centred at (0, y, 0): u = +x, v = +z, u x v = -y. */
void pn_sc_view(pn_scene_view *v, float ex, float ey, float ez, float ty, float fov,
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
