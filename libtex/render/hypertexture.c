/* hypertexture.c - object densities, soft booleans and the modulated hypertexture at a
 * point (thesis 2.9) */
#include <math.h>

#include "render/appfn.h"
#include "render/hypertexture.h"
#include "render/surface.h"

const char *const tex_hdensity_names[TEX_HD_NKINDS] = {
    "sphere", "box", "cylinder", "union", "intersection", "difference", "complement"};

int tex_hdensity_prepare(struct tex_hdensity *n, struct tex_hdensity **bad, const char **msg)
{
    double h = n->soft / 2;
    *bad = n;
    switch (n->kind) {
    case TEX_HD_SPHERE:
        if (!(n->radius > 0)) {
            *msg = "sphere radius must be > 0";
            return -1;
        }
        if (!(h <= n->radius)) {
            *msg = "soft width must be at most twice the radius (the inner radius r - s/2 >= 0)";
            return -1;
        }
        n->r0 = (n->radius + h) * (n->radius + h);
        n->r1 = (n->radius - h) * (n->radius - h);
        n->lo = tex_v3_sub(n->centre, tex_v3_make(n->radius + h, n->radius + h, n->radius + h));
        n->hi = tex_v3_add(n->centre, tex_v3_make(n->radius + h, n->radius + h, n->radius + h));
        return 0;
    case TEX_HD_BOX:
        if (!(n->max.x > n->min.x && n->max.y > n->min.y && n->max.z > n->min.z)) {
            *msg = "box needs min < max on every axis";
            return -1;
        }
        n->r0 = h;
        n->lo = tex_v3_sub(n->min, tex_v3_make(h, h, h));
        n->hi = tex_v3_add(n->max, tex_v3_make(h, h, h));
        return 0;
    case TEX_HD_CYLINDER: {
        tex_v3 a = tex_v3_sub(n->top, n->base);
        n->len = tex_v3_len(a);
        if (!(n->len > 0) || !(n->radius > 0)) {
            *msg = "cylinder needs base != top and radius > 0";
            return -1;
        }
        n->axis = tex_v3_scale(a, 1 / n->len);
        n->r0 = h;
        /* the caps' discs reach r sqrt(1 - a_i^2) along axis i */
        tex_v3 e = tex_v3_make(n->radius * sqrt(fmax(0, 1 - n->axis.x * n->axis.x)) + h,
                               n->radius * sqrt(fmax(0, 1 - n->axis.y * n->axis.y)) + h,
                               n->radius * sqrt(fmax(0, 1 - n->axis.z * n->axis.z)) + h);
        n->lo = tex_v3_sub(tex_v3_make(fmin(n->base.x, n->top.x), fmin(n->base.y, n->top.y),
                                       fmin(n->base.z, n->top.z)), e);
        n->hi = tex_v3_add(tex_v3_make(fmax(n->base.x, n->top.x), fmax(n->base.y, n->top.y),
                                       fmax(n->base.z, n->top.z)), e);
        return 0;
    }
    default:
        if (tex_hdensity_prepare(n->a, bad, msg) < 0)
            return -1;
        return n->kind == TEX_HD_COMPLEMENT ? 0 : tex_hdensity_prepare(n->b, bad, msg);
    }
}

int tex_hdensity_bounded(const struct tex_hdensity *n)
{
    switch (n->kind) {
    case TEX_HD_UNION: return tex_hdensity_bounded(n->a) && tex_hdensity_bounded(n->b);
    case TEX_HD_INTERSECTION: return tex_hdensity_bounded(n->a) || tex_hdensity_bounded(n->b);
    case TEX_HD_DIFFERENCE: return tex_hdensity_bounded(n->a);
    case TEX_HD_COMPLEMENT: return 0;
    default: return 1;
    }
}

/* A signed distance's density: 1 inside by s/2 or more, 0 outside by s/2, linear between */
static double ramp(double d, double soft)
{
    return soft > 0 ? clamp01(0.5 - d / soft) : d <= 0;
}

/* The signed distance of a box of half-sides q0 whose centre is at distance |q|: outside,
 * the length of the positive part; inside, minus the nearest face's distance */
static double box_distance(double qx, double qy, double qz)
{
    double ox = fmax(qx, 0), oy = fmax(qy, 0), oz = fmax(qz, 0);
    return sqrt(ox * ox + oy * oy + oz * oz) + fmin(fmax(qx, fmax(qy, qz)), 0);
}

double tex_hdensity_eval(const struct tex_hdensity *n, const tex_v3 *P)
{
    switch (n->kind) {
    case TEX_HD_SPHERE: {
        tex_v3 v = tex_v3_sub(*P, n->centre);
        double rx = tex_v3_dot(v, v);
        return rx <= n->r1 ? 1 : rx >= n->r0 ? 0 : (n->r0 - rx) / (n->r0 - n->r1);
    }
    case TEX_HD_BOX: {
        double qx = fabs(P->x - 0.5 * (n->min.x + n->max.x)) - 0.5 * (n->max.x - n->min.x);
        double qy = fabs(P->y - 0.5 * (n->min.y + n->max.y)) - 0.5 * (n->max.y - n->min.y);
        double qz = fabs(P->z - 0.5 * (n->min.z + n->max.z)) - 0.5 * (n->max.z - n->min.z);
        return ramp(box_distance(qx, qy, qz), n->soft);
    }
    case TEX_HD_CYLINDER: {
        tex_v3 v = tex_v3_sub(*P, n->base);
        double h = tex_v3_dot(v, n->axis);
        double rad = tex_v3_len(tex_v3_sub(v, tex_v3_scale(n->axis, h)));
        return ramp(box_distance(rad - n->radius, fabs(h - n->len / 2) - n->len / 2, -INFINITY),
                    n->soft);
    }
    case TEX_HD_UNION: return fmax(tex_hdensity_eval(n->a, P), tex_hdensity_eval(n->b, P));
    case TEX_HD_INTERSECTION:
        return fmin(tex_hdensity_eval(n->a, P), tex_hdensity_eval(n->b, P));
    case TEX_HD_DIFFERENCE:
        return fmin(tex_hdensity_eval(n->a, P), 1 - tex_hdensity_eval(n->b, P));
    default: return 1 - tex_hdensity_eval(n->a, P);
    }
}

/* The ray's span inside the box lo..hi (the slabs' test) */
static int box_span(tex_v3 lo, tex_v3 hi, const tex_v3 *o, const tex_v3 *d, double *t0,
                    double *t1)
{
    double a = -INFINITY, b = INFINITY;
    const double O[3] = {o->x, o->y, o->z}, D[3] = {d->x, d->y, d->z};
    const double L[3] = {lo.x, lo.y, lo.z}, H[3] = {hi.x, hi.y, hi.z};
    for (int i = 0; i < 3; i++) {
        if (D[i] == 0) {
            if (O[i] < L[i] || O[i] > H[i])
                return 0;
            continue;
        }
        double u = (L[i] - O[i]) / D[i], v = (H[i] - O[i]) / D[i];
        a = fmax(a, fmin(u, v));
        b = fmin(b, fmax(u, v));
    }
    *t0 = a, *t1 = b;
    return a <= b;
}

int tex_hdensity_span(const struct tex_hdensity *n, const tex_v3 *o, const tex_v3 *d,
                      double *t0, double *t1)
{
    double a0, a1, b0, b1;
    int ha, hb;
    switch (n->kind) {
    case TEX_HD_SPHERE: { /* |o + t d - c|^2 = (r + s/2)^2 */
        tex_v3 v = tex_v3_sub(*o, n->centre);
        double b = tex_v3_dot(v, *d), c = tex_v3_dot(v, v) - n->r0, disc = b * b - c;
        if (!(disc >= 0))
            return 0;
        double q = sqrt(disc);
        *t0 = -b - q, *t1 = -b + q;
        return 1;
    }
    case TEX_HD_BOX:
    case TEX_HD_CYLINDER: return box_span(n->lo, n->hi, o, d, t0, t1);
    case TEX_HD_COMPLEMENT: *t0 = -INFINITY, *t1 = INFINITY; return 1;
    case TEX_HD_DIFFERENCE: return tex_hdensity_span(n->a, o, d, t0, t1);
    default:
        ha = tex_hdensity_span(n->a, o, d, &a0, &a1);
        hb = tex_hdensity_span(n->b, o, d, &b0, &b1);
        if (n->kind == TEX_HD_UNION) {
            if (!ha || !hb) {
                *t0 = ha ? a0 : b0, *t1 = ha ? a1 : b1;
                return ha || hb;
            }
            *t0 = fmin(a0, b0), *t1 = fmax(a1, b1);
            return 1;
        }
        if (!ha || !hb)
            return 0;
        *t0 = fmax(a0, b0), *t1 = fmin(a1, b1);
        return *t0 <= *t1;
    }
}

/* Function fn of h at the point, its channels' mean clamped to its range */
static double scalar_fn(const struct tex_hyper *h, int fn, const float f[3], const float p[3],
                        const double uvw[3], double fw2, const double *q)
{
    double r[3];
    tex_appfn_eval(h->fn[fn], f, p, uvw, fw2, q, r);
    double x = (r[0] + r[1] + r[2]) / 3;
    return x > h->lo[fn] ? (x < h->hi[fn] ? x : h->hi[fn]) : h->lo[fn]; /* NaN -> lo */
}

static void colour_fn(const struct tex_hyper *h, int fn, const float f[3], const float p[3],
                      const double uvw[3], double fw2, const double *q, float out[3])
{
    double r[3];
    tex_appfn_eval(h->fn[fn], f, p, uvw, fw2, q, r);
    for (int k = 0; k < 3; k++)
        out[k] = (float)(r[k] > h->lo[fn] ? (r[k] < h->hi[fn] ? r[k] : h->hi[fn]) : h->lo[fn]);
}

void tex_hyper_at(const struct tex_hyper *h, const tex_v3 *P, double fw2, int shadow,
                  struct tex_hyper_sample *out)
{
    double D = tex_hdensity_eval(h->d, P);
    const double uvw[3] = {P->x, P->y, P->z};
    double q[TEX_Q_COUNT] = {0};
    q[TEX_Q_X] = q[TEX_Q_OX] = P->x;
    q[TEX_Q_Y] = q[TEX_Q_OY] = P->y;
    q[TEX_Q_Z] = q[TEX_Q_OZ] = P->z;
    const float fD[3] = {(float)D, (float)D, (float)D};
    double H = h->fn[TEX_HF_DENSITY] ? scalar_fn(h, TEX_HF_DENSITY, fD, fD, uvw, fw2, q) : D;
    const float fH[3] = {(float)H, (float)H, (float)H};
    double op = h->fn[TEX_HF_OPACITY] ? scalar_fn(h, TEX_HF_OPACITY, fH, fD, uvw, fw2, q) : H;
    out->sigma_t = (h->absorption + h->scattering) * op;
    out->sigma_s = h->scattering * op;
    if (shadow)
        return;
    if (h->fn[TEX_HF_COLOUR])
        colour_fn(h, TEX_HF_COLOUR, fH, fD, uvw, fw2, q, out->colour);
    else
        out->colour[0] = out->colour[1] = out->colour[2] = 1;
    if (h->fn[TEX_HF_EMISSION])
        colour_fn(h, TEX_HF_EMISSION, fH, fD, uvw, fw2, q, out->emission);
    else
        out->emission[0] = out->emission[1] = out->emission[2] = 0;
}
