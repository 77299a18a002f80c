/* pn_test_geom.h - test-only geometry and a double-precision brute-force ray caster that
 * shares no code with the library (an independent check of the rasterizer and the
 * predicate). */
#ifndef PN_TEST_GEOM_H
#define PN_TEST_GEOM_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pn_mesh.h"

/* Closed lat-long sphere with shared vertices: poles are fans, quads split in two.
 * Meridian edges lie in planes through the y axis, so a point on the axis sees
 * segments run exactly along edges: the watertightness stress case. */
static inline int pn_test_uv_sphere(pn_mesh *m, double cx, double cy, double cz, double r, int slices, int stacks)
{
    int i, j, nv = 2 + slices * (stacks - 1), nt = 2 * slices * (stacks - 1), t = 0;
    memset(m, 0, sizeof(*m));
    m->positions = (float *)malloc(sizeof(float) * 3u * (size_t)nv);
    m->indices = (uint32_t *)malloc(sizeof(uint32_t) * 3u * (size_t)nt);
    if (!m->positions || !m->indices) return 1;
    m->vertex_count = (uint32_t)nv;
    m->triangle_count = (uint32_t)nt;
    m->positions[0] = (float)cx; m->positions[1] = (float)(cy + r); m->positions[2] = (float)cz;
    m->positions[3] = (float)cx; m->positions[4] = (float)(cy - r); m->positions[5] = (float)cz;
    for (j = 1; j < stacks; j++)
        for (i = 0; i < slices; i++) {
            double th = M_PI * j / stacks, ph = 2.0 * M_PI * i / slices;
            float *p = m->positions + 3 * (2 + (j - 1) * slices + i);
            p[0] = (float)(cx + r * sin(th) * cos(ph));
            p[1] = (float)(cy + r * cos(th));
            p[2] = (float)(cz + r * sin(th) * sin(ph));
        }
#define V(jj, ii) (uint32_t)(2 + ((jj) - 1) * slices + ((ii) % slices))
    for (i = 0; i < slices; i++) { /* outward winding */
        uint32_t *x = m->indices + 3 * t++;
        x[0] = 0; x[1] = V(1, i + 1); x[2] = V(1, i);
        x = m->indices + 3 * t++;
        x[0] = 1; x[1] = V(stacks - 1, i); x[2] = V(stacks - 1, i + 1);
    }
    for (j = 1; j < stacks - 1; j++)
        for (i = 0; i < slices; i++) {
            uint32_t *x = m->indices + 3 * t++;
            x[0] = V(j, i); x[1] = V(j, i + 1); x[2] = V(j + 1, i + 1);
            x = m->indices + 3 * t++;
            x[0] = V(j, i); x[1] = V(j + 1, i + 1); x[2] = V(j + 1, i);
        }
#undef V
    pn_mesh_update_bbox(m);
    return 0;
}

/* Appends mesh b to mesh a. */
static inline int pn_test_append(pn_mesh *a, const pn_mesh *b)
{
    uint32_t nv = a->vertex_count + b->vertex_count, nt = a->triangle_count + b->triangle_count, t;
    float *p = (float *)realloc(a->positions, sizeof(float) * 3u * nv);
    uint32_t *x;
    if (!p) return 1;
    a->positions = p;
    x = (uint32_t *)realloc(a->indices, sizeof(uint32_t) * 3u * nt);
    if (!x) return 1;
    a->indices = x;
    memcpy(p + 3u * a->vertex_count, b->positions, sizeof(float) * 3u * b->vertex_count);
    for (t = 0; t < 3u * b->triangle_count; t++) x[3u * a->triangle_count + t] = b->indices[t] + a->vertex_count;
    a->vertex_count = nv;
    a->triangle_count = nt;
    pn_mesh_update_bbox(a);
    return 0;
}

/* Double-precision ray/triangle (Moller-Trumbore). Returns t (any sign) or -1 on a miss;
 * *margin gets min(u, v, 1-u-v): >= 0 inside, the barycentric distance to the nearest
 * edge; < 0 outside (0 if the ray is parallel). */
static inline double pn_test_ray_tri(const double o[3], const double d[3], const float *A, const float *B,
                              const float *C, double *margin)
{
    double e1[3], e2[3], p[3], q[3], s[3], det, inv, u, v, t;
    int a;
    for (a = 0; a < 3; a++) {
        e1[a] = (double)B[a] - A[a];
        e2[a] = (double)C[a] - A[a];
        s[a] = o[a] - A[a];
    }
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    *margin = 0.0;
    if (det == 0.0) return -1.0;
    inv = 1.0 / det;
    u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    *margin = fmin(fmin(u, v), 1.0 - u - v); /* negative: how far outside */
    if (*margin < 0.0) return -1.0;
    return t;
}

#endif
