/* spool.c - a stream's rows in an unlinked temporary file, read back in any order */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/error.h"
#include "io/file.h"
#include "io/spool.h"

/* An unlinked file in TMPDIR, ".prefix.XXXXXX": its descriptor */
static int spool_file(const char *prefix)
{
    const char *dir = getenv("TMPDIR");
    char tmp[4096];
    int fd;

    snprintf(tmp, sizeof tmp, "%s/.%s.XXXXXX", dir && *dir ? dir : "/tmp", prefix);
    if ((fd = mkstemp(tmp)) < 0)
        return tex_error("%s: %s", tmp, strerror(errno));
    unlink(tmp);
    return fd;
}

int tex_spool_rows(struct tex_spool *s, const char *prefix, tex_rows_reader *r,
                   const tex_map *head, const char *name, int rows,
                   void (*take)(void *arg, const float *rows, int y, int n), void *arg)
{
    size_t row = (size_t)head->w * head->nc;
    int band = (int)((1L << 20) / (row * sizeof(float)));
    float *buf;

    *s = (struct tex_spool){-1, head->w, rows, head->nc, name};
    band = band < 1 ? 1 : band > rows ? rows : band;
    if (!(buf = malloc(row * band * sizeof *buf)))
        return tex_error("out of memory");
    if ((s->fd = spool_file(prefix)) < 0) {
        free(buf);
        return -1;
    }
    for (int y = 0; y < rows; y += band) {
        int n = rows - y < band ? rows - y : band;
        if (tex_rows_read(r, y, n, buf, name) < 0 ||
            tex_rows_nonfinite(buf, head->w, n, head->nc, y, name) < 0 ||
            tex_write_all(s->fd, buf, row * n * sizeof *buf, "a spool") < 0) {
            free(buf);
            tex_spool_close(s);
            return -1;
        }
        if (take)
            take(arg, buf, y, n);
    }
    free(buf);
    return s->fd;
}

/* Rows y..y+n-1 (0 <= y, y + n <= h) */
static int spool_run(const struct tex_spool *s, int y, int n, float *rows)
{
    size_t row = (size_t)s->w * s->nc * sizeof(float);

    for (size_t done = 0, want = row * n; done < want;) {
        ssize_t k = pread(s->fd, (char *)rows + done, want - done, (off_t)(row * y + done));
        if (k <= 0 && !(k < 0 && errno == EINTR))
            return tex_error("%s: spooled rows: %s", s->name, k < 0 ? strerror(errno) : "short");
        done += k > 0 ? (size_t)k : 0;
    }
    return 0;
}

int tex_spool_read(const struct tex_spool *s, long y, int n, float *rows)
{
    size_t row = (size_t)s->w * s->nc;

    for (int k = 0; k < n;) {
        int v = (int)(((y + k) % s->h + s->h) % s->h);
        int run = s->h - v < n - k ? s->h - v : n - k;
        if (spool_run(s, v, run, rows + row * k) < 0)
            return -1;
        k += run;
    }
    return 0;
}

void tex_spool_close(struct tex_spool *s)
{
    if (s->fd >= 0)
        close(s->fd);
    s->fd = -1;
}
