/* noise_x86.h - noise.c's kernels for x86, which noise.c chooses at run time
 *
 * Every kernel performs its scalar twin's float operations in their order, so
 * the bytes are the same at every level (../noise_grid.h).  x86/noise_x86.c
 * holds the grid rows, the lattice rows' folds, the gradient's rows and the
 * band limit's weights; x86/noise_points_x86.c the point kernels.
 */
#ifndef TEX_NOISE_X86_H
#define TEX_NOISE_X86_H

#include "../noise_grid.h"

/* 3D noise at the points of c (a + f c[.][i] with a, else c itself; c[2] NULL: 0): the
 * first n - n % 8 of them, eight at a time (AVX2) or sixteen (VBMI, for 256 gradients and
 * no period); return how many, tex_noise3p's values as float. */
int tex_noise3_points_avx2(const tex_noise_table *t, int period, const double *a, double f,
                           const double *const c[3], int n, float *out);
int tex_noise3_points_vbmi(const tex_noise_table *t, int period, const double *a, double f,
                           const double *const c[3], int n, float *out);

/* Rows y.. y + rows - 1 of g (rows at most FOLD_ROWS) with the operation op into out[r],
 * eight pixels at a time (AVX2) or sixteen (AVX-512, a grid's wide rows) */
void tex_noise_grid_rows_avx2(const tex_noise_grid *g, int y, int rows, int op, struct row_k rk,
                              float *const *out);
void tex_noise_grid_rows_avx512(const tex_noise_grid *g, int y, int rows, int op,
                                struct row_k rk, float *const *out);

/* A lattice row's slots s0.. four at a time (SSE): folded over the slice's corners with
 * the weights zm (lattice row lj, reduced), or read from the table row T; return the
 * first slot left, at most s1 */
int tex_noise_lattice_sse(const tex_noise_grid *g, const float (*zm)[4], int lj,
                          const int32_t *lat, int s0, int s1, float *X, float *Y, float *C);
int tex_noise_lut_sse(const float (*T)[4], const int32_t *lat, int s0, int s1, float *X, float *Y,
                      float *C);

/* tex_noise_grad_scalar's pixels x..x1-1, eight at a time (AVX2) */
void tex_noise_grad_avx2(const tex_noise_grid *g, const float *const C[6], int sb, float *dx,
                         float *dy, float *dz, int x, int x1);

/* The band limit's weights of the first n - n % 4 footprints, four at a time (AVX2);
 * whether one is > 0 */
int tex_noise_band_weights_avx2(int n, const double *fw, double fk, float *wt);

#endif
