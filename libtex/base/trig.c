/* trig.c - sines and angles of many points (trig.h) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdint.h>

#include "base/x86/simd_x86.h"
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

/* ---- angles ----------------------------------------------------------------------- */

#define TAN_PI8 4.14213562373095034e-01 /* tan(pi/8), below it */
#define PIO4 7.85398163397448278999e-01
#define PIO2 1.57079632679489655800e+00
#define PI 3.14159265358979311600e+00

/* fdlibm's atan on |t| < 7/16: t - t (z (T0 + w (T2 + ...)) + w (T1 + w (T3 + ...))),
 * z = t^2, w = z^2 */
static const double AT[11] = {3.33333333333329318027e-01,  -1.99999999998764832476e-01,
                              1.42857142725034663711e-01,  -1.11111104054623557880e-01,
                              9.09088713343650656196e-02,  -7.69187620504482999495e-02,
                              6.66107313738753120669e-02,  -5.83357013379057348645e-02,
                              4.97687799461593236017e-02,  -3.65315727442169155270e-02,
                              1.62858201153657823623e-02};

double tex_atan2(double y, double x)
{
    double ax = fabs(x), ay = fabs(y);
    int swap = ay > ax, red;
    double num = swap ? ax : ay, den = swap ? ay : ax; /* t = num / den in [0, 1] */
    red = num > TAN_PI8 * den;                          /* then (t - 1) / (t + 1) */
    double a = red ? num - den : num, b = red ? num + den : den;
    double t = b == 0 ? 0 : a / b, z = t * t, w = z * z;
    double s1 = z * (AT[0] + w * (AT[2] + w * (AT[4] + w * (AT[6] + w * (AT[8] + w * AT[10])))));
    double s2 = w * (AT[1] + w * (AT[3] + w * (AT[5] + w * (AT[7] + w * AT[9]))));
    double r = t - t * (s1 + s2);
    r = red ? PIO4 + r : r;
    r = swap ? PIO2 - r : r;
    r = signbit(x) ? PI - r : r;
    return signbit(y) ? -r : r;
}

#ifdef TEX_X86
/* tex_atan2 of eight lanes, operation for operation */
TEX_AVX512 static __m512d atan2_avx512(__m512d y, __m512d x)
{
    const __m512i sign = _mm512_set1_epi64(INT64_MIN);
    __m512d ax = _mm512_abs_pd(x), ay = _mm512_abs_pd(y);
    __mmask8 swap = _mm512_cmp_pd_mask(ay, ax, _CMP_GT_OQ);
    __m512d num = _mm512_mask_blend_pd(swap, ay, ax), den = _mm512_mask_blend_pd(swap, ax, ay);
    __mmask8 red =
        _mm512_cmp_pd_mask(num, _mm512_mul_pd(_mm512_set1_pd(TAN_PI8), den), _CMP_GT_OQ);
    __m512d a = _mm512_mask_sub_pd(num, red, num, den), b = _mm512_mask_add_pd(den, red, num, den);
    __mmask8 zero = _mm512_cmp_pd_mask(b, _mm512_setzero_pd(), _CMP_EQ_OQ);
    __m512d t = _mm512_maskz_div_pd(~zero, a, b), z = _mm512_mul_pd(t, t), w = _mm512_mul_pd(z, z);
    __m512d p = _mm512_mul_pd(w, _mm512_set1_pd(AT[10]));
    __m512d q = _mm512_mul_pd(w, _mm512_set1_pd(AT[9]));
    for (int k = 8; k >= 2; k -= 2)
        p = _mm512_mul_pd(w, _mm512_add_pd(_mm512_set1_pd(AT[k]), p));
    for (int k = 7; k >= 3; k -= 2)
        q = _mm512_mul_pd(w, _mm512_add_pd(_mm512_set1_pd(AT[k]), q));
    __m512d s1 = _mm512_mul_pd(z, _mm512_add_pd(_mm512_set1_pd(AT[0]), p));
    __m512d s2 = _mm512_mul_pd(w, _mm512_add_pd(_mm512_set1_pd(AT[1]), q));
    __m512d r = _mm512_sub_pd(t, _mm512_mul_pd(t, _mm512_add_pd(s1, s2)));
    r = _mm512_mask_add_pd(r, red, _mm512_set1_pd(PIO4), r);
    r = _mm512_mask_sub_pd(r, swap, _mm512_set1_pd(PIO2), r);
    __mmask8 nx = _mm512_test_epi64_mask(_mm512_castpd_si512(x), sign);
    __mmask8 ny = _mm512_test_epi64_mask(_mm512_castpd_si512(y), sign);
    r = _mm512_mask_sub_pd(r, nx, _mm512_set1_pd(PI), r);
    return _mm512_castsi512_pd(_mm512_mask_xor_epi64(_mm512_castpd_si512(r), ny,
                                                     _mm512_castpd_si512(r), sign));
}

TEX_AVX512 static void atan2_n_avx512(int n, const double *y, const double *x, double *out)
{
    for (int i = 0; i < n; i += 8) {
        __mmask8 in = (__mmask8)((1u << (n - i < 8 ? n - i : 8)) - 1);
        _mm512_mask_storeu_pd(out + i, in,
                              atan2_avx512(_mm512_maskz_loadu_pd(in, y + i),
                                           _mm512_maskz_loadu_pd(in, x + i)));
    }
}
#endif

void tex_atan2_n(int n, const double *y, const double *x, double *out)
{
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX512) {
        atan2_n_avx512(n, y, x, out);
        return;
    }
#endif
    for (int i = 0; i < n; i++)
        out[i] = tex_atan2(y[i], x[i]);
}
