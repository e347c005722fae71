/* noise.c - gradient noise: point evaluation, vectorised grid rows, the noise primitive */

#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/x86/simd_x86.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/error.h"
#include "prim/noise.h"
#include "prim/prim.h"
#include "base/rng.h"

int tex_noise_init(tex_noise_table *t, uint64_t seed, int n, int period)
{
    tex_rng r;

    memset(t, 0, sizeof *t);
    if (n < 2 || n > TEX_NOISE_MAX_GRADIENTS)
        return tex_usage_error("the number of gradients must be 2..%d (got %d)",
                               TEX_NOISE_MAX_GRADIENTS, n);
    if (period < 0)
        return tex_usage_error("the noise period must be >= 0 (got %d)", period);
    t->n = n;
    t->period = period;
    t->perm = malloc(2 * n * sizeof *t->perm);
    t->grad = malloc(n * sizeof *t->grad);
    t->grad4 = malloc(n * sizeof *t->grad4);
    t->pgrad = malloc(2 * n * sizeof *t->pgrad);
    if (!t->perm || !t->grad || !t->grad4 || !t->pgrad) {
        tex_noise_free(t);
        return tex_error("out of memory");
    }
    tex_rng_seed(&r, seed);
    for (int i = 0; i < n; i++) {
        /* Uniform on the sphere: z uniform in [-1,1], longitude uniform. */
        double z = 2.0 * tex_rng_uniform(&r) - 1.0, phi = 2.0 * M_PI * tex_rng_uniform(&r);
        double s = sqrt(1.0 - z * z);
        t->grad[i][0] = (float)(s * cos(phi));
        t->grad[i][1] = (float)(s * sin(phi));
        t->grad[i][2] = (float)z;
        t->grad[i][3] = 0;
        t->perm[i] = i;
    }
    for (int i = 0; i < n; i++) {
        /* Uniform on the 4D sphere: a normalised Gaussian vector. */
        double g[4], len;
        do {
            len = 0;
            for (int k = 0; k < 4; k++) {
                g[k] = tex_rng_gauss(&r);
                len += g[k] * g[k];
            }
        } while (len < 1e-12);
        len = sqrt(len);
        for (int k = 0; k < 4; k++)
            t->grad4[i][k] = (float)(g[k] / len);
    }
    tex_rng_shuffle(&r, t->perm, n);
    memcpy(t->perm + n, t->perm, n * sizeof *t->perm);
    for (int m = 0; m < 2 * n; m++)
        for (int k = 0; k < 4; k++)
            t->pgrad[m][k] = t->grad[t->perm[m]][k];
    for (int i = 0; n == 256 && i < n; i++)
        t->perm8[i] = (unsigned char)t->perm[i];
    return 0;
}

void tex_noise_free(tex_noise_table *t)
{
    free(t->perm);
    free(t->grad);
    free(t->grad4);
    free(t->pgrad);
    t->pgrad = NULL;
    t->perm = NULL;
    t->grad = NULL;
    t->grad4 = NULL;
}

static inline int imod64(int64_t a, int64_t n)
{
    int64_t m = a % n;
    return (int)(m < 0 ? m + n : m);
}

/* A lattice index made ready for F: wrapped by the period, then mod n. */
static inline int lat_index(int64_t i, int period, int n)
{
    if (period)
        i = imod64(i, period);
    return imod64(i, n);
}

/* The fade of eq. 5.2 for t in [0,1] (w(0) = 1, w(1) = 0), written once for double, float
 * and the vector types, whose operators are their lanes' (C: a constant of type T): the same
 * operations in the same order at every width. */
#define FADE_FN(ATTR, NAME, T, C)                                                            \
    ATTR static inline __attribute__((always_inline)) T NAME(int kind, T t)                  \
    {                                                                                        \
        if (kind == TEX_FADE_QUINTIC)                                                        \
            return C(1) - t * t * t * (t * (t * C(6) - C(15)) + C(10));                      \
        return (C(2) * t - C(3)) * t * t + C(1);                                             \
    }
#define FADE_D(x) ((double)(x))
#define FADE_F(x) ((float)(x))
FADE_FN(, fade, double, FADE_D)
FADE_FN(, fadef, float, FADE_F)

/* The fade's derivative */
static inline double dfade(int kind, double t)
{
    if (kind == TEX_FADE_QUINTIC)
        return -30.0 * t * t * (t - 1.0) * (t - 1.0);
    return 6.0 * t * (t - 1.0);
}

/* Noise at p (dims 3 or 4) and, if g, its gradient. */
static double noise_point(const tex_noise_table *t, int period, int dims, const double p[4],
                          double g[4])
{
    const int *F = t->perm;
    int n = t->n, idx[4][2];
    double f[4], wt[4][2], dw[4][2], sum = 0;

    for (int a = 0; a < dims; a++) {
        double c = floor(p[a]);
        int64_t i = tex_noise_cell(c);
        int per = a < 2 ? period : 0;
        f[a] = p[a] - c;
        idx[a][0] = lat_index(i, per, n);
        idx[a][1] = lat_index(i + 1, per, n);
        wt[a][0] = fade(t->fade, f[a]);
        wt[a][1] = fade(t->fade, 1.0 - f[a]);
        dw[a][0] = dfade(t->fade, f[a]);
        dw[a][1] = -dfade(t->fade, 1.0 - f[a]);
    }
    if (g)
        g[0] = g[1] = g[2] = g[3] = 0;
    for (int c = 0; c < 1 << dims; c++) {
        int b[4] = {c & 1, c >> 1 & 1, c >> 2 & 1, c >> 3 & 1}, h;
        const float *gr;
        double d[4], dot = 0, w = 1;
        if (dims == 4) {
            h = F[idx[0][b[0]] +
                  F[idx[1][b[1]] + F[idx[2][b[2]] + F[idx[3][b[3]]]]]];
            gr = t->grad4[h];
        } else {
            h = F[idx[0][b[0]] + F[idx[1][b[1]] + F[idx[2][b[2]]]]];
            gr = t->grad[h];
        }
        for (int a = 0; a < dims; a++) {
            d[a] = f[a] - b[a];
            dot += gr[a] * d[a];
            w *= wt[a][b[a]];
        }
        sum += w * dot;
        if (g)
            for (int a = 0; a < dims; a++) {
                double dwa = dw[a][b[a]];
                for (int o = 0; o < dims; o++)
                    if (o != a)
                        dwa *= wt[o][b[o]];
                g[a] += dwa * dot + w * gr[a];
            }
    }
    return sum;
}

/* 3D noise's value: cells and fractions in double precision (far points keep their
 * texture), the corners' sum in float; noise3_avx2 performs these float operations in
 * this order, eight points at a time. */
static float noise3_point(const tex_noise_table *t, int period, const double p[3])
{
    const int *F = t->perm;
    int n = t->n, idx[3][2];
    float f[3], wt[3][2], sum = 0;

    for (int a = 0; a < 3; a++) {
        double c = floor(p[a]);
        int64_t i = tex_noise_cell(c);
        int per = a < 2 ? period : 0;
        f[a] = (float)(p[a] - c);
        idx[a][0] = lat_index(i, per, n);
        idx[a][1] = lat_index(i + 1, per, n);
        wt[a][0] = fadef(t->fade, f[a]);
        wt[a][1] = fadef(t->fade, 1.0f - f[a]);
    }
    for (int c = 0; c < 8; c++) {
        int b0 = c & 1, b1 = c >> 1 & 1, b2 = c >> 2 & 1;
        const float *gr = t->pgrad[idx[0][b0] + F[idx[1][b1] + F[idx[2][b2]]]];
        float d0 = b0 ? f[0] - 1.0f : f[0], d1 = b1 ? f[1] - 1.0f : f[1],
              d2 = b2 ? f[2] - 1.0f : f[2];
        float dot = gr[0] * d0 + gr[1] * d1 + gr[2] * d2;
        float w = wt[0][b0] * wt[1][b1] * wt[2][b2];
        sum += w * dot;
    }
    return sum;
}

double tex_noise3p(const tex_noise_table *t, int period, double x, double y, double z)
{
    double p[3] = {x, y, z};
    return noise3_point(t, period, p);
}

double tex_noise4p(const tex_noise_table *t, int period, double x, double y, double z, double w)
{
    double p[4] = {x, y, z, w};
    return noise_point(t, period, 4, p, NULL);
}

double tex_noise3(const tex_noise_table *t, double x, double y, double z)
{
    return tex_noise3p(t, t->period, x, y, z);
}

double tex_noise4(const tex_noise_table *t, double x, double y, double z, double w)
{
    return tex_noise4p(t, t->period, x, y, z, w);
}

double tex_noise3_grad(const tex_noise_table *t, int period, double x, double y, double z,
                       double g[3])
{
    double p[4] = {x, y, z, 0}, g4[4];
    double s = noise_point(t, period, 3, p, g4);
    g[0] = g4[0];
    g[1] = g4[1];
    g[2] = g4[2];
    return s;
}

/* ---- many points at once ---- */

/* tex_noise3p at a + f (u, v, w), the coordinates computed as the callers did */
static float noise3_at(const tex_noise_table *t, int period, const double a[3], double f,
                       double u, double v, double w)
{
    double p[3] = {a[0] + f * u, a[1] + f * v, a[2] + f * w};
    return noise3_point(t, period, p);
}

#ifdef TEX_X86
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

/* Four rows of four floats in each 128-bit half of a0..a3 as the vectors of their four
 * columns (row i of each half in lane i of that half) */
TEX_AVX2 static inline __attribute__((always_inline)) void
columns4(__m256 a0, __m256 a1, __m256 a2, __m256 a3, __m256 c[4])
{
    __m256 t0 = _mm256_unpacklo_ps(a0, a1), t1 = _mm256_unpacklo_ps(a2, a3);
    __m256 t2 = _mm256_unpackhi_ps(a0, a1), t3 = _mm256_unpackhi_ps(a2, a3);
    c[0] = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));
    c[1] = _mm256_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));
    c[2] = _mm256_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));
    c[3] = _mm256_shuffle_ps(t2, t3, _MM_SHUFFLE(3, 2, 3, 2));
}

/* Eight rows of four floats as the four vectors of their columns (row i in lane i) */
TEX_AVX2 static inline __attribute__((always_inline)) void columns8(const float *const row[8],
                                                                __m256 c[4])
{
    columns4(_mm256_loadu2_m128(row[4], row[0]), _mm256_loadu2_m128(row[5], row[1]),
             _mm256_loadu2_m128(row[6], row[2]), _mm256_loadu2_m128(row[7], row[3]), c);
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

/* Points i..i+7 (points16: i..i+15): a + f (u, v, w) (w NULL: 0) as tex_noise_points_at
 * makes them, or (u, v, w) themselves when a is NULL; the vector types' operators, a scalar
 * taken as a vector of it. */
#define POINTS_FN(ATTR, NAME, V, LOADU)                                                      \
    ATTR static inline __attribute__((always_inline)) void NAME(                             \
        const double *a, double f, const double *const c[3], int i, V p[3][2])               \
    {                                                                                        \
        enum { W = sizeof(V) / sizeof(double) };                                             \
        for (int k = 0; k < 3; k++)                                                          \
            for (int h = 0; h < 2; h++) {                                                    \
                V x = {0};                                                                   \
                if (c[k])                                                                    \
                    x = LOADU(c[k] + i + W * h);                                             \
                p[k][h] = x;                                                                 \
                if (a)                                                                       \
                    p[k][h] = a[k] + f * x;                                                  \
            }                                                                                \
    }
POINTS_FN(TEX_AVX2, points8, __m256d, _mm256_loadu_pd)

/* noise3_at at the points of points8, i < n, or tex_noise3p at (u, v, w) with a NULL */
static float noise3_src(const tex_noise_table *t, int period, const double *a, double f,
                        const double *const c[3], int i)
{
    const double w = c[2] ? c[2][i] : 0;
    return a ? noise3_at(t, period, a, f, c[0][i], c[1][i], w)
             : tex_noise3p(t, period, c[0][i], c[1][i], w);
}

/* The first n - n % W points, W at a time, the hashes of the next W made before these W's
 * corners are summed; returns how many.  One loop for both widths, which differ in their
 * lanes (struct LANES, points made by POINTS into vectors VD), their hashes, HASH(L, p) (0: a
 * cell beyond 2^30), what these need first (SETUP), and their sums, SUM(L, out). */
#define NOISE3_POINTS(TARGET, NAME, W, LANES, VD, SETUP, POINTS, HASH, SUM)                   \
    TARGET static int NAME(const tex_noise_table *t, int period, const double *a, double f, \
                           const double *const c[3], int n, float *out)                      \
    {                                                                                        \
        struct LANES L[2];                                                                   \
        int ok[2], m = n / W;                                                                \
        VD p[3][2];                                                                          \
        SETUP;                                                                               \
        if (m == 0)                                                                          \
            return 0;                                                                        \
        POINTS(a, f, c, 0, p);                                                               \
        ok[0] = HASH(&L[0], p);                                                              \
        for (int k = 0; k < m; k++) {                                                        \
            if (k + 1 < m) {                                                                 \
                POINTS(a, f, c, W * (k + 1), p);                                             \
                ok[(k + 1) & 1] = HASH(&L[(k + 1) & 1], p);                                  \
            }                                                                                \
            if (ok[k & 1])                                                                   \
                SUM(&L[k & 1], out + W * k);                                                 \
            else                                                                             \
                for (int i = W * k; i < W * k + W; i++)                                      \
                    out[i] = noise3_src(t, period, a, f, c, i);                              \
        }                                                                                    \
        return W * m;                                                                        \
    }
#define HASH8(Lp, pp) lanes8_hash(t, period, pp, Lp)
#define SUM8(Lp, o) lanes8_sum(t, period, Lp, o)
NOISE3_POINTS(TEX_AVX2, noise3_avx2_points, 8, lanes8, __m256d, (void)0, points8, HASH8, SUM8)

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

/* Four rows of four floats in each 128-bit quarter of r[0..3] as the vectors of their
 * columns (row i of each quarter in lane i of that quarter): columns4 on 512 bits */
TEX_AVX512 static inline __attribute__((always_inline)) void columns4_16(const __m512 r[4],
                                                                         __m512 c[4])
{
    __m512 t0 = _mm512_unpacklo_ps(r[0], r[1]), t1 = _mm512_unpacklo_ps(r[2], r[3]);
    __m512 t2 = _mm512_unpackhi_ps(r[0], r[1]), t3 = _mm512_unpackhi_ps(r[2], r[3]);
    c[0] = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));
    c[1] = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));
    c[2] = _mm512_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));
    c[3] = _mm512_shuffle_ps(t2, t3, _MM_SHUFFLE(3, 2, 3, 2));
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

POINTS_FN(TEX_VBMI, points16, __m512d, _mm512_loadu_pd)

/* The first n - n % 8 points: sixteen at a time, the last eight by noise3_avx2_points;
 * returns how many. */
#define HASH16(Lp, pp) lanes16_hash(t->fade, T, pp, Lp)
#define SUM16(Lp, o) lanes16_sum(t, Lp, o)
NOISE3_POINTS(TEX_VBMI, noise3_zmm_groups, 16, lanes16, __m512d, __m512i T[4]; perm8_load(t, T),
              points16, HASH16, SUM16)
TEX_VBMI static int noise3_zmm_points(const tex_noise_table *t, int period, const double *a,
                                      double f, const double *const c[3], int n, float *out)
{
    int i = noise3_zmm_groups(t, period, a, f, c, n, out);
    const double *ci[3] = {c[0] + i, c[1] + i, c[2] ? c[2] + i : NULL};
    return i + noise3_avx2_points(t, period, a, f, ci, n - i, out + i);
}

typedef int (*points_kernel)(const tex_noise_table *, int, const double *, double,
                             const double *const[3], int, float *);
/* The point kernel for t: sixteen lanes and the byte table for 256 gradients and no period
 * where the CPU has VBMI (the same bytes), else eight lanes and the gathers. */
static points_kernel points_kernel_for(const tex_noise_table *t, int period)
{
    return !period && t->n == 256 && tex_simd_vbmi() ? noise3_zmm_points : noise3_avx2_points;
}
#endif

void tex_noise_points(const tex_noise_table *t, int period, int dims, int n, const double *x,
                      const double *y, const double *z, const double *w, double *out)
{
    int i = 0;

#ifdef TEX_X86
    if (dims == 3 && tex_simd_level() >= TEX_SIMD_AVX2) {
        const double *c[3] = {x, y, z};
        float r[TEX_POINTS_BATCH];
        points_kernel kernel = points_kernel_for(t, period);
        for (; i + 8 <= n; i += TEX_POINTS_BATCH) {
            int m = n - i < TEX_POINTS_BATCH ? n - i : TEX_POINTS_BATCH;
            const double *ci[3] = {c[0] + i, c[1] + i, c[2] + i};
            int done = kernel(t, period, NULL, 1, ci, m, r);
            for (int k = 0; k < done; k++)
                out[i + k] = r[k];
            if (done < m) {
                i += done;
                break;
            }
        }
    }
#endif
    for (; i < n; i++)
        out[i] = dims == 4 ? tex_noise4p(t, period, x[i], y[i], z[i], w[i])
                           : tex_noise3p(t, period, x[i], y[i], z[i]);
}

void tex_noise_points_at(const tex_noise_table *t, int period, const double a[3], double f, int n,
                         const double *u, const double *v, const double *w, float *out)
{
    int i = 0;

#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2) {
        const double *c[3] = {u, v, w};
        i = points_kernel_for(t, period)(t, period, a, f, c, n, out);
    }
#endif
    for (; i < n; i++)
        out[i] = noise3_at(t, period, a, f, u[i], v[i], w ? w[i] : 0);
}

/* ---- grid sampling ---- */

/* Lattice rows kept for the pixel rows that follow: one entry per thread
 * that holds it (taken with an atomic flag, so any thread split works, and
 * a thread finding none busy-free computes the rows on its stack). */
struct cache_entry {
    int busy, valid[2];
    int64_t key[2];
    float *buf[2]; /* a folded lattice row: X, Y, C, each g->stride floats */
};

struct tex_noise_cache {
    int n;
    struct cache_entry e[];
};

static void grid_clear(tex_noise_grid *g)
{
    free(g->slot);
    free(g->lat);
    free(g->u);
    free(g->lut);
    free(g->plane);
    free(g->corner);
    if (g->cache) {
        for (int i = 0; i < g->cache->n; i++)
            free(g->cache->e[i].buf[0]);
        free(g->cache);
    }
    g->slot = g->lat = NULL;
    g->lut = NULL;
    g->plane = NULL;
    g->corner = g->corner2 = NULL;
    g->u = g->um1 = g->w0 = g->w1 = g->dw0 = g->dw1 = NULL;
    g->cache = NULL;
}

void tex_noise_grid_free(tex_noise_grid *g)
{
    grid_clear(g);
}

static int lut_init(tex_noise_grid *g, int fold);
static int corners_adjacent(const tex_noise_grid *g);

/* The slice's corners in z (and w): their weights, offsets and hash prefixes. */
static void slice_setup(tex_noise_grid *g, double z, double w4)
{
    const tex_noise_table *t = g->t;
    const int *F = t->perm;
    double zc = floor(z), wc = floor(w4), fr[2] = {z - zc, w4 - wc}, wt[2][2];
    int64_t base[2] = {tex_noise_cell(zc), tex_noise_cell(wc)};
    int li[2][2], axes = g->dims - 2;

    for (int a = 0; a < axes; a++) {
        li[a][0] = lat_index(base[a], 0, t->n);
        li[a][1] = lat_index(base[a] + 1, 0, t->n);
        wt[a][0] = fade(t->fade, fr[a]);
        wt[a][1] = fade(t->fade, 1.0 - fr[a]);
    }
    memset(g->zdm, 0, sizeof g->zdm);
    g->nz = 0;
    for (int c = 0; c < 1 << axes; c++) {
        int b[2] = {c & 1, c >> 1 & 1}, k = g->nz;
        double w = 1;
        for (int a = 0; a < axes; a++)
            w *= wt[a][b[a]];
        if (w == 0) /* a corner at distance 1: w(1) = 0 exactly */
            continue;
        g->zm[k][0] = g->zm[k][1] = (float)w;
        g->zm[k][2] = (float)(w * (fr[0] - b[0]));
        g->zm[k][3] = axes == 2 ? (float)(w * (fr[1] - b[1])) : 0;
        g->zh[k] = axes == 2 ? F[li[0][b[0]] + F[li[1][b[1]]]] : F[li[0][b[0]]];
        if (axes == 1) {
            /* d/dz of w(z) (G . d) = G.x w' dx + G.y w' dy + G.z (w' dz + w) */
            double dw = b[0] ? -dfade(t->fade, 1.0 - fr[0]) : dfade(t->fade, fr[0]);
            g->zdm[k][0] = g->zdm[k][1] = (float)dw;
            g->zdm[k][2] = (float)(dw * (fr[0] - b[0]) + w);
        }
        g->nz++;
    }
}

/* Pixel rows share lattice rows when a cell spans more than one row: keep
 * each thread's last two (without memory for them, rows compute their own). */
static void cache_init(tex_noise_grid *g)
{
#ifdef _OPENMP
    int n = omp_get_max_threads() + 1;
#else
    int n = 1;
#endif
    g->cache = calloc(1, sizeof *g->cache + n * sizeof g->cache->e[0]);
    if (!g->cache)
        return;
    g->cache->n = n;
    for (int i = 0; i < n; i++) {
        struct cache_entry *e = &g->cache->e[i];
        if (!(e->buf[0] = malloc(6 * (size_t)g->stride * sizeof *e->buf[0]))) {
            e->busy = 1; /* never taken */
            continue;
        }
        e->buf[1] = e->buf[0] + 3 * (size_t)g->stride;
    }
}

/* The most cells between the first and last of n columns from a multiple of n (the slots'
 * cells in list) */
static int grid_span(const tex_noise_grid *g, const int64_t *list, int n)
{
    int64_t most = 0;
    for (int x = 0; x + n - 1 < g->w; x += n) {
        int64_t d = list[g->slot[x + n - 1]] - list[g->slot[x]];
        most = d > most ? d : most;
    }
    return most > INT_MAX ? INT_MAX : (int)most;
}

/* Lattice rows from the table when the rows would fold more lattice points than it has
 * (cells spanning less than a pixel row are not kept); folded rows, with each column's
 * corner entry, where cells are narrower than the wide rows' (5 pixels) and the row has
 * more columns than the table entries (fBm from 1024 cells on 2048 columns: 1.5 times the
 * slots' rows at 2 pixels a cell, 1.1 at 4).  Without memory, rows fold their own. */
static void table_init(tex_noise_grid *g)
{
    int n = g->t->n;
    double rows = g->fy < 1 ? g->fy * g->h + 2 : 2.0 * g->h;

    if (n > 1024 || rows * g->nslots <= 2.0 * n * n)
        return;
    g->adjacent = corners_adjacent(g);
    if (g->adjacent && (g->paired || (!g->wide && n >= 16)) && g->w >= 2 * (n + 1) &&
        (g->corner = malloc(2 * (size_t)g->w * sizeof *g->corner))) {
        g->corner2 = g->corner + g->w;
        for (int x = 0; x < g->w; x++) {
            g->corner[x] = g->lat[g->slot[x]];
            g->corner2[x] = 2 * g->corner[x];
        }
    }
    if (lut_init(g, g->corner != NULL) < 0) {
        free(g->corner);
        g->corner = g->corner2 = NULL;
    }
}

int tex_noise_grid_init(tex_noise_grid *g, const tex_noise_table *t, int w, int h, double fx,
                        double fy, const double off[4], int dims, int period)
{
    int64_t *list;
    int ns = 0;

    memset(g, 0, sizeof *g);
    if (w < 1 || h < 1 || (dims != 3 && dims != 4))
        return tex_error("noise grid: bad size %dx%d or dimension %d", w, h, dims);
    g->t = t;
    g->w = w;
    g->h = h;
    g->dims = dims;
    g->period = period;
    g->fy = fy / h;
    g->oy = off[1];
    slice_setup(g, off[2], dims == 4 ? off[3] : 0);
    g->slot = malloc(w * sizeof *g->slot);
    g->lat = malloc((2 * w + 16) * sizeof *g->lat);
    g->u = malloc(6 * (w + 8) * sizeof *g->u);
    list = malloc((2 * w + 2) * sizeof *list);
    if (!g->slot || !g->lat || !g->u || !list) {
        free(list);
        grid_clear(g);
        return tex_error("out of memory");
    }
    g->um1 = g->u + (w + 8);
    g->w0 = g->um1 + (w + 8);
    g->w1 = g->w0 + (w + 8);
    g->dw0 = g->w1 + (w + 8);
    g->dw1 = g->dw0 + (w + 8);
    /* Columns: the cell and fraction in double, so that large offsets keep
     * their texture; the slots list each lattice column the row touches once,
     * a pixel's right corner sitting in the slot after its left one.  When eight
     * pixels span seven cells or more, sharing saves little and costs the rows
     * gathers: every column then has its own pair. */
    g->paired = fx >= 0.875 * w;
    g->wide = fx * 5 <= w;
    for (int x = 0; x < w; x++) {
        double X = off[0] + fx * ((x + 0.5) / w), c = floor(X);
        int64_t i = tex_noise_cell(c);
        double u = X - c;
        if (ns == 0 || i > list[ns - 1] || g->paired) {
            list[ns++] = i;
            list[ns++] = i + 1;
        } else if (i == list[ns - 1]) {
            list[ns++] = i + 1;
        }
        g->slot[x] = ns - 2;
        g->u[x] = (float)u;
        g->um1[x] = (float)(u - 1.0);
        g->w0[x] = (float)fade(t->fade, u);
        g->w1[x] = (float)fade(t->fade, 1.0 - u);
        g->dw0[x] = (float)dfade(t->fade, u);
        g->dw1[x] = (float)-dfade(t->fade, 1.0 - u);
    }
    g->span8 = grid_span(g, list, 8);
    g->span16 = grid_span(g, list, 16);
    for (int s = 0; s < ns; s++)
        g->lat[s] = lat_index(list[s], period, t->n);
    for (int s = ns; s < ns + 16; s++)
        g->lat[s] = 0;
    g->nslots = ns;
    g->stride = ns + 16;
    free(list);
    table_init(g);
    g->folded = g->corner != NULL;
    if (g->folded)
        g->wide = 1; /* row_lut_avx512: sixteen columns too */
    if (g->fy < 1)
        cache_init(g);
    return 0;
}

/* Lattice row j folded over the slice's corners, for slots s0..s1-1: with
 * m_c = W_c (1, 1, dz_c, dw_c) and a = sum_c G_c * m_c (component-wise,
 * corners in order, float),
 *   X = a.x,  Y = a.y,  C = a.z + a.w,
 * so that a pixel row between lattice rows j and j+1 needs two such rows.
 * Element-wise float operations: the SSE form below gives the same bits. */
static inline __attribute__((always_inline)) void
lattice_row_n(const tex_noise_grid *g, const float (*zm)[4], const int *A, const int32_t *lat,
              int s0, int s1, float *X, float *Y, float *C, const int nz)
{
    const int *F = g->t->perm;
    const float(*G)[4] = g->dims == 4 ? g->t->grad4 : g->t->grad;
    int s = s0;

#ifdef TEX_X86
    __m128 m[4];
    for (int c = 0; c < nz; c++)
        m[c] = _mm_loadu_ps(zm[c]);
    for (; s + 4 <= s1; s += 4) {
        __m128 a[4];
        for (int k = 0; k < 4; k++) {
            int i = lat[s + k];
            a[k] = _mm_setzero_ps();
            for (int c = 0; c < nz; c++)
                a[k] = _mm_add_ps(a[k], _mm_mul_ps(_mm_loadu_ps(G[F[i + A[c]]]), m[c]));
        }
        _MM_TRANSPOSE4_PS(a[0], a[1], a[2], a[3]);
        _mm_storeu_ps(X + s - s0, a[0]);
        _mm_storeu_ps(Y + s - s0, a[1]);
        _mm_storeu_ps(C + s - s0, _mm_add_ps(a[2], a[3]));
    }
#endif
    for (; s < s1; s++) {
        int i = lat[s];
        float a[4] = {0, 0, 0, 0};
        for (int c = 0; c < nz; c++)
            for (int k = 0; k < 4; k++)
                a[k] = a[k] + G[F[i + A[c]]][k] * zm[c][k];
        X[s - s0] = a[0];
        Y[s - s0] = a[1];
        C[s - s0] = a[2] + a[3];
    }
}

/* zm: the slice's weights, g->zm (noise) or g->zdm (its z derivative); lj the
 * lattice row reduced (lat_index), lat the slots' lattice columns. */
static void lattice_row_at(const tex_noise_grid *g, const float (*zm)[4], int lj,
                           const int32_t *lat, int s0, int s1, float *X, float *Y, float *C)
{
    const int *F = g->t->perm;
    int A[4];

    for (int c = 0; c < g->nz; c++)
        A[c] = F[lj + g->zh[c]];
    /* One copy per number of corners, so that the sums stay in registers. */
    switch (g->nz) {
    case 1:
        lattice_row_n(g, zm, A, lat, s0, s1, X, Y, C, 1);
        break;
    case 2:
        lattice_row_n(g, zm, A, lat, s0, s1, X, Y, C, 2);
        break;
    case 3:
        lattice_row_n(g, zm, A, lat, s0, s1, X, Y, C, 3);
        break;
    default:
        lattice_row_n(g, zm, A, lat, s0, s1, X, Y, C, 4);
        break;
    }
}

static void lattice_row_m(const tex_noise_grid *g, const float (*zm)[4], int64_t j, int s0, int s1,
                          float *X, float *Y, float *C)
{
    lattice_row_at(g, zm, lat_index(j, g->period, g->t->n), g->lat, s0, s1, X, Y, C);
}

/* Every column's right corner the table's next entry (entry n being entry 0). */
static int corners_adjacent(const tex_noise_grid *g)
{
    for (int x = 0; x < g->w; x++) {
        const int32_t *l = g->lat + g->slot[x];
        if (l[1] != l[0] + 1 && !(l[0] == g->t->n - 1 && l[1] == 0))
            return 0;
    }
    return 1;
}

/* The table of every lattice point's folded (X, Y, C), computed as lattice_row
 * does: the same operations, so the same bits.  For a folded grid (fold) as
 * planes of ps entries, a multiple of sixteen from n + 32 on, entry i being
 * lattice column i mod n: the vector folds need no tail, and planar rows read
 * up to 32 entries from a column's. */
static int lut_init(tex_noise_grid *g, int fold)
{
    int n = g->t->n, ps = (n + 32 + 15) & ~15;
    int32_t *id = malloc((ps + 16) * sizeof *id);
    float *r = malloc(3 * (size_t)ps * sizeof *r);

    if (fold)
        g->plane = malloc((size_t)n * 3 * ps * sizeof *g->plane);
    else
        g->lut = malloc((size_t)n * (n + 1) * sizeof *g->lut);
    if (!id || !r || (!g->plane && !g->lut)) {
        free(id);
        free(r);
        free(g->plane);
        free(g->lut);
        g->plane = NULL;
        g->lut = NULL;
        return -1;
    }
    g->ps = ps;
    for (int i = 0; i < ps + 16; i++)
        id[i] = i % n;
    for (int lj = 0; lj < n; lj++) {
        float *X = fold ? g->plane + (size_t)lj * 3 * ps : r;
        lattice_row_at(g, (const float(*)[4])g->zm, lj, id, 0, fold ? ps : n + 1, X, X + ps,
                       X + 2 * ps);
        if (fold)
            continue;
        float(*T)[4] = g->lut + (size_t)lj * (n + 1);
        for (int i = 0; i <= n; i++) {
            T[i][0] = r[i];
            T[i][1] = r[ps + i];
            T[i][2] = r[2 * ps + i];
            T[i][3] = 0;
        }
    }
    free(id);
    free(r);
    return 0;
}

/* The table's row for lattice row j. */
static inline const float (*lut_row(const tex_noise_grid *g, int64_t j))[4]
{
    int n = g->t->n;
    return (const float(*)[4])g->lut + (size_t)lat_index(j, g->period, n) * (n + 1);
}

/* A folded grid's table planes for lattice row j: X, then Y and C ps floats on */
static inline const float *plane_row(const tex_noise_grid *g, int64_t j)
{
    return g->plane + (size_t)lat_index(j, g->period, g->t->n) * 3 * g->ps;
}

static void lattice_row(const tex_noise_grid *g, int64_t j, int s0, int s1, float *X, float *Y,
                        float *C)
{
    const int32_t *lat = g->lat;
    const float(*T)[4];
    int s = s0;

    if (g->plane) {
        const float *TX = plane_row(g, j), *TY = TX + g->ps, *TC = TY + g->ps;
        for (; s < s1; s++) {
            X[s - s0] = TX[lat[s]];
            Y[s - s0] = TY[lat[s]];
            C[s - s0] = TC[lat[s]];
        }
        return;
    }
    if (!g->lut) {
        lattice_row_m(g, (const float(*)[4])g->zm, j, s0, s1, X, Y, C);
        return;
    }
    T = lut_row(g, j);
#ifdef TEX_X86
    for (; s + 4 <= s1; s += 4) {
        __m128 a0 = _mm_loadu_ps(T[lat[s]]), a1 = _mm_loadu_ps(T[lat[s + 1]]);
        __m128 a2 = _mm_loadu_ps(T[lat[s + 2]]), a3 = _mm_loadu_ps(T[lat[s + 3]]);
        _MM_TRANSPOSE4_PS(a0, a1, a2, a3);
        _mm_storeu_ps(X + s - s0, a0);
        _mm_storeu_ps(Y + s - s0, a1);
        _mm_storeu_ps(C + s - s0, a2);
    }
#endif
    for (; s < s1; s++) {
        X[s - s0] = T[lat[s]][0];
        Y[s - s0] = T[lat[s]][1];
        C[s - s0] = T[lat[s]][2];
    }
}

static struct cache_entry *cache_take(const tex_noise_grid *g)
{
    struct tex_noise_cache *c = g->cache;
    int start = 0;

    if (!c)
        return NULL;
#ifdef _OPENMP
    start = omp_get_thread_num();
#endif
    for (int k = 0; k < c->n; k++) {
        struct cache_entry *e = &c->e[(start + k) % c->n];
        int free_ = 0;
        if (__atomic_compare_exchange_n(&e->busy, &free_, 1, 0, __ATOMIC_ACQUIRE,
                                        __ATOMIC_RELAXED))
            return e;
    }
    return NULL;
}

static int cache_find(const struct cache_entry *e, int64_t j)
{
    for (int b = 0; b < 2; b++)
        if (e->valid[b] && e->key[b] == j)
            return b;
    return -1;
}

/* Lattice row j into buffer b of the entry. */
static void cache_fill(const tex_noise_grid *g, struct cache_entry *e, int b, int64_t j)
{
    float *r = e->buf[b];

    lattice_row(g, j, 0, g->nslots, r, r + g->stride, r + 2 * g->stride);
    e->key[b] = j;
    e->valid[b] = 1;
}

/* The entry's buffers holding lattice rows j and (if two) j + 1, computed
 * where missing without evicting the other. */
static void cache_rows(const tex_noise_grid *g, struct cache_entry *e, int64_t j, int two,
                       const float **r0, const float **r1)
{
    int b0 = cache_find(e, j), b1 = two ? cache_find(e, j + 1) : -1;

    if (b0 < 0)
        cache_fill(g, e, b0 = b1 == 0 ? 1 : 0, j);
    if (two && b1 < 0)
        cache_fill(g, e, b1 = 1 - b0, j + 1);
    *r0 = e->buf[b0];
    *r1 = two ? e->buf[b1] : NULL;
}

/* The two coefficients of each slot for the row (P[0] is slot s0's):
 * a pixel's noise is
 *   w0(u) (P[s] u + Q[s]) + w1(u) (P[s+1] (u-1) + Q[s+1]),  s = slot[x],
 * from the two lattice rows (X, Y, C; the second NULL when its weight is 0)
 * and the row's weights wy and offsets dy.  Shared by every SIMD level. */
static void row_coeffs(int ns, const float *wy, const float *dy, const float *const L0[3],
                       const float *const L1[3], float *P, float *Q)
{
    if (L1)
        for (int s = 0; s < ns; s++) {
            P[s] = wy[0] * L0[0][s] + wy[1] * L1[0][s];
            Q[s] = wy[0] * (L0[1][s] * dy[0] + L0[2][s]) + wy[1] * (L1[1][s] * dy[1] + L1[2][s]);
        }
    else
        for (int s = 0; s < ns; s++) {
            P[s] = wy[0] * L0[0][s];
            Q[s] = wy[0] * (L0[1][s] * dy[0] + L0[2][s]);
        }
    for (int s = ns; s < ns + 16; s++)
        P[s] = Q[s] = 0;
}

#ifdef TEX_X86
/* row_coeffs eight slots at a time: the same operations, element by element. */
TEX_AVX2 static inline void
row_coeffs_avx2(int ns, const float *wy, const float *dy, const float *const L0[3],
                const float *const L1[3], float *P, float *Q)
{
    __m256 a0 = _mm256_set1_ps(wy[0]), a1 = _mm256_set1_ps(wy[1]);
    __m256 d0 = _mm256_set1_ps(dy[0]), d1 = _mm256_set1_ps(dy[1]), z = _mm256_setzero_ps();
    int s = 0;

    if (L1)
        for (; s + 8 <= ns; s += 8) {
            __m256 p = _mm256_add_ps(_mm256_mul_ps(a0, _mm256_loadu_ps(L0[0] + s)),
                                     _mm256_mul_ps(a1, _mm256_loadu_ps(L1[0] + s)));
            __m256 q0 = _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(L0[1] + s), d0),
                                      _mm256_loadu_ps(L0[2] + s));
            __m256 q1 = _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(L1[1] + s), d1),
                                      _mm256_loadu_ps(L1[2] + s));
            _mm256_storeu_ps(P + s, p);
            _mm256_storeu_ps(Q + s, _mm256_add_ps(_mm256_mul_ps(a0, q0), _mm256_mul_ps(a1, q1)));
        }
    else
        for (; s + 8 <= ns; s += 8) {
            __m256 q0 = _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(L0[1] + s), d0),
                                      _mm256_loadu_ps(L0[2] + s));
            _mm256_storeu_ps(P + s, _mm256_mul_ps(a0, _mm256_loadu_ps(L0[0] + s)));
            _mm256_storeu_ps(Q + s, _mm256_mul_ps(a0, q0));
        }
    for (; s < ns; s++) {
        if (L1) {
            P[s] = wy[0] * L0[0][s] + wy[1] * L1[0][s];
            Q[s] = wy[0] * (L0[1][s] * dy[0] + L0[2][s]) + wy[1] * (L1[1][s] * dy[1] + L1[2][s]);
        } else {
            P[s] = wy[0] * L0[0][s];
            Q[s] = wy[0] * (L0[1][s] * dy[0] + L0[2][s]);
        }
    }
    _mm256_storeu_ps(P + ns, z);
    _mm256_storeu_ps(P + ns + 8, z);
    _mm256_storeu_ps(Q + ns, z);
    _mm256_storeu_ps(Q + ns + 8, z);
}
#endif

/* [0,1] clamps written as max then min, the order of the vector instructions
 * (the same result for -0 and NaN). */
static inline float clamp01(float x)
{
    float m = x > 0 ? x : 0;
    return m < 1 ? m : 1;
}

/* Pixel row y's place between lattice rows j and j + 1: their weights wy and offsets dy
 * (two: j + 1's weight is not 0) */
struct yrow {
    int64_t j;
    float wy[2], dy[2];
    int two;
};

static void yrow_at(const tex_noise_grid *g, int y, struct yrow *r)
{
    double Y = g->oy + g->fy * (y + 0.5), cy = floor(Y), fr = Y - cy;
    r->j = tex_noise_cell(cy);
    r->wy[0] = (float)fade(g->t->fade, fr);
    r->wy[1] = (float)fade(g->t->fade, 1.0 - fr);
    r->dy[0] = (float)fr;
    r->dy[1] = (float)(fr - 1.0);
    r->two = r->wy[1] != 0;
}

/* The pixel rows a kernel makes at once (1 or FOLD_ROWS: each column's data, read from
 * beyond the first-level cache in an octave sum, serves them all), row r's coefficients
 * from C[r] into out[r]: a folded grid's planar (Q ps floats after P) or interleaved, a
 * slot row's P and Q ROW_NS floats after it (ROW_CHUNK columns touch at most ROW_NS - 24
 * slots).  The kernels' loops over rows are unrolled ("GCC unroll 2"): GCC kept them
 * rolled around a kernel's branches, each row's noise through the stack, and unrolled the
 * sums run 3-13 % faster from 4 to 64 cells, and at AVX2 6-14 % at every frequency. */
#define FOLD_ROWS 2
#define ROW_CHUNK 1024
#define ROW_NS (2 * ROW_CHUNK + 24)
struct rowset {
    const float *C[FOLD_ROWS];
    float *out[FOLD_ROWS];
};

/* A row operation's constants (tex_noise_grid_row_op's a, b and c; the multifractal
 * finish's lo and inv), and where the multifractal operations keep their state: a sum at
 * o has its state sdelta bytes on (state_at), an address the kernels' loops form from
 * the sum's with one addition they can hoist, where st0 + (o - out0) took three in each */
struct row_k {
    float a, b, c, lo, inv;
    uintptr_t sdelta;
};

static inline float *state_at(const float *o, struct row_k rk)
{
    return (float *)((uintptr_t)o + rk.sdelta);
}

/* What a row does with each noise value r (tex_noise_grid_row_op), at o. */
static inline void apply_op(int op, float r, float *o, struct row_k rk)
{
    float s, w, *st = op >= TEX_ROW_RIDGED_FIRST ? state_at(o, rk) : NULL;

    switch (op) {
    case TEX_ROW_SET:
        *o = r;
        break;
    case TEX_ROW_MUL:
        *o = rk.a * r;
        break;
    case TEX_ROW_MUL_ABS:
        *o = rk.a * fabsf(r);
        break;
    case TEX_ROW_UNIT:
        *o = clamp01(0.5f + 0.5f * r);
        break;
    case TEX_ROW_ADD:
        *o = *o + rk.a * r;
        break;
    case TEX_ROW_ADD_ABS:
        *o = *o + rk.a * fabsf(r);
        break;
    case TEX_ROW_ADD_UNIT:
        *o = clamp01(0.5f + 0.5f * ((*o + rk.a * r) * rk.b));
        break;
    case TEX_ROW_ADD_ABS_CLAMP:
        *o = clamp01((*o + rk.a * fabsf(r)) * rk.b);
        break;
    case TEX_ROW_RIDGED_FIRST:
        s = rk.b - fabsf(r);
        *o = *st = s * s;
        break;
    case TEX_ROW_RIDGED:
    case TEX_ROW_RIDGED_LAST:
        s = rk.b - fabsf(r);
        w = *st * rk.c; /* the weight clamp01(st c): st c >= 0 */
        s = (w < 1 ? w : 1) * (s * s);
        *o = *o + s * rk.a;
        break;
    case TEX_ROW_HYBRID_FIRST:
        *o = *st = (r + rk.b) * rk.a;
        break;
    default: /* TEX_ROW_HYBRID, TEX_ROW_HYBRID_LAST */
        s = (*st < 1 ? *st : 1) * ((r + rk.b) * rk.a);
        *o = *o + s;
        break;
    }
    if (op == TEX_ROW_RIDGED || op == TEX_ROW_HYBRID)
        *st = s;
    else if (op == TEX_ROW_RIDGED_LAST || op == TEX_ROW_HYBRID_LAST)
        *o = clamp01((*o - rk.lo) * rk.inv);
}

/* Pixels x..x1-1 of the rows, the reference order of operations for every level; the
 * coefficients hold the slots from sb on. */
static inline __attribute__((always_inline)) void
row_scalar_op(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1, const int rows,
              const int op, struct row_k rk)
{
    const int32_t *restrict slot = g->slot;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;

    for (; x < x1; x++)
        for (int r = 0; r < rows; r++) {
            const float *P = rs.C[r], *Q = P + ROW_NS;
            int s = slot[x] - sb;
            float t0 = P[s] * u[x] + Q[s];
            float t1 = P[s + 1] * um1[x] + Q[s + 1];
            apply_op(op, w0[x] * t0 + w1[x] * t1, rs.out[r] + x, rk);
        }
}

/* One copy of the row loop FN per operation, the operation op folded in as a
 * constant: FN(PRE..., op, POST...), PRE and POST parenthesised argument lists.  A
 * sanitizer build (TEX_SANITIZE) keeps one copy that takes op as it comes: the same
 * statements, checked the same, where 28 instrumented copies took gcc three minutes. */
#define ARGS(...) __VA_ARGS__
#ifdef TEX_SANITIZE
#define ROW_OP_SWITCH(FN, PRE, POST) FN(ARGS PRE, op, ARGS POST)
#else
#define ROW_OP_SWITCH(FN, PRE, POST)                                                               \
    switch (op) {                                                                                  \
    case TEX_ROW_SET: FN(ARGS PRE, TEX_ROW_SET, ARGS POST); break;                                 \
    case TEX_ROW_MUL: FN(ARGS PRE, TEX_ROW_MUL, ARGS POST); break;                                 \
    case TEX_ROW_MUL_ABS: FN(ARGS PRE, TEX_ROW_MUL_ABS, ARGS POST); break;                         \
    case TEX_ROW_UNIT: FN(ARGS PRE, TEX_ROW_UNIT, ARGS POST); break;                               \
    case TEX_ROW_ADD: FN(ARGS PRE, TEX_ROW_ADD, ARGS POST); break;                                 \
    case TEX_ROW_ADD_ABS: FN(ARGS PRE, TEX_ROW_ADD_ABS, ARGS POST); break;                         \
    case TEX_ROW_ADD_UNIT: FN(ARGS PRE, TEX_ROW_ADD_UNIT, ARGS POST); break;                       \
    case TEX_ROW_ADD_ABS_CLAMP: FN(ARGS PRE, TEX_ROW_ADD_ABS_CLAMP, ARGS POST); break;             \
    case TEX_ROW_RIDGED_FIRST: FN(ARGS PRE, TEX_ROW_RIDGED_FIRST, ARGS POST); break;               \
    case TEX_ROW_RIDGED: FN(ARGS PRE, TEX_ROW_RIDGED, ARGS POST); break;                           \
    case TEX_ROW_RIDGED_LAST: FN(ARGS PRE, TEX_ROW_RIDGED_LAST, ARGS POST); break;                 \
    case TEX_ROW_HYBRID_FIRST: FN(ARGS PRE, TEX_ROW_HYBRID_FIRST, ARGS POST); break;               \
    case TEX_ROW_HYBRID: FN(ARGS PRE, TEX_ROW_HYBRID, ARGS POST); break;                           \
    default: FN(ARGS PRE, TEX_ROW_HYBRID_LAST, ARGS POST); break;                                  \
    }
#endif
/* A kernel FN(PRE..., rows, op, rk) for the rows at hand, one or two */
#define ROWS_SWITCH(FN, PRE)                                                                 \
    if (rows == 2) {                                                                         \
        ROW_OP_SWITCH(FN, (ARGS PRE, 2), (rk));                                              \
    } else {                                                                                 \
        ROW_OP_SWITCH(FN, (ARGS PRE, 1), (rk));                                              \
    }
/* the slot rows' own parameters */
#define ROW_PRE (g, rs, sb, x, x1)

static void row_scalar(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1,
                       int rows, int op, struct row_k rk)
{
    ROWS_SWITCH(row_scalar_op, ROW_PRE);
}

#ifdef TEX_X86
/* apply_op on W = |V| / 4 pixels at x of each of the rows at out, their noise r[i], for the
 * vector type V (AVX2's and AVX-512's), whose operators are their lanes' (MIN, MAX, ABS: its
 * intrinsics; clamps max, then min).  The multifractal operations load every row's sum and
 * state before any row's stores: from 256 cells 4-15 % faster than row by row.  The others
 * go row by row (step 1) where ROWWISE: at AVX-512 fBm and turbulence run 3-9 % faster so,
 * at AVX2 three times slower. */
#define APPLY_FN(ATTR, NAME, V, MIN, MAX, ABS, ROWWISE)                                       \
    ATTR static inline __attribute__((always_inline)) void NAME(                              \
        const int op, const V *r, float *const *out, int x, const int rows, struct row_k rk)  \
    {                                                                                         \
        const V zero = {0}, one = zero + 1.0f;                                                \
        const int first = op == TEX_ROW_RIDGED_FIRST || op == TEX_ROW_HYBRID_FIRST;           \
        const int last = op == TEX_ROW_RIDGED_LAST || op == TEX_ROW_HYBRID_LAST;              \
        float *sp[FOLD_ROWS]; /* the multifractal state */                                    \
        V v[FOLD_ROWS], s[FOLD_ROWS], st[FOLD_ROWS];                                          \
        const int step = ROWWISE && op < TEX_ROW_RIDGED_FIRST ? 1 : rows;                     \
        for (int i0 = 0; i0 < rows; i0 += step) {                                             \
            _Pragma("GCC unroll 2") for (int i = i0; i < i0 + step; i++) {                    \
                sp[i] = state_at(out[i] + x, rk);                                             \
                if (op >= TEX_ROW_ADD && !first)                                              \
                    memcpy(&v[i], out[i] + x, sizeof v[i]);                                   \
                if (op >= TEX_ROW_RIDGED_FIRST && !first)                                     \
                    memcpy(&st[i], sp[i], sizeof st[i]);                                      \
            }                                                                                 \
            _Pragma("GCC unroll 2") for (int i = i0; i < i0 + step; i++) {                    \
                switch (op) {                                                                 \
                case TEX_ROW_SET: v[i] = r[i]; break;                                         \
                case TEX_ROW_MUL: v[i] = rk.a * r[i]; break;                                  \
                case TEX_ROW_MUL_ABS: v[i] = rk.a * ABS(r[i]); break;                         \
                case TEX_ROW_UNIT: v[i] = MIN(MAX(0.5f + 0.5f * r[i], zero), one); break;     \
                case TEX_ROW_ADD: v[i] = v[i] + rk.a * r[i]; break;                           \
                case TEX_ROW_ADD_ABS: v[i] = v[i] + rk.a * ABS(r[i]); break;                  \
                case TEX_ROW_ADD_UNIT:                                                        \
                    v[i] = MIN(MAX(0.5f + 0.5f * ((v[i] + rk.a * r[i]) * rk.b), zero), one);  \
                    break;                                                                    \
                case TEX_ROW_ADD_ABS_CLAMP:                                                   \
                    v[i] = MIN(MAX((v[i] + rk.a * ABS(r[i])) * rk.b, zero), one);             \
                    break;                                                                    \
                case TEX_ROW_RIDGED_FIRST:                                                    \
                    s[i] = rk.b - ABS(r[i]);                                                  \
                    v[i] = s[i] = s[i] * s[i];                                                \
                    break;                                                                    \
                case TEX_ROW_RIDGED:                                                          \
                case TEX_ROW_RIDGED_LAST:                                                     \
                    s[i] = rk.b - ABS(r[i]);                                                  \
                    s[i] = MIN(st[i] * rk.c, one) * (s[i] * s[i]);                            \
                    v[i] = v[i] + s[i] * rk.a;                                                \
                    break;                                                                    \
                case TEX_ROW_HYBRID_FIRST: v[i] = s[i] = (r[i] + rk.b) * rk.a; break;         \
                default: /* TEX_ROW_HYBRID, TEX_ROW_HYBRID_LAST */                            \
                    s[i] = MIN(st[i], one) * ((r[i] + rk.b) * rk.a);                          \
                    v[i] = v[i] + s[i];                                                       \
                    break;                                                                    \
                }                                                                             \
                if (last)                                                                     \
                    v[i] = MIN(MAX((v[i] - rk.lo) * rk.inv, zero), one);                      \
            }                                                                                 \
            _Pragma("GCC unroll 2") for (int i = i0; i < i0 + step; i++) {                    \
                memcpy(out[i] + x, &v[i], sizeof v[i]);                                       \
                if (op >= TEX_ROW_RIDGED_FIRST && !last)                                      \
                    memcpy(sp[i], &s[i], sizeof s[i]);                                        \
            }                                                                                 \
        }                                                                                     \
    }
TEX_AVX2 static inline __attribute__((always_inline)) __m256 abs_avx2(__m256 v)
{
    return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v);
}
APPLY_FN(TEX_AVX2, apply_avx2, __m256, _mm256_min_ps, _mm256_max_ps, abs_avx2, 0)

/* Eight pixels' noise from their slots' coefficients, row_scalar_op's formula
 *   w0 (p0 u + q0) + w1 (p1 (u - 1) + q1) */
TEX_AVX2 static inline __attribute__((always_inline)) __m256
pixels8(const float *restrict u, const float *restrict um1, const float *restrict w0,
        const float *restrict w1, __m256 p0, __m256 p1, __m256 q0, __m256 q1)
{
    __m256 t0 = _mm256_add_ps(_mm256_mul_ps(p0, _mm256_loadu_ps(u)), q0);
    __m256 t1 = _mm256_add_ps(_mm256_mul_ps(p1, _mm256_loadu_ps(um1)), q1);
    return _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(w0), t0),
                         _mm256_mul_ps(_mm256_loadu_ps(w1), t1));
}

/* Eight pixels' slot values: a0 = V[s], a1 = V[s + 1] for their slots s
 * (k = s - s0, relative to the first pixel's slot s0; span = the last's k). */
TEX_AVX2 static inline __attribute__((always_inline)) void
expand(const float *V, int s0, __m256i s, __m256i k, int span, __m256 *a0, __m256 *a1)
{
    if (span <= 1) {
        /* Within two cells: broadcasts and a blend (cheaper than permutes). */
        __m256 m = _mm256_castsi256_ps(_mm256_slli_epi32(k, 31));
        *a0 = _mm256_blendv_ps(_mm256_broadcast_ss(V + s0), _mm256_broadcast_ss(V + s0 + 1), m);
        *a1 = _mm256_blendv_ps(_mm256_broadcast_ss(V + s0 + 1), _mm256_broadcast_ss(V + s0 + 2), m);
    } else if (span <= 7) {
        /* The eight pixels touch at most nine slots: permute, no gather. */
        *a0 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(V + s0), k);
        *a1 = _mm256_permutevar8x32_ps(_mm256_loadu_ps(V + s0 + 1), k);
    } else {
        *a0 = _mm256_i32gather_ps(V, s, 4);
        *a1 = _mm256_i32gather_ps(V + 1, s, 4);
    }
}

TEX_AVX2 static inline __attribute__((always_inline)) void
row_avx2_op(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1, const int rows,
            const int op, struct row_k rk)
{
    /* Locals, so that the stores to out do not reload the tables. */
    const int32_t *restrict slot = g->slot;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;
    __m256i vsb = _mm256_set1_epi32(sb);

    for (; x + 8 <= x1; x += 8) {
        __m256i s = _mm256_sub_epi32(_mm256_loadu_si256((const __m256i *)(slot + x)), vsb);
        int s0 = slot[x] - sb, span = slot[x + 7] - sb - s0;
        __m256i k = _mm256_sub_epi32(s, _mm256_set1_epi32(s0));
        __m256 v[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            __m256 p0, p1, q0, q1;
            expand(rs.C[r], s0, s, k, span, &p0, &p1);
            expand(rs.C[r] + ROW_NS, s0, s, k, span, &q0, &q1);
            v[r] = pixels8(u + x, um1 + x, w0 + x, w1 + x, p0, p1, q0, q1);
        }
        apply_avx2(op, v, rs.out, x, rows, rk);
    }
    row_scalar_op(g, rs, sb, x, x1, rows, op, rk);
}

/* Eight columns' slot values when each column has its own pair (g->paired):
 * V[s], V[s + 1] are V's even and odd entries from s, unzipped. */
TEX_AVX2 static inline __attribute__((always_inline)) void unzip(const float *V, __m256 *a0,
                                                             __m256 *a1)
{
    __m256 lo = _mm256_loadu_ps(V), hi = _mm256_loadu_ps(V + 8);
    __m256 e = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0));
    __m256 o = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1));
    *a0 = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(e), _MM_SHUFFLE(3, 1, 2, 0)));
    *a1 = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(o), _MM_SHUFFLE(3, 1, 2, 0)));
}

/* row_avx2_op for paired slots: the same operations without gathers. */
TEX_AVX2 static inline __attribute__((always_inline)) void
row_avx2_paired_op(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1,
                   const int rows, const int op, struct row_k rk)
{
    const int32_t *restrict slot = g->slot;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;

    for (; x + 8 <= x1; x += 8) {
        int s = slot[x] - sb;
        __m256 v[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            __m256 p0, p1, q0, q1;
            unzip(rs.C[r] + s, &p0, &p1);
            unzip(rs.C[r] + ROW_NS + s, &q0, &q1);
            v[r] = pixels8(u + x, um1 + x, w0 + x, w1 + x, p0, p1, q0, q1);
        }
        apply_avx2(op, v, rs.out, x, rows, rk);
    }
    row_scalar_op(g, rs, sb, x, x1, rows, op, rk);
}

/* A lattice row's folded (X, Y, C) at eight columns' left and right corners,
 * from the table row T: each column's two entries loaded as one vector and
 * the eight transposed. */
TEX_AVX2 static inline __attribute__((always_inline)) __m256 lut_pair(const float (*T)[4],
                                                                  const int32_t *lat, const int adj)
{
    if (adj) /* one load: the right corner is the next entry */
        return _mm256_loadu_ps(T[lat[0]]);
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(T[lat[0]])),
                                _mm_loadu_ps(T[lat[1]]), 1);
}

TEX_AVX2 static inline __attribute__((always_inline)) void
lut_load8(const float (*T)[4], const int32_t *lat, __m256 v[6], const int adj)
{
    __m256 a = lut_pair(T, lat, adj), b = lut_pair(T, lat + 2, adj);
    __m256 t0 = _mm256_unpacklo_ps(a, b), t1 = _mm256_unpackhi_ps(a, b); /* X0 X1 Y0 Y1, C0 C1 0 0 */
    a = lut_pair(T, lat + 4, adj), b = lut_pair(T, lat + 6, adj);
    __m256 t2 = _mm256_unpacklo_ps(a, b), t3 = _mm256_unpackhi_ps(a, b);
    __m256 x03 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
    __m256 y03 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 c03 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
    a = lut_pair(T, lat + 8, adj), b = lut_pair(T, lat + 10, adj);
    t0 = _mm256_unpacklo_ps(a, b), t1 = _mm256_unpackhi_ps(a, b);
    a = lut_pair(T, lat + 12, adj), b = lut_pair(T, lat + 14, adj);
    t2 = _mm256_unpacklo_ps(a, b), t3 = _mm256_unpackhi_ps(a, b);
    __m256 x47 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
    __m256 y47 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
    __m256 c47 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
    v[0] = _mm256_permute2f128_ps(x03, x47, 0x20);
    v[1] = _mm256_permute2f128_ps(y03, y47, 0x20);
    v[2] = _mm256_permute2f128_ps(c03, c47, 0x20);
    v[3] = _mm256_permute2f128_ps(x03, x47, 0x31);
    v[4] = _mm256_permute2f128_ps(y03, y47, 0x31);
    v[5] = _mm256_permute2f128_ps(c03, c47, 0x31);
}

/* A row of a paired grid with a table, in one pass: per column the
 * operations of row_coeffs then row_scalar_op, in their order. */
TEX_AVX2 static inline __attribute__((always_inline)) void
row_lut_avx2_op(const tex_noise_grid *g, const float (*T0)[4], const float (*T1)[4],
                const float *wy, const float *dy, float *out, const int op, const int adj,
                struct row_k rk)
{
    const int32_t *restrict lat = g->lat;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;
    __m256 a0 = _mm256_set1_ps(wy[0]), a1 = _mm256_set1_ps(wy[1]);
    __m256 d0 = _mm256_set1_ps(dy[0]), d1 = _mm256_set1_ps(dy[1]);
    int x = 0;

    for (; x + 8 <= g->w; x += 8) {
        __m256 l[6], P[2], Q[2];
        /* row j's products first, row j + 1's added: row_coeffs' operations */
        lut_load8(T0, lat + 2 * x, l, adj);
        for (int c = 0; c < 2; c++) {
            P[c] = _mm256_mul_ps(a0, l[3 * c]);
            Q[c] = _mm256_mul_ps(a0, _mm256_add_ps(_mm256_mul_ps(l[3 * c + 1], d0), l[3 * c + 2]));
        }
        if (T1) {
            lut_load8(T1, lat + 2 * x, l, adj);
            for (int c = 0; c < 2; c++) {
                P[c] = _mm256_add_ps(P[c], _mm256_mul_ps(a1, l[3 * c]));
                Q[c] = _mm256_add_ps(
                    Q[c], _mm256_mul_ps(a1, _mm256_add_ps(_mm256_mul_ps(l[3 * c + 1], d1),
                                                          l[3 * c + 2])));
            }
        }
        __m256 v = pixels8(u + x, um1 + x, w0 + x, w1 + x, P[0], P[1], Q[0], Q[1]);
        apply_avx2(op, &v, &out, x, 1, rk);
    }
    for (; x < g->w; x++) {
        float P[2], Q[2];
        for (int c = 0; c < 2; c++) {
            const float *e0 = T0[lat[2 * x + c]], *e1 = T1 ? T1[lat[2 * x + c]] : NULL;
            if (e1) {
                P[c] = wy[0] * e0[0] + wy[1] * e1[0];
                Q[c] = wy[0] * (e0[1] * dy[0] + e0[2]) + wy[1] * (e1[1] * dy[1] + e1[2]);
            } else {
                P[c] = wy[0] * e0[0];
                Q[c] = wy[0] * (e0[1] * dy[0] + e0[2]);
            }
        }
        float t0 = P[0] * u[x] + Q[0], t1 = P[1] * um1[x] + Q[1];
        apply_op(op, w0[x] * t0 + w1[x] * t1, out + x, rk);
    }
}

/* What a pixel row folds: its two lattice rows' table planes and their weights (yrow's) */
struct fold_src {
    const float *T0, *T1; /* the table planes of lattice rows j and j + 1 (NULL: weight 0) */
    int ps;               /* the planes' length */
    float a0, a1, d0, d1;
};

static inline void fold_src_at(const tex_noise_grid *g, const struct yrow *yr, struct fold_src *f)
{
    f->T0 = plane_row(g, yr->j);
    f->T1 = yr->two ? plane_row(g, yr->j + 1) : NULL;
    f->ps = g->ps;
    f->a0 = yr->wy[0], f->a1 = yr->wy[1], f->d0 = yr->dy[0], f->d1 = yr->dy[1];
}

/* A pixel row's coefficients (P, Q) at every entry of a folded grid's table, into P and
 * Q = P + ps (NAME; NAME_at: entries i..i + W - 1's): the operations row_coeffs performs
 * per slot, done once per entry, W = |V| / 4 entries at a time (V: __m256 or __m512, whose
 * operators are their lanes').  The table's planes go on past entry n (entry i is lattice
 * column i mod n), so that planar rows read up to 32 entries from a column's. */
#define FOLD_ROW_FN(ATTR, NAME, V)                                                           \
    ATTR static inline __attribute__((always_inline)) void NAME##_at(                        \
        const struct fold_src *f, int i, V *p, V *q)                                         \
    {                                                                                        \
        const int ps = f->ps;                                                                \
        V x, y, c;                                                                           \
        memcpy(&x, f->T0 + i, sizeof x);                                                     \
        memcpy(&y, f->T0 + ps + i, sizeof y);                                                \
        memcpy(&c, f->T0 + 2 * ps + i, sizeof c);                                            \
        *p = f->a0 * x;                                                                      \
        *q = f->a0 * (y * f->d0 + c);                                                        \
        if (f->T1) {                                                                         \
            memcpy(&x, f->T1 + i, sizeof x);                                                 \
            memcpy(&y, f->T1 + ps + i, sizeof y);                                            \
            memcpy(&c, f->T1 + 2 * ps + i, sizeof c);                                        \
            *p = *p + f->a1 * x;                                                             \
            *q = *q + f->a1 * (y * f->d1 + c);                                               \
        }                                                                                    \
    }                                                                                        \
    ATTR static void NAME(const tex_noise_grid *g, const struct yrow *yr, float *P)          \
    {                                                                                        \
        enum { W = sizeof(V) / sizeof(float) };                                              \
        struct fold_src f;                                                                   \
        fold_src_at(g, yr, &f);                                                              \
        for (int i = 0; i < f.ps; i += W) {                                                  \
            V p, q;                                                                          \
            NAME##_at(&f, i, &p, &q);                                                        \
            memcpy(P + i, &p, sizeof p);                                                     \
            memcpy(P + f.ps + i, &q, sizeof q);                                              \
        }                                                                                    \
    }
FOLD_ROW_FN(TEX_AVX2, fold_row_avx2, __m256)

/* Folded coefficients: planar P and Q, and interleaved (P, Q) pairs; two rows' interleaved
 * (P0, Q0, P1, Q1) entries, up to n + 15 (fold2_avx512; tables of over 1024 are not folded) */
#define FOLD_FLOATS (4 * (1024 + 32))
#define FOLD2_FLOATS (4 * (1024 + 16))

/* Planar coefficients (fold_row_*) interleaved into PQ, entries 0..n, for the rows whose
 * columns' corners lie too far apart for permutes (row_folded_*) */
TEX_AVX2 static void interleave(const tex_noise_grid *g, const float *P, float *PQ)
{
    const float *Q = P + g->ps;
    for (int i = 0; i <= g->t->n; i += 8) {
        __m256 p = _mm256_loadu_ps(P + i), q = _mm256_loadu_ps(Q + i);
        __m256 lo = _mm256_unpacklo_ps(p, q), hi = _mm256_unpackhi_ps(p, q);
        _mm256_storeu_ps(PQ + 2 * i, _mm256_permute2f128_ps(lo, hi, 0x20));
        _mm256_storeu_ps(PQ + 2 * i + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
    }
}

/* Entry i of folded coefficients PQ, its (P, Q) pair: addressed as the i-th 8-byte unit, so
 * that a load takes the index as it is (scaled by the address, not by arithmetic first) */
#define PQ_AT(PQ, i) ((const float *)((const double *)(PQ) + (i)))

/* A folded grid's rows from interleaved coefficients: a column's (P, Q) pairs for its two
 * corners are the four floats at its left entry. */
TEX_AVX2 static inline __attribute__((always_inline)) void
row_folded_avx2_op(const tex_noise_grid *g, struct rowset fr, int x, const int rows, const int op,
                   struct row_k rk)
{
    const int32_t *restrict corner = g->corner;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;

    for (; x + 8 <= g->w; x += 8) {
        __m256 v[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            const float *row[8];
            __m256 c[4]; /* the left corners' P, Q, the right corners' P, Q */
#pragma GCC unroll 8
            for (int i = 0; i < 8; i++)
                row[i] = PQ_AT(fr.C[r], corner[x + i]);
            columns8(row, c);
            v[r] = pixels8(u + x, um1 + x, w0 + x, w1 + x, c[0], c[2], c[1], c[3]);
        }
        apply_avx2(op, v, fr.out, x, rows, rk);
    }
    for (; x < g->w; x++)
        for (int r = 0; r < rows; r++) {
            const float *e = fr.C[r] + 2 * corner[x];
            float t0 = e[0] * u[x] + e[1], t1 = e[2] * um1[x] + e[3];
            apply_op(op, w0[x] * t0 + w1[x] * t1, fr.out[r] + x, rk);
        }
}

/* Columns x.. of folded rows from planar coefficients: row_planar_*'s order of operations */
static inline __attribute__((always_inline)) void
row_planar_tail(const tex_noise_grid *g, struct rowset fr, int x, const int rows, const int op,
                struct row_k rk)
{
    for (; x < g->w; x++)
        for (int r = 0; r < rows; r++) {
            const float *P = fr.C[r], *Q = P + g->ps;
            int c = g->corner[x];
            float t0 = P[c] * g->u[x] + Q[c], t1 = P[c + 1] * g->um1[x] + Q[c + 1];
            apply_op(op, g->w0[x] * t0 + g->w1[x] * t1, fr.out[r] + x, rk);
        }
}

/* A folded grid's rows from planar coefficients (fold_row_*, Q ps floats after P) where
 * eight columns' corners lie within eight entries of the first's (g->span8 <= 7: cells of
 * about a pixel or more), so that the slot rows' expand serves, with offsets taken mod n. */
TEX_AVX2 static inline __attribute__((always_inline)) void
row_planar_avx2_op(const tex_noise_grid *g, struct rowset fr, const int rows, const int op,
                   struct row_k rk)
{
    const int32_t *restrict corner = g->corner;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;
    __m256i vn = _mm256_set1_epi32(g->t->n);
    int x = 0;

    for (; x + 8 <= g->w; x += 8) {
        int c0 = corner[x];
        __m256i d = _mm256_sub_epi32(_mm256_loadu_si256((const __m256i *)(corner + x)),
                                     _mm256_set1_epi32(c0));
        __m256i k = _mm256_min_epu32(d, _mm256_add_epi32(d, vn)); /* d mod n, for d > -n */
        __m256 v[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            __m256 p0, p1, q0, q1;
            expand(fr.C[r], c0, k, k, 7, &p0, &p1);
            expand(fr.C[r] + g->ps, c0, k, k, 7, &q0, &q1);
            v[r] = pixels8(u + x, um1 + x, w0 + x, w1 + x, p0, p1, q0, q1);
        }
        apply_avx2(op, v, fr.out, x, rows, rk);
    }
    row_planar_tail(g, fr, x, rows, op, rk);
}

TEX_AVX2 static void row_lut_avx2(const tex_noise_grid *g, const struct yrow *yr, int rows,
                                  float *const *out, int op, struct row_k rk)
{
    if (g->folded) { /* more columns than entries: fold the entries first */
        float buf[FOLD_ROWS][FOLD_FLOATS];
        struct rowset fr;
        int planar = g->span8 <= 7 && g->span8 < g->t->n; /* offsets mod n unambiguous */
        for (int r = 0; r < rows; r++) {
            fold_row_avx2(g, &yr[r], buf[r]);
            if (!planar)
                interleave(g, buf[r], buf[r] + 2 * g->ps);
            fr.C[r] = planar ? buf[r] : buf[r] + 2 * g->ps;
            fr.out[r] = out[r];
        }
        if (planar) {
            ROWS_SWITCH(row_planar_avx2_op, (g, fr));
        } else {
            ROWS_SWITCH(row_folded_avx2_op, (g, fr, 0));
        }
        return;
    }
    for (int r = 0; r < rows; r++) {
        const float(*T0)[4] = lut_row(g, yr[r].j);
        const float(*T1)[4] = yr[r].two ? lut_row(g, yr[r].j + 1) : NULL;
        const float *wy = yr[r].wy, *dy = yr[r].dy;
        if (g->adjacent) {
            ROW_OP_SWITCH(row_lut_avx2_op, (g, T0, T1, wy, dy, out[r]), (1, rk));
        } else {
            ROW_OP_SWITCH(row_lut_avx2_op, (g, T0, T1, wy, dy, out[r]), (0, rk));
        }
    }
}

TEX_AVX2 static inline void row_avx2(const tex_noise_grid *g, struct rowset rs, int sb, int x,
                                     int x1, int rows, int op, struct row_k rk)
{
    if (g->paired) {
        ROWS_SWITCH(row_avx2_paired_op, ROW_PRE);
    } else {
        ROWS_SWITCH(row_avx2_op, ROW_PRE);
    }
}
#endif

#ifdef TEX_X86
/* ---- the rows sixteen pixels at a time (AVX-512): the AVX2 kernels' operations ---- */

APPLY_FN(TEX_AVX512, apply_avx512, __m512, _mm512_min_ps, _mm512_max_ps, _mm512_abs_ps, 1)

/* pixels8 for sixteen pixels */
TEX_AVX512 static inline __attribute__((always_inline)) __m512
pixels16(const float *restrict u, const float *restrict um1, const float *restrict w0,
         const float *restrict w1, __m512 p0, __m512 p1, __m512 q0, __m512 q1)
{
    __m512 t0 = _mm512_add_ps(_mm512_mul_ps(p0, _mm512_loadu_ps(u)), q0);
    __m512 t1 = _mm512_add_ps(_mm512_mul_ps(p1, _mm512_loadu_ps(um1)), q1);
    return _mm512_add_ps(_mm512_mul_ps(_mm512_loadu_ps(w0), t0),
                         _mm512_mul_ps(_mm512_loadu_ps(w1), t1));
}

/* expand for sixteen pixels (span at most 15: one permute; more: gathers) */
TEX_AVX512 static inline __attribute__((always_inline)) void
expand16(const float *V, int s0, __m512i s, __m512i k, int span, __m512 *a0, __m512 *a1)
{
    if (span <= 1) {
        __mmask16 m = _mm512_test_epi32_mask(k, _mm512_set1_epi32(1));
        *a0 = _mm512_mask_blend_ps(m, _mm512_set1_ps(V[s0]), _mm512_set1_ps(V[s0 + 1]));
        *a1 = _mm512_mask_blend_ps(m, _mm512_set1_ps(V[s0 + 1]), _mm512_set1_ps(V[s0 + 2]));
    } else if (span <= 15) {
        *a0 = _mm512_permutexvar_ps(k, _mm512_loadu_ps(V + s0));
        *a1 = _mm512_permutexvar_ps(k, _mm512_loadu_ps(V + s0 + 1));
    } else {
        *a0 = _mm512_i32gather_ps(s, V, 4);
        *a1 = _mm512_i32gather_ps(s, V + 1, 4);
    }
}

TEX_AVX512 static inline __attribute__((always_inline)) void
row_avx512_op(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1, const int rows,
              const int op, struct row_k rk)
{
    const int32_t *restrict slot = g->slot;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;
    __m512i vsb = _mm512_set1_epi32(sb);

    for (; x + 16 <= x1; x += 16) {
        __m512i s = _mm512_sub_epi32(_mm512_loadu_si512(slot + x), vsb);
        int s0 = slot[x] - sb, span = slot[x + 15] - sb - s0;
        __m512i k = _mm512_sub_epi32(s, _mm512_set1_epi32(s0));
        __m512 v[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            __m512 p0, p1, q0, q1;
            expand16(rs.C[r], s0, s, k, span, &p0, &p1);
            expand16(rs.C[r] + ROW_NS, s0, s, k, span, &q0, &q1);
            v[r] = pixels16(u + x, um1 + x, w0 + x, w1 + x, p0, p1, q0, q1);
        }
        apply_avx512(op, v, rs.out, x, rows, rk);
    }
    row_avx2_op(g, rs, sb, x, x1, rows, op, rk);
}

/* unzip for sixteen columns */
TEX_AVX512 static inline __attribute__((always_inline)) void unzip16(const float *V, __m512 *a0,
                                                                    __m512 *a1)
{
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26,
                                           28, 30);
    __m512 lo = _mm512_loadu_ps(V), hi = _mm512_loadu_ps(V + 16);
    *a0 = _mm512_permutex2var_ps(lo, even, hi);
    *a1 = _mm512_permutex2var_ps(lo, _mm512_add_epi32(even, _mm512_set1_epi32(1)), hi);
}

TEX_AVX512 static inline __attribute__((always_inline)) void
row_avx512_paired_op(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1,
                     const int rows, const int op, struct row_k rk)
{
    const int32_t *restrict slot = g->slot;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;

    for (; x + 16 <= x1; x += 16) {
        int s = slot[x] - sb;
        __m512 v[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            __m512 p0, p1, q0, q1;
            unzip16(rs.C[r] + s, &p0, &p1);
            unzip16(rs.C[r] + ROW_NS + s, &q0, &q1);
            v[r] = pixels16(u + x, um1 + x, w0 + x, w1 + x, p0, p1, q0, q1);
        }
        apply_avx512(op, v, rs.out, x, rows, rk);
    }
    row_avx2_paired_op(g, rs, sb, x, x1, rows, op, rk);
}

/* row_folded_avx2_op sixteen columns at a time: the rows of columns x + k, x + 4 + k,
 * x + 8 + k and x + 12 + k in the quarters of r[k], so that columns4_16 gives point order */
TEX_AVX512 static inline __attribute__((always_inline)) void
row_folded_avx512_op(const tex_noise_grid *g, struct rowset fr, const int rows, const int op,
                     struct row_k rk)
{
    const int32_t *restrict corner = g->corner;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;
    int x = 0;

    for (; x + 16 <= g->w; x += 16) {
        __m512 v[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            __m512 q[4], c[4]; /* c: the left corners' P, Q, the right corners' P, Q */
#pragma GCC unroll 4
            for (int k = 0; k < 4; k++) {
                const int32_t *l = corner + x + k;
                q[k] = _mm512_castps128_ps512(_mm_loadu_ps(PQ_AT(fr.C[r], l[0])));
                q[k] = _mm512_insertf32x4(q[k], _mm_loadu_ps(PQ_AT(fr.C[r], l[4])), 1);
                q[k] = _mm512_insertf32x4(q[k], _mm_loadu_ps(PQ_AT(fr.C[r], l[8])), 2);
                q[k] = _mm512_insertf32x4(q[k], _mm_loadu_ps(PQ_AT(fr.C[r], l[12])), 3);
            }
            columns4_16(q, c);
            v[r] = pixels16(u + x, um1 + x, w0 + x, w1 + x, c[0], c[2], c[1], c[3]);
        }
        apply_avx512(op, v, fr.out, x, rows, rk);
    }
    row_folded_avx2_op(g, fr, x, rows, op, rk);
}

FOLD_ROW_FN(TEX_AVX512, fold_row_avx512, __m512)

/* Two pixel rows' coefficients (fold_row's P0, Q0 and P1, Q1) as one table U of
 * (P0, Q0, P1, Q1) per entry, entries 0..n + 15, made without planar rows between: a
 * column's eight floats from its left entry are both rows' pairs at both corners. */
TEX_AVX512 static void fold2_avx512(const tex_noise_grid *g, const struct yrow yr[2], float *U)
{
    struct fold_src f[2];
    const int n = g->t->n; /* read once, not again after each store */
    fold_src_at(g, &yr[0], &f[0]);
    fold_src_at(g, &yr[1], &f[1]);
    for (int i = 0; i <= n; i += 16) {
        __m512 p0, q0, p1, q1;
        fold_row_avx512_at(&f[0], i, &p0, &q0);
        fold_row_avx512_at(&f[1], i, &p1, &q1);
        __m512 a = _mm512_unpacklo_ps(p0, q0), b = _mm512_unpackhi_ps(p0, q0);
        __m512 c = _mm512_unpacklo_ps(p1, q1), d = _mm512_unpackhi_ps(p1, q1);
        /* e[k]: in each quarter j, entry 4 j + k */
        __m512 e[4] = {_mm512_shuffle_ps(a, c, _MM_SHUFFLE(1, 0, 1, 0)),
                       _mm512_shuffle_ps(a, c, _MM_SHUFFLE(3, 2, 3, 2)),
                       _mm512_shuffle_ps(b, d, _MM_SHUFFLE(1, 0, 1, 0)),
                       _mm512_shuffle_ps(b, d, _MM_SHUFFLE(3, 2, 3, 2))};
        __m512 lo0 = _mm512_shuffle_f32x4(e[0], e[1], _MM_SHUFFLE(1, 0, 1, 0));
        __m512 lo1 = _mm512_shuffle_f32x4(e[2], e[3], _MM_SHUFFLE(1, 0, 1, 0));
        __m512 hi0 = _mm512_shuffle_f32x4(e[0], e[1], _MM_SHUFFLE(3, 2, 3, 2));
        __m512 hi1 = _mm512_shuffle_f32x4(e[2], e[3], _MM_SHUFFLE(3, 2, 3, 2));
        /* entries 0..3 are quarters 0 of e[0..3], entries 4..7 their quarters 1, ... */
        _mm512_storeu_ps(U + 4 * i, _mm512_shuffle_f32x4(lo0, lo1, _MM_SHUFFLE(2, 0, 2, 0)));
        _mm512_storeu_ps(U + 4 * i + 16, _mm512_shuffle_f32x4(lo0, lo1, _MM_SHUFFLE(3, 1, 3, 1)));
        _mm512_storeu_ps(U + 4 * i + 32, _mm512_shuffle_f32x4(hi0, hi1, _MM_SHUFFLE(2, 0, 2, 0)));
        _mm512_storeu_ps(U + 4 * i + 48, _mm512_shuffle_f32x4(hi0, hi1, _MM_SHUFFLE(3, 1, 3, 1)));
    }
}

/* Columns x + j and x + 4 + j's eight floats at U (fold2_avx512) in the halves of one vector
 * (corner2: g->corner2 + x + j) */
TEX_AVX512 static inline __attribute__((always_inline)) __m512
column_pair(const float *U, const int32_t *corner2)
{
    __m256 a = _mm256_loadu_ps((const float *)((const double *)U + corner2[0]));
    __m256 b = _mm256_loadu_ps((const float *)((const double *)U + corner2[4]));
    return _mm512_castpd_ps(
        _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(a)), _mm256_castps_pd(b), 1));
}

/* A folded grid's two rows from U (fold2_avx512) where sixteen columns' corners lie too far
 * apart for a permute of one register: one load per column serves both rows, then a
 * transpose in quarters (columns4_16) and a shuffle of quarters into point order. */
TEX_AVX512 static inline __attribute__((always_inline)) void
row_folded2_avx512_op(const tex_noise_grid *g, const float *U, float *const *out, const int op,
                      struct row_k rk)
{
    const int32_t *restrict corner = g->corner, *restrict corner2 = g->corner2;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;
    const int w = g->w; /* and the rows: read once, not again after each store */
    float *const o[2] = {out[0], out[1]};
    int x = 0;

    for (; x + 16 <= w; x += 16) {
        __m512 z[2][4], t[2][4]; /* quarters: left and right entries of columns j, 4 + j */
#pragma GCC unroll 4
        for (int j = 0; j < 4; j++) {
            z[0][j] = column_pair(U, corner2 + x + j);
            z[1][j] = column_pair(U, corner2 + x + 8 + j);
        }
        columns4_16(z[0], t[0]); /* t[h][v]: component v (P0, Q0, P1, Q1) */
        columns4_16(z[1], t[1]);
        __m512 v[2];
        for (int r = 0; r < 2; r++) {
            __m512 p = t[0][2 * r], p8 = t[1][2 * r], q = t[0][2 * r + 1], q8 = t[1][2 * r + 1];
            v[r] = pixels16(u + x, um1 + x, w0 + x, w1 + x,
                            _mm512_shuffle_f32x4(p, p8, _MM_SHUFFLE(2, 0, 2, 0)),
                            _mm512_shuffle_f32x4(p, p8, _MM_SHUFFLE(3, 1, 3, 1)),
                            _mm512_shuffle_f32x4(q, q8, _MM_SHUFFLE(2, 0, 2, 0)),
                            _mm512_shuffle_f32x4(q, q8, _MM_SHUFFLE(3, 1, 3, 1)));
        }
        apply_avx512(op, v, o, x, 2, rk);
    }
    for (; x < w; x++) /* row_planar_tail's order of operations */
        for (int r = 0; r < 2; r++) {
            const float *L = U + 4 * (size_t)corner[x] + 2 * r, *R = L + 4;
            float t0 = L[0] * u[x] + L[1], t1 = R[0] * um1[x] + R[1];
            apply_op(op, w0[x] * t0 + w1[x] * t1, out[r] + x, rk);
        }
}

/* row_planar_avx2_op sixteen columns at a time, their corners within 16 entries of the
 * first's (g->span16 <= 15: cells over 15/16 pixels): each corner's P and Q from a permute
 * of one register's entries */
TEX_AVX512 static inline __attribute__((always_inline)) void
row_planar_avx512_op(const tex_noise_grid *g, struct rowset fr, const int rows, const int op,
                     struct row_k rk)
{
    const int32_t *restrict corner = g->corner;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;
    __m512i vn = _mm512_set1_epi32(g->t->n);
    const int w = g->w; /* and the rows' planes: read once, not again after each store */
    const float *Q[FOLD_ROWS];
    int x = 0;

    for (int r = 0; r < rows; r++)
        Q[r] = fr.C[r] + g->ps;
    for (; x + 16 <= w; x += 16) {
        int c0 = corner[x];
        __m512i d = _mm512_sub_epi32(_mm512_loadu_si512(corner + x), _mm512_set1_epi32(c0));
        __m512i k = _mm512_min_epu32(d, _mm512_add_epi32(d, vn));
        __m512 n[FOLD_ROWS];
#pragma GCC unroll 2
        for (int r = 0; r < rows; r++) {
            const float *P = fr.C[r];
            __m512 v[4]; /* the left corners' P, Q, the right corners' P, Q */
            expand16(P, c0, k, k, 15, &v[0], &v[2]);
            expand16(Q[r], c0, k, k, 15, &v[1], &v[3]);
            n[r] = pixels16(u + x, um1 + x, w0 + x, w1 + x, v[0], v[2], v[1], v[3]);
        }
        apply_avx512(op, n, fr.out, x, rows, rk);
    }
    row_planar_tail(g, fr, x, rows, op, rk);
}

/* row_lut_avx2 with the folded rows sixteen columns at a time: by permutes where sixteen
 * columns' corners lie within sixteen entries, else by loads per column (two rows' from one
 * table where there are two: from sixteen entries on, 3-4 % faster than permutes of two
 * registers) */
TEX_AVX512 static void row_lut_avx512(const tex_noise_grid *g, const struct yrow *yr, int rows,
                                      float *const *out, int op, struct row_k rk)
{
    if (!g->folded) {
        row_lut_avx2(g, yr, rows, out, op, rk);
        return;
    }
    int span = g->span16 < g->t->n ? g->span16 : INT_MAX; /* offsets mod n unambiguous */
    if (span > 15 && rows == 2) {
        float U[FOLD2_FLOATS];
        fold2_avx512(g, yr, U);
        ROW_OP_SWITCH(row_folded2_avx512_op, (g, U, out), (rk));
        return;
    }
    float buf[FOLD_ROWS][FOLD_FLOATS];
    struct rowset fr;
    for (int r = 0; r < rows; r++) {
        fold_row_avx512(g, &yr[r], buf[r]);
        if (span > 15)
            interleave(g, buf[r], buf[r] + 2 * g->ps);
        fr.C[r] = span > 15 ? buf[r] + 2 * g->ps : buf[r];
        fr.out[r] = out[r];
    }
    if (span <= 15) {
        ROWS_SWITCH(row_planar_avx512_op, (g, fr));
    } else {
        ROWS_SWITCH(row_folded_avx512_op, (g, fr));
    }
}

TEX_AVX512 static inline void row_avx512(const tex_noise_grid *g, struct rowset rs, int sb, int x,
                                         int x1, int rows, int op, struct row_k rk)
{
    if (g->paired) {
        ROWS_SWITCH(row_avx512_paired_op, ROW_PRE);
    } else {
        ROWS_SWITCH(row_avx512_op, ROW_PRE);
    }
}

/* row_coeffs_avx2 sixteen slots at a time */
TEX_AVX512 static void row_coeffs_avx512(int ns, const float *wy, const float *dy,
                                         const float *const L0[3], const float *const L1[3],
                                         float *P, float *Q)
{
    __m512 a0 = _mm512_set1_ps(wy[0]), a1 = _mm512_set1_ps(wy[1]);
    __m512 d0 = _mm512_set1_ps(dy[0]), d1 = _mm512_set1_ps(dy[1]);
    int s = 0;

    if (L1)
        for (; s + 16 <= ns; s += 16) {
            __m512 p = _mm512_add_ps(_mm512_mul_ps(a0, _mm512_loadu_ps(L0[0] + s)),
                                     _mm512_mul_ps(a1, _mm512_loadu_ps(L1[0] + s)));
            __m512 q0 = _mm512_add_ps(_mm512_mul_ps(_mm512_loadu_ps(L0[1] + s), d0),
                                      _mm512_loadu_ps(L0[2] + s));
            __m512 q1 = _mm512_add_ps(_mm512_mul_ps(_mm512_loadu_ps(L1[1] + s), d1),
                                      _mm512_loadu_ps(L1[2] + s));
            _mm512_storeu_ps(P + s, p);
            _mm512_storeu_ps(Q + s, _mm512_add_ps(_mm512_mul_ps(a0, q0), _mm512_mul_ps(a1, q1)));
        }
    else
        for (; s + 16 <= ns; s += 16) {
            __m512 q0 = _mm512_add_ps(_mm512_mul_ps(_mm512_loadu_ps(L0[1] + s), d0),
                                      _mm512_loadu_ps(L0[2] + s));
            _mm512_storeu_ps(P + s, _mm512_mul_ps(a0, _mm512_loadu_ps(L0[0] + s)));
            _mm512_storeu_ps(Q + s, _mm512_mul_ps(a0, q0));
        }
    /* the rest, and the zeros after the last slot, as row_coeffs_avx2 makes them */
    const float *l0[3] = {L0[0] + s, L0[1] + s, L0[2] + s};
    const float *l1[3] = {L1 ? L1[0] + s : NULL, L1 ? L1[1] + s : NULL, L1 ? L1[2] + s : NULL};
    row_coeffs_avx2(ns - s, wy, dy, l0, L1 ? l1 : NULL, P + s, Q + s);
}
#endif

/* Row y: the lattice rows (kept or computed), the coefficients, the pixels.
 * Columns go in chunks, so that the coefficients stay on the stack and in L1
 * (a chunk of CHUNK columns touches at most 2 CHUNK slots).  One copy per
 * level, so that the vector parts inline. */
#define GRID_ROW grid_row_scalar
#define GRID_ATTR
#define GRID_COEFFS row_coeffs
#define GRID_PIXELS row_scalar
#include "prim/noise_row_template.c"
#ifdef TEX_X86
#define GRID_ROW grid_row_avx2
#define GRID_ATTR TEX_AVX2
#define GRID_COEFFS row_coeffs_avx2
#define GRID_PIXELS row_avx2
#define GRID_LUT_ROW row_lut_avx2
#include "prim/noise_row_template.c"
#define GRID_ROW grid_row_avx512
#define GRID_ATTR TEX_AVX512
#define GRID_COEFFS row_coeffs_avx512
#define GRID_PIXELS row_avx512
#define GRID_LUT_ROW row_lut_avx512
#include "prim/noise_row_template.c"
#endif

/* Rows y.. y + rows - 1 (rows at most FOLD_ROWS) at the level the CPU and the grid take */
static void grid_rows(const tex_noise_grid *g, int y, int rows, int op, struct row_k rk,
                      float *const *out)
{
#ifdef TEX_X86
    int level = tex_simd_level();
    if (level >= TEX_SIMD_AVX512 && g->wide) {
        grid_row_avx512(g, y, rows, op, rk, out);
        return;
    }
    if (level >= TEX_SIMD_AVX2) {
        grid_row_avx2(g, y, rows, op, rk, out);
        return;
    }
#endif
    grid_row_scalar(g, y, rows, op, rk, out);
}

/* Rows y.. y + n - 1 with the operation op, in twos */
static void grid_rows_k(const tex_noise_grid *g, int y, int n, int op, struct row_k rk,
                        float *out, size_t stride)
{
    for (int i = 0; i < n; i += FOLD_ROWS) {
        float *o[FOLD_ROWS] = {out + i * stride, i + 1 < n ? out + (i + 1) * stride : NULL};
        grid_rows(g, y + i, n - i < FOLD_ROWS ? n - i : FOLD_ROWS, op, rk, o);
    }
}

void tex_noise_grid_row_op(const tex_noise_grid *g, int y, int op, float a, float b, float c,
                           float *out)
{
    tex_noise_grid_rows_op(g, y, 1, op, a, b, c, out, 0);
}

/* The operations without a state: the state is the sum, never read. */
void tex_noise_grid_rows_op(const tex_noise_grid *g, int y, int n, int op, float a, float b,
                            float c, float *out, size_t stride)
{
    struct row_k rk = {a, b, c, 0, 0, 0};
    grid_rows_k(g, y, n, op, rk, out, stride);
}

void tex_noise_grid_rows_mf(const tex_noise_grid *g, int y, int n, int op,
                            const struct tex_mf_k *k, float *out, float *st, size_t stride)
{
    struct row_k rk = {k->amp, k->offset, k->gain, k->lo, k->inv,
                       (uintptr_t)st - (uintptr_t)out};
    grid_rows_k(g, y, n, op, rk, out, stride);
}

void tex_noise_grid_row(const tex_noise_grid *g, int y, float *out)
{
    tex_noise_grid_row_op(g, y, TEX_ROW_SET, 0, 0, 0, out);
}

void tex_noise_grid_row_add(const tex_noise_grid *g, int y, float amp, float *out)
{
    tex_noise_grid_row_op(g, y, TEX_ROW_ADD, amp, 0, 0, out);
}

/* ---- the analytic gradient over a row ---- */

/* The y derivative's coefficients: as row_coeffs with the row weights'
 * derivatives dwy, plus the lattice rows' own y slope wy Y. */
static void row_coeffs_dy(int ns, const float *wy, const float *dwy, const float *dy,
                          const float *const L0[3], const float *const L1[3], float *P, float *Q)
{
    for (int s = 0; s < ns; s++) {
        P[s] = dwy[0] * L0[0][s];
        Q[s] = dwy[0] * (L0[1][s] * dy[0] + L0[2][s]) + wy[0] * L0[1][s];
        if (L1) {
            P[s] = P[s] + dwy[1] * L1[0][s];
            Q[s] = Q[s] + (dwy[1] * (L1[1][s] * dy[1] + L1[2][s]) + wy[1] * L1[1][s]);
        }
    }
    for (int s = ns; s < ns + 16; s++)
        P[s] = Q[s] = 0;
}

/* Pixels x..x1-1 of the gradient from the three coefficient pairs (value,
 * y derivative, z derivative; Z NULL without dz): the reference order. */
static void grad_scalar(const tex_noise_grid *g, const float *const C[6], int sb, float *dx,
                        float *dy, float *dz, int x, int x1)
{
    for (; x < x1; x++) {
        int s = g->slot[x] - sb;
        float u = g->u[x], v = g->um1[x], w0 = g->w0[x], w1 = g->w1[x];
        float t0 = C[0][s] * u + C[1][s], t1 = C[0][s + 1] * v + C[1][s + 1];
        dx[x] = (g->dw0[x] * t0 + w0 * C[0][s]) + (g->dw1[x] * t1 + w1 * C[0][s + 1]);
        dy[x] = w0 * (C[2][s] * u + C[3][s]) + w1 * (C[2][s + 1] * v + C[3][s + 1]);
        if (dz)
            dz[x] = w0 * (C[4][s] * u + C[5][s]) + w1 * (C[4][s + 1] * v + C[5][s + 1]);
    }
}

#ifdef TEX_X86
TEX_AVX2 static void grad_avx2(const tex_noise_grid *g, const float *const C[6], int sb, float *dx,
                           float *dy, float *dz, int x, int x1)
{
    __m256i vsb = _mm256_set1_epi32(sb);

    for (; x + 8 <= x1; x += 8) {
        __m256i s = _mm256_sub_epi32(_mm256_loadu_si256((const __m256i *)(g->slot + x)), vsb);
        int s0 = g->slot[x] - sb, span = g->slot[x + 7] - sb - s0;
        __m256i k = _mm256_sub_epi32(s, _mm256_set1_epi32(s0));
        __m256 u = _mm256_loadu_ps(g->u + x), v = _mm256_loadu_ps(g->um1 + x);
        __m256 w0 = _mm256_loadu_ps(g->w0 + x), w1 = _mm256_loadu_ps(g->w1 + x);
        __m256 a0, a1, b0, b1;
        expand(C[0], s0, s, k, span, &a0, &a1);
        expand(C[1], s0, s, k, span, &b0, &b1);
        __m256 t0 = _mm256_add_ps(_mm256_mul_ps(a0, u), b0);
        __m256 t1 = _mm256_add_ps(_mm256_mul_ps(a1, v), b1);
        __m256 r0 =
            _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(g->dw0 + x), t0), _mm256_mul_ps(w0, a0));
        __m256 r1 =
            _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(g->dw1 + x), t1), _mm256_mul_ps(w1, a1));
        _mm256_storeu_ps(dx + x, _mm256_add_ps(r0, r1));
        for (int d = 1; d < (dz ? 3 : 2); d++) {
            expand(C[2 * d], s0, s, k, span, &a0, &a1);
            expand(C[2 * d + 1], s0, s, k, span, &b0, &b1);
            t0 = _mm256_mul_ps(w0, _mm256_add_ps(_mm256_mul_ps(a0, u), b0));
            t1 = _mm256_mul_ps(w1, _mm256_add_ps(_mm256_mul_ps(a1, v), b1));
            _mm256_storeu_ps((d == 1 ? dy : dz) + x, _mm256_add_ps(t0, t1));
        }
    }
    grad_scalar(g, C, sb, dx, dy, dz, x, x1);
}
#endif

void tex_noise_grid_row_grad(const tex_noise_grid *g, int y, float *dx, float *dy, float *dz)
{
    enum { CHUNK = 256, NS = 2 * CHUNK + 24 };
    float L[12][NS], K[6][NS];
    const float *const C[6] = {K[0], K[1], K[2], K[3], K[4], K[5]};
    double Y = g->oy + g->fy * (y + 0.5), cy = floor(Y), fr = Y - cy;
    int64_t j = tex_noise_cell(cy);
    int fd = g->t->fade;
    float wy[2] = {(float)fade(fd, fr), (float)fade(fd, 1.0 - fr)};
    float dwy[2] = {(float)dfade(fd, fr), (float)-dfade(fd, 1.0 - fr)};
    float ry[2] = {(float)fr, (float)(fr - 1.0)};
    int two = wy[1] != 0, level = tex_simd_level();

    for (int x0 = 0; x0 < g->w; x0 += CHUNK) {
        int x1 = x0 + CHUNK < g->w ? x0 + CHUNK : g->w;
        int s0 = g->slot[x0], s1 = g->slot[x1 - 1] + 2;
        const float *L0[3] = {L[0], L[1], L[2]}, *L1[3] = {L[3], L[4], L[5]};
        const float *D0[3] = {L[6], L[7], L[8]}, *D1[3] = {L[9], L[10], L[11]};
        lattice_row(g, j, s0, s1, L[0], L[1], L[2]);
        if (two)
            lattice_row(g, j + 1, s0, s1, L[3], L[4], L[5]);
        row_coeffs(s1 - s0, wy, ry, L0, two ? L1 : NULL, K[0], K[1]);
        row_coeffs_dy(s1 - s0, wy, dwy, ry, L0, two ? L1 : NULL, K[2], K[3]);
        if (dz) {
            lattice_row_m(g, (const float(*)[4])g->zdm, j, s0, s1, L[6], L[7], L[8]);
            if (two)
                lattice_row_m(g, (const float(*)[4])g->zdm, j + 1, s0, s1, L[9], L[10], L[11]);
            row_coeffs(s1 - s0, wy, ry, D0, two ? D1 : NULL, K[4], K[5]);
        }
#ifdef TEX_X86
        if (level >= TEX_SIMD_AVX2) {
            grad_avx2(g, C, s0, dx, dy, dz, x0, x1);
            continue;
        }
#endif
        grad_scalar(g, C, s0, dx, dy, dz, x0, x1);
    }
    (void)level;
}

/* ---- octaves ---- */

int tex_octaves_init(tex_octaves *o, uint64_t seed, int gradients, int fade, int n, double freq,
                     double lac, const double off[3], double z, double t, int dims, int tile,
                     int w, int h)
{
    /* Irrational-looking shifts so that the octaves do not all vanish together. */
    static const double shift[4] = {13.1367, 7.7351, 3.5193, 5.2371};

    memset(o, 0, sizeof *o);
    if (n < 1 || n > TEX_OCTAVES_MAX)
        return tex_usage_error("--octaves must be 1..%d (got %d)", TEX_OCTAVES_MAX, n);
    if (tile && (freq != floor(freq) || freq < 1))
        return tex_usage_error("--frequency must be a whole number >= 1 with --tile (got %g)",
                               freq);
    if (tile && lac != floor(lac))
        return tex_usage_error("--lacunarity must be a whole number with --tile (got %g)", lac);
    o->n = n;
    o->dims = dims;
    for (int k = 0; k < n; k++) {
        double s = pow(lac, k);
        o->freq[k] = freq * s;
        if (tile && o->freq[k] > 1e9)
            return tex_usage_error("--tile: the last octave's frequency %g is above 1e9 (lower "
                                   "--octaves, --frequency or --lacunarity)",
                                   o->freq[k]);
        o->period[k] = tile ? (int)o->freq[k] : 0;
        o->off[k][0] = s * off[0] + (k ? k * shift[0] : 0);
        o->off[k][1] = s * off[1] + (k ? k * shift[1] : 0);
        o->off[k][2] = s * (freq * z + off[2]) + (k ? k * shift[2] : 0);
        o->off[k][3] = dims == 4 ? s * freq * t + (k ? k * shift[3] : 0) : 0;
    }
    if (tex_noise_init(&o->t, seed, gradients, 0) < 0)
        return -1;
    o->t.fade = fade;
    if (w > 0 && h > 0) {
        int wide = 0;
        o->grid = 1;
        for (int k = 0; k < n; k++) {
            if (tex_noise_grid_init(&o->g[k], &o->t, w, h, o->freq[k], o->freq[k], o->off[k],
                                    dims, o->period[k]) < 0) {
                tex_octaves_free(o);
                return -1;
            }
            wide += o->g[k].wide;
        }
        /* AVX-512 rows for the wide octaves only where they are most of the sum: a map that
         * switches between 512- and 256-bit rows runs slower than on 256 alone (fBm of 8
         * octaves from 256 cells: 4 %; from 4 cells, all but one wide: 10-30 % faster). */
        for (int k = 0; 2 * wide < n && k < n; k++)
            o->g[k].wide = 0;
    }
    return 0;
}

void tex_octaves_free(tex_octaves *o)
{
    tex_noise_free(&o->t);
    for (int k = 0; k < o->n; k++)
        tex_noise_grid_free(&o->g[k]);
    o->grid = 0;
}

double tex_octave_point(const tex_octaves *o, int k, double u, double v, double w)
{
    double f = o->freq[k], x = o->off[k][0] + f * u, y = o->off[k][1] + f * v;

    if (o->dims == 4)
        return tex_noise4p(&o->t, o->period[k], x, y, o->off[k][2] + f * w, o->off[k][3]);
    return tex_noise3p(&o->t, o->period[k], x, y, o->off[k][2] + f * w);
}

void tex_octave_points(const tex_octaves *o, int k, int n, const double *u, const double *v,
                       const double *w, double *out)
{
    enum { B = TEX_POINTS_BATCH };
    double f = o->freq[k], X[B], Y[B], Z[B], W[B];
    float r[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        if (o->dims == 3) { /* tex_octave_point's coordinates, made in the kernel */
            tex_noise_points_at(&o->t, o->period[k], o->off[k], f, m, u + i0, v + i0,
                                w ? w + i0 : NULL, r);
            for (int i = 0; i < m; i++)
                out[i0 + i] = r[i];
            continue;
        }
#pragma omp simd
        for (int i = 0; i < m; i++) {
            X[i] = o->off[k][0] + f * u[i0 + i];
            Y[i] = o->off[k][1] + f * v[i0 + i];
            Z[i] = o->off[k][2] + f * (w ? w[i0 + i] : 0);
            W[i] = o->off[k][3];
        }
        tex_noise_points(&o->t, o->period[k], o->dims, m, X, Y, Z, W, out + i0);
    }
}

/* tex_octave_points as float, the 3D octaves straight from the kernel's floats */
static void octave_points_f(const tex_octaves *o, int k, int n, const double *u, const double *v,
                            const double *w, float *out)
{
    double r[TEX_POINTS_BATCH];

    if (o->dims == 3) {
        tex_noise_points_at(&o->t, o->period[k], o->off[k], o->freq[k], n, u, v, w, out);
        return;
    }
    for (int i0 = 0; i0 < n; i0 += TEX_POINTS_BATCH) {
        int m = n - i0 < TEX_POINTS_BATCH ? n - i0 : TEX_POINTS_BATCH;
        tex_octave_points(o, k, m, u + i0, v + i0, w ? w + i0 : NULL, r);
        for (int i = 0; i < m; i++)
            out[i0 + i] = (float)r[i];
    }
}

void tex_octave_abs_sum(const tex_octaves *o, int octaves, const float *amp, float start, int n,
                        const double *u, const double *v, const double *w, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    float rf[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        for (int i = 0; i < m; i++)
            out[i0 + i] = start;
        for (int k = 0; k < octaves; k++) {
            octave_points_f(o, k, m, u + i0, v + i0, w ? w + i0 : NULL, rf);
            float ak = amp[k], *restrict o = out + i0; /* o aliases neither amp nor rf */
#pragma omp simd
            for (int i = 0; i < m; i++)
                o[i] += ak * fabsf(rf[i]);
        }
    }
}

#ifdef TEX_X86
/* band_weights' first n - n % 4 */
TEX_AVX2 static int band_weights_avx2(int n, const double *fw, double fk, float *wt)
{
    const __m256d lo = _mm256_set1_pd(0.2), hi = _mm256_set1_pd(0.6), one = _mm256_set1_pd(1);
    __m128 any = _mm_setzero_ps();
    for (int i = 0; i + 4 <= n; i += 4) {
        __m256d c = _mm256_mul_pd(_mm256_loadu_pd(fw + i), _mm256_set1_pd(fk));
        __m256d ge = _mm256_cmp_pd(c, hi, _CMP_GE_OQ), le = _mm256_cmp_pd(c, lo, _CMP_LE_OQ);
        __m256d w = _mm256_and_pd(le, one); /* 1 - t t (3 - 2 t) at t = 0 and 1: 1 and 0 */
        if (_mm256_movemask_pd(_mm256_or_pd(ge, le)) != 15) { /* one inside the band */
            __m256d t = _mm256_div_pd(_mm256_sub_pd(c, lo), _mm256_set1_pd(0.4));
            t = _mm256_blendv_pd(t, one, ge);
            t = _mm256_blendv_pd(t, _mm256_setzero_pd(), le);
            w = _mm256_sub_pd(
                one, _mm256_mul_pd(_mm256_mul_pd(t, t),
                                   _mm256_sub_pd(_mm256_set1_pd(3), _mm256_add_pd(t, t))));
        }
        __m128 wf = _mm256_cvtpd_ps(w);
        _mm_storeu_ps(wt + i, wf);
        any = _mm_or_ps(any, _mm_cmpgt_ps(wf, _mm_setzero_ps()));
    }
    return _mm_movemask_ps(any) != 0;
}
#endif

/* 1 - smoothstep(0.2, 0.6, cells): an octave's weight where a pixel or footprint
 * spans that many of its lattice cells */
static double band_weight(double cells)
{
    double t = cells <= 0.2 ? 0 : cells >= 0.6 ? 1 : (cells - 0.2) / 0.4;
    return 1 - t * t * (3 - 2 * t);
}

/* wt[i] = band_weight(fw[i] fk) as float, i < n; whether one is > 0.  Four at a time with
 * AVX2, band_weight's operations in its order. */
static int band_weights(int n, const double *fw, double fk, float *wt)
{
    int any = 0, i = 0;
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2)
        any = band_weights_avx2(n, fw, fk, wt), i = n & ~3;
#endif
    for (; i < n; i++) {
        wt[i] = (float)band_weight(fw[i] * fk);
        any |= wt[i] > 0;
    }
    return any;
}

double tex_octave_band_weight(const tex_octaves *o, int k)
{
    return o->grid ? band_weight(o->g[k].fy) : 1; /* g.fy: lattice cells per pixel */
}

void tex_octave_points_fw(const tex_octaves *o, int k, int n, const double *u, const double *v,
                          const double *w, const double *fw, float *out, float *wt)
{
    if (band_weights(n, fw, o->freq[k], wt))
        octave_points_f(o, k, n, u, v, w, out);
    else
        memset(out, 0, n * sizeof *out);
}

double tex_noise_mean_abs(const tex_noise_table *t)
{
    enum { N = 16 };
    double x[N * N], y[N * N], z[N * N], r[N * N], sum = 0;

    /* a fixed jittered lattice over 16^3 cells: the same mean for the same table */
    for (int k = 0; k < N; k++) {
        for (int i = 0; i < N * N; i++) {
            x[i] = (i % N) + 0.5 + 0.37 * sin(i * 1.7 + k);
            y[i] = (double)(i / N) + 0.5 + 0.37 * sin(i * 2.3 + 2 * k);
            z[i] = k + 0.5 + 0.37 * sin(i * 0.9 + 3 * k);
        }
        tex_noise_points(t, 0, 3, N * N, x, y, z, NULL, r);
        for (int i = 0; i < N * N; i++)
            sum += fabs(r[i]);
    }
    return sum / (N * N * N);
}

void tex_octave_row(const tex_octaves *o, int k, int y, float *out)
{
    tex_noise_grid_row(&o->g[k], y, out);
}

void tex_octave_row_add(const tex_octaves *o, int k, int y, float amp, float *out)
{
    tex_noise_grid_row_add(&o->g[k], y, amp, out);
}

void tex_octave_row_op(const tex_octaves *o, int k, int y, int op, float a, float b, float c,
                       float *out)
{
    tex_noise_grid_row_op(&o->g[k], y, op, a, b, c, out);
}

void tex_octave_rows_op(const tex_octaves *o, int k, int y, int n, int op, float a, float b,
                        float c, float *out, size_t stride)
{
    tex_noise_grid_rows_op(&o->g[k], y, n, op, a, b, c, out, stride);
}

void tex_octave_rows_mf(const tex_octaves *o, int k, int y, int n, int op,
                        const struct tex_mf_k *mk, float *out, float *st, size_t stride)
{
    tex_noise_grid_rows_mf(&o->g[k], y, n, op, mk, out, st, stride);
}

/* ---- the primitive ---- */

struct noise_params {
    double frequency;
    double z;
    struct tex_reals w;
    struct tex_reals offset;
    int fade;
    int gradients;
    int frames, frame;
    double loop_radius;
};

static const struct tex_param noise_rows[] = {
    TEX_REAL(struct noise_params, frequency, 'f', 8, 0, 1e6, "F",
             "lattice cells across the map (a whole number with --tile)"),
    TEX_NOISE_ROWS(struct noise_params),
    TEX_NOISE_W_ROW(struct noise_params),
    TEX_NOISE_LOOP_ROWS(struct noise_params),
    {0}};

struct noise_state {
    tex_noise_table t;
    tex_noise_grid g;
    int period, dims;
    double off[4];
};

/* The state shared by noise and d_noise: the lattice tables from the seed, the
 * period under --tile, and the offset in lattice units (z slice included). */
static int state_init(struct tex_field *f, double frequency, const struct tex_reals *offset,
                      double z, int gradients, int fade)
{
    struct noise_state *s = calloc(1, sizeof *s);

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    if (f->tile) {
        if (frequency != floor(frequency) || frequency < 1)
            return tex_usage_error("--frequency must be a whole number >= 1 with --tile (got %g)",
                                   frequency);
        s->period = (int)frequency;
    }
    for (int a = 0; a < offset->n; a++)
        s->off[a] = offset->v[a];
    s->off[2] += frequency * z;
    if (tex_noise_init(&s->t, f->seed, gradients, s->period) < 0)
        return -1;
    s->t.fade = fade;
    return 0;
}

int tex_noise_loop(int frames, int frame, double radius, double *z, double *w, int *dims)
{
    if (frames == 0 && frame == 0)
        return 0;
    if (frame >= frames)
        return frames ? tex_usage_error("--frame must be 0..%d for --frames %d (got %d)",
                                        frames - 1, frames, frame)
                      : tex_usage_error("--frame %d needs --frames N", frame);
    double a = 2 * M_PI * ((double)frame / frames);
    *z += radius * cos(a);
    *w += radius * sin(a);
    *dims = 4;
    return 0;
}

static int noise_init(struct tex_field *f)
{
    const struct noise_params *p = f->params;
    struct noise_state *s;
    double z = p->z, w = p->w.n ? p->w.v[0] : 0;
    int dims = p->w.n ? 4 : 3;

    if (tex_noise_loop(p->frames, p->frame, p->loop_radius, &z, &w, &dims) < 0 ||
        state_init(f, p->frequency, &p->offset, z, p->gradients, p->fade) < 0)
        return -1;
    s = f->state;
    s->dims = dims;
    s->off[3] = dims == 4 ? p->frequency * w : 0;
    if (f->w > 0 && f->h > 0)
        return tex_noise_grid_init(&s->g, &s->t, f->w, f->h, p->frequency, p->frequency, s->off,
                                   s->dims, s->period);
    return 0;
}

static void noise_fini(struct tex_field *f)
{
    struct noise_state *s = f->state;
    if (!s)
        return;
    tex_noise_free(&s->t);
    tex_noise_grid_free(&s->g);
    free(s);
}

static inline float to_unit(float s)
{
    return clamp01(0.5f + 0.5f * s);
}

static void noise_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                        const double *w, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    const struct noise_params *p = f->params;
    const struct noise_state *s = f->state;
    double fr = p->frequency, X[B], Y[B], Z[B], W[B], r[B];
    float rf[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        if (s->dims == 3) { /* the coordinates below, made in the kernel */
            tex_noise_points_at(&s->t, s->period, s->off, fr, m, u + i0, v + i0,
                                w ? w + i0 : NULL, rf);
#pragma omp simd
            for (int i = 0; i < m; i++)
                out[i0 + i] = to_unit(rf[i]);
            continue;
        }
#pragma omp simd
        for (int i = 0; i < m; i++) { /* lattice coordinates: offset + frequency x point */
            X[i] = s->off[0] + fr * u[i0 + i];
            Y[i] = s->off[1] + fr * v[i0 + i];
            Z[i] = s->off[2] + fr * (w ? w[i0 + i] : 0);
            W[i] = s->off[3];
        }
        tex_noise_points(&s->t, s->period, s->dims, m, X, Y, Z, W, r);
        for (int i = 0; i < m; i++)
            out[i0 + i] = to_unit((float)r[i]);
    }
}

static void noise_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                        float *out)
{
    noise_eval3(f, n, u, v, NULL, out);
}

static void noise_row(const struct tex_field *f, int y, float *out)
{
    const struct noise_state *s = f->state;

    tex_noise_grid_row_op(&s->g, y, TEX_ROW_UNIT, 0, 0, 0, out);
}

const struct tex_primitive tex_prim_noise = {
    .name = "noise",
    .summary = "gradient noise of the thesis (Perlin), rescaled to [0,1]",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct noise_params),
    .params = noise_rows,
    .init = noise_init,
    .fini = noise_fini,
    .eval2 = noise_eval2,
    .eval3 = noise_eval3,
    .row = noise_row,
};

/* ---- d_noise: the analytic gradient (thesis 5.2.2.3) ---- */

struct dnoise_params {
    double frequency, z, strength;
    struct tex_reals offset;
    int channels, normal, fade, gradients;
};

static const struct tex_param dnoise_rows[] = {
    TEX_REAL(struct dnoise_params, frequency, 'f', 8, 0, 1e6, "F",
             "lattice cells across the map (a whole number with --tile)"),
    TEX_NOISE_ROWS(struct dnoise_params),
    TEX_INT(struct dnoise_params, channels, 0, 2, 2, 3, "N",
            "2: d/dx, d/dy; 3: also d/dz (raw gradient, lattice units)", .old = "-c"),
    TEX_FLAG(struct dnoise_params, normal, 0,
             "write a tangent-space normal map (x right, y up, z out) encoded as 0.5 + 0.5 n"),
    TEX_REAL(struct dnoise_params, strength, 0, 1, 0, 1e6, "S",
             "--normal: height scale, n = normalize(-S dn/dx, S dn/dy_up, 1)"),
    {0}};

static int dnoise_init(struct tex_field *f)
{
    const struct dnoise_params *p = f->params;
    struct noise_state *s;

    /* Values other than the defaults are the test: the rows are shared with scenes. */
    if (!p->normal && p->strength != 1)
        return tex_usage_error("--strength applies with --normal only");
    if (p->normal && p->channels != 2)
        return tex_usage_error("--channels applies without --normal only (a normal map has 3)");
    f->nc = p->normal ? 3 : p->channels;
    if (state_init(f, p->frequency, &p->offset, p->z, p->gradients, p->fade) < 0)
        return -1;
    s = f->state;
    s->dims = 3;
    if (f->w > 0 && f->h > 0)
        return tex_noise_grid_init(&s->g, &s->t, f->w, f->h, p->frequency, p->frequency, s->off,
                                   3, s->period);
    return 0;
}

static void dnoise_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                         const double *w, float *out)
{
    const struct dnoise_params *p = f->params;
    const struct noise_state *s = f->state;
    double fr = p->frequency;

    for (int i = 0; i < n; i++, out += f->nc) {
        double g[3];
        tex_noise3_grad(&s->t, s->period, s->off[0] + fr * u[i], s->off[1] + fr * v[i],
                        s->off[2] + fr * (w ? w[i] : 0), g);
        if (p->normal) {
            /* v grows downwards: the height's slope along y-up is -dn/dv. */
            double nx = -p->strength * g[0], ny = p->strength * g[1];
            double len = sqrt(nx * nx + ny * ny + 1);
            out[0] = (float)(0.5 + 0.5 * nx / len);
            out[1] = (float)(0.5 + 0.5 * ny / len);
            out[2] = (float)(0.5 + 0.5 / len);
        } else {
            for (int c = 0; c < f->nc; c++)
                out[c] = (float)g[c];
        }
    }
}

static void dnoise_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                         float *out)
{
    dnoise_eval3(f, n, u, v, NULL, out);
}

/* Grid rows: the gradient from the vectorised rows (float, within about 1e-5
 * of the points' double), then interleaved or made a normal. */
static void dnoise_row(const struct tex_field *f, int y, float *out)
{
    const struct dnoise_params *p = f->params;
    const struct noise_state *s = f->state;
    float *d = malloc(3 * (size_t)f->w * sizeof *d), S = (float)p->strength;

    if (!d) { /* no memory for the row buffers: the point path needs none */
        for (int x = 0; x < f->w; x++) {
            double u = (x + 0.5) / f->w, v = (y + 0.5) / f->h;
            dnoise_eval2(f, 1, &u, &v, out + (size_t)x * f->nc);
        }
        return;
    }
    tex_noise_grid_row_grad(&s->g, y, d, d + f->w, f->nc == 3 && !p->normal ? d + 2 * f->w : NULL);
    for (int x = 0; x < f->w; x++, out += f->nc) {
        float gx = d[x], gy = d[f->w + x];
        if (p->normal) {
            /* v grows downwards: the height's slope along y-up is -dn/dv. */
            float nx = -S * gx, ny = S * gy, len = sqrtf(nx * nx + ny * ny + 1);
            out[0] = 0.5f + 0.5f * (nx / len);
            out[1] = 0.5f + 0.5f * (ny / len);
            out[2] = 0.5f + 0.5f / len;
        } else {
            out[0] = gx;
            out[1] = gy;
            if (f->nc == 3)
                out[2] = d[2 * f->w + x];
        }
    }
    free(d);
}

const struct tex_primitive tex_prim_d_noise = {
    .name = "d_noise",
    .summary = "the analytic gradient of gradient noise, or a normal map from it",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct dnoise_params),
    .params = dnoise_rows,
    .init = dnoise_init,
    .fini = noise_fini,
    .eval2 = dnoise_eval2,
    .eval3 = dnoise_eval3,
    .row = dnoise_row,
};
