/* box4.h - four boxes side by side, and one ray's slab test of all four (libtex internal)
 *
 * The tree's eye-ray walk goes four children a node (render_bvh.c): a node holds its
 * children's boxes axis by axis, lane by lane (lo[axis][child]), so that one ray tests
 * them in vector lanes (x86/bvh_x86.h).  tex_box4_hit is the test in plain C, lane by
 * lane render_bvh.c's hit_box, its operations in its order: the lanes' answers are its.
 */
#ifndef TEX_BOX4_H
#define TEX_BOX4_H

#include "vecmath.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_box4 {
    double lo[3][4], hi[3][4];
};

/* The boxes of b a ray (origin o, reciprocal direction inv) enters within [tmin, tmax]:
 * bit c for box c, its entry distance in t[c] */
static inline int tex_box4_hit(const struct tex_box4 *b, const tex_v3 *o, const tex_v3 *inv,
                               double tmin, double tmax, double t[4])
{
    const double oc[3] = {o->x, o->y, o->z}, ic[3] = {inv->x, inv->y, inv->z};
    int in = 0;
    for (int c = 0; c < 4; c++) {
        double lo = tmin, hi = tmax;
        for (int a = 0; a < 3; a++) {
            double p = (b->lo[a][c] - oc[a]) * ic[a], q = (b->hi[a][c] - oc[a]) * ic[a];
            lo = tex_maxd(lo, tex_mind(p, q)), hi = tex_mind(hi, tex_maxd(p, q));
        }
        t[c] = lo;
        in |= (lo <= hi) << c;
    }
    return in;
}

#ifdef __cplusplus
}
#endif
#endif
