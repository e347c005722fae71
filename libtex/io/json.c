/* json.c - JSON strings quoted and escaped (RFC 8259, section 7) */
#include <stdio.h>
#include <string.h>

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
