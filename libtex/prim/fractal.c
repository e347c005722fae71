/* fractal.c - turbulence and the fractal primitives (thesis 5.2.2.4, 5.2.2.8, 2.3.2)
 *
 * turbulence  sum_k g^k |noise(L^k p)| / sum_k g^k
 * fractal     --mode fbm | ridged | hybrid    sums of noise octaves (Musgrave)
 *             --mode midpoint                 Fournier-Fussell-Carpenter on the grid
 *             --mode mandelbrot | julia       escape time of x -> x^2 + C
 *             --mode koch                     the Koch snowflake or curve
 */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/simd.h"
#include "prim/noise.h"
#include "prim/noise_grid.h"
#include "prim/prim.h"
#include "base/rng.h"

/* ---- turbulence ---- */

struct turb_params {
    double frequency, lacunarity, gain, z;
    int octaves, band_limit;
    struct tex_reals w, offset;
    int fade, gradients;
    int frames, frame;
    double loop_radius;
};

static const struct tex_param turb_rows[] = {
    TEX_REAL(struct turb_params, frequency, 'f', 4, 0, 1e6, "F",
             "lattice cells across the map at the first octave (whole with --tile)"),
    TEX_INT(struct turb_params, octaves, 'n', 6, 1, TEX_OCTAVES_MAX, "N", "octaves summed"),
    TEX_REAL(struct turb_params, lacunarity, 'l', 2, 1, 16, "L",
             "frequency ratio between octaves (whole with --tile)"),
    TEX_REAL(struct turb_params, gain, 'g', 0.5, 0, 1, "G", "amplitude ratio between octaves"),
    TEX_FLAG(struct turb_params, band_limit, 0,
             "fade octaves finer than a pixel to their mean, as Perlin's filtered "
             "turbulence: no aliasing, and faster (a solid texture in t_apply: finer than "
             "the ray's footprint at the hit)"),
    TEX_NOISE_ROWS(struct turb_params),
    TEX_NOISE_W_ROW(struct turb_params),
    TEX_NOISE_LOOP_ROWS(struct turb_params),
    {0}};

struct turb_state {
    tex_octaves o;
    float amp[TEX_OCTAVES_MAX], inv;
    int active;  /* octaves the rows sum: all, or those the band limit leaves */
    float fill;  /* what the faded octaves add: their amplitudes' share of the mean */
    float mean;  /* band limit: E|noise|, what a faded octave is replaced with */
};

/* Rows y.. y + rows - 1 of octaves 0..n-1 summed into out (rows of w samples): the first
 * octave sets the sum (no clearing pass), the last finishes it (rescale and clamp); a lone
 * octave adds its finish to cleared rows.  With fill, the rows start at fill instead. */
static void octave_sum_rows(const tex_octaves *o, int n, int y, int rows, int w, int first,
                            int mid, int last, const float *amp, float inv, float fill, float *out)
{
    if (n == 1 || fill != 0)
        for (size_t x = 0; x < (size_t)rows * w; x++)
            out[x] = fill;
    if (fill != 0)
        first = mid;
    for (int k = 0; k < n; k++)
        tex_octave_rows_op(o, k, y, rows, k == n - 1 ? last : k == 0 ? first : mid, amp[k], inv,
                           0, out, (size_t)w);
}

/* The band limit on the amplitudes: each octave weighted, the faded share of
 * the mean (0 for signed noise) gathered in fill, the silent octaves dropped. */
static void band_limit(const tex_octaves *o, float *amp, double mean, int *active, float *fill)
{
    double c = 0;
    *active = 0;
    for (int k = 0; k < o->n; k++) {
        double wk = tex_octave_band_weight(o, k);
        c += amp[k] * (1 - wk) * mean;
        amp[k] = (float)(amp[k] * wk);
        if (wk > 0)
            *active = k + 1;
    }
    if (*active == 0) /* the first octave always stays, however faint */
        *active = 1;
    *fill = (float)c;
}

static void offsets(const struct tex_reals *r, double off[3])
{
    off[0] = off[1] = off[2] = 0;
    for (int a = 0; a < r->n && a < 3; a++)
        off[a] = r->v[a];
}

/* The octaves' amplitudes g^k and the inverse of their sum */
static void turb_amplitudes(struct turb_state *s, double gain, int octaves)
{
    double sum = 0;
    for (int k = 0; k < octaves; k++) {
        s->amp[k] = (float)pow(gain, k);
        sum += s->amp[k];
    }
    s->inv = (float)(1.0 / sum);
    s->active = octaves;
    s->fill = 0;
}

static int turb_init(struct tex_field *f)
{
    const struct turb_params *p = f->params;
    struct turb_state *s = calloc(1, sizeof *s);
    double off[3];

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    offsets(&p->offset, off);
    turb_amplitudes(s, p->gain, p->octaves);
    double z = p->z, w = p->w.n ? p->w.v[0] : 0;
    int dims = p->w.n ? 4 : 3;
    if (tex_noise_loop(p->frames, p->frame, p->loop_radius, &z, &w, &dims) < 0 ||
        tex_octaves_init(&s->o, f->prim->params, f->seed, p->gradients, p->fade, p->octaves,
                         p->frequency, p->lacunarity, off, z, w, dims, f->tile, f->w, f->h) < 0)
        return -1;
    if (p->band_limit) {
        s->mean = (float)tex_noise_mean_abs(&s->o.t);
        band_limit(&s->o, s->amp, s->mean, &s->active, &s->fill);
        f->band_limit = 1;
    }
    return 0;
}

static void turb_fini(struct tex_field *f)
{
    struct turb_state *s = f->state;
    if (s)
        tex_octaves_free(&s->o);
    free(s);
}

/* Turbulence at n points (w NULL: 0): the octaves' sum rescaled and clamped. */
static void turb_points(const struct turb_state *s, int n, const double *u, const double *v,
                        const double *w, float *out)
{
    tex_octave_abs_sum(&s->o, s->active, s->amp, s->fill, n, u, v, w, out);
    for (int i = 0; i < n; i++)
        out[i] = clamp01(out[i] * s->inv);
}

static void turb_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                       const double *w, float *out)
{
    turb_points(f->state, n, u, v, w, out);
}

/* Turbulence through footprints: octave k adds amp_k (t |noise| + (1 - t) mean), t its
 * band weight at the point (t = 1: amp_k |noise|, turb_points' bits). */
static void turb_eval3_fw(const struct tex_field *f, int n, const double *u, const double *v,
                          const double *w, const double *fw, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    const struct turb_state *s = f->state;
    float r[B], t[B];
    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        float *o = out + i0;
        for (int i = 0; i < m; i++)
            o[i] = 0;
        for (int k = 0; k < s->o.n; k++) {
            tex_octave_points_fw(&s->o, k, m, u + i0, v + i0, w ? w + i0 : NULL, fw + i0, r, t);
            float ak = s->amp[k], mean = s->mean;
#pragma omp simd
            for (int i = 0; i < m; i++)
                o[i] += ak * (t[i] * fabsf(r[i]) + (1 - t[i]) * mean);
        }
        for (int i = 0; i < m; i++)
            o[i] = clamp01(o[i] * s->inv);
    }
}

static void turb_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                       float *out)
{
    turb_eval3(f, n, u, v, NULL, out);
}

static void turb_row_n(const struct tex_field *f, int y, int n, float *out)
{
    const struct turb_state *s = f->state;

    /* a |n| is never -0: the same as 0 + a |n| */
    octave_sum_rows(&s->o, s->active, y, n, f->w, TEX_ROW_MUL_ABS, TEX_ROW_ADD_ABS,
                    TEX_ROW_ADD_ABS_CLAMP, s->amp, s->inv, s->fill, out);
}

static void turb_row(const struct tex_field *f, int y, float *out)
{
    turb_row_n(f, y, 1, out);
}

const struct tex_primitive tex_prim_turbulence = {
    .name = "turbulence",
    .summary = "Perlin's turbulence: a sum of octaves of |noise|",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct turb_params),
    .params = turb_rows,
    .init = turb_init,
    .fini = turb_fini,
    .eval2 = turb_eval2,
    .eval3 = turb_eval3,
    .eval3_fw = turb_eval3_fw,
    .row = turb_row,
    .rows = turb_row_n,
};

/* ---- wood: rings about an axis, perturbed by turbulence (POV-Ray's wood) ---- */

struct wood_params {
    double rings, amount, frequency, tilt, offset, grain;
    int octaves;
};

static const struct tex_param wood_rows[] = {
    TEX_REAL(struct wood_params, rings, 0, 8, 0.01, 1e4, "R",
             "rings per unit of distance from the axis (the map is 1 wide)"),
    TEX_REAL_N("turbulence", struct wood_params, amount, 0, 0.04, 0, 10,
               "A", "turbulence added to the distance from the axis, in map widths",
               .old = "-a amount"),
    TEX_REAL(struct wood_params, frequency, 'f', 4, 0, 1e6, "F",
             "lattice cells of the turbulence across the map at its first octave"),
    TEX_INT(struct wood_params, octaves, 'n', 4, 1, TEX_OCTAVES_MAX, "N",
            "octaves of the turbulence"),
    TEX_REAL(struct wood_params, tilt, 0, 0, -90, 90, "DEG",
             "angle of the axis from w towards v: 0 shows the rings as in a cross-cut log, "
             "90 runs the grain down the map as on a plank"),
    TEX_REAL_N("axis_offset", struct wood_params, offset, 0, 0, -100, 100, "D",
               "distance of the axis from the map's centre along u, in map widths",
               .old = "offset"),
    TEX_REAL(struct wood_params, grain, 0, 0, 0, 1, "G",
             "weight of fine streaks along the axis (noise stretched along it)"),
    {0}};

struct wood_state {
    struct turb_state turb;
    tex_noise_table grain;
    double c, s; /* cosine and sine of the tilt */
};

static int wood_init(struct tex_field *f)
{
    const struct wood_params *p = f->params;
    struct wood_state *s = calloc(1, sizeof *s);
    double off[3] = {0, 0, 0};

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    turb_amplitudes(&s->turb, 0.5, p->octaves);
    s->c = cos(p->tilt * M_PI / 180);
    s->s = sin(p->tilt * M_PI / 180);
    if (tex_noise_init(&s->grain, f->seed ^ 0x5bd1e995u, 256, 0) < 0)
        return -1;
    return tex_octaves_init(&s->turb.o, f->prim->params, f->seed, 256, 0, p->octaves,
                            p->frequency, 2, off, 0, 0, 3, 0, 0, 0);
}

static void wood_fini(struct tex_field *f)
{
    struct wood_state *s = f->state;
    if (s) {
        tex_octaves_free(&s->turb.o);
        tex_noise_free(&s->grain);
    }
    free(s);
}

/* The distance r from the axis, perturbed by turbulence and counted in rings, modulo 1: a
 * sawtooth from early to late wood that a palette colours; grain mixes in noise stretched
 * 32 times along the axis.  Points go in batches: the turbulence and the grain's noise
 * through the vectorised point path. */
static void wood_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                       const double *w, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    const struct wood_params *p = f->params;
    const struct wood_state *s = f->state;
    double W[B], gx[B], gy[B], gz[B], g[B];
    float t[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        for (int i = 0; i < m; i++)
            W[i] = w ? w[i0 + i] : 0.5;
        if (p->amount > 0)
            turb_points(&s->turb, m, u + i0, v + i0, W, t);
        for (int i = 0; i < m; i++) {
            double x = u[i0 + i] - 0.5 - p->offset, y = v[i0 + i] - 0.5, z = W[i] - 0.5;
            double ya = y * s->c - z * s->s, za = y * s->s + z * s->c; /* the axis: za */
            double r = sqrt(x * x + ya * ya);
            double ring = (r + p->amount * (p->amount > 0 ? t[i] : 0)) * p->rings;
            gx[i] = 64 * x, gy[i] = 64 * ya, gz[i] = 2 * za;
            g[i] = ring - floor(ring); /* the value until the grain is mixed in */
        }
        if (p->grain > 0) {
            double gn[B];
            tex_noise_points(&s->grain, s->grain.period, 3, m, gx, gy, gz, NULL, gn);
            for (int i = 0; i < m; i++)
                g[i] = (1 - p->grain) * g[i] + p->grain * (0.5 + 0.5 * gn[i]);
        }
        for (int i = 0; i < m; i++)
            out[i0 + i] = clamp01((float)g[i]);
    }
}

static void wood_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                       float *out)
{
    wood_eval3(f, n, u, v, NULL, out);
}

const struct tex_primitive tex_prim_wood = {
    .name = "wood",
    .summary = "wood: rings about an axis perturbed by turbulence, with grain along it",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D,
    .params_size = sizeof(struct wood_params),
    .params = wood_rows,
    .init = wood_init,
    .fini = wood_fini,
    .eval2 = wood_eval2,
    .eval3 = wood_eval3,
};

/* ---- fractal ---- */

enum { FBM, RIDGED, HYBRID, MIDPOINT, MANDELBROT, JULIA, KOCH };

struct frac_params {
    int mode;
    double frequency, lacunarity, gain, mf_offset, z;
    int octaves;
    struct tex_reals h, w, offset;
    int fade, gradients;
    int frames, frame;
    double loop_radius;
    struct tex_reals centre, c;
    double zoom;
    int iterations, depth, koch;
    double line_width;
    int band_limit;
};

/* The modes each row applies to: bit k for mode k of the enum above. */
#define IN(m) (1u << (m))
#define NOISY (IN(FBM) | IN(RIDGED) | IN(HYBRID))
#define ESCAPE (IN(MANDELBROT) | IN(JULIA))
#define MANDEL_X -0.5 /* the centre of a Mandelbrot map without --centre: (MANDEL_X, 0) */
static const struct tex_param frac_rows[] = {
    TEX_ENUM(struct frac_params, mode, 'm', "fbm",
             "fbm|ridged|hybrid|midpoint|mandelbrot|julia|koch", "the fractal"),
    TEX_REAL(struct frac_params, frequency, 'f', 4, 0, 1e6, "F",
             "fbm, ridged, hybrid: lattice cells across the map at the first octave",
             .kinds = NOISY),
    TEX_INT(struct frac_params, octaves, 'n', 8, 1, TEX_OCTAVES_MAX, "N",
            "fbm, ridged, hybrid: octaves summed", .kinds = NOISY),
    TEX_REAL(struct frac_params, lacunarity, 'l', 2, 1, 16, "L",
             "fbm, ridged, hybrid: frequency ratio between octaves (whole with --tile)",
             .kinds = NOISY),
    TEX_REALS_N("hurst", struct frac_params, h, 0, "0.8", -20, 20, 16, "H[,H...]",
                "Hurst exponent per octave or level, the last repeating: amplitude falls by "
                "L^-H (fbm, ridged, hybrid) or 2^-H (midpoint) each step",
                .alias = "h", .kinds = NOISY | IN(MIDPOINT)),
    TEX_REAL_N("ridge_gain", struct frac_params, gain, 0, 2, 0, 16, "G",
               "ridged: Musgrave's weight gain", .old = "-g gain", .kinds = IN(RIDGED)),
    TEX_REAL(struct frac_params, mf_offset, 0, 1, 0, 4, "O",
             "ridged, hybrid: Musgrave's offset (try 0.7 for hybrid)",
             .kinds = IN(RIDGED) | IN(HYBRID)),
    TEX_FLAG(struct frac_params, band_limit, 0,
             "fbm: fade octaves finer than a pixel of the map out (Perlin's filtered fBm): "
             "no aliasing, and faster (a solid texture in t_apply: finer than the ray's "
             "footprint at the hit)",
             .kinds = IN(FBM)),
    TEX_NOISE_ROWS(struct frac_params, .kinds = NOISY),
    TEX_NOISE_W_ROW(struct frac_params, .kinds = NOISY),
    TEX_NOISE_LOOP_ROWS(struct frac_params, .kinds = NOISY),
    TEX_REALS(struct frac_params, centre, 0, NULL, -1e3, 1e3, 2, "X,Y",
              "mandelbrot, julia: complex point at the centre of the map (" TEX_XSTR(MANDEL_X)
              ",0 and 0,0)",
              .kinds = ESCAPE),
    TEX_REAL(struct frac_params, zoom, 0, 1, 1e-12, 1e12, "Z",
             "mandelbrot, julia: magnification; the map spans 4/Z", .kinds = ESCAPE),
    TEX_INT(struct frac_params, iterations, 'i', 256, 1, 100000, "N",
            "mandelbrot, julia: most iterations", .kinds = ESCAPE),
    TEX_REALS_N("julia_constant", struct frac_params, c, 0, "-0.8,0.156", -10, 10, 2, "RE,IM",
                "julia: the constant C", .alias = "c", .kinds = IN(JULIA)),
    TEX_INT_N("recursions", struct frac_params, depth, 0, 5, 0, 12, "N", "koch: recursion depth",
              .old = "-d", .kinds = IN(KOCH)),
    TEX_ENUM(struct frac_params, koch, 0, "snowflake", "snowflake|curve",
             "koch: the filled snowflake or the curve on one edge", .kinds = IN(KOCH)),
    TEX_REAL(struct frac_params, line_width, 0, 0.006, 1e-6, 1, "W",
             "koch curve: line width in map widths", .kinds = IN(KOCH)),
    {0}};

struct frac_state {
    tex_octaves o;
    int mode;
    float amp[TEX_OCTAVES_MAX];
    float inv, lo, hi; /* rescaling to [0,1] */
    int active;        /* fbm: octaves the rows sum (the band limit drops the rest) */
    float *mp;         /* midpoint: the displaced grid, mw x mh */
    int mw, mh;
};

/* Musgrave's ridged and hybrid multifractals over per-octave noise n[k]. */
static float ridged(const struct frac_state *s, const struct frac_params *p, const float *n)
{
    float off = (float)p->mf_offset, gain = (float)p->gain;
    float sig = off - fabsf(n[0]), res, wgt;

    sig *= sig;
    res = sig;
    for (int k = 1; k < s->o.n; k++) {
        wgt = clamp01(sig * gain);
        sig = off - fabsf(n[k]);
        sig *= sig;
        sig *= wgt;
        res += sig * s->amp[k];
    }
    return res;
}

static float hybrid(const struct frac_state *s, const struct frac_params *p, const float *n)
{
    float off = (float)p->mf_offset, res = (n[0] + off) * s->amp[0], wgt = res;

    for (int k = 1; k < s->o.n; k++) {
        float sig;
        wgt = wgt < 1 ? wgt : 1; /* as the vector min */
        sig = (n[k] + off) * s->amp[k];
        res += wgt * sig;
        wgt *= sig;
    }
    return res;
}

static float combine(const struct frac_state *s, const struct frac_params *p, const float *n)
{
    float acc = 0;

    switch (s->mode) {
    case RIDGED:
        return clamp01(ridged(s, p, n) * s->inv);
    case HYBRID:
        return clamp01((hybrid(s, p, n) - s->lo) * s->inv);
    default:
        for (int k = 0; k < s->o.n; k++)
            acc += s->amp[k] * n[k];
        return clamp01(0.5f + 0.5f * (acc * s->inv));
    }
}

/* Escape time of x -> x^2 + c from x0, smoothed: n + 1 - log2(log|x|) over
 * the iteration limit; 1 inside (no escape). */
static float escape(double x, double y, double cx, double cy, int iters)
{
    for (int n = 0; n < iters; n++) {
        double xx = x * x, yy = y * y;
        if (xx + yy > 256.0 * 256.0) {
            double nu = n + 1 - log2(0.5 * log(xx + yy));
            return clamp01((float)(nu / iters));
        }
        y = 2 * x * y + cy;
        x = xx - yy + cx;
    }
    return 1;
}

/* ---- Koch ---- */

struct pt {
    double x, y;
};

static int in_triangle(struct pt p, struct pt a, struct pt b, struct pt c)
{
    double d1 = (p.x - b.x) * (a.y - b.y) - (a.x - b.x) * (p.y - b.y);
    double d2 = (p.x - c.x) * (b.y - c.y) - (b.x - c.x) * (p.y - c.y);
    double d3 = (p.x - a.x) * (c.y - a.y) - (c.x - a.x) * (p.y - a.y);
    int neg = d1 < 0 || d2 < 0 || d3 < 0, pos = d1 > 0 || d2 > 0 || d3 > 0;
    return !(neg && pos);
}

/* The point at fraction t along ab, pushed by k |ab| to the right of a->b. */
static struct pt along(struct pt a, struct pt b, double t, double k)
{
    double dx = b.x - a.x, dy = b.y - a.y;
    return (struct pt){a.x + t * dx + k * dy, a.y + t * dy - k * dx};
}

/* Is p under the Koch bumps that edge a->b grows to its right at depth d?
 * They all lie in the triangle on ab with apex at height |ab|/(2 sqrt 3). */
static int koch_in(struct pt p, struct pt a, struct pt b, int d)
{
    struct pt p1, p2, p3, e[5];

    if (d == 0 || !in_triangle(p, a, b, along(a, b, 0.5, 0.5 / sqrt(3.0))))
        return 0;
    p1 = along(a, b, 1.0 / 3, 0);
    p3 = along(a, b, 2.0 / 3, 0);
    p2 = along(a, b, 0.5, sqrt(3.0) / 6);
    if (in_triangle(p, p1, p2, p3))
        return 1;
    e[0] = a, e[1] = p1, e[2] = p2, e[3] = p3, e[4] = b;
    for (int i = 0; i < 4; i++)
        if (koch_in(p, e[i], e[i + 1], d - 1))
            return 1;
    return 0;
}

static double seg_dist(struct pt p, struct pt a, struct pt b)
{
    double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

/* Distance from p to the Koch curve on a->b, if below best. */
static double koch_dist(struct pt p, struct pt a, struct pt b, int d, double best)
{
    struct pt apex = along(a, b, 0.5, 0.5 / sqrt(3.0)), e[5];

    if (d == 0)
        return fmin(best, seg_dist(p, a, b));
    /* Outside the bounding triangle by more than best: nothing closer here. */
    if (!in_triangle(p, a, b, apex) &&
        fmin(seg_dist(p, a, b), fmin(seg_dist(p, b, apex), seg_dist(p, apex, a))) >= best)
        return best;
    e[0] = a;
    e[1] = along(a, b, 1.0 / 3, 0);
    e[2] = along(a, b, 0.5, sqrt(3.0) / 6);
    e[3] = along(a, b, 2.0 / 3, 0);
    e[4] = b;
    for (int i = 0; i < 4; i++)
        best = koch_dist(p, e[i], e[i + 1], d - 1, best);
    return best;
}

static float koch(const struct frac_params *p, double u, double v)
{
    struct pt q = {u, v};

    if (p->koch == 1) { /* the curve along one edge, bumps upwards */
        struct pt a = {0.05, 0.7}, b = {0.95, 0.7};
        double d = koch_dist(q, a, b, p->depth, 1e9), hw = 0.5 * p->line_width;
        return clamp01((float)(1.0 - (d - hw) / hw));
    }
    /* The snowflake fills the circle of radius 0.45 about the centre: a
     * counter-clockwise triangle (v grows downwards), bumps to the outside. */
    struct pt t[3];
    for (int i = 0; i < 3; i++) {
        double a = M_PI / 2 + 2 * M_PI * i / 3;
        t[i] = (struct pt){0.5 + 0.45 * cos(a), 0.5 + 0.45 * sin(a)};
    }
    if (in_triangle(q, t[0], t[1], t[2]))
        return 1;
    for (int i = 0; i < 3; i++)
        if (koch_in(q, t[i], t[(i + 1) % 3], p->depth) ||
            koch_in(q, t[(i + 1) % 3], t[i], p->depth))
            return 1;
    return 0;
}

/* ---- midpoint displacement ---- */

static double level_scale(const struct tex_reals *h, int l)
{
    return pow(2.0, -h->v[l - 1 < h->n ? l - 1 : h->n - 1]);
}

/* Diamond-square on an N x N periodic lattice (tile) or (N+1)^2 points;
 * level l displaces new points by a Gaussian of deviation
 * prod_{m<=l} 2^-h_m (Fournier, Fussell and Carpenter; per-level h after
 * Haruyama and Barsky). */
static int midpoint(const struct frac_params *p, uint64_t seed, int tile, int w, int h,
                    float *out)
{
    int N = 1, S;
    double sd = 1, lo = INFINITY, hi = -INFINITY;
    float *g;
    tex_rng r;

    while (N < w || N < h)
        N *= 2;
    S = tile ? N : N + 1;
    if (!(g = malloc((size_t)S * S * sizeof *g)))
        return tex_error("out of memory");
    tex_rng_seed(&r, seed);
#define G(x, y) g[(size_t)((y) % S) * S + ((x) % S)]
    for (int y = 0; y < S; y += N)
        for (int x = 0; x < S; x += N)
            G(x, y) = (float)tex_rng_gauss(&r);
    for (int step = N, l = 1; step > 1; step /= 2, l++) {
        int hs = step / 2;
        sd *= level_scale(&p->h, l);
        /* Diamond: square centres from their four corners. */
        for (int y = hs; y < S; y += step)
            for (int x = hs; x < S; x += step)
                G(x, y) = (float)((G(x - hs, y - hs) + G(x + hs, y - hs) + G(x - hs, y + hs) +
                                   G(x + hs, y + hs)) / 4.0 + sd * tex_rng_gauss(&r));
        /* Square: edge midpoints from their (up to) four diamond neighbours. */
        for (int y = 0; y < S; y += hs)
            for (int x = (y / hs % 2 == 0) ? hs : 0; x < S; x += step) {
                double sum = 0;
                int k = 0;
                if (tile || y >= hs) sum += G(x, y - hs + S), k++;
                if (tile || y + hs < S) sum += G(x, y + hs), k++;
                if (tile || x >= hs) sum += G(x - hs + S, y), k++;
                if (tile || x + hs < S) sum += G(x + hs, y), k++;
                G(x, y) = (float)(sum / k + sd * tex_rng_gauss(&r));
            }
    }
    /* Onto the map: bilinear where the map is not N x N. */
    for (int y = 0; y < h; y++) {
        float *row = out + (size_t)y * w;
        for (int x = 0; x < w; x++) {
            double gx = (double)x * N / w, gy = (double)y * N / h;
            int ix = (int)gx, iy = (int)gy;
            double fx = gx - ix, fy = gy - iy;
            double a = G(ix, iy) + fx * (G(ix + 1, iy) - G(ix, iy));
            double b = G(ix, iy + 1) + fx * (G(ix + 1, iy + 1) - G(ix, iy + 1));
            row[x] = (float)(a + fy * (b - a));
            lo = fmin(lo, row[x]);
            hi = fmax(hi, row[x]);
        }
    }
#undef G
    free(g);
    for (size_t i = 0; i < (size_t)w * h; i++)
        out[i] = hi > lo ? (float)((out[i] - lo) / (hi - lo)) : 0.5f;
    return 0;
}

/* ---- the fractal primitive ---- */

static const char *const mode_names[] = {"fbm", "ridged", "hybrid", "midpoint",
                                         "mandelbrot", "julia", "koch"};

/* Messages name a parameter by its row (prim.h) */
#define FRAC_OPTION(field) TEX_OPTION(frac_rows, struct frac_params, field)

static int frac_init(struct tex_field *f)
{
    const struct frac_params *p = f->params;
    struct frac_state *s = calloc(1, sizeof *s);
    double off[3], sum = 0, amp = 1;
    float ones[TEX_OCTAVES_MAX], mones[TEX_OCTAVES_MAX], zeros[TEX_OCTAVES_MAX] = {0};

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    s->mode = p->mode;
    if (f->tile && p->mode >= MANDELBROT)
        return tex_usage_error("%s: %s %s is not periodic (fbm, ridged, hybrid and midpoint tile)",
                               TEX_FIELD_OPTION(tile), FRAC_OPTION(mode), mode_names[p->mode]);
    if (p->mode >= MIDPOINT && (p->frames || p->frame))
        return tex_usage_error("%s animates %s fbm, ridged and hybrid, which are made of noise "
                               "(got %s %s)",
                               FRAC_OPTION(frames), FRAC_OPTION(mode), FRAC_OPTION(mode),
                               mode_names[p->mode]);
    if (p->mode == MIDPOINT) {
        /* Scenes evaluate at points: they get a 512 x 512 map, sampled bilinearly. */
        s->mw = f->w > 0 ? f->w : 512;
        s->mh = f->h > 0 ? f->h : 512;
        /* the map and its lattice, (2^k + 1)^2 for the larger side, are held whole */
        if (tex_map_check_size(s->mw, s->mh, 1) < 0)
            return -1;
        if (s->mw > TEX_MAP_MAX_SIDE / 2 || s->mh > TEX_MAP_MAX_SIDE / 2)
            return tex_usage_error("%s midpoint at %dx%d: each side at most %d (its lattice is "
                                   "held whole, the larger side's power of 2 plus 1 squared)",
                                   FRAC_OPTION(mode), s->mw, s->mh, TEX_MAP_MAX_SIDE / 2);
        if (!(s->mp = malloc((size_t)s->mw * s->mh * sizeof *s->mp)))
            return tex_error("out of memory");
        return midpoint(p, f->seed, f->tile, s->mw, s->mh, s->mp);
    }
    if (p->mode >= MANDELBROT)
        return 0;
    for (int k = 0; k < p->octaves; k++) {
        if (k)
            amp *= pow(p->lacunarity, -p->h.v[k - 1 < p->h.n ? k - 1 : p->h.n - 1]);
        s->amp[k] = (float)amp;
        sum += s->amp[k];
        ones[k] = 1;
        mones[k] = -1;
    }
    if (!isfinite(sum) || sum <= 0)
        return tex_usage_error("%s: the octave amplitudes overflow (got %g over %d octaves)",
                               FRAC_OPTION(h), p->h.v[0], p->octaves);
    s->o.n = p->octaves;
    if (p->mode == FBM) {
        s->inv = (float)(1.0 / sum);
    } else if (p->mode == RIDGED) {
        /* Every octave's signal is at most max(offset, |1 - offset|)^2. */
        double m = fmax(p->mf_offset, fabs(1 - p->mf_offset));
        s->inv = (float)(1.0 / (m * m * sum));
        (void)zeros;
    } else {
        s->lo = hybrid(s, p, mones);
        s->hi = hybrid(s, p, ones);
        if (!(s->hi > s->lo))
            return tex_usage_error("%s %g gives hybrid a constant field", FRAC_OPTION(mf_offset),
                                   p->mf_offset);
        s->inv = 1.0f / (s->hi - s->lo);
    }
    offsets(&p->offset, off);
    double z = p->z, w = p->w.n ? p->w.v[0] : 0;
    int dims = p->w.n ? 4 : 3;
    if (tex_noise_loop(p->frames, p->frame, p->loop_radius, &z, &w, &dims) < 0)
        return -1;
    s->active = p->octaves;
    if (tex_octaves_init(&s->o, f->prim->params, f->seed, p->gradients, p->fade, p->octaves,
                         p->frequency, p->lacunarity, off, z, w, dims, f->tile, f->w, f->h) < 0)
        return -1;
    if (p->band_limit) {
        float fill;
        band_limit(&s->o, s->amp, 0, &s->active, &fill); /* signed noise: the mean is 0 */
        f->band_limit = 1;
    }
    return 0;
}

static void frac_fini(struct tex_field *f)
{
    struct frac_state *s = f->state;
    if (s) {
        tex_octaves_free(&s->o);
        free(s->mp);
    }
    free(s);
}

static float midpoint_at(const struct frac_state *s, double u, double v)
{
    double gx = u * s->mw - 0.5, gy = v * s->mh - 0.5;
    double x0 = floor(gx), y0 = floor(gy), fx = gx - x0, fy = gy - y0;
    int ix = (int)fmod(x0 + s->mw, s->mw), iy = (int)fmod(y0 + s->mh, s->mh);
    int jx = (ix + 1) % s->mw, jy = (iy + 1) % s->mh;
    const float *a = s->mp + (size_t)iy * s->mw, *b = s->mp + (size_t)jy * s->mw;
    double top = a[ix] + fx * (a[jx] - a[ix]), bot = b[ix] + fx * (b[jx] - b[ix]);

    if (!isfinite(u) || !isfinite(v))
        return 0.5f;
    return (float)(top + fy * (bot - top));
}

static float frac_point(const struct tex_field *f, double u, double v, double w)
{
    const struct frac_params *p = f->params;
    const struct frac_state *s = f->state;
    double zx, zy, sc = 4.0 / p->zoom;
    float n[TEX_OCTAVES_MAX] = {0};

    switch (s->mode) {
    case MANDELBROT:
    case JULIA:
        zx = (p->centre.n ? p->centre.v[0] : s->mode == MANDELBROT ? MANDEL_X : 0) + (u - 0.5) * sc;
        zy = (p->centre.n > 1 ? p->centre.v[1] : 0) + (0.5 - v) * sc;
        if (s->mode == MANDELBROT)
            return escape(0, 0, zx, zy, p->iterations);
        return escape(zx, zy, p->c.v[0], p->c.v[1], p->iterations);
    case KOCH:
        return koch(p, u, v);
    case MIDPOINT:
        return midpoint_at(s, u - floor(u), v - floor(v));
    default:
        for (int k = 0; k < s->o.n; k++)
            n[k] = (float)tex_octave_point(&s->o, k, u, v, w);
        return combine(s, p, n);
    }
}

/* frac_point over many points (w NULL: 0); the octave sums octave by octave. */
static void frac_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                       const double *w, float *out)
{
    enum { B = TEX_POINTS_BATCH / 4 };
    const struct frac_params *p = f->params;
    const struct frac_state *s = f->state;
    double r[B];
    float nk[B][TEX_OCTAVES_MAX];

    if (s->mode > HYBRID) {
        for (int i = 0; i < n; i++)
            out[i] = frac_point(f, u[i], v[i], w ? w[i] : 0);
        return;
    }
    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        for (int k = 0; k < s->o.n; k++) {
            tex_octave_points(&s->o, k, m, u + i0, v + i0, w ? w + i0 : NULL, r);
            for (int i = 0; i < m; i++)
                nk[i][k] = (float)r[i];
        }
        for (int i = 0; i < m; i++)
            out[i0 + i] = combine(s, p, nk[i]);
    }
}

/* fBm through footprints (the band limit is fbm's only): octave k weighted by its band
 * weight t at the point, its mean 0 for the rest (t = 1: frac_eval3's bits). */
static void frac_eval3_fw(const struct tex_field *f, int n, const double *u, const double *v,
                          const double *w, const double *fw, float *out)
{
    enum { B = TEX_POINTS_BATCH / 4 };
    const struct frac_params *p = f->params;
    const struct frac_state *s = f->state;
    float r[B], t[B], nk[B][TEX_OCTAVES_MAX];

    if (s->mode != FBM) {
        frac_eval3(f, n, u, v, w, out);
        return;
    }
    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        for (int k = 0; k < s->o.n; k++) {
            tex_octave_points_fw(&s->o, k, m, u + i0, v + i0, w ? w + i0 : NULL, fw + i0, r, t);
            for (int i = 0; i < m; i++)
                nk[i][k] = t[i] * r[i];
        }
        for (int i = 0; i < m; i++)
            out[i0 + i] = combine(s, p, nk[i]);
    }
}

static void frac_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                       float *out)
{
    frac_eval3(f, n, u, v, NULL, out);
}

static void frac_row_n(const struct tex_field *f, int y, int n, float *out)
{
    const struct frac_params *p = f->params;
    const struct frac_state *s = f->state;
    size_t w = (size_t)f->w;
    float *st;

    if (s->mode == FBM) {
        /* a n instead of 0 + a n: only the sign of a zero differs, and
         * 0.5 + 0.5 x erases it */
        octave_sum_rows(&s->o, s->active, y, n, f->w, TEX_ROW_MUL, TEX_ROW_ADD, TEX_ROW_ADD_UNIT,
                        s->amp, s->inv, 0, out);
        return;
    }
    st = s->mode <= HYBRID ? malloc(n * w * sizeof *st) : NULL;
    if (!st) { /* not an octave sum, or no memory for the states */
        for (int i = 0; i < n; i++)
            for (int x = 0; x < f->w; x++)
                out[i * w + x] = frac_point(f, (x + 0.5) / f->w, (y + i + 0.5) / f->h, 0);
        return;
    }
    /* the octaves' steps of ridged() and hybrid() in their order, on every pixel, the last
     * rescaling the sum: clamp01((x - lo) inv), lo 0 for ridged (x - 0 is x: a sum of
     * squares is never -0) */
    struct tex_mf_k mk = {0, (float)p->mf_offset, (float)p->gain, s->mode == RIDGED ? 0 : s->lo,
                          s->inv};
    static const int ops[2][3] = {{TEX_ROW_HYBRID_FIRST, TEX_ROW_HYBRID, TEX_ROW_HYBRID_LAST},
                                  {TEX_ROW_RIDGED_FIRST, TEX_ROW_RIDGED, TEX_ROW_RIDGED_LAST}};
    for (int k = 0; k < s->o.n; k++) {
        mk.amp = s->amp[k];
        tex_octave_rows_mf(&s->o, k, y, n, ops[s->mode == RIDGED][!k ? 0 : k < s->o.n - 1 ? 1 : 2],
                           &mk, out, st, w);
    }
    if (s->o.n == 1) /* the first step is the last */
        for (size_t x = 0; x < n * w; x++)
            out[x] = clamp01((out[x] - mk.lo) * mk.inv);
    free(st);
}

static void frac_row(const struct tex_field *f, int y, float *out)
{
    frac_row_n(f, y, 1, out);
}

static int frac_grid(const struct tex_field *f, tex_map *m)
{
    const struct frac_state *s = f->state;

    if (s->mode == MIDPOINT) {
        memcpy(m->px, s->mp, (size_t)f->w * f->h * sizeof *s->mp);
        return 0;
    }
    return tex_field_sample_rows(f, m);
}

/* Midpoint displacement draws its random numbers in sequence over the whole
 * lattice and rescales by the whole map's range: no window alone has them. */
static const char *frac_whole(const struct tex_field *f)
{
    static _Thread_local char why[128]; /* the reason, its option named by the row */
    const struct frac_params *p = f->params;

    if (p->mode != MIDPOINT)
        return NULL;
    snprintf(why, sizeof why, "%s midpoint draws the whole lattice in sequence and rescales by "
             "the whole map's range", FRAC_OPTION(mode));
    return why;
}

const struct tex_primitive tex_prim_fractal = {
    .name = "fractal",
    .summary = "fractals: fBm, multifractals, midpoint displacement, Mandelbrot, Julia, Koch",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE | TEX_PRIM_GRID,
    .params_size = sizeof(struct frac_params),
    .params = frac_rows,
    .init = frac_init,
    .fini = frac_fini,
    .eval2 = frac_eval2,
    .eval3 = frac_eval3,
    .eval3_fw = frac_eval3_fw,
    .row = frac_row,
    .rows = frac_row_n,
    .grid = frac_grid,
    .whole = frac_whole,
};
