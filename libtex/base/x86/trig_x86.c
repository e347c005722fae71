/* trig_x86.c - trig.c's sines four at a time (AVX2) and angles eight at a time (AVX-512) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdint.h>

#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "base/trig_fdlibm.h"
#include "base/x86/trig_x86.h"

TEX_AVX2 static inline __m256d poly_pd(__m256d z, const double c[6])
{
    __m256d p = _mm256_set1_pd(c[5]);
    for (int i = 4; i >= 0; i--)
        p = _mm256_add_pd(_mm256_set1_pd(c[i]), _mm256_mul_pd(z, p));
    return p;
}

/* sin1 four at a time, for the first n - n % 4 points; lanes past BIG left to sin1 */
TEX_AVX2 void tex_sin_avx2(int n, const double *x, double *out, int quarter)
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

TEX_AVX512 void tex_atan2_n_avx512(int n, const double *y, const double *x, double *out)
{
    for (int i = 0; i < n; i += 8) {
        __mmask8 in = (__mmask8)((1u << (n - i < 8 ? n - i : 8)) - 1);
        _mm512_mask_storeu_pd(out + i, in,
                              atan2_avx512(_mm512_maskz_loadu_pd(in, y + i),
                                           _mm512_maskz_loadu_pd(in, x + i)));
    }
}
#endif
