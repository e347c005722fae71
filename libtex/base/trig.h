/* trig.h - sines and cosines of many points, the same bytes everywhere
 *
 *   tex_sin_n(n, x, out, 0);   // out[i] = sin(x[i])
 *   tex_sin_n(n, x, out, 1);   // out[i] = cos(x[i])
 *
 * The primitives whose value is a sum of sines (colour variation, the
 * perturbed pattern) take their sines here, four points at a time with AVX2.
 * x is reduced by pi/2 (Cody and Waite: pi/2 in three pieces of 33 bits, so
 * k pi/2 is exact for the k that arise) and the remainder r, |r| <= pi/4,
 * goes through fdlibm's polynomials for sin r and cos r; the quadrant picks
 * one and its sign.  Results are within 2^-52 of the true values (the unit
 * test compares a million points with libm's: 2^-53 at worst).
 * Every SIMD level performs the same double operations in the same order,
 * and no libm call is made for |x| <= 2^19, so the bytes depend neither on
 * the CPU nor on the C library; beyond (and for infinities and NaN) the
 * value is libm's.
 */
#ifndef TEX_TRIG_H
#define TEX_TRIG_H

#ifdef __cplusplus
extern "C" {
#endif

/* out[i] = sin(x[i] + quarter pi/2) for i < n: quarter 0 sine, 1 cosine. out may be x. */
void tex_sin_n(int n, const double *x, double *out, int quarter);

#ifdef __cplusplus
}
#endif
#endif
