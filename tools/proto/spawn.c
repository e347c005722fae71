/* spawn.c - a pipeline run: its stages spawned without a shell, their output and first
 * error line gathered, all within RUN_SECONDS */
#define _GNU_SOURCE /* pipe2, posix_spawn_file_actions_addchdir_np */
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "proto.h"

/* The running pipelines' process groups: a signal to t_proto kills them all. */
static pthread_mutex_t groups_lock = PTHREAD_MUTEX_INITIALIZER;
static pid_t groups[256];

static void group_set(pid_t old, pid_t new)
{
    pthread_mutex_lock(&groups_lock);
    for (size_t i = 0; i < sizeof groups / sizeof *groups; i++)
        if (groups[i] == old) {
            groups[i] = new;
            break;
        }
    pthread_mutex_unlock(&groups_lock);
}

void kill_all(void)
{
    pthread_mutex_lock(&groups_lock);
    for (size_t i = 0; i < sizeof groups / sizeof *groups; i++)
        if (groups[i] > 0)
            kill(-groups[i], SIGKILL);
    pthread_mutex_unlock(&groups_lock);
}

/* The pipeline's stages started, each reading the one before (the first /dev/null), the
 * last writing to out, all to errfd; pid[i] 0 where one could not start */
static void spawn_stages(struct pipeline *pl, pid_t *pid, int out, int errfd)
{
    int in = -1;
    char path[PATH_MAX + 64];
    posix_spawnattr_t at;
    sigset_t none, dfl;

    /* the stages in a process group of their own, with t_proto's blocked signals and
     * ignored SIGPIPE undone */
    sigemptyset(&none);
    sigemptyset(&dfl);
    sigaddset(&dfl, SIGPIPE);
    posix_spawnattr_init(&at);
    posix_spawnattr_setsigmask(&at, &none);
    posix_spawnattr_setsigdefault(&at, &dfl);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF |
                                      POSIX_SPAWN_SETPGROUP);

    for (int i = 0; i < pl->n; i++) {
        int p[2] = {-1, out};
        posix_spawn_file_actions_t fa;
        if (i < pl->n - 1 && pipe2(p, O_CLOEXEC) < 0)
            break;
        posix_spawn_file_actions_init(&fa);
        if (in >= 0)
            posix_spawn_file_actions_adddup2(&fa, in, 0);
        else
            posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_adddup2(&fa, i < pl->n - 1 ? p[1] : out, 1);
        posix_spawn_file_actions_adddup2(&fa, errfd, 2);
        posix_spawn_file_actions_addchdir_np(&fa, proto.tmpdir);
        snprintf(path, sizeof path, "%s/%s", proto.bindir, pl->st[i].argv[0]);
        pl->st[i].argv[pl->st[i].n] = NULL;
        posix_spawnattr_setpgroup(&at, i ? pid[0] : 0);
        if ((i && pid[0] <= 0) ||
            posix_spawn(&pid[i], path, &fa, &at, (char **)pl->st[i].argv, environ) != 0)
            pid[i] = 0;
        if (i == 0 && pid[0] > 0)
            group_set(0, pid[0]);
        posix_spawn_file_actions_destroy(&fa);
        if (in >= 0)
            close(in);
        in = -1;
        if (i < pl->n - 1) {
            close(p[1]);
            in = p[0];
        }
    }
    if (in >= 0)
        close(in);
    posix_spawnattr_destroy(&at);
}

/* At most MAX_RUNS pipelines at once (a thread per connection would otherwise start one
 * per request): a slot, waited for until the request's end; 0, or -1 with pl->err. */
static pthread_mutex_t slots_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t slots_free = PTHREAD_COND_INITIALIZER;
static int running;

static int slot(struct pipeline *pl, time_t end, int take)
{
    struct timespec until = {end, 0};
    int rc = 0;
    pthread_mutex_lock(&slots_lock);
    if (!take) {
        running--;
        pthread_cond_signal(&slots_free);
    } else {
        while (running >= MAX_RUNS && rc == 0)
            rc = pthread_cond_timedwait(&slots_free, &slots_lock, &until);
        if (running < MAX_RUNS)
            running++, rc = 0;
    }
    pthread_mutex_unlock(&slots_lock);
    return rc ? fail(pl, "busy: %d pipelines ran for the whole %d s", MAX_RUNS, RUN_SECONDS) : 0;
}

static int run_slot(struct pipeline *pl, struct tex_str *out, time_t end);

/* Run the pipeline; the last stage's standard output into out.  Returns the
 * worst exit status (0 ok, 1 runtime, 2 usage) with stderr's first error line in err. */
int run(struct pipeline *pl, struct tex_str *out)
{
    time_t end = pl->end ? (time_t)pl->end : time(NULL) + RUN_SECONDS;
    if (slot(pl, end, 1) < 0)
        return 1;
    int status = run_slot(pl, out, end);
    slot(pl, end, 0);
    return status;
}

static int run_slot(struct pipeline *pl, struct tex_str *out, time_t end)
{
    pid_t pid[MAX_STAGES] = {0};
    int errp[2], outp[2], status = 0;
    struct tex_str err = {0};

    if (pipe2(errp, O_CLOEXEC) < 0 || pipe2(outp, O_CLOEXEC) < 0)
        return fail(pl, "cannot make a pipe"), 1;
    spawn_stages(pl, pid, outp[1], errp[1]);
    close(outp[1]);
    close(errp[1]);
    struct pollfd fds[2] = {{outp[0], POLLIN, 0}, {errp[0], POLLIN, 0}};
    while (fds[0].fd >= 0 || fds[1].fd >= 0) {
        int left = (int)(end - time(NULL));
        if (left <= 0 || poll(fds, 2, left * 1000) <= 0) {
            if (pid[0] > 0)
                kill(-pid[0], SIGKILL);
            snprintf(pl->err, sizeof pl->err, "the pipeline took longer than %d s", RUN_SECONDS);
            status = 1;
            break;
        }
        for (int k = 0; k < 2; k++) {
            char buf[65536];
            ssize_t got;
            if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            if ((got = read(fds[k].fd, buf, sizeof buf)) <= 0) {
                close(fds[k].fd);
                fds[k].fd = -1;
                continue;
            }
            struct tex_str *b = k ? &err : out;
            if (b->n + got > (size_t)64 << 20) /* more than any map of MAX_SIDE */
                continue;
            tex_str_bytes(b, buf, (size_t)got);
        }
    }
    for (int k = 0; k < 2; k++)
        if (fds[k].fd >= 0)
            close(fds[k].fd);
    for (int i = 0; i < pl->n; i++) {
        int ws;
        if (pid[i] <= 0) {
            status = 1;
            snprintf(pl->err, sizeof pl->err, "cannot run %s", pl->st[i].argv[0]);
            continue;
        }
        waitpid(pid[i], &ws, 0);
        int code = WIFEXITED(ws) ? WEXITSTATUS(ws) : 1;
        if (code > status)
            status = code;
    }
    if (pid[0] > 0)
        group_set(pid[0], 0);
    if (status && err.s) { /* the first error line: a progress bar may come before it */
        char *line = strstr(err.s, ": error: "), *nl;
        while (line && line > err.s && line[-1] != '\n' && line[-1] != '\r')
            line--;
        line = line ? line : err.s;
        if ((nl = strpbrk(line, "\r\n")))
            *nl = 0;
        snprintf(pl->err, sizeof pl->err, "%s", line);
    }
    free(err.s);
    return status;
}
