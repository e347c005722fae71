/* stream_io.c - throughput of the stream through a pipe.
 *
 * The parent makes a 2048x2048 RGBA map (not timed), then the clock runs
 * while it writes the map as the EXR stream into a pipe and a child reads
 * it back into a map, exactly as two tools of a pipeline do.  The baseline
 * moves the same bytes with plain write() and read() into a buffer, which is
 * what `cat | cat` does.  Prints the median of several runs of each, in GB/s.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "textura.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One timed transfer; raw = 1 moves bytes only.  The reader is forked
 * before the clock starts, so process creation is not timed. */
static double transfer(const tex_map *m, const tex_buf *bytes, int raw)
{
    int fd[2];
    pid_t pid;
    double t0, t1;
    int status;

    if (pipe(fd) < 0)
        exit(1);
    if ((pid = fork()) == 0) {
        close(fd[1]);
        if (raw) {
            static char buf[1 << 17];
            while (read(fd[0], buf, sizeof buf) > 0)
                ;
            _exit(0);
        }
        dup2(fd[0], 0);
        tex_map *r = tex_map_read("-");
        _exit(r && r->w == m->w ? 0 : 1);
    }
    close(fd[0]);
    t0 = now();
    if (raw)
        tex_write_all(fd[1], bytes->data, bytes->len, "pipe");
    else
        tex_exr_write_fd(m, fd[1], "pipe");
    close(fd[1]);
    waitpid(pid, &status, 0);
    t1 = now();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "stream_io: the reader failed\n");
        exit(1);
    }
    return t1 - t0;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 2048, runs = argc > 2 ? atoi(argv[2]) : 9;
    tex_map *m = tex_map_new(n, n, 4);
    tex_buf bytes = {0};
    double ts[64], tr[64];

    if (!m || runs < 1 || runs > 64)
        return 2;
    for (size_t i = 0; i < tex_map_samples(m); i++)
        m->px[i] = (float)(i % 1021) / 1021.0f;
    tex_exr_encode(m, TEX_COMPRESS_NONE, &bytes);
    for (int i = 0; i < runs; i++) {
        ts[i] = transfer(m, &bytes, 0);
        tr[i] = transfer(m, &bytes, 1);
    }
    qsort(ts, runs, sizeof *ts, cmp);
    qsort(tr, runs, sizeof *tr, cmp);
    printf("%zu %.6f %.6f\n", bytes.len, ts[runs / 2], tr[runs / 2]);
    return 0;
}
