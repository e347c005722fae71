/* bvh.h - the bounding-volume hierarchy and the scene's ray queries (libtex internal)
 *
 * The top-level objects sit in a BVH (render_bvh.c); a CSG block of many operands is
 * balanced into one too (tex_csg_balance).  Every ray of the renderer asks here: the
 * closest hit, any hit (shadows), the light passing through transparent solids.
 */
#ifndef TEX_BVH_H
#define TEX_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "shape.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_scene;
struct tex_ray;

/* The closest hit along a ray o + t d beyond tmin: 1 and *hit, or 0.  The
 * queries take the ray's vectors by address: every ray makes them.  from: a top-level
 * object the ray cannot meet, or NULL: it is not tested (a ray leaving a hull leaf's
 * surface outwards: o just outside it, d away from it). */
int tex_scene_trace(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d, double tmin,
                    double tmax, const struct tex_object *from, struct tex_hit *hit);

/* The closest hit of a ray known to miss the box of every bounded object (tex_scene_view):
 * the unbounded objects' alone, which is tex_scene_trace's answer for such a ray. */
int tex_scene_trace_unbounded(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                              double tmin, double tmax, struct tex_hit *hit);

/* The box of the bounded objects as seen from a point c in an orthonormal frame u, v, w (w
 * ahead): every point of the box lies ahead of c along w, and its projection (u, v) / w
 * lies inside rect = {u0, u1, v0, v1}, widened far beyond the rounding.  A ray from c
 * whose direction projects outside rect misses the box.  1, or 0 where there is no box or
 * it is not wholly ahead.  The same for the boxes of the first TEX_VIEW_OBJECTS bounded
 * objects in the tree's order (object; one not wholly ahead: the whole plane). */
#define TEX_VIEW_OBJECTS 63
struct tex_view {
    double rect[4];
    int n, more; /* objects with a rect in object; more: others follow them */
    double object[TEX_VIEW_OBJECTS][4];
};
int tex_scene_view(const struct tex_scene *s, tex_v3 c, tex_v3 u, tex_v3 v, tex_v3 w,
                   struct tex_view *vw);
/* The bounded objects a ray from vw's c can meet when its direction projects inside r =
 * {u0, u1, v0, v1}: bit i for object i, bit TEX_VIEW_OBJECTS for all past vw's n where
 * there are more; 0: none (r misses rect, or every object's) */
uint64_t tex_view_objects(const struct tex_view *vw, const double r[4]);
/* tex_scene_trace from 0 on, for a ray from the c of a tex_view whose direction projects
 * where tex_view_objects gave visit: the bounded objects out of visit (it cannot meet
 * them) untested */
int tex_scene_trace_view(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                         uint64_t visit, struct tex_hit *hit);

/* tex_scene_trace_view of n rays (n <= 64) at once, all of one packet's visit: the closest
 * hit of ray k (found[k]: 1 and hit[k], or 0), the one its own walk finds.  They walk the
 * tree together, a node's boxes against every ray still in it; a ray whose closest hit ties
 * with another object's walks alone after them.  The number of those. */
int tex_scene_trace_packet(const struct tex_scene *s, int n, const struct tex_ray *r,
                           uint64_t visit, struct tex_hit *hit, int *found);

/* Fraction of light passing along o + t d for t in (tmin, tmax): the product
 * of the surfaces' Kt over every boundary crossed, 0 if it falls to 1e-4.  from: as for
 * tex_scene_trace. */
double tex_scene_transmit(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                          double tmin, double tmax, const struct tex_object *from);
#define TEX_TRANSMIT_MAX 64
/* A ray as the tree's walks read it: o + t d, inv d's reciprocals for the boxes' slabs
 * (tex_v3_slab_inv), dd = d.d and idd = 1 / dd */
struct tex_bvh_ray {
    tex_v3 o, d, inv;
    double dd, idd;
};
/* Shadow rays to trace together, in the layout the walk reads: the caller writes ray i's o
 * and d into r[i], its segment (tmin[i], tmax[i]) and from[i]; tex_scene_transmit_n fills
 * the rest of r[i] in place and tr[i].  Nothing is copied on the way into the tree. */
struct tex_shadow_rays {
    int n;
    struct tex_bvh_ray r[TEX_TRANSMIT_MAX];
    double tmin[TEX_TRANSMIT_MAX], tmax[TEX_TRANSMIT_MAX];
    const struct tex_object *from[TEX_TRANSMIT_MAX];
    double tr[TEX_TRANSMIT_MAX];
};
/* Whether rays gain from going together through the scene's tree: more than one leaf's
 * objects (a tree of one leaf walked by a batch cost the spheres benchmark 7 % more CPU
 * than each ray's own walk) */
int tex_scene_shadow_batches(const struct tex_scene *s);
/* tex_scene_transmit of b's n rays (n <= TEX_TRANSMIT_MAX) at once, ray i o + t d for t in
 * (tmin[i], tmax[i]), not meeting from[i]: tr[i], the value tex_scene_transmit gives it */
void tex_scene_transmit_n(const struct tex_scene *s, struct tex_shadow_rays *b);

struct tex_bvh *tex_bvh_build(struct tex_object **obs, int n);
void tex_bvh_free(struct tex_bvh *b);
int tex_bvh_trace(const struct tex_bvh *b, const tex_v3 *o, const tex_v3 *d, double tmin,
                  double tmax, struct tex_hit *hit);
/* any = 1: stop at the first hit found, not necessarily the nearest (shadows). */
int tex_bvh_trace_any(const struct tex_bvh *b, const tex_v3 *o, const tex_v3 *d, double tmin,
                      double tmax, int any, struct tex_hit *hit);


/* CSG blocks as hierarchies.  alloc gives zeroed memory that lives as long as the scene
 * (it never returns NULL: it may longjmp, as the scene's pool does). */
typedef void *(*tex_csg_alloc)(void *ctx, size_t n);
/* kids[0..n) joined by op as a balanced tree (recursion log2(n) deep), its nodes marked
 * as clusters at line:col */
struct tex_object *tex_csg_balanced(enum tex_csg_op op, struct tex_object **kids, int n, int line,
                                    int col, tex_csg_alloc alloc, void *ctx);
/* The CSG blocks of ob's tree, each rebuilt spatially (after the world transforms are set:
 * the boxes are the world's).  A union's or an intersection's operands are all those under
 * ob; a difference's, those of the union it subtracts.  -1 out of memory. */
int tex_csg_spatial(struct tex_object *ob, tex_csg_alloc alloc, void *ctx);

#ifdef __cplusplus
}
#endif
#endif
