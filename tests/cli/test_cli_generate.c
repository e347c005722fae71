/* test_cli_generate.c - a generator's main and the band writer: a map written a band of
 * rows at a time (an EXR file, the stream on standard output, a window) has the pixels the
 * primitive samples whole; a per-pixel tool's bands are its whole map's */
#define _GNU_SOURCE
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "textura.h"
#include "unit.h"

static char dir[] = "/tmp/test_cli_generate.XXXXXX";

/* The primitive's map sampled whole, as a scene or script samples it (no tool). */
static tex_map *sampled(const struct tex_primitive *p, int w, int h, const char *name,
                        const char *value, int seed)
{
    struct tex_field *f = tex_field_new(p);
    tex_map *m = NULL;
    if (f && (!name || tex_field_set(f, name, value) == 0)) {
        f->seed = (uint64_t)seed;
        if (tex_field_init(f, w, h) == 0)
            m = tex_field_sample(f);
    }
    tex_field_free(f);
    return m;
}

static int same_pixels(const tex_map *a, const tex_map *b)
{
    return a && b && a->w == b->w && a->h == b->h && a->nc == b->nc &&
           !memcmp(a->px, b->px, tex_map_samples(a) * sizeof *a->px);
}

static int generate(const struct tex_primitive *p, char **argv)
{
    int argc = 0;
    while (argv[argc])
        argc++;
    return tex_generate_main(p, argc, argv);
}

static void test_bands(void)
{
    char exr[128], pfm[128], hist[300];
    tex_map *whole = sampled(&tex_prim_turbulence, 70, 300, "octaves", "3", 5), *a, *b;

    snprintf(exr, sizeof exr, "%s/t.exr", dir);
    snprintf(pfm, sizeof pfm, "%s/t.pfm", dir);
    generate(&tex_prim_turbulence,
             (char *[]){"t_turbulence", "-s", "70x300", "-n", "3", "-S", "5", "-o", exr, NULL});
    generate(&tex_prim_turbulence,
             (char *[]){"t_turbulence", "-s", "70x300", "-n", "3", "-S", "5", "-o", pfm, NULL});
    a = tex_map_read(exr);
    b = tex_map_read(pfm);
    CHECK(whole && same_pixels(a, whole), "an EXR file written in bands has the pixels the "
                                          "primitive samples whole");
    CHECK(same_pixels(b, whole), "and so has a PFM, written whole");
    snprintf(hist, sizeof hist, "t_turbulence -s 70x300 -n 3 -S 5 -o %s\n", exr);
    CHECK(a && a->history && !strcmp(a->history, hist), "its history is the command line");
    tex_map_free(a);
    tex_map_free(b);

    generate(&tex_prim_turbulence, (char *[]){"t_turbulence", "-s", "70x300", "-n", "3", "-S",
                                              "5", "--window", "10,150,33,77", "-o", exr, NULL});
    a = tex_map_read(exr);
    int crop = a && a->w == 33 && a->h == 77 && whole;
    for (int y = 0; crop && y < 77; y++)
        crop = !memcmp(tex_map_px(a, 0, y), tex_map_px(whole, 10, 150 + y), 33 * sizeof(float));
    CHECK(crop, "a window written in bands is the crop of the whole map");
    CHECK(a && a->x0 == 10 && a->y0 == 150 && a->full_w == 70 && a->full_h == 300,
          "and it keeps its place in the full map");
    tex_map_free(a);
    tex_map_free(whole);
    unlink(exr);
    unlink(pfm);
}

/* The stream on standard output, as in a pipeline (here into a file: fd 1 for a while).
 * Not in a child process: libgomp's threads do not survive a fork. */
static void test_stdout(void)
{
    char path[128];
    tex_map *whole = sampled(&tex_prim_checker, 64, 500, NULL, NULL, 1), *r = NULL;
    int fd, saved = dup(1), rc = -1;

    snprintf(path, sizeof path, "%s/stream", dir);
    fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    fflush(stdout);
    if (fd >= 0 && saved >= 0 && dup2(fd, 1) == 1) {
        rc = generate(&tex_prim_checker, (char *[]){"t_checker", "-s", "64x500", NULL});
        dup2(saved, 1);
        r = tex_map_read(path);
    }
    if (fd >= 0)
        close(fd);
    if (saved >= 0)
        close(saved);
    CHECK(rc == 0 && same_pixels(r, whole), "the stream on standard output, in bands: the "
                                            "whole map's pixels");
    tex_map_free(r);
    tex_map_free(whole);
    unlink(path);
}

static tex_map *scale_add(tex_map *band, void *arg)
{
    const float *k = arg;
    for (size_t i = 0; i < tex_map_samples(band); i++)
        band->px[i] = band->px[i] * k[0] + k[1];
    return band;
}

static tex_map *to_grey(tex_map *band, void *arg)
{
    tex_map *g = tex_map_new(band->w, band->h, 1);
    (void)arg;
    for (size_t i = 0; g && i < (size_t)band->w * band->h; i++)
        g->px[i] = band->px[3 * i] + band->px[3 * i + 1] - band->px[3 * i + 2];
    tex_map_free(band);
    return g;
}

/* A per-pixel tool's map in bands equals the same op over the whole map. */
static void test_stream(void)
{
    static const struct tex_tool tool = {"t_op", "[MAP]", "an operation", TEX_OPT_OUTPUT, NULL,
                                         0, 1};
    static float k[2] = {2.5f, -0.25f};
    struct tex_common c;
    char in[128], out[128], pfm[128];
    tex_map *m = sampled(&tex_prim_noise, 45, 333, NULL, NULL, 9), *c3, *r, *w;
    struct tex_write_opts o = TEX_WRITE_DEFAULTS;

    snprintf(in, sizeof in, "%s/in.exr", dir);
    snprintf(out, sizeof out, "%s/out.exr", dir);
    snprintf(pfm, sizeof pfm, "%s/out.pfm", dir);
    tex_map_write(m, in, &o);
    for (int whole = 0; whole <= 1; whole++) {
        tex_cli_parse(&tool, 3, (char *[]){"t_op", "-o", whole ? pfm : out, NULL}, &c, NULL);
        tex_cli_stream(in, &c, scale_add, k);
        free(c.cmdline);
        r = tex_map_read(whole ? pfm : out);
        w = scale_add(tex_map_clone(m), k);
        CHECKF(same_pixels(r, w), "scale and add over %s: the op's pixels",
               whole ? "the whole map (PFM out)" : "bands (EXR in and out)");
        tex_map_free(r);
        tex_map_free(w);
    }
    c3 = tex_map_new(45, 333, 3);
    for (size_t i = 0; c3 && i < tex_map_samples(c3); i++)
        c3->px[i] = m->px[i / 3] * (float)(i % 3 + 1);
    tex_map_write(c3, in, &o);
    tex_cli_parse(&tool, 3, (char *[]){"t_op", "-o", out, NULL}, &c, NULL);
    tex_cli_stream(in, &c, to_grey, NULL);
    free(c.cmdline);
    r = tex_map_read(out);
    w = to_grey(tex_map_clone(c3), NULL);
    CHECK(same_pixels(r, w), "an op that makes a map of its own per band: 3 channels in, 1 out");
    tex_map_free(r);
    tex_map_free(w);
    tex_map_free(c3);
    tex_map_free(m);
    unlink(in);
    unlink(out);
    unlink(pfm);
}

int main(void)
{
    void (*const tests[])(void) = {test_bands, test_stdout, test_stream};

    if (mkdtemp(dir))
        for (size_t i = 0; i < sizeof tests / sizeof *tests; i++)
            tests[i]();
    else
        CHECK(0, "a temporary folder");
    rmdir(dir);
    return unit_done();
}
