/* remap_x86.c - remap.c's gamma eight values at a time (AVX-512) */
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <string.h>

#include "base/x86/simd_x86.h"
#include "ops/remap.h"

#ifdef TEX_X86
#include "ops/x86/remap_x86.h"

/* Gamma eight values at a time (AVX-512).  pow(x, y), x in (0, 1], 0 < y <= 64, as
 * 2^(y log2 x): log2 from a table of 16 centres c and ln(1 + r), |r| <= 1/32, to degree 10;
 * 2^z from a table of 2^(j/16) and exp(g), |g| <= ln 2 / 32, to degree 7.  Their relative
 * error stays below 1e-11 (y times 4 ulp of |log2 x| <= 150 in the exponent, z >= -1000),
 * so that where pow's value times (1 -+ REL) gives one float after the later operations
 * (monotonic: quantise, invert, clamp), that float is pow's, as the scalar path has it;
 * elsewhere (about 1 value in 300), and for z < -1000, the scalar path decides. */
enum { POW_TABLE = 16 };
#define POW_REL 1e-10
static double pow_c[POW_TABLE], pow_log2c[POW_TABLE], pow_inv_c[POW_TABLE], pow_exp2[POW_TABLE];
static pthread_once_t pow_once = PTHREAD_ONCE_INIT;
/* ln(1 + r) / r = 1 - r/2 + r^2/3 ..., and exp(g) = sum g^k / k! */
static const double pow_ln[10] = {1.0,      -1.0 / 2, 1.0 / 3,  -1.0 / 4, 1.0 / 5,
                                  -1.0 / 6, 1.0 / 7,  -1.0 / 8, 1.0 / 9,  -1.0 / 10};
static const double pow_exp[8] = {1.0,      1.0,       1.0 / 2,   1.0 / 6,
                                  1.0 / 24, 1.0 / 120, 1.0 / 720, 1.0 / 5040};

static void pow_setup(void)
{
    for (int i = 0; i < POW_TABLE; i++) {
        double c = pow_c[i] = 1 + (i + 0.5) / POW_TABLE;
        pow_log2c[i] = log2(c);
        pow_inv_c[i] = 1 / c;
        pow_exp2[i] = exp2((double)i / POW_TABLE);
    }
}

/* A table of 16 doubles read at lanes' indices */
TEX_AVX512 static inline __m512d table16(const double *t, __m512i i)
{
    return _mm512_permutex2var_pd(_mm512_loadu_pd(t), i, _mm512_loadu_pd(t + 8));
}

/* pow(x, y) as above for x in (0, 1]; *ok: the lanes it serves (x normal, z >= -1000) */
TEX_AVX512 static __m512d pow8(__m512d x, double y, __mmask8 *ok)
{
    __m512i bits = _mm512_castpd_si512(x);
    __m512d e = _mm512_cvtepi32_pd(_mm512_cvtepi64_epi32(
        _mm512_sub_epi64(_mm512_srli_epi64(bits, 52), _mm512_set1_epi64(1023))));
    __m512i i = _mm512_and_si512(_mm512_srli_epi64(bits, 52 - 4), _mm512_set1_epi64(15));
    __m512d m = _mm512_castsi512_pd(_mm512_or_si512(
        _mm512_and_si512(bits, _mm512_set1_epi64((INT64_C(1) << 52) - 1)),
        _mm512_set1_epi64(INT64_C(1023) << 52)));
    __m512d r = _mm512_mul_pd(_mm512_sub_pd(m, table16(pow_c, i)), table16(pow_inv_c, i)), p;
    p = _mm512_set1_pd(pow_ln[9]);
#pragma GCC unroll 9
    for (int k = 8; k >= 0; k--)
        p = _mm512_add_pd(_mm512_set1_pd(pow_ln[k]), _mm512_mul_pd(r, p));
    __m512d lg = _mm512_add_pd(_mm512_add_pd(e, table16(pow_log2c, i)),
                               _mm512_mul_pd(_mm512_mul_pd(r, p), _mm512_set1_pd(1 / M_LN2)));
    __m512d z = _mm512_mul_pd(_mm512_set1_pd(y), lg);
    *ok = _mm512_cmp_pd_mask(z, _mm512_set1_pd(-1000), _CMP_GE_OQ) & /* x normal */
          _mm512_cmp_pd_mask(x, _mm512_set1_pd(DBL_MIN), _CMP_GE_OQ);
    z = _mm512_max_pd(z, _mm512_set1_pd(-1000));
    __m512d n = _mm512_roundscale_pd(_mm512_mul_pd(z, _mm512_set1_pd(POW_TABLE)),
                                     _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    __m512d g = _mm512_mul_pd(_mm512_sub_pd(z, _mm512_mul_pd(n, _mm512_set1_pd(1.0 / POW_TABLE))),
                              _mm512_set1_pd(M_LN2));
    __m512d q = _mm512_set1_pd(pow_exp[7]);
#pragma GCC unroll 7
    for (int k = 6; k >= 0; k--)
        q = _mm512_add_pd(_mm512_set1_pd(pow_exp[k]), _mm512_mul_pd(g, q));
    __m256i ni = _mm512_cvtpd_epi32(n); /* exact: n is an integer */
    __m512i j = _mm512_cvtepi32_epi64(_mm256_and_si256(ni, _mm256_set1_epi32(POW_TABLE - 1)));
    __m512i k2 = _mm512_slli_epi64(
        _mm512_cvtepi32_epi64(_mm256_add_epi32(_mm256_srai_epi32(ni, 4), _mm256_set1_epi32(1023))),
        52);
    return _mm512_mul_pd(_mm512_mul_pd(table16(pow_exp2, j), q), _mm512_castsi512_pd(k2));
}

TEX_AVX512 static inline __m512d unit8(__m512d t) /* unit's, lane by lane (NaN -> 0) */
{
    __mmask8 above = _mm512_cmp_pd_mask(t, _mm512_setzero_pd(), _CMP_GT_OQ);
    __mmask8 below1 = _mm512_cmp_pd_mask(t, _mm512_set1_pd(1.0), _CMP_LT_OQ);
    return _mm512_maskz_mov_pd(above, _mm512_mask_blend_pd(below1, _mm512_set1_pd(1.0), t));
}

/* tex_remap_value's quantise, invert and clamp, lane by lane */
TEX_AVX512 static inline __m512d after_gamma8(const struct tex_remap *r, __m512d v)
{
    if (r->quantize >= 2) {
        __m512d q = _mm512_set1_pd(r->quantize), q1 = _mm512_set1_pd(r->quantize - 1);
        __m512d k = _mm512_roundscale_pd(_mm512_mul_pd(unit8(v), q),
                                         _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
        k = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(k, q, _CMP_LT_OQ), q1, k);
        v = _mm512_div_pd(k, q1);
    }
    if (r->invert)
        v = _mm512_sub_pd(_mm512_set1_pd(1.0), v);
    if (r->clamp) {
        __m512d lo = _mm512_set1_pd(r->lo), hi = _mm512_set1_pd(r->hi);
        __mmask8 low = _mm512_cmp_pd_mask(v, lo, _CMP_LT_OQ);
        __mmask8 high = _mm512_cmp_pd_mask(v, hi, _CMP_GT_OQ);
        v = _mm512_mask_blend_pd(low, _mm512_mask_blend_pd(high, v, hi), lo);
    }
    return v;
}

/* Eight values of a remap whose one power is its gamma (gamma_alone): levels as the scalar
 * path has them, pow8 with the bounds of pow's value carried through the rest */
TEX_AVX512 static void gamma8(const struct tex_remap *r, float *px)
{
    __m512d v = _mm512_cvtps_pd(_mm256_loadu_ps(px)), one = _mm512_set1_pd(1.0);
    if (r->in0 != 0 || r->in1 != 1 || r->out0 != 0 || r->out1 != 1) {
        __m512d t = _mm512_div_pd(_mm512_sub_pd(v, _mm512_set1_pd(r->in0)),
                                  _mm512_set1_pd(r->in1 - r->in0));
        v = _mm512_add_pd(_mm512_set1_pd(r->out0),
                          _mm512_mul_pd(unit8(t), _mm512_set1_pd(r->out1 - r->out0)));
    }
    __m512d x = unit8(v);
    __mmask8 zero = _mm512_cmp_pd_mask(x, _mm512_setzero_pd(), _CMP_EQ_OQ), ok;
    __m512d a = _mm512_maskz_mov_pd(~zero, pow8(_mm512_mask_blend_pd(zero, x, one),
                                                1 / r->gamma, &ok)); /* pow(0, y) = 0 */
    __m256 lo = _mm512_cvtpd_ps(after_gamma8(r, _mm512_mul_pd(a, _mm512_set1_pd(1 - POW_REL))));
    __m256 hi = _mm512_cvtpd_ps(after_gamma8(r, _mm512_mul_pd(a, _mm512_set1_pd(1 + POW_REL))));
    int done = _mm256_movemask_ps(_mm256_cmp_ps(lo, hi, _CMP_EQ_OQ)) & (ok | zero);
    float in[8];
    memcpy(in, px, sizeof in);
    _mm256_storeu_ps(px, lo);
    for (int k = 0; k < 8; k++)
        if (!(done >> k & 1))
            px[k] = (float)tex_remap_value(r, in[k]);
}

size_t tex_remap_gamma_avx512(const struct tex_remap *r, float *px, size_t n)
{
    size_t runs = n / 8;
    pthread_once(&pow_once, pow_setup);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < runs; i++)
        gamma8(r, px + 8 * i);
    return 8 * runs;
}
#endif
