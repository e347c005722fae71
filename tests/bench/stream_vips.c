/* stream_vips - the libvips peer of tests/bench/stream's jobs (issue 58).
 *
 *   stream_vips 4stage N   vips_perlin (cell N/8), vips_linear to three bands (a two-colour
 *                          ramp), vips_gaussblur at sigma 2 in float, vips_stats: the job
 *                          `t_noise -s N -f 8 | t_palette RAMP | t_filter blur --sigma 2 | t_info`
 *   stream_vips op N       two vips_perlin of different seeds added, then shifted by a
 *                          quarter of the map with wrap-around (vips_wrap), vips_stats: the job
 *                          `t_op add <(t_noise) <(t_noise) | t_xform shift | t_info`
 *
 * libvips is demand-driven and threaded: vips_stats pulls the rows through the chain, and
 * only the tiles its operations need are held. Prints the mean of the first band, so that
 * the computation cannot be optimised away. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vips/vips.h>

static VipsImage *job_4stage(VipsObject *scope, int n)
{
    VipsImage **t = (VipsImage **)vips_object_local_array(scope, 3);
    double a[3] = {0.8, 0.3, 0.1}, b[3] = {0.1, 0.2, 0.6};

    if (vips_perlin(&t[0], n, n, "cell_size", n / 8, "seed", 1, NULL) ||
        vips_linear(t[0], &t[1], a, b, 3, NULL) ||
        vips_gaussblur(t[1], &t[2], 2.0, "precision", VIPS_PRECISION_FLOAT, NULL))
        return NULL;
    return t[2];
}

static VipsImage *job_op(VipsObject *scope, int n)
{
    VipsImage **t = (VipsImage **)vips_object_local_array(scope, 4);

    if (vips_perlin(&t[0], n, n, "cell_size", n / 8, "seed", 1, NULL) ||
        vips_perlin(&t[1], n, n, "cell_size", n / 8, "seed", 2, NULL) ||
        vips_add(t[0], t[1], &t[2], NULL) ||
        vips_wrap(t[2], &t[3], "x", n / 4, "y", n / 4, NULL))
        return NULL;
    return t[3];
}

int main(int argc, char **argv)
{
    if (argc != 3 || (strcmp(argv[1], "4stage") && strcmp(argv[1], "op"))) {
        fprintf(stderr, "usage: stream_vips 4stage|op N\n");
        return 2;
    }
    int n = atoi(argv[2]);
    if (n < 8 || n > 1 << 20) {
        fprintf(stderr, "stream_vips: N %s out of range [8, 1048576]\n", argv[2]);
        return 2;
    }
    if (VIPS_INIT(argv[0]))
        vips_error_exit(NULL);
    VipsObject *scope = VIPS_OBJECT(vips_image_new());
    VipsImage *last = strcmp(argv[1], "op") ? job_4stage(scope, n) : job_op(scope, n);
    VipsImage *stats = NULL;
    if (!last || vips_stats(last, &stats, NULL))
        vips_error_exit(NULL);
    double mean = *VIPS_MATRIX(stats, 4, 1);
    printf("%s %d mean %.6g\n", argv[1], n, mean);
    g_object_unref(stats);
    g_object_unref(scope);
    vips_shutdown();
    return 0;
}
