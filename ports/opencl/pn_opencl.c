/* pn_opencl.c - the OpenCL port's set-up: device choice and checks, the program built
 * from the embedded kernels/ sources, the one device buffer that mirrors the arena, the
 * public API, and the launch and transfer helpers the passes use. */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <math.h> /* sqrtf: the numerics probe's host side */
#include <stdio.h>
#include <stdlib.h> /* getenv */
#include <string.h>
#include <time.h>

#include "pn_cl_sources.h"
#include "pn_opencl_internal.h"

#define PN_CL_MAX_PLATFORMS 16u
#define PN_CL_MAX_DEVICES 64u

const char *const pn_cl_kernel_names[PN_CL_KERNEL_COUNT] = {
#define PN_CL_PASS_NAME(id, name, local, grain) "pn_k_" #name,
#define PN_CL_PRIM_NAME(id, name, local, args) #name,
    PN_PASSES(PN_CL_PASS_NAME) PN_CL_PRIMS(PN_CL_PRIM_NAME)
#undef PN_CL_PASS_NAME
#undef PN_CL_PRIM_NAME
};
const size_t pn_cl_local[PN_CL_KERNEL_COUNT] = {
#define PN_CL_PASS_LOCAL(id, name, local, grain) local,
#define PN_CL_PRIM_LOCAL(id, name, local, args) local,
    PN_PASSES(PN_CL_PASS_LOCAL) PN_CL_PRIMS(PN_CL_PRIM_LOCAL)
#undef PN_CL_PASS_LOCAL
#undef PN_CL_PRIM_LOCAL
};
const char *const pn_cl_prim_args[PN_CLP_COUNT] = {
#define PN_CL_PRIM_ARGS(id, name, local, args) args,
    PN_CL_PRIMS(PN_CL_PRIM_ARGS)
#undef PN_CL_PRIM_ARGS
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
    char pname[160], dname[200];
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

/* The keyword of a device type, as DEVICE CHOICE spells it. */
static const char *pn_cl_type_word(cl_device_type t)
{
    if (t & CL_DEVICE_TYPE_GPU) return "gpu";
    if (t & CL_DEVICE_TYPE_CPU) return "cpu";
    if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
    return "other";
}

/* "gpu", "cpu" or "accelerator" (any case), alone or followed by ":N" (the N-th device of
 * that type, from 0, in clinfo order): 1 and the type and N; 0 for any other string. */
static int pn_cl_type_spec(const char *spec, cl_device_type *type, unsigned *nth)
{
    static const struct {
        const char *word;
        cl_device_type type;
    } kw[] = {{"gpu", CL_DEVICE_TYPE_GPU}, {"cpu", CL_DEVICE_TYPE_CPU}, {"accelerator", CL_DEVICE_TYPE_ACCELERATOR}};
    size_t k, j;
    for (k = 0; k < sizeof(kw) / sizeof(kw[0]); k++) {
        const char *w = kw[k].word, *rest;
        unsigned long n = 0;
        for (j = 0; w[j] && tolower((unsigned char)spec[j]) == w[j]; j++) {
        }
        if (w[j]) continue;
        rest = spec + j;
        if (*rest == ':') {
            if (!rest[1]) return 0;
            for (rest++; *rest >= '0' && *rest <= '9'; rest++) {
                n = n * 10u + (unsigned long)(*rest - '0');
                if (n > 65535u) return 0;
            }
        }
        if (*rest) return 0;
        *type = kw[k].type;
        *nth = (unsigned)n;
        return 1;
    }
    return 0;
}

/* Every device of every platform, in clinfo order: calls visit(e, arg) for each until it
 * returns non-zero, which stops the walk. No list is kept (no heap). ctx may be NULL (the
 * status alone). */
typedef int (*pn_cl_visit_fn)(const pn_cl_dev *e, void *arg);

static pn_status pn_cl_each(pn_context *ctx, pn_cl_visit_fn visit, void *arg, unsigned *count)
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
        for (d = 0; d < nd && d < PN_CL_MAX_DEVICES; d++) {
            pn_cl_dev e;
            memset(&e, 0, sizeof(e));
            clGetDeviceInfo(devs[d], CL_DEVICE_NAME, sizeof(e.dname) - 1, e.dname, NULL);
            clGetDeviceInfo(devs[d], CL_DEVICE_TYPE, sizeof(e.type), &e.type, NULL);
            e.platform = plats[p];
            e.device = devs[d];
            e.pi = p;
            e.di = d;
            e.pocl = pn_cl_contains_nocase(pname, "Portable Computing Language") || pn_cl_contains_nocase(pname, "pocl");
            snprintf(e.pname, sizeof(e.pname), "%s", pname);
            snprintf(e.label, sizeof(e.label), "%s / %s", pname, e.dname);
            (*count)++;
            if (visit(&e, arg)) return PN_OK;
        }
    }
    if (*count == 0) return pn_cl_fail(ctx, "no OpenCL device on any platform; clGetDeviceIDs", CL_DEVICE_NOT_FOUND);
    return PN_OK;
}

typedef struct pn_cl_pick_state {
    const char *spec;
    unsigned pi, di, nth, seen;
    cl_device_type type;
    int by_index, by_type, found, first_set;
    pn_cl_dev pick, first;
    char list[200]; /* "P:D name (type), ..." for the message when a type has no device */
} pn_cl_pick_state;

static int pn_cl_pick_visit(const pn_cl_dev *e, void *arg)
{
    pn_cl_pick_state *s = (pn_cl_pick_state *)arg;
    int match;
    size_t len = strlen(s->list);
    if (!s->first_set) {
        s->first = *e;
        s->first_set = 1;
    }
    snprintf(s->list + len, sizeof(s->list) - len, "%s%u:%u %s (%s)", len ? ", " : "", e->pi, e->di, e->dname,
             pn_cl_type_word(e->type));
    if (s->by_type) match = (e->type & s->type) != 0 && s->seen++ == s->nth;
    else if (s->spec) match = s->by_index ? (e->pi == s->pi && e->di == s->di) : pn_cl_contains_nocase(e->label, s->spec);
    else match = e->pocl && (e->type & CL_DEVICE_TYPE_CPU);
    if (match) {
        s->pick = *e;
        s->found = 1;
    }
    /* A type keyword looks at every device, so that its message can list them all. */
    return match && !s->by_type;
}

static pn_status pn_cl_pick(pn_context *ctx, const char *spec, pn_cl_dev *out)
{
    pn_cl_pick_state s;
    unsigned n = 0;
    char tail;
    pn_status st;
    memset(&s, 0, sizeof(s));
    s.spec = spec && spec[0] ? spec : NULL;
    if (s.spec && pn_cl_type_spec(s.spec, &s.type, &s.nth)) s.by_type = 1;
    else if (s.spec && sscanf(s.spec, "%u:%u%c", &s.pi, &s.di, &tail) == 2) s.by_index = 1;
    if ((st = pn_cl_each(ctx, pn_cl_pick_visit, &s, &n)) != PN_OK) return st;
    if (!s.found && s.by_type) {
        char which[48] = "";
        if (strchr(s.spec, ':')) snprintf(which, sizeof(which), " number %u (from 0)", s.nth);
        return pn_fail(ctx, PN_E_DEVICE, "no OpenCL %s device%s for '%s'; the devices found: %s",
                       pn_cl_type_word(s.type), which, s.spec, s.list);
    }
    if (!s.found && s.spec)
        return pn_fail(ctx, PN_E_DEVICE, "no OpenCL device matches '%s' (give \"P:D\" or part of \"%s\")", s.spec,
                       s.first.label);
    *out = s.found ? s.pick : s.first;
    return PN_OK;
}

/* What bit-identical results need of the device (NUMERICS in opencl.h), asked of its
 * properties: PN_OK, or the status and its message in why (ctx-free, for
 * pn_opencl_devices too). */
static pn_status pn_cl_device_problem(cl_device_id dev, const char *label, char *why, size_t cap)
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
    char cver[256] = ""; /* the whole string: a short buffer fails the query */
    unsigned major = 0, minor = 0;
    cl_int err;
    size_t i;
#define PN_CL_QUERY_FAIL(what)                                                                                    \
    do {                                                                                                          \
        snprintf(why, cap, "%s: %s (%d)", what, pn_cl_error_name(err), (int)err);                                 \
        return PN_E_DEVICE;                                                                                       \
    } while (0)
    why[0] = 0;
    if ((err = clGetDeviceInfo(dev, CL_DEVICE_SINGLE_FP_CONFIG, sizeof(fp), &fp, NULL)) != CL_SUCCESS)
        PN_CL_QUERY_FAIL("clGetDeviceInfo(CL_DEVICE_SINGLE_FP_CONFIG)");
    for (i = 0; i < sizeof(need) / sizeof(need[0]); i++)
        if (!(fp & need[i].bit)) {
            snprintf(why, cap,
                     "OpenCL device '%s' lacks %s in CL_DEVICE_SINGLE_FP_CONFIG: its results could differ "
                     "from the scalar port's",
                     label, need[i].name);
            return PN_E_UNSUPPORTED;
        }
    if ((err = clGetDeviceInfo(dev, CL_DEVICE_ENDIAN_LITTLE, sizeof(little), &little, NULL)) != CL_SUCCESS)
        PN_CL_QUERY_FAIL("clGetDeviceInfo(CL_DEVICE_ENDIAN_LITTLE)");
    if ((little == CL_TRUE) != host_little) {
        snprintf(why, cap, "OpenCL device '%s' has the other byte order than the host", label);
        return PN_E_UNSUPPORTED;
    }
    if ((err = clGetDeviceInfo(dev, CL_DEVICE_COMPILER_AVAILABLE, sizeof(compiler), &compiler, NULL)) != CL_SUCCESS)
        PN_CL_QUERY_FAIL("clGetDeviceInfo(CL_DEVICE_COMPILER_AVAILABLE)");
    if (compiler != CL_TRUE) {
        snprintf(why, cap, "OpenCL device '%s' has no compiler", label);
        return PN_E_UNSUPPORTED;
    }
    /* A pass's arguments (the arena, pn_kpools, pn_kparams, n) by value. */
    {
        size_t most = 0, args = sizeof(cl_mem) + sizeof(pn_kpools) + sizeof(pn_kparams) + sizeof(cl_uint);
        if ((err = clGetDeviceInfo(dev, CL_DEVICE_MAX_PARAMETER_SIZE, sizeof(most), &most, NULL)) != CL_SUCCESS)
            PN_CL_QUERY_FAIL("clGetDeviceInfo(CL_DEVICE_MAX_PARAMETER_SIZE)");
        if (most < args) {
            snprintf(why, cap, "OpenCL device '%s' takes %llu bytes of kernel arguments, the passes pass %llu", label,
                     (unsigned long long)most, (unsigned long long)args);
            return PN_E_UNSUPPORTED;
        }
    }
    /* The kernels are OpenCL C 1.2 (-cl-std=CL1.2): "OpenCL C <major>.<minor> ...". */
    err = clGetDeviceInfo(dev, CL_DEVICE_OPENCL_C_VERSION, sizeof(cver) - 1, cver, NULL);
    if (err != CL_SUCCESS || sscanf(cver, "OpenCL C %u.%u", &major, &minor) != 2 || major * 100u + minor < 102u) {
        snprintf(why, cap, "OpenCL device '%s' compiles '%.40s', the kernels need OpenCL C 1.2", label,
                 err == CL_SUCCESS ? cver : "no OpenCL C version");
        return PN_E_UNSUPPORTED;
    }
#undef PN_CL_QUERY_FAIL
    return PN_OK;
}

static pn_status pn_cl_check_device(pn_context *ctx, cl_device_id dev, const char *label)
{
    char why[256];
    pn_status st = pn_cl_device_problem(dev, label, why, sizeof(why));
    return st == PN_OK ? PN_OK : pn_fail(ctx, st, "%s", why);
}

/* ---- Device list ------------------------------------------------------------------------- */

typedef struct pn_cl_list_state {
    pn_opencl_device *out;
    unsigned cap, n;
} pn_cl_list_state;

static int pn_cl_list_visit(const pn_cl_dev *e, void *arg)
{
    pn_cl_list_state *s = (pn_cl_list_state *)arg;
    pn_opencl_device *d;
    if (s->n < s->cap) {
        d = &s->out[s->n];
        memset(d, 0, sizeof(*d));
        snprintf(d->spec, sizeof(d->spec), "%u:%u", e->pi, e->di);
        snprintf(d->type, sizeof(d->type), "%s", pn_cl_type_word(e->type));
        snprintf(d->platform, sizeof(d->platform), "%s", e->pname);
        snprintf(d->name, sizeof(d->name), "%s", e->dname);
        {
            /* The whole string (a short buffer fails the query), cut to the field. */
            char v[1024] = "";
            clGetDeviceInfo(e->device, CL_DEVICE_VERSION, sizeof(v) - 1, v, NULL);
            snprintf(d->version, sizeof(d->version), "%s", v);
        }
        d->usable = pn_cl_device_problem(e->device, e->label, d->problem, sizeof(d->problem)) == PN_OK;
    }
    s->n++;
    return 0;
}

pn_status pn_opencl_devices(pn_opencl_device *out, unsigned cap, unsigned *count)
{
    pn_cl_list_state s;
    unsigned n = 0;
    pn_status st;
    if (!count || (!out && cap)) return PN_E_INVALID_ARG;
    *count = 0;
    s.out = out;
    s.cap = cap;
    s.n = 0;
    st = pn_cl_each(NULL, pn_cl_list_visit, &s, &n);
    *count = s.n;
    return st;
}

/* ---- Program ---------------------------------------------------------------------------- */

size_t pn_cl_arg_size(char kind)
{
    switch (kind) {
    case 'A': return sizeof(cl_mem);
    case 'P': return sizeof(pn_kpools);
    case 'K': return sizeof(pn_kparams);
    case 'u': return sizeof(cl_uint);
    case 'l': return sizeof(cl_ulong);
    }
    return 0;
}

/* ---- Numerics probe ---------------------------------------------------------------------- *
 * What the device's properties promise (pn_cl_device_problem), checked on the device: one
 * small kernel, built with the passes in the same program and with the same options, does
 * the arithmetic the passes rely on over PN_CL_PROBE_ITEMS hashed inputs, and the host does
 * the same in C (compiled, like the scalar port, without contraction). Each check sums a hash
 * of every item's result bits with integer atomics (any order gives the same sum); a sum that
 * differs from the host's means the device's results would differ from the scalar port's,
 * and the device is refused before a frame runs. */

#define PN_CL_PROBE_ITEMS 4096u
#define PN_CL_PROBE_CHECKS 5u
/* 2^-140: products of the inputs (2^-20 .. 2^21 in magnitude) with it are denormal or tiny. */
#define PN_CL_PROBE_TINY 7.17464814e-43f

static const char *const pn_cl_probe_what[PN_CL_PROBE_CHECKS] = {
    "a*b - p with p = a*b is not 0 (it contracts into fma despite FP_CONTRACT OFF)",
    "a*b + c*d (contraction)",
    "a/b is not correctly rounded",
    "sqrt is not correctly rounded",
    "denormal results are flushed to zero",
};

static const char pn_cl_probe_source[] =
    "#pragma OPENCL FP_CONTRACT OFF\n"
    "uint pn_probe_hash(uint x)\n"
    "{\n"
    "    x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;\n"
    "    return x;\n"
    "}\n"
    "float pn_probe_float(uint i)\n"
    "{\n"
    "    uint h = pn_probe_hash(i * 0x9e3779b9u + 0x632be5abu);\n"
    "    return as_float((h & 0x807FFFFFu) | ((107u + (h >> 23) % 41u) << 23));\n"
    "}\n"
    "__kernel void pn_k_numerics_probe(__global uint *out, uint n, float tiny)\n"
    "{\n"
    "    uint i = (uint)get_global_id(0);\n"
    "    float a, b, c, d, p;\n"
    "    if (i >= n) return;\n"
    "    a = pn_probe_float(4u * i);\n"
    "    b = pn_probe_float(4u * i + 1u);\n"
    "    c = pn_probe_float(4u * i + 2u);\n"
    "    d = pn_probe_float(4u * i + 3u);\n"
    "    p = a * b;\n"
    "    atomic_add(&out[0], pn_probe_hash(as_uint(a * b - p) ^ i));\n"
    "    atomic_add(&out[1], pn_probe_hash(as_uint(a * b + c * d) ^ i));\n"
    "    atomic_add(&out[2], pn_probe_hash(as_uint(a / b) ^ i));\n"
    "    atomic_add(&out[3], pn_probe_hash(as_uint(sqrt(fabs(c))) ^ i));\n"
    "    atomic_add(&out[4], pn_probe_hash(as_uint(d * tiny) ^ i));\n"
    "}\n";

static uint32_t pn_cl_probe_hash(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

static float pn_cl_probe_float(uint32_t i)
{
    uint32_t h = pn_cl_probe_hash(i * 0x9e3779b9u + 0x632be5abu), b = (h & 0x807FFFFFu) | ((107u + (h >> 23) % 41u) << 23);
    float f;
    memcpy(&f, &b, sizeof(f));
    return f;
}

static uint32_t pn_cl_probe_bits(float f, uint32_t i)
{
    uint32_t b;
    memcpy(&b, &f, sizeof(b));
    return pn_cl_probe_hash(b ^ i);
}

/* The host's sums: the scalar port's arithmetic (C, no contraction); tiny is volatile so that
 * its products are computed at run time, as the scalar port's would be. */
static void pn_cl_probe_host(uint32_t sums[PN_CL_PROBE_CHECKS])
{
    uint32_t i;
    memset(sums, 0, PN_CL_PROBE_CHECKS * sizeof(uint32_t));
    for (i = 0; i < PN_CL_PROBE_ITEMS; i++) {
        volatile float tiny = PN_CL_PROBE_TINY;
        float a = pn_cl_probe_float(4u * i), b = pn_cl_probe_float(4u * i + 1u);
        float c = pn_cl_probe_float(4u * i + 2u), d = pn_cl_probe_float(4u * i + 3u);
        float p = a * b;
        sums[0] += pn_cl_probe_bits(a * b - p, i);
        sums[1] += pn_cl_probe_bits(a * b + c * d, i);
        sums[2] += pn_cl_probe_bits(a / b, i);
        sums[3] += pn_cl_probe_bits(sqrtf(c < 0.0f ? -c : c), i);
        sums[4] += pn_cl_probe_bits(d * tiny, i);
    }
}

static pn_status pn_cl_probe(pn_opencl *cl)
{
    uint32_t dev[PN_CL_PROBE_CHECKS], host[PN_CL_PROBE_CHECKS];
    const cl_uint n = PN_CL_PROBE_ITEMS;
    const cl_float tiny = PN_CL_PROBE_TINY;
    size_t global = PN_CL_PROBE_ITEMS;
    cl_kernel kn;
    cl_mem buf;
    cl_int err;
    pn_status st = PN_OK;
    unsigned k;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    memset(dev, 0, sizeof(dev));
    kn = clCreateKernel(cl->program, "pn_k_numerics_probe", &err);
    if (err != CL_SUCCESS) return pn_cl_fail(cl->ctx, "clCreateKernel(pn_k_numerics_probe)", err);
    buf = clCreateBuffer(cl->clctx, CL_MEM_READ_WRITE, sizeof(dev), NULL, &err);
    if (err != CL_SUCCESS) {
        clReleaseKernel(kn);
        return pn_cl_fail(cl->ctx, "clCreateBuffer(numerics probe)", err);
    }
    err = clEnqueueWriteBuffer(cl->queue, buf, CL_TRUE, 0, sizeof(dev), dev, 0, NULL, NULL);
    if (err == CL_SUCCESS) err = clSetKernelArg(kn, 0, sizeof(cl_mem), &buf);
    if (err == CL_SUCCESS) err = clSetKernelArg(kn, 1, sizeof(cl_uint), &n);
    if (err == CL_SUCCESS) err = clSetKernelArg(kn, 2, sizeof(cl_float), &tiny);
    if (err == CL_SUCCESS) err = clEnqueueNDRangeKernel(cl->queue, kn, 1, NULL, &global, NULL, 0, NULL, NULL);
    if (err == CL_SUCCESS) err = clEnqueueReadBuffer(cl->queue, buf, CL_TRUE, 0, sizeof(dev), dev, 0, NULL, NULL);
    clReleaseMemObject(buf);
    clReleaseKernel(kn);
    if (err != CL_SUCCESS) return pn_cl_fail(cl->ctx, "running the numerics probe", err);
    pn_cl_probe_host(host);
    for (k = 0; k < PN_CL_PROBE_CHECKS && st == PN_OK; k++)
        if (dev[k] != host[k])
            st = pn_fail(cl->ctx, PN_E_UNSUPPORTED,
                         "OpenCL device '%s' fails the numerics probe: %s, so its results would differ from the "
                         "scalar port's",
                         cl->name, pn_cl_probe_what[k]);
    cl->probe_ms = pn_cl_ms(&t0);
    return st;
}

static pn_status pn_cl_build(pn_opencl *cl)
{
    char opts[320], what[128];
    cl_int err;
    struct timespec t0;
    int k;
    {
        /* The kernels' configuration, as the host compiled it (PN_KERNEL_CONFIG). */
        static const struct {
            const char *name;
            unsigned value;
        } cfg[] = {
#define PN_CL_CFG(m) {#m, (unsigned)(m)},
            PN_KERNEL_CONFIG(PN_CL_CFG)
#undef PN_CL_CFG
        };
        size_t i, len;
        snprintf(opts, sizeof(opts), "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt");
        for (i = 0; i < sizeof(cfg) / sizeof(cfg[0]); i++) {
            len = strlen(opts);
            snprintf(opts + len, sizeof(opts) - len, " -D%s=%uu", cfg[i].name, cfg[i].value);
        }
    }
    {
        const char *src[PN_CL_SOURCE_COUNT + 1];
        for (k = 0; k < PN_CL_SOURCE_COUNT; k++) src[k] = pn_cl_sources[k];
        src[PN_CL_SOURCE_COUNT] = pn_cl_probe_source;
        cl->program = clCreateProgramWithSource(cl->clctx, PN_CL_SOURCE_COUNT + 1, src, NULL, &err);
    }
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
    for (k = 0; k < PN_CL_KERNEL_COUNT; k++) {
        size_t most = 0;
        cl->kernels[k] = clCreateKernel(cl->program, pn_cl_kernel_names[k], &err);
        if (err != CL_SUCCESS) {
            snprintf(what, sizeof(what), "clCreateKernel(%s)", pn_cl_kernel_names[k]);
            return pn_cl_fail(cl->ctx, what, err);
        }
        /* The work-group size the port launches it with must fit what the device can run
         * of this kernel (registers, private memory): a clear refusal, not a launch error. */
        err = clGetKernelWorkGroupInfo(cl->kernels[k], cl->device, CL_KERNEL_WORK_GROUP_SIZE, sizeof(most), &most,
                                       NULL);
        if (err == CL_SUCCESS && most < pn_cl_local[k])
            return pn_fail(cl->ctx, PN_E_UNSUPPORTED,
                           "OpenCL device '%s' runs kernel %s in work groups of at most %z items; the port "
                           "launches %z",
                           cl->name, pn_cl_kernel_names[k], (unsigned long long)most,
                           (unsigned long long)pn_cl_local[k]);
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
    for (k = 0; k < PN_CL_KERNEL_COUNT; k++) {
        const char *a;
        cl_uint i = 0;
        for (a = k < PN_K_PASSES ? "APKu" : pn_cl_prim_args[k - PN_K_PASSES]; *a; a++, i++) {
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

/* ---- API --------------------------------------------------------------------------------- */

void pn_opencl_options_default(pn_opencl_options *opt)
{
    if (opt) memset(opt, 0, sizeof(*opt));
}

/* The state must fit the block PN_OPENCL_BYTES promises, at any alignment of it. */
typedef char pn_cl_state_fits[(sizeof(struct pn_opencl) + 63u <= PN_OPENCL_BYTES) ? 1 : -1];

size_t pn_opencl_size(void) { return sizeof(struct pn_opencl) + 63u; }

pn_status pn_opencl_create(pn_context *ctx, const pn_opencl_options *opt, void *memory, size_t bytes,
                           pn_opencl **out)
{
    pn_opencl *cl;
    pn_cl_dev dev;
    const char *spec = NULL;
    cl_int err;
    pn_status st;
    char what[128];
    if (!ctx) return PN_E_INVALID_ARG;
    if (!out || !memory) return pn_fail(ctx, PN_E_INVALID_ARG, "pn_opencl_create: memory and out must not be NULL");
    if (bytes < pn_opencl_size())
        return pn_fail(ctx, PN_E_ARENA_TOO_SMALL, "pn_opencl_create: the port's block is %z bytes, it needs %z",
                       (unsigned long long)bytes, (unsigned long long)pn_opencl_size());
    if (opt && opt->device && opt->device[0]) spec = opt->device;
    else spec = getenv("PN_OPENCL_DEVICE");
    if ((st = pn_cl_pick(ctx, spec, &dev)) != PN_OK) return st;
    if ((st = pn_cl_check_device(ctx, dev.device, dev.label)) != PN_OK) return st;
    cl = (pn_opencl *)(void *)((uint8_t *)memory + ((64u - ((uintptr_t)memory & 63u)) & 63u));
    memset(cl, 0, sizeof(*cl));
    cl->memory = memory;
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
    if ((st = pn_cl_build(cl)) != PN_OK || (st = pn_cl_probe(cl)) != PN_OK || (st = pn_cl_warm_up(cl)) != PN_OK)
        goto fail;
    cl->port.name = "opencl";
    cl->port.host_memory = 0;
    cl->port.exec = pn_cl_exec;
    cl->port.self = cl;
    cl->port.scene = &cl->scene;
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

pn_status pn_opencl_visibility_points(pn_opencl *cl, const pn_light *light, const pn_frame_options *opt,
                                      const float *points, const float *normals, const uint32_t *tri_ids, uint32_t n,
                                      float *out)
{
    if (!cl) return PN_E_INVALID_ARG;
    return pn_points_with(cl->ctx, &cl->port, light, opt, points, normals, tri_ids, n, out);
}

void *pn_opencl_destroy(pn_opencl *cl)
{
    int k;
    if (!cl) return NULL;
    for (k = 0; k < PN_CL_KERNEL_COUNT; k++)
        if (cl->kernels[k]) clReleaseKernel(cl->kernels[k]);
    if (cl->program) clReleaseProgram(cl->program);
    if (cl->arena) clReleaseMemObject(cl->arena);
    if (cl->queue) clReleaseCommandQueue(cl->queue);
    if (cl->clctx) clReleaseContext(cl->clctx);
    return cl->memory;
}

const char *pn_opencl_device_name(const pn_opencl *cl) { return cl ? cl->name : ""; }

pn_status pn_opencl_get_info(const pn_opencl *cl, pn_opencl_info *out)
{
    if (!cl || !out) return PN_E_INVALID_ARG;
    memset(out, 0, sizeof(*out));
    out->build_ms = cl->build_ms;
    out->warmup_ms = cl->warmup_ms;
    out->probe_ms = cl->probe_ms;
    out->buffer_bytes = cl->arena_bytes;
    out->scene_uploads = cl->scene.uploads;
    out->kernels = PN_CL_KERNEL_COUNT;
    return PN_OK;
}
