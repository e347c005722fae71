/* catalog.c - the node kinds and their parameter rows, as JSON for the page: every
 * primitive (rows from the registry) and the operator tools (rows from --help-json) */
#include <dirent.h>
#include <fcntl.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "io/json.h"
#include "textura.h"
#include "proto.h"

static void json_prim(struct tex_str *b, const struct tex_primitive *p, int composed, int first)
{
    tex_str_add(b, "%s{\"name\":", first ? "" : ",");
    tex_json_string(b, p->name);
    tex_str_add(b, ",\"summary\":");
    tex_json_string(b, p->summary);
    tex_str_add(b, ",\"composed\":%d,\"grid\":%d,\"tile\":%d,\"params\":", composed,
         !!(p->flags & TEX_PRIM_GRID), !!(p->flags & TEX_PRIM_TILE));
    tex_json_rows(b, p->params);
    tex_str_add(b, "}");
}

/* The palette names: the installed ones ("brick, clouds, ...") and NAME.pal files the
 * editor saved in the working folder, each a JSON string. */
static void json_palettes(struct tex_str *b)
{
    char names[4096];
    int first = 1;
    if (tex_palette_names(names, sizeof names) < 0)
        names[0] = 0;
    for (const char *k = names; *k;) {
        char one[128];
        size_t len = strcspn(k, ",");
        snprintf(one, sizeof one, "%.*s", (int)len, k);
        tex_str_add(b, first ? "" : ",");
        tex_json_string(b, one);
        first = 0;
        k += len;
        k += strspn(k, ", ");
    }
    int fd = openat(proto.workfd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC); /* its own offset */
    DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
    struct dirent *e;
    if (!d && fd >= 0)
        close(fd);
    for (int n = 0; d && n < 1000 && (e = readdir(d)); n++) /* bounded: a huge folder */
        if (is_saved_palette(e->d_name)) {
            tex_str_add(b, first ? "" : ",");
            tex_json_string(b, e->d_name);
            first = 0;
        }
    if (d)
        closedir(d);
}

/* The operator kinds of a graph's nodes: the tool, its operand word's row (the operation
 * of t_op and t_filter, t_palette's palette) and its input slots; the rest of its rows
 * come from the tool itself (kinds_load), but for those that make no map from the inputs
 * (t_palette's --from...) or that t_proto sets (-s). */
struct kind kinds[] = {
    {"op", "t_op", "op", "", /* its choices: libtex's operators, in kinds_load */
     "the operation: A op B; mix is A (1 - W) + B W; abs, invert and threshold take A alone",
     {"a", "b", "w"}, 2, NULL, 0, NULL}, /* needs: add's; each operation's own in graph.c */
    {"palette", "t_palette", "palette", NULL, "the palette: an installed one or a NAME.pal "
     "saved in the working folder", {"in"}, 1, "from to stops space list", 0, NULL},
    {"filter", "t_filter", "op", "", "the filter", {"in"}, 1, NULL, 0, NULL}, /* choices: too */
    {"remap", "t_remap", NULL, NULL, NULL, {"in"}, 1, NULL, 0, NULL},
    {"xform", "t_xform", NULL, NULL, NULL, {"in"}, 1, NULL, 0, NULL},
    {"warp", "t_warp", NULL, NULL, NULL, {"map", "by"}, 2, "size", 0, NULL},
    {"cascade", "t_cascade", NULL, NULL, NULL,
     {"ids", "1", "2", "3", "4", "5", "6", "7", "8"}, 2, NULL, 0, NULL},
    {"tile", "t_tile", NULL, NULL, NULL, {"1", "2", "3", "4"}, 1, "size", 1, NULL},
    {0}};

/* Is name one of the words of the space-separated list? */
static int listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *w = list; w && *w; w += strcspn(w, " "), w += *w == ' ')
        if (strcspn(w, " ") == n && !strncmp(w, name, n))
            return 1;
    return 0;
}

const struct kind *kind_find(const char *name)
{
    for (struct kind *k = kinds; k->name; k++)
        if (!strcmp(k->name, name))
            return k;
    return NULL;
}

const struct tex_json *kind_row(const struct kind *k, const char *name)
{
    const struct tex_json *rows = tex_json_get(k->help, "params");
    for (int i = 0; rows && i < rows->n; i++) {
        const struct tex_json *nm = tex_json_get(&rows->item[i], "name");
        if (nm && nm->str && !strcmp(nm->str, name) && !listed(k->skip, name))
            return &rows->item[i];
    }
    return NULL;
}

int kinds_load(void)
{
    static char filters[512];
    for (const struct tex_filter_op *f = tex_filter_ops; f->name; f++)
        snprintf(filters + strlen(filters), sizeof filters - strlen(filters), "%s%s",
                 f == tex_filter_ops ? "" : "|", f->name);
    kinds[0].choices = tex_op_names();
    kinds[2].choices = filters;
    for (struct kind *k = kinds; k->name; k++) {
        struct pipeline *pl = calloc(1, sizeof *pl);
        struct tex_str out = {0};
        char err[128];
        int rc = !pl || stage(pl, k->tool) < 0 || arg(pl, "--help-json") < 0 ? 1 : run(pl, &out);
        if (rc == 0 && !(k->help = tex_json_parse(out.s, out.n, err, sizeof err)))
            rc = fail(pl, "%s --help-json: %s", k->tool, err);
        if (rc)
            tex_error("cannot read %s's options: %s", k->tool, pl ? pl->err : "out of memory");
        free(out.s);
        free(pl);
        if (rc)
            return -1;
    }
    return 0;
}

/* A kind as the page reads it: its operand row first, then the tool's rows offered. */
static void json_kind(struct tex_str *b, const struct kind *k, int first_kind)
{
    const struct tex_json *sum = tex_json_get(k->help, "summary");
    const struct tex_json *rows = tex_json_get(k->help, "params");
    int first = 1;
    tex_str_add(b, first_kind ? "{\"name\":" : ",{\"name\":");
    tex_json_string(b, k->name);
    tex_str_add(b, ",\"tool\":");
    tex_json_string(b, k->tool);
    tex_str_add(b, ",\"summary\":");
    tex_json_string(b, sum ? sum->str : "");
    tex_str_add(b, ",\"needs\":%d,\"slots\":[", k->needs);
    for (int i = 0; i < MAX_SLOTS && k->slots[i]; i++) {
        tex_str_add(b, i ? "," : "");
        tex_json_string(b, k->slots[i]);
    }
    tex_str_add(b, "],\"params\":[");
    if (k->operand) {
        char def[64];
        snprintf(def, sizeof def, "%.*s", k->choices ? (int)strcspn(k->choices, "|") : 6,
                 k->choices ? k->choices : "marble");
        tex_str_add(b, "{\"name\":");
        tex_json_string(b, k->operand);
        tex_str_add(b, ",\"type\":\"%s\",\"min\":0,\"max\":0,\"default\":",
                    k->choices ? "enum" : "palette");
        tex_json_string(b, def);
        tex_str_add(b, ",\"help\":");
        tex_json_string(b, k->operand_help);
        tex_str_add(b, ",\"choices\":");
        tex_json_string(b, k->choices);
        tex_str_add(b, ",\"meta\":\"\",\"kinds\":0,\"operand\":1}");
        first = 0;
    }
    /* the tool's rows as it printed them, but for those skipped */
    for (int i = 0; rows && i < rows->n; i++) {
        const struct tex_json *nm = tex_json_get(&rows->item[i], "name");
        if (!nm || !nm->str || listed(k->skip, nm->str))
            continue;
        tex_str_add(b, first ? "{" : ",{");
        first = 0;
        for (int m = 0; m < rows->item[i].n; m++) {
            const struct tex_json *f = &rows->item[i].item[m];
            tex_str_add(b, m ? "," : "");
            tex_json_string(b, f->key);
            tex_str_add(b, ":");
            if (f->type == TEX_JSON_STRING)
                tex_json_string(b, f->str);
            else
                tex_str_add(b, "%s", f->str ? f->str : "null");
        }
        tex_str_add(b, "}");
    }
    tex_str_add(b, "]}");
}

void api_prims(struct tex_str *b)
{
    tex_str_add(b, "{\"primitives\":[");
    for (int i = 0; tex_primitives[i]; i++)
        json_prim(b, tex_primitives[i], 0, i == 0);
    for (int i = 0; tex_procs_get(proto.procs, i); i++)
        json_prim(b, tex_procs_get(proto.procs, i), 1, 0);
    tex_str_add(b, "],\"kinds\":[");
    for (int i = 0; kinds[i].name; i++)
        json_kind(b, &kinds[i], i == 0);
    tex_str_add(b, "],\"palettes\":[");
    json_palettes(b);
    tex_str_add(b, "]}");
}
