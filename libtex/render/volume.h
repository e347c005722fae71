/* volume.h - ray marching through a scene's hypertextures (libtex internal)
 *
 * A ray meets each hypertexture (hypertexture.h) where its density can be above 0 (its
 * bound); the spans that overlap are marched together, from the ray's start or the
 * bound's entry to its exit or the nearest opaque hit, whichever comes first.  Each step
 * samples the extinction sigma_t, the scattering sigma_s and its albedo, and the emission,
 * at a point moved within the step by a hash of the ray (never by thread state), and adds
 *
 *     T (1 - e^(-sigma_t dt)) / sigma_t x (emission + sigma_s albedo (Ka Ia + sum over
 *     lights of pi p(theta) E T_light))
 *
 * where T is the transmittance so far, E a light's colour times its attenuation, T_light
 * the light passing to it (opaque objects and Kt, tex_scene_transmit, then every
 * hypertexture, tex_volume_transmit) and p Henyey and Greenstein's phase function of the
 * angle between the ray and the light (g = 0: isotropic, 1/4pi).  pi p is the phase
 * function in the surfaces' units, where a white Lambertian surface facing a light of
 * colour E is E.  T falls by e^(-sigma_t dt) a step; below TEX_VOLUME_CUTOFF the march
 * stops, T 0.
 *
 * Steps: the longest is the hypertexture's step, or the ray's footprint where that is
 * wider (a pixel resolves no finer); where the extinction changes by g per unit length
 * the next step is sqrt(tolerance / g), down to a sixteenth of the longest.  Textures are
 * looked up through the ray's footprint, a shadow ray's as wide as its step (what it cannot
 * resolve: band-limited textures fade those octaves out; filter off, none).  No span of
 * a ray takes more than TEX_VOLUME_MAX_STEPS steps, nor of a shadow ray more than
 * TEX_VOLUME_SHADOW_STEPS: a longer one's steps lengthen, so that a ray's work is bounded
 * (at most their product per light) whatever the scene asks.
 */
#ifndef TEX_VOLUME_H
#define TEX_VOLUME_H

#include "colour.h"
#include "vecmath.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TEX_VOLUME_CUTOFF 1e-4
#define TEX_VOLUME_MAX_STEPS 4096
#define TEX_VOLUME_SHADOW_STEPS 1024

struct tex_render_ctx;
struct tex_scene;

/* Along ray r up to tmax (its nearest opaque hit, or infinity): the light the volumes add,
 * in the scene's colour space, into L; returns the transmittance left (0 past the cutoff). */
double tex_volume_march(const struct tex_render_ctx *c, const tex_ray *r, double tmax,
                        tex_colour *L);
/* The fraction of light passing along o + t d (d unit) for t in (0, dist) through every
 * hypertexture of s (1 where s has none), marched by their shadow steps. */
double tex_volume_transmit(const struct tex_scene *s, const tex_v3 *o, const tex_v3 *d,
                           double dist);

#ifdef __cplusplus
}
#endif
#endif
