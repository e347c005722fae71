/* light.h - the renderer's lights: distant, point, spot and area (libtex internal)
 *
 * Lights as the illumination paper gives them: a distant light's direction, a point's
 * attenuation 1/d^2 or min(1/(c1 + c2 d + c3 d^2), 1), a spot's I cos^c(theta) inside
 * its cone, an area light's parallelogram sampled n x n for soft shadows
 * (render_light.c).  The environment map that rays leaving the scene look up is the
 * scene's (scene.h).
 */
#ifndef TEX_LIGHT_H
#define TEX_LIGHT_H

#include "colour.h"
#include "render_shade.h"
#include "vecmath.h"

#ifdef __cplusplus
extern "C" {
#endif

enum tex_light_kind { TEX_LIGHT_DISTANT, TEX_LIGHT_POINT, TEX_LIGHT_SPOT, TEX_LIGHT_AREA };
enum tex_falloff { TEX_FALL_NONE, TEX_FALL_SQUARE, TEX_FALL_POLY };

struct tex_light {
    enum tex_light_kind kind;
    float rgb[3];          /* colour times intensity */
    tex_colour e;          /* the same in the scene's colour space */
    tex_v3 pos, dir;       /* dir: towards the light for distant, the axis for spot */
    tex_v3 edge1, edge2;   /* area: a parallelogram pos + a edge1 + b edge2 */
    int samples;           /* area: samples per side */
    enum tex_falloff falloff;
    double c1, c2, c3;
    double cos_angle, exponent; /* spot */
    struct tex_curve *spectrum; /* `spectrum D65|A|blackbody K` (spectrum.h), or NULL */
    /* as the scene gives them (tex_light_rows); rgb, dir and cos_angle follow */
    float colour[3];
    double intensity, angle;
    tex_v3 direction, at;
};

/* Number of samples of a light (n*n for an area light, else 1), and sample
 * k with jitter (jx, jy) in [0,1): the unit direction L from P towards it,
 * its distance (infinity for distant lights) and the attenuation times the
 * spot falloff and the sample's share.  0 if it sends no light to P. */
int tex_light_samples(const struct tex_light *l);
/* The attenuation at distance dl (inline: point lights are sampled in the shading loop). */
static inline double tex_light_falloff(const struct tex_light *l, double dl)
{
    switch (l->falloff) {
    case TEX_FALL_SQUARE: return 1 / (dl * dl);
    case TEX_FALL_POLY: {
        double q = l->c1 + l->c2 * dl + l->c3 * dl * dl;
        return q > 1 ? 1 / q : 1;
    }
    default: return 1;
    }
}
/* Direction L, distance and attenuation from P to a light's point pos; 0
 * when P is at the light.  The one point-light evaluation (tex_light_point_at). */
static inline int tex_light_towards(const struct tex_light *l, const tex_v3 *pos, const tex_v3 *P,
                                    tex_v3 *L, double *dist, double *fatt)
{
    tex_v3 d = tex_v3_sub(*pos, *P);
    double dl = tex_v3_len(d);
    if (!(dl > 0))
        return 0;
    *L = tex_v3_scale(d, 1 / dl);
    *dist = dl;
    *fatt = tex_light_falloff(l, dl);
    return 1;
}
/* tex_light_towards, then a spot light's cone and cos^exponent falloff: 0 outside the
 * cone.  Inline: the shading loop calls it for point and spot lights, tex_light_sample
 * for area samples. */
static inline int tex_light_point_at(const struct tex_light *l, const tex_v3 *pos,
                                     const tex_v3 *P, tex_v3 *L, double *dist, double *fatt)
{
    if (!tex_light_towards(l, pos, P, L, dist, fatt))
        return 0;
    if (l->kind == TEX_LIGHT_SPOT) {
        double c = -tex_v3_dot(*L, l->dir);
        if (c < l->cos_angle)
            return 0;
        *fatt *= tex_powi(c, l->exponent); /* whole exponents: by squaring */
    }
    return 1;
}
int tex_light_sample(const struct tex_light *l, int k, double jx, double jy, tex_v3 P, tex_v3 *L,
                     double *dist, double *fatt);
/* Whether tex_light_point_at takes l without pow: a point light, or a spot whose exponent
 * tex_powi takes by squaring (then its lanes can, x86/light_x86.h) */
static inline int tex_light_lanes(const struct tex_light *l)
{
    return l->kind == TEX_LIGHT_POINT ||
           (l->kind == TEX_LIGHT_SPOT && l->exponent >= 0 && l->exponent <= 4096 &&
            l->exponent == (int)l->exponent);
}
/* Whether tex_light_sample takes l's samples by a power of two's products, so its lanes
 * can (an area light whose samples a side are 1, 2, 4, ...) */
static inline int tex_light_area_lanes(const struct tex_light *l)
{
    return l->kind == TEX_LIGHT_AREA && l->samples > 0 && !(l->samples & (l->samples - 1));
}

#ifdef __cplusplus
}
#endif
#endif
