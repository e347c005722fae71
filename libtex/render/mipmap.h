/* mipmap.h - a texture's lookups: bilinear in a mip-map level, trilinear across two, and
 * primitives at hit points (libtex internal)
 *
 * The lookups every textured hit makes are inline here, so that the application
 * functions (appfn.c) and the packets (packet.c) inline them as the lookups' own file
 * (mipmap.c) does.  Maps repeat: u and v wrap around at the edges.
 */
#ifndef TEX_MIPMAP_H
#define TEX_MIPMAP_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "texture.h"
#include "vecmath.h"
#include "../base/simd.h"
#include "x86/mipmap_x86.h"

#ifdef __cplusplus
extern "C" {
#endif

static inline void to_rgb(const float *p, int nc, float out[3])
{
    if (nc >= 3) {
        out[0] = p[0], out[1] = p[1], out[2] = p[2];
    } else {
        out[0] = out[1] = out[2] = p[0];
    }
}

static inline int wrapi(int i, int n)
{
    i %= n;
    return i < 0 ? i + n : i;
}

/* u modulo 1, in [0, 1]; NaN and infinities, which have no place on a map, give 0 */
static inline double wrap01(double u)
{
    u -= tex_floord(u);
    return u >= 0 && u <= 1 ? u : 0;
}

/* floor() of a texel coordinate (|x| < 2^31), as an int and as a double (*f) */
static inline int floori(double x, double *f)
{
    int i = (int)x;
    double d = i;
    if (d > x)
        i--, d -= 1;
    *f = d;
    return i;
}

/* The four texels around (u, v) in [0, 1] on map m, between the texel centres
 * (x + 0.5) / w, wrapping around: t[0], t[1] on one row, t[2], t[3] on the next, and the
 * weights *ax, *ay of t[1] and t[2]. */
static inline __attribute__((always_inline)) void
texels(const tex_map *m, double u, double v, const float *t[4], double *ax, double *ay)
{
    int w = m->w, h = m->h, nc = m->nc;
    double x = u * w - 0.5, y = v * h - 0.5;
    double fx, fy;
    int ix = floori(x, &fx), iy = floori(y, &fy); /* -1 ... w - 1 */
    *ax = x - fx, *ay = y - fy;
    int x0 = ix < 0 ? w - 1 : ix, y0 = iy < 0 ? h - 1 : iy;
    int wn = w * nc; /* floats per row */
    const float *r0 = m->px + (size_t)y0 * wn, *r1 = y0 + 1 == h ? m->px : r0 + wn;
    x0 *= nc;
    int x1 = x0 + nc == wn ? 0 : x0 + nc; /* the next texel, wrapping */
    t[0] = r0 + x0, t[1] = r0 + x1, t[2] = r1 + x0, t[3] = r1 + x1;
}

/* The derivative of a bilinear interpolant along x (along y: swap t[1] and t[2], ax and ay)
 * from its corners' values a, b (on one row) and c, d (on the next) */
static inline double bilinear_dx(double a, double b, double c, double d, double ay)
{
    return (b - a) * (1 - ay) + (d - c) * ay;
}

/* Channels 0..k-1 of map m (k = 1: grey, 3: colour) at (u, v) in [0, 1], bilinear; g (or
 * NULL): the derivatives of their mean along the map's x and y, in texels. */
static inline __attribute__((always_inline)) void
bilinear(const tex_map *m, int k, double u, double v, float out[3], double g[2])
{
    const float *t[4];
    double ax, ay, gx[3], gy[3];
    texels(m, u, v, t, &ax, &ay);
    for (int c = 0; c < k; c++) {
        double a = t[0][c], b = t[1][c], cc = t[2][c], d = t[3][c];
        out[c] = (float)((a * (1 - ax) + b * ax) * (1 - ay) + (cc * (1 - ax) + d * ax) * ay);
        if (g) /* only for a bump: most lookups want none */
            gx[c] = bilinear_dx(a, b, cc, d, ay), gy[c] = bilinear_dx(a, cc, b, d, ax);
    }
    if (g && k == 3)
        g[0] = (gx[0] + gx[1] + gx[2]) / 3, g[1] = (gy[0] + gy[1] + gy[2]) / 3;
    else if (g)
        g[0] = gx[0], g[1] = gy[0];
}

/* log2(1 + m) / m on [0, 1): mip_level's polynomial (c0 + c1 m + ... + c6 m^6) */
static const double log2_poly[7] = {1.4426913825514791,   -0.72114329207588301,
                                    0.47749583390193867,  -0.33837682222577842,
                                    0.2139429748040822,   -0.094626704743473664,
                                    0.020016627787635053};

/* The pyramid level l of a footprint of x texels on the map (given as x2 = x^2, which spares
 * the footprint a square root), and the weight *a of level l + 1: lod = log2(x) clamped to
 * [0, nlevels - 1], l = floor(lod), *a = lod - l.  log2(x2) from the exponent bits and a
 * polynomial in the mantissa, not libm's, which cost a sixth of a textured hit: log2(1 + m) / m
 * interpolated at the 7 Chebyshev nodes of [0, 1], scaled to give 1 at m = 1; so *a is within
 * 1.1e-6 of libm's, monotonic and exact at powers of two (tests/render/test_render_mip.c). */
static inline int mip_level(const struct tex_texture *t, double x2, double *a)
{
    *a = 0;
    if (!(x2 > 1)) /* magnified, or no filtering (0), or NaN */
        return 0;
    uint64_t bits;
    memcpy(&bits, &x2, sizeof bits);
    int e = (int)(bits >> 52) - 1023, l = e >> 1; /* x2 > 1: positive, normal or infinite */
    if (l >= t->nlevels - 1)
        return t->nlevels - 1;
    bits = (bits & ((UINT64_C(1) << 52) - 1)) | UINT64_C(1023) << 52;
    double m;
    memcpy(&m, &bits, sizeof m);
    m -= 1; /* the mantissa minus 1, in [0, 1) */
    const double *c = log2_poly;
    double lm = c[6]; /* log2(1 + m) = m (c0 + c1 m + ... + c6 m^6) */
    for (int i = 5; i >= 0; i--)
        lm = lm * m + c[i];
    *a = ((e & 1) + lm * m) / 2; /* log2(x) = (e + log2(1 + m)) / 2 */
    return l;
}

/* A map's value at (u, v) in [0, 1] for a footprint of width sqrt(fw2): bilinear in the
 * mip-map level of the footprint and, between levels, linear across the two (trilinear).
 * grad (or NULL): the gradient of its luminance (the channels' mean) per unit of u and of v,
 * the bilinear interpolants' derivatives weighted as their values are (Blinn's Fu, Fv of the
 * map as it is looked up). */
static inline __attribute__((always_inline)) void
map_eval(const struct tex_texture *t, double u, double v, double fw2, float out[3],
         double grad[2])
{
    const tex_map *m = t->mip[0];
    int k = m->nc < 3 ? 1 : 3, side = m->w > m->h ? m->w : m->h;
    double a, g[2][2];
    int l = mip_level(t, fw2 * ((double)side * side), &a);
#ifdef TEX_X86
    if (k == 3 && tex_simd_level() >= TEX_SIMD_AVX2) {
        tex_map_eval3_avx2(t, l, a, u, v, out, grad ? g : NULL);
    } else
#endif
    {
        bilinear(t->mip[l], k, u, v, out, grad ? g[0] : NULL);
        if (a > 0) {
            float o1[3];
            bilinear(t->mip[l + 1], k, u, v, o1, grad ? g[1] : NULL);
            for (int c = 0; c < k; c++)
                out[c] = (float)(out[c] * (1 - a) + o1[c] * a);
        }
        if (k == 1)
            out[1] = out[2] = out[0];
    }
    if (!grad)
        return;
    const tex_map *ml = t->mip[l], *m1 = t->mip[a > 0 ? l + 1 : l]; /* x = u w - 0.5 */
    for (int i = 0; i < 2; i++) {
        double w = i ? ml->h : ml->w, w1 = i ? m1->h : m1->w;
        grad[i] = a > 0 ? g[0][i] * w * (1 - a) + g[1][i] * w1 * a : g[0][i] * w;
    }
}

/* Whether a solid primitive fades its octaves by the footprint (the packets' prefetch
 * takes footprints for those) */
static inline int band_limited(const struct tex_texture *t)
{
    return t->solid && t->field->band_limit && t->field->prim->eval3_fw;
}

/* Whether a texture's lookups use the footprint */
static inline int uses_footprint(const struct tex_texture *t)
{
    return t->mip || band_limited(t);
}

/* A primitive's values at n points (u, v[, w]) into out (n x its channels); fw: the
 * footprints' widths (NULL: none) */
/* A primitive's values at n points (u, v[, w]) into out (n x its channels); fw: the
 * footprints' widths (NULL: none) */
void tex_field_points(const struct tex_texture *t, int n, const double *u, const double *v,
                         const double *w, const double *fw, float *out);
/* A primitive's value val at a hit (its channels, the rest 0) as RGB, through the
 * texture's palette; returns the region id or 0. */
/* A primitive's value val at a hit (its channels, the rest 0) as RGB, through the
 * texture's palette; returns the region id or 0. */
int tex_field_finish(const struct tex_texture *t, float val[TEX_MAP_MAX_CHANNELS],
                        float out[3]);
/* A primitive's value at a hit point (u, v[, w]) seen through a footprint sqrt(fw2) wide */
/* A primitive's value at a hit point (u, v[, w]) seen through a footprint sqrt(fw2) wide */
int tex_field_eval(const struct tex_texture *t, double u, double v, double w, double fw2,
                      float out[3]);
/* texture_eval at any coordinates (wrapped as placed ones), out of line */
/* texture_eval at any coordinates (wrapped as placed ones), out of line */
int tex_texture_lookup(const struct tex_texture *t, double u, double v, double w, double fw2,
                          float out[3]);

/* A region map's id at (u, v) in [0, 1]: the nearest texel, never averaged. */
static inline int region_eval(const tex_map *m, double u, double v, float out[3])
{
    int x = wrapi((int)(u * m->w), m->w), y = wrapi((int)(v * m->h), m->h);
    float id = tex_map_px(m, x, y)[0];
    out[0] = out[1] = out[2] = id;
    return (int)lrintf(id);
}

/* tex_texture_eval at placed coordinates (see place(): u, v in [0, 1e6], the largest repeat
 * count), where truncation is floor, for a footprint of width sqrt(fw2); inline in the
 * lookup of every textured hit. */
static inline __attribute__((always_inline)) int
texture_eval(const struct tex_texture *t, double u, double v, double w, double fw2, float out[3],
             double grad[2])
{
    if (!t->mip)
        return tex_field_eval(t, u, v, w, fw2, out);
    u -= (int)u, v -= (int)v; /* maps repeat */
    if (t->subregions)
        return region_eval(t->mip[0], u, v, out);
    map_eval(t, u, v, fw2, out, grad);
    return 0;
}

#ifdef __cplusplus
}
#endif
#endif
