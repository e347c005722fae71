/* test_kdtree.c - tex_kdtree (FLANN's single kd-tree): exact k nearest against brute force
 * in 2 and 3 dimensions, float and double, nearest first; (1 + eps)-approximate neighbours
 * within their bound; radius searches find every point within the radius and no other,
 * capped at max; a search of a tree of the other type fails with a message. */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/kdtree.h"
#include "base/rng.h"
#include "unit.h"

enum { N = 4000, Q = 300, K = 5 };

static double d2_of(const double *a, const double *b, int dim)
{
    double s = 0;
    for (int j = 0; j < dim; j++)
        s += (a[j] - b[j]) * (a[j] - b[j]);
    return s;
}

/* the k-th smallest squared distance from q to the points, by sorting */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double kth(const double *p, const double *q, int dim, int k, double *tmp)
{
    for (int i = 0; i < N; i++)
        tmp[i] = d2_of(p + (size_t)i * dim, q, dim);
    qsort(tmp, N, sizeof *tmp, cmp_double);
    return tmp[k - 1];
}

/* knn in double: the distances are the brute force's k smallest, ascending, and each index's */
static void knn_double(const double *p, const double *q, int dim, double *tmp)
{
    tex_kdtree *t = tex_kdtree_new_d(p, N, dim, 8);
    int ind[Q * K], exact = 1, sorted = 1, consistent = 1;
    double d2[Q * K];
    CHECKF(t && tex_kdtree_knn_d(t, q, Q, K, 0, 1, ind, d2) == 0, "%dD double: tree and search",
           dim);
    for (int i = 0; t && i < Q; i++)
        for (int k = 0; k < K; k++) {
            const double *qi = q + (size_t)i * dim, *r = d2 + (size_t)i * K;
            exact &= r[k] == kth(p, qi, dim, k + 1, tmp);
            sorted &= k == 0 || r[k - 1] <= r[k];
            consistent &= d2_of(p + (size_t)ind[i * K + k] * dim, qi, dim) == r[k];
        }
    CHECKF(exact && sorted && consistent,
           "%dD double: the %d nearest of %d queries are brute force's, nearest first", dim, K, Q);
    tex_kdtree_free(t);
}

/* knn in float, exact and at eps 1: the approximate k-th is within (1 + eps)^2 in d2 */
static void knn_float(const double *p, const double *q, int dim, double *tmp)
{
    float *pf = malloc(sizeof *pf * N * dim), qf[Q * 3], d2[Q * K];
    double *pd = malloc(sizeof *pd * N * dim);
    int ind[Q * K], exact = 1, within = 1;
    for (int i = 0; i < N * dim; i++)
        pd[i] = pf[i] = (float)p[i];
    for (int i = 0; i < Q * dim; i++)
        qf[i] = (float)q[i];
    tex_kdtree *t = tex_kdtree_new_f(pf, N, dim, 10);
    CHECKF(t && tex_kdtree_knn_f(t, qf, Q, K, 0, 1, ind, d2) == 0, "%dD float: tree and search",
           dim);
    for (int i = 0; t && i < Q; i++) {
        double qd[3] = {qf[i * dim], qf[i * dim + 1], dim == 3 ? qf[i * dim + 2] : 0};
        /* float distances may order a near tie the other way: 1e-5 of slack */
        exact &= ind[i * K] >= 0 && d2_of(pd + (size_t)ind[i * K] * dim, qd, dim) <=
                                        kth(pd, qd, dim, 1, tmp) * (1 + 1e-5);
    }
    CHECKF(exact, "%dD float: each query's first neighbour is brute force's nearest", dim);
    CHECK(t && tex_kdtree_knn_f(t, qf, Q, K, 1, 1, ind, d2) == 0, "a search at eps 1");
    for (int i = 0; t && i < Q; i++) {
        double qd[3] = {qf[i * dim], qf[i * dim + 1], dim == 3 ? qf[i * dim + 2] : 0};
        within &= d2_of(pd + (size_t)ind[i * K] * dim, qd, dim) <=
                  4 * kth(pd, qd, dim, 1, tmp) * (1 + 1e-5);
    }
    CHECKF(within, "%dD float, eps 1: each first neighbour within twice the nearest's distance",
           dim);
    tex_kdtree_free(t);
    free(pf);
    free(pd);
}

/* every point within r2 found once, no other; at most max */
static void radius(const double *p, const double *q)
{
    tex_kdtree *t = tex_kdtree_new_d(p, N, 3, 8);
    int ind[N], all = 1, capped = 1;
    double d2[N];
    for (int i = 0; t && i < 40; i++) {
        const double *qi = q + (size_t)i * 3;
        int want = 0, got = tex_kdtree_radius_d(t, qi, 0.01f, N, ind, d2), ok = got >= 0;
        char *seen = calloc(N, 1);
        for (int j = 0; j < N; j++)
            want += d2_of(p + (size_t)j * 3, qi, 3) <= 0.01f;
        for (int k = 0; ok && k < got; k++) {
            ok &= !seen[ind[k]] && d2_of(p + (size_t)ind[k] * 3, qi, 3) <= 0.01f;
            seen[ind[k]] = 1;
        }
        all &= ok && got == want;
        capped &= tex_kdtree_radius_d(t, qi, 0.01f, 3, ind, d2) == (want < 3 ? want : 3);
        free(seen);
    }
    CHECK(t && all, "radius searches: every point within the radius, once, and no other");
    CHECK(capped, "radius searches stop at max");
    tex_kdtree_free(t);
}

int main(void)
{
    double *p = malloc(sizeof *p * N * 3), q[Q * 3], *tmp = malloc(sizeof *tmp * N);
    tex_rng r;
    tex_rng_seed(&r, 11);
    for (int i = 0; i < N * 3; i++) /* clustered: a third of the points near one corner */
        p[i] = i % 9 < 3 ? 0.1 * tex_rng_uniform(&r) : tex_rng_uniform(&r);
    for (int i = 0; i < Q * 3; i++)
        q[i] = 1.2 * tex_rng_uniform(&r) - 0.1;
    knn_double(p, q, 2, tmp);
    knn_double(p, q, 3, tmp);
    knn_float(p, q, 2, tmp);
    knn_float(p, q, 3, tmp);
    radius(p, q);
    tex_kdtree *t = tex_kdtree_new_d(p, N, 3, 8);
    float qf[3] = {0.5f, 0.5f, 0.5f}, df;
    int i1;
    CHECKF(t && tex_kdtree_knn_f(t, qf, 1, 1, 0, 1, &i1, &df) < 0 && strstr(tex_errmsg(), "type"),
           "a float search of a double tree fails: %s", tex_errmsg());
    tex_kdtree_free(t);
    tex_kdtree_free(NULL);
    free(p);
    free(tmp);
    return unit_done();
}
