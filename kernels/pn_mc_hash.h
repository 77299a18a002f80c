/* pn_mc_hash.h - Monte Carlo shadow maps, the sample hash: Appendix A's reduced MD5, the jittered samples. Part of pn_mcsm.h, which
 * includes it after the constants it uses; see there. */
#ifndef PN_MC_HASH_H
#define PN_MC_HASH_H

/* ---- The sample hash: Appendix A's reduced MD5 ------------------------------------------- */

/* One of the sixteen steps as the appendix writes them: F of the working state t (the
 * appendix's tD), message word m, constant c, rotation s; then the state rotates
 * (tD = tD.yzwx) and is added into the digest. */
PN_KFN void pn_md5r_step(uint32_t *t, uint32_t *dg, uint32_t F, uint32_t m, uint32_t c, uint32_t s)
{
    uint32_t r = t[0] + F + m + c, x = t[1] + ((r << s) + (r >> (32u - s)));
    t[0] = t[1];
    t[1] = t[2];
    t[2] = t[3];
    t[3] = x;
    dg[0] += t[0];
    dg[1] += t[1];
    dg[2] += t[2];
    dg[3] += t[3];
}

/* The round functions of t0, t1, t2. */
#define PN_MD5R_G1(a, b, c) (((a) & (b)) | (~(a) & (c)))
#define PN_MD5R_G2(a, b, c) (((c) & (a)) | (~(c) & (b)))
#define PN_MD5R_G3(a, b, c) ((a) ^ (b) ^ (c))
#define PN_MD5R_G4(a, b, c) ((b) ^ ((a) | ~(c)))
#define PN_MD5R_F1(t) PN_MD5R_G1((t)[0], (t)[1], (t)[2])
#define PN_MD5R_F2(t) PN_MD5R_G2((t)[0], (t)[1], (t)[2])
#define PN_MD5R_F3(t) PN_MD5R_G3((t)[0], (t)[1], (t)[2])
#define PN_MD5R_F4(t) PN_MD5R_G4((t)[0], (t)[1], (t)[2])

/* md5rand(seed, key) of Appendix A: 16 steps (four per round function); the message words
 * the appendix leaves commented out are zero. */
PN_KFN void pn_md5r(const uint32_t *seed, uint32_t key, uint32_t *out)
{
    uint32_t d0 = seed[0] ^ key, d1 = seed[1] ^ key, d2 = seed[2] ^ key, d3 = seed[3] ^ key, t[4];
    out[0] = 0x01234567u;
    out[1] = 0x89ABCDEFu;
    out[2] = 0xFEDCBA98u;
    out[3] = 0x76543210u;
    t[0] = out[0];
    t[1] = out[1];
    t[2] = out[2];
    t[3] = out[3];
    pn_md5r_step(t, out, PN_MD5R_F1(t), d0, 0xD76AA478u, 7u);
    pn_md5r_step(t, out, PN_MD5R_F1(t), d1, 0xE8C7B757u, 12u);
    pn_md5r_step(t, out, PN_MD5R_F1(t), d2, 0x242070DBu, 17u);
    pn_md5r_step(t, out, PN_MD5R_F1(t), d3, 0xC1BDCEEFu, 22u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), d1, 0xF61E2562u, 5u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), 0u, 0xC040B341u, 9u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), 0u, 0x265E5A52u, 14u);
    pn_md5r_step(t, out, PN_MD5R_F2(t), d0, 0xE9B6C7ABu, 20u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0xFFFA3942u, 4u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0x8771F681u, 11u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0x6D9D6122u, 16u);
    pn_md5r_step(t, out, PN_MD5R_F3(t), 0u, 0xFDE5380Cu, 23u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), d0, 0xF4292244u, 6u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), 0u, 0x432AFF98u, 10u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), 0u, 0xAB9423A7u, 15u);
    pn_md5r_step(t, out, PN_MD5R_F4(t), 0u, 0xFC93A039u, 21u);
}

/* The digest's first two words of pn_md5r({s0, s1, s2 + l, s3}, key) for the lanes
 * l = 0 .. PN_MD5R_LANES - 1 (the rays k .. k + 7 of a pixel): the same sixteen steps, each
 * a loop over the lanes with no test (the compilers vectorize it), the state's rotation
 * (tD = tD.yzwx) done by naming: a step with roles (A, B, C, D) = (t0, t1, t2, t3) writes
 * its new t3 into A, and the next step's roles are (B, C, D, A). The digest's other two
 * words, which the samples do not read, are not kept. tests/test_mcsm.c checks every lane
 * against pn_md5r. */
#define PN_MD5R_LANES 8u
#define PN_MD5R_LSTEP(G, A, B, C, D, M, K, S)                                  \
    for (l = 0; l < PN_MD5R_LANES; l++) {                                      \
        uint32_t r_ = A[l] + G(A[l], B[l], C[l]) + (M) + (K);                  \
        A[l] = B[l] + ((r_ << (S)) + (r_ >> (32u - (S))));                      \
        g0[l] += B[l];                                                         \
        g1[l] += C[l];                                                         \
    }
PN_KFN void pn_md5r_lanes(uint32_t s0, uint32_t s1, uint32_t s2, uint32_t s3, uint32_t key, uint32_t *g0,
                          uint32_t *g1)
{
    uint32_t d0 = s0 ^ key, d1 = s1 ^ key, d3 = s3 ^ key, d2[PN_MD5R_LANES], A[PN_MD5R_LANES], B[PN_MD5R_LANES];
    uint32_t C[PN_MD5R_LANES], D[PN_MD5R_LANES], l;
    (void)D;
    for (l = 0; l < PN_MD5R_LANES; l++) {
        d2[l] = (s2 + l) ^ key;
        A[l] = 0x01234567u;
        B[l] = 0x89ABCDEFu;
        C[l] = 0xFEDCBA98u;
        D[l] = 0x76543210u;
        g0[l] = 0x01234567u;
        g1[l] = 0x89ABCDEFu;
    }
    PN_MD5R_LSTEP(PN_MD5R_G1, A, B, C, D, d0, 0xD76AA478u, 7u)
    PN_MD5R_LSTEP(PN_MD5R_G1, B, C, D, A, d1, 0xE8C7B757u, 12u)
    PN_MD5R_LSTEP(PN_MD5R_G1, C, D, A, B, d2[l], 0x242070DBu, 17u)
    PN_MD5R_LSTEP(PN_MD5R_G1, D, A, B, C, d3, 0xC1BDCEEFu, 22u)
    PN_MD5R_LSTEP(PN_MD5R_G2, A, B, C, D, d1, 0xF61E2562u, 5u)
    PN_MD5R_LSTEP(PN_MD5R_G2, B, C, D, A, 0u, 0xC040B341u, 9u)
    PN_MD5R_LSTEP(PN_MD5R_G2, C, D, A, B, 0u, 0x265E5A52u, 14u)
    PN_MD5R_LSTEP(PN_MD5R_G2, D, A, B, C, d0, 0xE9B6C7ABu, 20u)
    PN_MD5R_LSTEP(PN_MD5R_G3, A, B, C, D, 0u, 0xFFFA3942u, 4u)
    PN_MD5R_LSTEP(PN_MD5R_G3, B, C, D, A, 0u, 0x8771F681u, 11u)
    PN_MD5R_LSTEP(PN_MD5R_G3, C, D, A, B, 0u, 0x6D9D6122u, 16u)
    PN_MD5R_LSTEP(PN_MD5R_G3, D, A, B, C, 0u, 0xFDE5380Cu, 23u)
    PN_MD5R_LSTEP(PN_MD5R_G4, A, B, C, D, d0, 0xF4292244u, 6u)
    PN_MD5R_LSTEP(PN_MD5R_G4, B, C, D, A, 0u, 0x432AFF98u, 10u)
    PN_MD5R_LSTEP(PN_MD5R_G4, C, D, A, B, 0u, 0xAB9423A7u, 15u)
    PN_MD5R_LSTEP(PN_MD5R_G4, D, A, B, C, 0u, 0xFC93A039u, 21u)
}
#undef PN_MD5R_LSTEP

/* The seed's last word of every ray's hash. */
#define PN_MC_SEED3 0x9E3779B9u

/* Jittered sample of ray (i, j) of the n x n grid from its hash's first two words h0, h1:
 * light coordinates (a, b) in [-1, 1)^2 (the light point c + a U + b V), 24 bits of each
 * word converted exactly. */
PN_KFN void pn_mc_jitter(uint32_t i, uint32_t j, uint32_t n, uint32_t h0, uint32_t h1, float *a, float *b)
{
    *a = 2.0f * (((float)i + (float)(h0 >> 8) * 5.9604644775390625e-8f) / (float)n) - 1.0f;
    *b = 2.0f * (((float)j + (float)(h1 >> 8) * 5.9604644775390625e-8f) / (float)n) - 1.0f;
}

/* Jittered sample of ray (i, j) of the n x n grid for pixel (x, y): pn_md5r seeded by
 * {x, y, j n + i, PN_MC_SEED3} and keyed by the frame key. (The pixel pass draws eight rays'
 * hashes at once, pn_md5r_lanes.) */
PN_KFN void pn_mc_sample(uint32_t x, uint32_t y, uint32_t i, uint32_t j, uint32_t n, uint32_t key, float *a, float *b)
{
    uint32_t seed[4], h[4];
    seed[0] = x;
    seed[1] = y;
    seed[2] = j * n + i;
    seed[3] = PN_MC_SEED3;
    pn_md5r(seed, key, h);
    pn_mc_jitter(i, j, n, h[0], h[1], a, b);
}

#endif
