/* fresnel.c - Fresnel reflectance of dielectrics and conductors */
#include "render/fresnel.h"

#include <math.h>

static double clamp01(double x)
{
    return x < 0 ? 0 : x > 1 ? 1 : x;
}

double tex_fresnel_dielectric(double cos_i, double eta_i, double eta_t, double *ft)
{
    cos_i = clamp01(cos_i);
    double sin_i2 = 1 - cos_i * cos_i;
    double r = eta_i / eta_t;
    double sin_t2 = r * r * sin_i2;
    if (sin_t2 >= 1) { /* total internal reflection */
        if (ft)
            *ft = 0;
        return 1;
    }
    double cos_t = sqrt(1 - sin_t2);
    double rpar = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    double rperp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    double fr = clamp01(0.5 * (rpar * rpar + rperp * rperp));
    if (ft)
        *ft = 1 - fr;
    return fr;
}

double tex_fresnel_conductor(double cos_i, double eta_i, double n, double k)
{
    double c = clamp01(cos_i);
    double c2 = c * c, s2 = 1 - c2;
    double eta = n / eta_i, kap = k / eta_i;
    double e2 = eta * eta, k2 = kap * kap;
    double t0 = e2 - k2 - s2;
    double a2b2 = sqrt(t0 * t0 + 4 * e2 * k2);
    double a = sqrt(fmax(0, 0.5 * (a2b2 + t0)));
    double t1 = a2b2 + c2, t2 = 2 * a * c;
    double rs = (t1 - t2) / (t1 + t2);
    double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
    /* At grazing incidence t3 + t4 can vanish only when c = 0 and s2 = 0, impossible. */
    double rp = rs * (t3 - t4) / (t3 + t4);
    return clamp01(0.5 * (rs + rp));
}

double tex_fresnel_conductor_approx(double cos_i, double n, double k)
{
    double c = clamp01(cos_i);
    double nk = n * n + k * k;
    double rpar2 = (nk * c * c - 2 * n * c + 1) / (nk * c * c + 2 * n * c + 1);
    double rperp2 = (nk - 2 * n * c + c * c) / (nk + 2 * n * c + c * c);
    return clamp01(0.5 * (rpar2 + rperp2));
}

void tex_fresnel_conductor_n(double cos_i, double eta_i, const float *n, const float *k,
                             int count, float *out)
{
    for (int i = 0; i < count; i++)
        out[i] = (float)tex_fresnel_conductor(cos_i, eta_i, n[i], k[i]);
}
