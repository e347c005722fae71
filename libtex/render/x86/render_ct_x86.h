/* render_ct_x86.h - the Cook-Torrance model's spectrum loops in SSE2 vectors
 * (render_ct.c's twins)
 *
 * GCC at -O2 does not vectorise sqrtf (errno), so these take four bands at a time with
 * intrinsics, the last group padded: every band takes the same instructions, and IEEE
 * sqrt and division give the scalar loops' results.
 */
#ifndef TEX_RENDER_CT_X86_H
#define TEX_RENDER_CT_X86_H

#include "../../base/simd.h"

#if defined(TEX_X86) && defined(__SSE2__)
/* tex_fresnel_conductor (fresnel.h, eta_i = 1) in single precision for a whole spectrum */
void tex_fresnel_conductor_n_sse2(double cos_i, const float *n, const float *k, int count,
                                  float *out);
/* tex_fresnel_dielectric (fresnel.h) in single precision for a whole spectrum: r[i] =
 * eta_i / eta_t per sample, cf the cosine of the angle of incidence */
void tex_fresnel_dielectric_n_sse2(float cf, const float *r, int count, float *out);
#endif

#endif
