/* noise_grid.c - gradient noise sampled on a map's pixels, a row at a time (noise.h's grids;
 * the vector kernels: x86/noise_x86.c; the workings: noise_grid.h) */
#include "base/fp_strict.h" /* first: no fused multiply-adds in this file */

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "base/error.h"
#include "base/simd.h"
#include "prim/noise.h"
#include "prim/noise_grid.h"
#include "prim/x86/noise_x86.h"

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
    return tex_noise_made(g, g ? tex_noise_grid_init(g, t, w, h, fx, fy, off, dims, period)
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
