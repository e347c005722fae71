/* graph.c - a node graph: nodes (a primitive, or an operator tool, with their parameters),
 * edges carrying maps into input slots, one output node.  The graph is checked whole
 * before anything runs (ids, kinds, slots, cycles, dangling inputs, every parameter as the
 * single-primitive page checks it), each message naming its node.  It runs as chains: in
 * the shell export (and previews above FILES_SIDE) a node whose map feeds one node only
 * pipes into it (its standard input); any other map goes to a file in the temporary folder
 * (ID.exr in the export).  The export is the preview's words with those names, so it gives
 * the same bytes.  A file is named by a hash of the words that make it (its inputs named
 * the same way, so of its whole upstream), and kept for the next request: an edit reruns
 * only the nodes downstream of it. */
#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "io/json.h"
#include "textura.h"
#include "proto.h"

struct gnode {
    const char *id, *kind;
    const struct tex_primitive *prim;  /* a primitive, or ... */
    const struct kind *k;              /* ... an operator kind */
    const struct tex_json *params;     /* an object, or NULL */
    const char *operand;               /* k's operand word: the operation, the palette */
    char first[32];                    /* the operand's default, when not given */
    int in[MAX_SLOTS];                 /* the node feeding each slot, or -1 */
    int want, cons, pipe, depth;       /* upstream of the target; its consumers there; the
                                        * node it pipes into (-1: a file); its chain's length */
    unsigned long long key;            /* its file's: the hash of the words that make it */
};

struct graph {
    struct tex_json *doc;
    struct gnode n[MAX_NODES];
    int nn, out, target, size;
    int order[MAX_NODES]; /* topological: every node after those feeding it */
};

/* pl->err prefixed with the node: "node 'b' (blur): ..." */
static int at_node(struct pipeline *pl, const struct gnode *n)
{
    char msg[sizeof pl->err];
    memcpy(msg, pl->err, sizeof msg);
    snprintf(pl->err, sizeof pl->err, "node '%.40s' (%.40s): %.400s", n->id, n->kind, msg);
    return -1;
}

/* A parameter's value as the command line writes it: strings and numbers as written,
 * true and false as 1 and 0; NULL for anything else. */
static const char *value_text(const struct tex_json *v)
{
    if (v->type == TEX_JSON_STRING || v->type == TEX_JSON_NUMBER)
        return v->str;
    return v->type == TEX_JSON_TRUE ? "1" : v->type == TEX_JSON_FALSE ? "0" : NULL;
}

static const char *member_text(const struct tex_json *obj, const char *key)
{
    const struct tex_json *v = tex_json_get(obj, key);
    return v ? value_text(v) : NULL;
}

static int find_id(const struct graph *g, const char *id)
{
    for (int i = 0; id && i < g->nn; i++)
        if (!strcmp(g->n[i].id, id))
            return i;
    return -1;
}

static int slot_index(const struct gnode *n, const char *slot)
{
    for (int s = 0; n->k && s < MAX_SLOTS && n->k->slots[s]; s++)
        if (!strcmp(n->k->slots[s], slot))
            return s;
    return -1;
}

/* The slots a node must have fed, and the most it takes: t_op's by its operation. */
static void arity(const struct gnode *n, int *need, int *most)
{
    *need = n->k ? n->k->needs : 0;
    *most = 0;
    for (int s = 0; n->k && s < MAX_SLOTS && n->k->slots[s]; s++)
        *most = s + 1;
    if (n->k && !strcmp(n->k->name, "op"))
        *need = *most = tex_op_arity((enum tex_op)tex_op_find(n->operand));
}

/* The operand word: one of the kind's choices, or a palette installed or saved. */
static int check_operand(struct pipeline *pl, struct gnode *n)
{
    const char *v = member_text(n->params, n->k->operand);
    char path[PATH_MAX];
    size_t len;
    if (!v) { /* the default: the first choice, or marble */
        const char *c = n->k->choices ? n->k->choices : "marble";
        snprintf(n->first, sizeof n->first, "%.*s", (int)strcspn(c, "|"), c);
        v = n->first;
    }
    n->operand = v;
    if (n->k->choices) {
        len = strlen(v);
        for (const char *c = n->k->choices; *c; c += strcspn(c, "|"), c += *c == '|')
            if (strcspn(c, "|") == len && !strncmp(c, v, len))
                return 0;
        return fail(pl, "%s must be one of %s (got '%.40s')", n->k->operand, n->k->choices, v);
    }
    if (is_saved_palette(v) || (is_name(v) && tex_palette_find(v, path, sizeof path) == 0))
        return 0;
    return fail(pl, "unknown palette '%.40s'", v);
}

/* The graph's nodes: ids unique names, kinds known, params objects, operands valid. */
static int load_nodes(struct pipeline *pl, struct graph *g, const struct tex_json *nodes)
{
    if (!nodes || nodes->type != TEX_JSON_ARRAY || nodes->n < 1)
        return fail(pl, "the graph has no \"nodes\" (an array of objects)");
    if (nodes->n > MAX_NODES)
        return fail(pl, "too many nodes (%d; at most %d)", nodes->n, MAX_NODES);
    for (int i = 0; i < nodes->n; i++) {
        struct gnode *n = &g->n[g->nn];
        const struct tex_json *p = &nodes->item[i];
        n->id = member_text(p, "id");
        n->kind = member_text(p, "kind");
        n->params = tex_json_get(p, "params");
        for (int s = 0; s < MAX_SLOTS; s++)
            n->in[s] = -1;
        if (!n->id || !is_name(n->id))
            return fail(pl, "node %d: its id must be a name of a-z, 0-9, '_' and '-' (got "
                        "'%.40s')", i + 1, n->id ? n->id : "");
        if (find_id(g, n->id) >= 0)
            return fail(pl, "node '%s' is there twice", n->id);
        g->nn++;
        if (!n->kind || !is_name(n->kind))
            return fail(pl, "node '%s' has no kind", n->id);
        if (n->params && n->params->type != TEX_JSON_OBJECT)
            return fail(pl, "node '%s': its params must be an object", n->id);
        if (!(n->k = kind_find(n->kind)) && !(n->prim = tex_procs_find(proto.procs, n->kind)))
            return fail(pl, "node '%s': unknown kind '%s' (a primitive, or one of op, palette, "
                        "filter, remap, xform, warp, cascade, tile)", n->id, n->kind);
        if (n->k && n->k->operand && check_operand(pl, n) < 0)
            return at_node(pl, n);
    }
    return 0;
}

/* The graph's edges: each from a node into a free slot of an operator node. */
static int load_edges(struct pipeline *pl, struct graph *g, const struct tex_json *edges)
{
    if (edges && edges->type != TEX_JSON_ARRAY)
        return fail(pl, "the graph's \"edges\" must be an array");
    for (int i = 0; edges && i < edges->n; i++) {
        const char *from = member_text(&edges->item[i], "from");
        const char *to = member_text(&edges->item[i], "to");
        const char *slot = member_text(&edges->item[i], "slot");
        int a = find_id(g, from), b = find_id(g, to), s;
        if (a < 0 || b < 0)
            return fail(pl, "edge %d: no node '%.40s'", i + 1, a < 0 ? (from ? from : "")
                                                                      : (to ? to : ""));
        if (!g->n[b].k)
            return fail(pl, "node '%s' (%s) takes no input (edge from '%s')", g->n[b].id,
                        g->n[b].kind, g->n[a].id);
        if (!slot || (s = slot_index(&g->n[b], slot)) < 0)
            return fail(pl, "node '%s' (%s) has no input '%.20s' (edge from '%s')", g->n[b].id,
                        g->n[b].kind, slot ? slot : "", g->n[a].id);
        if (g->n[b].in[s] >= 0)
            return fail(pl, "node '%s': input '%s' is fed twice", g->n[b].id, slot);
        g->n[b].in[s] = a;
    }
    return 0;
}

/* g->order, every node after those feeding it; a cycle found as the nodes left over. */
static int graph_order(struct pipeline *pl, struct graph *g)
{
    int done[MAX_NODES] = {0}, k = 0;
    for (int progress = 1; progress;) {
        progress = 0;
        for (int i = 0; i < g->nn; i++) {
            int ready = !done[i];
            for (int s = 0; ready && s < MAX_SLOTS; s++)
                ready = g->n[i].in[s] < 0 || done[g->n[i].in[s]];
            if (ready) {
                done[i] = 1;
                g->order[k++] = i;
                progress = 1;
            }
        }
    }
    for (int i = 0; i < g->nn; i++)
        if (!done[i]) { /* every node left has an input left: going up them ends on the cycle */
            for (int step = 0; step < g->nn; step++)
                for (int s = 0; s < MAX_SLOTS; s++)
                    if (g->n[i].in[s] >= 0 && !done[g->n[i].in[s]]) {
                        i = g->n[i].in[s];
                        break;
                    }
            return fail(pl, "the graph has a cycle through node '%s'", g->n[i].id);
        }
    return 0;
}

/* The graph read from its JSON and checked: nodes, edges, the output, no cycle. */
static int graph_load(struct pipeline *pl, struct graph *g, const struct tex_json *doc)
{
    const struct tex_json *out;
    if (load_nodes(pl, g, tex_json_get(doc, "nodes")) < 0 ||
        load_edges(pl, g, tex_json_get(doc, "edges")) < 0)
        return -1;
    out = tex_json_get(doc, "output");
    g->out = out ? find_id(g, value_text(out)) : g->nn == 1 ? 0 : -1;
    if (g->out < 0)
        return fail(pl, "the graph's \"output\" must name one of its nodes");
    return graph_order(pl, g);
}

static int graph_read(struct pipeline *pl, struct graph *g, const char *text)
{
    char err[128];
    if (!text)
        return fail(pl, "no graph");
    if (strlen(text) > MAX_GRAPH)
        return fail(pl, "the graph is longer than %d bytes", MAX_GRAPH);
    if (!(g->doc = tex_json_parse(text, strlen(text), err, sizeof err)))
        return fail(pl, "the graph is not JSON: %s", err);
    return graph_load(pl, g, g->doc);
}

/* A row of an operator tool, as it printed it: the value checked by its type and range
 * (the tool checks the rest: it is one word, no shell reads it). */
static int kind_param(struct pipeline *pl, const struct tex_json *row, const char *key,
                      const char *v)
{
    const char *type = member_text(row, "type"), *meta = member_text(row, "meta");
    const char *choices = member_text(row, "choices");
    type = type ? type : "";
    choices = choices ? choices : "";
    char name[72];
    double x, lo = 0, hi = 0;
    snprintf(name, sizeof name, "%s", key);
    for (char *c = name; *c; c++)
        if (*c == '_')
            *c = '-';
    if (plain_value(pl, key, v) < 0)
        return -1;
    if (!strcmp(type, "flag")) {
        if (strcmp(v, "0") && strcmp(v, "1"))
            return fail(pl, "--%s is 0 or 1 (got '%.20s')", name, v);
        return !strcmp(v, "1") ? arg(pl, word(pl, "--%s", name)) : 0;
    }
    if (!strcmp(type, "int") || !strcmp(type, "real")) {
        tex_parse_real(member_text(row, "min"), &lo);
        tex_parse_real(member_text(row, "max"), &hi);
        if (tex_parse_real(v, &x) < 0 || x < lo || x > hi || (type[0] == 'i' && x != (long)x))
            return fail(pl, "--%s must be %s %g..%g (got '%.20s')", name,
                        type[0] == 'i' ? "a whole number" : "a number", lo, hi, v);
    }
    if (!strcmp(type, "enum")) {
        size_t len = strlen(v);
        const char *c = choices;
        for (; *c; c += strcspn(c, "|"), c += *c == '|')
            if (strcspn(c, "|") == len && !strncmp(c, v, len))
                break;
        if (!*c)
            return fail(pl, "--%s must be one of %s (got '%.20s')", name, choices, v);
    }
    if (meta && !strcmp(meta, "FILE")) {
        const char *w = inside(pl, name, v);
        return w ? arg(pl, w) : -1;
    }
    return arg(pl, word(pl, "--%s=%s", name, v));
}

/* The name of node i's map file: ID.exr in the export, else its key's in the temporary
 * folder (tmp: the name it is written under, then renamed). */
static const char *map_path(struct pipeline *pl, const struct graph *g, int i, int export)
{
    if (export)
        return word(pl, "%s.exr", g->n[i].id);
    return word(pl, "%s/g.%016llx.exr", proto.tmpdir, g->n[i].key);
}

/* The hash of the words of pl's stages (FNV-1a), and of the time, size and inode of each
 * file a word names but the temporary folder's (a palette saved again, --defs edited). */
static unsigned long long words_key(const struct pipeline *pl)
{
    unsigned long long h = 14695981039346656037ull;
    size_t n = strlen(proto.tmpdir);
    for (int i = 0; i < pl->n; i++)
        for (int k = 0; k <= pl->st[i].n; k++) {
            const char *w = k < pl->st[i].n ? pl->st[i].argv[k] : "|", *eq = strchr(w, '=');
            const char *path = w[0] == '/' ? w : eq && eq[1] == '/' ? eq + 1 : NULL;
            struct stat st;
            for (const char *c = w; c == w || c[-1]; c++)
                h = (h ^ (unsigned char)*c) * 1099511628211ull;
            if (path && strncmp(path, proto.tmpdir, n) && stat(path, &st) == 0) {
                long long f[4] = {st.st_mtim.tv_sec, st.st_mtim.tv_nsec, st.st_size,
                                  (long long)st.st_ino};
                for (size_t b = 0; b < sizeof f; b++)
                    h = (h ^ ((const unsigned char *)f)[b]) * 1099511628211ull;
            }
        }
    return h;
}

/* A primitive node's stage: its tool (t_expr for a composed one), size and parameters. */
static int prim_stage(struct pipeline *pl, const struct graph *g, const struct gnode *n)
{
    const struct tex_json *ps = n->params;
    if (tex_primitive_get(n->prim->name) ? stage(pl, word(pl, "t_%s", n->prim->name))
                                         : stage(pl, "t_expr") | arg(pl, "--defs") |
                                               arg(pl, proto.defs) | arg(pl, n->prim->name))
        return -1;
    if (arg(pl, word(pl, "-s%d", g->size)) < 0)
        return -1;
    for (int m = 0; ps && m < ps->n; m++) {
        const char *key = ps->item[m].key, *v = value_text(&ps->item[m]);
        const struct tex_param *row;
        double x;
        if (!v)
            return fail(pl, "%s: a value is a string or a number", key);
        if (!strcmp(key, "seed")) {
            if (tex_parse_real(v, &x) < 0 || x != (int)x || x < 0 || x > TEX_SEED_MAX)
                return fail(pl, "seed must be 0..%d (got '%.20s')", TEX_SEED_MAX, v);
            if (arg(pl, word(pl, "-S%d", (int)x)) < 0)
                return -1;
        } else if (!strcmp(key, "tile") || !strcmp(key, "ids")) { /* common flags */
            if (strcmp(v, "0") && strcmp(v, "1"))
                return fail(pl, "%s is 0 or 1 (got '%.20s')", key, v);
            if (!strcmp(v, "1") && arg(pl, word(pl, "--%s", key)) < 0)
                return -1;
        } else if (!(row = tex_param_find(n->prim->params, key))) {
            return fail(pl, "%s has no parameter '%.40s'", n->prim->name, key);
        } else if (param_arg(pl, row, v) < 0) {
            return -1;
        }
    }
    return 0;
}

/* t_op's constant operand for a slot no node feeds: a number or r,g,b[,a]. */
static int op_constant(struct pipeline *pl, const char *slot, const char *c)
{
    char buf[128], *save = NULL;
    int ok = strlen(c) < sizeof buf;
    double x;
    snprintf(buf, sizeof buf, "%s", c);
    for (char *t = strtok_r(buf, ",", &save); t && ok; t = strtok_r(NULL, ",", &save))
        ok = tex_parse_real(t, &x) == 0;
    return ok ? 0 : fail(pl, "input '%s' is a node's map or a constant such as 0.5 or 1,0,0 "
                         "(got '%.20s')", slot, c);
}

/* An operator node's inputs, in slot order: standard input where one pipes in, else the
 * map's file, or a constant where t_op's params give one. */
static int op_inputs(struct pipeline *pl, const struct graph *g, int i, int export)
{
    const struct gnode *n = &g->n[i];
    int need, most, fed = 0;
    arity(n, &need, &most);
    for (int s = 0; s < MAX_SLOTS && n->k->slots[s]; s++) {
        const char *slot = n->k->slots[s], *w, *c = NULL;
        int src = n->in[s];
        if (src < 0 && !strcmp(n->k->name, "op") && (c = member_text(n->params, slot)) &&
            op_constant(pl, slot, c) < 0)
            return -1;
        if (src < 0 && !c) {
            if (s < need)
                return fail(pl, "input '%s' is not connected", slot);
            continue;
        }
        if (s >= most)
            return fail(pl, "%s takes %d input%s (input '%s' is connected)", n->operand, most,
                        most > 1 ? "s" : "", slot);
        w = c ? word(pl, "%s", c) : g->n[src].pipe == i ? "-" : map_path(pl, g, src, export);
        if (!strcmp(n->k->name, "cascade") && s > 0)
            w = w ? word(pl, "%s=%s", slot, w) : NULL;
        if (arg(pl, w) < 0)
            return -1;
        fed++;
    }
    if (fed < need) /* cascade: the region-id map and at least one region */
        return fail(pl, "needs %d inputs connected", need);
    return 0;
}

/* An operator node's parameters but its operand and t_op's constants, by its tool's rows. */
static int op_params(struct pipeline *pl, const struct gnode *n)
{
    const struct tex_json *ps = n->params;
    for (int m = 0; ps && m < ps->n; m++) {
        const char *key = ps->item[m].key, *v = value_text(&ps->item[m]);
        const struct tex_json *row;
        if ((n->k->operand && !strcmp(key, n->k->operand)) ||
            (!strcmp(n->k->name, "op") && slot_index(n, key) >= 0))
            continue;
        if (!v)
            return fail(pl, "%s: a value is a string or a number", key);
        if (!(row = kind_row(n->k, key)))
            return fail(pl, "%s has no parameter '%.40s'", n->k->tool, key);
        if (kind_param(pl, row, key, v) < 0)
            return -1;
    }
    return 0;
}

/* Node i's stage: its tool, operand, inputs, parameters and size; a message names it. */
static int node_stage(struct pipeline *pl, const struct graph *g, int i, int export)
{
    const struct gnode *n = &g->n[i];
    if (n->prim)
        return prim_stage(pl, g, n) < 0 ? at_node(pl, n) : 0;
    if (stage(pl, n->k->tool) < 0 ||
        (n->k->operand && arg(pl, is_saved_palette(n->operand)
                                      ? word(pl, "%s/%s", proto.dir, n->operand)
                                      : word(pl, "%s", n->operand)) < 0) ||
        op_inputs(pl, g, i, export) < 0 || op_params(pl, n) < 0 ||
        (n->k->sized && arg(pl, word(pl, "-s%d", g->size)) < 0))
        return at_node(pl, n);
    return 0;
}

/* The nodes upstream of target, checked (inputs fed, every parameter), and the chains:
 * with pipes, a node whose map feeds one node there pipes into it, in its first such slot;
 * without, every map is a file of its own. */
static int graph_select(struct pipeline *pl, struct graph *g, int target, int pipes)
{
    g->target = target;
    g->n[target].want = 1;
    for (int k = g->nn - 1; k >= 0; k--) { /* consumers come after what feeds them */
        struct gnode *n = &g->n[g->order[k]];
        for (int s = 0; n->want && s < MAX_SLOTS; s++)
            if (n->in[s] >= 0) {
                g->n[n->in[s]].want = 1;
                g->n[n->in[s]].cons++;
            }
    }
    for (int k = 0; k < g->nn; k++) {
        int i = g->order[k], piped = 0;
        struct gnode *n = &g->n[i];
        n->pipe = -1;
        n->depth = 1;
        for (int s = 0; n->want && s < MAX_SLOTS; s++) {
            int src = n->in[s];
            if (pipes && src >= 0 && !piped && g->n[src].cons == 1 &&
                g->n[src].depth < MAX_STAGES) {
                g->n[src].pipe = i;
                n->depth = g->n[src].depth + 1;
                piped = 1;
            }
        }
    }
    for (int k = 0; k < g->nn; k++) { /* every word checked before anything runs */
        if (!g->n[g->order[k]].want)
            continue;
        pl->n = 0;
        pl->used = 0;
        if (node_stage(pl, g, g->order[k], 0) < 0)
            return -1;
    }
    return 0;
}

/* The chain ending at node tail (a file's or the target's) as the stages of pl, with the
 * map's destination: the target's by last (its words), a file otherwise. */
static int chain(struct pipeline *pl, struct graph *g, int tail, int export, const char *last)
{
    int nodes[MAX_STAGES], k = 0;
    for (int i = tail; i >= 0 && k < MAX_STAGES;) {
        int up = -1;
        nodes[k++] = i;
        for (int s = 0; s < MAX_SLOTS; s++)
            if (g->n[i].in[s] >= 0 && g->n[g->n[i].in[s]].pipe == i)
                up = g->n[i].in[s];
        i = up;
    }
    pl->n = 0;
    pl->used = 0;
    pl->err[0] = 0;
    while (k--)
        if (node_stage(pl, g, nodes[k], export) < 0)
            return -1;
    if (tail == g->target)
        return last ? arg(pl, word(pl, "%s", last)) : 0;
    /* a file read back at once: zip would cost more than it saves */
    if (arg(pl, "--compression=none") < 0 || arg(pl, "-o") < 0)
        return -1;
    if (export)
        return arg(pl, map_path(pl, g, tail, 1));
    g->n[tail].key = words_key(pl);
    return arg(pl, word(pl, "%s/g.%016llx.%lx.exr", proto.tmpdir, g->n[tail].key,
                        (unsigned long)pthread_self()));
}

/* Name the node a tool's message came from ("t_op: error: ..."), else the chain's tail. */
static void blame(struct pipeline *pl, const struct graph *g, int tail)
{
    int who = tail;
    for (int i = 0; i < g->nn; i++) {
        const char *tool = g->n[i].prim ? g->n[i].prim->name : g->n[i].k->tool + 2;
        size_t len = strlen(tool);
        if (g->n[i].want && !strncmp(pl->err, "t_", 2) && !strncmp(pl->err + 2, tool, len) &&
            pl->err[2 + len] == ':') {
            int j = i; /* in this chain? */
            while (j >= 0 && j != tail)
                j = g->n[j].pipe;
            if (j == tail)
                who = i;
        }
    }
    at_node(pl, &g->n[who]);
}

/* At most KEEP files and KEEP_BYTES kept: the oldest go, but none used within RUN_SECONDS
 * (a request running may still read it). */
#define KEEP 64
#define KEEP_BYTES ((long long)256 << 20)
static void evict(void)
{
    struct { char name[64]; time_t t; long long size; } f[256];
    int n = 0;
    long long bytes = 0;
    DIR *d = opendir(proto.tmpdir);
    struct dirent *e;
    struct stat st;
    time_t now = time(NULL);
    while (d && (e = readdir(d)) && n < 256)
        if (!strncmp(e->d_name, "g.", 2) && strlen(e->d_name) == 22 &&
            fstatat(dirfd(d), e->d_name, &st, 0) == 0) {
            snprintf(f[n].name, sizeof f[n].name, "%.63s", e->d_name);
            f[n].t = st.st_mtime;
            bytes += f[n++].size = st.st_size;
        }
    for (int left = n; left > KEEP || bytes > KEEP_BYTES; left--) {
        int old = -1;
        for (int i = 0; i < n; i++)
            if (f[i].name[0] && f[i].t < now - RUN_SECONDS && (old < 0 || f[i].t < f[old].t))
                old = i;
        if (old < 0)
            break;
        unlinkat(dirfd(d), f[old].name, 0);
        f[old].name[0] = 0;
        bytes -= f[old].size;
    }
    if (d)
        closedir(d);
}

/* Run the chains in order, each file made unless kept from an earlier request: the
 * target's last writes its map by last ("--format=png" to out, or "-oFILE"); the status
 * (0, 1 runtime, 2 usage). */
static int graph_run(struct pipeline *pl, struct graph *g, const char *last, struct tex_str *out)
{
    int rc = 0;
    for (int k = 0; k < g->nn && !rc; k++) {
        int i = g->order[k];
        struct tex_str scratch = {0};
        char made[PATH_MAX + 64], kept[PATH_MAX + 64];
        if (!g->n[i].want || g->n[i].pipe >= 0)
            continue;
        if (chain(pl, g, i, 0, last) < 0)
            return 2;
        if (i != g->target) {
            snprintf(made, sizeof made, "%s", pl->st[pl->n - 1].argv[pl->st[pl->n - 1].n - 1]);
            snprintf(kept, sizeof kept, "%s/g.%016llx.exr", proto.tmpdir, g->n[i].key);
            if (utimensat(AT_FDCWD, kept, NULL, 0) == 0) /* kept: used now */
                continue;
        }
        rc = run(pl, i == g->target ? out : &scratch);
        free(scratch.s);
        if (rc)
            blame(pl, g, i);
        if (i != g->target && (rc || rename(made, kept) < 0))
            unlink(made);
    }
    evict();
    return rc;
}

/* Up to this side a preview keeps every node's map as a file: it costs what a pipe does
 * (tests/bench/proto) and spares rerunning the nodes above an edit; bigger maps pipe, or a
 * few nodes would fill the kept files' KEEP_BYTES. */
#define FILES_SIDE 1024

/* The graph of a request, its target (node=ID, else the output) selected and checked: an
 * export pipes where a map feeds one node, a preview as FILES_SIDE says. */
static int request_graph(struct MHD_Connection *c, struct pipeline *pl, struct graph *g,
                         int export)
{
    const char *node = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "node");
    int t;
    if ((g->size = get_size(c, pl, 256)) < 0 ||
        graph_read(pl, g, MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "graph")) < 0)
        return -1;
    if ((t = node ? find_id(g, node) : g->out) < 0)
        return fail(pl, "no node '%.40s' in the graph", node);
    return graph_select(pl, g, t, export || g->size > FILES_SIDE);
}

/* A value for a t_compose script: a number, a name, else a quoted string. */
static void compose_value(struct tex_str *b, const char *v)
{
    double x;
    if (tex_parse_real(v, &x) == 0 || is_name(v)) {
        tex_str_add(b, "%s", v);
        return;
    }
    tex_str_add(b, "\"");
    for (; *v; v++)
        tex_str_add(b, "%s%c", *v == '"' || *v == '\\' ? "\\" : "", *v);
    tex_str_add(b, "\"");
}

/* Node i as a t_compose image definition, or -1 naming what it cannot say. */
static int compose_node(struct pipeline *pl, const struct graph *g, int i, struct tex_str *b)
{
    static const char *const infix[][2] = {{"add", "+"}, {"sub", "-"}, {"mul", "*"},
        {"min", "min"}, {"max", "max"}, {"over", "over"}, {"under", "under"}, {"and", "and"},
        {"or", "or"}, {"xor", "xor"}};
    const struct gnode *n = &g->n[i];
    const struct tex_json *ps = n->params;
    const char *in[MAX_SLOTS] = {0};
    for (int s = 0; s < MAX_SLOTS; s++)
        in[s] = n->in[s] >= 0 ? g->n[n->in[s]].id : n->k ? member_text(ps, n->k->slots[s] ?
                                                           n->k->slots[s] : "") : NULL;
    tex_str_add(b, "  %s = ", n->id);
    if (n->prim) {
        int first = 1;
        tex_str_add(b, "%s(", n->prim->name);
        for (int m = 0; ps && m < ps->n; m++) {
            tex_str_add(b, "%s%s = ", first ? "" : ", ", ps->item[m].key);
            compose_value(b, value_text(&ps->item[m]));
            first = 0;
        }
        if (!tex_json_get(ps, "seed")) /* the tools' default, where t_compose's is its own */
            tex_str_add(b, "%sseed = 1", first ? "" : ", ");
        tex_str_add(b, ") %d by %d;\n", g->size, g->size);
        return 0;
    }
    const char *kn = n->k->name;
    int extra = 0; /* parameters other than those said */
    for (int m = 0; ps && m < ps->n; m++)
        extra += !(n->k->operand && !strcmp(ps->item[m].key, n->k->operand)) &&
                 slot_index(n, ps->item[m].key) < 0;
    for (int s = 0; s < MAX_SLOTS; s++) /* t_compose writes a colour with blanks */
        extra += n->in[s] < 0 && in[s] && strchr(in[s], ',');
    if (!strcmp(kn, "op")) {
        const char *t = member_text(ps, "threshold");
        for (size_t k = 0; k < sizeof infix / sizeof *infix && !extra; k++)
            if (!strcmp(n->operand, infix[k][0]))
                return tex_str_add(b, "%s %s %s;\n", in[0], infix[k][1], in[1]);
        if (!strcmp(n->operand, "mix") && !extra)
            return tex_str_add(b, "mix %s, %s by %s;\n", in[0], in[1], in[2]);
        if (!strcmp(n->operand, "abs") && !extra)
            return tex_str_add(b, "abs(%s);\n", in[0]);
        if (!strcmp(n->operand, "invert") && !extra)
            return tex_str_add(b, "filter invert %s;\n", in[0]);
        if (!strcmp(n->operand, "threshold") && extra == (t != NULL))
            return tex_str_add(b, "filter threshold %s by %s;\n", in[0], t ? t : "0.5");
    } else if (!strcmp(kn, "filter") && strcmp(n->operand, "blur")) {
        /* blur is the script's own (clamped edges), not t_filter's */
        tex_str_add(b, "filter %s %s", n->operand, in[0]);
        for (int m = 0; ps && m < ps->n; m++)
            if (strcmp(ps->item[m].key, "op")) {
                tex_str_add(b, " %s ", ps->item[m].key);
                compose_value(b, value_text(&ps->item[m]));
            }
        return tex_str_add(b, ";\n");
    } else if (!strcmp(kn, "warp")) {
        const char *a = member_text(ps, "displacement"), *iso = member_text(ps, "isotropic");
        if (extra == (a != NULL) + (iso != NULL))
            return tex_str_add(b, "warp %s by %s amount %s%s;\n", in[0], in[1], a ? a : "0.1",
                               iso && !strcmp(iso, "1") ? " isotropic" : "");
    }
    b->n -= strlen(n->id) + 5; /* the "  ID = " written */
    b->s[b->n] = 0;
    return fail(pl, "node '%s' (%s%s%s) has no t_compose equivalent: export the graph as a "
                "shell script", n->id, kn, n->operand ? " " : "", n->operand ? n->operand : "");
}

int graph_export(struct MHD_Connection *c, struct pipeline *pl, const char *form,
                 const char *map, struct tex_str *out)
{
    struct graph *g = calloc(1, sizeof *g);
    int rc = -1;
    form = form ? form : "sh";
    if (!g)
        return fail(pl, "out of memory");
    if (request_graph(c, pl, g, 1) < 0)
        goto done;
    if (!strcmp(form, "sh") || !strcmp(form, "apply")) {
        int apply = form[0] == 'a';
        const char *fn = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "apply");
        const char *k = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "strength");
        struct tex_str sh = {0};
        map = map ? map : apply ? "graph.exr" : "graph.png";
        if (save_name(pl, map, map_exts) < 0)
            goto done;
        tex_str_add(&sh, "%s# t_proto's graph: node '%s' at %d x %d into %s; a map that feeds "
                    "several nodes is a file ID.exr\n", apply ? "" : "#!/bin/sh\nset -e\n",
                    g->n[g->target].id, g->size, g->size, map);
        for (int k2 = 0; k2 < g->nn; k2++) {
            int i = g->order[k2];
            char last[128];
            if (!g->n[i].want || g->n[i].pipe >= 0)
                continue;
            snprintf(last, sizeof last, "--format=%s", strrchr(map, '.') + 1);
            if (chain(pl, g, i, 1, last) < 0)
                goto done_sh;
            tex_str_add(&sh, apply ? "#   " : "");
            cmdline(pl, &sh);
            tex_str_add(&sh, i == g->target ? " > %s\n" : "\n", map);
        }
        if (apply) { /* the standard scene, its map the file the script makes */
            tex_str_add(out, "# the map: the shell export of this graph, run in this folder, "
                        "makes %s:\n%s", map, sh.s);
            rc = scene_text(pl, out, fn, k, map);
        } else {
            tex_str_bytes(out, sh.s, sh.n);
            rc = 0;
        }
    done_sh:
        free(sh.s);
    } else if (!strcmp(form, "compose")) {
        tex_str_add(out, "# t_proto's graph: node '%s' at %d x %d\ntessellation %s;\n"
                    "size %d by %d;\n", g->n[g->target].id, g->size, g->size,
                    g->n[g->target].id[0] >= 'a' ? g->n[g->target].id : "graph", g->size,
                    g->size);
        if (proto.defs) {
            tex_str_add(out, "primitives ");
            compose_value(out, proto.defs);
            tex_str_add(out, ";\n");
        }
        tex_str_add(out, "images\n");
        rc = 0;
        for (int k2 = 0; k2 < g->nn && !rc; k2++)
            if (g->n[g->order[k2]].want)
                rc = compose_node(pl, g, g->order[k2], out);
        tex_str_add(out, "end images;\nbuilt with\n  (1,1) %s;\nend tessellation;\n",
                    g->n[g->target].id);
    } else {
        fail(pl, "the export form must be sh, compose or apply (got '%.20s')", form);
    }
done:
    tex_json_free(g->doc);
    free(g);
    return rc;
}

unsigned api_graph(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out,
                   const char **type)
{
    const char *what = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "what");
    what = what ? what : "preview";
    if (!strcmp(what, "sh") || !strcmp(what, "compose") || !strcmp(what, "apply"))
        return graph_export(c, pl, what,
                            MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "map"),
                            out) < 0 ? 400 : 200;
    if (strcmp(what, "preview") && strcmp(what, "scene"))
        return fail(pl, "what must be preview, scene, sh, compose or apply (got '%.20s')", what),
               400;
    struct graph *g = calloc(1, sizeof *g);
    char map[PATH_MAX + 64], last[PATH_MAX + 80];
    int r;
    if (!g)
        return fail(pl, "out of memory"), 500;
    snprintf(map, sizeof map, "%s/map.%lx.exr", proto.tmpdir, (unsigned long)pthread_self());
    snprintf(last, sizeof last, what[0] == 's' ? "-o%s" : "--format=png", map);
    r = request_graph(c, pl, g, 0) < 0 ? 2 : graph_run(pl, g, last, out);
    if (!r && what[0] == 's') {
        const char *fn = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "apply");
        const char *k = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "strength");
        free(out->s);
        *out = (struct tex_str){0};
        r = scene_stage(pl, fn, k, map) < 0 ? 2 : run(pl, out);
    }
    tex_json_free(g->doc);
    free(g);
    *type = r == 0 ? "image/png" : *type;
    return r == 0 ? 200 : r == 2 ? 400 : 500;
}

int project_check(struct pipeline *pl, const char *text)
{
    char err[128];
    struct tex_json *doc = tex_json_parse(text, strlen(text), err, sizeof err);
    const struct tex_json *gr = tex_json_get(doc, "graph"), *size = tex_json_get(doc, "size");
    struct graph *g = calloc(1, sizeof *g);
    double s = 256;
    int rc = 0;
    if (!g)
        rc = fail(pl, "out of memory");
    else if (!doc || doc->type != TEX_JSON_OBJECT)
        rc = fail(pl, "a project is a JSON object%s%s", doc ? "" : ": ", doc ? "" : err);
    else if (size && (!value_text(size) || tex_parse_real(value_text(size), &s) < 0 ||
                      s != (int)s || s < 1 || s > MAX_SIDE))
        rc = fail(pl, "the project's size must be 1..%d", MAX_SIDE);
    else if (gr && gr->type != TEX_JSON_OBJECT)
        rc = fail(pl, "the project's \"graph\" must be an object");
    else if (gr) /* a graph that loads back (one still being edited may lack an input) */
        rc = graph_load(pl, g, gr);
    free(g);
    tex_json_free(doc);
    return rc;
}
