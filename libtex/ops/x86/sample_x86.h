/* sample_x86.h - transform.c's sampler lookup for x86: tex_sample's body compiled for AVX2
 * (sample_template.c), the same floats, its floor and ceil one instruction each
 */
#ifndef TEX_SAMPLE_X86_H
#define TEX_SAMPLE_X86_H

struct tex_sampler;

/* tex_sample with AVX2's instructions, bit for bit its portable path's result */
void tex_sample_avx2(const struct tex_sampler *s, double x, double y, const double du[2],
                     const double dv[2], float *out);

#endif
