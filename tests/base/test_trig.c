/* test_trig.c - tex_sin_n: near libm's sine and cosine, the same bytes at every SIMD
 * level and in any batch, libm's own beyond the reduction's range; tex_atan2 and
 * tex_atan2_n: near libm's atan2, its signed zeros and axes, the same bytes at every SIMD
 * level and in any batch */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/rng.h"
#include "base/simd.h"
#include "base/trig.h"
#include "unit.h"

enum { N = 1 << 20 };

/* The points: most in a few turns, some up to the reduction's 2^19, the quadrants'
 * edges (multiples of pi/4 and pi/2), a few past 2^19, zeros, NaN and infinities. */
static void points(double *x)
{
    tex_rng r;
    tex_rng_seed(&r, 5);
    for (int i = 0; i < N; i++) {
        double u = 2 * tex_rng_uniform(&r) - 1;
        x[i] = i % 5 == 0 ? u * 0x1p19 : i % 7 == 0 ? (i % 2000) * M_PI / 4 : u * 40;
    }
    const double special[] = {0, -0.0, NAN, INFINITY, -INFINITY, 0x1p19, -0x1p19, 0x1p19 + 1,
                              1e300, -3e7, 1e-300, M_PI, M_PI / 2};
    for (size_t k = 0; k < sizeof special / sizeof *special; k++)
        x[N - 1 - 13 * k] = special[k];
}

/* the largest difference from libm's, where libm's is in [-1, 1], in units of 2^-53 */
static double worst(const double *x, const double *y, int quarter)
{
    double m = 0;
    for (int i = 0; i < N; i++) {
        double ref = quarter ? cos(x[i]) : sin(x[i]);
        if (isnan(ref) ? !isnan(y[i]) : fabs(y[i] - ref) * 0x1p53 > m)
            m = isnan(ref) ? INFINITY : fabs(y[i] - ref) * 0x1p53;
    }
    return m;
}

/* tex_atan2 over points of every octant and scale, the octants' edges, zeros of both
 * signs, NaN and an infinity: its largest difference from libm's, relative, in units of
 * 2^-53; the special points' libm values exactly; tex_atan2_n the same bytes at every SIMD
 * level, one point at a time or in a batch from any offset */
static void angles(void)
{
    double *y = malloc(sizeof *y * N), *x = malloc(sizeof *x * N), *a = malloc(sizeof *a * N);
    double *b = malloc(sizeof *b * N);
    if (!y || !x || !a || !b)
        exit(1);
    tex_rng r;
    tex_rng_seed(&r, 9);
    for (int i = 0; i < N; i++) {
        double s = ldexp(1, (int)(tex_rng_uniform(&r) * 80) - 40); /* magnitudes 2^-40..2^40 */
        x[i] = (2 * tex_rng_uniform(&r) - 1) * s;
        y[i] = i % 3 ? (2 * tex_rng_uniform(&r) - 1) * s
                     : x[i] * (i % 2 ? 0.41421356237309503 : -1); /* tan(pi/8), the diagonals */
    }
    const double sp[][2] = {{0, 0},   {-0.0, 0}, {0, -0.0}, {-0.0, -0.0}, {1, 0},
                            {-1, 0},  {1, -0.0}, {0, 1},    {0, -1},      {-0.0, -1},
                            {3, 3},   {-3, 3},   {3, -3},   {-3, -3},     {1e-300, 1},
                            {1, 1e-300}};
    int nsp = sizeof sp / sizeof *sp, exact = 0;
    for (int k = 0; k < nsp; k++)
        y[N - 1 - k] = sp[k][0], x[N - 1 - k] = sp[k][1];
    double m = 0;
    for (int i = 0; i < N; i++) {
        a[i] = tex_atan2(y[i], x[i]);
        double ref = atan2(y[i], x[i]);
        if (ref != 0)
            m = fmax(m, fabs(a[i] - ref) / fabs(ref) * 0x1p53);
    }
    for (int k = 0; k < nsp; k++) {
        double ref = atan2(y[N - 1 - k], x[N - 1 - k]), v = a[N - 1 - k];
        exact += k < 10 ? memcmp(&v, &ref, sizeof v) == 0 : fabs(v - ref) <= 4e-16 * fabs(ref);
    }
    CHECKF(m <= 4, "atan2 within 2^-51 of libm's, relative (worst %.2f x 2^-53)", m);
    CHECKF(exact == nsp, "atan2 at the axes and zeros of both signs: libm's (%d of %d)", exact,
           nsp);
    CHECK(isnan(tex_atan2(NAN, 1)) && isnan(tex_atan2(1, NAN)), "atan2 of NaN: NaN");
    CHECK(tex_atan2(1, INFINITY) == 0 && tex_atan2(-1, -INFINITY) == -M_PI,
          "atan2 along an infinite x: 0 and -pi");
    tex_simd_limit(TEX_SIMD_AVX512);
    int level = tex_simd_level();
    tex_atan2_n(N - 5, y + 5, x + 5, b + 5);
    for (int i = 0; i < 5; i++)
        tex_atan2_n(1, y + i, x + i, b + i);
    CHECKF(memcmp(a, b, sizeof *a * N) == 0, "atan2 at %s, in a batch from any offset or one "
           "at a time: tex_atan2's bytes", tex_simd_name(level));
    tex_simd_limit(TEX_SIMD_SCALAR);
    tex_atan2_n(N, y, x, b);
    CHECK(memcmp(a, b, sizeof *a * N) == 0, "atan2 on the portable path: the same bytes");
    tex_simd_limit(TEX_SIMD_AVX512);
    free(y), free(x), free(a), free(b);
}

int main(void)
{
    double *x = malloc(sizeof *x * N), *a = malloc(sizeof *a * N), *b = malloc(sizeof *b * N);
    if (!x || !a || !b)
        return 1;
    points(x);
    for (int q = 0; q < 2; q++) {
        const char *name = q ? "cos" : "sin";
        tex_simd_limit(TEX_SIMD_AVX512);
        int level = tex_simd_level();
        tex_sin_n(N, x, a, q);
        double e = worst(x, a, q);
        CHECKF(e <= 2, "%s within 2^-52 of libm's (%s; worst %.2f x 2^-53)", name,
               tex_simd_name(level), e);
        tex_simd_limit(TEX_SIMD_SCALAR);
        tex_sin_n(N, x, b, q);
        CHECKF(memcmp(a, b, sizeof *a * N) == 0, "%s: %s and the portable path, the same bytes",
               name, tex_simd_name(level));
        for (int i = 0; i < 7; i++) /* one at a time, and in place */
            tex_sin_n(1, x + i, b + i, q);
        memcpy(b + 7, x + 7, sizeof *b * (N - 7));
        tex_simd_limit(TEX_SIMD_AVX512);
        tex_sin_n(N - 7, b + 7, b + 7, q);
        CHECKF(memcmp(a, b, sizeof *a * N) == 0, "%s: one point at a time or in place, the same "
               "bytes", name);
        int far = 0, same = 0;
        for (int i = 0; i < N; i++)
            if (fabs(x[i]) > 0x1p19) {
                far++;
                same += memcmp(&a[i], &(double){q ? cos(x[i]) : sin(x[i])}, sizeof a[i]) == 0;
            }
        CHECKF(far == 5 && same == far, "%s past 2^19 and of infinities: libm's own (%d of %d)",
               name, same, far);
    }
    CHECK(a[N - 1] == 1 && signbit(b[N - 1]) == 0, "cos 0 = 1");
    free(x);
    free(a);
    free(b);
    angles();
    return unit_done();
}
