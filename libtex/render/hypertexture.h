/* hypertexture.h - Perlin and Hoffert's hypertexture (thesis 2.9): densities and their
 * modulation (libtex internal)
 *
 * An object density D(x) in [0, 1] whose soft region is 0 < D < 1, modulated into
 * H = fn(...f1(f0(D(x)))) by an expression over D, the point and the scene's textures
 * (bias and gain are lang/expr.h's functions), then coloured by application functions
 * over H and the point.  volume.h ray-marches it.
 *
 * Densities, each of a soft width s (0: a hard edge):
 *   sphere    the thesis's D[c,r,s]: 1 inside r - s/2, 0 outside r + s/2, and between
 *             (r0^2 - |x - c|^2) / (r0^2 - r1^2), r1 = r - s/2, r0 = r + s/2
 *             (the thesis prints x_z + c_z; the distance needs x_z - c_z)
 *   box       1 - (d + s/2) / s clamped to [0, 1], d the signed distance to the box
 *   cylinder  the same over a capped cylinder's signed distance
 * and the soft booleans, as fuzzy sets combine (Zadeh's, which keep D in [0, 1] and
 * reduce to CSG's where D is 0 or 1):
 *   union max(a, b)   intersection min(a, b)   difference min(a, 1 - b)   complement 1 - a
 *
 *   struct tex_hyper *h = ...;            // the scene parser's (render_scene.c)
 *   double t0, t1;
 *   if (tex_hdensity_span(h->d, &o, &d, &t0, &t1)) ...   // where D can be above 0
 *   struct tex_hyper_sample v;
 *   tex_hyper_at(h, &P, fw2, &v);        // extinction, albedo and emission at P
 */
#ifndef TEX_HYPERTEXTURE_H
#define TEX_HYPERTEXTURE_H

#include "../lang/expr.h"
#include "vecmath.h"

#ifdef __cplusplus
extern "C" {
#endif

enum tex_hdensity_kind { TEX_HD_SPHERE, TEX_HD_BOX, TEX_HD_CYLINDER, TEX_HD_UNION,
                         TEX_HD_INTERSECTION, TEX_HD_DIFFERENCE, TEX_HD_COMPLEMENT,
                         TEX_HD_NKINDS };
extern const char *const tex_hdensity_names[TEX_HD_NKINDS];

/* A node of a density tree: a shape's parameters (tex_hdensity_rows) or a boolean of a and
 * b (complement: a alone) */
struct tex_hdensity {
    enum tex_hdensity_kind kind;
    tex_v3 centre, min, max, base, top;
    double radius, soft;
    struct tex_hdensity *a, *b;
    /* made by tex_hdensity_prepare */
    tex_v3 axis;       /* cylinder: unit, base to top */
    double len;        /* cylinder: its length */
    double r0, r1;     /* sphere: squared radii r + s/2, r - s/2; others: the reach s/2 */
    tex_v3 lo, hi;     /* shapes: the box D is 0 outside */
    int line, col;
};

/* The application functions of a hypertexture (tex_hyper_fn_rows in this order) */
enum tex_hyper_fn { TEX_HF_DENSITY, TEX_HF_OPACITY, TEX_HF_COLOUR, TEX_HF_EMISSION,
                    TEX_HF_COUNT };
/* Their operands beyond lang/expr.h's: D is the leaf a surface's p is, H its f (so that
 * appfn.c's evaluator runs them), the point x y z (ox oy oz alike) and the textures,
 * looked up at the point */

#define TEX_HYPER_MAX 64 /* hypertextures in a scene */

/* `hypertexture { DENSITY [rows] [fn = EXPR]... }` */
struct tex_hyper {
    struct tex_hdensity *d;
    struct tex_expr *fn[TEX_HF_COUNT]; /* NULL: density D, opacity H, colour 1, emission 0 */
    double lo[TEX_HF_COUNT], hi[TEX_HF_COUNT]; /* each result's range (its row's) */
    double absorption, scattering; /* per unit length where the opacity is 1 */
    double phase;                  /* Henyey-Greenstein's g (0: isotropic) */
    double step, shadow_step;      /* the march's longest step, the shadow rays' (0: 2 step) */
    double tolerance;              /* the extinction's change per step that halves it */
    double jitter;                 /* the share of a step the sample moves by the ray's hash */
    double ambient;                /* the scattered share of the ambient light */
    int line, col;
};

/* A hypertexture at a point: its extinction per unit length (sigma_t = (absorption +
 * scattering) x opacity), scattering sigma_s, albedo (colour, RGB) and emission (RGB per
 * unit length). */
struct tex_hyper_sample {
    double sigma_t, sigma_s;
    float colour[3], emission[3];
};

/* Fill a tree's derived fields (sphere radii, cylinder axis, shapes' boxes): 0, or -1
 * with *bad the node at fault and msg its one-line reason */
int tex_hdensity_prepare(struct tex_hdensity *n, struct tex_hdensity **bad, const char **msg);
/* Whether D is 0 outside a bounded region: not for a complement that no intersection
 * or difference encloses */
int tex_hdensity_bounded(const struct tex_hdensity *n);
/* D at P, in [0, 1] */
double tex_hdensity_eval(const struct tex_hdensity *n, const tex_v3 *P);
/* The span [t0, t1] of the ray o + t d (d unit) outside which D is 0: 1, or 0 where the
 * ray misses it.  A sphere's is its ball of radius r + s/2, exactly; others their boxes. */
int tex_hdensity_span(const struct tex_hdensity *n, const tex_v3 *o, const tex_v3 *d,
                      double *t0, double *t1);

/* The hypertexture at P, textures seen through a footprint sqrt(fw2) wide; shadow: the
 * extinction alone (no colour or emission) */
void tex_hyper_at(const struct tex_hyper *h, const tex_v3 *P, double fw2, int shadow,
                  struct tex_hyper_sample *out);

#ifdef __cplusplus
}
#endif
#endif
