/* test_lang.c - the shared lexer and expression grammar (lang/lex.h, lang/expr.h) */
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "lang/expr.h"
#include "lang/lex.h"
#include "lang/script.h"
#include "render/scene.h"
#include "unit.h"

/* Memory for tokens and nodes: a list freed at the end. */
static void *blocks[1 << 17];
static int nblocks;

static void *alloc(void *ctx, size_t n)
{
    (void)ctx;
    if (nblocks == (int)(sizeof blocks / sizeof *blocks))
        abort();
    return blocks[nblocks++] = calloc(1, n);
}

static void free_all(void)
{
    while (nblocks)
        free(blocks[--nblocks]);
}

/* The test language: the operand x, and + - * / as in scenes. */
static struct tex_enode *operand(struct tex_expr_parser *xp)
{
    struct tex_lexer *lx = xp->lx;
    if (!tex_tok_is_word(&lx->t, "x"))
        tex_lex_fail(lx, lx->t.line, lx->t.col, "expected x");
    struct tex_enode *e = tex_expr_node(lx, TEX_EK_LEAF, &lx->t);
    tex_lex_next(lx);
    return e;
}

static const struct tex_expr_binop ops[] = {{"+", 1, TEX_EOP_ADD}, {"-", 1, TEX_EOP_SUB},
                                            {"*", 2, TEX_EOP_MUL}, {"/", 2, TEX_EOP_DIV},
                                            {NULL, 0, 0}};
static const struct tex_expr_lang lang = {ops, operand};

/* Compile text; NULL with tex_errmsg() on an error. */
static struct tex_expr *compile(const char *text)
{
    static struct tex_lexer lx;
    static jmp_buf fail;
    static struct tex_expr_parser xp;
    tex_lex_init(&lx, text, strlen(text), "t.x", &fail, alloc, NULL);
    xp = (struct tex_expr_parser){&lx, &lang, NULL, 0, 0};
    if (setjmp(fail))
        return NULL;
    tex_lex_next(&lx);
    struct tex_expr *e = tex_expr_compile(&lx, tex_expr_parse(&xp));
    if (lx.t.kind != TEX_TOK_EOF)
        tex_lex_fail(&lx, lx.t.line, lx.t.col, "left over");
    return e;
}

/* Run e's program (as the renderer does) with x = 2 on every channel. */
static double run(const struct tex_expr *e)
{
    double st[TEX_EXPR_MAX_STACK][3];
    int sp = 0;
    for (int i = 0; i < e->n; i++) {
        const struct tex_einsn *in = &e->code[i];
        double *a = sp ? st[sp - 1] : NULL, *b = st[sp];
        switch (in->op) {
        case TEX_EOP_CONST: memcpy(st[sp++], in->v, sizeof in->v); break;
        case TEX_EOP_LEAF: st[sp][0] = st[sp][1] = st[sp][2] = 2, sp++; break;
        case TEX_EOP_NEG: a[0] = -a[0]; break;
        case TEX_EOP_ABS: a[0] = a[0] < 0 ? -a[0] : a[0]; break;
        case TEX_EOP_RGB: sp -= 2; break;
        default:
            b = st[--sp], a = st[sp - 1];
            a[0] = in->op == TEX_EOP_ADD   ? a[0] + b[0]
                   : in->op == TEX_EOP_SUB ? a[0] - b[0]
                   : in->op == TEX_EOP_MUL ? a[0] * b[0]
                   : in->op == TEX_EOP_MIN ? (a[0] < b[0] ? a[0] : b[0])
                   : in->op == TEX_EOP_MAX ? (a[0] > b[0] ? a[0] : b[0])
                                           : (b[0] != 0 ? a[0] / b[0] : 0);
        }
    }
    return st[0][0];
}

/* "TERM OP TERM OP ..." of n terms, allocated */
static char *chain(const char *term, const char *op, int n)
{
    size_t tl = strlen(term), ol = strlen(op);
    char *s = malloc((size_t)n * (tl + ol) + 1), *p = s;
    for (int i = 0; i < n; i++) {
        memcpy(p, term, tl), p += tl;
        if (i + 1 < n)
            memcpy(p, op, ol), p += ol;
    }
    *p = '\0';
    return s;
}

static void test_lexer(void)
{
    static const char text[] = "size-spread -0.5 .25 \"a\\\"b\" # comment\n  { ;x-1";
    jmp_buf fail;
    struct tex_lexer lx;
    tex_lex_init(&lx, text, sizeof text - 1, "t.x", &fail, alloc, NULL);
    if (setjmp(fail)) {
        CHECKF(0, "lexer: no error (%s)", tex_errmsg());
        return;
    }
    tex_lex_next(&lx);
    CHECK(tex_tok_is_word(&lx.t, "size-spread"), "a hyphen before a letter joins the name");
    tex_lex_next(&lx);
    CHECK(lx.t.kind == TEX_TOK_NUM && lx.t.num == -0.5 && tex_tok_is_signed(&lx.t),
          "a sign written before a number is part of it");
    tex_lex_next(&lx);
    CHECK(lx.t.kind == TEX_TOK_NUM && lx.t.num == 0.25, "a number may start with '.'");
    tex_lex_next(&lx);
    CHECK(lx.t.kind == TEX_TOK_STR && lx.t.len == 3 && !memcmp(lx.t.text, "a\"b", 3),
          "a backslash escapes a quote in a string");
    tex_lex_next(&lx);
    CHECK(tex_tok_is_punct(&lx.t, '{') && lx.t.line == 2 && lx.t.col == 3,
          "comments are skipped; line and column from 1");
    tex_lex_next(&lx);
    CHECK(tex_tok_is_punct(&lx.t, ';'), "';' is punctuation unless semicolon_blank");
    tex_lex_next(&lx);
    CHECK(tex_tok_is_word(&lx.t, "x"), "a hyphen before a digit ends the name");
    tex_lex_next(&lx);
    CHECK(tex_tok_is_signed(&lx.t), "... and signs the number after it");
}

static void test_errors(void)
{
    struct {
        const char *text, *msg;
    } bad[] = {
        {"x + 3y", "t.x:1:5: malformed number '3y'"},
        {"x + @", "t.x:1:5: unexpected character '@'"},
        {"x + \"abc", "t.x:1:5: unterminated string"},
        {"min(x)", "t.x:1:1: min takes 2 arguments"},
        {"x + 1e999", "t.x:1:5: number out of range"},
        {"(x", "t.x:1:3: expected ')', found the end of the file"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        CHECKF(!compile(bad[i].text) && tex_errkind() == TEX_ERR_USAGE &&
                   !strcmp(tex_errmsg(), bad[i].msg),
               "'%s' fails with '%s' (got '%s')", bad[i].text, bad[i].msg, tex_errmsg());
    }
}

/* The largest stack e's code needs, by running it on counts (depth may be
 * more: it counts constants before they fold) */
static int stack_needed(const struct tex_expr *e)
{
    int sp = 0, most = 0;
    for (int i = 0; i < e->n; i++) {
        sp += 1 - tex_expr_arity(e->code[i].op);
        most = sp > most ? sp : most;
    }
    return most;
}

static void test_eval(void)
{
    struct {
        const char *text;
        double want;
        int n; /* instructions after folding (0: do not check) */
    } good[] = {
        {"1 + 2 * 3", 7, 1},      {"(1 + 2) * 3", 9, 1}, {"x -1", 1, 3},
        {"x - -1", 3, 3},         {"8 / 2 / 2", 2, 1},   {"1 / 0", 0, 1},
        {"-x * 3", -6, 0},        {"min(x, 1) + max(x, 5) + abs(0 - x)", 8, 0},
        {"rgb(x, 0, 0)", 2, 0},   {"0.5 0.25 1 * x", 1, 3},
        /* folded constants before a deeper stack (the evaluators size theirs by depth) */
        {"3 * 8 * x - 0.9 * x", 46.2, 7}, {"0. / 5 * x * x + 0.6 * x", 1.2, 0},
        {"(1 + 2) * x + x * (x - 1 * 2)", 6, 0}, {"min(1, 2) * max(x, x * (1 - x))", 2, 0},
    };
    for (size_t i = 0; i < sizeof good / sizeof *good; i++) {
        struct tex_expr *e = compile(good[i].text);
        double v = e ? run(e) : -1;
        CHECKF(e && v == good[i].want && (!good[i].n || e->n == good[i].n),
               "'%s' = %g in %d instructions (got %g in %d: %s)", good[i].text, good[i].want,
               good[i].n, v, e ? e->n : -1, e ? "" : tex_errmsg());
        CHECKF(e && e->depth >= stack_needed(e), "'%s' declares the stack it needs, %d (got %d)",
               good[i].text, e ? stack_needed(e) : -1, e ? e->depth : -1);
    }
}

static void test_limits(void)
{
    char *ok = chain("x", " + ", TEX_EXPR_MAX_TERMS + 1), *too = chain("x", " * ", 100000);
    struct tex_expr *e = compile(ok);
    CHECKF(e && run(e) == 2.0 * (TEX_EXPR_MAX_TERMS + 1) && e->depth == 2,
           "a chain of %d operators compiles, on a stack of 2", TEX_EXPR_MAX_TERMS);
    CHECKF(!compile(too) && strstr(tex_errmsg(), "t.x:1:") &&
               strstr(tex_errmsg(), "expression too long (more than 10000 operators)"),
           "a 100000-term product is refused (%s)", tex_errmsg());
    free(ok);
    free(too);
    char deep[2 * TEX_EXPR_MAX_DEPTH + 8], *p = deep;
    for (int i = 0; i < TEX_EXPR_MAX_DEPTH - 1; i++)
        *p++ = '(';
    *p++ = 'x';
    for (int i = 0; i < TEX_EXPR_MAX_DEPTH - 1; i++)
        *p++ = ')';
    *p = '\0';
    CHECK(compile(deep) != NULL, "100 levels of nesting are read");
    memmove(deep + 1, deep, strlen(deep) + 1);
    deep[0] = '-';
    CHECKF(!compile(deep) && strstr(tex_errmsg(), "nested too deeply (more than 100 levels)"),
           "101 levels are not (%s)", tex_errmsg());
}

/* Both languages, through their public entry points. */
static void test_languages(void)
{
    char *sum = chain("f", " + ", 100000), *text = malloc(strlen(sum) + 200);
    sprintf(text, "texture t noise { }\nsurface s { apply t { Kd = %s } }\n", sum);
    struct tex_scene *s = tex_scene_parse(text, strlen(text), "l.scene");
    CHECKF(!s && tex_errkind() == TEX_ERR_USAGE && !strncmp(tex_errmsg(), "l.scene:2:", 10) &&
               strstr(tex_errmsg(), "expression too long"),
           "scene: a 100000-term sum is refused (%s)", tex_errmsg());
    tex_scene_free(s);
    free(sum);
    sum = chain("noise()", " + ", 100000);
    text = realloc(text, strlen(sum) + 200);
    sprintf(text, "tessellation t; size 4 by 4;\nbuilt with (1,1) %s; end tessellation;\n", sum);
    tex_map *m = tex_script_run(text, strlen(text), "l.tc", NULL);
    CHECKF(!m && tex_errkind() == TEX_ERR_USAGE && !strncmp(tex_errmsg(), "l.tc:2:", 7) &&
               strstr(tex_errmsg(), "expression too long"),
           "script: a 100000-term sum is refused (%s)", tex_errmsg());
    tex_map_free(m);
    static const char scene[] = "texture t bubble { size-spread 0.5 }\n"
                                "surface s { apply t { Kd = max(f, 0.5) } }\nsphere { surface s }\n";
    s = tex_scene_parse(scene, sizeof scene - 1, "h.scene");
    CHECKF(s != NULL, "scene: size-spread and max() (%s)", s ? "" : tex_errmsg());
    tex_scene_free(s);
    static const char script[] = "tessellation t; size 4 by 4;\n"
                                 "built with (1,1) max(bubble(size-spread = 0.5), 0.5); "
                                 "end tessellation;\n";
    m = tex_script_run(script, sizeof script - 1, "h.tc", NULL);
    CHECKF(m != NULL, "script: size-spread and max() (%s)", m ? "" : tex_errmsg());
    tex_map_free(m);
    free(sum);
    free(text);
}

int main(void)
{
    test_lexer();
    test_errors();
    test_eval();
    test_limits();
    test_languages();
    free_all();
    return unit_done();
}
