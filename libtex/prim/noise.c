/* noise.c - gradient noise: tables, points, grid rows, octaves, noise and d_noise
 * (the vector kernels: x86/noise_x86.c, x86/noise_points_x86.c) */

#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/error.h"
#include "base/rng.h"
#include "base/simd.h"
#include "prim/noise.h"
#include "prim/noise_grid.h"
#include "prim/prim.h"
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

/* p made by its init, which returned rc (p NULL: out of memory), or NULL */
static void *made(void *p, int rc)
{
    if (rc < 0) {
        free(p);
        return NULL;
    }
    return p;
}

void tex_noise_delete(tex_noise_table *t)
{
    tex_noise_free(t); /* NULL: nothing */
    free(t);
}

tex_noise_table *tex_noise_new(uint64_t seed, int n, int period)
{
    tex_noise_table *t = malloc(sizeof *t);
    return made(t, t ? tex_noise_init(t, seed, n, period) : tex_error("out of memory"));
}

void tex_noise_set_fade(tex_noise_table *t, int fade)
{
    t->fade = fade;
}


/* The fade's derivative */
static inline double dfade(int kind, double t)
{
    if (kind == TEX_FADE_QUINTIC)
        return -30.0 * t * t * (t - 1.0) * (t - 1.0);
    return 6.0 * t * (t - 1.0);
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

/* ---- grid sampling ---- */

static void grid_clear(tex_noise_grid *g)
{
    free(g->slot);
    free(g->lat);
    free(g->u);
    free(g->lut);
    free(g->plane);
    free(g->corner);
    if (g->cache) {
        for (int i = 0; i < g->cache->n; i++)
            free(g->cache->e[i].buf[0]);
        free(g->cache);
    }
    g->slot = g->lat = NULL;
    g->lut = NULL;
    g->plane = NULL;
    g->corner = g->corner2 = NULL;
    g->u = g->um1 = g->w0 = g->w1 = g->dw0 = g->dw1 = NULL;
    g->cache = NULL;
}

void tex_noise_grid_free(tex_noise_grid *g)
{
    if (g)
        grid_clear(g);
}

void tex_noise_grid_delete(tex_noise_grid *g)
{
    tex_noise_grid_free(g); /* NULL: nothing */
    free(g);
}

tex_noise_grid *tex_noise_grid_new(const tex_noise_table *t, int w, int h, double fx, double fy,
                                   const double off[4], int dims, int period)
{
    tex_noise_grid *g = malloc(sizeof *g);
    return made(g, g ? tex_noise_grid_init(g, t, w, h, fx, fy, off, dims, period)
                     : tex_error("out of memory"));
}

static int lut_init(tex_noise_grid *g, int fold);
static int corners_adjacent(const tex_noise_grid *g);

/* The slice's corners in z (and w): their weights, offsets and hash prefixes. */
static void slice_setup(tex_noise_grid *g, double z, double w4)
{
    const tex_noise_table *t = g->t;
    const int *F = t->perm;
    double zc = floor(z), wc = floor(w4), fr[2] = {z - zc, w4 - wc}, wt[2][2];
    int64_t base[2] = {tex_noise_cell(zc), tex_noise_cell(wc)};
    int li[2][2], axes = g->dims - 2;

    for (int a = 0; a < axes; a++) {
        li[a][0] = lat_index(base[a], 0, t->n);
        li[a][1] = lat_index(base[a] + 1, 0, t->n);
        wt[a][0] = fade(t->fade, fr[a]);
        wt[a][1] = fade(t->fade, 1.0 - fr[a]);
    }
    memset(g->zdm, 0, sizeof g->zdm);
    g->nz = 0;
    for (int c = 0; c < 1 << axes; c++) {
        int b[2] = {c & 1, c >> 1 & 1}, k = g->nz;
        double w = 1;
        for (int a = 0; a < axes; a++)
            w *= wt[a][b[a]];
        if (w == 0) /* a corner at distance 1: w(1) = 0 exactly */
            continue;
        g->zm[k][0] = g->zm[k][1] = (float)w;
        g->zm[k][2] = (float)(w * (fr[0] - b[0]));
        g->zm[k][3] = axes == 2 ? (float)(w * (fr[1] - b[1])) : 0;
        g->zh[k] = axes == 2 ? F[li[0][b[0]] + F[li[1][b[1]]]] : F[li[0][b[0]]];
        if (axes == 1) {
            /* d/dz of w(z) (G . d) = G.x w' dx + G.y w' dy + G.z (w' dz + w) */
            double dw = b[0] ? -dfade(t->fade, 1.0 - fr[0]) : dfade(t->fade, fr[0]);
            g->zdm[k][0] = g->zdm[k][1] = (float)dw;
            g->zdm[k][2] = (float)(dw * (fr[0] - b[0]) + w);
        }
        g->nz++;
    }
}

/* Pixel rows share lattice rows when a cell spans more than one row: keep
 * each thread's last two (without memory for them, rows compute their own). */
static void cache_init(tex_noise_grid *g)
{
#ifdef _OPENMP
    int n = omp_get_max_threads() + 1;
#else
    int n = 1;
#endif
    g->cache = calloc(1, sizeof *g->cache + n * sizeof g->cache->e[0]);
    if (!g->cache)
        return;
    g->cache->n = n;
    for (int i = 0; i < n; i++) {
        struct cache_entry *e = &g->cache->e[i];
        if (!(e->buf[0] = malloc(6 * (size_t)g->stride * sizeof *e->buf[0]))) {
            e->busy = 1; /* never taken */
            continue;
        }
        e->buf[1] = e->buf[0] + 3 * (size_t)g->stride;
    }
}

/* The most cells between the first and last of n columns from a multiple of n (the slots'
 * cells in list) */
static int grid_span(const tex_noise_grid *g, const int64_t *list, int n)
{
    int64_t most = 0;
    for (int x = 0; x + n - 1 < g->w; x += n) {
        int64_t d = list[g->slot[x + n - 1]] - list[g->slot[x]];
        most = d > most ? d : most;
    }
    return most > INT_MAX ? INT_MAX : (int)most;
}

/* Lattice rows from the table when the rows would fold more lattice points than it has
 * (cells spanning less than a pixel row are not kept); folded rows, with each column's
 * corner entry, where cells are narrower than the wide rows' (5 pixels) and the row has
 * more columns than the table entries, where folding each entry once is cheaper than each
 * column's slots.  Without memory, rows fold their own. */
static void table_init(tex_noise_grid *g)
{
    int n = g->t->n;
    double rows = g->fy < 1 ? g->fy * g->h + 2 : 2.0 * g->h;

    if (n > 1024 || rows * g->nslots <= 2.0 * n * n)
        return;
    g->adjacent = corners_adjacent(g);
    if (g->adjacent && (g->paired || (!g->wide && n >= 16)) && g->w >= 2 * (n + 1) &&
        (g->corner = malloc(2 * (size_t)g->w * sizeof *g->corner))) {
        g->corner2 = g->corner + g->w;
        for (int x = 0; x < g->w; x++) {
            g->corner[x] = g->lat[g->slot[x]];
            g->corner2[x] = 2 * g->corner[x];
        }
    }
    if (lut_init(g, g->corner != NULL) < 0) {
        free(g->corner);
        g->corner = g->corner2 = NULL;
    }
}

int tex_noise_grid_init(tex_noise_grid *g, const tex_noise_table *t, int w, int h, double fx,
                        double fy, const double off[4], int dims, int period)
{
    int64_t *list;
    int ns = 0;

    memset(g, 0, sizeof *g);
    if (w < 1 || h < 1 || (dims != 3 && dims != 4))
        return tex_error("noise grid: bad size %dx%d or dimension %d", w, h, dims);
    g->t = t;
    g->w = w;
    g->h = h;
    g->dims = dims;
    g->period = period;
    g->fy = fy / h;
    g->oy = off[1];
    slice_setup(g, off[2], dims == 4 ? off[3] : 0);
    g->slot = malloc(w * sizeof *g->slot);
    g->lat = malloc((2 * w + 16) * sizeof *g->lat);
    g->u = malloc(6 * (w + 8) * sizeof *g->u);
    list = malloc((2 * w + 2) * sizeof *list);
    if (!g->slot || !g->lat || !g->u || !list) {
        free(list);
        grid_clear(g);
        return tex_error("out of memory");
    }
    g->um1 = g->u + (w + 8);
    g->w0 = g->um1 + (w + 8);
    g->w1 = g->w0 + (w + 8);
    g->dw0 = g->w1 + (w + 8);
    g->dw1 = g->dw0 + (w + 8);
    /* Columns: the cell and fraction in double, so that large offsets keep
     * their texture; the slots list each lattice column the row touches once,
     * a pixel's right corner sitting in the slot after its left one.  When eight
     * pixels span seven cells or more, sharing saves little and costs the rows
     * gathers: every column then has its own pair. */
    g->paired = fx >= 0.875 * w;
    g->wide = fx * 5 <= w;
    for (int x = 0; x < w; x++) {
        double X = off[0] + fx * ((x + 0.5) / w), c = floor(X);
        int64_t i = tex_noise_cell(c);
        double u = X - c;
        if (ns == 0 || i > list[ns - 1] || g->paired) {
            list[ns++] = i;
            list[ns++] = i + 1;
        } else if (i == list[ns - 1]) {
            list[ns++] = i + 1;
        }
        g->slot[x] = ns - 2;
        g->u[x] = (float)u;
        g->um1[x] = (float)(u - 1.0);
        g->w0[x] = (float)fade(t->fade, u);
        g->w1[x] = (float)fade(t->fade, 1.0 - u);
        g->dw0[x] = (float)dfade(t->fade, u);
        g->dw1[x] = (float)-dfade(t->fade, 1.0 - u);
    }
    g->span8 = grid_span(g, list, 8);
    g->span16 = grid_span(g, list, 16);
    for (int s = 0; s < ns; s++)
        g->lat[s] = lat_index(list[s], period, t->n);
    for (int s = ns; s < ns + 16; s++)
        g->lat[s] = 0;
    g->nslots = ns;
    g->stride = ns + 16;
    free(list);
    table_init(g);
    g->folded = g->corner != NULL;
    if (g->folded)
        g->wide = 1; /* row_lut_avx512: sixteen columns too */
    if (g->fy < 1)
        cache_init(g);
    return 0;
}

/* Lattice row j folded over the slice's corners, for slots s0..s1-1: with
 * m_c = W_c (1, 1, dz_c, dw_c) and a = sum_c G_c * m_c (component-wise,
 * corners in order, float),
 *   X = a.x,  Y = a.y,  C = a.z + a.w,
 * so that a pixel row between lattice rows j and j+1 needs two such rows.
 * Element-wise float operations: the SSE form below gives the same bits. */
static inline __attribute__((always_inline)) void
lattice_row_n(const tex_noise_grid *g, const float (*zm)[4], const int *A, const int32_t *lat,
              int s0, int s, int s1, float *X, float *Y, float *C, const int nz)
{
    const int *F = g->t->perm;
    const float(*G)[4] = g->dims == 4 ? g->t->grad4 : g->t->grad;

    for (; s < s1; s++) {
        int i = lat[s];
        float a[4] = {0, 0, 0, 0};
        for (int c = 0; c < nz; c++)
            for (int k = 0; k < 4; k++)
                a[k] = a[k] + G[F[i + A[c]]][k] * zm[c][k];
        X[s - s0] = a[0];
        Y[s - s0] = a[1];
        C[s - s0] = a[2] + a[3];
    }
}

/* zm: the slice's weights, g->zm (noise) or g->zdm (its z derivative); lj the
 * lattice row reduced (lat_index), lat the slots' lattice columns. */
static void lattice_row_at(const tex_noise_grid *g, const float (*zm)[4], int lj,
                           const int32_t *lat, int s0, int s1, float *X, float *Y, float *C)
{
    const int *F = g->t->perm;
    int A[4], s = s0;

    for (int c = 0; c < g->nz; c++)
        A[c] = F[lj + g->zh[c]];
#ifdef TEX_X86
    s = tex_noise_lattice_sse(g, zm, lj, lat, s0, s1, X, Y, C); /* four slots at a time */
#endif
    /* One copy per number of corners, so that the sums stay in registers. */
    switch (g->nz) {
    case 1:
        lattice_row_n(g, zm, A, lat, s0, s, s1, X, Y, C, 1);
        break;
    case 2:
        lattice_row_n(g, zm, A, lat, s0, s, s1, X, Y, C, 2);
        break;
    case 3:
        lattice_row_n(g, zm, A, lat, s0, s, s1, X, Y, C, 3);
        break;
    default:
        lattice_row_n(g, zm, A, lat, s0, s, s1, X, Y, C, 4);
        break;
    }
}

static void lattice_row_m(const tex_noise_grid *g, const float (*zm)[4], int64_t j, int s0, int s1,
                          float *X, float *Y, float *C)
{
    lattice_row_at(g, zm, lat_index(j, g->period, g->t->n), g->lat, s0, s1, X, Y, C);
}

/* Every column's right corner the table's next entry (entry n being entry 0). */
static int corners_adjacent(const tex_noise_grid *g)
{
    for (int x = 0; x < g->w; x++) {
        const int32_t *l = g->lat + g->slot[x];
        if (l[1] != l[0] + 1 && !(l[0] == g->t->n - 1 && l[1] == 0))
            return 0;
    }
    return 1;
}

/* The table of every lattice point's folded (X, Y, C), computed as lattice_row
 * does: the same operations, so the same bits.  For a folded grid (fold) as
 * planes of ps entries, a multiple of sixteen from n + 32 on, entry i being
 * lattice column i mod n: the vector folds need no tail, and planar rows read
 * up to 32 entries from a column's. */
static int lut_init(tex_noise_grid *g, int fold)
{
    int n = g->t->n, ps = (n + 32 + 15) & ~15;
    int32_t *id = malloc((ps + 16) * sizeof *id);
    float *r = malloc(3 * (size_t)ps * sizeof *r);

    if (fold)
        g->plane = malloc((size_t)n * 3 * ps * sizeof *g->plane);
    else
        g->lut = malloc((size_t)n * (n + 1) * sizeof *g->lut);
    if (!id || !r || (!g->plane && !g->lut)) {
        free(id);
        free(r);
        free(g->plane);
        free(g->lut);
        g->plane = NULL;
        g->lut = NULL;
        return -1;
    }
    g->ps = ps;
    for (int i = 0; i < ps + 16; i++)
        id[i] = i % n;
    for (int lj = 0; lj < n; lj++) {
        float *X = fold ? g->plane + (size_t)lj * 3 * ps : r;
        lattice_row_at(g, (const float(*)[4])g->zm, lj, id, 0, fold ? ps : n + 1, X, X + ps,
                       X + 2 * ps);
        if (fold)
            continue;
        float(*T)[4] = g->lut + (size_t)lj * (n + 1);
        for (int i = 0; i <= n; i++) {
            T[i][0] = r[i];
            T[i][1] = r[ps + i];
            T[i][2] = r[2 * ps + i];
            T[i][3] = 0;
        }
    }
    free(id);
    free(r);
    return 0;
}


void tex_noise_lattice_row(const tex_noise_grid *g, int64_t j, int s0, int s1, float *X, float *Y,
                           float *C)
{
    const int32_t *lat = g->lat;
    const float(*T)[4];
    int s = s0;

    if (g->plane) {
        const float *TX = plane_row(g, j), *TY = TX + g->ps, *TC = TY + g->ps;
        for (; s < s1; s++) {
            X[s - s0] = TX[lat[s]];
            Y[s - s0] = TY[lat[s]];
            C[s - s0] = TC[lat[s]];
        }
        return;
    }
    if (!g->lut) {
        lattice_row_m(g, (const float(*)[4])g->zm, j, s0, s1, X, Y, C);
        return;
    }
    T = lut_row(g, j);
#ifdef TEX_X86
    s = tex_noise_lut_sse(T, lat, s0, s1, X, Y, C);
#endif
    for (; s < s1; s++) {
        X[s - s0] = T[lat[s]][0];
        Y[s - s0] = T[lat[s]][1];
        C[s - s0] = T[lat[s]][2];
    }
}

struct cache_entry *tex_noise_cache_take(const tex_noise_grid *g)
{
    struct tex_noise_cache *c = g->cache;
    int start = 0;

    if (!c)
        return NULL;
#ifdef _OPENMP
    start = omp_get_thread_num();
#endif
    for (int k = 0; k < c->n; k++) {
        struct cache_entry *e = &c->e[(start + k) % c->n];
        int free_ = 0;
        if (__atomic_compare_exchange_n(&e->busy, &free_, 1, 0, __ATOMIC_ACQUIRE,
                                        __ATOMIC_RELAXED))
            return e;
    }
    return NULL;
}

static int cache_find(const struct cache_entry *e, int64_t j)
{
    for (int b = 0; b < 2; b++)
        if (e->valid[b] && e->key[b] == j)
            return b;
    return -1;
}

/* Lattice row j into buffer b of the entry. */
static void cache_fill(const tex_noise_grid *g, struct cache_entry *e, int b, int64_t j)
{
    float *r = e->buf[b];

    tex_noise_lattice_row(g, j, 0, g->nslots, r, r + g->stride, r + 2 * g->stride);
    e->key[b] = j;
    e->valid[b] = 1;
}

/* The entry's buffers holding lattice rows j and (if two) j + 1, computed
 * where missing without evicting the other. */
void tex_noise_cache_rows(const tex_noise_grid *g, struct cache_entry *e, int64_t j, int two,
                          const float **r0, const float **r1)
{
    int b0 = cache_find(e, j), b1 = two ? cache_find(e, j + 1) : -1;

    if (b0 < 0)
        cache_fill(g, e, b0 = b1 == 0 ? 1 : 0, j);
    if (two && b1 < 0)
        cache_fill(g, e, b1 = 1 - b0, j + 1);
    *r0 = e->buf[b0];
    *r1 = two ? e->buf[b1] : NULL;
}

/* The two coefficients of each slot for the row (P[0] is slot s0's):
 * a pixel's noise is
 *   w0(u) (P[s] u + Q[s]) + w1(u) (P[s+1] (u-1) + Q[s+1]),  s = slot[x],
 * from the two lattice rows (X, Y, C; the second NULL when its weight is 0)
 * and the row's weights wy and offsets dy.  Shared by every SIMD level. */
static void row_coeffs(int ns, const float *wy, const float *dy, const float *const L0[3],
                       const float *const L1[3], float *P, float *Q)
{
    if (L1)
        for (int s = 0; s < ns; s++) {
            P[s] = wy[0] * L0[0][s] + wy[1] * L1[0][s];
            Q[s] = wy[0] * (L0[1][s] * dy[0] + L0[2][s]) + wy[1] * (L1[1][s] * dy[1] + L1[2][s]);
        }
    else
        for (int s = 0; s < ns; s++) {
            P[s] = wy[0] * L0[0][s];
            Q[s] = wy[0] * (L0[1][s] * dy[0] + L0[2][s]);
        }
    for (int s = ns; s < ns + 16; s++)
        P[s] = Q[s] = 0;
}

void tex_noise_yrow_at(const tex_noise_grid *g, int y, struct yrow *r)
{
    double Y = g->oy + g->fy * (y + 0.5), cy = floor(Y), fr = Y - cy;
    r->j = tex_noise_cell(cy);
    r->wy[0] = (float)fade(g->t->fade, fr);
    r->wy[1] = (float)fade(g->t->fade, 1.0 - fr);
    r->dy[0] = (float)fr;
    r->dy[1] = (float)(fr - 1.0);
    r->two = r->wy[1] != 0;
}

static void row_scalar(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1,
                       int rows, int op, struct row_k rk)
{
    ROWS_SWITCH(row_scalar_op, ROW_PRE);
}

/* Row y: the lattice rows (kept or computed), the coefficients, the pixels.
 * Columns go in chunks, so that the coefficients stay on the stack and in L1
 * (a chunk of CHUNK columns touches at most 2 CHUNK slots).  One copy per
 * level (x86/noise_x86.c has the vector ones), so that the vector parts inline. */
#define GRID_ROW grid_row_scalar
#define GRID_ATTR static
#define GRID_COEFFS row_coeffs
#define GRID_PIXELS row_scalar
#include "prim/noise_row_template.c"

/* Rows y.. y + rows - 1 (rows at most FOLD_ROWS) at the level the CPU and the grid take */
static void grid_rows(const tex_noise_grid *g, int y, int rows, int op, struct row_k rk,
                      float *const *out)
{
#ifdef TEX_X86
    int level = tex_simd_level();
    if (level >= TEX_SIMD_AVX512 && g->wide) {
        tex_noise_grid_rows_avx512(g, y, rows, op, rk, out);
        return;
    }
    if (level >= TEX_SIMD_AVX2) {
        tex_noise_grid_rows_avx2(g, y, rows, op, rk, out);
        return;
    }
#endif
    grid_row_scalar(g, y, rows, op, rk, out);
}

/* Rows y.. y + n - 1 with the operation op, in twos */
static void grid_rows_k(const tex_noise_grid *g, int y, int n, int op, struct row_k rk,
                        float *out, size_t stride)
{
    for (int i = 0; i < n; i += FOLD_ROWS) {
        float *o[FOLD_ROWS] = {out + i * stride, i + 1 < n ? out + (i + 1) * stride : NULL};
        grid_rows(g, y + i, n - i < FOLD_ROWS ? n - i : FOLD_ROWS, op, rk, o);
    }
}

void tex_noise_grid_row_op(const tex_noise_grid *g, int y, int op, float a, float b, float c,
                           float *out)
{
    tex_noise_grid_rows_op(g, y, 1, op, a, b, c, out, 0);
}

/* The operations without a state: the state is the sum, never read. */
void tex_noise_grid_rows_op(const tex_noise_grid *g, int y, int n, int op, float a, float b,
                            float c, float *out, size_t stride)
{
    struct row_k rk = {a, b, c, 0, 0, 0};
    grid_rows_k(g, y, n, op, rk, out, stride);
}

void tex_noise_grid_rows_mf(const tex_noise_grid *g, int y, int n, int op,
                            const struct tex_mf_k *k, float *out, float *st, size_t stride)
{
    struct row_k rk = {k->amp, k->offset, k->gain, k->lo, k->inv,
                       (uintptr_t)st - (uintptr_t)out};
    grid_rows_k(g, y, n, op, rk, out, stride);
}

void tex_noise_grid_row(const tex_noise_grid *g, int y, float *out)
{
    tex_noise_grid_row_op(g, y, TEX_ROW_SET, 0, 0, 0, out);
}

void tex_noise_grid_row_add(const tex_noise_grid *g, int y, float amp, float *out)
{
    tex_noise_grid_row_op(g, y, TEX_ROW_ADD, amp, 0, 0, out);
}

/* ---- the analytic gradient over a row ---- */

/* The y derivative's coefficients: as row_coeffs with the row weights'
 * derivatives dwy, plus the lattice rows' own y slope wy Y. */
static void row_coeffs_dy(int ns, const float *wy, const float *dwy, const float *dy,
                          const float *const L0[3], const float *const L1[3], float *P, float *Q)
{
    for (int s = 0; s < ns; s++) {
        P[s] = dwy[0] * L0[0][s];
        Q[s] = dwy[0] * (L0[1][s] * dy[0] + L0[2][s]) + wy[0] * L0[1][s];
        if (L1) {
            P[s] = P[s] + dwy[1] * L1[0][s];
            Q[s] = Q[s] + (dwy[1] * (L1[1][s] * dy[1] + L1[2][s]) + wy[1] * L1[1][s]);
        }
    }
    for (int s = ns; s < ns + 16; s++)
        P[s] = Q[s] = 0;
}

/* Pixels x..x1-1 of the gradient from the three coefficient pairs (value,
 * y derivative, z derivative; Z NULL without dz): the reference order. */
void tex_noise_grad_scalar(const tex_noise_grid *g, const float *const C[6], int sb, float *dx,
                           float *dy, float *dz, int x, int x1)
{
    for (; x < x1; x++) {
        int s = g->slot[x] - sb;
        float u = g->u[x], v = g->um1[x], w0 = g->w0[x], w1 = g->w1[x];
        float t0 = C[0][s] * u + C[1][s], t1 = C[0][s + 1] * v + C[1][s + 1];
        dx[x] = (g->dw0[x] * t0 + w0 * C[0][s]) + (g->dw1[x] * t1 + w1 * C[0][s + 1]);
        dy[x] = w0 * (C[2][s] * u + C[3][s]) + w1 * (C[2][s + 1] * v + C[3][s + 1]);
        if (dz)
            dz[x] = w0 * (C[4][s] * u + C[5][s]) + w1 * (C[4][s + 1] * v + C[5][s + 1]);
    }
}

void tex_noise_grid_row_grad(const tex_noise_grid *g, int y, float *dx, float *dy, float *dz)
{
    enum { CHUNK = 256, NS = 2 * CHUNK + 24 };
    float L[12][NS], K[6][NS];
    const float *const C[6] = {K[0], K[1], K[2], K[3], K[4], K[5]};
    double Y = g->oy + g->fy * (y + 0.5), cy = floor(Y), fr = Y - cy;
    int64_t j = tex_noise_cell(cy);
    int fd = g->t->fade;
    float wy[2] = {(float)fade(fd, fr), (float)fade(fd, 1.0 - fr)};
    float dwy[2] = {(float)dfade(fd, fr), (float)-dfade(fd, 1.0 - fr)};
    float ry[2] = {(float)fr, (float)(fr - 1.0)};
    int two = wy[1] != 0, level = tex_simd_level();

    for (int x0 = 0; x0 < g->w; x0 += CHUNK) {
        int x1 = x0 + CHUNK < g->w ? x0 + CHUNK : g->w;
        int s0 = g->slot[x0], s1 = g->slot[x1 - 1] + 2;
        const float *L0[3] = {L[0], L[1], L[2]}, *L1[3] = {L[3], L[4], L[5]};
        const float *D0[3] = {L[6], L[7], L[8]}, *D1[3] = {L[9], L[10], L[11]};
        tex_noise_lattice_row(g, j, s0, s1, L[0], L[1], L[2]);
        if (two)
            tex_noise_lattice_row(g, j + 1, s0, s1, L[3], L[4], L[5]);
        row_coeffs(s1 - s0, wy, ry, L0, two ? L1 : NULL, K[0], K[1]);
        row_coeffs_dy(s1 - s0, wy, dwy, ry, L0, two ? L1 : NULL, K[2], K[3]);
        if (dz) {
            lattice_row_m(g, (const float(*)[4])g->zdm, j, s0, s1, L[6], L[7], L[8]);
            if (two)
                lattice_row_m(g, (const float(*)[4])g->zdm, j + 1, s0, s1, L[9], L[10], L[11]);
            row_coeffs(s1 - s0, wy, ry, D0, two ? D1 : NULL, K[4], K[5]);
        }
#ifdef TEX_X86
        if (level >= TEX_SIMD_AVX2) {
            tex_noise_grad_avx2(g, C, s0, dx, dy, dz, x0, x1);
            continue;
        }
#endif
        tex_noise_grad_scalar(g, C, s0, dx, dy, dz, x0, x1);
    }
    (void)level;
}

/* ---- octaves ---- */

/* How a message names the parameter called name: as the option of its row in rows (a
 * primitive's, tex_param_find), or as name itself for the library's callers (rows NULL) */
static const char *row_option(const struct tex_param *rows, const char *name, char *buf,
                              size_t n)
{
    const struct tex_param *p = rows ? tex_param_find(rows, name) : NULL;
    return p ? tex_param_option(p, buf, n) : name;
}

/* A usage error unless the frequency is a whole number >= 1: a tiling lattice's period */
static int whole_frequency(const struct tex_param *rows, double freq)
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
    if (whole_frequency(rows, freq) < 0)
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
    return made(o, o ? tex_octaves_init(o, NULL, seed, gradients, fade, n, freq, lac, off, z, t,
                                        dims, tile, w, h)
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

/* ---- the primitive ---- */

struct noise_params {
    double frequency;
    double z;
    struct tex_reals w;
    struct tex_reals offset;
    int fade;
    int gradients;
    int frames, frame;
    double loop_radius;
};

static const struct tex_param noise_rows[] = {
    TEX_REAL(struct noise_params, frequency, 'f', 8, 0, 1e6, "F",
             "lattice cells across the map (a whole number with --tile)"),
    TEX_NOISE_ROWS(struct noise_params),
    TEX_NOISE_W_ROW(struct noise_params),
    TEX_NOISE_LOOP_ROWS(struct noise_params),
    {0}};

struct noise_state {
    tex_noise_table t;
    tex_noise_grid g;
    int period, dims;
    double off[4];
};

/* The state shared by noise and d_noise: the lattice tables from the seed, the
 * period under --tile, and the offset in lattice units (z slice included). */
static int state_init(struct tex_field *f, double frequency, const struct tex_reals *offset,
                      double z, int gradients, int fade)
{
    struct noise_state *s = calloc(1, sizeof *s);

    if (!s)
        return tex_error("out of memory");
    f->state = s;
    if (f->tile) {
        if (whole_frequency(f->prim->params, frequency) < 0)
            return -1;
        s->period = (int)frequency;
    }
    for (int a = 0; a < offset->n; a++)
        s->off[a] = offset->v[a];
    s->off[2] += frequency * z;
    if (tex_noise_init(&s->t, f->seed, gradients, s->period) < 0)
        return -1;
    s->t.fade = fade;
    return 0;
}

/* The loop's rows as every primitive with a loop has them: its messages' names */
struct loop_params {
    int frames, frame;
    double loop_radius;
};
static const struct tex_param loop_rows[] = {TEX_NOISE_LOOP_ROWS(struct loop_params), {0}};
#define LOOP_OPTION(field) TEX_OPTION(loop_rows, struct loop_params, field)

int tex_noise_loop(int frames, int frame, double radius, double *z, double *w, int *dims)
{
    if (frames == 0 && frame == 0)
        return 0;
    if (frame >= frames)
        return frames ? tex_usage_error("%s must be 0..%d for %s %d (got %d)", LOOP_OPTION(frame),
                                        frames - 1, LOOP_OPTION(frames), frames, frame)
                      : tex_usage_error("%s %d needs %s N", LOOP_OPTION(frame), frame,
                                        LOOP_OPTION(frames));
    double a = 2 * M_PI * ((double)frame / frames);
    *z += radius * cos(a);
    *w += radius * sin(a);
    *dims = 4;
    return 0;
}

static int noise_init(struct tex_field *f)
{
    const struct noise_params *p = f->params;
    struct noise_state *s;
    double z = p->z, w = p->w.n ? p->w.v[0] : 0;
    int dims = p->w.n ? 4 : 3;

    if (tex_noise_loop(p->frames, p->frame, p->loop_radius, &z, &w, &dims) < 0 ||
        state_init(f, p->frequency, &p->offset, z, p->gradients, p->fade) < 0)
        return -1;
    s = f->state;
    s->dims = dims;
    s->off[3] = dims == 4 ? p->frequency * w : 0;
    if (f->w > 0 && f->h > 0)
        return tex_noise_grid_init(&s->g, &s->t, f->w, f->h, p->frequency, p->frequency, s->off,
                                   s->dims, s->period);
    return 0;
}

static void noise_fini(struct tex_field *f)
{
    struct noise_state *s = f->state;
    if (!s)
        return;
    tex_noise_free(&s->t);
    tex_noise_grid_free(&s->g);
    free(s);
}

static inline float to_unit(float s)
{
    return clamp01(0.5f + 0.5f * s);
}

static void noise_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                        const double *w, float *out)
{
    enum { B = TEX_POINTS_BATCH };
    const struct noise_params *p = f->params;
    const struct noise_state *s = f->state;
    double fr = p->frequency, X[B], Y[B], Z[B], W[B], r[B];
    float rf[B];

    for (int i0 = 0; i0 < n; i0 += B) {
        int m = n - i0 < B ? n - i0 : B;
        if (s->dims == 3) { /* the coordinates below, made in the kernel */
            tex_noise_points_at(&s->t, s->period, s->off, fr, m, u + i0, v + i0,
                                w ? w + i0 : NULL, rf);
#pragma omp simd
            for (int i = 0; i < m; i++)
                out[i0 + i] = to_unit(rf[i]);
            continue;
        }
#pragma omp simd
        for (int i = 0; i < m; i++) { /* lattice coordinates: offset + frequency x point */
            X[i] = s->off[0] + fr * u[i0 + i];
            Y[i] = s->off[1] + fr * v[i0 + i];
            Z[i] = s->off[2] + fr * (w ? w[i0 + i] : 0);
            W[i] = s->off[3];
        }
        tex_noise_points(&s->t, s->period, s->dims, m, X, Y, Z, W, r);
        for (int i = 0; i < m; i++)
            out[i0 + i] = to_unit((float)r[i]);
    }
}

static void noise_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                        float *out)
{
    noise_eval3(f, n, u, v, NULL, out);
}

static void noise_row(const struct tex_field *f, int y, float *out)
{
    const struct noise_state *s = f->state;

    tex_noise_grid_row_op(&s->g, y, TEX_ROW_UNIT, 0, 0, 0, out);
}

const struct tex_primitive tex_prim_noise = {
    .name = "noise",
    .summary = "gradient noise of the thesis (Perlin), rescaled to [0,1]",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct noise_params),
    .params = noise_rows,
    .init = noise_init,
    .fini = noise_fini,
    .eval2 = noise_eval2,
    .eval3 = noise_eval3,
    .row = noise_row,
};

/* ---- d_noise: the analytic gradient (thesis 5.2.2.3) ---- */

struct dnoise_params {
    double frequency, z, strength;
    struct tex_reals offset;
    int channels, normal, fade, gradients;
};

static const struct tex_param dnoise_rows[] = {
    TEX_REAL(struct dnoise_params, frequency, 'f', 8, 0, 1e6, "F",
             "lattice cells across the map (a whole number with --tile)"),
    TEX_NOISE_ROWS(struct dnoise_params),
    TEX_INT(struct dnoise_params, channels, 0, 2, 2, 3, "N",
            "2: d/dx, d/dy; 3: also d/dz (raw gradient, lattice units)", .old = "-c"),
    TEX_FLAG(struct dnoise_params, normal, 0,
             "write a tangent-space normal map (x right, y up, z out) encoded as 0.5 + 0.5 n"),
    TEX_REAL(struct dnoise_params, strength, 0, 1, 0, 1e6, "S",
             "--normal: height scale, n = normalize(-S dn/dx, S dn/dy_up, 1)"),
    {0}};

#define DNOISE_OPTION(field) TEX_OPTION(dnoise_rows, struct dnoise_params, field)

static int dnoise_init(struct tex_field *f)
{
    const struct dnoise_params *p = f->params;
    struct noise_state *s;

    /* Values other than the defaults are the test: the rows are shared with scenes. */
    if (!p->normal && p->strength != 1)
        return tex_usage_error("%s applies with %s only", DNOISE_OPTION(strength),
                               DNOISE_OPTION(normal));
    if (p->normal && p->channels != 2)
        return tex_usage_error("%s applies without %s only (a normal map has 3)",
                               DNOISE_OPTION(channels), DNOISE_OPTION(normal));
    f->nc = p->normal ? 3 : p->channels;
    if (state_init(f, p->frequency, &p->offset, p->z, p->gradients, p->fade) < 0)
        return -1;
    s = f->state;
    s->dims = 3;
    if (f->w > 0 && f->h > 0)
        return tex_noise_grid_init(&s->g, &s->t, f->w, f->h, p->frequency, p->frequency, s->off,
                                   3, s->period);
    return 0;
}

static void dnoise_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                         const double *w, float *out)
{
    const struct dnoise_params *p = f->params;
    const struct noise_state *s = f->state;
    double fr = p->frequency;

    for (int i = 0; i < n; i++, out += f->nc) {
        double g[3];
        tex_noise3_grad(&s->t, s->period, s->off[0] + fr * u[i], s->off[1] + fr * v[i],
                        s->off[2] + fr * (w ? w[i] : 0), g);
        if (p->normal) {
            /* v grows downwards: the height's slope along y-up is -dn/dv. */
            double nx = -p->strength * g[0], ny = p->strength * g[1];
            double len = sqrt(nx * nx + ny * ny + 1);
            out[0] = (float)(0.5 + 0.5 * nx / len);
            out[1] = (float)(0.5 + 0.5 * ny / len);
            out[2] = (float)(0.5 + 0.5 / len);
        } else {
            for (int c = 0; c < f->nc; c++)
                out[c] = (float)g[c];
        }
    }
}

static void dnoise_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                         float *out)
{
    dnoise_eval3(f, n, u, v, NULL, out);
}

/* Grid rows: the gradient from the vectorised rows (float, within about 1e-5
 * of the points' double), then interleaved or made a normal. */
static void dnoise_row(const struct tex_field *f, int y, float *out)
{
    const struct dnoise_params *p = f->params;
    const struct noise_state *s = f->state;
    float *d = malloc(3 * (size_t)f->w * sizeof *d), S = (float)p->strength;

    if (!d) { /* no memory for the row buffers: the point path needs none */
        for (int x = 0; x < f->w; x++) {
            double u = (x + 0.5) / f->w, v = (y + 0.5) / f->h;
            dnoise_eval2(f, 1, &u, &v, out + (size_t)x * f->nc);
        }
        return;
    }
    tex_noise_grid_row_grad(&s->g, y, d, d + f->w, f->nc == 3 && !p->normal ? d + 2 * f->w : NULL);
    for (int x = 0; x < f->w; x++, out += f->nc) {
        float gx = d[x], gy = d[f->w + x];
        if (p->normal) {
            /* v grows downwards: the height's slope along y-up is -dn/dv. */
            float nx = -S * gx, ny = S * gy, len = sqrtf(nx * nx + ny * ny + 1);
            out[0] = 0.5f + 0.5f * (nx / len);
            out[1] = 0.5f + 0.5f * (ny / len);
            out[2] = 0.5f + 0.5f / len;
        } else {
            out[0] = gx;
            out[1] = gy;
            if (f->nc == 3)
                out[2] = d[2 * f->w + x];
        }
    }
    free(d);
}

const struct tex_primitive tex_prim_d_noise = {
    .name = "d_noise",
    .summary = "the analytic gradient of gradient noise, or a normal map from it",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct dnoise_params),
    .params = dnoise_rows,
    .init = dnoise_init,
    .fini = noise_fini,
    .eval2 = dnoise_eval2,
    .eval3 = dnoise_eval3,
    .row = dnoise_row,
};
