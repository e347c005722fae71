/* camera_x86.c - the eye's rays in AVX-512 or AVX2 lanes */
#include "base/x86/simd_x86.h"
#include "render/x86/camera_x86.h"

#ifdef TEX_X86
/* camera_ray's rays through the n <= 8 pixels (x[k], y[k]) at (ox[k], oy[k]) inside each:
 * its operations in lanes, so its bits, the square roots and divisions of eight rays at
 * once.  x, y, ox and oy hold 8 readable entries. */
TEX_AVX512 void tex_eye_rays8_avx512(const struct tex_camera *cam, const struct tex_media *media,
                                     const int *x, const int *y, const double *ox,
                                     const double *oy, int n, tex_ray *r)
{
    __m512d v[3];
    __m512d px = _mm512_cvtepi32_pd(_mm256_loadu_si256((const __m256i *)x));
    __m512d py = _mm512_cvtepi32_pd(_mm256_loadu_si256((const __m256i *)y));
    __m512d a = _mm512_sub_pd(
        _mm512_mul_pd(_mm512_add_pd(px, _mm512_loadu_pd(ox)), _mm512_set1_pd(cam->kx)),
        _mm512_set1_pd(cam->sx));
    __m512d b = _mm512_sub_pd(
        _mm512_set1_pd(cam->sy),
        _mm512_mul_pd(_mm512_add_pd(py, _mm512_loadu_pd(oy)), _mm512_set1_pd(cam->ky)));
    const double f[3] = {cam->fwd.x, cam->fwd.y, cam->fwd.z};
    const double rt[3] = {cam->right.x, cam->right.y, cam->right.z};
    const double u[3] = {cam->up.x, cam->up.y, cam->up.z};
    for (int i = 0; i < 3; i++) /* fwd + (right a + up b) */
        v[i] = _mm512_add_pd(_mm512_set1_pd(f[i]),
                             _mm512_add_pd(_mm512_mul_pd(_mm512_set1_pd(rt[i]), a),
                                           _mm512_mul_pd(_mm512_set1_pd(u[i]), b)));
    __m512d l = _mm512_sqrt_pd(_mm512_add_pd(
        _mm512_add_pd(_mm512_mul_pd(v[0], v[0]), _mm512_mul_pd(v[1], v[1])),
        _mm512_mul_pd(v[2], v[2])));
    __mmask8 pos = _mm512_cmp_pd_mask(l, _mm512_setzero_pd(), _CMP_GT_OQ); /* tex_v3_norm */
    __m512d il = _mm512_div_pd(_mm512_set1_pd(1), l);
    double d[3][8];
    for (int i = 0; i < 3; i++)
        _mm512_storeu_pd(d[i], _mm512_mask_mul_pd(v[i], pos, v[i], il));
    for (int k = 0; k < n; k++)
        r[k] = (tex_ray){cam->eye, tex_v3_make(d[0][k], d[1][k], d[2][k]), 0, cam->spread,
                         media, 0};
}
/* tex_eye_rays8_avx512 in AVX2's lanes, four rays a vector */
TEX_AVX2 void tex_eye_rays4_avx2(const struct tex_camera *cam, const struct tex_media *media,
                                 const int *x, const int *y, const double *ox, const double *oy,
                                 int n, tex_ray *r)
{
    __m256d v[3];
    __m256d px = _mm256_cvtepi32_pd(_mm_loadu_si128((const __m128i *)x));
    __m256d py = _mm256_cvtepi32_pd(_mm_loadu_si128((const __m128i *)y));
    __m256d a = _mm256_sub_pd(
        _mm256_mul_pd(_mm256_add_pd(px, _mm256_loadu_pd(ox)), _mm256_set1_pd(cam->kx)),
        _mm256_set1_pd(cam->sx));
    __m256d b = _mm256_sub_pd(
        _mm256_set1_pd(cam->sy),
        _mm256_mul_pd(_mm256_add_pd(py, _mm256_loadu_pd(oy)), _mm256_set1_pd(cam->ky)));
    const double f[3] = {cam->fwd.x, cam->fwd.y, cam->fwd.z};
    const double rt[3] = {cam->right.x, cam->right.y, cam->right.z};
    const double u[3] = {cam->up.x, cam->up.y, cam->up.z};
    for (int i = 0; i < 3; i++) /* fwd + (right a + up b) */
        v[i] = _mm256_add_pd(_mm256_set1_pd(f[i]),
                             _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(rt[i]), a),
                                           _mm256_mul_pd(_mm256_set1_pd(u[i]), b)));
    __m256d l = _mm256_sqrt_pd(_mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(v[0], v[0]), _mm256_mul_pd(v[1], v[1])),
        _mm256_mul_pd(v[2], v[2])));
    __m256d pos = _mm256_cmp_pd(l, _mm256_setzero_pd(), _CMP_GT_OQ); /* tex_v3_norm */
    __m256d il = _mm256_div_pd(_mm256_set1_pd(1), l);
    double d[3][4];
    for (int i = 0; i < 3; i++)
        _mm256_storeu_pd(d[i], _mm256_blendv_pd(v[i], _mm256_mul_pd(v[i], il), pos));
    for (int k = 0; k < n; k++)
        r[k] = (tex_ray){cam->eye, tex_v3_make(d[0][k], d[1][k], d[2][k]), 0, cam->spread,
                         media, 0};
}
#endif
