/* interleave_x86.h - eight pixels' channels, each a vector of eight floats, interleaved into
 * pixels or taken out of them (AVX2), for the kernels that colour pixels (ops/x86/palette_x86.c)
 * and those that move a scanline between EXR's channel runs and a map's pixels
 * (io/x86/planes_x86.c).  Only moves: the floats are the same.
 */
#ifndef TEX_INTERLEAVE_X86_H
#define TEX_INTERLEAVE_X86_H

#include "simd_x86.h"

#ifdef TEX_X86
/* Eight pixels of c[0..2] interleaved into out: float g of the 24 is channel g % 3 of pixel
 * g / 3, each channel's vector permuted to the pixels and blended in where it belongs */
TEX_AVX2 static inline void tex_interleave3_avx2(const __m256 c[3], float *out)
{
    const __m256i i0 = _mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2);
    const __m256i i1 = _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5);
    const __m256i i2 = _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7);
#define PIX3(i, m1, m2)                                                                          \
    _mm256_blend_ps(_mm256_blend_ps(_mm256_permutevar8x32_ps(c[0], i),                          \
                                    _mm256_permutevar8x32_ps(c[1], i), m1),                     \
                    _mm256_permutevar8x32_ps(c[2], i), m2)
    _mm256_storeu_ps(out, PIX3(i0, 0x92, 0x24));
    _mm256_storeu_ps(out + 8, PIX3(i1, 0x24, 0x49));
    _mm256_storeu_ps(out + 16, PIX3(i2, 0x49, 0x92));
#undef PIX3
}

/* The same for four channels: two pixels a vector */
TEX_AVX2 static inline void tex_interleave4_avx2(const __m256 c[4], float *out)
{
    __m256 rg0 = _mm256_unpacklo_ps(c[0], c[1]), rg1 = _mm256_unpackhi_ps(c[0], c[1]);
    __m256 ba0 = _mm256_unpacklo_ps(c[2], c[3]), ba1 = _mm256_unpackhi_ps(c[2], c[3]);
    /* pixels 0 1 | 4 5, 2 3 | 6 7 */
    __m256 p0 = _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(rg0), _mm256_castps_pd(ba0)));
    __m256 p1 = _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(rg0), _mm256_castps_pd(ba0)));
    __m256 p2 = _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(rg1), _mm256_castps_pd(ba1)));
    __m256 p3 = _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(rg1), _mm256_castps_pd(ba1)));
    _mm256_storeu_ps(out, _mm256_permute2f128_ps(p0, p1, 0x20));
    _mm256_storeu_ps(out + 8, _mm256_permute2f128_ps(p2, p3, 0x20));
    _mm256_storeu_ps(out + 16, _mm256_permute2f128_ps(p0, p1, 0x31));
    _mm256_storeu_ps(out + 24, _mm256_permute2f128_ps(p2, p3, 0x31));
}

/* The inverse of tex_interleave3_avx2: channel k of the eight pixels at in, blended from the
 * three vectors where it lies and permuted into pixel order */
TEX_AVX2 static inline void tex_deinterleave3_avx2(const float *in, __m256 c[3])
{
    __m256 o0 = _mm256_loadu_ps(in), o1 = _mm256_loadu_ps(in + 8), o2 = _mm256_loadu_ps(in + 16);
    c[0] = _mm256_permutevar8x32_ps(_mm256_blend_ps(_mm256_blend_ps(o0, o1, 0x92), o2, 0x24),
                                    _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5));
    c[1] = _mm256_permutevar8x32_ps(_mm256_blend_ps(_mm256_blend_ps(o0, o1, 0x24), o2, 0x49),
                                    _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6));
    c[2] = _mm256_permutevar8x32_ps(_mm256_blend_ps(_mm256_blend_ps(o0, o1, 0x49), o2, 0x92),
                                    _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7));
}

/* The inverse of tex_interleave4_avx2: pixels p and p + 4 paired in a vector's halves, then
 * each half's four pixels transposed */
TEX_AVX2 static inline void tex_deinterleave4_avx2(const float *in, __m256 c[4])
{
    __m256 o0 = _mm256_loadu_ps(in), o1 = _mm256_loadu_ps(in + 8);
    __m256 o2 = _mm256_loadu_ps(in + 16), o3 = _mm256_loadu_ps(in + 24);
    __m256 a = _mm256_permute2f128_ps(o0, o2, 0x20), b = _mm256_permute2f128_ps(o0, o2, 0x31);
    __m256 d = _mm256_permute2f128_ps(o1, o3, 0x20), e = _mm256_permute2f128_ps(o1, o3, 0x31);
    __m256d t0 = _mm256_castps_pd(_mm256_unpacklo_ps(a, b));
    __m256d t1 = _mm256_castps_pd(_mm256_unpackhi_ps(a, b));
    __m256d t2 = _mm256_castps_pd(_mm256_unpacklo_ps(d, e));
    __m256d t3 = _mm256_castps_pd(_mm256_unpackhi_ps(d, e));
    c[0] = _mm256_castpd_ps(_mm256_unpacklo_pd(t0, t2));
    c[1] = _mm256_castpd_ps(_mm256_unpackhi_pd(t0, t2));
    c[2] = _mm256_castpd_ps(_mm256_unpacklo_pd(t1, t3));
    c[3] = _mm256_castpd_ps(_mm256_unpackhi_pd(t1, t3));
}
#endif

#endif
