/* cellular_impl.h - the insides of the nearest-point queries (cellular.h), shared by their files
 *
 * Internal to libtex (not installed).  The query structure is one struct,
 * built by tex_cellular_new (cellular.c) with the search its method needs:
 *   cellular.c         the structure, brute force, the dispatch of queries
 *   cellular_grid.c    grid buckets, and the candidate lists of 2D Euclidean sets
 *   cellular_kdtree.c  FLANN's kd-tree over the points and their periodic images
 *   cellular_tree.c    the adaptive tree of boxes over the unit square
 *   x86/cellular_x86.c the candidate lists' lanes in AVX2
 * Every method computes its final candidates' distances with acc_point_m and
 * keeps the two nearest with best_add, so all give the same bytes.
 */
#ifndef TEX_CELLULAR_IMPL_H
#define TEX_CELLULAR_IMPL_H

#include <math.h>
#include <stdlib.h>

#include "../base/kdtree.h"
#include "../base/simd.h"
#include "cellular.h"

/* p grown to n elements of size bytes, or p itself with *ok cleared when that
 * fails (or an earlier call failed): parallel arrays grow together and the
 * caller reports once. */
static inline void *grown(void *p, size_t n, size_t size, int *ok)
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

static inline double wrap1(double x)
{
    x -= floor(x);
    return x < 1.0 ? x : 0.0; /* -tiny - floor(-tiny) rounds to 1 */
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

static inline int cell_of(double x, int g)
{
    double t = x * g;
    if (!(t >= 0))
        return 0;
    return t >= g ? g - 1 : (int)t;
}

/* Candidate lists' points per bucket on average (cellular_grid.c) */
#ifndef CAND_FILL
#define CAND_FILL 0.15
#endif
/* The adaptive tree serves 2D sets of at most this many points (cellular_tree.c) */
#define TREE_NMAX 2000000

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


/* tex_metric_parse, its messages naming the parameter name ("--metric") */
int tex_metric_parse_as(const char *text, const char *name, enum tex_metric *m, double *p);

/* Brute force: every point (and its 3^dim periodic images) */
void tex_cellular_brute(const struct tex_cellular *c, const double *q, struct best *b);

/* Grid buckets (cellular_grid.c): the share of empty buckets on a grid of two points per
 * bucket (-1: out of memory), the buckets, the two nearest to q through them; candidate
 * lists of 2D Euclidean sets without radii, and n queries through them */
double tex_cellular_empty_share(const struct tex_cellular *c);
int tex_cellular_grid_build(struct tex_cellular *c);
void tex_cellular_grid_query(const struct tex_cellular *c, const double *q, struct best *b);
int tex_cellular_cand_build(struct tex_cellular *c);
void tex_cellular_cand_query(const struct tex_cellular *c, int n, const double *q, double *f1,
                             double *f2, long *id);
/* Up to 16 queries (qx, qy; nv vectors of four) against the list entries t0..e-1 of cx, cy,
 * cid: a1 (and a2, i1 if wanted) as best_add gives them, squared or, with roots, roots */
void tex_cellular_lanes(const double *cx, const double *cy, const long *cid, long t0, long e,
                        const double *qx, const double *qy, int nv, int want_id, int want_f2,
                        int roots, double *a1, double *a2, long *i1);

/* The kd-tree (cellular_kdtree.c): built over the points and their periodic images within a
 * margin; n queries (wrapped, finite) into b */
int tex_cellular_kdtree_build(struct tex_cellular *c);
void tex_cellular_kdtree_query(const struct tex_cellular *c, int n, const double *q,
                               struct best *b);

/* The adaptive tree of boxes (cellular_tree.c), over a kd-tree: 0 also when over its budget
 * (c->at stays 0 and the queries go to the kd-tree) */
int tex_cellular_tree_build(struct tex_cellular *c);
void tex_cellular_tree_query(const struct tex_cellular *c, int n, const double *q, struct best *b,
                             int want_id, int want_f2);
void tex_cellular_tree_free(struct tex_cellular *c);

#endif
