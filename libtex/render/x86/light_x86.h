/* light_x86.h - a point or spot light's direction, distance and falloff at four hits, or
 * four samples of an area light's at one, in AVX2's lanes (light.h's tex_light_point_at and
 * tex_light_sample, as tex_light_ahead_at takes them)
 *
 * tex_light_towards' operations in their order, the spot's cone and its whole exponent by
 * squaring: IEEE square roots and divisions in lanes give the scalar path's bits.
 */
#ifndef TEX_LIGHT_X86_H
#define TEX_LIGHT_X86_H

#include "../../base/x86/simd_x86.h"
#include "../whitted.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef TEX_X86
/* tex_light_ahead_at(l, 0, 0.5, 0.5, P + k, a + k) for k < 4, l a point or spot light
 * whose exponent tex_powi takes by squaring (tex_light_lanes); the fields of a light
 * sample that does not reach its hit (ok 0) are left undefined, as there. */
TEX_AVX2 void tex_light_points4_avx2(const struct tex_light *l, const tex_v3 *P,
                                     struct tex_light_ahead *a);
/* tex_light_ahead_at(l, k + i, jx[i], jy[i], P, a + i) for i < 4, l an area light whose
 * samples a side are a power of two (tex_light_area_lanes) */
TEX_AVX2 void tex_light_area4_avx2(const struct tex_light *l, int k, const double *jx,
                                   const double *jy, const tex_v3 *P, struct tex_light_ahead *a);
#endif

#ifdef __cplusplus
}
#endif
#endif
