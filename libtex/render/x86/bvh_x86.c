/* bvh_x86.c - a batch of shadow rays against a box in AVX-512's or AVX2's lanes, a packet's
 * eye rays against a node's four boxes in AVX2's */
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

/* slab8 in AVX2's four lanes */
TEX_AVX2 static inline void slab4(double lo_b, double hi_b, __m256d o, __m256d inv, __m256d *lo,
                                  __m256d *hi)
{
    __m256d a = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(lo_b), o), inv);
    __m256d c = _mm256_mul_pd(_mm256_sub_pd(_mm256_set1_pd(hi_b), o), inv);
    *lo = _mm256_max_pd(*lo, _mm256_min_pd(a, c));
    *hi = _mm256_min_pd(*hi, _mm256_max_pd(a, c));
}

TEX_AVX2 uint64_t tex_rays_box_avx2(const struct tex_bounds *b, const struct tex_ray_lanes *r,
                                    uint64_t m)
{
    const double blo[3] = {b->lo.x, b->lo.y, b->lo.z}, bhi[3] = {b->hi.x, b->hi.y, b->hi.z};
    uint64_t in = 0;
    for (int i = 0; i < 64 && m >> i; i += 4) {
        int k = (int)(m >> i & 15);
        if (!k)
            continue;
        /* masked loads, as tex_rays_box_avx512's: lanes past the batch are not read */
        __m256i km = _mm256_set_epi64x(-(k >> 3 & 1), -(k >> 2 & 1), -(k >> 1 & 1), -(k & 1));
        __m256d lo = _mm256_maskload_pd(r->tmin + i, km), hi = _mm256_maskload_pd(r->tmax + i, km);
        for (int c = 0; c < 3; c++)
            slab4(blo[c], bhi[c], _mm256_maskload_pd(r->o[c] + i, km),
                  _mm256_maskload_pd(r->inv[c] + i, km), &lo, &hi);
        in |= (uint64_t)(_mm256_movemask_pd(_mm256_cmp_pd(lo, hi, _CMP_LE_OQ)) & k) << i;
    }
    return in;
}

TEX_AVX2 void tex_box4_rays_avx2(const struct tex_box4 *b, int mask, const struct tex_ray_lanes *r,
                                 uint64_t m, uint64_t in[4], double t[4])
{
    for (int c = 0; c < 4; c++) {
        in[c] = 0, t[c] = INFINITY;
        if (!(mask >> c & 1))
            continue;
        __m256d blo[3], bhi[3], tc = _mm256_set1_pd(INFINITY);
        for (int a = 0; a < 3; a++)
            blo[a] = _mm256_set1_pd(b->lo[a][c]), bhi[a] = _mm256_set1_pd(b->hi[a][c]);
        for (int i = 0; i < 64 && m >> i; i += 4) {
            int k = (int)(m >> i & 15);
            if (!k)
                continue;
            __m256d lo = _mm256_loadu_pd(r->tmin + i), hi = _mm256_loadu_pd(r->tmax + i);
            for (int a = 0; a < 3; a++) { /* tex_box4_hit's operations, its operands' order */
                __m256d o = _mm256_loadu_pd(r->o[a] + i), inv = _mm256_loadu_pd(r->inv[a] + i);
                __m256d p = _mm256_mul_pd(_mm256_sub_pd(blo[a], o), inv);
                __m256d q = _mm256_mul_pd(_mm256_sub_pd(bhi[a], o), inv);
                lo = _mm256_max_pd(lo, _mm256_min_pd(p, q));
                hi = _mm256_min_pd(hi, _mm256_max_pd(p, q));
            }
            __m256d yes = _mm256_cmp_pd(lo, hi, _CMP_LE_OQ);
            int e = _mm256_movemask_pd(yes) & k;
            if (!e)
                continue;
            in[c] |= (uint64_t)e << i;
            /* the entries of the rays of m that enter; INFINITY in the other lanes */
            __m256d take = _mm256_and_pd(yes, _mm256_castsi256_pd(_mm256_set_epi64x(
                                                  -(k >> 3 & 1), -(k >> 2 & 1), -(k >> 1 & 1), -(k & 1))));
            tc = _mm256_min_pd(tc, _mm256_blendv_pd(_mm256_set1_pd(INFINITY), lo, take));
        }
        double v[4];
        _mm256_storeu_pd(v, tc);
        t[c] = tex_mind(tex_mind(v[0], v[1]), tex_mind(v[2], v[3]));
    }
}
#endif
