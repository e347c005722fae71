/* vecmath_x86.h - vecmath.h's operations in AVX-512 lanes, eight points at a time
 *
 * Each performs the scalar function's operations in its order (a . b as tex_v3_dot sums,
 * tex_turns and tex_polar through tex_atan2's lanes), so the same bits.  Static: the
 * kernels that include them inline them.
 */
#ifndef TEX_VECMATH_X86_H
#define TEX_VECMATH_X86_H

#include "../../base/x86/simd_x86.h"
#include "../vecmath.h"

#ifdef TEX_X86
/* a . b over three lanes of rows, in tex_v3_dot's order */
TEX_AVX512 static inline __m512d dot8(__m512d ax, __m512d ay, __m512d az, __m512d bx,
                                       __m512d by, __m512d bz)
{
    return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(ax, bx), _mm512_mul_pd(ay, by)),
                         _mm512_mul_pd(az, bz));
}

/* dot8 in AVX2's four lanes */
TEX_AVX2 static inline __m256d dot4(__m256d ax, __m256d ay, __m256d az, __m256d bx, __m256d by,
                                    __m256d bz)
{
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(ax, bx), _mm256_mul_pd(ay, by)),
                         _mm256_mul_pd(az, bz));
}

/* -x over lanes: the sign flipped, as C's unary minus does (for a zero too) */
TEX_AVX512 static inline __m512d neg8(__m512d x)
{
    return _mm512_castsi512_pd(
        _mm512_xor_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(INT64_MIN)));
}

/* fmin(1, fmax(0, x)) over lanes, NaN to 0 as there */
TEX_AVX512 static inline __m512d clamp8(__m512d x)
{
    __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1);
    __m512d a = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(x, zero, _CMP_GT_OQ), zero, x);
    return _mm512_mask_blend_pd(_mm512_cmp_pd_mask(a, one, _CMP_LT_OQ), one, a);
}

/* tex_turns over lanes */
TEX_AVX512 static __m512d turns8(__m512d y, __m512d x)
{
    double ya[8], xa[8], r[8];
    _mm512_storeu_pd(ya, y), _mm512_storeu_pd(xa, x);
    tex_atan2_n(8, ya, xa, r);
    __m512d a = _mm512_div_pd(_mm512_loadu_pd(r), _mm512_set1_pd(2 * M_PI));
    __mmask8 neg = _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_LT_OQ);
    return _mm512_mask_add_pd(a, neg, a, _mm512_set1_pd(1));
}

/* tex_polar over lanes */
TEX_AVX512 static __m512d polar8(__m512d c)
{
    __m512d one = _mm512_set1_pd(1), m = _mm512_set1_pd(-1);
    double ya[8], xa[8], r[8]; /* fmin(1, c) (NaN to 1), then fmax(-1, that) */
    c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(c, one, _CMP_LT_OQ), one, c);
    c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(c, m, _CMP_GT_OQ), m, c);
    _mm512_storeu_pd(xa, c);
    _mm512_storeu_pd(ya, _mm512_sqrt_pd(_mm512_mul_pd(_mm512_sub_pd(one, c),
                                                      _mm512_add_pd(one, c))));
    tex_atan2_n(8, ya, xa, r);
    return _mm512_div_pd(_mm512_loadu_pd(r), _mm512_set1_pd(M_PI));
}
#endif
#endif
