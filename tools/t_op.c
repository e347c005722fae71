/* t_op - per-pixel operators between texture maps and constants */
#include <stdlib.h>
#include <string.h>

#include "ops/compose.h"
#include "textura.h"

struct opts {
    double threshold;
    int resize;
};

static const struct tex_param rows[] = {
    TEX_REAL(struct opts, threshold, 't', 0.5, -1e30, 1e30, "T",
             "level of threshold, and of the binary contents for and, or, xor"),
    TEX_ENUM(struct opts, resize, 0, "error", "error|scale|tile",
             "how operands of another size than the first map are brought to its size"),
    {0}};

static const struct tex_tool tool = {
    "t_op", "OP A [B [W]]",
    "combine texture maps pixel by pixel: add sub mul div min max mix abs invert threshold, "
    "over under (Porter-Duff), and or xor; an operand is a map file, - (standard input) or a "
    "constant such as 0.5 or 1,0,0",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 2, 4};

/* The operation on a band of each map operand (the constants as they are) */
struct op_job {
    int op, n;
    double t;
    struct tex_operand ops[3];
};

static tex_map *op_band(tex_map *const *bands, void *arg)
{
    struct op_job *j = arg;

    for (int k = 0; k < j->n; k++)
        if (bands[k])
            j->ops[k].map = bands[k];
    return tex_op_apply(j->op, &j->ops[0], j->n > 1 ? &j->ops[1] : NULL,
                        j->n > 2 ? &j->ops[2] : NULL, j->t);
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), op, n, arity, stdin_used = 0;
    struct tex_operand ops[3];
    tex_map *owned[3] = {NULL, NULL, NULL}, *r;
    const tex_map *first = NULL;

    if ((op = tex_op_find(argv[i])) < 0)
        tex_die();
    n = argc - i - 1;
    arity = tex_op_arity(op);
    if (n != arity && !(op == TEX_OP_THRESHOLD && n == 2))
        tex_usage_die("%s takes %d operand%s%s (got %d)", argv[i], arity, arity > 1 ? "s" : "",
                      op == TEX_OP_THRESHOLD ? " and an optional level" : "", n);
    /* Parse every operand before reading any map, so a usage error reads nothing. */
    for (int k = 0; k < n; k++) {
        const char *a = argv[i + 1 + k];
        if (tex_operand_parse(a, &ops[k]) == 0)
            continue;
        if (!strcmp(a, "-") && stdin_used++)
            tex_usage_die("standard input (-) can be read only once");
    }
    /* Maps on pipes or in scanline EXR files of one size go a band at a time, in lockstep,
     * to an output that takes rows; anything else is read whole. */
    tex_lockstep *l = tex_cli_lockstep_new(n);
    struct op_job job = {op, n, o.threshold, {ops[0], ops[1], ops[2]}};
    for (int k = 0; k < n; k++)
        if (tex_operand_parse(argv[i + 1 + k], &job.ops[k]) != 0)
            tex_cli_lockstep_add(l, k, argv[i + 1 + k]);
    if (tex_cli_lockstep_streams(l, &c)) {
        tex_cli_lockstep_write(l, &c, 0, op_band, &job);
        tex_cli_lockstep_free(l);
        free(c.cmdline);
        return 0;
    }
    for (int k = 0; k < n; k++) {
        if (tex_operand_parse(argv[i + 1 + k], &ops[k]) == 0)
            continue;
        ops[k].map = owned[k] = tex_cli_lockstep_whole(l, k);
        if (!first)
            first = owned[k];
    }
    tex_cli_lockstep_free(l);
    for (int k = 0; k < n && first; k++) {
        tex_map *f;
        if (!owned[k] || owned[k] == first)
            continue;
        if (!(f = tex_fit(owned[k], first->w, first->h, (enum tex_fit)o.resize,
                          argv[i + 1 + k])))
            tex_die();
        tex_map_free(owned[k]);
        ops[k].map = owned[k] = f;
    }
    if (!(r = tex_op_apply(op, &ops[0], n > 1 ? &ops[1] : NULL, n > 2 ? &ops[2] : NULL,
                           o.threshold)))
        tex_die();
    tex_cli_write(r, &c);
    tex_map_free(r);
    for (int k = 0; k < 3; k++)
        tex_map_free(owned[k]);
    free(c.cmdline);
    return 0;
}
