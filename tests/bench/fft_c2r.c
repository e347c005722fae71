/* fft_c2r - the peer of t_ifft in tests/bench/fft: a bare FFTW complex-to-real
 * inverse transform of an H x W spectrum, single precision, ESTIMATE planner,
 * FFTW threads (one per core), no I/O.  Usage: fft_c2r W H */
#include <fftw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

int main(int argc, char **argv)
{
    int w = argc > 1 ? atoi(argv[1]) : 4096, h = argc > 2 ? atoi(argv[2]) : w, hw = w / 2 + 1;
    size_t nc = (size_t)h * hw;
    fftwf_complex *in;
    float *out;
    fftwf_plan p;
    double sum = 0;

    fftwf_init_threads();
    fftwf_plan_with_nthreads((int)sysconf(_SC_NPROCESSORS_ONLN));
    in = fftwf_alloc_complex(nc);
    out = fftwf_alloc_real((size_t)w * h);
    if (!in || !out)
        return 1;
    p = fftwf_plan_dft_c2r_2d(h, w, in, out, FFTW_ESTIMATE);
    for (size_t i = 0; i < nc; i++) {
        in[i][0] = (float)(i % 7) - 3.0f;
        in[i][1] = (float)(i % 5) - 2.0f;
    }
    fftwf_execute(p);
    for (int i = 0; i < w; i++)
        sum += out[i];
    printf("%g\n", sum); /* keeps the transform from being optimised away */
    fftwf_destroy_plan(p);
    fftwf_free(in);
    fftwf_free(out);
    return 0;
}
