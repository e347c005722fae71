/* trig.c - sines of many points (trig.h) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>

#include "base/simd.h"
#include "base/trig.h"

#define BIG 0x1p19           /* past it, libm's sine */
#define ROUND 0x1.8p52       /* x + ROUND - ROUND: x rounded to a whole number, |x| < 2^51 */
#define INV_PIO2 6.36619772367581382433e-01
#define PIO2_1 1.57079632673412561417e+00 /* pi/2 in three pieces of 33 bits */
#define PIO2_2 6.07710050630396597660e-11
#define PIO2_3 2.02226624871116645580e-21

/* fdlibm's kernels: sin r = r + r^3 (S1 + z S(z)), cos r = 1 - z/2 + z^2 C(z), z = r^2 */
static const double S[6] = {-1.66666666666666324348e-01, 8.33333333332248946124e-03,
                            -1.98412698298579493134e-04, 2.75573137070700676789e-06,
                            -2.50507602534068634195e-08, 1.58969099521155010221e-10};
static const double C[6] = {4.16666666666666019037e-02,  -1.38888888888741095749e-03,
                            2.48015872894767294178e-05,  -2.75573143513906633035e-07,
                            2.08757232129817482790e-09,  -1.13596475577881948265e-11};

/* One sine (quarter 0) or cosine (1), in the operations of sin_avx2's lanes. */
static double sin1(double x, int quarter)
{
    if (!(fabs(x) <= BIG))
        return quarter ? cos(x) : sin(x);
    double k = x * INV_PIO2 + ROUND - ROUND;
    double r = x - k * PIO2_1 - k * PIO2_2 - k * PIO2_3;
    double kq = k + quarter, q = kq - 4 * (kq * 0.25 - 0.375 + ROUND - ROUND); /* kq mod 4 */
    double z = r * r;
    double sr = r + z * r * (S[0] + z * (S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])))));
    double hz = 0.5 * z, w = 1 - hz;
    double cp = z * (C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5])))));
    double cr = w + ((1 - w - hz) + z * cp);
    double v = q == 1 || q == 3 ? cr : sr;
    return q >= 2 ? -v : v;
}

#ifdef TEX_X86
TEX_AVX2 static inline __m256d poly_pd(__m256d z, const double c[6])
{
    __m256d p = _mm256_set1_pd(c[5]);
    for (int i = 4; i >= 0; i--)
        p = _mm256_add_pd(_mm256_set1_pd(c[i]), _mm256_mul_pd(z, p));
    return p;
}

/* sin1 four at a time, for the first n - n % 4 points; lanes past BIG left to sin1 */
TEX_AVX2 static void sin_avx2(int n, const double *x, double *out, int quarter)
{
    const __m256d round = _mm256_set1_pd(ROUND), one = _mm256_set1_pd(1);
    const __m256d sign = _mm256_set1_pd(-0.0), big = _mm256_set1_pd(BIG);
    for (int i = 0; i + 4 <= n; i += 4) {
        __m256d v = _mm256_loadu_pd(x + i);
        __m256d k = _mm256_sub_pd(
            _mm256_add_pd(_mm256_mul_pd(v, _mm256_set1_pd(INV_PIO2)), round), round);
        __m256d r = _mm256_sub_pd(v, _mm256_mul_pd(k, _mm256_set1_pd(PIO2_1)));
        r = _mm256_sub_pd(r, _mm256_mul_pd(k, _mm256_set1_pd(PIO2_2)));
        r = _mm256_sub_pd(r, _mm256_mul_pd(k, _mm256_set1_pd(PIO2_3)));
        __m256d kq = _mm256_add_pd(k, _mm256_set1_pd(quarter));
        __m256d m = _mm256_sub_pd(
            _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(kq, _mm256_set1_pd(0.25)),
                                        _mm256_set1_pd(0.375)),
                          round),
            round);
        __m256d q = _mm256_sub_pd(kq, _mm256_mul_pd(_mm256_set1_pd(4), m));
        __m256d z = _mm256_mul_pd(r, r);
        __m256d sr = _mm256_add_pd(r, _mm256_mul_pd(_mm256_mul_pd(z, r), poly_pd(z, S)));
        __m256d hz = _mm256_mul_pd(_mm256_set1_pd(0.5), z), w = _mm256_sub_pd(one, hz);
        __m256d cp = _mm256_mul_pd(z, poly_pd(z, C));
        __m256d cr = _mm256_add_pd(
            w, _mm256_add_pd(_mm256_sub_pd(_mm256_sub_pd(one, w), hz), _mm256_mul_pd(z, cp)));
        __m256d odd = _mm256_or_pd(_mm256_cmp_pd(q, one, _CMP_EQ_OQ),
                                   _mm256_cmp_pd(q, _mm256_set1_pd(3), _CMP_EQ_OQ));
        __m256d s = _mm256_blendv_pd(sr, cr, odd);
        __m256d neg = _mm256_cmp_pd(q, _mm256_set1_pd(2), _CMP_GE_OQ);
        s = _mm256_xor_pd(s, _mm256_and_pd(neg, sign));
        int far = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_andnot_pd(sign, v), big, _CMP_NLE_UQ));
        if (far) { /* beyond the reduction, or NaN: libm's, read before out (may be x) is set */
            double t[4];
            _mm256_storeu_pd(t, s);
            for (int j = 0; j < 4; j++)
                if (far >> j & 1)
                    t[j] = sin1(x[i + j], quarter);
            s = _mm256_loadu_pd(t);
        }
        _mm256_storeu_pd(out + i, s);
    }
}
#endif

void tex_sin_n(int n, const double *x, double *out, int quarter)
{
    int i = 0;
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2) {
        sin_avx2(n, x, out, quarter);
        i = n & ~3;
    }
#endif
    for (; i < n; i++)
        out[i] = sin1(x[i], quarter);
}
