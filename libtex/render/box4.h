/* box4.h - four boxes side by side, and one ray's slab test of all four (libtex internal)
 *
 * The tree's eye-ray walk goes four children a node (render_bvh.c): a node holds its
 * children's boxes axis by axis, lane by lane (lo[axis][child]), so that one ray tests
 * them in vector lanes (x86/bvh_x86.h).  tex_box4_hit is the test in plain C, lane by
 * lane render_bvh.c's hit_box, its operations in its order: the lanes' answers are its.
 * A packet's eye rays walk the tree together (tex_scene_trace_packet): tex_box4_rays tests
 * a node's boxes against the packet's rays, in plain C here, four rays a vector in AVX2's
 * lanes (x86/bvh_x86.h), the same answers.
 */
#ifndef TEX_BOX4_H
#define TEX_BOX4_H

#include <stdint.h>

#include "vecmath.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_box4 {
    double lo[3][4], hi[3][4];
};

/* Rays lane by lane: origins, their directions' reciprocals, the bounds of t */
struct tex_ray_lanes {
    double o[3][64], inv[3][64];
    const double *tmin, *tmax;
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

/* The rays of m (bit i: lane i of r) that enter box c of b (of those in mask) within
 * [tmin[i], tmax[i]]: in[c]; the least of their entry distances in t[c] (INFINITY: none) */
static inline void tex_box4_rays(const struct tex_box4 *b, int mask, const struct tex_ray_lanes *r,
                                 uint64_t m, uint64_t in[4], double t[4])
{
    for (int c = 0; c < 4; c++)
        in[c] = 0, t[c] = INFINITY;
    for (; m; m &= m - 1) {
        int i = __builtin_ctzll(m);
        tex_v3 o = tex_v3_make(r->o[0][i], r->o[1][i], r->o[2][i]);
        tex_v3 inv = tex_v3_make(r->inv[0][i], r->inv[1][i], r->inv[2][i]);
        double tc[4];
        int hit = tex_box4_hit(b, &o, &inv, r->tmin[i], r->tmax[i], tc) & mask;
        for (; hit; hit &= hit - 1) {
            int c = __builtin_ctz(hit);
            in[c] |= 1ull << i;
            t[c] = tex_mind(t[c], tc[c]);
        }
    }
}

#ifdef __cplusplus
}
#endif
#endif
