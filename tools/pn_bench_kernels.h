/* pn_bench_kernels.h - the library's kernels/ compiled into the benchmark (the same
 * arithmetic as the scalar port: the tool is built with -ffp-contract=off like the core),
 * and the light set-up the core does in src/pn_frame.c, redone on the host. */
#ifndef PN_TOOLS_BENCH_KERNELS_H
#define PN_TOOLS_BENCH_KERNELS_H

#include "penumbra/penumbra.h"
#include "pn_reference.h" /* pn_predicate.h, pn_frustum_*, pn_tri_load */

/* Area light as the kernels see it: N = normalize(u x v), the frame's eps, a culling
 * slack, k samples per edge. */
void pn_bench_klight(const pn_light *l, uint32_t k, float eps, float cull_tol, pn_klight *kl);

#endif
