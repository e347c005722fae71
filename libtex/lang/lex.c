/* lex.c - the one lexer of the scene and script languages (see lex.h) */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lang/lex.h"

void tex_lex_vfail(struct tex_lexer *lx, enum tex_err_kind kind, int line, int col,
                   const char *fmt, va_list ap)
{
    char msg[512];
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (kind == TEX_ERR_RUNTIME)
        tex_error("%s:%d:%d: %s", lx->name, line, col, msg);
    else
        tex_usage_error("%s:%d:%d: %s", lx->name, line, col, msg);
    longjmp(*lx->fail, 1);
}

void tex_lex_fail(struct tex_lexer *lx, int line, int col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    tex_lex_vfail(lx, TEX_ERR_USAGE, line, col, fmt, ap);
}

int tex_lang_error(const char *name, int line, int col, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return tex_usage_error("%s:%d:%d: %s", name, line, col, msg);
}

void tex_lex_init(struct tex_lexer *lx, const char *text, size_t len, const char *name,
                  jmp_buf *fail, void *(*alloc)(void *ctx, size_t n), void *ctx)
{
    memset(lx, 0, sizeof *lx);
    lx->p = text;
    lx->end = text + len;
    lx->name = name;
    lx->line = lx->col = 1;
    lx->fail = fail;
    lx->alloc = alloc;
    lx->ctx = ctx;
}

static int is_name0(int c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

static int is_digit(int c)
{
    return c >= '0' && c <= '9';
}

static int is_name(int c)
{
    return is_name0(c) || is_digit(c);
}

/* Move n bytes on, none of them a newline. */
static void skip(struct tex_lexer *lx, size_t n)
{
    lx->p += n;
    lx->col += (int)n;
}

static void blanks(struct tex_lexer *lx)
{
    while (lx->p < lx->end) {
        char c = *lx->p;
        if (c == '\n') {
            lx->p++;
            lx->line++;
            lx->col = 1;
        } else if (c == ' ' || c == '\t' || c == '\r' || (c == ';' && lx->semicolon_blank)) {
            skip(lx, 1);
        } else if (c == '#') {
            while (lx->p < lx->end && *lx->p != '\n')
                skip(lx, 1);
        } else {
            break;
        }
    }
}

/* Does a number start at q (a digit, or '.' then a digit)? */
static int number_at(const struct tex_lexer *lx, const char *q)
{
    return q < lx->end &&
           (is_digit(*q) || (*q == '.' && q + 1 < lx->end && is_digit(q[1])));
}

static void lex_number(struct tex_lexer *lx)
{
    const char *p = lx->p, *q = p;
    struct tex_tok *t = &lx->t;
    char buf[64], *e;

    if (*q == '-' || *q == '+')
        q++;
    while (q < lx->end && (is_digit(*q) || *q == '.'))
        q++;
    if (q < lx->end && (*q == 'e' || *q == 'E')) {
        const char *x = q + 1;
        if (x < lx->end && (*x == '+' || *x == '-'))
            x++;
        if (x < lx->end && is_digit(*x)) {
            q = x;
            while (q < lx->end && is_digit(*q))
                q++;
        }
    }
    size_t n = (size_t)(q - p);
    if (n >= sizeof buf)
        tex_lex_fail(lx, t->line, t->col, "number too long");
    memcpy(buf, p, n);
    buf[n] = '\0';
    errno = 0;
    t->num = strtod(buf, &e);
    if (*e || (q < lx->end && is_name0(*q)))
        tex_lex_fail(lx, t->line, t->col, "malformed number '%.*s'", (int)(n + 1 < 40 ? n + 1 : 40),
                     p);
    if (!isfinite(t->num) || errno == ERANGE)
        tex_lex_fail(lx, t->line, t->col, "number out of range");
    t->kind = TEX_TOK_NUM;
    t->len = n;
    skip(lx, n);
}

static void lex_string(struct tex_lexer *lx)
{
    const char *p = lx->p, *q = p + 1;
    struct tex_tok *t = &lx->t;
    int esc = 0;

    while (q < lx->end && *q != '"' && *q != '\n') {
        if (*q == '\\' && q + 1 < lx->end && q[1] != '\n')
            q++, esc = 1;
        if (*q == '\0')
            tex_lex_fail(lx, t->line, t->col, "NUL byte in a string");
        q++;
    }
    if (q >= lx->end || *q != '"')
        tex_lex_fail(lx, t->line, t->col, "unterminated string");
    t->kind = TEX_TOK_STR;
    t->text = p + 1;
    t->len = (size_t)(q - p - 1);
    if (esc) { /* unescaped into the caller's memory */
        char *d = lx->alloc(lx->ctx, t->len + 1);
        size_t n = 0;
        for (const char *r = p + 1; r < q; r++) {
            if (*r == '\\')
                r++;
            d[n++] = *r;
        }
        t->text = d;
        t->len = n;
    }
    skip(lx, (size_t)(q - p) + 1);
}

void tex_lex_next(struct tex_lexer *lx)
{
    struct tex_tok *t = &lx->t;
    blanks(lx);
    *t = (struct tex_tok){TEX_TOK_EOF, lx->p, 0, 0, lx->line, lx->col};
    if (lx->p >= lx->end)
        return;
    const char *q = lx->p;
    int c = (unsigned char)*q;
    if (number_at(lx, q) || ((c == '-' || c == '+') && number_at(lx, q + 1))) {
        lex_number(lx);
    } else if (is_name0(c)) {
        size_t n = 1;
        for (;;) {
            while (q + n < lx->end && is_name((unsigned char)q[n]))
                n++;
            /* "size-spread": a hyphen before a letter belongs to the name */
            if (q + n + 1 < lx->end && q[n] == '-' && is_name0((unsigned char)q[n + 1]))
                n++;
            else
                break;
        }
        t->kind = TEX_TOK_NAME;
        t->len = n;
        skip(lx, n);
    } else if (c == '"') {
        lex_string(lx);
    } else if (c && strchr("{}(),;=+-*/<>", c)) {
        t->kind = TEX_TOK_PUNCT;
        t->len = strchr("<>=", c) && q + 1 < lx->end && q[1] == '=' ? 2 : 1;
        skip(lx, t->len);
    } else if (c == '!' && q + 1 < lx->end && q[1] == '=') {
        t->kind = TEX_TOK_PUNCT;
        t->len = 2;
        skip(lx, 2);
    } else if (c == 0) {
        tex_lex_fail(lx, t->line, t->col, "NUL byte");
    } else if (c >= 0x20 && c < 0x7f) {
        tex_lex_fail(lx, t->line, t->col, "unexpected character '%c'", c);
    } else {
        tex_lex_fail(lx, t->line, t->col, "unexpected byte 0x%02x", c);
    }
}

int tex_tok_is_word(const struct tex_tok *t, const char *w)
{
    return t->kind == TEX_TOK_NAME && strlen(w) == t->len && !memcmp(t->text, w, t->len);
}

int tex_tok_is_punct(const struct tex_tok *t, int c)
{
    return t->kind == TEX_TOK_PUNCT && t->len == 1 && t->text[0] == c;
}

int tex_tok_is_op(const struct tex_tok *t, const char *op)
{
    return t->kind == TEX_TOK_PUNCT && strlen(op) == t->len && !memcmp(t->text, op, t->len);
}

int tex_tok_is_signed(const struct tex_tok *t)
{
    return t->kind == TEX_TOK_NUM && (t->text[0] == '-' || t->text[0] == '+');
}

const char *tex_tok_desc(const struct tex_tok *t, char *buf, size_t n)
{
    if (t->kind == TEX_TOK_EOF)
        return "the end of the file";
    snprintf(buf, n, "'%.*s'", (int)(t->len > 32 ? 32 : t->len), t->text);
    return buf;
}

void tex_lex_expect(struct tex_lexer *lx, int c)
{
    char b[48];
    if (!tex_tok_is_punct(&lx->t, c))
        tex_lex_fail(lx, lx->t.line, lx->t.col, "expected '%c', found %s", c,
                     tex_tok_desc(&lx->t, b, sizeof b));
    tex_lex_next(lx);
}
