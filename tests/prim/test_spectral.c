/* test_spectral - the frequency-domain module: transforms, Hermitian
 * completion, fBm slope, anisotropy, band, sparse convolution, bad input */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/error.h"
#include "base/rng.h"
#include "prim/spectral.h"
#include "fixtures.h"
#include "unit.h"

static double maxdiff(const tex_map *a, int ca, const tex_map *b, int cb)
{
    double d = 0;
    for (size_t i = 0; i < (size_t)a->w * a->h; i++)
        d = fmax(d, fabs(a->px[i * a->nc + ca] - b->px[i * b->nc + cb]));
    return d;
}

static void roundtrip(int w, int h)
{
    tex_map *m = unit_random_map(w, h, 1, 7), *s = tex_fft(m, TEX_FFT_COMPLEX, 0), *b;
    struct tex_ifft_opts o = TEX_IFFT_DEFAULTS;
    b = tex_ifft(s, &o);
    CHECKF(b && maxdiff(m, 0, b, 0) < 1e-5, "fft then ifft of a %dx%d map gives it back (%g)", w,
           h, b ? maxdiff(m, 0, b, 0) : -1);
    /* DC is the mean, in the middle */
    double mean = 0;
    for (int i = 0; i < w * h; i++)
        mean += m->px[i];
    mean /= w * h;
    CHECKF(fabs(tex_map_px(s, w / 2, h / 2)[0] - mean) < 1e-6 &&
               fabs(tex_map_px(s, w / 2, h / 2)[1]) < 1e-6,
           "%dx%d: the DC term sits at (w/2,h/2) and is the mean", w, h);
    /* magnitude and phase maps, inverted with --phase MAP, give it back too */
    tex_map *mag = tex_fft(m, TEX_FFT_MAG, 0), *ph = tex_fft(m, TEX_FFT_PHASE, 0), *c;
    o.phase = TEX_PHASE_MAP;
    o.phase_map = ph;
    o.scale = TEX_SCALE_NONE;
    c = tex_ifft(mag, &o);
    CHECKF(c && maxdiff(m, 0, c, 0) < 2e-5, "%dx%d: magnitude and phase maps invert (%g)", w, h,
           c ? maxdiff(m, 0, c, 0) : -1);
    tex_map_free(m);
    tex_map_free(s);
    tex_map_free(b);
    tex_map_free(mag);
    tex_map_free(ph);
    tex_map_free(c);
}

static void single_frequency(int w, int h, int kx, int ky)
{
    tex_map *s = tex_map_new(w, h, 1), *t;
    struct tex_ifft_opts o = TEX_IFFT_DEFAULTS;
    double err = 0;

    tex_map_px(s, w / 2 + kx, h / 2 + ky)[0] = 1.0f;
    o.phase = TEX_PHASE_ZERO;
    o.symmetric = 1;
    t = tex_ifft(s, &o);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double want = 0.5 + 0.5 * cos(2 * M_PI * ((double)kx * x / w + (double)ky * y / h));
            err = fmax(err, fabs(tex_map_px(t, x, y)[0] - want));
        }
    CHECKF(err < 1e-4, "%dx%d: one painted frequency (%d,%d) is a cosine of that period and "
           "orientation (max error %g)", w, h, kx, ky, err);
    tex_map_free(s);
    tex_map_free(t);
}

/* One half painted with --symmetric equals the whole Hermitian spectrum
 * inverted without it; the latter's imaginary part is zero. */
static void half_plane(int w, int h, int random_phase_map)
{
    tex_map *half = tex_map_new(w, h, 1), *full = tex_map_new(w, h, 1);
    tex_map *ph = random_phase_map ? unit_random_map(w, h, 1, 11) : NULL, *phfull = NULL;
    tex_map *a, *b;
    struct tex_ifft_opts o = TEX_IFFT_DEFAULTS;
    tex_rng r;

    tex_rng_seed(&r, 3);
    if (ph)
        phfull = tex_map_clone(ph);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            int kx = x - w / 2, ky = y - h / 2;
            int xq = ((-kx % w + w) % w + w / 2) % w, yq = ((-ky % h + h) % h + h / 2) % h;
            /* paint one member of each pair k, -k: the first in the map */
            if (y * w + x < yq * w + xq) {
                float v = (float)tex_rng_uniform(&r);
                tex_map_px(half, x, y)[0] = v;
                tex_map_px(full, x, y)[0] = v;
                tex_map_px(full, xq, yq)[0] = v;
                if (ph) {
                    float p = tex_map_px(ph, x, y)[0];
                    tex_map_px(phfull, xq, yq)[0] = p > 0 ? 1.0f - p : 0.0f;
                }
            }
        }
    o.phase = ph ? TEX_PHASE_MAP : TEX_PHASE_ZERO;
    o.phase_map = ph;
    o.symmetric = 1;
    o.scale = TEX_SCALE_NONE;
    a = tex_ifft(half, &o);
    o.phase_map = phfull;
    o.symmetric = 0;
    o.output = TEX_IFFT_COMPLEX;
    b = tex_ifft(full, &o);
    double im = 0, peak = 0;
    for (int i = 0; i < w * h; i++) {
        im = fmax(im, fabs(b->px[2 * i + 1]));
        peak = fmax(peak, fabs(b->px[2 * i]));
    }
    CHECKF(im < 1e-5 * peak, "%dx%d%s: the Hermitian spectrum has a zero imaginary part (%g)", w,
           h, ph ? " phase map" : "", im);
    CHECKF(maxdiff(a, 0, b, 0) < 1e-5 * peak,
           "%dx%d%s: --symmetric on one painted half equals the whole spectrum (%g)", w, h,
           ph ? " phase map" : "", maxdiff(a, 0, b, 0));
    o.phase = TEX_PHASE_RANDOM;
    o.symmetric = 1;
    tex_map *c = tex_ifft(half, &o);
    double cim = 0;
    for (int i = 0; i < w * h; i++)
        cim = fmax(cim, fabs(c->px[2 * i + 1]));
    CHECK(cim == 0, "--symmetric --as complex has an imaginary channel of zeros");
    tex_map_free(half);
    tex_map_free(full);
    tex_map_free(ph);
    tex_map_free(phfull);
    tex_map_free(a);
    tex_map_free(b);
    tex_map_free(c);
}

/* Least-squares slope of log power against log f over annuli lo..hi. */
static double power_slope(const tex_map *m, double lo, double hi)
{
    tex_map *s = tex_fft(m, TEX_FFT_MAG, 0);
    int w = m->w, h = m->h, nb = (int)hi + 2;
    double *sum = calloc(nb, sizeof *sum), sx = 0, sy = 0, sxx = 0, sxy = 0;
    int *cnt = calloc(nb, sizeof *cnt), n = 0;

    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double kx = x - w / 2, ky = y - h / 2, f = sqrt(kx * kx + ky * ky);
            int b = (int)lround(f);
            if (b < nb) {
                double a = tex_map_px(s, x, y)[0];
                sum[b] += a * a;
                cnt[b]++;
            }
        }
    for (int b = (int)lo; b <= (int)hi; b++) {
        double lx = log((double)b), ly = log(sum[b] / cnt[b]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
        n++;
    }
    free(sum);
    free(cnt);
    tex_map_free(s);
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

static tex_map *fbm(int w, int h, double H, double angle, double ratio, double lo, double hi)
{
    tex_map *m = tex_map_new(w, h, 1);
    struct tex_fbm_spec p = {H, angle, ratio, lo, hi, 5};
    if (tex_spectral_fbm(m, &p) < 0) {
        tex_map_free(m);
        return NULL;
    }
    return m;
}

static void fbm_tests(void)
{
    const double hs[] = {0.2, 0.5, 0.8};
    for (int i = 0; i < 3; i++) {
        tex_map *m = fbm(256, 256, hs[i], 0, 1, 0, 1e6);
        double s = power_slope(m, 4, 100), want = -(2 * hs[i] + 2);
        CHECKF(fabs(s - want) < 0.1, "fBm H=%g: radially averaged power slope %.3f, wanted %.3f",
               hs[i], s, want);
        struct tex_stats st;
        tex_map_stats(m, 0, &st);
        CHECKF(st.min == 0 && st.max == 1, "fBm H=%g spans [0,1] (%g..%g)", hs[i], st.min,
               st.max);
        tex_map_free(m);
    }
    /* tiles: the wrap-around step is no larger than steps inside the map */
    tex_map *m = fbm(128, 96, 0.5, 0, 1, 0, 1e6);
    double seam = 0, inner = 0;
    for (int y = 0; y < m->h; y++) {
        seam += fabs(tex_map_px(m, 0, y)[0] - tex_map_px(m, m->w - 1, y)[0]);
        inner += fabs(tex_map_px(m, m->w / 2, y)[0] - tex_map_px(m, m->w / 2 - 1, y)[0]);
    }
    CHECKF(seam < 2 * inner, "fBm tiles left-right (seam %g, inside %g)", seam, inner);
    tex_map_free(m);
    /* anisotropy: stretched along u, so steps along u are smaller than along v */
    m = fbm(128, 128, 0.5, 0, 4, 0, 1e6);
    double du = 0, dv = 0;
    for (int y = 1; y < 128; y++)
        for (int x = 1; x < 128; x++) {
            du += fabs(tex_map_px(m, x, y)[0] - tex_map_px(m, x - 1, y)[0]);
            dv += fabs(tex_map_px(m, x, y)[0] - tex_map_px(m, x, y - 1)[0]);
        }
    CHECKF(du < 0.5 * dv, "--anisotropy 0,4 stretches along u (steps u %g, v %g)", du, dv);
    tex_map_free(m);
    m = fbm(128, 128, 0.5, 90, 4, 0, 1e6);
    du = dv = 0;
    for (int y = 1; y < 128; y++)
        for (int x = 1; x < 128; x++) {
            du += fabs(tex_map_px(m, x, y)[0] - tex_map_px(m, x - 1, y)[0]);
            dv += fabs(tex_map_px(m, x, y)[0] - tex_map_px(m, x, y - 1)[0]);
        }
    CHECKF(dv < 0.5 * du, "--anisotropy 90,4 stretches along v (steps u %g, v %g)", du, dv);
    tex_map_free(m);
    /* band: no energy outside lo..hi */
    m = fbm(128, 128, 0.5, 0, 1, 10, 20);
    tex_map *s = tex_fft(m, TEX_FFT_MAG, 0);
    double in = 0, out = 0;
    for (int y = 0; y < 128; y++)
        for (int x = 0; x < 128; x++) {
            double f = hypot(x - 64, y - 64), a = tex_map_px(s, x, y)[0];
            if (f == 0)
                continue;
            if (f >= 10 - 1e-9 && f <= 20 + 1e-9)
                in += a * a;
            else
                out += a * a;
        }
    CHECKF(out < 1e-8 * in, "--band 10,20 keeps the energy in the band (outside/inside %g)",
           out / in);
    tex_map_free(s);
    tex_map_free(m);
    m = tex_map_new(16, 16, 1);
    struct tex_fbm_spec p = {0.5, 0, 1, 100, 200, 1};
    CHECK(tex_spectral_fbm(m, &p) < 0 && tex_errkind() == TEX_ERR_USAGE,
          "a band that holds no frequency is a usage error");
    tex_map_free(m);
}

static void sparse_tests(void)
{
    /* a sample with one frequency along u, period 8: the field keeps it */
    tex_map *smp = tex_map_new(32, 32, 1), *f, *s;
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++)
            tex_map_px(smp, x, y)[0] = (float)(0.5 + 0.4 * cos(2 * M_PI * x / 8.0));
    struct tex_sparse_spec sp = {2, 3, 9};
    f = tex_sparse_convolve(smp, 128, 128, &sp);
    CHECK(f != NULL, "sparse convolution runs");
    s = tex_fft(f, TEX_FFT_MAG, 0);
    double near = 0, all = 0;
    for (int y = 0; y < 128; y++)
        for (int x = 0; x < 128; x++) {
            double a = tex_map_px(s, x, y)[0], e = a * a;
            if (x == 64 && y == 64)
                continue;
            all += e;
            if (hypot(abs(x - 64) - 16, y - 64) <= 4)
                near += e;
        }
    CHECKF(near > 0.6 * all, "the field's energy sits near the sample's frequency (+-16,0) "
           "(%.2f of it)", near / all);
    struct tex_stats a, b;
    tex_map_stats(smp, 0, &a);
    tex_map_stats(f, 0, &b);
    CHECKF(fabs(a.min - b.min) < 1e-6 && fabs(a.max - b.max) < 1e-6,
           "the field spans the sample's range (%g..%g / %g..%g)", a.min, a.max, b.min, b.max);
    tex_map_free(s);
    tex_map_free(f);
    tex_map *big = tex_map_new(200, 10, 1);
    CHECK(!tex_sparse_convolve(big, 128, 128, &sp) && tex_errkind() == TEX_ERR_USAGE,
          "a sample larger than the map is refused");
    tex_map_free(big);
    tex_map_free(smp);
}

static void bad_input(void)
{
    struct tex_ifft_opts o = TEX_IFFT_DEFAULTS;
    tex_map *z = tex_map_new(16, 16, 1), *ph = tex_map_new(8, 8, 1), *t;

    CHECK(!tex_ifft(z, &o) && strstr(tex_errmsg(), "zero"), "an all-zero spectrum is refused");
    z->px[3] = 1;
    o.phase = TEX_PHASE_MAP;
    o.phase_map = ph;
    CHECK(!tex_ifft(z, &o) && strstr(tex_errmsg(), "8x8"),
          "a phase map of another size is refused");
    o.phase = TEX_PHASE_RANDOM;
    z->px[5] = NAN;
    CHECK(!tex_ifft(z, &o) && strstr(tex_errmsg(), "(5,0)"), "a NaN pixel is refused, named");
    z->px[5] = INFINITY;
    CHECK(!tex_fft(z, TEX_FFT_MAG, 0), "an infinite pixel is refused by the forward transform");
    z->px[5] = 0;
    t = tex_ifft(z, &o);
    CHECK(t != NULL, "the repaired spectrum inverts");
    tex_map_free(t);
    tex_map_free(z);
    tex_map_free(ph);
}

static void determinism(void)
{
#ifdef _OPENMP
    tex_map *a, *b, *s = unit_random_map(300, 200, 1, 4), *c, *d;
    struct tex_ifft_opts o = TEX_IFFT_DEFAULTS;
    omp_set_num_threads(1);
    a = fbm(300, 200, 0.7, 20, 2, 0, 1e6);
    o.symmetric = 1;
    c = tex_ifft(s, &o);
    omp_set_num_threads(3);
    b = fbm(300, 200, 0.7, 20, 2, 0, 1e6);
    d = tex_ifft(s, &o);
    CHECK(!memcmp(a->px, b->px, tex_map_samples(a) * 4), "fBm: 1 and 3 threads, same bits");
    CHECK(!memcmp(c->px, d->px, tex_map_samples(c) * 4), "ifft: 1 and 3 threads, same bits");
    tex_map_free(a);
    tex_map_free(b);
    tex_map_free(c);
    tex_map_free(d);
    tex_map_free(s);
#endif
}

int main(void)
{
    roundtrip(64, 64);
    roundtrip(37, 24);
    roundtrip(1, 9);
    single_frequency(64, 64, 3, -2);
    single_frequency(48, 30, 5, 4);
    single_frequency(33, 17, -7, 1);
    half_plane(32, 32, 0);
    half_plane(31, 20, 1);
    half_plane(24, 17, 1);
    fbm_tests();
    sparse_tests();
    bad_input();
    determinism();
    return unit_done();
}
