/* test_bvh.c - the BVH's split references (config.h PN_BVH_SPLIT_DEPTH, PN_BVH_SPLIT_REFS):
 *
 *   containment  the leaf boxes a triangle is listed in cover the whole real triangle
 *                (its vertices, points along its edges, points inside it, in double), on
 *                long diagonal slivers at several scales and offsets, general triangles
 *                and near-degenerate ones; every node's box holds its children's; each
 *                non-degenerate triangle is listed, each degenerate one is not; the raster
 *                order lists every non-degenerate triangle once; a whole triangle's
 *                vertices lie in its leaf's box (the ray filter's bound relies on it) and
 *                only a split triangle's references carry PN_REF_SPLIT; and splitting happened
 *                (more references than triangles, smaller boxes), so none of it is vacuous
 *   frames       every algorithm renders the same bytes with splitting (the default
 *                reserve, and a reserve one short of what the scene wants) as without it
 *                (limits.bvh_refs = max_triangles), on the built-in thin scene and on a
 *                scene of random slivers
 *   limits       a reserve below max_triangles, above the default or above 2^26 is
 *                PN_E_LIMIT; a short reserve is never exceeded
 *   wide tree    the four-wide tree, the one the context keeps (pn_kbvh4, folded from the
 *                build's binary tree by src/pn_bvh_build.c pn_bvh_fold): every node
 *                reached once, 2 .. 4 children (the root 0 or 1 when the tree is empty or
 *                one leaf) and fewer than four only when all are leaves, every child box
 *                inside its parent's lane and every interior lane the union of its
 *                node's lanes, leaves of 2 .. PN_BVH_LEAF_MAX references (3 when that is
 *                smaller; 1 only in a tree of one) that together list every reference
 *                once, at most pn_bvh_wide_max nodes, a walk stack within PN_BVH_STACK,
 *                and a binary depth within PN_BVH_DEPTH_MAX; a chain of nested squares deep enough for the depth bound
 *                to act renders with every algorithm, the exact ones with the same bytes
 *   parallel     the same tree, byte for byte, under every schedule of the parallel-for
 *   short reserve  slivers whose first halving passes the reserve, and a scene without
 *                slivers, give the tree of no splitting, byte for byte, in parallel too */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "penumbra/penumbra.h"
#include "pn_internal.h"
#include "pn_test.h"
#include "pn_test_scene.h"

#define FRAME_W 64u
#define FRAME_H 48u

/* xorshift64*: the same scenes every run */
static uint64_t g_rng = 0x9e3779b97f4a7c15ull;
static double rnd(void)
{
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return (double)((g_rng * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}
static double rnd_in(double lo, double hi) { return lo + (hi - lo) * rnd(); }

typedef struct scene {
    float *pos;
    uint32_t *idx;
    uint32_t tris, verts;
} scene;

static void add_tri(scene *s, const double v[9])
{
    int i;
    for (i = 0; i < 9; i++) s->pos[s->verts * 3u + (uint32_t)i] = (float)v[i];
    for (i = 0; i < 3; i++) s->idx[s->tris * 3u + (uint32_t)i] = s->verts + (uint32_t)i;
    s->verts += 3u;
    s->tris++;
}

/* A sliver: length len along a random direction, width wid across it, centred at c. */
static void add_sliver(scene *s, const double c[3], double len, double wid)
{
    double d[3], w[3], v[9], n;
    int a;
    do {
        for (a = 0; a < 3; a++) d[a] = rnd_in(-1, 1);
        n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (n < 0.2);
    for (a = 0; a < 3; a++) d[a] /= n;
    /* a width direction: d x (a random vector), normalized */
    do {
        double r[3] = {rnd_in(-1, 1), rnd_in(-1, 1), rnd_in(-1, 1)};
        w[0] = d[1] * r[2] - d[2] * r[1];
        w[1] = d[2] * r[0] - d[0] * r[2];
        w[2] = d[0] * r[1] - d[1] * r[0];
        n = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    } while (n < 0.2);
    for (a = 0; a < 3; a++) {
        w[a] /= n;
        v[a] = c[a] - d[a] * len * 0.5;
        v[3 + a] = c[a] + d[a] * len * 0.5;
        v[6 + a] = c[a] + d[a] * len * rnd_in(-0.4, 0.4) + w[a] * wid;
    }
    add_tri(s, v);
}

/* Random slivers at several scales and offsets, general triangles, triangles flat in one
 * axis, and a few exactly degenerate ones. */
static void make_mixed(scene *s, uint32_t n)
{
    uint32_t i;
    s->pos = (float *)malloc((size_t)n * 9u * sizeof(float));
    s->idx = (uint32_t *)malloc((size_t)n * 3u * sizeof(uint32_t));
    s->tris = s->verts = 0;
    for (i = 0; i < n; i++) {
        double c[3], v[9];
        int a, kind = (int)(i % 8u);
        double off = (i % 3u == 0u) ? 0.0 : (i % 3u == 1u) ? 1000.0 : -250000.0;
        double scale = (i % 5u == 0u) ? 0.01 : (i % 5u == 1u) ? 100.0 : 1.0;
        for (a = 0; a < 3; a++) c[a] = off + rnd_in(-10, 10) * scale;
        if (kind < 5) {
            add_sliver(s, c, scale * rnd_in(1, 8), scale * rnd_in(1e-4, 1e-2));
        } else if (kind == 5) {
            for (a = 0; a < 9; a++) v[a] = c[a % 3] + scale * rnd_in(-1, 1);
            add_tri(s, v);
        } else if (kind == 6) {
            /* flat in y, diagonal in x and z */
            double t = rnd_in(0.5, 4) * scale;
            v[0] = c[0] - t, v[1] = c[1], v[2] = c[2] - t;
            v[3] = c[0] + t, v[4] = c[1], v[5] = c[2] + t;
            v[6] = c[0] + t * 0.01, v[7] = c[1], v[8] = c[2];
            add_tri(s, v);
        } else {
            if (i % 16u == 7u) {
                /* degenerate: three collinear points */
                for (a = 0; a < 3; a++) {
                    v[a] = c[a];
                    v[3 + a] = c[a] + 1.0;
                    v[6 + a] = c[a] + 2.0;
                }
            } else {
                add_sliver(s, c, scale * 20.0, scale * 1e-3);
                continue;
            }
            add_tri(s, v);
        }
    }
}

static void free_scene(scene *s)
{
    free(s->pos);
    free(s->idx);
}

/* A leaf of the wide tree: its box (its lane of its parent) and references. */
typedef struct leafrec {
    float lo[3], hi[3];
    uint32_t first, count;
} leafrec;

static int in_box(const leafrec *lf, const double p[3])
{
    int a;
    for (a = 0; a < 3; a++)
        if (!(p[a] >= (double)lf->lo[a] && p[a] <= (double)lf->hi[a])) return 0;
    return 1;
}

static double box_area(const float *lo, const float *hi)
{
    double dx = (double)hi[0] - lo[0], dy = (double)hi[1] - lo[1], dz = (double)hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
}

/* Leaves listing each triangle: (triangle, node) pairs, sorted by triangle. */
typedef struct pair {
    uint32_t tri, node, split;
} pair;

static int cmp_pair(const void *a, const void *b)
{
    const pair *x = (const pair *)a, *y = (const pair *)b;
    if (x->tri != y->tri) return x->tri < y->tri ? -1 : 1;
    return x->node < y->node ? -1 : x->node > y->node;
}

/* The wide tree's structure (the file's head); returns its leaves (malloc'd, *nleaves). */
static leafrec *check_wide(pn_context *ctx, uint32_t *nleaves)
{
    const pn_kbvh4 *w = ctx->wnodes;
    uint8_t *wide_seen = (uint8_t *)calloc(ctx->bvh_wide + 1u, 1);
    uint8_t *ref_seen = (uint8_t *)calloc(ctx->bvh_refs + 1u, 1);
    uint32_t *queue = (uint32_t *)malloc(((size_t)ctx->bvh_wide + 1u) * 2u * sizeof(uint32_t));
    leafrec *leaves = (leafrec *)malloc(((size_t)ctx->bvh_refs + 1u) * sizeof(leafrec));
    uint32_t head = 0, tail = 0, i, a, bad = 0, bad_leaf = 0, twice = 0, full = 0, need_max = 0, nl = 0;
    uint32_t leaf_max = PN_BVH_LEAF_MAX > 3u ? PN_BVH_LEAF_MAX : 3u;
    if (!wide_seen || !ref_seen || !queue || !leaves) {
        fprintf(stderr, "check_wide: out of memory\n");
        exit(1);
    }
    CHECK_MSG(ctx->bvh_wide >= 1u && ctx->bvh_wide <= pn_bvh_wide_max(pn_bvh_refs_max(&ctx->limits)),
              "%u wide nodes for a reserve of %u references", ctx->bvh_wide, pn_bvh_refs_max(&ctx->limits));
    CHECK_MSG(ctx->bvh_depth <= PN_BVH_DEPTH_MAX, "binary depth %u, PN_BVH_DEPTH_MAX %u", ctx->bvh_depth,
              (unsigned)PN_BVH_DEPTH_MAX);
    queue[tail++] = 0u; /* node, stack need on its path */
    queue[tail++] = 0u;
    while (head < tail) {
        uint32_t wi = queue[head++], need = queue[head++], c;
        const pn_kbvh4 *wn;
        if (wi >= ctx->bvh_wide || wide_seen[wi]) {
            bad++;
            continue;
        }
        wide_seen[wi] = 1u;
        wn = w + wi;
        if (wn->n > 4u || (wi != 0u && wn->n < 2u) || (wi == 0u && wn->n == 0u && ctx->bvh_refs > 0u)) bad++;
        if (wn->n == 4u) full++;
        for (c = 0; c < wn->n && c < 4u && wn->n < 4u; c++)
            if (!(wn->child[c] & PN_W4_LEAF)) bad++; /* the fold stops short of four only at leaves */
        need += wn->n > 0u ? wn->n - 1u : 0u;
        if (need + 1u > need_max) need_max = need + 1u;
        for (c = 0; c < wn->n && c < 4u; c++) {
            uint32_t ch = wn->child[c];
            for (a = 0; a < 3u; a++)
                if (!(wn->lo[a][c] <= wn->hi[a][c])) bad++;
            if (ch & PN_W4_LEAF) {
                leafrec *lf = leaves + nl;
                uint32_t e = PN_W4_LEAF | wi << 2 | c, q;
                lf->count = pn_w4_leaf_refs(w, e, &lf->first);
                pn_w4_leaf_box(w, e, lf->lo, lf->hi);
                if (lf->count > leaf_max || (lf->count < 2u && ctx->bvh_refs != 1u) ||
                    lf->first + lf->count > ctx->bvh_refs || nl >= ctx->bvh_refs) {
                    bad_leaf++;
                    continue;
                }
                for (q = lf->first; q < lf->first + lf->count; q++) {
                    twice += ref_seen[q];
                    ref_seen[q] = 1u;
                }
                nl++;
            } else {
                const pn_kbvh4 *cw;
                float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
                uint32_t d;
                if (ch >= ctx->bvh_wide || tail + 2u > ((size_t)ctx->bvh_wide + 1u) * 2u) {
                    bad++;
                    continue;
                }
                cw = w + ch;
                for (d = 0; d < cw->n && d < 4u; d++)
                    for (a = 0; a < 3u; a++) {
                        if (!(cw->lo[a][d] >= wn->lo[a][c] && cw->hi[a][d] <= wn->hi[a][c])) bad++;
                        lo[a] = fminf(lo[a], cw->lo[a][d]);
                        hi[a] = fmaxf(hi[a], cw->hi[a][d]);
                    }
                for (a = 0; a < 3u; a++)
                    if (lo[a] != wn->lo[a][c] || hi[a] != wn->hi[a][c]) bad++; /* tight */
                queue[tail++] = ch;
                queue[tail++] = need;
            }
        }
    }
    for (i = 0; i < ctx->bvh_refs; i++)
        if (!ref_seen[i]) bad_leaf++;
    for (i = 0; i < ctx->bvh_wide; i++)
        if (!wide_seen[i]) bad++;
    CHECK_MSG(bad == 0u, "wide tree: %u bad boxes, children or unreached nodes", bad);
    CHECK_MSG(bad_leaf == 0u && twice == 0u, "wide tree: %u bad or missing leaf references, %u listed twice",
              bad_leaf, twice);
    CHECK_MSG(need_max <= PN_BVH_STACK, "a wide walk needs %u stack entries, PN_BVH_STACK is %u", need_max,
              (unsigned)PN_BVH_STACK);
    /* the fold folds: some nodes four-wide, fewer wide nodes than a third of the binary */
    if (ctx->bvh_nodes >= 15u)
        CHECK_MSG(full > 0u && ctx->bvh_wide <= ctx->bvh_nodes / 3u, "%u wide nodes (%u four-wide) for %u binary",
                  ctx->bvh_wide, full, ctx->bvh_nodes);
    free(wide_seen);
    free(ref_seen);
    free(queue);
    *nleaves = nl;
    return leaves;
}

static void check_tree(pn_context *ctx, const scene *s, int expect_split)
{
    uint32_t nleaves = 0, n;
    leafrec *leaves = check_wide(ctx, &nleaves);
    pair *pairs = (pair *)malloc((size_t)ctx->bvh_refs * sizeof(pair) + 1u);
    uint8_t *raster_seen = (uint8_t *)calloc(s->tris + 1u, 1);
    uint32_t np = 0, i, nondegen = 0, bad_nest = 0, bad_cover = 0, unlisted = 0, degen_listed = 0;
    uint32_t raster_bad = 0, split_tris = 0, points = 0, whole_outside = 0, mark_bad = 0;
    double whole_area = 0.0, part_area = 0.0;
    REQUIRE(pairs && raster_seen);
    REQUIRE(ctx->bvh_wide >= 1u && ctx->bvh_refs >= ctx->bvh_tris);
    /* every leaf's entries collected */
    for (n = 0; n < nleaves; n++) {
        const leafrec *lf = leaves + n;
        for (i = lf->first; i < lf->first + lf->count; i++) {
            if (i >= ctx->bvh_refs || np >= ctx->bvh_refs) {
                bad_nest++;
                continue;
            }
            uint32_t t = ctx->tri_index[i] & PN_REF_TRI, v, a;
            pairs[np].tri = t;
            pairs[np].split = (ctx->tri_index[i] & PN_REF_SPLIT) != 0u;
            pairs[np++].node = n;
            /* a whole triangle's vertices lie in its leaf's box: the ray filter's bound
             * for it comes from that box (kernels/pn_raytrace.h) */
            if (!(ctx->tri_index[i] & PN_REF_SPLIT) && t < s->tris)
                for (v = 0; v < 3u; v++)
                    for (a = 0; a < 3u; a++) {
                        float x = s->pos[(size_t)t * 9u + v * 3u + a];
                        if (!(x >= lf->lo[a] && x <= lf->hi[a])) whole_outside++;
                    }
        }
    }
    CHECK_MSG(bad_nest == 0u, "%u leaf entries out of range", bad_nest);
    CHECK_MSG(whole_outside == 0u, "%u vertex coordinates of whole triangles outside their leaf's box", whole_outside);
    CHECK_MSG(np == ctx->bvh_refs, "leaves list %u entries, bvh_refs %u", np, ctx->bvh_refs);
    qsort(pairs, np, sizeof(pair), cmp_pair);
    /* every triangle against the leaves that list it */
    for (i = 0; i < s->tris; i++) {
        const float *f = s->pos + (size_t)i * 9u;
        uint32_t lo = 0, hi = np, first, last, e, q;
        int degenerate = (ctx->flags[i] & PN_TRI_DEGENERATE) != 0;
        while (lo < hi) {
            uint32_t mid = lo + (hi - lo) / 2u;
            if (pairs[mid].tri < i) lo = mid + 1u;
            else hi = mid;
        }
        first = last = lo;
        while (last < np && pairs[last].tri == i) last++;
        if (degenerate) {
            degen_listed += last != first;
            continue;
        }
        nondegen++;
        if (last == first) {
            unlisted++;
            continue;
        }
        /* PN_REF_SPLIT: on every reference of a triangle split in several, on none of a
         * whole one */
        for (e = first; e < last; e++) mark_bad += pairs[e].split != (last - first > 1u);
        if (last - first > 1u) {
            double wb = 0.0;
            int a;
            float wlo[3], whi[3];
            for (a = 0; a < 3; a++) {
                wlo[a] = fminf(f[a], fminf(f[3 + a], f[6 + a]));
                whi[a] = fmaxf(f[a], fmaxf(f[3 + a], f[6 + a]));
            }
            double pmin = 0.0;
            wb = box_area(wlo, whi);
            split_tris++;
            whole_area += wb;
            for (e = first; e < last; e++) {
                /* a split triangle's leaves hold its parts' boxes, with other parts or
                 * triangles (two or more references a leaf): the smallest of them, which
                 * without a split could not be smaller than the whole box */
                const leafrec *lf = leaves + pairs[e].node;
                double la = box_area(lf->lo, lf->hi);
                if (e == first || la < pmin) pmin = la;
            }
            part_area += pmin;
        }
        /* points: vertices, 63 along each edge, 200 inside */
        for (q = 0; q < 3u + 3u * 63u + 200u; q++) {
            double p[3];
            int a, found = 0;
            if (q < 3u) {
                for (a = 0; a < 3; a++) p[a] = f[q * 3u + (uint32_t)a];
            } else if (q < 3u + 3u * 63u) {
                uint32_t ed = (q - 3u) / 63u, k = (q - 3u) % 63u;
                const float *P = f + ed * 3u, *Q = f + ((ed + 1u) % 3u) * 3u;
                double t = (double)(k + 1u) / 64.0;
                for (a = 0; a < 3; a++) p[a] = (double)P[a] + t * ((double)Q[a] - (double)P[a]);
            } else {
                double u = rnd_in(0.001, 0.997), v = rnd_in(0.001, 0.998 - u);
                for (a = 0; a < 3; a++)
                    p[a] = (double)f[a] + u * ((double)f[3 + a] - f[a]) + v * ((double)f[6 + a] - f[a]);
            }
            for (e = first; e < last && !found; e++) found = in_box(leaves + pairs[e].node, p);
            points++;
            if (!found) {
                if (bad_cover < 5u)
                    fprintf(stderr, "triangle %u point %u (%.9g %.9g %.9g) in none of its %u leaves\n", i, q, p[0],
                            p[1], p[2], last - first);
                bad_cover++;
            }
        }
    }
    CHECK_MSG(bad_cover == 0u, "%u of %u triangle points outside every leaf listing the triangle", bad_cover, points);
    CHECK_MSG(mark_bad == 0u, "%u references marked otherwise than their triangle's split", mark_bad);
    CHECK_MSG(unlisted == 0u, "%u non-degenerate triangles in no leaf", unlisted);
    CHECK_MSG(degen_listed == 0u, "%u degenerate triangles listed", degen_listed);
    CHECK(ctx->bvh_tris == nondegen);
    for (i = 0; i < ctx->bvh_tris; i++) {
        uint32_t t = ctx->raster_index[i];
        if (t >= s->tris || raster_seen[t] || (ctx->flags[t] & PN_TRI_DEGENERATE)) raster_bad++;
        else raster_seen[t] = 1;
    }
    CHECK_MSG(raster_bad == 0u, "raster order: %u entries repeated, degenerate or out of range", raster_bad);
    if (expect_split) {
        CHECK_MSG(ctx->bvh_refs > ctx->bvh_tris + ctx->bvh_tris / 2u, "%u references for %u triangles",
                  ctx->bvh_refs, ctx->bvh_tris);
        /* not all: a sliver small against its distance from the origin keeps its box (the
         * margins, 2^-16 of the coordinates, are wider than it) */
        CHECK_MSG(split_tris * 4u > nondegen, "only %u of %u triangles split", split_tris, nondegen);
        /* the parts' boxes are together far smaller than the whole boxes */
        CHECK_MSG(part_area < 0.5 * whole_area, "split boxes' area %g of the whole boxes' %g", part_area,
                  whole_area);
    } else {
        CHECK_MSG(ctx->bvh_refs == ctx->bvh_tris && split_tris == 0u, "%u references for %u triangles unsplit",
                  ctx->bvh_refs, ctx->bvh_tris);
    }
    free(pairs);
    free(leaves);
    free(raster_seen);
}

static pn_context *open_ctx(pn_test_host *h, uint32_t tris, uint32_t refs)
{
    /* 0: the largest reserve, tris + PN_BVH_SPLIT_EXTRA (the library's own default is no
     * split reference at all: test_limits). */
    if (pn_test_open_refs(h, tris, FRAME_W, FRAME_H, refs ? refs : tris + (uint32_t)PN_BVH_SPLIT_EXTRA(tris)) != 0) {
        CHECK_MSG(0, "context for %u triangles, %u references", tris, refs);
        return NULL;
    }
    return h->ctx;
}

static void test_containment(void)
{
    scene s;
    pn_test_host h;
    pn_context *ctx;
    make_mixed(&s, 4000);
    ctx = open_ctx(&h, s.tris, 0);
    if (ctx) {
        CHECK(pn_scene_set(ctx, s.pos, s.verts, s.idx, s.tris) == PN_OK);
        check_tree(ctx, &s, 1);
        pn_test_close(&h);
    }
    ctx = open_ctx(&h, s.tris, s.tris);
    if (ctx) {
        pn_status st = pn_scene_set(ctx, s.pos, s.verts, s.idx, s.tris);
        CHECK_MSG(st == PN_OK, "%s", pn_last_error(ctx));
        check_tree(ctx, &s, 0);
        pn_test_close(&h);
    }
    free_scene(&s);
}

/* Renders every algorithm compiled in on three contexts (no splitting, the default
 * reserve, a reserve one short of the default's references) and compares the bytes. */
static void frames_same(const char *label, const float *pos, uint32_t verts, const uint32_t *idx, uint32_t tris,
                        const pn_camera *cam, const pn_light *light, float eps)
{
    pn_test_host h[3];
    pn_context *ctx[3];
    pn_stats st;
    uint32_t refs_default = 0, c, a, built = pn_build_info();
    size_t npix = (size_t)FRAME_W * FRAME_H;
    float *vis0 = (float *)malloc(npix * sizeof(float));
    uint8_t *rgba0 = (uint8_t *)malloc(npix * 4u);
    REQUIRE(vis0 && rgba0);
    ctx[0] = open_ctx(&h[0], tris, tris);
    ctx[1] = open_ctx(&h[1], tris, 0);
    REQUIRE(ctx[0] && ctx[1]);
    CHECK(pn_scene_set(ctx[0], pos, verts, idx, tris) == PN_OK);
    CHECK(pn_scene_set(ctx[1], pos, verts, idx, tris) == PN_OK);
    CHECK(pn_get_stats(ctx[0], &st) == PN_OK && st.bvh_refs <= tris);
    CHECK(pn_get_stats(ctx[1], &st) == PN_OK);
    refs_default = st.bvh_refs;
    CHECK_MSG(refs_default > tris + tris / 2u, "%s: %u references for %u triangles", label, refs_default, tris);
    ctx[2] = open_ctx(&h[2], tris, refs_default - 1u);
    REQUIRE(ctx[2]);
    CHECK(pn_scene_set(ctx[2], pos, verts, idx, tris) == PN_OK);
    CHECK(pn_get_stats(ctx[2], &st) == PN_OK);
    CHECK_MSG(st.bvh_refs <= refs_default - 1u && st.bvh_refs > tris, "%s: short reserve %u gave %u references",
              label, refs_default - 1u, st.bvh_refs);
    for (a = 0; a < PN_ALGO_COUNT; a++) {
        if (!(built & (1u << a))) continue;
        for (c = 0; c < 3u; c++) {
            pn_frame_options opt;
            pn_frame fr;
            pn_status rs;
            pn_test_frame_opts(&opt, FRAME_W, FRAME_H, a, eps, 0u);
            rs = pn_render(ctx[c], cam, light, &opt, &fr);
            CHECK_MSG(rs == PN_OK, "%s %s: %s", label, pn_algo_name((pn_algo)a), pn_last_error(ctx[c]));
            if (rs != PN_OK) break;
            if (c == 0u) {
                memcpy(vis0, fr.visibility, npix * sizeof(float));
                memcpy(rgba0, fr.rgba, npix * 4u);
            } else {
                CHECK_MSG(memcmp(vis0, fr.visibility, npix * sizeof(float)) == 0 && memcmp(rgba0, fr.rgba, npix * 4u) == 0,
                          "%s %s: reserve %s renders other bytes than no splitting", label, pn_algo_name((pn_algo)a),
                          c == 1u ? "default" : "short");
            }
        }
    }
    for (c = 0; c < 3u; c++) pn_test_close(&h[c]);
    free(vis0);
    free(rgba0);
}

static void test_frames_thin(void)
{
    pn_test_scene s;
    REQUIRE(pn_test_scene_load(&s, "thin") == 0);
    frames_same("thin", s.mesh.positions, s.mesh.vertex_count, s.mesh.indices, s.mesh.triangle_count, &s.camera,
                &s.light, s.eps);
    pn_test_scene_free(&s);
}

/* Random slivers above a floor, under thin's camera and light. */
static void test_frames_slivers(void)
{
    pn_test_scene th;
    scene s;
    uint32_t i;
    const uint32_t n = 1500;
    REQUIRE(pn_test_scene_load(&th, "thin") == 0);
    s.pos = (float *)malloc((size_t)(n + 2u) * 9u * sizeof(float));
    s.idx = (uint32_t *)malloc((size_t)(n + 2u) * 3u * sizeof(uint32_t));
    s.tris = s.verts = 0;
    for (i = 0; i < n; i++) {
        double c[3] = {rnd_in(-3, 3), rnd_in(0.8, 1.8), rnd_in(-3, 3)};
        add_sliver(&s, c, rnd_in(0.5, 3), rnd_in(0.002, 0.02));
    }
    {
        static const double f0[9] = {-6, 0, -6, -6, 0, 6, 6, 0, 6}, f1[9] = {-6, 0, -6, 6, 0, 6, 6, 0, -6};
        add_tri(&s, f0);
        add_tri(&s, f1);
    }
    frames_same("slivers", s.pos, s.verts, s.idx, s.tris, &th.camera, &th.light, th.eps);
    free_scene(&s);
    pn_test_scene_free(&th);
}

/* The tree of a scene of many slivers (more than its reserve) whose first halving already
 * passes the reserve (the dragon's case: cap 0) is the tree without splitting, byte for
 * byte, under every schedule of the parallel-for (the references written by ranges in
 * parallel, src/pn_bvh_build.c pn_bvh_refs), and so is that of a scene without slivers
 * under a reserve. The slivers' scene under the default reserve splits. */
static void test_refs_short_reserve(void)
{
    static const pn_test_order orders[2] = {PN_TEST_ITEMS_SHUFFLED, PN_TEST_CHUNKS_UNEVEN};
    pn_test_scene sp;
    scene s;
    uint32_t i, which, o;
    const uint32_t n = 5000; /* above PN_BVH_REF_PAR_MIN: the ranges handed out */
    REQUIRE(pn_test_scene_load(&sp, "spheres") == 0);
    s.pos = (float *)malloc((size_t)n * 9u * sizeof(float));
    s.idx = (uint32_t *)malloc((size_t)n * 3u * sizeof(uint32_t));
    REQUIRE(s.pos && s.idx);
    s.tris = s.verts = 0;
    for (i = 0; i < n; i++) {
        double c[3] = {rnd_in(-3, 3), rnd_in(0.8, 1.8), rnd_in(-3, 3)};
        add_sliver(&s, c, rnd_in(0.5, 3), rnd_in(0.002, 0.02));
    }
    for (which = 0; which < 2u; which++) {
        const float *pos = which ? sp.mesh.positions : s.pos;
        const uint32_t *idx = which ? sp.mesh.indices : s.idx;
        uint32_t verts = which ? sp.mesh.vertex_count : s.verts, tris = which ? sp.mesh.triangle_count : s.tris;
        pn_test_host h0, h1;
        pn_context *a = open_ctx(&h0, tris, tris), *b; /* no split reference */
        if (!a) break;
        REQUIRE(pn_scene_set(a, pos, verts, idx, tris) == PN_OK);
        CHECK(a->bvh_refs == tris);
        if (which == 0u) {
            /* the default reserve splits most of these slivers */
            b = open_ctx(&h1, tris, 0u);
            REQUIRE(b);
            CHECK(pn_scene_set(b, pos, verts, idx, tris) == PN_OK);
            CHECK_MSG(b->bvh_refs > tris + tris / 2u, "%u references for %u slivers", b->bvh_refs, tris);
            pn_test_close(&h1);
        }
        for (o = 0; o < 3u; o++) {
            pn_test_schedule sc;
            memset(&sc, 0, sizeof(sc));
            /* slivers: a reserve of 1 (cap 1 would take about 5000); spheres: the default */
            b = open_ctx(&h1, tris, which ? 0u : tris + 1u);
            if (!b) break;
            if (o < 2u) {
                sc.order = orders[o];
                pn_set_parallel_for(b, pn_test_parallel_for, &sc);
            }
            CHECK(pn_scene_set(b, pos, verts, idx, tris) == PN_OK);
            CHECK_MSG(a->bvh_nodes == b->bvh_nodes && a->bvh_refs == b->bvh_refs && a->bvh_wide == b->bvh_wide &&
                          memcmp(a->tri_index, b->tri_index, (size_t)a->bvh_refs * 4u) == 0 &&
                          memcmp(a->raster_index, b->raster_index, (size_t)a->bvh_tris * 4u) == 0 &&
                          memcmp(a->wnodes, b->wnodes, (size_t)a->bvh_wide * sizeof(pn_kbvh4)) == 0,
                      "%s, schedule %u: another tree than without splitting (%u references)",
                      which ? "spheres" : "slivers", o, b->bvh_refs);
            pn_test_close(&h1);
        }
        pn_test_close(&h0);
    }
    free_scene(&s);
    pn_test_scene_free(&sp);
}

/* A tree built to be deep (issue 50): 48 small squares at x = 4 * 0.5^i along a line toward
 * the light's axis, each a tenth of its distance across, over a floor, under square's light:
 * the binned SAH can only peel the farthest few off at each level (every other centroid
 * falls into the first bins), so the tree is a chain (depth 20 or more, where a balanced
 * tree of its 98 triangles would be 6 deep). Built as is, and again with the builder's
 * depth bound (PN_BVH_DEPTH_MAX, 41 at the default stack: a real scene seldom reaches it)
 * lowered to 10 so that it acts: the tree stays within it, the wide tree's walks within
 * PN_BVH_STACK (check_wide), and every algorithm walks it to the bottom without losing a
 * stack entry and renders the same bytes over both trees (a tree changes which triangles
 * are tested, never a result), the exact ones the reference's. */
static void test_deep_tree(void)
{
    enum { NEST = 48 };
    pn_test_scene sq;
    scene s;
    pn_test_host h;
    pn_context *ctx;
    pn_stats st;
    uint32_t a, i, pass, leaves, built = pn_build_info();
    size_t npix = (size_t)FRAME_W * FRAME_H;
    float *vis = (float *)malloc(npix * sizeof(float) * PN_ALGO_COUNT);
    REQUIRE(vis);
    REQUIRE(pn_test_scene_load(&sq, "square") == 0);
    s.pos = (float *)malloc((size_t)(NEST + 1u) * 18u * sizeof(float));
    s.idx = (uint32_t *)malloc((size_t)(NEST + 1u) * 6u * sizeof(uint32_t));
    REQUIRE(s.pos && s.idx);
    s.tris = s.verts = 0;
    for (i = 0; i <= NEST; i++) {
        double x = i < NEST ? 4.0 * pow(0.5, (double)i) : 0.0, r = i < NEST ? 0.05 * x : 6.0;
        double y = i < NEST ? 1.0 : 0.0;
        double t0[9] = {x - r, y, -r, x - r, y, r, x + r, y, r}, t1[9] = {x - r, y, -r, x + r, y, r, x + r, y, -r};
        add_tri(&s, t0);
        add_tri(&s, t1);
    }
    ctx = open_ctx(&h, s.tris, 0);
    REQUIRE(ctx);
    for (pass = 0; pass < 2u; pass++) {
        if (pass == 1u) ctx->bvh_depth_max = 10u;
        CHECK(pn_scene_set(ctx, s.pos, s.verts, s.idx, s.tris) == PN_OK);
        CHECK(pn_get_stats(ctx, &st) == PN_OK);
        fprintf(stderr, "deep tree: %u triangles, depth %u (bound %u, stack %u)\n", s.tris, st.bvh_depth,
                ctx->bvh_depth_max, (unsigned)PN_BVH_STACK);
        if (pass == 0u)
            CHECK_MSG(st.bvh_depth >= 20u && st.bvh_depth <= PN_BVH_DEPTH_MAX, "depth %u: not a deep tree, or too deep",
                      st.bvh_depth);
        else
            CHECK_MSG(st.bvh_depth == 10u, "depth %u with the bound at 10", st.bvh_depth);
        free(check_wide(ctx, &leaves));
        for (a = 0; a < PN_ALGO_COUNT; a++) {
            pn_frame_options opt;
            pn_frame fr;
            pn_status rs;
            if (!(built & (1u << a))) continue;
            pn_test_frame_opts(&opt, FRAME_W, FRAME_H, a, sq.eps, 0u);
            rs = pn_render(ctx, &sq.camera, &sq.light, &opt, &fr);
            CHECK_MSG(rs == PN_OK, "deep tree %s: %s", pn_algo_name((pn_algo)a), pn_last_error(ctx));
            if (rs != PN_OK) continue;
            if (pass == 0u) memcpy(vis + a * npix, fr.visibility, npix * sizeof(float));
            else
                CHECK_MSG(memcmp(vis + a * npix, fr.visibility, npix * sizeof(float)) == 0,
                          "deep tree %s: other bytes over the bounded tree", pn_algo_name((pn_algo)a));
            if (((pn_algo)a == PN_ALGO_GEARS || (pn_algo)a == PN_ALGO_RAYTRACE) && (built & (1u << PN_ALGO_REFERENCE)))
                CHECK_MSG(memcmp(vis + PN_ALGO_REFERENCE * npix, fr.visibility, npix * sizeof(float)) == 0,
                          "deep tree %s: not the reference's bytes", pn_algo_name((pn_algo)a));
        }
    }
    pn_test_close(&h);
    free_scene(&s);
    pn_test_scene_free(&sq);
    free(vis);
}

static void test_limits(void)
{
    pn_limits lim;
    size_t bytes, bytes_split, bytes_none;
    memset(&lim, 0, sizeof(lim));
    lim.max_triangles = 100;
    lim.max_width = 8;
    lim.max_height = 8;
    lim.bvh_refs = 99;
    CHECK(pn_arena_size(&lim, &bytes) == PN_E_LIMIT);
    lim.bvh_refs = (1u << 26) + 1u;
    CHECK(pn_arena_size(&lim, &bytes) == PN_E_LIMIT);
    /* at most 100 + min(PN_BVH_SPLIT_REFS, 15 x 100); PN_ARENA_BYTES_MAX plus
     * PN_BVH_SPLIT_REF_BYTES a split reference bounds every context */
    lim.bvh_refs = 101u + (uint32_t)PN_BVH_SPLIT_EXTRA(100u);
    CHECK(pn_arena_size(&lim, &bytes) == PN_E_LIMIT);
    lim.bvh_refs -= 1u;
    CHECK(pn_arena_size(&lim, &bytes) == PN_OK &&
          bytes <= PN_ARENA_BYTES_MAX(100, 8, 8) + PN_BVH_SPLIT_EXTRA(100u) * PN_BVH_SPLIT_REF_BYTES);
    lim.bvh_refs = 100;
    CHECK(pn_arena_size(&lim, &bytes_none) == PN_OK);
    {
        /* The default (0) reserves no split reference: the same arena as 100. */
        size_t bytes_default;
        lim.bvh_refs = 0;
        CHECK(pn_arena_size(&lim, &bytes_default) == PN_OK && bytes_default == bytes_none);
        lim.bvh_refs = 100;
    }
    lim.bvh_refs = PN_BVH_SPLIT_REFS >= 1000u && PN_BVH_SPLIT_DEPTH >= 4u ? 1100u : 100u;
    CHECK(pn_arena_size(&lim, &bytes_split) == PN_OK);
    /* 1000 references more: a third of a wide node and an index entry each (less what the
     * pools' alignment padding absorbs, under PN_ARENA_ALIGN a pool) */
    CHECK_MSG(bytes_split + 3u * PN_ARENA_ALIGN >= bytes_none + (lim.bvh_refs - 100u) * 46u, "%zu vs %zu", bytes_split,
              bytes_none);
    lim.bvh_refs = 0;
    CHECK(pn_arena_size(&lim, &bytes) == PN_OK);
    CHECK(bytes <= PN_ARENA_BYTES_MAX(100, 8, 8));
    /* a reserve far below what the slivers want: the deepest cap that fits, never more */
    {
        scene s;
        pn_test_host h;
        pn_context *ctx;
        pn_stats st;
        make_mixed(&s, 1000);
        ctx = open_ctx(&h, s.tris, s.tris + 37u);
        if (ctx) {
            CHECK(pn_scene_set(ctx, s.pos, s.verts, s.idx, s.tris) == PN_OK);
            CHECK(pn_get_stats(ctx, &st) == PN_OK && st.bvh_refs <= s.tris + 37u && st.bvh_refs == ctx->bvh_refs);
            check_tree(ctx, &s, 0);
            pn_test_close(&h);
        }
        free_scene(&s);
    }
}

/* The build in parallel (src/pn_bvh_build.c: subtrees as work items, a large node's passes
 * in chunks): the same tree, byte for byte (the wide tree, its box, leaf and raster
 * orders), whatever the schedule, on a scene small enough for one work item, on spheres
 * (subtrees), and on 90,000 mixed triangles split by the default reserve (chunked passes
 * over more than 65,536 references); and the serial loop's tree is the tree without
 * splitting's for a scene that split nothing. */
static void test_parallel_same_tree(void)
{
    static const pn_test_order orders[4] = {PN_TEST_ITEMS_FORWARD, PN_TEST_ITEMS_BACKWARD, PN_TEST_ITEMS_SHUFFLED,
                                            PN_TEST_CHUNKS_UNEVEN};
    pn_test_scene sp;
    scene mixed;
    uint32_t which;
    REQUIRE(pn_test_scene_load(&sp, "spheres") == 0);
    make_mixed(&mixed, 90000u);
    for (which = 0; which < 3u; which++) {
        const float *pos = which == 2u ? mixed.pos : sp.mesh.positions;
        const uint32_t *idx = which == 2u ? mixed.idx : sp.mesh.indices;
        uint32_t verts = which == 2u ? mixed.verts : sp.mesh.vertex_count;
        uint32_t tris = which == 0u ? 500u : which == 2u ? mixed.tris : sp.mesh.triangle_count;
        pn_test_host h0, h1;
        pn_context *a = open_ctx(&h0, tris, 0u), *b;
        uint32_t o;
        if (!a) break;
        REQUIRE(pn_scene_set(a, pos, verts, idx, tris) == PN_OK);
        if (which == 2u) CHECK_MSG(a->bvh_refs > 65536u, "%u references: the chunked passes are not reached", a->bvh_refs);
        for (o = 0; o < 4u; o++) {
            pn_test_schedule sc;
            memset(&sc, 0, sizeof(sc));
            sc.order = orders[o];
            b = open_ctx(&h1, tris, 0u);
            if (!b) break;
            pn_set_parallel_for(b, pn_test_parallel_for, &sc);
            CHECK(pn_scene_set(b, pos, verts, idx, tris) == PN_OK);
            CHECK_MSG(a->bvh_nodes == b->bvh_nodes && a->bvh_refs == b->bvh_refs && a->bvh_wide == b->bvh_wide &&
                          a->bvh_depth == b->bvh_depth &&
                          memcmp(a->tri_index, b->tri_index, (size_t)a->bvh_refs * 4u) == 0 &&
                          memcmp(a->raster_index, b->raster_index, (size_t)a->bvh_tris * 4u) == 0 &&
                          memcmp(a->wnodes, b->wnodes, (size_t)a->bvh_wide * sizeof(pn_kbvh4)) == 0,
                      "scene %u, schedule %u: another tree (%u nodes against %u)", which, o, b->bvh_nodes,
                      a->bvh_nodes);
            CHECK_MSG(which == 0u || sc.jobs > 0u, "scene %u: the build handed no work to the parallel-for", which);
            pn_test_close(&h1);
        }
        pn_test_close(&h0);
    }
    free_scene(&mixed);
    pn_test_scene_free(&sp);
}


int main(void)
{
    if (PN_BVH_SPLIT_DEPTH == 0u || PN_BVH_SPLIT_REFS == 0u) {
        /* nothing splits in this configuration: only the limits apply */
        RUN(test_limits);
        return pn_test_summary();
    }
    RUN(test_containment);
    RUN(test_frames_thin);
    RUN(test_frames_slivers);
    RUN(test_deep_tree);
    RUN(test_limits);
    RUN(test_parallel_same_tree);
    RUN(test_refs_short_reserve);
    return pn_test_summary();
}
