/* help.c - --help and the man pages' option lists, made from the option rows */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/internal.h"
#include "io/json.h"

static void usage_line(const struct tex_tool *t, FILE *fp)
{
    fprintf(fp, "usage: %s [options]%s%s\n", t->name, t->operands && *t->operands ? " " : "",
            t->operands ? t->operands : "");
}

void tex_cli_help(FILE *fp, const struct tex_tool *t, const struct tex_cli_opt *o, int n)
{
    usage_line(t, fp);
    fprintf(fp, "%s.\n\nOptions:\n", t->summary);
    for (int i = 0; i < n; i++) {
        const struct tex_param *p = o[i].row;
        char opt[64], lhs[128], rng[128], def[64];
        tex_param_option(p, opt, sizeof opt);
        snprintf(lhs, sizeof lhs, "%c%c%s%s%s%s %s", p->key ? '-' : ' ', p->key ? p->key : ' ',
                 p->key ? ", " : "  ", opt, p->alias ? ", --" : "", p->alias ? p->alias : "",
                 p->type == TEX_P_FLAG ? "" : p->bare ? "[NAME]" : p->type == TEX_P_ENUM ? "NAME"
                 : p->meta ? p->meta : "X");
        fprintf(fp, "  %-28s %s", lhs, p->help);
        tex_param_range(p, rng, sizeof rng);
        if (p->type != TEX_P_FLAG && p->type != TEX_P_STRING)
            fprintf(fp, " [%s]", rng);
        if (p->type != TEX_P_FLAG && (p->type != TEX_P_STRING || p->defstr))
            fprintf(fp, " (default %s)", tex_param_default(p, def, sizeof def));
        if (p->bare)
            fprintf(fp, " (alone: %s)", p->bare);
        fputc('\n', fp);
    }
    fprintf(fp, "  -h, --help                   show this help\n"
                "  -V, --version                show the version\n");
}

/* One option of the synopsis: its short letter if it has one, and its argument. */
static void synopsis_option(FILE *fp, const struct tex_param *p)
{
    char opt[64];
    tex_param_option(p, opt, sizeof opt);
    if (p->key)
        fprintf(fp, ".Op Fl %c", p->key);
    else
        fprintf(fp, ".Op Fl %s", opt + 1);
    if (p->type == TEX_P_ENUM && strlen(p->choices) <= 32)
        fprintf(fp, p->bare ? " Op Cm %s" : " Cm %s", p->choices);
    else if (p->type != TEX_P_FLAG)
        fprintf(fp, " Ar %s", p->type == TEX_P_ENUM ? "name" : p->meta ? p->meta : "x");
    fputc('\n', fp);
}

/* The operands as mdoc: "OP A [B [W]]" is .Ar OP A and .Op Ar B Op Ar W. */
static void synopsis_operands(FILE *fp, const char *s)
{
    int depth = 0, line = 0; /* line: a macro line is open */
    while (s && *s) {
        size_t n = strcspn(s, " []");
        if (*s == ' ') {
            s++;
        } else if (*s == '[') {
            if (!depth && line)
                fputc('\n', fp);
            fputs(depth++ ? " Op" : ".Op", fp);
            line = 1;
            s++;
        } else if (*s == ']') {
            if (--depth == 0) {
                fputc('\n', fp);
                line = 0;
            }
            s++;
        } else {
            int dots = n > 3 && !strncmp(s + n - 3, "...", 3);
            fprintf(fp, "%s%.*s%s", !line ? ".Ar " : depth ? " Ar " : " ", (int)(n - 3 * dots),
                    s, dots ? " ..." : "");
            line = 1;
            s += n;
        }
    }
    if (line)
        fputc('\n', fp);
}

static int own_row(const struct tex_tool *t, const struct tex_param *p)
{
    for (const struct tex_param *q = t->params; q && q->name; q++)
        if (q == p)
            return 1;
    return 0;
}

/* The synopsis as mdoc: the tool's own options, the shared ones, the operands. */
void tex_cli_synopsis(FILE *fp, const struct tex_tool *t, const struct tex_cli_opt *o, int n)
{
    fputs(".Nm\n", fp);
    for (int own = 1; own >= 0; own--)
        for (int i = 0; i < n; i++)
            if (own_row(t, o[i].row) == own)
                synopsis_option(fp, o[i].row);
    synopsis_operands(fp, t->operands);
}

/* The option list as mdoc, for the man page (checked by the tests). */
void tex_cli_mdoc(FILE *fp, const struct tex_tool *t, const struct tex_cli_opt *o, int n)
{
    int shared = 0;

    fputs(".Bl -tag -width Ds\n", fp);
    for (int i = 0; i < n; i++) {
        const struct tex_param *p = o[i].row;
        if (t && !own_row(t, p)) {
            shared++;
            continue;
        }
        char opt[64], rng[128], def[64];
        tex_param_option(p, opt, sizeof opt);
        fprintf(fp, ".It ");
        if (p->key)
            fprintf(fp, "Fl %c , ", p->key);
        fprintf(fp, "Fl %s", opt + 1);
        if (p->alias)
            fprintf(fp, " , Fl -%s", p->alias);
        if (p->type != TEX_P_FLAG)
            fprintf(fp, p->bare ? " Op Ar %s" : " Ar %s",
                    p->type == TEX_P_ENUM ? "name" : p->meta ? p->meta : "x");
        fprintf(fp, "\n%c%s",
                p->help[0] >= 'a' && p->help[0] <= 'z' ? p->help[0] - 32 : p->help[0],
                p->help + 1);
        if (p->type == TEX_P_ENUM)
            fprintf(fp, ": one of %s", tex_param_range(p, rng, sizeof rng));
        else if (p->type != TEX_P_FLAG && p->type != TEX_P_STRING)
            fprintf(fp, ", %s", tex_param_range(p, rng, sizeof rng));
        if (p->type != TEX_P_FLAG && (p->type != TEX_P_STRING || p->defstr)) {
            /* a default that ends in a full stop ("." the current folder) is quoted */
            const char *d = tex_param_default(p, def, sizeof def);
            size_t len = strlen(d);
            fprintf(fp, len && d[len - 1] == '.' ? "; default \\(lq%s\\(rq" : "; default %s", d);
        }
        if (p->bare)
            fprintf(fp, "; given alone, %s", p->bare);
        fputs(".\n", fp);
    }
    if (shared) { /* documented once, in textura(5) */
        fputs(".It Xo\n", fp);
        for (int i = 0, k = 0; i < n; i++) {
            const struct tex_param *p = o[i].row;
            char opt[64];
            if (own_row(t, p))
                continue;
            tex_param_option(p, opt, sizeof opt);
            if (p->key)
                fprintf(fp, ".Fl %c%s\n", p->key, ++k < shared ? " ," : "");
            else
                fprintf(fp, ".Fl %s%s\n", opt + 1, ++k < shared ? " ," : "");
        }
        fputs(".Xc\nThe options this tool shares with others, described once in\n"
              ".Xr textura 5 ,\nCOMMON OPTIONS.\n", fp);
    }
    fputs(".El\n", fp);
}

void tex_cli_json(FILE *fp, const struct tex_tool *t)
{
    struct tex_str b = {0};
    tex_str_add(&b, "{\"tool\":");
    tex_json_string(&b, t->name);
    tex_str_add(&b, ",\"operands\":");
    tex_json_string(&b, t->operands);
    tex_str_add(&b, ",\"summary\":");
    tex_json_string(&b, t->summary);
    tex_str_add(&b, ",\"params\":");
    tex_json_rows(&b, t->params);
    tex_str_add(&b, "}\n");
    if (b.s)
        fputs(b.s, fp);
    free(b.s);
}
