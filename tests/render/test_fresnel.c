/* test_fresnel.c - Fresnel reflectance: normal and grazing incidence, energy, exactness */
#include "render/fresnel.h"
#include "unit.h"

#include <complex.h>
#include <math.h>

/* Reference: the Fresnel amplitudes computed with complex arithmetic. */
static double complex_fresnel(double ci, double eta_i, double n, double k)
{
    double complex nt = n + I * k;
    double si2 = 1 - ci * ci;
    double complex ct = csqrt(1 - eta_i * eta_i * si2 / (nt * nt));
    double complex rs = (eta_i * ci - nt * ct) / (eta_i * ci + nt * ct);
    double complex rp = (nt * ci - eta_i * ct) / (nt * ci + eta_i * ct);
    return 0.5 * (creal(rs * conj(rs)) + creal(rp * conj(rp)));
}

int main(void)
{
    const double nk[][2] = {{0.14, 3.697}, {0.05, 3.093}, {1.175, 2.13}, {0.963, 6.7},
                            {3.18, 4.41},  {1.5, 0},      {0.5, 0.5}};
    for (unsigned i = 0; i < sizeof nk / sizeof nk[0]; i++) {
        double n = nk[i][0], k = nk[i][1];
        double want = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
        double got = tex_fresnel_conductor(1, 1, n, k);
        CHECKF(fabs(got - want) < 1e-12, "conductor n=%g k=%g at normal incidence %.6f = %.6f",
               n, k, got, want);
        double graze = tex_fresnel_conductor(1e-6, 1, n, k);
        CHECKF(graze > 0.9999, "conductor n=%g k=%g tends to 1 at grazing incidence (%.6f)", n,
               k, graze);
        double worst = 0;
        for (int a = 0; a <= 90; a++) {
            double c = cos(a * M_PI / 180);
            double d = fabs(tex_fresnel_conductor(c, 1, n, k) - complex_fresnel(c, 1, n, k));
            worst = fmax(worst, d);
        }
        CHECKF(worst < 1e-9, "conductor n=%g k=%g matches complex Fresnel at 0..90 deg (%.2g)",
               n, k, worst);
    }
    /* From glass (eta_i = 1.5) onto gold: the general incident medium. */
    double c = cos(0.7);
    CHECKF(fabs(tex_fresnel_conductor(c, 1.5, 0.43, 2.455) - complex_fresnel(c, 1.5, 0.43, 2.455)) <
               1e-9,
           "conductor seen from glass matches complex Fresnel");

    /* Dielectric. */
    double worst = 0, ft;
    for (int a = 0; a <= 90; a++) {
        double ci = cos(a * M_PI / 180);
        double fr = tex_fresnel_dielectric(ci, 1, 1.5, &ft);
        worst = fmax(worst, fabs(fr + ft - 1));
        fr = tex_fresnel_dielectric(ci, 1.5, 1, &ft);
        worst = fmax(worst, fabs(fr + ft - 1));
    }
    CHECKF(worst < 1e-12, "dielectric Fr + Ft = 1 both ways at 0..90 deg (%.2g)", worst);
    double f0 = tex_fresnel_dielectric(1, 1, 1.5, NULL);
    CHECKF(fabs(f0 - 0.04) < 1e-12, "air->glass normal incidence 0.04 (%.6f)", f0);
    CHECKF(tex_fresnel_dielectric(1e-7, 1, 1.5, NULL) > 0.9999, "air->glass grazing -> 1");
    double crit = asin(1 / 1.5);
    CHECK(tex_fresnel_dielectric(cos(crit + 0.01), 1.5, 1, &ft) == 1 && ft == 0,
          "glass->air beyond the critical angle: total internal reflection");
    CHECK(tex_fresnel_dielectric(cos(crit - 0.01), 1.5, 1, &ft) < 1 && ft > 0,
          "glass->air just inside the critical angle transmits");
    /* Brewster's angle: r_par = 0, so Fr = r_perp^2 / 2. */
    double tb = atan(1.5), ct = cos(M_PI / 2 - tb);
    double rperp = (cos(tb) - 1.5 * ct) / (cos(tb) + 1.5 * ct);
    double fb = tex_fresnel_dielectric(cos(tb), 1, 1.5, NULL);
    CHECKF(fabs(fb - 0.5 * rperp * rperp) < 1e-12, "Brewster angle: only r_perp reflects (%.6f)",
           fb);
    worst = 0;
    for (int a = 0; a <= 89; a++) {
        double ci = cos(a * M_PI / 180);
        worst = fmax(worst, fabs(tex_fresnel_conductor(ci, 1, 1.5, 0) -
                                 tex_fresnel_dielectric(ci, 1, 1.5, NULL)));
    }
    CHECKF(worst < 1e-12, "conductor formula with k = 0 equals the dielectric (%.2g)", worst);

    /* The seed's approximation (eq. 8) is close only when n^2 + k^2 >> 1. */
    double dal = 0, dlow = 0;
    for (int a = 0; a <= 85; a += 5) {
        double ci = cos(a * M_PI / 180);
        dal = fmax(dal, fabs(tex_fresnel_conductor_approx(ci, 0.963, 6.7) -
                             tex_fresnel_conductor(ci, 1, 0.963, 6.7)));
        dlow = fmax(dlow, fabs(tex_fresnel_conductor_approx(ci, 1.5, 0.1) -
                               tex_fresnel_conductor(ci, 1, 1.5, 0.1)));
    }
    CHECKF(dal < 0.01, "approximation within 0.01 for aluminium, n^2+k^2 = 46 (%.4f)", dal);
    CHECKF(dlow > 0.05, "approximation off by > 0.05 for n=1.5 k=0.1 (%.4f)", dlow);

    float n[3] = {0.14f, 0.43f, 1.46f}, k[3] = {3.697f, 2.455f, 1.933f}, out[3];
    tex_fresnel_conductor_n(0.8, 1, n, k, 3, out);
    CHECK(fabs(out[1] - tex_fresnel_conductor(0.8, 1, 0.43, 2.455)) < 1e-6,
          "per-sample conductor Fresnel matches the scalar one");
    return unit_done();
}
