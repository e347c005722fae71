/* palette_x86.h - palette.c's kernel for x86: OKLab to sRGB eight colours at a time
 * (AVX-512), the floats of tex_oklab_to_srgb
 */
#ifndef TEX_PALETTE_X86_H
#define TEX_PALETTE_X86_H

struct tex_srgb_enc;

/* The first n - n % 8 colours of lab (channels apart) as sRGB into rgb, the encoding's
 * table e filled; returns how many. */
int tex_oklab_srgb_avx512(const struct tex_srgb_enc *e, const float *const lab[3],
                          float *const rgb[3], int n);

#endif
