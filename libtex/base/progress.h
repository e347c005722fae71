/* progress.h - how long work tells how far it has gone
 *
 * Like warnings (error.h), progress goes to one handler for the process,
 * set by the tool (cli.h sets a bar on standard error when that is a
 * terminal and -q is off); with no handler, reporting costs one test.
 * Work reports in stages, each a part of the whole bar that begins where
 * the last one ended:
 *
 *   tex_progress_stage(0.7, cells);          // 70% of the bar, in cells
 *   for (k = 0; k < cells; k++) { ...; tex_progress_add(1); }
 *   tex_progress_stage(1, h);                // the rest, in rows
 *
 * tex_progress_add may be called from any thread; the handler is called
 * from one thread at a time: with (0, 100) when the first stage starts,
 * each time the whole percentage grows, with (percent, 100), and once more
 * with (100, 100) by tex_progress_done.
 */
#ifndef TEX_PROGRESS_H
#define TEX_PROGRESS_H

#include "api.h"

TEX_API_BEGIN

typedef void (*tex_progress_fn)(long done, long total, void *arg);

void tex_set_progress_handler(tex_progress_fn fn, void *arg);
/* A new stage: span of what remains of the bar (1: all of it), in total units. */
void tex_progress_stage(double span, long total);
/* n more units of the stage done. */
void tex_progress_add(long n);
/* Between hold(1) and hold(0), stages and units are not reported: the caller
 * counts what runs inside as one unit of its own stage (a script's cell). */
void tex_progress_hold(int on);
/* The work is over: the bar reaches 100% (if it was started at all). */
void tex_progress_done(void);

TEX_API_END
#endif
