/* maps.c - a tool's maps in and out: read, written whole, or written a band of rows at a
 * time as they are made */
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "base/error.h"
#include "base/progress.h"
#include "io/file.h"
#include "io/spool.h"
#include "io/stream.h"

int tex_cli_depth(const struct tex_common *c)
{
    static const int bits[] = {0, 8, 16, 32}; /* the rows of --depth: auto|8|16|32 */
    return bits[c->depth_choice];
}

/* The write options -o, --depth, --compression, --format, --exr-tiles and --mipmap give */
static struct tex_write_opts write_opts(const struct tex_common *c)
{
    struct tex_write_opts o = {tex_cli_depth(c), (enum tex_compression)c->compression, c->format,
                               c->exr_tiles, c->mipmap};
    return o;
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
    struct tex_write_opts o = write_opts(c);

    tex_progress_done();
    if (c->cmdline && tex_map_add_history(m, c->cmdline) < 0)
        tex_die();
    if (tex_map_write(m, c->output, &o) < 0)
        tex_die();
}

/* tex_cli_write_rows, the stream's rows taken where at says they lie */
static void write_rows_at(tex_map *head, const struct tex_common *c, tex_rows_fn fill,
                          tex_rows_at_fn at, void *arg)
{
    struct tex_write_opts o = write_opts(c);

    if (c->cmdline && tex_map_add_history(head, c->cmdline) < 0)
        tex_die();
    if (tex_map_write_rows_at(head, fill, at, arg, c->output, &o) < 0)
        tex_die();
}

void tex_cli_write_rows(tex_map *head, const struct tex_common *c, tex_rows_fn fill, void *arg)
{
    write_rows_at(head, c, fill, NULL, arg);
}

/* A band op's work: the band (n + 2 margin rows of input, from row y - margin) read a
 * band at a time, its output served to the writer's fill calls, whatever their size. */
struct window_job {
    tex_rows_reader *r;          /* the rows read from here, or */
    const struct tex_spool *sp;  /* from a spool (taken in through the policy already) */
    const char *name;
    int w, nc, subregions, h, margin, rows; /* rows: a band's output rows */
    enum tex_edge edge;
    tex_band_fn *op;
    void *arg;
    int consumes;  /* op frees the band it does not give back (tex_cli_stream's ops) */
    tex_map *band; /* kept from band to band: the overlap, and no fresh pages each time */
    tex_map *out;  /* the output of rows oy..oy+on-1, from row ofs of out */
    int oy, on, ofs;
};

/* Band rows y-margin..y+n-1+margin in j->band: the 2 margin rows the last band shared with
 * this one moved up, the next rows read, and the rows beyond the edges filled in. */
static int window_rows(struct window_job *j, int y, int n)
{
    int m = j->margin, top = y - m, cap = j->rows + 2 * m;
    size_t row = (size_t)j->w * j->nc;
    int from = top < 0 ? 0 : top, to = y + n + m < j->h ? y + n + m : j->h;

    /* every row up to n + 2 m set below: read, moved up or an edge's copy */
    if (!j->band && !(j->band = tex_map_new_unset(j->w, cap, j->nc)))
        return -1;
    if (y > 0 && m > 0) { /* the last band began at y - rows - m */
        memmove(j->band->px, j->band->px + (size_t)j->rows * row, 2 * m * row * sizeof(float));
        from = y + m < to ? y + m : to;
    }
    float *at = j->band->px + (size_t)(from - top) * row;
    if (to > from && (j->sp ? tex_spool_read(j->sp, from, to - from, at) < 0
                            : tex_rows_read(j->r, from, to - from, at, j->name) < 0 ||
                                  tex_rows_nonfinite(at, j->w, to - from, j->nc, from,
                                                     j->name) < 0))
        return -1;
    for (int v = top; v < y + n + m; v++)
        if (v < 0 || v >= j->h)
            memcpy(j->band->px + (size_t)(v - top) * row,
                   j->band->px + (size_t)(tex_edge_index(v, j->h, j->edge) - top) * row,
                   row * sizeof(float));
    j->band->h = n + 2 * m;
    j->band->subregions = j->subregions;
    return 0;
}

/* The next band's output, rows y.. of the map */
static int window_next(struct window_job *j, int y)
{
    int n = j->h - y < j->rows ? j->h - y : j->rows;
    struct tex_band b = {y, n, j->margin, j->h};
    tex_map *o;

    if (j->out != j->band)
        tex_map_free(j->out);
    j->out = NULL;
    if (window_rows(j, y, n) < 0 || !(o = j->op(j->band, &b, j->arg)))
        return -1;
    if (o != j->band && j->consumes)
        j->band = NULL; /* freed by op */
    if (o->w != j->w || (o->h != n && o->h != n + 2 * j->margin)) {
        if (o != j->band)
            tex_map_free(o);
        return tex_error("%s: a band of %d rows gave %dx%d", j->name, n, o->w, o->h);
    }
    j->out = o, j->oy = y, j->on = n, j->ofs = o->h == n ? 0 : j->margin;
    return 0;
}

/* Where the output's rows y.. lie, k of them (1..n, those of the band that holds y): k, or
 * -1 with the error set.  The stream's writer takes them from there (tex_rows_at_fn). */
static int window_at(void *arg, int y, int n, const float **rows)
{
    struct window_job *j = arg;

    if (y >= j->oy + j->on && window_next(j, y) < 0)
        return -1;
    *rows = j->out->px + (size_t)(y - j->oy + j->ofs) * j->w * j->out->nc;
    return j->oy + j->on - y < n ? j->oy + j->on - y : n;
}

/* The same rows copied into the writer's, for the writers that take no rows where they lie */
static int window_fill(void *arg, int y, int n, float *rows)
{
    struct window_job *j = arg;

    while (n > 0) {
        const float *at;
        int k = window_at(j, y, n, &at);
        if (k < 0)
            return -1;
        size_t orow = (size_t)j->w * j->out->nc;
        memcpy(rows, at, k * orow * sizeof *rows);
        rows += k * orow, y += k, n -= k;
    }
    return 0;
}

/* Rows of output per band: $TEXTURA_BAND_ROWS, or about 2 MiB of input in whole
 * multiples of the writer's 64 rows.  Small bands let the next stage start sooner, and
 * keep a band's maps below malloc's mmap threshold, so they reuse pages rather than
 * clear fresh ones for every band.  Rows wider than 32 KiB: 64 of them, or fewer where 64
 * pass 8 MiB (16 at least), so a stage of a 65536-wide map holds tens of MiB, not 100. */
int tex_cli_band_rows(int w, int nc)
{
    const char *e = getenv("TEXTURA_BAND_ROWS");
    char *end;
    long n;

    if (e && *e && !tex_rows_whole()) {
        n = strtol(e, &end, 10);
        if (*end || n < 1 || n > 65536)
            tex_usage_die("TEXTURA_BAND_ROWS must be 1..65536 or whole (got '%s')", e);
        return (int)n;
    }
    long row = (long)w * nc * (long)sizeof(float);
    n = (2L << 20) / row / 64 * 64;
    if (n < 64) {
        n = (8L << 20) / row;
        return n < 16 ? 16 : n > 64 ? 64 : (int)n;
    }
    return n > 4096 ? 4096 : (int)n;
}

tex_map *tex_cli_rows_whole(tex_rows_reader *r, tex_map *head, const char *name)
{
    tex_map *whole = tex_map_new(head->w, head->h, head->nc);

    if (!whole || tex_rows_read(r, 0, head->h, whole->px, name) < 0 ||
        tex_rows_nonfinite(whole->px, head->w, head->h, head->nc, 0, name) < 0)
        tex_die();
    whole->subregions = head->subregions;
    tex_map_inherit_place(whole, head);
    whole->history = head->history;
    head->history = NULL;
    tex_rows_close(r);
    return whole;
}

static void stream_whole(tex_map *whole, const struct tex_common *c, tex_band_fn *op, void *arg,
                         int consumes)
{
    struct tex_band b = {0, whole->h, 0, whole->h};
    tex_map *m = op(whole, &b, arg);

    if (!m)
        tex_die();
    tex_cli_write(m, c);
    if (m != whole && !consumes)
        tex_map_free(whole);
    tex_map_free(m);
}

/* j's bands written to -o or standard output as head (its history taken and freed) */
static void window_write(struct window_job *j, tex_map *head, const struct tex_common *c)
{
    if (window_next(j, 0) < 0) /* the first band before the header: its channels */
        tex_die();
    tex_map out = *head;
    out.nc = j->out->nc;
    out.subregions = j->out->subregions;
    head->history = NULL;
    write_rows_at(&out, c, window_fill, window_at, j);
    if (j->out != j->band)
        tex_map_free(j->out);
    tex_map_free(j->band);
    free(out.history);
}

static void stream_window(const char *path, const struct tex_common *c, int margin,
                          enum tex_edge edge, tex_band_fn *op, void *arg, int consumes)
{
    const char *name = path && strcmp(path, "-") ? path : "standard input";
    tex_map head, *whole = NULL;
    tex_rows_reader *r = NULL;

    if (tex_map_write_check(c->output, c->format) < 0)
        tex_die();
    if (tex_cli_takes_rows(c)) {
        r = tex_map_open_rows(path, &head, &whole);
        if (!r && !whole)
            tex_die();
    } else {
        whole = tex_cli_read(path);
    }
    if (r && margin > 0 && (edge == TEX_EDGE_WRAP || head.h < 2 * margin + 1)) {
        whole = tex_cli_rows_whole(r, &head, name); /* none read so far */
        r = NULL;
    }
    if (!r) {
        stream_whole(whole, c, op, arg, consumes);
        return;
    }
    struct window_job j = {.r = r, .name = name, .w = head.w, .nc = head.nc,
                           .subregions = head.subregions, .h = head.h, .margin = margin,
                           .rows = tex_cli_band_rows(head.w, head.nc), .edge = edge, .op = op,
                           .arg = arg, .consumes = consumes};
    window_write(&j, &head, c);
    tex_rows_close(r);
}

void tex_cli_stream_window(const char *path, const struct tex_common *c, int margin,
                           enum tex_edge edge, tex_band_fn *op, void *arg)
{
    stream_window(path, c, margin, edge, op, arg, 0);
}

struct pixel_op {
    tex_map *(*op)(tex_map *band, void *arg);
    void *arg;
};

static tex_map *pixel_band(tex_map *band, const struct tex_band *b, void *arg)
{
    struct pixel_op *p = arg;
    (void)b;
    return p->op(band, p->arg);
}

int tex_cli_streams(const struct tex_common *c)
{
    const char *file;

    return !c->exr_tiles && !c->mipmap &&
           tex_output_format(c->output, c->format, &file) == TEX_FMT_EXR;
}

int tex_cli_takes_rows(const struct tex_common *c)
{
    struct tex_write_opts o = write_opts(c);
    return !tex_rows_whole() && tex_map_write_streams(c->output, &o);
}

void tex_cli_stream(const char *path, const struct tex_common *c,
                    tex_map *(*op)(tex_map *band, void *arg), void *arg)
{
    struct pixel_op p = {op, arg};
    stream_window(path, c, 0, TEX_EDGE_CLAMP, pixel_band, &p, 1);
}

void tex_cli_stream_spool(const struct tex_spool *sp, tex_map *head, const struct tex_common *c,
                          tex_map *(*op)(tex_map *band, void *arg), void *arg)
{
    struct pixel_op p = {op, arg};
    struct window_job j = {.sp = sp, .name = sp->name, .w = sp->w, .nc = sp->nc,
                           .subregions = head->subregions, .h = sp->h,
                           .rows = tex_cli_band_rows(sp->w, sp->nc), .edge = TEX_EDGE_CLAMP,
                           .op = pixel_band, .arg = &p, .consumes = 1};
    window_write(&j, head, c);
}
