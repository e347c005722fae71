/* error.h - how libtex reports failure
 *
 * libtex never prints and never exits.  A function that fails returns -1
 * (or NULL) after recording a one-line message with tex_error() or
 * tex_usage_error(); the caller reads it with tex_errmsg() and decides how
 * to report it.  The message is per thread.
 *
 * The kind tells a tool which exit status to use: TEX_ERR_USAGE (2) for a
 * bad parameter or option value, TEX_ERR_RUNTIME (1) for everything else
 * (a missing file, a corrupt stream, memory).
 */
#ifndef TEX_ERROR_H
#define TEX_ERROR_H

#include "api.h"

TEX_API_BEGIN

enum tex_err_kind { TEX_ERR_RUNTIME = 1, TEX_ERR_USAGE = 2 };

/* Record a runtime error; returns -1 so that `return tex_error(...)` reads well. */
int tex_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Record a usage error (bad parameter, option or value); returns -1. */
int tex_usage_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Prefix the current message with "what: " (e.g. the input's name). */
void tex_error_context(const char *what);

const char *tex_errmsg(void);
enum tex_err_kind tex_errkind(void);

/* Warnings: one line about something done that is not a failure (e.g. a
 * file's channels past the fourth dropped).  libtex hands them to the
 * handler the application set (the command-line layer prints them unless
 * -q); with no handler they are dropped. */
typedef void (*tex_warning_fn)(const char *msg);
void tex_set_warning_handler(tex_warning_fn fn);
void tex_warning(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

TEX_API_END
#endif
