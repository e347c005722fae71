/* microfacet.h - the Cook-Torrance specular term (Cook and Torrance 1982; Ferreira 1991, eqs. 4, 13-17, 22)
 *
 * A rough surface is a field of mirror-like microfacets.  For a light
 * direction L, view direction V, normal N and half vector H = (L+V)/|L+V|,
 * the specular bidirectional reflectance is (eq. 13)
 *
 *     Rbd = (F/pi) * D * G / ((N.V)(N.L))
 *
 * with F the Fresnel reflectance at cos = V.H (fresnel.h), D the facet
 * distribution and G the geometric attenuation.  Only F depends on the
 * wavelength, so the renderer computes tex_ct_geometry() once per light and
 * multiplies by F per spectral sample.
 *
 * Distributions (alpha = angle between N and H, c = N.H = cos alpha):
 *   Beckmann (eq. 16)   D = exp((c^2 - 1) / (c^2 m^2)) / (pi m^2 c^4)
 *       m: rms slope of the facets (0.05 polished .. 0.5 matte).  This is
 *       Beckmann & Spizzichino's slope distribution exp(-tan^2 a / m^2)/(pi m^2)
 *       carried to projected facet area per solid angle (the 1/c^4), and it is
 *       normalised: the integral of D (N.H) over the hemisphere is 1.  The seed
 *       prints 1/(4 pi m^2 c^4) (Hall's form, whose 1/4 belongs with the pi of
 *       eq. 13); here the factor appears in tex_ct_geometry instead, see below.
 *   Blinn (eq. 14)      D = (N.H)^Ns
 *       peak 1 at H = N.  tex_blinn_d() returns it as printed;
 *       tex_blinn_d_norm() returns the normalised (Ns+2)/(2 pi) (N.H)^Ns,
 *       which is what enters Rbd so both distributions reflect the same energy.
 *
 * The roughness angle beta: the angle alpha at which D falls to half its peak.
 *   Blinn:    cos^Ns(beta) = 1/2  ->  Ns = -ln 2 / ln cos beta      (eq. 15)
 *   Beckmann: D(beta)/D(0) = exp(-tan^2 beta/m^2) / cos^4 beta = 1/2
 *             ->  m^2 = -tan^2 beta / ln(cos^4 beta / 2)
 *                     =  tan^2 beta / ln(2 / cos^4 beta).
 *   The seed prints eq. 17 as m^2 = tan^2 beta / ln(cos^4 beta / 2), which is
 *   negative for every beta (cos^4/2 < 1): the minus sign is lost.  We use the
 *   form derived above from Beckmann's distribution, and the unit test checks
 *   that D really is half its peak at beta.
 *
 * Geometric attenuation, Torrance & Sparrow (eq. 4), with L.H = V.H:
 *     G = min(1, 2(N.H)(N.V)/(V.H), 2(N.H)(N.L)/(V.H))
 *
 * tex_ct_geometry() returns  D G / (4 (N.V)(N.L))  with the normalised D, so
 * that Rbd = F * tex_ct_geometry(): this equals the seed's (F/pi) D' G/((N.V)(N.L))
 * with D' = pi D / 4 = exp(...)/(4 m^2 c^4), the form of Cook & Torrance's
 * thesis; the 1/4 is the Jacobian between facet and reflected solid angles
 * (Torrance & Sparrow 1967).  Multiply by the light's irradiance
 * I (N.L) dw to get the reflected radiance, and by s, with s + d = 1, for the
 * specular fraction of eq. 22.
 *
 * Ambient term (eq. 22, first line): Ra f Ia, with f the unoccluded fraction
 * of the hemisphere and Ra the directional-hemispherical reflectance.  With a
 * normalised lobe Ra ~ d Rd + s F(1) (Fresnel at normal incidence);
 * tex_ct_ambient() computes that per sample.
 */
#ifndef TEX_MICROFACET_H
#define TEX_MICROFACET_H

#include "../base/api.h"

TEX_API_BEGIN

enum tex_facet_dist { TEX_FACET_BECKMANN, TEX_FACET_BLINN };

struct tex_facets {
    enum tex_facet_dist dist;
    double m;  /* Beckmann rms slope, > 0 */
    double ns; /* Blinn exponent, >= 0 */
};

double tex_beckmann_d(double cos_nh, double m);
double tex_blinn_d(double cos_nh, double ns);
double tex_blinn_d_norm(double cos_nh, double ns);
/* Roughness conversions through the half-maximum angle beta (radians, 0 < beta < pi/2). */
double tex_blinn_ns_from_beta(double beta);
double tex_beckmann_m_from_beta(double beta);
double tex_torrance_sparrow_g(double nh, double nv, double nl, double vh);
/* D G / (4 (N.V)(N.L)) for the facets f; 0 when N.V <= 0 or N.L <= 0. */
double tex_ct_geometry(const struct tex_facets *f, double nh, double nv, double nl, double vh);
/* Per sample: ra[i] = d * rd[i] + s * f0[i]. */
void tex_ct_ambient(double s, const float *rd, const float *f0, int count, float *ra);

TEX_API_END
#endif
