/* proc.h - composed primitives: new primitives made of others (thesis 4.3.6)
 *
 * A composed primitive is an expression over the texture coordinates u, v,
 * w, its own parameters and calls of other primitives, registered or
 * composed, with their parameters named:
 *
 *   primitive marble(veins = 6 in 0 to 100 "sine periods across the map",
 *                    strength = 4 in 0 to 20 "turbulence added to the phase")
 *       "veined marble"
 *       = 0.5 + 0.5*sin(veins*u + strength*turbulence(octaves = 6));
 *
 * It becomes a struct tex_primitive (prim.h) like any other: its parameters
 * are descriptor rows (REAL, with the default and range declared), so
 * tex_field_new, tex_field_set, --help, scenes (solid too) and composition
 * scripts take it unchanged.  The expression is compiled once, to register
 * code over rows (rowcode.h), and evaluated 64 points at a time.
 *
 * The language (man 5 textura, "Composed primitives"):
 *   - the functions and operators of expr.h (+ - * /, comparisons, sin, mix,
 *     smoothstep, ...), u v w, pi, and the parameters declared;
 *   - NAME(coordinates, param = value, ...): a primitive at the point, or at
 *     the coordinates given (u, then v, then w: the rest stay), which warps
 *     its domain: noise(u + 0.1*turbulence(), v).  A value is a number, an
 *     expression of the parameters (checked by the callee's rows when the
 *     field starts), or a word (an enumeration's choice: mode = ridged).
 *     seed = K adds K to the field's seed; channel = K picks a channel of a
 *     primitive of several (0 by default).  Grid primitives cannot be
 *     called: they have no value at a point.
 *   - the result is one number per point (no colours: give a palette after).
 * A composed primitive is solid (3D) when every primitive it calls is, tiles
 * when every one does (its own use of u, v must be periodic for the result
 * to tile), and has w = 0 when evaluated in 2D.
 *
 * Errors carry the position: unknown names, wrong arity, a definition that
 * calls itself (definitions come before their use, so no cycle can form),
 * an expression too long or nested too deeply (expr.h's limits; calls nest
 * at most TEX_PROC_MAX_NEST deep, through the primitives they call).
 *
 *   struct tex_procs *set = tex_procs_new();
 *   if (tex_procs_read(set, "marble.tp") < 0) ...      // "marble.tp:3:9: ..."
 *   const struct tex_primitive *p = tex_procs_find(set, "marble");
 *   struct tex_field *f = tex_field_new(p);  ...  tex_field_free(f);
 *   tex_procs_free(set);                    // after the fields made from it
 */
#ifndef TEX_PROC_H
#define TEX_PROC_H

#include <stddef.h>

#include "../base/api.h"
#include "../prim/prim.h"

TEX_API_BEGIN

#define TEX_PROC_MAX_PARAMS 32   /* parameters of one composed primitive */
#define TEX_PROC_MAX_CALLS 256   /* calls in one definition */
#define TEX_PROC_MAX_NEST 8      /* calls within calls, through definitions */
#define TEX_PROC_MAX_REGS 32     /* values pending in one expression */

struct tex_procs;
struct tex_lexer;

struct tex_procs *tex_procs_new(void);
void tex_procs_free(struct tex_procs *set);
/* Read a definitions file: "primitive ..." statements.  -1 with
 * "name:line:col: message" (a usage error) on failure. */
int tex_procs_load(struct tex_procs *set, const char *text, size_t len, const char *name);
int tex_procs_read(struct tex_procs *set, const char *path);
/* One definition at the lexer's current token, which follows the word
 * 'primitive' (for languages that embed definitions: scenes, scripts); a
 * final ';' is taken.  Errors longjmp through the lexer. */
const struct tex_primitive *tex_procs_define(struct tex_procs *set, struct tex_lexer *lx);
/* A primitive named name (no parameters) from an expression alone, as
 * t_expr 'EXPR' gives; where names the text in messages. */
const struct tex_primitive *tex_procs_expr(struct tex_procs *set, const char *text,
                                           const char *name, const char *where);
/* The composed primitive called name in set (which may be NULL), else the
 * registered one, else NULL. */
const struct tex_primitive *tex_procs_find(const struct tex_procs *set, const char *name);
/* The composed primitives of set, in the order defined: i from 0 until NULL. */
const struct tex_primitive *tex_procs_get(const struct tex_procs *set, int i);

TEX_API_END
#endif
