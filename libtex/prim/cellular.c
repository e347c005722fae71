/* cellular.c - nearest-point queries: the structure, brute force and the dispatch (cellular.h) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/kdtree.h"
#include "prim/cellular.h"
#include "prim/cellular_impl.h"

int tex_metric_parse_as(const char *text, const char *name, enum tex_metric *m, double *p)
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
        if (end == text + 10 || *end || !(v >= 1 && v <= TEX_METRIC_P_MAX))
            return tex_usage_error("%s minkowski:P needs P in 1..%d (got '%s')", name,
                                   TEX_METRIC_P_MAX, text);
        *m = TEX_METRIC_MINKOWSKI;
        *p = v;
    } else
        return tex_usage_error("%s must be euclid|manhattan|chebyshev|minkowski:P (got '%s')",
                               name, text);
    return 0;
}

int tex_metric_parse(const char *text, enum tex_metric *m, double *p)
{
    return tex_metric_parse_as(text, "the metric", m, p);
}

void tex_cellular_brute(const struct tex_cellular *c, const double *q, struct best *b)
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
    tex_cellular_tree_free(c);
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
        double e = tex_cellular_empty_share(c);
        if (e < 0)
            goto oom;
        c->search = e < 0.3 ? TEX_SEARCH_GRID : TEX_SEARCH_KDTREE;
    }
    if (c->search == TEX_SEARCH_GRID) {
        if (tex_cellular_grid_build(c) < 0)
            goto fail;
        /* Candidate lists pay for themselves over many queries per cell; for far
         * more points than queries (10^7 points, a 256^2 map) they would cost
         * most of the time and memory, and the grid answers alike. */
        if (c->search == TEX_SEARCH_GRID && dim == 2 && c->metric == TEX_METRIC_EUCLID &&
            !c->ia && !(o->queries > 0 && c->n / CAND_FILL > 4.0 * o->queries) &&
            tex_cellular_cand_build(c) < 0)
            goto fail;
    }
    if (c->search == TEX_SEARCH_KDTREE &&
        (tex_cellular_kdtree_build(c) < 0 ||
         (dim == 2 && c->n <= TREE_NMAX && !getenv("TEXTURA_BUBBLE_NO_TREE") &&
          tex_cellular_tree_build(c) < 0)))
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
        tex_cellular_cand_query(c, n, q, f1, f2, id);
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
            c->at ? tex_cellular_tree_query(c, m, qb, b, id != NULL, f2 != NULL)
                  : tex_cellular_kdtree_query(c, m, qb, b);
        else
            for (int i = 0; i < m; i++) {
                const double *qi = qb + i * dim;
                if (c->search == TEX_SEARCH_GRID)
                    tex_cellular_grid_query(c, qi, b + i);
                else
                    tex_cellular_brute(c, qb + i * dim, b + i);
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
