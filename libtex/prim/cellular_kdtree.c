/* cellular_kdtree.c - nearest points through FLANN's kd-tree, for any set and metric */
#define _GNU_SOURCE /* qsort_r */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/kdtree.h"
#include "prim/cellular_impl.h"

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

/* Reps i and j (indices into c->rep) at the same place with the same radii: every
 * query finds them at the same distance, bit for bit. */
static int rep_place_cmp(const struct tex_cellular *c, long i, long j)
{
    for (int d = 0; d < c->dim; d++) {
        double x = c->rep[i * c->dim + d], y = c->rep[j * c->dim + d];
        if (x != y)
            return x < y ? -1 : 1;
    }
    for (int d = 0; c->ia && d < c->dim; d++) {
        double x = c->ia[c->repid[i] * c->dim + d], y = c->ia[c->repid[j] * c->dim + d];
        if (x != y)
            return x < y ? -1 : 1;
    }
    return 0;
}

/* By place, then by point id */
static int rep_cmp(const void *a, const void *b, void *arg)
{
    const struct tex_cellular *c = arg;
    long i = *(const long *)a, j = *(const long *)b;
    int k = rep_place_cmp(c, i, j);
    return k ? k : (c->repid[i] > c->repid[j]) - (c->repid[i] < c->repid[j]);
}

/* Coincident points (10^4 copies of one): FLANN then visits every leaf for
 * every query, and the candidate tree splits to its depth everywhere, for a
 * minute and more.  best_add keeps the nearest's distance and lowest id and
 * the second distance, so of reps at one place with the same radii the two
 * of lowest id give the same answers as all of them: the others go, the
 * order of those kept stays.  Equal reps share a Morton key, so only runs
 * of one key are compared; a set without coincident points is unchanged.
 * Returns the number of reps kept, now m's first entries. */
static long rep_dedup(const struct tex_cellular *c, struct morton *m, long n)
{
    long *run = NULL, cap = 0, kept = 0;
    unsigned char *drop = NULL;
    for (long r0 = 0, r1; r0 < n; r0 = r1) {
        for (r1 = r0 + 1; r1 < n && m[r1].key == m[r0].key; r1++)
            ;
        if (r1 - r0 < 3)
            continue;
        if (r1 - r0 > cap) {
            long *g = realloc(run, (r1 - r0) * sizeof *run);
            if (!g)
                break; /* keep them all: slower, the same answers */
            run = g, cap = r1 - r0;
        }
        if (!drop && !(drop = calloc(n, 1)))
            break;
        for (long i = r0; i < r1; i++)
            run[i - r0] = m[i].at;
        qsort_r(run, r1 - r0, sizeof *run, rep_cmp, (void *)c);
        for (long i = 2; i < r1 - r0; i++)
            drop[run[i]] = !rep_place_cmp(c, run[i], run[i - 2]);
    }
    for (long i = 0; i < n; i++)
        if (!drop || !drop[m[i].at])
            m[kept++] = m[i];
    free(run);
    free(drop);
    return kept;
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
    n = rep_dedup(c, m, n);
    for (long i = 0; i < n; i++) {
        memcpy(rep + i * dim, c->rep + m[i].at * dim, dim * sizeof *rep);
        repid[i] = c->repid[m[i].at];
        shift[i] = c->repshift[m[i].at];
    }
    free(c->rep), free(c->repid), free(c->repshift), free(m);
    c->rep = rep;
    c->repid = repid;
    c->repshift = shift;
    c->nrep = n;
    return 0;
}

int tex_cellular_kdtree_build(struct tex_cellular *c)
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

void tex_cellular_kdtree_query(const struct tex_cellular *c, int n, const double *q, struct best *b)
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
        tex_cellular_brute(c, q + (size_t)at * dim, b + at);
    }
    free(pend);
    free(qb);
    free(ind);
    free(dist);
}
