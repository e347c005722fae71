/* expr.c - the shared expression parser, function table and compiler (see expr.h) */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/expr.h"
#include "ops/palette.h"

const struct tex_expr_func tex_expr_funcs[] = {
    {"min", 2, TEX_EOP_MIN, "a, b", "the smaller of a and b"},
    {"max", 2, TEX_EOP_MAX, "a, b", "the larger of a and b"},
    {"abs", 1, TEX_EOP_ABS, "a", "the absolute value of a"},
    {"rgb", 3, TEX_EOP_RGB, "r, g, b", "a colour: red from r, green from g, blue from b"},
    {"mix", 3, TEX_EOP_MIX, "a, b, t",
     "a where t is 0, b where t is 1, linear between: a + (b - a) t"},
    {"smoothstep", 3, TEX_EOP_SMOOTHSTEP, "e0, e1, x",
     "0 below e0, 1 above e1, the cubic 3s^2 - 2s^3 between (s = (x - e0) / (e1 - e0))"},
    {"step", 2, TEX_EOP_STEP, "edge, x", "0 where x < edge, else 1"},
    {"clamp", 3, TEX_EOP_CLAMP, "x, lo, hi", "x limited to [lo, hi]"},
    {"pow", 2, TEX_EOP_POW, "a, b", "a to the power b; 0 where that is not a real number"},
    {"sin", 1, TEX_EOP_SIN, "a", "the sine of a (radians)"},
    {"cos", 1, TEX_EOP_COS, "a", "the cosine of a (radians)"},
    {"floor", 1, TEX_EOP_FLOOR, "a", "the largest integer not above a"},
    {"fract", 1, TEX_EOP_FRACT, "a", "a - floor(a), in [0, 1)"},
    {"if", 3, TEX_EOP_IF, "c, a, b", "a where c is not 0, else b (per channel)"},
    {"bias", 2, TEX_EOP_BIAS, "b, t",
     "Perlin's bias: t^(ln b / ln 0.5), t clamped to [0, 1]; b where t is 0.5"},
    {"gain", 2, TEX_EOP_GAIN, "g, t",
     "Perlin's gain, two bias curves: bias(1 - g, 2t) / 2 below t = 0.5, "
     "1 - bias(1 - g, 2 - 2t) / 2 above"},
    {NULL, 0, 0, NULL, NULL},
};

const struct tex_expr_binop tex_expr_arith_binops[] = {
    {"<", 1, TEX_EOP_LT},  {">", 1, TEX_EOP_GT},  {"<=", 1, TEX_EOP_LE}, {">=", 1, TEX_EOP_GE},
    {"==", 1, TEX_EOP_EQ}, {"!=", 1, TEX_EOP_NE}, {"+", 2, TEX_EOP_ADD}, {"-", 2, TEX_EOP_SUB},
    {"*", 3, TEX_EOP_MUL}, {"/", 3, TEX_EOP_DIV}, {NULL, 0, 0}};

const struct tex_expr_func *tex_expr_func_find(const struct tex_tok *t)
{
    for (const struct tex_expr_func *f = tex_expr_funcs; f->name; f++)
        if (tex_tok_is_word(t, f->name))
            return f;
    return NULL;
}


struct tex_enode *tex_expr_node(struct tex_lexer *lx, enum tex_ekind kind, const struct tex_tok *t)
{
    struct tex_enode *e = lx->alloc(lx->ctx, sizeof *e);
    e->kind = kind;
    e->line = t->line;
    e->col = t->col;
    return e;
}

void tex_expr_enter(struct tex_expr_parser *xp)
{
    if (++xp->depth > TEX_EXPR_MAX_DEPTH)
        tex_lex_fail(xp->lx, xp->lx->t.line, xp->lx->t.col,
                     "expression nested too deeply (more than %d levels)", TEX_EXPR_MAX_DEPTH);
}

void tex_expr_leave(struct tex_expr_parser *xp)
{
    xp->depth--;
}


static double number(struct tex_lexer *lx)
{
    char b[48];
    double v = lx->t.num;
    if (lx->t.kind != TEX_TOK_NUM)
        tex_lex_fail(lx, lx->t.line, lx->t.col, "expected a number, found %s",
                     tex_tok_desc(&lx->t, b, sizeof b));
    tex_lex_next(lx);
    return v;
}

/* Is the token after the current one an opening parenthesis? */
static int paren_follows(const struct tex_lexer *lx)
{
    struct tex_lexer peek = *lx;
    tex_lex_next(&peek);
    return tex_tok_is_punct(&peek.t, '(');
}

static struct tex_enode *call(struct tex_expr_parser *xp, const struct tex_expr_func *f)
{
    struct tex_lexer *lx = xp->lx;
    struct tex_enode *e = tex_expr_node(lx, TEX_EK_CALL, &lx->t), **arg[3];
    int n = 0;

    e->op = f->op;
    arg[0] = &e->a, arg[1] = &e->b, arg[2] = &e->c;
    tex_lex_next(lx);
    tex_lex_expect(lx, '(');
    while (!tex_tok_is_punct(&lx->t, ')')) {
        if (n && !tex_tok_is_punct(&lx->t, ','))
            tex_lex_expect(lx, ')');
        if (n)
            tex_lex_next(lx);
        if (n == f->nargs)
            tex_lex_fail(lx, e->line, e->col, "%s takes %d argument%s", f->name, f->nargs,
                         f->nargs > 1 ? "s" : "");
        *arg[n++] = tex_expr_parse(xp);
    }
    if (n != f->nargs)
        tex_lex_fail(lx, e->line, e->col, "%s takes %d argument%s", f->name, f->nargs,
                     f->nargs > 1 ? "s" : "");
    tex_lex_next(lx);
    return e;
}

static struct tex_enode *primary(struct tex_expr_parser *xp)
{
    struct tex_lexer *lx = xp->lx;
    struct tex_tok t = lx->t;
    const struct tex_expr_func *f;
    struct tex_enode *e;

    if (t.kind == TEX_TOK_NUM) {
        e = tex_expr_node(lx, TEX_EK_NUM, &t);
        e->v[0] = number(lx);
        /* three numbers in a row: a colour */
        if (lx->t.kind == TEX_TOK_NUM && !tex_tok_is_signed(&lx->t)) {
            e->kind = TEX_EK_RGB;
            e->v[1] = number(lx);
            e->v[2] = number(lx);
        }
        return e;
    }
    if (tex_tok_is_punct(&t, '(')) {
        tex_lex_next(lx);
        e = tex_expr_parse(xp);
        tex_lex_expect(lx, ')');
        return e;
    }
    if (t.kind == TEX_TOK_NAME && (f = tex_expr_func_find(&t)) && paren_follows(lx))
        return call(xp, f);
    return xp->lang->operand(xp);
}

struct tex_enode *tex_expr_unary(struct tex_expr_parser *xp)
{
    struct tex_lexer *lx = xp->lx;
    struct tex_enode *e;

    tex_expr_enter(xp);
    if (tex_tok_is_punct(&lx->t, '-')) {
        struct tex_tok t = lx->t;
        tex_lex_next(lx);
        e = tex_expr_unary(xp);
        if (e->kind == TEX_EK_NUM) {
            e->v[0] = -e->v[0];
        } else {
            struct tex_enode *n = tex_expr_node(lx, TEX_EK_NEG, &t);
            n->a = e;
            e = n;
        }
    } else {
        e = primary(xp);
    }
    tex_expr_leave(xp);
    return e;
}

/* The binary operator at the current token, or NULL.  A signed number after an
 * operand is the operator of its sign ("f -1" is "f - 1"). */
static const struct tex_expr_binop *binop(const struct tex_expr_parser *xp)
{
    const struct tex_tok *t = &xp->lx->t;
    for (const struct tex_expr_binop *o = xp->lang->binops; o->tok; o++) {
        int c = o->tok[0];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'))) {
            if (tex_tok_is_op(t, o->tok) ||
                (o->tok[1] == '\0' && tex_tok_is_signed(t) && t->text[0] == c))
                return o;
        } else if (tex_tok_is_word(t, o->tok)) {
            return o;
        }
    }
    return NULL;
}

static struct tex_enode *chain(struct tex_expr_parser *xp, int prec)
{
    struct tex_lexer *lx = xp->lx;
    struct tex_enode *e = tex_expr_unary(xp);
    const struct tex_expr_binop *o;

    while ((o = binop(xp)) && o->prec >= prec) {
        struct tex_enode *b = tex_expr_node(lx, TEX_EK_BIN, &lx->t);
        if (++xp->nterms > TEX_EXPR_MAX_TERMS)
            tex_lex_fail(lx, lx->t.line, lx->t.col,
                         "expression too long (more than %d operators)", TEX_EXPR_MAX_TERMS);
        if (lx->t.kind == TEX_TOK_NUM) { /* the sign is the operator: keep the number */
            if (lx->t.text[0] == '-')
                lx->t.num = -lx->t.num;
            lx->t.text++;
            lx->t.len--;
            lx->t.col++;
        } else {
            tex_lex_next(lx);
        }
        b->op = o->op;
        b->a = e;
        b->b = chain(xp, o->prec + 1);
        e = b;
    }
    return e;
}

struct tex_enode *tex_expr_parse(struct tex_expr_parser *xp)
{
    return chain(xp, 1);
}

/* ---- compiling ---- */

struct compiler {
    struct tex_lexer *lx;
    struct tex_einsn *code;
    int n, cap, sp, depth;
    const struct tex_enode **todo; /* the walk's stack: nodes, a flag in the low bit */
    int ntodo, captodo;
};

static void oom(struct compiler *c) __attribute__((noreturn));

static void oom(struct compiler *c)
{
    free(c->code);
    free(c->todo);
    tex_error("%s:%d:%d: out of memory", c->lx->name, c->lx->t.line, c->lx->t.col);
    longjmp(*c->lx->fail, 1);
}

static void emit(struct compiler *c, const struct tex_einsn *in)
{
    if (c->n == c->cap) {
        int cap = c->cap ? 2 * c->cap : 16;
        struct tex_einsn *a = realloc(c->code, cap * sizeof *a);
        if (!a)
            oom(c);
        c->code = a;
        c->cap = cap;
    }
    c->code[c->n++] = *in;
}

int tex_expr_arity(enum tex_eop op)
{
    switch (op) {
    case TEX_EOP_CONST:
    case TEX_EOP_LEAF: return 0;
    case TEX_EOP_NEG:
    case TEX_EOP_ABS:
    case TEX_EOP_SIN:
    case TEX_EOP_COS:
    case TEX_EOP_FLOOR:
    case TEX_EOP_FRACT:
    case TEX_EOP_PALETTE: return 1;
    case TEX_EOP_RGB:
    case TEX_EOP_MIX:
    case TEX_EOP_SMOOTHSTEP:
    case TEX_EOP_CLAMP:
    case TEX_EOP_IF: return 3;
    default: return 2;
    }
}

/* Where a palette takes colour a: its mean, clamped to [0, 1] */
static float palette_at(const double a[3])
{
    return tex_palette_t((a[0] + a[1] + a[2]) / 3, 0, 1, TEX_OUTSIDE_CLAMP);
}

void tex_expr_palette(const void *palette, const double a[3], float rgba[4])
{
    tex_palette_lookup(palette, palette_at(a), rgba);
}

void tex_expr_palette_n(const void *palette, const double (*a)[3], int n, float (*rgb)[3])
{
    float t[256];
    for (int i = 0; i < n; i += 256) {
        int m = n - i < 256 ? n - i : 256;
        for (int j = 0; j < m; j++)
            t[j] = palette_at(a[i + j]);
        tex_palette_lookup_n(palette, t, m, rgb[i]);
    }
}

double tex_expr_apply(const struct tex_einsn *in, int k, const double *a, const double *b,
                      const double *c)
{
    int n = tex_expr_arity(in->op);
    switch (in->op) {
    case TEX_EOP_PALETTE: {
        float rgba[4];
        tex_expr_palette(in->ptr, a, rgba);
        return rgba[k];
    }
    case TEX_EOP_RGB: return (k == 0 ? a : k == 1 ? b : c)[k];
    default: return tex_expr_op(in->op, a[k], n > 1 ? b[k] : 0, n > 2 ? c[k] : 0);
    }
}

int tex_expr_apply_row(enum tex_eop op, int n, const double *a, const double *b,
                       const double *c, double *out)
{
#define ROW(OP)                                                                                  \
    case OP:                                                                                     \
        for (int i = 0; i < n; i++)                                                              \
            out[i] = tex_expr_op(OP, a[i], b[i], c[i]);                                            \
        return 0
    switch (op) {
    ROW(TEX_EOP_NEG); ROW(TEX_EOP_ADD); ROW(TEX_EOP_SUB); ROW(TEX_EOP_MUL); ROW(TEX_EOP_DIV);
    ROW(TEX_EOP_MIN); ROW(TEX_EOP_MAX); ROW(TEX_EOP_ABS); ROW(TEX_EOP_LT); ROW(TEX_EOP_GT);
    ROW(TEX_EOP_LE); ROW(TEX_EOP_GE); ROW(TEX_EOP_EQ); ROW(TEX_EOP_NE); ROW(TEX_EOP_MIX);
    ROW(TEX_EOP_SMOOTHSTEP); ROW(TEX_EOP_STEP); ROW(TEX_EOP_CLAMP); ROW(TEX_EOP_POW);
    ROW(TEX_EOP_SIN); ROW(TEX_EOP_COS); ROW(TEX_EOP_FLOOR); ROW(TEX_EOP_FRACT); ROW(TEX_EOP_IF);
    ROW(TEX_EOP_BIAS); ROW(TEX_EOP_GAIN);
    default: return -1;
    }
#undef ROW
}

/* Emit operator op at node e (ptr: e's operand); constant operands are folded. */
static void emit_op(struct compiler *c, enum tex_eop op, const struct tex_enode *e)
{
    int k = tex_expr_arity(op), folded = c->n >= k;
    struct tex_einsn in = {op, 0, {0}, e->kind == TEX_EK_CALL ? e->ptr : NULL};
    for (int i = 1; folded && i <= k; i++)
        folded = c->code[c->n - i].op == TEX_EOP_CONST;
    if (folded) {
        struct tex_einsn r = {TEX_EOP_CONST, 0, {0}, NULL}, *o = c->code + c->n - k;
        for (int ch = 0; ch < 3; ch++)
            r.v[ch] = tex_expr_apply(&in, ch, o[0].v, k > 1 ? o[1].v : NULL,
                                     k > 2 ? o[2].v : NULL);
        c->n -= k;
        emit(c, &r);
    } else {
        emit(c, &in);
    }
    c->sp += 1 - k;
}

static void emit_leaf(struct compiler *c, const struct tex_enode *e)
{
    struct tex_einsn in = {TEX_EOP_CONST, 0, {e->v[0], e->v[0], e->v[0]}, NULL};
    if (e->kind == TEX_EK_RGB)
        in.v[1] = e->v[1], in.v[2] = e->v[2];
    else if (e->kind == TEX_EK_LEAF)
        in = (struct tex_einsn){TEX_EOP_LEAF, e->op, {0}, e->ptr};
    emit(c, &in);
    if (++c->sp > c->depth && (c->depth = c->sp) > TEX_EXPR_MAX_STACK) {
        free(c->code);
        free(c->todo);
        tex_lex_fail(c->lx, e->line, e->col, "expression too complex (more than %d values "
                     "pending)", TEX_EXPR_MAX_STACK);
    }
}

static void push(struct compiler *c, const struct tex_enode *e, int visited)
{
    if (!e)
        return;
    if (c->ntodo == c->captodo) {
        int cap = c->captodo ? 2 * c->captodo : 64;
        const struct tex_enode **a = realloc(c->todo, cap * sizeof *a);
        if (!a)
            oom(c);
        c->todo = a;
        c->captodo = cap;
    }
    c->todo[c->ntodo++] = (const struct tex_enode *)((uintptr_t)e | (uintptr_t)visited);
}

struct tex_expr *tex_expr_compile(struct tex_lexer *lx, const struct tex_enode *root)
{
    struct compiler c = {lx, NULL, 0, 0, 0, 0, NULL, 0, 0};

    push(&c, root, 0);
    while (c.ntodo) { /* post-order with an explicit stack: chains cost no C stack */
        uintptr_t top = (uintptr_t)c.todo[--c.ntodo];
        const struct tex_enode *e = (const struct tex_enode *)(top & ~(uintptr_t)1);
        if (e->kind == TEX_EK_NUM || e->kind == TEX_EK_RGB || e->kind == TEX_EK_LEAF) {
            emit_leaf(&c, e);
        } else if (top & 1) {
            emit_op(&c, e->kind == TEX_EK_NEG ? TEX_EOP_NEG : (enum tex_eop)e->op, e);
        } else {
            push(&c, e, 1);
            push(&c, e->c, 0);
            push(&c, e->b, 0);
            push(&c, e->a, 0);
        }
    }
    struct tex_expr *x = lx->alloc(lx->ctx, sizeof *x);
    x->code = lx->alloc(lx->ctx, (c.n ? c.n : 1) * sizeof *x->code);
    memcpy(x->code, c.code, c.n * sizeof *x->code);
    x->n = c.n;
    x->depth = c.depth;
    free(c.code);
    free(c.todo);
    return x;
}

/* a op b (a binary operator), in a; 0 if the result is not such a polynomial.  The
 * coefficients of a sum, a difference, a product or a quotient by a constant are the
 * operator's own on them (tex_expr_op). */
static int poly_op(enum tex_eop op, struct tex_expr_poly *a, const struct tex_expr_poly *b)
{
    struct tex_expr_poly r = {{{0}}, a->dx | b->dx, a->dy | b->dy};
    const double(*x)[3] = a->c, (*y)[3] = b->c;
    switch (op) {
    case TEX_EOP_ADD:
    case TEX_EOP_SUB:
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                r.c[i][k] = tex_expr_op(op, x[i][k], y[i][k], 0);
        break;
    case TEX_EOP_MUL: /* (x0 + x1 X + x2 Y + x3 XY)(y0 + ...), of degree 1 in each */
        if (a->dx + b->dx > 1 || a->dy + b->dy > 1)
            return 0;
        for (int k = 0; k < 3; k++) {
            double m[4][4]; /* m[i][j] = x_i y_j */
            for (int i = 0; i < 4; i++)
                for (int j = 0; j < 4; j++)
                    m[i][j] = tex_expr_op(TEX_EOP_MUL, x[i][k], y[j][k], 0);
            r.c[0][k] = m[0][0];
            r.c[1][k] = tex_expr_op(TEX_EOP_ADD, m[0][1], m[1][0], 0);
            r.c[2][k] = tex_expr_op(TEX_EOP_ADD, m[0][2], m[2][0], 0);
            r.c[3][k] = tex_expr_op(TEX_EOP_ADD, m[0][3], m[3][0], 0);
            r.c[3][k] = tex_expr_op(TEX_EOP_ADD, r.c[3][k], m[1][2], 0);
            r.c[3][k] = tex_expr_op(TEX_EOP_ADD, r.c[3][k], m[2][1], 0);
        }
        break;
    case TEX_EOP_DIV: /* by a constant; by 0 gives 0, as the operator does */
        if (b->dx || b->dy)
            return 0;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                r.c[i][k] = tex_expr_op(op, x[i][k], y[0][k], 0);
        r.dx = a->dx;
        r.dy = a->dy;
        break;
    default: /* min, max, comparisons: not polynomials */
        return 0;
    }
    *a = r;
    return 1;
}

int tex_expr_poly(const struct tex_expr *e, int x, int y, struct tex_expr_poly *r)
{
    struct tex_expr_poly *st = malloc((e->depth ? e->depth : 1) * sizeof *st);
    int sp = 0, ok = st != NULL;
    for (int i = 0; ok && i < e->n; i++) {
        const struct tex_einsn *in = &e->code[i];
        struct tex_expr_poly *a = &st[sp - 1];
        switch (in->op) {
        case TEX_EOP_CONST:
            a = &st[sp++];
            memset(a, 0, sizeof *a);
            for (int k = 0; k < 3; k++)
                a->c[0][k] = in->v[k];
            break;
        case TEX_EOP_LEAF:
            a = &st[sp++];
            memset(a, 0, sizeof *a);
            ok = in->leaf == x || in->leaf == y;
            for (int k = 0; k < 3; k++)
                a->c[in->leaf == x ? 1 : 2][k] = 1;
            a->dx = in->leaf == x;
            a->dy = in->leaf == y;
            break;
        case TEX_EOP_NEG:
            for (int j = 0; j < 4; j++)
                for (int k = 0; k < 3; k++)
                    a->c[j][k] = tex_expr_op(TEX_EOP_NEG, a->c[j][k], 0, 0);
            break;
        case TEX_EOP_RGB: /* channel k of argument k */
            sp -= 2;
            a = &st[sp - 1];
            for (int j = 0; j < 4; j++)
                a->c[j][1] = a[1].c[j][1], a->c[j][2] = a[2].c[j][2];
            a->dx |= a[1].dx | a[2].dx;
            a->dy |= a[1].dy | a[2].dy;
            break;
        default:
            if (tex_expr_arity(in->op) != 2) { /* abs, the functions: not polynomials */
                ok = 0;
                break;
            }
            sp--;
            ok = poly_op(in->op, &st[sp - 1], &st[sp]);
            break;
        }
    }
    if (ok)
        *r = st[0];
    free(st);
    return ok;
}
