/* render_ct_x86.c - the Cook-Torrance model's spectrum loops in SSE2 vectors */
#include "base/x86/simd_x86.h"
#include "render/x86/render_ct_x86.h"

#if defined(TEX_X86) && defined(__SSE2__)
static inline __m128 clamp01_ps(__m128 f)
{
    return _mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), _mm_set1_ps(1));
}

/* tex_fresnel_conductor (fresnel.h, eta_i = 1) in single precision for a whole
 * spectrum at once: the same exact formula without a call per sample. */
void tex_fresnel_conductor_n_sse2(double cos_i, const float *n, const float *k, int count,
                                   float *out)
{
    float cf = (float)(cos_i < 0 ? 0 : cos_i > 1 ? 1 : cos_i);
    __m128 c = _mm_set1_ps(cf), c2 = _mm_set1_ps(cf * cf), s2 = _mm_set1_ps(1 - cf * cf);
    __m128 half = _mm_set1_ps(0.5f), two = _mm_set1_ps(2), four = _mm_set1_ps(4);
    for (int i = 0; i < count; i += 4) {
        float nb[4] = {1, 1, 1, 1}, kb[4] = {0, 0, 0, 0}, ob[4];
        int m = count - i < 4 ? count - i : 4;
        for (int j = 0; j < m; j++)
            nb[j] = n[i + j], kb[j] = k[i + j];
        __m128 nv = _mm_loadu_ps(nb), kv = _mm_loadu_ps(kb);
        __m128 e2 = _mm_mul_ps(nv, nv), k2 = _mm_mul_ps(kv, kv);
        __m128 t0 = _mm_sub_ps(_mm_sub_ps(e2, k2), s2);
        __m128 a2b2 = _mm_sqrt_ps(
            _mm_add_ps(_mm_mul_ps(t0, t0), _mm_mul_ps(_mm_mul_ps(four, e2), k2)));
        __m128 h = _mm_mul_ps(half, _mm_add_ps(a2b2, t0));
        __m128 a = _mm_sqrt_ps(_mm_max_ps(h, _mm_setzero_ps()));
        __m128 t1 = _mm_add_ps(a2b2, c2), t2 = _mm_mul_ps(_mm_mul_ps(two, a), c);
        __m128 rs = _mm_div_ps(_mm_sub_ps(t1, t2), _mm_add_ps(t1, t2));
        __m128 t3 = _mm_add_ps(_mm_mul_ps(c2, a2b2), _mm_mul_ps(s2, s2));
        __m128 t4 = _mm_mul_ps(t2, s2);
        __m128 rp = _mm_div_ps(_mm_mul_ps(rs, _mm_sub_ps(t3, t4)), _mm_add_ps(t3, t4));
        _mm_storeu_ps(ob, clamp01_ps(_mm_mul_ps(half, _mm_add_ps(rs, rp))));
        for (int j = 0; j < m; j++)
            out[i + j] = ob[j];
    }
}

/* tex_fresnel_dielectric (fresnel.h) in single precision for a whole spectrum:
 * r[i] = eta_i / eta_t per sample, c = cos of the angle of incidence. */
void tex_fresnel_dielectric_n_sse2(float cf, const float *r, int count, float *out)
{
    __m128 c = _mm_set1_ps(cf), s2 = _mm_set1_ps(1 - cf * cf), one = _mm_set1_ps(1);
    __m128 half = _mm_set1_ps(0.5f);
    for (int i = 0; i < count; i += 4) {
        float rb[4] = {1, 1, 1, 1}, ob[4];
        int m = count - i < 4 ? count - i : 4;
        for (int j = 0; j < m; j++)
            rb[j] = r[i + j];
        __m128 rv = _mm_loadu_ps(rb);
        __m128 st2 = _mm_mul_ps(_mm_mul_ps(rv, rv), s2);
        __m128 ct = _mm_sqrt_ps(_mm_max_ps(_mm_sub_ps(one, st2), _mm_setzero_ps()));
        __m128 rc = _mm_mul_ps(rv, c), rct = _mm_mul_ps(rv, ct);
        __m128 rpar = _mm_div_ps(_mm_sub_ps(c, rct), _mm_add_ps(c, rct));
        __m128 rperp = _mm_div_ps(_mm_sub_ps(rc, ct), _mm_add_ps(rc, ct));
        __m128 f = clamp01_ps(
            _mm_mul_ps(half, _mm_add_ps(_mm_mul_ps(rpar, rpar), _mm_mul_ps(rperp, rperp))));
        __m128 tir = _mm_cmpge_ps(st2, one); /* total internal reflection */
        _mm_storeu_ps(ob, _mm_or_ps(_mm_and_ps(tir, one), _mm_andnot_ps(tir, f)));
        for (int j = 0; j < m; j++)
            out[i + j] = ob[j];
    }
}
#endif
