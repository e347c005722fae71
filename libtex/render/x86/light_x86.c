/* light_x86.c - a point or spot light at four hits, four samples of an area light at one,
 * in AVX2's lanes */
#include "render/x86/light_x86.h"

#ifdef TEX_X86
/* tex_light_point_at in four lanes from d = pos - P: L, the distance dl and the attenuation
 * fatt; the lanes where the light reaches P (ok: all bits set), fatt > 0 still to test */
static TEX_AVX2 inline __m256d towards4(const struct tex_light *l, const __m256d d[3],
                                        __m256d L[3], __m256d *dist, __m256d *att)
{
    __m256d one = _mm256_set1_pd(1), zero = _mm256_setzero_pd();
    __m256d dl = _mm256_sqrt_pd(_mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(d[0], d[0]), _mm256_mul_pd(d[1], d[1])),
        _mm256_mul_pd(d[2], d[2])));
    __m256d ok = _mm256_cmp_pd(dl, zero, _CMP_GT_OQ), s = _mm256_div_pd(one, dl);
    for (int c = 0; c < 3; c++)
        L[c] = _mm256_mul_pd(d[c], s);
    __m256d fatt = one; /* tex_light_falloff */
    if (l->falloff == TEX_FALL_SQUARE) {
        fatt = _mm256_div_pd(one, _mm256_mul_pd(dl, dl));
    } else if (l->falloff == TEX_FALL_POLY) {
        __m256d q = _mm256_add_pd(
            _mm256_add_pd(_mm256_set1_pd(l->c1), _mm256_mul_pd(_mm256_set1_pd(l->c2), dl)),
            _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(l->c3), dl), dl));
        fatt = _mm256_blendv_pd(one, _mm256_div_pd(one, q), _mm256_cmp_pd(q, one, _CMP_GT_OQ));
    }
    if (l->kind == TEX_LIGHT_SPOT) { /* the cone, then tex_powi's squares */
        __m256d c = _mm256_xor_pd(
            _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(L[0], _mm256_set1_pd(l->dir.x)),
                                        _mm256_mul_pd(L[1], _mm256_set1_pd(l->dir.y))),
                          _mm256_mul_pd(L[2], _mm256_set1_pd(l->dir.z))),
            _mm256_set1_pd(-0.0));
        ok = _mm256_and_pd(ok, _mm256_cmp_pd(c, _mm256_set1_pd(l->cos_angle), _CMP_NLT_UQ));
        __m256d r = one;
        for (int k = (int)l->exponent; k; k >>= 1, c = _mm256_mul_pd(c, c))
            if (k & 1)
                r = _mm256_mul_pd(r, c);
        fatt = _mm256_mul_pd(fatt, r);
    }
    *dist = dl, *att = fatt;
    return ok;
}

/* The four samples into a, ok where fatt > 0 too */
static TEX_AVX2 inline void samples4(const __m256d L[3], __m256d dl, __m256d fatt, __m256d ok,
                                     struct tex_light_ahead *a)
{
    ok = _mm256_and_pd(ok, _mm256_cmp_pd(fatt, _mm256_setzero_pd(), _CMP_GT_OQ));
    double lx[4], ly[4], lz[4], dist[4], fa[4];
    _mm256_storeu_pd(lx, L[0]), _mm256_storeu_pd(ly, L[1]), _mm256_storeu_pd(lz, L[2]);
    _mm256_storeu_pd(dist, dl), _mm256_storeu_pd(fa, fatt);
    int m = _mm256_movemask_pd(ok);
    for (int k = 0; k < 4; k++)
        a[k] = (struct tex_light_ahead){tex_v3_make(lx[k], ly[k], lz[k]), dist[k], fa[k],
                                        m >> k & 1};
}

TEX_AVX2 void tex_light_points4_avx2(const struct tex_light *l, const tex_v3 *P,
                                     struct tex_light_ahead *a)
{
    __m256d d[3], L[3], dl, fatt;
    const double pos[3] = {l->pos.x, l->pos.y, l->pos.z};
    for (int c = 0; c < 3; c++) /* pos - P, the four points' coordinate c */
        d[c] = _mm256_sub_pd(_mm256_set1_pd(pos[c]),
                             _mm256_setr_pd(tex_v3_get(P[0], c), tex_v3_get(P[1], c),
                                            tex_v3_get(P[2], c), tex_v3_get(P[3], c)));
    __m256d ok = towards4(l, d, L, &dl, &fatt);
    samples4(L, dl, fatt, ok, a);
}

TEX_AVX2 void tex_light_area4_avx2(const struct tex_light *l, int k, const double *jx,
                                   const double *jy, const tex_v3 *P, struct tex_light_ahead *a)
{
    int n = l->samples, e = __builtin_ctz((unsigned)n);
    union {
        uint64_t u;
        double d;
    } inv = {(uint64_t)(1023 - e) << 52}; /* 2^-e, tex_light_sample's */
    __m256d cx = _mm256_setr_pd(k & (n - 1), (k + 1) & (n - 1), (k + 2) & (n - 1),
                                (k + 3) & (n - 1));
    __m256d cy = _mm256_setr_pd(k >> e, (k + 1) >> e, (k + 2) >> e, (k + 3) >> e);
    __m256d i2 = _mm256_set1_pd(inv.d);
    __m256d ua = _mm256_mul_pd(_mm256_add_pd(cx, _mm256_loadu_pd(jx)), i2);
    __m256d ub = _mm256_mul_pd(_mm256_add_pd(cy, _mm256_loadu_pd(jy)), i2);
    __m256d d[3], L[3], dl, fatt;
    for (int c = 0; c < 3; c++) { /* pos + (edge1 a + edge2 b), less P */
        __m256d at = _mm256_add_pd(
            _mm256_set1_pd(tex_v3_get(l->pos, c)),
            _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(tex_v3_get(l->edge1, c)), ua),
                          _mm256_mul_pd(_mm256_set1_pd(tex_v3_get(l->edge2, c)), ub)));
        d[c] = _mm256_sub_pd(at, _mm256_set1_pd(tex_v3_get(*P, c)));
    }
    __m256d ok = towards4(l, d, L, &dl, &fatt);
    samples4(L, dl, _mm256_mul_pd(fatt, _mm256_mul_pd(i2, i2)), ok, a);
}
#endif
