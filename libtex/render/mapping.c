/* mapping.c - mappings into texture space, the texture's window and placement */
#include <math.h>
#include <string.h>

#include "prim/cell.h"
#include "render/mapping.h"

/* The wavy projection's shift of u at height y of the texture's frame */
static inline double wave_at(const struct tex_apply *ap, double y)
{
    return ap->wave[0] * sin(2 * M_PI * y / ap->wave[1]);
}

/* fract for the world mapping's repetition, robust where a surface lies on a whole
 * coordinate (the floor y = 0): a hit that rounding put less than TEX_CELL_EPS below it
 * is on it, at 0, where fract gave about 1 to its neighbours, the far side of the
 * repetition (prim/cell.h); elsewhere fract's, bit for bit. */
static inline double wrap_world(double c)
{
    double r = c - tex_floord(c + TEX_CELL_EPS);
    return r > 0 ? r : 0;
}

/* The world and solid mappings, from the world point P: face 1 */
static int map_point_world(const struct tex_apply *ap, const struct tex_object *leaf,
                           const tex_v3 *P, double uvw[3])
{
    enum tex_mapping mp = ap->mapping;
    int bounded_solid = mp == TEX_MAP_SOLID && leaf->root && leaf->root->bounded;
    tex_v3 Pt;
    if (ap->placed && (mp == TEX_MAP_WORLD || mp == TEX_MAP_SOLID)) {
        /* about the world's origin, or the solid's box centre */
        tex_v3 c = bounded_solid ? tex_v3_scale(tex_v3_add(leaf->root->wb.lo, leaf->root->wb.hi),
                                                0.5)
                                 : tex_v3_make(0, 0, 0);
        Pt = tex_v3_add(c, tex_xform_point(&ap->to_tex, tex_v3_sub(*P, c)));
        P = &Pt;
    }
    if (mp == TEX_MAP_WORLD || (mp == TEX_MAP_SOLID && !bounded_solid)) {
        uvw[0] = wrap_world(P->x * ap->scale);
        uvw[1] = wrap_world(-P->y * ap->scale);
        uvw[2] = wrap_world(P->z * ap->scale);
        if (mp == TEX_MAP_WORLD) {
            double t = uvw[1];
            uvw[1] = uvw[2], uvw[2] = t; /* 2D maps lie in the ground plane x,z */
        }
        return 1;
    }
    /* solid, across the object's box; clamped: a hit on the box's face may round to just
     * outside it */
    const struct tex_bounds *rb = &leaf->root->wb;
    tex_v3 e = tex_v3_sub(rb->hi, rb->lo);
    uvw[0] = e.x > 0 ? clamp01((P->x - rb->lo.x) / e.x) : 0;
    uvw[1] = e.y > 0 ? clamp01((rb->hi.y - P->y) / e.y) : 0; /* v down: the top is 0 */
    uvw[2] = e.z > 0 ? clamp01((P->z - rb->lo.z) / e.z) : 0;
    return 1;
}

/* A fixed-size natural mapping's repetitions (thesis 5.3.1, non-elastic): k[0], k[1] maps of
 * size W x H along u and v of face on leaf, the face's extents in the object's units (the
 * unit shape's through the scale of to_world per axis) over W and H.  Sphere: 2 pi r by
 * pi r, r the mean radius; cylinder and cone side: 2 pi r (the larger radius) by the
 * slant height; caps: 2r by 2r; box faces: their two sides; torus: 2 pi R by 2 pi r. */
static void natural_size(const struct tex_apply *ap, const struct tex_object *leaf, int face,
                         double k[2])
{
    double s[3], lu = 1, lv = 1, r;
    for (int i = 0; i < 3; i++) {
        const double(*m)[4] = leaf->to_world.m;
        s[i] = sqrt(m[0][i] * m[0][i] + m[1][i] * m[1][i] + m[2][i] * m[2][i]);
    }
    double sxz = (s[0] + s[2]) / 2, mean = (s[0] + s[1] + s[2]) / 3;
    switch (leaf->kind) {
    case TEX_SHAPE_SPHERE:
        lu = 2 * M_PI * mean, lv = M_PI * mean;
        break;
    case TEX_SHAPE_BOX:
        if (face >= 1 && face <= 6) {
            int a = tex_box_axes[face - 1][0], b = tex_box_axes[face - 1][1];
            lu = 2 * s[(a < 0 ? -a : a) - 1], lv = 2 * s[(b < 0 ? -b : b) - 1];
        }
        break;
    case TEX_SHAPE_CYLINDER:
    case TEX_SHAPE_CONE:
    case TEX_SHAPE_INF_CONE:
        if (face == 1) {
            r = (leaf->r0 > leaf->r1 ? leaf->r0 : leaf->r1) * sxz;
            lu = 2 * M_PI * r, lv = hypot(s[1], (leaf->r1 - leaf->r0) * sxz);
        } else {
            r = face == 2 ? leaf->r0 : leaf->r1;
            r = r > 0 ? r : 1;
            lu = 2 * r * s[0], lv = 2 * r * s[2];
        }
        break;
    case TEX_SHAPE_TORUS:
        lu = 2 * M_PI * leaf->r0 * sxz, lv = 2 * M_PI * leaf->r1 * mean;
        break;
    default: /* the plane: u = x, v = z, one unit each */
        lu = s[0], lv = s[2];
        break;
    }
    k[0] = lu / ap->size[0], k[1] = lv / ap->size[1];
}

/* A projection's frame on leaf: the point pl turned by the placement about the shape's
 * box centre c into *pt, and *q, *pt across the box (half extents *e): in [-1, 1] inside
 * it; a shape without a box (returns 0) takes c = 0, e = 1.  The box is the leaf's, kept
 * by tex_object_bounds: the shape's bounds method, called at every hit, stalled it. */
static int projection_frame(const struct tex_apply *ap, const struct tex_object *leaf,
                            const tex_v3 *pl, tex_v3 *pt, tex_v3 *q, tex_v3 *e)
{
    int bounded = leaf->bounded;
    tex_v3 c = bounded ? leaf->bc : tex_v3_make(0, 0, 0);
    *e = bounded ? leaf->be : tex_v3_make(1, 1, 1);
    *pt = ap->placed ? tex_v3_add(c, tex_xform_point(&ap->to_tex, tex_v3_sub(*pl, c))) : *pl;
    *q = tex_v3_make((pt->x - c.x) / e->x, (pt->y - c.y) / e->y, (pt->z - c.z) / e->z);
    return bounded;
}

/* map_point_at for every mapping but plane_planar */
int tex_map_point_other(const struct tex_apply *ap, const struct tex_object *leaf,
                           const tex_v3 *P, const tex_v3 *pl, double uvw[3])
{
    enum tex_mapping mp = ap->mapping;
    tex_v3 plt;
    uvw[2] = 0;
    if (mp == TEX_MAP_NATURAL) {
        int face = tex_shape_methods[leaf->kind].uv(leaf, *pl, &uvw[0], &uvw[1]);
        if (ap->size[0] > 0) { /* fixed size: the plane's from x and z, not yet wrapped */
            double k[2];
            natural_size(ap, leaf, face, k);
            if (leaf->kind == TEX_SHAPE_PLANE)
                uvw[0] = pl->x, uvw[1] = pl->z;
            uvw[0] = fract(uvw[0] * k[0]), uvw[1] = fract(uvw[1] * k[1]);
        }
        return face;
    }
    if (mp == TEX_MAP_WORLD || mp == TEX_MAP_SOLID)
        return map_point_world(ap, leaf, P, uvw);
    tex_v3 q, e;
    int bounded = projection_frame(ap, leaf, pl, &plt, &q, &e);
    pl = &plt;
    switch (mp) {
    case TEX_MAP_SPHERE:
        return tex_shape_methods[TEX_SHAPE_SPHERE].uv(leaf, q, &uvw[0], &uvw[1]);
    case TEX_MAP_BOX:
        return tex_shape_methods[TEX_SHAPE_BOX].uv(leaf, q, &uvw[0], &uvw[1]);
    case TEX_MAP_CYLINDER:
    case TEX_MAP_CONE: {
        uvw[0] = tex_turns(-q.z, q.x);
        uvw[1] = bounded ? fmin(1, fmax(0, (1 - q.y) / 2)) : fract(-pl->y * ap->scale);
        return 1;
    }
    case TEX_MAP_CROSS: /* the x-y plane's map at (u, v), the y-z plane's at (w, v) */
        if (!bounded) {
            uvw[0] = fract(pl->x * ap->scale);
            uvw[1] = fract(-pl->y * ap->scale);
            uvw[2] = fract(pl->z * ap->scale);
        } else {
            uvw[0] = clamp01((q.x + 1) / 2);
            uvw[1] = clamp01((1 - q.y) / 2);
            uvw[2] = clamp01((q.z + 1) / 2);
        }
        return 1;
    default: /* planar: x and z across the box; wavy: swept along a sine path in y */
        if (!bounded) {
            uvw[0] = pl->x * ap->scale;
            uvw[1] = fract(pl->z * ap->scale);
        } else {
            uvw[0] = clamp01((q.x + 1) / 2);
            uvw[1] = clamp01((q.z + 1) / 2);
        }
        if (mp == TEX_MAP_WAVY)
            uvw[0] += wave_at(ap, pl->y);
        if (!bounded || mp == TEX_MAP_WAVY)
            uvw[0] = fract(uvw[0]);
        return 1;
    }
}

/* The natural mappings' (sphere_map, box faces, cylinder_map / cone_map)
 * gradients of u and v in object space at *pp on face (map_point's answer);
 * 0 where there are none (other mappings, the poles, the axis). */
static int natural_gradient(const struct tex_apply *ap, const struct tex_object *leaf,
                            const tex_v3 *pp, int face, tex_v3 *du, tex_v3 *dv)
{
    if (ap->mapping != TEX_MAP_NATURAL)
        return 0;
    tex_v3 p = *pp;
    double rho2 = p.x * p.x + p.z * p.z;
    switch (leaf->kind) {
    case TEX_SHAPE_SPHERE: {
        /* u = atan2(-z, x) / 2pi, v = acos(y / r) / pi */
        double r2 = rho2 + p.y * p.y;
        if (!(rho2 > 1e-12 * r2))
            return 0;
        double rho = sqrt(rho2), k = 1 / (M_PI * rho * r2);
        *du = tex_v3_scale(tex_v3_make(p.z, 0, -p.x), 1 / (2 * M_PI * rho2));
        *dv = tex_v3_make(p.x * p.y * k, -rho2 * k, p.z * p.y * k);
        return 1;
    }
    case TEX_SHAPE_BOX: {
        if (face < 1 || face > 6)
            return 0;
        double g[2][3] = {{0, 0, 0}, {0, 0, 0}};
        for (int i = 0; i < 2; i++) {
            int c = tex_box_axes[face - 1][i];
            g[i][(c < 0 ? -c : c) - 1] = c < 0 ? -0.5 : 0.5;
        }
        *du = tex_v3_make(g[0][0], g[0][1], g[0][2]);
        *dv = tex_v3_make(g[1][0], g[1][1], g[1][2]);
        return 1;
    }
    case TEX_SHAPE_CYLINDER:
    case TEX_SHAPE_CONE:
    case TEX_SHAPE_INF_CONE:
        if (face == 1) { /* the side: u around the axis, v = 1 - y */
            if (!(rho2 > 1e-24))
                return 0;
            *du = tex_v3_scale(tex_v3_make(p.z, 0, -p.x), 1 / (2 * M_PI * rho2));
            *dv = tex_v3_make(0, -1, 0);
        } else { /* the caps: a disc of radius r across [0, 1]^2 */
            double r = face == 2 ? leaf->r0 : leaf->r1;
            r = r > 0 ? r : 1;
            *du = tex_v3_make(0.5 / r, 0, 0);
            *dv = tex_v3_make(0, 0, 0.5 / r);
        }
        return 1;
    default:
        return 0;
    }
}

/* natural_gradient's, times a fixed-size mapping's repetitions (natural_size) */
static int natural_gradient_sized(const struct tex_apply *ap, const struct tex_object *leaf,
                                  const tex_v3 *pp, int face, tex_v3 *du, tex_v3 *dv)
{
    if (!natural_gradient(ap, leaf, pp, face, du, dv))
        return 0;
    if (ap->size[0] > 0) {
        double k[2];
        natural_size(ap, leaf, face, k);
        *du = tex_v3_scale(*du, k[0]), *dv = tex_v3_scale(*dv, k[1]);
    }
    return 1;
}

/* A cylinder or cone projection's gradients of u and v in object space at *pl (the
 * derivatives of tex_map_point_other's formulas: u = atan2(-qz, qx) / 2pi, v = (1 - qy) / 2
 * across the box or -y scale without one, through the placement's linear part); 0 for
 * other mappings, on the axis and where v is clamped (the footprint then takes finite
 * differences). */
static int projection_gradient(const struct tex_apply *ap, const struct tex_object *leaf,
                               const tex_v3 *pl, tex_v3 *du, tex_v3 *dv)
{
    if (ap->mapping != TEX_MAP_CYLINDER && ap->mapping != TEX_MAP_CONE)
        return 0;
    tex_v3 pt, q, e;
    int bounded = projection_frame(ap, leaf, pl, &pt, &q, &e);
    double rho2 = q.x * q.x + q.z * q.z, vq = (1 - q.y) / 2;
    if (!(rho2 > 1e-24) || (bounded && !(vq > 0 && vq < 1)))
        return 0;
    double k = 1 / (2 * M_PI * rho2);
    double gu[3] = {q.z * k / e.x, 0, -q.x * k / e.z};
    double gv[3] = {0, bounded ? -0.5 / e.y : -ap->scale, 0};
    if (ap->placed) { /* pt = c + M (p - c): a gradient goes by M's transpose */
        const double(*m)[4] = ap->to_tex.m;
        double a[3], b[3];
        for (int j = 0; j < 3; j++) {
            a[j] = m[0][j] * gu[0] + m[1][j] * gu[1] + m[2][j] * gu[2];
            b[j] = m[0][j] * gv[0] + m[1][j] * gv[1] + m[2][j] * gv[2];
        }
        memcpy(gu, a, sizeof a), memcpy(gv, b, sizeof b);
    }
    *du = tex_v3_make(gu[0], gu[1], gu[2]), *dv = tex_v3_make(gv[0], gv[1], gv[2]);
    return 1;
}

/* The world-space gradients g[0], g[1] of u and v at the hit pl (object space, on face) of a
 * mapping that is not affine but has them in closed form (natural_gradient,
 * projection_gradient): the object-space ones through to_obj's transpose, as a normal goes,
 * so that they meet the footprint's world tangents as an affine mapping's do (and in the
 * same lanes, batch_widths).  0 where there are none. */
int tex_point_gradient(const struct tex_apply *ap, const struct tex_object *leaf,
                          const tex_v3 *pl, int face, tex_v3 g[2])
{
    if (!natural_gradient_sized(ap, leaf, pl, face, &g[0], &g[1]) &&
        !projection_gradient(ap, leaf, pl, &g[0], &g[1]))
        return 0;
    g[0] = tex_xform_normal(&leaf->to_obj, g[0]);
    g[1] = tex_xform_normal(&leaf->to_obj, g[1]);
    return 1;
}

void tex_placement_of(const struct tex_apply *ap, struct placement *pm)
{
    pm->iu = 1 / (ap->u2 - ap->u1), pm->iv = 1 / (ap->v2 - ap->v1);
    pm->su = ap->nu * pm->iu, pm->sv = ap->nv * pm->iv;
    pm->bump = 0;
    for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next)
        pm->bump |= fn->param == TEX_SP_BUMP;
}
