/* render_shade.h - t_apply's shading models: the interface every model fills
 *
 * At a hit point the renderer first resolves the surface's material: the
 * untextured shading parameters changed by the surface's application
 * functions (texture maps).  The result is a struct tex_material, with the
 * colours already in the scene's colour space (n samples: 3 in RGB mode).
 * The surface's shading model then answers two questions:
 *
 *   direct(m, N, V, L, E, n, out)
 *       add to out the light reflected towards V (unit, from the point to
 *       the eye) from one light arriving from direction L (unit, from the
 *       point to the light) with irradiance colour E (already attenuated
 *       and shadowed).  N is the unit shading normal facing V.
 *   weights(m, cosi, n, kr, kt)
 *       the colour weights of the recursive reflected and transmitted rays
 *       at the angle of incidence cosi = N.V; Whitted-Phong uses the
 *       constants Kr, Kt, Cook-Torrance Fresnel's Fr and Ft = 1 - Fr.
 *
 * The ambient term Ka * Ia is the renderer's (every model has it).
 * A model is chosen per surface (`model phong` in the scene); tex_shading_find
 * looks one up by name.  Whitted-Phong (thesis eq. 3.1):
 *   I = Ia ka Od + sum S fatt Ip [kd Od (N.L) + ks (N.H)^n] + kr Ir + kt It
 * with H = (L+V)/|L+V| (Blinn's half vector).
 *
 * Adding a model (Cook-Torrance, issue 10): write its direct and weights,
 * keep its own parameters behind model_data (e.g. m, the conductor's n and
 * k spectra), and add a row to the table in render_shade.c.
 */
#ifndef TEX_RENDER_SHADE_H
#define TEX_RENDER_SHADE_H

#include <math.h>

#include "colour.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_shading_model;

/* The shading parameters at one hit point, after the application functions. */
struct tex_material {
    tex_colour ka;   /* ambient reflectance (Ka times the surface colour) */
    tex_colour kd;   /* diffuse colour Kd Od */
    tex_colour ks;   /* specular colour (white * Ks for dielectrics) */
    double n;        /* Phong exponent, 1..10000 */
    double kr, kt;   /* reflection and transmission weights, 0..1 */
    double ior;      /* index of refraction, > 0 */
    double m, s;     /* Cook-Torrance: Beckmann's slope and the specular fraction here */
    double disp;     /* the shaded point's displacement along the normal (target P) */
    double au, av, T[3]; /* ward, ashikhmin-shirley: roughnesses, unit tangent (anisotropic.h) */
    const struct tex_shading_model *model;
    const void *model_data; /* the model's own parameters, or NULL */
    /* a blend of two surfaces (`blend = h`): the light this one reflects, times 1 - blend,
     * plus blend_m's times blend; NULL: none */
    float blend;
    const struct tex_material *blend_m;
};

struct tex_shading_model {
    const char *name; /* scene word: "phong" */
    void (*direct)(const struct tex_material *m, const double N[3], const double V[3],
                   const double L[3], const tex_colour *E, int n, tex_colour *out);
    void (*weights)(const struct tex_material *m, double cosi, int n, tex_colour *kr,
                    tex_colour *kt);
};

extern const struct tex_shading_model tex_shading_phong;
/* x^n: by squaring for whole n up to 4096 (the usual Phong exponents), a few
 * multiplications instead of pow's tens of cycles; pow otherwise. */
static inline double tex_powi(double x, double n)
{
    if (!(n >= 0 && n <= 4096) || n != (int)n)
        return pow(x, n);
    double r = 1;
    for (int k = (int)n; k; k >>= 1, x *= x)
        if (k & 1)
            r *= x;
    return r;
}

/* Whitted-Phong's direct(), inline for the renderer's common case (N, V, L:
 * three doubles each).  dull: the caller knows m's Ks zero and no sample of out -0
 * (tex_colour_no_negative_zero, which the sums here keep), tested once for a hit's many
 * light samples rather than at each: then the highlight adds nothing wherever E is finite. */
static inline void tex_phong_direct_dull(const struct tex_material *m, const double *N,
                                         const double *V, const double *L, const tex_colour *E,
                                         int n, int dull, tex_colour *out)
{
    double nl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
    if (nl <= 0)
        return;
    tex_colour_mmadd(out, n, &m->kd, E, (float)nl);
    /* without a specular colour (Ks 0, the default) the highlight adds zeros: where they
     * leave out as it is, no half vector, cut-off or power */
    if (dull ? tex_colour_finite(E, n)
             : tex_colour_zero(&m->ks, n) && tex_colour_zero_adds_nothing(out, E, n))
        return;
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    double hh = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    double q = N[0] * h[0] + N[1] * h[1] + N[2] * h[2];
    if (!(hh > 0) || q <= 0)
        return;
    /* skip where the highlight (N.H)^n = x^(n/2), x = (N.H)^2, is below 1e-13:
     * ln x <= -(y + y^2/2 + y^3/3) with y = 1 - x; no square root for those */
    double x = q * q / hh, y = 1 - x;
    if (0.5 * m->n * y * (1 + y * (0.5 + y * (1.0 / 3))) < 30)
        tex_colour_mmadd(out, n, &m->ks, E, (float)tex_powi(q / sqrt(hh), m->n));
}

static inline void tex_phong_direct(const struct tex_material *m, const double *N,
                                    const double *V, const double *L, const tex_colour *E,
                                    int n, tex_colour *out)
{
    tex_phong_direct_dull(m, N, V, L, E, n, 0, out);
}

/* tex_shading_find (render.h) finds a model by name. */

#ifdef __cplusplus
}
#endif
#endif
