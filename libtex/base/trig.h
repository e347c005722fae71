/* trig.h - sines, cosines and angles of many points, the same bytes everywhere
 *
 *   tex_sin_n(n, x, out, 0);   // out[i] = sin(x[i])
 *   tex_sin_n(n, x, out, 1);   // out[i] = cos(x[i])
 *   a = tex_atan2(y, x);       // atan2(y, x)
 *   tex_atan2_n(n, y, x, out); // out[i] = atan2(y[i], x[i])
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
 *
 * The natural mappings take their angles (u around a sphere's or a cylinder's
 * axis, v down a sphere) here, eight at a time with AVX-512.  The smaller of
 * |x| and |y| over the larger is brought below tan(pi/8) by (t - 1)/(t + 1),
 * one division either way, and goes through fdlibm's polynomial for atan on
 * |t| < 7/16; the octant adds pi/4, pi/2 and pi and the signs.  Results are
 * within 2^-51 of libm's (the unit test measures it); NaN gives NaN, and two
 * infinities NaN where libm gives a multiple of pi/4.
 */
#ifndef TEX_TRIG_H
#define TEX_TRIG_H

#include "api.h"

TEX_API_BEGIN

/* out[i] = sin(x[i] + quarter pi/2) for i < n: quarter 0 sine, 1 cosine. out may be x. */
void tex_sin_n(int n, const double *x, double *out, int quarter);

/* The angle of (x, y) from the x axis, in [-pi, pi], as atan2(y, x) (its signed zeros too) */
double tex_atan2(double y, double x);
/* out[i] = tex_atan2(y[i], x[i]) for i < n, eight at a time where the CPU has AVX-512. */
void tex_atan2_n(int n, const double *y, const double *x, double *out);

TEX_API_END
#endif
