/* bvh_x86.c - a batch of shadow rays against a box in AVX-512 lanes */
#include "render/x86/bvh_x86.h"

#ifdef TEX_X86
/* hit_box's slab of one axis: lo and hi narrowed as its tex_maxd and tex_mind narrow them
 * (max_pd and min_pd take the second operand where the first does not compare, as they
 * do) */
TEX_AVX512 static inline void slab8(double lo_b, double hi_b, __m512d o, __m512d inv,
                                    __m512d *lo, __m512d *hi)
{
    __m512d a = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(lo_b), o), inv);
    __m512d c = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(hi_b), o), inv);
    *lo = _mm512_max_pd(*lo, _mm512_min_pd(a, c));
    *hi = _mm512_min_pd(*hi, _mm512_max_pd(a, c));
}

TEX_AVX512 uint64_t tex_rays_box_avx512(const struct tex_bounds *b, const struct tex_ray_lanes *r,
                                        uint64_t m)
{
    const double blo[3] = {b->lo.x, b->lo.y, b->lo.z}, bhi[3] = {b->hi.x, b->hi.y, b->hi.z};
    uint64_t in = 0;
    for (int i = 0; i < 64 && m >> i; i += 8) {
        __mmask8 k = (__mmask8)(m >> i);
        if (!k)
            continue;
        /* masked loads: lanes past the batch are neither read nor answered */
        __m512d lo = _mm512_maskz_loadu_pd(k, r->tmin + i), hi = _mm512_maskz_loadu_pd(k, r->tmax + i);
        for (int c = 0; c < 3; c++)
            slab8(blo[c], bhi[c], _mm512_maskz_loadu_pd(k, r->o[c] + i),
                  _mm512_maskz_loadu_pd(k, r->inv[c] + i), &lo, &hi);
        in |= (uint64_t)_mm512_mask_cmp_pd_mask(k, lo, hi, _CMP_LE_OQ) << i;
    }
    return in;
}
#endif
