/* bvh_x86.h - a batch of shadow rays against a tree node's box in AVX-512 lanes, and one
 * ray against a node's two children in SSE2's (render_bvh.c's hit_box, its operations in
 * its order: the same answers)
 */
#ifndef TEX_BVH_X86_H
#define TEX_BVH_X86_H

#include <stdint.h>

#include "../../base/x86/simd_x86.h"
#include "../shape.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A batch's rays, lane by lane: origins, their directions' reciprocals, the bounds of t */
struct tex_ray_lanes {
    double o[3][64], inv[3][64];
    const double *tmin, *tmax;
};

/* A tree node's two children's boxes side by side (lo[axis][child]): one ray tests both
 * at once (tex_box_pair_sse2) */
struct tex_box_pair {
    double lo[3][2], hi[3][2];
};

#ifdef TEX_X86
/* hit_box (render_bvh.c) of one ray, origin org and reciprocal direction rcp, against both
 * boxes of p in the two lanes of an SSE2 vector: its operations in its order lane by lane
 * (max_pd and min_pd pick as its tex_maxd and tex_mind do, NaN included), so the same
 * answers: bit c for child c met in [tmin, tmax], its entry distance in t[c] */
static inline int tex_box_pair_sse2(const struct tex_box_pair *p, const tex_v3 *org,
                                    const tex_v3 *rcp, double tmin, double tmax, double t[2])
{
    const double o[3] = {org->x, org->y, org->z}, inv[3] = {rcp->x, rcp->y, rcp->z};
    __m128d lo = _mm_set1_pd(tmin), hi = _mm_set1_pd(tmax);
    for (int c = 0; c < 3; c++) {
        __m128d oc = _mm_set1_pd(o[c]), ic = _mm_set1_pd(inv[c]);
        __m128d a = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p->lo[c]), oc), ic);
        __m128d b = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p->hi[c]), oc), ic);
        lo = _mm_max_pd(lo, _mm_min_pd(a, b));
        hi = _mm_min_pd(hi, _mm_max_pd(a, b));
    }
    _mm_storeu_pd(t, lo);
    return _mm_movemask_pd(_mm_cmple_pd(lo, hi));
}

/* The rays of m (bit i: lane i) whose segments (tmin, tmax) enter box b, eight at a time */
TEX_AVX512 uint64_t tex_rays_box_avx512(const struct tex_bounds *b, const struct tex_ray_lanes *r,
                                        uint64_t m);
#endif

#ifdef __cplusplus
}
#endif
#endif
