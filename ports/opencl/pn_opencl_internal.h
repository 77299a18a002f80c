/* pn_opencl_internal.h - the OpenCL port's state and its kernels. Not installed. Host
 * code: may call the OpenCL runtime and libc, but takes no heap memory of its own (the
 * state lives in the caller's block, pn_opencl_create). */
#ifndef PN_OPENCL_INTERNAL_H
#define PN_OPENCL_INTERNAL_H

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include "penumbra/opencl.h"
#include "pn_device.h"
#include "pn_passes.h"

/* The port's own kernels (kernels/pn_prims.cl): the primitives that run on the device,
 * with their arguments, one letter each: A the arena buffer, u uint, l ulong (what the .cl
 * signatures say; a mismatch fails clSetKernelArg in the warm-up). The passes
 * (kernels/pn_passes.h) all take (A, pn_kpools, pn_kparams, uint n). */
#define PN_CL_PRIMS(X)                                 \
    X(SCAN_SUM, pn_k_scan_sum, 1, "Aluulu")            \
    X(SCAN_PARTIALS, pn_k_scan_partials, 1, "Alulu")   \
    X(SCAN_APPLY, pn_k_scan_apply, 1, "Aluulu")        \
    X(PAIRS_HIST, pn_k_pairs_hist, 64, "Alul")         \
    X(PAIRS_FILL, pn_k_pairs_fill, 64, "Alull")        \
    X(PAIRS_SORT_RUNS, pn_k_pairs_sort_runs, 16, "Alul")    \
    X(PAIRS_MERGE_RUNS, pn_k_pairs_merge_runs, 16, "Alull")

#define PN_CL_PRIM_ENUM(id, name, local, args) PN_CLP_##id,
enum { PN_CL_PRIMS(PN_CL_PRIM_ENUM) PN_CLP_COUNT };
#undef PN_CL_PRIM_ENUM

/* Kernel k of the program: the passes first (PN_K_*), then the primitives. */
#define PN_CL_KERNEL_COUNT (PN_K_PASSES + PN_CLP_COUNT)
#define PN_CL_PRIM(id) (PN_K_PASSES + PN_CLP_##id)

struct pn_opencl {
    void *memory; /* the caller's block, as given to pn_opencl_create */
    pn_context *ctx;
    pn_port port; /* the queue; port.self points back here */
    pn_port_scene scene;
    cl_platform_id platform;
    cl_device_id device;
    cl_context clctx;
    cl_command_queue queue;
    cl_program program;
    cl_kernel kernels[PN_CL_KERNEL_COUNT];
    cl_mem arena;        /* mirrors ctx->base .. ctx->base + layout.end */
    size_t arena_bytes;
    double build_ms, warmup_ms, probe_ms;
    char name[512];
};

/* pn_opencl.c */
extern const char *const pn_cl_kernel_names[PN_CL_KERNEL_COUNT];
extern const size_t pn_cl_local[PN_CL_KERNEL_COUNT];
extern const char *const pn_cl_prim_args[PN_CLP_COUNT];
size_t pn_cl_arg_size(char kind);
/* Records "<what>: <CL error name> (<code>)" as PN_E_DEVICE in the context. */
pn_status pn_cl_fail(pn_context *ctx, const char *what, cl_int err);

/* pn_opencl_queue.c: the port's command entry (pn_port.exec). */
pn_status pn_cl_exec(void *self, pn_context *ctx, const pn_devcmd *cmd);

#endif
