/* bubble_bench.c - nearest-point query throughput of libtex/cellular.c
 *
 *   bubble_bench SIZE N DIST SEARCH THREADS RUNS [f1|f2]
 * queries every pixel centre of a SIZE x SIZE map against N points of
 * distribution DIST (uniform|poisson|cluster) with SEARCH (auto|grid|kdtree|
 * brute), rows split over THREADS OpenMP threads as the sampler does, and
 * prints the median M queries/s of RUNS runs (set-up excluded) and the
 * set-up time (wall and CPU).  With SEARCH brute only every 64th row is queried.
 * Two rates: by wall time, and by the CPU time the threads spent (per core,
 * CLOCK_THREAD_CPUTIME_ID), which a busy shared machine distorts less. */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "prim/cellular.h"

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    if (argc != 7 && argc != 8) {
        fprintf(stderr, "usage: bubble_bench SIZE N DIST SEARCH THREADS RUNS [f1|f2]\n");
        return 2;
    }
    int size = atoi(argv[1]), threads = atoi(argv[5]), runs = atoi(argv[6]);
    long n = atol(argv[2]);
    const char *dists[] = {"uniform", "poisson", "cluster"}, *searches[] = {"auto", "grid", "kdtree", "brute"};
    int dist = 0, search = 0;
    for (int i = 0; i < 3; i++)
        if (!strcmp(argv[3], dists[i]))
            dist = i;
    for (int i = 0; i < 4; i++)
        if (!strcmp(argv[4], searches[i]))
            search = i;
    int want_f2 = !(argc == 8 && !strcmp(argv[7], "f1"));
    int step = search == TEX_SEARCH_BRUTE ? 64 : 1;
    tex_points ps;
    if (tex_points_random(&ps, 2, n, dist, 0, 1, 0) < 0)
        return 1;
    struct tex_cellular_opts o = {TEX_METRIC_EUCLID, 2, 0, search, 0};
    struct timespec c0, c1;
    double t0 = omp_get_wtime();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
    tex_cellular *c = tex_cellular_new(&ps, &o);
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
    double setup = omp_get_wtime() - t0;
    double setup_cpu = (c1.tv_sec - c0.tv_sec) + 1e-9 * (c1.tv_nsec - c0.tv_nsec);
    if (!c)
        return 1;
    double *t = malloc(runs * sizeof *t), *cpu = malloc(runs * sizeof *cpu), sink = 0;
    omp_set_num_threads(threads);
    for (int r = 0; r < runs; r++) {
        double s = omp_get_wtime(), used = 0;
#pragma omp parallel reduction(+ : sink, used)
        {
            struct timespec a, b;
            clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
            double *q = malloc(2 * size * sizeof *q), *f1 = malloc(size * sizeof *f1),
                   *f2 = malloc(size * sizeof *f2);
#pragma omp for schedule(dynamic, 4)
            for (int y = 0; y < size; y += step) {
                for (int x = 0; x < size; x++) {
                    q[2 * x] = (x + 0.5) / size;
                    q[2 * x + 1] = (y + 0.5) / size;
                }
                tex_cellular_query(c, size, q, f1, want_f2 ? f2 : NULL, NULL);
                sink += f1[size / 2] + (want_f2 ? f2[size / 3] : 0);
            }
            clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
            used += (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec);
            free(q);
            free(f1);
            free(f2);
        }
        t[r] = omp_get_wtime() - s;
        cpu[r] = used;
    }
    qsort(t, runs, sizeof *t, cmp);
    qsort(cpu, runs, sizeof *cpu, cmp);
    double rows = (size + step - 1) / step;
    printf("wall %.4g M/s cpu %.4g M/s/core setup %.3f s setup_cpu %.3f s search %s (%.3g)\n",
           rows * size / t[runs / 2] / 1e6, rows * size / cpu[runs / 2] / 1e6, setup, setup_cpu,
           searches[tex_cellular_search(c)], sink);
    tex_cellular_free(c);
    tex_points_free(&ps);
    free(t);
    free(cpu);
    return 0;
}
