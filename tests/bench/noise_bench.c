/* noise_bench.c - M samples/s of libtex noise grids (2048 x 2048), built by tests/bench/noise.
 *
 *   noise_bench KIND THREADS REPS   KIND: 2d | 3d | fbm8 | ridged8 | turb8 | dnoise | points3d
 * prints the best of REPS fills in M samples/s (the best: other jobs share the machine). */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"

int main(int argc, char **argv)
{
    const char *kind = argc > 1 ? argv[1] : "2d";
    int threads = argc > 2 ? atoi(argv[2]) : 1, reps = argc > 3 ? atoi(argv[3]) : 5, n = 2048;
    const struct tex_primitive *p = strcmp(kind, "fbm8") == 0 || strcmp(kind, "ridged8") == 0
                                        ? &tex_prim_fractal
                                    : strcmp(kind, "turb8") == 0  ? &tex_prim_turbulence
                                    : strcmp(kind, "dnoise") == 0 ? &tex_prim_d_noise
                                                                  : &tex_prim_noise;
    struct tex_field *f = tex_field_new(p);
    double best = 0;

    omp_set_num_threads(threads);
    f->seed = 1;
    /* The same frequency as the libnoise run: 8 lattice cells across. */
    tex_field_set(f, "frequency", "8");
    if (strcmp(kind, "3d") == 0 || strcmp(kind, "points3d") == 0)
        tex_field_set(f, "z", "0.3721"); /* a slice between lattice planes: 8 corners */
    if (p == &tex_prim_fractal || p == &tex_prim_turbulence)
        tex_field_set(f, "octaves", "8");
    if (strcmp(kind, "ridged8") == 0)
        tex_field_set(f, "mode", "ridged");
    if (tex_field_init(f, strcmp(kind, "points3d") == 0 ? 0 : n, n) < 0) {
        fprintf(stderr, "noise_bench: %s\n", tex_errmsg());
        return 1;
    }
    tex_map *m = tex_map_new(n, n, f->nc);
    for (int r = 0; r < reps; r++) {
        double t0 = omp_get_wtime(), t1;
        if (strcmp(kind, "points3d") == 0) {
            /* Arbitrary points through eval3: the path solid textures take. */
            static double u[2048], v[2048], w[2048];
            static float out[2048];
            int rows = 256;
            for (int y = 0; y < rows; y++) {
                for (int x = 0; x < n; x++)
                    u[x] = (x + 0.5) / n, v[x] = (y + 0.5) / n, w[x] = 0.3721 + x * 1e-4;
                p->eval3(f, n, u, v, w, out);
            }
            t1 = omp_get_wtime();
            if (n * (double)rows / (t1 - t0) / 1e6 > best)
                best = n * (double)rows / (t1 - t0) / 1e6;
            continue;
        }
        /* The sampler's loop over the descriptor's rows, into a map made once:
         * a fresh 16 MiB map per fill would time the kernel's page faults. */
#pragma omp parallel for schedule(dynamic, 4)
        for (int y = 0; y < n; y++)
            p->row(f, y, tex_map_row(m, y));
        t1 = omp_get_wtime();
        if ((double)n * n / (t1 - t0) / 1e6 > best)
            best = (double)n * n / (t1 - t0) / 1e6;
    }
    printf("%.1f\n", best);
    tex_map_free(m);
    tex_field_free(f);
    return 0;
}
