/* mipmap_x86.c - the mip-map lookups in vector lanes (AVX2, AVX-512) */
#include <math.h>
#include <stdint.h>

#include "base/x86/simd_x86.h"
#include "render/mipmap.h"

#ifdef TEX_X86
/* bilinear with k = 3, the channels in three of four double lanes: its operations in its
 * order, so the same floats (and the same derivatives g, or none). */
TEX_AVX2 static inline __m128 bilinear3_avx2(const tex_map *m, double u, double v, double g[2])
{
    const float *t[4];
    double ax, ay;
    texels(m, u, v, t, &ax, &ay);
    __m128i three = _mm_setr_epi32(-1, -1, -1, 0); /* the fourth float is not read */
    __m256d a = _mm256_cvtps_pd(_mm_maskload_ps(t[0], three));
    __m256d b = _mm256_cvtps_pd(_mm_maskload_ps(t[1], three));
    __m256d c = _mm256_cvtps_pd(_mm_maskload_ps(t[2], three));
    __m256d d = _mm256_cvtps_pd(_mm_maskload_ps(t[3], three));
    __m256d wx = _mm256_set1_pd(ax), wx1 = _mm256_set1_pd(1 - ax);
    __m256d wy = _mm256_set1_pd(ay), wy1 = _mm256_set1_pd(1 - ay);
    if (g) { /* bilinear_dx's operations, lane by lane */
        double x[4], y[4];
        _mm256_storeu_pd(x, _mm256_add_pd(_mm256_mul_pd(_mm256_sub_pd(b, a), wy1),
                                          _mm256_mul_pd(_mm256_sub_pd(d, c), wy)));
        _mm256_storeu_pd(y, _mm256_add_pd(_mm256_mul_pd(_mm256_sub_pd(c, a), wx1),
                                          _mm256_mul_pd(_mm256_sub_pd(d, b), wx)));
        g[0] = (x[0] + x[1] + x[2]) / 3, g[1] = (y[0] + y[1] + y[2]) / 3;
    }
    __m256d top = _mm256_add_pd(_mm256_mul_pd(a, wx1), _mm256_mul_pd(b, wx));
    __m256d bot = _mm256_add_pd(_mm256_mul_pd(c, wx1), _mm256_mul_pd(d, wx));
    return _mm256_cvtpd_ps(_mm256_add_pd(_mm256_mul_pd(top, wy1), _mm256_mul_pd(bot, wy)));
}

/* map_eval's colour case from level l (weight a of level l + 1), in vectors; g: as bilinear
 * gives them, level l's in g[0], l + 1's in g[1] */
TEX_AVX2 void tex_map_eval3_avx2(const struct tex_texture *t, int l, double a, double u,
                                double v, float out[3], double (*g)[2])
{
    __m128 o = bilinear3_avx2(t->mip[l], u, v, g ? g[0] : NULL);
    if (a > 0) {
        __m128 o1 = bilinear3_avx2(t->mip[l + 1], u, v, g ? g[1] : NULL);
        o = _mm256_cvtpd_ps(_mm256_add_pd(_mm256_mul_pd(_mm256_cvtps_pd(o), _mm256_set1_pd(1 - a)),
                                          _mm256_mul_pd(_mm256_cvtps_pd(o1), _mm256_set1_pd(a))));
    }
    _mm_maskstore_ps(out, _mm_setr_epi32(-1, -1, -1, 0), o);
}

/* mip_level of eight footprints fw2 on texture t: the levels (as 32-bit lanes) and the
 * weights *a of the next, operation for operation */
TEX_AVX512 static __m256i mip_levels8_avx512(const struct tex_texture *t, __m512d fw2,
                                               __m512d *a)
{
    const double *c = log2_poly;
    const tex_map *m0 = t->mip[0];
    int side = m0->w > m0->h ? m0->w : m0->h;
    __m512d x2 = _mm512_mul_pd(fw2, _mm512_set1_pd((double)side * side));
    __mmask8 minified = _mm512_cmp_pd_mask(x2, _mm512_set1_pd(1), _CMP_GT_OQ);
    __m512i bits = _mm512_castpd_si512(x2);
    __m512i e = _mm512_sub_epi64(_mm512_srli_epi64(bits, 52), _mm512_set1_epi64(1023));
    __m512i l = _mm512_srai_epi64(e, 1), top = _mm512_set1_epi64(t->nlevels - 1);
    __mmask8 below = _mm512_mask_cmplt_epi64_mask(minified, l, top); /* interpolated */
    __m512i mant = _mm512_and_si512(bits, _mm512_set1_epi64((INT64_C(1) << 52) - 1));
    __m512i mb = _mm512_or_si512(mant, _mm512_set1_epi64(INT64_C(1023) << 52));
    __m512d mm = _mm512_sub_pd(_mm512_castsi512_pd(mb), _mm512_set1_pd(1));
    __m512d lm = _mm512_set1_pd(c[6]);
    for (int i = 5; i >= 0; i--)
        lm = _mm512_add_pd(_mm512_mul_pd(lm, mm), _mm512_set1_pd(c[i]));
    __m512i e1 = _mm512_and_si512(e, _mm512_set1_epi64(1));
    __m512d odd = _mm512_cvtepi32_pd(_mm512_cvtepi64_epi32(e1));
    /* halved by a product: the same bits as mip_level's division by 2, without a division */
    __m512d w = _mm512_mul_pd(_mm512_add_pd(odd, _mm512_mul_pd(lm, mm)), _mm512_set1_pd(0.5));
    *a = _mm512_maskz_mov_pd(below, w);
    l = _mm512_mask_mov_epi64(_mm512_maskz_mov_epi64(minified, top), below, l);
    return _mm512_cvtepi64_epi32(l);
}

/* A texture's pyramid as bilinear8 looks it up: each level's width, height and texels'
 * offset (in floats) from level 0's, one level more repeating the last (0 beyond); below 16 levels
 * (maps up to 16384 wide) also in registers */
struct pyramid {
    int w[32], h[32];
    long long off[32];
    __m512i w16[2], h16[2], off8[2];
};

/* bilinear (k channels) of eight points (u, v) in [0, 1], each at its level lv of the
 * pyramid, into out[c]; g (or NULL): the derivatives of their mean along x and y in texels,
 * and the levels' widths and heights into wh[0], wh[1] */
TEX_AVX512 static void bilinear8_avx512(const struct tex_texture *t, const struct pyramid *py,
                                          int k, __m256i lv, __m512d u, __m512d v,
                                          __m256 out[3], __m512d g[2], __m512d wh[2])
{
    int nc = t->mip[0]->nc;
    __m256i w, h;
    __m512i base;
    if (t->nlevels < 16) { /* the tables in registers: permutes, not gathers */
        __m512i li = _mm512_castsi256_si512(lv);
        w = _mm512_castsi512_si256(_mm512_permutex2var_epi32(py->w16[0], li, py->w16[1]));
        h = _mm512_castsi512_si256(_mm512_permutex2var_epi32(py->h16[0], li, py->h16[1]));
        base = _mm512_permutex2var_epi64(py->off8[0], _mm512_cvtepi32_epi64(lv), py->off8[1]);
    } else {
        w = _mm256_i32gather_epi32(py->w, lv, 4), h = _mm256_i32gather_epi32(py->h, lv, 4);
        base = _mm512_i32gather_epi64(lv, py->off, 8);
    }
    __m512d x = _mm512_sub_pd(_mm512_mul_pd(u, _mm512_cvtepi32_pd(w)), _mm512_set1_pd(0.5));
    __m512d y = _mm512_sub_pd(_mm512_mul_pd(v, _mm512_cvtepi32_pd(h)), _mm512_set1_pd(0.5));
    __m512d one = _mm512_set1_pd(1);
    __m512d fx = _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(x)); /* floori */
    __m512d fy = _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(y));
    fx = _mm512_mask_sub_pd(fx, _mm512_cmp_pd_mask(fx, x, _CMP_GT_OQ), fx, one);
    fy = _mm512_mask_sub_pd(fy, _mm512_cmp_pd_mask(fy, y, _CMP_GT_OQ), fy, one);
    __m512d ax = _mm512_sub_pd(x, fx), ay = _mm512_sub_pd(y, fy);
    __m256i ix = _mm512_cvttpd_epi32(fx), iy = _mm512_cvttpd_epi32(fy);
    __m256i zero = _mm256_setzero_si256(), vnc = _mm256_set1_epi32(nc), c1 = _mm256_set1_epi32(1);
    /* texels' wrapping: x0 = ix < 0 ? w - 1 : ix, the next row and texel wrapping to 0 */
    __m256i x0 = _mm256_blendv_epi8(ix, _mm256_sub_epi32(w, c1), _mm256_cmpgt_epi32(zero, ix));
    __m256i y0 = _mm256_blendv_epi8(iy, _mm256_sub_epi32(h, c1), _mm256_cmpgt_epi32(zero, iy));
    __m256i wn = _mm256_mullo_epi32(w, vnc);
    __m256i r0 = _mm256_mullo_epi32(y0, wn), r1 = _mm256_add_epi32(r0, wn);
    r1 = _mm256_andnot_si256(_mm256_cmpeq_epi32(_mm256_add_epi32(y0, c1), h), r1);
    __m256i col0 = _mm256_mullo_epi32(x0, vnc), col1 = _mm256_add_epi32(col0, vnc);
    col1 = _mm256_andnot_si256(_mm256_cmpeq_epi32(col1, wn), col1);
    __m256i off[4] = {_mm256_add_epi32(r0, col0), _mm256_add_epi32(r0, col1),
                      _mm256_add_epi32(r1, col0), _mm256_add_epi32(r1, col1)};
    __m512i at[4];
    for (int j = 0; j < 4; j++)
        at[j] = _mm512_slli_epi64(_mm512_add_epi64(base, _mm512_cvtepi32_epi64(off[j])), 2);
    __m512d wx1 = _mm512_sub_pd(one, ax), wy1 = _mm512_sub_pd(one, ay), gx[3], gy[3];
    const float *px = t->mip[0]->px;
    __m512i pair[4]; /* colour: channels 0 and 1 of each texel in one 64-bit gather */
    for (int j = 0; k == 3 && j < 4; j++)
        pair[j] = _mm512_i64gather_epi64(at[j], px, 1);
    for (int ch = 0; ch < k; ch++) {
        __m512d q[4];
        for (int j = 0; j < 4; j++) {
            __m256 c = k == 3 && ch < 2 ? _mm256_castsi256_ps(_mm512_cvtepi64_epi32(
                                              ch ? _mm512_srli_epi64(pair[j], 32) : pair[j]))
                                        : _mm512_i64gather_ps(at[j], px + ch, 1);
            q[j] = _mm512_cvtps_pd(c);
        }
        __m512d top = _mm512_add_pd(_mm512_mul_pd(q[0], wx1), _mm512_mul_pd(q[1], ax));
        __m512d bot = _mm512_add_pd(_mm512_mul_pd(q[2], wx1), _mm512_mul_pd(q[3], ax));
        out[ch] = _mm512_cvtpd_ps(_mm512_add_pd(_mm512_mul_pd(top, wy1), _mm512_mul_pd(bot, ay)));
        if (g) { /* bilinear_dx along x, then along y */
            gx[ch] = _mm512_add_pd(_mm512_mul_pd(_mm512_sub_pd(q[1], q[0]), wy1),
                                   _mm512_mul_pd(_mm512_sub_pd(q[3], q[2]), ay));
            gy[ch] = _mm512_add_pd(_mm512_mul_pd(_mm512_sub_pd(q[2], q[0]), wx1),
                                   _mm512_mul_pd(_mm512_sub_pd(q[3], q[1]), ax));
        }
    }
    if (!g)
        return;
    if (k == 3) {
        __m512d three = _mm512_set1_pd(3);
        g[0] = _mm512_div_pd(_mm512_add_pd(_mm512_add_pd(gx[0], gx[1]), gx[2]), three);
        g[1] = _mm512_div_pd(_mm512_add_pd(_mm512_add_pd(gy[0], gy[1]), gy[2]), three);
    } else {
        g[0] = gx[0], g[1] = gy[0];
    }
    wh[0] = _mm512_cvtepi32_pd(w), wh[1] = _mm512_cvtepi32_pd(h);
}

/* tex_texture_points in vector lanes, eight points at a time */
TEX_AVX512 void tex_map_points_avx512(const struct tex_texture *t, int n, const double *u,
                                         const double *v, const double *fw2, float *out,
                                         double *grad)
{
    struct pyramid py;
    int k = t->mip[0]->nc < 3 ? 1 : 3;
    memset(py.w, 0, sizeof py.w), memset(py.h, 0, sizeof py.h), memset(py.off, 0, sizeof py.off);
    for (int l = 0; l <= t->nlevels; l++) { /* the levels a lookup can take; the rest 0 */
        const tex_map *m = t->mip[l < t->nlevels ? l : t->nlevels - 1];
        py.w[l] = m->w, py.h[l] = m->h;
        py.off[l] = ((intptr_t)m->px - (intptr_t)t->mip[0]->px) / (intptr_t)sizeof(float);
    }
    for (int r = 0; r < 2; r++) {
        py.w16[r] = _mm512_loadu_si512(py.w + 16 * r);
        py.h16[r] = _mm512_loadu_si512(py.h + 16 * r);
        py.off8[r] = _mm512_loadu_si512(py.off + 8 * r);
    }
    for (int i = 0; i < n; i += 8) {
        double pu[8], pv[8], pf[8]; /* the last eight padded with their first point */
        const double *ui = u + i, *vi = v + i, *fi = fw2 + i;
        if (n - i < 8) {
            for (int j = 0; j < 8; j++) {
                int q = i + (j < n - i ? j : 0);
                pu[j] = u[q], pv[j] = v[q], pf[j] = fw2[q];
            }
            ui = pu, vi = pv, fi = pf;
        }
        __m512d uu = _mm512_loadu_pd(ui), vv = _mm512_loadu_pd(vi), a;
        uu = _mm512_sub_pd(uu, _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(uu))); /* u -= (int)u */
        vv = _mm512_sub_pd(vv, _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(vv)));
        __m256i lv = mip_levels8_avx512(t, _mm512_loadu_pd(fi), &a);
        __m256 o[3], o1[3];
        __m512d g[2], g1[2], wh[2], wh1[2], *gp = grad ? g : NULL, *gp1 = grad ? g1 : NULL;
        bilinear8_avx512(t, &py, k, lv, uu, vv, o, gp, wh);
        __mmask8 two = _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_GT_OQ);
        __m512d a1 = _mm512_sub_pd(_mm512_set1_pd(1), a);
        if (two) { /* trilinear: the next level's, weighted */
            bilinear8_avx512(t, &py, k, _mm256_add_epi32(lv, _mm256_set1_epi32(1)), uu, vv, o1,
                             gp1, wh1);
            for (int ch = 0; ch < k; ch++) { /* lanes of a = 0 keep their value */
                __m512d od = _mm512_cvtps_pd(o[ch]);
                __m512d mix = _mm512_add_pd(_mm512_mul_pd(od, a1),
                                            _mm512_mul_pd(_mm512_cvtps_pd(o1[ch]), a));
                o[ch] = _mm512_cvtpd_ps(_mm512_mask_blend_pd(two, od, mix));
            }
        }
        float f[3][8];
        for (int ch = 0; ch < 3; ch++)
            _mm256_storeu_ps(f[ch], o[k == 3 ? ch : 0]);
        for (int j = 0; j < 8 && i + j < n; j++)
            for (int ch = 0; ch < 3; ch++)
                out[3 * (i + j) + ch] = f[ch][j];
        if (!grad)
            continue;
        double gg[2][8];
        for (int d = 0; d < 2; d++) { /* map_eval's, per unit of u and of v */
            __m512d r = _mm512_mul_pd(g[d], wh[d]);
            if (two)
                r = _mm512_mask_blend_pd(
                    two, r,
                    _mm512_add_pd(_mm512_mul_pd(_mm512_mul_pd(g[d], wh[d]), a1),
                                  _mm512_mul_pd(_mm512_mul_pd(g1[d], wh1[d]), a)));
            _mm512_storeu_pd(gg[d], r);
        }
        for (int j = 0; j < 8 && i + j < n; j++)
            grad[2 * (i + j)] = gg[0][j], grad[2 * (i + j) + 1] = gg[1][j];
    }
}
#endif
