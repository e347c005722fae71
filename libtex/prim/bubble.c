/* bubble.c - the bubble primitive: distances to the nearest random points (thesis 5.2.2.5) */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "base/error.h"
#include "base/progress.h"
#include "base/rng.h"
#include "prim/cellular.h"
#include "prim/cellular_impl.h"
#include "prim/prim.h"

enum { OUT_BUBBLE, OUT_F1, OUT_F2, OUT_F2F1, OUT_CELL };

struct bubble_params {
    int count;
    const char *points;
    int value;
    const char *metric;
    int distribution;
    int clusters;
    int dimension;
    double z;
    double size_spread;
    double axis_spread;
    int search;
};

#define BUBBLE_COUNT 64
#define BUBBLE_SLICE 0.5
static const struct tex_param bubble_rows[] = {
    TEX_INT(struct bubble_params, count, 'c', BUBBLE_COUNT, 1, TEX_POINTS_MAX, "N",
            "number of random points (bubbles)", .old = "-n"),
    TEX_STRING(struct bubble_params, points, 0, NULL, "FILE",
               "read the points from FILE instead of random ones (textura-points(5))"),
    TEX_ENUM(struct bubble_params, value, 0, "bubble", "bubble|f1|f2|f2-f1|cell",
             "what to write: bubble shading, distances F1, F2, F2-F1, or a random value per cell"),
    TEX_STRING(struct bubble_params, metric, 0, "euclid", "NAME",
               "distance: euclid|manhattan|chebyshev|minkowski:P with P in 1.." TEX_XSTR(
                   TEX_METRIC_P_MAX)),
    TEX_ENUM(struct bubble_params, distribution, 0, "uniform", "uniform|poisson|cluster",
             "how the random points are spread"),
    TEX_INT(struct bubble_params, clusters, 0, 0, 0, 1000000, "N",
            "clusters of the cluster distribution (0: about sqrt(N))"),
    TEX_ENUM(struct bubble_params, dimension, 0, "2", "2|3",
             "points in the plane, or in space for solid textures"),
    TEX_REAL_N("slice", struct bubble_params, z, 0, BUBBLE_SLICE, -1e6, 1e6, "Z",
               "the slice of the map through 3D points", .alias = "z"),
    TEX_REAL(struct bubble_params, size_spread, 0, 0, 0, 0.95, "S",
             "random bubble sizes: each radius is 1+S(2u-1), u uniform"),
    TEX_REAL(struct bubble_params, axis_spread, 0, 0, 0, 0.95, "E",
             "random ellipses (ellipsoids): each axis of a bubble scaled by 1+E(2u-1)"),
    TEX_ENUM(struct bubble_params, search, 0, "auto", "auto|grid|kdtree|brute",
             "nearest-point search: all give the same map; auto picks grid or FLANN's kd-tree"),
    {0}};

struct bubble_state {
    tex_cellular *c;
    double unit;  /* mean spacing of the points, N^(-1/dim) */
    uint64_t key; /* for the cell values */
    int dim;
};

static void bubble_fini(struct tex_field *f)
{
    struct bubble_state *s = f->state;
    if (s)
        tex_cellular_free(s->c);
    free(s);
    f->state = NULL;
}

/* Messages name a parameter by its row (prim.h) */
#define OPTION(field) TEX_OPTION(bubble_rows, struct bubble_params, field)
/* Dart throwing's most points (it slows as the discs fill the square) */
#define POISSON_MAX 2000000

static int bubble_init(struct tex_field *f)
{
    const struct bubble_params *p = f->params;
    struct tex_cellular_opts o = {TEX_METRIC_EUCLID, 2, f->tile, (enum tex_search)p->search,
                                  f->w ? (long)f->w * f->h : f->queries};
    struct bubble_state *s;
    tex_points ps;
    int dim = p->dimension + 2;

    if (tex_metric_parse_as(p->metric, OPTION(metric), &o.metric, &o.p) < 0)
        return -1;
    /* Options of another mode, told by values other than the defaults (the rows
     * serve scenes too, where nothing records what was given). */
    if (p->clusters && p->distribution != TEX_POINTS_CLUSTER)
        return tex_usage_error("%s applies to %s cluster only", OPTION(clusters),
                               OPTION(distribution));
    if (p->z != BUBBLE_SLICE && dim == 2)
        return tex_usage_error("%s applies to %s 3 only", OPTION(z), OPTION(dimension));
    if (p->points && (p->count != BUBBLE_COUNT || p->distribution || p->clusters))
        return tex_usage_error("%s, %s and %s apply to random points, not to %s", OPTION(count),
                               OPTION(distribution), OPTION(clusters), OPTION(points));
    tex_progress_stage(0.3, 2); /* the points, then their search structure */
    if (p->points) {
        if (tex_points_read(&ps, p->points, dim) < 0)
            return -1;
    } else {
        if (p->distribution == TEX_POINTS_POISSON && p->count > POISSON_MAX)
            return tex_usage_error("%s poisson takes at most %d points (got %d)",
                                   OPTION(distribution), POISSON_MAX, p->count);
        if (tex_points_random(&ps, dim, p->count, (enum tex_pointdist)p->distribution,
                              p->clusters, f->seed, f->tile) < 0)
            return -1;
    }
    tex_progress_add(1);
    if (tex_points_vary(&ps, p->size_spread, p->axis_spread, f->seed) < 0) {
        tex_points_free(&ps);
        return -1;
    }
    if (!(s = calloc(1, sizeof *s))) {
        tex_points_free(&ps);
        return tex_error("out of memory");
    }
    s->dim = dim;
    s->unit = pow((double)ps.n, -1.0 / dim);
    s->key = tex_hash64(f->seed ^ 0x63656c6c73ULL);
    tex_progress_add(1);
    tex_progress_stage(0.3, 1);
    s->c = tex_cellular_new(&ps, &o); /* its candidate lists, if built, are a stage of their own */
    tex_progress_add(1);
    tex_points_free(&ps);
    f->state = s;
    if (!s->c) {
        bubble_fini(f);
        return -1;
    }
    return 0;
}

static inline float unit_clamp(double x)
{
    return (float)(x < 0 ? 0 : x < 1 ? x : 1);
}

/* Shade n query points (q: n*dim). */
static void bubble_shade(const struct tex_field *f, int n, const double *q, float *out)
{
    enum { CHUNK = 256 };
    const struct bubble_params *p = f->params;
    const struct bubble_state *s = f->state;

    for (int i0 = 0; i0 < n; i0 += CHUNK) {
        int m = n - i0 < CHUNK ? n - i0 : CHUNK;
        double f1[CHUNK], f2[CHUNK];
        long id[CHUNK];
        /* F1 and the cell need no F2: the queries take a shorter path. */
        int need_f2 = p->value != OUT_F1 && p->value != OUT_CELL;
        tex_cellular_query(s->c, m, q + (size_t)i0 * s->dim, f1, need_f2 ? f2 : NULL,
                           p->value == OUT_CELL ? id : NULL);
        for (int i = 0; i < m; i++) {
            double a = f1[i], b = f2[i], t;
            float *o = out + i0 + i;
            switch (p->value) {
            case OUT_F1:
                *o = unit_clamp(a / (1.5 * s->unit));
                break;
            case OUT_F2:
                *o = unit_clamp(b / (2 * s->unit));
                break;
            case OUT_F2F1:
                *o = unit_clamp((b - a) / s->unit);
                break;
            case OUT_CELL:
                *o = (float)((tex_hash64((uint64_t)id[i] ^ s->key) >> 40) * 0x1p-24);
                break;
            default:
                /* t: 0 at the point, 1 where F1 = F2 (the cell border); a
                 * hemisphere's height over t reads as a lit bubble. */
                t = a + b > 0 ? 2 * a / (a + b) : 0;
                *o = unit_clamp(sqrt(1 - t * t > 0 ? 1 - t * t : 0));
                break;
            }
        }
    }
}

static void bubble_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                         const double *w, float *out)
{
    const struct bubble_state *s = f->state;
    double q[256 * 3];

    for (int i0 = 0; i0 < n; i0 += 256) {
        int m = n - i0 < 256 ? n - i0 : 256;
        for (int i = 0; i < m; i++) {
            q[i * s->dim] = u[i0 + i];
            q[i * s->dim + 1] = v[i0 + i];
            if (s->dim == 3)
                q[i * 3 + 2] = w ? w[i0 + i] : ((const struct bubble_params *)f->params)->z;
        }
        bubble_shade(f, m, q, out + i0);
    }
}

static void bubble_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                         float *out)
{
    bubble_eval3(f, n, u, v, NULL, out);
}

static void bubble_row(const struct tex_field *f, int y, float *out)
{
    double u[256], v[256];

    for (int x0 = 0; x0 < f->w; x0 += 256) {
        int m = f->w - x0 < 256 ? f->w - x0 : 256;
        for (int i = 0; i < m; i++) {
            u[i] = (x0 + i + 0.5) / f->w;
            v[i] = (y + 0.5) / f->h;
        }
        bubble_eval3(f, m, u, v, NULL, out + x0);
    }
}

const struct tex_primitive tex_prim_bubble = {
    .name = "bubble",
    .summary = "bubbles and Voronoi cells around random points (the thesis's t.bubble)",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct bubble_params),
    .params = bubble_rows,
    .init = bubble_init,
    .fini = bubble_fini,
    .eval2 = bubble_eval2,
    .eval3 = bubble_eval3,
    .row = bubble_row,
};
