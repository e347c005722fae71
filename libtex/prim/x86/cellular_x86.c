/* cellular_x86.c - the candidate lists' lanes in 32-byte AVX2 vectors, and SSE2 roots */
#include <math.h>

#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "prim/cellular_impl.h"
#include "prim/x86/cellular_x86.h"

#ifdef HAVE_AVX2_KERNEL
/* Without the index, the selections of lanes() are single AVX instructions:
 * vminpd(x, y) is x < y ? x : y and vmaxpd(x, y) is x > y ? x : y, so
 *   A1' = lt ? a : A1           = min(a, A1)
 *   A2' = min(lt ? A1 : a, A2)  = min(max(A1, a), A2)
 * with lt = a < A1: the same values as lanes(), in 3 operations, not 5. */
TEX_AVX2 __attribute__((always_inline)) static inline void
lanes_minmax(const double *cx, const double *cy, long t0, long e, const double *qx,
             const double *qy, const int nv, const int want_f2, double *a1, double *a2)
{
    __m256d X[4], Y[4], A1[4], A2[4];

#pragma GCC unroll 4
    for (int v = 0; v < nv; v++) {
        X[v] = _mm256_loadu_pd(qx + 4 * v);
        Y[v] = _mm256_loadu_pd(qy + 4 * v);
        A1[v] = A2[v] = _mm256_set1_pd(INFINITY);
    }
    for (long t = t0; t < e; t++) {
        __m256d px = _mm256_broadcast_sd(cx + t), py = _mm256_broadcast_sd(cy + t);
#pragma GCC unroll 4
        for (int v = 0; v < nv; v++) {
            __m256d dx = _mm256_sub_pd(X[v], px), dy = _mm256_sub_pd(Y[v], py);
            __m256d a = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
            if (want_f2)
                A2[v] = _mm256_min_pd(_mm256_max_pd(A1[v], a), A2[v]);
            A1[v] = _mm256_min_pd(a, A1[v]);
        }
    }
#pragma GCC unroll 4
    for (int v = 0; v < nv; v++) {
        _mm256_storeu_pd(a1 + 4 * v, A1[v]);
        if (want_f2)
            _mm256_storeu_pd(a2 + 4 * v, A2[v]);
    }
}

#define MINMAX_CASE(k)                                                                        \
    case k:                                                                                   \
        lanes_minmax(cx, cy, t0, e, qx, qy, (k) / 2 + 1, (k)&1, a1, a2);                     \
        break;

/* The same lanes in 32-byte AVX2 vectors, chosen at run time.  AVX2 alone
 * brings no fused multiply-add, so each lane rounds as the SSE2 code does. */
TEX_AVX2 void tex_cellular_lanes_avx2(const double *cx, const double *cy, const long *cid, long t0,
                                      long e, const double *qx, const double *qy, int nv,
                                      int want_id, int want_f2, int roots, double *a1, double *a2,
                                      long *i1)
{
    if (want_id) {
        LANES_SWITCH
    } else {
        switch ((nv - 1) * 2 + want_f2) {
            MINMAX_CASE(0) MINMAX_CASE(1) MINMAX_CASE(2) MINMAX_CASE(3) MINMAX_CASE(4)
            MINMAX_CASE(5) MINMAX_CASE(6) MINMAX_CASE(7)
        }
    }
    for (int l = 0; roots && l < 4 * nv; l += 4) {
        _mm256_storeu_pd(a1 + l, _mm256_sqrt_pd(_mm256_loadu_pd(a1 + l)));
        if (want_f2)
            _mm256_storeu_pd(a2 + l, _mm256_sqrt_pd(_mm256_loadu_pd(a2 + l)));
    }
}

void tex_cellular_roots_sse2(double *a1, double *a2, int n)
{
    for (int l = 0; l < n; l += 2) {
        _mm_storeu_pd(a1 + l, _mm_sqrt_pd(_mm_loadu_pd(a1 + l)));
        if (a2)
            _mm_storeu_pd(a2 + l, _mm_sqrt_pd(_mm_loadu_pd(a2 + l)));
    }
}
#endif
#endif
