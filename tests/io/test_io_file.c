/* test_io_file.c - writing map files: whole or not at all, through links, and windows
 * assembled into the full map */
#define _GNU_SOURCE
#include <dirent.h>
#include <math.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "textura.h"
#include "io/assemble.h"
#include "unit.h"

static char dir[] = "/tmp/test_io_file.XXXXXX";

/* A path in the folder, good until the fourth call after. */
static const char *in_dir(const char *name)
{
    static char path[4][128];
    static int k;
    k = (k + 1) % 4;
    snprintf(path[k], sizeof path[k], "%s/%s", dir, name);
    return path[k];
}

/* The names in the folder, sorted, space-separated. */
static const char *listing(void)
{
    static char s[512];
    struct dirent **e;
    int n = scandir(dir, &e, NULL, alphasort);
    s[0] = 0;
    for (int i = 0; i < n; i++) {
        if (strcmp(e[i]->d_name, ".") && strcmp(e[i]->d_name, ".."))
            snprintf(s + strlen(s), sizeof s - strlen(s), "%s%s", *s ? " " : "", e[i]->d_name);
        free(e[i]);
    }
    free(n >= 0 ? e : NULL);
    return s;
}

static tex_map *ramp(int w, int h, int nc)
{
    tex_map *m = tex_map_new(w, h, nc);
    for (size_t i = 0; m && i < tex_map_samples(m); i++)
        m->px[i] = (float)(i % 251) / 250.0f;
    return m;
}

static int same_pixels(const tex_map *a, const tex_map *b)
{
    return a && b && a->w == b->w && a->h == b->h && a->nc == b->nc &&
           !memcmp(a->px, b->px, tex_map_samples(a) * sizeof *a->px);
}

/* A write that fails part way (the file size limit) leaves no file, no temporary file,
 * and an older file as it was. */
static void test_atomic(void)
{
    static const char *const names[] = {"big.pfm", "big.exr", "big.ppm"};
    struct rlimit old, small;
    tex_map *m = ramp(128, 128, 3), *r;
    struct tex_write_opts o = TEX_WRITE_DEFAULTS;

    signal(SIGXFSZ, SIG_IGN); /* the write fails with EFBIG instead */
    getrlimit(RLIMIT_FSIZE, &old);
    small = old;
    small.rlim_cur = 10000;
    for (int k = 0; k < 3; k++) {
        int failed;
        o.compression = TEX_COMPRESS_NONE;
        setrlimit(RLIMIT_FSIZE, &small);
        failed = tex_map_write(m, in_dir(names[k]), &o) < 0;
        setrlimit(RLIMIT_FSIZE, &old);
        CHECKF(failed && strstr(tex_errmsg(), names[k]), "writing %s past the size limit fails "
               "naming it (%s)", names[k], tex_errmsg());
        CHECKF(!strcmp(listing(), ""), "and leaves no file behind (%s)", listing());
    }
    tex_map *small_map = ramp(4, 4, 3);
    tex_map_write(small_map, in_dir("keep.pfm"), &o);
    setrlimit(RLIMIT_FSIZE, &small);
    tex_map_write(m, in_dir("keep.pfm"), &o);
    setrlimit(RLIMIT_FSIZE, &old);
    r = tex_map_read(in_dir("keep.pfm"));
    CHECK(same_pixels(r, small_map) && !strcmp(listing(), "keep.pfm"),
          "a failed write leaves the older file as it was");
    tex_map_free(r);
    unlink(in_dir("keep.pfm"));

    /* a link is followed: its target replaced, the link kept */
    tex_map_write(small_map, in_dir("target.pfm"), &o);
    if (symlink("target.pfm", in_dir("link.pfm")) == 0 &&
        tex_map_write(m, in_dir("link.pfm"), &o) == 0) {
        struct stat st;
        r = tex_map_read(in_dir("target.pfm"));
        CHECK(lstat(in_dir("link.pfm"), &st) == 0 && S_ISLNK(st.st_mode) && same_pixels(r, m),
              "writing through a link replaces its target and keeps the link");
        tex_map_free(r);
    }
    unlink(in_dir("link.pfm"));
    unlink(in_dir("target.pfm"));
    CHECK(tex_map_write_check(in_dir("x.unknown"), NULL) < 0 && !strcmp(listing(), ""),
          "an unknown extension is refused before anything is written");
    tex_map_free(small_map);
    tex_map_free(m);
}

struct fail_after {
    int rows;
};

static int fill_then_fail(void *arg, int y, int n, float *rows)
{
    struct fail_after *f = arg;
    memset(rows, 0, sizeof *rows * 8 * 3 * (size_t)n);
    return y + n > f->rows ? tex_error("the sampler failed at row %d", y) : 0;
}

/* An output file whose rows stop coming: tex_out_close(-1) removes its temporary file. */
static void test_out_rows(void)
{
    tex_map head = {.w = 8, .h = 500, .nc = 3};
    struct fail_after f = {200};
    struct tex_out o;
    int r = tex_out_open(&o, in_dir("rows.exr"));
    if (r == 0)
        r = tex_exr_write_rows(&head, fill_then_fail, &f, 0, TEX_COMPRESS_ZIP, o.fd, o.name);
    r = tex_out_close(&o, r);
    CHECKF(r < 0 && !strcmp(listing(), ""), "rows that stop coming leave no file (%s)",
           listing());
}

/* Windows written with their place, put back together. */
static void test_assemble(void)
{
    static const int win[][4] = {{0, 0, 30, 8}, {0, 8, 12, 12}, {12, 8, 18, 12}};
    char names[3][128];
    const char *paths[3] = {names[0], names[1], names[2]};
    tex_map *whole = ramp(30, 20, 3), *r;
    struct tex_write_opts wo = TEX_WRITE_DEFAULTS;

    for (int k = 0; k < 3; k++) {
        tex_map *w = tex_map_new(win[k][2], win[k][3], 3);
        snprintf(names[k], sizeof names[k], "%s/w%d.exr", dir, k);
        for (int y = 0; y < w->h; y++)
            memcpy(tex_map_px(w, 0, y), tex_map_px(whole, win[k][0], win[k][1] + y),
                   sizeof *w->px * 3 * (size_t)w->w);
        w->x0 = win[k][0], w->y0 = win[k][1], w->full_w = 30, w->full_h = 20;
        tex_map_add_history(w, "t_noise --window");
        tex_map_write(w, paths[k], &wo);
        tex_map_free(w);
    }
    for (int tile = 0; tile <= 16; tile += 16) {
        const char *out = in_dir("out.exr");
        int fd = open(out, O_RDWR | O_CREAT | O_TRUNC, 0644);
        int rc = tex_assemble(paths, 3, fd, out, tile, TEX_COMPRESS_ZIP, "t_assemble w*.exr");
        close(fd);
        r = rc == 0 ? tex_map_read(out) : NULL;
        CHECKF(same_pixels(r, whole) && r->full_w == 0 && r->history &&
                   !strcmp(r->history, "t_noise --window\nt_assemble w*.exr\n"),
               "three windows make the whole map%s, the history appended",
               tile ? " in tiles" : "");
        tex_map_free(r);
        unlink(out);
    }
    {
        int fd = open("/dev/null", O_WRONLY);
        const char *two[2] = {paths[0], paths[2]}, *again[3] = {paths[0], paths[1], paths[1]};
        CHECKF(tex_assemble(two, 2, fd, "out", 0, TEX_COMPRESS_NONE, NULL) < 0 &&
                   tex_errkind() == TEX_ERR_USAGE,
               "a gap is refused as a usage error (%s)", tex_errmsg());
        CHECKF(tex_assemble(again, 3, fd, "out", 0, TEX_COMPRESS_NONE, NULL) < 0,
               "an overlap is refused (%s)", tex_errmsg());
        close(fd);
    }
    for (int k = 0; k < 3; k++)
        unlink(paths[k]);
    tex_map_free(whole);
}

/* tex_rows_nonfinite skips blocks of samples without a NaN or infinity in vector code: one
 * in any block, at a block's first or last sample or past the last whole block, is still
 * found, the first named and each replaced */
static void test_nonfinite_blocks(void)
{
    const int w = 301, h = 47, nc = 3; /* 42441 samples: 10 blocks of 4096 and a part */
    const size_t at[] = {0, 4095, 4096, 20000, (size_t)w * h * nc - 1};
    const float bad[] = {NAN, INFINITY, -INFINITY, NAN, INFINITY};
    size_t total = (size_t)w * h * nc;
    float *px = malloc(total * sizeof *px);
    if (!px) {
        CHECK(0, "a buffer");
        return;
    }
    for (int k = 0; k < 5; k++) {
        for (size_t i = 0; i < total; i++)
            px[i] = 0.5f;
        px[at[k]] = bad[k];
        tex_map_set_nonfinite(TEX_NONFINITE_REFUSE, 0);
        char want[64];
        snprintf(want, sizeof want, "pixel (%zu,%zu) channel %zu", at[k] / nc % w,
                 7 + at[k] / nc / w, at[k] % nc);
        CHECKF(tex_rows_nonfinite(px, w, h, nc, 7, "rows") < 0 && strstr(tex_errmsg(), want),
               "a non-finite sample at %zu refused: %s", at[k], tex_errmsg());
    }
    for (size_t i = 0; i < total; i++)
        px[i] = i % 7 == 0 ? 0.25f : 0.5f;
    for (int k = 0; k < 5; k++)
        px[at[k]] = bad[k];
    tex_map_set_nonfinite(TEX_NONFINITE_REPLACE, 0.75f);
    int same = tex_rows_nonfinite(px, w, h, nc, 0, "rows") == 0;
    for (size_t i = 0, k = 0; i < total; i++) {
        int is_bad = k < 5 && i == at[k];
        same &= px[i] == (is_bad ? 0.75f : i % 7 == 0 ? 0.25f : 0.5f);
        k += is_bad;
    }
    CHECK(same, "--nonfinite VALUE replaces the five non-finite samples and only those");
    tex_map_set_nonfinite(TEX_NONFINITE_REFUSE, 0);
    free(px);
}

int main(void)
{
    if (!mkdtemp(dir)) {
        CHECK(0, "a temporary folder");
        return unit_done();
    }
    test_atomic();
    test_out_rows();
    test_assemble();
    test_nonfinite_blocks();
    rmdir(dir);
    return unit_done();
}
