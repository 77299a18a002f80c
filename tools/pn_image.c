/* pn_image.c - PNG (stb_image_write), PFM and raw-id output (see pn_image.h). */
#include "pn_image.h"
#include "pn_mesh.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The implementation comes from libstb (Debian's -lstb); only the declarations are needed. */
#include "stb_image_write.h"

/* Per-side limit: keeps w * 4 inside int for stb and w * h * 4 far inside size_t. */
#define PN_IMAGE_MAX_DIM 65536u


static int pn_image_check_args(const char *fn, const char *path, const void *data, uint32_t w,
                               uint32_t h, char *err, size_t err_size)
{
    if (path == NULL || path[0] == '\0') {
        pn_tools_err(err, err_size, "%s: no path given", fn);
        return 1;
    }
    if (data == NULL) {
        pn_tools_err(err, err_size, "%s: '%s': pixel data is NULL", fn, path);
        return 1;
    }
    if (w == 0 || h == 0 || w > PN_IMAGE_MAX_DIM || h > PN_IMAGE_MAX_DIM) {
        pn_tools_err(err, err_size, "%s: '%s': size %ux%u outside 1..%u per side", fn, path,
                     (unsigned)w, (unsigned)h, PN_IMAGE_MAX_DIM);
        return 1;
    }
    return 0;
}

static void pn_put_le32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v & 0xffu);
    p[1] = (unsigned char)((v >> 8) & 0xffu);
    p[2] = (unsigned char)((v >> 16) & 0xffu);
    p[3] = (unsigned char)((v >> 24) & 0xffu);
}

/* Closes f and reports the first error of the write sequence (fclose flushes, so its failure
 * counts too). */
static int pn_close_checked(FILE *f, int write_failed, const char *fn, const char *path,
                            char *err, size_t err_size)
{
    int e = 0;
    if (write_failed || ferror(f)) {
        e = errno ? errno : EIO;
    }
    if (fclose(f) != 0 && e == 0) {
        e = errno ? errno : EIO;
    }
    if (e != 0) {
        pn_tools_err(err, err_size, "%s: cannot write '%s': %s", fn, path, strerror(e));
        return 1;
    }
    return 0;
}

/* stb writes through a callback so that file errors reach us with errno intact. */
typedef struct pn_png_sink {
    FILE *f;
    int failed;
} pn_png_sink;

static void pn_png_write_cb(void *ctx, void *data, int size)
{
    pn_png_sink *s = (pn_png_sink *)ctx;
    if (!s->failed && size > 0 && fwrite(data, 1, (size_t)size, s->f) != (size_t)size) {
        s->failed = 1;
    }
}

int pn_write_png(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h, char *err,
                 size_t err_size)
{
    pn_png_sink sink;
    int ok;
    if (pn_image_check_args("pn_write_png", path, rgba, w, h, err, err_size)) {
        return 1;
    }
    sink.f = fopen(path, "wb");
    if (sink.f == NULL) {
        pn_tools_err(err, err_size, "pn_write_png: cannot create '%s': %s", path,
                     strerror(errno));
        return 1;
    }
    sink.failed = 0;
    errno = 0;
    ok = stbi_write_png_to_func(pn_png_write_cb, &sink, (int)w, (int)h, 4, rgba, (int)(w * 4u));
    if (!ok) {
        fclose(sink.f);
        pn_tools_err(err, err_size, "pn_write_png: '%s': PNG encoding failed (out of memory?)",
                     path);
        return 1;
    }
    return pn_close_checked(sink.f, sink.failed, "pn_write_png", path, err, err_size);
}

int pn_write_pfm(const char *path, const float *gray, uint32_t w, uint32_t h, char *err,
                 size_t err_size)
{
    FILE *f;
    unsigned char *row;
    uint32_t x, y;
    int failed = 0;
    if (pn_image_check_args("pn_write_pfm", path, gray, w, h, err, err_size)) {
        return 1;
    }
    row = (unsigned char *)malloc((size_t)w * 4u);
    if (row == NULL) {
        pn_tools_err(err, err_size, "pn_write_pfm: out of memory");
        return 1;
    }
    f = fopen(path, "wb");
    if (f == NULL) {
        pn_tools_err(err, err_size, "pn_write_pfm: cannot create '%s': %s", path,
                     strerror(errno));
        free(row);
        return 1;
    }
    errno = 0;
    if (fprintf(f, "Pf\n%u %u\n-1.0\n", (unsigned)w, (unsigned)h) < 0) {
        failed = 1;
    }
    /* PFM stores the bottom row first. */
    for (y = h; y-- > 0 && !failed;) {
        const float *src = gray + (size_t)y * w;
        for (x = 0; x < w; x++) {
            uint32_t bits;
            memcpy(&bits, &src[x], sizeof bits);
            pn_put_le32(row + (size_t)x * 4u, bits);
        }
        if (fwrite(row, 4, w, f) != w) {
            failed = 1;
        }
    }
    free(row);
    return pn_close_checked(f, failed, "pn_write_pfm", path, err, err_size);
}

/* Reads one whitespace-delimited header token; returns its length, 0 on EOF/overflow. */
static size_t pn_pfm_token(FILE *f, char *tok, size_t cap)
{
    int c;
    size_t n = 0;
    do {
        c = fgetc(f);
    } while (c == ' ' || c == '\t' || c == '\n' || c == '\r');
    while (c != EOF && c != ' ' && c != '\t' && c != '\n' && c != '\r') {
        if (n + 1 >= cap) {
            return 0;
        }
        tok[n++] = (char)c;
        c = fgetc(f);
    }
    tok[n] = '\0';
    /* The single whitespace after the scale is consumed here, so the data starts next. */
    return c == EOF ? 0 : n;
}

static int pn_parse_dim(const char *s, uint32_t *v)
{
    char *end;
    unsigned long x;
    if (s[0] < '0' || s[0] > '9') {
        return 0;
    }
    errno = 0;
    x = strtoul(s, &end, 10);
    if (errno != 0 || *end != '\0' || x == 0 || x > PN_IMAGE_MAX_DIM) {
        return 0;
    }
    *v = (uint32_t)x;
    return 1;
}

int pn_read_pfm(const char *path, float **out, uint32_t *w, uint32_t *h, char *err,
                size_t err_size)
{
    FILE *f;
    char tok[64];
    uint32_t ww = 0, hh = 0, x, y;
    double scale;
    char *end;
    int big_endian;
    long data_start, file_end;
    float *pix = NULL;
    unsigned char *row = NULL;

    if (out == NULL || w == NULL || h == NULL || path == NULL) {
        pn_tools_err(err, err_size, "pn_read_pfm: NULL argument");
        return 1;
    }
    *out = NULL;
    *w = 0;
    *h = 0;
    f = fopen(path, "rb");
    if (f == NULL) {
        pn_tools_err(err, err_size, "pn_read_pfm: cannot open '%s': %s", path, strerror(errno));
        return 1;
    }
    if (pn_pfm_token(f, tok, sizeof tok) == 0 || strcmp(tok, "Pf") != 0) {
        pn_tools_err(err, err_size, "pn_read_pfm: '%s' is not a grayscale PFM (no \"Pf\")",
                     path);
        goto fail;
    }
    if (pn_pfm_token(f, tok, sizeof tok) == 0 || !pn_parse_dim(tok, &ww) ||
        pn_pfm_token(f, tok, sizeof tok) == 0 || !pn_parse_dim(tok, &hh)) {
        pn_tools_err(err, err_size, "pn_read_pfm: '%s': bad width/height (1..%u)", path,
                     PN_IMAGE_MAX_DIM);
        goto fail;
    }
    if (pn_pfm_token(f, tok, sizeof tok) == 0) {
        pn_tools_err(err, err_size, "pn_read_pfm: '%s': missing scale", path);
        goto fail;
    }
    scale = strtod(tok, &end);
    if (*end != '\0' || scale == 0.0 || !isfinite(scale)) {
        pn_tools_err(err, err_size, "pn_read_pfm: '%s': bad scale '%s'", path, tok);
        goto fail;
    }
    big_endian = scale > 0.0;
    /* Check the payload size before allocating, so a lying header cannot make us allocate
     * more than the file holds. */
    data_start = ftell(f);
    if (data_start < 0 || fseek(f, 0, SEEK_END) != 0 || (file_end = ftell(f)) < 0 ||
        fseek(f, data_start, SEEK_SET) != 0) {
        pn_tools_err(err, err_size, "pn_read_pfm: '%s': cannot seek", path);
        goto fail;
    }
    if ((uint64_t)(file_end - data_start) != (uint64_t)ww * hh * 4u) {
        pn_tools_err(err, err_size,
                     "pn_read_pfm: '%s': %ld data bytes, %ux%u floats need %llu", path,
                     file_end - data_start, (unsigned)ww, (unsigned)hh,
                     (unsigned long long)ww * hh * 4u);
        goto fail;
    }
    pix = (float *)malloc((size_t)ww * hh * sizeof(float));
    row = (unsigned char *)malloc((size_t)ww * 4u);
    if (pix == NULL || row == NULL) {
        pn_tools_err(err, err_size, "pn_read_pfm: '%s': out of memory", path);
        goto fail;
    }
    /* File rows run bottom to top; the caller gets top row first. */
    for (y = hh; y-- > 0;) {
        float *dst = pix + (size_t)y * ww;
        if (fread(row, 4, ww, f) != ww) {
            pn_tools_err(err, err_size, "pn_read_pfm: '%s': short read", path);
            goto fail;
        }
        for (x = 0; x < ww; x++) {
            const unsigned char *p = row + (size_t)x * 4u;
            uint32_t bits = big_endian
                ? ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | p[3]
                : ((uint32_t)p[3] << 24) | ((uint32_t)p[2] << 16) | ((uint32_t)p[1] << 8) | p[0];
            memcpy(&dst[x], &bits, sizeof bits);
        }
    }
    free(row);
    fclose(f);
    *out = pix;
    *w = ww;
    *h = hh;
    return 0;

fail:
    free(pix);
    free(row);
    fclose(f);
    return 1;
}

int pn_write_ids(const char *path, const uint32_t *ids, uint32_t w, uint32_t h, char *err,
                 size_t err_size)
{
    FILE *f;
    unsigned char *row;
    uint32_t x, y;
    int failed = 0;
    if (pn_image_check_args("pn_write_ids", path, ids, w, h, err, err_size)) {
        return 1;
    }
    row = (unsigned char *)malloc((size_t)w * 4u);
    if (row == NULL) {
        pn_tools_err(err, err_size, "pn_write_ids: out of memory");
        return 1;
    }
    f = fopen(path, "wb");
    if (f == NULL) {
        pn_tools_err(err, err_size, "pn_write_ids: cannot create '%s': %s", path,
                     strerror(errno));
        free(row);
        return 1;
    }
    errno = 0;
    for (y = 0; y < h && !failed; y++) {
        const uint32_t *src = ids + (size_t)y * w;
        for (x = 0; x < w; x++) {
            pn_put_le32(row + (size_t)x * 4u, src[x]);
        }
        if (fwrite(row, 4, w, f) != w) {
            failed = 1;
        }
    }
    free(row);
    return pn_close_checked(f, failed, "pn_write_ids", path, err, err_size);
}

void pn_vis_to_rgba(const float *vis, size_t n, uint8_t *rgba)
{
    size_t i;
    for (i = 0; i < n; i++) {
        uint8_t g = (uint8_t)lrintf(fminf(fmaxf(vis[i], 0.0f), 1.0f) * 255.0f);
        rgba[i * 4] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = g;
        rgba[i * 4 + 3] = 255;
    }
}

void pn_err_to_rgba(const float *vis, const float *ref, size_t n, uint8_t *rgba)
{
    size_t i;
    for (i = 0; i < n; i++) {
        float e = fminf(fabsf(vis[i] - ref[i]) * 4.0f, 1.0f); /* x4: 0.25 error is full scale */
        rgba[i * 4] = (uint8_t)lrintf(e > 0.0f ? 64.0f + 191.0f * fminf(e * 2.0f, 1.0f) : 0.0f);
        rgba[i * 4 + 1] = (uint8_t)lrintf(e > 0.5f ? 255.0f * (e - 0.5f) * 2.0f : 0.0f);
        rgba[i * 4 + 2] = 0;
        rgba[i * 4 + 3] = 255;
    }
}

void pn_blit_rgba(uint8_t *sheet, uint32_t sheet_w, const uint8_t *img, uint32_t w, uint32_t h,
                  uint32_t ox, uint32_t oy)
{
    uint32_t y;
    for (y = 0; y < h; y++)
        memcpy(sheet + ((size_t)(oy + y) * sheet_w + ox) * 4, img + (size_t)y * w * 4, (size_t)w * 4);
}

int pn_mkdir_p(const char *path)
{
    char buf[1024];
    size_t i, n = strlen(path);
    if (n == 0 || n >= sizeof(buf)) return 1;
    memcpy(buf, path, n + 1);
    for (i = 1; i <= n; i++)
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return 1;
            buf[i] = c;
        }
    return 0;
}
