/* noise_grid.h - the insides of noise.c's tables and grids, shared with its x86 kernels
 *
 * Internal to libtex (not installed).  noise.c makes the tables and grids and
 * holds every scalar definition; the vector kernels of x86/noise_x86.c (grid
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
 */
#ifndef TEX_NOISE_GRID_H
#define TEX_NOISE_GRID_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "noise.h"

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
 * rolled around a kernel's branches, each row's noise through the stack (doc/performance.md,
 * "Noise kernels"). */
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
