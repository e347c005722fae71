/* expr.h - the one expression grammar and evaluator of Textura's languages
 *
 * Modelled on FFmpeg's libavutil/eval.c: one parser, one function table and
 * one set of limits serve every language that takes an expression.  A
 * scene's application function ("Kd = 0.5*f + 0.1*p", t_apply(5)) and a
 * composition script's image expression ("a over b + 0.2", t_compose(5))
 * are both read here; each language supplies only its operands (a scene:
 * f, p and texture maps, for a cascade; a script: images, primitives and
 * transforms) and its table of binary operators.
 *
 * Grammar (tokens from lang/lex.h):
 *
 *   expr    = unary { binop unary }     binops by the language's precedence,
 *                                       left to right within one precedence
 *   unary   = '-' unary | primary
 *   primary = number [number number]    three numbers: a colour (r g b)
 *           | '(' expr ')'
 *           | function '(' expr {',' expr} ')'
 *           | operand                   the language's own (a name, ...)
 *
 * Functions, the same in both languages (tex_expr_funcs[], whose help
 * column t_apply(5) and t_compose(5) list):
 *   min(a, b)  max(a, b)  abs(a)  rgb(r, g, b)
 *   mix(a, b, t)  smoothstep(e0, e1, x)  step(edge, x)  clamp(x, lo, hi)
 *   pow(a, b)  sin(a)  cos(a)  floor(a)  fract(a)  if(c, a, b)
 *   bias(b, t)  gain(g, t)     Perlin's (ops/remap.h's), as hypertexture modulates density
 * In a scene they act per colour channel on numbers; in a script on every
 * pixel of images (rgb takes numbers only there, and makes a colour).  A
 * language may add comparisons (< > <= >= == !=, 1 or 0) to its binary
 * operators, and its own operands that are calls (a scene's palette(NAME, x)
 * compiles to TEX_EOP_PALETTE).  tex_expr_op is the one definition of
 * every operator, for constant folding and for the languages' evaluators.
 *
 * Limits, the same in both languages, checked while parsing so that every
 * later walk is bounded: TEX_EXPR_MAX_DEPTH levels of nesting (parentheses,
 * unary minus, function arguments, a language's own operands) and
 * TEX_EXPR_MAX_TERMS binary operators in one expression.  A longer chain
 * such as "f + f + ..." is refused with "file:line:col: expression too
 * long (more than 10000 operators)"; no walk over a tree recurses along a
 * chain, so nothing can exhaust the C stack.
 *
 *   struct tex_expr_parser xp = {&lexer, &my_lang, my_ctx};
 *   struct tex_enode *e = tex_expr_parse(&xp);
 *   struct tex_expr *prog = tex_expr_compile(&lexer, e);   // for per-hit use
 *
 * The compiled form (struct tex_expr) is a flat postfix program for a stack
 * machine: constants, operands, operators.  Its user runs it with a loop and
 * a switch, without recursion or allocation (the renderer does so per ray
 * hit, in render/appfn.c); stack never exceeds TEX_EXPR_MAX_STACK.
 */
#ifndef TEX_EXPR_H
#define TEX_EXPR_H

#include <math.h>

#include "lex.h"
#include "../ops/remap.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TEX_EXPR_MAX_DEPTH 100   /* nesting of one expression */
#define TEX_EXPR_MAX_TERMS 10000 /* binary operators in one expression */
#define TEX_EXPR_MAX_STACK 512   /* a compiled program's stack, in values */

/* Operators of the compiled form; also the scene's binary operator codes. */
enum tex_eop {
    TEX_EOP_CONST, /* push v */
    TEX_EOP_LEAF,  /* push the language's operand (leaf, ptr) */
    TEX_EOP_NEG, TEX_EOP_ADD, TEX_EOP_SUB, TEX_EOP_MUL, TEX_EOP_DIV, /* x / 0 = 0 */
    TEX_EOP_MIN, TEX_EOP_MAX, TEX_EOP_ABS, TEX_EOP_RGB, /* channel k of argument k */
    TEX_EOP_LT, TEX_EOP_GT, TEX_EOP_LE, TEX_EOP_GE, TEX_EOP_EQ, TEX_EOP_NE, /* 1 or 0 */
    TEX_EOP_MIX, TEX_EOP_SMOOTHSTEP, TEX_EOP_STEP, TEX_EOP_CLAMP, TEX_EOP_POW, TEX_EOP_SIN,
    TEX_EOP_COS, TEX_EOP_FLOOR, TEX_EOP_FRACT, TEX_EOP_IF, TEX_EOP_BIAS, TEX_EOP_GAIN,
    TEX_EOP_PALETTE /* ptr: a tex_palette (ops/palette.h) at the mean of the argument */
};

/* The function table: name, arity, operator, one-line help. */
struct tex_expr_func {
    const char *name;
    int nargs;
    enum tex_eop op;
    const char *args; /* the arguments' names, for help: "a, b, t" */
    const char *help;
};
extern const struct tex_expr_func tex_expr_funcs[];
/* The row named by t (a name), or NULL. */
const struct tex_expr_func *tex_expr_func_find(const struct tex_tok *t);

/* The syntax tree. */
enum tex_ekind { TEX_EK_NUM, TEX_EK_RGB, TEX_EK_LEAF, TEX_EK_NEG, TEX_EK_BIN, TEX_EK_CALL };
struct tex_enode {
    enum tex_ekind kind;
    int op;          /* BIN: the language's operator code; CALL: enum tex_eop; LEAF: leaf kind */
    int line, col;
    double v[3];     /* NUM: v[0]; RGB: v */
    const void *ptr; /* LEAF: the language's operand */
    struct tex_enode *a, *b, *c; /* operands, arguments */
};

/* A binary operator: punctuation or a word, its precedence (higher binds
 * tighter, from 1) and the code left in the node. */
struct tex_expr_binop {
    const char *tok;
    int prec;
    int op;
};

/* The arithmetic operators over numbers, as scenes and composed primitives
 * write them: comparisons (1), + - (2), * / (3), codes enum tex_eop. */
extern const struct tex_expr_binop tex_expr_arith_binops[];

struct tex_expr_parser;
struct tex_expr_lang {
    const struct tex_expr_binop *binops; /* ends with a NULL tok */
    /* The operand at the current token (a name, a string, ...); fails with
     * "expected ..., found ..." when there is none there. */
    struct tex_enode *(*operand)(struct tex_expr_parser *xp);
};

struct tex_expr_parser {
    struct tex_lexer *lx;
    const struct tex_expr_lang *lang;
    void *ctx;   /* the language's parser */
    int depth;   /* nesting now */
    int nterms;  /* binary operators so far */
};

/* Parse an expression / one operand (no binary operator) at lx->t. */
struct tex_enode *tex_expr_parse(struct tex_expr_parser *xp);
struct tex_enode *tex_expr_unary(struct tex_expr_parser *xp);
/* Enter / leave one level of nesting (for a language's own operands). */
void tex_expr_enter(struct tex_expr_parser *xp);
void tex_expr_leave(struct tex_expr_parser *xp);
/* A new node at t's position, from the lexer's memory. */
struct tex_enode *tex_expr_node(struct tex_lexer *lx, enum tex_ekind kind, const struct tex_tok *t);

/* The compiled form: n instructions in postfix order. */
struct tex_einsn {
    enum tex_eop op;
    int leaf;        /* LEAF: the language's kind */
    double v[3];     /* CONST */
    const void *ptr; /* LEAF */
};
struct tex_expr {
    int n, depth; /* instructions; the most values on the stack */
    struct tex_einsn *code;
};

/* The number of values operator op takes from the stack. */
int tex_expr_arity(enum tex_eop op);

/* Every scalar operator (not CONST, LEAF, RGB or PALETTE: 0 for those), defined once:
 * constant folding, tex_expr_apply, tex_expr_apply_row, the composition scripts' pixels,
 * the renderer's hits and the polynomials below all compute through it.  Inline: where op
 * is a constant in a loop, the switch folds away and the loop vectorises. */
static inline double tex_expr_op(enum tex_eop op, double a, double b, double c)
{
    double x;
    switch (op) {
    case TEX_EOP_NEG: return -a;
    case TEX_EOP_ADD: return a + b;
    case TEX_EOP_SUB: return a - b;
    case TEX_EOP_MUL: return a * b;
    case TEX_EOP_DIV: return b != 0 ? a / b : 0;
    case TEX_EOP_MIN: return fmin(a, b);
    case TEX_EOP_MAX: return fmax(a, b);
    case TEX_EOP_ABS: return fabs(a);
    case TEX_EOP_LT: return a < b;
    case TEX_EOP_GT: return a > b;
    case TEX_EOP_LE: return a <= b;
    case TEX_EOP_GE: return a >= b;
    case TEX_EOP_EQ: return a == b;
    case TEX_EOP_NE: return a != b;
    case TEX_EOP_MIX: return a + (b - a) * c;
    case TEX_EOP_SMOOTHSTEP:
        /* e0 = e1: a step at e0 */
        x = b != a ? (c - a) / (b - a) : c >= a;
        x = !(x > 0) ? 0 : x < 1 ? x : 1;
        return x * x * (3 - 2 * x);
    case TEX_EOP_STEP: return b >= a;
    case TEX_EOP_CLAMP: return fmin(fmax(a, b), c);
    case TEX_EOP_POW:
        x = pow(a, b);
        return isfinite(x) ? x : 0;
    case TEX_EOP_SIN: return sin(a);
    case TEX_EOP_COS: return cos(a);
    case TEX_EOP_FLOOR: return floor(a);
    case TEX_EOP_FRACT: return a - floor(a);
    case TEX_EOP_IF: return a != 0 ? b : c;
    case TEX_EOP_BIAS: /* b outside (0, 1): 0 where that is not a real number, as pow */
        x = tex_bias(a, b);
        return isfinite(x) ? x : 0;
    case TEX_EOP_GAIN:
        x = tex_gain(a, b);
        return isfinite(x) ? x : 0;
    default: return 0; /* CONST, LEAF, RGB, PALETTE: not scalar operators */
    }
}

/* TEX_EOP_PALETTE: palette (a tex_palette) at the mean of the colour a, clamped to [0, 1],
 * into rgba: one lookup for the three channels. */
void tex_expr_palette(const void *palette, const double a[3], float rgba[4]);
/* tex_expr_palette at n colours a, into rgb (three floats each): the same floats, the
 * lookups together (tex_palette_lookup_n) */
void tex_expr_palette_n(const void *palette, const double (*a)[3], int n, float (*rgb)[3]);
/* Channel k of operator in->op (not CONST or LEAF) on the colours a, b, c
 * (as many as its arity; the others may be NULL). */
double tex_expr_apply(const struct tex_einsn *in, int k, const double *a, const double *b,
                      const double *c);

/* Scalar operator op (not CONST, LEAF, RGB or PALETTE) on rows: out[i] = op(a[i],
 * b[i], c[i]) for i < n, with the formulas of tex_expr_apply.  Every row is read
 * whatever the arity (pass a for the unused ones); out may be one of them.
 * Returns -1 for an operator that is not scalar. */
int tex_expr_apply_row(enum tex_eop op, int n, const double *a, const double *b,
                       const double *c, double *out);

/* Compile e (whose BIN codes are enum tex_eop) into the lexer's memory;
 * iterative, constants folded. */
struct tex_expr *tex_expr_compile(struct tex_lexer *lx, const struct tex_enode *e);

/* A compiled expression folded to a polynomial in two of its operands x and y, per channel
 * k: c[0][k] + c[1][k] x + c[2][k] y + c[3][k] x y, where it is at most linear in each
 * (the renderer's application functions of f and p, which it then evaluates without the
 * stack machine).  Its coefficients are computed through tex_expr_op. */
struct tex_expr_poly {
    double c[4][3];
    int dx, dy; /* degrees in x and y */
};
/* e's polynomial in its operands of leaf kinds x and y: 1, or 0 where it is not one (another
 * operand, a function, a product of degree 2 in x or y, a division by a non-constant) or
 * out of memory. */
int tex_expr_poly(const struct tex_expr *e, int x, int y, struct tex_expr_poly *r);

#ifdef __cplusplus
}
#endif
#endif
