/* script.c - parser and interpreter of the pattern composition language
 *
 * Tokens come from lang/lex.h and image expressions from lang/expr.h, as in
 * scenes; this file adds the script's operands (images, primitives, transforms)
 * and their meaning on whole maps. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "ops/compose.h"
#include "base/error.h"
#include "base/names.h"
#include "base/progress.h"
#include "io/file.h"
#include "prim/prim.h"
#include "lang/script.h"
#include "ops/transform.h"
#include "ops/filter_ops.h"
#include "lang/expr.h"
#include "lang/lex.h"
#include "lang/proc.h"

#define MAX_EVAL_DEPTH 500 /* chains of definitions */

/* ---- syntax tree ---- */

/* The tessellations: the canvas cut into rectangles, hexagons, triangles or rows of
 * bricks. */
enum tess { T_RECTANGULAR, T_HEXAGONAL, T_TRIANGULAR, T_BRICK };
static const char *const tess_names[] = {"rectangular", "hexagonal", "triangular", "brick", NULL};

enum nk { N_REF, N_FILE, N_PRIM, N_NUM, N_EXPR, N_EXPAND, N_ROTATE, N_SCALE, N_RESIZE, N_SHIFT,
          N_CLIP, N_FILTER, N_TILE, N_MATRIX, N_WARP, N_MIX };

struct param {
    char *name, *value;
    int line, col;
};

struct node {
    enum nk k;
    int line, col;
    int op;               /* N_MATRIX: enum tex_rule */
    const struct filter *filter; /* N_FILTER: the script's own filter, or NULL */
    const struct tex_filter_op *fop; /* N_FILTER: else t_filter's, with fargs */
    struct tex_filter_args *fargs;
    struct tex_enode *x;  /* N_EXPR: an expression of lang/expr.h */
    int flag;             /* wrap, mirror, isotropic, background given */
    char *s;              /* name, file, primitive */
    struct node *a, *b, *c;
    struct node **list;   /* N_MATRIX */
    int nlist;
    double v[4];          /* numbers of the operation */
    float colour[4];
    struct param *params;
    int nparams;
    int w, h;             /* an explicit size, 0 if none */
    struct def *def;      /* N_REF, once resolved */
};

struct def {
    char *name;
    struct node *expr;
    int line, col;   /* where it was defined (or declared) */
    int state;       /* 0 not evaluated, 1 being evaluated, 2 done */
    tex_map *map;
};

struct cellref {
    int i, j, line, col;
    struct node *expr;
};

struct chunk {
    struct chunk *next;
    max_align_t data[];
};

struct S {
    const char *name;
    struct tex_lexer lx;  /* lx.t: the current token */
    struct tex_expr_parser xp;
    jmp_buf fail;
    struct chunk *arena;
    const struct tex_script_opts *o;
    /* what the script says */
    char *title;
    int have_kind, have_size, w, h, cw, ch;
    enum tess kind;
    float bg[4];
    struct def *defs;
    int ndefs, capdefs;
    struct tex_names defnames; /* index + 1 of each def by name: a walk per name was quadratic */
    struct node **refs;
    int nrefs, caprefs;
    struct cellref *cells;
    int ncells, capcells;
    struct tex_names cellnames; /* "I,J" to the line of its cell: a walk per cell was quadratic */
    int evaldepth, stdin_used;
    struct tex_procs *procs; /* the script's composed primitives */
};

static void *arena(struct S *s, size_t n)
{
    struct chunk *c = calloc(1, sizeof *c + n);

    if (!c) {
        tex_error("out of memory");
        longjmp(s->fail, 1);
    }
    c->next = s->arena;
    s->arena = c;
    return c->data;
}

static void *lex_alloc(void *ctx, size_t n)
{
    return arena(ctx, n);
}

/* Grow an array of elements of size sz to hold one more. */
static void *grow(struct S *s, void *a, int *cap, int n, size_t sz)
{
    void *b;
    if (n < *cap)
        return a;
    *cap = *cap ? 2 * *cap : 16;
    if (!(b = realloc(a, *cap * sz))) {
        tex_error("out of memory");
        longjmp(s->fail, 1);
    }
    return b;
}

static void fail_at(struct S *s, int line, int col, const char *fmt, ...)
    __attribute__((noreturn, format(printf, 4, 5)));

static void fail_at(struct S *s, int line, int col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    tex_lex_vfail(&s->lx, TEX_ERR_USAGE, line, col, fmt, ap);
}

static void next(struct S *s)
{
    tex_lex_next(&s->lx);
}

/* Keywords as the thesis writes them: in Portuguese, and its operations' capitals
 * (Rotate(a, P)).  Each row: the word, the keyword it stands for. */
static const char *const aliases[][2] = {
    {"celula", "cell"},        {"retangular", "rectangular"}, {"tijolo", "brick"},
    {"tamanho", "size"},       {"fundo", "background"},       {"imagens", "images"},
    {"expandir", "expand"},    {"rotacionar", "rotate"},      {"escalar", "scale"},
    {"deslocar", "shift"},     {"recortar", "clipping"},      {"filtro", "filter"},
    {"Rotate", "rotate"},      {"Scale", "scale"},            {"Shift", "shift"},
    {"Filter", "filter"},
};

static int is_word(const struct S *s, const char *w)
{
    if (tex_tok_is_word(&s->lx.t, w))
        return 1;
    for (size_t i = 0; i < sizeof aliases / sizeof *aliases; i++)
        if (!strcmp(aliases[i][1], w) && tex_tok_is_word(&s->lx.t, aliases[i][0]))
            return 1;
    return 0;
}

static int is_punct(const struct S *s, char c)
{
    return tex_tok_is_punct(&s->lx.t, c);
}

static const char *tok_desc(struct S *s)
{
    static _Thread_local char buf[48];
    switch (s->lx.t.kind) {
    case TEX_TOK_EOF: return "the end of the script";
    case TEX_TOK_STR: return "a string";
    case TEX_TOK_NUM: return "a number";
    default:
        snprintf(buf, sizeof buf, "'%.*s'", (int)(s->lx.t.len > 32 ? 32 : s->lx.t.len), s->lx.t.text);
        return buf;
    }
}

static void expect_word(struct S *s, const char *w)
{
    if (!is_word(s, w))
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected '%s', found %s", w, tok_desc(s));
    next(s);
}

static void expect_punct(struct S *s, char c)
{
    if (!is_punct(s, c))
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected '%c', found %s", c, tok_desc(s));
    next(s);
}

static int accept_word(struct S *s, const char *w)
{
    if (!is_word(s, w))
        return 0;
    next(s);
    return 1;
}

static char *take_name(struct S *s, const char *what)
{
    char *n;
    if (s->lx.t.kind != TEX_TOK_NAME)
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected %s, found %s", what, tok_desc(s));
    n = arena(s, s->lx.t.len + 1);
    memcpy(n, s->lx.t.text, s->lx.t.len);
    next(s);
    return n;
}

static double number(struct S *s)
{
    int neg = 0;
    double v;
    if (is_punct(s, '-')) {
        neg = 1;
        next(s);
    }
    if (s->lx.t.kind != TEX_TOK_NUM)
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected a number, found %s", tok_desc(s));
    v = neg ? -s->lx.t.num : s->lx.t.num;
    next(s);
    return v;
}

/* A whole number in lo..hi. */
static int integer(struct S *s, long lo, long hi, const char *what)
{
    int line = s->lx.t.line, col = s->lx.t.col;
    double v = number(s);
    if (v != floor(v) || v < lo || v > hi)
        fail_at(s, line, col, "%s must be a whole number in %ld..%ld (got %g)", what, lo, hi, v);
    return (int)v;
}

static void size_pair(struct S *s, int *w, int *h, const char *what)
{
    *w = integer(s, 1, TEX_MAP_MAX_SIDE, what);
    expect_word(s, "by");
    *h = integer(s, 1, TEX_MAP_MAX_SIDE, what);
}

/* 1-4 numbers in 0..1: grey, grey+alpha, RGB, RGBA (straight alpha). */
static void colour(struct S *s, float rgba[4])
{
    double v[4];
    int n = 0, line = s->lx.t.line, col = s->lx.t.col;
    do {
        if (n == 4)
            fail_at(s, line, col, "a colour has 1 to 4 values");
        v[n++] = number(s);
    } while (is_punct(s, ',') && (next(s), 1));
    for (int i = 0; i < n; i++)
        if (v[i] < 0 || v[i] > 1)
            fail_at(s, line, col, "colour values must be in 0..1 (got %g)", v[i]);
    rgba[0] = (float)v[0];
    rgba[1] = (float)(n >= 3 ? v[1] : v[0]);
    rgba[2] = (float)(n >= 3 ? v[2] : v[0]);
    rgba[3] = (float)(n == 2 ? v[1] : n == 4 ? v[3] : 1.0);
}

static struct node *new_node(struct S *s, enum nk k, int line, int col)
{
    struct node *n = arena(s, sizeof *n);
    n->k = k;
    n->line = line;
    n->col = col;
    return n;
}

static struct node *unary(struct S *s);
static struct node *expr(struct S *s);

/* A file, an image's name or a primitive call (numbers and parentheses are lang/expr.c's). */
static struct node *primary(struct S *s)
{
    int line = s->lx.t.line, col = s->lx.t.col;
    struct node *n;

    if (s->lx.t.kind == TEX_TOK_STR) {
        n = new_node(s, N_FILE, line, col);
        n->s = arena(s, s->lx.t.len + 1);
        memcpy(n->s, s->lx.t.text, s->lx.t.len);
        if (memchr(n->s, '\0', s->lx.t.len))
            fail_at(s, line, col, "NUL byte in a string");
        next(s);
        if (s->lx.t.kind == TEX_TOK_NUM && !tex_tok_is_signed(&s->lx.t))
            size_pair(s, &n->w, &n->h, "an image size");
        return n;
    }
    if (s->lx.t.kind != TEX_TOK_NAME)
        fail_at(s, line, col, "expected an image, found %s", tok_desc(s));
    n = new_node(s, N_REF, line, col);
    n->s = take_name(s, "an image name");
    if (!is_punct(s, '(')) { /* an image, or a file by its bare name (the thesis's leo) */
        s->refs = grow(s, s->refs, &s->caprefs, s->nrefs, sizeof *s->refs);
        s->refs[s->nrefs++] = n;
        if (s->lx.t.kind == TEX_TOK_NUM && !tex_tok_is_signed(&s->lx.t))
            size_pair(s, &n->w, &n->h, "an image size");
        return n;
    }
    /* A primitive call: name(param = value, ...) [W by H]. */
    n->k = N_PRIM;
    next(s);
    while (!is_punct(s, ')')) {
        struct param *p;
        if (n->nparams == 64)
            fail_at(s, s->lx.t.line, s->lx.t.col, "too many parameters");
        if (!n->params)
            n->params = arena(s, 64 * sizeof *n->params);
        p = &n->params[n->nparams++];
        p->line = s->lx.t.line;
        p->col = s->lx.t.col;
        p->name = take_name(s, "a parameter name");
        expect_punct(s, '=');
        if (s->lx.t.kind == TEX_TOK_NAME || s->lx.t.kind == TEX_TOK_STR) {
            p->value = arena(s, s->lx.t.len + 1);
            memcpy(p->value, s->lx.t.text, s->lx.t.len);
            next(s);
        } else {
            double v = number(s);
            p->value = arena(s, 40);
            snprintf(p->value, 40, "%.17g", v);
        }
        if (!is_punct(s, ')'))
            expect_punct(s, ',');
    }
    next(s);
    if (s->lx.t.kind == TEX_TOK_NUM && !tex_tok_is_signed(&s->lx.t))
        size_pair(s, &n->w, &n->h, "an image size");
    return n;
}

/* filter NAME IMAGE [by BY]: the filters, each a function of the map and BY. */
static tex_map *filter_blur(const tex_map *m, double by)
{
    return tex_blur(m, by);
}

static tex_map *filter_op(enum tex_op op, const tex_map *m, double by)
{
    struct tex_operand a = {m, 0, {0}}, b = {NULL, 1, {(float)by}};
    return tex_op_apply(op, &a, op == TEX_OP_THRESHOLD ? &b : NULL, NULL, by);
}

static tex_map *filter_threshold(const tex_map *m, double by)
{
    return filter_op(TEX_OP_THRESHOLD, m, by);
}

static tex_map *filter_invert(const tex_map *m, double by)
{
    return filter_op(TEX_OP_INVERT, m, by);
}

static tex_map *filter_abs(const tex_map *m, double by)
{
    return filter_op(TEX_OP_ABS, m, by);
}

struct filter {
    const char *name;
    tex_map *(*fn)(const tex_map *m, double by);
    double by;  /* BY's default */
    int radius; /* BY is a blur radius: at most max_blur */
    const char *help;
};

static const struct filter filters[] = {
    {"blur", filter_blur, 1.0, 1, "Gaussian blur, BY the radius (sigma) in pixels"},
    {"threshold", filter_threshold, 0.5, 0, "1 where the image is above BY, else 0"},
    {"invert", filter_invert, 1.0, 0, "1 - the image"},
    {"abs", filter_abs, 1.0, 0, "the absolute value of the image"},
    {NULL, NULL, 0, 0, NULL},
};

/* matrix RULE by I, J of IMAGES: how the images are laid out. */
static const struct rule {
    const char *name;
    enum tex_rule rule;
    const char *help;
} rules[] = {
    {"diagonal", TEX_RULE_DIAGONAL, "the first image on the diagonal, the second elsewhere"},
    {"checker", TEX_RULE_CHECKER, "the images alternate like a chequerboard"},
    {"rows", TEX_RULE_ROWS, "one image per row, in turn"},
    {"columns", TEX_RULE_COLUMNS, "one image per column, in turn"},
    {"cycle", TEX_RULE_CYCLE, "the images in turn, row by row"},
    {NULL, 0, NULL},
};

/* The row of a table (rows of size stride, each starting with its name, the
 * last one's NULL) named by the current word. */
static const void *pick(struct S *s, const void *table, size_t stride, const char *what)
{
    int line = s->lx.t.line, col = s->lx.t.col;
    for (const char *r = table; *(const char *const *)r; r += stride)
        if (accept_word(s, *(const char *const *)r))
            return r;
    fail_at(s, line, col, "unknown %s %s", what, tok_desc(s));
}

/* One of t_filter's parameters (p) of a filter node: the value at the token. */
static void filter_row(struct S *s, struct node *n, const struct tex_param *p)
{
    char text[64];
    int line = s->lx.t.line, col = s->lx.t.col;

    if (s->lx.t.kind == TEX_TOK_NAME || s->lx.t.kind == TEX_TOK_STR) {
        snprintf(text, sizeof text, "%.*s", (int)(s->lx.t.len < 60 ? s->lx.t.len : 60),
                 s->lx.t.text);
        next(s);
    } else {
        snprintf(text, sizeof text, "%.17g", number(s));
    }
    if (tex_param_parse(p, n->fargs, text, TEX_PARAM_WORD) < 0)
        fail_at(s, line, col, "filter %s: %s", n->fop->name, tex_errmsg());
}

/* After a t_filter operation's image: 'by VALUE' for its main parameter, then any of its
 * parameters by name, as t_filter(1)'s options (seed: -S); none after Filter(NAME, P). */
static void filter_params(struct S *s, struct node *n, int func)
{
    const struct tex_filter_op *op = n->fop;

    n->fargs = arena(s, sizeof *n->fargs);
    tex_params_defaults(tex_filter_rows, n->fargs);
    n->fargs->seed = 1; /* t_filter's -S */
    if (func)
        return;
    if (is_word(s, "by")) {
        if (!op->by)
            fail_at(s, s->lx.t.line, s->lx.t.col, "filter %s takes no 'by'", op->name);
        next(s);
        filter_row(s, n, tex_param_find(tex_filter_rows, op->by));
    }
    while (s->lx.t.kind == TEX_TOK_NAME) {
        char name[32];
        const struct tex_param *p;
        int line = s->lx.t.line, col = s->lx.t.col;
        if (accept_word(s, "seed")) {
            n->fargs->seed = (uint64_t)integer(s, 0, TEX_SEED_MAX, "the seed");
            continue;
        }
        snprintf(name, sizeof name, "%.*s", (int)(s->lx.t.len < 31 ? s->lx.t.len : 31),
                 s->lx.t.text);
        if (!(p = tex_param_find(tex_filter_rows, name)))
            break; /* an operator, or what follows the operand */
        if (p->kinds && !(p->kinds >> tex_filter_op_index(op) & 1))
            fail_at(s, line, col, "%s does not apply to filter %s", name, op->name);
        next(s);
        filter_row(s, n, p);
    }
}

/* The script's own filter called name, or NULL. */
static const struct filter *own_filter(const char *name)
{
    for (const struct filter *f = filters; f->name; f++)
        if (!strcmp(f->name, name))
            return f;
    return NULL;
}

/* filter NAME IMAGE [by V] [PARAM V ...], or the thesis's Filter(NAME, IMAGE). */
static void parse_filter(struct S *s, struct node *n, int line, int col)
{
    int func = is_punct(s, '(');
    char name[32];

    if (func)
        next(s);
    if (s->lx.t.kind != TEX_TOK_NAME)
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected a filter's name, found %s", tok_desc(s));
    snprintf(name, sizeof name, "%.*s", (int)(s->lx.t.len < 31 ? s->lx.t.len : 31), s->lx.t.text);
    n->filter = own_filter(name);
    if (!n->filter && !(n->fop = tex_filter_op_find(name))) {
        char list[256] = "";
        for (const struct filter *f = filters; f->name; f++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", f->name, "|");
        for (const struct tex_filter_op *o = tex_filter_ops; o->name; o++)
            if (!own_filter(o->name)) /* blur is the script's own */
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", o->name,
                         o[1].name ? "|" : "");
        fail_at(s, s->lx.t.line, s->lx.t.col, "unknown filter %s (one of %s)", tok_desc(s), list);
    }
    next(s);
    if (func)
        expect_punct(s, ',');
    n->a = func ? expr(s) : unary(s);
    if (func)
        expect_punct(s, ')');
    if (n->fop) {
        filter_params(s, n, func);
        return;
    }
    n->v[0] = n->filter->by;
    if (!func && (n->flag = accept_word(s, "by")))
        n->v[0] = number(s);
    if (n->filter->radius && !(n->v[0] >= 0 && n->v[0] <= s->o->max_blur))
        fail_at(s, line, col, "blur radius must be 0..%d (got %g)", s->o->max_blur, n->v[0]);
}

/* An operand inside a transform, and a whole expression: lang/expr.c's, as nodes. */
static struct node *wrap(struct S *s, struct tex_enode *e)
{
    struct node *n;
    if (e->kind == TEX_EK_LEAF)
        return (struct node *)e->ptr;
    n = new_node(s, e->kind == TEX_EK_NUM ? N_NUM : N_EXPR, e->line, e->col);
    n->v[0] = e->v[0];
    n->x = e;
    return n;
}

static struct node *unary(struct S *s)
{
    return wrap(s, tex_expr_unary(&s->xp));
}

static struct node *expr(struct S *s)
{
    return wrap(s, tex_expr_parse(&s->xp));
}

/* The other transforms (filter, tile, matrix, warp, mix), or a primary; line, col: where
 * the operand starts. */
static struct node *transform2(struct S *s, int line, int col)
{
    struct node *n;

    if (accept_word(s, "filter")) {
        n = new_node(s, N_FILTER, line, col);
        parse_filter(s, n, line, col);
    } else if (accept_word(s, "tile")) {
        n = new_node(s, N_TILE, line, col);
        n->a = unary(s);
        expect_word(s, "by");
        n->v[0] = integer(s, 1, 4096, "repetitions");
        expect_punct(s, ',');
        n->v[1] = integer(s, 1, 4096, "repetitions");
        n->flag = accept_word(s, "mirror");
    } else if (accept_word(s, "matrix")) {
        n = new_node(s, N_MATRIX, line, col);
        n->op = ((const struct rule *)pick(s, rules, sizeof *rules, "matrix rule"))->rule;
        expect_word(s, "by");
        n->v[0] = integer(s, 1, 4096, "matrix cells");
        expect_punct(s, ',');
        n->v[1] = integer(s, 1, 4096, "matrix cells");
        expect_word(s, "of");
        n->list = arena(s, 64 * sizeof *n->list);
        do {
            if (n->nlist == 64)
                fail_at(s, line, col, "a matrix takes at most 64 images");
            n->list[n->nlist++] = unary(s);
        } while (is_punct(s, ',') && (next(s), 1));
        n->flag = accept_word(s, "mirror");
    } else if (accept_word(s, "warp")) {
        n = new_node(s, N_WARP, line, col);
        n->a = unary(s);
        expect_word(s, "by");
        n->b = unary(s);
        n->v[0] = 0.1;
        if (accept_word(s, "amount"))
            n->v[0] = number(s);
        if (!(fabs(n->v[0]) <= 100))
            fail_at(s, line, col, "warp amount must be in -100..100 (got %g)", n->v[0]);
        n->flag = accept_word(s, "isotropic");
    } else if (accept_word(s, "mix")) {
        n = new_node(s, N_MIX, line, col);
        n->a = unary(s);
        expect_punct(s, ',');
        n->b = unary(s);
        expect_word(s, "by");
        n->c = unary(s);
    } else
        n = primary(s);
    return n;
}

/* After rotate, scale or shift: the thesis's form OP(n numbers, P) sets n->v and n->a and
 * gives 1; else 0, with *group the word form's image if it was in parentheses
 * (rotate (a over b) by 10). */
static int functional(struct S *s, struct node *n, int nnum, struct node **group)
{
    int line = s->lx.t.line, col = s->lx.t.col;
    struct node *first;

    *group = NULL;
    if (!is_punct(s, '('))
        return 0;
    next(s);
    first = expr(s);
    if (!is_punct(s, ',')) {
        expect_punct(s, ')');
        *group = first;
        return 0;
    }
    if (first->k != N_NUM)
        fail_at(s, line, col, "expected %d number%s and then an image", nnum, nnum > 1 ? "s" : "");
    n->v[0] = first->v[0];
    for (int k = 1; k < nnum; k++) {
        expect_punct(s, ',');
        n->v[k] = number(s);
    }
    expect_punct(s, ',');
    n->a = expr(s);
    expect_punct(s, ')');
    return 1;
}

static struct node *transform(struct S *s)
{
    struct node *g;
    int line = s->lx.t.line, col = s->lx.t.col;
    struct node *n;

    if (accept_word(s, "expand")) {
        n = new_node(s, N_EXPAND, line, col);
        n->a = unary(s);
        expect_word(s, "to");
        size_pair(s, &n->w, &n->h, "an expanded size");
        memcpy(n->colour, (float[4]){0, 0, 0, 1}, sizeof n->colour);
        if (accept_word(s, "background"))
            colour(s, n->colour);
    } else if (accept_word(s, "rotate")) {
        n = new_node(s, N_ROTATE, line, col);
        memcpy(n->colour, (float[4]){0, 0, 0, 1}, sizeof n->colour);
        if (functional(s, n, 1, &g)) { /* Rotate(alpha, P): alpha in radians */
            n->v[0] *= 180 / M_PI;
            return n;
        }
        n->a = g ? g : unary(s);
        expect_word(s, "by");
        n->v[0] = number(s);
        if ((n->flag = accept_word(s, "around"))) {
            n->v[1] = number(s);
            expect_punct(s, ',');
            n->v[2] = number(s);
        }
        if (accept_word(s, "background"))
            colour(s, n->colour);
    } else if (accept_word(s, "scale")) {
        n = new_node(s, N_SCALE, line, col);
        if (!functional(s, n, 2, &g)) {
            n->a = g ? g : unary(s);
            expect_word(s, "by");
            n->v[0] = n->v[1] = number(s);
            if (is_punct(s, ',')) {
                next(s);
                n->v[1] = number(s);
            }
        }
        if (!(n->v[0] >= 1e-3 && n->v[0] <= 1e3 && n->v[1] >= 1e-3 && n->v[1] <= 1e3))
            fail_at(s, line, col, "scale factors must be in 0.001..1000 (got %g, %g)", n->v[0],
                    n->v[1]);
    } else if (accept_word(s, "resize")) {
        n = new_node(s, N_RESIZE, line, col);
        n->a = unary(s);
        expect_word(s, "to");
        size_pair(s, &n->w, &n->h, "a size");
    } else if (accept_word(s, "shift")) {
        n = new_node(s, N_SHIFT, line, col);
        memcpy(n->colour, (float[4]){0, 0, 0, 1}, sizeof n->colour);
        if (functional(s, n, 2, &g))
            return n;
        n->a = g ? g : unary(s);
        expect_word(s, "by");
        n->v[0] = number(s);
        expect_punct(s, ',');
        n->v[1] = number(s);
        n->flag = accept_word(s, "wrap");
        if (accept_word(s, "background"))
            colour(s, n->colour);
    } else if (accept_word(s, "clipping") || accept_word(s, "clip")) {
        n = new_node(s, N_CLIP, line, col);
        n->a = unary(s);
        expect_word(s, "from");
        n->v[0] = integer(s, 0, TEX_MAP_MAX_SIDE, "a clipping corner");
        expect_punct(s, ',');
        n->v[1] = integer(s, 0, TEX_MAP_MAX_SIDE, "a clipping corner");
        expect_word(s, "to");
        n->v[2] = integer(s, 0, TEX_MAP_MAX_SIDE, "a clipping corner");
        expect_punct(s, ',');
        n->v[3] = integer(s, 0, TEX_MAP_MAX_SIDE, "a clipping corner");
    } else
        n = transform2(s, line, col);
    return n;
}

/* The thesis's operators written as functions: AND(P1,P2), OR, XOR, and +_up(P1,P2) (P2
 * over P1), +_down(P1,P2) (P2 under P1); in any case. */
static const struct {
    const char *name;
    enum tex_op op;
    int swap; /* the operands in the other order: P2 op P1 */
} op_calls[] = {{"and", TEX_OP_AND, 0}, {"or", TEX_OP_OR, 0},       {"xor", TEX_OP_XOR, 0},
                {"_up", TEX_OP_OVER, 1}, {"_down", TEX_OP_UNDER, 1}};

/* An operator call at the token, as a binary node; NULL if there is none. */
static struct tex_enode *op_call(struct S *s)
{
    struct tex_lexer at = s->lx;
    struct tex_tok t = s->lx.t;
    int plus = is_punct(s, '+'), k;
    struct tex_enode *e;

    if (plus)
        tex_lex_next(&at);
    for (k = 0; k < (int)(sizeof op_calls / sizeof *op_calls); k++)
        if (at.t.kind == TEX_TOK_NAME && at.t.len == strlen(op_calls[k].name) &&
            !strncasecmp(at.t.text, op_calls[k].name, at.t.len) &&
            plus == (op_calls[k].name[0] == '_'))
            break;
    if (k == (int)(sizeof op_calls / sizeof *op_calls))
        return NULL;
    tex_lex_next(&at);
    if (!tex_tok_is_punct(&at.t, '('))
        return NULL;
    if (++s->xp.nterms > TEX_EXPR_MAX_TERMS)
        fail_at(s, t.line, t.col, "expression too long (more than %d operators)",
                TEX_EXPR_MAX_TERMS);
    s->lx = at; /* past the name */
    next(s);
    e = tex_expr_node(&s->lx, TEX_EK_BIN, &t);
    e->op = op_calls[k].op;
    struct tex_enode *p1 = tex_expr_parse(&s->xp);
    expect_punct(s, ',');
    struct tex_enode *p2 = tex_expr_parse(&s->xp);
    expect_punct(s, ')');
    e->a = op_calls[k].swap ? p2 : p1;
    e->b = op_calls[k].swap ? p1 : p2;
    return e;
}

/* lang/expr.c's hook: the script's own operands, as leaves, or an operator call. */
static struct tex_enode *operand(struct tex_expr_parser *xp)
{
    struct S *s = xp->ctx;
    struct tex_enode *e = op_call(s);
    if (e)
        return e;
    e = tex_expr_node(&s->lx, TEX_EK_LEAF, &s->lx.t);
    e->ptr = transform(s);
    return e;
}

/* The operators between images, all of one precedence, left to right. */
static const struct tex_expr_binop binops[] = {
    {"over", 1, TEX_OP_OVER}, {"under", 1, TEX_OP_UNDER}, {"and", 1, TEX_OP_AND},
    {"or", 1, TEX_OP_OR},     {"xor", 1, TEX_OP_XOR},     {"min", 1, TEX_OP_MIN},
    {"max", 1, TEX_OP_MAX},   {"+", 1, TEX_OP_ADD},       {"-", 1, TEX_OP_SUB},
    {"*", 1, TEX_OP_MUL},     {NULL, 0, 0}};
static const struct tex_expr_lang script_lang = {binops, operand};

static struct def *find_def(struct S *s, const char *name)
{
    intptr_t k = (intptr_t)tex_names_get(&s->defnames, name);
    return k ? &s->defs[k - 1] : NULL;
}

static void define(struct S *s, char *name, struct node *e, int line, int col)
{
    struct def *d = find_def(s, name);

    if (d && d->expr)
        fail_at(s, line, col, "image '%s' is defined twice (first at line %d)", name, d->line);
    if (d && !e)
        fail_at(s, line, col, "image '%s' is declared twice (first at line %d)", name, d->line);
    if (!d) {
        s->defs = grow(s, s->defs, &s->capdefs, s->ndefs, sizeof *s->defs);
        d = &s->defs[s->ndefs++];
        memset(d, 0, sizeof *d);
        d->name = name;
        if (tex_names_put(&s->defnames, name, (void *)(intptr_t)s->ndefs) < 0)
            longjmp(s->fail, 1);
    }
    d->expr = e;
    d->line = line;
    d->col = col;
}

static int is_tess(struct S *s)
{
    return accept_word(s, "tessellation") || accept_word(s, "tesselation");
}

/* The header: tessellation NAME; size; tessellation KIND; cell; background.  Checks that the
 * size fits the pixel limit and the cell fits the size (a missing cell is the whole size). */
static int err_pos(struct S *s, int line, int col);

static struct tex_procs *script_procs(struct S *s)
{
    if (!s->procs && !(s->procs = tex_procs_new()))
        longjmp(s->fail, 1);
    return s->procs;
}

/* primitives "FILE": composed primitives from a definitions file. */
static void read_procs(struct S *s, int line, int col)
{
    char path[4096];
    if (s->lx.t.kind != TEX_TOK_STR || s->lx.t.len >= sizeof path)
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected a file name in quotes, found %s",
                tok_desc(s));
    if (!s->o->allow_files)
        fail_at(s, line, col, "reading files is not allowed here");
    memcpy(path, s->lx.t.text, s->lx.t.len);
    path[s->lx.t.len] = 0;
    if (tex_procs_read(script_procs(s), path) < 0) {
        err_pos(s, line, col);
        longjmp(s->fail, 1);
    }
    next(s);
}

/* The kind after a second 'tessellation'. */
static void tess_kind(struct S *s, int line, int col)
{
    int k;
    if (s->have_kind++)
        fail_at(s, line, col, "the tessellation kind is given twice");
    for (k = 0; tess_names[k] && !accept_word(s, tess_names[k]); k++)
        ;
    if (!tess_names[k])
        fail_at(s, s->lx.t.line, s->lx.t.col,
                "unknown tessellation %s (rectangular, hexagonal, triangular or brick)",
                tok_desc(s));
    s->kind = (enum tess)k;
}

static void parse_header(struct S *s)
{
    for (;;) {
        int line = s->lx.t.line, col = s->lx.t.col;
        if (is_tess(s)) {
            if (!s->title)
                s->title = take_name(s, "a name");
            else
                tess_kind(s, line, col);
        } else if (accept_word(s, "size")) {
            size_pair(s, &s->w, &s->h, "the size");
            s->have_size = 1;
        } else if (accept_word(s, "cell")) {
            size_pair(s, &s->cw, &s->ch, "the cell size");
        } else if (accept_word(s, "background")) {
            colour(s, s->bg);
        } else if (accept_word(s, "primitive")) {
            tex_procs_define(script_procs(s), &s->lx); /* takes its ';' */
            continue;
        } else if (accept_word(s, "primitives")) {
            read_procs(s, line, col);
        } else
            break;
        expect_punct(s, ';');
    }
    if (!s->title)
        fail_at(s, s->lx.t.line, s->lx.t.col, "a script starts with 'tessellation NAME;', found %s",
                tok_desc(s));
    if (!s->have_size)
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected 'size W by H;' before %s", tok_desc(s));
    if ((long long)s->w * s->h > s->o->max_pixels)
        fail_at(s, 1, 1, "size %d by %d is larger than the limit of %lld pixels", s->w, s->h,
                s->o->max_pixels);
    if (!s->cw) {
        s->cw = s->w;
        s->ch = s->h;
    }
    if (s->cw > s->w || s->ch > s->h)
        fail_at(s, 1, 1, "cell %d by %d is larger than the size %d by %d", s->cw, s->ch, s->w,
                s->h);
}

/* The optional block 'images NAME [= EXPR]; ... end images;': each name is declared, to be
 * defined later, or defined there. */
static void parse_images(struct S *s)
{
    if (!accept_word(s, "images"))
        return;
    while (!is_word(s, "end")) {
        int line = s->lx.t.line, col = s->lx.t.col;
        char *name = take_name(s, "an image name or 'end images'");
        struct node *e = NULL;
        if (is_punct(s, '=')) {
            next(s);
            e = expr(s);
        }
        define(s, name, e, line, col);
        expect_punct(s, ';');
    }
    next(s);
    expect_word(s, "images");
    expect_punct(s, ';');
}

/* The definitions NAME = EXPR; up to 'built'. */
static void parse_defs(struct S *s)
{
    while (!is_word(s, "built")) {
        int line = s->lx.t.line, col = s->lx.t.col;
        char *name;
        if (s->lx.t.kind == TEX_TOK_EOF)
            fail_at(s, line, col, "expected 'built with ... end tessellation;', found %s",
                    tok_desc(s));
        name = take_name(s, "an image name or 'built with'");
        expect_punct(s, '=');
        define(s, name, expr(s), line, col);
        expect_punct(s, ';');
    }
}

/* ---- tessellations ----
 *
 * A cell's box is cw x ch and its image is centred in it.  Rectangles fill the canvas from
 * its top left corner.  Bricks are rectangles whose odd rows (the 2nd, 4th...) start half a
 * cell to the left.  Hexagons stand on a vertex, inscribed in the box (regular when ch =
 * 2 cw / sqrt 3); their rows are 3/4 ch apart, the odd ones half a cell to the left.
 * Triangles are inscribed in the box too, base cw and height ch (regular when ch =
 * cw sqrt 3 / 2), half a cell apart and alternately pointing up and down: cell (1,1)
 * points up, centred on the left edge. */

/* The columns and rows of cells that reach the canvas. */
static void tess_grid(const struct S *s, int *cols, int *rows)
{
    double w = s->cw, h = s->ch;
    switch (s->kind) {
    case T_BRICK:
        *cols = (int)ceil((s->w + w / 2) / w);
        *rows = (int)ceil(s->h / h);
        break;
    case T_HEXAGONAL:
        *cols = (int)floor((s->w - 0.5 + w / 2) / w) + 1;
        *rows = (int)floor((s->h - 0.5) / (0.75 * h)) + 1;
        break;
    case T_TRIANGULAR:
        *cols = (int)floor((s->w - 0.5) / (w / 2)) + 2;
        *rows = (int)ceil(s->h / h);
        break;
    default:
        *cols = (int)ceil(s->w / w);
        *rows = (int)ceil(s->h / h);
    }
}

/* The cell (i, j), from 0, whose shape holds the centre of pixel (x, y) of a brick,
 * hexagonal or triangular tessellation, and the pixel's place (lx, ly) in its box. */
static void tess_locate(const struct S *s, int x, int y, int *i, int *j, int *lx, int *ly)
{
    double w = s->cw, h = s->ch, px = x + 0.5, py = y + 0.5, bx, by, off;
    if (s->kind == T_TRIANGULAR) {
        int k;
        *j = (int)floor(py / h);
        k = (int)floor(px / (w / 2));
        double t = py / h - *j, u = px / (w / 2) - k;
        int up = ((k + *j) & 1) == 0; /* triangle k's right half, or k+1's left half */
        *i = (up ? t >= u : t <= 1 - u) ? k : k + 1;
        bx = *i * (w / 2) - w / 2;
        by = *j * h;
    } else if (s->kind == T_HEXAGONAL) {
        int r = (int)floor(py / (0.75 * h));
        off = (r & 1) ? w / 2 : 0;
        double xx = px + off - w * floor((px + off) / w), yy = py - r * 0.75 * h;
        if (yy < h / 4 && yy < h / 4 * fabs(xx - w / 2) / (w / 2)) /* above a slanted edge */
            r--;
        off = (r & 1) ? w / 2 : 0;
        *j = r;
        *i = (int)floor((px + off) / w);
        bx = *i * w - off;
        by = r * 0.75 * h;
    } else { /* bricks */
        *j = (int)floor(py / h);
        off = (*j & 1) ? w / 2 : 0;
        *i = (int)floor((px + off) / w);
        bx = *i * w - off;
        by = *j * h;
    }
    *lx = (int)floor(px - bx);
    *ly = (int)floor(py - by);
    *lx = *lx < 0 ? 0 : *lx >= s->cw ? s->cw - 1 : *lx;
    *ly = *ly < 0 ? 0 : *ly >= s->ch ? s->ch - 1 : *ly;
}

/* The layout 'built with (I,J) EXPR; ... end tessellation;': each cell inside the
 * tessellation and given once; nothing may follow. */
static void parse_layout(struct S *s)
{
    next(s);
    expect_word(s, "with");
    while (!is_word(s, "end")) {
        struct cellref *c;
        int line = s->lx.t.line, col = s->lx.t.col;
        int cols, rows;
        tess_grid(s, &cols, &rows);
        expect_punct(s, '(');
        s->cells = grow(s, s->cells, &s->capcells, s->ncells, sizeof *s->cells);
        c = &s->cells[s->ncells];
        c->line = line;
        c->col = col;
        c->i = integer(s, 1, cols, "the column of a cell");
        expect_punct(s, ',');
        c->j = integer(s, 1, rows, "the row of a cell");
        expect_punct(s, ')');
        char key[24];
        snprintf(key, sizeof key, "%d,%d", c->i, c->j);
        intptr_t first = (intptr_t)tex_names_get(&s->cellnames, key);
        if (first)
            fail_at(s, line, col, "cell (%d,%d) is given twice (first at line %d)", c->i, c->j,
                    (int)first);
        if (tex_names_put(&s->cellnames, key, (void *)(intptr_t)line) < 0)
            longjmp(s->fail, 1);
        c->expr = expr(s);
        s->ncells++;
        expect_punct(s, ';');
    }
    next(s);
    if (!is_tess(s))
        fail_at(s, s->lx.t.line, s->lx.t.col, "expected 'end tessellation;', found %s", tok_desc(s));
    expect_punct(s, ';');
    if (s->lx.t.kind != TEX_TOK_EOF)
        fail_at(s, s->lx.t.line, s->lx.t.col, "unexpected %s after 'end tessellation;'", tok_desc(s));
}

/* The file a bare name stands for, as the thesis's maps were named (leo): the name
 * itself, or with the first extension of a format Textura reads (io/file.h's order)
 * that exists; NULL if none does. */
static char *image_file(struct S *s, const char *name)
{
    struct stat st;
    size_t n = strlen(name);
    char *path = arena(s, n + 8);

    memcpy(path, name, n + 1);
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode))
        return path;
    for (int f = TEX_FMT_EXR; f < TEX_FMT_COUNT; f++)
        for (const char *e = tex_format_exts((enum tex_format)f); *(e += strspn(e, " "));
             e += strcspn(e, " ")) {
            snprintf(path + n, 8, ".%.*s", (int)strcspn(e, " "), e);
            if (stat(path, &st) == 0 && S_ISREG(st.st_mode))
                return path;
        }
    return NULL;
}

/* Every name used must be defined somewhere, or be the bare name of an image file:
 * checked once all is read, as a use may come before its definition. */
static void resolve_refs(struct S *s)
{
    for (int i = 0; i < s->nrefs; i++) {
        struct node *r = s->refs[i];
        struct def *d = find_def(s, r->s);
        char *file;
        if (!d && s->o->allow_files && (file = image_file(s, r->s))) {
            r->k = N_FILE;
            r->s = file;
            continue;
        }
        if (!d)
            fail_at(s, r->line, r->col,
                    s->o->allow_files ? "undefined image '%s' (nor a file of that name, "
                                        "with or without .exr, .png, .tif...)"
                                      : "undefined image '%s'",
                    r->s);
        if (!d->expr)
            fail_at(s, r->line, r->col, "image '%s' is declared (line %d) but never defined",
                    r->s, d->line);
        r->def = d;
    }
}

static void parse(struct S *s)
{
    next(s);
    parse_header(s);
    parse_images(s);
    /* Definitions, then the layout. */
    parse_defs(s);
    parse_layout(s);
    resolve_refs(s);
}

/* ---- interpreter ---- */

struct val {
    const tex_map *m; /* NULL: the constant c */
    tex_map *own;     /* m, when this value owns it */
    float c[4];
    int nc;           /* the constant's values: 0 or 1 a number, 3 a colour */
};

static struct tex_operand operand_of(const struct val *v)
{
    if (v->m)
        return (struct tex_operand){v->m, 0, {0}};
    return (struct tex_operand){NULL, v->nc ? v->nc : 1, {v->c[0], v->c[1], v->c[2], v->c[3]}};
}

static void val_free(struct val *v)
{
    tex_map_free(v->own);
    v->own = NULL;
    v->m = NULL;
}

/* Record the position in front of the current libtex message. */
static int err_pos(struct S *s, int line, int col)
{
    char where[300];
    snprintf(where, sizeof where, "%s:%d:%d", s->name, line, col);
    tex_error_context(where);
    return -1;
}

static int err_at(struct S *s, const struct node *n)
{
    return err_pos(s, n->line, n->col);
}

static int fail_node(struct S *s, const struct node *n, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int fail_node(struct S *s, const struct node *n, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return tex_lang_error(s->name, n->line, n->col, "%s", msg);
}

static int check_pixels(struct S *s, const struct node *n, long long w, long long h)
{
    if (w * h > s->o->max_pixels)
        return fail_node(s, n, "a %lld by %lld image is larger than the limit of %lld pixels", w,
                         h, s->o->max_pixels);
    return 0;
}

static int set_result(struct S *s, const struct node *n, struct val *out, tex_map *m)
{
    if (!m)
        return err_at(s, n);
    out->m = out->own = m;
    return 0;
}

static int eval(struct S *s, const struct node *n, struct val *out);

static int eval_map(struct S *s, const struct node *n, struct val *out, const char *what)
{
    if (eval(s, n, out) < 0)
        return -1;
    if (!out->m)
        return fail_node(s, n, "%s needs an image, not a number", what);
    return 0;
}

static int eval_def(struct S *s, const struct node *ref, struct val *out)
{
    struct def *d = ref->def;

    if (d->state == 1)
        return fail_node(s, ref, "recursive definition: '%s' (line %d) needs itself", d->name,
                         d->line);
    if (d->state == 0) {
        struct val v = {0};
        d->state = 1;
        if (eval_map(s, d->expr, &v, d->name) < 0)
            return -1;
        d->map = v.own ? v.own : tex_map_clone(v.m);
        if (!d->map)
            return err_at(s, ref);
        d->state = 2;
    }
    if (ref->w && (ref->w != d->map->w || ref->h != d->map->h)) /* name W by H */
        return check_pixels(s, ref, ref->w, ref->h) < 0
                   ? -1
                   : set_result(s, ref, out, tex_resize(d->map, ref->w, ref->h));
    /* Uses borrow the map, which lives until the script ends: a value that
     * borrowed it may still be alive when another use comes. */
    out->m = d->map;
    return 0;
}

static int eval_prim(struct S *s, const struct node *n, struct val *out)
{
    const struct tex_primitive *p = tex_procs_find(s->procs, n->s);
    struct tex_field *f;
    int w = n->w ? n->w : s->cw, h = n->h ? n->h : s->ch;
    tex_map *m = NULL;

    if (!p)
        return fail_node(s, n, "%s", tex_errmsg());
    if (!(f = tex_field_new(p)))
        return err_at(s, n);
    f->style = TEX_PARAM_WORD;
    /* the primitive's parameters and seed, tile, ids, size: tex_field_rows */
    for (int i = 0; i < n->nparams; i++) {
        const struct param *q = &n->params[i];
        if (tex_field_set(f, q->name, q->value) < 0) {
            char where[300];
            tex_field_free(f);
            snprintf(where, sizeof where, "%s:%d:%d", s->name, q->line, q->col);
            tex_error_context(where);
            return -1;
        }
    }
    if (f->size)
        w = h = f->size;
    if (check_pixels(s, n, w, h) < 0) {
        tex_field_free(f);
        return -1;
    }
    if (tex_field_init(f, w, h) == 0)
        m = tex_field_sample(f);
    tex_field_free(f);
    return set_result(s, n, out, m);
}

static int eval_file(struct S *s, const struct node *n, struct val *out)
{
    tex_map *m;
    int is_stdin = !strcmp(n->s, "-");

    if (!s->o->allow_files)
        return fail_node(s, n, "reading files is not allowed here");
    if (is_stdin && !s->o->allow_stdin)
        return fail_node(s, n, "standard input is not available (the script came from it)");
    if (is_stdin && s->stdin_used++)
        return fail_node(s, n, "standard input can be read only once");
    if (!(m = tex_map_read(n->s)))
        return err_at(s, n);
    if (check_pixels(s, n, m->w, m->h) < 0) {
        tex_map_free(m);
        return -1;
    }
    if (n->w && (m->w != n->w || m->h != n->h)) {
        tex_map *r = tex_resize(m, n->w, n->h);
        tex_map_free(m);
        m = r;
    }
    return set_result(s, n, out, m);
}

/* ---- expressions of lang/expr.h on maps ---- */

static int eval_x(struct S *s, const struct tex_enode *x, struct val *out);

/* out = a op b, images or constants (at least one image); a and b are used up. */
static int combine(struct S *s, const struct tex_enode *at, enum tex_op op, struct val *a,
                   struct val *b, struct val *out)
{
    struct tex_operand oa = operand_of(a), ob = operand_of(b);
    tex_map *r = NULL;
    int rc = -1;

    if (!a->m && !b->m)
        tex_lang_error(s->name, at->line, at->col, "%s needs at least one image",
                       tex_op_name(op));
    else if (a->m && b->m && (a->m->w != b->m->w || a->m->h != b->m->h))
        tex_lang_error(s->name, at->line, at->col,
                       "%s of images of different sizes (%dx%d and %dx%d): resize one",
                       tex_op_name(op), a->m->w, a->m->h, b->m->w, b->m->h);
    else if (!(r = tex_op_apply(op, &oa, op == TEX_OP_ABS ? NULL : &ob, NULL, 0.5)))
        err_pos(s, at->line, at->col);
    else
        rc = 0;
    val_free(a);
    val_free(b);
    memset(out, 0, sizeof *out);
    out->m = out->own = r;
    return rc;
}

/* A chain a op b op c ...: along its left spine without recursion. */
static int eval_chain(struct S *s, const struct tex_enode *x, struct val *out)
{
    const struct tex_enode *e, **spine;
    int n = 0, i, rc;

    for (e = x; e->kind == TEX_EK_BIN; e = e->a)
        n++;
    if (!(spine = malloc(n * sizeof *spine)))
        return tex_error("out of memory"), err_pos(s, x->line, x->col);
    for (e = x, i = n; e->kind == TEX_EK_BIN; e = e->a)
        spine[--i] = e;
    rc = eval_x(s, e, out);
    for (i = 0; rc == 0 && i < n; i++) {
        struct val b = {0};
        if ((rc = eval_x(s, spine[i]->b, &b)) < 0)
            val_free(out);
        else
            rc = combine(s, spine[i], (enum tex_op)spine[i]->op, out, &b, out);
    }
    free(spine);
    return rc;
}

/* Channel c of value v at pixel i: a number serves every channel; a grey map's value every
 * colour channel; a missing alpha is 1. */
static double val_at(const struct val *v, size_t i, int c)
{
    int nc = v->m ? v->m->nc : v->nc > 1 ? v->nc : 1;
    const float *p = v->m ? v->m->px + i * nc : v->c;
    if (nc == 2) /* grey and alpha */
        return p[c == 3 ? 1 : 0];
    if (c < nc)
        return p[c];
    return c == 3 && nc > 1 ? 1 : p[0];
}

/* A function of lang/expr.h's table that has no image operator (mix, smoothstep, sin, ...):
 * tex_expr_apply on every pixel and channel, numbers standing for whole images.  The result
 * has the most channels of its arguments. */
static int eval_pointwise(struct S *s, const struct tex_enode *x, struct val *v, int n,
                          struct val *out)
{
    const tex_map *m = NULL;
    int nc = 1;
    for (int i = 0; i < n; i++) {
        const tex_map *mi = v[i].m;
        int ci = mi ? mi->nc : v[i].nc > 1 ? v[i].nc : 1;
        nc = ci > nc ? ci : nc;
        if (mi && m && (mi->w != m->w || mi->h != m->h))
            return tex_lang_error(s->name, x->line, x->col,
                                  "function of images of different sizes (%dx%d and %dx%d): "
                                  "resize one", m->w, m->h, mi->w, mi->h);
        m = mi ? mi : m;
    }
    const struct tex_einsn in = {(enum tex_eop)x->op, 0, {0}, NULL};
    size_t npx = m ? (size_t)m->w * m->h : 1;
    tex_map *r = m ? tex_map_new(m->w, m->h, nc) : NULL;
    if (m && !r)
        return err_pos(s, x->line, x->col);
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < npx; i++)
        for (int c = 0; c < nc; c++) {
            double a[3] = {0}, b[3] = {0}, cc[3] = {0};
            a[0] = val_at(&v[0], i, c);
            b[0] = n > 1 ? val_at(&v[1], i, c) : 0;
            cc[0] = n > 2 ? val_at(&v[2], i, c) : 0;
            float y = (float)tex_expr_apply(&in, 0, a, b, cc);
            if (r)
                r->px[i * nc + c] = y;
            else
                out->c[c] = y;
        }
    out->m = out->own = r;
    out->nc = r ? 0 : nc;
    return 0;
}

/* A function of lang/expr.h's table, on images (rgb: on numbers, a colour). */
static int eval_call(struct S *s, const struct tex_enode *x, struct val *out)
{
    const struct tex_enode *arg[3] = {x->a, x->b, x->c};
    struct val v[3] = {{0}};
    int n = tex_expr_arity((enum tex_eop)x->op);

    for (int i = 0; i < n; i++)
        if (eval_x(s, arg[i], &v[i]) < 0) {
            while (i--)
                val_free(&v[i]);
            return -1;
        }
    if (x->op == TEX_EOP_RGB) {
        memset(out, 0, sizeof *out);
        out->nc = 3;
        for (int i = 0; i < 3; i++) {
            if (v[i].m || v[i].nc > 1) {
                for (int j = 0; j < 3; j++)
                    val_free(&v[j]);
                return tex_lang_error(s->name, x->line, x->col, "rgb takes numbers");
            }
            out->c[i] = v[i].c[0];
        }
        return 0;
    }
    if (x->op == TEX_EOP_ABS && !v[0].m) {
        *out = v[0];
        for (int k = 0; k < 4; k++)
            out->c[k] = fabsf(out->c[k]);
        return 0;
    }
    if (x->op == TEX_EOP_ABS)
        return combine(s, x, TEX_OP_ABS, &v[0], &v[1], out);
    if (x->op == TEX_EOP_MIN || x->op == TEX_EOP_MAX)
        return combine(s, x, x->op == TEX_EOP_MIN ? TEX_OP_MIN : TEX_OP_MAX, &v[0], &v[1], out);
    int rc = eval_pointwise(s, x, v, n, out);
    for (int i = 0; i < n; i++)
        val_free(&v[i]);
    return rc;
}

static int eval_x(struct S *s, const struct tex_enode *x, struct val *out)
{
    struct val zero = {0}, a;

    memset(out, 0, sizeof *out);
    switch (x->kind) {
    case TEX_EK_NUM: out->c[0] = (float)x->v[0]; return 0;
    case TEX_EK_RGB:
        out->nc = 3;
        for (int k = 0; k < 3; k++)
            out->c[k] = (float)x->v[k];
        return 0;
    case TEX_EK_LEAF: return eval(s, x->ptr, out);
    case TEX_EK_BIN: return eval_chain(s, x, out);
    case TEX_EK_CALL: return eval_call(s, x, out);
    case TEX_EK_NEG: break;
    }
    if (eval_x(s, x->a, &a) < 0)
        return -1;
    if (a.m) /* -image: 0 - image */
        return combine(s, x, TEX_OP_SUB, &zero, &a, out);
    *out = a;
    for (int k = 0; k < 4; k++)
        out->c[k] = -out->c[k];
    return 0;
}

/* ---- operations on maps ----
 *
 * Each evaluates its operands into v[0..2] (eval frees them) and sets out to its map, or
 * reports the error and returns -1. */

static int eval_mix(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    struct tex_operand oa, ob, oc;

    if (eval_map(s, n->a, &v[0], "mix") < 0 || eval_map(s, n->b, &v[1], "mix") < 0 ||
        eval(s, n->c, &v[2]) < 0)
        return -1;
    if (v[0].m->w != v[1].m->w || v[0].m->h != v[1].m->h ||
        (v[2].m && (v[2].m->w != v[0].m->w || v[2].m->h != v[0].m->h)))
        return fail_node(s, n, "mix of images of different sizes: resize them");
    oa = (struct tex_operand){v[0].m, 0, {0}};
    ob = (struct tex_operand){v[1].m, 0, {0}};
    oc = operand_of(&v[2]);
    return set_result(s, n, out, tex_op_apply(TEX_OP_MIX, &oa, &ob, &oc, 0.5));
}

static int eval_expand(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    if (check_pixels(s, n, n->w, n->h) < 0 || eval_map(s, n->a, &v[0], "expand") < 0)
        return -1;
    return set_result(s, n, out, tex_expand(v[0].m, n->w, n->h, n->colour));
}

/* About the centre unless a centre is given (flag). */
static int eval_rotate(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    const tex_map *m;

    if (eval_map(s, n->a, &v[0], "rotate") < 0)
        return -1;
    m = v[0].m;
    return set_result(s, n, out, tex_rotate(m, n->v[0], n->flag ? n->v[1] : m->w / 2.0,
                                            n->flag ? n->v[2] : m->h / 2.0, n->colour));
}

/* By factors: the new size, rounded, must be a size a map may have. */
static int eval_scale(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    const tex_map *m;
    double w, h;

    if (eval_map(s, n->a, &v[0], "scale") < 0)
        return -1;
    m = v[0].m;
    w = floor(m->w * n->v[0] + 0.5);
    h = floor(m->h * n->v[1] + 0.5);
    if (w < 1 || h < 1 || w > TEX_MAP_MAX_SIDE || h > TEX_MAP_MAX_SIDE)
        return fail_node(s, n, "scaling a %dx%d image gives %.0f by %.0f", m->w, m->h, w, h);
    if (check_pixels(s, n, (long long)w, (long long)h) < 0)
        return -1;
    return set_result(s, n, out, tex_resize(m, (int)w, (int)h));
}

static int eval_resize(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    if (check_pixels(s, n, n->w, n->h) < 0 || eval_map(s, n->a, &v[0], "resize") < 0)
        return -1;
    return set_result(s, n, out, tex_resize(v[0].m, n->w, n->h));
}

static int eval_shift(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    if (eval_map(s, n->a, &v[0], "shift") < 0)
        return -1;
    return set_result(s, n, out, tex_shift(v[0].m, n->v[0], n->v[1], n->flag, n->colour));
}

static int eval_clip(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    if (eval_map(s, n->a, &v[0], "clipping") < 0)
        return -1;
    return set_result(s, n, out,
                      tex_clip(v[0].m, (int)n->v[0], (int)n->v[1], (int)n->v[2], (int)n->v[3]));
}

static int eval_filter(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    if (eval_map(s, n->a, &v[0], n->filter ? n->filter->name : n->fop->name) < 0)
        return -1;
    if (n->fop) {
        tex_map *r = tex_filter_op_apply(n->fop, v[0].m, n->fargs, 0, v[0].m->h, 0);
        if (!r)
            tex_error_in_words();
        return set_result(s, n, out, r);
    }
    return set_result(s, n, out, n->filter->fn(v[0].m, n->v[0]));
}

static int eval_tile(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    const tex_map *m;

    if (eval_map(s, n->a, &v[0], "tile") < 0)
        return -1;
    m = v[0].m;
    return set_result(s, n, out, tex_tile(&m, 1, TEX_RULE_CYCLE, (int)n->v[0], (int)n->v[1],
                                          n->flag, m->w, m->h));
}

/* The matrix's images, all evaluated before the tiling; its cells are the first's size. */
static int eval_matrix(struct S *s, const struct node *n, struct val *out)
{
    struct val *vs = calloc(n->nlist, sizeof *vs);
    const tex_map **ms = calloc(n->nlist, sizeof *ms);
    tex_map *r = NULL;
    int ok = vs && ms;

    if (!ok)
        tex_error("out of memory");
    for (int i = 0; ok && i < n->nlist; i++) {
        ok = eval_map(s, n->list[i], &vs[i], "matrix") == 0;
        if (ok)
            ms[i] = vs[i].m;
    }
    if (ok)
        r = tex_tile(ms, n->nlist, (enum tex_rule)n->op, (int)n->v[0], (int)n->v[1], n->flag,
                     ms[0]->w, ms[0]->h);
    for (int i = 0; vs && i < n->nlist; i++)
        val_free(&vs[i]);
    free(vs);
    free(ms);
    return ok ? set_result(s, n, out, r) : -1;
}

static int eval_warp(struct S *s, const struct node *n, struct val *v, struct val *out)
{
    struct tex_warp_opts wo = {n->v[0], 0, 0, n->flag, TEX_EDGE_WRAP};

    if (eval_map(s, n->a, &v[0], "warp") < 0 || eval_map(s, n->b, &v[1], "warp") < 0)
        return -1;
    return set_result(s, n, out, tex_warp(v[0].m, v[1].m, &wo, v[0].m->w, v[0].m->h));
}

static int eval(struct S *s, const struct node *n, struct val *out)
{
    struct val v[3] = {{0}};
    int rc = -1;

    memset(out, 0, sizeof *out);
    if (++s->evaldepth > MAX_EVAL_DEPTH) {
        s->evaldepth--;
        return fail_node(s, n, "definitions nested too deeply (more than %d)", MAX_EVAL_DEPTH);
    }
    switch (n->k) {
    case N_REF: rc = eval_def(s, n, out); break;
    case N_PRIM: rc = eval_prim(s, n, out); break;
    case N_FILE: rc = eval_file(s, n, out); break;
    case N_NUM:
        out->c[0] = (float)n->v[0];
        rc = 0;
        break;
    case N_EXPR: rc = eval_x(s, n->x, out); break;
    case N_MIX: rc = eval_mix(s, n, v, out); break;
    case N_EXPAND: rc = eval_expand(s, n, v, out); break;
    case N_ROTATE: rc = eval_rotate(s, n, v, out); break;
    case N_SCALE: rc = eval_scale(s, n, v, out); break;
    case N_RESIZE: rc = eval_resize(s, n, v, out); break;
    case N_SHIFT: rc = eval_shift(s, n, v, out); break;
    case N_CLIP: rc = eval_clip(s, n, v, out); break;
    case N_FILTER: rc = eval_filter(s, n, v, out); break;
    case N_TILE: rc = eval_tile(s, n, v, out); break;
    case N_MATRIX: rc = eval_matrix(s, n, out); break;
    case N_WARP: rc = eval_warp(s, n, v, out); break;
    }
    for (int i = 0; i < 3; i++)
        val_free(&v[i]);
    s->evaldepth--;
    return rc;
}

/* The cells of a brick, hexagonal or triangular tessellation on the canvas: each pixel
 * from the image of the cell whose shape holds it, the image centred in the cell's box. */
static int place_shapes(struct S *s, tex_map *canvas, const struct val *v)
{
    int cols, rows, nc = canvas->nc, rc = 0;
    tess_grid(s, &cols, &rows);
    int *at = malloc((size_t)cols * rows * sizeof *at);
    tex_map **img = calloc(s->ncells ? s->ncells : 1, sizeof *img);

    if (!at || !img) {
        rc = tex_error("out of memory");
        goto done;
    }
    for (int k = 0; k < cols * rows; k++)
        at[k] = -1;
    for (int k = 0; k < s->ncells; k++) {
        tex_map *e = tex_expand(v[k].m, s->cw, s->ch, s->bg);
        img[k] = e && e->nc != nc ? tex_map_channels(e, nc) : e;
        if (img[k] != e)
            tex_map_free(e);
        if (!img[k]) {
            rc = -1;
            goto done;
        }
        at[(s->cells[k].j - 1) * cols + s->cells[k].i - 1] = k;
    }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < s->h; y++)
        for (int x = 0; x < s->w; x++) {
            int i, j, lx, ly;
            tess_locate(s, x, y, &i, &j, &lx, &ly);
            if (i >= 0 && j >= 0 && i < cols && j < rows && at[j * cols + i] >= 0)
                memcpy(tex_map_px(canvas, x, y), tex_map_px(img[at[j * cols + i]], lx, ly),
                       (size_t)nc * sizeof(float));
        }
done:
    for (int k = 0; img && k < s->ncells; k++)
        tex_map_free(img[k]);
    free(img);
    free(at);
    return rc;
}

/* Lay the cells out on the canvas. */
static tex_map *build(struct S *s)
{
    tex_map *canvas = NULL;
    int nc = tex_bg_channels(&(tex_map){.nc = 1}, s->bg);
    struct val *v = calloc(s->ncells ? s->ncells : 1, sizeof *v);

    if (!v)
        return tex_error("out of memory"), NULL;
    if (s->bg[0] != s->bg[1] || s->bg[1] != s->bg[2])
        nc = nc < 3 ? 3 : nc;
    tex_progress_stage(1, s->ncells);
    for (int k = 0; k < s->ncells; k++) {
        int rc;
        tex_progress_hold(1);
        rc = eval_map(s, s->cells[k].expr, &v[k], "a cell");
        tex_progress_hold(0);
        if (rc < 0)
            goto fail;
        tex_progress_add(1);
        if (v[k].m->nc > nc)
            nc = v[k].m->nc;
    }
    for (int k = 0; k < s->ncells; k++)
        if (v[k].m->nc == 2 && nc != 2) {
            fail_node(s, s->cells[k].expr, "a 2-channel image does not combine with colours");
            goto fail;
        }
    /* The canvas: background everywhere, then each cell's image centred in it. */
    {
        float b[4] = {s->bg[0] * s->bg[3], s->bg[1] * s->bg[3], s->bg[2] * s->bg[3], s->bg[3]};
        size_t n = (size_t)s->w * s->h;
        if (nc == 2)
            b[1] = s->bg[3];
        if (!(canvas = tex_map_new(s->w, s->h, nc)))
            goto fail;
        for (size_t i = 0; i < n; i++)
            memcpy(canvas->px + i * nc, b, nc * sizeof *b);
    }
    if (s->kind != T_RECTANGULAR && place_shapes(s, canvas, v) < 0)
        goto fail;
    for (int k = 0; s->kind == T_RECTANGULAR && k < s->ncells; k++) {
        const struct cellref *c = &s->cells[k];
        int x0 = (c->i - 1) * s->cw, y0 = (c->j - 1) * s->ch;
        int cw = x0 + s->cw > s->w ? s->w - x0 : s->cw, ch = y0 + s->ch > s->h ? s->h - y0 : s->ch;
        tex_map *e = tex_expand(v[k].m, cw, ch, s->bg), *f;
        if (!e)
            goto fail;
        f = e->nc == nc ? e : tex_map_channels(e, nc);
        if (f != e)
            tex_map_free(e);
        if (!f)
            goto fail;
        for (int y = 0; y < ch; y++)
            memcpy(tex_map_px(canvas, x0, y0 + y), tex_map_row(f, y), (size_t)cw * nc * 4);
        tex_map_free(f);
    }
    for (int k = 0; k < s->ncells; k++)
        val_free(&v[k]);
    free(v);
    return canvas;
fail:
    for (int k = 0; k < s->ncells; k++)
        val_free(&v[k]);
    free(v);
    tex_map_free(canvas);
    return NULL;
}

/* parse and build longjmp back here on a script error. */
static tex_map *run(struct S *s)
{
    if (setjmp(s->fail))
        return NULL;
    parse(s);
    return build(s);
}

tex_map *tex_script_run(const char *text, size_t len, const char *name,
                        const struct tex_script_opts *o)
{
    static const struct tex_script_opts defaults = TEX_SCRIPT_DEFAULTS;
    struct S *s = calloc(1, sizeof *s);
    tex_map *m = NULL;

    if (!s)
        return tex_error("out of memory"), NULL;
    s->name = name ? name : "script";
    tex_lex_init(&s->lx, text, len, s->name, &s->fail, lex_alloc, s);
    s->xp = (struct tex_expr_parser){&s->lx, &script_lang, s, 0, 0};
    s->o = o ? o : &defaults;
    s->bg[3] = 1.0f;
    m = run(s);
    for (int i = 0; i < s->ndefs; i++)
        tex_map_free(s->defs[i].map);
    free(s->defs);
    tex_names_free(&s->defnames);
    tex_names_free(&s->cellnames);
    free(s->refs);
    free(s->cells);
    tex_procs_free(s->procs); /* after every field made from it */
    while (s->arena) {
        struct chunk *c = s->arena;
        s->arena = c->next;
        free(c);
    }
    free(s);
    return m;
}
