/* pn_scenes.h - built-in procedural scenes for the CLI, tests and benchmarks. Host code:
 * not part of the library, firmware never sees it.
 *
 * Every scene carries its own receiver (ground) geometry; the CLI's --ground flag is for
 * glTF scenes only. Conventions are those of penumbra.h: right-handed, Y up, light
 * centre c with half-edges u, v emitting toward N = normalize(u x v). Every built-in scene
 * puts the light above the geometry with N = -y, and every vertex strictly on the
 * emitting side of the light plane, except room's ceiling: an interior's light hangs below
 * its ceiling, so the ceiling and the top 1/16 of the walls lie behind the light (dark,
 * which the library defines: penumbra.h, "Light") and the walls cross the light plane.
 *
 * Scenes:
 *   square          axis-aligned square light over a parallel square occluder over a
 *                   receiver plane; the visibility on the receiver has a closed form
 *                   (pn_square_closed_form).
 *   spheres         9 x 9 spheres of 762 triangles each floating over a plane, the scene
 *                   of Forest et al. 2006 (penumbra-wedges blending), with a light wide
 *                   enough that neighbouring penumbrae overlap.
 *   elongated-cube  the hard case of Curtis 2009 (Monte Carlo shadow maps, Fig. 4.2): a
 *                   closed box long along the light's axis, floating over a plane.
 *   thin            2000 slivers (length 2, width 0.002) over a plane: where shadow maps
 *                   lose.
 *   room            an interior: a closed room under a ceiling light, with a table, six
 *                   chairs (four thin legs, the seat and back one open single-layer
 *                   shell), a bookcase of books, an open stair with thin balusters and
 *                   three spheres (4674 triangles): many occluders behind one another,
 *                   open sheets, and no background (the camera is inside).
 *   canopy          a tree: 3000 small leaves (double-sided: two coincident quads of
 *                   opposite winding each) at hashed orientations in clumps inside an
 *                   ellipsoidal crown, a trunk and six branches, over a ground under a
 *                   1.2 x 1.2 light (12150 triangles): dappled light, thousands of tiny
 *                   overlapping occluders, coincident back-to-back faces.
 *   colonnade       two facing rows of eight 12-sided columns (plinth, shaft, capital)
 *                   carrying semicircular arches of 11 voussoirs each under an
 *                   entablature beam, on a floor, under a 1 x 1 light high above and
 *                   offset (2962 triangles): curved shadows, column shadows across each
 *                   other's.
 *   closed-box      light leaks (58 triangles): a hollow box with walls 0.25 thick (outer
 *                   4 x 3 x 4, floating 0.5 over the ground) and one 0.5 x 0.5 square hole
 *                   through its top straight under a 1 x 1 light; a 0.5 cube stands on the
 *                   cavity floor at the edge of the spot the hole lets in. Everything inside
 *                   but that spot is dark; the camera is inside, looking down at the floor,
 *                   so a shadow map's leaks show as lit pixels where the reference has 0.
 *                   Not in pn_builtin_scene_names() (see there).
 *
 * Receivers (pn_mesh.receiver_first/count): every scene's range ends at its last
 * triangle and holds its pure receivers, floors with nothing beneath them (closed-box's
 * cavity floor: only the box's own bottom slab):
 *   square, spheres, elongated-cube, thin,  the ground: the last 2 triangles;
 *   canopy, colonnade
 *   room                                    the floor only (the last 2): the ceiling and
 *                                           the walls (the 10 before it) are left out;
 *   closed-box                              the cavity floor and the ground: the last 4.
 *
 * Meshes: indexed, shared vertices wherever a surface is closed (spheres, boxes, prisms,
 * voussoirs), CCW winding with outward normals (open sheets face +y, room's chair shells
 * their sitter: the seat up, the back forward; canopy's leaves are two-sided, a quad
 * each way on the same vertices; room's shell faces into the room;
 * closed-box's surface faces out of its material, so into the cavity inside it),
 * bbox filled over all vertices (ground included). Deterministic: the same name gives the
 * same mesh on every run. */
#ifndef PN_TOOLS_SCENES_H
#define PN_TOOLS_SCENES_H

#include <stddef.h>

#include "penumbra/penumbra.h"
#include "pn_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Default view and light for a built-in scene. Camera fields follow pn_camera (fov is
 * vertical, degrees); light fields follow pn_light. The view frames every vertex of the
 * scene at aspect ratio 1 (and therefore at any wider aspect); room's eye is inside the
 * room, so there it frames every vertex of the furniture, and the shell fills the rest;
 * closed-box's eye is inside the box's cavity and frames the cube and the spot under the
 * hole, the cavity's floor and walls filling the rest. */
typedef struct pn_scene_view {
    float eye[3], target[3], up[3], fov_deg;
    float light_center[3], light_u[3], light_v[3]; /* half-edges; N = normalize(u x v)
                                                      points toward the scene (the light
                                                      emits toward +N) */
} pn_scene_view;

/* The view's camera and light as the library takes them. */
void pn_scene_view_apply(const pn_scene_view *v, pn_camera *camera, pn_light *light);

/* Builds built-in scene `name` into *out (malloc'd arrays, free with pn_mesh_free);
 * fills *view if view != NULL. out and name must not be NULL; err may be NULL.
 * Returns 0, or non-zero with a message in err for an unknown name or an allocation
 * failure; on failure *out is left empty (zeroed) and *view is not written. */
int pn_builtin_scene(const char *name, pn_mesh *out, pn_scene_view *view, char *err,
                     size_t err_size);

/* NULL-terminated list of the shared scene names: square, spheres, elongated-cube, thin,
 * room, canopy, colonnade; the set the demo, the golden hashes (tests/test_golden.c), the benchmark and the
 * per-algorithm frame tests iterate. Static storage. */
const char *const *pn_builtin_scene_names(void);

/* NULL-terminated list of every name pn_builtin_scene() knows: the shared ones, then the
 * special-purpose scenes (closed-box), for --help and tests/test_scenes.c. Static storage. */
const char *const *pn_builtin_scene_names_all(void);

/* ---- The analytic `square` scene ------------------------------------------------------ */

/* Light: centre (0, light_y, 0), half-edges (light_half, 0, 0) and (0, 0, light_half)
 * (u x v = -y: emits downward). Occluder: the closed square |x|, |z| <= occluder_half at
 * y = occluder_y (two triangles). Receiver: |x|, |z| <= ground_half at y = ground_y (two
 * triangles). All values are exactly representable in float. */
typedef struct pn_square_params {
    float light_y, light_half, occluder_y, occluder_half, ground_y, ground_half;
} pn_square_params;

/* Fills *p with the parameters the `square` scene is built from. */
void pn_square_scene_params(pn_square_params *p);

/* Fraction of the light NOT hidden by the occluder, seen from receiver point
 * (x, p->ground_y, z), computed in double. k >= 1: fraction of the k x k samples
 * c + ((2i+1)/k - 1) u + ((2j+1)/k - 1) v that are not hidden, a sample being hidden iff
 * the segment from the point to it crosses the closed occluder square (boundary counts as
 * hidden). k == 0: continuous area fraction. Requires ground_y < occluder_y < light_y.
 * p->ground_y is only used as the receiver height: to model a shadow-ray origin lifted by
 * eps along the ground normal, pass a copy with ground_y + eps. */
double pn_square_closed_form(const pn_square_params *p, double x, double z, int k);

/* Smallest distance, in light-plane units, between any of the k x k samples and the
 * boundary of the occluder square projected from (x, p->ground_y, z) onto the light
 * plane. Tests skip receiver points where this is tiny (the sample is on a shadow edge
 * and float rounding decides). k <= 0 returns HUGE_VAL. */
double pn_square_min_edge_distance(const pn_square_params *p, double x, double z, int k);

#ifdef __cplusplus
}
#endif
#endif
