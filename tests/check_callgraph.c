/* check_callgraph.c - proves from GCC's own call graph that the library has no recursion,
 * no dynamically sized stack objects, function-pointer calls only at the documented
 * dispatch sites, and a bounded worst-case stack (DESIGN.md invariant 1). Host program,
 * run by ctest (no_recursion_bounded_stack, no_recursion_bounded_stack_m7).
 *
 *   check_callgraph --header include/penumbra/penumbra.h --budget 16384
 *                   --site pn_run=passed --site pn_render_with=table --site pn_now=external
 *                   [--source OBJ...] --objects OBJ... [--name TEXT]
 *
 * Inputs, next to each object X.o (GCC names them after the object):
 *   X.ci   -fcallgraph-info=su,da: one VCG graph per translation unit. Nodes are functions
 *          (title "name" for external linkage, "file.c:name" for static ones, so titles are
 *          unique across the library), labelled with the frame size and qualifier of
 *          -fstack-usage and the count of dynamically sized stack objects (VLAs, alloca);
 *          edges are direct calls; a call through a pointer is an edge to "__indirect_call".
 *   X.su   -fstack-usage: cross-checked against the .ci (same compile, nothing stale).
 *   X.*.cgraph   -fdump-ipa-cgraph (optional per set, needed once): which functions have
 *          their address taken, and by whom ("Referring: f/12 (addr)").
 *
 * --objects is the library as built (its frame sizes are the ones that run); --source is
 * the same sources compiled at -O0, where every call written in the source is still a call:
 * at -O2 GCC turns tail recursion into loops and inlines mutual recursion, so the optimised
 * graph alone cannot show that the *source* is free of recursion (OpenCL C forbids it, and
 * the kernels/ code is compiled for OpenCL too). Both sets get the structural checks:
 *
 *   (a) no cycle in the call graph (direct or mutual recursion), indirect calls included;
 *   (b) no function with a dynamically sized stack object ("N dynamic objects" > 0: VLA or
 *       alloca) and no unbounded "dynamic" frame. A "dynamic,bounded" frame with zero
 *       dynamic objects is accepted and listed: on x86-64 GCC pushes outgoing stack
 *       arguments (calls with more than six integer arguments, e.g. pn_fail's varargs)
 *       instead of reserving them in the prologue, so the frame grows and shrinks around
 *       the call; the number reported is its upper bound (GCC manual, -fstack-usage);
 *   (c) calls through a function pointer only inside the functions named by --site. Each
 *       site says what it may reach:
 *         passed    a function whose address some library function takes (and hands to the
 *                   site as an argument: the pn_task_fn given to pn_run),
 *         table     a function whose address sits in a static table (the pn_port pass table
 *                   dispatched by pn_render_with),
 *         external  only the caller's own callbacks (pn_now calls the user's clock).
 *       Every address-taken library function must be of a class some site serves, so no
 *       function pointer escapes the analysis. The resolution assumes a "passed" pointer is
 *       only ever handed down to a passed-class site and a table only read by a table-class
 *       site, which is what the port interface does; a new kind of dispatch needs a new site.
 *
 * On --objects it then computes, for every function declared in the public header, the
 * deepest call path weighted by frame sizes (indirect calls resolved as above; the frames
 * of the caller's callbacks -- parallel_for, clock -- and of memcpy/memset are not the
 * library's and are not counted) and fails if one exceeds --budget bytes. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { CLS_PASSED = 1, CLS_TABLE = 2, CLS_EXTERNAL = 4 };

static int g_failures;

static void fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("FAIL: ", stdout);
    vprintf(fmt, ap);
    fputc('\n', stdout);
    va_end(ap);
    g_failures++;
}

static void *xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (!q) {
        fprintf(stderr, "check_callgraph: out of memory\n");
        exit(2);
    }
    return q;
}

static char *xstrndup(const char *s, size_t n)
{
    char *d = (char *)xrealloc(NULL, n + 1);
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

static char *xstrdup(const char *s) { return xstrndup(s, strlen(s)); }

static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    size_t n = 0, cap = 0, r;
    if (!f) return NULL;
    do {
        if (cap - n < 4096) {
            cap = cap ? cap * 2 : 65536;
            buf = (char *)xrealloc(buf, cap + 1);
        }
        r = fread(buf + n, 1, cap - n, f);
        n += r;
    } while (r > 0);
    fclose(f);
    buf[n] = '\0';
    return buf;
}

/* ---- the graph ---------------------------------------------------------------------- */

typedef struct node {
    char *title;      /* unique key */
    char *name;       /* function name as printed by GCC (clones: "f.part.0") */
    char *loc;        /* file:line:col of the definition (or declaration) */
    int defined;      /* a .ci labelled it with a frame size */
    long bytes;       /* frame size, -fstack-usage */
    char qual[32];    /* static | dynamic | dynamic,bounded */
    long dyn_objects; /* VLAs / alloca */
    char *dyn_desc;
    int su_seen;      /* matched by a .su line */
    /* analysis */
    int color;        /* DFS: 0 white, 1 on stack, 2 done */
    long depth;       /* deepest stack from here, this frame included */
    int next;         /* successor on that path, -1 none */
    int next_edge;
} node;

typedef struct edge {
    int from, to; /* to == -1: call through a pointer, not yet resolved */
    char *loc;
    int indirect; /* 1: a resolved indirect call */
} edge;

typedef struct graph {
    const char *what;
    node *nodes;
    size_t nn, capn;
    edge *edges;
    size_t ne, cape;
    int **adj; /* per node: edge indices, -1 terminated, built by build_adj */
} graph;

static int node_find(const graph *g, const char *title)
{
    size_t i;
    for (i = 0; i < g->nn; i++)
        if (strcmp(g->nodes[i].title, title) == 0) return (int)i;
    return -1;
}

static int node_get(graph *g, const char *title)
{
    int i = node_find(g, title);
    node *n;
    if (i >= 0) return i;
    if (g->nn == g->capn) {
        g->capn = g->capn ? g->capn * 2 : 256;
        g->nodes = (node *)xrealloc(g->nodes, g->capn * sizeof(node));
    }
    n = &g->nodes[g->nn];
    memset(n, 0, sizeof(*n));
    n->title = xstrdup(title);
    n->name = xstrdup(title);
    n->loc = xstrdup("?");
    n->bytes = 0;
    n->next = -1;
    n->next_edge = -1;
    return (int)g->nn++;
}

static void edge_add(graph *g, int from, int to, const char *loc, int indirect)
{
    edge *e;
    if (g->ne == g->cape) {
        g->cape = g->cape ? g->cape * 2 : 1024;
        g->edges = (edge *)xrealloc(g->edges, g->cape * sizeof(edge));
    }
    e = &g->edges[g->ne++];
    e->from = from;
    e->to = to;
    e->loc = xstrdup(loc ? loc : "?");
    e->indirect = indirect;
}

/* The quoted value after `key` in a VCG line ("title: \"...\""), or NULL. */
static char *vcg_value(const char *line, const char *key)
{
    const char *p = strstr(line, key), *q;
    if (!p) return NULL;
    p += strlen(key);
    while (*p == ' ') p++;
    if (*p != '"') return NULL;
    p++;
    for (q = p; *q && *q != '"' && *q != '\n'; q++)
        if (*q == '\\' && q[1]) q++;
    return xstrndup(p, (size_t)(q - p));
}

/* Splits a VCG label on its literal "\n" sequences into at most `max` fields. */
static int label_fields(char *label, char **f, int max)
{
    int n = 0;
    char *p = label;
    while (n < max) {
        char *s = strstr(p, "\\n");
        f[n++] = p;
        if (!s) break;
        *s = '\0';
        p = s + 2;
    }
    return n;
}

/* Reads one .ci file into g; returns the translation unit's main file name or NULL. */
static char *parse_ci(graph *g, const char *path)
{
    char *buf = read_file(path), *line, *tu = NULL;
    if (!buf) return NULL;
    for (line = buf; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        char *eol = strchr(line, '\n');
        char save = 0;
        if (eol) {
            save = *eol;
            *eol = '\0';
        }
        if (strncmp(line, "graph:", 6) == 0) {
            free(tu);
            tu = vcg_value(line, "title:");
        } else if (strncmp(line, "node:", 5) == 0) {
            char *title = vcg_value(line, "title:"), *label = vcg_value(line, "label:");
            if (title && label && strcmp(title, "__indirect_call") != 0) {
                char *f[64];
                int nf = label_fields(label, f, 64), i = node_get(g, title);
                node *n = &g->nodes[i];
                long bytes;
                char qual[32];
                if (nf >= 3 && sscanf(f[2], "%ld bytes (%31[^)])", &bytes, qual) == 2) {
                    if (n->defined)
                        fail("%s: function %s is defined twice (%s and %s)", g->what, title, n->loc, nf > 1 ? f[1] : "?");
                    free(n->name);
                    free(n->loc);
                    n->name = xstrdup(f[0]);
                    n->loc = xstrdup(nf > 1 ? f[1] : "?");
                    n->defined = 1;
                    n->bytes = bytes;
                    strcpy(n->qual, qual);
                    if (nf >= 4) sscanf(f[3], "%ld dynamic objects", &n->dyn_objects);
                    if (nf >= 5) {
                        size_t len = 0;
                        int k;
                        for (k = 4; k < nf; k++) len += strlen(f[k]) + 2;
                        n->dyn_desc = (char *)xrealloc(NULL, len + 1);
                        n->dyn_desc[0] = '\0';
                        for (k = 4; k < nf; k++) {
                            strcat(n->dyn_desc, f[k]);
                            if (k + 1 < nf) strcat(n->dyn_desc, ";");
                        }
                    }
                } else if (!n->defined) {
                    free(n->name);
                    free(n->loc);
                    n->name = xstrdup(f[0]);
                    n->loc = xstrdup(nf > 1 ? f[1] : "?");
                }
            }
            free(title);
            free(label);
        } else if (strncmp(line, "edge:", 5) == 0) {
            char *s = vcg_value(line, "sourcename:"), *t = vcg_value(line, "targetname:"),
                 *l = vcg_value(line, "label:");
            if (s && t) {
                int from = node_get(g, s);
                int to = strcmp(t, "__indirect_call") == 0 ? -1 : node_get(g, t);
                edge_add(g, from, to, l, 0);
            }
            free(s);
            free(t);
            free(l);
        }
        if (eol) *eol = save;
    }
    free(buf);
    return tu;
}

/* Cross-checks a .su file against the graph: every line must match a defined node with the
 * same location, name and frame, or the .ci and .su come from different compiles. */
static void parse_su(graph *g, const char *path)
{
    char *buf = read_file(path), *line;
    if (!buf) {
        fail("%s: cannot read %s (is the target compiled with -fstack-usage?)", g->what, path);
        return;
    }
    for (line = strtok(buf, "\n"); line; line = strtok(NULL, "\n")) {
        char *tab1 = strchr(line, '\t'), *tab2, *colon;
        long bytes;
        size_t i;
        int found = 0;
        if (!tab1) continue;
        *tab1 = '\0';
        tab2 = strchr(tab1 + 1, '\t');
        if (!tab2) continue;
        *tab2 = '\0';
        bytes = strtol(tab1 + 1, NULL, 10);
        colon = strrchr(line, ':');
        if (!colon) continue;
        *colon = '\0';
        for (i = 0; i < g->nn; i++) {
            node *n = &g->nodes[i];
            if (n->defined && !n->su_seen && strcmp(n->name, colon + 1) == 0 && strcmp(n->loc, line) == 0) {
                n->su_seen = 1;
                found = 1;
                if (n->bytes != bytes || strcmp(n->qual, tab2 + 1) != 0)
                    fail("%s: %s says %s %ld %s but the .ci says %ld %s: stale files?", g->what, path,
                         colon + 1, bytes, tab2 + 1, n->bytes, n->qual);
                break;
            }
        }
        if (!found) fail("%s: %s lists %s (%s) which no .ci defines: stale files?", g->what, path, colon + 1, line);
    }
    free(buf);
}

/* ---- address-taken functions, from -fdump-ipa-cgraph -------------------------------- */

typedef struct taken {
    char *tu;        /* main file of the translation unit */
    char *name;      /* function name */
    int cls;         /* CLS_PASSED and/or CLS_TABLE */
    char *referrers; /* for the report */
} taken;

static taken *g_taken;
static size_t g_ntaken;

typedef struct dsym {
    char *name;
    int is_var, is_fn;
    char *ref_addr; /* "uid uid ..." of referrers taking the address, space separated */
} dsym;

static void taken_add(const char *tu, const char *name, int cls, const char *referrer)
{
    size_t i;
    taken *t = NULL;
    for (i = 0; i < g_ntaken; i++)
        if (strcmp(g_taken[i].tu, tu) == 0 && strcmp(g_taken[i].name, name) == 0) t = &g_taken[i];
    if (!t) {
        g_taken = (taken *)xrealloc(g_taken, (g_ntaken + 1) * sizeof(taken));
        t = &g_taken[g_ntaken++];
        t->tu = xstrdup(tu);
        t->name = xstrdup(name);
        t->cls = 0;
        t->referrers = xstrdup("");
    }
    t->cls |= cls;
    if (!strstr(t->referrers, referrer)) {
        size_t len = strlen(t->referrers) + strlen(referrer) + 3;
        char *r = (char *)xrealloc(NULL, len);
        snprintf(r, len, "%s%s%s", t->referrers, t->referrers[0] ? ", " : "", referrer);
        free(t->referrers);
        t->referrers = r;
    }
}

static void parse_cgraph_dump(const char *path, const char *tu)
{
    char *buf = read_file(path), *line, *save = NULL;
    dsym *syms = NULL;
    size_t nsyms = 0, i;
    long cur = -1;
    if (!buf) return;
    for (line = strtok_r(buf, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        char *slash, *end;
        long uid;
        if (line[0] != ' ' && (slash = strchr(line, '/')) != NULL && slash > line &&
            !memchr(line, ' ', (size_t)(slash - line)) && (uid = strtol(slash + 1, &end, 10)) >= 0 &&
            end != slash + 1 && strncmp(end, " (", 2) == 0) {
            if ((size_t)uid >= nsyms) {
                size_t k = nsyms;
                nsyms = (size_t)uid + 1;
                syms = (dsym *)xrealloc(syms, nsyms * sizeof(dsym));
                for (; k < nsyms; k++) memset(&syms[k], 0, sizeof(dsym));
            }
            if (!syms[uid].name) syms[uid].name = xstrndup(line, (size_t)(slash - line));
            cur = uid;
        } else if (line[0] != ' ') {
            cur = -1;
        } else if (cur >= 0 && strncmp(line, "  Type: function", 16) == 0) {
            syms[cur].is_fn = 1;
        } else if (cur >= 0 && strncmp(line, "  Type: variable", 16) == 0) {
            syms[cur].is_var = 1;
        } else if (cur >= 0 && strncmp(line, "  Referring:", 12) == 0) {
            /* tokens "name/uid (kind)" */
            char *p = line + 12;
            while ((p = strchr(p, '/')) != NULL) {
                long ruid = strtol(p + 1, &end, 10);
                if (end != p + 1 && strncmp(end, " (addr)", 7) == 0) {
                    char tok[32];
                    size_t len = syms[cur].ref_addr ? strlen(syms[cur].ref_addr) : 0;
                    snprintf(tok, sizeof(tok), " %ld ", ruid);
                    if (!syms[cur].ref_addr || !strstr(syms[cur].ref_addr, tok)) {
                        syms[cur].ref_addr = (char *)xrealloc(syms[cur].ref_addr, len + strlen(tok) + 1);
                        strcpy(syms[cur].ref_addr + len, tok);
                    }
                }
                p = end;
            }
        }
    }
    for (i = 0; i < nsyms; i++) {
        char *p;
        if (!syms[i].is_fn || !syms[i].ref_addr) continue;
        for (p = syms[i].ref_addr; *p;) {
            char *end;
            long r = strtol(p, &end, 10);
            if (end == p) break;
            p = end;
            if (r >= 0 && (size_t)r < nsyms && syms[r].name) {
                char who[256];
                snprintf(who, sizeof(who), "%s %s", syms[r].is_var ? "table" : "function", syms[r].name);
                taken_add(tu, syms[i].name, syms[r].is_var ? CLS_TABLE : CLS_PASSED, who);
            }
        }
    }
    for (i = 0; i < nsyms; i++) {
        free(syms[i].name);
        free(syms[i].ref_addr);
    }
    free(syms);
    free(buf);
}

/* ---- loading a set of objects ------------------------------------------------------- */

typedef struct objset {
    graph g;
    char **tus; /* main file per object */
    size_t ntus;
    int dumps;  /* how many -fdump-ipa-cgraph files were read */
} objset;

static char *find_dump(const char *stem)
{
    const char *slash = strrchr(stem, '/');
    char *dir = slash ? xstrndup(stem, (size_t)(slash - stem)) : xstrdup(".");
    const char *base = slash ? slash + 1 : stem;
    size_t blen = strlen(base);
    DIR *d = opendir(dir);
    struct dirent *e;
    char *found = NULL;
    if (d) {
        while ((e = readdir(d)) != NULL) {
            size_t len = strlen(e->d_name);
            if (len > blen + 7 && strncmp(e->d_name, base, blen) == 0 && e->d_name[blen] == '.' &&
                strcmp(e->d_name + len - 7, ".cgraph") == 0) {
                size_t n = strlen(dir) + len + 2;
                found = (char *)xrealloc(NULL, n);
                snprintf(found, n, "%s/%s", dir, e->d_name);
                break;
            }
        }
        closedir(d);
    }
    free(dir);
    return found;
}

static void load_objects(objset *s, char **objs, size_t nobjs)
{
    size_t i;
    for (i = 0; i < nobjs; i++) {
        const char *o = objs[i];
        size_t len = strlen(o), stemlen = len;
        char *stem, *ci, *su, *dump, *tu;
        if (len > 2 && strcmp(o + len - 2, ".o") == 0)
            stemlen = len - 2;
        else if (len > 4 && strcmp(o + len - 4, ".obj") == 0)
            stemlen = len - 4;
        stem = xstrndup(o, stemlen);
        ci = (char *)xrealloc(NULL, stemlen + 4);
        su = (char *)xrealloc(NULL, stemlen + 4);
        snprintf(ci, stemlen + 4, "%s.ci", stem);
        snprintf(su, stemlen + 4, "%s.su", stem);
        tu = parse_ci(&s->g, ci);
        if (!tu) {
            fail("%s: cannot read %s: build the library with GCC >= 10 and -fcallgraph-info=su,da "
                 "(cmake/PnWarnings.cmake)", s->g.what, ci);
        } else {
            parse_su(&s->g, su);
            s->tus = (char **)xrealloc(s->tus, (s->ntus + 1) * sizeof(char *));
            s->tus[s->ntus++] = xstrdup(tu);
            dump = find_dump(stem);
            if (dump) {
                parse_cgraph_dump(dump, tu);
                s->dumps++;
                free(dump);
            }
            free(tu);
        }
        free(stem);
        free(ci);
        free(su);
    }
}

/* ---- checks ------------------------------------------------------------------------- */

typedef struct site {
    const char *name;
    int cls;
} site;

static const char *cls_name(int cls)
{
    switch (cls) {
    case CLS_PASSED: return "passed";
    case CLS_TABLE: return "table";
    case CLS_EXTERNAL: return "external";
    default: return "passed+table";
    }
}

/* The node of an address-taken function in g: static functions are "tu:name". */
static int taken_node(const graph *g, const taken *t)
{
    size_t len = strlen(t->tu) + strlen(t->name) + 2;
    char *title = (char *)xrealloc(NULL, len);
    int i;
    snprintf(title, len, "%s:%s", t->tu, t->name);
    i = node_find(g, title);
    free(title);
    if (i < 0) i = node_find(g, t->name);
    return i >= 0 && g->nodes[i].defined ? i : -1;
}

static void resolve_indirect(graph *g, const site *sites, size_t nsites, int verbose)
{
    size_t e, ne = g->ne, k, t;
    char list[512] = "";
    for (k = 0; k < nsites; k++) {
        strncat(list, k ? ", " : "", sizeof(list) - strlen(list) - 1);
        strncat(list, sites[k].name, sizeof(list) - strlen(list) - 1);
    }
    /* Pointer calls outside the sites. */
    for (e = 0; e < ne; e++) {
        const edge *ed = &g->edges[e];
        const node *src = &g->nodes[ed->from];
        if (ed->to != -1) continue;
        for (k = 0; k < nsites && strcmp(src->title, sites[k].name) != 0; k++) {
        }
        if (k == nsites)
            fail("%s: call through a function pointer in %s at %s; only these functions may call "
                 "through pointers (--site): %s", g->what, src->name, ed->loc, nsites ? list : "(none)");
    }
    /* Each site: its call locations once, then the functions they may reach. */
    for (k = 0; k < nsites; k++) {
        int from = node_find(g, sites[k].name), printed = 0, reached = 0;
        if (from < 0) continue;
        for (e = 0; e < ne; e++) {
            /* edge_add may move g->edges: keep the call site, not a pointer into the array. */
            const char *loc = g->edges[e].loc;
            if (g->edges[e].to != -1 || g->edges[e].from != from) continue;
            if (verbose && printed) printf(", %s", loc);
            if (verbose && !printed) printf("  pointer calls in %s at %s", sites[k].name, loc);
            printed = 1;
            for (t = 0; t < g_ntaken && sites[k].cls != CLS_EXTERNAL; t++) {
                int to;
                if (!(g_taken[t].cls & sites[k].cls)) continue;
                to = taken_node(g, &g_taken[t]);
                if (to >= 0) edge_add(g, from, to, loc, 1);
            }
        }
        if (!printed || !verbose) continue;
        printf("\n      may reach (%s):", cls_name(sites[k].cls));
        if (sites[k].cls == CLS_EXTERNAL) printf(" only the caller's callback (not library code)");
        for (t = 0; t < g_ntaken; t++)
            if ((g_taken[t].cls & sites[k].cls) && taken_node(g, &g_taken[t]) >= 0) {
                printf(" %s", g_taken[t].name);
                reached++;
            }
        if (sites[k].cls & CLS_PASSED)
            printf("%s the caller's parallel_for (not library code)", reached ? ", and" : "");
        printf("\n");
    }
}

static void build_adj(graph *g)
{
    size_t *count = (size_t *)xrealloc(NULL, g->nn * sizeof(size_t)), i;
    memset(count, 0, g->nn * sizeof(size_t));
    for (i = 0; i < g->ne; i++)
        if (g->edges[i].to >= 0) count[g->edges[i].from]++;
    g->adj = (int **)xrealloc(NULL, g->nn * sizeof(int *));
    for (i = 0; i < g->nn; i++) {
        g->adj[i] = (int *)xrealloc(NULL, (count[i] + 1) * sizeof(int));
        count[i] = 0;
    }
    for (i = 0; i < g->ne; i++) {
        const edge *e = &g->edges[i];
        if (e->to >= 0) g->adj[e->from][count[e->from]++] = (int)i;
    }
    for (i = 0; i < g->nn; i++) g->adj[i][count[i]] = -1;
    free(count);
}

/* DFS; a back edge closes a cycle, printed from its first function round to itself. */
static int *g_stack_nodes, *g_stack_edges;
static size_t g_sp;

static void dfs_cycles(graph *g, int v)
{
    int *a;
    node *n = &g->nodes[v];
    n->color = 1;
    g_stack_nodes[g_sp++] = v;
    for (a = g->adj[v]; *a >= 0; a++) {
        const edge *e = &g->edges[*a];
        node *w = &g->nodes[e->to];
        g_stack_edges[g_sp - 1] = *a;
        if (w->color == 1) {
            size_t k = g_sp;
            while (k > 0 && g_stack_nodes[k - 1] != e->to) k--;
            printf("FAIL: %s: recursion: ", g->what);
            for (k = k - 1; k < g_sp; k++) {
                const edge *ce = &g->edges[g_stack_edges[k]];
                printf("%s -(%s%s)-> ", g->nodes[g_stack_nodes[k]].name, ce->indirect ? "via pointer, " : "",
                       ce->loc);
            }
            printf("%s\n", w->name);
            g_failures++;
        } else if (w->color == 0) {
            dfs_cycles(g, e->to);
        }
    }
    g_sp--;
    n->color = 2;
}

static void check_structure(graph *g)
{
    size_t i;
    int bounded = 0;
    for (i = 0; i < g->nn; i++) {
        node *n = &g->nodes[i];
        if (!n->defined) continue;
        if (n->dyn_objects > 0)
            fail("%s: %s (%s) has %ld dynamically sized stack object(s) (VLA or alloca): %s", g->what, n->name,
                 n->loc, n->dyn_objects, n->dyn_desc ? n->dyn_desc : "");
        else if (strcmp(n->qual, "static") != 0 && strcmp(n->qual, "dynamic,bounded") != 0)
            fail("%s: %s (%s) has an unbounded '%s' stack frame", g->what, n->name, n->loc, n->qual);
        else if (strcmp(n->qual, "dynamic,bounded") == 0) {
            if (!bounded) printf("  frames that push outgoing call arguments ('dynamic,bounded', no dynamic objects; "
                                 "the size is their bound):\n");
            bounded = 1;
            printf("      %s (%s): %ld bytes\n", n->name, n->loc, n->bytes);
        }
        if (!n->su_seen) fail("%s: %s (%s) is in the .ci but not in the .su: stale files?", g->what, n->name, n->loc);
    }
    build_adj(g);
    g_stack_nodes = (int *)xrealloc(g_stack_nodes, (g->nn + 1) * sizeof(int));
    g_stack_edges = (int *)xrealloc(g_stack_edges, (g->nn + 1) * sizeof(int));
    g_sp = 0;
    for (i = 0; i < g->nn; i++) g->nodes[i].color = 0;
    for (i = 0; i < g->nn; i++)
        if (g->nodes[i].color == 0) dfs_cycles(g, (int)i);
}

/* Deepest path; the graph is acyclic when this runs. */
static long depth_of(graph *g, int v)
{
    node *n = &g->nodes[v];
    int *a;
    if (n->color == 3) return n->depth;
    n->depth = n->defined ? n->bytes : 0;
    n->next = -1;
    for (a = g->adj[v]; *a >= 0; a++) {
        const edge *e = &g->edges[*a];
        long d = depth_of(g, e->to) + (n->defined ? n->bytes : 0);
        if (d > n->depth) {
            n->depth = d;
            n->next = e->to;
            n->next_edge = *a;
        }
    }
    n->color = 3;
    return n->depth;
}

static void print_path(const graph *g, int v)
{
    while (v >= 0) {
        const node *n = &g->nodes[v];
        const edge *e = n->next_edge >= 0 && n->next >= 0 ? &g->edges[n->next_edge] : NULL;
        printf("      %6ld  %-24s %s%s\n", n->defined ? n->bytes : 0L, n->name, n->defined ? n->loc : "(not library code)",
               e && e->indirect ? "  [calls the next through a pointer]" : "");
        v = n->next;
    }
}

/* "a > b > *c": the path on one line, '*' marking a call through a pointer. */
static void print_path_compact(const graph *g, int v)
{
    printf("%s", g->nodes[v].name);
    while (g->nodes[v].next >= 0) {
        const node *n = &g->nodes[v];
        printf(" > %s%s", g->edges[n->next_edge].indirect ? "*" : "", g->nodes[n->next].name);
        v = n->next;
    }
}

/* Public functions: identifiers pn_* followed by '(' outside comments and preprocessor lines. */
static size_t public_functions(const char *path, char ***out)
{
    char *buf = read_file(path), *p, *q;
    char **names = NULL;
    size_t n = 0;
    int bol = 1;
    if (!buf) {
        fail("cannot read the public header %s", path);
        *out = NULL;
        return 0;
    }
    for (p = q = buf; *p;) {
        if (p[0] == '/' && p[1] == '*') {
            char *e = strstr(p + 2, "*/");
            p = e ? e + 2 : p + strlen(p);
            *q++ = ' ';
        } else if (p[0] == '/' && p[1] == '/') {
            while (*p && *p != '\n') p++;
        } else if (bol && (*p == ' ' || *p == '\t')) {
            *q++ = *p++;
        } else if (bol && *p == '#') {
            while (*p && (*p != '\n' || p[-1] == '\\')) p++;
        } else {
            bol = *p == '\n';
            *q++ = *p++;
        }
    }
    *q = '\0';
    for (p = buf; (p = strstr(p, "pn_")) != NULL;) {
        char *s = p;
        if (s > buf && (s[-1] == '_' || (s[-1] >= 'a' && s[-1] <= 'z') || (s[-1] >= 'A' && s[-1] <= 'Z') ||
                        (s[-1] >= '0' && s[-1] <= '9'))) {
            p += 3;
            continue;
        }
        p += 3;
        while (*p == '_' || (*p >= 'a' && *p <= 'z') || (*p >= '0' && *p <= '9')) p++;
        q = p;
        while (*q == ' ' || *q == '\t' || *q == '\n') q++;
        if (*q == '(') { /* "(*pn_task_fn)(" has ')' after the name: not matched */
            size_t k;
            char *name = xstrndup(s, (size_t)(p - s));
            for (k = 0; k < n && strcmp(names[k], name) != 0; k++) {
            }
            if (k == n) {
                names = (char **)xrealloc(names, (n + 1) * sizeof(char *));
                names[n++] = name;
            } else {
                free(name);
            }
        }
    }
    free(buf);
    *out = names;
    return n;
}

static void check_stack(graph *g, char **pub, size_t npub, long budget)
{
    size_t i;
    int worst = -1;
    printf("\n%s: worst-case stack of each public function (bytes; frames from -fstack-usage,\n"
           "    indirect calls resolved as above and marked *, the frames of the caller's callbacks\n"
           "    and of memcpy/memset not counted):\n",
           g->what);
    for (i = 0; i < npub; i++) {
        int v = node_find(g, pub[i]);
        if (v < 0 || !g->nodes[v].defined) {
            fail("%s: %s is declared in the public header but not defined in the library", g->what, pub[i]);
            continue;
        }
        depth_of(g, v);
        printf("  %6ld  ", g->nodes[v].depth);
        print_path_compact(g, v);
        printf("\n");
        if (worst < 0 || g->nodes[v].depth > g->nodes[worst].depth) worst = v;
    }
    if (worst < 0) return;
    printf("\n%s: deepest: %s, %ld of %ld bytes budget:\n", g->what, g->nodes[worst].name,
           g->nodes[worst].depth, budget);
    print_path(g, worst);
    if (g->nodes[worst].depth > budget)
        fail("%s: %s needs %ld bytes of stack, over the %ld byte budget (path above)", g->what,
             g->nodes[worst].name, g->nodes[worst].depth, budget);
}

/* ---- main --------------------------------------------------------------------------- */

/* Collects object paths from argv[i..] up to the next "--option"; each argument may itself
 * be a ';'-separated list (CMake's $<TARGET_OBJECTS:...>). */
static size_t collect(int argc, char **argv, int *i, char ***objs, size_t n)
{
    while (*i + 1 < argc && strncmp(argv[*i + 1], "--", 2) != 0) {
        char *arg = argv[++*i], *tok, *save = NULL;
        for (tok = strtok_r(arg, ";", &save); tok; tok = strtok_r(NULL, ";", &save)) {
            if (!*tok) continue;
            *objs = (char **)xrealloc(*objs, (n + 1) * sizeof(char *));
            (*objs)[n++] = tok;
        }
    }
    return n;
}

static int usage(void)
{
    fprintf(stderr, "usage: check_callgraph --header penumbra.h --budget BYTES [--site NAME=passed|table|external]...\n"
                    "                       [--source OBJ...] --objects OBJ... [--name TEXT]\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *header = NULL, *name = "library";
    long budget = 16384;
    site sites[16];
    size_t nsites = 0, nsrc = 0, nobj = 0, npub, i, t;
    char **src = NULL, **obj = NULL, **pub;
    objset S, O;
    int served = 0;
    int a;
    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--header") == 0 && a + 1 < argc) {
            header = argv[++a];
        } else if (strcmp(argv[a], "--budget") == 0 && a + 1 < argc) {
            budget = strtol(argv[++a], NULL, 10);
        } else if (strcmp(argv[a], "--name") == 0 && a + 1 < argc) {
            name = argv[++a];
        } else if (strcmp(argv[a], "--site") == 0 && a + 1 < argc) {
            char *eq = strchr(argv[++a], '=');
            if (!eq || nsites == 16) return usage();
            *eq = '\0';
            sites[nsites].name = argv[a];
            if (strcmp(eq + 1, "passed") == 0)
                sites[nsites].cls = CLS_PASSED;
            else if (strcmp(eq + 1, "table") == 0)
                sites[nsites].cls = CLS_TABLE;
            else if (strcmp(eq + 1, "external") == 0)
                sites[nsites].cls = CLS_EXTERNAL;
            else
                return usage();
            served |= sites[nsites].cls;
            nsites++;
        } else if (strcmp(argv[a], "--source") == 0) {
            nsrc = collect(argc, argv, &a, &src, nsrc);
        } else if (strcmp(argv[a], "--objects") == 0) {
            nobj = collect(argc, argv, &a, &obj, nobj);
        } else {
            return usage();
        }
    }
    if (!header || nobj == 0) return usage();

    memset(&S, 0, sizeof(S));
    memset(&O, 0, sizeof(O));
    S.g.what = "source (-O0)";
    O.g.what = name;
    if (nsrc) load_objects(&S, src, nsrc);
    load_objects(&O, obj, nobj);
    if (g_failures) {
        printf("check_callgraph: %d failure(s) loading the call graphs\n", g_failures);
        return 1;
    }
    if (S.dumps + O.dumps == 0)
        fail("no -fdump-ipa-cgraph output next to any object: without it the targets of pointer calls "
             "are unknown and the stack bound would be too low");

    printf("address-taken library functions (from -fdump-ipa-cgraph):\n");
    for (t = 0; t < g_ntaken; t++) {
        printf("  %-24s %-12s taken by %s\n", g_taken[t].name, cls_name(g_taken[t].cls), g_taken[t].referrers);
        if ((g_taken[t].cls & served) != g_taken[t].cls)
            fail("the address of %s (%s) is taken by %s, but no --site dispatches '%s' pointers: the analysis "
                 "cannot follow it", g_taken[t].name, g_taken[t].tu, g_taken[t].referrers,
                 cls_name(g_taken[t].cls & ~served));
    }

    if (nsrc) {
        printf("\n%s: %zu functions, %zu calls in %zu translation units\n", S.g.what, S.g.nn, S.g.ne, S.ntus);
        resolve_indirect(&S.g, sites, nsites, 1);
        check_structure(&S.g);
    }
    printf("\n%s: %zu functions, %zu calls in %zu translation units\n", O.g.what, O.g.nn, O.g.ne, O.ntus);
    resolve_indirect(&O.g, sites, nsites, nsrc == 0);
    check_structure(&O.g);

    npub = public_functions(header, &pub);
    if (npub == 0) fail("no public functions found in %s", header);
    if (g_failures == 0) check_stack(&O.g, pub, npub, budget);

    for (i = 0; i < npub; i++) free(pub[i]);
    free(pub);
    free(src);
    free(obj);
    if (g_failures) {
        printf("\ncheck_callgraph: %d failure(s)\n", g_failures);
        return 1;
    }
    printf("\ncheck_callgraph: OK (no recursion, no dynamic stack objects, indirect calls only at %zu "
           "documented sites, stack within %ld bytes)\n", nsites, budget);
    return 0;
}
