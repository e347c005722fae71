/* noise_bench.c - M samples/s of libtex noise grids (2048 x 2048), built by tests/bench/noise.
 *
 *   noise_bench KIND THREADS REPS [CELLS]
 *   KIND: 2d | 3d | fbm8 | ridged8 | hybrid8 | turb8 | dnoise | points3d | points_turb6 |
 *         points_bubble3d
 * prints the median of REPS fills in M samples/s; CELLS: lattice cells across the map at
 * the first octave (8).  points*: arbitrary 3D points through eval3, 2048 per call
 * (points_bubble3d: solid bubbles around 1000 points, the primitive's nearest-point
 * search).
 * One thread is timed by its CPU time, so that other jobs on a shared machine do not
 * count; more threads by the wall clock. */

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "textura.h"

static double now(int threads)
{
    struct timespec t;
    if (threads > 1)
        return omp_get_wtime();
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    const char *kind = argc > 1 ? argv[1] : "2d";
    int threads = argc > 2 ? atoi(argv[2]) : 1, reps = argc > 3 ? atoi(argv[3]) : 5, n = 2048;
    const char *cells = argc > 4 ? argv[4] : "8";
    const struct tex_primitive *p = strcmp(kind, "fbm8") == 0 || strcmp(kind, "ridged8") == 0 ||
                                            strcmp(kind, "hybrid8") == 0
                                        ? &tex_prim_fractal
                                    : strncmp(kind, "turb", 4) == 0 ||
                                            strcmp(kind, "points_turb6") == 0
                                        ? &tex_prim_turbulence
                                    : strcmp(kind, "dnoise") == 0          ? &tex_prim_d_noise
                                    : strcmp(kind, "points_bubble3d") == 0 ? &tex_prim_bubble
                                                                           : &tex_prim_noise;
    struct tex_field *f = tex_field_new(p);
    double rate[64];
    int pts = strncmp(kind, "points", 6) == 0;

    omp_set_num_threads(threads);
    f->seed = 1;
    if (p == &tex_prim_bubble) {
        tex_field_set(f, "dimension", "3");
        tex_field_set(f, "count", "1000");
    } else {
        tex_field_set(f, "frequency", cells);
    }
    if (reps < 1 || reps > 64)
        reps = 5;
    if (strcmp(kind, "3d") == 0 || (pts && p != &tex_prim_bubble))
        tex_field_set(f, "z", "0.3721"); /* a slice between lattice planes: 8 corners */
    if (p == &tex_prim_fractal || p == &tex_prim_turbulence)
        tex_field_set(f, "octaves", pts ? "6" : "8");
    if (strcmp(kind, "ridged8") == 0)
        tex_field_set(f, "mode", "ridged");
    if (strcmp(kind, "hybrid8") == 0)
        tex_field_set(f, "mode", "hybrid");
    if (tex_field_init(f, pts ? 0 : n, pts ? 0 : n) < 0) {
        fprintf(stderr, "noise_bench: %s\n", tex_errmsg());
        return 1;
    }
    tex_map *m = tex_map_new(n, n, f->nc);
    for (int r = 0; r < reps; r++) {
        double t0 = now(threads), t1;
        if (pts) {
            /* Arbitrary points through eval3: the path solid textures take. */
            static double u[2048], v[2048], w[2048];
            static float out[2048];
            int rows = 256;
            for (int x = 0; x < n; x++) /* u and w are the same on every row */
                u[x] = (x + 0.5) / n, w[x] = 0.3721 + x * 1e-4;
            for (int y = 0; y < rows; y++) {
                double vy = (y + 0.5) / n;
                for (int x = 0; x < n; x++)
                    v[x] = vy;
                p->eval3(f, n, u, v, w, out);
            }
            t1 = now(threads);
            rate[r] = n * (double)rows / (t1 - t0) / 1e6;
            continue;
        }
        /* The sampler's rows, into a map made once: a fresh 16 MiB map per fill
         * would time the kernel's page faults. */
        if (tex_field_sample_rows(f, m) < 0)
            return 1;
        t1 = now(threads);
        rate[r] = (double)n * n / (t1 - t0) / 1e6;
    }
    for (int i = 1; i < reps; i++) /* the median: insertion sort */
        for (int k = i; k > 0 && rate[k - 1] > rate[k]; k--) {
            double t = rate[k];
            rate[k] = rate[k - 1];
            rate[k - 1] = t;
        }
    printf("%.1f\n", rate[reps / 2]);
    tex_map_free(m);
    tex_field_free(f);
    return 0;
}
