/* pn_opencl.c - the OpenCL port's set-up: device choice and checks, the program built
 * from the embedded kernels/ sources, the one device buffer that mirrors the arena, the
 * public API, and the launch and transfer helpers the passes use. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pn_cl_sources.h"
#include "pn_gears_pass.h"
#include "pn_opencl_internal.h"

#define PN_CL_MAX_PLATFORMS 16u
#define PN_CL_MAX_DEVICES 64u

static const char *const pn_cl_kernel_names[PN_CLK_COUNT] = {
#define PN_CL_NAME(id, name, local, args) #name,
    PN_CL_KERNELS(PN_CL_NAME)
#undef PN_CL_NAME
};
static const size_t pn_cl_local[PN_CLK_COUNT] = {
#define PN_CL_LOCAL(id, name, local, args) local,
    PN_CL_KERNELS(PN_CL_LOCAL)
#undef PN_CL_LOCAL
};
static const char *const pn_cl_args[PN_CLK_COUNT] = {
#define PN_CL_ARGS(id, name, local, args) args,
    PN_CL_KERNELS(PN_CL_ARGS)
#undef PN_CL_ARGS
};

/* ---- Errors -------------------------------------------------------------------------- */

const char *pn_cl_error_name(cl_int err)
{
    switch (err) {
#define PN_CL_E(name) case name: return #name;
        PN_CL_E(CL_SUCCESS)
        PN_CL_E(CL_DEVICE_NOT_FOUND)
        PN_CL_E(CL_DEVICE_NOT_AVAILABLE)
        PN_CL_E(CL_COMPILER_NOT_AVAILABLE)
        PN_CL_E(CL_MEM_OBJECT_ALLOCATION_FAILURE)
        PN_CL_E(CL_OUT_OF_RESOURCES)
        PN_CL_E(CL_OUT_OF_HOST_MEMORY)
        PN_CL_E(CL_PROFILING_INFO_NOT_AVAILABLE)
        PN_CL_E(CL_MEM_COPY_OVERLAP)
        PN_CL_E(CL_IMAGE_FORMAT_MISMATCH)
        PN_CL_E(CL_IMAGE_FORMAT_NOT_SUPPORTED)
        PN_CL_E(CL_BUILD_PROGRAM_FAILURE)
        PN_CL_E(CL_MAP_FAILURE)
        PN_CL_E(CL_MISALIGNED_SUB_BUFFER_OFFSET)
        PN_CL_E(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
        PN_CL_E(CL_COMPILE_PROGRAM_FAILURE)
        PN_CL_E(CL_LINKER_NOT_AVAILABLE)
        PN_CL_E(CL_LINK_PROGRAM_FAILURE)
        PN_CL_E(CL_DEVICE_PARTITION_FAILED)
        PN_CL_E(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
        PN_CL_E(CL_INVALID_VALUE)
        PN_CL_E(CL_INVALID_DEVICE_TYPE)
        PN_CL_E(CL_INVALID_PLATFORM)
        PN_CL_E(CL_INVALID_DEVICE)
        PN_CL_E(CL_INVALID_CONTEXT)
        PN_CL_E(CL_INVALID_QUEUE_PROPERTIES)
        PN_CL_E(CL_INVALID_COMMAND_QUEUE)
        PN_CL_E(CL_INVALID_HOST_PTR)
        PN_CL_E(CL_INVALID_MEM_OBJECT)
        PN_CL_E(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
        PN_CL_E(CL_INVALID_IMAGE_SIZE)
        PN_CL_E(CL_INVALID_SAMPLER)
        PN_CL_E(CL_INVALID_BINARY)
        PN_CL_E(CL_INVALID_BUILD_OPTIONS)
        PN_CL_E(CL_INVALID_PROGRAM)
        PN_CL_E(CL_INVALID_PROGRAM_EXECUTABLE)
        PN_CL_E(CL_INVALID_KERNEL_NAME)
        PN_CL_E(CL_INVALID_KERNEL_DEFINITION)
        PN_CL_E(CL_INVALID_KERNEL)
        PN_CL_E(CL_INVALID_ARG_INDEX)
        PN_CL_E(CL_INVALID_ARG_VALUE)
        PN_CL_E(CL_INVALID_ARG_SIZE)
        PN_CL_E(CL_INVALID_KERNEL_ARGS)
        PN_CL_E(CL_INVALID_WORK_DIMENSION)
        PN_CL_E(CL_INVALID_WORK_GROUP_SIZE)
        PN_CL_E(CL_INVALID_WORK_ITEM_SIZE)
        PN_CL_E(CL_INVALID_GLOBAL_OFFSET)
        PN_CL_E(CL_INVALID_EVENT_WAIT_LIST)
        PN_CL_E(CL_INVALID_EVENT)
        PN_CL_E(CL_INVALID_OPERATION)
        PN_CL_E(CL_INVALID_GL_OBJECT)
        PN_CL_E(CL_INVALID_BUFFER_SIZE)
        PN_CL_E(CL_INVALID_MIP_LEVEL)
        PN_CL_E(CL_INVALID_GLOBAL_WORK_SIZE)
        PN_CL_E(CL_INVALID_PROPERTY)
        PN_CL_E(CL_INVALID_IMAGE_DESCRIPTOR)
        PN_CL_E(CL_INVALID_COMPILER_OPTIONS)
        PN_CL_E(CL_INVALID_LINKER_OPTIONS)
        PN_CL_E(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef PN_CL_E
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    }
    return "unknown OpenCL error";
}

pn_status pn_cl_fail(pn_context *ctx, const char *what, cl_int err)
{
    char code[16];
    snprintf(code, sizeof(code), "%d", (int)err);
    return pn_fail(ctx, PN_E_DEVICE, "%s: %s (%s)", what, pn_cl_error_name(err), code);
}

static double pn_cl_ms(const struct timespec *t0)
{
    struct timespec t1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return (double)(t1.tv_sec - t0->tv_sec) * 1e3 + (double)(t1.tv_nsec - t0->tv_nsec) / 1e6;
}

/* ---- Device choice -------------------------------------------------------------------- */

typedef struct pn_cl_dev {
    cl_platform_id platform;
    cl_device_id device;
    unsigned pi, di;
    cl_device_type type;
    int pocl;
    char label[400]; /* "<platform> / <device>" */
} pn_cl_dev;

static int pn_cl_contains_nocase(const char *hay, const char *needle)
{
    size_t n = strlen(needle), i, j;
    for (i = 0; hay[i]; i++) {
        for (j = 0; j < n && hay[i + j] && tolower((unsigned char)hay[i + j]) == tolower((unsigned char)needle[j]); j++) {
        }
        if (j == n) return 1;
    }
    return n == 0;
}

/* Every device of every platform, in clinfo order. */
static pn_status pn_cl_list(pn_context *ctx, pn_cl_dev *list, unsigned cap, unsigned *count)
{
    cl_platform_id plats[PN_CL_MAX_PLATFORMS];
    cl_uint np = 0, p;
    cl_int err = clGetPlatformIDs(PN_CL_MAX_PLATFORMS, plats, &np);
    *count = 0;
    if (err != CL_SUCCESS || np == 0)
        return pn_cl_fail(ctx, "no OpenCL platform (Debian: apt install pocl-opencl-icd); clGetPlatformIDs",
                          err != CL_SUCCESS ? err : CL_DEVICE_NOT_FOUND);
    for (p = 0; p < np && p < PN_CL_MAX_PLATFORMS; p++) {
        cl_device_id devs[PN_CL_MAX_DEVICES];
        cl_uint nd = 0, d;
        char pname[160] = "";
        clGetPlatformInfo(plats[p], CL_PLATFORM_NAME, sizeof(pname) - 1, pname, NULL);
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, PN_CL_MAX_DEVICES, devs, &nd) != CL_SUCCESS) continue;
        for (d = 0; d < nd && d < PN_CL_MAX_DEVICES && *count < cap; d++) {
            pn_cl_dev *e = list + (*count)++;
            char dname[200] = "";
            clGetDeviceInfo(devs[d], CL_DEVICE_NAME, sizeof(dname) - 1, dname, NULL);
            clGetDeviceInfo(devs[d], CL_DEVICE_TYPE, sizeof(e->type), &e->type, NULL);
            e->platform = plats[p];
            e->device = devs[d];
            e->pi = p;
            e->di = d;
            e->pocl = pn_cl_contains_nocase(pname, "Portable Computing Language") || pn_cl_contains_nocase(pname, "pocl");
            snprintf(e->label, sizeof(e->label), "%s / %s", pname, dname);
        }
    }
    if (*count == 0) return pn_cl_fail(ctx, "no OpenCL device on any platform; clGetDeviceIDs", CL_DEVICE_NOT_FOUND);
    return PN_OK;
}

static pn_status pn_cl_pick(pn_context *ctx, const char *spec, pn_cl_dev *out)
{
    pn_cl_dev *list = (pn_cl_dev *)malloc(PN_CL_MAX_PLATFORMS * 4u * sizeof(pn_cl_dev));
    unsigned n = 0, i, pi, di;
    int pick = -1;
    char tail;
    pn_status st;
    if (!list) return pn_fail(ctx, PN_E_DEVICE, "OpenCL port: out of host memory");
    if ((st = pn_cl_list(ctx, list, PN_CL_MAX_PLATFORMS * 4u, &n)) != PN_OK) {
        free(list);
        return st;
    }
    if (spec && spec[0]) {
        if (sscanf(spec, "%u:%u%c", &pi, &di, &tail) == 2) {
            for (i = 0; i < n && pick < 0; i++)
                if (list[i].pi == pi && list[i].di == di) pick = (int)i;
        } else {
            for (i = 0; i < n && pick < 0; i++)
                if (pn_cl_contains_nocase(list[i].label, spec)) pick = (int)i;
        }
        if (pick < 0) {
            pn_fail(ctx, PN_E_DEVICE, "no OpenCL device matches '%s' (give \"P:D\" or part of \"%s\")", spec,
                    list[0].label);
            free(list);
            return PN_E_DEVICE;
        }
    } else {
        for (i = 0; i < n && pick < 0; i++)
            if (list[i].pocl && (list[i].type & CL_DEVICE_TYPE_CPU)) pick = (int)i;
        if (pick < 0) pick = 0;
    }
    *out = list[pick];
    free(list);
    return PN_OK;
}

/* What bit-identical results need of the device (NUMERICS in opencl.h). */
static pn_status pn_cl_check_device(pn_context *ctx, cl_device_id dev, const char *label)
{
    static const struct {
        cl_device_fp_config bit;
        const char *name;
    } need[] = {{CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT, "CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT"},
                {CL_FP_ROUND_TO_NEAREST, "CL_FP_ROUND_TO_NEAREST"},
                {CL_FP_DENORM, "CL_FP_DENORM"},
                {CL_FP_INF_NAN, "CL_FP_INF_NAN"}};
    cl_device_fp_config fp = 0;
    cl_bool little = CL_FALSE, compiler = CL_FALSE;
    const uint32_t one = 1u;
    int host_little = *(const unsigned char *)&one == 1u;
    cl_int err;
    size_t i;
    if ((err = clGetDeviceInfo(dev, CL_DEVICE_SINGLE_FP_CONFIG, sizeof(fp), &fp, NULL)) != CL_SUCCESS)
        return pn_cl_fail(ctx, "clGetDeviceInfo(CL_DEVICE_SINGLE_FP_CONFIG)", err);
    for (i = 0; i < sizeof(need) / sizeof(need[0]); i++)
        if (!(fp & need[i].bit))
            return pn_fail(ctx, PN_E_UNSUPPORTED,
                           "OpenCL device '%s' lacks %s in CL_DEVICE_SINGLE_FP_CONFIG: its results could differ "
                           "from the scalar port's",
                           label, need[i].name);
    if ((err = clGetDeviceInfo(dev, CL_DEVICE_ENDIAN_LITTLE, sizeof(little), &little, NULL)) != CL_SUCCESS)
        return pn_cl_fail(ctx, "clGetDeviceInfo(CL_DEVICE_ENDIAN_LITTLE)", err);
    if ((little == CL_TRUE) != host_little)
        return pn_fail(ctx, PN_E_UNSUPPORTED, "OpenCL device '%s' has the other byte order than the host", label);
    if ((err = clGetDeviceInfo(dev, CL_DEVICE_COMPILER_AVAILABLE, sizeof(compiler), &compiler, NULL)) != CL_SUCCESS)
        return pn_cl_fail(ctx, "clGetDeviceInfo(CL_DEVICE_COMPILER_AVAILABLE)", err);
    if (compiler != CL_TRUE)
        return pn_fail(ctx, PN_E_UNSUPPORTED, "OpenCL device '%s' has no compiler", label);
    return PN_OK;
}

/* ---- Program ---------------------------------------------------------------------------- */

static size_t pn_cl_arg_size(char kind)
{
    switch (kind) {
    case 'A': return sizeof(cl_mem);
    case 'P': return sizeof(pn_kpools);
    case 'V': return sizeof(pn_kview);
    case 'L': return sizeof(pn_klight);
    case 'S': return sizeof(pn_kshade);
    case 'F': return sizeof(pn_kfaces);
    case 'G': return sizeof(pn_kgrid);
    case 'T': return sizeof(pn_ktile);
    case 'u': return sizeof(cl_uint);
    case 'l': return sizeof(cl_ulong);
    }
    return 0;
}

static pn_status pn_cl_build(pn_opencl *cl)
{
    char opts[256], what[128];
    cl_int err;
    struct timespec t0;
    int k;
    snprintf(opts, sizeof(opts),
             "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt -DPN_MASK_WORDS_MAX=%uu -DPN_BVH_STACK=%uu",
             (unsigned)PN_MASK_WORDS_MAX, (unsigned)PN_BVH_STACK);
    cl->program = clCreateProgramWithSource(cl->clctx, PN_CL_SOURCE_COUNT, (const char **)pn_cl_sources, NULL, &err);
    if (err != CL_SUCCESS) return pn_cl_fail(cl->ctx, "clCreateProgramWithSource", err);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    err = clBuildProgram(cl->program, 1, &cl->device, opts, NULL, NULL);
    cl->build_ms = pn_cl_ms(&t0);
    if (err != CL_SUCCESS) {
        char log[200] = "";
        size_t len = 0, i;
        clGetProgramBuildInfo(cl->program, cl->device, CL_PROGRAM_BUILD_LOG, sizeof(log) - 1, log, &len);
        for (i = 0; log[i]; i++)
            if (log[i] == '\n') log[i] = ' ';
        snprintf(what, sizeof(what), "clBuildProgram (log: %.90s)", log);
        return pn_cl_fail(cl->ctx, what, err);
    }
    for (k = 0; k < PN_CLK_COUNT; k++) {
        cl->kernels[k] = clCreateKernel(cl->program, pn_cl_kernel_names[k], &err);
        if (err != CL_SUCCESS) {
            snprintf(what, sizeof(what), "clCreateKernel(%s)", pn_cl_kernel_names[k]);
            return pn_cl_fail(cl->ctx, what, err);
        }
    }
    return PN_OK;
}

/* Every kernel once, with zero counts (every work item returns at once): implementations
 * that compile work-group functions at the first launch (PoCL) do it here, so that
 * pn_opencl_get_info reports the whole build and the first frame runs at full speed. */
static pn_status pn_cl_warm_up(pn_opencl *cl)
{
    static const unsigned char zero[1024];
    struct timespec t0;
    int k;
    cl_int err;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (k = 0; k < PN_CLK_COUNT; k++) {
        const char *a;
        cl_uint i = 0;
        for (a = pn_cl_args[k]; *a; a++, i++) {
            err = *a == 'A' ? clSetKernelArg(cl->kernels[k], i, sizeof(cl_mem), &cl->arena)
                            : clSetKernelArg(cl->kernels[k], i, pn_cl_arg_size(*a), zero);
            if (err != CL_SUCCESS) {
                char what[128];
                snprintf(what, sizeof(what), "clSetKernelArg(%s, %u)", pn_cl_kernel_names[k], (unsigned)i);
                return pn_cl_fail(cl->ctx, what, err);
            }
        }
        err = clEnqueueNDRangeKernel(cl->queue, cl->kernels[k], 1, NULL, &pn_cl_local[k], &pn_cl_local[k], 0, NULL,
                                     NULL);
        if (err != CL_SUCCESS) return pn_cl_fail(cl->ctx, "clEnqueueNDRangeKernel (warm-up)", err);
    }
    if ((err = clFinish(cl->queue)) != CL_SUCCESS) return pn_cl_fail(cl->ctx, "clFinish (warm-up)", err);
    cl->warmup_ms = pn_cl_ms(&t0);
    return PN_OK;
}

/* ---- Launches and transfers ------------------------------------------------------------ */

cl_ulong pn_cl_off(const pn_opencl *cl, const void *p)
{
    return (cl_ulong)((const uint8_t *)p - cl->ctx->base);
}

pn_status pn_cl_run(pn_opencl *cl, int kernel, size_t n, const void *const *args)
{
    const char *a;
    cl_uint i = 0;
    size_t global;
    cl_int err = CL_SUCCESS;
    if (n == 0u) return PN_OK;
    for (a = pn_cl_args[kernel]; *a && err == CL_SUCCESS; a++, i++)
        err = clSetKernelArg(cl->kernels[kernel], i, pn_cl_arg_size(*a), args[i]);
    if (err == CL_SUCCESS) {
        global = (n + pn_cl_local[kernel] - 1u) / pn_cl_local[kernel] * pn_cl_local[kernel];
        err = clEnqueueNDRangeKernel(cl->queue, cl->kernels[kernel], 1, NULL, &global, &pn_cl_local[kernel], 0, NULL,
                                     NULL);
    }
    if (err != CL_SUCCESS) {
        char what[96];
        snprintf(what, sizeof(what), "running %s", pn_cl_kernel_names[kernel]);
        return pn_cl_fail(cl->ctx, what, err);
    }
    return PN_OK;
}

static pn_status pn_cl_transfer(pn_opencl *cl, int write, const void *host, size_t bytes, const char *what)
{
    cl_int err;
    char msg[96];
    if (bytes == 0u) return PN_OK;
    err = write ? clEnqueueWriteBuffer(cl->queue, cl->arena, CL_TRUE, (size_t)pn_cl_off(cl, host), bytes, host, 0,
                                       NULL, NULL)
                : clEnqueueReadBuffer(cl->queue, cl->arena, CL_TRUE, (size_t)pn_cl_off(cl, host), bytes,
                                      (void *)(uintptr_t)host, 0, NULL, NULL);
    if (err == CL_SUCCESS) return PN_OK;
    snprintf(msg, sizeof(msg), "%s %s", write ? "uploading" : "reading back", what);
    return pn_cl_fail(cl->ctx, msg, err);
}

pn_status pn_cl_read(pn_opencl *cl, const void *host, size_t bytes, const char *what)
{
    return pn_cl_transfer(cl, 0, host, bytes, what);
}

pn_status pn_cl_write(pn_opencl *cl, const void *host, size_t bytes, const char *what)
{
    return pn_cl_transfer(cl, 1, host, bytes, what);
}

pn_status pn_cl_fill_u32(pn_opencl *cl, const void *host, size_t count, uint32_t value, const char *what)
{
    cl_int err;
    if (count == 0u) return PN_OK;
    err = clEnqueueFillBuffer(cl->queue, cl->arena, &value, sizeof(value), (size_t)pn_cl_off(cl, host), count * 4u, 0,
                              NULL, NULL);
    if (err == CL_SUCCESS) return PN_OK;
    return pn_cl_fail(cl->ctx, what, err);
}

pn_status pn_cl_copy(pn_opencl *cl, const void *dst, const void *src, size_t bytes, const char *what)
{
    cl_int err;
    if (bytes == 0u) return PN_OK;
    err = clEnqueueCopyBuffer(cl->queue, cl->arena, cl->arena, (size_t)pn_cl_off(cl, src), (size_t)pn_cl_off(cl, dst),
                              bytes, 0, NULL, NULL);
    if (err == CL_SUCCESS) return PN_OK;
    return pn_cl_fail(cl->ctx, what, err);
}

pn_status pn_cl_scan(pn_opencl *cl, const uint32_t *a, uint32_t n, const uint32_t *scratch, uint32_t scratch_words)
{
    /* Enough blocks to spread over the device, few enough for one work item to scan the
     * partials, never more than the scratch holds. */
    cl_uint nb = n / 2048u + 1u, blk;
    cl_ulong oa = pn_cl_off(cl, a), op = pn_cl_off(cl, scratch);
    pn_status st;
    if (nb > 256u) nb = 256u;
    if (nb > scratch_words) nb = scratch_words;
    if (nb == 0u) return pn_fail(cl->ctx, PN_E_INTERNAL, "prefix sum without scratch");
    blk = (n + nb - 1u) / nb;
    if (blk == 0u) blk = 1u;
    if ((st = PN_CL_RUN(cl, PN_CLK_SCAN_SUM, nb, &cl->arena, &oa, &n, &blk, &op, &nb)) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_SCAN_PARTIALS, 1, &cl->arena, &oa, &n, &op, &nb)) != PN_OK)
        return st;
    return PN_CL_RUN(cl, PN_CLK_SCAN_APPLY, nb, &cl->arena, &oa, &n, &blk, &op, &nb);
}

void pn_cl_pools(const pn_opencl *cl, const pn_frame_state *fs, pn_kpools *P)
{
    const pn_context *ctx = cl->ctx;
    memset(P, 0, sizeof(*P));
    P->tris = pn_cl_off(cl, ctx->tris);
    P->flags = pn_cl_off(cl, ctx->flags);
    P->nodes = pn_cl_off(cl, ctx->nodes);
    P->index = pn_cl_off(cl, ctx->tri_index);
    P->depth = pn_cl_off(cl, fs->depth);
    P->tri_id = pn_cl_off(cl, fs->tri_id);
    P->pos = pn_cl_off(cl, fs->pos);
    P->nrm = pn_cl_off(cl, fs->nrm);
    P->vis = pn_cl_off(cl, fs->vis);
    P->rgba = pn_cl_off(cl, fs->rgba);
    P->rows = pn_cl_off(cl, fs->rows);
    P->counters = pn_cl_off(cl, fs->counters);
}

/* ---- API --------------------------------------------------------------------------------- */

void pn_opencl_options_default(pn_opencl_options *opt)
{
    if (opt) memset(opt, 0, sizeof(*opt));
}

pn_status pn_opencl_create(pn_context *ctx, const pn_opencl_options *opt, pn_opencl **out)
{
    pn_opencl *cl;
    pn_cl_dev dev;
    const char *spec = NULL;
    cl_int err;
    pn_status st;
    char what[128];
    if (!ctx) return PN_E_INVALID_ARG;
    if (!out) return pn_fail(ctx, PN_E_INVALID_ARG, "pn_opencl_create: out must not be NULL");
    if (opt && opt->device && opt->device[0]) spec = opt->device;
    else spec = getenv("PN_OPENCL_DEVICE");
    if ((st = pn_cl_pick(ctx, spec, &dev)) != PN_OK) return st;
    if ((st = pn_cl_check_device(ctx, dev.device, dev.label)) != PN_OK) return st;
    cl = (pn_opencl *)calloc(1, sizeof(*cl));
    if (!cl) return pn_fail(ctx, PN_E_DEVICE, "pn_opencl_create: out of host memory");
    cl->ctx = ctx;
    cl->platform = dev.platform;
    cl->device = dev.device;
    {
        /* "<device> (<platform>)" from "<platform> / <device>". */
        const char *sl = strstr(dev.label, " / ");
        if (sl) snprintf(cl->name, sizeof(cl->name), "%s (%.*s)", sl + 3, (int)(sl - dev.label), dev.label);
        else snprintf(cl->name, sizeof(cl->name), "%s", dev.label);
    }
    cl->clctx = clCreateContext(NULL, 1, &cl->device, NULL, NULL, &err);
    if (err != CL_SUCCESS) {
        st = pn_cl_fail(ctx, "clCreateContext", err);
        goto fail;
    }
    cl->queue = clCreateCommandQueue(cl->clctx, cl->device, 0, &err);
    if (err != CL_SUCCESS) {
        st = pn_cl_fail(ctx, "clCreateCommandQueue", err);
        goto fail;
    }
    /* The mirror of the arena: the same carve as pn_arena_size, from the aligned base. */
    cl->arena_bytes = ctx->layout.end;
    cl->arena = clCreateBuffer(cl->clctx, CL_MEM_READ_WRITE, cl->arena_bytes, NULL, &err);
    if (err == CL_SUCCESS) {
        /* Touch it all: allocation failures of lazy implementations show here, and the
         * mirror starts zeroed. */
        const uint8_t zero = 0;
        err = clEnqueueFillBuffer(cl->queue, cl->arena, &zero, 1, 0, cl->arena_bytes, 0, NULL, NULL);
        if (err == CL_SUCCESS) err = clFinish(cl->queue);
    }
    if (err != CL_SUCCESS) {
        cl_ulong max_alloc = 0;
        clGetDeviceInfo(cl->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof(max_alloc), &max_alloc, NULL);
        snprintf(what, sizeof(what), "clCreateBuffer(arena mirror, %llu bytes; device allows %llu)",
                 (unsigned long long)cl->arena_bytes, (unsigned long long)max_alloc);
        st = pn_cl_fail(ctx, what, err);
        goto fail;
    }
    if ((st = pn_cl_build(cl)) != PN_OK || (st = pn_cl_warm_up(cl)) != PN_OK) goto fail;
    pn_cl_port_init(cl);
    *out = cl;
    return PN_OK;
fail:
    pn_opencl_destroy(cl);
    return st;
}

pn_status pn_opencl_render(pn_opencl *cl, const pn_camera *camera, const pn_light *light,
                           const pn_frame_options *opt, pn_frame *out)
{
    if (!cl) return PN_E_INVALID_ARG;
    return pn_render_with(cl->ctx, &cl->port, camera, light, opt, out);
}

void pn_opencl_destroy(pn_opencl *cl)
{
    int k;
    if (!cl) return;
    for (k = 0; k < PN_CLK_COUNT; k++)
        if (cl->kernels[k]) clReleaseKernel(cl->kernels[k]);
    if (cl->program) clReleaseProgram(cl->program);
    if (cl->arena) clReleaseMemObject(cl->arena);
    if (cl->queue) clReleaseCommandQueue(cl->queue);
    if (cl->clctx) clReleaseContext(cl->clctx);
    free(cl);
}

const char *pn_opencl_device_name(const pn_opencl *cl) { return cl ? cl->name : ""; }

pn_status pn_opencl_get_info(const pn_opencl *cl, pn_opencl_info *out)
{
    if (!cl || !out) return PN_E_INVALID_ARG;
    memset(out, 0, sizeof(*out));
    out->build_ms = cl->build_ms;
    out->warmup_ms = cl->warmup_ms;
    out->buffer_bytes = cl->arena_bytes;
    out->scene_uploads = cl->scene_uploads;
    out->kernels = PN_CLK_COUNT;
    return PN_OK;
}
