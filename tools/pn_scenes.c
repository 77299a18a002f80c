/* pn_scenes.c - built-in procedural scenes (see pn_scenes.h).
 *
 * Layout of every mesh: the scene's own geometry first, in the order described at each
 * builder, then the ground (two triangles, four vertices) last. Tests rely on it. The
 * receiver range (pn_mesh.receiver_*) ends at the last triangle: the ground, and for
 * closed-box the box's inner floor just before it (pn_sc_receivers_next before them).
 *
 * Determinism: all randomness comes from an integer hash (lowbias32) of (seed, counter);
 * positions are computed in double and rounded to float once. The sphere and sliver
 * builders call libm sin/cos (spheres, thin, room, canopy, colonnade), so bit-exact positions across
 * different libms are not promised (glibc's are correctly rounded in practice); the square
 * and box scenes use only exactly representable constants.
 *
 * Files: pn_scenes.c (this one: the public entry points, the name tables, the `square`
 * scene's parameters and closed form), pn_scenes_build.h/.c (the builder and the shared
 * geometry helpers), pn_scenes_objects.c (square, spheres, elongated-cube, thin) and
 * pn_scenes_sets.c (room, closed-box, canopy, colonnade). */
#include "pn_scenes.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pn_scenes_build.h"

/* ---- The square scene's parameters ---------------------------------------------------- */

void pn_square_scene_params(pn_square_params *p)
{
    /* Occluder at half the light height: seen from the receiver its projection onto the
     * light plane is twice its size, so the umbra is |x|, |z| <= 2*0.5 - 0.5 = 0.5 and the
     * penumbra reaches |x| or |z| = 2*0.5 + 0.5 = 1.5. All values exact in float. */
    p->light_y = 4.0f;
    p->light_half = 0.5f;
    p->occluder_y = 2.0f;
    p->occluder_half = 0.5f;
    p->ground_y = 0.0f;
    p->ground_half = 4.0f;
}

/* ---- Public entry points -------------------------------------------------------------- */

typedef int (*pn_sc_build_fn)(pn_sc_builder *b, pn_scene_view *v);

/* pn_sc_all_names indexes pn_sc_builders; pn_sc_names is its first PN_SC_SHARED entries
 * (the set every frame test, the demo and the benchmark iterate). */
#define PN_SC_SHARED 7
static const char *const pn_sc_names[] = {"square", "spheres",  "elongated-cube", "thin",
                                           "room",   "canopy",   "colonnade",      NULL};
static const char *const pn_sc_all_names[] = {"square", "spheres",   "elongated-cube",
                                               "thin",   "room",      "canopy",
                                               "colonnade", "closed-box", NULL};
static const pn_sc_build_fn pn_sc_builders[] = {
    pn_sc_build_square,
    pn_sc_build_spheres,
    pn_sc_build_elongated_cube,
    pn_sc_build_thin,
    pn_sc_build_room,
    pn_sc_build_canopy,
    pn_sc_build_colonnade,
    pn_sc_build_closed_box,
};
/* Compile-time checks of the three tables' lengths (a negative array size fails). */
#define PN_SC_LEN(a) (sizeof(a) / sizeof((a)[0]))
typedef char pn_sc_check_shared[PN_SC_LEN(pn_sc_names) == PN_SC_SHARED + 1 ? 1 : -1];
typedef char
    pn_sc_check_builders[PN_SC_LEN(pn_sc_builders) + 1 == PN_SC_LEN(pn_sc_all_names) ? 1 : -1];

const char *const *pn_builtin_scene_names(void) { return pn_sc_names; }

const char *const *pn_builtin_scene_names_all(void) { return pn_sc_all_names; }

int pn_builtin_scene(const char *name, pn_mesh *out, pn_scene_view *view, char *err,
                     size_t err_size)
{
    pn_sc_builder b;
    pn_scene_view v;
    size_t i;

    if (out == NULL) {
        pn_tools_err(err, err_size, "pn_builtin_scene: out is NULL");
        return 1;
    }
    memset(out, 0, sizeof(*out));
    if (name == NULL) {
        pn_tools_err(err, err_size, "pn_builtin_scene: name is NULL");
        return 1;
    }
    for (i = 0; pn_sc_all_names[i] != NULL; i++) {
        if (strcmp(name, pn_sc_all_names[i]) == 0) {
            break;
        }
    }
    if (pn_sc_all_names[i] == NULL) {
        pn_tools_err(err, err_size,
                      "unknown built-in scene '%s' (known: square, spheres, elongated-cube, "
                      "thin, room, canopy, colonnade, closed-box)",
                      name);
        return 2;
    }
    memset(&v, 0, sizeof(v));
    if (pn_sc_builders[i](&b, &v) != 0) {
        pn_tools_err(err, err_size, "built-in scene '%s': out of memory", name);
        return 3;
    }
    if (b.overflow || b.nv != b.cap_v || b.nt != b.cap_t) {
        /* Unreachable unless a builder's counts drift from its capacity. */
        free(b.pos);
        free(b.idx);
        pn_tools_err(err, err_size,
                      "built-in scene '%s': internal error (%u/%u vertices, %u/%u triangles)",
                      name, (unsigned)b.nv, (unsigned)b.cap_v, (unsigned)b.nt,
                      (unsigned)b.cap_t);
        return 4;
    }
    out->positions = b.pos;
    out->vertex_count = b.nv;
    out->indices = b.idx;
    out->triangle_count = b.nt;
    out->receiver_first = b.recv_first;
    out->receiver_count = b.recv_count;
    pn_mesh_update_bbox(out);
    if (view != NULL) {
        *view = v;
    }
    return 0;
}

/* ---- Closed form of the square scene -------------------------------------------------- *
 *
 * Both squares are axis-aligned and parallel to the light, so a light point (s, t) (light
 * coordinates along x and z) is hidden from receiver point (x, z) iff the segment crosses
 * y = occluder_y inside the square, and the crossing is, per axis, the linear blend
 * x + f (s - x) with f = (occluder_y - ground_y) / (light_y - ground_y). The hidden set is
 * therefore a product of two intervals and every fraction factors per axis. */

/* Fraction of the light's extent hidden along one axis, for receiver coordinate x. */
static double pn_sc_axis_hidden(const pn_square_params *p, double x, int k)
{
    double f = ((double)p->occluder_y - (double)p->ground_y) /
               ((double)p->light_y - (double)p->ground_y);
    double L = (double)p->light_half, h = (double)p->occluder_half;
    if (k <= 0) {
        /* Hidden light coordinates: |x + f (s - x)| <= h  <=>  s in [lo, hi]. */
        double lo = (-h - (1.0 - f) * x) / f, hi = (h - (1.0 - f) * x) / f;
        double a = lo > -L ? lo : -L, c = hi < L ? hi : L;
        return c > a ? (c - a) / (2.0 * L) : 0.0;
    } else {
        int i, n = 0;
        for (i = 0; i < k; i++) {
            double s = ((double)(2 * i + 1) / (double)k - 1.0) * L;
            double cross = x + f * (s - x);
            if (fabs(cross) <= h) {
                n++;
            }
        }
        return (double)n / (double)k;
    }
}

double pn_square_closed_form(const pn_square_params *p, double x, double z, int k)
{
    return 1.0 - pn_sc_axis_hidden(p, x, k) * pn_sc_axis_hidden(p, z, k);
}

double pn_square_min_edge_distance(const pn_square_params *p, double x, double z, int k)
{
    double f, L, h, lox, hix, loz, hiz, best = HUGE_VAL;
    int i, j;
    if (k <= 0) {
        return HUGE_VAL;
    }
    f = ((double)p->occluder_y - (double)p->ground_y) /
        ((double)p->light_y - (double)p->ground_y);
    L = (double)p->light_half;
    h = (double)p->occluder_half;
    /* Occluder square projected from the receiver point onto the light plane. */
    lox = (-h - (1.0 - f) * x) / f;
    hix = (h - (1.0 - f) * x) / f;
    loz = (-h - (1.0 - f) * z) / f;
    hiz = (h - (1.0 - f) * z) / f;
    for (j = 0; j < k; j++) {
        double t = ((double)(2 * j + 1) / (double)k - 1.0) * L;
        for (i = 0; i < k; i++) {
            double s = ((double)(2 * i + 1) / (double)k - 1.0) * L;
            double d;
            if (s >= lox && s <= hix && t >= loz && t <= hiz) {
                /* Inside: nearest of the four edges. */
                d = s - lox;
                if (hix - s < d) d = hix - s;
                if (t - loz < d) d = t - loz;
                if (hiz - t < d) d = hiz - t;
            } else {
                double dx = s < lox ? lox - s : (s > hix ? s - hix : 0.0);
                double dz = t < loz ? loz - t : (t > hiz ? t - hiz : 0.0);
                d = sqrt(dx * dx + dz * dz);
            }
            if (d < best) {
                best = d;
            }
        }
    }
    return best;
}

void pn_scene_view_apply(const pn_scene_view *v, pn_camera *camera, pn_light *light)
{
    memcpy(camera->eye, v->eye, sizeof(v->eye));
    memcpy(camera->target, v->target, sizeof(v->target));
    memcpy(camera->up, v->up, sizeof(v->up));
    camera->fov_deg = v->fov_deg;
    memcpy(light->center, v->light_center, sizeof(v->light_center));
    memcpy(light->u, v->light_u, sizeof(v->light_u));
    memcpy(light->v, v->light_v, sizeof(v->light_v));
}
