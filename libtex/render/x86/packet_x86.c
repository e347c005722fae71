/* packet_x86.c - a packet's footprints and mappings in AVX-512 lanes; its footprints and a
 * plane's mapping in AVX2's too */
#include <math.h>
#include <stdint.h>

#include "base/x86/simd_x86.h"
#include "render/x86/packet_x86.h"
#include "render/x86/shape_x86.h"

#ifdef TEX_X86

/* The footprints (footprint_template.c) in AVX-512's eight lanes */
#define FP_TARGET TEX_AVX512
#define FP_TANGENTS tangents8
#define FP_FOOTPRINTS tex_footprints8_avx512
#define FP_SOLID_FOOTPRINTS tex_solid_footprints8_avx512
#define vd __m512d
#define vmask __mmask8
#define V_IN(n) ((__mmask8)((1u << (n)) - 1))
#define V_LD(a) _mm512_maskz_loadu_pd(in, (a) + i)
#define V_ST(a, v) _mm512_mask_storeu_pd((a) + i, in, v)
#define V_SET1 _mm512_set1_pd
#define V_ZERO _mm512_setzero_pd
#define V_ADD _mm512_add_pd
#define V_SUB _mm512_sub_pd
#define V_MUL _mm512_mul_pd
#define V_DIV _mm512_div_pd
#define V_SQRT _mm512_sqrt_pd
#define V_MAX _mm512_max_pd
#define V_DOT dot8
#define V_ABS _mm512_abs_pd
#define V_NEG neg8
#define V_GT_ELSE(a, lo) _mm512_mask_blend_pd(_mm512_cmp_pd_mask(a, lo, _CMP_GT_OQ), lo, a)
#define V_LT_BITS(a, b) ((unsigned)_mm512_cmp_pd_mask(a, b, _CMP_LT_OQ))
#include "render/x86/footprint_template.c"

/* the mask of lanes 0 to n - 1 (n <= 4) */
TEX_AVX2 static inline __m256i lanes4(int n)
{
    return _mm256_cmpgt_epi64(_mm256_set1_epi64x(n), _mm256_setr_epi64x(0, 1, 2, 3));
}

/* And in AVX2's four: the sign's bit cleared and flipped as AVX-512's abs and neg8 do */
#define FP_TARGET TEX_AVX2
#define FP_TANGENTS tangents4
#define FP_FOOTPRINTS tex_footprints4_avx2
#define FP_SOLID_FOOTPRINTS tex_solid_footprints4_avx2
#define vd __m256d
#define vmask __m256i
#define V_IN lanes4
#define V_LD(a) _mm256_maskload_pd((a) + i, in)
#define V_ST(a, v) _mm256_maskstore_pd((a) + i, in, v)
#define V_SET1 _mm256_set1_pd
#define V_ZERO _mm256_setzero_pd
#define V_ADD _mm256_add_pd
#define V_SUB _mm256_sub_pd
#define V_MUL _mm256_mul_pd
#define V_DIV _mm256_div_pd
#define V_SQRT _mm256_sqrt_pd
#define V_MAX _mm256_max_pd
#define V_DOT dot4
#define V_ABS(x) _mm256_andnot_pd(_mm256_set1_pd(-0.0), x)
#define V_NEG(x) _mm256_xor_pd(x, _mm256_set1_pd(-0.0))
#define V_GT_ELSE(a, lo) _mm256_blendv_pd(lo, a, _mm256_cmp_pd(a, lo, _CMP_GT_OQ))
#define V_LT_BITS(a, b) ((unsigned)_mm256_movemask_pd(_mm256_cmp_pd(a, b, _CMP_LT_OQ)))
#include "render/x86/footprint_template.c"

/* fract in lanes: x - tex_floord(x), tex_floord's floor (+0 for -0: floor's -0 plus 0), and
 * x - x beyond 2^52 */
TEX_AVX512 static inline __m512d fract8_avx512(__m512d x)
{
    __mmask8 small = _mm512_cmp_pd_mask(_mm512_abs_pd(x), _mm512_set1_pd(4503599627370496.0),
                                        _CMP_LT_OQ);
    __m512d f = _mm512_add_pd(_mm512_roundscale_pd(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                              _mm512_setzero_pd());
    return _mm512_sub_pd(x, _mm512_mask_blend_pd(small, x, f));
}

/* place over the lanes in from i on (the mapping's coordinates c0, c1, stored into u0, v0):
 * the placed ones into u, v; returns the lanes inside the window */
TEX_AVX512 static __mmask8 place8_avx512(const struct tex_apply *ap, const struct placement *pm,
                                         int i, __mmask8 in, __m512d c0, __m512d c1,
                                         double *u0, double *v0, double *u, double *v)
{
    _mm512_mask_storeu_pd(u0 + i, in, c0);
    _mm512_mask_storeu_pd(v0 + i, in, c1);
    __m512d s = _mm512_mul_pd(_mm512_sub_pd(c0, _mm512_set1_pd(ap->u1)), _mm512_set1_pd(pm->iu));
    __m512d t = _mm512_mul_pd(_mm512_sub_pd(c1, _mm512_set1_pd(ap->v1)), _mm512_set1_pd(pm->iv));
    __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1);
    __mmask8 inside = _mm512_mask_cmp_pd_mask(in, s, zero, _CMP_GE_OQ) &
                      _mm512_cmp_pd_mask(s, one, _CMP_LE_OQ) &
                      _mm512_cmp_pd_mask(t, zero, _CMP_GE_OQ) &
                      _mm512_cmp_pd_mask(t, one, _CMP_LE_OQ);
    _mm512_mask_storeu_pd(u + i, in, _mm512_mul_pd(s, _mm512_set1_pd(ap->nu)));
    _mm512_mask_storeu_pd(v + i, in, _mm512_mul_pd(t, _mm512_set1_pd(ap->nv)));
    return inside;
}

/* Row k of the affine map m applied to the lanes x, y, z, in tex_xform_point's order */
TEX_AVX512 static inline __m512d xform_row8(const double *r, __m512d x, __m512d y, __m512d z)
{
    __m512d a = _mm512_add_pd(_mm512_mul_pd(_mm512_set1_pd(r[0]), x),
                              _mm512_mul_pd(_mm512_set1_pd(r[1]), y));
    return _mm512_add_pd(_mm512_add_pd(a, _mm512_mul_pd(_mm512_set1_pd(r[2]), z)),
                         _mm512_set1_pd(r[3]));
}

/* map_hit of a plane's planar mapping over the n <= 8 lanes of L's points from i on, operation
 * for operation (tex_xform_point's x and z, map_point_at, place): the mapping's coordinates
 * into u0, v0, the placed ones into u, v; returns the lanes inside the window */
TEX_AVX512 unsigned tex_plane_map8_avx512(const struct tex_lanes *L, int i, int n, double *u0,
                                          double *v0, double *u, double *v)
{
    __mmask8 in = (__mmask8)((1u << n) - 1);
    const struct tex_apply *ap = L->sf->apply;
    const double(*m)[4] = L->leaf->to_obj.m;
    __m512d x = _mm512_maskz_loadu_pd(in, L->p[0] + i), y = _mm512_maskz_loadu_pd(in, L->p[1] + i);
    __m512d z = _mm512_maskz_loadu_pd(in, L->p[2] + i), sc = _mm512_set1_pd(ap->scale);
    __m512d c0 = fract8_avx512(_mm512_mul_pd(xform_row8(m[0], x, y, z), sc));
    __m512d c1 = fract8_avx512(_mm512_mul_pd(xform_row8(m[2], x, y, z), sc));
    return place8_avx512(ap, L->sf->cache->placement, i, in, c0, c1, u0, v0, u, v);
}

/* tex_plane_map8_avx512 in AVX2's four lanes (fract8_avx512, xform_row8 and place8_avx512's
 * operations in their order) */
TEX_AVX2 static inline __m256d xform_row4(const double *r, __m256d x, __m256d y, __m256d z)
{
    __m256d a = _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(r[0]), x),
                              _mm256_mul_pd(_mm256_set1_pd(r[1]), y));
    return _mm256_add_pd(_mm256_add_pd(a, _mm256_mul_pd(_mm256_set1_pd(r[2]), z)),
                         _mm256_set1_pd(r[3]));
}

TEX_AVX2 static inline __m256d fract4_avx2(__m256d x)
{
    __m256d ax = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    __m256d small = _mm256_cmp_pd(ax, _mm256_set1_pd(4503599627370496.0), _CMP_LT_OQ);
    __m256d f = _mm256_add_pd(_mm256_round_pd(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                              _mm256_setzero_pd());
    return _mm256_sub_pd(x, _mm256_blendv_pd(x, f, small));
}

TEX_AVX2 unsigned tex_plane_map4_avx2(const struct tex_lanes *L, int i, int n, double *u0,
                                      double *v0, double *u, double *v)
{
    __m256i in = lanes4(n);
    const struct tex_apply *ap = L->sf->apply;
    const struct placement *pm = L->sf->cache->placement;
    const double(*m)[4] = L->leaf->to_obj.m;
    __m256d x = _mm256_maskload_pd(L->p[0] + i, in), y = _mm256_maskload_pd(L->p[1] + i, in);
    __m256d z = _mm256_maskload_pd(L->p[2] + i, in), sc = _mm256_set1_pd(ap->scale);
    __m256d c0 = fract4_avx2(_mm256_mul_pd(xform_row4(m[0], x, y, z), sc));
    __m256d c1 = fract4_avx2(_mm256_mul_pd(xform_row4(m[2], x, y, z), sc));
    _mm256_maskstore_pd(u0 + i, in, c0);
    _mm256_maskstore_pd(v0 + i, in, c1);
    __m256d s = _mm256_mul_pd(_mm256_sub_pd(c0, _mm256_set1_pd(ap->u1)), _mm256_set1_pd(pm->iu));
    __m256d t = _mm256_mul_pd(_mm256_sub_pd(c1, _mm256_set1_pd(ap->v1)), _mm256_set1_pd(pm->iv));
    __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1);
    __m256d inside = _mm256_and_pd(
        _mm256_and_pd(_mm256_cmp_pd(s, zero, _CMP_GE_OQ), _mm256_cmp_pd(s, one, _CMP_LE_OQ)),
        _mm256_and_pd(_mm256_cmp_pd(t, zero, _CMP_GE_OQ), _mm256_cmp_pd(t, one, _CMP_LE_OQ)));
    _mm256_maskstore_pd(u + i, in, _mm256_mul_pd(s, _mm256_set1_pd(ap->nu)));
    _mm256_maskstore_pd(v + i, in, _mm256_mul_pd(t, _mm256_set1_pd(ap->nv)));
    return (unsigned)_mm256_movemask_pd(inside) & ((1u << n) - 1);
}

/* tex_point_gradient of a natural mapping over the lanes in (natural_gradient at the
 * object-space points p on faces f, then to world space), operation for operation, into
 * fr's rows from i on, with the placement's scales; returns the lanes that have them */
/* u's gradient around the axis over lanes, (z, 0, -x) / (2 pi rho2), into g */
TEX_AVX512 static inline void around8(const __m512d p[3], __m512d rho2, __m512d g[3])
{
    __m512d s = _mm512_div_pd(_mm512_set1_pd(1), _mm512_mul_pd(_mm512_set1_pd(2 * M_PI), rho2));
    g[0] = _mm512_mul_pd(p[2], s), g[1] = _mm512_mul_pd(_mm512_setzero_pd(), s);
    g[2] = _mm512_mul_pd(neg8(p[0]), s);
}

TEX_AVX512 static __mmask8 natural_gradient8_avx512(const struct tex_object *leaf,
                                                    const struct placement *pm, __mmask8 in,
                                                    const __m512d p[3], __m512i f,
                                                    struct frames *fr, int i)
{
    __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1), g[2][3];
    __m512d rho2 = _mm512_add_pd(_mm512_mul_pd(p[0], p[0]), _mm512_mul_pd(p[2], p[2]));
    __mmask8 ok = in;
    if (leaf->kind == TEX_SHAPE_BOX) { /* tex_box_axes: +-1/2 along one axis, by face */
        double tab[2][3][8] = {{{0}}};
        for (int fc = 0; fc < 6; fc++)
            for (int k = 0; k < 2; k++) {
                int c = tex_box_axes[fc][k];
                tab[k][(c < 0 ? -c : c) - 1][fc] = c < 0 ? -0.5 : 0.5;
            }
        __m512i idx = _mm512_sub_epi64(f, _mm512_set1_epi64(1));
        for (int k = 0; k < 2; k++)
            for (int c = 0; c < 3; c++)
                g[k][c] = _mm512_permutexvar_pd(idx, _mm512_loadu_pd(tab[k][c]));
    } else if (leaf->kind == TEX_SHAPE_SPHERE) { /* v = acos(y / r) / pi */
        __m512d r2 = _mm512_add_pd(rho2, _mm512_mul_pd(p[1], p[1]));
        ok &= _mm512_cmp_pd_mask(rho2, _mm512_mul_pd(_mm512_set1_pd(1e-12), r2), _CMP_GT_OQ);
        __m512d k = _mm512_div_pd(one, _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(M_PI),
                                                                   _mm512_sqrt_pd(rho2)), r2));
        around8(p, rho2, g[0]);
        g[1][0] = _mm512_mul_pd(_mm512_mul_pd(p[0], p[1]), k);
        g[1][1] = _mm512_mul_pd(neg8(rho2), k);
        g[1][2] = _mm512_mul_pd(_mm512_mul_pd(p[2], p[1]), k);
    } else { /* the side (face 1): around, v = 1 - y; the caps: discs of radius r */
        __mmask8 side = _mm512_cmp_epi64_mask(f, _mm512_set1_epi64(1), _MM_CMPINT_EQ);
        ok &= ~side | _mm512_cmp_pd_mask(rho2, _mm512_set1_pd(1e-24), _CMP_GT_OQ);
        __mmask8 bottom = _mm512_cmp_epi64_mask(f, _mm512_set1_epi64(2), _MM_CMPINT_EQ);
        double r0 = leaf->r0 > 0 ? leaf->r0 : 1, r1 = leaf->r1 > 0 ? leaf->r1 : 1;
        __m512d r = _mm512_mask_blend_pd(bottom, _mm512_set1_pd(r1), _mm512_set1_pd(r0));
        __m512d h = _mm512_div_pd(_mm512_set1_pd(0.5), r), around[3];
        around8(p, rho2, around);
        g[0][0] = _mm512_mask_blend_pd(side, h, around[0]);
        g[0][1] = _mm512_mask_blend_pd(side, zero, around[1]);
        g[0][2] = _mm512_mask_blend_pd(side, zero, around[2]);
        g[1][0] = zero;
        g[1][1] = _mm512_mask_blend_pd(side, zero, _mm512_set1_pd(-1));
        g[1][2] = _mm512_mask_blend_pd(side, h, zero);
    }
    const double(*m)[4] = leaf->to_obj.m;
    double(*rows[2])[CHUNK] = {fr->gu, fr->gv};
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 3; c++) /* tex_xform_normal: the transpose */
            _mm512_mask_storeu_pd(rows[k][c] + i, in,
                                  dot8(_mm512_set1_pd(m[0][c]), _mm512_set1_pd(m[1][c]),
                                       _mm512_set1_pd(m[2][c]), g[k][0], g[k][1], g[k][2]));
    _mm512_mask_storeu_pd(fr->su + i, in, _mm512_set1_pd(pm->su));
    _mm512_mask_storeu_pd(fr->sv + i, in, _mm512_set1_pd(pm->sv));
    return ok;
}

/* map_hit of a natural mapping on a box, cylinder, cone or sphere over the n <= 8 lanes of L's
 * points from i on, operation for operation (tex_xform_point, the shape's uv, place), as
 * tex_plane_map8_avx512 does a plane's, each lane's face into face[]; and their gradients into
 * fr's rows (natural_gradient8_avx512).  Returns the lanes inside the window that have
 * gradients. */
TEX_AVX512 unsigned tex_natural_map8_avx512(const struct tex_lanes *L, int i, int n, double *u0,
                                            double *v0, double *u, double *v, int *face,
                                            struct frames *fr)
{
    __mmask8 in = (__mmask8)((1u << n) - 1);
    const struct tex_object *leaf = L->leaf;
    const struct placement *pm = L->sf->cache->placement;
    const double(*m)[4] = leaf->to_obj.m;
    __m512d x = _mm512_maskz_loadu_pd(in, L->p[0] + i), y = _mm512_maskz_loadu_pd(in, L->p[1] + i);
    __m512d z = _mm512_maskz_loadu_pd(in, L->p[2] + i), p[3], c0, c1;
    __m512i f = _mm512_set1_epi64(1);
    for (int k = 0; k < 3; k++)
        p[k] = xform_row8(m[k], x, y, z);
    if (leaf->kind == TEX_SHAPE_BOX)
        box_uv8(p, &c0, &c1, &f);
    else if (leaf->kind == TEX_SHAPE_SPHERE)
        sphere_uv8(p, &c0, &c1);
    else
        cone_uv8(leaf, p, &c0, &c1, &f);
    _mm512_mask_cvtepi64_storeu_epi32(face + i, in, f);
    return place8_avx512(L->sf->apply, pm, i, in, c0, c1, u0, v0, u, v) &
           natural_gradient8_avx512(leaf, pm, in, p, f, fr, i);
}
#endif
