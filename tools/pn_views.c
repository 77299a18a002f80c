/* pn_views.c - evaluation views from a views file (../shared/scenes/views.json): a JSON
 * object whose keys are scene names (a .glb's file name without the extension) and whose
 * values give the image size, the camera, a one-sided rectangular light and the ground
 * flag (schema: ../shared/scenes/README.md). Host code only.
 *
 * The reader is a small JSON parser of its own (the tools link no JSON library): objects,
 * arrays, numbers, strings, true/false/null, nesting bounded, every error with the file and
 * the byte offset or the key it concerns. */
#include "pn_setup.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PN_VIEWS_MAX_BYTES (1u << 20)
#define PN_VIEWS_MAX_DEPTH 32

typedef struct jp {
    const char *s, *start, *end, *file;
    char *err;
    size_t err_size;
    int failed;
} jp;

static int jp_fail(jp *p, const char *what)
{
    if (!p->failed) snprintf(p->err, p->err_size, "%s: %s at byte %ld", p->file, what, (long)(p->s - p->start));
    p->failed = 1;
    return 1;
}

static void jp_ws(jp *p)
{
    while (p->s < p->end && (*p->s == ' ' || *p->s == '\t' || *p->s == '\n' || *p->s == '\r')) p->s++;
}

/* A string: writes up to out_size - 1 bytes of it (escapes other than \" and \\ kept as
 * they are: keys and names here are plain ASCII). */
static int jp_string(jp *p, char *out, size_t out_size)
{
    size_t n = 0;
    jp_ws(p);
    if (p->s >= p->end || *p->s != '"') return jp_fail(p, "expected a string");
    p->s++;
    while (p->s < p->end && *p->s != '"') {
        char c = *p->s++;
        if (c == '\\') {
            if (p->s >= p->end) break;
            c = *p->s++;
        }
        if (out && n + 1 < out_size) out[n++] = c;
    }
    if (p->s >= p->end) return jp_fail(p, "unterminated string");
    p->s++;
    if (out && out_size) out[n] = '\0';
    return 0;
}

static int jp_number(jp *p, double *out)
{
    char buf[64];
    size_t n = 0;
    char *e;
    jp_ws(p);
    while (p->s + n < p->end && n + 1 < sizeof(buf) && (isdigit((unsigned char)p->s[n]) || strchr("+-.eE", p->s[n])))
        n++;
    if (n == 0) return jp_fail(p, "expected a number");
    memcpy(buf, p->s, n);
    buf[n] = '\0';
    errno = 0;
    *out = strtod(buf, &e);
    if (*e != '\0' || errno != 0 || !isfinite(*out)) return jp_fail(p, "bad number");
    p->s += n;
    return 0;
}

static int jp_literal(jp *p, const char *lit)
{
    size_t n = strlen(lit);
    if ((size_t)(p->end - p->s) < n || memcmp(p->s, lit, n) != 0) return 1;
    p->s += n;
    return 0;
}

/* Skips one value of any type. Containers are tracked on an explicit stack (no recursion),
 * its depth bounded. */
static int jp_skip(jp *p)
{
    char stack[PN_VIEWS_MAX_DEPTH];
    int depth = 0;
    for (;;) {
        jp_ws(p);
        if (p->s >= p->end) return jp_fail(p, "unexpected end of file");
        /* A value. */
        if (*p->s == '{' || *p->s == '[') {
            if (depth == PN_VIEWS_MAX_DEPTH) return jp_fail(p, "nested too deeply");
            stack[depth++] = *p->s++;
            jp_ws(p);
            if (p->s < p->end && (*p->s == '}' || *p->s == ']')) {
                if ((*p->s == '}') != (stack[depth - 1] == '{')) return jp_fail(p, "mismatched bracket");
                p->s++;
                depth--;
            } else {
                if (stack[depth - 1] == '{') {
                    if (jp_string(p, NULL, 0)) return 1;
                    jp_ws(p);
                    if (p->s >= p->end || *p->s != ':') return jp_fail(p, "expected ':'");
                    p->s++;
                }
                continue;
            }
        } else if (*p->s == '"') {
            if (jp_string(p, NULL, 0)) return 1;
        } else if (jp_literal(p, "true") != 0 && jp_literal(p, "false") != 0 && jp_literal(p, "null") != 0) {
            double d;
            if (jp_number(p, &d)) return 1;
        }
        /* After a value: close containers, or go on to the next member. */
        for (;;) {
            if (depth == 0) return 0;
            jp_ws(p);
            if (p->s >= p->end) return jp_fail(p, "unexpected end of file");
            if (*p->s == '}' || *p->s == ']') {
                if ((*p->s == '}') != (stack[depth - 1] == '{')) return jp_fail(p, "mismatched bracket");
                p->s++;
                depth--;
                continue;
            }
            if (*p->s != ',') return jp_fail(p, "expected ',' or a closing bracket");
            p->s++;
            if (stack[depth - 1] == '{') {
                if (jp_string(p, NULL, 0)) return 1;
                jp_ws(p);
                if (p->s >= p->end || *p->s != ':') return jp_fail(p, "expected ':'");
                p->s++;
            }
            break;
        }
    }
}

/* An array of exactly n numbers. */
static int jp_numbers(jp *p, double *out, int n)
{
    int i;
    jp_ws(p);
    if (p->s >= p->end || *p->s != '[') return 1;
    p->s++;
    for (i = 0; i < n; i++) {
        if (i > 0) {
            jp_ws(p);
            if (p->s >= p->end || *p->s != ',') return 1;
            p->s++;
        }
        if (jp_number(p, &out[i])) return 1;
    }
    jp_ws(p);
    if (p->s >= p->end || *p->s != ']') return 1;
    p->s++;
    return 0;
}

enum { F_SIZE, F_EYE, F_TARGET, F_UP, F_FOV, F_LC, F_LU, F_LV, F_GROUND, F_COUNT };
static const char *const pn_view_fields[F_COUNT] = {"size",         "eye",     "target",  "up",    "fov",
                                                    "light_center", "light_u", "light_v", "ground"};

/* Parses one view object into v; `name` for messages. */
static int jp_view(jp *p, const char *name, pn_view *v)
{
    int have[F_COUNT] = {0}, f;
    char key[64];
    double d[3];
    memset(v, 0, sizeof(*v));
    snprintf(v->name, sizeof(v->name), "%s", name);
    v->camera.up[1] = 1.0f;
    v->ground = -1;
    jp_ws(p);
    if (p->s >= p->end || *p->s != '{') {
        snprintf(p->err, p->err_size, "%s: view '%s' is not an object", p->file, name);
        return p->failed = 1;
    }
    p->s++;
    jp_ws(p);
    if (p->s < p->end && *p->s == '}') {
        p->s++;
    } else {
        for (;;) {
            if (jp_string(p, key, sizeof(key))) return 1;
            jp_ws(p);
            if (p->s >= p->end || *p->s != ':') return jp_fail(p, "expected ':'");
            p->s++;
            jp_ws(p);
            for (f = 0; f < F_COUNT && strcmp(key, pn_view_fields[f]) != 0; f++) {
            }
            if (f == F_SIZE) {
                if (jp_numbers(p, d, 2) || !(d[0] >= 1.0 && d[1] >= 1.0 && d[0] <= 65536.0 && d[1] <= 65536.0) ||
                    d[0] != floor(d[0]) || d[1] != floor(d[1])) {
                    snprintf(p->err, p->err_size, "%s: view '%s': 'size' must be [W, H], whole numbers 1..65536",
                             p->file, name);
                    return p->failed = 1;
                }
                v->width = (uint32_t)d[0];
                v->height = (uint32_t)d[1];
            } else if (f == F_FOV) {
                if (jp_number(p, d) || !(d[0] > 0.0 && d[0] < 180.0)) {
                    p->failed = 0; /* the specific message below replaces jp_number's */
                    snprintf(p->err, p->err_size, "%s: view '%s': 'fov' must be a number of degrees in (0, 180)",
                             p->file, name);
                    return p->failed = 1;
                }
                v->camera.fov_deg = (float)d[0];
            } else if (f == F_GROUND) {
                if (jp_literal(p, "true") == 0) v->ground = 1;
                else if (jp_literal(p, "false") == 0) v->ground = 0;
                else {
                    snprintf(p->err, p->err_size, "%s: view '%s': 'ground' must be true or false", p->file, name);
                    return p->failed = 1;
                }
            } else if (f < F_COUNT) {
                float *dst = f == F_EYE ? v->camera.eye
                             : f == F_TARGET ? v->camera.target
                             : f == F_UP ? v->camera.up
                             : f == F_LC ? v->light.center
                             : f == F_LU ? v->light.u
                                         : v->light.v;
                int a;
                if (jp_numbers(p, d, 3)) {
                    p->failed = 0; /* the specific message below replaces jp_number's */
                    snprintf(p->err, p->err_size, "%s: view '%s': '%s' must be [x, y, z] (numbers)", p->file, name,
                             key);
                    return p->failed = 1;
                }
                for (a = 0; a < 3; a++) {
                    dst[a] = (float)d[a];
                    if (!isfinite(dst[a])) {
                        snprintf(p->err, p->err_size, "%s: view '%s': '%s' is out of float range", p->file, name, key);
                        return p->failed = 1;
                    }
                }
            } else if (jp_skip(p)) {
                return 1;
            }
            if (f < F_COUNT) have[f] = 1;
            jp_ws(p);
            if (p->s < p->end && *p->s == ',') {
                p->s++;
                continue;
            }
            if (p->s < p->end && *p->s == '}') {
                p->s++;
                break;
            }
            return jp_fail(p, "expected ',' or '}'");
        }
    }
    {
        static const int required[] = {F_EYE, F_TARGET, F_FOV, F_LC, F_LU, F_LV};
        size_t i;
        for (i = 0; i < sizeof(required) / sizeof(required[0]); i++)
            if (!have[required[i]]) {
                snprintf(p->err, p->err_size, "%s: view '%s' has no '%s'", p->file, name,
                         pn_view_fields[required[i]]);
                return p->failed = 1;
            }
    }
    return 0;
}

int pn_view_load(const char *path, const char *name, pn_view *v, char *err, size_t err_size)
{
    FILE *f;
    char *text;
    size_t n;
    jp p;
    char key[128], keys[512];
    size_t klen = 0;
    int found = 0, rc;
    if (!path || !name || !v) {
        snprintf(err, err_size, "pn_view_load: NULL argument");
        return 2;
    }
    f = fopen(path, "rb");
    if (!f) {
        snprintf(err, err_size, "cannot open views file %s: %s", path, strerror(errno));
        return 2;
    }
    text = (char *)malloc(PN_VIEWS_MAX_BYTES + 1u);
    n = text ? fread(text, 1, PN_VIEWS_MAX_BYTES + 1u, f) : 0;
    fclose(f);
    if (!text) {
        snprintf(err, err_size, "%s: out of memory", path);
        return 2;
    }
    if (n > PN_VIEWS_MAX_BYTES) {
        free(text);
        snprintf(err, err_size, "%s: larger than %u bytes", path, PN_VIEWS_MAX_BYTES);
        return 2;
    }
    memset(&p, 0, sizeof(p));
    p.s = p.start = text;
    p.end = text + n;
    p.file = path;
    p.err = err;
    p.err_size = err_size;
    keys[0] = '\0';
    jp_ws(&p);
    if (p.s >= p.end || *p.s != '{') {
        jp_fail(&p, "expected a JSON object of views");
    } else {
        p.s++;
        jp_ws(&p);
        if (p.s < p.end && *p.s == '}') p.s++;
        else
            for (;;) {
                if (jp_string(&p, key, sizeof(key))) break;
                jp_ws(&p);
                if (p.s >= p.end || *p.s != ':') {
                    jp_fail(&p, "expected ':'");
                    break;
                }
                p.s++;
                if (klen < sizeof(keys)) {
                    int w = snprintf(keys + klen, sizeof(keys) - klen, "%s%s", klen ? ", " : "", key);
                    if (w > 0) klen += (size_t)w;
                }
                if (!found && strcmp(key, name) == 0) {
                    if (jp_view(&p, name, v)) break;
                    found = 1;
                } else if (jp_skip(&p)) {
                    break;
                }
                jp_ws(&p);
                if (p.s < p.end && *p.s == ',') {
                    p.s++;
                    continue;
                }
                if (p.s < p.end && *p.s == '}') {
                    p.s++;
                    break;
                }
                jp_fail(&p, "expected ',' or '}'");
                break;
            }
    }
    if (!p.failed) {
        jp_ws(&p);
        if (p.s != p.end) jp_fail(&p, "trailing characters after the object");
    }
    if (p.failed) rc = 2;
    else if (!found) {
        snprintf(err, err_size, "%s: no view '%s' (views: %s)", path, name, klen ? keys : "none");
        rc = 1;
    } else rc = 0;
    free(text);
    return rc;
}
