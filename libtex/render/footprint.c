/* footprint.c - the pixel's footprint in texture units, by the mapping's derivatives or by
 * finite differences */
#include <math.h>

#include "render/footprint.h"

/* The unit tangents in leaf's object space (o1, o2) and the short steps along them from the
 * hit P (pl in object space) that finite differences take. */
static void footprint_steps(struct footprint *fp, const struct tex_object *leaf, const tex_v3 *P,
                            const tex_v3 *pl)
{
    if (fp->steps)
        return;
    footprint_unit(fp);
    fp->o1 = tex_xform_dir(&leaf->to_obj, fp->t1);
    fp->o2 = tex_xform_dir(&leaf->to_obj, fp->t2);
    double w1 = fp->width / fp->c, w2 = fp->width;
    fp->d1 = w1 < 1e-3 ? w1 : 1e-3, fp->d2 = w2 < 1e-3 ? w2 : 1e-3;
    fp->P1 = tex_v3_madd(*P, fp->t1, fp->d1), fp->P2 = tex_v3_madd(*P, fp->t2, fp->d2);
    fp->pl1 = tex_v3_madd(*pl, fp->o1, fp->d1), fp->pl2 = tex_v3_madd(*pl, fp->o2, fp->d2);
    fp->steps = 1;
}

/* The footprint's extents along t1 and t2 (squared, *l2 the second) in texture units, u
 * and v placed, over dims of them (2: u, v; 3: and w, a solid's), by short steps along t1
 * and t2 from the hit P (pl in object space), whose mapping gave uvw0 (no wrap-around),
 * scaled to the footprint; returns the first. */
static double stepped_width2(const struct tex_apply *ap, const struct placement *pm,
                             const struct tex_object *leaf, struct footprint *fp,
                             const tex_v3 *P, const tex_v3 *pl, const double uvw0[3], int dims,
                             double *l2out)
{
    double a[3], b[3];
    footprint_steps(fp, leaf, P, pl);
    map_point_at(ap, leaf, &fp->P1, &fp->pl1, a);
    map_point_at(ap, leaf, &fp->P2, &fp->pl2, b);
    double a0 = wrapdiff(a[0] - uvw0[0]) * pm->su, a1 = wrapdiff(a[1] - uvw0[1]) * pm->sv;
    double b0 = wrapdiff(b[0] - uvw0[0]) * pm->su, b1 = wrapdiff(b[1] - uvw0[1]) * pm->sv;
    double s1 = fp->width / fp->c / fp->d1, s2 = fp->width / fp->d2;
    double l1 = a0 * a0 + a1 * a1, l2 = b0 * b0 + b1 * b1;
    if (dims == 3) {
        double a2 = wrapdiff(a[2] - uvw0[2]), b2 = wrapdiff(b[2] - uvw0[2]);
        l1 += a2 * a2, l2 += b2 * b2;
    }
    *l2out = l2 * (s2 * s2);
    return l1 * (s1 * s1);
}

/* A band-limited solid's footprint width, squared: RenderMan's filterwidth, the square
 * root of the footprint's area (the mean of its extents over u, v and w), which does not
 * blur a surface seen at a grazing angle across its whole width as the longer extent
 * would. */
double tex_solid_width2(const struct tex_apply *ap, const struct placement *pm,
                           const struct tex_object *leaf, struct footprint *fp, const tex_v3 *P,
                           const tex_v3 *pl, const double uvw0[3])
{
    double l1 = 0, l2 = 0;
    tex_v3 g[3];
    if (map_gradient(ap, leaf, g)) { /* the derivatives along t1, t2, as tex_footprint_width2 */
        const double sc[3] = {pm->su, pm->sv, 1};
        footprint_tangents(fp);
        for (int k = 0; k < 3; k++) {
            double a = tex_v3_dot(g[k], fp->t1) * sc[k], b = tex_v3_dot(g[k], fp->t2) * sc[k];
            l1 += a * a, l2 += b * b;
        }
        return sqrt(l1 * l2) * (fp->width * fp->width) / (fp->c * fp->l2);
    }
    l1 = stepped_width2(ap, pm, leaf, fp, P, pl, uvw0, 3, &l2);
    return sqrt(l1 * l2);
}

/* The footprint's size in texture units (after placement) for texture ap at the hit P (pl)
 * that its mapping took to (u0, v0) on face: the longer of its extents along t1 and t2,
 * squared (the mip level takes it so: neither a root nor a normalised tangent here). */
double tex_footprint_width2(const struct tex_apply *ap, const struct placement *pm,
                               const struct tex_object *leaf, struct footprint *fp,
                               const tex_v3 *P, const tex_v3 *pl, int face, double u0, double v0)
{
    double du[2], dv[2], m2;
    if (placed_derivatives(ap, pm, leaf, fp, pl, face, du, dv)) { /* then over the length */
        double c2 = fp->c * fp->c, l1 = du[0] * du[0] + dv[0] * dv[0];
        double l2 = (du[1] * du[1] + dv[1] * dv[1]) * c2;
        return (l1 > l2 ? l1 : l2) * (fp->width * fp->width) / (fp->l2 * c2);
    }
    double m1 = stepped_width2(ap, pm, leaf, fp, P, pl, (double[3]){u0, v0, 0}, 2, &m2);
    return m1 > m2 ? m1 : m2;
}
