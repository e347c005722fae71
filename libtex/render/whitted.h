/* whitted.h - the integrator: Whitted's recursion from a ray's hit (libtex internal)
 *
 * I = Ia ka Od + sum over lights S fatt Ip [kd Od (N.L) + ks (N.H)^n] + kr Ir + kt It
 * (thesis eq. 3.1): the ambient term, every light sample that reaches the hit unshadowed
 * through the surface's shading model, then the reflected and refracted rays, traced to
 * the scene's depth and bailout (whitted.c).  render.c takes the pixels' samples, packets
 * and tiles to it.
 */
#ifndef TEX_WHITTED_H
#define TEX_WHITTED_H

#include "../base/rng.h"
#include "scene.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_render_ctx {
    const struct tex_scene *s;
    int n;                 /* colour samples */
    const tex_colour *ambient, *background;
    tex_rng *rng;
    int need_rng; /* jittered samples or area lights */
    int plain;    /* RGB, point and spot lights alone: plain hits shaded together */
    int batch;    /* a packet's shadow rays traced together (tex_scene_shadow_batches) */
};

static inline double tex_eps_at(tex_v3 p)
{
    return 1e-6 * (1 + tex_maxd(tex_maxd(fabs(p.x), fabs(p.y)), fabs(p.z)));
}

static inline const struct tex_surface *tex_surface_of(const struct tex_scene *s, const struct tex_object *leaf)
{
    return leaf->surface ? leaf->surface : s->surfaces[0];
}

/* World normal at a hit, facing outwards of the solid.  Inline: a returned
 * or passed tex_v3 goes through the stack and stalls the load after it. */
static inline __attribute__((always_inline)) tex_v3 tex_hit_normal(const struct tex_hit *h, tex_v3 P)
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

/* A hit once its material is resolved: the point, the shading normal N
 * facing the ray (bumped), the geometric normal Ngv on the ray's side, the
 * view direction, the points just outside and inside, the beam's width.
 * Pointers to trace's locals: the frame itself costs no copies. */
struct tex_hit_frame {
    const struct tex_hit *h;
    const tex_v3 *P, *N, *Ngv, *V, *Pout, *Pin;
    double width, dist; /* dist: the path's length from the eye to P */
    int entering;
    const struct tex_object *outside; /* the object hit where rays leaving cannot meet it */
};

/* A light sample at a hit: its direction, distance and attenuation; ok: it reaches the hit.
 * The first light's, a point or a spot, is made before the material (first_light), so that
 * its square root and division run beside the material's work rather than hold up the
 * shadow ray. */
struct tex_light_ahead {
    tex_v3 L;
    double dist, fatt;
    int ok;
};

/* Light sample k of l at P (jx, jy: an area light's jitter) into a. */
static inline void tex_light_ahead_at(const struct tex_light *l, int k, double jx, double jy,
                            const tex_v3 *P, struct tex_light_ahead *a)
{
    if (l->kind == TEX_LIGHT_POINT || l->kind == TEX_LIGHT_SPOT)
        a->ok = tex_light_point_at(l, &l->pos, P, &a->L, &a->dist, &a->fatt) && a->fatt > 0;
    else
        a->ok = tex_light_sample(l, k, jx, jy, *P, &a->L, &a->dist, &a->fatt);
}

/* Light sample a given tr, the light passing along its shadow ray (tex_scene_transmit):
 * ok where some passes, fatt scaled by it */
static inline void tex_light_pass(struct tex_light_ahead *a, double tr)
{
    a->ok = !(tr <= 0);
    a->fatt *= tr;
}

/* A hit between its material and its light (tex_shade_begin): the frame f points into it,
 * so it stays where it was made */
struct tex_shading {
    struct tex_hit h;
    tex_v3 P, N, Ngv, V, Pout, Pin;
    struct tex_material m[2]; /* m[1]: a blended surface's */
    struct tex_hit_frame f;
    struct tex_light_ahead la; /* the first light's, made ahead: a0 */
    const struct tex_light_ahead *a0;
};

/* tex_shade in three steps, so that a packet's shadow rays go together: the hit's
 * material and frame into sh; its light samples into lit[] (tex_light_rays: one per sample
 * of each light in turn, an area light's jitter drawn from c's rng as tex_shade draws it;
 * returns how many), their shadow rays traced by the caller (tex_light_pass); then the
 * shading and the rays sent on (tex_shade_end; lit NULL: the samples made there, each
 * shadow ray traced on its own). */
void tex_shade_begin(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_hit *hp,
                     tex_v3 P, tex_v3 Ng, const struct tex_prefetch *pre, int depth,
                     struct tex_shading *sh);
int tex_light_rays(const struct tex_render_ctx *c, const struct tex_shading *sh,
                   struct tex_light_ahead *lit);
void tex_shade_end(const struct tex_render_ctx *c, const tex_ray *r, struct tex_shading *sh,
                   const struct tex_light_ahead *lit, int depth, double weight, tex_colour *out);

/* What a ray that meets nothing sees: the background or the environment map. */
void tex_miss(const struct tex_render_ctx *c, const tex_ray *r, tex_colour *out);

/* Whitted's recursion from ray r's hit h at P, of normal Ng (hit_normal's): ambient,
 * direct light, then reflection and refraction (pre: the hit's lookups done ahead with its
 * packet, or NULL).  weight: the largest share of the pixel this ray can carry (1 for eye
 * rays); rays below the scene's bailout are not traced. */
void tex_shade(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_hit *hp, tex_v3 P,
                  tex_v3 Ng, const struct tex_prefetch *pre, int depth, double weight,
                  tex_colour *out);

/* The colour ray r brings back; from: tex_scene_trace's */
void tex_trace(const struct tex_render_ctx *c, const tex_ray *r, const struct tex_object *from,
                  int depth, double weight, tex_colour *out);

#ifdef __cplusplus
}
#endif
#endif
