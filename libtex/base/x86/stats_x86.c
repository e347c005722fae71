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

/* Four lanes' figures in registers */
struct lanes4 {
    __m128 lo, hi;
    __m256d sum, s1, s2;
    __m256i n, nan;
};

/* Four samples v into A's lanes, whose shifts are k: lane_take's operations */
TEX_AVX2 static inline __attribute__((always_inline)) void take4(struct lanes4 *A, __m128 v,
                                                                 __m256d k, int sums)
{
    const __m128 inf = _mm_set1_ps(__builtin_inff()), sign = _mm_set1_ps(-0.0f);
    /* finite: |v| < inf, false for NaN; min_ps(u, lo) is u < lo ? u : lo, as lane_take, u = v
     * where finite and +inf (never below lo) elsewhere: one operation on the chain from lo
     * to lo, not two */
    __m128 fin = _mm_cmplt_ps(_mm_andnot_ps(sign, v), inf);
    A->lo = _mm_min_ps(_mm_blendv_ps(inf, v, fin), A->lo);
    A->hi = _mm_max_ps(_mm_blendv_ps(_mm_xor_ps(inf, sign), v, fin), A->hi);
    __m256i f64 = _mm256_cvtepi32_epi64(_mm_castps_si128(fin)); /* all ones where finite */
    A->n = _mm256_sub_epi64(A->n, f64);
    if (sums) {
        __m256d vd = _mm256_cvtps_pd(v), m = _mm256_castsi256_pd(f64);
        __m256d d = _mm256_and_pd(m, _mm256_sub_pd(vd, k));
        A->sum = _mm256_add_pd(A->sum, _mm256_and_pd(m, vd));
        A->s1 = _mm256_add_pd(A->s1, d);
        A->s2 = _mm256_add_pd(A->s2, _mm256_mul_pd(d, d));
        __m128i isnan = _mm_castps_si128(_mm_cmpunord_ps(v, v));
        A->nan = _mm256_sub_epi64(A->nan, _mm256_cvtepi32_epi64(isnan));
    }
}

/* Lanes l[0..3] of the lane sets at[0..3] into A, or (out) A into them */
TEX_AVX2 static inline void lanes_move(struct lanes4 *A, struct tex_stats_lanes *const at[4],
                                       const int l[4], int out)
{
    float lo[4], hi[4];
    double sum[4], s1[4], s2[4];
    long long n[4], nan[4];
    if (out) {
        _mm_storeu_ps(lo, A->lo), _mm_storeu_ps(hi, A->hi);
        _mm256_storeu_pd(sum, A->sum), _mm256_storeu_pd(s1, A->s1), _mm256_storeu_pd(s2, A->s2);
        _mm256_storeu_si256((__m256i *)n, A->n), _mm256_storeu_si256((__m256i *)nan, A->nan);
    }
    for (int e = 0; e < 4; e++) {
        struct tex_stats_lanes *c = at[e];
        if (out) {
            c->lo[l[e]] = lo[e], c->hi[l[e]] = hi[e], c->sum[l[e]] = sum[e];
            c->s1[l[e]] = s1[e], c->s2[l[e]] = s2[e], c->n[l[e]] = n[e], c->nan[l[e]] = nan[e];
        } else {
            lo[e] = c->lo[l[e]], hi[e] = c->hi[l[e]], sum[e] = c->sum[l[e]];
            s1[e] = c->s1[l[e]], s2[e] = c->s2[l[e]], n[e] = c->n[l[e]], nan[e] = c->nan[l[e]];
        }
    }
    if (!out) {
        A->lo = _mm_loadu_ps(lo), A->hi = _mm_loadu_ps(hi);
        A->sum = _mm256_loadu_pd(sum), A->s1 = _mm256_loadu_pd(s1), A->s2 = _mm256_loadu_pd(s2);
        A->n = _mm256_loadu_si256((const __m256i *)n);
        A->nan = _mm256_loadu_si256((const __m256i *)nan);
    }
}

TEX_AVX2 size_t tex_stats_row_avx2(struct tex_stats_lanes *L, const float *px, size_t w, int nc,
                                   double k0, int sums)
{
    struct tex_stats_lanes *const at[4] = {L, L, L, L};
    static const int l[4] = {0, 1, 2, 3};
    const __m256d k = _mm256_set1_pd(k0);
    struct lanes4 A;
    size_t x = 0;

    lanes_move(&A, at, l, 0);
    for (; x + 4 <= w; x += 4)
        take4(&A, four(px, x, nc), k, sums);
    lanes_move(&A, at, l, 1);
    return x;
}

TEX_AVX2 size_t tex_stats_pixels3_avx2(struct tex_stats_lanes L[3], const float *px, size_t w,
                                       const double k0[3])
{
    size_t end = w - w % 4;

    /* vector g of each step at a time (its sums stay in registers through the row): its
     * sample e is the step's 4 g + e, channel (4 g + e) % 3 of pixel (4 g + e) / 3, whose
     * lane is its pixel's */
    for (int g = 0; g < 3; g++) {
        struct tex_stats_lanes *at[4];
        int l[4];
        double k[4];
        struct lanes4 A;
        for (int e = 0; e < 4; e++)
            at[e] = &L[(4 * g + e) % 3], l[e] = (4 * g + e) / 3, k[e] = k0[(4 * g + e) % 3];
        __m256d kv = _mm256_loadu_pd(k);
        lanes_move(&A, at, l, 0);
        for (size_t x = 0; x < end; x += 4)
            take4(&A, _mm_loadu_ps(px + x * 3 + 4 * g), kv, 1);
        lanes_move(&A, at, l, 1);
    }
    return end;
}
#endif
