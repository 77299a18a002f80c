/* pn_rayfilter.h - one shadow ray from O to a light sample: its set-up, the exact
 * ray/triangle decision and the slab test, shared by the per-ray walks (pn_raytrace.h:
 * per-sample ray tracing, SRT's hard path, the wedges' centre ray) and by the reference
 * (pn_reference.h), which decides a triangle whose footprint holds only a few open samples
 * ray by ray instead of setting up its forms over the whole grid.
 *
 * A ray decides each triangle exactly as pn_tri_sample() does (pn_predicate.h), but at the
 * cost of a ray/triangle test: a float filter in the watertight model of Woop, Benthin and
 * Wald (2013) with a rigorous rounding bound, and pn_tri_sample() itself only where that
 * filter cannot tell (tests/test_raytrace.c, fuzz/fuzz_gears.c).
 *
 * ---- What is decided -------------------------------------------------------------------
 * With D* = S - O for the exact sample point S = c + a U + b V and p = A - O, q = B - O,
 * r = C - O (exact), pn_tri_sample's edge values are the triple products
 * det(D*, p, q), det(D*, q, r), det(D*, r, p) (its canonical endpoint order changes its
 * floats, not these reals), and triangle ABC blocks the sample iff all three are >= 0 or
 * all <= 0 and the plane test holds (O off the plane, S strictly on its other side).
 *
 * ---- The filter (per ray, then per triangle) -------------------------------------------
 * Per ray: D = fl(fl(cO + fl(b V)) + fl(a U)), cO = fl(c - O); kz the axis of D's largest
 * magnitude, (kx, ky, kz) the cyclic rotation ending in it (one orientation for every
 * edge), sx = fl(D_kx * fl(1 / D_kz)) and sy likewise. Per triangle, for each vertex P:
 * P~ = fl(P - O) in that frame, X = fl(P~x - fl(sx P~z)), Y = fl(P~y - fl(sy P~z)), and
 * the three 2-D edge functions e = fl(fl(X1 Y2) - fl(Y1 X2)) over (B, C), (C, A), (A, B).
 * For exact inputs and sx = D*x / D*z, sy = D*y / D*z they are det(D*, ., .) / D*z, one
 * factor for all three, so the signs the predicate needs are theirs. Bounds (standard
 * model, u = 2^-24, u' = u / (1 - u); |.| componentwise):
 *   - the direction: |D - D*| <= u (|c - O| + |bV| + |cO + bV| + |aU| + |D|)
 *     <= 3.0001 u W, W = |cO| + |U| + |V| (|a|, |b| <= 1): dl = 3.25 u W + PN_KTINY per
 *     origin (the slack pays for computing dl; PN_KTINY for an underflowing a U or b V);
 *   - the shear: |D_kx| <= |D_kz|, so |sx| <= 1 + 2.01 u, and with w = dl_z / |D_z| <= 1/2
 *     |sx - D*x / D*z| <= 2.0001 u + (dl_x + dl_z) / (|D_z| - dl_z)
 *                     <= 2.0001 u + (dl_x + dl_z) (1 + 2 w) / |D_z| =: sigma;
 *     computed as 1.125 times that from fl(1 / D_z) (w > 1/4: the ray is not filtered);
 *   - a vertex in the box whose translated bounds are M_i = max |fl(box - O)|_i (rounding
 *     is monotone, so |P~_i| <= M_i exactly): |X - X*| <= (u + u') M_x
 *     + ((1 + 2.01 u)(2 u + u^2 + u') + sigma (1 + u')) M_z (+ an underflow of
 *     fl(sx P~z), below 2^-150) for X* = p_x - (D*x / D*z) p_z (the subtraction, the
 *     product, P~ - p and sx - D*x / D*z in turn): eps = 2.125 u max(M_x, M_y)
 *     + (3.125 u + 1.0625 sigma) M_z;
 *   - |X|, |Y| <= h, the largest magnitude fl(P~x - fl(sx P~z)) takes over the box: X is
 *     nondecreasing in P~x and monotone in P~z, so h comes from the box corners exactly;
 *   - an edge function: |e - e*| <= (4 u + 2 u^2) h^2 (two products and their
 *     difference) + 4 eps h + 2 eps^2 (|X1 Y2 - X1* Y2*| <= eps (|X1| + |Y2|) + eps^2);
 *     eb = 4.25 u h^2 + eps (4.25 h + 2.125 eps) + PN_KTINY, strictly above the error
 *     (the slack pays for computing eb; PN_KTINY for underflows, as pn_predicate.h argues).
 * eb comes from the box of the leaf holding the triangle (its vertices' box or larger:
 * the BVH build's leaf boxes hold the vertices of every whole triangle in them), once per
 * leaf; for a split triangle (PN_REF_SPLIT: the leaf boxes only a part of it) from its own
 * vertices' box (pn_ray_tri_bound). Then: some e >= eb and some e <= -eb: two exact
 * values of opposite strict signs, not blocked (the common answer). All e >= eb or all e <= -eb: the edges pass, and the
 * plane decides: Woop's t = T / P in (0, 1) in the same frame with its own bound
 * (pn_ray_hit), and where that cannot tell, the very test pn_tri_sample makes
 * (pn_tri_plane, the sample's float plane value against its bound, the exact sign
 * within it). Otherwise some edge value
 * lies within its bound (rays through or near a vertex or edge, shared edges, slivers
 * seen edge-on, huge or far triangles): pn_tri_sample() decides, so every answer is the
 * exact one (tests/test_raytrace.c counts these fallbacks on hostile triangles and checks
 * every answer against pn_tri_sample; fuzz/fuzz_gears.c checks them on fuzzed scenes).
 *
 * ---- Traversal -------------------------------------------------------------------------
 * Slab tests with per-ray reciprocals inv = 1 / D (a component below 1e-30 in magnitude,
 * zero included, gets +-1e30: the segment it stands for moves by < 2e-30) over the
 * four-wide tree (pn_kbvh4: the binary tree with up to three levels folded into a node),
 * the four children's boxes tested at once (pn_ray_box4, one SSE lane each), the nearest
 * entry visited next and the others pushed. Per origin, the chain of nodes from the root
 * down whose grown boxes hold O (pn_ray_chain) is taken as hit by every ray without a
 * test: a ray starts at the chain's end with the chain's other children tested and
 * pushed. A node is skipped only when the segment misses its box grown by tol.
 * Rigorous: a blocked sample's exact segment meets the triangle at O + t D*, t in [0, 1],
 * inside every box on the triangle's path; O + t D lies within dl of it; the computed
 * entry fl(fl(lo - fl(O + tol)) * inv) errs by at most 3.01 u |D_i| in t |D_i| plus the
 * u |O + tol| of the moved origin. tol = 1.0625 (cull_tol + max dl + 4 u (|O| + |W|)) +
 * 1e-29 exceeds all of it, for any coordinates (not only near the origin). */
#ifndef PN_RAYFILTER_H
#define PN_RAYFILTER_H

#include "pn_predicate.h"

/* Counting hook for tests: called once per triangle the filter leaves to pn_tri_sample()
 * (kind 0: an edge value within its bound) or to the plane test of pn_tri_sample (kind 1:
 * the edges passed, the sheared plane test cannot tell). The library compiles it away. */
#ifndef PN_RAY_FALLBACK_HOOK
#define PN_RAY_FALLBACK_HOOK(kind) ((void)0)
#endif

/* Direction components smaller than this in magnitude get reciprocal +-1/PN_RAY_DIR_MIN. */
#define PN_RAY_DIR_MIN 1e-30f

/* What a shadow-ray origin shares with all its k^2 rays. */
typedef struct pn_ray_origin {
    pn_v3 O, cO; /* origin, fl(c - O) */
    float dl[3]; /* bound of |D - (S - O)| per component, any sample */
    float tol;   /* growth of the boxes the slab test uses */
    float t0, t1; /* the segment's parameter range, 0 and 1 (see pn_ray_origin_make) */
    float mroot; /* max |fl(P - O)| over the scene box (its corners: rounding is monotone) */
    /* Four-wide nodes from the root down, chain[d + 1] being child slot[d] of chain[d],
     * the first child whose box grown by tol holds O: every ray from O enters them, so
     * the walk takes them as hit. */
    uint32_t chain[PN_BVH_STACK];
    uint32_t slot[PN_BVH_STACK];
    uint32_t chain_len;
} pn_ray_origin;

/* One ray: the slab test's and the filter's per-ray constants. */
typedef struct pn_ray {
    float inv[3];        /* 1 / D */
    float t0, t1;        /* the segment's parameter range [0, 1] */
    float ol[3], oh[3];  /* O + tol and O - tol: the grown box's planes lo - tol and hi + tol, moved */
    uint32_t kx, ky, kz; /* the shear frame */
    float ox, oy, oz;    /* O in it */
    float sx, sy;        /* the shear */
    float dz, dlz;       /* D_kz and dl_kz */
    float ez;            /* eps = PN_RAY_EX max(M_x, M_y) + ez M_z */
    float ebr;           /* eb of the scene box (for any triangle), PN_KINF when not filtered */
    uint32_t filt;       /* 0: every triangle goes to pn_tri_sample */
    pn_v3 O;
    float a, b;
    int32_t i, j;
} pn_ray;

#define PN_RAY_EX (2.125f * PN_KU)

PN_KFN float pn_ray_abs(float x) { return pn_kmaxf(x, -x); }

/* eb from h and eps (see the top). */
PN_KFN float pn_ray_eb(float h, float eps) { return 4.25f * PN_KU * h * h + eps * (4.25f * h + 2.125f * eps) + PN_KTINY; }

/* lo, hi: the scene's box (the BVH root's), xyz. */
PN_KFN void pn_ray_origin_make(pn_v3 O, const pn_klight *L, const float *lo, const float *hi, pn_ray_origin *X)
{
    pn_v3 W;
    float dmax, o[3];
    uint32_t q;
    o[0] = O.x;
    o[1] = O.y;
    o[2] = O.z;
    X->mroot = 0.0f;
    for (q = 0; q < 3u; q++) X->mroot = pn_kmaxf(X->mroot, pn_kmaxf(pn_ray_abs(lo[q] - o[q]), pn_ray_abs(hi[q] - o[q])));
    X->O = O;
    X->cO = pn_v3_sub(pn_light_c(L), O);
    W = pn_v3_add(pn_v3_add(pn_v3_abs(X->cO), pn_v3_abs(pn_light_U(L))), pn_v3_abs(pn_light_V(L)));
    X->dl[0] = 3.25f * PN_KU * W.x + PN_KTINY;
    X->dl[1] = 3.25f * PN_KU * W.y + PN_KTINY;
    X->dl[2] = 3.25f * PN_KU * W.z + PN_KTINY;
    dmax = pn_kmaxf(X->dl[0], pn_kmaxf(X->dl[1], X->dl[2]));
    X->tol = 1.0625f * (L->cull_tol + dmax + 4.0f * PN_KU * (pn_v3_linf(O) + pn_v3_linf(W))) + 1e-29f;
    /* 0 and 1, but not constants the compiler can see (tol is finite and positive): the
     * slab test's max with a constant 0 becomes a branch (GCC 12), with a variable a maxss. */
    X->t0 = 0.0f * X->tol;
    X->t1 = X->t0 + 1.0f;
}

/* Axis q of the slab test: the reciprocal of direction component d (of a component below
 * PN_RAY_DIR_MIN in magnitude, zero included: of +-PN_RAY_DIR_MIN), and the origin moved
 * so that lo - ol and hi - oh are the grown box's planes' offsets from O. */
PN_KFN_HOT void pn_ray_axis(pn_ray *R, uint32_t q, float d, float o, float tol)
{
    R->inv[q] = 1.0f / (pn_ray_abs(d) >= PN_RAY_DIR_MIN ? d : (d < 0.0f ? -PN_RAY_DIR_MIN : PN_RAY_DIR_MIN));
    R->ol[q] = o + tol;
    R->oh[q] = o - tol;
}

/* The ray along D = fl(fl(cO + fl(b V)) + fl(a U)) to sample (i, j) = (a, b). */
PN_KFN void pn_ray_set(const pn_ray_origin *X, pn_v3 D, float a, float b, int32_t i, int32_t j, pn_ray *R)
{
    float d[3], o[3], ax = pn_ray_abs(D.x), ay = pn_ray_abs(D.y), az = pn_ray_abs(D.z), adz, iz, w, sigma;
    uint32_t kz, kx, ky;
    pn_ray_axis(R, 0u, D.x, X->O.x, X->tol);
    pn_ray_axis(R, 1u, D.y, X->O.y, X->tol);
    pn_ray_axis(R, 2u, D.z, X->O.z, X->tol);
    d[0] = D.x;
    d[1] = D.y;
    d[2] = D.z;
    o[0] = X->O.x;
    o[1] = X->O.y;
    o[2] = X->O.z;
    kz = ax >= ay ? (ax >= az ? 0u : 2u) : (ay >= az ? 1u : 2u);
    kx = kz == 2u ? 0u : kz + 1u;
    ky = kx == 2u ? 0u : kx + 1u;
    adz = pn_kmaxf(ax, pn_kmaxf(ay, az));
    R->kz = kz;
    R->kx = kx;
    R->ky = ky;
    R->ox = o[kx];
    R->oy = o[ky];
    R->oz = o[kz];
    iz = R->inv[kz];
    R->sx = d[kx] * iz;
    R->sy = d[ky] * iz;
    R->dz = d[kz];
    R->dlz = X->dl[kz];
    iz = pn_ray_abs(iz);
    w = X->dl[kz] * iz;
    R->filt = adz >= PN_RAY_DIR_MIN && w <= 0.25f;
    sigma = 1.125f * (2.01f * PN_KU + (pn_kmaxf(X->dl[kx], X->dl[ky]) + X->dl[kz]) * (1.0f + 2.0f * w) * iz);
    R->ez = 3.125f * PN_KU + 1.0625f * sigma;
    /* The scene box's bound: |X|, |Y| <= (1 + (1 + 2.01 u)(1 + u)) mroot (1 + u) and eps
     * <= (2.125 u + ez) mroot, coarser than a leaf's but free per triangle. */
    R->ebr = R->filt ? pn_ray_eb(2.125f * X->mroot, (PN_RAY_EX + R->ez) * X->mroot) : PN_KINF;
    R->t0 = X->t0;
    R->t1 = X->t1;
    R->O = X->O;
    R->a = a;
    R->b = b;
    R->i = i;
    R->j = j;
}

/* fl(cO + fl(b V)): the part of D a row of samples shares. */
PN_KFN pn_v3 pn_ray_row(const pn_ray_origin *X, const pn_klight *L, float b)
{
    return pn_v3_add(X->cO, pn_v3_scale(pn_light_V(L), b));
}

PN_KFN void pn_ray_make(const pn_ray_origin *X, const pn_klight *L, int32_t i, int32_t j, pn_ray *R)
{
    float a = pn_sample_coord(i, L->k), b = pn_sample_coord(j, L->k);
    pn_ray_set(X, pn_v3_add(pn_ray_row(X, L, b), pn_v3_scale(pn_light_U(L), a)), a, b, i, j, R);
}

/* 1 when O lies in child c of wide node w, grown by tol. */
PN_KFN int pn_ray_holds_origin(const pn_ray_origin *X, PN_CONST pn_kbvh4 *w, uint32_t c)
{
    return w->lo[0][c] - X->tol <= X->O.x && X->O.x <= w->hi[0][c] + X->tol && w->lo[1][c] - X->tol <= X->O.y &&
           X->O.y <= w->hi[1][c] + X->tol && w->lo[2][c] - X->tol <= X->O.z && X->O.z <= w->hi[2][c] + X->tol;
}

/* No chain: the walk starts at the root. The chain repays itself over a pixel's k^2 rays
 * (per-sample ray tracing), not over a single ray from the origin (the penumbra wedges'
 * centre ray: on the chess set at 512^2 the chain cost 25 M instructions and the walk from
 * the root 9 M more than from the chain's end). */
PN_KFN void pn_ray_root(pn_ray_origin *X)
{
    X->chain_len = 1u;
    X->chain[0] = 0u;
}

/* X->chain: the walk is the same whatever it takes as hit (taking a box as hit only adds
 * tests, and each test is exact), so the chain needs no rounding argument. */
PN_KFN void pn_ray_chain(pn_ray_origin *X, PN_CONST pn_kbvh4 *wnodes)
{
    uint32_t n = 0u;
    X->chain_len = 1u;
    X->chain[0] = 0u;
    while (X->chain_len < PN_BVH_STACK) {
        PN_CONST pn_kbvh4 *w = wnodes + n;
        uint32_t c;
        for (c = 0; c < w->n; c++)
            if (!(w->child[c] & PN_W4_LEAF) && pn_ray_holds_origin(X, w, c)) break;
        if (c == w->n) break;
        X->slot[X->chain_len - 1u] = c;
        n = w->child[c];
        X->chain[X->chain_len++] = n;
    }
}

/* The slab test of the children of wide node w against the segment, one lane each: bit c
 * of the result when the segment may meet child c's box grown by tol, tn[c] its entry
 * parameter. lo - ol and hi - oh are the grown planes' offsets from O, so their products
 * with inv are the near and far distances in the order of inv's sign (fl(lo - fl(O + tol))
 * <= fl(hi - fl(O - tol)): rounding is monotone), and their min and max pick them without
 * a branch. The lane loop is plain float arithmetic over the node's arrays, which GCC
 * vectorizes (one SSE lane a child). */
PN_KFN_HOT uint32_t pn_ray_box4(const pn_ray *R, PN_CONST pn_kbvh4 *w, float *tn)
{
    float t1[4];
    uint32_t c, hit[4];
    for (c = 0; c < 4u; c++) {
        float ax = (w->lo[0][c] - R->ol[0]) * R->inv[0], bx = (w->hi[0][c] - R->oh[0]) * R->inv[0];
        float ay = (w->lo[1][c] - R->ol[1]) * R->inv[1], by = (w->hi[1][c] - R->oh[1]) * R->inv[1];
        float az = (w->lo[2][c] - R->ol[2]) * R->inv[2], bz = (w->hi[2][c] - R->oh[2]) * R->inv[2];
        tn[c] = pn_kmaxf(pn_kmaxf(pn_kminf(ax, bx), pn_kminf(ay, by)), pn_kmaxf(pn_kminf(az, bz), R->t0));
        t1[c] = pn_kminf(pn_kminf(pn_kmaxf(ax, bx), pn_kmaxf(ay, by)), pn_kminf(pn_kmaxf(az, bz), R->t1));
    }
    for (c = 0; c < 4u; c++) hit[c] = tn[c] <= t1[c] ? 1u << c : 0u;
    return (hit[0] | hit[1] | hit[2] | hit[3]) & ((1u << w->n) - 1u);
}

#if !defined(__OPENCL_VERSION__) && !defined(__OPENCL_C_VERSION__)
/* 1 when the segment may meet the box [lo, hi] (xyz) grown by tol; *tn its entry
 * parameter: the one slab test, on a wide node of one child in private memory (so host
 * code only: the tests' and fuzzers' check of a single box). */
PN_KFN int pn_ray_box(const pn_ray *R, const float *lo, const float *hi, float *tn)
{
    pn_kbvh4 w;
    float t[4];
    uint32_t a, c;
    for (a = 0; a < 3u; a++)
        for (c = 0; c < 4u; c++) {
            w.lo[a][c] = lo[a];
            w.hi[a][c] = hi[a];
        }
    w.n = 1u;
    a = pn_ray_box4(R, &w, t);
    *tn = t[0];
    return (int)a;
}
#endif

/* The edge functions' bound eb for every triangle inside the box [lo, hi] (xyz). */
PN_KFN float pn_ray_bound(const pn_ray *R, const float *lo, const float *hi)
{
    float lx = lo[R->kx] - R->ox, hx = hi[R->kx] - R->ox;
    float ly = lo[R->ky] - R->oy, hy = hi[R->ky] - R->oy;
    float lz = lo[R->kz] - R->oz, hz = hi[R->kz] - R->oz;
    float mx = pn_kmaxf(pn_ray_abs(lx), pn_ray_abs(hx));
    float my = pn_kmaxf(pn_ray_abs(ly), pn_ray_abs(hy));
    float mz = pn_kmaxf(pn_ray_abs(lz), pn_ray_abs(hz));
    /* The extremes of X and Y over the box, at the corners their monotonicity picks. */
    float x1 = hx - R->sx * (R->sx >= 0.0f ? lz : hz), x0 = lx - R->sx * (R->sx >= 0.0f ? hz : lz);
    float y1 = hy - R->sy * (R->sy >= 0.0f ? lz : hz), y0 = ly - R->sy * (R->sy >= 0.0f ? hz : lz);
    float h = pn_kmaxf(pn_kmaxf(pn_ray_abs(x1), pn_ray_abs(x0)), pn_kmaxf(pn_ray_abs(y1), pn_ray_abs(y0)));
    float eps = PN_RAY_EX * pn_kmaxf(mx, my) + R->ez * mz;
    return R->filt ? pn_ray_eb(h, eps) : PN_KINF;
}

/* pn_ray_bound over triangle p's own box (9 floats, A B C). */
PN_KFN float pn_ray_tri_bound(const pn_ray *R, PN_CONST float *p)
{
    float lo[3], hi[3];
    uint32_t a;
    for (a = 0; a < 3u; a++) {
        lo[a] = pn_kminf(p[a], pn_kminf(p[3u + a], p[6u + a]));
        hi[a] = pn_kmaxf(p[a], pn_kmaxf(p[3u + a], p[6u + a]));
    }
    return pn_ray_bound(R, lo, hi);
}

/* The three edge functions of triangle p (9 floats, A B C) into e. */
PN_KFN_HOT void pn_ray_edges(const pn_ray *R, PN_CONST float *p, float *e)
{
    float ax = p[R->kx] - R->ox, ay = p[R->ky] - R->oy, az = p[R->kz] - R->oz;
    float bx = p[3u + R->kx] - R->ox, by = p[3u + R->ky] - R->oy, bz = p[3u + R->kz] - R->oz;
    float cx = p[6u + R->kx] - R->ox, cy = p[6u + R->ky] - R->oy, cz = p[6u + R->kz] - R->oz;
    float Ax = ax - R->sx * az, Ay = ay - R->sy * az;
    float Bx = bx - R->sx * bz, By = by - R->sy * bz;
    float Cx = cx - R->sx * cz, Cy = cy - R->sy * cz;
    e[0] = Bx * Cy - By * Cx;
    e[1] = Cx * Ay - Cy * Ax;
    e[2] = Ax * By - Ay * Bx;
}

/* Their signs against the bound eb: 0 when two exact edge values have opposite strict
 * signs (not blocked), 1 when all three have the same strict sign, 2 when some value lies
 * within eb. */
PN_KFN_HOT int32_t pn_ray_signs(const float *e, float eb)
{
    float lo = pn_kminf(e[0], pn_kminf(e[1], e[2])), hi = pn_kmaxf(e[0], pn_kmaxf(e[1], e[2]));
    if (hi >= eb && lo <= -eb) return 0;
    if (lo >= eb || hi <= -eb) return 1;
    return 2;
}

/* The plane half of the predicate, exactly as pn_tri_sample and pn_tri_resolve decide
 * it: O off the plane and the sample strictly on its other side. */
PN_KFN uint32_t pn_ray_plane(pn_v3 O, pn_v3 A, pn_v3 B, pn_v3 C, const pn_klight *L, float a, float b)
{
    pn_tri_forms F;
    int32_t sp;
    if (!pn_tri_plane(O, A, B, C, L, &F)) return 0u;
    sp = pn_filter(pn_lin_at(F.plane, a, b), F.err_p);
    if (sp == 2) {
        PN_EXACT_HOOK(1);
        sp = -F.dsign * pn_exact_plane(A, B, C, L, a, b);
    }
    return (uint32_t)(sp > 0);
}

/* The plane test in the shear frame (Woop et al.'s t), once the edge functions e of
 * triangle p have one strict sign with bound eb: 1 blocked, 0 not, 2 cannot tell.
 * With the exact e*, the identity U a + V b + W c = det(a, b, c) R for R = (sx*, sy*, 1)
 * gives T* = e*0 p_z + e*1 q_z + e*2 r_z = det(p, q, r) = -(O - A).n, and
 * (S - A).n = P* - T* with P* = D*_z (e*0 + e*1 + e*2) = D*.n; so the predicate's plane
 * test (pn_tri_plane, then the sample's side) is T* != 0, sign T* = sign P* and
 * |T*| < |P*|. sign P* is exact: that of D_z (|D_z - D*_z| <= dl_z < |D_z|) times the
 * edges' common sign. Bounds (S1 = sum |e_q|, zmax = max |P~z| over the vertices):
 * T = fl(fl(fl(e0 A~z) + fl(e1 B~z)) + fl(e2 C~z)) errs by at most 3.0001 u S1 zmax
 * (rounding) + u' S1 zmax + 3.0001 eb zmax (the e and P~z errors): errT = zmax (4.25 u S1
 * + 3.25 eb) + PN_KTINY; P = fl(D_z fl(fl(e0 + e1) + e2)) by at most
 * |D_z| (3.001 u S1 + 3 eb) + (1.0001 S1 + 3 eb) dl_z: errP = |D_z| (3.25 u S1 + 3.25 eb)
 * + 1.0625 (S1 + 3 eb) dl_z + PN_KTINY. |P*| - |T*| > 0 is proved when
 * fl(|P| - |T|) > fl(errT + errP) (the subtraction's rounding is relative, inside the
 * slack), its opposite likewise. */
PN_KFN int32_t pn_ray_hit(const pn_ray *R, PN_CONST float *p, const float *e, float eb)
{
    float az = p[R->kz] - R->oz, bz = p[3u + R->kz] - R->oz, cz = p[6u + R->kz] - R->oz;
    float T = e[0] * az + e[1] * bz + e[2] * cz, P = R->dz * (e[0] + e[1] + e[2]);
    float s1 = pn_ray_abs(e[0]) + pn_ray_abs(e[1]) + pn_ray_abs(e[2]);
    float zmax = pn_kmaxf(pn_ray_abs(az), pn_kmaxf(pn_ray_abs(bz), pn_ray_abs(cz)));
    float errT = zmax * (4.25f * PN_KU * s1 + 3.25f * eb) + PN_KTINY;
    float errP = pn_ray_abs(R->dz) * (3.25f * PN_KU * s1 + 3.25f * eb) + 1.0625f * (s1 + 3.0f * eb) * R->dlz + PN_KTINY;
    float d = pn_ray_abs(P) - pn_ray_abs(T), r = errT + errP;
    if (!(pn_ray_abs(T) > errT)) return 2;
    if ((T > 0.0f) != ((R->dz > 0.0f) == (e[0] > 0.0f))) return 0; /* t < 0: behind O */
    if (d > r) return 1;
    if (-d > r) return 0; /* t > 1: beyond the sample */
    return 2;
}

/* The answer for triangle p from the filter's verdict s != 0 (pn_ray_signs, edge
 * functions e, bound eb): exactly pn_tri_sample()'s. Rare (a blocked ray's blocker, or a
 * value within its bound): out of the traversal loop. */
PN_KFN_COLD uint32_t pn_ray_decide(const pn_ray *R, const pn_klight *L, PN_CONST float *p, int32_t s, const float *e,
                                   float eb)
{
    pn_v3 A, B, C;
    if (s == 1) {
        int32_t h = R->filt ? pn_ray_hit(R, p, e, eb) : 2;
        if (h != 2) return (uint32_t)h;
    }
    A = pn_v3_load(p);
    B = pn_v3_load(p + 3);
    C = pn_v3_load(p + 6);
    if (s == 1) {
        PN_RAY_FALLBACK_HOOK(1);
        return pn_ray_plane(R->O, A, B, C, L, R->a, R->b);
    }
    PN_RAY_FALLBACK_HOOK(0);
    return pn_tri_sample(R->O, A, B, C, L, R->i, R->j);
}

/* The rays of one origin that the reference and GEARS have built, by sample: a pixel's
 * walk decides the same few open samples over many triangles, and a ray's set-up (three
 * divisions, its bounds) costs several times its test. Direct-mapped: sample (i, j) has
 * slot (i ^ (j * PN_RAY_CACHE_J)) mod PN_RAY_CACHE, so the samples of a row, and of a
 * column for k = 16 and 32, have slots of their own; a fetched ray is to be used before
 * the next fetch, which may take its slot. A ray is the same floats whenever it is built,
 * so what the cache holds changes no answer. */
#define PN_RAY_CACHE 16u
#define PN_RAY_CACHE_J 5u
#define PN_RAY_NOBIT 0xFFFFFFFFu

typedef struct pn_ray_cache {
    pn_ray r[PN_RAY_CACHE];
    uint32_t bit[PN_RAY_CACHE]; /* sample j k + i, or PN_RAY_NOBIT */
} pn_ray_cache;

PN_KFN void pn_ray_cache_clear(pn_ray_cache *RC)
{
    uint32_t s;
    for (s = 0; s < PN_RAY_CACHE; s++) RC->bit[s] = PN_RAY_NOBIT;
}

/* The ray to sample (i, j), built if its slot holds another. */
PN_KFN uint32_t pn_ray_cache_get(pn_ray_cache *RC, const pn_ray_origin *X, const pn_klight *L, int32_t i, int32_t j)
{
    uint32_t bit = (uint32_t)j * L->k + (uint32_t)i;
    uint32_t s = ((uint32_t)i ^ ((uint32_t)j * PN_RAY_CACHE_J)) & (PN_RAY_CACHE - 1u);
    if (RC->bit[s] != bit) {
        RC->bit[s] = bit;
        pn_ray_make(X, L, i, j, &RC->r[s]);
    }
    return s;
}

/* 1 if triangle p blocks the ray's sample, with the bound eb of a box holding it
 * (pn_ray_bound, or R->ebr). */
PN_KFN uint32_t pn_ray_tri(const pn_ray *R, const pn_klight *L, PN_CONST float *p, float eb)
{
    float e[3];
    int32_t s;
    pn_ray_edges(R, p, e);
    s = pn_ray_signs(e, eb);
    return s != 0 && pn_ray_decide(R, L, p, s, e, eb);
}


#endif
