/* vecmath.h - the renderer's geometry: vectors, affine transforms, rays and the media
 * they travel in (libtex internal)
 *
 * Geometry is double precision.  Every shape is canonical in its own space and placed by
 * an affine transform; rays are transformed, not normalised, so a ray parameter t means
 * the same point in every space.  The small functions are inline: every ray and hit
 * calls them, and a 24-byte argument passed on the stack costs a store-forwarding stall.
 */
#ifndef TEX_VECMATH_H
#define TEX_VECMATH_H

#include <math.h>

#include "../base/trig.h"

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

/* floor() in a few instructions (libm's takes tens at -O2 without SSE4.1);
 * exact, since doubles beyond 2^52 are integers (and NaN, inf pass through). */
static inline double tex_floord(double x)
{
    if (!(fabs(x) < 4503599627370496.0))
        return x;
    double t = (double)(long long)x;
    return t - (t > x); /* no branch: x's sign varies across a packet's hits */
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
/* The placements scenes write: a translation by v, a scale by v (per axis), and t after
 * turns of r.x degrees about x, then r.y about y, then r.z about z (in place). */
void tex_xform_translate(tex_xform *t, tex_v3 v);
void tex_xform_scale(tex_xform *t, tex_v3 v);
void tex_xform_rotate(tex_xform *t, tex_v3 r);
/* A frame taking the y axis to a (scaled to ylen), x and z at radius r about it, at
 * origin: world x (or z) made perpendicular to a, so that an upright plane keeps the
 * world's x and z as its planar coordinates. */
void tex_xform_frame(tex_xform *t, tex_v3 origin, tex_v3 a, double ylen, double r);
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
static inline tex_v3 tex_v3_min(tex_v3 a, tex_v3 b)
{
    return tex_v3_make(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z));
}
static inline tex_v3 tex_v3_max(tex_v3 a, tex_v3 b)
{
    return tex_v3_make(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z));
}

/* ---- rays and optics ---------------------------------------------------- */

struct tex_media;
struct tex_object;

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

#ifdef __cplusplus
}
#endif
#endif
