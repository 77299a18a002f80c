/* pn_ktypes.h - structs shared between the host core and the kernels. Fixed-width
 * integers and floats only (no enums, pointers or bool), laid out identically by C and
 * OpenCL C, so the OpenCL port can copy them into constant arguments verbatim. */
#ifndef PN_KTYPES_H
#define PN_KTYPES_H

#include "pn_kernel.h"

/* Primary camera, derived on the host from pn_camera (see src/pn_frame_setup.c). */
typedef struct pn_kview {
    float eye[3];
    float f[3], r[3], u[3]; /* orthonormal: forward, right, up */
    float tan_half;         /* tan(fov/2) */
    float aspect;           /* width / height */
    float znear;            /* near clipping distance along f, > 0 */
    uint32_t width, height;
} pn_kview;

/* Area or point light plus the shadow-ray parameters of a frame. */
typedef struct pn_klight {
    float c[3];     /* centre */
    float U[3];     /* half-edges (zero for a point light) */
    float V[3];
    float N[3];     /* unit normal, U x V normalized; zero for a point light */
    float eps;      /* shadow-ray origin offset along the normal, scene units */
    float cull_tol; /* slack of conservative frustum culling, scene units: the culls' own
                       rounding only, the predicate being exact (pn_predicate.h) */
    uint32_t k;     /* samples per light edge (1 for a point light) */
    uint32_t is_point;
} pn_klight;

/* The BVH: four-wide nodes, 128 bytes each (src/pn_bvh_build.c builds a binary tree in
 * the frame region and folds it, pn_bvh_fold, so that a walk tests up to four children's
 * boxes at once, one lane each: kernels/pn_raytrace.h). Child c < n: box lo[a][c] ..
 * hi[a][c], and child[c] either a wide node's index or a leaf, PN_W4_LEAF |
 * (count - 1) << PN_W4_COUNT_SHIFT | first: the references tri_index[first .. first +
 * count), 2 .. max(3, PN_BVH_LEAF_MAX) of them (one in a tree of one reference). A reference is a
 * triangle id (PN_REF_TRI), with PN_REF_SPLIT set when the triangle is split into several
 * references: a leaf box then holds the part of it that matters to the walks, not
 * necessarily its vertices. Lanes c >= n hold zeros and are never used. Node 0 is the
 * root, so no child index is 0; an empty tree's root has n = 0. The tree's box is the
 * union of the root's lanes (pn_w4_root_box). */
#define PN_REF_SPLIT 0x80000000u
#define PN_REF_TRI 0x7FFFFFFFu
#define PN_W4_LEAF 0x80000000u
#define PN_W4_COUNT_SHIFT 26u
#define PN_W4_FIRST 0x03FFFFFFu
typedef struct pn_kbvh4 {
    float lo[3][4];
    float hi[3][4];
    uint32_t child[4];
    uint32_t n;   /* children */
    uint32_t pad0, pad1, pad2;
} pn_kbvh4;

/* A walk's stack entry for child c of wide node w (wn = wnodes + w): the child's wide
 * index, or for a leaf PN_W4_LEAF | w << 2 | c, so that the leaf's box (lane c of w) is
 * at hand when the entry is popped (w < 2^29: at most 2^26 references). */
PN_KFN uint32_t pn_w4_entry(PN_CONST pn_kbvh4 *wn, uint32_t w, uint32_t c)
{
    uint32_t ch = wn->child[c];
    return (ch & PN_W4_LEAF) ? (PN_W4_LEAF | (w << 2) | c) : ch;
}

/* A leaf's child word (count 1 .. 16, first < 2^26), and back: its references
 * tri_index[*first .. *first + return value). */
PN_KFN uint32_t pn_w4_leaf_word(uint32_t first, uint32_t count)
{
    return PN_W4_LEAF | (count - 1u) << PN_W4_COUNT_SHIFT | first;
}
PN_KFN uint32_t pn_w4_word_refs(uint32_t ch, uint32_t *first)
{
    *first = ch & PN_W4_FIRST;
    return ((ch & ~PN_W4_LEAF) >> PN_W4_COUNT_SHIFT) + 1u;
}

/* A leaf entry's references (its child word's, pn_w4_word_refs). */
PN_KFN uint32_t pn_w4_leaf_refs(PN_CONST pn_kbvh4 *wnodes, uint32_t e, uint32_t *first)
{
    return pn_w4_word_refs(wnodes[(e & ~PN_W4_LEAF) >> 2].child[e & 3u], first);
}

/* The tree's box: the union of the root's lanes (zeros for an empty tree). Only its
 * bounds' magnitudes about a shadow origin matter (pn_ray_origin_make), so the sign of a
 * zero bound, which follows the order of the joins, never does. */
PN_KFN void pn_w4_root_box(PN_CONST pn_kbvh4 *wnodes, float *lo, float *hi)
{
    uint32_t c, a;
    for (a = 0; a < 3u; a++) {
        lo[a] = wnodes->n ? wnodes->lo[a][0] : 0.0f;
        hi[a] = wnodes->n ? wnodes->hi[a][0] : 0.0f;
        for (c = 1; c < wnodes->n; c++) {
            lo[a] = lo[a] < wnodes->lo[a][c] ? lo[a] : wnodes->lo[a][c];
            hi[a] = hi[a] > wnodes->hi[a][c] ? hi[a] : wnodes->hi[a][c];
        }
    }
}

/* A leaf entry's box. */
PN_KFN void pn_w4_leaf_box(PN_CONST pn_kbvh4 *wnodes, uint32_t e, float *lo, float *hi)
{
    PN_CONST pn_kbvh4 *w = wnodes + ((e & ~PN_W4_LEAF) >> 2);
    uint32_t c = e & 3u, a;
    for (a = 0; a < 3u; a++) {
        lo[a] = w->lo[a][c];
        hi[a] = w->hi[a][c];
    }
}

/* Shading constants. */
typedef struct pn_kshade {
    float albedo, ambient;
    uint32_t background; /* RGBA8 packed little-endian: r | g << 8 | b << 16 | a << 24 */
    uint32_t pad;
} pn_kshade;

/* Occlusion textures' frame constants (kernels/pn_occtex.h; src/pn_occtex.c sets them). */
typedef struct pn_kocc {
    float d;              /* centre of projection behind the light centre (0: point light) */
    float zmin, h;        /* slice k's bottom plane at light depth zmin + k h */
    float sfac_x, sfac_y; /* kernel side in texels = sfac (z - zb) / (z (zb + d)) */
    uint32_t live;        /* bit k: slice k holds a bit and was looked up */
    uint32_t pad0, pad1;
    uint32_t res;         /* texels per axis */
    uint32_t slices;      /* 2 .. PN_OCC_SLICES_MAX */
    uint32_t filter, combine, flags;
    uint32_t slice;       /* the slice a filter or lookup pass works on */
    uint32_t levels;      /* N-buffer and mipmap levels: floor(log2 res) + 1 */
    uint32_t level;       /* the level a filter pass builds */
} pn_kocc;

/* Monte Carlo shadow maps' frame constants (kernels/pn_mcsm.h; src/pn_mcsm.c sets them).
 * Light frame: origin at the light centre, axes lview's r, u, f; depth z along f. */
typedef struct pn_kmc {
    float d;          /* centre of projection behind the light centre (0: point light) */
    float sfac;       /* res ha / tx: a region's width in texels is sfac (z - zb) / (z (zb + d)) */
    float bias_k;     /* adaptive bias (eq. 3.2) per unit of (z + d) / cos */
    float blur_depth; /* blur: a neighbour's weight / (1 + |depth - centre| blur_depth / centre) */
    float whole[3];   /* the N-buffer's bound over the whole map (pn_nb_mm_rect), once a frame */
    float sfac_y;     /* res hb / ty: its height, sfac_y (z - zb) / (z (zb + d)) (the window fitted
                         to the occluders narrows tx and ty apart: the two differ) */
    uint32_t res;     /* texels per axis */
    uint32_t levels;  /* N-buffer levels: floor(log2 res) + 1 */
    uint32_t level;   /* the level an N-buffer pass builds */
    uint32_t layers;  /* 1 (near), 2 (near, far) or 3 (near, far and the eye's depth) */
    uint32_t search;  /* PN_MC_S_LINEAR or PN_MC_S_HIER */
    uint32_t rays;    /* n: n x n jittered rays per pixel, 1 .. 8 */
    uint32_t blur;    /* blur radius in pixels, 0 .. 8 (0: off) */
    uint32_t flags;   /* PN_MC_F_* */
    uint32_t seed;    /* frame key of the sample hash */
    uint32_t nb_step; /* the N-buffer keeps levels 0, nb_step, 2 nb_step, ... (1 or 3;
                         kernels/pn_nbuffer.h) */
    uint32_t pad5, pad6;
    float blur_w[12]; /* binomial weights C(2r, r + i), i = 0 .. r */
} pn_kmc;

/* Penumbra wedges' frame constants (kernels/pn_wedges.h; src/pn_wedges.c sets them). */
typedef struct pn_kwg {
    uint32_t mode;    /* PN_WG_M_BLEND or PN_WG_M_ADD */
    uint32_t runs;    /* edges of the scene (src/pn_connect.c) */
    uint32_t sils;    /* silhouette edges this frame */
    uint32_t tiles_x; /* screen tiles per row */
    float hmax;       /* the greatest height above the light plane, (X - c).N, of any point a
                         pixel's shadow origin may take: the scene box's, widened */
    uint32_t bx0, by0, bx1, by1; /* the band of tiles a binning pass fills: [bx0, bx1) x [by0, by1) */
    uint32_t pix0;    /* the pixel pass: its first pixel (item i is pixel pix0 + i) */
    uint32_t count_rows; /* 1: the count pass also adds each tile row's pairs (the band planner's) */
    uint32_t keep_cap; /* words of the pool the count keeps its tiles in (pn_wg_bin) */
    float front_g;    /* pn_wg_front's bound on the magnitudes of a triangle's plane terms: the
                         scene box's largest coordinate |X|inf times 3, plus |c|inf twice,
                         |U|inf, |V|inf and the eye's |e|inf */
    uint32_t no_cull; /* 1 (PN_WG_NO_CULL): every silhouette in every tile of a band, no box
                         test passes and no tile clear (the same bytes) */
    uint32_t full;    /* 1: some tiles' lists outgrew the pools, their boxes marked PN_WG_FULL */
} pn_kwg;

/* The G-buffer's triangle id of a pixel that sees no triangle. */
#define PN_NO_PIXEL_TRIANGLE 0xFFFFFFFFu

/* Triangle flags (one byte each). */
#define PN_TRI_DEGENERATE 1u
/* Receiver only (pn_scene_set_receivers): casts no shadow into the Monte Carlo shadow
 * maps' depth layers; every other algorithm treats it like any triangle. */
#define PN_TRI_RECEIVER 2u
/* Of an object that is not a solid (src/pn_connect.c pn_cn_solids: open, a sheet, a leaf
 * card): its surface has no inside, so the Monte Carlo shadow maps light whichever side
 * faces the light; a solid's face turned away from the light by its winding is in its own
 * shadow. Set at pn_scene_set for a context that runs MCSM or the wedges. */
#define PN_TRI_SHEET 4u
/* Of a closed object wound inside out for this frame's light (src/pn_connect.c
 * pn_connect_light: its signed volume is negative and the light centre lies outside its
 * box): MCSM and the wedges read its winding reversed, as for the solid wound outward. The
 * exact algorithms do not read the winding. */
#define PN_TRI_INVERTED 8u
/* Of a closed object of negative volume (pn_cn_solids): an inside-out solid, or a cavity
 * (a room wound inward), which the frame tells apart by its light (pn_connect_light). The
 * three bits hold its group: 1 .. PN_CN_NEG_MAX - 1 the largest such objects, one each;
 * PN_CN_NEG_MAX the others, read reversed in every frame. */
#define PN_TRI_NEGVOL_SHIFT 4u
#define PN_TRI_NEGVOL (7u << PN_TRI_NEGVOL_SHIFT)

/* Rows of pixels per rasterizer work item. */
#define PN_RASTER_BAND 8u

/* Triangles per chunk of the rasterizer's band walk (pn_raster_chunk), and the chunks of n
 * triangles. */
#define PN_RASTER_CHUNK 32u
#define PN_RASTER_CHUNKS(n) (((n) + PN_RASTER_CHUNK - 1u) / PN_RASTER_CHUNK)

/* Side in pixels of the screen tiles the per-pixel shadow passes take their pixels in
 * (pn_pix_tiled, kernels/pn_passes.h). */
#define PN_PIX_TILE 16u

/* Side in pixels of the penumbra wedges' screen tiles (kernels/pn_wedges.h; the arena sizes
 * their pools by it): the tiles the pixel passes run in, so that a tile's pixels, which
 * read one list, run one after another. */
#define PN_WG_TILE PN_PIX_TILE
#define PN_WG_TILES(n) (((n) + PN_WG_TILE - 1u) / PN_WG_TILE) /* tiles over n pixels */

#endif
