/* message.h - what a tool says on standard error, and how it ends
 *
 * Errors read "t_noise: error: ...", warnings "t_noise: warning: ..."; a tool dies
 * with status 2 for a usage error and 1 for any other (the error's kind, error.h).
 * A progress bar "t_noise: [####    ]  50%" may hold the last line of standard
 * error: a message ends it first, so that each starts on a line of its own.
 *
 *   tex_progname = "t_noise";            // tex_cli_parse sets it from the tool
 *   if (!m) tex_die();                   // libtex's message, its kind's status
 *   tex_usage_die("--n must be odd (got %d)", n);
 *
 * At exit, standard output is flushed and closed: a full disk or a closed pipe is
 * "standard output: ..." and status 1 (tex_cli_parse registers that).
 */
#ifndef TEX_CLI_MESSAGE_H
#define TEX_CLI_MESSAGE_H

#include "../base/api.h"

TEX_API_BEGIN

struct tex_common;

extern const char *tex_progname;

/* Print "prog: error: <tex_errmsg()>" and exit with its kind's status. */
void tex_die(void) __attribute__((noreturn));
/* Print "prog: error: <tex_errmsg()>" and go on, for a tool that reports each of
 * several operands as identify does; returns the status it would have exited with. */
int tex_report(void);
/* Print "prog: error: ..." and exit 2 (usage). */
void tex_usage_die(const char *fmt, ...) __attribute__((noreturn, format(printf, 1, 2)));

/* A progress bar on standard error, "t_NAME: [####    ]  50%", ending the
 * line at done == total, drawn once the work has run 0.3 s: for libtex's
 * progress callbacks (pass it only when standard error is a terminal and -q
 * is off: tex_cli_progress_wanted).  tex_cli_parse makes it the process's
 * progress handler (progress.h) under the same conditions, and
 * tex_cli_write completes it. */
void tex_cli_progress(long done, long total, void *arg);
int tex_cli_progress_wanted(const struct tex_common *c);

TEX_API_END
#endif
