/* test_gltf.c - host I/O: the glTF loader on the shared scene set and on hostile files built
 * here at run time (nothing binary is committed), the mesh helpers, and PFM / PNG / id
 * output. Generated files go to PN_TEST_OUT_DIR (the build directory). */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pn_gltf.h"
#include "pn_image.h"
#include "pn_mesh.h"
#include "pn_test.h"

#ifndef PN_SCENES_DIR
#error "PN_SCENES_DIR must be defined by the build (absolute path of ../shared/scenes)"
#endif
#ifndef PN_SCENE_GLBS
#define PN_SCENE_GLBS ""
#endif
#ifndef PN_TEST_OUT_DIR
#define PN_TEST_OUT_DIR "."
#endif

#define ERR_SIZE 512

/* ---- small helpers ---- */

static void out_path(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/test_gltf_%s", PN_TEST_OUT_DIR, name);
}

static unsigned char *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    unsigned char *data = NULL;
    long end;
    *size = 0;
    if (f == NULL) {
        return NULL;
    }
    if (fseek(f, 0, SEEK_END) == 0 && (end = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0) {
        data = (unsigned char *)malloc((size_t)end + 1u);
        if (data != NULL && fread(data, 1, (size_t)end, f) == (size_t)end) {
            *size = (size_t)end;
        } else {
            free(data);
            data = NULL;
        }
    }
    fclose(f);
    return data;
}

static int write_file(const char *path, const void *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    int ok;
    if (f == NULL) {
        return 0;
    }
    ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

static void put_le32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v & 0xffu);
    p[1] = (unsigned char)((v >> 8) & 0xffu);
    p[2] = (unsigned char)((v >> 16) & 0xffu);
    p[3] = (unsigned char)((v >> 24) & 0xffu);
}

static uint32_t get_le32(const unsigned char *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

static int mesh_is_zero(const pn_mesh *m)
{
    return m->positions == NULL && m->indices == NULL && m->vertex_count == 0 &&
           m->triangle_count == 0;
}

/* Growable string for JSON. */
typedef struct sbuf {
    char *s;
    size_t len, cap;
} sbuf;

static void sb_add(sbuf *b, const char *fmt, ...)
{
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0) {
        return;
    }
    if (b->len + (size_t)n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 256;
        char *s;
        while (cap < b->len + (size_t)n + 1) {
            cap *= 2;
        }
        s = (char *)realloc(b->s, cap);
        if (s == NULL) {
            return;
        }
        b->s = s;
        b->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(b->s + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    b->len += (size_t)n;
}

/* GLB = 12-byte header, JSON chunk (space padded), BIN chunk (zero padded, omitted when
 * bin_size is 0). */
static unsigned char *build_glb(const char *json, const void *bin, size_t bin_size,
                                size_t *out_size)
{
    size_t jlen = strlen(json), jpad = (jlen + 3u) & ~(size_t)3u;
    size_t bpad = (bin_size + 3u) & ~(size_t)3u;
    size_t total = 12u + 8u + jpad + (bin_size ? 8u + bpad : 0u);
    unsigned char *g = (unsigned char *)calloc(1, total);
    unsigned char *p;
    if (g == NULL) {
        *out_size = 0;
        return NULL;
    }
    memcpy(g, "glTF", 4);
    put_le32(g + 4, 2);
    put_le32(g + 8, (uint32_t)total);
    put_le32(g + 12, (uint32_t)jpad);
    memcpy(g + 16, "JSON", 4);
    memcpy(g + 20, json, jlen);
    memset(g + 20 + jlen, ' ', jpad - jlen);
    if (bin_size) {
        p = g + 20 + jpad;
        put_le32(p, (uint32_t)bpad);
        memcpy(p + 4, "BIN\0", 4);
        memcpy(p + 8, bin, bin_size);
    }
    *out_size = total;
    return g;
}

/* A small one-mesh scene; fields left zero/NULL take the defaults noted. */
typedef struct tiny_spec {
    const float *pos;       /* nverts * 3 */
    unsigned nverts;
    int itype;              /* 0 = not indexed; else the indices componentType */
    const uint32_t *idx;
    unsigned nidx;
    const char *nodes;      /* "nodes" array; NULL = [{"mesh":0}] */
    const char *scenes;     /* members before "nodes"; NULL = one default scene with node 0 */
    long pos_count;         /* POSITION accessor count; 0 = nverts */
    long view0_len;         /* positions bufferView byteLength; 0 = nverts * 12 */
    long view0_stride;      /* positions bufferView byteStride; 0 = absent */
    long buffer_len;        /* buffers[0].byteLength; 0 = the BIN size */
    int pos_ctype;          /* POSITION componentType; 0 = 5126 */
    const unsigned char *pos_raw; /* the positions' bytes as stored (nverts elements); NULL =
                                     pos as floats */
    unsigned pos_raw_len;   /* their length */
    int pos_norm;           /* POSITION "normalized": true */
    int mesh_prims;         /* copies of the primitive in mesh 0; 0 = 1 */
    const char *prim0;      /* extra members of the first primitive only */
    const char *top;        /* extra top-level members */
} tiny_spec;

static const float quad_pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static const uint32_t quad_idx[6] = {0, 1, 2, 0, 2, 3};

static size_t index_bytes(int itype)
{
    return itype == 5121 ? 1u : itype == 5123 ? 2u : 4u;
}

static unsigned char *build_tiny(const tiny_spec *sp, size_t *size)
{
    const float *pos = sp->pos ? sp->pos : quad_pos;
    unsigned nverts = sp->pos || sp->pos_raw ? sp->nverts : 4u;
    const uint32_t *idx = sp->idx ? sp->idx : quad_idx;
    unsigned nidx = sp->idx ? sp->nidx : 6u;
    size_t pos_bytes = sp->pos_raw ? ((size_t)sp->pos_raw_len + 3u) & ~(size_t)3u : (size_t)nverts * 12u;
    size_t isz = index_bytes(sp->itype);
    size_t idx_bytes = sp->itype ? (size_t)nidx * isz : 0u;
    size_t bin_size = pos_bytes + ((idx_bytes + 3u) & ~(size_t)3u);
    unsigned char *bin = (unsigned char *)calloc(1, bin_size ? bin_size : 1u);
    unsigned char *glb;
    sbuf j = {NULL, 0, 0};
    unsigned i;
    int p, nprims = sp->mesh_prims ? sp->mesh_prims : 1;

    if (sp->pos_raw) memcpy(bin, sp->pos_raw, sp->pos_raw_len);
    for (i = 0; !sp->pos_raw && i < nverts * 3u; i++) {
        uint32_t bits;
        memcpy(&bits, &pos[i], 4);
        put_le32(bin + (size_t)i * 4u, bits);
    }
    for (i = 0; sp->itype && i < nidx; i++) {
        unsigned char *q = bin + pos_bytes + (size_t)i * isz;
        if (isz == 1) {
            q[0] = (unsigned char)idx[i];
        } else if (isz == 2) {
            q[0] = (unsigned char)(idx[i] & 0xffu);
            q[1] = (unsigned char)(idx[i] >> 8);
        } else {
            put_le32(q, idx[i]);
        }
    }

    sb_add(&j, "{\"asset\":{\"version\":\"2.0\"},");
    sb_add(&j, "%s", sp->scenes ? sp->scenes : "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],");
    sb_add(&j, "\"nodes\":%s,", sp->nodes ? sp->nodes : "[{\"mesh\":0}]");
    sb_add(&j, "\"meshes\":[{\"primitives\":[");
    for (p = 0; p < nprims; p++) {
        sb_add(&j, "%s{\"attributes\":{\"POSITION\":0}", p ? "," : "");
        if (sp->itype) {
            sb_add(&j, ",\"indices\":1");
        }
        if (p == 0 && sp->prim0) {
            sb_add(&j, ",%s", sp->prim0);
        }
        sb_add(&j, "}");
    }
    sb_add(&j, "]}],");
    sb_add(&j, "\"buffers\":[{\"byteLength\":%ld}],",
           sp->buffer_len ? sp->buffer_len : (long)bin_size);
    sb_add(&j, "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%ld",
           sp->view0_len ? sp->view0_len : sp->pos_raw ? (long)sp->pos_raw_len : (long)pos_bytes);
    if (sp->view0_stride) {
        sb_add(&j, ",\"byteStride\":%ld", sp->view0_stride);
    }
    sb_add(&j, "}");
    if (sp->itype) {
        sb_add(&j, ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", pos_bytes,
               idx_bytes);
    }
    sb_add(&j, "],\"accessors\":[{\"bufferView\":0,\"componentType\":%d,\"count\":%ld,"
               "\"type\":\"VEC3\"%s}",
           sp->pos_ctype ? sp->pos_ctype : 5126, sp->pos_count ? sp->pos_count : (long)nverts,
           sp->pos_norm ? ",\"normalized\":true" : "");
    if (sp->itype) {
        sb_add(&j, ",{\"bufferView\":1,\"componentType\":%d,\"count\":%u,\"type\":\"SCALAR\"}",
               sp->itype, nidx);
    }
    sb_add(&j, "]");
    if (sp->top) {
        sb_add(&j, ",%s", sp->top);
    }
    sb_add(&j, "}");

    glb = j.s ? build_glb(j.s, bin, bin_size, size) : NULL;
    free(j.s);
    free(bin);
    return glb;
}

/* Loads glb bytes from memory and from a file; both must agree. Returns 0 on success with
 * the file-loaded mesh in *m. */
static int load_both(const char *name, const unsigned char *glb, size_t size, pn_mesh *m,
                     char *err)
{
    char path[1024];
    char err2[ERR_SIZE];
    pn_mesh mm;
    int rf, rm;
    out_path(path, sizeof path, name);
    if (!write_file(path, glb, size)) {
        snprintf(err, ERR_SIZE, "cannot write %.400s", path);
        memset(m, 0, sizeof *m);
        return -1;
    }
    rf = pn_gltf_load(path, m, err, ERR_SIZE);
    rm = pn_gltf_load_memory(glb, size, &mm, err2, sizeof err2);
    CHECK_MSG((rf == 0) == (rm == 0), "%s: file %d (%s) vs memory %d (%s)", name, rf, err, rm,
              err2);
    if (rf == 0 && rm == 0) {
        CHECK(m->vertex_count == mm.vertex_count && m->triangle_count == mm.triangle_count);
        if (m->vertex_count == mm.vertex_count && m->triangle_count == mm.triangle_count) {
            CHECK(memcmp(m->positions, mm.positions, (size_t)m->vertex_count * 12u) == 0);
            CHECK(memcmp(m->indices, mm.indices, (size_t)m->triangle_count * 12u) == 0);
        }
    } else {
        CHECK_MSG(err2[0] != '\0', "%s: memory load failed without a message", name);
        CHECK(mesh_is_zero(&mm));
    }
    pn_mesh_free(&mm);
    return rf;
}

static void expect_fail_bytes(const char *name, const unsigned char *glb, size_t size,
                              const char *must_contain)
{
    char err[ERR_SIZE];
    pn_mesh m;
    int r;
    memset(err, 0, sizeof err);
    r = load_both(name, glb, size, &m, err);
    CHECK_MSG(r != 0, "%s: malformed input was accepted", name);
    CHECK_MSG(err[0] != '\0', "%s: failure without a message", name);
    CHECK(mesh_is_zero(&m));
    if (must_contain != NULL) {
        CHECK_MSG(strstr(err, must_contain) != NULL, "%s: message '%s' lacks '%s'", name, err,
                  must_contain);
    }
    pn_mesh_free(&m);
}

static void expect_fail(const char *name, const tiny_spec *sp, const char *must_contain)
{
    size_t size;
    unsigned char *glb = build_tiny(sp, &size);
    if (glb == NULL) {
        CHECK_MSG(0, "%s: could not build", name);
        return;
    }
    expect_fail_bytes(name, glb, size, must_contain);
    free(glb);
}

/* Loads a spec that must succeed; returns 0 and the mesh, or non-zero after recording a
 * failure. */
static int expect_ok(const char *name, const tiny_spec *sp, pn_mesh *m)
{
    char err[ERR_SIZE];
    size_t size;
    int r;
    unsigned char *glb = build_tiny(sp, &size);
    memset(m, 0, sizeof *m);
    if (glb == NULL) {
        CHECK_MSG(0, "%s: could not build", name);
        return 1;
    }
    err[0] = '\0';
    r = load_both(name, glb, size, m, err);
    CHECK_MSG(r == 0, "%s: load failed: %s", name, err);
    free(glb);
    return r;
}

static int near(float a, double b, double tol)
{
    return fabs((double)a - b) <= tol;
}

/* ---- the shared scene set ---- */

typedef struct scene_row {
    const char *file;
    uint32_t tris, verts;
    double lo[3], hi[3];
    int decimals; /* printed precision of the README bbox */
} scene_row;

/* From ../shared/scenes/README.md. */
static const scene_row scene_table[] = {
    {"spot.glb", 5856, 2930, {-0.472, -0.737, -0.669}, {0.472, 0.954, 1.049}, 3},
    {"stanford_bunny.glb", 69451, 34834, {-0.095, 0.033, -0.062}, {0.061, 0.187, 0.059}, 3},
    {"chess_set.glb", 76920, 49150, {-0.277, 0.000, -0.277}, {0.277, 0.112, 0.277}, 3},
    {"happy_buddha_100k.glb", 100000, 49950, {-0.461, -1.002, -0.324}, {0.352, 0.978, 0.490},
     3},
    {"cad_infineon_easypim2b.glb", 194708, 194908, {-0.0061, -0.0014, -0.0017},
     {0.0187, 0.0049, 0.0206}, 4},
    {"stanford_dragon.glb", 871414, 437645, {-0.108, 0.053, -0.050}, {0.097, 0.197, 0.041}, 3},
    /* Interiors, architecture and foliage. */
    {"grey_white_room.glb", 139899, 116635, {-0.513, -0.003, -3.635}, {5.123, 2.879, 0.593}, 3},
    {"copper_beech.glb", 187308, 208784, {-3.991, 0.000, -3.530}, {3.522, 8.000, 3.771}, 3},
};
#define SCENE_COUNT (sizeof scene_table / sizeof scene_table[0])

static void test_scene_set(void)
{
    size_t s;
    for (s = 0; s < SCENE_COUNT; s++) {
        const scene_row *r = &scene_table[s];
        char path[1024], err[ERR_SIZE];
        pn_mesh m;
        int k, rc, in_range = 1, finite = 1;
        uint64_t i;
        /* The README rounds to `decimals` places: allow half a unit there, plus 1e-3 of the
         * extent for the rounding of the rounding. */
        double extent = 0.0, tol;
        for (k = 0; k < 3; k++) {
            extent = fmax(extent, r->hi[k] - r->lo[k]);
        }
        tol = 0.5 * pow(10.0, -r->decimals) + 1e-3 * extent;

        snprintf(path, sizeof path, "%s/%s", PN_SCENES_DIR, r->file);
        rc = pn_gltf_load(path, &m, err, sizeof err);
        CHECK_MSG(rc == 0, "%s: %s", r->file, err);
        if (rc != 0) {
            continue;
        }
        CHECK_MSG(m.triangle_count == r->tris, "%s: %u triangles, README says %u", r->file,
                  m.triangle_count, r->tris);
        CHECK_MSG(m.vertex_count == r->verts, "%s: %u vertices, README says %u", r->file,
                  m.vertex_count, r->verts);
        for (k = 0; k < 3; k++) {
            CHECK_MSG(near(m.bbox_min[k], r->lo[k], tol) && near(m.bbox_max[k], r->hi[k], tol),
                      "%s: bbox axis %d is %.6f..%.6f, README %.4f..%.4f", r->file, k,
                      (double)m.bbox_min[k], (double)m.bbox_max[k], r->lo[k], r->hi[k]);
        }
        for (i = 0; i < (uint64_t)m.triangle_count * 3u; i++) {
            in_range &= m.indices[i] < m.vertex_count;
        }
        for (i = 0; i < (uint64_t)m.vertex_count * 3u; i++) {
            finite &= isfinite(m.positions[i]) != 0;
        }
        CHECK(in_range);
        CHECK(finite);
        pn_mesh_free(&m);
        CHECK(mesh_is_zero(&m));
    }
}

/* Every .glb present at configure time must have a row in scene_table. */
static void test_scene_set_complete(void)
{
    const char *list = PN_SCENE_GLBS;
    int seen = 0;
    while (*list) {
        const char *end = strchr(list, ',');
        size_t n = end ? (size_t)(end - list) : strlen(list), s;
        int found = 0;
        for (s = 0; s < SCENE_COUNT; s++) {
            found |= strlen(scene_table[s].file) == n && strncmp(scene_table[s].file, list, n) == 0;
        }
        CHECK_MSG(found, "scene file '%.*s' has no row in scene_table", (int)n, list);
        seen++;
        list += n + (end ? 1 : 0);
    }
    CHECK_MSG(seen >= (int)SCENE_COUNT, "only %d .glb files found in %s", seen, PN_SCENES_DIR);
}

static void test_spot_memory_matches_file(void)
{
    char path[1024], err[ERR_SIZE];
    size_t size;
    unsigned char *data;
    pn_mesh a, b;
    snprintf(path, sizeof path, "%s/spot.glb", PN_SCENES_DIR);
    data = read_file(path, &size);
    REQUIRE(data != NULL);
    REQUIRE(pn_gltf_load(path, &a, err, sizeof err) == 0);
    CHECK_MSG(pn_gltf_load_memory(data, size, &b, err, sizeof err) == 0, "%s", err);
    CHECK(a.vertex_count == b.vertex_count && a.triangle_count == b.triangle_count);
    if (a.vertex_count == b.vertex_count && a.triangle_count == b.triangle_count) {
        CHECK(memcmp(a.positions, b.positions, (size_t)a.vertex_count * 12u) == 0);
        CHECK(memcmp(a.indices, b.indices, (size_t)a.triangle_count * 12u) == 0);
        CHECK(memcmp(a.bbox_min, b.bbox_min, sizeof a.bbox_min) == 0);
    }
    pn_mesh_free(&a);
    pn_mesh_free(&b);
    free(data);
}

/* ---- hostile whole files ---- */

static void test_truncated_and_corrupt_spot(void)
{
    char path[1024], name[64];
    size_t size, i;
    unsigned char *data, *copy;
    snprintf(path, sizeof path, "%s/spot.glb", PN_SCENES_DIR);
    data = read_file(path, &size);
    REQUIRE(data != NULL && size > 1000);
    copy = (unsigned char *)malloc(size);
    REQUIRE(copy != NULL);
    {
        const size_t cuts[] = {0, 1, 4, 11, 12, 19, 20, 21, 24, 100, 1000, size / 3, size / 2,
                               size - 100, size - 8, size - 4, size - 1};
        for (i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
            snprintf(name, sizeof name, "trunc_%zu.glb", cuts[i]);
            memcpy(copy, data, cuts[i]);
            expect_fail_bytes(name, copy, cuts[i], NULL);
        }
    }
    /* Truncated, with the header length patched to agree, so only the chunk and buffer
     * bookkeeping inside can catch it. */
    {
        uint32_t json_len = get_le32(data + 12);
        size_t cut = ((20u + json_len + 8u + 1000u) + 3u) & ~(size_t)3u;
        memcpy(copy, data, cut);
        put_le32(copy + 8, (uint32_t)cut);
        expect_fail_bytes("trunc_patched_len.glb", copy, cut, NULL);
        /* ... and the BIN chunk length patched too: now the buffer is larger than BIN. */
        put_le32(copy + 20 + json_len, (uint32_t)(cut - 20u - json_len - 8u));
        expect_fail_bytes("trunc_patched_bin.glb", copy, cut, NULL);
        /* BIN chunk length that forgets its own 8-byte header: runs 8 bytes past the end. */
        put_le32(copy + 20 + json_len, (uint32_t)(cut - 20u - json_len));
        expect_fail_bytes("bin_past_end.glb", copy, cut, "BIN");
    }
    memcpy(copy, data, size);
    copy[0] = 'x';
    expect_fail_bytes("wrong_magic.glb", copy, size, "magic");
    memcpy(copy, data, size);
    put_le32(copy + 4, 1);
    expect_fail_bytes("version1.glb", copy, size, "version");
    memcpy(copy, data, size);
    memcpy(copy + 16, "JSOX", 4);
    expect_fail_bytes("chunk0_not_json.glb", copy, size, NULL);
    memcpy(copy, data, size);
    put_le32(copy + 12, 0xfffffff0u);
    expect_fail_bytes("json_len_huge.glb", copy, size, NULL);
    /* Corrupt the JSON text itself. */
    memcpy(copy, data, size);
    copy[20] = '[';
    expect_fail_bytes("json_garbage.glb", copy, size, NULL);
    free(copy);
    free(data);
}

static void test_missing_and_odd_paths(void)
{
    char err[ERR_SIZE];
    pn_mesh m;
    const char *missing = PN_TEST_OUT_DIR "/test_gltf_does_not_exist.glb";
    CHECK(pn_gltf_load(missing, &m, err, sizeof err) != 0);
    CHECK(strstr(err, "does_not_exist") != NULL);
    CHECK(mesh_is_zero(&m));
    CHECK(pn_gltf_load(PN_TEST_OUT_DIR, &m, err, sizeof err) != 0); /* a directory */
    CHECK(err[0] != '\0');
    CHECK(pn_gltf_load("", &m, err, sizeof err) != 0);
    CHECK(pn_gltf_load(NULL, &m, err, sizeof err) != 0);
    CHECK(pn_gltf_load(missing, &m, NULL, 0) != 0); /* no message buffer: no crash */
    CHECK(pn_gltf_load(missing, NULL, err, sizeof err) != 0);
    CHECK(pn_gltf_load_memory(NULL, 0, &m, err, sizeof err) != 0);
    CHECK(err[0] != '\0');
    CHECK(pn_gltf_load_memory(NULL, 100, &m, err, sizeof err) != 0);
    {
        char small[8];
        CHECK(pn_gltf_load(missing, &m, small, sizeof small) != 0);
        CHECK(strlen(small) == sizeof small - 1); /* truncated, terminated */
    }
}

/* ---- hand-built files ---- */

static void check_quad(const char *name, const pn_mesh *m)
{
    unsigned i;
    CHECK_MSG(m->vertex_count == 4 && m->triangle_count == 2, "%s: %u verts %u tris", name,
              m->vertex_count, m->triangle_count);
    if (m->vertex_count != 4 || m->triangle_count != 2) {
        return;
    }
    CHECK(memcmp(m->positions, quad_pos, sizeof quad_pos) == 0);
    for (i = 0; i < 6; i++) {
        CHECK(m->indices[i] == quad_idx[i]);
    }
    CHECK(m->bbox_min[0] == 0.0f && m->bbox_min[1] == 0.0f && m->bbox_min[2] == 0.0f);
    CHECK(m->bbox_max[0] == 1.0f && m->bbox_max[1] == 1.0f && m->bbox_max[2] == 0.0f);
}

static void test_tiny_valid(void)
{
    tiny_spec sp;
    pn_mesh m;
    static const int types[3] = {5121, 5123, 5125};
    int t;
    for (t = 0; t < 3; t++) {
        char name[32];
        memset(&sp, 0, sizeof sp);
        sp.itype = types[t];
        snprintf(name, sizeof name, "tiny_%d.glb", types[t]);
        if (expect_ok(name, &sp, &m) == 0) {
            check_quad(name, &m);
        }
        pn_mesh_free(&m);
    }
    /* Not indexed: implicit 0, 1, 2, ... */
    {
        static const float six[18] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1};
        memset(&sp, 0, sizeof sp);
        sp.pos = six;
        sp.nverts = 6;
        if (expect_ok("non_indexed.glb", &sp, &m) == 0) {
            unsigned i;
            CHECK(m.vertex_count == 6 && m.triangle_count == 2);
            for (i = 0; i < 6 && m.triangle_count == 2; i++) {
                CHECK(m.indices[i] == i);
            }
            CHECK(m.bbox_max[2] == 1.0f);
        }
        pn_mesh_free(&m);
    }
    /* A primitive that is not triangles is skipped; the triangle one after it is kept. */
    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.mesh_prims = 2;
    sp.prim0 = "\"mode\":0";
    if (expect_ok("mixed_modes.glb", &sp, &m) == 0) {
        check_quad("mixed_modes.glb", &m);
    }
    pn_mesh_free(&m);
}

/* Positions with a byte stride: 4 vertices of 16 bytes (xyz + padding). */
static void test_stride(void)
{
    static const float pos16[18] = {0, 0, 0, 9, 1, 0, 0, 9, 1, 1, 0, 9, 0, 1, 0, 9, 0, 0};
    tiny_spec sp;
    pn_mesh m;
    memset(&sp, 0, sizeof sp);
    sp.pos = pos16;
    sp.nverts = 6;        /* 72 bytes of floats in BIN */
    sp.pos_count = 4;     /* read as 4 elements */
    sp.view0_len = 64;
    sp.view0_stride = 16;
    sp.itype = 5125;
    if (expect_ok("stride16.glb", &sp, &m) == 0) {
        check_quad("stride16.glb", &m);
    }
    pn_mesh_free(&m);
    sp.view0_len = 60; /* last element would end at 3*16+12 = 60: still fits */
    if (expect_ok("stride16_tight.glb", &sp, &m) == 0) {
        check_quad("stride16_tight.glb", &m);
    }
    pn_mesh_free(&m);
    sp.view0_len = 59;
    expect_fail("stride16_short.glb", &sp, "past the end");
    sp.view0_len = 64;
    sp.view0_stride = 8; /* smaller than a VEC3 */
    expect_fail("stride8.glb", &sp, "byteStride");
}

static void test_tiny_malformed(void)
{
    tiny_spec sp;
    uint32_t bad_idx[6] = {0, 1, 2, 0, 2, 4};
    float nan_pos[12];
    memcpy(nan_pos, quad_pos, sizeof nan_pos);

    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.idx = bad_idx;
    sp.nidx = 6;
    expect_fail("index_oob_u16.glb", &sp, "index");
    sp.itype = 5121;
    bad_idx[5] = 255;
    expect_fail("index_oob_u8.glb", &sp, "index");
    sp.itype = 5125;
    bad_idx[5] = 0xffffffffu;
    expect_fail("index_oob_u32.glb", &sp, "index");

    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.nidx = 5;
    sp.idx = quad_idx;
    expect_fail("index_count_5.glb", &sp, "multiple of 3");

    memset(&sp, 0, sizeof sp);
    sp.itype = 5126; /* float indices */
    expect_fail("index_float.glb", &sp, "componentType");
    sp.itype = 5122; /* signed short */
    expect_fail("index_i16.glb", &sp, "componentType");

    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.pos_count = 5; /* 60 bytes from a 48-byte view */
    expect_fail("accessor_past_view.glb", &sp, "past the end");
    sp.pos_count = 0;
    sp.view0_len = 1000; /* view past the buffer */
    expect_fail("view_past_buffer.glb", &sp, NULL);
    sp.view0_len = 0;
    sp.buffer_len = 4096; /* buffer larger than the BIN chunk */
    expect_fail("buffer_past_bin.glb", &sp, NULL);
    sp.buffer_len = 0;
    sp.pos_ctype = 5123; /* POSITION not float */
    expect_fail("position_u16.glb", &sp, "float");

    nan_pos[4] = (float)NAN;
    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.pos = nan_pos;
    sp.nverts = 4;
    expect_fail("nan_position.glb", &sp, "non-finite");
    nan_pos[4] = (float)INFINITY;
    expect_fail("inf_position.glb", &sp, "non-finite");
    nan_pos[4] = 0.0f;
    nan_pos[9] = 3e38f;
    sp.nodes = "[{\"mesh\":0,\"scale\":[10,10,10]}]"; /* finite input, overflowing result */
    expect_fail("overflow_transform.glb", &sp, "finite");

    /* Node graph errors. */
    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.nodes = "[{\"children\":[1]},{\"children\":[0],\"mesh\":0}]";
    expect_fail("cycle.glb", &sp, "twice");
    sp.nodes = "[{\"children\":[0],\"mesh\":0}]";
    expect_fail("self_child.glb", &sp, "twice");
    sp.scenes = "\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],";
    sp.nodes = "[{\"children\":[2]},{\"children\":[2]},{\"mesh\":0}]";
    expect_fail("two_parents.glb", &sp, "twice");
    sp.scenes = NULL;
    sp.nodes = "[{\"children\":[7],\"mesh\":0}]";
    expect_fail("child_oob.glb", &sp, "child");
    sp.nodes = "[{\"mesh\":3}]";
    expect_fail("mesh_oob.glb", &sp, "mesh");
    sp.nodes = NULL;
    sp.scenes = "\"scene\":5,\"scenes\":[{\"nodes\":[0]}],";
    expect_fail("scene_oob.glb", &sp, NULL);
    sp.scenes = "\"scene\":0,\"scenes\":[{\"nodes\":[9]}],";
    expect_fail("scene_node_oob.glb", &sp, "node");
    sp.scenes = NULL;
    sp.nodes = "[{\"mesh\":0,\"rotation\":[0,0,0,0]}]";
    expect_fail("zero_quaternion.glb", &sp, "quaternion");
    sp.nodes = "[{\"mesh\":0,\"matrix\":[1,0,0,0,1]}]";
    expect_fail("short_matrix.glb", &sp, "matrix");

    /* Nothing to load. */
    sp.nodes = NULL;
    sp.prim0 = "\"mode\":1"; /* lines only */
    expect_fail("lines_only.glb", &sp, "no triangles");
    sp.prim0 = NULL;
    sp.scenes = "\"scene\":0,\"scenes\":[{\"nodes\":[]}],";
    expect_fail("empty_scene.glb", &sp, "no triangles");
    sp.scenes = NULL;

    /* Things the loader refuses on principle. */
    sp.top = "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
             "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]";
    expect_fail("draco_required.glb", &sp, "KHR_draco_mesh_compression");
    {
        char deep[512];
        int i, n = 0;
        n += snprintf(deep + n, sizeof deep - (size_t)n, "\"extras\":");
        for (i = 0; i < 100; i++) deep[n++] = '[';
        for (i = 0; i < 100; i++) deep[n++] = ']';
        deep[n] = '\0';
        sp.top = deep;
        expect_fail("deep_json.glb", &sp, "nested");
    }
    sp.top = NULL;

    /* Raw GLB structure. */
    {
        size_t size;
        unsigned char *g = build_glb("{\"asset\":{\"version\":\"2.0\"}", NULL, 0, &size);
        expect_fail_bytes("json_unterminated.glb", g, size, NULL);
        free(g);
        g = build_glb("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":4}]}", NULL,
                      0, &size);
        expect_fail_bytes("no_bin_chunk.glb", g, size, NULL);
        free(g);
        g = build_glb("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":0}]}",
                      "abcd", 4, &size);
        expect_fail_bytes("zero_length_buffer.glb", g, size, NULL);
        free(g);
        g = build_glb("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":4,"
                      "\"uri\":\"/etc/hostname\"}]}",
                      "abcd", 4, &size);
        /* From memory external files are never read; from a file this one loads nothing. */
        expect_fail_bytes("external_uri.glb", g, size, NULL);
        free(g);
    }
}

/* More than PN_GLTF_MAX_TRIANGLES through instancing, from a 150 KB file: must be refused
 * before anything of that size is allocated. */
static void test_triangle_limit(void)
{
    const unsigned nv = 3u * 4096u;
    float *pos = (float *)calloc((size_t)nv * 3u, sizeof(float));
    sbuf nodes = {NULL, 0, 0}, scenes = {NULL, 0, 0};
    tiny_spec sp;
    unsigned i;
    REQUIRE(pos != NULL);
    for (i = 0; i < nv; i++) {
        pos[i * 3u] = (float)(i % 3u);
        pos[i * 3u + 1u] = (float)(i / 3u);
    }
    /* 256 primitives x 4096 triangles = 2^20 per node; 65 nodes = 2^26 + 2^20. */
    sb_add(&nodes, "[");
    sb_add(&scenes, "\"scene\":0,\"scenes\":[{\"nodes\":[");
    for (i = 0; i < 65; i++) {
        sb_add(&nodes, "%s{\"mesh\":0}", i ? "," : "");
        sb_add(&scenes, "%s%u", i ? "," : "", i);
    }
    sb_add(&nodes, "]");
    sb_add(&scenes, "]}],");
    memset(&sp, 0, sizeof sp);
    sp.pos = pos;
    sp.nverts = nv;
    sp.mesh_prims = 256;
    sp.nodes = nodes.s;
    sp.scenes = scenes.s;
    if (nodes.s && scenes.s) {
        expect_fail("too_many_triangles.glb", &sp, "triangles");
    }
    free(nodes.s);
    free(scenes.s);
    free(pos);

    /* The fuzzing entry point with a lower limit. */
    {
        size_t size;
        unsigned char *glb;
        char err[ERR_SIZE];
        pn_mesh m;
        memset(&sp, 0, sizeof sp);
        sp.itype = 5123;
        glb = build_tiny(&sp, &size);
        REQUIRE(glb != NULL);
        CHECK(pn_gltf_load_memory_limit(glb, size, 2, &m, err, sizeof err) == 0);
        CHECK(m.triangle_count == 2);
        pn_mesh_free(&m);
        CHECK(pn_gltf_load_memory_limit(glb, size, 1, &m, err, sizeof err) != 0);
        CHECK(strstr(err, "more than 1 triangles") != NULL && mesh_is_zero(&m));
        CHECK(pn_gltf_load_memory_limit(glb, size, 0, &m, err, sizeof err) != 0);
        CHECK(pn_gltf_load_memory_limit(glb, size, PN_GLTF_MAX_TRIANGLES + 1u, &m, err,
                                        sizeof err) != 0);
        free(glb);
    }
}

static void test_transforms(void)
{
    tiny_spec sp;
    pn_mesh m;
    unsigned i;
    const double tol = 1e-6;

    /* Scaled parent, translated child: world = S(2) * T(1,0,0). */
    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.nodes = "[{\"scale\":[2,2,2],\"children\":[1]},{\"translation\":[1,0,0],\"mesh\":0}]";
    if (expect_ok("hier_scale_translate.glb", &sp, &m) == 0 && m.vertex_count == 4) {
        for (i = 0; i < 4; i++) {
            CHECK(near(m.positions[i * 3], 2.0 * (quad_pos[i * 3] + 1.0), tol));
            CHECK(near(m.positions[i * 3 + 1], 2.0 * quad_pos[i * 3 + 1], tol));
            CHECK(near(m.positions[i * 3 + 2], 0.0, tol));
        }
        CHECK(near(m.bbox_min[0], 2.0, tol) && near(m.bbox_max[0], 4.0, tol));
    }
    pn_mesh_free(&m);

    /* Column-major matrix (translation y + 5) over a child rotated 90 degrees about +y:
     * (x, y, z) -> (z, y, -x). */
    sp.nodes = "[{\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,5,0,1],\"children\":[1]},"
               "{\"rotation\":[0,0.70710678118654752,0,0.70710678118654752],\"mesh\":0}]";
    if (expect_ok("hier_matrix_rotate.glb", &sp, &m) == 0 && m.vertex_count == 4) {
        for (i = 0; i < 4; i++) {
            CHECK(near(m.positions[i * 3], quad_pos[i * 3 + 2], tol));
            CHECK(near(m.positions[i * 3 + 1], quad_pos[i * 3 + 1] + 5.0, tol));
            CHECK(near(m.positions[i * 3 + 2], -quad_pos[i * 3], tol));
        }
    }
    pn_mesh_free(&m);

    /* TRS order on one node: T * R * S (scale first, then rotate, then translate). */
    sp.nodes = "[{\"translation\":[0,0,3],\"rotation\":[0,0,0.70710678118654752,"
               "0.70710678118654752],\"scale\":[2,1,1],\"mesh\":0}]";
    if (expect_ok("trs_order.glb", &sp, &m) == 0 && m.vertex_count == 4) {
        /* 90 degrees about +z: (x, y) -> (-y, x); after scaling x by 2. */
        for (i = 0; i < 4; i++) {
            CHECK(near(m.positions[i * 3], -quad_pos[i * 3 + 1], tol));
            CHECK(near(m.positions[i * 3 + 1], 2.0 * quad_pos[i * 3], tol));
            CHECK(near(m.positions[i * 3 + 2], 3.0, tol));
        }
    }
    pn_mesh_free(&m);

    /* Traversal order and instancing: node 0's children are [2, 1]; triangles 0-1 come from
     * node 2 (untransformed), 2-3 from node 1 (x + 10), each with its own vertices. */
    sp.nodes = "[{\"children\":[2,1]},{\"mesh\":0,\"translation\":[10,0,0]},{\"mesh\":0}]";
    if (expect_ok("order_instancing.glb", &sp, &m) == 0) {
        CHECK(m.vertex_count == 8 && m.triangle_count == 4);
        if (m.vertex_count == 8 && m.triangle_count == 4) {
            CHECK(memcmp(m.positions, quad_pos, sizeof quad_pos) == 0);
            CHECK(m.positions[12] == 10.0f && m.positions[15] == 11.0f);
            for (i = 0; i < 6; i++) {
                CHECK(m.indices[i] == quad_idx[i]);
                CHECK(m.indices[6 + i] == quad_idx[i] + 4u);
            }
            CHECK(m.bbox_max[0] == 11.0f);
        }
    }
    pn_mesh_free(&m);

    /* No default scene: every root node (nodes 0 and 2; 1 is 0's child), in index order. */
    sp.scenes = "";
    sp.nodes = "[{\"children\":[1],\"translation\":[0,0,1]},{\"mesh\":0},"
               "{\"mesh\":0,\"translation\":[0,3,0]}]";
    if (expect_ok("no_default_scene.glb", &sp, &m) == 0) {
        CHECK(m.triangle_count == 4 && m.vertex_count == 8);
        if (m.vertex_count == 8) {
            CHECK(m.positions[2] == 1.0f);      /* node 1 under node 0: z + 1 */
            CHECK(m.positions[12 + 1] == 3.0f); /* node 2: y + 3 */
        }
    }
    pn_mesh_free(&m);
    sp.scenes = NULL;

    /* A 5000-deep chain, each level translating by 0.001 in y: no recursion, so no stack
     * trouble, and the translations compose. */
    {
        sbuf nodes = {NULL, 0, 0};
        const int depth = 5000;
        int d;
        sb_add(&nodes, "[");
        for (d = 0; d < depth; d++) {
            if (d + 1 < depth) {
                sb_add(&nodes, "%s{\"translation\":[0,0.001,0],\"children\":[%d]}", d ? "," : "",
                       d + 1);
            } else {
                sb_add(&nodes, ",{\"translation\":[0,0.001,0],\"mesh\":0}");
            }
        }
        sb_add(&nodes, "]");
        sp.nodes = nodes.s;
        if (nodes.s && expect_ok("deep_chain.glb", &sp, &m) == 0 && m.vertex_count == 4) {
            CHECK(near(m.positions[1], 5.0, 1e-5));
            CHECK(near(m.positions[7], 6.0, 1e-5));
        }
        pn_mesh_free(&m);
        free(nodes.s);
        sp.nodes = NULL;
    }
}

/* .gltf (JSON) files: buffer as a data URI and as an external .bin beside the file. */
static void b64(sbuf *b, const unsigned char *d, size_t n)
{
    static const char tab[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t i;
    for (i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)d[i] << 16;
        if (i + 1 < n) v |= (uint32_t)d[i + 1] << 8;
        if (i + 2 < n) v |= d[i + 2];
        sb_add(b, "%c%c%c%c", tab[(v >> 18) & 63], tab[(v >> 12) & 63],
               i + 1 < n ? tab[(v >> 6) & 63] : '=', i + 2 < n ? tab[v & 63] : '=');
    }
}

static void test_ascii_gltf(void)
{
    unsigned char bin[60];
    sbuf j = {NULL, 0, 0};
    char path[1024], binpath[1024], err[ERR_SIZE];
    pn_mesh m;
    unsigned i;
    const char *tail =
        ",\"byteLength\":60}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
        "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":12}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}";
    const char *head = "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
                       "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
                       "{\"POSITION\":0},\"indices\":1}]}],\"buffers\":[{\"uri\":";
    for (i = 0; i < 12; i++) {
        uint32_t bits;
        memcpy(&bits, &quad_pos[i], 4);
        put_le32(bin + i * 4u, bits);
    }
    for (i = 0; i < 6; i++) {
        bin[48 + i * 2] = (unsigned char)quad_idx[i];
        bin[49 + i * 2] = 0;
    }

    sb_add(&j, "%s\"data:application/octet-stream;base64,", head);
    b64(&j, bin, sizeof bin);
    sb_add(&j, "\"%s", tail);
    out_path(path, sizeof path, "data_uri.gltf");
    REQUIRE(j.s != NULL && write_file(path, j.s, j.len));
    CHECK_MSG(pn_gltf_load(path, &m, err, sizeof err) == 0, "%s", err);
    check_quad("data_uri.gltf", &m);
    pn_mesh_free(&m);

    j.len = 0;
    sb_add(&j, "%s\"test_gltf_quad.bin\"%s", head, tail);
    out_path(path, sizeof path, "external.gltf");
    out_path(binpath, sizeof binpath, "quad.bin");
    REQUIRE(write_file(path, j.s, j.len) && write_file(binpath, bin, sizeof bin));
    CHECK_MSG(pn_gltf_load(path, &m, err, sizeof err) == 0, "%s", err);
    check_quad("external.gltf", &m);
    pn_mesh_free(&m);

    /* URIs that leave the file's directory are refused even though the file exists. */
    j.len = 0;
    sb_add(&j, "%s\"%s\"%s", head, binpath, tail); /* absolute path */
    REQUIRE(write_file(path, j.s, j.len));
    CHECK(pn_gltf_load(path, &m, err, sizeof err) != 0 && strstr(err, "refusing") != NULL);
    CHECK(mesh_is_zero(&m));
    j.len = 0;
    sb_add(&j, "%s\"x/../test_gltf_quad.bin\"%s", head, tail);
    REQUIRE(write_file(path, j.s, j.len));
    CHECK(pn_gltf_load(path, &m, err, sizeof err) != 0 && strstr(err, "refusing") != NULL);
    j.len = 0;
    sb_add(&j, "%s\"test_gltf_quad.bin\"%s", head, tail);
    REQUIRE(write_file(path, j.s, j.len));

    /* External .bin shorter than declared. */
    REQUIRE(write_file(binpath, bin, 40));
    CHECK(pn_gltf_load(path, &m, err, sizeof err) != 0);
    CHECK(err[0] != '\0' && mesh_is_zero(&m));
    remove(binpath);
    CHECK(pn_gltf_load(path, &m, err, sizeof err) != 0);
    CHECK(err[0] != '\0' && mesh_is_zero(&m));
    free(j.s);

    /* A .gltf that is binary, and a .glb that is JSON. */
    out_path(path, sizeof path, "empty.gltf");
    REQUIRE(write_file(path, "", 0));
    CHECK(pn_gltf_load(path, &m, err, sizeof err) != 0 && err[0] != '\0');
    out_path(path, sizeof path, "json.glb");
    REQUIRE(write_file(path, "{\"asset\":{\"version\":\"2.0\"}}", 27));
    CHECK(pn_gltf_load(path, &m, err, sizeof err) != 0 && strstr(err, "magic") != NULL);
}

/* Deterministic byte mutations of a valid tiny file: never crash, and anything accepted is
 * a consistent mesh. */
static void test_mutations(void)
{
    tiny_spec sp;
    size_t size, i;
    unsigned char *glb, *buf;
    uint32_t state = 12345u;
    int n, accepted = 0, ok_meshes = 1;
    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.nodes = "[{\"children\":[1],\"scale\":[1,2,1]},{\"mesh\":0}]";
    glb = build_tiny(&sp, &size);
    REQUIRE(glb != NULL);
    buf = (unsigned char *)malloc(size);
    REQUIRE(buf != NULL);
    for (n = 0; n < 3000; n++) {
        pn_mesh m;
        char err[ERR_SIZE];
        int flips, f;
        memcpy(buf, glb, size);
        state = state * 1664525u + 1013904223u;
        flips = 1 + (int)((state >> 28) & 3u);
        for (f = 0; f < flips; f++) {
            state = state * 1664525u + 1013904223u;
            i = (size_t)(state >> 8) % size;
            state = state * 1664525u + 1013904223u;
            /* Bias towards digits so JSON numbers change but the JSON still parses. */
            buf[i] = (state >> 30) ? (unsigned char)('0' + (state >> 8) % 10u)
                                   : (unsigned char)(state >> 16);
        }
        if (pn_gltf_load_memory(buf, size, &m, err, sizeof err) == 0) {
            uint64_t k;
            accepted++;
            for (k = 0; k < (uint64_t)m.triangle_count * 3u; k++) {
                ok_meshes &= m.indices[k] < m.vertex_count;
            }
            for (k = 0; k < (uint64_t)m.vertex_count * 3u; k++) {
                ok_meshes &= isfinite(m.positions[k]) != 0;
            }
        } else {
            ok_meshes &= err[0] != '\0' && mesh_is_zero(&m);
        }
        pn_mesh_free(&m);
    }
    CHECK(ok_meshes);
    CHECK(accepted > 0); /* some mutations only touch harmless bytes */
    free(buf);
    free(glb);
}

/* ---- pn_mesh helpers ---- */

static void test_mesh_ground(void)
{
    tiny_spec sp;
    pn_mesh m, empty;
    char err[ERR_SIZE];
    float diag, y;
    unsigned t, i;
    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.nodes = "[{\"mesh\":0,\"scale\":[1,1,2],\"translation\":[0,0,-1]}]";
    REQUIRE(expect_ok("ground_base.glb", &sp, &m) == 0);
    /* quad spans x 0..1, y 0..1, z -1 */
    diag = pn_mesh_diag(&m);
    CHECK(near(diag, sqrt(2.0), 1e-6));
    REQUIRE(pn_mesh_add_ground(&m, err, sizeof err) == 0);
    CHECK(m.vertex_count == 8 && m.triangle_count == 4);
    /* bbox unchanged: the ground is not part of the scene bounds */
    CHECK(m.bbox_min[1] == 0.0f && m.bbox_max[1] == 1.0f && m.bbox_max[2] == -1.0f);
    y = (float)(0.0 - 1e-3 * (double)diag);
    for (i = 4; i < 8; i++) {
        CHECK(m.positions[i * 3 + 1] == y);
        CHECK(near(fabsf(m.positions[i * 3] - 0.5f), 2.0 * diag, 1e-5));
        CHECK(near(fabsf(m.positions[i * 3 + 2] - -1.0f), 2.0 * diag, 1e-5));
    }
    for (t = 2; t < 4; t++) {
        const float *a = m.positions + m.indices[t * 3] * 3u;
        const float *b = m.positions + m.indices[t * 3 + 1] * 3u;
        const float *c = m.positions + m.indices[t * 3 + 2] * 3u;
        double e1[3], e2[3], n[3];
        for (i = 0; i < 3; i++) {
            e1[i] = (double)b[i] - a[i];
            e2[i] = (double)c[i] - a[i];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        CHECK(n[1] > 0.0 && fabs(n[0]) < 1e-9 && fabs(n[2]) < 1e-9);
        for (i = 0; i < 3; i++) {
            CHECK(m.indices[t * 3 + i] >= 4 && m.indices[t * 3 + i] < 8);
        }
    }
    /* The two triangles cover the square: together they use all four corners. */
    {
        unsigned seen = 0;
        for (i = 6; i < 12; i++) seen |= 1u << (m.indices[i] - 4u);
        CHECK(seen == 15u);
    }
    pn_mesh_free(&m);
    CHECK(mesh_is_zero(&m));

    memset(&empty, 0, sizeof empty);
    CHECK(pn_mesh_add_ground(&empty, err, sizeof err) != 0 && err[0] != '\0');
    CHECK(pn_mesh_add_ground(NULL, err, sizeof err) != 0);
    pn_mesh_update_bbox(&empty);
    CHECK(empty.bbox_min[0] == 0.0f && empty.bbox_max[2] == 0.0f);
    CHECK(pn_mesh_diag(&empty) == 0.0f);
    pn_mesh_free(&empty);
    pn_mesh_free(NULL);
}

/* ---- images ---- */

static void test_pfm(void)
{
    enum { W = 5, H = 3 };
    float img[W * H], *back = NULL;
    uint32_t w = 0, h = 0, x, y;
    char path[1024], err[ERR_SIZE];
    unsigned char *raw;
    size_t size;
    static const char header[] = "Pf\n5 3\n-1.0\n";
    const size_t hl = sizeof header - 1;
    for (y = 0; y < H; y++) {
        for (x = 0; x < W; x++) {
            img[y * W + x] = (float)(y * 10 + x) + 0.25f;
        }
    }
    img[1] = -0.0f;
    img[2] = 1e-40f; /* subnormal survives */
    out_path(path, sizeof path, "img.pfm");
    REQUIRE(pn_write_pfm(path, img, W, H, err, sizeof err) == 0);
    raw = read_file(path, &size);
    REQUIRE(raw != NULL);
    CHECK(size == hl + W * H * 4);
    CHECK(memcmp(raw, header, hl) == 0);
    /* The first stored row is the bottom row (y = H - 1), little endian. */
    if (size == hl + W * H * 4) {
        uint32_t bits;
        memcpy(&bits, &img[(H - 1) * W], 4);
        CHECK(get_le32(raw + hl) == bits);
        memcpy(&bits, &img[0], 4);
        CHECK(get_le32(raw + hl + (H - 1) * W * 4) == bits);
    }
    REQUIRE(pn_read_pfm(path, &back, &w, &h, err, sizeof err) == 0);
    CHECK(w == W && h == H);
    CHECK(memcmp(back, img, sizeof img) == 0);
    free(back);

    /* Big-endian PFM (positive scale) reads the same. */
    if (size == hl + W * H * 4) {
        unsigned char *be = (unsigned char *)malloc(size + 2);
        size_t o;
        REQUIRE(be != NULL);
        memcpy(be, "Pf\n5 3\n1.0\n", hl - 1);
        for (o = 0; o < W * H * 4; o += 4) {
            be[hl - 1 + o] = raw[hl + o + 3];
            be[hl - 1 + o + 1] = raw[hl + o + 2];
            be[hl - 1 + o + 2] = raw[hl + o + 1];
            be[hl - 1 + o + 3] = raw[hl + o];
        }
        out_path(path, sizeof path, "img_be.pfm");
        REQUIRE(write_file(path, be, size - 1));
        back = NULL;
        CHECK(pn_read_pfm(path, &back, &w, &h, err, sizeof err) == 0);
        CHECK(back != NULL && memcmp(back, img, sizeof img) == 0);
        free(back);
        /* Truncated data, a colour PFM, garbage dimensions: refused with a message. */
        REQUIRE(write_file(path, be, size - 5));
        back = NULL;
        CHECK(pn_read_pfm(path, &back, &w, &h, err, sizeof err) != 0 && back == NULL);
        CHECK(err[0] != '\0' && w == 0 && h == 0);
        be[1] = 'F';
        REQUIRE(write_file(path, be, size - 1));
        CHECK(pn_read_pfm(path, &back, &w, &h, err, sizeof err) != 0 && back == NULL);
        REQUIRE(write_file(path, "Pf\n99999999 3\n-1.0\n", 20));
        CHECK(pn_read_pfm(path, &back, &w, &h, err, sizeof err) != 0 && back == NULL);
        free(be);
    }
    free(raw);
    CHECK(pn_read_pfm(PN_TEST_OUT_DIR "/test_gltf_missing.pfm", &back, &w, &h, err,
                      sizeof err) != 0);
    CHECK(pn_write_pfm(path, img, 0, H, err, sizeof err) != 0 && err[0] != '\0');
    CHECK(pn_write_pfm(path, NULL, W, H, err, sizeof err) != 0);
    CHECK(pn_write_pfm(PN_TEST_OUT_DIR "/no_such_dir/x.pfm", img, W, H, err, sizeof err) != 0);
    CHECK(strstr(err, "no_such_dir") != NULL);
}

static void test_png_and_ids(void)
{
    enum { W = 7, H = 3 };
    uint8_t rgba[W * H * 4];
    uint32_t ids[W * H];
    char path[1024], err[ERR_SIZE];
    unsigned char *raw;
    size_t size, i;
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    for (i = 0; i < sizeof rgba; i++) {
        rgba[i] = (uint8_t)(i * 37u);
    }
    for (i = 0; i < W * H; i++) {
        ids[i] = 0x01020304u * (uint32_t)(i + 1) + (i == 5 ? 0xffffffffu : 0u);
    }
    out_path(path, sizeof path, "img.png");
    REQUIRE(pn_write_png(path, rgba, W, H, err, sizeof err) == 0);
    raw = read_file(path, &size);
    REQUIRE(raw != NULL);
    CHECK(size > 8 + 25 && memcmp(raw, sig, 8) == 0);
    /* IHDR carries the size, big endian. */
    CHECK(memcmp(raw + 12, "IHDR", 4) == 0);
    CHECK(raw[16] == 0 && raw[17] == 0 && raw[18] == 0 && raw[19] == W);
    CHECK(raw[20] == 0 && raw[21] == 0 && raw[22] == 0 && raw[23] == H);
    free(raw);
    CHECK(pn_write_png(PN_TEST_OUT_DIR "/no_such_dir/x.png", rgba, W, H, err, sizeof err) != 0);
    CHECK(strstr(err, "no_such_dir") != NULL);
    CHECK(pn_write_png(path, rgba, W, 0, err, sizeof err) != 0);

    out_path(path, sizeof path, "ids.bin");
    REQUIRE(pn_write_ids(path, ids, W, H, err, sizeof err) == 0);
    raw = read_file(path, &size);
    REQUIRE(raw != NULL);
    CHECK(size == W * H * 4);
    if (size == W * H * 4) {
        for (i = 0; i < W * H; i++) {
            CHECK(get_le32(raw + i * 4) == ids[i]); /* top row first, little endian */
        }
    }
    free(raw);
    CHECK(pn_write_ids(path, NULL, W, H, err, sizeof err) != 0);
}

/* z of triangle t's normal (B - A) x (C - A) in winding order: which side its front is on. */
static float front_z(const pn_mesh *m, unsigned t)
{
    const float *a = m->positions + 3u * m->indices[3u * t], *b = m->positions + 3u * m->indices[3u * t + 1u];
    const float *c = m->positions + 3u * m->indices[3u * t + 2u];
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* Loads sp and checks its triangles' indices (n of them) and that every front faces z's
 * sign sz. */
static void expect_triangles(const char *name, const tiny_spec *sp, const uint32_t *idx, unsigned n, float sz)
{
    pn_mesh m;
    unsigned i;
    if (expect_ok(name, sp, &m) == 0) {
        CHECK_MSG(m.triangle_count == n, "%s: %u triangles, want %u", name, m.triangle_count, n);
        for (i = 0; i < 3u * n && m.triangle_count == n; i++)
            CHECK_MSG(m.indices[i] == idx[i], "%s: index %u is %u, want %u", name, i, m.indices[i], idx[i]);
        for (i = 0; i < m.triangle_count; i++)
            CHECK_MSG(front_z(&m, i) * sz > 0.0f, "%s: triangle %u faces the wrong way", name, i);
    }
    pn_mesh_free(&m);
}

/* The glTF specification's winding: a node whose world matrix mirrors (negative determinant)
 * makes its primitives' front faces clockwise, so the loader reverses their winding and the
 * front stays where the file puts it (the approximations read it: MCSM rendered a mirrored
 * closed solid as umbra on its lit side). Triangle strips and fans as the specification
 * orders their triangles. */
static void test_winding_strips_fans(void)
{
    static const uint32_t flipped[6] = {0, 2, 1, 0, 3, 2}, strip[4] = {0, 1, 3, 2}, fan[4] = {0, 1, 2, 3};
    static const uint32_t strip_tris[6] = {0, 1, 3, 1, 2, 3}, fan_tris[6] = {1, 2, 0, 2, 3, 0};
    static const uint32_t strip_mirrored[6] = {0, 3, 1, 1, 3, 2}, plain_strip[6] = {0, 1, 2, 1, 3, 2};
    static const float zigzag[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    tiny_spec sp;
    pn_mesh m;
    unsigned i;

    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    expect_triangles("winding_plain.glb", &sp, quad_idx, 2, 1.0f);
    sp.nodes = "[{\"scale\":[-1,1,1],\"mesh\":0}]"; /* x mirrored: z, the front's side, stays */
    expect_triangles("winding_mirror_x.glb", &sp, flipped, 2, 1.0f);
    if (expect_ok("winding_mirror_x.glb", &sp, &m) == 0 && m.vertex_count == 4)
        for (i = 0; i < 4; i++) CHECK(m.positions[i * 3] == -quad_pos[i * 3]);
    pn_mesh_free(&m);
    sp.nodes = "[{\"scale\":[1,1,-1],\"mesh\":0}]"; /* z mirrored: the front turns to -z */
    expect_triangles("winding_mirror_z.glb", &sp, flipped, 2, -1.0f);
    /* A mirroring matrix (x and y swapped) under a translation. */
    sp.nodes = "[{\"translation\":[0,0,2],\"children\":[1]},"
               "{\"matrix\":[0,1,0,0, 1,0,0,0, 0,0,1,0, 0,0,0,1],\"mesh\":0}]";
    expect_triangles("winding_mirror_matrix.glb", &sp, flipped, 2, 1.0f);
    /* Two mirrors make a rotation (half a turn about y): the winding stays, the front -z. */
    sp.nodes = "[{\"scale\":[-1,1,1],\"children\":[1]},{\"scale\":[1,1,-1],\"mesh\":0}]";
    expect_triangles("winding_two_mirrors.glb", &sp, quad_idx, 2, -1.0f);
    sp.nodes = NULL;

    /* Strips: triangle t is (t, t+1, t+2) for even t and (t, t+2, t+1) for odd t. */
    sp.idx = strip;
    sp.nidx = 4;
    sp.prim0 = "\"mode\":5";
    expect_triangles("strip.glb", &sp, strip_tris, 2, 1.0f);
    sp.nodes = "[{\"scale\":[-1,1,1],\"mesh\":0}]";
    expect_triangles("strip_mirrored.glb", &sp, strip_mirrored, 2, 1.0f);
    sp.nodes = NULL;
    /* Fans: triangle t is (t+1, t+2, 0). */
    sp.idx = fan;
    sp.prim0 = "\"mode\":6";
    expect_triangles("fan.glb", &sp, fan_tris, 2, 1.0f);
    /* Not indexed: the elements are the vertices. */
    memset(&sp, 0, sizeof sp);
    sp.pos = zigzag;
    sp.nverts = 4;
    sp.prim0 = "\"mode\":5";
    expect_triangles("strip_not_indexed.glb", &sp, plain_strip, 2, 1.0f);
    /* Four elements are a strip's two triangles but no list of triangles; two are nothing. */
    sp.prim0 = NULL;
    expect_fail("list_of_four.glb", &sp, "multiple of 3");
    sp.nverts = 2;
    sp.prim0 = "\"mode\":6";
    expect_fail("fan_of_two.glb", &sp, "no triangles");
}

static void put_le16(unsigned char *p, int v)
{
    p[0] = (unsigned char)((unsigned)v & 0xffu);
    p[1] = (unsigned char)(((unsigned)v >> 8) & 0xffu);
}

/* KHR_mesh_quantization (what gltfpack writes by default): integer positions, normalized or
 * not, dequantized by the node's transform; refused without the extension; compressed
 * geometry refused with a way out. */
static void test_quantized_positions(void)
{
    static const int s16[12] = {0, 0, 0, 32767, 0, 0, 32767, 32767, -32768, 0, 32767, -32767};
    static const float s16_want[12] = {0, 0, 0, 1, 0, 0, 1, 1, -1, 0, 1, -1};
    static const int u16[12] = {0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0};
    static const signed char s8[12] = {0, 0, 0, 127, 0, 0, 127, 127, -128, 0, 127, -127};
    unsigned char raw[32];
    tiny_spec sp;
    pn_mesh m;
    unsigned i;
    const char *ext = "\"extensionsUsed\":[\"KHR_mesh_quantization\"],"
                      "\"extensionsRequired\":[\"KHR_mesh_quantization\"]";

    /* Unsigned shorts, not normalized, under a scale of 1/2 (gltfpack's layout: 8-byte
     * elements). */
    memset(&sp, 0, sizeof sp);
    memset(raw, 0, sizeof raw);
    for (i = 0; i < 12; i++) put_le16(raw + (i / 3u) * 8u + (i % 3u) * 2u, u16[i]);
    sp.itype = 5123;
    sp.pos_raw = raw;
    sp.pos_raw_len = 32;
    sp.nverts = 4;
    sp.view0_stride = 8;
    sp.pos_ctype = 5123;
    sp.top = ext;
    sp.nodes = "[{\"scale\":[0.5,0.5,0.5],\"mesh\":0}]";
    if (expect_ok("quantized_u16.glb", &sp, &m) == 0 && m.vertex_count == 4) {
        CHECK(memcmp(m.positions, quad_pos, sizeof quad_pos) == 0);
        for (i = 0; i < 6; i++) CHECK(m.indices[i] == quad_idx[i]);
    }
    pn_mesh_free(&m);
    /* The same file without the extension: integer positions are refused, saying why. */
    sp.top = NULL;
    expect_fail("quantized_u16_no_extension.glb", &sp, "KHR_mesh_quantization");
    sp.top = ext;
    sp.nodes = NULL;

    /* Signed shorts, normalized: c / 32767, at least -1. */
    for (i = 0; i < 12; i++) put_le16(raw + (i / 3u) * 8u + (i % 3u) * 2u, s16[i]);
    sp.pos_ctype = 5122;
    sp.pos_norm = 1;
    if (expect_ok("quantized_s16_normalized.glb", &sp, &m) == 0 && m.vertex_count == 4)
        for (i = 0; i < 12; i++) CHECK_MSG(m.positions[i] == s16_want[i], "s16 %u: %g", i, (double)m.positions[i]);
    pn_mesh_free(&m);

    /* Signed bytes, normalized (4-byte elements): c / 127, at least -1. */
    memset(raw, 0, sizeof raw);
    for (i = 0; i < 12; i++) raw[(i / 3u) * 4u + i % 3u] = (unsigned char)s8[i];
    sp.pos_raw_len = 16;
    sp.view0_stride = 4;
    sp.pos_ctype = 5120;
    if (expect_ok("quantized_s8_normalized.glb", &sp, &m) == 0 && m.vertex_count == 4)
        for (i = 0; i < 12; i++) CHECK_MSG(m.positions[i] == s16_want[i], "s8 %u: %g", i, (double)m.positions[i]);
    pn_mesh_free(&m);
    /* Unsigned bytes, normalized: c / 255. */
    for (i = 0; i < 12; i++) raw[(i / 3u) * 4u + i % 3u] = (unsigned char)(u16[i] ? 255 : 0);
    sp.pos_ctype = 5121;
    if (expect_ok("quantized_u8_normalized.glb", &sp, &m) == 0 && m.vertex_count == 4)
        CHECK(memcmp(m.positions, quad_pos, sizeof quad_pos) == 0);
    pn_mesh_free(&m);
    /* An integer type the extension does not allow for positions. */
    sp.pos_ctype = 5125;
    expect_fail("quantized_u32.glb", &sp, "componentType");

    /* Compressed geometry: refused, naming a way out. */
    memset(&sp, 0, sizeof sp);
    sp.itype = 5123;
    sp.top = "\"extensionsUsed\":[\"EXT_meshopt_compression\"],"
             "\"extensionsRequired\":[\"EXT_meshopt_compression\"]";
    expect_fail("meshopt_required.glb", &sp, "without -c");
}

int main(void)
{
    RUN(test_scene_set);
    RUN(test_scene_set_complete);
    RUN(test_spot_memory_matches_file);
    RUN(test_truncated_and_corrupt_spot);
    RUN(test_missing_and_odd_paths);
    RUN(test_tiny_valid);
    RUN(test_stride);
    RUN(test_tiny_malformed);
    RUN(test_triangle_limit);
    RUN(test_transforms);
    RUN(test_winding_strips_fans);
    RUN(test_quantized_positions);
    RUN(test_ascii_gltf);
    RUN(test_mutations);
    RUN(test_mesh_ground);
    RUN(test_pfm);
    RUN(test_png_and_ids);
    return pn_test_summary();
}
