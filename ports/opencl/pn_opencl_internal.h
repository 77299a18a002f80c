/* pn_opencl_internal.h - the OpenCL port's device state and its launch helpers. Not
 * installed. Host code: may call the OpenCL runtime, libc and malloc. */
#ifndef PN_OPENCL_INTERNAL_H
#define PN_OPENCL_INTERNAL_H

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include "penumbra/opencl.h"
#include "pn_internal.h"
#include "pn_kpools.h"

/* Every kernel of the program: its name, the work-group size it is launched with, and its
 * arguments, one letter each: A the arena buffer, P pn_kpools, V pn_kview, L pn_klight,
 * S pn_kshade, F pn_kfaces, G pn_kgrid, T pn_ktile, u uint, l ulong (what the .cl
 * signatures say; a mismatch fails clSetKernelArg in pn_opencl_create's warm-up).
 * Sizes are fixed, so the set of compiled work-group functions is too (PoCL compiles one
 * per kernel and size at the first launch; pn_opencl_create does those launches). Work
 * items that loop over a whole row or band get small groups so that rows spread over the
 * cores. */
#define PN_CL_KERNELS(X)                                   \
    X(GBUFFER_CLEAR, pn_k_gbuffer_clear, 64, "APu")        \
    X(RASTER_ROWS, pn_k_raster_rows, 64, "VAPu")           \
    X(RASTER_BAND, pn_k_raster_band, 1, "VAPu")            \
    X(GBUFFER_RESOLVE, pn_k_gbuffer_resolve, 64, "VAP")    \
    X(PER_PIXEL, pn_k_per_pixel, 16, "LuAPuu")             \
    X(SHADE, pn_k_shade, 64, "VLSAPu")                     \
    X(SCAN_SUM, pn_k_scan_sum, 1, "Aluulu")                \
    X(SCAN_PARTIALS, pn_k_scan_partials, 1, "Alulu")       \
    X(SCAN_APPLY, pn_k_scan_apply, 1, "Aluulu")            \
    X(GEARS_ORIGINS, pn_k_gears_origins, 1, "LAPuu")       \
    X(GEARS_PROJECT, pn_k_gears_project, 1, "LGAPuu")      \
    X(GEARS_PIXEL_CELLS, pn_k_gears_pixel_cells, 64, "LFAPu") \
    X(GEARS_TRI_RECTS, pn_k_gears_tri_rects, 64, "FLAPu")  \
    X(GEARS_ROW_PAIRS, pn_k_gears_row_pairs, 64, "FAPu")   \
    X(GEARS_ROW_CELLS, pn_k_gears_row_cells, 64, "TuAPu")  \
    X(GEARS_COUNT, pn_k_gears_count, 64, "TuAPu")          \
    X(GEARS_SCATTER, pn_k_gears_scatter, 64, "TuAPu")      \
    X(GEARS_CELL_HIST, pn_k_gears_cell_hist, 64, "APu")    \
    X(GEARS_CELL_FILL, pn_k_gears_cell_fill, 64, "APu")    \
    X(GEARS_CELL_SORT, pn_k_gears_cell_sort, 16, "APu")    \
    X(GEARS_MASKS, pn_k_gears_masks, 16, "LTuuAPuu")

#define PN_CL_ENUM(id, name, local, args) PN_CLK_##id,
enum { PN_CL_KERNELS(PN_CL_ENUM) PN_CLK_COUNT };
#undef PN_CL_ENUM

struct pn_opencl {
    pn_context *ctx;
    pn_port port; /* the pass table; port.self points back here */
    cl_platform_id platform;
    cl_device_id device;
    cl_context clctx;
    cl_command_queue queue;
    cl_program program;
    cl_kernel kernels[PN_CLK_COUNT];
    cl_mem arena;        /* mirrors ctx->base .. ctx->base + layout.end */
    size_t arena_bytes;
    uint32_t scene_version; /* ctx->scene_version last uploaded */
    uint32_t scene_valid;
    uint32_t scene_uploads;
    double build_ms, warmup_ms;
    char name[512];
};

/* pn_opencl.c */
const char *pn_cl_error_name(cl_int err);
/* Records "<what>: <CL error name> (<code>)" as PN_E_DEVICE in the context. */
pn_status pn_cl_fail(pn_context *ctx, const char *what, cl_int err);
/* Byte offset of an arena address (a pool pointer from the context or the frame). */
cl_ulong pn_cl_off(const pn_opencl *cl, const void *p);
/* The offsets of every pool the frame carved (the GEARS ones are filled in later). */
void pn_cl_pools(const pn_opencl *cl, const pn_frame_state *fs, pn_kpools *P);
/* Sets the kernel's arguments from pointers to their values (args[i] for argument i, of
 * the kind its letter says) and runs it over n work items (rounded up to its work-group
 * size; kernels ignore the rest). n == 0 enqueues nothing. PN_CL_RUN lists the pointers. */
pn_status pn_cl_run(pn_opencl *cl, int kernel, size_t n, const void *const *args);
#define PN_CL_RUN(cl, kernel, n, ...) pn_cl_run((cl), (kernel), (n), (const void *const[]){__VA_ARGS__})
pn_status pn_cl_read(pn_opencl *cl, const void *host, size_t bytes, const char *what);
pn_status pn_cl_write(pn_opencl *cl, const void *host, size_t bytes, const char *what);
pn_status pn_cl_fill_u32(pn_opencl *cl, const void *host, size_t count, uint32_t value, const char *what);
pn_status pn_cl_copy(pn_opencl *cl, const void *dst, const void *src, size_t bytes, const char *what);
/* Exclusive prefix sum of the n uint32 at `a` (arena address) in place, total to a[n];
 * `scratch` is an arena region of scratch_words uint32 free for the duration. */
pn_status pn_cl_scan(pn_opencl *cl, const uint32_t *a, uint32_t n, const uint32_t *scratch, uint32_t scratch_words);

/* pn_opencl_passes.c: the pass table (cl->port) */
void pn_cl_port_init(pn_opencl *cl);

/* pn_opencl_gears.c */
pn_status pn_cl_gears(pn_opencl *cl, pn_context *ctx, pn_frame_state *fs, pn_kpools *P);

#endif
