/* render_shape.c - the canonical shapes and CSG
 *
 * Canonical solids (object space):
 *   sphere    unit sphere at the origin
 *   box       the cube [-1,1]^3
 *   cylinder  radius 1, y in [0,1], capped (a cone with r0 = r1 = 1)
 *   cone      radius r0 at y = 0 and r1 at y = 1, capped (convex)
 *   plane     the half-space y <= 0, normal +y
 *   torus     around the y axis: (sqrt(x^2+z^2) - R)^2 + y^2 <= r^2 with
 *             R = r0 (major radius, >= 0) and r = r1 (minor radius, > 0)
 *   inf_cone  x^2 + z^2 <= (r0 + (r1 - r0) y)^2 for every y: the cone's side unbounded
 *             along its axis (both nappes; r0 = r1: an infinite cylinder)
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "render/scene.h"

/* ---- spans helpers ---------------------------------------------------------- */

static void span1(struct tex_spans *s, const struct tex_object *ob, double t0, double t1)
{
    s->n = 1;
    s->in[0].t = t0;
    s->in[0].leaf = isfinite(t0) ? ob : NULL;
    s->in[0].flip = 0;
    s->out[0].t = t1;
    s->out[0].leaf = isfinite(t1) ? ob : NULL;
    s->out[0].flip = 0;
}

/* ---- sphere ----------------------------------------------------------------- */

static inline __attribute__((always_inline)) void
sphere_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s)
{
    double a = tex_v3_dot(d, d), b = tex_v3_dot(o, d), c = tex_v3_dot(o, o) - 1;
    double disc = b * b - a * c;
    s->n = 0;
    if (disc <= 0 || a <= 0)
        return;
    double q = sqrt(disc), ia = 1 / a; /* the division beside the root, not after it */
    span1(s, ob, (-b - q) * ia, (-b + q) * ia);
}

static tex_v3 sphere_normal(const struct tex_object *ob, tex_v3 p)
{
    (void)ob;
    return p;
}

static int sphere_uv(const struct tex_object *ob, tex_v3 p, double *u, double *v)
{
    (void)ob;
    double r = tex_v3_len(p);
    *u = tex_turns(-p.z, p.x);
    *v = r > 0 ? tex_polar(p.y / r) : 0.5;
    return 1;
}

static int unit_bounds(const struct tex_object *ob, struct tex_bounds *b)
{
    (void)ob;
    b->lo = tex_v3_make(-1, -1, -1);
    b->hi = tex_v3_make(1, 1, 1);
    return 1;
}

/* ---- box -------------------------------------------------------------------- */

static inline __attribute__((always_inline)) void
box_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s)
{
    double t0 = -INFINITY, t1 = INFINITY;
    double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    s->n = 0;
    for (int i = 0; i < 3; i++) {
        double oi = oo[i], di = dd[i];
        if (di == 0) {
            if (oi < -1 || oi > 1)
                return;
            continue;
        }
        double inv = 1 / di, a = (-1 - oi) * inv, b = (1 - oi) * inv;
        if (a > b) {
            double x = a;
            a = b;
            b = x;
        }
        t0 = a > t0 ? a : t0;
        t1 = b < t1 ? b : t1;
    }
    if (t0 < t1)
        span1(s, ob, t0, t1);
}

static int box_face(tex_v3 p)
{
    double ax = fabs(p.x), ay = fabs(p.y), az = fabs(p.z);
    if (ax >= ay && ax >= az)
        return p.x > 0 ? 1 : 2;
    if (ay >= az)
        return p.y > 0 ? 3 : 4;
    return p.z > 0 ? 5 : 6;
}

static tex_v3 box_normal(const struct tex_object *ob, tex_v3 p)
{
    (void)ob;
    static const tex_v3 n[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    return n[box_face(p) - 1];
}

/* Faces 1..6 = +x -x +y -y +z -z, each seen from outside with v downwards: the axes of
 * u = (a + 1) / 2 and v = (b + 1) / 2 (shape.h) */
const signed char tex_box_axes[6][2] = {{-3, -2}, {3, -2}, {1, 3}, {1, -3}, {1, -2}, {-1, -2}};

static int box_uv(const struct tex_object *ob, tex_v3 p, double *u, double *v)
{
    (void)ob;
    int f = box_face(p);
    const double c[3] = {p.x, p.y, p.z};
    double ab[2];
    for (int i = 0; i < 2; i++) {
        int k = tex_box_axes[f - 1][i];
        ab[i] = k < 0 ? -c[-k - 1] : c[k - 1];
    }
    *u = fmin(1, fmax(0, (ab[0] + 1) / 2));
    *v = fmin(1, fmax(0, (ab[1] + 1) / 2));
    return f;
}

/* ---- cone and cylinder ---------------------------------------------------------- */

static inline __attribute__((always_inline)) void
cone_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s)
{
    double r0 = ob->r0, k = ob->r1 - ob->r0;
    double t[4];
    int n = 0;
    double a = d.x * d.x + d.z * d.z - k * k * d.y * d.y;
    double ry = r0 + k * o.y;
    double b = 2 * (o.x * d.x + o.z * d.z - ry * k * d.y);
    double c = o.x * o.x + o.z * o.z - ry * ry;
    s->n = 0;
    if (fabs(a) > 1e-14) {
        double disc = b * b - 4 * a * c;
        if (disc > 0) {
            double q = sqrt(disc), h = 0.5 / a;
            double r[2] = {(-b - q) * h, (-b + q) * h};
            for (int i = 0; i < 2; i++) {
                double y = o.y + r[i] * d.y;
                if (y >= 0 && y <= 1 && r0 + k * y >= 0)
                    t[n++] = r[i];
            }
        }
    } else if (fabs(b) > 1e-14) {
        double r = -c / b, y = o.y + r * d.y;
        if (y >= 0 && y <= 1)
            t[n++] = r;
    }
    if (d.y != 0) {
        double iy = 1 / d.y;
        for (int cap = 0; cap < 2; cap++) {
            double r = (cap - o.y) * iy;
            double x = o.x + r * d.x, z = o.z + r * d.z, rad = cap ? ob->r1 : r0;
            if (x * x + z * z <= rad * rad)
                t[n++] = r;
        }
    }
    if (n < 2)
        return;
    double lo = t[0], hi = t[0];
    for (int i = 1; i < n; i++) {
        lo = t[i] < lo ? t[i] : lo;
        hi = t[i] > hi ? t[i] : hi;
    }
    if (hi > lo)
        span1(s, ob, lo, hi);
}

/* 0: the side, 1: bottom cap, 2: top cap - whichever surface is nearest. */
static int cone_part(const struct tex_object *ob, tex_v3 p)
{
    double ry = ob->r0 + (ob->r1 - ob->r0) * p.y;
    double side = fabs(sqrt(p.x * p.x + p.z * p.z) - ry) / sqrt(1 + (ob->r1 - ob->r0) * (ob->r1 - ob->r0));
    double bot = fabs(p.y), top = fabs(p.y - 1);
    if (side <= bot && side <= top)
        return 0;
    return bot <= top ? 1 : 2;
}

static tex_v3 cone_normal(const struct tex_object *ob, tex_v3 p)
{
    int part = cone_part(ob, p);
    if (part == 1)
        return tex_v3_make(0, -1, 0);
    if (part == 2)
        return tex_v3_make(0, 1, 0);
    double k = ob->r1 - ob->r0, ry = ob->r0 + k * p.y;
    tex_v3 n = tex_v3_make(p.x, -k * ry, p.z);
    return tex_v3_len(n) > 0 ? n : tex_v3_make(0, 1, 0);
}

/* cylinder_map / cone_map: u around the axis, v down the side; caps as discs. */
static int cone_uv(const struct tex_object *ob, tex_v3 p, double *u, double *v)
{
    int part = cone_part(ob, p);
    if (part == 0) {
        *u = tex_turns(-p.z, p.x);
        *v = fmin(1, fmax(0, 1 - p.y));
        return 1;
    }
    double r = part == 1 ? ob->r0 : ob->r1;
    r = r > 0 ? r : 1;
    *u = fmin(1, fmax(0, (p.x / r + 1) / 2));
    *v = fmin(1, fmax(0, (p.z / r + 1) / 2));
    return part + 1;
}

static int cone_bounds(const struct tex_object *ob, struct tex_bounds *b)
{
    double r = ob->r0 > ob->r1 ? ob->r0 : ob->r1;
    b->lo = tex_v3_make(-r, 0, -r);
    b->hi = tex_v3_make(r, 1, r);
    return 1;
}

/* ---- infinite cone (thesis 5.3.1's inf_cone_map) ---------------------------------- */

/* Where x^2 + z^2 - (r0 + k y)^2 <= 0 along the ray: between the roots of the quadratic
 * where it opens upwards, outside them (two spans, one per nappe) where it opens
 * downwards, everywhere where it stays negative. */
static void inf_cone_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s)
{
    double k = ob->r1 - ob->r0, ry = ob->r0 + k * o.y;
    double a = d.x * d.x + d.z * d.z - k * k * d.y * d.y;
    double b = 2 * (o.x * d.x + o.z * d.z - ry * k * d.y);
    double c = o.x * o.x + o.z * o.z - ry * ry;
    s->n = 0;
    if (!(fabs(a) > 1e-14)) { /* along a generator's direction: linear */
        if (fabs(b) > 1e-14)
            span1(s, ob, b > 0 ? -INFINITY : -c / b, b > 0 ? -c / b : INFINITY);
        else if (c <= 0)
            span1(s, ob, -INFINITY, INFINITY);
        return;
    }
    double disc = b * b - 4 * a * c;
    if (!(disc > 0)) {
        if (a < 0)
            span1(s, ob, -INFINITY, INFINITY);
        return;
    }
    double q = sqrt(disc), h = 0.5 / a, t0 = (-b - q) * h, t1 = (-b + q) * h;
    if (t0 > t1) {
        double x = t0;
        t0 = t1, t1 = x;
    }
    if (a > 0) {
        span1(s, ob, t0, t1);
        return;
    }
    span1(s, ob, -INFINITY, t0);
    s->n = 2;
    s->in[1] = (struct tex_hit){.t = t1, .leaf = ob};
    s->out[1] = (struct tex_hit){.t = INFINITY, .leaf = NULL};
}

/* The gradient of x^2 + z^2 - (r0 + k y)^2, outwards on both nappes */
static tex_v3 inf_cone_normal(const struct tex_object *ob, tex_v3 p)
{
    double k = ob->r1 - ob->r0, ry = ob->r0 + k * p.y;
    tex_v3 n = tex_v3_make(p.x, -k * ry, p.z);
    return tex_v3_len(n) > 0 ? n : tex_v3_make(0, 1, 0);
}

/* inf_cone_map: u around the axis as cylinder_map's, v down the axis repeating every
 * base-to-top length; one face */
static int inf_cone_uv(const struct tex_object *ob, tex_v3 p, double *u, double *v)
{
    (void)ob;
    *u = tex_turns(-p.z, p.x);
    *v = -p.y - floor(-p.y);
    return 1;
}

/* Unbounded, like the plane: no box */
static int inf_cone_bounds(const struct tex_object *ob, struct tex_bounds *b)
{
    (void)ob, (void)b;
    return 0;
}

/* ---- plane ------------------------------------------------------------------ */

static void plane_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s)
{
    s->n = 0;
    if (d.y == 0) {
        if (o.y <= 0)
            span1(s, ob, -INFINITY, INFINITY);
        return;
    }
    double t = -o.y / d.y;
    if (d.y > 0)
        span1(s, ob, -INFINITY, t);
    else
        span1(s, ob, t, INFINITY);
}

static tex_v3 plane_normal(const struct tex_object *ob, tex_v3 p)
{
    (void)ob;
    (void)p;
    return tex_v3_make(0, 1, 0);
}

/* Planar: one texture-space unit per object-space unit, wrapping. */
static int plane_uv(const struct tex_object *ob, tex_v3 p, double *u, double *v)
{
    (void)ob;
    *u = p.x - floor(p.x);
    *v = p.z - floor(p.z);
    return 1;
}

static int plane_bounds(const struct tex_object *ob, struct tex_bounds *b)
{
    (void)ob;
    (void)b;
    return 0;
}

/* ---- torus -------------------------------------------------------------------- */

/* Polynomials c[0] + c[1] s + ... + c[n] s^n, solved on a bracket [a, b] by
 * the critical points (Yuksel, "High-performance polynomial root finding for
 * graphics", 2022): between consecutive roots of the derivative the
 * polynomial is monotonic, so each sign change there holds exactly one root,
 * found by Newton steps kept inside a shrinking bracket.  Unlike a closed
 * form (Ferrari) nothing cancels catastrophically, and a double root of a
 * grazing ray is a root of the derivative, found as well as any other. */
static double poly_eval(const double *c, int n, double s, double *ds)
{
    double f = c[n], d = 0;
    for (int i = n - 1; i >= 0; i--) {
        d = d * s + f;
        f = f * s + c[i];
    }
    *ds = d;
    return f;
}

static double poly_bracketed(const double *c, int n, double lo, double hi, double flo)
{
    double x = 0.5 * (lo + hi);
    for (int it = 0; it < 200; it++) {
        double d, f = poly_eval(c, n, x, &d);
        if (f == 0)
            return x;
        if ((f < 0) == (flo < 0))
            lo = x;
        else
            hi = x;
        double nx = d != 0 ? x - f / d : lo - 1;
        if (!(nx > lo && nx < hi))
            nx = 0.5 * (lo + hi);
        if (fabs(nx - x) <= 1e-15 * (1 + fabs(x)) || hi - lo <= 1e-15 * (1 + fabs(x)))
            return nx;
        x = nx;
    }
    return x;
}

/* Roots of c (degree n >= 2) in (a, b) where it changes sign, ascending, given the roots x
 * of its derivative there (nx of them, ascending, as poly_sign_roots makes them): between
 * them c is monotonic; returns their number (at most n). */
static int poly_roots_between(const double *c, int n, double a, double b, const double *x,
                              int nx, double *r)
{
    int k = 0;
    double d, lo = a, fa = poly_eval(c, n, a, &d);
    for (int i = 0; i <= nx; i++) {
        double hi = i < nx ? x[i] : b, fb = poly_eval(c, n, hi, &d);
        if (fa == 0 && i > 0)
            r[k++] = lo;
        else if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0))
            r[k++] = poly_bracketed(c, n, lo, hi, fa);
        lo = hi, fa = fb;
    }
    return k;
}

/* Roots of c (degree n >= 1) in (a, b) where it changes sign, ascending;
 * returns their number (at most n). */
static int poly_sign_roots(const double *c, int n, double a, double b, double *r)
{
    if (n == 1) {
        double x = -c[0] / c[1];
        if (c[1] != 0 && x > a && x < b) {
            r[0] = x;
            return 1;
        }
        return 0;
    }
    double dc[4], x[4];
    for (int i = 1; i <= n; i++)
        dc[i - 1] = i * c[i];
    return poly_roots_between(c, n, a, b, x, poly_sign_roots(dc, n - 1, a, b, x), r);
}

static int torus_inside(double R, double r, tex_v3 p)
{
    double q = sqrt(p.x * p.x + p.z * p.z) - R;
    return q * q + p.y * p.y < r * r;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The n (at most 10) cuts ascending: by insertion, where qsort's call per comparison cost
 * more than the few moves; qsort where one is NaN, which orders nothing */
static void sort_cuts(double *cut, int n)
{
    for (int i = 0; i < n; i++)
        if (isnan(cut[i])) {
            qsort(cut, n, sizeof *cut, cmp_double);
            return;
        }
    for (int i = 1; i < n; i++) {
        double v = cut[i];
        int j = i;
        for (; j > 0 && cut[j - 1] > v; j--)
            cut[j] = cut[j - 1];
        cut[j] = v;
    }
}

/* The quartic (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + z^2) = 0 along the ray,
 * solved with d made unit and the origin moved to the point nearest the
 * centre (well scaled whatever the distance).  Its roots and critical
 * points cut the chord through the bounding sphere into pieces, each inside
 * or outside (tested at its middle), so grazing rays (double roots) and
 * spindle tori (r > R: the quartic's extra inner sheet) still give the
 * solid's true intervals: up to two, four crossings. */
static void torus_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s)
{
    double R = ob->r0, r = ob->r1, len = tex_v3_len(d);
    s->n = 0;
    if (!(len > 0))
        return;
    d = tex_v3_scale(d, 1 / len);
    double tc = -tex_v3_dot(o, d);
    o = tex_v3_madd(o, d, tc);
    double big = R + r, h2 = big * big - tex_v3_dot(o, o);
    if (!(h2 > 0))
        return;
    double h = sqrt(h2) * 1.0001 + 1e-9 * big;
    double G = tex_v3_dot(o, o) + R * R - r * r, k = tex_v3_dot(o, d); /* k ~ 0 */
    double dxz = d.x * d.x + d.z * d.z, oxz = o.x * d.x + o.z * d.z;
    double c[5] = {G * G - 4 * R * R * (o.x * o.x + o.z * o.z), 4 * k * G - 8 * R * R * oxz,
                   4 * k * k + 2 * G - 4 * R * R * dxz, 4 * k, 1};
    double cut[10], dc[4] = {c[1], 2 * c[2], 3 * c[3], 4 * c[4]};
    int n = 0;
    cut[n++] = -h;
    double x[3]; /* the critical points: the quartic's own roots found between them */
    int nx = poly_sign_roots(dc, 3, -h, h, x);
    n += poly_roots_between(c, 4, -h, h, x, nx, cut + n);
    for (int i = 0; i < nx; i++)
        cut[n++] = x[i];
    cut[n++] = h;
    sort_cuts(cut, n);
    int in = 0;
    for (int i = 0; i + 1 < n; i++) {
        if (!(cut[i + 1] > cut[i]))
            continue;
        int now = torus_inside(R, r, tex_v3_madd(o, d, 0.5 * (cut[i] + cut[i + 1])));
        if (now == in)
            continue;
        in = now;
        double t = (tc + cut[i]) / len;
        if (now) {
            s->in[s->n].t = t;
            s->in[s->n].leaf = ob;
            s->in[s->n].flip = 0;
        } else {
            s->out[s->n].t = t;
            s->out[s->n].leaf = ob;
            s->out[s->n].flip = 0;
            s->n++;
        }
    }
}

/* q^2 + y^2 at o + t d over r^2: below 1 inside the solid, above 1 outside */
static double torus_depth(double R, double r, tex_v3 o, tex_v3 d, double t)
{
    tex_v3 p = tex_v3_madd(o, d, t);
    double q = sqrt(p.x * p.x + p.z * p.z) - R;
    return (q * q + p.y * p.y) / (r * r);
}

/* x^2 + z^2 at o + t d */
static double torus_rho2(tex_v3 o, tex_v3 d, double t)
{
    double x = o.x + t * d.x, z = o.z + t * d.z;
    return x * x + z * z;
}

/* Does o + t d, t in (tmin, tmax), cross the torus's surface?  -1 where it surely does not:
 * it stays beyond the tube's slab, or within it in the hole or beyond the rim.  1 where it
 * surely does: a point of it lies deep inside and an end clearly outside (the points tried:
 * where it crosses the tube's plane and the core circle's cylinder, where shadow rays
 * through a torus are inside).  0: only torus_spans can tell.  The margins (1e-6 of r) are
 * far beyond the rounding of either test, so a sure answer is torus_spans' own (its pieces
 * keep one side each). */
static int torus_segment(const struct tex_object *ob, tex_v3 o, tex_v3 d, double tmin,
                         double tmax)
{
    double R = ob->r0, r = ob->r1, m = r * 1e-6, u = tmin, v = tmax;
    if (d.y != 0) { /* the slab |y| <= r + m, beyond which the depth is > 1 + 2e-6 */
        double ta = (-(r + m) - o.y) / d.y, tb = (r + m - o.y) / d.y;
        u = tex_maxd(u, tex_mind(ta, tb)), v = tex_mind(v, tex_maxd(ta, tb));
    } else if (!(fabs(o.y) <= r + m)) {
        return -1;
    }
    if (u > v)
        return -1;
    double a = d.x * d.x + d.z * d.z, b = o.x * d.x + o.z * d.z;
    double hole = R - r - m, rim = R + r + m, tv = a > 0 ? tex_mind(v, tex_maxd(u, -b / a)) : u;
    if ((hole > 0 && torus_rho2(o, d, u) < hole * hole && torus_rho2(o, d, v) < hole * hole) ||
        torus_rho2(o, d, tv) > rim * rim)
        return -1;
    double rmin2 = torus_rho2(o, d, tv), len = v - u;
    if (rmin2 > 0 && isfinite(len)) {
        /* D^2 = q^2 + y^2 (q = rho - R) from u on: its value and slope there, and its second
         * derivative 2 (q'^2 + q rho'' + y'^2) bounded below by K (rho'' in [0, a / rho]) */
        tex_v3 p = tex_v3_madd(o, d, u);
        double rho = sqrt(p.x * p.x + p.z * p.z), q = rho - R, rmin = sqrt(rmin2);
        double D2 = q * q + p.y * p.y, slope = 2 * (q * (p.x * d.x + p.z * d.z) / rho + p.y * d.y);
        double K = 2 * (d.y * d.y + tex_mind(0, rmin - R) * a / rmin);
        double low = tex_mind(0, len * (slope + 0.5 * K * len)), tk = K > 0 ? -slope / K : -1;
        if (tk > 0 && tk < len)
            low = tex_mind(low, -0.5 * slope * slope / K);
        if (D2 + low > r * r * (1 + 4e-6))
            return -1; /* D stays above r on the whole piece */
    }
    double lo = 1 - 1e-6, hi = 1 + 1e-6;
    if (!(torus_depth(R, r, o, d, tmin) > hi) && !(torus_depth(R, r, o, d, tmax) > hi))
        return 0;
    double t[3];
    int n = 0;
    if (d.y != 0)
        t[n++] = -o.y / d.y;
    double disc = b * b - a * (o.x * o.x + o.z * o.z - R * R);
    if (a > 0 && disc > 0) {
        double q = sqrt(disc);
        t[n++] = (-b - q) / a, t[n++] = (-b + q) / a;
    }
    for (int k = 0; k < n; k++)
        if (t[k] > tmin && t[k] < tmax && torus_depth(R, r, o, d, t[k]) < lo)
            return 1;
    return 0;
}

/* The gradient of (rho - R)^2 + y^2: away from the tube's centre circle. */
static tex_v3 torus_normal(const struct tex_object *ob, tex_v3 p)
{
    double rho = sqrt(p.x * p.x + p.z * p.z);
    if (!(rho > 0))
        return tex_v3_make(0, p.y < 0 ? -1 : 1, 0);
    double k = 1 - ob->r0 / rho;
    return tex_v3_make(p.x * k, p.y, p.z * k);
}

/* torus_map: u around the major circle (as sphere_map's longitude), v around
 * the tube from the top (v = 0) down the outside (0.25 at the outer
 * equator), under (0.5) and up the inside (0.75). */
static int torus_uv(const struct tex_object *ob, tex_v3 p, double *u, double *v)
{
    *u = tex_turns(-p.z, p.x);
    *v = tex_turns(sqrt(p.x * p.x + p.z * p.z) - ob->r0, p.y);
    return 1;
}

static int torus_bounds(const struct tex_object *ob, struct tex_bounds *b)
{
    double e = ob->r0 + ob->r1;
    b->lo = tex_v3_make(-e, -ob->r1, -e);
    b->hi = tex_v3_make(e, ob->r1, e);
    return 1;
}

const struct tex_shape_methods tex_shape_methods[TEX_SHAPE_NKINDS] = {
    [TEX_SHAPE_SPHERE] = {"sphere", sphere_spans, sphere_normal, sphere_uv, unit_bounds},
    [TEX_SHAPE_BOX] = {"box", box_spans, box_normal, box_uv, unit_bounds},
    [TEX_SHAPE_CYLINDER] = {"cylinder", cone_spans, cone_normal, cone_uv, cone_bounds},
    [TEX_SHAPE_CONE] = {"cone", cone_spans, cone_normal, cone_uv, cone_bounds},
    [TEX_SHAPE_PLANE] = {"plane", plane_spans, plane_normal, plane_uv, plane_bounds},
    [TEX_SHAPE_TORUS] = {"torus", torus_spans, torus_normal, torus_uv, torus_bounds},
    [TEX_SHAPE_INF_CONE] = {"inf_cone", inf_cone_spans, inf_cone_normal, inf_cone_uv,
                            inf_cone_bounds},
};

/* ---- objects ------------------------------------------------------------------ */

/* Does the line o + t d meet box b?  inv is 1/d with zero components nudged
 * to +-1e300 (as the BVH does), so the slab test needs no division. */
static int ray_box(const struct tex_bounds *b, tex_v3 o, tex_v3 inv)
{
    double a = (b->lo.x - o.x) * inv.x, c = (b->hi.x - o.x) * inv.x;
    double t0 = a < c ? a : c, t1 = a < c ? c : a;
    a = (b->lo.y - o.y) * inv.y, c = (b->hi.y - o.y) * inv.y;
    t0 = t0 > (a < c ? a : c) ? t0 : (a < c ? a : c);
    t1 = t1 < (a < c ? c : a) ? t1 : (a < c ? c : a);
    a = (b->lo.z - o.z) * inv.z, c = (b->hi.z - o.z) * inv.z;
    t0 = t0 > (a < c ? a : c) ? t0 : (a < c ? a : c);
    t1 = t1 < (a < c ? c : a) ? t1 : (a < c ? c : a);
    return t0 <= t1;
}

/* A world ray in the leaf's object space */
static inline __attribute__((always_inline)) void
leaf_ray(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d, tex_v3 *lo, tex_v3 *ld)
{
    if (ob->scaled) { /* the full products' zero terms change no more than a zero's sign */
        const double(*m)[4] = ob->to_obj.m;
        *lo = tex_v3_make(m[0][0] * o->x + m[0][3], m[1][1] * o->y + m[1][3],
                          m[2][2] * o->z + m[2][3]);
        *ld = tex_v3_make(m[0][0] * d->x, m[1][1] * d->y, m[2][2] * d->z);
    } else {
        *lo = tex_xform_point(&ob->to_obj, *o), *ld = tex_xform_dir(&ob->to_obj, *d);
    }
}

/* A leaf's spans along a world ray: a switch, not the method table, so the
 * common shapes (always_inline) are inlined and the object-space ray stays in registers
 * (a tex_v3 passed by value goes through the stack, and the load after the
 * store stalls). */
void tex_leaf_spans(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                    struct tex_spans *s)
{
    tex_v3 lo, ld;
    leaf_ray(ob, o, d, &lo, &ld);
    switch (ob->kind) {
    case TEX_SHAPE_SPHERE: sphere_spans(ob, lo, ld, s); break;
    case TEX_SHAPE_BOX: box_spans(ob, lo, ld, s); break;
    case TEX_SHAPE_CYLINDER:
    case TEX_SHAPE_CONE: cone_spans(ob, lo, ld, s); break;
    default: tex_shape_methods[ob->kind].spans(ob, lo, ld, s); break;
    }
}

int tex_leaf_segment(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                     double tmin, double tmax)
{
    if (ob->kind != TEX_SHAPE_TORUS)
        return 0;
    tex_v3 lo, ld;
    leaf_ray(ob, o, d, &lo, &ld);
    return torus_segment(ob, lo, ld, tmin, tmax);
}

static void object_spans(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                         const tex_v3 *inv, struct tex_spans *s);

/* A CSG node's spans from its children's (its own box already passed). */
static void node_spans(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                       const tex_v3 *inv, struct tex_spans *s)
{
    struct tex_spans a, b;
    object_spans(ob->a, o, d, inv, &a);
    if (a.n == 0 && ob->op != TEX_CSG_UNION) {
        s->n = 0;
        return;
    }
    object_spans(ob->b, o, d, inv, &b);
    tex_csg_combine(ob->op, &a, &b, s);
}

static void object_spans(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                         const tex_v3 *inv, struct tex_spans *s)
{
    if (ob->op == TEX_CSG_LEAF) {
        tex_leaf_spans(ob, o, d, s);
        return;
    }
    if (ob->bounded && !ray_box(&ob->wb, *o, *inv)) {
        s->n = 0;
        return;
    }
    node_spans(ob, o, d, inv, s);
}

void tex_object_spans(const struct tex_object *ob, tex_v3 o, tex_v3 d, struct tex_spans *s)
{
    tex_v3 inv = tex_v3_slab_inv(d);
    object_spans(ob, &o, &d, &inv, s);
}

void tex_csg_spans(const struct tex_object *ob, const tex_v3 *o, const tex_v3 *d,
                   const tex_v3 *inv, struct tex_spans *s)
{
    if (ob->op == TEX_CSG_LEAF)
        tex_leaf_spans(ob, o, d, s);
    else
        node_spans(ob, o, d, inv, s);
}

/* holds: every node above ob keeps only what lies inside ob */
static void mark_hulls(struct tex_object *ob, int holds)
{
    if (ob->op == TEX_CSG_LEAF) { /* cones have radii >= 0 (the parser's): no double cone */
        ob->hull = holds && ob->kind != TEX_SHAPE_TORUS && ob->kind != TEX_SHAPE_INF_CONE;
        return;
    }
    mark_hulls(ob->a, holds && ob->op != TEX_CSG_UNION);
    mark_hulls(ob->b, holds && ob->op == TEX_CSG_INTERSECTION);
}

void tex_object_hulls(struct tex_object *ob)
{
    mark_hulls(ob, 1);
}

/* The leaf's normal fast path (struct tex_object's fast). */
static void leaf_fast(struct tex_object *ob)
{
    const double(*m)[4] = ob->to_world.m, (*q)[4] = ob->to_obj.m;
    ob->fast = 0;
    ob->scaled = q[0][1] == 0 && q[0][2] == 0 && q[1][0] == 0 && q[1][2] == 0 && q[2][0] == 0 &&
                 q[2][1] == 0;
    if (ob->kind == TEX_SHAPE_PLANE) { /* the normal: the y row of the inverse */
        tex_v3 n = tex_v3_make(q[1][0], q[1][1], q[1][2]);
        if (tex_v3_len(n) > 0) {
            ob->fast = 1;
            ob->fn = tex_v3_norm(n);
        }
    } else if (ob->kind == TEX_SHAPE_SPHERE) {
        /* orthogonal columns of equal length: the sphere stays round */
        tex_v3 c0 = tex_v3_make(m[0][0], m[1][0], m[2][0]);
        tex_v3 c1 = tex_v3_make(m[0][1], m[1][1], m[2][1]);
        tex_v3 c2 = tex_v3_make(m[0][2], m[1][2], m[2][2]);
        double s2 = tex_v3_dot(c0, c0), tol = 1e-12 * s2;
        if (s2 > 0 && fabs(tex_v3_dot(c1, c1) - s2) <= tol &&
            fabs(tex_v3_dot(c2, c2) - s2) <= tol && fabs(tex_v3_dot(c0, c1)) <= tol &&
            fabs(tex_v3_dot(c1, c2)) <= tol && fabs(tex_v3_dot(c0, c2)) <= tol) {
            ob->fast = 2;
            ob->fn = tex_v3_make(m[0][3], m[1][3], m[2][3]);
            ob->fr = 1 / sqrt(s2);
        }
    }
}

int tex_object_bounds(struct tex_object *ob)
{
    if (ob->op == TEX_CSG_LEAF) {
        leaf_fast(ob);
        struct tex_bounds lb;
        ob->bounded = tex_shape_methods[ob->kind].bounds(ob, &lb);
        if (!ob->bounded)
            return 0;
        ob->bc = tex_v3_scale(tex_v3_add(lb.lo, lb.hi), 0.5);
        ob->be = tex_v3_scale(tex_v3_sub(lb.hi, lb.lo), 0.5);
        ob->wb.lo = tex_v3_make(INFINITY, INFINITY, INFINITY);
        ob->wb.hi = tex_v3_make(-INFINITY, -INFINITY, -INFINITY);
        for (int c = 0; c < 8; c++) {
            tex_v3 p = tex_v3_make(c & 1 ? lb.hi.x : lb.lo.x, c & 2 ? lb.hi.y : lb.lo.y,
                                   c & 4 ? lb.hi.z : lb.lo.z);
            p = tex_xform_point(&ob->to_world, p);
            ob->wb = tex_bounds_union(ob->wb, (struct tex_bounds){p, p});
        }
        return 1;
    }
    int ba = tex_object_bounds(ob->a), bb = tex_object_bounds(ob->b);
    switch (ob->op) {
    case TEX_CSG_UNION:
        ob->bounded = ba && bb;
        if (ob->bounded) {
            ob->wb = tex_bounds_union(ob->a->wb, ob->b->wb);
        }
        break;
    case TEX_CSG_INTERSECTION:
        ob->bounded = ba || bb;
        if (ba && bb) {
            ob->wb = tex_bounds_meet(ob->a->wb, ob->b->wb);
        } else if (ob->bounded) {
            ob->wb = ba ? ob->a->wb : ob->b->wb;
        }
        break;
    default: /* difference: inside a */
        ob->bounded = ba;
        ob->wb = ob->a->wb;
        break;
    }
    return ob->bounded;
}

/* ---- CSG on intervals ------------------------------------------------------------ */

static int csg_inside(enum tex_csg_op op, int a, int b)
{
    switch (op) {
    case TEX_CSG_UNION: return a || b;
    case TEX_CSG_INTERSECTION: return a && b;
    default: return a && !b;
    }
}

/* Sweep the boundaries of a and b in order; a boundary of the result is
 * wherever the combined inside/outside state changes.  Surfaces of the
 * subtracted solid face the other way. */
/* a and b of one interval each (convex leaves), all ends distinct: the
 * sweep's answer directly.  0 where the general sweep must decide. */
static int combine11(enum tex_csg_op op, const struct tex_spans *a, const struct tex_spans *b,
                     struct tex_spans *r)
{
    double a0 = a->in[0].t, a1 = a->out[0].t, b0 = b->in[0].t, b1 = b->out[0].t;
    if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1)
        return 0;
    if (op == TEX_CSG_INTERSECTION) {
        r->n = 0;
        if (a0 > b1 || b0 > a1)
            return 1;
        r->n = 1;
        r->in[0] = a0 > b0 ? a->in[0] : b->in[0];
        r->out[0] = a1 < b1 ? a->out[0] : b->out[0];
        return 1;
    }
    if (op != TEX_CSG_DIFFERENCE)
        return 0;
    struct tex_hit fb0 = b->in[0], fb1 = b->out[0]; /* the subtracted surfaces face the other way */
    fb0.flip = !fb0.flip;
    fb1.flip = !fb1.flip;
    r->n = 0;
    if (b1 < a0 || b0 > a1) { /* apart */
        r->in[0] = a->in[0];
        r->out[0] = a->out[0];
        r->n = 1;
        return 1;
    }
    if (b0 < a0 && b1 > a1) /* b covers a */
        return 1;
    if (b0 > a0) { /* a starts outside b */
        r->in[0] = a->in[0];
        r->out[0] = fb0;
        r->n = 1;
    }
    if (b1 < a1) { /* a goes on after b */
        r->in[r->n] = fb1;
        r->out[r->n] = a->out[0];
        r->n++;
    }
    return 1;
}

void tex_csg_combine(enum tex_csg_op op, const struct tex_spans *a, const struct tex_spans *b,
                     struct tex_spans *r)
{
    if (a->n == 1 && b->n == 1 && combine11(op, a, b, r))
        return;
    int ia = 0, ib = 0, na = 2 * a->n, nb = 2 * b->n;
    int ina = 0, inb = 0, inr = 0;
    r->n = 0;
    while (ia < na || ib < nb) {
        const struct tex_hit *ha = ia < na ? (ia & 1 ? &a->out[ia / 2] : &a->in[ia / 2]) : NULL;
        const struct tex_hit *hb = ib < nb ? (ib & 1 ? &b->out[ib / 2] : &b->in[ib / 2]) : NULL;
        struct tex_hit h;
        int fromb = !ha || (hb && hb->t < ha->t);
        if (fromb) {
            h = *hb;
            ib++;
            inb = !inb;
            if (op == TEX_CSG_DIFFERENCE)
                h.flip = !h.flip;
        } else {
            h = *ha;
            ia++;
            ina = !ina;
        }
        int now = csg_inside(op, ina, inb);
        if (now == inr)
            continue;
        inr = now;
        if (now) {
            if (r->n == TEX_SPANS_MAX)
                return; /* keep the nearest intervals */
            r->in[r->n] = h;
        } else {
            r->out[r->n++] = h;
        }
    }
}
