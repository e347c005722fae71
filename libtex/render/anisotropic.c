/* anisotropic.c - Ward's and Ashikhmin-Shirley's anisotropic shading models */
#include "render/anisotropic.h"

#include "render/mapping.h"
#include "render/render_ct.h"
#include "render/shape.h"
#include "render/surface.h"

#include <math.h>

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

int tex_aniso_frame(const double N[3], const double T[3], double t[3])
{
    double d = dot3(N, T), tt = dot3(T, T), x[3];
    for (int k = 0; k < 3; k++)
        x[k] = T[k] - d * N[k];
    double l2 = dot3(x, x);
    /* sin of T's angle to N above 1e-4: below it the part across N is rounding */
    int ok = l2 > 1e-8 * tt && isfinite(l2);
    if (!ok) { /* x, or y where N is near x, across N */
        double a[3] = {fabs(N[0]) < 0.9, fabs(N[0]) >= 0.9, 0};
        d = dot3(N, a);
        for (int k = 0; k < 3; k++)
            x[k] = a[k] - d * N[k];
        l2 = dot3(x, x);
    }
    double s = 1 / sqrt(l2);
    for (int k = 0; k < 3; k++)
        t[k] = x[k] * s;
    return ok;
}

double tex_ward_brdf(const double N[3], const double T[3], const double L[3],
                     const double V[3], double au, double av)
{
    double nl = dot3(N, L), nv = dot3(N, V), B[3];
    if (!(nl > 0 && nv > 0))
        return 0;
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    double hn = dot3(h, N);
    if (!(hn > 0))
        return 0;
    cross3(N, T, B);
    double ht = dot3(h, T) / au, hb = dot3(h, B) / av, hn2 = hn * hn;
    return dot3(h, h) / (M_PI * au * av * hn2 * hn2) * exp(-(ht * ht + hb * hb) / hn2);
}

double tex_as_brdf(const double N[3], const double T[3], const double L[3], const double V[3],
                   double nu, double nv)
{
    double nl = dot3(N, L), nvw = dot3(N, V), B[3];
    if (!(nl > 0 && nvw > 0))
        return 0;
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    double hl = sqrt(dot3(h, h));
    if (!(hl > 0))
        return 0;
    double H[3] = {h[0] / hl, h[1] / hl, h[2] / hl};
    double nh = dot3(N, H), vh = dot3(V, H);
    if (!(nh > 0 && vh > 0))
        return 0;
    cross3(N, T, B);
    /* (H.T)^2 + (H.B)^2 = 1 - (N.H)^2, without its cancellation near H = N */
    double ht = dot3(H, T), hb = dot3(H, B), s2 = ht * ht + hb * hb;
    double e = s2 > 0 ? (nu * ht * ht + nv * hb * hb) / s2 : nu;
    return sqrt((nu + 1) * (nv + 1)) / (8 * M_PI) * pow(nh, e) / (vh * fmax(nl, nvw));
}

double tex_as_exponent(double alpha)
{
    return 2 / (alpha * alpha) - 2;
}

int tex_shading_anisotropic(const struct tex_shading_model *model)
{
    return model == &tex_shading_ward || model == &tex_shading_ashikhmin_shirley;
}

/* The light's specular part: s pi F(V.H) f E (N.L), f = the model's lobe at the hit */
static void specular(const struct tex_material *mat, const double N[3], const double V[3],
                     const double L[3], const tex_colour *E, int n, tex_colour *out, int ward)
{
    double t[3], nl = dot3(N, L);
    if (fabs(dot3(N, mat->T)) < 1e-12) /* the material's, across this N already */
        t[0] = mat->T[0], t[1] = mat->T[1], t[2] = mat->T[2];
    else
        tex_aniso_frame(N, mat->T, t); /* the shading normal's plane */
    double f = ward ? tex_ward_brdf(N, t, L, V, mat->au, mat->av)
                    : tex_as_brdf(N, t, L, V, tex_as_exponent(mat->au),
                                  tex_as_exponent(mat->av));
    double w = mat->s * M_PI * f * nl;
    /* F <= 1: a highlight below 1e-12 of the light needs no Fresnel term (as render_ct.c) */
    if (!(w > 1e-12))
        return;
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    tex_colour F;
    tex_ct_fresnel(mat, dot3(V, h) / sqrt(dot3(h, h)), n, &F);
    tex_colour_mmadd(out, n, &F, E, (float)w);
}

static void ward_direct(const struct tex_material *mat, const double N[3], const double V[3],
                        const double L[3], const tex_colour *E, int n, tex_colour *out)
{
    double nl = dot3(N, L);
    if (nl <= 0)
        return;
    tex_colour_mmadd(out, n, &mat->kd, E, (float)((1 - mat->s) * nl));
    if (mat->s > 0)
        specular(mat, N, V, L, E, n, out, 1);
}

static double pow5(double x)
{
    double x2 = x * x;
    return x2 * x2 * x;
}

static void as_direct(const struct tex_material *mat, const double N[3], const double V[3],
                      const double L[3], const tex_colour *E, int n, tex_colour *out)
{
    double nl = dot3(N, L), nv = dot3(N, V);
    if (nl <= 0)
        return;
    nv = nv > 0 ? nv : 0;
    /* pi f_d (N.L): the diffuse light the specular layer lets through, Rs = s F(1) */
    double c = 28.0 / 23 * (1 - pow5(1 - nl / 2)) * (1 - pow5(1 - nv / 2)) * nl;
    tex_colour f0, d;
    tex_ct_fresnel(mat, 1, n, &f0);
    for (int i = 0; i < n; i++)
        d.v[i] = mat->kd.v[i] * (float)(1 - mat->s * f0.v[i]);
    tex_colour_mmadd(out, n, &d, E, (float)c);
    if (mat->s > 0)
        specular(mat, N, V, L, E, n, out, 0);
}

/* Cook-Torrance's weights: Fresnel's Fr and 1 - Fr per sample (render_ct.h) */
static void aniso_weights(const struct tex_material *m, double cosi, int n, tex_colour *kr,
                          tex_colour *kt)
{
    tex_shading_cook_torrance.weights(m, cosi, n, kr, kt);
}

const struct tex_shading_model tex_shading_ward = {"ward", ward_direct, aniso_weights};
const struct tex_shading_model tex_shading_ashikhmin_shirley = {"ashikhmin-shirley", as_direct,
                                                                aniso_weights};

/* The shape's own mapping's (u, v) and face at P on leaf: 1 where they are numbers */
static int shape_uv(const struct tex_object *leaf, tex_v3 P, double uv[2], int *face)
{
    tex_v3 pl = tex_xform_point(&leaf->to_obj, P);
    *face = tex_shape_methods[leaf->kind].uv(leaf, pl, &uv[0], &uv[1]);
    return isfinite(uv[0]) && isfinite(uv[1]);
}

/* The direction u (along_v: v) of the shape's own mapping grows in at P on leaf: its
 * gradient, in closed form where the mapping has one (mapping.h's map_gradient, the plane's,
 * and tex_point_gradient, the sphere's, box's, cylinder's and cones'), as the footprints
 * take it (placed_derivatives), else by differences along two tangents made from N
 * alone (so the same at a point for any ray), the mapping's Jacobian inverted: dP/du, which
 * the gradient is along on these orthogonal mappings; zero where u does not change. */
static tex_v3 mapping_tangent(const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *N,
                              int along_v)
{
    static const struct tex_apply natural = {.mapping = TEX_MAP_NATURAL, .scale = 1};
    const double h = 1e-4;
    double n[3] = {N->x, N->y, N->z}, zero[3] = {0, 0, 0}, t[2][3], uv0[2], d[2][2];
    int face0, face;
    tex_v3 g[3], pl = tex_xform_point(&leaf->to_obj, *P);
    if (map_gradient(&natural, leaf, g))
        return g[along_v];
    if (!shape_uv(leaf, *P, uv0, &face0))
        return tex_v3_make(0, 0, 0);
    if (tex_point_gradient(&natural, leaf, &pl, face0, g))
        return g[along_v];
    tex_aniso_frame(n, zero, t[0]);
    cross3(n, t[0], t[1]);
    for (int i = 0; i < 2; i++) {
        double uv[2], s = h; /* a step onto another face goes the other way */
        tex_v3 Ti = tex_v3_make(t[i][0], t[i][1], t[i][2]);
        if (!shape_uv(leaf, tex_v3_madd(*P, Ti, s), uv, &face) || face != face0) {
            s = -h;
            if (!shape_uv(leaf, tex_v3_madd(*P, Ti, s), uv, &face) || face != face0)
                return tex_v3_make(0, 0, 0);
        }
        d[i][0] = wrapdiff(uv[0] - uv0[0]) / s;
        d[i][1] = wrapdiff(uv[1] - uv0[1]) / s;
    }
    /* d[i] = (du, dv) along t[i]; (a, b) with du = 1, dv = 0 (u) or du = 0, dv = 1 (v) */
    double det = d[0][0] * d[1][1] - d[1][0] * d[0][1], a, b;
    if (det != 0 && isfinite(det)) {
        a = along_v ? -d[1][0] / det : d[1][1] / det;
        b = along_v ? d[0][0] / det : -d[0][1] / det;
    } else {
        a = d[0][along_v], b = d[1][along_v];
    }
    return tex_v3_make(a * t[0][0] + b * t[1][0], a * t[0][1] + b * t[1][1],
                       a * t[0][2] + b * t[1][2]);
}

void tex_aniso_material(struct tex_material *m, const struct tex_surface *sf,
                        const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *N,
                        const float flow[3], double angle, double au, double av)
{
    tex_v3 T;
    if (flow[0] != 0 || flow[1] != 0 || flow[2] != 0)
        T = tex_v3_make(flow[0], flow[1], flow[2]);
    else if (sf->tangent_from == TEX_TANGENT_FIXED)
        T = sf->tangent;
    else
        T = mapping_tangent(leaf, P, N, sf->tangent_from == TEX_TANGENT_V);
    double n[3] = {N->x, N->y, N->z}, tv[3] = {T.x, T.y, T.z}, t[3];
    tex_aniso_frame(n, tv, t);
    if (angle != 0) { /* about N: t cos a + (N x t) sin a */
        double b[3], a = angle * (M_PI / 180), c = cos(a), s = sin(a);
        cross3(n, t, b);
        for (int k = 0; k < 3; k++)
            t[k] = c * t[k] + s * b[k];
    }
    for (int k = 0; k < 3; k++)
        m->T[k] = t[k];
    m->au = au;
    m->av = av;
}
