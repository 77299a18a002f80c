/* pn_opencl_queue.c - the OpenCL port's device queue (src/pn_device.h): passes as kernel
 * launches over the arena mirror, fills and copies as buffer commands, transfers between
 * the host arena and its mirror at the same offsets, and the prefix sum and the sort by key
 * as kernels of kernels/pn_prims.cl. One in-order queue: commands complete in the order
 * given; reads back are blocking. Knows no algorithm. */
#include <stdio.h>
#include <string.h>

#include "pn_opencl_internal.h"

static size_t pn_cl_offset(const pn_opencl *cl, const void *p)
{
    return (size_t)((const uint8_t *)p - cl->ctx->base);
}

/* Launches kernel k over n items (rounded up to its work-group size; items past n do
 * nothing); its arguments are already set. */
static pn_status pn_cl_enqueue(pn_opencl *cl, uint32_t k, size_t n)
{
    size_t local = pn_cl_local[k], global = (n + local - 1u) / local * local;
    cl_int err = clEnqueueNDRangeKernel(cl->queue, cl->kernels[k], 1, NULL, &global, &local, 0, NULL, NULL);
    if (err != CL_SUCCESS) {
        char what[96];
        snprintf(what, sizeof(what), "running %s", pn_cl_kernel_names[k]);
        return pn_cl_fail(cl->ctx, what, err);
    }
    return PN_OK;
}

static pn_status pn_cl_arg_fail(pn_opencl *cl, uint32_t k, cl_uint i, cl_int err)
{
    char what[128];
    snprintf(what, sizeof(what), "clSetKernelArg(%s, %u)", pn_cl_kernel_names[k], (unsigned)i);
    return pn_cl_fail(cl->ctx, what, err);
}

/* A pass: (A, pn_kpools, pn_kparams, n). */
static pn_status pn_cl_run_pass(pn_opencl *cl, const pn_devcmd *c)
{
    cl_kernel kn;
    cl_uint n = c->n;
    cl_int err;
    if (c->pass >= PN_K_PASSES) return pn_fail(cl->ctx, PN_E_INTERNAL, "OpenCL port: no pass %u", c->pass);
    kn = cl->kernels[c->pass];
    if ((err = clSetKernelArg(kn, 0, sizeof(cl_mem), &cl->arena)) != CL_SUCCESS) return pn_cl_arg_fail(cl, c->pass, 0, err);
    if ((err = clSetKernelArg(kn, 1, sizeof(pn_kpools), c->P)) != CL_SUCCESS) return pn_cl_arg_fail(cl, c->pass, 1, err);
    if ((err = clSetKernelArg(kn, 2, sizeof(pn_kparams), c->K)) != CL_SUCCESS) return pn_cl_arg_fail(cl, c->pass, 2, err);
    if ((err = clSetKernelArg(kn, 3, sizeof(cl_uint), &n)) != CL_SUCCESS) return pn_cl_arg_fail(cl, c->pass, 3, err);
    return pn_cl_enqueue(cl, c->pass, n);
}

/* A primitive: its arguments from pointers to their values, of the kinds its letters say. */
static pn_status pn_cl_run_prim(pn_opencl *cl, uint32_t prim, size_t n, const void *const *args)
{
    uint32_t k = PN_K_PASSES + prim;
    const char *a;
    cl_uint i = 0;
    cl_int err;
    if (n == 0u) return PN_OK;
    for (a = pn_cl_prim_args[prim]; *a; a++, i++) {
        const void *v = *a == 'A' ? (const void *)&cl->arena : args[i];
        if ((err = clSetKernelArg(cl->kernels[k], i, pn_cl_arg_size(*a), v)) != CL_SUCCESS)
            return pn_cl_arg_fail(cl, k, i, err);
    }
    return pn_cl_enqueue(cl, k, n);
}
#define PN_CL_PRIM_RUN(cl, id, n, ...) \
    pn_cl_run_prim((cl), PN_CLP_##id, (n), (const void *const[]){NULL, __VA_ARGS__})

static pn_status pn_cl_fill(pn_opencl *cl, const void *a, size_t words, uint32_t value)
{
    cl_int err;
    if (words == 0u) return PN_OK;
    err = clEnqueueFillBuffer(cl->queue, cl->arena, &value, sizeof(value), pn_cl_offset(cl, a), words * 4u, 0, NULL,
                              NULL);
    return err == CL_SUCCESS ? PN_OK : pn_cl_fail(cl->ctx, "clEnqueueFillBuffer", err);
}

static pn_status pn_cl_copy(pn_opencl *cl, const void *dst, const void *src, size_t bytes)
{
    cl_int err;
    if (bytes == 0u) return PN_OK;
    err = clEnqueueCopyBuffer(cl->queue, cl->arena, cl->arena, pn_cl_offset(cl, src), pn_cl_offset(cl, dst), bytes, 0,
                              NULL, NULL);
    return err == CL_SUCCESS ? PN_OK : pn_cl_fail(cl->ctx, "clEnqueueCopyBuffer", err);
}

/* Exclusive prefix sum in three kernels over nb blocks: enough blocks to spread over the
 * device, few enough for one work item to scan the partials (in the port scratch pool). */
static pn_status pn_cl_scan(pn_opencl *cl, const uint32_t *a, uint32_t n)
{
    cl_uint nb = n / 2048u + 1u, blk, un = n;
    cl_ulong oa = pn_cl_offset(cl, a), op = pn_cl_offset(cl, cl->ctx->scratch);
    pn_status st;
    if (nb > PN_PORT_SCRATCH_WORDS) nb = PN_PORT_SCRATCH_WORDS;
    blk = (n + nb - 1u) / nb;
    if (blk == 0u) blk = 1u;
    if ((st = PN_CL_PRIM_RUN(cl, SCAN_SUM, nb, &oa, &un, &blk, &op, &nb)) != PN_OK ||
        (st = PN_CL_PRIM_RUN(cl, SCAN_PARTIALS, 1, &oa, &un, &op, &nb)) != PN_OK)
        return st;
    return PN_CL_PRIM_RUN(cl, SCAN_APPLY, nb, &oa, &un, &blk, &op, &nb);
}

/* Sort by key: histogram into the scratch counts, offsets = their prefix sum, every pair
 * into the next slot of its key with an atomic cursor, then each key's run sorted, with
 * the pairs' buffer (2 n words, dead once every value is placed) as the merge's scratch. */
static pn_status pn_cl_sort_pairs(pn_opencl *cl, const pn_devcmd *c)
{
    cl_ulong op = pn_cl_offset(cl, c->a), ov = pn_cl_offset(cl, c->b), oo = pn_cl_offset(cl, c->c);
    cl_ulong oc = pn_cl_offset(cl, c->d);
    cl_uint n = c->n, keys = c->keys;
    pn_status st;
    if ((st = pn_cl_fill(cl, c->d, keys, 0u)) != PN_OK || (st = PN_CL_PRIM_RUN(cl, PAIRS_HIST, n, &op, &n, &oc)) != PN_OK ||
        (st = pn_cl_copy(cl, c->c, c->d, (size_t)keys * 4u)) != PN_OK ||
        (st = pn_cl_scan(cl, (const uint32_t *)c->c, keys)) != PN_OK ||
        (st = pn_cl_copy(cl, c->d, c->c, (size_t)keys * 4u)) != PN_OK ||
        (st = PN_CL_PRIM_RUN(cl, PAIRS_FILL, n, &op, &n, &oc, &ov)) != PN_OK)
        return st;
    return PN_CL_PRIM_RUN(cl, PAIRS_MERGE_RUNS, keys, &oo, &keys, &ov, &op);
}

/* Each key's run of values sorted (the runs of a scatter by atomic cursors). */
static pn_status pn_cl_sort_runs(pn_opencl *cl, const pn_devcmd *c)
{
    cl_ulong oo = pn_cl_offset(cl, c->c), ov = pn_cl_offset(cl, c->b);
    cl_uint keys = c->keys;
    return PN_CL_PRIM_RUN(cl, PAIRS_SORT_RUNS, keys, &oo, &keys, &ov);
}

static pn_status pn_cl_transfer(pn_opencl *cl, int write, const void *host, size_t bytes)
{
    cl_int err;
    if (bytes == 0u) return PN_OK;
    err = write ? clEnqueueWriteBuffer(cl->queue, cl->arena, CL_TRUE, pn_cl_offset(cl, host), bytes, host, 0, NULL,
                                       NULL)
                : clEnqueueReadBuffer(cl->queue, cl->arena, CL_TRUE, pn_cl_offset(cl, host), bytes,
                                      (void *)(uintptr_t)host, 0, NULL, NULL);
    if (err == CL_SUCCESS) return PN_OK;
    return pn_cl_fail(cl->ctx, write ? "clEnqueueWriteBuffer" : "clEnqueueReadBuffer", err);
}

pn_status pn_cl_exec(void *self, pn_context *ctx, const pn_devcmd *c)
{
    pn_opencl *cl = (pn_opencl *)self;
    cl_int err;
    (void)ctx;
    switch (c->op) {
    case PN_DEV_RUN: return pn_cl_run_pass(cl, c);
    case PN_DEV_FILL: return pn_cl_fill(cl, c->a, c->n, c->value);
    case PN_DEV_COPY: return pn_cl_copy(cl, c->a, c->b, c->bytes);
    case PN_DEV_SCAN: return pn_cl_scan(cl, (const uint32_t *)c->a, c->n);
    case PN_DEV_SORT_PAIRS: return pn_cl_sort_pairs(cl, c);
    case PN_DEV_SORT_RUNS: return pn_cl_sort_runs(cl, c);
    case PN_DEV_TO_HOST: return pn_cl_transfer(cl, 0, c->a, c->bytes);
    case PN_DEV_TO_DEVICE: return pn_cl_transfer(cl, 1, c->a, c->bytes);
    case PN_DEV_FINISH:
        err = clFinish(cl->queue);
        return err == CL_SUCCESS ? PN_OK : pn_cl_fail(cl->ctx, "clFinish", err);
    }
    return pn_fail(cl->ctx, PN_E_INTERNAL, "OpenCL port: no command %u", c->op);
}
