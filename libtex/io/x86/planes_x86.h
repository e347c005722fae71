/* planes_x86.h - planes.c's moves eight pixels at a time (AVX2), for three or four channels */
#ifndef TEX_PLANES_X86_H
#define TEX_PLANES_X86_H

#include <stddef.h>

/* tex_planes_join and tex_planes_split of the first w - w % 8 pixels, nc 3 or 4; return how
 * many */
size_t tex_planes_join_avx2(float *px, const float *const *plane, int nc, size_t w);
size_t tex_planes_split_avx2(float *const *plane, const float *px, int nc, size_t w);

#endif
