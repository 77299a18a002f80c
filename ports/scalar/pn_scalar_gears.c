/* pn_scalar_gears.c - GEARS on the scalar port (paper §3-4): origins -> grid cameras ->
 * pixel cells -> triangle cell rectangles -> per tile: pair counts, exclusive prefix sum,
 * scatter of (cell, triangle) pairs, counting sort by cell -> per-pixel masks.
 * Work items write disjoint memory; the serial steps (prefix sums, the stable counting
 * sort, tile planning) run on the calling thread, so the result and every statistic are
 * independent of the schedule. */
#include <string.h>

#include "pn_gears_host.h"
#include "pn_scalar.h"

#if PN_ENABLE_GEARS

#define PN_TRI_CHUNK 4096u

typedef struct pn_gears_run {
    pn_context *ctx;
    pn_frame_state *fs;
    pn_kgrid faces[6];
    uint32_t nfaces, res;
    pn_cellrect *rects;   /* [tri * 6 + face] */
    uint32_t *tri_off;    /* [tri + 1] */
    uint32_t *pix_cell;   /* global cell or PN_CELL_NONE */
    float *row_box;       /* 8 floats per row */
    uint32_t *cell_off;   /* [cells + 1] for the current tile */
    uint32_t *cell_pix;   /* pixels per cell */
    uint32_t *cell_cur;
    uint64_t *row_pairs;  /* pairs per global grid row */
    uint32_t *pairs;      /* (cell, tri) */
    uint32_t *sorted;     /* tris by cell */
    /* current tile: face, rows [r0, r1], columns [x0, x1] */
    uint32_t tf, tr0, tr1, tx0, tx1;
    uint32_t chunks, cells;
    uint64_t pool;
    /* statistics over all tiles */
    uint64_t total_pairs, assignments, sum_tris_cell;
    uint32_t tiles, pairs_high, max_tris_cell;
} pn_gears_run;

/* uint64 -> float through two 32-bit halves: a bare-metal target converts those in
 * hardware, where a direct 64-bit conversion needs a libgcc helper. */
static float pn_u64_to_f32(uint64_t v)
{
    return (float)(uint32_t)(v >> 32) * 4294967296.0f + (float)(uint32_t)v;
}

static pn_v3 pn_g3(const float *a, size_t i) { return pn_v3_make(a[i * 3u], a[i * 3u + 1u], a[i * 3u + 2u]); }

/* Shadow-ray origin of a pixel, or 0 when the pixel has no triangle or cannot see the
 * light (its visibility is then final: 1 or 0). */
static int pn_pixel_origin(const pn_frame_state *fs, size_t pix, pn_v3 *O)
{
    if (fs->tri_id[pix] == PN_NO_TRIANGLE) return 0;
    return pn_shadow_origin(pn_g3(fs->pos, pix), pn_g3(fs->nrm, pix), &fs->light, O);
}

static void pn_task_origins(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    uint32_t y, x;
    for (y = begin; y < end; y++) {
        float *b = r->row_box + (size_t)y * 8u;
        pn_shadow_counters *cnt = (pn_shadow_counters *)fs->counters + y;
        memset(cnt, 0, sizeof(*cnt));
        pn_box3_empty(b);
        for (x = 0; x < fs->width; x++) {
            size_t pix = (size_t)y * fs->width + x;
            pn_v3 O;
            if (!pn_pixel_origin(fs, pix, &O)) {
                fs->vis[pix] = fs->tri_id[pix] == PN_NO_TRIANGLE ? 1.0f : 0.0f;
                continue;
            }
            fs->vis[pix] = 1.0f; /* until a tile's triangles block samples */
            cnt->lit++;
            pn_box3_add(b, O);
        }
    }
}

static void pn_task_project(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    uint32_t y, x;
    for (y = begin; y < end; y++) {
        float *b = r->row_box + (size_t)y * 8u;
        pn_box2_empty(b);
        for (x = 0; x < fs->width; x++) {
            size_t pix = (size_t)y * fs->width + x;
            pn_v3 O;
            float px, py;
            if (!pn_pixel_origin(fs, pix, &O)) continue;
            pn_grid_project(&r->faces[0], O, &px, &py);
            pn_box2_add(b, px, py);
        }
    }
}

static void pn_task_pixel_cells(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    uint32_t y, x, cells = r->res * r->res;
    for (y = begin; y < end; y++)
        for (x = 0; x < fs->width; x++) {
            size_t pix = (size_t)y * fs->width + x;
            pn_v3 O;
            float px, py;
            uint32_t f;
            if (!pn_pixel_origin(fs, pix, &O)) {
                r->pix_cell[pix] = PN_CELL_NONE;
                continue;
            }
            f = pn_gears_origin_face(&fs->light, O);
            pn_grid_project(&r->faces[f], O, &px, &py);
            r->pix_cell[pix] = f * cells + pn_grid_cell(&r->faces[f], px, py);
        }
}

static void pn_task_tri_rects(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t n = r->ctx->tri_count, c;
    for (c = begin; c < end; c++) {
        uint32_t t, t1 = (c + 1u) * PN_TRI_CHUNK < n ? (c + 1u) * PN_TRI_CHUNK : n, f;
        for (t = c * PN_TRI_CHUNK; t < t1; t++) {
            pn_v3 A, B, C;
            if (r->ctx->flags[t] & PN_TRI_DEGENERATE) {
                for (f = 0; f < r->nfaces; f++) r->rects[(size_t)t * 6u + f] = pn_cellrect_empty();
                continue;
            }
            pn_tri_load(r->ctx->tris, t, &A, &B, &C);
            for (f = 0; f < r->nfaces; f++)
                r->rects[(size_t)t * 6u + f] = pn_gears_tri_cells(&r->faces[f], &r->fs->light, A, B, C);
        }
    }
}

/* The triangle's rectangle on the current tile's face, clipped to the tile. */
static int pn_tile_rect(const pn_gears_run *r, uint32_t t, uint32_t *x0, uint32_t *y0, uint32_t *x1, uint32_t *y1)
{
    pn_cellrect rc = r->rects[(size_t)t * 6u + r->tf];
    if (pn_cellrect_is_empty(rc)) return 0;
    *x0 = rc.lo & 0xFFFFu;
    *y0 = rc.lo >> 16;
    *x1 = rc.hi & 0xFFFFu;
    *y1 = rc.hi >> 16;
    if (*y0 < r->tr0) *y0 = r->tr0;
    if (*y1 > r->tr1) *y1 = r->tr1;
    if (*x0 < r->tx0) *x0 = r->tx0;
    if (*x1 > r->tx1) *x1 = r->tx1;
    return *x0 <= *x1 && *y0 <= *y1;
}

/* Pairs are made only for cells that hold pixels (paper §5.4: cells where no pixel
 * sample projects are discarded). */
static void pn_task_count(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t n = r->ctx->tri_count, c, base = r->tf * r->res * r->res;
    for (c = begin; c < end; c++) {
        uint32_t t, t1 = (c + 1u) * PN_TRI_CHUNK < n ? (c + 1u) * PN_TRI_CHUNK : n;
        for (t = c * PN_TRI_CHUNK; t < t1; t++) {
            uint32_t x0, y0, x1, y1, x, y, cnt = 0;
            if (pn_tile_rect(r, t, &x0, &y0, &x1, &y1))
                for (y = y0; y <= y1; y++)
                    for (x = x0; x <= x1; x++) cnt += r->cell_pix[base + y * r->res + x] != 0u;
            r->tri_off[t] = cnt;
        }
    }
}

static void pn_task_scatter(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    uint32_t n = r->ctx->tri_count, c, base = r->tf * r->res * r->res;
    for (c = begin; c < end; c++) {
        uint32_t t, t1 = (c + 1u) * PN_TRI_CHUNK < n ? (c + 1u) * PN_TRI_CHUNK : n;
        for (t = c * PN_TRI_CHUNK; t < t1; t++) {
            uint32_t x0, y0, x1, y1, x, y, o = r->tri_off[t];
            if (!pn_tile_rect(r, t, &x0, &y0, &x1, &y1)) continue;
            for (y = y0; y <= y1; y++)
                for (x = x0; x <= x1; x++) {
                    uint32_t cell = base + y * r->res + x;
                    if (!r->cell_pix[cell]) continue;
                    r->pairs[(size_t)o * 2u] = cell;
                    r->pairs[(size_t)o * 2u + 1u] = t;
                    o++;
                }
        }
    }
}

static int pn_in_tile(const pn_gears_run *r, uint32_t cell)
{
    uint32_t cells = r->res * r->res, f = cell / cells, local = cell % cells;
    uint32_t y = local / r->res, x = local % r->res;
    return f == r->tf && y >= r->tr0 && y <= r->tr1 && x >= r->tx0 && x <= r->tx1;
}

static void pn_task_masks(void *task, uint32_t begin, uint32_t end)
{
    pn_gears_run *r = (pn_gears_run *)task;
    pn_frame_state *fs = r->fs;
    pn_context *ctx = r->ctx;
    uint32_t y, x, k = fs->light.k;
    for (y = begin; y < end; y++) {
        pn_shadow_counters *cnt = (pn_shadow_counters *)fs->counters + y;
        for (x = 0; x < fs->width; x++) {
            size_t pix = (size_t)y * fs->width + x;
            uint32_t cell = r->pix_cell[pix], e, own = fs->tri_id[pix];
            uint32_t m[PN_MASK_WORDS_MAX];
            pn_frustum fr;
            pn_v3 O;
            /* A pixel has a cell only if it has an origin. */
            if (cell == PN_CELL_NONE || !pn_in_tile(r, cell) || !pn_pixel_origin(fs, pix, &O)) continue;
            pn_mask_clear(m);
            pn_frustum_make(O, &fs->light, &fr);
            for (e = r->cell_off[cell]; e < r->cell_off[cell + 1u]; e++) {
                uint32_t t = r->sorted[e];
                pn_v3 A, B, C;
                pn_kbvh_node box;
                if (t == own) continue;
                pn_tri_load(ctx->tris, t, &A, &B, &C);
                /* The reference's conservative frustum test, on the triangle's own box:
                 * a cheap reject before the predicate. */
                box.bmin[0] = pn_kminf(A.x, pn_kminf(B.x, C.x));
                box.bmin[1] = pn_kminf(A.y, pn_kminf(B.y, C.y));
                box.bmin[2] = pn_kminf(A.z, pn_kminf(B.z, C.z));
                box.bmax[0] = pn_kmaxf(A.x, pn_kmaxf(B.x, C.x));
                box.bmax[1] = pn_kmaxf(A.y, pn_kmaxf(B.y, C.y));
                box.bmax[2] = pn_kmaxf(A.z, pn_kmaxf(B.z, C.z));
                if (!pn_frustum_box(&fr, &box)) continue;
                cnt->candidates++;
                cnt->blocking += pn_tri_mask(O, A, B, C, &fs->light, m);
                if (!fs->exact_stats && pn_mask_full(m, k)) break;
            }
            fs->vis[pix] = pn_mask_visibility(m, k);
        }
    }
}

/* One tile: count -> exclusive prefix sum -> scatter -> counting sort by cell -> masks. */
static pn_status pn_gears_tile(pn_gears_run *r, uint32_t face, uint32_t r0, uint32_t r1, uint32_t x0, uint32_t x1)
{
    pn_context *ctx = r->ctx;
    uint32_t T = ctx->tri_count, t, c, acc = 0;
    uint64_t need = 0;
    r->tf = face;
    r->tr0 = r0;
    r->tr1 = r1;
    r->tx0 = x0;
    r->tx1 = x1;
    pn_run(ctx, r->chunks, pn_task_count, r);
    for (t = 0; t < T; t++) {
        uint32_t n = r->tri_off[t];
        r->tri_off[t] = (uint32_t)need;
        need += n;
    }
    r->tri_off[T] = (uint32_t)need;
    if (need > r->pool) return pn_fail(ctx, PN_E_INTERNAL, "GEARS tile plan exceeded the pair pool");
    r->tiles++;
    r->total_pairs += need;
    if (need > r->pairs_high) r->pairs_high = (uint32_t)need;
    pn_run(ctx, r->chunks, pn_task_scatter, r);
    memset(r->cell_cur, 0, (size_t)r->cells * 4u);
    for (t = 0; t < (uint32_t)need; t++) r->cell_cur[r->pairs[(size_t)t * 2u]]++;
    for (c = 0; c < r->cells; c++) {
        uint32_t n = r->cell_cur[c];
        r->cell_off[c] = acc;
        r->cell_cur[c] = acc;
        acc += n;
        if (n && r->cell_pix[c]) {
            r->assignments += (uint64_t)n * r->cell_pix[c];
            r->sum_tris_cell += n;
            if (n > r->max_tris_cell) r->max_tris_cell = n;
        }
    }
    r->cell_off[r->cells] = acc;
    /* Stable: pairs are in triangle order, so each cell lists its triangles ascending. */
    for (t = 0; t < (uint32_t)need; t++) r->sorted[r->cell_cur[r->pairs[(size_t)t * 2u]]++] = r->pairs[(size_t)t * 2u + 1u];
    pn_run(ctx, r->fs->height, pn_task_masks, r);
    return PN_OK;
}

/* Pairs per cell of one grid row, into cell_cur[0 .. res). */
static void pn_row_cell_counts(pn_gears_run *r, uint32_t face, uint32_t ry)
{
    uint32_t t, x;
    memset(r->cell_cur, 0, (size_t)r->res * 4u);
    for (t = 0; t < r->ctx->tri_count; t++) {
        pn_cellrect rc = r->rects[(size_t)t * 6u + face];
        if (pn_cellrect_is_empty(rc) || ry < (rc.lo >> 16) || ry > (rc.hi >> 16)) continue;
        for (x = rc.lo & 0xFFFFu; x <= (rc.hi & 0xFFFFu); x++)
            r->cell_cur[x] += r->cell_pix[(face * r->res + ry) * r->res + x] != 0u;
    }
}

/* A grid row whose pairs alone exceed the pool: tiles of consecutive cells of the row.
 * (cell_cur is the tile's histogram too, so the row's counts are taken again per run.) */
static pn_status pn_gears_split_row(pn_gears_run *r, uint32_t row)
{
    uint32_t G = r->res, face = row / G, ry = row % G, x, xs = 0;
    pn_status st;
    pn_row_cell_counts(r, face, ry);
    for (x = 0; x < G; x++)
        if (r->cell_cur[x] > r->pool)
            return pn_fail(r->ctx, PN_E_POOL_EXHAUSTED,
                           "GEARS pair pool 'gears pairs' holds %u pairs; cell %u of grid row %u alone "
                           "needs %u (raise pn_limits.gears_pairs or PN_GEARS_PAIRS)",
                           (uint32_t)r->pool, x, row, r->cell_cur[x]);
    while (xs < G) {
        uint64_t sum = 0;
        uint32_t xe = xs;
        if (xs > 0) pn_row_cell_counts(r, face, ry);
        while (xe < G && sum + r->cell_cur[xe] <= r->pool) sum += r->cell_cur[xe++];
        if ((st = pn_gears_tile(r, face, ry, ry, xs, xe - 1u)) != PN_OK) return st;
        xs = xe;
    }
    return PN_OK;
}

pn_status pn_scalar_gears(pn_context *ctx, pn_frame_state *fs)
{
    pn_gears_run r;
    size_t px = (size_t)fs->width * fs->height, p;
    uint32_t T = ctx->tri_count, G = fs->gears_grid;
    uint32_t y, f, t, rows, start, used_cells = 0, max_pix_cell = 0;
    uint64_t lit = 0;
    float obox[6];
    pn_status st;

    memset(&r, 0, sizeof(r));
    r.ctx = ctx;
    r.fs = fs;
    r.res = G;
    r.chunks = (T + PN_TRI_CHUNK - 1u) / PN_TRI_CHUNK;
    r.pool = pn_gears_pairs_max(&ctx->limits);
    {
        /* Same pools, same order as pn_frame_pools() in src/pn_arena.c. */
        uint32_t gmax = pn_gears_grid_max(&ctx->limits);
        size_t cmax = 6u * (size_t)gmax * gmax;
        if (!(r.rects = (pn_cellrect *)pn_frame_alloc(ctx, ctx->limits.max_triangles, 6u * 8u, "gears cell rects")) ||
            !(r.tri_off = (uint32_t *)pn_frame_alloc(ctx, (size_t)ctx->limits.max_triangles + 1u, 4u, "gears pair offsets")) ||
            !(r.pix_cell = (uint32_t *)pn_frame_alloc(ctx, px, 4u, "gears pixel cells")) ||
            !(r.row_box = (float *)pn_frame_alloc(ctx, fs->height, 32u, "gears row boxes")) ||
            !(r.cell_off = (uint32_t *)pn_frame_alloc(ctx, cmax + 1u, 4u, "gears cell offsets")) ||
            !(r.cell_pix = (uint32_t *)pn_frame_alloc(ctx, cmax, 4u, "gears pixels per cell")) ||
            !(r.cell_cur = (uint32_t *)pn_frame_alloc(ctx, cmax, 4u, "gears cell cursors")) ||
            !(r.row_pairs = (uint64_t *)pn_frame_alloc(ctx, 6u * (size_t)gmax, 8u, "gears pairs per row")) ||
            !(r.pairs = (uint32_t *)pn_frame_alloc(ctx, r.pool, 8u, "gears pairs")) ||
            !(r.sorted = (uint32_t *)pn_frame_alloc(ctx, r.pool, 4u, "gears sorted pairs")))
            return PN_E_POOL_EXHAUSTED;
    }
    memset(&ctx->gears, 0, sizeof(ctx->gears));

    /* A.1/A.2: origins, cameras, grid bounds, pixel cells. */
    pn_run(ctx, fs->height, pn_task_origins, &r);
    pn_box3_empty(obox);
    for (y = 0; y < fs->height; y++) {
        lit += ((pn_shadow_counters *)fs->counters)[y].lit;
        pn_box_join_n(obox, r.row_box + (size_t)y * 8u, 6u);
    }
    if (lit == 0u) return PN_OK; /* nothing can be shadowed */
    r.nfaces = pn_gears_faces(&fs->light, obox, ctx->scene_diag, r.faces);
    if (fs->light.is_point) {
        for (f = 0; f < 6; f++) pn_gears_bounds(&r.faces[f], -1.0f, -1.0f, 1.0f, 1.0f, G);
    } else {
        float pb[4];
        pn_box2_empty(pb);
        pn_run(ctx, fs->height, pn_task_project, &r);
        for (y = 0; y < fs->height; y++) pn_box_join_n(pb, r.row_box + (size_t)y * 8u, 4u);
        pn_gears_bounds(&r.faces[0], pb[0], pb[1], pb[2], pb[3], G);
    }
    pn_run(ctx, fs->height, pn_task_pixel_cells, &r);
    r.cells = r.nfaces * G * G;
    memset(r.cell_pix, 0, (size_t)r.cells * 4u);
    for (p = 0; p < px; p++)
        if (r.pix_cell[p] != PN_CELL_NONE) r.cell_pix[r.pix_cell[p]]++;

    /* A.3: every triangle's rectangle of cells on every face. */
    pn_run(ctx, r.chunks, pn_task_tri_rects, &r);

    /* Tile plan: runs of global grid rows whose pairs fit the pool. */
    rows = r.nfaces * G;
    memset(r.row_pairs, 0, (size_t)rows * 8u);
    for (t = 0; t < T; t++)
        for (f = 0; f < r.nfaces; f++) {
            pn_cellrect rc = r.rects[(size_t)t * 6u + f];
            uint32_t yy;
            if (pn_cellrect_is_empty(rc)) continue;
            for (yy = rc.lo >> 16; yy <= rc.hi >> 16; yy++) {
                const uint32_t *cp = r.cell_pix + (size_t)(f * G + yy) * G;
                uint32_t xx;
                for (xx = rc.lo & 0xFFFFu; xx <= (rc.hi & 0xFFFFu); xx++) r.row_pairs[f * G + yy] += cp[xx] != 0u;
            }
        }
    for (start = 0; start < rows;) {
        uint32_t end, s0;
        if (!pn_gears_next_tile(r.row_pairs, rows, start, r.pool, &end)) {
            if ((st = pn_gears_split_row(&r, start)) != PN_OK) return st;
            start++;
            continue;
        }
        for (s0 = start; s0 < end;) { /* a tile never spans two faces */
            uint32_t face = s0 / G, e0 = (face + 1u) * G < end ? (face + 1u) * G : end;
            if ((st = pn_gears_tile(&r, face, s0 % G, (e0 - 1u) % G, 0, G - 1u)) != PN_OK) return st;
            s0 = e0;
        }
        start = end;
    }

    for (p = 0; p < r.cells; p++)
        if (r.cell_pix[p]) {
            used_cells++;
            if (r.cell_pix[p] > max_pix_cell) max_pix_cell = r.cell_pix[p];
        }
    ctx->gears.pairs = r.total_pairs;
    ctx->gears.assignments = r.assignments;
    ctx->gears.tiles = r.tiles;
    ctx->gears.faces = r.nfaces;
    ctx->gears.cells_used = used_cells;
    ctx->gears.max_tris = r.max_tris_cell;
    ctx->gears.max_pix = max_pix_cell;
    ctx->gears.mean_tris = used_cells ? pn_u64_to_f32(r.sum_tris_cell) / (float)used_cells : 0.0f;
    ctx->gears.mean_pix = used_cells ? pn_u64_to_f32(lit) / (float)used_cells : 0.0f;
    ctx->gears.pairs_high = r.pairs_high;
    return PN_OK;
}

#endif
