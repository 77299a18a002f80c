/* penumbra/opencl.h - the OpenCL port: the same passes as pn_render(), run as OpenCL
 * kernels built from the same kernels/ source, byte for byte the same results.
 *
 * WHAT IT IS
 *   A separate static library (penumbra_opencl), built only where OpenCL headers and an
 *   ICD loader exist; the core library never links OpenCL. It binds to one pn_context:
 *   the device holds ONE buffer that mirrors the context's arena (the same pools at the
 *   same offsets, sized by the same carve as pn_arena_size), the scene is uploaded when
 *   pn_scene_set changed it, and every frame's results are read back into the host arena,
 *   so the pn_frame of pn_opencl_render points into the caller's memory exactly as with
 *   pn_render. Kernel sources are compiled into the library; nothing is read from disk.
 *
 * NUMERICS
 *   Kernels are built with -cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt and
 *   FP_CONTRACT OFF; they use no relaxed math, no float atomics, and nothing whose result
 *   depends on the order work items run in. A device must report correctly rounded
 *   divide/sqrt, round to nearest, denormals and inf/NaN for single precision, the host's
 *   endianness, a compiler, OpenCL C 1.2 or later and room for a pass's arguments
 *   (CL_DEVICE_MAX_PARAMETER_SIZE), and run every kernel in work groups of the size the port
 *   launches (CL_KERNEL_WORK_GROUP_SIZE), or pn_opencl_create returns PN_E_UNSUPPORTED
 *   saying which is missing. The kernels need no extension (32-bit integer atomics on
 *   global memory are core OpenCL C 1.1). Then a numerics probe runs on the device: a*b - p
 *   with p = a*b (contraction), a*b + c*d, a/b, sqrt and denormal products over 4096 hashed
 *   inputs, compared bit for bit (through order-independent sums of hashes) with the same
 *   arithmetic in C on the host; a device that differs (a compiler that contracts despite
 *   FP_CONTRACT OFF, a division that is not correctly rounded although the device says it
 *   is, denormals flushed) gets PN_E_UNSUPPORTED naming the check, before any frame runs.
 *   The probe catches what a device's properties promise and its compiler breaks; the
 *   cross-port tests (test_crossport, test_golden --port opencl) prove the bytes on it.
 *
 * DEVICE CHOICE (first that applies)
 *   1. pn_opencl_options.device, if not NULL and not empty;
 *   2. the environment variable PN_OPENCL_DEVICE, if set and not empty;
 *   3. the first CPU device of a PoCL platform ("Portable Computing Language"), else the
 *      first device of the first platform that has one.
 *   A device string is one of, in this order:
 *   - a device type: "gpu", "cpu" or "accelerator" (any case), the first device of that
 *     CL_DEVICE_TYPE in clinfo order; "gpu:N" (likewise "cpu:N", "accelerator:N") the N-th
 *     one, from 0. No such device: PN_E_DEVICE, the message listing the devices found
 *     ("P:D name (type)"). The type picks the device; the checks below still apply to it.
 *   - "P:D" (platform index, device index, as clinfo -l lists them);
 *   - text matched, ignoring case, against "<platform name> / <device name>" (the first
 *     device that contains it).
 *   pn_opencl_devices lists what is there, with the type and the index of each.
 *
 * MEMORY
 *   The port's state lives in a block the caller hands to pn_opencl_create (size query:
 *   pn_opencl_size, or PN_OPENCL_BYTES for a static block); the port calls no allocator
 *   (the OpenCL runtime's own allocations are its business). Device memory is one buffer
 *   of the arena's size. PoCL caches compiled kernels on disk (POCL_CACHE_DIR).
 *
 * THREADS
 *   As for pn_context: one call at a time per context, and the port counts as a user of
 *   its context (do not render with the scalar port on another thread meanwhile). */
#ifndef PENUMBRA_OPENCL_H
#define PENUMBRA_OPENCL_H

#include "penumbra/penumbra.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pn_opencl pn_opencl;

typedef struct pn_opencl_options {
    const char *device; /* device string (see DEVICE CHOICE) or NULL; copied, not kept */
} pn_opencl_options;

/* No device string: PN_OPENCL_DEVICE or the default device. */
void pn_opencl_options_default(pn_opencl_options *opt);

/* Bytes of caller memory the port's own state needs, at any alignment (the port calls no
 * allocator: like the core, it lives in memory the caller owns). PN_OPENCL_BYTES is a
 * compile-time bound of it, for a static block. */
#define PN_OPENCL_BYTES 4096u
size_t pn_opencl_size(void);

/* Picks the device, checks it, builds the kernels (and runs each once on an empty range so
 * that implementations that compile per launch, like PoCL, have compiled everything) and
 * creates the device buffer. The port's state goes into `memory` (bytes >= pn_opencl_size(),
 * any alignment, caller-owned, must outlive the port; its contents are the port's until
 * pn_opencl_destroy and unspecified after a failure). opt may be NULL (defaults). On PN_OK
 * *out is a new port bound to ctx, which must outlive it. Statuses: PN_E_INVALID_ARG (NULL
 * ctx, memory or out), PN_E_ARENA_TOO_SMALL (bytes < pn_opencl_size()),
 * PN_E_DEVICE (no platform or device, no device matching the device string, a failing
 * OpenCL call: the message names the call, the OpenCL error and its code, e.g.
 * "clCreateBuffer(arena, 123456 bytes): CL_MEM_OBJECT_ALLOCATION_FAILURE (-4)"; a kernel
 * build error: the message starts the build log), PN_E_UNSUPPORTED (the device lacks a
 * capability listed under NUMERICS, or the arena exceeds its largest buffer).
 * Messages are in pn_last_error(ctx). *out is written only on PN_OK. */
pn_status pn_opencl_create(pn_context *ctx, const pn_opencl_options *opt, void *memory, size_t bytes,
                           pn_opencl **out);

/* pn_render() on the device: the same validation, statuses and results (byte for byte),
 * plus PN_E_INVALID_ARG for a NULL port and PN_E_DEVICE when an OpenCL call fails. */
pn_status pn_opencl_render(pn_opencl *cl, const pn_camera *camera, const pn_light *light,
                           const pn_frame_options *opt, pn_frame *out);

/* pn_visibility_points() on the device: the same checks, statuses and results (byte for
 * byte), plus PN_E_INVALID_ARG for a NULL port and PN_E_DEVICE when an OpenCL call fails. */
pn_status pn_opencl_visibility_points(pn_opencl *cl, const pn_light *light, const pn_frame_options *opt,
                                      const float *points, const float *normals, const uint32_t *tri_ids, uint32_t n,
                                      float *out);

/* Releases the device objects. Returns the block given to pn_opencl_create (the caller's
 * to reuse or free), or NULL for NULL. */
void *pn_opencl_destroy(pn_opencl *cl);

/* "<device name> (<platform name>)"; "" for NULL. Valid until pn_opencl_destroy. */
const char *pn_opencl_device_name(const pn_opencl *cl);

typedef struct pn_opencl_info {
    double build_ms;       /* clBuildProgram, wall clock */
    double warmup_ms;      /* the first launch of every kernel (per-launch JIT, PoCL) */
    double probe_ms;       /* the numerics probe (NUMERICS), its first launch included */
    uint64_t buffer_bytes; /* the device buffer: the arena's carved size */
    uint32_t scene_uploads;  /* scenes uploaded so far (one per changed scene) */
    uint32_t kernels;        /* kernels in the program */
} pn_opencl_info;

/* Statuses: PN_E_INVALID_ARG (NULL). */
pn_status pn_opencl_get_info(const pn_opencl *cl, pn_opencl_info *out);

/* One OpenCL device as pn_opencl_devices reports it. */
typedef struct pn_opencl_device {
    char spec[24];      /* "P:D", a device string that picks exactly this device */
    char type[16];      /* "gpu", "cpu", "accelerator" or "other" (the type keywords) */
    char platform[160]; /* CL_PLATFORM_NAME */
    char name[200];     /* CL_DEVICE_NAME */
    char version[64];   /* CL_DEVICE_VERSION */
    int usable;         /* 1: its properties pass the checks of NUMERICS (the numerics probe
                         * and the kernel build run in pn_opencl_create only) */
    char problem[256];  /* when usable is 0: why, as pn_opencl_create would say it */
} pn_opencl_device;

/* Every OpenCL device of every platform, in clinfo order: the first `cap` into out[] (the
 * caller's array; out may be NULL when cap is 0), the number there is into *count. Needs no
 * context and builds nothing. Statuses: PN_E_INVALID_ARG (count NULL, or out NULL with cap
 * > 0), PN_E_DEVICE (no OpenCL platform or no device: *count is 0). */
pn_status pn_opencl_devices(pn_opencl_device *out, unsigned cap, unsigned *count);

#ifdef __cplusplus
}
#endif
#endif
