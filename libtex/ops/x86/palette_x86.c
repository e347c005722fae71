/* palette_x86.c - palette.c's OKLab to sRGB eight colours at a time (AVX-512) or four
 * (AVX2), and its colouring of a run sixteen values at a time (AVX-512) */
#include <math.h>
#include <stdint.h>

#include "base/x86/interleave_x86.h"
#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "ops/palette.h"
#include "ops/palette_srgb.h"
#include "ops/x86/palette_x86.h"

/* srgb_encode of eight values: enc_pow's operations in its order, lane by lane, so the same
 * floats; NaNs, and the lanes where the polynomial cannot decide, go to srgb_encode. */
TEX_AVX512 static __m256 srgb_encode8(const struct tex_srgb_enc *e, __m512d x)
{
    const __m512d half = _mm512_set1_pd(0.5), pieces = _mm512_set1_pd(2 * ENC_PIECES);
    __mmask8 toe = _mm512_cmp_pd_mask(x, _mm512_set1_pd(0.0031308), _CMP_LE_OQ);
    __mmask8 mid = _mm512_cmp_pd_mask(x, _mm512_set1_pd(1.0), _CMP_LT_OQ) & ~toe; /* not NaN */
    __m512i bits = _mm512_castpd_si512(_mm512_mask_blend_pd(mid, half, x)); /* c = m 2^e */
    __m512i ie = _mm512_sub_epi64(_mm512_set1_epi64(1022), _mm512_srli_epi64(bits, 52)); /* -e */
    bits = _mm512_or_si512(_mm512_and_si512(bits, _mm512_set1_epi64((INT64_C(1) << 52) - 1)),
                           _mm512_set1_epi64(INT64_C(1022) << 52));
    __m512d m = _mm512_castsi512_pd(bits);
    __m256i i = _mm512_cvttpd_epi32(_mm512_mul_pd(_mm512_sub_pd(m, half), pieces));
    __m512d centre = _mm512_div_pd(_mm512_add_pd(_mm512_cvtepi32_pd(i), half), pieces);
    __m512d t = _mm512_sub_pd(m, _mm512_add_pd(half, centre));
    __m512d t2 = _mm512_mul_pd(t, t), p[ENC_DEGREE + 1];
    __m512i i64 = _mm512_cvtepi32_epi64(i); /* 0..31: a permute of 16 entries, by bit 4 */
    __mmask8 upper = _mm512_test_epi64_mask(i64, _mm512_set1_epi64(16));
    for (int k = 0; k <= ENC_DEGREE; k++) {
        const double *ck = e->coef[k];
        __m512d lo16 = _mm512_permutex2var_pd(_mm512_loadu_pd(ck), i64, _mm512_loadu_pd(ck + 8));
        __m512d hi16 =
            _mm512_permutex2var_pd(_mm512_loadu_pd(ck + 16), i64, _mm512_loadu_pd(ck + 24));
        p[k] = _mm512_mask_blend_pd(upper, lo16, hi16);
    }
    __m512d a = _mm512_add_pd(p[0], _mm512_mul_pd(p[1], t));
    __m512d b = _mm512_mul_pd(t2, _mm512_add_pd(p[2], _mm512_mul_pd(p[3], t)));
    __m512d d = _mm512_add_pd(_mm512_add_pd(p[4], _mm512_mul_pd(p[5], t)), _mm512_mul_pd(t2, p[6]));
    __m512d y = _mm512_add_pd(_mm512_add_pd(a, b), _mm512_mul_pd(_mm512_mul_pd(t2, t2), d));
    y = _mm512_mul_pd(y, _mm512_permutex2var_pd(_mm512_loadu_pd(e->scale), ie,
                                                _mm512_loadu_pd(e->scale + 8)));
    __m512d v = _mm512_sub_pd(_mm512_mul_pd(_mm512_set1_pd(1.055), y), _mm512_set1_pd(0.055));
    __m256 lo = _mm512_cvtpd_ps(_mm512_sub_pd(v, _mm512_set1_pd(2e-12)));
    __m256 hi = _mm512_cvtpd_ps(_mm512_add_pd(v, _mm512_set1_pd(2e-12)));
    int done = _mm256_movemask_ps(_mm256_cmp_ps(lo, hi, _CMP_EQ_OQ)) & mid;
    if (done != 0xff) {
        __m256 lin = _mm512_cvtpd_ps(_mm512_mul_pd(_mm512_set1_pd(12.92), x)); /* the toe's */
        double c[8];
        _mm512_storeu_pd(c, x);
        for (int k = 0; k < 8; k++)
            if (!(done >> k & 1))
                lo[k] = toe >> k & 1 && c[k] > 0.0 ? lin[k] : tex_palette_srgb_encode(c[k]);
    }
    return lo;
}

/* Eight colours: oklab_linear's operations lane by lane */
TEX_AVX512 static void oklab_srgb8(const struct tex_srgb_enc *e, const float *lab[3], float *rgb[3])
{
    __m512d L = _mm512_cvtps_pd(_mm256_loadu_ps(lab[0]));
    __m512d A = _mm512_cvtps_pd(_mm256_loadu_ps(lab[1]));
    __m512d B = _mm512_cvtps_pd(_mm256_loadu_ps(lab[2])), c[3];
    for (int k = 0; k < 3; k++) {
        c[k] = _mm512_add_pd(_mm512_add_pd(L, _mm512_mul_pd(_mm512_set1_pd(ok_lms[k][0]), A)),
                             _mm512_mul_pd(_mm512_set1_pd(ok_lms[k][1]), B));
        c[k] = _mm512_mul_pd(_mm512_mul_pd(c[k], c[k]), c[k]);
    }
    for (int k = 0; k < 3; k++) {
        __m512d lin = _mm512_mul_pd(_mm512_set1_pd(ok_rgb[k][0]), c[0]);
        lin = _mm512_add_pd(lin, _mm512_mul_pd(_mm512_set1_pd(ok_rgb[k][1]), c[1]));
        lin = _mm512_add_pd(lin, _mm512_mul_pd(_mm512_set1_pd(ok_rgb[k][2]), c[2]));
        _mm256_storeu_ps(rgb[k], srgb_encode8(e, lin));
    }
}

int tex_oklab_srgb_avx512(const struct tex_srgb_enc *e, const float *const lab[3],
                          float *const rgb[3], int n)
{
    int i = 0;
    for (; i + 8 <= n; i += 8)
        oklab_srgb8(e, (const float *[3]){lab[0] + i, lab[1] + i, lab[2] + i},
                    (float *[3]){rgb[0] + i, rgb[1] + i, rgb[2] + i});
    return i;
}

/* srgb_encode8 on four lanes with AVX2: the same operations, the tables gathered */
TEX_AVX2 static __m128 srgb_encode4(const struct tex_srgb_enc *e, __m256d x)
{
    const __m256d half = _mm256_set1_pd(0.5), pieces = _mm256_set1_pd(2 * ENC_PIECES);
    __m256d toe = _mm256_cmp_pd(x, _mm256_set1_pd(0.0031308), _CMP_LE_OQ);
    __m256d mid = _mm256_andnot_pd(toe, _mm256_cmp_pd(x, _mm256_set1_pd(1.0), _CMP_LT_OQ));
    __m256i bits = _mm256_castpd_si256(_mm256_blendv_pd(half, x, mid)); /* c = m 2^e */
    __m256i ie = _mm256_sub_epi64(_mm256_set1_epi64x(1022), _mm256_srli_epi64(bits, 52));
    bits = _mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi64x((INT64_C(1) << 52) - 1)),
                           _mm256_set1_epi64x(INT64_C(1022) << 52));
    __m256d m = _mm256_castsi256_pd(bits);
    __m128i i = _mm256_cvttpd_epi32(_mm256_mul_pd(_mm256_sub_pd(m, half), pieces));
    __m256d centre = _mm256_div_pd(_mm256_add_pd(_mm256_cvtepi32_pd(i), half), pieces);
    __m256d t = _mm256_sub_pd(m, _mm256_add_pd(half, centre));
    __m256d t2 = _mm256_mul_pd(t, t), p[ENC_DEGREE + 1];
    for (int k = 0; k <= ENC_DEGREE; k++)
        p[k] = _mm256_i32gather_pd(e->coef[k], i, 8);
    __m256d a = _mm256_add_pd(p[0], _mm256_mul_pd(p[1], t));
    __m256d b = _mm256_mul_pd(t2, _mm256_add_pd(p[2], _mm256_mul_pd(p[3], t)));
    __m256d d = _mm256_add_pd(_mm256_add_pd(p[4], _mm256_mul_pd(p[5], t)), _mm256_mul_pd(t2, p[6]));
    __m256d y = _mm256_add_pd(_mm256_add_pd(a, b), _mm256_mul_pd(_mm256_mul_pd(t2, t2), d));
    y = _mm256_mul_pd(y, _mm256_i64gather_pd(e->scale, ie, 8));
    __m256d v = _mm256_sub_pd(_mm256_mul_pd(_mm256_set1_pd(1.055), y), _mm256_set1_pd(0.055));
    __m128 lo = _mm256_cvtpd_ps(_mm256_sub_pd(v, _mm256_set1_pd(2e-12)));
    __m128 hi = _mm256_cvtpd_ps(_mm256_add_pd(v, _mm256_set1_pd(2e-12)));
    int done = _mm_movemask_ps(_mm_cmp_ps(lo, hi, _CMP_EQ_OQ)) & _mm256_movemask_pd(mid);
    if (done != 0xf) {
        int low = _mm256_movemask_pd(toe);
        float r[4], lin[4];
        double c[4];
        _mm_storeu_ps(r, lo);
        /* the toe's */
        _mm_storeu_ps(lin, _mm256_cvtpd_ps(_mm256_mul_pd(_mm256_set1_pd(12.92), x)));
        _mm256_storeu_pd(c, x);
        for (int k = 0; k < 4; k++)
            if (!(done >> k & 1))
                r[k] = low >> k & 1 && c[k] > 0.0 ? lin[k] : tex_palette_srgb_encode(c[k]);
        lo = _mm_loadu_ps(r);
    }
    return lo;
}

TEX_AVX2 int tex_oklab_srgb_avx2(const struct tex_srgb_enc *e, const float *const lab[3],
                                 float *const rgb[3], int n)
{
    int i = 0;
    for (; i + 4 <= n; i += 4) { /* oklab_srgb8's operations on four lanes */
        __m256d L = _mm256_cvtps_pd(_mm_loadu_ps(lab[0] + i));
        __m256d A = _mm256_cvtps_pd(_mm_loadu_ps(lab[1] + i));
        __m256d B = _mm256_cvtps_pd(_mm_loadu_ps(lab[2] + i)), c[3];
        for (int k = 0; k < 3; k++) {
            c[k] = _mm256_add_pd(_mm256_add_pd(L, _mm256_mul_pd(_mm256_set1_pd(ok_lms[k][0]), A)),
                                 _mm256_mul_pd(_mm256_set1_pd(ok_lms[k][1]), B));
            c[k] = _mm256_mul_pd(_mm256_mul_pd(c[k], c[k]), c[k]);
        }
        for (int k = 0; k < 3; k++) {
            __m256d lin = _mm256_mul_pd(_mm256_set1_pd(ok_rgb[k][0]), c[0]);
            lin = _mm256_add_pd(lin, _mm256_mul_pd(_mm256_set1_pd(ok_rgb[k][1]), c[1]));
            lin = _mm256_add_pd(lin, _mm256_mul_pd(_mm256_set1_pd(ok_rgb[k][2]), c[2]));
            _mm_storeu_ps(rgb[k] + i, srgb_encode4(e, lin));
        }
    }
    return i;
}
/* palette_t of eight values: its double operations lane by lane (fmod(u, 2) is
 * u - 2 trunc(u / 2), exactly) */
TEX_AVX512 static __m256 palette_t8(__m256 v, double lo, double hi, int outside)
{
    const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0);
    __m512d t = zero, r;
    if (hi > lo)
        t = _mm512_div_pd(_mm512_sub_pd(_mm512_cvtps_pd(v), _mm512_set1_pd(lo)),
                          _mm512_set1_pd(hi - lo));
    t = _mm512_maskz_mov_pd(_mm512_cmp_pd_mask(_mm512_abs_pd(t), _mm512_set1_pd(INFINITY),
                                               _CMP_LT_OQ), t); /* not finite: 0 */
    __mmask8 low = _mm512_cmp_pd_mask(t, zero, _CMP_LT_OQ);
    __mmask8 off = low | _mm512_cmp_pd_mask(t, one, _CMP_GT_OQ);
    if (!off)
        return _mm512_cvtpd_ps(t);
    if (outside == TEX_OUTSIDE_REPEAT) {
        r = _mm512_sub_pd(t, _mm512_roundscale_pd(t, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
    } else if (outside == TEX_OUTSIDE_MIRROR) {
        __m512d u = _mm512_abs_pd(t), two = _mm512_set1_pd(2.0);
        __m512d q = _mm512_roundscale_pd(_mm512_mul_pd(u, _mm512_set1_pd(0.5)),
                                         _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
        u = _mm512_sub_pd(u, _mm512_mul_pd(two, q));
        r = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(u, one, _CMP_GT_OQ), u, _mm512_sub_pd(two, u));
    } else {
        r = _mm512_mask_blend_pd(low, one, zero);
    }
    return _mm512_cvtpd_ps(_mm512_mask_blend_pd(off, t, r));
}

/* Sixteen values coloured into c[channel] */
TEX_AVX512 static void colour16(const struct tex_palette_lanes *l, const struct tex_srgb_enc *e,
                                const float *v, double lo, double hi, int outside, __m512 c[4])
{
    const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
    __m256 t0 = palette_t8(_mm256_loadu_ps(v), lo, hi, outside);
    __m256 t1 = palette_t8(_mm256_loadu_ps(v + 8), lo, hi, outside);
    __m512 t = _mm512_castpd_ps(
        _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(t0)), _mm256_castps_pd(t1), 1));
    t = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(t, zero, _CMP_GE_OQ), t); /* stop_t */
    t = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(t, one, _CMP_GT_OQ), t, one);
    __m512i after = _mm512_setzero_si512(), k1 = _mm512_set1_epi32(1);
    for (int i = 0; i < l->n; i++)
        after = _mm512_mask_add_epi32(
            after, _mm512_cmp_ps_mask(_mm512_set1_ps(l->pos[i]), t, _CMP_LE_OQ), after, k1);
    __m512i ia = _mm512_max_epi32(_mm512_sub_epi32(after, k1), _mm512_setzero_si512());
    __m512i ib = _mm512_min_epi32(after, _mm512_set1_epi32(l->n - 1));
    __m512 pos = _mm512_loadu_ps(l->pos);
    __m512 pa = _mm512_permutexvar_ps(ia, pos), pb = _mm512_permutexvar_ps(ib, pos);
    __mmask16 ends = _mm512_cmpeq_epi32_mask(after, _mm512_setzero_si512()) |
                     _mm512_cmpeq_epi32_mask(after, _mm512_set1_epi32(l->n));
    __m512 f = _mm512_div_ps(_mm512_sub_ps(t, pa), _mm512_sub_ps(pb, pa));
    __mmask16 at = ends | _mm512_cmp_ps_mask(f, zero, _CMP_LE_OQ); /* a stop's own colour */
    f = _mm512_maskz_mov_ps(~at, f);
    __m512 a[4], mix[4];
    for (int k = 0; k < 4; k++) {
        const float *q = l->oklab && k < 3 ? l->lab[k] : l->rgba[k];
        __m512 qa = _mm512_permutexvar_ps(ia, _mm512_loadu_ps(q));
        __m512 qb = _mm512_permutexvar_ps(ib, _mm512_loadu_ps(q));
        mix[k] = _mm512_add_ps(qa, _mm512_mul_ps(f, _mm512_sub_ps(qb, qa)));
        a[k] = l->oklab && k < 3 ? _mm512_permutexvar_ps(ia, _mm512_loadu_ps(l->rgba[k])) : qa;
    }
    if (l->oklab) {
        float lab[3][16], rgb[3][16];
        for (int k = 0; k < 3; k++)
            _mm512_storeu_ps(lab[k], mix[k]);
        for (int h = 0; h < 16; h += 8)
            oklab_srgb8(e, (const float *[3]){lab[0] + h, lab[1] + h, lab[2] + h},
                        (float *[3]){rgb[0] + h, rgb[1] + h, rgb[2] + h});
        for (int k = 0; k < 3; k++)
            mix[k] = _mm512_loadu_ps(rgb[k]);
    }
    for (int k = 0; k < 4; k++)
        c[k] = _mm512_mask_blend_ps(at, mix[k], a[k]);
}

TEX_AVX512 int tex_palette_colour_avx512(const struct tex_palette_lanes *l, const struct tex_srgb_enc *e,
                              const float *v, int n, double lo, double hi, int outside,
                              float *out, int nc)
{
    /* pixels interleaved by permutes: float g of a block of 16 nc is channel g % nc of pixel
     * g / nc, taken from the pair (R, G) or (B, A) */
    int idx[4][16];
    __mmask16 ba[4] = {0};
    for (int g = 0; g < 16 * nc; g++) {
        idx[g / 16][g % 16] = g / nc + (g % nc & 1) * 16;
        ba[g / 16] |= (__mmask16)((g % nc >= 2) << (g % 16));
    }
    int i = 0;
    for (; i + 16 <= n; i += 16) {
        __m512 c[4];
        colour16(l, e, v + i, lo, hi, outside, c);
        for (int o = 0; o < nc; o++) {
            __m512i x = _mm512_loadu_si512(idx[o]);
            __m512 rg = _mm512_permutex2var_ps(c[0], x, c[1]);
            __m512 bal = _mm512_permutex2var_ps(c[2], x, c[3]);
            _mm512_storeu_ps(out + (size_t)(i * nc + 16 * o), _mm512_mask_blend_ps(ba[o], rg, bal));
        }
    }
    return i;
}
/* palette_t8 on four lanes with AVX2: the same double operations */
TEX_AVX2 static __m128 palette_t4(__m128 v, double lo, double hi, int outside)
{
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
    const __m256d sign = _mm256_set1_pd(-0.0);
    __m256d t = zero, r;
    if (hi > lo)
        t = _mm256_div_pd(_mm256_sub_pd(_mm256_cvtps_pd(v), _mm256_set1_pd(lo)),
                          _mm256_set1_pd(hi - lo));
    t = _mm256_and_pd(_mm256_cmp_pd(_mm256_andnot_pd(sign, t), _mm256_set1_pd(INFINITY),
                                    _CMP_LT_OQ), t); /* not finite: 0 */
    __m256d low = _mm256_cmp_pd(t, zero, _CMP_LT_OQ);
    __m256d off = _mm256_or_pd(low, _mm256_cmp_pd(t, one, _CMP_GT_OQ));
    if (_mm256_testz_pd(off, off))
        return _mm256_cvtpd_ps(t);
    if (outside == TEX_OUTSIDE_REPEAT) {
        r = _mm256_sub_pd(t, _mm256_round_pd(t, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
    } else if (outside == TEX_OUTSIDE_MIRROR) {
        __m256d u = _mm256_andnot_pd(sign, t), two = _mm256_set1_pd(2.0);
        __m256d q = _mm256_round_pd(_mm256_mul_pd(u, _mm256_set1_pd(0.5)),
                                    _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
        u = _mm256_sub_pd(u, _mm256_mul_pd(two, q));
        r = _mm256_blendv_pd(u, _mm256_sub_pd(two, u), _mm256_cmp_pd(u, one, _CMP_GT_OQ));
    } else {
        r = _mm256_blendv_pd(one, zero, low);
    }
    return _mm256_cvtpd_ps(_mm256_blendv_pd(t, r, off));
}

/* The stops' quantity q (16 floats, those past the last stop 0) at indices ix: one permute of
 * eight where the palette has at most eight stops, two and a blend by bit 3 for up to 16 */
TEX_AVX2 static inline __m256 stop_q(const float *q, __m256i ix, int wide, __m256 upper)
{
    __m256 lo = _mm256_permutevar8x32_ps(_mm256_loadu_ps(q), ix);
    if (!wide)
        return lo;
    return _mm256_blendv_ps(lo, _mm256_permutevar8x32_ps(_mm256_loadu_ps(q + 8), ix), upper);
}

/* colour16 on eight values with AVX2: the stops permuted within eight lanes */
TEX_AVX2 static void colour8(const struct tex_palette_lanes *l, const struct tex_srgb_enc *e,
                             const float *v, double lo, double hi, int outside, __m256 c[4])
{
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
    __m256 t = _mm256_set_m128(palette_t4(_mm_loadu_ps(v + 4), lo, hi, outside),
                               palette_t4(_mm_loadu_ps(v), lo, hi, outside));
    t = _mm256_and_ps(_mm256_cmp_ps(t, zero, _CMP_GE_OQ), t); /* stop_t */
    t = _mm256_blendv_ps(t, one, _mm256_cmp_ps(t, one, _CMP_GT_OQ));
    __m256i after = _mm256_setzero_si256(), k1 = _mm256_set1_epi32(1);
    for (int i = 0; i < l->n; i++) /* a true compare is -1 */
        after = _mm256_sub_epi32(after, _mm256_castps_si256(_mm256_cmp_ps(
                                            _mm256_set1_ps(l->pos[i]), t, _CMP_LE_OQ)));
    __m256i ia = _mm256_max_epi32(_mm256_sub_epi32(after, k1), _mm256_setzero_si256());
    __m256i ib = _mm256_min_epi32(after, _mm256_set1_epi32(l->n - 1));
    int wide = l->n > 8;
    __m256i seven = _mm256_set1_epi32(7);
    __m256 ua = _mm256_castsi256_ps(_mm256_cmpgt_epi32(ia, seven));
    __m256 ub = _mm256_castsi256_ps(_mm256_cmpgt_epi32(ib, seven));
    __m256 pa = stop_q(l->pos, ia, wide, ua), pb = stop_q(l->pos, ib, wide, ub);
    __m256 ends = _mm256_castsi256_ps(
        _mm256_or_si256(_mm256_cmpeq_epi32(after, _mm256_setzero_si256()),
                        _mm256_cmpeq_epi32(after, _mm256_set1_epi32(l->n))));
    __m256 f = _mm256_div_ps(_mm256_sub_ps(t, pa), _mm256_sub_ps(pb, pa));
    __m256 at = _mm256_or_ps(ends, _mm256_cmp_ps(f, zero, _CMP_LE_OQ)); /* a stop's own colour */
    f = _mm256_andnot_ps(at, f);
    __m256 a[4], mix[4];
    for (int k = 0; k < 4; k++) {
        const float *q = l->oklab && k < 3 ? l->lab[k] : l->rgba[k];
        __m256 qa = stop_q(q, ia, wide, ua), qb = stop_q(q, ib, wide, ub);
        mix[k] = _mm256_add_ps(qa, _mm256_mul_ps(f, _mm256_sub_ps(qb, qa)));
        a[k] = l->oklab && k < 3 ? stop_q(l->rgba[k], ia, wide, ua) : qa;
    }
    if (l->oklab) {
        float lab[3][8], rgb[3][8];
        for (int k = 0; k < 3; k++)
            _mm256_storeu_ps(lab[k], mix[k]);
        tex_oklab_srgb_avx2(e, (const float *const[3]){lab[0], lab[1], lab[2]},
                            (float *const[3]){rgb[0], rgb[1], rgb[2]}, 8);
        for (int k = 0; k < 3; k++)
            mix[k] = _mm256_loadu_ps(rgb[k]);
    }
    for (int k = 0; k < 4; k++)
        c[k] = _mm256_blendv_ps(mix[k], a[k], at);
}

TEX_AVX2 int tex_palette_colour_avx2(const struct tex_palette_lanes *l,
                                     const struct tex_srgb_enc *e, const float *v, int n,
                                     double lo, double hi, int outside, float *out, int nc)
{
    int i = 0;
    for (; i + 8 <= n; i += 8) {
        __m256 c[4];
        colour8(l, e, v + i, lo, hi, outside, c);
        if (nc == 3)
            tex_interleave3_avx2(c, out + (size_t)i * 3);
        else
            tex_interleave4_avx2(c, out + (size_t)i * 4);
    }
    return i;
}
#endif
