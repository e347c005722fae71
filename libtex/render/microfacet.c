/* microfacet.c - the Cook-Torrance specular term */
#include "render/microfacet.h"

#include <math.h>

double tex_beckmann_d(double c, double m)
{
    if (c <= 0 || m <= 0)
        return 0;
    double c2 = c * c, m2 = m * m;
    return exp((c2 - 1) / (c2 * m2)) / (M_PI * m2 * c2 * c2);
}

double tex_blinn_d(double c, double ns)
{
    return c <= 0 ? 0 : pow(c, ns);
}

double tex_blinn_d_norm(double c, double ns)
{
    return (ns + 2) / (2 * M_PI) * tex_blinn_d(c, ns);
}

double tex_blinn_ns_from_beta(double beta)
{
    return -log(2.0) / log(cos(beta));
}

double tex_beckmann_m_from_beta(double beta)
{
    double t = tan(beta), c = cos(beta);
    return sqrt(t * t / log(2 / (c * c * c * c)));
}

double tex_torrance_sparrow_g(double nh, double nv, double nl, double vh)
{
    if (vh <= 0)
        return 0;
    double g = 1, a = 2 * nh * nv / vh, b = 2 * nh * nl / vh;
    if (a < g)
        g = a;
    if (b < g)
        g = b;
    return g < 0 ? 0 : g;
}

double tex_ct_geometry(const struct tex_facets *f, double nh, double nv, double nl, double vh)
{
    if (nv <= 0 || nl <= 0)
        return 0;
    double d = f->dist == TEX_FACET_BECKMANN ? tex_beckmann_d(nh, f->m)
                                             : tex_blinn_d_norm(nh, f->ns);
    return d * tex_torrance_sparrow_g(nh, nv, nl, vh) / (4 * nv * nl);
}

void tex_ct_ambient(double s, const float *rd, const float *f0, int count, float *ra)
{
    for (int i = 0; i < count; i++)
        ra[i] = (float)((1 - s) * rd[i] + s * f0[i]);
}
