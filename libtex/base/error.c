/* error.c - the per-thread error message of libtex */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"

static _Thread_local char msg[512];
static _Thread_local enum tex_err_kind kind = TEX_ERR_RUNTIME;

static int record(enum tex_err_kind k, const char *fmt, va_list ap)
{
    vsnprintf(msg, sizeof msg, fmt, ap);
    kind = k;
    return -1;
}

int tex_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    record(TEX_ERR_RUNTIME, fmt, ap);
    va_end(ap);
    return -1;
}

int tex_usage_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    record(TEX_ERR_USAGE, fmt, ap);
    va_end(ap);
    return -1;
}

void tex_error_context(const char *what)
{
    char old[sizeof msg];
    size_t n = strlen(what);
    int room;

    /* Don't repeat a context the message already starts with. */
    if (strncmp(msg, what, n) == 0 && msg[n] == ':')
        return;
    memcpy(old, msg, sizeof old);
    /* Keep the message within the buffer: the context is cut before the detail. */
    room = (int)(sizeof msg / 2);
    snprintf(msg, sizeof msg, "%.*s: %.*s", room, what, (int)(sizeof msg - room - 3), old);
}

const char *tex_errmsg(void)
{
    return msg[0] ? msg : "unknown error";
}

enum tex_err_kind tex_errkind(void)
{
    return kind;
}

static tex_warning_fn warning_handler;

void tex_set_warning_handler(tex_warning_fn fn)
{
    warning_handler = fn;
}

void tex_warning(const char *fmt, ...)
{
    char line[512];
    va_list ap;

    if (!warning_handler)
        return;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    warning_handler(line);
}
