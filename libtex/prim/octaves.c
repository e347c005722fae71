/* octaves.c - octaves of gradient noise: sums at growing frequencies, at points and on grids */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/simd.h"
#include "prim/noise.h"
#include "prim/noise_grid.h"
#include "prim/prim.h"
#include "prim/x86/noise_x86.h"

/* How a message names the parameter called name: as the option of its row in rows (a
 * primitive's, tex_param_find), or as name itself for the library's callers (rows NULL) */
static const char *row_option(const struct tex_param *rows, const char *name, char *buf,
                              size_t n)
{
    const struct tex_param *p = rows ? tex_param_find(rows, name) : NULL;
    return p ? tex_param_option(p, buf, n) : name;
}

int tex_noise_whole_frequency(const struct tex_param *rows, double freq)
{
    char nf[64];
    if (freq != floor(freq) || freq < 1)
        return tex_usage_error("%s must be a whole number >= 1 with %s (got %g)",
                               row_option(rows, "frequency", nf, sizeof nf),
                               rows ? TEX_FIELD_OPTION(tile) : "tile", freq);
    return 0;
}

/* The octaves' checks: their count, and with tile whole frequencies within 1e9 */
static int octaves_check(const struct tex_param *rows, int n, double freq, double lac, int tile)
{
    char no[64], nf[64], nl[64];
    const char *octaves = row_option(rows, "octaves", no, sizeof no);
    const char *lacunarity = row_option(rows, "lacunarity", nl, sizeof nl);

    if (n < 1 || n > TEX_OCTAVES_MAX)
        return tex_usage_error("%s must be 1..%d (got %d)", octaves, TEX_OCTAVES_MAX, n);
    if (!tile)
        return 0;
    if (tex_noise_whole_frequency(rows, freq) < 0)
        return -1;
    if (lac != floor(lac))
        return tex_usage_error("%s must be a whole number with %s (got %g)", lacunarity,
                               rows ? TEX_FIELD_OPTION(tile) : "tile", lac);
    for (int k = 0; k < n; k++)
        if (freq * pow(lac, k) > 1e9)
            return tex_usage_error("%s: the last octave's frequency %g is above 1e9 (lower %s, %s "
                                   "or %s)", rows ? TEX_FIELD_OPTION(tile) : "tile",
                                   freq * pow(lac, k), octaves,
                                   row_option(rows, "frequency", nf, sizeof nf), lacunarity);
    return 0;
}

int tex_octaves_init(tex_octaves *o, const struct tex_param *rows, uint64_t seed, int gradients,
                     int fade, int n, double freq, double lac, const double off[3], double z,
                     double t, int dims, int tile, int w, int h)
{
    /* Irrational-looking shifts so that the octaves do not all vanish together. */
    static const double shift[4] = {13.1367, 7.7351, 3.5193, 5.2371};

    memset(o, 0, sizeof *o);
    if (octaves_check(rows, n, freq, lac, tile) < 0)
        return -1;
    o->n = n;
    o->dims = dims;
    for (int k = 0; k < n; k++) {
        double s = pow(lac, k);
        o->freq[k] = freq * s;
        o->period[k] = tile ? (int)o->freq[k] : 0;
        o->off[k][0] = s * off[0] + (k ? k * shift[0] : 0);
        o->off[k][1] = s * off[1] + (k ? k * shift[1] : 0);
        o->off[k][2] = s * (freq * z + off[2]) + (k ? k * shift[2] : 0);
        o->off[k][3] = dims == 4 ? s * freq * t + (k ? k * shift[3] : 0) : 0;
    }
    if (tex_noise_init(&o->t, seed, gradients, 0) < 0)
        return -1;
    o->t.fade = fade;
    if (w > 0 && h > 0) {
        int wide = 0;
        o->grid = 1;
        for (int k = 0; k < n; k++) {
            if (tex_noise_grid_init(&o->g[k], &o->t, w, h, o->freq[k], o->freq[k], o->off[k],
                                    dims, o->period[k]) < 0) {
                tex_octaves_free(o);
                return -1;
            }
            wide += o->g[k].wide;
        }
        /* AVX-512 rows for the wide octaves only where they are most of the sum: a map that
         * switches between 512- and 256-bit rows runs slower than on 256 alone. */
        for (int k = 0; 2 * wide < n && k < n; k++)
            o->g[k].wide = 0;
    }
    return 0;
}

void tex_octaves_free(tex_octaves *o)
{
    if (!o)
        return;
    tex_noise_free(&o->t);
    for (int k = 0; k < o->n; k++)
        tex_noise_grid_free(&o->g[k]);
    o->grid = 0;
}

void tex_octaves_delete(tex_octaves *o)
{
    tex_octaves_free(o); /* NULL: nothing */
    free(o);
}

tex_octaves *tex_octaves_new(uint64_t seed, int gradients, int fade, int n, double freq,
                             double lac, const double off[3], double z, double t, int dims,
                             int tile, int w, int h)
{
    tex_octaves *o = malloc(sizeof *o);
    return tex_noise_made(o, o ? tex_octaves_init(o, NULL, seed, gradients, fade, n, freq, lac,
                                                  off, z, t, dims, tile, w, h)
                               : tex_error("out of memory"));
}

double tex_octave_point(const tex_octaves *o, int k, double u, double v, double w)
{
    double f = o->freq[k], x = o->off[k][0] + f * u, y = o->off[k][1] + f * v;

    if (o->dims == 4)
        return tex_noise4p(&o->t, o->period[k], x, y, o->off[k][2] + f * w, o->off[k][3]);
    return tex_noise3p(&o->t, o->period[k], x, y, o->off[k][2] + f * w);
}

void tex_octave_points(const tex_octaves *o, int k, int n, const double *u, const double *v,
                       const double *w, double *out)
{
    enum { B = TEX_POINTS_BATCH };
    double f = o->freq[k], X[B], Y[B], Z[B], W[B];
    float r[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        if (o->dims == 3) { /* tex_octave_point's coordinates, made in the kernel */
            tex_noise_points_at(&o->t, o->period[k], o->off[k], f, m, u + i0, v + i0,
                                w ? w + i0 : NULL, r);
            for (int i = 0; i < m; i++)
                out[i0 + i] = r[i];
            continue;
        }
#pragma omp simd
        for (int i = 0; i < m; i++) {
            X[i] = o->off[k][0] + f * u[i0 + i];
            Y[i] = o->off[k][1] + f * v[i0 + i];
            Z[i] = o->off[k][2] + f * (w ? w[i0 + i] : 0);
            W[i] = o->off[k][3];
        }
        tex_noise_points(&o->t, o->period[k], o->dims, m, X, Y, Z, W, out + i0);
    }
}

/* tex_octave_points as float, the 3D octaves straight from the kernel's floats */
static void octave_points_f(const tex_octaves *o, int k, int n, const double *u, const double *v,
                            const double *w, float *out)
{
    double r[TEX_POINTS_BATCH];

    if (o->dims == 3) {
        tex_noise_points_at(&o->t, o->period[k], o->off[k], o->freq[k], n, u, v, w, out);
        return;
    }
    for (int i0 = 0; i0 < n; i0 += TEX_POINTS_BATCH) {
        int m = n - i0 < TEX_POINTS_BATCH ? n - i0 : TEX_POINTS_BATCH;
        tex_octave_points(o, k, m, u + i0, v + i0, w ? w + i0 : NULL, r);
        for (int i = 0; i < m; i++)
            out[i0 + i] = (float)r[i];
    }
}

void tex_octave_abs_sum(const tex_octaves *o, int octaves, const float *amp, float start, int n,
                        const double *u, const double *v, const double *w, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    float rf[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        for (int i = 0; i < m; i++)
            out[i0 + i] = start;
        for (int k = 0; k < octaves; k++) {
            octave_points_f(o, k, m, u + i0, v + i0, w ? w + i0 : NULL, rf);
            float ak = amp[k], *restrict o = out + i0; /* o aliases neither amp nor rf */
#pragma omp simd
            for (int i = 0; i < m; i++)
                o[i] += ak * fabsf(rf[i]);
        }
    }
}

/* 1 - smoothstep(0.2, 0.6, cells): an octave's weight where a pixel or footprint
 * spans that many of its lattice cells */
static double band_weight(double cells)
{
    double t = cells <= 0.2 ? 0 : cells >= 0.6 ? 1 : (cells - 0.2) / 0.4;
    return 1 - t * t * (3 - 2 * t);
}

/* wt[i] = band_weight(fw[i] fk) as float, i < n; whether one is > 0.  Four at a time with
 * AVX2, band_weight's operations in its order. */
static int band_weights(int n, const double *fw, double fk, float *wt)
{
    int any = 0, i = 0;
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2)
        any = tex_noise_band_weights_avx2(n, fw, fk, wt), i = n & ~3;
#endif
    for (; i < n; i++) {
        wt[i] = (float)band_weight(fw[i] * fk);
        any |= wt[i] > 0;
    }
    return any;
}

double tex_octave_band_weight(const tex_octaves *o, int k)
{
    return o->grid ? band_weight(o->g[k].fy) : 1; /* g.fy: lattice cells per pixel */
}

void tex_octave_points_fw(const tex_octaves *o, int k, int n, const double *u, const double *v,
                          const double *w, const double *fw, float *out, float *wt)
{
    if (band_weights(n, fw, o->freq[k], wt))
        octave_points_f(o, k, n, u, v, w, out);
    else
        memset(out, 0, n * sizeof *out);
}

void tex_octave_row(const tex_octaves *o, int k, int y, float *out)
{
    tex_noise_grid_row(&o->g[k], y, out);
}

void tex_octave_row_add(const tex_octaves *o, int k, int y, float amp, float *out)
{
    tex_noise_grid_row_add(&o->g[k], y, amp, out);
}

void tex_octave_row_op(const tex_octaves *o, int k, int y, int op, float a, float b, float c,
                       float *out)
{
    tex_noise_grid_row_op(&o->g[k], y, op, a, b, c, out);
}

void tex_octave_rows_op(const tex_octaves *o, int k, int y, int n, int op, float a, float b,
                        float c, float *out, size_t stride)
{
    tex_noise_grid_rows_op(&o->g[k], y, n, op, a, b, c, out, stride);
}

void tex_octave_rows_mf(const tex_octaves *o, int k, int y, int n, int op,
                        const struct tex_mf_k *mk, float *out, float *st, size_t stride)
{
    tex_noise_grid_rows_mf(&o->g[k], y, n, op, mk, out, st, stride);
}
