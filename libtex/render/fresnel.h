/* fresnel.h - Fresnel reflectance of dielectrics and conductors (Ferreira 1991, eqs. 5-8)
 *
 * Light is taken as unpolarised, so every reflectance here is the mean of
 * the parallel and perpendicular components:  Fr = (r_par^2 + r_perp^2)/2.
 * Angles are given by their cosine cos_i = N.L >= 0 on the incident side.
 *
 *   double ft;
 *   double fr = tex_fresnel_dielectric(cos_i, 1.0, 1.5, &ft);   // air -> glass
 *       eta_i, eta_t: real indices of the incident and transmitting media.
 *       Snell: eta_i sin_i = eta_t sin_t.  With cos_t = sqrt(1 - sin_t^2),
 *         r_par  = (eta_t cos_i - eta_i cos_t) / (eta_t cos_i + eta_i cos_t)
 *         r_perp = (eta_i cos_i - eta_t cos_t) / (eta_i cos_i + eta_t cos_t)
 *       (the seed's eq. 5 with N.T = -cos_t).  Returns Fr; *ft (may be NULL)
 *       gets Ft = 1 - Fr (eq. 7).  Total internal reflection (sin_t >= 1)
 *       gives Fr = 1, Ft = 0.
 *
 *   double fr = tex_fresnel_conductor(cos_i, eta_i, n, k);
 *       The exact reflectance of an absorbing medium of complex index
 *       n + ik seen from a dielectric of index eta_i (Born & Wolf, 13.2).
 *       With eta = n/eta_i, kappa = k/eta_i, s2 = sin^2 i, c = cos i:
 *         a^2 + b^2 = sqrt((eta^2 - kappa^2 - s2)^2 + 4 eta^2 kappa^2)
 *         a         = sqrt((a^2 + b^2 + eta^2 - kappa^2 - s2) / 2)
 *         Rs = (a^2+b^2 - 2ac + c^2) / (a^2+b^2 + 2ac + c^2)
 *         Rp = Rs (c^2(a^2+b^2) - 2ac s2 + s2^2) / (c^2(a^2+b^2) + 2ac s2 + s2^2)
 *         Fr = (Rs + Rp) / 2
 *       At normal incidence Fr = ((eta-1)^2 + kappa^2) / ((eta+1)^2 + kappa^2);
 *       at grazing incidence Fr -> 1.  k = 0 gives the dielectric result.
 *
 *   double fr = tex_fresnel_conductor_approx(cos_i, n, k);
 *       The seed's eq. 8, valid only when n^2 + k^2 >> 1 (from air):
 *         r_par^2  = ((n^2+k^2) c^2 - 2nc + 1) / ((n^2+k^2) c^2 + 2nc + 1)
 *         r_perp^2 = ((n^2+k^2) - 2nc + c^2)   / ((n^2+k^2) + 2nc + c^2)
 *       (as printed, the seed swaps subscripts i and t; this is the intended
 *       formula).  Kept for comparison; the renderer uses the exact one.
 *
 *   tex_fresnel_conductor_n(cos_i, eta_i, n, k, count, out);
 *       The exact formula for `count` wavelength samples at once (a spectrum).
 */
#ifndef TEX_FRESNEL_H
#define TEX_FRESNEL_H

#include "../base/api.h"

TEX_API_BEGIN

double tex_fresnel_dielectric(double cos_i, double eta_i, double eta_t, double *ft);
double tex_fresnel_conductor(double cos_i, double eta_i, double n, double k);
double tex_fresnel_conductor_approx(double cos_i, double n, double k);
void tex_fresnel_conductor_n(double cos_i, double eta_i, const float *n, const float *k,
                             int count, float *out);

TEX_API_END
#endif
