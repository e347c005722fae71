/* test_noise.c - gradient noise, its grid rows, derivative, octaves and the stochastic
 * primitives' statistics (range, continuity, tiling, spectra) */
/* The expected row operations below are written out: no fused multiply-adds. */
#include "base/fp_strict.h"

#include <complex.h>
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "prim/noise_grid.h" /* the insides: tables and grids in the test's memory */
#include "base/simd.h"
#include "textura.h"
#include "unit.h"

static tex_map *sample(const struct tex_primitive *p, int n, int tile, const char *const *kv)
{
    struct tex_field *f = tex_field_new(p);
    tex_map *m = NULL;

    f->seed = 7;
    f->tile = tile;
    for (int i = 0; kv && kv[i]; i += 2)
        if (tex_field_set(f, kv[i], kv[i + 1]) < 0)
            goto out;
    if (tex_field_init(f, n, n) == 0)
        m = tex_field_sample(f);
out:
    tex_field_free(f);
    return m;
}

/* Mean absolute difference across the seam (last column/row to the first)
 * over the mean between interior neighbours. */
static double seam_ratio(const tex_map *m)
{
    double seam = 0, in = 0;
    int w = m->w, h = m->h, nc = m->nc;

    for (int y = 0; y < h; y++)
        for (int c = 0; c < nc; c++) {
            const float *r = tex_map_row(m, y);
            seam += fabs(r[(w - 1) * nc + c] - r[c]);
            seam += fabs(tex_map_row(m, h - 1)[y * nc + c] - tex_map_row(m, 0)[y * nc + c]);
            for (int x = 1; x < w; x++) {
                in += fabs(r[x * nc + c] - r[(x - 1) * nc + c]) / (w - 1);
                in += fabs(tex_map_row(m, x)[y * nc + c] - tex_map_row(m, x - 1)[y * nc + c]) /
                      (h - 1);
            }
        }
    return in > 0 ? seam / in : 1e9;
}

/* Slope of log power against log frequency, radially averaged, over k in [k0, k1]. */
static double spectrum_slope(const tex_map *m, int k0, int k1)
{
    int n = m->w;
    float *in = fftwf_malloc(sizeof *in * n * n);
    fftwf_complex *out = fftwf_malloc(sizeof *out * n * (n / 2 + 1));
    fftwf_plan plan = fftwf_plan_dft_r2c_2d(n, n, in, out, FFTW_ESTIMATE);
    double pw[1024] = {0}, cnt[1024] = {0}, sx = 0, sy = 0, sxx = 0, sxy = 0, mean = 0;
    int np = 0;

    for (int i = 0; i < n * n; i++)
        mean += m->px[i];
    mean /= n * n;
    for (int i = 0; i < n * n; i++)
        in[i] = (float)(m->px[i] - mean);
    fftwf_execute(plan);
    for (int y = 0; y < n; y++)
        for (int x = 0; x <= n / 2; x++) {
            int ky = y <= n / 2 ? y : y - n, k = (int)lround(sqrt((double)x * x + ky * ky));
            if (k < 1024) {
                pw[k] += cabsf(out[y * (n / 2 + 1) + x]) * cabsf(out[y * (n / 2 + 1) + x]);
                cnt[k]++;
            }
        }
    for (int k = k0; k <= k1; k++) {
        double lx = log(k), ly = log(pw[k] / cnt[k]);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, np++;
    }
    fftwf_destroy_plan(plan);
    fftwf_free(in);
    fftwf_free(out);
    return (np * sxy - sx * sy) / (np * sxx - sx * sx);
}

/* Slope of log E[(f(x+d) - f(x))^2] against log d, d = 1..16 (2H for fBm). */
static double variogram_slope(const tex_map *m)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int np = 0;

    for (int d = 1; d <= 16; d *= 2) {
        double v = 0;
        int c = 0;
        for (int y = 0; y < m->h; y++)
            for (int x = 0; x + d < m->w; x++, c++) {
                double a = tex_map_row(m, y)[x + d] - tex_map_row(m, y)[x];
                v += a * a;
            }
        double lx = log(d), ly = log(v / c);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, np++;
    }
    return (np * sxy - sx * sy) / (np * sxx - sx * sx);
}

/* Band-limited solids at points (t_apply's footprints, eval3_fw): with no footprint
 * they are eval3 bit for bit; N points equal N single points; the roughness falls as
 * the footprint grows; a footprint wider than every octave's cells leaves the mean:
 * 0.5 for fBm, E|noise| for turbulence. */
static void test_footprints(int n, const double *u, const double *v, const double *w)
{
    static const struct {
        const struct tex_primitive *p;
        const char *mode;
    } pp[] = {{&tex_prim_turbulence, NULL}, {&tex_prim_fractal, "fbm"}};
    static float big[1031], one[1031], flat[1031];
    static double fw[1031];
    for (size_t k = 0; k < sizeof pp / sizeof pp[0]; k++) {
        struct tex_field *f = tex_field_new(pp[k].p);
        const char *name = pp[k].p->name;
        tex_field_set(f, "frequency", "4");
        tex_field_set(f, "octaves", "6");
        tex_field_set(f, "band_limit", "1");
        if (pp[k].mode)
            tex_field_set(f, "mode", pp[k].mode);
        CHECKF(tex_field_init(f, 0, 0) == 0 && f->band_limit && f->prim->eval3_fw,
               "%s band_limit: a footprint-filtered solid", name);
        if (!f->band_limit || !f->prim->eval3_fw) {
            tex_field_free(f);
            continue;
        }
        for (int i = 0; i < n; i++)
            fw[i] = 0;
        f->prim->eval3(f, n, u, v, w, flat);
        f->prim->eval3_fw(f, n, u, v, w, fw, big);
        CHECKF(!memcmp(big, flat, n * sizeof *big), "%s: footprint 0 gives eval3's bits", name);
        for (int i = 0; i < n; i++)
            fw[i] = 0.04 * (i % 9) / 8.0; /* from none to every octave but the first faded */
        f->prim->eval3_fw(f, n, u, v, w, fw, big);
        for (int i = 0; i < n; i++)
            f->prim->eval3_fw(f, 1, u + i, v + i, w + i, fw + i, one + i);
        CHECKF(!memcmp(big, one, n * sizeof *big), "%s: eval3_fw over N points equals N single "
               "points", name);
        double rough[3] = {0};
        for (int c = 0; c < 3; c++) {
            static double du[1031];
            static float near[1031];
            for (int i = 0; i < n; i++) {
                fw[i] = c * 0.02;
                du[i] = u[i] + 0.003; /* neighbours a small step apart */
            }
            f->prim->eval3_fw(f, n, u, v, w, fw, big);
            f->prim->eval3_fw(f, n, du, v, w, fw, near);
            for (int i = 0; i < n; i++)
                rough[c] += fabs(big[i] - near[i]) / n;
        }
        CHECKF(rough[1] < 0.8 * rough[0] && rough[2] < 0.8 * rough[1],
               "%s: wider footprints, smoother values (steps %.4f %.4f %.4f)", name, rough[0],
               rough[1], rough[2]);
        for (int i = 0; i < n; i++)
            fw[i] = 1e3;
        f->prim->eval3_fw(f, n, u, v, w, fw, big);
        float want = pp[k].mode ? 0.5f : big[0];
        double mean = 0;
        int same = 1;
        for (int i = 0; i < n; i++) {
            same &= big[i] == want;
            mean += flat[i] / n;
        }
        CHECKF(same && fabs(mean - want) < 0.15 * want,
               "%s: a footprint wider than every cell leaves the mean everywhere (%g; the "
               "unfiltered mean %g)", name, want, mean);
        tex_field_free(f);
    }
}

/* The point path: tex_noise_points equals tex_noise3p bit for bit (vectorised where
 * the CPU has AVX2), at odd counts, far from the origin, with and without a period,
 * with n a power of two or not, and both fades; and every point primitive's eval3 over N points equals N calls of one
 * point (the scalar path), for N = 1, odd N and a whole batch and more. */
/* Every registered primitive with a point path, at its defaults: n points in one call
 * equal n calls of one point, every channel, in 2D and 3D. */
static void test_every_point_path(int n, const double *u, const double *v, const double *w)
{
    int tried = 0;
    for (int k = 0; tex_primitives[k]; k++) {
        const struct tex_primitive *p = tex_primitives[k];
        struct tex_field *f = tex_field_new(p);
        if (!f || (!p->eval2 && !p->eval3) || tex_field_init(f, 0, 0) < 0) {
            tex_field_free(f);
            continue;
        }
        int nc = f->nc, diff = 0;
        float *big = malloc(sizeof *big * n * nc), *one = malloc(sizeof *one * n * nc);
        for (int d = 2; big && one && d <= 3; d++) {
            if (d == 2 ? !p->eval2 : !p->eval3)
                continue;
            if (d == 2)
                p->eval2(f, n, u, v, big);
            else
                p->eval3(f, n, u, v, w, big);
            for (int i = 0; i < n; i++)
                if (d == 2)
                    p->eval2(f, 1, u + i, v + i, one + i * nc);
                else
                    p->eval3(f, 1, u + i, v + i, w + i, one + i * nc);
            diff += memcmp(big, one, sizeof *big * n * nc) != 0;
        }
        CHECKF(big && one && diff == 0, "%s at its defaults: %d points in one call equal %d calls",
               p->name, n, n);
        tried++;
        free(big);
        free(one);
        tex_field_free(f);
    }
    CHECKF(tried >= 20, "the primitives with a point path start at points (%d)", tried);
}

/* Noise primitives with their parameters set: eval3 and eval2 over n points equal n
 * single points, and over 3 (fewer than a vector). */
static void test_point_primitives(int n, const double *u, const double *v, const double *w,
                                  float *big, float *one)
{
    static const struct {
        const struct tex_primitive *p;
        const char *kv[6];
    } pp[] = {{&tex_prim_noise, {"frequency", "5"}},
              {&tex_prim_noise, {"frequency", "3", "time", "0.3"}},
              {&tex_prim_turbulence, {"octaves", "6", "frequency", "3"}},
              {&tex_prim_fractal, {"octaves", "7"}},
              {&tex_prim_fractal, {"mode", "ridged", "octaves", "5"}},
              {&tex_prim_fractal, {"mode", "hybrid", "octaves", "5"}},
              {&tex_prim_wood, {"grain", "0.4"}},
              {&tex_prim_perturb, {"octaves", "5"}},
              {&tex_prim_colorvar, {"noise", "0.7"}},
              {&tex_prim_bubble, {"dimension", "3", "count", "300"}},
              {&tex_prim_holes, {"seed", "4"}}};
    for (size_t k = 0; k < sizeof pp / sizeof pp[0]; k++) {
        struct tex_field *f = tex_field_new(pp[k].p);
        int diff = 0;
        for (int i = 0; i < 6 && pp[k].kv[i]; i += 2)
            tex_field_set(f, pp[k].kv[i], pp[k].kv[i + 1]);
        tex_field_init(f, 0, 0);
        for (int pass = 0; pass < 2; pass++) {
            int m = pass ? n : 3;
            f->prim->eval3(f, m, u, v, w, big);
            for (int i = 0; i < m; i++)
                f->prim->eval3(f, 1, u + i, v + i, w + i, one + i);
            diff += memcmp(big, one, m * sizeof *big) != 0;
            f->prim->eval2(f, m, u, v, big);
            for (int i = 0; i < m; i++)
                f->prim->eval2(f, 1, u + i, v + i, one + i);
            diff += memcmp(big, one, m * sizeof *big) != 0;
        }
        CHECKF(diff == 0, "%s %s %s: eval3/eval2 over N points equal N single points",
               pp[k].p->name, pp[k].kv[0], pp[k].kv[1]);
        tex_field_free(f);
    }
}

static void test_points(void)
{
    enum { N = 1031 };
    static double x[N], y[N], z[N], a[N], u[N], v[N], w[N];
    static float big[N], one[N];
    tex_rng r;
    int bad = 0, bad_at = 0;
    tex_rng_seed(&r, 17);
    for (int i = 0; i < N; i++) {
        /* 3e8: past the 2^30 cells, in some of the kernels' groups of 8 and 16 (one such point
         * sends its group to the scalar path) */
        double s = i % 61 == 0 ? 3e8 : i % 5 == 0 ? 2e3 : 20;
        x[i] = s * (2 * tex_rng_uniform(&r) - 1);
        y[i] = s * (2 * tex_rng_uniform(&r) - 1);
        z[i] = i % 11 == 0 ? floor(z[i - 1 > 0 ? i - 1 : 0]) : 20 * tex_rng_uniform(&r);
        u[i] = 4 * tex_rng_uniform(&r) - 2;
        v[i] = 4 * tex_rng_uniform(&r) - 2;
        w[i] = i % 13 == 0 ? 1e6 : tex_rng_uniform(&r);
    }
    for (int c = 0; c < 6; c++) { /* n = 97: the lattice index is no mask */
        tex_noise_table t;
        int period = c & 1 ? 7 : 0, cnt = c == 2 ? 1019 : c == 4 ? 5 : N; /* 1019: 16s, 8, 3 */
        tex_noise_init(&t, 11 + c, c >= 3 ? 97 : 256, 0);
        t.fade = c >= 2 ? TEX_FADE_QUINTIC : TEX_FADE_CUBIC;
        tex_noise_points(&t, period, 3, cnt, x, y, z, NULL, a);
        for (int i = 0; i < cnt; i++)
            bad += memcmp(&a[i], &(double){tex_noise3p(&t, period, x[i], y[i], z[i])},
                          sizeof a[i]) != 0;
        /* at a + f (x, y, z) and a + f (x, y, 0): x and y past 2^30 cells at times */
        const double off[3] = {0.37, -12.5, 3.25}, f = c & 2 ? -2.5 : 3;
        for (int k = 0; k < 2; k++) {
            tex_noise_points_at(&t, period, off, f, cnt, x, y, k ? NULL : z, big);
            for (int i = 0; i < cnt; i++) {
                float s = (float)tex_noise3p(&t, period, off[0] + f * x[i], off[1] + f * y[i],
                                             off[2] + f * (k ? 0 : z[i]));
                bad_at += memcmp(&big[i], &s, sizeof s) != 0;
            }
        }
        tex_noise_free(&t);
    }
    const char *kernel = tex_simd_vbmi() ? "avx512 vbmi" : tex_simd_name(tex_simd_level());
    CHECKF(bad == 0, "tex_noise_points equals tex_noise3p bit for bit (%s; %d differ)", kernel,
           bad);
    CHECKF(bad_at == 0, "tex_noise_points_at equals tex_noise3p at its points bit for bit (%s; "
           "%d differ)", kernel, bad_at);
    test_point_primitives(N, u, v, w, big, one);
    test_footprints(N, u, v, w);
    test_every_point_path(N, u, v, w);
}

/* Grid rows agree with the point evaluation: 2D, 3D slice, 4D, period, far away. */
static void test_rows_points(const tex_noise_table *t)
{
    struct {
        double off[4];
        int dims, period, w;
        double freq;
    } cs[] = {{{0, 0, 0, 0}, 3, 0, 300, 8},       {{0.3, 0.1, 2.37, 0}, 3, 0, 257, 33},
              {{0, 0, 0.5, 1.25}, 4, 0, 128, 5},  {{0, 0, 0, 0}, 3, 16, 64, 16},
              {{1e6, -3e6, 1e6, 0}, 3, 0, 100, 7}, {{0, 0, 0.1, 0}, 3, 0, 50, 400}};
    for (int c = 0; c < 6; c++) {
        tex_noise_grid g;
        float row[512];
        double err = 0;
        tex_noise_grid_init(&g, t, cs[c].w, 40, cs[c].freq, cs[c].freq, cs[c].off, cs[c].dims,
                            cs[c].period);
        for (int y = 0; y < 40; y += 3) {
            tex_noise_grid_row(&g, y, row);
            for (int x = 0; x < cs[c].w; x++) {
                double X = cs[c].off[0] + cs[c].freq * ((x + 0.5) / cs[c].w),
                       Y = cs[c].off[1] + cs[c].freq * ((y + 0.5) / 40);
                double s = cs[c].dims == 4 ? tex_noise4p(t, cs[c].period, X, Y, cs[c].off[2],
                                                         cs[c].off[3])
                                           : tex_noise3p(t, cs[c].period, X, Y, cs[c].off[2]);
                err = fmax(err, fabs(s - row[x]));
                if (isnan(row[x]))
                    err = INFINITY;
            }
        }
        tex_noise_grid_free(&g);
        CHECKF(err < 2e-6, "grid case %d (dims %d, period %d, f %g) matches points (%g)", c,
               cs[c].dims, cs[c].period, cs[c].freq, err);
    }
}

/* Rows kept between calls (lattice rows shared by neighbouring pixel rows)
 * give the same bytes whatever order the rows come in: in order, backwards,
 * scattered, each row from a fresh grid; with one octave or many. */
static void test_rows_kept(const tex_noise_table *t)
{
    enum { W = 300, H = 200 };
    double off[4] = {0.25, 3.5, 0.7, 0};
    float *ref = malloc(sizeof *ref * W * H), row[W];
    tex_noise_grid g;
    int bad[3] = {0, 0, 0};
    tex_noise_grid_init(&g, t, W, H, 11, 11, off, 3, 0);
    CHECK(g.cache != NULL, "a grid with cells taller than a pixel keeps lattice rows");
    for (int y = 0; y < H; y++)
        tex_noise_grid_row_op(&g, y, TEX_ROW_UNIT, 0, 0, 0, ref + y * W);
    for (int y = H - 1; y >= 0; y--) {
        tex_noise_grid_row_op(&g, y, TEX_ROW_UNIT, 0, 0, 0, row);
        bad[0] |= memcmp(row, ref + y * W, sizeof row) != 0;
    }
    for (int i = 0; i < H; i++) {
        int y = (i * 37 + 11) % H; /* 37 is prime to 200: every row once */
        tex_noise_grid_row_op(&g, y, TEX_ROW_UNIT, 0, 0, 0, row);
        bad[1] |= memcmp(row, ref + y * W, sizeof row) != 0;
    }
    tex_noise_grid_free(&g);
    for (int y = 0; y < H; y += 7) {
        tex_noise_grid_init(&g, t, W, H, 11, 11, off, 3, 0);
        tex_noise_grid_row_op(&g, y, TEX_ROW_UNIT, 0, 0, 0, row);
        bad[2] |= memcmp(row, ref + y * W, sizeof row) != 0;
        tex_noise_grid_free(&g);
    }
    CHECKF(!bad[0] && !bad[1] && !bad[2],
           "grid rows: same bytes backwards %d, scattered %d, from fresh grids %d", !bad[0],
           !bad[1], !bad[2]);
    free(ref);
}

/* The row operations are what they say, on the same noise. */
static void test_row_ops(const tex_noise_table *t)
{
    float n[64], o[128], v[128]; /* the sum, then the multifractal steps' state */
    double off[4] = {0.1, 0.2, 0.3, 0};
    int bad = 0;
    tex_noise_grid g;
    tex_noise_grid_init(&g, t, 64, 8, 5, 5, off, 3, 0);
    tex_noise_grid_row(&g, 3, n);
    for (int op = TEX_ROW_SET; op <= TEX_ROW_HYBRID_LAST; op++) {
        struct tex_mf_k k = {0.7f, 1.3f, 0.8f, 0.3f, 0.6f};
        for (int x = 0; x < 128; x++)
            o[x] = v[x] = 0.25f - 0.01f * (x % 64) + (x >= 64 ? 0.9f : 0);
        if (op < TEX_ROW_RIDGED_FIRST)
            tex_noise_grid_row_op(&g, 3, op, 0.7f, 1.3f, 0.8f, o);
        else
            tex_noise_grid_rows_mf(&g, 3, 1, op, &k, o, o + 64, 0);
        for (int x = 0; x < 64; x++) {
            float a = 0.7f, b = 1.3f, c = 0.8f, r = n[x], e, st = v[64 + x], s = st;
            switch (op) {
            case TEX_ROW_SET: e = r; break;
            case TEX_ROW_MUL: e = a * r; break;
            case TEX_ROW_MUL_ABS: e = a * fabsf(r); break;
            case TEX_ROW_UNIT: e = fminf(fmaxf(0.5f + 0.5f * r, 0), 1); break;
            case TEX_ROW_ADD: e = v[x] + a * r; break;
            case TEX_ROW_ADD_ABS: e = v[x] + a * fabsf(r); break;
            case TEX_ROW_ADD_UNIT: e = fminf(fmaxf(0.5f + 0.5f * ((v[x] + a * r) * b), 0), 1); break;
            case TEX_ROW_ADD_ABS_CLAMP: e = fminf(fmaxf((v[x] + a * fabsf(r)) * b, 0), 1); break;
            case TEX_ROW_RIDGED_FIRST: e = s = (b - fabsf(r)) * (b - fabsf(r)); break;
            case TEX_ROW_RIDGED:
                s = fminf(fmaxf(st * c, 0), 1) * ((b - fabsf(r)) * (b - fabsf(r)));
                e = v[x] + s * a;
                break;
            case TEX_ROW_RIDGED_LAST: /* the step, the finish, the state kept */
                e = v[x] + fminf(fmaxf(st * c, 0), 1) * ((b - fabsf(r)) * (b - fabsf(r))) * a;
                e = fminf(fmaxf((e - k.lo) * k.inv, 0), 1);
                break;
            case TEX_ROW_HYBRID_FIRST: e = s = (r + b) * a; break;
            case TEX_ROW_HYBRID: s = fminf(st, 1) * ((r + b) * a), e = v[x] + s; break;
            default:
                e = fminf(fmaxf((v[x] + fminf(st, 1) * ((r + b) * a) - k.lo) * k.inv, 0), 1);
                break;
            }
            bad += o[x] != e || o[64 + x] != s;
        }
    }
    tex_noise_grid_free(&g);
    CHECKF(bad == 0, "row operations set, mul, |n|, unit, add, the finishes and the multifractal "
                     "steps (%d wrong)", bad);
}

/* Rows made together (tex_noise_grid_rows_op: the kernels two rows at a time) equal rows
 * made one by one, for every kind of grid, an odd count, every kind of operation. */
static void test_rows_together(const tex_noise_table *t)
{
    enum { W = 1100, N = 5 };
    /* cells across and down 400 rows: wide, then folded (planar permutes; loads per
     * column, from two rows' table or one row's interleaved, 1900 and 4000 across), then
     * without a table (slots, paired slots) */
    static const double cells[][2] = {{20, 40},     {300, 600},  {1000, 2000}, {1900, 3800},
                                      {4000, 8000}, {300, 150}, {1000, 40}};
    static const int ops[] = {TEX_ROW_SET,    TEX_ROW_ADD_UNIT, TEX_ROW_RIDGED,
                              TEX_ROW_HYBRID, TEX_ROW_RIDGED_LAST, TEX_ROW_HYBRID_LAST};
    const struct tex_mf_k k = {0.6f, 0.9f, 1.2f, 0.2f, 0.7f};
    static float a[N * 2 * W], b[N * 2 * W];
    double off[4] = {0.37, 0.21, 0.3, 0};
    int bad = 0, folded = 0;

    for (size_t c = 0; c < sizeof cells / sizeof *cells; c++) {
        tex_noise_grid g;
        tex_noise_grid_init(&g, t, W, 400, cells[c][0], cells[c][1], off, 3, 0);
        folded += g.folded;
        for (size_t o = 0; o < sizeof ops / sizeof *ops; o++) {
            for (int i = 0; i < N * 2 * W; i++)
                a[i] = b[i] = 0.5f + 0.001f * (i % 97);
            if (ops[o] < TEX_ROW_RIDGED_FIRST)
                tex_noise_grid_rows_op(&g, 7, N, ops[o], 0.6f, 0.9f, 1.2f, a, 2 * W);
            else
                tex_noise_grid_rows_mf(&g, 7, N, ops[o], &k, a, a + W, 2 * W);
            for (int r = 0; r < N; r++)
                if (ops[o] < TEX_ROW_RIDGED_FIRST)
                    tex_noise_grid_row_op(&g, 7 + r, ops[o], 0.6f, 0.9f, 1.2f, b + r * 2 * W);
                else
                    tex_noise_grid_rows_mf(&g, 7 + r, 1, ops[o], &k, b + r * 2 * W,
                                           b + r * 2 * W + W, 0);
            bad += memcmp(a, b, sizeof a) != 0;
        }
        tex_noise_grid_free(&g);
    }
    CHECKF(bad == 0 && folded == 4, "rows made two at a time equal rows one by one (%d differ, "
                                    "%d grids folded)", bad, folded);
}

/* 3D noise's range, mean, continuity and zeros, and its analytic gradient. */
static void test_noise3_values(tex_noise_table *t)
{
    tex_rng r;
    double lo = 1, hi = -1, sum = 0, maxstep = 0, maxerr = 0;
    int n = 200000;

    tex_rng_seed(&r, 1);
    for (int i = 0; i < n; i++) {
        double x = 100 * tex_rng_uniform(&r), y = 100 * tex_rng_uniform(&r),
               z = 100 * tex_rng_uniform(&r), s = tex_noise3(t, x, y, z);
        lo = fmin(lo, s), hi = fmax(hi, s), sum += s;
        /* Continuity: a step of 1e-4 moves the noise by at most a few 1e-4. */
        maxstep = fmax(maxstep, fabs(tex_noise3(t, x + 1e-4, y, z) - s));
    }
    CHECKF(lo >= -1 && hi <= 1 && hi - lo > 0.8, "3D noise within [-1,1] and spread (%g..%g)", lo,
           hi);
    CHECKF(fabs(sum / n) < 0.01, "3D noise mean near 0 (%g)", sum / n);
    CHECKF(maxstep < 4e-4, "noise is continuous (largest change %g over 1e-4)", maxstep);
    CHECK(tex_noise3(t, 5, -7, 11) == 0, "noise vanishes at lattice points");

    /* The analytic gradient matches central differences of its own value (double
     * precision throughout), and that value is 3D noise's (whose corners sum in float)
     * to float precision; both fades. */
    for (int fade = 0; fade < 2; fade++) {
        double verr = 0;
        t->fade = fade;
        maxerr = 0;
        for (int i = 0; i < 2000; i++) {
            double x = 50 * tex_rng_uniform(&r), y = 50 * tex_rng_uniform(&r),
                   z = 50 * tex_rng_uniform(&r), g[3], h[3], e = 1e-5;
            double s = tex_noise3_grad(t, 0, x, y, z, g);
            double fd[3] = {(tex_noise3_grad(t, 0, x + e, y, z, h) -
                             tex_noise3_grad(t, 0, x - e, y, z, h)) / (2 * e),
                            (tex_noise3_grad(t, 0, x, y + e, z, h) -
                             tex_noise3_grad(t, 0, x, y - e, z, h)) / (2 * e),
                            (tex_noise3_grad(t, 0, x, y, z + e, h) -
                             tex_noise3_grad(t, 0, x, y, z - e, h)) / (2 * e)};
            for (int a = 0; a < 3; a++)
                maxerr = fmax(maxerr, fabs(fd[a] - g[a]));
            verr = fmax(verr, fabs(s - tex_noise3(t, x, y, z)));
        }
        CHECKF(maxerr < 1e-6, "%s: gradient matches finite differences (error %g)",
               fade ? "quintic" : "cubic", maxerr);
        CHECKF(verr > 0 && verr < 4e-6, "%s: the gradient's value is the noise's, to float "
               "precision (%g)", fade ? "quintic" : "cubic", verr);
    }
    t->fade = 0;
}

static void test_grid_gradient(tex_noise_table *t)
{
    /* Grid rows of the gradient agree with the point evaluation's. */
    for (int fd = 0; fd < 2; fd++) {
        struct {
            double off[4];
            int period, w;
            double freq;
        } cs[] = {{{0, 0, 0, 0}, 0, 300, 8},      {{0.3, 0.1, 2.37, 0}, 0, 257, 33},
                  {{0, 0, 0.5, 0}, 16, 64, 16},   {{1e6, -3e6, 1e6, 0}, 0, 100, 7},
                  {{0, 0, 0.1, 0}, 0, 50, 400}};
        double err = 0;
        t->fade = fd;
        for (int c = 0; c < 5; c++) {
            tex_noise_grid g;
            float d[3][512];
            tex_noise_grid_init(&g, t, cs[c].w, 40, cs[c].freq, cs[c].freq, cs[c].off, 3,
                                cs[c].period);
            for (int y = 0; y < 40; y += 3) {
                tex_noise_grid_row_grad(&g, y, d[0], d[1], d[2]);
                for (int x = 0; x < cs[c].w; x++) {
                    double X = cs[c].off[0] + cs[c].freq * ((x + 0.5) / cs[c].w),
                           Y = cs[c].off[1] + cs[c].freq * ((y + 0.5) / 40), gr[3];
                    tex_noise3_grad(t, cs[c].period, X, Y, cs[c].off[2], gr);
                    for (int a = 0; a < 3; a++)
                        err = isnan(d[a][x]) ? INFINITY : fmax(err, fabs(gr[a] - d[a][x]));
                }
            }
            tex_noise_grid_free(&g);
        }
        CHECKF(err < 2e-5, "%s: grid rows of the gradient match the points' (%g)",
               fd ? "quintic" : "cubic", err);
    }
    t->fade = 0;
}

static void test_d_noise_rows(void)
{
    /* t_d_noise's grid rows agree with its points (raw gradient and normal map). */
    for (int normal = 0; normal < 2; normal++) {
        struct tex_field *f = tex_field_new(&tex_prim_d_noise);
        tex_map *m;
        double err = 0;
        f->seed = 3;
        tex_field_set(f, "frequency", "6");
        tex_field_set(f, "z", "0.4");
        if (normal)
            tex_field_set(f, "normal", NULL);
        else
            tex_field_set(f, "channels", "3");
        tex_field_init(f, 70, 30);
        m = tex_field_sample(f);
        for (int y = 0; m && y < 30; y++) {
            double u[70], v[70];
            float pt[70 * 3];
            for (int x = 0; x < 70; x++)
                u[x] = (x + 0.5) / 70, v[x] = (y + 0.5) / 30;
            f->prim->eval2(f, 70, u, v, pt);
            for (int i = 0; i < 70 * 3; i++)
                err = fmax(err, fabs(pt[i] - tex_map_row(m, y)[i]));
        }
        CHECKF(m && m->nc == 3 && err < 1e-5, "d_noise%s: map rows match points (%g)",
               normal ? " --normal" : "", err);
        tex_map_free(m);
        tex_field_free(f);
    }
}

static void test_far(const tex_noise_table *t)
{
    /* Far from the origin the texture survives. */
    {
        double s2 = 0;
        for (int i = 0; i < 1000; i++) {
            double s = tex_noise3(t, 1e12 + i * 0.173, 3e9 + i * 0.071, 0.5);
            s2 += s * s;
            if (isnan(s))
                s2 = NAN;
        }
        CHECKF(sqrt(s2 / 1000) > 0.1, "noise at 1e12 keeps its texture (rms %g)", sqrt(s2 / 1000));
    }
}

static void test_primitive_maps(void)
{
    /* Statistics and tiling of the primitives through their descriptors. */
    {
        const char *noise_kv[] = {"frequency", "8", NULL};
        tex_map *m = sample(&tex_prim_noise, 256, 0, noise_kv);
        struct tex_stats st;
        tex_map_stats(m, 0, &st);
        CHECKF(st.min >= 0 && st.max <= 1 && fabs(st.mean - 0.5) < 0.03,
               "t_noise in [0,1] with mean near 0.5 (%g..%g, mean %g)", st.min, st.max, st.mean);
        tex_map_free(m);
    }
    {
        struct {
            const struct tex_primitive *p;
            const char *kv[7];
        } tp[] = {{&tex_prim_noise, {"frequency", "5", NULL}},
                  {&tex_prim_noise, {"frequency", "3", "w", "0.4", NULL}},
                  {&tex_prim_d_noise, {"frequency", "4", "normal", NULL, NULL}},
                  {&tex_prim_turbulence, {"frequency", "3", NULL}},
                  {&tex_prim_fractal, {"mode", "fbm", "frequency", "2", NULL}},
                  {&tex_prim_fractal, {"mode", "ridged", "frequency", "2", NULL}},
                  {&tex_prim_fractal, {"mode", "hybrid", "frequency", "2", NULL}},
                  {&tex_prim_fractal, {"mode", "midpoint", NULL}},
                  {&tex_prim_holes, {"grid_cells", "5", NULL}},
                  {&tex_prim_colorvar, {"noise", "1", NULL}},
                  {&tex_prim_perturb, {"frequency", "3", NULL}}};
        for (size_t i = 0; i < sizeof tp / sizeof *tp; i++) {
            const char *kv[7];
            memcpy(kv, tp[i].kv, sizeof kv);
            if (tp[i].p == &tex_prim_d_noise)
                kv[2] = NULL; /* --normal is a flag: leave the defaults */
            tex_map *m = sample(tp[i].p, 128, 1, kv);
            double q = m ? seam_ratio(m) : 1e9;
            CHECKF(q < 1.6, "%s %s tiles: seam/interior difference %.3f", tp[i].p->name,
                   kv[1] ? kv[1] : "", q);
            tex_map_free(m);
        }
        const char *kv[] = {"frequency", "5.5", NULL};
        tex_map *m = sample(&tex_prim_noise, 128, 0, kv);
        double q = seam_ratio(m);
        CHECKF(q > 3, "without --tile the seam is a jump (%.3f): the tiling check can fail", q);
        tex_map_free(m);
    }
}

/* The octave sums' rows (the multifractal steps in the row operations, the last one
 * finishing the sum; a lone octave finished on its own) agree with their points.  600
 * pixels: the finer octaves' grids are folded, the finest into two rows' table (fold2). */
static void test_sum_rows_points(void)
{
    enum { N = 600 };
    static const char *const modes[] = {"fbm", "ridged", "hybrid"}, *const octaves[] = {"1", "6"};
    static double u[N], v[N];
    static float pt[N];
    for (int m = 0; m < 3; m++)
        for (int o = 0; o < 2; o++) {
            struct tex_field *f = tex_field_new(&tex_prim_fractal);
            double err = 0;
            f->seed = 5;
            tex_field_set(f, "mode", modes[m]);
            tex_field_set(f, "octaves", octaves[o]);
            tex_field_set(f, "frequency", "40"); /* 15 pixels a cell down to 0.47 */
            tex_field_set(f, "mf_offset", m == 2 ? "0.7" : "1");
            tex_field_init(f, N, N);
            tex_map *map = tex_field_sample(f);
            for (int y = 0; map && y < N; y += 7) {
                for (int x = 0; x < N; x++)
                    u[x] = (x + 0.5) / N, v[x] = (y + 0.5) / N;
                f->prim->eval2(f, N, u, v, pt);
                for (int x = 0; x < N; x++)
                    err = fmax(err, isnan(map->px[y * N + x]) ? INFINITY
                                                               : fabs(map->px[y * N + x] - pt[x]));
            }
            CHECKF(map && err < 1e-5, "%s, %s octave(s): rows agree with points (%g)", modes[m],
                   octaves[o], err);
            tex_map_free(map);
            tex_field_free(f);
        }
}

/* fBm's spectrum, midpoint displacement's variogram and the Mandelbrot set. */
static void test_fractal_statistics(void)
{
    /* fBm's spectrum falls as k^-(2H+2): compare H = 0.4 and H = 1. */
    {
        const char *a[] = {"mode", "fbm", "h", "0.4", "frequency", "2", "octaves", "8", NULL};
        const char *b[] = {"mode", "fbm", "h", "1", "frequency", "2", "octaves", "8", NULL};
        tex_map *ma = sample(&tex_prim_fractal, 256, 1, a), *mb = sample(&tex_prim_fractal, 256, 1, b);
        double sa = spectrum_slope(ma, 6, 60), sb = spectrum_slope(mb, 6, 60);
        CHECKF(fabs(sa + 2.8) < 0.6 && fabs(sb + 4) < 0.6,
               "fBm spectral slopes match -(2H+2): H=0.4 %.2f (-2.8), H=1 %.2f (-4)", sa, sb);
        tex_map_free(ma);
        tex_map_free(mb);
    }
    /* Midpoint displacement with one h has fBm statistics: variogram ~ d^(2H). */
    for (int i = 0; i < 2; i++) {
        const char *h = i ? "0.8" : "0.4";
        const char *kv[] = {"mode", "midpoint", "h", h, NULL};
        tex_map *m = sample(&tex_prim_fractal, 256, 0, kv);
        double s = variogram_slope(m);
        CHECKF(fabs(s - 2 * atof(h)) < 0.3, "midpoint h=%s: variogram slope %.2f (2H = %.1f)", h,
               s, 2 * atof(h));
        tex_map_free(m);
    }
    /* Known points of the Mandelbrot set. */
    {
        struct tex_field *f = tex_field_new(&tex_prim_fractal);
        double u[2] = {0.5, 0.75}, v[2] = {0.5, 0.5};
        float out[2];
        tex_field_set(f, "mode", "mandelbrot");
        tex_field_set(f, "centre", "0,0");
        tex_field_init(f, 0, 0);
        f->prim->eval2(f, 2, u, v, out);
        CHECKF(out[0] == 1 && out[1] < 0.1, "Mandelbrot: c=0 inside (%g), c=1 outside (%g)", out[0],
               out[1]);
        tex_field_free(f);
    }
}

/* The public header's tables, grids and octaves (made by _new, opaque) give what libtex's own
 * ones in the caller's memory give, and refuse what those refuse. */
static void test_public(const tex_noise_table *t)
{
    tex_noise_table *h = tex_noise_new(3, 256, 0), q;
    const double off[4] = {0.3, -1.7, 0.4, 0};
    float a[64], b[64];
    int same = 1, quintic = 1;

    CHECK(h != NULL, "tex_noise_new makes a table");
    if (!h)
        return;
    for (int i = 0; i < 200; i++) {
        double x = i * 0.173, y = i * 0.071 - 3, z = 0.25 + i * 0.01;
        same &= tex_noise3(h, x, y, z) == tex_noise3(t, x, y, z);
    }
    tex_noise_init(&q, 3, 256, 0);
    q.fade = TEX_FADE_QUINTIC;
    tex_noise_set_fade(h, TEX_FADE_QUINTIC);
    for (int i = 0; i < 200; i++)
        quintic &= tex_noise3(h, i * 0.31, 0.5, 0.25) == tex_noise3(&q, i * 0.31, 0.5, 0.25);
    tex_noise_free(&q);
    tex_noise_set_fade(h, TEX_FADE_CUBIC);
    CHECK(same && quintic, "a table from tex_noise_new gives the values of one in the caller's "
                           "memory, with either fade");
    tex_noise_grid *g = tex_noise_grid_new(h, 64, 8, 5, 5, off, 3, 0), sg;
    tex_noise_grid_init(&sg, t, 64, 8, 5, 5, off, 3, 0);
    same = g != NULL;
    for (int y = 0; g && y < 8; y++) {
        tex_noise_grid_row(g, y, a);
        tex_noise_grid_row(&sg, y, b);
        same &= memcmp(a, b, sizeof a) == 0;
    }
    tex_noise_grid_free(&sg);
    tex_noise_grid_delete(g);
    CHECK(same, "a grid from tex_noise_grid_new gives the rows of one in the caller's memory");
    CHECK(tex_noise_grid_new(h, 0, 8, 5, 5, off, 3, 0) == NULL, "a grid of no columns is refused");
    tex_octaves so, *o = tex_octaves_new(3, 256, 0, 4, 3, 2, off, 0.1, 0, 3, 0, 64, 8);
    tex_octaves_init(&so, NULL, 3, 256, 0, 4, 3, 2, off, 0.1, 0, 3, 0, 64, 8);
    same = o != NULL;
    for (int k = 0; o && k < 4; k++) {
        same &= tex_octave_point(o, k, 0.3, 0.6, 0.2) == tex_octave_point(&so, k, 0.3, 0.6, 0.2);
        tex_octave_row(o, k, 5, a);
        tex_octave_row(&so, k, 5, b);
        same &= memcmp(a, b, sizeof a) == 0;
    }
    tex_octaves_free(&so);
    tex_octaves_delete(o);
    CHECK(same, "octaves from tex_octaves_new give the points and rows of octaves in the "
                "caller's memory");
    CHECK(tex_octaves_new(3, 256, 0, TEX_OCTAVES_MAX + 1, 3, 2, off, 0, 0, 3, 0, 0, 0) == NULL,
          "too many octaves are refused");
    tex_noise_delete(h);
    CHECK(tex_noise_new(3, TEX_NOISE_MAX_GRADIENTS + 1, 0) == NULL,
          "too many gradients are refused");
}

int main(void)
{
    tex_noise_table t;

    CHECK(tex_noise_init(&t, 3, 256, 0) == 0, "noise table");
    test_noise3_values(&t);
    test_rows_points(&t);
    test_sum_rows_points();
    test_rows_kept(&t);
    test_row_ops(&t);
    test_rows_together(&t);
    if (tex_simd_level() >= TEX_SIMD_AVX512) { /* and the AVX2 kernels */
        tex_simd_limit(TEX_SIMD_AVX2);
        test_rows_together(&t);
        tex_simd_limit(TEX_SIMD_AVX512);
    }
    test_grid_gradient(&t);
    test_d_noise_rows();
    test_far(&t);
    test_public(&t);
    tex_noise_free(&t);
    test_primitive_maps();
    test_fractal_statistics();
    test_points();
    if (tex_simd_vbmi()) { /* that was the byte-table kernel: the gathers too */
        tex_simd_limit(TEX_SIMD_AVX2);
        test_points();
        tex_simd_limit(TEX_SIMD_AVX512);
    }
    return unit_done();
}
