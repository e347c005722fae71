/* shape.h - the renderer's shapes and CSG (libtex internal)
 *
 * Sphere, box, cylinder, cone, plane and torus, each canonical in its own space and
 * placed by an affine transform, with a method table (render_shape.c): the intervals a
 * ray spends inside it, its normal, its own inverse mapping (u, v) and its bounds.  CSG
 * objects combine the intervals of their operands: union, intersection, difference.
 */
#ifndef TEX_SHAPE_H
#define TEX_SHAPE_H

#include "vecmath.h"

#ifdef __cplusplus
extern "C" {
#endif

enum tex_shape_kind { TEX_SHAPE_SPHERE, TEX_SHAPE_BOX, TEX_SHAPE_CYLINDER, TEX_SHAPE_CONE,
                      TEX_SHAPE_PLANE, TEX_SHAPE_TORUS, TEX_SHAPE_INF_CONE, TEX_SHAPE_NKINDS };

struct tex_surface;
struct tex_surface_cache;
struct tex_object;

/* One boundary crossing of a ray with a leaf shape. */
struct tex_hit {
    double t;
    const struct tex_object *leaf; /* NULL at +-infinity */
    int flip;                      /* 1: the normal points the other way (difference) */
};

/* A solid's extent along a ray: sorted disjoint intervals [in, out]. */
#define TEX_SPANS_MAX 16
struct tex_spans {
    int n;
    struct tex_hit in[TEX_SPANS_MAX], out[TEX_SPANS_MAX];
};

struct tex_bounds {
    tex_v3 lo, hi;
};
/* The box around both (BVH nodes, unions). */
static inline struct tex_bounds tex_bounds_union(struct tex_bounds a, struct tex_bounds b)
{
    return (struct tex_bounds){tex_v3_min(a.lo, b.lo), tex_v3_max(a.hi, b.hi)};
}
/* The box both share (intersections; lo > hi where they do not meet). */
static inline struct tex_bounds tex_bounds_meet(struct tex_bounds a, struct tex_bounds b)
{
    return (struct tex_bounds){tex_v3_max(a.lo, b.lo), tex_v3_min(a.hi, b.hi)};
}

struct tex_shape_methods {
    const char *name;
    /* Intervals of the canonical solid along o + t d (object space). */
    void (*spans)(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s);
    /* Outward normal (object space, any length) at a surface point. */
    tex_v3 (*normal)(const struct tex_object *ob, tex_v3 p);
    /* The shape's own inverse mapping: (u,v) in [0,1] and a face id (1...). */
    int (*uv)(const struct tex_object *ob, tex_v3 p, double *u, double *v);
    /* Bounds of the canonical solid; 0 if unbounded. */
    int (*bounds)(const struct tex_object *ob, struct tex_bounds *b);
};
extern const struct tex_shape_methods tex_shape_methods[TEX_SHAPE_NKINDS];
/* The box's own mapping: on faces 1..6 (+x -x +y -y +z -z, each seen from outside, v
 * downwards) u = (a + 1) / 2 and v = (b + 1) / 2, a and b the axes (1..3: x y z) given
 * here, negative where negated.  Its gradients (mapping.c) and lanes (x86/shape_x86.h)
 * read the same table. */
extern const signed char tex_box_axes[6][2];

enum tex_csg_op { TEX_CSG_LEAF, TEX_CSG_UNION, TEX_CSG_INTERSECTION, TEX_CSG_DIFFERENCE };

struct tex_object {
    enum tex_csg_op op;
    enum tex_shape_kind kind;   /* leaves */
    double r0, r1;              /* cone radii at y = 0 and y = 1 */
    tex_xform to_world, to_obj; /* leaves: the accumulated transform */
    const struct tex_surface *surface;
    struct tex_object *a, *b;   /* CSG children */
    const struct tex_object *root; /* the top-level object (solid texturing's box) */
    struct tex_bounds wb;       /* world bounds */
    int bounded;
    int cluster;                /* 1: a node joining a CSG block's children (no words of its own) */
    int line, col;              /* where it was declared */
    /* leaves, set by tex_object_bounds: the world normal without the transforms,
     * 1: a plane of unit normal fn; 2: a sphere placed by a similarity, n = (P - fn) fr */
    int fast;
    tex_v3 fn;
    double fr;
    int scaled; /* leaves: to_obj only scales and shifts (spans skip its zero terms) */
    /* bounded leaves, set by tex_object_bounds: the centre and half extents of the shape's
     * own box in object space (projection mappings' frame) */
    tex_v3 bc, be;
    /* leaves: 1 if convex (not a torus) and holding all of the top-level object, every node
     * above keeping only what lies inside it (an intersection, a difference's first
     * operand): a ray leaving its surface outwards cannot meet the object again */
    int hull;
};

/* The top-level object leaf belongs to: its root, or itself where none is set. */
static inline const struct tex_object *tex_object_top(const struct tex_object *leaf)
{
    return leaf->root ? leaf->root : leaf;
}

/* A shape's own words as its block gives them (tex_object_rows), at the rows'
 * defaults until then; the parser checks them against each other and turns
 * them into the placement of the canonical shape. */
struct tex_shape_params {
    tex_v3 centre;           /* sphere, torus */
    tex_v3 min, max;         /* box */
    tex_v3 base, top;        /* cylinder, cone */
    tex_v3 normal;           /* plane */
    tex_v3 axis;             /* torus */
    double radius;           /* sphere, cylinder */
    double radius1, radius2; /* cone: at the base and the top */
    double distance;         /* plane */
    double major, minor;     /* torus */
};

/* Intervals of an object (leaf or CSG tree) along a world ray o + t d. */
void tex_object_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s);
/* The same, for a ray whose line is known to meet ob's world box: inv is
 * tex_v3_slab_inv(d) (the BVH's ray). */
void tex_csg_spans(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                   const tex_v3 *inv, struct tex_spans *s);
/* The spans of a leaf (its transform applied) along a world ray. */
void tex_leaf_spans(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                    struct tex_spans *s);
/* Does the world segment o + t d, t in (tmin, tmax), cross the leaf's surface?  1 where it
 * surely does, -1 where it surely does not (as tex_leaf_spans would show), 0 where only
 * tex_leaf_spans can tell: a shadow ray's test without the spans.  Only the torus, whose
 * quartic is the dearest solve, answers other than 0. */
int tex_leaf_segment(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                     double tmin, double tmax);
/* Combine two interval lists with a CSG operation. */
void tex_csg_combine(enum tex_csg_op op, const struct tex_spans *a, const struct tex_spans *b,
                     struct tex_spans *r);
/* World bounds of an object; 0 if unbounded. */
int tex_object_bounds(struct tex_object *ob);
/* Marks the leaves of top-level object ob that hold all of it (struct tex_object's hull). */
void tex_object_hulls(struct tex_object *ob);

#ifdef __cplusplus
}
#endif
#endif
