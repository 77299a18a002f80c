/* pn_kernel.h - the qualifier vocabulary that lets kernels/ compile both as C99 (scalar
 * port, host) and as OpenCL C 1.2 (OpenCL port). Every kernels/ header includes it first.
 * OpenCL compilers define __OPENCL_VERSION__; Clang without a device target defines only
 * __OPENCL_C_VERSION__, so either selects the OpenCL branch.
 *
 *   PN_KFN      a kernel helper function (static inline in C, plain inline-able in CL)
 *   PN_KFN_HOT  a small helper of an inner loop that must be inlined wherever it is used
 *               (GCC's inliner otherwise decides by the size of the caller, so the same
 *               loop costs more or less depending on what a pass wraps around it)
 *   PN_KFN_COLD a helper of a rare path that must stay out of the inner loop calling it
 *               (inlined, it costs that loop registers: the ray tracer's exact fallback)
 *   PN_GLOBAL   pointer into the arena (device global memory in OpenCL)
 *   PN_CONST    read-only pointer into the arena
 *   pn_katomic_add(p, v)   32-bit unsigned atomic add into the arena, returns the old value:
 *               for order-independent reductions (counts, histograms) only, never for
 *               anything whose result depends on which work item came first (a cursor's
 *               slots only when a sort of each run follows: GEARS' cell lists)
 *   pn_katomic_or(p, v)    32-bit atomic or into the arena (bit sets: order-independent)
 *   pn_katomic_imin(p, v), pn_katomic_imax(p, v)   32-bit signed atomic min / max into the
 *               arena, return the old value: order-independent; on the bits of floats
 *               that are >= 0 or -inf (pn_kfbits) the signed order is the floats' order
 *
 *   pn_f4, pn_i4   (C only, where PN_KVEC4 is 1) four float / int32 lanes, operated on
 *               lane by lane: for a loop that must run four lanes at a time whatever the
 *               compiler's vectorizer makes of it; the OpenCL side keeps the loop over lanes
 *
 * Kernel code uses only + - * / and pn_ksqrt on float (in lanes or not), 32-bit integers,
 * fixed-size arrays, loops and no recursion, no function pointers, no double, no libc: both
 * compilers then produce correctly rounded IEEE results in the same order, which is what
 * makes the two ports bit-identical (with contraction off on both sides). */
#ifndef PN_KERNEL_H
#define PN_KERNEL_H

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#pragma OPENCL FP_CONTRACT OFF
#define PN_KFN static inline
#define PN_KFN_HOT static inline
#define PN_KFN_COLD static inline
#define PN_GLOBAL __global
#define PN_CONST __global const
typedef uint uint32_t;
typedef int int32_t;
typedef ushort uint16_t;
typedef uchar uint8_t;
typedef ulong uint64_t;
#define pn_ksqrt(x) sqrt(x)
#define pn_kfabs(x) fabs(x)
#define PN_KINF INFINITY
#define pn_katomic_add(p, v) atomic_add((p), (v))
#define pn_katomic_or(p, v) atomic_or((p), (v))
#define pn_katomic_imin(p, v) atomic_min((p), (v))
#define pn_katomic_imax(p, v) atomic_max((p), (v))
#define pn_kclz(x) clz((uint)(x))
/* No pn_f4 here: PoCL vectorizes the plain loops over lanes across work items itself, and
 * measured float4 slower (the reference on the chess set 1.14x, thin 1.05x). */
#define PN_KVEC4 0
/* The OpenCL port passes the host's configuration as build options (-D...), so both
 * ports size their private arrays alike. */
#if !defined(PN_MASK_WORDS_MAX) || !defined(PN_BVH_STACK) || !defined(PN_ENABLE_REFERENCE) || \
    !defined(PN_ENABLE_RAYTRACE) || !defined(PN_ENABLE_GEARS) || !defined(PN_ENABLE_SRT) || !defined(PN_SRT_MAP_MAX) || \
    !defined(PN_ENABLE_OCCTEX) || !defined(PN_OCCTEX_MAP_MAX) || !defined(PN_ENABLE_MCSM) || \
    !defined(PN_ENABLE_WEDGES)
#error "OpenCL build options must define PN_MASK_WORDS_MAX, PN_BVH_STACK and PN_ENABLE_* (ports/opencl does)"
#endif
#else
#include <stdint.h>
#include "penumbra/config.h"
/* The configuration values kernels/ reads: a device port hands each to its compiler as
 * -D<name>=<value>u, so both ports size private arrays and select passes alike. A new
 * option the kernels read is added here (and to the #error list above). */
#define PN_KERNEL_CONFIG(X) \
    X(PN_MASK_WORDS_MAX) X(PN_BVH_STACK) X(PN_ENABLE_REFERENCE) X(PN_ENABLE_RAYTRACE) X(PN_ENABLE_GEARS) \
    X(PN_ENABLE_SRT) X(PN_SRT_MAP_MAX) X(PN_ENABLE_OCCTEX) X(PN_OCCTEX_MAP_MAX) X(PN_ENABLE_MCSM) \
    X(PN_ENABLE_WEDGES)
#define PN_KFN static inline
#define PN_KFN_HOT static inline __attribute__((always_inline))
#define PN_KFN_COLD static __attribute__((noinline, cold))
#define PN_GLOBAL
#define PN_CONST const
/* __builtin_sqrtf is correctly rounded and needs no libm symbol on bare metal when built
 * with -fno-math-errno (it becomes vsqrt.f32 on Cortex-M7, sqrtss on x86). */
#define pn_ksqrt(x) __builtin_sqrtf(x)
#define pn_kfabs(x) __builtin_fabsf(x)
#define PN_KINF (__builtin_inff())
/* GCC/Clang builtin (like the two above): inline on x86 and on ARMv7-M (ldrex/strex), no
 * library call, so it stays freestanding. Relaxed: only the sum matters, and the caller's
 * parallel-for joins before anything reads it. */
#define pn_katomic_add(p, v) __atomic_fetch_add((p), (v), __ATOMIC_RELAXED)
#define pn_katomic_or(p, v) __atomic_fetch_or((p), (v), __ATOMIC_RELAXED)
/* Min (up = 0) or max (up = 1) by compare-and-swap (the same builtins): the old value. */
PN_KFN int32_t pn_katomic_iext(int32_t *p, int32_t v, int up)
{
    int32_t cur = __atomic_load_n(p, __ATOMIC_RELAXED);
    while ((up ? v > cur : v < cur) && !__atomic_compare_exchange_n(p, &cur, v, 1, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
    return cur;
}
#define pn_katomic_imin(p, v) pn_katomic_iext((p), (v), 0)
#define pn_katomic_imax(p, v) pn_katomic_iext((p), (v), 1)
/* Leading zero bits of a non-zero uint32_t (OpenCL's clz; lzcnt or bsr on x86, clz on
 * ARMv7-M): no library call either. */
#define pn_kclz(x) ((uint32_t)__builtin_clz((unsigned)(x)))
/* Four float lanes (GCC/Clang vector extension: + - * and the comparisons lane by lane,
 * correctly rounded like the scalar operations, a comparison giving -1 or 0 per lane), for
 * the loops a compiler may not vectorize well by itself: PN_KVEC4 where the target has
 * four-lane float SIMD (SSE on x86-64, NEON); elsewhere (Cortex-M) the plain loops, which
 * the vector code would only lower to the same scalar operations in more code. */
#if defined(__SSE2__) || defined(__ARM_NEON) || defined(__ARM_NEON__)
#define PN_KVEC4 1
typedef float pn_f4 __attribute__((vector_size(16)));
typedef int32_t pn_i4 __attribute__((vector_size(16)));
#define pn_f4_make(a, b, c, d) ((pn_f4){(a), (b), (c), (d)})
#define pn_f4_splat(x) ((pn_f4){(x), (x), (x), (x)})
/* The lanes of a comparison's result (-1 or 0 each) as bits 0-3. */
PN_KFN uint32_t pn_i4_bits(pn_i4 m)
{
    m = m & (pn_i4){1, 2, 4, 8};
    return (uint32_t)(m[0] | m[1] | m[2] | m[3]);
}
#else
#define PN_KVEC4 0
#endif
#endif

#endif
