/* geometry_x86.c - the solid checker's cells in AVX2's lanes (geometry_x86.h) */
#include <math.h>

#include "base/x86/simd_x86.h"
#include "prim/cell.h"
#include "prim/x86/geometry_x86.h"

#ifdef TEX_X86
/* geometry.c's half_odd of four coordinates s: all ones where the cell is odd */
TEX_AVX2 static inline __m256d half_odd4(__m256d s)
{
    const __m256d two = _mm256_set1_pd(2);
    __m256d c = _mm256_floor_pd(
        _mm256_add_pd(_mm256_mul_pd(two, s), _mm256_set1_pd(TEX_CELL_EPS)));
    __m256d odd = _mm256_sub_pd(c, _mm256_mul_pd(two, _mm256_floor_pd(_mm256_div_pd(c, two))));
    __m256d finite = _mm256_cmp_pd(_mm256_andnot_pd(_mm256_set1_pd(-0.0), c),
                                   _mm256_set1_pd(INFINITY), _CMP_LT_OQ);
    return _mm256_and_pd(finite, _mm256_cmp_pd(odd, _mm256_setzero_pd(), _CMP_NEQ_UQ));
}

TEX_AVX2 int tex_checker3_avx2(double nu, double nv, double nw, int n, const double *u,
                               const double *v, const double *w, float *out)
{
    int i = 0;
    for (; i + 4 <= n; i += 4) {
        __m256d pu = half_odd4(_mm256_mul_pd(_mm256_loadu_pd(u + i), _mm256_set1_pd(nu)));
        __m256d pv = half_odd4(_mm256_mul_pd(_mm256_loadu_pd(v + i), _mm256_set1_pd(nv)));
        __m256d pw = half_odd4(_mm256_mul_pd(_mm256_loadu_pd(w + i), _mm256_set1_pd(nw)));
        __m256d p = _mm256_xor_pd(_mm256_xor_pd(pu, pv), pw); /* the sum's parity */
        __m256d r = _mm256_add_pd(_mm256_set1_pd(1), _mm256_and_pd(p, _mm256_set1_pd(1)));
        _mm_storeu_ps(out + i, _mm256_cvtpd_ps(r)); /* 1 or 2: exact in float */
    }
    return i;
}
#endif
