/* pn_gears.c - GEARS' whole frame (sequence in pn_gears_frame.h): the grid cameras (paper
 * §4 A.1), grid bounds, the plan that splits a frame's (triangle, cell) pairs into tiles
 * the pair pool can hold, and the passes of kernels/pn_passes.h between them, run on the
 * frame's port. Written once: both ports run this sequence. */
#include <string.h>

#include "pn_algorithms.h"
#include "pn_device.h"
#include "pn_gears_frame.h"
#include "pn_passes.h"

#if PN_ENABLE_GEARS

/* The context's GEARS limits: the largest grid (default PN_GEARS_GRID_MAX, at most 1024),
 * and the pair pool. Besides its pairs, a tile costs two passes over the triangles (count
 * and scatter), one over the pixels (masks) and the cells of its grid rows: a pool of a
 * few pairs a triangle, one a pixel and one a cell of the largest grid keeps those passes
 * to a fraction of the pairs' own work, whatever the tiles. That is the default: 4 a
 * triangle + 1 a pixel of the largest frame + the grid's cells, at most 16 a pixel (more
 * would seldom tile less), no fewer than the triangles (one cell's pairs, which no tiling
 * splits, are at most one a triangle), at most PN_GEARS_PAIRS; a request up to 2^28. */
int pn_gears_limits_ok(const pn_limits *l) { return l->gears_pairs <= (1u << 28) && l->gears_grid_max <= 1024u; }
static uint32_t pn_gears_grid_max(const pn_limits *l) { return l->gears_grid_max ? l->gears_grid_max : PN_GEARS_GRID_MAX; }
static uint32_t pn_gears_pairs_max(const pn_limits *l)
{
    uint64_t px = (uint64_t)l->max_width * l->max_height, g = pn_gears_grid_max(l);
    uint64_t n = 4u * (uint64_t)l->max_triangles + px + g * g;
    if (l->gears_pairs) return l->gears_pairs;
    if (n > 16u * px) n = 16u * px;
    if (n < l->max_triangles) n = l->max_triangles;
    return (uint32_t)(n > PN_GEARS_PAIRS ? PN_GEARS_PAIRS : n);
}

/* PN_ALGO_GEARS's options (pn_algorithms.h): the grid; 0 is the default,
 * PN_GEARS_GRID_DEFAULT cells per axis or the context's limit if smaller. */
pn_status pn_gears_prepare(pn_frame_state *fs, const pn_frame_options *opt)
{
    pn_context *ctx = fs->ctx;
    uint32_t gmax = pn_gears_grid_max(&ctx->limits);
    if (opt->gears.grid > gmax)
        return pn_fail(ctx, PN_E_INVALID_ARG, "gears.grid = %u; it must be 0 or in 1 .. %u (pn_limits.gears_grid_max)",
                       opt->gears.grid, gmax);
    fs->res = opt->gears.grid ? opt->gears.grid : gmax < PN_GEARS_GRID_DEFAULT ? gmax : PN_GEARS_GRID_DEFAULT;
    return PN_OK;
}

/* One frame's pools (addresses in the arena, pn_gears_carve), grid, tile plan and
 * statistics. */
typedef struct pn_gears_frame {
    pn_kfaces *faces;    /* [1]: the grid cameras, written by the host, read by passes */
    pn_cellrect *rects;  /* [max_triangles]: rectangle of triangle t on the plan's face */
    uint32_t *pix_cell;  /* [pixels]: global cell or PN_CELL_NONE */
    float *row_box;      /* [height * 8]: box of a row's origins (3-D, then projected 2-D) */
    uint32_t *cell_bits; /* [rows][W]: per global grid row, a bit a cell that holds pixels */
    uint32_t *cell_rank; /* [rows][W + 1]: per grid row, the set bits before each word */
    uint32_t *cell_off;  /* [res^2 + 1]: a tile's pairs per cell of its face, prefix-summed */
    uint32_t *cell_pix;  /* [res^2]: pixels per cell of one face (face_ready) */
    uint32_t *cell_cur;  /* [res^2]: a tile's pairs per cell, then the scatter's cursors; the
                          * counts of a grid row being split */
    uint32_t *row_pairs; /* [rows * 2]: pairs per global grid row, low and high word */
    uint32_t *sorted;    /* [pool]: triangles by cell, in raster order within a cell */
    float *chunk_box;    /* [pool / PN_GEARS_CHUNK + 1][6]: box of each chunk of sorted */
    float *super_box;    /* [pool / (PN_GEARS_CHUNK PN_GEARS_SUPER) + 1][6]: of each superchunk */
    uint32_t cells;      /* res^2: the cells of a face */
    uint32_t rows;       /* faces * res: global grid rows */
    uint32_t pool;       /* pairs one tile may hold */
    uint64_t lit;
    /* tile plan: runs of global rows [start, end) handed out face by face from s0; a row
     * too big for the pool (split) handed out as runs of cells from xs */
    uint32_t plan_start, plan_end, plan_s0, plan_split, plan_xs, plan_counted;
    uint32_t face_ready; /* the face of rects, of its rows' pairs and of cell_pix; 6: none */
    /* statistics over all tiles */
    uint64_t total_pairs, assignments, sum_tris_cell;
    uint32_t tiles, pairs_high, max_tris_cell, cells_used, max_pix;
} pn_gears_frame_pools;

enum { PN_GEARS_PLAN_DONE = 0, PN_GEARS_PLAN_TILE = 1, PN_GEARS_PLAN_COUNT_ROW = 2, PN_GEARS_PLAN_FACE = 3 };

static void pn_set3(float *d, pn_v3 v)
{
    d[0] = v.x;
    d[1] = v.y;
    d[2] = v.z;
}

/* Area light: eye on the line from the centre of the box of origins and light corners to
 * the light centre, one light diagonal behind the light; axes U^, V^, N. */
uint32_t pn_gears_faces(const pn_klight *L, const float obox[6], float scene_diag, pn_kgrid faces[6])
{
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    uint32_t f;
    memset(faces, 0, 6u * sizeof(pn_kgrid));
    if (L->is_point) {
        /* A cube around the light: face f looks along +-x, +-y, +-z. */
        static const float axes[6][9] = {
            {0, 0, -1, 0, 1, 0, 1, 0, 0},  {0, 0, 1, 0, 1, 0, -1, 0, 0}, {1, 0, 0, 0, 0, -1, 0, 1, 0},
            {1, 0, 0, 0, 0, 1, 0, -1, 0},  {1, 0, 0, 0, 1, 0, 0, 0, 1},  {-1, 0, 0, 0, 1, 0, 0, 0, -1}};
        for (f = 0; f < 6; f++) {
            pn_kgrid *g = faces + f;
            pn_set3(g->eye, c);
            memcpy(g->ax, axes[f], 3u * sizeof(float));
            memcpy(g->ay, axes[f] + 3, 3u * sizeof(float));
            memcpy(g->az, axes[f] + 6, 3u * sizeof(float));
            g->near_depth = 1e-4f * scene_diag;
            if (!(g->near_depth > 0.0f)) g->near_depth = 1e-30f;
            g->face = f;
            g->is_point = 1;
        }
        return 6;
    } else {
        pn_kgrid *g = faces;
        pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]);
        pn_v3 V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
        pn_v3 N = pn_v3_make(L->N[0], L->N[1], L->N[2]);
        pn_v3 lo = pn_v3_make(obox[0], obox[1], obox[2]), hi = pn_v3_make(obox[3], obox[4], obox[5]);
        pn_v3 mid, dir, E;
        float diag = 2.0f * pn_ksqrt(pn_v3_dot(U, U) + pn_v3_dot(V, V)), far = 0.0f, dn;
        uint32_t q;
        for (q = 0; q < 4; q++) { /* the light corners join the box */
            pn_v3 Lq = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, (q & 1u) ? 1.0f : -1.0f),
                                              pn_v3_scale(V, (q & 2u) ? 1.0f : -1.0f)));
            lo = pn_v3_make(pn_kminf(lo.x, Lq.x), pn_kminf(lo.y, Lq.y), pn_kminf(lo.z, Lq.z));
            hi = pn_v3_make(pn_kmaxf(hi.x, Lq.x), pn_kmaxf(hi.y, Lq.y), pn_kmaxf(hi.z, Lq.z));
        }
        mid = pn_v3_scale(pn_v3_add(lo, hi), 0.5f);
        dir = pn_v3_normalize(pn_v3_sub(c, mid));
        /* The eye must stay well behind the light plane so that the light plane has a
         * depth of at least a quarter diagonal (the paper's line can run almost parallel
         * to the light when the scene is off to its side). */
        dn = -pn_v3_dot(dir, N);
        if (!(dn >= 0.25f)) dir = pn_v3_normalize(pn_v3_sub(pn_v3_scale(dir, 1.0f), pn_v3_scale(N, 0.25f - dn + 0.01f)));
        if (!(-pn_v3_dot(dir, N) >= 0.2f)) dir = pn_v3_scale(N, -1.0f);
        E = pn_v3_add(c, pn_v3_scale(dir, diag));
        for (q = 0; q < 8; q++) {
            pn_v3 k = pn_v3_make((q & 1u) ? hi.x : lo.x, (q & 2u) ? hi.y : lo.y, (q & 4u) ? hi.z : lo.z);
            far = pn_kmaxf(far, pn_v3_dot(pn_v3_sub(k, E), N));
        }
        pn_set3(g->eye, E);
        pn_set3(g->ax, pn_v3_normalize(U));
        pn_set3(g->ay, pn_v3_normalize(V));
        pn_set3(g->az, N);
        g->far_depth = far;
        g->near_depth = pn_v3_dot(pn_v3_sub(c, E), N);
        return 1;
    }
}

/* Grid of `res` cells per axis over a projected box, widened a little so every origin
 * is strictly inside. */
void pn_gears_bounds(pn_kgrid *g, float x0, float y0, float x1, float y1, uint32_t res)
{
    float ex = x1 - x0, ey = y1 - y0, m;
    if (!(ex >= 0.0f) || !(ey >= 0.0f)) {
        x0 = y0 = -1.0f;
        ex = ey = 2.0f;
    }
    m = pn_kmaxf(pn_kmaxf(ex, ey), 1e-6f * pn_kmaxf(pn_kmaxf(x0 < 0 ? -x0 : x0, y0 < 0 ? -y0 : y0), 1.0f));
    ex = pn_kmaxf(ex, 1e-3f * m);
    ey = pn_kmaxf(ey, 1e-3f * m);
    g->gx0 = x0 - 1e-3f * ex;
    g->gy0 = y0 - 1e-3f * ey;
    g->inv_cell_x = (float)res / (ex * 1.002f);
    g->inv_cell_y = (float)res / (ey * 1.002f);
    g->res_x = res;
    g->res_y = res;
}

/* uint64 -> float through two 32-bit halves: a bare-metal target converts those in
 * hardware, where a direct 64-bit conversion needs a libgcc helper. */
static float pn_u64_to_f32(uint64_t v)
{
    return (float)(uint32_t)(v >> 32) * 4294967296.0f + (float)(uint32_t)v;
}

/* The frame's pools at w x h: run by the frame on the frame region and by pn_gears_query
 * at the limits' maxima. The per-triangle and per-cell pools are the context's (its
 * triangles, its largest grid: the occupancy of six faces' rows, the cell tables of one
 * face), the pair pool what a tile may hold. */
static void pn_gears_carve(pn_carver *c, const pn_limits *l, uint32_t w, uint32_t h, pn_gears_frame_pools *g)
{
    uint64_t px = (uint64_t)w * h, gmax = pn_gears_grid_max(l), cmax = gmax * gmax, rmax = 6u * gmax;
    uint64_t W = pn_gears_row_words((uint32_t)gmax), pool = pn_gears_pairs_max(l);
    g->pool = (uint32_t)pool;
    g->faces = (pn_kfaces *)pn_pool(c, 1u, sizeof(pn_kfaces), "gears grid cameras");
    g->rects = (pn_cellrect *)pn_pool(c, l->max_triangles, 8u, "gears cell rects");
    g->pix_cell = (uint32_t *)pn_pool(c, px, 4u, "gears pixel cells");
    g->row_box = (float *)pn_pool(c, h, 32u, "gears row boxes");
    g->cell_bits = (uint32_t *)pn_pool(c, rmax * W, 4u, "gears cell occupancy");
    g->cell_rank = (uint32_t *)pn_pool(c, rmax * (W + 1u), 4u, "gears occupancy prefixes");
    g->cell_off = (uint32_t *)pn_pool(c, cmax + 1u, 4u, "gears cell offsets");
    g->cell_pix = (uint32_t *)pn_pool(c, cmax, 4u, "gears pixels per cell");
    g->cell_cur = (uint32_t *)pn_pool(c, cmax, 4u, "gears cell cursors");
    g->row_pairs = (uint32_t *)pn_pool(c, rmax, 8u, "gears pairs per row");
    g->sorted = (uint32_t *)pn_pool(c, pool, 4u, "gears sorted pairs");
    g->chunk_box = (float *)pn_pool(c, pool / PN_GEARS_CHUNK + 1u, 24u, "gears chunk boxes");
    g->super_box = (float *)pn_pool(c, pool / (PN_GEARS_CHUNK * PN_GEARS_SUPER) + 1u, 24u, "gears superchunk boxes");
}

/* PN_GEARS_BYTES_MAX (include/penumbra/penumbra.h) counts a 24-byte chunk box per 8 pairs
 * and a superchunk box per 64. */
typedef char pn_gears_chunk_is_8[(PN_GEARS_CHUNK == 8u && PN_GEARS_SUPER == 8u && sizeof(pn_kfaces) <= 576u) ? 1 : -1];

void pn_gears_query(pn_carver *c, const pn_limits *l)
{
    pn_gears_frame_pools g;
    pn_gears_carve(c, l, l->max_width, l->max_height, &g);
}

static pn_status pn_gears_begin(pn_frame_state *fs, pn_gears_frame_pools *g)
{
    pn_context *ctx = fs->ctx;
    pn_kpools *P = &fs->P;
    pn_carver c;
    memset(g, 0, sizeof(*g));
    pn_carver_frame(&c, ctx);
    pn_gears_carve(&c, &ctx->limits, fs->width, fs->height, g);
    if (!c.ok) return PN_E_POOL_EXHAUSTED;
    memset(g->faces, 0, sizeof(*g->faces));
    g->faces->res = fs->res;
    P->faces = pn_dev_off(ctx, g->faces);
    P->rects = pn_dev_off(ctx, g->rects);
    P->pix_cell = pn_dev_off(ctx, g->pix_cell);
    P->row_box = pn_dev_off(ctx, g->row_box);
    P->cell_bits = pn_dev_off(ctx, g->cell_bits);
    P->cell_rank = pn_dev_off(ctx, g->cell_rank);
    P->cell_off = pn_dev_off(ctx, g->cell_off);
    P->cell_pix = pn_dev_off(ctx, g->cell_pix);
    P->cell_cur = pn_dev_off(ctx, g->cell_cur);
    P->row_pairs = pn_dev_off(ctx, g->row_pairs);
    P->sorted = pn_dev_off(ctx, g->sorted);
    P->chunk_box = pn_dev_off(ctx, g->chunk_box);
    P->super_box = pn_dev_off(ctx, g->super_box);
    memset(&ctx->stats.gears, 0, sizeof(ctx->stats.gears));
    return PN_OK;
}

/* Joins the row boxes and lit counts of the origins pass; returns 0 when no pixel is lit
 * (nothing can be shadowed: the frame is done), else sets up the grid cameras (and, for a
 * point light, their bounds) and returns 1. */
static uint32_t pn_gears_cameras(pn_context *ctx, const pn_frame_state *fs, pn_gears_frame_pools *g)
{
    float obox[6];
    uint32_t y, f, G = g->faces->res;
    pn_box3_empty(obox);
    for (y = 0; y < fs->height; y++) {
        g->lit += ((const pn_row_counters *)fs->counters)[y].c.lit;
        pn_box_join_n(obox, g->row_box + (size_t)y * 8u, 6u);
    }
    if (g->lit == 0u) return 0;
    g->faces->n = pn_gears_faces(&fs->K.light, obox, ctx->scene_diag, g->faces->f);
    g->cells = G * G;
    g->rows = g->faces->n * G;
    g->face_ready = 6u;
    if (fs->K.light.is_point)
        for (f = 0; f < 6; f++) pn_gears_bounds(&g->faces->f[f], -1.0f, -1.0f, 1.0f, 1.0f, G);
    return 1;
}

/* Area light: the grid bounds from the projected row boxes. */
static void pn_gears_grid(const pn_frame_state *fs, pn_gears_frame_pools *g)
{
    float pb[4];
    uint32_t y;
    pn_box2_empty(pb);
    for (y = 0; y < fs->height; y++) pn_box_join_n(pb, g->row_box + (size_t)y * 8u, 4u);
    pn_gears_bounds(&g->faces->f[0], pb[0], pb[1], pb[2], pb[3], g->faces->res);
}

static uint64_t pn_row_pairs_at(const pn_gears_frame_pools *g, uint32_t r)
{
    return (uint64_t)g->row_pairs[2u * r] | ((uint64_t)g->row_pairs[2u * r + 1u] << 32);
}

static void pn_tile_set(pn_ktile *t, uint32_t face, uint32_t r0, uint32_t r1, uint32_t x0, uint32_t x1)
{
    memset(t, 0, sizeof(*t));
    t->face = face;
    t->r0 = r0;
    t->r1 = r1;
    t->x0 = x0;
    t->x1 = x1;
}

/* Tiles: runs of global grid rows (face * res + row) whose pairs fit the pool, within one
 * face (a tile never spans two), each face announced first (PN_GEARS_PLAN_FACE: its
 * rectangles and rows' pairs are computed then); a row that alone exceeds the pool goes
 * as runs of consecutive cells, its per-cell counts taken afresh before each run (the
 * tile before it used cell_cur). */
static pn_status pn_gears_plan_next(pn_context *ctx, pn_gears_frame_pools *g, pn_ktile *tile, uint32_t *action)
{
    uint32_t G = g->faces->res;
    for (;;) {
        if (g->plan_split) {
            uint32_t row = g->plan_start, face = row / G, ry = row % G, x, xe;
            const uint32_t *counts = g->cell_cur + (size_t)ry * G; /* the row's, pn_gears_count_cells */
            uint64_t sum = 0;
            if (g->plan_xs >= G) {
                g->plan_split = 0;
                g->plan_start++;
                continue;
            }
            if (!g->plan_counted) {
                pn_tile_set(tile, face, ry, ry, 0, G - 1u);
                g->plan_counted = 1;
                *action = PN_GEARS_PLAN_COUNT_ROW;
                return PN_OK;
            }
            for (x = 0; g->plan_xs == 0u && x < G; x++)
                if (counts[x] > g->pool)
                    return pn_fail(ctx, PN_E_POOL_EXHAUSTED,
                                   "GEARS pair pool 'gears pairs' holds %u pairs; cell %u of grid row %u alone "
                                   "needs %u (raise pn_limits.gears_pairs or PN_GEARS_PAIRS)",
                                   g->pool, x, row, counts[x]);
            for (xe = g->plan_xs; xe < G && sum + counts[xe] <= g->pool; xe++) sum += counts[xe];
            pn_tile_set(tile, face, ry, ry, g->plan_xs, xe - 1u);
            g->plan_xs = xe;
            g->plan_counted = 0;
            *action = PN_GEARS_PLAN_TILE;
            return PN_OK;
        }
        if (g->plan_s0 < g->plan_end) { /* a run never spans two faces */
            pn_tile_set(tile, g->plan_s0 / G, g->plan_s0 % G, (g->plan_end - 1u) % G, 0, G - 1u);
            g->plan_s0 = g->plan_end;
            *action = PN_GEARS_PLAN_TILE;
            return PN_OK;
        }
        if (g->plan_start >= g->rows) {
            *action = PN_GEARS_PLAN_DONE;
            return PN_OK;
        }
        if (g->plan_start / G != g->face_ready) { /* its rectangles and rows' pairs first */
            pn_tile_set(tile, g->plan_start / G, 0, G - 1u, 0, G - 1u);
            *action = PN_GEARS_PLAN_FACE;
            return PN_OK;
        }
        {
            uint64_t sum = 0;
            uint32_t r = g->plan_start, end = (g->plan_start / G + 1u) * G;
            while (r < end && sum + pn_row_pairs_at(g, r) <= g->pool) sum += pn_row_pairs_at(g, r++);
            if (r == g->plan_start) { /* this row alone exceeds the pool */
                g->plan_split = 1;
                g->plan_xs = 0;
                g->plan_counted = 0;
            } else {
                g->plan_s0 = g->plan_start;
                g->plan_end = r;
                g->plan_start = r;
            }
        }
    }
}

static pn_status pn_gears_tile_pairs(pn_context *ctx, pn_gears_frame_pools *g, uint64_t need)
{
    if (need > g->pool) return pn_fail(ctx, PN_E_INTERNAL, "GEARS tile plan exceeded the pair pool");
    g->tiles++;
    g->total_pairs += need;
    if (need > g->pairs_high) g->pairs_high = (uint32_t)need;
    return PN_OK;
}

/* The tile's cells, [c0, c1) of its face: their pairs, and the pairs times the pixels. */
static void pn_gears_tile_cells(pn_gears_frame_pools *g, uint32_t c0, uint32_t c1)
{
    uint32_t c;
    for (c = c0; c < c1; c++) {
        uint32_t n = g->cell_off[c + 1u] - g->cell_off[c];
        if (n && g->cell_pix[c]) {
            g->assignments += (uint64_t)n * g->cell_pix[c];
            g->sum_tris_cell += n;
            if (n > g->max_tris_cell) g->max_tris_cell = n;
        }
    }
}

/* The plan's next face (fs->K.tile.face; the plan visits every face, in order): every
 * triangle's rectangle of cells on it, the pairs of its grid rows (to the host, for the
 * plan), its pixels per cell (to the host) and their statistics. */
static pn_status pn_gears_face(pn_frame_state *fs, pn_gears_frame_pools *g)
{
    uint32_t c, face = fs->K.tile.face, G = g->faces->res, T = fs->ctx->tri_count;
    pn_status st;
    g->face_ready = face;
    if ((st = pn_dev_run(fs, PN_K_GEARS_TRI_RECTS, T)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_GEARS_ROW_PAIRS, T)) != PN_OK ||
        (st = pn_dev_to_host(fs, g->row_pairs + (size_t)face * G * 2u, (size_t)G * 8u)) != PN_OK ||
        (st = pn_dev_fill(fs, g->cell_pix, g->cells, 0u)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_GEARS_FACE_PIXELS, fs->width * fs->height)) != PN_OK ||
        (st = pn_dev_to_host(fs, g->cell_pix, (size_t)g->cells * 4u)) != PN_OK)
        return st;
    for (c = 0; c < g->cells; c++)
        if (g->cell_pix[c]) {
            g->cells_used++;
            if (g->cell_pix[c] > g->max_pix) g->max_pix = g->cell_pix[c];
        }
    return PN_OK;
}

static void pn_gears_end(pn_context *ctx, const pn_gears_frame_pools *g)
{
    uint32_t used = g->cells_used, max_pix = g->max_pix;
    ctx->stats.gears.pairs = g->total_pairs;
    ctx->stats.gears.assignments = g->assignments;
    ctx->stats.gears.tiles = g->tiles;
    ctx->stats.gears.faces = g->faces->n;
    ctx->stats.gears.grid = g->faces->res;
    ctx->stats.gears.cells_used = used;
    ctx->stats.gears.max_tris_per_cell = g->max_tris_cell;
    ctx->stats.gears.max_pixels_per_cell = max_pix;
    ctx->stats.gears.mean_tris_per_cell = used ? pn_u64_to_f32(g->sum_tris_cell) / (float)used : 0.0f;
    ctx->stats.gears.mean_pixels_per_cell = used ? pn_u64_to_f32(g->lit) / (float)used : 0.0f;
    ctx->stats.gears.pairs_high_water = g->pairs_high;
}

/* The pairs of each cell of the tile's grid rows into cell_cur (cells of its face):
 * each triangle's rectangle as differences per row, then each row's running sums, kept
 * where a cell holds pixels. */
static pn_status pn_gears_count_cells(pn_frame_state *fs, pn_gears_frame_pools *g)
{
    const pn_ktile *tl = &fs->K.tile;
    uint32_t rows = tl->r1 - tl->r0 + 1u;
    pn_status st;
    if ((st = pn_dev_fill(fs, g->cell_cur + (size_t)tl->r0 * g->faces->res, rows * g->faces->res, 0u)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_GEARS_COUNT, fs->K.raster_tris)) != PN_OK)
        return st;
    return pn_dev_run(fs, PN_K_GEARS_CELL_ROWS, rows);
}

/* One tile: pairs per cell (differences per row, then their running sums) -> exclusive
 * prefix sum (the offsets, to the host) -> each triangle into its cells' next slots ->
 * each cell's run sorted -> chunk and superchunk boxes -> masks. The runs come out in
 * raster order (work item r: the triangle rindex[r], entry r) on every port and thread
 * count: a sorted run of distinct values is unique; the chunk pass turns the entries into
 * triangle ids. The per-cell steps cover the tile's grid rows, [c0, c0 + C) of its face,
 * whose offsets start from 0 (a tile's list is the pool from its start): the cells of a
 * face cost once a frame, not once a tile. */
static pn_status pn_gears_tile(pn_frame_state *fs, pn_gears_frame_pools *g)
{
    const pn_ktile *tl = &fs->K.tile;
    uint32_t R = fs->K.raster_tris; /* every triangle but the degenerate */
    uint32_t c0 = tl->r0 * g->faces->res, C = (tl->r1 - tl->r0 + 1u) * g->faces->res, n;
    uint32_t *cur = g->cell_cur + c0, *off = g->cell_off + c0;
    pn_status st;
    if ((st = pn_gears_count_cells(fs, g)) != PN_OK || (st = pn_dev_copy(fs, off, cur, (size_t)C * 4u)) != PN_OK ||
        (st = pn_dev_scan(fs, off, C)) != PN_OK ||
        (st = pn_dev_to_host(fs, off, ((size_t)C + 1u) * 4u)) != PN_OK ||
        (st = pn_gears_tile_pairs(fs->ctx, g, off[C])) != PN_OK)
        return st;
    n = off[C];
    if ((st = pn_dev_copy(fs, cur, off, (size_t)C * 4u)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_GEARS_SCATTER, R)) != PN_OK ||
        (st = pn_dev_sort_runs(fs, g->sorted, off, C)) != PN_OK)
        return st;
    pn_gears_tile_cells(g, c0, c0 + C);
    fs->K.tile.pairs = n;
    if ((st = pn_dev_run(fs, PN_K_GEARS_CHUNKS, (n + PN_GEARS_CHUNK * PN_GEARS_SUPER - 1u) /
                                                    (PN_GEARS_CHUNK * PN_GEARS_SUPER))) != PN_OK)
        return st;
    return pn_dev_run(fs, PN_K_GEARS_MASKS, fs->width * fs->height);
}

pn_status pn_gears_frame(pn_frame_state *fs)
{
    pn_context *ctx = fs->ctx;
    pn_gears_frame_pools g;
    uint32_t H = fs->height, action = PN_GEARS_PLAN_DONE;
    pn_status st;

    if ((st = pn_gears_begin(fs, &g)) != PN_OK) return st;

    /* A.1/A.2: origins, cameras, grid bounds, pixel cells. */
    if ((st = pn_dev_run(fs, PN_K_GEARS_ORIGINS, H)) != PN_OK ||
        (st = pn_dev_to_host(fs, g.row_box, (size_t)H * 32u)) != PN_OK ||
        (st = pn_dev_to_host(fs, fs->counters, (size_t)H * sizeof(pn_row_counters))) != PN_OK)
        return st;
    if (!pn_gears_cameras(ctx, fs, &g)) return PN_OK;
    if ((st = pn_dev_to_device(fs, g.faces, sizeof(pn_kfaces))) != PN_OK) return st;
    if (!fs->K.light.is_point) {
        if ((st = pn_dev_run(fs, PN_K_GEARS_PROJECT, H)) != PN_OK ||
            (st = pn_dev_to_host(fs, g.row_box, (size_t)H * 32u)) != PN_OK)
            return st;
        pn_gears_grid(fs, &g);
        if ((st = pn_dev_to_device(fs, g.faces, sizeof(pn_kfaces))) != PN_OK) return st;
    }
    if ((st = pn_dev_fill(fs, g.cell_bits, g.rows * pn_gears_row_words(g.faces->res), 0u)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_GEARS_PIXEL_CELLS, fs->width * H)) != PN_OK ||
        (st = pn_dev_run(fs, PN_K_GEARS_ROW_PREFIX, g.rows)) != PN_OK)
        return st;

    /* A.3 (face by face, as the plan reaches each): the triangles' rectangles of cells,
     * the pairs per grid row; then the tiles. */
    if ((st = pn_dev_fill(fs, g.row_pairs, g.rows * 2u, 0u)) != PN_OK) return st;
    for (;;) {
        if ((st = pn_gears_plan_next(ctx, &g, &fs->K.tile, &action)) != PN_OK) return st;
        if (action == PN_GEARS_PLAN_DONE) break;
        if (action == PN_GEARS_PLAN_FACE) {
            if ((st = pn_gears_face(fs, &g)) != PN_OK) return st;
        } else if (action == PN_GEARS_PLAN_COUNT_ROW) {
            if ((st = pn_gears_count_cells(fs, &g)) != PN_OK ||
                (st = pn_dev_to_host(fs, g.cell_cur + (size_t)fs->K.tile.r0 * g.faces->res,
                                     (size_t)g.faces->res * 4u)) != PN_OK)
                return st;
        } else if ((st = pn_gears_tile(fs, &g)) != PN_OK) {
            return st;
        }
    }
    pn_gears_end(ctx, &g);
    return PN_OK;
}

PN_ALGO_NO_SCENE(gears)
#else
PN_ALGO_STUBS(GEARS, gears)
#endif
