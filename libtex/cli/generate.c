/* generate.c - the whole main of a generator tool: parse, sample, write (in bands when
 * the output streams) */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "base/error.h"
#include "base/progress.h"
#include "io/file.h"
#include "ops/palette.h"

/* The colours of subregions 1..n through the palette named. */
static float *region_colors(const char *palette, int n)
{
    tex_palette *pal = tex_palette_load(palette);
    float *c = pal ? tex_palette_region_colours(pal, n) : NULL;
    tex_palette_free(pal);
    return c;
}

struct gen_job {
    struct tex_field *f;
    int x, y, w; /* the window the bands cut (the whole grid without --window) */
};

/* A band sampled straight into the encoder's rows: a map of its own for each band
 * would be fresh memory each time, and a first touch of a page is dear. */
static int gen_fill(void *arg, int y, int n, float *rows)
{
    struct gen_job *j = arg;
    tex_map b = {.w = j->w, .h = n, .nc = tex_field_channels(j->f), .px = rows};
    int rc;

    j->f->wx = j->x;
    j->f->wy = j->y + y;
    j->f->ww = j->w;
    j->f->wh = n;
    memset(rows, 0, tex_map_samples(&b) * sizeof *rows); /* as tex_map_new's maps come */
    tex_progress_hold(1); /* the band counts as its rows of the whole map */
    rc = tex_field_sample_into(j->f, &b);
    tex_progress_hold(0);
    if (rc < 0)
        return -1;
    tex_progress_add(n);
    return 0;
}

static int gen_probe(struct gen_job *j, tex_map **probe)
{
    struct tex_field *f = j->f;
    int saved[4] = {f->wx, f->wy, f->ww, f->wh};
    f->wx = j->x;
    f->wy = j->y;
    f->ww = f->wh = 1;
    *probe = tex_field_sample(f);
    f->wx = saved[0], f->wy = saved[1], f->ww = saved[2], f->wh = saved[3];
    return *probe ? 0 : -1;
}

/* A generator's map written as it is sampled, a band of rows at a time. */
static void generate_bands(struct tex_field *f, const struct tex_common *c)
{
    int win = f->ww > 0;
    struct gen_job j = {f, win ? f->wx : 0, win ? f->wy : 0, win ? f->ww : f->w};
    tex_map head = {0};
    tex_map *probe;
    head.w = j.w;
    head.h = win ? f->wh : f->h;
    /* channels and subregions as the sampler makes them: its first pixel */
    if (gen_probe(&j, &probe) < 0)
        tex_die();
    head.nc = probe->nc;
    head.subregions = probe->subregions;
    tex_map_free(probe);
    if (win) {
        head.x0 = f->wx;
        head.y0 = f->wy;
        head.full_w = f->w;
        head.full_h = f->h;
    }
    tex_progress_stage(1, head.h);
    tex_cli_write_rows(&head, c, gen_fill, &j);
    free(head.history);
}

int tex_generate_main(const struct tex_primitive *p, int argc, char **argv)
{
    char name[64];
    snprintf(name, sizeof name, "t_%s", p->name);
    return tex_generate_main_rows(p, name, "", NULL, NULL, argc, argv);
}

int tex_generate_main_rows(const struct tex_primitive *p, const char *name,
                           const char *operands, const struct tex_param *rows, void *opts,
                           int argc, char **argv)
{
    float *colors = NULL;
    struct tex_common c;
    struct tex_field *f;
    tex_map *m;
    int nops = operands[0] != 0;
    struct tex_tool t = {name, operands, p->summary,
                         TEX_OPT_OUTPUT | TEX_OPT_SIZE | TEX_OPT_SEED | TEX_OPT_WINDOW,
                         rows ? rows : p->params, nops, nops};

    if (p->flags & TEX_PRIM_TILE)
        t.common |= TEX_OPT_TILE;
    if (p->flags & TEX_PRIM_REGIONS)
        t.common |= TEX_OPT_IDS | TEX_OPT_PALETTE;
    if (!(f = tex_field_new(p)))
        tex_die();
    if (opts) /* the primitive's parameters lead the tool's own */
        memcpy(opts, f->params, p->params_size);
    tex_cli_parse(&t, argc, argv, &c, opts ? opts : f->params);
    if (opts)
        memcpy(f->params, opts, p->params_size);
    if (tex_map_write_check(c.output, c.format) < 0)
        tex_die(); /* now, not after the work */
    f->seed = (uint64_t)c.seed;
    f->tile = c.tile;
    f->ids = c.ids;
    if (c.palette && c.ids)
        tex_usage_die("--palette colours the subregions; --ids writes their ids instead: "
                      "give one of them");
    if (c.win[2] > 0 && tex_field_window(f, c.win[0], c.win[1], c.win[2], c.win[3]) < 0)
        tex_die();
    if (tex_field_init(f, c.w, c.h) < 0)
        tex_die();
    if (c.palette && !(colors = region_colors(c.palette, f->nregions)))
        tex_die();
    if (colors)
        f->colors = (const float(*)[3])colors;
    if (tex_cli_takes_rows(&c) && !tex_field_whole(f)) {
        generate_bands(f, &c); /* the same pixels, a band of rows at a time */
    } else {
        if (!(m = tex_field_sample(f)))
            tex_die();
        tex_cli_write(m, &c);
        tex_map_free(m);
    }
    tex_field_free(f);
    free(colors);
    free(c.cmdline);
    return 0;
}
