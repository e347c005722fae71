/* t_filter - blur, sharpen, edges, emboss, median, noise and normal maps of a texture map */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"

struct job {
    const struct tex_filter_op *op;
    const struct tex_filter_args *a;
};

/* A band's rows filtered: the filter over the band, of which the caller keeps the middle */
static tex_map *filter_band(tex_map *band, const struct tex_band *b, void *arg)
{
    const struct job *j = arg;
    return tex_filter_op_apply(j->op, band, j->a, b->y - b->margin, b->full_h, b->margin);
}

/* --help's summary, from the table: each operation and what it takes. */
static const char *summary(void)
{
    static char text[1024];
    size_t n = snprintf(text, sizeof text, "filter a texture map by OP, one of:");
    for (const struct tex_filter_op *op = tex_filter_ops; op->name && n < sizeof text; op++)
        n += snprintf(text + n, sizeof text - n, "\n  %-10s %s", op->name, op->help);
    return text;
}

int main(int argc, char **argv)
{
    const struct tex_tool tool = {"t_filter", "OP [MAP]", summary(), TEX_OPT_OUTPUT | TEX_OPT_MAPS | TEX_OPT_SEED,
                                  tex_filter_rows, 1, 2};
    struct tex_common c;
    struct tex_filter_args a;
    int i = tex_cli_parse(&tool, argc, argv, &c, &a);
    const struct tex_filter_op *op = tex_filter_op_find(argv[i++]);
    char choices[256] = "";

    for (const struct tex_filter_op *o = tex_filter_ops; o->name; o++)
        snprintf(choices + strlen(choices), sizeof choices - strlen(choices), "%s%s",
                 o == tex_filter_ops ? "" : "|", o->name);
    char near[32];
    if (!op && tex_choice_nearest(choices, argv[i - 1], near, sizeof near))
        tex_usage_die("unknown operation '%s'; did you mean %s? (one of %s)", argv[i - 1], near,
                      choices);
    if (!op)
        tex_usage_die("unknown operation '%s' (one of %s)", argv[i - 1], choices);
    tex_cli_check_kinds(&tool, choices, tex_filter_op_index(op), "the operation");
    a.seed = (uint64_t)c.seed;
    struct job j = {op, &a};
    tex_cli_stream_window(i < argc ? argv[i] : "-", &c, tex_filter_margin(op, &a),
                          (enum tex_edge)a.edge, filter_band, &j);
    free(c.cmdline);
    return 0;
}
