/* synth_bench.c - time of libtex's texture synthesis (ops/synth.c)
 *
 *   synth_bench SAMPLE SIZE THREADS RUNS [coherent|exhaustive]
 * synthesises a SIZE x SIZE map from SAMPLE with the default options on
 * THREADS OpenMP threads, RUNS times, and prints the median wall seconds and
 * the median CPU seconds of the process (all threads) of one synthesis,
 * reading excluded.  "exhaustive" tries every sample position for every
 * pixel (Wei and Levoy's full search): the brute-force baseline. */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/error.h"
#include "io/file.h"
#include "ops/synth.h"

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc != 5 && argc != 6) {
        fprintf(stderr, "usage: synth_bench SAMPLE SIZE THREADS RUNS [coherent|exhaustive]\n");
        return 2;
    }
    int size = atoi(argv[2]), threads = atoi(argv[3]), runs = atoi(argv[4]);
    struct tex_synth_opts o = TEX_SYNTH_DEFAULTS;
    tex_map *s = tex_map_read(argv[1]);
    double *wall = malloc(runs * sizeof *wall), *cpu = malloc(runs * sizeof *cpu);

    if (!s || !wall || !cpu || runs < 1) {
        fprintf(stderr, "synth_bench: %s\n", tex_errmsg());
        return 1;
    }
    if (argc == 6 && !strcmp(argv[5], "exhaustive"))
        o.search = TEX_SYNTH_EXHAUSTIVE;
    omp_set_num_threads(threads);
    for (int r = 0; r < runs; r++) {
        double t0 = omp_get_wtime(), c0 = cpu_now();
        tex_map *m = tex_synth(s, size, size, &o, NULL, NULL);
        wall[r] = omp_get_wtime() - t0;
        cpu[r] = cpu_now() - c0;
        if (!m) {
            fprintf(stderr, "synth_bench: %s\n", tex_errmsg());
            return 1;
        }
        tex_map_free(m);
    }
    qsort(wall, runs, sizeof *wall, cmp);
    qsort(cpu, runs, sizeof *cpu, cmp);
    printf("%.3f %.3f\n", wall[runs / 2], cpu[runs / 2]);
    tex_map_free(s);
    free(wall);
    free(cpu);
    return 0;
}
