/* palette_x86.c - palette.c's OKLab to sRGB eight colours at a time (AVX-512) */
#include <stdint.h>

#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "ops/palette_srgb.h"
#include "ops/x86/palette_x86.h"

/* srgb_encode of eight values: enc_pow's operations in its order, lane by lane, so the same
 * floats; NaNs, and the lanes where the polynomial cannot decide, go to srgb_encode. */
TEX_AVX512 static __m256 srgb_encode8(const struct tex_srgb_enc *e, __m512d x)
{
    const __m512d half = _mm512_set1_pd(0.5), pieces = _mm512_set1_pd(2 * ENC_PIECES);
    __mmask8 toe = _mm512_cmp_pd_mask(x, _mm512_set1_pd(0.0031308), _CMP_LE_OQ);
    __mmask8 mid = _mm512_cmp_pd_mask(x, _mm512_set1_pd(1.0), _CMP_LT_OQ) & ~toe; /* not NaN */
    __m512i bits = _mm512_castpd_si512(_mm512_mask_blend_pd(mid, half, x)); /* c = m 2^e */
    __m512i ie = _mm512_sub_epi64(_mm512_set1_epi64(1022), _mm512_srli_epi64(bits, 52)); /* -e */
    bits = _mm512_or_si512(_mm512_and_si512(bits, _mm512_set1_epi64((INT64_C(1) << 52) - 1)),
                           _mm512_set1_epi64(INT64_C(1022) << 52));
    __m512d m = _mm512_castsi512_pd(bits);
    __m256i i = _mm512_cvttpd_epi32(_mm512_mul_pd(_mm512_sub_pd(m, half), pieces));
    __m512d centre = _mm512_div_pd(_mm512_add_pd(_mm512_cvtepi32_pd(i), half), pieces);
    __m512d t = _mm512_sub_pd(m, _mm512_add_pd(half, centre));
    __m512d t2 = _mm512_mul_pd(t, t), p[ENC_DEGREE + 1];
    __m512i i64 = _mm512_cvtepi32_epi64(i); /* 0..31: a permute of 16 entries, by bit 4 */
    __mmask8 upper = _mm512_test_epi64_mask(i64, _mm512_set1_epi64(16));
    for (int k = 0; k <= ENC_DEGREE; k++) {
        const double *ck = e->coef[k];
        __m512d lo16 = _mm512_permutex2var_pd(_mm512_loadu_pd(ck), i64, _mm512_loadu_pd(ck + 8));
        __m512d hi16 =
            _mm512_permutex2var_pd(_mm512_loadu_pd(ck + 16), i64, _mm512_loadu_pd(ck + 24));
        p[k] = _mm512_mask_blend_pd(upper, lo16, hi16);
    }
    __m512d a = _mm512_add_pd(p[0], _mm512_mul_pd(p[1], t));
    __m512d b = _mm512_mul_pd(t2, _mm512_add_pd(p[2], _mm512_mul_pd(p[3], t)));
    __m512d d = _mm512_add_pd(_mm512_add_pd(p[4], _mm512_mul_pd(p[5], t)), _mm512_mul_pd(t2, p[6]));
    __m512d y = _mm512_add_pd(_mm512_add_pd(a, b), _mm512_mul_pd(_mm512_mul_pd(t2, t2), d));
    y = _mm512_mul_pd(y, _mm512_permutex2var_pd(_mm512_loadu_pd(e->scale), ie,
                                                _mm512_loadu_pd(e->scale + 8)));
    __m512d v = _mm512_sub_pd(_mm512_mul_pd(_mm512_set1_pd(1.055), y), _mm512_set1_pd(0.055));
    __m256 lo = _mm512_cvtpd_ps(_mm512_sub_pd(v, _mm512_set1_pd(2e-12)));
    __m256 hi = _mm512_cvtpd_ps(_mm512_add_pd(v, _mm512_set1_pd(2e-12)));
    int done = _mm256_movemask_ps(_mm256_cmp_ps(lo, hi, _CMP_EQ_OQ)) & mid;
    if (done != 0xff) {
        __m256 lin = _mm512_cvtpd_ps(_mm512_mul_pd(_mm512_set1_pd(12.92), x)); /* the toe's */
        double c[8];
        _mm512_storeu_pd(c, x);
        for (int k = 0; k < 8; k++)
            if (!(done >> k & 1))
                lo[k] = toe >> k & 1 && c[k] > 0.0 ? lin[k] : tex_palette_srgb_encode(c[k]);
    }
    return lo;
}

/* Eight colours: oklab_linear's operations lane by lane */
TEX_AVX512 static void oklab_srgb8(const struct tex_srgb_enc *e, const float *lab[3], float *rgb[3])
{
    __m512d L = _mm512_cvtps_pd(_mm256_loadu_ps(lab[0]));
    __m512d A = _mm512_cvtps_pd(_mm256_loadu_ps(lab[1]));
    __m512d B = _mm512_cvtps_pd(_mm256_loadu_ps(lab[2])), c[3];
    for (int k = 0; k < 3; k++) {
        c[k] = _mm512_add_pd(_mm512_add_pd(L, _mm512_mul_pd(_mm512_set1_pd(ok_lms[k][0]), A)),
                             _mm512_mul_pd(_mm512_set1_pd(ok_lms[k][1]), B));
        c[k] = _mm512_mul_pd(_mm512_mul_pd(c[k], c[k]), c[k]);
    }
    for (int k = 0; k < 3; k++) {
        __m512d lin = _mm512_mul_pd(_mm512_set1_pd(ok_rgb[k][0]), c[0]);
        lin = _mm512_add_pd(lin, _mm512_mul_pd(_mm512_set1_pd(ok_rgb[k][1]), c[1]));
        lin = _mm512_add_pd(lin, _mm512_mul_pd(_mm512_set1_pd(ok_rgb[k][2]), c[2]));
        _mm256_storeu_ps(rgb[k], srgb_encode8(e, lin));
    }
}

int tex_oklab_srgb_avx512(const struct tex_srgb_enc *e, const float *const lab[3],
                          float *const rgb[3], int n)
{
    int i = 0;
    for (; i + 8 <= n; i += 8)
        oklab_srgb8(e, (const float *[3]){lab[0] + i, lab[1] + i, lab[2] + i},
                    (float *[3]){rgb[0] + i, rgb[1] + i, rgb[2] + i});
    return i;
}
#endif
