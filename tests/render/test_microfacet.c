/* test_microfacet.c - facet distributions, beta relations, Torrance-Sparrow G, energy */
#include "render/microfacet.h"
#include "unit.h"

#include <math.h>

/* Integral over the hemisphere of D(cos t) cos t, by the midpoint rule in t. */
static double hemi(double (*d)(double, double), double p)
{
    const int steps = 200000;
    double h = (M_PI / 2) / steps, s = 0;
    for (int i = 0; i < steps; i++) {
        double t = (i + 0.5) * h;
        s += d(cos(t), p) * cos(t) * sin(t);
    }
    return 2 * M_PI * s * h;
}

int main(void)
{
    const double ms[] = {0.05, 0.2, 0.5, 0.9};
    for (int i = 0; i < 4; i++) {
        double v = hemi(tex_beckmann_d, ms[i]);
        CHECKF(fabs(v - 1) < 1e-4, "Beckmann m=%g: D (N.H) integrates to 1 (%.6f)", ms[i], v);
    }
    const double ns[] = {1, 10, 100, 2000};
    for (int i = 0; i < 4; i++) {
        double v = hemi(tex_blinn_d_norm, ns[i]);
        CHECKF(fabs(v - 1) < 1e-4, "normalised Blinn Ns=%g integrates to 1 (%.6f)", ns[i], v);
    }
    CHECK(tex_blinn_d(1, 50) == 1, "Blinn D as printed peaks at 1 for H = N");

    for (double deg = 2; deg <= 40; deg += 7) {
        double beta = deg * M_PI / 180;
        double n = tex_blinn_ns_from_beta(beta), m = tex_beckmann_m_from_beta(beta);
        double rb = tex_blinn_d(cos(beta), n);
        double rk = tex_beckmann_d(cos(beta), m) / tex_beckmann_d(1, m);
        CHECKF(fabs(rb - 0.5) < 1e-9 && fabs(rk - 0.5) < 1e-9,
               "beta=%g deg: Blinn Ns=%.1f and Beckmann m=%.4f fall to half at beta (%.6f %.6f)",
               deg, n, m, rb, rk);
        double c = cos(beta), printed = tan(beta) * tan(beta) / log(c * c * c * c / 2);
        CHECKF(printed < 0 && fabs(-printed - m * m) < 1e-12,
               "beta=%g deg: the seed's eq. 17 as printed is -m^2 (%.5f)", deg, printed);
    }

    CHECK(tex_torrance_sparrow_g(1, 1, 1, 1) == 1, "G = 1 when V = L = N");
    double g = tex_torrance_sparrow_g(0.9, 0.1, 0.8, 0.6);
    CHECKF(fabs(g - 2 * 0.9 * 0.1 / 0.6) < 1e-12, "G masks at grazing view (%.4f)", g);
    int bad = 0;
    for (int i = 0; i < 1000; i++) {
        double a = (i % 37) / 36.0, b = (i % 11) / 10.0, c = (i % 7) / 6.0 + 0.01;
        double v = tex_torrance_sparrow_g(1, a, b, c);
        bad += !(v >= 0 && v <= 1);
    }
    CHECK(!bad, "G stays in [0,1]");

    /* Energy: with F = 1 and V = N, the specular lobe reflects <= 1 and, for a
     * smooth surface (G ~ 1), nearly all of it: sum of Rbd (N.L) dw over L. */
    const double rough[] = {0.1, 0.3};
    for (int r = 0; r < 2; r++) {
        struct tex_facets f = {TEX_FACET_BECKMANN, rough[r], 0};
        const int nt = 4000, np = 64;
        double s = 0, ht = (M_PI / 2) / nt, hp = 2 * M_PI / np;
        for (int i = 0; i < nt; i++) {
            double t = (i + 0.5) * ht;
            for (int j = 0; j < np; j++) {
                double p = (j + 0.5) * hp;
                double L[3] = {sin(t) * cos(p), sin(t) * sin(p), cos(t)}, V[3] = {0, 0, 1};
                double H[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
                double hl = sqrt(H[0] * H[0] + H[1] * H[1] + H[2] * H[2]);
                double nh = H[2] / hl, vh = (V[0] * H[0] + V[1] * H[1] + V[2] * H[2]) / hl;
                s += tex_ct_geometry(&f, nh, 1, L[2], vh) * L[2] * sin(t) * ht * hp;
            }
        }
        CHECKF(s <= 1.001 && s > (r == 0 ? 0.97 : 0.85),
               "Cook-Torrance lobe m=%g with F=1 reflects %.4f of the light (<= 1)", rough[r], s);
    }
    struct tex_facets f = {TEX_FACET_BECKMANN, 0.3, 0};
    CHECK(tex_ct_geometry(&f, 1, 0, 0.5, 1) == 0 && tex_ct_geometry(&f, 1, 0.5, -0.1, 1) == 0,
          "no specular term below the horizon");
    float rd[2] = {0.5f, 0.2f}, f0[2] = {0.9f, 0.04f}, ra[2];
    tex_ct_ambient(0.25, rd, f0, 2, ra);
    CHECK(fabs(ra[0] - (0.75 * 0.5 + 0.25 * 0.9)) < 1e-6 && fabs(ra[1] - (0.75 * 0.2 + 0.01)) < 1e-6,
          "ambient reflectance Ra = d Rd + s F0 with s + d = 1");
    return unit_done();
}
