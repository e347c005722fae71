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
    const struct tex_shading_model *model;
    const void *model_data; /* the model's own parameters, or NULL */
};

struct tex_shading_model {
    const char *name; /* scene word: "phong" */
    void (*direct)(const struct tex_material *m, const double N[3], const double V[3],
                   const double L[3], const tex_colour *E, int n, tex_colour *out);
    void (*weights)(const struct tex_material *m, double cosi, int n, tex_colour *kr,
                    tex_colour *kt);
};

extern const struct tex_shading_model tex_shading_phong;
/* NULL if no model has that name. */
const struct tex_shading_model *tex_shading_find(const char *name);

#ifdef __cplusplus
}
#endif
#endif
