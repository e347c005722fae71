/* stochastic.c - holes (thesis 5.2.2.6), Gardner's colour variation (5.2.2.7) and the
 * perturbed regular pattern (5.2.2.2) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "prim/noise.h"
#include "prim/noise_grid.h"
#include "prim/prim.h"
#include "base/rng.h"
#include "base/trig.h"

static inline float clamp_unit(float x)
{
    return x < 0 ? 0 : x > 1 ? 1 : x;
}

/* A usage error unless v, the value of the row of rows at offset off, is a whole number
 * (WHOLE: field fl of *p, a struct S) */
static int whole(const struct tex_param *rows, size_t off, double v)
{
    char name[64];
    if (v != floor(v))
        return tex_usage_error("%s must be a whole number with %s (got %g)",
                               tex_rows_option(rows, off, name, sizeof name),
                               TEX_FIELD_OPTION(tile), v);
    return 0;
}
#define WHOLE(rows, S, p, fl) whole(rows, offsetof(S, fl), (p)->fl)

/* ---- holes ---- */

struct holes_params {
    int count;
    double diameter, jitter, density, depth;
    int formula;
};

static const struct tex_param holes_rows[] = {
    TEX_INT_N("grid_cells", struct holes_params, count, 0, 8, 1, 100000, "N",
              "grid cells across the map, at most one hole each", .old = "-n count"),
    TEX_REAL(struct holes_params, diameter, 0, 0.6, 0.001, 1, "D",
             "hole diameter, in cells", .old = "-d"),
    TEX_REAL(struct holes_params, jitter, 0, 0.3, 0, 1, "J",
             "random variation of the diameter, a fraction of D"),
    TEX_REAL_N("probability", struct holes_params, density, 0, 0.8, 0, 1, "P",
               "probability that a cell has a hole", .old = "density"),
    TEX_REAL_N("hole_depth", struct holes_params, depth, 0, 1, 0, 1, "A",
               "depth of the holes (Fact)", .old = "depth"),
    TEX_ENUM(struct holes_params, formula, 0, "scaled", "scaled|thesis",
             "the well: 1 - A e^(-8 R/D), the same shape at any diameter, or the thesis's "
             "-A e^(-N^2 R/D) with N = 4/D, R and D in cells"),
    {0}};

/* The hole of cell (i, j[, k]), wrapped by the grid: centre in cell units, diameter.  A solid
 * field (dims 3) hashes k too; the map's cells keep their 2D hash. */
static int hole(const struct tex_field *f, int dims, const int64_t c[3], double ctr[3], double *d)
{
    const struct holes_params *p = f->params;
    int64_t n = p->count, kc[3];
    for (int a = 0; a < dims; a++)
        kc[a] = f->tile ? ((c[a] % n) + n) % n : c[a];
    uint64_t h = tex_hash64(f->seed ^ tex_hash64((uint64_t)kc[0] * 0x9e3779b1u ^
                                                  tex_hash64((uint64_t)kc[1])));
    if (dims == 3)
        h = tex_hash64(h ^ tex_hash64((uint64_t)kc[2] * 0x85ebca6bu));
    double r0 = (h & 0xffff) / 65536.0, r1 = (h >> 16 & 0xffff) / 65536.0;
    double r2 = (h >> 32 & 0xffff) / 65536.0, r3 = (h >> 48) / 65536.0;

    if (r3 >= p->density)
        return 0;
    *d = p->diameter * (1 + p->jitter * (2 * r2 - 1));
    /* On the map, the rim inside the cell, so that the 3 x 3 neighbourhood sees every hole.
     * In space, the centre anywhere the rim stays within the neighbouring cells (a diameter
     * up to 1: anywhere in the cell), where the 27 cells around a point see it: kept inside
     * its cell, no hole would reach a cell's face, and a box's face, which lies on one
     * under the solid mapping, or the floor y = 0 under the world mapping, had none. */
    double room = dims == 3 ? (*d < 1 ? 1 : 2 - *d) : 1 - (*d < 1 ? *d : 1);
    ctr[0] = c[0] + 0.5 + (r0 - 0.5) * room;
    ctr[1] = c[1] + 0.5 + (r1 - 0.5) * room;
    /* in space: the third coordinate from the hash's other bits */
    ctr[2] = dims == 3 ? c[2] + 0.5 + ((double)(tex_hash64(h) & 0xffff) / 65536.0 - 0.5) * room
                       : 0;
    return 1;
}

/* The holes of the cells the last points looked at: neighbouring points (a map's row, a
 * packet's hits) share most of their cells, and a hole's hashes cost more than a look-up. */
enum { HOLE_CACHE = 64 };
struct hole_cache {
    int64_t key[HOLE_CACHE][3];
    signed char has[HOLE_CACHE]; /* -1: empty; 0: the cell has no hole; 1: it has */
    double ctr[HOLE_CACHE][3], d[HOLE_CACHE];
};

static void hole_cache_init(struct hole_cache *hc)
{
    memset(hc->has, -1, sizeof hc->has);
}

/* hole() through the cache */
static int cached_hole(struct hole_cache *hc, const struct tex_field *f, int dims,
                       const int64_t c[3], double ctr[3], double *d)
{
    unsigned e = (unsigned)((uint64_t)c[0] * 0x9e3779b1u ^ (uint64_t)c[1] * 0x85ebca6bu ^
                            (uint64_t)c[2] * 0xc2b2ae35u) %
                 HOLE_CACHE;
    if (hc->has[e] < 0 || hc->key[e][0] != c[0] || hc->key[e][1] != c[1] ||
        hc->key[e][2] != c[2]) {
        memcpy(hc->key[e], c, sizeof hc->key[e]);
        hc->has[e] = (signed char)hole(f, dims, c, hc->ctr[e], &hc->d[e]);
    }
    memcpy(ctr, hc->ctr[e], sizeof hc->ctr[e]);
    *d = hc->d[e];
    return hc->has[e];
}

/* The thesis's T = -Fact e^(-N^2 R / D) at p (dims coordinates in map units): the deepest
 * hole among the neighbouring cells', as 1 - depth e^(-8 R / D).  The deepest is the one
 * of least R / D, so exp runs once, not once per hole.  A hole's centre lies in its cell
 * and its diameter is at most dmax, so a neighbour whose gap to p exceeds the least R / D
 * so far times dmax (with a margin for rounding) cannot lower it: its hash is skipped, and
 * the minimum, which does not depend on the order, is the same to the bit. */
static float holes_point(const struct tex_field *f, struct hole_cache *hc, int dims,
                         const double *pt)
{
    const struct holes_params *p = f->params;
    double x[3] = {0, 0, 0}, rmin = INFINITY, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    double dmax = p->diameter * (1 + p->jitter) * (1 + 1e-9);
    int64_t i[3] = {0, 0, 0};
    for (int a = 0; a < dims; a++) {
        x[a] = pt[a] * p->count;
        i[a] = (int64_t)floor(x[a]);
        lo[a] = x[a] - i[a], hi[a] = i[a] + 1 - x[a]; /* gaps to the lower and upper cells */
    }
    /* the point's own cell first, whose hole bounds the others; the plane's 9, then space's */
    static const signed char off[27][3] = {
        {0, 0, 0},   {-1, 0, 0},  {1, 0, 0},   {0, -1, 0},  {0, 1, 0},  {-1, -1, 0}, {1, -1, 0},
        {-1, 1, 0},  {1, 1, 0},   {0, 0, -1},  {0, 0, 1},   {-1, 0, -1}, {1, 0, -1}, {0, -1, -1},
        {0, 1, -1},  {-1, 0, 1},  {1, 0, 1},   {0, -1, 1},  {0, 1, 1},  {-1, -1, -1}, {1, -1, -1},
        {-1, 1, -1}, {1, 1, -1},  {-1, -1, 1}, {1, -1, 1},  {-1, 1, 1}, {1, 1, 1}};
    for (int k = 0; k < (dims == 3 ? 27 : 9); k++) {
        int di = off[k][0], dj = off[k][1], dk = off[k][2];
        double g[3] = {di < 0 ? lo[0] : di > 0 ? hi[0] : 0, dj < 0 ? lo[1] : dj > 0 ? hi[1] : 0,
                       dk < 0 ? lo[2] : dk > 0 ? hi[2] : 0};
        double g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2], bound = rmin * dmax;
        if (g2 > bound * bound)
            continue;
        int64_t c[3] = {i[0] + di, i[1] + dj, i[2] + dk};
        double ctr[3], d;
        if (cached_hole(hc, f, dims, c, ctr, &d)) {
            /* N = 4/D scaled so that the well falls to e^-4 at the rim R = D/2 */
            double e[3] = {x[0] - ctr[0], x[1] - ctr[1], x[2] - ctr[2]};
            double s2 = e[0] * e[0] + e[1] * e[1] + (dims == 3 ? e[2] * e[2] : 0), lim = rmin * d;
            if (s2 > lim * lim * (1 + 1e-9)) /* farther than rmin beyond any rounding */
                continue;
            double r = (dims == 3 ? sqrt(s2) : hypot(e[0], e[1])) / d;
            rmin = r < rmin ? r : rmin; /* fmin's value: a NaN r leaves rmin, as in fmin */
        }
    }
    double best = rmin < INFINITY ? exp(-8.0 * rmin) : 0;
    return clamp_unit((float)(1.0 - p->depth * best));
}

/* The thesis's well as printed, -A e^(-N^2 R / D) with N = 4/D, R and D in cells: the
 * exponent 16 R / D^3 depends on the diameter's size, not only on R / D.  The deepest hole
 * is the one of least R / D^3; a neighbour whose gap exceeds the least so far times dmax^3
 * cannot lower it. */
static float holes_point_thesis(const struct tex_field *f, struct hole_cache *hc, int dims,
                                const double *pt)
{
    const struct holes_params *p = f->params;
    double x[3] = {0, 0, 0}, qmin = INFINITY, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    double dmax = p->diameter * (1 + p->jitter) * (1 + 1e-9), dmax3 = dmax * dmax * dmax;
    int64_t i[3] = {0, 0, 0};
    for (int a = 0; a < dims; a++) {
        x[a] = pt[a] * p->count;
        i[a] = (int64_t)floor(x[a]);
        lo[a] = x[a] - i[a], hi[a] = i[a] + 1 - x[a];
    }
    for (int di = -1; di <= 1; di++)
        for (int dj = -1; dj <= 1; dj++)
            for (int dk = dims == 3 ? -1 : 0; dk <= (dims == 3 ? 1 : 0); dk++) {
                double g[3] = {di < 0 ? lo[0] : di > 0 ? hi[0] : 0,
                               dj < 0 ? lo[1] : dj > 0 ? hi[1] : 0,
                               dk < 0 ? lo[2] : dk > 0 ? hi[2] : 0};
                double bound = qmin * dmax3;
                if (g[0] * g[0] + g[1] * g[1] + g[2] * g[2] > bound * bound)
                    continue;
                int64_t c[3] = {i[0] + di, i[1] + dj, i[2] + dk};
                double ctr[3], d;
                if (!cached_hole(hc, f, dims, c, ctr, &d))
                    continue;
                double e[3] = {x[0] - ctr[0], x[1] - ctr[1], dims == 3 ? x[2] - ctr[2] : 0};
                double q = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) / (d * d * d);
                qmin = q < qmin ? q : qmin;
            }
    double best = qmin < INFINITY ? exp(-16.0 * qmin) : 0;
    return clamp_unit((float)(1.0 - p->depth * best));
}

static void holes_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                        float *out)
{
    struct hole_cache hc;
    hole_cache_init(&hc);
    for (int i = 0; i < n; i++)
        out[i] = ((const struct holes_params *)f->params)->formula
                     ? holes_point_thesis(f, &hc, 2, (const double[2]){u[i], v[i]})
                     : holes_point(f, &hc, 2, (const double[2]){u[i], v[i]});
}

/* Spherical holes in space (thesis 5.2.2.6): the cells are cubes. */
static void holes_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                        const double *w, float *out)
{
    struct hole_cache hc;
    hole_cache_init(&hc);
    for (int i = 0; i < n; i++)
        out[i] = ((const struct holes_params *)f->params)->formula
                     ? holes_point_thesis(f, &hc, 3, (const double[3]){u[i], v[i], w[i]})
                     : holes_point(f, &hc, 3, (const double[3]){u[i], v[i], w[i]});
}

const struct tex_primitive tex_prim_holes = {
    .name = "holes",
    .summary = "randomly placed round holes (the thesis's hole model)",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct holes_params),
    .params = holes_rows,
    .eval2 = holes_eval2,
    .eval3 = holes_eval3,
};

/* ---- colour variation (Gardner) ---- */

struct colorvar_params {
    double frequency, k1, k2, b, noise;
    int terms, formula;
    float color[4];
};

static const struct tex_param colorvar_rows[] = {
    TEX_REAL(struct colorvar_params, frequency, 'f', 2, 0, 1e4, "F",
             "cycles of the first term across the map: w1 = 2 pi F (whole with --tile)"),
    TEX_INT(struct colorvar_params, terms, 0, 5, 1, 16, "N",
            "terms of each sum: C(i+1) = C(i)/sqrt 2, w(i+1) = 2 w(i)", .old = "-n"),
    TEX_REAL_N("z_phase", struct colorvar_params, k1, 0, 0.5, -100, 100, "K",
               "phase shift P_z = K1 sin(2 pi v)", .alias = "k1"),
    TEX_REAL_N("x_phase", struct colorvar_params, k2, 0, 0.5, -100, 100, "K",
               "phase shift P_x = K2 sin(2 pi B u)", .alias = "k2"),
    TEX_REAL_N("x_phase_frequency", struct colorvar_params, b, 0, 1, -1e4, 1e4, "B",
               "frequency of P_x (whole with --tile)", .alias = "b"),
    TEX_REAL(struct colorvar_params, noise, 0, 0, 0, 100, "A",
             "add A times gradient noise to both phases (breaks the regularity)"),
    TEX_COLOR_N("colour", struct colorvar_params, color, 0, NULL,
                "write an RGB map: the colour scaled by Fact (default: Fact alone)"),
    TEX_ENUM(struct colorvar_params, formula, 0, "scaled", "scaled|thesis",
             "Fact: the product over its largest value, random phases per term, in [0,1]; "
             "or the thesis's 0.5 + 0.5 (product), no phases, C_1 making the product at "
             "most 1, in [0.5,1]"),
    {0}};

struct colorvar_state {
    tex_noise_table t;
    double sumc, phase[2][16]; /* per-term phases from the seed, as in Gardner's model */
};

static int colorvar_init(struct tex_field *f)
{
    const struct colorvar_params *p = f->params;
    struct colorvar_state *s = calloc(1, sizeof *s);
    double c = 1;

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    if (f->tile && (WHOLE(colorvar_rows, struct colorvar_params, p, frequency) < 0 ||
                    WHOLE(colorvar_rows, struct colorvar_params, p, b) < 0))
        return -1;
    tex_rng r;
    tex_rng_seed(&r, f->seed);
    for (int i = 0; i < p->terms; i++, c /= sqrt(2.0)) {
        s->sumc += c;
        s->phase[0][i] = 2 * M_PI * tex_rng_uniform(&r);
        s->phase[1][i] = 2 * M_PI * tex_rng_uniform(&r);
        if (p->formula) /* the thesis's sums have no phases of their own */
            s->phase[0][i] = s->phase[1][i] = 0;
    }
    f->nc = p->color[3] > 0 ? 3 : 1;
    return tex_noise_init(&s->t, f->seed, 256, f->tile ? 4 : 0);
}

static void colorvar_fini(struct tex_field *f)
{
    struct colorvar_state *s = f->state;
    if (s)
        tex_noise_free(&s->t);
    free(s);
}

/* Fact = sum C_i (sin(w_i u + P_z + a_i) + 1) * sum C_i (sin(w_i v + P_x + b_i) + 1), over its
 * largest value (2 sum C_i)^2 so that it lies in [0,1]; (u, v) are the thesis's (x, z), and
 * h the height y that only the noise sees (the map: 0.5 / 4).  m points (m <= B), noise[]
 * the noise at each; the sines term by term over the points (tex_sin_n). */
static void colorvar_fact(const struct tex_field *f, int m, const double *u, const double *v,
                          const double *noise, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    const struct colorvar_params *p = f->params;
    const struct colorvar_state *s = f->state;
    double pz[B], px[B], su[B], sv[B], a[B], c = 1, w = 2 * M_PI * p->frequency,
                                            wb = 2 * M_PI * p->b;
    for (int i = 0; i < m; i++)
        a[i] = 2 * M_PI * v[i];
    tex_sin_n(m, a, pz, 0);
    for (int i = 0; i < m; i++)
        a[i] = wb * u[i];
    tex_sin_n(m, a, px, 0);
    for (int i = 0; i < m; i++) {
        pz[i] *= p->k1, px[i] *= p->k2;
        if (p->noise > 0) {
            double nz = p->noise * noise[i];
            pz[i] += nz;
            px[i] += nz;
        }
        su[i] = sv[i] = 0;
    }
    for (int t = 0; t < p->terms; t++, c /= sqrt(2.0), w *= 2) {
        for (int i = 0; i < m; i++)
            a[i] = w * u[i] + pz[i] + s->phase[0][t];
        tex_sin_n(m, a, a, 0);
        for (int i = 0; i < m; i++)
            su[i] += c * (a[i] + 1);
        for (int i = 0; i < m; i++)
            a[i] = w * v[i] + px[i] + s->phase[1][t];
        tex_sin_n(m, a, a, 0);
        for (int i = 0; i < m; i++)
            sv[i] += c * (a[i] + 1);
    }
    for (int i = 0; i < m; i++) {
        /* the product over its largest, (2 sum C_i)^2: in [0,1]; the thesis's 0.5 + 0.5 x */
        double fact = su[i] * sv[i] / (4 * s->sumc * s->sumc);
        if (p->formula)
            fact = 0.5 + 0.5 * fact;
        if (f->nc == 1)
            out[i] = clamp_unit((float)fact);
        else
            for (int ch = 0; ch < 3; ch++)
                out[(size_t)i * 3 + ch] = clamp_unit((float)(fact * p->color[ch]));
    }
}

/* Points (u, v) at height h[k] (NULL: 0.125), the noise batched through the point path. */
static void colorvar_points(const struct tex_field *f, int n, const double *u, const double *v,
                            const double *h, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    const struct colorvar_state *s = f->state;
    double x[B], y[B], z[B], nz[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        for (int i = 0; i < m; i++) {
            x[i] = 4 * u[i0 + i];
            y[i] = 4 * v[i0 + i];
            z[i] = 4 * (h ? h[i0 + i] + 0.125 : 0.125);
            nz[i] = 0;
        }
        if (((const struct colorvar_params *)f->params)->noise > 0)
            tex_noise_points(&s->t, s->t.period, 3, m, x, y, z, NULL, nz);
        colorvar_fact(f, m, u + i0, v + i0, nz, out + (size_t)i0 * f->nc);
    }
}

static void colorvar_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                           float *out)
{
    colorvar_points(f, n, u, v, NULL, out);
}

/* In space, as the thesis writes it: the sums run along x (u) and z (w); y (v) enters
 * through the noise only, so the slice v = 0 is the map at (u, w). */
static void colorvar_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                           const double *w, float *out)
{
    colorvar_points(f, n, u, w, v, out);
}

const struct tex_primitive tex_prim_colorvar = {
    .name = "colorvar",
    .summary = "Gardner's colour variation: products of sums of sines with shifted phases",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct colorvar_params),
    .params = colorvar_rows,
    .init = colorvar_init,
    .fini = colorvar_fini,
    .eval2 = colorvar_eval2,
    .eval3 = colorvar_eval3,
};

/* ---- perturbed regular pattern ---- */

struct perturb_params {
    double a, b, c, d, frequency;
    int octaves;
};

static const struct tex_param perturb_rows[] = {
    TEX_REAL_N("stripes", struct perturb_params, a, 0, 3, -1e4, 1e4, "A",
               "stripes across the map (whole with --tile)", .alias = "a", .old = "-a"),
    TEX_REAL_N("perturbation", struct perturb_params, b, 0, 10, -1e4, 1e4, "B",
               "strength of the perturbation", .alias = "b", .old = "-b"),
    TEX_REAL_N("turbulence_weight", struct perturb_params, c, 0, 4, -1e4, 1e4, "C",
               "weight of the turbulence", .alias = "c", .old = "-c"),
    TEX_REAL_N("waves", struct perturb_params, d, 0, 1, -1e4, 1e4, "D",
               "waves of the regular cosine along v (whole with --tile)", .alias = "d",
               .old = "-d"),
    TEX_REAL(struct perturb_params, frequency, 'f', 4, 0, 1e6, "F",
             "lattice cells across the map of the turbulence (whole with --tile)"),
    TEX_INT(struct perturb_params, octaves, 'n', 5, 1, TEX_OCTAVES_MAX, "N",
            "octaves of the turbulence"),
    {0}};

struct perturb_state {
    tex_octaves o;
    float amp[TEX_OCTAVES_MAX], inv;
};

static int perturb_init(struct tex_field *f)
{
    const struct perturb_params *p = f->params;
    struct perturb_state *s = calloc(1, sizeof *s);
    double off[3] = {0, 0, 0}, sum = 0;

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    if (f->tile && (WHOLE(perturb_rows, struct perturb_params, p, a) < 0 ||
                    WHOLE(perturb_rows, struct perturb_params, p, d) < 0))
        return -1;
    for (int k = 0; k < p->octaves; k++) {
        s->amp[k] = (float)pow(0.5, k);
        sum += s->amp[k];
    }
    s->inv = (float)(1 / sum);
    return tex_octaves_init(&s->o, f->prim->params, f->seed, 256, TEX_FADE_CUBIC, p->octaves,
                            p->frequency, 2, off, 0, 0, 3, f->tile, f->w, f->h);
}

static void perturb_fini(struct tex_field *f)
{
    struct perturb_state *s = f->state;
    if (s)
        tex_octaves_free(&s->o);
    free(s);
}

/* T = 0.5 + 0.5 sin(2 pi [A u + B/10 (C turbulence + 1 + cos(2 pi D v))]) at m <= B
 * points, out[i] the turbulence there on entry and T on return. */
static void perturb_values(const struct perturb_params *p, int m, const double *u,
                           const double *v, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    double a[B], c[B], wd = 2 * M_PI * p->d;
    for (int i = 0; i < m; i++)
        a[i] = wd * v[i];
    tex_sin_n(m, a, c, 1);
    for (int i = 0; i < m; i++)
        a[i] = 2 * M_PI * (p->a * u[i] + p->b / 10 * (p->c * out[i] + 1 + c[i]));
    tex_sin_n(m, a, a, 0);
    for (int i = 0; i < m; i++)
        out[i] = clamp_unit((float)(0.5 + 0.5 * a[i]));
}

static void perturb_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                          const double *w, float *out)
{
    const struct perturb_state *s = f->state;

    tex_octave_abs_sum(&s->o, s->o.n, s->amp, 0, n, u, v, w, out);
    for (int i0 = 0; i0 < n; i0 += TEX_POINTS_BATCH) {
        int m = n - i0 < TEX_POINTS_BATCH ? n - i0 : TEX_POINTS_BATCH;
        for (int i = i0; i < i0 + m; i++)
            out[i] *= s->inv;
        perturb_values(f->params, m, u + i0, v + i0, out + i0);
    }
}

static void perturb_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                          float *out)
{
    perturb_eval3(f, n, u, v, NULL, out);
}

static void perturb_row(const struct tex_field *f, int y, float *out)
{
    const struct perturb_state *s = f->state;
    double v = (y + 0.5) / f->h;

    for (int k = 0; k < s->o.n; k++) /* a |n| is never -0: the same as 0 + a |n| */
        tex_octave_row_op(&s->o, k, y, k ? TEX_ROW_ADD_ABS : TEX_ROW_MUL_ABS, s->amp[k], 0, 0, out);
    double U[TEX_POINTS_BATCH], V[TEX_POINTS_BATCH];
    for (int x0 = 0; x0 < f->w; x0 += TEX_POINTS_BATCH) {
        int m = f->w - x0 < TEX_POINTS_BATCH ? f->w - x0 : TEX_POINTS_BATCH;
        for (int i = 0; i < m; i++) {
            U[i] = (x0 + i + 0.5) / f->w, V[i] = v;
            out[x0 + i] *= s->inv;
        }
        perturb_values(f->params, m, U, V, out + x0);
    }
}

const struct tex_primitive tex_prim_perturb = {
    .name = "perturb",
    .summary = "a regular pattern perturbed by turbulence: marble-like veins",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct perturb_params),
    .params = perturb_rows,
    .init = perturb_init,
    .fini = perturb_fini,
    .eval2 = perturb_eval2,
    .eval3 = perturb_eval3,
    .row = perturb_row,
};
