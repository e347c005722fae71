/* noise_points_x86.c - 3D noise at many points: eight at a time (AVX2), sixteen in 512-bit
 * registers (VBMI), the floats of noise.c's noise3_point */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdint.h>

#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "prim/noise_grid.h"
#include "prim/x86/noise_columns.h"
#include "prim/x86/noise_x86.h"

/* c mod m for whole numbers |c| < 2^31 in double, exactly: the quotient from
 * the reciprocal may be one off either way, and the remainder says which. */
TEX_AVX2 static inline __attribute__((always_inline)) __m256d mod_pd(__m256d c, double m, double inv)
{
    __m256d vm = _mm256_set1_pd(m), z = _mm256_setzero_pd();
    __m256d r = _mm256_sub_pd(
        c, _mm256_mul_pd(_mm256_floor_pd(_mm256_mul_pd(c, _mm256_set1_pd(inv))), vm));
    r = _mm256_add_pd(r, _mm256_and_pd(_mm256_cmp_pd(r, z, _CMP_LT_OQ), vm));
    return _mm256_sub_pd(r, _mm256_and_pd(_mm256_cmp_pd(r, vm, _CMP_GE_OQ), vm));
}

/* lat_index of the cells c (whole, in double) as 32-bit lanes. */
TEX_AVX2 static inline __attribute__((always_inline)) __m128i lat_pd(__m256d c, int period, int n)
{
    if (period)
        c = mod_pd(c, period, 1.0 / period);
    return _mm256_cvttpd_epi32(mod_pd(c, n, 1.0 / n));
}

#define FADE_PS(x) _mm256_set1_ps(x)
FADE_FN(TEX_AVX2, fade_ps, __m256, FADE_PS)

/* Eight 32-bit lanes from two groups of four */
TEX_AVX2 static inline __attribute__((always_inline)) __m256i join_epi32(__m128i lo, __m128i hi)
{
    return _mm256_inserti128_si256(_mm256_castsi128_si256(lo), hi, 1);
}

/* Eight rows of two gradients (x y z 0 x y z 0) as the columns x, y, z of each: row i
 * in lane i of c[0][*] (the first gradient) and c[1][*] (the second).  The immediates
 * are literal: an unoptimised build does not unroll a loop to make them constant. */
TEX_AVX2 static inline __attribute__((always_inline)) void columns8x2(const __m256 r[8],
                                                                  __m256 c[2][4])
{
    /* rows i and i + 4: their first halves (0x20), their second (0x31) */
    columns4(_mm256_permute2f128_ps(r[0], r[4], 0x20), _mm256_permute2f128_ps(r[1], r[5], 0x20),
             _mm256_permute2f128_ps(r[2], r[6], 0x20), _mm256_permute2f128_ps(r[3], r[7], 0x20),
             c[0]);
    columns4(_mm256_permute2f128_ps(r[0], r[4], 0x31), _mm256_permute2f128_ps(r[1], r[5], 0x31),
             _mm256_permute2f128_ps(r[2], r[6], 0x31), _mm256_permute2f128_ps(r[3], r[7], 0x31),
             c[1]);
}

/* noise3_point for eight points, in two steps so that the next eight's hashes (two
 * levels of dependent gathers) are under way while this eight's corners are summed. */
struct lanes8 {
    __m256 f[3], dm[3], wt[3][2]; /* fractions, fractions - 1, weights */
    int off[2][4][8]; /* [b0][b1 + 2 b2]: byte offsets of the corners' pgrad rows (b0 = 1
                       * only with a period: otherwise b0 = 0's row holds both) */
};

/* off from the x corners' indices x and the hashes of y and z, F[iy + F[iz]]: made with the
 * hashes, a stage before the sum reads them, as the sixteen-lane kernel does (there a 512-bit
 * store read back as integers at once stalled the row loads). */
TEX_AVX2 static inline __attribute__((always_inline)) void
lanes8_offsets(int period, const __m256i x[2], const __m256i hy[2][2], struct lanes8 *L)
{
    for (int q = 0; q < 4; q++)
        for (int b0 = 0; b0 < 1 + !!period; b0++)
            _mm256_storeu_si256((__m256i *)L->off[b0][q],
                                _mm256_slli_epi32(_mm256_add_epi32(x[b0], hy[q & 1][q >> 1]), 4));
}

/* The cells, fractions and weights of eight points, and the lattice indices of x, and of y
 * and z still to hash (iy, iz); 0 when a cell is beyond 2^30 (the caller's scalar path takes
 * those). */
TEX_AVX2 static inline __attribute__((always_inline)) int
lanes8_cells(const tex_noise_table *t, int period, const __m256d p[3][2], struct lanes8 *L,
             __m256i ix[2], __m256i iy[2], __m256i iz[2])
{
    const __m256d lim = _mm256_set1_pd(0x1p30), sign = _mm256_set1_pd(-0.0);
    const __m256 one = _mm256_set1_ps(1.0f);
    __m256i idx[3][2];

    for (int a = 0; a < 3; a++) {
        __m256d p0 = p[a][0], p1 = p[a][1];
        __m256d c0 = _mm256_floor_pd(p0), c1 = _mm256_floor_pd(p1);
        __m256d big = _mm256_or_pd(_mm256_cmp_pd(_mm256_andnot_pd(sign, c0), lim, _CMP_NLT_UQ),
                                   _mm256_cmp_pd(_mm256_andnot_pd(sign, c1), lim, _CMP_NLT_UQ));
        if (_mm256_movemask_pd(big))
            return 0;
        int per = a < 2 ? period : 0;
        __m256 f = _mm256_insertf128_ps(
            _mm256_castps128_ps256(_mm256_cvtpd_ps(_mm256_sub_pd(p0, c0))),
            _mm256_cvtpd_ps(_mm256_sub_pd(p1, c1)), 1);
        if (!per && !(t->n & (t->n - 1))) /* mod a power of two: a mask, negatives too */
            idx[a][0] = _mm256_and_si256(
                join_epi32(_mm256_cvttpd_epi32(c0), _mm256_cvttpd_epi32(c1)),
                _mm256_set1_epi32(t->n - 1));
        else
            idx[a][0] = join_epi32(lat_pd(c0, per, t->n), lat_pd(c1, per, t->n));
        if (per) {
            __m256d d1 = _mm256_set1_pd(1.0);
            idx[a][1] = join_epi32(lat_pd(_mm256_add_pd(c0, d1), per, t->n),
                                   lat_pd(_mm256_add_pd(c1, d1), per, t->n));
        } else { /* unwrapped: F and pgrad repeat after n entries */
            idx[a][1] = _mm256_add_epi32(idx[a][0], _mm256_set1_epi32(1));
        }
        L->f[a] = f;
        L->dm[a] = _mm256_sub_ps(f, one);
        L->wt[a][0] = fade_ps(t->fade, f);
        L->wt[a][1] = fade_ps(t->fade, _mm256_sub_ps(one, f));
    }
    ix[0] = idx[0][0], ix[1] = idx[0][1];
    iy[0] = idx[1][0], iy[1] = idx[1][1];
    iz[0] = idx[2][0], iz[1] = idx[2][1];
    return 1;
}

/* The hashes of y and z, F[iy + F[iz]], by gathers. */
TEX_AVX2 static inline __attribute__((always_inline)) int
lanes8_hash(const tex_noise_table *t, int period, const __m256d p[3][2], struct lanes8 *L)
{
    __m256i ix[2], iy[2], iz[2], hy[2][2];
    if (!lanes8_cells(t, period, p, L, ix, iy, iz))
        return 0;
    for (int b2 = 0; b2 < 2; b2++) {
        __m256i hz = _mm256_i32gather_epi32(t->perm, iz[b2], 4);
        for (int b1 = 0; b1 < 2; b1++)
            hy[b1][b2] = _mm256_i32gather_epi32(t->perm, _mm256_add_epi32(iy[b1], hz), 4);
    }
    lanes8_offsets(period, ix, hy, L);
    return 1;
}

/* Up to 64 entries of F at the byte indices b (their low 8 bits: n = 256, where F's second
 * copy repeats the first), from perm8 held in T[0..3]: two 128-byte permutes, bit 7 picks. */
TEX_VBMI static inline __attribute__((always_inline)) __m512i perm8_lookup(const __m512i T[4],
                                                                           __m512i b)
{
    __m512i lo = _mm512_permutex2var_epi8(T[0], b, T[1]);
    __m512i hi = _mm512_permutex2var_epi8(T[2], b, T[3]);
    return _mm512_mask_blend_epi8(_mm512_movepi8_mask(b), lo, hi);
}

/* perm8 in four registers. */
TEX_VBMI static inline __attribute__((always_inline)) void perm8_load(const tex_noise_table *t,
                                                                     __m512i T[4])
{
    for (int q = 0; q < 4; q++)
        T[q] = _mm512_loadu_si512(t->perm8 + 64 * q);
}

/* The eight corners' sum, corner by corner in noise3_point's order. */
TEX_AVX2 static inline __attribute__((always_inline)) void
lanes8_sum(const tex_noise_table *t, int period, const struct lanes8 *L, float *out)
{
    const char *G = (const char *)t->pgrad;
    __m256 wxy[2][2], sum = _mm256_setzero_ps();

    for (int b1 = 0; b1 < 2; b1++)
        for (int b0 = 0; b0 < 2; b0++)
            wxy[b0][b1] = _mm256_mul_ps(L->wt[0][b0], L->wt[1][b1]);
#pragma GCC unroll 4
    for (int q = 0; q < 4; q++) { /* corners 2q and 2q + 1, which differ in x alone */
        const int b1 = q & 1, b2 = q >> 1;
        /* Without a period corner 1's row follows corner 0's (idx + 1 unwrapped reaches
         * pgrad[n..2n), which repeats pgrad[0..n)). */
        const int *m0 = L->off[0][q], *m1 = L->off[1][q];
        __m256 r[8], gr[2][4];
#pragma GCC unroll 8
        for (int i = 0; i < 8; i++)
            r[i] = period ? _mm256_loadu2_m128((const float *)(G + m1[i]),
                                               (const float *)(G + m0[i]))
                          : _mm256_loadu_ps((const float *)(G + m0[i]));
        columns8x2(r, gr);
#pragma GCC unroll 2
        for (int b0 = 0; b0 < 2; b0++) {
            __m256 dot = _mm256_mul_ps(gr[b0][0], b0 ? L->dm[0] : L->f[0]);
            dot = _mm256_add_ps(dot, _mm256_mul_ps(gr[b0][1], b1 ? L->dm[1] : L->f[1]));
            dot = _mm256_add_ps(dot, _mm256_mul_ps(gr[b0][2], b2 ? L->dm[2] : L->f[2]));
            __m256 w = _mm256_mul_ps(wxy[b0][b1], L->wt[2][b2]);
            sum = _mm256_add_ps(sum, _mm256_mul_ps(w, dot));
        }
    }
    _mm256_storeu_ps(out, sum);
}

/* The first n - n % 8 points, eight at a time: lanes8 */
#define POINTS_NAME tex_noise3_points_avx2
#define POINTS_COORDS points8
#define POINTS_ATTR TEX_AVX2
#define POINTS_STATIC
#define POINTS_W 8
#define POINTS_VD __m256d
#define POINTS_LOADU _mm256_loadu_pd
#define POINTS_LANES lanes8
#define POINTS_SETUP (void)0
#define POINTS_HASH(Lp, pp) lanes8_hash(t, period, pp, Lp)
#define POINTS_SUM(Lp, o) lanes8_sum(t, period, Lp, o)
#include "prim/x86/noise_points_template.c"

/* ---- sixteen points in 512-bit registers (VBMI: 256 gradients, no period) ----
 * Eight points' two x corners share a register: [p0..3 | p0..3 | p4..7 | p4..7], corner
 * b0 = 0 in the first and third quarters, b0 = 1 in the others; sixteen points are two such
 * sets.  A point's 32-byte row of pgrad (both x corners) fills half a register, so that
 * columns4 leaves the gradients in this order without crossing quarters, and the corners'
 * products return to point order once per corner pair.  Same operations as noise3_point. */
struct lanes16 {
    __m512 dx[2], wx[2];       /* [set]: f | f - 1 and their fades, by corner b0 */
    __m512 dy[2][2], dz[2][2]; /* [set][b]: f or f - 1, each point twice */
    __m512 wy[2][2], wz[2][2]; /* [set][b]: the fades */
    int off[4][16];            /* [b1 + 2 b2]: the byte offsets of the points' pgrad rows */
};

#define FADE_PS16(x) _mm512_set1_ps(x)
FADE_FN(TEX_VBMI, fade_ps16, __m512, FADE_PS16)

/* One axis of sixteen points in point order: v = f, f - 1, fade (f), fade (1 - f), and the
 * cells' lattice indices as bytes mod 256 (byte i: point i); 0 when a cell is beyond 2^30. */
TEX_VBMI static inline __attribute__((always_inline)) int
lanes16_axis(int fade, const __m512d p[2], __m512 v[4], __m128i *idx)
{
    const __m512 one = _mm512_set1_ps(1.0f);
    const __m512d lim = _mm512_set1_pd(0x1p30);
    __m512d c0 = _mm512_roundscale_pd(p[0], _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    __m512d c1 = _mm512_roundscale_pd(p[1], _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    if (_mm512_cmp_pd_mask(_mm512_abs_pd(c0), lim, _CMP_NLT_UQ) |
        _mm512_cmp_pd_mask(_mm512_abs_pd(c1), lim, _CMP_NLT_UQ))
        return 0;
    __m512 f = _mm512_castpd_ps(_mm512_insertf64x4(
        _mm512_castpd256_pd512(_mm256_castps_pd(_mm512_cvtpd_ps(_mm512_sub_pd(p[0], c0)))),
        _mm256_castps_pd(_mm512_cvtpd_ps(_mm512_sub_pd(p[1], c1))), 1));
    __m512i ic = _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvttpd_epi32(c0)),
                                    _mm512_cvttpd_epi32(c1), 1);
    /* the low bytes of the sixteen dwords: mod 256, negatives too */
    const __m512i low = _mm512_set_epi32(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x3c383430,
                                         0x2c282420, 0x1c181410, 0x0c080400);
    *idx = _mm512_castsi512_si128(_mm512_permutexvar_epi8(low, ic));
    v[0] = f;
    v[1] = _mm512_sub_ps(f, one);
    v[2] = fade_ps16(fade, f);
    v[3] = fade_ps16(fade, _mm512_sub_ps(one, f));
    return 1;
}

/* The fractions, fades and hashes of sixteen points; 0 when a cell is beyond 2^30. */
TEX_VBMI static inline __attribute__((always_inline)) int
lanes16_hash(int fade, const __m512i T[4], const __m512d p[3][2], struct lanes16 *L)
{
    /* set s: points 8s..8s+3 twice, then 8s+4..8s+7 twice; for x the second of each pair
     * from the second source (corner b0 = 1) */
    const __m512i twice[2] = {
        _mm512_set_epi32(7, 6, 5, 4, 7, 6, 5, 4, 3, 2, 1, 0, 3, 2, 1, 0),
        _mm512_set_epi32(15, 14, 13, 12, 15, 14, 13, 12, 11, 10, 9, 8, 11, 10, 9, 8)};
    const __m512i pair[2] = {
        _mm512_set_epi32(23, 22, 21, 20, 7, 6, 5, 4, 19, 18, 17, 16, 3, 2, 1, 0),
        _mm512_set_epi32(31, 30, 29, 28, 15, 14, 13, 12, 27, 26, 25, 24, 11, 10, 9, 8)};
    __m512 vx[4], vy[4], vz[4];
    __m128i ix, iy, iz;
    if (!lanes16_axis(fade, p[0], vx, &ix) || !lanes16_axis(fade, p[1], vy, &iy) ||
        !lanes16_axis(fade, p[2], vz, &iz))
        return 0;
    for (int s = 0; s < 2; s++) {
        L->dx[s] = _mm512_permutex2var_ps(vx[0], pair[s], vx[1]);
        L->wx[s] = _mm512_permutex2var_ps(vx[2], pair[s], vx[3]);
        for (int b = 0; b < 2; b++) {
            L->dy[s][b] = _mm512_permutexvar_ps(twice[s], vy[b]);
            L->wy[s][b] = _mm512_permutexvar_ps(twice[s], vy[2 + b]);
            L->dz[s][b] = _mm512_permutexvar_ps(twice[s], vz[b]);
            L->wz[s][b] = _mm512_permutexvar_ps(twice[s], vz[2 + b]);
        }
    }
    __m512i x = _mm512_cvtepu8_epi32(ix);
    /* bytes 0..15: F[iz], 16..31: F[iz + 1]; then quarter b1 + 2 b2: F[iy + b1 + F[iz + b2]]
     * (bytes add mod 256, as F repeats after 256) */
    const __m512i plus1 = _mm512_set_epi64(0, 0, 0, 0, 0x0101010101010101,
                                           0x0101010101010101, 0, 0);
    __m512i hz = perm8_lookup(T, _mm512_add_epi8(_mm512_broadcast_i32x4(iz), plus1));
    __m512i by = _mm512_add_epi8(_mm512_broadcast_i32x4(iy),
                                 _mm512_shuffle_i32x4(plus1, plus1, 0x44));
    __m512i hy = perm8_lookup(T, _mm512_add_epi8(by, _mm512_shuffle_i32x4(hz, hz, 0x50)));
    __m128i hq[4] = {_mm512_castsi512_si128(hy), _mm512_extracti32x4_epi32(hy, 1),
                     _mm512_extracti32x4_epi32(hy, 2), _mm512_extracti32x4_epi32(hy, 3)};
    for (int q = 0; q < 4; q++) /* pgrad[x + F[...]], 16 bytes a row */
        _mm512_storeu_si512(L->off[q],
                            _mm512_slli_epi32(_mm512_add_epi32(x, _mm512_cvtepu8_epi32(hq[q])), 4));
    return 1;
}

/* The eight corners' sum of sixteen points, corner by corner in noise3_point's order. */
TEX_VBMI static inline __attribute__((always_inline)) void
lanes16_sum(const tex_noise_table *t, const struct lanes16 *L, float *out)
{
    const char *G = (const char *)t->pgrad;
    __m512 wxy[2][2], sum = _mm512_setzero_ps();

    for (int s = 0; s < 2; s++)
        for (int b1 = 0; b1 < 2; b1++)
            wxy[s][b1] = _mm512_mul_ps(L->wx[s], L->wy[s][b1]);
#pragma GCC unroll 4
    for (int q = 0; q < 4; q++) { /* corners 2q and 2q + 1 */
        const int b1 = q & 1, b2 = q >> 1;
        const int *m = L->off[q];
        __m512 prod[2];
#pragma GCC unroll 2
        for (int s = 0; s < 2; s++) {
            __m512 r[4], g[4];
#pragma GCC unroll 4
            for (int k = 0; k < 4; k++)
                r[k] = _mm512_castpd_ps(_mm512_insertf64x4(
                    _mm512_castpd256_pd512(_mm256_loadu_pd((const double *)(G + m[8 * s + k]))),
                    _mm256_loadu_pd((const double *)(G + m[8 * s + 4 + k])), 1));
            columns4_16(r, g);
            __m512 dot = _mm512_mul_ps(g[0], L->dx[s]);
            dot = _mm512_add_ps(dot, _mm512_mul_ps(g[1], L->dy[s][b1]));
            dot = _mm512_add_ps(dot, _mm512_mul_ps(g[2], L->dz[s][b2]));
            prod[s] = _mm512_mul_ps(_mm512_mul_ps(wxy[s][b1], L->wz[s][b2]), dot);
        }
        sum = _mm512_add_ps(sum, _mm512_shuffle_f32x4(prod[0], prod[1], _MM_SHUFFLE(2, 0, 2, 0)));
        sum = _mm512_add_ps(sum, _mm512_shuffle_f32x4(prod[0], prod[1], _MM_SHUFFLE(3, 1, 3, 1)));
    }
    _mm512_storeu_ps(out, sum);
}

/* The first n - n % 16 points, sixteen at a time: lanes16, the hashes from perm8 in
 * registers */
#define POINTS_NAME noise3_zmm_groups
#define POINTS_COORDS points16
#define POINTS_ATTR TEX_VBMI
#define POINTS_STATIC static
#define POINTS_W 16
#define POINTS_VD __m512d
#define POINTS_LOADU _mm512_loadu_pd
#define POINTS_LANES lanes16
#define POINTS_SETUP                                                                             \
    __m512i T[4];                                                                                \
    perm8_load(t, T)
#define POINTS_HASH(Lp, pp) lanes16_hash(t->fade, T, pp, Lp)
#define POINTS_SUM(Lp, o) lanes16_sum(t, Lp, o)
#include "prim/x86/noise_points_template.c"

/* The first n - n % 8 points: sixteen at a time, the last eight by tex_noise3_points_avx2;
 * returns how many. */
TEX_VBMI int tex_noise3_points_vbmi(const tex_noise_table *t, int period, const double *a,
                                    double f, const double *const c[3], int n, float *out)
{
    int i = noise3_zmm_groups(t, period, a, f, c, n, out);
    const double *ci[3] = {c[0] + i, c[1] + i, c[2] ? c[2] + i : NULL};
    return i + tex_noise3_points_avx2(t, period, a, f, ci, n - i, out + i);
}
#endif
