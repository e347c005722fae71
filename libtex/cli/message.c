/* message.c - errors, warnings, the progress bar and the checked close of standard output */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/internal.h"
#include "base/error.h"
#include "base/progress.h"

const char *tex_progname = "textura";

static int bar_drawn; /* a progress bar is on the last line of standard error */

/* Messages start on a line of their own. */
static void end_bar(void)
{
    if (bar_drawn)
        fputc('\n', stderr);
    bar_drawn = 0;
}

static void vmsg(const char *kind, const char *fmt, va_list ap)
{
    end_bar();
    fprintf(stderr, "%s: %s", tex_progname, kind);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

void tex_cli_warning(const char *msg)
{
    end_bar();
    fprintf(stderr, "%s: warning: %s\n", tex_progname, msg);
}

void tex_die(void)
{
    tex_set_progress_handler(NULL, NULL); /* the bar ends where the work failed */
    end_bar();
    fprintf(stderr, "%s: error: %s\n", tex_progname, tex_errmsg());
    exit(tex_errkind() == TEX_ERR_USAGE ? 2 : 1);
}

void tex_usage_die(const char *fmt, ...)
{
    va_list ap;
    tex_set_progress_handler(NULL, NULL);
    va_start(ap, fmt);
    vmsg("error: ", fmt, ap);
    va_end(ap);
    exit(2);
}

/* At exit: text written to standard output (help, reports, palettes) must
 * have reached it; a full disk or a closed pipe is an error (exit 1). */
void tex_cli_close_stdout(void)
{
    tex_progress_done();
    end_bar();
    int bad = fflush(stdout) != 0 || ferror(stdout);
    int e = errno;

    if (fclose(stdout) != 0 && !bad) {
        e = errno;
        bad = e != EBADF; /* standard output closed and never written to */
    }
    if (bad) {
        fprintf(stderr, "%s: error: standard output: %s\n", tex_progname,
                e ? strerror(e) : "write error");
        fflush(stderr);
        _exit(1);
    }
}

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

void tex_cli_progress(long done, long total, void *arg)
{
    static const char bar[] = "########################################";
    static double start = -1;
    int w = (int)sizeof bar - 1, k = total > 0 ? (int)(w * done / total) : w;
    (void)arg;
    if (start < 0)
        start = seconds();
    if (!bar_drawn && seconds() - start < 0.3)
        return; /* work that ends within a moment draws no bar */
    bar_drawn = done < total;
    fprintf(stderr, "\r%s: [%.*s%*s] %3d%%", tex_progname, k, bar, w - k, "",
            total > 0 ? (int)(100 * done / total) : 100);
    if (done >= total)
        fputc('\n', stderr);
}

int tex_cli_progress_wanted(const struct tex_common *c)
{
    return !c->quiet && isatty(2);
}
