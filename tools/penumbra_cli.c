/* penumbra - command-line front end: render a glTF or built-in scene with any compiled-in
 * algorithm, and the demo. Host tool; see README.md for usage. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#if PN_HAVE_OPENCL
#include "penumbra/opencl.h"
#include "pn_cl_host.h"
#endif
#include "pn_image.h"
#include "pn_scenes.h"
#include "pn_setup.h"

#if PN_HAVE_OPENCL
#define PN_CLI_PORTS "scalar opencl"
#else
#define PN_CLI_PORTS "scalar"
#endif

/* The algorithms are the registry's (pn_algo 0 .. PN_ALGO_COUNT - 1, pn_algo_name, compiled
 * in when pn_build_info() has bit 1u << algo). The demo renders all but raytrace, a baseline
 * with the reference's bits by construction and the slowest of all (k^2 rays per pixel);
 * the benchmark measures it. */
#define PN_DEMO_ALGO_COUNT (PN_ALGO_COUNT - 1u)

static void usage(FILE *f)
{
    const char *const *names = pn_builtin_scene_names();
    size_t i;
    fprintf(f,
            "usage:\n"
            "  penumbra render [SCENE.glb | --builtin NAME] [--algo A] [--port P] [--cl-device SPEC]\n"
            "                  [--size WxH] [--k K]\n"
            "                  [--view NAME [--views FILE]]\n"
            "                  [--eye x,y,z --target x,y,z --up x,y,z --fov DEG]\n"
            "                  [--light-center x,y,z --light-u x,y,z --light-v x,y,z]\n"
            "                  [--ground on|off] [--eps E] [--grid N] [--gears-pairs N] [--exact-stats] [--threads N]\n"
            "                  [--srt-map N] [--srt-delta D] [--srt-no-conservative] [--srt-force-pip]\n"
            "                  [--occ-slices N] [--occ-map N] [--occ-filter nbuffer|sat|mipmap]\n"
            "                  [--occ-combine product|max|sum] [--occ-leak-fix] [--occ-paper-fade]\n"
            "                  [--mc-layers 1|2|3] [--mc-search linear|hier] [--mc-rays N] [--mc-blur N|off]\n"
            "                  [--mc-map N] [--mc-no-bias] [--mc-no-classify] [--mc-no-stacked] [--mc-seed N] [--mc-sparse-nbuffer]\n"
            "                  [--wg-mode blend|additive] [--wg-no-cull] [--wg-silhouettes N]\n"
            "                  --out image.png [--vis vis.pfm] [--ids ids.bin] [--stats stats.json]\n"
            "  penumbra bake [the scene, view, light and algorithm options of render]\n"
            "                --out lightmap.pfm [--size WxH]\n"
            "      the light map of the ground plane under the scene (a built-in: its own ground):\n"
            "      visibility at the centres of WxH texels (default 256x256) over the scene's x,z\n"
            "      extent (a built-in: its ground's), +x right, +z down\n"
            "  penumbra demo [--out DIR] [--size WxH] [--k K] [--threads N]\n"
            "  penumbra info [--no-build]\n"
            "algorithms:");
    for (i = 0; i < PN_ALGO_COUNT; i++)
        if (pn_build_info() & (1u << i)) fprintf(f, " %s", pn_algo_name((pn_algo)i));
    fprintf(f, "\nports: " PN_CLI_PORTS "\nbuilt-in scenes:");
    for (; *names; names++) fprintf(f, " %s", *names);
    fprintf(f, "\n");
}

static int find_algo(const char *name, pn_algo *out)
{
    uint32_t i;
    for (i = 0; i < PN_ALGO_COUNT; i++)
        if (strcmp(name, pn_algo_name((pn_algo)i)) == 0) {
            if (!(pn_build_info() & (1u << i))) return 2;
            *out = (pn_algo)i;
            return 0;
        }
    return 1;
}

static const char *algo_name(pn_algo a) { return pn_algo_name(a) ? pn_algo_name(a) : "?"; }

/* The port a frame is rendered with: "scalar" (pn_render) or "opencl" (pn_opencl_render,
 * on the device PN_OPENCL_DEVICE or --cl-device picks). */
typedef struct cli_port {
    const char *name;
#if PN_HAVE_OPENCL
    pn_opencl *cl;
#endif
} cli_port;

static int cli_port_known(const char *name)
{
    return strcmp(name, "scalar") == 0 || (PN_HAVE_OPENCL && strcmp(name, "opencl") == 0);
}

/* 0, or 1 after printing why the port cannot run on ctx. */
static int cli_port_open(cli_port *p, const char *name, const char *device, pn_context *ctx)
{
    memset(p, 0, sizeof(*p));
    p->name = name;
#if PN_HAVE_OPENCL
    if (strcmp(name, "opencl") == 0) {
        pn_opencl_options o;
        pn_status st;
        pn_opencl_info info;
        pn_opencl_options_default(&o);
        o.device = device;
        if ((st = pn_cl_open(ctx, &o, &p->cl)) != PN_OK) {
            fprintf(stderr, "penumbra: OpenCL port: %s (%s)\n", pn_last_error(ctx), pn_status_str(st));
            return 1;
        }
        pn_opencl_get_info(p->cl, &info);
        fprintf(stderr, "OpenCL: %s, kernels built in %.0f ms (+%.0f ms first launches)\n", pn_opencl_device_name(p->cl),
                info.build_ms, info.warmup_ms);
    }
#else
    (void)device;
    (void)ctx;
#endif
    return 0;
}

static pn_status cli_port_render(cli_port *p, pn_context *ctx, const pn_camera *cam, const pn_light *light,
                                 const pn_frame_options *opt, pn_frame *fr)
{
#if PN_HAVE_OPENCL
    if (p->cl) return pn_opencl_render(p->cl, cam, light, opt, fr);
#endif
    return pn_render(ctx, cam, light, opt, fr);
}

static pn_status cli_port_points(cli_port *p, pn_context *ctx, const pn_light *light, const pn_frame_options *opt,
                                 const float *pts, const float *nrm, const uint32_t *ids, uint32_t n, float *out)
{
#if PN_HAVE_OPENCL
    if (p->cl) return pn_opencl_visibility_points(p->cl, light, opt, pts, nrm, ids, n, out);
#endif
    return pn_visibility_points(ctx, light, opt, pts, nrm, ids, n, out);
}

/* The light map's points: the centres of w x h texels over an x,z extent, on the ground
 * plane (the last two triangles: the quad pn_mesh_add_ground appends, s->ground, or a
 * built-in scene's own ground, tools/pn_scenes.h), each on the ground triangle that holds
 * it, with that triangle's normal as the scene winds it (pn_visibility_points' contract).
 * The extent: with an appended ground, the scene's without it (the ground reaches far
 * beyond); a built-in's ground, its own. Row r at z = zmin + (r + 0.5) dz. */
static void ground_points(const pn_setup *s, uint32_t w, uint32_t h, float *pts, float *nrm, uint32_t *ids)
{
    const pn_mesh *m = &s->mesh;
    uint32_t tg = m->triangle_count - 2u, v, x, y, c;
    const uint32_t *gi = m->indices + (size_t)tg * 3u; /* the two ground triangles' corners */
    float lo[2] = {0.0f, 0.0f}, hi[2] = {0.0f, 0.0f}, n[2][3], gy = m->positions[(size_t)gi[0] * 3u + 1u];
    int first = 1;
    for (v = 0; v < m->vertex_count; v++) {
        const float *p = m->positions + (size_t)v * 3u;
        int in_ground = 0;
        for (c = 0; c < 6u; c++) in_ground |= gi[c] == v;
        if (s->ground ? in_ground : !in_ground) continue; /* appended: the scene's; own: the ground's */
        if (first) {
            lo[0] = hi[0] = p[0];
            lo[1] = hi[1] = p[2];
            first = 0;
        }
        lo[0] = p[0] < lo[0] ? p[0] : lo[0];
        hi[0] = p[0] > hi[0] ? p[0] : hi[0];
        lo[1] = p[2] < lo[1] ? p[2] : lo[1];
        hi[1] = p[2] > hi[1] ? p[2] : hi[1];
    }
    for (c = 0; c < 2u; c++) { /* unit winding normals: (B - A) x (C - A) */
        const float *A = m->positions + (size_t)gi[c * 3u] * 3u, *B = m->positions + (size_t)gi[c * 3u + 1u] * 3u,
                    *C = m->positions + (size_t)gi[c * 3u + 2u] * 3u;
        double e1[3], e2[3], q[3], l;
        uint32_t k;
        for (k = 0; k < 3u; k++) {
            e1[k] = (double)B[k] - A[k];
            e2[k] = (double)C[k] - A[k];
        }
        q[0] = e1[1] * e2[2] - e1[2] * e2[1];
        q[1] = e1[2] * e2[0] - e1[0] * e2[2];
        q[2] = e1[0] * e2[1] - e1[1] * e2[0];
        l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        for (k = 0; k < 3u; k++) n[c][k] = (float)(q[k] / l);
    }
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            float px = lo[0] + (hi[0] - lo[0]) * ((float)x + 0.5f) / (float)w;
            float pz = lo[1] + (hi[1] - lo[1]) * ((float)y + 0.5f) / (float)h;
            /* the first triangle when (px, pz) lies on no edge's outer side of it (x,z) */
            double side[3];
            uint32_t e, t;
            for (e = 0; e < 3u; e++) {
                const float *A = m->positions + (size_t)gi[e] * 3u, *B = m->positions + (size_t)gi[(e + 1u) % 3u] * 3u;
                side[e] = ((double)B[2] - A[2]) * ((double)px - A[0]) - ((double)B[0] - A[0]) * ((double)pz - A[2]);
            }
            t = (side[0] >= 0.0 && side[1] >= 0.0 && side[2] >= 0.0) || (side[0] <= 0.0 && side[1] <= 0.0 && side[2] <= 0.0)
                    ? 0u
                    : 1u;
            pts[i * 3u] = px;
            pts[i * 3u + 1u] = gy;
            pts[i * 3u + 2u] = pz;
            nrm[i * 3u] = n[t][0];
            nrm[i * 3u + 1u] = n[t][1];
            nrm[i * 3u + 2u] = n[t][2];
            ids[i] = tg + t;
        }
}

/* The OpenCL device's name when the port is OpenCL, else NULL. */
static const char *cli_port_device(const cli_port *p)
{
#if PN_HAVE_OPENCL
    if (p->cl) return pn_opencl_device_name(p->cl);
#endif
    (void)p;
    return NULL;
}

static void cli_port_close(cli_port *p)
{
#if PN_HAVE_OPENCL
    pn_cl_close(p->cl);
#endif
    memset(p, 0, sizeof(*p));
}

static void json_vec(FILE *f, const char *key, const float v[3], int comma)
{
    fprintf(f, "  \"%s\": [%.9g, %.9g, %.9g]%s\n", key, v[0], v[1], v[2], comma ? "," : "");
}

/* A JSON string value: quotes, backslashes and control characters escaped. */
static void json_str(FILE *f, const char *v)
{
    fputc('"', f);
    for (; *v; v++) {
        unsigned char c = (unsigned char)*v;
        if (c == '"' || c == '\\') fprintf(f, "\\%c", c);
        else if (c < 0x20u) fprintf(f, "\\u%04x", c);
        else fputc(c, f);
    }
    fputc('"', f);
}

/* device: the OpenCL device's name for --port opencl ("opencl_device" in the file), else NULL. */
static int write_stats(const char *path, const pn_setup *s, const pn_frame_options *opt, const char *port,
                       const char *device, int threads, const pn_stats *st, double ms_total, const pn_frame *fr)
{
    FILE *f = fopen(path, "w");
    double mean = 0.0;
    size_t i, n = (size_t)fr->width * fr->height;
    if (!f) return 1;
    for (i = 0; i < n; i++) mean += fr->visibility[i];
    mean /= (double)n;
    fprintf(f, "{\n");
    fprintf(f, "  \"scene\": \"%s\",\n  \"triangles\": %u,\n  \"ground\": %s,\n", s->name, st->triangles,
            s->ground ? "true" : "false");
    fprintf(f, "  \"view_source\": \"%s\",\n  \"light_source\": \"%s\",\n", s->view_source, s->light_source);
    json_vec(f, "eye", s->camera.eye, 1);
    json_vec(f, "target", s->camera.target, 1);
    json_vec(f, "up", s->camera.up, 1);
    fprintf(f, "  \"fov_deg\": %.9g,\n", s->camera.fov_deg);
    json_vec(f, "light_center", s->light.center, 1);
    json_vec(f, "light_u", s->light.u, 1);
    json_vec(f, "light_v", s->light.v, 1);
    fprintf(f, "  \"scene_diag\": %.9g,\n  \"eps_rel\": %.9g,\n  \"eps\": %.9g,\n", s->diag, s->eps_rel, opt->eps);
    fprintf(f, "  \"width\": %u,\n  \"height\": %u,\n  \"k\": %u,\n", opt->width, opt->height, opt->k);
    fprintf(f, "  \"algo\": \"%s\",\n  \"port\": \"%s\",\n  \"threads\": %d,\n", algo_name(opt->algo), port, threads);
    if (device) {
        fprintf(f, "  \"opencl_device\": ");
        json_str(f, device);
        fprintf(f, ",\n");
    }
    fprintf(f, "  \"arena_bytes\": %zu,\n  \"arena_carved\": %zu,\n  \"arena_persistent\": %zu,\n"
               "  \"arena_high_water\": %zu,\n",
            st->arena_bytes, st->arena_carved, st->arena_persistent, st->arena_high_water);
    fprintf(f, "  \"degenerate_triangles\": %u,\n  \"bvh_nodes\": %u,\n  \"bvh_depth\": %u,\n"
               "  \"bvh_max_leaf\": %u,\n  \"bvh_refs\": %u,\n  \"bvh_wide_nodes\": %u,\n",
            st->degenerate_triangles, st->bvh_nodes, st->bvh_depth, st->bvh_max_leaf, st->bvh_refs,
            st->bvh_wide_nodes);
    fprintf(f, "  \"ms_scene_algos\": %.3f,\n", st->pass_ns[PN_PASS_SCENE_ALGOS] / 1e6);
    fprintf(f, "  \"ms_scene_copy\": %.3f,\n  \"ms_bvh_build\": %.3f,\n  \"ms_gbuffer\": %.3f,\n"
               "  \"ms_shadow\": %.3f,\n  \"ms_shade\": %.3f,\n  \"ms_render_total\": %.3f,\n",
            st->pass_ns[PN_PASS_SCENE_COPY] / 1e6, st->pass_ns[PN_PASS_BVH_BUILD] / 1e6,
            st->pass_ns[PN_PASS_GBUFFER] / 1e6, st->pass_ns[PN_PASS_SHADOW] / 1e6, st->pass_ns[PN_PASS_SHADE] / 1e6,
            ms_total);
    fprintf(f, "  \"shadow_candidates\": %llu,\n  \"shadow_blocking\": %llu,\n  \"shadow_nodes\": %llu,\n  \"lit_pixels\": %u,\n",
            (unsigned long long)st->shadow_candidates, (unsigned long long)st->shadow_blocking,
            (unsigned long long)st->shadow_nodes, st->lit_pixels);
    fprintf(f, "  \"gears_grid\": %u,\n  \"gears_pairs\": %llu,\n  \"gears_assignments\": %llu,\n"
               "  \"gears_tiles\": %u,\n  \"gears_faces\": %u,\n  \"gears_cells_used\": %u,\n"
               "  \"gears_max_tris_per_cell\": %u,\n  \"gears_mean_tris_per_cell\": %.3f,\n"
               "  \"gears_max_pixels_per_cell\": %u,\n  \"gears_mean_pixels_per_cell\": %.3f,\n"
               "  \"gears_pairs_high_water\": %u,\n",
            st->gears.grid, /* the grid rendered: gears.grid, or the library's default */
            (unsigned long long)st->gears.pairs, (unsigned long long)st->gears.assignments,
            st->gears.tiles, st->gears.faces, st->gears.cells_used, st->gears.max_tris_per_cell,
            st->gears.mean_tris_per_cell, st->gears.max_pixels_per_cell, st->gears.mean_pixels_per_cell,
            st->gears.pairs_high_water);
    fprintf(f, "  \"srt_map\": %u,\n  \"srt_pip\": %u,\n  \"srt_thin\": %u,\n  \"srt_cons_texels\": %u,\n"
               "  \"srt_tiles_masked\": %u,\n",
            st->srt.map, st->srt.pip, st->srt.thin, st->srt.cons_texels, st->srt.tiles_masked);
    fprintf(f, "  \"ms_srt_map\": %.3f,\n  \"ms_srt_classify\": %.3f,\n  \"ms_srt_exact\": %.3f,\n",
            (double)st->srt.ns_map * 1e-6, (double)st->srt.ns_classify * 1e-6, (double)st->srt.ns_exact * 1e-6);
    fprintf(f, "  \"occ_map\": %u,\n  \"occ_slices\": %u,\n  \"occ_outside\": %u,\n  \"occ_texels_set\": %llu,\n  \"occ_lookups\": %llu,\n",
            st->occtex.map, st->occtex.slices, st->occtex.outside, (unsigned long long)st->occtex.texels_set,
            (unsigned long long)st->occtex.lookups);
    fprintf(f, "  \"ms_occ_slice\": %.3f,\n  \"ms_occ_filter\": %.3f,\n  \"ms_occ_lookup\": %.3f,\n",
            (double)st->occtex.ns_slice * 1e-6, (double)st->occtex.ns_filter * 1e-6, (double)st->occtex.ns_lookup * 1e-6);
    fprintf(f, "  \"mc_map\": %u,\n  \"mc_lit\": %u,\n  \"mc_umbra\": %u,\n  \"mc_penumbra\": %u,\n",
            st->mcsm.map, st->mcsm.lit, st->mcsm.umbra, st->mcsm.penumbra);
    fprintf(f, "  \"mc_penumbra_open\": %u,\n  \"mc_penumbra_shut\": %u,\n", st->mcsm.penumbra_open, st->mcsm.penumbra_shut);
    fprintf(f, "  \"mc_rays\": %llu,\n  \"mc_steps\": %llu,\n  \"mc_capped\": %u,\n  \"mc_outside\": %u,\n  \"mc_grazing\": %u,\n",
            (unsigned long long)st->mcsm.rays, (unsigned long long)st->mcsm.steps, st->mcsm.capped, st->mcsm.outside,
            st->mcsm.grazing);
    fprintf(f, "  \"mc_stacked\": %u,\n", st->mcsm.stacked);
    fprintf(f, "  \"ms_mc_layers\": %.3f,\n  \"ms_mc_nbuffer\": %.3f,\n  \"ms_mc_rays\": %.3f,\n  \"ms_mc_blur\": %.3f,\n",
            (double)st->mcsm.ns_layers * 1e-6, (double)st->mcsm.ns_nbuffer * 1e-6, (double)st->mcsm.ns_rays * 1e-6,
            (double)st->mcsm.ns_blur * 1e-6);
    fprintf(f, "  \"wg_vertices\": %u,\n  \"wg_edges\": %u,\n  \"wg_open_edges\": %u,\n  \"wg_nonmanifold_edges\": %u,\n",
            st->wedges.vertices, st->wedges.edges, st->wedges.open_edges, st->wedges.nonmanifold_edges);
    fprintf(f, "  \"wg_objects\": %u,\n  \"wg_closed_objects\": %u,\n  \"wg_inverted_objects\": %u,\n  \"wg_duplicates\": %u,\n  \"wg_silhouettes\": %u,\n  \"wg_pairs\": %llu,\n  \"wg_bands\": %u,\n  \"wg_sil_bands\": %u,\n",
            st->wedges.objects, st->wedges.closed_objects, st->wedges.inverted_objects, st->wedges.duplicates, st->wedges.silhouettes, (unsigned long long)st->wedges.pairs,
            st->wedges.bands, st->wedges.sil_bands);
    fprintf(f, "  \"wg_evaluated\": %llu,\n  \"wg_touched\": %llu,\n  \"wg_hard_blockers\": %llu,\n  \"wg_hard_overflow\": %u,\n  \"wg_exact_pixels\": %u,\n  \"wg_full_tiles\": %u,\n",
            (unsigned long long)st->wedges.evaluated, (unsigned long long)st->wedges.touched,
            (unsigned long long)st->wedges.hard_blockers, st->wedges.hard_overflow, st->wedges.exact_pixels,
            st->wedges.full_tiles);
    fprintf(f, "  \"ms_wg_silhouettes\": %.3f,\n  \"ms_wg_binning\": %.3f,\n  \"ms_wg_pixels\": %.3f,\n",
            (double)st->wedges.ns_silhouettes * 1e-6, (double)st->wedges.ns_binning * 1e-6, (double)st->wedges.ns_pixels * 1e-6);
    fprintf(f, "  \"mean_visibility\": %.9g\n}\n", mean);
    return fclose(f) != 0;
}

/* The ground's light map: one batch of width x height points (cmd_render's set-up done);
 * closes the port, the context and the scene. 0, or 1 after a message. */
static int cmd_bake(pn_setup *s, pn_host *h, cli_port *cp, const pn_frame_options *opt, const char *out)
{
    size_t n = (size_t)opt->width * opt->height;
    float *pts = (float *)malloc(n * 12u), *nrm = (float *)malloc(n * 12u), *vis = (float *)malloc(n * 4u);
    uint32_t *ids = (uint32_t *)malloc(n * 4u);
    char err[512];
    int rc = 1;
    pn_status st;
    uint64_t t0;
    double ms;
    if (!pts || !nrm || !vis || !ids) {
        fprintf(stderr, "penumbra: out of memory for %zu points\n", n);
        goto done;
    }
    ground_points(s, opt->width, opt->height, pts, nrm, ids);
    t0 = pn_threads_now_ns(NULL);
    st = cli_port_points(cp, h->ctx, &s->light, opt, pts, nrm, ids, (uint32_t)n, vis);
    ms = (pn_threads_now_ns(NULL) - t0) / 1e6;
    if (st != PN_OK) {
        fprintf(stderr, "penumbra: bake failed: %s (%s)\n", pn_last_error(h->ctx), pn_status_str(st));
        goto done;
    }
    if (pn_write_pfm(out, vis, opt->width, opt->height, err, sizeof(err))) {
        fprintf(stderr, "penumbra: %s\n", err);
        goto done;
    }
    fprintf(stderr, "%s: light map %ux%u k=%u %s/%s %.1f ms (%.0f points/s)\n", s->name, opt->width, opt->height, opt->k,
            algo_name(opt->algo), cp->name, ms, ms > 0.0 ? (double)n / (ms * 1e-3) : 0.0);
    rc = 0;
done:
    free(pts);
    free(nrm);
    free(vis);
    free(ids);
    cli_port_close(cp);
    pn_host_close(h);
    pn_setup_free(s);
    return rc;
}

/* render, or with bake set the ground's light map (usage). */
static int cmd_render(int argc, char **argv, int bake)
{
    const char *scene = NULL, *builtin = NULL, *out = NULL, *vis = NULL, *ids = NULL, *stats = NULL;
    const char *port = "scalar", *device = NULL, *view_name = NULL, *views_file = NULL;
    char views_path[1200];
    pn_view view;
    cli_port cp;
    pn_frame_options opt;
    pn_setup s;
    pn_host h;
    pn_frame fr;
    pn_stats st;
    pn_status rs;
    char err[512];
    int ground = -1, threads = 0, i, user_view = 0, user_light = 0, have_size = 0;
    uint32_t wg_sils = 0u; /* --wg-silhouettes: the wedges' silhouette pool (0: the library's default) */
    long gears_pairs = -1; /* --gears-pairs: -1 the host's (PN_GEARS_PAIRS), 0 the library's default */
    uint32_t lim_flags = 0u; /* --mc-sparse-nbuffer: PN_LIMITS_SPARSE_NBUFFER */
    float eps_rel = -1.0f;
    pn_limits lim;
    pn_camera cam;
    pn_light light;
    int have[7] = {0};
    uint64_t t0;
    double ms;

    pn_frame_options_default(&opt);
    memset(&cam, 0, sizeof(cam));
    memset(&light, 0, sizeof(light));
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED_ARG                                                  \
    do {                                                          \
        if (!v) {                                                 \
            fprintf(stderr, "penumbra: %s needs a value\n", a);   \
            return 2;                                             \
        }                                                         \
        i++;                                                      \
    } while (0)
#define BAD(what)                                                           \
    do {                                                                    \
        fprintf(stderr, "penumbra: bad value for %s: '%s'\n", what, v);     \
        return 2;                                                           \
    } while (0)
        if (strcmp(a, "--builtin") == 0) { NEED_ARG; builtin = v; }
        else if (strcmp(a, "--algo") == 0) {
            int r;
            NEED_ARG;
            r = find_algo(v, &opt.algo);
            if (r == 2) { fprintf(stderr, "penumbra: algorithm '%s' is not compiled in\n", v); return 2; }
            if (r) BAD("--algo");
        } else if (strcmp(a, "--port") == 0) {
            NEED_ARG;
            if (!cli_port_known(v)) {
                fprintf(stderr, "penumbra: port '%s' is not available in this build (ports: " PN_CLI_PORTS ")\n", v);
                return 2;
            }
            port = v;
        } else if (strcmp(a, "--cl-device") == 0) {
            NEED_ARG;
            device = v;
        } else if (strcmp(a, "--size") == 0) { NEED_ARG; if (pn_parse_size(v, &opt.width, &opt.height)) BAD("--size"); have_size = 1; }
        else if (strcmp(a, "--view") == 0) { NEED_ARG; view_name = v; }
        else if (strcmp(a, "--views") == 0) { NEED_ARG; views_file = v; }
        else if (strcmp(a, "--k") == 0) { NEED_ARG; opt.k = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--eye") == 0) { NEED_ARG; if (pn_parse_vec3(v, cam.eye)) BAD(a); have[0] = 1; }
        else if (strcmp(a, "--target") == 0) { NEED_ARG; if (pn_parse_vec3(v, cam.target)) BAD(a); have[1] = 1; }
        else if (strcmp(a, "--up") == 0) { NEED_ARG; if (pn_parse_vec3(v, cam.up)) BAD(a); have[2] = 1; }
        else if (strcmp(a, "--fov") == 0) { NEED_ARG; cam.fov_deg = strtof(v, NULL); have[3] = 1; }
        else if (strcmp(a, "--light-center") == 0) { NEED_ARG; if (pn_parse_vec3(v, light.center)) BAD(a); have[4] = 1; }
        else if (strcmp(a, "--light-u") == 0) { NEED_ARG; if (pn_parse_vec3(v, light.u)) BAD(a); have[5] = 1; }
        else if (strcmp(a, "--light-v") == 0) { NEED_ARG; if (pn_parse_vec3(v, light.v)) BAD(a); have[6] = 1; }
        else if (strcmp(a, "--ground") == 0) {
            NEED_ARG;
            if (strcmp(v, "on") == 0) ground = 1;
            else if (strcmp(v, "off") == 0) ground = 0;
            else BAD("--ground");
        } else if (strcmp(a, "--eps") == 0) { NEED_ARG; eps_rel = strtof(v, NULL); }
        else if (strcmp(a, "--grid") == 0) { NEED_ARG; opt.gears.grid = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--gears-pairs") == 0) {
            NEED_ARG;
            gears_pairs = strtol(v, NULL, 10);
            if (gears_pairs < 0 || gears_pairs > (1L << 28)) BAD("--gears-pairs");
        }
        else if (strcmp(a, "--exact-stats") == 0) opt.exact_stats = 1;
        else if (strcmp(a, "--srt-map") == 0) { NEED_ARG; opt.srt.map = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--srt-delta") == 0) { NEED_ARG; opt.srt.delta = strtof(v, NULL); }
        else if (strcmp(a, "--srt-no-conservative") == 0) opt.srt.flags |= PN_SRT_NO_CONSERVATIVE;
        else if (strcmp(a, "--srt-force-pip") == 0) opt.srt.flags |= PN_SRT_FORCE_PIP;
        else if (strcmp(a, "--occ-slices") == 0) { NEED_ARG; opt.occtex.slices = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--occ-map") == 0) { NEED_ARG; opt.occtex.map = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--occ-filter") == 0) {
            NEED_ARG;
            if (strcmp(v, "nbuffer") == 0) opt.occtex.filter = PN_OCC_FILTER_NBUFFER;
            else if (strcmp(v, "sat") == 0) opt.occtex.filter = PN_OCC_FILTER_SAT;
            else if (strcmp(v, "mipmap") == 0) opt.occtex.filter = PN_OCC_FILTER_MIPMAP;
            else BAD(a);
        }
        else if (strcmp(a, "--occ-combine") == 0) {
            NEED_ARG;
            if (strcmp(v, "product") == 0) opt.occtex.combine = PN_OCC_COMBINE_PRODUCT;
            else if (strcmp(v, "max") == 0) opt.occtex.combine = PN_OCC_COMBINE_MAX;
            else if (strcmp(v, "sum") == 0) opt.occtex.combine = PN_OCC_COMBINE_SUM;
            else BAD(a);
        }
        else if (strcmp(a, "--occ-leak-fix") == 0) opt.occtex.flags |= PN_OCC_LEAK_FIX;
        else if (strcmp(a, "--occ-paper-fade") == 0) opt.occtex.flags |= PN_OCC_PAPER_FADE;
        else if (strcmp(a, "--mc-layers") == 0) { NEED_ARG; opt.mcsm.layers = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--mc-search") == 0) {
            NEED_ARG;
            if (strcmp(v, "linear") == 0) opt.mcsm.search = PN_MC_SEARCH_LINEAR;
            else if (strcmp(v, "hier") == 0) opt.mcsm.search = PN_MC_SEARCH_HIER;
            else BAD(a);
        }
        else if (strcmp(a, "--mc-rays") == 0) { NEED_ARG; opt.mcsm.rays = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--mc-blur") == 0) {
            NEED_ARG;
            opt.mcsm.blur = strcmp(v, "off") == 0 ? PN_MC_BLUR_OFF : (uint32_t)strtoul(v, NULL, 10);
        }
        else if (strcmp(a, "--mc-map") == 0) { NEED_ARG; opt.mcsm.map = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--mc-sparse-nbuffer") == 0) lim_flags |= PN_LIMITS_SPARSE_NBUFFER;
        else if (strcmp(a, "--mc-no-bias") == 0) opt.mcsm.flags |= PN_MC_NO_BIAS;
        else if (strcmp(a, "--mc-no-classify") == 0) opt.mcsm.flags |= PN_MC_NO_CLASSIFY;
        else if (strcmp(a, "--mc-no-stacked") == 0) opt.mcsm.flags |= PN_MC_NO_STACKED;
        else if (strcmp(a, "--mc-seed") == 0) { NEED_ARG; opt.mcsm.seed = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--wg-mode") == 0) {
            NEED_ARG;
            if (strcmp(v, "blend") == 0) opt.wedges.mode = PN_WG_MODE_BLEND;
            else if (strcmp(v, "additive") == 0) opt.wedges.mode = PN_WG_MODE_ADDITIVE;
            else BAD(a);
        }
        else if (strcmp(a, "--wg-no-cull") == 0) opt.wedges.flags |= PN_WG_NO_CULL;
        else if (strcmp(a, "--wg-silhouettes") == 0) { NEED_ARG; wg_sils = (uint32_t)strtoul(v, NULL, 10); }
        else if (strcmp(a, "--threads") == 0) { NEED_ARG; threads = atoi(v); if (threads < 1) BAD(a); }
        else if (strcmp(a, "--out") == 0) { NEED_ARG; out = v; }
        else if (strcmp(a, "--vis") == 0) { NEED_ARG; vis = v; }
        else if (strcmp(a, "--ids") == 0) { NEED_ARG; ids = v; }
        else if (strcmp(a, "--stats") == 0) { NEED_ARG; stats = v; }
        else if (a[0] == '-') { fprintf(stderr, "penumbra: unknown option %s\n", a); usage(stderr); return 2; }
        else if (!scene) scene = a;
        else { fprintf(stderr, "penumbra: more than one scene given\n"); return 2; }
#undef NEED_ARG
#undef BAD
    }
    if ((scene != NULL) == (builtin != NULL)) {
        fprintf(stderr, "penumbra: give exactly one of SCENE.glb or --builtin NAME\n");
        usage(stderr);
        return 2;
    }
    if (!out) { fprintf(stderr, "penumbra: --out %s is required\n", bake ? "lightmap.pfm" : "image.png"); return 2; }
    if (bake && ground == 0) { fprintf(stderr, "penumbra: bake bakes the ground plane: --ground off is not allowed\n"); return 2; }
    if (bake && builtin && ground > 0) {
        fprintf(stderr, "penumbra: bake: a built-in scene bakes its own ground; --ground is for glTF scenes\n");
        return 2;
    }
    if (bake && (vis || ids)) { fprintf(stderr, "penumbra: bake writes the light map only (--out)\n"); return 2; }
    if (views_file && !view_name) { fprintf(stderr, "penumbra: --views FILE needs --view NAME\n"); return 2; }
    /* A named view: the camera, light, size and ground of views.json; explicit flags still
     * override its fields one by one below. */
    if (view_name) {
        int vr;
        if (views_file) {
            snprintf(views_path, sizeof(views_path), "%s", views_file);
        } else if (pn_views_file_for(scene, views_path, sizeof(views_path)) != 0) {
            fprintf(stderr, "penumbra: --view %s: no views file (looked for views.json beside the scene and for "
                            "%s; give --views FILE)\n", view_name, PN_VIEWS_FALLBACK);
            return 2;
        }
        vr = pn_view_load(views_path, view_name, &view, err, sizeof(err));
        if (vr != 0) {
            fprintf(stderr, "penumbra: --view %s: %s\n", view_name, err);
            return 2;
        }
        if (ground < 0) ground = view.ground;
        if (bake && ground == 0) { /* an interior: its floor is no plane the CLI can name */
            fprintf(stderr, "penumbra: bake: view %s has no ground plane (\"ground\": false); give --ground on to bake "
                            "a plane under the scene\n", view_name);
            return 2;
        }
        if (!have_size && view.width > 0 && !bake) {
            opt.width = view.width;
            opt.height = view.height;
        }
    }

    if (pn_setup_load(&s, builtin ? builtin : scene, builtin != NULL, ground, err, sizeof(err)) != 0) {
        fprintf(stderr, "penumbra: %s\n", err);
        return 1;
    }
    if (view_name) pn_setup_use_view(&s, &view);
    /* Flags override the defaults one by one; the stats file records the result. */
    for (i = 0; i < 4; i++) user_view |= have[i];
    for (i = 4; i < 7; i++) user_light |= have[i];
    if (have[0]) memcpy(s.camera.eye, cam.eye, sizeof(cam.eye));
    if (have[1]) memcpy(s.camera.target, cam.target, sizeof(cam.target));
    if (have[2]) memcpy(s.camera.up, cam.up, sizeof(cam.up));
    if (have[3]) s.camera.fov_deg = cam.fov_deg;
    if (have[4]) memcpy(s.light.center, light.center, sizeof(light.center));
    if (have[5]) memcpy(s.light.u, light.u, sizeof(light.u));
    if (have[6]) memcpy(s.light.v, light.v, sizeof(light.v));
    if (user_view) snprintf(s.view_source, sizeof(s.view_source), "user");
    if (user_light) snprintf(s.light_source, sizeof(s.light_source), "user");
    if (eps_rel >= 0.0f) s.eps_rel = eps_rel;
    s.eps = s.eps_rel * s.diag;
    opt.eps = s.eps;

    if (bake && !have_size) opt.width = opt.height = 256u;
    pn_host_limits(&lim, s.mesh.triangle_count, opt.width > 0 ? opt.width : 1, opt.height > 0 ? opt.height : 1);
    if (gears_pairs >= 0) lim.gears_pairs = (uint32_t)gears_pairs;
    lim.wg_silhouettes = wg_sils;
    lim.flags |= lim_flags;
    if (pn_host_open_limits(&h, &lim, threads, err, sizeof(err)) != 0) {
        fprintf(stderr, "penumbra: %s\n", err);
        pn_setup_free(&s);
        return 1;
    }
    h.threads.progress = 1;
    h.threads.label = "render";
    memset(&cp, 0, sizeof(cp));
    if ((rs = pn_setup_upload(h.ctx, &s)) != PN_OK) {
        fprintf(stderr, "penumbra: scene rejected: %s (%s)\n", pn_last_error(h.ctx), pn_status_str(rs));
        goto fail;
    }
    if (cli_port_open(&cp, port, device, h.ctx) != 0) goto fail;
    if (bake) return cmd_bake(&s, &h, &cp, &opt, out) == 0 ? 0 : 1;
    t0 = pn_threads_now_ns(NULL);
    rs = cli_port_render(&cp, h.ctx, &s.camera, &s.light, &opt, &fr);
    ms = (pn_threads_now_ns(NULL) - t0) / 1e6;
    if (rs != PN_OK) {
        fprintf(stderr, "penumbra: render failed: %s (%s)\n", pn_last_error(h.ctx), pn_status_str(rs));
        goto fail;
    }
    pn_get_stats(h.ctx, &st);
    if (pn_write_png(out, fr.rgba, fr.width, fr.height, err, sizeof(err)) ||
        (vis && pn_write_pfm(vis, fr.visibility, fr.width, fr.height, err, sizeof(err))) ||
        (ids && pn_write_ids(ids, fr.tri_id, fr.width, fr.height, err, sizeof(err)))) {
        fprintf(stderr, "penumbra: %s\n", err);
        goto fail;
    }
    if (stats && write_stats(stats, &s, &opt, port, cli_port_device(&cp), h.threads.count, &st, ms, &fr)) {
        fprintf(stderr, "penumbra: cannot write %s: %s\n", stats, strerror(errno));
        goto fail;
    }
    fprintf(stderr, "%s: %ux%u k=%u %s/%s %.1f ms (bvh %.1f ms)\n", s.name, fr.width, fr.height, opt.k,
            algo_name(opt.algo), port, ms, st.pass_ns[PN_PASS_BVH_BUILD] / 1e6);
    cli_port_close(&cp);
    pn_host_close(&h);
    pn_setup_free(&s);
    return 0;
fail:
    cli_port_close(&cp);
    pn_host_close(&h);
    pn_setup_free(&s);
    return 1;
}

/* ---- demo --------------------------------------------------------------------------- */

static void vis_error(const float *v, const float *ref, size_t n, double *rmse, double *max_err)
{
    double se = 0.0, mx = 0.0;
    size_t p;
    for (p = 0; p < n; p++) {
        double e = fabs((double)v[p] - ref[p]);
        se += e * e;
        if (e > mx) mx = e;
    }
    *rmse = sqrt(se / (double)n);
    *max_err = mx;
}

static int cmd_demo(int argc, char **argv)
{
    const char *outdir = "out/demo";
    const char *const *names = pn_builtin_scene_names();
    uint32_t w = 384, hgt = 384, k = 16, nscenes = 0, si;
    int threads = 0, i, rc = 0;
    char err[512], path[1200];
    uint8_t *sheet;
    uint32_t cols = 2 + 2 * (PN_DEMO_ALGO_COUNT - 1u), sw, sh, gap = 4;
    for (i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) outdir = argv[++i];
        else if (strcmp(argv[i], "--size") == 0 && i + 1 < argc) {
            if (pn_parse_size(argv[++i], &w, &hgt)) { fprintf(stderr, "penumbra: bad --size\n"); return 2; }
        } else if (strcmp(argv[i], "--k") == 0 && i + 1 < argc) k = (uint32_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc) threads = atoi(argv[++i]);
        else { fprintf(stderr, "penumbra demo: unknown option %s\n", argv[i]); return 2; }
    }
    if (pn_mkdir_p(outdir)) { fprintf(stderr, "penumbra: cannot create %s\n", outdir); return 1; }
    while (names[nscenes]) nscenes++;
    /* Sheet: one row per scene: shaded reference, reference visibility, then per algorithm
     * its shaded image and its error heat map against the reference. */
    sw = cols * w + (cols + 1) * gap;
    sh = nscenes * hgt + (nscenes + 1) * gap;
    sheet = (uint8_t *)calloc((size_t)sw * sh, 4);
    if (!sheet) return 1;
    for (i = 0; i < (int)((size_t)sw * sh); i++) sheet[(size_t)i * 4 + 3] = 255;
    printf("%-16s %-10s %-7s %10s %10s %10s\n", "scene", "algorithm", "port", "ms", "rmse", "max_err");
    for (si = 0; si < nscenes; si++) {
        pn_setup s;
        pn_host h;
        pn_frame_options opt;
        float *ref = NULL;
        uint8_t *tmp, *kept;
        cli_port cp;
        size_t a, n = (size_t)w * hgt;
        if (pn_setup_load(&s, names[si], 1, -1, err, sizeof(err)) ||
            pn_host_open(&h, s.mesh.triangle_count, w, hgt, threads, err, sizeof(err))) {
            fprintf(stderr, "penumbra: %s\n", err);
            rc = 1;
            break;
        }
        pn_frame_options_default(&opt);
        opt.width = w;
        opt.height = hgt;
        opt.k = k;
        opt.eps = s.eps;
        ref = (float *)malloc(n * sizeof(float));
        tmp = (uint8_t *)malloc(n * 4);
        kept = (uint8_t *)malloc(n * 8);
        memset(&cp, 0, sizeof(cp));
        if (!ref || !tmp || !kept || pn_setup_upload(h.ctx, &s) != PN_OK) {
            fprintf(stderr, "penumbra: %s: %s\n", names[si], h.ctx ? pn_last_error(h.ctx) : "out of memory");
            rc = 1;
        }
        /* Every frame again on the OpenCL port when it is built: same bytes, its time. */
        if (rc == 0 && PN_HAVE_OPENCL && cli_port_open(&cp, "opencl", NULL, h.ctx) != 0)
            fprintf(stderr, "penumbra demo: scalar port only\n");
        for (a = 0; rc == 0 && a < PN_ALGO_COUNT; a++) {
            pn_frame fr;
            uint64_t t0;
            double ms, se = 0.0, mx = 0.0;
            /* the sheet's column: the reference, then every other algorithm but raytrace */
            uint32_t d = (uint32_t)a - ((uint32_t)a > PN_ALGO_RAYTRACE), col = d == 0 ? 0 : 2 + 2 * (d - 1u);
            const char *an = pn_algo_name((pn_algo)a);
            if (a == PN_ALGO_RAYTRACE || !(pn_build_info() & (1u << a))) continue;
            opt.algo = (pn_algo)a;
            t0 = pn_threads_now_ns(NULL);
            if (pn_render(h.ctx, &s.camera, &s.light, &opt, &fr) != PN_OK) {
                fprintf(stderr, "penumbra: %s/%s: %s\n", names[si], an, pn_last_error(h.ctx));
                rc = 1;
                break;
            }
            ms = (pn_threads_now_ns(NULL) - t0) / 1e6;
            if (a == 0) memcpy(ref, fr.visibility, n * sizeof(float));
            vis_error(fr.visibility, ref, n, &se, &mx);
            printf("%-16s %-10s %-7s %10.1f %10.6f %10.6f\n", names[si], an, "scalar", ms, se, mx);
            snprintf(path, sizeof(path), "%s/%s_%s.png", outdir, names[si], an);
            if (pn_write_png(path, fr.rgba, w, hgt, err, sizeof(err))) { fprintf(stderr, "%s\n", err); rc = 1; }
            pn_blit_rgba(sheet, sw, fr.rgba, w, hgt, gap + col * (w + gap), gap + si * (hgt + gap));
            if (a == 0) {
                pn_vis_to_rgba(fr.visibility, n, tmp);
                pn_blit_rgba(sheet, sw, tmp, w, hgt, gap + 1 * (w + gap), gap + si * (hgt + gap));
            } else {
                pn_err_to_rgba(fr.visibility, ref, n, tmp);
                pn_blit_rgba(sheet, sw, tmp, w, hgt, gap + (col + 1) * (w + gap), gap + si * (hgt + gap));
            }
#if PN_HAVE_OPENCL
            if (cp.cl) { /* after the sheet used the scalar frame: this one overwrites it */
                pn_frame fo;
                memcpy(kept, fr.visibility, n * 4);
                memcpy(kept + n * 4, fr.rgba, n * 4);
                t0 = pn_threads_now_ns(NULL);
                if (cli_port_render(&cp, h.ctx, &s.camera, &s.light, &opt, &fo) != PN_OK) {
                    fprintf(stderr, "penumbra: %s/%s/opencl: %s\n", names[si], an, pn_last_error(h.ctx));
                    rc = 1;
                    break;
                }
                ms = (pn_threads_now_ns(NULL) - t0) / 1e6;
                vis_error(fo.visibility, ref, n, &se, &mx);
                printf("%-16s %-10s %-7s %10.1f %10.6f %10.6f\n", names[si], an, "opencl", ms, se, mx);
                if (memcmp(kept, fo.visibility, n * 4) != 0 || memcmp(kept + n * 4, fo.rgba, n * 4) != 0) {
                    fprintf(stderr, "penumbra: %s/%s: the OpenCL frame differs from the scalar one\n", names[si],
                            an);
                    rc = 1;
                }
            }
#endif
        }
        free(ref);
        free(tmp);
        free(kept);
        cli_port_close(&cp);
        pn_host_close(&h);
        pn_setup_free(&s);
        if (rc) break;
    }
    if (rc == 0) {
        snprintf(path, sizeof(path), "%s/sheet.png", outdir);
        if (pn_write_png(path, sheet, sw, sh, err, sizeof(err))) { fprintf(stderr, "%s\n", err); rc = 1; }
        else printf("wrote %s/*.png and %s (rows: scenes; columns: shaded reference, reference visibility, "
                    "then each algorithm's image and its error x4 heat map)\n", outdir, path);
    }
    free(sheet);
    return rc;
}

/* penumbra info: the OpenCL devices, with their type and whether the port takes them; with
 * build, each one the checks pass is also opened on a small context (kernels built, the
 * numerics probe run), which is what decides. */
static void cl_info(int build)
{
#if PN_HAVE_OPENCL
    enum { CAP = 16 };
    static pn_opencl_device devs[CAP];
    unsigned n = 0, i;
    pn_status st = pn_opencl_devices(devs, CAP, &n);
    printf("OpenCL devices (--cl-device / PN_OPENCL_DEVICE: P:D, gpu, cpu, accelerator, gpu:N, or part of the name):\n");
    if (st != PN_OK || n == 0) {
        printf("  none: no OpenCL platform or device is installed (%s)\n", pn_status_str(st));
        return;
    }
    for (i = 0; i < n && i < CAP; i++) {
        const pn_opencl_device *d = &devs[i];
        printf("  %-5s %-11s %s / %s [%s]: ", d->spec, d->type, d->platform, d->name, d->version);
        if (!d->usable) {
            printf("refused: %s\n", d->problem);
            continue;
        }
        if (!build) {
            printf("checks pass (kernels not built: --no-build)\n");
            continue;
        }
        {
            pn_host h;
            char err[256];
            pn_opencl *cl = NULL;
            pn_opencl_options o;
            pn_opencl_info info;
            if (pn_host_open(&h, 16, 16, 16, 1, err, sizeof(err)) != 0) {
                printf("cannot open a context: %s\n", err);
                continue;
            }
            pn_opencl_options_default(&o);
            o.device = d->spec;
            st = pn_cl_open(h.ctx, &o, &cl);
            if (st == PN_OK && pn_opencl_get_info(cl, &info) == PN_OK)
                printf("accepted (kernels built in %.0f ms + %.0f ms first launches, numerics probe passed)\n",
                       info.build_ms, info.warmup_ms);
            else
                printf("refused: %s (%s)\n", pn_last_error(h.ctx), pn_status_str(st));
            pn_cl_close(cl);
            pn_host_close(&h);
        }
    }
    if (n > CAP) printf("  ... and %u more\n", n - CAP);
#else
    (void)build;
    printf("OpenCL devices: the OpenCL port is not built\n");
#endif
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "render") == 0) return cmd_render(argc - 2, argv + 2, 0);
    if (strcmp(argv[1], "bake") == 0) return cmd_render(argc - 2, argv + 2, 1);
    if (strcmp(argv[1], "demo") == 0) return cmd_demo(argc - 2, argv + 2);
    if (strcmp(argv[1], "info") == 0) {
        int build = !(argc > 2 && strcmp(argv[2], "--no-build") == 0);
        if (argc > 2 + !build) {
            usage(stderr);
            return 2;
        }
        printf("penumbra build: flags 0x%x, PN_MASK_K_MAX %u, PN_MAX_TRIANGLES %u, max image %ux%u\n",
               pn_build_info(), (unsigned)PN_MASK_K_MAX, (unsigned)PN_MAX_TRIANGLES, (unsigned)PN_MAX_WIDTH,
               (unsigned)PN_MAX_HEIGHT);
        usage(stdout);
        cl_info(build);
        return 0;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        usage(stdout);
        return 0;
    }
    fprintf(stderr, "penumbra: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
