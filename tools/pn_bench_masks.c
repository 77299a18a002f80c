/* pn_bench_masks.c - G-buffer snapshots, mask sets and our exact per-pixel masks for the
 * benchmark's bit-level comparison with Embree (see pn_bench.h).
 *
 * The library reports visibility, not masks, so the tool recomputes the masks with the
 * library's own kernels (pn_shadow_origin, pn_frustum_make/pn_frustum_aabb, pn_tri_mask)
 * over a BVH of its own: any conservative candidate set gives the same OR, and the caller
 * checks every popcount against the reference's visibility buffer. */
#include <stdlib.h>
#include <string.h>

#include "pn_bench.h"
#include "pn_bench_kernels.h"
#include "pn_internal.h" /* pn_bvh_fold */

int pn_gbuf_copy(pn_gbuf *g, const pn_frame *fr)
{
    size_t n = (size_t)fr->width * fr->height;
    memset(g, 0, sizeof(*g));
    g->pos = (float *)malloc(n * 3 * sizeof(float));
    g->nrm = (float *)malloc(n * 3 * sizeof(float));
    g->tri = (uint32_t *)malloc(n * sizeof(uint32_t));
    if (!g->pos || !g->nrm || !g->tri) {
        pn_gbuf_free(g);
        return 1;
    }
    g->width = fr->width;
    g->height = fr->height;
    memcpy(g->pos, fr->position, n * 3 * sizeof(float));
    memcpy(g->nrm, fr->normal, n * 3 * sizeof(float));
    memcpy(g->tri, fr->tri_id, n * sizeof(uint32_t));
    return 0;
}

void pn_gbuf_free(pn_gbuf *g)
{
    free(g->pos);
    free(g->nrm);
    free(g->tri);
    memset(g, 0, sizeof(*g));
}

int pn_masks_alloc(pn_masks *m, uint32_t w, uint32_t h, uint32_t k)
{
    size_t n = (size_t)w * h;
    memset(m, 0, sizeof(*m));
    m->words = pn_mask_words(k);
    m->bits = (uint32_t *)calloc(n * m->words, sizeof(uint32_t));
    m->lit = (uint8_t *)calloc(n, 1);
    if (!m->bits || !m->lit) {
        pn_masks_free(m);
        return 1;
    }
    m->width = w;
    m->height = h;
    m->k = k;
    return 0;
}

void pn_masks_free(pn_masks *m)
{
    free(m->bits);
    free(m->lit);
    memset(m, 0, sizeof(*m));
}

void pn_masks_compare(const pn_masks *a, const pn_masks *b, pn_mask_diff *d)
{
    size_t n = (size_t)a->width * a->height, p;
    uint32_t w;
    memset(d, 0, sizeof(*d));
    for (p = 0; p < n; p++) {
        const uint32_t *ma = a->bits + p * a->words, *mb = b->bits + p * b->words;
        uint64_t before = d->differ;
        if (!a->lit[p] || !b->lit[p]) continue;
        d->lit_pixels++;
        d->bits += (uint64_t)a->k * a->k;
        for (w = 0; w < a->words; w++) {
            d->only_a += pn_kpopcount(ma[w] & ~mb[w]);
            d->only_b += pn_kpopcount(mb[w] & ~ma[w]);
            d->differ += pn_kpopcount(ma[w] ^ mb[w]);
        }
        if (d->differ != before) d->pixels_differ++;
    }
}

void pn_bench_klight(const pn_light *l, uint32_t k, float eps, float cull_tol, pn_klight *kl)
{
    pn_v3 U = pn_v3_make(l->u[0], l->u[1], l->u[2]), V = pn_v3_make(l->v[0], l->v[1], l->v[2]);
    pn_v3 N = pn_v3_normalize(pn_v3_cross(U, V));
    memset(kl, 0, sizeof(*kl));
    memcpy(kl->c, l->center, sizeof(kl->c));
    memcpy(kl->U, l->u, sizeof(kl->U));
    memcpy(kl->V, l->v, sizeof(kl->V));
    /* As src/pn_frame.c derives it: the one-sided test in pn_shadow_origin reads N. */
    kl->N[0] = N.x;
    kl->N[1] = N.y;
    kl->N[2] = N.z;
    kl->eps = eps;
    kl->cull_tol = cull_tol;
    kl->k = k;
    kl->is_point = 0;
}

/* ---- A host-side BVH: median split on the longest centroid axis ----------------------- */

typedef struct pn_hbvh {
    pn_bnode *nodes;
    pn_kbvh4 *wnodes; /* the library's fold of it (pn_bvh_fold) */
    uint32_t *index;
    float *tris; /* 9 floats per triangle, scene order */
    uint32_t node_count;
} pn_hbvh;

static float pn_centroid(const float *tris, uint32_t t, int axis)
{
    const float *p = tris + (size_t)t * 9u;
    return p[axis] + p[3 + axis] + p[6 + axis];
}

/* Quickselect (Hoare partition around the middle element): index[lo..hi) reordered so
 * that everything before position mid has a centroid <= everything from mid on. */
static void pn_select(uint32_t *index, uint32_t lo, uint32_t hi, uint32_t mid, const float *tris, int axis)
{
    while (hi - lo > 1u) {
        float pivot = pn_centroid(tris, index[lo + (hi - lo - 1u) / 2u], axis);
        uint32_t i = lo - 1u, j = hi; /* lo - 1 wraps at 0 and is incremented first */
        for (;;) {
            uint32_t tmp;
            do i++; while (pn_centroid(tris, index[i], axis) < pivot);
            do j--; while (pn_centroid(tris, index[j], axis) > pivot);
            if (i >= j) break;
            tmp = index[i];
            index[i] = index[j];
            index[j] = tmp;
        }
        if (mid <= j) hi = j + 1u;
        else lo = j + 1u;
    }
}

static void pn_hbvh_bounds(pn_hbvh *b, pn_bnode *nd, uint32_t first, uint32_t count)
{
    uint32_t e;
    int a, v;
    for (a = 0; a < 3; a++) {
        nd->bmin[a] = PN_KINF;
        nd->bmax[a] = -PN_KINF;
    }
    for (e = first; e < first + count; e++) {
        const float *p = b->tris + (size_t)b->index[e] * 9u;
        for (v = 0; v < 3; v++)
            for (a = 0; a < 3; a++) {
                nd->bmin[a] = pn_kminf(nd->bmin[a], p[v * 3 + a]);
                nd->bmax[a] = pn_kmaxf(nd->bmax[a], p[v * 3 + a]);
            }
    }
}

static int pn_hbvh_build(pn_hbvh *b, const pn_mesh *m)
{
    uint32_t n = m->triangle_count, t, sp = 0;
    uint32_t (*stack)[3]; /* node, first, count */
    memset(b, 0, sizeof(*b));
    b->tris = (float *)malloc((size_t)n * 9u * sizeof(float));
    b->index = (uint32_t *)malloc((size_t)n * sizeof(uint32_t));
    b->nodes = (pn_bnode *)malloc((size_t)(2u * n + 1u) * sizeof(pn_bnode));
    b->wnodes = (pn_kbvh4 *)malloc((size_t)(n + 1u) * sizeof(pn_kbvh4));
    stack = (uint32_t(*)[3])malloc((size_t)(2u * n + 1u) * sizeof(*stack));
    if (!b->tris || !b->index || !b->nodes || !b->wnodes || !stack) {
        free(stack);
        return 1;
    }
    for (t = 0; t < n; t++) {
        int v;
        b->index[t] = t;
        for (v = 0; v < 3; v++)
            memcpy(b->tris + (size_t)t * 9u + v * 3, m->positions + (size_t)m->indices[t * 3u + v] * 3u,
                   3 * sizeof(float));
    }
    b->node_count = 1;
    stack[sp][0] = 0;
    stack[sp][1] = 0;
    stack[sp][2] = n;
    sp++;
    while (sp > 0) {
        uint32_t node, first, count, mid;
        pn_bnode *nd;
        float cmin[3] = {PN_KINF, PN_KINF, PN_KINF}, cmax[3] = {-PN_KINF, -PN_KINF, -PN_KINF};
        int axis = 0, a;
        uint32_t e;
        sp--;
        node = stack[sp][0];
        first = stack[sp][1];
        count = stack[sp][2];
        nd = b->nodes + node;
        pn_hbvh_bounds(b, nd, first, count);
        nd->first = first;
        nd->count = count;
        if (count <= 4u) continue;
        for (e = first; e < first + count; e++)
            for (a = 0; a < 3; a++) {
                float c = pn_centroid(b->tris, b->index[e], a);
                cmin[a] = pn_kminf(cmin[a], c);
                cmax[a] = pn_kmaxf(cmax[a], c);
            }
        for (a = 1; a < 3; a++)
            if (cmax[a] - cmin[a] > cmax[axis] - cmin[axis]) axis = a;
        mid = first + count / 2u;
        pn_select(b->index, first, first + count, mid, b->tris, axis);
        nd->first = b->node_count; /* interior: children at first, first + 1 */
        nd->count = 0;
        stack[sp][0] = b->node_count;
        stack[sp][1] = first;
        stack[sp][2] = mid - first;
        sp++;
        stack[sp][0] = b->node_count + 1u;
        stack[sp][1] = mid;
        stack[sp][2] = first + count - mid;
        sp++;
        b->node_count += 2u;
    }
    free(stack);
    {
        /* leaves of 2 .. 4 triangles (of 5 or more: halves), depth log2 n: its walks fit */
        uint32_t need;
        if (pn_bvh_fold(b->nodes, NULL, b->wnodes, n + 1u, &need) == 0u || need > PN_BVH_STACK) return 1;
    }
    return 0;
}

static void pn_hbvh_free(pn_hbvh *b)
{
    free(b->nodes);
    free(b->wnodes);
    free(b->index);
    free(b->tris);
    memset(b, 0, sizeof(*b));
}

/* ---- Our masks -------------------------------------------------------------------------- */

typedef struct pn_mask_task {
    const pn_hbvh *bvh;
    const pn_gbuf *g;
    pn_klight light;
    pn_masks *out;
    float *vis;
    uint32_t depth_overflow;
} pn_mask_task;

#define PN_HBVH_STACK 128u

static void pn_mask_pixel(pn_mask_task *tk, size_t pix)
{
    const pn_gbuf *g = tk->g;
    const pn_hbvh *b = tk->bvh;
    uint32_t m[PN_MASK_WORDS_MAX], stack[PN_HBVH_STACK], sp = 0, w;
    uint32_t own = g->tri[pix], k = tk->light.k;
    pn_frustum fr;
    pn_v3 O;
    pn_mask_clear(m);
    if (own == PN_NO_TRIANGLE) {
        if (tk->vis) tk->vis[pix] = 1.0f;
        return;
    }
    if (!pn_shadow_origin(pn_v3_load(g->pos + pix * 3u), pn_v3_load(g->nrm + pix * 3u), &tk->light, &O)) {
        if (tk->vis) tk->vis[pix] = 0.0f;
        return;
    }
    {
        /* The horizon of the own triangle, as every exact algorithm applies it. */
        pn_horizon H;
        pn_horizon_of(pn_v3_load(g->pos + pix * 3u), pn_v3_load(g->nrm + pix * 3u), own, b->tris, &tk->light, &H);
        pn_horizon_mask(&H, &tk->light, m);
    }
    pn_frustum_make(O, &tk->light, &fr);
    stack[sp++] = 0;
    while (sp > 0) {
        const pn_bnode *nd = b->nodes + stack[--sp];
        if (!pn_frustum_aabb(&fr, pn_v3_make(nd->bmin[0], nd->bmin[1], nd->bmin[2]),
                             pn_v3_make(nd->bmax[0], nd->bmax[1], nd->bmax[2])))
            continue;
        if (nd->count == 0u) {
            if (sp + 2u > PN_HBVH_STACK) {
                tk->depth_overflow = 1;
                continue;
            }
            stack[sp++] = nd->first + 1u;
            stack[sp++] = nd->first;
        } else {
            uint32_t e;
            for (e = nd->first; e < nd->first + nd->count; e++) {
                uint32_t t = b->index[e];
                pn_v3 A, B, C;
                if (t == own) continue;
                pn_tri_load(b->tris, t, &A, &B, &C);
                pn_tri_mask(O, A, B, C, &tk->light, m);
            }
        }
    }
    tk->out->lit[pix] = 1;
    for (w = 0; w < tk->out->words; w++) tk->out->bits[pix * tk->out->words + w] = m[w];
    if (tk->vis) tk->vis[pix] = pn_mask_visibility(m, k);
}

static void pn_mask_rows(void *task, uint32_t begin, uint32_t end)
{
    pn_mask_task *tk = (pn_mask_task *)task;
    uint32_t y, x;
    for (y = begin; y < end; y++)
        for (x = 0; x < tk->g->width; x++) pn_mask_pixel(tk, (size_t)y * tk->g->width + x);
}

int pn_our_masks(const pn_mesh *mesh, const pn_gbuf *g, const pn_light *light, uint32_t k, float eps,
                 float cull_tol, pn_threads *threads, pn_masks *out, float *vis, char *err,
                 size_t err_size)
{
    pn_hbvh bvh;
    pn_mask_task tk;
    if (pn_hbvh_build(&bvh, mesh) != 0) {
        pn_hbvh_free(&bvh);
        pn_tools_err(err, err_size, "host BVH: out of memory");
        return 1;
    }
    memset(&tk, 0, sizeof(tk));
    tk.bvh = &bvh;
    tk.g = g;
    tk.out = out;
    tk.vis = vis;
    pn_bench_klight(light, k, eps, cull_tol, &tk.light);
    pn_threads_parallel_for(threads, g->height, pn_mask_rows, &tk);
    pn_hbvh_free(&bvh);
    if (tk.depth_overflow) {
        pn_tools_err(err, err_size, "host BVH deeper than %u levels", PN_HBVH_STACK);
        return 1;
    }
    return 0;
}

/* ---- The reference's cost by pixel class ------------------------------------------------ */

typedef struct pn_class_task {
    const pn_hbvh *bvh;
    const pn_gbuf *g;
    pn_klight light;
    const float *ref_vis;
    double *row_ns, *row_work; /* 3 per row */
    uint64_t *row_pixels;      /* 3 per row */
    uint8_t *row_agree;        /* 1 per row */
} pn_class_task;

static void pn_class_rows(void *task, uint32_t begin, uint32_t end)
{
    pn_class_task *tk = (pn_class_task *)task;
    const pn_gbuf *g = tk->g;
    uint32_t y, x;
    for (y = begin; y < end; y++) {
        tk->row_agree[y] = 1;
        for (x = 0; x < g->width; x++) {
            size_t pix = (size_t)y * g->width + x;
            pn_shadow_counters cnt;
            pn_v3 P, n, O;
            uint64_t t0;
            float v;
            int c;
            if (g->tri[pix] == PN_NO_TRIANGLE) continue;
            P = pn_v3_load(g->pos + pix * 3u);
            n = pn_v3_load(g->nrm + pix * 3u);
            if (!pn_shadow_origin(P, n, &tk->light, &O)) continue;
            memset(&cnt, 0, sizeof(cnt));
            t0 = pn_threads_now_ns(NULL);
            v = pn_reference_pixel(P, n, g->tri[pix], tk->bvh->tris, tk->bvh->wnodes, tk->bvh->index,
                                   &tk->light, &cnt);
            c = v == 1.0f ? 0 : v == 0.0f ? 1 : 2;
            tk->row_ns[y * 3u + (uint32_t)c] += (double)(pn_threads_now_ns(NULL) - t0);
            tk->row_work[y * 3u + (uint32_t)c] += (double)cnt.nodes + (double)cnt.candidates;
            tk->row_pixels[y * 3u + (uint32_t)c]++;
            if (tk->ref_vis && v != tk->ref_vis[pix]) tk->row_agree[y] = 0;
        }
    }
}

int pn_reference_class_cost(const pn_mesh *mesh, const pn_gbuf *g, const pn_light *light, uint32_t k, float eps,
                            float cull_tol, pn_threads *threads, const float *ref_vis, pn_class_cost *out, char *err,
                            size_t err_size)
{
    pn_hbvh bvh;
    pn_class_task tk;
    uint32_t y;
    int c;
    memset(out, 0, sizeof(*out));
    memset(&tk, 0, sizeof(tk));
    tk.row_ns = (double *)calloc((size_t)g->height * 3u, sizeof(double));
    tk.row_work = (double *)calloc((size_t)g->height * 3u, sizeof(double));
    tk.row_pixels = (uint64_t *)calloc((size_t)g->height * 3u, sizeof(uint64_t));
    tk.row_agree = (uint8_t *)calloc(g->height, 1);
    if (!tk.row_ns || !tk.row_work || !tk.row_pixels || !tk.row_agree || pn_hbvh_build(&bvh, mesh) != 0) {
        free(tk.row_ns);
        free(tk.row_work);
        free(tk.row_pixels);
        free(tk.row_agree);
        pn_tools_err(err, err_size, "class cost: out of memory");
        return 1;
    }
    tk.bvh = &bvh;
    tk.g = g;
    tk.ref_vis = ref_vis;
    pn_bench_klight(light, k, eps, cull_tol, &tk.light);
    pn_threads_parallel_for(threads, g->height, pn_class_rows, &tk);
    out->vis_agrees = ref_vis != NULL;
    for (y = 0; y < g->height; y++) {
        for (c = 0; c < 3; c++) {
            out->ns[c] += tk.row_ns[y * 3u + (uint32_t)c];
            out->work[c] += tk.row_work[y * 3u + (uint32_t)c];
            out->pixels[c] += tk.row_pixels[y * 3u + (uint32_t)c];
        }
        if (!tk.row_agree[y]) out->vis_agrees = 0;
    }
    free(tk.row_ns);
    free(tk.row_work);
    free(tk.row_pixels);
    free(tk.row_agree);
    pn_hbvh_free(&bvh);
    return 0;
}
