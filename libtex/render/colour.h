/* colour.h - the renderer's colour: n samples, RGB or spectral
 *
 * t_apply shades in one of two colour modes, chosen per scene:
 *   TEX_COLOUR_RGB       n = 3 samples: linear R, G, B (Whitted-Phong)
 *   TEX_COLOUR_SPECTRAL  n = sample count: the mean of a spectrum over n
 *                        equal bands between lambda0 and lambda1 nm (Hall)
 * A tex_colour holds up to TEX_COLOUR_MAX samples; only the first n are
 * meaningful, and every operation takes n so that an RGB scene pays for
 * 3 floats, not TEX_COLOUR_MAX.  Colours are linear (radiance, reflectance);
 * the conversion to display RGB happens once per pixel sample, through the
 * scene's tex_colour_space (to_rgb), and the sRGB non-linearity only when a
 * file is written in an 8/16-bit format.
 *
 *   tex_colour c, k;
 *   tex_colour_set(&c, n, 0.0f);            // c = 0
 *   tex_colour_madd(&c, n, &k, 0.5f);       // c += 0.5 k
 *   tex_colour_mul(&c, n, &c, &k);          // c = c * k (per sample)
 *
 * A colour space converts to and from the n samples:
 *   cs->from_rgb(cs, rgb, kind, &c)   an RGB triple (reflectance or light,
 *                                     TEX_SPECTRUM_REFLECTANCE / _ILLUMINANT)
 *                                     to n samples (identity in RGB mode)
 *   cs->to_rgb(cs, &c, rgb)           n samples to linear display RGB
 *                                     (identity in RGB mode; spectral: CIE
 *                                     1931 -> XYZ -> RGB, gamut mapping)
 * tex_colour_space_rgb() fills the RGB space; the spectral space is made by
 * the spectrum module (issue 10) and plugs into the same two functions.
 */
#ifndef TEX_COLOUR_H
#define TEX_COLOUR_H

#include "../base/api.h"

#include <math.h>
#include <string.h>

TEX_API_BEGIN

#define TEX_COLOUR_MAX 64 /* most spectral samples a scene may ask for */

typedef struct tex_colour {
    float v[TEX_COLOUR_MAX];
} tex_colour;

enum tex_colour_mode { TEX_COLOUR_RGB, TEX_COLOUR_SPECTRAL };
enum tex_spectrum_kind { TEX_SPECTRUM_REFLECTANCE, TEX_SPECTRUM_ILLUMINANT };

struct tex_colour_space {
    enum tex_colour_mode mode;
    int n;                  /* samples per colour: 3 in RGB mode */
    double lambda0, lambda1; /* spectral: the sampled range in nm */
    void (*from_rgb)(const struct tex_colour_space *cs, const float rgb[3],
                     enum tex_spectrum_kind kind, tex_colour *out);
    void (*to_rgb)(const struct tex_colour_space *cs, const tex_colour *c, float rgb[3]);
    void *data; /* the mode's tables (matching functions, basis spectra) */
};

/* The RGB colour space (n = 3, identity conversions). */
void tex_colour_space_rgb(struct tex_colour_space *cs);

/* sRGB transfer function (IEC 61966-2-1) on one linear value, and back. */
float tex_srgb_encode(float linear);
float tex_srgb_decode(float encoded);

/* The band count of spectral scenes unless they ask for another (spectrum.h's
 * TEX_BANDS_DEFAULT): loops over it have a constant length, whole vectors without a loop. */
#define TEX_COLOUR_BANDS 16

/* d->v[i] = expr for every sample i < n: RGB unrolled (n = 3), with all
 * three values computed before any is stored (d may be an operand: the
 * compiler need not reload after each store), spectra vectorised
 * (TEX_COLOUR_BANDS of them unrolled). */
#define TEX_COLOUR_EACH(n, d, expr)                                                        \
    do {                                                                                   \
        float r_[3];                                                                       \
        if ((n) == 3) {                                                                    \
            for (int i = 0; i < 3; i++) r_[i] = (expr);                                    \
            (d)->v[0] = r_[0], (d)->v[1] = r_[1], (d)->v[2] = r_[2];                        \
        } else if ((n) == TEX_COLOUR_BANDS)                                                \
            _Pragma("omp simd") for (int i = 0; i < TEX_COLOUR_BANDS; i++)(d)->v[i] = (expr); \
        else _Pragma("omp simd") for (int i = 0; i < (n); i++)(d)->v[i] = (expr);          \
    } while (0)

static inline void tex_colour_set(tex_colour *d, int n, float x)
{
    TEX_COLOUR_EACH(n, d, x);
}

static inline void tex_colour_copy(tex_colour *d, int n, const tex_colour *a)
{
    if (n == 3) {
        TEX_COLOUR_EACH(3, d, a->v[i]);
        return;
    }
    /* spectra in blocks of a constant size: the loop alone became a call to memmove,
     * 2 % of the five spheres in 16 bands */
    if (n == TEX_COLOUR_BANDS) {
        memcpy(d->v, a->v, TEX_COLOUR_BANDS * sizeof *d->v);
        return;
    }
    int i = 0;
    for (; i + 8 <= n; i += 8)
        memcpy(d->v + i, a->v + i, 8 * sizeof *d->v);
    for (; i < n; i++)
        d->v[i] = a->v[i];
}

static inline void tex_colour_add(tex_colour *d, int n, const tex_colour *a, const tex_colour *b)
{
    TEX_COLOUR_EACH(n, d, a->v[i] + b->v[i]);
}

static inline void tex_colour_mul(tex_colour *d, int n, const tex_colour *a, const tex_colour *b)
{
    TEX_COLOUR_EACH(n, d, a->v[i] * b->v[i]);
}

static inline void tex_colour_scale(tex_colour *d, int n, const tex_colour *a, float s)
{
    TEX_COLOUR_EACH(n, d, a->v[i] * s);
}

/* d += a * s */
static inline void tex_colour_madd(tex_colour *d, int n, const tex_colour *a, float s)
{
    TEX_COLOUR_EACH(n, d, d->v[i] + a->v[i] * s);
}

/* d += a * b * s (per sample) */
static inline void tex_colour_mmadd(tex_colour *d, int n, const tex_colour *a, const tex_colour *b,
                                    float s)
{
    TEX_COLOUR_EACH(n, d, d->v[i] + a->v[i] * b->v[i] * s);
}

/* 1 if every sample of e is finite (RGB unrolled, as TEX_COLOUR_EACH) */
static inline int tex_colour_finite(const tex_colour *e, int n)
{
    if (n == 3)
        return isfinite(e->v[0]) && isfinite(e->v[1]) && isfinite(e->v[2]);
    for (int i = 0; i < n; i++)
        if (!isfinite(e->v[i]))
            return 0;
    return 1;
}

/* 1 if no sample of d is -0.  A sum keeps it so: x + y is -0 only where both are */
static inline int tex_colour_no_negative_zero(const tex_colour *d, int n)
{
    for (int i = 0; i < n; i++)
        if (d->v[i] == 0 && signbit(d->v[i]))
            return 0;
    return 1;
}

/* 1 if d + a * e * s, a zero colour a and s finite, is d itself: every sample of e finite
 * (0 inf is NaN) and none of d -0 (-0 + +0 is +0) */
static inline int tex_colour_zero_adds_nothing(const tex_colour *d, const tex_colour *e, int n)
{
    return tex_colour_finite(e, n) && tex_colour_no_negative_zero(d, n);
}

/* 1 if every sample is zero (of either sign) */
static inline int tex_colour_zero(const tex_colour *a, int n)
{
    if (n == 3)
        return a->v[0] == 0 && a->v[1] == 0 && a->v[2] == 0;
    for (int i = 0; i < n; i++)
        if (a->v[i] != 0)
            return 0;
    return 1;
}

/* tex_colour_max of n, a multiple of 4: four lanes (one vector); the reduction from v[1]
 * stored and reloaded its partial vector, a stall that was 1/7 of a spectral tex_shade.
 * The scalar loop's number: NaN where v[0] is, else the largest of the others (a zero's
 * sign aside, which no caller asks). */
static inline float tex_colour_max4_(const tex_colour *a, int n)
{
    typedef float f4 __attribute__((vector_size(16)));
    typedef int i4 __attribute__((vector_size(16)));
    float m = a->v[0];
    f4 l = {m, -INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i += 4) { /* x > l ? x : l in whole vectors: it was lane by lane */
        f4 x;
        memcpy(&x, a->v + i, sizeof x);
        i4 gt = x > l;
        l = (f4)(((i4)x & gt) | ((i4)l & ~gt));
    }
    m = l[0]; /* v[0] and lane 0's v[4], v[8], ... */
    for (int j = 1; j < 4; j++)
        m = l[j] > m ? l[j] : m;
    return m;
}

static inline float tex_colour_max(const tex_colour *a, int n)
{
    float m = a->v[0];
    if (n == 3) { /* unrolled, as TEX_COLOUR_EACH */
        m = a->v[1] > m ? a->v[1] : m;
        return a->v[2] > m ? a->v[2] : m;
    }
    if (n % 4) {
        for (int i = 1; i < n; i++)
            m = a->v[i] > m ? a->v[i] : m;
        return m;
    }
    return n == TEX_COLOUR_BANDS ? tex_colour_max4_(a, TEX_COLOUR_BANDS) : tex_colour_max4_(a, n);
}

TEX_API_END
#endif
