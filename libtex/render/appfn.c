/* appfn.c - application functions: a surface's textures applied to its shading
 * parameters at a hit (thesis 4.3.4, 5.3)
 *
 * g[region][parameter] = h: each texture a surface applies is looked up where its mapping
 * takes the hit, and its functions change Ka, Kd, Ks, n, Kr, Kt, the index of refraction,
 * the normal (Blinn's bump mapping, normal maps), Cook-Torrance's m and s and a blended
 * surface's weight; results are clamped to each parameter's range.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "ops/palette.h"
#include "render/anisotropic.h"
#include "render/appfn.h"
#include "render/render_ct.h"
#include "render/scene.h"

const struct tex_scene_word tex_quantities[TEX_Q_COUNT + 1] = {
    {"dist", NULL, "the path's length from the eye to the hit (through reflections)"},
    {"footprint", NULL, "the ray's footprint at the hit in texture units (the map is 1 wide)"},
    {"lod", NULL, "log2(footprint), at least -60: -9 where a pixel covers a texel of a 512 map"},
    {"ndotv", NULL, "the cosine between the normal and the direction to the viewer, 0..1"},
    {"depth", NULL, "0 for eye rays, one more per reflection or refraction"},
    {"x", NULL, "the hit's world x"},
    {"y", NULL, "the hit's world y"},
    {"z", NULL, "the hit's world z"},
    {"ox", NULL, "the hit's x in the object's own space"},
    {"oy", NULL, "the hit's y in the object's own space"},
    {"oz", NULL, "the hit's z in the object's own space"},
    {"u", NULL, "the mapping's u at the hit, 0..1 (before window and repeat)"},
    {"v", NULL, "the mapping's v at the hit"},
    {"w", NULL, "the mapping's w at the hit (solid mappings; else 0)"},
    {"nx", NULL, "the normal's world x, facing the ray (before bump)"},
    {"ny", NULL, "the normal's world y"},
    {"nz", NULL, "the normal's world z"},
    {"region", NULL, "the map's subregion id at the hit (0: a map without regions)"},
    {"face", NULL, "the shape's face at the hit: box 1..6 (+x -x +y -y +z -z), cylinder and "
                   "cone side 1, bottom cap 2, top cap 3; other shapes 1"},
    {NULL, NULL, NULL},
};

struct evalctx {
    const float *f;     /* map value, RGB */
    const float *p;     /* untextured value, RGB */
    const double *uvw;  /* where the map was looked up (for cascades) */
    double fw2; /* the footprint's squared width */
    const double *q;    /* the quantities at the hit (TEX_Q_COUNT), or NULL if none is read */
};

/* Function in (not rgb or palette) of the values at arg, its result in arg[0], by
 * lang/expr.h's definitions; once for arguments that are grey (the same in every channel),
 * as scalar parameters' are: sin and pow are not cheap. */
static void call(const struct tex_einsn *in, double (*arg)[3])
{
    int k = tex_expr_arity(in->op), grey = 1;
    double r[3];
    for (int i = 0; i < k; i++)
        grey &= arg[i][0] == arg[i][1] && arg[i][1] == arg[i][2];
    for (int ch = 0; ch < (grey ? 1 : 3); ch++)
        r[ch] = tex_expr_apply(in, ch, arg[0], k > 1 ? arg[1] : NULL, k > 2 ? arg[2] : NULL);
    if (grey)
        r[1] = r[2] = r[0];
    arg[0][0] = r[0], arg[0][1] = r[1], arg[0][2] = r[2];
}

/* Operand in (TEX_EOP_LEAF) at the hit c, into a */
static inline void leaf_value(const struct tex_einsn *in, const struct evalctx *c, double a[3])
{
    const float *v = in->leaf == TEX_LEAF_F ? c->f : c->p;
    float t[3];
    if (in->leaf >= TEX_LEAF_Q) {
        a[0] = a[1] = a[2] = c->q[in->leaf - TEX_LEAF_Q];
        return;
    }
    if (in->leaf == TEX_LEAF_TEX) {
        tex_texture_lookup(in->ptr, c->uvw[0], c->uvw[1], c->uvw[2], c->fw2, t);
        v = t;
    }
    a[0] = v[0], a[1] = v[1], a[2] = v[2];
}

/* Run the compiled function e (lang/expr.h) per channel: a loop over its postfix code
 * with the values on a stack in this frame; no recursion, no allocation. */
static void expr_eval(const struct tex_expr *e, const struct evalctx *c, double out[3])
{
    double st[TEX_EXPR_MAX_STACK][3], *a;
    int sp = 0;
    for (const struct tex_einsn *in = e->code, *end = in + e->n; in < end; in++) {
        switch (in->op) {
        case TEX_EOP_CONST:
            a = st[sp++];
            a[0] = in->v[0], a[1] = in->v[1], a[2] = in->v[2];
            continue;
        case TEX_EOP_LEAF:
            leaf_value(in, c, st[sp++]);
            continue;
        case TEX_EOP_RGB: /* channel k of argument k */
            sp -= 2;
            st[sp - 1][1] = st[sp][1];
            st[sp - 1][2] = st[sp + 1][2];
            continue;
        case TEX_EOP_PALETTE: { /* one lookup for the three channels */
            float rgba[4];
            a = st[sp - 1];
            tex_expr_palette(in->ptr, a, rgba);
            a[0] = rgba[0], a[1] = rgba[1], a[2] = rgba[2];
            continue;
        }
        case TEX_EOP_NEG: case TEX_EOP_ABS: /* cheap: in place, channel by channel */
            a = st[sp - 1];
            for (int k = 0; k < 3; k++)
                a[k] = tex_expr_op(in->op, a[k], 0, 0);
            continue;
        case TEX_EOP_ADD: case TEX_EOP_SUB: case TEX_EOP_MUL: case TEX_EOP_DIV:
        case TEX_EOP_MIN: case TEX_EOP_MAX:
            a = st[--sp - 1];
            for (int k = 0; k < 3; k++)
                a[k] = tex_expr_op(in->op, a[k], st[sp][k], 0);
            continue;
        default: /* the other functions of lang/expr.h */
            sp -= tex_expr_arity(in->op);
            call(in, st + sp);
            sp++;
            continue;
        }
    }
    out[0] = st[0][0], out[1] = st[0][1], out[2] = st[0][2];
}

/* The most values e's program holds on its stack */
static int expr_depth(const struct tex_expr *e)
{
    int sp = 0, most = 0;
    for (int i = 0; i < e->n; i++) {
        enum tex_eop op = e->code[i].op;
        sp += op == TEX_EOP_CONST || op == TEX_EOP_LEAF ? 1 : 1 - tex_expr_arity(op);
        most = sp > most ? sp : most;
    }
    return most;
}

/* expr_eval at the n <= TEX_LATER_MAX hits c (e's depth at most LATER_STACK): its program
 * walked once, each instruction over every hit, the same doubles; the palettes looked up
 * together */
#define LATER_STACK 8
static void expr_eval_n(const struct tex_expr *e, const struct evalctx *c, int n,
                        double (*out)[3])
{
    double st[LATER_STACK][TEX_LATER_MAX][3], (*a)[3];
    float rgb[TEX_LATER_MAX][3];
    int sp = 0;
    for (const struct tex_einsn *in = e->code, *end = in + e->n; in < end; in++) {
        switch (in->op) {
        case TEX_EOP_CONST:
            a = st[sp++];
            for (int i = 0; i < n; i++)
                a[i][0] = in->v[0], a[i][1] = in->v[1], a[i][2] = in->v[2];
            continue;
        case TEX_EOP_LEAF:
            a = st[sp++];
            for (int i = 0; i < n; i++)
                leaf_value(in, &c[i], a[i]);
            continue;
        case TEX_EOP_RGB:
            sp -= 2;
            for (int i = 0; i < n; i++)
                st[sp - 1][i][1] = st[sp][i][1], st[sp - 1][i][2] = st[sp + 1][i][2];
            continue;
        case TEX_EOP_PALETTE:
            a = st[sp - 1];
            tex_expr_palette_n(in->ptr, (const double(*)[3])a, n, rgb);
            for (int i = 0; i < n; i++)
                a[i][0] = rgb[i][0], a[i][1] = rgb[i][1], a[i][2] = rgb[i][2];
            continue;
        case TEX_EOP_NEG: case TEX_EOP_ABS:
            a = st[sp - 1];
            for (int i = 0; i < n; i++)
                for (int k = 0; k < 3; k++)
                    a[i][k] = tex_expr_op(in->op, a[i][k], 0, 0);
            continue;
        case TEX_EOP_ADD: case TEX_EOP_SUB: case TEX_EOP_MUL: case TEX_EOP_DIV:
        case TEX_EOP_MIN: case TEX_EOP_MAX:
            a = st[--sp - 1];
            for (int i = 0; i < n; i++)
                for (int k = 0; k < 3; k++)
                    a[i][k] = tex_expr_op(in->op, a[i][k], st[sp][i][k], 0);
            continue;
        default: { /* call's arguments gathered hit by hit */
            int k = tex_expr_arity(in->op);
            sp -= k;
            for (int i = 0; i < n; i++) {
                double arg[3][3];
                for (int j = 0; j < k; j++)
                    memcpy(arg[j], st[sp + j][i], sizeof arg[j]);
                call(in, arg);
                memcpy(st[sp][i], arg[0], sizeof arg[0]);
            }
            sp++;
            continue;
        }
        }
    }
    memcpy(out, st[0], (size_t)n * sizeof *out);
}

/* The polynomial of e in f and p (lang/expr.h), and whether it is folded */
static int poly_of(const struct tex_expr *e, struct poly *r)
{
    if (!tex_expr_poly(e, TEX_LEAF_F, TEX_LEAF_P, &r->p))
        return 0;
    const double *c0 = r->p.c[0];
    r->folded = !r->p.dx && !r->p.dy && c0[0] != 0 && c0[1] != 0 && c0[2] != 0;
    r->mean = (c0[0] + c0[1] + c0[2]) / 3;
    return 1;
}

/* Channel k of a compiled function at f, p */
static inline double poly_at(const struct poly *q, int k, double f, double p)
{
    const double(*c)[3] = q->p.c;
    return c[0][k] + c[1][k] * f + c[2][k] * p + c[3][k] * f * p;
}

typedef float float4 __attribute__((vector_size(16)));

/* Colour c of struct params set to v[0..2] by one store of four floats, the fourth as it
 * was: a later load of part of them is forwarded from the store, where one spanning three
 * single stores would wait for them to reach the cache (material's loads did, on Intel). */
static inline void colour_set(float *c, float4 v)
{
    v[3] = c[3];
    memcpy(c, &v, sizeof v);
}

static double clampd(double x, double lo, double hi)
{
    return !(x >= lo) ? lo : x > hi ? hi : x;
}

static float lum(const float v[3])
{
    return (v[0] + v[1] + v[2]) / 3;
}

/* A colour c of struct params through its compiled function q of the map value f, clamped
 * to lo..hi: channel k reads only its channel k. */
static inline __attribute__((always_inline)) void
colour_poly(const struct poly *q, const float f[3], double lo, double hi, float *c)
{
    float4 v;
    for (int k = 0; k < 3; k++)
        v[k] = (float)clampd(poly_at(q, k, f[k], c[k]), lo, hi);
    colour_set(c, v);
}

/* Function fn (compiled to q, or NULL) of the map value f looked up at uvw (footprint fw2),
 * applied to the parameters pr: the colour Kd per channel; a scalar parameter sees the map's
 * luminance as f and takes the mean of the channels.  Results clamped to the valid range. */
static void apply_fn(const struct tex_appfn *fn, const struct poly *q, const float f[3],
                     const double uvw[3], double fw2, const double *qv, struct params *pr)
{
    float *scalar = NULL, *colour = pr->kd, fg[3], p[3], sc = 0; /* sc: m or s, as a float */
    double lo = fn->lo, hi = fn->hi, r[3]; /* the parameter's row's range */
    switch (fn->param) {
    case TEX_SP_KD: break;
    case TEX_SP_KA: scalar = &pr->ka; break;
    case TEX_SP_KS: scalar = &pr->ks; break;
    case TEX_SP_N: scalar = &pr->n; break;
    case TEX_SP_KR: scalar = &pr->kr; break;
    case TEX_SP_KT: scalar = &pr->kt; break;
    case TEX_SP_IOR: scalar = &pr->ior; break;
    case TEX_SP_M: scalar = &sc, sc = (float)pr->m; break;
    case TEX_SP_S: scalar = &sc, sc = (float)pr->s; break;
    case TEX_SP_BLEND: scalar = &pr->blend; break;
    case TEX_SP_P: scalar = &pr->disp; break;
    case TEX_SP_AU: scalar = &pr->au; break;
    case TEX_SP_AV: scalar = &pr->av; break;
    case TEX_SP_ANGLE: scalar = &pr->angle; break;
    case TEX_SP_TANGENT: /* p: along the texture's u */
        colour = pr->tangent;
        colour[0] = 1, colour[1] = colour[2] = 0.5f;
        break;
    case TEX_SP_NORMAL: /* p: the flat normal */
        colour = pr->normal;
        colour[0] = colour[1] = 0.5f, colour[2] = 1;
        break;
    case TEX_SP_GRADIENT:
        colour = pr->gradient;
        colour[0] = colour[1] = colour[2] = 0;
        break;
    default: scalar = &pr->bump; break;
    }
    const float *fv = f, *pv = colour;
    /* a constant function where lum(f) and p are finite: poly_at's values are its c[0] */
    int folded = scalar && q && q->folded && isfinite(f[0] + f[1] + f[2]) && isfinite(*scalar);
    if (scalar && !folded) {
        fg[0] = fg[1] = fg[2] = lum(f);
        p[0] = p[1] = p[2] = *scalar;
        fv = fg, pv = p;
    }
    if (!q) {
        struct evalctx c = {fv, pv, uvw, fw2, qv};
        expr_eval(fn->e, &c, r);
    }
    if (scalar) {
        for (int k = 0; q && !folded && k < 3; k++)
            r[k] = poly_at(q, k, fv[k], pv[k]);
        *scalar = (float)clampd(folded ? q->mean : (r[0] + r[1] + r[2]) / 3, lo, hi);
        if (fn->param == TEX_SP_M)
            pr->m = sc;
        else if (fn->param == TEX_SP_S)
            pr->s = sc;
    } else if (q) {
        colour_poly(q, f, lo, hi, colour);
    } else {
        colour_set(colour, (float4){(float)clampd(r[0], lo, hi), (float)clampd(r[1], lo, hi),
                                    (float)clampd(r[2], lo, hi), 0});
    }
}

/* Kd's function fn (an expression) left in later to run with other hits'
 * (tex_plain_later_run): its operands as apply_fn would give them, f and Kd as p */
static void leave(struct tex_plain_later *later, const struct tex_appfn *fn, const float f[3],
                  const float kd[3], const double uvw[3], double fw2, const double *qv)
{
    later->fn = fn, later->fw2 = fw2, later->has_q = qv != NULL;
    memcpy(later->f, f, sizeof later->f), memcpy(later->p, kd, sizeof later->p);
    memcpy(later->uvw, uvw, sizeof later->uvw);
    if (qv)
        memcpy(later->q, qv, sizeof later->q);
}

/* fn at the hit, or left in later where it is the function left to run later (is_later) */
static void take_fn(struct tex_plain_later *later, int is_later, const struct tex_appfn *fn,
                    const struct poly *q, const float f[3], const double uvw[3], double fw2,
                    const double *qv, struct params *pr)
{
    if (later && is_later)
        leave(later, fn, f, pr->kd, uvw, fw2, qv);
    else
        apply_fn(fn, q, f, uvw, fw2, qv, pr);
}

/* The surface gradients (world space, texture units per world unit) of the placed u and v of
 * texture ap at the hit, (u0, v0) by its mapping, by finite differences along the tangents. */
static void uv_gradients(const struct tex_apply *ap, const struct placement *pm,
                         const struct tex_object *leaf, const tex_v3 *P, struct footprint *fp,
                         double width, double u0, double v0, tex_v3 *gu, tex_v3 *gv)
{
    double h = width > 1e-4 ? width : 1e-4, du[2], dv[2];
    footprint_unit(fp);
    for (int i = 0; i < 2; i++) {
        tex_v3 Pi = tex_v3_madd(*P, i ? fp->t2 : fp->t1, h);
        tex_v3 pli = tex_xform_point(&leaf->to_obj, Pi);
        double a[3];
        map_point_at(ap, leaf, &Pi, &pli, a);
        du[i] = wrapdiff(a[0] - u0) * pm->su / h;
        dv[i] = wrapdiff(a[1] - v0) * pm->sv / h;
    }
    *gu = tex_v3_add(tex_v3_scale(fp->t1, du[0]), tex_v3_scale(fp->t2, du[1]));
    *gv = tex_v3_add(tex_v3_scale(fp->t1, dv[0]), tex_v3_scale(fp->t2, dv[1]));
}

/* A tangent-space normal map's normal (encoded 0.5 + 0.5 n: x along u, y against v, since v
 * grows down the map, z along N) in world space; N itself where the map is flat. */
static tex_v3 normal_mapped(const float enc[3], const tex_v3 *N, const tex_v3 *gu,
                            const tex_v3 *gv)
{
    double x = 2.0 * enc[0] - 1, y = 2.0 * enc[1] - 1, z = 2.0 * enc[2] - 1;
    if (x == 0 && y == 0) /* flat: N as it is, to the bit */
        return *N;
    tex_v3 t = tex_v3_norm(*gu), b = tex_v3_scale(tex_v3_norm(*gv), -1);
    return tex_v3_norm(tex_v3_add(tex_v3_add(tex_v3_scale(t, x), tex_v3_scale(b, y)),
                                  tex_v3_scale(*N, z)));
}

/* A tilt's direction along the footprint's tangents t1, t2 from the luminance's
 * derivatives g along them; where grad (the map's gradient per u and v) is given, g is made
 * from it first, through the derivatives du, dv of u and v along t1, t2. */
tex_v3 tex_tilt_along(const double *grad, const double du[2], const double dv[2],
                         double g[2], tex_v3 t1, tex_v3 t2)
{
    if (grad)
        g[0] = grad[0] * du[0] + grad[1] * dv[0], g[1] = grad[0] * du[1] + grad[1] * dv[1];
    return tex_v3_add(tex_v3_scale(t1, g[0]), tex_v3_scale(t2, g[1]));
}

/* Blinn's bump mapping: the tilt of the normal against the surface gradient of texture ap's
 * luminance (f at the hit; pl: the hit in object space, on face).  grad (or NULL): the
 * gradient per placed u and v that the map's lookup gave (map_eval), taken through the
 * mapping's derivatives where they have a closed form; else (a primitive, a region map, a
 * mapping without them) finite differences along the footprint's tangents. */
static tex_v3 bump_tilt(const struct tex_apply *ap, const struct placement *pm,
                        const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *pl,
                        int face, struct footprint *fp, double width, double fw2,
                        const double *grad, const float f[3], double strength)
{
    double h = width > 1e-4 ? width : 1e-4, g[2], du[2], dv[2];
    footprint_unit(fp);
    if (grad && placed_derivatives(ap, pm, leaf, fp, pl, face, du, dv))
        return tex_v3_scale(tex_tilt_along(grad, du, dv, g, fp->t1, fp->t2), strength);
    for (int i = 0; i < 2; i++) {
        tex_v3 Pi = tex_v3_madd(*P, i ? fp->t2 : fp->t1, h);
        tex_v3 pli = tex_xform_point(&leaf->to_obj, Pi);
        double uvw[3];
        float fi[3];
        map_point_at(ap, leaf, &Pi, &pli, uvw);
        if (!place(ap, pm, uvw))
            return tex_v3_make(0, 0, 0);
        tex_texture_lookup(ap->tex, uvw[0], uvw[1], uvw[2], fw2, fi);
        g[i] = (lum(fi) - lum(f)) / h;
    }
    return tex_v3_scale(tex_tilt_along(NULL, NULL, NULL, g, fp->t1, fp->t2), strength);
}

/* A cross mapping's value (thesis 5.2.1.3): the map on the x-y plane (f, at u, v) combined
 * with the second map on the y-z plane, at (w, v), w placed as u is. */
static void cross_combine(const struct tex_apply *ap, const struct placement *pm,
                          const double uvw[3], double fw2, float f[3])
{
    float g[3];
    double w = (uvw[2] - ap->u1) * pm->iu * ap->nu;
    tex_texture_lookup(ap->cross, w, uvw[1], 0, fw2, g);
    for (int k = 0; k < 3; k++)
        f[k] = ap->combine == TEX_COMBINE_PRODUCT ? f[k] * g[k]
               : ap->combine == TEX_COMBINE_MIN   ? fminf(f[k], g[k])
                                                   : fmaxf(f[k], g[k]);
}

/* The quantities of the hit that do not depend on the texture (tex_quantities); the face,
 * the shape's own whatever the mapping, where read (bits, as tex_surface_cache's). */
static void hit_quantities(const struct tex_shade_at *at, const tex_v3 *pl, const tex_v3 *N,
                           int read, double q[TEX_Q_COUNT])
{
    double u, v;
    q[TEX_Q_FACE] = read & 1 << TEX_Q_FACE
                        ? tex_shape_methods[at->leaf->kind].uv(at->leaf, *pl, &u, &v) : 0;
    q[TEX_Q_DIST] = at->dist;
    q[TEX_Q_NDOTV] = fabs(tex_v3_dot(*N, *at->D));
    q[TEX_Q_DEPTH] = at->depth;
    q[TEX_Q_X] = at->P->x, q[TEX_Q_Y] = at->P->y, q[TEX_Q_Z] = at->P->z;
    q[TEX_Q_OX] = pl->x, q[TEX_Q_OY] = pl->y, q[TEX_Q_OZ] = pl->z;
    q[TEX_Q_NX] = N->x, q[TEX_Q_NY] = N->y, q[TEX_Q_NZ] = N->z;
}

/* The footprint (squared) that texture ap's lookups take at the hit P (pl), whose mapping
 * is pa: 0 where none uses one (filter off, primitives other than band-limited solids, a
 * band-limited value that came with the packet and no bump to look up); a band-limited
 * solid's over w too; a map's that came with the packet, the one it was looked up with.
 * *mapped: it is tex_footprint_width2's. */
static double lookup_width2(const struct tex_apply *ap, const struct placement *pm,
                            const struct tex_object *leaf, struct footprint *fp, const tex_v3 *P,
                            const tex_v3 *pl, const struct tex_prefetch_ap *pa, int filter,
                            int *mapped)
{
    if (pa->has_val && ap->tex->mip) { /* a map's value came with its footprint */
        *mapped = filter;
        return pa->fw;
    }
    int need = filter && ((uses_footprint(ap->tex) && (!pa->has_val || pm->bump)) ||
                          (ap->mapping == TEX_MAP_CROSS && uses_footprint(ap->cross)));
    *mapped = 0;
    if (!need)
        return 0;
    if (band_limited(ap->tex))
        return tex_solid_width2(ap, pm, leaf, fp, P, pl, pa->uvw0);
    *mapped = 1;
    return tex_footprint_width2(ap, pm, leaf, fp, P, pl, pa->face, pa->uvw0[0], pa->uvw0[1]);
}

/* The quantities of texture ap at the hit (its mapping pa) into q: the footprint fw2 when
 * lookup_width2 gave tex_footprint_width2's, else (fw2 < 0) the real one through fq, where
 * read (bits, as tex_surface_cache's quantities). */
static void texture_quantities(const struct tex_apply *ap, const struct placement *pm,
                               const struct tex_object *leaf, struct footprint *fq,
                               const tex_v3 *P, const tex_v3 *pl,
                               const struct tex_prefetch_ap *pa, double fw2, int region,
                               int read, double *q)
{
    if (read & (1 << TEX_Q_FOOTPRINT | 1 << TEX_Q_LOD)) { /* else unread: not made */
        double w2 = fw2 >= 0 ? fw2
                             : tex_footprint_width2(ap, pm, leaf, fq, P, pl, pa->face, pa->uvw0[0],
                                                pa->uvw0[1]);
        q[TEX_Q_FOOTPRINT] = sqrt(w2);
        q[TEX_Q_LOD] = w2 > 0x1p-120 ? log2(w2) / 2 : -60;
    }
    q[TEX_Q_U] = pa->uvw0[0], q[TEX_Q_V] = pa->uvw0[1], q[TEX_Q_W] = pa->uvw0[2];
    q[TEX_Q_REGION] = region;
}

/* Texture ap's value f at a hit its mapping took to pa, for a footprint fw2: the value that
 * came with the packet, or one lookup (region maps and primitives ignore the footprint),
 * combined with the cross mapping's second map; returns the region id.  grad (or NULL): a
 * map's gradient with its value (map_eval). */
static int texture_value(const struct tex_apply *ap, const struct placement *pm,
                         const struct tex_prefetch_ap *pa, double fw2, float f[3], double *grad)
{
    int region;
    if (pa->has_val && ap->tex->mip) { /* a map's, RGB already, and its gradient */
        memcpy(f, pa->val, 3 * sizeof *f);
        if (grad)
            grad[0] = pa->grad[0], grad[1] = pa->grad[1];
        return 0;
    }
    if (pa->has_val) {
        float val[TEX_MAP_MAX_CHANNELS];
        memcpy(val, pa->val, sizeof val);
        region = tex_field_finish(ap->tex, val, f);
    } else {
        region = texture_eval(ap->tex, pa->uvw[0], pa->uvw[1], pa->uvw[2], fw2, f, grad);
    }
    if (ap->mapping == TEX_MAP_CROSS)
        cross_combine(ap, pm, pa->uvw, fw2, f);
    return region;
}

/* The tilt's direction made ahead with the packet (lane_tilt), at the bump's strength */
static tex_v3 tilt_ahead(const struct tex_prefetch_ap *pa, double strength)
{
    return tex_v3_scale(tex_v3_make(pa->tilt[0], pa->tilt[1], pa->tilt[2]), strength);
}

/* N bent by the bumps' summed tilt (zero where none bumped) */
static void bend(tex_v3 tilt, tex_v3 *N)
{
    if (tex_v3_dot(tilt, tilt) > 0)
        *N = tex_v3_norm(tex_v3_sub(*N, tilt));
}

/* The textures of sf applied at the hit (normal N; filter: mip-mapped lookups) to pr, N bent
 * by bump maps; 1 if one of them set Ks. */
/* A normal map's or a height gradient's function, along the mapping's (u, v) at the hit:
 * the normal map bends N itself (0), the gradient gives its tilt in *t (1) */
static int uv_bend(enum tex_sparam param, const struct tex_apply *ap, const struct placement *pm,
                   const struct tex_object *leaf, const tex_v3 *P, struct footprint *fp,
                   double width, const struct tex_prefetch_ap *pa, const struct params *pr,
                   tex_v3 *N, tex_v3 *t)
{
    tex_v3 gu, gv;
    uv_gradients(ap, pm, leaf, P, fp, width, pa->uvw0[0], pa->uvw0[1], &gu, &gv);
    if (param == TEX_SP_NORMAL) {
        *N = normal_mapped(pr->normal, N, &gu, &gv);
        return 0;
    }
    *t = tex_v3_add(tex_v3_scale(gu, pr->gradient[0]), tex_v3_scale(gv, pr->gradient[1]));
    return 1;
}

/* A flow field's direction (anisotropic.h): the encoded R and G along the mapping's u and
 * against its v at the hit, in world space, into pr->flow (zero where the map is flat) */
static void flow_field(const struct tex_apply *ap, const struct placement *pm,
                       const struct tex_object *leaf, const tex_v3 *P, struct footprint *fp,
                       const struct tex_prefetch_ap *pa, struct params *pr)
{
    tex_v3 gu, gv;
    double x = 2.0 * pr->tangent[0] - 1, y = 2.0 * pr->tangent[1] - 1;
    /* the shortest step (width 0): a direction, not a filtered gradient as uv_bend's */
    uv_gradients(ap, pm, leaf, P, fp, 0, pa->uvw0[0], pa->uvw0[1], &gu, &gv);
    gu = tex_v3_norm(gu), gv = tex_v3_norm(gv);
    tex_v3 d = tex_v3_sub(tex_v3_scale(gu, x), tex_v3_scale(gv, y));
    if (!(tex_v3_dot(d, d) > 0)) /* flat, or a mapping without gradients here */
        d = tex_v3_make(0, 0, 0);
    pr->flow[0] = (float)d.x, pr->flow[1] = (float)d.y, pr->flow[2] = (float)d.z;
}

static int apply_textures(const struct tex_surface *sf, const struct tex_shade_at *at,
                          const struct tex_prefetch *pre, tex_v3 *N, int filter,
                          struct params *pr, struct tex_plain_later *later)
{
    const struct tex_object *leaf = at->leaf;
    const tex_v3 *P = at->P;
    tex_v3 Pd, N0 = *N; /* P moved by a P target along N0: the textures after it look there */
    float moved = 0;
    double width = filter ? at->width : 0;
    struct footprint fp;
    footprint_at(&fp, at->D, N, width);
    tex_v3 pl = pre ? pre->pl : tex_xform_point(&leaf->to_obj, *P), tilt = tex_v3_make(0, 0, 0);
    const struct tex_surface_cache *cache = sf->cache;
    const struct placement *pm = cache->placement;
    int nfn = 0, ks_textured = 0; /* nfn: the function's index in the cache */
    double qv[TEX_Q_COUNT], *q = NULL;
    struct footprint fq; /* the real footprint for the quantities, filtered or not */
    if (cache->quantities) {
        q = qv;
        hit_quantities(at, &pl, N, cache->quantities, q);
        footprint_at(&fq, at->D, N, at->width);
    }
    int j = 0;
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next, pm++, j++) {
        float f[3];
        /* the packet's mapping (the same computation, done ahead) or the hit's own */
        struct tex_prefetch_ap own;
        const struct tex_prefetch_ap *pa = pre && j < pre->n ? &pre->ap[j] : NULL;
        if (!pa) {
            map_hit(ap, pm, leaf, P, &pl, &own);
            pa = &own;
        }
        const double *uvw = pa->uvw;
        if (!pa->inside) {
            for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next)
                nfn++;
            continue;
        }
        int mapped; /* fw2 is tex_footprint_width2's, which the quantities report */
        double fw2 = lookup_width2(ap, pm, leaf, &fp, P, &pl, pa, filter, &mapped);
        double grad[2], *gp = pm->bump && ap->tex->mip && !ap->tex->subregions &&
                                      ap->mapping != TEX_MAP_CROSS ? grad : NULL;
        int region = texture_value(ap, pm, pa, fw2, f, gp);
        if (q)
            texture_quantities(ap, pm, leaf, &fq, P, &pl, pa, mapped ? fw2 : -1, region,
                               cache->quantities, q);
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++) {
            if (fn->region && fn->region != region)
                continue;
            ks_textured |= fn->param == TEX_SP_KS;
            take_fn(later, nfn == cache->later, fn, cache->compiled[nfn] ? &cache->poly[nfn] : NULL,
                    f, uvw, fw2, q, pr);
            if (fn->param == TEX_SP_BUMP && pr->bump != 0) {
                if (pa->has_tilt && ap->next) /* as bump_tilt leaves it for those after */
                    footprint_unit(&fp);
                tilt = tex_v3_add(tilt, pa->has_tilt ? tilt_ahead(pa, pr->bump)
                                                     : bump_tilt(ap, pm, leaf, P, &pl, pa->face,
                                                                 &fp, width, fw2, gp, f,
                                                                 pr->bump));
                pr->bump = 0;
            } else if (fn->param == TEX_SP_NORMAL || fn->param == TEX_SP_GRADIENT) {
                tex_v3 t;
                if (uv_bend(fn->param, ap, pm, leaf, P, &fp, width, pa, pr, N, &t))
                    tilt = tex_v3_add(tilt, t);
            } else if (fn->param == TEX_SP_TANGENT) {
                flow_field(ap, pm, leaf, P, &fp, pa, pr);
            }
        }
        if (pr->disp != moved && ap->next) { /* P moved: the next textures map it there */
            struct tex_shade_at atd = *at;
            moved = pr->disp;
            Pd = tex_v3_madd(*at->P, N0, moved);
            atd.P = P = &Pd, pl = tex_xform_point(&leaf->to_obj, Pd), pre = NULL;
            if (q)
                hit_quantities(&atd, &pl, &N0, cache->quantities, q);
        }
    }
    bend(tilt, N);
    return ks_textured;
}

/* cs->from_rgb of a reflectance; RGB mode's is the identity: copied without the call */
static inline void reflectance(const struct tex_colour_space *cs, const float rgb[3],
                               tex_colour *out)
{
    if (cs->mode == TEX_COLOUR_RGB)
        out->v[0] = rgb[0], out->v[1] = rgb[1], out->v[2] = rgb[2];
    else
        cs->from_rgb(cs, rgb, TEX_SPECTRUM_REFLECTANCE, out);
}

/* The material from the parameters pr (ks_textured: Ks was set by a texture). */
static inline __attribute__((always_inline)) void
material(const struct tex_colour_space *cs, const struct tex_surface *sf,
                            const struct params *pr, int ks_textured, struct tex_material *m)
{
    const struct tex_surface_cache *sc = sf->cache;
    int n = cs->n, cached = sc->cached; /* untextured surfaces: every colour cached */
    if (cached & 1) {
        tex_colour_copy(&m->ka, n, &sc->col[0]);
    } else {
        float ka[3] = {pr->ka * pr->kd[0], pr->ka * pr->kd[1], pr->ka * pr->kd[2]};
        reflectance(cs, ka, &m->ka);
    }
    if (cached & 2)
        tex_colour_copy(&m->kd, n, &sc->col[1]);
    else
        reflectance(cs, pr->kd, &m->kd);
    if (cached & 4) {
        tex_colour_copy(&m->ks, n, &sc->col[2]);
    } else {
        float ks[3] = {pr->ks, pr->ks, pr->ks};
        reflectance(cs, ks_textured ? ks : sf->ks, &m->ks);
    }
    m->n = pr->n;
    m->kr = pr->kr;
    m->kt = pr->kt;
    m->ior = pr->ior;
    m->m = pr->m;
    m->s = pr->s;
    m->disp = pr->disp;
    m->model = sf->model;
    m->model_data = sf->ct;
    m->blend = 0;
    m->blend_m = NULL;
}

/* The value f of a direct surface's texture t that came with the packet in pa (texture_value's
 * for it): a map's, RGB already, or a primitive's through its palette into fin */
static inline const float *direct_value(const struct tex_texture *t,
                                        const struct tex_prefetch_ap *pa, float fin[3])
{
    if (t->mip)
        return pa->val;
    float val[TEX_MAP_MAX_CHANNELS];
    memcpy(val, pa->val, sizeof val);
    tex_field_finish(t, val, fin);
    return fin;
}

/* apply_textures for a direct surface (tex_surface_cache) whose texture's value came with
 * the packet in pa: a map's with its footprint, and a bump's tilt where it bumps; a
 * primitive's without (lookup_width2's 0 for a value made ahead).  Its functions in order,
 * without the general path's set-up; N bent as apply_textures bends it */
static int apply_direct(const struct tex_surface *sf, const struct tex_prefetch_ap *pa,
                        tex_v3 *N, struct params *pr, struct tex_plain_later *later)
{
    const struct tex_surface_cache *c = sf->cache;
    int ks_textured = 0, i = 0;
    tex_v3 tilt = tex_v3_make(0, 0, 0);
    float fin[3];
    const float *f = pa->inside ? direct_value(sf->apply->tex, pa, fin) : NULL;
    double fw2 = sf->apply->tex->mip ? pa->fw : 0;
    for (const struct tex_appfn *fn = sf->apply->fns; pa->inside && fn; fn = fn->next, i++) {
        const struct poly *q = c->compiled[i] ? &c->poly[i] : NULL;
        ks_textured |= fn->param == TEX_SP_KS;
        if (q && fn->param == TEX_SP_KD) { /* apply_fn's path for it, without the call */
            colour_poly(q, f, fn->lo, fn->hi, pr->kd);
            continue;
        }
        take_fn(later, i == c->later, fn, q, f, pa->uvw, fw2, NULL, pr);
        if (fn->param == TEX_SP_BUMP && pr->bump != 0) {
            tilt = tex_v3_add(tilt, tilt_ahead(pa, pr->bump));
            pr->bump = 0;
        }
    }
    bend(tilt, N);
    return ks_textured;
}

/* A textured surface's parameters at the hit into pr, N bent by its bumps; 1 if a texture
 * set Ks.  later: resolve's. */
static int textured_params(const struct tex_scene *s, const struct tex_surface *sf,
                           const struct tex_shade_at *at, tex_v3 *N, struct params *pr,
                           struct tex_plain_later *later)
{
    *pr = sf->cache->base;
    const struct tex_prefetch *pre = at->pre && at->pre->sf == sf ? at->pre : NULL;
    int filter = s->settings.filter && at->width > 0;
    /* a bumped direct surface's tilt made ahead in lanes, or the general path's own */
    int direct = pre && sf->cache->direct && pre->n && pre->ap[0].has_val &&
                 (!sf->cache->placement[0].bump || pre->ap[0].has_tilt);
    int ks_textured = direct ? apply_direct(sf, &pre->ap[0], N, pr, later)
                             : apply_textures(sf, at, pre, N, filter, pr, later);
    if (later && later->fn)
        later->ka = pr->ka;
    return ks_textured;
}

/* One surface's material at the hit; returns its blend's weight there.  later (or NULL):
 * where the surface's function cache->later is to be left (tex_plain_resolve). */
static float resolve(const struct tex_scene *s, const struct tex_surface *sf,
                     const struct tex_shade_at *at, tex_v3 *N, struct tex_material *m,
                     struct tex_plain_later *later)
{
    if (!sf->apply) { /* the cache as it is, without the textured path's set-up */
        const struct params *b = &sf->cache->base;
        material(&s->cs, sf, b, 0, m);
        if (tex_shading_anisotropic(sf->model))
            tex_aniso_material(m, sf, at->leaf, at->P, N, b->flow, b->angle, b->au, b->av);
        return 0;
    }
    struct params pr;
    int ks_textured = textured_params(s, sf, at, N, &pr, later);
    material(&s->cs, sf, &pr, ks_textured, m);
    if (tex_shading_anisotropic(sf->model))
        tex_aniso_material(m, sf, at->leaf, at->P, N, pr.flow, pr.angle, pr.au, pr.av);
    return pr.blend;
}

void tex_resolve_material(const struct tex_scene *s, const struct tex_surface *sf,
                          const struct tex_shade_at *at, tex_v3 *N, struct tex_material m[2])
{
    tex_v3 N1 = *N; /* this surface's normal shades both */
    float w = resolve(s, sf, at, N, &m[0], NULL);
    if (sf->blend && w > 0) { /* the other surface at the same hit, its own textures */
        resolve(s, sf->blend, at, &N1, &m[1], NULL); /* its own blend's weight unused */
        tex_colour_scale(&m[0].ka, s->cs.n, &m[0].ka, 1 - w); /* the ambient term, mixed */
        for (int i = 0; i < s->cs.n; i++)
            m[0].ka.v[i] += w * m[1].ka.v[i];
        m[0].blend = w;
        m[0].blend_m = &m[1];
    }
}

/* The quantities (tex_quantities) function fn reads, bit k for quantity k */
static int fn_quantities(const struct tex_appfn *fn)
{
    int q = 0;
    for (int i = 0; i < fn->e->n; i++)
        if (fn->e->code[i].op == TEX_EOP_LEAF && fn->e->code[i].leaf >= TEX_LEAF_Q)
            q |= 1 << (fn->e->code[i].leaf - TEX_LEAF_Q);
    return q;
}

/* The surface's own parameters, before its textures (Cook-Torrance's m and s: the
 * surface's, or the defaults) */
static struct params surface_params(const struct tex_surface *sf)
{
    struct tex_material ctm;
    tex_ct_material(&ctm, sf->ct);
    return (struct params){{sf->kd[0], sf->kd[1], sf->kd[2]}, sf->ka, sf->ks[0], (float)sf->n,
                           (float)sf->kr, (float)sf->kt, (float)sf->ior, 0, ctm.m, ctm.s, 0,
                           {0.5f, 0.5f, 1}, {0, 0, 0}, 0, (float)sf->alpha[0],
                           (float)sf->alpha[1], 0, {1, 0.5f, 0.5f}, {0, 0, 0}, 0};
}

int tex_surface_energy(const struct tex_surface *sf, double *e)
{
    static const double corner[9][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1},
                                        {1, 0, 1}, {0, 1, 1}, {1, 1, 1}, {0.5, 0.5, 0.5}};
    int ks_textured = 0, levels = sf->apply ? 17 : 1, places = sf->apply ? 9 : 1;
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next)
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next) {
            ks_textured |= fn->param == TEX_SP_KS;
            if (fn_quantities(fn))
                return 0; /* the hit's quantities: no value without a hit */
        }
    const struct params base = surface_params(sf);
    *e = 0;
    for (int l = 0; l < levels; l++)
        for (int c = 0; c < places; c++) {
            struct params pr = base;
            float f[3] = {(float)l / 16, (float)l / 16, (float)l / 16};
            for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next)
                for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next)
                    apply_fn(fn, NULL, f, corner[c], 0, NULL, &pr);
            double kd = fmax(pr.kd[0], fmax(pr.kd[1], pr.kd[2]));
            double ks = ks_textured ? pr.ks : fmax(sf->ks[0], fmax(sf->ks[1], sf->ks[2]));
            /* Ks (the lights' highlight) and Kr (the scene's mirror image) are one specular
             * reflectance seen in two kinds of incident light, as Whitted's single ks;
             * the microfacet models (Cook-Torrance, Ward, Ashikhmin-Shirley) split light
             * s to 1 - s, and Fresnel's F to 1 - F splits Kr from Kt */
            double sum = kd + fmax(ks, pr.kr) + pr.kt;
            if (sf->model != &tex_shading_phong)
                sum = (1 - pr.s) * kd +
                      fmax(pr.s, fmax(pr.kr, sf->ct && sf->ct->conductor ? 0 : pr.kt));
            *e = sum > *e ? sum : *e;
        }
    return 1;
}

int tex_surface_cache(struct tex_surface *sf, const struct tex_colour_space *cs)
{
    int textured = 0, nfn = 0, nap = 0; /* textured: bits of enum tex_sparam */
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next, nap++)
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++)
            textured |= 1 << fn->param;
    tex_surface_uncache(sf);
    struct tex_surface_cache *c = calloc(1, sizeof *c);
    sf->cache = c;
    if (!c || !(c->poly = malloc((nfn ? nfn : 1) * sizeof *c->poly)) ||
        !(c->compiled = malloc(nfn ? nfn : 1)) ||
        !(c->placement = malloc((nap ? nap : 1) * sizeof *c->placement))) {
        tex_surface_uncache(sf);
        return tex_error("out of memory");
    }
    nfn = nap = 0;
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next) {
        tex_placement_of(ap, &c->placement[nap]);
        c->footprints |= band_limited(ap->tex) || (!nap && map_ahead(ap));
        c->direct = !nap && !ap->next && (map_ahead(ap) || value_ahead(ap));
        nap++;
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++) {
            c->direct &= !fn->region && fn->param != TEX_SP_NORMAL &&
                         fn->param != TEX_SP_GRADIENT && fn->param != TEX_SP_P &&
                         fn->param != TEX_SP_TANGENT;
            c->compiled[nfn] = (char)poly_of(fn->e, &c->poly[nfn]);
            c->quantities |= fn_quantities(fn);
        }
    }
    c->direct &= !c->quantities;
    c->lanes = c->direct && map_ahead(sf->apply) && tex_simd_level() >= TEX_SIMD_AVX2;
    c->base = surface_params(sf);
    float ka[3] = {sf->ka * sf->kd[0], sf->ka * sf->kd[1], sf->ka * sf->kd[2]};
    cs->from_rgb(cs, ka, TEX_SPECTRUM_REFLECTANCE, &c->col[0]);
    cs->from_rgb(cs, sf->kd, TEX_SPECTRUM_REFLECTANCE, &c->col[1]);
    cs->from_rgb(cs, sf->ks, TEX_SPECTRUM_REFLECTANCE, &c->col[2]);
    if (sf->ct && tex_ct_tabulate(sf->ct, cs->n) < 0) {
        tex_surface_uncache(sf);
        return -1;
    }
    c->cached = (textured & (1 << TEX_SP_KA | 1 << TEX_SP_KD) ? 0 : 1) |
                (textured & 1 << TEX_SP_KD ? 0 : 2) | (textured & 1 << TEX_SP_KS ? 0 : 4);
    int plain = sf->model == &tex_shading_phong && !sf->blend && c->base.kr <= 0 &&
                c->base.kt <= 0 && !(textured & (1 << TEX_SP_KR | 1 << TEX_SP_KT));
    int lean = !sf->apply || (c->direct && !c->placement[0].bump); /* tex_plain_material's */
    nfn = 0;
    for (const struct tex_appfn *fn = sf->apply ? sf->apply->fns : NULL; fn; fn = fn->next)
        lean &= fn->param == TEX_SP_KD && c->compiled[nfn++];
    plain &= !(textured & 1 << TEX_SP_P); /* a moved P: shade_begin's */
    c->plain = plain ? (lean ? 1 : 2) : 0;
    /* a plain surface's last Kd function, where an expression that is no polynomial (a
     * palette's, a sine's) and shallow enough to run over a packet's hits */
    c->later = -1;
    nfn = 0;
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next)
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++)
            if (fn->param == TEX_SP_KD)
                c->later = c->plain == 2 && !c->compiled[nfn] && expr_depth(fn->e) <= LATER_STACK
                               ? nfn : -1;
    return 0;
}

int tex_surface_plain(const struct tex_surface *sf)
{
    return sf->cache->plain;
}

/* material's colours and exponent in RGB (a plain surface's scene) from Ka, Kd, Ks and n,
 * the cached colours where untextured */
static void plain_colours(const struct tex_surface_cache *c, float ka, const float kd[3],
                          const float ks[3], float n, struct tex_plain *m)
{
    for (int k = 0; k < 3; k++) {
        m->ka[k] = c->cached & 1 ? c->col[0].v[k] : ka * kd[k];
        m->kd[k] = c->cached & 2 ? c->col[1].v[k] : kd[k];
        m->ks[k] = c->cached & 4 ? c->col[2].v[k] : ks[k];
    }
    m->n = n;
}

void tex_plain_resolve(const struct tex_scene *s, const struct tex_surface *sf,
                       const struct tex_shade_at *at, tex_v3 *N, struct tex_plain *pm,
                       struct tex_plain_later *later)
{
    struct params pr; /* a plain surface is textured (tex_surface_cache's 2), has no blend */
    if (later)
        later->fn = NULL;
    int ks_textured = textured_params(s, sf, at, N, &pr, sf->cache->later >= 0 ? later : NULL);
    float ks[3] = {pr.ks, pr.ks, pr.ks};
    plain_colours(sf->cache, pr.ka, pr.kd, ks_textured ? ks : sf->ks, pr.n, pm);
}

void tex_plain_later_run(struct tex_plain_later *later, struct tex_plain *m, int n)
{
    if (n > TEX_LATER_MAX) {
        tex_plain_later_run(later + TEX_LATER_MAX, m + TEX_LATER_MAX, n - TEX_LATER_MAX);
        n = TEX_LATER_MAX;
    }
    int todo[TEX_LATER_MAX], left = 0;
    for (int i = 0; i < n; i++)
        if (later[i].fn)
            todo[left++] = i;
    while (left) { /* the hits of one function together */
        const struct tex_appfn *fn = later[todo[0]].fn;
        struct evalctx c[TEX_LATER_MAX];
        double r[TEX_LATER_MAX][3];
        int at[TEX_LATER_MAX], g = 0, rest = 0;
        for (int j = 0; j < left; j++) {
            struct tex_plain_later *l = &later[todo[j]];
            if (l->fn != fn) {
                todo[rest++] = todo[j];
                continue;
            }
            at[g] = todo[j];
            c[g++] = (struct evalctx){l->f, l->p, l->uvw, l->fw2, l->has_q ? l->q : NULL};
        }
        left = rest;
        expr_eval_n(fn->e, c, g, r);
        for (int j = 0; j < g; j++) /* apply_fn's Kd, then material's Ka Kd */
            for (int k = 0; k < 3; k++) {
                float kd = (float)clampd(r[j][k], fn->lo, fn->hi);
                m[at[j]].kd[k] = kd, m[at[j]].ka[k] = later[at[j]].ka * kd;
            }
    }
}

int tex_plain_material(const struct tex_surface *sf, const struct tex_prefetch *pre,
                       struct tex_plain *m)
{
    const struct tex_surface_cache *c = sf->cache;
    const struct tex_prefetch_ap *pa = &pre->ap[0];
    float v[4] = {c->base.kd[0], c->base.kd[1], c->base.kd[2], 0}, fin[3];
    if (sf->apply && !(pre->sf == sf && pre->n && pa->has_val))
        return 0;
    const float *f = sf->apply && pa->inside ? direct_value(sf->apply->tex, pa, fin) : NULL;
    int i = 0; /* apply_direct's compiled Kd functions, in order */
    for (const struct tex_appfn *fn = f ? sf->apply->fns : NULL; fn; fn = fn->next, i++)
        colour_poly(&c->poly[i], f, fn->lo, fn->hi, v);
    plain_colours(c, c->base.ka, v, sf->ks, c->base.n, m);
    return 1;
}

void tex_surface_uncache(struct tex_surface *sf)
{
    if (sf->ct)
        tex_ct_untabulate(sf->ct);
    if (sf->cache) {
        free(sf->cache->poly);
        free(sf->cache->compiled);
        free(sf->cache->placement);
        free(sf->cache);
    }
    sf->cache = NULL;
}

void tex_appfn_eval(const struct tex_expr *e, const float f[3], const float p[3],
                    const double uvw[3], double fw2, const double *q, double out[3])
{
    struct evalctx c = {f, p, uvw, fw2, q};
    expr_eval(e, &c, out);
}
