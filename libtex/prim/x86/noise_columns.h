/* noise_columns.h - transposes of rows of four floats, for noise.c's x86 kernels
 *
 * Shared by x86/noise_points_x86.c (a point's gradients) and x86/noise_x86.c (a
 * column's coefficients): rows loaded from tables become the vectors of their
 * columns, without gathers.
 */
#ifndef TEX_NOISE_COLUMNS_H
#define TEX_NOISE_COLUMNS_H

#include "../../base/x86/simd_x86.h"

/* Four rows of four floats in each 128-bit half of a0..a3 as the vectors of their four
 * columns (row i of each half in lane i of that half) */
TEX_AVX2 static inline __attribute__((always_inline)) void
columns4(__m256 a0, __m256 a1, __m256 a2, __m256 a3, __m256 c[4])
{
    __m256 t0 = _mm256_unpacklo_ps(a0, a1), t1 = _mm256_unpacklo_ps(a2, a3);
    __m256 t2 = _mm256_unpackhi_ps(a0, a1), t3 = _mm256_unpackhi_ps(a2, a3);
    c[0] = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));
    c[1] = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));
    c[2] = _mm256_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));
    c[3] = _mm256_shuffle_ps(t2, t3, _MM_SHUFFLE(3, 2, 3, 2));
}

/* Eight rows of four floats as the four vectors of their columns (row i in lane i) */
TEX_AVX2 static inline __attribute__((always_inline)) void columns8(const float *const row[8],
                                                                __m256 c[4])
{
    columns4(_mm256_loadu2_m128(row[4], row[0]), _mm256_loadu2_m128(row[5], row[1]),
             _mm256_loadu2_m128(row[6], row[2]), _mm256_loadu2_m128(row[7], row[3]), c);
}

/* Four rows of four floats in each 128-bit quarter of r[0..3] as the vectors of their
 * columns (row i of each quarter in lane i of that quarter): columns4 on 512 bits */
TEX_AVX512 static inline __attribute__((always_inline)) void columns4_16(const __m512 r[4],
                                                                         __m512 c[4])
{
    __m512 t0 = _mm512_unpacklo_ps(r[0], r[1]), t1 = _mm512_unpacklo_ps(r[2], r[3]);
    __m512 t2 = _mm512_unpackhi_ps(r[0], r[1]), t3 = _mm512_unpackhi_ps(r[2], r[3]);
    c[0] = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));
    c[1] = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));
    c[2] = _mm512_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));
    c[3] = _mm512_shuffle_ps(t2, t3, _MM_SHUFFLE(3, 2, 3, 2));
}

#endif
