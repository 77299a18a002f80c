/* pn_test_geom.h - test-only geometry and a double-precision brute-force ray caster that
 * shares no code with the library (an independent check of the rasterizer and the
 * predicate). */
#ifndef PN_TEST_GEOM_H
#define PN_TEST_GEOM_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pn_test_scene.h"

/* Closed lat-long sphere with shared vertices: poles are fans, quads split in two.
 * Meridian edges lie in planes through the y axis, so a point on the axis sees
 * segments run exactly along edges: the watertightness stress case. */
static inline int pn_test_uv_sphere(pn_test_mesh *m, double cx, double cy, double cz, double r, int slices, int stacks)
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
    pn_test_mesh_update_bbox(m);
    return 0;
}

/* Appends mesh b to mesh a (b's receiver range is not carried over). */
static inline int pn_test_append(pn_test_mesh *a, const pn_test_mesh *b)
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
    pn_test_mesh_update_bbox(a);
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

/* Double-precision normal (B - A) x (C - A) of a float triangle. */
static inline void pn_test_tri_normal(const float *A, const float *B, const float *C, double n[3])
{
    double e1[3], e2[3];
    int c;
    for (c = 0; c < 3; c++) {
        e1[c] = (double)B[c] - A[c];
        e2[c] = (double)C[c] - A[c];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

/* Double-precision distance from point p to the segment [a, b]. */
static inline double pn_test_point_seg(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], t, den = 0.0, num = 0.0, d2 = 0.0;
    int c;
    for (c = 0; c < 3; c++) {
        ab[c] = b[c] - a[c];
        ap[c] = p[c] - a[c];
        den += ab[c] * ab[c];
        num += ab[c] * ap[c];
    }
    t = den > 0.0 ? num / den : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    for (c = 0; c < 3; c++) {
        double e = ap[c] - t * ab[c];
        d2 += e * e;
    }
    return sqrt(d2);
}

/* Double-precision distance from point p to the closed triangle ABC: to its plane when the
 * foot lies inside, else to the nearest edge. */
static inline double pn_test_point_tri(const double p[3], const float *A, const float *B, const float *C)
{
    double a[3], b[3], c3[3], n[3], ap[3], nn, h, foot[3], w[3];
    int c;
    for (c = 0; c < 3; c++) {
        a[c] = A[c];
        b[c] = B[c];
        c3[c] = C[c];
        ap[c] = p[c] - a[c];
    }
    pn_test_tri_normal(A, B, C, n);
    nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (nn > 0.0) {
        /* Barycentrics of the foot from the sub-triangle areas. */
        h = (ap[0] * n[0] + ap[1] * n[1] + ap[2] * n[2]) / nn;
        for (c = 0; c < 3; c++) foot[c] = p[c] - h * n[c];
        {
            const double *v[3] = {a, b, c3};
            int q, inside = 1;
            for (q = 0; q < 3; q++) {
                const double *s = v[q], *t = v[(q + 1) % 3];
                double x[3], y[3];
                for (c = 0; c < 3; c++) {
                    x[c] = t[c] - s[c];
                    y[c] = foot[c] - s[c];
                }
                w[q] = (x[1] * y[2] - x[2] * y[1]) * n[0] + (x[2] * y[0] - x[0] * y[2]) * n[1] +
                       (x[0] * y[1] - x[1] * y[0]) * n[2];
                inside &= w[q] >= 0.0;
            }
            if (inside) return fabs(h) * sqrt(nn);
        }
    }
    return fmin(pn_test_point_seg(p, a, b), fmin(pn_test_point_seg(p, b, c3), pn_test_point_seg(p, c3, a)));
}

/* Double-precision distance by which the segment [o, s] misses triangle ABC, measured where
 * the crossing is: from the point where the segment's line crosses the triangle's plane,
 * clamped to the segment (the exact predicate blocks only segments that meet the triangle,
 * so a blocked sample's miss is double rounding). */
static inline double pn_test_seg_miss(const double o[3], const double s[3], const float *A, const float *B,
                                      const float *C)
{
    double n[3], d0 = 0.0, ds = 0.0, t, x[3];
    int c;
    pn_test_tri_normal(A, B, C, n);
    for (c = 0; c < 3; c++) {
        d0 += (o[c] - A[c]) * n[c];
        ds += (s[c] - A[c]) * n[c];
    }
    t = d0 != ds ? d0 / (d0 - ds) : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    for (c = 0; c < 3; c++) x[c] = o[c] + t * (s[c] - o[c]);
    return pn_test_point_tri(x, A, B, C);
}

#endif
