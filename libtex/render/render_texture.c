/* render_texture.c - textures, mappings and application functions
 *
 * A texture is a map (with a mip-map pyramid for filtered lookups) or a
 * primitive evaluated at hit points.  A surface applies textures in order;
 * each one maps the hit point to texture space (its mapping), keeps the
 * point only inside its window (u1,v1)-(u2,v2), repeats the map nu x nv
 * times there (1 x 1 stretches it), looks up the value f and changes the
 * shading parameters through its application functions g[region][param].
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/x86/simd_x86.h"
#include "render/scene.h"
#include "render/render_ct.h"
#include "ops/palette.h"

/* ---- mip-mapped maps ------------------------------------------------------------ */

int tex_texture_build_mip(struct tex_texture *t)
{
    tex_map *m = t->mip[0];
    int n = 1;
    for (int w = m->w, h = m->h; w > 1 || h > 1; w = (w + 1) / 2, h = (h + 1) / 2)
        n++;
    tex_map **mip = realloc(t->mip, n * sizeof *mip);
    if (!mip)
        return tex_error("out of memory");
    t->mip = mip;
    t->nlevels = 1;
    if (t->subregions)
        return 0; /* region ids are never averaged */
    for (int l = 1; l < n; l++) {
        tex_map *d = tex_map_reduce(mip[l - 1]);
        if (!d)
            return -1;
        mip[l] = d;
        t->nlevels = l + 1;
        if (d->w == 1 && d->h == 1)
            break;
    }
    return 0;
}

static void to_rgb(const float *p, int nc, float out[3])
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

/* floor() in a few instructions (libm's takes tens at -O2 without SSE4.1);
 * exact, since doubles beyond 2^52 are integers (and NaN, inf pass through). */
static inline double floord(double x)
{
    if (!(fabs(x) < 4503599627370496.0))
        return x;
    double t = (double)(long long)x;
    return t - (t > x); /* no branch: x's sign varies across a packet's hits */
}

/* u modulo 1, in [0, 1]; NaN and infinities, which have no place on a map, give 0 */
static inline double wrap01(double u)
{
    u -= floord(u);
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

#ifdef TEX_X86
/* bilinear with k = 3, the channels in three of four double lanes: its operations in its
 * order, so the same floats (and the same derivatives g, or none). */
TEX_AVX2 static inline __m128 bilinear3_avx2(const tex_map *m, double u, double v, double g[2])
{
    const float *t[4];
    double ax, ay;
    texels(m, u, v, t, &ax, &ay);
    __m128i three = _mm_setr_epi32(-1, -1, -1, 0); /* the fourth float is not read */
    __m256d a = _mm256_cvtps_pd(_mm_maskload_ps(t[0], three));
    __m256d b = _mm256_cvtps_pd(_mm_maskload_ps(t[1], three));
    __m256d c = _mm256_cvtps_pd(_mm_maskload_ps(t[2], three));
    __m256d d = _mm256_cvtps_pd(_mm_maskload_ps(t[3], three));
    __m256d wx = _mm256_set1_pd(ax), wx1 = _mm256_set1_pd(1 - ax);
    __m256d wy = _mm256_set1_pd(ay), wy1 = _mm256_set1_pd(1 - ay);
    if (g) { /* bilinear_dx's operations, lane by lane */
        double x[4], y[4];
        _mm256_storeu_pd(x, _mm256_add_pd(_mm256_mul_pd(_mm256_sub_pd(b, a), wy1),
                                          _mm256_mul_pd(_mm256_sub_pd(d, c), wy)));
        _mm256_storeu_pd(y, _mm256_add_pd(_mm256_mul_pd(_mm256_sub_pd(c, a), wx1),
                                          _mm256_mul_pd(_mm256_sub_pd(d, b), wx)));
        g[0] = (x[0] + x[1] + x[2]) / 3, g[1] = (y[0] + y[1] + y[2]) / 3;
    }
    __m256d top = _mm256_add_pd(_mm256_mul_pd(a, wx1), _mm256_mul_pd(b, wx));
    __m256d bot = _mm256_add_pd(_mm256_mul_pd(c, wx1), _mm256_mul_pd(d, wx));
    return _mm256_cvtpd_ps(_mm256_add_pd(_mm256_mul_pd(top, wy1), _mm256_mul_pd(bot, wy)));
}

/* map_eval's colour case from level l (weight a of level l + 1), in vectors; g: as bilinear
 * gives them, level l's in g[0], l + 1's in g[1] */
TEX_AVX2 static void map_eval3_avx2(const struct tex_texture *t, int l, double a, double u,
                                double v, float out[3], double (*g)[2])
{
    __m128 o = bilinear3_avx2(t->mip[l], u, v, g ? g[0] : NULL);
    if (a > 0) {
        __m128 o1 = bilinear3_avx2(t->mip[l + 1], u, v, g ? g[1] : NULL);
        o = _mm256_cvtpd_ps(_mm256_add_pd(_mm256_mul_pd(_mm256_cvtps_pd(o), _mm256_set1_pd(1 - a)),
                                          _mm256_mul_pd(_mm256_cvtps_pd(o1), _mm256_set1_pd(a))));
    }
    _mm_maskstore_ps(out, _mm_setr_epi32(-1, -1, -1, 0), o);
}
#endif

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
 * 1.1e-6 of libm's, monotonic and exact at powers of two (tests/unit/test_render_mip.c). */
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
        map_eval3_avx2(t, l, a, u, v, out, grad ? g : NULL);
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
static void field_points(const struct tex_texture *t, int n, const double *u, const double *v,
                         const double *w, const double *fw, float *out)
{
    const struct tex_field *f = t->field;
    if (fw && band_limited(t))
        f->prim->eval3_fw(f, n, u, v, w, fw, out);
    else if (t->solid)
        f->prim->eval3(f, n, u, v, w, out);
    else
        f->prim->eval2(f, n, u, v, out);
}

/* A primitive's value val at a hit (its channels, the rest 0) as RGB, through the
 * texture's palette; returns the region id or 0. */
static int field_finish(const struct tex_texture *t, float val[TEX_MAP_MAX_CHANNELS],
                        float out[3])
{
    const struct tex_field *f = t->field;
    int region = (f->prim->flags & TEX_PRIM_REGIONS) && f->ids ? (int)lrintf(val[0]) : 0;
    if (t->palette) { /* a region's indexed colour, or the value in [0, 1] */
        float rgba[4];
        if (region)
            tex_palette_index_n(t->palette, region, f->nregions, rgba);
        else
            tex_palette_lookup(t->palette, tex_palette_t(val[0], 0, 1, TEX_OUTSIDE_CLAMP), rgba);
        val[0] = rgba[0], val[1] = rgba[1], val[2] = rgba[2];
        to_rgb(val, 3, out);
    } else {
        to_rgb(val, f->nc, out);
    }
    return region;
}

/* A primitive's value at a hit point (u, v[, w]) seen through a footprint sqrt(fw2) wide */
static int field_eval(const struct tex_texture *t, double u, double v, double w, double fw2,
                      float out[3])
{
    float val[TEX_MAP_MAX_CHANNELS] = {0};
    double fw = sqrt(fw2);
    field_points(t, 1, &u, &v, &w, &fw, val);
    return field_finish(t, val, out);
}

/* A region map's id at (u, v) in [0, 1]: the nearest texel, never averaged. */
static int region_eval(const tex_map *m, double u, double v, float out[3])
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
        return field_eval(t, u, v, w, fw2, out);
    u -= (int)u, v -= (int)v; /* maps repeat */
    if (t->subregions)
        return region_eval(t->mip[0], u, v, out);
    map_eval(t, u, v, fw2, out, grad);
    return 0;
}

/* texture_eval at any coordinates (wrapped as placed ones), out of line */
static int texture_lookup(const struct tex_texture *t, double u, double v, double w, double fw2,
                          float out[3])
{
    if (t->mip)
        u = wrap01(u), v = wrap01(v);
    return texture_eval(t, u, v, w, fw2, out, NULL);
}

int tex_texture_eval(const struct tex_texture *t, double u, double v, double w, double fw,
                     float out[3])
{
    return texture_lookup(t, u, v, w, fw > 0 ? fw * fw : 0, out);
}

/* ---- mappings -------------------------------------------------------------------- */

static double fract(double x)
{
    return x - floord(x);
}

static inline double clamp01(double x)
{
    return x > 0 ? (x < 1 ? x : 1) : 0;
}

/* A planar mapping on an unbounded plane: u, v are its object-space x and z, scaled. */
static inline int plane_planar(const struct tex_apply *ap, const struct tex_object *leaf)
{
    return (ap->mapping == TEX_MAP_NATURAL || ap->mapping == TEX_MAP_PLANAR) &&
           leaf->kind == TEX_SHAPE_PLANE && !ap->placed;
}

/* The wavy projection's shift of u at height y of the texture's frame */
static inline double wave_at(const struct tex_apply *ap, double y)
{
    return ap->wave[0] * sin(2 * M_PI * y / ap->wave[1]);
}

/* The world and solid mappings, from the world point P: face 1 */
static int map_point_world(const struct tex_apply *ap, const struct tex_object *leaf,
                           const tex_v3 *P, double uvw[3])
{
    enum tex_mapping mp = ap->mapping;
    int bounded_solid = mp == TEX_MAP_SOLID && leaf->root && leaf->root->bounded;
    tex_v3 Pt;
    if (ap->placed && (mp == TEX_MAP_WORLD || mp == TEX_MAP_SOLID)) {
        /* about the world's origin, or the solid's box centre */
        tex_v3 c = bounded_solid ? tex_v3_scale(tex_v3_add(leaf->root->wb.lo, leaf->root->wb.hi),
                                                0.5)
                                 : tex_v3_make(0, 0, 0);
        Pt = tex_v3_add(c, tex_xform_point(&ap->to_tex, tex_v3_sub(*P, c)));
        P = &Pt;
    }
    if (mp == TEX_MAP_WORLD || (mp == TEX_MAP_SOLID && !bounded_solid)) {
        uvw[0] = fract(P->x * ap->scale);
        uvw[1] = fract(-P->y * ap->scale);
        uvw[2] = fract(P->z * ap->scale);
        if (mp == TEX_MAP_WORLD) {
            double t = uvw[1];
            uvw[1] = uvw[2], uvw[2] = t; /* 2D maps lie in the ground plane x,z */
        }
        return 1;
    }
    /* solid, across the object's box; clamped: a hit on the box's face may round to just
     * outside it */
    const struct tex_bounds *rb = &leaf->root->wb;
    tex_v3 e = tex_v3_sub(rb->hi, rb->lo);
    uvw[0] = e.x > 0 ? clamp01((P->x - rb->lo.x) / e.x) : 0;
    uvw[1] = e.y > 0 ? clamp01((rb->hi.y - P->y) / e.y) : 0; /* v down: the top is 0 */
    uvw[2] = e.z > 0 ? clamp01((P->z - rb->lo.z) / e.z) : 0;
    return 1;
}

/* A projection's frame on leaf: the point pl turned by the placement about the shape's
 * box centre c into *pt, and *q, *pt across the box (half extents *e): in [-1, 1] inside
 * it; a shape without a box (returns 0) takes c = 0, e = 1.  The box is the leaf's, kept
 * by tex_object_bounds: the shape's bounds method, called at every hit, stalled it. */
static int projection_frame(const struct tex_apply *ap, const struct tex_object *leaf,
                            const tex_v3 *pl, tex_v3 *pt, tex_v3 *q, tex_v3 *e)
{
    int bounded = leaf->bounded;
    tex_v3 c = bounded ? leaf->bc : tex_v3_make(0, 0, 0);
    *e = bounded ? leaf->be : tex_v3_make(1, 1, 1);
    *pt = ap->placed ? tex_v3_add(c, tex_xform_point(&ap->to_tex, tex_v3_sub(*pl, c))) : *pl;
    *q = tex_v3_make((pt->x - c.x) / e->x, (pt->y - c.y) / e->y, (pt->z - c.z) / e->z);
    return bounded;
}

/* map_point_at for every mapping but plane_planar */
static int map_point_other(const struct tex_apply *ap, const struct tex_object *leaf,
                           const tex_v3 *P, const tex_v3 *pl, double uvw[3])
{
    enum tex_mapping mp = ap->mapping;
    tex_v3 plt;
    uvw[2] = 0;
    if (mp == TEX_MAP_NATURAL)
        return tex_shape_methods[leaf->kind].uv(leaf, *pl, &uvw[0], &uvw[1]);
    if (mp == TEX_MAP_WORLD || mp == TEX_MAP_SOLID)
        return map_point_world(ap, leaf, P, uvw);
    tex_v3 q, e;
    int bounded = projection_frame(ap, leaf, pl, &plt, &q, &e);
    pl = &plt;
    switch (mp) {
    case TEX_MAP_SPHERE:
        return tex_shape_methods[TEX_SHAPE_SPHERE].uv(leaf, q, &uvw[0], &uvw[1]);
    case TEX_MAP_BOX:
        return tex_shape_methods[TEX_SHAPE_BOX].uv(leaf, q, &uvw[0], &uvw[1]);
    case TEX_MAP_CYLINDER:
    case TEX_MAP_CONE: {
        uvw[0] = tex_turns(-q.z, q.x);
        uvw[1] = bounded ? fmin(1, fmax(0, (1 - q.y) / 2)) : fract(-pl->y * ap->scale);
        return 1;
    }
    case TEX_MAP_CROSS: /* the x-y plane's map at (u, v), the y-z plane's at (w, v) */
        if (!bounded) {
            uvw[0] = fract(pl->x * ap->scale);
            uvw[1] = fract(-pl->y * ap->scale);
            uvw[2] = fract(pl->z * ap->scale);
        } else {
            uvw[0] = clamp01((q.x + 1) / 2);
            uvw[1] = clamp01((1 - q.y) / 2);
            uvw[2] = clamp01((q.z + 1) / 2);
        }
        return 1;
    default: /* planar: x and z across the box; wavy: swept along a sine path in y */
        if (!bounded) {
            uvw[0] = pl->x * ap->scale;
            uvw[1] = fract(pl->z * ap->scale);
        } else {
            uvw[0] = clamp01((q.x + 1) / 2);
            uvw[1] = clamp01((q.z + 1) / 2);
        }
        if (mp == TEX_MAP_WAVY)
            uvw[0] += wave_at(ap, pl->y);
        if (!bounded || mp == TEX_MAP_WAVY)
            uvw[0] = fract(uvw[0]);
        return 1;
    }
}

/* Texture-space coordinates of world point P (pl in leaf's object space); returns the face id.
 * Inline for the commonest, a plane's (unbounded: no box). */
static inline int map_point_at(const struct tex_apply *ap, const struct tex_object *leaf,
                               const tex_v3 *P, const tex_v3 *pl, double uvw[3])
{
    if (!plane_planar(ap, leaf))
        return map_point_other(ap, leaf, P, pl, uvw);
    uvw[0] = fract(pl->x * ap->scale);
    uvw[1] = fract(pl->z * ap->scale);
    uvw[2] = 0;
    return 1;
}

/* Where the mapping is affine in P (modulo wrapping), its world-space gradients of u, v and
 * w in g[0..2]: 1, else 0 (the footprint then takes finite differences). */
static inline __attribute__((always_inline)) int
map_gradient(const struct tex_apply *ap, const struct tex_object *leaf, tex_v3 g[3])
{
    static const double id[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    const double(*m)[4] = ap->placed ? ap->to_tex.m : id;
    double s[3] = {ap->scale, ap->scale, ap->scale};
    int row[3] = {0, 2, 1}; /* u = x s, v = z s, w = -y s of the point (world mapping) */
    if (plane_planar(ap, leaf)) { /* of the object-space point; w = 0 */
        m = leaf->to_obj.m, s[2] = 0;
    } else if (ap->mapping == TEX_MAP_SOLID) { /* u = x s, v = -y s, w = z s */
        row[1] = 1, row[2] = 2;
        s[1] = -s[1];
        if (leaf->root && leaf->root->bounded) { /* across the box, v down */
            tex_v3 e = tex_v3_sub(leaf->root->wb.hi, leaf->root->wb.lo);
            s[0] = e.x > 0 ? 1 / e.x : 0, s[1] = e.y > 0 ? -1 / e.y : 0;
            s[2] = e.z > 0 ? 1 / e.z : 0;
        }
    } else if (ap->mapping == TEX_MAP_WORLD) {
        s[2] = -s[2];
    } else {
        return 0;
    }
    for (int k = 0; k < 3; k++) {
        const double *r = m[row[k]];
        g[k] = tex_v3_make(r[0] * s[k], r[1] * s[k], r[2] * s[k]);
    }
    return 1;
}

/* box_uv's u = (a + 1) / 2 and v = (b + 1) / 2 on faces 1..6: the axes (1..3: x y z) of a
 * and b, negative where negated */
static const signed char box_axes[6][2] = {{-3, -2}, {3, -2}, {1, 3}, {1, -3}, {1, -2}, {-1, -2}};

/* The natural mappings' (sphere_map, box faces, cylinder_map / cone_map)
 * gradients of u and v in object space at *pp on face (map_point's answer);
 * 0 where there are none (other mappings, the poles, the axis). */
static int natural_gradient(const struct tex_apply *ap, const struct tex_object *leaf,
                            const tex_v3 *pp, int face, tex_v3 *du, tex_v3 *dv)
{
    if (ap->mapping != TEX_MAP_NATURAL)
        return 0;
    tex_v3 p = *pp;
    double rho2 = p.x * p.x + p.z * p.z;
    switch (leaf->kind) {
    case TEX_SHAPE_SPHERE: {
        /* u = atan2(-z, x) / 2pi, v = acos(y / r) / pi */
        double r2 = rho2 + p.y * p.y;
        if (!(rho2 > 1e-12 * r2))
            return 0;
        double rho = sqrt(rho2), k = 1 / (M_PI * rho * r2);
        *du = tex_v3_scale(tex_v3_make(p.z, 0, -p.x), 1 / (2 * M_PI * rho2));
        *dv = tex_v3_make(p.x * p.y * k, -rho2 * k, p.z * p.y * k);
        return 1;
    }
    case TEX_SHAPE_BOX: {
        if (face < 1 || face > 6)
            return 0;
        double g[2][3] = {{0, 0, 0}, {0, 0, 0}};
        for (int i = 0; i < 2; i++) {
            int c = box_axes[face - 1][i];
            g[i][(c < 0 ? -c : c) - 1] = c < 0 ? -0.5 : 0.5;
        }
        *du = tex_v3_make(g[0][0], g[0][1], g[0][2]);
        *dv = tex_v3_make(g[1][0], g[1][1], g[1][2]);
        return 1;
    }
    case TEX_SHAPE_CYLINDER:
    case TEX_SHAPE_CONE:
        if (face == 1) { /* the side: u around the axis, v = 1 - y */
            if (!(rho2 > 1e-24))
                return 0;
            *du = tex_v3_scale(tex_v3_make(p.z, 0, -p.x), 1 / (2 * M_PI * rho2));
            *dv = tex_v3_make(0, -1, 0);
        } else { /* the caps: a disc of radius r across [0, 1]^2 */
            double r = face == 2 ? leaf->r0 : leaf->r1;
            r = r > 0 ? r : 1;
            *du = tex_v3_make(0.5 / r, 0, 0);
            *dv = tex_v3_make(0, 0, 0.5 / r);
        }
        return 1;
    default:
        return 0;
    }
}


/* A cylinder or cone projection's gradients of u and v in object space at *pl (the
 * derivatives of map_point_other's formulas: u = atan2(-qz, qx) / 2pi, v = (1 - qy) / 2
 * across the box or -y scale without one, through the placement's linear part); 0 for
 * other mappings, on the axis and where v is clamped (the footprint then takes finite
 * differences). */
static int projection_gradient(const struct tex_apply *ap, const struct tex_object *leaf,
                               const tex_v3 *pl, tex_v3 *du, tex_v3 *dv)
{
    if (ap->mapping != TEX_MAP_CYLINDER && ap->mapping != TEX_MAP_CONE)
        return 0;
    tex_v3 pt, q, e;
    int bounded = projection_frame(ap, leaf, pl, &pt, &q, &e);
    double rho2 = q.x * q.x + q.z * q.z, vq = (1 - q.y) / 2;
    if (!(rho2 > 1e-24) || (bounded && !(vq > 0 && vq < 1)))
        return 0;
    double k = 1 / (2 * M_PI * rho2);
    double gu[3] = {q.z * k / e.x, 0, -q.x * k / e.z};
    double gv[3] = {0, bounded ? -0.5 / e.y : -ap->scale, 0};
    if (ap->placed) { /* pt = c + M (p - c): a gradient goes by M's transpose */
        const double(*m)[4] = ap->to_tex.m;
        double a[3], b[3];
        for (int j = 0; j < 3; j++) {
            a[j] = m[0][j] * gu[0] + m[1][j] * gu[1] + m[2][j] * gu[2];
            b[j] = m[0][j] * gv[0] + m[1][j] * gv[1] + m[2][j] * gv[2];
        }
        memcpy(gu, a, sizeof a), memcpy(gv, b, sizeof b);
    }
    *du = tex_v3_make(gu[0], gu[1], gu[2]), *dv = tex_v3_make(gv[0], gv[1], gv[2]);
    return 1;
}

/* A texture's window and placement, the divisions done once (tex_surface_cache): (u, v) is
 * in the window where s = (u - u1) iu and t = (v - v1) iv lie in [0, 1], and goes to
 * (s nu, t nv) on the map; su = nu iu and sv = nv iv scale the footprint likewise. */
struct placement {
    double iu, iv, su, sv;
    int bump; /* a function of this texture sets bump (more lookups, footprint and all) */
};

static void placement_of(const struct tex_apply *ap, struct placement *pm)
{
    pm->iu = 1 / (ap->u2 - ap->u1), pm->iv = 1 / (ap->v2 - ap->v1);
    pm->su = ap->nu * pm->iu, pm->sv = ap->nv * pm->iv;
    pm->bump = 0;
    for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next)
        pm->bump |= fn->param == TEX_SP_BUMP;
}

/* Window and placement: 0 if the point is outside the window (or not a number), else the
 * placed coordinates, u in [0, nu] and v in [0, nv]. */
static inline int place(const struct tex_apply *ap, const struct placement *pm, double uvw[3])
{
    double s = (uvw[0] - ap->u1) * pm->iu, t = (uvw[1] - ap->v1) * pm->iv;
    if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1))
        return 0;
    uvw[0] = s * ap->nu;
    uvw[1] = t * ap->nv;
    return 1;
}

static double wrapdiff(double d)
{
    return d - floord(d + 0.5);
}

/* ---- the pixel footprint ------------------------------------------------------------ */

/* The pixel's footprint on the surface at a hit: tangents t1 (the ray projected on the
 * surface) and t2 = N x t1, both of length sqrt(l2), and the footprint's widths along them,
 * width / c (c: the cosine of incidence, at least 0.02) and width.  Mappings with gradients
 * take the tangents as they are; finite differences want them of unit length
 * (footprint_unit) and short steps d1, d2 along them from the hit (footprint_steps: P1, P2
 * in world space, pl1, pl2 in object space, o1, o2 the tangents there). */
struct footprint {
    tex_v3 D, N;
    tex_v3 t1, t2;
    double l2, width, c;
    int tangents; /* 1: t1, t2, l2 and c are made (footprint_tangents) */
    int unit; /* 1: t1, t2 have unit length (l2 = 1) */
    int steps; /* 1: o1, o2 and the steps are made (footprint_steps) */
    tex_v3 o1, o2, P1, P2, pl1, pl2;
    double d1, d2;
};

/* A footprint of the ray D on the surface of normal N; its tangents are made when first
 * asked for (footprint_tangents), which a hit whose lookups take none never does. */
static void footprint_at(struct footprint *fp, const tex_v3 *D, const tex_v3 *N, double width)
{
    fp->D = *D, fp->N = *N;
    fp->width = width;
    fp->tangents = fp->unit = fp->steps = 0;
}

static void footprint_tangents(struct footprint *fp)
{
    if (fp->tangents)
        return;
    const tex_v3 *D = &fp->D, *N = &fp->N;
    double dn = tex_v3_dot(*D, *N), cosv = fabs(dn);
    tex_v3 t1 = tex_v3_madd(*D, *N, -dn);
    double l2 = tex_v3_dot(t1, t1);
    if (l2 < 1e-18) { /* head-on: any tangent */
        t1 = fabs(N->x) < 0.9 ? tex_v3_cross(*N, tex_v3_make(1, 0, 0))
                              : tex_v3_cross(*N, tex_v3_make(0, 1, 0));
        t1 = tex_v3_norm(t1);
        l2 = 1;
    }
    fp->t1 = t1;
    fp->t2 = tex_v3_cross(*N, t1);
    fp->l2 = l2;
    fp->c = cosv > 0.02 ? cosv : 0.02;
    fp->tangents = 1;
}

static void footprint_unit(struct footprint *fp)
{
    if (fp->unit)
        return;
    footprint_tangents(fp);
    double s = 1 / sqrt(fp->l2);
    fp->t1 = tex_v3_scale(fp->t1, s), fp->t2 = tex_v3_scale(fp->t2, s);
    fp->l2 = 1;
    fp->unit = 1;
}

/* The unit tangents in leaf's object space (o1, o2) and the short steps along them from the
 * hit P (pl in object space) that finite differences take. */
static void footprint_steps(struct footprint *fp, const struct tex_object *leaf, const tex_v3 *P,
                            const tex_v3 *pl)
{
    if (fp->steps)
        return;
    footprint_unit(fp);
    fp->o1 = tex_xform_dir(&leaf->to_obj, fp->t1);
    fp->o2 = tex_xform_dir(&leaf->to_obj, fp->t2);
    double w1 = fp->width / fp->c, w2 = fp->width;
    fp->d1 = w1 < 1e-3 ? w1 : 1e-3, fp->d2 = w2 < 1e-3 ? w2 : 1e-3;
    fp->P1 = tex_v3_madd(*P, fp->t1, fp->d1), fp->P2 = tex_v3_madd(*P, fp->t2, fp->d2);
    fp->pl1 = tex_v3_madd(*pl, fp->o1, fp->d1), fp->pl2 = tex_v3_madd(*pl, fp->o2, fp->d2);
    fp->steps = 1;
}

/* The footprint's extents along t1 and t2 (squared, *l2 the second) in texture units, u
 * and v placed, over dims of them (2: u, v; 3: and w, a solid's), by short steps along t1
 * and t2 from the hit P (pl in object space), whose mapping gave uvw0 (no wrap-around),
 * scaled to the footprint; returns the first. */
static double stepped_width2(const struct tex_apply *ap, const struct placement *pm,
                             const struct tex_object *leaf, struct footprint *fp,
                             const tex_v3 *P, const tex_v3 *pl, const double uvw0[3], int dims,
                             double *l2out)
{
    double a[3], b[3];
    footprint_steps(fp, leaf, P, pl);
    map_point_at(ap, leaf, &fp->P1, &fp->pl1, a);
    map_point_at(ap, leaf, &fp->P2, &fp->pl2, b);
    double a0 = wrapdiff(a[0] - uvw0[0]) * pm->su, a1 = wrapdiff(a[1] - uvw0[1]) * pm->sv;
    double b0 = wrapdiff(b[0] - uvw0[0]) * pm->su, b1 = wrapdiff(b[1] - uvw0[1]) * pm->sv;
    double s1 = fp->width / fp->c / fp->d1, s2 = fp->width / fp->d2;
    double l1 = a0 * a0 + a1 * a1, l2 = b0 * b0 + b1 * b1;
    if (dims == 3) {
        double a2 = wrapdiff(a[2] - uvw0[2]), b2 = wrapdiff(b[2] - uvw0[2]);
        l1 += a2 * a2, l2 += b2 * b2;
    }
    *l2out = l2 * (s2 * s2);
    return l1 * (s1 * s1);
}

/* A band-limited solid's footprint width, squared: RenderMan's filterwidth, the square
 * root of the footprint's area (the mean of its extents over u, v and w), which does not
 * blur a surface seen at a grazing angle across its whole width as the longer extent
 * would. */
static double solid_width2(const struct tex_apply *ap, const struct placement *pm,
                           const struct tex_object *leaf, struct footprint *fp, const tex_v3 *P,
                           const tex_v3 *pl, const double uvw0[3])
{
    double l1 = 0, l2 = 0;
    tex_v3 g[3];
    if (map_gradient(ap, leaf, g)) { /* the derivatives along t1, t2, as footprint_width2 */
        const double sc[3] = {pm->su, pm->sv, 1};
        footprint_tangents(fp);
        for (int k = 0; k < 3; k++) {
            double a = tex_v3_dot(g[k], fp->t1) * sc[k], b = tex_v3_dot(g[k], fp->t2) * sc[k];
            l1 += a * a, l2 += b * b;
        }
        return sqrt(l1 * l2) * (fp->width * fp->width) / (fp->c * fp->l2);
    }
    l1 = stepped_width2(ap, pm, leaf, fp, P, pl, uvw0, 3, &l2);
    return sqrt(l1 * l2);
}

/* The world-space gradients g[0], g[1] of u and v at the hit pl (object space, on face) of a
 * mapping that is not affine but has them in closed form (natural_gradient,
 * projection_gradient): the object-space ones through to_obj's transpose, as a normal goes,
 * so that they meet the footprint's world tangents as an affine mapping's do (and in the
 * same lanes, batch_widths).  0 where there are none. */
static int point_gradient(const struct tex_apply *ap, const struct tex_object *leaf,
                          const tex_v3 *pl, int face, tex_v3 g[2])
{
    if (!natural_gradient(ap, leaf, pl, face, &g[0], &g[1]) &&
        !projection_gradient(ap, leaf, pl, &g[0], &g[1]))
        return 0;
    g[0] = tex_xform_normal(&leaf->to_obj, g[0]);
    g[1] = tex_xform_normal(&leaf->to_obj, g[1]);
    return 1;
}

/* The derivatives of the placed u and v along the footprint's tangents t1, t2 as they are
 * (du[i], dv[i] along ti) at the hit P (pl in object space, on face), where the mapping has
 * them in closed form (map_gradient, point_gradient): 1, else 0. */
static inline __attribute__((always_inline)) int
placed_derivatives(const struct tex_apply *ap, const struct placement *pm,
                   const struct tex_object *leaf, struct footprint *fp, const tex_v3 *pl,
                   int face, double du[2], double dv[2])
{
    tex_v3 g[3];
    footprint_tangents(fp);
    if (!map_gradient(ap, leaf, g) && !point_gradient(ap, leaf, pl, face, g))
        return 0;
    for (int i = 0; i < 2; i++) {
        const tex_v3 *e = i ? &fp->t2 : &fp->t1;
        du[i] = tex_v3_dot(g[0], *e) * pm->su, dv[i] = tex_v3_dot(g[1], *e) * pm->sv;
    }
    return 1;
}

/* The footprint's size in texture units (after placement) for texture ap at the hit P (pl)
 * that its mapping took to (u0, v0) on face: the longer of its extents along t1 and t2,
 * squared (the mip level takes it so: neither a root nor a normalised tangent here). */
static double footprint_width2(const struct tex_apply *ap, const struct placement *pm,
                               const struct tex_object *leaf, struct footprint *fp,
                               const tex_v3 *P, const tex_v3 *pl, int face, double u0, double v0)
{
    double du[2], dv[2], m2;
    if (placed_derivatives(ap, pm, leaf, fp, pl, face, du, dv)) { /* then over the length */
        double c2 = fp->c * fp->c, l1 = du[0] * du[0] + dv[0] * dv[0];
        double l2 = (du[1] * du[1] + dv[1] * dv[1]) * c2;
        return (l1 > l2 ? l1 : l2) * (fp->width * fp->width) / (fp->l2 * c2);
    }
    double m1 = stepped_width2(ap, pm, leaf, fp, P, pl, (double[3]){u0, v0, 0}, 2, &m2);
    return m1 > m2 ? m1 : m2;
}

/* ---- application functions ---------------------------------------------------------- */

const struct tex_scene_word tex_quantities[TEX_Q_COUNT + 1] = {
    {"dist", NULL, "the path's length from the eye to the hit (through reflections)"},
    {"footprint", NULL, "the ray's footprint at the hit in texture units (the map is 1 wide)"},
    {"lod", NULL, "log2(footprint), at least -60: -9 where a pixel covers a texel of a 512 map"},
    {"ndotv", NULL, "the cosine between the normal and the direction to the viewer, 0..1"},
    {"depth", NULL, "0 for eye rays, one more per reflection or refraction"},
    {"x", NULL, "the hit's world x"},
    {"y", NULL, "the hit's world y"},
    {"z", NULL, "the hit's world z"},
    {"ox", NULL, "the hit's x in the object's own space"},
    {"oy", NULL, "the hit's y in the object's own space"},
    {"oz", NULL, "the hit's z in the object's own space"},
    {"u", NULL, "the mapping's u at the hit, 0..1 (before window and repeat)"},
    {"v", NULL, "the mapping's v at the hit"},
    {"w", NULL, "the mapping's w at the hit (solid mappings; else 0)"},
    {"nx", NULL, "the normal's world x, facing the ray (before bump)"},
    {"ny", NULL, "the normal's world y"},
    {"nz", NULL, "the normal's world z"},
    {"region", NULL, "the map's subregion id at the hit (0: a map without regions)"},
    {NULL, NULL, NULL},
};


struct evalctx {
    const float *f;     /* map value, RGB */
    const float *p;     /* untextured value, RGB */
    const double *uvw;  /* where the map was looked up (for cascades) */
    double fw2; /* the footprint's squared width */
    const double *q;    /* the quantities at the hit (TEX_Q_COUNT), or NULL if none is read */
};

/* Function in (not a binary operator, rgb or palette) of the values at arg, its result in
 * arg[0], by lang/expr.h's definitions; once for arguments that are grey (the same in every
 * channel), as scalar parameters' are: sin and pow are not cheap. */
static void call(const struct tex_einsn *in, double (*arg)[3])
{
    int k = tex_expr_arity(in->op), grey = 1;
    double r[3];
    for (int i = 0; i < k; i++)
        grey &= arg[i][0] == arg[i][1] && arg[i][1] == arg[i][2];
    for (int ch = 0; ch < (grey ? 1 : 3); ch++)
        r[ch] = tex_expr_apply(in, ch, arg[0], k > 1 ? arg[1] : NULL, k > 2 ? arg[2] : NULL);
    if (grey)
        r[1] = r[2] = r[0];
    arg[0][0] = r[0], arg[0][1] = r[1], arg[0][2] = r[2];
}

/* Run the compiled function e (lang/expr.h) per channel: a loop over its postfix code
 * with the values on a stack in this frame; no recursion, no allocation. */
static void expr_eval(const struct tex_expr *e, const struct evalctx *c, double out[3])
{
    double st[TEX_EXPR_MAX_STACK][3], *a, *b;
    int sp = 0;
    for (const struct tex_einsn *in = e->code, *end = in + e->n; in < end; in++) {
        switch (in->op) {
        case TEX_EOP_CONST:
            a = st[sp++];
            a[0] = in->v[0], a[1] = in->v[1], a[2] = in->v[2];
            continue;
        case TEX_EOP_LEAF: {
            const float *v = in->leaf == TEX_LEAF_F ? c->f : c->p;
            float t[3];
            a = st[sp++];
            if (in->leaf >= TEX_LEAF_Q) {
                a[0] = a[1] = a[2] = c->q[in->leaf - TEX_LEAF_Q];
                continue;
            }
            if (in->leaf == TEX_LEAF_TEX) {
                texture_lookup(in->ptr, c->uvw[0], c->uvw[1], c->uvw[2], c->fw2, t);
                v = t;
            }
            a[0] = v[0], a[1] = v[1], a[2] = v[2];
            continue;
        }
        case TEX_EOP_NEG:
            a = st[sp - 1];
            a[0] = -a[0], a[1] = -a[1], a[2] = -a[2];
            continue;
        case TEX_EOP_ABS:
            a = st[sp - 1];
            a[0] = fabs(a[0]), a[1] = fabs(a[1]), a[2] = fabs(a[2]);
            continue;
        case TEX_EOP_RGB: /* channel k of argument k */
            sp -= 2;
            st[sp - 1][1] = st[sp][1];
            st[sp - 1][2] = st[sp + 1][2];
            continue;
        case TEX_EOP_ADD: case TEX_EOP_SUB: case TEX_EOP_MUL: case TEX_EOP_DIV:
        case TEX_EOP_MIN: case TEX_EOP_MAX:
            break;
        case TEX_EOP_PALETTE: { /* one lookup for the three channels */
            float rgba[4];
            a = st[sp - 1];
            tex_palette_lookup(in->ptr, tex_palette_t((a[0] + a[1] + a[2]) / 3, 0, 1,
                                                      TEX_OUTSIDE_CLAMP), rgba);
            a[0] = rgba[0], a[1] = rgba[1], a[2] = rgba[2];
            continue;
        }
        default: /* the other functions of lang/expr.h */
            sp -= tex_expr_arity(in->op);
            call(in, st + sp);
            sp++;
            continue;
        }
        b = st[--sp];
        a = st[sp - 1];
        for (int k = 0; k < 3; k++) {
            switch (in->op) {
            case TEX_EOP_ADD: a[k] = a[k] + b[k]; break;
            case TEX_EOP_SUB: a[k] = a[k] - b[k]; break;
            case TEX_EOP_MUL: a[k] = a[k] * b[k]; break;
            case TEX_EOP_MIN: a[k] = fmin(a[k], b[k]); break;
            case TEX_EOP_MAX: a[k] = fmax(a[k], b[k]); break;
            default: a[k] = b[k] != 0 ? a[k] / b[k] : 0; break;
            }
        }
    }
    out[0] = st[0][0], out[1] = st[0][1], out[2] = st[0][2];
}

/* An application function compiled to c0 + c1 f + c2 p + c3 f p per channel,
 * where its expression is at most linear in each of f and p (no cascade). */
struct poly {
    double c[4][3];
    int df, dp; /* degrees in f and p */
    /* folded: of degree 0 with no zero constant, so that poly_at gives c[0] itself wherever
     * f and p are finite (c[0] + 0 f is not c[0] at a zero's sign, nor at f infinite);
     * mean: the channels' mean, as a scalar parameter takes it */
    int folded;
    double mean;
};

/* a op b, in a; 0 if the result is not such a polynomial. */
static int poly_op(enum tex_eop op, struct poly *a, const struct poly *b)
{
    struct poly r = {{{0}}, a->df | b->df, a->dp | b->dp, 0, 0};
    double sg = op == TEX_EOP_SUB ? -1 : 1;
    switch (op) {
    case TEX_EOP_ADD:
    case TEX_EOP_SUB:
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                r.c[i][k] = a->c[i][k] + sg * b->c[i][k];
        break;
    case TEX_EOP_MUL:
        if (a->df + b->df > 1 || a->dp + b->dp > 1)
            return 0;
        for (int k = 0; k < 3; k++) {
            r.c[0][k] = a->c[0][k] * b->c[0][k];
            r.c[1][k] = a->c[0][k] * b->c[1][k] + a->c[1][k] * b->c[0][k];
            r.c[2][k] = a->c[0][k] * b->c[2][k] + a->c[2][k] * b->c[0][k];
            r.c[3][k] = a->c[0][k] * b->c[3][k] + a->c[3][k] * b->c[0][k] +
                        a->c[1][k] * b->c[2][k] + a->c[2][k] * b->c[1][k];
        }
        break;
    case TEX_EOP_DIV: /* by a constant; by 0 gives 0 as in expr_eval */
        if (b->df || b->dp)
            return 0;
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 3; k++)
                r.c[i][k] = b->c[0][k] != 0 ? a->c[i][k] / b->c[0][k] : 0;
        r.df = a->df;
        r.dp = a->dp;
        break;
    default: /* min, max, abs: not polynomials */
        return 0;
    }
    *a = r;
    return 1;
}

/* The polynomial of e, by running its code on a stack of polynomials. */
static int poly_of(const struct tex_expr *e, struct poly *r)
{
    struct poly *st = malloc((e->depth ? e->depth : 1) * sizeof *st);
    int sp = 0, ok = st != NULL;
    for (int i = 0; ok && i < e->n; i++) {
        const struct tex_einsn *in = &e->code[i];
        struct poly *a = &st[sp - 1];
        switch (in->op) {
        case TEX_EOP_CONST:
            a = &st[sp++];
            memset(a, 0, sizeof *a);
            for (int k = 0; k < 3; k++)
                a->c[0][k] = in->v[k];
            break;
        case TEX_EOP_LEAF:
            a = &st[sp++];
            memset(a, 0, sizeof *a);
            ok = in->leaf == TEX_LEAF_F || in->leaf == TEX_LEAF_P;
            a->c[in->leaf == TEX_LEAF_F ? 1 : 2][0] = 1;
            a->c[in->leaf == TEX_LEAF_F ? 1 : 2][1] = 1;
            a->c[in->leaf == TEX_LEAF_F ? 1 : 2][2] = 1;
            a->df = in->leaf == TEX_LEAF_F;
            a->dp = in->leaf == TEX_LEAF_P;
            break;
        case TEX_EOP_NEG:
            for (int j = 0; j < 4; j++)
                for (int k = 0; k < 3; k++)
                    a->c[j][k] = -a->c[j][k];
            break;
        case TEX_EOP_RGB: /* channel k of argument k */
            sp -= 2;
            a = &st[sp - 1];
            for (int j = 0; j < 4; j++)
                a->c[j][1] = a[1].c[j][1], a->c[j][2] = a[2].c[j][2];
            a->df |= a[1].df | a[2].df;
            a->dp |= a[1].dp | a[2].dp;
            break;
        default:
            if (tex_expr_arity(in->op) != 2) { /* abs, the functions: not polynomials */
                ok = 0;
                break;
            }
            sp--;
            ok = poly_op(in->op, &st[sp - 1], &st[sp]);
            break;
        }
    }
    if (ok) {
        *r = st[0];
        r->folded = !r->df && !r->dp && r->c[0][0] != 0 && r->c[0][1] != 0 && r->c[0][2] != 0;
        r->mean = (r->c[0][0] + r->c[0][1] + r->c[0][2]) / 3;
    }
    free(st);
    return ok;
}

/* Channel k of a compiled function at f, p */
static inline double poly_at(const struct poly *q, int k, double f, double p)
{
    return q->c[0][k] + q->c[1][k] * f + q->c[2][k] * p + q->c[3][k] * f * p;
}

/* The parameters being textured, in RGB, before conversion to the colour space.  A float
 * follows each colour (ka kd's, gradient[0] normal's, end gradient's): colour_set writes
 * the colour with it. */
struct params {
    float kd[3], ka, ks, n, kr, kt, ior, bump;
    double m, s; /* Cook-Torrance's slope and specular fraction (double: as the model's) */
    float blend; /* the blended surface's weight */
    float normal[3], gradient[3]; /* one apply block's normal map and height gradient */
    float end;
};

typedef float float4 __attribute__((vector_size(16)));

/* Colour c of struct params set to v[0..2] by one store of four floats, the fourth as it
 * was: a later load of part of them is forwarded from the store, where one spanning three
 * single stores would wait for them to reach the cache (material's loads did, on Intel). */
static inline void colour_set(float *c, float4 v)
{
    v[3] = c[3];
    memcpy(c, &v, sizeof v);
}

struct tex_surface_cache {
    struct params base;          /* the surface's own parameters */
    tex_colour col[3];           /* Ka Kd, Kd, Ks in the scene's colour space */
    int cached;                  /* bit i: col[i] is constant (untextured) */
    struct placement *placement; /* per texture applied, in order */
    struct poly *poly;           /* per application function, in order */
    char *compiled;              /* 1: poly[i] holds function i */
    int quantities;              /* bit k: a function reads quantity k (tex_quantities) */
    int footprints;              /* 1: lookups ahead take footprints (tex_surface_footprints) */
    /* 1: one texture, a map looked up ahead, whose functions read no quantity, see every
     * region and bend no normal but by a bump (apply_direct) */
    int direct;
    int lanes; /* 1: direct, and AVX-512: its planes' hits go in lanes (tex_lanes_take) */
    int plain; /* tex_surface_plain: 1, a material tex_plain_material makes; 2, any other */
};

static double clampd(double x, double lo, double hi)
{
    return !(x >= lo) ? lo : x > hi ? hi : x;
}

static float lum(const float v[3])
{
    return (v[0] + v[1] + v[2]) / 3;
}

/* A colour c of struct params through its compiled function q of the map value f, clamped
 * to lo..hi: channel k reads only its channel k. */
static inline __attribute__((always_inline)) void
colour_poly(const struct poly *q, const float f[3], double lo, double hi, float *c)
{
    float4 v;
    for (int k = 0; k < 3; k++)
        v[k] = (float)clampd(poly_at(q, k, f[k], c[k]), lo, hi);
    colour_set(c, v);
}

/* Function fn (compiled to q, or NULL) of the map value f looked up at uvw (footprint fw2),
 * applied to the parameters pr: the colour Kd per channel; a scalar parameter sees the map's
 * luminance as f and takes the mean of the channels.  Results clamped to the valid range. */
static void apply_fn(const struct tex_appfn *fn, const struct poly *q, const float f[3],
                     const double uvw[3], double fw2, const double *qv, struct params *pr)
{
    float *scalar = NULL, *colour = pr->kd, fg[3], p[3], sc = 0; /* sc: m or s, as a float */
    double lo = fn->lo, hi = fn->hi, r[3]; /* the parameter's row's range */
    switch (fn->param) {
    case TEX_SP_KD: break;
    case TEX_SP_KA: scalar = &pr->ka; break;
    case TEX_SP_KS: scalar = &pr->ks; break;
    case TEX_SP_N: scalar = &pr->n; break;
    case TEX_SP_KR: scalar = &pr->kr; break;
    case TEX_SP_KT: scalar = &pr->kt; break;
    case TEX_SP_IOR: scalar = &pr->ior; break;
    case TEX_SP_M: scalar = &sc, sc = (float)pr->m; break;
    case TEX_SP_S: scalar = &sc, sc = (float)pr->s; break;
    case TEX_SP_BLEND: scalar = &pr->blend; break;
    case TEX_SP_NORMAL: /* p: the flat normal */
        colour = pr->normal;
        colour[0] = colour[1] = 0.5f, colour[2] = 1;
        break;
    case TEX_SP_GRADIENT:
        colour = pr->gradient;
        colour[0] = colour[1] = colour[2] = 0;
        break;
    default: scalar = &pr->bump; break;
    }
    const float *fv = f, *pv = colour;
    /* a constant function where lum(f) and p are finite: poly_at's values are its c[0] */
    int folded = scalar && q && q->folded && isfinite(f[0] + f[1] + f[2]) && isfinite(*scalar);
    if (scalar && !folded) {
        fg[0] = fg[1] = fg[2] = lum(f);
        p[0] = p[1] = p[2] = *scalar;
        fv = fg, pv = p;
    }
    if (!q) {
        struct evalctx c = {fv, pv, uvw, fw2, qv};
        expr_eval(fn->e, &c, r);
    }
    if (scalar) {
        for (int k = 0; q && !folded && k < 3; k++)
            r[k] = poly_at(q, k, fv[k], pv[k]);
        *scalar = (float)clampd(folded ? q->mean : (r[0] + r[1] + r[2]) / 3, lo, hi);
        if (fn->param == TEX_SP_M)
            pr->m = sc;
        else if (fn->param == TEX_SP_S)
            pr->s = sc;
    } else if (q) {
        colour_poly(q, f, lo, hi, colour);
    } else {
        colour_set(colour, (float4){(float)clampd(r[0], lo, hi), (float)clampd(r[1], lo, hi),
                                    (float)clampd(r[2], lo, hi), 0});
    }
}

/* The surface gradients (world space, texture units per world unit) of the placed u and v of
 * texture ap at the hit, (u0, v0) by its mapping, by finite differences along the tangents. */
static void uv_gradients(const struct tex_apply *ap, const struct placement *pm,
                         const struct tex_object *leaf, const tex_v3 *P, struct footprint *fp,
                         double width, double u0, double v0, tex_v3 *gu, tex_v3 *gv)
{
    double h = width > 1e-4 ? width : 1e-4, du[2], dv[2];
    footprint_unit(fp);
    for (int i = 0; i < 2; i++) {
        tex_v3 Pi = tex_v3_madd(*P, i ? fp->t2 : fp->t1, h);
        tex_v3 pli = tex_xform_point(&leaf->to_obj, Pi);
        double a[3];
        map_point_at(ap, leaf, &Pi, &pli, a);
        du[i] = wrapdiff(a[0] - u0) * pm->su / h;
        dv[i] = wrapdiff(a[1] - v0) * pm->sv / h;
    }
    *gu = tex_v3_add(tex_v3_scale(fp->t1, du[0]), tex_v3_scale(fp->t2, du[1]));
    *gv = tex_v3_add(tex_v3_scale(fp->t1, dv[0]), tex_v3_scale(fp->t2, dv[1]));
}

/* A tangent-space normal map's normal (encoded 0.5 + 0.5 n: x along u, y against v, since v
 * grows down the map, z along N) in world space; N itself where the map is flat. */
static tex_v3 normal_mapped(const float enc[3], const tex_v3 *N, const tex_v3 *gu,
                            const tex_v3 *gv)
{
    double x = 2.0 * enc[0] - 1, y = 2.0 * enc[1] - 1, z = 2.0 * enc[2] - 1;
    if (x == 0 && y == 0) /* flat: N as it is, to the bit */
        return *N;
    tex_v3 t = tex_v3_norm(*gu), b = tex_v3_scale(tex_v3_norm(*gv), -1);
    return tex_v3_norm(tex_v3_add(tex_v3_add(tex_v3_scale(t, x), tex_v3_scale(b, y)),
                                  tex_v3_scale(*N, z)));
}

/* A tilt's direction along the footprint's tangents t1, t2 from the luminance's
 * derivatives g along them; where grad (the map's gradient per u and v) is given, g is made
 * from it first, through the derivatives du, dv of u and v along t1, t2. */
static tex_v3 tilt_along(const double *grad, const double du[2], const double dv[2],
                         double g[2], tex_v3 t1, tex_v3 t2)
{
    if (grad)
        g[0] = grad[0] * du[0] + grad[1] * dv[0], g[1] = grad[0] * du[1] + grad[1] * dv[1];
    return tex_v3_add(tex_v3_scale(t1, g[0]), tex_v3_scale(t2, g[1]));
}

/* Blinn's bump mapping: the tilt of the normal against the surface gradient of texture ap's
 * luminance (f at the hit; pl: the hit in object space, on face).  grad (or NULL): the
 * gradient per placed u and v that the map's lookup gave (map_eval), taken through the
 * mapping's derivatives where they have a closed form; else (a primitive, a region map, a
 * mapping without them) finite differences along the footprint's tangents. */
static tex_v3 bump_tilt(const struct tex_apply *ap, const struct placement *pm,
                        const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *pl,
                        int face, struct footprint *fp, double width, double fw2,
                        const double *grad, const float f[3], double strength)
{
    double h = width > 1e-4 ? width : 1e-4, g[2], du[2], dv[2];
    footprint_unit(fp);
    if (grad && placed_derivatives(ap, pm, leaf, fp, pl, face, du, dv))
        return tex_v3_scale(tilt_along(grad, du, dv, g, fp->t1, fp->t2), strength);
    for (int i = 0; i < 2; i++) {
        tex_v3 Pi = tex_v3_madd(*P, i ? fp->t2 : fp->t1, h);
        tex_v3 pli = tex_xform_point(&leaf->to_obj, Pi);
        double uvw[3];
        float fi[3];
        map_point_at(ap, leaf, &Pi, &pli, uvw);
        if (!place(ap, pm, uvw))
            return tex_v3_make(0, 0, 0);
        texture_lookup(ap->tex, uvw[0], uvw[1], uvw[2], fw2, fi);
        g[i] = (lum(fi) - lum(f)) / h;
    }
    return tex_v3_scale(tilt_along(NULL, NULL, NULL, g, fp->t1, fp->t2), strength);
}

/* A cross mapping's value (thesis 5.2.1.3): the map on the x-y plane (f, at u, v) combined
 * with the second map on the y-z plane, at (w, v), w placed as u is. */
static void cross_combine(const struct tex_apply *ap, const struct placement *pm,
                          const double uvw[3], double fw2, float f[3])
{
    float g[3];
    double w = (uvw[2] - ap->u1) * pm->iu * ap->nu;
    texture_lookup(ap->cross, w, uvw[1], 0, fw2, g);
    for (int k = 0; k < 3; k++)
        f[k] = ap->combine == TEX_COMBINE_PRODUCT ? f[k] * g[k]
               : ap->combine == TEX_COMBINE_MIN   ? fminf(f[k], g[k])
                                                   : fmaxf(f[k], g[k]);
}

/* The quantities of the hit that do not depend on the texture (tex_quantities). */
static void hit_quantities(const struct tex_shade_at *at, const tex_v3 *pl, const tex_v3 *N,
                           double q[TEX_Q_COUNT])
{
    q[TEX_Q_DIST] = at->dist;
    q[TEX_Q_NDOTV] = fabs(tex_v3_dot(*N, *at->D));
    q[TEX_Q_DEPTH] = at->depth;
    q[TEX_Q_X] = at->P->x, q[TEX_Q_Y] = at->P->y, q[TEX_Q_Z] = at->P->z;
    q[TEX_Q_OX] = pl->x, q[TEX_Q_OY] = pl->y, q[TEX_Q_OZ] = pl->z;
    q[TEX_Q_NX] = N->x, q[TEX_Q_NY] = N->y, q[TEX_Q_NZ] = N->z;
}

/* Application ap's mapping of the hit P (pl in object space) into a: the mapping's
 * coordinates, then placed, and whether the placement holds the point; no value yet.
 * Always inlined: gcc's size limit left it out of the packet's loop after changes
 * elsewhere, and workshop took 2-3 % longer. */
static inline __attribute__((always_inline)) void
map_hit(const struct tex_apply *ap, const struct placement *pm, const struct tex_object *leaf,
        const tex_v3 *P, const tex_v3 *pl, struct tex_prefetch_ap *a)
{
    double uvw[3], placed[3]; /* in registers where map_point_at is inlined */
    a->tex = ap->tex;
    a->face = map_point_at(ap, leaf, P, pl, uvw);
    for (int i = 0; i < 3; i++)
        a->uvw0[i] = placed[i] = uvw[i];
    a->inside = place(ap, pm, placed); /* placed in registers, then stored: not reloaded */
    for (int i = 0; i < 3; i++)
        a->uvw[i] = placed[i];
    a->pending = a->inside && !ap->tex->mip;
    a->bump = pm->bump;
    a->has_val = a->has_tilt = 0;
    a->fw = 0;
}

/* The footprint (squared) that texture ap's lookups take at the hit P (pl), whose mapping
 * is pa: 0 where none uses one (filter off, primitives other than band-limited solids, a
 * band-limited value that came with the packet and no bump to look up); a band-limited
 * solid's over w too; a map's that came with the packet, the one it was looked up with.
 * *mapped: it is footprint_width2's. */
static double lookup_width2(const struct tex_apply *ap, const struct placement *pm,
                            const struct tex_object *leaf, struct footprint *fp, const tex_v3 *P,
                            const tex_v3 *pl, const struct tex_prefetch_ap *pa, int filter,
                            int *mapped)
{
    if (pa->has_val && ap->tex->mip) { /* a map's value came with its footprint */
        *mapped = filter;
        return pa->fw;
    }
    int need = filter && ((uses_footprint(ap->tex) && (!pa->has_val || pm->bump)) ||
                          (ap->mapping == TEX_MAP_CROSS && uses_footprint(ap->cross)));
    *mapped = 0;
    if (!need)
        return 0;
    if (band_limited(ap->tex))
        return solid_width2(ap, pm, leaf, fp, P, pl, pa->uvw0);
    *mapped = 1;
    return footprint_width2(ap, pm, leaf, fp, P, pl, pa->face, pa->uvw0[0], pa->uvw0[1]);
}

/* The quantities of texture ap at the hit (its mapping pa) into q: the footprint fw2 when
 * lookup_width2 gave footprint_width2's, else (fw2 < 0) the real one through fq, where
 * read (bits, as tex_surface_cache's quantities). */
static void texture_quantities(const struct tex_apply *ap, const struct placement *pm,
                               const struct tex_object *leaf, struct footprint *fq,
                               const tex_v3 *P, const tex_v3 *pl,
                               const struct tex_prefetch_ap *pa, double fw2, int region,
                               int read, double *q)
{
    if (read & (1 << TEX_Q_FOOTPRINT | 1 << TEX_Q_LOD)) { /* else unread: not made */
        double w2 = fw2 >= 0 ? fw2
                             : footprint_width2(ap, pm, leaf, fq, P, pl, pa->face, pa->uvw0[0],
                                                pa->uvw0[1]);
        q[TEX_Q_FOOTPRINT] = sqrt(w2);
        q[TEX_Q_LOD] = w2 > 0x1p-120 ? log2(w2) / 2 : -60;
    }
    q[TEX_Q_U] = pa->uvw0[0], q[TEX_Q_V] = pa->uvw0[1], q[TEX_Q_W] = pa->uvw0[2];
    q[TEX_Q_REGION] = region;
}

/* Texture ap's value f at a hit its mapping took to pa, for a footprint fw2: the value that
 * came with the packet, or one lookup (region maps and primitives ignore the footprint),
 * combined with the cross mapping's second map; returns the region id.  grad (or NULL): a
 * map's gradient with its value (map_eval). */
static int texture_value(const struct tex_apply *ap, const struct placement *pm,
                         const struct tex_prefetch_ap *pa, double fw2, float f[3], double *grad)
{
    int region;
    if (pa->has_val && ap->tex->mip) { /* a map's, RGB already, and its gradient */
        memcpy(f, pa->val, 3 * sizeof *f);
        if (grad)
            grad[0] = pa->grad[0], grad[1] = pa->grad[1];
        return 0;
    }
    if (pa->has_val) {
        float val[TEX_MAP_MAX_CHANNELS];
        memcpy(val, pa->val, sizeof val);
        region = field_finish(ap->tex, val, f);
    } else {
        region = texture_eval(ap->tex, pa->uvw[0], pa->uvw[1], pa->uvw[2], fw2, f, grad);
    }
    if (ap->mapping == TEX_MAP_CROSS)
        cross_combine(ap, pm, pa->uvw, fw2, f);
    return region;
}

/* The tilt's direction made ahead with the packet (lane_tilt), at the bump's strength */
static tex_v3 tilt_ahead(const struct tex_prefetch_ap *pa, double strength)
{
    return tex_v3_scale(tex_v3_make(pa->tilt[0], pa->tilt[1], pa->tilt[2]), strength);
}

/* N bent by the bumps' summed tilt (zero where none bumped) */
static void bend(tex_v3 tilt, tex_v3 *N)
{
    if (tex_v3_dot(tilt, tilt) > 0)
        *N = tex_v3_norm(tex_v3_sub(*N, tilt));
}

/* The textures of sf applied at the hit (normal N; filter: mip-mapped lookups) to pr, N bent
 * by bump maps; 1 if one of them set Ks. */
static int apply_textures(const struct tex_surface *sf, const struct tex_shade_at *at,
                          const struct tex_prefetch *pre, tex_v3 *N, int filter,
                          struct params *pr)
{
    const struct tex_object *leaf = at->leaf;
    const tex_v3 *P = at->P;
    double width = filter ? at->width : 0;
    struct footprint fp;
    footprint_at(&fp, at->D, N, width);
    tex_v3 pl = pre ? pre->pl : tex_xform_point(&leaf->to_obj, *P), tilt = tex_v3_make(0, 0, 0);
    const struct tex_surface_cache *cache = sf->cache;
    const struct placement *pm = cache->placement;
    int nfn = 0, ks_textured = 0; /* nfn: the function's index in the cache */
    double qv[TEX_Q_COUNT], *q = NULL;
    struct footprint fq; /* the real footprint for the quantities, filtered or not */
    if (cache->quantities) {
        q = qv;
        hit_quantities(at, &pl, N, q);
        footprint_at(&fq, at->D, N, at->width);
    }
    int j = 0;
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next, pm++, j++) {
        float f[3];
        /* the packet's mapping (the same computation, done ahead) or the hit's own */
        struct tex_prefetch_ap own;
        const struct tex_prefetch_ap *pa = pre && j < pre->n ? &pre->ap[j] : NULL;
        if (!pa) {
            map_hit(ap, pm, leaf, P, &pl, &own);
            pa = &own;
        }
        const double *uvw = pa->uvw;
        if (!pa->inside) {
            for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next)
                nfn++;
            continue;
        }
        int mapped; /* fw2 is footprint_width2's, which the quantities report */
        double fw2 = lookup_width2(ap, pm, leaf, &fp, P, &pl, pa, filter, &mapped);
        double grad[2], *gp = pm->bump && ap->tex->mip && !ap->tex->subregions &&
                                      ap->mapping != TEX_MAP_CROSS ? grad : NULL;
        int region = texture_value(ap, pm, pa, fw2, f, gp);
        if (q)
            texture_quantities(ap, pm, leaf, &fq, P, &pl, pa, mapped ? fw2 : -1, region,
                               cache->quantities, q);
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++) {
            if (fn->region && fn->region != region)
                continue;
            ks_textured |= fn->param == TEX_SP_KS;
            apply_fn(fn, cache->compiled[nfn] ? &cache->poly[nfn] : NULL, f, uvw, fw2, q, pr);
            if (fn->param == TEX_SP_BUMP && pr->bump != 0) {
                if (pa->has_tilt && ap->next) /* as bump_tilt leaves it for those after */
                    footprint_unit(&fp);
                tilt = tex_v3_add(tilt, pa->has_tilt ? tilt_ahead(pa, pr->bump)
                                                     : bump_tilt(ap, pm, leaf, P, &pl, pa->face,
                                                                 &fp, width, fw2, gp, f,
                                                                 pr->bump));
                pr->bump = 0;
            } else if (fn->param == TEX_SP_NORMAL || fn->param == TEX_SP_GRADIENT) {
                tex_v3 gu, gv;
                uv_gradients(ap, pm, leaf, P, &fp, width, pa->uvw0[0], pa->uvw0[1], &gu, &gv);
                if (fn->param == TEX_SP_NORMAL) {
                    *N = normal_mapped(pr->normal, N, &gu, &gv);
                } else {
                    tilt = tex_v3_add(tilt, tex_v3_add(tex_v3_scale(gu, pr->gradient[0]),
                                                       tex_v3_scale(gv, pr->gradient[1])));
                }
            }
        }
    }
    bend(tilt, N);
    return ks_textured;
}

/* cs->from_rgb of a reflectance; RGB mode's is the identity: copied without the call */
static inline void reflectance(const struct tex_colour_space *cs, const float rgb[3],
                               tex_colour *out)
{
    if (cs->mode == TEX_COLOUR_RGB)
        out->v[0] = rgb[0], out->v[1] = rgb[1], out->v[2] = rgb[2];
    else
        cs->from_rgb(cs, rgb, TEX_SPECTRUM_REFLECTANCE, out);
}

/* The material from the parameters pr (ks_textured: Ks was set by a texture). */
static inline __attribute__((always_inline)) void
material(const struct tex_colour_space *cs, const struct tex_surface *sf,
                            const struct params *pr, int ks_textured, struct tex_material *m)
{
    const struct tex_surface_cache *sc = sf->cache;
    int n = cs->n, cached = sc->cached; /* untextured surfaces: every colour cached */
    if (cached & 1) {
        tex_colour_copy(&m->ka, n, &sc->col[0]);
    } else {
        float ka[3] = {pr->ka * pr->kd[0], pr->ka * pr->kd[1], pr->ka * pr->kd[2]};
        reflectance(cs, ka, &m->ka);
    }
    if (cached & 2)
        tex_colour_copy(&m->kd, n, &sc->col[1]);
    else
        reflectance(cs, pr->kd, &m->kd);
    if (cached & 4) {
        tex_colour_copy(&m->ks, n, &sc->col[2]);
    } else {
        float ks[3] = {pr->ks, pr->ks, pr->ks};
        reflectance(cs, ks_textured ? ks : sf->ks, &m->ks);
    }
    m->n = pr->n;
    m->kr = pr->kr;
    m->kt = pr->kt;
    m->ior = pr->ior;
    m->m = pr->m;
    m->s = pr->s;
    m->model = sf->model;
    m->model_data = sf->ct;
    m->blend = 0;
    m->blend_m = NULL;
}

/* apply_textures for a direct surface (tex_surface_cache) whose map's value and footprint
 * came with the packet in pa, and a bump's tilt where it bumps: its functions in order,
 * without the general path's set-up; N bent as apply_textures bends it */
static int apply_direct(const struct tex_surface *sf, const struct tex_prefetch_ap *pa,
                        tex_v3 *N, struct params *pr)
{
    const struct tex_surface_cache *c = sf->cache;
    int ks_textured = 0, i = 0;
    tex_v3 tilt = tex_v3_make(0, 0, 0);
    for (const struct tex_appfn *fn = sf->apply->fns; pa->inside && fn; fn = fn->next, i++) {
        const struct poly *q = c->compiled[i] ? &c->poly[i] : NULL;
        ks_textured |= fn->param == TEX_SP_KS;
        if (q && fn->param == TEX_SP_KD) { /* apply_fn's path for it, without the call */
            colour_poly(q, pa->val, fn->lo, fn->hi, pr->kd);
            continue;
        }
        apply_fn(fn, q, pa->val, pa->uvw, pa->fw, NULL, pr);
        if (fn->param == TEX_SP_BUMP && pr->bump != 0) {
            tilt = tex_v3_add(tilt, tilt_ahead(pa, pr->bump));
            pr->bump = 0;
        }
    }
    bend(tilt, N);
    return ks_textured;
}

/* One surface's material at the hit; *blend: its blend's weight there. */
static void resolve(const struct tex_scene *s, const struct tex_surface *sf,
                    const struct tex_shade_at *at, tex_v3 *N, struct tex_material *m,
                    float *blend)
{
    *blend = 0;
    if (!sf->apply) { /* the cache as it is, without the textured path's set-up */
        material(&s->cs, sf, &sf->cache->base, 0, m);
        return;
    }
    struct params pr = sf->cache->base;
    const struct tex_prefetch *pre = at->pre && at->pre->sf == sf ? at->pre : NULL;
    int filter = s->settings.filter && at->width > 0;
    /* a bumped direct surface's tilt made ahead in lanes, or the general path's own */
    int direct = pre && sf->cache->direct && pre->n && pre->ap[0].has_val &&
                 (!sf->cache->placement[0].bump || pre->ap[0].has_tilt);
    int ks_textured = direct ? apply_direct(sf, &pre->ap[0], N, &pr)
                             : apply_textures(sf, at, pre, N, filter, &pr);
    material(&s->cs, sf, &pr, ks_textured, m);
    *blend = pr.blend;
}

void tex_resolve_material(const struct tex_scene *s, const struct tex_surface *sf,
                          const struct tex_shade_at *at, tex_v3 *N, struct tex_material m[2])
{
    float w, w1;
    tex_v3 N1 = *N; /* this surface's normal shades both */
    resolve(s, sf, at, N, &m[0], &w);
    if (sf->blend && w > 0) { /* the other surface at the same hit, its own textures */
        resolve(s, sf->blend, at, &N1, &m[1], &w1);
        tex_colour_scale(&m[0].ka, s->cs.n, &m[0].ka, 1 - w); /* the ambient term, mixed */
        for (int i = 0; i < s->cs.n; i++)
            m[0].ka.v[i] += w * m[1].ka.v[i];
        m[0].blend = w;
        m[0].blend_m = &m[1];
    }
}

/* ---- mip-mapped lookups over a packet ----------------------------------------------- */

/* Whether the packet looks texture ap up ahead when it is a surface's first: a filtered
 * map, with its gradient where bumped (a cross mapping wants a second map). */
static int map_ahead(const struct tex_apply *ap)
{
    return ap->tex->mip && !ap->tex->subregions && ap->mapping != TEX_MAP_CROSS;
}

/* Points per batch, a multiple of 8: a packet's hits.  At 256 the batch's rows (struct frames),
 * 2 KiB apart, shared few L1 sets, and every scene took 1-4 % longer. */
enum { CHUNK = 64 };

/* The points of a batch in lanes: the shading frames (D, N, width: rows of its own, or a
 * lanes' queue's, which are not copied) and the mappings' gradients gu, gv and placement
 * scales su, sv of those whose footprints go in lanes. */
struct frames {
    const double *d[3], *nn[3], *w;
    double rows[7][CHUNK]; /* D, N and width where the batch makes them (batch_widths) */
    double gu[3][CHUNK], gv[3][CHUNK], su[CHUNK], sv[CHUNK];
    double gw[3][CHUNK]; /* band-limited solids: the gradient of w */
    /* for bumps: the unit tangents e1, e2 and the placed u's and v's derivatives along them
     * (du1, dv1, du2, dv2), as footprint_unit and placed_derivatives make them */
    double e1[3][CHUNK], e2[3][CHUNK], du[2][CHUNK], dv[2][CHUNK];
    int shared; /* gu, gv, gw, su, sv hold lane 0's only, which every lane shares */
};

/* The gradients g and scales of pm into lane l of fr (gw where solid) */
static void lane_mapping(struct frames *fr, int l, const tex_v3 g[3], const struct placement *pm,
                         int solid)
{
    for (int c = 0; c < 3; c++) {
        fr->gu[c][l] = (&g[0].x)[c], fr->gv[c][l] = (&g[1].x)[c];
        if (solid)
            fr->gw[c][l] = (&g[2].x)[c];
    }
    fr->su[l] = pm->su, fr->sv[l] = pm->sv;
}

#ifdef TEX_X86

/* a . b over three lanes of rows, in tex_v3_dot's order */
TEX_AVX512 static inline __m512d dot8(__m512d ax, __m512d ay, __m512d az, __m512d bx,
                                       __m512d by, __m512d bz)
{
    return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(ax, bx), _mm512_mul_pd(ay, by)),
                         _mm512_mul_pd(az, bz));
}

/* -x over lanes: the sign flipped, as C's unary minus does (for a zero too) */
TEX_AVX512 static inline __m512d neg8(__m512d x)
{
    return _mm512_castsi512_pd(
        _mm512_xor_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(INT64_MIN)));
}

/* footprint_tangents of the lanes in of fr from i on, operation for operation: t1, t2 (x, y,
 * z), l2 and c; the lanes seen head-on (no tangent from the ray) in the mask returned */
TEX_AVX512 static inline __attribute__((always_inline)) __mmask8
tangents8(const struct frames *fr, int i, __mmask8 in, __m512d t1[3], __m512d t2[3],
          __m512d *l2, __m512d *c)
{
    __m512d d[3], nn[3];
    for (int k = 0; k < 3; k++) {
        d[k] = _mm512_maskz_loadu_pd(in, fr->d[k] + i);
        nn[k] = _mm512_maskz_loadu_pd(in, fr->nn[k] + i);
    }
    __m512d dn = dot8(d[0], d[1], d[2], nn[0], nn[1], nn[2]), cosv = _mm512_abs_pd(dn);
    __m512d ndn = neg8(dn);
    for (int k = 0; k < 3; k++)
        t1[k] = _mm512_add_pd(d[k], _mm512_mul_pd(nn[k], ndn));
    *l2 = dot8(t1[0], t1[1], t1[2], t1[0], t1[1], t1[2]);
    for (int k = 0; k < 3; k++) /* N x t1 */
        t2[k] = _mm512_sub_pd(_mm512_mul_pd(nn[(k + 1) % 3], t1[(k + 2) % 3]),
                              _mm512_mul_pd(nn[(k + 2) % 3], t1[(k + 1) % 3]));
    __m512d lo = _mm512_set1_pd(0.02);
    *c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(cosv, lo, _CMP_GT_OQ), lo, cosv);
    return _mm512_cmp_pd_mask(*l2, _mm512_set1_pd(1e-18), _CMP_LT_OQ);
}

/* the lanes in of row a from lane i on; LDG: of a row the lanes may share (struct frames) */
#define LD(a) _mm512_maskz_loadu_pd(in, (a) + i)
#define LDG(a) (fr->shared ? _mm512_set1_pd((a)[0]) : LD(a))

/* footprint_width2 of the n <= 8 affine points from i on (footprint_tangents,
 * placed_derivatives and its end, operation for operation) into fw2[i...], and where bump,
 * the frames' bump members; returns the lanes seen head-on, which the scalar path takes. */
TEX_AVX512 static __mmask8 footprints8_avx512(struct frames *fr, int i, int n, int bump,
                                              double *fw2)
{
    __mmask8 in = (__mmask8)((1u << n) - 1);
    __m512d t1[3], t2[3], l2, c;
    __mmask8 headon = tangents8(fr, i, in, t1, t2, &l2, &c);
    __m512d t1x = t1[0], t1y = t1[1], t1z = t1[2], t2x = t2[0], t2y = t2[1], t2z = t2[2];
    __m512d gux = LDG(fr->gu[0]), guy = LDG(fr->gu[1]), guz = LDG(fr->gu[2]);
    __m512d gvx = LDG(fr->gv[0]), gvy = LDG(fr->gv[1]), gvz = LDG(fr->gv[2]);
    __m512d su = LDG(fr->su), sv = LDG(fr->sv), w = LD(fr->w);
    __m512d du0 = _mm512_mul_pd(dot8(gux, guy, guz, t1x, t1y, t1z), su);
    __m512d dv0 = _mm512_mul_pd(dot8(gvx, gvy, gvz, t1x, t1y, t1z), sv);
    __m512d du1 = _mm512_mul_pd(dot8(gux, guy, guz, t2x, t2y, t2z), su);
    __m512d dv1 = _mm512_mul_pd(dot8(gvx, gvy, gvz, t2x, t2y, t2z), sv);
    __m512d c2 = _mm512_mul_pd(c, c);
    __m512d l1 = _mm512_add_pd(_mm512_mul_pd(du0, du0), _mm512_mul_pd(dv0, dv0));
    __m512d m2 =
        _mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(du1, du1), _mm512_mul_pd(dv1, dv1)), c2);
    __m512d r = _mm512_mul_pd(_mm512_max_pd(l1, m2), _mm512_mul_pd(w, w)); /* l1 > m2 ? l1 : m2 */
    _mm512_mask_storeu_pd(fw2 + i, in, _mm512_div_pd(r, _mm512_mul_pd(l2, c2)));
    if (bump) { /* footprint_unit's tangents, placed_derivatives along them */
        __m512d s = _mm512_div_pd(_mm512_set1_pd(1), _mm512_sqrt_pd(l2));
        __m512d e1[3] = {_mm512_mul_pd(t1x, s), _mm512_mul_pd(t1y, s), _mm512_mul_pd(t1z, s)};
        __m512d e2[3] = {_mm512_mul_pd(t2x, s), _mm512_mul_pd(t2y, s), _mm512_mul_pd(t2z, s)};
        __m512d dd[4] = {
            _mm512_mul_pd(dot8(gux, guy, guz, e1[0], e1[1], e1[2]), su),
            _mm512_mul_pd(dot8(gvx, gvy, gvz, e1[0], e1[1], e1[2]), sv),
            _mm512_mul_pd(dot8(gux, guy, guz, e2[0], e2[1], e2[2]), su),
            _mm512_mul_pd(dot8(gvx, gvy, gvz, e2[0], e2[1], e2[2]), sv)};
        for (int c = 0; c < 3; c++) {
            _mm512_mask_storeu_pd(fr->e1[c] + i, in, e1[c]);
            _mm512_mask_storeu_pd(fr->e2[c] + i, in, e2[c]);
        }
        for (int c = 0; c < 4; c++)
            _mm512_mask_storeu_pd(c & 1 ? fr->dv[c / 2] + i : fr->du[c / 2] + i, in, dd[c]);
    }
    return headon & in;
}

/* The footprint widths of the n <= 8 band-limited solid points from i on, as
 * sqrt(solid_width2) makes them under an affine mapping (footprint_tangents, the three
 * gradients' derivatives along t1 and t2, operation for operation), into fw[i...]; returns
 * the lanes seen head-on, which the scalar path takes. */
TEX_AVX512 static __mmask8 solid_footprints8_avx512(const struct frames *fr, int i, int n,
                                                    double *fw)
{
    __mmask8 in = (__mmask8)((1u << n) - 1);
    __m512d t1[3], t2[3], l2, c;
    __mmask8 headon = tangents8(fr, i, in, t1, t2, &l2, &c);
    const double(*g[3])[CHUNK] = {fr->gu, fr->gv, fr->gw};
    __m512d sc[3] = {LDG(fr->su), LDG(fr->sv), _mm512_set1_pd(1)}, l1 = _mm512_setzero_pd();
    __m512d m2 = _mm512_setzero_pd(), w = LD(fr->w);
    for (int k = 0; k < 3; k++) { /* l1 += a a, m2 += b b, as solid_width2 sums them */
        __m512d gx = LDG(g[k][0]), gy = LDG(g[k][1]), gz = LDG(g[k][2]);
        __m512d a = _mm512_mul_pd(dot8(gx, gy, gz, t1[0], t1[1], t1[2]), sc[k]);
        __m512d b = _mm512_mul_pd(dot8(gx, gy, gz, t2[0], t2[1], t2[2]), sc[k]);
        l1 = _mm512_add_pd(l1, _mm512_mul_pd(a, a));
        m2 = _mm512_add_pd(m2, _mm512_mul_pd(b, b));
    }
    __m512d r = _mm512_div_pd(
        _mm512_mul_pd(_mm512_sqrt_pd(_mm512_mul_pd(l1, m2)), _mm512_mul_pd(w, w)),
        _mm512_mul_pd(c, l2));
    _mm512_mask_storeu_pd(fw + i, in, _mm512_sqrt_pd(r));
    return headon & in;
#undef LD
#undef LDG
}

/* mip_level of eight footprints fw2 on texture t: the levels (as 32-bit lanes) and the
 * weights *a of the next, operation for operation */
TEX_AVX512 static __m256i mip_levels8_avx512(const struct tex_texture *t, __m512d fw2,
                                               __m512d *a)
{
    const double *c = log2_poly;
    const tex_map *m0 = t->mip[0];
    int side = m0->w > m0->h ? m0->w : m0->h;
    __m512d x2 = _mm512_mul_pd(fw2, _mm512_set1_pd((double)side * side));
    __mmask8 minified = _mm512_cmp_pd_mask(x2, _mm512_set1_pd(1), _CMP_GT_OQ);
    __m512i bits = _mm512_castpd_si512(x2);
    __m512i e = _mm512_sub_epi64(_mm512_srli_epi64(bits, 52), _mm512_set1_epi64(1023));
    __m512i l = _mm512_srai_epi64(e, 1), top = _mm512_set1_epi64(t->nlevels - 1);
    __mmask8 below = _mm512_mask_cmplt_epi64_mask(minified, l, top); /* interpolated */
    __m512i mant = _mm512_and_si512(bits, _mm512_set1_epi64((INT64_C(1) << 52) - 1));
    __m512i mb = _mm512_or_si512(mant, _mm512_set1_epi64(INT64_C(1023) << 52));
    __m512d mm = _mm512_sub_pd(_mm512_castsi512_pd(mb), _mm512_set1_pd(1));
    __m512d lm = _mm512_set1_pd(c[6]);
    for (int i = 5; i >= 0; i--)
        lm = _mm512_add_pd(_mm512_mul_pd(lm, mm), _mm512_set1_pd(c[i]));
    __m512i e1 = _mm512_and_si512(e, _mm512_set1_epi64(1));
    __m512d odd = _mm512_cvtepi32_pd(_mm512_cvtepi64_epi32(e1));
    /* halved by a product: the same bits as mip_level's division by 2, without a division */
    __m512d w = _mm512_mul_pd(_mm512_add_pd(odd, _mm512_mul_pd(lm, mm)), _mm512_set1_pd(0.5));
    *a = _mm512_maskz_mov_pd(below, w);
    l = _mm512_mask_mov_epi64(_mm512_maskz_mov_epi64(minified, top), below, l);
    return _mm512_cvtepi64_epi32(l);
}

/* A texture's pyramid as bilinear8 looks it up: each level's width, height and texels'
 * offset (in floats) from level 0's, one level more repeating the last (0 beyond); below 16 levels
 * (maps up to 16384 wide) also in registers */
struct pyramid {
    int w[32], h[32];
    long long off[32];
    __m512i w16[2], h16[2], off8[2];
};

/* bilinear (k channels) of eight points (u, v) in [0, 1], each at its level lv of the
 * pyramid, into out[c]; g (or NULL): the derivatives of their mean along x and y in texels,
 * and the levels' widths and heights into wh[0], wh[1] */
TEX_AVX512 static void bilinear8_avx512(const struct tex_texture *t, const struct pyramid *py,
                                          int k, __m256i lv, __m512d u, __m512d v,
                                          __m256 out[3], __m512d g[2], __m512d wh[2])
{
    int nc = t->mip[0]->nc;
    __m256i w, h;
    __m512i base;
    if (t->nlevels < 16) { /* the tables in registers: permutes, not gathers */
        __m512i li = _mm512_castsi256_si512(lv);
        w = _mm512_castsi512_si256(_mm512_permutex2var_epi32(py->w16[0], li, py->w16[1]));
        h = _mm512_castsi512_si256(_mm512_permutex2var_epi32(py->h16[0], li, py->h16[1]));
        base = _mm512_permutex2var_epi64(py->off8[0], _mm512_cvtepi32_epi64(lv), py->off8[1]);
    } else {
        w = _mm256_i32gather_epi32(py->w, lv, 4), h = _mm256_i32gather_epi32(py->h, lv, 4);
        base = _mm512_i32gather_epi64(lv, py->off, 8);
    }
    __m512d x = _mm512_sub_pd(_mm512_mul_pd(u, _mm512_cvtepi32_pd(w)), _mm512_set1_pd(0.5));
    __m512d y = _mm512_sub_pd(_mm512_mul_pd(v, _mm512_cvtepi32_pd(h)), _mm512_set1_pd(0.5));
    __m512d one = _mm512_set1_pd(1);
    __m512d fx = _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(x)); /* floori */
    __m512d fy = _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(y));
    fx = _mm512_mask_sub_pd(fx, _mm512_cmp_pd_mask(fx, x, _CMP_GT_OQ), fx, one);
    fy = _mm512_mask_sub_pd(fy, _mm512_cmp_pd_mask(fy, y, _CMP_GT_OQ), fy, one);
    __m512d ax = _mm512_sub_pd(x, fx), ay = _mm512_sub_pd(y, fy);
    __m256i ix = _mm512_cvttpd_epi32(fx), iy = _mm512_cvttpd_epi32(fy);
    __m256i zero = _mm256_setzero_si256(), vnc = _mm256_set1_epi32(nc), c1 = _mm256_set1_epi32(1);
    /* texels' wrapping: x0 = ix < 0 ? w - 1 : ix, the next row and texel wrapping to 0 */
    __m256i x0 = _mm256_blendv_epi8(ix, _mm256_sub_epi32(w, c1), _mm256_cmpgt_epi32(zero, ix));
    __m256i y0 = _mm256_blendv_epi8(iy, _mm256_sub_epi32(h, c1), _mm256_cmpgt_epi32(zero, iy));
    __m256i wn = _mm256_mullo_epi32(w, vnc);
    __m256i r0 = _mm256_mullo_epi32(y0, wn), r1 = _mm256_add_epi32(r0, wn);
    r1 = _mm256_andnot_si256(_mm256_cmpeq_epi32(_mm256_add_epi32(y0, c1), h), r1);
    __m256i col0 = _mm256_mullo_epi32(x0, vnc), col1 = _mm256_add_epi32(col0, vnc);
    col1 = _mm256_andnot_si256(_mm256_cmpeq_epi32(col1, wn), col1);
    __m256i off[4] = {_mm256_add_epi32(r0, col0), _mm256_add_epi32(r0, col1),
                      _mm256_add_epi32(r1, col0), _mm256_add_epi32(r1, col1)};
    __m512i at[4];
    for (int j = 0; j < 4; j++)
        at[j] = _mm512_slli_epi64(_mm512_add_epi64(base, _mm512_cvtepi32_epi64(off[j])), 2);
    __m512d wx1 = _mm512_sub_pd(one, ax), wy1 = _mm512_sub_pd(one, ay), gx[3], gy[3];
    const float *px = t->mip[0]->px;
    __m512i pair[4]; /* colour: channels 0 and 1 of each texel in one 64-bit gather */
    for (int j = 0; k == 3 && j < 4; j++)
        pair[j] = _mm512_i64gather_epi64(at[j], px, 1);
    for (int ch = 0; ch < k; ch++) {
        __m512d q[4];
        for (int j = 0; j < 4; j++) {
            __m256 c = k == 3 && ch < 2 ? _mm256_castsi256_ps(_mm512_cvtepi64_epi32(
                                              ch ? _mm512_srli_epi64(pair[j], 32) : pair[j]))
                                        : _mm512_i64gather_ps(at[j], px + ch, 1);
            q[j] = _mm512_cvtps_pd(c);
        }
        __m512d top = _mm512_add_pd(_mm512_mul_pd(q[0], wx1), _mm512_mul_pd(q[1], ax));
        __m512d bot = _mm512_add_pd(_mm512_mul_pd(q[2], wx1), _mm512_mul_pd(q[3], ax));
        out[ch] = _mm512_cvtpd_ps(_mm512_add_pd(_mm512_mul_pd(top, wy1), _mm512_mul_pd(bot, ay)));
        if (g) { /* bilinear_dx along x, then along y */
            gx[ch] = _mm512_add_pd(_mm512_mul_pd(_mm512_sub_pd(q[1], q[0]), wy1),
                                   _mm512_mul_pd(_mm512_sub_pd(q[3], q[2]), ay));
            gy[ch] = _mm512_add_pd(_mm512_mul_pd(_mm512_sub_pd(q[2], q[0]), wx1),
                                   _mm512_mul_pd(_mm512_sub_pd(q[3], q[1]), ax));
        }
    }
    if (!g)
        return;
    if (k == 3) {
        __m512d three = _mm512_set1_pd(3);
        g[0] = _mm512_div_pd(_mm512_add_pd(_mm512_add_pd(gx[0], gx[1]), gx[2]), three);
        g[1] = _mm512_div_pd(_mm512_add_pd(_mm512_add_pd(gy[0], gy[1]), gy[2]), three);
    } else {
        g[0] = gx[0], g[1] = gy[0];
    }
    wh[0] = _mm512_cvtepi32_pd(w), wh[1] = _mm512_cvtepi32_pd(h);
}

/* tex_texture_points in vector lanes, eight points at a time */
TEX_AVX512 static void map_points_avx512(const struct tex_texture *t, int n, const double *u,
                                         const double *v, const double *fw2, float *out,
                                         double *grad)
{
    struct pyramid py;
    int k = t->mip[0]->nc < 3 ? 1 : 3;
    memset(py.w, 0, sizeof py.w), memset(py.h, 0, sizeof py.h), memset(py.off, 0, sizeof py.off);
    for (int l = 0; l <= t->nlevels; l++) { /* the levels a lookup can take; the rest 0 */
        const tex_map *m = t->mip[l < t->nlevels ? l : t->nlevels - 1];
        py.w[l] = m->w, py.h[l] = m->h;
        py.off[l] = ((intptr_t)m->px - (intptr_t)t->mip[0]->px) / (intptr_t)sizeof(float);
    }
    for (int r = 0; r < 2; r++) {
        py.w16[r] = _mm512_loadu_si512(py.w + 16 * r);
        py.h16[r] = _mm512_loadu_si512(py.h + 16 * r);
        py.off8[r] = _mm512_loadu_si512(py.off + 8 * r);
    }
    for (int i = 0; i < n; i += 8) {
        double pu[8], pv[8], pf[8]; /* the last eight padded with their first point */
        const double *ui = u + i, *vi = v + i, *fi = fw2 + i;
        if (n - i < 8) {
            for (int j = 0; j < 8; j++) {
                int q = i + (j < n - i ? j : 0);
                pu[j] = u[q], pv[j] = v[q], pf[j] = fw2[q];
            }
            ui = pu, vi = pv, fi = pf;
        }
        __m512d uu = _mm512_loadu_pd(ui), vv = _mm512_loadu_pd(vi), a;
        uu = _mm512_sub_pd(uu, _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(uu))); /* u -= (int)u */
        vv = _mm512_sub_pd(vv, _mm512_cvtepi32_pd(_mm512_cvttpd_epi32(vv)));
        __m256i lv = mip_levels8_avx512(t, _mm512_loadu_pd(fi), &a);
        __m256 o[3], o1[3];
        __m512d g[2], g1[2], wh[2], wh1[2], *gp = grad ? g : NULL, *gp1 = grad ? g1 : NULL;
        bilinear8_avx512(t, &py, k, lv, uu, vv, o, gp, wh);
        __mmask8 two = _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_GT_OQ);
        __m512d a1 = _mm512_sub_pd(_mm512_set1_pd(1), a);
        if (two) { /* trilinear: the next level's, weighted */
            bilinear8_avx512(t, &py, k, _mm256_add_epi32(lv, _mm256_set1_epi32(1)), uu, vv, o1,
                             gp1, wh1);
            for (int ch = 0; ch < k; ch++) { /* lanes of a = 0 keep their value */
                __m512d od = _mm512_cvtps_pd(o[ch]);
                __m512d mix = _mm512_add_pd(_mm512_mul_pd(od, a1),
                                            _mm512_mul_pd(_mm512_cvtps_pd(o1[ch]), a));
                o[ch] = _mm512_cvtpd_ps(_mm512_mask_blend_pd(two, od, mix));
            }
        }
        float f[3][8];
        for (int ch = 0; ch < 3; ch++)
            _mm256_storeu_ps(f[ch], o[k == 3 ? ch : 0]);
        for (int j = 0; j < 8 && i + j < n; j++)
            for (int ch = 0; ch < 3; ch++)
                out[3 * (i + j) + ch] = f[ch][j];
        if (!grad)
            continue;
        double gg[2][8];
        for (int d = 0; d < 2; d++) { /* map_eval's, per unit of u and of v */
            __m512d r = _mm512_mul_pd(g[d], wh[d]);
            if (two)
                r = _mm512_mask_blend_pd(
                    two, r,
                    _mm512_add_pd(_mm512_mul_pd(_mm512_mul_pd(g[d], wh[d]), a1),
                                  _mm512_mul_pd(_mm512_mul_pd(g1[d], wh1[d]), a)));
            _mm512_storeu_pd(gg[d], r);
        }
        for (int j = 0; j < 8 && i + j < n; j++)
            grad[2 * (i + j)] = gg[0][j], grad[2 * (i + j) + 1] = gg[1][j];
    }
}

/* fract in lanes: x - floord(x), floord's floor (+0 for -0: floor's -0 plus 0), and
 * x - x beyond 2^52 */
TEX_AVX512 static inline __m512d fract8_avx512(__m512d x)
{
    __mmask8 small = _mm512_cmp_pd_mask(_mm512_abs_pd(x), _mm512_set1_pd(4503599627370496.0),
                                        _CMP_LT_OQ);
    __m512d f = _mm512_add_pd(_mm512_roundscale_pd(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC),
                              _mm512_setzero_pd());
    return _mm512_sub_pd(x, _mm512_mask_blend_pd(small, x, f));
}

/* place over the lanes in from i on (the mapping's coordinates c0, c1, stored into u0, v0):
 * the placed ones into u, v; returns the lanes inside the window */
TEX_AVX512 static __mmask8 place8_avx512(const struct tex_apply *ap, const struct placement *pm,
                                         int i, __mmask8 in, __m512d c0, __m512d c1,
                                         double *u0, double *v0, double *u, double *v)
{
    _mm512_mask_storeu_pd(u0 + i, in, c0);
    _mm512_mask_storeu_pd(v0 + i, in, c1);
    __m512d s = _mm512_mul_pd(_mm512_sub_pd(c0, _mm512_set1_pd(ap->u1)), _mm512_set1_pd(pm->iu));
    __m512d t = _mm512_mul_pd(_mm512_sub_pd(c1, _mm512_set1_pd(ap->v1)), _mm512_set1_pd(pm->iv));
    __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1);
    __mmask8 inside = _mm512_mask_cmp_pd_mask(in, s, zero, _CMP_GE_OQ) &
                      _mm512_cmp_pd_mask(s, one, _CMP_LE_OQ) &
                      _mm512_cmp_pd_mask(t, zero, _CMP_GE_OQ) &
                      _mm512_cmp_pd_mask(t, one, _CMP_LE_OQ);
    _mm512_mask_storeu_pd(u + i, in, _mm512_mul_pd(s, _mm512_set1_pd(ap->nu)));
    _mm512_mask_storeu_pd(v + i, in, _mm512_mul_pd(t, _mm512_set1_pd(ap->nv)));
    return inside;
}

/* Row k of the affine map m applied to the lanes x, y, z, in tex_xform_point's order */
TEX_AVX512 static inline __m512d xform_row8(const double *r, __m512d x, __m512d y, __m512d z)
{
    __m512d a = _mm512_add_pd(_mm512_mul_pd(_mm512_set1_pd(r[0]), x),
                              _mm512_mul_pd(_mm512_set1_pd(r[1]), y));
    return _mm512_add_pd(_mm512_add_pd(a, _mm512_mul_pd(_mm512_set1_pd(r[2]), z)),
                         _mm512_set1_pd(r[3]));
}

/* map_hit of a plane's planar mapping over the lanes in of L's points from i on, operation
 * for operation (tex_xform_point's x and z, map_point_at, place): the mapping's coordinates
 * into u0, v0, the placed ones into u, v; returns the lanes inside the window */
TEX_AVX512 static __mmask8 plane_map8_avx512(const struct tex_lanes *L, int i, __mmask8 in,
                                             double *u0, double *v0, double *u, double *v)
{
    const struct tex_apply *ap = L->sf->apply;
    const double(*m)[4] = L->leaf->to_obj.m;
    __m512d x = _mm512_maskz_loadu_pd(in, L->p[0] + i), y = _mm512_maskz_loadu_pd(in, L->p[1] + i);
    __m512d z = _mm512_maskz_loadu_pd(in, L->p[2] + i), sc = _mm512_set1_pd(ap->scale);
    __m512d c0 = fract8_avx512(_mm512_mul_pd(xform_row8(m[0], x, y, z), sc));
    __m512d c1 = fract8_avx512(_mm512_mul_pd(xform_row8(m[2], x, y, z), sc));
    return place8_avx512(ap, L->sf->cache->placement, i, in, c0, c1, u0, v0, u, v);
}

/* fmin(1, fmax(0, x)) over lanes, NaN to 0 as there */
TEX_AVX512 static inline __m512d clamp8(__m512d x)
{
    __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1);
    __m512d a = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(x, zero, _CMP_GT_OQ), zero, x);
    return _mm512_mask_blend_pd(_mm512_cmp_pd_mask(a, one, _CMP_LT_OQ), one, a);
}

/* (a + 1) / 2 over lanes, clamped: a coordinate across a box face or a cap */
TEX_AVX512 static inline __m512d across8(__m512d a)
{
    return clamp8(_mm512_div_pd(_mm512_add_pd(a, _mm512_set1_pd(1)), _mm512_set1_pd(2)));
}

/* box_uv over lanes (p: the object-space point): u, v and the face */
TEX_AVX512 static void box_uv8(const __m512d p[3], __m512d *u, __m512d *v, __m512i *face)
{
    __m512d zero = _mm512_setzero_pd(), ax = _mm512_abs_pd(p[0]), ay = _mm512_abs_pd(p[1]);
    __m512d az = _mm512_abs_pd(p[2]);
    __mmask8 fx = _mm512_cmp_pd_mask(ax, ay, _CMP_GE_OQ) & _mm512_cmp_pd_mask(ax, az, _CMP_GE_OQ);
    __mmask8 fy = ~fx & _mm512_cmp_pd_mask(ay, az, _CMP_GE_OQ), fz = ~(fx | fy);
    __mmask8 pos = (fx & _mm512_cmp_pd_mask(p[0], zero, _CMP_GT_OQ)) |
                   (fy & _mm512_cmp_pd_mask(p[1], zero, _CMP_GT_OQ)) |
                   (fz & _mm512_cmp_pd_mask(p[2], zero, _CMP_GT_OQ));
    __m512i f = _mm512_mask_blend_epi64(fy, _mm512_set1_epi64(5), _mm512_set1_epi64(3));
    f = _mm512_mask_blend_epi64(fx, f, _mm512_set1_epi64(1));
    *face = _mm512_mask_add_epi64(f, ~pos, f, _mm512_set1_epi64(1));
    /* faces 1..6: a = -z z x x x -x, b = -y -y z -z -y -y */
    __m512d nx = neg8(p[0]), ny = neg8(p[1]), nz = neg8(p[2]);
    __m512d a = _mm512_mask_blend_pd(fz & ~pos, p[0], nx);
    a = _mm512_mask_blend_pd(fx, a, _mm512_mask_blend_pd(pos, p[2], nz));
    __m512d b = _mm512_mask_blend_pd(fy, ny, _mm512_mask_blend_pd(pos, nz, p[2]));
    *u = across8(a), *v = across8(b);
}

/* tex_turns over lanes */
TEX_AVX512 static __m512d turns8(__m512d y, __m512d x)
{
    double ya[8], xa[8], r[8];
    _mm512_storeu_pd(ya, y), _mm512_storeu_pd(xa, x);
    tex_atan2_n(8, ya, xa, r);
    __m512d a = _mm512_div_pd(_mm512_loadu_pd(r), _mm512_set1_pd(2 * M_PI));
    __mmask8 neg = _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_LT_OQ);
    return _mm512_mask_add_pd(a, neg, a, _mm512_set1_pd(1));
}

/* tex_polar over lanes */
TEX_AVX512 static __m512d polar8(__m512d c)
{
    __m512d one = _mm512_set1_pd(1), m = _mm512_set1_pd(-1);
    double ya[8], xa[8], r[8]; /* fmin(1, c) (NaN to 1), then fmax(-1, that) */
    c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(c, one, _CMP_LT_OQ), one, c);
    c = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(c, m, _CMP_GT_OQ), m, c);
    _mm512_storeu_pd(xa, c);
    _mm512_storeu_pd(ya, _mm512_sqrt_pd(_mm512_mul_pd(_mm512_sub_pd(one, c),
                                                      _mm512_add_pd(one, c))));
    tex_atan2_n(8, ya, xa, r);
    return _mm512_div_pd(_mm512_loadu_pd(r), _mm512_set1_pd(M_PI));
}

/* cone_uv (cone_part and all) over lanes (p: the object-space point) */
TEX_AVX512 static void cone_uv8(const struct tex_object *ob, const __m512d p[3], __m512d *u,
                                __m512d *v, __m512i *face)
{
    double k = ob->r1 - ob->r0, den = sqrt(1 + (ob->r1 - ob->r0) * (ob->r1 - ob->r0));
    __m512d one = _mm512_set1_pd(1);
    __m512d ry = _mm512_add_pd(_mm512_set1_pd(ob->r0), _mm512_mul_pd(_mm512_set1_pd(k), p[1]));
    __m512d rho = _mm512_sqrt_pd(
        _mm512_add_pd(_mm512_mul_pd(p[0], p[0]), _mm512_mul_pd(p[2], p[2])));
    __m512d side = _mm512_div_pd(_mm512_abs_pd(_mm512_sub_pd(rho, ry)), _mm512_set1_pd(den));
    __m512d bot = _mm512_abs_pd(p[1]), top = _mm512_abs_pd(_mm512_sub_pd(p[1], one));
    __mmask8 s0 = _mm512_cmp_pd_mask(side, bot, _CMP_LE_OQ) &
                  _mm512_cmp_pd_mask(side, top, _CMP_LE_OQ);
    __mmask8 part1 = ~s0 & _mm512_cmp_pd_mask(bot, top, _CMP_LE_OQ);
    /* the caps: discs of radius r across [0, 1]^2 */
    __m512d r = _mm512_mask_blend_pd(part1, _mm512_set1_pd(ob->r1 > 0 ? ob->r1 : 1),
                                     _mm512_set1_pd(ob->r0 > 0 ? ob->r0 : 1));
    __m512d cu = across8(_mm512_div_pd(p[0], r)), cv = across8(_mm512_div_pd(p[2], r));
    *u = s0 ? _mm512_mask_blend_pd(s0, cu, turns8(neg8(p[2]), p[0])) : cu; /* caps alone */
    *v = _mm512_mask_blend_pd(s0, cv, clamp8(_mm512_sub_pd(one, p[1])));
    *face = _mm512_mask_blend_epi64(s0, _mm512_mask_blend_epi64(part1, _mm512_set1_epi64(3),
                                                                _mm512_set1_epi64(2)),
                                    _mm512_set1_epi64(1));
}

/* sphere_uv over lanes (p: the object-space point) */
TEX_AVX512 static void sphere_uv8(const __m512d p[3], __m512d *u, __m512d *v)
{
    __m512d r = _mm512_sqrt_pd(dot8(p[0], p[1], p[2], p[0], p[1], p[2]));
    __mmask8 pos = _mm512_cmp_pd_mask(r, _mm512_setzero_pd(), _CMP_GT_OQ);
    *u = turns8(neg8(p[2]), p[0]);
    *v = _mm512_mask_blend_pd(pos, _mm512_set1_pd(0.5), polar8(_mm512_div_pd(p[1], r)));
}

/* point_gradient of a natural mapping over the lanes in (natural_gradient at the
 * object-space points p on faces f, then to world space), operation for operation, into
 * fr's rows from i on, with the placement's scales; returns the lanes that have them */
/* u's gradient around the axis over lanes, (z, 0, -x) / (2 pi rho2), into g */
TEX_AVX512 static inline void around8(const __m512d p[3], __m512d rho2, __m512d g[3])
{
    __m512d s = _mm512_div_pd(_mm512_set1_pd(1), _mm512_mul_pd(_mm512_set1_pd(2 * M_PI), rho2));
    g[0] = _mm512_mul_pd(p[2], s), g[1] = _mm512_mul_pd(_mm512_setzero_pd(), s);
    g[2] = _mm512_mul_pd(neg8(p[0]), s);
}

TEX_AVX512 static __mmask8 natural_gradient8_avx512(const struct tex_object *leaf,
                                                    const struct placement *pm, __mmask8 in,
                                                    const __m512d p[3], __m512i f,
                                                    struct frames *fr, int i)
{
    __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1), g[2][3];
    __m512d rho2 = _mm512_add_pd(_mm512_mul_pd(p[0], p[0]), _mm512_mul_pd(p[2], p[2]));
    __mmask8 ok = in;
    if (leaf->kind == TEX_SHAPE_BOX) { /* box_axes: +-1/2 along one axis, by face */
        double tab[2][3][8] = {{{0}}};
        for (int fc = 0; fc < 6; fc++)
            for (int k = 0; k < 2; k++) {
                int c = box_axes[fc][k];
                tab[k][(c < 0 ? -c : c) - 1][fc] = c < 0 ? -0.5 : 0.5;
            }
        __m512i idx = _mm512_sub_epi64(f, _mm512_set1_epi64(1));
        for (int k = 0; k < 2; k++)
            for (int c = 0; c < 3; c++)
                g[k][c] = _mm512_permutexvar_pd(idx, _mm512_loadu_pd(tab[k][c]));
    } else if (leaf->kind == TEX_SHAPE_SPHERE) { /* v = acos(y / r) / pi */
        __m512d r2 = _mm512_add_pd(rho2, _mm512_mul_pd(p[1], p[1]));
        ok &= _mm512_cmp_pd_mask(rho2, _mm512_mul_pd(_mm512_set1_pd(1e-12), r2), _CMP_GT_OQ);
        __m512d k = _mm512_div_pd(one, _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(M_PI),
                                                                   _mm512_sqrt_pd(rho2)), r2));
        around8(p, rho2, g[0]);
        g[1][0] = _mm512_mul_pd(_mm512_mul_pd(p[0], p[1]), k);
        g[1][1] = _mm512_mul_pd(neg8(rho2), k);
        g[1][2] = _mm512_mul_pd(_mm512_mul_pd(p[2], p[1]), k);
    } else { /* the side (face 1): around, v = 1 - y; the caps: discs of radius r */
        __mmask8 side = _mm512_cmp_epi64_mask(f, _mm512_set1_epi64(1), _MM_CMPINT_EQ);
        ok &= ~side | _mm512_cmp_pd_mask(rho2, _mm512_set1_pd(1e-24), _CMP_GT_OQ);
        __mmask8 bottom = _mm512_cmp_epi64_mask(f, _mm512_set1_epi64(2), _MM_CMPINT_EQ);
        double r0 = leaf->r0 > 0 ? leaf->r0 : 1, r1 = leaf->r1 > 0 ? leaf->r1 : 1;
        __m512d r = _mm512_mask_blend_pd(bottom, _mm512_set1_pd(r1), _mm512_set1_pd(r0));
        __m512d h = _mm512_div_pd(_mm512_set1_pd(0.5), r), around[3];
        around8(p, rho2, around);
        g[0][0] = _mm512_mask_blend_pd(side, h, around[0]);
        g[0][1] = _mm512_mask_blend_pd(side, zero, around[1]);
        g[0][2] = _mm512_mask_blend_pd(side, zero, around[2]);
        g[1][0] = zero;
        g[1][1] = _mm512_mask_blend_pd(side, zero, _mm512_set1_pd(-1));
        g[1][2] = _mm512_mask_blend_pd(side, h, zero);
    }
    const double(*m)[4] = leaf->to_obj.m;
    double(*rows[2])[CHUNK] = {fr->gu, fr->gv};
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 3; c++) /* tex_xform_normal: the transpose */
            _mm512_mask_storeu_pd(rows[k][c] + i, in,
                                  dot8(_mm512_set1_pd(m[0][c]), _mm512_set1_pd(m[1][c]),
                                       _mm512_set1_pd(m[2][c]), g[k][0], g[k][1], g[k][2]));
    _mm512_mask_storeu_pd(fr->su + i, in, _mm512_set1_pd(pm->su));
    _mm512_mask_storeu_pd(fr->sv + i, in, _mm512_set1_pd(pm->sv));
    return ok;
}

/* map_hit of a natural mapping on a box, cylinder, cone or sphere over the lanes in of L's
 * points from i on, operation for operation (tex_xform_point, the shape's uv, place), as
 * plane_map8_avx512 does a plane's, each lane's face into face[]; and their gradients into
 * fr's rows (natural_gradient8_avx512).  Returns the lanes inside the window that have
 * gradients. */
TEX_AVX512 static __mmask8 natural_map8_avx512(const struct tex_lanes *L, int i, __mmask8 in,
                                               double *u0, double *v0, double *u, double *v,
                                               int *face, struct frames *fr)
{
    const struct tex_object *leaf = L->leaf;
    const struct placement *pm = L->sf->cache->placement;
    const double(*m)[4] = leaf->to_obj.m;
    __m512d x = _mm512_maskz_loadu_pd(in, L->p[0] + i), y = _mm512_maskz_loadu_pd(in, L->p[1] + i);
    __m512d z = _mm512_maskz_loadu_pd(in, L->p[2] + i), p[3], c0, c1;
    __m512i f = _mm512_set1_epi64(1);
    for (int k = 0; k < 3; k++)
        p[k] = xform_row8(m[k], x, y, z);
    if (leaf->kind == TEX_SHAPE_BOX)
        box_uv8(p, &c0, &c1, &f);
    else if (leaf->kind == TEX_SHAPE_SPHERE)
        sphere_uv8(p, &c0, &c1);
    else
        cone_uv8(leaf, p, &c0, &c1, &f);
    _mm512_mask_cvtepi64_storeu_epi32(face + i, in, f);
    return place8_avx512(L->sf->apply, pm, i, in, c0, c1, u0, v0, u, v) &
           natural_gradient8_avx512(leaf, pm, in, p, f, fr, i);
}
#endif

void tex_texture_points(const struct tex_texture *t, int n, const double *u, const double *v,
                        const double *fw2, float *out, double *grad)
{
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX512 && t->nlevels < 32) { /* struct pyramid's room */
        map_points_avx512(t, n, u, v, fw2, out, grad);
        return;
    }
#endif
    for (int i = 0; i < n; i++)
        texture_eval(t, u[i], v[i], 0, fw2[i], out + 3 * i, grad ? grad + 2 * i : NULL);
}

/* The j-th texture sf applies */
static const struct tex_apply *apply_at(const struct tex_surface *sf, int j)
{
    const struct tex_apply *ap = sf->apply;
    while (j-- > 0)
        ap = ap->next;
    return ap;
}

/* The footprint of hit pf's texture j (mapping a) on the hit's own frame, as
 * apply_textures takes it: a band-limited solid's width (solid), else a map's
 * footprint_width2 */
static double scalar_width(const struct tex_prefetch *pf, int j, const struct tex_prefetch_ap *a,
                           int solid)
{
    const struct tex_apply *ap = apply_at(pf->sf, j);
    const struct placement *pm = pf->sf->cache->placement + j;
    struct footprint fp;
    footprint_at(&fp, &pf->D, &pf->N, pf->width);
    return solid ? sqrt(solid_width2(ap, pm, pf->leaf, &fp, &pf->P, &pf->pl, a->uvw0))
                 : footprint_width2(ap, pm, pf->leaf, &fp, &pf->P, &pf->pl, a->face, a->uvw0[0],
                                    a->uvw0[1]);
}

/* The footprints fw of n pending points of one texture (hit[i], its texture number j[i]
 * there, or the first where j is NULL; mapping a[i]), as scalar_width makes them: 0
 * unfiltered; in vector lanes where the CPU has AVX-512 those whose mapping has gradients
 * (affine, or a map's point_gradient), but those seen head-on.  A map's (solid 0) also
 * gives, where lane is given, the lane of fr of each point (else -1) and, where bump, the
 * frames' bump members. */
static void batch_widths(int n, struct tex_prefetch *const *hit, struct tex_prefetch_ap *const *a,
                         const int *j, int solid, int bump, struct frames *fr, double *fw,
                         int *lane)
{
    for (int c = 0; c < 3; c++) /* the frames' rows: fr's own */
        fr->d[c] = fr->rows[c], fr->nn[c] = fr->rows[3 + c];
    fr->w = fr->rows[6];
    int lanes = 0, at[CHUNK], affine = 0, simd = tex_simd_level() >= TEX_SIMD_AVX512;
    /* the gradients' leaf and texture, kept while hits share them; lane 0's (leaf0, ap0) */
    const struct tex_object *leaf = NULL, *leaf0 = NULL;
    const struct tex_apply *gap = NULL, *ap = NULL, *ap0 = NULL;
    const struct tex_surface *sf = NULL; /* ap and pm's, kept while hits share them */
    const struct placement *pm = NULL, *pm0 = NULL;
    tex_v3 g[3], g0[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; /* g0, pm0: lane 0's */
    tex_v3 pg[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; /* a point's own (point_gradient) */
    for (int i = 0, jk = -1; i < n; i++) {
        const struct tex_prefetch *pf = hit[i];
        int ji = j ? j[i] : 0; /* the point's texture number at its hit */
        if (pf->sf != sf || ji != jk) {
            sf = pf->sf, jk = ji;
            ap = apply_at(sf, jk), pm = sf->cache->placement + jk;
        }
        fw[i] = 0;
        if (lane)
            lane[i] = -1;
        if (!(pf->width > 0))
            continue;
        if (simd && (pf->leaf != leaf || ap != gap))
            affine = map_gradient(gap = ap, leaf = pf->leaf, g);
        /* own: a mapping that is not affine, its gradients the point's own */
        int own = simd && !affine && !solid && point_gradient(ap, leaf, &pf->pl, a[i]->face, pg);
        if (!simd || (!affine && !own)) {
            fw[i] = scalar_width(pf, ji, a[i], solid);
            continue;
        }
        const double *d = &pf->D.x, *nn = &pf->N.x;
        for (int c = 0; c < 3; c++)
            fr->rows[c][lanes] = d[c], fr->rows[3 + c][lanes] = nn[c];
        fr->rows[6][lanes] = pf->width;
        if (!lanes) { /* lane 0's mapping, which the lanes share until one differs */
            fr->shared = !own, leaf0 = leaf, ap0 = gap, pm0 = pm;
            memcpy(g0, g, sizeof g0);
        } else if (fr->shared && (own || leaf != leaf0 || gap != ap0)) {
            for (int k = fr->shared = 0; k < lanes; k++) /* no longer shared: written out */
                lane_mapping(fr, k, g0, pm0, solid);
        }
        if (!lanes || !fr->shared)
            lane_mapping(fr, lanes, own ? pg : g, pm, solid);
        at[lanes++] = i;
    }
#ifdef TEX_X86
    double lw[CHUNK];
    for (int l = 0; l < lanes; l += 8) {
        int m = lanes - l < 8 ? lanes - l : 8;
        __mmask8 headon = solid ? solid_footprints8_avx512(fr, l, m, lw)
                                : footprints8_avx512(fr, l, m, bump, lw);
        for (int k = l; k < l + m; k++) {
            int on = !(headon >> (k - l) & 1), i = at[k];
            fw[i] = on ? lw[k] : scalar_width(hit[i], j ? j[i] : 0, a[i], solid);
            if (lane)
                lane[i] = on ? k : -1;
        }
    }
#endif
}

/* bump_tilt's direction (before its strength) from a map's gradient grad and the footprint
 * in lane l of fr */
static void lane_tilt(const struct frames *fr, int l, const double grad[2], double tilt[3])
{
    double du[2] = {fr->du[0][l], fr->du[1][l]}, dv[2] = {fr->dv[0][l], fr->dv[1][l]};
    double g[2] = {0, 0}; /* made from grad (tilt_along) */
    tex_v3 e1 = tex_v3_make(fr->e1[0][l], fr->e1[1][l], fr->e1[2][l]);
    tex_v3 e2 = tex_v3_make(fr->e2[0][l], fr->e2[1][l], fr->e2[2][l]);
    tex_v3 d = tilt_along(grad, du, dv, g, e1, e2);
    tilt[0] = d.x, tilt[1] = d.y, tilt[2] = d.z;
}

/* A map's lookup into the record a of its point: the value val (RGB), the footprint fw2 and,
 * where bumped, the gradient grad and, where the footprint was made in lane l of fr (else
 * l < 0), the tilt's direction */
static void lookup_record(struct tex_prefetch_ap *a, const float val[3], double fw2,
                          const double *grad, const struct frames *fr, int l)
{
    memcpy(a->val, val, 3 * sizeof *val);
    if (grad)
        a->grad[0] = grad[0], a->grad[1] = grad[1];
    if (grad && l >= 0)
        lane_tilt(fr, l, grad, a->tilt);
    a->has_tilt = grad && l >= 0;
    a->fw = fw2;
    a->has_val = 1;
}

/* The values of n pending points a[i] of mip-mapped texture t (hits hit[i], placed at u, v)
 * and their footprints, as apply_textures would look them up: into a[i]->val as RGB, the
 * footprint (squared) into a[i]->fw; bumped, the gradient and (from the lanes) the tilt's
 * direction. */
static void map_batch(const struct tex_texture *t, int n, struct tex_prefetch *const *hit,
                      struct tex_prefetch_ap *const *a, const double *u, const double *v)
{
    struct frames fr;
    double fw2[CHUNK], grad[2 * CHUNK], *gp = NULL;
    float out[3 * CHUNK];
    int lane[CHUNK];
    for (int i = 0; i < n && !gp; i++)
        if (a[i]->bump) /* then every point's gradient */
            gp = grad;
    batch_widths(n, hit, a, NULL, 0, gp != NULL, &fr, fw2, lane);
    tex_texture_points(t, n, u, v, fw2, out, gp);
    for (int i = 0; i < n; i++)
        lookup_record(a[i], out + 3 * i, fw2[i], gp ? gp + 2 * i : NULL, &fr, lane[i]);
}

void tex_prefetch_map(struct tex_prefetch *pf, const struct tex_surface *sf,
                      const struct tex_object *leaf, const tex_v3 *P)
{
    const struct placement *pm = sf->cache->placement;
    pf->sf = sf;
    pf->n = 0;
    pf->width = 0;
    if (!sf->apply) /* untextured: nothing to look up */
        return;
    pf->leaf = leaf;
    pf->P = *P;
    pf->pl = tex_xform_point(&leaf->to_obj, *P);
    for (const struct tex_apply *ap = sf->apply; ap && pf->n < TEX_PREFETCH_MAX;
         ap = ap->next, pm++) {
        struct tex_prefetch_ap *a = &pf->ap[pf->n++];
        map_hit(ap, pm, leaf, P, &pf->pl, a);
        /* the first texture only: a later one may find the footprint's tangents normalised
         * by an earlier one (footprint_unit), which the batch does not follow */
        if (pf->n == 1 && map_ahead(ap))
            a->pending = a->inside;
    }
}

/* Whether the lanes map hits of ap on leaf: a plane's planar mapping, or a natural one on a
 * box, cylinder, cone or sphere */
static int lanes_mapping(const struct tex_apply *ap, const struct tex_object *leaf)
{
    int k = leaf->kind;
    return plane_planar(ap, leaf) ||
           (ap->mapping == TEX_MAP_NATURAL && (k == TEX_SHAPE_BOX || k == TEX_SHAPE_CYLINDER ||
                                               k == TEX_SHAPE_CONE || k == TEX_SHAPE_SPHERE));
}

int tex_lanes_take(struct tex_lanes *L, struct tex_prefetch *pf, const struct tex_surface *sf,
                   const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *D,
                   const tex_v3 *N, double width)
{
    if (!sf->cache->lanes || !(width > 0) || L->n == TEX_LANES ||
        (L->n && (L->leaf != leaf || L->sf != sf)) || !lanes_mapping(sf->apply, leaf))
        return 0;
    int i = L->n++;
    L->sf = sf, L->leaf = leaf, L->pf[i] = pf;
    L->p[0][i] = P->x, L->p[1][i] = P->y, L->p[2][i] = P->z;
    L->d[0][i] = D->x, L->d[1][i] = D->y, L->d[2][i] = D->z;
    L->nn[0][i] = N->x, L->nn[1][i] = N->y, L->nn[2][i] = N->z;
    L->w[i] = width;
    return 1;
}

/* Queued hit i of L, which the lanes could not finish, mapped the usual way */
static void lanes_leftover(const struct tex_lanes *L, int i)
{
    tex_v3 P = tex_v3_make(L->p[0][i], L->p[1][i], L->p[2][i]);
    tex_v3 D = tex_v3_make(L->d[0][i], L->d[1][i], L->d[2][i]);
    tex_v3 N = tex_v3_make(L->nn[0][i], L->nn[1][i], L->nn[2][i]);
    tex_prefetch_map(L->pf[i], L->sf, L->leaf, &P);
    tex_prefetch_footprints(L->pf[i], &D, &N, L->w[i]);
}

#ifdef TEX_X86
/* Record pf of a hit the lanes finished, in lane l of fr: map_hit's fields (face: the
 * mapping's), then the lookup's (grad: a bump's gradient, else NULL) */
static void lanes_record(const struct tex_lanes *L, struct tex_prefetch *pf, int face,
                         double u0, double v0, double u, double v, double fw2,
                         const float val[3], const struct frames *fr, int l, const double *grad)
{
    struct tex_prefetch_ap *a = &pf->ap[0];
    pf->sf = L->sf, pf->leaf = L->leaf, pf->n = 1;
    a->tex = L->sf->apply->tex;
    a->face = face, a->inside = 1, a->pending = 0;
    a->bump = L->sf->cache->placement[0].bump;
    a->uvw0[0] = u0, a->uvw0[1] = v0, a->uvw0[2] = 0;
    a->uvw[0] = u, a->uvw[1] = v, a->uvw[2] = 0;
    lookup_record(a, val, fw2, grad, fr, l);
}
#endif

int tex_prefetch_lanes(struct tex_lanes *L, struct tex_prefetch **rest)
{
    int n = L->n, nrest = 0;
    L->n = 0;
    if (!n)
        return 0;
#ifdef TEX_X86
    struct frames fr;
    /* u, v and fw2: the finished hits' moved to the front, at[] giving their lanes (set to 0
     * first: gcc cannot follow the masked stores that fill them) */
    double u0[TEX_LANES], v0[TEX_LANES], u[TEX_LANES] = {0}, v[TEX_LANES] = {0};
    double fw2[TEX_LANES] = {0};
    float out[3 * TEX_LANES];
    int at[TEX_LANES], m = 0, bump = L->sf->cache->placement[0].bump;
    int face[TEX_LANES], natural = L->leaf->kind != TEX_SHAPE_PLANE;
    double grad[2 * TEX_LANES];
    tex_v3 g[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    _Static_assert(TEX_LANES <= CHUNK, "a struct frames holds the lanes");
    for (int c = 0; c < 3; c++)
        fr.d[c] = L->d[c], fr.nn[c] = L->nn[c];
    fr.w = L->w;
    fr.shared = !natural; /* a plane's mapping is affine: every lane shares lane 0's */
    if (!natural) {
        map_gradient(L->sf->apply, L->leaf, g);
        lane_mapping(&fr, 0, g, L->sf->cache->placement, 0);
    }
    for (int i = 0; i < n; i += 8) {
        int k = n - i < 8 ? n - i : 8;
        __mmask8 in = (__mmask8)((1u << k) - 1);
        __mmask8 inside = natural ? natural_map8_avx512(L, i, in, u0, v0, u, v, face, &fr)
                                  : plane_map8_avx512(L, i, in, u0, v0, u, v);
        __mmask8 done = inside & ~footprints8_avx512(&fr, i, k, bump, fw2);
        for (int j = i; j < i + k; j++) {
            if (done >> (j - i) & 1)
                u[m] = u[j], v[m] = v[j], fw2[m] = fw2[j], at[m++] = j;
            else
                lanes_leftover(L, j), rest[nrest++] = L->pf[j];
        }
    }
    tex_texture_points(L->sf->apply->tex, m, u, v, fw2, out, bump ? grad : NULL);
    for (int q = 0; q < m; q++)
        lanes_record(L, L->pf[at[q]], natural ? face[at[q]] : 1, u0[at[q]], v0[at[q]], u[q],
                     v[q], fw2[q], out + 3 * q, &fr, at[q], bump ? grad + 2 * q : NULL);
#else
    for (int i = 0; i < n; i++)
        lanes_leftover(L, i), rest[nrest++] = L->pf[i];
#endif
    return nrest;
}

int tex_surface_footprints(const struct tex_surface *sf)
{
    return sf->cache->footprints;
}

void tex_prefetch_footprints(struct tex_prefetch *pf, const tex_v3 *D, const tex_v3 *N,
                             double width)
{
    if (width > 0) /* the frame of the footprints tex_prefetch_eval makes, on apply_textures' N */
        pf->D = *D, pf->N = *N, pf->width = width;
}

void tex_prefetch_eval(struct tex_prefetch *const *pf, int n)
{
    double u[CHUNK], v[CHUNK], w[CHUNK], fw[CHUNK]; /* fw: band-limited solids' footprints */
    float out[CHUNK * TEX_MAP_MAX_CHANNELS];
    struct frames fr;
    struct tex_prefetch_ap *who[CHUNK];
    struct tex_prefetch *hit[CHUNK];
    int at[CHUNK]; /* the point's texture number at its hit */
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < pf[i]->n; j++) {
            if (!pf[i]->ap[j].pending)
                continue;
            /* every pending point of this primitive from here on, up to a chunk */
            const struct tex_texture *t = pf[i]->ap[j].tex;
            int m = 0;
            for (int k = i; k < n && m < CHUNK; k++) {
                for (int l = k == i ? j : 0; l < pf[k]->n && m < CHUNK; l++) {
                    struct tex_prefetch_ap *b = &pf[k]->ap[l];
                    if (!b->pending || b->tex != t)
                        continue;
                    b->pending = 0;
                    who[m] = b, hit[m] = pf[k], at[m] = l;
                    u[m] = b->uvw[0], v[m] = b->uvw[1], w[m] = b->uvw[2], fw[m] = 0;
                    m++;
                }
            }
            if (t->mip) {
                map_batch(t, m, hit, who, u, v);
                continue;
            }
            if (band_limited(t))
                batch_widths(m, hit, who, at, 1, 0, &fr, fw, NULL);
            field_points(t, m, u, v, w, fw, out);
            int nc = t->field->nc;
            for (int q = 0; q < m; q++) {
                memset(who[q]->val, 0, sizeof who[q]->val);
                memcpy(who[q]->val, out + (size_t)q * nc, nc * sizeof *out);
                who[q]->has_val = 1;
            }
        }
    }
}

int tex_surface_cache(struct tex_surface *sf, const struct tex_colour_space *cs)
{
    int textured = 0, nfn = 0, nap = 0; /* textured: bits of enum tex_sparam */
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next, nap++)
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++)
            textured |= 1 << fn->param;
    tex_surface_uncache(sf);
    struct tex_surface_cache *c = calloc(1, sizeof *c);
    sf->cache = c;
    if (!c || !(c->poly = malloc((nfn ? nfn : 1) * sizeof *c->poly)) ||
        !(c->compiled = malloc(nfn ? nfn : 1)) ||
        !(c->placement = malloc((nap ? nap : 1) * sizeof *c->placement))) {
        tex_surface_uncache(sf);
        return tex_error("out of memory");
    }
    nfn = nap = 0;
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next) {
        placement_of(ap, &c->placement[nap]);
        c->footprints |= band_limited(ap->tex) || (!nap && map_ahead(ap));
        c->direct = !nap && !ap->next && map_ahead(ap);
        nap++;
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next, nfn++) {
            c->direct &= !fn->region && fn->param != TEX_SP_NORMAL &&
                         fn->param != TEX_SP_GRADIENT;
            c->compiled[nfn] = (char)poly_of(fn->e, &c->poly[nfn]);
            for (int i = 0; i < fn->e->n; i++)
                if (fn->e->code[i].op == TEX_EOP_LEAF && fn->e->code[i].leaf >= TEX_LEAF_Q)
                    c->quantities |= 1 << (fn->e->code[i].leaf - TEX_LEAF_Q);
        }
    }
    c->direct &= !c->quantities;
    c->lanes = c->direct && tex_simd_level() >= TEX_SIMD_AVX512;
    struct tex_material ctm; /* Cook-Torrance's m and s: the surface's, or the defaults */
    tex_ct_material(&ctm, sf->ct);
    c->base = (struct params){{sf->kd[0], sf->kd[1], sf->kd[2]}, sf->ka, sf->ks[0], (float)sf->n,
                              (float)sf->kr, (float)sf->kt, (float)sf->ior, 0, ctm.m, ctm.s, 0,
                              {0.5f, 0.5f, 1}, {0, 0, 0}, 0};
    float ka[3] = {sf->ka * sf->kd[0], sf->ka * sf->kd[1], sf->ka * sf->kd[2]};
    cs->from_rgb(cs, ka, TEX_SPECTRUM_REFLECTANCE, &c->col[0]);
    cs->from_rgb(cs, sf->kd, TEX_SPECTRUM_REFLECTANCE, &c->col[1]);
    cs->from_rgb(cs, sf->ks, TEX_SPECTRUM_REFLECTANCE, &c->col[2]);
    if (sf->ct && tex_ct_tabulate(sf->ct, cs->n) < 0) {
        tex_surface_uncache(sf);
        return -1;
    }
    c->cached = (textured & (1 << TEX_SP_KA | 1 << TEX_SP_KD) ? 0 : 1) |
                (textured & 1 << TEX_SP_KD ? 0 : 2) | (textured & 1 << TEX_SP_KS ? 0 : 4);
    int plain = sf->model == &tex_shading_phong && !sf->blend && c->base.kr <= 0 &&
                c->base.kt <= 0 && !(textured & (1 << TEX_SP_KR | 1 << TEX_SP_KT));
    int lean = !sf->apply || (c->direct && !c->placement[0].bump); /* tex_plain_material's */
    nfn = 0;
    for (const struct tex_appfn *fn = sf->apply ? sf->apply->fns : NULL; fn; fn = fn->next)
        lean &= fn->param == TEX_SP_KD && c->compiled[nfn++];
    c->plain = plain ? (lean ? 1 : 2) : 0;
    return 0;
}

int tex_surface_plain(const struct tex_surface *sf)
{
    return sf->cache->plain;
}

void tex_plain_resolve(const struct tex_scene *s, const struct tex_surface *sf,
                       const struct tex_shade_at *at, tex_v3 *N, struct tex_plain *pm)
{
    struct tex_material m;
    float blend; /* none: a plain surface has no blend */
    resolve(s, sf, at, N, &m, &blend);
    for (int k = 0; k < 3; k++)
        pm->ka[k] = m.ka.v[k], pm->kd[k] = m.kd.v[k], pm->ks[k] = m.ks.v[k];
    pm->n = m.n;
}

int tex_plain_material(const struct tex_surface *sf, const struct tex_prefetch *pre,
                       struct tex_plain *m)
{
    const struct tex_surface_cache *c = sf->cache;
    const struct tex_prefetch_ap *pa = &pre->ap[0];
    float v[4] = {c->base.kd[0], c->base.kd[1], c->base.kd[2], 0};
    if (sf->apply && !(pre->sf == sf && pre->n && pa->has_val))
        return 0;
    int i = 0; /* apply_direct's compiled Kd functions, in order */
    for (const struct tex_appfn *fn = sf->apply && pa->inside ? sf->apply->fns : NULL; fn;
         fn = fn->next, i++)
        colour_poly(&c->poly[i], pa->val, fn->lo, fn->hi, v);
    for (int k = 0; k < 3; k++) { /* material's, in RGB */
        m->ka[k] = c->cached & 1 ? c->col[0].v[k] : c->base.ka * v[k];
        m->kd[k] = c->cached & 2 ? c->col[1].v[k] : v[k];
        m->ks[k] = c->cached & 4 ? c->col[2].v[k] : sf->ks[k];
    }
    m->n = c->base.n;
    return 1;
}

void tex_surface_uncache(struct tex_surface *sf)
{
    if (sf->ct)
        tex_ct_untabulate(sf->ct);
    if (sf->cache) {
        free(sf->cache->poly);
        free(sf->cache->compiled);
        free(sf->cache->placement);
        free(sf->cache);
    }
    sf->cache = NULL;
}

/* ---- the environment -------------------------------------------------------------- */

void tex_environment_eval(const struct tex_environment *e, const tex_v3 *d, double spread,
                          float rgb[3])
{
    tex_v3 m = tex_xform_dir(&e->to_map, *d);
    double y = m.y > 1 ? 1 : m.y < -1 ? -1 : m.y;
    double u = 0.5 + atan2(m.x, m.z) / (2 * M_PI), v = acos(y) / M_PI;
    /* the footprint: spread radians are spread / pi of the map's height */
    tex_texture_eval(e->map, u, v, 0, spread > 0 ? spread / M_PI : 0, rgb);
    for (int k = 0; k < 3; k++)
        rgb[k] = (float)(rgb[k] * e->intensity);
}
