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

/* The operands a band of rows at a time, read in lockstep from each map's reader */
struct lockstep {
    int op, n;
    double t;
    struct tex_operand ops[3]; /* a map operand's map is its band */
    tex_rows_reader *r[3];
    tex_map *band[3];
    const char *name[3];
    int rows; /* the bands' room */
};

static int lockstep_fill(void *arg, int y, int n, float *rows)
{
    struct lockstep *s = arg;
    tex_map *out;

    for (int k = 0; k < s->n; k++) {
        tex_map *b = s->band[k];
        if (!s->r[k])
            continue;
        if (n > s->rows) { /* the writer's bands: the same height but the last */
            int w = b->w, nc = b->nc;
            tex_map_free(b);
            if (!(b = s->band[k] = tex_map_new(w, n, nc)))
                return -1;
            s->ops[k].map = b;
        }
        b->h = n;
        if (tex_rows_read(s->r[k], y, n, b->px, s->name[k]) < 0 ||
            tex_rows_nonfinite(b->px, b->w, n, b->nc, y, s->name[k]) < 0)
            return -1;
    }
    if (!(out = tex_op_apply(s->op, &s->ops[0], s->n > 1 ? &s->ops[1] : NULL,
                             s->n > 2 ? &s->ops[2] : NULL, s->t)))
        return -1;
    memcpy(rows, out->px, tex_map_samples(out) * sizeof *rows);
    tex_map_free(out);
    s->rows = n > s->rows ? n : s->rows;
    return 0;
}

/* Every map operand open for rows (heads[k]), all of one size: the result written as bands
 * of them pass, in lockstep.  The channels are those of the operation on 1 x 1 bands. */
static void lockstep(struct lockstep *s, tex_map *heads, const struct tex_common *c)
{
    tex_map head = {0}, *probe;

    for (int k = 0; k < s->n; k++)
        if (s->r[k]) {
            if (!(s->band[k] = tex_map_new(heads[k].w, 1, heads[k].nc)))
                tex_die();
            s->band[k]->subregions = heads[k].subregions;
            s->ops[k].map = s->band[k];
            if (!head.w)
                head.w = heads[k].w, head.h = heads[k].h;
        }
    if (!(probe = tex_op_apply(s->op, &s->ops[0], s->n > 1 ? &s->ops[1] : NULL,
                               s->n > 2 ? &s->ops[2] : NULL, s->t)))
        tex_die();
    head.nc = probe->nc;
    tex_map_free(probe);
    s->rows = 1;
    if (s->r[0] && heads[0].history) /* the result's history is the first operand's */
        head.history = heads[0].history, heads[0].history = NULL;
    tex_cli_write_rows(&head, c, lockstep_fill, s);
    free(head.history);
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
    /* To an output that takes rows, maps on a pipe or in scanline EXR files of one size go
     * a band at a time, in lockstep; anything else is read whole. */
    struct lockstep s = {.op = op, .n = n, .t = o.threshold};
    tex_map heads[3];
    int rows = tex_cli_takes_rows(&c), w = -1, h = -1;
    for (int k = 0; k < n; k++) {
        const char *a = argv[i + 1 + k];
        s.ops[k] = ops[k];
        if (tex_operand_parse(a, &ops[k]) == 0)
            continue;
        s.name[k] = strcmp(a, "-") ? a : "standard input";
        if (!rows)
            owned[k] = tex_cli_read(a);
        else if (!(s.r[k] = tex_map_open_rows(a, &heads[k], &owned[k])) && !owned[k])
            tex_die();
        const tex_map *m = s.r[k] ? &heads[k] : owned[k];
        rows &= s.r[k] && (w < 0 || (m->w == w && m->h == h));
        w = w < 0 ? m->w : w, h = h < 0 ? m->h : h;
    }
    if (rows) {
        lockstep(&s, heads, &c);
        for (int k = 0; k < n; k++) {
            tex_map_free(s.band[k]);
            tex_rows_close(s.r[k]);
            if (s.r[k])
                free(heads[k].history);
        }
        free(c.cmdline);
        return 0;
    }
    for (int k = 0; k < n; k++) {
        if (s.r[k])
            owned[k] = tex_cli_rows_whole(s.r[k], &heads[k], s.name[k]);
        ops[k].map = owned[k];
        if (owned[k] && !first)
            first = owned[k];
    }
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
