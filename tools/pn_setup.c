#include "pn_setup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pn_gltf.h"
#include "pn_scenes.h"

static void pn_basename(const char *path, char *out, size_t n)
{
    const char *b = strrchr(path, '/');
    snprintf(out, n, "%s", b ? b + 1 : path);
    {
        char *dot = strrchr(out, '.');
        if (dot) *dot = '\0';
    }
}

void pn_setup_auto_view(const float bmin[3], const float bmax[3], pn_camera *cam, pn_light *light)
{
    float c[3], d[3], diag;
    int a;
    for (a = 0; a < 3; a++) {
        c[a] = 0.5f * (bmin[a] + bmax[a]);
        d[a] = bmax[a] - bmin[a];
    }
    diag = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(diag > 0.0f)) diag = 1.0f;
    {
        /* Direction (0.6, 0.55, 1.0), normalized, at 1.5 diagonals: the box fits a 40 degree fov. */
        float dir[3] = {0.6f, 0.55f, 1.0f};
        float len = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (a = 0; a < 3; a++) {
            cam->eye[a] = c[a] + dir[a] / len * 1.5f * diag;
            cam->target[a] = c[a];
        }
        cam->up[0] = 0.0f;
        cam->up[1] = 1.0f;
        cam->up[2] = 0.0f;
        cam->fov_deg = 40.0f;
    }
    light->center[0] = c[0] + 0.25f * diag;
    light->center[1] = c[1] + 1.0f * diag;
    light->center[2] = c[2] + 0.15f * diag;
    /* u x v = (0, -s^2, 0): emits downward. */
    light->u[0] = 0.1f * diag;
    light->u[1] = 0.0f;
    light->u[2] = 0.0f;
    light->v[0] = 0.0f;
    light->v[1] = 0.0f;
    light->v[2] = 0.1f * diag;
}

int pn_setup_load(pn_setup *s, const char *source, int builtin, int ground, char *err, size_t err_size)
{
    memset(s, 0, sizeof(*s));
    s->eps_rel = 1e-4f;
    if (builtin) {
        pn_scene_view view;
        if (pn_builtin_scene(source, &s->mesh, &view, err, err_size) != 0) return 1;
        pn_scene_view_apply(&view, &s->camera, &s->light);
        snprintf(s->name, sizeof(s->name), "%s", source);
        snprintf(s->view_source, sizeof(s->view_source), "builtin");
        snprintf(s->light_source, sizeof(s->light_source), "builtin");
        s->builtin = 1;
        if (ground < 0) ground = 0;
    } else {
        if (pn_gltf_load(source, &s->mesh, err, err_size) != 0) return 1;
        pn_setup_auto_view(s->mesh.bbox_min, s->mesh.bbox_max, &s->camera, &s->light);
        pn_basename(source, s->name, sizeof(s->name));
        snprintf(s->view_source, sizeof(s->view_source), "auto");
        snprintf(s->light_source, sizeof(s->light_source), "auto");
        if (ground < 0) ground = 1;
    }
    s->diag = pn_mesh_diag(&s->mesh);
    s->eps = s->eps_rel * s->diag;
    if (ground) {
        if (pn_mesh_add_ground(&s->mesh, err, err_size) != 0) {
            pn_mesh_free(&s->mesh);
            return 1;
        }
        s->ground = 1;
    }
    return 0;
}

int pn_views_file_for(const char *scene_path, char *out, size_t out_size)
{
    FILE *f;
    if (scene_path) {
        const char *slash = strrchr(scene_path, '/');
        int n = slash ? (int)(slash - scene_path) : 0;
        snprintf(out, out_size, "%.*s%sviews.json", n, scene_path, slash ? "/" : "");
        if ((f = fopen(out, "rb")) != NULL) {
            fclose(f);
            return 0;
        }
    }
    snprintf(out, out_size, "%s", PN_VIEWS_FALLBACK);
    if ((f = fopen(out, "rb")) != NULL) {
        fclose(f);
        return 0;
    }
    return 1;
}

int pn_view_for_scene(const char *dir, const char *name, pn_view *v, char *err, size_t err_size)
{
    char path[1200];
    FILE *f;
    int rc;
    snprintf(path, sizeof(path), "%s/views.json", dir);
    if ((f = fopen(path, "rb")) == NULL) return 1;
    fclose(f);
    rc = pn_view_load(path, name, v, err, err_size);
    return rc;
}

void pn_setup_use_view(pn_setup *s, const pn_view *v)
{
    s->camera = v->camera;
    s->light = v->light;
    snprintf(s->view_source, sizeof(s->view_source), "view");
    snprintf(s->light_source, sizeof(s->light_source), "view");
}

int pn_setup_load_viewed(pn_setup *s, const char *source, int builtin, const char *views_dir, char *err,
                         size_t err_size)
{
    pn_view v;
    int hv = 1;
    if (!builtin && views_dir) {
        char stem[128];
        pn_basename(source, stem, sizeof(stem));
        hv = pn_view_for_scene(views_dir, stem, &v, err, err_size);
        if (hv == 2) {
            memset(s, 0, sizeof(*s));
            return 1;
        }
    }
    if (pn_setup_load(s, source, builtin, hv == 0 ? v.ground : -1, err, err_size) != 0) return 1;
    if (hv == 0) pn_setup_use_view(s, &v);
    return 0;
}

void pn_setup_free(pn_setup *s)
{
    pn_mesh_free(&s->mesh);
    memset(s, 0, sizeof(*s));
}

pn_status pn_setup_upload(pn_context *ctx, const pn_setup *s)
{
    pn_status st;
    if (ctx == NULL || s == NULL) return PN_E_INVALID_ARG;
    st = pn_scene_set(ctx, s->mesh.positions, s->mesh.vertex_count, s->mesh.indices, s->mesh.triangle_count);
    if (st != PN_OK) return st;
    return pn_scene_set_receivers(ctx, s->mesh.receiver_first, s->mesh.receiver_count);
}

void pn_host_limits(pn_limits *lim, uint32_t max_triangles, uint32_t max_w, uint32_t max_h)
{
    memset(lim, 0, sizeof(*lim));
    lim->max_triangles = max_triangles;
    lim->max_width = max_w;
    lim->max_height = max_h;
    {
        /* A host has the memory: reserve the split references (the library reserves them
         * only on request), with which the exact algorithms trace slivers faster. */
        uint64_t refs = (uint64_t)max_triangles + PN_BVH_SPLIT_EXTRA(max_triangles), most = 1u << 26;
        lim->bvh_refs = (uint32_t)(refs <= most ? refs : max_triangles > most ? max_triangles : most);
    }
    /* ...GEARS grids up to 256 (the benchmark's grid sweep, the CLI's --grid), and GEARS'
     * largest pair pool (frames in one pass where the default would tile them). */
    lim->gears_grid_max = 256;
    lim->gears_pairs = PN_GEARS_PAIRS;
}

int pn_host_open(pn_host *h, uint32_t max_triangles, uint32_t max_w, uint32_t max_h, int threads,
                 char *err, size_t err_size)
{
    pn_limits lim;
    pn_host_limits(&lim, max_triangles, max_w, max_h);
    return pn_host_open_limits(h, &lim, threads, err, err_size);
}

int pn_host_open_limits(pn_host *h, const pn_limits *limits, int threads, char *err, size_t err_size)
{
    pn_limits lim = *limits;
    pn_status st;
    memset(h, 0, sizeof(*h));
    st = pn_arena_size(&lim, &h->bytes);
    if (st != PN_OK) {
        snprintf(err, err_size, "pn_arena_size: %s", pn_status_str(st));
        return 1;
    }
    h->memory = malloc(h->bytes);
    if (!h->memory) {
        snprintf(err, err_size, "cannot allocate %zu bytes of arena", h->bytes);
        return 1;
    }
    st = pn_init(&h->ctx, h->memory, h->bytes, &lim);
    if (st != PN_OK) {
        snprintf(err, err_size, "pn_init: %s", pn_status_str(st));
        free(h->memory);
        h->memory = NULL;
        return 1;
    }
    h->threads.count = threads > 0 ? threads : pn_threads_cores();
    h->threads.progress = 0;
    h->threads.label = NULL;
    pn_set_parallel_for(h->ctx, pn_threads_parallel_for, &h->threads);
    pn_set_clock(h->ctx, pn_threads_now_ns, NULL);
    return 0;
}

void pn_host_close(pn_host *h)
{
    free(h->memory);
    memset(h, 0, sizeof(*h));
}

int pn_parse_vec3(const char *s, float out[3])
{
    char tail;
    float v[3];
    if (!s || sscanf(s, "%f,%f,%f%c", &v[0], &v[1], &v[2], &tail) != 3) return 1;
    memcpy(out, v, sizeof(v));
    return 0;
}

int pn_parse_size(const char *s, uint32_t *w, uint32_t *h)
{
    unsigned a, b;
    char tail;
    if (!s || sscanf(s, "%ux%u%c", &a, &b, &tail) != 2) return 1;
    *w = a;
    *h = b;
    return 0;
}
