/* pn_kmath.h - 3-vectors as float[3]-compatible structs and the few scalar helpers the
 * kernels need. Operations are written out component by component in a fixed order so
 * that C and OpenCL evaluate identical expressions. */
#ifndef PN_KMATH_H
#define PN_KMATH_H

#include "pn_kernel.h"

typedef struct pn_v3 {
    float x, y, z;
} pn_v3;

PN_KFN pn_v3 pn_v3_make(float x, float y, float z)
{
    pn_v3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}
PN_KFN pn_v3 pn_v3_load(PN_CONST float *p) { return pn_v3_make(p[0], p[1], p[2]); }
/* v into element i of three coordinate arrays (a run's structure of arrays). */
PN_KFN void pn_v3_put(float *x, float *y, float *z, uint32_t i, pn_v3 v)
{
    x[i] = v.x;
    y[i] = v.y;
    z[i] = v.z;
}
PN_KFN pn_v3 pn_v3_add(pn_v3 a, pn_v3 b) { return pn_v3_make(a.x + b.x, a.y + b.y, a.z + b.z); }
PN_KFN pn_v3 pn_v3_sub(pn_v3 a, pn_v3 b) { return pn_v3_make(a.x - b.x, a.y - b.y, a.z - b.z); }
PN_KFN pn_v3 pn_v3_scale(pn_v3 a, float s) { return pn_v3_make(a.x * s, a.y * s, a.z * s); }
PN_KFN float pn_v3_dot(pn_v3 a, pn_v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
PN_KFN pn_v3 pn_v3_cross(pn_v3 a, pn_v3 b)
{
    return pn_v3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* Unit vector along a; zero for a zero vector. Scaled by the largest component first, so
 * a.a can neither underflow (a 1e-20 triangle's normal) nor overflow (2^82 components). */
PN_KFN pn_v3 pn_v3_normalize(pn_v3 a)
{
    float ax = a.x < 0.0f ? -a.x : a.x, ay = a.y < 0.0f ? -a.y : a.y, az = a.z < 0.0f ? -a.z : a.z;
    float m = ax > ay ? (ax > az ? ax : az) : (ay > az ? ay : az), len2;
    if (!(m > 0.0f)) return pn_v3_make(0.0f, 0.0f, 0.0f);
    a = pn_v3_scale(a, 1.0f / m);
    len2 = pn_v3_dot(a, a);
    return pn_v3_scale(a, 1.0f / pn_ksqrt(len2));
}

/* |x| + |y| + |z|: a magnitude for error bounds that cannot overflow where the Euclidean
 * length's square would. */
PN_KFN float pn_v3_l1(pn_v3 a)
{
    return (a.x < 0.0f ? -a.x : a.x) + (a.y < 0.0f ? -a.y : a.y) + (a.z < 0.0f ? -a.z : a.z);
}
PN_KFN float pn_kminf(float a, float b) { return a < b ? a : b; }
PN_KFN float pn_kmaxf(float a, float b) { return a > b ? a : b; }

/* Componentwise |a|, and max(|x|, |y|, |z|): for rounding bounds (pn_predicate.h). */
PN_KFN pn_v3 pn_v3_abs(pn_v3 a)
{
    return pn_v3_make(a.x < 0.0f ? -a.x : a.x, a.y < 0.0f ? -a.y : a.y, a.z < 0.0f ? -a.z : a.z);
}
PN_KFN float pn_v3_linf(pn_v3 a)
{
    pn_v3 b = pn_v3_abs(a);
    return pn_kmaxf(b.x, pn_kmaxf(b.y, b.z));
}
PN_KFN int32_t pn_kmini(int32_t a, int32_t b) { return a < b ? a : b; }
PN_KFN int32_t pn_kmaxi(int32_t a, int32_t b) { return a > b ? a : b; }
PN_KFN uint32_t pn_kminu(uint32_t a, uint32_t b) { return a < b ? a : b; }
PN_KFN uint32_t pn_kmaxu(uint32_t a, uint32_t b) { return a > b ? a : b; }

/* Float to integer, clamped to [lo, hi] *before* the conversion (an out-of-range
 * conversion is undefined in C and implementation-defined in OpenCL); NaN gives lo. Every
 * caller's bounds are at most 2^24 in magnitude, so exact in float: v is clamped as a
 * float (pn_kclampf), and the rounding of an in-range float (pn_kfloor_in, pn_kceil_in)
 * leaves a clamped bound alone. Selects, not early returns, and split in two so that a
 * loop over lanes (pn_foot_index) can run each half side by side. */
PN_KFN float pn_kclampf(float v, int32_t lo, int32_t hi)
{
    /* Two flat selects, and the roundings below add a comparison's 0 or 1: written so, GCC
     * vectorizes a loop over lanes that clamps and converts (as nested selects it keeps a
     * branch there: the rows pass's eight triangles, pn_raster_rows_group). */
    float fl = (float)lo, fh = (float)hi, c = v > fl ? v : fl;
    return c < fh ? c : fh;
}
PN_KFN int32_t pn_kfloor_in(float v)
{
    int32_t i = (int32_t)v; /* truncation toward zero */
    return i - (int32_t)((float)i > v);
}
PN_KFN int32_t pn_kceil_in(float v)
{
    int32_t i = (int32_t)v;
    return i + (int32_t)((float)i < v);
}
PN_KFN int32_t pn_kfloor_clamp(float v, int32_t lo, int32_t hi) { return pn_kfloor_in(pn_kclampf(v, lo, hi)); }
PN_KFN int32_t pn_kceil_clamp(float v, int32_t lo, int32_t hi) { return pn_kceil_in(pn_kclampf(v, lo, hi)); }

/* A float's bits and back (as_uint / as_float in OpenCL). */
PN_KFN uint32_t pn_kfbits(float v)
{
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
    return as_uint(v);
#else
    union {
        float f;
        uint32_t u;
    } x;
    x.f = v;
    return x.u;
#endif
}

PN_KFN float pn_kbitsf(uint32_t v)
{
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
    return as_float(v);
#else
    union {
        float f;
        uint32_t u;
    } x;
    x.u = v;
    return x.f;
#endif
}

PN_KFN uint32_t pn_kpopcount(uint32_t v)
{
    v = v - ((v >> 1) & 0x55555555u);
    v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
    v = (v + (v >> 4)) & 0x0F0F0F0Fu;
    return (v * 0x01010101u) >> 24;
}

/* Index of the lowest set bit of v != 0. */
PN_KFN uint32_t pn_kctz(uint32_t v) { return pn_kpopcount((v & (0u - v)) - 1u); }

/* Lexicographic "a < b" on (x, y, z): the canonical vertex order that makes a shared
 * edge evaluate identically in both triangles that use it. */
PN_KFN int pn_v3_less(pn_v3 a, pn_v3 b)
{
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

#endif
