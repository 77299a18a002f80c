/* test_scenes.c - built-in procedural scenes: mesh invariants, default views, and the
 * closed form of the `square` scene against its own limits and a brute-force
 * segment/triangle loop over the built mesh. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pn_mesh.h"
#include "pn_scenes.h"
#include "pn_setup.h"
#include "pn_test.h"

/* ---- small double vector helpers ---- */

static void sub3(double r[3], const double a[3], const double b[3])
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

static void cross3(double r[3], const double a[3], const double b[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    r[0] = x;
    r[1] = y;
    r[2] = z;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(double a[3])
{
    double l = sqrt(dot3(a, a));
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
}

static void f2d(double d[3], const float f[3])
{
    d[0] = f[0];
    d[1] = f[1];
    d[2] = f[2];
}

static void vert(double d[3], const pn_mesh *m, uint32_t v)
{
    f2d(d, m->positions + (size_t)v * 3u);
}

/* Unnormalized geometric normal (b - a) x (c - a) of triangle t, and its centroid. */
static void tri_normal(double n[3], double centroid[3], const pn_mesh *m, uint32_t t)
{
    double a[3], b[3], c[3], e1[3], e2[3];
    const uint32_t *ix = m->indices + (size_t)t * 3u;
    int k;
    vert(a, m, ix[0]);
    vert(b, m, ix[1]);
    vert(c, m, ix[2]);
    sub3(e1, b, a);
    sub3(e2, c, a);
    cross3(n, e1, e2);
    for (k = 0; k < 3; k++) centroid[k] = (a[k] + b[k] + c[k]) / 3.0;
}

/* Open segment (o, o + dir*[0,1]) against a closed triangle, double precision
 * Moller-Trumbore. Only used away from edges (callers skip ambiguous cases). */
static int seg_hits_tri(const double o[3], const double dir[3], const double a[3],
                        const double b[3], const double c[3])
{
    double e1[3], e2[3], p[3], s[3], q[3], det, u, v, t;
    sub3(e1, b, a);
    sub3(e2, c, a);
    cross3(p, dir, e2);
    det = dot3(e1, p);
    if (fabs(det) < 1e-300) {
        return 0;
    }
    sub3(s, o, a);
    u = dot3(s, p) / det;
    if (u < 0.0 || u > 1.0) {
        return 0;
    }
    cross3(q, s, e1);
    v = dot3(dir, q) / det;
    if (v < 0.0 || u + v > 1.0) {
        return 0;
    }
    t = dot3(e2, q) / det;
    return t > 1e-9 && t < 1.0 - 1e-9;
}

/* Does the segment from a to b hit any triangle in [t0, t1) other than `skip`? */
static int seg_blocked(const pn_mesh *m, const double a[3], const double b[3], uint32_t t0,
                       uint32_t t1)
{
    double dir[3], lo[3], hi[3];
    uint32_t t;
    int k;
    sub3(dir, b, a);
    for (k = 0; k < 3; k++) {
        lo[k] = a[k] < b[k] ? a[k] : b[k];
        hi[k] = a[k] < b[k] ? b[k] : a[k];
    }
    for (t = t0; t < t1; t++) {
        double p0[3], p1[3], p2[3];
        const uint32_t *ix = m->indices + (size_t)t * 3u;
        vert(p0, m, ix[0]);
        vert(p1, m, ix[1]);
        vert(p2, m, ix[2]);
        for (k = 0; k < 3; k++) {
            double tmin = p0[k] < p1[k] ? p0[k] : p1[k];
            double tmax = p0[k] < p1[k] ? p1[k] : p0[k];
            if (p2[k] < tmin) tmin = p2[k];
            if (p2[k] > tmax) tmax = p2[k];
            if (tmax < lo[k] || tmin > hi[k]) break;
        }
        if (k < 3) {
            continue;
        }
        if (seg_hits_tri(a, dir, p0, p1, p2)) {
            return 1;
        }
    }
    return 0;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

/* Triangles [t0, t1) form a closed, consistently wound 2-manifold: every directed edge
 * occurs exactly once and its reverse exactly once. Returns 1 if so. */
/* The directed edges (from << 32 | to) of triangles [t0, t1), sorted; *n of them. NULL when
 * out of memory. */
static uint64_t *sorted_edges(const pn_mesh *m, uint32_t t0, uint32_t t1, size_t *n)
{
    uint64_t *e;
    uint32_t t;
    *n = (size_t)(t1 - t0) * 3u;
    e = (uint64_t *)malloc(*n * sizeof(uint64_t) + 1u);
    if (e == NULL) {
        return NULL;
    }
    for (t = t0; t < t1; t++) {
        const uint32_t *ix = m->indices + (size_t)t * 3u;
        int c;
        for (c = 0; c < 3; c++) {
            e[(size_t)(t - t0) * 3u + (size_t)c] =
                ((uint64_t)ix[c] << 32) | (uint64_t)ix[(c + 1) % 3];
        }
    }
    qsort(e, *n, sizeof(uint64_t), cmp_u64);
    return e;
}

static int closed_manifold(const pn_mesh *m, uint32_t t0, uint32_t t1)
{
    size_t n, i;
    uint64_t *e = sorted_edges(m, t0, t1, &n);
    int ok = 1;
    if (e == NULL) {
        return 0;
    }
    for (i = 0; i < n && ok; i++) {
        uint64_t rev = (e[i] << 32) | (e[i] >> 32);
        if (i + 1 < n && e[i + 1] == e[i]) {
            ok = 0; /* directed edge used twice: inconsistent winding or non-manifold */
        } else if ((uint32_t)e[i] == (uint32_t)(e[i] >> 32)) {
            ok = 0; /* degenerate edge */
        } else if (bsearch(&rev, e, n, sizeof(uint64_t), cmp_u64) == NULL) {
            ok = 0; /* open boundary */
        }
    }
    free(e);
    return ok;
}

static double signed_volume(const pn_mesh *m, uint32_t t0, uint32_t t1)
{
    double vol = 0.0;
    uint32_t t;
    for (t = t0; t < t1; t++) {
        double a[3], b[3], c[3], bc[3];
        const uint32_t *ix = m->indices + (size_t)t * 3u;
        vert(a, m, ix[0]);
        vert(b, m, ix[1]);
        vert(c, m, ix[2]);
        cross3(bc, b, c);
        vol += dot3(a, bc) / 6.0;
    }
    return vol;
}

static uint32_t distinct_vertices(const pn_mesh *m, uint32_t t0, uint32_t t1)
{
    uint8_t *seen = (uint8_t *)calloc(m->vertex_count, 1);
    uint32_t n = 0, t;
    if (seen == NULL) {
        return 0;
    }
    for (t = t0; t < t1; t++) {
        int c;
        for (c = 0; c < 3; c++) {
            uint32_t v = m->indices[(size_t)t * 3u + (size_t)c];
            if (!seen[v]) {
                seen[v] = 1;
                n++;
            }
        }
    }
    free(seen);
    return n;
}

/* ---- per-scene generic checks ---- */

/* room (the interior, pn_scenes.h): 118 boxes (table 5, chair legs 24, bookcase 7, books
 * 56, stair 26), the six chair shells (an open 10 x 8 grid of quads each), 3 spheres, then
 * the shell (ceiling and four walls on 8 shared corners), then the floor. */
#define ROOM_BOXES 118u
#define ROOM_CHAIRS 6u
#define CHAIR_ALONG 10u
#define CHAIR_ACROSS 8u
#define CHAIR_TRIS (2u * CHAIR_ALONG * CHAIR_ACROSS)
#define CHAIR_VERTS ((CHAIR_ALONG + 1u) * (CHAIR_ACROSS + 1u))
#define CHAIR_LEG_TOP 0.45
#define ROOM_SHELL_TRIS 10u
#define ROOM_SHELL_VERTS 8u

/* canopy (pn_scenes.h): 3000 leaves of 4 triangles on 4 vertices, the trunk (an
 * octagonal frustum: 28 triangles, 16 vertices), 6 hexagonal branches (20, 12), ground.
 * The crown ellipsoid: centre (0, 4.2, 0), semi-axes 2.6, 1.3, 2.6. */
#define CAN_LEAVES 3000u
#define CAN_TRUNK_TRIS 28u
#define CAN_TRUNK_VERTS 16u
#define CAN_BRANCHES 6u
#define CAN_BRANCH_TRIS 20u
#define CAN_BRANCH_VERTS 12u
#define CAN_CROWN_Y 4.2
#define CAN_CROWN_RX 2.6
#define CAN_CROWN_RY 1.3

/* colonnade (pn_scenes.h): 16 columns (plinth 12/8, 12-sided shaft 44/24, capital 12/8
 * triangles/vertices), 14 arches of 11 voussoirs (12/8 each), 2 beams (12/8), floor. Rows
 * at z = -1.6, +1.6; columns 1.5 apart from x = -5.25; arches spring at y = 2.8, inner
 * radius 0.5, outer 0.8, 0.4 deep; capitals 0.5 square. */
#define COL_COLUMNS 16u
#define COL_PER_ROW 8u
#define COL_COLUMN_TRIS 68u
#define COL_COLUMN_VERTS 40u
#define COL_ARCHES 14u
#define COL_VOUSSOIRS 11u
#define COL_SPRING 2.8
#define COL_R_IN 0.5
#define COL_R_OUT 0.8
#define COL_DEPTH 0.4

/* closed-box (pn_scenes.h): the cube (12 triangles, 8 vertices), the box's surface
 * without the cavity floor (42 triangles; 24 vertices with the floor's), the cavity
 * floor (2), the ground (2). The box: outer [-2, 2] x [0.5, 3.5] x [-2, 2], cavity
 * [-1.75, 1.75] x [0.75, 3.25] x [-1.75, 1.75], the hole |x|, |z| <= 0.25 through the top
 * slab y in [3.25, 3.5]. */
#define CB_CUBE_TRIS 12u
#define CB_CUBE_VERTS 8u
#define CB_SHELL_TRIS 44u /* cavity floor included */
#define CB_SHELL_VERTS 24u
#define CB_OUT 2.0
#define CB_CAV 1.75
#define CB_HOLE 0.25
#define CB_Y0 0.5
#define CB_FLOOR 0.75
#define CB_CEIL 3.25
#define CB_TOP 3.5

static uint32_t expected_triangles(const char *name)
{
    if (strcmp(name, "square") == 0) return 4u;
    if (strcmp(name, "spheres") == 0) return 81u * 762u + 2u;
    if (strcmp(name, "elongated-cube") == 0) return 12u + 2u;
    if (strcmp(name, "thin") == 0) return 2000u + 2u;
    if (strcmp(name, "room") == 0)
        return ROOM_BOXES * 12u + ROOM_CHAIRS * CHAIR_TRIS + 3u * 762u + ROOM_SHELL_TRIS + 2u;
    if (strcmp(name, "canopy") == 0)
        return CAN_LEAVES * 4u + CAN_TRUNK_TRIS + CAN_BRANCHES * CAN_BRANCH_TRIS + 2u;
    if (strcmp(name, "colonnade") == 0)
        return COL_COLUMNS * COL_COLUMN_TRIS + COL_ARCHES * COL_VOUSSOIRS * 12u + 24u + 2u;
    if (strcmp(name, "closed-box") == 0) return CB_CUBE_TRIS + CB_SHELL_TRIS + 2u;
    return 0u;
}

static void check_scene(const char *name)
{
    pn_mesh m;
    pn_scene_view v;
    char err[256] = "";
    double lc[3], lu[3], lv[3], n[3], f[3], r[3], up[3], eye[3], target[3], centre[3];
    double tan_half, min_side = HUGE_VAL, lo[3], hi[3], plo[3], phi[3];
    uint32_t i, ground_t0, framed_nv, behind = 0;
    int finite = 1, in_range = 1, framed = 1, ground_flat = 1, recv_flat = 1, k;
    int shadow_seen = 0, lit_seen = 0;
    /* The interior scene's ceiling and the top of its walls (the shell's 4 upper corners)
     * lie behind its ceiling light, and its eye is inside the shell, which therefore
     * cannot be in frame: the view frames the furniture (test_room checks the rest). */
    int interior = strcmp(name, "room") == 0;
    /* closed-box's eye is inside the box: the view frames the cube in it, and the shadow
     * probes lie on the cavity floor, not the ground (test_closed_box checks the rest). */
    int boxed = strcmp(name, "closed-box") == 0;

    REQUIRE(pn_builtin_scene(name, &m, &v, err, sizeof(err)) == 0);
    CHECK_MSG(m.triangle_count == expected_triangles(name), "%s: %u triangles", name,
              (unsigned)m.triangle_count);
    REQUIRE(m.triangle_count >= 3u && m.positions != NULL && m.indices != NULL);

    for (i = 0; i < m.triangle_count * 3u; i++) {
        if (m.indices[i] >= m.vertex_count) in_range = 0;
    }
    CHECK_MSG(in_range, "%s: index out of range", name);
    for (i = 0; i < m.vertex_count * 3u; i++) {
        if (!isfinite(m.positions[i])) finite = 0;
    }
    CHECK_MSG(finite, "%s: non-finite position", name);
    if (!in_range || !finite) {
        pn_mesh_free(&m);
        return;
    }
    /* Every vertex is referenced (no strays), so the bbox is simply over all of them. */
    CHECK(distinct_vertices(&m, 0, m.triangle_count) == m.vertex_count);
    for (k = 0; k < 3; k++) {
        lo[k] = HUGE_VAL;
        hi[k] = -HUGE_VAL;
    }
    for (i = 0; i < m.vertex_count; i++) {
        for (k = 0; k < 3; k++) {
            double c = m.positions[(size_t)i * 3u + (size_t)k];
            if (c < lo[k]) lo[k] = c;
            if (c > hi[k]) hi[k] = c;
        }
    }
    for (k = 0; k < 3; k++) {
        CHECK(m.bbox_min[k] == (float)lo[k] && m.bbox_max[k] == (float)hi[k]);
        centre[k] = 0.5 * (lo[k] + hi[k]);
    }

    /* Ground: last two triangles, flat at the lowest y, facing +y. */
    ground_t0 = m.triangle_count - 2u;
    for (i = ground_t0 * 3u; i < m.triangle_count * 3u; i++) {
        if (m.positions[(size_t)m.indices[i] * 3u + 1u] != m.bbox_min[1]) ground_flat = 0;
    }
    CHECK_MSG(ground_flat, "%s: last two triangles are not the ground", name);
    for (i = ground_t0; i < m.triangle_count; i++) {
        double nn[3], cen[3];
        tri_normal(nn, cen, &m, i);
        CHECK(nn[1] > 0.0);
    }
    /* Receivers: a range ending at the last triangle: the ground (room: its floor, which
     * is its ground), and closed-box's cavity floor before it; each flat, facing +y. */
    CHECK_MSG(m.receiver_count == (boxed ? 4u : 2u) &&
                  m.receiver_first == m.triangle_count - m.receiver_count,
              "%s: receivers [%u, +%u)", name, (unsigned)m.receiver_first,
              (unsigned)m.receiver_count);
    for (i = m.receiver_first; i < m.triangle_count && i - m.receiver_first < m.receiver_count; i++) {
        double nn[3], cen[3];
        const uint32_t *ix = m.indices + (size_t)i * 3u;
        float y0 = m.positions[(size_t)ix[0] * 3u + 1u];
        tri_normal(nn, cen, &m, i);
        if (!(nn[1] > 0.0) || m.positions[(size_t)ix[1] * 3u + 1u] != y0 ||
            m.positions[(size_t)ix[2] * 3u + 1u] != y0)
            recv_flat = 0;
    }
    CHECK_MSG(recv_flat, "%s: a receiver is not a flat triangle facing +y", name);

    /* Light: orthogonal non-degenerate half-edges, N = u x v points down and toward the
     * scene, every vertex strictly on the emitting side. */
    f2d(lc, v.light_center);
    f2d(lu, v.light_u);
    f2d(lv, v.light_v);
    CHECK(dot3(lu, lu) > 0.0 && dot3(lv, lv) > 0.0);
    CHECK(fabs(dot3(lu, lv)) <= 1e-12 * sqrt(dot3(lu, lu) * dot3(lv, lv)));
    cross3(n, lu, lv);
    normalize3(n);
    CHECK(n[1] < -0.99);
    {
        double d[3];
        sub3(d, centre, lc);
        CHECK_MSG(dot3(d, n) > 0.0, "%s: light faces away from the scene centre", name);
    }
    for (i = 0; i < m.vertex_count; i++) {
        double p[3], d[3];
        vert(p, &m, i);
        sub3(d, p, lc);
        if (!(dot3(d, n) > 0.0)) {
            behind++;
            if (!interior || p[1] != hi[1]) {
                CHECK_MSG(0, "%s: vertex %u behind the light plane", name, (unsigned)i);
                break;
            }
        }
    }
    if (interior) {
        CHECK_MSG(behind == 4u, "%s: %u vertices behind the light", name, (unsigned)behind);
        CHECK(lc[1] < hi[1]);
    } else {
        CHECK(behind == 0u);
        CHECK(lc[1] > hi[1]);
    }

    /* Camera: every vertex (interior: every furniture vertex, those before the shell's and
     * the floor's) inside the frustum at aspect 1 (so at any wider aspect too). */
    framed_nv = interior ? m.vertex_count - ROOM_SHELL_VERTS - 4u
                         : (boxed ? CB_CUBE_VERTS : m.vertex_count);
    f2d(eye, v.eye);
    f2d(target, v.target);
    f2d(up, v.up);
    CHECK(v.fov_deg > 0.0f && v.fov_deg < 180.0f);
    sub3(f, target, eye);
    normalize3(f);
    cross3(r, f, up);
    normalize3(r);
    cross3(up, r, f);
    tan_half = tan(0.5 * (double)v.fov_deg * 3.14159265358979323846 / 180.0);
    for (i = 0; i < framed_nv; i++) {
        double p[3], d[3], z, sx, sy;
        vert(p, &m, i);
        sub3(d, p, eye);
        z = dot3(d, f);
        sx = dot3(d, r) / (z * tan_half);
        sy = dot3(d, up) / (z * tan_half);
        if (!(z > 0.0) || fabs(sx) > 1.0 || fabs(sy) > 1.0) {
            framed = 0;
        } else {
            double side = 1.0 - (fabs(sx) > fabs(sy) ? fabs(sx) : fabs(sy));
            if (side < min_side) min_side = side;
        }
    }
    CHECK_MSG(framed, "%s: a vertex is outside the default view", name);

    /* Shadows visible: project the centroid of sampled occluder triangles from the light
     * centre onto the ground; that ground point is blocked (the segment passes through
     * the centroid) and at least some of them must be seen from the eye. Also some
     * ground point that the light centre reaches must be seen (a 4 x 4 grid, then the
     * point beneath the light centre). closed-box: the cavity floor instead. */
    for (k = 0; k < 3; k++) {
        plo[k] = boxed ? -CB_CAV : lo[k];
        phi[k] = boxed ? CB_CAV : hi[k];
    }
    {
        uint32_t step = ground_t0 / 64u + 1u, t;
        double gy = boxed ? CB_FLOOR : lo[1];
        for (t = 0; t < ground_t0; t += step) {
            double a[3], b[3], c[3], cen[3], g[3], s;
            vert(a, &m, m.indices[t * 3u]);
            vert(b, &m, m.indices[t * 3u + 1u]);
            vert(c, &m, m.indices[t * 3u + 2u]);
            for (k = 0; k < 3; k++) cen[k] = (a[k] + b[k] + c[k]) / 3.0;
            s = (lc[1] - gy) / (lc[1] - cen[1]);
            for (k = 0; k < 3; k++) g[k] = lc[k] + s * (cen[k] - lc[k]);
            g[1] = gy + 1e-6;
            if (fabs(g[0]) > phi[0] || fabs(g[2]) > phi[2]) continue;
            if (seg_blocked(&m, g, lc, 0, ground_t0) && !seg_blocked(&m, g, eye, 0, ground_t0)) {
                shadow_seen++;
            }
        }
        for (t = 0; t < 17u && !lit_seen; t++) {
            double g[3];
            g[0] = plo[0] + (phi[0] - plo[0]) * (0.05 + 0.9 * (double)(t % 4u) / 3.0);
            g[1] = gy + 1e-6;
            g[2] = plo[2] + (phi[2] - plo[2]) * (0.05 + 0.9 * (double)(t / 4u) / 3.0);
            if (t == 16u) {
                g[0] = lc[0];
                g[2] = lc[2];
            }
            if (!seg_blocked(&m, g, lc, 0, ground_t0) && !seg_blocked(&m, g, eye, 0, ground_t0)) {
                lit_seen = 1;
            }
        }
    }
    CHECK_MSG(shadow_seen > 0, "%s: no shadowed ground point visible from the eye", name);
    CHECK_MSG(lit_seen, "%s: no lit ground point visible from the eye", name);
    fprintf(stderr, "  %-15s %6u vertices %6u triangles, frame margin %.3f, %d shadow probes seen\n",
            name, (unsigned)m.vertex_count, (unsigned)m.triangle_count, min_side, shadow_seen);
    pn_mesh_free(&m);
}

static void test_all_scenes(void)
{
    const char *const *names = pn_builtin_scene_names_all();
    const char *const *shared = pn_builtin_scene_names();
    int count = 0, i;
    REQUIRE(names != NULL && shared != NULL);
    for (; *names != NULL; names++) {
        check_scene(*names);
        count++;
    }
    CHECK(count == 8);
    /* The shared list (what the demo, the golden hashes and the frame tests iterate) is
     * the first seven, without closed-box; the new scenes come after room. */
    names = pn_builtin_scene_names_all();
    for (i = 0; shared[i] != NULL; i++) CHECK(names[i] != NULL && strcmp(shared[i], names[i]) == 0);
    CHECK(i == 7);
    CHECK(strcmp(names[4], "room") == 0 && strcmp(names[5], "canopy") == 0 &&
          strcmp(names[6], "colonnade") == 0);
    CHECK(strcmp(names[7], "closed-box") == 0);
}

static void test_unknown_name(void)
{
    pn_mesh m;
    pn_scene_view v;
    char err[128] = "";
    memset(&v, 0x5a, sizeof(v));
    m.positions = (float *)&m; /* garbage that must be overwritten */
    m.triangle_count = 7u;
    m.receiver_count = 3u;
    CHECK(pn_builtin_scene("no-such-scene", &m, &v, err, sizeof(err)) != 0);
    CHECK(err[0] != '\0');
    CHECK(strstr(err, "no-such-scene") != NULL);
    CHECK(strstr(err, "closed-box") != NULL);
    CHECK(strstr(err, "canopy") != NULL && strstr(err, "colonnade") != NULL);
    CHECK(m.positions == NULL && m.indices == NULL && m.triangle_count == 0u &&
          m.vertex_count == 0u && m.receiver_count == 0u);
    CHECK(((unsigned char *)&v)[0] == 0x5a); /* view not written on failure */
    CHECK(pn_builtin_scene("no-such-scene", &m, NULL, NULL, 0) != 0);
    CHECK(pn_builtin_scene(NULL, &m, NULL, err, sizeof(err)) != 0);
    /* view may be NULL on success */
    CHECK(pn_builtin_scene("square", &m, NULL, NULL, 0) == 0);
    pn_mesh_free(&m);
}

static void test_deterministic(void)
{
    const char *const *names = pn_builtin_scene_names_all();
    for (; *names != NULL; names++) {
        pn_mesh a, b;
        pn_scene_view va, vb;
        REQUIRE(pn_builtin_scene(*names, &a, &va, NULL, 0) == 0);
        REQUIRE(pn_builtin_scene(*names, &b, &vb, NULL, 0) == 0);
        CHECK(a.vertex_count == b.vertex_count && a.triangle_count == b.triangle_count);
        CHECK(memcmp(a.positions, b.positions, (size_t)a.vertex_count * 3u * sizeof(float)) == 0);
        CHECK(memcmp(a.indices, b.indices, (size_t)a.triangle_count * 3u * sizeof(uint32_t)) == 0);
        CHECK(memcmp(&va, &vb, sizeof(va)) == 0);
        pn_mesh_free(&a);
        pn_mesh_free(&b);
    }
}

/* Each sphere: closed, consistently wound, genus 0, outward, on its sphere, no
 * degenerate triangle; 383 vertices of its own. */
static void test_spheres_closed(void)
{
    pn_mesh m;
    uint32_t s;
    int manifold = 1, outward = 1, euler = 1, on_sphere = 1, nondegenerate = 1;
    double min_angle = 180.0;
    REQUIRE(pn_builtin_scene("spheres", &m, NULL, NULL, 0) == 0);
    REQUIRE(m.triangle_count == 81u * 762u + 2u);
    CHECK(m.vertex_count == 81u * 383u + 4u);
    for (s = 0; s < 81u; s++) {
        uint32_t t0 = s * 762u, t1 = t0 + 762u, t, nv;
        double c[3] = {0.0, 0.0, 0.0}, vol, r = 0.4;
        if (!closed_manifold(&m, t0, t1)) manifold = 0;
        nv = distinct_vertices(&m, t0, t1);
        /* V - E + F with E = 3F/2 for a closed manifold. */
        if ((int)nv - (int)(3u * 762u / 2u) + 762 != 2) euler = 0;
        /* Sphere s uses vertices [383 s, 383 (s + 1)): centre = mean of the poles. */
        {
            double np[3], sp[3];
            vert(np, &m, s * 383u);
            vert(sp, &m, s * 383u + 382u);
            for (int k = 0; k < 3; k++) c[k] = 0.5 * (np[k] + sp[k]);
        }
        for (t = t0; t < t1; t++) {
            double a[3], b[3], cc[3], e1[3], e2[3], e3[3], nn[3], area2;
            const uint32_t *ix = m.indices + (size_t)t * 3u;
            vert(a, &m, ix[0]);
            vert(b, &m, ix[1]);
            vert(cc, &m, ix[2]);
            sub3(e1, b, a);
            sub3(e2, cc, a);
            sub3(e3, cc, b);
            cross3(nn, e1, e2);
            area2 = sqrt(dot3(nn, nn));
            if (!(area2 > 1e-6)) nondegenerate = 0;
            /* smallest angle, at a */
            {
                double l1 = sqrt(dot3(e1, e1)), l2 = sqrt(dot3(e2, e2)), l3 = sqrt(dot3(e3, e3));
                double lmin = l1 < l2 ? (l1 < l3 ? l1 : l3) : (l2 < l3 ? l2 : l3);
                double lmax = l1 > l2 ? (l1 > l3 ? l1 : l3) : (l2 > l3 ? l2 : l3);
                /* angle opposite the shortest edge: sin = area2 / (product of the others) */
                double ang = asin(area2 / ((l1 + l2 + l3 - lmin - lmax) * lmax)) * 180.0 /
                             3.14159265358979323846;
                if (ang < min_angle) min_angle = ang;
            }
        }
        for (t = s * 383u; t < (s + 1u) * 383u; t++) {
            double p[3], d[3];
            vert(p, &m, t);
            sub3(d, p, c);
            if (fabs(sqrt(dot3(d, d)) - r) > 1e-5) on_sphere = 0;
        }
        /* Volume relative to the sphere's centre; a translation would add nothing for a
         * closed mesh, but this keeps the check well conditioned. */
        {
            pn_mesh local = m;
            float *moved = (float *)malloc((size_t)m.vertex_count * 3u * sizeof(float));
            REQUIRE(moved != NULL);
            for (t = 0; t < m.vertex_count; t++) {
                for (int k = 0; k < 3; k++)
                    moved[(size_t)t * 3u + (size_t)k] =
                        (float)((double)m.positions[(size_t)t * 3u + (size_t)k] - c[k]);
            }
            local.positions = moved;
            vol = signed_volume(&local, t0, t1);
            free(moved);
            /* A unit-sphere polyhedron of this resolution holds > 97% of the ball. */
            if (!(vol > 0.97 * 4.0 / 3.0 * 3.14159265358979323846 * r * r * r)) outward = 0;
            if (s == 0) {
                fprintf(stderr, "  sphere volume ratio %.4f, smallest angle %.1f deg\n",
                        vol / (4.0 / 3.0 * 3.14159265358979323846 * r * r * r), min_angle);
            }
        }
    }
    CHECK(manifold);
    CHECK(euler);
    CHECK(outward);
    CHECK(on_sphere);
    CHECK(nondegenerate);
    CHECK(min_angle > 25.0);
    pn_mesh_free(&m);
}

static void test_box_closed(void)
{
    pn_mesh m;
    REQUIRE(pn_builtin_scene("elongated-cube", &m, NULL, NULL, 0) == 0);
    REQUIRE(m.triangle_count == 14u);
    CHECK(closed_manifold(&m, 0, 12));
    CHECK(distinct_vertices(&m, 0, 12) == 8u);
    CHECK(fabs(signed_volume(&m, 0, 12) - 0.6 * 0.6 * 3.0) < 1e-5);
    /* Elongated along the light axis: height 5 x each horizontal side (float 0.3 rounds up). */
    {
        double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        uint32_t v;
        for (v = 0; v < 8u; v++) {
            for (int k = 0; k < 3; k++) {
                double c = m.positions[(size_t)v * 3u + (size_t)k];
                if (c < lo[k]) lo[k] = c;
                if (c > hi[k]) hi[k] = c;
            }
        }
        CHECK(hi[1] - lo[1] >= 4.99 * (hi[0] - lo[0]));
        CHECK(hi[1] - lo[1] >= 4.99 * (hi[2] - lo[2]));
        CHECK(lo[1] > m.bbox_min[1]); /* floats above the ground */
    }
    /* The hard case itself: from the ground point beneath the box, every light sample is
     * blocked, while the top face alone (all a single near depth map sees) blocks less
     * than half of them - the umbra comes from the long side walls. */
    {
        pn_scene_view v;
        pn_mesh top;
        uint32_t top_idx[6], t, n_top = 0;
        int i, j, k = 16, all = 0, by_top = 0;
        double P[3] = {0.0, 0.0, 0.0};
        pn_mesh_free(&m);
        REQUIRE(pn_builtin_scene("elongated-cube", &m, &v, NULL, 0) == 0);
        P[1] = m.bbox_min[1];
        /* the +y face: the two box triangles with every vertex at the box top, y = 4 */
        for (t = 0; t < 12u; t++) {
            const uint32_t *ix = m.indices + (size_t)t * 3u;
            int c, on_top = 1;
            for (c = 0; c < 3; c++) {
                if (m.positions[(size_t)ix[c] * 3u + 1u] != 4.0f) on_top = 0;
            }
            if (on_top && n_top < 2u) {
                memcpy(top_idx + n_top * 3u, ix, 3u * sizeof(uint32_t));
                n_top++;
            }
        }
        REQUIRE(n_top == 2u);
        top = m;
        top.indices = top_idx;
        top.triangle_count = 2u;
        for (j = 0; j < k; j++) {
            for (i = 0; i < k; i++) {
                double S[3];
                S[0] = v.light_center[0] + ((double)(2 * i + 1) / k - 1.0) * v.light_u[0];
                S[1] = v.light_center[1];
                S[2] = v.light_center[2] + ((double)(2 * j + 1) / k - 1.0) * v.light_v[2];
                all += seg_blocked(&m, P, S, 0, 12);
                by_top += seg_blocked(&top, P, S, 0, 2);
            }
        }
        CHECK(all == k * k);
        CHECK(by_top > 0 && by_top < k * k / 2);
        fprintf(stderr, "  beneath the box: %d/%d samples blocked, top face alone %d\n", all,
                k * k, by_top);
    }
    pn_mesh_free(&m);
}

static void test_thin_slivers(void)
{
    pn_mesh m;
    uint32_t t;
    int ok = 1, up = 1;
    REQUIRE(pn_builtin_scene("thin", &m, NULL, NULL, 0) == 0);
    REQUIRE(m.triangle_count == 2002u);
    for (t = 0; t < 2000u; t++) {
        double a[3], b[3], c[3], e1[3], e2[3], nn[3], l, area, h;
        vert(a, &m, m.indices[t * 3u]);
        vert(b, &m, m.indices[t * 3u + 1u]);
        vert(c, &m, m.indices[t * 3u + 2u]);
        sub3(e1, b, a);
        sub3(e2, c, a);
        cross3(nn, e1, e2);
        area = 0.5 * sqrt(dot3(nn, nn));
        l = sqrt(dot3(e2, e2));
        h = 2.0 * area / l; /* width of the base seen across the long edge */
        if (!(l > 1.9 && l < 2.1 && h > 0.0015 && h < 0.0025)) ok = 0;
        if (!(nn[1] > 0.0)) up = 0;
    }
    CHECK(ok);
    CHECK(up);
    pn_mesh_free(&m);
}

/* Triangles [t0, t1) form a consistently wound 2-manifold that may have a boundary: no
 * directed edge twice, none degenerate. *boundary: the edges with one triangle only. */
static int open_manifold(const pn_mesh *m, uint32_t t0, uint32_t t1, uint32_t *boundary)
{
    size_t n, i;
    uint64_t *e = sorted_edges(m, t0, t1, &n);
    int ok = 1;
    *boundary = 0;
    if (e == NULL) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        uint64_t rev = (e[i] << 32) | (e[i] >> 32);
        if (i + 1 < n && e[i + 1] == e[i]) ok = 0;
        if ((uint32_t)e[i] == (uint32_t)(e[i] >> 32)) ok = 0;
        if (bsearch(&rev, e, n, sizeof(uint64_t), cmp_u64) == NULL) (*boundary)++;
    }
    free(e);
    return ok;
}

/* room's chairs: each shell (after the boxes) one open single-layer sheet: 99 vertices of
 * its own, consistently wound, a disc (V - E + F = 1) whose boundary is the grid's rim
 * (2 (10 + 8) edges, each in one triangle only), no two triangles on the same three
 * vertices (no second layer); the seat's triangles face up, the back's face the sitter
 * (away from the back, found as the high part's offset from the low part); each of the
 * chair's four legs (boxes 5 + 4c ..) reaches to within 1 cm under the sheet without
 * piercing it, and the sheet lies over the leg tops. */
static void check_chair_shells(const pn_mesh *m)
{
    uint32_t c, t;
    int seat_up = 1, back_front = 1, legs = 1;
    for (c = 0; c < ROOM_CHAIRS; c++) {
        uint32_t t0 = ROOM_BOXES * 12u + c * CHAIR_TRIS, t1 = t0 + CHAIR_TRIS, bnd = 0, edges;
        double lowc[3] = {0, 0, 0}, highc[3] = {0, 0, 0}, back[3], miny = HUGE_VAL;
        int nl = 0, nh = 0, k, l, seat_n = 0, back_n = 0;
        CHECK(open_manifold(m, t0, t1, &bnd));
        CHECK_MSG(bnd == 2u * (CHAIR_ALONG + CHAIR_ACROSS), "chair %u: %u boundary edges",
                  (unsigned)c, (unsigned)bnd);
        CHECK(distinct_vertices(m, t0, t1) == CHAIR_VERTS);
        edges = (3u * CHAIR_TRIS + bnd) / 2u;
        CHECK((int)CHAIR_VERTS - (int)edges + (int)CHAIR_TRIS == 1);
        /* single layer: no triangle's vertex set repeats (sorted triples differ) */
        for (t = t0; t < t1; t++) {
            uint32_t u;
            const uint32_t *a = m->indices + (size_t)t * 3u;
            for (u = t + 1u; u < t1; u++) {
                const uint32_t *q = m->indices + (size_t)u * 3u;
                int same = 0;
                for (k = 0; k < 3; k++)
                    for (l = 0; l < 3; l++) same += a[k] == q[l];
                CHECK(same < 3);
            }
        }
        for (t = t0; t < t1; t++) {
            double nn[3], cen[3];
            tri_normal(nn, cen, m, t);
            if (cen[1] < 0.5) {
                for (k = 0; k < 3; k++) lowc[k] += cen[k];
                nl++;
            } else if (cen[1] > 0.7) {
                for (k = 0; k < 3; k++) highc[k] += cen[k];
                nh++;
            }
            for (k = 0; k < 3; k++) {
                double y = m->positions[(size_t)m->indices[t * 3u + (uint32_t)k] * 3u + 1u];
                if (y < miny) miny = y;
            }
        }
        REQUIRE(nl > 0 && nh > 0);
        for (k = 0; k < 3; k++) back[k] = highc[k] / nh - lowc[k] / nl;
        back[1] = 0.0;
        normalize3(back);
        for (t = t0; t < t1; t++) {
            double nn[3], cen[3], l2;
            tri_normal(nn, cen, m, t);
            l2 = sqrt(dot3(nn, nn));
            if (cen[1] < 0.465) { /* the flat seat, up to the start of the bend */
                seat_n++;
                if (!(nn[1] > 0.9 * l2)) seat_up = 0;
            } else if (cen[1] > 0.7) {
                back_n++;
                if (!(-dot3(nn, back) > 0.9 * l2)) back_front = 0;
            }
        }
        CHECK(seat_n >= 64 && back_n >= 32);
        CHECK(miny > 0.4 && miny < CHAIR_LEG_TOP + 0.01);
        /* legs: boxes 5 + 4c .. 5 + 4c + 3 */
        for (l = 0; l < 4; l++) {
            uint32_t b0 = (5u + 4u * c + (uint32_t)l) * 12u, v;
            double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
            double p0[3], p1[3], p2[3];
            for (v = b0 * 3u; v < (b0 + 12u) * 3u; v++) {
                for (k = 0; k < 3; k++) {
                    double x = m->positions[(size_t)m->indices[v] * 3u + (size_t)k];
                    if (x < lo[k]) lo[k] = x;
                    if (x > hi[k]) hi[k] = x;
                }
            }
            if (!(lo[1] == 0.0 && fabs(hi[1] - CHAIR_LEG_TOP) < 1e-6 && hi[0] - lo[0] < 0.05 &&
                  hi[2] - lo[2] < 0.05))
                legs = 0;
            /* from the leg's top centre: up 1 cm hits the sheet, the leg itself does not */
            p0[0] = p1[0] = p2[0] = 0.5 * (lo[0] + hi[0]);
            p0[2] = p1[2] = p2[2] = 0.5 * (lo[2] + hi[2]);
            p0[1] = 0.2;
            p1[1] = hi[1];
            p2[1] = hi[1] + 0.01;
            if (!seg_blocked(m, p1, p2, t0, t1) || seg_blocked(m, p0, p1, t0, t1)) legs = 0;
        }
    }
    CHECK_MSG(seat_up, "a chair seat triangle does not face up");
    CHECK_MSG(back_front, "a chair back triangle does not face the sitter");
    CHECK_MSG(legs, "a chair leg does not stand under its seat");
}

/* The interior: the shell and the floor close the room (welded by position they form a
 * closed manifold wound inward); the eye, the light and every furniture vertex are inside
 * it, the furniture at least 1 cm off the walls and below the light; the boxes are closed
 * and outward, the spheres closed. */
static void test_room(void)
{
    pn_mesh m, welded;
    pn_scene_view v;
    uint32_t nt, nv, shell_t0, shell_v0, t, i, *idx;
    double lo[3], hi[3], top = -HUGE_VAL;
    int k, corners = 1, inward = 1, inside = 1, boxes = 1;
    REQUIRE(pn_builtin_scene("room", &m, &v, NULL, 0) == 0);
    nt = m.triangle_count;
    nv = m.vertex_count;
    REQUIRE(nt == expected_triangles("room"));
    CHECK(nv == ROOM_BOXES * 8u + ROOM_CHAIRS * CHAIR_VERTS + 3u * 383u + ROOM_SHELL_VERTS + 4u);
    shell_t0 = nt - 2u - ROOM_SHELL_TRIS;
    shell_v0 = nv - 4u - ROOM_SHELL_VERTS;
    for (k = 0; k < 3; k++) {
        lo[k] = m.bbox_min[k];
        hi[k] = m.bbox_max[k];
    }
    /* Shell: its own 8 vertices, each a corner of the bounding box; normals inward. */
    for (t = shell_t0; t < nt - 2u; t++) {
        double nn[3], cen[3], toc[3];
        const uint32_t *ix = m.indices + (size_t)t * 3u;
        int c3;
        for (c3 = 0; c3 < 3; c3++) {
            const float *p = m.positions + (size_t)ix[c3] * 3u;
            if (ix[c3] < shell_v0 || ix[c3] >= nv - 4u) corners = 0;
            for (k = 0; k < 3; k++)
                if (p[k] != m.bbox_min[k] && p[k] != m.bbox_max[k]) corners = 0;
        }
        tri_normal(nn, cen, &m, t);
        for (k = 0; k < 3; k++) toc[k] = 0.5 * (lo[k] + hi[k]) - cen[k];
        if (!(dot3(nn, toc) > 0.0)) inward = 0;
    }
    CHECK(corners);
    CHECK(inward);
    /* Closed: the floor's corners welded onto the shell's bottom ones. */
    idx = (uint32_t *)malloc((size_t)nt * 3u * sizeof(uint32_t));
    REQUIRE(idx != NULL);
    memcpy(idx, m.indices, (size_t)nt * 3u * sizeof(uint32_t));
    for (i = (nt - 2u) * 3u; i < nt * 3u; i++) {
        uint32_t w;
        for (w = shell_v0; w < nv - 4u; w++) {
            const float *p = m.positions + (size_t)idx[i] * 3u, *q = m.positions + (size_t)w * 3u;
            if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) idx[i] = w;
        }
    }
    welded = m;
    welded.indices = idx;
    CHECK(closed_manifold(&welded, shell_t0, nt));
    {
        double room_volume = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
        CHECK(fabs(signed_volume(&welded, shell_t0, nt) + room_volume) < 1e-9); /* inward */
    }
    free(idx);
    /* Furniture: inside, off the walls and the ceiling; each box closed and outward. */
    for (i = 0; i < shell_v0; i++) {
        const float *p = m.positions + (size_t)i * 3u;
        for (k = 0; k < 3; k += 2)
            if (!(p[k] >= lo[k] + 0.01 && p[k] <= hi[k] - 0.01)) inside = 0;
        if (!(p[1] >= lo[1])) inside = 0;
        if (p[1] > top) top = p[1];
    }
    CHECK(inside);
    for (t = 0; t < ROOM_BOXES; t++) {
        if (!closed_manifold(&m, t * 12u, t * 12u + 12u)) boxes = 0;
        if (!(signed_volume(&m, t * 12u, t * 12u + 12u) > 0.0)) boxes = 0;
    }
    CHECK(boxes);
    for (t = 0; t < 3u; t++) {
        uint32_t t0 = ROOM_BOXES * 12u + ROOM_CHAIRS * CHAIR_TRIS + t * 762u;
        CHECK(closed_manifold(&m, t0, t0 + 762u));
    }
    check_chair_shells(&m);
    /* Light: a panel inside the ceiling, below it and above all furniture. */
    CHECK(v.light_center[1] > top && v.light_center[1] < hi[1]);
    for (k = 0; k < 3; k += 2) {
        double reach = fabs(v.light_u[k]) + fabs(v.light_v[k]);
        CHECK(v.light_center[k] - reach > lo[k] && v.light_center[k] + reach < hi[k]);
    }
    /* Eye: inside the room, so every pixel sees the shell, the floor or furniture. */
    for (k = 0; k < 3; k++) CHECK(v.eye[k] > lo[k] && v.eye[k] < hi[k]);
    fprintf(stderr, "  room: furniture up to y = %.3f, light at %.4f, ceiling %.1f\n", top,
            v.light_center[1], hi[1]);
    pn_mesh_free(&m);
}

/* closed-box: is x inside the box's material (the outer box without the cavity and the
 * hole)? Open on every boundary: the callers stay 1e-3 off the faces. */
static int cb_material(const double x[3])
{
    int in_out = fabs(x[0]) < CB_OUT && fabs(x[2]) < CB_OUT && x[1] > CB_Y0 && x[1] < CB_TOP;
    int in_cav = fabs(x[0]) < CB_CAV && fabs(x[2]) < CB_CAV && x[1] > CB_FLOOR && x[1] < CB_CEIL;
    int in_hole = fabs(x[0]) < CB_HOLE && fabs(x[2]) < CB_HOLE && x[1] >= CB_CEIL - 1e-9;
    return in_out && !in_cav && !in_hole;
}

/* Light sample (i, j) of k x k of view v. */
static void light_sample(double S[3], const pn_scene_view *v, int i, int j, int k)
{
    double a = (double)(2 * i + 1) / k - 1.0, b = (double)(2 * j + 1) / k - 1.0;
    int c;
    for (c = 0; c < 3; c++) S[c] = (double)v->light_center[c] + a * v->light_u[c] + b * v->light_v[c];
}

/* The leak scene: the box one closed surface of genus 0 facing out of its material, the
 * hole straight under the light and inside its footprint, the cube standing on the
 * cavity floor, the eye inside the cavity; and the light gets in through the hole only:
 * every unblocked segment from a point inside to a light sample crosses the top inside
 * the hole, the floor beneath the light sees all of it, the cavity's far corners none. */
static void test_closed_box(void)
{
    pn_mesh m;
    pn_scene_view v;
    const uint32_t s0 = CB_CUBE_TRIS, s1 = CB_CUBE_TRIS + CB_SHELL_TRIS;
    const int k = 8;
    uint32_t t, i, hole_top = 0, hole_ceil = 0;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    int outward = 1, cube_in = 1, through_hole = 1, c;
    int probes = 0, lit_probes = 0, lit_samples = 0, wall_lit = 0, under = 0, corner = 0;
    REQUIRE(pn_builtin_scene("closed-box", &m, &v, NULL, 0) == 0);
    REQUIRE(m.triangle_count == expected_triangles("closed-box"));
    CHECK(m.vertex_count == CB_CUBE_VERTS + CB_SHELL_VERTS + 4u);
    CHECK(m.receiver_first == s1 - 2u && m.receiver_count == 4u);

    /* The cube: closed, outward, 0.5 on a side, standing on the cavity floor, inside. */
    CHECK(closed_manifold(&m, 0, s0));
    CHECK(distinct_vertices(&m, 0, s0) == CB_CUBE_VERTS);
    CHECK(fabs(signed_volume(&m, 0, s0) - 0.125) < 1e-12);
    for (i = 0; i < CB_CUBE_VERTS; i++) {
        const float *p = m.positions + (size_t)i * 3u;
        if (!(fabs(p[0]) < CB_CAV && fabs(p[2]) < CB_CAV && p[1] >= CB_FLOOR && p[1] < CB_CEIL)) cube_in = 0;
        if (p[1] < lo[1]) lo[1] = p[1];
    }
    CHECK(cube_in);
    CHECK(lo[1] == CB_FLOOR);

    /* The box: one closed, consistently wound surface of genus 0 (V - E + F = 2) on its
     * own 24 vertices; its volume is the material's (outer - cavity - hole), so it faces
     * out of the material overall, and every face does locally. */
    CHECK(closed_manifold(&m, s0, s1));
    CHECK(distinct_vertices(&m, s0, s1) == CB_SHELL_VERTS);
    CHECK((int)CB_SHELL_VERTS - (int)(3u * CB_SHELL_TRIS / 2u) + (int)CB_SHELL_TRIS == 2);
    {
        double vol = 2.0 * CB_OUT * 2.0 * CB_OUT * (CB_TOP - CB_Y0) -
                     2.0 * CB_CAV * 2.0 * CB_CAV * (CB_CEIL - CB_FLOOR) -
                     2.0 * CB_HOLE * 2.0 * CB_HOLE * (CB_TOP - CB_CEIL);
        CHECK_MSG(fabs(signed_volume(&m, s0, s1) - vol) < 1e-9, "volume %.9f, expected %.9f",
                  signed_volume(&m, s0, s1), vol);
    }
    for (t = s0; t < s1; t++) {
        double nn[3], cen[3], a[3], b[3];
        tri_normal(nn, cen, &m, t);
        normalize3(nn);
        for (c = 0; c < 3; c++) {
            a[c] = cen[c] + 1e-3 * nn[c];
            b[c] = cen[c] - 1e-3 * nn[c];
        }
        if (cb_material(a) || !cb_material(b)) outward = 0;
    }
    CHECK_MSG(outward, "a face of the box does not face out of its material");
    for (c = 0; c < 3; c++) {
        lo[c] = HUGE_VAL;
        hi[c] = -HUGE_VAL;
    }
    for (i = s0 * 3u; i < s1 * 3u; i++) {
        const float *p = m.positions + (size_t)m.indices[i] * 3u;
        for (c = 0; c < 3; c++) {
            if (p[c] < lo[c]) lo[c] = p[c];
            if (p[c] > hi[c]) hi[c] = p[c];
        }
    }
    CHECK(lo[0] == -CB_OUT && lo[1] == CB_Y0 && lo[2] == -CB_OUT);
    CHECK(hi[0] == CB_OUT && hi[1] == CB_TOP && hi[2] == CB_OUT);
    CHECK(m.bbox_min[1] == 0.0f && m.bbox_max[1] == (float)CB_TOP);
    CHECK(m.bbox_min[0] < -CB_OUT && m.bbox_max[0] > CB_OUT); /* the ground reaches past it */

    /* The hole: 4 corners at the top and 4 at the cavity ceiling, |x| = |z| = 0.25,
     * centred straight under the light centre and inside the light's footprint. */
    for (i = CB_CUBE_VERTS; i < CB_CUBE_VERTS + CB_SHELL_VERTS; i++) {
        const float *p = m.positions + (size_t)i * 3u;
        if (fabs(p[0]) == CB_HOLE && fabs(p[2]) == CB_HOLE) {
            if (p[1] == CB_TOP) hole_top++;
            if (p[1] == CB_CEIL) hole_ceil++;
        }
    }
    CHECK(hole_top == 4u && hole_ceil == 4u);
    CHECK(v.light_center[0] == 0.0f && v.light_center[2] == 0.0f);
    CHECK(v.light_center[1] > CB_TOP);
    for (c = 0; c < 3; c += 2) CHECK(fabs(v.light_u[c]) + fabs(v.light_v[c]) > CB_HOLE);
    /* The eye: inside the cavity, off its faces. */
    CHECK(fabs(v.eye[0]) < CB_CAV && fabs(v.eye[2]) < CB_CAV && v.eye[1] > CB_FLOOR &&
          v.eye[1] < CB_CEIL);

    /* Light gets in through the hole only. Probes on the cavity floor (a 15 x 15 grid)
     * and on its walls (15 x 9 a wall), 1e-6 off the face, against k x k samples. */
    for (i = 0; i < 225u + 4u * 135u; i++) {
        double P[3], a = -1.6 + 3.2 * (double)(i % 15u) / 14.0;
        int lit = 0, si, sj, wall = i >= 225u;
        if (!wall) {
            P[0] = a;
            P[1] = CB_FLOOR + 1e-6;
            P[2] = -1.6 + 3.2 * (double)(i / 15u) / 14.0;
        } else {
            uint32_t w = (i - 225u) / 135u, r = (i - 225u) % 135u;
            double along = -1.6 + 3.2 * (double)(r % 15u) / 14.0, d = CB_CAV - 1e-6;
            P[1] = CB_FLOOR + 0.1 + 2.3 * (double)(r / 15u) / 8.0;
            P[0] = w == 0 ? d : (w == 1 ? -d : along);
            P[2] = w == 2 ? d : (w == 3 ? -d : along);
        }
        for (sj = 0; sj < k; sj++) {
            for (si = 0; si < k; si++) {
                double S[3], f, x, z;
                light_sample(S, &v, si, sj, k);
                if (seg_blocked(&m, P, S, 0, m.triangle_count)) continue;
                lit++;
                f = (CB_TOP - P[1]) / (S[1] - P[1]);
                x = P[0] + f * (S[0] - P[0]);
                z = P[2] + f * (S[2] - P[2]);
                if (!(fabs(x) <= CB_HOLE && fabs(z) <= CB_HOLE)) through_hole = 0;
            }
        }
        probes++;
        lit_samples += lit;
        if (lit > 0) lit_probes++;
        if (wall && lit > 0) wall_lit++;
    }
    CHECK_MSG(through_hole, "light reaches the inside of the box past the hole");
    CHECK(lit_probes > 0 && lit_probes < probes / 4);
    CHECK(wall_lit == 0); /* the hole's light falls on the floor (and the cube) only */
    /* Beneath the light centre: every sample; the cavity floor's corners: none. */
    for (i = 0; i < 5u; i++) {
        double P[3] = {0.0, CB_FLOOR + 1e-6, 0.0};
        int si, sj, n = 0;
        if (i > 0) {
            P[0] = (i & 1u) ? 1.7 : -1.7;
            P[2] = (i & 2u) ? 1.7 : -1.7;
        }
        for (sj = 0; sj < k; sj++) {
            for (si = 0; si < k; si++) {
                double S[3];
                light_sample(S, &v, si, sj, k);
                n += !seg_blocked(&m, P, S, 0, m.triangle_count);
            }
        }
        if (i == 0) under = n;
        else corner += n;
    }
    CHECK(under == k * k);
    CHECK(corner == 0);
    fprintf(stderr, "  closed-box: %d/%d probes inside lit (%d samples), none on the walls\n",
            lit_probes, probes, lit_samples);
    pn_mesh_free(&m);
}

/* canopy: every leaf two coincident quads of opposite winding on its own 4 vertices (the
 * back quad's triangles are the front's reversed), a small convex quad (its longer diagonal
 * about 1/50 of the crown's width) centred inside the crown ellipsoid; the orientations
 * spread over the sphere; the trunk and branches closed and outward, the trunk standing on
 * the ground; and the ground under the crown dappled: brute-force visibility over a grid
 * under the crown ranges from deep shade to nearly full light. */
static void test_canopy(void)
{
    pn_mesh m;
    pn_scene_view v;
    uint32_t l, t, leaf_t1 = CAN_LEAVES * 4u, ground_t0;
    int pairs = 1, own = 1, size = 1, inside = 1, solids = 1, steep = 0, k;
    double sum_n[3] = {0, 0, 0}, xmin = HUGE_VAL, xmax = -HUGE_VAL;
    REQUIRE(pn_builtin_scene("canopy", &m, &v, NULL, 0) == 0);
    REQUIRE(m.triangle_count == expected_triangles("canopy"));
    CHECK(m.vertex_count == CAN_LEAVES * 4u + CAN_TRUNK_VERTS + CAN_BRANCHES * CAN_BRANCH_VERTS + 4u);
    ground_t0 = m.triangle_count - 2u;
    for (t = 0; t < CAN_LEAVES * 4u; t++) {
        const float *p = m.positions + (size_t)t * 3u;
        if (p[0] < xmin) xmin = p[0];
        if (p[0] > xmax) xmax = p[0];
    }
    for (l = 0; l < CAN_LEAVES; l++) {
        const uint32_t *ix = m.indices + (size_t)l * 12u;
        double n0[3], n1[3], n2[3], n3[3], cen[3], c[3] = {0, 0, 0}, p[4][3], d0[3], d1[3], l0, l1;
        uint32_t i;
        for (i = 0; i < 12u; i++)
            if (ix[i] < 4u * l || ix[i] >= 4u * l + 4u) own = 0;
        /* back quad = the front quad's triangles reversed: (a,b,c),(a,c,d) then
         * (a,d,c),(a,c,b) */
        if (!(ix[6] == ix[0] && ix[7] == ix[5] && ix[8] == ix[4] && ix[9] == ix[0] &&
              ix[10] == ix[2] && ix[11] == ix[1] && ix[3] == ix[0] && ix[4] == ix[2]))
            pairs = 0;
        tri_normal(n0, cen, &m, 4u * l);
        tri_normal(n1, cen, &m, 4u * l + 1u);
        tri_normal(n2, cen, &m, 4u * l + 2u);
        tri_normal(n3, cen, &m, 4u * l + 3u);
        /* front halves agree, backs exactly opposite, and all non-degenerate */
        if (!(dot3(n0, n1) > 0.0 && dot3(n0, n2) < 0.0 && dot3(n1, n3) < 0.0 &&
              dot3(n0, n0) > 1e-10))
            pairs = 0;
        for (i = 0; i < 4u; i++) {
            vert(p[i], &m, 4u * l + i);
            for (k = 0; k < 3; k++) c[k] += 0.25 * p[i][k];
        }
        sub3(d0, p[2], p[0]);
        sub3(d1, p[3], p[1]);
        l0 = sqrt(dot3(d0, d0));
        l1 = sqrt(dot3(d1, d1));
        if (!(l0 > (xmax - xmin) / 70.0 && l0 < (xmax - xmin) / 35.0 && l1 > 0.3 * l0 && l1 < l0))
            size = 0;
        {
            double x = c[0] / CAN_CROWN_RX, y = (c[1] - CAN_CROWN_Y) / CAN_CROWN_RY,
                   z = c[2] / CAN_CROWN_RX;
            if (!(x * x + y * y + z * z < 1.0)) inside = 0;
        }
        normalize3(n0);
        for (k = 0; k < 3; k++) sum_n[k] += n0[k];
        if (fabs(n0[1]) < 0.5) steep++;
    }
    CHECK_MSG(own, "a leaf uses another leaf's vertices");
    CHECK_MSG(pairs, "a leaf's two quads are not coincident with opposite winding");
    CHECK_MSG(size, "a leaf is not about 1/50 of the crown's width");
    CHECK_MSG(inside, "a leaf's centre is outside the crown");
    CHECK(xmax - xmin > 2.0 * CAN_CROWN_RX * 0.7 && xmax - xmin < 2.0 * CAN_CROWN_RX);
    /* uniform on the sphere: |n_y| < 1/2 for half of them, the mean normal near zero */
    CHECK_MSG(steep > (int)CAN_LEAVES * 4 / 10 && steep < (int)CAN_LEAVES * 6 / 10, "%d steep", steep);
    CHECK(sqrt(dot3(sum_n, sum_n)) < 0.1 * CAN_LEAVES);
    /* trunk and branches: closed, outward, each on its own vertices */
    for (t = leaf_t1; t < ground_t0;) {
        uint32_t n = t == leaf_t1 ? CAN_TRUNK_TRIS : CAN_BRANCH_TRIS;
        uint32_t nv = t == leaf_t1 ? CAN_TRUNK_VERTS : CAN_BRANCH_VERTS;
        if (!closed_manifold(&m, t, t + n) || !(signed_volume(&m, t, t + n) > 0.0) ||
            distinct_vertices(&m, t, t + n) != nv || (int)nv - (int)(3u * n / 2u) + (int)n != 2)
            solids = 0;
        t += n;
    }
    CHECK(solids);
    {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        uint32_t i;
        for (i = leaf_t1 * 3u; i < (leaf_t1 + CAN_TRUNK_TRIS) * 3u; i++) {
            double y = m.positions[(size_t)m.indices[i] * 3u + 1u];
            if (y < lo) lo = y;
            if (y > hi) hi = y;
        }
        CHECK(lo == m.bbox_min[1] && hi > CAN_CROWN_Y - CAN_CROWN_RY);
    }
    /* dappled ground: 13 x 13 points under the crown (|x|, |z| <= 1.8), 6 x 6 samples each */
    {
        const int kk = 6;
        int i, shade = 0, light = 0, mid = 0;
        double vmin = 1.0, vmax = 0.0;
        for (i = 0; i < 169; i++) {
            double P[3];
            int si, sj, lit = 0;
            P[0] = -1.8 + 3.6 * (double)(i % 13) / 12.0;
            P[1] = m.bbox_min[1] + 1e-6;
            P[2] = -1.8 + 3.6 * (double)(i / 13) / 12.0;
            if (fabs(P[0]) < 0.4 && fabs(P[2]) < 0.4) continue; /* the trunk */
            for (sj = 0; sj < kk; sj++) {
                for (si = 0; si < kk; si++) {
                    double S[3];
                    light_sample(S, &v, si, sj, kk);
                    lit += !seg_blocked(&m, P, S, 0, ground_t0);
                }
            }
            {
                double vis = (double)lit / (kk * kk);
                if (vis < vmin) vmin = vis;
                if (vis > vmax) vmax = vis;
                if (vis < 0.4) shade++;
                else if (vis > 0.75) light++;
                else mid++;
            }
        }
        fprintf(stderr, "  canopy: ground under the crown: visibility %.2f..%.2f, %d shaded, %d mid, %d lit\n",
                vmin, vmax, shade, mid, light);
        CHECK(vmin < 0.3 && vmax > 0.8);
        CHECK(shade >= 10 && light >= 10);
    }
    pn_mesh_free(&m);
}

/* colonnade: columns (plinth, shaft, capital) closed and outward, the shaft a 12-sided
 * prism of its own 24 vertices; every voussoir a closed outward hexahedron, those of an
 * arch face to face (voussoir j's upper-angle face is j + 1's lower one) between the two
 * capitals' tops, their inner corners on the intrados circle and outer on the extrados,
 * the arch's volume that of the polygonal half-annulus; the beam on the keystone; and the
 * opening lets the light through where the ring stops it: from the light centre, through
 * points of each +z-row arch's plane, the floor behind the opening's middle is lit and
 * the floor behind the ring is not. */
static void test_colonnade(void)
{
    pn_mesh m;
    pn_scene_view v;
    const uint32_t a0 = COL_COLUMNS * COL_COLUMN_TRIS;
    const double step = 3.14159265358979323846 / COL_VOUSSOIRS;
    uint32_t c, a, j, t;
    int columns = 1, vous = 1, radii = 1, faces = 1, springs = 1, volume = 1, through = 1, k;
    double key_top = -HUGE_VAL, beam_lo = HUGE_VAL;
    REQUIRE(pn_builtin_scene("colonnade", &m, &v, NULL, 0) == 0);
    REQUIRE(m.triangle_count == expected_triangles("colonnade"));
    CHECK(m.vertex_count == COL_COLUMNS * COL_COLUMN_VERTS + COL_ARCHES * COL_VOUSSOIRS * 8u + 16u + 4u);
    for (c = 0; c < COL_COLUMNS; c++) {
        uint32_t t0 = c * COL_COLUMN_TRIS;
        const uint32_t part[4] = {t0, t0 + 12u, t0 + 56u, t0 + 68u};
        for (k = 0; k < 3; k++) {
            if (!closed_manifold(&m, part[k], part[k + 1]) ||
                !(signed_volume(&m, part[k], part[k + 1]) > 0.0))
                columns = 0;
        }
        if (distinct_vertices(&m, part[1], part[2]) != 24u) columns = 0;
    }
    CHECK_MSG(columns, "a column part is not a closed outward solid");
    for (a = 0; a < COL_ARCHES; a++) {
        uint32_t t0 = a0 + a * COL_VOUSSOIRS * 12u, v0 = COL_COLUMNS * COL_COLUMN_VERTS + a * COL_VOUSSOIRS * 8u;
        double row_z = a < COL_ARCHES / 2u ? -1.6 : 1.6;
        double cx = -5.25 + 1.5 * ((double)(a % (COL_ARCHES / 2u)) + 0.5), vol = 0.0;
        for (j = 0; j < COL_VOUSSOIRS; j++) {
            uint32_t s0 = t0 + j * 12u, vv;
            if (!closed_manifold(&m, s0, s0 + 12u) || !(signed_volume(&m, s0, s0 + 12u) > 0.0))
                vous = 0;
            vol += signed_volume(&m, s0, s0 + 12u);
            for (vv = v0 + j * 8u; vv < v0 + j * 8u + 8u; vv++) {
                double p[3], r;
                vert(p, &m, vv);
                r = sqrt((p[0] - cx) * (p[0] - cx) + (p[1] - COL_SPRING) * (p[1] - COL_SPRING));
                if (!(fabs(r - COL_R_IN) < 1e-5 || fabs(r - COL_R_OUT) < 1e-5)) radii = 0;
                if (!(p[1] >= COL_SPRING - 1e-6) || !(fabs(fabs(p[2] - row_z) - 0.5 * COL_DEPTH) < 1e-6))
                    radii = 0;
                if (j == COL_VOUSSOIRS / 2u && p[1] > key_top) key_top = p[1];
            }
            /* face to face with the next: voussoir j's corners 0, 1, 4, 5 (its smaller
             * angle; j runs from the -x springing down in angle) are j + 1's 2, 3, 6, 7 */
            if (j + 1u < COL_VOUSSOIRS) {
                static const int hi_c[4] = {2, 3, 6, 7}, lo_c[4] = {0, 1, 4, 5};
                for (k = 0; k < 4; k++) {
                    const float *p = m.positions + (size_t)(v0 + j * 8u + (uint32_t)lo_c[k]) * 3u;
                    const float *q = m.positions + (size_t)(v0 + (j + 1u) * 8u + (uint32_t)hi_c[k]) * 3u;
                    if (fabs(p[0] - q[0]) > 1e-6 || fabs(p[1] - q[1]) > 1e-6 || p[2] != q[2]) faces = 0;
                }
            }
        }
        /* springing: the end voussoirs' bottom corners (voussoir 0's larger angle, the
         * last one's smaller) at the capitals' top, over them */
        for (k = 0; k < 8; k++) {
            const float *p0 = m.positions + (size_t)(v0 + (uint32_t)k) * 3u;
            const float *p1 = m.positions + (size_t)(v0 + (COL_VOUSSOIRS - 1u) * 8u + (uint32_t)k) * 3u;
            if (k & 2) {
                if (fabs(p0[1] - COL_SPRING) > 1e-6 || !(p0[0] <= cx - COL_R_IN + 1e-6) ||
                    !(p0[0] >= cx - 1.0)) springs = 0;
            } else if (fabs(p1[1] - COL_SPRING) > 1e-6 || !(p1[0] >= cx + COL_R_IN - 1e-6) ||
                       !(p1[0] <= cx + 1.0)) {
                springs = 0;
            }
        }
        {
            double expect = COL_VOUSSOIRS * 0.5 * sin(step) * (COL_R_OUT * COL_R_OUT - COL_R_IN * COL_R_IN) * COL_DEPTH;
            if (fabs(vol - expect) > 1e-5) volume = 0;
        }
        /* through the opening: from the light centre through a point of the +z-row arch's
         * plane in the middle of the opening (0.3 under the springing: the ray crosses the
         * row's 0.4 depth at a slant, so it must stay clear of the intrados over 1 unit
         * of height) the floor is lit; through the ring 0.1 over the springing, 0.65
         * either side of the middle, not. */
        if (row_z > 0.0) {
            static const double dxs[3] = {0.0, -0.65, 0.65}, dys[3] = {-0.3, 0.1, 0.1};
            double L[3];
            f2d(L, v.light_center);
            for (k = 0; k < 3; k++) {
                double T[3], P[3], s;
                int i2, blocked;
                T[0] = cx + dxs[k];
                T[1] = COL_SPRING + dys[k];
                T[2] = row_z;
                s = L[1] / (L[1] - T[1]);
                for (i2 = 0; i2 < 3; i2++) P[i2] = L[i2] + s * (T[i2] - L[i2]);
                P[1] = 1e-6;
                blocked = seg_blocked(&m, P, L, 0, m.triangle_count - 2u);
                if (blocked != (k != 0)) {
                    through = 0;
                    fprintf(stderr, "  arch %u, offset %.2f: blocked %d\n", (unsigned)a, dxs[k], blocked);
                }
            }
        }
    }
    CHECK_MSG(vous, "a voussoir is not a closed outward solid");
    CHECK_MSG(radii, "a voussoir corner is off the intrados/extrados");
    CHECK_MSG(faces, "neighbouring voussoirs do not meet face to face");
    CHECK_MSG(springs, "an arch does not spring from its capitals");
    CHECK_MSG(volume, "an arch's volume is not the half-annulus's");
    CHECK_MSG(through, "light through the arch openings is wrong");
    /* beams: closed, resting on the keystones */
    for (t = a0 + COL_ARCHES * COL_VOUSSOIRS * 12u; t < m.triangle_count - 2u; t += 12u) {
        uint32_t i;
        CHECK(closed_manifold(&m, t, t + 12u) && signed_volume(&m, t, t + 12u) > 0.0);
        for (i = t * 3u; i < (t + 12u) * 3u; i++) {
            double y = m.positions[(size_t)m.indices[i] * 3u + 1u];
            if (y < beam_lo) beam_lo = y;
        }
    }
    CHECK(fabs(beam_lo - key_top) < 1e-6);
    /* the light is high above everything and off the middle along both axes */
    CHECK(v.light_center[1] > 3.0f * m.bbox_max[1]);
    CHECK(v.light_center[0] != 0.0f && v.light_center[2] != 0.0f);
    fprintf(stderr, "  colonnade: keystones' top %.4f, beams from %.4f\n", key_top, beam_lo);
    pn_mesh_free(&m);
}

/* Receiver ranges through pn_mesh_add_ground and pn_setup_load. */
static void test_receiver_ranges(void)
{
    pn_mesh m;
    pn_setup s;
    char err[256];
    REQUIRE(pn_builtin_scene("elongated-cube", &m, NULL, NULL, 0) == 0);
    CHECK(m.receiver_first == 12u && m.receiver_count == 2u);
    /* A range ending at the last triangle takes the new ground in. */
    REQUIRE(pn_mesh_add_ground(&m, NULL, 0) == 0);
    CHECK(m.triangle_count == 16u && m.receiver_first == 12u && m.receiver_count == 4u);
    /* Any other range is replaced by the new ground; so is none. */
    m.receiver_first = 0u;
    m.receiver_count = 12u;
    REQUIRE(pn_mesh_add_ground(&m, NULL, 0) == 0);
    CHECK(m.triangle_count == 18u && m.receiver_first == 16u && m.receiver_count == 2u);
    m.receiver_first = 0u;
    m.receiver_count = 0u;
    REQUIRE(pn_mesh_add_ground(&m, NULL, 0) == 0);
    CHECK(m.triangle_count == 20u && m.receiver_first == 18u && m.receiver_count == 2u);
    pn_mesh_free(&m);
    CHECK(m.receiver_first == 0u && m.receiver_count == 0u);
    /* The setup keeps the scene's range, with --ground on extended over the new plane. */
    REQUIRE(pn_setup_load(&s, "room", 1, -1, err, sizeof(err)) == 0);
    CHECK(s.mesh.receiver_count == 2u && s.mesh.receiver_first == s.mesh.triangle_count - 2u);
    pn_setup_free(&s);
    REQUIRE(pn_setup_load(&s, "closed-box", 1, 1, err, sizeof(err)) == 0);
    CHECK(s.mesh.triangle_count == 60u && s.mesh.receiver_first == 54u && s.mesh.receiver_count == 6u);
    pn_setup_free(&s);
}

/* ---- the square scene and its closed form ---- */

static uint32_t rng_state = 12345u;
static double rnd(void)
{
    /* xorshift32: test-local, deterministic */
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return (double)(rng_state >> 8) / 16777216.0;
}

static void test_square_mesh_matches_params(void)
{
    pn_square_params p;
    pn_mesh m;
    pn_scene_view v;
    uint32_t i;
    int occ = 0, gnd = 0;
    pn_square_scene_params(&p);
    /* ground_y < occluder_y < light_y and the shadow fits on the ground. */
    CHECK(p.ground_y < p.occluder_y && p.occluder_y < p.light_y);
    REQUIRE(pn_builtin_scene("square", &m, &v, NULL, 0) == 0);
    CHECK(v.light_center[0] == 0.0f && v.light_center[1] == p.light_y && v.light_center[2] == 0.0f);
    CHECK(v.light_u[0] == p.light_half && v.light_u[1] == 0.0f && v.light_u[2] == 0.0f);
    CHECK(v.light_v[0] == 0.0f && v.light_v[1] == 0.0f && v.light_v[2] == p.light_half);
    for (i = 0; i < m.vertex_count; i++) {
        const float *q = m.positions + (size_t)i * 3u;
        if (q[1] == p.occluder_y && fabsf(q[0]) == p.occluder_half &&
            fabsf(q[2]) == p.occluder_half)
            occ++;
        if (q[1] == p.ground_y && fabsf(q[0]) == p.ground_half && fabsf(q[2]) == p.ground_half)
            gnd++;
    }
    CHECK(occ == 4 && gnd == 4 && m.vertex_count == 8u);
    /* Penumbra edge (|x| = 2h + L for this geometry) lies on the ground. */
    CHECK(p.ground_half > 2.0f * p.occluder_half + p.light_half);
    pn_mesh_free(&m);
}

static void test_square_closed_form_values(void)
{
    pn_square_params p;
    int k, ks[] = {0, 1, 2, 4, 8, 16, 32};
    double x, prev;
    pn_square_scene_params(&p);
    for (k = 0; k < (int)(sizeof(ks) / sizeof(ks[0])); k++) {
        /* Far outside the shadow: fully lit. */
        CHECK(pn_square_closed_form(&p, 3.0, 3.0, ks[k]) == 1.0);
        CHECK(pn_square_closed_form(&p, -1.6, 0.0, ks[k]) == 1.0);
        CHECK(pn_square_closed_form(&p, 0.0, 1.51, ks[k]) == 1.0);
        /* Umbra: |x|, |z| <= 2h - L = 0.5 with these numbers. */
        CHECK(pn_square_closed_form(&p, 0.0, 0.0, ks[k]) == 0.0);
        CHECK(pn_square_closed_form(&p, 0.49, -0.49, ks[k]) == 0.0);
    }
    /* Half way across the penumbra along x: the projected occluder covers [-2, 0] of the
     * light's [-0.5, 0.5]: half the light hidden. */
    CHECK(fabs(pn_square_closed_form(&p, 1.0, 0.0, 0) - 0.5) < 1e-15);
    CHECK(fabs(pn_square_closed_form(&p, 1.0, 1.0, 0) - 0.75) < 1e-15);
    CHECK(pn_square_closed_form(&p, 1.0, 0.0, 4) == 0.5);
    /* Monotone along +x from the centre; strictly increasing inside the penumbra. */
    prev = -1.0;
    for (x = 0.0; x <= 2.0; x += 1.0 / 64.0) {
        double vis = pn_square_closed_form(&p, x, 0.0, 0);
        CHECK(vis >= prev);
        if (x > 0.5 && x < 1.5) CHECK(vis > prev);
        prev = vis;
        for (k = 1; k <= 16; k *= 2) {
            static double prevk[17];
            double vk = pn_square_closed_form(&p, x, 0.1, k);
            if (x > 0.0) CHECK(vk >= prevk[k]);
            prevk[k] = vk;
        }
    }
    /* Symmetry in x, z and swapping the axes. */
    for (k = 0; k < 200; k++) {
        double a = 4.0 * rnd() - 2.0, b = 4.0 * rnd() - 2.0;
        double v0 = pn_square_closed_form(&p, a, b, 0);
        CHECK(fabs(v0 - pn_square_closed_form(&p, -a, b, 0)) < 1e-12);
        CHECK(fabs(v0 - pn_square_closed_form(&p, b, a, 0)) < 1e-12);
        CHECK(v0 >= 0.0 && v0 <= 1.0);
    }
}

/* Sample counts converge to the area. Per axis the k samples are the midpoints of k
 * equal cells of the light; the number of midpoints inside any interval of length l
 * is floor(l/w) or floor(l/w) + 1 (w = cell width), so the per-axis hidden fraction g
 * differs from the area fraction a by at most 1/k. For the products of two such
 * fractions in [0, 1]: |gx gz - ax az| <= |gx - ax| gz + ax |gz - az| <= 2/k. */
static void test_square_convergence(void)
{
    pn_square_params p;
    int i, k;
    double worst[10] = {0};
    pn_square_scene_params(&p);
    for (i = 0; i < 2000; i++) {
        double x = 3.2 * rnd() - 1.6, z = 3.2 * rnd() - 1.6;
        double a = pn_square_closed_form(&p, x, z, 0);
        int e = 0;
        for (k = 1; k <= 512; k *= 2, e++) {
            double d = fabs(pn_square_closed_form(&p, x, z, k) - a);
            CHECK_MSG(d <= 2.0 / k + 1e-12, "x=%g z=%g k=%d diff=%g", x, z, k, d);
            if (d > worst[e]) worst[e] = d;
        }
    }
    /* ...and the bound is not vacuous: the error actually shrinks. */
    CHECK(worst[9] < worst[2]);
    CHECK(worst[9] <= 2.0 / 512.0);
}

/* Brute force against the built mesh: for random receiver points, each of the k x k
 * samples is tested with a double segment/triangle intersection against the occluder's
 * two triangles; points with a sample near a projected edge are skipped. */
static void test_square_brute_force(void)
{
    pn_square_params p;
    pn_mesh m;
    int i, tested = 0, skipped = 0, partial = 0;
    const int ks[] = {1, 3, 4, 8, 16};
    pn_square_scene_params(&p);
    REQUIRE(pn_builtin_scene("square", &m, NULL, NULL, 0) == 0);
    for (i = 0; i < 600; i++) {
        int k = ks[i % 5], si, sj, hidden = 0;
        double x = 3.4 * rnd() - 1.7, z = 3.4 * rnd() - 1.7, expect;
        double P[3];
        if (pn_square_min_edge_distance(&p, x, z, k) < 1e-6) {
            skipped++;
            continue;
        }
        P[0] = x;
        P[1] = p.ground_y;
        P[2] = z;
        for (sj = 0; sj < k; sj++) {
            for (si = 0; si < k; si++) {
                double S[3];
                S[0] = ((double)(2 * si + 1) / k - 1.0) * p.light_half;
                S[1] = p.light_y;
                S[2] = ((double)(2 * sj + 1) / k - 1.0) * p.light_half;
                /* triangles 0, 1 are the occluder */
                hidden += seg_blocked(&m, P, S, 0, 2);
            }
        }
        expect = 1.0 - (double)hidden / ((double)k * k);
        CHECK_MSG(fabs(pn_square_closed_form(&p, x, z, k) - expect) < 1e-12,
                  "x=%g z=%g k=%d closed %g brute %g", x, z, k,
                  pn_square_closed_form(&p, x, z, k), expect);
        if (expect > 0.0 && expect < 1.0) partial++;
        tested++;
    }
    CHECK(tested > 500);
    CHECK(partial > 100);
    fprintf(stderr, "  brute force: %d points (%d in penumbra), %d skipped\n", tested, partial,
            skipped);
    pn_mesh_free(&m);
}

static void test_square_edge_distance(void)
{
    pn_square_params p;
    pn_square_scene_params(&p);
    /* k = 2: samples at +-0.25. From x = 0.75 the projected occluder spans [-1.75, 0.25]
     * in x: a sample sits exactly on the projected edge. */
    CHECK(pn_square_min_edge_distance(&p, 0.75, 0.0, 2) == 0.0);
    /* From x = 0.7 the projected x-interval ends at (0.5 - 0.5 * 0.7) / 0.5 = 0.3. */
    CHECK(fabs(pn_square_min_edge_distance(&p, 0.7, 0.0, 2) - 0.05) < 1e-12);
    /* Centre: projected square [-1, 1]^2, nearest sample (+-0.25) is 0.75 from an edge. */
    CHECK(fabs(pn_square_min_edge_distance(&p, 0.0, 0.0, 2) - 0.75) < 1e-12);
    /* Outside past a corner: Euclidean distance to the corner. From (3, 3) the square is
     * [-4, -2]^2; the nearest sample (-0.25, -0.25) is (1.75, 1.75) from its corner. */
    CHECK(fabs(pn_square_min_edge_distance(&p, 3.0, 3.0, 2) - 1.75 * sqrt(2.0)) < 1e-12);
    CHECK(pn_square_min_edge_distance(&p, 0.0, 0.0, 0) == HUGE_VAL);
}

int main(void)
{
    RUN(test_all_scenes);
    RUN(test_unknown_name);
    RUN(test_deterministic);
    RUN(test_spheres_closed);
    RUN(test_box_closed);
    RUN(test_thin_slivers);
    RUN(test_room);
    RUN(test_canopy);
    RUN(test_colonnade);
    RUN(test_closed_box);
    RUN(test_receiver_ranges);
    RUN(test_square_mesh_matches_params);
    RUN(test_square_closed_form_values);
    RUN(test_square_convergence);
    RUN(test_square_brute_force);
    RUN(test_square_edge_distance);
    return pn_test_summary();
}
