/* proc.c - composed primitives: parsing, compiling, evaluating (see proc.h) */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/names.h"
#include "io/file.h"
#include "lang/expr.h"
#include "lang/lex.h"
#include "lang/proc.h"
#include "lang/rowcode.h"

#define CHUNK 64 /* points evaluated together: the registers live on the stack */
#define NAME_MAX_LEN 63

enum leaf { L_U, L_V, L_W, L_PARAM, L_CALL };

/* One argument of a call: a word or string as written, or an expression of
 * the caller's parameters, evaluated when the field starts. */
struct arg {
    char name[NAME_MAX_LEN + 1];
    char *text;
    struct tex_rowcode *value;
    int line, col;
};

struct call {
    const struct tex_primitive *prim;
    int line, col;
    int ncoord;
    struct tex_rowcode *coord[3];
    int nargs;
    struct arg *args;
};

/* A definition's parameters: the rows point at the names, so the block never moves. */
struct pblock {
    struct tex_param rows[TEX_PROC_MAX_PARAMS + 1];
    char names[TEX_PROC_MAX_PARAMS][NAME_MAX_LEN + 1];
    char *help[TEX_PROC_MAX_PARAMS];
};

static const struct tex_param no_rows[1];

struct proc {
    struct tex_primitive prim; /* first: a field's prim points at the whole */
    char name[NAME_MAX_LEN + 1];
    char *summary, *file;
    struct pblock *pb; /* NULL while there are no parameters: in place, 7 KB per definition */
    int nparams, ncalls, capcalls, depth, line, col;
    struct call *calls; /* grown as calls are read: 256 in place made each definition 23 KB */
    struct tex_rowcode *code;
    struct proc *next;
};

struct tex_procs {
    struct proc *first, *last;
    struct tex_names names; /* each proc by name: a walk of the list per name was quadratic */
    struct proc *building; /* the definition being read, freed if it fails */
};

/* The reader of one definition: expr.h's hook gets it as ctx. */
struct reader {
    struct tex_procs *set;
    struct proc *p;
    struct tex_lexer *lx;
    int nest; /* calls around the current token */
};

/* The field's state: one started field per call. */
struct state {
    struct tex_field *sub[TEX_PROC_MAX_CALLS];
    int channel[TEX_PROC_MAX_CALLS];
};

/* ---- evaluation ---- */

struct run {
    const struct tex_field *f;
    const struct proc *p;
    const struct state *st;
    const double *u, *v, *w; /* w NULL in 2D */
    int solid;
    float *const *pre; /* grid rows: call k's values over the whole row, or NULL */
    int i0;            /* the chunk's first point in those rows */
};

static int leaf(void *ctx, const struct tex_rinsn *in, int n, double *out);

/* Call k of the definition at n points: its coordinates, then its field. */
static int call_row(const struct run *r, int k, int n, double *out)
{
    const struct call *c = &r->p->calls[k];
    const struct tex_field *sub = r->st->sub[k];
    double regs[TEX_PROC_MAX_REGS * CHUNK], xyz[3][CHUNK], zero[CHUNK] = {0};
    const double *at[3] = {r->u, r->v, r->w ? r->w : zero};
    float res[4 * CHUNK];

    if (r->pre && r->pre[k]) { /* sampled already by the callee's own row path */
        const float *pk = r->pre[k] + (size_t)r->i0 * sub->nc + r->st->channel[k];
        for (int i = 0; i < n; i++)
            out[i] = pk[(size_t)i * sub->nc];
        return 0;
    }
    for (int i = 0; i < c->ncoord; i++) {
        if (tex_rowcode_run(c->coord[i], n, regs, leaf, (void *)r) < 0)
            return -1;
        memcpy(xyz[i], regs, sizeof *regs * n);
        at[i] = xyz[i];
    }
    if ((r->solid || c->ncoord == 3 || !sub->prim->eval2) && sub->prim->eval3)
        sub->prim->eval3(sub, n, at[0], at[1], at[2], res);
    else
        sub->prim->eval2(sub, n, at[0], at[1], res);
    for (int i = 0; i < n; i++)
        out[i] = res[i * sub->nc + r->st->channel[k]];
    return 0;
}

static int leaf(void *ctx, const struct tex_rinsn *in, int n, double *out)
{
    const struct run *r = ctx;
    const double *src = NULL;
    switch ((enum leaf)in->leaf) {
    case L_U: src = r->u; break;
    case L_V: src = r->v; break;
    case L_W: src = r->w; break;
    case L_PARAM: {
        double x = ((const double *)r->f->params)[(intptr_t)in->ptr];
        for (int i = 0; i < n; i++)
            out[i] = x;
        return 0;
    }
    case L_CALL: return call_row(r, (int)(intptr_t)in->ptr, n, out);
    }
    for (int i = 0; i < n; i++)
        out[i] = src ? src[i] : 0;
    return 0;
}

/* One chunk of m <= CHUNK points; i0: the chunk's place in pre's rows. */
static void run_chunk(const struct tex_field *f, int m, const double *u, const double *v,
                      const double *w, float *const *pre, int i0, float *out)
{
    double regs[TEX_PROC_MAX_REGS * CHUNK];
    struct run r = {f, (const struct proc *)f->prim, f->state, u, v, w, w != NULL, pre, i0};

    tex_rowcode_run(r.p->code, m, regs, leaf, &r);
    for (int i = 0; i < m; i++) { /* a float map holds finite floats */
        double x = regs[i];
        out[i] = !isfinite(x) ? 0.f : x > FLT_MAX ? FLT_MAX : x < -FLT_MAX ? -FLT_MAX : (float)x;
    }
}

static void run_rows(const struct tex_field *f, int n, const double *u, const double *v,
                     const double *w, float *out)
{
    for (int i0 = 0; i0 < n; i0 += CHUNK)
        run_chunk(f, n - i0 < CHUNK ? n - i0 : CHUNK, u + i0, v + i0, w ? w + i0 : NULL, NULL,
                  0, out + i0);
}

static void eval2(const struct tex_field *f, int n, const double *u, const double *v, float *out)
{
    run_rows(f, n, u, v, NULL, out);
}

static void eval3(const struct tex_field *f, int n, const double *u, const double *v,
                  const double *w, float *out)
{
    run_rows(f, n, u, v, w, out);
}

/* Can call k be sampled by its callee's row path?  At the grid's own points
 * (no coordinates given), when the callee has one and writes values. */
static int by_row(const struct call *c)
{
    return !c->ncoord && c->prim->row && !(c->prim->flags & TEX_PRIM_REGIONS);
}

/* Row y of the grid: the calls that allow it are sampled a whole row at a time
 * by their own row paths (vector kernels, lattice reuse), the rest at points.
 * Without memory for a call's row, that call goes the point path instead. */
static void row(const struct tex_field *f, int y, float *out)
{
    const struct proc *p = (const struct proc *)f->prim;
    const struct state *st = f->state;
    float *pre[TEX_PROC_MAX_CALLS] = {0};
    double u[CHUNK], v[CHUNK];

    for (int k = 0; k < p->ncalls; k++)
        if (by_row(&p->calls[k]) && (pre[k] = malloc(sizeof **pre * st->sub[k]->nc * f->w)))
            p->calls[k].prim->row(st->sub[k], y, pre[k]);
    for (int i = 0; i < CHUNK; i++)
        v[i] = (y + 0.5) / f->h;
    for (int i0 = 0; i0 < f->w; i0 += CHUNK) {
        int m = f->w - i0 < CHUNK ? f->w - i0 : CHUNK;
        for (int i = 0; i < m; i++)
            u[i] = (i0 + i + 0.5) / f->w;
        run_chunk(f, m, u, v, NULL, pre, i0, out + i0);
    }
    for (int k = 0; k < p->ncalls; k++)
        free(pre[k]);
}

static void fini(struct tex_field *f)
{
    struct state *st = f->state;
    const struct proc *p = (const struct proc *)f->prim;
    if (!st)
        return;
    for (int k = 0; k < p->ncalls; k++)
        tex_field_free(st->sub[k]);
    free(st);
    f->state = NULL;
}

/* The argument's value as text for the callee's row. */
static int arg_text(const struct tex_field *f, const struct arg *a, char *buf, size_t n)
{
    double x[TEX_PROC_MAX_REGS];
    struct run r = {f, (const struct proc *)f->prim, NULL, NULL, NULL, NULL, 0, NULL, 0};
    if (a->text) {
        snprintf(buf, n, "%s", a->text);
        return 0;
    }
    tex_rowcode_run(a->value, 1, x, leaf, &r); /* parameters only: no call, no point */
    snprintf(buf, n, "%.17g", x[0]);
    return 0;
}

/* Start one field per call, with the arguments set through the callee's rows. */
static int init(struct tex_field *f)
{
    const struct proc *p = (const struct proc *)f->prim;
    struct state *st = calloc(1, sizeof *st);
    char where[600], text[256];

    if (!st)
        return tex_error("out of memory");
    f->state = st;
    f->nc = 1;
    for (int k = 0; k < p->ncalls; k++) {
        const struct call *c = &p->calls[k];
        struct tex_field *sub = st->sub[k] = tex_field_new(c->prim);
        if (!sub)
            return -1;
        sub->style = TEX_PARAM_WORD;
        sub->seed = f->seed;
        sub->tile = f->tile;
        for (int i = 0; i < c->nargs; i++) {
            const struct arg *a = &c->args[i];
            int rc;
            arg_text(f, a, text, sizeof text);
            snprintf(where, sizeof where, "%s:%d:%d", p->file, a->line, a->col);
            if (!strcmp(a->name, "channel")) {
                double ch;
                rc = tex_parse_real(text, &ch);
                if (rc < 0 || ch != floor(ch) || ch < 0 || ch > 3)
                    rc = tex_usage_error("channel must be 0..3 (got %s)", text);
                else
                    st->channel[k] = (int)ch;
            } else {
                rc = tex_field_set(sub, a->name, text);
                if (!strcmp(a->name, "seed")) /* relative to the composed field's seed */
                    sub->seed = (f->seed + sub->seed) % ((uint64_t)TEX_SEED_MAX + 1);
            }
            if (rc < 0) {
                tex_error_context(where);
                return -1;
            }
        }
        snprintf(where, sizeof where, "%s:%d:%d", p->file, c->line, c->col);
        /* on a grid, the calls sampled by rows see it too; the others are
         * asked once per pixel */
        sub->queries = f->w ? (long)f->w * f->h : f->queries;
        if (tex_field_init(sub, by_row(c) ? f->w : 0, by_row(c) ? f->h : 0) < 0) {
            tex_error_context(where);
            return -1;
        }
        if (sub->nc > 4 || st->channel[k] >= sub->nc) {
            tex_usage_error("%s has %d channel%s (channel %d asked)", c->prim->name, sub->nc,
                            sub->nc > 1 ? "s" : "", st->channel[k]);
            tex_error_context(where);
            return -1;
        }
    }
    return 0;
}

/* ---- reading ---- */

static void proc_free(struct proc *p)
{
    if (!p)
        return;
    for (int k = 0; k < p->ncalls; k++) {
        struct call *c = &p->calls[k];
        for (int i = 0; i < c->ncoord; i++)
            tex_rowcode_free(c->coord[i]);
        for (int i = 0; i < c->nargs; i++) {
            free(c->args[i].text);
            tex_rowcode_free(c->args[i].value);
        }
        free(c->args);
    }
    /* a help read before its row failed too */
    for (int i = 0; p->pb && i < TEX_PROC_MAX_PARAMS; i++)
        free(p->pb->help[i]);
    free(p->pb);
    tex_rowcode_free(p->code);
    free(p->calls);
    free(p->summary);
    free(p->file);
    free(p);
}

static void *xalloc(struct tex_lexer *lx, void *q)
{
    if (!q) {
        tex_error("%s:%d:%d: out of memory", lx->name, lx->t.line, lx->t.col);
        longjmp(*lx->fail, 1);
    }
    return q;
}

static char *tok_copy(struct tex_lexer *lx, const struct tex_tok *t)
{
    char *s = xalloc(lx, malloc(t->len + 1));
    memcpy(s, t->text, t->len);
    s[t->len] = 0;
    return s;
}


static void name_of(struct tex_lexer *lx, char *out, const char *what)
{
    char b[48];
    if (lx->t.kind != TEX_TOK_NAME)
        tex_lex_fail(lx, lx->t.line, lx->t.col, "expected %s, found %s", what,
                     tex_tok_desc(&lx->t, b, sizeof b));
    if (lx->t.len > NAME_MAX_LEN)
        tex_lex_fail(lx, lx->t.line, lx->t.col, "name too long (more than %d characters)",
                     NAME_MAX_LEN);
    memcpy(out, lx->t.text, lx->t.len);
    out[lx->t.len] = 0;
    tex_lex_next(lx);
}


static double number(struct tex_lexer *lx, const char *what)
{
    char b[48];
    double x = lx->t.num;
    if (lx->t.kind != TEX_TOK_NUM)
        tex_lex_fail(lx, lx->t.line, lx->t.col, "expected %s, found %s", what,
                     tex_tok_desc(&lx->t, b, sizeof b));
    tex_lex_next(lx);
    return x;
}

static void expect_word(struct tex_lexer *lx, const char *w)
{
    char b[48];
    if (!tex_tok_is_word(&lx->t, w))
        tex_lex_fail(lx, lx->t.line, lx->t.col, "expected '%s', found %s", w,
                     tex_tok_desc(&lx->t, b, sizeof b));
    tex_lex_next(lx);
}

/* The token after the current one. */
static struct tex_tok peek(const struct tex_lexer *lx)
{
    struct tex_lexer l = *lx;
    tex_lex_next(&l);
    return l.t;
}

static int param_index(const struct proc *p, const struct tex_tok *t)
{
    for (int i = 0; i < p->nparams; i++)
        if (tex_tok_is_word(t, p->pb->names[i]))
            return i;
    return -1;
}

static int is_coordinate(const struct tex_tok *t)
{
    return tex_tok_is_word(t, "u") || tex_tok_is_word(t, "v") || tex_tok_is_word(t, "w") ||
           tex_tok_is_word(t, "pi");
}

/* Compile e into register code; fail at e's position when it is a colour or
 * needs too many registers. */
static struct tex_rowcode *compile(struct reader *rd, const struct tex_enode *e)
{
    struct tex_expr *x = tex_expr_compile(rd->lx, e);
    struct tex_rowcode *rc = tex_rowcode_new(x);
    if (!rc)
        tex_lex_fail(rd->lx, e->line, e->col, "%s", tex_errmsg());
    if (rc->nreg > TEX_PROC_MAX_REGS) {
        tex_rowcode_free(rc);
        tex_lex_fail(rd->lx, e->line, e->col,
                     "expression too complex (more than %d values pending)", TEX_PROC_MAX_REGS);
    }
    return rc;
}

static void named_arg(struct tex_expr_parser *xp, struct call *c)
{
    struct reader *rd = xp->ctx;
    struct tex_lexer *lx = rd->lx;
    struct arg *a = &c->args[c->nargs];
    struct tex_tok after;

    a->line = lx->t.line;
    a->col = lx->t.col;
    name_of(lx, a->name, "a parameter name");
    if (!strcmp(a->name, "size"))
        tex_lex_fail(lx, a->line, a->col, "size has no meaning at a point");
    if (strcmp(a->name, "channel") && !tex_param_find(c->prim->params, a->name) &&
        !tex_param_find(tex_field_rows, a->name)) {
        char near[64], hint[80] = "";
        if (tex_param_nearest(c->prim->params, -1, a->name, near, sizeof near))
            snprintf(hint, sizeof hint, "; did you mean %s?", near);
        tex_lex_fail(lx, a->line, a->col, "%s has no parameter '%s'%s", c->prim->name, a->name,
                     hint);
    }
    for (int i = 0; i < c->nargs; i++)
        if (!strcmp(c->args[i].name, a->name))
            tex_lex_fail(lx, a->line, a->col, "%s is given twice", a->name);
    tex_lex_expect(lx, '=');
    c->nargs++; /* from here on, what it holds is freed with the definition */
    after = peek(lx);
    if (lx->t.kind == TEX_TOK_STR ||
        (lx->t.kind == TEX_TOK_NAME && param_index(rd->p, &lx->t) < 0 && !is_coordinate(&lx->t) &&
         (tex_tok_is_punct(&after, ',') || tex_tok_is_punct(&after, ')')))) {
        a->text = tok_copy(lx, &lx->t); /* a word: the callee's row reads it */
        tex_lex_next(lx);
    } else {
        int line = lx->t.line, col = lx->t.col;
        a->value = compile(rd, tex_expr_parse(xp));
        for (int i = 0; i < a->value->n; i++)
            if (a->value->code[i].op == TEX_EOP_LEAF && a->value->code[i].leaf != L_PARAM)
                tex_lex_fail(lx, line, col, "the value of %s must not depend on the "
                             "point (a number or %s's parameters)", a->name, rd->p->name);
    }
}

/* "unknown primitive or function 'nosie'; did you mean noise?", at e. */
__attribute__((noreturn)) static void unknown_callee(struct tex_lexer *lx,
                                                    const struct tex_enode *e, const char *name)
{
    char near[64], hint[96] = "";
    if (tex_primitive_nearest(name, near, sizeof near))
        snprintf(hint, sizeof hint, "; did you mean %s?", near);
    tex_lex_fail(lx, e->line, e->col, "unknown primitive or function '%s'%s", name, hint);
}

/* NAME(coordinates, name = value, ...) at the current token. */
static struct tex_enode *call(struct tex_expr_parser *xp)
{
    struct reader *rd = xp->ctx;
    struct tex_lexer *lx = rd->lx;
    struct proc *p = rd->p;
    struct tex_enode *e = tex_expr_node(lx, TEX_EK_LEAF, &lx->t);
    char name[NAME_MAX_LEN + 1];
    const struct tex_primitive *callee;
    struct call *c;
    int depth;

    name_of(lx, name, "a primitive");
    if (!strcmp(name, p->name))
        tex_lex_fail(lx, e->line, e->col, "recursive definition: '%s' calls itself", name);
    if (!(callee = tex_procs_find(rd->set, name)))
        unknown_callee(lx, e, name);
    if (!callee->eval2 && !callee->eval3)
        tex_lex_fail(lx, e->line, e->col, "%s is made on a whole grid: it has no value at a "
                     "point to compose", name);
    if (p->ncalls == TEX_PROC_MAX_CALLS)
        tex_lex_fail(lx, e->line, e->col, "too many calls (more than %d)", TEX_PROC_MAX_CALLS);
    depth = rd->nest + 1 + (callee->init == init ? ((const struct proc *)callee)->depth : 0);
    if (depth > TEX_PROC_MAX_NEST)
        tex_lex_fail(lx, e->line, e->col, "calls nested too deeply (more than %d levels, "
                     "counting those of the primitives called)", TEX_PROC_MAX_NEST);
    if (depth > p->depth)
        p->depth = depth;
    if (p->ncalls == p->capcalls) {
        int cap = p->capcalls ? 2 * p->capcalls : 4;
        struct call *nc = xalloc(lx, realloc(p->calls, cap * sizeof *nc));
        memset(nc + p->ncalls, 0, (size_t)(cap - p->ncalls) * sizeof *nc);
        p->calls = nc;
        p->capcalls = cap;
    }
    c = &p->calls[p->ncalls];
    c->prim = callee;
    c->line = e->line;
    c->col = e->col;
    c->args = xalloc(lx, calloc(64, sizeof *c->args));
    e->op = L_CALL;
    int k = p->ncalls++;
    e->ptr = (const void *)(intptr_t)k;
    tex_lex_expect(lx, '(');
    tex_expr_enter(xp);
    rd->nest++;
    for (int first = 1; !tex_tok_is_punct(&lx->t, ')'); first = 0) {
        struct tex_tok after;
        c = &p->calls[k]; /* calls inside the arguments may have moved the array */
        if (!first)
            tex_lex_expect(lx, ',');
        after = peek(lx);
        if (lx->t.kind == TEX_TOK_NAME && tex_tok_is_punct(&after, '=')) {
            if (c->nargs == 64)
                tex_lex_fail(lx, lx->t.line, lx->t.col, "too many parameters");
            named_arg(xp, c);
            continue;
        }
        if (c->nargs)
            tex_lex_fail(lx, lx->t.line, lx->t.col,
                         "coordinates come before the named parameters");
        if (c->ncoord == 3)
            tex_lex_fail(lx, lx->t.line, lx->t.col, "%s takes at most 3 coordinates (u, v, w)",
                         name);
        struct tex_rowcode *rc = compile(rd, tex_expr_parse(xp));
        c = &p->calls[k];
        c->coord[c->ncoord++] = rc;
    }
    c = &p->calls[k];
    tex_lex_next(lx);
    rd->nest--;
    tex_expr_leave(xp);
    if (c->ncoord == 3 && !callee->eval3)
        tex_lex_fail(lx, e->line, e->col, "%s has no solid (3D) form: give it u and v only", name);
    if (!callee->eval3)
        p->prim.flags &= ~(unsigned)TEX_PRIM_3D;
    if (!(callee->flags & TEX_PRIM_TILE))
        p->prim.flags &= ~(unsigned)TEX_PRIM_TILE;
    return e;
}

static struct tex_enode *operand(struct tex_expr_parser *xp)
{
    struct reader *rd = xp->ctx;
    struct tex_lexer *lx = rd->lx;
    struct tex_tok t = lx->t, after;
    struct tex_enode *e;
    int i;
    char b[48];

    if (t.kind != TEX_TOK_NAME)
        tex_lex_fail(lx, t.line, t.col, "expected a number, a name or '(', found %s",
                     tex_tok_desc(&t, b, sizeof b));
    after = peek(lx);
    if (tex_tok_is_punct(&after, '('))
        return call(xp);
    e = tex_expr_node(lx, TEX_EK_LEAF, &t);
    if (tex_tok_is_word(&t, "pi")) {
        e->kind = TEX_EK_NUM;
        e->v[0] = M_PI;
    } else if (tex_tok_is_word(&t, "u") || tex_tok_is_word(&t, "v") ||
               tex_tok_is_word(&t, "w")) {
        e->op = t.text[0] == 'u' ? L_U : t.text[0] == 'v' ? L_V : L_W;
    } else if ((i = param_index(rd->p, &t)) >= 0) {
        e->op = L_PARAM;
        e->ptr = (const void *)(intptr_t)i;
    } else {
        tex_lex_fail(lx, t.line, t.col, "unknown name '%.*s' (not u, v, w, pi or a parameter "
                     "of %s)", (int)(t.len > 32 ? 32 : t.len), t.text, rd->p->name);
    }
    tex_lex_next(lx);
    return e;
}

/* Names a parameter cannot take: the language's own and the tools' options. */
static const char *const reserved[] = {
    "u", "v", "w", "pi", "seed", "tile", "ids", "size", "channel", "output", "depth",
    "compression", "format", "threads", "quiet", "help", "version", "palette", "nonfinite",
    "defs", "primitive", NULL};

static void check_name(struct reader *rd, const char *name, int line, int col, int param)
{
    struct tex_tok t = {TEX_TOK_NAME, name, strlen(name), 0, line, col};
    for (int i = 0; reserved[i]; i++)
        if (!strcmp(name, reserved[i]))
            tex_lex_fail(rd->lx, line, col, "'%s' is a reserved word", name);
    if (tex_expr_func_find(&t))
        tex_lex_fail(rd->lx, line, col, "'%s' is a function", name);
    if (param) {
        if (param_index(rd->p, &t) >= 0)
            tex_lex_fail(rd->lx, line, col, "parameter '%s' is declared twice", name);
        return;
    }
    if (tex_primitive_get(name))
        tex_lex_fail(rd->lx, line, col, "'%s' is a primitive already", name);
    const struct proc *q = tex_names_get(&rd->set->names, name);
    if (q)
        tex_lex_fail(rd->lx, line, col, "primitive '%s' is defined twice (first at %s:%d:%d)",
                     name, q->file, q->line, q->col);
}

/* ( NAME = DEFAULT in MIN to MAX ["help"], ... ) */
static void params(struct reader *rd)
{
    struct tex_lexer *lx = rd->lx;
    struct proc *p = rd->p;

    tex_lex_expect(lx, '(');
    for (int first = 1; !tex_tok_is_punct(&lx->t, ')'); first = 0) {
        int i = p->nparams, line = lx->t.line, col = lx->t.col;
        double def, lo, hi;
        if (!first)
            tex_lex_expect(lx, ',');
        if (i == TEX_PROC_MAX_PARAMS)
            tex_lex_fail(lx, line, col, "too many parameters (more than %d)",
                         TEX_PROC_MAX_PARAMS);
        line = lx->t.line, col = lx->t.col;
        struct pblock *pb = p->pb ? p->pb : (p->pb = xalloc(lx, calloc(1, sizeof *p->pb)));
        name_of(lx, pb->names[i], "a parameter name");
        check_name(rd, pb->names[i], line, col, 1);
        tex_lex_expect(lx, '=');
        def = number(lx, "the default (a number)");
        expect_word(lx, "in");
        lo = number(lx, "the least value (a number)");
        expect_word(lx, "to");
        hi = number(lx, "the greatest value (a number)");
        if (!(lo <= hi) || !(def >= lo && def <= hi))
            tex_lex_fail(lx, line, col, "parameter %s: the default %g is not in %g..%g",
                         pb->names[i], def, lo, hi);
        if (lx->t.kind == TEX_TOK_STR) {
            pb->help[i] = tok_copy(lx, &lx->t);
            tex_lex_next(lx);
        }
        pb->rows[i] = (struct tex_param){pb->names[i], 0, TEX_P_REAL, i * sizeof(double), def,
                                         lo, hi, NULL, NULL, 0, "X",
                                         pb->help[i] ? pb->help[i] : "a parameter", 0, 0, 0,
                                         NULL, NULL, NULL, NULL};
        p->nparams++;
    }
    tex_lex_next(lx);
}

static void body(struct reader *rd)
{
    static const struct tex_expr_lang lang = {tex_expr_arith_binops, operand};
    struct tex_expr_parser xp = {rd->lx, &lang, rd, 0, 0};
    struct proc *p = rd->p;

    p->prim.flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE;
    p->code = compile(rd, tex_expr_parse(&xp));
    p->prim.name = p->name;
    p->prim.summary = p->summary ? p->summary : "a composed primitive";
    p->prim.params_size = p->nparams * sizeof(double);
    p->prim.params = p->pb ? p->pb->rows : no_rows;
    p->prim.init = init;
    p->prim.fini = fini;
    p->prim.eval2 = eval2;
    p->prim.eval3 = p->prim.flags & TEX_PRIM_3D ? eval3 : NULL;
    p->prim.row = row;
}

/* Start the field once with the defaults: arguments out of their callee's
 * range are found now, at their position. */
static void trial(struct reader *rd)
{
    struct tex_field *f = tex_field_new(&rd->p->prim);
    if (f)
        f->queries = 1; /* asked nothing: search tables that pay off over many points wait */
    int rc = f ? tex_field_init(f, 0, 0) : -1;
    tex_field_free(f);
    if (rc < 0)
        longjmp(*rd->lx->fail, 1);
}

static const struct tex_primitive *finish(struct reader *rd)
{
    struct tex_procs *set = rd->set;
    trial(rd);
    if (tex_names_put(&set->names, rd->p->name, rd->p) < 0)
        longjmp(*rd->lx->fail, 1);
    if (set->last)
        set->last->next = rd->p;
    else
        set->first = rd->p;
    set->last = rd->p;
    set->building = NULL;
    return &rd->p->prim;
}

static struct proc *start(struct tex_procs *set, struct tex_lexer *lx)
{
    proc_free(set->building);
    set->building = NULL;
    struct proc *p = xalloc(lx, calloc(1, sizeof *p));
    set->building = p;
    p->file = xalloc(lx, strdup(lx->name));
    p->line = lx->t.line;
    p->col = lx->t.col;
    return p;
}

const struct tex_primitive *tex_procs_define(struct tex_procs *set, struct tex_lexer *lx)
{
    struct reader rd = {set, start(set, lx), lx, 0};
    int line = lx->t.line, col = lx->t.col;

    name_of(lx, rd.p->name, "the new primitive's name");
    check_name(&rd, rd.p->name, line, col, 0);
    if (tex_tok_is_punct(&lx->t, '('))
        params(&rd);
    if (lx->t.kind == TEX_TOK_STR) {
        rd.p->summary = tok_copy(lx, &lx->t);
        tex_lex_next(lx);
    }
    tex_lex_expect(lx, '=');
    body(&rd);
    if (tex_tok_is_punct(&lx->t, ';'))
        tex_lex_next(lx);
    return finish(&rd);
}

/* Memory for one reading's tokens and trees, freed when it ends. */
struct chunk {
    struct chunk *next;
    max_align_t data[];
};
struct pool {
    struct chunk *head;
    jmp_buf *fail;
};

static void *pool_alloc(void *ctx, size_t n)
{
    struct pool *pl = ctx;
    struct chunk *c = calloc(1, sizeof *c + n);
    if (!c) { /* the lexer's alloc does not return NULL */
        tex_error("out of memory");
        longjmp(*pl->fail, 1);
    }
    c->next = pl->head;
    pl->head = c;
    return c->data;
}

static void pool_free(struct pool *pl)
{
    for (struct chunk *c = pl->head, *n; c; c = n) {
        n = c->next;
        free(c);
    }
    pl->head = NULL;
}

int tex_procs_load(struct tex_procs *set, const char *text, size_t len, const char *name)
{
    struct tex_lexer lx;
    jmp_buf fail;
    struct pool pool = {NULL, &fail};
    char b[48];

    if (setjmp(fail)) {
        pool_free(&pool);
        proc_free(set->building);
        set->building = NULL;
        return -1;
    }
    tex_lex_init(&lx, text, len, name, &fail, pool_alloc, &pool);
    tex_lex_next(&lx);
    while (lx.t.kind != TEX_TOK_EOF) {
        if (!tex_tok_is_word(&lx.t, "primitive"))
            tex_lex_fail(&lx, lx.t.line, lx.t.col, "expected 'primitive', found %s",
                         tex_tok_desc(&lx.t, b, sizeof b));
        tex_lex_next(&lx);
        tex_procs_define(set, &lx);
    }
    pool_free(&pool);
    return 0;
}

int tex_procs_read(struct tex_procs *set, const char *path)
{
    size_t n;
    char *text = tex_read_text(path, 1u << 24, &n, "a definitions file");
    int rc;
    if (!text)
        return -1;
    rc = tex_procs_load(set, text, n, path);
    free(text);
    return rc;
}

const struct tex_primitive *tex_procs_expr(struct tex_procs *set, const char *text,
                                           const char *name, const char *where)
{
    struct tex_lexer lx;
    jmp_buf fail;
    struct pool pool = {NULL, &fail};
    struct reader rd = {set, NULL, &lx, 0};
    const struct tex_primitive *p;
    char b[48];

    if (setjmp(fail)) {
        pool_free(&pool);
        proc_free(set->building);
        set->building = NULL;
        return NULL;
    }
    tex_lex_init(&lx, text, strlen(text), where, &fail, pool_alloc, &pool);
    tex_lex_next(&lx);
    rd.p = start(set, &lx);
    snprintf(rd.p->name, sizeof rd.p->name, "%s", name);
    body(&rd);
    if (lx.t.kind != TEX_TOK_EOF)
        tex_lex_fail(&lx, lx.t.line, lx.t.col, "expected an operator or the end, found %s",
                     tex_tok_desc(&lx.t, b, sizeof b));
    p = finish(&rd);
    pool_free(&pool);
    return p;
}

struct tex_procs *tex_procs_new(void)
{
    struct tex_procs *set = calloc(1, sizeof *set);
    if (!set)
        tex_error("out of memory");
    return set;
}

void tex_procs_free(struct tex_procs *set)
{
    if (!set)
        return;
    for (struct proc *p = set->first, *n; p; p = n) {
        n = p->next;
        proc_free(p);
    }
    proc_free(set->building);
    tex_names_free(&set->names);
    free(set);
}

const struct tex_primitive *tex_procs_find(const struct tex_procs *set, const char *name)
{
    const struct proc *p = set ? tex_names_get(&set->names, name) : NULL;
    return p ? &p->prim : tex_primitive_find(name);
}

const struct tex_primitive *tex_procs_get(const struct tex_procs *set, int i)
{
    const struct proc *p = set ? set->first : NULL;
    while (p && i-- > 0)
        p = p->next;
    return p ? &p->prim : NULL;
}
