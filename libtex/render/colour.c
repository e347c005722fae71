/* colour.c - the RGB colour space and the sRGB transfer function */
#include <math.h>
#include <stddef.h>

#include "render/colour.h"

static void rgb_from_rgb(const struct tex_colour_space *cs, const float rgb[3],
                         enum tex_spectrum_kind kind, tex_colour *out)
{
    (void)cs;
    (void)kind;
    out->v[0] = rgb[0];
    out->v[1] = rgb[1];
    out->v[2] = rgb[2];
}

static void rgb_to_rgb(const struct tex_colour_space *cs, const tex_colour *c, float rgb[3])
{
    (void)cs;
    rgb[0] = c->v[0];
    rgb[1] = c->v[1];
    rgb[2] = c->v[2];
}

void tex_colour_space_rgb(struct tex_colour_space *cs)
{
    cs->mode = TEX_COLOUR_RGB;
    cs->n = 3;
    cs->lambda0 = 0;
    cs->lambda1 = 0;
    cs->from_rgb = rgb_from_rgb;
    cs->to_rgb = rgb_to_rgb;
    cs->data = NULL;
}

float tex_srgb_encode(float x)
{
    if (!(x > 0))
        return 0;
    if (x >= 1)
        return 1;
    return x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1 / 2.4f) - 0.055f;
}

float tex_srgb_decode(float x)
{
    if (!(x > 0))
        return 0;
    if (x >= 1)
        return 1;
    return x <= 0.04045f ? x / 12.92f : powf((x + 0.055f) / 1.055f, 2.4f);
}
