/* volume.c - ray marching through hypertextures: absorption, emission and single
 * scattering with shadow rays through the volume */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "base/rng.h"
#include "render/hypertexture.h"
#include "render/volume.h"
#include "render/whitted.h"

#define GOLDEN 0.6180339887498949 /* the jitter's sequence from step to step */

/* A hypertexture's span along a ray */
struct span {
    double t0, t1;
    const struct tex_hyper *h;
};

/* The spans of s's hypertextures along o + t d inside (tmin, tmax), sorted by entry, into sp */
static int spans(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d, double tmin,
                 double tmax, struct span *sp)
{
    int n = 0;
    for (int i = 0; i < s->nhypers; i++) {
        double t0, t1;
        if (!tex_hdensity_span(s->hypers[i]->d, o, d, &t0, &t1))
            continue;
        t0 = fmax(t0, tmin), t1 = fmin(t1, tmax);
        if (!(t0 < t1))
            continue;
        int j = n++;
        for (; j > 0 && sp[j - 1].t0 > t0; j--) /* insertion: scenes hold few of them */
            sp[j] = sp[j - 1];
        sp[j] = (struct span){t0, t1, s->hypers[i]};
    }
    return n;
}

/* The spans from i on that overlap sp[i]'s, merged into [*t0, *t1]: returns the first after */
static int group(const struct span *sp, int n, int i, double *t0, double *t1)
{
    *t0 = sp[i].t0, *t1 = sp[i].t1;
    for (i++; i < n && sp[i].t0 <= *t1; i++)
        *t1 = fmax(*t1, sp[i].t1);
    return i;
}

/* The samples of the hypertextures of sp[i..j) whose spans hold t, summed: extinction,
 * scattering and emission added, colours weighted by each one's scattering, and the phase
 * (*g) of the one that scatters most */
static void sample(const struct span *sp, int i, int j, double t, const tex_v3 *P, double fw2,
                   int shadow, struct tex_hyper_sample *v, double *g)
{
    memset(v, 0, sizeof *v);
    *g = 0;
    for (; i < j; i++) {
        if (t < sp[i].t0 || t > sp[i].t1)
            continue;
        struct tex_hyper_sample x;
        tex_hyper_at(sp[i].h, P, fw2, shadow, &x);
        v->sigma_t += x.sigma_t;
        if (shadow)
            continue;
        for (int k = 0; k < 3; k++) { /* colour carries sigma_s: divided out below */
            v->colour[k] += (float)(x.sigma_s * x.colour[k]);
            v->emission[k] += x.emission[k];
        }
        if (x.sigma_s > v->sigma_s) /* the phase of the most scattering one */
            *g = sp[i].h->phase;
        v->sigma_s += x.sigma_s;
    }
}

/* The longest step of sp[i..j) and the smallest tolerance */
static void steps(const struct span *sp, int i, int j, int shadow, double *step, double *tol)
{
    *step = INFINITY, *tol = INFINITY;
    for (; i < j; i++) {
        *step = fmin(*step, shadow ? sp[i].h->shadow_step : sp[i].h->step);
        *tol = fmin(*tol, sp[i].h->tolerance);
    }
}

double tex_volume_transmit(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                           double dist)
{
    struct span sp[TEX_HYPER_MAX];
    int n = s->nhypers ? spans(s, o, d, 0, dist, sp) : 0;
    double tau = 0;
    for (int i = 0, j; i < n; i = j) {
        double t0, t1, step, tol, g;
        j = group(sp, n, i, &t0, &t1);
        steps(sp, i, j, 1, &step, &tol);
        double dt = fmax(step, (t1 - t0) / TEX_VOLUME_SHADOW_STEPS);
        /* t + dt == t past a double's resolution: nothing left to march */
        for (double t = t0; t < t1 && t + dt > t; t += dt) {
            double h = fmin(dt, t1 - t), tm = t + h / 2;
            tex_v3 P = tex_v3_madd(*o, *d, tm);
            struct tex_hyper_sample v;
            sample(sp, i, j, tm, &P, s->settings.filter ? h * h : 0, 1, &v, &g);
            tau += v.sigma_t * h;
            if (tau > -log(TEX_VOLUME_CUTOFF))
                return 0;
        }
    }
    return exp(-tau);
}

/* Henyey and Greenstein's phase function times pi, of the cosine between the ray and the
 * direction to the light (forward scattering, g > 0, is brightest looking at it) */
static double phase_pi(double g, double cosv)
{
    double den = 1 + g * g - 2 * g * cosv;
    return (1 - g * g) / (4 * den * sqrt(den));
}

/* The light in-scattered at P per unit of sigma_s albedo, from ray direction d: the lights'
 * through their shadow rays, and the ambient share amb of Ia, into S */
static void in_scatter(const struct tex_render_ctx *c, const tex_v3 *P, const tex_v3 *d,
                       double g, double amb, tex_colour *S)
{
    const struct tex_scene *s = c->s;
    int n = c->n;
    tex_colour_scale(S, n, c->ambient, (float)amb);
    for (int li = 0; li < s->nlights; li++) {
        const struct tex_light *l = &s->lights[li];
        for (int k = 0, ns = tex_light_samples(l); k < ns; k++) {
            struct tex_light_ahead a;
            tex_light_ahead_at(l, k, 0.5, 0.5, P, &a); /* cell centres: no rng drawn */
            if (!a.ok)
                continue;
            double tr = tex_scene_transmit(s, P, &a.L, 0, a.dist, NULL);
            if (tr > 0)
                tr *= tex_volume_transmit(s, P, &a.L, a.dist);
            if (tr > 0)
                tex_colour_madd(S, n, &l->e,
                                (float)(a.fatt * tr * phase_pi(g, tex_v3_dot(a.L, *d))));
        }
    }
}

/* RGB into the scene's colour space */
static void to_scene(const struct tex_scene *s, const float rgb[3], enum tex_spectrum_kind kind,
                     tex_colour *out)
{
    if (s->cs.mode == TEX_COLOUR_RGB)
        out->v[0] = rgb[0], out->v[1] = rgb[1], out->v[2] = rgb[2];
    else
        s->cs.from_rgb(&s->cs, rgb, kind, out);
}

/* The jitter of ray r: a hash of its origin and direction, in [0, 1) */
static double ray_hash(const tex_ray *r)
{
    uint64_t b[6], h = 0;
    memcpy(b, &r->o, 3 * sizeof(double));
    memcpy(b + 3, &r->d, 3 * sizeof(double));
    for (int i = 0; i < 6; i++)
        h = tex_hash64(h ^ b[i]);
    return (double)(h >> 11) * (1.0 / 9007199254740992.0);
}

/* One group of spans sp[i..j), t0..t1, marched into L; T the transmittance, updated */
static void march(const struct tex_render_ctx *c, const tex_ray *r, const struct span *sp, int i,
                  int j, double t0, double t1, double *T, tex_colour *L)
{
    const struct tex_scene *s = c->s;
    int n = c->n;
    double step, tol, g, u = ray_hash(r), jit = sp[i].h->jitter, amb = sp[i].h->ambient;
    double sprev = 0, tprev = -INFINITY, dnext = INFINITY, dt;
    steps(sp, i, j, 0, &step, &tol);
    double dmin = (t1 - t0) / TEX_VOLUME_MAX_STEPS;
    for (double t = t0; t < t1 && *T > 0; t += dt) {
        double fp = fabs(r->width + t * r->spread);
        double dmax = fmax(fmax(step, fp), dmin);
        dt = fmin(fmax(fmin(dmax, fmax(dnext, dmax / 16)), dmin), t1 - t);
        if (!(t + dt > t)) /* past a double's resolution: nothing left to march */
            break;
        u += GOLDEN;
        u -= floor(u);
        double tm = t + dt * (0.5 + jit * (u - 0.5));
        tex_v3 P = tex_v3_madd(r->o, r->d, tm);
        struct tex_hyper_sample v;
        sample(sp, i, j, tm, &P, s->settings.filter ? fp * fp : 0, 0, &v, &g);
        if (tm > tprev) { /* the next step from the extinction's slope since the last sample */
            double grad = fabs(v.sigma_t - sprev) / (tm - tprev);
            dnext = grad > 0 ? sqrt(tol / grad) : INFINITY;
        }
        sprev = v.sigma_t, tprev = tm;
        int glows = v.emission[0] > 0 || v.emission[1] > 0 || v.emission[2] > 0;
        if (!(v.sigma_t > 0) && !glows)
            continue;
        double tau = v.sigma_t * dt;
        /* the share of a step's source that leaves it: (1 - e^-tau) / sigma_t */
        float w = (float)(*T * (v.sigma_t > 1e-12 ? -expm1(-tau) / v.sigma_t : dt));
        tex_colour e;
        if (glows) {
            to_scene(s, v.emission, TEX_SPECTRUM_ILLUMINANT, &e);
            tex_colour_madd(L, n, &e, w);
        }
        if (v.sigma_s > 0) {
            tex_colour S, a;
            float alb[3];
            for (int k = 0; k < 3; k++)
                alb[k] = (float)(v.colour[k] / v.sigma_s);
            to_scene(s, alb, TEX_SPECTRUM_REFLECTANCE, &a);
            in_scatter(c, &P, &r->d, g, amb, &S);
            tex_colour_mul(&S, n, &S, &a);
            tex_colour_madd(L, n, &S, (float)(w * v.sigma_s));
        }
        *T *= exp(-tau);
        if (*T < TEX_VOLUME_CUTOFF)
            *T = 0;
    }
}

double tex_volume_march(const struct tex_render_ctx *c, const tex_ray *r, double tmax,
                        tex_colour *L)
{
    const struct tex_scene *s = c->s;
    struct span sp[TEX_HYPER_MAX];
    double T = 1;
    tex_colour_set(L, c->n, 0);
    int n = spans(s, &r->o, &r->d, 0, tmax, sp);
    for (int i = 0, j; i < n && T > 0; i = j) {
        double t0, t1;
        j = group(sp, n, i, &t0, &t1);
        march(c, r, sp, i, j, t0, t1, &T, L);
    }
    return T;
}
