/* trig.c - sines and angles of many points (trig.h) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdint.h>

#include "base/simd.h"
#include "base/trig.h"
#include "base/trig_fdlibm.h"
#include "base/x86/trig_x86.h"

void tex_sin_n(int n, const double *x, double *out, int quarter)
{
    int i = 0;
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2) {
        tex_sin_avx2(n, x, out, quarter);
        i = n & ~3;
    }
#endif
    for (; i < n; i++)
        out[i] = sin1(x[i], quarter);
}

/* ---- angles ----------------------------------------------------------------------- */

double tex_atan2(double y, double x)
{
    double ax = fabs(x), ay = fabs(y);
    int swap = ay > ax, red;
    double num = swap ? ax : ay, den = swap ? ay : ax; /* t = num / den in [0, 1] */
    red = num > TAN_PI8 * den;                          /* then (t - 1) / (t + 1) */
    double a = red ? num - den : num, b = red ? num + den : den;
    double t = b == 0 ? 0 : a / b, z = t * t, w = z * z;
    double s1 = z * (AT[0] + w * (AT[2] + w * (AT[4] + w * (AT[6] + w * (AT[8] + w * AT[10])))));
    double s2 = w * (AT[1] + w * (AT[3] + w * (AT[5] + w * (AT[7] + w * AT[9]))));
    double r = t - t * (s1 + s2);
    r = red ? PIO4 + r : r;
    r = swap ? PIO2 - r : r;
    r = signbit(x) ? PI - r : r;
    return signbit(y) ? -r : r;
}

void tex_atan2_n(int n, const double *y, const double *x, double *out)
{
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX512) {
        tex_atan2_n_avx512(n, y, x, out);
        return;
    }
#endif
    for (int i = 0; i < n; i++)
        out[i] = tex_atan2(y[i], x[i]);
}
