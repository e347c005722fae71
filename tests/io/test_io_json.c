/* test_io_json.c - the growable string and JSON strings (RFC 8259, section 7) */
#include <stdlib.h>
#include <string.h>

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

int main(void)
{
    test_strings();
    test_builder();
    return unit_done();
}
