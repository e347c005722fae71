/* trig_fdlibm.h - the reduction and polynomials of trig.c, shared with its x86 kernels
 *
 * Internal to libtex (not installed): trig.c's scalar sine and angle and the
 * vector kernels of x86/trig_x86.c perform the same double operations in the
 * same order on these constants, so every level gives the same bytes.
 * Sines: x reduced by pi/2 (Cody and Waite, pi/2 in three pieces of 33 bits),
 * the remainder through fdlibm's kernels for sin and cos on |r| <= pi/4.
 * Angles: fdlibm's atan on |t| < 7/16.
 */
#ifndef TEX_TRIG_FDLIBM_H
#define TEX_TRIG_FDLIBM_H

#include <math.h>

#define BIG 0x1p19           /* past it, libm's sine */
#define ROUND 0x1.8p52       /* x + ROUND - ROUND: x rounded to a whole number, |x| < 2^51 */
#define INV_PIO2 6.36619772367581382433e-01
#define PIO2_1 1.57079632673412561417e+00 /* pi/2 in three pieces of 33 bits */
#define PIO2_2 6.07710050630396597660e-11
#define PIO2_3 2.02226624871116645580e-21

/* fdlibm's kernels: sin r = r + r^3 (S1 + z S(z)), cos r = 1 - z/2 + z^2 C(z), z = r^2 */
static const double S[6] = {-1.66666666666666324348e-01, 8.33333333332248946124e-03,
                            -1.98412698298579493134e-04, 2.75573137070700676789e-06,
                            -2.50507602534068634195e-08, 1.58969099521155010221e-10};
static const double C[6] = {4.16666666666666019037e-02,  -1.38888888888741095749e-03,
                            2.48015872894767294178e-05,  -2.75573143513906633035e-07,
                            2.08757232129817482790e-09,  -1.13596475577881948265e-11};

/* One sine (quarter 0) or cosine (1), in the operations of tex_sin_avx2's lanes. */
static inline double sin1(double x, int quarter)
{
    if (!(fabs(x) <= BIG))
        return quarter ? cos(x) : sin(x);
    double k = x * INV_PIO2 + ROUND - ROUND;
    double r = x - k * PIO2_1 - k * PIO2_2 - k * PIO2_3;
    double kq = k + quarter, q = kq - 4 * (kq * 0.25 - 0.375 + ROUND - ROUND); /* kq mod 4 */
    double z = r * r;
    double sr = r + z * r * (S[0] + z * (S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])))));
    double hz = 0.5 * z, w = 1 - hz;
    double cp = z * (C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5])))));
    double cr = w + ((1 - w - hz) + z * cp);
    double v = q == 1 || q == 3 ? cr : sr;
    return q >= 2 ? -v : v;
}

#define TAN_PI8 4.14213562373095034e-01 /* tan(pi/8), below it */
#define PIO4 7.85398163397448278999e-01
#define PIO2 1.57079632679489655800e+00
#define PI 3.14159265358979311600e+00

/* fdlibm's atan on |t| < 7/16: t - t (z (T0 + w (T2 + ...)) + w (T1 + w (T3 + ...))),
 * z = t^2, w = z^2 */
static const double AT[11] = {3.33333333333329318027e-01,  -1.99999999998764832476e-01,
                              1.42857142725034663711e-01,  -1.11111104054623557880e-01,
                              9.09088713343650656196e-02,  -7.69187620504482999495e-02,
                              6.66107313738753120669e-02,  -5.83357013379057348645e-02,
                              4.97687799461593236017e-02,  -3.65315727442169155270e-02,
                              1.62858201153657823623e-02};

#endif
