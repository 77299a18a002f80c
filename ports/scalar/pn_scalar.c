/* pn_scalar.c - the scalar port: every pass is a loop over work items calling the
 * kernels/ functions compiled as C, handed to the caller's parallel-for if there is one.
 * Work items write disjoint memory (rows, bands, per-row counters), so the result does
 * not depend on how they are scheduled. */
#include <string.h>

#include "pn_raster.h"
#include "pn_raytrace.h"
#include "pn_scalar.h"
#include "pn_shade.h"

#define PN_SETUP_CHUNK 4096u

typedef struct pn_scalar_task {
    pn_context *ctx;
    pn_frame_state *fs;
} pn_scalar_task;

static void pn_task_rows_setup(void *task, uint32_t begin, uint32_t end)
{
    pn_scalar_task *tk = (pn_scalar_task *)task;
    uint32_t n = tk->ctx->tri_count, c;
    for (c = begin; c < end; c++) {
        uint32_t t, t1 = (c + 1u) * PN_SETUP_CHUNK < n ? (c + 1u) * PN_SETUP_CHUNK : n;
        for (t = c * PN_SETUP_CHUNK; t < t1; t++)
            tk->fs->rows[t] = pn_raster_rows(&tk->fs->view, tk->ctx->tris, tk->ctx->flags, t);
    }
}

static void pn_task_raster(void *task, uint32_t begin, uint32_t end)
{
    pn_scalar_task *tk = (pn_scalar_task *)task;
    pn_frame_state *fs = tk->fs;
    uint32_t b;
    for (b = begin; b < end; b++) {
        uint32_t y0 = b * PN_RASTER_BAND, y1 = y0 + PN_RASTER_BAND - 1u, x, y;
        if (y1 >= fs->height) y1 = fs->height - 1u;
        for (y = y0; y <= y1; y++)
            for (x = 0; x < fs->width; x++) {
                size_t pix = (size_t)y * fs->width + x;
                fs->depth[pix] = PN_KINF;
                fs->tri_id[pix] = PN_NO_TRIANGLE;
            }
        pn_raster_band(&fs->view, tk->ctx->tris, fs->rows, tk->ctx->tri_count, y0, y1,
                       fs->depth, fs->tri_id);
        for (y = y0; y <= y1; y++)
            for (x = 0; x < fs->width; x++)
                pn_gbuffer_resolve(&fs->view, tk->ctx->tris, x, y, fs->depth, fs->tri_id, fs->pos, fs->nrm);
    }
}

static pn_status pn_scalar_gbuffer(pn_context *ctx, pn_frame_state *fs)
{
    pn_scalar_task tk;
    tk.ctx = ctx;
    tk.fs = fs;
    pn_run(ctx, (ctx->tri_count + PN_SETUP_CHUNK - 1u) / PN_SETUP_CHUNK, pn_task_rows_setup, &tk);
    pn_run(ctx, (fs->height + PN_RASTER_BAND - 1u) / PN_RASTER_BAND, pn_task_raster, &tk);
    return PN_OK;
}

static pn_v3 pn_px3(const float *a, size_t pix) { return pn_v3_make(a[pix * 3u], a[pix * 3u + 1u], a[pix * 3u + 2u]); }

/* Rows [begin, end) of a per-pixel algorithm: PN_ALGO_REFERENCE or PN_ALGO_RAYTRACE. */
static void pn_task_per_pixel(void *task, uint32_t begin, uint32_t end)
{
    pn_scalar_task *tk = (pn_scalar_task *)task;
    pn_frame_state *fs = tk->fs;
    pn_context *ctx = tk->ctx;
    pn_shadow_counters *cnt = (pn_shadow_counters *)fs->counters;
    uint32_t y, x;
    for (y = begin; y < end; y++) {
        pn_shadow_counters c;
        memset(&c, 0, sizeof(c));
        for (x = 0; x < fs->width; x++) {
            size_t pix = (size_t)y * fs->width + x;
            uint32_t id = fs->tri_id[pix];
            pn_v3 P = pn_px3(fs->pos, pix), N = pn_px3(fs->nrm, pix);
            if (id == PN_NO_TRIANGLE)
                fs->vis[pix] = 1.0f;
#if PN_ENABLE_RAYTRACE
            else if (fs->algo == PN_ALGO_RAYTRACE)
                fs->vis[pix] = pn_raytrace_pixel(P, N, id, ctx->tris, ctx->nodes, ctx->tri_index, &fs->light, &c);
#endif
            else
                fs->vis[pix] = pn_reference_pixel(P, N, id, ctx->tris, ctx->nodes, ctx->tri_index, &fs->light, &c);
        }
        cnt[y] = c;
    }
}

static pn_status pn_scalar_shadow(pn_context *ctx, pn_frame_state *fs)
{
    pn_scalar_task tk;
    tk.ctx = ctx;
    tk.fs = fs;
    switch (fs->algo) {
#if PN_ENABLE_REFERENCE
    case PN_ALGO_REFERENCE:
        pn_run(ctx, fs->height, pn_task_per_pixel, &tk);
        break;
#endif
#if PN_ENABLE_RAYTRACE
    case PN_ALGO_RAYTRACE:
        pn_run(ctx, fs->height, pn_task_per_pixel, &tk);
        break;
#endif
#if PN_ENABLE_GEARS
    case PN_ALGO_GEARS: {
        pn_status st = pn_scalar_gears(ctx, fs);
        if (st != PN_OK) return st;
        break;
    }
#endif
    default:
        return pn_fail(ctx, PN_E_UNSUPPORTED, "scalar port: algorithm %u not available", fs->algo);
    }
    return PN_OK;
}

static void pn_task_shade(void *task, uint32_t begin, uint32_t end)
{
    pn_scalar_task *tk = (pn_scalar_task *)task;
    pn_frame_state *fs = tk->fs;
    uint32_t y, x;
    for (y = begin; y < end; y++)
        for (x = 0; x < fs->width; x++) {
            size_t pix = (size_t)y * fs->width + x;
            uint32_t c = pn_shade_pixel(&fs->view, &fs->light, &fs->shade, fs->tri_id[pix], pn_px3(fs->pos, pix),
                                        pn_px3(fs->nrm, pix), fs->vis[pix]);
            fs->rgba[pix * 4u + 0u] = (uint8_t)(c & 0xFFu);
            fs->rgba[pix * 4u + 1u] = (uint8_t)((c >> 8) & 0xFFu);
            fs->rgba[pix * 4u + 2u] = (uint8_t)((c >> 16) & 0xFFu);
            fs->rgba[pix * 4u + 3u] = (uint8_t)(c >> 24);
        }
}

static pn_status pn_scalar_shade(pn_context *ctx, pn_frame_state *fs)
{
    pn_scalar_task tk;
    tk.ctx = ctx;
    tk.fs = fs;
    pn_run(ctx, fs->height, pn_task_shade, &tk);
    return PN_OK;
}

static const pn_port pn_port_scalar = {"scalar", pn_scalar_gbuffer, pn_scalar_shadow, pn_scalar_shade, NULL};

pn_status pn_render(pn_context *ctx, const pn_camera *camera, const pn_light *light,
                    const pn_frame_options *opt, pn_frame *out)
{
    return pn_render_with(ctx, &pn_port_scalar, camera, light, opt, out);
}
