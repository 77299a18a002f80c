/* pn_device.h - the port interface: a port is a small device queue (Blender Cycles'
 * DeviceQueue: enqueue a kernel over n work items, fill, copy, host/device sync), and
 * knows no algorithm. Every algorithm's frame is a sequence of these commands, written
 * once in src/ (docs/architecture.md); the port only carries them out.
 *
 * Memory: a port works on the context's arena. Pools are named by their host address in
 * the arena (ctx->base + offset); the kernels see them as offsets (pn_kpools). The scalar
 * port works in the arena itself. A device port mirrors it in one buffer: what the host
 * writes must be handed over (pn_dev_to_device) before a pass reads it, and what a pass
 * writes must be fetched (pn_dev_to_host) before the host reads it. Commands run in the
 * order given; pn_dev_to_host returns when the data is in host memory. Not installed. */
#ifndef PN_DEVICE_H
#define PN_DEVICE_H

#include "pn_internal.h"

/* Commands (pn_devcmd.op). */
enum {
    PN_DEV_RUN = 1,     /* pass `pass` over items [0, n) with *P and *K */
    PN_DEV_FILL,        /* n uint32 at a := value */
    PN_DEV_COPY,        /* `bytes` from b to a (no overlap) */
    PN_DEV_SCAN,        /* exclusive prefix sum of the n uint32 at a, in place, total to a[n] */
    PN_DEV_SORT_PAIRS,  /* n (key, value) uint32 pairs at a, keys < `keys`, values ascending
                           within each key (as a scatter in value order writes them): the
                           stable order by key. Out: values by key at b, offsets[keys + 1] at
                           c (the first pair of each key; c[keys] = n); d: `keys` uint32 of
                           scratch, and the pairs' 2 n words are scratch too (undefined
                           after). Any sort may be used: the output is the one ascending
                           (key, value) order */
    PN_DEV_SORT_RUNS,   /* the run of each key k < `keys` of the uint32 values at b,
                           [c[k], c[k + 1]) (offsets at c), sorted ascending in place: the
                           one order of a run whose slots atomics handed out in any order */
    PN_DEV_TO_HOST,     /* `bytes` at a: make them readable by the host */
    PN_DEV_TO_DEVICE,   /* `bytes` at a: the host wrote them; passes may read them */
    PN_DEV_FINISH       /* wait until every command given so far has completed */
};

typedef struct pn_devcmd {
    uint32_t op, pass, n, value, keys;
    const void *a, *b, *c, *d; /* arena addresses */
    size_t bytes;
    const pn_kpools *P;
    const pn_kparams *K;
} pn_devcmd;

/* Which scene a device port holds (kept by src/pn_frame.c: the scene is handed over only
 * when pn_scene_set changed it). */
typedef struct pn_port_scene {
    uint32_t version, valid, uploads;
} pn_port_scene;

/* A port: one entry point for every command. host_memory = 1: the port works in the
 * arena itself, so TO_HOST, TO_DEVICE and FINISH are no-ops and src/ skips them (and
 * `scene` may be NULL). */
struct pn_port {
    const char *name;
    uint32_t host_memory;
    pn_status (*exec)(void *self, pn_context *ctx, const pn_devcmd *cmd);
    void *self;
    pn_port_scene *scene;
};

/* The one call through a port's function pointer (in pn_context.c, beside pn_run and
 * pn_now, so that it is never inlined: tests/check_callgraph.c's "table" site). */
pn_status pn_dev_exec(const pn_port *port, pn_context *ctx, const pn_devcmd *cmd);

/* The commands as calls on a frame (fs->port, fs->P, fs->K). Each returns the port's
 * status (PN_E_DEVICE with a message when a device call failed). */
pn_status pn_dev_run(pn_frame_state *fs, uint32_t pass, uint32_t n);
pn_status pn_dev_fill(pn_frame_state *fs, const void *a, uint32_t n, uint32_t value);
pn_status pn_dev_copy(pn_frame_state *fs, const void *dst, const void *src, size_t bytes);
pn_status pn_dev_scan(pn_frame_state *fs, const uint32_t *a, uint32_t n);
pn_status pn_dev_sort_pairs(pn_frame_state *fs, uint32_t *pairs, uint32_t n, uint32_t keys, uint32_t *values,
                            uint32_t *offsets, uint32_t *scratch);
pn_status pn_dev_sort_runs(pn_frame_state *fs, uint32_t *values, const uint32_t *offsets, uint32_t keys);
pn_status pn_dev_to_host(pn_frame_state *fs, const void *a, size_t bytes);
pn_status pn_dev_to_device(pn_frame_state *fs, const void *a, size_t bytes);
/* The context's clock after every command so far has completed (pass timings). */
uint64_t pn_dev_timestamp(pn_frame_state *fs);
/* The arena offset of a pool address, for pn_kpools. */
uint64_t pn_dev_off(const pn_context *ctx, const void *p);

#endif
