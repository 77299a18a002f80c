/* pn_context.c - statuses and messages, execution hooks, statistics. */
#include <stdarg.h>
#include <string.h>

#include "pn_device.h"
#include "pn_algorithms.h"
#include "pn_internal.h"

const char *pn_status_str(pn_status status)
{
    switch (status) {
    case PN_OK: return "PN_OK: success";
    case PN_E_INVALID_ARG: return "PN_E_INVALID_ARG: NULL pointer or option out of range";
    case PN_E_ARENA_TOO_SMALL: return "PN_E_ARENA_TOO_SMALL: arena smaller than pn_arena_size()";
    case PN_E_LIMIT: return "PN_E_LIMIT: count, size or coordinate exceeds a limit";
    case PN_E_NONFINITE: return "PN_E_NONFINITE: NaN or infinite value";
    case PN_E_INDEX_RANGE: return "PN_E_INDEX_RANGE: triangle index >= vertex count";
    case PN_E_LIGHT_DEGENERATE: return "PN_E_LIGHT_DEGENERATE: exactly one light edge is zero";
    case PN_E_LIGHT_NOT_ORTHO: return "PN_E_LIGHT_NOT_ORTHO: light edges are not orthogonal";
    case PN_E_CAMERA: return "PN_E_CAMERA: degenerate camera";
    case PN_E_IMAGE_SIZE: return "PN_E_IMAGE_SIZE: zero image width or height";
    case PN_E_NO_SCENE: return "PN_E_NO_SCENE: no scene set";
    case PN_E_UNSUPPORTED: return "PN_E_UNSUPPORTED: not compiled in, or not offered for this request";
    case PN_E_POOL_EXHAUSTED: return "PN_E_POOL_EXHAUSTED: a pool is too small for this frame";
    case PN_E_DEVICE: return "PN_E_DEVICE: device error";
    case PN_E_INTERNAL: return "PN_E_INTERNAL: broken invariant";
    }
    return "unknown pn_status";
}

/* Minimal formatter: %s, %u (uint32_t), %z (size_t or uint64_t passed as unsigned long
 * long), %%. Truncates to the buffer. */
static void pn_vformat(char *dst, size_t cap, const char *fmt, va_list ap)
{
    size_t n = 0;
    const char *p;
    for (p = fmt; *p && n + 1 < cap; p++) {
        char digits[24];
        int nd = 0;
        unsigned long long v;
        const char *s;
        if (*p != '%' || p[1] == '\0') {
            dst[n++] = *p;
            continue;
        }
        p++;
        switch (*p) {
        case 's':
            s = va_arg(ap, const char *);
            if (!s) s = "(null)";
            while (*s && n + 1 < cap) dst[n++] = *s++;
            break;
        case 'u':
        case 'z':
            v = *p == 'u' ? (unsigned long long)va_arg(ap, unsigned int)
                          : va_arg(ap, unsigned long long);
            do {
                digits[nd++] = (char)('0' + (int)(v % 10u));
                v /= 10u;
            } while (v && nd < 24);
            while (nd > 0 && n + 1 < cap) dst[n++] = digits[--nd];
            break;
        default:
            dst[n++] = *p;
            break;
        }
    }
    dst[n] = '\0';
}

pn_status pn_fail(pn_context *ctx, pn_status status, const char *fmt, ...)
{
    va_list ap;
    if (!ctx) return status;
    va_start(ap, fmt);
    pn_vformat(ctx->message, sizeof(ctx->message), fmt, ap);
    va_end(ap);
    return status;
}

const char *pn_last_error(const pn_context *ctx)
{
    if (!ctx) return "pn_last_error: NULL context";
    return ctx->message;
}

pn_status pn_set_parallel_for(pn_context *ctx, pn_parallel_for_fn parallel_for, void *user)
{
    if (!ctx) return PN_E_INVALID_ARG;
    ctx->parallel_for = parallel_for;
    ctx->parallel_user = user;
    return PN_OK;
}

pn_status pn_set_clock(pn_context *ctx, pn_clock_fn clock, void *user)
{
    if (!ctx) return PN_E_INVALID_ARG;
    ctx->clock = clock;
    ctx->clock_user = user;
    return PN_OK;
}

uint64_t pn_now(const pn_context *ctx) { return ctx->clock ? ctx->clock(ctx->clock_user) : 0u; }

pn_status pn_dev_exec(const pn_port *port, pn_context *ctx, const pn_devcmd *cmd)
{
    return port->exec(port->self, ctx, cmd);
}

void pn_run(pn_context *ctx, uint32_t count, pn_task_fn fn, void *task)
{
    if (count == 0u) return;
    if (ctx->parallel_for)
        ctx->parallel_for(ctx->parallel_user, count, fn, task);
    else
        fn(task, 0u, count);
}

pn_status pn_get_stats(const pn_context *ctx, pn_stats *out)
{
    pn_stats s;
    uint32_t i;
    if (!ctx || !out) return PN_E_INVALID_ARG;
    s = ctx->stats; /* each algorithm's sub-struct, as its module left it */
    s.arena_bytes = ctx->bytes;
    s.arena_carved = ctx->layout.end;
    s.arena_persistent = ctx->layout.frame;
    s.arena_high_water = ctx->layout.frame + ctx->frame_high;
    s.triangles = ctx->has_scene ? ctx->tri_count : 0u;
    s.degenerate_triangles = ctx->has_scene ? ctx->degenerate : 0u;
    s.bvh_nodes = ctx->bvh_nodes;
    s.bvh_depth = ctx->bvh_depth;
    s.bvh_max_leaf = ctx->bvh_max_leaf;
    s.bvh_refs = ctx->bvh_refs;
    s.bvh_wide_nodes = ctx->bvh_wide;
    for (i = 0; i < PN_PASS_COUNT; i++) s.pass_ns[i] = ctx->pass_ns[i];
    s.shadow_candidates = ctx->shadow_candidates;
    s.shadow_blocking = ctx->shadow_blocking;
    s.shadow_nodes = ctx->shadow_nodes;
    s.lit_pixels = ctx->lit_pixels;
    s.cull_tol = ctx->cull_tol;
    *out = s;
    return PN_OK;
}

uint32_t pn_build_info(void)
{
#define PN_ALGO_BIT(ID, name) | (PN_ENABLE_##ID ? PN_BUILD_##ID : 0u)
    return PN_BUILD_PORT_SCALAR PN_ALGORITHMS(PN_ALGO_BIT);
#undef PN_ALGO_BIT
}

const char *pn_algo_name(pn_algo algo)
{
#define PN_ALGO_NAME(ID, name) #name,
    static const char *const names[PN_ALGO_COUNT] = {PN_ALGORITHMS(PN_ALGO_NAME)};
#undef PN_ALGO_NAME
    return (uint32_t)algo < PN_ALGO_COUNT ? names[algo] : NULL;
}
