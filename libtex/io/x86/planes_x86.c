/* planes_x86.c - planes.c's moves of three and four channels eight pixels at a time (AVX2) */
#include "base/x86/interleave_x86.h"
#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "io/x86/planes_x86.h"

TEX_AVX2 size_t tex_planes_join_avx2(float *px, const float *const *plane, int nc, size_t w)
{
    size_t x = 0;
    __m256 c[4];
    if (nc == 3)
        for (; x + 8 <= w; x += 8) {
            for (int k = 0; k < 3; k++)
                c[k] = _mm256_loadu_ps(plane[k] + x);
            tex_interleave3_avx2(c, px + x * 3);
        }
    else if (nc == 4)
        for (; x + 8 <= w; x += 8) {
            for (int k = 0; k < 4; k++)
                c[k] = _mm256_loadu_ps(plane[k] + x);
            tex_interleave4_avx2(c, px + x * 4);
        }
    return x;
}

TEX_AVX2 size_t tex_planes_split_avx2(float *const *plane, const float *px, int nc, size_t w)
{
    size_t x = 0;
    __m256 c[4];
    if (nc == 3)
        for (; x + 8 <= w; x += 8) {
            tex_deinterleave3_avx2(px + x * 3, c);
            for (int k = 0; k < 3; k++)
                _mm256_storeu_ps(plane[k] + x, c[k]);
        }
    else if (nc == 4)
        for (; x + 8 <= w; x += 8) {
            tex_deinterleave4_avx2(px + x * 4, c);
            for (int k = 0; k < 4; k++)
                _mm256_storeu_ps(plane[k] + x, c[k]);
        }
    return x;
}
#endif
