/* rowcode.h - expressions compiled to straight-line code over rows of points
 *
 * tex_expr_compile (expr.h) turns an expression into a postfix program for a
 * stack machine, run per point.  Here that program becomes register code
 * for whole rows: the stack slot an instruction writes is its register, so
 * the code is straight-line, and each instruction is one loop over a row of
 * n points (tex_expr_apply_row, the same formulas).  The cost of reading
 * the program is paid once per row, not per point, and the loops vectorise.
 * Composed primitives (proc.h) run on it; the renderer can too.
 *
 *   struct tex_rowcode *rc = tex_rowcode_new(prog);        // once
 *   double *regs = malloc(sizeof *regs * rc->nreg * n);
 *   tex_rowcode_run(rc, n, regs, my_leaf, my_ctx);          // per row
 *   // the result is regs[0 .. n)
 *   tex_rowcode_free(rc);
 *
 * The code is scalar: a colour (three numbers, rgb()) or a palette call is
 * refused by tex_rowcode_new.  Operands are the language's: leaf(ctx, in,
 * n, out) fills out[0 .. n) with the operand of instruction in (in->leaf,
 * in->ptr as the parser left them) and returns 0, or -1 with an error,
 * which ends the run.  Constants are folded by the compiler already.
 */
#ifndef TEX_ROWCODE_H
#define TEX_ROWCODE_H

#include "expr.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_rinsn {
    enum tex_eop op; /* CONST, LEAF or a scalar operator */
    int dst, a, b, c; /* registers: the result and the operands (unused ones = a) */
    int leaf;         /* LEAF: the language's kind */
    const void *ptr;  /* LEAF: the language's operand */
    double v;         /* CONST */
};

struct tex_rowcode {
    int n, nreg;
    struct tex_rinsn *code;
};

typedef int (*tex_rowcode_leaf)(void *ctx, const struct tex_rinsn *in, int n, double *out);

/* Register code for x (malloc'd); NULL with an error for a colour or palette. */
struct tex_rowcode *tex_rowcode_new(const struct tex_expr *x);
void tex_rowcode_free(struct tex_rowcode *rc);
/* Run rc over n points with regs (rc->nreg * n doubles); the result is
 * regs[0 .. n).  Returns 0, or -1 when leaf failed. */
int tex_rowcode_run(const struct tex_rowcode *rc, int n, double *regs, tex_rowcode_leaf leaf,
                    void *ctx);

#ifdef __cplusplus
}
#endif
#endif
