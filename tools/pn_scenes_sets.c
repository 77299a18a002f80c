/* pn_scenes_sets.c - the built-in scenes assembled from many parts (see pn_scenes.h): room
 * (with its chairs), closed-box, canopy, colonnade. */
#include "pn_scenes_build.h"

#include <math.h>
#include <stdint.h>

/* ---- room ----------------------------------------------------------------------------- */

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
int pn_sc_build_room(pn_sc_builder *b, pn_scene_view *v)
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
/* ---- closed-box ----------------------------------------------------------------------- */

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
int pn_sc_build_closed_box(pn_sc_builder *b, pn_scene_view *v)
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
int pn_sc_build_canopy(pn_sc_builder *b, pn_scene_view *v)
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
int pn_sc_build_colonnade(pn_sc_builder *b, pn_scene_view *v)
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
