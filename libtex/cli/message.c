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

int tex_report(void)
{
    end_bar();
    fprintf(stderr, "%s: error: %s\n", tex_progname, tex_errmsg());
    return tex_errkind() == TEX_ERR_USAGE ? 2 : 1;
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

/* A time as people read it: "8.4 s", "2:05", "1:02:05". */
static const char *clock_text(double s, char *b, size_t n)
{
    long t = (long)(s + 0.5);
    if (s < 60)
        snprintf(b, n, "%.1f s", s);
    else if (t < 3600)
        snprintf(b, n, "%ld:%02ld", t / 60, t % 60);
    else
        snprintf(b, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    return b;
}

/* The bar: drawn from 0% when the work starts, at most ten times a second, with the time
 * spent and an estimate of the time left from the rate so far; at the end it becomes one
 * line with the whole time, or is erased when the work took less than a moment (a quick
 * stage of a pipeline leaves nothing on the screen). */
void tex_cli_progress(long done, long total, void *arg)
{
    static const char full[] = "##############################";
    static double start = -1, last;
    double now = seconds(), t, f = total > 0 ? (double)done / (double)total : 1;
    int w = (int)sizeof full - 1, k = (int)(w * f);
    char a[24], b[24];
    (void)arg;
    if (start < 0)
        start = now, last = now - 1;
    t = now - start;
    if (f < 1) {
        if (now - last < 0.1)
            return;
        last = now;
        bar_drawn = 1;
        fprintf(stderr, "\r%s: [%.*s%*s] %3d%%  %s, %s left\033[K", tex_progname, k, full, w - k,
                "", (int)(100 * f), clock_text(t, a, sizeof a),
                f > 0 ? clock_text(t * (1 - f) / f, b, sizeof b) : "?");
    } else if (bar_drawn) {
        bar_drawn = 0;
        if (t < 0.3)
            fputs("\r\033[K", stderr);
        else
            fprintf(stderr, "\r%s: [%s] 100%%  done in %s\033[K\n", tex_progname, full,
                    clock_text(t, a, sizeof a));
    }
}

int tex_cli_progress_wanted(const struct tex_common *c)
{
    return !c->quiet && isatty(2);
}
