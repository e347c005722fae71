/* t_tile - repeat a texture map nu x nv times, or lay out a matrix of maps by a rule */
#include <stdlib.h>
#include <string.h>

#include "ops/compose.h"
#include "textura.h"

struct opts {
    int nu, nv, mirror;
    const char *matrix, *size;
};

static const struct tex_param rows[] = {
    TEX_INT(struct opts, nu, 0, 2, 1, 4096, "N", "cells across (along u)"),
    TEX_INT(struct opts, nv, 0, 2, 1, 4096, "M", "cells down (along v)"),
    TEX_FLAG(struct opts, mirror, 0, "flip odd columns left-right and odd rows top-bottom"),
    TEX_STRING(struct opts, matrix, 0, NULL, "RULE",
               "choose each cell's map by a rule over the cell indices: "
               "diagonal|checker|rows|columns|cycle"),
    TEX_STRING(struct opts, size, 's', NULL, "N|WxH", "size of the result (default: the first "
                                                      "map's)"),
    {0}};

static const struct tex_tool tool = {
    "t_tile", "MAP...",
    "repeat a texture map nu x nv times, plain or mirrored, or fill an nu x nv matrix with maps "
    "chosen by a rule",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 1, 64};

int main(int argc, char **argv)
{
    static const char *const rules[] = {"diagonal", "checker", "rows", "columns", "cycle"};
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), n = argc - i, rule = TEX_RULE_CYCLE;
    int w = 0, h = 0, stdin_used = 0;
    tex_map *maps[64], *r;

    if (o.matrix) {
        rule = -1;
        for (int k = 0; k < 5; k++)
            if (!strcmp(o.matrix, rules[k]))
                rule = k;
        if (rule < 0)
            tex_usage_die("--matrix must be one of %s (got '%s')", TEX_RULE_NAMES, o.matrix);
        if ((rule == TEX_RULE_DIAGONAL || rule == TEX_RULE_CHECKER) && n != 2)
            tex_usage_die("--matrix %s takes 2 maps (got %d)", o.matrix, n);
    } else if (n != 1)
        tex_usage_die("repetition takes one map (got %d; use --matrix RULE for several)", n);
    if (o.size && tex_parse_size(o.size, &w, &h) < 0)
        tex_usage_die("-s must be N or WxH with each side 1..%d (got '%s')", TEX_MAP_MAX_SIDE,
                      o.size);
    for (int k = 0; k < n; k++)
        if (!strcmp(argv[i + k], "-") && stdin_used++)
            tex_usage_die("standard input (-) can be read only once");
    for (int k = 0; k < n; k++)
        maps[k] = tex_cli_read(argv[i + k]);
    if (!o.size) {
        w = maps[0]->w;
        h = maps[0]->h;
    }
    if (!(r = tex_tile((const tex_map *const *)maps, n, (enum tex_rule)rule, o.nu, o.nv, o.mirror,
                       w, h)))
        tex_die();
    tex_cli_write(r, &c);
    tex_map_free(r);
    for (int k = 0; k < n; k++)
        tex_map_free(maps[k]);
    free(c.cmdline);
    return 0;
}
