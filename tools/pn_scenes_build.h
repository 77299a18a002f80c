/* pn_scenes_build.h - internal to the built-in scenes (pn_scenes*.c, see pn_scenes.h): the
 * exact-capacity mesh builder, the geometry helpers the scenes share (pn_scenes_build.c)
 * and the scene builders (pn_scenes_objects.c, pn_scenes_sets.c) that pn_scenes.c's table
 * dispatches to. Each helper is documented at its definition. Host code, not installed. */
#ifndef PN_TOOLS_SCENES_BUILD_H
#define PN_TOOLS_SCENES_BUILD_H

#include <stdint.h>

#include "pn_scenes.h"

#define PN_SC_PI 3.14159265358979323846

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

/* ---- The builder (pn_scenes_build.c) ---- */
int pn_sc_builder_init(pn_sc_builder *b, uint32_t cap_v, uint32_t cap_t);
uint32_t pn_sc_vertex(pn_sc_builder *b, double x, double y, double z);
void pn_sc_tri(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2);
void pn_sc_receivers_next(pn_sc_builder *b, uint32_t count);

/* ---- Shapes (pn_scenes_build.c) ---- */
void pn_sc_quad(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2, uint32_t d);
void pn_sc_hsquare(pn_sc_builder *b, double cx, double y, double cz, double h);
void pn_sc_box_ex(pn_sc_builder *b, const double lo[3], const double hi[3], double rise,
                  int inside);
void pn_sc_box(pn_sc_builder *b, const double lo[3], const double hi[3]);
void pn_sc_block(pn_sc_builder *b, double x0, double y0, double z0, double x1, double y1,
                 double z1);
void pn_sc_quad_toward(pn_sc_builder *b, uint32_t a, uint32_t c1, uint32_t c2, uint32_t d,
                       const double dir[3]);
void pn_sc_prism(pn_sc_builder *b, const double a[3], const double e[3], double r0,
                 double r1, uint32_t n, double phase);
void pn_sc_hex(pn_sc_builder *b, const double c[8][3]);

/* The 762-triangle sphere of Forest et al. 2006 (pn_sc_sphere): its vertex and triangle
 * counts, for the scenes' capacities. */
#define PN_SC_SPHERE_VERTS 383u
#define PN_SC_SPHERE_TRIS 762u
void pn_sc_sphere(pn_sc_builder *b, double cx, double cy, double cz, double r);

/* ---- Randomness and views (pn_scenes_build.c) ---- */
double pn_sc_rand01(uint32_t seed, uint32_t counter);
void pn_sc_set3(float d[3], float x, float y, float z);
void pn_sc_view(pn_scene_view *v, float ex, float ey, float ez, float ty, float fov,
                float light_y, float light_half);

/* ---- The scenes: each fills *b (pn_sc_builder_init first; 1 if that fails) and *v ---- */
/* pn_scenes_objects.c */
int pn_sc_build_square(pn_sc_builder *b, pn_scene_view *v);
int pn_sc_build_spheres(pn_sc_builder *b, pn_scene_view *v);
int pn_sc_build_elongated_cube(pn_sc_builder *b, pn_scene_view *v);
int pn_sc_build_thin(pn_sc_builder *b, pn_scene_view *v);
/* pn_scenes_sets.c */
int pn_sc_build_room(pn_sc_builder *b, pn_scene_view *v);
int pn_sc_build_closed_box(pn_sc_builder *b, pn_scene_view *v);
int pn_sc_build_canopy(pn_sc_builder *b, pn_scene_view *v);
int pn_sc_build_colonnade(pn_sc_builder *b, pn_scene_view *v);

#endif
