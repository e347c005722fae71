/* mapping.h - mappings: a hit's place in texture space (libtex internal)
 *
 * The thesis's mappings (5.3.2): the shapes' own inverse maps (sphere, cylinder, cone,
 * box, plane), projections of a 2D map along an axis, a cylinder, a wavy path or across
 * two planes, and solid texturing across the object's box or in world units.  Then the
 * texture's window (u1,v1)-(u2,v2) and its repetition nu x nv (the placement).  The
 * common cases and the placement are inline: every textured hit takes them.
 */
#ifndef TEX_MAPPING_H
#define TEX_MAPPING_H

#include "surface.h"

#ifdef __cplusplus
extern "C" {
#endif

static inline double fract(double x)
{
    return x - tex_floord(x);
}

static inline double clamp01(double x)
{
    return x > 0 ? (x < 1 ? x : 1) : 0;
}

/* A planar mapping on an unbounded plane: u, v are its object-space x and z, scaled. */
static inline int plane_planar(const struct tex_apply *ap, const struct tex_object *leaf)
{
    return (ap->mapping == TEX_MAP_NATURAL || ap->mapping == TEX_MAP_PLANAR) &&
           leaf->kind == TEX_SHAPE_PLANE && !ap->placed && !(ap->size[0] > 0);
}

/* map_point_at for every mapping but plane_planar */
/* map_point_at for every mapping but plane_planar */
int tex_map_point_other(const struct tex_apply *ap, const struct tex_object *leaf,
                           const tex_v3 *P, const tex_v3 *pl, double uvw[3]);

/* Texture-space coordinates of world point P (pl in leaf's object space); returns the face id.
 * Inline for the commonest, a plane's (unbounded: no box). */
static inline int map_point_at(const struct tex_apply *ap, const struct tex_object *leaf,
                               const tex_v3 *P, const tex_v3 *pl, double uvw[3])
{
    if (!plane_planar(ap, leaf))
        return tex_map_point_other(ap, leaf, P, pl, uvw);
    uvw[0] = fract(pl->x * ap->scale);
    uvw[1] = fract(pl->z * ap->scale);
    uvw[2] = 0;
    return 1;
}

/* Where the mapping is affine in P (modulo wrapping), its world-space gradients of u, v and
 * w in g[0..2]: 1, else 0 (the footprint then takes finite differences). */
static inline __attribute__((always_inline)) int
map_gradient(const struct tex_apply *ap, const struct tex_object *leaf, tex_v3 g[3])
{
    static const double id[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    const double(*m)[4] = ap->placed ? ap->to_tex.m : id;
    double s[3] = {ap->scale, ap->scale, ap->scale};
    int row[3] = {0, 2, 1}; /* u = x s, v = z s, w = -y s of the point (world mapping) */
    if (plane_planar(ap, leaf)) { /* of the object-space point; w = 0 */
        m = leaf->to_obj.m, s[2] = 0;
    } else if (ap->mapping == TEX_MAP_SOLID) { /* u = x s, v = -y s, w = z s */
        row[1] = 1, row[2] = 2;
        s[1] = -s[1];
        if (leaf->root && leaf->root->bounded) { /* across the box, v down */
            tex_v3 e = tex_v3_sub(leaf->root->wb.hi, leaf->root->wb.lo);
            s[0] = e.x > 0 ? 1 / e.x : 0, s[1] = e.y > 0 ? -1 / e.y : 0;
            s[2] = e.z > 0 ? 1 / e.z : 0;
        }
    } else if (ap->mapping == TEX_MAP_WORLD) {
        s[2] = -s[2];
    } else {
        return 0;
    }
    for (int k = 0; k < 3; k++) {
        const double *r = m[row[k]];
        g[k] = tex_v3_make(r[0] * s[k], r[1] * s[k], r[2] * s[k]);
    }
    return 1;
}

/* The world-space gradients g[0], g[1] of u and v at the hit pl (object space, on face) of a
 * mapping that is not affine but has them in closed form (the natural mappings, the
 * cylinder and cone projections): the object-space ones through to_obj's transpose, as a
 * normal goes, so that they meet the footprint's world tangents as an affine mapping's do
 * (and in the same lanes, packet.c).  0 where there are none. */
/* The world-space gradients g[0], g[1] of u and v at the hit pl (object space, on face) of a
 * mapping that is not affine but has them in closed form (natural_gradient,
 * projection_gradient): the object-space ones through to_obj's transpose, as a normal goes,
 * so that they meet the footprint's world tangents as an affine mapping's do (and in the
 * same lanes, batch_widths).  0 where there are none. */
int tex_point_gradient(const struct tex_apply *ap, const struct tex_object *leaf,
                          const tex_v3 *pl, int face, tex_v3 g[2]);

/* A texture's window and placement, the divisions done once (tex_surface_cache): (u, v) is
 * in the window where s = (u - u1) iu and t = (v - v1) iv lie in [0, 1], and goes to
 * (s nu, t nv) on the map; su = nu iu and sv = nv iv scale the footprint likewise. */
struct placement {
    double iu, iv, su, sv;
    int bump; /* a function of this texture sets bump (more lookups, footprint and all) */
};

void tex_placement_of(const struct tex_apply *ap, struct placement *pm);

/* Window and placement: 0 if the point is outside the window (or not a number), else the
 * placed coordinates, u in [0, nu] and v in [0, nv]. */
static inline int place(const struct tex_apply *ap, const struct placement *pm, double uvw[3])
{
    double s = (uvw[0] - ap->u1) * pm->iu, t = (uvw[1] - ap->v1) * pm->iv;
    if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1))
        return 0;
    uvw[0] = s * ap->nu;
    uvw[1] = t * ap->nv;
    return 1;
}

static inline double wrapdiff(double d)
{
    return d - tex_floord(d + 0.5);
}

/* Application ap's mapping of the hit P (pl in object space) into a: the mapping's
 * coordinates, then placed, and whether the placement holds the point; no value yet.
 * Always inlined: gcc's size limit left it out of the packet's loop after changes
 * elsewhere, and workshop took 2-3 % longer. */
static inline __attribute__((always_inline)) void
map_hit(const struct tex_apply *ap, const struct placement *pm, const struct tex_object *leaf,
        const tex_v3 *P, const tex_v3 *pl, struct tex_prefetch_ap *a)
{
    double uvw[3], placed[3]; /* in registers where map_point_at is inlined */
    a->tex = ap->tex;
    a->face = map_point_at(ap, leaf, P, pl, uvw);
    for (int i = 0; i < 3; i++)
        a->uvw0[i] = placed[i] = uvw[i];
    a->inside = place(ap, pm, placed); /* placed in registers, then stored: not reloaded */
    for (int i = 0; i < 3; i++)
        a->uvw[i] = placed[i];
    a->pending = a->inside && !ap->tex->mip;
    a->bump = pm->bump;
    a->has_val = a->has_tilt = 0;
    a->fw = 0;
}

#ifdef __cplusplus
}
#endif
#endif
