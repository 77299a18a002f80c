/* pn_connect.c - the scene's connectivity for the penumbra wedges, built once at
 * pn_scene_set (kernels/pn_wedges.h reads it every frame), and which triangles belong to
 * sheets (PN_TRI_SHEET, which the Monte Carlo shadow maps read):
 *
 *   weld     triangle corners with the same position (bits, -0 as +0) get one vertex id:
 *            glTF files split vertices by normal and texture coordinate;
 *   objects  triangles joined by shared vertices (union-find, by smaller id), numbered in
 *            the order of their least vertex id;
 *   edges    the half-edges of non-degenerate triangles sorted by (object, lower vertex id,
 *            higher vertex id), ties by half-edge id: an edge is a run of equal keys.
 *
 * Sorting works in the caller's arena: the half-edge and run pools themselves, and the
 * frame region (free between frames) for the vertex ids and the union-find, 24 bytes a
 * triangle, which pn_carve reserves. The weld is an LSD radix sort by bytes whose Morton
 * codes travel with their corners through those two words, so it reads them in order; the
 * edges are counted by lower vertex in half-edge order, which reads the corners in order,
 * then sorted by comparison within a vertex, then counted by object. (Chained radix sorts
 * reading each key at its item's index in sorted order, a cache miss a read, took 0.9 s
 * of the dragon's set-up.) No recursion, no allocation.
 *
 *   solids   objects closed but for small holes and seams (pn_cn_solids) cast as solids,
 *            the others as sheets. */
#include <string.h>

#include "pn_wedges_frame.h"

#if PN_ENABLE_WEDGES || PN_ENABLE_MCSM
#include "pn_wedges.h"

typedef struct pn_cn {
    const float *tris;
    const uint32_t *canon; /* corner -> vertex id */
    const uint32_t *comp;  /* triangle -> object */
} pn_cn;

static uint32_t pn_cn_fbits(float v)
{
    uint32_t b;
    memcpy(&b, &v, sizeof(b));
    return b == 0x80000000u ? 0u : b;
}

/* Key word `which` of a half-edge: its higher vertex, lower vertex or object. */
#define PN_CN_HI 0u
#define PN_CN_LO 1u
#define PN_CN_OBJ 2u
static uint32_t pn_cn_key(const pn_cn *c, uint32_t which, uint32_t item)
{
    uint32_t t, e, x, y;
    t = item / 3u;
    e = item % 3u;
    if (which == PN_CN_OBJ) return c->comp[t];
    x = c->canon[(size_t)t * 3u + e];
    y = c->canon[(size_t)t * 3u + (e == 2u ? 0u : e + 1u)];
    if (which == PN_CN_HI) return x > y ? x : y;
    return x < y ? x : y;
}

/* The histograms of the four bytes of a sort's keys, taken in one pass over them (a
 * byte's counts do not depend on the order the other bytes' passes leave); a byte whose
 * keys all fall in one bucket needs no pass. */
static void pn_cn_hist_clear(uint32_t h[4][256])
{
    uint32_t d, b;
    for (d = 0; d < 4u; d++)
        for (b = 0; b < 256u; b++) h[d][b] = 0u;
}

static void pn_cn_hist_add(uint32_t h[4][256], uint32_t k)
{
    h[0][k & 255u]++;
    h[1][(k >> 8) & 255u]++;
    h[2][(k >> 16) & 255u]++;
    h[3][k >> 24]++;
}

/* Byte d's histogram h[d] into its buckets' starts; 0 when one bucket holds all n. */
static int pn_cn_starts(uint32_t *h, uint32_t n)
{
    uint32_t b, sum = 0u;
    for (b = 0; b < 256u; b++)
        if (h[b] == n) return 0;
    for (b = 0; b < 256u; b++) {
        uint32_t k = h[b];
        h[b] = sum;
        sum += k;
    }
    return 1;
}

/* Stable sort of (*a)[0, n) by keys (*ka)[0, n) ((*ka)[i] is item (*a)[i]'s), bytes least
 * significant first, keys and items through *kb and *b; the sorted ones end in *ka and *a
 * (both pairs of pointers swap). */
static void pn_cn_radix_kv(uint32_t **ka, uint32_t **kb, uint32_t **a, uint32_t **b, uint32_t n)
{
    uint32_t h[4][256], d, i;
    pn_cn_hist_clear(h);
    for (i = 0; i < n; i++) pn_cn_hist_add(h, (*ka)[i]);
    for (d = 0; d < 4u; d++) {
        uint32_t shift = 8u * d, *t;
        if (!pn_cn_starts(h[d], n)) continue;
        for (i = 0; i < n; i++) {
            uint32_t k = (*ka)[i], j = h[d][(k >> shift) & 255u]++;
            (*kb)[j] = k;
            (*b)[j] = (*a)[i];
        }
        t = *a;
        *a = *b;
        *b = t;
        t = *ka;
        *ka = *kb;
        *kb = t;
    }
}

/* Stable counting sort of half-edges in[0, n) into out by key word `which` (below
 * `buckets`), counted in cnt (buckets + 1 words); after it cnt[k] is the end of key k's. */
static void pn_cn_count_sort(const pn_cn *c, uint32_t which, const uint32_t *in, uint32_t *out, uint32_t n,
                             uint32_t *cnt, uint32_t buckets)
{
    uint32_t i;
    for (i = 0; i <= buckets; i++) cnt[i] = 0u;
    for (i = 0; i < n; i++) cnt[pn_cn_key(c, which, in[i]) + 1u]++;
    for (i = 1u; i <= buckets; i++) cnt[i] += cnt[i - 1u];
    for (i = 0; i < n; i++) out[cnt[pn_cn_key(c, which, in[i])]++] = in[i];
}

/* The two orders sorted by comparison (pn_cn_sort): corners by position, x, then y, then z,
 * by their bits (-0 as +0), the order of the weld's ties; half-edges of one lower vertex by
 * (higher vertex, half-edge id), a total order. */
#define PN_CN_BY_POS 0u
#define PN_CN_BY_HI 1u

static int pn_cn_less(const pn_cn *c, uint32_t order, uint32_t x, uint32_t y)
{
    uint32_t a;
    if (order == PN_CN_BY_HI) {
        uint32_t u = pn_cn_key(c, PN_CN_HI, x), v = pn_cn_key(c, PN_CN_HI, y);
        return u != v ? u < v : x < y;
    }
    for (a = 0; a < 3u; a++) {
        uint32_t u = pn_cn_fbits(c->tris[(size_t)x * 3u + a]), v = pn_cn_fbits(c->tris[(size_t)y * 3u + a]);
        if (u != v) return u < v;
    }
    return 0;
}

/* Item v sifted down the heap s[0, n) from place r (the larger child up while it comes
 * after v). */
static void pn_cn_sift(const pn_cn *c, uint32_t order, uint32_t *s, uint32_t n, uint32_t r, uint32_t v)
{
    for (;;) {
        uint32_t ch = 2u * r + 1u;
        if (ch >= n) break;
        if (ch + 1u < n && pn_cn_less(c, order, s[ch], s[ch + 1u])) ch++;
        if (!pn_cn_less(c, order, v, s[ch])) break;
        s[r] = s[ch];
        r = ch;
    }
    s[r] = v;
}

/* Items s[0, n) sorted by `order` (equal items in any order): insertion for a few, else
 * heapsort (no recursion, n log n for any run). */
static void pn_cn_sort(const pn_cn *c, uint32_t order, uint32_t *s, uint32_t n)
{
    uint32_t i, m;
    if (n <= 16u) {
        for (i = 1u; i < n; i++) {
            uint32_t v = s[i], j = i;
            for (; j > 0u && pn_cn_less(c, order, v, s[j - 1u]); j--) s[j] = s[j - 1u];
            s[j] = v;
        }
        return;
    }
    for (m = n; m-- > 0u;) pn_cn_sift(c, order, s, n, m, s[m]); /* heapify */
    for (m = n; m-- > 1u;) {                                     /* the largest to the end */
        uint32_t v = s[m];
        s[m] = s[0];
        pn_cn_sift(c, order, s, m, 0u, v);
    }
}

/* Corners s[0, m) sorted by position (the order of pn_cn_less's PN_CN_BY_POS) by radix,
 * z, then y, then x, through m words each of scratch: s1 for the corners, k0 and k1 for
 * their coordinates' bits. For the runs of one Morton code too long for their positions to
 * stay in cache (8,192 corners' triangles: 288 KB, an L2), which a dense mesh in one cell of
 * a much larger scene box makes: 300,000 triangles 1e-4 across beside one 1e3 across took
 * 0.9 s by heap, 0.5 s so. Shorter runs keep the heap, whose reads stay in cache (the
 * shared scenes' longest run, with the CLI's ground plane: 283 corners). */
#define PN_CN_RADIX_RUN 8192u
static void pn_cn_sort_pos_radix(const float *tris, uint32_t *s, uint32_t *s1, uint32_t *k0, uint32_t *k1, uint32_t m)
{
    uint32_t axis, i, *a = s, *b = s1, *ka = k0, *kb = k1;
    for (axis = 3u; axis-- > 0u;) {
        for (i = 0; i < m; i++) ka[i] = pn_cn_fbits(tris[(size_t)a[i] * 3u + axis]);
        pn_cn_radix_kv(&ka, &kb, &a, &b, m);
    }
    if (a != s) memcpy(s, a, (size_t)m * sizeof(uint32_t));
}

/* 10 bits of p's place in [lo, hi] spread to every third bit. */
static uint32_t pn_cn_spread(float p, float lo, float hi)
{
    float f = hi > lo ? (p - lo) / (hi - lo) * 1024.0f : 0.0f;
    uint32_t q = f >= 1023.0f ? 1023u : (f > 0.0f ? (uint32_t)f : 0u), r = 0u, b;
    for (b = 0; b < 10u; b++) r |= ((q >> b) & 1u) << (3u * b);
    return r;
}

static uint32_t pn_cn_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static void pn_cn_union(uint32_t *parent, uint32_t x, uint32_t y)
{
    x = pn_cn_find(parent, x);
    y = pn_cn_find(parent, y);
    if (x < y)
        parent[y] = x;
    else if (y < x)
        parent[x] = y;
}

/* Whether triangles a and b have the same three welded vertices (in any order). */
static int pn_cn_same_tri(const uint32_t *canon, uint32_t a, uint32_t b)
{
    const uint32_t *p = canon + 3u * a, *q = canon + 3u * b;
    uint32_t i, j, used = 0u;
    for (i = 0; i < 3u; i++) {
        for (j = 0; j < 3u && (((used >> j) & 1u) || q[j] != p[i]); j++) {
        }
        if (j == 3u) return 0;
        used |= 1u << j;
    }
    return 1;
}

/* The longest edge run searched for duplicate triangles (pairs within it: quadratic). */
#define PN_CN_DUP_RUN 8u

/* A solid whose signed volume is below -PN_CN_INVERTED_V (its area)^1.5 is wound inside
 * out, or is a cavity (a sphere's volume is 0.094 (area)^1.5, a leaf of the shared tree's
 * 0.002 and more; the sum's rounding, taken from the object's first corner, far below
 * 1e-4). A solid with small holes must be below that by the holes' share too (below). */
#define PN_CN_INVERTED_V 1e-4f

/* Solid objects (PN_WG_CLOSED: they cast with the triangles facing the light centre; the
 * others, sheets, with all of theirs turned to face it, and are marked PN_TRI_SHEET in the
 * triangle flags: the Monte Carlo shadow maps light a sheet on its side toward the light). A scanned statue or an exported
 * model is closed but for a few holes or seams (the Buddha: 4 open edges among 150,000):
 * cast as a sheet, every crossing of it counts twice, front and back, and its penumbrae
 * came out twice as dark (0.74 % of the Buddha's pixels darker than the reference by more
 * than 0.25 at 512 x 512; 0.04 % as a solid). Cast as
 * a solid, only light through a hole is lost, so an object is solid when its holes are
 * small beside its surface. Two measures, both against its area A (non-degenerate,
 * non-duplicate triangles):
 *   D = |sum of its triangles' vector areas| / A: 0 for a closed surface; the vector area
 *       of its holes otherwise (1 for a flat sheet, 1/2 for a bowl);
 *   H = (length of its boundary: edges whose half-edges do not cancel)^2 / (4 pi A): at least the holes' area
 *       over A (the isoperimetric inequality), so an open tube or lamp shade (D = 0: its
 *       two ends' vector areas cancel) is not taken for a solid.
 * Solid when D <= PN_CN_SOLID_D and H <= PN_CN_SOLID_H. A solid whose signed volume is
 * negative is an inside-out solid or a cavity (PN_TRI_NEGVOL; the frame
 * tells them apart, pn_connect_light). The sums run in triangle and
 * edge order (the same bits every time) over the frame scratch: six floats an object (24
 * bytes a triangle are reserved). */
#define PN_CN_SOLID_D 0.05f
#define PN_CN_SOLID_H 0.2f

/* Each object's first triangle into float `slot` of its six (its bits): the corner its volume
 * and its farthest corner are measured from (pn_cn_apex). */
static void pn_cn_firsts(float *acc, uint32_t slot, const uint32_t *tcomp, uint32_t T)
{
    uint32_t t;
    for (t = T; t-- > 0u;) memcpy(acc + 6u * (tcomp[t] & PN_WG_OBJ) + slot, &t, sizeof(t));
}

static const float *pn_cn_apex(const pn_context *ctx, const float *a, uint32_t slot)
{
    uint32_t first;
    memcpy(&first, a + slot, sizeof(first));
    return ctx->tris + (size_t)first * 9u;
}

static void pn_cn_solids(pn_context *ctx, uint32_t *scratch, const uint32_t *hedge, const uint32_t *run, uint32_t nr,
                         uint32_t *tcomp, uint32_t ncomp)
{
    /* per object: vector area x, y, z, area (all twice), boundary length, six times the
     * volume; the boundary's place holds the object's first triangle until the edges */
    float *acc = (float *)(void *)scratch;
    uint32_t T = ctx->tri_count, i, t, r;
    for (i = 0; i < 6u * ncomp; i++) acc[i] = 0.0f;
    pn_cn_firsts(acc, 4u, tcomp, T);
    for (t = 0; t < T; t++) {
        const float *p = ctx->tris + (size_t)t * 9u, *o;
        float *a = acc + 6u * (tcomp[t] & PN_WG_OBJ);
        float ex = p[3] - p[0], ey = p[4] - p[1], ez = p[5] - p[2], fx = p[6] - p[0], fy = p[7] - p[1], fz = p[8] - p[2];
        float nx = ey * fz - ez * fy, ny = ez * fx - ex * fz, nz = ex * fy - ey * fx;
        if ((ctx->flags[t] & PN_TRI_DEGENERATE) || (tcomp[t] & PN_WG_DUP)) continue;
        o = pn_cn_apex(ctx, a, 4u); /* the volume's apex: the object's first corner */
        a[0] += nx;
        a[1] += ny;
        a[2] += nz;
        a[3] += pn_ksqrt(nx * nx + ny * ny + nz * nz);
        a[5] += (p[0] - o[0]) * nx + (p[1] - o[1]) * ny + (p[2] - o[2]) * nz;
    }
    for (i = 0; i < ncomp; i++) acc[6u * i + 4u] = 0.0f;
    for (r = 0; r < nr; r++) {
        uint32_t lo = run[r], hi = run[r + 1u], h = hedge[lo] & ~PN_WG_REV, e = h % 3u;
        const float *p = ctx->tris + (size_t)(h / 3u) * 9u, *x = p + 3u * e, *y = p + 3u * (e == 2u ? 0u : e + 1u);
        float dx = y[0] - x[0], dy = y[1] - x[1], dz = y[2] - x[2];
        /* A boundary when its half-edges do not cancel: open, an odd count, or more one way
         * than the other. Closed surfaces that touch along an edge (stacked boxes, the
         * steps of a stair, walls meeting at a corner) meet it with two pairs winding
         * opposite ways: their union is closed there. */
        {
            uint32_t k;
            int32_t wsum = 0;
            for (k = lo; k < hi; k++) wsum += (hedge[k] & PN_WG_REV) ? -1 : 1;
            if (wsum == 0) continue;
        }
        acc[6u * (tcomp[h / 3u] & PN_WG_OBJ) + 4u] += pn_ksqrt(dx * dx + dy * dy + dz * dz);
    }
    ctx->stats.wedges.closed_objects = 0;
    ctx->stats.wedges.inverted_objects = 0;
    ctx->neg_groups = ctx->neg_mask = 0u;
    for (i = 0; i < PN_CN_NEG_MAX; i++) {
        ctx->neg[i].lo[0] = ctx->neg[i].lo[1] = ctx->neg[i].lo[2] = PN_KINF;
        ctx->neg[i].hi[0] = ctx->neg[i].hi[1] = ctx->neg[i].hi[2] = -PN_KINF;
        ctx->neg[i].objects = 0u;
    }
    for (i = 0; i < ncomp; i++) {
        float *a = acc + 6u * i, A = a[3], D = pn_ksqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), h = 0.5f * A;
        int solid = A > 0.0f && D <= PN_CN_SOLID_D * A && a[4] * a[4] <= PN_CN_SOLID_H * (4.0f * 3.14159265f) * (0.5f * A);
        ctx->stats.wedges.closed_objects += (uint32_t)solid;
        /* a candidate (D >= 0) when solid and of negative volume; a[2]: its apex's farthest
         * corner, squared (below) */
        a[0] = solid && a[5] < -6.0f * PN_CN_INVERTED_V * h * pn_ksqrt(h) ? D : -1.0f;
        a[2] = 0.0f;
        a[4] = solid ? 1.0f : 0.0f; /* the boundary's length is no longer needed */
    }
    /* A surface with holes has a volume that depends on its apex, by at most the holes'
     * vector area (D) times their distance from it (at most R, its farthest corner): a
     * candidate is of negative volume only below -2 R D too. */
    pn_cn_firsts(acc, 1u, tcomp, T); /* the same apex again (the boundary took its place) */
    for (t = 0; t < T; t++) {
        float *a = acc + 6u * (tcomp[t] & PN_WG_OBJ);
        const float *p = ctx->tris + (size_t)t * 9u, *o;
        uint32_t v;
        if (!(a[0] >= 0.0f)) continue;
        o = pn_cn_apex(ctx, a, 1u);
        for (v = 0; v < 3u; v++) {
            float dx = p[3u * v] - o[0], dy = p[3u * v + 1u] - o[1], dz = p[3u * v + 2u] - o[2];
            a[2] = pn_kmaxf(a[2], dx * dx + dy * dy + dz * dz);
        }
    }
    {
        /* The PN_CN_NEG_MAX - 1 largest (by area; ties by id) of negative volume get a group
         * each, for the frame to place its light against their boxes: a cavity is a room,
         * larger than what stands in it. The others share the last group, read reversed in
         * every frame (an inside-out part, a piece of furniture). */
        uint32_t top[PN_CN_NEG_MAX - 1u], ntop = 0u, k;
        for (i = 0; i < ncomp; i++) {
            float *a = acc + 6u * i, h = 0.5f * a[3];
            int neg = a[0] >= 0.0f && a[5] < -(6.0f * PN_CN_INVERTED_V * h * pn_ksqrt(h) + 2.0f * pn_ksqrt(a[2]) * a[0]);
            acc[6u * i] = a[4] != 0.0f ? 1.0f : 0.0f; /* solid */
            acc[6u * i + 1u] = neg ? (float)PN_CN_NEG_MAX : 0.0f;
            if (!neg) continue;
            ctx->neg[PN_CN_NEG_MAX - 1u].objects++;
            /* insertion into the largest so far, by area descending */
            k = ntop < PN_CN_NEG_MAX - 1u ? ntop++ : PN_CN_NEG_MAX - 1u;
            if (k == PN_CN_NEG_MAX - 1u && !(a[3] > acc[6u * top[k - 1u] + 3u])) continue;
            for (; k > 0u && a[3] > acc[6u * top[k - 1u] + 3u]; k--)
                if (k < PN_CN_NEG_MAX - 1u) top[k] = top[k - 1u];
            top[k] = i;
        }
        for (k = 0; k < ntop; k++) {
            acc[6u * top[k] + 1u] = (float)(k + 1u);
            ctx->neg[k].objects = 1u;
            ctx->neg[PN_CN_NEG_MAX - 1u].objects--;
        }
        ctx->neg_groups = ctx->neg[PN_CN_NEG_MAX - 1u].objects ? PN_CN_NEG_MAX : ntop;
    }
    for (t = 0; t < T; t++) {
        uint32_t o = tcomp[t] & PN_WG_OBJ, g = (uint32_t)acc[6u * o + 1u];
        ctx->flags[t] = (uint8_t)(ctx->flags[t] & ~(PN_TRI_SHEET | PN_TRI_INVERTED | PN_TRI_NEGVOL));
        if (acc[6u * o] != 0.0f)
            tcomp[t] |= PN_WG_CLOSED;
        else
            ctx->flags[t] = (uint8_t)(ctx->flags[t] | PN_TRI_SHEET);
        if (g) { /* the group's box, for the frames to place their light against */
            uint32_t c, v;
            const float *p = ctx->tris + (size_t)t * 9u;
            ctx->flags[t] = (uint8_t)(ctx->flags[t] | (g << PN_TRI_NEGVOL_SHIFT));
            for (v = 0; v < 3u; v++)
                for (c = 0; c < 3u; c++) {
                    ctx->neg[g - 1u].lo[c] = pn_kminf(ctx->neg[g - 1u].lo[c], p[3u * v + c]);
                    ctx->neg[g - 1u].hi[c] = pn_kmaxf(ctx->neg[g - 1u].hi[c], p[3u * v + c]);
                }
        }
    }
}

/* Which closed objects of negative volume this frame reads reversed (PN_TRI_INVERTED): the
 * largest ones whose box the light centre lies outside of, and every other. A closed
 * surface of negative volume is
 * an inside-out solid, whose fronts face in, or a cavity (a room modelled as a box wound
 * inward, its lamp inside), whose fronts are right; with the light outside its box it is the
 * solid (a cavity would show such a light nothing of its inside). The flags change only when
 * the choice does; a device port then copies the scene again (its version changes).
 * pn_stats.wedges.inverted_objects counts the objects read reversed. */
void pn_connect_light(pn_context *ctx, const pn_klight *L)
{
    uint32_t mask = 0u, g, t, n = 0u;
    for (g = 0; g < ctx->neg_groups; g++) {
        uint32_t c, in = g + 1u < PN_CN_NEG_MAX; /* the last group: always reversed */
        for (c = 0; c < 3u; c++) in &= (uint32_t)(L->c[c] >= ctx->neg[g].lo[c] && L->c[c] <= ctx->neg[g].hi[c]);
        if (!in && ctx->neg[g].objects) {
            mask |= 1u << g;
            n += ctx->neg[g].objects;
        }
    }
    ctx->stats.wedges.inverted_objects = n;
    if (mask == ctx->neg_mask) return;
    for (t = 0; t < ctx->tri_count; t++) {
        uint32_t f = ctx->flags[t], gt = (f & PN_TRI_NEGVOL) >> PN_TRI_NEGVOL_SHIFT;
        if (gt) ctx->flags[t] = (uint8_t)((f & ~PN_TRI_INVERTED) | ((mask >> (gt - 1u)) & 1u ? PN_TRI_INVERTED : 0u));
    }
    ctx->neg_mask = mask;
    ctx->scene_version++;
}

void pn_connect_build(pn_context *ctx, uint32_t *hedge, uint32_t *run, uint32_t *tcomp)
{
    uint32_t T = ctx->tri_count, n = 3u * T, i, t, r, nv = 0, ncomp = 0, nh = 0, nr = 0;
    uint32_t *canon = (uint32_t *)(void *)ctx->frame, *parent = canon + n, *a, *b;
    pn_cn c;
    c.tris = ctx->tris;
    c.canon = canon;
    c.comp = tcomp;

    /* Weld: corners sorted by position, one id per distinct position, in the Morton order
     * of the positions in the scene's box (ties: by the position's bits), so that edges,
     * numbered by their vertices, are numbered near their neighbours in space: a pixel's
     * list of silhouettes comes in blocks of nearby edges (kernels/pn_wedges.h). The codes
     * are kept in canon's place until the ids overwrite them. */
    for (i = 0; i < n; i++) {
        const float *p = ctx->tris + (size_t)i * 3u;
        canon[i] = pn_cn_spread(p[0], ctx->scene_min[0], ctx->scene_max[0]) |
                   (pn_cn_spread(p[1], ctx->scene_min[1], ctx->scene_max[1]) << 1) |
                   (pn_cn_spread(p[2], ctx->scene_min[2], ctx->scene_max[2]) << 2);
        hedge[i] = i;
    }
    /* By Morton code with the codes at hand (canon and parent, free until the union-find,
     * carry them), then each run of one code by position: the order of (code, x, y, z).
     * Ids by sorted place into b first (positions compared while their lines are at hand;
     * two codes are two positions), then to the corners. */
    {
        uint32_t *ka = canon, *kb = parent, j, k;
        a = hedge;
        b = run;
        pn_cn_radix_kv(&ka, &kb, &a, &b, n);
        for (i = 0; i < n; i = j) {
            for (j = i + 1u; j < n && ka[j] == ka[i]; j++) {
            }
            if (j - i > PN_CN_RADIX_RUN)
                pn_cn_sort_pos_radix(ctx->tris, a + i, b + i, ka + i, kb + i, j - i); /* the run's codes are spent */
            else if (j - i > 1u)
                pn_cn_sort(&c, PN_CN_BY_POS, a + i, j - i);
            if (i > 0u) nv++;
            b[i] = nv;
            for (k = i + 1u; k < j; k++) {
                if (pn_cn_less(&c, PN_CN_BY_POS, a[k - 1u], a[k])) nv++;
                b[k] = nv;
            }
        }
        for (i = 0; i < n; i++) canon[a[i]] = b[i];
    }
    nv++;

    /* Objects: union-find over vertex ids, then labels by first triangle. */
    for (i = 0; i < nv; i++) parent[i] = i;
    for (t = 0; t < T; t++) {
        if (ctx->flags[t] & PN_TRI_DEGENERATE) continue;
        pn_cn_union(parent, canon[3u * t], canon[3u * t + 1u]);
        pn_cn_union(parent, canon[3u * t], canon[3u * t + 2u]);
    }
    /* Labels in the order of the roots, each its object's least vertex id: objects are
     * numbered in the Morton order of their least vertex, so neighbouring objects (a
     * tree's leaves) have neighbouring numbers and their silhouettes share blocks. */
    for (i = 0; i < nv; i++) hedge[i] = 0u;
    for (t = 0; t < T; t++) hedge[pn_cn_find(parent, canon[3u * t])] = 1u;
    for (i = 0; i < nv; i++) hedge[i] = hedge[i] ? ncomp++ : 0xFFFFFFFFu;
    for (t = 0; t < T; t++) tcomp[t] = hedge[pn_cn_find(parent, canon[3u * t])];

    /* Edges: the half-edges of non-degenerate triangles with two distinct vertices, by
     * (object, lower, higher); ties keep half-edge order (the sort is stable). */
    for (i = 0; i < n; i++) {
        t = i / 3u;
        if (ctx->flags[t] & PN_TRI_DEGENERATE) continue;
        if (pn_cn_key(&c, PN_CN_HI, i) == pn_cn_key(&c, PN_CN_LO, i)) continue;
        hedge[nh++] = i;
    }
    /* By lower vertex, counted into run (nv + 1 <= 3 T + 1 words) and placed into parent
     * (free now) in ascending half-edge order, which reads the corners in order; each
     * vertex's half-edges then by (higher vertex, id) in place; then by object, placed back
     * into hedge in that order (counted into run again). */
    pn_cn_count_sort(&c, PN_CN_LO, hedge, parent, nh, run, nv);
    for (i = 0, r = 0; r < nv; r++) { /* run[r]: the end of vertex r's half-edges */
        if (run[r] - i > 1u) pn_cn_sort(&c, PN_CN_BY_HI, parent + i, run[r] - i);
        i = run[r];
    }
    pn_cn_count_sort(&c, PN_CN_OBJ, parent, hedge, nh, run, ncomp);

    /* Runs. */
    ctx->stats.wedges.open_edges = 0;
    ctx->stats.wedges.nonmanifold_edges = 0;
    i = 0;
    while (i < nh) {
        uint32_t j = i + 1u, h = hedge[i], s = tcomp[h / 3u];
        uint32_t lo = pn_cn_key(&c, PN_CN_LO, h), hi = pn_cn_key(&c, PN_CN_HI, h);
        while (j < nh && pn_cn_key(&c, PN_CN_LO, hedge[j]) == lo && pn_cn_key(&c, PN_CN_HI, hedge[j]) == hi &&
               tcomp[hedge[j] / 3u] == s)
            j++;
        run[nr++] = i;
        if (j - i == 1u) {
            ctx->stats.wedges.open_edges++;
        } else {
            uint32_t x0 = canon[hedge[i]], x1 = canon[hedge[i + 1u]];
            /* two windings the opposite way: the half-edges start at different vertices */
            if (j - i != 2u || x0 == x1) ctx->stats.wedges.nonmanifold_edges++;
        }
        i = j;
    }
    run[nr] = nh;
    /* Duplicates: a triangle on the same three vertices as an earlier one of its edges' runs
     * (a double-sided sheet's back, a face given twice) casts nothing, so that a sheet casts
     * once (runs of more than PN_CN_DUP_RUN half-edges are left alone). */
    ctx->stats.wedges.duplicates = 0;
    for (r = 0; r < nr; r++) {
        uint32_t lo = run[r], hi = run[r + 1u], x, y;
        if (hi - lo < 2u || hi - lo > PN_CN_DUP_RUN) continue;
        for (x = lo; x < hi; x++)
            for (y = x + 1u; y < hi; y++) {
                uint32_t ta = hedge[x] / 3u, tb = hedge[y] / 3u, th = ta < tb ? tb : ta;
                if (ta != tb && !(tcomp[th] & PN_WG_DUP) && pn_cn_same_tri(canon, ta, tb)) {
                    tcomp[th] |= PN_WG_DUP;
                    ctx->stats.wedges.duplicates++;
                }
            }
    }
    /* Direction flags, now that the keys are no longer needed. */
    for (i = 0; i < nh; i++) {
        uint32_t h = hedge[i];
        if (pn_cn_key(&c, PN_CN_LO, h) != canon[h]) hedge[i] = h | PN_WG_REV;
    }
    pn_cn_solids(ctx, canon, hedge, run, nr, tcomp, ncomp);
    ctx->stats.wedges.edges = nr;
    ctx->stats.wedges.objects = ncomp;
    ctx->stats.wedges.vertices = nv;
}

#endif
