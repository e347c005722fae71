/* footprint.h - the pixel's footprint on a surface, in texture units (libtex internal)
 *
 * A ray carries the width of its pixel's footprint (render.c); at a hit the footprint lies
 * along two tangents of the surface, and its extents in texture space choose the mip-map
 * level of a map's lookup and band-limit a solid texture's octaves (Igehy 1999's ray
 * differentials, simplified to a width per ray).
 */
#ifndef TEX_FOOTPRINT_H
#define TEX_FOOTPRINT_H

#include "mapping.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The pixel's footprint on the surface at a hit: tangents t1 (the ray projected on the
 * surface) and t2 = N x t1, both of length sqrt(l2), and the footprint's widths along them,
 * width / c (c: the cosine of incidence, at least 0.02) and width.  Mappings with gradients
 * take the tangents as they are; finite differences want them of unit length
 * (footprint_unit) and short steps d1, d2 along them from the hit (footprint_steps: P1, P2
 * in world space, pl1, pl2 in object space, o1, o2 the tangents there). */
struct footprint {
    tex_v3 D, N;
    tex_v3 t1, t2;
    double l2, width, c;
    int tangents; /* 1: t1, t2, l2 and c are made (footprint_tangents) */
    int unit; /* 1: t1, t2 have unit length (l2 = 1) */
    int steps; /* 1: o1, o2 and the steps are made (footprint_steps) */
    tex_v3 o1, o2, P1, P2, pl1, pl2;
    double d1, d2;
};

/* A footprint of the ray D on the surface of normal N; its tangents are made when first
 * asked for (footprint_tangents), which a hit whose lookups take none never does. */
static inline void footprint_at(struct footprint *fp, const tex_v3 *D, const tex_v3 *N, double width)
{
    fp->D = *D, fp->N = *N;
    fp->width = width;
    fp->tangents = fp->unit = fp->steps = 0;
}

static inline void footprint_tangents(struct footprint *fp)
{
    if (fp->tangents)
        return;
    const tex_v3 *D = &fp->D, *N = &fp->N;
    double dn = tex_v3_dot(*D, *N), cosv = fabs(dn);
    tex_v3 t1 = tex_v3_madd(*D, *N, -dn);
    double l2 = tex_v3_dot(t1, t1);
    if (l2 < 1e-18) { /* head-on: any tangent */
        t1 = fabs(N->x) < 0.9 ? tex_v3_cross(*N, tex_v3_make(1, 0, 0))
                              : tex_v3_cross(*N, tex_v3_make(0, 1, 0));
        t1 = tex_v3_norm(t1);
        l2 = 1;
    }
    fp->t1 = t1;
    fp->t2 = tex_v3_cross(*N, t1);
    fp->l2 = l2;
    fp->c = cosv > 0.02 ? cosv : 0.02;
    fp->tangents = 1;
}

static inline void footprint_unit(struct footprint *fp)
{
    if (fp->unit)
        return;
    footprint_tangents(fp);
    double s = 1 / sqrt(fp->l2);
    fp->t1 = tex_v3_scale(fp->t1, s), fp->t2 = tex_v3_scale(fp->t2, s);
    fp->l2 = 1;
    fp->unit = 1;
}

/* A band-limited solid's footprint width, squared: RenderMan's filterwidth, the square
 * root of the footprint's area (the mean of its extents over u, v and w). */
/* A band-limited solid's footprint width, squared: RenderMan's filterwidth, the square
 * root of the footprint's area (the mean of its extents over u, v and w), which does not
 * blur a surface seen at a grazing angle across its whole width as the longer extent
 * would. */
double tex_solid_width2(const struct tex_apply *ap, const struct placement *pm,
                           const struct tex_object *leaf, struct footprint *fp, const tex_v3 *P,
                           const tex_v3 *pl, const double uvw0[3]);

/* The derivatives of the placed u and v along the footprint's tangents t1, t2 as they are
 * (du[i], dv[i] along ti) at the hit P (pl in object space, on face), where the mapping has
 * them in closed form (map_gradient, tex_point_gradient): 1, else 0. */
static inline __attribute__((always_inline)) int
placed_derivatives(const struct tex_apply *ap, const struct placement *pm,
                   const struct tex_object *leaf, struct footprint *fp, const tex_v3 *pl,
                   int face, double du[2], double dv[2])
{
    tex_v3 g[3];
    footprint_tangents(fp);
    if (!map_gradient(ap, leaf, g) && !tex_point_gradient(ap, leaf, pl, face, g))
        return 0;
    for (int i = 0; i < 2; i++) {
        const tex_v3 *e = i ? &fp->t2 : &fp->t1;
        du[i] = tex_v3_dot(g[0], *e) * pm->su, dv[i] = tex_v3_dot(g[1], *e) * pm->sv;
    }
    return 1;
}

/* The footprint's size in texture units (after placement) for texture ap at the hit P (pl)
 * that its mapping took to (u0, v0) on face: the longer of its extents along t1 and t2,
 * squared (the mip level takes it so: neither a root nor a normalised tangent here). */
/* The footprint's size in texture units (after placement) for texture ap at the hit P (pl)
 * that its mapping took to (u0, v0) on face: the longer of its extents along t1 and t2,
 * squared (the mip level takes it so: neither a root nor a normalised tangent here). */
double tex_footprint_width2(const struct tex_apply *ap, const struct placement *pm,
                               const struct tex_object *leaf, struct footprint *fp,
                               const tex_v3 *P, const tex_v3 *pl, int face, double u0, double v0);

#ifdef __cplusplus
}
#endif
#endif
