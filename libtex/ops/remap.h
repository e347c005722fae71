/* remap.h - value remapping of texture maps: bias, gain, gamma, levels, clamp, quantise
 *
 * Perlin's bias and gain (Perlin 1985, thesis 4.3.2) bend [0,1] onto itself:
 *
 *   bias_b(t) = t^(ln b / ln 0.5)          bias_b(0.5) = b
 *   gain_g(t) = bias_{1-g}(2t) / 2          for t < 0.5
 *             = 1 - bias_{1-g}(2 - 2t) / 2  otherwise;  gain_g(0.5) = 0.5
 *
 * b, g in (0,1); 0.5 is the identity.  Values below 0 count as 0 and above
 * 1 as 1 for bias, gain and gamma (they are defined on [0,1]).
 *
 * struct tex_remap holds every operation; tex_remap_map applies the ones
 * that differ from the identity, in this order: levels, bias, gain, gamma,
 * quantise, invert, clamp (so --clamp keeps the result within a valid
 * range, the thesis's "parameter within its physical range").  Colour
 * channels only: the alpha of an RGBA map is kept.
 *
 *   struct tex_remap r = TEX_REMAP_IDENTITY;
 *   r.bias = 0.3;
 *   tex_remap_map(m, &r);      // in place
 */
#ifndef TEX_REMAP_H
#define TEX_REMAP_H

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

struct tex_remap {
    double bias, gain, gamma;   /* 0.5, 0.5, 1: identity */
    double in0, in1, out0, out1; /* levels: [in0,in1] -> [out0,out1], input clamped */
    int quantize;               /* N >= 2 levels, 0: off */
    int invert;                 /* v -> 1 - v */
    int clamp;                  /* clamp to [lo, hi] */
    double lo, hi;
};
#define TEX_REMAP_IDENTITY {0.5, 0.5, 1, 0, 1, 0, 1, 0, 0, 0, 0, 1}

double tex_bias(double b, double t);
double tex_gain(double g, double t);
/* One value through every operation of r. */
double tex_remap_value(const struct tex_remap *r, double v);
/* Check r's parameters: -1 with a usage error naming the bad one. */
int tex_remap_check(const struct tex_remap *r);
/* Remap m's colour channels in place (parallel); -1 if r is invalid. */
int tex_remap_map(tex_map *m, const struct tex_remap *r);

TEX_API_END
#endif
