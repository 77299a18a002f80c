/* pn_mesh.c - host-side triangle mesh helpers (see pn_mesh.h). */
#include "pn_mesh.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void pn_tools_err(char *err, size_t err_size, const char *fmt, ...)
{
    va_list ap;
    if (err == NULL || err_size == 0) {
        return;
    }
    va_start(ap, fmt);
    vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
}

void pn_mesh_free(pn_mesh *mesh)
{
    if (mesh == NULL) {
        return;
    }
    free(mesh->positions);
    free(mesh->indices);
    memset(mesh, 0, sizeof(*mesh));
}

void pn_mesh_update_bbox(pn_mesh *mesh)
{
    float lo[3] = {0.0f, 0.0f, 0.0f};
    float hi[3] = {0.0f, 0.0f, 0.0f};
    int any = 0;
    uint64_t i, n;
    int k;

    if (mesh == NULL) {
        return;
    }
    n = (uint64_t)mesh->triangle_count * 3u;
    if (mesh->positions != NULL && mesh->indices != NULL) {
        for (i = 0; i < n; i++) {
            uint32_t v = mesh->indices[i];
            const float *p;
            /* The header promises indices < vertex_count; skipping a bad one keeps this
             * function memory-safe on a mesh that has not been validated yet. */
            if (v >= mesh->vertex_count) {
                continue;
            }
            p = mesh->positions + (size_t)v * 3u;
            for (k = 0; k < 3; k++) {
                if (!any || p[k] < lo[k]) {
                    lo[k] = p[k];
                }
                if (!any || p[k] > hi[k]) {
                    hi[k] = p[k];
                }
            }
            any = 1;
        }
    }
    for (k = 0; k < 3; k++) {
        mesh->bbox_min[k] = lo[k];
        mesh->bbox_max[k] = hi[k];
    }
}

float pn_mesh_diag(const pn_mesh *mesh)
{
    double s = 0.0;
    int k;
    if (mesh == NULL) {
        return 0.0f;
    }
    /* double so that tiny (CAD, metres) and huge extents neither underflow nor overflow
     * in the squares. */
    for (k = 0; k < 3; k++) {
        double d = (double)mesh->bbox_max[k] - (double)mesh->bbox_min[k];
        s += d * d;
    }
    return (float)sqrt(s);
}

int pn_mesh_add_ground(pn_mesh *mesh, char *err, size_t err_size)
{
    float diag, y, cx, cz, h;
    float *pos;
    uint32_t *idx;
    uint32_t v0;
    size_t nv, nt;

    if (mesh == NULL) {
        pn_tools_err(err, err_size, "pn_mesh_add_ground: mesh is NULL");
        return 1;
    }
    if (mesh->triangle_count == 0 || mesh->vertex_count == 0 || mesh->positions == NULL ||
        mesh->indices == NULL) {
        pn_tools_err(err, err_size, "pn_mesh_add_ground: mesh is empty");
        pn_mesh_free(mesh);
        return 1;
    }
    /* The ground is sized from the stored bbox (the loaders keep it current); a mesh that
     * collapses to a point would give a zero-area ground, which is an input error, not a
     * plane. */
    diag = pn_mesh_diag(mesh);
    if (!(diag > 0.0f) || !isfinite(diag)) {
        pn_tools_err(err, err_size,
                        "pn_mesh_add_ground: mesh bounding box has no extent (diagonal %g)",
                        (double)diag);
        pn_mesh_free(mesh);
        return 1;
    }
    if (mesh->vertex_count > UINT32_MAX - 4u || mesh->triangle_count > UINT32_MAX / 3u - 2u) {
        pn_tools_err(err, err_size, "pn_mesh_add_ground: mesh too large to extend");
        pn_mesh_free(mesh);
        return 1;
    }

    nv = (size_t)mesh->vertex_count + 4u;
    nt = (size_t)mesh->triangle_count + 2u;
    pos = (float *)realloc(mesh->positions, nv * 3u * sizeof(float));
    if (pos == NULL) {
        pn_tools_err(err, err_size, "pn_mesh_add_ground: out of memory (%zu vertices)", nv);
        pn_mesh_free(mesh);
        return 1;
    }
    mesh->positions = pos;
    idx = (uint32_t *)realloc(mesh->indices, nt * 3u * sizeof(uint32_t));
    if (idx == NULL) {
        pn_tools_err(err, err_size, "pn_mesh_add_ground: out of memory (%zu triangles)", nt);
        pn_mesh_free(mesh);
        return 1;
    }
    mesh->indices = idx;

    /* Centre and offset in double so the plane position is the same whichever order
     * the terms are evaluated in; the 1e-3*diag drop keeps the ground strictly below the
     * lowest vertex so no scene triangle is coplanar with it. */
    cx = (float)(0.5 * ((double)mesh->bbox_min[0] + (double)mesh->bbox_max[0]));
    cz = (float)(0.5 * ((double)mesh->bbox_min[2] + (double)mesh->bbox_max[2]));
    y = (float)((double)mesh->bbox_min[1] - 1e-3 * (double)diag);
    h = 2.0f * diag;

    v0 = mesh->vertex_count;
    pos += (size_t)v0 * 3u;
    /* v0 (-x,-z), v1 (+x,-z), v2 (+x,+z), v3 (-x,+z) */
    pos[0] = cx - h;  pos[1] = y;  pos[2] = cz - h;
    pos[3] = cx + h;  pos[4] = y;  pos[5] = cz - h;
    pos[6] = cx + h;  pos[7] = y;  pos[8] = cz + h;
    pos[9] = cx - h;  pos[10] = y; pos[11] = cz + h;

    /* (v0, v3, v2) and (v0, v2, v1): (b - a) x (c - a) = +y for both, i.e. counter-clockwise
     * when seen from above. */
    idx += (size_t)mesh->triangle_count * 3u;
    idx[0] = v0;      idx[1] = v0 + 3u; idx[2] = v0 + 2u;
    idx[3] = v0;      idx[4] = v0 + 2u; idx[5] = v0 + 1u;

    /* The receiver range: contiguous by definition, so it can take the new ground in only
     * when it ends where the ground begins. */
    if (mesh->receiver_count > 0u && mesh->receiver_first <= mesh->triangle_count &&
        mesh->receiver_count == mesh->triangle_count - mesh->receiver_first) {
        mesh->receiver_count += 2u;
    } else {
        mesh->receiver_first = mesh->triangle_count;
        mesh->receiver_count = 2u;
    }
    mesh->vertex_count += 4u;
    mesh->triangle_count += 2u;
    return 0;
}

/* lowbias32 (C. Wellons, "Prospecting for hash functions"): a full-avalanche integer
 * hash; the generator is hash(seed ^ hash(counter)), stateless and order-independent. */
uint32_t pn_hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
