/* remap_x86.h - remap.c's kernel for x86: a remap whose one power is its gamma, eight
 * values at a time (AVX-512), the floats of tex_remap_value
 */
#ifndef TEX_REMAP_X86_H
#define TEX_REMAP_X86_H

#include <stddef.h>

struct tex_remap;

/* The first n - n % 8 of the n values at px remapped by r (threads share them); returns
 * how many.  r's gamma is its one power, 1 / gamma at most 64 (remap.c's gamma_alone). */
size_t tex_remap_gamma_avx512(const struct tex_remap *r, float *px, size_t n);

#endif
