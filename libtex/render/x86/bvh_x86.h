/* bvh_x86.h - a batch of shadow rays against a tree node's box in AVX-512's or AVX2's lanes,
 * and one ray against a node's four children in SSE2's (render_bvh.c's hit_box, its
 * operations in its order: the same answers)
 */
#ifndef TEX_BVH_X86_H
#define TEX_BVH_X86_H

#include <stdint.h>

#include "../../base/x86/simd_x86.h"
#include "../box4.h"
#include "../shape.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef TEX_X86
/* tex_box4_hit (../box4.h) in the lanes of two SSE2 vectors, boxes 0 and 1 in the first:
 * its operations in its order lane by lane (max_pd and min_pd pick as its tex_maxd and
 * tex_mind do, NaN included), so the same answers */
static inline int tex_box4_sse2(const struct tex_box4 *b, const tex_v3 *org, const tex_v3 *rcp,
                                double tmin, double tmax, double t[4])
{
    const double o[3] = {org->x, org->y, org->z}, inv[3] = {rcp->x, rcp->y, rcp->z};
    __m128d lo0 = _mm_set1_pd(tmin), hi0 = _mm_set1_pd(tmax), lo1 = lo0, hi1 = hi0;
    for (int c = 0; c < 3; c++) {
        __m128d oc = _mm_set1_pd(o[c]), ic = _mm_set1_pd(inv[c]);
        __m128d a0 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(b->lo[c]), oc), ic);
        __m128d b0 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(b->hi[c]), oc), ic);
        __m128d a1 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(b->lo[c] + 2), oc), ic);
        __m128d b1 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(b->hi[c] + 2), oc), ic);
        lo0 = _mm_max_pd(lo0, _mm_min_pd(a0, b0));
        hi0 = _mm_min_pd(hi0, _mm_max_pd(a0, b0));
        lo1 = _mm_max_pd(lo1, _mm_min_pd(a1, b1));
        hi1 = _mm_min_pd(hi1, _mm_max_pd(a1, b1));
    }
    _mm_storeu_pd(t, lo0);
    _mm_storeu_pd(t + 2, lo1);
    return _mm_movemask_pd(_mm_cmple_pd(lo0, hi0)) | _mm_movemask_pd(_mm_cmple_pd(lo1, hi1)) << 2;
}

/* tex_box4_hit in the four lanes of AVX2 vectors, as tex_box4_sse2 */
TEX_AVX2 static inline int tex_box4_avx2(const struct tex_box4 *b, const tex_v3 *org,
                                         const tex_v3 *rcp, double tmin, double tmax,
                                         double t[4])
{
    const double o[3] = {org->x, org->y, org->z}, inv[3] = {rcp->x, rcp->y, rcp->z};
    __m256d lo = _mm256_set1_pd(tmin), hi = _mm256_set1_pd(tmax);
    for (int c = 0; c < 3; c++) {
        __m256d oc = _mm256_set1_pd(o[c]), ic = _mm256_set1_pd(inv[c]);
        __m256d a = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(b->lo[c]), oc), ic);
        __m256d d = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(b->hi[c]), oc), ic);
        lo = _mm256_max_pd(lo, _mm256_min_pd(a, d));
        hi = _mm256_min_pd(hi, _mm256_max_pd(a, d));
    }
    _mm256_storeu_pd(t, lo);
    return _mm256_movemask_pd(_mm256_cmp_pd(lo, hi, _CMP_LE_OQ));
}

/* tex_box4_rays (../box4.h) four rays a vector in AVX2's lanes, as tex_box4_avx2 (the lanes
 * of r past the last ray of m are read, not answered) */
TEX_AVX2 void tex_box4_rays_avx2(const struct tex_box4 *b, int mask, const struct tex_ray_lanes *r,
                                 uint64_t m, uint64_t in[4], double t[4]);

/* The rays of m (bit i: lane i) whose segments (tmin, tmax) enter box b, eight at a time */
TEX_AVX512 uint64_t tex_rays_box_avx512(const struct tex_bounds *b, const struct tex_ray_lanes *r,
                                        uint64_t m);
/* tex_rays_box_avx512 four rays at a time in AVX2's lanes: the same answers */
TEX_AVX2 uint64_t tex_rays_box_avx2(const struct tex_bounds *b, const struct tex_ray_lanes *r,
                                    uint64_t m);
#endif

#ifdef __cplusplus
}
#endif
#endif
