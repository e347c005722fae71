/* render_ct.c - the Cook-Torrance shading model */
#include "render/render_ct.h"

#include "render/colour_spectral.h"
#include "base/error.h"
#include "render/fresnel.h"
#include "render/x86/render_ct_x86.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int tex_ct_init(struct tex_ct *ct, const struct tex_colour_space *cs,
                const struct tex_matdb_entry *entry, enum tex_facet_dist dist, double m,
                double ns, double s)
{
    memset(ct, 0, sizeof *ct);
    if (dist == TEX_FACET_BECKMANN && !(m > 0 && m <= 2))
        return tex_usage_error("Beckmann slope m = %g outside (0, 2]", m);
    if (dist == TEX_FACET_BLINN && !(ns >= 0 && ns <= 1e5))
        return tex_usage_error("Blinn exponent Ns = %g outside [0, 100000]", ns);
    if (!(s >= 0 && s <= 1))
        return tex_usage_error("specular fraction s = %g outside [0, 1]", s);
    ct->facets.dist = dist;
    ct->facets.m = m;
    ct->facets.ns = ns;
    ct->s = s;
    ct->entry = entry;
    tex_ct_set_space(ct, cs);
    return 0;
}

void tex_ct_set_space(struct tex_ct *ct, const struct tex_colour_space *cs)
{
    const struct tex_matdb_entry *entry = ct->entry;
    ct->has_eta = entry != NULL;
    ct->conductor = entry && entry->kind == TEX_CONDUCTOR;
    ct->flat = 0;
    if (entry) {
        tex_colour_space_curve(cs, &entry->n, &ct->eta);
        tex_colour_space_curve(cs, &entry->k, &ct->k);
        ct->flat = !ct->conductor;
        for (int i = 1; i < cs->n; i++)
            ct->flat &= ct->eta.v[i] == ct->eta.v[0];
    }
}

/* A surface that names the model but sets none of its parameters: a dielectric of the
 * surface's ior, Beckmann's m and s at the model's defaults. */
static const struct tex_ct ct_default = {
    {TEX_FACET_BECKMANN, TEX_CT_M, 0}, TEX_CT_S, 0, 0, {{0}}, {{0}}, NULL, 0, NULL, 0, 0};

static const struct tex_ct *params(const struct tex_material *mat)
{
    return mat->model_data ? mat->model_data : &ct_default;
}

void tex_ct_material(struct tex_material *m, const struct tex_ct *ct)
{
    const struct tex_ct *c = ct ? ct : &ct_default;
    m->model = &tex_shading_cook_torrance;
    m->model_data = ct;
    m->m = c->facets.m;
    m->s = c->s;
}

/* The two spectrum loops below are the hottest shading steps of a spectral scene (per
 * hit, per light, per band): on x86 they run four bands at a time (x86/render_ct_x86.c),
 * the same results. */

/* tex_fresnel_conductor (fresnel.h, eta_i = 1) in single precision for a whole
 * spectrum at once: the same exact formula without a call per sample. */
static void fresnel_conductor_n(double cos_i, const float *n, const float *k, int count,
                                float *out)
{
#if defined(TEX_X86) && defined(__SSE2__)
    tex_fresnel_conductor_n_sse2(cos_i, n, k, count, out);
    return;
#endif
    float c = (float)(cos_i < 0 ? 0 : cos_i > 1 ? 1 : cos_i);
    float c2 = c * c, s2 = 1 - c2;
    for (int i = 0; i < count; i++) {
        float e2 = n[i] * n[i], k2 = k[i] * k[i];
        float t0 = e2 - k2 - s2;
        float a2b2 = sqrtf(t0 * t0 + 4 * e2 * k2);
        float h = 0.5f * (a2b2 + t0);
        float a = sqrtf(h > 0 ? h : 0);
        float t1 = a2b2 + c2, t2 = 2 * a * c;
        float rs = (t1 - t2) / (t1 + t2);
        float t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
        float rp = rs * (t3 - t4) / (t3 + t4);
        float f = 0.5f * (rs + rp);
        out[i] = f < 0 ? 0 : f > 1 ? 1 : f;
    }
}

/* tex_fresnel_dielectric (fresnel.h) in single precision for a whole spectrum:
 * r[i] = eta_i / eta_t per sample, c = cos of the angle of incidence. */
static void fresnel_dielectric_n(float c, const float *r, int count, float *out)
{
#if defined(TEX_X86) && defined(__SSE2__)
    tex_fresnel_dielectric_n_sse2(c, r, count, out);
    return;
#endif
    float s2 = 1 - c * c;
    for (int i = 0; i < count; i++) {
        float st2 = r[i] * r[i] * s2;
        float ct = sqrtf(st2 < 1 ? 1 - st2 : 0);
        float rc = r[i] * c, rct = r[i] * ct;
        float rpar = (c - rct) / (c + rct), rperp = (rc - ct) / (rc + ct);
        float f = 0.5f * (rpar * rpar + rperp * rperp);
        f = f < 0 ? 0 : f > 1 ? 1 : f;
        out[i] = st2 >= 1 ? 1 : f; /* total internal reflection */
    }
}

/* The dispersive dielectric's ratios eta_i / eta_t per sample, seen from
 * outside (cos_i >= 0) or from inside. */
static void dielectric_ratios(const struct tex_ct *ct, int outside, int n, float *r)
{
    if (outside) {
#pragma omp simd
        for (int i = 0; i < n; i++)
            r[i] = 1 / ct->eta.v[i];
    } else {
        for (int i = 0; i < n; i++)
            r[i] = ct->eta.v[i];
    }
}

int tex_ct_tabulate(struct tex_ct *ct, int n)
{
    tex_ct_untabulate(ct);
    if (!ct->has_eta)
        return 0; /* the surface's ior, which a texture may change per hit */
    int cols = ct->flat ? 1 : n; /* one index: one column for every sample */
    if (!(ct->table = malloc(sizeof *ct->table * (TEX_CT_STEPS + 1) * cols)))
        return tex_error("out of memory");
    ct->table_n = n;
    ct->table_cols = cols;
    float r[TEX_COLOUR_MAX];
    if (!ct->conductor)
        dielectric_ratios(ct, 1, n, r);
    for (int j = 0; j <= TEX_CT_STEPS; j++) {
        double c = (double)j / TEX_CT_STEPS;
        float *row = ct->table + j * cols;
        if (ct->conductor)
            fresnel_conductor_n(c, ct->eta.v, ct->k.v, n, row);
        else if (ct->flat)
            row[0] = (float)tex_fresnel_dielectric(c, 1, ct->eta.v[0], NULL);
        else
            fresnel_dielectric_n((float)c, r, n, row);
    }
    return 0;
}

void tex_ct_untabulate(struct tex_ct *ct)
{
    free(ct->table);
    ct->table = NULL;
    ct->table_n = ct->table_cols = 0;
}

/* Fresnel reflectance per sample at cos_i (< 0: from inside). */
static void fresnel(const struct tex_material *mat, const struct tex_ct *ct, double cos_i,
                    int n, tex_colour *fr)
{
    /* the table, but not inside a dielectric: beyond the critical angle the
     * curve has a corner that steps cannot follow */
    if (ct->table && ct->table_n == n && (ct->conductor || cos_i >= 0)) {
        double x = (cos_i < 0 ? -cos_i : cos_i) * TEX_CT_STEPS;
        x = x < TEX_CT_STEPS ? x : TEX_CT_STEPS; /* NaN too */
        int j = (int)x, cols = ct->table_cols;
        j = j < TEX_CT_STEPS ? j : TEX_CT_STEPS - 1;
        float a = (float)(x - j);
        const float *f0 = ct->table + j * cols, *f1 = f0 + cols;
        if (cols == 1) {
            tex_colour_set(fr, n, f0[0] + a * (f1[0] - f0[0]));
            return;
        }
        TEX_COLOUR_EACH(n, fr, f0[i] + a * (f1[i] - f0[i]));
        return;
    }
    if (ct->conductor) {
        fresnel_conductor_n(fabs(cos_i), ct->eta.v, ct->k.v, n, fr->v);
        return;
    }
    if (!ct->has_eta || ct->flat) { /* one index: one evaluation for every sample */
        double eta = ct->has_eta ? ct->eta.v[0] : mat->ior;
        double f = cos_i >= 0 ? tex_fresnel_dielectric(cos_i, 1, eta, NULL)
                              : tex_fresnel_dielectric(-cos_i, eta, 1, NULL);
        tex_colour_set(fr, n, (float)f);
        return;
    }
    float r[TEX_COLOUR_MAX];
    double c = cos_i >= 0 ? cos_i : -cos_i;
    dielectric_ratios(ct, cos_i >= 0, n, r);
    fresnel_dielectric_n((float)(c > 1 ? 1 : c), r, n, fr->v);
}

void tex_ct_fresnel(const struct tex_material *mat, double cos_i, int n, tex_colour *fr)
{
    fresnel(mat, params(mat), cos_i, n, fr);
}

/* Whether the highlight's weight w = s pi D G / (4 (N.V)) of a Beckmann lobe is surely
 * under cut, found without D's exp (a third of five_spheres' highlights in 16 bands):
 * G <= 2 (N.H)(N.V) / (V.H) gives w <= s exp(e) / (2 m^2 c^3 (V.H)), and exp(e) <= 2^k / 2
 * with k the next whole number up from e log2(e), plus one.  Four times under cut: far
 * beyond the roundings, so the computed w is under it too. */
static int highlight_below(const struct tex_facets *fc, double c, double vh, double s,
                           double cut)
{
    if (fc->dist != TEX_FACET_BECKMANN || !(c > 0 && fc->m > 0 && vh > 0))
        return 0;
    double c2 = c * c, m2 = fc->m * fc->m, e = (c2 - 1) / (c2 * m2);
    if (!(e < -20)) /* NaN too */
        return 0;
    double t = e * M_LOG2E;
    int k = t < -1000 ? -1000 : (int)t + 1; /* (int) rounds toward zero: up */
    union {
        uint64_t u;
        double d;
    } p = {(uint64_t)(k + 1023) << 52}; /* 2^k */
    return s * p.d <= cut * m2 * c2 * c * vh;
}

static void ct_direct(const struct tex_material *mat, const double N[3], const double V[3],
                      const double L[3], const tex_colour *E, int n, tex_colour *out)
{
    const struct tex_ct *ct = params(mat);
    double nl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
    double nv = N[0] * V[0] + N[1] * V[1] + N[2] * V[2];
    if (nl <= 0)
        return;
    /* m and s at this hit: the surface's, or its application functions' */
    double s = mat->s;
    struct tex_facets fc = ct->facets;
    fc.m = mat->m;
    tex_colour_mmadd(out, n, &mat->kd, E, (float)((1 - s) * nl));
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    if (hl <= 0 || nv <= 0 || s <= 0)
        return;
    double nh = (N[0] * h[0] + N[1] * h[1] + N[2] * h[2]) / hl;
    double vh = (V[0] * h[0] + V[1] * h[1] + V[2] * h[2]) / hl;
    if (highlight_below(&fc, nh, vh, s, 1e-12))
        return; /* as the test of w below would */
    double g = tex_ct_geometry(&fc, nh, nv, nl, vh);
    double w = s * M_PI * g * nl;
    /* F <= 1: a highlight below 1e-12 of the light (far from H) needs no Fresnel term */
    if (!(w > 1e-12))
        return;
    tex_colour f;
    fresnel(mat, ct, vh, n, &f);
    tex_colour_mmadd(out, n, &f, E, (float)w);
}

static void ct_weights(const struct tex_material *mat, double cosi, int n, tex_colour *kr,
                       tex_colour *kt)
{
    const struct tex_ct *ct = params(mat);
    tex_colour f;
    fresnel(mat, ct, cosi, n, &f);
    float wr = (float)mat->kr, wt = ct->conductor ? 0 : (float)mat->kt;
    TEX_COLOUR_EACH(n, kr, wr * f.v[i]);
    TEX_COLOUR_EACH(n, kt, wt * (1 - f.v[i]));
}

const struct tex_shading_model tex_shading_cook_torrance = {"cook-torrance", ct_direct,
                                                            ct_weights};
