/* bvh_x86.h - a batch of shadow rays against a tree node's box in AVX-512 lanes
 * (render_bvh.c's hit_box, its operations in its order: the same answers)
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

#ifdef TEX_X86
/* The rays of m (bit i: lane i) whose segments (tmin, tmax) enter box b, eight at a time */
TEX_AVX512 uint64_t tex_rays_box_avx512(const struct tex_bounds *b, const struct tex_ray_lanes *r,
                                        uint64_t m);
#endif

#ifdef __cplusplus
}
#endif
#endif
