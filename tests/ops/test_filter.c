/* test_filter - properties of the filters: blur statistics, Sobel on a ramp, tileability,
 * normal maps of planes, noise, median, determinism across thread counts */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/error.h"
#include "ops/filter.h"
#include "base/rng.h"
#include "fixtures.h"
#include "unit.h"

static double mean_of(const tex_map *m, int c)
{
    struct tex_stats s;
    tex_map_stats(m, c, &s);
    return s.mean;
}

static double var_of(const tex_map *m, int c)
{
    struct tex_stats s;
    tex_map_stats(m, c, &s);
    return s.stddev * s.stddev;
}

/* m shifted circularly by (dx, dy) */
static tex_map *shifted(const tex_map *m, int dx, int dy)
{
    tex_map *s = tex_map_new(m->w, m->h, m->nc);
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            memcpy(tex_map_px(s, (x + dx) % m->w, (y + dy) % m->h), tex_map_px(m, x, y),
                   m->nc * sizeof(float));
    return s;
}

static double maxdiff(const tex_map *a, const tex_map *b)
{
    double d = 0;
    for (size_t i = 0; i < tex_map_samples(a); i++)
        d = fmax(d, fabs((double)a->px[i] - b->px[i]));
    return d;
}

/* Does filter f commute with a circular shift (so tileable maps stay tileable)? */
static double shift_error(tex_map *(*f)(const tex_map *, enum tex_edge), const tex_map *m,
                          enum tex_edge e)
{
    tex_map *s = shifted(m, 37, 21), *fs = f(s, e), *fm = f(m, e), *sfm = shifted(fm, 37, 21);
    double d = maxdiff(fs, sfm);
    tex_map_free(s);
    tex_map_free(fs);
    tex_map_free(fm);
    tex_map_free(sfm);
    return d;
}

static tex_map *blur3(const tex_map *m, enum tex_edge e) { return tex_filter_blur(m, 3, e); }
static tex_map *sobel1(const tex_map *m, enum tex_edge e) { return tex_filter_sobel(m, 0, 1, e); }
static tex_map *median1(const tex_map *m, enum tex_edge e) { return tex_filter_median(m, 1, e); }
static tex_map *normal4(const tex_map *m, enum tex_edge e) { return tex_filter_normal(m, 4, e); }
static tex_map *box2(const tex_map *m, enum tex_edge e) { return tex_filter_box(m, 2, e); }

/* A band of a stream (tex_filter_*_rows): its own rows have the whole map's bits when its
 * context rows cover the kernel's reach; a band with no rows of its own is refused. */
static void test_band_rows(void)
{
    tex_map *m = unit_random_map(37, 41, 3, 5), *band = tex_map_new(37, 11 + 2 * 6, 3);
    tex_map *whole[3] = {tex_filter_blur(m, 1.2, TEX_EDGE_CLAMP), tex_filter_box(m, 3, TEX_EDGE_WRAP),
                         tex_filter_smooth(m, TEX_EDGE_MIRROR)};
    size_t row = (size_t)m->w * m->nc;
    int same = 0, bands = 0;
    for (int y0 = 6; y0 + 11 + 6 <= m->h; y0 += 11, bands++) { /* rows y0..y0+10, 6 of context */
        memcpy(band->px, tex_map_row(m, y0 - 6), row * band->h * sizeof *band->px);
        tex_map *b[3] = {tex_filter_blur_rows(band, 1.2, TEX_EDGE_CLAMP, 6),
                         tex_filter_box_rows(band, 3, TEX_EDGE_WRAP, 6),
                         tex_filter_smooth_rows(band, TEX_EDGE_MIRROR, 6)};
        for (int k = 0; k < 3; k++) {
            same += b[k] && b[k]->h == 11 &&
                    !memcmp(b[k]->px, tex_map_row(whole[k], y0), row * 11 * sizeof *band->px);
            tex_map_free(b[k]);
        }
    }
    CHECKF(bands == 2 && same == 3 * bands, "blur, box and smooth of %d bands: the whole map's "
           "bits in their own rows (%d of %d)", bands, same, 3 * bands);
    tex_map *none = tex_filter_blur_rows(band, 1.2, TEX_EDGE_CLAMP, 12);
    CHECKF(!none && strstr(tex_errmsg(), "no rows between its 12 rows of context"),
           "a band with no rows of its own is refused (%s)", tex_errmsg());
    for (int k = 0; k < 3; k++)
        tex_map_free(whole[k]);
    tex_map_free(band);
    tex_map_free(m);
}

/* The separable passes against the sum written out per sample, in its order (k0 times the
 * sample, then kj times the sum of the pair at distance j, j from 1 up), each row and column
 * by the edge rule: the same bits, for widths that fill blocks of lanes and leave tails
 * (w * nc a multiple of 64 and not), rows narrower than the kernel, and bands with context */
static float taps(const float *p, long i, long n, long step, const float *k, int r,
                  enum tex_edge e)
{
    float acc = k[0] * p[i * step];
    for (int j = 1; j <= r; j++)
        acc += k[j] * (p[tex_edge_index(i - j, n, e) * step] +
                       p[tex_edge_index(i + j, n, e) * step]);
    return acc;
}

static void test_separable_sums(void)
{
    static const int sizes[][3] = {{64, 9, 1}, {128, 21, 3}, {67, 40, 3}, {150, 33, 4}, {5, 23, 2},
                                   {1, 19, 1}, {300, 70, 3}};
    static const float k[] = {0.3f, 0.2f, 0.1f, 0.05f, 0.025f, 0.0125f, 0.00625f, 0.003f, 0.001f};
    int cases = 0, same = 0;
    for (size_t s = 0; s < sizeof sizes / sizeof *sizes; s++)
        for (int r = 1; r <= 8; r += 7)
            for (enum tex_edge e = TEX_EDGE_CLAMP; e <= TEX_EDGE_MIRROR; e++) {
                int w = sizes[s][0], h = sizes[s][1], nc = sizes[s][2];
                int skip = h > 2 * r + 1 ? r : 0;
                tex_map *m = unit_random_map(w, h, nc, (uint64_t)(s * 31 + r)), *want;
                tex_map *tmp = tex_map_new(w, h, nc), *got;
                want = tex_map_new(w, h - 2 * skip, nc);
                for (int y = 0; y < h; y++)
                    for (int x = 0; x < w; x++)
                        for (int c = 0; c < nc; c++)
                            tex_map_px(tmp, x, y)[c] =
                                taps(tex_map_row(m, y) + c, x, w, nc, k, r, e);
                for (int y = skip; y < h - skip; y++)
                    for (long i = 0; i < (long)w * nc; i++)
                        tex_map_row(want, y - skip)[i] =
                            taps(tmp->px + i, y, h, (long)w * nc, k, r, e);
                got = tex_filter_separable_rows(m, k, r, e, skip);
                cases++;
                same += got && !memcmp(got->px, want->px, tex_map_samples(want) * sizeof(float));
                tex_map_free(got);
                tex_map_free(want);
                tex_map_free(tmp);
                tex_map_free(m);
            }
    CHECKF(same == cases, "separable passes: the sums per sample, bit for bit (%d of %d)", same,
           cases);
}

/* Blur, box and smooth of white noise, threads, and tileable maps */
static void test_white_noise(void)
{
    tex_map *m, *b;

    /* Blur of white noise: the mean stays, the variance falls by (sum g^2)^2, which for a
     * sampled Gaussian is close to the continuous 1 / (4 pi sigma^2). */
    m = unit_random_map(256, 256, 1, 7);
    for (double sigma = 1.5; sigma <= 3.0; sigma += 1.5) {
        double want = 1 / (4 * M_PI * sigma * sigma), got;
        b = tex_filter_blur(m, sigma, TEX_EDGE_WRAP);
        got = var_of(b, 0) / var_of(m, 0);
        CHECKF(fabs(mean_of(b, 0) - mean_of(m, 0)) < 1e-5, "blur %g keeps the mean (%.7f vs %.7f)",
               sigma, mean_of(b, 0), mean_of(m, 0));
        CHECKF(fabs(got / want - 1) < 0.15, "blur %g divides the variance by %.1f (want %.1f)",
               sigma, 1 / got, 1 / want);
        tex_map_free(b);
    }
    b = tex_filter_box(m, 2, TEX_EDGE_WRAP);
    CHECKF(fabs(var_of(b, 0) / var_of(m, 0) * 25 - 1) < 0.15,
           "a 5x5 box divides the variance of white noise by 25 (%.1f)", var_of(m, 0) / var_of(b, 0));
    tex_map_free(b);
    b = tex_filter_smooth(m, TEX_EDGE_WRAP);
    CHECKF(fabs(var_of(b, 0) / var_of(m, 0) / (0.375 * 0.375) - 1) < 0.15,
           "smooth divides the variance by (3/8)^-2 = 7.1 (%.2f)", var_of(m, 0) / var_of(b, 0));
    tex_map_free(b);

    /* Every thread count gives the same bits. */
#ifdef _OPENMP
    {
        tex_map *rgba = unit_random_map(203, 131, 4, 3), *a1, *a2, *n1, *n2;
        omp_set_num_threads(1);
        a1 = tex_filter_blur(rgba, 4.5, TEX_EDGE_MIRROR);
        n1 = tex_filter_noise(rgba, 0.1, 9);
        omp_set_num_threads(3);
        a2 = tex_filter_blur(rgba, 4.5, TEX_EDGE_MIRROR);
        n2 = tex_filter_noise(rgba, 0.1, 9);
        CHECK(!memcmp(a1->px, a2->px, tex_map_samples(a1) * 4), "blur: same bits on 1 and 3 threads");
        CHECK(!memcmp(n1->px, n2->px, tex_map_samples(n1) * 4), "noise: same bits on 1 and 3 threads");
        tex_map_free(a1);
        tex_map_free(a2);
        tex_map_free(n1);
        tex_map_free(n2);
        tex_map_free(rgba);
        omp_set_num_threads(2);
    }
#endif

    /* Wrap mode commutes with circular shifts: tileable in, tileable out.  Clamp does not. */
    CHECKF(shift_error(blur3, m, TEX_EDGE_WRAP) < 1e-6, "blur, wrap: tileable stays tileable");
    CHECKF(shift_error(blur3, m, TEX_EDGE_CLAMP) > 1e-3, "blur, clamp: the seams differ (the "
                                                          "check can fail)");
    CHECKF(shift_error(box2, m, TEX_EDGE_WRAP) < 1e-6, "box, wrap: tileable stays tileable");
    CHECKF(shift_error(sobel1, m, TEX_EDGE_WRAP) == 0, "sobel, wrap: tileable stays tileable");
    CHECKF(shift_error(median1, m, TEX_EDGE_WRAP) == 0, "median, wrap: tileable stays tileable");
    CHECKF(shift_error(normal4, m, TEX_EDGE_WRAP) == 0, "normal, wrap: tileable stays tileable");
    tex_map_free(m);
}

/* Sobel, normals and gradient of a ramp, a level plane and a bump */
static void test_slopes(void)
{
    tex_map *m, *b;

    /* Sobel of a ramp is constant: the ramp's slope. */
    m = tex_map_new(64, 48, 1);
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            tex_map_px(m, x, y)[0] = 0.01f * x + 0.02f * y;
    b = tex_filter_sobel(m, 0, 1, TEX_EDGE_CLAMP);
    {
        double lo = 1e9, hi = -1e9, want = sqrt(0.01 * 0.01 + 0.02 * 0.02);
        for (int y = 1; y < m->h - 1; y++)
            for (int x = 1; x < m->w - 1; x++) {
                lo = fmin(lo, tex_map_px(b, x, y)[0]);
                hi = fmax(hi, tex_map_px(b, x, y)[0]);
            }
        CHECKF(hi - lo < 1e-5 && fabs(lo - want) < 1e-5, "sobel of a ramp is its slope %.5f (%.6f..%.6f)",
               want, lo, hi);
    }
    tex_map_free(b);
    b = tex_filter_sobel(m, 1, 1, TEX_EDGE_CLAMP);
    {
        /* rising right and downwards: angle atan2(-0.02, 0.01), wrapped into [0,1) */
        double want = atan2(-0.02, 0.01) / (2 * M_PI) + 1;
        CHECKF(fabs(tex_map_px(b, 30, 20)[0] - want) < 1e-5, "sobel direction %.4f (want %.4f)",
               tex_map_px(b, 30, 20)[0], want);
    }
    tex_map_free(b);

    /* The normal map of a plane is flat: constant, and (0,0,1) for a level plane. */
    b = tex_filter_normal(m, 10, TEX_EDGE_CLAMP);
    {
        double k = 10, nx = -k * 0.01, ny = k * 0.02, len = sqrt(nx * nx + ny * ny + 1), err = 0;
        for (int y = 1; y < m->h - 1; y++)
            for (int x = 1; x < m->w - 1; x++) {
                float *p = tex_map_px(b, x, y);
                err = fmax(err, fabs(p[0] - (0.5 + 0.5 * nx / len)));
                err = fmax(err, fabs(p[1] - (0.5 + 0.5 * ny / len)));
                err = fmax(err, fabs(p[2] - (0.5 + 0.5 / len)));
            }
        CHECKF(err < 1e-5, "the normal map of a tilted plane is one normal (error %g)", err);
    }
    tex_map_free(b);
    for (size_t i = 0; i < tex_map_samples(m); i++)
        m->px[i] = 0.3f;
    b = tex_filter_normal(m, 10, TEX_EDGE_CLAMP);
    {
        int flat = 1;
        for (size_t i = 0; i < (size_t)b->w * b->h; i++)
            flat &= b->px[3 * i] == 0.5f && b->px[3 * i + 1] == 0.5f && b->px[3 * i + 2] == 1.0f;
        CHECK(flat, "the normal map of a level plane is (0.5, 0.5, 1) everywhere");
    }
    tex_map_free(b);
    /* A bump: light is elevation, so the normal on its right flank points right. */
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++)
            tex_map_px(m, x, y)[0] = (float)exp(-((x - 32) * (x - 32) + (y - 24) * (y - 24)) / 50.0);
    b = tex_filter_normal(m, 4, TEX_EDGE_CLAMP);
    CHECKF(tex_map_px(b, 38, 24)[0] > 0.6f && tex_map_px(b, 26, 24)[0] < 0.4f &&
               tex_map_px(b, 32, 18)[1] > 0.6f,
           "normals lean away from a bright bump (%.2f %.2f %.2f)", tex_map_px(b, 38, 24)[0],
           tex_map_px(b, 26, 24)[0], tex_map_px(b, 32, 18)[1]);
    tex_map_free(b);
    b = tex_filter_gradient(m, TEX_EDGE_CLAMP);
    CHECK(b->nc == 2 && tex_map_px(b, 38, 24)[0] < 0 && tex_map_px(b, 32, 28)[1] < 0,
          "gradient: 2 channels, downhill away from the bump");
    tex_map_free(b);
    tex_map_free(m);
}

/* Median and edges around a one-pixel spike */
static void test_spike(void)
{
    tex_map *m = tex_map_new(64, 48, 1), *b;

    /* Median removes a lone spike; sharpen and edges keep flat areas. */
    for (size_t i = 0; i < tex_map_samples(m); i++)
        m->px[i] = 0.25f;
    tex_map_px(m, 10, 10)[0] = 1;
    b = tex_filter_median(m, 1, TEX_EDGE_CLAMP);
    CHECK(tex_map_px(b, 10, 10)[0] == 0.25f, "median removes a one-pixel spike");
    tex_map_free(b);
    b = tex_filter_edges(m, 1, TEX_EDGE_CLAMP);
    CHECK(tex_map_px(b, 10, 10)[0] > 1 && tex_map_px(b, 30, 30)[0] == 0.25f,
          "edges enhances the spike and keeps flat areas");
    tex_map_free(b);
    tex_map_free(m);
}

/* The noise filter */
static void test_noise(void)
{
    tex_map *m, *b;

    /* Noise: the asked standard deviation, alpha untouched; a seed is repeatable. */
    m = tex_map_new(128, 128, 4);
    for (size_t i = 0; i < tex_map_samples(m); i++)
        m->px[i] = 0.5f;
    b = tex_filter_noise(m, 0.1, 5);
    CHECKF(fabs(mean_of(b, 0) - 0.5) < 0.005 && fabs(sqrt(var_of(b, 1)) - 0.1) < 0.005,
           "noise: mean 0.5, sd 0.1 (%.4f, %.4f)", mean_of(b, 0), sqrt(var_of(b, 1)));
    CHECK(var_of(b, 3) == 0, "noise leaves alpha alone");
    {
        tex_map *c = tex_filter_noise(m, 0.1, 6);
        CHECK(maxdiff(b, c) > 0.01, "another seed gives other noise");
        tex_map_free(c);
    }
    tex_map_free(b);
    tex_map_free(m);
}

/* Bad input */
static void test_bad(void)
{
    tex_map *m, *b;

    /* Bad input. */
    m = tex_map_new(16, 16, 1);
    b = tex_filter_blur(m, 5, TEX_EDGE_WRAP);
    CHECKF(!b && tex_errkind() == TEX_ERR_USAGE && strstr(tex_errmsg(), "larger than the 16x16"),
           "a kernel larger than the map is refused (%s)", tex_errmsg());
    b = tex_filter_blur(m, 0, TEX_EDGE_WRAP);
    CHECK(!b && strstr(tex_errmsg(), "sigma"), "sigma 0 is refused");
    b = tex_filter_median(m, 20, TEX_EDGE_WRAP);
    CHECK(!b && strstr(tex_errmsg(), "1..15"), "a median radius above 15 is refused");
    tex_map_free(m);
}

int main(void)
{
    test_white_noise();
    test_slopes();
    test_spike();
    test_noise();
    test_bad();
    test_band_rows();
    test_separable_sums();
    return unit_done();
}
