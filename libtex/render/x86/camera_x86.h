/* camera_x86.h - the eye's rays in AVX-512 or AVX2 lanes (camera.c's twins) */
#ifndef TEX_CAMERA_X86_H
#define TEX_CAMERA_X86_H

#include "../../base/x86/simd_x86.h"
#include "../camera.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef TEX_X86
/* camera_ray's rays through the n <= 8 pixels (x[k], y[k]) at (ox[k], oy[k]) inside each:
 * its operations in lanes, so its bits, the square roots and divisions of eight rays at
 * once.  x, y, ox and oy hold 8 readable entries. */
TEX_AVX512 void tex_eye_rays8_avx512(const struct tex_camera *cam, const struct tex_media *media,
                                     const int *x, const int *y, const double *ox,
                                     const double *oy, int n, tex_ray *r);
/* The same, n <= 4 rays in AVX2's lanes; x, y, ox and oy hold 4 readable entries. */
TEX_AVX2 void tex_eye_rays4_avx2(const struct tex_camera *cam, const struct tex_media *media,
                                 const int *x, const int *y, const double *ox, const double *oy,
                                 int n, tex_ray *r);
#endif

#ifdef __cplusplus
}
#endif
#endif
