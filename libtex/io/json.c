/* json.c - JSON strings quoted and escaped (RFC 8259, section 7), parameter rows written,
 * documents read */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/param.h"
#include "io/json.h"

int tex_json_string(struct tex_str *b, const char *s)
{
    size_t len = s ? strlen(s) : 0;
    char *e;

    if (tex_str_room(b, 6 * len + 2) < 0) /* \u00XX at most for each byte, and the quotes */
        return -1;
    e = b->s + b->n;
    *e++ = '"';
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == '"' || c == '\\') {
            *e++ = '\\';
            *e++ = (char)c;
        } else if (c == '\n') {
            *e++ = '\\';
            *e++ = 'n';
        } else if (c < 0x20) {
            e += sprintf(e, "\\u%04x", c);
        } else {
            *e++ = (char)c;
        }
    }
    *e++ = '"';
    *e = 0;
    b->n = (size_t)(e - b->s);
    return 0;
}

void tex_json_rows(struct tex_str *b, const struct tex_param *t)
{
    static const char *const types[] = {"int", "real", "flag", "enum", "reals", "colour",
                                        "string", "real", "special"};
    char buf[256];
    tex_str_add(b, "[");
    for (int i = 0; t && t[i].name; i++) {
        tex_str_add(b, "%s{\"name\":", i ? "," : "");
        tex_json_string(b, t[i].name);
        tex_str_add(b, ",\"type\":\"%s\",\"min\":%.17g,\"max\":%.17g,\"default\":",
                    types[t[i].type], t[i].min, t[i].max);
        tex_json_string(b, tex_param_default(&t[i], buf, sizeof buf));
        tex_str_add(b, ",\"help\":");
        tex_json_string(b, t[i].help);
        tex_str_add(b, ",\"choices\":");
        tex_json_string(b, t[i].choices);
        tex_str_add(b, ",\"meta\":");
        tex_json_string(b, t[i].meta);
        tex_str_add(b, ",\"kinds\":%u}", t[i].kinds);
    }
    tex_str_add(b, "]");
}

/* The reader: recursive descent over a cursor, the first error kept. */
struct rd {
    const char *s, *end, *at;
    char *err;
    size_t errn;
    int failed;
};

static int bad(struct rd *r, const char *what)
{
    if (!r->failed)
        snprintf(r->err, r->errn, "%s at byte %ld", what, (long)(r->at - r->s));
    r->failed = 1;
    return -1;
}

static void blanks(struct rd *r)
{
    while (r->at < r->end && (*r->at == ' ' || *r->at == '\t' || *r->at == '\n' || *r->at == '\r'))
        r->at++;
}

static int hex4(struct rd *r, unsigned *u)
{
    *u = 0;
    for (int i = 0; i < 4; i++, r->at++) {
        char c = r->at < r->end ? *r->at : 0;
        int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
              : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0)
            return bad(r, "bad \\u escape");
        *u = *u * 16 + (unsigned)d;
    }
    return 0;
}

static void utf8(struct tex_str *b, unsigned u)
{
    char c[4];
    int n = u < 0x80 ? 1 : u < 0x800 ? 2 : u < 0x10000 ? 3 : 4;
    if (n == 1)
        c[0] = (char)u;
    else {
        for (int i = n - 1; i > 0; i--, u >>= 6)
            c[i] = (char)(0x80 | (u & 0x3f));
        c[0] = (char)((0xf00 >> n) | u); /* 110xxxxx, 1110xxxx, 11110xxx */
    }
    tex_str_bytes(b, c, (size_t)n);
}

/* A string after its opening quote: its bytes, NUL-terminated, malloc'd (NULL on error). */
static char *string(struct rd *r)
{
    struct tex_str b = {0};
    tex_str_room(&b, 16);
    while (!r->failed) {
        if (r->at >= r->end) {
            bad(r, "unterminated string");
            break;
        }
        unsigned char c = (unsigned char)*r->at++;
        if (c == '"') {
            if (b.s)
                b.s[b.n] = 0; /* room made for it, written by appends only */
            return b.s ? b.s : calloc(1, 1);
        }
        if (c < 0x20) {
            r->at--;
            bad(r, "control character in a string");
        } else if (c != '\\') {
            tex_str_bytes(&b, &c, 1);
        } else if (r->at >= r->end) {
            bad(r, "unterminated string");
        } else {
            const char *from = "\"\\/bfnrt", *to = "\"\\/\b\f\n\r\t", *k;
            char e = *r->at++;
            unsigned u, lo;
            if (e && (k = strchr(from, e)))
                tex_str_bytes(&b, to + (k - from), 1);
            else if (e != 'u')
                r->at--, bad(r, "bad escape");
            else if (hex4(r, &u) == 0) {
                if (u >= 0xd800 && u < 0xdc00 && r->end - r->at >= 6 && r->at[0] == '\\' &&
                    r->at[1] == 'u') {
                    r->at += 2;
                    if (hex4(r, &lo) == 0 && lo >= 0xdc00 && lo < 0xe000)
                        u = 0x10000 + ((u - 0xd800) << 10) + (lo - 0xdc00);
                    else
                        bad(r, "bad surrogate pair");
                }
                if (u == 0)
                    bad(r, "\\u0000 in a string");
                else
                    utf8(&b, u);
            }
        }
    }
    free(b.s);
    return NULL;
}

static int value(struct rd *r, struct tex_json *v, int depth);

/* The items of an array or members of an object, up to close. */
static int items(struct rd *r, struct tex_json *v, char close, int depth)
{
    int cap = 0;
    blanks(r);
    if (r->at < r->end && *r->at == close) {
        r->at++;
        return 0;
    }
    for (;;) {
        char *key = NULL;
        blanks(r);
        if (close == '}') {
            if (r->at >= r->end || *r->at != '"')
                return bad(r, "expected a member's name");
            r->at++;
            if (!(key = string(r)))
                return -1;
            blanks(r);
            if (r->at >= r->end || *r->at != ':') {
                free(key);
                return bad(r, "expected ':'");
            }
            r->at++;
        }
        if (v->n == cap) {
            struct tex_json *m = realloc(v->item, (size_t)(cap = cap ? 2 * cap : 8) * sizeof *m);
            if (!m) {
                free(key);
                return bad(r, "out of memory");
            }
            v->item = m;
        }
        v->item[v->n] = (struct tex_json){TEX_JSON_NULL, key, NULL, NULL, 0};
        if (value(r, &v->item[v->n++], depth + 1) < 0)
            return -1;
        blanks(r);
        if (r->at < r->end && *r->at == ',') {
            r->at++;
            continue;
        }
        if (r->at < r->end && *r->at == close) {
            r->at++;
            return 0;
        }
        return bad(r, close == '}' ? "expected ',' or '}'" : "expected ',' or ']'");
    }
}

static int value(struct rd *r, struct tex_json *v, int depth)
{
    static const struct { const char *w; enum tex_json_type t; } words[] = {
        {"null", TEX_JSON_NULL}, {"false", TEX_JSON_FALSE}, {"true", TEX_JSON_TRUE}};
    blanks(r);
    if (depth > 64)
        return bad(r, "nested more than 64 deep");
    if (r->at >= r->end)
        return bad(r, "expected a value");
    char c = *r->at;
    if (c == '{' || c == '[') {
        r->at++;
        v->type = c == '{' ? TEX_JSON_OBJECT : TEX_JSON_ARRAY;
        return items(r, v, c == '{' ? '}' : ']', depth);
    }
    if (c == '"') {
        r->at++;
        v->type = TEX_JSON_STRING;
        return (v->str = string(r)) ? 0 : -1;
    }
    for (size_t i = 0; i < sizeof words / sizeof *words; i++) {
        size_t n = strlen(words[i].w);
        if ((size_t)(r->end - r->at) >= n && !strncmp(r->at, words[i].w, n)) {
            r->at += n;
            v->type = words[i].t;
            return 0;
        }
    }
    /* -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)? */
    const char *p = r->at;
    int ok = 1;
#define DIGITS(need) do { const char *q = p; while (p < r->end && *p >= '0' && *p <= '9') p++; \
                          ok &= !(need) || p > q; } while (0)
    if (p < r->end && *p == '-')
        p++;
    if (p < r->end && *p == '0')
        p++;
    else
        DIGITS(1);
    if (ok && p < r->end && *p == '.') {
        p++;
        DIGITS(1);
    }
    if (ok && p < r->end && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < r->end && (*p == '+' || *p == '-'))
            p++;
        DIGITS(1);
    }
#undef DIGITS
    if (!ok || p == r->at)
        return bad(r, "expected a value");
    v->type = TEX_JSON_NUMBER;
    if (!(v->str = malloc((size_t)(p - r->at) + 1)))
        return bad(r, "out of memory");
    memcpy(v->str, r->at, (size_t)(p - r->at));
    v->str[p - r->at] = 0;
    r->at = p;
    return 0;
}

static void release(struct tex_json *v)
{
    for (int i = 0; i < v->n; i++)
        release(&v->item[i]);
    free(v->item);
    free(v->key);
    free(v->str);
}

struct tex_json *tex_json_parse(const char *text, size_t len, char *err, size_t errn)
{
    struct rd r = {text, text + len, text, err, errn, 0};
    struct tex_json *v = calloc(1, sizeof *v);
    if (!v) {
        snprintf(err, errn, "out of memory");
        return NULL;
    }
    if (value(&r, v, 0) == 0) {
        blanks(&r);
        if (r.at < r.end)
            bad(&r, "text after the value");
    }
    if (r.failed) {
        tex_json_free(v);
        return NULL;
    }
    return v;
}

const struct tex_json *tex_json_get(const struct tex_json *v, const char *key)
{
    for (int i = 0; v && v->type == TEX_JSON_OBJECT && i < v->n; i++)
        if (!strcmp(v->item[i].key, key))
            return &v->item[i];
    return NULL;
}

void tex_json_free(struct tex_json *v)
{
    if (v) {
        release(v);
        free(v);
    }
}
