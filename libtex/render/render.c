/* render.c - camera, sampling, Whitted recursion, tiles and threads
 *
 * Each pixel draws its sample positions (and area-light jitter) from an
 * RNG seeded by the scene seed and the pixel's index, and pixels are
 * independent, so any thread count gives the same image, and a region of
 * the image the same pixels as the whole render.  Tiles of 16x16
 * pixels are shared among OpenMP threads dynamically.
 *
 * Eye rays go in packets of 8x8 pixels (render_packet): all find their hits,
 * then the primitives evaluated at hit points, and the image maps that
 * surfaces apply first, are evaluated over the packet's hits in one call each
 * (tex_prefetch_eval: a map's footprints and trilinear lookups in vector
 * lanes; a leaf's hits of one planar map on a plane, or of one natural map on a
 * box, cylinder, cone or sphere, in lanes from their points on,
 * tex_prefetch_lanes), then every hit is shaded: those on plain surfaces (Phong
 * without rays of their own, tex_surface_plain) together, light by light
 * (plain_shade), the others one by one.  A point gets the same value in a call
 * of any length, and each pixel draws from its own rng in the same order, so
 * the image is the one pixel-by-pixel tracing makes; TEXTURA_PACKETS=0 in the
 * environment traces pixel by pixel (tests/t_apply_packets.sh compares the
 * two).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/rng.h"
#include "base/simd.h"
#include "render/camera.h"
#include "render/scene.h"

#define TILE 16

struct ctx {
    const struct tex_scene *s;
    int n;                 /* colour samples */
    const tex_colour *ambient, *background;
    tex_rng *rng;
    int need_rng; /* jittered samples or area lights */
    int plain;    /* RGB, point and spot lights alone: plain hits shaded together */
};

static double eps_at(tex_v3 p)
{
    return 1e-6 * (1 + tex_maxd(tex_maxd(fabs(p.x), fabs(p.y)), fabs(p.z)));
}

static const struct tex_surface *surface_of(const struct tex_scene *s, const struct tex_object *leaf)
{
    return leaf->surface ? leaf->surface : s->surfaces[0];
}

/* World normal at a hit, facing outwards of the solid.  Inline: a returned
 * or passed tex_v3 goes through the stack and stalls the load after it. */
static inline __attribute__((always_inline)) tex_v3 hit_normal(const struct tex_hit *h, tex_v3 P)
{
    const struct tex_object *l = h->leaf;
    tex_v3 n;
    if (l->fast == 1) { /* planes and round spheres: no transforms, no square root */
        n = l->fn;
    } else if (l->fast == 2) {
        n = tex_v3_scale(tex_v3_sub(P, l->fn), l->fr);
    } else {
        n = tex_shape_methods[l->kind].normal(l, tex_xform_point(&l->to_obj, P));
        n = tex_v3_norm(tex_xform_normal(&l->to_obj, n));
    }
    return h->flip ? tex_v3_scale(n, -1) : n;
}

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
        tex_v3 t = i ? t2 : t1, n = hit_normal(h, tex_v3_madd(P, t, e));
        if (tex_v3_dot(n, Nf) < 0)
            n = tex_v3_scale(n, -1);
        k[i] = tex_v3_dot(tex_v3_sub(n, Nf), t) / e;
    }
    k[0] /= cosd;
    return fabs(k[0]) > fabs(k[1]) ? k[0] : k[1];
}

/* A hit once its material is resolved: the point, the shading normal N
 * facing the ray (bumped), the geometric normal Ngv on the ray's side, the
 * view direction, the points just outside and inside, the beam's width.
 * Pointers to trace's locals: the frame itself costs no copies. */
struct hit_frame {
    const struct tex_hit *h;
    const tex_v3 *P, *N, *Ngv, *V, *Pout, *Pin;
    double width, dist; /* dist: the path's length from the eye to P */
    int entering;
    const struct tex_object *outside; /* the object hit where rays leaving cannot meet it */
};

static void trace(const struct ctx *c, const tex_ray *r, const struct tex_object *from,
                  int depth, double weight, tex_colour *out);

/* One light sample of irradiance E from L through m's shading model. */
static inline void shade_direct(const struct tex_material *m, const tex_v3 *N, const tex_v3 *V,
                                const tex_v3 *L, const tex_colour *E, int n, tex_colour *out)
{
    if (m->model == &tex_shading_phong) /* inline: no call for the common model */
        tex_phong_direct(m, &N->x, &V->x, &L->x, E, n, out);
    else
        m->model->direct(m, &N->x, &V->x, &L->x, E, n, out);
}

/* A light sample at a hit: its direction, distance and attenuation; ok: it reaches the hit.
 * The first light's, a point or a spot, is made before the material (first_light), so that
 * its square root and division run beside the material's work rather than hold up the
 * shadow ray. */
struct light_ahead {
    tex_v3 L;
    double dist, fatt;
    int ok;
};

/* Light sample k of l at P (jx, jy: an area light's jitter) into a. */
static inline void light_at(const struct tex_light *l, int k, double jx, double jy,
                            const tex_v3 *P, struct light_ahead *a)
{
    if (l->kind == TEX_LIGHT_POINT || l->kind == TEX_LIGHT_SPOT)
        a->ok = tex_light_point_at(l, &l->pos, P, &a->L, &a->dist, &a->fatt) && a->fatt > 0;
    else
        a->ok = tex_light_sample(l, k, jx, jy, *P, &a->L, &a->dist, &a->fatt);
}

static inline const struct light_ahead *first_light(const struct tex_scene *s, const tex_v3 *P,
                                                    struct light_ahead *a)
{
    const struct tex_light *l = s->lights;
    if (!s->nlights || (l->kind != TEX_LIGHT_POINT && l->kind != TEX_LIGHT_SPOT))
        return NULL;
    light_at(l, 0, 0.5, 0.5, P, a);
    return a;
}

/* Direct lighting: every light sample that reaches P unshadowed, through the
 * surface's shading model (pbrt's SampleLd); a0: the first light's, made ahead. */
static void direct_light(const struct ctx *c, const struct tex_material *m,
                         const struct hit_frame *f, const struct light_ahead *a0,
                         tex_colour *out)
{
    const struct tex_scene *s = c->s;
    int n = c->n;
    const tex_v3 *N = f->N, *V = f->V;
    for (int li = 0; li < s->nlights; li++) {
        const struct tex_light *l = &s->lights[li];
        int ns = tex_light_samples(l);
        for (int k = 0; k < ns; k++) {
            double jx = 0.5, jy = 0.5;
            if (l->kind == TEX_LIGHT_AREA) {
                jx = tex_rng_uniform(c->rng);
                jy = tex_rng_uniform(c->rng);
            }
            struct light_ahead own;
            const struct light_ahead *a = !li && a0 ? a0 : &own;
            if (a == &own)
                light_at(l, k, jx, jy, f->P, &own);
            if (!a->ok)
                continue;
            tex_v3 L = a->L;
            double dist = a->dist, fatt = a->fatt;
            if (tex_v3_dot(L, *N) <= 0 || tex_v3_dot(L, *f->Ngv) <= 0)
                continue;
            double sh = tex_scene_transmit(s, f->Pout, &L, 0, dist, f->outside);
            if (sh <= 0)
                continue;
            tex_colour E;
            tex_colour_scale(&E, n, &l->e, (float)(fatt * sh));
            if (!m->blend_m) {
                shade_direct(m, N, V, &L, &E, n, out);
            } else { /* a mixture of two surfaces: each one's light, weighted */
                tex_colour a, b;
                tex_colour_set(&a, n, 0);
                tex_colour_set(&b, n, 0);
                shade_direct(m, N, V, &L, &E, n, &a);
                shade_direct(m->blend_m, N, V, &L, &E, n, &b);
                for (int i = 0; i < n; i++)
                    out->v[i] += (1 - m->blend) * a.v[i] + m->blend * b.v[i];
            }
        }
    }
}

/* The refracted ray from n1 into n2, weighted by kt: 0 at total internal
 * reflection.  A refracting surface of curvature kc bends the beam by
 * (eta cos_i - cos_t) kc w (paraxial lens power). */
static int refraction(const struct ctx *c, const tex_ray *r, const struct hit_frame *f,
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
        trace(c, &rt, NULL, depth + 1, w, &I);
        tex_colour_mmadd(out, c->n, kt, &I, 1);
    }
    return 1;
}

/* Reflection and refraction (Whitted's kr Ir + kt It).  The media on both
 * sides (nested solids) give Fresnel the solid's index relative to what lies
 * beyond it; an opaque Phong mirror needs neither. */
static void secondary(const struct ctx *c, const tex_ray *r, const struct hit_frame *f,
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
        trace(c, &rr, tex_v3_dot(rr.d, *f->Ngv) > 0 ? f->outside : NULL, depth + 1, wr, &I);
        tex_colour_mmadd(out, n, &kr, &I, 1);
    }
}

/* Does the material send rays on?  An opaque Phong mirror of Kr 0 does not. */
static inline int reflects(const struct tex_material *m)
{
    return !(m->kr <= 0 && m->kt <= 0 && m->model == &tex_shading_phong);
}

/* What a ray that meets nothing sees: the background or the environment map. */
static void miss(const struct ctx *c, const tex_ray *r, tex_colour *out)
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

/* Whitted's recursion from ray r's hit h at P, of normal Ng (hit_normal's): ambient,
 * direct light, then reflection and refraction (pre: the hit's lookups done ahead with its
 * packet, or NULL).  weight: the largest share of the pixel this ray can carry (1 for eye
 * rays); rays below the scene's bailout are not traced. */
static void shade(const struct ctx *c, const tex_ray *r, const struct tex_hit *hp, tex_v3 P,
                  tex_v3 Ng, const struct tex_prefetch *pre, int depth, double weight,
                  tex_colour *out)
{
    const struct tex_scene *s = c->s;
    struct tex_hit h = *hp;
    int entering = tex_v3_dot(r->d, Ng) < 0;
    tex_v3 N = entering ? Ng : tex_v3_scale(Ng, -1);
    double width = fabs(r->width + h.t * r->spread); /* a focused beam crosses 0 */
    struct tex_material m[2]; /* m[1]: a blended surface's */
    struct tex_shade_at at = {h.leaf, &P, &r->d, width, r->dist + h.t, depth, pre};
    struct light_ahead la;
    const struct light_ahead *a0 = first_light(s, &P, &la);
    tex_resolve_material(s, surface_of(s, h.leaf), &at, &N, m);
    tex_v3 V = tex_v3_scale(r->d, -1);
    double e = eps_at(P);
    /* offset along the geometric normal so bumped normals cannot start rays inside */
    tex_v3 Ngv = entering ? Ng : tex_v3_scale(Ng, -1);
    tex_v3 Pout = tex_v3_madd(P, Ngv, e), Pin = tex_v3_madd(P, Ngv, -e);
    /* rays leaving a hull leaf from outside, away from its surface, skip its object */
    const struct tex_object *outside = entering && h.leaf->hull ? tex_object_top(h.leaf) : NULL;
    struct hit_frame f = {&h, &P, &N, &Ngv, &V, &Pout, &Pin, width, at.dist, entering, outside};

    tex_colour_mul(out, c->n, c->ambient, &m->ka);
    direct_light(c, m, &f, a0, out);
    if (depth < s->settings.depth && (reflects(&m[0]) || (m->blend_m && reflects(&m[1]))))
        secondary(c, r, &f, m, depth, weight, out);
}

/* The colour ray r brings back; from: tex_scene_trace's */
static void trace(const struct ctx *c, const tex_ray *r, const struct tex_object *from,
                  int depth, double weight, tex_colour *out)
{
    struct tex_hit h;
    if (!tex_scene_trace(c->s, &r->o, &r->d, 0, INFINITY, from, &h))
        miss(c, r, out);
    else {
        tex_v3 P = tex_v3_madd(r->o, r->d, h.t);
        shade(c, r, &h, P, hit_normal(&h, P), NULL, depth, weight, out);
    }
}


/* A sample's colour col added to the pixel's sum acc, in RGB */
static inline void accumulate(const struct tex_scene *s, const tex_colour *col, double acc[3])
{
    float rgb[3];
    if (s->cs.mode == TEX_COLOUR_RGB) { /* the identity: no call, no store and reload */
        for (int j = 0; j < 3; j++)
            acc[j] += col->v[j];
        return;
    }
    s->cs.to_rgb(&s->cs, col, rgb);
    for (int j = 0; j < 3; j++)
        acc[j] += rgb[j];
}

static void seed_pixel(const struct ctx *c, int x, int y, tex_rng *rng)
{
    const struct tex_settings *st = &c->s->settings;
    if (c->need_rng)
        tex_rng_seed(rng, tex_hash64(st->seed ^ tex_hash64((uint64_t)y * st->w + x)));
}

static void put_pixel(int spp, const double acc[3], float *px)
{
    for (int j = 0; j < 3; j++)
        px[j] = (float)(spp == 1 ? acc[j] : acc[j] / spp);
}

/* One pixel, its samples traced one by one (TEXTURA_PACKETS=0) */
static void render_pixel(const struct ctx *c0, const struct tex_camera *cam, int x, int y, float *px)
{
    tex_rng rng;
    seed_pixel(c0, x, y, &rng);
    struct ctx c = *c0;
    c.rng = &rng;
    int spp = c0->s->settings.spp;
    double acc[3] = {0, 0, 0};
    for (int i = 0; i < spp; i++) {
        tex_ray r;
        tex_colour col;
        tex_camera_ray(c.s, cam, x, y, i, &rng, &r);
        trace(&c, &r, NULL, 0, 1, &col);
        accumulate(c0->s, &col, acc);
    }
    put_pixel(spp, acc, px);
}

/* A packet of eye rays: a square of PACKET x PACKET pixels, traced a sample at a time.
 * Every ray finds its hit first; then the textures of all the hits are looked up together
 * (tex_prefetch_eval: one batched call per primitive); then each hit is shaded.  Each
 * pixel keeps its own rng and draws from it in the order render_pixel does, and the
 * lookups ahead are the same computations, so the bytes are the per-pixel render's. */
#define PACKET 8
#define QUEUES 3 /* lanes' queues: a packet's leaves (a floor, an object's faces) */
#define NP (PACKET * PACKET)

/* A packet's hits on plain surfaces (tex_surface_plain), in an RGB scene lit by point and
 * spot lights alone: shade's work for them (ambient, then each light's direction, shadow
 * ray and Phong) without its general set-up (nor the material's, where tex_plain_material
 * makes it), done light by light over all of them, their shadow rays together.  Each sum in
 * the same order as shade's: the same bits. */
struct plain {
    int n, k[NP];                        /* k: the hit in the packet */
    const struct tex_object *outside[NP]; /* shade's */
    tex_v3 P[NP], N[NP], V[NP], Pout[NP];
    struct light_ahead a[NP];            /* the light's from each */
    struct tex_plain m[NP];
    float out[NP][3];
    int nbent, bent[NP]; /* the hits whose N the general path made */
    tex_v3 Ngv[NP];      /* their geometric normals */
};

struct packet {
    tex_rng rng[PACKET * PACKET];
    int x[PACKET * PACKET], y[PACKET * PACKET]; /* the pixels: no division by the width */
    double acc[PACKET * PACKET][3];
    tex_ray r[PACKET * PACKET];
    struct tex_hit h[PACKET * PACKET];
    int hit[PACKET * PACKET];
    tex_v3 P[PACKET * PACKET], Ng[PACKET * PACKET];
    struct tex_prefetch pre[PACKET * PACKET], *pp[PACKET * PACKET];
    struct tex_lanes lanes[QUEUES];
    struct plain plain;
};

/* The packet's hit k taken as the next plain one: its frame (shade's) from the normal Ngv
 * facing the ray (Pout's) and the shading normal N, and its ambient light */
static inline __attribute__((always_inline)) void plain_frame(const struct ctx *c,
                                                               struct packet *pk, int k,
                                                               int entering, tex_v3 Ngv,
                                                               tex_v3 N)
{
    struct plain *pl = &pk->plain;
    int i = pl->n++;
    const struct tex_object *leaf = pk->h[k].leaf;
    tex_v3 P = pk->P[k];
    pl->k[i] = k;
    pl->outside[i] = entering && leaf->hull ? tex_object_top(leaf) : NULL;
    pl->P[i] = P, pl->N[i] = N, pl->V[i] = tex_v3_scale(pk->r[k].d, -1);
    pl->Pout[i] = tex_v3_madd(P, Ngv, eps_at(P));
    for (int j = 0; j < 3; j++)
        pl->out[i][j] = c->ambient->v[j] * pl->m[i].ka[j];
}

/* Hit k (normal Ngv facing the ray) taken as a plain one where its surface's material takes
 * the general path (tex_surface_plain 2), its normal bent there.  Not inlined: the plain
 * surfaces' loop stays small. */
static __attribute__((noinline)) void plain_resolve(const struct ctx *c, struct packet *pk,
                                                    int k, const struct tex_surface *sf,
                                                    int entering, tex_v3 Ngv)
{
    struct plain *pl = &pk->plain;
    const tex_ray *r = &pk->r[k];
    const struct tex_hit *h = &pk->h[k];
    tex_v3 N = Ngv;
    struct tex_shade_at at = {h->leaf, &pk->P[k], &r->d, fabs(r->width + h->t * r->spread),
                              r->dist + h->t, 0, &pk->pre[k]};
    tex_plain_resolve(c->s, sf, &at, &N, &pl->m[pl->n]);
    pl->bent[pl->nbent++] = pl->n;
    pl->Ngv[pl->n] = Ngv;
    plain_frame(c, pk, k, entering, Ngv, N);
}

/* Hit k of the packet taken as a plain one: 1, or 0 for shade */
static int plain_take(const struct ctx *c, struct packet *pk, int k)
{
    struct plain *pl = &pk->plain;
    const struct tex_surface *sf = surface_of(c->s, pk->h[k].leaf);
    int kind = tex_surface_plain(sf);
    if (!kind || (kind == 1 && !tex_plain_material(sf, &pk->pre[k], &pl->m[pl->n])))
        return 0;
    tex_v3 Ng = pk->Ng[k];
    int entering = tex_v3_dot(pk->r[k].d, Ng) < 0;
    tex_v3 N = entering ? Ng : tex_v3_scale(Ng, -1);
    if (kind == 2)
        plain_resolve(c, pk, k, sf, entering, N);
    else
        plain_frame(c, pk, k, entering, N, N);
    return 1;
}

/* Light l's share at the plain hits (direct_light's) */
static void plain_light(const struct tex_scene *s, const struct tex_light *l, struct plain *pl)
{
    for (int i = 0; i < pl->n; i++) { /* direct_light's tests */
        struct light_ahead *a = &pl->a[i];
        light_at(l, 0, 0.5, 0.5, &pl->P[i], a);
        a->ok = a->ok && !(tex_v3_dot(a->L, pl->N[i]) <= 0);
    }
    for (int j = 0; j < pl->nbent; j++) { /* and the geometric normal's, where bent */
        struct light_ahead *a = &pl->a[pl->bent[j]];
        a->ok = a->ok && !(tex_v3_dot(a->L, pl->Ngv[pl->bent[j]]) <= 0);
    }
    for (int i = 0; i < pl->n; i++) {
        struct light_ahead *a = &pl->a[i];
        if (!a->ok)
            continue;
        double sh = tex_scene_transmit(s, &pl->Pout[i], &a->L, 0, a->dist, pl->outside[i]);
        a->ok = !(sh <= 0);
        a->fatt *= sh; /* E's scale */
    }
    for (int i = 0; i < pl->n; i++) {
        if (!pl->a[i].ok)
            continue;
        struct tex_material m;
        tex_colour E, out;
        for (int j = 0; j < 3; j++) {
            E.v[j] = l->e.v[j] * (float)pl->a[i].fatt;
            m.kd.v[j] = pl->m[i].kd[j], m.ks.v[j] = pl->m[i].ks[j], out.v[j] = pl->out[i][j];
        }
        m.n = pl->m[i].n;
        tex_phong_direct(&m, &pl->N[i].x, &pl->V[i].x, &pl->a[i].L.x, &E, 3, &out);
        for (int j = 0; j < 3; j++)
            pl->out[i][j] = out.v[j];
    }
}

/* The plain hits taken shaded, into their pixels' sums */
static void plain_shade(const struct ctx *c, struct packet *pk)
{
    struct plain *pl = &pk->plain;
    const struct tex_scene *s = c->s;
    for (int li = 0; li < s->nlights; li++)
        plain_light(s, &s->lights[li], pl);
    for (int i = 0; i < pl->n; i++)
        for (int j = 0; j < 3; j++)
            pk->acc[pl->k[i]][j] += pl->out[i][j];
    pl->n = pl->nbent = 0;
}

/* Hit k of the packet queued for the lanes (tex_lanes_take) in the first queue of its leaf
 * and surface, or an empty one: 1, else 0 */
static int take_lanes(struct packet *pk, int k, const struct tex_surface *sf,
                      const struct tex_object *leaf, const tex_v3 *N, double w)
{
    for (int q = 0; q < QUEUES; q++) {
        if (tex_lanes_take(&pk->lanes[q], &pk->pre[k], sf, leaf, &pk->P[k], &pk->r[k].d, N, w))
            return 1;
        if (!pk->lanes[q].n) /* an empty queue refused it: every queue would */
            return 0;
    }
    return 0;
}

/* The packet's hits made ready to shade: their points and normals, their mappings and
 * footprints, then the lookups of all of them together. */
static void look_ahead(const struct tex_scene *s, struct packet *pk, int n)
{
    int m = 0;
    for (int q = 0; q < QUEUES; q++)
        pk->lanes[q].n = 0;
    for (int k = 0; k < n; k++) {
        tex_ray *r = &pk->r[k];
        if (!pk->hit[k])
            continue;
        pk->P[k] = tex_v3_madd(r->o, r->d, pk->h[k].t);
        pk->Ng[k] = hit_normal(&pk->h[k], pk->P[k]);
        const struct tex_object *leaf = pk->h[k].leaf;
        const struct tex_surface *sf = surface_of(s, leaf);
        if (!tex_surface_footprints(sf) || !s->settings.filter) {
            tex_prefetch_map(&pk->pre[k], sf, leaf, &pk->P[k]);
        } else { /* the frame as shade() has it */
            tex_v3 N = pk->Ng[k];
            N = tex_v3_dot(r->d, N) < 0 ? N : tex_v3_scale(N, -1);
            double w = fabs(r->width + pk->h[k].t * r->spread);
            if (take_lanes(pk, k, sf, leaf, &N, w))
                continue;
            tex_prefetch_map(&pk->pre[k], sf, leaf, &pk->P[k]);
            tex_prefetch_footprints(&pk->pre[k], &r->d, &N, w);
        }
        pk->pp[m++] = &pk->pre[k];
    }
    for (int q = 0; q < QUEUES; q++)
        m += tex_prefetch_lanes(&pk->lanes[q], pk->pp + m);
    tex_prefetch_eval(pk->pp, m);
}

/* The pixels [x0, x1) x [y0, y1) of the image (at most PACKET square) into img, whose
 * origin is the image's (rx, ry). */
static void render_packet(const struct ctx *c0, const struct tex_camera *cam, struct packet *pk,
                          int x0, int y0, int x1, int y1, tex_map *img, int rx, int ry)
{
    const struct tex_scene *s = c0->s;
    int spp = s->settings.spp, np = 0;
    struct ctx c = *c0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++, np++)
            pk->x[np] = x, pk->y[np] = y;
    for (int k = 0; k < np; k++) {
        seed_pixel(c0, pk->x[k], pk->y[k], &pk->rng[k]);
        pk->acc[k][0] = pk->acc[k][1] = pk->acc[k][2] = 0;
    }
    /* a packet beside the box (most of a floor or a sky) tests only the unbounded objects,
     * and one beside an object's box does not test it */
    uint64_t visit = tex_camera_objects(cam, x0, y0, x1, y1);
    for (int i = 0; i < spp; i++) {
        tex_camera_rays(c.s, cam, pk->x, pk->y, np, i, pk->rng, pk->r);
        for (int k = 0; k < np; k++)
            pk->hit[k] = visit ? tex_scene_trace_view(s, &pk->r[k].o, &pk->r[k].d, visit,
                                                          &pk->h[k])
                                   : tex_scene_trace_unbounded(s, &pk->r[k].o, &pk->r[k].d, 0,
                                                               INFINITY, &pk->h[k]);
        look_ahead(s, pk, np);
        for (int k = 0; k < np; k++) {
            tex_colour col;
            c.rng = &pk->rng[k];
            if (pk->hit[k] && c.plain && plain_take(&c, pk, k))
                continue;
            if (pk->hit[k])
                shade(&c, &pk->r[k], &pk->h[k], pk->P[k], pk->Ng[k], &pk->pre[k], 0, 1, &col);
            else
                miss(&c, &pk->r[k], &col);
            accumulate(s, &col, pk->acc[k]);
        }
        plain_shade(&c, pk);
    }
    for (int k = 0; k < np; k++)
        put_pixel(spp, pk->acc[k], tex_map_px(img, pk->x[k] - rx, pk->y[k] - ry));
}

tex_map *tex_render(struct tex_scene *s, void (*progress)(long, long, void *), void *arg)
{
    return tex_render_region(s, 0, 0, s->settings.w, s->settings.h, progress, arg);
}

/* A packet for each of n threads, made on the first band and kept for the others, in one
 * huge page where the kernel gives it (tex_pages_new): each thread's first touch of its own
 * 4 KiB pages was 29 page faults, 1 % of a render at -j 2 on a virtual machine. NULL
 * without the memory. */
static struct packet *packet_pool(struct tex_scene *s, int n)
{
    if (s->npackets < n) {
        tex_pages_free(s->packets, s->packets_mapped);
        s->packets = tex_pages_new(n * sizeof(struct packet), 0, &s->packets_mapped);
        s->npackets = s->packets ? n : 0;
    }
    return s->packets;
}

/* The scene prepared and the region inside its image, or -1 with the error set. */
static int region_check(struct tex_scene *s, int rx, int ry, int rw, int rh)
{
    if (!s->bvh && tex_scene_prepare(s) < 0)
        return -1;
    const struct tex_settings *st = &s->settings;
    if (rx < 0 || ry < 0 || rw < 1 || rh < 1 || rx > st->w - rw || ry > st->h - rh)
        return tex_usage_error("region %d,%d,%d,%d lies outside the %dx%d image", rx, ry, rw,
                               rh, st->w, st->h);
    return 0;
}

/* The pixels of img (the region of its size at rx, ry), or -1 with the error set. */
static int render_into(struct tex_scene *s, int rx, int ry, tex_map *img,
                       void (*progress)(long, long, void *), void *arg)
{
    const struct tex_settings *st = &s->settings;
    int rw = img->w, rh = img->h;
    for (int i = 0; i < s->nsurfaces; i++) {
        if (tex_surface_cache(s->surfaces[i], &s->cs) < 0) {
            for (int j = 0; j <= i; j++)
                tex_surface_uncache(s->surfaces[j]);
            return -1;
        }
    }
    tex_colour ambient, background;
    s->cs.from_rgb(&s->cs, s->ambient, TEX_SPECTRUM_ILLUMINANT, &ambient);
    s->cs.from_rgb(&s->cs, s->background, TEX_SPECTRUM_ILLUMINANT, &background);
    struct ctx c = {s, s->cs.n, &ambient, &background, NULL, st->spp > 1,
                    s->cs.mode == TEX_COLOUR_RGB};
    for (int i = 0; i < s->nlights; i++) {
        c.need_rng |= s->lights[i].kind == TEX_LIGHT_AREA;
        c.plain &= s->lights[i].kind == TEX_LIGHT_POINT || s->lights[i].kind == TEX_LIGHT_SPOT;
    }
    struct tex_camera cam;
    tex_camera_setup(s, &cam);
    int tw = (rw + TILE - 1) / TILE, th = (rh + TILE - 1) / TILE;
    long ntiles = (long)tw * th, done = 0;
    int threads = st->threads > 0 ? st->threads : omp_get_max_threads();
    /* TEXTURA_PACKETS=0: every pixel on its own (the tests compare the two) */
    const char *pe = getenv("TEXTURA_PACKETS");
    int packets = !(pe && !strcmp(pe, "0"));
    struct packet *pool = packets ? packet_pool(s, threads) : NULL;
#pragma omp parallel num_threads(threads)
    {
        /* without the memory for packets, a thread goes pixel by pixel: the same bytes */
        struct packet *pk = pool ? &pool[omp_get_thread_num()] : NULL;
#pragma omp for schedule(dynamic, 1)
        for (long t = 0; t < ntiles; t++) {
            int x0 = (int)(t % tw) * TILE, y0 = (int)(t / tw) * TILE;
            int x1 = x0 + TILE < rw ? x0 + TILE : rw, y1 = y0 + TILE < rh ? y0 + TILE : rh;
            /* pixels keep their place in the whole image: camera rays and seeds */
            for (int py = y0; pk && py < y1; py += PACKET)
                for (int px = x0; px < x1; px += PACKET)
                    render_packet(&c, &cam, pk, rx + px, ry + py,
                                  rx + (px + PACKET < x1 ? px + PACKET : x1),
                                  ry + (py + PACKET < y1 ? py + PACKET : y1), img, rx, ry);
            for (int y = y0; !pk && y < y1; y++)
                for (int x = x0; x < x1; x++)
                    render_pixel(&c, &cam, rx + x, ry + y, tex_map_px(img, x, y));
            long d;
#pragma omp atomic capture
            d = ++done;
            if (progress && omp_get_thread_num() == 0)
                progress(d, ntiles, arg);
        }
    }
    if (progress)
        progress(ntiles, ntiles, arg);
    for (int i = 0; i < s->nsurfaces; i++)
        tex_surface_uncache(s->surfaces[i]);
    return 0;
}

tex_map *tex_render_region(struct tex_scene *s, int rx, int ry, int rw, int rh,
                           void (*progress)(long, long, void *), void *arg)
{
    tex_map *img;
    if (region_check(s, rx, ry, rw, rh) < 0 || !(img = tex_map_new(rw, rh, 3)))
        return NULL;
    if (rw != s->settings.w || rh != s->settings.h) {
        img->x0 = rx;
        img->y0 = ry;
        img->full_w = s->settings.w;
        img->full_h = s->settings.h;
    }
    if (render_into(s, rx, ry, img, progress, arg) < 0) {
        tex_map_free(img);
        return NULL;
    }
    return img;
}

int tex_render_rows(struct tex_scene *s, int rx, int ry, int rw, int rh, float *px)
{
    tex_map img = {.w = rw, .h = rh, .nc = 3, .px = px};
    return region_check(s, rx, ry, rw, rh) < 0 ? -1 : render_into(s, rx, ry, &img, NULL, NULL);
}
