/* cellular_grid.c - nearest points through grid buckets, and the candidate lists of 2D
 * Euclidean sets */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/progress.h"
#include "prim/cellular_impl.h"
#include "prim/x86/cellular_x86.h"

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

int tex_cellular_grid_build(struct tex_cellular *c)
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
double tex_cellular_empty_share(const struct tex_cellular *c)
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

void tex_cellular_grid_query(const struct tex_cellular *c, const double *q, struct best *b)
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

int tex_cellular_cand_build(struct tex_cellular *c)
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
        tex_cellular_grid_query(c, m, &b);
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

/* Baseline build: GCC lowers each 32-byte vector to two SSE2 ones. */
void tex_cellular_lanes(const double *cx, const double *cy, const long *cid, long t0, long e,
                        const double *qx, const double *qy, int nv, int want_id, int want_f2,
                        int roots, double *a1, double *a2, long *i1)
{
    LANES_SWITCH
    if (!roots)
        return;
#ifdef HAVE_AVX2_KERNEL
    tex_cellular_roots_sse2(a1, want_f2 ? a2 : NULL, 4 * nv);
#else
    for (int l = 0; l < 4 * nv; l++) {
        a1[l] = sqrt(a1[l]);
        if (want_f2)
            a2[l] = sqrt(a2[l]);
    }
#endif
}

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

void tex_cellular_cand_query(const struct tex_cellular *c, int n, const double *q, double *f1,
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
                tex_cellular_grid_query(c, qq, &b);
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
                tex_cellular_lanes_avx2(c->cx, c->cy, c->cid, t0, e, lx, ly, nv, want_id, want_f2,
                                        1, a1 + i, a2 + i, i1 + i);
            else
#endif
                tex_cellular_lanes(c->cx, c->cy, c->cid, t0, e, lx, ly, nv, want_id, want_f2, 1,
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
