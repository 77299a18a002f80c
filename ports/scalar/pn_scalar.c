/* pn_scalar.c - the scalar port: the device queue of src/pn_device.h in C, on the arena
 * itself. A pass is a loop over its work items calling the kernels/ entry function
 * compiled as C, in tasks of `grain` items (kernels/pn_passes.h) handed to the caller's
 * parallel-for if there is one, and so is the sort of each key's run; the prefix sum and
 * the sort by key run on the calling thread. Items write disjoint memory or add integers
 * atomically, so the result does not depend on how tasks are scheduled. Knows no algorithm: the pass table is generated. */
#include <string.h>

#include "pn_device.h"
#include "pn_passes.h"
#include "pn_sort.h"

typedef struct pn_sc_launch {
    PN_GLOBAL uint8_t *A;
    const pn_kpools *P;
    const pn_kparams *K;
    uint32_t n;
} pn_sc_launch;

/* One task function per pass: items [begin * grain, min(end * grain, n)). */
#define PN_SC_TASK(id, name, local, grain)                                         \
    static void pn_sc_##name(void *task, uint32_t begin, uint32_t end)             \
    {                                                                              \
        const pn_sc_launch *l = (const pn_sc_launch *)task;                        \
        uint32_t i = begin * (uint32_t)(grain), e = end * (uint32_t)(grain);       \
        if (e > l->n || e < i) e = l->n;                                           \
        for (; i < e; i++) pn_e_##name(l->A, l->P, l->K, i);                       \
    }
PN_PASSES(PN_SC_TASK)
#undef PN_SC_TASK

static pn_status pn_sc_run(pn_context *ctx, const pn_devcmd *c)
{
    pn_sc_launch l;
    l.A = ctx->base;
    l.P = c->P;
    l.K = c->K;
    l.n = c->n;
    switch (c->pass) {
#define PN_SC_CASE(id, name, local, grain)                                                  \
    case PN_K_##id:                                                                         \
        pn_run(ctx, (c->n + (uint32_t)(grain) - 1u) / (uint32_t)(grain), pn_sc_##name, &l); \
        return PN_OK;
        PN_PASSES(PN_SC_CASE)
#undef PN_SC_CASE
    }
    return pn_fail(ctx, PN_E_INTERNAL, "scalar port: no pass %u", c->pass);
}

/* Counting sort by key: stable, so values that ascend within each key stay so. */
static void pn_sc_sort_pairs(const pn_devcmd *c)
{
    const uint32_t *pairs = (const uint32_t *)c->a;
    uint32_t *values = (uint32_t *)(uintptr_t)c->b, *off = (uint32_t *)(uintptr_t)c->c;
    uint32_t *cur = (uint32_t *)(uintptr_t)c->d, p, k, acc = 0;
    memset(cur, 0, (size_t)c->keys * 4u);
    for (p = 0; p < c->n; p++) cur[pairs[(size_t)p * 2u]]++;
    for (k = 0; k < c->keys; k++) {
        uint32_t n = cur[k];
        off[k] = acc;
        cur[k] = acc;
        acc += n;
    }
    off[c->keys] = acc;
    for (p = 0; p < c->n; p++) values[cur[pairs[(size_t)p * 2u]]++] = pairs[(size_t)p * 2u + 1u];
}

/* Each key's run, sorted ascending (pn_sort_u32: one pass over a run already in order, as
 * GEARS' scatter in one task writes it, PN_ONE_TASK), in tasks of PN_SC_SORT_KEYS keys on
 * the caller's parallel-for: the runs are disjoint, so any schedule sorts them alike. When
 * the scatter ran in tasks on two threads, its runs came out interleaved and their sort on
 * the calling thread was the frame's serial part (the dragon at 512x512: 2,380 ms on two
 * threads, 2,537 on one). */
#define PN_SC_SORT_KEYS 64u
static void pn_sc_sort_task(void *task, uint32_t begin, uint32_t end)
{
    const pn_devcmd *c = (const pn_devcmd *)task;
    uint32_t *values = (uint32_t *)(uintptr_t)c->b, k, e = end * PN_SC_SORT_KEYS;
    const uint32_t *off = (const uint32_t *)c->c;
    if (e > c->keys) e = c->keys;
    for (k = begin * PN_SC_SORT_KEYS; k < e; k++) pn_sort_u32(values + off[k], off[k + 1u] - off[k]);
}

static void pn_sc_sort_runs(pn_context *ctx, const pn_devcmd *c)
{
    pn_run(ctx, (c->keys + PN_SC_SORT_KEYS - 1u) / PN_SC_SORT_KEYS, pn_sc_sort_task, (void *)(uintptr_t)c);
}

static pn_status pn_sc_exec(void *self, pn_context *ctx, const pn_devcmd *c)
{
    (void)self;
    switch (c->op) {
    case PN_DEV_RUN: return pn_sc_run(ctx, c);
    case PN_DEV_FILL: {
        uint32_t *a = (uint32_t *)(uintptr_t)c->a, i;
        for (i = 0; i < c->n; i++) a[i] = c->value;
        return PN_OK;
    }
    case PN_DEV_COPY: memcpy((void *)(uintptr_t)c->a, c->b, c->bytes); return PN_OK;
    case PN_DEV_SCAN: {
        uint32_t *a = (uint32_t *)(uintptr_t)c->a, i, run = 0;
        for (i = 0; i < c->n; i++) {
            uint32_t v = a[i];
            a[i] = run;
            run += v;
        }
        a[c->n] = run;
        return PN_OK;
    }
    case PN_DEV_SORT_PAIRS: pn_sc_sort_pairs(c); return PN_OK;
    case PN_DEV_SORT_RUNS: pn_sc_sort_runs(ctx, c); return PN_OK;
    case PN_DEV_TO_HOST:
    case PN_DEV_TO_DEVICE:
    case PN_DEV_FINISH: return PN_OK; /* the arena is the device memory */
    }
    return pn_fail(ctx, PN_E_INTERNAL, "scalar port: no command %u", c->op);
}

/* No state: one constant port serves every context. */
static const pn_port pn_port_scalar = {"scalar", 1u, pn_sc_exec, NULL, NULL};

pn_status pn_render(pn_context *ctx, const pn_camera *camera, const pn_light *light,
                    const pn_frame_options *opt, pn_frame *out)
{
    return pn_render_with(ctx, &pn_port_scalar, camera, light, opt, out);
}

pn_status pn_visibility_points(pn_context *ctx, const pn_light *light, const pn_frame_options *opt,
                               const float *points, const float *normals, const uint32_t *tri_ids, uint32_t n,
                               float *out)
{
    return pn_points_with(ctx, &pn_port_scalar, light, opt, points, normals, tri_ids, n, out);
}
