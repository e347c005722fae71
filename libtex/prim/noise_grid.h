/* noise_grid.h - the insides of noise.h's tables, grids and octaves, shared with the x86
 * kernels
 *
 * Internal to libtex (not installed).  noise.c makes the tables and noise at
 * points, noise_grid.c the grids and their rows, octaves.c the octaves, and
 * noise_primitives.c the noise and d_noise primitives from them; these hold
 * every scalar definition.  The vector kernels of x86/noise_x86.c (grid
 * rows) and x86/noise_points_x86.c (points) read the same structures and
 * perform the same float operations in the same order, so the bytes never
 * depend on the level.  What both sides need is here: the lattice index and
 * the fade, the rows' operations (apply_op) and their scalar order
 * (row_scalar_op), the pixel row's place between lattice rows (struct yrow),
 * the kept lattice rows (the cache), and the table rows of a folded grid.
 *
 * A grid row is made in three steps (noise_row_template.c, once per level):
 * the two lattice rows around it (kept per thread, or from the grid's table),
 * their coefficients P and Q per slot with the row's y weights, then the
 * pixels w0 (P u + Q) + w1 (P' (u - 1) + Q') with the row's operation.
 *
 * The types of noise.h are opaque to library users: libtex's own files make
 * them in their memory (tex_noise_init, tex_noise_grid_init, tex_octaves_init)
 * and read their fields.
 *
 * A grid's cell indices and fractions are computed once per column in
 * double precision.  A lattice row (the gradients of one lattice y over
 * the row's lattice columns) is folded once over the slice's corners in z
 * (and w) into three floats per column; pixel rows inside the same cell
 * share it (each grid keeps the last two per thread), and a pixel row
 * combines two of them with its y weights into two coefficients per
 * lattice column.  The per-pixel work is then four float multiplies and
 * three adds, with the row's operation (rescale, weighted sum, |n|, the last
 * octave's finish: tex_noise_grid_row_op) in the same pass.  When cells are
 * smaller than pixels, so that every pixel row needs lattice rows of its own,
 * the folded lattice rows are read from a table of all n x n lattice points
 * made once per grid (the lattice repeats every n cells), and every column
 * gets its own pair of slots, so that the vector rows read them without
 * gathers: a map's cost then no longer grows with its frequency.  A row with
 * more columns than the table has entries, where cells are under 5 pixels
 * wide, first combines its two table rows with its y weights into one
 * coefficient pair per entry (the operations each column would do; the table
 * kept as planes of X, Y and C for it), and each column reads its corners'
 * pairs: where eight or sixteen columns' corners lie within a register's
 * entries (cells of about a pixel or more; half a pixel with AVX-512), by
 * permutes of the coefficients, else one load per column (with AVX-512, one
 * for two rows, their coefficients interleaved entry by entry).  Rows are made
 * two at a time where their coefficients fit on the stack together
 * (tex_noise_grid_rows_op), so that an octave sum, whose octaves' per-column
 * data outgrow the first-level cache, reads them once for both.  Rows are
 * vectorised (AVX2, chosen at run time, and AVX-512 for cells 5 pixels wide
 * or more and for rows from folded table coefficients, unless most of an
 * octave sum's cells are neither: a map that
 * switches between the two ran slower; TEXTURA_SIMD=scalar or avx2 caps
 * the level) and every level performs the
 * same float operations in the same order, so the bytes are identical
 * whatever the level, the thread count or the order rows come in.  They
 * agree with tex_noise3/4 to about 1e-6.
 */
#ifndef TEX_NOISE_GRID_H
#define TEX_NOISE_GRID_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "noise.h"

/* ---- the insides of noise.h's types ---- */

struct tex_noise_table {
    int n;       /* gradients */
    int period;  /* 0: none; used by tex_noise3/tex_noise4 */
    int fade;    /* TEX_FADE_CUBIC (eq. 5.2, the default) or TEX_FADE_QUINTIC */
    int *perm;   /* F, stored twice (2n entries) so that F[a + b] needs no mod */
    float (*grad)[4];  /* n unit vectors on the sphere (w = 0) */
    float (*grad4)[4]; /* n unit vectors on the 4D sphere */
    float (*pgrad)[4]; /* grad[perm[m]] for m < 2n: the last hash step and its gradient in one */
    unsigned char perm8[256]; /* perm as bytes where n = 256: the point kernel's lookups in
                               * registers (AVX-512 VBMI) */
};

/* A table in the caller's memory: tex_noise_new's insides, freed by tex_noise_free. */
int tex_noise_init(tex_noise_table *t, uint64_t seed, int n, int period);
void tex_noise_free(tex_noise_table *t);

struct tex_noise_cache; /* lattice rows kept for the next pixel rows (noise.c) */

struct tex_noise_grid {
    const tex_noise_table *t;
    int w, h, dims, period;
    double fy, oy;
    int nslots, stride;
    int32_t *slot;     /* per column: slot of its cell's left lattice column */
    int32_t *lat;      /* per slot: lattice column index reduced mod period and n */
    float *u, *um1, *w0, *w1; /* per column: fraction, fraction - 1, the two x weights */
    float *dw0, *dw1;  /* per column: the x weights' derivatives in u */
    int nz, zh[4];     /* the slice's corners in z (and w) of non-zero weight, hash prefixes */
    float zm[4][4];    /* their weight W (1, 1, dz, dw) */
    float zdm[4][4];   /* dims 3: the z derivative's (W', W', W' dz + W, 0) */
    float (*lut)[4];   /* NULL, or per lattice row mod n the folded (X, Y, C, 0) of every
                        * lattice column mod n and column 0 again (n + 1 entries), when
                        * the grid needs more lattice rows than the table has */
    float *plane;      /* a folded grid's table instead: per lattice row mod n its X, Y and
                        * C, each over ps entries (entry i is lattice column i mod n) */
    int ps;
    int paired;        /* every column has its own two slots, 2x and 2x + 1 */
    int adjacent;      /* every column's right corner is the table's next entry */
    int folded;        /* adjacent, with more columns than the table has entries and cells
                        * under 5 pixels wide: rows from the table row folded with their y
                        * weights once (fold_row_*), each column reading its corners' pairs */
    int32_t *corner;   /* folded: per column, the table entry of its left corner */
    int32_t *corner2;  /* ... twice over (in the same block): an 8-byte index into a
                        * table of four floats an entry, which loads scale as they are */
    int span8, span16; /* the most cells between the first and last columns of 8 (16)
                        * columns from a multiple of 8 (16) */
    int wide;          /* AVX-512 rows where the CPU has it: cells 5 pixels wide or more, or
                        * rows made from folded table coefficients */
    struct tex_noise_cache *cache;
};

/* A grid in the caller's memory (tex_noise_grid_new's), freed by tex_noise_grid_free. */
int tex_noise_grid_init(tex_noise_grid *g, const tex_noise_table *t, int w, int h, double fx,
                        double fy, const double off[4], int dims, int period);
void tex_noise_grid_free(tex_noise_grid *g);

struct tex_octaves {
    tex_noise_table t;
    int n, dims, grid;
    double freq[TEX_OCTAVES_MAX], off[TEX_OCTAVES_MAX][4];
    int period[TEX_OCTAVES_MAX];
    tex_noise_grid g[TEX_OCTAVES_MAX]; /* when sampled on a grid (w, h > 0) */
};

/* Octaves in the caller's memory (tex_octaves_new's), freed by tex_octaves_free.  Messages
 * name the parameters as the rows of a primitive call them (octaves, frequency, lacunarity;
 * NULL rows: by tex_octaves_new's argument names). */
int tex_octaves_init(tex_octaves *o, const struct tex_param *rows, uint64_t seed, int gradients,
                     int fade, int n, double freq, double lac, const double off[3], double z,
                     double t, int dims, int tile, int w, int h);
void tex_octaves_free(tex_octaves *o);

/* The public _new functions: p made by its init, which returned rc (p NULL: out of memory),
 * or NULL */
static inline void *tex_noise_made(void *p, int rc)
{
    if (rc < 0) {
        free(p);
        return NULL;
    }
    return p;
}

/* A usage error unless the frequency is a whole number >= 1, a tiling lattice's period; the
 * message names the frequency and tile as rows (a primitive's) call them (octaves.c) */
int tex_noise_whole_frequency(const struct tex_param *rows, double freq);

/* ---- rows of a grid ---- */

static inline int imod64(int64_t a, int64_t n)
{
    int64_t m = a % n;
    return (int)(m < 0 ? m + n : m);
}

/* A lattice index made ready for F: wrapped by the period, then mod n. */
static inline int lat_index(int64_t i, int period, int n)
{
    if (period)
        i = imod64(i, period);
    return imod64(i, n);
}

/* The fade of eq. 5.2 for t in [0,1] (w(0) = 1, w(1) = 0), written once for double, float
 * and the vector types, whose operators are their lanes' (C: a constant of type T): the same
 * operations in the same order at every width. */
#define FADE_FN(ATTR, NAME, T, C)                                                            \
    ATTR static inline __attribute__((always_inline)) T NAME(int kind, T t)                  \
    {                                                                                        \
        if (kind == TEX_FADE_QUINTIC)                                                        \
            return C(1) - t * t * t * (t * (t * C(6) - C(15)) + C(10));                      \
        return (C(2) * t - C(3)) * t * t + C(1);                                             \
    }
#define FADE_D(x) ((double)(x))
#define FADE_F(x) ((float)(x))
FADE_FN(, fade, double, FADE_D)
FADE_FN(, fadef, float, FADE_F)

/* The fade's derivative */
static inline double dfade(int kind, double t)
{
    if (kind == TEX_FADE_QUINTIC)
        return -30.0 * t * t * (t - 1.0) * (t - 1.0);
    return 6.0 * t * (t - 1.0);
}

/* Lattice rows kept for the pixel rows that follow: one entry per thread
 * that holds it (taken with an atomic flag, so any thread split works, and
 * a thread finding none busy-free computes the rows on its stack). */
struct cache_entry {
    int busy, valid[2];
    int64_t key[2];
    float *buf[2]; /* a folded lattice row: X, Y, C, each g->stride floats */
};

struct tex_noise_cache {
    int n;
    struct cache_entry e[];
};

/* [0,1] clamps written as max then min, the order of the vector instructions
 * (the same result for -0 and NaN). */
static inline float clamp01(float x)
{
    float m = x > 0 ? x : 0;
    return m < 1 ? m : 1;
}

/* Pixel row y's place between lattice rows j and j + 1: their weights wy and offsets dy
 * (two: j + 1's weight is not 0) */
struct yrow {
    int64_t j;
    float wy[2], dy[2];
    int two;
};

/* Pixel row y of g between its lattice rows */
void tex_noise_yrow_at(const tex_noise_grid *g, int y, struct yrow *r);
/* This thread's cache entry (released by storing 0 in busy), or NULL: none free */
struct cache_entry *tex_noise_cache_take(const tex_noise_grid *g);
/* The entry's buffers holding lattice rows j and (if two) j + 1, computed where missing */
void tex_noise_cache_rows(const tex_noise_grid *g, struct cache_entry *e, int64_t j, int two,
                          const float **r0, const float **r1);
/* Lattice row j's folded X, Y, C for slots s0..s1-1 (from the table where the grid has one) */
void tex_noise_lattice_row(const tex_noise_grid *g, int64_t j, int s0, int s1, float *X, float *Y,
                           float *C);

/* The pixel rows a kernel makes at once (1 or FOLD_ROWS: each column's data, read from
 * beyond the first-level cache in an octave sum, serves them all), row r's coefficients
 * from C[r] into out[r]: a folded grid's planar (Q ps floats after P) or interleaved, a
 * slot row's P and Q ROW_NS floats after it (ROW_CHUNK columns touch at most ROW_NS - 24
 * slots).  The kernels' loops over rows are unrolled ("GCC unroll 2"): GCC kept them
 * rolled around a kernel's branches, each row's noise through the stack. */
#define FOLD_ROWS 2
#define ROW_CHUNK 1024
#define ROW_NS (2 * ROW_CHUNK + 24)
struct rowset {
    const float *C[FOLD_ROWS];
    float *out[FOLD_ROWS];
};

/* A row operation's constants (tex_noise_grid_row_op's a, b and c; the multifractal
 * finish's lo and inv), and where the multifractal operations keep their state: a sum at
 * o has its state sdelta bytes on (state_at), an address the kernels' loops form from
 * the sum's with one addition they can hoist, where st0 + (o - out0) took three in each */
struct row_k {
    float a, b, c, lo, inv;
    uintptr_t sdelta;
};

static inline float *state_at(const float *o, struct row_k rk)
{
    return (float *)((uintptr_t)o + rk.sdelta);
}


/* What a row does with each noise value r (tex_noise_grid_row_op), at o. */
static inline void apply_op(int op, float r, float *o, struct row_k rk)
{
    float s, w, *st = op >= TEX_ROW_RIDGED_FIRST ? state_at(o, rk) : NULL;

    switch (op) {
    case TEX_ROW_SET:
        *o = r;
        break;
    case TEX_ROW_MUL:
        *o = rk.a * r;
        break;
    case TEX_ROW_MUL_ABS:
        *o = rk.a * fabsf(r);
        break;
    case TEX_ROW_UNIT:
        *o = clamp01(0.5f + 0.5f * r);
        break;
    case TEX_ROW_ADD:
        *o = *o + rk.a * r;
        break;
    case TEX_ROW_ADD_ABS:
        *o = *o + rk.a * fabsf(r);
        break;
    case TEX_ROW_ADD_UNIT:
        *o = clamp01(0.5f + 0.5f * ((*o + rk.a * r) * rk.b));
        break;
    case TEX_ROW_ADD_ABS_CLAMP:
        *o = clamp01((*o + rk.a * fabsf(r)) * rk.b);
        break;
    case TEX_ROW_RIDGED_FIRST:
        s = rk.b - fabsf(r);
        *o = *st = s * s;
        break;
    case TEX_ROW_RIDGED:
    case TEX_ROW_RIDGED_LAST:
        s = rk.b - fabsf(r);
        w = *st * rk.c; /* the weight clamp01(st c): st c >= 0 */
        s = (w < 1 ? w : 1) * (s * s);
        *o = *o + s * rk.a;
        break;
    case TEX_ROW_HYBRID_FIRST:
        *o = *st = (r + rk.b) * rk.a;
        break;
    default: /* TEX_ROW_HYBRID, TEX_ROW_HYBRID_LAST */
        s = (*st < 1 ? *st : 1) * ((r + rk.b) * rk.a);
        *o = *o + s;
        break;
    }
    if (op == TEX_ROW_RIDGED || op == TEX_ROW_HYBRID)
        *st = s;
    else if (op == TEX_ROW_RIDGED_LAST || op == TEX_ROW_HYBRID_LAST)
        *o = clamp01((*o - rk.lo) * rk.inv);
}

/* Pixels x..x1-1 of the rows, the reference order of operations for every level; the
 * coefficients hold the slots from sb on. */
static inline __attribute__((always_inline)) void
row_scalar_op(const tex_noise_grid *g, struct rowset rs, int sb, int x, int x1, const int rows,
              const int op, struct row_k rk)
{
    const int32_t *restrict slot = g->slot;
    const float *restrict u = g->u, *restrict um1 = g->um1, *restrict w0 = g->w0,
                          *restrict w1 = g->w1;

    for (; x < x1; x++)
        for (int r = 0; r < rows; r++) {
            const float *P = rs.C[r], *Q = P + ROW_NS;
            int s = slot[x] - sb;
            float t0 = P[s] * u[x] + Q[s];
            float t1 = P[s + 1] * um1[x] + Q[s + 1];
            apply_op(op, w0[x] * t0 + w1[x] * t1, rs.out[r] + x, rk);
        }
}

/* One copy of the row loop FN per operation, the operation op folded in as a
 * constant: FN(PRE..., op, POST...), PRE and POST parenthesised argument lists.  A
 * sanitizer build (TEX_SANITIZE) keeps one copy that takes op as it comes: the same
 * statements, checked the same, where 28 instrumented copies took gcc three minutes. */
#define ARGS(...) __VA_ARGS__
#ifdef TEX_SANITIZE
#define ROW_OP_SWITCH(FN, PRE, POST) FN(ARGS PRE, op, ARGS POST)
#else
#define ROW_OP_CASE(FN, PRE, POST, OP)                                                           \
    case OP: FN(ARGS PRE, OP, ARGS POST); break;
/* M(..., OP) for every operation but the last, TEX_ROW_HYBRID_LAST */
#define ROW_OPS_BUT_LAST(M, ...)                                                                 \
    M(__VA_ARGS__, TEX_ROW_SET) M(__VA_ARGS__, TEX_ROW_MUL) M(__VA_ARGS__, TEX_ROW_MUL_ABS)     \
    M(__VA_ARGS__, TEX_ROW_UNIT) M(__VA_ARGS__, TEX_ROW_ADD) M(__VA_ARGS__, TEX_ROW_ADD_ABS)    \
    M(__VA_ARGS__, TEX_ROW_ADD_UNIT) M(__VA_ARGS__, TEX_ROW_ADD_ABS_CLAMP)                      \
    M(__VA_ARGS__, TEX_ROW_RIDGED_FIRST) M(__VA_ARGS__, TEX_ROW_RIDGED)                         \
    M(__VA_ARGS__, TEX_ROW_RIDGED_LAST) M(__VA_ARGS__, TEX_ROW_HYBRID_FIRST)                    \
    M(__VA_ARGS__, TEX_ROW_HYBRID)
/* the last is the default: the switch covers every value */
#define ROW_OP_SWITCH(FN, PRE, POST)                                                             \
    switch (op) {                                                                                \
        ROW_OPS_BUT_LAST(ROW_OP_CASE, FN, PRE, POST)                                             \
    default: FN(ARGS PRE, TEX_ROW_HYBRID_LAST, ARGS POST); break;                                \
    }
#endif
/* A kernel FN(PRE..., rows, op, rk) for the rows at hand, one or two */
#define ROWS_SWITCH(FN, PRE)                                                                 \
    if (rows == 2) {                                                                         \
        ROW_OP_SWITCH(FN, (ARGS PRE, 2), (rk));                                              \
    } else {                                                                                 \
        ROW_OP_SWITCH(FN, (ARGS PRE, 1), (rk));                                              \
    }
/* the slot rows' own parameters */
#define ROW_PRE (g, rs, sb, x, x1)

/* The table's row for lattice row j. */
static inline const float (*lut_row(const tex_noise_grid *g, int64_t j))[4]
{
    int n = g->t->n;
    return (const float(*)[4])g->lut + (size_t)lat_index(j, g->period, n) * (n + 1);
}

/* A folded grid's table planes for lattice row j: X, then Y and C ps floats on */
static inline const float *plane_row(const tex_noise_grid *g, int64_t j)
{
    return g->plane + (size_t)lat_index(j, g->period, g->t->n) * 3 * g->ps;
}

/* What a pixel row folds: its two lattice rows' table planes and their weights (yrow's) */
struct fold_src {
    const float *T0, *T1; /* the table planes of lattice rows j and j + 1 (NULL: weight 0) */
    int ps;               /* the planes' length */
    float a0, a1, d0, d1;
};

static inline void fold_src_at(const tex_noise_grid *g, const struct yrow *yr, struct fold_src *f)
{
    f->T0 = plane_row(g, yr->j);
    f->T1 = yr->two ? plane_row(g, yr->j + 1) : NULL;
    f->ps = g->ps;
    f->a0 = yr->wy[0], f->a1 = yr->wy[1], f->d0 = yr->dy[0], f->d1 = yr->dy[1];
}

/* The gradient's pixels x..x1-1 from the three coefficient pairs C (value, y derivative,
 * z derivative; C[4] unread without dz), slots from sb on: the reference order */
void tex_noise_grad_scalar(const tex_noise_grid *g, const float *const C[6], int sb, float *dx,
                           float *dy, float *dz, int x, int x1);

/* tex_noise3p at point i of c (a + f c[.][i] with a, as tex_noise_points_at makes them; c[2]
 * NULL: 0): the point kernels' values for points they leave, cells beyond 2^30 */
float tex_noise3_point_at(const tex_noise_table *t, int period, const double *a, double f,
                          const double *const c[3], int i);

#endif
