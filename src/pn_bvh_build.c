/* pn_bvh_build.c - binned SAH BVH over triangle references, built top-down without
 * recursion as a binary tree in the frame region, then folded into the four-wide tree the
 * context keeps and the walks read (pn_bvh_fold; kernels/pn_ktypes.h pn_kbvh4).
 *
 * References. Every non-degenerate triangle is one reference with its box, or, when its
 * box is far larger than itself, several (early split clipping, Ernst and Greiner 2007;
 * config.h PN_BVH_SPLIT_DEPTH, PN_BVH_SPLIT_REFS): its box is halved along the longest
 * axis while the two halves' boxes of the triangle's part in them have under 5/8 of the
 * parent's surface area. A leaf lists triangle ids (tri_index), a split triangle's in
 * several leaves and marked PN_REF_SPLIT there (its leaf box need not hold its vertices,
 * so the ray filter bounds it by its own box); the walks test whole triangles, so only
 * which boxes a ray or a pyramid meets changes, never a result. A part's box must hold
 * the real part: see pn_part_box.
 *
 * Work list: after a split the larger child is pushed and the smaller one is built next,
 * so every pushed entry at least halves the remaining count: the list never holds more
 * than log2(N) + 1 entries (32 is plenty). Leaves hold at least PN_BVH_LEAF_MIN (2)
 * references, which bounds the wide tree at a third of a node a reference. Depth: where
 * the median splits a node still needs would take the tree below PN_BVH_DEPTH_MAX, the
 * split is the object median (an iterative quickselect), which halves the count at each
 * level, so the tree never passes that depth (2^26 references need 25 levels:
 * check_config.h keeps it above) and no walk's stack can overflow (pn_bvh_fold). Node 0
 * is the root; children are allocated in pairs, so at most 2R - 1 nodes exist for R
 * references, R - 1 with leaves of two or more. Everything is deterministic: same
 * triangles, same tree.
 *
 * In parallel (pn_set_parallel_for), with the same tree: a node's split depends on its own
 * references alone (pn_bvh_node), so the top of the tree is split on the calling thread,
 * a large node's two passes (bounds, bins) in chunks whose partials merge exactly (min, max
 * and counts), and the subtrees below it are built as work items, each in its own range of
 * nodes, closed up afterwards (pn_bvh_build). The references move with their indices, so a
 * node's references are contiguous in memory; a child's bounds come from its parent's bins
 * and partition, not from another pass. Only the nodes' numbering differs from a build in
 * one piece, and it is the same for any schedule (test_bvh). */
#include <string.h>

#include "pn_internal.h"
#include "pn_kmath.h"

typedef struct pn_box {
    float lo[3], hi[3];
} pn_box;

typedef char pn_bnode_size_check[sizeof(pn_bnode) == PN_BVH_NODE_BYTES ? 1 : -1];

static void pn_box_empty(pn_box *b)
{
    int a;
    for (a = 0; a < 3; a++) {
        b->lo[a] = PN_KINF;
        b->hi[a] = -PN_KINF;
    }
}

static void pn_box_point(pn_box *b, float x, float y, float z)
{
    b->lo[0] = pn_kminf(b->lo[0], x);
    b->lo[1] = pn_kminf(b->lo[1], y);
    b->lo[2] = pn_kminf(b->lo[2], z);
    b->hi[0] = pn_kmaxf(b->hi[0], x);
    b->hi[1] = pn_kmaxf(b->hi[1], y);
    b->hi[2] = pn_kmaxf(b->hi[2], z);
}

static void pn_box_join(pn_box *b, const pn_box *o)
{
    int a;
    for (a = 0; a < 3; a++) {
        b->lo[a] = pn_kminf(b->lo[a], o->lo[a]);
        b->hi[a] = pn_kmaxf(b->hi[a], o->hi[a]);
    }
}

/* A whole triangle's box (p: its 9 floats): a reference's box when it is not split, and
 * the start of a split. pn_bvh_refit reuses it so that a refitted leaf's box has the bits a
 * build of the same tree gives. */
static void pn_tri_box(const float *p, pn_box *b)
{
    pn_box_empty(b);
    pn_box_point(b, p[0], p[1], p[2]);
    pn_box_point(b, p[3], p[4], p[5]);
    pn_box_point(b, p[6], p[7], p[8]);
}

static float pn_box_area(const pn_box *b)
{
    float dx = b->hi[0] - b->lo[0], dy = b->hi[1] - b->lo[1], dz = b->hi[2] - b->lo[2];
    if (!(dx >= 0.0f)) return 0.0f;
    return dx * dy + dy * dz + dz * dx;
}

/* A reference: its box, the point it is binned and sorted by (the triangle's centroid when
 * whole, the part's box centre when split), its triangle. PN_BVH_REF_BYTES each. */
typedef struct pn_bref {
    float lo[3], hi[3], c[3];
    uint32_t tri;
} pn_bref;

typedef char pn_bref_size_check[sizeof(pn_bref) == PN_BVH_REF_BYTES ? 1 : -1];

/* A node's bounds when its parent's split already gave them (known): its box and its
 * references' centroid box; out of pn_bvh_node, the two children's (b[0], b[1] the first
 * child's, b[2], b[3] the second's) when known. */
typedef struct pn_bounds {
    pn_box b[4];
    int known;
} pn_bounds;

static void pn_ref_box(const pn_bref *refs, uint32_t r, pn_box *b)
{
    int a;
    for (a = 0; a < 3; a++) {
        b->lo[a] = refs[r].lo[a];
        b->hi[a] = refs[r].hi[a];
    }
}

static float pn_centroid(const pn_bref *refs, uint32_t r, int axis) { return refs[r].c[axis]; }

/* Total order for the median split: centroid, then reference index (ix: the references are
 * kept in the order of ix, so position a holds reference ix[a]). */
static int pn_key_less(const pn_bref *refs, const uint32_t *ix, int axis, uint32_t a, uint32_t b)
{
    float ca = pn_centroid(refs, a, axis), cb = pn_centroid(refs, b, axis);
    if (ca != cb) return ca < cb;
    return ix[a] < ix[b];
}

/* The box of the part of triangle p (9 floats) inside the region [rlo, rhi], widened by m,
 * then cut back to the region; 0 when the part is empty. Sutherland-Hodgman against the
 * region's six planes each moved out by m (float; a polygon of at most 9 vertices).
 * Why it holds the real part: m is 2^-16 of the triangle's largest coordinate magnitude
 * plus its extent, every computed vertex is a convex combination of points within a few
 * rounding errors (2^-24 relative each, six clips) of the real clipped polygon's, far
 * below m; so every real point of the triangle in the region, at least m inside each
 * moved plane, survives every clip within that error, and the box widened by m holds
 * it. Cutting back to the region is exact (the region's bounds are floats). */
static int pn_part_box(const float *p, const float *rlo, const float *rhi, float m, pn_box *out)
{
    float poly[2][9][3];
    uint32_t n = 3, i, c;
    int src = 0, a;
    for (i = 0; i < 3; i++)
        for (a = 0; a < 3; a++) poly[0][i][a] = p[i * 3u + (uint32_t)a];
    for (c = 0; c < 6u; c++) {
        int ax = (int)(c >> 1), hi = (int)(c & 1u), dst = src ^ 1;
        float plane = hi ? rhi[ax] + m : rlo[ax] - m;
        uint32_t k = 0, outside = 0;
        for (i = 0; i < n; i++) outside += hi ? poly[src][i][ax] > plane : poly[src][i][ax] < plane;
        if (outside == 0u) continue; /* all inside: this plane cuts nothing */
        for (i = 0; i < n; i++) {
            const float *P = poly[src][i], *Q = poly[src][i + 1u < n ? i + 1u : 0u];
            int pin = hi ? P[ax] <= plane : P[ax] >= plane, qin = hi ? Q[ax] <= plane : Q[ax] >= plane;
            if (pin) {
                for (a = 0; a < 3; a++) poly[dst][k][a] = P[a];
                k++;
            }
            if (pin != qin) {
                float t = (plane - P[ax]) / (Q[ax] - P[ax]);
                for (a = 0; a < 3; a++) poly[dst][k][a] = P[a] + t * (Q[a] - P[a]);
                poly[dst][k][ax] = plane;
                k++;
            }
        }
        n = k;
        src = dst;
        if (n == 0u) return 0;
    }
    pn_box_empty(out);
    for (i = 0; i < n; i++) pn_box_point(out, poly[src][i][0], poly[src][i][1], poly[src][i][2]);
    for (a = 0; a < 3; a++) {
        out->lo[a] = pn_kmaxf(out->lo[a] - m, rlo[a]);
        out->hi[a] = pn_kminf(out->hi[a] + m, rhi[a]);
        if (!(out->lo[a] <= out->hi[a])) return 0;
    }
    return 1;
}

/* Whether triangle p (9 floats) with box b may be split: only slivers, a box of surface
 * area over four times the triangle's (twice its area is |cross|); a compact triangle's
 * halves never shrink enough. Far from float's range only (mag: its largest coordinate
 * magnitude; the split's margins must not overflow). */
static int pn_tri_sliver(const float *p, const pn_box *b, float mag)
{
    pn_v3 A = pn_v3_make(p[0], p[1], p[2]), B = pn_v3_make(p[3], p[4], p[5]), C = pn_v3_make(p[6], p[7], p[8]);
    pn_v3 n = pn_v3_cross(pn_v3_sub(B, A), pn_v3_sub(C, A));
    return mag < 1e18f && pn_box_area(b) > 4.0f * pn_ksqrt(pn_v3_dot(n, n));
}

/* Splits triangle t: the parts at most `cap` halvings deep. Counts, for every depth d up
 * to cap, the references a cap of d would give (into count[d], when count is not NULL;
 * count[d] for d above cap gets this cap's), and writes the references of this cap from refs[*r] on, those below index `room` only
 * (*r counts them all). Depth first over an explicit stack (at most depth + 1 entries). */
static void pn_split_tri(const float *tris, uint32_t t, uint32_t cap, uint64_t *count, pn_bref *refs, uint32_t *r,
                         uint32_t room)
{
    struct {
        pn_box b;
        uint32_t depth;
    } st[PN_BVH_SPLIT_DEPTH + 2u];
    const float *p = tris + (size_t)t * 9u;
    uint32_t sp = 1, d;
    float mag = 0.0f, ext = 0.0f, m;
    int a;
    pn_tri_box(p, &st[0].b);
    st[0].depth = 0;
    for (a = 0; a < 3; a++) {
        mag = pn_kmaxf(mag, pn_kmaxf(-st[0].b.lo[a], st[0].b.hi[a]));
        ext = pn_kmaxf(ext, st[0].b.hi[a] - st[0].b.lo[a]);
    }
    m = (mag + ext) * (1.0f / 65536.0f);
    if (cap > 0u && !pn_tri_sliver(p, &st[0].b, mag)) cap = 0;
    while (sp > 0u) {
        pn_box cur = st[--sp].b, L, R;
        uint32_t dep = st[sp].depth;
        int split = 0;
        if (dep < cap) {
            int ax = 0;
            float mid, lhi[3], rlo[3];
            for (a = 1; a < 3; a++)
                if (cur.hi[a] - cur.lo[a] > cur.hi[ax] - cur.lo[ax]) ax = a;
            mid = cur.lo[ax] + (cur.hi[ax] - cur.lo[ax]) * 0.5f;
            for (a = 0; a < 3; a++) {
                lhi[a] = cur.hi[a];
                rlo[a] = cur.lo[a];
            }
            lhi[ax] = mid;
            rlo[ax] = mid;
            if (mid > cur.lo[ax] && mid < cur.hi[ax] && pn_part_box(p, cur.lo, lhi, m, &L) &&
                pn_part_box(p, rlo, cur.hi, m, &R) &&
                pn_box_area(&L) + pn_box_area(&R) < 0.625f * pn_box_area(&cur))
                split = 1;
        }
        if (count) {
            /* a leaf here is one reference for every cap from dep on; a split node is one
             * for the cap dep itself */
            if (split)
                count[dep]++;
            else
                for (d = dep; d <= PN_BVH_SPLIT_DEPTH; d++) count[d]++;
        }
        if (!split && *r >= room) {
            (*r)++; /* counted, not written: the caller splits everything less deep */
            continue;
        }
        if (split) {
            st[sp].b = R;
            st[sp++].depth = dep + 1u;
            st[sp].b = L;
            st[sp++].depth = dep + 1u;
        } else {
            pn_bref *o = refs + (*r)++;
            for (a = 0; a < 3; a++) {
                o->lo[a] = cur.lo[a];
                o->hi[a] = cur.hi[a];
                o->c[a] = cur.lo[a] + (cur.hi[a] - cur.lo[a]) * 0.5f;
            }
            if (dep == 0u)
                for (a = 0; a < 3; a++) o->c[a] = (p[a] + p[3 + a] + p[6 + a]) * (1.0f / 3.0f);
            o->tri = t | (dep > 0u ? PN_REF_SPLIT : 0u); /* a part of a split triangle */
        }
    }
}

/* The references themselves move with their indices, so that a node's references are
 * contiguous in memory at every level (the passes read them in order). */
static void pn_swap(pn_bref *refs, uint32_t *ix, uint32_t a, uint32_t b)
{
    uint32_t t = ix[a];
    pn_bref r = refs[a];
    ix[a] = ix[b];
    ix[b] = t;
    refs[a] = refs[b];
    refs[b] = r;
}

/* Places the element of rank kth (within [lo, hi]) at kth, smaller ones before it. */
static void pn_select(pn_bref *refs, uint32_t *ix, int axis, uint32_t lo, uint32_t hi, uint32_t kth)
{
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2u, i, j;
        /* median of three to hi as pivot */
        if (pn_key_less(refs, ix, axis, mid, lo)) pn_swap(refs, ix, mid, lo);
        if (pn_key_less(refs, ix, axis, hi, lo)) pn_swap(refs, ix, hi, lo);
        if (pn_key_less(refs, ix, axis, mid, hi)) pn_swap(refs, ix, mid, hi);
        i = lo;
        for (j = lo; j < hi; j++)
            if (pn_key_less(refs, ix, axis, j, hi)) pn_swap(refs, ix, i++, j);
        pn_swap(refs, ix, i, hi);
        if (i == kth) return;
        if (kth < i)
            hi = i - 1u;
        else
            lo = i + 1u;
    }
}

typedef struct pn_work {
    uint32_t node, depth;
    int known;      /* box and cbox hold the node's bounds (pn_bounds) */
    pn_box box, cbox;
} pn_work;

/* Whether the context splits references (limits.bvh_refs above max_triangles). */
static int pn_bvh_splits(const pn_context *ctx)
{
    return PN_BVH_SPLIT_DEPTH > 0u && pn_bvh_refs_max(&ctx->limits) > ctx->limits.max_triangles;
}

/* The references of the scene into refs (the frame region): every triangle split as deep
 * as the reserve allows (the same cap for all: the deepest whose count fits).
 *
 * First, in parallel (pn_run) over PN_BVH_REF_CHUNKS fixed ranges of triangles (they
 * depend on the scene alone), the slivers (pn_tri_sliver) are marked in ix (free until
 * the tree is built) and counted per range. When there are more of them than the
 * reserve, their boxes are halved once, again in parallel, and a sliver whose box was not
 * split unmarked: if cap 1 then passes the reserve (the dragon's slivers), or no box was
 * split, every triangle is one reference, as when there is no sliver (most scenes); the
 * ranges write them in parallel, each from where the ranges before it end (the per-range
 * counts sit in the subtrees' work items, unused until the tree is built).
 *
 * Otherwise one pass in order splits to the deepest cap still possible, counting every
 * shallower cap's references and writing while they fit; the cap drops as soon as its
 * count, plus one reference for every triangle still to come, passes the reserve (its
 * final count would), so a scene that wants far more than the reserve stops paying for
 * deep splits early, and the cap is the one a full count would choose. Only when it
 * dropped, a second pass writes it. Both take an unmarked triangle without its split
 * test. The same references, in the same order, either way. */
#define PN_BVH_REF_CHUNKS 32u
typedef struct pn_bvh_refjob {
    const pn_context *ctx;
    pn_bref *refs;
    uint32_t *sliver;     /* per triangle: 1 when its box may be split */
    uint32_t (*count)[3]; /* per range: triangles, slivers (pass 0) or references at cap 1 (pass 1) */
    uint32_t split, pass, most; /* split: splits allowed; pass 0: mark, 1: halve once, 2: write */
} pn_bvh_refjob;

/* Below this many triangles the pass in order alone (the ranges' extra pass and their
 * hand-out cost more than they save: 0.2 ms on a scene of 4 triangles). */
#define PN_BVH_REF_PAR_MIN 4096u

typedef char pn_bvh_refjob_bytes[PN_BVH_REF_CHUNKS * 12u <= PN_BVH_TASK_BYTES ? 1 : -1];

static void pn_bvh_refs_fn(void *task, uint32_t begin, uint32_t end)
{
    const pn_bvh_refjob *j = (const pn_bvh_refjob *)task;
    const pn_context *ctx = j->ctx;
    const float *tris = ctx->tris;
    uint32_t k, t;
    for (k = begin; k < end; k++) {
        uint32_t t0 = (uint32_t)((uint64_t)ctx->tri_count * k / PN_BVH_REF_CHUNKS);
        uint32_t t1 = (uint32_t)((uint64_t)ctx->tri_count * (k + 1u) / PN_BVH_REF_CHUNKS), r = 0, n = 0, m = 0;
        if (j->pass == 2u) {
            /* one reference a triangle, from the end of the ranges before this one */
            for (t = 0; t < k; t++) r += j->count[t][0];
            for (t = t0; t < t1; t++)
                if (!(ctx->flags[t] & PN_TRI_DEGENERATE)) pn_split_tri(tris, t, 0u, NULL, j->refs, &r, j->most);
            continue;
        }
        for (t = t0; t < t1; t++) {
            if (ctx->flags[t] & PN_TRI_DEGENERATE) continue;
            n++;
            if (j->pass == 0u) {
                pn_box b;
                float mag = 0.0f;
                int a;
                pn_tri_box(tris + (size_t)t * 9u, &b);
                for (a = 0; a < 3; a++) mag = pn_kmaxf(mag, pn_kmaxf(-b.lo[a], b.hi[a]));
                j->sliver[t] = j->split && pn_tri_sliver(tris + (size_t)t * 9u, &b, mag);
                m += j->sliver[t];
            } else if (j->sliver[t]) {
                uint64_t count[PN_BVH_SPLIT_DEPTH + 1u] = {0};
                /* room 0: counted, nothing written; a split box: two references at cap 1 */
                pn_split_tri(tris, t, 1u, count, j->refs, &r, 0u);
                j->sliver[t] = count[1] > 1u;
                m += (uint32_t)count[1] - 1u;
            }
        }
        j->count[k][0] = n;
        j->count[k][j->pass + 1u] = m;
    }
}

static uint32_t pn_bvh_refs(pn_context *ctx, pn_bref *refs, uint32_t *sliver, void *scratch, uint32_t *tris_out)
{
    uint64_t count[PN_BVH_SPLIT_DEPTH + 1u], most = pn_bvh_refs_max(&ctx->limits), n = 0, m = 0;
    uint32_t t, r = 0, d, first_cap, cap, rest = ctx->tri_count - ctx->degenerate, k, marked;
    pn_bvh_refjob j;
    first_cap = cap = pn_bvh_splits(ctx) ? PN_BVH_SPLIT_DEPTH : 0u;
    *tris_out = rest;
    j.ctx = ctx;
    j.refs = refs;
    j.sliver = sliver;
    j.count = (uint32_t(*)[3])scratch;
    j.split = cap > 0u;
    j.most = (uint32_t)most;
    j.pass = 0;
    /* the ranges mark the slivers, and may write every reference; small scenes: the pass
     * in order alone, every triangle's split tested */
    marked = ctx->tri_count >= PN_BVH_REF_PAR_MIN;
    if (marked) {
        pn_run(ctx, PN_BVH_REF_CHUNKS, pn_bvh_refs_fn, &j);
        for (k = 0; k < PN_BVH_REF_CHUNKS; k++) {
            n += j.count[k][0];
            m += j.count[k][1];
        }
        if (m > most - n) { /* more slivers than the reserve: does cap 1 fit? */
            j.pass = 1;
            pn_run(ctx, PN_BVH_REF_CHUNKS, pn_bvh_refs_fn, &j);
            for (m = 0, k = 0; k < PN_BVH_REF_CHUNKS; k++) m += j.count[k][2];
            if (m > most - n) m = 0; /* cap 0 */
        }
        if (m == 0u) { /* one reference a triangle (max_triangles <= most) */
            j.pass = 2;
            pn_run(ctx, PN_BVH_REF_CHUNKS, pn_bvh_refs_fn, &j);
            return (uint32_t)n;
        }
    }
    for (d = 0; d <= PN_BVH_SPLIT_DEPTH; d++) count[d] = 0;
    for (t = 0; t < ctx->tri_count; t++)
        if (!(ctx->flags[t] & PN_TRI_DEGENERATE)) {
            rest--;
            pn_split_tri(ctx->tris, t, marked && !sliver[t] ? 0u : cap, count, refs, &r, (uint32_t)most);
            /* count[0] + rest = the non-degenerate triangles <= max_triangles <= most: the
             * loop ends at 0 at the latest */
            while (count[cap] + rest > most) cap--;
        }
    if (cap == first_cap) return r; /* = count[cap] <= most, all written */
    r = 0;
    for (t = 0; t < ctx->tri_count; t++)
        if (!(ctx->flags[t] & PN_TRI_DEGENERATE))
            pn_split_tri(ctx->tris, t, marked && !sliver[t] ? 0u : cap, NULL, refs, &r, (uint32_t)most);
    return r;
}

static float pn_node_area(const pn_bnode *nd)
{
    float dx = nd->bmax[0] - nd->bmin[0], dy = nd->bmax[1] - nd->bmin[1], dz = nd->bmax[2] - nd->bmin[2];
    return dx * dy + dy * dz + dz * dx;
}

/* The children of binary interior node b, opened up to four, by one of two rules. Greedy
 * (the walks' better tree: callgrind, per-sample ray tracing on the bunny 3.88 G -> 3.59 G
 * instructions against breadth first): while there are fewer than four, the interior child
 * with the largest box (the first of equals) is replaced in place by its two children.
 * Breadth first (the bound on the walk stack, pn_bvh_fold): both of b's children when
 * both are interior; else the interior one, and then the larger interior one of its two.
 * Either keeps the tree's left-to-right order, and stops short of four only when every
 * child is a leaf. */
static uint32_t pn_fold_children(const pn_bnode *nodes, uint32_t b, int greedy, uint32_t *ch)
{
    uint32_t n = 2u, i, best, from = 0u;
    ch[0] = nodes[b].first;
    ch[1] = nodes[b].first + 1u;
    if (!greedy && nodes[ch[0]].count == 0u && nodes[ch[1]].count == 0u) {
        ch[2] = nodes[ch[1]].first;
        ch[3] = ch[2] + 1u;
        ch[1] = nodes[ch[0]].first + 1u;
        ch[0] = nodes[ch[0]].first;
        return 4u;
    }
    while (n < 4u) {
        float ba = -1.0f;
        best = n;
        for (i = from; i < n; i++)
            if (nodes[ch[i]].count == 0u && pn_node_area(nodes + ch[i]) > ba) {
                ba = pn_node_area(nodes + ch[i]);
                best = i;
            }
        if (best == n) break;
        for (i = n; i > best + 1u; i--) ch[i] = ch[i - 1u];
        ch[best + 1u] = nodes[ch[best]].first + 1u;
        ch[best] = nodes[ch[best]].first;
        n++;
        /* breadth first: after b's one interior child, only its two children */
        if (!greedy) from = best;
    }
    return n;
}

/* Walk-stack entries a path may leave pushed below a node of binary height h folded breadth
 * first, times two: 3 (h - 1) + 6 for h >= 1 (pn_bvh_fold), 0 for a leaf. */
static uint32_t pn_fold_room2(uint32_t h) { return h ? 3u * (h - 1u) + 6u : 0u; }

/* The four-wide tree (pn_kbvh4) over the binary one (nodes, root 0) into w, in
 * breadth-first order: the wide nodes themselves are the queue (pad0 names the binary
 * node a wide node folds, pad1 the walk-stack entries its path has pushed; both zeroed at
 * the end). height[b]: binary node b's height (edges to its deepest leaf), or NULL to fold
 * every node breadth first. Returns the count, or 0 when it would pass `room`; *need the
 * stack a walk needs: the largest sum over a root-to-leaf path of (children - 1), the
 * entries a walk leaves pushed, plus one.
 *
 * Count: with every leaf of at least two references (the builder's, pn_bvh_node) a tree of
 * R >= 2 references has L <= R / 2 leaves; a wide node of fewer than four children has
 * only leaves below it (either rule), so there are at most L / 2 of those, and counting
 * children (every node but the root is a child) gives at most (2L - 1) / 3 <= R / 3 wide
 * nodes (pn_bvh_wide_max).
 *
 * Stack. A node folded breadth first that a path goes on below pushes at most 3 entries
 * for the at least 2 binary levels the path crosses in it; the last node on a path pushes
 * at most 3; so below a node of height h a path pushes at most F(h) = 1.5 (h - 1) + 3
 * (pn_fold_room2 = 2F), and a tree of depth D <= PN_BVH_DEPTH_MAX (pn_bvh_node keeps to
 * it) needs F(D) + 1 <= PN_BVH_STACK. A greedy node may cross only one level for its 3
 * entries, so it is folded greedily only where p + 3 + F(h - 1) <= PN_BVH_STACK - 1 (p: the
 * path's entries above it), which leaves every child's subtree within the stack however
 * it is folded; elsewhere breadth first, whose children's subtrees fit as F(h) = 3 +
 * F(h - 2) does. At the root p + F(D) fits, so every path does: real scenes' trees, far
 * shallower than the bound, are folded greedily throughout. */
uint32_t pn_bvh_fold(const pn_bnode *nodes, const uint8_t *height, pn_kbvh4 *w, uint32_t room, uint32_t *need_out)
{
    uint32_t head = 0, tail = 1, need_max = 1, ch[4], n, c, a;
    w[0].pad0 = 0u;
    w[0].pad1 = 0u;
    while (head < tail) {
        pn_kbvh4 *wn = w + head++;
        uint32_t b = wn->pad0, need = wn->pad1;
        if (nodes[b].count != 0u || nodes[b].first == 0u) { /* the root is a leaf, or empty */
            ch[0] = b;
            n = nodes[b].count != 0u ? 1u : 0u;
        } else {
            int greedy = height && 2u * need + 6u + pn_fold_room2(height[b] - 1u) <= 2u * ((uint32_t)PN_BVH_STACK - 1u);
            n = pn_fold_children(nodes, b, greedy, ch);
        }
        need += n > 0u ? n - 1u : 0u;
        if (need + 1u > need_max) need_max = need + 1u;
        for (c = 0; c < 4u; c++) {
            for (a = 0; a < 3u; a++) {
                wn->lo[a][c] = c < n ? nodes[ch[c]].bmin[a] : 0.0f;
                wn->hi[a][c] = c < n ? nodes[ch[c]].bmax[a] : 0.0f;
            }
            wn->child[c] = 0u;
            if (c >= n) continue;
            if (nodes[ch[c]].count != 0u) {
                wn->child[c] = pn_w4_leaf_word(nodes[ch[c]].first, nodes[ch[c]].count);
            } else {
                if (tail >= room) return 0u;
                w[tail].pad0 = ch[c];
                w[tail].pad1 = need;
                wn->child[c] = tail++;
            }
        }
        wn->n = n;
    }
    for (c = 0; c < tail; c++) w[c].pad0 = w[c].pad1 = w[c].pad2 = 0u;
    *need_out = need_max;
    return tail;
}

/* The wide tree of the binary one (its n nodes; height: room for n bytes, where the nodes'
 * heights are written first). Children come after their parent, so one pass from the last
 * node down meets every child before its parent. */
static pn_status pn_bvh_widen(pn_context *ctx, const pn_bnode *nodes, uint32_t n, uint8_t *height)
{
    uint32_t need, i;
    for (i = n; i-- > 0u;) {
        uint32_t h0, h1;
        if (nodes[i].count != 0u || (i == 0u && nodes[0].first == 0u)) {
            height[i] = 0u;
            continue;
        }
        h0 = height[nodes[i].first];
        h1 = height[nodes[i].first + 1u];
        height[i] = (uint8_t)((h0 > h1 ? h0 : h1) + 1u);
    }
    ctx->bvh_wide = pn_bvh_fold(nodes, height, ctx->wnodes, pn_bvh_wide_max(pn_bvh_refs_max(&ctx->limits)), &need);
    if (ctx->bvh_wide == 0u) return pn_fail(ctx, PN_E_INTERNAL, "BVH fold: more wide nodes than the reserve");
    if (need > PN_BVH_STACK)
        return pn_fail(ctx, PN_E_INTERNAL, "BVH fold: a walk needs %u stack entries, PN_BVH_STACK is %u", need,
                       (uint32_t)PN_BVH_STACK);
    return PN_OK;
}

/* The top of the tree's large nodes bin in parallel: PN_BVH_CHUNKS ranges of a node's
 * references, each into its own partial bounds or bins (pn_bvh_part), merged in range
 * order. Min and max are exact and counts are integers, so the merged bins are the ones a
 * single pass gives, whatever the schedule. The partials live in the node pool's tail,
 * which the top of the tree does not reach (pn_bvh_par.room). */
#define PN_BVH_CHUNKS 16u
#define PN_BVH_PAR_MIN 65536u
typedef struct pn_bvh_part {
    pn_box box, cbox;
    pn_box bb[3][PN_BVH_BINS];
    uint32_t bc[3][PN_BVH_BINS];
} pn_bvh_part;

typedef struct pn_bvh_par {
    pn_context *ctx;
    pn_bvh_part *part; /* PN_BVH_CHUNKS of them at the node pool's end, and after them pre:
                          a large node's bounds and bins, merged (pn_bvh_large) */
    uint32_t room;     /* nodes below them: a node may use them while its split's children fit under */
} pn_bvh_par;

typedef struct pn_bvh_chunks {
    const pn_bref *refs;
    uint32_t first, count, bins; /* bins: 0 the node's bounds, 1 its bins */
    const pn_box *cbox;
    const float *scale;
    pn_bvh_part *part;
} pn_bvh_chunks;

/* The bins' scale per axis from the centroids' box (0: all centroids coincide on it, the
 * axis is not binned). */
static void pn_bin_scale(const pn_box *cbox, float *scale)
{
    int a;
    for (a = 0; a < 3; a++) {
        float ext = cbox->hi[a] - cbox->lo[a];
        scale[a] = ext > 0.0f ? (float)PN_BVH_BINS / ext : 0.0f;
    }
}

static void pn_bins_empty(pn_box bb[3][PN_BVH_BINS], uint32_t bc[3][PN_BVH_BINS])
{
    uint32_t a, b;
    for (a = 0; a < 3u; a++)
        for (b = 0; b < PN_BVH_BINS; b++) {
            pn_box_empty(&bb[a][b]);
            bc[a][b] = 0;
        }
}

/* References [from, to) into the bins bb, bc (scale[a] 0: axis a not binned). */
static void pn_bin_range(const pn_bref *refs, uint32_t from, uint32_t to, const pn_box *cbox,
                         const float *scale, pn_box bb[3][PN_BVH_BINS], uint32_t bc[3][PN_BVH_BINS])
{
    uint32_t i;
    int a;
    for (i = from; i < to; i++) {
        pn_box tb;
        pn_ref_box(refs, i, &tb);
        for (a = 0; a < 3; a++) {
            int32_t bin;
            if (scale[a] == 0.0f) continue;
            bin = pn_kfloor_clamp((pn_centroid(refs, i, a) - cbox->lo[a]) * scale[a], 0, (int32_t)PN_BVH_BINS - 1);
            pn_box_join(&bb[a][bin], &tb);
            bc[a][bin]++;
        }
    }
}

/* References [from, to) of ix: their box and their centroids' box. */
static void pn_bounds_range(const pn_bref *refs, uint32_t from, uint32_t to, pn_box *box,
                            pn_box *cbox)
{
    uint32_t i;
    for (i = from; i < to; i++) {
        pn_box tb;
        pn_ref_box(refs, i, &tb);
        pn_box_join(box, &tb);
        pn_box_point(cbox, pn_centroid(refs, i, 0), pn_centroid(refs, i, 1), pn_centroid(refs, i, 2));
    }
}

static void pn_bvh_chunk_fn(void *task, uint32_t begin, uint32_t end)
{
    const pn_bvh_chunks *j = (const pn_bvh_chunks *)task;
    uint32_t k;
    for (k = begin; k < end; k++) {
        pn_bvh_part *p = j->part + k;
        uint32_t from = j->first + (uint32_t)((uint64_t)j->count * k / PN_BVH_CHUNKS);
        uint32_t to = j->first + (uint32_t)((uint64_t)j->count * (k + 1u) / PN_BVH_CHUNKS);
        if (j->bins) {
            pn_bins_empty(p->bb, p->bc);
            pn_bin_range(j->refs, from, to, j->cbox, j->scale, p->bb, p->bc);
        } else {
            pn_box_empty(&p->box);
            pn_box_empty(&p->cbox);
            pn_bounds_range(j->refs, from, to, &p->box, &p->cbox);
        }
    }
}

/* A large node's two passes, each in PN_BVH_CHUNKS work items, into pre: its bounds
 * (given when its parent's split gave them) and its bins, the partials merged in order. */
static void pn_bvh_large(pn_bvh_par *par, const pn_bref *refs, uint32_t first, uint32_t count, const pn_bounds *known)
{
    pn_bvh_chunks j;
    pn_bvh_part *pre = par->part + PN_BVH_CHUNKS;
    float scale[3];
    uint32_t k, a, b;
    j.refs = refs;
    j.first = first;
    j.count = count;
    j.cbox = &pre->cbox;
    j.scale = scale;
    j.part = par->part;
    pn_box_empty(&pre->box);
    pn_box_empty(&pre->cbox);
    if (known->known) {
        pre->box = known->b[0];
        pre->cbox = known->b[1];
    } else {
        j.bins = 0;
        pn_run(par->ctx, PN_BVH_CHUNKS, pn_bvh_chunk_fn, &j);
        for (k = 0; k < PN_BVH_CHUNKS; k++) {
            pn_box_join(&pre->box, &par->part[k].box);
            pn_box_join(&pre->cbox, &par->part[k].cbox);
        }
    }
    pn_bin_scale(&pre->cbox, scale);
    j.bins = 1;
    pn_run(par->ctx, PN_BVH_CHUNKS, pn_bvh_chunk_fn, &j);
    pn_bins_empty(pre->bb, pre->bc);
    for (k = 0; k < PN_BVH_CHUNKS; k++)
        for (a = 0; a < 3u; a++)
            for (b = 0; b < PN_BVH_BINS; b++) {
                pn_box_join(&pre->bb[a][b], &par->part[k].bb[a][b]);
                pre->bc[a][b] += par->part[k].bc[a][b];
            }
}

/* The levels of median splits that bring `count` references down to leaves (fewer than
 * 2 PN_BVH_LEAF_MIN references each). */
static uint32_t pn_median_levels(uint32_t count)
{
    uint32_t m = 0;
    while (count >= 2u * PN_BVH_LEAF_MIN) {
        count = count - count / 2u; /* the larger half */
        m++;
    }
    return m;
}

/* Node nd (its references ix[first, first + count) set) at `depth`: its box written, then
 * either a leaf (0) or a split (1) of its references into [first, first + *split_out) and
 * the rest, ix partitioned in place. It reads and writes nothing beyond the node and its
 * range of ix, so nodes can be processed in any order, on any thread, and give the same
 * tree. */
static int pn_bvh_node(pn_bnode *nd, pn_bref *refs, uint32_t *ix, uint32_t depth, uint32_t dmax, uint32_t *split_out,
                       pn_bounds *io, const pn_bvh_part *pre)
{
    uint32_t first = nd->first, count = nd->count, i, split = 0;
    pn_box box, cbox;
    int axis = -1, leaf = 0, median = 0;

    if (pre) {
        box = pre->box;
        cbox = pre->cbox;
    } else if (io->known) {
        box = io->b[0];
        cbox = io->b[1];
    } else {
        pn_box_empty(&box);
        pn_box_empty(&cbox);
        pn_bounds_range(refs, first, first + count, &box, &cbox);
    }
    io->known = 0;
    for (i = 0; i < 3; i++) {
        nd->bmin[i] = box.lo[i];
        nd->bmax[i] = box.hi[i];
    }
    if (count < 2u * PN_BVH_LEAF_MIN) {
        leaf = 1;
    } else if (depth + pn_median_levels(count) < dmax) {
        /* Binned SAH over all three axes, binned in one pass over the triangles.
         * Costs: traversal 1, triangle 1. A split leaves at least PN_BVH_LEAF_MIN
         * references on each side. */
        float best = PN_KINF, parent = pn_box_area(&box), scale[3];
        int best_axis = -1;
        uint32_t best_bin = 0;
        pn_box bb[3][PN_BVH_BINS];
        uint32_t bc[3][PN_BVH_BINS];
        int a;
        pn_bin_scale(&cbox, scale);
        if (pre) {
            memcpy(bb, pre->bb, sizeof(bb));
            memcpy(bc, pre->bc, sizeof(bc));
        } else {
            pn_bins_empty(bb, bc);
            pn_bin_range(refs, first, first + count, &cbox, scale, bb, bc);
        }
        for (a = 0; a < 3; a++) {
            pn_box acc;
            uint32_t b, left = 0, rc = 0, right_count[PN_BVH_BINS];
            float right_area[PN_BVH_BINS];
            if (scale[a] == 0.0f) continue;
            /* An empty bin's box is empty: joining it changes nothing, so it is skipped (a
             * small node fills few of the bins). */
            pn_box_empty(&acc);
            for (b = PN_BVH_BINS - 1u; b > 0u; b--) {
                if (bc[a][b]) {
                    pn_box_join(&acc, &bb[a][b]);
                    rc += bc[a][b];
                    right_area[b] = pn_box_area(&acc);
                } else {
                    right_area[b] = b + 1u < PN_BVH_BINS ? right_area[b + 1u] : pn_box_area(&acc);
                }
                right_count[b] = rc;
            }
            pn_box_empty(&acc);
            for (b = 0; b + 1u < PN_BVH_BINS; b++) {
                float cost;
                if (!bc[a][b]) continue; /* the same cost as the bin before, or none */
                pn_box_join(&acc, &bb[a][b]);
                left += bc[a][b];
                if (left < PN_BVH_LEAF_MIN || right_count[b + 1u] < PN_BVH_LEAF_MIN) continue;
                cost = pn_box_area(&acc) * (float)left + right_area[b + 1u] * (float)right_count[b + 1u];
                if (cost < best) {
                    best = cost;
                    best_axis = a;
                    best_bin = b;
                }
            }
        }
        if (best_axis < 0) {
            /* No bin boundary leaves two references a side (the centroids coincide or
             * crowd one bin): a leaf when small enough, else the median. */
            if (count <= PN_BVH_LEAF_MAX) leaf = 1;
            else median = 1;
        } else if (count <= PN_BVH_LEAF_MAX &&
                   (parent <= 0.0f || (float)count <= 1.0f + best / parent)) {
            leaf = 1;
        } else {
            /* The partition also gives the children's bounds: their boxes are the unions of
             * their bins' (every reference of a bin goes to the same side), their centroid
             * boxes are taken on the way; min and max are exact, so these are the bits a
             * pass over each child gives. */
            uint32_t lo = first, hi = first + count, b;
            pn_box_empty(&io->b[1]);
            pn_box_empty(&io->b[3]);
            while (lo < hi) {
                const float *c = refs[lo].c;
                int32_t bin = pn_kfloor_clamp((c[best_axis] - cbox.lo[best_axis]) * scale[best_axis], 0,
                                              (int32_t)PN_BVH_BINS - 1);
                if ((uint32_t)bin <= best_bin) {
                    pn_box_point(&io->b[1], c[0], c[1], c[2]);
                    lo++;
                } else {
                    pn_box_point(&io->b[3], c[0], c[1], c[2]);
                    pn_swap(refs, ix, lo, --hi);
                }
            }
            split = lo - first;
            pn_box_empty(&io->b[0]);
            pn_box_empty(&io->b[2]);
            for (b = 0; b < PN_BVH_BINS; b++) pn_box_join(&io->b[b <= best_bin ? 0 : 2], &bb[best_axis][b]);
            io->known = 1;
            if (split == 0u || split == count) {
                split = count / 2u;
                io->known = 0;
            }
        }
    } else {
        median = 1; /* at the depth where only halving still stays within dmax */
    }
    if (median) {
        /* The object median along the centroids' longest axis: halves the count, at least
         * PN_BVH_LEAF_MIN a side. */
        int a;
        float ext = -1.0f;
        for (a = 0; a < 3; a++)
            if (cbox.hi[a] - cbox.lo[a] > ext) {
                ext = cbox.hi[a] - cbox.lo[a];
                axis = a;
            }
        split = count / 2u;
        pn_select(refs, ix, axis, first, first + count - 1u, first + split);
    }
    *split_out = split;
    return !leaf;
}

/* Subtrees: the top of the tree is built on the calling thread down to nodes of at most
 * `small` references (pn_bvh_build), which are handed, up to PN_BVH_TASKS of them, to
 * pn_run as work items; each builds its subtree into its own range of nodes (c - 2 for c
 * references), and the ranges are closed up afterwards. Which nodes are handed over
 * depends on the scene alone, and every node's split on its own references alone
 * (pn_bvh_node), so the tree is the same for any number of threads, and its shape the one
 * a build in one piece gives (only the nodes' numbering differs). */
#define PN_BVH_TASKS 64u
#define PN_BVH_TASK_MIN 2048u
typedef struct pn_bvh_task {
    uint32_t node, depth; /* the subtree's root and its depth */
    uint32_t base, end;   /* its descendants' nodes: [base, end) */
    uint32_t used, max_depth, max_leaf;
    pn_status st;         /* PN_E_INTERNAL: a work list or node range overflowed */
} pn_bvh_task;

typedef char pn_bvh_task_bytes[PN_BVH_TASKS * sizeof(pn_bvh_task) <= PN_BVH_TASK_BYTES ? 1 : -1];

typedef struct pn_bvh_job {
    pn_bref *refs;
    uint32_t *ix;
    pn_bnode *nodes;
    pn_bvh_task *tasks;
    uint32_t dmax;
} pn_bvh_job;

/* The subtree under t->node (start: its bounds when known, else NULL), its descendants
 * allocated from t->base up to t->end. With defer (the top of the tree), a node of at most
 * `small` references goes to defer[] instead while *ndefer < PN_BVH_TASKS. Work list:
 * after a split the larger child is pushed and the smaller one built next (the file's
 * head). */
static void pn_bvh_grow(pn_bref *refs, uint32_t *ix, pn_bnode *nodes, uint32_t dmax, pn_bvh_task *t, const pn_work *start,
                        uint32_t small, pn_bvh_task *defer, uint32_t *ndefer)
{
    pn_work list[32], cur; /* at most log2(2^26 references) + 1 entries (the file's head) */
    pn_bounds bd;
    uint32_t sp = 0, next = t->base, split;
    if (start) {
        cur = *start;
    } else {
        cur.node = t->node;
        cur.depth = t->depth;
        cur.known = 0;
    }
    t->max_depth = t->max_leaf = 0;
    t->st = PN_OK;
    for (;;) {
        pn_bnode *nd = nodes + cur.node;
        if (defer && nd->count <= small && *ndefer < PN_BVH_TASKS) {
            defer[*ndefer].node = cur.node;
            defer[*ndefer].depth = cur.depth;
            (*ndefer)++;
        } else {
            if (cur.depth > t->max_depth) t->max_depth = cur.depth;
            bd.known = cur.known;
            bd.b[0] = cur.box;
            bd.b[1] = cur.cbox;
            if (pn_bvh_node(nd, refs, ix, cur.depth, dmax, &split, &bd, NULL)) {
                uint32_t l = next, r = next + 1u, first = nd->first, count = nd->count;
                pn_work sm, lg;
                if (next + 2u > t->end || sp >= 32u) {
                    t->st = PN_E_INTERNAL;
                    return;
                }
                next += 2u;
                nodes[l].first = first;
                nodes[l].count = split;
                nodes[r].first = first + split;
                nodes[r].count = count - split;
                nd->first = l;
                nd->count = 0;
                sm.node = split <= count - split ? l : r;
                lg.node = split <= count - split ? r : l;
                sm.depth = lg.depth = cur.depth + 1u;
                sm.known = lg.known = bd.known;
                sm.box = bd.b[sm.node == l ? 0 : 2];
                sm.cbox = bd.b[sm.node == l ? 1 : 3];
                lg.box = bd.b[lg.node == l ? 0 : 2];
                lg.cbox = bd.b[lg.node == l ? 1 : 3];
                list[sp++] = lg;
                cur = sm;
                continue;
            }
            if (nd->count > t->max_leaf) t->max_leaf = nd->count;
        }
        if (sp == 0u) break;
        cur = list[--sp];
    }
    t->used = next - t->base;
}

static void pn_bvh_task_fn(void *task, uint32_t begin, uint32_t end)
{
    const pn_bvh_job *j = (const pn_bvh_job *)task;
    uint32_t i;
    for (i = begin; i < end; i++) pn_bvh_grow(j->refs, j->ix, j->nodes, j->dmax, j->tasks + i, NULL, 0u, NULL, NULL);
}

pn_status pn_bvh_build(pn_context *ctx)
{
    pn_bref *refs = (pn_bref *)(void *)ctx->frame;
    uint32_t *ix = ctx->tri_index;
    pn_bnode *nodes;
    pn_bvh_task top, *tasks;
    pn_bvh_job job;
    pn_bvh_par par;
    pn_work large[16]; /* the large nodes waiting: beyond 16, grown as the others are */
    uint32_t n, t, node_count, ntasks = 0, max_depth, max_leaf, refs_max = pn_bvh_refs_max(&ctx->limits), small, i;
    uint32_t nl;

    /* after the references and the bit per triangle (pn_bvh_scratch_bytes) */
    tasks = (pn_bvh_task *)(void *)((uint8_t *)(refs + refs_max) + ((size_t)ctx->limits.max_triangles / 32u + 1u) * 4u);
    nodes = (pn_bnode *)(void *)(ctx->frame + pn_bvh_nodes_at(&ctx->limits));
    n = pn_bvh_refs(ctx, refs, ix, tasks, &ctx->bvh_tris);
    for (t = 0; t < n; t++) ix[t] = t;
    ctx->bvh_refs = n;
    nodes[0].first = 0;
    nodes[0].count = n;
    if (n == 0u) {
        int a;
        for (a = 0; a < 3; a++) {
            nodes[0].bmin[a] = 0.0f;
            nodes[0].bmax[a] = 0.0f;
        }
        ctx->bvh_nodes = 1;
        ctx->bvh_depth = 0;
        ctx->bvh_max_leaf = 0;
        return pn_bvh_widen(ctx, nodes, 1u, (uint8_t *)(void *)refs);
    }
    /* The top, here: nodes of PN_BVH_PAR_MIN references or more each split with their two
     * passes in chunks (pn_bvh_large; their partials at the node pool's end, below which
     * the top's nodes stay), the others grown on this thread (pn_bvh_grow) down to about
     * PN_BVH_TASKS / 2 subtrees of at most `small` references. */
    small = n / (PN_BVH_TASKS / 2u);
    if (small < PN_BVH_TASK_MIN) small = PN_BVH_TASK_MIN;
    par.ctx = ctx;
    /* (a pool too small for the partials has no node of PN_BVH_PAR_MIN references) */
    par.room = 0u;
    par.part = NULL;
    if ((size_t)refs_max * sizeof(pn_bnode) >= (PN_BVH_CHUNKS + 1u) * sizeof(pn_bvh_part)) {
        par.part = (pn_bvh_part *)(void *)(nodes + (size_t)refs_max) - (PN_BVH_CHUNKS + 1u);
        par.room = (uint32_t)(((uintptr_t)par.part - (uintptr_t)nodes) / sizeof(pn_bnode));
    }
    max_depth = max_leaf = 0;
    node_count = 1u;
    large[0].node = 0;
    large[0].depth = 0;
    large[0].known = 0;
    for (nl = 1; nl > 0u;) {
        pn_work w = large[--nl];
        pn_bnode *nd = nodes + w.node;
        pn_bounds bd;
        uint32_t split, first = nd->first, count = nd->count, c;
        if (count < PN_BVH_PAR_MIN || node_count + 2u > par.room || nl + 2u > 16u) {
            top.node = w.node;
            top.depth = w.depth;
            top.base = node_count;
            top.end = refs_max;
            pn_bvh_grow(refs, ix, nodes, ctx->bvh_depth_max, &top, &w, small, tasks, &ntasks);
            if (top.st != PN_OK) return pn_fail(ctx, PN_E_INTERNAL, "BVH build: a work list or the node pool overflowed");
            node_count += top.used;
            if (top.max_depth > max_depth) max_depth = top.max_depth;
            if (top.max_leaf > max_leaf) max_leaf = top.max_leaf;
            continue;
        }
        bd.known = w.known;
        bd.b[0] = w.box;
        bd.b[1] = w.cbox;
        pn_bvh_large(&par, refs, first, count, &bd);
        if (w.depth > max_depth) max_depth = w.depth;
        if (!pn_bvh_node(nd, refs, ix, w.depth, ctx->bvh_depth_max, &split, &bd, par.part + PN_BVH_CHUNKS)) {
            if (count > max_leaf) max_leaf = count;
            continue;
        }
        /* the children: the second pushed first, so the first is split next */
        nodes[node_count].first = first;
        nodes[node_count].count = split;
        nodes[node_count + 1u].first = first + split;
        nodes[node_count + 1u].count = count - split;
        nd->first = node_count;
        nd->count = 0;
        for (c = 2u; c-- > 0u;) {
            pn_work *k = large + nl++;
            k->node = node_count + c;
            k->depth = w.depth + 1u;
            k->known = bd.known;
            k->box = bd.b[2u * c];
            k->cbox = bd.b[2u * c + 1u];
        }
        node_count += 2u;
    }
    top.used = node_count - 1u;
    top.max_depth = max_depth;
    top.max_leaf = max_leaf;
    /* Each subtree's range: c - 2 nodes below a root of c >= 2 references (its leaves hold
     * two or more, so it has at most c / 2 - 1 interior nodes, two children each). */
    for (i = 0; i < ntasks; i++) {
        tasks[i].base = node_count;
        node_count += nodes[tasks[i].node].count >= 2u ? nodes[tasks[i].node].count - 2u : 0u;
        tasks[i].end = node_count;
    }
    if (node_count > refs_max) return pn_fail(ctx, PN_E_INTERNAL, "BVH node pool overflow at %u nodes", node_count);
    job.refs = refs;
    job.ix = ix;
    job.nodes = nodes;
    job.tasks = tasks;
    job.dmax = ctx->bvh_depth_max;
    pn_run(ctx, ntasks, pn_bvh_task_fn, &job);
    /* The ranges closed up, in order: a subtree moves down by the room the ones before it
     * left, its interior nodes' child indices (and its root's) with it. */
    max_depth = top.max_depth;
    max_leaf = top.max_leaf;
    node_count = 1u + top.used;
    for (i = 0; i < ntasks; i++) {
        const pn_bvh_task *k = tasks + i;
        uint32_t shift = k->base - node_count, m;
        if (k->st != PN_OK) return pn_fail(ctx, PN_E_INTERNAL, "BVH build: a work list or node range overflowed");
        if (shift) {
            /* down, in ascending order (the ranges may overlap; no memmove in the core) */
            for (m = 0; m < k->used; m++) {
                pn_bnode c = nodes[k->base + m];
                if (c.count == 0u) c.first -= shift;
                nodes[node_count + m] = c;
            }
            if (nodes[k->node].count == 0u) nodes[k->node].first -= shift;
        }
        node_count += k->used;
        if (k->max_depth > max_depth) max_depth = k->max_depth;
        if (k->max_leaf > max_leaf) max_leaf = k->max_leaf;
    }
    /* References to triangle ids; the raster order: each triangle at its first reference
     * (a bit per triangle after the references marks the ones written). */
    {
        uint32_t *seen = (uint32_t *)(void *)(refs + refs_max), k = 0;
        for (t = 0; t <= ctx->tri_count / 32u; t++) seen[t] = 0;
        for (i = 0; i < n; i++) {
            ix[i] = refs[i].tri; /* the references are in ix's order */
            t = ix[i] & PN_REF_TRI;
            if (!(seen[t >> 5] & (1u << (t & 31u)))) {
                seen[t >> 5] |= 1u << (t & 31u);
                ctx->raster_index[k++] = t;
            }
        }
    }
    ctx->bvh_nodes = node_count;
    ctx->bvh_depth = max_depth;
    ctx->bvh_max_leaf = max_leaf;
    if (max_depth > ctx->bvh_depth_max)
        return pn_fail(ctx, PN_E_INTERNAL, "BVH depth %u exceeds its bound %u", max_depth, ctx->bvh_depth_max);
    /* the references are ids now: their records hold the nodes' heights */
    return pn_bvh_widen(ctx, nodes, node_count, (uint8_t *)(void *)refs);
}

/* The tree's shape, leaf order and raster order kept, every box recomputed from the
 * triangles' new positions: a leaf's as the union of its triangles' boxes (pn_tri_box, as
 * pn_bvh_refs gives a whole triangle's reference, joined in leaf order as the build joins
 * them), an interior child's as the union of its wide node's lanes. Both are the smallest
 * box over the vertices below it, the box pn_bvh_build gives a node (min and max are
 * exact; only the sign of a zero bound can follow the order of the joins), so a walk
 * meets what it would in a built tree of this shape. Wide nodes come after their parent
 * (breadth-first order), so one pass from the last node down meets every child before
 * its parent. bvh_nodes, bvh_depth, bvh_max_leaf, bvh_refs and bvh_tris describe the
 * shape and stay. A refit cannot stand in for a build when the leaves no longer list
 * exactly the non-degenerate triangles, or when the tree holds split references (a part's
 * box is the triangle clipped to the region the build chose, pn_part_box): then the tree
 * is built anew. A context that may split but whose tree split nothing (most scenes) is
 * refitted: a triangle the move made long and thin may then go unsplit, which costs time,
 * never bits. */
pn_status pn_bvh_refit(pn_context *ctx)
{
    pn_kbvh4 *w = ctx->wnodes;
    uint32_t n, i, c, a;
    if (ctx->bvh_refs != ctx->bvh_tris || ctx->bvh_tris != ctx->tri_count - ctx->degenerate) return pn_bvh_build(ctx);
    /* raster_index lists each listed triangle once: all bvh_tris of them non-degenerate and
     * as many as there are, they are the same set */
    for (i = 0; i < ctx->bvh_tris; i++)
        if (ctx->flags[ctx->raster_index[i]] & PN_TRI_DEGENERATE) return pn_bvh_build(ctx);
    if (ctx->bvh_refs == 0u) return PN_OK; /* every triangle degenerate: the empty root stays */
    for (n = ctx->bvh_wide; n-- > 0u;) {
        pn_kbvh4 *wn = w + n;
        for (c = 0; c < wn->n; c++) {
            uint32_t ch = wn->child[c];
            pn_box box;
            pn_box_empty(&box);
            if (ch & PN_W4_LEAF) {
                uint32_t first, count = pn_w4_word_refs(ch, &first);
                for (i = first; i < first + count; i++) {
                    pn_box tb;
                    pn_tri_box(ctx->tris + (size_t)(ctx->tri_index[i] & PN_REF_TRI) * 9u, &tb);
                    pn_box_join(&box, &tb);
                }
            } else {
                const pn_kbvh4 *cw = w + ch;
                uint32_t d;
                for (d = 0; d < cw->n; d++)
                    for (a = 0; a < 3u; a++) {
                        box.lo[a] = pn_kminf(box.lo[a], cw->lo[a][d]);
                        box.hi[a] = pn_kmaxf(box.hi[a], cw->hi[a][d]);
                    }
            }
            for (a = 0; a < 3u; a++) {
                wn->lo[a][c] = box.lo[a];
                wn->hi[a][c] = box.hi[a];
            }
        }
    }
    return PN_OK;
}
