/* progress.c - one progress handler for the process, fed in stages */
#include "base/progress.h"

static struct {
    tex_progress_fn fn;
    void *arg;
    double at, span;  /* the stage: from at, span of the whole */
    long total, done; /* its units */
    int shown;        /* the percentage last reported */
    int held;         /* inside a part that its caller counts as one unit */
} pr;

void tex_set_progress_handler(tex_progress_fn fn, void *arg)
{
    pr.fn = fn;
    pr.arg = arg;
    pr.at = pr.span = 0;
    pr.total = pr.done = 0;
    pr.shown = -1;
    pr.held = 0;
}

void tex_progress_hold(int on)
{
    pr.held += on ? 1 : -1;
}

void tex_progress_stage(double span, long total)
{
    if (!pr.fn || pr.held)
        return;
    if (pr.shown < 0) { /* the first stage: the bar starts at 0% */
        pr.shown = 0;
        pr.fn(0, 100, pr.arg);
    }
    pr.at += pr.span;
    pr.span = span * (1 - pr.at);
    pr.total = total > 0 ? total : 1;
    pr.done = 0;
}

void tex_progress_add(long n)
{
    long done;
    int percent, shown;

    if (!pr.fn || pr.held)
        return;
#pragma omp atomic capture
    done = pr.done += n;
    percent = (int)(100 * (pr.at + pr.span * (double)done / (double)pr.total));
#pragma omp atomic read
    shown = pr.shown;
    if (percent <= shown || percent >= 100)
        return; /* 100% is for tex_progress_done */
#pragma omp critical(tex_progress)
    if (percent > pr.shown) {
#pragma omp atomic write
        pr.shown = percent;
        pr.fn(percent, 100, pr.arg);
    }
}

void tex_progress_done(void)
{
    if (pr.fn && pr.shown >= 0 && pr.shown < 100) {
        pr.shown = 100;
        pr.fn(100, 100, pr.arg);
    }
}
