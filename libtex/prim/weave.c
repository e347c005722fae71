/* weave.c - woven cloth: warp and weft threads interlaced in a plain, twill or satin weave
 * (the fabric of the thesis's Photo 6.1, and the weaving its future work asks for, 6.2)
 *
 * The map is a grid of threads: warp thread i runs down column i, weft thread j across row j,
 * and in cell (i, j) one of them lies on top as the weave says.  A thread is a cylinder of
 * its width: bright along its crown, darker at its sides, diving under the crossing thread
 * where its float ends; the thread beneath shows in the gaps beside the top one, in shadow,
 * and the gaps between threads are dark.  Yarn irregularity varies each thread's width and
 * place, and its fibres' brightness along it. */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/rng.h"
#include "prim/prim.h"

enum { PLAIN, TWILL, SATIN };
enum { COLOUR, HEIGHT };
enum { MAX_COLOURS = 64 };

struct weave_params {
    int weave, threads, shafts, floats, map;
    double width, irregularity;
    const char *warp, *weft;
};

static const struct tex_param weave_rows[] = {
    TEX_ENUM(struct weave_params, weave, 0, "plain", "plain|twill|satin",
             "the weave: plain (over one, under one), twill (diagonal ribs) or satin (long floats)"),
    TEX_INT_N("thread_count", struct weave_params, threads, 0, 24, 1, 4096, "N",
            "warp threads across the map, and weft threads down it"),
    TEX_INT(struct weave_params, shafts, 0, 0, 0, 32, "N",
            "twill, satin: threads in one repeat of the weave, at least 3 (0: 4 for a twill, 5 "
            "for a satin)"),
    TEX_INT_N("float", struct weave_params, floats, 0, 2, 1, 31, "F",
              "twill: threads a warp thread passes over before it dives (less than --shafts)"),
    TEX_REAL_N("thread_width", struct weave_params, width, 0, 0.85, 0.1, 1, "W",
               "width of a thread, a fraction of its spacing"),
    TEX_REAL(struct weave_params, irregularity, 0, 0.25, 0, 1, "R",
             "yarn irregularity: variation of each thread's width and place, and of its fibres"),
    TEX_STRING_N("warp_colours", struct weave_params, warp, 0, "#2b4a7a", "LIST",
                 "colours of the warp threads, in turn across the map: #rrggbb,..."),
    TEX_STRING_N("weft_colours", struct weave_params, weft, 0, "#d9cfb4", "LIST",
                 "colours of the weft threads, in turn down the map: #rrggbb,..."),
    TEX_ENUM(struct weave_params, map, 0, "colour", "colour|height",
             "the map: the cloth's colours, or its height (for a bump)"),
    {0}};

struct weave_state {
    int nwarp, nweft, step;
    float warp[MAX_COLOURS][3], weft[MAX_COLOURS][3];
};

/* A list of colours "#rrggbb,#rrggbb,..." into c; their count, or -1 with a usage error. */
static int colours(const struct tex_param *row, const char *list, float (*c)[3])
{
    char word[32], opt[64];
    int n = 0;
    tex_param_option(row, opt, sizeof opt);
    for (const char *s = list; *s; s += *s == ',') {
        size_t len = strcspn(s, ",");
        float rgba[4];
        if (len >= sizeof word || n == MAX_COLOURS)
            return tex_usage_error("%s: at most %d colours of the form #rrggbb (got '%s')", opt,
                                   MAX_COLOURS, list);
        memcpy(word, s, len);
        word[len] = 0;
        if (tex_parse_color(word, rgba) < 0 || word[0] != '#')
            return tex_usage_error("%s: '%s' is not a colour #rgb or #rrggbb", opt, word);
        memcpy(c[n++], rgba, sizeof c[0]);
        s += len;
    }
    return n ? n : tex_usage_error("%s: no colour given", opt);
}

static int gcd(int a, int b)
{
    while (b) {
        int t = a % b;
        a = b;
        b = t;
    }
    return a;
}

static int weave_init(struct tex_field *f)
{
    struct weave_params *p = f->params;
    struct weave_state *s = calloc(1, sizeof *s);
    if (!s)
        return tex_error("out of memory");
    f->state = s;
    if ((s->nwarp = colours(tex_param_find(weave_rows, "warp_colours"), p->warp, s->warp)) < 0 ||
        (s->nweft = colours(tex_param_find(weave_rows, "weft_colours"), p->weft, s->weft)) < 0)
        return -1;
    if (!p->shafts)
        p->shafts = p->weave == SATIN ? 5 : 4;
    if (p->shafts < 3)
        return tex_usage_error("%s must be 0 or 3..32 (got %d)",
                               TEX_OPTION(weave_rows, struct weave_params, shafts), p->shafts);
    if (p->weave == TWILL && p->floats >= p->shafts)
        return tex_usage_error("%s must be less than %s (got %d and %d)",
                               TEX_OPTION(weave_rows, struct weave_params, floats),
                               TEX_OPTION(weave_rows, struct weave_params, shafts), p->floats,
                               p->shafts);
    /* satin: each row's warp float starts a step on; a step sharing no factor with the
     * shafts, neither 1 nor shafts - 1 (those make a twill) */
    for (s->step = 2; p->weave == SATIN && s->step < p->shafts - 1; s->step++)
        if (gcd(s->step, p->shafts) == 1)
            break;
    if (p->weave == SATIN && s->step >= p->shafts - 1)
        return tex_usage_error("a satin of %d shafts has no step: use 5, 7, 8 or more",
                               p->shafts);
    /* tiling: the last thread runs on into the first, so the weave and the colours repeat a
     * whole number of times */
    int repeat = p->weave == PLAIN ? 2 : p->shafts;
    if (f->tile && (p->threads % repeat || p->threads % s->nwarp || p->threads % s->nweft))
        return tex_usage_error("%s with %s %d needs a multiple of the weave's %d threads and "
                               "of the colour lists' %d and %d",
                               TEX_FIELD_OPTION(tile),
                               TEX_OPTION(weave_rows, struct weave_params, threads), p->threads,
                               repeat, s->nwarp, s->nweft);
    f->nc = p->map == COLOUR ? 3 : 1;
    return 0;
}

static void weave_fini(struct tex_field *f)
{
    free(f->state);
    f->state = NULL;
}

/* Is warp thread i on top of weft thread j? */
static int warp_up(const struct weave_params *p, const struct weave_state *s, long i, long j)
{
    long n = p->shafts;
    switch (p->weave) {
    case TWILL: return ((i + j) % n + n) % n < p->floats;
    case SATIN: return ((i - s->step * j) % n + n) % n != 0; /* warp-faced */
    default: return ((i + j) & 1) == 0;
    }
}

/* A thread's width and centre in its cell, and its fibres' seed: from its index. */
struct thread {
    double width, centre;
    uint64_t seed;
};

static struct thread thread(const struct tex_field *f, int weft, long k)
{
    const struct weave_params *p = f->params;
    long n = p->threads, w = f->tile ? (k % n + n) % n : k;
    uint64_t h = tex_hash64(f->seed ^ tex_hash64((uint64_t)w * 2 + (uint64_t)weft));
    double r0 = (h & 0xffff) / 65536.0 - 0.5, r1 = (h >> 16 & 0xffff) / 65536.0 - 0.5;
    struct thread t;
    t.width = p->width * (1 + 0.5 * p->irregularity * r0);
    t.width = t.width > 1 ? 1 : t.width;
    t.centre = 0.5 + (1 - t.width) * p->irregularity * r1;
    t.seed = h;
    return t;
}

/* Value noise of the fibres along a thread, in [0,1]: 6 bumps per cell. */
static double fibres(uint64_t seed, double along)
{
    double x = along * 6;
    int64_t i = (int64_t)floor(x);
    double t = x - i, a = (tex_hash64(seed ^ (uint64_t)i) >> 11) * 0x1p-53,
           b = (tex_hash64(seed ^ (uint64_t)(i + 1)) >> 11) * 0x1p-53;
    t = t * t * (3 - 2 * t);
    return a + (b - a) * t;
}

/* Shade of a thread at a point: its crown across (0 at the edges, 1 on the axis) times its
 * dive where its float ends (end0, end1: it dives at the cell's start or end). */
static double shade(const struct weave_params *p, const struct thread *t, double across,
                    double along, int end0, int end1, long cell)
{
    double a = fabs(across - t->centre) / (t->width / 2), crown = sqrt(1 - a * a), dive = 1;
    if (end0 && along < 0.35)
        dive = 0.55 + 0.45 * sin(M_PI / 2 * along / 0.35);
    if (end1 && along > 0.65)
        dive = 0.55 + 0.45 * sin(M_PI / 2 * (1 - along) / 0.35);
    return crown * dive * (1 + 0.6 * p->irregularity * (fibres(t->seed, cell + along) - 0.5));
}

static void weave_point(const struct tex_field *f, double u, double v, float *out)
{
    const struct weave_params *p = f->params;
    const struct weave_state *s = f->state;
    double x = u * p->threads, y = v * p->threads;
    long i = (long)floor(x), j = (long)floor(y);
    double fx = x - i, fy = y - j, value = 0, height = 0;
    struct thread wa = thread(f, 0, i), we = thread(f, 1, j);
    int up = warp_up(p, s, i, j);
    int in_warp = fabs(fx - wa.centre) < wa.width / 2, in_weft = fabs(fy - we.centre) < we.width / 2;
    const float *c = NULL;

    if (in_warp && (up || !in_weft)) { /* the warp, along v: on top, or beside the weft */
        value = shade(p, &wa, fx, fy, up && !warp_up(p, s, i, j - 1), up && !warp_up(p, s, i, j + 1), j);
        value *= up ? 1 : 0.5;
        height = up ? 0.5 + 0.5 * value : 0.4 * value;
        c = s->warp[((i % s->nwarp) + s->nwarp) % s->nwarp];
    } else if (in_weft) { /* the weft, along u */
        value = shade(p, &we, fy, fx, !up && warp_up(p, s, i - 1, j), !up && warp_up(p, s, i + 1, j), i);
        value *= !up ? 1 : 0.5;
        height = !up ? 0.5 + 0.5 * value : 0.4 * value;
        c = s->weft[((j % s->nweft) + s->nweft) % s->nweft];
    }
    if (p->map == HEIGHT) {
        out[0] = (float)height;
        return;
    }
    for (int k = 0; k < 3; k++) /* the gaps: the shadow between threads */
        out[k] = c ? (float)(c[k] * (0.25 + 0.75 * value)) : 0.04f;
}

static void weave_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                        float *out)
{
    for (int i = 0; i < n; i++)
        weave_point(f, u[i], v[i], out + (size_t)i * f->nc);
}

const struct tex_primitive tex_prim_weave = {
    .name = "weave",
    .summary = "woven cloth: warp and weft threads in a plain, twill or satin weave",
    .flags = TEX_PRIM_2D | TEX_PRIM_TILE,
    .params_size = sizeof(struct weave_params),
    .params = weave_rows,
    .init = weave_init,
    .fini = weave_fini,
    .eval2 = weave_eval2,
};
