/* render_texture.c - textures, mappings and application functions
 *
 * A texture is a map (with a mip-map pyramid for filtered lookups) or a
 * primitive evaluated at hit points.  A surface applies textures in order;
 * each one maps the hit point to texture space (its mapping), keeps the
 * point only inside its window (u1,v1)-(u2,v2), repeats the map nu x nv
 * times there (1 x 1 stretches it), looks up the value f and changes the
 * shading parameters through its application functions g[region][param].
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "render.h"

/* ---- mip-mapped maps ------------------------------------------------------------ */

int tex_texture_build_mip(struct tex_texture *t)
{
    tex_map *m = t->mip[0];
    int n = 1;
    for (int w = m->w, h = m->h; w > 1 || h > 1; w = (w + 1) / 2, h = (h + 1) / 2)
        n++;
    tex_map **mip = realloc(t->mip, n * sizeof *mip);
    if (!mip)
        return tex_error("out of memory");
    t->mip = mip;
    t->nlevels = 1;
    if (t->subregions)
        return 0; /* region ids are never averaged */
    for (int l = 1; l < n; l++) {
        const tex_map *s = mip[l - 1];
        tex_map *d = tex_map_new(s->w > 1 ? s->w / 2 : 1, s->h > 1 ? s->h / 2 : 1, s->nc);
        if (!d)
            return -1;
        int fx = s->w / d->w, fy = s->h / d->h;
        for (int y = 0; y < d->h; y++) {
            for (int x = 0; x < d->w; x++) {
                float *o = tex_map_px(d, x, y);
                for (int j = 0; j < fy; j++)
                    for (int i = 0; i < fx; i++) {
                        const float *p = tex_map_px(s, x * fx + i, y * fy + j);
                        for (int c = 0; c < s->nc; c++)
                            o[c] += p[c];
                    }
                for (int c = 0; c < s->nc; c++)
                    o[c] /= fx * fy;
            }
        }
        mip[l] = d;
        t->nlevels = l + 1;
        if (d->w == 1 && d->h == 1)
            break;
    }
    return 0;
}

static void to_rgb(const float *p, int nc, float out[3])
{
    if (nc >= 3) {
        out[0] = p[0], out[1] = p[1], out[2] = p[2];
    } else {
        out[0] = out[1] = out[2] = p[0];
    }
}

static inline int wrapi(int i, int n)
{
    i %= n;
    return i < 0 ? i + n : i;
}

/* floor() in a few instructions (libm's takes tens at -O2 without SSE4.1);
 * exact, since doubles beyond 2^52 are integers (and NaN, inf pass through). */
static inline double floord(double x)
{
    if (!(fabs(x) < 4503599627370496.0))
        return x;
    double t = (double)(long long)x;
    return t > x ? t - 1 : t;
}

/* i in [-1, n] (u, v in [0, 1]) wraps without a division */
static inline int wrap1(int i, int n)
{
    return i < 0 ? (i + n < 0 ? wrapi(i, n) : i + n) : i >= n ? wrapi(i, n) : i;
}

/* One channel of a grey map (nc 1 or 2), bilinear: the same arithmetic as bilinear(). */
static inline float bilinear_grey(const tex_map *m, double u, double v)
{
    double x = u * m->w - 0.5, y = v * m->h - 0.5;
    double fx = floord(x), fy = floord(y);
    double ax = x - fx, ay = y - fy;
    int w = m->w, h = m->h, nc = m->nc;
    int x0 = wrap1((int)fx, w), y0 = wrap1((int)fy, h);
    int x1 = x0 + 1 == w ? 0 : x0 + 1, y1 = y0 + 1 == h ? 0 : y0 + 1;
    const float *r0 = m->px + (size_t)y0 * w * nc, *r1 = m->px + (size_t)y1 * w * nc;
    double a = r0[x0 * nc], b = r0[x1 * nc], c = r1[x0 * nc], d = r1[x1 * nc];
    return (float)((a * (1 - ax) + b * ax) * (1 - ay) + (c * (1 - ax) + d * ax) * ay);
}

static void bilinear(const tex_map *m, double u, double v, float out[3])
{
    double x = u * m->w - 0.5, y = v * m->h - 0.5;
    double fx = floord(x), fy = floord(y);
    double ax = x - fx, ay = y - fy;
    int x0 = wrap1((int)fx, m->w), y0 = wrap1((int)fy, m->h);
    int x1 = x0 + 1 == m->w ? 0 : x0 + 1, y1 = y0 + 1 == m->h ? 0 : y0 + 1;
    if (m->nc < 3) { /* grey: one channel to interpolate */
        double a = tex_map_px(m, x0, y0)[0], b = tex_map_px(m, x1, y0)[0];
        double c = tex_map_px(m, x0, y1)[0], d = tex_map_px(m, x1, y1)[0];
        out[0] = out[1] = out[2] =
            (float)((a * (1 - ax) + b * ax) * (1 - ay) + (c * (1 - ax) + d * ax) * ay);
        return;
    }
    float a[3], b[3], c[3], d[3];
    to_rgb(tex_map_px(m, x0, y0), m->nc, a);
    to_rgb(tex_map_px(m, x1, y0), m->nc, b);
    to_rgb(tex_map_px(m, x0, y1), m->nc, c);
    to_rgb(tex_map_px(m, x1, y1), m->nc, d);
    for (int k = 0; k < 3; k++)
        out[k] = (float)((a[k] * (1 - ax) + b[k] * ax) * (1 - ay) + (c[k] * (1 - ax) + d[k] * ax) * ay);
}

int tex_texture_eval(const struct tex_texture *t, double u, double v, double w, double fw,
                     float out[3])
{
    if (t->mip) {
        const tex_map *m = t->mip[0];
        u -= floord(u);
        v -= floord(v);
        if (t->subregions) {
            int x = wrapi((int)(u * m->w), m->w), y = wrapi((int)(v * m->h), m->h);
            float id = tex_map_px(m, x, y)[0];
            out[0] = out[1] = out[2] = id;
            return (int)lrintf(id);
        }
        int side = m->w > m->h ? m->w : m->h;
        double lod = fw > 0 ? log2(fw * side) : 0;
        if (m->nc < 3) { /* grey: one channel through the levels */
            float g;
            if (!(lod > 0) || t->nlevels == 1) {
                g = bilinear_grey(m, u, v);
            } else if (lod >= t->nlevels - 1) {
                g = bilinear_grey(t->mip[t->nlevels - 1], u, v);
            } else {
                int l = (int)lod;
                double a = lod - l;
                float g0 = bilinear_grey(t->mip[l], u, v), g1 = bilinear_grey(t->mip[l + 1], u, v);
                g = (float)(g0 * (1 - a) + g1 * a);
            }
            out[0] = out[1] = out[2] = g;
            return 0;
        }
        if (!(lod > 0) || t->nlevels == 1) {
            bilinear(m, u, v, out);
            return 0;
        }
        if (lod >= t->nlevels - 1) {
            bilinear(t->mip[t->nlevels - 1], u, v, out);
            return 0;
        }
        int l = (int)lod;
        double a = lod - l;
        float o0[3], o1[3];
        bilinear(t->mip[l], u, v, o0);
        bilinear(t->mip[l + 1], u, v, o1);
        for (int k = 0; k < 3; k++)
            out[k] = (float)(o0[k] * (1 - a) + o1[k] * a);
        return 0;
    }
    float val[TEX_MAP_MAX_CHANNELS] = {0};
    const struct tex_field *f = t->field;
    if (t->solid)
        f->prim->eval3(f, 1, &u, &v, &w, val);
    else
        f->prim->eval2(f, 1, &u, &v, val);
    to_rgb(val, f->nc, out);
    if ((f->prim->flags & TEX_PRIM_REGIONS) && f->ids)
        return (int)lrintf(val[0]);
    return 0;
}

/* ---- mappings -------------------------------------------------------------------- */

static double fract(double x)
{
    return x - floord(x);
}

static void local_box(const struct tex_object *leaf, struct tex_bounds *b, int *bounded)
{
    *bounded = tex_shape_methods[leaf->kind].bounds(leaf, b);
}

/* Texture-space coordinates of world point P on leaf; returns the face id. */
static int map_point_at(const struct tex_apply *ap, const struct tex_object *leaf, tex_v3 P,
                        tex_v3 pl, double uvw[3])
{
    struct tex_bounds b;
    int bounded, face = 1;
    enum tex_mapping mp = ap->mapping;
    uvw[2] = 0;
    if (mp == TEX_MAP_NATURAL && leaf->kind == TEX_SHAPE_PLANE)
        mp = TEX_MAP_PLANAR;
    if (mp == TEX_MAP_NATURAL)
        return tex_shape_methods[leaf->kind].uv(leaf, pl, &uvw[0], &uvw[1]);
    if (mp == TEX_MAP_WORLD || (mp == TEX_MAP_SOLID && !(leaf->root && leaf->root->bounded))) {
        uvw[0] = fract(P.x * ap->scale);
        uvw[1] = fract(-P.y * ap->scale);
        uvw[2] = fract(P.z * ap->scale);
        if (mp == TEX_MAP_WORLD) {
            double t = uvw[1];
            uvw[1] = uvw[2], uvw[2] = t; /* 2D maps lie in the ground plane x,z */
        }
        return 1;
    }
    if (mp == TEX_MAP_SOLID) {
        const struct tex_bounds *rb = &leaf->root->wb;
        tex_v3 e = tex_v3_sub(rb->hi, rb->lo);
        uvw[0] = e.x > 0 ? (P.x - rb->lo.x) / e.x : 0;
        uvw[1] = e.y > 0 ? (rb->hi.y - P.y) / e.y : 0; /* v downwards: top of the box is 0 */
        uvw[2] = e.z > 0 ? (P.z - rb->lo.z) / e.z : 0;
        return 1;
    }
    if (mp == TEX_MAP_PLANAR && leaf->kind == TEX_SHAPE_PLANE) { /* unbounded: no box */
        uvw[0] = fract(pl.x * ap->scale);
        uvw[1] = fract(pl.z * ap->scale);
        return face;
    }
    local_box(leaf, &b, &bounded);
    tex_v3 c = bounded ? tex_v3_scale(tex_v3_add(b.lo, b.hi), 0.5) : tex_v3_make(0, 0, 0);
    tex_v3 e = bounded ? tex_v3_scale(tex_v3_sub(b.hi, b.lo), 0.5) : tex_v3_make(1, 1, 1);
    tex_v3 q = tex_v3_make((pl.x - c.x) / e.x, (pl.y - c.y) / e.y, (pl.z - c.z) / e.z);
    switch (mp) {
    case TEX_MAP_SPHERE:
        return tex_shape_methods[TEX_SHAPE_SPHERE].uv(leaf, q, &uvw[0], &uvw[1]);
    case TEX_MAP_BOX:
        return tex_shape_methods[TEX_SHAPE_BOX].uv(leaf, q, &uvw[0], &uvw[1]);
    case TEX_MAP_CYLINDER:
    case TEX_MAP_CONE: {
        double a = atan2(-q.z, q.x) / (2 * M_PI);
        uvw[0] = a < 0 ? a + 1 : a;
        uvw[1] = bounded ? fmin(1, fmax(0, (1 - q.y) / 2)) : fract(-pl.y * ap->scale);
        return face;
    }
    default: /* planar: x and z across the box */
        if (!bounded) {
            uvw[0] = fract(pl.x * ap->scale);
            uvw[1] = fract(pl.z * ap->scale);
        } else {
            uvw[0] = fmin(1, fmax(0, (q.x + 1) / 2));
            uvw[1] = fmin(1, fmax(0, (q.z + 1) / 2));
        }
        return face;
    }
}

/* Where the mapping is affine in P (modulo wrapping), its world-space
 * gradients of u and v: 1, else 0 (the footprint then takes finite differences). */
static int map_gradient(const struct tex_apply *ap, const struct tex_object *leaf, tex_v3 *du,
                        tex_v3 *dv)
{
    enum tex_mapping mp = ap->mapping;
    double s = ap->scale;
    if ((mp == TEX_MAP_NATURAL || mp == TEX_MAP_PLANAR) && leaf->kind == TEX_SHAPE_PLANE) {
        /* planar on an unbounded shape: u = x, v = z of the object space, scaled */
        const double(*m)[4] = leaf->to_obj.m;
        *du = tex_v3_make(m[0][0] * s, m[0][1] * s, m[0][2] * s);
        *dv = tex_v3_make(m[2][0] * s, m[2][1] * s, m[2][2] * s);
        return 1;
    }
    if (mp == TEX_MAP_WORLD) {
        *du = tex_v3_make(s, 0, 0);
        *dv = tex_v3_make(0, 0, s);
        return 1;
    }
    return 0;
}

/* The natural mappings' (sphere_map, box faces, cylinder_map / cone_map)
 * gradients of u and v in object space at p on face (map_point's answer);
 * 0 where there are none (other mappings, the poles, the axis). */
static int natural_gradient(const struct tex_apply *ap, const struct tex_object *leaf, tex_v3 p,
                            int face, tex_v3 *du, tex_v3 *dv)
{
    if (ap->mapping != TEX_MAP_NATURAL)
        return 0;
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
        /* box_uv: u = (a + 1) / 2, v = (b + 1) / 2 with a, b signed coordinates */
        static const signed char ab[6][2] = {{-3, -2}, {3, -2}, {1, 3}, {1, -3}, {1, -2}, {-1, -2}};
        if (face < 1 || face > 6)
            return 0;
        double g[2][3] = {{0, 0, 0}, {0, 0, 0}};
        for (int i = 0; i < 2; i++) {
            int c = ab[face - 1][i];
            g[i][(c < 0 ? -c : c) - 1] = c < 0 ? -0.5 : 0.5;
        }
        *du = tex_v3_make(g[0][0], g[0][1], g[0][2]);
        *dv = tex_v3_make(g[1][0], g[1][1], g[1][2]);
        return 1;
    }
    case TEX_SHAPE_CYLINDER:
    case TEX_SHAPE_CONE:
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

static int map_point(const struct tex_apply *ap, const struct tex_object *leaf, tex_v3 P,
                     double uvw[3])
{
    return map_point_at(ap, leaf, P, tex_xform_point(&leaf->to_obj, P), uvw);
}

/* Window and placement: 0 if the point is outside the window. */
static int place(const struct tex_apply *ap, double uvw[3])
{
    double s = (uvw[0] - ap->u1) / (ap->u2 - ap->u1), t = (uvw[1] - ap->v1) / (ap->v2 - ap->v1);
    if (s < 0 || s > 1 || t < 0 || t > 1)
        return 0;
    uvw[0] = s * ap->nu;
    uvw[1] = t * ap->nv;
    return 1;
}

static double wrapdiff(double d)
{
    return d - floord(d + 0.5);
}

/* ---- application functions ---------------------------------------------------------- */

struct evalctx {
    const float *f;     /* map value, RGB */
    const float *p;     /* untextured value, RGB */
    double uvw[3], fw;
};

static void expr_eval(const struct tex_expr *e, const struct evalctx *c, double out[3])
{
    double a[3], b[3];
    switch (e->op) {
    case TEX_E_NUM:
        out[0] = out[1] = out[2] = e->v[0];
        return;
    case TEX_E_RGB:
        out[0] = e->v[0], out[1] = e->v[1], out[2] = e->v[2];
        return;
    case TEX_E_F:
        out[0] = c->f[0], out[1] = c->f[1], out[2] = c->f[2];
        return;
    case TEX_E_P:
        out[0] = c->p[0], out[1] = c->p[1], out[2] = c->p[2];
        return;
    case TEX_E_TEX: {
        float v[3];
        tex_texture_eval(e->tex, c->uvw[0], c->uvw[1], c->uvw[2], c->fw, v);
        out[0] = v[0], out[1] = v[1], out[2] = v[2];
        return;
    }
    case TEX_E_NEG:
        expr_eval(e->a, c, a);
        out[0] = -a[0], out[1] = -a[1], out[2] = -a[2];
        return;
    default:
        break;
    }
    expr_eval(e->a, c, a);
    expr_eval(e->b, c, b);
    for (int k = 0; k < 3; k++) {
        switch (e->op) {
        case TEX_E_ADD: out[k] = a[k] + b[k]; break;
        case TEX_E_SUB: out[k] = a[k] - b[k]; break;
        case TEX_E_MUL: out[k] = a[k] * b[k]; break;
        default: out[k] = b[k] != 0 ? a[k] / b[k] : 0; break;
        }
    }
}

/* An application function compiled to c0 + c1 f + c2 p + c3 f p per channel,
 * where its expression is at most linear in each of f and p (no cascade). */
struct poly {
    double c[4][3];
    int df, dp; /* degrees in f and p */
};

static int poly_of(const struct tex_expr *e, struct poly *r)
{
    struct poly a, b;
    memset(r, 0, sizeof *r);
    switch (e->op) {
    case TEX_E_NUM:
        r->c[0][0] = r->c[0][1] = r->c[0][2] = e->v[0];
        return 1;
    case TEX_E_RGB:
        for (int k = 0; k < 3; k++)
            r->c[0][k] = e->v[k];
        return 1;
    case TEX_E_F:
        r->c[1][0] = r->c[1][1] = r->c[1][2] = 1;
        r->df = 1;
        return 1;
    case TEX_E_P:
        r->c[2][0] = r->c[2][1] = r->c[2][2] = 1;
        r->dp = 1;
        return 1;
    case TEX_E_NEG:
        if (!poly_of(e->a, r))
            return 0;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                r->c[i][k] = -r->c[i][k];
        return 1;
    case TEX_E_ADD:
    case TEX_E_SUB:
    case TEX_E_MUL:
    case TEX_E_DIV:
        break;
    default:
        return 0;
    }
    if (!poly_of(e->a, &a) || !poly_of(e->b, &b))
        return 0;
    double sg = e->op == TEX_E_SUB ? -1 : 1;
    switch (e->op) {
    case TEX_E_ADD:
    case TEX_E_SUB:
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                r->c[i][k] = a.c[i][k] + sg * b.c[i][k];
        r->df = a.df | b.df;
        r->dp = a.dp | b.dp;
        return 1;
    case TEX_E_MUL:
        if (a.df + b.df > 1 || a.dp + b.dp > 1)
            return 0;
        for (int k = 0; k < 3; k++) {
            r->c[0][k] = a.c[0][k] * b.c[0][k];
            r->c[1][k] = a.c[0][k] * b.c[1][k] + a.c[1][k] * b.c[0][k];
            r->c[2][k] = a.c[0][k] * b.c[2][k] + a.c[2][k] * b.c[0][k];
            r->c[3][k] = a.c[0][k] * b.c[3][k] + a.c[3][k] * b.c[0][k] + a.c[1][k] * b.c[2][k] +
                         a.c[2][k] * b.c[1][k];
        }
        r->df = a.df | b.df;
        r->dp = a.dp | b.dp;
        return 1;
    default: /* division by a constant; by 0 gives 0 as in expr_eval */
        if (b.df || b.dp)
            return 0;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                r->c[i][k] = b.c[0][k] != 0 ? a.c[i][k] / b.c[0][k] : 0;
        r->df = a.df;
        r->dp = a.dp;
        return 1;
    }
}

static void poly_eval(const struct poly *q, const float f[3], const float p[3], double out[3])
{
    for (int k = 0; k < 3; k++) {
        double fk = f[k], pk = p[k];
        out[k] = q->c[0][k] + q->c[1][k] * fk + q->c[2][k] * pk + q->c[3][k] * fk * pk;
    }
}

struct tex_surface_cache {
    tex_colour col[3]; /* Ka Kd, Kd, Ks in the scene's colour space */
    int cached;        /* bit i: col[i] is constant (untextured) */
    struct poly *poly; /* per application function, in order */
    char *compiled;    /* 1: poly[i] holds function i */
};

static double clampd(double x, double lo, double hi)
{
    return !(x >= lo) ? lo : x > hi ? hi : x;
}

/* The parameters being textured, in RGB, before conversion to the colour space. */
struct params {
    float ka, kd[3], ks, n, kr, kt, ior, bump;
};

static void eval_fn(const struct tex_appfn *fn, const struct poly *q, const struct evalctx *c,
                    double r[3])
{
    if (q)
        poly_eval(q, c->f, c->p, r);
    else
        expr_eval(fn->e, c, r);
}

static void apply_fn(const struct tex_appfn *fn, const struct poly *q, struct params *pr,
                     const struct evalctx *base)
{
    struct evalctx c = *base;
    float p[3];
    double r[3];
    float *scalar = NULL;
    double lo = 0, hi = 1;
    switch (fn->param) {
    case TEX_SP_KD:
        c.p = pr->kd;
        eval_fn(fn, q, &c, r);
        for (int k = 0; k < 3; k++)
            pr->kd[k] = (float)clampd(r[k], 0, 1);
        return;
    case TEX_SP_KA: scalar = &pr->ka; break;
    case TEX_SP_KS: scalar = &pr->ks; break;
    case TEX_SP_N: scalar = &pr->n, lo = 0.1, hi = 10000; break;
    case TEX_SP_KR: scalar = &pr->kr; break;
    case TEX_SP_KT: scalar = &pr->kt; break;
    case TEX_SP_IOR: scalar = &pr->ior, lo = 0.1, hi = 10; break;
    default: scalar = &pr->bump, lo = -1000, hi = 1000; break;
    }
    p[0] = p[1] = p[2] = *scalar;
    c.p = p;
    /* a scalar parameter sees the map's luminance as f */
    float fl = (c.f[0] + c.f[1] + c.f[2]) / 3, fg[3] = {fl, fl, fl};
    c.f = fg;
    eval_fn(fn, q, &c, r);
    *scalar = (float)clampd((r[0] + r[1] + r[2]) / 3, lo, hi);
}

static float lum(const float v[3])
{
    return (v[0] + v[1] + v[2]) / 3;
}

/* Value of the applied texture at world point P (after mapping and placement). */
static int look(const struct tex_apply *ap, const struct tex_object *leaf, tex_v3 P, double fw,
                double uvw[3], float f[3])
{
    map_point(ap, leaf, P, uvw);
    if (!place(ap, uvw))
        return -1;
    return tex_texture_eval(ap->tex, uvw[0], uvw[1], uvw[2], fw, f);
}

void tex_resolve_material(const struct tex_scene *s, const struct tex_surface *sf,
                          const struct tex_object *leaf, tex_v3 P, tex_v3 D, tex_v3 *N,
                          double width, struct tex_material *m)
{
    const struct tex_surface_cache *sc = sf->cache;
    if (!sf->apply && sc && sc->cached == 7) { /* untextured: the cached colours as they are */
        int n = s->cs.n;
        tex_colour_copy(&m->ka, n, &sc->col[0]);
        tex_colour_copy(&m->kd, n, &sc->col[1]);
        tex_colour_copy(&m->ks, n, &sc->col[2]);
        m->n = (float)sf->n;
        m->kr = (float)sf->kr;
        m->kt = (float)sf->kt;
        m->ior = (float)sf->ior;
        m->model = sf->model;
        m->model_data = sf->ct;
        return;
    }
    struct params pr = {sf->ka, {sf->kd[0], sf->kd[1], sf->kd[2]}, sf->ks[0], (float)sf->n,
                        (float)sf->kr, (float)sf->kt, (float)sf->ior, 0};
    float ks_rgb[3] = {sf->ks[0], sf->ks[1], sf->ks[2]};
    int ks_textured = 0;
    if (sf->apply) {
        /* the pixel footprint on the surface: across the ray's projection
         * (stretched by 1/cos) and along the tangent perpendicular to it */
        double cosv = fabs(tex_v3_dot(D, *N));
        tex_v3 t1 = tex_v3_sub(D, tex_v3_scale(*N, tex_v3_dot(D, *N)));
        double l1 = tex_v3_len(t1);
        if (l1 < 1e-9) {
            t1 = fabs(N->x) < 0.9 ? tex_v3_cross(*N, tex_v3_make(1, 0, 0))
                                  : tex_v3_cross(*N, tex_v3_make(0, 1, 0));
            t1 = tex_v3_norm(t1);
        } else {
            t1 = tex_v3_scale(t1, 1 / l1);
        }
        tex_v3 t2 = tex_v3_cross(*N, t1);
        double w1 = width / (cosv > 0.02 ? cosv : 0.02), w2 = width;
        tex_v3 bumpg = tex_v3_make(0, 0, 0);
        int filter = s->settings.filter && width > 0;
        /* the hit and the two footprint steps in object space, once for every texture */
        double d1 = w1 < 1e-3 ? w1 : 1e-3, d2 = w2 < 1e-3 ? w2 : 1e-3;
        tex_v3 pl = tex_xform_point(&leaf->to_obj, P), pl1 = pl, pl2 = pl;
        tex_v3 P1 = P, P2 = P, o1 = t1, o2 = t2;
        int steps = 0; /* the tangents in object space and the footprint steps: computed */
        const struct tex_surface_cache *cache = sf->cache;
        int nfn = 0; /* index of the function in the cache */
        for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next) {
            double uvw[3], a[3], b[3];
            float f[3], fa[3], fb[3];
            int face = map_point_at(ap, leaf, P, pl, uvw);
            double u0 = uvw[0], v0 = uvw[1];
            if (!place(ap, uvw)) {
                for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next)
                    nfn++;
                continue;
            }
            double fw = 0;
            if (filter) {
                double su = ap->nu / (ap->u2 - ap->u1), sv = ap->nv / (ap->v2 - ap->v1);
                double a0, a1, b0, b1, l1, l2;
                tex_v3 du, dv;
                int grad = map_gradient(ap, leaf, &du, &dv); /* affine: world gradients */
                if (!grad && natural_gradient(ap, leaf, pl, face, &du, &dv)) {
                    if (!steps) { /* object-space gradients: object-space tangents */
                        o1 = tex_xform_dir(&leaf->to_obj, t1);
                        o2 = tex_xform_dir(&leaf->to_obj, t2);
                        P1 = tex_v3_madd(P, t1, d1), P2 = tex_v3_madd(P, t2, d2);
                        pl1 = tex_v3_madd(pl, o1, d1), pl2 = tex_v3_madd(pl, o2, d2);
                        steps = 1;
                    }
                    grad = 2;
                }
                if (grad) { /* the exact derivatives along the two tangents */
                    tex_v3 e1 = grad == 1 ? t1 : o1, e2 = grad == 1 ? t2 : o2;
                    a0 = tex_v3_dot(du, e1) * su, a1 = tex_v3_dot(dv, e1) * sv;
                    b0 = tex_v3_dot(du, e2) * su, b1 = tex_v3_dot(dv, e2) * sv;
                    l1 = (a0 * a0 + a1 * a1) * (w1 * w1); /* squared: one root below */
                    l2 = (b0 * b0 + b1 * b1) * (w2 * w2);
                } else {
                    if (!steps) {
                        o1 = tex_xform_dir(&leaf->to_obj, t1);
                        o2 = tex_xform_dir(&leaf->to_obj, t2);
                        P1 = tex_v3_madd(P, t1, d1), P2 = tex_v3_madd(P, t2, d2);
                        pl1 = tex_v3_madd(pl, o1, d1), pl2 = tex_v3_madd(pl, o2, d2);
                        steps = 1;
                    }
                    /* derivatives over a short step (no wrap-around), scaled to the footprint */
                    map_point_at(ap, leaf, P1, pl1, a);
                    map_point_at(ap, leaf, P2, pl2, b);
                    a0 = wrapdiff(a[0] - u0) * su, a1 = wrapdiff(a[1] - v0) * sv;
                    b0 = wrapdiff(b[0] - u0) * su, b1 = wrapdiff(b[1] - v0) * sv;
                    double s1 = w1 / d1, s2 = w2 / d2;
                    l1 = (a0 * a0 + a1 * a1) * (s1 * s1);
                    l2 = (b0 * b0 + b1 * b1) * (s2 * s2);
                }
                fw = sqrt(l1 > l2 ? l1 : l2);
            }
            /* one lookup: region maps and primitives ignore the footprint */
            int region = tex_texture_eval(ap->tex, uvw[0], uvw[1], uvw[2], fw, f);
            struct evalctx c = {f, NULL, {uvw[0], uvw[1], uvw[2]}, fw};
            for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++) {
                if (fn->region && fn->region != region)
                    continue;
                if (fn->param == TEX_SP_KS)
                    ks_textured = 1;
                apply_fn(fn, cache && cache->compiled[nfn] ? &cache->poly[nfn] : NULL, &pr, &c);
                if (fn->param == TEX_SP_BUMP && pr.bump != 0) {
                    /* Blinn: tilt N against the surface gradient of the map value */
                    double h = width > 1e-4 ? width : 1e-4;
                    double uv2[3];
                    int ra = look(ap, leaf, tex_v3_madd(P, t1, h), fw, uv2, fa);
                    int rb = look(ap, leaf, tex_v3_madd(P, t2, h), fw, uv2, fb);
                    if (ra >= 0 && rb >= 0) {
                        double g1 = (lum(fa) - lum(f)) / h, g2 = (lum(fb) - lum(f)) / h;
                        bumpg = tex_v3_add(bumpg, tex_v3_scale(tex_v3_add(tex_v3_scale(t1, g1),
                                                                          tex_v3_scale(t2, g2)),
                                                               pr.bump));
                    }
                    pr.bump = 0;
                }
            }
        }
        if (tex_v3_dot(bumpg, bumpg) > 0)
            *N = tex_v3_norm(tex_v3_sub(*N, bumpg));
    }
    const struct tex_colour_space *cs = &s->cs;
    float ka[3] = {pr.ka * pr.kd[0], pr.ka * pr.kd[1], pr.ka * pr.kd[2]};
    float ks[3];
    for (int k = 0; k < 3; k++)
        ks[k] = ks_textured ? pr.ks : ks_rgb[k];
    int n = cs->n, cached = sf->cache ? sf->cache->cached : 0;
    if (cached & 1)
        tex_colour_copy(&m->ka, n, &sf->cache->col[0]);
    else
        cs->from_rgb(cs, ka, TEX_SPECTRUM_REFLECTANCE, &m->ka);
    if (cached & 2)
        tex_colour_copy(&m->kd, n, &sf->cache->col[1]);
    else
        cs->from_rgb(cs, pr.kd, TEX_SPECTRUM_REFLECTANCE, &m->kd);
    if (cached & 4)
        tex_colour_copy(&m->ks, n, &sf->cache->col[2]);
    else
        cs->from_rgb(cs, ks, TEX_SPECTRUM_REFLECTANCE, &m->ks);
    m->n = pr.n;
    m->kr = pr.kr;
    m->kt = pr.kt;
    m->ior = pr.ior;
    m->model = sf->model;
    m->model_data = sf->ct;
}

int tex_surface_cache(struct tex_surface *sf, const struct tex_colour_space *cs)
{
    int textured = 0, nfn = 0; /* bits of enum tex_sparam */
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next)
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++)
            textured |= 1 << fn->param;
    tex_surface_uncache(sf);
    struct tex_surface_cache *c = calloc(1, sizeof *c);
    if (!c || !(c->poly = malloc((nfn ? nfn : 1) * sizeof *c->poly)) ||
        !(c->compiled = malloc(nfn ? nfn : 1))) {
        if (c)
            free(c->poly);
        free(c);
        return tex_error("out of memory");
    }
    nfn = 0;
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next)
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++)
            c->compiled[nfn] = (char)poly_of(fn->e, &c->poly[nfn]);
    float ka[3] = {sf->ka * sf->kd[0], sf->ka * sf->kd[1], sf->ka * sf->kd[2]};
    cs->from_rgb(cs, ka, TEX_SPECTRUM_REFLECTANCE, &c->col[0]);
    cs->from_rgb(cs, sf->kd, TEX_SPECTRUM_REFLECTANCE, &c->col[1]);
    cs->from_rgb(cs, sf->ks, TEX_SPECTRUM_REFLECTANCE, &c->col[2]);
    c->cached = (textured & (1 << TEX_SP_KA | 1 << TEX_SP_KD) ? 0 : 1) |
                (textured & 1 << TEX_SP_KD ? 0 : 2) | (textured & 1 << TEX_SP_KS ? 0 : 4);
    sf->cache = c;
    return 0;
}

void tex_surface_uncache(struct tex_surface *sf)
{
    if (sf->cache) {
        free(sf->cache->poly);
        free(sf->cache->compiled);
        free(sf->cache);
    }
    sf->cache = NULL;
}
