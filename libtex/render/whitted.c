/* whitted.c - Whitted's recursion: ambient, direct light, reflection and refraction */
#include <math.h>

#include "render/volume.h"
#include "render/whitted.h"
#include "render/x86/light_x86.h"

/* The surface's largest normal curvature at P (unit facing normal Nf, unit
 * ray direction d): > 0 where it bulges towards the ray (a convex mirror
 * spreads a beam), < 0 where it is hollow, from the shape's own normals a
 * short step away along two tangents; the step along the ray's projection
 * is stretched by 1/cos, as the footprint is. */
static double curvature(const struct tex_hit *h, tex_v3 P, tex_v3 Nf, tex_v3 d)
{
    const struct tex_object *l = h->leaf;
    double cosd = tex_maxd(fabs(tex_v3_dot(d, Nf)), 0.02);
    if (l->fast == 1) /* planes are flat */
        return 0;
    if (l->fast == 2) /* round spheres: 1/r both ways, convex where Nf points outwards */
        return (tex_v3_dot(Nf, tex_v3_sub(P, l->fn)) > 0 ? l->fr : -l->fr) / cosd;
    tex_v3 t1 = tex_v3_sub(d, tex_v3_scale(Nf, tex_v3_dot(d, Nf)));
    if (tex_v3_len(t1) < 1e-9)
        t1 = tex_v3_cross(Nf, fabs(Nf.x) < 0.9 ? tex_v3_make(1, 0, 0) : tex_v3_make(0, 1, 0));
    t1 = tex_v3_norm(t1);
    tex_v3 t2 = tex_v3_cross(Nf, t1);
    double e = 1e-4 * (1 + tex_maxd(fabs(P.x), tex_maxd(fabs(P.y), fabs(P.z))));
    double k[2];
    for (int i = 0; i < 2; i++) {
        tex_v3 t = i ? t2 : t1, n = tex_hit_normal(h, tex_v3_madd(P, t, e));
        if (tex_v3_dot(n, Nf) < 0)
            n = tex_v3_scale(n, -1);
        k[i] = tex_v3_dot(tex_v3_sub(n, Nf), t) / e;
    }
    k[0] /= cosd;
    return fabs(k[0]) > fabs(k[1]) ? k[0] : k[1];
}

/* One light sample of irradiance E from L through m's shading model (dull: Phong's,
 * tex_phong_direct_dull's). */
static inline void shade_direct(const struct tex_material *m, const tex_v3 *N, const tex_v3 *V,
                                const tex_v3 *L, const tex_colour *E, int n, int dull,
                                tex_colour *out)
{
    if (m->model == &tex_shading_phong) /* inline: no call for the common model */
        tex_phong_direct_dull(m, &N->x, &V->x, &L->x, E, n, dull, out);
    else
        m->model->direct(m, &N->x, &V->x, &L->x, E, n, out);
}

static inline const struct tex_light_ahead *first_light(const struct tex_scene *s, const tex_v3 *P,
                                                    struct tex_light_ahead *a)
{
    const struct tex_light *l = s->lights;
    if (!s->nlights || (l->kind != TEX_LIGHT_POINT && l->kind != TEX_LIGHT_SPOT))
        return NULL;
    tex_light_ahead_at(l, 0, 0.5, 0.5, P, a);
    return a;
}

/* Light sample k of light li at the hit of frame f into a (an area light's jitter drawn
 * from c's rng; a0: the first light's, made ahead), ok where it lights the surface from
 * above both normals, its shadow ray yet to be traced */
static inline __attribute__((always_inline)) void light_at(const struct tex_render_ctx *c, const struct tex_hit_frame *f,
                            const struct tex_light_ahead *a0, int li, int k,
                            struct tex_light_ahead *a)
{
    const struct tex_light *l = &c->s->lights[li];
    double jx = 0.5, jy = 0.5;
    if (l->kind == TEX_LIGHT_AREA) {
        jx = tex_rng_uniform(c->rng);
        jy = tex_rng_uniform(c->rng);
    }
    if (!li && a0)
        *a = *a0;
    else
        tex_light_ahead_at(l, k, jx, jy, f->P, a);
    a->ok = a->ok && !(tex_v3_dot(a->L, *f->N) <= 0 || tex_v3_dot(a->L, *f->Ngv) <= 0);
}

/* Light sample a of light l, its shadow ray traced (tex_light_pass), through m's shading
 * model into out (dull: direct_light's) */
static inline __attribute__((always_inline)) void light_shade(const struct tex_render_ctx *c, const struct tex_material *m,
                               const struct tex_hit_frame *f, const struct tex_light *l,
                               const struct tex_light_ahead *a, int dull, tex_colour *out)
{
    int n = c->n;
    const tex_v3 *N = f->N, *V = f->V;
    tex_colour E;
    tex_colour_scale(&E, n, &l->e, (float)a->fatt);
    if (!m->blend_m) {
        shade_direct(m, N, V, &a->L, &E, n, dull, out);
    } else { /* a mixture of two surfaces: each one's light, weighted */
        tex_colour ca, cb;
        tex_colour_set(&ca, n, 0);
        tex_colour_set(&cb, n, 0);
        shade_direct(m, N, V, &a->L, &E, n, 0, &ca);
        shade_direct(m->blend_m, N, V, &a->L, &E, n, 0, &cb);
        for (int i = 0; i < n; i++)
            out->v[i] += (1 - m->blend) * ca.v[i] + m->blend * cb.v[i];
    }
}

#ifdef TEX_X86
/* light_at's samples of area light l (ns of them, tex_light_area_lanes) into lit, four at a
 * time in lanes, their jitters drawn first in light_at's order; returns how many were made
 * (a multiple of 4: light_at makes the rest, after them, drawing on) */
static int area_lanes(const struct tex_render_ctx *c, const struct tex_hit_frame *f,
                      const struct tex_light *l, int ns, struct tex_light_ahead *lit)
{
    enum { MAX = 64 };
    double jx[MAX], jy[MAX];
    int m = (ns < MAX ? ns : MAX) & ~3;
    for (int k = 0; k < m; k++) {
        jx[k] = tex_rng_uniform(c->rng);
        jy[k] = tex_rng_uniform(c->rng);
    }
    for (int k = 0; k < m; k += 4)
        tex_light_area4_avx2(l, k, jx + k, jy + k, f->P, lit + k);
    for (int k = 0; k < m; k++) /* light_at's tests */
        lit[k].ok = lit[k].ok && !(tex_v3_dot(lit[k].L, *f->N) <= 0 ||
                                   tex_v3_dot(lit[k].L, *f->Ngv) <= 0);
    return m;
}
#endif

int tex_light_rays(const struct tex_render_ctx *c, const struct tex_shading *sh,
                   struct tex_light_ahead *lit)
{
    const struct tex_scene *s = c->s;
    int j = 0;
    for (int li = 0; li < s->nlights; li++) {
        int k = 0, ns = tex_light_samples(&s->lights[li]);
#ifdef TEX_X86
        if (ns >= 4 && (li || !sh->a0) && tex_light_area_lanes(&s->lights[li]) &&
            tex_simd_level() >= TEX_SIMD_AVX2)
            k = area_lanes(c, &sh->f, &s->lights[li], ns, lit + j);
#endif
        for (; k < ns; k++)
            light_at(c, &sh->f, sh->a0, li, k, &lit[j + k]);
        j += ns;
    }
    return j;
}

/* Direct lighting: every light sample that reaches P unshadowed, through the surface's
 * shading model (pbrt's SampleLd); a0: the first light's, made ahead.  lit: the samples
 * made and their shadow rays traced (tex_light_rays), else NULL: made here, each shadow
 * ray traced on its own. */
static inline __attribute__((always_inline)) void direct_light(const struct tex_render_ctx *c, const struct tex_material *m,
                         const struct tex_hit_frame *f, const struct tex_light_ahead *a0,
                         const struct tex_light_ahead *lit, tex_colour *out)
{
    const struct tex_scene *s = c->s;
    /* a Phong surface without highlights: its Ks and out's zeros tested once, not at
     * each of the samples (16 an area light) */
    int dull = m->model == &tex_shading_phong && !m->blend_m && tex_colour_zero(&m->ks, c->n) &&
               tex_colour_no_negative_zero(out, c->n);
    for (int li = 0; li < s->nlights; li++) {
        const struct tex_light *l = &s->lights[li];
        int ns = tex_light_samples(l);
        for (int k = 0; k < ns; k++) {
            struct tex_light_ahead own;
            const struct tex_light_ahead *a = lit ? lit++ : &own;
            if (!lit) {
                light_at(c, f, a0, li, k, &own);
                if (own.ok) {
                    double tr = tex_scene_transmit(s, f->Pout, &own.L, 0, own.dist, f->outside);
                    if (tr > 0 && s->nhypers) /* and through the hypertextures */
                        tr *= tex_volume_transmit(s, f->Pout, &own.L, own.dist);
                    tex_light_pass(&own, tr);
                }
            }
            if (a->ok)
                light_shade(c, m, f, l, a, dull, out);
        }
    }
}

/* The refracted ray from n1 into n2, weighted by kt: 0 at total internal
 * reflection.  A refracting surface of curvature kc bends the beam by
 * (eta cos_i - cos_t) kc w (paraxial lens power). */
static int refraction(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_hit_frame *f,
                      const struct tex_media *beyond, double n1, double n2, double kc, int depth,
                      double w, const tex_colour *kt, tex_colour *out)
{
    tex_ray rt = {*f->Pin, r->d, f->width, r->spread, beyond, f->dist};
    tex_colour I;
    if (!tex_refract(r->d, *f->N, n1, n2, &rt.d))
        return 0;
    if (w >= c->s->settings.bailout) {
        double eta = n1 / n2, ci = fabs(tex_v3_dot(r->d, *f->Ngv)), ct = fabs(tex_v3_dot(rt.d, *f->Ngv));
        if (ct > 1e-3)
            rt.spread = tex_mind(eta * ci / ct * r->spread + (eta * ci - ct) * kc * f->width, 1);
        tex_trace(c, &rt, NULL, depth + 1, w, &I);
        tex_colour_mmadd(out, c->n, kt, &I, 1);
    }
    return 1;
}

/* Reflection and refraction (Whitted's kr Ir + kt It).  The media on both
 * sides (nested solids) give Fresnel the solid's index relative to what lies
 * beyond it; an opaque Phong mirror needs neither. */
static inline __attribute__((always_inline)) void secondary(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_hit_frame *f,
                      struct tex_material *m, int depth, double weight, tex_colour *out)
{
    const struct tex_scene *s = c->s;
    int n = c->n;
    tex_colour kr, kt, I;
    double cosi = tex_v3_dot(*f->N, *f->V);
    struct tex_media beyond;
    double n1 = 1, n2 = 1;
    if (m->kt > 0 || m->model != &tex_shading_phong) {
        tex_media_cross(r->media, tex_object_top(f->h->leaf), f->entering,
                        m->ior, &beyond, &n1, &n2);
        m->ior = f->entering ? n2 / n1 : n1 / n2;
    }
    m->model->weights(m, cosi, n, &kr, &kt);
    if (m->blend_m) { /* the two surfaces' weights, mixed */
        tex_colour kr1, kt1;
        m->blend_m->model->weights(m->blend_m, cosi, n, &kr1, &kt1);
        for (int i = 0; i < n; i++) {
            kr.v[i] = (1 - m->blend) * kr.v[i] + m->blend * kr1.v[i];
            kt.v[i] = (1 - m->blend) * kt.v[i] + m->blend * kt1.v[i];
        }
    }
    tex_ray rr = {*f->Pout, tex_reflect(r->d, *f->N), f->width, r->spread, r->media, f->dist};
    if (tex_v3_dot(rr.d, *f->Ngv) <= 0)
        rr.d = tex_reflect(r->d, *f->Ngv);
    /* footprints after curved surfaces: a mirror of curvature k turns a beam
     * of width w by 2 k w more (its focal length is 1/2k) */
    double kr_max = tex_colour_max(&kr, n), kt_max = tex_colour_max(&kt, n);
    double kmax = tex_maxd(kr_max, kt_max);
    double kc = s->settings.filter && f->width > 0 && kmax > 0 && weight * kmax >= s->settings.bailout
                    ? curvature(f->h, *f->P, *f->Ngv, r->d)
                    : 0;
    rr.spread = tex_mind(r->spread + 2 * kc * f->width, 1);
    if (kt_max > 0 &&
        !refraction(c, r, f, &beyond, n1, n2, kc, depth, weight * kt_max, &kt, out)) {
        tex_colour_add(&kr, n, &kr, &kt); /* total internal reflection */
        kr_max = tex_colour_max(&kr, n);
    }
    double wr = weight * kr_max;
    if (wr > 0 && wr >= s->settings.bailout) {
        tex_trace(c, &rr, tex_v3_dot(rr.d, *f->Ngv) > 0 ? f->outside : NULL, depth + 1, wr, &I);
        tex_colour_mmadd(out, n, &kr, &I, 1);
    }
}

/* Does the material send rays on?  An opaque Phong mirror of Kr 0 does not. */
static inline int reflects(const struct tex_material *m)
{
    return !(m->kr <= 0 && m->kt <= 0 && m->model == &tex_shading_phong);
}

/* What a ray that meets nothing sees: the background or the environment map. */
void tex_miss(const struct tex_render_ctx *c, const tex_ray *r, tex_colour *out)
{
    const struct tex_scene *s = c->s;
    if (!s->env.map) {
        tex_colour_copy(out, c->n, c->background);
        return;
    }
    float rgb[3];
    tex_environment_eval(&s->env, &r->d, s->settings.filter ? r->spread : 0, rgb);
    if (s->cs.mode == TEX_COLOUR_RGB)
        out->v[0] = rgb[0], out->v[1] = rgb[1], out->v[2] = rgb[2];
    else
        s->cs.from_rgb(&s->cs, rgb, TEX_SPECTRUM_ILLUMINANT, out);
}

/* tex_shade_begin's and tex_shade_end's work, inlined into tex_shade whole: its state
 * stays in registers and one frame, as it did before the packets' batches split it */
static inline __attribute__((always_inline)) void shade_begin(
    const struct tex_render_ctx *c, const tex_ray *r, const struct tex_hit *hp, tex_v3 P,
    tex_v3 Ng, const struct tex_prefetch *pre, int depth, struct tex_shading *sh)
{
    const struct tex_scene *s = c->s;
    sh->h = *hp;
    sh->P = P;
    int entering = tex_v3_dot(r->d, Ng) < 0;
    sh->N = entering ? Ng : tex_v3_scale(Ng, -1);
    double width = fabs(r->width + sh->h.t * r->spread); /* a focused beam crosses 0 */
    struct tex_shade_at at = {sh->h.leaf, &sh->P, &r->d, width, r->dist + sh->h.t, depth, pre};
    sh->a0 = first_light(s, &sh->P, &sh->la);
    tex_v3 Nf = sh->N; /* the normal facing the ray, before bump */
    tex_resolve_material(s, tex_surface_of(s, sh->h.leaf), &at, &sh->N, sh->m);
    if (sh->m[0].disp != 0) { /* P as a target: the light is shaded at the moved point */
        sh->P = tex_v3_madd(P, Nf, sh->m[0].disp);
        sh->a0 = first_light(s, &sh->P, &sh->la);
    }
    sh->V = tex_v3_scale(r->d, -1);
    double e = tex_eps_at(P);
    /* offset along the geometric normal so bumped normals cannot start rays inside */
    sh->Ngv = entering ? Ng : tex_v3_scale(Ng, -1);
    sh->Pout = tex_v3_madd(P, sh->Ngv, e), sh->Pin = tex_v3_madd(P, sh->Ngv, -e);
    /* rays leaving a hull leaf from outside, away from its surface, skip its object */
    const struct tex_object *outside =
        entering && sh->h.leaf->hull ? tex_object_top(sh->h.leaf) : NULL;
    sh->f = (struct tex_hit_frame){&sh->h, &sh->P, &sh->N,    &sh->Ngv, &sh->V,  &sh->Pout,
                                   &sh->Pin, width,  at.dist, entering, outside};
}

static inline __attribute__((always_inline)) void shade_end(
    const struct tex_render_ctx *c, const tex_ray *r, struct tex_shading *sh,
    const struct tex_light_ahead *lit, int depth, double weight, tex_colour *out)
{
    struct tex_material *m = sh->m;
    tex_colour_mul(out, c->n, c->ambient, &m->ka);
    direct_light(c, m, &sh->f, sh->a0, lit, out);
    if (depth < c->s->settings.depth && (reflects(&m[0]) || (m->blend_m && reflects(&m[1]))))
        secondary(c, r, &sh->f, m, depth, weight, out);
}

void tex_shade_begin(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_hit *hp,
                     tex_v3 P, tex_v3 Ng, const struct tex_prefetch *pre, int depth,
                     struct tex_shading *sh)
{
    shade_begin(c, r, hp, P, Ng, pre, depth, sh);
}

void tex_shade_end(const struct tex_render_ctx *c, const tex_ray *r, struct tex_shading *sh,
                   const struct tex_light_ahead *lit, int depth, double weight, tex_colour *out)
{
    shade_end(c, r, sh, lit, depth, weight, out);
}

/* Whitted's recursion from ray r's hit h at P, of normal Ng (hit_normal's): ambient,
 * direct light, then reflection and refraction (pre: the hit's lookups done ahead with its
 * packet, or NULL).  weight: the largest share of the pixel this ray can carry (1 for eye
 * rays); rays below the scene's bailout are not traced. */
void tex_shade(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_hit *hp, tex_v3 P,
                  tex_v3 Ng, const struct tex_prefetch *pre, int depth, double weight,
                  tex_colour *out)
{
    struct tex_shading sh;
    shade_begin(c, r, hp, P, Ng, pre, depth, &sh);
    shade_end(c, r, &sh, NULL, depth, weight, out);
}

/* The colour ray r brings back; from: tex_scene_trace's */
void tex_trace(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_object *from,
                  int depth, double weight, tex_colour *out)
{
    struct tex_hit h;
    int hit = tex_scene_trace(c->s, &r->o, &r->d, 0, INFINITY, from, &h);
    tex_colour Lv; /* the hypertextures before the hit: their light and transmittance T */
    double T = c->s->nhypers ? tex_volume_march(c, r, hit ? h.t : INFINITY, &Lv) : 1;
    if (!(T > 0)) {
        tex_colour_copy(out, c->n, &Lv);
        return;
    }
    if (!hit)
        tex_miss(c, r, out);
    else {
        tex_v3 P = tex_v3_madd(r->o, r->d, h.t);
        tex_shade(c, r, &h, P, tex_hit_normal(&h, P), NULL, depth, weight * T, out);
    }
    if (c->s->nhypers)
        TEX_COLOUR_EACH(c->n, out, out->v[i] * (float)T + Lv.v[i]);
}
