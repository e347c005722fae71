/* shape_x86.h - the shapes' own mappings (render_shape.c's uv) in AVX-512 lanes
 *
 * box_uv, cone_uv and sphere_uv's operations in their order over eight points, for the
 * packets' natural mappings (packet_x86.c, their one includer: static, so they inline
 * there).
 */
#ifndef TEX_SHAPE_X86_H
#define TEX_SHAPE_X86_H

#include "vecmath_x86.h"
#include "../mapping.h"

#ifdef TEX_X86
/* (a + 1) / 2 over lanes, clamped: a coordinate across a box face or a cap */
TEX_AVX512 static inline __m512d across8(__m512d a)
{
    return clamp8(_mm512_div_pd(_mm512_add_pd(a, _mm512_set1_pd(1)), _mm512_set1_pd(2)));
}

/* box_uv over lanes (p: the object-space point): u, v and the face */
TEX_AVX512 static void box_uv8(const __m512d p[3], __m512d *u, __m512d *v, __m512i *face)
{
    __m512d zero = _mm512_setzero_pd(), ax = _mm512_abs_pd(p[0]), ay = _mm512_abs_pd(p[1]);
    __m512d az = _mm512_abs_pd(p[2]);
    __mmask8 fx = _mm512_cmp_pd_mask(ax, ay, _CMP_GE_OQ) & _mm512_cmp_pd_mask(ax, az, _CMP_GE_OQ);
    __mmask8 fy = ~fx & _mm512_cmp_pd_mask(ay, az, _CMP_GE_OQ), fz = ~(fx | fy);
    __mmask8 pos = (fx & _mm512_cmp_pd_mask(p[0], zero, _CMP_GT_OQ)) |
                   (fy & _mm512_cmp_pd_mask(p[1], zero, _CMP_GT_OQ)) |
                   (fz & _mm512_cmp_pd_mask(p[2], zero, _CMP_GT_OQ));
    __m512i f = _mm512_mask_blend_epi64(fy, _mm512_set1_epi64(5), _mm512_set1_epi64(3));
    f = _mm512_mask_blend_epi64(fx, f, _mm512_set1_epi64(1));
    *face = _mm512_mask_add_epi64(f, ~pos, f, _mm512_set1_epi64(1));
    /* faces 1..6: a = -z z x x x -x, b = -y -y z -z -y -y */
    __m512d nx = neg8(p[0]), ny = neg8(p[1]), nz = neg8(p[2]);
    __m512d a = _mm512_mask_blend_pd(fz & ~pos, p[0], nx);
    a = _mm512_mask_blend_pd(fx, a, _mm512_mask_blend_pd(pos, p[2], nz));
    __m512d b = _mm512_mask_blend_pd(fy, ny, _mm512_mask_blend_pd(pos, nz, p[2]));
    *u = across8(a), *v = across8(b);
}

/* cone_uv (cone_part and all) over lanes (p: the object-space point) */
TEX_AVX512 static void cone_uv8(const struct tex_object *ob, const __m512d p[3], __m512d *u,
                                __m512d *v, __m512i *face)
{
    double k = ob->r1 - ob->r0, den = sqrt(1 + (ob->r1 - ob->r0) * (ob->r1 - ob->r0));
    __m512d one = _mm512_set1_pd(1);
    __m512d ry = _mm512_add_pd(_mm512_set1_pd(ob->r0), _mm512_mul_pd(_mm512_set1_pd(k), p[1]));
    __m512d rho = _mm512_sqrt_pd(
        _mm512_add_pd(_mm512_mul_pd(p[0], p[0]), _mm512_mul_pd(p[2], p[2])));
    __m512d side = _mm512_div_pd(_mm512_abs_pd(_mm512_sub_pd(rho, ry)), _mm512_set1_pd(den));
    __m512d bot = _mm512_abs_pd(p[1]), top = _mm512_abs_pd(_mm512_sub_pd(p[1], one));
    __mmask8 s0 = _mm512_cmp_pd_mask(side, bot, _CMP_LE_OQ) &
                  _mm512_cmp_pd_mask(side, top, _CMP_LE_OQ);
    __mmask8 part1 = ~s0 & _mm512_cmp_pd_mask(bot, top, _CMP_LE_OQ);
    /* the caps: discs of radius r across [0, 1]^2 */
    __m512d r = _mm512_mask_blend_pd(part1, _mm512_set1_pd(ob->r1 > 0 ? ob->r1 : 1),
                                     _mm512_set1_pd(ob->r0 > 0 ? ob->r0 : 1));
    __m512d cu = across8(_mm512_div_pd(p[0], r)), cv = across8(_mm512_div_pd(p[2], r));
    *u = s0 ? _mm512_mask_blend_pd(s0, cu, turns8(neg8(p[2]), p[0])) : cu; /* caps alone */
    *v = _mm512_mask_blend_pd(s0, cv, clamp8(_mm512_sub_pd(one, p[1])));
    *face = _mm512_mask_blend_epi64(s0, _mm512_mask_blend_epi64(part1, _mm512_set1_epi64(3),
                                                                _mm512_set1_epi64(2)),
                                    _mm512_set1_epi64(1));
}

/* sphere_uv over lanes (p: the object-space point) */
TEX_AVX512 static void sphere_uv8(const __m512d p[3], __m512d *u, __m512d *v)
{
    __m512d r = _mm512_sqrt_pd(dot8(p[0], p[1], p[2], p[0], p[1], p[2]));
    __mmask8 pos = _mm512_cmp_pd_mask(r, _mm512_setzero_pd(), _CMP_GT_OQ);
    *u = turns8(neg8(p[2]), p[0]);
    *v = _mm512_mask_blend_pd(pos, _mm512_set1_pd(0.5), polar8(_mm512_div_pd(p[1], r)));
}
#endif
#endif
