/* colour_spectral.c - the spectral colour space for the renderer */
#include "render/colour_spectral.h"

#include "base/error.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* colour.h's loops of constant length are for the band count spectral scenes take unasked */
_Static_assert(TEX_COLOUR_BANDS == TEX_BANDS_DEFAULT, "colour.h's TEX_COLOUR_BANDS follows "
                                                      "spectrum.h's TEX_BANDS_DEFAULT");

struct spectral_data {
    struct tex_bands bands;
    float d65[TEX_BANDS_MAX]; /* Y = 1 */
    unsigned long serial;     /* this space's own, never reused: the memo's key */
};

/* Each thread's last few conversions.  A textured surface's colours come back to a few
 * values hit after hit (a checker's two, and Ka times each): converting each anew was
 * 5 % of the five spheres in 16 bands.  Keyed by the space's serial, the kind and the
 * RGB's bits, so a remembered spectrum is the one the conversion would give. */
#define MEMO 4
struct memo {
    unsigned long serial; /* 0: empty */
    uint32_t r, g, b, kind; /* the RGB's bits */
    float v[TEX_BANDS_MAX];
};
static _Thread_local struct memo memo[MEMO];
static _Thread_local int memo_next;

static void spec_from_rgb(const struct tex_colour_space *cs, const float rgb[3],
                          enum tex_spectrum_kind kind, tex_colour *out)
{
    const struct spectral_data *d = cs->data;
    uint32_t r, g, b; /* in registers: the compares load no stored key */
    memcpy(&r, &rgb[0], sizeof r);
    memcpy(&g, &rgb[1], sizeof g);
    memcpy(&b, &rgb[2], sizeof b);
    for (int k = 0; k < MEMO; k++) {
        const struct memo *m = &memo[k];
        if (m->r == r && m->g == g && m->b == b && m->kind == (uint32_t)kind &&
            m->serial == d->serial) {
            memcpy(out->v, m->v, cs->n * sizeof *out->v);
            return;
        }
    }
    double c[3] = {rgb[0], rgb[1], rgb[2]};
    tex_bands_from_rgb(&d->bands, c, kind == TEX_SPECTRUM_REFLECTANCE, out->v);
    if (kind == TEX_SPECTRUM_ILLUMINANT)
        for (int i = 0; i < cs->n; i++)
            out->v[i] *= d->d65[i];
    struct memo *m = &memo[memo_next];
    memo_next = (memo_next + 1) % MEMO;
    m->serial = d->serial;
    m->r = r, m->g = g, m->b = b, m->kind = (uint32_t)kind;
    memcpy(m->v, out->v, cs->n * sizeof *out->v);
}

static void spec_to_rgb(const struct tex_colour_space *cs, const tex_colour *c, float rgb[3])
{
    const struct spectral_data *d = cs->data;
    double r[3];
    tex_bands_to_rgb(&d->bands, c->v, TEX_GAMUT_CHROMA, r);
    for (int i = 0; i < 3; i++)
        rgb[i] = (float)r[i];
}

int tex_colour_space_spectral(struct tex_colour_space *cs, int n, const char *colord)
{
    if (n < 1 || n > TEX_COLOUR_MAX || n > TEX_BANDS_MAX)
        return tex_usage_error("spectral samples %d outside [1, %d]", n, TEX_BANDS_MAX);
    tex_colorimetry *cm = malloc(sizeof *cm);
    struct spectral_data *d = malloc(sizeof *d);
    if (!cm || !d) {
        free(cm);
        free(d);
        return tex_error("out of memory");
    }
    int rc = tex_colorimetry_load(cm, colord);
    if (rc == 0)
        rc = tex_bands_init(&d->bands, n, cm);
    if (rc == 0 && tex_bands_light(&d->bands, &cm->d65, d->d65) < 0)
        rc = tex_error("D65 has no luminance");
    static unsigned long serials;
    d->serial = __atomic_add_fetch(&serials, 1, __ATOMIC_RELAXED);
    free(cm);
    if (rc < 0) {
        free(d);
        return -1;
    }
    cs->mode = TEX_COLOUR_SPECTRAL;
    cs->n = n;
    cs->lambda0 = TEX_LAMBDA_MIN;
    cs->lambda1 = TEX_LAMBDA_MAX;
    cs->from_rgb = spec_from_rgb;
    cs->to_rgb = spec_to_rgb;
    cs->data = d;
    return 0;
}

void tex_colour_space_spectral_free(struct tex_colour_space *cs)
{
    if (cs->mode == TEX_COLOUR_SPECTRAL) {
        free(cs->data);
        cs->data = NULL;
    }
}

const struct tex_bands *tex_colour_space_bands(const struct tex_colour_space *cs)
{
    return cs->mode == TEX_COLOUR_SPECTRAL ? &((const struct spectral_data *)cs->data)->bands
                                           : NULL;
}

int tex_colour_space_spectral_light(const struct tex_colour_space *cs, const tex_curve *c,
                                    tex_colour *out)
{
    const struct tex_bands *b = tex_colour_space_bands(cs);
    if (b) {
        if (tex_bands_light(b, c, out->v) < 0)
            return tex_usage_error("light spectrum has no luminance");
        return 0;
    }
    /* RGB mode: the curve's colour through 16 bands and the CIE tables, Y = 1. */
    tex_colorimetry *cm = malloc(sizeof *cm);
    struct tex_bands *tb = malloc(sizeof *tb);
    int rc = cm && tb ? 0 : tex_error("out of memory");
    float s[TEX_BANDS_MAX];
    if (rc == 0)
        rc = tex_colorimetry_load(cm, NULL);
    if (rc == 0)
        rc = tex_bands_init(tb, TEX_BANDS_DEFAULT, cm);
    if (rc == 0 && tex_bands_light(tb, c, s) < 0)
        rc = tex_usage_error("light spectrum has no luminance");
    if (rc == 0) {
        double rgb[3];
        tex_bands_to_rgb(tb, s, TEX_GAMUT_CHROMA, rgb);
        for (int i = 0; i < 3; i++)
            out->v[i] = (float)rgb[i];
    }
    free(cm);
    free(tb);
    return rc;
}

void tex_colour_space_curve(const struct tex_colour_space *cs, const tex_curve *c,
                            tex_colour *out)
{
    const struct tex_bands *b = tex_colour_space_bands(cs);
    if (b) {
        tex_bands_sample(b, c, out->v);
        return;
    }
    out->v[0] = (float)tex_curve_at(c, 610);
    out->v[1] = (float)tex_curve_at(c, 550);
    out->v[2] = (float)tex_curve_at(c, 465);
}
