/* pn_mc_pixel.h - Monte Carlo shadow maps, one pixel: classes, runs of pixels, the pixel's rays. Part of pn_mcsm.h, which
 * includes it after the constants it uses; see there. */
#ifndef PN_MC_PIXEL_H
#define PN_MC_PIXEL_H

/* Pixel classes (the counters: class c counts in word c - 1). A pixel the classification
 * left potentially in penumbra is then told apart by what its rays found: some blocked and
 * some not (PENUMBRA), none blocked by the layers (PENUMBRA_OPEN: the classification could
 * have called it lit; its visibility is the horizon's alone), or samples in front of its
 * surface and every one of them blocked by the layers (PENUMBRA_SHUT). The last two measure how tight the classification is (§3.6:
 * "two iterations are generally sufficient to produce a tight bound around penumbrae"). */
#define PN_MC_CLASS_NONE 0u
#define PN_MC_CLASS_LIT 1u
#define PN_MC_CLASS_UMBRA 2u
#define PN_MC_CLASS_PENUMBRA 3u
#define PN_MC_CLASS_PENUMBRA_OPEN 4u
#define PN_MC_CLASS_PENUMBRA_SHUT 5u
#define PN_MC_CLASS_GRAZING 6u /* resolved by the exact fallback: PN_MC_VIS_OUTSIDE */
#define PN_MC_CLASS_STACKED 8u /* resolved by exact rays: PN_MC_VIS_STACKED (class 7 is the
                                  capped searches' word) */

/* Pixels of a row that the classification first tests as one run (pn_mc_run). */
#define PN_MC_RUN 16u

/* 1: the pixel pass's ray lanes also compute where each ray's own region lies in the
 * N-buffer (pn_mc_region_at, eight rays in a loop of selects); 0: each ray that needs its
 * region computes it (pn_mc_region). The same lookups either way. The lanes pay where the
 * compiler vectorizes that loop, which takes 32-bit vector multiplies (SSE4.1, NEON): chess,
 * 512x512, callgrind: x86-64-v3 226.3 -> 218.8 M instructions with them; the baseline
 * x86-64 target (SSE2) 355.8 -> 385.9 M, every lane's region computed one by one. */
#ifndef PN_MC_LANE_REGIONS
#if defined(__SSE4_1__) || defined(__ARM_NEON)
#define PN_MC_LANE_REGIONS 1
#else
#define PN_MC_LANE_REGIONS 0
#endif
#endif

/* A G-buffer pixel as the pixel pass takes it (pn_mc_run). */
#define PN_MC_PX_NONE 0u     /* no surface: visibility 1 */
#define PN_MC_PX_NO_ORIGIN 1u /* no shadow-ray origin (pn_shadow_origin): visibility 0 */
#define PN_MC_PX_SURFACE 2u  /* the fields below hold */
#define PN_MC_PX_LIT 3u      /* a surface of a run found lit, facing the light centre, not grazed
                              * (pn_mc_bias), with the light's four corners in front of its
                              * plane: visibility 1, class lit (pn_mc_pixel's answer); no field
                              * below is set */
#define PN_MC_PX_OUTSIDE 4u  /* a surface whose origin no window holds (pn_lview_outside): the
                              * layers hold none of its occluders; the pixel pass marks it
                              * PN_MC_VIS_OUTSIDE for the exact fallback's pass; no field below
                              * is set */
#define PN_MC_VIS_OUTSIDE (-1.0f) /* the visibility buffer's mark of such a pixel */
#define PN_MC_VIS_STACKED (-2.0f) /* ...and of a pixel whose rays a stacked texel blocked */
typedef struct pn_mc_px {
    pn_v3 nrm, O, E; /* unit normal, shadow-ray origin, O in the light frame */
    float ex, ey;    /* E's image, and */
    float b[4];      /* the classification's first region (pn_mc_reach at whole[0]): set
                      * when the classification looks at the pixel (faces, E beyond whole[0]) */
    uint32_t kind;   /* PN_MC_PX_* */
    uint32_t faces;  /* E in front of the light plane and the normal toward the light centre
                      * (else umbra before any classification, pn_mc_pixel) */
    uint32_t front;  /* the light's corners on the front side of its plane (0 .. 4) */
} pn_mc_px;

/* The run of count G-buffer pixels from pix on (S) into px[0 .. count), and
 * whether the classification may call every one lit at once. Each pixel that the
 * classification would look at has its first region, pn_mc_reach at the whole map's
 * nearest depth zb: the rays from every light point to it stay there from zb on. When no
 * occluder in the union of those regions is nearer than the farthest of their origins, no
 * ray of any of them meets a layer: each is lit, as its own first region would have told
 * (a region's lookup covers a superset of its box, pn_nb_mm_rect_at, and the union's can
 * miss part of one pixel's: that part holds none of the pixel's rays, so the pixel would
 * have traced them all unblocked, the same visibility). One lookup for the run instead of
 * one or two per lit pixel, most of a frame (chess, 512x512: the classification's 247,934
 * lookups become 84,290 and 16,384 runs'; its pass 6% fewer instructions, 11% less time).
 * Without the classification (point light, PN_MC_F_NO_CLASSIFY): 0. A surface of a lit run
 * that faces the light centre with the whole light in front of its plane comes back as
 * PN_MC_PX_LIT (most of a frame's pixels); the others get the fields pn_mc_pixel reads. */
PN_KFN int pn_mc_run(const pn_mc_ctx *m, const pn_ksurf *S, size_t pix, uint32_t count, pn_mc_px *px)
{
    const pn_kmc *mc = m->mc;
    const pn_klight *L = m->L;
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]);
    float zb = mc->whole[0], zmax = 0.0f, u[4], q[PN_NB_MM];
    float Ox[PN_MC_RUN], Oy[PN_MC_RUN], Oz[PN_MC_RUN], Ex[PN_MC_RUN], Ey[PN_MC_RUN], Ez[PN_MC_RUN];
    float Nx[PN_MC_RUN], Ny[PN_MC_RUN], Nz[PN_MC_RUN];
    float ex[PN_MC_RUN], ey[PN_MC_RUN], b0[PN_MC_RUN], b1[PN_MC_RUN], b2[PN_MC_RUN], b3[PN_MC_RUN];
    int sees[PN_MC_RUN], faces[PN_MC_RUN], front[PN_MC_RUN], looks[PN_MC_RUN], sheet[PN_MC_RUN], inv[PN_MC_RUN];
    int grazed[PN_MC_RUN];
    int out[PN_MC_RUN];
    uint32_t i, any = 0u;
    int lit;
    int classify = !(mc->flags & PN_MC_F_NO_CLASSIFY) && !L->is_point;
    PN_CONST uint32_t *ids = S->tri_id;
    /* Every pixel's origin, light-frame point, image and first region, in one loop with no
     * branch (the compilers vectorize it: seven divisions a pixel), whatever its kind; a
     * pixel with no surface has some point and normal in the G-buffer, whose results are
     * not read. */
    /* A sheet's side toward the light centre is its front (PN_TRI_SHEET), an inside-out
     * solid's is the side its winding turns away (PN_TRI_INVERTED): which pixels see one,
     * looked up apart so that the loop below stays free of loads by index. */
    for (i = 0; i < count; i++) {
        uint32_t id = ids[pix + i], f = id != PN_NO_PIXEL_TRIANGLE ? m->flags[id] : 0u;
        pn_v3 P, n;
        sheet[i] = (f & PN_TRI_SHEET) != 0u;
        inv[i] = (f & PN_TRI_INVERTED) != 0u;
        pn_surf_at(S, pix + i, &P, &n); /* into the arrays the loop below writes */
        pn_v3_put(Ox, Oy, Oz, i, P);
        pn_v3_put(Nx, Ny, Nz, i, n);
    }
    for (i = 0; i < count; i++) {
        pn_v3 n = pn_v3_make(Nx[i], Ny[i], Nz[i]), P = pn_v3_make(Ox[i], Oy[i], Oz[i]), O, E;
        float b[4], x, y;
        n = pn_v3_scale(n, (sheet[i] && pn_v3_dot(n, pn_v3_sub(c, P)) < 0.0f) || inv[i] ? -1.0f : 1.0f);
        sees[i] = pn_shadow_origin(P, n, L, &O);
        E = pn_lview_frame(m->lv, L, O);
        faces[i] = E.z > 0.0f && !(pn_v3_dot(n, pn_v3_sub(c, O)) < 0.0f);
        grazed[i] = pn_mc_cos(n, pn_v3_sub(c, O)) < PN_MC_COS_MIN; /* pn_mc_bias's test */
        out[i] = pn_lview_outside(E, m->ha, m->hb);
        front[i] = (pn_v3_dot(pn_v3_sub(m->corner[0], O), n) > 0.0f) + (pn_v3_dot(pn_v3_sub(m->corner[1], O), n) > 0.0f) +
                   (pn_v3_dot(pn_v3_sub(m->corner[2], O), n) > 0.0f) + (pn_v3_dot(pn_v3_sub(m->corner[3], O), n) > 0.0f);
        pn_mc_proj(m, E, &x, &y);
        pn_mc_reach(m, E, x, y, zb, b);
        pn_v3_put(Nx, Ny, Nz, i, n);
        pn_v3_put(Ox, Oy, Oz, i, O);
        pn_v3_put(Ex, Ey, Ez, i, E);
        ex[i] = x;
        ey[i] = y;
        b0[i] = b[0];
        b1[i] = b[1];
        b2[i] = b[2];
        b3[i] = b[3];
    }
    /* Each pixel's kind, and the union of the first regions the classification would look
     * at (a surface facing the light, beyond the whole map's nearest depth: else lit by that
     * alone), in pixel order. */
    u[0] = u[1] = PN_KINF;
    u[2] = u[3] = -PN_KINF;
    for (i = 0; i < count; i++) {
        px[i].kind = ids[pix + i] == 0xFFFFFFFFu ? PN_MC_PX_NONE /* PN_NO_PIXEL_TRIANGLE */
                                                 : (sees[i] ? PN_MC_PX_SURFACE : PN_MC_PX_NO_ORIGIN);
        if (px[i].kind == PN_MC_PX_SURFACE && out[i]) px[i].kind = PN_MC_PX_OUTSIDE;
        looks[i] = px[i].kind == PN_MC_PX_SURFACE && classify && faces[i] && zb < Ez[i];
        if (!looks[i]) continue;
        u[0] = pn_kminf(u[0], b0[i]);
        u[1] = pn_kminf(u[1], b1[i]);
        u[2] = pn_kmaxf(u[2], b2[i]);
        u[3] = pn_kmaxf(u[3], b3[i]);
        zmax = pn_kmaxf(zmax, Ez[i]);
        any = 1u;
    }
    if (!classify) lit = 0;
    else if (!any) lit = 1;
    else {
        pn_mc_region(m, u[0], u[1], u[2], u[3], q);
        lit = !(pn_kmaxf(zb, q[0]) < zmax);
    }
    /* What pn_mc_pixel reads, for the surfaces it will see. */
    for (i = 0; i < count; i++) {
        pn_mc_px *p = px + i;
        if (p->kind != PN_MC_PX_SURFACE) continue;
        if (lit && faces[i] && front[i] == 4 && !grazed[i]) {
            p->kind = PN_MC_PX_LIT;
            continue;
        }
        p->nrm = pn_v3_make(Nx[i], Ny[i], Nz[i]);
        p->O = pn_v3_make(Ox[i], Oy[i], Oz[i]);
        p->E = pn_v3_make(Ex[i], Ey[i], Ez[i]);
        p->front = (uint32_t)front[i];
        p->faces = (uint32_t)faces[i];
        if (!looks[i]) continue;
        p->ex = ex[i];
        p->ey = ey[i];
        p->b[0] = b0[i];
        p->b[1] = b1[i];
        p->b[2] = b2[i];
        p->b[3] = b3[i];
    }
    return lit;
}

/* The first two hash words of rays k .. of pixel (x, y) (n2 rays in all) into h0, h1 at
 * k % PN_MD5R_LANES: eight lanes at once, or the last ray alone (the ninth of 3x3: eight
 * lanes cost about what three single hashes do). The same words either way (test_mcsm). */
PN_KFN void pn_mc_hashes(uint32_t x, uint32_t y, uint32_t k, uint32_t n2, uint32_t key, uint32_t *h0, uint32_t *h1)
{
    uint32_t seed[4], h[4];
    if (n2 - k > 1u) {
        pn_md5r_lanes(x, y, k, PN_MC_SEED3, key, h0, h1);
        return;
    }
    seed[0] = x;
    seed[1] = y;
    seed[2] = k;
    seed[3] = PN_MC_SEED3;
    pn_md5r(seed, key, h);
    h0[0] = h[0];
    h1[0] = h[1];
}

/* Visibility of G-buffer pixel (x, y), a surface with a shadow-ray origin as pn_mc_run gave
 * it (p); run_lit: pn_mc_run said its run is lit. *cls: its class; *rays: rays searched. */
PN_KFN float pn_mc_pixel(pn_mc_ctx *m, uint32_t x, uint32_t y, const pn_mc_px *p, int run_lit, uint32_t *cls,
                         uint32_t *rays)
{
    const pn_kmc *mc = m->mc;
    const pn_klight *L = m->L;
    pn_v3 nrm = p->nrm, O = p->O, E = p->E;
    pn_v3 c = pn_v3_make(L->c[0], L->c[1], L->c[2]), toc = pn_v3_sub(c, O);
    pn_v3 U = pn_v3_make(L->U[0], L->U[1], L->U[2]), V = pn_v3_make(L->V[0], L->V[1], L->V[2]);
    /* q is set whenever it is read; GCC 12 for arm-none-eabi cannot tell and warns */
    float ze = E.z, bias = 0.0f, zlo = 0.0f, zhi = PN_KINF, q[PN_NB_MM] = {0.0f, 0.0f, 0.0f};
    uint32_t n = L->is_point ? 1u : mc->rays, i, j, k = 0u, open = 0u, ahead = 0u, h0[PN_MD5R_LANES], h1[PN_MD5R_LANES];
    int classify = !(mc->flags & PN_MC_F_NO_CLASSIFY);
    m->stacked = 0u;
    *rays = 0u;
    *cls = PN_MC_CLASS_PENUMBRA;
    /* A surface whose winding turns it away from the light centre is umbra: the thesis'
     * first early-out, "the surface normal faces opposite the ray", per fragment toward the
     * light centre (§3.7 allows it), which is what the exact algorithms' convention gives a
     * closed mesh (the normal turned toward the light puts the origin inside the solid,
     * whose own faces then block every sample). The layers cannot show a surface its own
     * back side, so without it such a face is lit through its own solid. Otherwise nrm
     * faces the light centre, and a ray toward a light point behind its plane is blocked
     * (invariant 6's horizon). An origin on or behind the light plane sees no light. */
    if (!p->faces) { /* pn_mc_run: !(E.z > 0) or the normal's dot with toc below 0 */
        *cls = PN_MC_CLASS_UMBRA;
        return 0.0f;
    }
    /* A grazed surface (pn_mc_bias): the exact fallback's pass, before any class (whose
     * model it leaves: with the class first, a grazed pixel called lit took the horizon's
     * count, 0 or 1 from pixel to pixel, where the rays' pass took the exact answer;
     * fuzz_culls). */
    bias = pn_mc_bias(mc, nrm, toc, ze);
    if (bias < 0.0f) {
        *cls = PN_MC_CLASS_GRAZING;
        return PN_MC_VIS_OUTSIDE;
    }
    if (classify && !L->is_point && run_lit) {
        *cls = PN_MC_CLASS_LIT;
        n = 0u;
    } else if (classify && !L->is_point) {
        /* Penumbra classification (§3.6): the region every ray can reach from depth zb on
         * (pn_mc_reach), its smallest near depth the next zb, twice, from the whole map's. */
        uint32_t it;
        float zb = mc->whole[0], nz, b[4]; /* the whole map's, src/pn_mcsm.c */
        for (it = 0; it < 2u && zb < ze; it++) {
            /* the first region pn_mc_run's (it set it: the pixel faces, zb < ze here) */
            if (it == 0u) b[0] = p->b[0], b[1] = p->b[1], b[2] = p->b[2], b[3] = p->b[3];
            else pn_mc_reach(m, E, p->ex, p->ey, zb, b);
            pn_mc_region(m, b[0], b[1], b[2], b[3], q);
            nz = pn_kmaxf(zb, q[0]);
            if (nz == zb) break; /* zb stays: the next region would be this one */
            zb = nz;
        }
        if (!(zb < ze)) {
            *cls = PN_MC_CLASS_LIT;
            n = 0u; /* every ray unblocked but for the horizon */
        } else {
            /* Umbra: every ray ends behind every near texel it can cross. With three
             * layers too: the eye could clear some of those texels, but the six scenes the
             * third layer moves most gave the same RMSE to four digits without this class
             * (512x512), and the class saves their searches. */
            if (ze - bias > q[2]) {
                *cls = PN_MC_CLASS_UMBRA;
                return 0.0f;
            }
            zlo = zb;
            if (mc->layers >= 2u) zhi = q[1];
        }
    }
    if (n == 0u) {
        /* Lit: only the horizon blocks. A light wholly in front of (behind) the surface
         * leaves every ray open (blocked): the sample points are convex combinations of the
         * corners. Otherwise the rays' light points, as they would be drawn. */
        uint32_t g = mc->rays, vis = 0u;
        if (p->front == 4u) return 1.0f; /* pn_mc_run counted the corners in front */
        if (p->front == 0u) return 0.0f;
        for (j = 0; j < g; j++)
            for (i = 0; i < g; i++, k++) {
                float a, b;
                pn_v3 S;
                if (k % PN_MD5R_LANES == 0u) pn_mc_hashes(x, y, k, g * g, mc->seed, h0, h1);
                pn_mc_jitter(i, j, g, h0[k % PN_MD5R_LANES], h1[k % PN_MD5R_LANES], &a, &b);
                S = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, a), pn_v3_scale(V, b)));
                vis += pn_v3_dot(pn_v3_sub(S, O), nrm) > 0.0f;
            }
        return (float)vis / (float)(g * g);
    }
    if (L->is_point) {
        /* One ray to the light's centre, and one texel holds it: a shadow-map test. */
        float len = pn_ksqrt(pn_v3_dot(pn_v3_sub(O, c), pn_v3_sub(O, c))), tend, zend, T[PN_NB_MM];
        pn_v3 Sl = pn_lview_frame(m->lv, L, c);
        pn_mc_ray r;
        int out, blocked;
        *cls = PN_MC_CLASS_PENUMBRA_OPEN; /* no sample blocked by a layer, on the two returns below */
        if (!(pn_v3_dot(toc, nrm) > 0.0f)) return 0.0f; /* behind P's own plane: no sample ahead */
        r.xs = Sl.x;
        r.ys = Sl.y;
        r.xe = E.x;
        r.ye = E.y;
        r.ze = ze;
        tend = len > bias ? 1.0f - bias / len : 0.0f;
        if (!(tend > 0.0f)) return 1.0f;
        zend = tend * ze;
        pn_nb_mm_get(pn_mc_texel(m, pn_mc_at(&r, tend), &out), T);
        blocked = !out && (mc->layers == 1u ? zend >= T[0] : zend >= T[0] && T[1] >= 0.0f);
        if (blocked && mc->layers == 3u) {
            float za = pn_kmaxf(T[0], 0.0f), zb2 = pn_kminf(T[1], zend);
            blocked = !pn_mc_seen(m, pn_mc_at(&r, 0.5f * (za + zb2) / ze), T[1] - T[0]);
        }
        *rays += 1u;
        m->steps++;
        if (blocked && !out && pn_mc_stacked_texel(pn_mc_texel(m, pn_mc_at(&r, tend), &out))) {
            *cls = PN_MC_CLASS_STACKED;
            return PN_MC_VIS_STACKED;
        }
        *cls = blocked ? PN_MC_CLASS_PENUMBRA_SHUT : PN_MC_CLASS_PENUMBRA_OPEN;
        return blocked ? 0.0f : 1.0f;
    }
    for (k = 0; k < n * n; k += PN_MD5R_LANES) {
        /* Eight rays at a time: their set-up (sample, plane test, light-frame start, biased
         * end, the clip to the map, the images of the end and of the searched range's ends;
         * then where the end's texel, and with PN_MC_LANE_REGIONS the ray's own region, lie
         * in the N-buffer) in loops with no branch, which the compilers vectorize; then each
         * ray's lookups and search in order. Every ray's float operations are the ones it had
         * alone, in the same order. */
        uint32_t cnt = pn_kminu(PN_MD5R_LANES, n * n - k), l;
        uint32_t li[PN_MD5R_LANES], lj[PN_MD5R_LANES], eat[PN_MD5R_LANES];
        int ah[PN_MD5R_LANES], eout[PN_MD5R_LANES];
#if PN_MC_LANE_REGIONS
        uint32_t rn[PN_MD5R_LANES], ra[4][PN_MD5R_LANES], rl[PN_MD5R_LANES]; /* box b of lane l's region at
                                                                                 ra[b][l], of level rl[l] */
        int rbey[PN_MD5R_LANES];
#endif
        float xs[PN_MD5R_LANES], ys[PN_MD5R_LANES], te[PN_MD5R_LANES], lt0[PN_MD5R_LANES], lt1[PN_MD5R_LANES];
        float epx[PN_MD5R_LANES], epy[PN_MD5R_LANES], ax[PN_MD5R_LANES], ay[PN_MD5R_LANES], bx[PN_MD5R_LANES],
            by[PN_MD5R_LANES];
        float t0s = zlo / ze * (1.0f - PN_MC_T_SLACK), t1s = zhi / ze * (1.0f + PN_MC_T_SLACK);
        pn_mc_hashes(x, y, k, n * n, mc->seed, h0, h1);
        for (l = 0, i = k % n, j = k / n; l < cnt; l++) {
            li[l] = i;
            lj[l] = j;
            if (++i == n) i = 0u, j++;
        }
        for (l = 0; l < cnt; l++) {
            float a, b, len, bl, tend, t0 = t0s, t1;
            pn_v3 S, Sl;
            pn_mc_ray r;
            pn_mc_jitter(li[l], lj[l], n, h0[l], h1[l], &a, &b);
            S = pn_v3_add(c, pn_v3_add(pn_v3_scale(U, a), pn_v3_scale(V, b)));
            ah[l] = pn_v3_dot(pn_v3_sub(S, O), nrm) > 0.0f; /* else behind P's own plane */
            Sl = pn_lview_frame(m->lv, L, S);
            r.xs = Sl.x;
            r.ys = Sl.y;
            r.xe = E.x;
            r.ye = E.y;
            r.ze = ze;
            len = pn_ksqrt(pn_v3_dot(pn_v3_sub(O, S), pn_v3_sub(O, S)));
            bl = 1.0f - bias / len; /* on every path: a select, not a branch */
            tend = len > bias ? bl : 0.0f;
            t1 = pn_kminf(tend, t1s);
            pn_mc_clip(m, &r, &t0, &t1);
            pn_mc_proj(m, pn_mc_at(&r, tend), &epx[l], &epy[l]);
            pn_mc_proj(m, pn_mc_at(&r, t0), &ax[l], &ay[l]);
            pn_mc_proj(m, pn_mc_at(&r, t1), &bx[l], &by[l]);
            xs[l] = r.xs;
            ys[l] = r.ys;
            te[l] = tend;
            lt0[l] = t0;
            lt1[l] = t1;
        }
        for (l = 0; l < cnt; l++) {
            /* where the two lookups below read: the end's texel, the ray's own region (a
             * loop of its own: in the one above, GCC vectorizes neither) */
            eat[l] = pn_mc_texel_at(m, epx[l], epy[l], &eout[l]);
#if PN_MC_LANE_REGIONS
            {
                uint32_t at4[4], b;
                rn[l] = pn_mc_region_at(m, ax[l], ay[l], bx[l], by[l], at4, &rl[l], &rbey[l]);
                for (b = 0; b < 4u; b++) ra[b][l] = at4[b];
            }
#endif
        }
        for (l = 0; l < cnt; l++) {
            float t0 = lt0[l], t1 = lt1[l];
            pn_mc_ray r;
            if (!ah[l]) continue;
            ahead++;
            if (!(te[l] > 0.0f)) {
                open++;
                continue;
            }
            r.xs = xs[l];
            r.ys = ys[l];
            r.xe = E.x;
            r.ye = E.y;
            r.ze = ze;
            {
                /* The ray's end inside a texel's interval: blocked, with one lookup. Part of
                 * the model, not only an early-out: the searches walk [t0, t1) and leave out
                 * the end itself, and an end exactly on the edge of a solid texel (thin,
                 * 512x512: a ray whose image ends at x = 426.000) is blocked by this test
                 * and by no search step. */
                int st = pn_mc_state_at(m, pn_mc_at(&r, te[l]), eat[l], eout[l]);
                m->steps++;
                if (st == PN_MC_INSIDE) {
                    if (pn_mc_stacked_texel(m->nb + eat[l])) m->stacked = 1u;
                    continue;
                }
            }
            if (classify && t0 < t1) {
                /* The ray's own region (§3.7): nothing before its end, or shortened. */
#if PN_MC_LANE_REGIONS
                uint32_t at4[4], b;
                for (b = 0; b < 4u; b++) at4[b] = ra[b][l];
                pn_mc_region_get(m, at4, rn[l], rl[l], rbey[l], q);
#else
                pn_mc_region(m, ax[l], ay[l], bx[l], by[l], q);
#endif
                m->steps++;
                t0 = pn_kmaxf(t0, q[0] / ze * (1.0f - PN_MC_T_SLACK));
                if (mc->layers >= 2u) t1 = pn_kminf(t1, q[1] / ze * (1.0f + PN_MC_T_SLACK));
            }
            if (!(t0 <= t1)) {
                open++;
                continue;
            }
            *rays += 1u;
            if (!(mc->search == PN_MC_S_LINEAR ? pn_mc_linear(m, &r, t0, t1) : pn_mc_hier(m, &r, t0, t1))) open++;
        }
    }
    /* A ray the layers blocked in a stacked texel: the gap between two solids along the
     * light's ray may be where it passes. The pixel's rays are traced exactly instead
     * (pn_mc_exact_rays, the fallback's pass). */
    if (m->stacked) {
        *cls = PN_MC_CLASS_STACKED;
        return PN_MC_VIS_STACKED;
    }
    /* open: the samples in front of P's plane (ahead) that no layer blocked */
    *cls = open == ahead ? PN_MC_CLASS_PENUMBRA_OPEN : (open == 0u ? PN_MC_CLASS_PENUMBRA_SHUT : PN_MC_CLASS_PENUMBRA);
    return (float)open / (float)(n * n);
}

#endif
