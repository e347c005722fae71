/* appfn.h - application functions compiled for a surface (libtex internal)
 *
 * tex_surface_cache (appfn.c) compiles a surface's functions once before rendering; the
 * packets (packet.c) read what it found: which lookups go ahead, which go in lanes.
 */
#ifndef TEX_APPFN_H
#define TEX_APPFN_H

#include "footprint.h"
#include "mipmap.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An application function compiled to c0 + c1 f + c2 p + c3 f p per channel, where its
 * expression is at most linear in each of f and p (no cascade): lang/expr.h's polynomial.
 * folded: of degree 0 with no zero constant, so that poly_at gives c[0] itself wherever f
 * and p are finite (c[0] + 0 f is not c[0] at a zero's sign, nor at f infinite); mean: the
 * channels' mean, as a scalar parameter takes it */
struct poly {
    struct tex_expr_poly p;
    int folded;
    double mean;
};

/* The parameters being textured, in RGB, before conversion to the colour space.  A float
 * follows each colour (ka kd's, gradient[0] normal's, disp gradient's, flow[0]
 * tangent's): colour_set writes the colour with it. */
struct params {
    float kd[3], ka, ks, n, kr, kt, ior, bump;
    double m, s; /* Cook-Torrance's slope and specular fraction (double: as the model's) */
    float blend; /* the blended surface's weight */
    float normal[3], gradient[3]; /* one apply block's normal map and height gradient */
    float disp; /* P's displacement along the normal (P = D) */
    float au, av, angle; /* anisotropic: roughnesses, the tangent's turn in degrees */
    float tangent[3], flow[3]; /* a flow field's encoded value, then its world direction */
    float end;
};

/* Thesis 4.4: the largest of Kd's channels plus the larger of Ks and Kr (one specular
 * reflectance, of the lights and of the scene) plus Kt (the microfacet models: (1 - s) Kd
 * plus the largest of s, Kr and a dielectric's Kt), the surface's own and, where its
 * textures set them, its functions' at texture values 0, 1/16, ..., 1 (grey) and at the
 * corners and middle of (u, v, w), every function in order, regions alike, into *e: 1, or
 * 0 when it cannot tell (a function reads the hit's quantities). */
int tex_surface_energy(const struct tex_surface *sf, double *e);

struct tex_surface_cache {
    struct params base;          /* the surface's own parameters */
    tex_colour col[3];           /* Ka Kd, Kd, Ks in the scene's colour space */
    int cached;                  /* bit i: col[i] is constant (untextured) */
    struct placement *placement; /* per texture applied, in order */
    struct poly *poly;           /* per application function, in order */
    char *compiled;              /* 1: poly[i] holds function i */
    int quantities;              /* bit k: a function reads quantity k (tex_quantities) */
    int footprints;              /* 1: lookups ahead take footprints (tex_surface_footprints) */
    /* 1: one texture, a map looked up ahead or a primitive evaluated ahead, whose
     * functions read no quantity, see every region and bend no normal but by a bump
     * (apply_direct) */
    int direct;
    int lanes; /* 1: direct, a map, and AVX2: its hits go in lanes (tex_lanes_take) */
    int plain; /* tex_surface_plain: 1, a material tex_plain_material makes; 2, any other */
    int later; /* the function tex_plain_resolve leaves to tex_plain_later_run, or -1 */
};

/* A tilt's direction along the footprint's tangents t1, t2 from the luminance's
 * derivatives g along them; where grad (the map's gradient per u and v) is given, g is made
 * from it first, through the derivatives du, dv of u and v along t1, t2. */
/* A tilt's direction along the footprint's tangents t1, t2 from the luminance's
 * derivatives g along them; where grad (the map's gradient per u and v) is given, g is made
 * from it first, through the derivatives du, dv of u and v along t1, t2. */
tex_v3 tex_tilt_along(const double *grad, const double du[2], const double dv[2],
                         double g[2], tex_v3 t1, tex_v3 t2);

/* An application function's expression e run per channel, as a hit runs it: its f and p
 * leaves read f and p, its textures are looked up at uvw through a footprint sqrt(fw2)
 * wide, its quantities read q[TEX_Q_COUNT] (NULL where e reads none).  Hypertextures run
 * theirs through it (hypertexture.h). */
void tex_appfn_eval(const struct tex_expr *e, const float f[3], const float p[3],
                    const double uvw[3], double fw2, const double *q, double out[3]);

/* Whether the packet looks texture ap up ahead when it is a surface's first: a filtered
 * map, with its gradient where bumped (a cross mapping wants a second map). */
static inline int map_ahead(const struct tex_apply *ap)
{
    return ap->tex->mip && !ap->tex->subregions && ap->mapping != TEX_MAP_CROSS;
}

/* Whether a packet's lookups ahead make ap's texture's value whole: a primitive's (the
 * texture's palette aside), not crossed with a second map (tex_prefetch_eval) */
static inline int value_ahead(const struct tex_apply *ap)
{
    return !ap->tex->mip && ap->mapping != TEX_MAP_CROSS;
}

#ifdef __cplusplus
}
#endif
#endif
