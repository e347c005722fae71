/* scene.h - inside t_apply's ray tracer: the scene's data, shapes, CSG,
 * BVH, textures, application functions, lights and media (libtex internal;
 * the public interface is render.h: load, set options, render, free)
 *
 * A minimal Whitted ray tracer (thesis 4.3.4-4.4, 5.3; DESIGN section 6)
 * that maps texture maps onto CSG objects through application functions.
 * The scene language is described in t_apply(5).
 *
 * Errors name the place: "vase.scene:12:7: unknown texture 'wood'".
 * Warnings (e.g. the camera inside an object) are kept in s->warnings,
 * one per line, for the tool to print.
 *
 * Modules (Rayshade's split):
 *   render_scene.c   the scene language (its blocks; tokens and expressions
 *                    through lang/lex.h and lang/expr.h)
 *   render_params.c  the scene's parameters as rows (param.h)
 *   render_shape.c   sphere, box, cylinder, cone, plane, torus: a method
 *                    table per shape (intervals along a ray, normal, uv,
 *                    bounds), and CSG: union, intersection, difference of
 *                    hit intervals
 *   render_bvh.c     bounding-volume hierarchy over the top-level objects
 *   render_texture.c textures (maps with mip-map pyramids, primitives),
 *                    mappings and application functions
 *   render_light.c   distant, point, spot and area lights; shadows
 *   render_media.c   the stack of nested transparent media along a ray
 *   render_shade.c   shading models (Whitted-Phong), see render_shade.h
 *   render_ct.c      the Cook-Torrance model, see render_ct.h
 *   render.c         camera, sampling, the integrator (direct light,
 *                    reflection, refraction), tiles and threads
 *
 * Geometry is double precision.  Every shape is canonical in its own space
 * and placed by an affine transform; rays are transformed, not normalised,
 * so a ray parameter t means the same point in every space.
 */
#ifndef TEX_SCENE_H
#define TEX_SCENE_H

#include <math.h>
#include <stdint.h>

#include "colour.h"
#include "../base/map.h"
#include "../base/trig.h"
#include "../prim/prim.h"
#include "../lang/expr.h"
#include "render_shade.h"
#include "render.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- vectors ------------------------------------------------------------ */

/* The smaller and larger of two numbers by plain compares: fmin and fmax
 * are library calls at -O2 (for their NaN rules). */
static inline double tex_mind(double a, double b)
{
    return a < b ? a : b;
}
static inline double tex_maxd(double a, double b)
{
    return a > b ? a : b;
}

typedef struct tex_v3 {
    double x, y, z;
} tex_v3;

static inline tex_v3 tex_v3_make(double x, double y, double z)
{
    tex_v3 r = {x, y, z};
    return r;
}
static inline tex_v3 tex_v3_add(tex_v3 a, tex_v3 b)
{
    return tex_v3_make(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline tex_v3 tex_v3_sub(tex_v3 a, tex_v3 b)
{
    return tex_v3_make(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline tex_v3 tex_v3_scale(tex_v3 a, double s)
{
    return tex_v3_make(a.x * s, a.y * s, a.z * s);
}
static inline tex_v3 tex_v3_madd(tex_v3 a, tex_v3 b, double s)
{
    return tex_v3_make(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s);
}
static inline double tex_v3_dot(tex_v3 a, tex_v3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline tex_v3 tex_v3_cross(tex_v3 a, tex_v3 b)
{
    return tex_v3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double tex_v3_len(tex_v3 a)
{
    return sqrt(tex_v3_dot(a, a));
}
static inline tex_v3 tex_v3_norm(tex_v3 a)
{
    double l = tex_v3_len(a);
    return l > 0 ? tex_v3_scale(a, 1 / l) : a;
}
static inline double tex_v3_get(tex_v3 a, int i)
{
    return i == 0 ? a.x : i == 1 ? a.y : a.z;
}

/* 1/d per component for slab tests, zeros nudged to 1e-300 first: IEEE
 * division would give +-inf, and 0 * inf is NaN where the ray's origin lies
 * on a slab's plane.  An addition instead of a test: 1e-300 vanishes beside
 * any component over 1e-284. */
static inline tex_v3 tex_v3_slab_inv(tex_v3 d)
{
    return tex_v3_make(1 / (d.x + 1e-300), 1 / (d.y + 1e-300), 1 / (d.z + 1e-300));
}

/* The angle of (x, y) in turns, in [0, 1): u around an axis, as the natural mappings
 * and the projections take it (tex_atan2: the same bytes in lanes) */
static inline double tex_turns(double y, double x)
{
    double a = tex_atan2(y, x) / (2 * M_PI);
    return a < 0 ? a + 1 : a;
}

/* The angle from the y axis in half turns, in [0, 1], of a direction whose y over its
 * length is c: v down a sphere, acos(c) / pi, as tex_atan2 takes it */
static inline double tex_polar(double c)
{
    c = fmax(-1, fmin(1, c));
    return tex_atan2(sqrt((1 - c) * (1 + c)), c) / M_PI;
}

/* Affine transform: p' = m[0..2][0..2] p + m[..][3]. */
typedef struct tex_xform {
    double m[3][4];
} tex_xform;

void tex_xform_identity(tex_xform *t);
/* r = a after b (apply b first). */
void tex_xform_mul(tex_xform *r, const tex_xform *a, const tex_xform *b);
/* -1 if singular. */
int tex_xform_invert(tex_xform *r, const tex_xform *a);
/* Inline: every ray meets them per leaf. */
static inline tex_v3 tex_xform_point(const tex_xform *t, tex_v3 p)
{
    const double(*m)[4] = t->m;
    return tex_v3_make(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                       m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                       m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]);
}
static inline tex_v3 tex_xform_dir(const tex_xform *t, tex_v3 d)
{
    const double(*m)[4] = t->m;
    return tex_v3_make(m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z,
                       m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
                       m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z);
}
/* The normal transform: the inverse's transpose applied to n (pass the inverse). */
static inline tex_v3 tex_xform_normal(const tex_xform *inv, tex_v3 n)
{
    const double(*m)[4] = inv->m;
    return tex_v3_make(m[0][0] * n.x + m[1][0] * n.y + m[2][0] * n.z,
                       m[0][1] * n.x + m[1][1] * n.y + m[2][1] * n.z,
                       m[0][2] * n.x + m[1][2] * n.y + m[2][2] * n.z);
}

/* ---- rays and optics ---------------------------------------------------- */

struct tex_media;

typedef struct tex_ray {
    tex_v3 o, d;      /* d is unit length in world space */
    double width;     /* footprint width at o (for filtered texture lookups) */
    double spread;    /* footprint growth per unit distance (pixel angle) */
    const struct tex_media *media; /* the solids it travels inside; NULL: air */
    double dist;      /* the path's length from the eye to o */
} tex_ray;

/* Nested transparent media: the top-level solids a ray is inside, innermost
 * last.  A refracted ray entering a solid pushes it, one leaving pops it, so
 * Snell's law sees the real indices on both sides: glass in water bends by
 * 1.33 -> 1.5, an air bubble in glass by 1.5 -> 1.  The stack is bounded by
 * the recursion depth; past TEX_MEDIA_MAX the outermost are forgotten. */
#define TEX_MEDIA_MAX 16
struct tex_media {
    int n;
    const struct tex_object *ob[TEX_MEDIA_MAX];
    double ior[TEX_MEDIA_MAX];
};
/* The index of the medium a ray with stack m travels in (1: air). */
double tex_media_ior(const struct tex_media *m);
/* A crossing of solid ob's boundary (entering or not) whose surface has
 * index ior: *out is the stack beyond it, *n1 and *n2 the indices before
 * and after.  m may be NULL (air). */
void tex_media_cross(const struct tex_media *m, const struct tex_object *ob, int entering,
                     double ior, struct tex_media *out, double *n1, double *n2);

/* Mirror direction of unit d about unit n.  Inline, as the next two: every
 * reflective hit calls it, and a 24-byte argument passed on the stack
 * costs a store-forwarding stall. */
static inline tex_v3 tex_reflect(tex_v3 d, tex_v3 n)
{
    return tex_v3_madd(d, n, -2 * tex_v3_dot(d, n));
}
/* Refraction of unit d through a surface with unit normal n facing against
 * d, from index n1 into index n2 (Snell).  Returns 0 on total internal
 * reflection, else 1 with *t the unit refracted direction. */
static inline int tex_refract(tex_v3 d, tex_v3 n, double n1, double n2, tex_v3 *t)
{
    double eta = n1 / n2;
    double cosi = -tex_v3_dot(d, n);
    double k = 1 - eta * eta * (1 - cosi * cosi);
    if (k < 0)
        return 0;
    *t = tex_v3_norm(tex_v3_add(tex_v3_scale(d, eta), tex_v3_scale(n, eta * cosi - sqrt(k))));
    return 1;
}

/* ---- shapes and CSG ----------------------------------------------------- */

enum tex_shape_kind { TEX_SHAPE_SPHERE, TEX_SHAPE_BOX, TEX_SHAPE_CYLINDER, TEX_SHAPE_CONE,
                      TEX_SHAPE_PLANE, TEX_SHAPE_TORUS, TEX_SHAPE_NKINDS };

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
static inline tex_v3 tex_v3_min(tex_v3 a, tex_v3 b)
{
    return tex_v3_make(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}
static inline tex_v3 tex_v3_max(tex_v3 a, tex_v3 b)
{
    return tex_v3_make(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}
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
/* Combine two interval lists with a CSG operation. */
void tex_csg_combine(enum tex_csg_op op, const struct tex_spans *a, const struct tex_spans *b,
                     struct tex_spans *r);
/* World bounds of an object; 0 if unbounded. */
int tex_object_bounds(struct tex_object *ob);
/* Marks the leaves of top-level object ob that hold all of it (struct tex_object's hull). */
void tex_object_hulls(struct tex_object *ob);

/* ---- textures, mappings, application functions --------------------------- */

enum tex_mapping { TEX_MAP_NATURAL, TEX_MAP_SPHERE, TEX_MAP_CYLINDER, TEX_MAP_CONE,
                   TEX_MAP_BOX, TEX_MAP_PLANAR, TEX_MAP_SOLID, TEX_MAP_WORLD, TEX_MAP_WAVY,
                   TEX_MAP_CROSS };
/* How a cross mapping combines its two maps */
enum tex_combine { TEX_COMBINE_PRODUCT, TEX_COMBINE_MIN, TEX_COMBINE_MAX };

struct tex_texture {
    char *name;
    tex_map **mip;       /* a map's pyramid: mip[0] is the map; NULL for point primitives */
    int levels_read;     /* 1: the pyramid's levels came from a mip-mapped file, not built */
    int nlevels;
    int subregions;      /* > 0: the map holds region ids (nearest lookup, no filtering) */
    struct tex_field *field; /* a primitive evaluated at hit points */
    int solid;           /* the field is evaluated at (u,v,w) */
    const struct tex_palette *palette; /* `palette NAME`: colours the values (ops/palette.h) */
    int line, col;
};

/* Sample a texture at (u,v[,w]) with a footprint of fw texture-space units;
 * out receives RGB (grey maps repeated).  Returns the region id or 0. */
int tex_texture_eval(const struct tex_texture *t, double u, double v, double w, double fw,
                     float out[3]);
/* A mip-mapped map's (no region ids) trilinear values at n placed points (u, v in
 * [0, 1000000], repeating every unit) for footprints of squared widths fw2, as RGB into
 * out[3 n]; grad (or NULL): the gradients of their luminance per unit of u and of v into
 * grad[2 n].  In vector lanes where the CPU has AVX-512: the same bytes. */
void tex_texture_points(const struct tex_texture *t, int n, const double *u, const double *v,
                        const double *fw2, float *out, double *grad);
struct tex_scene;
/* A hit's textures looked up ahead, with the other hits of its packet (render.c traces
 * a tile's eye rays first): for the first TEX_PREFETCH_MAX textures its surface sf
 * applies, where the mapping took the hit (as tex_resolve_material would find it) and,
 * for primitives evaluated at hit points, their values from one call over the packet. */
#define TEX_PREFETCH_MAX 8
struct tex_prefetch {
    const struct tex_surface *sf; /* the surface these are for; NULL: none */
    const struct tex_object *leaf;
    tex_v3 P, pl;                 /* the hit, in world and in its leaf's object space */
    tex_v3 D, N;                  /* the shading frame's ray and normal (width > 0) */
    double width;                 /* the footprint's width there, 0 if not filtered */
    int n;                        /* applied textures prefetched */
    struct tex_prefetch_ap {
        const struct tex_texture *tex;
        double uvw0[3], uvw[3]; /* the mapping's coordinates, then placed (if inside) */
        int face, inside, pending, has_val; /* pending: a value still to evaluate */
        int bump; /* a function of its texture bumps (struct placement's) */
        double fw; /* a map's footprint (squared), looked up with it */
        double grad[2]; /* a bumped map's gradient (map_eval's) */
        int has_tilt;   /* and the tilt's direction, made ahead (the bump scales it) */
        double tilt[3];
        float val[TEX_MAP_MAX_CHANNELS]; /* the primitive's value; a map's as RGB (has_val) */
    } ap[TEX_PREFETCH_MAX];
};
/* Where a ray met a surface, as the application functions see it. */
struct tex_shade_at {
    const struct tex_object *leaf;
    const tex_v3 *P, *D; /* the world point, the ray's unit direction */
    double width;        /* the ray's footprint at P (filtered lookups if the scene filters) */
    double dist;         /* the path's length from the eye to P */
    int depth;           /* 0 for eye rays, +1 per reflection or refraction */
    const struct tex_prefetch *pre; /* the hit's prefetched lookups, or NULL */
};
/* A packet's lookups ahead (render.c): pf's mapping of the hit P on leaf, surface sf;
 * then the values of every primitive at the pending points of the n hits pf[i], each
 * primitive in batched calls (eval3 / eval2 over many points), and of a surface's first
 * texture where it is a mip-mapped map, footprints and all (and where bumped, its
 * gradient and the tilt's direction). */
void tex_prefetch_map(struct tex_prefetch *pf, const struct tex_surface *sf,
                      const struct tex_object *leaf, const tex_v3 *P);
/* Whether sf's lookups ahead take footprints (a band-limited solid texture, a mip-mapped
 * map); then, after tex_prefetch_map, the hit's shading frame as tex_resolve_material gets
 * it (D, N as shade() orients it; width 0 when the scene does not filter). */
int tex_surface_footprints(const struct tex_surface *sf);
void tex_prefetch_footprints(struct tex_prefetch *pf, const tex_v3 *D, const tex_v3 *N,
                             double width);
void tex_prefetch_eval(struct tex_prefetch *const *pf, int n);
/* A packet's hits on one leaf whose surface's one map is mapped planar on a plane (a
 * plane's natural mapping is) or natural on a box, cylinder, cone or sphere are looked up
 * in vector lanes from end to end: mapping (gradients and all), footprint and trilinear
 * lookup, with no pass through the records between the steps (tex_prefetch_lanes).  Their
 * records, and their points, shading frames (D, N as shade() orients them) and footprint
 * widths in rows. */
#define TEX_LANES 64
struct tex_lanes {
    int n;
    const struct tex_surface *sf;
    const struct tex_object *leaf;
    struct tex_prefetch *pf[TEX_LANES];
    double p[3][TEX_LANES], d[3][TEX_LANES], nn[3][TEX_LANES], w[TEX_LANES];
};
/* Whether the hit of record pf on leaf (surface sf, whose lookups take footprints; P, D, N
 * and width > 0 as for tex_prefetch_footprints) goes in L's lanes: 1, queued there (a
 * direct surface, tex_resolve_material's short way, whose map's mapping the lanes make,
 * where the CPU has AVX-512, and the same leaf as the hits queued before); else 0, for
 * tex_prefetch_map and the rest. */
int tex_lanes_take(struct tex_lanes *L, struct tex_prefetch *pf, const struct tex_surface *sf,
                   const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *D,
                   const tex_v3 *N, double width);
/* The queued hits' records made as tex_prefetch_map, tex_prefetch_footprints and
 * tex_prefetch_eval make them, the same bytes; those the lanes cannot finish (outside the
 * map's window, seen head-on) are mapped the usual way and listed in rest for
 * tex_prefetch_eval: returns how many.  L is emptied. */
int tex_prefetch_lanes(struct tex_lanes *L, struct tex_prefetch **rest);
/* The material at a hit (surface sf): the application functions evaluated,
 * N bent by bump and normal maps, colours in the scene's colour space;
 * m[1] is the blended surface's where m[0].blend > 0 (its weight).
 * sf's cache must be filled (tex_surface_cache). */
void tex_resolve_material(const struct tex_scene *s, const struct tex_surface *sf,
                          const struct tex_shade_at *at, tex_v3 *N, struct tex_material m[2]);
/* Whether sf's material at a hit is a plain one, Whitted-Phong without a blend or rays of
 * its own (Kr and Kt 0, neither textured): 0, not; 1, untextured or a direct surface (see
 * tex_lanes_take) whose functions are compiled ones of Kd alone, whose material
 * tex_plain_material gives from the hit's lookups ahead pre (0 where they were not made);
 * 2, any other, whose material (and normal N, bent) tex_plain_resolve gives through
 * tex_resolve_material's path, at.  In an RGB scene: the colours and exponent
 * tex_resolve_material would give (Kr and Kt stay 0). */
struct tex_plain {
    float ka[3], kd[3], ks[3];
    double n;
};
int tex_surface_plain(const struct tex_surface *sf);
int tex_plain_material(const struct tex_surface *sf, const struct tex_prefetch *pre,
                       struct tex_plain *m);
void tex_plain_resolve(const struct tex_scene *s, const struct tex_surface *sf,
                       const struct tex_shade_at *at, tex_v3 *N, struct tex_plain *m);
/* Fill (tex_render, before tracing) and free a surface's cache: its untextured
 * colours in the scene's colour space, its application functions compiled. */
int tex_surface_cache(struct tex_surface *sf, const struct tex_colour_space *cs);
void tex_surface_uncache(struct tex_surface *sf);
/* Build the pyramid of mip[0] (box filter, wrapping). */
int tex_texture_build_mip(struct tex_texture *t);

/* The parameters an application function can set: the surface's Ka..ior, then bump,
 * Cook-Torrance's m and s, the weight of a blended surface, a tangent-space normal map and
 * a height gradient (tex_sparam_row gives each one's row). */
enum tex_sparam { TEX_SP_KA, TEX_SP_KD, TEX_SP_KS, TEX_SP_N, TEX_SP_KR, TEX_SP_KT, TEX_SP_IOR,
                  TEX_SP_BUMP, TEX_SP_M, TEX_SP_S, TEX_SP_BLEND, TEX_SP_NORMAL,
                  TEX_SP_GRADIENT, TEX_SP_COUNT };

/* An application function's expression, compiled (lang/expr.h): a postfix
 * program over f (the map value), p (the untextured value), numbers, colours,
 * other textures (a cascade) and the renderer's quantities at the hit, run
 * per RGB channel.  Its operands: */
enum tex_eleaf { TEX_LEAF_F, TEX_LEAF_P, TEX_LEAF_TEX /* ptr: the texture */,
                 TEX_LEAF_Q /* TEX_LEAF_Q + q: quantity q */ };

/* The renderer's quantities an application function can read (composition
 * at application time, thesis 5.2.4.1): their names and help are
 * tex_quantities[q], in this order. */
enum tex_quantity { TEX_Q_DIST, TEX_Q_FOOTPRINT, TEX_Q_LOD, TEX_Q_NDOTV, TEX_Q_DEPTH,
                    TEX_Q_X, TEX_Q_Y, TEX_Q_Z, TEX_Q_OX, TEX_Q_OY, TEX_Q_OZ,
                    TEX_Q_U, TEX_Q_V, TEX_Q_W, TEX_Q_NX, TEX_Q_NY, TEX_Q_NZ, TEX_Q_REGION,
                    TEX_Q_COUNT };
extern const struct tex_scene_word tex_quantities[TEX_Q_COUNT + 1]; /* render.h */

/* g[region][parameter] = h: one application function. */
struct tex_appfn {
    int region;          /* 0: every region (or a map without regions) */
    enum tex_sparam param;
    double lo, hi;       /* the range results are clamped to: tex_sparam_row(param)'s */
    struct tex_expr *e;
    struct tex_appfn *next;
};

/* One texture applied to a surface: its mapping, window, placement and functions. */
struct tex_apply {
    const struct tex_texture *tex;
    enum tex_mapping mapping;
    double u1, v1, u2, v2; /* the texture window */
    double nu, nv;         /* repeat counts (1 1: stretch) */
    double scale;          /* world / planar mapping: texture units per world unit */
    /* projections (thesis 5.2.1.3): the texture's frame relative to the object, its y axis
     * along `axis`, then rotated and translated; to_tex takes points into it */
    tex_v3 axis;
    tex_xform place, to_tex;
    int placed;                        /* 1: to_tex is not the identity */
    double wave[2];                    /* wavy: amplitude (in u) and wavelength (along y) */
    const struct tex_texture *cross;   /* cross: the map on the y-z plane */
    enum tex_combine combine;          /* cross: how the two maps combine */
    struct tex_appfn *fns;
    struct tex_apply *next;
    int line, col;
};

struct tex_surface {
    char *name;
    float ka, kd[3], ks[3]; /* ka scalar times kd colour; ks scalar times white or colour */
    double n, kr, kt, ior;
    const struct tex_shading_model *model;
    struct tex_ct *ct;      /* Cook-Torrance parameters (render_ct.h); NULL: its defaults */
    const struct tex_surface *blend; /* `blend SURFACE`: mixed in by `blend = h`, or NULL */
    struct tex_apply *apply;
    int line, col;
    struct tex_surface_cache *cache; /* tex_render's (render_texture.c), or NULL */
};

/* ---- lights ------------------------------------------------------------- */

enum tex_light_kind { TEX_LIGHT_DISTANT, TEX_LIGHT_POINT, TEX_LIGHT_SPOT, TEX_LIGHT_AREA };
enum tex_falloff { TEX_FALL_NONE, TEX_FALL_SQUARE, TEX_FALL_POLY };

struct tex_light {
    enum tex_light_kind kind;
    float rgb[3];          /* colour times intensity */
    tex_colour e;          /* the same in the scene's colour space */
    tex_v3 pos, dir;       /* dir: towards the light for distant, the axis for spot */
    tex_v3 edge1, edge2;   /* area: a parallelogram pos + a edge1 + b edge2 */
    int samples;           /* area: samples per side */
    enum tex_falloff falloff;
    double c1, c2, c3;
    double cos_angle, exponent; /* spot */
    struct tex_curve *spectrum; /* `spectrum D65|A|blackbody K` (spectrum.h), or NULL */
    /* as the scene gives them (tex_light_rows); rgb, dir and cos_angle follow */
    float colour[3];
    double intensity, angle;
    tex_v3 direction, at;
};

/* Number of samples of a light (n*n for an area light, else 1), and sample
 * k with jitter (jx, jy) in [0,1): the unit direction L from P towards it,
 * its distance (infinity for distant lights) and the attenuation times the
 * spot falloff and the sample's share.  0 if it sends no light to P. */
int tex_light_samples(const struct tex_light *l);
/* The attenuation at distance dl (inline: point lights are sampled in the shading loop). */
static inline double tex_light_falloff(const struct tex_light *l, double dl)
{
    switch (l->falloff) {
    case TEX_FALL_SQUARE: return 1 / (dl * dl);
    case TEX_FALL_POLY: {
        double q = l->c1 + l->c2 * dl + l->c3 * dl * dl;
        return q > 1 ? 1 / q : 1;
    }
    default: return 1;
    }
}
/* Direction L, distance and attenuation from P to a light's point pos; 0
 * when P is at the light.  The one point-light evaluation (tex_light_point_at). */
static inline int tex_light_towards(const struct tex_light *l, const tex_v3 *pos, const tex_v3 *P,
                                    tex_v3 *L, double *dist, double *fatt)
{
    tex_v3 d = tex_v3_sub(*pos, *P);
    double dl = tex_v3_len(d);
    if (!(dl > 0))
        return 0;
    *L = tex_v3_scale(d, 1 / dl);
    *dist = dl;
    *fatt = tex_light_falloff(l, dl);
    return 1;
}
/* tex_light_towards, then a spot light's cone and cos^exponent falloff: 0 outside the
 * cone.  Inline: the shading loop calls it for point and spot lights, tex_light_sample
 * for area samples. */
static inline int tex_light_point_at(const struct tex_light *l, const tex_v3 *pos,
                                     const tex_v3 *P, tex_v3 *L, double *dist, double *fatt)
{
    if (!tex_light_towards(l, pos, P, L, dist, fatt))
        return 0;
    if (l->kind == TEX_LIGHT_SPOT) {
        double c = -tex_v3_dot(*L, l->dir);
        if (c < l->cos_angle)
            return 0;
        *fatt *= tex_powi(c, l->exponent); /* whole exponents: by squaring */
    }
    return 1;
}
int tex_light_sample(const struct tex_light *l, int k, double jx, double jy, tex_v3 P, tex_v3 *L,
                     double *dist, double *fatt);

/* ---- the scene ------------------------------------------------------------ */

struct tex_settings {
    int w, h, spp, depth, threads;
    int filter;       /* 1: mip-mapped texture lookups */
    uint64_t seed;
    double bailout;   /* reflected/refracted rays weighing less are not traced */
};

struct tex_bvh;

/* `environment FILE { ... }`: a lat-long map (Blinn and Newell's reflection map, thesis
 * 2.2.2) that rays leaving the scene look up by their direction: u = 0.5 + atan2(x, z) / 2pi
 * (+z, the default view, at the map's centre), v = acos(y) / pi (up at the top row). */
struct tex_environment {
    struct tex_texture *map;  /* NULL: the background colour */
    tex_v3 rotate;            /* degrees about x, y, z, as objects turn */
    double intensity;
    tex_xform to_map;         /* world directions into the map's frame */
};

struct tex_procs;
struct tex_scene {
    char *file;
    struct tex_procs *procs; /* composed primitives (lang/proc.h), or NULL */
    tex_v3 eye, look, up;
    double fov;                 /* horizontal, degrees */
    struct tex_settings settings;
    float ambient[3], background[3];
    struct tex_environment env;
    struct tex_colour_space cs;
    struct tex_light *lights;
    int nlights;
    struct tex_object **objects; /* top-level objects */
    int nobjects, cobjects;      /* in use, allocated */
    struct tex_bvh *bvh;
    struct tex_media eye_media; /* the transparent solids the camera is inside (prepare's) */
    /* everything allocated, freed together */
    struct tex_texture **textures;
    int ntextures;
    struct tex_surface **surfaces;
    int nsurfaces;
    struct tex_palette **palettes; /* the palettes scenes name (ops/palette.h) */
    int npalettes;
    void **pool;
    size_t npool, cpool;
    char *warnings;
    void *packets; /* render.c's packets, one a thread, kept from band to band */
    size_t packets_mapped;
    int npackets;
};

/* ---- the scene's parameters as rows (render_params.c) ------------------------ */

/* One table per block of t_apply(5), rows as in param.h: each row gives a
 * word, its type, default, range and help, and where the value is stored.
 * The scene parser reads a block by looking its words up here; t_apply
 * --help-scene prints them and t_apply(5)'s lists are made from them. */
extern const struct tex_param tex_settings_rows[]; /* top level, over struct tex_scene */
extern const struct tex_param tex_camera_rows[];   /* camera { }, over struct tex_scene */
extern const struct tex_param tex_light_rows[];    /* light KIND { }, over struct tex_light;
                                                    * kinds: bit enum tex_light_kind */
extern const struct tex_param tex_surface_rows[];  /* surface NAME { }, over struct tex_surface;
                                                    * rows 0..TEX_SP_IOR are Ka..ior in
                                                    * enum tex_sparam order */
extern const struct tex_param tex_apply_rows[];    /* apply TEXTURE { }, over struct tex_apply */
extern const struct tex_param tex_object_rows[];   /* SHAPE { }, over struct tex_shape_params;
                                                    * kinds: bit enum tex_shape_kind; surface
                                                    * and the transforms are also CSG words */
extern const struct tex_param tex_target_rows[];   /* bump, m, s, blend, normal, gradient:
                                                    * TEX_SP_BUMP.. in order */
extern const struct tex_param tex_environment_rows[]; /* environment FILE { }, over
                                                       * struct tex_environment */
/* The environment's colour (RGB, times its intensity) in direction d (unit, world), for a
 * ray whose footprint spreads by `spread` radians (0: no filtering). */
void tex_environment_eval(const struct tex_environment *e, const tex_v3 *d, double spread,
                          float rgb[3]);
/* The row of an application function's parameter: its name and the range its
 * results are clamped to. */
const struct tex_param *tex_sparam_row(enum tex_sparam sp);

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

/* Fraction of light passing along o + t d for t in (tmin, tmax): the product
 * of the surfaces' Kt over every boundary crossed, 0 if it falls to 1e-4.  from: as for
 * tex_scene_trace. */
double tex_scene_transmit(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                          double tmin, double tmax, const struct tex_object *from);

struct tex_bvh *tex_bvh_build(struct tex_object **obs, int n);
void tex_bvh_free(struct tex_bvh *b);
int tex_bvh_trace(const struct tex_bvh *b, const tex_v3 *o, const tex_v3 *d, double tmin,
                  double tmax, struct tex_hit *hit);
/* any = 1: stop at the first hit found, not necessarily the nearest (shadows). */
int tex_bvh_trace_any(const struct tex_bvh *b, const tex_v3 *o, const tex_v3 *d, double tmin,
                      double tmax, int any, struct tex_hit *hit);


#ifdef __cplusplus
}
#endif
#endif
