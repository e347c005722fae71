/* maps.c - a tool's maps in and out: read, written whole, or written a band of rows at a
 * time as they are made */
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "base/error.h"
#include "base/progress.h"
#include "io/file.h"
#include "io/stream.h"

int tex_cli_depth(const struct tex_common *c)
{
    static const int bits[] = {0, 8, 16, 32}; /* the rows of --depth: auto|8|16|32 */
    return bits[c->depth_choice];
}

tex_map *tex_cli_read(const char *path)
{
    tex_map *m = tex_map_read(path);
    if (!m)
        tex_die();
    return m;
}

void tex_cli_write(tex_map *m, const struct tex_common *c)
{
    struct tex_write_opts o = {tex_cli_depth(c), (enum tex_compression)c->compression, c->format,
                               c->exr_tiles, c->mipmap};

    tex_progress_done();
    if (c->cmdline && tex_map_add_history(m, c->cmdline) < 0)
        tex_die();
    if (tex_map_write(m, c->output, &o) < 0)
        tex_die();
}

void tex_cli_write_rows(tex_map *head, const struct tex_common *c, tex_rows_fn fill, void *arg)
{
    struct tex_out o = {.fd = 1};
    const char *oname = "standard output";
    int rc;

    if (c->cmdline && tex_map_add_history(head, c->cmdline) < 0)
        tex_die();
    if (c->output && strcmp(c->output, "-")) {
        if (tex_out_open(&o, c->output) < 0) {
            tex_out_close(&o, -1);
            tex_die();
        }
        oname = c->output;
    }
    rc = tex_exr_write_rows(head, fill, arg, 0, (enum tex_compression)c->compression, o.fd,
                            oname);
    if (o.fd != 1)
        rc = tex_out_close(&o, rc);
    if (rc < 0)
        tex_die();
}

struct band_job {
    tex_rows_reader *r;
    const char *name;
    int w, nc, subregions;
    tex_map *(*op)(tex_map *, void *);
    void *arg;
    tex_map *keep; /* a band the op gave back as it took it, for the next band's rows */
};

/* The op's band is the last one's map where the op gave that back (the bands are one
 * size but the last): a map of its own for each band would be fresh pages each time. */
static int band_fill(void *arg, int y, int n, float *rows)
{
    struct band_job *j = arg;
    tex_map *b = j->keep, *o;

    j->keep = NULL;
    if (b && b->h < n) {
        tex_map_free(b);
        b = NULL;
    }
    if (!b && !(b = tex_map_new(j->w, n, j->nc)))
        return -1;
    b->h = n;
    b->subregions = j->subregions;
    if (tex_rows_read(j->r, y, n, b->px, j->name) < 0 ||
        tex_rows_nonfinite(b->px, j->w, n, j->nc, y, j->name) < 0 || !(o = j->op(b, j->arg))) {
        tex_map_free(b);
        return -1;
    }
    memcpy(rows, o->px, tex_map_samples(o) * sizeof *rows);
    if (o->w == j->w && o->nc == j->nc)
        j->keep = o;
    else
        tex_map_free(o);
    return 0;
}

int tex_cli_streams(const struct tex_common *c)
{
    if (c->exr_tiles || c->mipmap || (c->format && strcmp(c->format, "exr") != 0))
        return 0;
    return !c->output || !strcmp(c->output, "-") ||
           tex_format_from_name(c->output) == TEX_FMT_EXR;
}

void tex_cli_stream(const char *path, const struct tex_common *c,
                    tex_map *(*op)(tex_map *band, void *arg), void *arg)
{
    const char *name = path && strcmp(path, "-") ? path : "standard input";
    tex_map head, *whole = NULL, *probe, *m;
    tex_rows_reader *r = NULL;

    if (tex_map_write_check(c->output) < 0)
        tex_die();
    if (tex_cli_streams(c)) {
        r = tex_map_open_rows(path, &head, &whole);
        if (!r && !whole)
            tex_die();
    } else {
        whole = tex_cli_read(path);
    }
    if (!r) { /* the same op over the whole map */
        if (!(m = op(whole, arg)))
            tex_die();
        tex_cli_write(m, c);
        tex_map_free(m);
        return;
    }
    if (!(probe = tex_map_new(1, 1, head.nc)))
        tex_die();
    for (int k = 0; k < head.nc; k++)
        probe->px[k] = 1;
    probe->subregions = head.subregions;
    if (!(probe = op(probe, arg)))
        tex_die();
    {
        struct band_job j = {r, name, head.w, head.nc, head.subregions, op, arg, NULL};
        tex_map out = head;
        out.nc = probe->nc;
        out.subregions = probe->subregions;
        tex_map_free(probe);
        tex_cli_write_rows(&out, c, band_fill, &j);
        tex_map_free(j.keep);
        tex_rows_close(r);
        free(out.history);
    }
}
