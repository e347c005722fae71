/* strbuf.c - a growable string */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/strbuf.h"

int tex_str_room(struct tex_str *b, size_t n)
{
    if (b->n + n + 1 <= b->cap)
        return 0;
    size_t cap = (b->n + n + 1) * 2;
    char *s = realloc(b->s, cap);
    if (!s)
        return -1;
    b->s = s;
    b->cap = cap;
    return 0;
}

int tex_str_add(struct tex_str *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (k < 0 || tex_str_room(b, (size_t)k) < 0)
        return -1;
    va_start(ap, fmt);
    vsnprintf(b->s + b->n, (size_t)k + 1, fmt, ap);
    va_end(ap);
    b->n += (size_t)k;
    return 0;
}

int tex_str_bytes(struct tex_str *b, const void *data, size_t n)
{
    if (tex_str_room(b, n) < 0)
        return -1;
    memcpy(b->s + b->n, data, n);
    b->n += n;
    b->s[b->n] = 0;
    return 0;
}
