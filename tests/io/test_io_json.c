/* test_io_json.c - the growable string, JSON strings (RFC 8259, section 7), parameter rows
 * as JSON, and documents read back */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/param.h"
#include "io/json.h"
#include "io/strbuf.h"
#include "unit.h"

/* Undo the escapes a JSON reader undoes (the ones RFC 8259 allows, \u00XX only):
 * the bytes between the quotes, or -1 for text that is not one JSON string. */
static int unescape(const char *s, size_t n, char *out)
{
    size_t k = 0;
    if (n < 2 || s[0] != '"' || s[n - 1] != '"')
        return -1;
    for (size_t i = 1; i < n - 1; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c < 0x20 || c == '"')
            return -1; /* must have been escaped */
        if (c != '\\') {
            out[k++] = (char)c;
            continue;
        }
        c = (unsigned char)s[++i];
        if (c == 'u') {
            unsigned v;
            if (i + 4 >= n - 1 || sscanf(s + i + 1, "%4x", &v) != 1 || v > 0xff)
                return -1;
            out[k++] = (char)v;
            i += 4;
        } else {
            const char *from = "\"\\/bfnrt", *to = "\"\\/\b\f\n\r\t", *p = strchr(from, c);
            if (!c || !p)
                return -1;
            out[k++] = to[p - from];
        }
    }
    return (int)k;
}

static void test_strings(void)
{
    char all[256], back[256];
    struct tex_str b = {0};
    int n, ok;

    for (int i = 1; i < 256; i++)
        all[i - 1] = (char)i;
    all[255] = 0;
    CHECK(tex_json_string(&b, all) == 0, "every byte from 1 to 255 escaped");
    n = unescape(b.s, b.n, back);
    CHECK(n == 255 && !memcmp(back, all, 255), "and read back as the same bytes");
    CHECK(strstr(b.s, "\\n") && strstr(b.s, "\\u0001") && strstr(b.s, "\\\"") &&
              strstr(b.s, "\\\\"),
          "newline as \\n, other controls as \\u00XX, quote and backslash escaped");
    ok = 1;
    for (size_t i = 0; i < b.n; i++)
        ok &= (unsigned char)b.s[i] >= 0x20;
    CHECK(ok && b.s[b.n] == 0, "no control byte left, and a NUL after the text");
    b.n = 0;
    tex_json_string(&b, "caf\xc3\xa9 \xe2\x80\x94 t_noise -s 64\nt_palette marble\n");
    CHECK(!strcmp(b.s, "\"caf\xc3\xa9 \xe2\x80\x94 t_noise -s 64\\nt_palette marble\\n\""),
          "UTF-8 copied as it is, a history's lines joined by \\n");
    b.n = 0;
    tex_json_string(&b, NULL);
    tex_str_add(&b, ",");
    tex_json_string(&b, "");
    CHECK(b.n == 5 && !strcmp(b.s, "\"\",\"\""), "NULL and the empty string are \"\"");
    free(b.s);
}

static void test_builder(void)
{
    struct tex_str b = {0};
    static const char png[] = "\x89PNG\r\n\x1a\n\0\0\0\rIHDR";
    int ok = 1;

    for (int i = 0; i < 1000; i++)
        ok &= tex_str_add(&b, "%d,", i) == 0;
    CHECK(ok && b.n == 3890 && !strncmp(b.s, "0,1,2,", 6) && !strcmp(b.s + b.n - 4, "999,"),
          "a thousand appends, in order");
    b.n = 0;
    tex_str_bytes(&b, png, sizeof png - 1);
    tex_str_add(&b, "%s", "!");
    CHECK(b.n == sizeof png && !memcmp(b.s, png, sizeof png - 1) && b.s[b.n - 1] == '!' &&
              b.s[b.n] == 0,
          "bytes with NULs appended whole, text after them");
    free(b.s);
}

/* Every byte string written by tex_json_string reads back the same; the values of a
 * document as written; bad text refused naming where. */
static void test_reader(void)
{
    char all[256], err[128];
    struct tex_str b = {0};
    struct tex_json *v;
    for (int i = 1; i < 256; i++)
        all[i - 1] = (char)i;
    all[255] = 0;
    tex_json_string(&b, all);
    v = tex_json_parse(b.s, b.n, err, sizeof err);
    CHECK(v && v->type == TEX_JSON_STRING && !strcmp(v->str, all),
          "every byte from 1 to 255 written as a string reads back the same");
    tex_json_free(v);
    free(b.s);

    static const char doc[] = " {\"a\": [1, -2.5e3, 0, true, false, null, \"x\\u00e9\\ud83d\\ude00\"],"
                              " \"b\": {}, \"c\": [], \"a\": 7 } ";
    v = tex_json_parse(doc, sizeof doc - 1, err, sizeof err);
    const struct tex_json *a = tex_json_get(v, "a");
    CHECK(v && v->type == TEX_JSON_OBJECT && v->n == 4 && a && a->type == TEX_JSON_ARRAY &&
              a->n == 7, "an object of four members, the first an array of seven");
    CHECK(a && a->n == 7 && !strcmp(a->item[0].str, "1") && !strcmp(a->item[1].str, "-2.5e3") &&
              a->item[3].type == TEX_JSON_TRUE && a->item[4].type == TEX_JSON_FALSE &&
              a->item[5].type == TEX_JSON_NULL,
          "numbers keep their text as written; true, false and null");
    CHECK(a && a->n == 7 && !strcmp(a->item[6].str, "x\xc3\xa9\xf0\x9f\x98\x80"),
          "\\u escapes, a surrogate pair too, become UTF-8");
    CHECK(tex_json_get(v, "b")->type == TEX_JSON_OBJECT && tex_json_get(v, "b")->n == 0 &&
              tex_json_get(v, "c")->n == 0 && !tex_json_get(v, "d") && !tex_json_get(a, "a"),
          "empty object and array; an absent key, or a key of an array, is NULL");
    CHECK(tex_json_get(v, "a") == &v->item[0], "a key twice: the first is found");
    tex_json_free(v);

    static const struct { const char *text, *err; } bad[] = {
        {"", "expected a value at byte 0"},
        {"[1,]", "expected a value at byte 3"},
        {"{\"a\" 1}", "expected ':' at byte 5"},
        {"[01]", "expected ',' or ']' at byte 2"},
        {"\"a\nb\"", "control character in a string at byte 2"},
        {"\"\\u0000\"", "\\u0000 in a string at byte 7"},
        {"[1] x", "text after the value at byte 4"},
        {"{\"a\": tru}", "expected a value at byte 6"},
        {"\"abc", "unterminated string at byte 4"},
    };
    int ok = 1;
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        err[0] = 0;
        v = tex_json_parse(bad[i].text, strlen(bad[i].text), err, sizeof err);
        if (v || strcmp(err, bad[i].err)) {
            printf("# %s: %s\n", bad[i].text, err);
            ok = 0;
        }
        tex_json_free(v);
    }
    CHECK(ok, "text that is not JSON is refused, naming what was expected and where");
    char deep[200];
    memset(deep, '[', 100);
    memset(deep + 100, ']', 100);
    v = tex_json_parse(deep, 200, err, sizeof err);
    CHECK(!v && strstr(err, "nested more than 64 deep"), "nesting is bounded (64)");
}

struct rowed {
    double f;
    int mode;
};

static void test_rows(void)
{
    static const struct tex_param rows[] = {
        TEX_REAL(struct rowed, f, 'f', 8, 0, 1e6, "F", "frequency \"cells\""),
        TEX_ENUM(struct rowed, mode, 0, "fbm", "fbm|ridged", "the mode", .kinds = 2),
        {0}};
    struct tex_str b = {0};
    char err[128];
    tex_json_rows(&b, rows);
    struct tex_json *v = tex_json_parse(b.s, b.n, err, sizeof err);
    const struct tex_json *f = v && v->n == 2 ? &v->item[0] : NULL, *m = f ? &v->item[1] : NULL;
    CHECK(f && !strcmp(tex_json_get(f, "name")->str, "f") &&
              !strcmp(tex_json_get(f, "type")->str, "real") &&
              !strcmp(tex_json_get(f, "max")->str, "1000000") &&
              !strcmp(tex_json_get(f, "default")->str, "8") &&
              !strcmp(tex_json_get(f, "help")->str, "frequency \"cells\"") &&
              !strcmp(tex_json_get(f, "meta")->str, "F"),
          "a row as JSON: name, type, range, default, help, argument name");
    CHECK(m && !strcmp(tex_json_get(m, "choices")->str, "fbm|ridged") &&
              !strcmp(tex_json_get(m, "default")->str, "fbm") &&
              !strcmp(tex_json_get(m, "kinds")->str, "2"),
          "an enum row's choices, default and modes");
    tex_json_free(v);
    free(b.s);
}

int main(void)
{
    test_strings();
    test_builder();
    test_reader();
    test_rows();
    return unit_done();
}
