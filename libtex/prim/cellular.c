/* cellular.c - point sets, nearest-point queries and the bubble primitive */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "prim/cellular.h"
#include "base/error.h"
#include "base/kdtree.h"
#include "base/progress.h"
#include "prim/prim.h"
#include "base/rng.h"
#include "base/x86/simd_x86.h"

/* p grown to n elements of size bytes, or p itself with *ok cleared when that
 * fails (or an earlier call failed): parallel arrays grow together and the
 * caller reports once. */
static void *grown(void *p, size_t n, size_t size, int *ok)
{
    void *q = *ok ? realloc(p, n * size) : NULL;
    if (!q) {
        *ok = 0;
        return p;
    }
    return q;
}

#if defined(TEX_X86) && defined(__x86_64__)
#define HAVE_AVX2_KERNEL 1 /* the AVX2 kernel; SSE2, x86-64's baseline, elsewhere in this file */
#endif

/* ---- point sets ---- */

static int points_alloc(tex_points *ps, int dim, long n)
{
    ps->dim = dim;
    ps->n = n;
    ps->axes = NULL;
    if (!(ps->x = malloc((size_t)n * dim * sizeof *ps->x)))
        return tex_error("out of memory for %ld points", n);
    return 0;
}

void tex_points_free(tex_points *ps)
{
    free(ps->x);
    free(ps->axes);
    ps->x = ps->axes = NULL;
    ps->n = 0;
}

static inline double wrap1(double x)
{
    x -= floor(x);
    return x < 1.0 ? x : 0.0; /* -tiny - floor(-tiny) rounds to 1 */
}

void tex_points_wrap(tex_points *ps)
{
    for (long i = 0; i < ps->n * ps->dim; i++)
        ps->x[i] = wrap1(ps->x[i]);
}

/* Dart throwing on a background grid whose cells (side <= r/sqrt(dim))
 * hold at most one point each. */
static int poisson(tex_points *ps, tex_rng *rng, int tile)
{
    int dim = ps->dim;
    long n = ps->n, placed = 0;
    double cover = dim == 2 ? 0.35 : 0.2; /* dart throwing saturates at 0.547 and 0.38 */
    double r = dim == 2 ? 2 * sqrt(cover / (M_PI * n)) : 2 * cbrt(cover * 3 / (4 * M_PI * n));
    int g = (int)ceil(sqrt((double)dim) / r), reach = 2;
    long cells = (long)g * g * (dim == 3 ? g : 1);
    long *owner = malloc(cells * sizeof *owner);
    long tries = 0, budget = 1000 * n + 100000;

    if (!owner)
        return tex_error("out of memory for the Poisson-disk grid");
    for (long i = 0; i < cells; i++)
        owner[i] = -1;
    while (placed < n && tries++ < budget) {
        double p[3] = {0, 0, 0};
        int k[3] = {0, 0, 0}, ok = 1;
        for (int j = 0; j < dim; j++) {
            p[j] = tex_rng_uniform(rng);
            k[j] = (int)(p[j] * g);
            if (k[j] >= g)
                k[j] = g - 1;
        }
        for (int dz = dim == 3 ? -reach : 0; ok && dz <= (dim == 3 ? reach : 0); dz++)
            for (int dy = -reach; ok && dy <= reach; dy++)
                for (int dx = -reach; ok && dx <= reach; dx++) {
                    int o[3] = {dx, dy, dz}, kk[3] = {0, 0, 0};
                    long cell = 0;
                    for (int j = 0; j < dim; j++) {
                        kk[j] = k[j] + o[j];
                        if (tile)
                            kk[j] = (kk[j] % g + g) % g;
                        else if (kk[j] < 0 || kk[j] >= g)
                            goto next;
                    }
                    cell = kk[0] + (long)g * (kk[1] + (long)g * kk[2]);
                    if (owner[cell] >= 0) {
                        const double *q = ps->x + owner[cell] * dim;
                        double d2 = 0;
                        for (int j = 0; j < dim; j++) {
                            double d = fabs(p[j] - q[j]);
                            if (tile && d > 0.5)
                                d = 1 - d;
                            d2 += d * d;
                        }
                        if (d2 < r * r)
                            ok = 0;
                    }
                next:;
                }
        if (ok) {
            owner[k[0] + (long)g * (k[1] + (long)g * k[2])] = placed;
            memcpy(ps->x + placed * dim, p, dim * sizeof *p);
            placed++;
        }
    }
    free(owner);
    if (placed < n)
        return tex_error("Poisson-disk sampling placed only %ld of %ld points", placed, n);
    return 0;
}

int tex_points_random(tex_points *ps, int dim, long n, enum tex_pointdist dist, int clusters,
                      uint64_t seed, int tile)
{
    tex_rng rng;

    memset(ps, 0, sizeof *ps);
    if (dim != 2 && dim != 3)
        return tex_usage_error("points must have 2 or 3 dimensions (got %d)", dim);
    if (n < 1 || n > TEX_POINTS_MAX)
        return tex_usage_error("the number of points must be 1..%d (got %ld)", TEX_POINTS_MAX, n);
    if (points_alloc(ps, dim, n) < 0)
        return -1;
    tex_rng_seed(&rng, seed);
    if (dist == TEX_POINTS_POISSON) {
        if (poisson(ps, &rng, tile) < 0) {
            tex_points_free(ps);
            return -1;
        }
    } else if (dist == TEX_POINTS_CLUSTER) {
        long k = clusters > 0 ? clusters : lround(sqrt((double)n));
        double sigma = 0.25 / pow((double)k, 1.0 / dim), *parent;
        if (k < 1)
            k = 1;
        if (!(parent = malloc((size_t)k * dim * sizeof *parent))) {
            tex_points_free(ps);
            return tex_error("out of memory");
        }
        for (long i = 0; i < k * dim; i++)
            parent[i] = tex_rng_uniform(&rng);
        for (long i = 0; i < n; i++) {
            const double *c = parent + (long)tex_rng_below(&rng, (uint32_t)k) * dim;
            for (int j = 0; j < dim; j++)
                ps->x[i * dim + j] = wrap1(c[j] + sigma * tex_rng_gauss(&rng));
        }
        free(parent);
    } else {
        for (long i = 0; i < n * dim; i++)
            ps->x[i] = tex_rng_uniform(&rng);
    }
    return 0;
}

int tex_points_vary(tex_points *ps, double size, double shape, uint64_t seed)
{
    tex_rng rng;
    int dim = ps->dim;

    if (!(size >= 0 && size <= 0.95 && shape >= 0 && shape <= 0.95))
        return tex_usage_error("size and shape spreads must be 0..0.95");
    if (size == 0 && shape == 0)
        return 0;
    if (!ps->axes) {
        if (!(ps->axes = malloc((size_t)ps->n * dim * sizeof *ps->axes)))
            return tex_error("out of memory");
        for (long i = 0; i < ps->n * dim; i++)
            ps->axes[i] = 1;
    }
    /* A stream of its own, so that the positions do not move with the spreads. */
    tex_rng_seed(&rng, tex_hash64(seed ^ 0x6275626231657331ULL));
    for (long i = 0; i < ps->n; i++) {
        double s = 1 + size * (2 * tex_rng_uniform(&rng) - 1);
        for (int j = 0; j < dim; j++)
            ps->axes[i * dim + j] *= s * (1 + shape * (2 * tex_rng_uniform(&rng) - 1));
    }
    return 0;
}

/* The numbers of one line of a point file into v, its comment cut: x y [z] and an optional
 * radius w.  Returns how many, 0 for a blank line, or -1 with the error recorded. */
static int point_line(char *line, double *v, int dim, const char *path, long lineno)
{
    int cols = 0;
    char *s = line, *hash = strchr(line, '#');

    if (hash)
        *hash = '\0';
    for (;;) {
        char *end;
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
            s++;
        if (!*s)
            break;
        if (cols == dim + 1)
            return tex_error("%s:%ld: too many columns (want %s)", path, lineno,
                             dim == 2 ? "x y [w]" : "x y z [w]");
        errno = 0;
        v[cols] = strtod(s, &end);
        if (end == s || (*end && !strchr(" \t\r\n", *end))) {
            int len = (int)strcspn(s, " \t\r\n");
            return tex_error("%s:%ld: not a number: '%.*s'", path, lineno, len < 20 ? len : 20,
                             s);
        }
        if (!isfinite(v[cols]))
            return tex_error("%s:%ld: not a finite number: '%.*s'", path, lineno,
                             (int)(end - s), s);
        cols++;
        s = end;
    }
    if (cols == 0)
        return 0;
    if (cols < dim)
        return tex_error("%s:%ld: %d column%s, want %s", path, lineno, cols,
                         cols == 1 ? "" : "s", dim == 2 ? "x y [w]" : "x y z [w]");
    if (cols == dim + 1 && !(v[dim] > 0))
        return tex_error("%s:%ld: the radius must be > 0 (got %g)", path, lineno, v[dim]);
    return cols;
}

/* Store point n (cols numbers in v) in ps, which has room for *alloc.  The axes start
 * with the first radius, at 1 for the points before it. */
static int add_point(tex_points *ps, const double *v, int cols, long n, size_t *alloc,
                     const char *path, long lineno)
{
    int dim = ps->dim;

    if (n == TEX_POINTS_MAX)
        return tex_error("%s:%ld: more than %d points", path, lineno, TEX_POINTS_MAX);
    if ((size_t)n == *alloc) {
        size_t na = *alloc ? 2 * *alloc : 1024;
        int ok = 1;
        ps->x = grown(ps->x, na * dim, sizeof *ps->x, &ok);
        if (ps->axes)
            ps->axes = grown(ps->axes, na * dim, sizeof *ps->axes, &ok);
        if (!ok)
            return tex_error("out of memory reading %s", path);
        *alloc = na;
    }
    if (cols == dim + 1 && !ps->axes) {
        if (!(ps->axes = malloc(*alloc * dim * sizeof *ps->axes)))
            return tex_error("out of memory reading %s", path);
        for (long i = 0; i < n * dim; i++)
            ps->axes[i] = 1;
    }
    for (int j = 0; j < dim; j++) {
        ps->x[n * dim + j] = v[j];
        if (ps->axes)
            ps->axes[n * dim + j] = cols == dim + 1 ? v[dim] : 1;
    }
    return 0;
}

int tex_points_read(tex_points *ps, const char *path, int dim)
{
    FILE *fp;
    char *line = NULL;
    size_t cap = 0, alloc = 0;
    long lineno = 0, n = 0;
    int ret = -1;

    memset(ps, 0, sizeof *ps);
    ps->dim = dim;
    if (!(fp = fopen(path, "r")))
        return tex_error("%s: %s", path, strerror(errno));
    while (getline(&line, &cap, fp) >= 0) {
        double v[5];
        int cols = point_line(line, v, dim, path, ++lineno);
        if (cols < 0)
            goto out;
        if (cols == 0)
            continue;
        if (add_point(ps, v, cols, n, &alloc, path, lineno) < 0)
            goto out;
        n++;
    }
    if (ferror(fp)) {
        tex_error("%s: %s", path, strerror(errno));
        goto out;
    }
    if (n == 0) {
        tex_error("%s:%ld: no points in the file", path, lineno);
        goto out;
    }
    ps->n = n;
    ret = 0;
out:
    free(line);
    fclose(fp);
    if (ret < 0)
        tex_points_free(ps);
    return ret;
}

int tex_metric_parse(const char *text, enum tex_metric *m, double *p)
{
    *p = 2;
    if (strcmp(text, "euclid") == 0)
        *m = TEX_METRIC_EUCLID;
    else if (strcmp(text, "manhattan") == 0)
        *m = TEX_METRIC_MANHATTAN, *p = 1;
    else if (strcmp(text, "chebyshev") == 0)
        *m = TEX_METRIC_CHEBYSHEV, *p = INFINITY;
    else if (strncmp(text, "minkowski:", 10) == 0) {
        char *end;
        double v = strtod(text + 10, &end);
        if (end == text + 10 || *end || !(v >= 1 && v <= 64))
            return tex_usage_error("--metric minkowski:P needs P in 1..64 (got '%s')", text);
        *m = TEX_METRIC_MINKOWSKI;
        *p = v;
    } else
        return tex_usage_error(
            "--metric must be euclid|manhattan|chebyshev|minkowski:P (got '%s')", text);
    return 0;
}

/* ---- nearest-point queries ---- */

/* A bucket NEAR_R or fewer away from a query's on every axis (offset o), and
 * stop: F2 (accumulated) below it ends the search, the least distance
 * between a point of the query's bucket and a point of this one or of any
 * later in the table (grid_near_build). */
#define NEAR_R 2
struct near_bucket {
    double stop;
    signed char o[3];
};

struct tex_cellular {
    int dim, tile;
    long n;
    enum tex_metric metric;
    double p, rmax;
    enum tex_search search;
    double *x, *ia; /* coordinates and inverse radii (NULL: all 1) */
    /* grid: points in bucket order */
    int g;
    long *start, *gid;
    double *gx, *gia, gfac;
    struct near_bucket *near; /* the buckets around a query's, nearest first */
    int nnear;
    /* 2D Euclidean without radii: per bucket, every point that can be one of
     * the two nearest to a query inside it */
    int cgx, cgy;
    long *cstart;
    double *cx, *cy;
    long *cid;
    int avx2; /* the CPU runs the AVX2 kernel */
    /* kd-tree over the points (and their periodic images within margin) */
    tex_kdtree *index;
    double *rep, margin, kfac, lip, amin;
    long *repid;
    unsigned char *repshift;
    long nrep;
    /* adaptive candidate tree over the unit square: top grid at x at, per
     * node its first child (-1 leaf, -2 left to kdtree_query) and leaf
     * list; list entries as x, y and point ids */
    int at, *achild, *alen;
    long *astart, *aid;
    double *ax, *ay;
};

/* The "accumulated" distance: squared for L2, the p-th power for Lp, so that
 * comparisons need no root.  Every search method calls this one function
 * for its final candidates, which keeps them bit-identical. */
static inline __attribute__((always_inline)) double
acc_point_m(const struct tex_cellular *c, enum tex_metric metric, int dim, const double *q,
            const double *p, const double *ia, const double *s)
{
    double a = 0;
#pragma GCC unroll 3
    for (int j = 0; j < dim; j++) {
        double d = q[j] - (p[j] + s[j]);
        if (ia)
            d *= ia[j];
        d = fabs(d);
        switch (metric) {
        case TEX_METRIC_EUCLID:
            a += d * d;
            break;
        case TEX_METRIC_MANHATTAN:
            a += d;
            break;
        case TEX_METRIC_CHEBYSHEV:
            a = d > a ? d : a;
            break;
        case TEX_METRIC_MINKOWSKI:
            a += pow(d, c->p);
            break;
        }
    }
    return a;
}

static inline double acc_point(const struct tex_cellular *c, const double *q, const double *p,
                               const double *ia, const double *s)
{
    return acc_point_m(c, c->metric, c->dim, q, p, ia, s);
}

static inline double acc_finish(const struct tex_cellular *c, double a)
{
    switch (c->metric) {
    case TEX_METRIC_EUCLID:
        return sqrt(a);
    case TEX_METRIC_MINKOWSKI:
        return pow(a, 1 / c->p);
    default:
        return a;
    }
}

static inline double acc_of(const struct tex_cellular *c, double d)
{
    switch (c->metric) {
    case TEX_METRIC_EUCLID:
        return d * d;
    case TEX_METRIC_MINKOWSKI:
        return pow(d, c->p);
    default:
        return d;
    }
}

struct best {
    double a1, a2;
    long i1;
};

static inline void best_add(struct best *b, double a, long i)
{
    if (a < b->a1 || (a == b->a1 && i < b->i1)) {
        b->a2 = b->a1;
        b->a1 = a;
        b->i1 = i;
    } else if (a < b->a2) {
        b->a2 = a;
    }
}

static inline void best_init(struct best *b)
{
    b->a1 = b->a2 = INFINITY;
    b->i1 = -1;
}

/* Shift number k (0 .. 3^dim-1) as a vector of -1, 0, 1. */
static inline void shift_of(int k, int dim, double *s)
{
    for (int j = 0; j < dim; j++, k /= 3)
        s[j] = k % 3 - 1;
    for (int j = dim; j < 3; j++)
        s[j] = 0;
}

static void brute1(const struct tex_cellular *c, const double *q, struct best *b)
{
    int dim = c->dim, nshift = c->tile ? (dim == 2 ? 9 : 27) : 1;
    double zero[3] = {0, 0, 0}, s[3];

    best_init(b);
    for (int k = 0; k < nshift; k++) {
        if (c->tile)
            shift_of(k, dim, s);
        for (long i = 0; i < c->n; i++)
            best_add(b, acc_point(c, q, c->x + i * dim, c->ia ? c->ia + i * dim : NULL,
                                  c->tile ? s : zero),
                     i);
    }
}

static inline int cell_of(double x, int g)
{
    double t = x * g;
    if (!(t >= 0))
        return 0;
    return t >= g ? g - 1 : (int)t;
}

/* Points per bucket on average.  Small buckets keep the candidate lists
 * short; an even set leaves about exp(-GRID_FILL) of them empty. */
#ifndef GRID_FILL
#define GRID_FILL 0.25
#endif
#ifndef GRID_FILL3
#define GRID_FILL3 2
#endif

/* The squared least distance, in buckets, between points of two buckets o apart */
static int near_lb(const signed char *o)
{
    int l = 0;
    for (int j = 0; j < 3; j++) {
        int a = abs(o[j]) - 1;
        l += a > 0 ? a * a : 0;
    }
    return l;
}

static int near_cmp(const void *x, const void *y)
{
    const struct near_bucket *a = x, *b = y;
    int la = near_lb(a->o), lb = near_lb(b->o);
    return la != lb ? (la > lb) - (la < lb) : memcmp(a->o, b->o, sizeof a->o);
}

/* c->near: the buckets up to NEAR_R away, by their least distance.  Their
 * Euclidean distance bounds the metric's: from below by itself for L2 and
 * L1, by itself over sqrt(dim) for the others (every Lp is at least
 * L-infinity). */
static int grid_near_build(struct tex_cellular *c)
{
    int dim = c->dim, side = 2 * NEAR_R + 1, n = dim == 3 ? side * side * side : side * side;
    double f = c->metric == TEX_METRIC_EUCLID || c->metric == TEX_METRIC_MANHATTAN ? 1
                                                                                   : 1 / sqrt(dim);
    if (!(c->near = malloc(n * sizeof *c->near)))
        return tex_error("out of memory for the bucket grid");
    c->nnear = n;
    for (int i = 0; i < n; i++) {
        struct near_bucket *e = &c->near[i];
        e->o[0] = (signed char)(i % side - NEAR_R);
        e->o[1] = (signed char)(i / side % side - NEAR_R);
        e->o[2] = (signed char)(dim == 3 ? i / (side * side) - NEAR_R : 0);
    }
    qsort(c->near, n, sizeof *c->near, near_cmp);
    for (int i = 0; i < n; i++) {
        double d = (sqrt(near_lb(c->near[i].o)) / c->g - 1e-14) * f * c->gfac;
        c->near[i].stop = d > 0 ? acc_of(c, d) : -INFINITY;
    }
    return 0;
}

static int grid_build(struct tex_cellular *c)
{
    int dim = c->dim;
    double want = c->n / (dim == 3 ? GRID_FILL3 : GRID_FILL);
    long cells, *fill;
    int g = (int)floor(pow(want, 1.0 / dim));

    g = g < 1 ? 1 : g;
    while (dim == 2 ? (double)g * g > 1 << 24 : (double)g * g * g > 1 << 24)
        g--;
    c->g = g;
    cells = dim == 2 ? (long)g * g : (long)g * g * g;
    c->start = calloc(cells + 1, sizeof *c->start);
    fill = calloc(cells, sizeof *fill);
    c->gid = malloc(c->n * sizeof *c->gid);
    c->gx = malloc(c->n * dim * sizeof *c->gx);
    if (c->ia)
        c->gia = malloc(c->n * dim * sizeof *c->gia);
    if (!c->start || !fill || !c->gid || !c->gx || (c->ia && !c->gia)) {
        free(fill);
        return tex_error("out of memory for the bucket grid");
    }
    for (long i = 0; i < c->n; i++) {
        const double *p = c->x + i * dim;
        long k = cell_of(p[0], g) + (long)g * (cell_of(p[1], g) + (dim == 3 ? (long)g * cell_of(p[2], g) : 0));
        fill[k]++;
    }
    for (long k = 0; k < cells; k++)
        c->start[k + 1] = c->start[k] + fill[k];
    memset(fill, 0, cells * sizeof *fill);
    for (long i = 0; i < c->n; i++) {
        const double *p = c->x + i * dim;
        long k = cell_of(p[0], g) + (long)g * (cell_of(p[1], g) + (dim == 3 ? (long)g * cell_of(p[2], g) : 0));
        long at = c->start[k] + fill[k]++;
        c->gid[at] = i;
        memcpy(c->gx + at * dim, p, dim * sizeof *p);
        if (c->ia)
            memcpy(c->gia + at * dim, c->ia + i * dim, dim * sizeof *p);
    }
    free(fill);
    /* Unvisited points lie beyond the searched box: their L-infinity offset,
     * a lower bound of every Lp norm, is at least the distance to its faces,
     * and radii shrink distances at most by rmax.  The slack absorbs rounding. */
    c->gfac = (1 - 1e-9) / c->rmax;
    return grid_near_build(c);
}

/* The share of empty buckets on a grid of two points per bucket: about
 * exp(-2) = 0.14 for uniform points, less for Poisson-disk ones, and most
 * of them for clustered sets, where the ring search and the candidate
 * lists degenerate.  -1 when out of memory. */
static double empty_share(const struct tex_cellular *c)
{
    int dim = c->dim, g = (int)floor(pow(c->n / 2.0, 1.0 / dim));
    long cells, empty = 0;
    unsigned char *hit;

    g = g < 1 ? 1 : g > 1024 ? 1024 : g;
    cells = dim == 2 ? (long)g * g : (long)g * g * g;
    if (!(hit = calloc(cells, 1)))
        return -1;
    for (long i = 0; i < c->n; i++) {
        const double *p = c->x + i * dim;
        hit[cell_of(p[0], g) + (long)g * (cell_of(p[1], g) + (dim == 3 ? (long)g * cell_of(p[2], g) : 0))] = 1;
    }
    for (long k = 0; k < cells; k++)
        empty += !hit[k];
    free(hit);
    return (double)empty / cells;
}

/* Bucket k of an axis: wrapped, with the shift *s of its periodic image, when
 * the map tiles; else -1 outside the grid. */
static inline int ring_axis(const struct tex_cellular *c, int k, double *s)
{
    int g = c->g;
    if (!c->tile)
        return k < 0 || k >= g ? -1 : k;
    int w = (k % g + g) % g;
    *s = (k - w) / g;
    return w;
}

/* Whether the buckets up to r away from q's (cc) on every axis, searched,
 * hold the two nearest points: F2 so far is below the distance from q to the
 * faces of their box (none where the box covers the grid). */
static int rings_done(const struct tex_cellular *c, int dim, const double *q, const int *cc, int r,
                      const struct best *b)
{
    int g = c->g;
    double bound = INFINITY;
    for (int j = 0; j < dim; j++) {
        if (c->tile || cc[j] - r > 0) {
            double d = q[j] - (double)(cc[j] - r) / g;
            bound = d < bound ? d : bound;
        }
        if (c->tile || cc[j] + r < g - 1) {
            double d = (double)(cc[j] + r + 1) / g - q[j];
            bound = d < bound ? d : bound;
        }
    }
    return bound == INFINITY || b->a2 < acc_of(c, bound * c->gfac);
}

/* Rings NEAR_R + 1, NEAR_R + 2, ... of buckets around q's (cc), until no bucket beyond
 * can hold one of the two nearest points: the search past the near buckets, rare, so one
 * copy with the metric read at run time. */
static void grid_rings(const struct tex_cellular *c, const double *q, const int *cc,
                       struct best *b)
{
    int g = c->g, dim = c->dim;
    for (int r = NEAR_R + 1; !rings_done(c, dim, q, cc, r - 1, b); r++) {
        int rz = dim == 3 ? r : 0;
        for (int oz = -rz; oz <= rz; oz++) {
            double sv[3] = {0, 0, 0};
            int kz = dim == 3 ? ring_axis(c, cc[2] + oz, &sv[2]) : 0;
            if (kz < 0)
                continue;
            for (int oy = -r; oy <= r; oy++) {
                int ky = ring_axis(c, cc[1] + oy, &sv[1]);
                /* inside the ring's faces only its ends: visited in earlier rings */
                int step = r == 0 || abs(oy) == r || (dim == 3 && abs(oz) == r) ? 1 : 2 * r;
                if (ky < 0)
                    continue;
                long row = (long)g * (ky + (long)g * kz);
                for (int ox = -r; ox <= r; ox += step) {
                    int kx = ring_axis(c, cc[0] + ox, &sv[0]);
                    if (kx < 0)
                        continue;
                    for (long at = c->start[row + kx]; at < c->start[row + kx + 1]; at++)
                        best_add(b, acc_point(c, q, c->gx + at * dim,
                                              c->gia ? c->gia + at * dim : NULL, sv),
                                 c->gid[at]);
                }
            }
        }
    }
}

/* The two nearest points to q through the buckets, nearest buckets first:
 * the table c->near (grid_near_build) up to NEAR_R buckets away on every
 * axis, then whole rings.  The walk stops where F2 so far is below the next
 * entry's least distance from any point of q's bucket; it passes over a
 * bucket whose gaps to q along the axes already put it beyond F2.  Skipped
 * points could not change the result, and best_add's result does not depend
 * on the order of the points, so the bytes are those of a search through
 * every bucket.  The gaps and distances are taken 1e-14 short (a point's
 * bucket comes from a rounded product) and times gfac (radii), as the rings'
 * bound is.  metric and dim are c's, constants in each call so that
 * acc_point_m's switch and loop fold. */
static inline __attribute__((always_inline)) void
grid_walk(const struct tex_cellular *c, enum tex_metric metric, int dim, const double *q,
          struct best *b)
{
    int g = c->g, cc[3] = {0, 0, 0};
    /* per axis and offset + NEAR_R: the bucket's part of the cell index (-1:
     * outside the grid), its periodic image's shift, its gap to q */
    long part[3][2 * NEAR_R + 1];
    double shift[3][2 * NEAR_R + 1], gaps[3][2 * NEAR_R + 1], ig = 1.0 / g;
    const double zero[3] = {0, 0, 0};

    best_init(b);
    for (int j = 0, mul = 1; j < dim; j++, mul *= g) {
        cc[j] = cell_of(q[j], g);
        double lo = q[j] - cc[j] * ig, hi = (cc[j] + 1) * ig - q[j]; /* to the bucket's faces */
        for (int o = -NEAR_R; o <= NEAR_R; o++) {
            double d = o < 0 ? lo + (-o - 1) * ig : o > 0 ? hi + (o - 1) * ig : 0;
            shift[j][o + NEAR_R] = 0;
            int k = ring_axis(c, cc[j] + o, &shift[j][o + NEAR_R]);
            gaps[j][o + NEAR_R] = d > 1e-14 ? (d - 1e-14) * c->gfac : 0;
            part[j][o + NEAR_R] = k < 0 ? -1 : (long)k * mul;
        }
    }
    for (int i = 0; i < c->nnear; i++) {
        const struct near_bucket *e = &c->near[i];
        double sv[3] = {0, 0, 0}, gv[3] = {0, 0, 0};
        long cell = 0;
        if (b->a2 < e->stop)
            return;
#pragma GCC unroll 3
        for (int j = 0; j < dim; j++) {
            int o = e->o[j] + NEAR_R;
            if (part[j][o] < 0)
                goto next;
            cell += part[j][o];
            sv[j] = shift[j][o];
            gv[j] = gaps[j][o];
        }
        if (c->start[cell] == c->start[cell + 1] ||
            b->a2 < acc_point_m(c, metric, dim, gv, zero, NULL, zero))
            continue;
        for (long at = c->start[cell]; at < c->start[cell + 1]; at++)
            best_add(b, acc_point_m(c, metric, dim, q, c->gx + at * dim,
                                    c->gia ? c->gia + at * dim : NULL, sv),
                     c->gid[at]);
    next:;
    }
    grid_rings(c, q, cc, b);
}

static void grid_query1(const struct tex_cellular *c, const double *q, struct best *b)
{
#define WALK(m)                                                                                  \
    c->dim == 3 ? grid_walk(c, m, 3, q, b) : grid_walk(c, m, 2, q, b);                          \
    break
    switch (c->metric) {
    case TEX_METRIC_EUCLID: WALK(TEX_METRIC_EUCLID);
    case TEX_METRIC_MANHATTAN: WALK(TEX_METRIC_MANHATTAN);
    case TEX_METRIC_CHEBYSHEV: WALK(TEX_METRIC_CHEBYSHEV);
    default: WALK(TEX_METRIC_MINKOWSKI);
    }
#undef WALK
}

/* Candidate lists (2D Euclidean without radii).  F2 is 1-Lipschitz, so
 * inside bucket C (centre m, half diagonal hd) F2(q) <= F2(m) + hd = U, and
 * a point that is one of the two nearest to q lies within U of q, hence
 * within U of the box C.  The lists hold the points (and periodic images)
 * within U of each box.  These buckets have their own grid, wider than
 * tall: a row of pixels stays longer in one, and its queries share the
 * list. */
#ifndef CAND_FILL
#define CAND_FILL 0.15
#endif
#ifndef CAND_ASPECT
#define CAND_ASPECT 1.0
#endif

static int cand_push(struct tex_cellular *c, size_t *cap, size_t used, double x, double y,
                     long id)
{
    if (used == *cap) {
        size_t nc = *cap ? 2 * *cap : 4096;
        int ok = 1;
        c->cx = grown(c->cx, nc, sizeof *c->cx, &ok);
        c->cy = grown(c->cy, nc, sizeof *c->cy, &ok);
        c->cid = grown(c->cid, nc, sizeof *c->cid, &ok);
        if (!ok)
            return tex_error("out of memory for the candidate lists");
        *cap = nc;
    }
    c->cx[used] = x;
    c->cy[used] = y;
    c->cid[used] = id;
    return 0;
}

static int cand_build(struct tex_cellular *c)
{
    int g = c->g;
    double want = c->n / CAND_FILL;
    int gx = (int)lround(sqrt(want * CAND_ASPECT)), gy = (int)lround(sqrt(want / CAND_ASPECT));
    size_t cap = 0, used = 0;

    gx = gx < 1 ? 1 : gx > 1 << 12 ? 1 << 12 : gx;
    gy = gy < 1 ? 1 : gy > 1 << 10 ? 1 << 10 : gy;
    c->cgx = gx;
    c->cgy = gy;
    double hd = 0.5 * sqrt(1.0 / ((double)gx * gx) + 1.0 / ((double)gy * gy));
    long cells = (long)gx * gy;
    if (!(c->cstart = malloc((cells + 1) * sizeof *c->cstart)))
        return tex_error("out of memory for the candidate lists");
    tex_progress_stage(0.8, cells); /* the longest part of a large point set's map */
    for (long k = 0; k < cells; k++) {
        int kx = (int)(k % gx), ky = (int)(k / gx), k0[2], k1[2];
        if ((k & 1023) == 1023)
            tex_progress_add(1024);
        double lo[2] = {(double)kx / gx, (double)ky / gy};
        double hi[2] = {(double)(kx + 1) / gx, (double)(ky + 1) / gy};
        double m[2] = {(kx + 0.5) / gx, (ky + 0.5) / gy}, u, ur;
        struct best b;
        c->cstart[k] = (long)used;
        grid_query1(c, m, &b);
        u = (sqrt(b.a2) + hd) * (1 + 1e-9) + 1e-12;
        ur = u < 2 ? u : 2; /* for the cell range: images beyond one period never count */
        for (int j = 0; j < 2; j++) {
            if (c->tile) {
                k0[j] = (int)floor((lo[j] - ur) * g);
                k1[j] = (int)floor((hi[j] + ur) * g);
                k0[j] = k0[j] < -g ? -g : k0[j];
                k1[j] = k1[j] > 2 * g - 1 ? 2 * g - 1 : k1[j];
            } else {
                k0[j] = cell_of(lo[j] - u, g);
                k1[j] = cell_of(hi[j] + u, g);
            }
        }
        for (int yy = k0[1]; yy <= k1[1]; yy++)
            for (int xx = k0[0]; xx <= k1[0]; xx++) {
                int wx = (xx % g + g) % g, wy = (yy % g + g) % g;
                double sx = (xx - wx) / g, sy = (yy - wy) / g;
                long cell = wx + (long)g * wy;
                for (long at = c->start[cell]; at < c->start[cell + 1]; at++) {
                    double px = c->gx[at * 2] + sx, py = c->gx[at * 2 + 1] + sy;
                    double dx = px < lo[0] ? lo[0] - px : px > hi[0] ? px - hi[0] : 0;
                    double dy = py < lo[1] ? lo[1] - py : py > hi[1] ? py - hi[1] : 0;
                    if (dx * dx + dy * dy > u * u)
                        continue;
                    if (cand_push(c, &cap, used, px, py, c->gid[at]) < 0)
                        return -1;
                    used++;
                }
            }
    }
    c->cstart[cells] = (long)used;
    return 0;
}

/* The hot loop: 2D Euclidean through a candidate list for up to 16 queries
 * that fall in the same bucket (neighbouring pixels of a row), one query
 * per vector lane, nv vectors of four.  Every lane does the scalar
 * arithmetic of acc_point and best_add (no fused multiply-add), so the
 * results do not depend on the grouping, the vector width or the CPU.
 * Several independent vectors hide the latency of the compare-and-select
 * chain.  Writes squared distances; the callers take the roots. */
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32)));

/* A macro, not a function: a 32-byte vector argument outside AVX code
 * would change the ABI. */
#define vsel(m, x, y) ((v4d)(((v4l)(x) & (m)) | ((v4l)(y) & ~(m))))

static inline __attribute__((always_inline)) void
lanes(const double *cx, const double *cy, const long *cid, long t0, long e, const double *qx,
      const double *qy, const int nv, const int want_id, const int want_f2, double *a1,
      double *a2, long *i1)
{
    v4d X[4], Y[4], A1[4], A2[4], I1[4];

    /* Fully unrolled, so that the accumulators stay in registers. */
#pragma GCC unroll 4
    for (int v = 0; v < nv; v++) {
        for (int l = 0; l < 4; l++)
            X[v][l] = qx[4 * v + l], Y[v][l] = qy[4 * v + l];
        A1[v] = A2[v] = (v4d){INFINITY, INFINITY, INFINITY, INFINITY};
        I1[v] = (v4d){-1, -1, -1, -1};
    }
    for (long t = t0; t < e; t++) {
        double d = want_id ? (double)cid[t] : 0;
        v4d px = {cx[t], cx[t], cx[t], cx[t]}, py = {cy[t], cy[t], cy[t], cy[t]};
        v4d id = {d, d, d, d};
#pragma GCC unroll 4
        for (int v = 0; v < nv; v++) {
            v4d dx = X[v] - px, dy = Y[v] - py, a = dx * dx + dy * dy;
            v4l lt = a < A1[v];
            if (want_id) {
                lt |= (a == A1[v]) & (id < I1[v]);
                I1[v] = vsel(lt, id, I1[v]);
            }
            if (want_f2) {
                v4d lose = vsel(lt, A1[v], a);
                A2[v] = vsel(lose < A2[v], lose, A2[v]);
            }
            A1[v] = vsel(lt, a, A1[v]);
        }
    }
#pragma GCC unroll 4
    for (int v = 0; v < nv; v++)
        for (int l = 0; l < 4; l++) {
            a1[4 * v + l] = A1[v][l];
            if (want_f2)
                a2[4 * v + l] = A2[v][l];
            if (want_id)
                i1[4 * v + l] = (long)I1[v][l];
        }
}

#define LANES_CASE(k)                                                                         \
    case k:                                                                                   \
        lanes(cx, cy, cid, t0, e, qx, qy, (k) / 4 + 1, ((k) >> 1) & 1, (k)&1, a1, a2, i1);   \
        break;
#define LANES_SWITCH                                                                          \
    switch ((nv - 1) * 4 + want_id * 2 + want_f2) {                                           \
        LANES_CASE(0) LANES_CASE(1) LANES_CASE(2) LANES_CASE(3) LANES_CASE(4) LANES_CASE(5)   \
        LANES_CASE(6) LANES_CASE(7) LANES_CASE(8) LANES_CASE(9) LANES_CASE(10) LANES_CASE(11) \
        LANES_CASE(12) LANES_CASE(13) LANES_CASE(14) LANES_CASE(15)                           \
    }

/* Baseline build: GCC lowers each 32-byte vector to two SSE2 ones. */
static void cand_lanes(const double *cx, const double *cy, const long *cid, long t0, long e,
                       const double *qx, const double *qy, int nv, int want_id, int want_f2,
                       int roots, double *a1, double *a2, long *i1)
{
    LANES_SWITCH
    /* Vector square roots: correctly rounded like sqrt(), without its errno check. */
    for (int l = 0; roots && l < 4 * nv; l += 2) {
#ifdef HAVE_AVX2_KERNEL
        _mm_storeu_pd(a1 + l, _mm_sqrt_pd(_mm_loadu_pd(a1 + l)));
        if (want_f2)
            _mm_storeu_pd(a2 + l, _mm_sqrt_pd(_mm_loadu_pd(a2 + l)));
#else
        for (int k = l; k < l + 2; k++) {
            a1[k] = sqrt(a1[k]);
            if (want_f2)
                a2[k] = sqrt(a2[k]);
        }
#endif
    }
}

#ifdef HAVE_AVX2_KERNEL
/* Without the index, the selections of lanes() are single AVX instructions:
 * vminpd(x, y) is x < y ? x : y and vmaxpd(x, y) is x > y ? x : y, so
 *   A1' = lt ? a : A1           = min(a, A1)
 *   A2' = min(lt ? A1 : a, A2)  = min(max(A1, a), A2)
 * with lt = a < A1: the same values as lanes(), in 3 operations, not 5. */
TEX_AVX2 __attribute__((always_inline)) static inline void
lanes_minmax(const double *cx, const double *cy, long t0, long e, const double *qx,
             const double *qy, const int nv, const int want_f2, double *a1, double *a2)
{
    __m256d X[4], Y[4], A1[4], A2[4];

#pragma GCC unroll 4
    for (int v = 0; v < nv; v++) {
        X[v] = _mm256_loadu_pd(qx + 4 * v);
        Y[v] = _mm256_loadu_pd(qy + 4 * v);
        A1[v] = A2[v] = _mm256_set1_pd(INFINITY);
    }
    for (long t = t0; t < e; t++) {
        __m256d px = _mm256_broadcast_sd(cx + t), py = _mm256_broadcast_sd(cy + t);
#pragma GCC unroll 4
        for (int v = 0; v < nv; v++) {
            __m256d dx = _mm256_sub_pd(X[v], px), dy = _mm256_sub_pd(Y[v], py);
            __m256d a = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
            if (want_f2)
                A2[v] = _mm256_min_pd(_mm256_max_pd(A1[v], a), A2[v]);
            A1[v] = _mm256_min_pd(a, A1[v]);
        }
    }
#pragma GCC unroll 4
    for (int v = 0; v < nv; v++) {
        _mm256_storeu_pd(a1 + 4 * v, A1[v]);
        if (want_f2)
            _mm256_storeu_pd(a2 + 4 * v, A2[v]);
    }
}

#define MINMAX_CASE(k)                                                                        \
    case k:                                                                                   \
        lanes_minmax(cx, cy, t0, e, qx, qy, (k) / 2 + 1, (k)&1, a1, a2);                     \
        break;

/* The same lanes in 32-byte AVX2 vectors, chosen at run time.  AVX2 alone
 * brings no fused multiply-add, so each lane rounds as the SSE2 code does. */
TEX_AVX2 static void
cand_lanes_avx2(const double *cx, const double *cy, const long *cid, long t0, long e,
                const double *qx, const double *qy, int nv, int want_id, int want_f2, int roots,
                double *a1, double *a2, long *i1)
{
    if (want_id) {
        LANES_SWITCH
    } else {
        switch ((nv - 1) * 2 + want_f2) {
            MINMAX_CASE(0) MINMAX_CASE(1) MINMAX_CASE(2) MINMAX_CASE(3) MINMAX_CASE(4)
            MINMAX_CASE(5) MINMAX_CASE(6) MINMAX_CASE(7)
        }
    }
    for (int l = 0; roots && l < 4 * nv; l += 4) {
        _mm256_storeu_pd(a1 + l, _mm256_sqrt_pd(_mm256_loadu_pd(a1 + l)));
        if (want_f2)
            _mm256_storeu_pd(a2 + l, _mm256_sqrt_pd(_mm256_loadu_pd(a2 + l)));
    }
}
#endif

/* The queries of a chunk (m <= 256), wrapped and non-finite coordinates
 * made 0 as everywhere, and their buckets as cell_of gives them (-1 outside
 * the unit square), two at a time in SSE2 vectors without branches: the
 * clamps keep the conversions defined.  qx, qy, kk have room for m + 1. */
static void cand_buckets(const struct tex_cellular *c, int m, const double *q, double *qx,
                         double *qy, long *kk)
{
    typedef double v2d __attribute__((vector_size(16)));
    typedef long long v2l __attribute__((vector_size(16)));
    typedef int v2i __attribute__((vector_size(8)));
    const v2d zero = {0, 0}, one = {1, 1}, big = {DBL_MAX, DBL_MAX};
    const v2l mag = {INT64_MAX, INT64_MAX};
    const v2d gx = {c->cgx, c->cgx}, gy = {c->cgy, c->cgy}, gx1 = gx - one, gy1 = gy - one;
    const v2i gxi = {c->cgx, c->cgx};
    int m2 = (m + 1) & ~1;

    if (m < m2)
        qx[m] = qy[m] = 0;
    for (int i = 0; i < m2; i += 2) {
        v2d x = {q[2 * i], i + 1 < m ? q[2 * i + 2] : 0};
        v2d y = {q[2 * i + 1], i + 1 < m ? q[2 * i + 3] : 0};
        v2l fx = (v2d)((v2l)x & mag) <= big, fy = (v2d)((v2l)y & mag) <= big;
        x = (v2d)((v2l)x & fx); /* NaN and infinities: 0 */
        y = (v2d)((v2l)y & fy);
        memcpy(qx + i, &x, sizeof x);
        memcpy(qy + i, &y, sizeof y);
    }
    if (c->tile)
        for (int i = 0; i < m; i++)
            qx[i] = wrap1(qx[i]), qy[i] = wrap1(qy[i]);
    for (int i = 0; i < m2; i += 2) {
        v2d x, y, tx, ty;
        memcpy(&x, qx + i, sizeof x);
        memcpy(&y, qy + i, sizeof y);
        tx = x * gx;
        ty = y * gy;
        tx = (v2d)((v2l)tx & (tx > zero)); /* max(t, 0), min(t, g - 1) */
        ty = (v2d)((v2l)ty & (ty > zero));
        v2l cx = tx < gx1, cy = ty < gy1;
        tx = (v2d)(((v2l)tx & cx) | ((v2l)gx1 & ~cx));
        ty = (v2d)(((v2l)ty & cy) | ((v2l)gy1 & ~cy));
        v2l in = (x >= zero) & (x < one) & (y >= zero) & (y < one);
        v2i k = __builtin_convertvector(tx, v2i) + gxi * __builtin_convertvector(ty, v2i);
        v2l kl = __builtin_convertvector(k, v2l) | ~in;
        kk[i] = (long)kl[0], kk[i + 1] = (long)kl[1];
    }
}

static void cand_query(const struct tex_cellular *c, int n, const double *q, double *f1,
                       double *f2, long *id)
{
    enum { CHUNK = 256, RUN = 16 };
    int want_id = id != NULL, want_f2 = f2 != NULL;

    for (int i0 = 0; i0 < n; i0 += CHUNK) {
        int m = n - i0 < CHUNK ? n - i0 : CHUNK;
        double qx[CHUNK + 1], qy[CHUNK + 1], a1[CHUNK + RUN], a2[CHUNK + RUN];
        long kk[CHUNK + 1], i1[CHUNK + RUN];
        cand_buckets(c, m, q + 2 * (size_t)i0, qx, qy, kk);
        for (int i = 0; i < m;) {
            int j = i + 1;
            if (kk[i] < 0) {
                struct best b;
                double qq[2] = {qx[i], qy[i]};
                grid_query1(c, qq, &b);
                a1[i] = sqrt(b.a1), a2[i] = sqrt(b.a2), i1[i] = b.i1;
                i = j;
                continue;
            }
            while (j < m && j - i < RUN && kk[j] == kk[i])
                j++;
            int nv = (j - i + 3) / 4;
            double lx[RUN], ly[RUN];
            for (int l = 0; l < 4 * nv; l++) { /* pad the lanes with the run's first query */
                lx[l] = qx[i + l < j ? i + l : i];
                ly[l] = qy[i + l < j ? i + l : i];
            }
            long t0 = c->cstart[kk[i]], e = c->cstart[kk[i] + 1];
#ifdef HAVE_AVX2_KERNEL
            if (c->avx2)
                cand_lanes_avx2(c->cx, c->cy, c->cid, t0, e, lx, ly, nv, want_id, want_f2, 1,
                                a1 + i, a2 + i, i1 + i);
            else
#endif
                cand_lanes(c->cx, c->cy, c->cid, t0, e, lx, ly, nv, want_id, want_f2, 1,
                           a1 + i, a2 + i, i1 + i);
            i = j;
        }
        memcpy(f1 + i0, a1, m * sizeof *f1);
        if (f2)
            memcpy(f2 + i0, a2, m * sizeof *f2);
        if (id)
            memcpy(id + i0, i1, m * sizeof *id);
    }
}

/* Reps in Morton order of a 1024^dim grid over their bounding box: the
 * points FLANN returns for one box then lie close in memory. */
struct morton {
    uint64_t key;
    long at;
};

static int morton_cmp(const void *a, const void *b)
{
    const struct morton *x = a, *y = b;
    return x->key != y->key ? (x->key < y->key ? -1 : 1) : (x->at > y->at) - (x->at < y->at);
}

static int rep_sort(struct tex_cellular *c)
{
    int dim = c->dim;
    long n = c->nrep;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    struct morton *m = malloc(n * sizeof *m);
    double *rep = malloc(n * dim * sizeof *rep);
    long *repid = malloc(n * sizeof *repid);
    unsigned char *shift = malloc(n);

    if (!m || !rep || !repid || !shift) {
        free(m), free(rep), free(repid), free(shift);
        return tex_error("out of memory for the kd-tree");
    }
    for (long i = 0; i < n * dim; i++) {
        lo[i % dim] = fmin(lo[i % dim], c->rep[i]);
        hi[i % dim] = fmax(hi[i % dim], c->rep[i]);
    }
    for (long i = 0; i < n; i++) {
        uint64_t key = 0;
        for (int d = 0; d < dim; d++) {
            double t = hi[d] > lo[d] ? (c->rep[i * dim + d] - lo[d]) / (hi[d] - lo[d]) : 0;
            uint64_t k = (uint64_t)(t * 1023.999);
            for (int b = 0; b < 10; b++)
                key |= ((k >> b) & 1) << (b * dim + d);
        }
        m[i].key = key;
        m[i].at = i;
    }
    qsort(m, n, sizeof *m, morton_cmp);
    for (long i = 0; i < n; i++) {
        memcpy(rep + i * dim, c->rep + m[i].at * dim, dim * sizeof *rep);
        repid[i] = c->repid[m[i].at];
        shift[i] = c->repshift[m[i].at];
    }
    free(c->rep), free(c->repid), free(c->repshift), free(m);
    c->rep = rep;
    c->repid = repid;
    c->repshift = shift;
    return 0;
}

static int kdtree_build(struct tex_cellular *c)
{
    int dim = c->dim, nshift = c->tile ? (dim == 2 ? 9 : 27) : 1;
    long cap = c->n * nshift;

    if (c->tile) {
        /* Images within margin of the unit cube; farther ones are at least
         * margin away in L-infinity from any query in [0,1). */
        double m = 4 * c->rmax * pow((double)c->n, -1.0 / dim);
        c->margin = c->n <= 1000000 || m > 0.5 ? 0.5 : m < 0.05 ? 0.05 : m;
    }
    if (cap > 0x7fffffffL)
        return tex_error("too many points for the kd-tree (%ld with periodic images)", cap);
    c->rep = malloc(cap * dim * sizeof *c->rep);
    c->repid = malloc(cap * sizeof *c->repid);
    c->repshift = malloc(cap);
    if (!c->rep || !c->repid || !c->repshift)
        return tex_error("out of memory for the kd-tree");
    for (int k = 0; k < nshift; k++) {
        double s[3] = {0, 0, 0};
        if (c->tile)
            shift_of(k, dim, s);
        for (long i = 0; i < c->n; i++) {
            const double *p = c->x + i * dim;
            int in = 1;
            for (int j = 0; j < dim; j++)
                in &= p[j] + s[j] >= -c->margin && p[j] + s[j] < 1 + c->margin;
            if (!c->tile || in) {
                for (int j = 0; j < dim; j++)
                    c->rep[c->nrep * dim + j] = p[j] + s[j];
                c->repid[c->nrep] = i;
                c->repshift[c->nrep++] = (unsigned char)k;
            }
        }
    }
    if (rep_sort(c) < 0)
        return -1;
    if (!(c->index = tex_kdtree_new_d(c->rep, c->nrep, dim, 8)))
        return -1;
    /* Lp >= L2 for p <= 2 and Lp >= L2 * dim^(1/p - 1/2) beyond. */
    c->kfac = (1 - 1e-9) / c->rmax;
    /* Upward, ||x / a||_p <= ||x||_2 / amin times dim^(1/p - 1/2) for p < 2:
     * every distance, hence F1 and F2, is lip-Lipschitz in the query. */
    c->lip = (1 + 1e-9) / c->amin;
    if (c->metric == TEX_METRIC_MANHATTAN)
        c->lip *= sqrt((double)dim);
    else if (c->metric == TEX_METRIC_MINKOWSKI && c->p < 2)
        c->lip *= pow((double)dim, 1 / c->p - 0.5);
    if (c->metric == TEX_METRIC_CHEBYSHEV)
        c->kfac /= sqrt((double)dim);
    else if (c->metric == TEX_METRIC_MINKOWSKI && c->p > 2)
        c->kfac *= pow((double)dim, 1 / c->p - 0.5);
    return 0;
}

static void kdtree_query(const struct tex_cellular *c, int n, const double *q, struct best *b)
{
    int dim = c->dim, npend = n, k = 3;
    int *pend = malloc(n * sizeof *pend), *ind = NULL;
    double *qb = malloc((size_t)n * dim * sizeof *qb), *dist = NULL;

    if (!pend || !qb)
        goto brute;
    for (int i = 0; i < n; i++)
        pend[i] = i;
    if (c->ia || c->metric != TEX_METRIC_EUCLID)
        k = 8;
    while (npend > 0) {
        int next = 0;
        if (k > c->nrep)
            k = (int)c->nrep;
        free(ind);
        free(dist);
        ind = malloc((size_t)npend * k * sizeof *ind);
        dist = malloc((size_t)npend * k * sizeof *dist);
        if (!ind || !dist)
            goto brute;
        for (int i = 0; i < npend; i++)
            memcpy(qb + (size_t)i * dim, q + (size_t)pend[i] * dim, dim * sizeof *qb);
        if (tex_kdtree_knn_d(c->index, qb, npend, k, 0, 1, ind, dist) < 0)
            goto brute;
        for (int i = 0; i < npend; i++) {
            struct best *bi = b + pend[i];
            const double *qi = q + (size_t)pend[i] * dim;
            double bound = INFINITY;
            best_init(bi);
            for (int t = 0; t < k; t++) {
                long r = ind[(size_t)i * k + t], id = c->repid[r];
                double s[3] = {0, 0, 0};
                if (c->tile)
                    shift_of(c->repshift[r], dim, s);
                best_add(bi, acc_point(c, qi, c->x + id * dim, c->ia ? c->ia + id * dim : NULL, s),
                         id);
            }
            if (k < c->nrep)
                bound = sqrt(dist[(size_t)i * k + k - 1]) * c->kfac;
            if (c->tile && c->margin * c->gfac < bound)
                bound = c->margin * c->gfac;
            if (!(bound == INFINITY || bi->a2 < acc_of(c, bound)))
                pend[next++] = pend[i];
        }
        npend = next;
        if (npend > 0 && (k >= 256 || k >= c->nrep))
            goto brute;
        k *= 4;
    }
    free(pend);
    free(qb);
    free(ind);
    free(dist);
    return;
brute:
    /* Out of memory or a degenerate set (many equal distances): exact anyway. */
    if (!pend)
        npend = n;
    for (int i = 0; i < npend; i++) {
        int at = pend ? pend[i] : i;
        brute1(c, q + (size_t)at * dim, b + at);
    }
    free(pend);
    free(qb);
    free(ind);
    free(dist);
}

/* The adaptive candidate tree (kd-tree search).  FLANN answers per query
 * at about a microsecond; a row of pixels asks it the same question over
 * and over.  So the unit square (cube) is cut once into boxes, each with a
 * complete candidate list: every point (periodic image) that can be one
 * of the two nearest to a query in the box.  Queries then search their
 * box's list exactly as brute force does, point by point.
 *
 * A box B (centre m, half diagonal hd) gets its list from FLANN: the K
 * nearest neighbours of m are all the points closer than the K-th, E.  Let
 * U bound F2 over B: F2(m) (or the second smallest distance among the K)
 * plus lip hd, F2 being lip-Lipschitz.  A point that is one of the two
 * nearest to q in B has d(q) <= F2(q) <= U, so it lies within U / kfac of
 * B in L2 (kfac: the lower norm bound), and within U / kfac + hd of m.
 * While that is below E (and below the tiling margin), the K points hold
 * the list; otherwise B is split and its children ask FLANN.  A box whose
 * list is long is split too, and its children filter their lists from it:
 * the parent's list is complete at the child's centre, so F2 there is exact
 * and the child's bound is no larger than the parent's.  Boxes FLANN cannot
 * settle even small (many coincident points) leave their queries to
 * kdtree_query.  Lists are built in depth-first order, so the tree is the
 * same on every run. */
enum { ACT_CMAX = 400, ACT_RMAX = 8192, ACT_LEAF = 48, ACT_DEPTH = 14, ACT_NMAX = 2000000 };

/* Lists under construction, one set per depth: coordinates (dim per
 * entry) and point ids; kid holds the 2^dim children's lists of the node
 * being split at the depth above, own a list straight from FLANN. */
struct act_list {
    double *p;
    long *id, cap;
};

struct act_build {
    int rind[ACT_RMAX];
    double rdist[ACT_RMAX];
    long nnode, capnode, nent, capent, budget, nodebudget;
    struct act_list kid[ACT_DEPTH + 2], own[ACT_DEPTH + 2];
};

static int act_reserve(struct act_list *l, long n, int dim)
{
    if (n > l->cap) {
        int ok = 1;
        l->p = grown(l->p, (size_t)n * dim, sizeof *l->p, &ok);
        l->id = grown(l->id, n, sizeof *l->id, &ok);
        if (!ok)
            return tex_error("out of memory for the candidate tree");
        l->cap = n;
    }
    return 0;
}

static int act_grow(struct tex_cellular *c, struct act_build *B, long nodes, long ents)
{
    if (B->nnode + nodes > B->capnode) {
        long nc = 2 * (B->nnode + nodes);
        int ok = 1;
        c->achild = grown(c->achild, nc, sizeof *c->achild, &ok);
        c->astart = grown(c->astart, nc, sizeof *c->astart, &ok);
        c->alen = grown(c->alen, nc, sizeof *c->alen, &ok);
        if (!ok)
            return tex_error("out of memory for the candidate tree");
        B->capnode = nc;
    }
    if (B->nent + ents > B->capent) {
        long nc = 2 * (B->nent + ents);
        int ok = 1;
        c->ax = grown(c->ax, nc, sizeof *c->ax, &ok);
        c->ay = grown(c->ay, nc, sizeof *c->ay, &ok);
        c->aid = grown(c->aid, nc, sizeof *c->aid, &ok);
        if (!ok)
            return tex_error("out of memory for the candidate tree");
        B->capent = nc;
    }
    return 0;
}

/* Two smallest squared L2 distances from each of the 2^D child centres to
 * the list (an upper bound only: rounding here is absorbed by the slack). */
static inline __attribute__((always_inline)) void act_f2_euclid(const double *lp, int n,
                                                                const int D, double cm[8][3],
                                                                double *s1, double *s2)
{
    for (int t = 0; t < n; t++) {
        const double *p = lp + (size_t)t * D;
        for (int k = 0; k < 1 << D; k++) {
            double a = 0;
            for (int d = 0; d < D; d++)
                a += (cm[k][d] - p[d]) * (cm[k][d] - p[d]);
            double lo = a < s1[k] ? a : s1[k], hi = a < s1[k] ? s1[k] : a;
            s1[k] = lo;
            s2[k] = hi < s2[k] ? hi : s2[k];
        }
    }
}

/* Each child's list: the entries within sqrt(thr[k]) of its box. */
static inline __attribute__((always_inline)) void
act_filter(const double *lp, const long *lid, int n, const int D, double clo[8][3],
           double chi[8][3], const double *thr, struct act_list *kid, int *cn)
{
    for (int t = 0; t < n; t++) {
        const double *p = lp + (size_t)t * D;
        for (int k = 0; k < 1 << D; k++) {
            double e2 = 0;
            for (int d = 0; d < D; d++) {
                double x = fmax(clo[k][d] - p[d], p[d] - chi[k][d]);
                x = x > 0 ? x : 0;
                e2 += x * x;
            }
            if (e2 <= thr[k]) {
                long at = (long)k * n + cn[k]++;
                for (int d = 0; d < D; d++)
                    kid->p[at * D + d] = p[d];
                kid->id[at] = lid[t];
            }
        }
    }
}

/* What act_gather decided for a node. */
enum { ACT_LISTED, ACT_SPLIT, ACT_DONE };

/* F2 at m from its two nearest representatives: the reach R within which
 * every point that may matter in a box of half-diagonal hd lies, F2 itself,
 * and the squared distance to the second nearest. */
static int act_reach(const struct tex_cellular *c, const double *m, double hd,
                     double *R, double *f2, double *d2)
{
    int k2 = c->nrep < 2 ? 1 : 2, ind[2];
    double dist[2], s1 = INFINITY, s2 = INFINITY, zero[3] = {0, 0, 0};
    if (tex_kdtree_knn_d(c->index, m, 1, k2, 0, 0, ind, dist) < 0)
        return -1;
    for (int t = 0; t < k2; t++) {
        long id = c->repid[ind[t]];
        double a = acc_point(c, m, c->rep + (size_t)ind[t] * c->dim,
                             c->ia ? c->ia + id * c->dim : NULL, zero);
        s2 = t == 0 ? INFINITY : a > s1 ? a : s1;
        s1 = t == 0 ? a : a < s1 ? a : s1;
    }
    *f2 = acc_finish(c, s2) / c->kfac;
    *R = ((acc_finish(c, s2) + c->lip * hd) / c->kfac) * (1 + 1e-9) + 1e-12 + hd * (1 + 1e-9);
    *d2 = dist[k2 - 1];
    return 0;
}

/* Keep, in `own`, the n points found around m that lie within the exact
 * reach of the box lo + [0,side)^dim. */
static int act_keep(const struct tex_cellular *c, const struct act_build *B, struct act_list *own,
                    const double *m, const double *lo, double side, double hd, int n)
{
    int dim = c->dim, nl = 0;
    double s1 = INFINITY, s2 = INFINITY, thr, zero[3] = {0, 0, 0};
    for (int t = 0; t < n; t++) {
        long id = c->repid[B->rind[t]];
        double a = acc_point(c, m, c->rep + (size_t)B->rind[t] * dim,
                             c->ia ? c->ia + id * dim : NULL, zero);
        if (a < s1)
            s2 = s1, s1 = a;
        else if (a < s2)
            s2 = a;
    }
    thr = ((acc_finish(c, s2) + c->lip * hd) / c->kfac) * (1 + 1e-9) + 1e-12;
    if (act_reserve(own, n, dim) < 0)
        return -1;
    for (int t = 0; t < n; t++) {
        const double *p = c->rep + (size_t)B->rind[t] * dim;
        double e2 = 0;
        for (int d = 0; d < dim; d++) {
            double x = p[d] < lo[d] ? lo[d] - p[d] : p[d] > lo[d] + side ? p[d] - (lo[d] + side) : 0;
            e2 += x * x;
        }
        if (e2 <= thr * thr) {
            memcpy(own->p + (size_t)nl * dim, p, dim * sizeof *p);
            own->id[nl++] = c->repid[B->rind[t]];
        }
    }
    return nl;
}

/* A node without a list: F2 at its centre, then every point within reach
 * from FLANN, kept in B->own[depth] (*n of them).  Returns ACT_LISTED,
 * ACT_SPLIT (too many points: split without a list), ACT_DONE (the node
 * stays a kd-tree query) or -1. */
static int act_gather(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                      double side, int depth, int *n)
{
    int dim = c->dim, maxnn, got;
    double hd = 0.5 * side * sqrt((double)dim), m[3], R = 0, f2 = 0, d2 = 0, est;
    for (int d = 0; d < dim; d++)
        m[d] = lo[d] + 0.5 * side;
    if (act_reach(c, m, hd, &R, &f2, &d2) < 0)
        return -1;
    if (c->tile && !(R < c->margin * (1 - 1e-9))) {
        /* Images beyond the margin are not in the tree: smaller boxes
         * help while F2 stays well inside it, else kdtree_query. */
        c->achild[node] = -2;
        return f2 < 0.5 * c->margin && depth < ACT_DEPTH ? ACT_SPLIT : ACT_DONE;
    }
    /* Points within R: about 2 (R / |m - second nearest|)^dim. */
    est = R == INFINITY ? (double)c->nrep : 2 * pow(R / fmax(sqrt(d2), 1e-300), dim) + 16;
    if (est > ACT_CMAX && est < c->nrep && depth < ACT_DEPTH) {
        c->achild[node] = -2;
        return ACT_SPLIT;
    }
    maxnn = est < ACT_RMAX ? (int)est + 16 : ACT_RMAX;
    for (;;) {
        float r2 = R == INFINITY ? INFINITY : nextafterf((float)(R * R), INFINITY);
        if (maxnn > c->nrep)
            maxnn = (int)c->nrep + 1;
        got = tex_kdtree_radius_d(c->index, m, r2, maxnn, B->rind, B->rdist);
        if (got < 0)
            return -1;
        if (got < maxnn)
            break; /* all of them */
        if (maxnn < ACT_RMAX) {
            maxnn = 4 * maxnn < ACT_RMAX ? 4 * maxnn : ACT_RMAX;
            continue;
        }
        c->achild[node] = -2;
        return depth < ACT_DEPTH ? ACT_SPLIT : ACT_DONE;
    }
    /* F2 at m is exact now; keep the points within reach of the box. */
    if ((*n = act_keep(c, B, &B->own[depth], m, lo, side, hd, got)) < 0)
        return -1;
    return ACT_LISTED;
}

/* A leaf: its list goes into the flat arrays.  1 when the budget runs out. */
static int act_fill_leaf(struct tex_cellular *c, struct act_build *B, long node, const double *lp,
                         const long *lid, int n)
{
    int dim = c->dim;
    if (B->nent + n > B->budget)
        return 1;
    if (act_grow(c, B, 0, n) < 0)
        return -1;
    c->achild[node] = -1;
    c->astart[node] = B->nent;
    c->alen[node] = n;
    memcpy(c->aid + B->nent, lid, (size_t)n * sizeof *lid);
    for (int t = 0; t < n; t++) {
        c->ax[B->nent + t] = lp[t * dim];
        c->ay[B->nent + t] = lp[t * dim + 1];
    }
    B->nent += n;
    return 0;
}

static int act_node(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                    double side, int depth, const double *lp, const long *lid, int n);

/* Split a node into 2^dim children.  With a complete list, F2 at every
 * child's centre is exact: each child's list keeps the entries within its
 * reach.  Without one, each child gathers its own. */
static int act_split(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                     double side, int depth, const double *lp, const long *lid, int n)
{
    int dim = c->dim, nch = 1 << dim, ret = 0, cn[8] = {0};
    int euclid = c->metric == TEX_METRIC_EUCLID && !c->ia;
    double hd = 0.5 * side * sqrt((double)dim), zero[3] = {0, 0, 0};
    long first = B->nnode;
    struct act_list *kid = &B->kid[depth + 1];
    double clo[8][3], chi[8][3], cm[8][3], s1[8], s2[8], thr[8];
    if (B->nnode + nch > B->nodebudget)
        return 1;
    if (act_grow(c, B, nch, 0) < 0 || (lp && act_reserve(kid, (long)nch * n, dim) < 0))
        return -1;
    B->nnode += nch;
    c->achild[node] = (int)first;
    for (int k = 0; k < nch; k++) {
        for (int d = 0; d < dim; d++) {
            clo[k][d] = lo[d] + ((k >> d) & 1) * 0.5 * side;
            chi[k][d] = clo[k][d] + 0.5 * side;
            cm[k][d] = clo[k][d] + 0.25 * side;
        }
        s1[k] = s2[k] = INFINITY;
    }
    if (lp) {
        if (euclid && dim == 2)
            act_f2_euclid(lp, n, 2, cm, s1, s2);
        else if (euclid)
            act_f2_euclid(lp, n, 3, cm, s1, s2);
        else
            for (int t = 0; t < n; t++)
                for (int k = 0; k < nch; k++) {
                    double a = acc_point(c, cm[k], lp + (size_t)t * dim,
                                         c->ia ? c->ia + lid[t] * dim : NULL, zero);
                    if (a < s1[k])
                        s2[k] = s1[k], s1[k] = a;
                    else if (a < s2[k])
                        s2[k] = a;
                }
        for (int k = 0; k < nch; k++) {
            thr[k] = ((acc_finish(c, s2[k]) + c->lip * 0.5 * hd) / c->kfac) * (1 + 1e-9) + 1e-12;
            thr[k] *= thr[k];
        }
        if (dim == 2)
            act_filter(lp, lid, n, 2, clo, chi, thr, kid, cn);
        else
            act_filter(lp, lid, n, 3, clo, chi, thr, kid, cn);
    }
    for (int k = 0; k < nch && ret == 0; k++)
        ret = act_node(c, B, first + k, clo[k], 0.5 * side, depth + 1,
                       lp ? kid->p + (size_t)k * n * dim : NULL, lp ? kid->id + (size_t)k * n : NULL,
                       cn[k]);
    return ret;
}

/* Fill node `node` (box lo + [0,side)^dim) from its complete list lp, lid
 * (n entries) or, without one, from FLANN.  Returns -1 on failure, 1 when
 * a budget runs out. */
static int act_node(struct tex_cellular *c, struct act_build *B, long node, const double *lo,
                    double side, int depth, const double *lp, const long *lid, int n)
{
    if (!lp) {
        int r = act_gather(c, B, node, lo, side, depth, &n);
        if (r < 0)
            return -1;
        if (r == ACT_DONE)
            return 0;
        if (r == ACT_SPLIT)
            return act_split(c, B, node, lo, side, depth, NULL, NULL, 0);
        lp = B->own[depth].p;
        lid = B->own[depth].id;
    }
    if (n <= ACT_LEAF || depth >= ACT_DEPTH)
        return act_fill_leaf(c, B, node, lp, lid, n);
    return act_split(c, B, node, lo, side, depth, lp, lid, n);
}

static void act_free(struct tex_cellular *c)
{
    free(c->achild), free(c->astart), free(c->alen);
    free(c->ax), free(c->ay), free(c->aid);
    c->achild = c->alen = NULL;
    c->astart = c->aid = NULL;
    c->ax = c->ay = NULL;
    c->at = 0;
}

/* Top boxes of about ACT_K / 4 points; an entry budget keeps memory in
 * check (beyond it the queries go to kdtree_query). */
static int act_build(struct tex_cellular *c)
{
    int dim = c->dim, T = 1, ret = 0;
    struct act_build *B = calloc(1, sizeof *B);
    long ntop;

    if (!B)
        return tex_error("out of memory for the candidate tree");
    B->budget = 32 * c->n + (1L << 20);
    B->nodebudget = 16 * c->n + (1L << 16);
    while (pow(2.0 * T, dim) <= c->n / 32.0 && T < (dim == 2 ? 1024 : 64))
        T *= 2;
    ntop = dim == 2 ? (long)T * T : (long)T * T * T;
    if (act_grow(c, B, ntop, 0) < 0) {
        free(B);
        return -1;
    }
    B->nnode = ntop;
    c->at = T;
    for (long k = 0; k < ntop && ret == 0; k++) {
        double lo[3] = {(double)(k % T) / T, (double)(k / T % T) / T, (double)(k / T / T) / T};
        ret = act_node(c, B, k, lo, 1.0 / T, 0, NULL, NULL, 0);
    }
    for (int d = 0; d < ACT_DEPTH + 2; d++) {
        free(B->kid[d].p), free(B->kid[d].id);
        free(B->own[d].p), free(B->own[d].id);
    }
    free(B);
    if (ret > 0)
        act_free(c); /* over budget: the queries go to kdtree_query */
    return ret < 0 ? -1 : 0;
}

/* The leaf holding q (in [0,1)^dim): its node, box corner lo and side. */
static long act_leaf(const struct tex_cellular *c, const double *q, double *lo, double *side)
{
    int dim = c->dim, T = c->at;
    long node = 0;

    *side = 1.0 / T;
    for (int d = dim - 1; d >= 0; d--) {
        int k = cell_of(q[d], T);
        node = node * T + k;
        lo[d] = (double)k / T;
    }
    while (c->achild[node] >= 0) {
        int k = 0;
        *side *= 0.5;
        for (int d = 0; d < dim; d++)
            if (q[d] >= lo[d] + *side) {
                k |= 1 << d;
                lo[d] += *side;
            }
        node = c->achild[node] + k;
    }
    return node;
}

/* Queries (wrapped, finite) through the tree; b as brute force gives it. */
static void act_query(const struct tex_cellular *c, int n, const double *q, struct best *b,
                      int want_id, int want_f2)
{
    int dim = c->dim, vec = dim == 2 && c->metric == TEX_METRIC_EUCLID && !c->ia;
    double lo[3] = {0, 0, 0}, side = -1, zero[3] = {0, 0, 0};
    long node = -1;

    for (int i = 0; i < n;) {
        const double *qi = q + (size_t)i * dim;
        int in = 1, inleaf = side > 0, j = i + 1;
        for (int d = 0; d < dim; d++) {
            in &= qi[d] >= 0 && qi[d] < 1;
            inleaf &= qi[d] >= lo[d] && qi[d] < lo[d] + side;
        }
        if (!in) {
            kdtree_query(c, 1, qi, b + i);
            i = j;
            continue;
        }
        if (!inleaf)
            node = act_leaf(c, qi, lo, &side);
        if (c->achild[node] == -2) {
            kdtree_query(c, 1, qi, b + i);
            i = j;
            continue;
        }
        long t0 = c->astart[node], e = t0 + c->alen[node];
        if (vec) {
            /* The run of queries in this leaf, up to 16 at a time. */
            for (; j < n && j - i < 16; j++) {
                const double *qj = q + 2 * (size_t)j;
                if (!(qj[0] >= lo[0] && qj[0] < lo[0] + side && qj[1] >= lo[1] &&
                      qj[1] < lo[1] + side))
                    break;
            }
            int m = j - i, nv = (m + 3) / 4;
            double qx[16], qy[16], a1[16], a2[16];
            long i1[16];
            for (int l = 0; l < 4 * nv; l++) {
                qx[l] = q[2 * (size_t)(i + (l < m ? l : 0))];
                qy[l] = q[2 * (size_t)(i + (l < m ? l : 0)) + 1];
            }
#ifdef HAVE_AVX2_KERNEL
            if (c->avx2)
                cand_lanes_avx2(c->ax, c->ay, c->aid, t0, e, qx, qy, nv, want_id, want_f2, 0,
                                a1, a2, i1);
            else
#endif
                cand_lanes(c->ax, c->ay, c->aid, t0, e, qx, qy, nv, want_id, want_f2, 0, a1, a2,
                           i1);
            for (int l = 0; l < m; l++)
                b[i + l].a1 = a1[l], b[i + l].a2 = a2[l], b[i + l].i1 = i1[l];
        } else {
            best_init(b + i);
            for (long t = t0; t < e; t++) {
                long id = c->aid[t];
                double pt[2] = {c->ax[t], c->ay[t]};
                best_add(b + i, acc_point(c, qi, pt, c->ia ? c->ia + id * 2 : NULL, zero), id);
            }
        }
        i = j;
    }
}

void tex_cellular_free(tex_cellular *c)
{
    if (!c)
        return;
    tex_kdtree_free(c->index);
    free(c->x);
    free(c->ia);
    free(c->start);
    free(c->near);
    free(c->gid);
    free(c->gx);
    free(c->gia);
    free(c->rep);
    free(c->repid);
    free(c->repshift);
    free(c->cstart);
    free(c->cx);
    free(c->cy);
    free(c->cid);
    act_free(c);
    free(c);
}

tex_cellular *tex_cellular_new(const tex_points *ps, const struct tex_cellular_opts *o)
{
    struct tex_cellular *c = calloc(1, sizeof *c);
    int dim = ps->dim;

    if (!c) {
        tex_error("out of memory");
        return NULL;
    }
    c->dim = dim;
    c->n = ps->n;
    c->tile = o->tile;
    c->metric = o->metric;
    c->p = o->metric == TEX_METRIC_EUCLID ? 2 : o->p;
    c->rmax = c->amin = 1;
    if (!(c->x = malloc(c->n * dim * sizeof *c->x)))
        goto oom;
    memcpy(c->x, ps->x, c->n * dim * sizeof *c->x);
    if (c->tile)
        for (long i = 0; i < c->n * dim; i++)
            c->x[i] = wrap1(c->x[i]);
    if (ps->axes) {
        if (!(c->ia = malloc(c->n * dim * sizeof *c->ia)))
            goto oom;
        c->rmax = 0;
        c->amin = INFINITY;
        for (long i = 0; i < c->n * dim; i++) {
            c->ia[i] = 1 / ps->axes[i];
            c->rmax = ps->axes[i] > c->rmax ? ps->axes[i] : c->rmax;
            c->amin = ps->axes[i] < c->amin ? ps->axes[i] : c->amin;
        }
    }
    c->gfac = (1 - 1e-9) / c->rmax;
#ifdef HAVE_AVX2_KERNEL
    c->avx2 = tex_simd_level() >= TEX_SIMD_AVX2;
#endif
    c->search = o->search;
    if (c->search == TEX_SEARCH_AUTO) {
        double e = empty_share(c);
        if (e < 0)
            goto oom;
        c->search = e < 0.3 ? TEX_SEARCH_GRID : TEX_SEARCH_KDTREE;
    }
    if (c->search == TEX_SEARCH_GRID) {
        if (grid_build(c) < 0)
            goto fail;
        /* Candidate lists pay for themselves over many queries per cell; for far
         * more points than queries (10^7 points, a 256^2 map) they would cost
         * most of the time and memory, and the grid answers alike. */
        if (c->search == TEX_SEARCH_GRID && dim == 2 && c->metric == TEX_METRIC_EUCLID &&
            !c->ia && !(o->queries > 0 && c->n / CAND_FILL > 4.0 * o->queries) &&
            cand_build(c) < 0)
            goto fail;
    }
    if (c->search == TEX_SEARCH_KDTREE &&
        (kdtree_build(c) < 0 ||
         (dim == 2 && c->n <= ACT_NMAX && !getenv("TEXTURA_BUBBLE_NO_TREE") && act_build(c) < 0)))
        goto fail;
    return c;
oom:
    tex_error("out of memory");
fail:
    tex_cellular_free(c);
    return NULL;
}

enum tex_search tex_cellular_search(const tex_cellular *c)
{
    return c->search;
}

void tex_cellular_query(const tex_cellular *c, int n, const double *q, double *f1, double *f2,
                        long *id)
{
    enum { CHUNK = 256 };
    int dim = c->dim;

    if (c->search == TEX_SEARCH_GRID && c->cstart) {
        cand_query(c, n, q, f1, f2, id);
        return;
    }
    for (int i0 = 0; i0 < n; i0 += CHUNK) {
        int m = n - i0 < CHUNK ? n - i0 : CHUNK;
        double qb[CHUNK * 3];
        struct best b[CHUNK];
        for (int i = 0; i < m; i++)
            for (int j = 0; j < dim; j++) {
                double x = q[(size_t)(i0 + i) * dim + j];
                if (!isfinite(x))
                    x = 0;
                qb[i * dim + j] = c->tile ? wrap1(x) : x;
            }
        if (c->search == TEX_SEARCH_KDTREE)
            c->at ? act_query(c, m, qb, b, id != NULL, f2 != NULL) : kdtree_query(c, m, qb, b);
        else
            for (int i = 0; i < m; i++) {
                const double *qi = qb + i * dim;
                if (c->search == TEX_SEARCH_GRID)
                    grid_query1(c, qi, b + i);
                else
                    brute1(c, qb + i * dim, b + i);
            }
        for (int i = 0; i < m; i++) {
            f1[i0 + i] = acc_finish(c, b[i].a1);
            if (f2)
                f2[i0 + i] = acc_finish(c, b[i].a2);
            if (id)
                id[i0 + i] = b[i].i1;
        }
    }
}

/* ---- the bubble primitive ---- */

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
               "distance: euclid|manhattan|chebyshev|minkowski:P with P in 1..64"),
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

static int bubble_init(struct tex_field *f)
{
    const struct bubble_params *p = f->params;
    struct tex_cellular_opts o = {TEX_METRIC_EUCLID, 2, f->tile, (enum tex_search)p->search,
                                  f->w ? (long)f->w * f->h : f->queries};
    struct bubble_state *s;
    tex_points ps;
    int dim = p->dimension + 2;

    if (tex_metric_parse(p->metric, &o.metric, &o.p) < 0)
        return -1;
    /* Options of another mode, told by values other than the defaults (the rows
     * serve scenes too, where nothing records what was given). */
    if (p->clusters && p->distribution != TEX_POINTS_CLUSTER)
        return tex_usage_error("--clusters applies to --distribution cluster only");
    if (p->z != BUBBLE_SLICE && dim == 2)
        return tex_usage_error("--slice applies to --dimension 3 only");
    if (p->points && (p->count != BUBBLE_COUNT || p->distribution || p->clusters))
        return tex_usage_error("--count, --distribution and --clusters apply to random points, "
                               "not to --points");
    tex_progress_stage(0.3, 2); /* the points, then their search structure */
    if (p->points) {
        if (tex_points_read(&ps, p->points, dim) < 0)
            return -1;
    } else {
        if (p->distribution == TEX_POINTS_POISSON && p->count > 2000000)
            return tex_usage_error("--distribution poisson takes at most 2000000 points (got %d)",
                                   p->count);
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
