/* pn_scenes_objects.c - the built-in scenes of single objects over a ground (see
 * pn_scenes.h): square, spheres, elongated-cube, thin. */
#include "pn_scenes_build.h"

#include <math.h>
#include <stdint.h>

/* Triangles: occluder (2), ground (2). */
int pn_sc_build_square(pn_sc_builder *b, pn_scene_view *v)
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
int pn_sc_build_spheres(pn_sc_builder *b, pn_scene_view *v)
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
int pn_sc_build_elongated_cube(pn_sc_builder *b, pn_scene_view *v)
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

#define PN_SC_THIN_COUNT 2000u
#define PN_SC_THIN_SEED 0x7411u

/* 2000 needles: apex at one end, a base 0.002 wide at the other, 2 long; centres uniform
 * in x, z in [-3, 3], y in [1, 1.6]; yaw uniform, pitch within +-10 degrees; the width
 * direction is horizontal, so each sliver's shadow is as thin as it can be. A 512-texel
 * shadow map over this 10-unit scene has texels of 0.02, ten times a sliver's width.
 * Triangles: sliver s is triangle s (vertices 3s..3s+2, facing up); ground last. */
int pn_sc_build_thin(pn_sc_builder *b, pn_scene_view *v)
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
