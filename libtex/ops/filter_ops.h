/* filter_ops.h - the registry of neighbourhood filters, by name
 *
 * Every operation of ops/filter.h under its name, with the parameters it
 * takes as rows (base/param.h) and how far it reaches above and below a
 * row.  t_filter(1) takes its operations, options, --help and man page from
 * it, and the composition language (t_compose(5)) its 'filter NAME' words,
 * so the two offer the same filters with the same parameters.
 *
 *   struct tex_filter_args a;
 *   const struct tex_filter_op *op = tex_filter_op_find("emboss");
 *   tex_params_defaults(tex_filter_rows, &a);
 *   tex_param_set(tex_param_find(tex_filter_rows, "angle"), &a, "45");
 *   tex_map *r = tex_filter_op_apply(op, m, &a, 0, m->h, 0);
 *
 * Row k of tex_filter_rows applies to the operations whose bit is set in
 * its kinds (bit i: tex_filter_ops[i]).  tex_filter_op_apply takes a map, or
 * a band of rows of a taller map: y0 is the band's first row in the whole
 * map and full_h the whole map's height (0 and m->h for a whole map);
 * noise and gradient depend on them, the others do not.  margin is the rows
 * of context above and below the band's output rows (0 for a whole map):
 * blur, box and smooth leave them out of the map they return, the others
 * return them filtered too.
 */
#ifndef TEX_FILTER_OPS_H
#define TEX_FILTER_OPS_H

#include <stdint.h>

#include "../base/api.h"
#include "../base/map.h"
#include "../base/param.h"

TEX_API_BEGIN

/* The parameters of every filter (each operation reads its own). */
struct tex_filter_args {
    double sigma, strength, amount, angle;
    int radius, edge, direction;
    uint64_t seed; /* noise: the seed (-S, not a row) */
};
extern const struct tex_param tex_filter_rows[];

/* How far an operation reaches above and below a row. */
enum tex_filter_reach { TEX_REACH_NONE, TEX_REACH_ONE, TEX_REACH_SIGMA, TEX_REACH_RADIUS };

struct tex_filter_op {
    const char *name;
    enum tex_filter_reach reach;
    const char *help;
    const char *by; /* the row a script's 'by VALUE' sets, or NULL */
};
/* The operations in a fixed order; the last one's name is NULL. */
extern const struct tex_filter_op tex_filter_ops[];

/* The operation called name, or NULL. */
const struct tex_filter_op *tex_filter_op_find(const char *name);
/* The operation on m (NULL with tex_errmsg() on failure). */
tex_map *tex_filter_op_apply(const struct tex_filter_op *op, const tex_map *m,
                             const struct tex_filter_args *a, int y0, int full_h, int margin);
/* Its index in tex_filter_ops (the bit of its rows' kinds). */
int tex_filter_op_index(const struct tex_filter_op *op);
/* The rows above and below an output row that it reads. */
int tex_filter_margin(const struct tex_filter_op *op, const struct tex_filter_args *a);

TEX_API_END
#endif
