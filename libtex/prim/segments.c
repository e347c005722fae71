/* segments.c - randomly placed, nearly parallel line segments (thesis 4.5, Figure 4.7: the
 * roughness of the varnished table), as a map and as a solid texture
 *
 * Segments lie in the cells of a grid (squares, or cubes in space) at least half a segment
 * wide, so that a point meets only the segments of its own and the neighbouring cells.  A
 * cell holds a Poisson number of them, from a generator seeded by the cell and the seed:
 * centre anywhere in the cell, direction the angle give or take the spread (in space also
 * tilted out of the uv plane by as much), length give or take its spread.  The value at a
 * point is (1 - (2 r / width)^2)^2 for the nearest segment at distance r under half the
 * width, else 0: a groove with a rounded profile and rounded ends, 1 on its axis. */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/rng.h"
#include "prim/prim.h"

enum { SEG_LAMBDA = 256 }; /* the most segments a cell may hold on average */

struct segments_params {
    int count;
    double angle, spread, length, length_spread, width;
};

static const struct tex_param segments_rows[] = {
    TEX_INT_N("segments", struct segments_params, count, 0, 300, 1, 1000000, "N",
              "mean number of segments per unit square of the map (per unit cube in space)"),
    TEX_REAL(struct segments_params, angle, 'a', 0, -360, 360, "DEG",
             "direction of the segments, degrees counter-clockwise from +u"),
    TEX_REAL_N("angle_spread", struct segments_params, spread, 0, 4, 0, 90, "DEG",
               "each segment's direction varies by up to this many degrees either way"),
    TEX_REAL(struct segments_params, length, 0, 0.2, 0.001, 1, "L",
             "mean length of a segment, in map widths"),
    TEX_REAL_N("length_spread", struct segments_params, length_spread, 0, 0.5, 0, 0.99, "F",
               "each length varies by up to this fraction of L either way"),
    TEX_REAL(struct segments_params, width, 0, 0.004, 0.0001, 0.2, "W",
             "width of a segment's groove, in map widths"),
    {0}};

struct segments_state {
    int cells;     /* the grid's cells across the unit square or cube */
    double lambda; /* mean segments per cell */
    int most;      /* segments a cell may hold: far in the Poisson tail of lambda */
};

static int segments_init(struct tex_field *f)
{
    const struct segments_params *p = f->params;
    struct segments_state *s = calloc(1, sizeof *s);
    /* a segment reaches half its longest length plus half its width from its centre */
    double reach = p->length * (1 + p->length_spread) / 2 + p->width / 2;
    double g = floor(1 / reach);
    if (!s)
        return tex_error("out of memory");
    s->cells = g < 1 ? 1 : g > 4096 ? 4096 : (int)g;
    s->lambda = p->count / ((double)s->cells * s->cells);
    s->most = (int)(s->lambda + 10 * sqrt(s->lambda) + 16);
    f->state = s;
    if (s->lambda > SEG_LAMBDA) {
        char n[64], l[64];
        return tex_usage_error("%s %d is too many for segments %g long: at most %d at this %s",
                               tex_rows_option(segments_rows,
                                               offsetof(struct segments_params, count), n, 64),
                               p->count, p->length, SEG_LAMBDA * s->cells * s->cells,
                               tex_rows_option(segments_rows,
                                               offsetof(struct segments_params, length), l, 64));
    }
    return 0;
}

static void segments_fini(struct tex_field *f)
{
    free(f->state);
    f->state = NULL;
}

/* A segment: centre c, unit direction d, half-length h, in map units. */
struct seg {
    double c[3], d[3], h;
};
/* One cell's segments. */
struct seg_cell {
    int64_t key[3];
    int n; /* -1: not made yet */
    struct seg *s;
};

/* The segments of cell k (dims coordinates), wrapped by the grid when the field tiles. */
static void make_cell(const struct tex_field *f, int dims, const int64_t k[3], struct seg_cell *sc)
{
    const struct segments_params *p = f->params;
    const struct segments_state *s = f->state;
    int64_t n = s->cells, w[3] = {0, 0, 0};
    double g = 1.0 / n, lambda = dims == 3 ? s->lambda / n : s->lambda, e = exp(-lambda), t = 1;
    tex_rng r;

    for (int a = 0; a < dims; a++)
        w[a] = f->tile ? ((k[a] % n) + n) % n : k[a];
    tex_rng_seed(&r, tex_hash64(f->seed ^ tex_hash64((uint64_t)w[0] * 0x9e3779b1u ^
                                                      tex_hash64((uint64_t)w[1] ^
                                                                 tex_hash64((uint64_t)w[2])))));
    sc->n = 0;
    while ((t *= tex_rng_uniform(&r)) > e && sc->n < s->most) /* Poisson, Knuth's way */
        sc->n++;
    for (int i = 0; i < sc->n; i++) {
        struct seg *q = &sc->s[i];
        double a = (p->angle + p->spread * (2 * tex_rng_uniform(&r) - 1)) * (M_PI / 180);
        double tilt = dims == 3 ? p->spread * (2 * tex_rng_uniform(&r) - 1) * (M_PI / 180) : 0;
        for (int ax = 0; ax < 3; ax++)
            q->c[ax] = ax < dims ? (k[ax] + tex_rng_uniform(&r)) * g : 0;
        q->d[0] = cos(a) * cos(tilt);
        q->d[1] = sin(a) * cos(tilt);
        q->d[2] = sin(tilt);
        q->h = p->length * (1 + p->length_spread * (2 * tex_rng_uniform(&r) - 1)) / 2;
    }
    memcpy(sc->key, k, sizeof sc->key);
}

enum { SEG_CACHE = 32 };

/* The value at x (dims coordinates, y up): the deepest groove of the neighbouring cells'. */
static float segments_point(const struct tex_field *f, struct seg_cell *cache, int dims,
                            const double *x)
{
    const struct segments_params *p = f->params;
    const struct segments_state *s = f->state;
    double hw = p->width / 2, best = hw * hw;
    int64_t i[3] = {0, 0, 0};
    for (int a = 0; a < dims; a++)
        i[a] = (int64_t)floor(x[a] * s->cells);
    for (int dk = dims == 3 ? -1 : 0; dk <= (dims == 3 ? 1 : 0); dk++)
        for (int dj = -1; dj <= 1; dj++)
            for (int di = -1; di <= 1; di++) {
                int64_t k[3] = {i[0] + di, i[1] + dj, i[2] + dk};
                unsigned e = (unsigned)((uint64_t)k[0] * 0x9e3779b1u ^ (uint64_t)k[1] * 0x85ebca6bu ^
                                        (uint64_t)k[2] * 0xc2b2ae35u) % SEG_CACHE;
                struct seg_cell *sc = &cache[e];
                if (sc->n < 0 || memcmp(sc->key, k, sizeof k))
                    make_cell(f, dims, k, sc);
                for (const struct seg *g = sc->s; g < sc->s + sc->n; g++) {
                    double q[3] = {x[0] - g->c[0], x[1] - g->c[1], dims == 3 ? x[2] - g->c[2] : 0};
                    double t = q[0] * g->d[0] + q[1] * g->d[1] + q[2] * g->d[2];
                    t = t < -g->h ? -g->h : t > g->h ? g->h : t;
                    double r[3] = {q[0] - t * g->d[0], q[1] - t * g->d[1], q[2] - t * g->d[2]};
                    double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
                    best = r2 < best ? r2 : best;
                }
            }
    double u = best / (hw * hw);
    return (float)((1 - u) * (1 - u));
}

/* The cache's cells and, after them, room for each one's segments. */
static struct seg_cell *new_cache(const struct tex_field *f)
{
    const struct segments_state *s = f->state;
    struct seg_cell *c = malloc(SEG_CACHE * (sizeof *c + s->most * sizeof(struct seg)));
    if (!c)
        return NULL;
    struct seg *room = (struct seg *)(c + SEG_CACHE);
    for (int i = 0; i < SEG_CACHE; i++) {
        c[i].n = -1;
        c[i].s = room + (size_t)i * s->most;
    }
    return c;
}

/* On a map, y = -v: the angle turns counter-clockwise on the screen, as t_stripe's does. */
static void segments_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                           float *out)
{
    struct seg_cell *cache = new_cache(f);
    for (int i = 0; i < n; i++)
        out[i] = cache ? segments_point(f, cache, 2, (const double[2]){u[i], -v[i]}) : 0;
    free(cache);
}

static void segments_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                           const double *w, float *out)
{
    struct seg_cell *cache = new_cache(f);
    for (int i = 0; i < n; i++)
        out[i] = cache ? segments_point(f, cache, 3, (const double[3]){u[i], v[i], w[i]}) : 0;
    free(cache);
}

const struct tex_primitive tex_prim_segments = {
    .name = "segments",
    .summary = "randomly placed, nearly parallel line segments (the thesis's wood roughness)",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct segments_params),
    .params = segments_rows,
    .init = segments_init,
    .fini = segments_fini,
    .eval2 = segments_eval2,
    .eval3 = segments_eval3,
};
