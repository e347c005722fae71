/* test_io_stream.c - the EXR stream: maps through a pipe and a file with their metadata,
 * a band of rows at a time, tiled with mip levels, and broken streams refused by name */
#define _GNU_SOURCE
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "textura.h"
#include "unit.h"

/* A map whose samples differ everywhere, with every attribute set. */
static tex_map *sample_map(int w, int h, int nc)
{
    tex_map *m = tex_map_new(w, h, nc);
    for (size_t i = 0; m && i < tex_map_samples(m); i++)
        m->px[i] = (float)((i * 40503u) % 977) / 977.0f - 0.25f;
    if (m) {
        m->subregions = 5;
        tex_map_add_history(m, "t_noise -s 16x9");
        tex_map_add_history(m, "t_palette 'my palette.pal' -");
        m->x0 = 3, m->y0 = 2, m->full_w = w + 5, m->full_h = h + 4; /* a window */
    }
    return m;
}

static int same_map(const tex_map *a, const tex_map *b)
{
    return a && b && a->w == b->w && a->h == b->h && a->nc == b->nc &&
           memcmp(a->px, b->px, tex_map_samples(a) * sizeof *a->px) == 0;
}

static int same_metadata(const tex_map *a, const tex_map *b)
{
    return a && b && a->subregions == b->subregions && a->history && b->history &&
           !strcmp(a->history, b->history) && a->x0 == b->x0 && a->y0 == b->y0 &&
           a->full_w == b->full_w && a->full_h == b->full_h;
}

/* 1 to 4 channels through a pipe, as one tool hands a map to the next. */
static void test_pipe_round_trip(void)
{
    for (int nc = 1; nc <= 4; nc++) {
        tex_map *m = sample_map(16, 9, nc), *r = NULL;
        int p[2];
        if (pipe(p) == 0) { /* 16 x 9 maps fit in the pipe's buffer */
            if (tex_exr_write_fd(m, p[1], "standard output") == 0) {
                close(p[1]);
                r = tex_exr_read_fd(p[0], NULL, 0, "standard input");
            } else {
                close(p[1]);
            }
            close(p[0]);
        }
        CHECKF(same_map(m, r), "%d channel(s) through a pipe: the same samples", nc);
        CHECKF(same_metadata(m, r), "%d channel(s) through a pipe: subregions, history and "
               "the window's place kept", nc);
        tex_map_free(m);
        tex_map_free(r);
    }
}

/* A file written by tex_map_write and read by tex_map_read, compressed or not. */
static void test_file_round_trip(void)
{
    char dir[] = "/tmp/test_io_stream.XXXXXX", path[64];
    if (!mkdtemp(dir)) {
        CHECK(0, "a temporary folder");
        return;
    }
    snprintf(path, sizeof path, "%s/m.exr", dir);
    for (int c = TEX_COMPRESS_NONE; c <= TEX_COMPRESS_PIZ; c++)
        for (int tiled = 0; tiled <= 1; tiled++) {
            tex_map *m = sample_map(70, 33, 3), *r;
            struct tex_write_opts o = {0, (enum tex_compression)c, NULL, tiled, 0};
            if (tiled) /* tiled files are whole maps */
                m->x0 = m->y0 = m->full_w = m->full_h = 0;
            r = tex_map_write(m, path, &o) == 0 ? tex_map_read(path) : NULL;
            CHECKF(same_map(m, r) && same_metadata(m, r),
                   "a file, compression %d%s: the same map and metadata", c,
                   tiled ? ", in tiles" : "");
            tex_map_free(m);
            tex_map_free(r);
        }
    unlink(path);
    rmdir(dir);
}

struct rows_src {
    const tex_map *m;
    int calls, last_y;
};

static int copy_rows(void *arg, int y, int n, float *rows)
{
    struct rows_src *s = arg;
    size_t row = (size_t)s->m->w * s->m->nc;
    if (y != s->last_y) /* rows come from the top, in order */
        return tex_error("rows %d asked after %d", y, s->last_y);
    memcpy(rows, s->m->px + (size_t)y * row, (size_t)n * row * sizeof *rows);
    s->calls++;
    s->last_y = y + n;
    return 0;
}

/* A map written a band of rows at a time and read back a band at a time. */
static void test_rows(void)
{
    char path[] = "/tmp/test_io_rows.XXXXXX";
    int fd = mkstemp(path), ok = 1;
    tex_map *m = sample_map(50, 300, 2), head = *m, *r = NULL;
    struct rows_src s = {m, 0, 0};
    tex_rows_reader *rd;

    head.px = NULL;
    CHECK(fd >= 0 && tex_exr_write_rows(&head, copy_rows, &s, 0, TEX_COMPRESS_ZIP, fd,
                                        path) == 0,
          "300 rows written a band at a time");
    CHECKF(s.calls > 1 && s.last_y == 300, "in bands from the top (%d bands)", s.calls);
    if (fd >= 0)
        close(fd);
    r = tex_map_read(path);
    CHECK(same_map(m, r) && same_metadata(m, r), "read whole: the same map and metadata");
    tex_map_free(r);
    memset(&head, 0, sizeof head);
    rd = tex_rows_open(-1, NULL, 0, path, path, &head, NULL);
    CHECK(rd && head.w == 50 && head.h == 300 && head.nc == 2 && head.subregions == 5,
          "the rows reader gives the header");
    float *band = malloc(sizeof *band * 50 * 2 * 64);
    for (int y = 0; rd && band && y < 300; y += 64) {
        int n = y + 64 <= 300 ? 64 : 300 - y;
        ok &= tex_rows_read(rd, y, n, band, path) == 0 &&
              !memcmp(band, m->px + (size_t)y * 100, sizeof *band * 100 * n);
    }
    CHECK(rd && band && ok, "bands of 64 rows read back as written");
    free(band);
    free(head.history);
    tex_rows_close(rd);
    unlink(path);
    tex_map_free(m);
}

/* A tiled file with its mip levels, each the reduction of the one above. */
static void test_mip_levels(void)
{
    tex_map *m = sample_map(37, 20, 4), **lv;
    tex_buf b = {0};
    int n = 0, halves = 1;

    m->subregions = 0; /* ids are not averaged */
    m->x0 = m->y0 = m->full_w = m->full_h = 0;
    lv = tex_exr_encode_tiled(m, 16, 1, TEX_COMPRESS_ZIP, &b) == 0
             ? tex_exr_decode_levels(b.data, b.len, "m.tx", &n)
             : NULL;
    CHECKF(lv && n == 6, "37 x 20 has 6 levels down to 1 x 1 (got %d)", n);
    CHECK(lv && same_map(m, lv[0]), "the first level is the map");
    for (int i = 1; lv && i < n; i++)
        halves &= lv[i]->w == (lv[i - 1]->w > 1 ? lv[i - 1]->w / 2 : 1) &&
                  lv[i]->h == (lv[i - 1]->h > 1 ? lv[i - 1]->h / 2 : 1);
    CHECK(lv && halves, "each level is half the one above, rounded down");
    for (int i = 0; lv && i < n; i++)
        tex_map_free(lv[i]);
    free(lv);
    tex_buf_free(&b);
    tex_map_free(m);
}

/* A stream cut short or damaged: no map, and a message that names the input. */
static void test_broken(void)
{
    tex_map *m = sample_map(24, 18, 3);
    tex_buf b = {0};
    char path[] = "/tmp/test_io_cut.XXXXXX";
    int fd = mkstemp(path), named = 1, refused = 1, cuts = 0;

    tex_exr_encode(m, TEX_COMPRESS_NONE, &b);
    for (size_t cut = 1; fd >= 0 && cut < b.len; cut += 1 + cut / 3, cuts++) {
        tex_map *r;
        if (ftruncate(fd, 0) < 0 || pwrite(fd, b.data, cut, 0) != (ssize_t)cut)
            break;
        r = tex_map_read(path);
        refused &= r == NULL;
        named &= r == NULL && strstr(tex_errmsg(), path) != NULL;
        if (!named && cuts < 100)
            printf("# cut at %zu: %s\n", cut, tex_errmsg()), cuts = 100;
        tex_map_free(r);
    }
    CHECK(refused, "no file cut short is read");
    CHECK(named, "every refusal names the file");
    {
        unsigned char *p = memmem(b.data, b.len, "compression\0compression", 23);
        tex_map *r = NULL;
        if (p && fd >= 0 && ftruncate(fd, 0) == 0) {
            p[23 + 4] = 42; /* no such compression */
            if (pwrite(fd, b.data, b.len, 0) == (ssize_t)b.len)
                r = tex_map_read(path);
            p[23 + 4] = TEX_COMPRESS_NONE;
        }
        CHECKF(p && !r && strstr(tex_errmsg(), path), "a damaged header is refused by name (%s)",
               tex_errmsg());
        tex_map_free(r);
    }
    if (fd >= 0) { /* standard input, as a tool reads "-" */
        int p[2], in = dup(0);
        tex_map *r = NULL;
        if (in >= 0 && pipe(p) == 0) {
            ssize_t half = write(p[1], b.data, b.len / 2);
            close(p[1]);
            if (half > 0 && dup2(p[0], 0) == 0)
                r = tex_map_read("-");
            close(p[0]);
            dup2(in, 0);
            close(in);
        }
        CHECKF(!r && strstr(tex_errmsg(), "standard input"),
               "a stream cut short on standard input is refused naming it (%s)", tex_errmsg());
        tex_map_free(r);
        close(fd);
        unlink(path);
    }
    tex_buf_free(&b);
    tex_map_free(m);
}

int main(void)
{
    test_pipe_round_trip();
    test_file_round_trip();
    test_rows();
    test_mip_levels();
    test_broken();
    return unit_done();
}
