/* test_cellular.c - every search method against brute force, point sets */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "prim/cellular.h"
#include "base/rng.h"
#include "base/simd.h"
#include "unit.h"

/* Compare grid and kd-tree with brute force on nq random queries; returns
 * the number of mismatches (f1, f2 bit for bit, and the nearest index). */
static int compare(const tex_points *ps, enum tex_metric m, double p, int tile, int nq,
                   uint64_t seed, int *chosen_grid)
{
    int dim = ps->dim, bad = 0;
    struct tex_cellular_opts o = {m, p, tile, TEX_SEARCH_BRUTE, 0};
    tex_cellular *ref = tex_cellular_new(ps, &o), *c[4];
    double *q = malloc(sizeof *q * nq * dim), *r1 = malloc(sizeof *r1 * nq),
           *r2 = malloc(sizeof *r2 * nq), *f1 = malloc(sizeof *f1 * nq),
           *f2 = malloc(sizeof *f2 * nq);
    long *rid = malloc(sizeof *rid * nq), *id = malloc(sizeof *id * nq);
    tex_rng rng;

    o.search = TEX_SEARCH_GRID;
    c[0] = tex_cellular_new(ps, &o);
    o.search = TEX_SEARCH_KDTREE;
    c[1] = tex_cellular_new(ps, &o);
    o.search = TEX_SEARCH_AUTO;
    c[2] = tex_cellular_new(ps, &o);
    /* The grid without candidate lists: a caller that will ask few points. */
    o.search = TEX_SEARCH_GRID;
    o.queries = 1;
    c[3] = tex_cellular_new(ps, &o);
    if (!ref || !c[0] || !c[1] || !c[2] || !c[3] || !q || !r1 || !r2 || !f1 || !f2 || !rid || !id)
        return -1;
    *chosen_grid = tex_cellular_search(c[2]) == TEX_SEARCH_GRID;
    tex_rng_seed(&rng, seed);
    for (int pattern = 0; pattern < 2; pattern++) {
        int nr = pattern == 0 ? nq : nq / 2;
        if (pattern == 0) {
            /* Mostly inside the unit square, some beyond it (solid textures, files). */
            for (int i = 0; i < nq * dim; i++)
                q[i] = i % 7 == 0 ? 3 * tex_rng_uniform(&rng) - 1 : tex_rng_uniform(&rng);
        } else {
            /* Rows of pixel centres, as the sampler asks: neighbouring queries
             * share buckets and kd-tree runs; the rows overhang the square a
             * little (seams when tiling). */
            int w = 97;
            double z = tex_rng_uniform(&rng);
            for (int i = 0; i < nr; i++) {
                q[i * dim] = -0.15 + 1.3 * (i % w + 0.5) / w;
                q[i * dim + 1] = -0.15 + 1.3 * (i / w + 0.5) / ((nr + w - 1) / w);
                if (dim == 3)
                    q[i * dim + 2] = z;
            }
        }
        tex_cellular_query(ref, nr, q, r1, r2, rid);
        for (int k = 0; k < 4; k++) {
            tex_cellular_query(c[k], nr, q, f1, f2, id);
            for (int i = 0; i < nr; i++)
                bad += f1[i] != r1[i] || f2[i] != r2[i] || id[i] != rid[i];
            /* F1 alone, F1 with the index, and F1 with F2 but without the index. */
            tex_cellular_query(c[k], nr, q, f1, NULL, NULL);
            for (int i = 0; i < nr; i++)
                bad += f1[i] != r1[i];
            tex_cellular_query(c[k], nr, q, f1, NULL, id);
            for (int i = 0; i < nr; i++)
                bad += f1[i] != r1[i] || id[i] != rid[i];
            tex_cellular_query(c[k], nr, q, f1, f2, NULL);
            for (int i = 0; i < nr; i++)
                bad += f1[i] != r1[i] || f2[i] != r2[i];
            /* One query at a time gives the same as batches (any thread split). */
            for (int i = 0; i < nr; i += 37) {
                double a, b;
                long j;
                tex_cellular_query(c[k], 1, q + i * dim, &a, &b, &j);
                bad += a != r1[i] || b != r2[i] || j != rid[i];
            }
        }
    }
    for (int k = 0; k < 4; k++)
        tex_cellular_free(c[k]);
    tex_cellular_free(ref);
    free(q), free(r1), free(r2), free(f1), free(f2), free(rid), free(id);
    return bad;
}

static const char *const dists[] = {"uniform", "poisson", "cluster"};

/* Every search against brute force: 2D and 3D, three distributions, plain and tiled,
 * with and without radii, five metrics; then the baseline kernels. */
static void test_searches(void)
{
    static const char *metrics[] = {"euclid", "manhattan", "chebyshev", "minkowski:3",
                                    "minkowski:1.5"};

    for (int dim = 2; dim <= 3; dim++)
        for (int d = 0; d < 3; d++)
            for (int tile = 0; tile <= 1; tile++)
                for (int radii = 0; radii <= 1; radii++) {
                    tex_points ps;
                    long n = d == 2 ? 600 : 250;
                    int grid = 0;
                    if (tex_points_random(&ps, dim, n, d, 0, 11 + d, tile) < 0 ||
                        (radii && tex_points_vary(&ps, 0.5, 0.4, 5) < 0)) {
                        CHECK(0, "points generated");
                        continue;
                    }
                    for (int m = 0; m < 5; m++) {
                        enum tex_metric metric;
                        double p;
                        tex_metric_parse(metrics[m], &metric, &p);
                        /* Minkowski's pow makes brute force over 27 tiled copies
                         * the suite's costliest reference: fewer queries there */
                        int nq = m >= 3 ? 200 : 400;
                        int bad = compare(&ps, metric, p, tile, nq, 100 + m, &grid);
                        CHECKF(bad == 0,
                               "%dD %s%s%s %s: grid, kd-tree and auto equal brute force "
                               "(%d mismatches)",
                               dim, dists[d], tile ? " tiled" : "", radii ? " with radii" : "",
                               metrics[m], bad);
                    }
                    if (!radii && !tile && d < 2)
                        CHECKF(grid, "auto picks the grid for %dD %s points", dim, dists[d]);
                    tex_points_free(&ps);
                }

    /* The baseline (SSE2) kernels where the CPU would take the AVX2 ones:
     * the grid's candidate lists and the box tree, plain and tiled. */
    tex_simd_limit(TEX_SIMD_SCALAR);
    for (int d = 0; d < 3; d++)
        for (int tile = 0; tile <= 1; tile++) {
            tex_points ps;
            int grid = 0;
            if (tex_points_random(&ps, 2, d == 2 ? 600 : 250, d, 0, 21 + d, tile) < 0) {
                CHECK(0, "points generated");
                continue;
            }
            int bad = compare(&ps, TEX_METRIC_EUCLID, 2, tile, 400, 40 + d, &grid);
            CHECKF(bad == 0, "2D %s%s euclid, baseline kernels: equal brute force (%d)",
                   dists[d], tile ? " tiled" : "", bad);
            tex_points_free(&ps);
        }
    tex_simd_limit(TEX_SIMD_AVX512);
}

/* Sets that push the search choice and the ties. */
static void test_degenerate_sets(void)
{
    /* Five tight clusters: auto leaves the grid to FLANN's kd-tree. */
    {
        tex_points ps;
        int grid = 1;
        tex_points_random(&ps, 2, 2000, TEX_POINTS_CLUSTER, 5, 7, 0);
        for (long i = 0; i < ps.n * 2; i++) /* tighten them */
            ps.x[i] = 0.5 + 0.1 * (ps.x[i] - 0.5);
        CHECKF(compare(&ps, TEX_METRIC_EUCLID, 2, 0, 400, 8, &grid) == 0 && !grid,
               "tight clusters: auto picks the kd-tree, and it is exact");
        tex_points_free(&ps);
    }

    /* Tiny and degenerate sets: one point, coincident points, a lattice (ties). */
    {
        double one[2] = {0.3, 0.6}, same[6] = {0.5, 0.5, 0.5, 0.5, 0.2, 0.9}, lat[2 * 64];
        tex_points a = {2, 1, one, NULL}, b = {2, 3, same, NULL}, l = {2, 64, lat, NULL};
        int g;
        for (int i = 0; i < 64; i++)
            lat[2 * i] = (i % 8 + 0.5) / 8, lat[2 * i + 1] = (i / 8 + 0.5) / 8;
        for (int tile = 0; tile <= 1; tile++) {
            CHECKF(compare(&a, TEX_METRIC_EUCLID, 2, tile, 300, 1, &g) == 0,
                   "one point%s: all searches agree", tile ? " tiled" : "");
            CHECKF(compare(&b, TEX_METRIC_MANHATTAN, 1, tile, 300, 2, &g) == 0,
                   "coincident points%s: all searches agree", tile ? " tiled" : "");
            CHECKF(compare(&l, TEX_METRIC_EUCLID, 2, tile, 600, 3, &g) == 0,
                   "a lattice with ties%s: all searches agree", tile ? " tiled" : "");
            CHECKF(compare(&l, TEX_METRIC_CHEBYSHEV, 2, tile, 600, 4, &g) == 0,
                   "a lattice, Chebyshev%s: all searches agree", tile ? " tiled" : "");
        }
        /* One point without tile has no F2. */
        struct tex_cellular_opts o = {TEX_METRIC_EUCLID, 2, 0, TEX_SEARCH_AUTO, 0};
        tex_cellular *c = tex_cellular_new(&a, &o);
        double q[2] = {0.3, 0.6}, f1, f2;
        tex_cellular_query(c, 1, q, &f1, &f2, NULL);
        CHECKF(f1 == 0 && isinf(f2), "one point: F1 0 at the point, F2 infinite (%g %g)", f1, f2);
        tex_cellular_free(c);
    }
}

/* The point generators: spacing, range, seeds. */
static void test_point_sets(void)
{
    /* Poisson-disk points keep their distance; cluster and uniform stay in [0,1). */
    for (int dim = 2; dim <= 3; dim++) {
        tex_points ps;
        long n = 2000;
        double cover = dim == 2 ? 0.35 : 0.2;
        double r = dim == 2 ? 2 * sqrt(cover / (M_PI * n)) : 2 * cbrt(cover * 3 / (4 * M_PI * n));
        double dmin = INFINITY;
        int inside = 1;
        tex_points_random(&ps, dim, n, TEX_POINTS_POISSON, 0, 3, 0);
        for (long i = 0; i < n; i++)
            for (long j = i + 1; j < n; j++) {
                double d2 = 0;
                for (int k = 0; k < dim; k++)
                    d2 += (ps.x[i * dim + k] - ps.x[j * dim + k]) *
                          (ps.x[i * dim + k] - ps.x[j * dim + k]);
                dmin = d2 < dmin ? d2 : dmin;
            }
        CHECKF(sqrt(dmin) >= r, "%dD Poisson-disk: closest pair %g >= r = %g", dim, sqrt(dmin), r);
        tex_points_free(&ps);
        for (int d = 0; d < 3; d += 2) {
            tex_points_random(&ps, dim, n, d, 0, 4, 0);
            for (long i = 0; i < n * dim; i++)
                inside &= ps.x[i] >= 0 && ps.x[i] < 1;
            tex_points_free(&ps);
        }
        CHECKF(inside, "%dD uniform and cluster points lie in [0,1)", dim);
    }

    /* Same seed, same points; another seed, other points. */
    {
        tex_points a, b, c;
        tex_points_random(&a, 2, 100, TEX_POINTS_CLUSTER, 0, 9, 0);
        tex_points_random(&b, 2, 100, TEX_POINTS_CLUSTER, 0, 9, 0);
        tex_points_random(&c, 2, 100, TEX_POINTS_CLUSTER, 0, 10, 0);
        CHECK(memcmp(a.x, b.x, 200 * sizeof *a.x) == 0, "a seed gives the same points");
        CHECK(memcmp(a.x, c.x, 200 * sizeof *a.x) != 0, "another seed gives other points");
        tex_points_free(&a), tex_points_free(&b), tex_points_free(&c);
    }
}

static void test_metric_names(void)
{
    /* Metric names. */
    {
        enum tex_metric m;
        double p;
        CHECK(tex_metric_parse("minkowski:2.5", &m, &p) == 0 && m == TEX_METRIC_MINKOWSKI &&
                  p == 2.5,
              "minkowski:2.5 parses");
        CHECK(tex_metric_parse("minkowski:0.5", &m, &p) < 0, "minkowski:0.5 is refused");
        CHECK(tex_metric_parse("minkowski:", &m, &p) < 0, "minkowski: without P is refused");
        CHECK(tex_metric_parse("cosine", &m, &p) < 0, "an unknown metric is refused");
    }
}

int main(void)
{
    test_searches();
    test_degenerate_sets();
    test_point_sets();
    test_metric_names();
    return unit_done();
}
