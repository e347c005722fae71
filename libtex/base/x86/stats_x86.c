/* stats_x86.c - map.c's statistics of a row in four lanes at once (AVX2, see stats_x86.h) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "base/x86/stats_x86.h"

/* Samples x..x+3, nc floats apart */
TEX_AVX2 static inline __m128 four(const float *px, size_t x, int nc)
{
    if (nc == 1)
        return _mm_loadu_ps(px + x);
    return _mm_set_ps(px[(x + 3) * nc], px[(x + 2) * nc], px[(x + 1) * nc], px[x * nc]);
}

TEX_AVX2 size_t tex_stats_row_avx2(struct tex_stats_lanes *L, const float *px, size_t w, int nc,
                                   double k0, int sums)
{
    const __m128 inf = _mm_set1_ps(__builtin_inff()), sign = _mm_set1_ps(-0.0f);
    const __m256d k = _mm256_set1_pd(k0);
    __m128 lo = _mm_loadu_ps(L->lo), hi = _mm_loadu_ps(L->hi);
    __m256d sum = _mm256_loadu_pd(L->sum), s1 = _mm256_loadu_pd(L->s1), s2 = _mm256_loadu_pd(L->s2);
    __m256i n = _mm256_loadu_si256((const __m256i *)L->n);
    __m256i nan = _mm256_loadu_si256((const __m256i *)L->nan);
    size_t x = 0;

    for (; x + 4 <= w; x += 4) {
        __m128 v = four(px, x, nc);
        /* finite: |v| < inf, false for NaN; min_ps(v, lo) is v < lo ? v : lo, as lane_take */
        __m128 fin = _mm_cmplt_ps(_mm_andnot_ps(sign, v), inf);
        lo = _mm_blendv_ps(lo, _mm_min_ps(v, lo), fin);
        hi = _mm_blendv_ps(hi, _mm_max_ps(v, hi), fin);
        __m256i f64 = _mm256_cvtepi32_epi64(_mm_castps_si128(fin)); /* all ones where finite */
        n = _mm256_sub_epi64(n, f64);
        if (sums) {
            __m256d vd = _mm256_cvtps_pd(v), m = _mm256_castsi256_pd(f64);
            __m256d d = _mm256_and_pd(m, _mm256_sub_pd(vd, k));
            sum = _mm256_add_pd(sum, _mm256_and_pd(m, vd));
            s1 = _mm256_add_pd(s1, d);
            s2 = _mm256_add_pd(s2, _mm256_mul_pd(d, d));
            __m128i isnan = _mm_castps_si128(_mm_cmpunord_ps(v, v));
            nan = _mm256_sub_epi64(nan, _mm256_cvtepi32_epi64(isnan));
        }
    }
    _mm_storeu_ps(L->lo, lo), _mm_storeu_ps(L->hi, hi);
    _mm256_storeu_pd(L->sum, sum), _mm256_storeu_pd(L->s1, s1), _mm256_storeu_pd(L->s2, s2);
    _mm256_storeu_si256((__m256i *)L->n, n);
    _mm256_storeu_si256((__m256i *)L->nan, nan);
    return x;
}
#endif
