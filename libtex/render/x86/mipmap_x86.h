/* mipmap_x86.h - the mip-map lookups in vector lanes (mipmap.h's twins)
 *
 * Each performs the scalar lookup's float operations in its order, so the same bytes.
 */
#ifndef TEX_MIPMAP_X86_H
#define TEX_MIPMAP_X86_H

#include "../../base/simd.h"

#ifdef __cplusplus
extern "C" {
#endif

struct tex_texture;
#ifdef TEX_X86
/* map_eval's colour case from level l (weight a of level l + 1), in AVX2 vectors; g: as
 * bilinear gives them, level l's in g[0], l + 1's in g[1] */
void tex_map_eval3_avx2(const struct tex_texture *t, int l, double a, double u, double v,
                        float out[3], double (*g)[2]);
/* tex_texture_points in AVX-512 lanes, eight points at a time (t->nlevels < 32) */
void tex_map_points_avx512(const struct tex_texture *t, int n, const double *u, const double *v,
                           const double *fw2, float *out, double *grad);
#endif

#ifdef __cplusplus
}
#endif
#endif
