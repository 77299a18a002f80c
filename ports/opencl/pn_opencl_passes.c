/* pn_opencl_passes.c - the OpenCL port's pass table: the G-buffer, the shadow pass of each
 * algorithm and shading as kernels over the arena mirror, each pass reading its results
 * back into the host arena (where pn_render_with's pn_frame points). The scene goes to the
 * device only when pn_scene_set changed it. */
#include <string.h>

#include "pn_opencl_internal.h"
#include "pn_reference.h"

static pn_status pn_cl_upload_scene(pn_opencl *cl, const pn_context *ctx)
{
    pn_status st;
    if (cl->scene_valid && cl->scene_version == ctx->scene_version) return PN_OK;
    cl->scene_valid = 0;
    if ((st = pn_cl_write(cl, ctx->tris, (size_t)ctx->tri_count * 9u * sizeof(float), "triangles")) != PN_OK ||
        (st = pn_cl_write(cl, ctx->flags, ctx->tri_count, "triangle flags")) != PN_OK ||
        (st = pn_cl_write(cl, ctx->nodes, (size_t)ctx->bvh_nodes * sizeof(pn_kbvh_node), "BVH nodes")) != PN_OK ||
        (st = pn_cl_write(cl, ctx->tri_index, (size_t)ctx->bvh_tris * sizeof(uint32_t), "BVH leaf order")) != PN_OK)
        return st;
    cl->scene_version = ctx->scene_version;
    cl->scene_valid = 1;
    cl->scene_uploads++;
    return PN_OK;
}

static pn_status pn_cl_gbuffer(pn_context *ctx, pn_frame_state *fs)
{
    pn_opencl *cl = (pn_opencl *)fs->self;
    cl_uint npix = fs->width * fs->height, T = ctx->tri_count;
    size_t px = npix;
    pn_kpools P;
    pn_status st;
    if ((st = pn_cl_upload_scene(cl, ctx)) != PN_OK) return st;
    pn_cl_pools(cl, fs, &P);
    if ((st = PN_CL_RUN(cl, PN_CLK_GBUFFER_CLEAR, npix, &cl->arena, &P, &npix)) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_RASTER_ROWS, T, &fs->view, &cl->arena, &P, &T)) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_RASTER_BAND, (fs->height + PN_RASTER_BAND - 1u) / PN_RASTER_BAND, &fs->view,
                        &cl->arena, &P, &T)) != PN_OK ||
        (st = PN_CL_RUN(cl, PN_CLK_GBUFFER_RESOLVE, npix, &fs->view, &cl->arena, &P)) != PN_OK)
        return st;
    if ((st = pn_cl_read(cl, fs->depth, px * sizeof(float), "depth")) != PN_OK ||
        (st = pn_cl_read(cl, fs->tri_id, px * sizeof(uint32_t), "triangle ids")) != PN_OK ||
        (st = pn_cl_read(cl, fs->pos, px * 3u * sizeof(float), "positions")) != PN_OK)
        return st;
    return pn_cl_read(cl, fs->nrm, px * 3u * sizeof(float), "normals");
}

static pn_status pn_cl_shadow(pn_context *ctx, pn_frame_state *fs)
{
    pn_opencl *cl = (pn_opencl *)fs->self;
    cl_uint npix = fs->width * fs->height, width = fs->width, per_sample = 0u;
    pn_kpools P;
    pn_status st;
    pn_cl_pools(cl, fs, &P);
    if ((st = pn_cl_fill_u32(cl, fs->counters, (size_t)fs->height * 4u, 0u, "clearing shadow counters")) != PN_OK)
        return st;
    switch (fs->algo) {
#if PN_ENABLE_REFERENCE
    case PN_ALGO_REFERENCE:
        st = PN_CL_RUN(cl, PN_CLK_PER_PIXEL, npix, &fs->light, &per_sample, &cl->arena, &P, &width, &npix);
        break;
#endif
#if PN_ENABLE_RAYTRACE
    case PN_ALGO_RAYTRACE:
        per_sample = 1u;
        st = PN_CL_RUN(cl, PN_CLK_PER_PIXEL, npix, &fs->light, &per_sample, &cl->arena, &P, &width, &npix);
        break;
#endif
#if PN_ENABLE_GEARS
    case PN_ALGO_GEARS:
        st = pn_cl_gears(cl, ctx, fs, &P);
        break;
#endif
    default:
        return pn_fail(ctx, PN_E_UNSUPPORTED, "OpenCL port: algorithm %u not available", fs->algo);
    }
    if (st != PN_OK || (st = pn_cl_read(cl, fs->vis, (size_t)npix * sizeof(float), "visibility")) != PN_OK) return st;
    /* pn_render_with sums the rows' counters. */
    return pn_cl_read(cl, fs->counters, (size_t)fs->height * sizeof(pn_shadow_counters), "shadow counters");
}

static pn_status pn_cl_shade(pn_context *ctx, pn_frame_state *fs)
{
    pn_opencl *cl = (pn_opencl *)fs->self;
    cl_uint npix = fs->width * fs->height;
    pn_kpools P;
    pn_status st;
    (void)ctx;
    pn_cl_pools(cl, fs, &P);
    if ((st = PN_CL_RUN(cl, PN_CLK_SHADE, npix, &fs->view, &fs->light, &fs->shade, &cl->arena, &P, &npix)) != PN_OK)
        return st;
    return pn_cl_read(cl, fs->rgba, (size_t)npix * 4u, "RGBA image");
}

void pn_cl_port_init(pn_opencl *cl)
{
    cl->port.name = "opencl";
    cl->port.gbuffer = pn_cl_gbuffer;
    cl->port.shadow = pn_cl_shadow;
    cl->port.shade = pn_cl_shade;
    cl->port.self = cl;
}
