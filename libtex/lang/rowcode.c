/* rowcode.c - postfix programs as register code over rows (see rowcode.h) */
#include <stdlib.h>

#include "base/error.h"
#include "lang/rowcode.h"

struct tex_rowcode *tex_rowcode_new(const struct tex_expr *x)
{
    struct tex_rowcode *rc = calloc(1, sizeof *rc);
    int sp = 0;

    if (!rc || !(rc->code = calloc(x->n ? x->n : 1, sizeof *rc->code))) {
        free(rc);
        tex_error("out of memory");
        return NULL;
    }
    for (int i = 0; i < x->n; i++) {
        const struct tex_einsn *e = &x->code[i];
        struct tex_rinsn *r = &rc->code[i];
        int k = tex_expr_arity(e->op);
        r->op = e->op;
        if (e->op == TEX_EOP_RGB || e->op == TEX_EOP_PALETTE ||
            (e->op == TEX_EOP_CONST && (e->v[1] != e->v[0] || e->v[2] != e->v[0]))) {
            tex_rowcode_free(rc);
            tex_usage_error("a colour where a number is needed");
            return NULL;
        }
        /* the k operands are the top k slots; the result replaces the first */
        r->dst = r->a = r->b = r->c = sp - k;
        if (k > 1)
            r->b = sp - k + 1;
        if (k > 2)
            r->c = sp - k + 2;
        r->leaf = e->leaf;
        r->ptr = e->ptr;
        r->v = e->v[0];
        sp += 1 - k;
        if (sp > rc->nreg)
            rc->nreg = sp;
    }
    rc->n = x->n;
    if (rc->nreg < 1)
        rc->nreg = 1;
    return rc;
}

void tex_rowcode_free(struct tex_rowcode *rc)
{
    if (rc)
        free(rc->code);
    free(rc);
}

int tex_rowcode_run(const struct tex_rowcode *rc, int n, double *regs, tex_rowcode_leaf leaf,
                    void *ctx)
{
    for (int i = 0; i < rc->n; i++) {
        const struct tex_rinsn *r = &rc->code[i];
        double *d = regs + (size_t)r->dst * n;
        if (r->op == TEX_EOP_CONST) {
            for (int j = 0; j < n; j++)
                d[j] = r->v;
        } else if (r->op == TEX_EOP_LEAF) {
            if (leaf(ctx, r, n, d) < 0)
                return -1;
        } else {
            tex_expr_apply_row(r->op, n, regs + (size_t)r->a * n, regs + (size_t)r->b * n,
                               regs + (size_t)r->c * n, d);
        }
    }
    return 0;
}
