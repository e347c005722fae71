/* geometry_x86.h - geometry.c's kernels for x86, which geometry.c chooses at run time
 *
 * The solid checker's cells four points a vector: half_odd's operations in their order,
 * floor's rounding exact in the lanes as in libm, so the same values at every level.
 */
#ifndef TEX_GEOMETRY_X86_H
#define TEX_GEOMETRY_X86_H

/* checker_eval3 (nu, nv, nw its repetitions) at the first n - n % 4 points; returns how
 * many */
int tex_checker3_avx2(double nu, double nv, double nw, int n, const double *u, const double *v,
                      const double *w, float *out);

#endif
