/* noise_x86.c - noise.c's grid rows and its other kernels for x86: rows eight pixels at a
 * time (AVX2) and sixteen (AVX-512), the lattice rows' folds four slots at a time (SSE),
 * the gradient's rows, the band limit's weights */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <limits.h>
#include <math.h>
#include <string.h>

#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "prim/noise_grid.h"
#include "prim/x86/noise_columns.h"
#include "prim/x86/noise_x86.h"

/* ---- lattice rows (SSE, x86-64's baseline) ---- */

/* Slots s.. of lattice_row_n four at a time, nz corners: the same operations, element by
 * element, the four transposed */
static inline __attribute__((always_inline)) int
lattice_sse_n(const tex_noise_grid *g, const float (*zm)[4], const int *A, const int32_t *lat,
              int s0, int s1, float *X, float *Y, float *C, const int nz)
{
    const int *F = g->t->perm;
    const float(*G)[4] = g->dims == 4 ? g->t->grad4 : g->t->grad;
    int s = s0;
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
    return s;
}

int tex_noise_lattice_sse(const tex_noise_grid *g, const float (*zm)[4], int lj,
                          const int32_t *lat, int s0, int s1, float *X, float *Y, float *C)
{
    const int *F = g->t->perm;
    int A[4];

    for (int c = 0; c < g->nz; c++)
        A[c] = F[lj + g->zh[c]];
    /* One copy per number of corners, so that the sums stay in registers. */
    switch (g->nz) {
    case 1:
        return lattice_sse_n(g, zm, A, lat, s0, s1, X, Y, C, 1);
    case 2:
        return lattice_sse_n(g, zm, A, lat, s0, s1, X, Y, C, 2);
    case 3:
        return lattice_sse_n(g, zm, A, lat, s0, s1, X, Y, C, 3);
    default:
        return lattice_sse_n(g, zm, A, lat, s0, s1, X, Y, C, 4);
    }
}

int tex_noise_lut_sse(const float (*T)[4], const int32_t *lat, int s0, int s1, float *X, float *Y,
                      float *C)
{
    int s = s0;

    for (; s + 4 <= s1; s += 4) {
        __m128 a0 = _mm_loadu_ps(T[lat[s]]), a1 = _mm_loadu_ps(T[lat[s + 1]]);
        __m128 a2 = _mm_loadu_ps(T[lat[s + 2]]), a3 = _mm_loadu_ps(T[lat[s + 3]]);
        _MM_TRANSPOSE4_PS(a0, a1, a2, a3);
        _mm_storeu_ps(X + s - s0, a0);
        _mm_storeu_ps(Y + s - s0, a1);
        _mm_storeu_ps(C + s - s0, a2);
    }
    return s;
}

/* ---- rows eight pixels at a time (AVX2) ---- */

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

TEX_AVX2 static inline __attribute__((always_inline)) __m256 abs_avx2(__m256 v)
{
    return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v);
}

/* apply_op on eight pixels of each row */
#define APPLY_NAME apply_avx2
#define APPLY_ATTR TEX_AVX2
#define APPLY_V __m256
#define APPLY_MIN _mm256_min_ps
#define APPLY_MAX _mm256_max_ps
#define APPLY_ABS abs_avx2
#define APPLY_ROWWISE 0
#include "prim/x86/noise_apply_template.c"

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


#define FOLD_NAME fold_row_avx2
#define FOLD_AT fold_row_avx2_at
#define FOLD_ATTR TEX_AVX2
#define FOLD_V __m256
#include "prim/x86/noise_fold_template.c"

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

/* ---- the rows sixteen pixels at a time (AVX-512): the AVX2 kernels' operations ---- */

/* apply_op on sixteen pixels of each row */
#define APPLY_NAME apply_avx512
#define APPLY_ATTR TEX_AVX512
#define APPLY_V __m512
#define APPLY_MIN _mm512_min_ps
#define APPLY_MAX _mm512_max_ps
#define APPLY_ABS _mm512_abs_ps
#define APPLY_ROWWISE 1
#include "prim/x86/noise_apply_template.c"

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

#define FOLD_NAME fold_row_avx512
#define FOLD_AT fold_row_avx512_at
#define FOLD_ATTR TEX_AVX512
#define FOLD_V __m512
#include "prim/x86/noise_fold_template.c"

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
 * table where there are two: faster than permutes of two registers) */
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

/* Rows of a grid at each level: the template's steps with the level's kernels */
#define GRID_ROW grid_rows_avx2
#define GRID_ATTR TEX_AVX2 static
#define GRID_COEFFS row_coeffs_avx2
#define GRID_PIXELS row_avx2
#define GRID_LUT_ROW row_lut_avx2
#include "prim/noise_row_template.c"
#define GRID_ROW grid_rows_avx512
#define GRID_ATTR TEX_AVX512 static
#define GRID_COEFFS row_coeffs_avx512
#define GRID_PIXELS row_avx512
#define GRID_LUT_ROW row_lut_avx512
#include "prim/noise_row_template.c"

/* The entry points, which tell the kernels that rows is 1 or FOLD_ROWS (what the callers
 * pass): the kernels' loops over rows and their row buffers are compiled for those alone,
 * as when the rows came from noise.c's grid_rows_k in the same file. */
TEX_AVX2 void tex_noise_grid_rows_avx2(const tex_noise_grid *g, int y, int rows, int op,
                                       struct row_k rk, float *const *out)
{
    grid_rows_avx2(g, y, rows > 1 ? FOLD_ROWS : 1, op, rk, out);
}

TEX_AVX512 void tex_noise_grid_rows_avx512(const tex_noise_grid *g, int y, int rows, int op,
                                           struct row_k rk, float *const *out)
{
    grid_rows_avx512(g, y, rows > 1 ? FOLD_ROWS : 1, op, rk, out);
}

/* ---- the analytic gradient over a row ---- */

TEX_AVX2 void tex_noise_grad_avx2(const tex_noise_grid *g, const float *const C[6], int sb,
                                  float *dx, float *dy, float *dz, int x, int x1)
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
    tex_noise_grad_scalar(g, C, sb, dx, dy, dz, x, x1);
}

/* ---- the band limit ---- */

/* band_weights' first n - n % 4 */
TEX_AVX2 int tex_noise_band_weights_avx2(int n, const double *fw, double fk, float *wt)
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
