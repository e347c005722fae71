/* render_ct.h - the Cook-Torrance shading model for t_apply (Ferreira 1991, eq. 22)
 *
 * A shading model in the sense of render_shade.h, chosen per surface with
 * `model cook-torrance`.  Its own parameters (the model_data of a
 * struct tex_material) are a struct tex_ct:
 *
 *   struct tex_ct ct;
 *   tex_ct_init(&ct, &cs, entry, TEX_FACET_BECKMANN, 0.2, 0, 0.8);
 *       cs:      the scene's colour space (RGB or spectral, colour.h)
 *       entry:   a material of the database (matdb.h), or NULL for a plain
 *                dielectric of the surface's ior
 *       m / ns:  Beckmann slope or Blinn exponent (microfacet.h)
 *       s:       specular fraction, d = 1 - s the diffuse one
 *   mat.model = &tex_shading_cook_torrance; mat.model_data = &ct;
 * With model_data NULL the model shades a dielectric of the surface's ior
 * with Beckmann's m = TEX_CT_M and s = TEX_CT_S.
 *
 * direct(): for a light of irradiance colour E from L,
 *     out += d kd E (N.L) + s pi F(V.H) [D G / (4 (N.V)(N.L))] E (N.L)
 * per sample.  The bracket is tex_ct_geometry (normalised D), F the exact
 * Fresnel reflectance per sample: a conductor's from its n + ik (so metal
 * highlights take the metal's colour), a dielectric's from its index (so
 * glass and the floor get the highlights Whitted-Phong misses).  The pi
 * converts the BRDF to the renderer's light unit, in which a Lambertian
 * surface reflects kd E (N.L) (the Phong model's diffuse term); the seed's
 * Rbd = (F/pi) D G/((N.V)(N.L)) carries that pi inside its D.
 *
 * weights(): the recursive rays at cos_i = N.V: reflected kr * Fr(cos_i),
 * transmitted kt * Ft = kt (1 - Fr), per sample (coloured for metals,
 * k > 0 means no transmission).  cos_i < 0 means the ray is inside the
 * object, leaving it: the indices swap, and beyond the critical angle
 * Fr = 1 (total internal reflection).
 *
 * The ambient term Ra f Ia is the renderer's Ka Ia with Ka = the ambient
 * reflectance; tex_ct_ambient (microfacet.h) gives Ra = d Rd + s F(1) for
 * a scene that wants it.
 */
#ifndef TEX_RENDER_CT_H
#define TEX_RENDER_CT_H

/* The model's parameters where a surface gives none, and their ranges, written once: the
 * scene's rows (facets, specular; the targets m and s) and help quote them. */
#define TEX_CT_M 0.2         /* Beckmann's slope of the microfacets */
#define TEX_CT_M_MIN 0.001
#define TEX_CT_M_MAX 2
#define TEX_CT_S 0.5         /* the specular fraction */
#define TEX_CT_NS_MAX 100000 /* Blinn's exponent, 0 up */
#define TEX_CT_BETA_MIN 0.01 /* a lobe's half-maximum angle in degrees, instead of m or ns */
#define TEX_CT_BETA_MAX 89

#include "matdb.h"
#include "microfacet.h"
#include "render_shade.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_ct {
    struct tex_facets facets;
    double s;          /* specular fraction, 0..1 */
    int conductor;     /* 1: n + ik, no transmission */
    int has_eta;       /* 0: use the material's ior */
    tex_colour eta, k; /* per sample */
    const struct tex_matdb_entry *entry; /* where eta and k come from (kept for resampling) */
    int flat;          /* a dielectric whose eta is the same in every sample */
    /* tex_ct_tabulate's: Fresnel reflectance at cos_i = j / TEX_CT_STEPS,
     * j = 0..TEX_CT_STEPS, table_cols values a row (1 for a flat dielectric,
     * else one per sample), for table_n samples; conductors, and dielectrics
     * seen from outside.  NULL: computed at every hit. */
    float *table;
    int table_n, table_cols;
};

/* Steps of the Fresnel table over cos_i in [0, 1].  Linear interpolation
 * between exact values is within 2e-5 of the formula for the database's
 * metals and glasses (test_render_ct), far below a display's resolution,
 * and replaces two square roots and two divisions per four samples. */
#define TEX_CT_STEPS 1024

extern const struct tex_shading_model tex_shading_cook_torrance;

/* Make m a Cook-Torrance material of parameters ct (NULL: the defaults): its
 * model, model_data, and m and s at a hit, which application functions may
 * then change per hit (the model reads them from the material). */
void tex_ct_material(struct tex_material *m, const struct tex_ct *ct);

int tex_ct_init(struct tex_ct *ct, const struct tex_colour_space *cs,
                const struct tex_matdb_entry *entry, enum tex_facet_dist dist, double m,
                double ns, double s);
/* Sample eta and k again for another colour space (a scene's colour model
 * overridden after its surfaces were read); the entry must still exist. */
void tex_ct_set_space(struct tex_ct *ct, const struct tex_colour_space *cs);
/* Fresnel's reflectance per sample at cos_i (< 0: from inside) for a material whose
 * model_data is a struct tex_ct or NULL (the anisotropic models share it). */
void tex_ct_fresnel(const struct tex_material *mat, double cos_i, int n, tex_colour *fr);
/* Tabulate the Fresnel reflectance for n samples (the renderer, before
 * tracing), and free the table; a surface without a table computes it. */
int tex_ct_tabulate(struct tex_ct *ct, int n);
void tex_ct_untabulate(struct tex_ct *ct);

#ifdef __cplusplus
}
#endif
#endif
