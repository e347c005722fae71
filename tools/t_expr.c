/* t_expr - a composed primitive (an expression of primitives) as a texture map */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"

struct opts {
    double params[TEX_PROC_MAX_PARAMS]; /* the composed primitive's, first */
    const char *defs;
};

static const struct tex_param defs_row =
    TEX_STRING(struct opts, defs, 0, NULL, "FILE",
               "read composed primitives from FILE (textura(5)); EXPR may then name one");

/* Options that take no value: the rest take one (the next argument). */
static int is_flag(const char *a)
{
    static const char *const flags[] = {"-q", "--quiet", "-h", "--help", "-V", "--version",
                                        "--tile", "--ids", "--help-mdoc", NULL};
    for (int i = 0; flags[i]; i++)
        if (!strcmp(a, flags[i]))
            return 1;
    return a[1] != '-' && a[2] != 0; /* -qj2, -s256: the value is in the word */
}

/* Before the options can be parsed, their rows must be known: find --defs and
 * the operand (EXPR or NAME) by a first look at argv. */
static void scan(int argc, char **argv, const char **defs, const char **expr)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--")) {
            if (i + 1 < argc && !*expr)
                *expr = argv[i + 1];
            return;
        }
        if (a[0] != '-' || !a[1]) {
            if (!*expr)
                *expr = a;
        } else if (!strncmp(a, "--defs=", 7)) {
            *defs = a + 7;
        } else if (!strcmp(a, "--defs") && i + 1 < argc) {
            *defs = argv[++i];
        } else if (!strchr(a, '=') && !is_flag(a)) {
            i++;
        }
    }
}

int main(int argc, char **argv)
{
    const char *defs = NULL, *expr = NULL;
    static struct tex_param rows[TEX_PROC_MAX_PARAMS + 2];
    static struct opts o;
    struct tex_procs *set;
    const struct tex_primitive *p;
    int n = 0;

    tex_progname = "t_expr";
    scan(argc, argv, &defs, &expr);
    if (!(set = tex_procs_new()) || (defs && tex_procs_read(set, defs) < 0))
        tex_die();
    if (!expr) { /* --help, --version, or a usage error: the front end says which */
        const struct tex_param own[] = {defs_row, {0}};
        const struct tex_tool t = {"t_expr", "EXPR|NAME",
                                          "a composed primitive as a texture map",
                                          TEX_OPT_OUTPUT | TEX_OPT_SIZE | TEX_OPT_SEED |
                                          TEX_OPT_TILE, own, 1, 1};
        struct tex_common c;
        tex_cli_parse(&t, argc, argv, &c, &o);
        return 2;
    }
    if (!(p = tex_procs_find(set, expr)) && !(p = tex_procs_expr(set, expr, "expr", "EXPR")))
        tex_die();
    for (; p->params[n].name; n++)
        rows[n] = p->params[n];
    rows[n] = defs_row;
    if (p->params_size > sizeof o.params)
        tex_usage_die("%s has too many parameters for t_expr", p->name);
    n = tex_generate_main_rows(p, "t_expr", "EXPR|NAME", rows, &o, argc, argv);
    tex_procs_free(set);
    return n;
}
