/* compose.h - composition of texture maps (thesis 4.2.7, 5.2.4)
 *
 * New textures from simpler ones: per-pixel operators between maps and
 * constants, cascades (region k of one map filled by another map),
 * repetition nu x nv and the n x m matrix of maps chosen by a rule over
 * the cell indices, domain perturbation (warp), and a Gaussian blur.
 *
 * Operands.  A struct tex_operand is a map or a constant of 1-4 values.
 * Map operands of one operation must have the same size (resize them
 * first with tex_fit); channels broadcast: a 1-channel operand is repeated
 * over the colour channels of a 3- or 4-channel one, and an operand
 * without alpha meeting a 4-channel one counts as opaque.  2-channel maps
 * (vectors) combine only with 1- or 2-channel operands.
 *
 * Alpha.  A 4-channel map is RGBA with premultiplied colour (as in EXR);
 * maps without alpha are opaque.  Porter-Duff, a and b the first and second
 * operands:
 *   over  (the thesis's +_up: b below, a on top)   r = a + b (1 - alpha_a)
 *   under (the thesis's +_down: a below b)          r = b + a (1 - alpha_b)
 * mix (a (1 - w) + b w) works on every channel, alpha included.  The other
 * operators work on the colour channels and keep the alpha of a:
 * add sub mul div min max; div by zero gives 0; abs; invert is 1 - x
 * (alpha - x for RGBA); threshold is x >= t ? 1 : 0; and, or, xor
 * threshold both operands at t and combine the bits (0 or 1).
 *
 *   struct tex_operand a = {map_a}, b = tex_constant(0.5);
 *   tex_map *r = tex_op_apply(TEX_OP_MUL, &a, &b, NULL, 0.5);
 *
 * Every function returns a new map, or NULL with tex_errmsg().
 */
#ifndef TEX_COMPOSE_H
#define TEX_COMPOSE_H

#include "../base/api.h"
#include "../base/map.h"
#include "transform.h"

TEX_API_BEGIN

enum tex_op {
    TEX_OP_ADD, TEX_OP_SUB, TEX_OP_MUL, TEX_OP_DIV, TEX_OP_MIN, TEX_OP_MAX, TEX_OP_MIX,
    TEX_OP_ABS, TEX_OP_INVERT, TEX_OP_THRESHOLD, TEX_OP_OVER, TEX_OP_UNDER, TEX_OP_AND,
    TEX_OP_OR, TEX_OP_XOR, TEX_OP_COUNT
};

struct tex_operand {
    const tex_map *map; /* NULL: the constant below */
    int nc;             /* constant: 1..4 values */
    float c[4];
};

/* The operator called name ("add", "over", ...), or -1 with a usage error. */
int tex_op_find(const char *name);
const char *tex_op_name(enum tex_op op);
/* "add|sub|..." for messages and help. */
const char *tex_op_names(void);
/* Operands the operator takes: 1 (abs invert threshold), 2, or 3 (mix). */
int tex_op_arity(enum tex_op op);

/* A constant operand from "0.5" or "1,0.5,0" (1-4 numbers); -1 if not one. */
int tex_operand_parse(const char *text, struct tex_operand *o);

/* Apply op: b is the second operand (for threshold: the level, or NULL for
 * t), w the weight of mix; t the threshold of threshold/and/or/xor. */
tex_map *tex_op_apply(enum tex_op op, const struct tex_operand *a, const struct tex_operand *b,
                      const struct tex_operand *w, double t);

/* How maps of different sizes are brought to one size. */
enum tex_fit { TEX_FIT_ERROR, TEX_FIT_SCALE, TEX_FIT_TILE };
/* m at w x h: a copy if already that size; else scaled (filtered) or
 * tiled (repeated from the top left corner), or a usage error naming what. */
tex_map *tex_fit(const tex_map *m, int w, int h, enum tex_fit fit, const char *what);

/* Cascade: pixel with region id k (1..nregions) takes maps[k]'s pixel;
 * ids with maps[k] == NULL, or outside 1..nregions, take def (RGBA).
 * maps has nregions + 1 entries (maps[0] unused) of ids' size. */
tex_map *tex_cascade(const tex_map *ids, int nregions, const tex_map *const *maps,
                     const float def[4]);

/* Repetition and the matrix of maps.  The output (w x h) is divided into
 * nu x nv cells; cell (u',v') = (int(u nu), int(v nv)) shows map number
 * rule(u',v') shrunk into the cell (mirror: odd columns flipped left-right,
 * odd rows top-bottom).  Rules over the cell indices, for n maps:
 *   diagonal  map 0 where u' = v', map 1 elsewhere (the thesis's diagonal_flower)
 *   checker   map (u' + v') mod n
 *   rows      map v' mod n
 *   columns   map u' mod n
 *   cycle     map (v' nu + u') mod n
 * With one map every rule repeats it (figures 5.11, 5.12). */
enum tex_rule { TEX_RULE_DIAGONAL, TEX_RULE_CHECKER, TEX_RULE_ROWS, TEX_RULE_COLUMNS,
                TEX_RULE_CYCLE };
#define TEX_RULE_NAMES "diagonal|checker|rows|columns|cycle"
tex_map *tex_tile(const tex_map *const *maps, int nmaps, enum tex_rule rule, int nu, int nv,
                  int mirror, int w, int h);

/* Domain perturbation: out(u,v) = m(u + amount d_u, v + amount d_v), with
 * (u,v) in texture units (the unit square) and d from `by` sampled at (u,v):
 *   by with >= 2 channels:  d = (by_0 - centre, by_1 - centre);
 *   1 channel, isotropic:   d = (by(u,v) - centre, by(u + 0.5, v + 0.5) - centre),
 *                           the second lookup half a map away, where noise
 *                           is decorrelated;
 *   1 channel otherwise:    d = (by - centre) (cos angle, -sin angle), a push
 *                           along one direction (angle 0: along u, as in marble).
 * by is read with wrapping; m with the edge rule (clamp or wrap). */
struct tex_warp_opts {
    double amount, centre, angle;
    int isotropic;
    enum tex_edge edge;
};
tex_map *tex_warp(const tex_map *m, const tex_map *by, const struct tex_warp_opts *o, int w,
                  int h);
/* The warp a band of rows at a time (t_warp in bounded memory): rows y..y+out->h-1 of
 * tex_warp(M, BY, o, out->w, h) into out (M's channels), bit for bit, from m, by and by2
 * (transform.h's struct tex_map_rows: bands of M and BY, wrapping where the edge rule
 * does) holding every row that tex_warp_reads names: by for BY's first lookup, by2 for
 * the isotropic's second (by again when none).  0, or -1 with the error set. */
int tex_warp_rows(struct tex_map_rows m, struct tex_map_rows by, struct tex_map_rows by2,
                  const struct tex_warp_opts *o, tex_map *out, int y, int h);
/* The rows [from, to) that rows y..y+n-1 of a warp h rows tall read, before the edge rule
 * (they may pass either edge): by and by2 of BY (bh rows tall; by2 the isotropic's second
 * lookup), m of M (mh rows tall) when BY's channel c (of bnc) lies within lo[c]..hi[c].
 * M's rows reach amount (3 max|BY - neutral| at most) x mh either side of the row's
 * own, less where BY's range is narrow.  0, or -1 when a bound passes any row index
 * (BY not finite, a displacement of more than 10^12 rows): then any row may be read. */
struct tex_warp_reach {
    long by[2], by2[2], m[2];
};
int tex_warp_reads(const struct tex_warp_opts *o, int bnc, const double lo[4],
                   const double hi[4], int bh, int mh, int h, int y, int n,
                   struct tex_warp_reach *r);

/* The composition language's blur: tex_filter_gaussian (filter.h) with
 * standard deviation sigma pixels (0..TEX_BLUR_MAX), edges clamped, any
 * map size; 0 copies the map. */
#define TEX_BLUR_MAX 256
tex_map *tex_blur(const tex_map *m, double sigma);

TEX_API_END
#endif
