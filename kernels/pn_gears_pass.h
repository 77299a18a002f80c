/* pn_gears_pass.h - the work items of a GEARS frame (paper §3-4), behind the GEARS entries
 * of kernels/pn_passes.h that both ports run. The frame that sequences them with its host
 * steps (grid cameras, tile plan, statistics) is src/pn_gears.c.
 *
 *   per row       origins (visibility start, lit count, box of origins), projected box
 *   per pixel     grid cell of the pixel's origin, and that cell's occupancy bit
 *   per grid row  the prefix count of its cells that hold pixels, a word at a time
 *   per pixel     (once a face) its cell's pixel count, in the face's own tables
 *   per triangle  cell rectangle on a face and pairs per grid row (tile plan), a face at
 *                 a time; pairs per cell of a tile's rows (or of one grid row split into
 *                 runs of cells), then each into its cell's next slot (a sort of each
 *                 cell's run between the tile's passes makes the order the raster order)
 *   per superchunk  the boxes of 8 consecutive list entries (a chunk) and of 64 (a
 *                 superchunk), after the sort by cell
 *   per pixel     the mask of the pixel's cell's triangles, chunk by chunk
 *
 * Counts that many work items add to (pixels per cell, pairs per row or cell) use
 * pn_katomic_add: integer sums, the same whatever the order; the occupancy bits
 * pn_katomic_or, the same; a cell's slots are handed out by pn_katomic_add in any order
 * and its run sorted after.
 *
 * Tables. Per global grid row (face * res + row), for every face: the occupancy bits (a
 * bit a cell, pn_gears_row_words words a row), their prefix counts (a word a bitmap word,
 * and the row's total) and the row's pairs. Per cell, for one face at a time (a tile never
 * spans two): its pixels, the tile's pair offsets and its counts, then cursors, indexed by
 * the cell within its face. Per triangle its rectangle on that face. Per pair its entry
 * (4 bytes) and its part of a chunk's and a superchunk's box. Against three tables over
 * every face's cells, a fourth of prefix counts a word a cell, six rectangles a triangle,
 * a (cell, entry) pair besides each entry and a count a triangle: docs/bench/MEMORY.md. */
#ifndef PN_GEARS_PASS_H
#define PN_GEARS_PASS_H

#include "pn_gears.h"
#include "pn_kpools.h"
#include "pn_raster.h"
#include "pn_reference.h"

/* The grid cameras of a frame: n faces (1 area light, 6 point light) of res x res cells. */
typedef struct pn_kfaces {
    pn_kgrid f[6];
    uint32_t n, res, pad0, pad1;
} pn_kfaces;

/* Shadow-ray origin of a pixel, or 0 when the pixel has no triangle or cannot see the
 * light (its visibility is then final: 1 or 0). */
PN_KFN int pn_gears_origin(const pn_klight *L, const pn_ksurf *S, size_t pix, pn_v3 *O)
{
    pn_v3 P, n;
    if (S->tri_id[pix] == 0xFFFFFFFFu) return 0;
    pn_surf_at(S, pix, &P, &n);
    return pn_shadow_origin(P, n, L, O);
}

/* Row y: visibility of final pixels (background 1, facing away 0) and 1 for the rest
 * until a tile's triangles block samples; the row's counters (lit pixels); the 3-D box of
 * its origins into row_box[y * 8 ..]. */
PN_KFN void pn_gears_origins_row(const pn_klight *L, uint32_t width, uint32_t y, const pn_ksurf *S, PN_GLOBAL float *vis,
                                 PN_GLOBAL float *row_box, PN_GLOBAL pn_row_counters *cnt)
{
    float b[6];
    uint32_t x, i, lit = 0;
    pn_box3_empty(b);
    for (x = 0; x < width; x++) {
        size_t pix = (size_t)y * width + x;
        pn_v3 O;
        if (!pn_gears_origin(L, S, pix, &O)) {
            vis[pix] = S->tri_id[pix] == 0xFFFFFFFFu ? 1.0f : 0.0f;
            continue;
        }
        vis[pix] = 1.0f;
        lit++;
        pn_box3_add(b, O);
    }
    for (i = 0; i < 6u; i++) row_box[(size_t)y * 8u + i] = b[i];
    cnt[y].c.candidates = 0u;
    cnt[y].c.blocking = 0u;
    cnt[y].c.lit = lit;
    cnt[y].c.overflow = 0u;
    cnt[y].c.capped = 0u;
}

/* Row y: the 2-D box of its origins projected by the area light's grid camera. */
PN_KFN void pn_gears_project_row(const pn_klight *L, const pn_kgrid *g, uint32_t width, uint32_t y,
                                 const pn_ksurf *S, PN_GLOBAL float *row_box)
{
    float b[4];
    uint32_t x, i;
    pn_box2_empty(b);
    for (x = 0; x < width; x++) {
        pn_v3 O;
        if (pn_gears_origin(L, S, (size_t)y * width + x, &O)) pn_box_add(g, O, b);
    }
    for (i = 0; i < 4u; i++) row_box[(size_t)y * 8u + i] = b[i];
}

/* Words of a grid row's occupancy bits. */
PN_KFN uint32_t pn_gears_row_words(uint32_t res) { return (res + 31u) >> 5; }

/* Pixel pix: its global cell (face * res^2 + cell) or PN_CELL_NONE, and that cell's
 * occupancy bit set (occ zeroed beforehand). */
PN_KFN void pn_gears_pixel_cell(const pn_klight *L, PN_CONST pn_kfaces *F, const pn_ksurf *S, size_t pix,
                                PN_GLOBAL uint32_t *pix_cell, PN_GLOBAL uint32_t *occ)
{
    pn_v3 O;
    pn_kgrid g;
    float px, py;
    uint32_t f, in_face, x, r;
    if (!pn_gears_origin(L, S, pix, &O)) {
        pix_cell[pix] = PN_CELL_NONE;
        return;
    }
    f = pn_gears_origin_face(L, O);
    g = F->f[f]; /* the faces live in the arena: a private copy for the helpers */
    pn_grid_project(&g, O, &px, &py);
    in_face = pn_grid_cell(&g, px, py);
    pix_cell[pix] = f * F->res * F->res + in_face;
    r = f * F->res + in_face / F->res;
    x = in_face % F->res;
    pn_katomic_or(&occ[(size_t)r * pn_gears_row_words(F->res) + (x >> 5)], 1u << (x & 31u));
}

/* Pixel pix, if its cell lies on face `face`: one more pixel in that cell's count,
 * cell_pix[cell within the face] (zeroed beforehand). */
PN_KFN void pn_gears_face_pixel(PN_CONST uint32_t *pix_cell, uint32_t res, uint32_t face, size_t pix,
                                PN_GLOBAL uint32_t *cell_pix)
{
    uint32_t cell = pix_cell[pix], cells = res * res;
    if (cell != PN_CELL_NONE && cell / cells == face) pn_katomic_add(&cell_pix[cell % cells], 1u);
}

/* Triangle t: its rectangle of cells on face `face` (A.3), rects[t]. */
PN_KFN void pn_gears_tri_rects(PN_CONST pn_kfaces *F, const pn_klight *L, PN_CONST float *tris,
                               PN_CONST uint8_t *flags, uint32_t face, uint32_t t, PN_GLOBAL pn_cellrect *rects)
{
    pn_v3 A, B, C;
    pn_kgrid g;
    if (flags[t] & PN_TRI_DEGENERATE) {
        rects[t] = pn_cellrect_empty();
        return;
    }
    pn_tri_load(tris, t, &A, &B, &C);
    g = F->f[face];
    rects[t] = pn_gears_tri_cells(&g, L, A, B, C);
}

/* Global grid row r (face * res + row): occ_pre[r * (W + 1) + w] = the cells of the row
 * in words before w that hold pixels, w = 0 .. W (W = pn_gears_row_words). */
PN_KFN void pn_gears_row_prefix(PN_CONST uint32_t *occ, uint32_t res, uint32_t r, PN_GLOBAL uint32_t *occ_pre)
{
    uint32_t W = pn_gears_row_words(res), w, n = 0;
    PN_CONST uint32_t *bits = occ + (size_t)r * W;
    PN_GLOBAL uint32_t *pre = occ_pre + (size_t)r * (W + 1u);
    for (w = 0; w < W; w++) {
        pre[w] = n;
        n += pn_kpopcount(bits[w]);
    }
    pre[W] = n;
}

/* The cells of global grid row r left of column x (0 .. res) that hold pixels. */
PN_KFN uint32_t pn_gears_rank(PN_CONST uint32_t *occ, PN_CONST uint32_t *occ_pre, uint32_t res, uint32_t r, uint32_t x)
{
    uint32_t W = pn_gears_row_words(res), w = x >> 5, b = x & 31u;
    uint32_t n = occ_pre[(size_t)r * (W + 1u) + w];
    if (b) n += pn_kpopcount(occ[(size_t)r * W + w] & ((1u << b) - 1u));
    return n;
}

/* The bits x0 .. x1 (x0 <= x1 within one word) of a word. */
PN_KFN uint32_t pn_gears_bits(uint32_t word, uint32_t x0, uint32_t x1)
{
    return word & (0xFFFFFFFFu << (x0 & 31u)) & (0xFFFFFFFFu >> (31u - (x1 & 31u)));
}

/* Pairs are made only for cells that hold pixels (paper §5.4: cells where no pixel
 * sample projects are discarded). Pairs of rectangle row y, columns [x0, x1]: the set bits
 * of the row's occupancy there, by one word's count when the columns lie in one word,
 * else two ranks (pn_gears_row_prefix), instead of a walk over the columns (the dragon at
 * 512x512: the walks of the row-pairs and count passes were 5% of the run). */
PN_KFN uint32_t pn_gears_row_count(PN_CONST uint32_t *occ, PN_CONST uint32_t *occ_pre, uint32_t res, uint32_t face,
                                   uint32_t y, uint32_t x0, uint32_t x1)
{
    uint32_t r = face * res + y;
    if (x0 >> 5 == x1 >> 5)
        return pn_kpopcount(pn_gears_bits(occ[(size_t)r * pn_gears_row_words(res) + (x0 >> 5)], x0, x1));
    return pn_gears_rank(occ, occ_pre, res, r, x1 + 1u) - pn_gears_rank(occ, occ_pre, res, r, x0);
}

/* Triangle t: its pairs added to each grid row of face `face` it covers (global row r =
 * face * res + row), as a 64-bit count in two words (low, high) per row: row_pairs[2 r],
 * row_pairs[2 r + 1]. The carry goes with the add that wrapped the low word, so the sum is
 * exact in any order. */
PN_KFN void pn_gears_tri_row_pairs(uint32_t res, PN_CONST pn_cellrect *rects, PN_CONST uint32_t *occ,
                                   PN_CONST uint32_t *occ_pre, uint32_t face, uint32_t t, PN_GLOBAL uint32_t *row_pairs)
{
    uint32_t y;
    pn_cellrect rc = rects[t];
    if (pn_cellrect_is_empty(rc)) return;
    for (y = rc.lo >> 16; y <= rc.hi >> 16; y++) {
        uint32_t n = pn_gears_row_count(occ, occ_pre, res, face, y, rc.lo & 0xFFFFu, rc.hi & 0xFFFFu);
        PN_GLOBAL uint32_t *w = row_pairs + 2u * ((size_t)face * res + y);
        if (n != 0u && pn_katomic_add(&w[0], n) > 0xFFFFFFFFu - n) pn_katomic_add(&w[1], 1u);
    }
}

/* Triangle t's rectangle on the tile's face, clipped to the tile; 0 if nothing is left. */
PN_KFN int pn_gears_tile_rect(PN_CONST pn_cellrect *rects, uint32_t t, const pn_ktile *tl, uint32_t *x0, uint32_t *y0,
                              uint32_t *x1, uint32_t *y1)
{
    pn_cellrect rc = rects[t];
    if (pn_cellrect_is_empty(rc)) return 0;
    *x0 = rc.lo & 0xFFFFu;
    *y0 = rc.lo >> 16;
    *x1 = rc.hi & 0xFFFFu;
    *y1 = rc.hi >> 16;
    if (*y0 < tl->r0) *y0 = tl->r0;
    if (*y1 > tl->r1) *y1 = tl->r1;
    if (*x0 < tl->x0) *x0 = tl->x0;
    if (*x1 > tl->x1) *x1 = tl->x1;
    return *x0 <= *x1 && *y0 <= *y1;
}

/* Triangle t: its rectangle in the tile, as a difference per grid row: +1 at its first
 * column, -1 (a wrapping add) after its last, into counts[cell within the face] (zeroed
 * beforehand); pn_gears_cell_row turns a row of those into each cell's pairs. */
PN_KFN void pn_gears_tri_diff(PN_CONST pn_cellrect *rects, uint32_t res, const pn_ktile *tl, uint32_t t,
                              PN_GLOBAL uint32_t *counts)
{
    uint32_t x0, y0, x1, y1, y;
    if (!pn_gears_tile_rect(rects, t, tl, &x0, &y0, &x1, &y1)) return;
    for (y = y0; y <= y1; y++) {
        pn_katomic_add(&counts[y * res + x0], 1u);
        if (x1 + 1u < res) pn_katomic_add(&counts[y * res + x1 + 1u], 0xFFFFFFFFu);
    }
}

/* Grid row y of the tile's face: the running sum of its differences (pn_gears_tri_diff),
 * the triangles whose rectangles cover each cell, kept where the cell holds pixels (its
 * pairs), else 0; in place. */
PN_KFN void pn_gears_cell_row(PN_CONST uint32_t *occ, uint32_t res, const pn_ktile *tl, uint32_t y,
                              PN_GLOBAL uint32_t *counts)
{
    uint32_t x, run = 0u;
    PN_GLOBAL uint32_t *c = counts + (size_t)y * res;
    PN_CONST uint32_t *bits = occ + (size_t)(tl->face * res + y) * pn_gears_row_words(res);
    for (x = 0; x < res; x++) {
        run += c[x];
        c[x] = (bits[x >> 5] >> (x & 31u)) & 1u ? run : 0u;
    }
}

/* Triangle t, raster position v: v into the next slot of each cell of the tile that it
 * covers and that holds pixels (cursors: the cells' next free slots, from their exclusive
 * prefix sum on). The slots a cell's entries get depend on the order the work items ran
 * in; the sort of each cell's run (PN_DEV_SORT_RUNS) that follows makes it the one
 * ascending order (raster order). */
PN_KFN void pn_gears_tri_scatter(PN_CONST pn_cellrect *rects, PN_CONST uint32_t *occ, uint32_t res, const pn_ktile *tl,
                                 uint32_t t, uint32_t v, PN_GLOBAL uint32_t *cursors, PN_GLOBAL uint32_t *sorted)
{
    uint32_t x0, y0, x1, y1, y, w, w0, w1, m0, m1, W = pn_gears_row_words(res);
    PN_CONST uint32_t *row;
    PN_GLOBAL uint32_t *cur;
    if (!pn_gears_tile_rect(rects, t, tl, &x0, &y0, &x1, &y1)) return;
    /* The rectangle's part of each row's occupancy, a word at a time, its cells with
     * pixels by their highest bit first (the order within a triangle does not matter: it
     * adds one entry to each cell). */
    w0 = x0 >> 5;
    w1 = x1 >> 5;
    m0 = 0xFFFFFFFFu << (x0 & 31u);
    m1 = 0xFFFFFFFFu >> (31u - (x1 & 31u));
    row = occ + (size_t)(tl->face * res + y0) * W;
    cur = cursors + (size_t)y0 * res;
    for (y = y0; y <= y1; y++, row += W, cur += res)
        for (w = w0; w <= w1; w++) {
            uint32_t bits = row[w] & (w == w0 ? m0 : 0xFFFFFFFFu) & (w == w1 ? m1 : 0xFFFFFFFFu);
            while (bits) {
                uint32_t b = 31u - pn_kclz(bits);
                bits ^= 1u << b;
                sorted[pn_katomic_add(&cur[w * 32u + b], 1u)] = v;
            }
        }
}

/* Consecutive entries of a tile's cell-sorted list that share one box (chunk_box): the
 * per-pixel step tests a chunk's box against the pixel's light frustum and its footprint
 * against the samples still open before it looks at the chunk's triangles. A cell's
 * entries follow the BVH's leaf order (the raster order, `rindex`: pairs are scattered by
 * raster position and sorted by cell, then by that position), which keeps spatial
 * neighbours together, so a chunk's box is small. Against the mesh's own order (ids):
 * callgrind, dragon 256x256, one thread, GEARS frame 10.84 G -> 9.42 G instructions, its
 * per-pixel step 8.01 G -> 6.50 G. Visiting the BVH's children nearer the light first
 * instead (a per-frame order) measured 7.92 G there; farther first 6.47 G. */
#define PN_GEARS_CHUNK 8u

/* Chunks per superchunk: a pixel tests a superchunk's box (PN_GEARS_SUPER chunks, 64
 * entries) before its chunks' (on the dragon at 256x256 three quarters of the superchunks
 * a pixel meets are outside its frustum). */
#define PN_GEARS_SUPER 8u

/* Superchunk s of a tile's cell-sorted list: the box of each of its chunks q (entries
 * [q C, min(q C + C, n)), C = PN_GEARS_CHUNK, n the tile's pairs) into chunk_box[q * 6 ..]
 * (lo xyz, hi xyz), and the box of them all into super_box[s * 6 ..]; each entry, a
 * raster position until then, becomes its triangle id (rindex[entry]). A chunk may straddle
 * two cells: its box then holds the triangles of both, and is still a box of either
 * cell's part (the same for a superchunk). */
PN_KFN void pn_gears_chunk_boxes(PN_GLOBAL uint32_t *sorted, uint32_t n, PN_CONST uint32_t *rindex,
                                 PN_CONST float *tris, uint32_t s, PN_GLOBAL float *chunk_box,
                                 PN_GLOBAL float *super_box)
{
    uint32_t q, e, i;
    float sb[6];
    pn_box3_empty(sb);
    for (q = s * PN_GEARS_SUPER; q < s * PN_GEARS_SUPER + PN_GEARS_SUPER && q * PN_GEARS_CHUNK < n; q++) {
        uint32_t e1 = pn_kminu(q * PN_GEARS_CHUNK + PN_GEARS_CHUNK, n);
        float b[6];
        pn_box3_empty(b);
        for (e = q * PN_GEARS_CHUNK; e < e1; e++) {
            PN_CONST float *p;
            sorted[e] = rindex[sorted[e]];
            p = tris + (size_t)sorted[e] * 9u;
            for (i = 0; i < 9u; i += 3u) pn_box3_add(b, pn_v3_make(p[i], p[i + 1u], p[i + 2u]));
        }
        for (i = 0; i < 6u; i++) chunk_box[(size_t)q * 6u + i] = b[i];
        pn_box3_add(sb, pn_v3_make(b[0], b[1], b[2]));
        pn_box3_add(sb, pn_v3_make(b[3], b[4], b[5]));
    }
    for (i = 0; i < 6u; i++) super_box[(size_t)s * 6u + i] = sb[i];
}

/* Boxes first .. first + 3 of a box array (6 floats each, lo xyz then hi xyz), each index
 * clipped to `last`, as four lanes lo[a * 4 + c], hi[a * 4 + c]. */
PN_KFN void pn_gears_boxes4(PN_CONST float *boxes, uint32_t first, uint32_t last, float *lo, float *hi)
{
    uint32_t c, a;
    for (c = 0; c < 4u; c++) {
        PN_CONST float *b = boxes + (size_t)pn_kminu(first + c, last) * 6u;
        for (a = 0; a < 3u; a++) {
            lo[a * 4u + c] = b[a];
            hi[a * 4u + c] = b[3u + a];
        }
    }
}

/* Chunk q of a cell's list sorted[e0 .. e1), whose footprint is rc (the whole light with
 * `exact`): its triangles into mask m by pn_tris_block4, with their boxes against the
 * frustum first (the reference's conservative test). Returns 1 when the mask is full
 * (never with `exact`). Inlined always: its one caller is the pixel's loop, and when GCC
 * kept it apart (b6cff78's smaller tile test changed its sums) the canopy's GEARS frame
 * took 5.8% more instructions. */
PN_KFN_HOT uint32_t pn_gears_chunk_mask(uint32_t q, pn_rect rc, uint32_t e0, uint32_t e1, uint32_t own,
                                        PN_CONST uint32_t *sorted, PN_CONST float *tris, uint32_t exact,
                                        const pn_frustum *fr, const pn_foot *fp, pn_v3 O, const pn_klight *L,
                                        const pn_ray_origin *X, pn_ray_cache *RC, uint32_t *m, uint32_t *any,
                                        pn_shadow_counters *cnt)
{
    uint32_t e = pn_kmaxu(e0, q * PN_GEARS_CHUNK), end = pn_kminu(q * PN_GEARS_CHUNK + PN_GEARS_CHUNK, e1);
    /* No open sample in the chunk's footprint: none of its triangles can block. (The
     * reference's first leaf rule, the box's rectangle for each triangle when it holds at
     * most PN_REF_RAYS open samples, measured worse here on the first chunked walk,
     * d5fd710's predecessor with a footprint per triangle (its projected vertices, since
     * removed): mask pass 3.11 G -> 3.62 G instructions, dragon at 128x128; its rays over
     * the chunk below 1, 2, 4 or 8 open samples, on 64e459d: dragon -7.6% at 2, bunny
     * +2.5%, spheres +2.1%.) */
    if (!exact && !pn_rect_open(m, L->k, rc)) return 0u;
    return e < end ? pn_tris_block4(sorted + e, end - e, own, 1u, exact, tris, fr, fp, O, L, X, RC, m, any, cnt) : 0u;
}

/* Queued chunks qs[0 .. nq) (nq <= 4, inside the frustum, boxes in lanes blo, bhi): their
 * footprints four at a time (pn_foot_box4; the whole light with `exact` or while nothing
 * is blocked, when a footprint can only miss between samples), then each chunk's
 * triangles (pn_gears_chunk_mask). Returns 1 when the mask is full. */
PN_KFN uint32_t pn_gears_queue_mask(const uint32_t *qs, uint32_t nq, const float *blo, const float *bhi, uint32_t e0,
                                    uint32_t e1, uint32_t own, PN_CONST uint32_t *sorted, PN_CONST float *tris,
                                    uint32_t exact, const pn_frustum *fr, const pn_foot *fp, pn_v3 O,
                                    const pn_klight *L, const pn_ray_origin *X, pn_ray_cache *RC, uint32_t *m,
                                    uint32_t *any, pn_shadow_counters *cnt)
{
    pn_rect r4[4];
    uint32_t w;
    if (!exact && *any) {
        pn_foot_box4(fp, blo, bhi, r4);
    } else {
        for (w = 0; w < 4u; w++) r4[w] = pn_rect_full(L->k);
    }
    for (w = 0; w < nq; w++)
        if (pn_gears_chunk_mask(qs[w], r4[w], e0, e1, own, sorted, tris, exact, fr, fp, O, L, X, RC, m, any, cnt))
            return 1u;
    return 0u;
}

/* Whether global cell `cell` is in the tile: a tile is a run of whole grid rows of one
 * face, or a run of cells of one row (src/pn_gears.c's plan), so its cells are the global
 * cells from (face, r0, x0) to (face, r1, x1) in row-major order, one compare. */
PN_KFN int pn_gears_in_tile(const pn_ktile *tl, uint32_t res, uint32_t cell)
{
    uint32_t lo = (tl->face * res + tl->r0) * res + tl->x0, hi = (tl->face * res + tl->r1) * res + tl->x1;
    return cell - lo <= hi - lo;
}

/* Pixel pix, if its cell is in the tile: the mask of the cell's triangles
 * sorted[cell_off[c] .. cell_off[c + 1]) (in raster order; c the cell within its face),
 * stopping at a full mask unless `exact`; returns 1 and the visibility in *vis_out, else 0. A superchunk or a
 * chunk of the list (PN_GEARS_SUPER, PN_GEARS_CHUNK) whose box is outside the pixel's
 * light frustum, or (unless `exact`, and once a sample is blocked) whose footprint holds
 * no open sample, is skipped whole: none of its triangles can block a sample still open,
 * so the mask is the same. Boxes go four at a time through each test (pn_frustum_box4p,
 * pn_foot_box4). The superchunks' footprints: callgrind, one thread, dragon 256x256 GEARS
 * frame 9.42 -> 8.96 G instructions, 128x128 dragon and buddha -2.5%, bunny, chess,
 * spheres and room within 0.3%. The superchunk and chunk boxes tested against the frustum
 * are counted in cnt->nodes (pn_stats.shadow_nodes), as the reference counts its BVH's. */
PN_KFN int pn_gears_pixel_mask(const pn_klight *L, uint32_t exact, const pn_ktile *tl, uint32_t res,
                               const pn_ksurf *S, PN_CONST uint32_t *pix_cell, PN_CONST uint32_t *cell_off, PN_CONST uint32_t *sorted,
                               PN_CONST float *chunk_box, PN_CONST float *super_box, PN_CONST float *tris,
                               PN_CONST pn_kbvh4 *wnodes, size_t pix,
                               pn_shadow_counters *cnt, float *vis_out)
{
    uint32_t cell = pix_cell[pix], own = S->tri_id[pix], e0, e1, s0, slast, k = L->k, any, nq = 0u, qs[4], done = 0u;
    float blo[12], bhi[12], tlo[12], thi[12];
    uint32_t m[PN_MASK_WORDS_MAX];
    pn_frustum fr;
    pn_foot fp;
    pn_ray_origin X;
    pn_ray_cache RC;
    pn_horizon H;
    pn_v3 O, Ps, ns;
    /* A pixel has a cell only if it has an origin. */
    if (cell == PN_CELL_NONE || !pn_gears_in_tile(tl, res, cell) || own == 0xFFFFFFFFu) return 0;
    pn_surf_at(S, pix, &Ps, &ns);
    if (!pn_shadow_origin(Ps, ns, L, &O)) return 0;
    pn_mask_clear(m);
    /* The horizon first, as the reference does (a cell is in exactly one tile, so this runs
     * once per pixel). */
    pn_horizon_of(Ps, ns, own, tris, L, &H);
    any = pn_horizon_mask(&H, L, m) != 0u;
    pn_frustum_make(O, L, &fr);
    pn_foot_make(O, L, &fp);
    pn_tri_block_origin(O, L, wnodes, &X);
    pn_ray_cache_clear(&RC);
    cell -= tl->face * res * res;
    e0 = cell_off[cell];
    e1 = cell_off[cell + 1u];
    /* The superchunks of the list, four at a time against the frustum and (once a sample
     * is blocked) their footprints; the chunks of those left, four at a time; the chunks
     * inside queue up four at a time for pn_foot_box4, then each is walked with its
     * rectangle. */
    slast = e0 < e1 ? (e1 - 1u) / (PN_GEARS_CHUNK * PN_GEARS_SUPER) : 0u;
    for (s0 = e0 / (PN_GEARS_CHUNK * PN_GEARS_SUPER); e0 < e1 && s0 <= slast && !done; s0 += 4u) {
        uint32_t sbits, cs;
        pn_gears_boxes4(super_box, s0, slast, tlo, thi);
        sbits = pn_frustum_box4p(&fr, tlo, thi);
        cnt->nodes += pn_kminu(4u, slast - s0 + 1u);
        if (sbits && any && !exact) {
            pn_rect rs[4];
            pn_foot_box4(&fp, tlo, thi, rs);
            for (cs = 0; cs < 4u; cs++)
                if (((sbits >> cs) & 1u) && !pn_rect_open(m, k, rs[cs])) sbits &= ~(1u << cs);
        }
        for (cs = 0; cs < 4u && s0 + cs <= slast && !done; cs++) {
            uint32_t s = s0 + cs, q0, qlast;
            if (!((sbits >> cs) & 1u)) continue;
            qlast = (pn_kminu(e1, (s + 1u) * PN_GEARS_CHUNK * PN_GEARS_SUPER) - 1u) / PN_GEARS_CHUNK;
            for (q0 = pn_kmaxu(e0 / PN_GEARS_CHUNK, s * PN_GEARS_SUPER); q0 <= qlast && !done; q0 += 4u) {
                uint32_t bits, c;
                pn_gears_boxes4(chunk_box, q0, qlast, tlo, thi);
                bits = pn_frustum_box4p(&fr, tlo, thi);
                cnt->nodes += pn_kminu(4u, qlast - q0 + 1u);
                for (c = 0; c < 4u && q0 + c <= qlast && !done; c++) {
                    if (!((bits >> c) & 1u)) continue;
                    pn_lanes_put(blo, bhi, nq, pn_v3_make(tlo[c], tlo[4u + c], tlo[8u + c]),
                                 pn_v3_make(thi[c], thi[4u + c], thi[8u + c]));
                    qs[nq++] = q0 + c;
                    if (nq == 4u) {
                        done = pn_gears_queue_mask(qs, nq, blo, bhi, e0, e1, own, sorted, tris, exact, &fr, &fp, O, L,
                                                   &X, &RC, m, &any, cnt);
                        nq = 0u;
                    }
                }
            }
        }
    }
    if (nq > 0u && !done)
        pn_gears_queue_mask(qs, nq, blo, bhi, e0, e1, own, sorted, tris, exact, &fr, &fp, O, L, &X, &RC, m, &any, cnt);
    *vis_out = pn_mask_visibility(m, k);
    return 1;
}

#endif
