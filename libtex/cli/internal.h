/* internal.h - what the front end's files share and the tools do not use
 *
 * tex_cli_parse (options.c) prints --help and --help-mdoc through help.c, makes
 * message.c's warning the process's warning handler and its checked close of standard
 * output an exit handler, and sets OpenMP's threads through threads.c.
 */
#ifndef TEX_CLI_INTERNAL_H
#define TEX_CLI_INTERNAL_H

#include <stdio.h>

#include "../base/param.h"

struct tex_tool;

/* One option the tool takes: its row, and the struct the row's offset is into. */
struct tex_cli_opt {
    const struct tex_param *row;
    void *obj;
};

/* --help: the usage line, the summary and one line per option, then -h and -V. */
void tex_cli_help(FILE *fp, const struct tex_tool *t, const struct tex_cli_opt *o, int n);
/* --help-synopsis: the SYNOPSIS as mdoc, every option and the operands (tests/mkman). */
void tex_cli_synopsis(FILE *fp, const struct tex_tool *t, const struct tex_cli_opt *o, int n);
/* --help-mdoc: the option list as mdoc, for the man page (tests/mkman): t's own options
 * in full, then one item naming the shared ones, which textura(5) describes once
 * (--help-common-mdoc: every row in full, t NULL). */
void tex_cli_mdoc(FILE *fp, const struct tex_tool *t, const struct tex_cli_opt *o, int n);

/* --help-json: the tool's name, operands, summary and own rows (tex_json_rows), for
 * editors such as t_proto to offer its options. */
void tex_cli_json(FILE *fp, const struct tex_tool *t);

/* "prog: warning: msg" on a line of its own: the warning handler (error.h). */
void tex_cli_warning(const char *msg);
/* At exit: standard output flushed and closed, or "standard output: ..." and _exit(1). */
void tex_cli_close_stdout(void);

/* At the start of main: OpenMP's idle threads made to sleep (may run the tool again). */
void tex_cli_passive_threads(char **argv);
/* -j N: N threads (0: OpenMP's default). */
void tex_cli_threads(int n);

#endif
