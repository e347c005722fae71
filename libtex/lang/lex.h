/* lex.h - the one lexer of Textura's languages (scenes and composition scripts)
 *
 * Both t_apply(5) scenes and t_compose(5) scripts are read by this lexer,
 * so they share one rule for each kind of token:
 *
 *   name      a letter or '_', then letters, digits and '_'; a hyphen joins
 *             the name when a letter or '_' follows it ("size-spread",
 *             "major-radius").  To subtract, write spaces: "a - b".
 *   number    digits with an optional fraction and exponent ("2", ".5",
 *             "1e-3"); a '-' or '+' written right before one is its sign
 *             ("-0.5").  A number runs into no letter ("3x" is an error)
 *             and must be finite.  After an operand, a signed number is
 *             read as the operator and the number: "f -1" is "f - 1".
 *   string    "text" on one line; a backslash takes the next character as
 *             it is ("\"", "\\").
 *   punct     one of  { } ( ) , ; = + - * / < >  or a comparison of two
 *             characters: <= >= == !=
 *   comments  '#' to the end of the line; blanks, tabs and newlines
 *             separate tokens (in a scene, so does ';': semicolon_blank).
 *
 * Every token carries its line and column (from 1).  An error is one line,
 * "file:line:col: message", recorded with tex_usage_error() (base/error.h),
 * and ends the parse by a longjmp to the caller's jmp_buf:
 *
 *   jmp_buf fail;
 *   struct tex_lexer lx;
 *   if (setjmp(fail))
 *       return -1;                         // tex_errmsg() says what and where
 *   tex_lex_init(&lx, text, len, "scene.t", &fail, my_alloc, my_pool);
 *   tex_lex_next(&lx);                     // lx.t is the first token
 *
 * Strings with backslashes are copied, unescaped, into memory from alloc
 * (which must not return NULL: it may longjmp itself); other tokens point
 * into the text, which must outlive them.  A string's text is not
 * NUL-terminated unless it was copied: use len.
 */
#ifndef TEX_LEX_H
#define TEX_LEX_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include "../base/error.h"

#ifdef __cplusplus
extern "C" {
#endif

enum tex_tok_kind { TEX_TOK_EOF, TEX_TOK_NUM, TEX_TOK_NAME, TEX_TOK_STR, TEX_TOK_PUNCT };

struct tex_tok {
    enum tex_tok_kind kind;
    const char *text; /* the token as written (a string: its contents) */
    size_t len;
    double num;       /* TEX_TOK_NUM: the value, sign included */
    int line, col;
};

struct tex_lexer {
    const char *p, *end, *name; /* the rest of the text; the file's name */
    int line, col;              /* of p */
    struct tex_tok t;           /* the current token */
    jmp_buf *fail;
    void *(*alloc)(void *ctx, size_t n); /* zeroed memory that lives as long as the tokens */
    void *ctx;
    int semicolon_blank; /* 1: ';' separates tokens like a blank (scenes) */
};

/* Start reading text[0..len) named name; errors jump to *fail. */
void tex_lex_init(struct tex_lexer *lx, const char *text, size_t len, const char *name,
                  jmp_buf *fail, void *(*alloc)(void *ctx, size_t n), void *ctx);
/* Read the next token into lx->t. */
void tex_lex_next(struct tex_lexer *lx);

/* Is t the name w / the punctuation c / a number written with a sign? */
int tex_tok_is_word(const struct tex_tok *t, const char *w);
int tex_tok_is_punct(const struct tex_tok *t, int c);
/* Is t the punctuation op, of one or two characters ("<=")? */
int tex_tok_is_op(const struct tex_tok *t, const char *op);
int tex_tok_is_signed(const struct tex_tok *t);

/* The token for a message: "'text'" (at most 32 characters) or "the end of
 * the file". */
const char *tex_tok_desc(const struct tex_tok *t, char *buf, size_t n);
/* Take the punctuation c, or fail with "expected 'c', found ...". */
void tex_lex_expect(struct tex_lexer *lx, int c);

/* Record "file:line:col: message" as an error of the given kind and jump out. */
void tex_lex_fail(struct tex_lexer *lx, int line, int col, const char *fmt, ...)
    __attribute__((noreturn, format(printf, 4, 5)));
void tex_lex_vfail(struct tex_lexer *lx, enum tex_err_kind kind, int line, int col,
                   const char *fmt, va_list ap) __attribute__((noreturn));
/* The same message without the jump (for errors found after parsing); returns -1. */
int tex_lang_error(const char *name, int line, int col, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#ifdef __cplusplus
}
#endif
#endif
