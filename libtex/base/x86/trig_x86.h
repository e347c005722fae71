/* trig_x86.h - trig.c's kernels for x86: sines four at a time (AVX2), angles eight (AVX-512)
 *
 * Called by trig.c where tex_simd_level() allows; the same doubles as its scalar
 * definitions, operation for operation (../trig_fdlibm.h).
 */
#ifndef TEX_TRIG_X86_H
#define TEX_TRIG_X86_H

/* tex_sin_n's first n - n % 4 values (AVX2) */
void tex_sin_avx2(int n, const double *x, double *out, int quarter);
/* tex_atan2_n of all n (AVX-512, the last lanes masked) */
void tex_atan2_n_avx512(int n, const double *y, const double *x, double *out);

#endif
