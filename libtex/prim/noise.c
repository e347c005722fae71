/* noise.c - gradient noise: the tables, noise at points (the point kernels:
 * x86/noise_points_x86.c); grids are noise_grid.c's, octaves octaves.c's */

#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/rng.h"
#include "base/simd.h"
#include "prim/noise.h"
#include "prim/noise_grid.h"
#include "prim/x86/noise_x86.h"

int tex_noise_init(tex_noise_table *t, uint64_t seed, int n, int period)
{
    tex_rng r;

    memset(t, 0, sizeof *t);
    if (n < 2 || n > TEX_NOISE_MAX_GRADIENTS)
        return tex_usage_error("the number of gradients must be 2..%d (got %d)",
                               TEX_NOISE_MAX_GRADIENTS, n);
    if (period < 0)
        return tex_usage_error("the noise period must be >= 0 (got %d)", period);
    t->n = n;
    t->period = period;
    t->perm = malloc(2 * n * sizeof *t->perm);
    t->grad = malloc(n * sizeof *t->grad);
    t->grad4 = malloc(n * sizeof *t->grad4);
    t->pgrad = malloc(2 * n * sizeof *t->pgrad);
    if (!t->perm || !t->grad || !t->grad4 || !t->pgrad) {
        tex_noise_free(t);
        return tex_error("out of memory");
    }
    tex_rng_seed(&r, seed);
    for (int i = 0; i < n; i++) {
        /* Uniform on the sphere: z uniform in [-1,1], longitude uniform. */
        double z = 2.0 * tex_rng_uniform(&r) - 1.0, phi = 2.0 * M_PI * tex_rng_uniform(&r);
        double s = sqrt(1.0 - z * z);
        t->grad[i][0] = (float)(s * cos(phi));
        t->grad[i][1] = (float)(s * sin(phi));
        t->grad[i][2] = (float)z;
        t->grad[i][3] = 0;
        t->perm[i] = i;
    }
    for (int i = 0; i < n; i++) {
        /* Uniform on the 4D sphere: a normalised Gaussian vector. */
        double g[4], len;
        do {
            len = 0;
            for (int k = 0; k < 4; k++) {
                g[k] = tex_rng_gauss(&r);
                len += g[k] * g[k];
            }
        } while (len < 1e-12);
        len = sqrt(len);
        for (int k = 0; k < 4; k++)
            t->grad4[i][k] = (float)(g[k] / len);
    }
    tex_rng_shuffle(&r, t->perm, n);
    memcpy(t->perm + n, t->perm, n * sizeof *t->perm);
    for (int m = 0; m < 2 * n; m++)
        for (int k = 0; k < 4; k++)
            t->pgrad[m][k] = t->grad[t->perm[m]][k];
    for (int i = 0; n == 256 && i < n; i++)
        t->perm8[i] = (unsigned char)t->perm[i];
    return 0;
}

void tex_noise_free(tex_noise_table *t)
{
    if (!t)
        return;
    free(t->perm);
    free(t->grad);
    free(t->grad4);
    free(t->pgrad);
    t->pgrad = NULL;
    t->perm = NULL;
    t->grad = NULL;
    t->grad4 = NULL;
}

void tex_noise_delete(tex_noise_table *t)
{
    tex_noise_free(t); /* NULL: nothing */
    free(t);
}

tex_noise_table *tex_noise_new(uint64_t seed, int n, int period)
{
    tex_noise_table *t = malloc(sizeof *t);
    return tex_noise_made(t, t ? tex_noise_init(t, seed, n, period)
                               : tex_error("out of memory"));
}

void tex_noise_set_fade(tex_noise_table *t, int fade)
{
    t->fade = fade;
}


/* Noise at p (dims 3 or 4) and, if g, its gradient. */
static double noise_point(const tex_noise_table *t, int period, int dims, const double p[4],
                          double g[4])
{
    const int *F = t->perm;
    int n = t->n, idx[4][2];
    double f[4], wt[4][2], dw[4][2], sum = 0;

    for (int a = 0; a < dims; a++) {
        double c = floor(p[a]);
        int64_t i = tex_noise_cell(c);
        int per = a < 2 ? period : 0;
        f[a] = p[a] - c;
        idx[a][0] = lat_index(i, per, n);
        idx[a][1] = lat_index(i + 1, per, n);
        wt[a][0] = fade(t->fade, f[a]);
        wt[a][1] = fade(t->fade, 1.0 - f[a]);
        dw[a][0] = dfade(t->fade, f[a]);
        dw[a][1] = -dfade(t->fade, 1.0 - f[a]);
    }
    if (g)
        g[0] = g[1] = g[2] = g[3] = 0;
    for (int c = 0; c < 1 << dims; c++) {
        int b[4] = {c & 1, c >> 1 & 1, c >> 2 & 1, c >> 3 & 1}, h;
        const float *gr;
        double d[4], dot = 0, w = 1;
        if (dims == 4) {
            h = F[idx[0][b[0]] +
                  F[idx[1][b[1]] + F[idx[2][b[2]] + F[idx[3][b[3]]]]]];
            gr = t->grad4[h];
        } else {
            h = F[idx[0][b[0]] + F[idx[1][b[1]] + F[idx[2][b[2]]]]];
            gr = t->grad[h];
        }
        for (int a = 0; a < dims; a++) {
            d[a] = f[a] - b[a];
            dot += gr[a] * d[a];
            w *= wt[a][b[a]];
        }
        sum += w * dot;
        if (g)
            for (int a = 0; a < dims; a++) {
                double dwa = dw[a][b[a]];
                for (int o = 0; o < dims; o++)
                    if (o != a)
                        dwa *= wt[o][b[o]];
                g[a] += dwa * dot + w * gr[a];
            }
    }
    return sum;
}

/* 3D noise's value: cells and fractions in double precision (far points keep their
 * texture), the corners' sum in float; the point kernels (x86/noise_points_x86.c)
 * perform these float operations in this order, eight or sixteen points at a time. */
static float noise3_point(const tex_noise_table *t, int period, const double p[3])
{
    const int *F = t->perm;
    int n = t->n, idx[3][2];
    float f[3], wt[3][2], sum = 0;

    for (int a = 0; a < 3; a++) {
        double c = floor(p[a]);
        int64_t i = tex_noise_cell(c);
        int per = a < 2 ? period : 0;
        f[a] = (float)(p[a] - c);
        idx[a][0] = lat_index(i, per, n);
        idx[a][1] = lat_index(i + 1, per, n);
        wt[a][0] = fadef(t->fade, f[a]);
        wt[a][1] = fadef(t->fade, 1.0f - f[a]);
    }
    for (int c = 0; c < 8; c++) {
        int b0 = c & 1, b1 = c >> 1 & 1, b2 = c >> 2 & 1;
        const float *gr = t->pgrad[idx[0][b0] + F[idx[1][b1] + F[idx[2][b2]]]];
        float d0 = b0 ? f[0] - 1.0f : f[0], d1 = b1 ? f[1] - 1.0f : f[1],
              d2 = b2 ? f[2] - 1.0f : f[2];
        float dot = gr[0] * d0 + gr[1] * d1 + gr[2] * d2;
        float w = wt[0][b0] * wt[1][b1] * wt[2][b2];
        sum += w * dot;
    }
    return sum;
}

double tex_noise3p(const tex_noise_table *t, int period, double x, double y, double z)
{
    double p[3] = {x, y, z};
    return noise3_point(t, period, p);
}

double tex_noise4p(const tex_noise_table *t, int period, double x, double y, double z, double w)
{
    double p[4] = {x, y, z, w};
    return noise_point(t, period, 4, p, NULL);
}

double tex_noise3(const tex_noise_table *t, double x, double y, double z)
{
    return tex_noise3p(t, t->period, x, y, z);
}

double tex_noise4(const tex_noise_table *t, double x, double y, double z, double w)
{
    return tex_noise4p(t, t->period, x, y, z, w);
}

double tex_noise3_grad(const tex_noise_table *t, int period, double x, double y, double z,
                       double g[3])
{
    double p[4] = {x, y, z, 0}, g4[4];
    double s = noise_point(t, period, 3, p, g4);
    g[0] = g4[0];
    g[1] = g4[1];
    g[2] = g4[2];
    return s;
}

/* ---- many points at once ---- */

/* tex_noise3p at a + f (u, v, w), the coordinates computed as the callers did */
static float noise3_at(const tex_noise_table *t, int period, const double a[3], double f,
                       double u, double v, double w)
{
    double p[3] = {a[0] + f * u, a[1] + f * v, a[2] + f * w};
    return noise3_point(t, period, p);
}

float tex_noise3_point_at(const tex_noise_table *t, int period, const double *a, double f,
                          const double *const c[3], int i)
{
    const double w = c[2] ? c[2][i] : 0;
    return a ? noise3_at(t, period, a, f, c[0][i], c[1][i], w)
             : tex_noise3p(t, period, c[0][i], c[1][i], w);
}

#ifdef TEX_X86
typedef int (*points_kernel)(const tex_noise_table *, int, const double *, double,
                             const double *const[3], int, float *);
/* The point kernel for t: sixteen lanes and the byte table for 256 gradients and no period
 * where the CPU has VBMI (the same bytes), else eight lanes and the gathers. */
static points_kernel points_kernel_for(const tex_noise_table *t, int period)
{
    return !period && t->n == 256 && tex_simd_vbmi() ? tex_noise3_points_vbmi
                                                     : tex_noise3_points_avx2;
}
#endif

void tex_noise_points(const tex_noise_table *t, int period, int dims, int n, const double *x,
                      const double *y, const double *z, const double *w, double *out)
{
    int i = 0;

#ifdef TEX_X86
    if (dims == 3 && tex_simd_level() >= TEX_SIMD_AVX2) {
        const double *c[3] = {x, y, z};
        float r[TEX_POINTS_BATCH];
        points_kernel kernel = points_kernel_for(t, period);
        for (; i + 8 <= n; i += TEX_POINTS_BATCH) {
            int m = n - i < TEX_POINTS_BATCH ? n - i : TEX_POINTS_BATCH;
            const double *ci[3] = {c[0] + i, c[1] + i, c[2] + i};
            int done = kernel(t, period, NULL, 1, ci, m, r);
            for (int k = 0; k < done; k++)
                out[i + k] = r[k];
            if (done < m) {
                i += done;
                break;
            }
        }
    }
#endif
    for (; i < n; i++)
        out[i] = dims == 4 ? tex_noise4p(t, period, x[i], y[i], z[i], w[i])
                           : tex_noise3p(t, period, x[i], y[i], z[i]);
}

void tex_noise_points_at(const tex_noise_table *t, int period, const double a[3], double f, int n,
                         const double *u, const double *v, const double *w, float *out)
{
    int i = 0;

#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2) {
        const double *c[3] = {u, v, w};
        i = points_kernel_for(t, period)(t, period, a, f, c, n, out);
    }
#endif
    for (; i < n; i++)
        out[i] = noise3_at(t, period, a, f, u[i], v[i], w ? w[i] : 0);
}

double tex_noise_mean_abs(const tex_noise_table *t)
{
    enum { N = 16 };
    double x[N * N], y[N * N], z[N * N], r[N * N], sum = 0;

    /* a fixed jittered lattice over 16^3 cells: the same mean for the same table */
    for (int k = 0; k < N; k++) {
        for (int i = 0; i < N * N; i++) {
            x[i] = (i % N) + 0.5 + 0.37 * sin(i * 1.7 + k);
            y[i] = (double)(i / N) + 0.5 + 0.37 * sin(i * 2.3 + 2 * k);
            z[i] = k + 0.5 + 0.37 * sin(i * 0.9 + 3 * k);
        }
        tex_noise_points(t, 0, 3, N * N, x, y, z, NULL, r);
        for (int i = 0; i < N * N; i++)
            sum += fabs(r[i]);
    }
    return sum / (N * N * N);
}
