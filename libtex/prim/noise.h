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
 * A table holds the gradients and the permutation of one seed; a grid samples
 * a table on the pixels of a map, a row at a time; octaves are the tables and
 * grids of a sum of noise at growing frequencies.  Each is made by its _new
 * function (NULL on failure, with the error in error.h) and freed by its
 * _delete; their insides are libtex's own.
 *
 *   tex_noise_table *t = tex_noise_new(seed, 256, 0);  // n = 256, not periodic
 *   double s = tex_noise3(t, x, y, z);                  // signed
 *   tex_noise_points(t, 0, 3, n, x, y, z, NULL, out);   // n points at once
 *
 *   double off[4] = {ox, oy, Z, W};                     // lattice offset, slice Z, W
 *   tex_noise_grid *g = tex_noise_grid_new(t, w, h, fx, fy, off, 3, 0);
 *   tex_noise_grid_row(g, y, row);                      // w signed values of row y
 *   tex_noise_grid_delete(g);
 *   tex_noise_delete(t);
 *
 * 3D noise at a point finds its cell and fractions in double precision and
 * sums the corners in float, as the grid rows do.  Many points at once (the
 * solid textures at a packet's hit points) go eight at a time through an
 * AVX2 kernel that performs those float operations in their order, so its
 * values are tex_noise3p's bit for bit; the primitives' eval2/eval3 batch
 * their octaves through it.  4D noise and tex_noise3_grad stay in double.
 *
 * With period p > 0 (the table's, or the p argument of the *p variants) the
 * lattice wraps every p cells along x and y, so a field sampled over
 * [0,p) tiles.  Lattice cells are found in double precision and 64-bit
 * integers, so coordinates of 1e6 and far beyond keep their texture.
 *
 * A grid's pixel (x,y) is the lattice point (ox + fx (x+0.5)/w, oy + fy
 * (y+0.5)/h, Z[, W]).  Its rows cost a few float operations a pixel whatever
 * the frequency, with the row's operation (rescale, weighted sum, |n|, an
 * octave sum's last step: tex_noise_grid_row_op) in the same pass.  They are
 * vectorised (AVX2 and AVX-512, chosen at run time; TEXTURA_SIMD=scalar or
 * avx2 caps the level) and every level performs the same float operations in
 * the same order, so the bytes are identical whatever the level, the thread
 * count or the order rows come in.  They agree with tex_noise3/4 to about 1e-6.
 */
#ifndef TEX_NOISE_H
#define TEX_NOISE_H

#include <stdint.h>

#include "../base/api.h"
#include "../base/param.h"

TEX_API_BEGIN

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

/* The gradients and permutation of one seed */
typedef struct tex_noise_table tex_noise_table;

/* A table of n gradients (2..TEX_NOISE_MAX_GRADIENTS; the thesis uses 256) from seed, with
 * period (0: none) for tex_noise3 and tex_noise4; the cubic fade.  NULL on failure. */
tex_noise_table *tex_noise_new(uint64_t seed, int n, int period);
/* The fade from now on: TEX_FADE_CUBIC (eq. 5.2, the default) or TEX_FADE_QUINTIC */
void tex_noise_set_fade(tex_noise_table *t, int fade);
void tex_noise_delete(tex_noise_table *t);
double tex_noise3(const tex_noise_table *t, double x, double y, double z);
double tex_noise4(const tex_noise_table *t, double x, double y, double z, double w);
/* With an explicit period (0: none) instead of the table's. */
double tex_noise3p(const tex_noise_table *t, int period, double x, double y, double z);
double tex_noise4p(const tex_noise_table *t, int period, double x, double y, double z, double w);
/* Noise at n points (x[i], y[i], z[i][, w[i]]), dims 3 or 4 (w unused with 3):
 * the values of tex_noise3p / tex_noise4p, bit for bit, eight points at a
 * time with AVX2 (3D); with 256 gradients and no period, sixteen at a time in
 * 512-bit registers, the permutation's bytes in registers, where the CPU has
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

/* A table sampled on the pixels of a w x h map, a row at a time */
typedef struct tex_noise_grid tex_noise_grid;

/* fx and fy lattice cells across and down the map, offset by off[0], off[1]; dims is 3
 * (off[2] is the slice Z) or 4 (off[3] is W); period 0: none.  The grid reads t, which
 * must outlive it.  NULL on failure. */
tex_noise_grid *tex_noise_grid_new(const tex_noise_table *t, int w, int h, double fx, double fy,
                                   const double off[4], int dims, int period);
void tex_noise_grid_delete(tex_noise_grid *g);
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

/* Octaves: noise at frequencies F L^k, k = 0..n-1, for turbulence and
 * fractal sums.  Octave k samples the lattice point
 *     L^k (F u + off) + shift_k,   shift_0 = 0,
 * the fixed shifts keeping the octaves' zeros at the origin apart.  With
 * tile, F and L must be whole numbers and octave k's period is F L^k.
 * u, v, w are texture coordinates; w is the slice for 3D (dims 3) and
 * t the fourth coordinate for dims 4. */
#define TEX_OCTAVES_MAX 30
typedef struct tex_octaves tex_octaves;

/* n octaves from frequency freq and lacunarity lac, their table of gradients from seed;
 * off: the offset (x, y, z) in lattice units of octave 0; z and t the slice and fourth
 * coordinate in texture units; with w, h > 0, sampled on a w x h grid too (the row
 * functions).  NULL on failure; usage errors name the options. */
tex_octaves *tex_octaves_new(uint64_t seed, int gradients, int fade, int n, double freq,
                             double lac, const double off[3], double z, double t, int dims,
                             int tile, int w, int h);
void tex_octaves_delete(tex_octaves *o);
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

TEX_API_END
#endif
