/* pn_device.c - the port commands of pn_device.h as calls, all through pn_dev_exec. */
#include <string.h>

#include "pn_device.h"

static void pn_cmd(pn_devcmd *c, uint32_t op)
{
    memset(c, 0, sizeof(*c));
    c->op = op;
}

uint64_t pn_dev_off(const pn_context *ctx, const void *p)
{
    return (uint64_t)((const uint8_t *)p - ctx->base);
}

pn_status pn_dev_run(pn_frame_state *fs, uint32_t pass, uint32_t n)
{
    pn_devcmd c;
    if (n == 0u) return PN_OK;
    pn_cmd(&c, PN_DEV_RUN);
    c.pass = pass;
    c.n = n;
    c.P = &fs->P;
    c.K = &fs->K;
    return pn_dev_exec(fs->port, fs->ctx, &c);
}

pn_status pn_dev_fill(pn_frame_state *fs, const void *a, uint32_t n, uint32_t value)
{
    pn_devcmd c;
    if (n == 0u) return PN_OK;
    pn_cmd(&c, PN_DEV_FILL);
    c.a = a;
    c.n = n;
    c.value = value;
    return pn_dev_exec(fs->port, fs->ctx, &c);
}

pn_status pn_dev_copy(pn_frame_state *fs, const void *dst, const void *src, size_t bytes)
{
    pn_devcmd c;
    if (bytes == 0u) return PN_OK;
    pn_cmd(&c, PN_DEV_COPY);
    c.a = dst;
    c.b = src;
    c.bytes = bytes;
    return pn_dev_exec(fs->port, fs->ctx, &c);
}

pn_status pn_dev_scan(pn_frame_state *fs, const uint32_t *a, uint32_t n)
{
    pn_devcmd c;
    pn_cmd(&c, PN_DEV_SCAN);
    c.a = a;
    c.n = n;
    return pn_dev_exec(fs->port, fs->ctx, &c);
}

pn_status pn_dev_sort_pairs(pn_frame_state *fs, uint32_t *pairs, uint32_t n, uint32_t keys, uint32_t *values,
                            uint32_t *offsets, uint32_t *scratch)
{
    pn_devcmd c;
    pn_cmd(&c, PN_DEV_SORT_PAIRS);
    c.a = pairs;
    c.b = values;
    c.c = offsets;
    c.d = scratch;
    c.n = n;
    c.keys = keys;
    return pn_dev_exec(fs->port, fs->ctx, &c);
}

pn_status pn_dev_sort_runs(pn_frame_state *fs, uint32_t *values, const uint32_t *offsets, uint32_t keys)
{
    pn_devcmd c;
    pn_cmd(&c, PN_DEV_SORT_RUNS);
    c.b = values;
    c.c = offsets;
    c.keys = keys;
    return pn_dev_exec(fs->port, fs->ctx, &c);
}

static pn_status pn_dev_sync(pn_frame_state *fs, uint32_t op, const void *a, size_t bytes)
{
    pn_devcmd c;
    if (fs->port->host_memory || bytes == 0u) return PN_OK;
    pn_cmd(&c, op);
    c.a = a;
    c.bytes = bytes;
    return pn_dev_exec(fs->port, fs->ctx, &c);
}

pn_status pn_dev_to_host(pn_frame_state *fs, const void *a, size_t bytes)
{
    return pn_dev_sync(fs, PN_DEV_TO_HOST, a, bytes);
}

pn_status pn_dev_to_device(pn_frame_state *fs, const void *a, size_t bytes)
{
    return pn_dev_sync(fs, PN_DEV_TO_DEVICE, a, bytes);
}

uint64_t pn_dev_timestamp(pn_frame_state *fs)
{
    pn_devcmd c;
    /* Without a clock there is nothing to time: no device sync (issue 46: 10-12 finishes a
     * frame on the OpenCL port for timing nobody asked for). */
    if (!fs->ctx->clock) return 0u;
    if (!fs->port->host_memory) {
        pn_cmd(&c, PN_DEV_FINISH);
        /* A failure here shows again at the next command that reads results. */
        (void)pn_dev_exec(fs->port, fs->ctx, &c);
    }
    return pn_now(fs->ctx);
}
