/* noise.h - the thesis's gradient noise (Perlin 1985, thesis 5.2.2.1)
 *
 * n unit gradients G uniformly on the sphere and a random permutation F of
 * 0..n-1 are drawn from the seed.  The lattice point (i,j,k) gets
 *     G(i,j,k) = G[F[(i + F[(j + F[k mod n]) mod n]) mod n]]
 * and the noise at P is the sum over the 8 corners of P's cell of
 *     w(u) w(v) w(w) (G . (u,v,w)),   (u,v,w) = P - corner,
 *     w(t) = 2|t|^3 - 3|t|^2 + 1     (eqs. 5.1-5.3, the default fade)
 * or, with TEX_FADE_QUINTIC, w(t) = 1 - (6|t|^5 - 15|t|^4 + 10|t|^3)
 * (Perlin 2002).  The sum is signed, 0 at every lattice point, and lies in
 * [-1,1]; measured over large samples it stays within about +-0.75.
 * 4D noise adds an axis l: G4[F[(i + F[(j + F[(k + F[l mod n]) mod n]) mod n]) mod n]]
 * with gradients uniform on the 4D sphere, 16 corners.
 *
 *   tex_noise_table t;
 *   tex_noise_init(&t, seed, 256, 0);       // n = 256, not periodic
 *   double s = tex_noise3(&t, x, y, z);      // signed
 *   tex_noise_points(&t, 0, 3, n, x, y, z, NULL, out); // n points at once
 *
 * 3D noise at a point finds its cell and fractions in double precision and
 * sums the corners in float, as the grid rows do.  Many points at once (the
 * solid textures at a packet's hit points) go eight at a time through an
 * AVX2 kernel that performs those float operations in their order, so its
 * values are tex_noise3p's bit for bit; the primitives' eval2/eval3 batch
 * their octaves through it.  4D noise and tex_noise3_grad stay in double.
 *
 * With period p > 0 (t.period, or the p argument of the *p variants) the
 * lattice wraps every p cells along x and y, so a field sampled over
 * [0,p) tiles.  Lattice cells are found in double precision and 64-bit
 * integers, so coordinates of 1e6 and far beyond keep their texture.
 *
 * Grid sampling (the fast path the primitives' row callbacks use):
 *
 *   tex_noise_grid g;
 *   double off[4] = {ox, oy, Z, W};          // lattice offset, slice Z, W
 *   tex_noise_grid_init(&g, &t, w, h, fx, fy, off, 3, period);
 *   tex_noise_grid_row(&g, y, out);          // w signed values of row y
 *   tex_noise_grid_free(&g);
 *
 * pixel (x,y) is the lattice point (ox + fx (x+0.5)/w, oy + fy (y+0.5)/h,
 * Z[, W]).  Cell indices and fractions are computed once per column in
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
#ifndef TEX_NOISE_H
#define TEX_NOISE_H

#include <stdint.h>

#include "../base/param.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TEX_NOISE_MAX_GRADIENTS 4096

/* The lattice cell of a coordinate already floored.  Past 2^52 every double is
 * a lattice point, where gradient noise is 0 whatever the cell, so clamping
 * (high octaves of a large frequency reach 1e35) changes no value and keeps
 * the conversion defined. */
static inline int64_t tex_noise_cell(double c)
{
    return (int64_t)(c < -0x1p62 ? -0x1p62 : c > 0x1p62 ? 0x1p62 : c);
}

enum { TEX_FADE_CUBIC = 0, TEX_FADE_QUINTIC = 1 };

typedef struct tex_noise_table {
    int n;       /* gradients */
    int period;  /* 0: none; used by tex_noise3/tex_noise4 */
    int fade;    /* TEX_FADE_CUBIC (eq. 5.2, the default) or TEX_FADE_QUINTIC */
    int *perm;   /* F, stored twice (2n entries) so that F[a + b] needs no mod */
    float (*grad)[4];  /* n unit vectors on the sphere (w = 0) */
    float (*grad4)[4]; /* n unit vectors on the 4D sphere */
    float (*pgrad)[4]; /* grad[perm[m]] for m < 2n: the last hash step and its gradient in one */
    unsigned char perm8[256]; /* perm as bytes where n = 256: the point kernel's lookups in
                               * registers (AVX-512 VBMI) */
} tex_noise_table;

int tex_noise_init(tex_noise_table *t, uint64_t seed, int n, int period);
void tex_noise_free(tex_noise_table *t);
double tex_noise3(const tex_noise_table *t, double x, double y, double z);
double tex_noise4(const tex_noise_table *t, double x, double y, double z, double w);
/* With an explicit period (0: none) instead of t->period. */
double tex_noise3p(const tex_noise_table *t, int period, double x, double y, double z);
double tex_noise4p(const tex_noise_table *t, int period, double x, double y, double z, double w);
/* Noise at n points (x[i], y[i], z[i][, w[i]]), dims 3 or 4 (w unused with 3):
 * the values of tex_noise3p / tex_noise4p, bit for bit, eight points at a
 * time with AVX2 (3D); with 256 gradients and no period, sixteen at a time in
 * 512-bit registers, their hashes from perm8 in registers, where the CPU has
 * AVX-512 VBMI. */
void tex_noise_points(const tex_noise_table *t, int period, int dims, int n, const double *x,
                      const double *y, const double *z, const double *w, double *out);
/* 3D noise at the n points (a[0] + f u[i], a[1] + f v[i], a[2] + f w[i]) (w NULL: 0),
 * tex_noise3p's values there as float, the coordinates made in the kernel rather than
 * in the caller's arrays (the octaves' and the primitives' points). */
void tex_noise_points_at(const tex_noise_table *t, int period, const double a[3], double f, int n,
                         const double *u, const double *v, const double *w, float *out);
/* Noise and its analytic gradient d/dx, d/dy, d/dz in g. */
double tex_noise3_grad(const tex_noise_table *t, int period, double x, double y, double z,
                       double g[3]);

struct tex_noise_cache; /* lattice rows kept for the next pixel rows (noise.c) */

typedef struct tex_noise_grid {
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
} tex_noise_grid;

/* dims is 3 (off[2] is the slice Z) or 4 (off[3] is W); period 0: none. */
int tex_noise_grid_init(tex_noise_grid *g, const tex_noise_table *t, int w, int h, double fx,
                        double fy, const double off[4], int dims, int period);
/* What a row does with each noise value n, in the same vectorised pass
 * (clamp01(x) is min(max(x, 0), 1)).  The multifractal steps (Musgrave's
 * ridged and hybrid octaves, as fractal.c's points sum them) keep a state st
 * per column, and the last octave's step finishes the sum: they go through
 * tex_noise_grid_rows_mf, whose constants a, b, c are amp, offset, gain. */
enum {
    TEX_ROW_SET,           /* out = n */
    TEX_ROW_MUL,           /* out = a n */
    TEX_ROW_MUL_ABS,       /* out = a |n| */
    TEX_ROW_UNIT,          /* out = clamp01(0.5 + 0.5 n) */
    TEX_ROW_ADD,           /* out = out + a n */
    TEX_ROW_ADD_ABS,       /* out = out + a |n| */
    TEX_ROW_ADD_UNIT,      /* out = clamp01(0.5 + 0.5 ((out + a n) b)): fBm's last octave */
    TEX_ROW_ADD_ABS_CLAMP, /* out = clamp01((out + a |n|) b): turbulence's last octave */
    TEX_ROW_RIDGED_FIRST,  /* s = (b - |n|)^2: out = st = s */
    TEX_ROW_RIDGED,        /* s = min(st c, 1) (b - |n|)^2: out = out + s a, st = s (with
                            * c >= 0 and the states from these steps, st c >= 0: Musgrave's
                            * weight clamp01(st c)) */
    TEX_ROW_RIDGED_LAST,   /* as TEX_ROW_RIDGED, then out = clamp01((out - lo) inv) */
    TEX_ROW_HYBRID_FIRST,  /* s = (n + b) a: out = st = s */
    TEX_ROW_HYBRID,        /* s = min(st, 1) ((n + b) a): out = out + s, st = s */
    TEX_ROW_HYBRID_LAST    /* as TEX_ROW_HYBRID, then out = clamp01((out - lo) inv) */
};
/* The operations up to TEX_ROW_ADD_ABS_CLAMP, with their constants a, b, c. */
void tex_noise_grid_row_op(const tex_noise_grid *g, int y, int op, float a, float b, float c,
                           float *out);
/* tex_noise_grid_row_op on rows y.. y + n - 1, row i at out + i stride: the same bytes,
 * made two at a time where they can be (each column's data read once for both). */
void tex_noise_grid_rows_op(const tex_noise_grid *g, int y, int n, int op, float a, float b,
                            float c, float *out, size_t stride);
/* The multifractal operations' constants */
struct tex_mf_k {
    float amp, offset, gain; /* a, b and c */
    float lo, inv;           /* the last step's finish */
};
/* A multifractal operation on rows y.. y + n - 1: row i's sum at out + i stride, its state
 * at st + i stride. */
void tex_noise_grid_rows_mf(const tex_noise_grid *g, int y, int n, int op,
                            const struct tex_mf_k *k, float *out, float *st, size_t stride);
/* tex_noise_grid_row_op with TEX_ROW_SET and TEX_ROW_ADD. */
void tex_noise_grid_row(const tex_noise_grid *g, int y, float *out);
void tex_noise_grid_row_add(const tex_noise_grid *g, int y, float amp, float *out);
/* The analytic gradient over row y, in lattice units: dn/dX, dn/dY and, if dz
 * is not NULL, dn/dZ, w floats each (dims 3; the same at every SIMD level,
 * within about 1e-5 of tex_noise3_grad). */
void tex_noise_grid_row_grad(const tex_noise_grid *g, int y, float *dx, float *dy, float *dz);
void tex_noise_grid_free(tex_noise_grid *g);

/* Octaves: noise at frequencies F L^k, k = 0..n-1, for turbulence and
 * fractal sums.  Octave k samples the lattice point
 *     L^k (F u + off) + shift_k,   shift_0 = 0,
 * the fixed shifts keeping the octaves' zeros at the origin apart.  With
 * tile, F and L must be whole numbers and octave k's period is F L^k.
 * u, v, w are texture coordinates; w is the slice for 3D (dims 3) and
 * t the fourth coordinate for dims 4. */
#define TEX_OCTAVES_MAX 30
typedef struct tex_octaves {
    tex_noise_table t;
    int n, dims, grid;
    double freq[TEX_OCTAVES_MAX], off[TEX_OCTAVES_MAX][4];
    int period[TEX_OCTAVES_MAX];
    tex_noise_grid g[TEX_OCTAVES_MAX]; /* when sampled on a grid (w, h > 0) */
} tex_octaves;

/* off: the offset (x, y, z) in lattice units of octave 0; z and t the slice
 * and fourth coordinate in texture units; usage errors name the options. */
int tex_octaves_init(tex_octaves *o, uint64_t seed, int gradients, int fade, int n, double freq,
                     double lac, const double off[3], double z, double t, int dims, int tile,
                     int w, int h);
void tex_octaves_free(tex_octaves *o);
/* Signed noise of octave k at texture point (u, v, w), w added to the slice. */
double tex_octave_point(const tex_octaves *o, int k, double u, double v, double w);
/* Signed noise of octave k at n texture points (w NULL: 0), tex_octave_point's
 * values through tex_noise_points. */
#define TEX_POINTS_BATCH 256
void tex_octave_points(const tex_octaves *o, int k, int n, const double *u, const double *v,
                       const double *w, double *out);
/* Turbulence's sum at n points: start + sum over k < octaves of amp[k] |octave k|,
 * in float, octave by octave. */
void tex_octave_abs_sum(const tex_octaves *o, int octaves, const float *amp, float start, int n,
                        const double *u, const double *v, const double *w, float *out);
/* Perlin's band limit (filtered fBm, as RenderMan's): octave k's weight on a grid,
 * 1 - smoothstep(0.2, 0.6, fw) for pixels fw lattice cells wide; 1 off a grid.
 * Octaves fade out as their cells shrink towards a pixel, instead of aliasing. */
double tex_octave_band_weight(const tex_octaves *o, int k);
/* tex_octave_points (as float) at n points seen through footprints fw[i] texture units
 * wide (t_apply's solid textures), with the octave's weights there, wt[i] = 1 -
 * smoothstep(0.2, 0.6, fw[i] freq_k); where every weight is 0 the noise is not
 * evaluated, and out is 0. */
void tex_octave_points_fw(const tex_octaves *o, int k, int n, const double *u, const double *v,
                          const double *w, const double *fw, float *out, float *wt);
/* The mean of |noise| (what a faded octave of |noise| is replaced with). */
double tex_noise_mean_abs(const tex_noise_table *t);
/* Signed noise of octave k over row y of the grid. */
void tex_octave_row(const tex_octaves *o, int k, int y, float *out);
void tex_octave_row_add(const tex_octaves *o, int k, int y, float amp, float *out);
void tex_octave_row_op(const tex_octaves *o, int k, int y, int op, float a, float b, float c,
                       float *out);
void tex_octave_rows_op(const tex_octaves *o, int k, int y, int n, int op, float a, float b,
                        float c, float *out, size_t stride);
void tex_octave_rows_mf(const tex_octaves *o, int k, int y, int n, int op,
                        const struct tex_mf_k *mk, float *out, float *st, size_t stride);

/* The parameter rows every noise-based primitive shares (param.h), declared once:
 * struct S must have double z, struct tex_reals offset, int fade, int gradients
 * (and struct tex_reals w for TEX_NOISE_W_ROW).  Where the field lies in the
 * lattice (slice, offset), then the lattice's own rows (fade, gradients). */
#define TEX_NOISE_ROWS(S, ...)                                                                     \
    TEX_NOISE_PLACE_ROWS(S, __VA_ARGS__), TEX_NOISE_TABLE_ROWS(S, __VA_ARGS__)
#define TEX_NOISE_PLACE_ROWS(S, ...)                                                               \
    TEX_REAL_N("slice", S, z, 0, 0, -1e9, 1e9, "Z",                                                \
               "the slice of the solid field, in map widths", .alias = "z", __VA_ARGS__),          \
        TEX_REALS(S, offset, 0, NULL, -1e12, 1e12, 3, "X[,Y[,Z]]",                                 \
                  "lattice offset added to the scaled coordinates (of the first octave)",          \
                  __VA_ARGS__)
#define TEX_NOISE_TABLE_ROWS(S, ...)                                                               \
    TEX_ENUM(S, fade, 0, "cubic", "cubic|quintic",                                                 \
             "noise weight function: the thesis's cubic (eq. 5.2) or Perlin's quintic",            \
             __VA_ARGS__),                                                                         \
        TEX_INT(S, gradients, 0, 256, 2, TEX_NOISE_MAX_GRADIENTS, "N",                             \
                "gradients on the sphere (the thesis's n)", __VA_ARGS__)
#define TEX_NOISE_W_ROW(S, ...)                                                                    \
    TEX_REALS_N("time", S, w, 0, NULL, -1e9, 1e9, 1, "W",                                          \
                "use 4D noise at fourth coordinate W, in map widths (loops in time)",             \
                .alias = "w", __VA_ARGS__)
/* Looping animation (thesis ch. 6, "dynamic textures in time"): frame K of
 * N moves through 4D noise on a circle of radius R map widths in the (z, w)
 * plane, z + R cos(2 pi K/N), w + R sin(2 pi K/N), so that frame N would be
 * frame 0 again and every step is the same arc 2 pi R / N.  The angle is
 * 2 pi (K / N): frame K of N and frame 2K of 2N are the same map. */
#define TEX_NOISE_LOOP_ROWS(S, ...)                                                                \
    TEX_INT(S, frames, 0, 0, 0, 1000000, "N",                                                      \
            "frames of a looping animation through 4D noise (0: a still map)", __VA_ARGS__),       \
        TEX_INT(S, frame, 0, 0, 0, 999999, "K", "with --frames N: the frame to make, 0..N-1",      \
                __VA_ARGS__),                                                                      \
        TEX_REAL(S, loop_radius, 0, 0.25, 0.0001, 1e6, "R",                                         \
                 "with --frames: radius of the loop in map widths (larger: faster change)",        \
                 __VA_ARGS__)
/* z and w (map widths) and dims (3 or 4) of frame `frame` of `frames` (0: a
 * still map, unchanged); -1 with a usage error when frame is not 0..frames-1. */
int tex_noise_loop(int frames, int frame, double radius, double *z, double *w, int *dims);

#ifdef __cplusplus
}
#endif
#endif
