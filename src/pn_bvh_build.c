/* pn_bvh_build.c - binned SAH BVH, built top-down into the arena without recursion.
 *
 * Work list: after a split the larger child is pushed and the smaller one is built next,
 * so every pushed entry at least halves the remaining count: the list never holds more
 * than log2(N) + 1 entries (64 is plenty). Below depth PN_BVH_SAH_DEPTH the split is the
 * object median (an iterative quickselect), which halves the count at each level and so
 * bounds the tree depth by PN_BVH_SAH_DEPTH + 27 <= PN_BVH_STACK (check_config.h): the
 * traversal stack can never overflow. Node 0 is the root; children are allocated in
 * pairs, so at most 2N - 1 nodes exist. Everything is deterministic: same triangles,
 * same tree. */
#include "pn_internal.h"
#include "pn_kmath.h"

typedef struct pn_box {
    float lo[3], hi[3];
} pn_box;

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

static float pn_box_area(const pn_box *b)
{
    float dx = b->hi[0] - b->lo[0], dy = b->hi[1] - b->lo[1], dz = b->hi[2] - b->lo[2];
    if (!(dx >= 0.0f)) return 0.0f;
    return dx * dy + dy * dz + dz * dx;
}

static void pn_tri_box(const float *tris, uint32_t t, pn_box *b)
{
    const float *p = tris + (size_t)t * 9u;
    pn_box_empty(b);
    pn_box_point(b, p[0], p[1], p[2]);
    pn_box_point(b, p[3], p[4], p[5]);
    pn_box_point(b, p[6], p[7], p[8]);
}

static float pn_centroid(const float *tris, uint32_t t, int axis)
{
    const float *p = tris + (size_t)t * 9u;
    return (p[axis] + p[3 + axis] + p[6 + axis]) * (1.0f / 3.0f);
}

/* Total order for the median split: centroid, then triangle index. */
static int pn_key_less(const float *tris, int axis, uint32_t a, uint32_t b)
{
    float ca = pn_centroid(tris, a, axis), cb = pn_centroid(tris, b, axis);
    if (ca != cb) return ca < cb;
    return a < b;
}

static void pn_swap(uint32_t *ix, uint32_t a, uint32_t b)
{
    uint32_t t = ix[a];
    ix[a] = ix[b];
    ix[b] = t;
}

/* Places the element of rank kth (within [lo, hi]) at kth, smaller ones before it. */
static void pn_select(const float *tris, uint32_t *ix, int axis, uint32_t lo, uint32_t hi, uint32_t kth)
{
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2u, i, j;
        /* median of three to hi as pivot */
        if (pn_key_less(tris, axis, ix[mid], ix[lo])) pn_swap(ix, mid, lo);
        if (pn_key_less(tris, axis, ix[hi], ix[lo])) pn_swap(ix, hi, lo);
        if (pn_key_less(tris, axis, ix[mid], ix[hi])) pn_swap(ix, mid, hi);
        i = lo;
        for (j = lo; j < hi; j++)
            if (pn_key_less(tris, axis, ix[j], ix[hi])) pn_swap(ix, i++, j);
        pn_swap(ix, i, hi);
        if (i == kth) return;
        if (kth < i)
            hi = i - 1u;
        else
            lo = i + 1u;
    }
}

typedef struct pn_work {
    uint32_t node, depth;
} pn_work;

pn_status pn_bvh_build(pn_context *ctx)
{
    const float *tris = ctx->tris;
    uint32_t *ix = ctx->tri_index;
    pn_kbvh_node *nodes = ctx->nodes;
    pn_work list[64];
    uint32_t sp = 0, n = 0, t, node_count = 1, max_depth = 0, max_leaf = 0;
    pn_work cur;

    for (t = 0; t < ctx->tri_count; t++)
        if (!(ctx->flags[t] & PN_TRI_DEGENERATE)) ix[n++] = t;
    ctx->bvh_tris = n;
    nodes[0].first = 0;
    nodes[0].count = n;
    cur.node = 0;
    cur.depth = 0;
    if (n == 0u) {
        int a;
        for (a = 0; a < 3; a++) {
            nodes[0].bmin[a] = 0.0f;
            nodes[0].bmax[a] = 0.0f;
        }
        ctx->bvh_nodes = 1;
        ctx->bvh_depth = 0;
        ctx->bvh_max_leaf = 0;
        return PN_OK;
    }

    for (;;) {
        pn_kbvh_node *nd = nodes + cur.node;
        uint32_t first = nd->first, count = nd->count, i, split = 0;
        pn_box box, cbox;
        int axis = -1, leaf = 0;

        pn_box_empty(&box);
        pn_box_empty(&cbox);
        for (i = first; i < first + count; i++) {
            pn_box tb;
            pn_tri_box(tris, ix[i], &tb);
            pn_box_join(&box, &tb);
            pn_box_point(&cbox, pn_centroid(tris, ix[i], 0), pn_centroid(tris, ix[i], 1),
                         pn_centroid(tris, ix[i], 2));
        }
        for (i = 0; i < 3; i++) {
            nd->bmin[i] = box.lo[i];
            nd->bmax[i] = box.hi[i];
        }
        if (cur.depth > max_depth) max_depth = cur.depth;

        if (count == 1u) {
            leaf = 1;
        } else if (cur.depth >= PN_BVH_SAH_DEPTH) {
            int a;
            float ext = -1.0f;
            for (a = 0; a < 3; a++)
                if (cbox.hi[a] - cbox.lo[a] > ext) {
                    ext = cbox.hi[a] - cbox.lo[a];
                    axis = a;
                }
            split = count / 2u;
            pn_select(tris, ix, axis, first, first + count - 1u, first + split);
        } else {
            /* Binned SAH over all three axes, binned in one pass over the triangles.
             * Costs: traversal 1, triangle 1. */
            float best = PN_KINF, parent = pn_box_area(&box), scale[3];
            int best_axis = -1;
            uint32_t best_bin = 0;
            pn_box bb[3][PN_BVH_BINS];
            uint32_t bc[3][PN_BVH_BINS];
            int a;
            for (a = 0; a < 3; a++) {
                float ext = cbox.hi[a] - cbox.lo[a];
                uint32_t b;
                scale[a] = ext > 0.0f ? (float)PN_BVH_BINS / ext : 0.0f;
                for (b = 0; b < PN_BVH_BINS; b++) {
                    pn_box_empty(&bb[a][b]);
                    bc[a][b] = 0;
                }
            }
            for (i = first; i < first + count; i++) {
                pn_box tb;
                pn_tri_box(tris, ix[i], &tb);
                for (a = 0; a < 3; a++) {
                    int32_t bin;
                    if (scale[a] == 0.0f) continue;
                    bin = pn_kfloor_clamp((pn_centroid(tris, ix[i], a) - cbox.lo[a]) * scale[a], 0,
                                          (int32_t)PN_BVH_BINS - 1);
                    pn_box_join(&bb[a][bin], &tb);
                    bc[a][bin]++;
                }
            }
            for (a = 0; a < 3; a++) {
                pn_box acc;
                uint32_t b, left = 0, rc = 0, right_count[PN_BVH_BINS];
                float right_area[PN_BVH_BINS];
                if (scale[a] == 0.0f) continue;
                pn_box_empty(&acc);
                for (b = PN_BVH_BINS - 1u; b > 0u; b--) {
                    pn_box_join(&acc, &bb[a][b]);
                    rc += bc[a][b];
                    right_area[b] = pn_box_area(&acc);
                    right_count[b] = rc;
                }
                pn_box_empty(&acc);
                for (b = 0; b + 1u < PN_BVH_BINS; b++) {
                    float cost;
                    pn_box_join(&acc, &bb[a][b]);
                    left += bc[a][b];
                    if (left == 0u || right_count[b + 1u] == 0u) continue;
                    cost = pn_box_area(&acc) * (float)left + right_area[b + 1u] * (float)right_count[b + 1u];
                    if (cost < best) {
                        best = cost;
                        best_axis = a;
                        best_bin = b;
                    }
                }
            }
            if (best_axis < 0) {
                /* All centroids coincide: split by position in the list. */
                if (count <= PN_BVH_LEAF_MAX) leaf = 1;
                else split = count / 2u;
            } else if (count <= PN_BVH_LEAF_MAX &&
                       (parent <= 0.0f || (float)count <= 1.0f + best / parent)) {
                leaf = 1;
            } else {
                uint32_t lo = first, hi = first + count;
                while (lo < hi) {
                    int32_t bin = pn_kfloor_clamp(
                        (pn_centroid(tris, ix[lo], best_axis) - cbox.lo[best_axis]) * scale[best_axis], 0,
                        (int32_t)PN_BVH_BINS - 1);
                    if ((uint32_t)bin <= best_bin)
                        lo++;
                    else
                        pn_swap(ix, lo, --hi);
                }
                split = lo - first;
                if (split == 0u || split == count) split = count / 2u;
            }
        }

        if (leaf) {
            if (count > max_leaf) max_leaf = count;
            if (sp == 0u) break;
            cur = list[--sp];
            continue;
        }
        {
            uint32_t l = node_count, r = node_count + 1u;
            pn_work small, large;
            if (node_count + 2u > 2u * ctx->limits.max_triangles)
                return pn_fail(ctx, PN_E_INTERNAL, "BVH node pool overflow at %u nodes", node_count);
            node_count += 2u;
            nodes[l].first = first;
            nodes[l].count = split;
            nodes[r].first = first + split;
            nodes[r].count = count - split;
            nd->first = l;
            nd->count = 0;
            small.node = split <= count - split ? l : r;
            large.node = split <= count - split ? r : l;
            small.depth = large.depth = cur.depth + 1u;
            if (sp >= 64u) return pn_fail(ctx, PN_E_INTERNAL, "BVH build list overflow");
            list[sp++] = large;
            cur = small;
        }
    }
    ctx->bvh_nodes = node_count;
    ctx->bvh_depth = max_depth;
    ctx->bvh_max_leaf = max_leaf;
    if (max_depth + 1u > PN_BVH_STACK)
        return pn_fail(ctx, PN_E_INTERNAL, "BVH depth %u exceeds PN_BVH_STACK", max_depth);
    return PN_OK;
}
